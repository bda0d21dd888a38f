"""Calibration (sources: hand-written CSV files; synthetic data made by the exact solver
at a known u, gain or α; the closed-form weighted least-squares uncertainty; the
snippet merged back into a device file and loaded)."""

import io
import json
import math

import numpy as np
import pytest
from ruamel.yaml import YAML
from typer.testing import CliRunner

from betvdesign.cli import app
from betvdesign.dynamics import periodic_orbit, simulate
from betvdesign.errors import UsageError
from betvdesign.nondim.device import derive_set
from betvdesign.spec.loader import load_device, load_device_text
from betvdesign.studies.calibration import calibrate, fitted
from betvdesign.studies.measurements import Measurements, read_measurements


def test_reads_units_from_the_header(tmp_path):
    f = tmp_path / "s.csv"
    f.write_text("# measured 2026-11\nvoltage [V],speed [um/s],sigma [um/s]\n6,10,1\n8,20.5,2\n")
    m = read_measurements(f, "speed")
    assert np.allclose(m.x, [6, 8]) and np.allclose(m.y, [10e-6, 20.5e-6])
    assert np.allclose(m.sigma, [1e-6, 2e-6])
    f.write_text("time [ms],displacement [nm]\n0.5,100\n1.0,250\n")
    m = read_measurements(f, "displacement")
    assert np.allclose(m.x, [5e-4, 1e-3]) and np.allclose(m.y, [1e-7, 2.5e-7])
    assert m.sigma is None


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("voltage,speed\n1,2\n", ":1: column 1: header 'voltage' must read 'name [unit]'"),
        ("voltage [V],speed [um/s]\n", "needs a header and at least one data row"),
        ("voltage [V],speed [wibble]\n1,2\n", "unknown unit"),
        ("voltage [V],speed [um]\n1,2\n", "speed: unit micrometer is not a um/s unit"),
        ("voltage [V],velocity [um/s]\n1,2\n", "needs columns voltage [V], speed [um/s]"),
        ("voltage [V],speed [um/s]\n1,2\n3\n", ":3: expected 2 fields, got 1"),
        ("voltage [V],speed [um/s]\n1,fast\n", ":2: speed: 'fast' is not a number"),
        ("voltage [V],speed [um/s],sigma [um/s]\n1,2,0\n", "sigma must be > 0"),
    ],
)
def test_bad_csv_names_file_line_and_column(tmp_path, text, fragment):
    f = tmp_path / "bad.csv"
    f.write_text(text)
    with pytest.raises(UsageError) as exc:
        read_measurements(f, "speed")
    assert str(exc.value).startswith(str(f))
    assert fragment in str(exc.value)


# -- fits against synthetic data made by the exact solver ---------------------------


DEVICE = "devices/pull_demo.yaml"  # ϖ = 0.8 (inside the window), linear law 0.015 um/V


def _truth(alpha=None):
    spec = load_device(DEVICE)
    d = derive_set(spec, spec.actuator_sets[0])
    p = (
        d.params
        if alpha is None
        else d.params.__class__(d.params.varpi, alpha, d.params.beta, d.params.kappa)
    )
    res = periodic_orbit(p)
    assert res.success
    # speed per unit amplitude [1/s]: Δs·cosθ·f_act
    return p, d.scales, res.delta_s * math.cos(d.scales.theta_rad) * d.scales.f_act_hz


def _csv(tmp_path, header, cols):
    f = tmp_path / "data.csv"
    lines = [",".join(header)] + [
        ",".join(repr(float(x)) for x in row) for row in zip(*cols, strict=True)
    ]
    f.write_text("\n".join(lines) + "\n")
    return f


def test_linear_gain_recovered_from_noise_free_speeds():
    _, _, a = _truth()
    volts = np.array([4.0, 5.0, 6.0, 7.0, 8.0])
    g_true = 0.0123e-6  # m/V
    data = Measurements("speed", volts, abs(a) * g_true * volts, None, "synthetic")
    r = calibrate(DEVICE, data, law="linear")  # magnitudes, as a lab records them
    g, err = fitted(r, "gain")
    assert r.status == "converged" and r.direction == "-x" and r.warnings == []
    assert r.r_squared == pytest.approx(1.0, abs=1e-12)
    assert g == pytest.approx(g_true, rel=1e-8)
    assert err is not None and err < 1e-8 * g_true  # no noise: no scatter
    assert r.delta_s < 0  # the pull design moves against its impact direction


