"""Options of the optional physics for commands that take raw dimensionless parameters
(``betv sweep pushpull|lambda|regime``, ``betv ladder``, ``betv simulate`` without a
device file): head damping per direction as a quality factor or a damping ratio, and the
coefficient of restitution (docs/MODEL.md, "Beyond the paper's idealisation").

``--quality-normal Q`` or ``--zeta-v ζ`` (not both), ``--quality-tangential Q`` or
``--zeta-h ζ`` (not both), ``--restitution e``; absent: the paper's model. Each value is
checked by :mod:`betvdesign.model.damping` (the checks a device file's fields get), so a bad
value is a click usage error naming the option (exit 2); giving both forms of one
direction is a :class:`UsageError` (exit 2 under ``user_errors``).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Annotated, Any

import typer

from betvdesign.errors import UsageError
from betvdesign.model import damping
from betvdesign.model.params import ZETA_MAX, ZETA_MIN


def _checked(check: Callable[[Any], float]) -> Callable[[float | None], float | None]:
    """Click callback: ``check`` (a :mod:`betvdesign.model.damping` check) as a BadParameter."""

    def callback(value: float | None) -> float | None:
        if value is None:
            return None
        try:
            return check(value)
        except ValueError as exc:
            # the checks speak of a device file's fields; here they are options
            raise typer.BadParameter(str(exc).replace("the field out", "the option out")) from None

    return callback


QualityNormalOpt = Annotated[
    float | None,
    typer.Option(
        "--quality-normal",
        help=f"Head's normal quality factor Q_v = 1/(2ζ_v) [-], {damping.Q_MIN:g} to "
        f"{damping.Q_MAX:g} (in air 10–100); absent: undamped. Or --zeta-v.",
        callback=_checked(damping.check_quality_factor),
    ),
]
ZetaVOpt = Annotated[
    float | None,
    typer.Option(
        "--zeta-v",
        help="Head's normal damping ratio ζ_v [-]: 0 or "
        f"{ZETA_MIN:g} to {ZETA_MAX:g}. Or --quality-normal.",
        callback=_checked(damping.check_damping_ratio),
    ),
]
QualityTangentialOpt = Annotated[
    float | None,
    typer.Option(
        "--quality-tangential",
        help=f"Head's tangential quality factor Q_h = 1/(2ζ_h) [-], {damping.Q_MIN:g} to "
        f"{damping.Q_MAX:g}; absent: undamped. Or --zeta-h.",
        callback=_checked(damping.check_quality_factor),
    ),
]
ZetaHOpt = Annotated[
    float | None,
    typer.Option(
        "--zeta-h",
        help="Head's tangential damping ratio ζ_h [-]: 0 or "
        f"{ZETA_MIN:g} to {ZETA_MAX:g}. Or --quality-tangential.",
        callback=_checked(damping.check_damping_ratio),
    ),
]
RestitutionOpt = Annotated[
    float | None,
    typer.Option(
        "--restitution",
        help="Coefficient of restitution e of normal impacts, 0 ≤ e < 1 [-]; absent or 0: "
        "plastic impacts (the paper's model).",
        callback=_checked(damping.check_restitution),
    ),
]


def _zeta(quality: float | None, zeta: float | None, q_name: str, z_name: str) -> float:
    if quality is not None and zeta is not None:
        raise UsageError(f"give {q_name} or {z_name}, not both (Q = 1/(2ζ))")
    if quality is not None:
        return float(damping.zeta_from_quality(quality))
    return 0.0 if zeta is None else float(zeta)


def physics_terms(
    quality_normal: float | None = None,
    zeta_v: float | None = None,
    quality_tangential: float | None = None,
    zeta_h: float | None = None,
    restitution: float | None = None,
) -> dict[str, float]:
    """``{"zeta_v", "zeta_h", "restitution"}`` from the options (absent: 0);
    :class:`UsageError` when both forms of one direction are given."""
    return {
        "zeta_v": _zeta(quality_normal, zeta_v, "--quality-normal", "--zeta-v"),
        "zeta_h": _zeta(quality_tangential, zeta_h, "--quality-tangential", "--zeta-h"),
        "restitution": 0.0 if restitution is None else float(restitution),
    }


#: Option names of the terms, as :func:`physics_terms` takes them.
OPTION_NAMES = {
    "quality_normal": "--quality-normal",
    "zeta_v": "--zeta-v",
    "quality_tangential": "--quality-tangential",
    "zeta_h": "--zeta-h",
    "restitution": "--restitution",
}


def given_options(values: Mapping[str, float | None]) -> list[str]:
    """The option names (``--zeta-v`` ...) of the terms in ``values`` that were given."""
    return [OPTION_NAMES[k] for k, v in values.items() if v is not None]
