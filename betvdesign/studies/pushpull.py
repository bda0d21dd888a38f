"""Push/pull map: every (ϖ, α, β, κ) grid point solved to its periodic state.

Two rungs (docs/MODEL.md, "Push/pull criterion" and "Slider"):

* ``periodic`` (default, the reference): ``dynamics.periodic_orbit`` per point,
  giving Δs, the simulated mode, period in cycles, fixed-point residual,
  Floquet radius and a converged flag.
* ``lambda``: the closed-form fit λ = (κ/ϖ²)(1/(ακ) − (1/β − β)/(22(κ+1)))
  only. It costs microseconds, but it is a fit: near λ = 1 it can name the
  wrong mode, so a map made with it says so.

The summary compares the λ < 1 rule with the simulated mode at every converged
point and lists every disagreement and every point that did not converge
(status ``unbounded``, the exact tangential resonance α·ϖ² = 1 where the head's
motion grows without bound, is also listed on its own), so nothing is dropped silently.

Damping ζ_v, ζ_h and restitution e (docs/MODEL.md, "Beyond the paper's idealisation";
:mod:`betvdesign.studies.terms`) are fixed over a map: every point is then the exact
periodic orbit with them (near α·ϖ² = 1 a finite Δs instead of "unbounded"), λ stays the
idealised fit it is compared with, and the ``lambda`` rung is refused.

A point's row, its periodic solve and the rung statements are shared with the other
studies: :mod:`betvdesign.studies.points`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from betvdesign.errors import UsageError
from betvdesign.studies.engine.grid import Grid, require_positive
from betvdesign.studies.engine.runner import Study, StudyRun, run_study, split_run_args
from betvdesign.studies.points import (
    COLUMNS,
    MODEL_STATEMENT,
    Fidelity,
    periodic_point,
    point_row,
    require_fidelity,
    rung_reason,
    vertical_precheck,
)
from betvdesign.studies.terms import Terms, columns_with, model_statement, require_ideal_rung

AXES = ("kappa", "beta", "alpha", "varpi")


def lambda_point(task: Mapping[str, Any]) -> dict[str, Any]:
    """Worker of the ``lambda`` rung: λ and the mode it predicts, nothing simulated.

    Parameters
    ----------
    task : mapping
        A map task: ``key``, ϖ, α, β, κ [-] (see :func:`betvdesign.studies.points.point_row`).

    Returns
    -------
    dict
        One row of :data:`betvdesign.studies.points.COLUMNS`: λ of the closed-form fit of
        Shin et al. [1]_ and the mode it predicts; status "lambda-only".

    References
    ----------
    .. [1] K. Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773
    """
    row = point_row(task)
    row.update(status="lambda-only", converged=False, message="closed-form λ fit only")
    return row


@dataclass(frozen=True)
class MapPoints:
    """The points of a map: its grid, the terms and solver options, and each point's task.

    Built (and checked) by :func:`map_points`; shared by :func:`pushpull_study` (one task
    per grid point) and the atlas (:mod:`betvdesign.studies.atlas`, tasks built a chunk
    at a time in the workers), so both solve every point alike.
    """

    grid: Grid
    terms: Terms
    fidelity: str
    tol: float
    max_cycles: int | None
    #: ϖ -> why no contact recurs there (:func:`points.vertical_precheck`).
    idle: dict[float, dict[str, Any]]

    def task(self, key: int) -> dict[str, Any]:
        """The task of the grid point ``key``.

        Parameters
        ----------
        key : int
            The point's flat key (C order: κ slowest, ϖ fastest).

        Returns
        -------
        dict
            ``key``, κ, β, α, ϖ [-], the terms [-], ``tol``, ``max_cycles`` and
            ``not_driven`` (None, or why no contact recurs at this ϖ).
        """
        values = self.grid.point(key).values
        return {
            "key": key,
            **values,
            **self.terms.as_dict(),
            "tol": self.tol,
            "max_cycles": self.max_cycles,
            "not_driven": self.idle.get(values["varpi"]),
        }

    @property
    def worker(self) -> Any:
        """The worker of the rung: :func:`points.periodic_point` or :func:`lambda_point`."""
        return periodic_point if self.fidelity == "periodic" else lambda_point

    @property
    def columns(self) -> dict[str, type]:
        """The rows' columns (:data:`points.COLUMNS`, with the terms when set)."""
        return columns_with(COLUMNS, self.terms, "kappa")

    @property
    def parameters(self) -> dict[str, Any]:
        """What defines the rows: the grid, the rung, the solver's options, the terms."""
        params = {
            "grid": self.grid.as_dict(),
            "fidelity": self.fidelity,
            "tol": self.tol,
            "max_cycles": self.max_cycles,
        }
        return params | self.terms.as_dict()  # a store of other terms is never resumed


