"""Helpers shared by the CLI commands: error reporting, exit codes, interruption,
validation of numeric options and output paths, and the options the study commands
share (execution, output, ``--json``, ``-q``: declared once here, used by ``betv sweep``,
``betv tolerance`` and ``betv calibrate``; ``betv report`` takes ``-q`` and the progress
bar).

Every command turns user errors into ``error: ...`` lines and exit code 2
(:func:`user_errors`), stops cleanly on Ctrl-C or SIGTERM with exit 130
(:func:`interruptible`), validates numeric options with click callbacks that put
the allowed range in the message (:func:`int_option`, :func:`float_option`,
:func:`seed_option`), and checks output paths before any work
(:func:`output_file`, :func:`output_dir`, from :mod:`betvdesign.output.files`, which
also writes every file atomically).
"""

from __future__ import annotations

import contextlib
import json
import math
import signal
import sys
import threading
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any, TypeVar

import typer

from betvdesign.errors import BetvError
from betvdesign.output.files import check_output_dir, check_output_file
from betvdesign.spec import limits

if TYPE_CHECKING:  # the study engine loads when a study runs, not for `betv --help`
    from betvdesign.studies.engine.runner import StudyRun

EXIT_OK = 0
EXIT_RULE_FAILED = 1
EXIT_BAD_INPUT = 2
#: Interrupted by Ctrl-C or SIGTERM (128 + SIGINT, the shell's convention).
EXIT_INTERRUPTED = 130

__all__ = [
    "EXIT_BAD_INPUT",
    "EXIT_INTERRUPTED",
    "EXIT_OK",
    "EXIT_RULE_FAILED",
    "ChunkOpt",
    "Execution",
    "ExecutorOpt",
    "FidelityOpt",
    "JsonOpt",
    "MaxCyclesOpt",
    "OutOpt",
    "OverwriteOpt",
    "QuietOpt",
    "ResidualTolOpt",
    "RetiredTolOpt",
    "SchedulerOpt",
    "WorkersOpt",
    "emit",
    "float_option",
    "int_option",
    "interruptible",
    "output_dir",
    "output_file",
    "progress_bar",
    "renamed_option",
    "run_block",
    "seed_option",
    "user_errors",
]

output_file = check_output_file
output_dir = check_output_dir
T = TypeVar("T")


