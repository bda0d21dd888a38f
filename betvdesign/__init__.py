"""betvdesign: design toolkit for bidirectional electrothermal vibromotors (BETV).

Layers (each only imports from the ones before it):
``units``/``spec`` (pint, pydantic, YAML) -> ``nondim`` (the only place units are
stripped) -> unit-free ``dynamics`` -> ``rules``, ``studies`` -> ``plots``,
``report``, ``cli``.
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("betvdesign")
except PackageNotFoundError:  # pragma: no cover - running from a source tree
    __version__ = "0.0.0+unknown"

__all__ = ["__version__"]
