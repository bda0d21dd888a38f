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

from betvdesign.dynamics import shooting
from betvdesign.dynamics.flows import phase_table
from betvdesign.dynamics.jit import compile_note
from betvdesign.dynamics.result import PeriodicResult
from betvdesign.dynamics.solver import CycleFailure, CycleRunner
from betvdesign.dynamics.vertical import VerticalSchedule, VerticalSearchError
from betvdesign.errors import ParameterError
from betvdesign.model.domain import ROUND_OFF_SCALE, mode_of
from betvdesign.model.params import ModelParams

#: |α·ϖ² − 1| at or below which the free-flight tangential resonance counts as exact.
RESONANCE_RTOL = 1e-9
#: Cycles over which the secular growth at an exact resonance is measured.
GROWTH_WINDOW = 256


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


def _spent(vs: VerticalSchedule, count: np.ndarray | None, t0: float) -> dict[str, Any]:
    """What every answer of :func:`_periodic_orbit` carries.

    Parameters
    ----------
    vs : VerticalSchedule
        The vertical motion.
    count : numpy.ndarray or None
        The periodic map's counters [cycles, events, root evaluations] (None before it
        ran).
    t0 : float
        :func:`time.perf_counter` at the start [s].

    Returns
    -------
    dict
        The vertical motion's hits and contact fraction, the counters so far and the
        time taken [s].
    """
    cycles, events, evals = (0, 0, 0) if count is None else count.tolist()
    return dict(
        impacts_per_cycle=vs.hits_per_cycle(),
        contact_fraction=vs.contact_fraction(),
        n_cycles=cycles,
        n_events=events,
        n_root_evals=evals + vs.n_root_evals,
        elapsed_s=time.perf_counter() - t0,
    )


def _map_failure(c: np.ndarray, vs: VerticalSchedule, m0: int, n: int, x: np.ndarray) -> str:
    """Why the map over cycles m0..m0+n−1 from (ζ, ζ', s') = x failed (rare path).

    The compiled search only says that a contact could not be advanced; the same cycles
    are run again where the failure is explained (:class:`~solver.CycleRunner`).

    Returns
    -------
    str
        The failure's message.
    """
    try:
        CycleRunner(c, vs).run(m0, n, x[0], x[1], 0.0, x[2], check_finite=False)
    except (CycleFailure, RuntimeError) as exc:
        return str(exc)
    return f"a contact could not be advanced from cycle {m0}"


