"""Failure map "grazing": contacts shorter than a step near ϖ → 2.

Sources: the exact solver's event log (one contact per cycle, certified hits) against
an independent solution (solve_ivp DOP853 with event location, rtol 1e-11); the
coarse fixed-step method (RK4, events post-detected at step ends) reproduces the
failure: contacts taken for impulsive hits and s off by more than 1e-3.
"""

from __future__ import annotations

import pytest

from betvdesign.bench.fixedstep import rk4_post
from betvdesign.dynamics import reference, simulate
from betvdesign.model.params import ModelParams

P = ModelParams(1.99, 1.0, 0.5, 0.1)  # contact ≈ 0.2 % of the cycle
CYCLES = 30


@pytest.fixture(scope="module")
def exact():
    return simulate(P, CYCLES)


def test_exact_one_contact_per_cycle(exact):
    """Exact: one contact-opening hit per cycle, no impulsive hit, s = solve_ivp's."""
    kinds = [e.kind for e in exact.events]
    assert kinds.count("impact") == CYCLES
    assert kinds.count("impulsive") == 0
    assert kinds.count("separation") == CYCLES
    ref = reference.simulate(P, CYCLES, method="DOP853", rtol=1e-11, atol=1e-13)
    assert ref.success
    assert exact.s == pytest.approx(ref.s, rel=1e-8)


def test_coarse_fixed_step_misses_contacts(exact):
    """RK4 at h = T/50 with post-detection: contacts become impulsive hits, s drifts."""
    r = rk4_post(P, CYCLES, 50)
    assert r.success  # it does not notice anything
    assert r.n_impulsive > 5  # ... but several contacts were taken for impulsive hits
    assert r.n_contacts < CYCLES
    assert abs(r.s - exact.s) / abs(exact.s) > 1e-3


def test_exact_continuous_at_window_edge():
    """ϖ = 0.5: the head lands exactly at a contact start (a phase boundary); the exact
    solver's s is the limit from both sides (no misclassified hit)."""
    vals = [
        simulate(ModelParams(w, 0.5, 0.5, 0.4), 10, log_events=False).s
        for w in (0.5 - 1e-9, 0.5, 0.5 + 1e-9)
    ]
    assert vals[1] == pytest.approx(vals[0], rel=1e-6)
    assert vals[1] == pytest.approx(vals[2], rel=1e-6)
