"""The one decorator of the compiled dynamics: :func:`kernel` (numba ``njit``, cached).

Every function of the contact loop, the certified event search, the phase rule, the
closed-form flows and the vertical schedule is written once, as plain Python that numba
can compile, and decorated with :func:`kernel`. Under ``NUMBA_DISABLE_JIT=1`` numba
returns the functions unchanged: the very same source then runs as Python (debugging,
coverage).

Compiled code is cached on disk in a directory named after a hash of every source file
of this package that defines kernels and of numba's version, so that an edit of any
shared helper can never leave a stale compiled kernel in use. :func:`compile_note`
tells a user on stderr when a command has to compile (no cached machine code), and how
long it took.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import sys
import threading
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import TypeVar

import numba

try:
    import fcntl
except ImportError:  # pragma: no cover - not on POSIX
    fcntl = None  # type: ignore[assignment]

F = TypeVar("F", bound=Callable)

#: modules whose functions are kernels (the cache key covers all of them)
KERNEL_MODULES = (
    "jit",
    "flows",
    "bounds",
    "evaluators",
    "values",
    "search",
    "contact",
    "schedule",
    "shooting",
    "coupled",
)


def cache_dir() -> str:
    """Per-source cache directory of the compiled kernels [path].

    Returns
    -------
    str
        The directory, keyed by a hash of the solver's sources.
    """
    h = hashlib.sha256()
    here = Path(__file__).resolve().parent
    for name in KERNEL_MODULES:
        h.update((here / f"{name}.py").read_bytes())
    h.update(numba.__version__.encode())
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "betvdesign", "numba", h.hexdigest()[:16])


_CACHE_DIR = numba.config.CACHE_DIR or cache_dir()


#: every kernel's dispatcher (their compile statistics tell when a call compiled)
KERNELS: list = []


def kernel(fn: F | None = None, *, inline: bool = False):
    """Compile a kernel with numba, cached, without the GIL.

    ``numba.njit(cache=True, nogil=True)`` with the cache in :func:`cache_dir`;
    ``inline=True``: inlined into its callers by numba (hot helpers taking an
    :class:`evaluators.Evaluator`, which would otherwise be passed field by field).
    """
    if fn is None:
        return lambda f: kernel(f, inline=inline)
    saved = numba.config.CACHE_DIR
    numba.config.CACHE_DIR = _CACHE_DIR  # read when a cached function is decorated
    try:
        opts = {"inline": "always"} if inline else {}
        disp = numba.njit(cache=True, nogil=True, **opts)(fn)
    finally:
        numba.config.CACHE_DIR = saved
    if hasattr(disp, "stats"):
        KERNELS.append(disp)
        _lock_cache_file(disp)
    return disp


def _lock_cache_file(disp: object) -> None:
    """Serialise the kernel's cache index between processes (a lock file beside it).

    numba saves an entry by reading the index, numbering a new data file after the
    entries it holds and writing both back, without a lock: two processes compiling
    two signatures of one kernel at once (the workers of a pool or of the test suite,
    starting cold) can leave the index naming, for one signature, the machine code of
    the other, and a later load of it crashes the process (a segmentation fault, seen
    under ``pytest -n 2``). Saves here hold an exclusive lock, loads a shared one.
    """
    files = getattr(getattr(disp, "_cache", None), "_cache_file", None)
    index = getattr(files, "_index_path", None)
    if index is None or fcntl is None:  # no cache (NUMBA_DISABLE_JIT), another numba, no flock
        return
    save, load = files.save, files.load
    lock = index + ".lock"

    def locked_save(key: object, data: object) -> None:
        with _flocked(lock, fcntl.LOCK_EX):
            save(key, data)

    def locked_load(key: object) -> object:
        with _flocked(lock, fcntl.LOCK_SH):
            return load(key)

    files.save, files.load = locked_save, locked_load


@contextlib.contextmanager
def _flocked(path: str, how: int) -> Iterator[None]:
    """Hold ``flock(how)`` on ``path`` (created) for the block."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "a") as fh:
        fcntl.flock(fh, how)
        try:
            yield
        finally:
            fcntl.flock(fh, fcntl.LOCK_UN)


def jit_enabled() -> bool:
    """True unless ``NUMBA_DISABLE_JIT`` makes the kernels run as plain Python.

    Returns
    -------
    bool
        Whether numba compiles the kernels.
    """
    return not numba.config.DISABLE_JIT


