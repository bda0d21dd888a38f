"""The device with one designer field changed: the robustness sweep's inputs.

A designer sets drive frequencies, resonances, friction surfaces and beam widths, not
α or β. The fields are those of :data:`betvdesign.spec.fields.FIELDS` (the one list,
also ``betv fix``'s): per physical quantity the first field the actuator set gives, of
those that move ϖ, α, β or κ (:func:`shown_fields`). Each variant goes through the same
path as the device itself: the spec with the field changed
(:meth:`betvdesign.spec.models.DeviceSpec.replace`, validated like a device file) ->
:func:`betvdesign.nondim.device.derive_set` (the only place units are stripped). A value the
spec rejects (e.g. an impact angle past 90°) is kept with its reason, never dropped.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pint

from betvdesign.errors import BetvError
from betvdesign.nondim.device import derive_set
from betvdesign.report.analysis import FieldVariant
from betvdesign.spec.fields import FIELDS
from betvdesign.spec.models import DeviceSpec
from betvdesign.spec.paths import given, in_set, numeric
from betvdesign.spec.units import format_quantity


def shown_fields(spec: DeviceSpec, set_index: int) -> list[tuple[str, Any]]:
    """The fields the sweep varies in actuator set ``set_index`` and their values.

    Parameters
    ----------
    spec : DeviceSpec
        The device.
    set_index : int
        Index of the actuator set.

    Returns
    -------
    list of (str, value)
        Field path (as in :data:`~betvdesign.spec.fields.FIELDS`) and its value in the
        set, in the list's order: per quantity the first numeric field the set gives, of
        the fields that move a model parameter.
    """
    out: list[tuple[str, Any]] = []
    done: set[str] = set()
    for f in FIELDS:
        if not f.moves_model or f.quantity in done:
            continue
        values = given(spec, in_set(f.path, set_index))
        if values and numeric(values[0]):
            out.append((f.path, values[0]))
            done.add(f.quantity)
    return out


def relative_changes(points: int, span: float) -> np.ndarray:
    """``points`` relative changes evenly over [−span, +span], 0 (the device) included."""
    n = max(points, 3) | 1  # odd: the nominal device sits in the middle
    return np.linspace(-span, span, n)


def field_variants(spec: DeviceSpec, set_index: int, changes: np.ndarray) -> list[FieldVariant]:
    """Variants of actuator set ``set_index`` of ``spec``: each field of
    :func:`shown_fields` scaled by (1 + change)."""
    out: list[FieldVariant] = []
    for field, nominal in shown_fields(spec, set_index):
        path = in_set(field, set_index)
        shown = (
            format_quantity(nominal, ".4g")
            if isinstance(nominal, pint.Quantity)
            else f"{nominal:g}"
        )
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
                    field, shown, float(r), sd.params, sd.scales.length_m * sd.scales.f_act_hz
                )
            )
    return out