def test_gain_uncertainty_matches_weighted_least_squares_closed_form():
    """Noisy speeds with given σ: the fit's 1σ equals 1/sqrt(Σ (a·V/σ)²), the closed form
    of a weighted straight line through the origin, and the estimate is within 4σ."""
    _, _, a = _truth()
    rng = np.random.default_rng(11)
    volts = np.linspace(3.0, 9.0, 13)
    g_true = 0.0123e-6
    clean = a * g_true * volts
    sigma = 0.03 * np.abs(clean)
    data = Measurements(
        "speed", volts, clean + sigma * rng.standard_normal(volts.size), sigma, "synthetic"
    )
    r = calibrate(DEVICE, data, law="linear", signed=True)
    g, err = fitted(r, "gain")
    closed = 1.0 / math.sqrt(np.sum((a * volts / sigma) ** 2))
    # goodness of fit, written out: R² about the mean, χ²/dof with the given σ
    resid = a * g * volts - data.y
    assert r.r_squared == pytest.approx(
        1 - np.sum(resid**2) / np.sum((data.y - data.y.mean()) ** 2), rel=1e-9
    )
    assert r.chi2_reduced == pytest.approx(np.sum((resid / sigma) ** 2) / (13 - 1), rel=1e-6)
    assert err == pytest.approx(closed, rel=1e-6)
    assert abs(g - g_true) < 4 * closed


def test_per_voltage_amplitudes_and_measured_snippet():
    _, _, a = _truth()
    volts = np.array([5.0, 5.0, 7.0, 7.0])
    u = {5.0: 0.06e-6, 7.0: 0.1e-6}
    speeds = np.array([a * u[v] for v in volts]) * np.array([1.01, 0.99, 1.02, 0.98])
    r = calibrate(
        DEVICE,
        Measurements("speed", volts, speeds, None, "synthetic"),
        law="per-voltage",
        signed=True,
    )
    assert fitted(r, "u(5 V)")[0] == pytest.approx(0.06e-6, rel=1e-9)
    assert fitted(r, "u(7 V)")[0] == pytest.approx(0.1e-6, rel=1e-9)
    assert "law: measured" in r.snippet and "voltage: 5 V" in r.snippet


def test_amplitude_recovered_from_displacement_against_time():
    """x(t) = s(t/t_s)·u·cosθ from the exact transient at u = 0.083 µm; fit u."""
    p, scales, _ = _truth()
    u_true = 0.083e-6
    t = np.linspace(0.0, 12.0, 40) / scales.f_act_hz  # 12 actuation cycles
    traj = simulate(p, 14, dense=True)
    s = np.asarray(traj.sample(t / scales.time_s))[:, 4]
    x = s * u_true * math.cos(scales.theta_rad)
    data = Measurements("displacement", t, x, None, "synthetic")
    r = calibrate(DEVICE, data, law="per-voltage", signed=True)
    (name,) = r.names
    assert fitted(r, name)[0] == pytest.approx(u_true, rel=1e-8)
    assert "amplitude:" in r.snippet


def test_alpha_recovered_with_the_amplitude_held():
    """law fixed (u from the device): fit α to speeds made at α = 0.36."""
    spec = load_device(DEVICE)
    d = derive_set(spec, spec.actuator_sets[0])
    _, _, a = _truth(alpha=0.36)
    volts = np.array([6.0, 6.0, 6.0])
    speeds = np.full(3, a * d.scales.u_m)
    r = calibrate(
        DEVICE,
        Measurements("speed", volts, speeds, None, "synthetic"),
        law="fixed",
        fit_alpha=True,
        signed=True,
    )
    assert fitted(r, "alpha")[0] == pytest.approx(0.36, rel=1e-6)


def test_cli_snippet_merges_into_the_device_file(tmp_path):
    """betv calibrate writes a YAML snippet; merged into the device it loads and gives u."""
    _, _, a = _truth()
    volts = np.array([4.0, 6.0, 8.0])
    f = _csv(tmp_path, ["voltage [V]", "speed [um/s]"], [volts, a * 0.0123 * volts])
    out = tmp_path / "cal.yaml"
    r = CliRunner().invoke(
        app,
        ["calibrate", DEVICE, str(f), "--law", "linear", "--signed", "-o", str(out), "--json"],
    )
    assert r.exit_code == 0, r.stderr
    payload = json.loads(r.stdout)
    assert payload["parameters"][0]["name"] == "gain"
    yaml = YAML(typ="rt")
    doc = yaml.load(open(DEVICE).read())
    snippet = yaml.load(out.read_text())
    doc["actuator_sets"][0]["actuator"]["calibration"] = snippet["actuator"]["calibration"]
    buf = io.StringIO()
    yaml.dump(doc, buf)
    spec = load_device_text(buf.getvalue(), "merged.yaml")
    gain = spec.actuator_sets[0].actuator.calibration.gain.to("um/V").magnitude
    assert gain == pytest.approx(0.0123, rel=1e-5)


