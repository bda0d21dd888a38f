"""Pydantic validation errors of a device spec as messages a designer can act on.

Shared by the loader (device files, with line and column) and the what-if helper
(:mod:`betvdesign.spec.whatif`, edits of a loaded spec): one wording for both. The model is
passed in, so this module sits below :mod:`betvdesign.spec.models` and imports nothing of it.
"""

from __future__ import annotations

import difflib
import functools
from typing import Any

_EXPECTED = {
    "model_type": "a mapping of fields",
    "model_attributes_type": "a mapping of fields",
    "dict_type": "a mapping",
    "list_type": "a list",
    "string_type": "a string",
    "int_type": "an integer",
    "float_type": "a number",
    "bool_type": "true or false",
}


def split_path(rel: str) -> tuple[Any, ...]:
    """A relative field path as a pydantic location.

    Parameters
    ----------
    rel : str
        E.g. ``"points[1].voltage"``.

    Returns
    -------
    tuple
        E.g. ``("points", 1, "voltage")``.
    """
    out: list[Any] = []
    for part in rel.split("."):
        name, _, rest = part.partition("[")
        if name:
            out.append(name)
        while rest:
            idx, _, rest = rest.partition("]")
            out.append(int(idx))
            rest = rest.lstrip("[")
    return tuple(out)


@functools.cache
def known_fields(model: Any) -> tuple[str, ...]:
    """Every field name anywhere in a model's JSON schema (for did-you-mean hints).

    Parameters
    ----------
    model : type
        A pydantic model class.

    Returns
    -------
    tuple of str
        The names, sorted.
    """
    names: set[str] = set()

    def walk(obj: Any) -> None:
        if isinstance(obj, dict):
            props = obj.get("properties")
            if isinstance(props, dict):
                names.update(props)
            for v in obj.values():
                walk(v)
        elif isinstance(obj, list):
            for v in obj:
                walk(v)

    walk(model.model_json_schema())
    return tuple(sorted(names))


def _kind_of(value: Any) -> str:
    if isinstance(value, bool):
        return f"the boolean {str(value).lower()}"
    if isinstance(value, dict):
        return "a mapping"
    if isinstance(value, list):
        return "a list"
    if value is None:
        return "nothing (null)"
    if isinstance(value, str):
        return f"the string {value!r}"
    return f"{value!r}"


def message(err: dict[str, Any], fields: tuple[str, ...] = ()) -> str:
    """The user-facing message of one pydantic error.

    Parameters
    ----------
    err : dict
        One item of ``ValidationError.errors()``.
    fields : tuple of str
        Field names for did-you-mean hints.

    Returns
    -------
    str
        The message (``"missing unit in '5': ..."``, ``"unknown field; did you mean
        'beam_length'?"``).
    """
    kind = err["type"]
    msg = str(err["msg"])
    if kind == "extra_forbidden":
        key = err["loc"][-1] if err["loc"] else ""
        close = difflib.get_close_matches(str(key), fields, n=1)
        hint = f"; did you mean '{close[0]}'?" if close else ""
        return f"unknown field{hint} (see `betv schema` for the allowed fields)"
    if kind == "missing":
        return "missing required field"
    ctx = err.get("ctx") or {}
    if kind == "too_long" and "max_length" in ctx:
        return f"{ctx.get('actual_length', 'too many')} items; the limit is {ctx['max_length']}"
    if kind == "string_too_long" and "max_length" in ctx:
        got = err.get("input")
        n = f"{len(got):,} characters" if isinstance(got, str) else "too long"
        return f"string of {n}; the limit is {ctx['max_length']:,}"
    if kind in _EXPECTED:
        return f"expected {_EXPECTED[kind]}, got {_kind_of(err.get('input'))}"
    if msg.startswith("Value error, "):
        msg = msg[len("Value error, ") :]
    if msg.startswith("Assertion failed, "):
        msg = msg[len("Assertion failed, ") :]
    return msg


def located(err: dict[str, Any], fields: tuple[str, ...] = ()) -> tuple[tuple[Any, ...], str]:
    """The location and message of one pydantic error.

    A message ``"@sub.path: text"`` (from :func:`betvdesign.spec.models.at`) moves the
    location to that sub-field.

    Parameters
    ----------
    err : dict
        One item of ``ValidationError.errors()``.
    fields : tuple of str
        Field names for did-you-mean hints.

    Returns
    -------
    tuple
        (location, message).
    """
    loc, msg = tuple(err["loc"]), message(err, fields)
    if msg.startswith("@") and ": " in msg:
        rel, msg = msg[1:].split(": ", 1)
        loc = loc + split_path(rel)
    return loc, msg


def dotted(loc: tuple[Any, ...]) -> str:
    """A pydantic location written as a field path.

    Parameters
    ----------
    loc : tuple
        E.g. ``("actuator_sets", 0, "drive", "voltage")``.

    Returns
    -------
    str
        E.g. ``"actuator_sets[0].drive.voltage"``.
    """
    out = ""
    for el in loc:
        if isinstance(el, int):
            out += f"[{el}]"
        else:
            out += ("." if out else "") + str(el)
    return out
