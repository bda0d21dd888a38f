"""`betv sweep FILE --vary FIELD=LO:HI`: studies of a device's own fields.

Independent truths: each point's exact mode is that of `betv check` on the device file
with the field set to that value (the check's own path, not the sweep's vectorised
derivation); a flip located by bisection has the two modes on either side by the check;
the CSV resumes (a second run computes nothing).
"""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from betvdesign.checks.checker import check_derivation
from betvdesign.cli import app
from betvdesign.nondim.device import derive
from betvdesign.spec.loader import load_device

ROOT = Path(__file__).resolve().parents[1]
DESIGNER = ROOT / "tests/data/designer_pull.yaml"


def run(*args):
    return CliRunner().invoke(app, [str(a) for a in args])


def _check(path: Path, field: str, value: str):
    """``betv check``'s answer over the travel for one value (a map cell's basis: the
    check without its determination re-solves)."""
    spec = load_device(path).replace(field, value)
    res = check_derivation(derive(spec), margin=False, determine=False, adequacy=False)
    return res.sets[0]


def _check_mode(path: Path, field: str, value: str) -> str:
    """The check's mode in the map's words ("no crossing" where the check says the
    slider does not cross its travel within the horizon)."""
    sc = _check(path, field, value)
    return "no crossing" if sc.travel.basis == "no-crossing" else sc.verdict_mode


def test_one_field_speed_modes_and_flips(tmp_path):
    out, fig = tmp_path / "f.csv", tmp_path / "f.svg"
    r = run(
        "sweep",
        DESIGNER,
        "--vary",
        "drive.frequency=1.8kHz:2.2kHz",
        "-n",
        "5",
        "-x",
        "serial",
        "-q",
        "--out",
        out,
        "--figure",
        fig,
        "--json",
    )
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert doc["study"] == "fieldsweep" and doc["points"] == 5
    assert doc["fields"][0]["unit"] == "kHz" and doc["fields"][0]["device_value"] == 2.0
    rows = list(csv.DictReader(out.open()))
    assert [float(r["drive.frequency [kHz]"]) for r in rows] == pytest.approx(
        [1.8, 1.9, 2.0, 2.1, 2.2]
    )
    for row in rows[::2]:
        khz = row["drive.frequency [kHz]"]
        assert row["exact_mode"] == _check_mode(DESIGNER, "drive.frequency", f"{khz} kHz")
        if row["exact_mode"] in ("push", "pull"):
            sc = _check(DESIGNER, "drive.frequency", f"{khz} kHz")
            assert row["basis"] == sc.travel.basis and float(row["speed_m_s"]) != 0.0
            # a magnitude, as the check's JSON speed_m_s; the mode says which way
            assert float(row["speed_m_s"]) == pytest.approx(abs(sc.speed_m_s), rel=1e-12)
    # push below ~1.923 kHz, pull above ~1.925 kHz: between them the speed passes through
    # zero and the slider does not cross its travel within the horizon (every change
    # located, each bracket 0.1 % of the range wide: 0.4 Hz)
    flips = doc["flips"]
    assert [f["below"] for f in flips] == ["push", "no crossing"]
    assert [f["above"] for f in flips] == ["no crossing", "pull"]
    for flip in flips:
        lo, hi = flip["bracket"]
        assert 1.9 < lo < flip["at"] < hi < 2.0 and hi - lo <= 1e-3 * (2.2 - 1.8)
        assert _check_mode(DESIGNER, "drive.frequency", f"{lo!r} kHz") == flip["below"]
        assert _check_mode(DESIGNER, "drive.frequency", f"{hi!r} kHz") == flip["above"]
    assert fig.read_text().startswith("<?xml")
    again = run(
        "sweep",
        DESIGNER,
        "--vary",
        "drive.frequency=1.8kHz:2.2kHz",
        "-n",
        "5",
        "-x",
        "serial",
        "-q",
        "--out",
        out,
        "--json",
    )
    assert json.loads(again.stdout)["computed"] == 0  # resumed


