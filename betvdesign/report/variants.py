"""The device with one designer field changed: the robustness sweep's inputs.

A designer sets drive frequencies, resonances, friction surfaces and beam widths, not
α or β. Each variant goes through the same path as the device itself: the spec with the
field changed (:meth:`betvdesign.spec.models.DeviceSpec.replace`, validated like a device file)
-> :func:`betvdesign.nondim.device.derive_set` (the only place units are stripped). A value the
spec rejects (e.g. an impact angle past 90°) is kept with its reason, never dropped.
"""

from __future__ import annotations

import numpy as np

from betvdesign.errors import BetvError
from betvdesign.nondim.device import derive_set
from betvdesign.report.analysis import FieldVariant
from betvdesign.spec.models import DeviceSpec
from betvdesign.spec.units import format_quantity

#: Fields a designer changes, in the order shown; per group the first one the set gives
#: is varied (a resonance or a stiffness, a head mass or its geometry's thickness).
FIELD_GROUPS: tuple[tuple[str, ...], ...] = (
    ("drive.frequency",),
    ("actuator.horizontal_resonance", "actuator.horizontal_stiffness", "actuator.alpha"),
    ("head.mass", "head.geometry.thickness"),
    ("contact.friction",),
    ("slider.beam_width",),
)


def relative_changes(points: int, span: float) -> np.ndarray:
    """``points`` relative changes evenly over [−span, +span], 0 (the device) included."""
    n = max(points, 3) | 1  # odd: the nominal device sits in the middle
    return np.linspace(-span, span, n)


def _get(obj: object, path: str) -> object | None:
    for name in path.split("."):
        obj = getattr(obj, name, None)
        if obj is None:
            return None
    return obj


def field_variants(spec: DeviceSpec, set_index: int, changes: np.ndarray) -> list[FieldVariant]:
    """Variants of actuator set ``set_index`` of ``spec``: each field of
    :data:`FIELD_GROUPS` the device gives, scaled by (1 + change)."""
    aset = spec.actuator_sets[set_index]
    out: list[FieldVariant] = []
    for group in FIELD_GROUPS:
        for field in group:
            on_slider = field.startswith("slider.")
            nominal = _get(spec if on_slider else aset, field)
            if nominal is None or isinstance(nominal, bool):
                continue
            path = field if on_slider else f"actuator_sets.{set_index}.{field}"
            shown = format_quantity(nominal, ".4g") if hasattr(nominal, "units") else f"{nominal:g}"
            for r in changes:
                value = nominal * (1.0 + float(r))
                try:
                    changed = spec.replace(path, value) if r != 0 else spec
                    sd = derive_set(changed, changed.actuator_sets[set_index])
                except BetvError as exc:
                    reason = str(exc).splitlines()[0]
                    out.append(FieldVariant(field, shown, float(r), None, reason=reason))
                    continue
                out.append(
                    FieldVariant(
                        field,
                        shown,
                        float(r),
                        sd.params,
                        sd.scales.length_m * sd.scales.f_act_hz,
                    )
                )
            break
    return out
