"""Shared test fixtures: the shipped device files and external tools.

External programs (chromium, poppler-utils) may be missing on a developer's
machine: tests needing them skip there, printing why. Under CI (environment
variable CI set, as .ci/run does) a missing program is a failure, never a skip; the
same holds for optional test modules (:func:`require_module`, e.g. dask.distributed).
"""

from __future__ import annotations

import contextlib
import fcntl
import importlib
import os
import shutil
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import settings

from betvdesign.model.domain import mode_of
from betvdesign.model.params import ModelParams

# CI gates on a reproducible suite: the same hypothesis examples on every run
# (a new counterexample is found in development, where the database keeps it).
settings.register_profile("ci", derandomize=True, print_blob=True)
if os.environ.get("CI"):
    settings.load_profile("ci")

REPO = Path(__file__).resolve().parents[1]
DEVICES = REPO / "devices"

# Every check runs afresh in the tests (several monkeypatch the solver and call the CLI):
# no stored answer of `betv check` is given again, here or in the commands the tests
# start; tests/test_answers.py turns the cache on in a directory of its own.
os.environ["BETV_ANSWER_CACHE"] = "off"


def _window_sets(n: int = 20, seed: int = 20041) -> list[ModelParams]:
    """n designs spread over the window 0.5 ≤ ϖ < 2 (log-uniform α, β, κ); the same
    draw as benchmarks/bench_solver.py ``window_sets``."""
    rng = np.random.default_rng(seed)
    return [
        ModelParams(
            float(rng.uniform(0.55, 1.95)),
            float(10 ** rng.uniform(-1.3, 0.5)),
            float(10 ** rng.uniform(-1, 1)),
            float(10 ** rng.uniform(-1.3, 0)),
        )
        for _ in range(n)
    ]


#: 20 designs spread over the window (tests of the exact solver against other methods).
WINDOW_SETS = _window_sets()


def orbit_stand_in(
    delta_s: float | None, *, status: str = "success", message: str = "stand-in", **fields
) -> Any:
    """A :class:`betvdesign.dynamics.PeriodicResult` as a stand-in solver returns it
    (nothing is solved): Δs per cycle [-] and status as given, period 1, the rest neutral
    or ``fields``."""
    from betvdesign.dynamics.result import PeriodicResult

    ok = status == "success"
    values = {
        "params": ModelParams(1.0, 1.0, 1.0, 1.0),
        "status": status,
        "message": message,
        "delta_s": delta_s,
        "mode": mode_of(delta_s) if ok else None,
        "period_cycles": 1 if ok else None,
        "residual": None,
        "floquet": None,
        "stable": None,
        "state": None,
        "impacts_per_cycle": 1.0,
        "contact_fraction": 0.5,
        "n_cycles": 0,
        "n_newton": 0,
        "n_events": 0,
        "n_root_evals": 0,
        "elapsed_s": 0.0,
    }
    return PeriodicResult(**(values | fields))


def device_files() -> list[Path]:
    """Every shipped device file, sorted (usable in parametrize)."""
    return sorted(DEVICES.glob("*.yaml"))


def require_program(name: str, *, candidates: tuple[str, ...] = ()) -> str:
    """Absolute path of an external program; skip (outside CI) or fail (CI) if absent."""
    for cand in (name, *candidates):
        found = shutil.which(cand) or (
            cand if os.path.isabs(cand) and os.access(cand, os.X_OK) else None
        )
        if found:
            return found
    reason = f"{name} not found (install it: bash scripts/sysdeps.sh test, as root)"
    if os.environ.get("CI"):
        pytest.fail(f"CI: {reason}")
    print(f"SKIP reason: {reason}")
    pytest.skip(reason)


def require_module(name: str, *, extra: str = "test"):
    """Import an optional test dependency; skip without it (outside CI) or fail (CI)."""
    try:
        return importlib.import_module(name)
    except ImportError as exc:
        reason = f"{name} not importable ({exc}); install the extra: pip install -e '.[{extra}]'"
    if os.environ.get("CI"):
        pytest.fail(f"CI: {reason}")
    print(f"SKIP reason: {reason}")
    pytest.skip(reason)


@pytest.fixture(scope="session")
def devices() -> list[Path]:
    """The shipped device files (at least one)."""
    files = device_files()
    assert files, f"no device files in {DEVICES}"
    return files


@contextlib.contextmanager
def _locked(path: Path) -> Iterator[None]:
    """Hold an exclusive lock on ``path`` (created) for the block; others wait for it."""
    with open(path, "a") as fh:
        fcntl.flock(fh, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(fh, fcntl.LOCK_UN)


@pytest.fixture(scope="session")
def reports_dir(tmp_path_factory: pytest.TempPathFactory, devices: list[Path]) -> Path:
    """Reports (HTML + PDF) of every shipped device, written once per run: under
    pytest-xdist (``-n``) the first worker that needs them writes them in the run's
    temporary folder, under a lock, and the others read them (the tests only read)."""
    from betvdesign.report import write_reports

    base = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        base = base.parent  # the run's folder, above each worker's own
    out, done = base / "shared-reports", base / "shared-reports.done"
    with _locked(base / "shared-reports.lock"):
        if not done.exists():
            shutil.rmtree(out, ignore_errors=True)
            out.mkdir()
            write_reports(devices, out)
            done.write_text("")
    return out


def pytest_sessionstart(session: pytest.Session) -> None:
    """Compile (or load) every solver kernel a check uses before any test runs.

    On a fresh clone numba compiles the kernels on first use (about a minute on two
    cores); without this the test that happens to come first pays for it, and a test
    with a wall-clock guard (the hostile corpus' 30 s) fails on compile time, not on its
    own work. A hook, not a fixture: no test's timeout counts it. Under pytest-xdist the
    controller skips it and each worker runs it under a lock beside numba's cache, so one
    compiles and the others load the machine code. A check of the damped demo device runs
    every entry point (orbit, vertical motion, settling, determination, adequacy's damped
    rungs).
    """
    xdist_controller = getattr(session.config.option, "numprocesses", None) and not os.environ.get(
        "PYTEST_XDIST_WORKER"
    )
    if xdist_controller or session.config.option.collectonly:
        return
    from betvdesign import check
    from betvdesign.dynamics.jit import cache_dir, jit_enabled
    from betvdesign.dynamics.warm import warm

    if not jit_enabled():
        return
    lock = Path(cache_dir())
    lock.mkdir(parents=True, exist_ok=True)
    with _locked(lock / "tests-warm.lock"):
        warm()
        check(DEVICES / "damped_demo.yaml", advice=False)
