"""The controls of ``betv explore``: the fields a designer changes, in their own units.

One function, :func:`designer_fields`, says which fields the page offers for an actuator
set and over which range its slider moves. The list of fields a designer changes and
their realistic bounds live in :mod:`betvdesign.studies.fixfields` (``betv fix``'s
``DEFAULT_BOUNDS`` and ``parse_vary``); the optional physics takes its range from
:func:`betvdesign.model.damping.term_range`. Only the fields ``betv fix`` does not vary
(beam thickness and count, friction, waveform, damping, restitution) are listed here;
when the project's one list of designer fields exists, only :func:`designer_fields`
changes. A typed value is judged by the device file's validation, never by these
ranges (they only bound the sliders).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal

from betvdesign.errors import BetvError
from betvdesign.model.damping import term_range
from betvdesign.spec.models import MU_MAX, MeasuredCalibration
from betvdesign.spec.paths import SET_PREFIXES, get
from betvdesign.spec.units import format_quantity
from betvdesign.studies.fixfields import DEFAULT_BOUNDS, parse_vary

Kind = Literal["quantity", "number", "integer", "choice"]

#: Groups of the page, in order, with (field, label) of each control in order. Per
#: alternative (a head by mass or by geometry, α by a resonance, a stiffness or α) only
#: the fields the set gives appear.
GROUPS: tuple[tuple[str, tuple[tuple[str, str], ...]], ...] = (
    (
        "Drive",
        (
            ("drive.frequency", "drive frequency"),
            ("drive.voltage", "drive voltage"),
            ("actuator.amplitude", "actuator amplitude u"),
            ("drive.waveform", "waveform"),
        ),
    ),
    (
        "Slider",
        (
            ("slider.beam_width", "beam width"),
            ("slider.beam_length", "beam length"),
            ("slider.beam_thickness", "beam thickness"),
            ("slider.beam_count", "beam count"),
        ),
    ),
    (
        "Head",
        (
            ("head.geometry.diameter", "head diameter"),
            ("head.geometry.length", "head length"),
            ("head.geometry.width", "head width"),
            ("head.geometry.thickness", "head thickness"),
            ("head.mass", "head mass"),
        ),
    ),
    (
        "Contact",
        (
            ("contact.impact_angle", "impact angle θ"),
            ("contact.friction", "friction μ"),
        ),
    ),
    (
        "Actuator",
        (
            ("actuator.vertical_resonance", "vertical resonance f_v"),
            ("actuator.horizontal_resonance", "horizontal resonance f_h"),
            ("actuator.horizontal_stiffness", "horizontal stiffness k_h"),
            ("actuator.alpha", "α = k_v/k_h"),
        ),
    ),
    (
        "Damping and rebound",
        (
            ("actuator.quality_factor_normal", "Q normal (empty: undamped)"),
            ("actuator.damping_ratio_normal", "ζ normal"),
            ("actuator.quality_factor_tangential", "Q tangential (empty: undamped)"),
            ("actuator.damping_ratio_tangential", "ζ tangential"),
            ("contact.restitution", "restitution e (empty: plastic, e = 0)"),
        ),
    ),
)

#: Slider bounds of the fields ``betv fix`` does not vary: factors of the file's value,
#: or absolute (lo, hi) with the marker "abs".
EXTRA_BOUNDS: dict[str, tuple[float, float] | tuple[float, float, str]] = {
    "slider.beam_thickness": (0.5, 2.0),
    "head.geometry.thickness": (0.5, 2.0),
    "contact.friction": (0.05, MU_MAX, "abs"),
    "slider.beam_count": (1.0, 8.0, "abs"),
}
#: Restitution slider: the model takes e in [0, 1); the slider stops short of 1.
RESTITUTION_MAX = 0.95
#: Waveforms the spec accepts.
WAVEFORMS = ("ac", "dc-biased", "unipolar")


@dataclass(frozen=True)
class FieldControl:
    """One control: a dotted field (relative to an actuator set, or ``slider.``), what
    it shows, its current value (None: an optional field left out) and its slider range.

    ``unit`` is the file's own unit (ASCII), ``lo``/``hi`` are in it; ``log``: the slider
    moves in log10 of the value.
    """

    field: str
    label: str
    group: str
    kind: Kind
    unit: str
    value: float | str | None
    lo: float = math.nan
    hi: float = math.nan
    log: bool = False
    choices: tuple[str, ...] = ()
    optional: bool = False

    @property
    def in_set(self) -> bool:
        """A field of an actuator set (rather than of the device's slider)."""
        return self.field.startswith(SET_PREFIXES)

    def text(self, value: float | str | None) -> str:
        """``value`` as the device file writes it ("" for an optional field left out)."""
        if value is None:
            return ""
        if self.kind == "choice":
            return str(value)
        if self.kind == "integer":
            return str(round(float(value)))
        x = float(value)
        num = f"{x:.4g}"
        return f"{num} {self.unit}" if self.unit else num

    def file_value(self, text: str) -> Any:
        """A typed text as the device file would hold it: a number for dimensionless
        fields (when it reads as one), the text otherwise; None for an empty optional."""
        t = text.strip()
        if not t:
            return None
        if self.kind in ("number", "integer"):
            try:
                x = float(t)
            except ValueError:
                return t  # the file's validation says what is wrong with it
            if self.kind == "integer" and x.is_integer():
                return int(x)
            return x
        return t


def _ascii_unit(unit: str) -> str:
    return unit.replace("µ", "u").replace("μ", "u")


def _one_set(spec: Any, set_index: int) -> Any:
    return spec.model_copy(update={"actuator_sets": [spec.actuator_sets[set_index]]})


def current_value(spec: Any, set_index: int, field: str) -> Any:
    """The value of ``field`` (relative to an actuator set, or ``slider.``) for set
    ``set_index`` of ``spec`` (None where the set does not give it)."""
    if field.startswith("slider."):
        return get(spec, field.split("."))
    return get(spec.actuator_sets[set_index], field.split("."))


def _number_bounds(field: str, x0: float) -> tuple[float, float]:
    b = EXTRA_BOUNDS.get(field, (0.5, 2.0))
    if len(b) == 3:
        return float(b[0]), float(b[1])
    return x0 * b[0], x0 * b[1]


def designer_fields(spec: Any, set_index: int) -> list[FieldControl]:
    """The controls for actuator set ``set_index`` of ``spec`` (a DeviceSpec), in page
    order (see the module docstring)."""
    aset = spec.actuator_sets[set_index]
    one = _one_set(spec, set_index)
    out: list[FieldControl] = []
    for group, fields in GROUPS:
        for field, label in fields:
            value = current_value(spec, set_index, field)
            rng = term_range(field)
            leaf = field.rsplit(".", 1)[-1]
            if field == "drive.waveform":
                out.append(
                    FieldControl(field, label, group, "choice", "", value, choices=WAVEFORMS)
                )
                continue
            if rng is not None:  # optional physics: shown when the spec allows it
                kind_q = leaf.startswith("quality_factor_")
                twin = field.replace("quality_factor", "damping_ratio")
                if not kind_q:
                    twin = field.replace("damping_ratio", "quality_factor")
                if (
                    value is None
                    and leaf != "restitution"
                    and (not kind_q or current_value(spec, set_index, twin) is not None)
                ):
                    continue  # the set gives the other form of this damping, or neither
                lo, hi, _ = rng
                if leaf == "restitution":
                    out.append(
                        FieldControl(
                            field,
                            label,
                            group,
                            "number",
                            "",
                            float(value or 0.0),
                            0.0,
                            RESTITUTION_MAX,
                            optional=True,
                        )
                    )
                else:
                    out.append(
                        FieldControl(
                            field,
                            label,
                            group,
                            "number",
                            "",
                            None if value is None else float(value),
                            lo,
                            hi,
                            log=True,
                            optional=True,
                        )
                    )
                continue
            if value is None:
                continue
            if field == "slider.beam_count":
                lo, hi = _number_bounds(field, float(value))
                out.append(FieldControl(field, label, group, "integer", "", int(value), lo, hi))
                continue
            if field in DEFAULT_BOUNDS:
                try:
                    v = parse_vary(one, [field])[0]
                except BetvError:
                    continue
                unit, x0, lo, hi = _ascii_unit(v.unit), v.x0, v.lo, v.hi
            elif hasattr(value, "units"):
                unit = _ascii_unit(format_quantity(value).split(" ", 1)[1])
                x0 = float(value.magnitude)
                lo, hi = _number_bounds(field, x0)
            else:
                unit, x0 = "", float(value)
                lo, hi = _number_bounds(field, x0)
            if field == "drive.voltage" and isinstance(
                aset.actuator.calibration, MeasuredCalibration
            ):
                vlo, vhi = (
                    float(q.to(unit).magnitude) for q in aset.actuator.calibration.voltage_range
                )
                lo, hi = max(lo, vlo, 1e-3 * x0), min(hi, vhi)
            kind: Kind = "quantity" if unit else "number"
            lo, hi = min(lo, x0), max(hi, x0)
            out.append(
                FieldControl(
                    field,
                    label,
                    group,
                    kind,
                    unit,
                    x0,
                    lo,
                    hi,
                    log=unit != "deg" and lo > 0 and hi / lo > 3.0,
                )
            )
    return out
