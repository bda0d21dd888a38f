"""Settling from rest: how long until the slider shows its periodic speed (unit-free).

The periodic Δs is what a device shows only after it settles (docs/MODEL.md,
"Slider": settling can take from a few hundred to about 10⁵ cycles, and near ϖ → 2
far more). :func:`settling` runs the exact transient from rest
(:func:`betvdesign.dynamics.simulate`, compiled, states only) and measures

- ``cycles_to_settle``: the first cycle m from which the running mean increment
  (s_{m+k} − s_m)/k over the orbit's period k stays within ``rtol``·|Δs*| of the
  periodic Δs* for every later simulated cycle (and for at least
  :data:`MIN_TAIL` cycles);
- ``cycles_to_cross``: the first cycle at which |s| reaches the travel range
  (in units of u·cosθ), and ``crossing_delta_s`` = s/m there, the mean increment a
  designer sees over the whole travel from rest.

The transient is extended in doubling chunks up to ``max_cycles``. When it has not
settled by then the result says so and ``settle_cycles`` is the lower bound
``simulated_cycles``. No extrapolation is offered: the slowest Floquet multiplier
describes only the last, linear stage of settling, and measured near ϖ → 2 it
under-predicts the settling of the whole transient by factors of 2 to 25
(tests/test_check_exact.py).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Any, ClassVar, NamedTuple, get_args

import numpy as np

from betvdesign.dynamics.result import SettlingStatus, SolverResult
from betvdesign.dynamics.solver import simulate
from betvdesign.model.domain import TRAVEL_HORIZON
from betvdesign.model.params import ModelParams

#: Settled means within this fraction of the periodic Δs [-].
SETTLE_RTOL = 0.01
#: Cycles within tolerance needed after the settling cycle before it is accepted.
MIN_TAIL = 32
#: First transient chunk (the cap on simulated cycles is the check's horizon,
#: :data:`betvdesign.model.domain.TRAVEL_HORIZON`).
FIRST_CHUNK = 512


@dataclass(frozen=True, kw_only=True)
class Settling(SolverResult):
    """Settling and crossing from rest (all counts in actuation cycles).

    Attributes
    ----------
    status : SettlingStatus
        "settled" (within ``rtol`` of the periodic Δs for the rest of the run, the
        success word), "not_settled" (not within ``simulated_cycles``, a lower bound on
        settling) or "failed" (the transient itself failed; ``message`` says why)
        (:data:`SettlingStatus`); with the other fields of :class:`SolverResult`
        (``n_cycles``: the cycles simulated from rest, ``n_events`` and ``n_root_evals``
        of the transient).
    cycles_to_settle : int or None
        First cycle from which the running mean increment stays within ``rtol`` of the
        periodic Δs (None: not settled).
    cycles_to_cross : int or None
        First cycle at which |s| reaches the travel range (None: not reached or not
        asked).
    crossing_delta_s : float or None
        s/m at that cycle [-, units of u·cosθ]: the mean increment over the whole travel
        from rest.
    rtol : float
        Settled means within this fraction of the periodic Δs [-].
    """

    STATUSES: ClassVar[tuple[str, ...]] = get_args(SettlingStatus)
    SUCCESS: ClassVar[str] = "settled"

    status: SettlingStatus
    cycles_to_settle: int | None
    cycles_to_cross: int | None
    crossing_delta_s: float | None
    rtol: float = SETTLE_RTOL

    @property
    def settled(self) -> bool:
        """True when the slider settled (``status`` "settled": :attr:`success`)."""
        return self.success

    @property
    def simulated_cycles(self) -> int:
        """The cycles simulated from rest [-] (``n_cycles``)."""
        return self.n_cycles

    @property
    def settle_cycles(self) -> float:
        """Measured settling cycles, else their lower bound (the cycles simulated)."""
        if self.cycles_to_settle is not None:
            return float(self.cycles_to_settle)
        return float(self.simulated_cycles)

    def as_dict(self) -> dict[str, Any]:
        """The fields a report shows (JSON-friendly)."""
        return {
            "status": self.status,
            "message": self.message,
            "cycles_to_settle": self.cycles_to_settle,
            "cycles_to_cross": self.cycles_to_cross,
            "crossing_delta_s": self.crossing_delta_s,
            "simulated_cycles": self.simulated_cycles,
            "rtol": self.rtol,
        }


class _FromRest(NamedTuple):
    """The transient from rest of :func:`_from_rest`.

    ``s``: the travel [-] at every cycle end (s[0] = 0); ``done``: cycles simulated;
    ``settle``, ``cross``: the cycle the running mean settles from and the one the
    travel range is crossed at (None: not within ``done``); counters of the solver;
    ``failure``: the solver's message when a chunk failed (``s`` then ends before it,
    ``failed_at``: the cycles it reached).
    """

    s: np.ndarray
    done: int
    settle: int | None
    cross: int | None
    n_events: int
    n_root_evals: int
    failure: str | None = None
    failed_at: int = 0


def _from_rest(
    p: ModelParams, k: int, target: float | None, tol: float, travel_s: float, max_cycles: int
) -> _FromRest:
    """Simulate from rest in doubling chunks until settled (and crossed) or at the cap.

    Parameters
    ----------
    p : ModelParams
        The model.
    k : int
        The orbit's period [cycles].
    target : float or None
        The periodic Δs* [-]; None: no periodic answer, the run stops once it crosses.
    tol : float
        Settled means within ``tol`` of Δs* [-].
    travel_s : float
        Travel range [-]; inf: no crossing asked.
    max_cycles : int
        Cap on the cycles simulated [-].

    Returns
    -------
    _FromRest
        The travel at every cycle end, where it settles and crosses, the counters.
    """
    s_all = [np.zeros(1)]
    state = None
    done, chunk = 0, FIRST_CHUNK
    n_events = n_root_evals = 0
    if math.isfinite(travel_s) and target is not None and target != 0.0:
        chunk = max(chunk, min(max_cycles, int(2 * travel_s / abs(target)) + 1))
    settle: int | None = None
    cross: int | None = None
    while True:
        n = min(chunk, max_cycles - done)
        tr = simulate(p, n, state0=state, log_events=False)
        n_events += tr.n_events
        n_root_evals += tr.n_root_evals
        if not tr.success:
            s = np.concatenate(s_all)
            return _FromRest(
                s, done, None, cross, n_events, n_root_evals, tr.message, done + len(tr.delta_s)
            )
        s_all.append(s_all[-1][-1] + tr.section[1:, 4] - tr.section[0, 4])
        state = tr.section[-1].copy()
        done += n
        s = np.concatenate(s_all)
        s_all = [s]
        if cross is None and math.isfinite(travel_s):
            hit = np.nonzero(np.abs(s) >= travel_s)[0]
            cross = int(hit[0]) if len(hit) else None
        settle = None if target is None else _settle_index(s, k, target, tol)
        crossed = cross is not None or not math.isfinite(travel_s)
        if (target is None and crossed) or (settle is not None and crossed):
            return _FromRest(s, done, settle, cross, n_events, n_root_evals)
        if done >= max_cycles:
            return _FromRest(s, done, settle, cross, n_events, n_root_evals)
        chunk = done  # double the horizon


def _result(run: _FromRest, rtol: float, t0: float, **fields: Any) -> Settling:
    """The :class:`Settling` of a transient from rest, with its counters.

    Parameters
    ----------
    run : _FromRest
        The transient.
    rtol : float
        The settling tolerance [-].
    t0 : float
        :func:`time.perf_counter` at the start [s].
    **fields
        The answer's other fields (status, message, cycles).

    Returns
    -------
    Settling
        The answer.
    """
    return Settling(
        rtol=rtol,
        cycles_to_cross=run.cross,
        n_events=run.n_events,
        n_root_evals=run.n_root_evals,
        elapsed_s=time.perf_counter() - t0,
        **fields,
    )


def settling(
    p: ModelParams,
    delta_s: float | None,
    *,
    period_cycles: int = 1,
    travel_s: float = math.inf,
    mu_max: float | None = None,
    rtol: float = SETTLE_RTOL,
    max_cycles: int = TRAVEL_HORIZON,
) -> Settling:
    """Transient from rest against the periodic increment: how long until it shows.

    Parameters
    ----------
    p : ModelParams
        The model.
    delta_s : float or None
        The periodic slider increment Δs* per actuation cycle [-, units of u·cosθ]
        (:attr:`PeriodicResult.delta_s <betvdesign.dynamics.result.PeriodicResult>`);
        None when there is no periodic answer: only the crossing of the travel is
        measured (status "not_settled", the run stops once it crosses).
    period_cycles : int
        The orbit's period k [cycles]; the running mean is taken over k cycles.
    travel_s : float
        Travel range [-, units of u·cosθ]; inf: no crossing asked.
    mu_max : float, optional
        Slowest Floquet modulus |μ|max [-], quoted when settling is not reached.
    rtol : float
        Settled means within ``rtol``·|Δs*| of Δs* [-].
    max_cycles : int
        Cap on the cycles simulated [-].

    Returns
    -------
    Settling
        "settled", "not_settled" (``simulated_cycles`` is then a lower bound) or "failed".

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773 (settling from rest takes
    from a few hundred to about 10⁵ cycles).
    """
    t0 = time.perf_counter()
    target = None if delta_s is None else float(delta_s)
    tol = 0.0 if target is None else rtol * abs(target)
    run = _from_rest(p, max(1, int(period_cycles)), target, tol, travel_s, max_cycles)
    s, done, settle, cross = run.s, run.done, run.settle, run.cross

    def result(status: SettlingStatus, message: str, cycles: int, **fields: Any) -> Settling:
        return _result(run, rtol, t0, status=status, message=message, n_cycles=cycles, **fields)

    if run.failure is not None:
        return result(
            "failed",
            f"transient from rest failed after {done} cycles: {run.failure}",
            run.failed_at,
            cycles_to_settle=None,
            crossing_delta_s=None,
        )
    crossing = None if cross is None else float(s[cross] / cross)
    status, message = _verdict(run, target, rtol, mu_max)
    return result(status, message, done, cycles_to_settle=settle, crossing_delta_s=crossing)


def _verdict(
    run: _FromRest, target: float | None, rtol: float, mu_max: float | None
) -> tuple[SettlingStatus, str]:
    """The status and message of a transient from rest that did not fail.

    Parameters
    ----------
    run : _FromRest
        The transient.
    target : float or None
        The periodic Δs* [-] (None: crossing only).
    rtol : float
        The settling tolerance [-].
    mu_max : float, optional
        Slowest Floquet modulus |μ|max [-], quoted when not settled.

    Returns
    -------
    tuple
        ("settled" or "not_settled", what was found).
    """
    if target is None:
        return "not_settled", "no periodic Δs to settle to: the transient from rest " + (
            f"crosses the travel after {run.cross} cycles"
            if run.cross is not None
            else f"does not cross the travel within {run.done} cycles"
        )
    if run.settle is not None:
        return "settled", (
            f"within {rtol:.0%} of the periodic Δs from cycle {run.settle} on "
            f"({run.done} cycles simulated from rest)"
        )
    shown = f" (slowest Floquet multiplier |μ| = {mu_max:.6g})" if mu_max is not None else ""
    return "not_settled", (
        f"not within {rtol:.0%} of the periodic Δs after {run.done} cycles from rest{shown}"
    )


def _settle_index(s: np.ndarray, k: int, target: float, tol: float) -> int | None:
    """First cycle from which the mean speed stays within ``tol`` of ``target``.

    First m such that |(s_{j+k} − s_j)/k − target| ≤ tol for every j ≥ m, with at
    least :data:`MIN_TAIL` such j; None when the run is too short to say.
    """
    if len(s) <= k:
        return None
    mean = (s[k:] - s[:-k]) / k
    bad = np.nonzero(np.abs(mean - target) > tol)[0]
    first = int(bad[-1]) + 1 if len(bad) else 0
    return first if len(mean) - first >= MIN_TAIL else None
