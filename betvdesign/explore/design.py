"""The design being explored: the user's device file plus the values changed in the page.

A :class:`Design` holds the file's text and spec and an ordered set of edits (dotted
path -> the value as a device file writes it). Every proposed edit goes through
:meth:`betvdesign.spec.models.DeviceSpec.replace`, the device file's own validation, and
then the derivation ``betv check`` runs on a file
(:func:`betvdesign.nondim.device.derive_refusing`), so a refused value raises the same
:class:`~betvdesign.errors.SpecError` ``betv check`` gives the file and leaves the design
as it was. Every applied change can be undone (:meth:`Design.undo`, last first), and
:meth:`Design.reset` goes back to the file (itself undoable).

:meth:`Design.yaml_text` writes the user's file with only the changed values replaced,
in place (every other byte kept: comments, layout, flow mappings), a value the file does
not give yet added beside its siblings; the text is read back by
:func:`betvdesign.spec.loader.load_device_text` and must give the design's spec.
:meth:`Design.save` never overwrites a file unless told to.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from betvdesign.errors import BetvError, SpecError
from betvdesign.spec.loader import load_device_text
from betvdesign.spec.paths import is_set_field, targets

__all__ = ["Design", "SaveResult", "free_name", "set_path"]


def set_path(field: str, set_name: str | None) -> str:
    """The edit path of ``field`` (relative to an actuator set, or ``slider.``) for one set
    (``set_name``) or, with None, every set."""
    if set_name is None or not is_set_field(field):
        return field
    return f"actuator_sets.{set_name}.{field}"


def free_name(path: Path) -> Path:
    """``path`` itself when no file is there, else ``STEM-2.SUFFIX``, ``STEM-3...``."""
    if not path.exists():
        return path
    stem, suffix = path.stem, path.suffix or ".yaml"
    base = stem.rsplit("-", 1)[0] if stem.rsplit("-", 1)[-1].isdigit() else stem
    k = 2
    while (cand := path.with_name(f"{base}-{k}{suffix}")).exists():
        k += 1
    return cand


@dataclass(frozen=True)
class SaveResult:
    """What :meth:`Design.save` did: ``written`` (the path), or nothing written and
    ``message`` says why; ``exists``: only because a file is there (the caller may ask
    before overwriting it)."""

    path: Path
    written: bool
    message: str
    exists: bool = False


class Design:
    """The user's device file and the edits made in the page (see the module docstring).

    Parameters
    ----------
    text : str
        The device file's text.
    filename : str
        Its path (messages, save location).
    """

    def __init__(self, text: str, filename: str) -> None:
        self.text = text
        self.filename = filename
        self.original = _derivable(load_device_text(text, filename), filename)
        self.spec = self.original
        self.edits: dict[str, Any] = {}
        #: (edits, spec) before each undoable step, the latest last.
        self.history: list[tuple[dict[str, Any], Any]] = []

    @classmethod
    def from_file(cls, path: str | Path) -> Design:
        """Read a device file (validated; :class:`SpecError` as ``betv check`` gives it)."""
        from betvdesign.spec import safeyaml

        return cls(safeyaml.read_text(Path(path)), str(path))

    # --- edits -------------------------------------------------------------------------

    def _merged(self, changes: dict[str, Any]) -> dict[str, Any]:
        edits = dict(self.edits)
        for path, value in changes.items():
            edits.pop(path, None)
            if is_set_field(path):
                # a change to every set supersedes the per-set edits of that field
                for k in [k for k in edits if k.startswith("actuator_sets.")]:
                    if k.split(".", 2)[2] == path:
                        del edits[k]
            edits[path] = value
        return edits

    def propose(self, changes: dict[str, Any]) -> Any:
        """The spec with ``changes`` (path -> value) on top of the current edits,
        refused exactly as ``betv check`` refuses a file: validated like a device file,
        then derived (a value the model cannot take, such as a voltage where the
        calibration gives no stroke); raises that :class:`SpecError`."""
        edits = self._merged(changes)
        if not edits:
            return self.original
        items = list(edits.items())
        spec = self.original.replace(items[0][0], items[0][1], *items[1:])
        return _derivable(spec, self.filename)

    def apply(self, changes: dict[str, Any], *, merge: bool = False) -> Any:
        """Commit ``changes`` (validated first; the design is unchanged when refused).

        One undo step each, unless ``merge``: then :meth:`undo` goes back past this
        change and the one before it together (the positions of one slider drag)."""
        spec = self.propose(changes)
        if not merge or not self.history:
            self.history.append((self.edits, self.spec))
        self.edits = self._merged(changes)
        self.spec = spec
        return spec

    def undo(self) -> bool:
        """Back to the design before the last step (False: nothing to undo)."""
        if not self.history:
            return False
        self.edits, self.spec = self.history.pop()
        return True

    def reset(self) -> None:
        """Back to the file as read (one undo step, unless the design is the file)."""
        if self.edits:
            self.history.append((self.edits, self.spec))
        self.edits = {}
        self.spec = self.original

    @property
    def changed(self) -> bool:
        return self.spec != self.original

    # --- the file ----------------------------------------------------------------------

    def yaml_text(self) -> str:
        """The user's file with the changed values only (see the module docstring);
        :class:`BetvError` when the result would not read back as this design."""
        if not self.edits:
            return self.text
        text = _edited(self.text, self._leaves())
        try:
            back = load_device_text(text, self.filename)
        except SpecError as exc:  # a bug of the in-place writer, never silent
            raise BetvError(f"the edited file does not load: {exc}") from None
        if back != self.spec:
            raise BetvError("the edited file does not read back as the design shown")
        return text

    def _leaves(self) -> list[tuple[tuple[Any, ...], Any]]:
        """(YAML key path, value) of every value to write, sets resolved
        (:func:`betvdesign.spec.paths.targets`: a set field without a set goes to every
        set, a set by name to its index)."""
        out: dict[tuple[Any, ...], Any] = {}
        for path, value in self.edits.items():
            for k in targets(self.original, path):
                out[k] = value
        return list(out.items())

    def save(self, name: str, *, overwrite: bool = False) -> SaveResult:
        """Write :meth:`yaml_text` to the file ``name`` beside the device file; a name
        with a folder (absolute, ``~``, ``..``, ``a/b.yaml``) or without one is refused
        with a message (nothing written); an existing file is only replaced with
        ``overwrite``."""
        from betvdesign.output.files import check_output_file, write_atomic

        folder = Path(self.filename).resolve().parent
        name = str(name).strip()
        if not name:
            return SaveResult(
                folder,
                False,
                f"give a file name ending in .yaml (saved beside the device file, in {folder})",
            )
        if Path(name).name != name or name.startswith("~") or name in (".", ".."):
            return SaveResult(
                folder / Path(name).name,
                False,
                f"{name}: give a file name only; the design is saved beside the device file, "
                f"in {folder}",
            )
        p = folder / name
        if p.suffix.lower() not in (".yaml", ".yml"):
            return SaveResult(p, False, f"{p.name}: the file name must end in .yaml")
        try:
            check_output_file(p)
        except BetvError as exc:
            return SaveResult(p, False, str(exc))
        if p.exists() and not overwrite:
            return SaveResult(
                p, False, f"{p} exists; overwrite it, or give another name", exists=True
            )
        text = self.yaml_text()
        write_atomic(p, text)
        diff = difflib.unified_diff(self.text.splitlines(), text.splitlines(), n=0, lineterm="")
        n = sum(1 for d in diff if d.startswith("+") and not d.startswith("+++"))
        return SaveResult(p, True, f"wrote {p} ({n} changed line{'s' * (n != 1)})")


def _derivable(spec: Any, filename: str) -> Any:
    """``spec`` when the model can take it, else ``betv check``'s refusal of its file
    (:func:`betvdesign.nondim.device.derive_refusing`: a :class:`SpecError`)."""
    from betvdesign.nondim.device import derive_refusing

    derive_refusing(spec, filename)
    return spec


# --- writing values in place -------------------------------------------------------------


def _scalar_text(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, int):
        return str(value)
    s = str(value)
    needs_quotes = (
        not s
        or s[0] in "!&*{}[]|>'\"%@`#,?:-+"
        or ": " in s
        or " #" in s
        or any(c in s for c in ",[]{}")
        or s.strip() != s
        or s.lower() in ("yes", "no", "true", "false", "on", "off", "null", "~")
    )
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"' if needs_quotes else s


def _scalar_end(line: str, col: int, flow: bool) -> int:
    """End column (exclusive) of the scalar starting at ``col`` on ``line``."""
    if col < len(line) and line[col] in "\"'":
        q = line[col]
        i = col + 1
        while i < len(line):
            if line[i] == "\\" and q == '"':
                i += 2
                continue
            if line[i] == q:
                if q == "'" and i + 1 < len(line) and line[i + 1] == "'":
                    i += 2
                    continue
                return i + 1
            i += 1
        raise BetvError(f"unterminated quoted value: {line.strip()}")
    stops = [len(line)]
    if (k := line.find(" #", col)) >= 0:
        stops.append(k)
    if flow:
        for ch in ",}]":
            if (k := line.find(ch, col)) >= 0:
                stops.append(k)
    end = min(stops)
    while end > col and line[end - 1] in " \t":
        end -= 1
    return end


def _node(data: Any, keys: Iterable[Any]) -> Any:
    node = data
    for k in keys:
        node = node[k]
    return node


def _edited(text: str, leaves: list[tuple[tuple[Any, ...], Any]]) -> str:
    """``text`` with each (key path, value) written in place (None: the key removed)."""
    from ruamel.yaml import YAML

    data = YAML(typ="rt").load(text)
    lines = text.splitlines(keepends=True)
    edits: list[tuple[int, int, int, str]] = []  # (line, start, end, replacement)
    inserts: list[tuple[int, str]] = []  # (before line, new line)
    removals: list[int] = []
    for keys, value in leaves:
        try:
            parent = _node(data, keys[:-1])
        except (KeyError, IndexError, TypeError):
            raise BetvError(f"{'.'.join(map(str, keys))}: no such section in the file") from None
        key = keys[-1]
        flow = bool(parent.fa.flow_style())
        if key in parent:
            line, col = parent.lc.value(key)
            if value is None:
                kline, _ = parent.lc.key(key)
                if flow or kline != line or len(parent) == 1:
                    raise BetvError(
                        f"{'.'.join(map(str, keys))}: cannot leave this value out in place; "
                        "edit the file by hand"
                    )
                removals.append(line)
                continue
            body = lines[line].rstrip("\r\n")
            end = _scalar_end(body, col, flow)
            edits.append((line, col, end, _scalar_text(value)))
            continue
        if value is None:
            continue
        new = f"{key}: {_scalar_text(value)}"
        first = next(iter(parent))
        kline, kcol = parent.lc.key(first)
        if flow:
            last = list(parent)[-1]
            vline, vcol = parent.lc.value(last)
            body = lines[vline].rstrip("\r\n")
            end = _scalar_end(body, vcol, True)
            edits.append((vline, end, end, f", {new}"))
        elif lines[kline][:kcol].strip() == "":
            eol = "\r\n" if lines[kline].endswith("\r\n") else "\n"
            inserts.append((kline, " " * kcol + new + eol))
        else:
            raise BetvError(f"{'.'.join(map(str, keys))}: cannot add this value in place")
    for line, start, end, rep in sorted(edits, key=lambda e: (e[0], -e[1])):
        body = lines[line]
        lines[line] = body[:start] + rep + body[end:]
    for line in sorted(set(removals), reverse=True):
        del lines[line]
    for line, new in sorted(inserts, key=lambda t: -t[0]):
        shift = sum(1 for r in removals if r < line)
        lines.insert(line - shift, new)
    return "".join(lines)
