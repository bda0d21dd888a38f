"""A resumable directory of result chunks: a manifest, one file per chunk, a merged table.

The store of a design-space atlas (:mod:`betvdesign.studies.atlas`): millions of rows,
computed in chunks of consecutive grid keys on any executor, each chunk kept as soon as
it is finished. The directory holds:

* ``atlas.json``, the manifest: the format, what defines the rows (``definition``: the
  grid, the options, the device file's hash), the columns and their types, the number of
  points and of points per chunk, the package versions, and the run's ``status``
  (``running`` / ``interrupted`` / ``complete``) with the executor of the last run;
* ``chunks/NNNNNNNN.npz``, one per finished chunk (chunk ``i`` holds keys
  ``i·chunk_points`` to ``(i + 1)·chunk_points − 1``), each written to a temporary file
  beside it, synced, and renamed into place (:func:`betvdesign.output.files.atomic_path`):
  a chunk file is whole or absent, whatever stops the run (Ctrl-C, SIGTERM, SIGKILL, a
  dead worker, a full disk);
* ``.atlas.lock``, locked by the run in progress (a second run into the directory at
  the same time is refused);
* after the last chunk, ``table.npz`` (every row, in key order), ``summary.json``
  (points per mode) and, when asked, ``table.csv`` (floats by ``repr``: exact round
  trip).

Opening a directory that holds a manifest resumes it when the manifest describes the
same rows (definition, columns, points, chunk size, betvdesign version); anything else
is refused with a :class:`~betvdesign.errors.UsageError` naming the entry that differs,
never a silently mixed atlas. Temporary files left by a killed run are removed.

Columns are stored as arrays, bit for bit: floats as float64, integers as int64,
booleans as bool, strings as one UTF-8 byte array with offsets; a column holding None
(an empty cell) carries a mask ``<name>.none``. The ``.npz`` files are written with
fixed zip timestamps, so the same rows give the same bytes (an interrupted and resumed
atlas and an uninterrupted one give identical tables).
"""

from __future__ import annotations

import contextlib
import io
import itertools
import json
import os
import re
import zipfile
from collections.abc import Iterable, Iterator, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from betvdesign.errors import UsageError
from betvdesign.output.files import atomic_path, check_output_dir, write_atomic
from betvdesign.studies.engine.store import ColumnType, encode, versions

FORMAT = "betvdesign-atlas/1"
MANIFEST = "atlas.json"
CHUNKS = "chunks"
TABLE = "table.npz"
TABLE_CSV = "table.csv"
SUMMARY = "summary.json"
#: The advisory lock a run holds on its directory.
LOCK = ".atlas.lock"
#: Chunk files: ``chunks/00000042.npz``.
_CHUNK_RE = re.compile(r"^(\d{8})\.npz$")
#: A fixed zip timestamp (the earliest a zip can hold): equal rows, equal bytes.
_ZIP_DATE = (1980, 1, 1, 0, 0, 0)
#: Rows written to ``table.csv`` at a time (their cells are Python objects meanwhile).
CSV_BLOCK = 65536
_KINDS: dict[str, ColumnType] = {"float": float, "int": int, "bool": bool, "str": str}


