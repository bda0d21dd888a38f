"""betvdesign: design toolkit for bidirectional electrothermal vibromotors (BETV).

Layers (each only imports from the ones before it):
``units``/``spec`` (pint, pydantic, YAML) -> ``nondim`` (the only place units are
stripped) -> unit-free ``dynamics`` -> ``rules``, ``studies`` -> ``plots``,
``report``, ``cli``.

Notebook use::

    import betvdesign as bd
    spec = bd.load_device("devices/push_demo.yaml")
    bd.check(spec)                                  # compact verdict (HTML in Jupyter)
    bd.check(spec.replace("drive.frequency", "2.5 kHz"))
    bd.adequacy(spec)                               # is the idealised model enough?
    q = bd.ureg.Quantity("6 um")                    # the package's pint registry

The model: W. P. Shin, M. Pai, Y. Y. Lin, C. Y. Hui, N. C. Tien, "Impact dynamics of
micromachined bidirectional electrothermal vibromotors", J. Appl. Phys. 96(12),
7603–7611 (2004); restated in docs/MODEL.md.
The names below are imported on first use, so ``import betvdesign`` stays cheap.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys
import warnings
from importlib.metadata import PackageNotFoundError, version
from typing import Any

try:
    __version__ = version("betvdesign")
except PackageNotFoundError:  # pragma: no cover - running from a source tree
    __version__ = "0.0.0+unknown"

#: Public names and the module each lives in (imported lazily by ``__getattr__``).
_LAZY = {
    "ureg": "betvdesign.spec.units",
    "Quantity": "betvdesign.spec.units",
    "DeviceSpec": "betvdesign.spec.models",
    "load_device": "betvdesign.spec.loader",
    "derive": "betvdesign.nondim.device",
    "check": "betvdesign.api",
    "adequacy": "betvdesign.api",
    "CheckOptions": "betvdesign.api",
    "DeviceView": "betvdesign.checks.view",
    "SpecError": "betvdesign.errors",
}

__all__ = ["__version__", *_LAZY]

#: Modules moved into the layered packages in 0.2 (issue 20): the old import paths still
#: work for one release (each import warns once with ``DeprecationWarning``) and go after.
#: (``betvdesign.spec`` and ``betvdesign.nondim`` are packages now; they serve the names of
#: the former modules themselves.)
MOVED = {
    "betvdesign.params": "betvdesign.model.params",
    "betvdesign.domain": "betvdesign.model.domain",
    "betvdesign.damping": "betvdesign.model.damping",
    "betvdesign.rolloff": "betvdesign.model.rolloff",
    "betvdesign.outputs": "betvdesign.output.files",
    "betvdesign.siformat": "betvdesign.output.siformat",
    "betvdesign.units": "betvdesign.spec.units",
    "betvdesign.loader": "betvdesign.spec.loader",
    "betvdesign.safeyaml": "betvdesign.spec.safeyaml",
    "betvdesign.limits": "betvdesign.spec.limits",
    "betvdesign.validation": "betvdesign.spec.messages",
    "betvdesign.whatif": "betvdesign.spec.whatif",
    "betvdesign.studies.specpaths": "betvdesign.spec.paths",
    "betvdesign.derivation": "betvdesign.nondim.record",
    "betvdesign.nondim_terms": "betvdesign.nondim.terms",
    "betvdesign.studies.settling": "betvdesign.dynamics.settling",
    "betvdesign.checker": "betvdesign.checks.checker",
    "betvdesign.rules": "betvdesign.checks.rules",
    "betvdesign.ruledata": "betvdesign.checks.rules",
    "betvdesign.rules_motion": "betvdesign.checks.rules",
    "betvdesign.rules_adequacy": "betvdesign.checks.rules",
    "betvdesign.checkview": "betvdesign.checks.view",
    "betvdesign.checkview_adequacy": "betvdesign.checks.adequacy",
    "betvdesign.fidelity": "betvdesign.checks.fidelity",
    "betvdesign.studies.adequacy": "betvdesign.checks.adequacy",
    "betvdesign.studies.adequacy_data": "betvdesign.checks.adequacy",
    "betvdesign.studies.executors": "betvdesign.studies.engine.executors",
    "betvdesign.studies.runner": "betvdesign.studies.engine.runner",
    "betvdesign.studies.store": "betvdesign.studies.engine.store",
    "betvdesign.studies.grid": "betvdesign.studies.engine.grid",
    "betvdesign.studies.validation": "betvdesign.paper.study",
    "betvdesign.studies.validation_common": "betvdesign.paper.common",
    "betvdesign.studies.validation_maps": "betvdesign.paper.maps",
    "betvdesign.studies.validation_slider": "betvdesign.paper.slider",
    "betvdesign.studies.validation_vertical": "betvdesign.paper.vertical",
    "betvdesign.plots._figure": "betvdesign.plots.figure",
}


class _MovedModule(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Resolves an old module path to the module now at its new path (with a warning)."""

    def find_spec(self, fullname: str, path: Any, target: Any = None) -> Any:
        if fullname not in MOVED:
            return None
        return importlib.util.spec_from_loader(fullname, self)

    def create_module(self, spec: Any) -> Any:
        new = MOVED[spec.name]
        warnings.warn(
            f"{spec.name} moved to {new}; the old path is removed in the next release",
            DeprecationWarning,
            stacklevel=2,
        )
        return importlib.import_module(new)

    def exec_module(self, module: Any) -> None:
        """Nothing to run: the module is the one already imported at its new path."""


sys.meta_path.insert(0, _MovedModule())


def __dir__() -> list[str]:
    """The module's names with the lazily imported public ones (``load_device``,
    ``check``, ...), so ``dir(betvdesign)`` and tab completion show them."""
    return sorted(set(globals()) | set(_LAZY))


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'betvdesign' has no attribute {name!r}")