@contextlib.contextmanager
def user_errors() -> Iterator[None]:
    """Turn :class:`BetvError` into a clean message on stderr and exit code 2."""
    try:
        yield
    except BetvError as exc:
        for line in str(exc).splitlines() or [type(exc).__name__]:
            print(f"error: {line}", file=sys.stderr)
        raise typer.Exit(EXIT_BAD_INPUT) from None


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised where Ctrl-C would be, so both take the same clean-up path."""


#: The signals received inside :func:`interruptible` (its handlers note them): an error
#: raised after one of them (a dask client cancelled mid-call, a pool torn down) is the
#: interruption's consequence, and the command ends as interrupted, not with a traceback.
_RECEIVED: list[int] = []


def raise_terminated(signum: int, frame: Any) -> None:
    """SIGTERM handler: raise :class:`Terminated` where the program is (after a running
    solve returns: :func:`betvdesign.dynamics.jit.interrupt`)."""
    from betvdesign.dynamics.jit import interrupt

    _RECEIVED.append(signum)
    interrupt(Terminated())


def raise_interrupted(signum: int, frame: Any) -> None:
    """Ctrl-C handler: raise ``KeyboardInterrupt`` where the program is (after a running
    solve returns: :func:`betvdesign.dynamics.jit.interrupt`)."""
    from betvdesign.dynamics.jit import interrupt

    _RECEIVED.append(signum)
    interrupt(KeyboardInterrupt())


@contextlib.contextmanager
def interruptible(kept: str | Path | None = None, *, resumable: bool = True) -> Iterator[None]:
    """Ctrl-C or SIGTERM: clean up (the ``finally`` blocks below run: workers stop,
    a study's sidecar says ``interrupted``), say what was kept and exit 130 without a
    traceback.

    kept: the output holding the finished work, if any; resumable: whether running
    the same command again continues where it stopped (studies) or starts afresh.
    """
    previous = previous_int = None
    _RECEIVED.clear()
    if threading.current_thread() is threading.main_thread():
        previous = signal.signal(signal.SIGTERM, raise_terminated)
        if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
            previous_int = signal.signal(signal.SIGINT, raise_interrupted)
    try:
        yield
    except BaseException as exc:
        if isinstance(exc, typer.Exit) or not (isinstance(exc, KeyboardInterrupt) or _RECEIVED):
            raise
        term = isinstance(exc, Terminated) or signal.SIGTERM in _RECEIVED
        what = "terminated" if term else "interrupted"
        if resumable:
            where = f"finished points are kept in {kept}; " if kept else ""
            tail = f"{where}run the same command again to resume"
        else:
            tail = "nothing was left half-written (each file is written whole or not at all)"
        print(f"{what}: {tail}", file=sys.stderr)
        raise typer.Exit(EXIT_INTERRUPTED) from None
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)
        if previous_int is not None:
            signal.signal(signal.SIGINT, previous_int)


def _bounds_text(lo: float | None, hi: float | None, lo_open: bool, hi_open: bool) -> str:
    def fmt(x: float) -> str:
        return f"{x:,}" if isinstance(x, int) else f"{x:g}"

    parts = []
    if lo is not None:
        parts.append(f"{'>' if lo_open else '>='} {fmt(lo)}")
    if hi is not None:
        parts.append(f"{'<' if hi_open else '<='} {fmt(hi)}")
    return " and ".join(parts)


def int_option(lo: int | None = None, hi: int | None = None, *, why: str = "") -> Callable:
    """Click callback: an integer option within ``[lo, hi]`` (None = unbounded)."""

    def check(value: int | None) -> int | None:
        if value is None:
            return None
        if (lo is not None and value < lo) or (hi is not None and value > hi):
            note = f" ({why})" if why else ""
            raise typer.BadParameter(
                f"must be {_bounds_text(lo, hi, False, False)}{note}, got {value:,}"
            )
        return value

    return check


def float_option(
    *,
    gt: float | None = None,
    ge: float | None = None,
    lt: float | None = None,
    le: float | None = None,
) -> Callable:
    """Click callback: a finite float option within the given bounds."""
    lo, lo_open = (gt, True) if gt is not None else (ge, False)
    hi, hi_open = (lt, True) if lt is not None else (le, False)

    def check(value: float | None) -> float | None:
        if value is None:
            return None
        ok = math.isfinite(value)
        ok = ok and (lo is None or (value > lo if lo_open else value >= lo))
        ok = ok and (hi is None or (value < hi if hi_open else value <= hi))
        if not ok:
            rng = _bounds_text(lo, hi, lo_open, hi_open)
            raise typer.BadParameter(f"must be a finite number {rng}, got {value:g}".strip())
        return value

    return check


def seed_option(value: int | None) -> int | None:
    """Click callback: a seed numpy's ``SeedSequence`` takes, 0 <= seed < 2**128."""
    if value is not None and not 0 <= value < limits.SEED_BOUND:
        raise typer.BadParameter(
            f"must be an integer with 0 <= seed < 2**128 (numpy's SeedSequence), got {value}"
        )
    return value


def renamed_option(new: str, meaning: str) -> Callable:
    """Click callback of a hidden, retired option: any use is an error naming ``new``."""

    def check(value: Any) -> None:
        if value:
            raise typer.BadParameter(f"renamed: use {new} ({meaning})")

    return check


# -- options shared by the study commands (betv sweep ..., betv tolerance, betv calibrate)
ExecutorOpt = Annotated[
    str,
    typer.Option(
        "--executor", "-x", help="serial, process (all cores) or dask (case-insensitive)."
    ),
]
WorkersOpt = Annotated[
    int | None,
    typer.Option(
        "--workers",
        "-j",
        help=f"Worker processes (default: all cores; 1 to {limits.MAX_WORKERS}).",
        callback=int_option(1, limits.MAX_WORKERS),
    ),
]
ChunkOpt = Annotated[
    int | None,
    typer.Option(
        "--chunksize",
        help=f"Points per task sent to a worker (1 to {limits.MAX_CHUNKSIZE:,}).",
        callback=int_option(1, limits.MAX_CHUNKSIZE),
    ),
]
SchedulerOpt = Annotated[
    str | None, typer.Option("--scheduler", help="dask.distributed scheduler tcp://host:port.")
]
OutOpt = Annotated[
    Path | None,
    typer.Option("--out", "-o", help="Stream rows to this CSV (+ .json sidecar); resumable."),
]
MaxCyclesOpt = Annotated[
    int | None,
    typer.Option(
        "--max-cycles",
        help="Cycle budget per periodic solve (default: the solver's, 100000; at most "
        f"{limits.MAX_CYCLES:,}); points that do not settle within it are listed as not "
        "converged.",
        callback=int_option(1, limits.MAX_CYCLES),
    ),
]
ResidualTolOpt = Annotated[
    float,
    typer.Option(
        "--residual-tol",
        help="Periodic solver: fixed-point residual accepted [-], in (0, 0.1].",
        callback=float_option(gt=0.0, le=0.1),
    ),
]
#: ``--tol`` meant a solver residual here but a Monte Carlo spread in ``betv tolerance``;
#: both have their own names now, and the old one says so.
RetiredTolOpt = Annotated[
    str | None,
    typer.Option(
        "--tol",
        hidden=True,
        callback=renamed_option(
            "--residual-tol", "the solver's residual; the Monte Carlo spread is `--spread`"
        ),
    ),
]
FidelityOpt = Annotated[
    str,
    typer.Option(
        help="Fidelity rung: periodic (exact periodic orbits) or lambda (closed-form fit)."
    ),
]
OverwriteOpt = Annotated[
    bool, typer.Option("--overwrite", help="Start afresh even if --out holds other results.")
]
JsonOpt = Annotated[bool, typer.Option("--json", help="Print a JSON summary on stdout.")]
QuietOpt = Annotated[bool, typer.Option("--quiet", "-q", help="No progress bar.")]


@dataclass(frozen=True)
class Execution:
    """The execution options every study command takes, and how to apply them."""

    executor: str
    workers: int | None
    chunksize: int | None
    scheduler: str | None
    out: Path | None
    overwrite: bool
    quiet: bool

    def run(self, label: str, fn: Callable[..., T], /, *args: Any, **kwargs: Any) -> T:
        """``fn(*args, **kwargs)`` with the executor, output and a progress bar."""
        from betvdesign.studies.engine.executors import make_executor

        if self.out is not None:
            output_file(self.out, create_parent=True)
        ex = make_executor(
            self.executor, workers=self.workers, chunksize=self.chunksize, scheduler=self.scheduler
        )
        with progress_bar(label, self.quiet) as progress:
            return fn(
                *args,
                executor=ex,
                out=str(self.out) if self.out else None,
                overwrite=self.overwrite,
                progress=progress,
                **kwargs,
            )


@contextlib.contextmanager
def progress_bar(label: str, quiet: bool) -> Iterator[Callable[[int, int], None] | None]:
    """A rich progress bar on stderr; yields the ``progress(done, total)`` callback."""
    if quiet:
        yield None
        return
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TimeRemainingColumn

    bar = Progress(
        "[progress.description]{task.description}",
        BarColumn(),
        MofNCompleteColumn(),
        TimeRemainingColumn(),
        console=Console(stderr=True),
        transient=False,
    )
    task_id = bar.add_task(label, total=None)
    started = False

    def update(done: int, total: int) -> None:
        nonlocal started
        if not started:  # start on the first report, so input errors print no bar
            bar.start()
            started = True
        bar.update(task_id, completed=done, total=total)

    try:
        yield update
    finally:
        if started:
            bar.stop()


def emit(summary: dict[str, Any], as_json: bool, human: Callable[[], None]) -> None:
    """Print the JSON summary on stdout, or the human-readable form (led by the fidelity
    rung the study used and why, when the summary states one)."""
    if as_json:
        typer.echo(json.dumps(summary, indent=2, allow_nan=False))
        return
    if "fidelity" in summary and "fidelity_reason" in summary:
        typer.echo(f"fidelity rung {summary['fidelity']}: {summary['fidelity_reason']}")
    human()


def run_block(run: StudyRun) -> dict[str, Any]:
    """The execution part of every summary."""
    return {
        "points": run.total,
        "computed": run.computed,
        "resumed": run.resumed,
        "elapsed_s": round(run.elapsed_s, 6),
        "executor": run.executor.backend,
        "workers": run.executor.workers,
        "out": str(run.path) if run.path else None,
    }
