"""The house holds: no import in betvdesign runs up the layers of
:mod:`betvdesign.layers`, and docs/ARCHITECTURE.md shows that table.

Every import counts: module level or inside a function (a lazy import is a dependence
all the same), ``import a.b``, ``from a import b``, relative imports and
``importlib.import_module("...")`` / ``__import__("...")`` with a literal name. The
detector is tested on a copy of the package with upward imports planted in it.
"""

from __future__ import annotations

import ast
import importlib
import re
import shutil
from dataclasses import dataclass
from pathlib import Path

import betvdesign
from betvdesign.layers import LAYERS, layer_of, markdown_table

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = Path(betvdesign.__file__).resolve().parent
DOC = ROOT / "docs" / "ARCHITECTURE.md"


@dataclass(frozen=True)
class Import:
    """One import found in a module: where it is and the module it names."""

    file: Path
    line: int
    target: str  # dotted module name inside the package, or the package itself


def module_names(pkg_dir: Path) -> dict[str, Path]:
    """Dotted name -> file, for every module of the package at ``pkg_dir``."""
    names = {}
    for f in sorted(pkg_dir.rglob("*.py")):
        parts = (pkg_dir.name, *f.relative_to(pkg_dir).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        names[".".join(parts)] = f
    return names


def _literal_import_call(node: ast.Call) -> str | None:
    """The literal module name of ``importlib.import_module("x")`` / ``__import__("x")``."""
    func = node.func
    name = func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", None)
    if name not in {"import_module", "__import__"} or not node.args:
        return None
    arg = node.args[0]
    return arg.value if isinstance(arg, ast.Constant) and isinstance(arg.value, str) else None


def imports_of(name: str, file: Path, modules: dict[str, Path]) -> list[Import]:
    """Every import of the package's own modules that ``file`` (module ``name``) makes."""
    pkg = name.split(".")[0]
    is_init = file.name == "__init__.py"
    found: list[Import] = []

    def add(node: ast.AST, dotted: str) -> None:
        imp = Import(file, node.lineno, dotted)  # type: ignore[attr-defined]
        if (dotted == pkg or dotted.startswith(pkg + ".")) and imp not in found:
            found.append(imp)

    for node in ast.walk(ast.parse(file.read_text(encoding="utf-8"), str(file))):
        if isinstance(node, ast.Import):
            for alias in node.names:
                add(node, alias.name)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = name.split(".")
                base = base[: len(base) - node.level + (1 if is_init else 0)]
                prefix = ".".join([*base, *([node.module] if node.module else [])])
            else:
                prefix = node.module or ""
            for alias in node.names:
                # ``from a import b``: the module a.b when b is one, else a itself
                # (from the root, a name it serves: ``from betvdesign import check``)
                sub = f"{prefix}.{alias.name}"
                add(node, sub if sub in modules or prefix == pkg else prefix)
        elif isinstance(node, ast.Call):
            literal = _literal_import_call(node)
            if literal is not None:
                add(node, literal)
    return found


def upward_imports(pkg_dir: Path) -> list[str]:
    """``file:line: A (layer i) imports B (layer j > i)`` for every import up the layers,
    and ``file: ... in no layer`` for a module outside the table."""
    modules = module_names(pkg_dir)
    pkg = pkg_dir.name
    lazy: dict[str, str] = getattr(betvdesign, "_LAZY", {})
    problems = []
    for name, file in modules.items():
        if name == pkg:
            continue  # the root: __version__ and the public names, imported on first use
        part = name.split(".")[1]
        try:
            own = layer_of(part)
        except KeyError as exc:
            problems.append(f"{file}: {exc.args[0]}")
            continue
        for imp in imports_of(name, file, modules):
            target = imp.target
            if target == pkg:
                continue  # ``import betvdesign``: the root is imported before any module
            first = target.split(".")[1]
            if first in lazy:  # ``from betvdesign import check``: where the name lives
                target = lazy[first]
            elif f"{pkg}.{first}" not in modules:
                continue  # the root's own names (``__version__``)
            other = target.split(".")[1]
            try:
                theirs = layer_of(other)
            except KeyError as exc:
                problems.append(f"{imp.file}:{imp.line}: {exc.args[0]}")
                continue
            if theirs > own:
                problems.append(
                    f"{imp.file}:{imp.line}: {part} (layer {own}) imports {target} "
                    f"({other}, layer {theirs}): up the layers"
                )
    return problems


def test_no_import_runs_up_the_layers() -> None:
    """Every module of betvdesign imports only from its own layer and the ones below."""
    assert upward_imports(PACKAGE) == []


def test_every_package_is_in_the_table_and_every_row_exists() -> None:
    """The table names each sub-package and top-level module once, and nothing else."""
    on_disk = {
        p.stem if p.is_file() else p.name
        for p in PACKAGE.iterdir()
        if (p.is_file() and p.suffix == ".py" and p.stem != "__init__")
        or (p.is_dir() and (p / "__init__.py").exists())
    }
    names = [layer.name for layer in LAYERS]
    assert len(names) == len(set(names))
    assert set(names) == on_disk


def _plant(path: Path, text: str) -> int:
    """Append ``text`` to a module; the line number of its first line."""
    before = path.read_text(encoding="utf-8")
    path.write_text(before + text, encoding="utf-8")
    return before.count("\n") + 1


def test_planted_upward_imports_are_found(tmp_path: Path) -> None:
    """The detector finds each kind of upward import planted in a copy of the package,
    with its file and line, and nothing else."""
    copy = tmp_path / "betvdesign"
    shutil.copytree(PACKAGE, copy, ignore=shutil.ignore_patterns("__pycache__", "data"))
    assert upward_imports(copy) == []  # the copy is as clean as the original
    plants = {
        # a lazy import inside a function: model (1 above the bottom) -> cli (top)
        copy / "model" / "params.py": "\n\ndef _planted():\n    from betvdesign.cli import app\n",
        # a relative import: spec -> checks
        copy / "spec" / "paths.py": "\nfrom ..checks import rule\n",
        # importlib with a literal name: dynamics -> report
        copy / "dynamics" / "rigid.py": (
            "\n\ndef _planted():\n"
            "    import importlib\n"
            "    return importlib.import_module('betvdesign.report.build')\n"
        ),
        # ``from betvdesign import check`` (a public name served by the root): output -> api
        copy / "output" / "numbers.py": "\nfrom betvdesign import check\n",
        # a plain ``import a.b``: plots -> report
        copy / "plots" / "figure.py": "\nimport betvdesign.report.model\n",
    }
    expected = {}
    for path, text in plants.items():
        first = _plant(path, text)
        offset = next(i for i, line in enumerate(text.splitlines()) if "import" in line)
        if "importlib.import_module" in text:
            offset = next(i for i, ln in enumerate(text.splitlines()) if "import_module" in ln)
        expected[path] = first + offset
    found = upward_imports(copy)
    assert len(found) == len(plants), found
    for path, line in expected.items():
        assert any(f.startswith(f"{path}:{line}: ") and "up the layers" in f for f in found), (
            path,
            line,
            found,
        )


def test_a_module_outside_the_table_is_named(tmp_path: Path) -> None:
    """A new package that is in no layer is an error, not a silent pass."""
    copy = tmp_path / "betvdesign"
    shutil.copytree(PACKAGE, copy, ignore=shutil.ignore_patterns("__pycache__", "data"))
    (copy / "newpart").mkdir()
    (copy / "newpart" / "__init__.py").write_text('"""New."""\n', encoding="utf-8")
    found = upward_imports(copy)
    assert found == [
        f"{copy / 'newpart' / '__init__.py'}: betvdesign.newpart is in no layer "
        "of betvdesign.layers.LAYERS"
    ]


def test_an_import_downward_or_within_a_layer_passes(tmp_path: Path) -> None:
    """Imports down the layers and inside one package are allowed (the detector does not
    flag everything)."""
    copy = tmp_path / "betvdesign"
    shutil.copytree(PACKAGE, copy, ignore=shutil.ignore_patterns("__pycache__", "data"))
    _plant(copy / "cli" / "common.py", "\nfrom betvdesign.model import params as _p\n")
    _plant(copy / "checks" / "rule.py", "\nfrom . import travel as _t\n")
    assert upward_imports(copy) == []


def _doc_table() -> str:
    text = DOC.read_text(encoding="utf-8")
    begin, end = "<!-- layers: begin -->\n", "<!-- layers: end -->"
    assert begin in text and end in text, "docs/ARCHITECTURE.md lost its layer-table markers"
    return text.split(begin, 1)[1].split(end, 1)[0]


def test_the_document_shows_the_table() -> None:
    """docs/ARCHITECTURE.md's layer table is :func:`markdown_table` (regenerate with
    ``python -m betvdesign.layers``)."""
    assert _doc_table() == markdown_table()


#: A dotted path in backquotes whose first part is a package or module of betvdesign.
_PATH = re.compile(r"`(?:betvdesign\.)?([a-z_]+(?:\.[A-Za-z_][A-Za-z0-9_]*)+)(?:\([^`]*\))?`")


def resolve(path: str) -> bool:
    """Whether ``betvdesign.<path>`` names a module or an attribute of one."""
    parts = path.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            obj: object = importlib.import_module(".".join(["betvdesign", *parts[:cut]]))
        except ModuleNotFoundError:
            continue
        for name in parts[cut:]:
            if not hasattr(obj, name):
                return False
            obj = getattr(obj, name)
        return True
    return False


def doc_paths(text: str) -> list[str]:
    """The dotted betvdesign paths the document names (``checks.rules.evaluate``)."""
    firsts = {layer.name for layer in LAYERS}
    return sorted(
        {m for m in _PATH.findall(text) if m.split(".")[0] in firsts and m.split(".")[1] != "py"}
    )


def test_the_document_names_only_paths_that_exist() -> None:
    """Every ``package.module.name`` in docs/ARCHITECTURE.md exists (no path from before a
    reorganisation survives in the document)."""
    paths = doc_paths(DOC.read_text(encoding="utf-8"))
    assert len(paths) > 100  # the document is read, not skipped
    assert [p for p in paths if not resolve(p)] == []


def test_a_stale_path_in_the_document_is_found() -> None:
    """The path check fails on names from before the reorganisation."""
    text = "`checks.rules.evaluate`, `studies.runner.Study`, `studies.validation.run_validation()`"
    assert [p for p in doc_paths(text) if not resolve(p)] == [
        "studies.runner.Study",
        "studies.validation.run_validation",
    ]
