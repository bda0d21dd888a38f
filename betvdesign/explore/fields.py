"""The controls of ``betv explore``: the fields a designer changes, in their own units.

One function, :func:`designer_fields`, says which fields the page offers for an actuator
set and over which range its slider moves. The fields a designer changes, what each
moves, how it is set and its range are the project's one list,
:data:`betvdesign.spec.fields.FIELDS` (read by ``betv fix`` and the report's robustness
figure too): the page shows those the set gives, grouped by how they are set (drive
settings, drawn dimensions, layer thicknesses, resonances, materials), with the slider
over the field's :attr:`~betvdesign.spec.fields.DesignField.bounds` as ``betv fix``
resolves them (:func:`betvdesign.studies.fixfields.parse_vary`). The page adds the
controls that list leaves out (:data:`EXTRA`): the waveform, the beam count, and the
optional physics (damping as Q or ζ, restitution e) where the spec allows it, over the
range the model takes (:func:`betvdesign.model.damping.term_range`). Where the spec
itself bounds a field, the slider spans that: the drive voltage spans the set's measured
calibration (from its first point, 0 V included, to its last), the beam count the
spec's 1 to :data:`betvdesign.spec.limits.MAX_BEAM_COUNT`, the friction stops at
:data:`betvdesign.spec.models.MU_MAX`. A typed value is judged by the device file's
validation, never by these ranges (they only bound the sliders).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal, get_args

from betvdesign.errors import BetvError
from betvdesign.model.damping import term_range
from betvdesign.spec import limits
from betvdesign.spec.fields import FIELDS, DesignField
from betvdesign.spec.fields import Kind as FieldKind
from betvdesign.spec.models import MU_MAX, Drive, MeasuredCalibration
from betvdesign.spec.paths import in_set, is_set_field, targets, value_at
from betvdesign.studies.fixfields import drawn_springs_inert, parse_vary

Kind = Literal["quantity", "number", "integer", "choice"]

#: The page's group of each kind of designer field (:data:`betvdesign.spec.fields.Kind`).
GROUP_OF_KIND: dict[FieldKind, str] = {
    "drive setting": "Drive settings",
    "drawn dimension": "Drawn dimensions",
    "layer thickness": "Layer thicknesses",
    "resonance": "Resonances",
    "material": "Materials",
}
#: The group of the optional physics (:data:`EXTRA`).
PHYSICS_GROUP = "Damping and rebound"


@dataclass(frozen=True)
class Extra:
    """A control the designer-field list leaves out: its field, label and the kind of
    designer field it sits with (None: :data:`PHYSICS_GROUP`, after every kind)."""

    field: str
    label: str
    beside: FieldKind | None


#: Controls beyond :data:`betvdesign.spec.fields.FIELDS`, each shown after the fields of
#: its kind: the waveform and the beam count, and the optional physics.
EXTRA: tuple[Extra, ...] = (
    Extra("drive.waveform", "waveform", "drive setting"),
    Extra("slider.beam_count", "slider beam count", "drawn dimension"),
    Extra("actuator.quality_factor_normal", "Q normal (empty: undamped)", None),
    Extra("actuator.damping_ratio_normal", "ζ normal", None),
    Extra("actuator.quality_factor_tangential", "Q tangential (empty: undamped)", None),
    Extra("actuator.damping_ratio_tangential", "ζ tangential", None),
    Extra("contact.restitution", "restitution e (empty: plastic, e = 0)", None),
)
#: Slider positions per control.
SLIDER_STEPS = 200
#: Slider range of the beam count: what the spec takes (``slider.beam_count``).
BEAM_COUNT_RANGE = (1.0, float(limits.MAX_BEAM_COUNT))
#: Upper ends of the slider the spec sets (its limits): friction μ ≤ :data:`MU_MAX`.
SPEC_MAX: dict[str, float] = {"contact.friction": MU_MAX}
#: Restitution slider: the model takes e in [0, 1); the slider stops short of 1.
RESTITUTION_MAX = 0.95
#: Waveforms the spec accepts (its ``Drive.waveform``).
WAVEFORMS: tuple[str, ...] = get_args(Drive.model_fields["waveform"].annotation)


@dataclass(frozen=True)
class FieldControl:
    """One control: a dotted field (relative to an actuator set, or ``slider.``), what
    it shows (``label``: the designer field's ``what``), its group, its current value
    (None: an optional field left out) and its slider range.

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
    def shown_unit(self) -> str:
        """The unit as the page shows it to people (``µm`` for the file's ``um``)."""
        return "µ" + self.unit[1:] if self.unit.startswith("u") else self.unit

    def shown(self, value: float | str | None) -> str:
        """``value`` for people (slider tooltips, screen readers): 4 significant digits
        and the unit, ``µ`` written as such ("3 kHz", "10 µm")."""
        if value is None or self.kind == "choice":
            return self.text(value)
        text = self.text(value)
        return text[: len(text) - len(self.unit)] + self.shown_unit if self.unit else text

    @property
    def in_set(self) -> bool:
        """A field of an actuator set (rather than of the device's slider)."""
        return is_set_field(self.field)

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
    found = targets(spec, in_set(field, set_index))
    return value_at(spec, found[0]) if found else None


def _designer_control(spec: Any, set_index: int, f: DesignField) -> FieldControl | None:
    """The slider of one designer field over its bounds (None: the set does not give
    it as a positive number, or it is a drawn-actuator dimension that changes nothing
    because every set's file gives the head's resonance and α, as ``betv fix`` decides)."""
    if drawn_springs_inert(spec, f.path):
        return None
    try:
        v = parse_vary(_one_set(spec, set_index), [f.path])[0]
    except BetvError:
        return None
    unit, x0, lo, hi = _ascii_unit(v.unit), v.x0, v.lo, v.hi
    linear = unit == "deg"
    hi = min(hi, SPEC_MAX.get(f.path, math.inf))
    calibration = spec.actuator_sets[set_index].actuator.calibration
    if f.path == "drive.voltage" and isinstance(calibration, MeasuredCalibration):
        # the whole measured range, from its first point on (a linear slider from 0 V:
        # its first position above 0 V, the spec takes only a voltage > 0)
        lo, hi = (float(q.to(unit).magnitude) for q in calibration.voltage_range)
        if lo <= 0.0:
            lo, linear = hi / SLIDER_STEPS, True
    lo, hi = min(lo, x0), max(hi, x0)
    return FieldControl(
        f.path,
        f.what,
        GROUP_OF_KIND[f.kind],
        "quantity" if unit else "number",
        unit,
        x0,
        lo,
        hi,
        log=not linear and lo > 0 and hi / lo > 3.0,
    )


def _extra_control(spec: Any, set_index: int, e: Extra) -> FieldControl | None:
    """The control of one of :data:`EXTRA` (None: not offered for this set)."""
    value = current_value(spec, set_index, e.field)
    group = GROUP_OF_KIND[e.beside] if e.beside is not None else PHYSICS_GROUP
    if e.field == "drive.waveform":
        return FieldControl(e.field, e.label, group, "choice", "", value, choices=WAVEFORMS)
    if e.field == "slider.beam_count":
        if value is None:
            return None
        lo, hi = BEAM_COUNT_RANGE
        return FieldControl(e.field, e.label, group, "integer", "", int(value), lo, hi)
    rng = term_range(e.field)
    if rng is None:
        raise ValueError(f"{e.field}: no control for this field")
    leaf = e.field.rsplit(".", 1)[-1]
    if leaf == "restitution":  # e = 0 is the plastic impact the model takes by default
        x = float(value or 0.0)
        return FieldControl(
            e.field, e.label, group, "number", "", x, 0.0, RESTITUTION_MAX, optional=True
        )
    # damping: Q or ζ, whichever form the set gives (Q when it gives neither)
    if leaf.startswith("quality_factor_"):
        twin = e.field.replace("quality_factor", "damping_ratio")
        shown = value is not None or current_value(spec, set_index, twin) is None
    else:
        shown = value is not None
    if not shown:
        return None
    lo, hi, _ = rng
    x0 = None if value is None else float(value)
    return FieldControl(e.field, e.label, group, "number", "", x0, lo, hi, log=True, optional=True)


def designer_fields(spec: Any, set_index: int) -> list[FieldControl]:
    """The controls for actuator set ``set_index`` of ``spec`` (a DeviceSpec), in page
    order: per kind of designer field the fields of :data:`~betvdesign.spec.fields.FIELDS`
    the set gives (in that list's order), then the extras of that kind; the optional
    physics last (see the module docstring)."""
    kinds: list[FieldKind] = list(dict.fromkeys(f.kind for f in FIELDS))
    out: list[FieldControl] = []
    for kind in [*kinds, None]:
        if kind is not None:
            for f in FIELDS:
                if f.kind == kind and (c := _designer_control(spec, set_index, f)) is not None:
                    out.append(c)
        for e in EXTRA:
            if e.beside == kind and (c := _extra_control(spec, set_index, e)) is not None:
                out.append(c)
    return out
