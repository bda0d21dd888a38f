"""Streamed, resumable study results: a CSV file plus a JSON sidecar.

``results.csv`` gets one line per finished point, appended and flushed as
chunks complete, each keyed by the point's grid ``key``. ``results.json``
(the sidecar, same stem) records the study, its parameters, the columns, the
seed, package versions, the executor and the run's status
(``running`` / ``interrupted`` / ``complete``).

Opening an existing output resumes it: the sidecar must describe the same
study and parameters (otherwise a :class:`UsageError` says which entry
differs), finished keys are skipped, and a torn last line left by a killed
process is dropped. When the run completes the CSV is rewritten sorted by key
through a temporary file and an atomic rename, so an interrupted-and-resumed
run and an uninterrupted one give byte-identical files.

Floats are written with ``repr`` (shortest round-trip form), so values read
back are bitwise the values computed.
"""

from __future__ import annotations

import csv
import io
import json
import os
import platform
import sys
import time
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

from betvdesign.errors import UsageError
from betvdesign.output.files import check_output_file, write_atomic

FORMAT = "betvdesign-study/1"
#: Appended rows are flushed to the kernel at once (a killed process loses none) and
#: fsynced at most this often [s] (a power loss loses at most the last second).
FSYNC_EVERY_S = 1.0

#: Column types a study may declare.
ColumnType = type[float] | type[int] | type[bool] | type[str]


def sidecar_path(path: Path) -> Path:
    """The sidecar of an output: ``results.csv`` -> ``results.json``.

    Parameters
    ----------
    path : Path
        The output CSV.

    Returns
    -------
    Path
        Its JSON sidecar.
    """
    return path.with_suffix(".json")


def versions() -> dict[str, str]:
    """Versions that can change results (recorded in every sidecar).

    Returns
    -------
    dict of str to str
        betvdesign, numpy, scipy, python and the platform.
    """
    import numpy
    import scipy

    from betvdesign import __version__

    return {
        "betvdesign": __version__,
        "numpy": numpy.__version__,
        "scipy": scipy.__version__,
        "python": sys.version.split()[0],
        "platform": platform.platform(),
    }


def encode(value: Any) -> str:
    """One CSV cell: floats by ``repr`` (exact round trip), None as empty.

    Parameters
    ----------
    value : float, int, bool, str or None
        A row's value.

    Returns
    -------
    str
        The cell (booleans as ``true``/``false``).
    """
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value)
    return str(value)


def decode(text: str, kind: ColumnType) -> Any:
    """Inverse of :func:`encode` for a column of type ``kind``.

    Parameters
    ----------
    text : str
        The cell.
    kind : type
        The column's type: float, int, bool or str.

    Returns
    -------
    float, int, bool, str or None
        The value (None for an empty cell).

    Raises
    ------
    ValueError
        A cell that is not of ``kind``.
    """
    if text == "":
        return None
    if kind is bool:
        if text not in ("true", "false"):
            raise ValueError(f"not a boolean: {text!r}")
        return text == "true"
    return kind(text)


def _csv_line(values: Iterable[str]) -> str:
    buf = io.StringIO()
    csv.writer(buf, lineterminator="\n").writerow(list(values))
    return buf.getvalue()


