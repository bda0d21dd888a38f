"""Fix writes layout (issue 23, slice 6), and the issue's closing scenario: a layout drawn
by `betv layout`, edited as a designer would in KLayout (here with klayout.db: the
flexure widened by 1 µm), checked, fixed and back as a GDS.

Independent truths: KLayout writes the edited layout; the fixed layout is read back by
the same reader as any other and must pass `betv check`; the fix of the published
device's YAML file (drive frequency 500 Hz -> 772.1 Hz: the bisected boundary 735.4 Hz
plus the 5 % margin) is unchanged by drawing it.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from typer.testing import CliRunner

from betvdesign.cli import app
from betvdesign.nondim.device import derive
from betvdesign.spec.loader import load_device, load_device_text
from betvdesign.studies.fixfields import parse_vary

pytest.importorskip("gdstk")
from betvdesign.layout.extract import extract

DEVICES = Path(__file__).resolve().parents[1] / "devices"


def run(*args: str):
    return CliRunner().invoke(app, list(args))


def _widen_flexure(kdb, src: Path, dst: Path, by_um: float) -> None:
    """The designer's edit in KLayout: the flexure (40 × 2.5 µm, the narrow box at the
    actuator's root) widened by ``by_um``, centred, in the actuator cell."""
    ly = kdb.Layout()
    ly.read(str(src))
    poly1 = ly.layer(45, 0)
    done = 0
    for cell in ly.each_cell():
        if not cell.name.startswith("ACT_"):
            continue
        for shape in cell.each_shape(poly1):
            box = shape.polygon.bbox()
            if box.left == 0 and box.width() == 40000 and box.height() == 2500:
                d = round(by_um * 1000 / 2)
                shape.polygon = kdb.Polygon(kdb.Box(box.left, box.bottom - d, box.right,
                                                    box.top + d))  # fmt: skip
                done += 1
    assert done == 1
    ly.write(str(dst))


def test_draw_edit_in_klayout_check_fix_and_back(tmp_path):
    kdb = pytest.importorskip("klayout.db")
    drawn, edited, fixed = (tmp_path / n for n in ("shin.gds", "edited.gds", "fixed.gds"))
    assert run("layout", str(DEVICES / "shin2004.yaml"), "-o", str(drawn)).exit_code == 0
    _widen_flexure(kdb, drawn, edited, 1.0)
    res = run("check", "--json", "--verbose", "--no-adequacy", str(edited))
    assert res.exit_code == 1  # the published data: below the frequency window
    dev = json.loads(res.stdout)["devices"][0]
    w_flex = next(r for r in dev["sets"][0]["record"] if r["symbol"] == "w_flex")
    assert w_flex["value"] == "3.5 um"
    res = run("fix", str(edited), "-o", str(fixed), "--json")
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert doc["layout"] == str(fixed)
    best = doc["candidates"][0]["changes"][0]
    of_yaml = json.loads(run("fix", str(DEVICES / "shin2004.yaml"), "--json").stdout)
    assert best == of_yaml["candidates"][0]["changes"][0]
    assert best["field"] == "drive.frequency" and best["to"].endswith(" Hz")
    assert run("check", "--no-adequacy", str(fixed)).exit_code == 0
    back = extract(fixed).spec
    assert all(s.actuator.geometry.flexure_width.to("um").magnitude == pytest.approx(3.5)
               for s in back.actuator_sets)  # fmt: skip
    assert back.actuator_sets[0].drive.frequency.to("Hz").magnitude == pytest.approx(
        float(best["to"].split()[0]), abs=1e-9
    )


def test_fix_yaml_with_layout(tmp_path):
    out = tmp_path / "fixed.gds"
    res = run("fix", str(DEVICES / "shin2004.yaml"), "--layout", str(out))
    assert res.exit_code == 0, res.output
    assert f"wrote {out} (betv check {out} passes)" in res.output
    # the layout carries the value betv fix proposes (its first passing candidate)
    best = json.loads(run("fix", str(DEVICES / "shin2004.yaml"), "--json").stdout)
    (change,) = best["candidates"][0]["changes"]
    assert change["field"] == "drive.frequency" and change["to"].endswith(" Hz")
    drawn = extract(out).spec.actuator_sets[1].drive.frequency.to("Hz").magnitude
    assert drawn == pytest.approx(float(change["to"].split()[0]), abs=1e-9)


def test_fix_of_a_layout_writes_no_yaml(tmp_path):
    gds = tmp_path / "s.gds"
    assert run("layout", str(DEVICES / "shin2004.yaml"), "-o", str(gds)).exit_code == 0
    res = run("fix", str(gds), "-o", str(tmp_path / "x.yaml"))
    assert res.exit_code == 2 and "betv extract" in res.stderr


def _geometry_springs() -> str:
    """push_demo with its springs from the drawing: no resonance, no α; driven where the
    drawn head's resonance puts ϖ in the window."""
    text = (DEVICES / "push_demo.yaml").read_text()
    text = re.sub(r"\n *vertical_resonance: [^\n]*", "", text)
    text = re.sub(r"\n *horizontal_resonance: [^\n]*", "", text)
    return text


def test_fixes_name_drawn_dimensions_where_the_drawing_gives_the_springs():
    spec = load_device_text(_geometry_springs(), str(DEVICES / "x.yaml"))
    fields = [v.field for v in parse_vary(spec, [])]
    assert "actuator.geometry.flexure_width" in fields
    assert "actuator.geometry.length" in fields
    assert "actuator.vertical_resonance" not in fields
    # where the file's resonances are used, the drawing changes nothing: not a default
    shipped = load_device(DEVICES / "push_demo.yaml")
    assert not any(v.field.startswith("actuator.geometry") for v in parse_vary(shipped, []))
    # a wider flexure is a stiffer head: a higher f_v
    (v,) = parse_vary(spec, ["actuator.geometry.flexure_width=3um:6um"])
    wide = spec.replace("actuator.geometry.flexure_width", "6 um")
    f = [derive(s).sets[0].step("f_v").magnitude for s in (spec, wide)]
    assert v.lo == pytest.approx(3.0) and f[1] > f[0]
