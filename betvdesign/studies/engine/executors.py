"""Executors: run one study serially, on local processes, or on a dask cluster.

Every study is a list of independent tasks and a module-level worker function
``fn(task) -> row`` taking and returning plain picklable data. An executor
splits the tasks into chunks (to amortise inter-process traffic), runs
``fn`` over each chunk somewhere, and yields each finished chunk's rows as
soon as it completes (completion order, not task order). Rows carry their
grid key, so the caller (``studies.engine.runner``) can stream them to disk and a
resumed run can skip what is finished.

Backends:

* :class:`SerialExecutor` -- in this process; the reference, and what tests and
  debuggers want.
* :class:`ProcessExecutor` -- ``concurrent.futures`` over ``forkserver``
  processes (safe next to threads; the default, all cores).
* :class:`DaskExecutor` -- a ``dask.distributed`` scheduler (``tcp://host:port``)
  or a given ``Client``; dask is an optional extra (``pip install betvdesign[dask]``).

Work is submitted through a bounded window of in-flight chunks, so a study of
millions of points does not create millions of futures, and an interrupted run
(exception, Ctrl-C) cancels what has not started.

All three run the same worker code, so they return bitwise-identical floats.
"""

from __future__ import annotations

import contextlib
import itertools
import math
import multiprocessing
import os
import pickle
import select
import signal
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import (
    FIRST_COMPLETED,
    Future,
    InvalidStateError,
    ProcessPoolExecutor,
    wait,
)
from dataclasses import dataclass, field
from typing import Any, Protocol

from betvdesign.errors import UsageError
from betvdesign.spec import limits

Task = Any
Row = dict[str, Any]
Worker = Callable[[Task], Row]

#: Modules the fork server imports once so workers start warm (missing ones are skipped).
_PRELOAD = (
    "numpy",
    "scipy.optimize",
    "betvdesign.spec.loader",
    "betvdesign.nondim.device",
    "betvdesign.dynamics",
)

#: Per backend: chunks per worker the default chunk size aims at, and the most tasks
#: per chunk. A local pool hands over a chunk in well under a millisecond, so many small
#: chunks balance heavy-tailed point costs; a dask chunk costs a scheduler round trip
#: and a client-side result (about 1-10 ms), so dask gets few large chunks.
_CHUNKING = {"process": (16, 32), "serial": (16, 32), "dask": (8, 2048)}

#: Studies of at most this many tasks run in this process when the chunk size is the
#: default (two of the pool's largest chunks): starting a pool costs more than they do.
SMALL_STUDY = 2 * _CHUNKING["process"][1]

#: Module the fork server imports after ``_PRELOAD``: it loads (or compiles) the solver
#: kernels once, so that every worker forked from it starts with them in memory.
_WARM_MODULE = "betvdesign.studies.engine.preload"

#: In-flight chunks per worker (keeps workers busy without flooding the queue).
_WINDOW_PER_WORKER = 4


def _watch_parent(pid: int) -> None:
    """Exit this worker as soon as process ``pid`` (the study's main process) is gone.

    Workers are children of the fork server, not of the main process, so neither
    their parent's exit nor a closed queue tells them that the main process was
    killed (SIGKILL runs no clean-up): without this they would wait for work for
    ever. A ``pidfd`` (Linux >= 5.3) wakes the thread the moment ``pid`` exits;
    elsewhere it polls every 0.2 s.
    """
    try:
        fd = os.pidfd_open(pid)
    except (AttributeError, OSError):
        fd = None
    if fd is not None:
        select.select([fd], [], [])
        os._exit(1)
    while True:
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            os._exit(1)
        except PermissionError:  # pid reused by another user's process: ours is gone
            os._exit(1)
        time.sleep(0.2)


