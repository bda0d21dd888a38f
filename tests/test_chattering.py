"""Chattering sequences against a direct event-by-event sum in 50-digit arithmetic.

Source of truth: tests/mp_vertical.py (mpmath, 50 digits): the head's free flight
integrated by its own Taylor series from MODEL.md's damped equation, every rebound
(ξ' → −e ξ') located by a root search on ξ/h, and the sequence followed hit by hit until
the flights are below 1e-35: its accumulation time is a plain sum (no closure formula,
no error bound to trust). Starting point: a contact end (ξ = ξ' = 0 at τ = π/ϖ, exact in
every solver), so the next contact's hits and start depend on nothing else.

Checked: the exact solver's rebound hits and contact start (schedule.vertical_run via
VerticalSchedule), the reference's contact start (its own geometric tail after flights
of 1e-9), and the tangential state at the contact start (the head flies tangentially
free through the sequence; mp integrates that flight from the solver's own section).
"""

from __future__ import annotations

import math
from itertools import pairwise

import mp_vertical as mv
import mpmath as mp
import numpy as np
import pytest

from betvdesign.dynamics import reference, simulate
from betvdesign.dynamics.vertical import VerticalSchedule
from betvdesign.model.params import ModelParams


@pytest.fixture(autouse=True)
def _fifty_digits():
    """Every test here at 50 digits (other modules set the global mp.mp.dps)."""
    with mp.workdps(50):
        yield


TOL_T = 1e-12  # contact start and hit times [-] (τ up to 2·2π/ϖ ≈ 40)
TOL_STATE = 1e-11

#: The damped cases were the exact solver's chattering defect until 2026-11-25 (its
#: contact start off by 8.6e-10 to 2.2e-7, hits drifting as the flights shrink: the
#: damped gap closed form carries an absolute round-off ~1e-16, a time error ~1e-16/v
#: for a rebound of velocity v); tiny flights now come from schedule.short_flight.
#: (ϖ, ζ_v, e): every one chatters into a contact in each cycle (period 1); the damped
#: ones are the vertical motions of test_damped_reference's chattering designs, and more
CASES = [
    (0.77, 0.016, 0.32),
    (0.63, 0.242, 0.03),
    (0.77, 0.077, 0.09),
    (0.78, 0.018, 0.09),
    (0.9, 0.05, 0.3),
    (0.67, 0.0, 0.44),
    (0.98, 0.0, 0.10),
    (1.22, 0.0, 0.05),
    (0.3, 0.0, 0.5),
]


def _params(case) -> list:
    return [pytest.param(c, id=f"w{c[0]}-zv{c[1]}-e{c[2]}") for c in case]


_MP: dict = {}


def truth(case) -> dict:
    """The mp sequence after the contact end at π/ϖ, times in the next cycle's local
    time (τ − 2π/ϖ), cached per case."""
    if case not in _MP:
        w, zv, e = case
        T = 2 * mp.pi / mp.mpf(w)
        r = mv.chattering(w, zv, e, mp.pi / mp.mpf(w), 2 * T)
        assert r["contact"] is not None, "no accumulation within two cycles"
        _MP[case] = {
            "hits": [h - T for h in r["hits"]],
            "contact": r["contact"] - T,
            "v_in": r["v_in"],
        }
    return _MP[case]


def _exact_cycle(case):
    w, zv, e = case
    vs = VerticalSchedule(w, horizon=50, zeta_v=zv, restitution=e)
    assert vs.period == 1 and vs.first_end is not None
    return vs.cycle(vs.first_end + 1)


@pytest.mark.parametrize("case", _params(CASES))
def test_exact_contact_start_is_the_accumulation_time(case):
    """The exact solver's contact start after the sequence = the 50-digit sum."""
    cyc = _exact_cycle(case)
    tc = float(truth(case)["contact"])
    assert abs(cyc.contact_start - tc) <= TOL_T, f"off by {cyc.contact_start - tc:.3g}"


