"""The device file with a fix applied, verified by ``betv check``.

The device file with a fix applied: the user's own text with only the changed values'
lines edited (each value replaced in place, with a comment saying what changed and
why), verified by ``betv check`` before it is returned.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from betvdesign.errors import BetvError
from betvdesign.spec.paths import holder, targets, value_at


def _value_end(line: str, col: int, flow: bool) -> int:
    """Index just past the scalar that starts at ``col`` of ``line``."""
    if col < len(line) and line[col] in "'\"":
        q = line[col]
        i = col + 1
        while i < len(line):
            if line[i] == q and not (q == '"' and line[i - 1] == "\\"):
                if q == "'" and i + 1 < len(line) and line[i + 1] == "'":
                    i += 2
                    continue
                return i + 1
            i += 1
        return len(line)
    end = len(line)
    hash_at = line.find(" #", col)
    if hash_at >= 0:
        end = hash_at
    if flow:
        for stop in (",", "}", "]"):
            j = line.find(stop, col)
            if 0 <= j < end:
                end = j
    while end > col and line[end - 1] in " \t":
        end -= 1
    return end


def fixed_values(res: Any, cand: Any) -> dict[str, Any]:
    """The fix's new values as a device file writes them (quantities to 4 digits).

    Parameters
    ----------
    res : FixResult
        The fix search's answer.
    cand : Candidate
        The fix.

    Returns
    -------
    dict
        New value per field path.
    """
    from betvdesign.spec.units import format_quantity

    out = {}
    for f, x in cand.changes.items():
        v = res.varies[f]
        out[f] = format_quantity(v.quantity(x), ".4g") if v.unit else float(f"{x:.4g}")
    return out


def fixed_text(path: str | Path, res: Any, cand: Any) -> str:
    """The text of ``path`` with ``cand``'s changes applied.

    Only the lines holding a changed value differ from the file: the value is replaced
    in place and a comment ``# betv fix: was OLD; WHY`` added (an existing comment on
    the line is kept after it). Raises :class:`BetvError` if the result does not load
    or does not pass ``betv check`` (never written then).

    Parameters
    ----------
    path : path
        The device file.
    res : FixResult
        The fix search's answer.
    cand : Candidate
        The fix.

    Returns
    -------
    str
        The fixed file's text.
    """
    from ruamel.yaml import YAML

    from betvdesign.checks.checker import check_derivation
    from betvdesign.nondim.device import derive
    from betvdesign.spec.loader import load_device_text

    original = Path(path).read_text("utf-8")
    data = YAML(typ="rt").load(original)
    lines = original.splitlines(keepends=True)
    new_values = fixed_values(res, cand)
    for f in cand.changes:
        v = res.varies[f]
        new = str(new_values[f])
        note = f"betv fix: was {v.text(v.x0)}; {cand.why}"
        for target in targets(data, f):  # every actuator set that gives the field
            if value_at(data, target) is None:
                continue
            node, key = holder(data, target)
            row, col = node.lc.value(key)
            line = lines[row]
            body = line.rstrip("\r\n")
            eol = line[len(body) :]
            flow = bool(getattr(node, "fa", None) and node.fa.flow_style())
            end = _value_end(body, col, flow)
            rest = body[end:]
            if flow:
                body = f"{body[:col]}{new}{rest}  # {note}"
            else:
                old_comment = rest.strip()
                tail = f"; {old_comment.lstrip('#').strip()}" if old_comment else ""
                body = f"{body[:col]}{new}  # {note}{tail}"
            lines[row] = body + (eol or "\n")
    text = "".join(lines)
    check = check_derivation(derive(load_device_text(text, str(path))))
    if check.verdict != "pass":
        failing = ", ".join(r.id for r in check.rules if r.severity == "error" and not r.passed)
        raise BetvError(f"the fixed file does not pass betv check ({failing}); not written")
    return text
