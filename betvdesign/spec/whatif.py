"""What-if edits of a device spec, validated exactly like a device file.

``spec.replace("slider.beam_width", "6 um")`` (:meth:`betvdesign.spec.models.DeviceSpec.replace`)
returns a new, validated :class:`~betvdesign.spec.models.DeviceSpec`; the original is frozen
and unchanged. The edited spec is written back to YAML and read by
:func:`betvdesign.spec.loader.load_device_text`, so a bad value raises the same
:class:`~betvdesign.errors.SpecError` (field path, message, did-you-mean) a device
file would, never an error deep inside the derivation.

Paths are dotted, as in the device file: ``slider.beam_width``, ``material``,
``actuator_sets.0.drive.voltage`` or ``actuator_sets.forward.drive.voltage`` (a set by
index or name). Paths below an actuator set without the set (``drive.voltage``,
``head.mass``, ``contact.friction``, ``actuator.vertical_resonance``) apply to every set,
as in tolerance studies.
"""

from __future__ import annotations

import difflib
from typing import Any

from pydantic import ValidationError

from betvdesign.errors import Location, SpecError, SpecIssue
from betvdesign.spec.messages import dotted, known_fields, located

#: Paths relative to an actuator set (applied to every set when no set is named).
SET_PREFIXES = ("head", "contact", "actuator", "drive", "intended_mode", "impact_direction")


def replace(spec: Any, path: str, value: Any, *more: tuple[str, Any]) -> Any:
    """A copy of ``spec`` with ``path`` set to ``value`` (and each ``(path, value)`` of
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
    """The loader's messages (:mod:`betvdesign.spec.messages`) with dotted field paths; union
    tags pydantic adds to a location (not keys of the data) are left out, as there."""
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
    if hasattr(value, "units") and hasattr(value, "magnitude"):
        from betvdesign.spec.units import format_quantity, ureg

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
    parts = path.split(".")
    if not path or any(not p for p in parts):
        raise _fail(where, path, "empty field path; write e.g. slider.beam_width")
    sets = data.get("actuator_sets", [])
    if parts[0] in SET_PREFIXES:  # every set
        for i in range(len(sets)):
            _set_in(sets[i], parts, value, where, f"actuator_sets.{i}.")
        return
    if parts[0] == "actuator_sets" and len(parts) > 2:
        key = parts[1]
        names = [s.get("name") for s in sets]
        if key.isdigit() and int(key) < len(sets):
            i = int(key)
        elif key in names:
            i = names.index(key)
        else:
            raise _fail(
                where, path, f"no actuator set {key!r} (sets: {', '.join(map(str, names))})"
            )
        _set_in(sets[i], parts[2:], value, where, f"actuator_sets.{i}.")
        return
    _set_in(data, parts, value, where, "")


def _set_in(node: dict[str, Any], parts: list[str], value: Any, where: str, prefix: str) -> None:
    """Walk existing sections; the last key may be new (the validation judges it) and
    ``None`` removes it."""
    for depth, key in enumerate(parts[:-1]):
        child = node.get(key)
        if not isinstance(child, dict):
            full = prefix + ".".join(parts[: depth + 1])
            close = difflib.get_close_matches(key, [k for k in node if isinstance(node[k], dict)])
            hint = f"; did you mean {close[0]!r}?" if close else ""
            raise _fail(where, full, f"no section {key!r} in this device{hint}")
        node = child
    if value is None:
        node.pop(parts[-1], None)
    else:
        node[parts[-1]] = value