@pytest.mark.parametrize("case", _params(CASES))
def test_exact_rebound_hits_are_the_event_by_event_ones(case):
    """Every hit the exact solver resolves before closing the sequence is one of the
    mp sequence's, at the same time; the exact solver closes it only where the flights
    are already tiny (its last flight below 1e-6 of a cycle)."""
    cyc = _exact_cycle(case)
    hits = [h for h in cyc.impulsive if h < cyc.contact_start]
    ref = [float(h) for h in truth(case)["hits"]]
    assert len(hits) >= 3 and len(hits) <= len(ref)
    err = max(abs(a - b) for a, b in zip(hits, ref, strict=False))
    assert err <= TOL_T, f"hits off by up to {err:.3g}"
    T = 2 * math.pi / case[0]
    assert hits[-1] - hits[-2] < 1e-6 * T


@pytest.mark.parametrize("case", CASES, ids=lambda c: f"w{c[0]}-zv{c[1]}-e{c[2]}")
def test_reference_contact_start_is_the_accumulation_time(case):
    """The reference closes the sequence by its own tail (module doc of reference_terms):
    its contact start in cycle 1 = the 50-digit sum."""
    w, zv, e = case
    rf = reference.simulate(ModelParams(w, 0.3, 1.0, 0.3, zv, 0.0, e), 2, rtol=1e-13, atol=1e-14)
    assert rf.success and "chattering" in rf.message
    starts = [ev.tau for ev in rf.events if ev.kind == "impact"]
    T = 2 * math.pi / w
    assert abs(starts[1] - T - float(truth(case)["contact"])) <= TOL_T


def test_mp_sequence_is_geometric():
    """The helper's own law near accumulation (Budd & Dux 1994): late flights shrink by
    e and impact velocities by e, to first order in the flight (flights of 1e-35 are
    differences of times ~1 in 50 digits: 15 digits left), in every case."""
    for case in CASES:
        h, v = truth(case)["hits"], truth(case)["v_in"]
        fl = [b - a for a, b in pairwise(h)]
        assert fl[-1] < mv.FLIGHT_END / case[2]
        assert abs(fl[-1] / fl[-2] - case[2]) < 1e-12
        assert abs(v[-1] / v[-2] - case[2]) < 1e-30


def test_mp_flight_matches_the_undamped_closed_form():
    """The Taylor integrator of mp_vertical against ξ'' + ξ = −sin ϖτ solved by hand
    (ξ = (ϖ sin τ − sin ϖτ)/(1 − ϖ²) from rest at τ = 0), over two cycles."""
    w = mp.mpf(0.77)
    osc = mv.vertical(0.77, 0.0)
    t = 4 * mp.pi / w
    y, v = osc.advance(mp.mpf(0), 0, 0, t)
    exact = (w * mp.sin(t) - mp.sin(w * t)) / (1 - w * w)
    rate = w * (mp.cos(t) - mp.cos(w * t)) / (1 - w * w)
    assert abs(y - exact) < mp.mpf("1e-40") and abs(v - rate) < mp.mpf("1e-40")


STATE_CASES = [
    ((0.98, 0.0, 0.10), 0.3, 1.5, 0.4, 0.05),
    ((0.67, 0.0, 0.44), 0.6, 0.5, 0.3, 0.2),
    ((0.78, 0.018, 0.09), 0.78, 4.36, 0.21, 0.018),
]


def _free_flight(case, alpha, zeta_h, start, t0, t1) -> np.ndarray:
    """(ζ, ζ', s, s') at t1 from (ζ, ζ', s, s') = start at t0, tangentially free (mp)."""
    w, zv, _ = case
    osc = mv.tangential(w, zv, alpha, zeta_h)
    z, zd = osc.advance(mp.mpf(t0), mp.mpf(start[0]), mp.mpf(start[1]), t1 - t0)
    s = mp.mpf(start[2]) + mp.mpf(start[3]) * (t1 - t0)
    return np.array([float(z), float(zd), float(s), float(start[3])])


