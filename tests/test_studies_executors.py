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
