"""Process files as data (issue 23, slice 1) and the process's design rules in `betv check`
(slice 2). Sources: the PolyMUMPs Design Handbook values in the shipped file (2 µm Poly1,
2 µm minimum width and spacing, etch holes beyond 30 µm); hand-written bad files whose
line and column are known."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from typer.testing import CliRunner

from betvdesign.checks.process_rules import process_rules
from betvdesign.cli import app
from betvdesign.errors import SpecError
from betvdesign.spec.loader import load_device, load_device_text, load_process
from betvdesign.spec.process import SHIPPED_DIR, shipped_processes

DEVICES = Path(__file__).resolve().parents[1] / "devices"
POLYMUMPS = SHIPPED_DIR / "polymumps.yaml"
#: The published device as shipped (it names PolyMUMPs and draws its actuators) ...
SHIN_SHIPPED = (DEVICES / "shin2004.yaml").read_text()
#: ... and without process and actuator geometry (as before issue 23).
SHIN = re.sub(
    r"\n *geometry:\n( {8}[a-z_]+: [^\n]*\n)+",
    "\n",
    re.sub(r"\n *# The drawn hot/cold[^\n]*\n *# compared[^\n]*", "", SHIN_SHIPPED),
)
SHIN = re.sub(r"\nprocess: polymumps[^\n]*", "", SHIN)


def shin() -> str:
    """shin2004 naming the polymumps process (without actuator geometry)."""
    return SHIN.replace("material: polysilicon", "process: polymumps\nmaterial: polysilicon", 1)


def sub(old: str, new: str, text: str | None = None) -> str:
    text = shin() if text is None else text
    assert old in text, old
    return text.replace(old, new, 1)


def issues(text: str, name: str = "dev.yaml") -> list[str]:
    with pytest.raises(SpecError) as err:
        load_device_text(text, name)
    return [str(i) for i in err.value.issues]


# --- slice 1: process files ---------------------------------------------------------------


def test_shipped_polymumps_has_the_handbook_values():
    assert "polymumps" in shipped_processes()
    p = load_process(POLYMUMPS)
    poly1 = p.structural()
    assert p.default_structural == "poly1"
    assert poly1.thickness.to("um").magnitude == pytest.approx(2.0)
    assert p.structural("poly2").thickness.to("um").magnitude == pytest.approx(1.5)
    assert poly1.min_width.to("um").magnitude == 2.0
    assert poly1.min_spacing.to("um").magnitude == 2.0
    assert poly1.max_unreleased_width.to("um").magnitude == 30.0
    assert poly1.gds.pair == (45, 0)
    assert p.by_gds((44, 0)) == "hole1"
    assert p.layers[p.annotation].role == "annotation"
    # a value listed as unsourced says so wherever it is cited
    assert "NOT sourced" in p.cite("layers.poly1.youngs_modulus")
    assert "Handbook" in p.cite("layers.poly1.thickness")


def _process_text(**subs: str) -> str:
    text = POLYMUMPS.read_text()
    for old, new in subs.items():
        assert old in text, old
        text = text.replace(old, new, 1)
    return text


@pytest.mark.parametrize(
    ("old", "new", "line_of", "expect"),
    [
        ("gds: 45/0", "gds: 45-0", "gds: 45-0", "LAYER/DATATYPE"),
        ("gds: 44/0", "gds: 45/0", "    gds: 45/0\n    role: hole", "also layer 'poly1'"),
        ("thickness: 2.0 um", "thickness: 2.0 kg", "thickness: 2.0 kg", "wrong dimension"),
        ("layer: hole1,", "layer: holeX,", "release_holes: {layer: holeX", "no layer 'holeX'"),
        ("  - grid ", "  - gridd ", "- gridd", "not a value of this file"),
        ("min_spacing: 2 um\n    max_unreleased_width: 30 um\n    release_holes: {layer: hole1",
         "max_unreleased_width: 30 um\n    release_holes: {layer: hole1", "  poly1:",
         "needs min_spacing"),
    ],
)  # fmt: skip
def test_bad_process_file_names_file_line_and_column(tmp_path, old, new, line_of, expect):
    text = _process_text(**{old: new})
    f = tmp_path / "proc.yaml"
    f.write_text(text)
    with pytest.raises(SpecError) as err:
        load_process(f)
    msg = str(err.value)
    assert expect in msg
    line = text[: text.index(line_of)].count("\n") + 1
    assert f"{f}:{line}:" in msg or f"{f}:{line + 1}:" in msg, msg


def test_device_names_its_process_by_name_or_relative_path(tmp_path):
    own = tmp_path / "procs" / "mine.yaml"
    own.parent.mkdir()
    own.write_text(_process_text(**{"name: polymumps": "name: mine"}))
    dev = tmp_path / "dev.yaml"
    dev.write_text(shin().replace("process: polymumps", "process: procs/mine.yaml"))
    assert load_device(dev).process.name == "mine"
    assert load_device_text(shin(), "x.yaml").process.name == "polymumps"


def test_unknown_or_broken_process_is_reported_at_the_process_line(tmp_path):
    text = shin().replace("process: polymumps", "process: nosuch")
    (msg,) = issues(text)
    line = text[: text.index("process:")].count("\n") + 1
    assert msg.startswith(f"dev.yaml:{line}:10: process: ")
    assert "no shipped process 'nosuch'" in msg and "polymumps" in msg
    bad = tmp_path / "bad.yaml"
    bad.write_text(_process_text(**{"gds: 45/0": "gds: 45-0"}))
    dev = tmp_path / "dev.yaml"
    dev.write_text(shin().replace("process: polymumps", "process: bad.yaml"))
    with pytest.raises(SpecError) as err:
        load_device(dev)
    msg = str(err.value)
    assert f"{dev}:{line}:10: process: " in msg and f"{bad}:" in msg and "LAYER/DATATYPE" in msg


def test_a_beam_below_one_nanometre_is_refused_at_its_line():
    """Issue 23: a 1e-30 µm beam passed `betv check`; it is not a dimension at all."""
    for width, why in (("0.5 nm", "below 1 nm"), ("1e-30 um", "outside 1e-12 m to 1 m")):
        text = SHIN.replace("beam_width: 5 um", f"beam_width: {width}")
        (msg,) = issues(text)
        line = text[: text.index("beam_width:")].count("\n") + 1
        assert msg.startswith(f"dev.yaml:{line}:15: slider.beam_width: ")
        assert why in msg


def test_layer_names_must_be_structural_layers_of_the_process():
    text = sub("  travel_range: 40 um", "  travel_range: 40 um\n  layer: hole1")
    (msg,) = issues(text)
    assert "slider.layer" in msg and "no structural layer 'hole1'" in msg
    (msg,) = issues(SHIN.replace("  travel_range: 40 um", "  travel_range: 40 um\n  layer: poly1"))
    assert "slider.layer" in msg and "only applies with 'process'" in msg


def test_whatif_keeps_the_process():
    spec = load_device_text(shin(), "x.yaml")
    again = spec.replace("slider.beam_width", "6 um")
    assert again.process == spec.process


# --- slice 2: process rules ---------------------------------------------------------------


def rules(text: str) -> dict:
    return {r.id: r for r in process_rules(load_device_text(text, "x.yaml"))}


def test_published_device_passes_the_polymumps_rules():
    got = rules(shin())
    assert set(got) == {
        "process.thickness",
        "process.material",
        "process.min-width",
        "process.min-spacing",
        "process.release",
        "geometry.beam-aspect",
    }
    assert all(r.passed for r in got.values())
    assert "Handbook" in got["process.min-width"].source


def test_narrow_beam_fails_min_width_with_a_fix():
    r = rules(sub("beam_width: 5 um", "beam_width: 1.5 um"))["process.min-width"]
    assert not r.passed and r.severity == "error"
    assert r.value == pytest.approx(1.5e-6)
    assert "slider beam 1.5 µm < 2 µm (slider.beam_width)" in r.message
    assert "widen" in r.fix


def test_narrow_arm_gap_fails_min_spacing():
    """The Handbook's 2 µm minimum spacing: a 1.5 µm arm gap fails (both sets of the
    published device draw the same gap; listed once, the right set first); the value is
    the smallest gap, the hot arm to the cold arm (the flexure sits farther out)."""
    text = SHIN_SHIPPED.replace("gap: 3 um", "gap: 1.5 um")
    r = rules(text)["process.min-spacing"]
    assert not r.passed and r.severity == "error"
    assert r.value == pytest.approx(1.5e-6)
    assert r.message.startswith("gaps below the process's minimum spacing: set right: hot arm")
    assert "1.5 µm < 2 µm (actuator_sets[0].actuator.geometry.gap)" in r.message
    assert "set left" not in r.message
    assert r.threshold == "gap >= minimum spacing (poly1: 2 µm)"
    ok = rules(SHIN_SHIPPED)["process.min-spacing"]
    assert ok.passed and ok.value == pytest.approx(3e-6)
    assert "smallest: set right: hot arm to cold arm 3 µm" in ok.message


def test_wide_plate_needs_release_holes():
    """Issue 23: a 45 µm-wide plate cannot be released without etch holes."""
    r = rules(sub("beam_width: 5 um", "beam_width: 45 um"))["process.release"]
    assert not r.passed and r.severity == "warning"
    assert "45 µm > 30 µm (4 µm holes at 25.2 µm pitch take 2.5% of its mass" in r.message
    assert "betv layout" in r.fix


def test_thickness_must_be_the_layers():
    r = rules(sub("beam_thickness: 2 um", "beam_thickness: 2.5 um"))["process.thickness"]
    assert not r.passed and r.severity == "error"
    assert "slider beam 2.5 µm" in r.message and "poly1: 2 µm" in r.message
    # the same beam on poly2 (1.5 um): wrong the other way; on a 2.5 um layer it passes
    text = sub("  travel_range: 40 um", "  travel_range: 40 um\n  layer: poly2")
    assert not rules(text)["process.thickness"].passed


def test_material_density_is_compared_with_the_layer():
    text = sub(
        "material: polysilicon",
        "material: {name: poly-ish, density: 2000 kg/m^3}",
    )
    r = rules(text)["process.material"]
    assert not r.passed and r.severity == "warning" and "2000 kg/m³" in r.message


def test_devices_without_a_process_get_only_the_note_that_its_rules_were_not_checked():
    (r,) = process_rules(load_device_text(SHIN, "x.yaml"))
    assert (r.id, r.severity, r.passed) == ("process", "warning", False)
    assert "not checked" in r.message and "process: polymumps" in r.fix


def run(*args: str):
    return CliRunner().invoke(app, list(args))


@pytest.mark.slow
def test_cli_check_fails_a_narrow_beam_with_message(tmp_path):
    f = tmp_path / "narrow.yaml"
    f.write_text(sub("beam_width: 5 um", "beam_width: 1 um"))
    res = run("check", "--json", "--no-adequacy", str(f))
    assert res.exit_code == 1, res.output
    doc = json.loads(res.stdout)
    (dev,) = doc["devices"] if "devices" in doc else [doc]
    ids = {r["id"]: r for r in dev["rules"]}
    assert ids["process.min-width"]["passed"] is False
    assert "1 µm < 2 µm" in ids["process.min-width"]["message"]


def test_cli_check_refuses_a_sub_nanometre_beam(tmp_path):
    f = tmp_path / "tiny.yaml"
    f.write_text(SHIN.replace("beam_width: 5 um", "beam_width: 0.5 nm"))
    res = run("check", str(f))
    assert res.exit_code == 2
    assert "below 1 nm" in res.stderr and "Traceback" not in res.output


# --- concrete fixes of the process rules (issue 32, item 10) ----------------------------------


def _check_json(path: Path) -> dict:
    res = run("check", "--json", "--no-adequacy", str(path))
    assert res.exit_code in (0, 1), res.output
    doc = json.loads(res.stdout)
    (dev,) = doc["devices"] if "devices" in doc else [doc]
    return dev


@pytest.mark.slow
def test_a_narrow_beam_gets_the_geometry_fix_of_the_process(tmp_path):
    """A 0.5 µm beam in a PolyMUMPs device: 'widen slider.beam_width to ≥ 2 µm', the 2 µm
    read from the process file itself, not a search of other fields; the same fix in the
    text output."""
    import yaml

    poly1 = yaml.safe_load(POLYMUMPS.read_text())["layers"]["poly1"]
    f = tmp_path / "thin.yaml"
    f.write_text(SHIN_SHIPPED.replace("beam_width: 5 um", "beam_width: 0.5 um"))
    rule = {r["id"]: r for r in _check_json(f)["rules"]}["process.min-width"]
    width = poly1["min_width"].replace(" um", " µm")
    want = f"widen slider.beam_width to ≥ {width} (process.min-width)"
    assert rule["fix"].startswith(want), rule["fix"]
    assert "no single field" not in rule["fix"]
    text = run("check", "--no-adequacy", str(f)).stdout
    block = text[text.index("FAIL process.min-width") :]
    assert "fix: widen slider.beam_width to ≥ 2 µm" in block.split("FAIL", 2)[1]


@pytest.mark.slow
def test_a_wrong_thickness_is_set_to_the_process_film(tmp_path):
    import yaml

    poly1 = yaml.safe_load(POLYMUMPS.read_text())["layers"]["poly1"]
    thickness = poly1["thickness"].replace(".0 um", " µm").replace(" um", " µm")
    f = tmp_path / "thick.yaml"
    f.write_text(SHIN_SHIPPED.replace("beam_thickness: 2 um", "beam_thickness: 2.5 um"))
    rule = {r["id"]: r for r in _check_json(f)["rules"]}["process.thickness"]
    assert rule["fix"].startswith(f"set slider.beam_thickness to {thickness} (poly1)"), rule["fix"]


def test_a_device_without_a_process_is_told_its_rules_were_not_checked(tmp_path):
    f = tmp_path / "free.yaml"
    f.write_text(SHIN)
    dev = _check_json(f)
    rule = {r["id"]: r for r in dev["rules"]}["process"]
    assert rule["severity"] == "warning" and "not checked" in rule["message"]
    assert "process" not in dev["failed"]  # a note: the verdict is the rules'
    assert "process: no process named" in run("check", "--no-adequacy", str(f)).stdout
