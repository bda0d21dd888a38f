"""Dotted field paths into a device spec: resolve them, read and replace the values.

The one home of the idea. A path is written as in the device file:
``slider.beam_width``, ``material.density``, ``actuator_sets.0.drive.voltage`` or
``actuator_sets.forward.drive.voltage`` (one actuator set, by index or by name). A path
that starts inside an actuator set (:data:`SET_FIELDS`: ``head.mass``,
``contact.friction``, ``actuator.vertical_resonance``, ``drive.voltage``, ...) without
naming the set addresses that field in every set.

:func:`targets` resolves a path into full key paths (:data:`Target`); the functions
below follow them through any of the trees a device takes:

- a :class:`~betvdesign.spec.models.DeviceSpec` (pydantic models): :func:`value_at`,
  :func:`given`, and :func:`replace` / :func:`with_values`, copies *without* validation
  (the values may be numpy arrays of samples; whatever is derived from the result goes
  through :mod:`betvdesign.nondim.device`, files written from it through the loader);
- the plain data of a spec (``model_dump``): :func:`holder` gives the mapping a value
  goes into; :mod:`betvdesign.spec.whatif` edits it and validates the result like a
  device file;
- the YAML tree of the file itself (ruamel round-trip mappings): the same
  :func:`holder`, so ``betv fix`` writes the user's own file back with its comments.
"""

from __future__ import annotations

import difflib
from collections.abc import Mapping, MutableMapping, Sequence
from typing import Any, TypeVar

import pint
from pydantic import BaseModel

#: A resolved path: the keys from the device down to the field, an actuator set by its
#: index, e.g. ``("actuator_sets", 0, "drive", "voltage")``.
Target = tuple[str | int, ...]

#: A device: a spec (pydantic models), its plain data or the YAML tree of its file.
Tree = BaseModel | Mapping[str, Any]
#: The type :func:`replace` and :func:`with_values` copy and return.
T = TypeVar("T", bound=BaseModel)

#: First keys of the paths relative to an actuator set (applied to every set when the
#: path names no set).
SET_FIELDS = ("head", "contact", "actuator", "drive", "intended_mode", "impact_direction")


class PathError(ValueError):
    """A path through a section the tree does not have.

    Parameters
    ----------
    path : str
        The dotted path down to the missing section.
    message : str
        What is wrong, with the closest section names.
    """

    def __init__(self, path: str, message: str) -> None:
        super().__init__(message)
        self.path = path


def is_set_field(field: str) -> bool:
    """Whether ``field`` is relative to an actuator set (``drive.voltage``).

    Parameters
    ----------
    field : str
        A dotted field path.

    Returns
    -------
    bool
        True when its first key is one of :data:`SET_FIELDS`.
    """
    return field.split(".", 1)[0] in SET_FIELDS


def in_set(field: str, index: int) -> str:
    """The path of ``field`` in actuator set ``index`` only.

    Parameters
    ----------
    field : str
        A dotted field path (``drive.frequency``, ``slider.beam_width``).
    index : int
        Index of the actuator set.

    Returns
    -------
    str
        ``actuator_sets.<index>.<field>`` for a field of a set; ``field`` itself for a
        field outside the sets.
    """
    return f"actuator_sets.{index}.{field}" if is_set_field(field) else field


def text(target: Target) -> str:
    """A resolved path written back as a dotted path (``actuator_sets.0.drive.voltage``).

    Parameters
    ----------
    target : Target
        Keys from :func:`targets`.

    Returns
    -------
    str
        The keys joined by dots.
    """
    return ".".join(str(k) for k in target)


def _child(node: Any, key: str | int) -> Any:
    """The value below ``node`` at ``key``; None where there is none."""
    if isinstance(node, BaseModel):
        return getattr(node, key) if key in type(node).model_fields else None
    if isinstance(node, Mapping):
        return node.get(key)
    if isinstance(node, list) and isinstance(key, int) and 0 <= key < len(node):
        return node[key]
    return None


def _sets(tree: Any) -> Sequence[Any]:
    return _child(tree, "actuator_sets") or []


def set_index(tree: Tree, key: str) -> int | None:
    """The index of the actuator set a path names: by index, else by name.

    Parameters
    ----------
    tree : DeviceSpec or Mapping
        The device (a spec, its plain data or its YAML tree).
    key : str
        The set as a path gives it: ``"0"`` or ``"forward"``.

    Returns
    -------
    int or None
        The index; None when the device has no such set.
    """
    sets = _sets(tree)
    if key.isdigit() and int(key) < len(sets):
        return int(key)
    names = [_child(s, "name") for s in sets]
    return names.index(key) if key in names else None


