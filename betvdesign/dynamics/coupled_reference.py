"""Coupled head, independent reference: scipy ``solve_ivp`` of docs/MODEL.md "Coupled head".

The head with a symmetric 2×2 stiffness in the slider's frame (coupling ρ, χ = √α·tanθ:
:class:`~betvdesign.model.params.HeadCoupling`), the paper's ideal model otherwise
(undamped, plastic impacts, Coulomb stick/slip). Written from MODEL.md only: nothing of
the exact solver nor of :mod:`reference` is imported (no shared phase rule, closed form
or event search), nor of the exact coupled solver :mod:`coupled`, which it checks
(tests/test_coupled_kernel.py); at ρ = 0 it is compared with the exact decoupled solver
(tests/test_coupled_reference.py).

Dimensionless spring forces (y_n = ξ + sin ϖτ, y_t = ζ − sin ϖτ, a = 1/(1 − ρ²)):
F_n = a(y_n + (ρ/χ) y_t) along the gap, R = a(ρχ y_n + y_t) along the slider.

- free flight: ξ'' = −F_n, α ζ'' = −R, s'' = 0; event ξ = 0 falling (a hit);
- contact (ξ ≡ 0), normal reaction n = F_n at ξ = 0; slip (σ = +1) / reverse (σ = −1):
  α ζ'' = −R − σακn, s'' = σβκn, event ζ' = s'; stick: α(1 + 1/β) ζ'' = −R, s'' = ζ'',
  events R + bn = 0 falling (→ slip) and bn − R = 0 falling (→ reverse), b = ακ(1 + β);
  every contact phase: event n = 0 falling (separation);
- a hit sets ξ' = 0; contact opens where n > 0 (or n = 0 and rising), else the hit is
  impulsive and the head leaves; entering stick the common velocity conserves ζ' + s'/β;
  the phase at a contact start or at ζ' = s' comes from the band tested a short
  look-ahead (:data:`LOOKAHEAD` of a cycle) on the stick flow's third-order Taylor
  series.

Cost: an explicit method resolves the stiff mode √λ₊ ≈ √(a(1 + α)/α); per cycle the
steps grow like √λ₊/ϖ (the rigid-direction limit is stated in MODEL.md, not
implemented); the exact solver :mod:`coupled` is some hundred times faster.

References
----------
Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773 (the decoupled model).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

from betvdesign.errors import ParameterError
from betvdesign.model.domain import mode_of
from betvdesign.model.params import HeadCoupling, ModelParams

FREE, SLIP, STICK, REVERSE = "free", "slip", "stick", "reverse"
#: relative velocity |ζ' − s'| below which ζ' = s' is taken as reached (scaled)
VTOL = 1e-9
#: look-ahead [fraction of a cycle] at which the stick band and the contact force are
#: tested at a contact start or at ζ' = s'
LOOKAHEAD = 1e-6
#: an event already at 0 where a phase starts is masked over MASK·(2π/ϖ)
MASK = 1e-9
#: phase switches in one cycle before it is declared chattering (a failure)
MAX_SWITCHES = 2000
#: restarts of Newton after ``transient`` iterations of the map, when no step helps
MAX_RESTARTS = 3
#: integrations of one piece again to a skipped crossing (:func:`_missed`) at most
MAX_RERUNS = 20


@dataclass(frozen=True)
class CoupledRun:
    """Cycles of the coupled model (:func:`simulate_coupled`).

    Attributes
    ----------
    status : str
        "success" or "failed" (``message`` says why; ``section`` holds the cycles done).
    message : str
        What happened.
    section : numpy.ndarray
        (ξ, ξ', ζ, ζ', s, s') [-] at τ = 2mπ/ϖ, m = 0..cycles done, shape (m + 1, 6).
    delta_s : numpy.ndarray
        Per-cycle slider increments [-, units of u·cosθ].
    events : list of (float, str)
        (τ [-], kind): "impact", "impulsive", "separation", "velocity-match", "band-exit".
    n_fev : int
        Right-hand-side evaluations [-].
    mode_end : str
        The automaton's phase at the last section (free, slip, stick, reverse).
    """

    status: str
    message: str
    section: np.ndarray
    delta_s: np.ndarray
    events: list = field(default_factory=list)
    n_fev: int = 0
    mode_end: str = FREE


@dataclass(frozen=True)
class CoupledOrbit:
    """Periodic orbit of the coupled model by Newton shooting (:func:`coupled_periodic_orbit`).

    Attributes
    ----------
    status : str
        "success", "not_converged" or "failed".
    delta_s : float or None
        Slider increment per cycle on the orbit [-, units of u·cosθ].
    mode : str or None
        :func:`betvdesign.model.domain.mode_of` of Δs.
    state : numpy.ndarray or None
        (ξ, ξ', ζ, ζ', s, s') [-] at τ = 0 on the orbit (s = 0).
    residual : float
        Max-norm of map(x) − x over (ξ, ξ', ζ, ζ', s') [-] (the best reached).
    period : int
        Period [cycles].
    n_newton : int
        Newton iterations [-].
    n_fev : int
        Right-hand-side evaluations [-].
    elapsed_s : float
        Wall time [s].
    message : str
        What happened.
    """

    status: str
    delta_s: float | None
    mode: str | None
    state: np.ndarray | None
    residual: float
    period: int
    n_newton: int
    n_fev: int
    elapsed_s: float
    message: str


class _Model:
    """The coupled equations (module docstring) for one parameter set."""

    def __init__(self, p: ModelParams, cpl: HeadCoupling) -> None:
        if not isinstance(p, ModelParams):
            raise ParameterError(f"p must be a ModelParams, got {type(p).__name__}")
        if not isinstance(cpl, HeadCoupling):
            raise ParameterError(f"coupling must be a HeadCoupling, got {type(cpl).__name__}")
        if not p.ideal:
            raise ParameterError(
                "the coupled reference solves the ideal model only (no damping, plastic "
                f"impacts); got zeta_v={p.zeta_v}, zeta_h={p.zeta_h}, e={p.restitution}"
            )
        self.w, self.al, self.be, self.ka = p.varpi, p.alpha, p.beta, p.kappa
        rho, chi = cpl.rho, cpl.chi
        self.a = 1.0 / ((1.0 - rho) * (1.0 + rho))
        self.cn, self.ct = rho / chi, rho * chi  # F_n = a(y_n + cn y_t), R = a(ct y_n + y_t)
        self.b = self.al * self.ka * (1.0 + self.be)
        self.A = self.al * (1.0 + 1.0 / self.be)  # stick inertia
        self.T = 2.0 * math.pi / self.w

    # forces ----------------------------------------------------------------------------
    def n(self, t: float, z: float) -> float:
        """Normal reaction n at ξ = 0 [-]."""
        p = math.sin(self.w * t)
        return self.a * (p + self.cn * (z - p))

    def n_dot(self, t: float, zd: float) -> float:
        """dn/dτ at ξ = 0 [-]."""
        pd = self.w * math.cos(self.w * t)
        return self.a * (pd + self.cn * (zd - pd))

    def r_contact(self, t: float, z: float) -> float:
        """Tangential spring force R at ξ = 0 [-]."""
        p = math.sin(self.w * t)
        return self.a * (self.ct * p + z - p)

    def rhs(self, mode: str):
        """The right-hand side of a phase."""
        w, al, be, ka, a, cn, ct, A = (
            self.w,
            self.al,
            self.be,
            self.ka,
            self.a,
            self.cn,
            self.ct,
            self.A,
        )

        if mode == FREE:

            def f(t: float, y: np.ndarray) -> list[float]:
                p = math.sin(w * t)
                yn, yt = y[0] + p, y[2] - p
                return [y[1], -a * (yn + cn * yt), y[3], -a * (ct * yn + yt) / al, y[5], 0.0]

            return f
        if mode == STICK:

            def f(t: float, y: np.ndarray) -> list[float]:
                p = math.sin(w * t)
                zdd = -a * (ct * p + y[2] - p) / A
                return [0.0, 0.0, y[3], zdd, y[5], zdd]

            return f
        sig = 1.0 if mode == SLIP else -1.0

        def f(t: float, y: np.ndarray) -> list[float]:
            p = math.sin(w * t)
            yt = y[2] - p
            n = a * (p + cn * yt)
            r = a * (ct * p + yt)
            return [0.0, 0.0, y[3], (-r - sig * al * ka * n) / al, y[5], sig * be * ka * n]

        return f

    def events(self, mode: str) -> list:
        """The terminal events of a phase.

        Each crosses 0 in its ``direction`` and carries ``slope(t, y, f)``, its derivative
        along the flow f = y' (the grazing watch, :func:`_missed`).
        """
        w, a, cn, ct, b = self.w, self.a, self.cn, self.ct, self.b

        def n_slope(t: float, y: np.ndarray, f: list) -> float:
            pd = w * math.cos(w * t)
            return a * ((1.0 - cn) * pd + cn * y[3])

        def r_slope(t: float, y: np.ndarray, f: list) -> float:
            pd = w * math.cos(w * t)
            return a * ((ct - 1.0) * pd + y[3])

        if mode == FREE:

            def gap(t: float, y: np.ndarray) -> float:
                return y[0]

            gap.direction, gap.kind = -1, "impact"
            gap.slope = lambda t, y, f: y[1]
            return [gap]

        def sep(t: float, y: np.ndarray) -> float:
            return self.n(t, y[2])

        sep.direction, sep.kind, sep.slope = -1, "separation", n_slope
        if mode == STICK:

            def lo(t: float, y: np.ndarray) -> float:
                return self.r_contact(t, y[2]) + b * self.n(t, y[2])

            def hi(t: float, y: np.ndarray) -> float:
                return b * self.n(t, y[2]) - self.r_contact(t, y[2])

            lo.direction, lo.kind = -1, "band-exit"
            hi.direction, hi.kind = -1, "band-exit"
            lo.slope = lambda t, y, f: r_slope(t, y, f) + b * n_slope(t, y, f)
            hi.slope = lambda t, y, f: b * n_slope(t, y, f) - r_slope(t, y, f)
            return [sep, lo, hi]

        def vel(t: float, y: np.ndarray) -> float:
            return y[3] - y[5]

        vel.direction, vel.kind = (-1 if mode == SLIP else 1), "velocity-match"
        vel.slope = lambda t, y, f: f[3] - f[5]
        return [sep, vel]

    # the automaton's rules -------------------------------------------------------------
    def stick_velocity(self, zd: float, sd: float) -> float:
        """Common velocity conserving ζ' + s'/β [-]."""
        return (zd + sd / self.be) / (1.0 + 1.0 / self.be)

    def band(self, t: float, z: float, vs: float) -> str:
        """Stick-band verdict a look-ahead d after τ on the stick flow (3rd-order Taylor)."""
        d = LOOKAHEAD * self.T
        w, a, ct, A = self.w, self.a, self.ct, self.A
        p, pd = math.sin(w * t), w * math.cos(w * t)
        z2 = -a * (ct * p + z - p) / A
        z3 = -a * (ct * pd + vs - pd) / A
        zn = z + vs * d + z2 * d * d / 2.0 + z3 * d**3 / 6.0
        r, n = self.r_contact(t + d, zn), self.n(t + d, zn)
        if r + self.b * n < 0.0:
            return SLIP
        if self.b * n - r < 0.0:
            return REVERSE
        return STICK

    def contact_opens(self, t: float, z: float, zd: float) -> bool:
        """Whether a hit at τ with ζ, ζ' opens a contact (n > 0, or n = 0 and rising)."""
        n = self.n(t, z)
        scale = self.a * (1.0 + abs(z))
        if abs(n) > 1e-13 * scale:
            return n > 0.0
        return self.n_dot(t, zd) > 0.0


def _mask(ev, t0: float, mask: float):
    """``ev`` held on its side before the crossing (−direction) until τ0 + mask."""

    def g(t: float, y: np.ndarray) -> float:
        if t < t0 + mask:
            return -ev.direction * 1.0
        return ev(t, y)

    g.terminal, g.direction, g.kind, g.slope = True, ev.direction, ev.kind, ev.slope
    return g


def _slope(ev, rhs):
    """Non-terminal companion of ``ev``: its slope along the flow (0 at an extremum)."""

    def h(t: float, y: np.ndarray) -> float:
        return ev.slope(t, y, rhs(t, y))

    h.terminal, h.direction = False, 0
    return h


def _missed(evs: list, watch: list, sol) -> float | None:
    """Where to stop again when ``sol`` skipped a crossing; None if it did not.

    A crossing is skipped when an event function crosses twice within one step (seen at
    an extremum of it, before where ``sol`` stopped, that lies past its crossing), or when
    the step that a terminal event cut short went on past another event's crossing
    (that event lies past its crossing where ``sol`` stopped). The earliest such time.
    """
    t_stop, y_stop = sol.t[-1], sol.y[:, -1]
    fired = [i for i in range(len(evs)) if sol.t_events[i].size]
    first = None
    for i, ev in enumerate(evs):
        if sol.status == 1 and i not in fired and ev.direction * ev(t_stop, y_stop) > 0.0:
            first = t_stop
        for t, y in zip(sol.t_events[len(evs) + i], sol.y_events[len(evs) + i], strict=True):
            if t < t_stop and ev.direction * ev(t, y) > 0.0 and (first is None or t < first):
                first = float(t)
    return first


class _Runner:
    """The hybrid automaton of the coupled model, integrated piece by piece."""

    def __init__(self, mdl: _Model, rtol: float, atol: float) -> None:
        self.m, self.rtol, self.atol = mdl, rtol, atol
        self.nfev = 0
        self.events: list = []

    def start_mode(self, t: float, y: np.ndarray) -> str:
        """The phase at τ from the state: contact opens where ξ = 0, ξ' ≤ 0 and n ≥ 0."""
        if y[0] == 0.0 and y[1] <= 0.0:
            return self.hit(t, y, log=False)
        return FREE

    def hit(self, t: float, y: np.ndarray, log: bool = True) -> str:
        """A hit at τ: ξ = ξ' = 0; the phase that follows."""
        y[0], y[1] = 0.0, 0.0
        mdl = self.m
        if not mdl.contact_opens(t, y[2], y[3]):
            if log:
                self.events.append((t, "impulsive"))
            return FREE
        if log:
            self.events.append((t, "impact"))
        return self.decide(t, y, matched=False)

    def decide(self, t: float, y: np.ndarray, matched: bool) -> str:
        """Contact phase at τ (a contact start or ζ' = s'); sets the common velocity in stick."""
        mdl = self.m
        v = y[3] - y[5]
        if not matched and abs(v) > VTOL * (1.0 + abs(y[3]) + abs(y[5])):
            return SLIP if v > 0.0 else REVERSE
        vs = mdl.stick_velocity(y[3], y[5])
        mode = mdl.band(t, y[2], vs)
        if mode == STICK or matched:
            y[3] = y[5] = vs
        return mode

    def cycle(self, y: np.ndarray, mode: str, t0: float, t1: float) -> tuple[np.ndarray, str, str]:
        """Integrate from τ0 to τ1 through every event; (state, phase, error message)."""
        mdl = self.m
        t, switches = t0, 0
        mask_scale = MASK * mdl.T  # events at 0 where a piece starts are masked
        while t < t1:
            evs = []
            for ev in mdl.events(mode):
                g0 = ev(t, y)
                zero = abs(g0) <= 1e-12 * (1.0 + mdl.a * (1.0 + abs(y[2])) + abs(y[3]) + abs(y[5]))
                e = _mask(ev, t, mask_scale) if zero else ev
                e.terminal, e.direction = True, ev.direction
                evs.append(e)
            rhs = mdl.rhs(mode)
            watch = [_slope(ev, rhs) for ev in evs]
            t_end = t1
            for _ in range(MAX_RERUNS):
                sol = solve_ivp(
                    rhs, (t, t_end), y, method="DOP853", rtol=self.rtol, atol=self.atol,
                    events=evs + watch,
                )  # fmt: skip
                self.nfev += sol.nfev
                if sol.status == -1:
                    return y, mode, f"solve_ivp failed at τ = {t:.6g}: {sol.message}"
                missed = _missed(evs, watch, sol)
                if missed is None:
                    break
                t_end = missed  # a skipped crossing: integrate again, stopping there
            else:
                return y, mode, f"an event crossing could not be bracketed near τ = {t_end:.6g}"
            hits = [i for i in range(len(evs)) if sol.t_events[i].size]
            if not hits:
                if sol.t[-1] < t1:  # reached a missed crossing's extremum: impossible
                    return y, mode, f"event bracket lost near τ = {sol.t[-1]:.6g}"
                return sol.y[:, -1].copy(), mode, ""
            k = min(hits, key=lambda i: sol.t_events[i][0])
            t = float(sol.t_events[k][0])
            y = sol.y_events[k][0].copy()
            switches += 1
            if switches > MAX_SWITCHES:
                return y, mode, f"more than {MAX_SWITCHES} switches in a cycle near τ = {t:.6g}"
            kind = evs[k].kind
            if kind == "impact":
                mode = self.hit(t, y)
            elif kind == "separation":
                self.events.append((t, "separation"))
                y[0], y[1] = 0.0, 0.0
                mode = FREE
            elif kind == "velocity-match":
                self.events.append((t, "velocity-match"))
                mode = self.decide(t, y, matched=True)
            else:
                self.events.append((t, "band-exit"))
                mode = self.decide(t, y, matched=True)
            if mode != FREE:
                y[0], y[1] = 0.0, 0.0
        return y, mode, ""


def _check(cycles: object, rtol: float, atol: float) -> int:
    if isinstance(cycles, bool) or not isinstance(cycles, (int, np.integer)) or cycles < 0:
        raise ParameterError(f"cycles must be an integer ≥ 0, got {cycles!r}")
    for name, v in (("rtol", rtol), ("atol", atol)):
        if not (isinstance(v, (int, float)) and v > 0.0 and math.isfinite(v)):
            raise ParameterError(f"{name} must be > 0, got {v!r}")
    return int(cycles)


def simulate_coupled(
    p: ModelParams,
    coupling: HeadCoupling,
    cycles: int,
    *,
    state0: object = None,
    rtol: float = 1e-12,
    atol: float = 1e-14,
) -> CoupledRun:
    """Integrate ``cycles`` actuation cycles of the coupled model from ``state0`` at τ = 0.

    Parameters
    ----------
    p : ModelParams
        ϖ, α, β, κ (ideal: no damping, plastic impacts).
    coupling : HeadCoupling
        ρ and χ (ρ = 0: the paper's model).
    cycles : int
        Actuation cycles [-] (≥ 0).
    state0 : sequence of 6 floats, optional
        (ξ, ξ', ζ, ζ', s, s') [-] at τ = 0, ξ ≥ 0; default all zero (a contact start
        where n rises).
    rtol, atol : float
        solve_ivp's tolerances [-].

    Returns
    -------
    CoupledRun
        Sections, increments, events and counters.

    Raises
    ------
    ParameterError
        For invalid parameters, cycles, tolerances or state0.
    """
    mdl = _Model(p, coupling)
    n = _check(cycles, rtol, atol)
    y = np.zeros(6) if state0 is None else np.array(state0, dtype=float).reshape(-1)
    if y.shape != (6,) or not np.all(np.isfinite(y)) or y[0] < 0.0:
        raise ParameterError(
            f"state0 must be 6 finite numbers (ξ, ξ', ζ, ζ', s, s') with ξ ≥ 0, got {state0!r}"
        )
    run = _Runner(mdl, rtol, atol)
    mode = run.start_mode(0.0, y)
    if mode != FREE:
        run.events.append((0.0, "impact"))
    sec = np.empty((n + 1, 6))
    sec[0] = y
    for m in range(n):
        y, mode, err = run.cycle(y, mode, m * mdl.T, (m + 1) * mdl.T)
        if err:
            return CoupledRun(
                "failed",
                err,
                sec[: m + 1].copy(),
                np.diff(sec[: m + 1, 4]),
                run.events,
                run.nfev,
                mode,
            )
        sec[m + 1] = y
    return CoupledRun(
        "success", f"{n} cycles integrated", sec, np.diff(sec[:, 4]), run.events, run.nfev, mode
    )


def _map(
    mdl: _Model, x: np.ndarray, period: int, rtol: float, atol: float
) -> tuple[np.ndarray, float, int, str]:
    """Section map over ``period`` cycles of x = (ξ, ξ', ζ, ζ', s'): (map(x), Δs, nfev, error)."""
    y = np.array([x[0], x[1], x[2], x[3], 0.0, x[4]])
    run = _Runner(mdl, rtol, atol)
    mode = run.start_mode(0.0, y)
    for m in range(period):
        y, mode, err = run.cycle(y, mode, m * mdl.T, (m + 1) * mdl.T)
        if err:
            return x, math.nan, run.nfev, err
    return np.array([y[0], y[1], y[2], y[3], y[5]]), y[4] / period, run.nfev, ""


def coupled_periodic_orbit(
    p: ModelParams,
    coupling: HeadCoupling,
    *,
    guess: object = None,
    period: int = 1,
    transient: int = 40,
    tol: float = 1e-10,
    max_newton: int = 30,
    rtol: float = 1e-12,
    atol: float = 1e-14,
) -> CoupledOrbit:
    """Periodic orbit of the coupled model: Newton shooting on the section map.

    The unknown is x = (ξ, ξ', ζ, ζ', s') at τ = 0 (the slider position drifts); the
    residual map(x) − x over ``period`` cycles, its Jacobian by forward differences
    (steps 1e-7·max(1, |x_i|), ξ stepped upward), the step by least squares (the plastic
    impact can make the map flat in a direction), halved while the residual grows; when
    no step helps, ``transient`` iterations of the map and Newton again (at most
    :data:`MAX_RESTARTS` times). Accepted when ‖map(x) − x‖∞ ≤ tol.

    Parameters
    ----------
    p, coupling
        The model (as :func:`simulate_coupled`).
    guess : sequence of 6 floats, optional
        (ξ, ξ', ζ, ζ', s, s') [-] to start Newton from (e.g. the decoupled orbit's
        state); default: the state after ``transient`` cycles from rest.
    period : int
        Period [cycles] (≥ 1).
    transient : int
        Cycles from rest before Newton when no guess is given [-].
    tol : float
        Accepted residual [-].
    max_newton : int
        Newton iterations at most [-].
    rtol, atol : float
        solve_ivp's tolerances [-].

    Returns
    -------
    CoupledOrbit
        "success" with Δs and the state, or "not_converged" / "failed" with the reason.
    """
    t_start = time.perf_counter()
    mdl = _Model(p, coupling)
    if isinstance(period, bool) or not isinstance(period, (int, np.integer)) or period < 1:
        raise ParameterError(f"period must be an integer ≥ 1, got {period!r}")
    _check(transient, rtol, atol)
    nfev = 0

    def fail(status: str, msg: str, res: float, it: int) -> CoupledOrbit:
        return CoupledOrbit(
            status, None, None, None, res, period, it, nfev, time.perf_counter() - t_start, msg
        )

    if guess is None:
        tr = simulate_coupled(p, coupling, transient, rtol=rtol, atol=atol)
        nfev += tr.n_fev
        if tr.status != "success":
            return fail("failed", tr.message, math.inf, 0)
        y0 = tr.section[-1]
    else:
        y0 = np.array(guess, dtype=float).reshape(-1)
        if y0.shape != (6,) or not np.all(np.isfinite(y0)) or y0[0] < 0.0:
            raise ParameterError(f"guess must be 6 finite numbers with ξ ≥ 0, got {guess!r}")
    x = np.array([y0[0], y0[1], y0[2], y0[3], y0[5]])
    fx, ds, k, err = _map(mdl, x, period, rtol, atol)
    nfev += k
    if err:
        return fail("failed", err, math.inf, 0)
    r = fx - x
    res = float(np.max(np.abs(r)))
    best, restarts = res, 0
    for it in range(1, max_newton + 1):
        if res <= tol:
            st = np.array([x[0], x[1], x[2], x[3], 0.0, x[4]])
            return CoupledOrbit(
                "success", ds, mode_of(ds), st, res, period, it - 1, nfev,
                time.perf_counter() - t_start, f"residual {res:.2e} after {it - 1} Newton steps",
            )  # fmt: skip
        J = np.empty((5, 5))
        for i in range(5):
            h = 1e-7 * max(1.0, abs(x[i]))
            xi = x.copy()
            xi[i] += h
            fi, _, k, err = _map(mdl, xi, period, rtol, atol)
            nfev += k
            if err:
                return fail("failed", err, best, it)
            J[:, i] = ((fi - xi) - r) / h
        # least squares: the plastic impact can make the map flat in ξ' (rank-deficient J)
        dx = np.linalg.lstsq(J, -r, rcond=1e-12)[0]
        lam = 1.0
        for _ in range(12):
            xn = x + lam * dx
            if xn[0] < 0.0:
                xn[0] = 0.0
            fn, dsn, k, err = _map(mdl, xn, period, rtol, atol)
            nfev += k
            if not err:
                rn = fn - xn
                resn = float(np.max(np.abs(rn)))
                if resn < res or resn <= tol:
                    break
            lam *= 0.5
        else:  # no step lowers the residual: iterate the map (a stable orbit attracts)
            if restarts == MAX_RESTARTS:
                return fail(
                    "not_converged", f"no Newton step lowers the residual {res:.2e}", best, it
                )
            restarts += 1
            for _ in range(transient):
                xn, dsn, k, err = _map(mdl, x, period, rtol, atol)
                nfev += k
                if err:
                    return fail("failed", err, best, it)
                rn, x = xn - x, xn
            xn, resn = x, float(np.max(np.abs(rn)))
            fx, dsn, k, err = _map(mdl, xn, period, rtol, atol)
            nfev += k
            if err:
                return fail("failed", err, best, it)
            rn, resn = fx - xn, float(np.max(np.abs(fx - xn)))
        x, r, res, ds = xn, rn, resn, dsn
        best = min(best, res)
    return fail(
        "not_converged", f"residual {res:.2e} after {max_newton} Newton steps", best, max_newton
    )
