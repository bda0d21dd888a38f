"""Head damping and restitution of normal impacts: conversions and the checks of the
values a device file gives (unit-free: plain numbers, floats or numpy arrays).

MODEL.md, "Beyond the paper's idealisation": dampers in parallel with the head's
springs, damping ratio ζ or quality factor Q = 1/(2ζ) per direction (normal ζ_v,
tangential ζ_h); a coefficient of restitution e ∈ [0, 1) of normal impacts. (The
normal force's phase δ and factor A: :func:`betvdesign.model.params.normal_force_phase`.)

The one implementation of Q ↔ ζ. :mod:`betvdesign.spec.models` declares its
fields with the types and ``Field`` s at the end (checked by the ``check_*`` functions:
a ``ValueError`` whose message the loader places at the field's file:line);
:mod:`betvdesign.nondim.terms` derives and records ζ (and δ, A). The supported range of
ζ is :data:`betvdesign.model.params.ZETA_MIN` to :data:`~betvdesign.model.params.ZETA_MAX` (its one
home): these checks apply it to the number as written in the file (so an error names the
field), :class:`~betvdesign.model.params.ModelParams` once more to the model parameters.
"Unit-free": the values are plain numbers; the field types need pydantic only.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Annotated, Any

from betvdesign.model.params import ZETA_MAX, ZETA_MIN

#: Quality factors Q = 1/(2ζ) of the supported damping ratios [-].
Q_MIN = 1.0 / (2.0 * ZETA_MAX)
Q_MAX = 1.0 / (2.0 * ZETA_MIN)


def term_range(field: str) -> tuple[float, float, bool] | None:
    """(lo, hi, hi_open) [-] a device field of the optional physics can take, by its
    dotted path (e.g. ``contact.restitution``): e ∈ [0, 1), Q in [Q_MIN, Q_MAX], ζ in
    [ZETA_MIN, ZETA_MAX]; None for every other field."""
    leaf = field.rsplit(".", 1)[-1]
    if leaf == "restitution":
        return 0.0, 1.0, True
    if leaf.startswith("quality_factor_"):
        return Q_MIN, Q_MAX, False
    if leaf.startswith("damping_ratio_"):
        return ZETA_MIN, ZETA_MAX, False
    return None


def zeta_from_quality(q: Any) -> Any:
    """Damping ratio ζ = 1/(2Q) [-] of a quality factor Q [-] (float or array)."""
    return 1.0 / (2.0 * q)


def quality_from_zeta(zeta: Any) -> Any:
    """Quality factor Q = 1/(2ζ) [-] of a damping ratio ζ > 0 [-] (float or array)."""
    return 1.0 / (2.0 * zeta)


def _number(value: Any, symbol: str) -> float:
    v = float(value)
    if not math.isfinite(v):
        undamped = " (undamped: leave the field out)" if symbol.startswith("q") else ""
        raise ValueError(f"{symbol} must be a finite number, got {v!r}{undamped}")
    return v


def _range() -> str:
    return f"{ZETA_MIN:g} ≤ ζ ≤ {ZETA_MAX:g}, i.e. {Q_MIN:g} ≤ Q ≤ {Q_MAX:g}"


def check_damping_ratio(value: Any) -> float:
    """A damping ratio ζ as a device file gives it: 0 (undamped) or within
    [ZETA_MIN, ZETA_MAX]; ``ValueError`` (message for the user) otherwise."""
    z = _number(value, "damping ratio ζ")
    if z < 0.0:
        raise ValueError(f"damping ratio ζ must be ≥ 0 (0: undamped), got {z:g}")
    if z != 0.0 and not ZETA_MIN <= z <= ZETA_MAX:
        raise ValueError(
            f"damping ratio ζ = {z:g} is outside the supported range: 0 (undamped) or "
            f"{_range()}"
            + (
                f"; below {ZETA_MIN:g} the damped closed form loses more than 4 digits near "
                "resonance: give 0"
                if z < ZETA_MIN
                else f"; above {ZETA_MAX:g} the head is too overdamped for an impact model"
            )
        )
    return z


def check_quality_factor(value: Any) -> float:
    """A quality factor Q as a device file gives it: Q > 0 with ζ = 1/(2Q) within
    [ZETA_MIN, ZETA_MAX]; ``ValueError`` (message for the user) otherwise."""
    q = _number(value, "quality factor Q")
    if q <= 0.0:
        raise ValueError(
            f"quality factor Q must be > 0, got {q:g} (Q = 1/(2ζ); "
            "for an undamped head leave the field out)"
        )
    z = zeta_from_quality(q)
    if not ZETA_MIN <= z <= ZETA_MAX:
        raise ValueError(
            f"quality factor Q = {q:g} (ζ = 1/(2Q) = {z:g}) is outside the supported range "
            f"{_range()}"
            + (
                f"; above Q = {Q_MAX:g} the damped closed form loses more than 4 digits near "
                "resonance: leave the field out (undamped, Q = ∞)"
                if q > Q_MAX
                else f"; below Q = {Q_MIN:g} the head is too overdamped for an impact model"
            )
        )
    return q


def check_restitution(value: Any) -> float:
    """A coefficient of restitution e ∈ [0, 1); ``ValueError`` otherwise."""
    e = _number(value, "coefficient of restitution e")
    if not 0.0 <= e < 1.0:
        raise ValueError(
            f"coefficient of restitution e = {e:g} is outside [0, 1) "
            "(0: plastic impacts, the paper's model; e ≥ 1 would gain energy or never settle)"
        )
    return e


# --- field types of the device file (betvdesign.spec.models) ----------------------------------


def _optional(check: Callable[[Any], float]) -> Callable[[Any], float | None]:
    return lambda v: None if v is None else check(v)


#: Optional dimensionless fields (plain numbers), checked as above: ``DampingRatio``,
#: ``QualityFactor`` and ``Restitution``, built on first use (:func:`__getattr__`) so the
#: checks above import without pydantic (the CLI's options use them).
_FIELD_CHECKS = {
    "DampingRatio": check_damping_ratio,
    "QualityFactor": check_quality_factor,
    "Restitution": check_restitution,
}


def __getattr__(name: str) -> Any:
    """The pydantic field types of :data:`_FIELD_CHECKS`, built once on first use."""
    if name not in _FIELD_CHECKS:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    from pydantic import AfterValidator

    value = Annotated[float | None, AfterValidator(_optional(_FIELD_CHECKS[name]))]
    globals()[name] = value
    return value


def ratio_field(symbol: str, direction: str) -> Any:
    """The ``Field`` (default None: undamped; schema description) of a damping ratio."""
    from pydantic import Field

    return Field(
        default=None,
        description=(
            f"Damping ratio {symbol} [-] of the head's {direction} oscillator (a plain "
            f"number): 0 (undamped, the default) or {_range()}; or give "
            f"quality_factor_{direction}."
        ),
    )


def quality_field(symbol: str, direction: str) -> Any:
    """The ``Field`` (default None: undamped; schema description) of a quality factor."""
    from pydantic import Field

    return Field(
        default=None,
        description=(
            f"Quality factor {symbol} = 1/(2ζ) [-] of the head's {direction} oscillator (a "
            f"plain number, e.g. 30; in air typically 10–100): {Q_MIN:g} ≤ Q ≤ {Q_MAX:g}; "
            f"absent: undamped. Or give damping_ratio_{direction}."
        ),
    )


def restitution_field() -> Any:
    """The ``Field`` (default None: plastic impacts; schema description) of e."""
    from pydantic import Field

    return Field(
        default=None,
        description=(
            "Coefficient of restitution e [-] of normal head/slider impacts (a plain number): "
            "0 ≤ e < 1, the normal velocity after a hit is −e times the one before; "
            "absent or 0: plastic impacts (the paper's model)."
        ),
    )