def targets(tree: Tree, field: str) -> list[Target]:
    """The full key paths ``field`` addresses in ``tree``.

    Parameters
    ----------
    tree : DeviceSpec or Mapping
        The device (a spec, its plain data or its YAML tree).
    field : str
        A dotted field path (see the module docstring).

    Returns
    -------
    list of Target
        One per actuator set for a path relative to a set; one otherwise. Empty when the
        path has an empty part or names an actuator set the device does not have. The
        targets are not checked further: :func:`value_at` is None where a field is absent.
    """
    parts = field.split(".")
    if any(not p for p in parts):
        return []
    if parts[0] in SET_FIELDS:
        return [("actuator_sets", i, *parts) for i in range(len(_sets(tree)))]
    if parts[0] == "actuator_sets" and len(parts) > 2:
        i = set_index(tree, parts[1])
        return [] if i is None else [("actuator_sets", i, *parts[2:])]
    return [tuple(parts)]


def value_at(tree: Tree, target: Target) -> Any:
    """The value at a resolved path.

    Parameters
    ----------
    tree : DeviceSpec or Mapping
        The device (a spec, its plain data or its YAML tree).
    target : Target
        Keys from :func:`targets`.

    Returns
    -------
    Any
        The value (a quantity, a number, a sub-model or mapping); None where the tree
        has no such field or the field is not given.
    """
    node = tree
    for key in target:
        node = _child(node, key)
        if node is None:
            return None
    return node


def given(tree: Tree, field: str) -> list[Any]:
    """The values ``field`` holds in ``tree``, absent ones left out.

    Parameters
    ----------
    tree : DeviceSpec or Mapping
        The device.
    field : str
        A dotted field path.

    Returns
    -------
    list
        One value per target that holds one (per actuator set for a set field).
    """
    values = (value_at(tree, t) for t in targets(tree, field))
    return [v for v in values if v is not None]


def numeric(value: Any) -> bool:
    """Whether ``value`` is one studies may vary.

    Parameters
    ----------
    value : Any
        A field's value.

    Returns
    -------
    bool
        True for a pint quantity or a plain float (not a bool, an int or a text).
    """
    return isinstance(value, pint.Quantity) or (
        isinstance(value, float) and not isinstance(value, bool)
    )


def holder(tree: MutableMapping[str, Any], target: Target) -> tuple[Any, str | int]:
    """The mapping of a plain or YAML tree that holds the last key of ``target``.

    Parameters
    ----------
    tree : MutableMapping
        The plain data of a spec or the YAML tree of a device file.
    target : Target
        Keys from :func:`targets`; every key but the last must exist (the last may be
        new: a value is set or removed there).

    Returns
    -------
    tuple
        ``(mapping, key)``: set ``mapping[key]`` to change the field.

    Raises
    ------
    PathError
        A section on the way is missing (with the closest section names).
    """
    node: Any = tree
    for depth, key in enumerate(target[:-1]):
        child = _child(node, key)
        into_set = isinstance(child, list) and isinstance(target[depth + 1], int)
        if not (isinstance(child, MutableMapping) or into_set):
            sections = [k for k, v in node.items() if isinstance(v, Mapping)]
            close = difflib.get_close_matches(str(key), sections)
            hint = f"; did you mean {close[0]!r}?" if close else ""
            raise PathError(text(target[: depth + 1]), f"no section {key!r} in this device{hint}")
        node = child
    return node, target[-1]


def replace(tree: Any, target: Target, value: Any) -> Any:
    """A copy of ``tree`` with ``value`` at a resolved path, *not* validated.

    Parameters
    ----------
    tree : DeviceSpec
        The device (pydantic models; plain mappings and lists are copied alike).
    target : Target
        Keys from :func:`targets`.
    value : Any
        The new value: a quantity, a number, or a numpy array of samples of either.

    Returns
    -------
    DeviceSpec
        The copy (``model_copy`` along the path; ``tree`` is unchanged).

    Raises
    ------
    PathError
        The tree has no section or field at ``target``.
    """
    if not target:
        return value
    key, rest = target[0], target[1:]
    child = _child(tree, key)
    known = (
        key in type(tree).model_fields
        if isinstance(tree, BaseModel)
        else isinstance(tree, Mapping) or child is not None
    )
    if not known or (rest and child is None):
        raise PathError(str(key), f"no field {key!r} here")
    new = replace(child, rest, value)
    if isinstance(tree, BaseModel):
        return tree.model_copy(update={key: new})
    if isinstance(tree, list):
        return [new if i == key else item for i, item in enumerate(tree)]
    return {**tree, key: new}


def with_values(spec: T, values: Mapping[str, Any]) -> T:
    """``spec`` with each field path set to its value, *not* validated.

    Parameters
    ----------
    spec : DeviceSpec
        The device.
    values : Mapping
        Field path -> value (a quantity, a float, or a numpy array of samples).

    Returns
    -------
    DeviceSpec
        The copy; a field of the actuator sets is set in every set that gives it.
    """
    for name, value in values.items():
        for target in targets(spec, name):
            if value_at(spec, target) is not None:
                spec = replace(spec, target, value)
    return spec