def _misses() -> int:
    """Compilations so far in this process (cache misses of every kernel)."""
    return sum(sum(d.stats.cache_misses.values()) for d in KERNELS)


#: entry points that have run once in this process (their kernels are loaded)
_ready: set[str] = set()
#: compilations counted when the last entry point's first call ended
_seen: list[int] = [0]


#: Entry-point calls running compiled kernels in the main thread now (nested count), and
#: the interrupt a signal handler deferred meanwhile (:func:`interrupt`).
_in_kernels = [0]
_pending: list[BaseException] = []


def interrupt(exc: BaseException) -> None:
    """Raise ``exc`` now, or when the compiled kernels running in the main thread return.

    A signal handler that raises (Ctrl-C's ``KeyboardInterrupt``, the CLI's SIGTERM) runs
    in the main thread at the next bytecode, which can be inside numba's boxing of a
    kernel's named-tuple result (Python code): an exception raised there crashed the
    process with a segmentation fault (measured: 3 of 5 SIGTERMs during ``simulate``,
    5 of 5 on a bare njit kernel returning a namedtuple; numba 0.6x). Handlers call this
    instead of raising: inside an entry point (:func:`compile_note`) the exception is kept
    and raised as soon as the call returns, at most one solve later.

    Parameters
    ----------
    exc : BaseException
        The exception the handler would raise.

    Raises
    ------
    BaseException
        ``exc``, when no kernel runs in the main thread.
    """
    if _in_kernels[0] > 0 and threading.current_thread() is threading.main_thread():
        if not _pending:
            _pending.append(exc)
        return
    raise exc


def compile_note(what: str, run: Callable[[], object]) -> object:
    """Run ``run()`` (an entry point of the kernels), interrupts deferred to its return.

    The main thread's signal handlers that go through :func:`interrupt` raise only after
    ``run()`` returns (or fails); :func:`_compile_note` says when it compiles.

    Parameters
    ----------
    what : str
        The entry point, named in the note.
    run : callable
        What to run.

    Returns
    -------
    object
        What ``run()`` returns.
    """
    main = threading.current_thread() is threading.main_thread()
    if main:
        _in_kernels[0] += 1
    try:
        return _compile_note(what, run)
    finally:
        if main:
            _in_kernels[0] -= 1
            if _in_kernels[0] == 0 and _pending:
                raise _pending.pop()


def _compile_note(what: str, run: Callable[[], object]) -> object:
    """Run ``run()``, saying on stderr when it compiles kernels.

    Run ``run()``; when it has to compile kernels (no cached machine code for this
    solver version yet), say so on stderr in one line, with what and how long, instead of
    compiling silently (``make demo`` compiles them ahead: :mod:`warm`). The first call of
    each entry point is watched from a thread (the note appears when compiling starts);
    later calls count compilations only when they lasted long enough to have compiled
    (counting on every call cost as much as a periodic orbit).

    Parameters
    ----------
    what : str
        The entry point, named in the note.
    run : callable
        What to run.

    Returns
    -------
    object
        What ``run()`` returns.
    """
    if not jit_enabled():
        return run()
    t0 = time.perf_counter()
    if what in _ready:  # loaded: only a call lasting long enough can have compiled
        out = run()
        dt = time.perf_counter() - t0
        if dt > 0.5 and _misses() > _seen[0]:
            _seen[0] = _misses()
            print(f"betv: compiled solver kernels for {what} in {dt:.1f} s", file=sys.stderr)
        return out
    before = _misses()
    done = threading.Event()
    said: list[float] = []

    def watch() -> None:
        while not done.wait(0.25):
            if _misses() > before:
                print(
                    f"betv: compiling the solver kernels for {what} (once per install or "
                    "solver version; `make demo` does it ahead)...",
                    file=sys.stderr,
                    end="",
                    flush=True,
                )
                said.append(time.perf_counter())
                return

    watcher = threading.Thread(target=watch, daemon=True)
    watcher.start()
    try:
        out = run()
        _ready.add(what)
        _seen[0] = _misses()
        return out
    finally:
        done.set()
        watcher.join()
        if said:
            print(f" done in {time.perf_counter() - t0:.1f} s", file=sys.stderr, flush=True)
