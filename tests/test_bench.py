"""Work-precision study (betvdesign.bench) and ``betv bench``.

Sources: the exact solver as reference and scipy's DOP853 at rtol 1e-13 as the
independent bound on its error; convergence of the fixed-step RK4 in h (a
first-order method once events are post-detected); file outputs checked by
parsing them back (PNG signature, SVG XML, CSV, JSON); CLI runs with typer's
CliRunner. Quick settings only: the full study lives in benchmarks/.
"""

from __future__ import annotations

import csv
import json
import xml.etree.ElementTree as ET

import pytest
from typer.testing import CliRunner

from betvdesign.bench import workprecision as wp
from betvdesign.bench.chart import write_outputs
from betvdesign.bench.fixedstep import rk4_post
from betvdesign.cli import app
from betvdesign.dynamics import simulate

PULL = wp.DESIGNS["pull"].params


@pytest.fixture(scope="module")
def rows():
    return wp.run("quick", designs=["pull"], only={"exact", "rk4-post", "solve_ivp-DOP853"})


def test_rk4_post_converges_first_order():
    """RK4 + post-detected events: error falls with h, but only ~O(h), vs the exact s."""
    ref = simulate(PULL, 4, log_events=False).s
    errs = [abs(rk4_post(PULL, 4, n).s - ref) / abs(ref) for n in (40, 400, 4000)]
    assert errs[2] < errs[0] / 5
    assert errs[2] > 1e-9  # event post-detection caps the order: never near round-off


def test_exact_rows_at_roundoff(rows):
    """The exact solver is within 1e-10 of DOP853 at rtol 1e-13 on both metrics."""
    exact = [r for r in rows if r.method == "exact"]
    assert {r.metric for r in exact} == {"s_N", "delta_s"}
    for r in exact:
        assert r.status == "success"
        assert r.error is not None and r.error <= 1e-10
        assert "bounded by distance to solve_ivp-DOP853" in r.message


def test_alternatives_measured_against_exact(rows):
    """Every alternative row carries an error; DOP853 tightens with rtol; RK4 does not
    reach 1e-6 (post-detection)."""
    dop = sorted(
        (r for r in rows if r.method == "solve_ivp-DOP853" and r.metric == "s_N"),
        key=lambda r: float(r.setting.split("=")[1]),
    )
    assert len(dop) == 2
    assert dop[0].error < dop[1].error
    rk = [r for r in rows if r.method == "rk4-post"]
    assert rk and all(r.error is not None and r.error > 1e-6 for r in rk)


def test_summary_names_cheapest_alternative(rows):
    """Summary: per metric, the cheapest alternative at ≤ 1e-6 and the cost ratio."""
    summ = {s["metric"]: s for s in wp.summarise(rows)}
    for metric in ("s_N", "delta_s"):
        s = summ[metric]
        assert s["cheapest_alternative"].startswith("solve_ivp-DOP853")
        assert s["alternative_error"] <= 1e-6
        assert s["ratio"] == pytest.approx(s["alternative_seconds"] / s["exact_seconds"])


def test_outputs_written_and_reproducible(rows, tmp_path):
    """PNG + SVG chart, CSV and JSON tables; same rows give byte-identical SVG/CSV/JSON."""
    a = write_outputs(rows, tmp_path / "a")
    b = write_outputs(rows, tmp_path / "b")
    names = sorted(p.name for p in a)
    assert names == [f"work_precision.{e}" for e in ("csv", "json", "png", "svg")]
    by = {p.suffix: p for p in a}
    assert by[".png"].read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    root = ET.fromstring(by[".svg"].read_text())
    assert root.tag.endswith("svg")
    with by[".csv"].open() as fh:
        table = list(csv.DictReader(fh))
    assert len(table) == len(rows)
    assert set(table[0]) >= {"method", "setting", "design", "error", "seconds", "status"}
    doc = json.loads(by[".json"].read_text())
    assert len(doc["rows"]) == len(rows) and doc["summary"]
    for pa, pb in zip(sorted(a), sorted(b), strict=True):
        if pa.suffix != ".png":
            assert pa.read_bytes() == pb.read_bytes(), pa.name


def test_cli_json_rows():
    """``betv bench --json``: rows with the contract keys, our solver's method "exact"."""
    res = CliRunner().invoke(
        app, ["bench", "--json", "--design", "pull", "--method", "exact", "--method", "rk4-post"]
    )
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    keys = {"method", "setting", "design", "error", "seconds", "status"}
    assert all(keys <= set(r) for r in data)
    assert {r["method"] for r in data} == {"exact", "rk4-post"}
    assert all(r["design"] == "pull" for r in data)


@pytest.mark.parametrize(
    "args, msg",
    [
        (["--design", "nope"], "unknown design nope"),
        (["--method", "euler"], "unknown method euler"),
    ],
)
def test_cli_bad_input(args, msg):
    """Unknown design/method: one clear line on stderr, exit 2, no traceback."""
    res = CliRunner().invoke(app, ["bench", *args])
    assert res.exit_code == 2
    assert msg in res.stderr
    assert "Traceback" not in res.output


def test_cli_output_not_a_directory(tmp_path):
    """-o pointing at a file: exit 2 and the file is left untouched."""
    f = tmp_path / "file.txt"
    f.write_text("keep")
    res = CliRunner().invoke(app, ["bench", "--design", "pull", "--method", "exact", "-o", str(f)])
    assert res.exit_code == 2
    assert "not a directory" in res.stderr
    assert f.read_text() == "keep"


def test_failure_map_scan_along_varpi(tmp_path):
    """Scan along ϖ (at the resonance ϖ = 1 too): exact within 1e-10 of DOP853 rtol 1e-13,
    every alternative measured; outputs written (PNG, SVG, JSON)."""
    from betvdesign.bench.failuremap import scan, write_failure_map

    rows = scan([1.0, 1.7], cycles=3)
    assert {r["method"] for r in rows} == {"exact", "solve_ivp-RK45", "tanh-LSODA", "rk4-post"}
    for r in rows:
        assert r["exact_status"] == "success" and r["error"] is not None
        if r["method"] == "exact":
            assert r["error"] <= 1e-10
        if r["method"] == "rk4-post":
            assert r["error"] > 1e-6
    paths = write_failure_map(rows, tmp_path)
    assert sorted(p.suffix for p in paths) == [".json", ".png", ".svg"]
    assert json.loads(paths[-1].read_text())["rows"] == rows
