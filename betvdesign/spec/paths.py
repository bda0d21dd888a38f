"""Field paths into a device spec: read and replace a value by its dotted path.

A path is written as in the device file (``slider.beam_width``, ``drive.frequency``).
Paths below an actuator set (``head.``, ``contact.``, ``actuator.``, ``drive.``)
address that field in every actuator set. Replacement is ``model_copy`` (no
validation: the values may be numpy arrays of samples); whatever is derived from the
result goes through :mod:`betvdesign.nondim.device`, and files written from it through the
loader.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import pint
from pydantic import BaseModel

SET_PREFIXES = ("head.", "contact.", "actuator.", "drive.")


def get(obj: Any, path: Sequence[str]) -> Any:
    """The value at ``path`` below ``obj`` (None where the model has no such field)."""
    for name in path:
        if not isinstance(obj, BaseModel) or name not in type(obj).model_fields:
            return None
        obj = getattr(obj, name)
    return obj


def _set(obj: Any, path: Sequence[str], value: Any) -> Any:
    if not path:
        return value
    child = getattr(obj, path[0])
    return obj.model_copy(update={path[0]: _set(child, path[1:], value)})


def targets(spec: Any, field: str) -> list[tuple[str, ...]]:
    """Full attribute paths a field path addresses in ``spec`` (several for set fields)."""
    parts = tuple(field.split("."))
    if field.startswith(SET_PREFIXES):
        return [("actuator_sets", str(i), *parts) for i in range(len(spec.actuator_sets))]
    return [parts]


def value_at(spec: Any, target: tuple[str, ...]) -> Any:
    """The value at a full target path (from :func:`targets`)."""
    if target[0] == "actuator_sets":
        return get(spec.actuator_sets[int(target[1])], target[2:])
    return get(spec, target)


def replace(spec: Any, target: tuple[str, ...], value: Any) -> Any:
    """A copy of ``spec`` with ``value`` at a full target path (no validation)."""
    if target[0] == "actuator_sets":
        i = int(target[1])
        sets = list(spec.actuator_sets)
        sets[i] = _set(sets[i], target[2:], value)
        return spec.model_copy(update={"actuator_sets": sets})
    return _set(spec, target, value)


def numeric(value: Any) -> bool:
    """A quantity or a plain float (the fields studies may vary)."""
    return isinstance(value, pint.Quantity) or (
        isinstance(value, float) and not isinstance(value, bool)
    )


def with_values(spec: Any, values: dict[str, Any]) -> Any:
    """``spec`` with each field path set to its value (set fields: every actuator set
    that has the field)."""
    for name, value in values.items():
        for target in targets(spec, name):
            if value_at(spec, target) is not None:
                spec = replace(spec, target, value)
    return spec
