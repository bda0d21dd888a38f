"""The damped closed forms (flows.forced, flows.decaying_basis) against high precision.

Sources of truth, both written here without the solver's formulas:

- the general solution of y'' + 2g y' + w0² y = f in 50-digit arithmetic: the free part
  from the characteristic roots r = −g ± √(g² − w0²) (complex square root, a repeated
  root at g = w0 exactly), fitted to the initial state; the forced part from the 2×2
  linear system of the sinusoidal ansatz solved by ``mp.lu_solve``. At 50 digits the
  near-critical cancellation (r1 − r2 ≈ 1e-4 at ζ = 1 ± 1e-9) costs 5 of them.
- ``mpmath.odefun`` (Taylor-series ODE integration at 30 digits) on a few cases, which
  shares nothing but the equation.

The closed forms must hold to a few units of round-off of the size of the terms they
sum: underdamped, critically damped, overdamped, ζ = 1 ± 1e-9 and ± 1e-6, both sides of
decaying_basis's Taylor branch (|(w0² − g²)h²| = 0.01), short and long steps.
"""

from __future__ import annotations

import math

import mpmath as mp
import pytest

from betvdesign.dynamics.flows import decaying_basis, forced, oscillator
from betvdesign.dynamics.schedule import short_flight


@pytest.fixture(autouse=True)
def _fifty_digits():
    """Every test here at 50 digits (other modules set the global mp.mp.dps)."""
    with mp.workdps(50):
        yield


RATIOS = [0.01, 0.3, 0.9, 1 - 1e-6, 1 - 1e-9, 1.0, 1 + 1e-9, 1 + 1e-6, 1.1, 3.0, 30.0]
W0 = [0.3, 1.0, 3.3]
H = [1e-6, 0.01, 0.5, 3.0, 20.0]


def _roots(w0, g):
    d = mp.sqrt(mp.mpc(g * g - w0 * w0))
    return -g + d, -g - d


def free_mp(w0: float, g: float, u0, u1, h):
    """(y, y') at h of y'' + 2g y' + w0² y = 0 from (u0, u1), by its characteristic roots."""
    w0, g, h, u0, u1 = (mp.mpf(x) for x in (w0, g, h, u0, u1))
    r1, r2 = _roots(w0, g)
    if r1 == r2:  # critically damped: (C1 + C2 h) e^(rh)
        r = r1.real
        c2 = u1 - r * u0
        ex = mp.exp(r * h)
        return (u0 + c2 * h) * ex, (c2 + r * (u0 + c2 * h)) * ex
    c1 = (u1 - r2 * u0) / (r1 - r2)
    c2 = (r1 * u0 - u1) / (r1 - r2)
    e1, e2 = mp.exp(r1 * h), mp.exp(r2 * h)
    return (c1 * e1 + c2 * e2).real, (c1 * r1 * e1 + c2 * r2 * e2).real


def forced_mp(w0, g, wf, F, G, y0, v0, sp0, cp0, h):
    """(y, y') at h of y'' + 2g y' + w0² y = F sin φ + G cos φ, sin φ = sp0 cos ϖh +
    cp0 sin ϖh, cos φ = cp0 cos ϖh − sp0 sin ϖh (the floats given, exactly)."""
    w0, g, wf, F, G, sp0, cp0, h = (mp.mpf(x) for x in (w0, g, wf, F, G, sp0, cp0, h))
    P, Q = F * sp0 + G * cp0, F * cp0 - G * sp0  # f = P cos ϖh + Q sin ϖh
    # y_p = A cos ϖh + B sin ϖh: (w0² − ϖ²) A + 2gϖ B = P, (w0² − ϖ²) B − 2gϖ A = Q
    M = mp.matrix([[w0 * w0 - wf * wf, 2 * g * wf], [-2 * g * wf, w0 * w0 - wf * wf]])
    A, B = mp.lu_solve(M, mp.matrix([P, Q]))
    yh, vh = free_mp(w0, g, mp.mpf(y0) - A, mp.mpf(v0) - wf * B, h)
    c, s = mp.cos(wf * h), mp.sin(wf * h)
    return A * c + B * s + yh, wf * (B * c - A * s) + vh, abs(A) + abs(B)


