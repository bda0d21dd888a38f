"""The design-space atlas (``betv sweep atlas``): rows, backends, resume, refusals.

Sources of truth: the push/pull map's and the field sweep's own studies (another path:
one task list, the study runner and its CSV store) for the rows; the serial atlas for the
process pool and dask (a ``distributed.LocalCluster`` of 2 worker processes), bit for bit
per column; an uninterrupted atlas for an interrupted-and-resumed one; the scipy reference
integrator (:mod:`betvdesign.dynamics.reference`) for the physics of a few points.
"""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from conftest import require_module
from typer.testing import CliRunner

from betvdesign.cli import app
from betvdesign.errors import UsageError
from betvdesign.studies.atlas import device_atlas, pushpull_atlas, run_atlas
from betvdesign.studies.engine.chunkstore import (
    concat_columns,
    decode_rows,
    encode_columns,
    read_table,
)
from betvdesign.studies.engine.executors import SerialExecutor
from betvdesign.studies.engine.runner import run_study
from betvdesign.studies.pushpull import pushpull_study

ROOT = Path(__file__).resolve().parents[1]
PUSH_DEMO = ROOT / "devices" / "push_demo.yaml"

#: A 10³-point sub-grid of the benchmark's 10⁶-point atlas (benchmarks/bench_atlas.py,
#: 40 ϖ × 25 α × 25 β × 40 κ): 10 ϖ (every 4th), 10 α and 10 β (every 2nd), κ = 0.05.
GRID_1000 = {
    "varpi": np.linspace(0.3, 3.0, 40)[::4][:10],
    "alpha": np.geomspace(0.1, 10.0, 25)[::2][:10],
    "beta": np.geomspace(0.05, 2.0, 25)[::2][:10],
    "kappa": np.linspace(0.05, 0.6, 40)[::4][:1],
}