def test_two_fields_map_in_the_fields_units(tmp_path):
    fig = tmp_path / "m.png"
    r = run(
        "sweep",
        DESIGNER,
        "--vary",
        "drive.frequency=1k:4k",
        "--vary",
        "slider.beam_width=5um:45um",
        "-n",
        "4",
        "-x",
        "serial",
        "-q",
        "--figure",
        fig,
        "--json",
    )
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert doc["points"] == 16 and [f["unit"] for f in doc["fields"]] == ["kHz", "µm"]
    assert sum(doc["modes"].values()) == 16 and fig.stat().st_size > 0


@pytest.mark.parametrize(
    ("vary", "words"),
    [
        ("drive.frequency=1:4", "missing unit"),
        ("drive.frequency=4kHz:1kHz", "LO < HI"),
        ("drive.frequency=1kg:2kg", "drive.frequency"),
        ("drive.nonsense=1:2", "not a numeric field"),
        ("drive.frequency", "FIELD=LO:HI"),
    ],
)
def test_bad_input_exit_2(vary, words):
    r = run("sweep", DESIGNER, "--vary", vary, "-x", "serial", "-q")
    assert r.exit_code == 2, r.output
    assert words in r.stderr and "Traceback" not in r.output


def test_dimensionless_sweeps_stay():
    r = run("sweep", "pushpull", "--help")
    assert r.exit_code == 0 and "--varpi" in r.stdout


def test_marks_window_and_subresonances_against_the_files_resonances(tmp_path):
    """Issue 32 item 12: the sub-resonances α·ϖ² = 1/n² lie at f_act = f_h/n. By hand from
    designer_pull's own numbers: f_h = 12 kHz, an AC drive (f_act = 2·f_drive), so the
    drive frequency of order n is 6/n kHz; the window 0.5 ≤ ϖ < 2 with f_v = 8 kHz is
    f_drive = 2–8 kHz. The flips of the pull design at 2 kHz sit just below f_h/3 and are
    named so; the CSV's field column carries its unit; speeds are magnitudes."""
    out, fig = tmp_path / "s.csv", tmp_path / "s.svg"
    args = ("sweep", DESIGNER, "--vary", "drive.frequency=1.1kHz:4kHz", "-n", "30")
    r = run(*args, "-x", "serial", "-q", "--out", out, "--figure", fig, "--json")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    marks = doc["marks"]
    at = {m["n"]: m["at"] for m in marks["subresonances"]}
    assert sorted(at) == [2, 3, 4, 5]
    for n, x in at.items():
        assert x == pytest.approx(6.0 / n, rel=1e-9), n
    ((lo, hi),) = marks["window"]
    assert lo == pytest.approx(2.0, rel=1e-9) and hi == 4.0
    assert marks["undamped_resonance"] == []  # f_h is at 6 kHz of drive, outside the range
    near = [f for f in doc["flips"] if 1.8 < f["at"] < 2.0]
    assert near, doc["flips"]
    for f in near:  # (2·f/12)² within the ratio 1.25 of 1/9, by hand
        assert f["subresonance"] == 3 and 1 / 1.25 < (2 * f["at"] / 12) ** 2 * 9 < 1.25
    header = out.read_text("utf-8").splitlines()[0].split(",")
    assert "drive.frequency [kHz]" in header and "drive.frequency" not in header
    rows = list(csv.DictReader(out.open()))
    assert all(float(r["speed_m_s"]) >= 0 for r in rows if r["speed_m_s"])
    svg = fig.read_text("utf-8")
    assert "f_h/3" in svg and "outside the design window" in svg
    text = run(*args, "-x", "serial", "-q", "--out", out).stdout
    assert "(near f_act = f_h/3, at 2)" in text
    assert "design window 0.5 ≤ ϖ < 2 at drive.frequency: 2–4 kHz" in text


