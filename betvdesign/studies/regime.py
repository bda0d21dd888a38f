"""Vertical regime diagram: impact period and contact fraction over ϖ ∈ (0, 10].

The head's vertical motion does not depend on the slider ("model no more than
a scene needs"): this study uses only the exact vertical model
(``dynamics.vertical``), never the slider. Per ϖ it records the solver's
impact period (cycles between contact ends), hits and impulsive hits per
cycle, and contact fraction, after transients, and labels the point
(docs/MODEL.md, "What the model shows"):

* ``period-1``: one hit per cycle with finite contact (the design window);
* ``multi-hit``: several hits per cycle (small ϖ);
* ``period-k``: one contact every k ≥ 2 cycles (k = 2: period doubled);
* ``impulsive``: no finite contact recurs, the hits are impulsive (zero
  duration) and repeat periodically; the slider is not driven;
* ``aperiodic``: impulsive hits that repeat with no period found.

The overview merges periods longer than :data:`LONG_PERIOD` cycles into
``aperiodic`` (at a grid resolution they are indistinguishable from it); the
full intervals keep every label.

Impulsive-only motion is a circle map: an impulsive hit leaves ξ = ξ' = 0, so
the motion after it depends only on the hit's phase in the cycle. Its period
is found from the hit phases over the second half of the horizon (after
transients): period p hits if every phase recurs p hits later to 1e-9 of a
cycle. Contiguous runs of one label are reported as ϖ intervals. With restitution
(e > 0) a hit is a rebound and that argument fails: the period found from the phases
must then also return the section state (ξ, ξ') to :data:`STATE_RTOL`.

Normal damping ζ_v and restitution e (MODEL.md, "Beyond the paper's idealisation")
enter the vertical model; ζ_h and the slider do not, so the study takes those two
only (fixed over the sweep; 0: the paper's model, the study of before they existed).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Unpack

import numpy as np

from betvdesign.errors import UsageError
from betvdesign.studies.engine.grid import Grid
from betvdesign.studies.engine.runner import RunArgs, Study, StudyRun, run_study
from betvdesign.studies.points import solver_error
from betvdesign.studies.terms import Terms, model_statement

if TYPE_CHECKING:
    from betvdesign.dynamics.vertical import VerticalSchedule

#: Relative (to one cycle) tolerance for two hit phases to count as equal.
PHASE_RTOL = 1e-9
#: Periods longer than this many cycles are shown as aperiodic in the overview.
LONG_PERIOD = 8
#: Longest impulsive-hit period (in hits) searched for.
MAX_HIT_PERIOD = 64
#: With restitution: section states k cycles apart must agree to this (relative to 1).
STATE_RTOL = 1e-9
#: The vertical model's optional terms (ζ_h acts on the tangential motion only).
VERTICAL_TERMS = ("zeta_v", "restitution")

COLUMNS: dict[str, type] = {
    "key": int,
    "varpi": float,
    "status": str,
    "label": str,
    "regime": str,
    "period_cycles": int,
    "hits_per_cycle": float,
    "impulsive_per_cycle": float,
    "contact_fraction": float,
    "message": str,
}


def impulsive_period(vs: VerticalSchedule) -> tuple[int | None, float]:
    """Period and hit rate of impulsive-only motion.

    Uses the hit phases of the second half of the schedule's cycles (see module doc):
    an impulsive hit leaves ξ = ξ' = 0 in the model of Shin et al. [1]_, so the motion
    after it depends on the hit's phase in the cycle T = 2π/ϖ only.

    Parameters
    ----------
    vs : VerticalSchedule
        The vertical motion's cycles
        (:func:`betvdesign.dynamics.vertical.vertical_motion_schedule`).

    Returns
    -------
    tuple of (int or None, float)
        The period [cycles] (None: none found) and the impulsive hits per cycle [-].

    References
    ----------
    .. [1] K. Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773
    """
    T = 2.0 * math.pi / vs.varpi
    # the hits of the second half of the prefix cycles, in order, read from the
    # schedule's arrays (no per-cycle Python objects)
    n = vs.n_prefix
    half = n // 2
    rows = vs.table[half:n]
    counts = rows["imp_count"].astype(np.intp)
    n_hits = int(counts.sum())
    n_cyc = max(1, n - half)
    rate = n_hits / n_cyc
    if n_hits < 4:
        return None, rate
    first = np.cumsum(counts) - counts  # each cycle's first hit among the selected
    index = np.repeat(rows["imp_start"].astype(np.intp) - first, counts) + np.arange(n_hits)
    phase = vs.impulsive[index] / T
    cycle = np.repeat(np.arange(half, n), counts)
    for p in range(1, min(MAX_HIT_PERIOD, n_hits // 2) + 1):
        d = np.abs(phase[p:] - phase[:-p])
        d = np.minimum(d, 1.0 - d)
        if np.all(d <= PHASE_RTOL):
            k = np.unique(cycle[p:] - cycle[:-p])
            if k.size == 1 and (vs.restitution == 0.0 or _state_recurs(vs, int(k[0]))):
                return int(k[0]), rate
    return None, rate


def _state_recurs(vs: VerticalSchedule, k: int) -> bool:
    """Whether the normal section state of the schedule recurs k cycles later.

    Whether the section state (ξ, ξ') of every cycle of the second half of the
    schedule recurs k cycles later (to :data:`STATE_RTOL`): with rebounds (e > 0) the
    state after a hit is not fixed by its phase, so the phases alone prove no period.
    """
    rows = vs.table[vs.n_prefix // 2 : vs.n_prefix]
    if len(rows) <= k:
        return False
    state = np.column_stack((rows["xi0"], rows["xid0"])).astype(float)
    return bool(np.all(np.abs(state[k:] - state[:-k]) <= STATE_RTOL * (1.0 + np.abs(state[:-k]))))


def regime_point(task: Mapping[str, Any]) -> dict[str, Any]:
    """Worker: vertical-only motion at one ϖ (plain data in and out).

    Parameters
    ----------
    task : mapping
        ``key``, ``varpi`` ϖ [-], ``max_cycles`` (the horizon [cycles]) and optionally
        ``zeta_v`` ζ_v and ``restitution`` e [-].

    Returns
    -------
    dict
        One row of :func:`regime_columns`: status, label (see module doc), the vertical
        solver's regime, period [cycles], hits and impulsive hits per cycle [-], contact
        fraction [-] and message; a solve that raises gives status "error".
    """
    from betvdesign.dynamics.vertical import vertical_motion_schedule

    terms = {n: float(task[n]) for n in VERTICAL_TERMS if task.get(n)}
    row: dict[str, Any] = dict.fromkeys(regime_columns(bool(terms)))
    row.update(key=task["key"], varpi=task["varpi"])
    if terms:
        row.update(dict.fromkeys(VERTICAL_TERMS, 0.0) | terms)
    try:
        r, vs = vertical_motion_schedule(
            task["varpi"],
            zeta_v=task.get("zeta_v", 0.0),
            restitution=task.get("restitution", 0.0),
            max_cycles=task["max_cycles"],
        )
    except Exception as exc:  # a failed point is recorded and listed, never dropped
        row.update(status="error", label="error", message=solver_error(exc))
        return row
    row.update(
        status=r.status,
        regime=r.regime,
        period_cycles=r.period_cycles,
        hits_per_cycle=float(r.hits_per_cycle),
        impulsive_per_cycle=float(r.impulsive_per_cycle),
        contact_fraction=float(r.contact_fraction),
        message=r.message,
    )
    if r.period_cycles is not None:
        k = r.period_cycles
        row["label"] = (
            f"period-{k}" if k > 1 else ("multi-hit" if r.regime == "multi-impact" else "period-1")
        )
        return row
    k, rate = impulsive_period(vs)  # the schedule already computed, not a second run
    row.update(period_cycles=k, impulsive_per_cycle=rate, hits_per_cycle=rate)
    if rate == 0.0:
        row["label"] = "no-impact"
    else:
        row["label"] = "impulsive" if k is not None else "aperiodic"
    return row


def regime_columns(with_terms: bool) -> dict[str, type]:
    """The result columns of the regime study.

    Parameters
    ----------
    with_terms : bool
        Whether ζ_v or e is set.

    Returns
    -------
    dict of str to type
        :data:`COLUMNS`, with ``zeta_v`` and ``restitution`` after ϖ when a term is set.
    """
    if not with_terms:
        return dict(COLUMNS)
    head = {"key": int, "varpi": float} | dict.fromkeys(VERTICAL_TERMS, float)
    return head | COLUMNS


def regime_study(
    varpi: Sequence[float],
    *,
    max_cycles: int = 400,
    zeta_v: float = 0.0,
    restitution: float = 0.0,
) -> Study:
    """One vertical-only solve per ϖ (ascending).

    Parameters
    ----------
    varpi : sequence of float
        Normalised actuation frequencies ϖ = ω·sqrt(m/k_v) [-] (> 0).
    max_cycles : int
        Horizon of each solve [cycles] (>= 4).
    zeta_v : float
        Normal damping ratio ζ_v [-], fixed (0: undamped).
    restitution : float
        Coefficient of restitution e [-], fixed (0: plastic impacts; both 0: the paper's
        model).

    Returns
    -------
    Study
        One task per ϖ, worker :func:`regime_point`.

    Raises
    ------
    UsageError
        A non-positive ϖ or ``max_cycles`` < 4.
    """
    terms = Terms(zeta_v=zeta_v, restitution=restitution)
    fixed = {n: getattr(terms, n) for n in VERTICAL_TERMS} if not terms.ideal else {}
    v = np.asarray(varpi, dtype=float)
    if np.any(~(v > 0)):
        raise UsageError("varpi: values must be > 0")
    if max_cycles < 4:
        raise UsageError(f"--max-cycles must be >= 4, got {max_cycles}")
    grid = Grid({"varpi": np.sort(v)})
    tasks = [{"key": p.key, **p.values, **fixed, "max_cycles": max_cycles} for p in grid]
    params = {"grid": grid.as_dict(), "max_cycles": max_cycles, **fixed}  # keys the store
    return Study("regime", regime_columns(bool(fixed)), params, tasks, regime_point)


@dataclass(frozen=True)
class Interval:
    """A run of grid points sharing one label: ϖ from ``lo`` to ``hi`` [-]."""

    label: str
    lo: float
    hi: float
    points: int

    def as_dict(self) -> dict[str, Any]:
        """The interval as plain data.

        Returns
        -------
        dict
            ``label``, ``from`` and ``to`` (ϖ [-]) and ``points``.
        """
        return {"label": self.label, "from": self.lo, "to": self.hi, "points": self.points}


def coarse_label(label: str) -> str:
    """Label for the overview.

    Parameters
    ----------
    label : str
        A point's label.

    Returns
    -------
    str
        ``label``, except long periods (k > :data:`LONG_PERIOD`) that join ``aperiodic``.
    """
    if label.startswith("period-") and int(label.split("-")[1]) > LONG_PERIOD:
        return "aperiodic"
    return label


def intervals(rows: Sequence[Mapping[str, Any]], *, coarse: bool = False) -> list[Interval]:
    """Contiguous runs of equal labels along ϖ.

    Parameters
    ----------
    rows : sequence of mapping
        The study's rows (``varpi``, ``label``).
    coarse : bool
        Label the overview's way (:func:`coarse_label`).

    Returns
    -------
    list of Interval
        The runs in ascending ϖ.
    """
    out: list[Interval] = []
    for r in sorted(rows, key=lambda r: r["varpi"]):
        label = coarse_label(r["label"]) if coarse else r["label"]
        if out and out[-1].label == label:
            last = out[-1]
            out[-1] = Interval(last.label, last.lo, r["varpi"], last.points + 1)
        else:
            out.append(Interval(label, r["varpi"], r["varpi"], 1))
    return out


def summarise(rows: Sequence[Mapping[str, Any]], terms: Terms | None = None) -> dict[str, Any]:
    """Intervals, counts per label, and every failed point.

    Parameters
    ----------
    rows : sequence of mapping
        The study's rows.
    terms : Terms, optional
        The ζ_v and e the diagram was made with, stated when set (None: the paper's model).

    Returns
    -------
    dict
        Rung ("vertical"), model statement and why, points, counts per label, the
        overview's and the full intervals, and every point whose solve raised.
    """
    terms = terms or Terms()
    extra = {} if terms.ideal else {"terms": {n: getattr(terms, n) for n in VERTICAL_TERMS}}
    ivs = intervals(rows)
    overview = intervals(rows, coarse=True)
    counts: dict[str, int] = {}
    for r in rows:
        counts[r["label"]] = counts.get(r["label"], 0) + 1
    return {
        "fidelity": "vertical",
        "model": model_statement(
            "vertical-only exact model (dynamics.vertical): the head's vertical motion "
            "does not depend on the slider, so no slider is simulated",
            terms,
            VERTICAL_TERMS,
        ),
        **extra,
        "fidelity_reason": "regimes need the head's vertical motion only: the cheapest exact "
        "rung for them (fidelity.choose_rung)",
        "points": len(rows),
        "counts": counts,
        "overview": [i.as_dict() for i in overview],
        "intervals": [i.as_dict() for i in ivs],
        "errors": [
            {"varpi": r["varpi"], "message": r["message"]} for r in rows if r["status"] == "error"
        ],
    }


def run_regime(
    varpi: Sequence[float],
    *,
    max_cycles: int = 400,
    zeta_v: float = 0.0,
    restitution: float = 0.0,
    **run: Unpack[RunArgs],
) -> tuple[StudyRun, dict[str, Any]]:
    """Build, run and summarise the vertical regime diagram.

    Parameters
    ----------
    varpi, max_cycles, zeta_v, restitution
        As :func:`regime_study`.
    **run
        :class:`~betvdesign.studies.engine.runner.RunArgs` (executor, out, overwrite,
        progress).

    Returns
    -------
    tuple of (StudyRun, dict)
        The run (its rows) and :func:`summarise`'s summary.
    """
    study = regime_study(varpi, max_cycles=max_cycles, zeta_v=zeta_v, restitution=restitution)
    result = run_study(study, **run)
    return result, summarise(result.rows, Terms.of(study.parameters))