@pytest.mark.parametrize("w0", W0)
@pytest.mark.parametrize("ratio", RATIOS, ids=lambda r: f"g/w0={r!r}")
def test_decaying_basis(w0, ratio):
    """(e^(−gh) cos w_d h, e^(−gh) sin(w_d h)/w_d): the free motions from (1, −g) and
    (0, 1), to 1e-14 of the size of the exponentials they combine, for every h."""
    g = w0 * ratio
    for h in H:
        ec, es = decaying_basis(w0, g, h)
        ec_mp, _ = free_mp(w0, g, 1, -g, h)
        es_mp, _ = free_mp(w0, g, 0, 1, h)
        r1, r2 = _roots(mp.mpf(w0), mp.mpf(g))
        big = max(abs(mp.exp(r1 * h)), abs(mp.exp(r2 * h)))
        assert abs(ec - ec_mp) <= 1e-14 * max(abs(ec_mp), big) + 1e-300, (h, ec, ec_mp)
        assert abs(es - es_mp) <= 1e-14 * max(abs(es_mp), h * big) + 1e-300, (h, es, es_mp)


@pytest.mark.parametrize("side", [0.0099, 0.0101, -0.0099, -0.0101])
def test_decaying_basis_across_its_taylor_branch(side):
    """Both sides of |x| = 0.01, x = (w0² − g²)h², where decaying_basis switches from
    its Taylor series to cos/sin (x > 0) or the exponentials (x < 0)."""
    w0 = 1.3
    for g in (0.2, 0.9, 1.25, 1.35, 2.0, 5.0):
        if (w0 * w0 - g * g) * side <= 0:
            continue
        h = math.sqrt(side / (w0 * w0 - g * g))
        ec, es = decaying_basis(w0, g, h)
        ec_mp, _ = free_mp(w0, g, 1, -g, h)
        es_mp, _ = free_mp(w0, g, 0, 1, h)
        assert abs(ec - ec_mp) <= 2e-16 * 4 and abs(es - es_mp) <= 4 * 2e-16 * h


CASES = [
    # (w0, g, ϖ, F, G): under-, critically, over- and near-critically damped, near and
    # far from resonance, the tangential (α = 0.1, ζ_h = 0.3) and stick-like rates
    (1.0, 0.05, 0.9, -1.0, -0.09),
    (1.0, 0.3, 1.7, -1.04, -0.6),
    (1.0, 1.0, 0.8, -1.0, -1.6),
    (1.0, 1 - 1e-9, 0.8, -1.0, -1.6),
    (1.0, 1 + 1e-9, 0.8, -1.0, -1.6),
    (1.0, 1 + 1e-6, 1.2, 0.7, 0.3),
    (1.0, 4.0, 0.6, -1.0, -4.8),
    (3.1623, 0.949, 1.3, 9.6, 2.4),
    (1.2, 1.2, 1.2, 0.5, -0.2),
    (2.0, 0.02, 2.0, 1.0, 0.0),
    (0.7, 0.0, 1.1, 1.0, 0.4),
]


@pytest.mark.parametrize("case", CASES, ids=[f"w0={c[0]}-g={c[1]!r}" for c in CASES])
def test_forced_matches_the_general_solution(case):
    """(y, y') of flows.forced over steps from 1e-6 to 20, from a state and forcing
    phase given as floats: within 1e-13 of the sizes summed (initial state, forced
    amplitude, result)."""
    w0, g, wf, F, G = case
    for h in H:
        for y0, v0, phi in ((0.3, -0.7, 0.4), (0.0, 0.0, math.pi), (-1.2, 2.5, 2.9)):
            sp0, cp0 = math.sin(phi), math.cos(phi)
            y, v = forced(w0, g, wf, F, G, y0, v0, sp0, cp0, h)
            ym, vm, amp = forced_mp(w0, g, wf, F, G, y0, v0, sp0, cp0, h)
            scale = abs(y0) + abs(v0) / w0 + amp + abs(ym)
            assert abs(y - ym) <= 1e-13 * scale, (h, y, float(ym))
            assert abs(v - vm) <= 1e-13 * w0 * (scale + abs(vm) / w0), (h, v, float(vm))


