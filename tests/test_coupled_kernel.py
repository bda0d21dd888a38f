"""The coupled head's exact compiled solver (betvdesign.dynamics.coupled).

Independent truths:
- the coupled reference (scipy solve_ivp, DOP853 with events; it imports nothing of the
  kernel): sections and Δs to 1e-8 on 34 seeded designs, ρ from −0.999 to 0.9, χ from
  0.1 to 3 (a negative slip stiffness among them);
- the two-mode closed form of free flight (modal decomposition, no matrix exponential);
- at ρ = 0 the exact decoupled solver, bit for bit (the kernel dispatches to it);
- the kernel's periodic orbit is a fixed point of the reference's map.
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from betvdesign.checks.coupled import coupled_rung, coupling_of
from betvdesign.dynamics import periodic_orbit, simulate
from betvdesign.dynamics.coupled import (
    SLIP,
    CoupledModel,
    coupled_periodic_orbit,
    expm,
    simulate_coupled,
)
from betvdesign.dynamics.coupled_reference import simulate_coupled as reference
from betvdesign.errors import ParameterError
from betvdesign.model.params import HeadCoupling, ModelParams
from betvdesign.nondim.device import derive_file

DEVICES = Path(__file__).resolve().parents[1] / "devices"
TOL = 1e-8


def _designs() -> list[tuple[ModelParams, HeadCoupling]]:
    """32 seeded designs with ρ spread over [−0.999, 0.9] and χ over [0.1, 3], and two
    with a negative slip stiffness a(1 ± ακρ/χ) < 0."""
    rng = np.random.default_rng(2030)
    out = []
    for rho in np.linspace(-0.999, 0.9, 32):
        p = ModelParams(
            float(rng.uniform(0.5, 1.9)),
            float(rng.uniform(0.08, 2.5)),
            float(rng.uniform(0.2, 6.0)),
            float(rng.uniform(0.08, 0.6)),
        )
        out.append((p, HeadCoupling(float(rho), float(np.exp(rng.uniform(np.log(0.1), 1.1))))))
    out.append((ModelParams(1.1, 1.5, 1.0, 0.5), HeadCoupling(-0.6, 0.1)))
    out.append((ModelParams(0.9, 2.0, 2.0, 0.6), HeadCoupling(-0.3, 0.12)))
    return out


def _close(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.abs(a - b) / np.maximum(1.0, np.abs(b))))


@pytest.mark.parametrize(("p", "c"), _designs())
def test_matches_the_reference(p, c):
    """3 cycles from rest: sections, Δs and the event sequence of the solve_ivp reference."""
    n = 3
    ker = simulate_coupled(p, c, n)
    ref = reference(p, c, n)
    assert ker.status == "success", ker.message
    assert ref.status == "success", ref.message
    assert ker.solver == "coupled-exact"
    assert _close(ker.section, ref.section) < TOL
    scale = max(1.0, float(np.max(np.abs(ref.section[:, 4]))))
    assert np.max(np.abs(ker.delta_s - ref.delta_s)) < TOL * scale
    assert [e.kind for e in ker.events] == [k for _, k in ref.events]


def test_the_designs_cover_a_negative_slip_stiffness():
    """Two designs have a slip phase whose ζ stiffness is negative (a real growth rate)."""
    grow = 0
    for p, c in _designs()[-2:]:
        m = CoupledModel(p, c)
        lam = np.linalg.eigvals(m.amats[SLIP][2:4, 2:4])
        grow += bool(np.max(lam.real) > 0.0)
    assert grow >= 1


@pytest.mark.parametrize(
    ("rho", "chi", "alpha"), [(0.95, 0.7, 1.3), (-0.999, 0.4, 0.5), (0.6, 2.2, 2.0)]
)
def test_free_flight_is_the_two_mode_closed_form(rho, chi, alpha):
    """A cycle without a hit: the state is the modal closed form of
    ξ'' + a(ξ + cn ζ) = −a(1 − cn) sin ϖτ, α ζ'' + a(ct ξ + ζ) = −a(ct − 1) sin ϖτ."""
    c = HeadCoupling(rho, chi)
    p = ModelParams(5.0, alpha, 1.0, 0.3)
    a, cn, ct = c.a, rho / chi, rho * chi
    w = p.varpi
    kmat = np.array([[a, a * cn], [a * ct / alpha, a / alpha]])  # M⁻¹K
    f = np.array([-a * (1.0 - cn), -a * (ct - 1.0) / alpha])  # M⁻¹ forcing of sin ϖτ
    lam, vec = np.linalg.eig(kmat)
    lam, vec = lam.real, vec.real
    soft = vec[:, int(np.argmin(lam))]
    q0 = 1e3 * soft / soft[0]  # far out along the soft mode: no hit in one cycle
    y0 = [q0[0], 0.0, q0[1], 0.0, 0.3, 0.05]
    run = simulate_coupled(p, c, 1, state0=y0)
    assert run.status == "success" and not run.events
    tau = 2.0 * math.pi / w
    inv = np.linalg.inv(vec)
    eta0, g = inv @ q0, inv @ f
    om = np.sqrt(lam)
    eta = eta0 * np.cos(om * tau) + g / (lam - w**2) * (np.sin(w * tau) - w / om * np.sin(om * tau))
    deta = -eta0 * om * np.sin(om * tau) + g / (lam - w**2) * (
        w * np.cos(w * tau) - w * np.cos(om * tau)
    )
    q, dq = vec @ eta, vec @ deta
    want = np.array([q[0], dq[0], q[1], dq[1], 0.3 + 0.05 * tau, 0.05])
    assert _close(run.section[1], want) < 1e-11


@pytest.mark.parametrize("seed", [3, 11])
def test_rho_zero_is_the_exact_solver_bit_for_bit(seed):
    """ρ = 0 (any χ): the kernel returns the exact decoupled solver's answers unchanged."""
    rng = np.random.default_rng(seed)
    p = ModelParams(*(float(x) for x in rng.uniform((0.6, 0.1, 0.3, 0.1), (1.8, 2.0, 4.0, 0.5))))
    ex, ker = simulate(p, 20), simulate_coupled(p, HeadCoupling(0.0, 0.7), 20)
    assert np.array_equal(ex.section, ker.section) and ker.solver == ex.solver
    po, ko = periodic_orbit(p), coupled_periodic_orbit(p, HeadCoupling(0.0, 2.0))
    assert ko.status == po.status and ko.delta_s == po.delta_s
    if po.state is not None:
        assert np.array_equal(po.state, ko.state)


