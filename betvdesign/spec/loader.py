"""YAML device and process files -> validated specs.

YAML device files -> :class:`~betvdesign.spec.models.DeviceSpec` (and process files ->
:class:`~betvdesign.spec.process.Process`), with errors a user can act on.

Every problem found in a file is collected and raised together as one
:class:`~betvdesign.errors.SpecError` whose issues print as
``file:line:col: field.path: message``. YAML 1.2 semantics (ruamel.yaml round-trip
loader: ``yes``/``no`` stay strings, ``0.4`` is a float); duplicate keys are errors.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from pydantic import ValidationError
from ruamel.yaml.comments import CommentedMap, CommentedSeq
from ruamel.yaml.error import MarkedYAMLError, YAMLError
from ruamel.yaml.nodes import MappingNode, Node, SequenceNode
from ruamel.yaml.reader import ReaderError

from betvdesign.errors import Location, SpecError, SpecIssue
from betvdesign.output import answers
from betvdesign.spec import limits, safeyaml
from betvdesign.spec.messages import known_fields, located, message
from betvdesign.spec.models import DeviceSpec
from betvdesign.spec.process import Process, shipped_process_path, shipped_processes


def load_device(path: str | Path) -> DeviceSpec:
    """Read and validate one device file.

    The file is read within the size limit of :mod:`betvdesign.spec.limits` (UTF-8, with
    or without BOM, or UTF-16 with a BOM) and checked by :func:`load_device_text`.

    Parameters
    ----------
    path : str or Path
        The device YAML file.

    Returns
    -------
    DeviceSpec
        The validated device.

    Raises
    ------
    SpecError
        Listing every issue, each at ``file:line:col`` with its field path.
    """
    path = Path(path)
    return load_device_text(safeyaml.read_text(path), str(path))


def load_device_text(text: str, filename: str = "<string>") -> DeviceSpec:
    """Validate device YAML given as text.

    A ``process:`` naming a shipped process or a file (relative to ``filename``'s
    directory) is loaded here (:func:`resolve_process`); its problems are reported at the
    ``process`` line of the device file, with the process file's own positions.

    Parameters
    ----------
    text : str
        The YAML text.
    filename : str
        Used in messages.

    Returns
    -------
    DeviceSpec
        The validated device.

    Raises
    ------
    SpecError
        Listing every issue (limits of :mod:`betvdesign.spec.limits`, malformed YAML,
        duplicate keys, validation), each at ``file:line:col`` with its field path.
    """
    return load_model_text(text, filename, DeviceSpec, _DEVICE_HINT)


_DEVICE_HINT = "expected a mapping with 'name', 'slider', 'actuator_sets'"


def load_process(path: str | Path) -> Process:
    """Read and validate one process file (:mod:`betvdesign.spec.process`).

    A file read before and unchanged since (same size and modification time) is not
    read again (a process is frozen data).

    Parameters
    ----------
    path : str or Path
        The process YAML file.

    Returns
    -------
    Process
        The validated process.

    Raises
    ------
    SpecError
        Listing every issue, each at ``file:line:col`` with its field path.
    """
    path = Path(path)
    try:
        st = path.stat()
        key = (str(path.resolve()), str(path), st.st_mtime_ns, st.st_size)
    except OSError:
        key = None
    if key is not None and key in _PROCESSES:
        answers.note_read(path)  # read earlier in this process: still an input
        return _PROCESSES[key]
    proc = load_model_text(
        safeyaml.read_text(path), str(path), Process, "expected a mapping with 'name', 'layers'"
    )
    if key is not None:
        if len(_PROCESSES) >= 64:
            _PROCESSES.clear()
        _PROCESSES[key] = proc
    return proc


_PROCESSES: dict[tuple, Process] = {}


def resolve_process(ref: str, base_dir: str | Path | None = None) -> Process:
    """The process a device names.

    Parameters
    ----------
    ref : str
        A shipped process's name (``polymumps``) or the path of a process file.
    base_dir : str or Path, optional
        The directory a relative path is taken from (the device file's).

    Returns
    -------
    Process
        The validated process.

    Raises
    ------
    SpecError
        An unknown name (listing the shipped ones), or the process file's issues.
    """
    shipped = shipped_process_path(ref)
    if shipped is not None:
        return load_process(shipped)
    path = Path(ref)
    if not path.is_absolute() and base_dir is not None:
        path = Path(base_dir) / path
    if path.suffix.lower() not in (".yaml", ".yml") or not path.is_file():
        known = ", ".join(shipped_processes())
        raise _one(
            ref,
            f"no shipped process {ref!r} and no process file {str(path)!r} "
            f"(shipped: {known}; or give the path of your own process file)",
        )
    return load_process(path)


def _parse_yaml(text: str, filename: str) -> tuple[Any, list[SpecIssue]]:
    """Parse YAML text within the size limits, finding every duplicate key.

    Parameters
    ----------
    text : str
        The YAML text.
    filename : str
        The file, for messages.

    Returns
    -------
    data : Any
        The round-trip data (None for an empty text).
    issues : list of SpecIssue
        The duplicate keys (the caller adds what validation finds).

    Raises
    ------
    SpecError
        At a crossed limit (:func:`safeyaml.load`) or malformed YAML, with its
        ``file:line:col`` where known.
    """
    issues: list[SpecIssue] = []
    try:  # one parse, bounded: each event is checked before the composer takes it
        root_node, data = safeyaml.load(text, filename, allow_duplicate_keys=True)
        issues.extend(_duplicate_keys(root_node, filename))  # all of them, on the tree
    except MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        loc = Location(filename, mark.line + 1, mark.column + 1) if mark else Location(filename)
        problem = exc.problem or exc.context or "malformed YAML"
        cm = exc.context_mark
        if exc.problem and exc.context and cm is not None and cm is not mark:
            problem += f" ({exc.context} at line {cm.line + 1}, column {cm.column + 1})"
        raise SpecError([*issues, SpecIssue(loc, "", f"invalid YAML: {problem}")]) from None
    except YAMLError as exc:  # a ReaderError (control character) knows only its offset
        pos = exc.position if isinstance(exc, ReaderError) else None
        loc = Location(filename)
        msg = str(exc).split("\n")[0]
        if isinstance(pos, int) and 0 <= pos <= len(text):
            line = text.count("\n", 0, pos) + 1
            loc = Location(filename, line, pos - (text.rfind("\n", 0, pos) + 1) + 1)
            msg = msg.split(":")[0].strip() + " (a control character in a text file)"
        raise SpecError([*issues, SpecIssue(loc, "", f"invalid YAML: {msg}")]) from None
    return data, issues


def _resolve_process_ref(
    plain: dict[str, Any], data: CommentedMap, filename: str, issues: list[SpecIssue]
) -> None:
    """Replace a device's ``process:`` reference by the process it names, in ``plain``.

    Parameters
    ----------
    plain : dict
        The device file's plain data (changed in place).
    data : CommentedMap
        The round-trip data, for the reference's position.
    filename : str
        The file: a relative path is taken from its directory.
    issues : list of SpecIssue
        The issues found so far (raised with the process's).

    Raises
    ------
    SpecError
        When the process cannot be read, at the reference's ``file:line:col``.
    """
    if isinstance(plain.get("process"), str):
        try:
            base = Path(filename).parent if not filename.startswith("<") else None
            plain["process"] = resolve_process(plain["process"], base)
        except SpecError as exc:
            line, col = _key_pos(data, "process", value=True)
            nested = "; ".join(str(i) for i in exc.issues)
            issues.append(SpecIssue(Location(filename, line + 1, col + 1), "process", nested))
            raise SpecError(issues) from None


def load_model_text(text: str, filename: str, model: Any, empty_hint: str) -> Any:
    """Validate YAML text against a pydantic model with the device file's rules.

    Parameters
    ----------
    text : str
        The YAML text.
    filename : str
        Used in messages (and, for a device, the directory a relative ``process:`` path
        is taken from).
    model : type
        The pydantic model (:class:`DeviceSpec`, :class:`Process`).
    empty_hint : str
        What an empty file should have held.

    Returns
    -------
    Any
        The validated model instance.

    Raises
    ------
    SpecError
        Listing every issue (size and structure limits, malformed YAML, duplicate keys,
        validation), each at ``file:line:col`` with its field path.
    """
    cap = limits.max_file_bytes()
    if len(text) > cap:
        raise _one(
            filename,
            f"text of {len(text):,} characters; the limit is {cap:,} "
            f"(set {limits.FILE_BYTES_ENV} to raise it)",
        )
    data, issues = _parse_yaml(text, filename)
    if data is None:
        raise _one(filename, f"empty file: {empty_hint}")
    if not isinstance(data, CommentedMap):
        raise SpecError(
            [
                SpecIssue(
                    Location(filename, 1, 1),
                    "",
                    "expected a mapping at the top level, got "
                    + ("a list" if isinstance(data, list) else f"a {type(data).__name__}"),
                )
            ]
        )
    plain = _plain(data)
    if model is DeviceSpec:
        _resolve_process_ref(plain, data, filename, issues)
    try:
        spec = model.model_validate(plain)
    except ValidationError as exc:
        issues.extend(_validation_issues(exc, data, filename, model))
        raise SpecError(issues) from None
    if issues:
        raise SpecError(issues)
    return spec


# --- helpers ---------------------------------------------------------------------------


def _one(filename: str, message: str) -> SpecError:
    return SpecError([SpecIssue(Location(filename), "", message)])


def _duplicate_keys(node: Node | None, filename: str) -> list[SpecIssue]:
    """Every repeated key of every mapping in the composed node tree."""
    out: list[SpecIssue] = []
    stack: list[tuple[Node | None, str]] = [(node, "")]
    while stack:
        n, path = stack.pop()
        if isinstance(n, MappingNode):
            seen: dict[Any, int] = {}
            for knode, vnode in n.value:
                key = knode.value
                if isinstance(key, str) and key in seen:
                    m = knode.start_mark
                    out.append(
                        SpecIssue(
                            Location(filename, m.line + 1, m.column + 1),
                            _join(path, key),
                            f"duplicate key (first given on line {seen[key]})",
                        )
                    )
                elif isinstance(key, str):
                    seen[key] = knode.start_mark.line + 1
                stack.append((vnode, _join(path, key)))
        elif isinstance(n, SequenceNode):
            for i, item in enumerate(n.value):
                stack.append((item, f"{path}[{i}]"))
    return sorted(out, key=lambda i: (i.location.line or 0, i.location.col or 0))


def _join(path: str, key: Any) -> str:
    if isinstance(key, int):
        return f"{path}[{key}]"
    return f"{path}.{key}" if path else str(key)


def _plain(x: Any) -> Any:
    """Ruamel round-trip objects -> plain Python (dict, list, str, int, float, bool)."""
    if isinstance(x, dict):
        return {_plain(k): _plain(v) for k, v in x.items()}
    if isinstance(x, list):
        return [_plain(v) for v in x]
    if isinstance(x, bool) or type(x).__name__ == "ScalarBoolean":
        return bool(x)
    if isinstance(x, int):
        return int(x)
    if isinstance(x, float):
        return float(x)
    if isinstance(x, str):
        return str(x)
    return x


def _key_pos(node: CommentedMap, key: Any, *, value: bool) -> tuple[int, int]:
    """0-based (line, col) of a key (or its value) in a YAML mapping.

    0-based (line, col) of a key (or its value); keys brought in by a YAML merge key
    (``<<: *anchor``) are found in the anchored mapping; else the mapping itself.
    """
    data = node.lc.data
    if key in data:
        entry = data[key]
        return (entry[2], entry[3]) if value else (entry[0], entry[1])
    for item in node.merge:
        # ruamel versions differ: (index, map) tuples or the maps themselves
        merged = item[1] if isinstance(item, tuple) else item
        if isinstance(merged, CommentedMap) and key in merged:
            return _key_pos(merged, key, value=value)
    return node.lc.line, node.lc.col


def _item_pos(node: CommentedSeq, index: int) -> tuple[int, int]:
    data = node.lc.data
    if index in data:
        return data[index][0], data[index][1]
    return node.lc.line, node.lc.col


def _locate(
    root: CommentedMap, loc: tuple[Any, ...], *, name_missing: bool = True
) -> tuple[int, int, str]:
    """Walk a pydantic error location through the YAML data: 1-based line/col and path.

    Elements of ``loc`` that are not keys in the data (discriminator tags, union
    member names) are skipped, except a last element (a missing field) which names
    the field but keeps the position of its parent mapping.
    """
    node: Any = root
    line, col = root.lc.line, root.lc.col
    path = ""
    for i, el in enumerate(loc):
        last = i == len(loc) - 1
        if isinstance(node, CommentedMap) and el in node:
            line, col = _key_pos(node, el, value=not last)
            node = node[el]
            path = _join(path, el)
        elif isinstance(node, CommentedSeq) and isinstance(el, int) and 0 <= el < len(node):
            line, col = _item_pos(node, el)
            node = node[el]
            path = _join(path, el)
        elif last and name_missing and isinstance(el, str | int):
            path = _join(path, el)
    return line + 1, col + 1, path


def _last_key_value_pos(root: CommentedMap, loc: tuple[Any, ...]) -> tuple[int, int] | None:
    """Position of the *value* of the last key of ``loc`` (for wrong values)."""
    node: Any = root
    pos = None
    for el in loc:
        if isinstance(node, CommentedMap) and el in node:
            pos = _key_pos(node, el, value=True)
            node = node[el]
        elif isinstance(node, CommentedSeq) and isinstance(el, int) and 0 <= el < len(node):
            pos = _item_pos(node, el)
            node = node[el]
    return None if pos is None else (pos[0] + 1, pos[1] + 1)


def _validation_issues(
    exc: ValidationError, root: CommentedMap, filename: str, model: Any = DeviceSpec
) -> list[SpecIssue]:
    grouped: dict[tuple[int, int, str], list[str]] = {}
    for err in exc.errors():
        msg = message(err, known_fields(model))
        relocated = msg.startswith("@") and ": " in msg  # spec.at(): a sub-field's error
        loc, msg = located(err, known_fields(model))
        # a last loc element absent from the data names a missing field; otherwise it is
        # a union tag (e.g. "measured", "float") and is left out of the path
        name_missing = relocated or err["type"] in ("missing", "extra_forbidden")
        try:
            line, col, path = _locate(root, loc, name_missing=name_missing)
            if err["type"] not in ("extra_forbidden", "missing"):
                pos = _last_key_value_pos(root, loc)
                if pos is not None:
                    line, col = pos
        except (KeyError, IndexError, TypeError, AttributeError):  # never a traceback
            line, col, path = 0, 0, ".".join(str(x) for x in loc)
        msgs = grouped.setdefault((line, col, path), [])
        if msg not in msgs:
            msgs.append(msg)
    issues = [
        SpecIssue(Location(filename, line or None, col or None), path, "; or ".join(msgs))
        for (line, col, path), msgs in grouped.items()
    ]
    return sorted(issues, key=lambda i: (i.location.line or 0, i.location.col or 0, i.field))
