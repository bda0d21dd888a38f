"""Project defaults for the CLI from a ``[tool.betv]`` table in ``pyproject.toml``.

Like ruff and mypy, ``betv`` looks for the nearest ``pyproject.toml`` in the
current directory or its parents; options given on the command line win::

    [tool.betv]
    select = ["frequency-window", "mode"]   # rules that count (default: all)
    ignore = ["published-fit"]              # rules that do not count
    target-speed = "1 mm/s"                 # required slider speed (adds a rule)

An unknown key, a wrong type or a file that is not TOML is bad input (exit 2).
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from pathlib import Path

from betvdesign.errors import UsageError

KEYS = ("select", "ignore", "target-speed")


@dataclass(frozen=True)
class Config:
    """Defaults of ``betv check`` (``source``: the file they came from, or "")."""

    select: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()
    target_speed: str | None = None
    source: str = ""


def find_pyproject(start: Path | None = None) -> Path | None:
    """The nearest ``pyproject.toml`` at or above ``start`` (default: the cwd)."""
    here = (start or Path.cwd()).resolve()
    for d in (here, *here.parents):
        p = d / "pyproject.toml"
        if p.is_file():
            return p
    return None


def load_config(path: Path | None = None) -> Config:
    """Read ``[tool.betv]`` of ``path`` (default: :func:`find_pyproject`); no table,
    no file: the built-in defaults."""
    path = path or find_pyproject()
    if path is None:
        return Config()
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as exc:
        raise UsageError(f"{path}: cannot read: {exc.strerror}") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise UsageError(f"{path}: not valid TOML: {exc}") from None
    table = data.get("tool", {}).get("betv")
    if table is None:
        return Config()
    where = f"{path}: [tool.betv]"
    if not isinstance(table, dict):
        raise UsageError(f"{where} must be a table")
    unknown = sorted(set(table) - set(KEYS))
    if unknown:
        raise UsageError(f"{where}: unknown key {unknown[0]!r} (keys: {', '.join(KEYS)})")
    lists = {}
    for key in ("select", "ignore"):
        v = table.get(key, [])
        if not isinstance(v, list) or not all(isinstance(x, str) and x for x in v):
            raise UsageError(f'{where}: {key} must be a list of rule ids, e.g. ["mode"]')
        lists[key] = tuple(v)
    speed = table.get("target-speed")
    if speed is not None and not isinstance(speed, str):
        raise UsageError(f"{where}: target-speed must be a string with a unit, e.g. '1 mm/s'")
    return Config(lists["select"], lists["ignore"], speed, str(path))
