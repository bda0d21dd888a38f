"""The device file as given: every leaf value with its field path and line.

Shown verbatim in the report so every number can be traced to the file. This is
display only; validation is the loader's job (the file has already passed it).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ruamel.yaml import YAML
from ruamel.yaml.comments import CommentedMap, CommentedSeq

from betvdesign.nondim.device import derive_file
from betvdesign.nondim.record import DeviceDerivation
from betvdesign.report.model import InputRow


@dataclass(frozen=True)
class PreparedDevice:
    """A device file that loaded and derived cleanly (input is valid)."""

    path: Path
    derivation: DeviceDerivation
    inputs: list[InputRow]


def prepare(path: str | Path) -> PreparedDevice:
    """Load, validate and derive ``path`` (raises SpecError/ParameterError on bad input)."""
    path = Path(path)
    derivation = derive_file(path)  # derived values outside the model: SpecError naming the file
    return PreparedDevice(path, derivation, device_inputs(path))


def _walk(node: Any, path: str, line: int | None, out: list[InputRow]) -> None:
    if isinstance(node, CommentedMap):
        for key, value in node.items():
            lc = node.lc.key(key) if hasattr(node, "lc") else None
            child_line = lc[0] + 1 if lc else line
            _walk(value, f"{path}.{key}" if path else str(key), child_line, out)
    elif isinstance(node, CommentedSeq):
        for i, value in enumerate(node):
            lc = node.lc.item(i) if hasattr(node, "lc") else None
            child_line = lc[0] + 1 if lc else line
            _walk(value, f"{path}[{i}]", child_line, out)
    else:
        out.append(InputRow(path=path, value=str(node), line=line))


def device_inputs(path: str | Path) -> list[InputRow]:
    """Leaf values of a device YAML file in file order [text as written]."""
    yaml = YAML(typ="rt")
    with open(path, encoding="utf-8") as fh:
        data = yaml.load(fh)
    rows: list[InputRow] = []
    _walk(data, "", None, rows)
    return rows
