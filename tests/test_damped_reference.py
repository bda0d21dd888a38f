"""Exact solver with damping and restitution against the independent solve_ivp reference.

Source of truth: :mod:`betvdesign.dynamics.reference` (with :mod:`reference_terms`), a
second method: the full state is integrated numerically (DOP853, rtol 1e-13), events are
located by ``solve_ivp``'s own root finding (with a watch for crossings inside one step),
the damped equations, normal force, stick band and restitution are written there again
from shared MODEL.md "Beyond the paper's idealisation", and chattering sequences are
followed hit by hit to flights of 1e-9 before a geometric tail of its own closes them.
Nothing of the exact solver's closed forms, event search or chattering closure is
shared (test_dynamics_reference.py checks the imports).

Designs: 24 drawn over the design window 0.5 ≤ ϖ < 2 (α, β, κ log-uniform as in
conftest.WINDOW_SETS), ζ_v and ζ_h log-uniform in [0.005, 0.3] (one of them 0 in a third
of the designs each), restitution e in [0.02, 0.6] in every other design (at ϖ ≤ 1.3,
where contacts recur, so that chattering sequences are exercised). Compared: 100-cycle
transients, and the exact solver's periodic orbits as fixed points of one reference cycle.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from betvdesign.dynamics import reference, simulate
from betvdesign.model.params import ModelParams

CYCLES = 100
TOL = 1e-8
RTOL, ATOL = 1e-13, 1e-14


def damped_designs(n: int = 24, seed: int = 2026) -> list[ModelParams]:
    """n designs with damping and (every other one) restitution; see module doc."""
    rng = np.random.default_rng(seed)
    out = []
    for i in range(n):

        def lz() -> float:
            return float(10 ** rng.uniform(math.log10(0.005), math.log10(0.3)))

        w = float(rng.uniform(0.5, 1.95)) if i % 2 == 0 else float(rng.uniform(0.5, 1.3))
        zv = lz() if i % 3 != 2 else 0.0
        zh = lz() if i % 3 != 1 else 0.0
        e = 0.0 if i % 2 == 0 else float(rng.uniform(0.02, 0.6))
        out.append(
            ModelParams(
                w,
                float(10 ** rng.uniform(-1.3, 0.5)),
                float(10 ** rng.uniform(-1, 1)),
                float(10 ** rng.uniform(-1.3, 0)),
                zv,
                zh,
                e,
            )
        )
    return out


DESIGNS = damped_designs()


def _cases():
    for i, p in enumerate(DESIGNS):
        ident = f"{i}-w{p.varpi:.2f}-zv{p.zeta_v:.3f}-zh{p.zeta_h:.3f}-e{p.restitution:.2f}"
        yield pytest.param(p, id=ident)


def _run(p: ModelParams):
    ex = simulate(p, CYCLES)
    rf = reference.simulate(p, CYCLES, method="DOP853", rtol=RTOL, atol=ATOL)
    assert ex.success and rf.success, (ex.message, rf.message)
    return ex, rf


def _contacts(tr) -> list[tuple[str, str, str]]:
    """The event sequence without impulsive hits (whose number in a chattering sequence
    depends on where each method closes it)."""
    return [(e.kind, e.phase_before, e.phase_after) for e in tr.events if e.kind != "impulsive"]


@pytest.mark.slow
@pytest.mark.parametrize("p", list(_cases()))
def test_exact_agrees_with_reference_after_100_cycles(p):
    """Every section state (ξ, ξ', ζ, ζ', s, s') of 100 cycles within 1e-8 (relative to
    max(1, |x|)), the same contact events in the same order, contact starts within 1e-8."""
    ex, rf = _run(p)
    scale = np.maximum(1.0, np.abs(ex.section))
    err = float(np.max(np.abs(ex.section - rf.section) / scale))
    assert err <= TOL, f"sections differ by {err:.3g}"
    a, b = _contacts(ex), _contacts(rf)
    assert a == b
    ta = np.array([e.tau for e in ex.events if e.kind != "impulsive"])
    tb = np.array([e.tau for e in rf.events if e.kind != "impulsive"])
    assert np.max(np.abs(ta - tb)) <= TOL * max(1.0, float(ta[-1]))


def test_designs_exercise_every_term():
    """The set is what the module doc says: damping in both directions, restitution with
    recurring (chattering) contacts, spread over the window."""
    w = [p.varpi for p in DESIGNS]
    assert len(DESIGNS) >= 20 and min(w) < 0.7 and max(w) > 1.6
    assert sum(p.zeta_v > 0 for p in DESIGNS) >= 12 and sum(p.zeta_h > 0 for p in DESIGNS) >= 12
    bouncy = [p for p in DESIGNS if p.restitution > 0]
    assert len(bouncy) >= 10 and max(p.restitution for p in bouncy) > 0.4
    chattering = 0
    for p in bouncy:
        rf = reference.simulate(p, 6, rtol=1e-10, atol=1e-12)
        chattering += "chattering" in rf.message
    assert chattering >= 5


def test_normal_force_vanishes_at_the_contact_ends():
    """The time origin both solvers share (N rises through 0 at τ = 0): MODEL.md's
    N = sin ϖτ_o + 2ζ_vϖ cos ϖτ_o, with τ = τ_o + δ/ϖ, is 0 at τ = 0 and τ = π/ϖ, where
    the reference integrates contacts to (its lead δ computed from its definition)."""
    from betvdesign.dynamics.reference_terms import constants, normal_force

    for p in DESIGNS:
        k = constants(p)
        T = 2.0 * math.pi / p.varpi
        assert abs(normal_force(k, 0.0)) < 1e-15 and abs(normal_force(k, T / 2)) < 1e-15
        assert normal_force(k, T / 4) > 0.0 > normal_force(k, 3 * T / 4)


def test_reference_sees_the_damping():
    """The reference is not blind to the terms: each of ζ_v, ζ_h, e changes its sections
    by far more than the agreement tolerance."""
    p = DESIGNS[3]
    base = reference.simulate(ModelParams(p.varpi, p.alpha, p.beta, p.kappa), 10).section
    for kw in ({"zeta_v": 0.02}, {"zeta_h": 0.02}, {"restitution": 0.2}):
        q = ModelParams(p.varpi, p.alpha, p.beta, p.kappa, **kw)
        assert np.max(np.abs(reference.simulate(q, 10).section - base)) > 1e-4, kw


def test_reference_gives_up_loudly_on_endless_rebounds(monkeypatch):
    """A rebound sequence is never followed for ever: past MAX_HITS hits in a cycle the
    reference stops with status "failed", the cycles done so far kept."""
    monkeypatch.setattr(reference, "MAX_HITS", 5)
    p = ModelParams(0.67, 1.64, 0.49, 0.39, 0.0, 0.072, 0.44)  # ≈ 27 hits per cycle
    rf = reference.simulate(p, 4, rtol=1e-10, atol=1e-12)
    assert rf.status == "failed" and not rf.success
    assert "more than 5 hits" in rf.message and rf.n_cycles < 4
    assert rf.section.shape == (rf.n_cycles + 1, 6)


def _orbit_cases():
    for i, p in enumerate(DESIGNS):
        yield pytest.param(p, id=f"{i}-e{p.restitution:.2f}")


@pytest.mark.parametrize("p", list(_orbit_cases()))
def test_periodic_orbit_is_a_fixed_point_of_the_reference(p):
    """The exact solver's periodic orbit (shooting on its closed forms) is mapped onto
    itself, shifted by Δs, by one reference cycle (1e-10 of the state's size); designs
    whose contact does not recur are reported not driven by both."""
    from betvdesign.dynamics import periodic_orbit

    po = periodic_orbit(p)
    if not po.success:
        assert po.status == "not_driven"
        rf = reference.simulate(p, 3, rtol=1e-10, atol=1e-12)
        assert sum(e.kind == "impact" for e in rf.events) == 1  # only the initial contact
        return
    rf = reference.simulate(p, 1, state0=po.state, rtol=RTOL, atol=ATOL)
    d = rf.section[1] - np.asarray(po.state)
    d[4] -= po.delta_s
    assert np.max(np.abs(d)) <= 1e-10 * max(1.0, float(np.max(np.abs(po.state))))


@pytest.mark.slow
@pytest.mark.parametrize(
    "p,what",
    [
        (ModelParams(1.0, 0.5, 1.0, 0.4, 0.01, 0.0), "ϖ = 1: vertical resonance, damped"),
        (ModelParams(1.0, 1.0, 1.0, 0.4, 0.0, 0.02), "αϖ² = 1: free tangential resonance"),
        (ModelParams(1.25, 0.32, 1.0, 0.4, 0.01, 0.01), "α(1+1/β)ϖ² = 1: stick resonance"),
        (ModelParams(0.9, 0.1, 0.9, 0.4, 1.0, 1.0), "critically damped head"),
        (ModelParams(0.9, 0.1, 0.9, 0.4, 0.02, 3.0), "tangentially overdamped"),
        (ModelParams(0.6, 0.3, 2.0, 0.5, 2.0, 0.5, 0.2), "overdamped normal, chattering"),
    ],
)
def test_resonant_and_heavily_damped_against_reference(p, what):
    """Where the undamped closed forms are secular or the damped ones change branch
    (critical, overdamped): 40 cycles within 1e-8."""
    ex = simulate(p, 40)
    rf = reference.simulate(p, 40, rtol=RTOL, atol=ATOL)
    assert ex.success and rf.success, (ex.message, rf.message)
    err = float(np.max(np.abs(ex.section - rf.section) / np.maximum(1.0, np.abs(ex.section))))
    assert err <= TOL, (what, err)


def _slip_sign_violation(tr, m: int, p: ModelParams) -> float:
    """Largest violation of the slip direction in cycle m on the dense output (2000
    points per phase): ζ' − s' ≥ 0 in slip, ≤ 0 in reverse slip (MODEL.md: the phase is
    the sign of ζ' − s')."""
    T = 2 * math.pi / p.varpi
    ev = [e for e in tr.events if m * T <= e.tau < (m + 1) * T]
    worst = 0.0
    for a, b in zip(ev, [*ev[1:], None], strict=True):
        t1 = b.tau if b is not None else (m + 1) * T
        if a.phase_after not in ("slip", "reverse") or t1 <= a.tau:
            continue
        x = tr.sample(np.linspace(a.tau, t1, 2000)[1:-1])
        rel = (x[:, 3] - x[:, 5]) * (1.0 if a.phase_after == "slip" else -1.0)
        worst = max(worst, float(-rel.min()))
    return worst


def test_reference_finds_grazing_velocity_matches(monkeypatch):
    """Design 19 grazes ζ' = s' in cycle 10 (at rtol 1e-12 a dip of 6e-5 inside one step):
    with the minimum watch the reference sees it (slip never runs the wrong way);
    without it, slip carries on with ζ' < s'."""
    p, n = DESIGNS[19], 11
    rf = reference.simulate(p, n, rtol=1e-12, atol=1e-13, dense=True)
    assert "grazing" in rf.message
    assert _slip_sign_violation(rf, 10, p) < 1e-9
    monkeypatch.setattr(reference, "WATCHED", ())
    blind = reference.simulate(p, n, rtol=1e-12, atol=1e-13, dense=True)
    assert _slip_sign_violation(blind, 10, p) > 1e-5


@pytest.mark.parametrize("alpha", [1.0, 4.0, 0.25, 1.21])
def test_balanced_dampers_start_of_contact(alpha):
    """ζ_h√α = ζ_v (e.g. Q_v = Q_h at α = 1): at the contact start from rest both the
    normal force and the tangential drive vanish, a doubly degenerate phase decision
    (the exact solver once chattered there between slip and velocity match at τ ≈ 1e-17,
    found by a Q = 30 map at α = 1). 20 cycles agree with the reference to 1e-8 and
    the first contact phase is the reference's."""
    zv = 1 / 60
    p = ModelParams(0.8, alpha, 0.5, 0.4, zv, zv / math.sqrt(alpha), 0.0)
    ex = simulate(p, 20)
    rf = reference.simulate(p, 20, method="DOP853", rtol=RTOL, atol=ATOL)
    assert ex.success and rf.success, (ex.message, rf.message)
    assert ex.events[0].phase_after == rf.events[0].phase_after
    d = np.abs(ex.section - rf.section) / np.maximum(1.0, np.abs(rf.section))
    assert d.max() <= TOL


@pytest.mark.parametrize("idx", [0, 3, 8, 13, 17, 19, 23])
def test_floquet_multipliers_are_the_reference_maps(idx):
    """The damped periodic orbit's Floquet multipliers (the exact solver's variational
    closed forms) are the eigenvalues of the reference's one-cycle map on (ζ, ζ', s'),
    differentiated by central differences (step 1e-6, reference at rtol 1e-13): to 1e-7
    (measured 1e-9 to 2e-8: the differences' truncation and the reference's tolerance)."""
    from betvdesign.dynamics import periodic_orbit

    p = DESIGNS[idx]
    po = periodic_orbit(p)
    assert po.success and po.floquet is not None, po.message
    x0 = np.asarray(po.state, dtype=float)
    keys, h = (2, 3, 5), 1e-6
    J = np.empty((3, 3))
    for j, k in enumerate(keys):
        cols = []
        for sgn in (1.0, -1.0):
            x = x0.copy()
            x[k] += sgn * h
            rf = reference.simulate(p, 1, state0=x, rtol=RTOL, atol=ATOL)
            assert rf.success, rf.message
            cols.append(rf.section[1][list(keys)])
        J[:, j] = (cols[0] - cols[1]) / (2 * h)
    mu_ref = np.sort_complex(np.linalg.eigvals(J))
    mu = np.sort_complex(np.asarray(po.floquet, dtype=complex))
    assert np.allclose(mu, mu_ref, rtol=0.0, atol=1e-7), (mu, mu_ref)
