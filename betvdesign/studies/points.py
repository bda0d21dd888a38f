"""One design point of a study.

One design point of a study: the exact orbit as a row, the solver's error as text,
the fidelity a study may use.

Every study that solves design points shares these pieces: the push/pull map
(:mod:`betvdesign.studies.pushpull`), the λ scan (:mod:`betvdesign.studies.lambda_scan`),
the tolerance analysis (:mod:`betvdesign.studies.tolerance`), the regime diagram
(:mod:`betvdesign.studies.regime`) and the paper's validation (:mod:`betvdesign.paper`).

* :func:`periodic_point`: the exact periodic orbit of one (ϖ, α, β, κ) point
  (:func:`betvdesign.dynamics.periodic_orbit`) as one row of :data:`COLUMNS`;
* :func:`vertical_precheck`: the ϖ values at which no contact recurs, found once per ϖ
  by the vertical model instead of once per point;
* :func:`solver_error`: the message of a row whose solve raised;
* :data:`MODEL_STATEMENT`, :func:`rung_reason`, :func:`require_fidelity`: the two
  rungs of the fidelity ladder a study offers (docs/MODEL.md, "Push/pull criterion"),
  what each is and why a study runs on it.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any, Literal

import numpy as np

from betvdesign.checks.fidelity import RUNGS
from betvdesign.errors import UsageError
from betvdesign.model.params import ModelParams
from betvdesign.output.numbers import json_float
from betvdesign.studies.terms import Terms, columns_with

#: The rungs of the fidelity ladder a study of design points offers.
Fidelity = Literal["periodic", "lambda"]

#: What each rung is and why a study would use it (stated in every summary).
MODEL_STATEMENT: dict[str, str] = {
    "periodic": "exact periodic orbit per point (dynamics.periodic_orbit, Newton shooting on "
    "the Poincaré map): the reference; the mode is the sign of the simulated Δs",
    "lambda": "closed-form λ fit only (no simulation): microseconds per point, but a fit that "
    "can name the wrong mode near λ = 1",
}

#: Result columns of one design point (types for the CSV store).
COLUMNS: dict[str, type] = {
    "key": int,
    "varpi": float,
    "alpha": float,
    "beta": float,
    "kappa": float,
    "lam": float,
    "lambda_mode": str,
    "status": str,
    "converged": bool,
    "mode": str,
    "delta_s": float,
    "period_cycles": int,
    "residual": float,
    "floquet_radius": float,
    "impacts_per_cycle": float,
    "contact_fraction": float,
    "cycles": int,
    "message": str,
}

#: Vertical horizon [cycles] within which a contact must recur (as in ``periodic_orbit``).
VERTICAL_HORIZON = 1000


def rung_reason(fidelity: str) -> str:
    """Why a study runs on a rung of the fidelity ladder.

    Parameters
    ----------
    fidelity : {"periodic", "lambda"}
        The rung.

    Returns
    -------
    str
        The ``fidelity_reason`` stated next to ``fidelity`` and ``model`` in every
        summary; for λ it states the fit's held-out error rate.
    """
    if fidelity == "lambda":
        from betvdesign.checks.fidelity import lambda_error_statement

        return (
            "chosen with --fidelity lambda: λ alone, a fit whose mode can be wrong: "
            + lambda_error_statement()
        )
    return (
        "the default: every point's mode and Δs from the exact periodic orbit, the "
        "reference the λ rule is measured against"
    )


def require_fidelity(fidelity: str, offered: Sequence[str] = ("periodic", "lambda")) -> None:
    """Refuse a rung the study does not offer.

    Parameters
    ----------
    fidelity : str
        The rung asked for.
    offered : sequence of str
        The rungs the study offers.

    Raises
    ------
    UsageError
        Unless ``fidelity`` is one of ``offered`` (the message names the ladder's rungs).
    """
    if fidelity in offered:
        return
    what = "fidelity" if fidelity in RUNGS else "unknown fidelity"
    raise UsageError(
        f"{what} {fidelity!r}: this study offers {' or '.join(offered)} "
        f"(rungs of the fidelity ladder: {', '.join(RUNGS)})"
    )


def task_params(task: Mapping[str, Any]) -> ModelParams:
    """The model parameters of a task.

    Parameters
    ----------
    task : mapping
        A study task: ``varpi`` ϖ, ``alpha`` α, ``beta`` β, ``kappa`` κ [-] and the
        optional terms ``zeta_v``, ``zeta_h``, ``restitution`` [-] (absent: 0, the
        paper's model).

    Returns
    -------
    ModelParams
        The point's parameters.
    """
    return Terms.of(task).params(task["varpi"], task["alpha"], task["beta"], task["kappa"])


def point_row(task: Mapping[str, Any]) -> dict[str, Any]:
    """The row of a point before any solve: its key, parameters, λ and the mode λ predicts.

    Parameters
    ----------
    task : mapping
        A study task (see :func:`task_params`) with its ``key``.

    Returns
    -------
    dict
        Every column of :data:`COLUMNS` (with the task's optional terms after κ), the
        solver's columns None. λ is the closed-form fit of Shin et al. [1]_,
        λ = (κ/ϖ²)(1/(ακ) − (1/β − β)/(22(κ+1))) [-]; λ < 1 predicts push.

    References
    ----------
    .. [1] K. Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773
    """
    p = task_params(task)
    row: dict[str, Any] = dict.fromkeys(columns_with(COLUMNS, Terms.of(task), "kappa"))
    row.update(key=task["key"], **p.as_dict(), lam=p.lam, lambda_mode=p.lambda_mode)
    return row


def periodic_point(task: Mapping[str, Any]) -> dict[str, Any]:
    """Worker of the ``periodic`` rung: one periodic-orbit solve (plain data in and out).

    Parameters
    ----------
    task : mapping
        A study task (see :func:`point_row`) with ``tol``, the fixed-point residual
        accepted [-], ``max_cycles`` (None: the solver's budget) and ``not_driven``
        (from :func:`vertical_precheck`, or None).

    Returns
    -------
    dict
        One row of :data:`COLUMNS`: status, converged, mode, Δs [-] per cycle, period
        [cycles], residual [-], largest Floquet multiplier modulus [-], impacts per cycle,
        contact fraction [-], cycles from rest and the solver's message. A task carrying
        ``not_driven`` is answered without the slider (no contact recurs, so nothing
        drives it); a solve that raises gives status "error" and :func:`solver_error`.
    """
    return periodic_solve(task)[0]


def periodic_solve(task: Mapping[str, Any]) -> tuple[dict[str, Any], Any]:
    """The periodic point's row with the solver's result.

    :func:`periodic_point`'s row with the solver's result (for a worker that goes on
    from the orbit, e.g. to the travel from rest).

    Parameters
    ----------
    task : mapping
        As :func:`periodic_point`.

    Returns
    -------
    tuple
        (the row, the :class:`~betvdesign.dynamics.result.PeriodicResult`, or None when
        the task was answered without the slider or the solve raised).
    """
    from betvdesign.dynamics import periodic_orbit

    row = point_row(task)
    if task.get("not_driven"):
        nd = task["not_driven"]
        row.update(
            status="not_driven",
            converged=False,
            impacts_per_cycle=nd["hits_per_cycle"],
            contact_fraction=0.0,
            cycles=0,
            message=nd["message"],
        )
        return row, None
    p = task_params(task)
    kwargs: dict[str, Any] = {"tol": task["tol"]}
    if task.get("max_cycles") is not None:
        kwargs["max_cycles"] = task["max_cycles"]
    try:
        res = periodic_orbit(p, **kwargs)
    except Exception as exc:  # a solver crash is recorded and listed, never fatal to a sweep
        row.update(status="error", converged=False, message=solver_error(exc))
        return row, None
    return orbit_row(row, res), res


def orbit_row(row: dict[str, Any], res: Any) -> dict[str, Any]:
    """A point's row with its orbit's columns filled in (:data:`COLUMNS`).

    Parameters
    ----------
    row : dict
        The point's row (:func:`point_row`); updated in place.
    res : PeriodicResult
        Its orbit (any model's: the decoupled exact solver's, the coupled head's).

    Returns
    -------
    dict
        ``row``, with status, converged, mode, Δs [-] per cycle, period [cycles],
        residual [-], largest Floquet multiplier modulus [-], impacts per cycle, contact
        fraction [-], cycles from rest and the solver's message.
    """
    radius = None
    if res.floquet is not None and len(res.floquet):
        radius = float(np.max(np.abs(np.asarray(res.floquet))))
    row.update(
        status=str(res.status),
        converged=bool(res.success),
        mode=res.mode if res.success else None,
        delta_s=json_float(res.delta_s),
        period_cycles=None if res.period_cycles is None else int(res.period_cycles),
        residual=json_float(res.residual),
        floquet_radius=radius,
        impacts_per_cycle=json_float(res.impacts_per_cycle),
        contact_fraction=json_float(res.contact_fraction),
        cycles=int(res.transient_cycles),
        message=str(res.message),
    )
    return row


def solver_error(exc: BaseException) -> str:
    """The message of a row whose solve raised.

    Parameters
    ----------
    exc : BaseException
        What the solver raised.

    Returns
    -------
    str
        The message: a solver defect, to be reported with the point's parameters.
    """
    return f"solver raised {type(exc).__name__}: {exc} (a defect; report these parameters)"


def vertical_precheck(
    varpi: Sequence[float], terms: Terms | None = None
) -> dict[float, dict[str, Any]]:
    """The ϖ values at which no contact recurs: the slider is not driven.

    Found by the vertical model alone, once per ϖ instead of once per grid point
    ("model no more than a scene needs"; docs/MODEL.md, "Vertical motion").

    Parameters
    ----------
    varpi : sequence of float
        Frequency ratios ϖ = ω/ω_v [-] of the study's points (repeats are solved once).
    terms : Terms, optional
        The optional terms; the vertical model takes ζ_v and e [-] (None: the paper's
        model).

    Returns
    -------
    dict
        ``{ϖ: {"hits_per_cycle": ..., "message": ...}}`` for every ϖ at which no contact
        recurs within :data:`VERTICAL_HORIZON` cycles. A ϖ whose vertical motion cannot be
        computed is left out: the periodic solve reports it.
    """
    from betvdesign.dynamics import vertical_motion
    from betvdesign.dynamics.vertical import VerticalSearchError

    t = terms or Terms()
    out = {}
    for v in sorted(set(float(x) for x in varpi)):
        try:
            r = vertical_motion(
                v, zeta_v=t.zeta_v, restitution=t.restitution, max_cycles=VERTICAL_HORIZON
            )
        except VerticalSearchError:
            continue
        if r.period_cycles is None:
            out[v] = {"hits_per_cycle": float(r.hits_per_cycle), "message": r.message}
    return out
