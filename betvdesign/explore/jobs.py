"""The slow work of ``betv explore`` on worker processes, never in the page's way.

The settling transient, the model-adequacy scan, the fix search, the field map and the
report run on :class:`Workers`: one worker process per lane (spawned at its first job,
niced, deaf to Ctrl-C; the page's own updates keep the server's process to
themselves). A worker exits when its pipe to the server closes, so it never outlives
the server, and a worker that dies fails its jobs (the page says so) and is started
again by the next job. Every job takes the design as its YAML text (what a saved file
would hold) and returns plain data.

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
import signal
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
    # Ctrl-C reaches the whole process group: the server stops the workers itself (the
    # worker was started ignoring SIGINT already: _sigint_ignored)
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
    from betvdesign.studies.fix import find_fixes
    from betvdesign.studies.fixfields import parse_vary

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


@contextlib.contextmanager
def _sigint_ignored() -> Any:
    """SIGINT ignored while a worker process is started, so that it starts ignoring it
    (an ignored signal stays ignored across the exec of a spawned process; a blocked one
    does not): a Ctrl-C to the process group while the worker imports is then no
    KeyboardInterrupt traceback. Only the main thread can set a handler; elsewhere the
    worker starts as it is."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


class _Lane:
    """One worker process and its jobs (started at the first job, again after a crash)."""

    def __init__(self, ctx: Any, name: str, gen: Any) -> None:
        self.ctx, self.name, self.gen = ctx, name, gen
        self.lock = threading.Lock()
        self.proc: Any = None
        self.conn: Any = None
        self.jobs: dict[int, tuple[Callable[[Any], None], Callable[[BaseException], None]]] = {}
        self.next_id = 0
        self.closed = False

    def _ensure(self) -> None:
        if self.proc is not None and self.proc.is_alive():
            return
        parent, child = self.ctx.Pipe()
        proc = self.ctx.Process(
            target=_serve, args=(child, self.gen), name=f"betv-explore-{self.name}", daemon=True
        )
        with _sigint_ignored():
            proc.start()
        child.close()
        self.proc, self.conn = proc, parent
        threading.Thread(
            target=self._read, args=(parent, proc), name=f"betv-explore-{self.name}", daemon=True
        ).start()

    def submit(
        self,
        fn: Callable[..., Any],
        args: tuple[Any, ...],
        done: Callable[[Any], None],
        failed: Callable[[BaseException], None],
    ) -> None:
        try:
            with self.lock:
                if self.closed:
                    return
                self._ensure()
                self.next_id += 1
                self.jobs[self.next_id] = (done, failed)
                self.conn.send((self.next_id, fn, args))
        except (OSError, EOFError, ValueError) as exc:  # the worker cannot start or is gone
            failed(exc)

    def _read(self, conn: Any, proc: Any) -> None:
        """Deliver results until the worker's pipe closes or the worker exits."""
        from multiprocessing.connection import wait

        while True:
            ready = wait([conn, proc.sentinel])
            if conn not in ready:
                break
            try:
                jid, ok, value = conn.recv()
            except (EOFError, OSError):
                break
            with self.lock:
                callbacks = self.jobs.pop(jid, None)
            if callbacks is not None:
                callbacks[0 if ok else 1](value)
        with self.lock:
            lost, self.jobs = (self.jobs, {}) if self.proc is proc else ({}, self.jobs)
            if self.proc is proc:
                self.proc = None
        for _, failed in lost.values():
            failed(RuntimeError(f"the {self.name} worker stopped (exit code {proc.exitcode})"))

    def close(self) -> None:
        with self.lock:
            self.closed = True
            proc, self.proc, self.jobs = self.proc, None, {}
        if proc is not None:
            proc.terminate()
            proc.join(5)
            if proc.is_alive():
                proc.kill()
                proc.join(5)


def _serve(conn: Any, gen: Any) -> None:
    """A worker: run the jobs the server sends until its pipe closes."""
    _init(gen)
    while True:
        try:
            jid, fn, args = conn.recv()
        except (EOFError, OSError, KeyboardInterrupt):
            return
        try:
            reply = (jid, True, fn(*args))
        except BaseException as exc:  # reported to the page, never a dead worker
            reply = (jid, False, RuntimeError(f"{type(exc).__name__}: {exc}"))
        try:
            conn.send(reply)
        except (OSError, EOFError):
            return


class Workers:
    """The job lanes (see the module docstring): one worker process per lane, started
    by its first job; :meth:`close` at the end (kills what still runs)."""

    def __init__(self) -> None:
        ctx = multiprocessing.get_context("spawn")
        self.gen = ctx.Array("q", SLOTS * len(LANES), lock=False)
        self.lanes = {name: _Lane(ctx, name, self.gen) for name in LANES}
        self._lock = threading.Lock()
        self._slots = 0

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
        """Queue ``fn(slot', gen, *args)`` (a module-level function) on ``lane``;
        ``done(result)`` or ``failed(exc)`` run on a reader thread (stale jobs give
        None)."""
        index = LANES.index(lane) * SLOTS + slot
        self.lanes[lane].submit(fn, (index, gen, *args), done, failed)

    def close(self) -> None:
        """Stop every worker now (running jobs are killed)."""
        for lane in self.lanes.values():
            lane.close()
