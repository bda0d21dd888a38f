"""The slow work of ``betv explore`` on worker processes, never in the page's way.

The settling transient, the model-adequacy scan, the fix search, the field map and the
report run on :class:`Workers`: forkserver process pools (one process per lane, so
the page's own updates keep the server's process to themselves). Every job takes the
design as its YAML text (what a saved file would hold) and returns plain data.

A job carries the generation of its lane when it was queued; a session bumps its lane
(:meth:`Workers.bump`) when the design moves on, and a queued job that finds its lane
moved on returns ``None`` at once: the latest design wins, stale work is dropped
before it starts.
"""

from __future__ import annotations

import contextlib
import functools
import multiprocessing
import os
import threading
from collections.abc import Callable
from dataclasses import asdict
from typing import Any

__all__ = ["LANES", "Workers", "check_job", "fix_job", "map_job", "report_job"]

#: Job lanes: "check" (settling, adequacy, fixes), "map" (the field map), "report".
LANES = ("check", "map", "report")
#: Sessions that can run jobs at once without sharing generation slots.
SLOTS = 64
#: Niceness added to the worker processes (the server's own updates come first).
NICE = 10
_GEN: Any = None  # the shared generations, in each worker (set by _init)


def _init(gen: Any) -> None:
    import signal

    global _GEN
    _GEN = gen
    # Ctrl-C reaches the whole process group: the server stops the workers itself
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    with contextlib.suppress(OSError):  # the page's own updates come first
        os.nice(NICE)
    try:  # load the compiled kernels now, not in the first job
        from betvdesign.dynamics import periodic_orbit
        from betvdesign.model.params import ModelParams

        periodic_orbit(ModelParams(1.2, 2.0, 0.5, 0.15))
    except Exception:  # a worker that cannot warm up still answers (with the error)
        pass


def _stale(slot: int, gen: int) -> bool:
    return _GEN is not None and _GEN[slot] != gen


@functools.lru_cache(maxsize=8)
def _spec(text: str, filename: str) -> Any:
    from betvdesign.spec.loader import load_device_text

    return load_device_text(text, filename)


def check_job(
    slot: int, gen: int, text: str, filename: str, stage: str, options: dict[str, Any]
) -> dict[str, Any] | None:
    """One stage of :func:`betvdesign.explore.compute.evaluate` (without traces)."""
    if _stale(slot, gen):
        return None
    from betvdesign.explore.compute import evaluate

    ev = evaluate(_spec(text, filename), stage, source_file=filename, **options)  # type: ignore[arg-type]
    return {"stage": ev.stage, "out": ev.out, "settling": ev.settling, "elapsed_s": ev.elapsed_s}


def map_job(
    slot: int, gen: int, text: str, filename: str, set_index: int, x: Any, y: Any, rows: list[int]
) -> dict[str, Any] | None:
    """Rows of :func:`betvdesign.studies.fieldmap.map_rows` as plain data."""
    if _stale(slot, gen):
        return None
    from betvdesign.studies.fieldmap import map_rows

    part = map_rows(_spec(text, filename), set_index, x, y, rows)
    d = asdict(part)
    d["reasons"] = [[j, i, r] for (j, i), r in part.reasons.items()]
    return d


def fix_job(
    slot: int, gen: int, text: str, filename: str, target_speed_m_s: float | None
) -> dict[str, Any] | None:
    """``betv fix`` (:func:`betvdesign.studies.fix.find_fixes`, default fields): its JSON
    with, per candidate, each change as the device file writes it."""
    if _stale(slot, gen):
        return None
    from betvdesign.errors import BetvError
    from betvdesign.spec.units import format_quantity
    from betvdesign.studies.fix import find_fixes, parse_vary

    spec = _spec(text, filename)
    try:
        res = find_fixes(spec, parse_vary(spec, []), target_speed_m_s=target_speed_m_s)
    except BetvError as exc:
        return {"status": "error", "message": str(exc), "candidates": []}
    d = res.as_dict()
    for c, cd in zip(res.candidates, d["candidates"], strict=True):
        files = {}
        for f, x in c.changes.items():
            v = res.varies[f]
            files[f] = format_quantity(v.quantity(x), ".4g") if v.unit else float(f"{x:.4g}")
        cd["values"] = {f: [float(x), res.varies[f].unit] for f, x in c.changes.items()}
        cd["file_values"] = files
    return d


def report_job(slot: int, gen: int, text: str, filename: str, name: str) -> str | None:
    """The HTML ``betv report`` writes for the design saved as ``name`` (its path)."""
    if _stale(slot, gen):
        return None
    import dataclasses
    import tempfile
    from pathlib import Path

    from betvdesign.report import build_report, prepare, render_html

    with tempfile.TemporaryDirectory(prefix="betv-explore-") as tmp:
        path = Path(tmp) / Path(name).name
        path.write_text(text, encoding="utf-8")
        prepared = dataclasses.replace(prepare(path), path=Path(name))
        return render_html(build_report(prepared))


class Workers:
    """The job lanes (see the module docstring); ``start`` before use, ``close`` at the
    end (kills what still runs)."""

    def __init__(self) -> None:
        ctx = multiprocessing.get_context("forkserver")
        self._ctx = ctx
        self.gen = ctx.Array("q", SLOTS * len(LANES), lock=False)
        self.pools: dict[str, Any] = {}
        self._lock = threading.Lock()
        self._slots = 0

    def start(self, lanes: tuple[str, ...] = ("check", "map")) -> None:
        """Start the pools of ``lanes`` (each warms its kernels in the background)."""
        with self._lock:
            for lane in lanes:
                if lane not in self.pools:
                    self.pools[lane] = self._ctx.Pool(1, initializer=_init, initargs=(self.gen,))

    def slot(self) -> int:
        """A generation slot for a new session."""
        with self._lock:
            self._slots += 1
            return (self._slots - 1) % SLOTS

    def bump(self, lane: str, slot: int) -> int:
        """Move ``slot``'s lane on (its queued jobs are dropped); the new generation."""
        i = LANES.index(lane) * SLOTS + slot
        self.gen[i] += 1
        return int(self.gen[i])

    def submit(
        self,
        lane: str,
        slot: int,
        gen: int,
        fn: Callable[..., Any],
        args: tuple[Any, ...],
        done: Callable[[Any], None],
        failed: Callable[[BaseException], None],
    ) -> None:
        """Queue ``fn(slot', gen, *args)`` on ``lane``; ``done(result)`` or ``failed(exc)``
        run on a pool thread (results of stale jobs are None)."""
        self.start((lane,))
        index = LANES.index(lane) * SLOTS + slot
        self.pools[lane].apply_async(fn, (index, gen, *args), callback=done, error_callback=failed)

    def close(self) -> None:
        """Stop every pool now (running jobs are killed)."""
        with self._lock:
            pools, self.pools = self.pools, {}
        for pool in pools.values():
            pool.terminate()
        for pool in pools.values():
            pool.join()
