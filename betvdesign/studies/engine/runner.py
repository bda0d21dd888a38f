"""Run a study: tasks -> executor -> streamed store -> sorted rows.

A :class:`Study` is plain data: a name, typed result columns, the parameters
that define its results (recorded in the sidecar and checked on resume), a
list of tasks (dicts with an integer ``key``) and a module-level worker
``fn(task) -> row``. :func:`run_study` skips keys already on disk, sends the
rest to an executor, appends rows as chunks finish, and reports progress
through a callback ``progress(done, total)``. A study whose estimated time exceeds
the budget of :mod:`betvdesign.spec.limits` is refused before anything is written.
If anything interrupts the run (an exception, Ctrl-C, SIGTERM), the rows finished
so far stay on disk and the sidecar says ``interrupted``; running again resumes.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TypedDict

from betvdesign.spec import limits
from betvdesign.studies.engine.executors import Executor, ExecutorInfo, Row, SerialExecutor, Worker
from betvdesign.studies.engine.store import ColumnType, ResultStore

Progress = Callable[[int, int], None]


class RunArgs(TypedDict, total=False):
    """Keyword arguments of :func:`run_study` that the ``run_*`` helpers pass through."""

    executor: Executor | None
    out: str | os.PathLike[str] | None
    overwrite: bool
    progress: Progress | None


def split_run_args(kwargs: Mapping[str, Any]) -> tuple[dict[str, Any], RunArgs]:
    """Split keyword arguments into the study builder's and :class:`RunArgs`.

    Parameters
    ----------
    kwargs : mapping
        Keywords of a ``run_*`` helper.

    Returns
    -------
    tuple of (dict, RunArgs)
        The study builder's keywords and those of :func:`run_study`.
    """
    run = {k: v for k, v in kwargs.items() if k in RunArgs.__annotations__}
    rest = {k: v for k, v in kwargs.items() if k not in run}
    return rest, RunArgs(**run)  # type: ignore[typeddict-item]


@dataclass(frozen=True)
class Study:
    """Everything needed to run (and resume) one study."""

    name: str
    columns: Mapping[str, ColumnType]
    parameters: Mapping[str, Any]
    tasks: list[dict[str, Any]]
    worker: Worker
    seed: int | None = None


@dataclass
class StudyRun:
    """Outcome of :func:`run_study`: rows sorted by key plus counters."""

    study: str
    rows: list[Row]
    total: int
    computed: int
    resumed: int
    elapsed_s: float
    executor: ExecutorInfo
    path: Path | None = None
    extra: dict[str, Any] = field(default_factory=dict)


def _open_store(
    study: Study, executor: Executor, out: str | os.PathLike[str] | None, overwrite: bool
) -> tuple[ResultStore | None, dict[int, Row]]:
    """Open the output of ``study`` (resuming one of the same study) and its done rows.

    Parameters
    ----------
    study : Study
        The study.
    executor : Executor
        Where the tasks run (recorded in the sidecar).
    out : path or None
        The CSV file (None: rows kept in memory only).
    overwrite : bool
        Replace an output of another study.

    Returns
    -------
    store : ResultStore or None
        The output.
    done : dict of int to Row
        The rows already computed, by key (the store's own, kept up to date by it).
    """
    total = len(study.tasks)
    store: ResultStore | None = None
    done: dict[int, Row] = {}
    if out is not None:
        store = ResultStore(
            out,
            study=study.name,
            columns=study.columns,
            parameters=study.parameters,
            seed=study.seed,
            total=total,
            overwrite=overwrite,
        )
        store.write_sidecar(executor=executor.info().__dict__)
        done = store.done
    return store, done


def _compute(
    study: Study,
    executor: Executor,
    todo: list[dict[str, Any]],
    sink: tuple[ResultStore | None, dict[int, Row]],
    progress: Progress | None,
) -> int:
    """Run the tasks not done yet, streaming their rows to the store (or ``done``).

    Parameters
    ----------
    study : Study
        The study.
    executor : Executor
        Where the tasks run.
    todo : list of dict
        The tasks to run.
    sink : tuple
        The store (None: none) and the done rows by key.
    progress : callable, optional
        ``progress(done, total)`` after every chunk.

    Returns
    -------
    int
        Rows computed.

    Raises
    ------
    BaseException
        Whatever interrupts the run, after the store is closed as "interrupted".
    """
    store, done = sink
    total = len(study.tasks)
    computed = 0
    try:
        for rows in executor.run(study.worker, todo):
            if store is not None:
                store.append(rows)
            else:
                for row in rows:
                    done[int(row["key"])] = row
            computed += len(rows)
            if progress:
                progress(len(done), total)
    except BaseException:
        if store is not None:
            store.close("interrupted", computed_this_run=computed)
        raise
    return computed


def run_study(
    study: Study,
    executor: Executor | None = None,
    *,
    out: str | os.PathLike[str] | None = None,
    overwrite: bool = False,
    progress: Progress | None = None,
) -> StudyRun:
    """Run ``study`` (serially unless an executor is given), streaming to ``out``.

    Parameters
    ----------
    study : Study
        The study.
    executor : Executor, optional
        Where the tasks run (None: :class:`SerialExecutor`).
    out : path, optional
        CSV file the rows are appended to as chunks finish (with a JSON sidecar); a
        finished or interrupted output of the same study is resumed.
    overwrite : bool
        Replace an output of another study instead of refusing it.
    progress : callable, optional
        ``progress(done, total)`` after every chunk.

    Returns
    -------
    StudyRun
        Rows sorted by key, counts (total, computed, resumed), elapsed time [s], the
        executor and the output's path.

    Raises
    ------
    UsageError
        A study over the time budget of :mod:`betvdesign.spec.limits`, or an output that
        cannot be resumed.
    """
    executor = executor or SerialExecutor()
    total = len(study.tasks)
    workers = executor.info().workers
    if workers:  # 0: a dask cluster not reached yet, of unknown size
        limits.refuse_long_study(
            f"{study.name} study", total, limits.point_cost_s(study.name, study.parameters), workers
        )
    store, done = _open_store(study, executor, out, overwrite)
    resumed = len(done)
    todo = [t for t in study.tasks if t["key"] not in done]
    if progress:
        progress(len(done), total)
    t0 = time.perf_counter()
    computed = _compute(study, executor, todo, (store, done), progress)
    elapsed = time.perf_counter() - t0
    if store is not None:
        # the executor again: a dask cluster's size is known only once it has run
        store.close(
            "complete",
            computed_this_run=computed,
            elapsed_s=elapsed,
            executor=executor.info().__dict__,
        )
    return StudyRun(
        study=study.name,
        rows=[done[k] for k in sorted(done)],
        total=total,
        computed=computed,
        resumed=resumed,
        elapsed_s=elapsed,
        executor=executor.info(),
        path=Path(out) if out is not None else None,
    )