def _periodic_orbit(
    p: ModelParams, tol: float, max_cycles: int, max_period: int, transient: int
) -> PeriodicResult:
    """The search of :func:`periodic_orbit` (its arguments, checked).

    The vertical motion first (:class:`VerticalSchedule`: not driven, or its period), then
    the whole search in one compiled call (:func:`shooting.orbit`: the transient from
    rest, the growth at the resonance, brute force, Newton with Anderson starts, the
    shortest period, the Floquet multipliers), whose arrays make the answer here.

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
    m0 = vs.n_prefix  # the first cycle after the first contact end
    bound = resonance_growth_bound(p)
    code, x, mu, fo, io, count = shooting.orbit(
        k,
        vs.table,
        vs.impulsive,
        m0,
        kv,
        float(tol),  # one compiled signature, whatever number types the caller passed
        int(max_cycles),
        int(max_period),
        int(transient),
        math.nan if bound is None else bound,
        int(min(GROWTH_WINDOW, max_cycles - m0)),
        int(shooting.ANDERSON_BUDGET),
    )
    if code == shooting.FOUND:
        return _orbit(p, vs, t0, x, mu, fo.tolist(), io.tolist(), count, tol)
    f, i = fo.tolist(), io.tolist()
    if code == shooting.NOT_CONVERGED:
        return _not_converged(p, vs, t0, f, i, max_period, count)
    if code == shooting.UNBOUNDED:
        assert bound is not None
        return PeriodicResult.failure(
            p,
            "unbounded",
            _unbounded_message(p, bound, f[5], i[4], f[6], m0 + i[4]),
            transient_cycles=m0 + i[4],
            transient_s=f[2] + f[7],
            **_spent(vs, count, t0),
        )
    if code == shooting.FLOQUET_FAILED:
        raise CycleFailure("a contact could not be advanced (Jacobian)", m0)
    if code == shooting.REST_FAILED:
        why = f"transient from rest failed: {_map_failure(k, vs, 0, i[4], x)}"
    elif code == shooting.CHUNK_FAILED:
        why = f"brute-force iteration failed after {i[2]} cycles: " + _map_failure(
            k, vs, m0, i[4], x
        )
    else:
        why = f"state became non-finite after {i[2]} cycles"
    return PeriodicResult.failure(p, "failed", why, **_spent(vs, count, t0))


def _orbit(
    p: ModelParams,
    vs: VerticalSchedule,
    t0: float,
    xs: np.ndarray,
    mu: np.ndarray,
    f: list[float],
    i: list[int],
    count: np.ndarray,
    tol: float,
) -> PeriodicResult:
    """The answer for an accepted periodic orbit (:data:`shooting.FOUND`).

    Parameters
    ----------
    p : ModelParams
        The model.
    vs : VerticalSchedule
        The vertical motion.
    t0 : float
        :func:`time.perf_counter` at the start [s].
    xs : numpy.ndarray
        The fixed point (ζ, ζ', s') [-].
    mu : numpy.ndarray
        The multipliers' real parts, imaginary parts and moduli, (3, 3) [-].
    f, i : list
        :func:`shooting.orbit`'s floats and ints.
    count : numpy.ndarray
        The map's counters.
    tol : float
        The residual asked [-].

    Returns
    -------
    PeriodicResult
        Status "success"; the multipliers complex (real when they all are, as
        :func:`numpy.linalg.eigvals` gives them).
    """
    r_final, s, s_total, xi, xid = f[:5]
    n, n_newton, brute = i[:3]
    if any(mu[1].tolist()):  # as numpy's eigvals: real unless an imaginary part is not 0
        floquet = np.empty(3, complex)
        floquet.real, floquet.imag = mu[0], mu[1]
    else:
        floquet = mu[0].copy()
    ds = s / n
    return PeriodicResult(
        params=p,
        status="success",
        message=f"periodic orbit of {n} cycle(s), residual {r_final:.2e} ≤ {tol:.0e}, "
        f"|μ|max = {float(mu[2, 0]):.6f}",
        delta_s=ds,
        mode=mode_of(ds),
        period_cycles=n,
        residual=r_final,
        floquet=floquet,
        stable=True,
        state=np.array([xi, xid, xs[0], xs[1], 0.0, xs[2]]),
        n_newton=n_newton,
        transient_cycles=brute,
        transient_s=s_total,
        **_spent(vs, count, t0),
    )


def _not_converged(
    p: ModelParams,
    vs: VerticalSchedule,
    t0: float,
    f: list[float],
    i: list[int],
    max_period: int,
    count: np.ndarray,
) -> PeriodicResult:
    """The answer when the cycle budget is spent with no stable orbit accepted.

    Parameters
    ----------
    p : ModelParams
        The model.
    vs : VerticalSchedule
        The vertical motion.
    t0 : float
        :func:`time.perf_counter` at the start [s].
    f, i : list
        :func:`shooting.orbit`'s floats (best residual, transient travel) and ints
        (Newton iterations, transient cycles, period of the best residual).
    max_period : int
        The longest period tried, in vertical periods.
    count : numpy.ndarray
        The map's counters.

    Returns
    -------
    PeriodicResult
        Status "not_converged".
    """
    kv = vs.period
    best_r, s_total = f[0], f[2]
    n_newton, brute, best_n = i[1], i[2], i[3]
    return PeriodicResult.failure(
        p,
        "not_converged",
        f"no stable periodic orbit of period ≤ {max_period * kv} cycles found within "
        f"{brute} cycles (best residual {best_r:.2e} for period {best_n}); the "
        "motion may be quasi-periodic or growing (near a·ϖ² = 1); try a larger "
        "max_cycles or max_period",
        n_newton=n_newton,
        transient_cycles=brute,
        transient_s=s_total,
        residual=best_r,
        **_spent(vs, count, t0),
    )


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
