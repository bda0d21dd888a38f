"""CLI of the studies: bad input gives one clear line and exit 2, --json gives
machine-readable stdout (source: typer CliRunner runs of the real commands)."""

import json
import os

import pytest
from typer.testing import CliRunner

from betvdesign.cli import app

runner = CliRunner()
MAP = ["sweep", "pushpull", "--alpha", "1", "--beta", "0.5", "--kappa", "0.4"]


def _run(args):
    return runner.invoke(app, args)


@pytest.mark.parametrize(
    ("varpi", "fragment"),
    [
        ("", "varpi: empty range"),
        ("2:0.5:0.1", "varpi: inverted range"),
        ("0.5:2:0", "varpi: step must be > 0"),
        ("0.5:2", "three fields"),
        ("x", "not a number"),
        ("0,1", "varpi: values must be > 0"),
    ],
)
def test_bad_ranges_exit_2_with_message(varpi, fragment):
    r = _run([*MAP, "--varpi", varpi, "-x", "serial", "--fidelity", "lambda"])
    assert r.exit_code == 2, r.output
    assert fragment in r.stderr
    assert "Traceback" not in r.output
    assert r.stdout == ""


def test_unknown_parameter_is_a_usage_error():
    r = _run([*MAP, "--varpi", "1", "--gamma", "2"])
    assert r.exit_code == 2
    assert "--gamma" in r.stderr


def test_unknown_executor_and_fidelity():
    r = _run([*MAP, "--varpi", "1", "-x", "gpu"])
    assert r.exit_code == 2 and "unknown executor 'gpu'" in r.stderr
    r = _run([*MAP, "--varpi", "1", "-x", "serial", "--fidelity", "guess"])
    assert r.exit_code == 2 and "unknown fidelity" in r.stderr


def test_unwritable_output_exit_2_and_nothing_written(tmp_path):
    blocker = tmp_path / "not-a-dir"
    blocker.write_text("x")
    out = blocker / "map.csv"
    r = _run([*MAP, "--varpi", "1", "-x", "serial", "--fidelity", "lambda", "-o", str(out)])
    assert r.exit_code == 2
    assert "cannot create output directory" in r.stderr
    a_dir = tmp_path / "m.csv"
    a_dir.mkdir()
    r = _run([*MAP, "--varpi", "1", "-x", "serial", "--fidelity", "lambda", "-o", str(a_dir)])
    assert r.exit_code == 2
    assert "is a directory, expected a file name" in r.stderr
    assert list(a_dir.iterdir()) == []


@pytest.mark.skipif(os.geteuid() == 0, reason="root may write into read-only directories")
def test_read_only_directory_exit_2(tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o500)
    try:
        r = _run(
            [*MAP, "--varpi", "1", "-x", "serial", "--fidelity", "lambda", "-o", str(ro / "m.csv")]
        )
        assert r.exit_code == 2
        assert "not writable" in r.stderr
        assert list(ro.iterdir()) == []
    finally:
        ro.chmod(0o700)


def test_lambda_rung_json_summary_and_streamed_output(tmp_path):
    out = tmp_path / "m.csv"
    args = [*MAP, "--varpi", "0.5:1.5:0.5", "-x", "serial", "--fidelity", "lambda", "-o", str(out)]
    r = _run([*args, "--json"])
    assert r.exit_code == 0, r.stderr
    data = json.loads(r.stdout)
    assert data["points"] == 3 and data["computed"] == 3 and data["out"] == str(out)
    assert out.exists() and (tmp_path / "m.json").exists()
    again = json.loads(_run([*args, "--json"]).stdout)
    assert again["computed"] == 0 and again["resumed"] == 3


DEVICE = "devices/shin2004.yaml"


@pytest.mark.parametrize(
    ("tol", "fragment"),
    [
        ("slider.gizmo=2%", "slider.gizmo: not a numeric field"),
        ("drive.waveform=2%", "drive.waveform: not a numeric field"),
        ("slider.beam_width", "must read FIELD="),
        ("slider.beam_width=-2%", "must be > 0"),
        ("slider.beam_width=normal:0.2 kHz", "not in units of"),
    ],
)
def test_tolerance_bad_fields_exit_2(tol, fragment):
    r = _run(
        ["tolerance", DEVICE, "--spread", tol, "-n", "4", "--fidelity", "lambda", "-x", "serial"]
    )
    assert r.exit_code == 2, r.output
    assert fragment in r.stderr
    assert "Traceback" not in r.output


def test_tolerance_needs_a_tolerance_and_a_known_set():
    r = _run(["tolerance", DEVICE, "-n", "4", "-x", "serial"])
    assert r.exit_code == 2 and "at least one tolerance" in r.stderr
    r = _run(["tolerance", DEVICE, "--spread", "head.mass=1%", "--set", "up", "-x", "serial"])
    assert r.exit_code == 2 and "no actuator set 'up'" in r.stderr


def test_tolerance_file_errors_name_file_and_line(tmp_path):
    f = tmp_path / "tol.yaml"
    f.write_text(
        "tolerances:\n  head.mass: {dist: normal, sigma: 1%}\n  head.mass2: {dist: cauchy}\n"
    )
    r = _run(["tolerance", DEVICE, "--tolerances", str(f), "-x", "serial", "--fidelity", "lambda"])
    assert r.exit_code == 2
    assert f"{f}:3: head.mass2: unknown distribution 'cauchy'; use normal, uniform" in r.stderr


