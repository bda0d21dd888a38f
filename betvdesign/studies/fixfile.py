"""The device file with a fix applied: the user's own YAML, comments kept, changed
values marked with a comment saying what changed and why, verified by ``betv check``.
"""

from __future__ import annotations

import io
from pathlib import Path
from typing import Any

from betvdesign.errors import BetvError
from betvdesign.spec.paths import holder, targets, value_at


def fixed_text(path: str | Path, res: Any, cand: Any) -> str:
    """The text of ``path`` with ``cand``'s changes applied; raises :class:`BetvError`
    if the result does not load or does not pass ``betv check`` (never written then)."""
    from ruamel.yaml import YAML

    from betvdesign.checks.checker import check_derivation
    from betvdesign.nondim.device import derive
    from betvdesign.spec.loader import load_device_text
    from betvdesign.spec.units import format_quantity

    yaml = YAML(typ="rt")
    yaml.preserve_quotes = True
    yaml.width = 100
    data = yaml.load(Path(path).read_text("utf-8"))
    for f, x in cand.changes.items():
        v = res.varies[f]
        q = v.quantity(x)
        new = format_quantity(q, ".4g") if v.unit else float(f"{x:.4g}")
        old = v.text(v.x0)
        for target in targets(data, f):  # every actuator set that gives the field
            if value_at(data, target) is None:
                continue
            node, key = holder(data, target)
            node[key] = new
            node.yaml_add_eol_comment(f"betv fix: was {old}; {cand.why}", key)
    buf = io.StringIO()
    yaml.dump(data, buf)
    text = f"# Fixed by `betv fix {Path(path).name}`: {res.message}\n" + buf.getvalue()
    check = check_derivation(derive(load_device_text(text, str(path))))
    if check.verdict != "pass":
        failing = ", ".join(r.id for r in check.rules if r.severity == "error" and not r.passed)
        raise BetvError(f"the fixed file does not pass betv check ({failing}); not written")
    return text