def test_speed_axis_keeps_the_operating_region_readable():
    """A resonance spike of 150 mm/s among ~1 mm/s speeds: the axis turns symmetric-log
    with the operating speeds in its linear part; the same spike inside an undamped
    head's resonance band is greyed and left out of the range (a linear axis)."""
    from betvdesign.plots.fieldsweep import speed_with_modes
    from betvdesign.plots.figure import new_figure

    xs = np.linspace(1.0, 3.0, 21)
    speeds = [150e-3 if i == 10 else 1e-3 * (1 + 0.02 * i) for i in range(21)]
    rows = [
        {"f [kHz]": x, "speed_m_s": v, "exact_mode": "pull", "zeta_h": None}
        for x, v in zip(xs, speeds, strict=True)
    ]
    f = {"field": "f", "column": "f [kHz]", "unit": "kHz", "device_value": 1.5}
    summary = {"fields": [f], "flips": [], "marks": {"window": [[1.0, 3.0]]}}
    _, ax = new_figure()
    speed_with_modes(rows, summary, ax=ax)
    assert ax.get_yscale() == "symlog"
    linthresh = ax.yaxis.get_transform().linthresh
    assert linthresh >= 1e3 * max(v for v in speeds if v < 0.1)  # µm/s: linear part
    summary["marks"]["undamped_resonance"] = [[1.95, 2.05]]
    _, ax = new_figure()
    speed_with_modes(rows, summary, ax=ax)
    assert ax.get_yscale() == "linear" and ax.get_ylim()[1] < 2e3  # µm/s: spike left out


def test_nearest_subresonance_by_hand():
    """1/n² levels: 0.26 is near 1/4; 0.5 lies a ratio 2 from both 1 and 1/4: none."""
    from betvdesign.model.domain import nearest_subresonance

    assert nearest_subresonance([0.26]) == 2
    assert nearest_subresonance([0.5]) is None
    assert nearest_subresonance([0.105, 0.095]) == 3
    assert nearest_subresonance([0.7, 0.95]) == 1


def test_sweep_figures_keep_every_text_inside_and_the_legend_off_the_axes():
    """Issue 32 item 13: the title, labels and legend of both sweep figures lie inside the
    figure and the legend outside the axes (a legend beside the axes clipped the title),
    measured on the rendered figure."""
    from matplotlib.axis import Tick
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.text import Text

    from betvdesign.plots.fieldsweep import fieldsweep_figure

    xs = np.linspace(1.0, 3.0, 9)
    one = [
        {"f [kHz]": x, "speed_m_s": 1e-3, "exact_mode": "pull", "varpi": x / 4, "alpha": 0.3}
        for x in xs
    ]
    f = {"field": "f", "column": "f [kHz]", "unit": "kHz", "device_value": 2.0, "points": 9}
    marks = {"window": [[2.0, 3.0]], "subresonances": [{"n": 3, "at": 2.4}]}
    g = {"field": "g", "column": "g", "unit": "", "device_value": 0.3, "points": 3}
    two = [{**r, "g": a, "alpha": a, "lam": 2.0} for r in one for a in (0.2, 0.3, 0.4)]
    for rows, summary in (
        (one, {"name": "a_long_device_name", "fields": [f], "flips": [], "marks": marks}),
        (two, {"name": "a_long_device_name", "fields": [f, g]}),
    ):
        fig = fieldsweep_figure(rows, summary)
        FigureCanvasAgg(fig).draw()
        r = fig.canvas.get_renderer()
        ticks = {id(x) for tk in fig.findobj(Tick) for x in (tk.label1, tk.label2)}
        page = fig.bbox
        for t in fig.findobj(Text):
            if id(t) in ticks or not t.get_visible() or not t.get_text().strip():
                continue
            e = t.get_window_extent(r)
            assert page.x0 - 1 <= e.x0 and e.x1 <= page.x1 + 1, t.get_text()
            assert page.y0 - 1 <= e.y0 and e.y1 <= page.y1 + 1, t.get_text()
        (ax,) = fig.axes
        legend, box = ax.get_legend().get_window_extent(r), ax.get_window_extent(r)
        assert legend.y1 <= box.y0 or legend.x0 >= box.x1, (legend, box)
