"""How well Δs is determined, and which answer a verdict quotes (issue 24).

Independent truths: the transient from rest (time stepping, not Newton), an
independent solve_ivp integration (dynamics.reference, no shared code), and periodic
re-solves at other perturbation sizes than the estimate uses (brute force).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from betvdesign.checks.travel import travel_answer
from betvdesign.dynamics import periodic_orbit, simulate
from betvdesign.dynamics.determination import degeneracy, determine
from betvdesign.dynamics.reference import simulate as reference_simulate
from betvdesign.dynamics.settling import settling
from betvdesign.model.domain import DELTA_S_STALL, mode_of
from betvdesign.model.params import ModelParams

PUSH = ModelParams(1.2, 2.04, 0.509, 0.15)


def _spread(p: ModelParams, rel: float) -> float:
    """Brute force: largest change of Δs when ϖ, α, β, κ move by ±rel (8 full solves)."""
    base = periodic_orbit(p).delta_s
    out = 0.0
    for name in ("varpi", "alpha", "beta", "kappa"):
        for sign in (1.0, -1.0):
            q = dataclasses.replace(p, **{name: getattr(p, name) * (1 + sign * rel)})
            r = periodic_orbit(q)
            out = max(out, abs(r.delta_s - base) if r.success else math.inf)
    return out


def test_mode_of_reads_the_error() -> None:
    assert mode_of(2.0) == "push" and mode_of(-2.0) == "pull" and mode_of(0.0) == "stalled"
    assert mode_of(2.0, error=1e-12) == "push"
    assert mode_of(2.0, error=0.5) == "undetermined"  # speed not known to 1 %
    assert mode_of(-0.3, error=0.4) == "undetermined"  # sign not known
    assert mode_of(1e-10, error=1e-10) == "stalled"
    assert mode_of(1e-10, error=5e-9) == "undetermined"  # cannot tell stalled from moving
    assert mode_of(1.0, error=math.nan) == "undetermined"


@pytest.mark.slow
def test_a_typical_design_is_determined_and_its_delta_s_is_what_the_transient_shows() -> None:
    po = periodic_orbit(PUSH)
    d = determine(PUSH, po)
    assert d.status == "determined" and d.mode == "push"
    assert d.delta_s_error < 1e-9
    # truth: the transient from rest (time stepping) settles onto the same increment
    tr = simulate(PUSH, 600, log_events=False)
    assert np.mean(tr.delta_s[-50:]) == pytest.approx(po.delta_s, rel=1e-8)


def test_friction_below_round_off_is_named_before_solving_and_the_slider_does_not_move() -> None:
    """Impact angle 1e-12° (κ ≈ 7e-15): the orbit the solver finds is noise (issue 24)."""
    p = ModelParams(1.2, 2.04, 0.509, 0.4 * math.tan(math.radians(1e-12)))
    found = degeneracy(p)
    assert found is not None
    why, fix = found
    assert "friction κ" in why and "impact angle" in fix
    d = determine(p, periodic_orbit(p))
    assert d.status == "degenerate" and d.mode == "undetermined"
    # truth: an independent integration (solve_ivp, its own switching) barely moves it
    ref = reference_simulate(p, 20, rtol=1e-10, atol=1e-12)
    assert abs(ref.s) < 1e-9


@pytest.mark.parametrize("kappa", [1e-10, 3e-10])
def test_vanishing_friction_is_undetermined_where_brute_force_disagrees(kappa: float) -> None:
    p = dataclasses.replace(PUSH, kappa=kappa)
    po = periodic_orbit(p)
    d = determine(p, po)
    assert d.status == "undetermined" and d.mode == "undetermined" and "not determined" in d.reason
    # truth: other perturbation sizes (not the estimate's) move Δs by more than 1 %
    assert _spread(p, 1e-11) > 0.01 * abs(po.delta_s)


@pytest.mark.parametrize(
    "p",
    [
        dataclasses.replace(PUSH, kappa=1e-6),
        dataclasses.replace(PUSH, beta=1e-6),
        ModelParams(1.0, 0.999, 1.0, 0.4),  # undamped, 0.1 % from α·ϖ² = 1
        ModelParams(1.2, 2.04, 0.509, 0.15, zeta_v=0.02, zeta_h=0.02, restitution=0.1),
    ],
    ids=["kappa-1e-6", "beta-1e-6", "near-resonance", "damped-restitution"],
)
def test_slow_but_determined_orbits_are_determined_and_brute_force_agrees(p) -> None:
    po = periodic_orbit(p)
    d = determine(p, po)
    assert d.status == "determined", d.reason
    # truth: brute-force re-solves at other perturbations than the estimate's agree within 1 %
    assert _spread(p, 3e-11) <= 0.01 * abs(po.delta_s)


def test_a_heavy_slider_quotes_its_travel_not_its_orbit() -> None:
    """β = 1e-6: periodic Δs = 2.22 but the transient from rest gains ~0.05 per cycle after
    10⁵ cycles (issue 24): the answer is the crossing, whatever the orbit says."""
    p = dataclasses.replace(PUSH, beta=1e-6)
    po = periodic_orbit(p)
    assert po.delta_s == pytest.approx(2.216, rel=1e-3)
    st = settling(p, po.delta_s, travel_s=380.0, max_cycles=20_000)
    ans = travel_answer(po, determine(p, po), st)
    # truth: the transient itself
    tr = simulate(p, 20_000, log_events=False)
    s = tr.section[:, 4]
    crossed = np.nonzero(np.abs(s) >= 380.0)[0]
    if len(crossed):
        assert ans.basis == "crossing" and ans.cycles_to_cross == int(crossed[0])
        assert ans.delta_s == pytest.approx(s[crossed[0]] / crossed[0], rel=1e-12)
        assert ans.delta_s < 0.5 * po.delta_s
    else:
        assert ans.basis == "no-crossing" and ans.delta_s is None


def test_near_resonance_without_damping_quotes_the_travel() -> None:
    """α·ϖ² = 0.9999: |μ| → 1, the transient is still far from the orbit when it crosses."""
    p = ModelParams(1.0, 0.9999, 1.0, 0.4)
    po = periodic_orbit(p)
    st = settling(p, po.delta_s, travel_s=380.0, max_cycles=20_000)
    ans = travel_answer(po, determine(p, po), st)
    assert ans.basis in ("crossing", "no-crossing")
    tr = simulate(p, 200, log_events=False)
    s = tr.section[:, 4]
    if ans.basis == "crossing":
        m = ans.cycles_to_cross
        assert np.sign(s[min(m, 200)]) == np.sign(ans.delta_s)  # the direction it travels


def test_stall_threshold_unchanged_for_exact_reads() -> None:
    """error = 0 reads Δs as before: the stall threshold is the only cut."""
    assert mode_of(DELTA_S_STALL) == "stalled" and mode_of(2 * DELTA_S_STALL) == "push"


# --- the verdict against the transient, over the edges of the parameter space -------------

TRAVEL = 380.0  # travel range [units of u·cosθ], about 50 µm at u·cosθ = 0.13 µm


def _transient_truth(p: ModelParams, horizon: int) -> tuple[int | None, float]:
    """(first cycle at which |s| ≥ TRAVEL, s there) of a plain run from rest (no Newton,
    no settling logic), or (None, s at the horizon)."""
    tr = simulate(p, horizon, log_events=False)
    s = tr.section[:, 4]
    hit = np.nonzero(np.abs(s) >= TRAVEL)[0]
    return (int(hit[0]), float(s[hit[0]])) if len(hit) else (None, float(s[-1]))


def _assert_transient_agrees(p: ModelParams) -> dict:
    from betvdesign.bench.verdictmap import classify

    row = classify(p, TRAVEL)
    if row["label"] in ("periodic", "crossing") and row["mode"] in ("push", "pull"):
        n = row["cycles_to_cross"]
        cross, s = _transient_truth(p, (n or 1000) + 10)
        assert cross is not None, f"{p}: the verdict says it crosses; the transient does not"
        assert (s > 0) == (row["mode"] == "push"), f"{p}: {row['mode']} but s = {s}"
        if row["label"] == "crossing":
            assert cross == n and row["delta_s"] == pytest.approx(s / cross, rel=1e-12)
    elif row["label"] == "no-crossing":
        cross, _ = _transient_truth(p, 200_000)
        assert cross is None, f"{p}: no-crossing, but the transient crosses at {cross}"
    elif row["label"] == "undetermined":
        assert row["mode"] == "undetermined"
        cross, _ = _transient_truth(p, 20_000)
        assert cross is None
    return row


@pytest.mark.parametrize(
    "p",
    [
        dataclasses.replace(PUSH, kappa=1e-14),  # κ → 0: friction below round-off
        dataclasses.replace(PUSH, kappa=1e-9),  # κ → 0: determined, but never crosses
        dataclasses.replace(PUSH, kappa=1e-5),  # κ → 0: crosses long before it settles
        dataclasses.replace(PUSH, beta=1e-6),  # β → 0: heavy slider
        dataclasses.replace(PUSH, beta=1e3),  # β → ∞: light slider
        dataclasses.replace(PUSH, alpha=1e-5),  # α → 0: rigid contact, pull
        dataclasses.replace(PUSH, alpha=1e3),  # α → ∞
        ModelParams(1.0, 0.9999, 1.0, 0.4),  # α·ϖ² → 1, undamped
        ModelParams(1.0, 0.9999, 1.0, 0.4, zeta_v=0.005, zeta_h=0.005),  # damped, Q = 100
        dataclasses.replace(PUSH, varpi=0.5),  # lower window edge
        dataclasses.replace(PUSH, varpi=1.99),  # upper window edge
        dataclasses.replace(PUSH, restitution=0.9),  # e near its not-driven threshold
    ],
    ids=[
        "kappa-1e-14",
        "kappa-1e-9",
        "kappa-1e-5",
        "beta-1e-6",
        "beta-1e3",
        "alpha-1e-5",
        "alpha-1e3",
        "resonance",
        "resonance-damped",
        "varpi-0.5",
        "varpi-1.99",
        "restitution-0.9",
    ],
)
def test_edge_families_the_verdict_is_what_the_transient_shows(p: ModelParams) -> None:
    _assert_transient_agrees(p)


@pytest.mark.slow
def test_no_random_design_passes_with_a_mode_its_transient_contradicts() -> None:
    """Designs drawn log-uniformly over many decades (seeded): every push/pull answer is
    borne out by the plain transient from rest."""
    rng = np.random.default_rng(20261125)
    for _ in range(24):
        p = ModelParams(
            float(rng.uniform(0.5, 1.99)),
            float(10 ** rng.uniform(-4, 3)),
            float(10 ** rng.uniform(-8, 3)),
            float(10 ** rng.uniform(-14, 1)),
        )
        _assert_transient_agrees(p)


# --- what a designer reads: headline, settling line and verdict agree ----------------------

DEVICES = __import__("pathlib").Path(__file__).resolve().parents[1] / "devices"


@pytest.mark.slow
@pytest.mark.parametrize(
    "angle, verdict",
    # the smallest angle a file may give is 1e-6 deg (spec.limits: below it derived values
    # underflow): κ = 0.4·tan(1e-6°) ≈ 7e-9 does not cross its travel within the horizon
    [("20.56 deg", "pass"), ("1e-6 deg", "fail"), ("3e-6 deg", None), ("0.001 deg", None)],
)
def test_headline_and_settling_line_never_contradict(angle: str, verdict: str | None) -> None:
    import betvdesign as bd

    spec = bd.load_device(DEVICES / "push_demo.yaml").replace("contact.impact_angle", angle)
    res = bd.check(spec)
    text = res.view.text(width=400)
    sc = res.sets[0]
    settle = next((r for r in sc.rules if r.id == "settling"), None)
    headline = text.splitlines()[1]
    says_crosses = " in " in headline and "toward" in headline
    if settle is not None and "does not cross" in settle.message:
        assert not says_crosses and "does not cross" in headline
        assert res.verdict == "fail"
    if says_crosses:
        assert settle is None or "does not cross" not in settle.message
        assert sc.travel.basis in ("periodic", "crossing")
    if sc.mode == "undetermined":
        assert res.verdict == "fail" and "undetermined" in headline
    if verdict is not None:
        assert res.verdict == verdict
