"""The device file as given: every leaf value with its field path and line.

Shown verbatim in the report so every number can be traced to the file. This is
display only; validation is the loader's job (the file has already passed it).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ruamel.yaml import YAML
from ruamel.yaml.comments import CommentedMap, CommentedSeq

from betvdesign.report.model import InputRow


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
