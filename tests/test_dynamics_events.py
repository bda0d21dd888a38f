"""Certified event location and the vertical fast path (sources: constructed grazing
trajectories whose dip below zero is known in closed form — a coarse scan provably
misses them; the model's vertical rules of docs/MODEL.md; the design window)."""

import math

import numpy as np
import pytest

from betvdesign.dynamics import evaluators, simulate, vertical_motion
from betvdesign.dynamics.bounds import envelope_at, envelope_prep, safe_step
from betvdesign.dynamics.evaluators import EVALUATOR_DTYPE, gap_evaluator
from betvdesign.dynamics.flows import REVERSE, SLIP, oscillator, phase_table
from betvdesign.dynamics.search import ROOT, first_root, workspace
from betvdesign.errors import ParameterError
from betvdesign.model.params import ModelParams

W = 0.5
SP0, CP0 = 0.0, -1.0  # a free flight starting at phase π (a contact end)


def _xi(x0, v0, h):
    return oscillator(1.0, W, -1.0, x0, v0, SP0, CP0, h)


def _first_hit(x0: float, v0: float, H: float) -> float | None:
    """First h in [0, H] with ξ = 0 by the certified search, or None."""
    ws = workspace()
    gap_evaluator(W, 0.0, 1.0, x0, v0, SP0, CP0, H, False, ws.ev[0])
    code, h, _, _ = first_root(ws.ev[0], H, ws)
    return h if code == ROOT else None


def envelope_time(K: float, E: float, a: float, th0: float, wf: float) -> float:
    return envelope_at(*envelope_prep(K, E, a), th0, wf)


def _grazing_start(depth: float) -> tuple[float, float, float]:
    """Initial gap state whose free flight dips to exactly −depth at a known h_m.

    The flight from (ξ, ξ') = (0.5, 0) at phase π decreases to a first local minimum
    v_m > 0 at h_m. Adding c·cos(h − h_m) (a free solution with zero slope at h_m),
    c = −v_m − depth < 0, moves that minimum to −depth without moving it and keeps
    ξ(h) > ξ(h_m) before it (c(cos − 1) ≥ 0). Returns (ξ0, ξ0', h_m).
    """
    lo, hi = 1.0, 2.5  # ξ' changes sign once in there (checked below)
    assert _xi(0.5, 0.0, lo)[1] < 0 < _xi(0.5, 0.0, hi)[1]
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _xi(0.5, 0.0, mid)[1] < 0 else (lo, mid)
    hm = 0.5 * (lo + hi)
    vm = _xi(0.5, 0.0, hm)[0]
    assert vm > 0.2
    c = -vm - depth
    return 0.5 + c * math.cos(hm), c * math.sin(hm), hm


@pytest.mark.parametrize("depth", [1e-8, 1e-11])
def test_grazing_hit_found_where_a_coarse_scan_misses_it(depth):
    x0, v0, hm = _grazing_start(depth)
    # the dip below zero lasts 2·sqrt(2·depth/ξ'') ≪ the 1e-3 grid of a coarse scan
    grid = np.arange(0.0, hm + 1.0, 1e-3)
    assert min(_xi(x0, v0, h)[0] for h in grid) > 0.0
    h = _first_hit(x0, v0, hm + 1.0)
    assert h is not None
    assert hm - 1e-3 < h <= hm
    assert abs(_xi(x0, v0, h)[0]) < 1e-14


def test_near_miss_is_not_an_event():
    """A flight that comes within 1e-9 of the slider without touching has no hit there."""
    x0, v0, hm = _grazing_start(-1e-9)
    assert _first_hit(x0, v0, hm + 0.05) is None


def test_return_exactly_at_the_section_opens_contact_at_phase_zero():
    """ϖ = 1/2: the flight from a contact end, ξ = (sin(h/2) − sin(h)/2)/(3/4), returns to
    ξ = 0 exactly at h = 2π, i.e. at phase 0 of the next cycle: contact from ϖτ = 0."""
    v = vertical_motion(0.5)
    assert v.regime == "single-impact" and v.contact_phase == pytest.approx(0.0, abs=1e-12)
    assert v.contact_fraction == pytest.approx(0.5, abs=1e-12)
    tr = simulate(ModelParams(0.5, 1.0, 1.0, 0.4), 3)
    assert tr.success and [e.kind for e in tr.events].count("impact") == 3