class ResultStore:
    """Append-only CSV of rows keyed by ``key`` with a JSON sidecar (see module doc).

    ``columns`` maps column name to type and must start with ``key`` (int).
    ``parameters`` is everything that defines the study's results (grid,
    options, seed); a resumed run must match it exactly.
    """

    def __init__(
        self,
        path: str | os.PathLike[str],
        *,
        study: str,
        columns: Mapping[str, ColumnType],
        parameters: Mapping[str, Any],
        seed: int | None = None,
        total: int,
        overwrite: bool = False,
    ):
        self.path = Path(path)
        self.sidecar = sidecar_path(self.path)
        if self.path.suffix.lower() == ".json":
            raise UsageError(f"{self.path}: results are CSV; the .json name is the sidecar's")
        if next(iter(columns), None) != "key":
            raise ValueError("the first column must be 'key'")
        self.study = study
        self.columns = dict(columns)
        # JSON round trip so the comparison with a stored sidecar is like for like.
        self.parameters = json.loads(json.dumps(dict(parameters)))
        self.seed = seed
        self.total = total
        self.done: dict[int, dict[str, Any]] = {}
        self.meta: dict[str, Any] = {}
        self._fh: io.TextIOWrapper | None = None
        self._open(overwrite)

    # -- opening and resuming -------------------------------------------------
    def _check_writable(self) -> None:
        check_output_file(self.path, create_parent=True)
        check_output_file(self.sidecar)
        for p in (self.path, self.sidecar):
            if p.exists() and not os.access(p, os.W_OK):
                raise UsageError(f"{p}: exists and is not writable")

    def _open(self, overwrite: bool) -> None:
        self._check_writable()
        resuming = self.path.exists() and not overwrite
        if resuming:
            self._load_existing()
        else:
            write_atomic(self.path, _csv_line(self.columns))
        self.meta = {
            "format": FORMAT,
            "study": self.study,
            "parameters": self.parameters,
            "columns": {n: t.__name__ for n, t in self.columns.items()},
            "seed": self.seed,
            "total": self.total,
            "versions": versions(),
            "status": "running",
            "done": len(self.done),
        }
        self.write_sidecar()
        try:
            self._fh = open(self.path, "a", encoding="utf-8", newline="")
            self._synced = time.monotonic()
        except OSError as exc:
            raise UsageError(f"{self.path}: cannot open for writing: {exc}") from None

    def _load_existing(self) -> None:
        if not self.sidecar.exists():
            raise UsageError(
                f"{self.path}: exists but has no sidecar {self.sidecar.name}, so it is not a "
                "betv study output; choose another path or pass --overwrite"
            )
        try:
            old = json.loads(self.sidecar.read_text(encoding="utf-8"))
        except (OSError, ValueError) as exc:
            raise UsageError(f"{self.sidecar}: unreadable sidecar: {exc}") from None
        expected = {
            "format": FORMAT,
            "study": self.study,
            "parameters": self.parameters,
            "columns": {n: t.__name__ for n, t in self.columns.items()},
            "seed": self.seed,
        }
        for name, value in expected.items():
            if old.get(name) != value:
                raise UsageError(
                    f"{self.path}: existing results were made with a different {name!r}; "
                    "cannot resume them (choose another path or pass --overwrite)"
                )
        old_version = old.get("versions", {}).get("betvdesign")
        if old_version != versions()["betvdesign"]:
            raise UsageError(
                f"{self.path}: existing results come from betvdesign {old_version}; "
                "cannot mix versions (pass --overwrite)"
            )
        self._read_rows()

    def _read_rows(self) -> None:
        raw = self.path.read_bytes()
        if raw and not raw.endswith(b"\n"):
            # A killed writer can leave a torn last line: drop it.
            cut = raw.rfind(b"\n") + 1
            with open(self.path, "r+b") as fh:
                fh.truncate(cut)
            raw = raw[:cut]
        reader = csv.reader(io.StringIO(raw.decode("utf-8")))
        header = next(reader, None)
        if header != list(self.columns):
            raise UsageError(f"{self.path}: header does not match the study's columns")
        types = list(self.columns.values())
        for lineno, cells in enumerate(reader, start=2):
            if len(cells) != len(types):
                raise UsageError(f"{self.path}:{lineno}: expected {len(types)} fields")
            try:
                row = {
                    n: decode(c, t) for (n, t), c in zip(self.columns.items(), cells, strict=True)
                }
            except ValueError as exc:
                raise UsageError(f"{self.path}:{lineno}: {exc}") from None
            self.done.setdefault(row["key"], row)

    # -- writing --------------------------------------------------------------
    def write_sidecar(self, **updates: Any) -> None:
        """Update the sidecar's fields and write it atomically.

        Parameters
        ----------
        **updates
            Sidecar fields (status, executor, counts...).
        """
        self.meta.update(updates)
        write_atomic(self.sidecar, json.dumps(self.meta, indent=2, sort_keys=False) + "\n")

    def append(self, rows: Iterable[Mapping[str, Any]]) -> None:
        """Write finished rows and flush them to disk.

        Parameters
        ----------
        rows : iterable of mapping
            Finished rows (a key already stored is skipped).
        """
        assert self._fh is not None, "store is closed"
        lines = []
        for row in rows:
            key = int(row["key"])
            if key in self.done:
                continue
            self.done[key] = dict(row)
            lines.append(_csv_line(encode(row[c]) for c in self.columns))
        if lines:
            self._fh.write("".join(lines))
            self._fh.flush()  # in the kernel now: a killed process loses nothing
            now = time.monotonic()
            if now - self._synced >= FSYNC_EVERY_S:  # power loss: at most ~1 s of rows
                os.fsync(self._fh.fileno())
                self._synced = now

    def close(self, status: str, **updates: Any) -> None:
        """Close the stream; on ``complete`` rewrite the CSV sorted by key.

        Parameters
        ----------
        status : {"complete", "interrupted"}
            The run's outcome, written to the sidecar.
        **updates
            Further sidecar fields.
        """
        if self._fh is not None:
            self._fh.close()
            self._fh = None
        if status == "complete":
            lines = [_csv_line(self.columns)]
            for key in sorted(self.done):
                row = self.done[key]
                lines.append(_csv_line(encode(row[c]) for c in self.columns))
            write_atomic(self.path, "".join(lines))
        self.write_sidecar(status=status, done=len(self.done), **updates)

    def rows(self) -> list[dict[str, Any]]:
        """Every finished row, sorted by key.

        Returns
        -------
        list of dict
            The rows.
        """
        return [self.done[k] for k in sorted(self.done)]


def read_results(path: str | os.PathLike[str]) -> tuple[dict[str, Any], list[dict[str, Any]]]:
    """Load a finished (or partial) output.

    Parameters
    ----------
    path : path
        The output CSV (its JSON sidecar next to it).

    Returns
    -------
    tuple of (dict, list of dict)
        The sidecar and the rows sorted by key.

    Raises
    ------
    UsageError
        Either file unreadable.
    """
    p = Path(path)
    try:
        meta = json.loads(sidecar_path(p).read_text(encoding="utf-8"))
        text = p.read_text(encoding="utf-8")
    except (OSError, ValueError) as exc:
        raise UsageError(f"{p}: cannot read study results: {exc}") from None
    kinds = {"float": float, "int": int, "bool": bool, "str": str}
    columns = {n: kinds[t] for n, t in meta["columns"].items()}
    reader = csv.reader(io.StringIO(text))
    next(reader, None)
    rows = [
        {n: decode(c, t) for (n, t), c in zip(columns.items(), cells, strict=True)}
        for cells in reader
        if len(cells) == len(columns)
    ]
    rows.sort(key=lambda r: r["key"])
    return meta, rows