def map_points(
    varpi: Sequence[float],
    alpha: Sequence[float],
    beta: Sequence[float],
    kappa: Sequence[float],
    *,
    fidelity: Fidelity = "periodic",
    tol: float = 1e-10,
    max_cycles: int | None = None,
    zeta_v: float = 0.0,
    zeta_h: float = 0.0,
    restitution: float = 0.0,
) -> MapPoints:
    """The checked points of a map; grid order κ, β, α, ϖ (ϖ fastest).

    Parameters
    ----------
    varpi : sequence of float
        Normalised actuation frequencies ϖ = ω·sqrt(m/k_v) [-] (> 0).
    alpha : sequence of float
        Relative impact compliances α = k_v/k_h [-] (> 0).
    beta : sequence of float
        Relative masses β = m/M [-] (> 0).
    kappa : sequence of float
        Normalised friction κ = μ·tanθ [-] (> 0).
    fidelity : {"periodic", "lambda"}
        The rung: the exact periodic orbit per point (the reference) or the λ fit only.
    tol : float
        Fixed-point residual accepted for a periodic orbit [-].
    max_cycles : int, optional
        Cycle budget of each periodic solve (None: the solver's own).
    zeta_v, zeta_h : float
        Normal and tangential damping ratios [-], fixed over the map
        (:mod:`betvdesign.studies.terms`; 0: undamped).
    restitution : float
        Coefficient of restitution e [-] (0: plastic impacts). All three 0 is the paper's
        model and the study of before they existed; the ``lambda`` rung refuses them (a fit
        of the idealised model).

    Returns
    -------
    MapPoints
        The grid, the options, and the ϖ at which no contact recurs (periodic rung).

    Raises
    ------
    UsageError
        A non-positive axis value, a rung the map does not offer, the λ rung with the
        optional terms, or ``max_cycles`` < 1.
    """
    terms = Terms(zeta_v, zeta_h, restitution)
    axes = {
        "kappa": require_positive(np.asarray(kappa, float), "kappa"),
        "beta": require_positive(np.asarray(beta, float), "beta"),
        "alpha": require_positive(np.asarray(alpha, float), "alpha"),
        "varpi": require_positive(np.asarray(varpi, float), "varpi"),
    }
    grid = Grid(axes)
    require_fidelity(fidelity)
    require_ideal_rung(fidelity, terms)
    if max_cycles is not None and max_cycles < 1:
        raise UsageError(f"--max-cycles must be >= 1, got {max_cycles}")
    idle = vertical_precheck(axes["varpi"], terms) if fidelity == "periodic" else {}
    return MapPoints(grid, terms, fidelity, tol, max_cycles, idle)


def pushpull_study(*args: Any, **kwargs: Any) -> tuple[Study, Grid]:
    """Build the map study; grid order κ, β, α, ϖ (ϖ fastest).

    Parameters
    ----------
    *args, **kwargs
        The arguments of :func:`map_points` (ϖ, α, β, κ [-], the rung, the solver's
        options and the terms).

    Returns
    -------
    tuple of (Study, Grid)
        The study (one task per grid point, worker :func:`points.periodic_point` or
        :func:`lambda_point`) and its grid.

    Raises
    ------
    UsageError
        As :func:`map_points`.
    """
    mp = map_points(*args, **kwargs)
    tasks = [mp.task(k) for k in range(mp.grid.size)]
    return Study("pushpull", mp.columns, mp.parameters, tasks, mp.worker), mp.grid


@dataclass
class PushPullSummary:
    """Agreement of the λ < 1 rule with the simulated modes, and every exception."""

    fidelity: str
    n_points: int
    n_converged: int
    n_push: int
    n_pull: int
    n_agree: int
    n_predicted_push: int
    disagreements: list[dict[str, Any]]
    not_converged: list[dict[str, Any]]
    #: The subset of ``not_converged`` whose status is "unbounded" (no periodic orbit
    #: exists: the head's tangential motion grows linearly; the message gives the rate).
    unbounded: list[dict[str, Any]] = field(default_factory=list)
    #: The optional terms the map was made with (default: the paper's model).
    terms: Terms = field(default_factory=Terms)

    @property
    def agreement(self) -> float | None:
        """Fraction of converged points where λ names the simulated mode."""
        return self.n_agree / self.n_converged if self.n_converged else None

    def as_dict(self) -> dict[str, Any]:
        """The summary as plain data.

        Returns
        -------
        dict
            Rung, model statement and why, counts, agreement of λ [-], disagreements and
            points without an orbit; ``terms`` (and the note on λ) only when set.
        """
        extra: dict[str, Any] = {}
        if not self.terms.ideal:
            extra = {"terms": self.terms.as_dict(), "lambda_note": LAMBDA_NOTE}
        return {
            "fidelity": self.fidelity,
            "model": model_statement(MODEL_STATEMENT[self.fidelity], self.terms),
            **extra,
            "fidelity_reason": rung_reason(self.fidelity),
            "points": self.n_points,
            "converged": self.n_converged,
            "push": self.n_push,
            "pull": self.n_pull,
            "lambda_predicts_push": self.n_predicted_push,
            "lambda_agrees": self.n_agree,
            "lambda_agreement": self.agreement,
            "disagreements": self.disagreements,
            "not_converged": self.not_converged,
            "unbounded": self.unbounded,
        }


