"""Energy balance per cycle of the damped model with restitution (an independent truth).

Source of truth: the work–energy identity of MODEL.md's equations, derived here (not in
the solvers). With the cart at c = sin ψ (ψ = ϖτ − δ, the solvers' time origin), the
normal spring stretched by q = ξ + c and the tangential one by r = ζ − c:

- vertical: E_v = ½ξ'² + ½q²; the cart feeds c'(q + 2ζ_v q'), the damper takes
  2ζ_v q'² (in contact ξ ≡ 0: E_v = ½c², the feed is c'N), a hit takes ½ξ'⁻²(1 − e²)
  (a contact start ½ξ'⁻²);
- tangential: E_h = ½αζ'² + ½r² + ½(α/β)s'²; the cart feeds −c'(r + 2ζ_h√α r'), the
  damper takes 2ζ_h√α r'², friction takes ακN|ζ' − s'| in contact (0 in stick), N =
  sin ψ + 2ζ_vϖ cos ψ.

So over every cycle, work by the forcing − change of stored energy = damper dissipation
+ friction work + impact losses, in each direction. The terms are integrated here by
Gauss–Legendre quadrature (16 nodes on pieces ≤ 0.25 long between the logged events,
where the motion is smooth) of the solver's dense output; the impact velocities are its
left limits at the hits. Checked on the exact solver's trajectory and on the reference's.
"""

from __future__ import annotations

import math
from itertools import pairwise

import numpy as np
import pytest

from betvdesign.dynamics import reference, simulate
from betvdesign.model.params import ModelParams

NODES, LEG = np.polynomial.legendre.leggauss(16)
PIECE = 0.25
CYCLES = 3

DESIGNS = [
    ModelParams(0.9, 0.1, 0.9, 0.4, 0.05, 0.05, 0.0),  # published fit, Q = 10
    ModelParams(1.3, 0.43, 2.09, 0.7, 0.0, 0.013, 0.0),
    ModelParams(0.76, 0.23, 0.51, 0.53, 0.069, 0.034, 0.0),
    ModelParams(1.43, 0.48, 6.83, 0.10, 0.074, 0.0, 0.0),
    ModelParams(0.98, 0.64, 0.64, 0.5, 0.0, 0.14, 0.10),  # chattering, undamped vertical
    ModelParams(0.67, 1.64, 0.49, 0.39, 0.0, 0.072, 0.44),
    ModelParams(0.9, 0.3, 1.0, 0.3, 0.05, 0.3, 0.3),  # chattering with damping
    ModelParams(1.0, 1.0, 1.0, 0.4, 1.0, 0.02, 0.0),  # critically damped head, αϖ² = 1
]


class Terms:
    """The energy terms of one parameter set (module doc), on arrays of τ and states."""

    def __init__(self, p: ModelParams, zeta_h: float | None = None):
        self.p = p
        self.w = p.varpi
        self.lead = math.atan2(2.0 * p.zeta_v * p.varpi, 1.0)
        self.ch = 2.0 * (p.zeta_h if zeta_h is None else zeta_h) * math.sqrt(p.alpha)

    def cart(self, tau):
        psi = self.w * tau - self.lead
        return np.sin(psi), self.w * np.cos(psi)

    def stored(self, tau, x) -> tuple:
        c, _ = self.cart(tau)
        p = self.p
        ev = 0.5 * x[..., 1] ** 2 + 0.5 * (x[..., 0] + c) ** 2
        eh = 0.5 * p.alpha * x[..., 3] ** 2 + 0.5 * (x[..., 2] - c) ** 2
        return ev, eh + 0.5 * p.alpha / p.beta * x[..., 5] ** 2

    def rates(self, tau, x, contact: bool) -> np.ndarray:
        """(feed_v, damper_v, feed_h, damper_h, friction) at τ."""
        p = self.p
        c, cd = self.cart(tau)
        q, qd = x[:, 0] + c, x[:, 1] + cd
        r, rd = x[:, 2] - c, x[:, 3] - cd
        n = c + 2.0 * p.zeta_v * cd
        fr = p.alpha * p.kappa * n * np.abs(x[:, 3] - x[:, 5]) if contact else 0.0 * n
        return np.array(
            [
                cd * (q + 2.0 * p.zeta_v * qd),
                2.0 * p.zeta_v * qd**2,
                -cd * (r + self.ch * rd),
                self.ch * rd**2,
                fr,
            ]
        )

    def xi_acc(self, tau: float, x: np.ndarray) -> float:
        c, cd = self.cart(tau)
        return -c - 2.0 * self.p.zeta_v * (x[1] + cd) - x[0]


