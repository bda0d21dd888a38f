"""The drawn actuator's temperature limit and ``betv fix`` against it (issue 31, item 6).

Independent truths: the cited 63 % of the absolute melting point (Tuck et al., J. Eng.
Mater. Technol. 127 (2005) 90); voltages found here by bisection of the electrothermal
model's own peak temperature (not by the rule or the fix under test); the FE of the same
drawing for the peak at the proposed voltage.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from test_drawn_stroke import drawn_only
from typer.testing import CliRunner

from betvdesign.checks.thermal_rules import TEMPERATURE_MARGIN, thermal_rules
from betvdesign.cli import app
from betvdesign.model.electrothermal import electrothermal
from betvdesign.nondim.actuator import frame_geometry
from betvdesign.nondim.device import derive
from betvdesign.nondim.stroke import thermal_material
from betvdesign.spec.loader import load_device, load_process
from betvdesign.spec.paths import with_values
from betvdesign.spec.process import shipped_process_path
from betvdesign.spec.units import ureg
from betvdesign.studies.fix import FIELD_MARGIN

ROOT = Path(__file__).resolve().parents[1]
runner = CliRunner()


def drawn_pull(tmp_path: Path, voltage: str, length: str, frequency: str) -> Path:
    """A drawn-only device with long arms (ϖ in the window), pull intended (what the
    drawing's α ≈ 1 gives), a 1 mm travel (the crossing from rest does not depend on the
    stroke)."""
    p = drawn_only(tmp_path, voltage=voltage, frequency=frequency)
    text = p.read_text().replace("length: 240 um", f"length: {length}")
    text = text.replace("intended_mode: push", "intended_mode: pull")
    text = text.replace("travel_range: 50 um", "travel_range: 1000 um")
    p.write_text(text)
    return p


def hot_pull(tmp_path: Path) -> Path:
    """Passes but for its temperature: 1.5 mm arms driven at 1.3 kHz (heating at 2.6 kHz,
    within the thermal bandwidth), 42 V (the peak above the onset)."""
    return drawn_pull(tmp_path, "42 V", "1500 um", "1.3 kHz")


def peak_voltage(spec, target_k: float) -> float:
    """The voltage where the model's peak temperature is ``target_k``, by bisection."""
    aset = spec.actuator_sets[0]
    g, mat = frame_geometry(spec, aset), thermal_material(spec, aset)
    lo, hi = 0.0, 1.0
    while electrothermal(g, mat, hi).t_max < target_k:
        lo, hi = hi, 2 * hi
    for _ in range(60):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if electrothermal(g, mat, mid).t_max < target_k else (lo, mid)
    return (lo + hi) / 2


def peak_rule(spec, volts: float):
    s = derive(with_values(spec, {"drive.voltage": volts * ureg.V})).sets[0]
    rules = thermal_rules(s, spec.process)
    return s, next(r for r in rules if r.id == "thermal.peak-temperature")


def test_the_shipped_onset_is_the_cited_63_percent_of_the_melting_point():
    proc = load_process(shipped_process_path("polymumps"))
    for layer in ("poly1", "poly2"):
        et = proc.layers[layer].electrothermal
        melt = et.melting_point.to("K").magnitude
        assert et.deformation_onset.to("K").magnitude == pytest.approx(0.63 * melt, abs=0.5)
        assert "Tuck" in et.source and "127 (2005) 90" in et.source
        assert f"layers.{layer}.electrothermal.deformation_onset" not in proc.unsourced
    mat = proc.thermal_material("poly1")
    assert mat.deformation_temperature == pytest.approx(1063.0)


def test_error_above_the_onset_warning_within_10_percent_melting_a_fail(tmp_path):
    spec = load_device(drawn_only(tmp_path))
    onset = spec.process.thermal_material().deformation_temperature
    melt = spec.process.thermal_material().melting_temperature
    cases = {
        "pass": onset * (1 - TEMPERATURE_MARGIN) - 20,
        "warning": onset * (1 - TEMPERATURE_MARGIN / 2),
        "onset": (onset + melt) / 2,
        "melts": melt + 50,
    }
    for name, target in cases.items():
        v = peak_voltage(spec, target)
        s, r = peak_rule(spec, v)
        assert s.stroke.t_max_k == pytest.approx(target, rel=1e-6)  # the model's own peak
        assert math.isfinite(r.value) and r.value == pytest.approx(target, rel=1e-6)
        assert "1063 K" in r.threshold and "deformation_onset" in r.threshold
        if name == "pass":
            assert r.passed
        elif name == "warning":
            assert not r.passed and r.severity == "warning"
            assert "within 10% of the onset of plastic deformation 1063 K" in r.message
        elif name == "onset":
            assert not r.passed and r.severity == "error"
            assert "above the onset of plastic deformation 1063 K" in r.message
            assert f"{target:.0f} K" in r.message
        else:
            assert not r.passed and r.severity == "error"
            assert s.stroke.status == "melts"
            assert f"peak temperature {target:.0f} K" in r.message
            assert "melting point 1687 K" in r.message


