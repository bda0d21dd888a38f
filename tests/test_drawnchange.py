"""Fixes in drawn dimensions through the frame, within the process's rules (issue 30, item 6).

Independent truths: the structure's first in-plane mode by plane-stress FE
(:func:`betvdesign.model.frame_fe.frame_modes`, a second method) moves by the ratio the
drawn change was asked for; the process's minimum width read from the process file; the
window's edge ϖ = 0.5 re-derived at the proposed dimension and at the actuation
frequency the text asks for.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from betvdesign.api import CheckOptions, run_check
from betvdesign.model.frame_fe import frame_modes
from betvdesign.nondim.actuator import frame_geometry
from betvdesign.nondim.device import derive
from betvdesign.spec.loader import load_device
from betvdesign.spec.paths import with_values
from betvdesign.spec.units import ureg
from betvdesign.studies.drawnchange import drawn_reach, floor, in_drawing
from betvdesign.studies.fixfields import parse_vary

ROOT = Path(__file__).resolve().parents[1]
SHIN = ROOT / "devices" / "shin2004.yaml"
PUSH = ROOT / "devices" / "push_demo.yaml"


def _fe_f1(spec) -> float:
    aset = spec.actuator_sets[0]
    g = frame_geometry(spec, aset)
    m = derive(spec).sets[0].springs.m_head_kg
    return frame_modes(g, density=2330.0, head_mass=m).frequencies_hz[0]


def _drawn_only(tmp_path: Path, *, frequency: str | None = None) -> Path:
    text = PUSH.read_text()
    keep = [ln for ln in text.splitlines() if "_resonance" not in ln]
    text = "\n".join(keep)
    proc = ROOT / "betvdesign" / "data" / "processes" / "demo25.yaml"
    text = text.replace("process: demo25", f"process: {proc}")
    if frequency is not None:
        text = text.replace("frequency: 3 kHz", f"frequency: {frequency}")
    p = tmp_path / "drawn_push.yaml"
    p.write_text(text + "\n")
    return p


def test_a_resonance_change_said_in_drawn_dimensions_moves_the_fe_mode_by_its_ratio():
    spec = load_device(SHIN)
    text = in_drawing(spec, "actuator.vertical_resonance", 2.94, 2.94 * 0.7)
    m = re.search(r"flexure length ([\d.]+) µm -> ([\d.]+) µm", text)
    assert m, text
    x0, x = float(m.group(1)), float(m.group(2))
    assert x > x0  # a softer suspension: a longer flexure
    changed = with_values(spec, {"actuator.geometry.flexure_length": x * ureg.um})
    ratio = _fe_f1(changed) / _fe_f1(spec)
    assert ratio == pytest.approx(0.7, rel=0.05)  # FE, not the frame closed form


def test_no_width_is_proposed_below_the_process_minimum():
    spec = load_device(SHIN)
    mn = spec.process.layers["poly1"].min_width.to("um").magnitude
    assert floor(spec, "actuator.geometry.flexure_width")[0] == mn
    text = in_drawing(spec, "actuator.vertical_resonance", 2.94, 1.8)
    # shin2004's flexure is drawn at the minimum already: it cannot be narrowed
    assert f"flexure width cannot: at {mn:g} µm" in text
    for w in re.findall(r"width [\d.]+ µm -> ([\d.]+) µm", text):
        assert float(w) >= mn
    for v in parse_vary(spec, []):
        if v.field.startswith("actuator.geometry.") and v.field.endswith("_width"):
            assert v.lo >= mn


def test_no_drawing_no_drawn_meaning():
    spec = load_device(SHIN)
    bare = spec.model_copy(
        update={
            "actuator_sets": [
                s.model_copy(update={"actuator": s.actuator.model_copy(update={"geometry": None})})
                for s in spec.actuator_sets
            ]
        }
    )
    assert in_drawing(bare, "actuator.vertical_resonance", 2.94, 1.8) == ""
    assert in_drawing(spec, "drive.frequency", 500, 800) == ""


def test_a_drawn_only_device_is_told_the_drawn_change_that_reaches_the_window(tmp_path):
    src = _drawn_only(tmp_path)
    res = run_check(src, CheckOptions(advice=False))
    text = drawn_reach(res)
    m = re.search(r"(\w[\w ]*?) ([\d.]+) µm -> ([\d.]+) µm brings ϖ", text)
    assert m, text
    field = "actuator.geometry." + m.group(1).split(":")[-1].strip().replace(" ", "_")
    spec = load_device(src)
    at = with_values(spec, {field: float(m.group(3)) * ureg.um})
    assert derive(at).sets[0].params.varpi == pytest.approx(0.5, rel=2e-3)
    # the check's window fix carries it
    advised = run_check(src, CheckOptions())
    window = next(r for r in advised.rules if r.id == "frequency-window")
    assert "brings ϖ" in window.fix


def test_unreachable_window_says_the_nearest_and_what_must_change(tmp_path):
    src = _drawn_only(tmp_path, frequency="100 Hz")  # ϖ ~ 0.002: far below the window
    res = run_check(src, CheckOptions(advice=False))
    text = drawn_reach(res)
    assert text.startswith("no drawn dimension brings ϖ"), text
    near = float(re.search(r"the nearest is ϖ = ([\d.e-]+)", text).group(1))
    assert 0 < near < 0.5
    f_act = float(re.search(r"f_act ≥ ([\d.]+) kHz", text).group(1)) * 1e3
    spec = load_device(src)  # the drive (AC: f_act = 2 f) at that f_act reaches the edge
    at = with_values(spec, {"drive.frequency": f_act / 2 * ureg.Hz})
    assert derive(at).sets[0].params.varpi == pytest.approx(0.5, rel=1e-3)