def balance(tr, p: ModelParams, m: int, zeta_h: float | None = None) -> dict:
    """The terms of cycle m from trajectory tr (dense) and their two residuals."""
    k = Terms(p, zeta_h)
    T = 2.0 * math.pi / p.varpi
    a, b = m * T, (m + 1) * T
    contact = False
    for ev in tr.events:
        if ev.tau >= a:
            break
        contact = {"impact": True, "separation": False}.get(ev.kind, contact)
    evs = [ev for ev in tr.events if a <= ev.tau < b]
    cuts = [a] + [ev.tau for ev in evs] + [b]
    integ = np.zeros(5)
    loss, prev = 0.0, a
    for i, (t0, t1) in enumerate(pairwise(cuts)):
        n = max(1, math.ceil((t1 - t0) / PIECE))
        edges = np.linspace(t0, t1, n + 1)
        for u0, u1 in pairwise(edges):
            if u1 <= u0:
                continue
            tau = 0.5 * (u0 + u1) + 0.5 * (u1 - u0) * NODES
            integ += 0.5 * (u1 - u0) * k.rates(tau, tr.sample(tau), contact) @ LEG
        if i < len(evs):
            ev = evs[i]
            if ev.kind in ("impact", "impulsive") and ev.tau > prev:
                eps = 1e-7 * (ev.tau - prev)
                x = tr.sample(np.array([ev.tau - eps]))[0]
                v = x[1] + k.xi_acc(ev.tau - eps, x) * eps  # left limit of ξ'
                keep = p.restitution**2 if ev.kind == "impulsive" else 0.0
                loss += 0.5 * v * v * (1.0 - keep)
            contact = {"impact": True, "separation": False}.get(ev.kind, contact)
            prev = ev.tau
    ev0, eh0 = k.stored(a, tr.section[m])
    ev1, eh1 = k.stored(b, tr.section[m + 1])
    fv, dv, fh, dh, df = integ
    return {
        "vertical": (fv - (ev1 - ev0)) - (dv + loss),
        "tangential": (fh - (eh1 - eh0)) - (dh + df),
        "scale_v": abs(fv) + abs(ev1 - ev0) + dv + loss,
        "scale_h": abs(fh) + abs(eh1 - eh0) + dh + df,
        "loss": loss,
        "friction": df,
        "damper": dv + dh,
    }


def _ids(p: ModelParams) -> str:
    return f"w{p.varpi}-zv{p.zeta_v}-zh{p.zeta_h}-e{p.restitution}"


@pytest.mark.parametrize("p", DESIGNS, ids=_ids)
def test_exact_trajectory_balances_its_energy(p):
    """Every cycle of the exact solver's dense output: both residuals within 1e-12 of
    the gross terms (measured ≤ 3e-14), with every dissipation channel active where the
    design has it."""
    tr = simulate(p, CYCLES, dense=True)
    assert tr.success, tr.message
    for m in range(CYCLES):
        r = balance(tr, p, m)
        assert abs(r["vertical"]) <= 1e-12 * r["scale_v"], (m, r)
        assert abs(r["tangential"]) <= 1e-12 * r["scale_h"], (m, r)
        assert r["friction"] > 0.0 and (r["damper"] > 0.0 or p.zeta_v == p.zeta_h == 0.0)
        assert r["loss"] > 0.0 or m == 0 or p.restitution == 0.0


@pytest.mark.parametrize("p", DESIGNS[::2], ids=_ids)
def test_reference_trajectory_balances_its_energy(p):
    """The same identity on the reference's dense output (DOP853, rtol 1e-12; measured
    ≤ 5e-12): a check of the reference's own transcription of the damped equations."""
    tr = reference.simulate(p, CYCLES, rtol=1e-12, atol=1e-13, dense=True)
    assert tr.success, tr.message
    for m in range(CYCLES):
        r = balance(tr, p, m)
        assert abs(r["vertical"]) <= 1e-10 * r["scale_v"], (m, r)
        assert abs(r["tangential"]) <= 1e-10 * r["scale_h"], (m, r)


def test_balance_detects_a_wrong_damper():
    """The check can fail: the same trajectory with ζ_h taken 10 % off in the bookkeeping
    leaves a residual far beyond the tolerance."""
    p = DESIGNS[0]
    tr = simulate(p, 2, dense=True)
    r = balance(tr, p, 1, zeta_h=1.1 * p.zeta_h)
    assert abs(r["tangential"]) > 1e-4 * r["scale_h"]
