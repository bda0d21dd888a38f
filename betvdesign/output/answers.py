"""A command's answer, kept for the same inputs: ``betv check`` and ``betv report`` answer
again at once.

An answer (what the command printed on stdout and stderr, its exit status and the files
it wrote) is stored
under a key made of everything it can depend on:

- the command's name and its options, as parsed;
- each input file's path as given, its resolved path and the SHA-256 of its bytes;
- the package itself: the SHA-256 of every file of ``betvdesign`` (sources, shipped
  processes and data), so any change of the code or its data is another key;
- the Python version and the names of the installed distributions (``*.dist-info``,
  which carry the versions of numpy, numba, scipy, pint, pydantic, ...);
- what the output's form depends on: whether stdout is a terminal, the terminal's size,
  the environment variables that steer colour and width, and every ``BETV_*`` variable.

The files the command reads besides its arguments (a device's process file) are noted
while it runs (:func:`note_read`, called by the YAML reader) and stored with the answer
with their SHA-256; an answer is only given again when each of them is unchanged.
Nothing else is trusted: a missing, unreadable or malformed entry is a miss, and the
command runs as if there were no cache. Entries live in the user's cache directory
(``$XDG_CACHE_HOME/betvdesign/answers``, else ``~/.cache/...``); ``BETV_ANSWER_CACHE``
names another directory, or ``off`` (also ``0``, ``no``, ``false``) turns the cache off.
"""

from __future__ import annotations

import base64
import contextlib
import hashlib
import json
import os
import sys
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

__all__ = ["Answer", "answer_key", "cache_root", "lookup", "note_read", "recording", "store"]

#: Environment variable: the cache directory, or ``off`` to turn the cache off.
CACHE_ENV = "BETV_ANSWER_CACHE"
#: Values of :data:`CACHE_ENV` that turn the cache off.
OFF = frozenset({"off", "0", "no", "false"})
#: Entries kept, and their total size [bytes]; the oldest beyond either are removed when
#: one is stored (a report's entry holds its HTML and PDF: about 1-2 MB).
MAX_ENTRIES = 1000
MAX_BYTES = 256 * 2**20
#: Environment variables that change how the same answer is printed (rich, click).
_FORM_ENV = ("COLUMNS", "LINES", "TERM", "NO_COLOR", "FORCE_COLOR", "TTY_COMPATIBLE", "CLICOLOR")
#: Format of an entry (another format is a miss).
_FORMAT = 1


@dataclass(frozen=True)
class Answer:
    """What a command printed and how it ended.

    Attributes
    ----------
    stdout, stderr : str
        The text written to each stream.
    exit_code : int
        The process's exit status.
    files : dict of str to bytes
        Files the command wrote, by name (``betv report``: the HTML and the PDF).
    """

    stdout: str
    stderr: str
    exit_code: int
    files: Mapping[str, bytes] = field(default_factory=dict)


def cache_root() -> Path | None:
    """The cache directory, or None when :data:`CACHE_ENV` turns the cache off.

    Returns
    -------
    Path or None
        ``$BETV_ANSWER_CACHE``, else ``$XDG_CACHE_HOME/betvdesign/answers`` (default
        ``~/.cache/betvdesign/answers``).
    """
    raw = os.environ.get(CACHE_ENV, "").strip()
    if raw.lower() in OFF:
        return None
    if raw:
        return Path(raw)
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "betvdesign" / "answers"


def _file_digest(path: str | os.PathLike[str]) -> str | None:
    """SHA-256 of a file's bytes (None: not a readable regular file; a pipe or a device
    is not opened)."""
    try:
        if not os.path.isfile(path):
            return None
        with open(path, "rb") as fh:
            return hashlib.file_digest(fh, "sha256").hexdigest()
    except OSError:
        return None


_CODE: list[str] = []


def code_fingerprint() -> str:
    """SHA-256 over every file of the ``betvdesign`` package (paths and bytes; no
    ``__pycache__``), computed once per process (~20 ms).

    Returns
    -------
    str
        The hex digest.
    """
    if not _CODE:
        root = Path(__file__).resolve().parents[1]
        h = hashlib.sha256()
        for here, dirs, files in os.walk(root):
            dirs[:] = sorted(d for d in dirs if d != "__pycache__")
            for name in sorted(files):
                if name.endswith((".pyc", ".pyo")):
                    continue
                path = os.path.join(here, name)
                h.update(os.path.relpath(path, root).encode("utf-8", "surrogateescape"))
                h.update(b"\0")
                with open(path, "rb") as fh:
                    h.update(hashlib.file_digest(fh, "sha256").digest())
        _CODE.append(h.hexdigest())
    return _CODE[0]


def _installed() -> list[str]:
    """Names of the installed distributions (``name-version.dist-info``) on ``sys.path``."""
    names: set[str] = set()
    for entry in sys.path:
        try:
            with os.scandir(entry or ".") as it:
                names.update(d.name for d in it if d.name.endswith((".dist-info", ".egg-info")))
        except OSError:
            continue
    return sorted(names)