def encode_columns(
    rows: Sequence[Mapping[str, Any]], columns: Mapping[str, ColumnType]
) -> dict[str, np.ndarray]:
    """Rows as column arrays, bit for bit (see the module doc).

    Parameters
    ----------
    rows : sequence of mapping
        The rows, each with every column.
    columns : mapping of str to type
        Column name -> float, int, bool or str.

    Returns
    -------
    dict of str to numpy.ndarray
        Per column ``i`` (in ``columns``' order): ``c{i}`` (a string column:
        ``c{i}.utf8`` and ``c{i}.offsets``) and, when some row holds None, ``c{i}.none``.
    """
    out: dict[str, np.ndarray] = {}
    for i, (name, kind) in enumerate(columns.items()):
        values = [r[name] for r in rows]
        none = np.array([v is None for v in values], dtype=bool)
        tag = f"c{i}"
        if kind is str:
            parts = [b"" if v is None else str(v).encode("utf-8") for v in values]
            offsets = np.zeros(len(parts) + 1, dtype=np.int64)
            np.cumsum([len(p) for p in parts], out=offsets[1:])
            out[f"{tag}.utf8"] = np.frombuffer(b"".join(parts), dtype=np.uint8)
            out[f"{tag}.offsets"] = offsets
        else:
            dtype = {float: np.float64, int: np.int64, bool: np.bool_}[kind]
            fill = {float: np.nan, int: 0, bool: False}[kind]
            out[tag] = np.array([fill if v is None else v for v in values], dtype=dtype)
        if none.any():
            out[f"{tag}.none"] = none
    return out


def column_values(
    arrays: Mapping[str, np.ndarray],
    i: int,
    kind: ColumnType,
    rows: slice | None = None,
) -> list[Any]:
    """Column ``i`` of :func:`encode_columns`' arrays as Python values (None restored).

    Parameters
    ----------
    arrays : mapping of str to numpy.ndarray
        The encoded columns.
    i : int
        The column's position.
    kind : type
        Its type: float, int, bool or str.
    rows : slice, optional
        The rows wanted (a step-1 slice; None: every row).

    Returns
    -------
    list
        The values, in row order.
    """
    tag = f"c{i}"
    sel = rows if rows is not None else slice(None)
    if kind is str:
        off = arrays[f"{tag}.offsets"]
        start, stop, _ = sel.indices(len(off) - 1)
        bounds = off[start : stop + 1].tolist()
        blob = arrays[f"{tag}.utf8"][bounds[0] : bounds[-1]].tobytes() if bounds else b""
        base = bounds[0] if bounds else 0
        values: list[Any] = [
            blob[a - base : b - base].decode("utf-8") for a, b in itertools.pairwise(bounds)
        ]
    else:
        values = arrays[tag][sel].tolist()
    none = arrays.get(f"{tag}.none")
    if none is not None:
        values = [None if n else v for v, n in zip(values, none[sel].tolist(), strict=True)]
    return values


def decode_rows(
    arrays: Mapping[str, np.ndarray], columns: Mapping[str, ColumnType]
) -> list[dict[str, Any]]:
    """Inverse of :func:`encode_columns`.

    Parameters
    ----------
    arrays : mapping of str to numpy.ndarray
        The encoded columns.
    columns : mapping of str to type
        Column name -> type, in the encoding's order.

    Returns
    -------
    list of dict
        The rows.
    """
    cols = [column_values(arrays, i, k) for i, k in enumerate(columns.values())]
    names = list(columns)
    return [dict(zip(names, vals, strict=True)) for vals in zip(*cols, strict=True)]


