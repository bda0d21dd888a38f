"""The coupled head's reference solver (betvdesign.dynamics.coupled_reference).

Independent truths:
- at ρ = 0 the coupled model is the paper's (docs/MODEL.md "Coupled head", reduction):
  the exact closed-form solver's sections, increments and periodic Δs, on 32 designs;
- for ρ from −0.999 to 0.9 (32 designs): a second implementation of the coupled hybrid
  automaton written here from MODEL.md, whose phases are advanced *exactly* by the
  matrix exponential of the phase's linear system augmented with the forcing
  (p, q) = (sin ϖτ, cos ϖτ) (free flight: the two-mode closed form, as its modal
  decomposition), events bracketed on a grid finer than the stiff mode and refined by
  brentq. No solve_ivp, no code of the module under test.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.linalg import expm
from scipy.optimize import brentq

from betvdesign.dynamics import periodic_orbit, simulate
from betvdesign.dynamics.coupled_reference import (
    coupled_periodic_orbit,
    simulate_coupled,
)
from betvdesign.errors import ParameterError
from betvdesign.model.params import HeadCoupling, ModelParams

RTOL = 1e-8


def _designs(n: int, seed: int) -> list[ModelParams]:
    rng = np.random.default_rng(seed)
    return [
        ModelParams(
            float(rng.uniform(0.5, 1.9)),
            float(rng.uniform(0.08, 2.5)),
            float(rng.uniform(0.2, 6.0)),
            float(rng.uniform(0.08, 0.6)),
        )
        for _ in range(n)
    ]


def _close(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.abs(a - b) / np.maximum(1.0, np.abs(b))))


# -- ρ = 0: the paper's model, against the exact solver ------------------------------------


@pytest.mark.parametrize("p", _designs(32, 3))
def test_decoupled_transient_matches_exact_solver(p):
    """ρ = 0 (any χ): 12 cycles from rest, sections and Δs to 1e-8 of the exact solver."""
    ex = simulate(p, 12)
    ref = simulate_coupled(p, HeadCoupling(0.0, 0.7), 12)
    assert ref.status == "success", ref.message
    assert _close(ref.section, ex.section) < RTOL
    assert np.max(np.abs(ref.delta_s - ex.delta_s)) < RTOL


@pytest.mark.parametrize("p", _designs(6, 11))
def test_decoupled_orbit_matches_exact_orbit(p):
    """ρ = 0: Newton from a start 1e-3 off converges to the exact periodic orbit."""
    ex = periodic_orbit(p)
    assert ex.status == "success"
    g = ex.state.copy()
    g[2:4] += (1e-3, -5e-4)
    g[5] += 5e-4
    o = coupled_periodic_orbit(p, HeadCoupling(0.0, 1.3), guess=g, period=ex.period_cycles)
    assert o.status == "success", o.message
    assert abs(o.delta_s - ex.delta_s) < RTOL * max(1.0, abs(ex.delta_s))
    assert _close(o.state, ex.state) < RTOL


# -- ρ ≠ 0: against an exact-flow second implementation ------------------------------------


class _Exact:
    """The coupled automaton with exact (matrix-exponential) phase flows.

    Augmented state z = (ξ, ξ', ζ, ζ', s, s', p, q), p = sin ϖτ, q = cos ϖτ.
    """

    def __init__(self, p: ModelParams, c: HeadCoupling) -> None:
        w, al, be, ka = p.varpi, p.alpha, p.beta, p.kappa
        a, cn, ct = 1.0 / (1.0 - c.rho**2), c.rho / c.chi, c.rho * c.chi
        self.w, self.T = w, 2.0 * math.pi / w
        self.b = al * ka * (1.0 + be)
        As = al * (1.0 + 1.0 / be)
        rot = np.zeros((8, 8))
        rot[6, 7], rot[7, 6] = w, -w
        n_row = np.array([0, 0, a * cn, 0, 0, 0, a * (1 - cn), 0])
        r_row = np.array([0, 0, a, 0, 0, 0, a * (ct - 1), 0])
        free = rot.copy()
        free[0, 1] = free[2, 3] = free[4, 5] = 1.0
        free[1] = [-a, 0, -a * cn, 0, 0, 0, -a * (1 - cn), 0]
        free[3] = [-a * ct / al, 0, -a / al, 0, 0, 0, -a * (ct - 1) / al, 0]
        self.A = {"free": free}
        for sig, name in ((1.0, "slip"), (-1.0, "reverse")):
            m = rot.copy()
            m[2, 3] = m[4, 5] = 1.0
            m[3] = (-r_row - sig * al * ka * n_row) / al
            m[5] = sig * be * ka * n_row
            self.A[name] = m
        st = rot.copy()
        st[2, 3] = st[4, 5] = 1.0
        st[3] = st[5] = -r_row / As
        self.A["stick"] = st
        self.n_row, self.r_row = n_row, r_row
        lam = np.linalg.eigvals(free[:6, :6])
        wmax = max(float(np.max(np.abs(lam.imag))), float(np.max(np.abs(lam.real))), w)
        self.dh = min(self.T / 2000.0, 2.0 * math.pi / wmax / 40.0)
        self.E = {k: expm(v * self.dh) for k, v in self.A.items()}
        self.beta = be

    def events(self, mode: str) -> list[tuple[np.ndarray, str]]:
        """(linear functional g with g·z, kind); every event is g falling through 0."""
        if mode == "free":
            return [(np.eye(8)[0], "impact")]
        evs = [(self.n_row, "separation")]
        if mode == "stick":
            evs += [
                (self.r_row + self.b * self.n_row, "band"),
                (self.b * self.n_row - self.r_row, "band"),
            ]
        else:
            sig = 1.0 if mode == "slip" else -1.0
            evs.append((sig * (np.eye(8)[3] - np.eye(8)[5]), "match"))
        return evs

    def decide(self, z: np.ndarray, matched: bool) -> str:
        v = z[3] - z[5]
        if not matched and abs(v) > 1e-9 * (1 + abs(z[3]) + abs(z[5])):
            return "slip" if v > 0 else "reverse"
        vs = (z[3] + z[5] / self.beta) / (1 + 1 / self.beta)
        zz = z.copy()
        zz[3] = zz[5] = vs
        ahead = expm(self.A["stick"] * 1e-7 * self.T) @ zz
        if (self.r_row + self.b * self.n_row) @ ahead < 0:
            return "slip"
        if (self.b * self.n_row - self.r_row) @ ahead < 0:
            return "reverse"
        z[3] = z[5] = vs
        return "stick"

    def hit(self, z: np.ndarray) -> str:
        z[0] = z[1] = 0.0
        n = self.n_row @ z
        ndot = self.n_row @ (self.A["stick"] @ z)  # n depends on ζ, p only: any contact flow
        if n > 1e-13 * (1 + abs(z[2])) or (abs(n) <= 1e-13 * (1 + abs(z[2])) and ndot > 0):
            return self.decide(z, matched=False)
        return "free"

    def run(self, cycles: int) -> np.ndarray:
        z = np.zeros(8)
        z[7] = 1.0
        mode = self.hit(z)
        out = [z[:6].copy()]
        for m in range(cycles):
            t, t1 = m * self.T, (m + 1) * self.T
            while True:
                z[6], z[7] = math.sin(self.w * t), math.cos(self.w * t)
                A, E = self.A[mode], self.E[mode]
                evs = self.events(mode)
                g_prev = [g @ z for g, _ in evs]
                found = None
                h = 0.0
                while h < t1 - t and found is None:
                    step = min(self.dh, t1 - t - h)
                    zn = E @ z if step == self.dh else expm(A * step) @ z
                    for i, (g, kind) in enumerate(evs):
                        gn = g @ zn
                        if g_prev[i] > 0.0 >= gn:
                            z0 = z.copy()
                            r = brentq(
                                lambda x, g=g, z0=z0, A=A: g @ (expm(A * x) @ z0),
                                0.0,
                                step,
                                xtol=1e-16,
                                rtol=8.9e-16,
                            )
                            if found is None or r < found[0]:
                                found = (r, i, kind, h)
                        g_prev[i] = gn
                    if found is None:
                        z, h = zn, h + step
                if found is None:
                    t = t1
                    break
                r, _, kind, h0 = found
                z = expm(A * r) @ z
                t = t + h0 + r
                if kind == "impact":
                    mode = self.hit(z)
                elif kind == "separation":
                    z[0] = z[1] = 0.0
                    mode = "free"
                else:
                    mode = self.decide(z, matched=True)
                if mode != "free":
                    z[0] = z[1] = 0.0
            out.append(z[:6].copy())
        return np.array(out)


def _coupled_designs() -> list[tuple[ModelParams, HeadCoupling]]:
    rhos = np.linspace(-0.999, 0.9, 32)
    rng = np.random.default_rng(30)
    out = []
    for p, rho in zip(_designs(32, 7), rhos, strict=True):
        theta = float(rng.uniform(math.radians(30), math.radians(60)))
        out.append((p, HeadCoupling.from_angle(float(rho), p.alpha, theta)))
    return out


@pytest.mark.parametrize(("p", "c"), _coupled_designs())
def test_coupled_matches_exact_flow_automaton(p, c):
    """ρ ∈ [−0.999, 0.9]: 4 cycles from rest, sections and Δs within 1e-8 of _Exact."""
    n = 4
    truth = _Exact(p, c).run(n)
    ref = simulate_coupled(p, c, n)
    assert ref.status == "success", ref.message
    assert _close(ref.section, truth) < RTOL
    assert np.max(np.abs(ref.delta_s - np.diff(truth[:, 4]))) < RTOL * max(
        1.0, float(np.max(np.abs(truth[:, 4])))
    )


def test_coupling_moves_the_answer():
    """The coupling is not inert: ρ = 0.5 moves Δs of a design by more than 1 %."""
    p = ModelParams(1.2, 2.04, 0.5, 0.15)
    d0 = simulate_coupled(p, HeadCoupling(0.0, 1.0), 6).delta_s
    d1 = simulate_coupled(p, HeadCoupling.from_angle(0.5, p.alpha, math.pi / 4), 6).delta_s
    assert np.max(np.abs(d1 - d0)) > 0.01 * np.max(np.abs(d0))


@pytest.mark.parametrize(
    ("args", "match"),
    [
        ((1.0, 1.0), "rho"),
        ((-1.2, 1.0), "rho"),
        ((0.3, 0.0), "chi"),
        ((math.nan, 1.0), "rho"),
        (("x", 1.0), "rho"),
    ],
)
def test_bad_coupling(args, match):
    with pytest.raises(ParameterError, match=match):
        HeadCoupling(*args)


def test_bad_inputs():
    c = HeadCoupling(0.2, 1.0)
    with pytest.raises(ParameterError, match="ideal"):
        simulate_coupled(ModelParams(1.0, 1.0, 1.0, 0.3, zeta_v=0.01), c, 2)
    with pytest.raises(ParameterError, match="cycles"):
        simulate_coupled(ModelParams(1.0, 1.0, 1.0, 0.3), c, -1)
    with pytest.raises(ParameterError, match="state0"):
        simulate_coupled(ModelParams(1.0, 1.0, 1.0, 0.3), c, 2, state0=[-1, 0, 0, 0, 0, 0])
    with pytest.raises(ParameterError, match="angle"):
        HeadCoupling.from_angle(0.2, 1.0, 2.0)


# -- the dimensionless equations against the dimensional ones -------------------------------


def _dimensional(rho: float, alpha: float, theta: float):
    """A head in SI-like units (frame.py's convention: n toward the slider, t along it in the
    impact direction, stroke u·sin ωt·(sinθ, cosθ)); compliance C from ρ, C_nn, C_tt."""
    m, c_nn = 2.0e-12, 1.0 / 30.0  # kg, m/N
    c_tt = alpha * c_nn  # α = k_v/k_h = C_tt/C_nn
    c_nt = rho * math.sqrt(c_nn * c_tt)
    K = np.linalg.inv(np.array([[c_nn, c_nt], [c_nt, c_tt]]))
    return m, K, 1.0 / c_nn


@pytest.mark.parametrize(
    ("rho", "alpha", "deg"), [(0.95, 1.3, 45.0), (-0.7, 0.4, 30.0), (0.3, 2.2, 60.0)]
)
def test_contact_force_and_spring_forces_match_the_dimensional_head(rho, alpha, deg):
    """n and R of MODEL.md are the dimensional K·(c − x) scaled by k_v u sinθ and k_h u cosθ."""
    th = math.radians(deg)
    _, K, kv = _dimensional(rho, alpha, th)
    kh = kv / alpha
    c = HeadCoupling.from_angle(rho, alpha, th)
    a, cn, ct = c.a, c.rho / c.chi, c.rho * c.chi
    u = 1.7e-7
    rng = np.random.default_rng(1)
    for _ in range(20):
        p, xi, z = rng.uniform(-1, 1, 3)
        x = np.array([-xi * u * math.sin(th), z * u * math.cos(th)])  # (x_n, x_t)
        cart = u * p * np.array([math.sin(th), math.cos(th)])
        f = K @ (cart - x)  # spring force on the head, (n, t)
        # along the gap (−n) the force is −f_n = −F_n·k_v u sinθ (MODEL.md: ξ'' = −F_n);
        # along t it is f_t = −R·k_h u cosθ (α ζ'' = −R)
        fn = f[0] / (kv * u * math.sin(th))
        r = -f[1] / (kh * u * math.cos(th))
        assert fn == pytest.approx(a * ((xi + p) + cn * (z - p)), rel=1e-10, abs=1e-12)
        assert r == pytest.approx(a * (ct * (xi + p) + (z - p)), rel=1e-10, abs=1e-12)


@pytest.mark.parametrize(
    ("rho", "alpha", "deg"), [(0.95, 1.3, 45.0), (-0.999, 0.4, 30.0), (0.6, 2.2, 60.0)]
)
def test_free_flight_matches_the_dimensional_head(rho, alpha, deg):
    """Free flight (no hit): the reference's state after a cycle is the dimensional
    m x'' = K(c(t) − x) advanced exactly (matrix exponential), scaled back."""
    th = math.radians(deg)
    m, K, kv = _dimensional(rho, alpha, th)
    u, tscale = 1.0e-7, math.sqrt(m / kv)
    p = ModelParams(5.0, alpha, 1.0, 0.3)  # a cycle shorter than half the soft mode
    w = p.varpi / tscale  # rad/s
    c = HeadCoupling.from_angle(rho, alpha, th)
    # start far out along the soft mode (its eigenvector), at rest: ξ stays > 0 for a cycle
    stiff = c.a * np.array([[1.0, c.rho / c.chi], [c.rho * c.chi / alpha, 1.0 / alpha]])
    lam, vec = np.linalg.eig(stiff)
    soft = vec[:, int(np.argmin(lam.real))].real
    soft = 1e3 * soft / soft[0]
    y0 = np.array([soft[0], 0.0, soft[1], 0.0, 0.0, 0.05])
    ref = simulate_coupled(p, c, 1, state0=y0)
    assert ref.status == "success"
    assert not ref.events  # free flight throughout
    # dimensional augmented state (x_n, x_t, v_n, v_t, sin ωt, cos ωt)
    S = np.array([u * math.sin(th), u * math.cos(th)])
    A = np.zeros((6, 6))
    A[0:2, 2:4] = np.eye(2)
    A[2:4, 0:2] = -K / m
    A[2:4, 4] = K @ S / m
    A[4, 5], A[5, 4] = w, -w
    sc = np.array([-u * math.sin(th), u * math.cos(th)])  # x = sc·(ξ, ζ)
    z0 = np.concatenate([sc * y0[[0, 2]], sc * y0[[1, 3]] / tscale, [0.0, 1.0]])
    z1 = expm(A * 2 * math.pi / w) @ z0
    got = np.array([z1[0] / sc[0], z1[2] * tscale / sc[0], z1[1] / sc[1], z1[3] * tscale / sc[1]])
    want = ref.section[1][[0, 1, 2, 3]]
    assert np.allclose(got, want, rtol=1e-8, atol=1e-8 * max(1.0, np.max(np.abs(want))))
