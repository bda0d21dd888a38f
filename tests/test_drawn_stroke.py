"""A drawn-only device gets a verdict: its stroke predicted from the drawing (issue 31).

Independent truths: Joule heating makes the stroke ∝ V² at small rises (the linear
thermoelastic limit), the roll-off tends to 1 at low heating frequency, the electrical
power is V²/R, and the exact solver's mode and the CLI's exit status.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from typer.testing import CliRunner

from betvdesign.cli import app
from betvdesign.nondim.device import derive
from betvdesign.spec.loader import load_device
from betvdesign.spec.paths import with_values
from betvdesign.spec.units import ureg

ROOT = Path(__file__).resolve().parents[1]
PUSH = ROOT / "devices" / "push_demo.yaml"
runner = CliRunner()


def drawn_only(tmp_path: Path, *, voltage: str = "9 V", frequency: str = "3 kHz",
               process: str = "polymumps") -> Path:  # fmt: skip
    """push_demo without resonances, amplitude or calibration, in PolyMUMPs (2 µm)."""
    keep, skip = [], False
    for ln in PUSH.read_text().splitlines():
        s = ln.strip()
        if "_resonance" in s:
            continue
        if s.startswith("calibration:"):
            skip = True
            continue
        if skip and (s.startswith(("law:", "points:", "- {voltage"))):
            continue
        skip = False
        keep.append(ln)
    text = "\n".join(keep) + "\n"
    text = text.replace("process: demo25", f"process: {process}").replace("2.5 um", "2 um")
    text = text.replace("voltage: 9 V", f"voltage: {voltage}")
    text = text.replace("frequency: 3 kHz", f"frequency: {frequency}")
    p = tmp_path / "drawn_only.yaml"
    p.write_text(text)
    return p


def test_a_drawn_only_device_gets_a_verdict_from_the_exact_solver(tmp_path):
    r = runner.invoke(app, ["check", str(drawn_only(tmp_path)), "--json", "--no-advice"])
    assert r.exit_code in (0, 1), r.output
    d = json.loads(r.stdout)["devices"][0]
    s = d["sets"][0]
    assert s["mode"] in ("push", "pull", "stalled", "not_driven")
    drawn = s["derived"]["drawn"]
    assert drawn["stroke_status"] == "ok"
    assert 0 < drawn["stroke_m"] < drawn["u_static_m"] < 50e-6  # a physical stroke
    assert 300 < drawn["t_max_k"] < 1687  # above the substrate, below melting
    assert drawn["power_w"] == pytest.approx(9.0**2 / drawn["resistance_ohm"], rel=1e-9)
    assert drawn["current_a"] == pytest.approx(9.0 / drawn["resistance_ohm"], rel=1e-9)
    assert drawn["f_heat_hz"] == pytest.approx(6000.0)  # AC: 2·f
    assert 10 < drawn["f_thermal_hz"] < 1e5  # the stroke's cut-off
    # the cut-off: the stroke's gain is 1/√2 when the drive heats there (AC: 2f)
    spec = load_device(drawn_only(tmp_path))
    f_drive = drawn["f_thermal_hz"] / 2 * ureg.Hz
    at = derive(with_values(spec, {"drive.frequency": f_drive})).sets[0].stroke
    assert at.gain == pytest.approx(2**-0.5, rel=1e-6)
    assert s["derived"]["amplitude_m"] == pytest.approx(drawn["stroke_m"], rel=1e-12)
    ids = {x["id"] for x in s["rules"]}
    assert {"thermal.peak-temperature", "thermal.bandwidth", "thermal.power"} <= ids


def test_stroke_goes_as_v_squared_and_rolls_off_to_its_static_half_swing(tmp_path):
    spec = load_device(drawn_only(tmp_path, frequency="1 Hz"))
    u = {}
    for v in (0.05, 0.1):
        s = derive(with_values(spec, {"drive.voltage": v * ureg.V})).sets[0]
        u[v] = s.stroke
    # small rises: thermoelastic and Joule heat linear, u ∝ P ∝ V²
    assert u[0.1].stroke_m / u[0.05].stroke_m == pytest.approx(4.0, rel=2e-3)
    # 2 Hz heating, far below the thermal corner: the half swing is u_static/2
    assert u[0.1].gain == pytest.approx(1.0, abs=1e-3)
    assert u[0.1].stroke_m == pytest.approx(u[0.1].u_static_m / 2, rel=1e-3)


def test_a_voltage_that_melts_the_arm_is_a_clear_fail(tmp_path):
    r = runner.invoke(
        app, ["check", str(drawn_only(tmp_path, voltage="14 V")), "--json", "--no-advice"]
    )
    assert r.exit_code == 1, r.output
    d = json.loads(r.stdout)["devices"][0]
    rule = next(x for x in d["sets"][0]["rules"] if x["id"] == "thermal.peak-temperature")
    assert not rule["passed"] and rule["severity"] == "error"
    assert math.isfinite(rule["value"]) and rule["value"] > 1687
    assert "melting point 1687 K" in rule["message"]
    assert "thermal.peak-temperature" in d["failed"]


def test_far_above_the_thermal_cutoff_warns_with_the_stroke_left(tmp_path):
    spec = load_device(drawn_only(tmp_path, frequency="20 kHz"))
    s = derive(spec).sets[0]
    r = runner.invoke(
        app,
        ["check", str(drawn_only(tmp_path, frequency="20 kHz")), "--json", "--no-advice"],
    )
    d = json.loads(r.stdout)["devices"][0]
    rule = next(x for x in d["sets"][0]["rules"] if x["id"] == "thermal.bandwidth")
    assert not rule["passed"] and rule["value"] == pytest.approx(s.stroke.gain)
    assert f"{s.stroke.gain:.1%}" in rule["message"]


def test_missing_process_data_is_exit_2_naming_the_field(tmp_path):
    text = (ROOT / "betvdesign" / "data" / "processes" / "polymumps.yaml").read_text()
    out, skip, indent = [], False, 0
    for ln in text.splitlines():
        if ln.strip() == "electrothermal:":
            skip, indent = True, len(ln) - len(ln.lstrip())
            continue
        if skip and (not ln.strip() or len(ln) - len(ln.lstrip()) > indent):
            continue
        skip = False
        if "electrothermal" not in ln:
            out.append(ln)
    (tmp_path / "noet.yaml").write_text("\n".join(out) + "\n")
    dev = drawn_only(tmp_path, process="noet.yaml")
    r = runner.invoke(app, ["check", str(dev)])
    assert r.exit_code == 2
    assert "layers.poly1.electrothermal is missing" in r.output
    assert "Traceback" not in r.output


def test_a_drawn_stroke_needs_the_drive_voltage(tmp_path):
    dev = drawn_only(tmp_path)
    dev.write_text(dev.read_text().replace("      voltage: 9 V", ""))
    r = runner.invoke(app, ["check", str(dev)])
    assert r.exit_code == 2 and "drive.voltage" in r.output


def test_a_file_with_a_measured_stroke_has_no_drawn_stroke():
    r = runner.invoke(app, ["check", str(PUSH), "--json", "--no-advice"])
    drawn = json.loads(r.stdout)["devices"][0]["sets"][0]["derived"]["drawn"]
    assert drawn["stroke_m"] is None and drawn["t_max_k"] is None


def test_sweep_of_the_voltage_on_a_drawn_only_device(tmp_path):
    out = tmp_path / "v.csv"
    r = runner.invoke(
        app,
        ["sweep", "device", str(drawn_only(tmp_path)), "--vary", "drive.voltage=4V:8V",
         "--points", "3", "-o", str(out)],
    )  # fmt: skip
    assert r.exit_code == 0, r.output
    rows = out.read_text().splitlines()
    assert len(rows) == 4
