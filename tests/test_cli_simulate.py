"""``betv simulate`` (source: typer CliRunner runs of the command, checked against the
Python API it wraps and against the JSON contract of issue 3 / docs/ARCHITECTURE.md)."""

import json
import math
from pathlib import Path

import pytest
from typer.testing import CliRunner

from betvdesign.cli import app
from betvdesign.dynamics import periodic_orbit, simulate
from betvdesign.model.params import ModelParams
from betvdesign.nondim.device import derive_file
from betvdesign.output.siformat import format_si

DEVICES = Path(__file__).resolve().parents[1] / "devices"
KEYS = {
    "params",
    "status",
    "message",
    "cycles",
    "s",
    "delta_s",
    "mode",
    "period_cycles",
    "residual",
    "floquet",
    "impacts_per_cycle",
    "contact_fraction",
}
ARGS = ["--varpi", "1.2", "--alpha", "0.5", "--beta", "1", "--kappa", "0.4"]


def _run(args):
    return CliRunner().invoke(app, ["simulate", *args])


def test_transient_json_matches_api():
    r = _run([*ARGS, "--cycles", "30", "--json"])
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    assert KEYS <= set(out)
    tr = simulate(ModelParams(1.2, 0.5, 1.0, 0.4), 30)
    assert out["s"] == tr.s and out["delta_s"] == tr.delta_s[-1] and out["cycles"] == 30
    assert out["params"] == {"varpi": 1.2, "alpha": 0.5, "beta": 1.0, "kappa": 0.4}
    assert out["period_cycles"] is None and out["floquet"] is None


def test_periodic_json_matches_api():
    r = _run([*ARGS, "--periodic", "--json"])
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    po = periodic_orbit(ModelParams(1.2, 0.5, 1.0, 0.4))
    assert out["delta_s"] == po.delta_s and out["mode"] == "pull" == po.mode
    assert out["period_cycles"] == 1 and out["residual"] <= 1e-10
    assert len(out["floquet"]) == 3 and max(out["floquet"]) < 1


def test_device_file_gives_physical_units():
    path = DEVICES / "push_demo.yaml"
    r = _run([str(path), "--periodic", "--json"])
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    d = derive_file(path).sets[0]
    ph = out["physical"]
    assert out["set"] == d.name and out["params"] == d.params.as_dict()
    # SI floats under unit-named keys; u = 0.14 µm, θ = 20.56°, f_act = 6 kHz by hand
    ell = 0.14e-6 * math.cos(math.radians(20.56))
    assert ph["length_scale_m"] == pytest.approx(ell, rel=1e-3)
    assert ph["speed_m_s"] == pytest.approx(out["delta_s"] * ell * 6000.0, rel=1e-3)
    assert ph["delta_s_m"] == pytest.approx(out["delta_s"] * d.scales.length_m, rel=1e-12)
    assert ph["cycle_s"] == pytest.approx(1 / 6000.0)
    text = _run([str(path), "--periodic"]).stdout
    assert f"mean speed {format_si(ph['speed_m_s'], 'm/s', digits=4)}" in text
    assert "mm/s" in text and "µm/s" not in text  # 1.84 mm/s, by magnitude


def test_text_output():
    r = _run([*ARGS, "--cycles", "5"])
    assert r.exit_code == 0
    assert "last-cycle Δs" in r.stdout and "pull" in r.stdout


@pytest.mark.parametrize(
    "args,needle",
    [
        (["--varpi", "1.2", "--alpha", "nan", "--beta", "1", "--kappa", "0.4"], "alpha"),
        (["--varpi", "0", "--alpha", "1", "--beta", "1", "--kappa", "0.4"], "varpi"),
        (["--varpi", "1.2"], "missing"),
        ([str(DEVICES / "push_demo.yaml"), "--varpi", "1"], "not both"),
        ([str(DEVICES / "push_demo.yaml"), "--set", "nope"], "no actuator set"),
        (["does-not-exist.yaml"], "does-not-exist.yaml"),
    ],
)
def test_bad_input_exit_2_without_traceback(args, needle):
    r = _run(args)
    assert r.exit_code == 2
    assert needle in r.stderr
    assert "Traceback" not in r.output


def test_solver_failure_exit_1_with_message():
    """ϖ beyond the window: no contact recurs, the slider is not driven (MODEL.md)."""
    r = _run(
        ["--varpi", "2.3", "--alpha", "1", "--beta", "1", "--kappa", "0.4", "--periodic", "--json"]
    )
    assert r.exit_code == 1
    out = json.loads(r.stdout)
    assert out["status"] == "not_driven" and out["delta_s"] is None and out["mode"] is None


def test_pull_device_states_travel_direction_beside_the_magnitude():
    """One convention with ``betv check`` (issue 32 item 13): the speed is a magnitude
    beside the travel direction, in JSON and text; Δs keeps its sign (− pull)."""
    path = DEVICES / "pull_demo.yaml"
    out = json.loads(_run([str(path), "--periodic", "--json"]).stdout)
    ph = out["physical"]
    assert out["mode"] == "pull" and out["delta_s"] < 0 and ph["delta_s_m"] < 0
    assert ph["speed_m_s"] == pytest.approx(-ph["delta_s_m"] * ph["f_act_hz"], rel=1e-12)
    check_json = json.loads(CliRunner().invoke(app, ["check", str(path), "--json"]).stdout)
    assert check_json["devices"][0]["sets"][0]["speed_m_s"] > 0  # the check's: a magnitude
    d = derive_file(path).sets[0]
    assert out["impact_direction"] == ("+x" if d.impact_sign > 0 else "-x")
    assert ph["travel_direction"] == ("-x" if d.impact_sign > 0 else "+x")
    text = _run([str(path), "--periodic"]).stdout
    magnitude = format_si(abs(ph["speed_m_s"]), "m/s", digits=4)
    assert f"mean speed {magnitude} toward {ph['travel_direction']}" in text
    check = CliRunner().invoke(app, ["check", str(path)]).stdout
    assert f"toward {ph['travel_direction']}" in check
