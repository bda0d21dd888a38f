"""Size and documentation of the betvdesign source, per package (issue 28's counts).

    python scripts/codeaudit.py            # per-package table and every function > 80 lines
    python scripts/codeaudit.py --long 60  # another length threshold
    python scripts/codeaudit.py --check    # exit 1 if a long function gives no reason

Counted with :mod:`ast`, nothing imported:

- *lines*: physical lines of the package's ``.py`` files;
- *long functions*: every ``def`` (nested ones too) whose ``end_lineno - lineno + 1``
  exceeds the threshold, decorators not counted; one whose docstring says why
  (:data:`REASON`, e.g. "Over 80 lines on purpose: ...") is marked as such;
- *numpydoc coverage*: of the public functions and methods (module-level ``def`` and
  ``def`` directly in a class, names without a leading underscore, in a module whose
  name has none either; ``__init__.py`` counts as public), the share whose docstring
  has a numpydoc ``Parameters``, ``Returns`` or ``Yields`` section (the heading followed
  by a line of dashes).
"""

from __future__ import annotations

import argparse
import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PKG = ROOT / "betvdesign"
REASON = re.compile(r"over \d+ lines on purpose", re.IGNORECASE)
SECTION = re.compile(r"^\s*(Parameters|Returns|Yields)\s*\n\s*-{3,}\s*$", re.MULTILINE)


def package_of(path: Path) -> str:
    """Name the package a source file belongs to.

    Parameters
    ----------
    path
        A ``.py`` file under ``betvdesign/``.

    Returns
    -------
    str
        The first-level subpackage (``dynamics``), or the module name for a top-level
        module (``api``).
    """
    rel = path.relative_to(PKG)
    return rel.parts[0] if len(rel.parts) > 1 else rel.stem


def public_defs(tree: ast.Module) -> list[ast.FunctionDef | ast.AsyncFunctionDef]:
    """List the public functions and methods of a module.

    Parameters
    ----------
    tree
        The parsed module.

    Returns
    -------
    list of ast.FunctionDef
        Module-level functions and methods of module-level classes whose names (and
        class names) do not start with an underscore.
    """
    fdef = (ast.FunctionDef, ast.AsyncFunctionDef)
    out = []
    for node in tree.body:
        if isinstance(node, fdef) and not node.name.startswith("_"):
            out.append(node)
        elif isinstance(node, ast.ClassDef) and not node.name.startswith("_"):
            out += [n for n in node.body if isinstance(n, fdef) and not n.name.startswith("_")]
    return out


def audit(long: int) -> tuple[dict[str, list[int]], list[tuple[int, str, bool]]]:
    """Count lines, documented public functions and long functions per package.

    Parameters
    ----------
    long
        Length threshold [lines]: functions longer than this are listed.

    Returns
    -------
    table : dict of str to list of int
        Per package: ``[lines, public functions, with a numpydoc section]``.
    longs : list of (int, str, bool)
        ``(length, "module:function", reason given)`` of every function over the
        threshold, longest first.
    """
    table: dict[str, list[int]] = {}
    longs: list[tuple[int, str, bool]] = []
    for path in sorted(PKG.rglob("*.py")):
        src = path.read_text()
        tree = ast.parse(src)
        row = table.setdefault(package_of(path), [0, 0, 0])
        row[0] += len(src.splitlines())
        if not path.stem.startswith("_") or path.stem == "__init__":
            for f in public_defs(tree):
                row[1] += 1
                row[2] += bool(SECTION.search(ast.get_docstring(f) or ""))
        mod = ".".join(path.relative_to(ROOT).with_suffix("").parts)
        for node in ast.walk(tree):
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                n = node.end_lineno - node.lineno + 1
                if n > long:
                    why = bool(REASON.search(ast.get_docstring(node) or ""))
                    longs.append((n, f"{mod}:{node.name}", why))
    longs.sort(key=lambda t: (-t[0], t[1]))
    return table, longs


def main() -> None:
    """Print the per-package table and the long functions.

    With ``--check`` exit with status 1 when a long function gives no reason.
    """
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--long", type=int, default=80, help="length threshold [lines]")
    ap.add_argument(
        "--check", action="store_true", help="exit 1 if a long function gives no reason"
    )
    args = ap.parse_args()
    table, longs = audit(args.long)
    print(f"{'package':<12}{'lines':>7}{'public':>8}{'numpydoc':>10}{'share':>7}")
    tot = [0, 0, 0]
    for name, (n, pub, doc) in sorted(table.items()):
        tot = [tot[0] + n, tot[1] + pub, tot[2] + doc]
        share = f"{100 * doc / pub:.0f} %" if pub else "-"
        print(f"{name:<12}{n:>7}{pub:>8}{doc:>10}{share:>7}")
    print(f"{'total':<12}{tot[0]:>7}{tot[1]:>8}{tot[2]:>10}{100 * tot[2] / tot[1]:>5.0f} %")
    print(f"\n{len(longs)} functions over {args.long} lines:")
    for n, name, why in longs:
        print(f"{n:>5}  {name}" + ("  (reason given)" if why else ""))
    if args.check and not all(why for *_, why in longs):
        raise SystemExit(1)


if __name__ == "__main__":
    main()
