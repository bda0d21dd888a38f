"""Executors give identical results (source: the serial executor as reference;
dask against an in-test distributed.LocalCluster with 2 worker processes)."""

import json

import pytest
from conftest import require_module

from betvdesign.errors import UsageError
from betvdesign.studies.engine.executors import (
    DaskExecutor,
    ProcessExecutor,
    SerialExecutor,
    chunked,
    default_chunksize,
    make_executor,
)
from betvdesign.studies.engine.runner import run_study
from betvdesign.studies.pushpull import pushpull_study


@pytest.fixture(scope="module")
def cluster():
    distributed = require_module("distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cl:
        yield cl


def test_chunking_covers_every_task_once():
    tasks = list(range(10))
    chunks = chunked(tasks, 3)
    assert [len(c) for c in chunks] == [3, 3, 3, 1]
    assert [t for c in chunks for t in c] == tasks
    assert default_chunksize(1152, 2) == 32 and default_chunksize(10, 2) == 1


def test_lambda_rung_identical_on_all_backends(cluster):
    study, _ = pushpull_study([0.5, 1.0, 1.5], [0.1, 2.0], [0.1, 1.5], [0.4], fidelity="lambda")
    ref = run_study(study, SerialExecutor()).rows
    proc = run_study(study, ProcessExecutor(workers=2, chunksize=2)).rows
    dask = run_study(study, DaskExecutor(cluster.scheduler_address, chunksize=2)).rows
    assert ref == proc == dask
    assert len(ref) == 12


def test_make_executor_choices_and_errors():
    assert make_executor("serial").info().backend == "serial"
    assert make_executor("process", workers=3).info().workers == 3
    assert make_executor(scheduler="tcp://127.0.0.1:1").info().backend == "dask"
    with pytest.raises(UsageError, match="unknown executor"):
        make_executor("gpu")
    with pytest.raises(UsageError, match="--scheduler"):
        make_executor("dask")
    with pytest.raises(UsageError, match=">= 1"):
        make_executor("process", workers=0)


def test_periodic_map_bitwise_identical_on_all_backends(cluster):
    """The exact periodic solver on a tiny grid: serial, 2 processes and a dask
    LocalCluster give the same rows, floats bit for bit."""
    study, _ = pushpull_study([0.9, 1.3], [0.1, 1.0], [0.5], [0.4])
    ref = run_study(study, SerialExecutor()).rows
    proc = run_study(study, ProcessExecutor(workers=2, chunksize=1)).rows
    dask = run_study(study, DaskExecutor(cluster.scheduler_address, chunksize=1)).rows
    assert all(r["converged"] for r in ref)
    for a, b, c in zip(ref, proc, dask, strict=True):
        for col in ("delta_s", "residual", "floquet_radius", "contact_fraction"):
            assert a[col].hex() == b[col].hex() == c[col].hex()
    assert ref == proc == dask


def test_cli_runs_on_a_dask_scheduler(cluster, tmp_path):
    """betv sweep ... --scheduler tcp://...: same CSV bytes as a serial run."""
    from typer.testing import CliRunner

    from betvdesign.cli import app

    base = [
        "sweep",
        "pushpull",
        "--varpi",
        "0.9,1.3",
        "--alpha",
        "1",
        "--beta",
        "0.5",
        "--kappa",
        "0.4",
        "-q",
    ]
    r1 = CliRunner().invoke(app, [*base, "-x", "serial", "-o", str(tmp_path / "a.csv")])
    r2 = CliRunner().invoke(
        app, [*base, "--scheduler", cluster.scheduler_address, "-o", str(tmp_path / "b.csv")]
    )
    assert r1.exit_code == 0 and r2.exit_code == 0, r2.stderr
    assert (tmp_path / "a.csv").read_bytes() == (tmp_path / "b.csv").read_bytes()
    sidecar = json.loads((tmp_path / "b.json").read_text())
    assert sidecar["executor"]["backend"] == "dask"
    # the cluster's real size (2 workers × 1 thread), not 0 (issue 13)
    assert sidecar["executor"]["workers"] == 2
    r3 = CliRunner().invoke(
        app,
        [*base, "--scheduler", cluster.scheduler_address, "--json", "-o", str(tmp_path / "c.csv")],
    )
    assert r3.exit_code == 0, r3.stderr
    assert json.loads(r3.stdout)["workers"] == 2


def _pid_row(task):
    """A worker that says which process ran it (module level: it pickles by name)."""
    import os

    return {"key": task["key"], "pid": os.getpid()}


def _kernels_row(task):
    """A worker that says how many solver kernels its process holds compiled or loaded."""
    from betvdesign.dynamics.jit import KERNELS

    return {"key": task["key"], "loaded": sum(len(d.signatures) for d in KERNELS)}


def test_pool_workers_start_with_the_kernels_loaded():
    """The fork server loads the kernels once (studies.engine.preload): the first task of
    every worker finds them in its process, though no task there has solved anything."""
    tasks = [{"key": i} for i in range(8)]
    rows = [r for c in ProcessExecutor(2, chunksize=1).run(_kernels_row, tasks) for r in c]
    assert len(rows) == 8
    assert min(r["loaded"] for r in rows) > 0


def test_chunk_size_per_backend():
    """Dask gets few large chunks (a chunk is a scheduler task), the pool many small ones."""
    # 2e5 tasks, 16 workers: 8 chunks per worker of ceil(2e5 / 128) tasks
    assert default_chunksize(200_000, 16, "dask") == 1563
    assert default_chunksize(10**7, 16, "dask") == 2048  # bounded
    assert default_chunksize(10, 4, "dask") == 1
    assert default_chunksize(200_000, 16, "process") == 32
    assert default_chunksize(200_000, 16) == default_chunksize(200_000, 16, "process")


def test_small_study_runs_in_this_process_large_on_the_pool():
    import os

    from betvdesign.studies.engine.executors import SMALL_STUDY

    small = [{"key": i} for i in range(SMALL_STUDY)]
    rows = [r for chunk in ProcessExecutor(workers=2).run(_pid_row, small) for r in chunk]
    assert sorted(r["key"] for r in rows) == list(range(SMALL_STUDY))
    assert {r["pid"] for r in rows} == {os.getpid()}
    large = [{"key": i} for i in range(SMALL_STUDY + 1)]
    rows = [r for chunk in ProcessExecutor(workers=2).run(_pid_row, large) for r in chunk]
    assert sorted(r["key"] for r in rows) == list(range(SMALL_STUDY + 1))
    assert os.getpid() not in {r["pid"] for r in rows}
    # an explicit chunk size always uses the pool
    rows = [r for chunk in ProcessExecutor(2, chunksize=2).run(_pid_row, small[:4]) for r in chunk]
    assert os.getpid() not in {r["pid"] for r in rows}


def test_tolerance_study_identical_on_dask_with_default_chunks(cluster):
    """A small tolerance study of push_demo (periodic rung): the dask run with its own
    default chunking (large chunks, scattered worker, warmed kernels) gives the serial
    run's rows, floats bit for bit; the workers then hold the warm-up plugin."""
    from betvdesign.studies.engine.daskplugin import NAME
    from betvdesign.studies.tolerance import parse_tolerance, tolerance_study

    tols = [
        parse_tolerance("slider.beam_width=normal:0.3 um"),
        parse_tolerance("contact.friction=uniform:25%"),
        parse_tolerance("drive.frequency=normal:1%"),
    ]
    study = tolerance_study("devices/push_demo.yaml", tols, samples=60, seed=5)
    ref = run_study(study, SerialExecutor()).rows
    executor = DaskExecutor(cluster.scheduler_address)
    dask = run_study(study, executor).rows
    assert sum(r["converged"] for r in ref) > 50
    for a, b in zip(ref, dask, strict=True):
        assert a == b
        if a["delta_s"] is not None:
            assert a["delta_s"].hex() == b["delta_s"].hex()
    assert executor.workers == 2

    from distributed import Client

    with Client(cluster.scheduler_address) as client:
        has = client.run(lambda dask_worker: NAME in dask_worker.plugins)
    assert list(has.values()) == [True, True]


def test_dask_warm_plugin_loads_kernels_before_any_task():
    """On a fresh worker the plugin alone loads the solver kernels (numba dispatchers
    with a compiled signature), before any study task has run there."""
    distributed = require_module("distributed")
    from betvdesign.studies.engine.daskplugin import WarmKernels

    def loaded() -> int:
        from betvdesign.dynamics.jit import KERNELS

        return sum(len(d.signatures) for d in KERNELS)

    with (
        distributed.LocalCluster(
            n_workers=1, threads_per_worker=1, processes=True, dashboard_address=":0"
        ) as cl,
        distributed.Client(cl) as client,
    ):
        before = client.run(loaded)
        client.register_plugin(WarmKernels())
        after = client.run(loaded)
    assert list(before.values()) == [0]
    [n_after] = after.values()
    assert n_after > 0
