"""Output files: checked for writability up front, written whole or not at all.

Every file the toolkit writes (reports, figures, schemas, sidecars, calibration
snippets; streamed CSV rows aside, which are resumable by design) goes through
:func:`write_atomic` or :func:`atomic_path`: the content goes to a temporary file
in the target's directory, is flushed to disk, and is renamed over the target, so
a crash, a signal or a full disk leaves either the old file or the new one, never
half of one. :func:`write_group` extends that to files that belong together (a
report's HTML and PDF): all are renamed into place or none is.

:func:`check_output_file` and :func:`check_output_dir` refuse, before any work,
paths that cannot be written: special files (``/proc/x``, ``/dev/null``), a
directory where a file is due (or the reverse), a path under a regular file,
missing or read-only directories. They probe by creating (and removing) a
temporary file, which is the only test that ``/proc`` or a read-only mount answers
truthfully. Problems raise :class:`~betvdesign.errors.UsageError` (CLI exit 2).
"""

from __future__ import annotations

import contextlib
import os
import stat
import tempfile
from collections.abc import Iterator, Mapping
from pathlib import Path

from betvdesign.errors import UsageError


def _directory(path: Path) -> Path:
    return path.parent if str(path.parent) else Path(".")


def _why(exc: OSError) -> str:
    return exc.strerror or type(exc).__name__


def _probe(directory: Path, what: Path) -> None:
    """Create and remove a temporary file in ``directory`` or raise UsageError."""
    try:
        fd, tmp = tempfile.mkstemp(prefix=".betv-probe-", dir=directory)
    except OSError as exc:
        raise UsageError(f"{what}: cannot write in {directory}: {_why(exc)}") from None
    os.close(fd)
    with contextlib.suppress(OSError):
        os.unlink(tmp)


def _check_ancestors(path: Path, what: Path) -> Path:
    """The nearest existing ancestor of ``path`` (a directory), or UsageError."""
    probe = path
    while not probe.exists():
        if probe.parent == probe:
            break
        probe = probe.parent
    if probe.exists() and not probe.is_dir():
        raise UsageError(
            f"{what}: cannot create output directory: {probe} is a file, not a directory"
        )
    return probe


def check_output_file(
    path: str | os.PathLike[str],
    *,
    suffixes: tuple[str, ...] | None = None,
    create_parent: bool = False,
) -> Path:
    """Refuse an output file path that cannot be written (see module doc).

    suffixes: allowed lower-case suffixes (``(".svg", ".png")``), or None for any.
    create_parent: a missing parent directory is created (else it is an error).
    """
    p = Path(path)
    if suffixes is not None and p.suffix.lower() not in suffixes:
        raise UsageError(f"{p}: the file name must end in {', '.join(suffixes)}")
    if p.name in ("", ".", ".."):
        raise UsageError(f"{p}: not a file name")
    if p.exists() or p.is_symlink():
        try:
            mode = p.stat().st_mode
        except OSError as exc:
            raise UsageError(f"{p}: cannot use as output: {_why(exc)}") from None
        if stat.S_ISDIR(mode):
            raise UsageError(f"{p}: is a directory, expected a file name")
        if not stat.S_ISREG(mode):
            raise UsageError(f"{p}: is a special file (device, pipe or socket), not a file")
    directory = _directory(p)
    if not directory.is_dir():
        base = _check_ancestors(directory, p)
        if not create_parent:
            raise UsageError(f"{p}: directory {directory} does not exist")
        _probe(base, p)
        _mkdir(directory, f"{p}: cannot create directory {directory}")
    _probe(directory, p)
    return p


def _mkdir(directory: Path, refusal: str) -> None:
    """Make ``directory`` and its parents; an OS error is a UsageError ``refusal: why``."""
    try:
        directory.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise UsageError(f"{refusal}: {_why(exc)}") from None


def check_output_dir(path: str | os.PathLike[str], *, create: bool = True) -> Path:
    """Refuse an output directory that cannot be written (or created).

    create: make a missing directory now; False only checks that it could be made
    (its nearest existing ancestor is a writable directory), so a run that fails
    later on bad input leaves nothing behind.
    """
    p = Path(path)
    if p.exists() and not p.is_dir():
        raise UsageError(f"output path {p} exists and is not a directory")
    if not p.exists():
        base = _check_ancestors(p, p)
        _probe(base, p)
        if not create:
            return p
        _mkdir(p, f"cannot create output directory {p}")
    _probe(p, p)
    return p


def _temp_beside(path: Path) -> Path:
    """An empty temporary file next to ``path``, readable like a normal file (0644)."""
    fd, tmp = tempfile.mkstemp(
        prefix=f".{path.name}.", suffix=f".tmp{path.suffix}", dir=_directory(path)
    )
    os.close(fd)
    os.chmod(tmp, 0o644)
    return Path(tmp)


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike[str]) -> Iterator[Path]:
    """A temporary path beside ``path`` (same suffix, so writers that look at it pick
    the right format); renamed over ``path`` when the block ends without error,
    removed otherwise. OS errors become :class:`UsageError`."""
    p = Path(path)
    try:
        tmp = _temp_beside(p)
    except OSError as exc:
        raise UsageError(f"{p}: cannot write: {_why(exc)}") from None
    try:
        yield tmp
        _fsync(tmp)
        os.replace(tmp, p)
    except OSError as exc:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise UsageError(f"{p}: cannot write: {_why(exc)}") from None
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def _fsync(path: Path) -> None:
    with open(path, "rb") as fh:
        os.fsync(fh.fileno())


def write_atomic(path: str | os.PathLike[str], data: str | bytes) -> Path:
    """Write ``data`` (text as UTF-8, newlines untouched) to ``path`` whole or not at all."""
    p = Path(path)
    with atomic_path(p) as tmp:
        tmp.write_bytes(data.encode("utf-8") if isinstance(data, str) else data)
    return p


def write_group(files: Mapping[str | os.PathLike[str], str | bytes]) -> list[Path]:
    """Write several files that belong together: every one is renamed into place, or
    (on any error, signal or interruption before the last rename) none is new.

    All temporaries are written and flushed first, then renamed in order; a failure
    during the renames removes the files already renamed, so a reader never sees a
    new member next to a missing or old one.
    """
    temps: list[tuple[Path, Path]] = []
    done: list[Path] = []
    try:
        for path, data in files.items():
            p = Path(path)
            tmp = _temp_beside(p)
            temps.append((tmp, p))
            with open(tmp, "wb") as fh:
                fh.write(data.encode("utf-8") if isinstance(data, str) else data)
                fh.flush()
                os.fsync(fh.fileno())
        for tmp, p in temps:
            os.replace(tmp, p)
            done.append(p)
    except BaseException as exc:
        for tmp, _ in temps:
            with contextlib.suppress(OSError):
                os.unlink(tmp)
        if len(done) < len(temps):
            for p in done:
                with contextlib.suppress(OSError):
                    os.unlink(p)
        if isinstance(exc, OSError):
            where = next((str(p) for _, p in temps if p not in done), "output")
            raise UsageError(f"{where}: cannot write: {_why(exc)}") from None
        raise
    return done
