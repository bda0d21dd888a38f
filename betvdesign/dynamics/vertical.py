"""The head's vertical motion, exactly, and the vertical-only fast path (unit-free).

docs/MODEL.md, "Impacts and separation" and "What the model shows". The motion itself
is computed by the compiled :func:`schedule.vertical_run` (exactly periodic from the
first contact end); :class:`VerticalSchedule` holds its tables and answers "what happens
vertically in cycle m" for any m without integrating again. When no contact recurs
within the horizon (only impulsive hits, large ϖ) there is no period and the slider is
not driven.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from functools import cached_property
from typing import ClassVar, get_args

import numpy as np

from betvdesign.dynamics import schedule
from betvdesign.dynamics.jit import compile_note
from betvdesign.dynamics.result import SolverResult, VerticalStatus
from betvdesign.dynamics.search import search_failure_message
from betvdesign.errors import ParameterError
from betvdesign.model.params import normal_force_phase


class VerticalSearchError(RuntimeError):
    """The certified search for a hit did not terminate (a degenerate, non-isolated hit)."""


@dataclass(slots=True)
class VerticalCycle:
    """What the head does vertically during one actuation cycle [local time t ∈ [0, 2π/ϖ)].

    ``contact_start``: local time of the hit opening a contact (which lasts to π/ϖ),
    or None. ``impulsive``: local times of impulsive hits. ``free``: free-flight
    pieces (t_from, ξ, ξ', sin ϖt_from, cos ϖt_from) for dense output; ``xi0``,
    ``xid0``: state at t = 0 (the Poincaré section).
    """

    xi0: float
    xid0: float
    contact_start: float | None = None
    impulsive: list[float] = field(default_factory=list)
    free: list[tuple[float, float, float, float, float]] = field(default_factory=list)


class VerticalSchedule:
    """Exact vertical motion from (ξ0, ξ0') at τ = 0, cycle by cycle.

    ``table``: the distinct cycles (:data:`schedule.CYCLE_DTYPE`): cycles 0..first_end
    (the first contact end), then the ``period`` cycles after it, repeated for ever
    (``period`` None when no contact recurred within the horizon: then the table holds
    every computed cycle); ``impulsive`` and ``pieces`` the hit times and free-flight
    pieces they index. ``prefix`` / ``pattern``: the same as :class:`VerticalCycle` lists.
    """

    def __init__(
        self,
        varpi: float,
        xi0: float = 0.0,
        xid0: float = 0.0,
        horizon: int = 1000,
        *,
        zeta_v: float = 0.0,
        restitution: float = 0.0,
    ):
        if not (math.isfinite(xi0) and math.isfinite(xid0)) or xi0 < 0.0:
            raise ParameterError(f"vertical state must be finite with ξ ≥ 0, got ({xi0}, {xid0})")
        if not (zeta_v >= 0.0 and 0.0 <= restitution < 1.0):
            raise ParameterError(f"need ζ_v ≥ 0 and 0 ≤ e < 1, got {zeta_v!r}, {restitution!r}")
        self.varpi = varpi
        self.zeta_v = float(zeta_v)
        self.restitution = float(restitution)
        self.A = normal_force_phase(self.zeta_v, varpi)[1]
        self.T = 2.0 * math.pi / varpi
        self.te = math.pi / varpi
        # Tables sized for the whole run at once (at most 2·horizon + 1 cycles: the
        # horizon, then a period's search after the first contact end), up to 4096 rows;
        # past that, or with more hits than 4 per cycle, they double and the run restarts
        # (from 16 rows, a run took 3 starts on average).
        n_cyc = min(2 * int(horizon) + 2, 4096)
        n_imp = 4 * n_cyc
        while True:
            cyc = np.empty(n_cyc, schedule.CYCLE_DTYPE)
            imp = np.empty(n_imp)
            pieces = np.empty(2 * n_imp, schedule.PIECE_DTYPE)
            run = schedule.vertical_run(
                float(varpi),
                self.zeta_v,
                self.A,
                self.restitution,
                float(xi0),
                float(xid0),
                int(horizon),
                cyc,
                imp,
                pieces,
            )
            if run.code != schedule.FULL:
                break
            n_cyc, n_imp = 2 * n_cyc, 2 * n_imp
        if run.code == schedule.FAILED:
            raise VerticalSearchError(search_failure_message(run.H))
        if run.code == schedule.CHATTERED:
            raise VerticalSearchError(
                f"a chattering sequence (e = {restitution:g}) did not accumulate within "
                f"{schedule.MAX_BOUNCES} hits in cycle {run.cycles - 1} (local time "
                f"{run.H:.6g}): its error bound never fell below round-off; try a smaller "
                "restitution or check ϖ"
            )
        self.table = cyc[: run.cycles]
        self.impulsive = imp[: run.hits]
        self.pieces = pieces[: run.pieces]
        self.first_end: int | None = None if run.first_end < 0 else int(run.first_end)
        self.period: int | None = None if run.period < 0 else int(run.period)
        self.n_root_evals = int(run.evals)
        self.n_prefix = int(run.cycles) if self.period is None else int(run.first_end) + 1

    # -- queries ------------------------------------------------------------------
    def _cycle(self, i: int) -> VerticalCycle:
        r = self.table[i]
        tc = float(r["tc"])
        i0, ni, f0, nf = (int(r[k]) for k in ("imp_start", "imp_count", "free_start", "free_count"))
        return VerticalCycle(
            float(r["xi0"]),
            float(r["xid0"]),
            None if tc != tc else tc,
            [float(t) for t in self.impulsive[i0 : i0 + ni]],
            [tuple(float(x) for x in p) for p in self.pieces[f0 : f0 + nf]],  # type: ignore[misc]
        )

    @cached_property
    def prefix(self) -> list[VerticalCycle]:
        """Cycles 0..first_end (or every computed cycle when there is no period)."""
        return [self._cycle(i) for i in range(self.n_prefix)]

    @cached_property
    def pattern(self) -> list[VerticalCycle]:
        """The period's cycles after the first contact end (empty: no period)."""
        return [self._cycle(i) for i in range(self.n_prefix, len(self.table))]

    def row(self, m: np.ndarray) -> np.ndarray:
        """Row of ``table`` of cycles m (int array, 0-based, increasing).

        Parameters
        ----------
        m : numpy.ndarray
            Cycles (int, 0-based, increasing).

        Returns
        -------
        numpy.ndarray
            Their rows (cycles past the prefix map into the first period).

        Raises
        ------
        IndexError
            For a cycle beyond the computed horizon of a motion with no period.
        """
        k = self.n_prefix
        if m.size and m[-1] >= k:
            if self.period is None:
                raise IndexError(f"cycle {int(m[-1])} beyond the computed vertical horizon")
            m = schedule.cycle_rows(m, k, self.period)
        return m

    def cycle(self, m: int) -> VerticalCycle:
        """Vertical events of cycle m (0-based).

        Parameters
        ----------
        m : int
            The cycle (0-based).

        Returns
        -------
        VerticalCycle
            Its section state, hits and contact.
        """
        return self._cycle(int(self.row(np.array([m]))[0]))

    def arrays(self, m0: int, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Cycles m0..m0+n−1 of the vertical motion as arrays.

        Cycles m0..m0+n−1 as arrays: section state ξ0, ξ0' [-], contact-opening local
        time [-] (NaN: none) and number of impulsive hits.

        Parameters
        ----------
        m0 : int
            First cycle (0-based).
        n : int
            Number of cycles.

        Returns
        -------
        tuple of numpy.ndarray
            ξ0, ξ0' [-], contact-opening time [-] and impulsive hits, per cycle.
        """
        rows = self.table[self.row(np.arange(m0, m0 + n))]
        return rows["xi0"], rows["xid0"], rows["tc"], rows["imp_count"]

    def gap(self, m: np.ndarray, t: np.ndarray) -> np.ndarray:
        """(ξ, ξ') [-] at local times t of cycles m, shape (n, 2) (0 during contact).

        Parameters
        ----------
        m : numpy.ndarray
            Cycles (int, 0-based).
        t : numpy.ndarray
            Local times [-].

        Returns
        -------
        numpy.ndarray
            (ξ, ξ') [-], shape (n, 2).
        """
        out = np.empty((t.size, 2))
        rows = self.table[self.row(m)]
        for j in range(t.size):
            r = rows[j]
            out[j] = schedule.gap_at(
                self.varpi,
                self.zeta_v,
                self.A,
                r["tc"],
                self.pieces,
                r["free_start"],
                r["free_count"],
                t[j],
            )
        return out

    def period_rows(self) -> np.ndarray:
        """The table's rows of one period (or of the whole horizon when there is none)."""
        return self.table[self.n_prefix :] if self.period else self.table[: self.n_prefix]

    @cached_property
    def _per_period(self) -> tuple[float, float]:
        first, last = (self.n_prefix, len(self.table)) if self.period else (0, self.n_prefix)
        return schedule.period_rates(self.table, first, last, self.T, self.te)

    def n_hits(self) -> int:
        """Hits located in the cycles of ``table``.

        Hits (contact starts + impulsive) located in the cycles of ``table`` (the
        prefix and one period, or the whole horizon when there is none).
        """
        rows = self.table
        return int(rows["imp_count"].sum()) + int(np.count_nonzero(~np.isnan(rows["tc"])))

    def hits_per_cycle(self) -> float:
        """Hits (contact starts + impulsive) per cycle over one period (or the horizon)."""
        return self._per_period[0]

    def contact_fraction(self) -> float:
        """Fraction of time in contact over one period (or the computed horizon)."""
        return self._per_period[1]

    def chattering_into_contact(self) -> int:
        """Rebounds per cycle of a period-1 motion closing into its contact.

        Rebounds per cycle of a period-1 motion whose only impulsive hits are the
        chattering sequence that closes into its contact (restitution, docs/damping.md
        §4): every hit before the contact start lies where N > 0, so it belongs to that
        one sequence. 0 when the motion is not of that kind.
        """
        if self.restitution == 0.0 or self.period != 1:
            return 0
        (row,) = self.period_rows()
        tc, i0, n = float(row["tc"]), int(row["imp_start"]), int(row["imp_count"])
        if n == 0 or tc != tc or not np.all(self.impulsive[i0 : i0 + n] < tc):
            return 0
        return n


@dataclass(frozen=True, kw_only=True)
class VerticalResult(SolverResult):
    """Vertical-only answer (no slider): MODEL.md "Vertical motion".

    Attributes
    ----------
    varpi : float
        ϖ [-].
    status : VerticalStatus
        "success" (periodic) or "not_periodic" (:data:`VerticalStatus`); with the other
        fields of :class:`SolverResult` (``n_cycles``: cycles computed, up to the end of
        the first period; ``n_events``: the hits located in them).
    regime : str
        "single-impact" (the design window: one hit per cycle with finite contact),
        "chattering-contact" (one contact per cycle, reached by a chattering sequence of
        rebounds: restitution), "multi-impact", "period-k", or "impulsive-only".
    period_cycles : int or None
        Cycles between contacts once periodic (None: no contact recurs within
        ``n_cycles``).
    hits_per_cycle : float
        Contact-opening and impulsive hits per cycle [-].
    impulsive_per_cycle : float
        Impulsive hits per cycle [-].
    contact_fraction : float
        Fraction of the time in contact [-].
    contact_phase : float or None
        ϖτ at the contact-opening hit [rad].
    """

    STATUSES: ClassVar[tuple[str, ...]] = get_args(VerticalStatus)

    status: VerticalStatus
    varpi: float
    regime: str
    period_cycles: int | None
    hits_per_cycle: float
    impulsive_per_cycle: float
    contact_fraction: float
    contact_phase: float | None

    @classmethod
    def failure(cls, varpi: float, message: str) -> VerticalResult:
        """The answer when the vertical motion could not be computed.

        Parameters
        ----------
        varpi : float
            ϖ [-] asked for.
        message : str
            What failed.

        Returns
        -------
        VerticalResult
            Status "failed", regime "failed", no period, nan rates.
        """
        nan = float("nan")
        return cls(
            status="failed",
            message=message,
            varpi=varpi,
            regime="failed",
            period_cycles=None,
            hits_per_cycle=nan,
            impulsive_per_cycle=nan,
            contact_fraction=nan,
            contact_phase=None,
        )


def vertical_motion(
    varpi: float, *, zeta_v: float = 0.0, restitution: float = 0.0, max_cycles: int = 1000
) -> VerticalResult:
    """Vertical motion from rest (the "model no more than a scene needs" fast path).

    The head's normal motion does not depend on the slider (MODEL.md "Vertical
    motion"): it is computed exactly until it repeats, and classified.

    Parameters
    ----------
    varpi : float
        ϖ [-] (> 0, finite).
    zeta_v : float
        Normal damping ratio ζ_v [-] (0: the paper's model; docs/damping.md).
    restitution : float
        Coefficient of restitution e [-] of normal impacts (0: plastic).
    max_cycles : int
        Horizon [cycles] within which a contact must recur.

    Returns
    -------
    VerticalResult
        "success" with the regime, or "not_periodic" (impulsive hits only)
        (:data:`~betvdesign.dynamics.result.VerticalStatus`).

    Raises
    ------
    ParameterError
        For a ϖ that is not a finite number > 0, or invalid ζ_v or e.
    VerticalSearchError
        When the certified hit search does not terminate or a chattering sequence does
        not accumulate.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773 (vertical regimes against ϖ).
    Budd & Dux, Phil. Trans. R. Soc. A 347 (1994), doi:10.1098/rsta.1994.0044 (chattering, with
    restitution).
    """
    return vertical_motion_schedule(
        varpi, zeta_v=zeta_v, restitution=restitution, max_cycles=max_cycles
    )[0]


def _not_periodic(vs: VerticalSchedule, v: float, max_cycles: int, el: float) -> VerticalResult:
    """The answer for a motion whose contact never recurs within ``max_cycles``.

    Parameters
    ----------
    vs : VerticalSchedule
        The schedule (no period).
    v : float
        ϖ [-].
    max_cycles : int
        The horizon searched [cycles].
    el : float
        Time taken [s].

    Returns
    -------
    VerticalResult
        Status "not_periodic", regime "impulsive-only".
    """
    imp = vs.hits_per_cycle()
    return VerticalResult(
        varpi=v,
        status="not_periodic",
        message=f"no contact recurred within {max_cycles} cycles: hits are impulsive only "
        "and the slider is not driven ("
        + (
            f"restitution e = {vs.restitution:g}: the rebounds never settle into contact "
            "before the normal force falls to zero; "
            if vs.restitution > 0.0
            else ""
        )
        + "MODEL.md: ϖ beyond about 2); increase max_cycles to look further",
        regime="impulsive-only",
        period_cycles=None,
        hits_per_cycle=imp,
        impulsive_per_cycle=imp,
        contact_fraction=0.0,
        contact_phase=None,
        n_cycles=vs.n_prefix,
        n_events=vs.n_hits(),
        n_root_evals=vs.n_root_evals,
        elapsed_s=el,
    )


def _periodic(vs: VerticalSchedule, v: float, el: float) -> VerticalResult:
    """The answer for a periodic vertical motion: its regime, hits and contact.

    Parameters
    ----------
    vs : VerticalSchedule
        The schedule (periodic).
    v : float
        ϖ [-].
    el : float
        Time taken [s].

    Returns
    -------
    VerticalResult
        Status "success" with the regime: period-k, chattering-contact, multi-impact or
        single-impact.
    """
    k = vs.period
    imp = int(vs.period_rows()["imp_count"].sum()) / k
    hits = vs.hits_per_cycle()
    chatter = vs.chattering_into_contact()
    if k > 1:
        regime = f"period-{k}"
    elif chatter:
        regime = "chattering-contact"
    elif hits > 1.0:
        regime = "multi-impact"
    else:
        regime = "single-impact"
    tcs = vs.period_rows()["tc"]
    tc = float(tcs[~np.isnan(tcs)][0])
    return VerticalResult(
        varpi=v,
        status="success",
        message=f"vertical motion periodic with {k} cycle(s) per period"
        + (
            f"; its contact is reached by a chattering sequence of {chatter} rebound(s)"
            if chatter
            else ""
        ),
        regime=regime,
        period_cycles=k,
        hits_per_cycle=hits,
        impulsive_per_cycle=imp,
        contact_fraction=vs.contact_fraction(),
        contact_phase=v * tc,
        n_cycles=(vs.first_end or 0) + 1 + k,
        n_events=vs.n_hits(),
        n_root_evals=vs.n_root_evals,
        elapsed_s=el,
    )


def vertical_motion_schedule(
    varpi: float, *, zeta_v: float = 0.0, restitution: float = 0.0, max_cycles: int = 1000
) -> tuple[VerticalResult, VerticalSchedule]:
    """:func:`vertical_motion` and the schedule it was read from.

    Parameters
    ----------
    varpi, zeta_v, restitution, max_cycles
        As in :func:`vertical_motion`.

    Returns
    -------
    tuple of (VerticalResult, VerticalSchedule)
        The answer and its schedule, for further analysis (e.g. the hit phases of
        impulsive-only motion) without computing the motion again.

    Raises
    ------
    ParameterError, VerticalSearchError
        As :func:`vertical_motion`.
    """
    try:
        v = float(varpi)
    except (TypeError, ValueError):
        raise ParameterError(f"varpi must be a number, got {varpi!r}") from None
    if not math.isfinite(v) or v <= 0.0:
        raise ParameterError(f"varpi must be finite and > 0, got {varpi!r}")
    t0 = time.perf_counter()
    vs: VerticalSchedule = compile_note(  # type: ignore[assignment]
        "vertical_motion",
        lambda: VerticalSchedule(v, horizon=max_cycles, zeta_v=zeta_v, restitution=restitution),
    )
    el = time.perf_counter() - t0
    if vs.period is None:
        return _not_periodic(vs, v, max_cycles, el), vs
    return _periodic(vs, v, el), vs