@pytest.mark.parametrize(
    "case,alpha,beta,kappa,zeta_h",
    [pytest.param(*c, id=f"w{c[0][0]}-zv{c[0][1]}") for c in STATE_CASES],
)
def test_exact_state_at_contact_start(case, alpha, beta, kappa, zeta_h):
    """(ζ, ζ', s, s') where the contact of cycle 1 starts: the exact solver's dense
    output there vs the mp tangential free flight from its section at τ = 2π/ϖ to the
    mp accumulation time."""
    w, zv, e = case
    p = ModelParams(w, alpha, beta, kappa, zv, zeta_h, e)
    tr = simulate(p, 2, dense=True)
    T = 2 * math.pi / w
    tc_ex = next(ev.tau for ev in tr.events if ev.kind == "impact" and ev.tau > T)
    got = tr.sample(np.array([tc_ex]))[0, 2:]
    tc = T + truth(case)["contact"]
    want = _free_flight(case, alpha, zeta_h, tr.section[1, 2:], T, tc)
    assert np.max(np.abs(got - want)) <= TOL_STATE * max(1.0, np.abs(want).max())


@pytest.mark.parametrize("case,alpha,beta,kappa,zeta_h", STATE_CASES, ids=["a", "b", "c"])
def test_reference_state_at_contact_start(case, alpha, beta, kappa, zeta_h):
    """The same for the reference (its dense output, its own section)."""
    w, zv, e = case
    p = ModelParams(w, alpha, beta, kappa, zv, zeta_h, e)
    rf = reference.simulate(p, 2, rtol=1e-13, atol=1e-14, dense=True)
    T = 2 * math.pi / w
    tc_rf = next(ev.tau for ev in rf.events if ev.kind == "impact" and ev.tau > T)
    got = rf.sample(np.array([tc_rf]))[0, 2:]
    tc = T + truth(case)["contact"]
    want = _free_flight(case, alpha, zeta_h, rf.section[1, 2:], T, tc)
    assert np.max(np.abs(got - want)) <= TOL_STATE * max(1.0, np.abs(want).max())


@pytest.mark.parametrize("case", _params(CASES[:5]))
def test_regime_rung_sees_the_chattering(case):
    """What ``betv check`` and the regime question read (dynamics.vertical_motion through
    the fidelity ladder's vertical rung, given ζ_v and e): one contact per cycle lasting
    from the 50-digit accumulation time to π/ϖ (kernel time), not the idealised motion's."""
    from betvdesign.checks import fidelity

    w, zv, e = case
    p = ModelParams(w, 0.3, 1.0, 0.3, zv, 0.0, e)
    ans = fidelity.answer(p, "regime")
    assert ans.choice.rung == "vertical" and ans.success, ans.message
    frac = (math.pi / w - float(truth(case)["contact"])) / (2 * math.pi / w)
    assert ans.value["period_cycles"] == 1
    assert abs(ans.value["contact_fraction"] - frac) <= 1e-12
    ideal = fidelity.answer(ModelParams(w, 0.3, 1.0, 0.3), "regime")
    assert abs(ideal.value["contact_fraction"] - frac) > 1e-6


@pytest.mark.parametrize("case", _params(CASES))
def test_chattering_into_contact_is_one_contact_per_cycle(case):
    """Every case chatters into one contact per cycle (the 50-digit sequence closes at
    its contact start before π/ϖ): the vertical fast path calls it "chattering-contact"
    (not "multi-impact"), its rebounds are hits of that sequence, and the regime study
    keeps it in the one-contact-per-cycle label "period-1"."""
    from betvdesign.dynamics import vertical_motion
    from betvdesign.studies.regime import regime_point

    w, zv, e = case
    assert float(truth(case)["contact"]) < math.pi / w  # closes within the half cycle
    r = vertical_motion(w, zeta_v=zv, restitution=e)
    assert r.regime == "chattering-contact" and r.period_cycles == 1, r.message
    assert r.impulsive_per_cycle >= 3 and "chattering sequence" in r.message
    row = regime_point({"key": 0, "varpi": w, "zeta_v": zv, "restitution": e, "max_cycles": 50})
    assert row["label"] == "period-1"
