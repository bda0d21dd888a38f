"""Field descriptions of the file models from their attribute docstrings, on demand.

Every field of a model read from a file (:class:`~betvdesign.spec.process.StrictModel`)
is documented by the string literal after it, as pydantic's ``use_attribute_docstrings``
reads them. That option reads each class's source anew when the class is created (about
0.1 s for the device and process models, paid by every command); only the JSON schema
shows the descriptions (``betv schema``), so :func:`describe_fields` attaches them when
a schema is asked for: each module's source parsed once, each field given its
docstring, the models rebuilt, those a model refers to first. The schema is the one
``use_attribute_docstrings`` gives (``tests/test_cli_check.py``).
"""

from __future__ import annotations

import ast
import inspect
import sys
from typing import Any, get_args

__all__ = ["describe_fields"]

_DONE: set[type] = set()


def describe_fields(root: type) -> None:
    """Give every field of ``root`` and of the models it holds its attribute docstring.

    A field with a description of its own (``Field(description=...)``) keeps it. Done
    once per model; later calls return at once.

    Parameters
    ----------
    root : type
        A pydantic model class (e.g. :class:`~betvdesign.spec.models.DeviceSpec`).
    """
    order = _dependencies_first(root)
    todo = [cls for cls in order if cls not in _DONE]
    if not todo:
        return
    sources: dict[str, dict[str, dict[str, str]]] = {}
    for cls in todo:
        docs: dict[str, str] = {}
        for base in reversed(cls.__mro__):  # a class's own docstrings win over a base's
            if base.__module__ not in sources:
                sources[base.__module__] = _module_docstrings(base.__module__)
            docs.update(sources[base.__module__].get(base.__qualname__, {}))
        changed = False
        for name, info in cls.model_fields.items():
            if info.description is None and name in docs:
                info.description = docs[name]
                changed = True
        if changed or any(dep in todo for dep in _held_models(cls)):
            cls.model_rebuild(force=True)
        _DONE.add(cls)


def _module_docstrings(module: str) -> dict[str, dict[str, str]]:
    """Per top-level class of ``module`` (by name): field -> the string literal after it."""
    try:
        source = inspect.getsource(sys.modules[module])
    except (KeyError, OSError, TypeError):
        return {}
    out: dict[str, dict[str, str]] = {}
    for node in ast.parse(source).body:
        if not isinstance(node, ast.ClassDef):
            continue
        docs: dict[str, str] = {}
        for prev, stmt in zip(node.body, node.body[1:], strict=False):
            if (
                isinstance(prev, ast.AnnAssign)
                and isinstance(prev.target, ast.Name)
                and isinstance(stmt, ast.Expr)
                and isinstance(stmt.value, ast.Constant)
                and isinstance(stmt.value.value, str)
            ):
                docs[prev.target.id] = inspect.cleandoc(stmt.value.value)
        out[node.name] = docs
    return out


def _held_models(cls: type) -> set[type]:
    """The pydantic models named in the annotations of ``cls``'s fields."""
    found: set[type] = set()

    def walk(tp: Any) -> None:
        if isinstance(tp, type) and hasattr(tp, "model_fields"):
            found.add(tp)
        for arg in get_args(tp):
            walk(arg)

    for info in cls.model_fields.values():
        walk(info.annotation)
    return found


def _dependencies_first(root: type) -> list[type]:
    """``root`` and every model it holds, each after the models it holds (post-order)."""
    order: list[type] = []
    seen: set[type] = set()

    def visit(cls: type) -> None:
        if cls in seen:
            return
        seen.add(cls)
        for dep in sorted(_held_models(cls), key=lambda c: c.__qualname__):
            visit(dep)
        order.append(cls)

    visit(root)
    return order