def concat_columns(
    parts: Iterable[Mapping[str, np.ndarray]], columns: Mapping[str, ColumnType], total: int
) -> dict[str, np.ndarray]:
    """Encoded chunks joined end to end (as if the rows had been encoded at once).

    The chunks are taken one at a time (a generator reading them from disk holds one
    chunk and the joined columns, not every chunk besides).

    Parameters
    ----------
    parts : iterable of mapping
        Encoded chunks (:func:`encode_columns`), in row order.
    columns : mapping of str to type
        Column name -> type (the first: ``key``, int).
    total : int
        Rows in all the chunks.

    Returns
    -------
    dict of str to numpy.ndarray
        The encoded columns of all rows.

    Raises
    ------
    ValueError
        The chunks hold other than ``total`` rows.
    """
    kinds = list(columns.values())
    dtypes = {float: np.float64, int: np.int64, bool: np.bool_}
    out: dict[str, np.ndarray] = {
        f"c{i}": np.empty(total, dtype=dtypes[k]) for i, k in enumerate(kinds) if k is not str
    }
    blobs: dict[int, list[np.ndarray]] = {i: [] for i, k in enumerate(kinds) if k is str}
    offsets = {i: [np.zeros(1, np.int64)] for i in blobs}
    pos = 0
    for part in parts:
        m = len(part["c0"])
        if pos + m > total:
            raise ValueError(f"the chunks hold more than {total} rows")
        for i, kind in enumerate(kinds):
            tag = f"c{i}"
            if kind is str:
                base = int(offsets[i][-1][-1])
                blobs[i].append(part[f"{tag}.utf8"])
                offsets[i].append(part[f"{tag}.offsets"][1:] + base)
            else:
                out[tag][pos : pos + m] = part[tag]
            none = part.get(f"{tag}.none")
            if none is not None:
                if f"{tag}.none" not in out:
                    out[f"{tag}.none"] = np.zeros(total, dtype=bool)
                out[f"{tag}.none"][pos : pos + m] = none
        pos += m
    if pos != total:
        raise ValueError(f"the chunks hold {pos} rows, not {total}")
    for i in blobs:
        out[f"c{i}.utf8"] = np.concatenate([np.zeros(0, np.uint8), *blobs[i]])
        out[f"c{i}.offsets"] = np.concatenate(offsets[i])
    return out


def write_npz(path: Path, arrays: Mapping[str, np.ndarray], *, compress: bool = False) -> None:
    """Write arrays as an ``.npz`` whole or not at all, with fixed zip timestamps.

    Parameters
    ----------
    path : Path
        The file.
    arrays : mapping of str to numpy.ndarray
        Named arrays (no object arrays).
    compress : bool
        Deflate the members (a chunk of 1000 map rows: 265 kB stored, 39 kB deflated,
        written in 16 ms instead of 9 ms), or store them.
    """
    method = zipfile.ZIP_DEFLATED if compress else zipfile.ZIP_STORED
    with atomic_path(path) as tmp, zipfile.ZipFile(tmp, "w", compression=method) as zf:
        for name in sorted(arrays):
            info = zipfile.ZipInfo(f"{name}.npy", date_time=_ZIP_DATE)
            info.compress_type = method
            with zf.open(info, "w", force_zip64=True) as fh:
                np.lib.format.write_array(fh, np.asarray(arrays[name]), allow_pickle=False)


def read_npz(path: Path) -> dict[str, np.ndarray]:
    """Every array of an ``.npz`` (no pickles).

    Parameters
    ----------
    path : Path
        The file.

    Returns
    -------
    dict of str to numpy.ndarray
        The arrays by name.

    Raises
    ------
    UsageError
        An unreadable file (named, with what to do).
    """
    try:
        with np.load(path, allow_pickle=False) as z:
            return {k: z[k] for k in z.files}
    except (OSError, ValueError, zipfile.BadZipFile, EOFError) as exc:
        raise UsageError(
            f"{path}: unreadable chunk or table ({exc}); delete it and run again to recompute it"
        ) from None


def _first_difference(a: Any, b: Any, where: str) -> str | None:
    """The dotted path of the first entry where two JSON values differ (None: equal)."""
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b:
                return f"{where}.{k}"
            d = _first_difference(a[k], b[k], f"{where}.{k}")
            if d:
                return d
        return None
    return None if a == b else where


