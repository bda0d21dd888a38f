"""Device specs: units, models, loader, limits, paths and what-if edits.

Device specs: pint quantities and units, the pydantic models, the YAML loader with
file:line:col messages, input limits, spec paths (:mod:`~betvdesign.spec.paths`, the one
home of the idea) and validated what-if edits on them, and the one list of the fields a
designer changes (:mod:`~betvdesign.spec.fields`).

Above :mod:`betvdesign.model`; units live here and in :mod:`betvdesign.nondim`, which
strips them. Nothing below imports this package.

The names of the former module ``betvdesign.spec`` (now :mod:`betvdesign.spec.models`)
are still served from here for one release, with a ``DeprecationWarning``.
"""

from __future__ import annotations

import importlib
import pkgutil
import types
import warnings
from typing import Any


def __getattr__(name: str) -> Any:
    # a submodule not imported yet is not a name of the former module: ``from
    # betvdesign.spec import limits`` while models is still importing must not import it
    if name.startswith("__") or name in {m.name for m in pkgutil.iter_modules(__path__)}:
        raise AttributeError(name)
    models = importlib.import_module("betvdesign.spec.models")
    if not hasattr(models, name) or isinstance(getattr(models, name), types.ModuleType):
        # not a name of the former module (a submodule is imported by the import system)
        raise AttributeError(f"module 'betvdesign.spec' has no attribute {name!r}")
    warnings.warn(
        f"betvdesign.spec.{name} moved to betvdesign.spec.models.{name}; the old path is "
        "removed in the next release",
        DeprecationWarning,
        stacklevel=2,
    )
    value = getattr(models, name)
    globals()[name] = value  # warned once
    return value
