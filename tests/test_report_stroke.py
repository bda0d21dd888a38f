"""The report of a drawn-only device: u(V) and u(f) of the stroke predicted from the drawing.

Sources: the stroke at the device's voltage against ``betv check --json``'s
``derived.drawn.stroke_m`` (a second path: the check's derivation,
:func:`betvdesign.nondim.stroke.drawn_stroke`); the melting voltage against the
electrothermal model's own peak temperature just below and above it; the bisection
against a closed form; the u(f) curve against ``u_static/2·modal_gain`` of the modes;
byte-reproducibility by two independent builds.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from test_drawn_stroke import drawn_only
from test_report import expected_figures, text_of
from typer.testing import CliRunner

from betvdesign.cli import app
from betvdesign.model.electrothermal import electrothermal, modal_gain
from betvdesign.nondim.actuator import frame_geometry
from betvdesign.nondim.device import derive
from betvdesign.nondim.stroke import thermal_material
from betvdesign.output.siformat import format_si
from betvdesign.report import ReportOptions, build_report, prepare, render_html
from betvdesign.report import thermal as report_thermal
from betvdesign.report.analysis import Missing, Piece
from betvdesign.spec.loader import load_device

#: Few orbits: the tests are about the stroke's figures, not the slider's sweeps.
TINY = ReportOptions(
    regime_points=5, robustness_points=3, map_points=3, frequency_points=5, full=True
)
runner = CliRunner()


@pytest.fixture(scope="module")
def device(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return drawn_only(tmp_path_factory.mktemp("drawn"))


@pytest.fixture(scope="module")
def html(device: Path) -> str:
    return render_html(build_report(prepare(device), options=TINY))


@pytest.fixture(scope="module")
def sweep(device: Path) -> report_thermal.StrokeSweep:
    der = derive(load_device(device))
    return report_thermal.stroke_sweep(der.spec, der.sets[0])


def test_the_report_shows_u_of_v_and_u_of_f(html: str) -> None:
    """Both figures are drawn (SVG, no 'Not drawn'), their captions name the model, the
    process and that nothing is fitted; the speed-frequency caption uses the drawing's
    roll-off instead of saying the device gives none."""
    text = text_of(html)
    for title, key in (
        ("Predicted stroke against drive voltage", "s1-stroke-uv"),
        ("Predicted stroke against actuation frequency", "s1-stroke-uf"),
    ):
        assert title in text
        block = html.split(f'id="fig-{key}"', 1)[1].split("</figure>", 1)[0]
        assert "<svg" in block and "Not drawn" not in block
        cap = text.split(title, 1)[1].split("Figure ", 1)[0]
        assert "nothing is fitted" in cap and "process polymumps" in cap, cap
        assert "electrothermal model" in cap
    assert "Not drawn:" not in text.split("4. Figures", 1)[1].split("5. Model adequacy")[0]
    assert "gives no thermal cut-off" not in text
    assert "the drawing's thermal roll-off" in text
    assert "Mean speed against actuation frequency, with thermal roll-off" in text
    assert "not a calibration u(V)" not in text
    assert "Speeds with the stroke predicted from the drawing at f_act" in text


def test_a_coupled_verdict_says_which_figures_are_decoupled(device: Path, html: str) -> None:
    """The drawn-only device's check (the CLI's JSON: its own path) takes the coupled
    head's answer; the report's verdict is the same, and the report says so under the
    set's figures and names the figures that still solve the paper's decoupled springs."""
    r = runner.invoke(app, ["check", str(device), "--json", "--no-advice"])
    assert r.exit_code in (0, 1), r.output
    ((s,),) = [d["sets"] for d in json.loads(r.output)["devices"]]
    assert s["model"] == "coupled"
    text = text_of(html)
    assert "decoupled model: betv check uses the coupled head for this set" in text
    assert "robustness" in text.split("uses the coupled head for this set", 1)[1][:400]
    assert f"Predicted mode {s['mode']}" in text  # the report's verdict is the check's


def test_the_stroke_at_the_device_voltage_is_the_checks(
    device: Path, sweep: report_thermal.StrokeSweep, html: str
) -> None:
    """The u(V) curve at the device's V equals ``derived.drawn.stroke_m`` of
    ``betv check --json`` (the check's own derivation), exactly; the caption prints it."""
    r = runner.invoke(app, ["check", str(device), "--json", "--no-advice"])
    assert r.exit_code in (0, 1), r.output
    drawn = json.loads(r.stdout)["devices"][0]["sets"][0]["derived"]["drawn"]
    i = sweep.device_index
    assert sweep.volts[i] == sweep.device_v == 9.0  # drawn_only's drive.voltage
    assert float(sweep.stroke_m[i]) == drawn["stroke_m"]
    assert float(sweep.t_max_k[i]) == pytest.approx(drawn["t_max_k"], rel=1e-12)
    cap = text_of(html).split("Predicted stroke against drive voltage", 1)[1]
    assert f"u = {format_si(drawn['stroke_m'], 'm')}" in cap


def test_the_melting_voltage_is_where_t_max_crosses_the_melting_point(
    device: Path, sweep: report_thermal.StrokeSweep
) -> None:
    """T_max of the electrothermal model just below the bisected voltage is under the
    melting point and just above it is over; the curve ends there (the device's V below)."""
    spec = load_device(device)
    aset = spec.actuator_sets[0]
    g, mat = frame_geometry(spec, aset), thermal_material(spec, aset)
    v = sweep.melting_v
    assert electrothermal(g, mat, v * (1 - 1e-6)).t_max < mat.melting_temperature
    assert electrothermal(g, mat, v * (1 + 1e-6)).t_max > mat.melting_temperature
    assert sweep.melting_k == mat.melting_temperature
    assert sweep.volts[0] == 0.0 and sweep.volts[-1] == v > sweep.device_v
    assert np.all(np.diff(sweep.t_max_k) > 0)
    assert np.all(sweep.t_max_k[:-1] < mat.melting_temperature)
    assert sweep.t_max_k[-1] >= mat.melting_temperature


def test_the_onset_voltage_is_where_t_max_crosses_the_deformation_onset(
    device: Path, sweep: report_thermal.StrokeSweep, html: str
) -> None:
    """The process's onset of plastic deformation (1063 K) is crossed between the bisected
    voltage's two sides on the electrothermal model, below the melting voltage, and the
    caption names it."""
    spec = load_device(device)
    aset = spec.actuator_sets[0]
    g, mat = frame_geometry(spec, aset), thermal_material(spec, aset)
    assert sweep.onset_k == 1063.0
    v = sweep.onset_v
    assert v is not None and v < sweep.melting_v
    assert electrothermal(g, mat, v * (1 - 1e-6)).t_max < 1063.0
    assert electrothermal(g, mat, v * (1 + 1e-6)).t_max > 1063.0
    assert v in sweep.volts
    cap = text_of(html).split("Predicted stroke against drive voltage", 1)[1]
    assert f"onset of plastic deformation 1063 K at {v:.4g} V" in cap


def test_u_of_f_is_the_modal_roll_off(device: Path, sweep: report_thermal.StrokeSweep) -> None:
    """u(f) = u_static/2·G(f) with G = modal_gain of the device's modes (heating at f_act),
    the device's own point on it."""
    der = derive(load_device(device))
    st = der.sets[0].stroke
    assert st is not None
    expected = st.u_static_m / 2 * modal_gain(st.modes, sweep.f_act_hz, "ac")
    np.testing.assert_allclose(sweep.stroke_f_m, expected, rtol=1e-12)
    j = int(np.flatnonzero(sweep.f_act_hz == der.sets[0].scales.f_act_hz)[0])
    assert sweep.stroke_f_m[j] == pytest.approx(st.stroke_m, rel=1e-12)
    assert sweep.f_act_hz[0] < st.f_thermal_hz and sweep.f_act_hz[-1] > 2 * (
        der.sets[0].scales.f_act_hz / der.sets[0].params.varpi
    )


def test_a_device_above_its_melting_voltage_is_drawn_past_it(tmp_path: Path) -> None:
    """A drive above the melting voltage: the curve reaches the device's V, the caption
    says how far above it lies."""
    der = derive(load_device(drawn_only(tmp_path, voltage="12 V")))
    sd = der.sets[0]
    s = report_thermal.stroke_sweep(der.spec, sd)
    assert s.melting_v < 12.0 == s.volts[-1] == s.device_v
    fig = report_thermal.figures("k", der.spec, sd, Piece(value=s))[0]
    assert fig.svg is not None
    assert f"{12.0 / s.melting_v:.3g}× that" in fig.caption


def test_melting_voltage_bisects_a_closed_form() -> None:
    """T(V) = 300 K + 10 K·V²/V²: the melting point 1687 K at sqrt(138.7) V, within the
    bracket's relative width; a T_max that never melts is a clear reason."""
    v, n = report_thermal.melting_voltage(lambda v: 300.0 + 10.0 * v * v, 1687.0, 1.0)
    assert v == pytest.approx(math.sqrt(138.7), rel=2e-9) and v >= math.sqrt(138.7)
    assert n < 60
    with pytest.raises(Missing, match="stays below the melting point"):
        report_thermal.melting_voltage(lambda v: 300.0, 1687.0, 1.0)
    with pytest.raises(Missing, match="not finite"):
        report_thermal.melting_voltage(lambda v: math.inf * 0, 1687.0, 1.0)


def test_the_drawn_report_is_byte_reproducible(device: Path, html: str) -> None:
    """A second, independent build renders byte-identical HTML (figures included)."""
    again = render_html(build_report(prepare(device), options=TINY))
    assert again == html
    assert len(re.findall(r"<figure", html)) == 12 == expected_figures(device)  # 10 + u(V), u(f)


def test_speed_frequency_curves_of_a_drawn_stroke_differ_by_the_modal_gain(device: Path) -> None:
    """Whatever Δs the orbits give, the rolled-off speed over the one with u held at its
    f_act value is G(f)/G(f_act), G the modal gain of the drawing's thermal modes."""
    from betvdesign.report.frequency import FrequencySweep, frequency_grid, speeds

    sd = derive(load_device(device)).sets[0]
    st = sd.stroke
    assert st is not None and not sd.scales.has_rolloff and sd.scales.thermal_modes
    f = frequency_grid(sd.params.varpi, 7) * sd.scales.f_act_hz / sd.params.varpi
    ds = [0.2 + 0.05 * k for k in range(len(f))]
    rolled, constant = speeds(sd, FrequencySweep(f, ds, [""] * len(f), len(f) - 1))
    g_act = modal_gain(st.modes, sd.scales.f_act_hz, "ac")
    cos = math.cos(sd.scales.theta_rad)
    for fk, d, v, v0 in zip(f, ds, rolled, constant, strict=True):
        assert v0 == pytest.approx(d * st.stroke_m * cos * fk, rel=1e-12)
        assert v / v0 == pytest.approx(modal_gain(st.modes, fk, "ac") / g_act, rel=1e-12)


def test_the_plots_draw_the_data_they_are_given() -> None:
    """u(V): the two stroke curves and T_max (twin axis) are the data given, the melting
    voltage a vertical line there; u(f): the curve, the cut-off line and the window band
    0.5·f_v..2·f_v (object-oriented matplotlib, no pyplot)."""
    from matplotlib.figure import Figure

    from betvdesign.plots import stroke_vs_frequency, stroke_vs_voltage

    v = np.linspace(0.0, 4.0, 5)
    u, us, t = 1e-7 * v**2, 4e-7 * v**2, 300.0 + 80.0 * v**2
    ax = Figure().subplots()
    stroke_vs_voltage(v, u, us, t, device_v=2.0, device_stroke_m=4e-7, melting_v=4.0,
                      melting_k=1580.0, ax=ax)  # fmt: skip
    ys = [line.get_ydata() for line in ax.lines]
    np.testing.assert_allclose(ys[0], us * 1e6)  # [µm]
    np.testing.assert_allclose(ys[1], u * 1e6)
    assert any(list(line.get_xdata()) == [4.0, 4.0] for line in ax.lines)
    (twin,) = [a for a in ax.figure.axes if a is not ax]
    np.testing.assert_allclose(twin.lines[0].get_ydata(), t)
    ax = Figure().subplots()
    stroke_vs_voltage(v, u, us, t, device_v=2.0, device_stroke_m=4e-7, melting_v=4.0,
                      melting_k=1580.0, onset_v=3.5, onset_k=1063.0, ax=ax)  # fmt: skip
    assert any(list(line.get_xdata()) == [3.5, 3.5] for line in ax.lines)
    (twin,) = [a for a in ax.figure.axes if a is not ax]
    assert any(list(line.get_ydata()) == [1063.0, 1063.0] for line in twin.lines)
    f = np.geomspace(10.0, 1e6, 9)
    ax = Figure().subplots()
    stroke_vs_frequency(f, 1e-6 / (1 + f / 1e3), f_v_hz=1e4, cutoff_hz=1e3,
                        operating=(2e3, 1e-6 / 3), ax=ax)  # fmt: skip
    np.testing.assert_allclose(ax.lines[0].get_xdata(), f)
    assert any(list(line.get_xdata()) == [1e3, 1e3] for line in ax.lines)
    (band,) = [p for p in ax.patches if p.get_label().startswith("design window")]
    x0, x1 = band.get_x(), band.get_x() + band.get_width()
    assert (x0, x1) == pytest.approx((5e3, 2e4))