@pytest.fixture(scope="module")
def cluster():
    distributed = require_module("distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cl:
        yield cl


def _bits(table: dict[str, np.ndarray]) -> dict[str, bytes]:
    """Every encoded column as raw bytes (floats bit for bit, NaN included)."""
    return {k: np.ascontiguousarray(v).tobytes() for k, v in table.items()}


def test_columns_round_trip_every_type_and_none():
    columns = {"key": int, "x": float, "ok": bool, "mode": str, "n": int}
    rows = [
        {"key": 0, "x": 0.1, "ok": True, "mode": "push", "n": 3},
        {"key": 1, "x": None, "ok": None, "mode": None, "n": None},
        {"key": 2, "x": float("nan"), "ok": False, "mode": "ϖ ≤ 1e-10, |μ|", "n": -7},
        {"key": 3, "x": -0.0, "ok": False, "mode": "", "n": 2**40},
    ]
    enc = encode_columns(rows, columns)
    back = decode_rows(enc, columns)
    assert back[0] == rows[0] and back[1] == rows[1] and back[3] == rows[3]
    assert np.isnan(back[2]["x"]) and back[2]["mode"] == rows[2]["mode"]
    assert str(back[3]["x"]) == "-0.0"  # the sign bit survives
    assert back[1]["mode"] is None and back[3]["mode"] == ""  # None is not ""
    # chunks joined end to end encode as the rows encoded at once
    parts = [encode_columns(rows[:1], columns), encode_columns(rows[1:], columns)]
    assert _bits(concat_columns(iter(parts), columns, 4)) == _bits(enc)
    with pytest.raises(ValueError, match="not 5"):
        concat_columns(parts, columns, 5)


def test_pushpull_atlas_rows_are_the_maps_rows(tmp_path, monkeypatch):
    """The atlas of a small (ϖ, α, β, κ) grid holds the rows `betv sweep pushpull` makes
    (its study: one task list, the runner), key for key, floats bit for bit; its
    table.csv (written 5 rows at a time here) is the map's CSV, byte for byte."""
    import betvdesign.studies.engine.chunkstore as chunkstore

    axes = {"varpi": [0.7, 1.2, 2.0], "alpha": [0.3, 2.0], "beta": [0.5], "kappa": [0.1, 0.4]}
    study, _ = pushpull_study(**axes)
    ref = run_study(study, SerialExecutor(), out=tmp_path / "map.csv").rows
    monkeypatch.setattr(chunkstore, "CSV_BLOCK", 5)
    run = run_atlas(
        pushpull_atlas(**axes), tmp_path / "a", backend="serial", chunk_points=5, csv=True
    )
    assert (tmp_path / "a" / "table.csv").read_bytes() == (tmp_path / "map.csv").read_bytes()
    assert (run.total, run.chunks, run.computed, run.resumed) == (12, 3, 3, 0)
    _, columns, table = read_table(tmp_path / "a")
    assert list(columns) == list(study.columns)
    rows = decode_rows(table, columns)
    assert rows == ref
    for a, b in zip(rows, ref, strict=True):
        if a["delta_s"] is not None:
            assert a["delta_s"].hex() == b["delta_s"].hex()
    modes = run.summary["modes"]
    assert sum(modes.values()) == 12
    assert modes.get("push", 0) == sum(r["converged"] and r["mode"] == "push" for r in ref)
    on_disk = json.loads((tmp_path / "a" / "summary.json").read_text())
    assert on_disk == run.summary


def test_atlas_on_dask_and_pool_identical_to_serial_on_1000_points(tmp_path, cluster):
    """A 10³-point atlas: the process pool (2 workers) and a dask cluster (2 worker
    processes) give the serial atlas's table, every column bit for bit, and the same
    bytes on disk."""
    atlas = pushpull_atlas(**GRID_1000)
    assert atlas.total == 1000
    serial = run_atlas(atlas, tmp_path / "s", backend="serial", chunk_points=64)
    pool = run_atlas(atlas, tmp_path / "p", backend="process", workers=2, chunk_points=64)
    dask = run_atlas(atlas, tmp_path / "d", scheduler=cluster.scheduler_address, chunk_points=64)
    assert dask.executor["backend"] == "dask" and pool.executor["backend"] == "process"
    assert serial.chunks == pool.chunks == dask.chunks == 16
    tables = [read_table(tmp_path / d)[2] for d in ("s", "p", "d")]
    assert _bits(tables[0]) == _bits(tables[1]) == _bits(tables[2])
    raw = [(tmp_path / d / "table.npz").read_bytes() for d in ("s", "p", "d")]
    assert raw[0] == raw[1] == raw[2]
    assert serial.summary == pool.summary == dask.summary
    assert serial.summary["converged"] > 500  # a map with orbits, not only refusals


def test_summary_counts_every_row_once_across_blocks(tmp_path, monkeypatch):
    """The summary, read a block of rows at a time (blocks of 7 here), counts what the
    rows themselves hold."""
    from collections import Counter

    import betvdesign.studies.atlas as atlas_module

    axes = {
        "varpi": [0.3, 0.7, 1.2, 2.0, 3.0],
        "alpha": [0.3, 1.0, 2.5],
        "beta": [0.5],
        "kappa": [0.1, 0.4],
    }
    atlas = pushpull_atlas(**axes)
    run_atlas(atlas, tmp_path / "a", backend="serial")
    _, columns, table = read_table(tmp_path / "a")
    rows = decode_rows(table, columns)
    monkeypatch.setattr(atlas_module, "SUMMARY_BLOCK", 7)
    got = atlas_module.summarise_table(atlas, table)
    assert got["modes"] == dict(Counter(r["mode"] if r["converged"] else r["status"] for r in rows))
    assert got["status"] == dict(Counter(r["status"] for r in rows))
    assert got["converged"] == sum(r["converged"] for r in rows)
    assert got["lambda_agrees"] == sum(
        r["converged"] and r["mode"] == r["lambda_mode"] for r in rows
    )
    assert len(set(got["modes"])) >= 3


def test_interrupted_atlas_resumes_to_the_same_table(tmp_path):
    """Ctrl-C after 3 chunks (raised where the run reports progress, as the signal
    handler raises it): whole chunks only, the manifest says interrupted; the same call
    again computes only the rest, and the table is the uninterrupted atlas's, byte for
    byte."""
    axes = {"varpi": [0.6, 0.9, 1.3, 1.8], "alpha": [0.5, 2.0], "beta": [0.5], "kappa": [0.2, 0.4]}
    whole = run_atlas(pushpull_atlas(**axes), tmp_path / "whole", backend="serial", chunk_points=2)
    assert whole.chunks == 8
    seen = []

    def stop_after_three(done: int, total: int) -> None:
        seen.append(done)
        if len(seen) == 4:  # the first call reports what was on disk
            raise KeyboardInterrupt

    out = tmp_path / "cut"
    with pytest.raises(KeyboardInterrupt):
        run_atlas(
            pushpull_atlas(**axes),
            out,
            backend="process",
            workers=2,
            chunk_points=2,
            progress=stop_after_three,
        )
    chunks = sorted((out / "chunks").iterdir())
    assert len(chunks) >= 3 and all(p.name.endswith(".npz") for p in chunks)  # no temporaries
    assert json.loads((out / "atlas.json").read_text())["status"] == "interrupted"
    assert not (out / "table.npz").exists()
    (out / "chunks" / ".00000007.npz.abc.tmp.npz").write_bytes(b"half")  # a killed write
    again = run_atlas(pushpull_atlas(**axes), out, backend="serial")
    assert again.resumed == len(chunks) and again.computed == 8 - len(chunks)
    assert not (out / "chunks" / ".00000007.npz.abc.tmp.npz").exists()
    assert (out / "table.npz").read_bytes() == (tmp_path / "whole" / "table.npz").read_bytes()
    assert json.loads((out / "atlas.json").read_text())["status"] == "complete"
    # a complete atlas run again computes nothing and writes the same table
    third = run_atlas(pushpull_atlas(**axes), out, backend="serial")
    assert (third.computed, third.resumed) == (0, 8)
    assert (out / "table.npz").read_bytes() == (tmp_path / "whole" / "table.npz").read_bytes()


def test_killed_pool_worker_is_a_clear_error_and_the_atlas_resumes(tmp_path):
    """A pool worker killed (SIGKILL, as the OOM killer does) mid-run: a clear error
    naming the chunks kept, not a traceback; the same call again finishes the atlas."""
    psutil = require_module("psutil")
    axes = {"varpi": [0.6, 0.9, 1.3, 1.8], "alpha": [0.5, 2.0], "beta": [0.5], "kappa": [0.2, 0.4]}

    killed = []

    def kill_a_worker(done: int, total: int) -> None:
        if done and not killed:  # after the first chunk (workers: the fork server's children)
            workers = [p for c in psutil.Process().children() for p in c.children()]
            workers[-1].send_signal(signal.SIGKILL)
            killed.append(workers[-1].pid)

    out = tmp_path / "a"
    with pytest.raises(UsageError, match=r"worker process died.*run the same command again"):
        run_atlas(
            pushpull_atlas(**axes), out, backend="process", workers=2, chunk_points=1,
            progress=kill_a_worker,
        )  # fmt: skip
    kept = len(list((out / "chunks").glob("*.npz")))
    assert 1 <= kept < 16
    again = run_atlas(pushpull_atlas(**axes), out, backend="serial")
    assert again.resumed == kept and again.computed == 16 - kept


@pytest.mark.slow
def test_killed_cli_run_leaves_whole_chunks_and_resumes(tmp_path):
    """SIGKILL of `betv sweep atlas` (its pool running): every chunk file on disk is
    whole, and the same command again finishes the atlas with the uninterrupted table."""
    args = [
        "--varpi", "0.4:2.4:0.05", "--alpha", "0.3,1,3", "--beta", "0.5", "--kappa",
        "0.1,0.3", "--chunksize", "4", "-j", "2", "-q",
    ]  # fmt: skip
    cmd = [sys.executable, "-c", "from betvdesign.cli import main; main()", "sweep", "atlas"]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    out = tmp_path / "k"
    proc = subprocess.Popen([*cmd, *args, "-o", str(out)], env=env)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and proc.poll() is None:
        if len(list((out / "chunks").glob("*.npz")) if (out / "chunks").exists() else []) >= 3:
            break
        time.sleep(0.05)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    kept = sorted((out / "chunks").glob("[0-9]*.npz"))
    assert kept, "no chunk was finished before the kill"
    for p in kept:
        with np.load(p, allow_pickle=False) as z:
            assert len(z["c0"]) == 4 or p == kept[-1]
    r = subprocess.run([*cmd, *args, "-o", str(out), "--json"], env=env, capture_output=True)
    assert r.returncode == 0, r.stderr.decode()
    data = json.loads(r.stdout)
    assert data["resumed_chunks"] >= len(kept) and data["points"] == 41 * 3 * 2
    whole = subprocess.run([*cmd, *args, "-o", str(tmp_path / "w")], env=env)
    assert whole.returncode == 0
    assert (out / "table.npz").read_bytes() == (tmp_path / "w" / "table.npz").read_bytes()


def test_other_arguments_into_an_atlas_are_refused_with_exit_2(tmp_path):
    out = tmp_path / "atlas"
    base = ["sweep", "atlas", "--fidelity", "lambda", "--beta", "0.5", "--kappa", "0.4"]
    base += ["-x", "serial", "-q", "-o", str(out)]
    r = CliRunner().invoke(app, [*base, "--varpi", "0.5:2:0.5", "--alpha", "0.5,1"])
    assert r.exit_code == 0, r.output
    assert "atlas of 8 points" in r.output and "table.npz" in r.output
    r = CliRunner().invoke(app, [*base, "--varpi", "0.5:2:0.5", "--alpha", "0.5,2"])
    assert r.exit_code == 2
    assert "definition.grid.alpha differs" in r.output and "--overwrite" in r.output
    r = CliRunner().invoke(
        app, [*base, "--varpi", "0.5:2:0.5", "--alpha", "0.5,1", "--chunksize", "3"]
    )
    assert r.exit_code == 2 and "points per chunk" in r.output
    r = CliRunner().invoke(app, [*base, "--varpi", "0.5:2:0.5", "--alpha", "0.5,1", "--json"])
    assert r.exit_code == 0 and json.loads(r.output)["resumed_chunks"] == 8
    r = CliRunner().invoke(app, [*base, "--varpi", "0.5:2:0.5", "--alpha", "0.5,2", "--overwrite"])
    assert r.exit_code == 0
    from betvdesign.studies.engine.chunkstore import ChunkStore

    holder = ChunkStore(
        out, kind="pushpull", definition={}, columns={"key": int}, total=1, chunk_points=None,
        default_chunk=1, overwrite=True,
    )  # fmt: skip
    r = CliRunner().invoke(app, [*base, "--varpi", "0.5:2:0.5", "--alpha", "0.5,2"])
    assert r.exit_code == 2 and "in use by another run" in r.output
    holder.close()
    other = tmp_path / "other"
    other.mkdir()
    (other / "notes.txt").write_text("mine")
    r = CliRunner().invoke(app, [*base[:-1], str(other), "--varpi", "1", "--alpha", "1"])
    assert r.exit_code == 2 and "not an atlas" in r.output
    assert (other / "notes.txt").read_text() == "mine"
    r = CliRunner().invoke(app, ["sweep", "atlas", "--varpi", "1", "-o", str(tmp_path / "x")])
    assert r.exit_code == 2 and "--alpha" in r.output
    r = CliRunner().invoke(
        app, ["sweep", "atlas", str(PUSH_DEMO), "--varpi", "1", "-o", str(tmp_path / "x")]
    )
    assert r.exit_code == 2 and "not with a device FILE" in r.output


def test_device_atlas_rows_are_the_field_sweeps_rows(tmp_path, monkeypatch):
    """Two fields of push_demo: the atlas holds `betv sweep FILE`'s rows (its study,
    derived over the whole grid at once; the atlas derives chunk by chunk)."""
    from betvdesign.spec.loader import load_device
    from betvdesign.studies.fieldsweep import fieldsweep_study, parse_axis

    spec = load_device(PUSH_DEMO)
    axes = [
        parse_axis(spec, "drive.frequency=3kHz:8kHz", 6),
        parse_axis(spec, "contact.friction=0.2:0.6", 4),
    ]
    ref = run_study(fieldsweep_study(PUSH_DEMO, axes), SerialExecutor()).rows
    run_atlas(device_atlas(PUSH_DEMO, axes), tmp_path / "d", backend="serial", chunk_points=7)
    meta, columns, table = read_table(tmp_path / "d")
    assert decode_rows(table, columns) == ref
    assert meta["about"]["device"] == str(PUSH_DEMO.resolve())
    # the same file by another path (from another directory): the same atlas, resumed
    monkeypatch.chdir(PUSH_DEMO.parent)
    again = run_atlas(device_atlas("push_demo.yaml", axes), tmp_path / "d", backend="serial")
    assert (again.computed, again.resumed) == (0, again.chunks)
    # three fields: more than a sweep takes
    three = [*axes, parse_axis(spec, "slider.beam_width=8um:12um", 2)]
    run = run_atlas(device_atlas(PUSH_DEMO, three), tmp_path / "t", backend="serial")
    assert run.total == 48 and sum(run.summary["modes"].values()) == 48
    with pytest.raises(UsageError, match="1 to 4"):
        device_atlas(PUSH_DEMO, [*three, *axes])


def test_atlas_modes_against_the_reference_integrator(tmp_path):
    """Δs of the atlas's exact orbits against the scipy reference integrator (a second
    method) run 120 cycles from rest, with damping ζ_v = ζ_h = 0.1 so that transients
    decay: wherever the reference has settled (its last two cycles agree to 1e-9), both
    give the same Δs, and the mode is the sign of both (push and pull both met)."""
    from betvdesign.dynamics import reference
    from betvdesign.studies.terms import Terms

    axes = {"varpi": [0.8, 1.5], "alpha": [0.5, 2.0], "beta": [0.5], "kappa": [0.3]}
    atlas = pushpull_atlas(**axes, zeta_v=0.1, zeta_h=0.1)
    run_atlas(atlas, tmp_path / "a", backend="serial")
    _, columns, table = read_table(tmp_path / "a")
    rows = [r for r in decode_rows(table, columns) if r["converged"]]
    checked = []
    for r in rows:
        p = Terms.of(r).params(r["varpi"], r["alpha"], r["beta"], r["kappa"])
        ref = reference.simulate(p, 120, rtol=1e-11, atol=1e-12)
        assert ref.status == "success"
        last, before = float(ref.delta_s[-1]), float(ref.delta_s[-2])
        if abs(last - before) > 1e-9 * abs(last):
            continue  # still settling (near the tangential resonance): no verdict
        assert last == pytest.approx(r["delta_s"], rel=1e-7)
        assert (last > 0) == (r["mode"] == "push")
        checked.append(r["mode"])
    assert len(checked) >= 3 and set(checked) == {"push", "pull"}


def test_cli_dask_without_scheduler_starts_its_own_cluster(tmp_path):
    """`-x dask` without --scheduler: a local cluster of -j workers, started and closed by
    the command; its table is the serial one's, byte for byte."""
    require_module("distributed")
    grid = ["--varpi", "0.6,1.2", "--alpha", "0.5,2", "--beta", "0.5", "--kappa", "0.2,0.4"]
    base = ["sweep", "atlas", *grid, "-q", "--json"]
    r = CliRunner().invoke(app, [*base, "-x", "dask", "-j", "1", "-o", str(tmp_path / "d")])
    assert r.exit_code == 0, r.output
    data = json.loads(r.output)
    assert data["executor"]["backend"] == "dask" and data["executor"]["workers"] == 1
    r = CliRunner().invoke(app, [*base, "-x", "serial", "-o", str(tmp_path / "s")])
    assert r.exit_code == 0, r.output
    assert (tmp_path / "d" / "table.npz").read_bytes() == (
        tmp_path / "s" / "table.npz"
    ).read_bytes()


@pytest.mark.slow
def test_ctrl_c_on_a_local_dask_cluster_stops_cleanly(tmp_path):
    """SIGINT to `betv sweep atlas -x dask` (its own local cluster): exit 130 with the
    resume hint, whole chunks only, the manifest says interrupted, and no process of the
    cluster is left."""
    psutil = require_module("psutil")
    require_module("distributed")
    out = tmp_path / "a"
    cmd = [sys.executable, "-c", "from betvdesign.cli import main; main()", "sweep", "atlas"]
    cmd += ["--varpi", "0.4:2.4:0.02", "--alpha", "0.3,1,3", "--beta", "0.5", "--kappa"]
    cmd += ["0.1,0.3", "--chunksize", "4", "-x", "dask", "-j", "2", "-q", "-o", str(out)]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    proc = subprocess.Popen(cmd, env=env, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and proc.poll() is None:
        if (out / "chunks").is_dir() and len(list((out / "chunks").glob("*.npz"))) >= 3:
            break
        time.sleep(0.05)
    children = psutil.Process(proc.pid).children(recursive=True)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130 and "run the same command again to resume" in err, err[-3000:]
    meta = json.loads((out / "atlas.json").read_text())
    assert meta["status"] == "interrupted"
    kept = sorted((out / "chunks").iterdir())
    assert all(p.name[0].isdigit() for p in kept) and len(kept) < meta["chunks"]
    for p in kept:
        with np.load(p, allow_pickle=False) as z:
            assert len(z["c0"]) == 4
    deadline = time.monotonic() + 10
    while time.monotonic() < deadline:
        left = [c for c in children if c.is_running() and c.status() != psutil.STATUS_ZOMBIE]
        if not left:
            break
        time.sleep(0.2)
    assert not left, f"{len(left)} processes of the cluster remain"
