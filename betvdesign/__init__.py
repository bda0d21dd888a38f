"""betvdesign: design toolkit for bidirectional electrothermal vibromotors (BETV).

Layers (each only imports from the ones before it; the table is
:data:`betvdesign.layers.LAYERS`, enforced by ``tests/test_layers.py``): ``errors`` ->
``model`` (unit-free facts) -> ``output`` -> ``spec`` (pint, pydantic, YAML) ->
``nondim`` (the only place units are stripped) -> unit-free ``dynamics`` -> ``checks``
(the verdict) -> ``studies`` -> ``layout`` -> ``paper`` -> ``plots`` -> ``bench`` ->
``api`` -> ``report`` -> ``explore`` -> ``cli``.

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
from typing import Any


def _version() -> str:
    """The installed distribution's version (read on first use of ``__version__``:
    ``importlib.metadata`` costs more than ``betv --help`` itself)."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("betvdesign")
    except PackageNotFoundError:  # pragma: no cover - running from a source tree
        return "0.0.0+unknown"


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


def __dir__() -> list[str]:
    """The module's names with the lazily imported public ones (``load_device``,
    ``check``, ...), so ``dir(betvdesign)`` and tab completion show them."""
    return sorted(set(globals()) | set(_LAZY) | {"__version__"})


def __getattr__(name: str) -> Any:
    if name == "__version__":
        globals()[name] = value = _version()
        return value
    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'betvdesign' has no attribute {name!r}")
