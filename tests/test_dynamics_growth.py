"""Unbounded tangential growth at the free-flight resonance α·ϖ² = 1 (status "unbounded").

Sources: the closed-form bound of betvdesign.dynamics.periodic (module docstring):
with w = ζ' − iϖζ, (w e^{iϖτ})' = ϖ²F e^{iϖτ}, so ζ at the section falls by at least
π(1 − ακ/2) per cycle from any state when ακ < 2 (no periodic orbit can exist); the
solve_ivp reference solver as a second method for that fall; long brute-force runs
(periodic_orbit's own budget) for the points that must NOT be flagged: detuned points
settling with |μ| → 1, ϖ → 2 transients of thousands of cycles, the stick resonance,
and exact resonance with ακ ≥ 2 where the bound says nothing.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from betvdesign.dynamics import periodic_orbit, reference, simulate
from betvdesign.dynamics.periodic import GROWTH_WINDOW, resonance_growth_bound
from betvdesign.model.params import ModelParams
from betvdesign.studies.pushpull import run_pushpull

#: The issue-5 push/pull map axes.
MAP_VARPI = [round(0.5 + 0.1 * i, 10) for i in range(16)]
MAP_ALPHA = [0.1, *[0.5 * i for i in range(1, 9)]]
MAP_BETA = [0.1, 0.5, 1.0, 1.5]
MAP_KAPPA = [0.1, 0.4]
#: The (ϖ, α) of the map on α·ϖ² = 1.
RESONANT = [(1.0, 1.0), (0.5, 4.0)]


def _fall_per_cycle(section: np.ndarray) -> np.ndarray:
    return -np.diff(section[:, 2])


@pytest.mark.parametrize(("varpi", "alpha"), RESONANT)
@pytest.mark.parametrize(("beta", "kappa"), [(0.1, 0.4), (1.5, 0.1), (1.0, 0.49)])
def test_bound_holds_every_cycle_from_rest_and_from_random_states(varpi, alpha, beta, kappa):
    """ζ(section) falls by ≥ π(1 − ακ/2) in every one of 1000 cycles, from rest and from
    seeded random states (the bound holds from any state, whatever β)."""
    p = ModelParams(varpi, alpha, beta, kappa)
    bound = resonance_growth_bound(p)
    assert bound == pytest.approx(math.pi * (1 - alpha * kappa / 2))
    rng = np.random.default_rng(7)
    starts = [None] + [(0.0, 0.0, *rng.normal(0, 5, 2), 0.0, rng.normal(0, 5)) for _ in range(2)]
    for state0 in starts:
        tr = simulate(p, 1000, log_events=False, state0=state0)
        assert tr.success
        fall = _fall_per_cycle(tr.section)
        assert fall.min() >= bound - 1e-9 * (1 + np.abs(tr.section[:, 2]).max())


def test_reference_solver_shows_the_same_fall():
    """solve_ivp (DOP853, exact switching) reproduces the fall per cycle and the bound."""
    p = ModelParams(0.5, 4.0, 0.5, 0.4)
    ref = reference.simulate(p, 12, method="DOP853", rtol=1e-11, atol=1e-13)
    ex = simulate(p, 12, log_events=False)
    assert ref.success
    assert _fall_per_cycle(ref.section).min() >= resonance_growth_bound(p) - 1e-6
    np.testing.assert_allclose(ref.section[:, 2], ex.section[:, 2], rtol=1e-7, atol=1e-7)


@pytest.mark.parametrize(
    ("varpi", "alpha", "beta", "kappa"),
    [(v, a, b, k) for (v, a), b, k in itertools.product(RESONANT, MAP_BETA, MAP_KAPPA)],
)
def test_map_resonant_points_flagged_within_a_few_hundred_cycles(varpi, alpha, beta, kappa):
    """All 16 resonant map points: status "unbounded" within GROWTH_WINDOW + the cycles
    to periodic vertical motion, never a mode or Δs; the message names the resonance, α,
    the proven and measured rates and what to try."""
    p = ModelParams(varpi, alpha, beta, kappa)
    po = periodic_orbit(p)
    assert po.status == "unbounded" and not po.success
    assert po.mode is None and po.delta_s is None and po.period_cycles is None
    assert po.transient_cycles <= GROWTH_WINDOW + 10
    m = po.message
    assert "a·ϖ² = 1" in m and f"α = {alpha:g}" in m and "Move ϖ or α" in m
    bound = resonance_growth_bound(p)
    rate = float(m.split("measured ")[1].split(" per cycle")[0])
    assert rate >= bound - 1e-9
    assert f"{bound:.6g} per cycle" in m


def test_budget_is_respected():
    """A budget shorter than the window: still flagged, within the budget."""
    po = periodic_orbit(ModelParams(1.0, 1.0, 0.5, 0.1), max_cycles=40)
    assert po.status == "unbounded" and po.transient_cycles <= 40


def test_only_exact_resonances_of_the_map_qualify():
    """Over the whole issue-5 map the criterion applies at exactly the 16 points with
    α·ϖ² = 1 (periodic_orbit returns "unbounded" only where it applies)."""
    hits = [
        (v, a)
        for v, a, b, k in itertools.product(MAP_VARPI, MAP_ALPHA, MAP_BETA, MAP_KAPPA)
        if resonance_growth_bound(ModelParams(v, a, b, k)) is not None
    ]
    assert len(hits) == 16 and set(hits) == set(RESONANT)


@pytest.mark.parametrize(
    ("varpi", "alpha", "beta", "kappa", "min_cycles", "min_mu"),
    [
        (1.0, 1.0 + 1e-5, 0.5, 0.1, 30_000, 0.99999),  # detuned 1e-5: |μ| ≈ 1 − 1e-6
        (1.0, 1.001, 0.5, 0.1, 500, 0.9999),  # detuned 1e-3
        (0.5, 4.02, 0.5, 0.1, 1, 0.99),  # detuned 0.5 %, below the resonance
        (1.95, 1.0, 0.5, 0.1, 10_000, 0.9),  # ϖ → 2: ~16 000 cycles to settle
        (1.9, 1.0, 0.1, 0.1, 4_000, 0.98),  # the ϖ = 1.9 map points beyond 3000 cycles
        (1.0, 0.5, 1.0, 0.4, 1, 0.5),  # on the stick resonance α(1 + 1/β)ϖ² = 1
    ],
)
def test_slow_or_near_resonant_orbits_still_converge(varpi, alpha, beta, kappa, min_cycles, min_mu):
    """Never flagged: these settle (shooting to residual ≤ 1e-10), though plain iteration
    from rest has not settled after ``min_cycles``."""
    p = ModelParams(varpi, alpha, beta, kappa)
    po = periodic_orbit(p)
    assert po.status == "success", po.message
    assert abs(simulate(p, min_cycles, log_events=False).delta_s[-1] - po.delta_s) > 1e-6
    assert max(po.floquet_moduli) >= min_mu


def test_exact_resonance_with_strong_friction_is_not_claimed_unbounded():
    """ακ ≥ 2: the bound gives nothing, so the status is never "unbounded"."""
    p = ModelParams(1.0, 1.0, 0.5, 2.5)
    assert resonance_growth_bound(p) is None
    assert periodic_orbit(p, max_cycles=2000).status != "unbounded"


def test_pushpull_summary_lists_unbounded_points_separately():
    """The map summary: the resonant point is listed under "unbounded" (and among the
    points without an orbit), with the growth message; the other point converges."""
    run, s = run_pushpull([0.5, 0.6], [4.0], [0.5], [0.4], executor=None)
    assert s.n_converged == 1
    assert [(d["varpi"], d["status"], d["resonance"]) for d in s.unbounded] == [
        (0.5, "unbounded", "alpha")
    ]
    assert s.unbounded[0] in s.not_converged
    assert "per cycle" in s.as_dict()["unbounded"][0]["message"]
    row = next(r for r in run.rows if r["varpi"] == 0.5)
    assert row["status"] == "unbounded" and row["mode"] is None and not row["converged"]


def test_unbounded_orbit_fails_the_mode_rule_with_its_reason():
    """rules: an unbounded result fails the mode rule (no steady motion, so the verdict
    fails) and says what to change; a plain solver failure fails it too."""
    from betvdesign.checks.rule import verdict
    from betvdesign.checks.rules import evaluate
    from betvdesign.nondim.device import derive
    from betvdesign.spec.loader import load_device

    base = derive(load_device(Path(__file__).resolve().parents[1] / "devices/shin2004.yaml"))
    p = ModelParams(1.5, 1 / 1.5**2, 0.5, 0.2)
    s = dataclasses.replace(base.sets[0], params=p, lam=p.lam, published=[])
    po = periodic_orbit(p)
    assert po.status == "unbounded"
    res = evaluate(s, orbit=po)
    (r,) = [r for r in res if r.id == "mode"]
    assert not r.passed and r.severity == "error" and "no periodic orbit exists" in r.message
    assert "unbounded" in r.message and "detune" in r.fix
    assert verdict(res) == "fail"
    plain = SimpleNamespace(success=False, status="not_converged", message="x", mode=None)
    (r,) = [r for r in evaluate(s, orbit=plain) if r.id == "mode"]
    assert r.severity == "error" and not r.passed and "not_converged" in r.message
