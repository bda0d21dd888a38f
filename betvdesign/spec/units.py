"""The package's one pint registry and pydantic field types for physical quantities.

Device files give every dimensional value as a string with units ("5 um",
"2.94 kHz", "45 deg", "0.036 ug"). The types here parse such strings with
:data:`ureg`, check the dimension, reject bare numbers where a unit is due,
enforce simple bounds, and serialise back to strings that parse again.

Only :mod:`betvdesign.nondim.device` strips units; every other layer above the spec keeps
pint quantities or unit-free model parameters.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Annotated, Any

import pint
from pydantic import GetCoreSchemaHandler, GetJsonSchemaHandler
from pydantic.json_schema import JsonSchemaValue
from pydantic_core import PydanticCustomError, core_schema

from betvdesign.spec import limits


def unit_registry(cache_folder: str | None = ":auto:") -> pint.UnitRegistry:
    """The default pint registry, its parsed definitions cached on disk.

    Building the registry parses pint's definition file (about 0.2 s); pint keeps the
    parsed form in ``cache_folder`` (``":auto:"``: the user's cache folder, e.g.
    ``~/.cache/pint``; the entries are keyed by pint's and Python's versions and the
    definitions' content), and a later start loads it (about 0.04 s). The registry is the
    same either way (``tests/test_units.py`` compares every unit's root units and
    dimensionality with an uncached build). A cache that cannot be written or read (a
    read-only home, a file half-written by a process starting at the same time) is
    skipped: the registry is then built from the definitions.

    Parameters
    ----------
    cache_folder : str or None
        Where pint caches the parsed definitions; None: no cache.

    Returns
    -------
    pint.UnitRegistry
        A new registry.
    """
    if cache_folder is not None:
        try:
            return pint.UnitRegistry(cache_folder=cache_folder)
        except Exception:  # any failure of the cache (OSError, a truncated pickle, ...)
            pass
    return pint.UnitRegistry()


#: The one unit registry of the package. Quantities from another registry cannot mix.
ureg = unit_registry()
Quantity = ureg.Quantity

#: Dimension labels accepted by :class:`QuantitySpec` (pint dimensionality strings).
#: "angle" is special: pint treats radians as dimensionless, so angles are recognised
#: by their root unit (radian) instead.
ANGLE = "angle"


#: A number: decimal or scientific, or nan/inf (refused later as not finite, by name).
_NUMBER = r"[+-]?(?:(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|nan|inf(?:inity)?)"
#: One unit factor: a name with at most one numeric power (``m^3``, ``V**-2``).
_NAME = re.compile(r"[^\W\d]\w*")
_POWER = re.compile(r"(?:\*\*|\^)\s*([+-]?\d+(?:\.\d+)?)")
_SHAPE = re.compile(
    rf"\s*(?P<num>{_NUMBER})?\s*"
    r"(?P<units>(?:[%°µμΩ]|[^\W\d])[\w°µμΩ]*(?:\s*(?:\*\*|\^)\s*[+-]?\d+(?:\.\d+)?)?"
    r"(?:\s*(?:[*/]\s*|\s)\s*(?:[%°µμΩ]|[^\W\d])[\w°µμΩ]*"
    r"(?:\s*(?:\*\*|\^)\s*[+-]?\d+(?:\.\d+)?)?)*)?\s*",
    re.IGNORECASE,
)


def _check_shape(text: str) -> None:
    """Bound the work pint may do on ``text`` before it sees it.

    Bound the work pint may do on ``text`` before it sees it: a number and at most
    :data:`~betvdesign.spec.limits.MAX_UNIT_FACTORS` unit names joined by ``*``, ``/`` or
    spaces, each with at most one integer power of modest size. No parentheses, no
    powers of powers, no arithmetic on numbers: a quantity is written "2330 kg/m^3".
    """
    if len(text) > limits.MAX_QUANTITY_CHARS:
        raise ValueError(
            f"quantity string of {len(text)} characters; the limit is "
            f"{limits.MAX_QUANTITY_CHARS} (expected e.g. '5 um')"
        )
    m = _SHAPE.fullmatch(text)
    if m is None or (m.group("num") is None and m.group("units") is None):
        raise ValueError(
            f"cannot read {text!r} as a quantity: write a number and units such as "
            "'5 um' or '2330 kg/m^3' (one power per unit, no parentheses or arithmetic)"
        )
    digits = sum(ch.isdigit() for ch in m.group("num") or "")
    if digits > limits.MAX_NUMBER_DIGITS:
        raise ValueError(
            f"number of {digits:,} digits in a quantity; the limit is "
            f"{limits.MAX_NUMBER_DIGITS} digits"
        )
    units = m.group("units") or ""
    n_factors = len(_NAME.findall(_POWER.sub("", units)))
    if n_factors > limits.MAX_UNIT_FACTORS:
        raise ValueError(
            f"{text!r} has {n_factors} unit factors; the limit is {limits.MAX_UNIT_FACTORS}"
        )
    for exp in _POWER.findall(units):
        if abs(float(exp)) > limits.MAX_UNIT_EXPONENT:
            raise ValueError(
                f"unit power {exp} in {text!r} exceeds the limit of ±{limits.MAX_UNIT_EXPONENT}"
            )


def parse_quantity(text: str) -> pint.Quantity:
    """Parse ``"5 um"`` into a quantity of :data:`ureg`.

    The text is first checked against a bounded shape (length, digits of the number,
    number of unit factors, one modest power each), so a hostile string cannot make pint
    evaluate towers of powers.

    Parameters
    ----------
    text : str
        A number and units (``"2330 kg/m^3"``), or units alone (a magnitude of 1).

    Returns
    -------
    pint.Quantity
        The quantity.

    Raises
    ------
    ValueError
        With a user-facing message, for text that fails the check or that pint cannot
        read.
    """
    _check_shape(text)
    try:
        q = ureg.Quantity(text)
    except pint.UndefinedUnitError as exc:
        raise ValueError(f"unknown unit in {text!r}: {exc}{_unit_hint(text)}") from None
    except pint.OffsetUnitCalculusError:
        raise ValueError(
            f"{text!r}: offset units (degC, degF) have no meaning here; use kelvin or a "
            "unit of the field's dimension"
        ) from None
    except Exception:  # pint's tokenizer raises assorted errors for malformed text
        raise ValueError(f"cannot read {text!r} as a quantity (expected e.g. '5 um')") from None
    if not isinstance(q, pint.Quantity):  # e.g. a bare unit name parses to a Unit
        q = ureg.Quantity(1.0, q)
    return q


#: Units a did-you-mean suggests for a mistyped unit (case and spelling).
COMMON_UNITS = (
    "Hz",
    "kHz",
    "MHz",
    "m",
    "mm",
    "um",
    "nm",
    "V",
    "mV",
    "kg",
    "g",
    "mg",
    "ug",
    "ng",
    "s",
    "ms",
    "us",
    "N/m",
    "deg",
    "rad",
    "m/s",
    "mm/s",
    "um/s",
    "kg/m^3",
    "Pa",
    "GPa",
)


def _unit_hint(text: str) -> str:
    """Suggest ``"; did you mean '2 kHz'?"`` for a unit in the wrong case or nearly right."""
    import difflib

    number, _, unit = text.strip().partition(" ")
    if not unit:
        i = next((k for k, c in enumerate(text) if c.isalpha()), len(text))
        number, unit = text[:i].strip(), text[i:].strip()
    if not unit:
        return ""
    folded = {u.casefold(): u for u in COMMON_UNITS}
    hit = folded.get(unit.casefold().replace("µ", "u"))
    if hit is None:
        close = difflib.get_close_matches(unit, COMMON_UNITS, n=1, cutoff=0.6)
        hit = close[0] if close else None
    if hit is None:
        return ""
    return f"; did you mean '{number} {hit}'?" if number else f"; did you mean '{hit}'?"


def parse_positive(text: str, unit: str, what: str) -> float:
    """Magnitude of a user-given quantity such as ``"1 mm/s"`` (a CLI option).

    Parameters
    ----------
    text : str
        The quantity.
    unit : str
        The unit to express it in; fixes the dimension.
    what : str
        The option, for messages.

    Returns
    -------
    float
        The magnitude in ``unit``.

    Raises
    ------
    UsageError
        Unless it parses, has the dimension of ``unit`` and is finite and > 0.
    """
    from betvdesign.errors import UsageError

    try:
        q = parse_quantity(text)
        if q.dimensionless and not ureg.Quantity(1.0, unit).dimensionless:
            raise UsageError(
                f"{what}: missing unit in {text!r} (write e.g. '{text.strip()} {unit}')"
            )
        v = float(q.to(unit).magnitude)
    except pint.DimensionalityError as exc:  # e.g. "mm/S" (siemens) for "mm/s"
        raise UsageError(
            f"{what}: {exc} (expected a quantity in units of {unit}){_unit_hint(text)}"
        ) from None
    except (ValueError, pint.PintError) as exc:
        raise UsageError(f"{what}: {exc} (expected a quantity in units of {unit})") from None
    if not (math.isfinite(v) and v > 0):
        raise UsageError(f"{what}: must be finite and > 0, got {text!r}")
    return v


def parse_speed(text: str, what: str = "speed") -> float:
    """A speed such as ``"1 mm/s"`` (see :func:`parse_positive`).

    Parameters
    ----------
    text : str
        The quantity.
    what : str
        The option, for messages.

    Returns
    -------
    float
        The speed [m/s].
    """
    return parse_positive(text, "m/s", what)


def parse_units(text: str) -> pint.Unit:
    """Parse a unit expression such as ``"um/s"`` with the bounds of :func:`parse_quantity`.

    Parameters
    ----------
    text : str
        The units.

    Returns
    -------
    pint.Unit
        The unit.

    Raises
    ------
    ValueError
        With a user-facing message (unreadable, or a number other than 1 in front).
    """
    q = parse_quantity(text)
    if q.magnitude != 1:
        raise ValueError(f"{text!r} is not a unit (it has the factor {q.magnitude:g})")
    return q.units


def format_quantity(q: pint.Quantity, fmt: str = "") -> str:
    """Write a quantity as a string that :func:`parse_quantity` reads back.

    The micro sign is written as ``u`` so files stay ASCII.

    Parameters
    ----------
    q : pint.Quantity
        The quantity.
    fmt : str
        A float format spec (e.g. ``".4g"``); empty keeps full precision.

    Returns
    -------
    str
        E.g. ``"5 um"``.
    """
    mag = q.magnitude
    if isinstance(mag, float):
        mag_s = format(mag, fmt) if fmt else repr(mag)
    else:
        mag_s = format(mag, fmt) if fmt else str(mag)
    unit_s = format(q.units, "~C").replace("µ", "u").replace("μ", "u")
    if unit_s.startswith("1/"):  # no numerator: '1/K' does not read back, 'K^-1' does
        unit_s = (
            "*".join(
                ureg.get_symbol(name) + ("" if p == 1 else f"^{p:g}")
                for name, p in q.units._units.items()
            )
            .replace("µ", "u")
            .replace("μ", "u")
        )
    return f"{mag_s} {unit_s}".strip() if unit_s else mag_s


def is_angle(q: pint.Quantity) -> bool:
    """Whether a quantity is expressed in an angle unit (deg, rad, ...).

    Parameters
    ----------
    q : pint.Quantity
        The quantity.

    Returns
    -------
    bool
        True when its root unit is the radian (pint treats angles as dimensionless).
    """
    return ureg.get_root_units(q.units)[1] == ureg.radian


@dataclass(frozen=True)
class QuantitySpec:
    """Pydantic annotation: a quantity of one dimension, with optional bounds.

    dimension: a label for messages (``"[length]"``) or :data:`ANGLE`.
    unit: the canonical unit; it fixes the dimension checked and the unit of the bounds.
    example: shown in messages and in the JSON schema.
    gt/ge/lt: bounds in ``unit`` (exclusive/inclusive/exclusive).
    """

    dimension: str
    unit: str
    example: str
    gt: float | None = None
    ge: float | None = None
    lt: float | None = None

    # --- validation -----------------------------------------------------------------
    def validate(self, value: Any) -> pint.Quantity:
        """The pydantic validator: a quantity of this field's dimension and bounds.

        Parameters
        ----------
        value : Any
            A quantity string, or a quantity of :data:`ureg`.

        Returns
        -------
        pint.Quantity
            The quantity, in the units given.

        Raises
        ------
        PydanticCustomError
            A bare number, no number, an unknown unit, a quantity of another registry, the
            wrong dimension, not finite, or out of bounds.
        """
        if isinstance(value, bool) or isinstance(value, int | float):
            raise PydanticCustomError(
                "missing_unit",
                "missing unit: got the bare number {value}, write it with units, e.g. '{example}'",
                {"value": value, "example": self.example},
            )
        if isinstance(value, pint.Quantity):
            if value._REGISTRY is not ureg:
                raise PydanticCustomError(
                    "foreign_registry", "quantity from another pint registry; use betvdesign.ureg"
                )
            q = value
        elif isinstance(value, str):
            try:
                q = parse_quantity(value)
            except ValueError as exc:
                raise PydanticCustomError("bad_quantity", str(exc)) from None
            if _SHAPE.fullmatch(value).group("num") is None:  # parse_quantity matched it
                raise PydanticCustomError(
                    "missing_number",
                    "missing number in {text}: write e.g. '{example}'",
                    {"text": repr(value), "example": self.example},
                )
            if q.units == ureg.dimensionless:
                raise PydanticCustomError(
                    "missing_unit",
                    "missing unit in {text}: write it with units, e.g. '{example}'",
                    {"text": repr(value), "example": self.example},
                )
        else:
            raise PydanticCustomError(
                "bad_quantity",
                "expected a quantity string such as '{example}', got {kind}",
                {"example": self.example, "kind": type(value).__name__},
            )
        self._check_dimension(q)
        mag = q.to(self.unit).magnitude
        if not math.isfinite(float(mag)):
            raise PydanticCustomError("not_finite", "value must be finite, got {q}", {"q": str(q)})
        self._check_bounds(q, float(mag))
        return q

    def _check_dimension(self, q: pint.Quantity) -> None:
        if self.dimension == ANGLE:
            ok = is_angle(q)
            want = "an angle"
        else:
            ok = q.dimensionality == ureg.parse_units(self.unit).dimensionality
            want = f"dimension {self.dimension}"
        if not ok:
            raise PydanticCustomError(
                "wrong_dimension",
                "wrong dimension: {got} has {dim}, expected {want} (e.g. '{example}')",
                {
                    "got": format_quantity(q),
                    "dim": "no angle unit" if self.dimension == ANGLE else str(q.dimensionality),
                    "want": want,
                    "example": self.example,
                },
            )

    def _check_bounds(self, q: pint.Quantity, mag: float) -> None:
        u = self.unit
        if self.gt is not None and not mag > self.gt:
            raise PydanticCustomError(
                "out_of_range",
                "must be > {b} {u}, got {q}",
                {"b": f"{self.gt:g}", "u": u, "q": format_quantity(q)},
            )
        if self.ge is not None and not mag >= self.ge:
            raise PydanticCustomError(
                "out_of_range",
                "must be >= {b} {u}, got {q}",
                {"b": f"{self.ge:g}", "u": u, "q": format_quantity(q)},
            )
        if self.lt is not None and not mag < self.lt:
            raise PydanticCustomError(
                "out_of_range",
                "must be < {b} {u}, got {q}",
                {"b": f"{self.lt:g}", "u": u, "q": format_quantity(q)},
            )
        problem = range_problem(q)
        if problem is not None:
            raise PydanticCustomError("out_of_model_range", "{problem}", {"problem": problem})

    # --- pydantic hooks -------------------------------------------------------------
    def __get_pydantic_core_schema__(
        self, source: Any, handler: GetCoreSchemaHandler
    ) -> core_schema.CoreSchema:
        """Validate with :meth:`validate` (pydantic hook)."""
        return core_schema.no_info_plain_validator_function(
            self.validate,
            serialization=core_schema.plain_serializer_function_ser_schema(
                format_quantity, when_used="always"
            ),
        )

    def __get_pydantic_json_schema__(
        self, schema: core_schema.CoreSchema, handler: GetJsonSchemaHandler
    ) -> JsonSchemaValue:
        """The JSON schema of the quantity: a string with its unit and bounds (pydantic hook)."""
        bounds = []
        if self.gt is not None:
            bounds.append(f"> {self.gt:g} {self.unit}")
        if self.ge is not None:
            bounds.append(f">= {self.ge:g} {self.unit}")
        if self.lt is not None:
            bounds.append(f"< {self.lt:g} {self.unit}")
        dim = "an angle" if self.dimension == ANGLE else self.dimension
        desc = f"Quantity string with units of {dim}"
        if bounds:
            desc += ", " + " and ".join(bounds)
        return {
            "x-quantity": desc,
            "type": "string",
            "pattern": r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*\S.*$",
            "description": desc,
            "examples": [self.example],
        }


def range_problem(q: pint.Quantity) -> str | None:
    """Why a quantity lies outside the range the model computes with, or None.

    The range is that of its dimension in :data:`betvdesign.spec.limits.QUANTITY_RANGE`
    (the one home of these bounds; device files, ``--vary`` bounds); 0 and quantities of
    a dimension without a range are not refused here.

    Parameters
    ----------
    q : pint.Quantity
        The quantity.

    Returns
    -------
    str or None
        The message ("1e-320 V is outside 1e-06 V to 1e+06 V, ..."), None when inside.
    """
    key = _range_unit(q)
    if key is None:
        return None
    mag = float(q.to(key).magnitude)
    lo, hi, what = limits.QUANTITY_RANGE[key]
    if mag == 0.0 or lo <= abs(mag) <= hi:
        return None
    return (
        f"{format_quantity(q)} is outside {_exact(lo)} {key} to {_exact(hi)} {key}, the range "
        f"of {what} the model computes with (inside it no derived value underflows or "
        "overflows)"
    )


def _range_unit(q: pint.Quantity) -> str | None:
    """The unit of :data:`~betvdesign.spec.limits.QUANTITY_RANGE` of ``q``'s dimension."""
    if is_angle(q):
        return "deg"
    if q.dimensionless:
        return None
    return next(
        (
            u
            for u in limits.QUANTITY_RANGE
            if u != "deg" and q.dimensionality == ureg.parse_units(u).dimensionality
        ),
        None,
    )


def _exact(x: float) -> str:
    """``x`` short (``1e+06``) where that is exact, else with the digits it needs."""
    return f"{x:g}" if float(f"{x:g}") == x else repr(x)


def _q(dimension: str, unit: str, example: str, **bounds: float) -> Any:
    return Annotated[pint.Quantity, QuantitySpec(dimension, unit, example, **bounds)]


# Field types used by :mod:`betvdesign.spec.models`. Positive unless the name says otherwise.
Length = _q("[length]", "m", "5 um", gt=0.0)
NonNegativeLength = _q("[length]", "m", "0.11 um", ge=0.0)
Mass = _q("[mass]", "kg", "0.036 ug", gt=0.0)
NonNegativeMass = _q("[mass]", "kg", "0 ug", ge=0.0)
Frequency = _q("[frequency]", "Hz", "2.94 kHz", gt=0.0)
Duration = _q("[time]", "s", "0.2 ms", gt=0.0)
Density = _q("[mass]/[length]**3", "kg/m**3", "2330 kg/m^3", gt=0.0)
Stiffness = _q("[mass]/[time]**2", "N/m", "12 N/m", gt=0.0)
Voltage = _q("[voltage]", "V", "8 V", gt=0.0)
NonNegativeVoltage = _q("[voltage]", "V", "0 V", ge=0.0)
#: Impact angle θ: strictly between 0° and 90° (tanθ must be finite and positive).
ImpactAngle = _q(ANGLE, "deg", "45 deg", gt=0.0, lt=90.0)
LinearGain = _q("[length]/[voltage]", "m/V", "0.01375 um/V", gt=0.0)
QuadraticGain = _q("[length]/[voltage]**2", "m/V**2", "0.0017 um/V^2", gt=0.0)
