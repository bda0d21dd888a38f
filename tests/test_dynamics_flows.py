"""Closed-form phase flows (source: the phase ODEs of docs/MODEL.md, checked by their
residual with finite differences, by scipy solve_ivp as a second method, and by the
textbook secular solutions at exact resonance)."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from betvdesign.dynamics.flows import (
    FREE,
    REVERSE,
    SLIP,
    STICK,
    flow,
    oscillator,
    phase_table,
    sinc,
)
from betvdesign.model.params import ModelParams


def _ode_residual(w0, wf, F, y0, v0, phi0, h, d=1e-4):
    sp0, cp0 = math.sin(phi0), math.cos(phi0)
    ym = oscillator(w0, wf, F, y0, v0, sp0, cp0, h - d)[0]
    y = oscillator(w0, wf, F, y0, v0, sp0, cp0, h)[0]
    yp = oscillator(w0, wf, F, y0, v0, sp0, cp0, h + d)[0]
    ydd = (yp - 2 * y + ym) / (d * d)
    return ydd + w0 * w0 * y - F * math.sin(phi0 + wf * h)


@pytest.mark.parametrize("w0,wf", [(1.0, 0.7), (1.0, 1.0), (3.16, 0.9), (0.9, 0.9 + 1e-9)])
def test_oscillator_satisfies_its_ode(w0, wf):
    """y'' + w0² y = F sin(φ0 + ϖh), including exact and near resonance."""
    for h in (0.3, 1.7, 5.0):
        assert abs(_ode_residual(w0, wf, 2.5, 0.3, -0.4, 0.8, h)) < 2e-5


@pytest.mark.parametrize("w0,wf", [(1.0, 0.6), (2.0, 1.3), (1.1, 1.1), (1.0, 1.0 - 1e-7)])
def test_oscillator_matches_solve_ivp(w0, wf):
    """Second method: DOP853 at rtol 1e-12."""
    F, y0, v0, phi0, H = -1.3, 0.2, 0.5, 0.4, 9.0
    sol = solve_ivp(
        lambda t, y: [y[1], F * math.sin(phi0 + wf * t) - w0 * w0 * y[0]],
        (0, H),
        [y0, v0],
        method="DOP853",
        rtol=1e-12,
        atol=1e-13,
    )
    y, yd, sp, cp = oscillator(w0, wf, F, y0, v0, math.sin(phi0), math.cos(phi0), H)
    assert y == pytest.approx(sol.y[0, -1], abs=1e-10)
    assert yd == pytest.approx(sol.y[1, -1], abs=1e-10)
    assert sp == pytest.approx(math.sin(phi0 + wf * H), abs=1e-14)
    assert cp == pytest.approx(math.cos(phi0 + wf * H), abs=1e-14)


def test_vertical_resonance_is_the_secular_solution():
    """ϖ = 1, from rest at phase 0: ξ = (τ cos τ − sin τ)/2 (MODEL.md hint: τ·cos τ/2 term)."""
    for t in (0.5, 3.0, 20.0):
        xi, xid, _, _ = oscillator(1.0, 1.0, -1.0, 0.0, 0.0, 0.0, 1.0, t)
        assert xi == pytest.approx((t * math.cos(t) - math.sin(t)) / 2, abs=1e-14)
        assert xid == pytest.approx(-t * math.sin(t) / 2, abs=1e-14)


def test_near_resonance_is_continuous():
    """No cancellation: δ = 1e-12 off resonance agrees with the exact secular case."""
    a = oscillator(1.0, 1.0, 1.0, 0.1, 0.2, 0.3, math.sqrt(1 - 0.09), 7.0)
    b = oscillator(1.0 + 1e-12, 1.0, 1.0, 0.1, 0.2, 0.3, math.sqrt(1 - 0.09), 7.0)
    assert np.allclose(a, b, atol=1e-10, rtol=0)


def test_sinc_small_and_large():
    assert sinc(0.0) == 1.0
    assert sinc(1e-4) == pytest.approx(math.sin(1e-4) / 1e-4, rel=1e-16)
    assert sinc(2.0) == pytest.approx(math.sin(2.0) / 2.0, rel=1e-16)


@pytest.mark.parametrize("phase", [FREE, SLIP, REVERSE, STICK])
def test_phase_flow_matches_model_equations(phase):
    """Each phase of the MODEL.md table integrated by DOP853 agrees with flow()."""
    p = ModelParams(0.9, 0.3, 0.8, 0.4)
    k = phase_table(p)[0]
    al, be, ka, w = p.alpha, p.beta, p.kappa, p.varpi
    phi0 = 0.3
    z0, zd0, s0, sd0 = 0.1, 0.2, -0.3, 0.2 if phase == STICK else -0.1
    coef = {
        FREE: (al, 1.0, 0.0),
        SLIP: (al, 1 - al * ka, be * ka),
        REVERSE: (al, 1 + al * ka, -be * ka),
        STICK: (al * (1 + 1 / be), 1.0, None),
    }[phase]
    a, c, ds = coef

    def rhs(t, y):
        sn = math.sin(phi0 + w * t)
        zdd = (c * sn - y[0]) / a
        sdd = zdd if ds is None else ds * sn
        return [y[1], zdd, y[3], sdd]

    sol = solve_ivp(rhs, (0, 2.5), [z0, zd0, s0, sd0], method="DOP853", rtol=1e-12, atol=1e-13)
    out = flow(k, phase, z0, zd0, s0, sd0, math.sin(phi0), math.cos(phi0), 2.5)
    assert np.allclose(out[:4], sol.y[:, -1], atol=1e-9, rtol=0)
