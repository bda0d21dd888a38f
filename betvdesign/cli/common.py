"""Helpers shared by the CLI commands: error reporting, exit codes, interruption, and
validation of numeric options and output paths.

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
import math
import signal
import sys
import threading
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import typer

from betvdesign.errors import BetvError
from betvdesign.output.files import check_output_dir, check_output_file
from betvdesign.spec import limits

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
    "float_option",
    "int_option",
    "interruptible",
    "output_dir",
    "output_file",
    "seed_option",
    "user_errors",
]

output_file = check_output_file
output_dir = check_output_dir


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


def raise_terminated(signum: int, frame: Any) -> None:
    """SIGTERM handler: raise :class:`Terminated` where the program is."""
    raise Terminated()


@contextlib.contextmanager
def interruptible(kept: str | Path | None = None, *, resumable: bool = True) -> Iterator[None]:
    """Ctrl-C or SIGTERM: clean up (the ``finally`` blocks below run: workers stop,
    a study's sidecar says ``interrupted``), say what was kept and exit 130 without a
    traceback.

    kept: the output holding the finished work, if any; resumable: whether running
    the same command again continues where it stopped (studies) or starts afresh.
    """
    previous = None
    if threading.current_thread() is threading.main_thread():
        previous = signal.signal(signal.SIGTERM, raise_terminated)
    try:
        yield
    except KeyboardInterrupt as exc:
        what = "terminated" if isinstance(exc, Terminated) else "interrupted"
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
