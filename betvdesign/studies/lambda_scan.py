"""Δs against λ for fixed (κ, β), across the push/pull boundary.

The fit λ = (κ/ϖ²)(1/(ακ) − D), D = (1/β − β)/(22(κ+1)) (docs/MODEL.md,
"Push/pull criterion") is inverted for the parameter that is varied:

* ``vary="varpi"`` (α fixed): ϖ = sqrt(κ(1/(ακ) − D)/λ), needs 1/(ακ) > D;
* ``vary="alpha"`` (ϖ fixed): α = 1/(κ(λϖ²/κ + D)), needs λϖ²/κ + D > 0.

Each λ target is then solved to its periodic state with the same worker as the
push/pull map, and the summary locates the simulated boundary: the pairs of
neighbouring λ values between which the converged Δs changes sign, to compare
with the fit's λ = 1. The bracket is reported, not an interpolated root: near
λ = 1 |Δs| often grows sharply on both sides (the speed changes abruptly), so
a straight line between the two points would say nothing reliable.

With damping or restitution (``zeta_v``, ``zeta_h``, ``restitution``, fixed over the
scan; :mod:`betvdesign.studies.terms`) λ stays the coordinate of the idealised fit and
Δs comes from the exact periodic orbit with the terms, so the scan shows where they move
the boundary away from λ = 1.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np

from betvdesign.errors import UsageError
from betvdesign.model.params import fit_offset
from betvdesign.studies.engine.grid import require_positive
from betvdesign.studies.engine.runner import Study, StudyRun, run_study, split_run_args
from betvdesign.studies.points import (
    COLUMNS,
    MODEL_STATEMENT,
    periodic_point,
    vertical_precheck,
)
from betvdesign.studies.terms import Terms, columns_with, model_statement

Vary = Literal["varpi", "alpha"]


def params_for_lambda(
    lam: float, *, kappa: float, beta: float, vary: Vary, alpha: float | None, varpi: float | None
) -> dict[str, float]:
    """The (ϖ, α, β, κ) point whose λ equals ``lam`` (see module doc).

    Inverts the push/pull fit of Shin et al. [1]_,
    λ = (κ/ϖ²)(1/(ακ) − D), D = (1/β − β)/(22(κ+1)), for ϖ or α.

    Parameters
    ----------
    lam : float
        Target λ [-] (> 0).
    kappa : float
        Normalised friction κ = μ·tanθ [-].
    beta : float
        Relative mass β = m/M [-].
    vary : {"varpi", "alpha"}
        The parameter solved for.
    alpha : float, optional
        Fixed α = k_v/k_h [-] (needed when ``vary="varpi"``).
    varpi : float, optional
        Fixed ϖ = ω·sqrt(m/k_v) [-] (needed when ``vary="alpha"``).

    Returns
    -------
    dict
        ``{"varpi": ϖ, "alpha": α, "beta": β, "kappa": κ}`` [-].

    Raises
    ------
    UsageError
        The fixed parameter is missing, or no positive ϖ or α reaches ``lam``.

    References
    ----------
    .. [1] K. Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773
    """
    d = fit_offset(kappa, beta)
    if vary == "varpi":
        if alpha is None:
            raise UsageError("varying ϖ needs a fixed --alpha")
        c = 1.0 / (alpha * kappa) - d
        if c <= 0:
            raise UsageError(
                f"with α={alpha:g}, β={beta:g}, κ={kappa:g} the fit gives λ ≤ 0 for every ϖ; "
                "no ϖ reaches the requested λ (vary alpha instead)"
            )
        return {"varpi": math.sqrt(kappa * c / lam), "alpha": alpha, "beta": beta, "kappa": kappa}
    if vary == "alpha":
        if varpi is None:
            raise UsageError("varying α needs a fixed --varpi")
        y = lam * varpi**2 / kappa + d
        if y <= 0:
            raise UsageError(f"λ = {lam:g} needs a negative α at ϖ={varpi:g}; outside the model")
        return {"varpi": varpi, "alpha": 1.0 / (kappa * y), "beta": beta, "kappa": kappa}
    raise UsageError(f"--vary must be varpi or alpha, not {vary!r}")


def lambda_study(
    lam: Sequence[float],
    *,
    kappa: float,
    beta: float,
    vary: Vary = "varpi",
    alpha: float | None = None,
    varpi: float | None = None,
    tol: float = 1e-10,
    max_cycles: int | None = None,
    zeta_v: float = 0.0,
    zeta_h: float = 0.0,
    restitution: float = 0.0,
) -> Study:
    """One periodic solve per λ target (the order kept as given).

    Parameters
    ----------
    lam : sequence of float
        λ targets [-] (> 0).
    kappa, beta, vary, alpha, varpi
        As :func:`params_for_lambda`.
    tol : float
        Fixed-point residual accepted for a periodic orbit [-].
    max_cycles : int, optional
        Cycle budget of each periodic solve (None: the solver's own).
    zeta_v, zeta_h : float
        Normal and tangential damping ratios [-], fixed (0: undamped).
    restitution : float
        Coefficient of restitution e [-], fixed (0: plastic impacts; all three 0: the
        paper's model).

    Returns
    -------
    Study
        One task per λ target, worker :func:`betvdesign.studies.points.periodic_point`.

    Raises
    ------
    UsageError
        A non-positive λ, ``max_cycles`` < 1, or a λ no point reaches.
    """
    terms = Terms(zeta_v, zeta_h, restitution)
    lam_arr = require_positive(np.asarray(lam, float), "lambda")
    if max_cycles is not None and max_cycles < 1:
        raise UsageError(f"--max-cycles must be >= 1, got {max_cycles}")
    tasks = []
    for key, target in enumerate(lam_arr):
        p = params_for_lambda(
            float(target), kappa=kappa, beta=beta, vary=vary, alpha=alpha, varpi=varpi
        )
        tasks.append({"key": key, **p, **terms.as_dict(), "tol": tol, "max_cycles": max_cycles})
    idle = vertical_precheck([t["varpi"] for t in tasks], terms)
    for t in tasks:
        t["not_driven"] = idle.get(t["varpi"])
    params = {
        "lambda": [float(x) for x in lam_arr],
        "kappa": kappa,
        "beta": beta,
        "vary": vary,
        "alpha": alpha,
        "varpi": varpi,
        "tol": tol,
        "max_cycles": max_cycles,
        **terms.as_dict(),  # a store of other terms is never resumed (store.py)
    }
    return Study("lambda", columns_with(COLUMNS, terms, "kappa"), params, tasks, periodic_point)


@dataclass
class LambdaSummary:
    """Where the simulated Δs changes sign, against the fit's λ = 1."""

    n_points: int
    n_converged: int
    crossings: list[dict[str, float]]
    not_converged: list[dict[str, Any]]
    terms: Terms = field(default_factory=Terms)

    def as_dict(self) -> dict[str, Any]:
        """The summary as plain data.

        Returns
        -------
        dict
            Rung, model statement and why, counts, sign changes and points without an
            orbit; ``terms`` only when set.
        """
        extra = {} if self.terms.ideal else {"terms": self.terms.as_dict()}
        return {
            "fidelity": "periodic",
            "model": model_statement(MODEL_STATEMENT["periodic"], self.terms),
            **extra,
            "fidelity_reason": "the scan locates where the exact Δs changes sign against the "
            "fit's λ = 1, which only the periodic orbit gives",
            "points": self.n_points,
            "converged": self.n_converged,
            "sign_changes": self.crossings,
            "not_converged": self.not_converged,
        }


def summarise(rows: Sequence[Mapping[str, Any]], terms: Terms | None = None) -> LambdaSummary:
    """Brackets [λ_a, λ_b] where Δs changes sign (converged points only, in λ order).

    Parameters
    ----------
    rows : sequence of mapping
        The scan's rows (:data:`betvdesign.studies.points.COLUMNS`).
    terms : Terms, optional
        The optional terms the scan was made with (None: the paper's model).

    Returns
    -------
    LambdaSummary
        Every neighbouring pair of converged λ [-] between which Δs [-] changes sign, to
        compare with the fit's λ = 1, and every point without an orbit.
    """
    conv = sorted((r for r in rows if r["converged"]), key=lambda r: r["lam"])
    crossings = [
        {
            "from": a["lam"],
            "to": b["lam"],
            "delta_s_from": a["delta_s"],
            "delta_s_to": b["delta_s"],
        }
        for a, b in itertools.pairwise(conv)
        if (a["delta_s"] > 0) != (b["delta_s"] > 0)
    ]
    failed = [
        {k: r[k] for k in ("key", "lam", "varpi", "alpha", "status", "message")}
        for r in rows
        if not r["converged"]
    ]
    return LambdaSummary(len(rows), len(conv), crossings, failed, terms or Terms())


def run_lambda_scan(*args: Any, **kwargs: Any) -> tuple[StudyRun, LambdaSummary]:
    """Build, run and summarise a Δs-against-λ scan.

    Parameters
    ----------
    *args, **kwargs
        Arguments of :func:`lambda_study` and the keywords of
        :class:`~betvdesign.studies.engine.runner.RunArgs` (executor, out, overwrite,
        progress).

    Returns
    -------
    tuple of (StudyRun, LambdaSummary)
        The run (its rows) and :func:`summarise`'s summary.
    """
    study_kw, run = split_run_args(kwargs)
    study = lambda_study(*args, **study_kw)
    result = run_study(study, **run)
    return result, summarise(result.rows, Terms.of(study.parameters))
