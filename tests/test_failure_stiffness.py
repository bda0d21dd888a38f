"""Failure map "stiffness": α → 0 (tangential frequency 1/√α).

Sources: right-hand-side evaluation counts of solve_ivp RK45 (explicit) at two α; the
fixed-step RK4's linear stability limit h < 2.8√α; the exact solver against the
α → 0 rigid limit in closed form (betvdesign.dynamics.rigid), a separate derivation.
"""

from __future__ import annotations

import math

import numpy as np

from betvdesign.bench.fixedstep import rk4_post
from betvdesign.dynamics import periodic_orbit, reference
from betvdesign.dynamics.rigid import rigid_periodic
from betvdesign.model.params import ModelParams


def test_explicit_cost_grows_like_inverse_sqrt_alpha():
    """RK45 needs ≥ 10× the evaluations when α drops 100× (1/√α = 10×)."""
    n = {}
    for a in (0.1, 0.001):
        r = reference.simulate(ModelParams(0.6, a, 1.5, 0.4), 3, method="RK45", rtol=1e-6)
        assert r.success
        n[a] = r.n_fev
    assert n[0.001] > 5 * n[0.1]


def test_fixed_step_blows_up_and_says_so():
    """h = T/100 > 2.8√α at α = 1e-4: RK4 diverges; reported as failed, never NaN."""
    p = ModelParams(0.6, 1e-4, 1.5, 0.4)
    h = 2 * math.pi / (0.6 * 100)
    assert h > 2.8 * math.sqrt(p.alpha)
    r = rk4_post(p, 5, 100)
    assert not r.success and r.status == "failed"
    assert "non-finite" in r.message and "1/sqrt(α)" in r.message
    assert np.all(np.isfinite(r.section))


def test_exact_converges_to_rigid_limit():
    """Exact periodic Δs at α = 1e-4 equals the closed-form α → 0 limit to 1e-3."""
    p = ModelParams(0.6, 1e-4, 1.5, 0.4)
    po = periodic_orbit(p)
    rig = rigid_periodic(p)
    assert po.success and rig.success
    assert po.mode == rig.mode == "pull"
    assert abs(po.delta_s - rig.delta_s) / abs(rig.delta_s) < 1e-3