class ChunkStore:
    """The chunk directory of one atlas (see the module doc).

    Parameters
    ----------
    directory : path
        The output directory (created if absent).
    kind : str
        What the rows are (``pushpull``, ``device``).
    definition : mapping
        Everything that defines the rows (JSON data), compared on resume.
    columns : mapping of str to type
        The rows' columns.
    total : int
        Number of points (keys 0 to ``total`` − 1).
    chunk_points : int or None
        Points per chunk (None: the manifest's on resume, else ``default_chunk``).
    default_chunk : int
        Points per chunk of a new atlas when ``chunk_points`` is None.
    overwrite : bool
        Discard an atlas of other rows in ``directory`` instead of refusing it.

    Raises
    ------
    UsageError
        A directory that is not an atlas, an atlas of other rows (without
        ``overwrite``), an explicit chunk size other than the atlas's, or an
        unwritable directory.
    """

    def __init__(
        self,
        directory: str | os.PathLike[str],
        *,
        kind: str,
        definition: Mapping[str, Any],
        columns: Mapping[str, ColumnType],
        total: int,
        chunk_points: int | None,
        default_chunk: int,
        overwrite: bool = False,
    ):
        self.dir = check_output_dir(directory)
        self.chunk_dir = self.dir / CHUNKS
        self.manifest_path = self.dir / MANIFEST
        self.columns = dict(columns)
        if next(iter(self.columns.items()), None) != ("key", int):
            raise ValueError("the first column must be 'key' (int)")
        self.total = int(total)
        identity = {
            "format": FORMAT,
            "kind": kind,
            "definition": json.loads(json.dumps(dict(definition))),
            "columns": {n: t.__name__ for n, t in self.columns.items()},
            "total": self.total,
        }
        old = self._existing()  # read only: a directory that is no atlas is left as it is
        self._lock = self._acquire()
        try:
            if old is not None and overwrite:
                self._clear()
                old = None
            if old is not None:
                self._check_same(old, identity, chunk_points)
                chunk_points = int(old["chunk_points"])
            self.chunk_points = int(chunk_points or default_chunk)
            if self.chunk_points < 1:
                raise UsageError(f"points per chunk must be >= 1, got {self.chunk_points}")
            self.n_chunks = -(-self.total // self.chunk_points)
            self.meta: dict[str, Any] = {
                **identity,
                "chunk_points": self.chunk_points,
                "chunks": self.n_chunks,
                "versions": versions(),
                "status": "running",
            }
            self.chunk_dir.mkdir(exist_ok=True)
            self._remove_temporaries()
            self.write_manifest()
        except BaseException:
            self.close()
            raise

    # -- opening -------------------------------------------------------------
    def _acquire(self) -> Any:
        """Hold ``DIR/.atlas.lock`` (an advisory lock) while this store is open.

        A second run into the same directory at the same time (another terminal, a job
        scheduled twice) would compute the same chunks and race on the manifest: it is
        refused instead. The lock goes with the process, however it ends.
        """
        import fcntl

        try:
            fh = open(self.dir / LOCK, "a")  # held until close()
        except OSError as exc:
            raise UsageError(f"{self.dir}: cannot write: {exc}") from None
        try:
            fcntl.flock(fh.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            fh.close()
            raise UsageError(
                f"{self.dir}: in use by another run of this atlas (wait for it to end, or "
                "stop it: the same command then resumes)"
            ) from None
        return fh

    def close(self) -> None:
        """Release the directory's lock (the process's end releases it too)."""
        if self._lock is not None:
            self._lock.close()
            self._lock = None

    def _existing(self) -> dict[str, Any] | None:
        if not self.manifest_path.exists():
            stray = [p.name for p in self.dir.iterdir() if not p.name.startswith(".")]
            if stray:
                raise UsageError(
                    f"{self.dir}: not empty and not an atlas (no {MANIFEST}; it holds "
                    f"{', '.join(sorted(stray)[:3])}{' ...' if len(stray) > 3 else ''}): "
                    "choose a new or empty directory"
                )
            return None
        try:
            old = json.loads(self.manifest_path.read_text(encoding="utf-8"))
        except (OSError, ValueError) as exc:
            raise UsageError(f"{self.manifest_path}: unreadable manifest: {exc}") from None
        if not isinstance(old, dict) or old.get("format") != FORMAT:
            raise UsageError(f"{self.manifest_path}: not a betv atlas manifest ({FORMAT})")
        return old

    def _check_same(
        self, old: Mapping[str, Any], identity: Mapping[str, Any], chunk_points: int | None
    ) -> None:
        for key, value in identity.items():
            where = _first_difference(old.get(key), value, key)
            if where is not None:
                raise UsageError(
                    f"{self.dir}: holds an atlas of other rows ({where} differs from this "
                    "command's); cannot resume it: run the command that made it, choose "
                    "another directory, or pass --overwrite"
                )
        if chunk_points is not None and int(chunk_points) != int(old["chunk_points"]):
            raise UsageError(
                f"{self.dir}: its atlas has {old['chunk_points']} points per chunk, not "
                f"{chunk_points}: omit --chunksize to resume it"
            )
        made = old.get("versions", {}).get("betvdesign")
        if made != versions()["betvdesign"]:
            raise UsageError(
                f"{self.dir}: its atlas comes from betvdesign {made}; cannot mix versions "
                "(pass --overwrite, or choose another directory)"
            )

    def _clear(self) -> None:
        """Remove this store's own files (``--overwrite``): chunks, table, manifest."""
        if self.chunk_dir.is_dir():
            for p in self.chunk_dir.iterdir():
                if _CHUNK_RE.match(p.name) or p.name.startswith("."):
                    p.unlink()
        for name in (TABLE, TABLE_CSV, SUMMARY, MANIFEST):
            with contextlib.suppress(FileNotFoundError):
                (self.dir / name).unlink()

    def _remove_temporaries(self) -> None:
        """Temporary files of a run killed while writing (never renamed into place)."""
        for where in (self.chunk_dir, self.dir):
            for p in where.iterdir():
                if p.name.startswith(".") and ".tmp" in p.name:
                    with contextlib.suppress(OSError):
                        p.unlink()

    # -- chunks --------------------------------------------------------------
    def chunk_path(self, index: int) -> Path:
        """The file of chunk ``index``.

        Parameters
        ----------
        index : int
            The chunk's index.

        Returns
        -------
        Path
            ``chunks/NNNNNNNN.npz``.
        """
        return self.chunk_dir / f"{index:08d}.npz"

    def bounds(self, index: int) -> tuple[int, int]:
        """The keys of chunk ``index``: ``start`` to ``stop`` − 1.

        Parameters
        ----------
        index : int
            The chunk's index.

        Returns
        -------
        tuple of int
            ``(start, stop)``.
        """
        start = index * self.chunk_points
        return start, min(self.total, start + self.chunk_points)

    def done(self) -> set[int]:
        """The indices of the chunks on disk.

        Returns
        -------
        set of int
            Finished chunks.
        """
        found = set()
        for p in self.chunk_dir.iterdir():
            m = _CHUNK_RE.match(p.name)
            if m and int(m.group(1)) < self.n_chunks:
                found.add(int(m.group(1)))
        return found

    def missing(self) -> list[int]:
        """The chunks still to compute, in order.

        Returns
        -------
        list of int
            Their indices.
        """
        have = self.done()
        return [i for i in range(self.n_chunks) if i not in have]

    def write_chunk(self, index: int, arrays: Mapping[str, np.ndarray]) -> None:
        """Keep a finished chunk (whole or not at all).

        Parameters
        ----------
        index : int
            The chunk's index.
        arrays : mapping of str to numpy.ndarray
            Its rows, encoded (:func:`encode_columns`).
        """
        write_npz(self.chunk_path(index), arrays, compress=True)

    def read_chunk(self, index: int) -> dict[str, np.ndarray]:
        """A chunk's encoded rows, checked for its number of rows.

        Parameters
        ----------
        index : int
            The chunk's index.

        Returns
        -------
        dict of str to numpy.ndarray
            The encoded columns.

        Raises
        ------
        UsageError
            An unreadable chunk, or one of the wrong length.
        """
        path = self.chunk_path(index)
        arrays = read_npz(path)
        start, stop = self.bounds(index)
        keys = arrays.get("c0")
        if keys is None or not np.array_equal(keys, np.arange(start, stop)):
            raise UsageError(
                f"{path}: does not hold keys {start} to {stop - 1}; delete it and run again"
            )
        return arrays

    # -- the end -------------------------------------------------------------
    def merge(self, *, csv: bool = False) -> dict[str, np.ndarray]:
        """Join every chunk into ``table.npz`` (and ``table.csv`` when asked).

        Parameters
        ----------
        csv : bool
            Also write ``table.csv`` (one line per row, floats by ``repr``).

        Returns
        -------
        dict of str to numpy.ndarray
            The table's encoded columns (``__columns__`` and ``__types__`` name them).
        """
        parts = (self.read_chunk(i) for i in range(self.n_chunks))
        table = concat_columns(parts, self.columns, self.total)
        table["__columns__"] = np.array(list(self.columns), dtype=str)
        table["__types__"] = np.array([t.__name__ for t in self.columns.values()], dtype=str)
        write_npz(self.dir / TABLE, table, compress=True)
        if csv:
            with (
                atomic_path(self.dir / TABLE_CSV) as tmp,
                open(tmp, "w", encoding="utf-8", newline="") as fh,
            ):
                _write_csv(fh, table, self.columns)
        return table

    def write_manifest(self, **updates: Any) -> None:
        """Update the manifest's fields and write it atomically.

        Parameters
        ----------
        **updates
            Manifest fields (status, executor, counts...).
        """
        self.meta.update(updates)
        write_atomic(self.manifest_path, json.dumps(self.meta, indent=2) + "\n")


def _write_csv(
    fh: io.TextIOBase, table: Mapping[str, np.ndarray], columns: Mapping[str, ColumnType]
) -> None:
    """The table as CSV, :data:`CSV_BLOCK` rows at a time.

    A header, then one line per row (cells by ``store.encode``: floats by ``repr``).
    """
    import csv

    writer = csv.writer(fh, lineterminator="\n")
    writer.writerow(list(columns))
    n = len(table["c0"])
    for start in range(0, n, CSV_BLOCK):
        rows = slice(start, min(n, start + CSV_BLOCK))
        cols = [column_values(table, i, k, rows) for i, k in enumerate(columns.values())]
        writer.writerows([encode(v) for v in row] for row in zip(*cols, strict=True))


def read_table(
    directory: str | os.PathLike[str],
) -> tuple[dict[str, Any], dict[str, ColumnType], dict[str, np.ndarray]]:
    """A merged atlas: its manifest, its columns and their encoded arrays.

    Parameters
    ----------
    directory : path
        The atlas directory.

    Returns
    -------
    tuple of (dict, dict, dict)
        The manifest, column name -> type, and the encoded columns
        (:func:`decode_rows` turns them into rows).

    Raises
    ------
    UsageError
        No finished atlas there.
    """
    d = Path(directory)
    try:
        meta = json.loads((d / MANIFEST).read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        raise UsageError(f"{d}: no readable atlas manifest: {exc}") from None
    table = read_npz(d / TABLE)
    columns = {n: _KINDS[t] for n, t in meta["columns"].items()}
    return meta, columns, table


def iter_missing(store: ChunkStore) -> Iterator[dict[str, int]]:
    """The tasks of the chunks still to compute: ``{"key": index, "start", "stop"}``.

    Parameters
    ----------
    store : ChunkStore
        The store.

    Yields
    ------
    dict of str to int
        One task per missing chunk, in order.
    """
    for i in store.missing():
        start, stop = store.bounds(i)
        yield {"key": i, "start": start, "stop": stop}


def count_values(values: Iterable[Any]) -> dict[str, int]:
    """How often each value occurs, in order of first occurrence.

    Parameters
    ----------
    values : iterable
        Values (None counted as ``"none"``).

    Returns
    -------
    dict of str to int
        Value -> count.
    """
    out: dict[str, int] = {}
    for v in values:
        k = "none" if v is None else str(v)
        out[k] = out.get(k, 0) + 1
    return out
