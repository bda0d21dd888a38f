"""Streamed results and resume (source: an uninterrupted run of the same study,
compared byte for byte after an interrupted run is resumed)."""

import json

import pytest

from betvdesign.errors import UsageError
from betvdesign.studies.engine.executors import ProcessExecutor, SerialExecutor
from betvdesign.studies.engine.runner import run_study
from betvdesign.studies.engine.store import ResultStore, read_results
from betvdesign.studies.pushpull import pushpull_study


class Stop(Exception):
    pass


def _lambda_study():
    study, _ = pushpull_study(
        [0.5, 0.9, 1.3, 1.7], [0.1, 1.0, 4.0], [0.5], [0.1, 0.4], fidelity="lambda"
    )
    return study


def _interrupt_after(k):
    def progress(done, total):
        if done >= k:
            raise Stop

    return progress


@pytest.mark.parametrize("executor", [SerialExecutor(chunksize=3), ProcessExecutor(2, 2)])
def test_interrupted_then_resumed_equals_uninterrupted(tmp_path, executor):
    study = _lambda_study()
    ref = run_study(study, SerialExecutor(), out=tmp_path / "ref.csv")
    out = tmp_path / "run.csv"
    with pytest.raises(Stop):
        run_study(study, executor, out=out, progress=_interrupt_after(7))
    meta = json.loads((tmp_path / "run.json").read_text())
    assert meta["status"] == "interrupted"
    partial = meta["done"]
    assert 7 <= partial < study.tasks.__len__()
    resumed = run_study(study, executor, out=out)
    assert resumed.resumed == partial
    assert resumed.computed == len(study.tasks) - partial  # nothing recomputed
    assert out.read_bytes() == (tmp_path / "ref.csv").read_bytes()
    assert resumed.rows == ref.rows
    meta = json.loads((tmp_path / "run.json").read_text())
    assert meta["status"] == "complete" and meta["done"] == len(study.tasks)
    assert set(meta["versions"]) >= {"betvdesign", "numpy", "scipy", "python"}


def test_torn_last_line_is_dropped_and_recomputed(tmp_path):
    study = _lambda_study()
    out = tmp_path / "r.csv"
    ref = run_study(study, out=tmp_path / "ref.csv")
    with pytest.raises(Stop):
        run_study(study, SerialExecutor(chunksize=4), out=out, progress=_interrupt_after(4))
    with open(out, "a") as fh:  # what a killed writer leaves behind
        fh.write("5,0.9,0.1,0.5")
    run = run_study(study, out=out)
    assert run.resumed == 4
    assert out.read_bytes() == (tmp_path / "ref.csv").read_bytes()
    assert run.rows == ref.rows


def test_floats_round_trip_bitwise(tmp_path):
    study = _lambda_study()
    run = run_study(study, out=tmp_path / "r.csv")
    _, rows = read_results(tmp_path / "r.csv")
    assert [r["lam"] for r in rows] == [r["lam"] for r in run.rows]
    assert all(r["mode"] is None and r["converged"] is False for r in rows)


def test_resume_refuses_a_different_study(tmp_path):
    out = tmp_path / "r.csv"
    run_study(_lambda_study(), out=out)
    other, _ = pushpull_study([0.5], [0.1], [0.5], [0.1], fidelity="lambda")
    with pytest.raises(UsageError, match="different 'parameters'"):
        run_study(other, out=out)
    run = run_study(other, out=out, overwrite=True)
    assert run.computed == 1


def test_foreign_file_and_unwritable_paths(tmp_path):
    study = _lambda_study()
    foreign = tmp_path / "mine.csv"
    foreign.write_text("a,b\n1,2\n")
    with pytest.raises(UsageError, match="no sidecar"):
        run_study(study, out=foreign)
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(UsageError, match="cannot create output directory"):
        run_study(study, out=blocker / "sub" / "r.csv")
    with pytest.raises(UsageError, match="sidecar"):
        ResultStore(tmp_path / "r.json", study="x", columns={"key": int}, parameters={}, total=0)


def test_resumed_periodic_map_is_byte_identical(tmp_path):
    """Real solver: interrupt after 3 of 6 points, resume on 2 processes, compare files."""
    study, _ = pushpull_study([0.9, 1.3, 1.7], [1.0, 4.0], [0.5], [0.4])
    ref = run_study(study, SerialExecutor(), out=tmp_path / "ref.csv")
    out = tmp_path / "run.csv"
    with pytest.raises(Stop):
        run_study(study, SerialExecutor(chunksize=1), out=out, progress=_interrupt_after(3))
    resumed = run_study(study, ProcessExecutor(2, 1), out=out)
    assert (resumed.resumed, resumed.computed) == (3, 3)
    assert out.read_bytes() == (tmp_path / "ref.csv").read_bytes()
    assert all(r["converged"] for r in ref.rows)