@pytest.mark.parametrize(("stem", "period"), [("shin2004", 1), ("pull_demo", 3)])
def test_rung_orbit_is_a_fixed_point_of_the_reference_map(stem, period):
    """The drawn set's coupled orbit (the rung: Newton on the kernel) repeats under the
    reference over its period; pull_demo's settles to period 3."""
    sd = derive_file(DEVICES / f"{stem}.yaml").sets[0]
    p = replace(sd.params, zeta_v=0.0, zeta_h=0.0, restitution=0.0)
    r = coupled_rung(sd)
    o = r.coupled
    assert o.status == "success" and o.period == period
    run = reference(p, coupling_of(sd), period, state0=o.state)
    assert abs(np.mean(run.delta_s) - o.delta_s) < 1e-8 * abs(o.delta_s)
    assert np.allclose(run.section[-1][[0, 1, 2, 3, 5]], o.state[[0, 1, 2, 3, 5]], atol=1e-8)


def test_an_unstable_orbit_is_not_an_answer():
    """pull_demo: Newton from the decoupled orbit lands on an unstable period-1 orbit of
    the coupled model (the reference's Newton finds the same Δs): it is refused, with
    its multipliers."""
    sd = derive_file(DEVICES / "pull_demo.yaml").sets[0]
    p = replace(sd.params, zeta_v=0.0, zeta_h=0.0, restitution=0.0)
    ex = periodic_orbit(p)
    o = coupled_periodic_orbit(p, coupling_of(sd), guess=ex.state, period=1)
    assert o.status == "not_converged" and "unstable" in o.message
    assert o.stable is False and abs(o.floquet[0]) > 1.0
    assert o.delta_s is None and o.state is None


def test_expm_against_closed_forms():
    """exp of a rotation and of a Jordan block, to round-off."""
    t = 37.3
    r = expm(np.array([[0.0, t], [-t, 0.0]]))
    assert np.allclose(r, [[math.cos(t), math.sin(t)], [-math.sin(t), math.cos(t)]], atol=1e-12)
    j = expm(np.array([[2.0, 1.0], [0.0, 2.0]]))
    assert np.allclose(j, math.exp(2.0) * np.array([[1.0, 1.0], [0.0, 1.0]]), rtol=1e-14)


def test_stiff_head_does_not_crawl():
    """ρ = 0.9999 (a = 5000, √λ₊/ϖ ≈ 72): 50 cycles run in well under a second and the
    first 3 agree with the reference to 1e-7 (the reference's own error there: 3e-8
    against the exact-flow automaton of test_coupled_reference, measured, which the
    kernel meets to 3e-9; the stiff mode amplifies round-off)."""
    p = ModelParams(1.2, 2.04, 0.5, 0.15)
    c = HeadCoupling.from_angle(0.9999, p.alpha, math.pi / 4)
    ker = simulate_coupled(p, c, 50, log_events=False)
    assert ker.status == "success"
    assert ker.elapsed_s < 1.0
    ref = reference(p, c, 3)
    assert _close(ker.section[:4], ref.section) < 1e-7


def test_bad_inputs():
    c = HeadCoupling(0.2, 1.0)
    p = ModelParams(1.0, 1.0, 1.0, 0.3)
    with pytest.raises(ParameterError, match="ideal"):
        simulate_coupled(ModelParams(1.0, 1.0, 1.0, 0.3, zeta_v=0.01), c, 2)
    with pytest.raises(ParameterError, match="cycles"):
        simulate_coupled(p, c, -1)
    with pytest.raises(ParameterError, match="state0"):
        simulate_coupled(p, c, 2, state0=[-1, 0, 0, 0, 0, 0])
    with pytest.raises(ParameterError, match="HeadCoupling"):
        simulate_coupled(p, (0.2, 1.0), 2)
    with pytest.raises(ParameterError, match="period"):
        coupled_periodic_orbit(p, c, period=0)
    with pytest.raises(ParameterError, match="guess"):
        coupled_periodic_orbit(p, c, guess=[0.0, 0.0])
