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
    assert "is not a writable file" in r.stderr
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
    r = _run(["tolerance", DEVICE, "--tol", tol, "-n", "4", "--fidelity", "lambda", "-x", "serial"])
    assert r.exit_code == 2, r.output
    assert fragment in r.stderr
    assert "Traceback" not in r.output


def test_tolerance_needs_a_tolerance_and_a_known_set():
    r = _run(["tolerance", DEVICE, "-n", "4", "-x", "serial"])
    assert r.exit_code == 2 and "at least one tolerance" in r.stderr
    r = _run(["tolerance", DEVICE, "--tol", "head.mass=1%", "--set", "up", "-x", "serial"])
    assert r.exit_code == 2 and "no actuator set 'up'" in r.stderr


def test_tolerance_file_errors_name_file_and_line(tmp_path):
    f = tmp_path / "tol.yaml"
    f.write_text(
        "tolerances:\n  head.mass: {dist: normal, sigma: 1%}\n  head.mass2: {dist: cauchy}\n"
    )
    r = _run(["tolerance", DEVICE, "--tolerances", str(f), "-x", "serial", "--fidelity", "lambda"])
    assert r.exit_code == 2
    assert f"{f}:3: head.mass2: dist must be normal or uniform" in r.stderr