def test_cli_bad_input(tmp_path):
    f = tmp_path / "d.csv"
    f.write_text("voltage [V],speed [um/s]\n6,1\n")
    r = CliRunner().invoke(app, ["calibrate", DEVICE, str(f), "--kind", "acceleration"])
    assert r.exit_code == 2 and "--kind must be speed or displacement" in r.stderr
    r = CliRunner().invoke(app, ["calibrate", DEVICE, str(f), "--law", "cubic"])
    assert r.exit_code == 2 and "unknown law" in r.stderr
    r = CliRunner().invoke(app, ["calibrate", DEVICE, str(f), "-o", str(tmp_path / "no/x.yaml")])
    assert r.exit_code == 2 and "does not exist" in r.stderr
    r = CliRunner().invoke(app, ["calibrate", DEVICE, str(f), "--law", "linear", "--fit-alpha"])
    assert r.exit_code == 2 and "cannot determine 2 parameters" in r.stderr


def test_positive_lab_speeds_fit_a_pull_device_and_the_wrong_sign_is_an_error(tmp_path):
    """Issue 13: positive measured speeds on a pull design gave gain 6.8e-19 um/V,
    "converged". Magnitudes are now read toward the set's travel direction (pull_demo:
    impacts +x, pull -> -x) and give the true gain; the same numbers declared signed, or
    observed moving +x, contradict the model (Δs < 0) and say so (exit 2, no snippet)."""
    _, _, a = _truth()
    volts = np.array([4.0, 6.0, 8.0])
    f = _csv(tmp_path, ["voltage [V]", "speed [um/s]"], [volts, abs(a) * 0.0123 * volts])
    out = tmp_path / "cal.yaml"
    r = CliRunner().invoke(app, ["calibrate", DEVICE, str(f), "--json", "-o", str(out)])
    assert r.exit_code == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["parameters"][0]["value"] == pytest.approx(0.0123e-6, rel=1e-8)
    assert d["direction"] == "-x" and d["r_squared"] == pytest.approx(1.0, abs=1e-12)
    assert "R² 1" in out.read_text()
    for extra in (["--signed"], ["--direction", "+x"]):
        out.unlink(missing_ok=True)
        r = CliRunner().invoke(app, ["calibrate", DEVICE, str(f), "-o", str(out), *extra])
        assert r.exit_code == 2, r.stdout
        assert "data and model disagree in sign" in r.stderr and "Traceback" not in r.stderr
        assert "pull mode" in r.stderr and not out.exists()
    neg = _csv(tmp_path, ["voltage [V]", "speed [um/s]"], [volts, a * 0.0123 * volts])
    r = CliRunner().invoke(app, ["calibrate", DEVICE, str(neg)])
    assert r.exit_code == 2 and "must be a magnitude" in r.stderr and "--signed" in r.stderr
    r = CliRunner().invoke(app, ["calibrate", DEVICE, str(f), "--direction", "up"])
    assert r.exit_code == 2 and "+x or -x" in r.stderr


def test_poor_fit_is_flagged_and_help_shows_the_csv_format():
    """Speeds that fall with voltage cannot follow u = g·V: R² < 0.9 is a warning; the help
    keeps its "[unit]" cells (rich markup used to swallow them)."""
    _, _, a = _truth()
    volts = np.array([4.0, 6.0, 8.0, 10.0])
    speeds = abs(a) * 0.0123e-6 * np.array([10.0, 6.0, 8.0, 4.0])
    r = calibrate(DEVICE, Measurements("speed", volts, speeds, None, "synthetic"))
    assert r.r_squared < 0.9 and any("explains the data poorly" in w for w in r.warnings)
    assert "# warning:" in r.snippet
    h = CliRunner().invoke(app, ["calibrate", "--help"], terminal_width=120)
    assert "voltage [V], speed [um/s]" in h.stdout and "time [ms], displacement [um]" in h.stdout


def test_gain_and_alpha_from_speeds_say_they_cannot_be_told_apart():
    """Issue 21: speeds against voltage with a σ column, fitting the linear gain and α,
    said "no sigma column". With u = g·V the speed is g·V·Δs(α)·cosθ·f_act: g and α
    act alike at every voltage (the Jacobian's columns are parallel), so no uncertainty
    exists, and the warning says so and why, naming the parameters."""
    _, _, a = _truth()
    volts = np.array([4.0, 5.0, 6.0, 7.0, 8.0])
    speeds = a * 0.0123e-6 * volts
    r = calibrate(
        DEVICE,
        Measurements("speed", volts, speeds, np.full(5, 1e-7), "synthetic"),
        law="linear",
        fit_alpha=True,
        signed=True,
    )
    assert r.stderr is None
    text = " ".join(r.warnings)
    assert "no sigma column" not in text
    assert "cannot be told apart" in text and "alpha" in text and "gain" in text
