"""One formatter for physical quantities shown to a designer (units layer).

Everything a designer reads (``betv check`` text, reports, notebook reprs) writes
values with an SI prefix chosen by magnitude: ``1.84 mm/s``, ``10 kHz``, ``5.93 ng``,
``110 nm``. JSON carries SI floats under unit-named keys (``speed_m_s``,
``f_act_hz``), built with :func:`si_key`. Device files keep their own ASCII
spelling (:func:`betvdesign.spec.units.format_quantity`).

Only the standard library is used here, so the formatter is cheap to import; a
pint quantity is accepted wherever a float is (converted with its own ``.to``).
"""

from __future__ import annotations

import math
import re
from typing import Any

#: Engineering prefixes (every 10³) from pico to giga.
PREFIXES: dict[int, str] = {-12: "p", -9: "n", -6: "µ", -3: "m", 0: "", 3: "k", 6: "M", 9: "G"}

#: Units that take a prefix on their first factor, with the largest exponent allowed
#: (no "ks" or "km": a designer reads 36 s and 5 m, not 0.036 ks).
_PREFIXABLE: dict[str, int] = {
    "m": 0,
    "s": 0,
    "Hz": 9,
    "g": 3,
    "V": 3,
    "N": 0,
    "A": 0,
    "W": 3,
    "J": 3,
    "Pa": 9,
    "m/s": 0,
    "m/s^2": 3,
    "N/m": 3,
    "m/V": 0,
    "m/V^2": 0,
}


def format_si(value: Any, unit: str, *, digits: int = 3, ascii: bool = False) -> str:
    """A value with an SI prefix chosen by magnitude, e.g. ``format_si(1.84e-3, "m/s")``.

    Parameters
    ----------
    value : float or pint.Quantity
        The value in ``unit`` [unit]; a pint quantity is converted to ``unit`` first.
    unit : str
        The SI unit of ``value`` (``"m"``, ``"m/s"``, ``"Hz"``, ``"kg"``, ``"N/m"``,
        ``"V"``, ``"s"``, ...). Masses in ``"kg"`` are written in grams with a prefix
        (``5.93e-12 kg`` -> ``"5.93 ng"``). Units without a natural prefix (``"rad/s"``,
        ``"deg"``, ``""``) are written as they are.
    digits : int
        Significant digits (3: ``1.84 mm/s``).
    ascii : bool
        Write the micro prefix as ``u`` instead of ``µ``.

    Returns
    -------
    str
        ``"1.84 mm/s"``, ``"10 kHz"``, ``"110 nm"``, ``"0 m/s"``; non-finite values give
        ``"nan m/s"`` / ``"inf s"``.
    """
    if hasattr(value, "to") and hasattr(value, "magnitude"):
        value = value.to(unit).magnitude
    x = float(value)
    if unit == "kg":
        x, unit = x * 1e3, "g"
    if not math.isfinite(x):
        return f"{x} {unit}".strip()
    top = _PREFIXABLE.get(unit)
    if top is None or x == 0.0:
        return f"{_mantissa(x, digits)} {unit}".strip()
    exp = 3 * math.floor(math.log10(abs(x)) / 3)
    exp = max(-12, min(top, exp))
    m = _round_sig(x / 10.0**exp, digits)
    if abs(m) >= 1000.0 and exp + 3 <= top:
        exp += 3
        m = _round_sig(x / 10.0**exp, digits)
    prefix = PREFIXES[exp]
    if ascii:
        prefix = prefix.replace("µ", "u")
    return f"{_mantissa(m, digits)} {prefix}{unit}"


#: SI units tried, in order, for a pint quantity of unknown unit (:func:`format_q`).
_SI_UNITS = ("m", "s", "Hz", "kg", "N/m", "V", "m/s", "m/V", "m/V^2", "N", "kg/m^3")


def format_q(q: Any, *, digits: int = 3, ascii: bool = False) -> str:
    """A pint quantity in its SI unit with a prefix: ``0.036 ug`` -> ``"36 ng"``,
    ``2.94 kHz`` -> ``"2.94 kHz"``. Angles, angular rates and units outside the SI set
    above keep their own unit (``45 deg``, ``4.9e+04 rad/s``)."""
    text = f"{q.units}"
    if "radian" not in text and "degree" not in text:
        for unit in _SI_UNITS:
            if q.is_compatible_with(unit):
                return format_si(q.to(unit).magnitude, unit, digits=digits, ascii=ascii)
    return f"{_mantissa(float(q.magnitude), digits)} {q.units:~P}".strip()


def scale_for(max_abs: float, unit: str) -> tuple[float, str]:
    """(factor, prefixed unit) for an axis whose largest |value| is ``max_abs`` [unit]:
    ``scale_for(3e-4, "m/s") == (1e6, "µm/s")``; multiply the data by the factor."""
    text = format_si(max_abs if max_abs and math.isfinite(max_abs) else 1.0, unit)
    prefixed = text.split(" ", 1)[1] if " " in text else unit
    base = "g" if unit == "kg" else unit
    prefix = prefixed[: len(prefixed) - len(base)] if prefixed.endswith(base) else ""
    exp = next((e for e, p in PREFIXES.items() if p == prefix), 0)
    factor = 10.0 ** (-exp) * (1e3 if unit == "kg" else 1.0)
    return factor, prefixed


def format_dimensionless(x: float, digits: int = 3) -> str:
    """A dimensionless number to ``digits`` significant digits, never in ``e+`` notation
    below 10⁶ (``1.2``, ``87.4``, ``12300``)."""
    return _mantissa(float(x), digits)


def si_key(name: str, unit: str) -> str:
    """JSON key naming a quantity and its SI unit: ``si_key("speed", "m/s") == "speed_m_s"``,
    ``si_key("f_act", "Hz") == "f_act_hz"``, ``si_key("k_v", "N/m") == "k_v_n_m"``."""
    slug = re.sub(r"[^0-9a-z]+", "_", unit.lower().replace("^", "")).strip("_")
    return f"{name}_{slug}" if slug else name


def _round_sig(x: float, digits: int) -> float:
    if x == 0.0 or not math.isfinite(x):
        return x
    return round(x, digits - 1 - math.floor(math.log10(abs(x))))


def _mantissa(x: float, digits: int) -> str:
    if not math.isfinite(x):
        return str(x)
    text = f"{x:.{digits}g}"
    if "e" in text and 1.0 <= abs(x) < 1e6:  # e.g. 36000 s with no larger prefix allowed
        text = f"{_round_sig(x, digits):.0f}"
    return text
