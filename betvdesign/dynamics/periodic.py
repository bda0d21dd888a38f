"""The periodic state of the slider: Newton shooting on the Poincaré map (unit-free).

docs/MODEL.md, "Slider". Once the vertical motion is periodic (k_v cycles, exact,
:mod:`vertical`), the section state at τ = 2mπ/ϖ that still evolves is
x = (ζ, ζ', s'); the slider position s only drifts (translation invariance, a
structural multiplier 1 that is excluded). A periodic orbit of n = j·k_v cycles
is a root of G(x) = Φⁿ(x) − x, where Φⁿ is the exact map over n cycles.

Algorithm: brute-force iteration from rest gives the initial guess (and is the
fallback: chunks doubling in length up to ``max_cycles``); from it, Newton with a
forward-difference Jacobian and backtracking on ‖G‖∞. Acceptance is *only* on the
fixed-point residual ‖G(x)‖∞ ≤ tol over the whole section state (the vertical
part is periodic by construction and checked too), never on successive Δs
agreeing (settling can take ~10⁵ cycles). Stability: the Floquet multipliers are
the eigenvalues of the central-difference Jacobian of Φⁿ at the fixed point; an
unstable fixed point is not what the device settles to and is not accepted (the
next period j·k_v is tried, then more brute force).

Unbounded tangential motion (MODEL.md, last design note): at the free-flight
resonance α·ϖ² = 1 no bounded motion exists while ακ < 2, whatever β — proof, for
the oscillator α ζ'' + ζ = F(τ) of free flight and slip, with w = ζ' − iϖζ:
(w e^{iϖτ})' = ϖ² F e^{iϖτ}, so over a cycle (e^{iϖτ} = 1 at both sections)
Im w grows by ϖ² ∫₀ᵀ F sin ϖτ dτ. F = sin ϖτ in free flight; in contact (only where
sin ϖτ ≥ 0) F = (1 − ακσ) sin ϖτ with σ = ±1 in slip and |σ| ≤ 1 in stick (the
band rule; stick written as α ζ'' + ζ = sin ϖτ − α·friction). Hence
Im w = −ϖ ζ at the section grows by at least ϖ²(π/ϖ − ακ·π/(2ϖ)), i.e.
**ζ(section) falls by at least π(1 − ακ/2) every cycle**, from any state: the
amplitude grows linearly without bound and no periodic orbit of any period exists.
Such a point gets status ``"unbounded"`` after a short window that measures the
rate (and checks it against the bound), instead of a 10⁵-cycle budget ending in
``not_converged``. "Exact" means |α·ϖ² − 1| ≤ RESONANCE_RTOL: a detuning δ turns
the per-cycle increment by ≈ πδ, so the growth stays linear for ≳ 0.01/δ ≈ 10⁷
cycles there, far beyond any budget. Detuned points, however close, take the normal
path (they settle, with |μ| → 1, or end ``not_converged``), so a slowly settling
orbit is never flagged. The stick resonance α(1 + 1/β)·ϖ² = 1 is bounded: stick
holds only while ζ stays within the friction band, so it cannot grow.
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from betvdesign.dynamics import contact, shooting
from betvdesign.dynamics.flows import phase_table
from betvdesign.dynamics.jit import compile_note
from betvdesign.dynamics.result import PeriodicResult
from betvdesign.dynamics.shooting import TRUST
from betvdesign.dynamics.solver import CycleFailure, CycleRunner
from betvdesign.dynamics.vertical import VerticalSchedule, VerticalSearchError
from betvdesign.errors import ParameterError
from betvdesign.model.domain import ROUND_OFF_SCALE, mode_of
from betvdesign.model.params import ModelParams

POLISH = 1e-14
#: |α·ϖ² − 1| at or below which the free-flight tangential resonance counts as exact.
RESONANCE_RTOL = 1e-9
#: Cycles over which the secular growth at an exact resonance is measured.
GROWTH_WINDOW = 256
#: Anderson acceleration: differences kept, map evaluations allowed, evaluations without a
#: new best residual before giving up, residual at which Newton takes over.
ANDERSON_DEPTH = 5
ANDERSON_BUDGET = 600
ANDERSON_STALL = 24
ANDERSON_HANDOFF = 1e-8
#: Bisection steps on the slider velocity when Anderson stalls (:func:`_bracket_slider`).
BRACKET_BISECT = 40


def resonance_growth_bound(p: ModelParams) -> float | None:
    """Proven least fall of ζ per cycle at the section at the free-flight resonance.

    Parameters
    ----------
    p : ModelParams
        The model.

    Returns
    -------
    float or None
        π(1 − ακ/2) [-/cycle] when α·ϖ² = 1 (within :data:`RESONANCE_RTOL`), ακ < 2 and
        the model is the paper's (no damping, no restitution); None when the bound does
        not apply (module docstring; MODEL.md "Dimensionless model", no-contact and slip).

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773 (the model; unbounded
    tangential motion near a·ϖ² = 1).
    """
    ak = p.alpha * p.kappa
    if not p.ideal or abs(p.alpha * p.varpi**2 - 1.0) > RESONANCE_RTOL or ak >= 2.0:
        return None
    return math.pi * (1.0 - 0.5 * ak)


class _Map:
    """The section map Φⁿ of the periodic search, with its counters.

    Φⁿ: section state (ζ, ζ', s') at the first periodic cycle → n cycles later
    (compiled: :mod:`shooting`); counts cycles, events and evaluations.
    """

    def __init__(self, c: np.ndarray, vs: VerticalSchedule, m0: int):
        self.c, self.vs, self.m0 = c, vs, m0
        self.count = np.zeros(3, dtype=np.int64)  # cycles, events, evaluations
        self._shots: dict[int, tuple] = {}
        self._rows = np.empty((0, 4))
        self._log = np.empty(0, contact.LOG_DTYPE)
        self._segs = np.empty(0, contact.SEG_DTYPE)

    @property
    def n_cycles(self) -> int:
        return int(self.count[0])

    @property
    def n_events(self) -> int:
        return int(self.count[1])

    @property
    def n_evals(self) -> int:
        return int(self.count[2])

    def shot(self, n: int) -> tuple:
        """The map's arguments over n cycles (:data:`shooting.SHOT`)."""
        sh = self._shots.get(n)
        if sh is None:
            idx = self.vs.row(np.arange(self.m0, self.m0 + n))
            sh = (
                self.c,
                self.vs.table,
                idx,
                self.vs.impulsive,
                self.m0,
                self._rows,
                self._log,
                self._segs,
                self.count,
            )
            if n <= 64:  # repeated calls of the periodic map; a long transient runs once
                self._shots[n] = sh
        return sh

    def __call__(self, x: np.ndarray, n: int) -> tuple[np.ndarray, float]:
        ok, y, s = shooting.section_map(*self.shot(n), np.asarray(x, dtype=float))
        if not ok:  # run again where the failure is explained (rare path)
            CycleRunner(self.c, self.vs).run(self.m0, n, x[0], x[1], 0.0, x[2], check_finite=False)
            raise CycleFailure(f"a contact could not be advanced from cycle {self.m0}", self.m0)
        return y, s

    def residual(self, x: np.ndarray, n: int) -> tuple[float, np.ndarray, float]:
        return shooting.residual(*self.shot(n), np.asarray(x, dtype=float))

    def jacobian(self, x: np.ndarray, n: int, y: np.ndarray, central: bool = False) -> np.ndarray:
        ok, J = shooting.jacobian(*self.shot(n), x, y, central)
        if not ok:
            raise CycleFailure("a contact could not be advanced (Jacobian)", self.m0)
        return J


