"""Fields ``betv fix`` may change, their default bounds, and ``--vary``.

The fields and their bounds are those of :mod:`betvdesign.spec.fields` (the one list of
the fields a designer changes); by default ``betv fix`` varies the ones the designer
chooses (:attr:`~betvdesign.spec.fields.DesignField.chosen`; the drawn actuator's
dimensions only where they give the head's springs, not where every set's file gives
its resonance and α). A field is a dotted path
as in the device file (:mod:`betvdesign.spec.paths`); its bounds are factors of the
current value, or absolute values in a unit.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import pint

from betvdesign.errors import UsageError
from betvdesign.model.damping import term_range
from betvdesign.spec.fields import FIELDS, Bounds, bounds
from betvdesign.spec.models import DeviceSpec
from betvdesign.spec.paths import given

#: Default fields of ``betv fix`` and their search bounds, in ranking order: the fields
#: of :data:`betvdesign.spec.fields.FIELDS` the designer chooses.
DEFAULT_BOUNDS: dict[str, Bounds] = {f.path: f.bounds for f in FIELDS if f.chosen}


def drawn_springs_inert(spec: DeviceSpec, name: str) -> bool:
    """Tell whether a drawn-actuator field changes nothing for ``spec``.

    A drawn-actuator field changes nothing when every set's file gives the head's
    resonance and α (the file's values are used): not a default field then.

    Parameters
    ----------
    spec : DeviceSpec
        The device.
    name : str
        The field's path.

    Returns
    -------
    bool
        Whether changing the field leaves the model unchanged.
    """
    if not name.startswith("actuator.geometry."):
        return False
    return all(
        a.vertical_resonance is not None
        and (
            a.alpha is not None
            or a.horizontal_stiffness is not None
            or a.horizontal_resonance is not None
        )
        for a in (s.actuator for s in spec.actuator_sets)
    )


@dataclass(frozen=True)
class Vary:
    """A field to vary and its bounds, in the field's own unit (``unit``)."""

    field: str
    x0: float
    lo: float
    hi: float
    unit: str
    #: The range of the field the device's measured calibration covers [``unit``]
    #: (``drive.voltage`` with measured points; no extrapolation): a value outside it
    #: cannot be checked. None: no such range.
    calibrated: tuple[float, float] | None = None

    def quantity(self, x: float) -> Any:
        """The magnitude ``x`` in the field's unit (a float for a unit-less field)."""
        from betvdesign.spec.units import ureg

        return ureg.Quantity(x, self.unit) if self.unit else float(x)

    def text(self, x: float) -> str:
        """The magnitude ``x`` with the field's unit, as text."""
        return f"{x:.4g} {self.unit}".strip()


def current_value(spec: Any, name: str) -> tuple[float, str] | None:
    """The current magnitude and unit of a numeric field.

    The current magnitude and unit of a numeric field (None when the spec does not
    give it or it is not numeric); :class:`UsageError` when the sets differ.

    Parameters
    ----------
    spec : DeviceSpec
        The device.
    name : str
        The field's path.

    Returns
    -------
    tuple of (float, str) or None
        Magnitude and unit.

    Raises
    ------
    UsageError
        When the sets give different values.
    """
    present = given(spec, name)
    if not present:
        return None
    first = present[0]
    if any(v != first for v in present):
        raise UsageError(f"--vary {name}: differs between actuator sets; vary one value")
    if isinstance(first, pint.Quantity):
        return float(first.magnitude), f"{first.units:~}"
    if isinstance(first, float | int) and not isinstance(first, bool):
        return float(first), ""
    return None


def parse_vary(spec: Any, items: Sequence[str]) -> list[Vary]:
    """Parse ``FIELD`` or ``FIELD=LO:HI`` items into field axes.

    Parameters
    ----------
    spec : DeviceSpec
        The device.
    items : sequence of str
        ``FIELD`` or ``FIELD=LO:HI``, quantities in any unit of the field (e.g.
        ``drive.frequency=400Hz:3kHz``); none: every default field the spec has.

    Returns
    -------
    list of Vary
        The fields and their bounds.

    Raises
    ------
    UsageError
        For unknown fields, unreadable, inverted or out-of-range bounds.
    """
    out: list[Vary] = []
    names = list(items) or [
        f
        for f in DEFAULT_BOUNDS
        if current_value(spec, f) is not None and not drawn_springs_inert(spec, f)
    ]
    for item in names:
        name, _, rng = item.partition("=")
        name = name.strip()
        cur = current_value(spec, name)
        if cur is None:
            known = ", ".join(f for f in DEFAULT_BOUNDS if current_value(spec, f) is not None)
            raise UsageError(
                f"--vary {name}: not a numeric field of device {spec.name!r}; it has {known}"
            )
        x0, unit = cur
        if x0 <= 0:
            raise UsageError(f"--vary {name}: current value {x0:g} is not positive")
        lo, hi = _vary_bounds(item, name, rng, x0, unit)
        if not rng:  # default bounds: never below the process's minimum width or spacing
            lo = max(lo, _process_floor(spec, name, unit))
            if lo >= hi:
                continue
        cal = calibrated_range(spec, name, unit)
        if cal is not None and not rng:  # default bounds: only what the points cover
            lo, hi = max(lo, cal[0]), min(hi, cal[1])
            if not 0 < lo < hi:
                continue
        out.append(Vary(name, x0, lo, hi, unit, cal))
    if len({v.field for v in out}) != len(out):
        raise UsageError("--vary: a field is given twice")
    return out


def _process_floor(spec: Any, name: str, unit: str) -> float:
    """The process's minimum of a drawn width or gap in ``unit`` (0 when none applies)."""
    from betvdesign.spec.units import ureg
    from betvdesign.studies.drawnchange import floor

    if not name.startswith("actuator.geometry."):
        return 0.0
    fl = floor(spec, name)
    return 0.0 if fl is None else float((fl[0] * ureg.um).to(unit).magnitude)


def _vary_bounds(item: str, name: str, rng: str, x0: float, unit: str) -> tuple[float, float]:
    """The bounds of one ``--vary`` item, checked.

    Parameters
    ----------
    item : str
        The item as given (``FIELD`` or ``FIELD=LO:HI``).
    name : str
        The field's dotted path.
    rng : str
        ``LO:HI`` ("" for the field's default bounds, :func:`bounds`).
    x0 : float
        The field's current value [``unit``].
    unit : str
        The unit of the field's value in the file.

    Returns
    -------
    tuple of float
        (LO, HI) [``unit``].

    Raises
    ------
    UsageError
        Unreadable or inverted bounds, bounds a device file could not give, or outside
        what the model takes for an optional term.
    """
    from betvdesign.spec.units import parse_quantity, range_problem

    if rng:
        lo_s, sep, hi_s = rng.partition(":")
        if not sep:
            raise UsageError(f"--vary {item}: bounds must be LO:HI, e.g. {name}=1um:8um")
        try:
            qs = [parse_quantity(t.strip()) for t in (lo_s, hi_s)]
            lo, hi = (_magnitude(q, unit) for q in qs)
        except (ValueError, pint.PintError) as exc:
            raise UsageError(f"--vary {item}: {exc}") from None
        for q in qs:  # what a device file could not give either
            if isinstance(q, pint.Quantity) and (problem := range_problem(q)) is not None:
                raise UsageError(f"--vary {name}: {problem}")
    else:
        b = bounds(name)
        if len(b) == 3:
            from betvdesign.spec.units import ureg

            lo, hi = (float(ureg.Quantity(v, b[2]).to(unit).magnitude) for v in b[:2])
        else:
            lo, hi = x0 * b[0], x0 * b[1]
    dom = term_range(name)
    if dom is not None:  # optional physics: its own range, e = 0 included
        dlo, dhi, hi_open = dom
        if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi and dlo <= lo):
            raise UsageError(
                f"--vary {item}: need 0 < LO < HI (got {lo:g} to {hi:g}; the search is "
                "log-spaced: for nearly plastic impacts give e.g. LO = 0.001)"
                if dlo == 0
                else f"--vary {item}: need {dlo:g} ≤ LO < HI (got {lo:g} to {hi:g})"
            )
        if hi > dhi or (hi_open and hi == dhi):
            raise UsageError(
                f"--vary {item}: HI {hi:g} outside what the model takes "
                f"({'<' if hi_open else '≤'} {dhi:g})"
            )
    elif not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi):
        raise UsageError(f"--vary {item}: need 0 < LO < HI (got {lo:g} to {hi:g} {unit})".rstrip())
    return lo, hi


def calibrated_range(spec: Any, name: str, unit: str) -> tuple[float, float] | None:
    """The drive voltages every set's measured calibration covers [``unit``].

    The drive voltages every set's measured calibration covers [``unit``] (for
    ``drive.voltage``; the calibration is interpolated, never extrapolated); None for
    another field or a device without measured points.

    Parameters
    ----------
    spec : DeviceSpec
        The device.
    name : str
        The field's dotted path.
    unit : str
        The unit of the field's value in the file.

    Returns
    -------
    tuple of float or None
        (lowest, highest) voltage measured, intersected over the sets.
    """
    from betvdesign.spec.models import MeasuredCalibration

    if name != "drive.voltage":
        return None
    ranges = [
        tuple(float(v.to(unit).magnitude) for v in s.actuator.calibration.voltage_range)
        for s in spec.actuator_sets
        if isinstance(s.actuator.calibration, MeasuredCalibration)
    ]
    if not ranges:
        return None
    return max(r[0] for r in ranges), min(r[1] for r in ranges)


def _magnitude(q: Any, unit: str) -> float:
    if not isinstance(q, pint.Quantity):
        return float(q)
    if not unit:
        return float(q.to("dimensionless").magnitude)
    return float(q.to(unit).magnitude)