def answer_key(
    command: str, options: Mapping[str, Any], files: Sequence[str | os.PathLike[str]]
) -> str | None:
    """The key of a command's answer (None: an input file cannot be read: no caching).

    Parameters
    ----------
    command : str
        The command's name (``"check"``).
    options : Mapping
        Its parsed options, every one that can change what it prints (JSON-serialisable).
    files : sequence of path
        Its input files as given.

    Returns
    -------
    str or None
        A hex SHA-256.
    """
    inputs = []
    for f in files:
        digest = _file_digest(f)
        if digest is None:
            return None
        inputs.append([os.fspath(f), os.path.realpath(f), digest])
    env = {k: v for k, v in os.environ.items() if k in _FORM_ENV or k.startswith("BETV_")}
    parts = {
        "format": _FORMAT,
        "command": command,
        "options": dict(options),
        "inputs": inputs,
        "cwd": os.getcwd(),
        "code": code_fingerprint(),
        "python": sys.version,
        "installed": _installed(),
        "env": sorted(env.items()),
        "tty": [_isatty(sys.stdout), _isatty(sys.stderr)],
        "terminal": _terminal_sizes(),
    }
    text = json.dumps(parts, sort_keys=True, default=str)
    return hashlib.sha256(text.encode("utf-8", "surrogateescape")).hexdigest()


def _terminal_sizes() -> list[list[int] | None]:
    """The terminal size on stdin, stdout and stderr (None: not a terminal); rich sizes
    its output by the first of them."""
    sizes: list[list[int] | None] = []
    for fd in (0, 1, 2):
        try:
            sizes.append(list(os.get_terminal_size(fd)))
        except (OSError, ValueError):
            sizes.append(None)
    return sizes


def _isatty(stream: Any) -> bool:
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError, OSError):
        return False


_READS: list[list[str]] = []


def note_read(path: str | os.PathLike[str]) -> None:
    """Record that ``path`` was read while an answer is being recorded (:func:`recording`);
    nothing happens otherwise."""
    for log in _READS:
        log.append(os.path.realpath(path))


@contextlib.contextmanager
def recording() -> Iterator[list[str]]:
    """Collect the paths given to :func:`note_read` while the block runs.

    Yields
    ------
    list of str
        The resolved paths read, in order (filled as the block runs).
    """
    log: list[str] = []
    _READS.append(log)
    try:
        yield log
    finally:
        _READS.remove(log)


def lookup(key: str) -> Answer | None:
    """The stored answer of ``key`` if every file it read is unchanged, else None.

    Parameters
    ----------
    key : str
        From :func:`answer_key`.

    Returns
    -------
    Answer or None
        None for a missing, malformed or stale entry, or a cache turned off.
    """
    root = cache_root()
    if root is None:
        return None
    try:
        entry = json.loads((root / f"{key}.json").read_text("utf-8"))
        if entry["format"] != _FORMAT or entry["key"] != key:
            return None
        for path, digest in entry["reads"]:
            if _file_digest(path) != digest:
                return None
        files = {}
        for name, (text, digest) in entry["files"].items():
            data = base64.b64decode(text, validate=True)
            if hashlib.sha256(data).hexdigest() != digest:
                return None
            files[str(name)] = data
        answer = Answer(str(entry["stdout"]), str(entry["stderr"]), int(entry["exit_code"]), files)
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return None
    return answer


def store(key: str, answer: Answer, reads: Sequence[str]) -> None:
    """Keep ``answer`` under ``key`` with the SHA-256 of every file in ``reads``; a cache
    that cannot be written is left alone (the answer was printed anyway).

    Parameters
    ----------
    key : str
        From :func:`answer_key`.
    answer : Answer
        What the command printed and its exit status.
    reads : sequence of str
        The files the command read besides its arguments (:func:`recording`).
    """
    root = cache_root()
    if root is None:
        return
    digests = []
    for path in dict.fromkeys(reads):
        digest = _file_digest(path)
        if digest is None:  # read but gone or unreadable: the answer cannot be checked
            return
        digests.append([path, digest])
    entry = {
        "format": _FORMAT,
        "key": key,
        "reads": digests,
        "stdout": answer.stdout,
        "stderr": answer.stderr,
        "exit_code": answer.exit_code,
        "files": {
            name: [base64.b64encode(data).decode("ascii"), hashlib.sha256(data).hexdigest()]
            for name, data in answer.files.items()
        },
    }
    from betvdesign.output.files import write_atomic

    try:
        root.mkdir(parents=True, exist_ok=True)
        write_atomic(root / f"{key}.json", json.dumps(entry))
        _prune(root)
    except OSError:
        return


def _prune(root: Path) -> None:
    """Remove the oldest entries beyond :data:`MAX_ENTRIES` or :data:`MAX_BYTES`."""
    stats = []
    for p in root.glob("*.json"):
        with contextlib.suppress(OSError):
            st = p.stat()
            stats.append((st.st_mtime_ns, st.st_size, p))
    stats.sort(reverse=True)  # newest first
    total = 0
    for i, (_, size, p) in enumerate(stats):
        total += size
        if i >= MAX_ENTRIES or (i and total > MAX_BYTES):
            with contextlib.suppress(OSError):
                p.unlink()