def test_safe_step_never_overshoots_a_quadratic_lower_bound():
    f, fp, m2 = 0.3, -0.7, 2.0
    x = safe_step(f, fp, m2)
    assert f + fp * x - m2 * x * x / 2 == pytest.approx(0.0, abs=1e-15)


@pytest.mark.parametrize("w", [0.55, 0.9, 1.0, 1.5, 1.9])
def test_design_window_single_impact(w):
    """MODEL.md: 0.5 ≤ ϖ < 2 gives one hit per cycle with finite contact."""
    v = vertical_motion(w)
    assert v.success and v.regime == "single-impact" and v.period_cycles == 1
    assert v.hits_per_cycle == 1.0 and 0 < v.contact_fraction < 0.5
    # contact runs from the hit to the contact end: fraction = (π − ϖτ_c)/(2π)
    assert v.contact_fraction == pytest.approx((math.pi - v.contact_phase) / (2 * math.pi))


@pytest.mark.parametrize("w", [2.1, 2.5])
def test_beyond_window_hits_are_impulsive(w):
    """MODEL.md: beyond ϖ ≈ 2 (up to about 2.6) hits are impulsive, slider not driven."""
    v = vertical_motion(w, max_cycles=300)
    assert not v.success and v.regime == "impulsive-only" and v.contact_fraction == 0.0
    assert v.impulsive_per_cycle > 0


def test_vertical_matches_simulate_event_log():
    p = ModelParams(0.9, 1.0, 1.0, 0.4)
    v = vertical_motion(p.varpi)
    tr = simulate(p, 6)
    hits = [e.tau for e in tr.events if e.kind == "impact"]
    T = 2 * math.pi / p.varpi
    phases = [(t % T) * p.varpi for t in hits[1:]]
    assert np.allclose(phases, v.contact_phase, atol=1e-12)


@pytest.mark.parametrize("bad", [0.0, -1.0, math.nan, math.inf, "x"])
def test_vertical_rejects_bad_varpi(bad):
    with pytest.raises(ParameterError, match="varpi"):
        vertical_motion(bad)


def test_envelope_time_closed_form_and_grid():
    """First t with K cos(θ0 + ϖt) + E ≤ a: hand values, then a fine grid (second method)."""
    assert envelope_time(1.0, 0.0, 0.5, 0.0, 1.0) == pytest.approx(math.pi / 3)
    assert envelope_time(-1.0, 0.0, 0.5, 0.0, 1.0) == 0.0
    assert envelope_time(-1.0, 0.0, 0.5, math.pi, 1.0) == pytest.approx(math.pi / 3)
    assert envelope_time(1.0, 3.0, 0.5, 0.0, 1.0) == math.inf
    rng = np.random.default_rng(3)
    for _ in range(200):
        K, E, a, th0, w = rng.normal(), rng.normal(), abs(rng.normal()), rng.uniform(-9, 9), 0.7
        t = envelope_time(K, E, a, th0, w)
        grid = np.linspace(0.0, 20.0, 200001)
        below = K * np.cos(th0 + w * grid) + E <= a
        expect = grid[np.argmax(below)] if below.any() else math.inf
        if math.isinf(expect):
            assert t > 20.0 - 1e-3
        else:
            assert t == pytest.approx(expect, abs=2e-4)


@pytest.mark.parametrize("general", [False, True])
@pytest.mark.parametrize("kind", ["slip", "reverse", "stick", "gap"])
def test_an_evaluator_writes_every_field_of_its_record(kind, general):
    """Each evaluator fills its record by field name from a neutral start: what the record
    held before (a previous phase's evaluator, here garbage) never shows through."""
    table = phase_table(ModelParams(1.2, 0.5, 1.0, 0.4), general=general)
    c = table[0]
    sp0, cp0 = 0.3, math.sqrt(1.0 - 0.09)
    out = []
    for fill in (0x00, 0xFF):
        rec = np.empty(1, EVALUATOR_DTYPE)
        rec.view(np.uint8)[:] = fill
        e = rec[0]
        if kind == "stick":
            evaluators.stick_evaluator(c, 0.1, 0.2, sp0, cp0, 1.0, -1, e)
        elif kind == "gap":
            wf = float(c["varpi"])
            evaluators.gap_evaluator(wf, 0.0, 1.0, 0.1, 0.2, sp0, cp0, 1.0, general, e)
        else:
            phase = SLIP if kind == "slip" else REVERSE
            evaluators.slip_evaluator(c, phase, 0.1, 0.2, 0.0, 0.05, sp0, cp0, 1.0, False, e)
        out.append(rec.tobytes())
    assert out[0] == out[1]