@pytest.mark.slow
@pytest.mark.parametrize("case", [CASES[0], CASES[2], CASES[6]], ids=["under", "critical", "over"])
def test_forced_matches_mpmath_odefun(case):
    """A second truth sharing only the equation: mpmath's Taylor ODE integrator."""
    w0, g, wf, F, G = case
    y0, v0, phi0, h = 0.25, -0.4, 1.1, 2.5
    sp0, cp0 = math.sin(phi0), math.cos(phi0)
    y, v = forced(w0, g, wf, F, G, y0, v0, sp0, cp0, h)
    with mp.workdps(30):
        a, b, c, f_, gg = (mp.mpf(x) for x in (w0, g, wf, F, G))
        s0, c0 = mp.mpf(sp0), mp.mpf(cp0)

        def rhs(t, u):
            sn = s0 * mp.cos(c * t) + c0 * mp.sin(c * t)
            cs = c0 * mp.cos(c * t) - s0 * mp.sin(c * t)
            return [u[1], f_ * sn + gg * cs - 2 * b * u[1] - a * a * u[0]]

        sol = mp.odefun(rhs, 0, [mp.mpf(y0), mp.mpf(v0)])
        ym, vm = sol(mp.mpf(h))
    assert abs(y - ym) <= 1e-14 and abs(v - vm) <= 1e-14


def test_forced_over_a_tiny_flight_is_accurate_to_its_absolute_round_off():
    """flows.forced sums a steady part and a free part of size ≈ 1, so over a tiny
    rebound flight (ξ = 0, ξ' = v) its ξ is right to ~1e-16 absolute, not relative to
    v·h: why the solver takes such flights from schedule.short_flight (below)."""
    zv, wf = 0.05, 0.9
    A = math.hypot(1.0, 2 * zv * wf)
    phi = 1.3
    for v in (1e-3, 1e-6, 5e-9):
        h = v / (A * math.sin(phi))
        y, _ = forced(1.0, zv, wf, -A, 0.0, 0.0, v, math.sin(phi), math.cos(phi), h)
        ym, _, _ = forced_mp(1.0, zv, wf, -A, 0.0, 0.0, v, math.sin(phi), math.cos(phi), h)
        assert abs(y - ym) <= 1e-15, (v, y, float(ym))


@pytest.mark.parametrize("zv", [0.0, 0.05, 0.7, 1.0, 2.5])
@pytest.mark.parametrize("wf", [0.5, 1.01, 1.9])
def test_short_flight_keeps_its_own_scale(zv, wf):
    """A rebound flight of a chattering sequence as the solver takes it
    (schedule.short_flight: certified Taylor series): its flight time and landing
    velocity are the 50-digit closed form's (root of ξ(h)/h by mpmath) to 1e-13
    relative, down to v = 1e-12 (the closed form in floats loses 1e-16/v² there)."""
    A = math.hypot(1.0, 2 * zv * wf)
    for phi in (0.05, 1.3, 2.9):
        sp, cp = math.sin(phi), math.cos(phi)
        for v in (1e-2, 1e-5, 1e-8, 1e-12):
            h, vl = short_flight(wf, zv, A, v, sp, cp)
            if 2.0 * v / (A * sp) > 0.1:  # beyond the series' reach (left to the search)
                continue
            assert h > 0.0, (phi, v)

            def gap(t, v=v, sp=sp, cp=cp):
                return forced_mp(1.0, zv, wf, -A, 0.0, 0.0, v, sp, cp, t)[0] / t

            with mp.workdps(50):
                hm = mp.findroot(gap, (mp.mpf(h) * 0.99, mp.mpf(h) * 1.01), solver="anderson")
                vm = forced_mp(1.0, zv, wf, -A, 0.0, 0.0, v, sp, cp, hm)[1]
            assert abs(h - hm) <= 1e-13 * hm, (phi, v, h, float(hm))
            assert abs(vl - vm) <= 1e-13 * abs(vm), (phi, v, vl, float(vm))


def test_short_flight_refuses_long_flights():
    """A flight beyond the series' certified reach is left to the gap search (−1)."""
    A = 1.0
    assert short_flight(1.0, 0.0, A, 0.5, 0.1, math.sqrt(0.99))[0] == -1.0
    assert short_flight(1.0, 0.0, A, 1e-3, -0.1, math.sqrt(0.99))[0] == -1.0


def test_undamped_oscillator_over_a_tiny_flight_keeps_its_own_scale():
    """The same flight without damping through flows.oscillator (the undamped path of
    vertical_flight), a divided-difference form that keeps the flight's own scale."""
    wf, phi = 0.9, 1.3
    for v in (1e-3, 1e-6, 5e-9):
        h = v / math.sin(phi)
        y, _, _, _ = oscillator(1.0, wf, -1.0, 0.0, v, math.sin(phi), math.cos(phi), h)
        ym, _, _ = forced_mp(1.0, 0.0, wf, -1.0, 0.0, 0.0, v, math.sin(phi), math.cos(phi), h)
        assert abs(y - ym) <= 1e-8 * v * h, (v, y, float(ym))
