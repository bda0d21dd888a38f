"""What-if edits of a device spec, validated exactly like a device file.

``spec.replace("slider.beam_width", "6 um")`` (:meth:`betvdesign.spec.models.DeviceSpec.replace`)
returns a new, validated :class:`~betvdesign.spec.models.DeviceSpec`; the original is frozen
and unchanged. The edit is made on the spec's plain data, which is then validated like a
device file, so a bad value raises the same :class:`~betvdesign.errors.SpecError` (field
path, message, did-you-mean) a device file would, never an error deep inside the
derivation.

Paths are those of :mod:`betvdesign.spec.paths` (the one home of the idea): dotted, as in
the device file; a set by index or name (``actuator_sets.forward.drive.voltage``); a
path below an actuator set without the set (``drive.voltage``) applies to every set.
This module is the thin validated layer on top: an unvalidated copy
(:func:`betvdesign.spec.paths.replace`) may hold arrays of samples, this one may not.
"""

from __future__ import annotations

from typing import Any, TypeVar

import pint
from pydantic import BaseModel, ValidationError

from betvdesign.errors import Location, SpecError, SpecIssue
from betvdesign.spec.messages import dotted, known_fields, located
from betvdesign.spec.paths import PathError, holder, targets
from betvdesign.spec.units import format_quantity, ureg

#: A spec model (a :class:`~betvdesign.spec.models.DeviceSpec`); the edit returns the same type.
Spec = TypeVar("Spec", bound=BaseModel)


def replace(spec: Spec, path: str, value: Any, *more: tuple[str, Any]) -> Spec:
    """A validated copy of ``spec`` with ``path`` set to ``value``.

    A copy of ``spec`` with ``path`` set to ``value`` (and each ``(path, value)`` of
    ``more``), validated like a device file.

    Parameters
    ----------
    spec : DeviceSpec
        The device to start from (unchanged).
    path : str
        Dotted field path (see the module doc).
    value : str, float, int, dict, pint.Quantity or None
        The new value as a device file would give it: ``"6 um"``, ``0.3``, ``"ac"``; a
        pint quantity of :data:`betvdesign.ureg` is written with its unit; None removes
        the field (e.g. ``head.geometry`` before giving ``head.mass``).
    *more : tuple of (str, value)
        Further edits, applied in order before the one validation.

    Returns
    -------
    DeviceSpec
        The edited, validated device.

    Raises
    ------
    SpecError
        Unknown path (with the closest field names) or a value the device file would
        reject (wrong unit, out of range, inconsistent with other fields).
    """
    data = spec.model_dump(mode="json", exclude_unset=True, by_alias=True)
    where = f"{spec.name} with {path} = {value!r}"
    for p, v in ((path, value), *more):
        _assign(data, p, _plain(v), where)
    model = type(spec)
    try:  # the device file's own validation, on the same plain data the loader builds
        return model.model_validate(data)
    except ValidationError as exc:
        raise SpecError(_issues(exc, data, model, f"<{where}>")) from None


def _issues(exc: ValidationError, data: Any, model: Any, where: str) -> list[SpecIssue]:
    """The loader's messages with dotted field paths.

    The loader's messages (:mod:`betvdesign.spec.messages`) with dotted field paths; union
    tags pydantic adds to a location (not keys of the data) are left out, as there.
    """
    out: list[SpecIssue] = []
    for err in exc.errors():
        loc, msg = located(err, known_fields(model))
        kept, node = [], data
        for i, el in enumerate(loc):
            last = i == len(loc) - 1
            if isinstance(node, dict) and el in node:
                kept.append(el)
                node = node[el]
            elif isinstance(node, list) and isinstance(el, int) and 0 <= el < len(node):
                kept.append(el)
                node = node[el]
            elif last and err["type"] in ("missing", "extra_forbidden"):
                kept.append(el)
        issue = SpecIssue(Location(where), dotted(tuple(kept)), msg)
        if issue not in out:
            out.append(issue)
    return out


def _plain(value: Any) -> Any:
    if isinstance(value, pint.Quantity):
        if value._REGISTRY is not ureg:
            raise SpecError(
                [
                    SpecIssue(
                        Location("<what-if>"),
                        "",
                        "quantity from another pint registry; use betvdesign.ureg",
                    )
                ]
            )
        return format_quantity(value)
    return value


def _fail(where: str, path: str, message: str) -> SpecError:
    return SpecError([SpecIssue(Location(f"<{where}>"), path, message)])


def _assign(data: dict[str, Any], path: str, value: Any, where: str) -> None:
    """Set (None: remove) ``path`` in the plain ``data``.

    Set (None: remove) ``path`` in the plain ``data``; the last key may be new (the
    validation judges it).
    """
    found = targets(data, path)
    if not found:
        parts = path.split(".")
        if any(not p for p in parts):
            raise _fail(where, path, "empty field path; write e.g. slider.beam_width")
        names = ", ".join(str(s.get("name")) for s in data.get("actuator_sets", []))
        raise _fail(where, path, f"no actuator set {parts[1]!r} (sets: {names})")
    for target in found:
        try:
            node, key = holder(data, target)
        except PathError as exc:
            raise _fail(where, exc.path, str(exc)) from None
        if value is None:
            node.pop(key, None)
        else:
            node[key] = value
