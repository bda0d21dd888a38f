"""Design-space atlas: up to millions of points, in chunks, on any executor, resumable.

``betv sweep atlas`` maps a design space too large for one study's list of tasks and
one CSV: the dimensionless (ϖ, α, β, κ) grid of the push/pull map
(:func:`pushpull_atlas`, each point the map's own solve,
:class:`betvdesign.studies.pushpull.MapPoints`), or one to :data:`MAX_FIELDS` fields of a
device file in their units (:func:`device_atlas`, each point the field sweep's own solve,
:func:`betvdesign.studies.fieldsweep.fieldsweep_point`: ``betv check``'s travel answer).

The grid's keys (C order, first axis slowest, as the map and the sweep number them) are
cut into chunks of consecutive keys. A chunk is one task of the executor (serial, the
process pool, or ``dask.distributed``: a cluster's scheduler, or a local cluster of its
own): the worker (:class:`ChunkWorker`) builds its points' tasks itself from the atlas's
definition, solves them, and returns its rows as column arrays; the calling process keeps
each chunk as one file the moment it arrives (:mod:`betvdesign.studies.engine.chunkstore`:
written whole or not at all). Running the same command again computes only the chunks
not on disk; another command into the same directory is refused. When every chunk is
there, the chunks are merged into one table (``table.npz``, ``table.csv`` on request) and
a summary (points per mode) is returned.

Rows do not depend on the executor, the number of workers or on interruptions: each
point is solved by the same function from the same floats, and chunks are joined in key
order.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import time
from collections import Counter
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import BrokenExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from betvdesign.errors import UsageError
from betvdesign.output.files import write_atomic
from betvdesign.spec import limits
from betvdesign.studies.engine.chunkstore import (
    SUMMARY,
    ChunkStore,
    column_values,
    count_values,
    encode_columns,
    iter_missing,
)
from betvdesign.studies.engine.executors import check_backend, open_executor

__all__ = [
    "DEFAULT_CHUNK_POINTS",
    "MAX_FIELDS",
    "Atlas",
    "AtlasRun",
    "ChunkWorker",
    "device_atlas",
    "pushpull_atlas",
    "run_atlas",
    "summarise_table",
]

#: Most device fields one atlas varies.
MAX_FIELDS = 4
#: Most points per chunk by default (a few seconds of solves on one core), so a
#: 10⁶-point atlas is 1 000 chunk files; smaller atlases get at least 64 chunks.
DEFAULT_CHUNK_POINTS = 1000
#: Chunks a small atlas is cut into at least (they spread over the workers).
MIN_CHUNKS = 64
#: Rows whose values the summary holds as Python objects at once.
SUMMARY_BLOCK = 65536

Progress = Callable[[int, int], None]


@dataclass(frozen=True)
class Atlas:
    """One atlas: what defines its rows, its columns, and the worker of its chunks.

    Attributes
    ----------
    kind : {"pushpull", "device"}
        The dimensionless map or a device's fields.
    definition : dict
        Everything that defines the rows (JSON data; compared when an atlas is resumed).
    columns : dict of str to type
        The rows' columns (the first is ``key``).
    total : int
        Number of points.
    worker : ChunkWorker
        Solves one chunk.
    mode_column : str
        The column whose values the summary counts (``mode``, or ``exact_mode``).
    about : dict
        Recorded in the manifest but not compared on resume (the device file's path).
    """

    kind: str
    definition: dict[str, Any]
    columns: dict[str, type]
    total: int
    worker: ChunkWorker
    mode_column: str
    about: dict[str, Any] = field(default_factory=dict)


class ChunkWorker:
    """Solves one chunk of an atlas: its tasks built here, rows returned as column arrays.

    Picklable (module level, plain data inside), so the process pool sends it with each
    chunk and dask scatters it to every worker once.

    Parameters
    ----------
    kind : {"pushpull", "device"}
        The atlas's kind.
    columns : dict of str to type
        The rows' columns.
    payload : dict
        ``pushpull``: ``points`` (:class:`~betvdesign.studies.pushpull.MapPoints`);
        ``device``: ``device`` (path), ``sha256`` (its content's), ``set_index``,
        ``axes`` (:class:`~betvdesign.studies.fieldsweep.FieldAxis`) and ``tol``.
    """

    def __init__(self, kind: str, columns: Mapping[str, type], payload: Mapping[str, Any]):
        self.kind = kind
        self.columns = dict(columns)
        self.payload = dict(payload)

    def rows(self, start: int, stop: int) -> list[dict[str, Any]]:
        """The rows of keys ``start`` to ``stop`` − 1.

        Parameters
        ----------
        start, stop : int
            The chunk's keys.

        Returns
        -------
        list of dict
            One row per key, in key order.
        """
        keys = range(start, stop)
        if self.kind == "pushpull":
            mp = self.payload["points"]
            worker = mp.worker
            return [worker(mp.task(k)) for k in keys]
        from betvdesign.studies.fieldsweep import field_tasks, fieldsweep_point

        p = self.payload
        spec = _device(p["device"], p["sha256"])
        tasks = field_tasks(spec, p["axes"], p["set_index"], p["tol"], keys, max_fields=MAX_FIELDS)
        return [fieldsweep_point(t) for t in tasks]

    def __call__(self, task: Mapping[str, int]) -> dict[str, Any]:
        """Solve one chunk.

        Parameters
        ----------
        task : mapping
            ``key`` (the chunk's index), ``start`` and ``stop`` (its keys).

        Returns
        -------
        dict
            ``key`` and ``arrays``, the rows encoded
            (:func:`~betvdesign.studies.engine.chunkstore.encode_columns`).
        """
        rows = self.rows(int(task["start"]), int(task["stop"]))
        return {"key": task["key"], "arrays": encode_columns(rows, self.columns)}


#: Devices loaded in this process, by (path, content hash): a worker parses its file once.
_DEVICES: dict[tuple[str, str], Any] = {}


def _device(path: str, sha256: str) -> Any:
    """The device file ``path``, loaded once per process; refused if it has changed."""
    key = (path, sha256)
    if key not in _DEVICES:
        from betvdesign.spec.loader import load_device

        if _sha256(path) != sha256:
            raise UsageError(f"{path}: changed since the atlas was defined; run again")
        _DEVICES[key] = load_device(path)
    return _DEVICES[key]


def _sha256(path: str | os.PathLike[str]) -> str:
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except OSError as exc:
        raise UsageError(f"{path}: cannot read: {exc}") from None


def pushpull_atlas(
    varpi: Sequence[float],
    alpha: Sequence[float],
    beta: Sequence[float],
    kappa: Sequence[float],
    **options: Any,
) -> Atlas:
    """The atlas of the dimensionless push/pull map over ϖ, α, β, κ.

    Parameters
    ----------
    varpi, alpha, beta, kappa : sequence of float
        The axes [-] (> 0).
    **options
        ``fidelity``, ``tol``, ``max_cycles``, ``zeta_v``, ``zeta_h``, ``restitution``
        (:func:`betvdesign.studies.pushpull.map_points`).

    Returns
    -------
    Atlas
        Rows of :data:`betvdesign.studies.points.COLUMNS` (as ``betv sweep pushpull``),
        keyed as that map keys them (κ slowest, ϖ fastest).

    Raises
    ------
    UsageError
        As :func:`~betvdesign.studies.pushpull.map_points`.
    """
    from betvdesign.studies.pushpull import map_points

    mp = map_points(varpi, alpha, beta, kappa, **options)
    worker = ChunkWorker("pushpull", mp.columns, {"points": mp})
    return Atlas("pushpull", mp.parameters, mp.columns, mp.grid.size, worker, "mode")


def device_atlas(
    device: str | os.PathLike[str],
    axes: Sequence[Any],
    *,
    set_name: str | None = None,
    tol: float = 1e-10,
) -> Atlas:
    """The atlas of one to :data:`MAX_FIELDS` fields of a device file.

    Parameters
    ----------
    device : path
        The device YAML file (on a remote dask cluster, its workers must see the same
        path).
    axes : sequence of FieldAxis
        The fields and their grids (:func:`betvdesign.studies.fieldsweep.parse_axis`).
    set_name : str, optional
        The actuator set (default: the first).
    tol : float
        Fixed-point residual accepted [-].

    Returns
    -------
    Atlas
        Rows of :func:`betvdesign.studies.fieldsweep.columns` (as ``betv sweep FILE``),
        keyed in row-major order of the fields (the first slowest).

    Raises
    ------
    UsageError
        An unreadable device, an unknown set, no or too many fields, or a grid over
        :data:`~betvdesign.spec.limits.MAX_STUDY_POINTS`.
    """
    from betvdesign.studies.fieldsweep import _set_index, columns

    if not 1 <= len(axes) <= MAX_FIELDS or len({a.field for a in axes}) != len(axes):
        raise UsageError(f"--vary: give 1 to {MAX_FIELDS} different fields")
    total = math.prod(len(a.values) for a in axes)
    if total > limits.MAX_STUDY_POINTS:
        raise UsageError(
            f"atlas of {total:,} points exceeds the limit of {limits.MAX_STUDY_POINTS:,} "
            "points per study; use fewer points per field"
        )
    sha = _sha256(device)
    spec = _device(str(device), sha)
    index, set_name = _set_index(spec, set_name)
    cols = columns(axes)
    path = str(Path(device).resolve())  # workers may run in another directory
    definition = {
        "device_sha256": sha[:16],  # the file's content, not its path, defines the rows
        "set": set_name,
        "tol": tol,
        "axes": {a.field: {"unit": a.unit, "log": a.log, "values": list(a.values)} for a in axes},
    }
    payload = {"device": path, "sha256": sha, "set_index": index, "axes": list(axes)}
    worker = ChunkWorker("device", cols, {**payload, "tol": tol})
    return Atlas("device", definition, cols, total, worker, "exact_mode", {"device": path})


@dataclass
class AtlasRun:
    """Outcome of :func:`run_atlas`.

    Attributes
    ----------
    path : Path
        The atlas directory.
    total : int
        Points.
    chunks : int
        Chunks.
    chunk_points : int
        Points per chunk.
    computed : int
        Chunks computed by this run.
    computed_points : int
        Points computed by this run.
    resumed : int
        Chunks found on disk.
    elapsed_s : float
        Time computing chunks [s].
    merge_s : float
        Time merging them into the table [s].
    executor : dict
        What ran the chunks (backend, workers, scheduler).
    summary : dict
        :func:`summarise_table`.
    """

    path: Path
    total: int
    chunks: int
    chunk_points: int
    computed: int
    computed_points: int
    resumed: int
    elapsed_s: float
    merge_s: float
    executor: dict[str, Any]
    summary: dict[str, Any] = field(default_factory=dict)

    def as_dict(self) -> dict[str, Any]:
        """The run as JSON data (the summary inside)."""
        return {
            "out": str(self.path),
            "points": self.total,
            "chunks": self.chunks,
            "chunk_points": self.chunk_points,
            "computed_chunks": self.computed,
            "computed_points": self.computed_points,
            "resumed_chunks": self.resumed,
            "elapsed_s": round(self.elapsed_s, 6),
            "merge_s": round(self.merge_s, 6),
            "executor": self.executor,
            **self.summary,
        }


def default_chunk_points(total: int) -> int:
    """Points per chunk of a new atlas (independent of the executor, so any may resume).

    Parameters
    ----------
    total : int
        Points of the atlas.

    Returns
    -------
    int
        ``min(DEFAULT_CHUNK_POINTS, ceil(total / MIN_CHUNKS))``, at least 1.
    """
    return max(1, min(DEFAULT_CHUNK_POINTS, -(-total // MIN_CHUNKS)))


def run_atlas(
    atlas: Atlas,
    out: str | os.PathLike[str],
    *,
    backend: str = "process",
    workers: int | None = None,
    scheduler: str | None = None,
    chunk_points: int | None = None,
    overwrite: bool = False,
    csv: bool = False,
    progress: Progress | None = None,
) -> AtlasRun:
    """Compute the atlas's missing chunks into ``out``, then merge and summarise it.

    Parameters
    ----------
    atlas : Atlas
        The atlas (:func:`pushpull_atlas`, :func:`device_atlas`).
    out : path
        Its directory (new or empty; or holding this atlas, which is then resumed).
    backend : {"serial", "process", "dask"}
        Where chunks run: this process, the local process pool, or dask (``scheduler``,
        else a local cluster of ``workers`` processes).
    workers : int, optional
        Worker processes (None: every core).
    scheduler : str, optional
        A dask scheduler address ``tcp://host:port``.
    chunk_points : int, optional
        Points per chunk of a new atlas (None: :func:`default_chunk_points`); an
        existing atlas keeps its own.
    overwrite : bool
        Discard an atlas of other rows in ``out``.
    csv : bool
        Also write ``table.csv``.
    progress : callable, optional
        ``progress(points_done, total)`` after every chunk kept.

    Returns
    -------
    AtlasRun
        Counts, times, the executor and :func:`summarise_table`'s summary.

    Raises
    ------
    UsageError
        A directory holding other rows or no atlas, options out of bounds, an estimated
        time over :mod:`betvdesign.spec.limits`' budget, a dask scheduler not reached.
    """
    backend = check_backend(backend, scheduler)  # before the directory is made
    if workers is not None and not 1 <= workers <= limits.MAX_WORKERS:
        raise UsageError(f"workers must be >= 1 and <= {limits.MAX_WORKERS:,}, got {workers}")
    store = ChunkStore(
        out,
        kind=atlas.kind,
        definition=atlas.definition,
        columns=atlas.columns,
        total=atlas.total,
        chunk_points=chunk_points,
        default_chunk=default_chunk_points(atlas.total),
        overwrite=overwrite,
    )
    try:
        if atlas.about:
            store.write_manifest(about=atlas.about)
        return _run(atlas, store, backend, workers, scheduler, csv, progress)
    finally:
        store.close()


def _run(
    atlas: Atlas,
    store: ChunkStore,
    backend: str,
    workers: int | None,
    scheduler: str | None,
    csv: bool,
    progress: Progress | None,
) -> AtlasRun:
    """:func:`run_atlas` once its store is open."""
    todo = list(iter_missing(store))
    resumed = store.n_chunks - len(todo)
    points_left = sum(t["stop"] - t["start"] for t in todo)
    n_workers = 1 if backend == "serial" else (workers or os.cpu_count() or 1)
    if todo and scheduler is None:
        cost = limits.point_cost_s(atlas.kind, atlas.definition)
        limits.refuse_long_study(f"{atlas.kind} atlas", points_left, cost, n_workers)
    done_points = atlas.total - points_left
    if progress:
        progress(done_points, atlas.total)
    computed = computed_points = 0
    info: dict[str, Any] = {"backend": backend, "workers": n_workers, "scheduler": scheduler}
    t0 = time.perf_counter()
    try:
        if todo:
            with open_executor(backend, workers=workers, chunksize=1, scheduler=scheduler) as ex:
                chunks = ex.run(atlas.worker, todo)
                try:
                    for batch in chunks:
                        for result in batch:
                            i = int(result["key"])
                            store.write_chunk(i, result["arrays"])
                            computed += 1
                            start, stop = store.bounds(i)
                            done_points += stop - start
                            computed_points += stop - start
                            if progress:
                                progress(done_points, atlas.total)
                finally:
                    chunks.close()  # an interrupted run stops its workers now
                info = {**ex.info().__dict__}
                info.pop("extra", None)
    except BaseException as exc:
        kept = store.n_chunks - len(store.missing())
        store.write_manifest(status="interrupted", done=kept)
        if isinstance(exc, BrokenExecutor):  # a worker killed (OOM killer, kill -9)
            raise UsageError(
                f"a worker process died ({exc}); the {kept:,} finished chunks of "
                f"{store.n_chunks:,} are kept in {store.dir}: run the same command again "
                "to resume"
            ) from None
        raise
    elapsed = time.perf_counter() - t0
    t1 = time.perf_counter()
    table = store.merge(csv=csv)
    summary = summarise_table(atlas, table)
    merge_s = time.perf_counter() - t1
    write_atomic(store.dir / SUMMARY, json.dumps(summary, indent=2) + "\n")
    store.write_manifest(status="complete", done=store.n_chunks, executor=info, summary=summary)
    return AtlasRun(
        path=store.dir,
        total=atlas.total,
        chunks=store.n_chunks,
        chunk_points=store.chunk_points,
        computed=computed,
        computed_points=computed_points,
        resumed=resumed,
        elapsed_s=elapsed,
        merge_s=merge_s,
        executor=info,
        summary=summary,
    )


def summarise_table(atlas: Atlas, table: Mapping[str, np.ndarray]) -> dict[str, Any]:
    """Points per mode (and per solver status) of a merged atlas.

    Parameters
    ----------
    atlas : Atlas
        The atlas.
    table : mapping of str to numpy.ndarray
        Its encoded columns (:meth:`ChunkStore.merge`).

    Returns
    -------
    dict
        ``modes``: points per mode (``pushpull``: the simulated mode of each converged
        point, else its status; ``device``: the exact mode, as ``betv sweep FILE``);
        ``status``: points per solver status; for ``pushpull``, ``converged`` and
        ``lambda_agrees`` (converged points where λ < 1 names the simulated mode).
    """
    names = list(atlas.columns)
    n = len(table["c0"])
    modes: Counter[str] = Counter()
    status: Counter[str] = Counter()
    out: dict[str, Any] = {"kind": atlas.kind}
    converged = agrees = 0
    for start in range(0, n, SUMMARY_BLOCK):  # a block of Python values at a time
        rows = slice(start, min(n, start + SUMMARY_BLOCK))

        def col(name: str, rows: slice = rows) -> list[Any]:
            return column_values(table, names.index(name), atlas.columns[name], rows)

        st = col("status")
        status.update(count_values(st))
        if atlas.kind == "pushpull":
            conv, mode, lam = col("converged"), col("mode"), col("lambda_mode")
            modes.update(
                count_values(m if c else s for m, c, s in zip(mode, conv, st, strict=True))
            )
            converged += sum(bool(c) for c in conv)
            agrees += sum(bool(c) and m == lm for c, m, lm in zip(conv, mode, lam, strict=True))
        else:
            modes.update(count_values(col(atlas.mode_column)))
    if atlas.kind == "pushpull":
        out["converged"] = converged
        out["lambda_agrees"] = agrees
    out["modes"] = dict(sorted(modes.items(), key=lambda kv: (-kv[1], kv[0])))
    out["status"] = dict(sorted(status.items(), key=lambda kv: (-kv[1], kv[0])))
    return out