def _init_worker(main_pid: int) -> None:
    """Worker start-up: leave Ctrl-C to the main process, watch for it to end.

    Worker start-up: Ctrl-C is the main process's to handle (it stops the pool;
    a worker printing its own KeyboardInterrupt traceback would only be noise), and
    a watchdog ends the worker when the main process is gone.
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    threading.Thread(
        target=_watch_parent, args=(main_pid,), name="betv-parent-watch", daemon=True
    ).start()


def apply_chunk(fn: Worker, chunk: Sequence[Task]) -> list[Row]:
    """Run ``fn`` over one chunk of tasks (module level so it pickles by reference).

    Parameters
    ----------
    fn : callable
        The study's worker ``fn(task) -> row``.
    chunk : sequence
        The tasks.

    Returns
    -------
    list of dict
        One row per task, in the chunk's order.
    """
    return [fn(task) for task in chunk]


def apply_pickled_chunk(fn: Worker, blob: bytes) -> list[Row]:
    """Run ``fn`` over one chunk of tasks sent as one pickle (the dask path).

    ``client.submit`` walks every list, tuple and dict among a task's arguments (looking
    for futures and building graph nodes): for a chunk of 2048 tolerance tasks that took
    0.13-0.25 s on the client, against 0.014-0.033 s for the same chunk as bytes (2 cores,
    load 5-9), and the client submits every chunk of the study, one after another.

    Parameters
    ----------
    fn : callable
        The study's worker ``fn(task) -> row``.
    blob : bytes
        The chunk's tasks, pickled.

    Returns
    -------
    list of dict
        One row per task, in the chunk's order.
    """
    return apply_chunk(fn, pickle.loads(blob))  # our own chunk, pickled by the client


def chunked(tasks: Sequence[Task], size: int) -> list[list[Task]]:
    """Split ``tasks`` into consecutive chunks.

    Parameters
    ----------
    tasks : sequence
        The tasks.
    size : int
        Most tasks per chunk (>= 1).

    Returns
    -------
    list of list
        The chunks, in the tasks' order.

    Raises
    ------
    UsageError
        ``size`` < 1.
    """
    if size < 1:
        raise UsageError(f"chunk size must be >= 1, got {size}")
    return [list(tasks[i : i + size]) for i in range(0, len(tasks), size)]


def default_chunksize(n_tasks: int, workers: int, backend: str = "process") -> int:
    """The default chunk size of a backend: a few chunks per worker, of bounded size.

    The local pool aims at sixteen chunks per worker of 1 to 32 tasks: point costs are
    heavy-tailed (a point that never settles burns the whole cycle budget), so many small
    chunks balance the load, and a chunk of even one periodic solve (milliseconds) still
    dwarfs the pool's hand-over. Dask aims at eight chunks per worker of 1 to 2048 tasks:
    each chunk is a scheduler task with its own round trips (milliseconds), so 32-task
    chunks would spend more time in the scheduler than in the solver.

    Parameters
    ----------
    n_tasks : int
        Number of tasks.
    workers : int
        Number of workers.
    backend : {"process", "serial", "dask"}
        The executor.

    Returns
    -------
    int
        Tasks per chunk.
    """
    if n_tasks <= 0:
        return 1
    per_worker, most = _CHUNKING[backend]
    return max(1, min(most, math.ceil(n_tasks / (per_worker * max(1, workers)))))


@dataclass
class ExecutorInfo:
    """What ran a study (recorded in the results sidecar)."""

    backend: str
    workers: int
    chunksize: int | None
    scheduler: str | None = None
    extra: dict[str, Any] = field(default_factory=dict)


class Executor(Protocol):
    """Runs a worker over tasks and yields finished chunks of rows."""

    def info(self) -> ExecutorInfo:
        """What runs the study (recorded in the results sidecar).

        Returns
        -------
        ExecutorInfo
            Backend, workers, chunk size.
        """
        ...

    def run(self, fn: Worker, tasks: Sequence[Task]) -> Iterator[list[Row]]:
        """Run ``fn`` over ``tasks``.

        Parameters
        ----------
        fn : callable
            Module-level worker ``fn(task) -> row`` (plain, picklable data in and out).
        tasks : sequence
            The tasks, each a dict with an integer ``key``.

        Yields
        ------
        list of dict
            The rows of each finished chunk, in completion order.
        """
        ...


class SerialExecutor:
    """Runs every task in this process, in order; chunks only to pace the output."""

    def __init__(self, chunksize: int | None = None):
        self.chunksize = chunksize

    def info(self) -> ExecutorInfo:
        """What runs the study (:meth:`Executor.info`)."""
        return ExecutorInfo("serial", 1, self.chunksize)

    def run(self, fn: Worker, tasks: Sequence[Task]) -> Iterator[list[Row]]:
        """Run ``fn`` over ``tasks`` in this process, in order (:meth:`Executor.run`)."""
        size = self.chunksize or default_chunksize(len(tasks), 1)
        for chunk in chunked(tasks, size):
            yield apply_chunk(fn, chunk)


def _drain(
    submit: Callable[[list[Task]], Any],
    chunks: list[list[Task]],
    window: int,
    wait_any: Callable[[set[Any]], tuple[set[Any], set[Any]]],
    result: Callable[[Any], list[Row]],
    cancel: Callable[[Any], Any],
) -> Iterator[list[Row]]:
    """Bounded-window submit/yield loop of the process pool (dask: ``as_completed``)."""
    pending: set[Any] = set()
    todo = iter(chunks)
    try:
        for chunk in itertools.islice(todo, window):
            pending.add(submit(chunk))
        while pending:
            done, pending = wait_any(pending)
            for fut in done:
                rows = result(fut)
                nxt = next(todo, None)
                if nxt is not None:
                    pending.add(submit(nxt))
                yield rows
    finally:
        for fut in pending:
            cancel(fut)


class ProcessExecutor:
    """Local worker processes (``forkserver``); default workers = ``os.cpu_count()``."""

    def __init__(self, workers: int | None = None, chunksize: int | None = None):
        if workers is not None and workers < 1:
            raise UsageError(f"workers must be >= 1, got {workers}")
        self.workers = workers or os.cpu_count() or 1
        self.chunksize = chunksize

    def info(self) -> ExecutorInfo:
        """What runs the study (:meth:`Executor.info`)."""
        return ExecutorInfo("process", self.workers, self.chunksize)

    def run(self, fn: Worker, tasks: Sequence[Task]) -> Iterator[list[Row]]:
        """Run ``fn`` over ``tasks`` on local worker processes.

        Run ``fn`` over ``tasks`` on local worker processes (:meth:`Executor.run`); an
        interrupted run terminates them. A study of at most :data:`SMALL_STUDY` tasks
        with the default chunk size runs in this process instead (same worker, same
        rows): the pool's start-up would cost more than the study.
        """
        if not tasks:
            return
        if self.chunksize is None and len(tasks) <= SMALL_STUDY:
            # a pool's start (fork server, imports, kernels) costs more than the study
            yield from SerialExecutor().run(fn, tasks)
            return
        size = self.chunksize or default_chunksize(len(tasks), self.workers)
        chunks = chunked(tasks, size)
        workers = min(self.workers, len(chunks))
        ctx = multiprocessing.get_context("forkserver")
        # Import the heavy modules and load the kernels once, in the fork server, not in
        # every worker (the fork server is started once per process: the first pool's
        # list holds).
        ctx.set_forkserver_preload([*_PRELOAD, fn.__module__, _WARM_MODULE])
        pool = ProcessPoolExecutor(
            max_workers=workers,
            mp_context=ctx,
            initializer=_init_worker,
            initargs=(os.getpid(),),
        )
        finished = False
        try:
            yield from _drain(
                lambda chunk: pool.submit(apply_chunk, fn, chunk),
                chunks,
                _WINDOW_PER_WORKER * workers,
                _wait_first,
                Future.result,
                Future.cancel,
            )
            finished = True
        finally:
            if not finished:  # interrupted (signal, error): stop now, not after the chunks
                _terminate(pool)
            pool.shutdown(wait=True, cancel_futures=True)


def _terminate(pool: ProcessPoolExecutor) -> None:
    """Terminate the pool's worker processes and shut the pool down.

    Terminate the pool's worker processes and shut the pool down (the rows they
    finished are already ours; what they were computing is recomputed on resume).

    The pool's manager thread then marks the futures it still holds as broken; on
    Python < 3.12 it raises ``InvalidStateError`` for those already cancelled
    (CPython gh-94777), which would print a thread traceback: that one exception
    from that thread is silenced while the pool shuts down.
    """
    procs = list((getattr(pool, "_processes", None) or {}).values())
    previous = threading.excepthook

    def quiet(args: threading.ExceptHookArgs) -> None:
        if not isinstance(args.exc_value, InvalidStateError):
            previous(args)

    threading.excepthook = quiet
    try:
        for proc in procs:
            with contextlib.suppress(Exception):
                proc.terminate()
        for proc in procs:
            with contextlib.suppress(Exception):
                proc.join(timeout=5)
        pool.shutdown(wait=True, cancel_futures=True)  # joins the manager thread
    finally:
        threading.excepthook = previous


def _wait_first(pending: set[Future]) -> tuple[set[Future], set[Future]]:
    done, rest = wait(pending, return_when=FIRST_COMPLETED)
    return set(done), set(rest)


class DaskExecutor:
    """A ``dask.distributed`` cluster: ``address`` (``tcp://host:port``) or ``client``."""

    def __init__(
        self,
        address: str | None = None,
        *,
        client: Any = None,
        chunksize: int | None = None,
    ):
        try:
            import distributed  # noqa: F401
        except ImportError:  # pragma: no cover - the extra is installed in the test env
            raise UsageError(
                "the dask executor needs dask.distributed: pip install 'betvdesign[dask]'"
            ) from None
        if address is None and client is None:
            raise UsageError("the dask executor needs a scheduler address (tcp://host:port)")
        self.address = address
        self._client = client
        self.chunksize = chunksize
        #: Threads the cluster gave the last run (0 until a run has connected).
        self.workers = 0

    def _connect(self) -> tuple[Any, bool]:
        if self._client is not None:
            return self._client, False
        from distributed import Client

        try:
            return Client(self.address, timeout="10s"), True
        except (OSError, TimeoutError) as exc:
            raise UsageError(f"cannot reach dask scheduler {self.address}: {exc}") from None

    def info(self) -> ExecutorInfo:
        """What runs the study (:meth:`Executor.info`)."""
        address = self.address
        if address is None and self._client is not None:
            address = self._client.scheduler.address
        return ExecutorInfo("dask", self.workers, self.chunksize, scheduler=address)

    def run(self, fn: Worker, tasks: Sequence[Task]) -> Iterator[list[Row]]:
        """Run ``fn`` over ``tasks`` on the dask cluster (:meth:`Executor.run`).

        The kernels are warmed once per worker (the worker plugin
        :class:`~betvdesign.studies.engine.daskplugin.WarmKernels`), ``fn`` is sent to
        every worker once (scattered, then named by its future in each chunk), the
        chunks are large (:func:`default_chunksize` of ``"dask"``) and travel as one
        pickle each (:func:`apply_pickled_chunk`), and finished chunks are collected by
        ``distributed.as_completed``, which fetches results on the client's event loop
        instead of a blocking round trip per chunk.
        """
        if not tasks:
            return
        from distributed import as_completed

        from betvdesign.studies.engine.daskplugin import WarmKernels

        client, owned = self._connect()
        pending: set[Any] = set()
        try:
            workers = max(1, sum(client.nthreads().values()))
            self.workers = workers
            size = self.chunksize or default_chunksize(len(tasks), workers, "dask")
            client.register_plugin(WarmKernels())
            [fn_remote] = client.scatter([fn], broadcast=True, hash=False)
            todo = iter(chunked(tasks, size))

            def submit(chunk: list[Task]) -> Any:
                blob = pickle.dumps(chunk, protocol=pickle.HIGHEST_PROTOCOL)
                fut = client.submit(apply_pickled_chunk, fn_remote, blob, pure=False)
                pending.add(fut)
                return fut

            first = [submit(c) for c in itertools.islice(todo, _WINDOW_PER_WORKER * workers)]
            done = as_completed(first, with_results=True)
            for fut, rows in done:
                pending.discard(fut)
                nxt = next(todo, None)
                if nxt is not None:
                    done.add(submit(nxt))
                yield rows
        finally:
            if pending:
                with contextlib.suppress(Exception):
                    client.cancel(list(pending))
            if owned:
                client.close()


def make_executor(
    backend: str = "process",
    *,
    workers: int | None = None,
    chunksize: int | None = None,
    scheduler: str | None = None,
) -> Executor:
    """Executor by name: ``serial``, ``process`` (default) or ``dask``.

    Parameters
    ----------
    backend : {"serial", "process", "dask"}
        The executor (case-insensitive).
    workers : int, optional
        Worker processes of ``process`` (None: every core).
    chunksize : int, optional
        Tasks per chunk (None: :func:`default_chunksize`).
    scheduler : str, optional
        A dask scheduler address ``tcp://host:port``; implies ``dask``.

    Returns
    -------
    Executor
        The executor.

    Raises
    ------
    UsageError
        An unknown backend, bounds of :mod:`betvdesign.spec.limits` exceeded, or dask
        without a scheduler.
    """
    backend = check_backend(backend, scheduler)
    if chunksize is not None and not 1 <= chunksize <= limits.MAX_CHUNKSIZE:
        raise UsageError(
            f"chunk size must be >= 1 and <= {limits.MAX_CHUNKSIZE:,}, got {chunksize}"
        )
    if workers is not None and not 1 <= workers <= limits.MAX_WORKERS:
        raise UsageError(f"workers must be >= 1 and <= {limits.MAX_WORKERS:,}, got {workers}")
    if scheduler is not None:
        return DaskExecutor(scheduler, chunksize=chunksize)
    if backend == "serial":
        return SerialExecutor(chunksize)
    if backend == "process":
        return ProcessExecutor(workers, chunksize)
    raise UsageError("the dask executor needs --scheduler tcp://host:port")


def check_backend(backend: str, scheduler: str | None = None) -> str:
    """An executor's name, checked before any work (and any output) starts.

    Parameters
    ----------
    backend : str
        ``serial``, ``process`` or ``dask`` (case-insensitive).
    scheduler : str, optional
        A dask scheduler address (allowed with ``dask``, and with ``process``, the
        default, which it then turns into ``dask``).

    Returns
    -------
    str
        The name, lower case.

    Raises
    ------
    UsageError
        An unknown executor, or a scheduler with the serial one.
    """
    name = backend.strip().lower()
    if name not in ("serial", "process", "dask"):
        raise UsageError(f"unknown executor {name!r} (serial, process or dask)")
    if scheduler is not None and name == "serial":
        raise UsageError(f"--scheduler needs the dask executor, not {name!r}")
    return name


@contextlib.contextmanager
def open_executor(
    backend: str = "process",
    *,
    workers: int | None = None,
    chunksize: int | None = None,
    scheduler: str | None = None,
) -> Iterator[Executor]:
    """An executor by name, with a local dask cluster of its own when dask has no scheduler.

    As :func:`make_executor`, except that ``dask`` without a ``scheduler`` starts a
    ``distributed.LocalCluster`` of ``workers`` single-thread worker processes (default:
    every core) for the duration of the block, and closes it after.

    Parameters
    ----------
    backend : {"serial", "process", "dask"}
        The executor (case-insensitive).
    workers : int, optional
        Worker processes of ``process`` and of a local dask cluster (None: every core).
    chunksize : int, optional
        Tasks per chunk (None: :func:`default_chunksize`).
    scheduler : str, optional
        A dask scheduler address ``tcp://host:port``; implies ``dask``.

    Yields
    ------
    Executor
        The executor.

    Raises
    ------
    UsageError
        As :func:`make_executor`; dask not installed.
    """
    if check_backend(backend, scheduler) != "dask" or scheduler is not None:
        yield make_executor(backend, workers=workers, chunksize=chunksize, scheduler=scheduler)
        return
    if workers is not None and not 1 <= workers <= limits.MAX_WORKERS:
        raise UsageError(f"workers must be >= 1 and <= {limits.MAX_WORKERS:,}, got {workers}")
    try:
        import logging

        from distributed import Client, LocalCluster
    except ImportError:  # pragma: no cover - the extra is installed in the test env
        raise UsageError(
            "the dask executor needs dask.distributed: pip install 'betvdesign[dask]'"
        ) from None
    cluster = LocalCluster(
        n_workers=workers or os.cpu_count() or 1,
        threads_per_worker=1,
        processes=True,
        dashboard_address=":0",  # its HTTP server on a free port: never "8787 in use"
        silence_logs=logging.ERROR,
    )
    try:
        with Client(cluster) as client:
            yield DaskExecutor(client=client, chunksize=chunksize)
    finally:
        cluster.close()
