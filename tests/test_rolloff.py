"""Thermal roll-off of the actuator stroke (docs/MODEL.md, "Device-to-parameter relations";
shared MODEL.md, "Thermal roll-off of the actuator"): u = u_cal·H(f_act)/H(f_cal),
H(f) = 1/sqrt(1 + (f/f_c)²), f_c = 1/(2π τ_th).

Independent truths: the closed form written out here with ``math.sqrt`` (the package
uses ``hypot``), numbers computed by hand for devices/rolloff_demo.yaml; derivation
values stored before the roll-off fields existed (tests/data/nondim_baseline.json,
bit-identical); the exact periodic Δs of the same device without the fields (the
roll-off may only rescale the speed, by the closed-form ratio); file:line positions
read off the texts below by hand.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from betvdesign.cli import app
from betvdesign.errors import SpecError
from betvdesign.nondim.device import derive, derive_file, derive_samples, derive_set
from betvdesign.report.frequency import FrequencySweep, frequency_grid, speeds
from betvdesign.spec.loader import load_device, load_device_text
from betvdesign.spec.paths import replace, targets
from betvdesign.spec.units import ureg

TESTS = Path(__file__).resolve().parent
DEVICES = TESTS.parent / "devices"
DEMO = DEVICES / "rolloff_demo.yaml"
BASELINE = json.loads((TESTS / "data" / "nondim_baseline.json").read_text("utf-8"))
ROLLOFF_LINES = (
    "      thermal_time_constant: 0.2 ms    # or thermal_cutoff: 796 Hz (f_c = 1/(2π τ_th))\n"
    "      calibration_frequency: 200 Hz    # actuation frequency of the calibration above\n"
)


def closed_form_ratio(f: float, f_cal: float, f_c: float) -> float:
    """H(f)/H(f_cal) for H(f) = 1/sqrt(1 + (f/f_c)²), written out."""
    return math.sqrt(1.0 + (f_cal / f_c) ** 2) / math.sqrt(1.0 + (f / f_c) ** 2)


def demo_text(**swap: str) -> str:
    text = DEMO.read_text("utf-8")
    assert ROLLOFF_LINES in text
    return text.replace(ROLLOFF_LINES, swap.get("rolloff", ROLLOFF_LINES))


def run(*args):
    return CliRunner().invoke(app, [str(a) for a in args])


# --- the closed form -----------------------------------------------------------------


def test_demo_amplitude_by_hand():
    """u_cal = 0.14 µm (9 V halfway between 8 V: 0.11 µm and 10 V: 0.17 µm), τ_th = 0.2 ms
    -> f_c = 795.7747 Hz, f_act = 2 × 3 kHz = 6 kHz, f_cal = 200 Hz:
    u = 0.14 µm·sqrt(1 + (200/795.77)²)/sqrt(1 + (6000/795.77)²) = 0.018979 µm."""
    sd = derive_file(DEMO).sets[0]
    f_c = 1.0 / (2.0 * math.pi * 0.2e-3)
    assert f_c == pytest.approx(795.7747154594767, rel=1e-15)
    ratio = closed_form_ratio(6000.0, 200.0, f_c)
    assert ratio == pytest.approx(0.135567, rel=1e-5)  # by hand: 1.03108/7.60573
    sc = sd.scales
    assert sc.u_m == pytest.approx(0.14e-6 * ratio, rel=1e-14)
    assert sc.u_m == pytest.approx(1.8979e-8, rel=1e-4)
    assert sc.length_m == pytest.approx(sc.u_m * math.cos(math.radians(20.56)), rel=1e-14)
    assert sc.cutoff_hz == pytest.approx(f_c, rel=1e-15) and sc.calibration_hz == 200.0
    assert sc.rolloff_factor == pytest.approx(ratio, rel=1e-14)
    # at another frequency the scales give u_cal·H(f)/H(f_cal) as well
    assert sc.amplitude_m(2500.0) == pytest.approx(
        0.14e-6 * closed_form_ratio(2500.0, 200.0, f_c), rel=1e-14
    )
    assert sc.amplitude_m(200.0) == pytest.approx(0.14e-6, rel=1e-14)


def test_record_shows_every_new_quantity():
    sd = derive_file(DEMO).sets[0]
    rows = {s.symbol: s for s in sd.record}
    assert rows["u_cal"].formula == "interp(V; measured points)"
    assert rows["u_cal"].value.to("um").magnitude == pytest.approx(0.14, rel=1e-14)
    assert rows["τ_th"].formula == "spec: actuator.thermal_time_constant"
    assert rows["f_c"].formula == "1/(2π·τ_th)" and rows["f_c"].inputs == ("τ_th",)
    assert rows["f_cal"].formula == "spec: actuator.calibration_frequency"
    assert rows["H(f_act)"].inputs == ("f_act", "f_c")
    f_c = 1.0 / (2.0 * math.pi * 0.2e-3)
    assert rows["H(f_act)"].magnitude == pytest.approx(1 / math.sqrt(1 + (6000 / f_c) ** 2))
    assert rows["H(f_cal)"].magnitude == pytest.approx(1 / math.sqrt(1 + (200 / f_c) ** 2))
    assert rows["u"].formula == "u_cal·H(f_act)/H(f_cal)"
    assert rows["ℓ"].inputs == ("u", "θ")  # the length scale uses the rolled-off u
    order = [s.symbol for s in sd.record]
    assert order.index("u") < order.index("ℓ")
    assert sd.derived()["u"] == rows["u"].value_str  # `betv check --json` shows it
    assert {s.key for s in sd.record} >= {"tau_th", "H_act", "H_cal", "u_cal", "f_c", "f_cal"}


def test_cutoff_and_time_constant_agree():
    f_c = 1.0 / (2.0 * math.pi * 0.2e-3)
    by_tau = derive_file(DEMO).sets[0].scales
    spec = load_device_text(
        demo_text(
            rolloff=f"      thermal_cutoff: {f_c!r} Hz\n      calibration_frequency: 200 Hz\n"
        ),
        "c.yaml",
    )
    by_fc = derive(spec).sets[0].scales
    assert by_fc.u_m == pytest.approx(by_tau.u_m, rel=1e-15)


def test_calibration_at_the_operating_frequency_keeps_u_exactly():
    """f_cal = f_act: H(f_act)/H(f_cal) = 1 exactly, so every number equals the device
    without the fields (push_demo's physics)."""
    plain = derive(load_device_text(demo_text(rolloff=""), "p.yaml")).sets[0]
    at_act = derive(
        load_device_text(
            demo_text(rolloff="      thermal_cutoff: 300 Hz\n      calibration_frequency: 6 kHz\n"),
            "a.yaml",
        )
    ).sets[0]
    assert at_act.scales.u_m == plain.scales.u_m
    assert at_act.scales.length_m == plain.scales.length_m
    assert at_act.params == plain.params


def test_roll_off_acts_at_the_actuation_frequency_after_ac_doubling():
    """AC at 3 kHz and a unipolar drive at 6 kHz have the same actuation frequency and so
    the same stroke; H at the drive frequency (3 kHz) would give a different one."""
    ac = derive_file(DEMO).sets[0].scales
    uni = derive(
        load_device_text(
            DEMO.read_text("utf-8")
            .replace("waveform: ac ", "waveform: unipolar ")
            .replace("frequency: 3 kHz", "frequency: 6 kHz"),
            "u.yaml",
        )
    ).sets[0]
    assert uni.scales.f_act_hz == 6000.0
    assert uni.scales.u_m == ac.u_m
    f_c = 1.0 / (2.0 * math.pi * 0.2e-3)
    wrong = 0.14e-6 * closed_form_ratio(3000.0, 200.0, f_c)
    assert abs(ac.u_m / wrong - 1.0) > 0.4  # ≈ 3000/6000 far above f_c


def test_mode_parameters_do_not_depend_on_the_roll_off():
    plain = derive(load_device_text(demo_text(rolloff=""), "p.yaml")).sets[0]
    rolled = derive_file(DEMO).sets[0]
    assert rolled.params == plain.params and rolled.lam == plain.lam
    assert rolled.scales.time_s == plain.scales.time_s
    f_c = 1.0 / (2.0 * math.pi * 0.2e-3)
    assert rolled.scales.length_m / plain.scales.length_m == pytest.approx(
        closed_form_ratio(6000.0, 200.0, f_c), rel=1e-14
    )


# --- defaults: the paper's model, bit for bit ----------------------------------------


@pytest.mark.parametrize("name", sorted(BASELINE["devices"]))
def test_without_the_fields_the_derivation_is_bit_identical(name, tmp_path):
    """Every number of the derivation (record, parameters, λ, scales) equals, bit for bit,
    what the code computed before the roll-off fields existed."""
    stored = BASELINE["devices"][name]
    f = tmp_path / name
    f.write_text(stored["text"], "utf-8")
    der = derive_file(f)
    assert [s.name for s in der.sets] == list(stored["sets"])
    for sd in der.sets:
        want = stored["sets"][sd.name]
        p = sd.params
        assert [float.hex(x) for x in (p.varpi, p.alpha, p.beta, p.kappa)] == want["params"]
        assert float.hex(sd.lam) == want["lam"]
        for key, value in want["scales"].items():
            assert float.hex(getattr(sd.scales, key)) == value, key
        got = [
            [s.symbol, s.formula, str(s.value.units), float.hex(float(s.value.magnitude))]
            for s in sd.record
        ]
        assert got == want["record"]
        assert not sd.scales.has_rolloff and sd.scales.rolloff_factor == 1.0


# --- the vectorised derivation (tolerance studies) -----------------------------------


@pytest.mark.parametrize("device", [DEMO, DEVICES / "damped_demo.yaml"], ids=lambda p: p.stem)
def test_derive_samples_matches_derive_set_with_roll_off(device):
    """Arrays of drive frequencies and time constants through derive_samples equal the
    one-by-one derive_set of each sample (the same code, vectorised); on damped_demo
    (Q = 30, e = 0.1) the damping and restitution columns too."""
    spec = load_device(device)
    f_drive = np.array([1.5e3, 2.2e3, 3e3, 4.1e3])
    tau = np.array([0.1, 0.2, 0.5, 1.0])  # ms
    arrays = spec
    for field, value in (
        ("drive.frequency", ureg.Quantity(f_drive, "Hz")),
        ("actuator.thermal_time_constant", ureg.Quantity(tau, "ms")),
    ):
        (target,) = targets(spec, field)
        arrays = replace(arrays, target, value)
    many = derive_samples(arrays, arrays.actuator_sets[0])
    for i in range(len(f_drive)):
        one = spec.replace(
            "actuator_sets.0.drive.frequency",
            f"{float(f_drive[i])!r} Hz",
            ("actuator_sets.0.actuator.thermal_time_constant", f"{float(tau[i])!r} ms"),
        )
        sd = derive_set(one, one.actuator_sets[0])
        assert many.length_m[i] == pytest.approx(sd.scales.length_m, rel=1e-15)
        assert many.varpi[i] == pytest.approx(sd.params.varpi, rel=1e-15)
        extra = (many.zeta_v[i], many.zeta_h[i], many.restitution[i])
        assert extra == (sd.params.zeta_v, sd.params.zeta_h, sd.params.restitution)
        f_c = 1.0 / (2.0 * math.pi * tau[i] * 1e-3)
        ratio = closed_form_ratio(2.0 * f_drive[i], 200.0, f_c)
        assert many.length_m[i] == pytest.approx(
            0.14e-6 * ratio * math.cos(math.radians(20.56)), rel=1e-13
        )


# --- the report's speed-frequency figure ---------------------------------------------


def test_speed_frequency_curves_differ_by_the_closed_form_ratio():
    """Whatever Δs the orbits give, the rolled-off speed over the constant-stroke one is
    H(f)/H(f_cal) at each frequency, and both equal Δs·u·cosθ·f; the grid holds the
    device's own ϖ."""
    sd = derive_file(DEMO).sets[0]
    grid = frequency_grid(sd.params.varpi, 9)
    assert sd.params.varpi in grid and grid[0] <= 0.5 and grid[-1] < 2.0
    f_v = sd.scales.f_act_hz / sd.params.varpi
    f = grid * f_v
    i = int(np.argmin(np.abs(grid - sd.params.varpi)))
    ds = [0.3 + 0.1 * k if k != (i + 2) % len(f) else None for k in range(len(f))]
    rolled, constant = speeds(sd, FrequencySweep(f, ds, [""] * len(f), len(f) - 1))
    f_c = 1.0 / (2.0 * math.pi * 0.2e-3)
    cos = math.cos(math.radians(20.56))
    for fk, d, v, v0 in zip(f, ds, rolled, constant, strict=True):
        if d is None:
            assert v is None and v0 is None
            continue
        assert v0 == pytest.approx(d * 0.14e-6 * cos * fk, rel=1e-13)
        assert v / v0 == pytest.approx(closed_form_ratio(fk, 200.0, f_c), rel=1e-13)
    assert rolled[i] == pytest.approx(sd.scales.speed_m_s(ds[i]), rel=1e-13)


@pytest.mark.slow
def test_report_of_the_demo_has_the_roll_off_figure():
    from betvdesign.report import ReportOptions, build_report, prepare

    opts = ReportOptions(regime_points=5, robustness_points=3, frequency_points=6)
    figs = build_report(prepare(DEMO), options=opts).figures()
    (fig,) = [x for x in figs if "actuation frequency, with thermal roll-off" in x.title]
    assert fig.svg is not None, fig.unavailable
    assert "f_c = 796 Hz" in fig.caption and "0.136 × u_cal" in fig.caption
    volt = next(x for x in figs if x.title == "Mean speed against drive voltage")
    assert "H(f_act)/H(f_cal) = 0.136" in volt.caption


# --- betv check and betv fix ---------------------------------------------------------


def _check(path: Path) -> dict:
    r = run("check", path, "--json", "-v")
    assert r.exit_code in (0, 1), r.output
    (dev,) = json.loads(r.stdout)["devices"]
    return dev


def test_check_speed_is_the_rolled_off_speed(tmp_path):
    """betv check: same exact Δs with and without the fields; speed scaled by the
    closed-form ratio."""
    plain = tmp_path / "plain.yaml"
    plain.write_text(demo_text(rolloff=""), "utf-8")
    a, b = _check(DEMO)["sets"][0], _check(plain)["sets"][0]
    assert a["delta_s"] == b["delta_s"] and a["mode"] == b["mode"] == "push"
    f_c = 1.0 / (2.0 * math.pi * 0.2e-3)
    ratio = closed_form_ratio(6000.0, 200.0, f_c)
    assert a["speed_m_s"] / b["speed_m_s"] == pytest.approx(ratio, rel=1e-12)
    # the time to cross is the transient's own (from rest): the periodic speed's travel
    # time plus the lag of the settling (the slider starts from rest and is within 1 % of
    # its periodic speed after cycles_to_settle; it loses at most that many cycles)
    for s in (a, b):
        lag = s["settling"]["cycles_to_settle"] / 6000.0
        ideal = s["travel_range_m"] / abs(s["speed_m_s"])
        assert 0.0 <= s["time_to_cross_s"] - ideal <= lag + 1.0 / 6000.0
    da, db = a["derived"], b["derived"]
    assert da["calibrated_amplitude_m"] == db["amplitude_m"] == pytest.approx(0.14e-6)
    assert da["thermal_cutoff_hz"] == pytest.approx(f_c) and da["calibration_frequency_hz"] == 200
    assert da["amplitude_m"] == pytest.approx(0.14e-6 * ratio, rel=1e-14)
    assert not {"calibrated_amplitude_m", "thermal_cutoff_hz"} & set(db)
    text = run("check", DEMO).stdout
    assert "u 19 nm (roll-off ×0.136)" in text and "249 µm/s" in text


def test_fix_changing_the_drive_frequency_reports_the_rolled_off_speed(tmp_path):
    """shin2004 (ϖ ≈ 0.34, below the window) with a low cut-off f_c = 300 Hz, calibrated
    at its own f_act = 1 kHz: `betv fix --vary drive.frequency` raises the frequency, and
    the speed it reports (and `betv check` of the written file) is the exact speed of the
    same frequency without roll-off times sqrt(1 + (f_cal/f_c)²)/sqrt(1 + (f_new/f_c)²)."""
    text = (DEVICES / "shin2004.yaml").read_text("utf-8")
    gain = "        gain: 0.01375 um/V\n"
    assert text.count(gain) == 2
    src = tmp_path / "shin_rolloff.yaml"
    src.write_text(
        text.replace(
            gain, gain + "      thermal_cutoff: 300 Hz\n      calibration_frequency: 1 kHz\n"
        ),
        "utf-8",
    )
    out = tmp_path / "fixed.yaml"
    r = run("fix", src, "--vary", "drive.frequency", "-o", out, "--json")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    best = next(c for c in doc["candidates"] if c["passed"])
    assert best["changes"][0]["field"] == "drive.frequency"
    fixed = load_device(out)
    f_drive = fixed.actuator_sets[0].drive.frequency.to("Hz").magnitude
    f_new = 2.0 * f_drive  # AC drive: actuation frequency doubled
    assert f_new > 2940.0 * 0.5  # into the window, far above the 300 Hz cut-off
    ratio = closed_form_ratio(f_new, 1000.0, 300.0)
    assert ratio < 0.7
    # the exact periodic Δs of the written file, by `betv check`; u_cal = 8 V × 0.01375 µm/V
    rolled = _check(out)
    assert rolled["verdict"] == "pass"
    for sc in rolled["sets"]:
        speed_rule = next(x for x in sc["rules"] if x["id"] == "speed")
        assert speed_rule["message"].endswith("[periodic orbit]")
        periodic_no_rolloff = abs(sc["delta_s"]) * 0.11e-6 * math.cos(math.pi / 4) * f_new
        assert abs(sc["speed_m_s"]) == pytest.approx(periodic_no_rolloff * ratio, rel=1e-12)
    # the same written frequency without the fields: the same Δs (the mode is unchanged)
    plain = tmp_path / "fixed_plain.yaml"
    written = out.read_text("utf-8")
    plain.write_text(re.sub(r"\n *(thermal_cutoff|calibration_frequency): [^\n]*", "", written))
    assert written.count("thermal_cutoff: 300 Hz") == 2 and "thermal_" not in plain.read_text()
    flat = _check(plain)
    assert [x["delta_s"] for x in flat["sets"]] == [x["delta_s"] for x in rolled["sets"]]
    # fix's own report is the rolled-off speed (its value unrounded, the file 4 digits)
    assert abs(best["speed_m_s"]) == pytest.approx(abs(rolled["sets"][0]["speed_m_s"]), rel=2e-3)


# --- bad input -----------------------------------------------------------------------

BASE = (TESTS / "data" / "specs" / "valid_base.yaml").read_text("utf-8")
ANCHOR = "      alpha: 0.1\n"  # line 18 of valid_base.yaml; new lines start at 19
A = "actuator_sets[0].actuator."

BAD = {
    "cutoff_zero": (
        "thermal_cutoff: 0 Hz\ncalibration_frequency: 200 Hz",
        [(19, 23, A + "thermal_cutoff", "must be > 0 Hz, got 0 Hz")],
    ),
    "cutoff_negative": (
        "thermal_cutoff: -1 kHz\ncalibration_frequency: 200 Hz",
        [(19, 23, A + "thermal_cutoff", "must be > 0 Hz, got -1 kHz")],
    ),
    "tau_zero": (
        "thermal_time_constant: 0 ms\ncalibration_frequency: 200 Hz",
        [(19, 30, A + "thermal_time_constant", "must be > 0 s, got 0 ms")],
    ),
    "both": (
        "thermal_cutoff: 1 kHz\nthermal_time_constant: 0.2 ms\ncalibration_frequency: 200 Hz",
        [(20, 30, A + "thermal_time_constant", "give 'thermal_cutoff' or this, not both")],
    ),
    "no_calibration_frequency": (
        "thermal_cutoff: 1 kHz",
        [(19, 23, A + "thermal_cutoff", "needs 'calibration_frequency' too")],
    ),
    "no_calibration_frequency_tau": (
        "thermal_time_constant: 0.2 ms",
        [(19, 30, A + "thermal_time_constant", "needs 'calibration_frequency' too")],
    ),
    "calibration_frequency_alone": (
        "calibration_frequency: 200 Hz",
        [(19, 30, A + "calibration_frequency", "only applies with 'thermal_cutoff'")],
    ),
    "cutoff_in_seconds": (
        "thermal_cutoff: 1 ms\ncalibration_frequency: 200 Hz",
        [(19, 23, A + "thermal_cutoff", "wrong dimension: 1 ms has [time]")],
    ),
    "tau_in_hertz": (
        "thermal_time_constant: 1 kHz\ncalibration_frequency: 200 Hz",
        [(19, 30, A + "thermal_time_constant", "expected dimension [time]")],
    ),
    "calibration_in_microns": (
        "thermal_cutoff: 1 kHz\ncalibration_frequency: 5 um",
        [(20, 30, A + "calibration_frequency", "wrong dimension: 5 um has [length]")],
    ),
    "cutoff_bare_number": (
        "thermal_cutoff: 800\ncalibration_frequency: 200 Hz",
        [(19, 23, A + "thermal_cutoff", "missing unit: got the bare number 800")],
    ),
    # a calibration where the stroke was already cut > 100×: f_cal/f_c = 90 kHz/800 Hz = 112.5
    "calibration_far_above_cutoff": (
        "thermal_cutoff: 800 Hz\ncalibration_frequency: 90 kHz",
        [(20, 30, A + "calibration_frequency", "is 112× the thermal cut-off 800 Hz")],
    ),
    # f_c = 1/(2π·0.2 ms) = 795.77 Hz
    "calibration_far_above_tau_cutoff": (
        "thermal_time_constant: 0.2 ms\ncalibration_frequency: 1 GHz",
        [(20, 30, A + "calibration_frequency", "the thermal cut-off 795.8 Hz")],
    ),
    "calibration_zero": (
        "thermal_cutoff: 800 Hz\ncalibration_frequency: 0 Hz",
        [(20, 30, A + "calibration_frequency", "must be > 0 Hz")],
    ),
    "cutoff_infinite": (
        "thermal_cutoff: inf Hz\ncalibration_frequency: 200 Hz",
        [(19, 23, A + "thermal_cutoff", "must be finite")],
    ),
    # a subnormal cut-off (H(f_act) would underflow to 0): refused at itself, outside
    # the load-time range of a frequency (limits.QUANTITY_RANGE), no NaN
    "cutoff_subnormal": (
        "thermal_cutoff: 1e-320 Hz\ncalibration_frequency: 200 Hz",
        [(19, 23, A + "thermal_cutoff", "1e-320 Hz is outside 0.001 Hz to 1e+12 Hz")],
    ),
    # the smallest cut-off the range takes: f_cal/f_c = 2e5, refused at f_cal
    "cutoff_far_below": (
        "thermal_cutoff: 1 mHz\ncalibration_frequency: 200 Hz",
        [(20, 30, A + "calibration_frequency", "is 2e+05× the thermal cut-off 0.001 Hz")],
    ),
}


def _bad_file(tmp_path: Path, name: str) -> Path:
    lines = "".join(f"      {ln}\n" for ln in BAD[name][0].splitlines())
    f = tmp_path / f"{name}.yaml"
    f.write_text(BASE.replace(ANCHOR, ANCHOR + lines), "utf-8")
    return f


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_roll_off_input_names_file_line_and_field(name, tmp_path):
    f = _bad_file(tmp_path, name)
    with pytest.raises(SpecError) as exc:
        derive_file(f)
    issues = exc.value.issues
    expected = BAD[name][1]
    assert len(issues) == len(expected), [str(i) for i in issues]
    for issue, (line, col, field, fragment) in zip(issues, expected, strict=True):
        assert issue.location.file == str(f)
        assert (issue.location.line, issue.location.col) == (line, col), str(issue)
        assert issue.field == field, str(issue)
        assert fragment in issue.message, str(issue)


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_roll_off_input_is_exit_2_without_traceback(name, tmp_path):
    f = _bad_file(tmp_path, name)
    for cmd in (["check", f], ["report", f, "-o", tmp_path / "out", "--no-pdf", "-q"]):
        r = run(*cmd)
        assert r.exit_code == 2, r.output
        assert r.stdout == "" and "Traceback" not in r.stderr
        assert r.stderr.startswith(f"error: {f}")
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


def test_schema_documents_the_fields():
    schema = json.loads(run("schema").stdout)
    props = schema["$defs"]["Actuator"]["properties"]
    assert "cut-off" in props["thermal_cutoff"]["description"]
    assert "τ_th" in props["thermal_time_constant"]["description"]
    assert "required with a thermal cut-off" in props["calibration_frequency"]["description"]
    assert "H(f) = 1/sqrt(1 + (f/f_c)²)" in schema["$defs"]["Actuator"]["description"]