# -- real runs of the exact solver through the CLI -----------------------------------
def test_pushpull_map_json_figure_and_resume(tmp_path):
    out, fig = tmp_path / "map.csv", tmp_path / "map.svg"
    args = [
        "sweep",
        "pushpull",
        "--varpi",
        "0.9,1.3,2.2",
        "--alpha",
        "0.1,4",
        "--beta",
        "0.5",
        "--kappa",
        "0.4",
        "-x",
        "serial",
        "-o",
        str(out),
        "--figure",
        str(fig),
        "--json",
    ]
    r = _run(args)
    assert r.exit_code == 0, r.stderr
    data = json.loads(r.stdout)
    assert data["points"] == 6 and data["computed"] == 6
    assert data["converged"] == 4 and data["push"] + data["pull"] == 4
    assert {d["status"] for d in data["not_converged"]} == {"not_driven"}  # ϖ = 2.2
    assert fig.read_text().startswith("<?xml") and out.exists()
    first = out.read_bytes()
    again = json.loads(_run(args).stdout)
    assert again["computed"] == 0 and again["resumed"] == 6
    assert out.read_bytes() == first


def test_human_output_lists_failures():
    r = _run(
        [
            "sweep",
            "pushpull",
            "--varpi",
            "2.2",
            "--alpha",
            "1",
            "--beta",
            "0.5",
            "--kappa",
            "0.4",
            "-x",
            "serial",
            "-q",
        ]
    )
    assert r.exit_code == 0
    assert "not converged: ϖ=2.2" in r.stdout and "not_driven" in r.stdout


def test_lambda_and_regime_commands():
    r = _run(
        [
            "sweep",
            "lambda",
            "--kappa",
            "0.4",
            "--beta",
            "0.5",
            "--alpha",
            "1",
            "--lambda",
            "0.8,0.9,1.0,1.2",
            "-x",
            "serial",
            "--json",
        ]
    )
    assert r.exit_code == 0, r.stderr
    data = json.loads(r.stdout)
    assert [round(x["lam"], 12) for x in data["rows"]] == [0.8, 0.9, 1.0, 1.2]
    assert data["sign_changes"] and data["sign_changes"][0]["from"] < data["sign_changes"][0]["to"]
    r = _run(["sweep", "lambda", "--kappa", "0.4", "--beta", "0.5", "-x", "serial"])
    assert r.exit_code == 2 and "needs a fixed --alpha" in r.stderr
    r = _run(["sweep", "regime", "--varpi", "0.5:2.5:0.5", "-x", "serial", "--json"])
    assert r.exit_code == 0, r.stderr
    data = json.loads(r.stdout)
    assert [iv["label"] for iv in data["overview"]] == ["period-1", "impulsive"]


def test_tolerance_periodic_rung_cli(tmp_path):
    """`betv tolerance` on push_demo with f_h and f_drive spread: every row's speed is
    Δs·u·cosθ·f_act worked out by hand from the sampled values (f_act = 2·f_drive, AC;
    ϖ = f_act/f_v, α = (f_v/f_h)², f_v = 5 kHz; u = 0.14 µm, θ = 20.56°; Δs from the
    periodic orbit of those parameters), and the summary's percentiles and push share
    are those of the rows (numpy's percentile, a count)."""
    import csv
    import math

    import numpy as np

    from betvdesign.dynamics import periodic_orbit
    from betvdesign.model.params import ModelParams

    out = tmp_path / "tol.csv"
    r = _run(
        [
            "tolerance",
            "devices/push_demo.yaml",
            "--spread",
            "actuator.horizontal_resonance=5%",
            "--spread",
            "drive.frequency=uniform:2%",
            "-n",
            "3",
            "--seed",
            "4",
            "-x",
            "serial",
            "--json",
            "-o",
            str(out),
        ]
    )
    assert r.exit_code == 0, r.stderr
    s = json.loads(r.stdout)["sets"]["forward"]
    assert s["mode_from"] == "periodic orbit"
    with out.open(newline="", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == 3
    theta = math.radians(20.56)
    beta = (math.pi / 4 * 36**2 * 2.5) / (200 * 10 * 2.5)
    speeds = []
    for row in rows:
        f_h = float(row["in:actuator.horizontal_resonance"])  # kHz, as the file gives it
        f_act = 2 * float(row["in:drive.frequency"])  # kHz
        p = ModelParams(f_act / 5, (5 / f_h) ** 2, beta, 0.4 * math.tan(theta))
        po = periodic_orbit(p)
        assert po.success, po.message
        speed_um_s = po.delta_s * 0.14 * math.cos(theta) * f_act * 1e3
        assert float(row["speed_um_s"]) == pytest.approx(speed_um_s, rel=1e-9)
        speeds.append(speed_um_s)
    assert s["p_push"] == sum(v > 0 for v in speeds) / 3 and s["p_pull"] == 0.0
    pct = s["speed_um_s_percentiles"]
    for q in (5, 25, 50, 75, 95):
        assert pct[f"p{q}"] == pytest.approx(np.percentile(speeds, q), rel=1e-9)


def test_ctrl_c_keeps_finished_points_and_exits_130(tmp_path, monkeypatch):
    from betvdesign.studies import pushpull

    calls = {"n": 0}
    real = pushpull.lambda_point

    def flaky(task):
        calls["n"] += 1
        if calls["n"] > 2:
            raise KeyboardInterrupt
        return real(task)

    monkeypatch.setattr(pushpull, "lambda_point", flaky)
    out = tmp_path / "m.csv"
    r = _run(
        [
            *MAP,
            "--varpi",
            "0.5:1.5:0.25",
            "-x",
            "serial",
            "--chunksize",
            "1",
            "--fidelity",
            "lambda",
            "-o",
            str(out),
        ]
    )
    assert r.exit_code == 130
    assert "run the same command again to resume" in r.stderr
    meta = json.loads((tmp_path / "m.json").read_text())
    assert meta["status"] == "interrupted" and meta["done"] == 2