#: What λ's agreement means on a map with damping or restitution.
LAMBDA_NOTE = (
    "λ and lambda_mode are the fit of the idealised model (undamped, plastic impacts); "
    "with damping or restitution their agreement with the simulated modes measures how far "
    "these terms move the push/pull boundary, not the fit's accuracy"
)

#: Relative distance to a·ϖ² = 1 below which a point counts as at the tangential resonance.
RESONANCE_RTOL = 1e-9


def tangential_resonance(row: Mapping[str, Any]) -> str | None:
    """Which tangential resonance a·ϖ² = 1 the point sits on, if any.

    The head's tangential motion is undamped in free flight and can grow without bound
    there (docs/MODEL.md; the model of Shin et al. [1]_).

    Parameters
    ----------
    row : mapping
        A row with ``varpi`` ϖ, ``alpha`` α and ``beta`` β [-].

    Returns
    -------
    {"alpha", "stick"} or None
        ``"alpha"`` (a = α, free flight), ``"stick"`` (a = α(1 + 1/β)) when
        |a·ϖ² − 1| ≤ :data:`RESONANCE_RTOL`, else None.

    References
    ----------
    .. [1] K. Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773
    """
    w2 = row["varpi"] ** 2
    for name, a in (("alpha", row["alpha"]), ("stick", row["alpha"] * (1 + 1 / row["beta"]))):
        if abs(a * w2 - 1.0) <= RESONANCE_RTOL:
            return name
    return None


def _brief(row: Mapping[str, Any], keys: Sequence[str]) -> dict[str, Any]:
    return {k: row[k] for k in keys}


def summarise(
    rows: Sequence[Mapping[str, Any]], fidelity: str = "periodic", terms: Terms | None = None
) -> PushPullSummary:
    """Compare λ with the simulations; list disagreements and non-converged points.

    Parameters
    ----------
    rows : sequence of mapping
        The map's rows (:data:`betvdesign.studies.points.COLUMNS`).
    fidelity : {"periodic", "lambda"}
        The rung the rows were made on (points without an orbit are listed for
        "periodic" only).
    terms : Terms, optional
        The optional terms the map was made with, stated in the summary (None: the
        paper's model).

    Returns
    -------
    PushPullSummary
        Counts, agreement of the λ < 1 rule of Shin et al. [1]_ with the simulated modes,
        every disagreement and every point without an orbit (with the tangential
        resonance it sits on, :func:`tangential_resonance`).

    References
    ----------
    .. [1] K. Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773
    """
    point = ("key", "varpi", "alpha", "beta", "kappa", "lam")
    conv = [r for r in rows if r["converged"]]
    disagree = [
        _brief(r, (*point, "lambda_mode", "mode", "delta_s"))
        for r in conv
        if r["mode"] != r["lambda_mode"]
    ]
    failed = (
        [
            {**_brief(r, (*point, "status", "message")), "resonance": tangential_resonance(r)}
            for r in rows
            if not r["converged"]
        ]
        if fidelity == "periodic"
        else []
    )
    return PushPullSummary(
        fidelity=fidelity,
        n_points=len(rows),
        n_converged=len(conv),
        n_push=sum(r["mode"] == "push" for r in conv),
        n_pull=sum(r["mode"] == "pull" for r in conv),
        n_agree=len(conv) - len(disagree),
        n_predicted_push=sum(r["lambda_mode"] == "push" for r in rows),
        disagreements=disagree,
        not_converged=failed,
        unbounded=[d for d in failed if d["status"] == "unbounded"],
        terms=terms or Terms(),
    )


def run_pushpull(*args: Any, **kwargs: Any) -> tuple[StudyRun, PushPullSummary]:
    """Build, run and summarise a map.

    Parameters
    ----------
    *args, **kwargs
        Arguments of :func:`pushpull_study` and the keywords of
        :class:`~betvdesign.studies.engine.runner.RunArgs` (executor, out, overwrite,
        progress; streamed and resumable with ``out``).

    Returns
    -------
    tuple of (StudyRun, PushPullSummary)
        The run (its rows) and :func:`summarise`'s summary.
    """
    study_kw, run = split_run_args(kwargs)
    study, _ = pushpull_study(*args, **study_kw)
    result = run_study(study, **run)
    return result, summarise(result.rows, study.parameters["fidelity"], Terms.of(study.parameters))