def _newton(
    phi: _Map, x: np.ndarray, n: int, tol: float, polish: float = 0.0
) -> tuple[np.ndarray, float, float, int]:
    """Newton on Φⁿ(x) − x = 0 (:func:`shooting.newton`): (x, residual, s, iterations)."""
    x, r, s, it = shooting.newton(*phi.shot(n), np.asarray(x, dtype=float), tol, polish)
    return x, r, s, int(it)


def _anderson(phi: _Map, x: np.ndarray, n: int) -> np.ndarray | None:
    """A start for Newton from iterate ``x``: Anderson-accelerated iteration of Φⁿ.

    Plain iteration settles at the rate |μ|max per period (≥ 0.99 near ϖ → 2: thousands of
    cycles), and Newton fails far from the orbit because the map is only piecewise smooth
    (far out a whole contact slips one way: s' is then neutral and J − I singular).
    Anderson mixing (type II, depth :data:`ANDERSON_DEPTH`) extrapolates from the last
    iterates; every extrapolated point must stay in the trust region around the starting
    iterate (Newton's) — else the history is dropped and the plain image taken.
    This keeps it off the round-off "fixed points" at |s'| ~ 1e14, where a whole contact
    slips one way and the slider's increment falls below the ulp of s'.
    Returns the best point (‖Φⁿ(x) − x‖∞ ≤ :data:`ANDERSON_HANDOFF`), or None. Never
    accepts anything itself: Newton's residual test decides.
    """
    X: list[np.ndarray] = []
    F: list[np.ndarray] = []
    best, best_r, since = None, math.inf, 0
    x0, radius = x, TRUST * (1.0 + float(np.max(np.abs(x))))
    for _ in range(ANDERSON_BUDGET // n):
        r, y, _ = phi.residual(x, n)
        if not math.isfinite(r):
            return None
        if r < best_r:
            best, best_r, since = x, r, 0
            if r <= ANDERSON_HANDOFF:
                return best
        else:
            since += n
            if since > ANDERSON_STALL:
                break
        f = y - x
        X.append(x)
        F.append(f)
        if len(X) > ANDERSON_DEPTH + 1:
            del X[0], F[0]
        xn = y
        if len(X) > 1:
            dF = np.diff(np.array(F), axis=0).T
            dX = np.diff(np.array(X), axis=0).T
            try:
                g = np.linalg.lstsq(dF, f, rcond=None)[0]
                xn = y - (dX + dF) @ g
            except np.linalg.LinAlgError:
                xn = y
            if not (float(np.max(np.abs(xn - x0))) <= radius):
                X, F, xn = [], [], y
        x = xn
    if best is None:
        return None
    return _bracket_slider(phi, best, n, radius)


def _bracket_slider(phi: _Map, x: np.ndarray, n: int, radius: float) -> np.ndarray | None:
    """Move s' alone to where its increment over n cycles changes sign (bisection).

    Where a whole contact slips one way the slider's velocity s' does not act on the head
    (ζ, ζ'), so Anderson stalls with ζ, ζ' settled and a constant s' increment c ≠ 0.
    A periodic orbit needs the friction to change sign within the contact, i.e. s' inside
    the range of ζ' there: s' is walked (doubling steps, within ``radius``) in the
    direction of c until the increment changes sign, then bisected on that sign.
    """
    r, y, _ = phi.residual(x, n)
    if not math.isfinite(r):
        return None
    c = float(y[2] - x[2])
    if c == 0.0:
        return x
    lo, hi = float(x[2]), None
    step = 0.01 * (1.0 + abs(float(x[1])))
    while step <= radius:
        xt = x.copy()
        xt[2] = lo + math.copysign(step, c)
        rt, yt, _ = phi.residual(xt, n)
        if not math.isfinite(rt):
            return None
        if (yt[2] - xt[2]) * c <= 0.0:
            hi = float(xt[2])
            break
        step *= 2.0
    if hi is None:
        return None
    lo = hi - math.copysign(step, c) if step > 0.01 * (1.0 + abs(float(x[1]))) else lo
    for _ in range(BRACKET_BISECT):
        mid = 0.5 * (lo + hi)
        xt = x.copy()
        xt[2] = mid
        rt, yt, _ = phi.residual(xt, n)
        if not math.isfinite(rt):
            return None
        if (yt[2] - xt[2]) * c > 0.0:
            lo = mid
        else:
            hi = mid
    x = x.copy()
    x[2] = 0.5 * (lo + hi)
    return x


def periodic_orbit(
    p: ModelParams,
    *,
    tol: float = 1e-10,
    max_cycles: int = 100_000,
    max_period: int = 4,
    transient: int = 16,
) -> PeriodicResult:
    """Periodic state reached from rest (MODEL.md "Initial state"), by shooting.

    Newton (with Anderson-accelerated starts) on the exact Poincaré map of the section
    state (ζ, ζ', s'), accepted on the fixed-point residual only, stable orbits only
    (module docstring).

    Parameters
    ----------
    p : ModelParams
        The model, with its optional damping and restitution.
    tol : float
        Accepted fixed-point residual ‖Φⁿ(x) − x‖∞ [-].
    max_cycles : int
        Brute-force budget [cycles from rest] before giving up.
    max_period : int
        Periods j·k_v tried, j ≤ max_period [-] (k_v the vertical period).
    transient : int
        Cycles from rest before the first Newton attempt [-].

    Returns
    -------
    PeriodicResult
        Status (:data:`~betvdesign.dynamics.result.PeriodicStatus`): "success";
        "unbounded" (exact free-flight tangential resonance α·ϖ² = 1 with ακ < 2: no
        bounded motion exists, proven and measured, see the module docstring);
        "not_converged" (budget spent); "not_driven" (no contact recurs); "failed".

    Raises
    ------
    ParameterError
        For a ``p`` that is not a ModelParams or a ``tol`` that is not finite and > 0.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773 (the model; the slider
    settles to a periodic motion of the actuator's period).
    Budd & Dux, Phil. Trans. R. Soc. A 347 (1994), doi:10.1098/rsta.1994.0044 (chattering, with
    restitution).
    """
    if not isinstance(p, ModelParams):
        raise ParameterError(f"p must be a ModelParams, got {type(p).__name__}")
    if not (math.isfinite(tol) and tol > 0.0):
        raise ParameterError(f"tol must be finite and > 0, got {tol!r}")
    return compile_note(  # type: ignore[return-value]
        "periodic_orbit", lambda: _periodic_orbit(p, tol, max_cycles, max_period, transient)
    )


def not_driven_message(p: ModelParams, cycles: int, contact_fraction: float | None = None) -> str:
    """Why the slider is not driven: no contact recurs (status "not_driven").

    The one wording of that verdict, shared by the periodic orbit and the fidelity
    ladder's transient rung (:mod:`betvdesign.checks.fidelity`).

    Parameters
    ----------
    p : ModelParams
        The design's dimensionless parameters.
    cycles : int
        Actuation cycles [-] within which no contact recurred.
    contact_fraction : float, optional
        The periodic vertical motion's share of a cycle in contact [-], when contact
        recurs but lasts at most :data:`~betvdesign.model.domain.ROUND_OFF_SCALE` of
        the cycle (then only the first contact from rest kicks the slider, which
        coasts).

    Returns
    -------
    str
        The verdict and its cause (restitution that never settles, or ϖ beyond the
        design window).
    """
    if contact_fraction is not None:
        return (
            f"contact lasts {contact_fraction:.2g} of each cycle at ϖ = {p.varpi:.17g}, "
            f"below round-off ({ROUND_OFF_SCALE:g}): the slider only coasts on its first "
            "contact from rest and is not driven (MODEL.md design window 0.5 ≤ ϖ < 2; "
            "contact vanishes at its upper edge)"
        )
    return (
        f"no contact recurs within {cycles} cycles at ϖ = {p.varpi:g}: hits are "
        "impulsive only and the slider is not driven ("
        + (
            f"restitution e = {p.restitution:g}: the rebounds never settle into contact "
            "before the normal force falls to zero; a lower ϖ or e lets them settle"
            if p.restitution > 0.0 and p.varpi < 2.0
            else "MODEL.md design window 0.5 ≤ ϖ < 2"
        )
        + ")"
    )


def _spent(vs: VerticalSchedule, phi: _Map | None, t0: float) -> dict[str, Any]:
    """What every answer of :func:`_periodic_orbit` carries.

    Parameters
    ----------
    vs : VerticalSchedule
        The vertical motion.
    phi : _Map or None
        The section map (None before it exists).
    t0 : float
        :func:`time.perf_counter` at the start [s].

    Returns
    -------
    dict
        The vertical motion's hits and contact fraction, the counters so far and the
        time taken [s].
    """
    return dict(
        impacts_per_cycle=vs.hits_per_cycle(),
        contact_fraction=vs.contact_fraction(),
        n_cycles=phi.n_cycles if phi else 0,
        n_events=phi.n_events if phi else 0,
        n_root_evals=(phi.n_evals if phi else 0) + vs.n_root_evals,
        elapsed_s=time.perf_counter() - t0,
    )


def _from_rest(
    p: ModelParams, vs: VerticalSchedule, phi: _Map, max_cycles: int, t0: float
) -> PeriodicResult | tuple[np.ndarray, float]:
    """Run from rest to the first periodic cycle of the vertical motion.

    A design whose motion provably grows without bound (:func:`resonance_growth_bound`)
    is told here, from a measured window of growth.

    Parameters
    ----------
    p : ModelParams
        The model.
    vs : VerticalSchedule
        Its vertical motion (periodic).
    phi : _Map
        The section map from the first periodic cycle.
    max_cycles : int
        The cycle budget [-].
    t0 : float
        :func:`time.perf_counter` at the start [s].

    Returns
    -------
    PeriodicResult or tuple
        A failure ("failed", "unbounded"), or the section state (ζ, ζ', s') [-] at the
        first periodic cycle and the travel s [-] so far.
    """
    m0, kv = phi.m0, vs.period
    pre = _Map(phi.c, vs, 0)
    try:
        x, s_total = pre(np.zeros(3), m0)
    except (CycleFailure, RuntimeError) as exc:
        return PeriodicResult.failure(
            p, "failed", f"transient from rest failed: {exc}", **_spent(vs, phi, t0)
        )
    bound = resonance_growth_bound(p)
    if bound is not None:
        window = min(GROWTH_WINDOW, max_cycles - m0)  # the budget holds here too
        grown = _measure_growth(phi, x.copy(), bound, kv, window)
        if grown is not None:
            rate, n, amp, s_win = grown
            return PeriodicResult.failure(
                p,
                "unbounded",
                _unbounded_message(p, bound, rate, n, amp, m0 + n),
                transient_cycles=m0 + n,
                transient_s=s_total + s_win,
                **_spent(vs, phi, t0),
            )
    return x, s_total


def _newton_period(
    phi: _Map, x: np.ndarray, n: int, tol: float, accelerated: set[int]
) -> tuple[np.ndarray, float, float, int]:
    """Newton for a fixed point of Φⁿ from ``x``, restarted once per n from Anderson.

    Parameters
    ----------
    phi : _Map
        The section map.
    x : numpy.ndarray
        The start (ζ, ζ', s') [-].
    n : int
        The period tried [cycles].
    tol : float
        The residual asked [-].
    accelerated : set of int
        The periods already restarted from Anderson (updated).

    Returns
    -------
    tuple
        The state [-], its residual [-], the travel over n cycles [-] and the Newton
        iterations.
    """
    xs, r, s, n_newton = _newton(phi, x.copy(), n, tol, POLISH)
    if r > tol and n not in accelerated:  # once per period: a better start
        accelerated.add(n)
        xa = _anderson(phi, x.copy(), n)
        if xa is not None:
            xs, r, s, it = _newton(phi, xa, n, tol, POLISH)
            n_newton += it
    return xs, r, s, n_newton


def _shortest_period(
    phi: _Map, found: tuple[np.ndarray, float, float], j: int, kv: int, tol: float
) -> tuple[np.ndarray, float, float, int, int]:
    """The shortest period of a fixed point of Φ^(j·kv): a divisor's, if it is one too.

    Parameters
    ----------
    phi : _Map
        The section map.
    found : tuple
        The fixed point (ζ, ζ', s') [-], its residual [-] and travel [-].
    j : int
        Its period in vertical periods.
    kv : int
        The vertical period [cycles].
    tol : float
        The residual asked [-].

    Returns
    -------
    tuple
        The state, residual, travel and period [cycles] kept, and the Newton iterations
        spent.
    """
    xs, r, s = found
    n, n_newton = j * kv, 0
    for d in range(1, j):  # a period-n fixed point may have a shorter period
        if j % d == 0:
            xd, rd, sd, itd = _newton(phi, xs.copy(), d * kv, tol, POLISH)
            n_newton += itd
            if rd <= tol and float(np.max(np.abs(xd - xs))) <= 1e3 * tol:
                xs, r, s, n = xd, rd, sd, d * kv
                break
    return xs, r, s, n, n_newton


def _accept(
    phi: _Map, vs: VerticalSchedule, xs: np.ndarray, n: int, tol: float
) -> tuple[float, np.ndarray, list[float], float] | None:
    """Accept a fixed point of Φⁿ if it is stable and periodic to ``tol`` in full.

    Parameters
    ----------
    phi : _Map
        The section map.
    vs : VerticalSchedule
        The vertical motion.
    xs : numpy.ndarray
        The fixed point (ζ, ζ', s') [-].
    n : int
        Its period [cycles].
    tol : float
        The residual asked [-].

    Returns
    -------
    tuple or None
        The residual of the whole state, tangential and vertical [-], the Floquet
        multipliers by decreasing modulus, the vertical section state (ξ, ξ') [-] and
        the travel over n cycles [-]; None for an unstable orbit (not where the device
        settles) or one not periodic to ``tol``.
    """
    J = phi.jacobian(xs, n, xs, central=True)
    mu = np.linalg.eigvals(J)
    mu = mu[np.argsort(-np.abs(mu))]
    if np.max(np.abs(mu)) >= 1.0:
        return None  # an unstable orbit: not where the device settles
    r_final, _, s = phi.residual(xs, n)
    a, b = vs.table[vs.row(np.array([phi.m0, phi.m0 + n]))].tolist()
    vert = abs(b[0] - a[0]) + abs(b[1] - a[1])
    r_final = max(r_final, vert)
    if r_final > tol:
        return None
    return r_final, mu, a, s


def _orbit(
    p: ModelParams,
    vs: VerticalSchedule,
    phi: _Map,
    t0: float,
    found: tuple[np.ndarray, int, float],
    accepted: tuple[float, np.ndarray, list[float], float],
    counts: tuple[int, int, float],
) -> PeriodicResult:
    """The answer for an accepted periodic orbit.

    Parameters
    ----------
    p : ModelParams
        The model.
    vs : VerticalSchedule
        The vertical motion.
    phi : _Map
        The section map.
    t0 : float
        :func:`time.perf_counter` at the start [s].
    found : tuple
        The fixed point (ζ, ζ', s') [-], its period [cycles] and the residual asked [-].
    accepted : tuple
        :func:`_accept`'s answer.
    counts : tuple
        Newton iterations, transient cycles and the travel s [-] over them.

    Returns
    -------
    PeriodicResult
        Status "success".
    """
    xs, n, tol = found
    n_newton, brute, s_total = counts
    r_final, mu, a, s = accepted
    ds = s / n
    return PeriodicResult(
        params=p,
        status="success",
        message=f"periodic orbit of {n} cycle(s), residual {r_final:.2e} ≤ {tol:.0e}, "
        f"|μ|max = {abs(mu[0]):.6f}",
        delta_s=ds,
        mode=mode_of(ds),
        period_cycles=n,
        residual=r_final,
        floquet=mu,
        stable=True,
        state=np.array([a[0], a[1], xs[0], xs[1], 0.0, xs[2]]),
        n_newton=n_newton,
        transient_cycles=brute,
        transient_s=s_total,
        **_spent(vs, phi, t0),
    )


def _not_converged(
    p: ModelParams,
    vs: VerticalSchedule,
    phi: _Map,
    t0: float,
    best: tuple[float, int],
    max_period: int,
    counts: tuple[int, int, float],
) -> PeriodicResult:
    """The answer when the cycle budget is spent with no stable orbit accepted.

    Parameters
    ----------
    p : ModelParams
        The model.
    vs : VerticalSchedule
        The vertical motion.
    phi : _Map
        The section map.
    t0 : float
        :func:`time.perf_counter` at the start [s].
    best : tuple of (float, int)
        The smallest residual found [-] and its period [cycles].
    max_period : int
        The longest period tried, in vertical periods.
    counts : tuple
        Newton iterations, transient cycles and the travel s [-] over them.

    Returns
    -------
    PeriodicResult
        Status "not_converged".
    """
    kv = vs.period
    n_newton, brute, s_total = counts
    return PeriodicResult.failure(
        p,
        "not_converged",
        f"no stable periodic orbit of period ≤ {max_period * kv} cycles found within "
        f"{brute} cycles (best residual {best[0]:.2e} for period {best[1]}); the "
        "motion may be quasi-periodic or growing (near a·ϖ² = 1); try a larger "
        "max_cycles or max_period",
        n_newton=n_newton,
        transient_cycles=brute,
        transient_s=s_total,
        residual=best[0],
        **_spent(vs, phi, t0),
    )


def _periodic_orbit(
    p: ModelParams, tol: float, max_cycles: int, max_period: int, transient: int
) -> PeriodicResult:
    """The search of :func:`periodic_orbit` (its arguments, checked).

    The vertical motion first (:class:`VerticalSchedule`), the transient from rest
    (:func:`_from_rest`), then chunks of brute-force iteration, each followed by Newton
    for every period up to ``max_period`` vertical periods (:func:`_newton_period`,
    :func:`_shortest_period`, :func:`_accept`).

    Returns
    -------
    PeriodicResult
        The first stable periodic orbit, or why there is none.
    """
    t0 = time.perf_counter()
    k = phase_table(p)
    try:
        vs = VerticalSchedule(p.varpi, horizon=1000, zeta_v=p.zeta_v, restitution=p.restitution)
    except VerticalSearchError as exc:
        return PeriodicResult.failure(
            p, "failed", f"vertical motion: {exc}", elapsed_s=time.perf_counter() - t0
        )
    if vs.period is None:
        return PeriodicResult.failure(
            p, "not_driven", not_driven_message(p, vs.n_prefix), **_spent(vs, None, t0)
        )
    frac = vs.contact_fraction()
    if frac <= ROUND_OFF_SCALE:  # contact recurs, but below round-off of the cycle
        return PeriodicResult.failure(
            p, "not_driven", not_driven_message(p, vs.n_prefix, frac), **_spent(vs, None, t0)
        )
    kv = vs.period
    assert vs.first_end is not None
    m0 = vs.first_end + 1
    phi = _Map(k, vs, m0)
    # From rest to the first periodic cycle, then `transient` more (multiples of k_v).
    start = _from_rest(p, vs, phi, max_cycles, t0)
    if isinstance(start, PeriodicResult):
        return start
    x, s_total = start
    brute = m0
    chunk = max(kv, (transient // kv) * kv)
    n_newton = 0
    accelerated: set[int] = set()
    best: tuple[float, int] = (math.inf, kv)
    while True:
        try:
            x, s_chunk = phi(x, chunk)
            s_total += s_chunk
        except (CycleFailure, RuntimeError) as exc:
            why = f"brute-force iteration failed after {brute} cycles: {exc}"
            return PeriodicResult.failure(p, "failed", why, **_spent(vs, phi, t0))
        brute += chunk
        if not np.all(np.isfinite(x)):
            why = f"state became non-finite after {brute} cycles"
            return PeriodicResult.failure(p, "failed", why, **_spent(vs, phi, t0))
        for j in range(1, max_period + 1):
            xs, r, s, it = _newton_period(phi, x, j * kv, tol, accelerated)
            n_newton += it
            if r < best[0]:
                best = (r, j * kv)
            if r > tol:
                continue
            xs, r, s, n, it = _shortest_period(phi, (xs, r, s), j, kv, tol)
            n_newton += it
            accepted = _accept(phi, vs, xs, n, tol)
            if accepted is None:
                continue
            found = (xs, n, tol)
            return _orbit(p, vs, phi, t0, found, accepted, (n_newton, brute, s_total))
        if brute >= max_cycles:
            counts = (n_newton, brute, s_total)
            return _not_converged(p, vs, phi, t0, best, max_period, counts)
        chunk = min(2 * chunk, max(kv, ((max_cycles - brute) // kv) * kv))


def _measure_growth(
    phi: _Map, x: np.ndarray, bound: float, kv: int, window: int
) -> tuple[float, int, float, float] | None:
    """Check a proven per-cycle fall of ζ by iterating the map.

    Iterate about ``window`` cycles (at least ``kv``) from ``x`` in steps of the vertical
    period ``kv``; return (mean fall of ζ per cycle [-], cycles, final amplitude
    sqrt(ζ² + (ζ'/ϖ)²) [-], s gained [-]) when every step's fall is at least ``kv`` times
    the proven per-cycle ``bound`` (up to round-off), else None (the bound is not borne
    out, e.g. a solver defect: then the normal search decides).
    """
    varpi = float(phi.c["varpi"][0])
    z0 = float(x[0])
    steps = max(1, window // kv)
    s_total = 0.0
    try:
        for _ in range(steps):
            z_prev = float(x[0])
            x, s = phi(x, kv)
            s_total += s
            if z_prev - float(x[0]) < kv * bound - 1e-9 * max(1.0, abs(z_prev)):
                return None
    except (CycleFailure, RuntimeError):
        return None
    if not np.all(np.isfinite(x)):
        return None
    n = steps * kv
    return (z0 - float(x[0])) / n, n, math.hypot(float(x[0]), float(x[1]) / varpi), s_total


def _unbounded_message(
    p: ModelParams, bound: float, rate: float, window: int, amp: float, cycles: int
) -> str:
    """What grows, why, by how much, and what to try (status "unbounded")."""
    ak = p.alpha * p.kappa
    return (
        f"unbounded tangential motion: free-flight tangential resonance a·ϖ² = 1 with "
        f"a = α = {p.alpha:g} at ϖ = {p.varpi:g} (α·ϖ² = {p.alpha * p.varpi**2:.12g}; stick "
        f"has a = α(1 + 1/β) = {p.alpha * (1 + 1 / p.beta):g}). Contact friction cancels at "
        f"most the fraction ακ/2 = {ak / 2:g} < 1 of the resonant drive, so no periodic "
        f"orbit exists: "
        f"ζ at the section falls by ≥ π(1 − ακ/2) = {bound:.6g} per cycle (proven); "
        f"measured {rate:.6g} per cycle over {window} cycles, amplitude {amp:.4g} "
        f"after {cycles} cycles. Move ϖ or α away from the resonance (α·ϖ² ≠ 1, "
        f"e.g. by a few %)"
    )