def test_without_an_onset_the_melting_point_is_checked_and_the_onset_named_unsourced(tmp_path):
    text = (ROOT / "betvdesign" / "data" / "processes" / "polymumps.yaml").read_text()
    text = text.replace("      deformation_onset: 1063 K\n", "")
    (tmp_path / "noonset.yaml").write_text(text)
    spec = load_device(drawn_only(tmp_path, process="noonset.yaml"))
    melt = spec.process.thermal_material().melting_temperature
    v = peak_voltage(spec, (1063 + melt * (1 - TEMPERATURE_MARGIN)) / 2)  # above the onset
    s, r = peak_rule(spec, v)
    assert s.stroke.deformation_k is None
    assert r.passed  # the melting point alone: below its 10 % band
    assert "NOT sourced" in r.threshold and "1687 K" in r.threshold


def test_an_onset_above_the_melting_point_is_refused_naming_the_field(tmp_path):
    text = (ROOT / "betvdesign" / "data" / "processes" / "polymumps.yaml").read_text()
    text = text.replace("deformation_onset: 1063 K", "deformation_onset: 1800 K")
    (tmp_path / "bad.yaml").write_text(text)
    r = runner.invoke(app, ["check", str(drawn_only(tmp_path, process="bad.yaml"))])
    assert r.exit_code == 2, r.output
    assert "deformation_onset" in r.output and "melting_point" in r.output
    assert "Traceback" not in r.output


def test_fix_lowers_the_voltage_to_just_under_the_onset(tmp_path):
    dev = hot_pull(tmp_path)
    spec = load_device(dev)
    onset = spec.process.thermal_material().deformation_temperature
    v_star = peak_voltage(spec, onset)  # the model's peak reaches the onset here
    assert 1 < v_star < 42
    r = runner.invoke(app, ["fix", str(dev), "--vary", "drive.voltage", "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["status"] == "fixed"
    best = d["candidates"][0]
    assert "thermal.peak-temperature" in best["why"].split(";")[0]
    boundary = ureg.Quantity(best["boundary"]["drive.voltage"]).to("V").magnitude
    proposed = ureg.Quantity(best["changes"][0]["to"]).to("V").magnitude
    # the boundary is where the peak reaches the onset (bisected to 0.2 %, printed to 4
    # digits), the proposal a factor 1 + FIELD_MARGIN below it
    assert boundary == pytest.approx(v_star, rel=3e-3)
    assert proposed == pytest.approx(boundary / (1 + FIELD_MARGIN), rel=1e-3)
    aset = spec.actuator_sets[0]
    g, mat = frame_geometry(spec, aset), thermal_material(spec, aset)
    t_prop = electrothermal(g, mat, proposed).t_max
    assert t_prop < onset
    # and a second method: the plane FE of the same drawing puts the peak there too
    from betvdesign.model.electrothermal_fe import electrothermal_fe

    fe = electrothermal_fe(g, mat, proposed, level=1)
    assert fe.t_max < onset
    assert fe.t_max == pytest.approx(t_prop, rel=0.03)


def test_the_check_advises_the_voltage_for_a_too_hot_actuator(tmp_path):
    r = runner.invoke(app, ["check", str(hot_pull(tmp_path)), "--json"])
    assert r.exit_code == 1, r.output
    d = json.loads(r.stdout)["devices"][0]
    assert d["failed"] == ["thermal.peak-temperature"]
    rule = next(x for x in d["sets"][0]["rules"] if x["id"] == "thermal.peak-temperature")
    assert "lower drive.voltage 42 V -> " in rule["fix"]  # with the longer arms
    assert "betv fix" in rule["fix"]


def test_fix_moves_the_drawing_and_the_drive_into_the_thermal_bandwidth(tmp_path):
    """Only ``thermal.bandwidth`` fails (the drive heats at 3× the cut-off): no single field
    clears it with ϖ in the window, a pair does; its |H(f_heat)| recomputed here from the
    model's own thermal modes of the changed drawing."""
    dev = drawn_pull(tmp_path, "9 V", "900 um", "3 kHz")
    spec = load_device(dev)
    s0 = derive(spec).sets[0]
    assert s0.stroke.gain < 0.5  # the current design is far above its cut-off
    r = runner.invoke(
        app,
        ["fix", str(dev), "--vary", "actuator.geometry.length", "--vary", "drive.frequency",
         "--json"],
    )  # fmt: skip
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["status"] == "fixed"
    best = d["candidates"][0]
    assert best["why"].startswith("fixes thermal.bandwidth")
    changes = {c["field"]: ureg.Quantity(c["to"]) for c in best["changes"]}
    fixed = with_values(spec, changes)
    aset = fixed.actuator_sets[0]
    res = electrothermal(frame_geometry(fixed, aset), thermal_material(fixed, aset), 9.0)
    f_heat = 2 * changes["drive.frequency"].to("Hz").magnitude  # AC: heats at 2f
    gain = abs(sum(a / (1 + 2j * math.pi * f_heat * tau) for tau, a in res.modes))
    assert gain >= 0.5


def test_a_process_missing_one_electrothermal_value_names_it_with_exit_2(tmp_path):
    text = (ROOT / "betvdesign" / "data" / "processes" / "polymumps.yaml").read_text()
    text = text.replace("      thermal_conductivity: 32 W/m/K\n", "")
    (tmp_path / "nok.yaml").write_text(text)
    r = runner.invoke(app, ["check", str(drawn_only(tmp_path, process="nok.yaml"))])
    assert r.exit_code == 2, r.output
    assert "layers.poly1.electrothermal.thermal_conductivity: missing required field" in r.output
    assert "nok.yaml:" in r.output and "Traceback" not in r.output
