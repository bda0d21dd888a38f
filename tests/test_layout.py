"""Layout out and in (issue 23, slices 4 and 5): `betv layout`, `betv extract`,
`betv check FILE.gds`.

Independent truths: the derived parameters of the device file the layout was drawn from
(round trip, every shipped device and 50 seeded random ones); KLayout's own reader
(cells, layers, polygon areas against the drawn dimensions) and its own width and space
checks (against `betv check`'s, on seeded layouts with deliberate violations); hand-made
bad layouts whose fault is known.
"""

from __future__ import annotations

import hashlib
import math
import os
import re
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from betvdesign.cli import app
from betvdesign.errors import BetvError, SpecError
from betvdesign.nondim.device import derive
from betvdesign.spec.loader import load_device, load_device_text
from betvdesign.spec.process import SHIPPED_DIR

gdstk = pytest.importorskip("gdstk")
from betvdesign.layout.drc import findings  # noqa: E402
from betvdesign.layout.extract import extract  # noqa: E402
from betvdesign.layout.write import write_layout  # noqa: E402

DEVICES = Path(__file__).resolve().parents[1] / "devices"
SHIPPED = sorted(DEVICES.glob("*.yaml"))


def run(*args: str):
    return CliRunner().invoke(app, list(args))


def _params(spec):
    return [(s.name, s.params, s.scales) for s in derive(spec).sets]


def _same(a, b, rtol: float) -> None:
    for (na, pa, sa), (nb, pb, sb) in zip(a, b, strict=True):
        assert na == nb
        for k in ("varpi", "alpha", "beta", "kappa", "zeta_v", "zeta_h", "restitution"):
            assert getattr(pb, k) == pytest.approx(getattr(pa, k), rel=rtol, abs=1e-15), k
        assert sb.length_m == pytest.approx(sa.length_m, rel=rtol)
        assert sb.f_act_hz == pytest.approx(sa.f_act_hz, rel=rtol)


# --- round trip ---------------------------------------------------------------------------


@pytest.mark.parametrize("f", SHIPPED, ids=lambda p: p.stem)
def test_round_trip_of_the_shipped_devices(f, tmp_path):
    """YAML -> GDS -> YAML: the same derived parameters (a head given by its mass comes
    back as the disc of that mass, its diameter on the 1 nm grid: rtol 1e-4)."""
    spec = load_device(f)
    gds = tmp_path / f"{f.stem}.gds"
    out = tmp_path / f"{f.stem}.yaml"
    res = run("layout", str(f), "-o", str(gds))
    assert res.exit_code == 0, res.output
    res = run("extract", str(gds), "-o", str(out))
    assert res.exit_code == 0, res.output
    back = load_device(out)
    by_mass = any(s.head.mass is not None for s in spec.actuator_sets)
    _same(_params(spec), _params(back), 1e-4 if by_mass else 1e-12)
    for a, b in zip(spec.actuator_sets, back.actuator_sets, strict=True):
        assert a.impact_direction == b.impact_direction
        assert b.actuator.geometry.flexure_width == a.actuator.geometry.flexure_width
    assert back.slider.travel_range == spec.slider.travel_range
    assert back.published_fit == spec.published_fit


def _random_device(rng: np.random.Generator, i: int) -> str:
    """A drawable random device on PolyMUMPs' Poly1 (2 µm): one or two sets."""
    two = rng.uniform() < 0.5
    th = rng.uniform(15, 75)
    wh, wf = rng.uniform(2.5, 4), rng.uniform(2.5, 4)
    wc, gap, lt = rng.uniform(6, 20), rng.uniform(2.5, 5), rng.uniform(5, 15)
    H = wh + gap + wc
    r_min = (H**2 / 4 + lt**2 / 4) / lt * 1.01 + 0.05  # covers the tip (head-tip rule)
    box = rng.uniform() < 0.2
    r = rng.uniform(r_min, r_min + 20)
    head = (
        f"geometry: {{shape: box, length: {2 * r:.3f} um, width: {H + 1:.3f} um, thickness: 2 um}}"
        if box
        else f"geometry: {{shape: disc, diameter: {2 * r:.3f} um, thickness: 2 um}}"
        if rng.uniform() < 0.7
        else f"mass: {rng.uniform(0.5, 3) * 2330e-18 * math.pi * r * r * 2 * 1e9:.4g} ug"
    )
    length = rng.uniform(100, 400)
    lf = max(rng.uniform(0.1, 0.4) * length, 10 * wf)
    beam_l = max(rng.uniform(150, 400), 4 * (r + 3) + 40)
    w = rng.uniform(3, 45)
    n = int(rng.integers(1, 4))
    geo = (
        f"geometry: {{length: {length:.3f} um, hot_arm_width: {wh:.3f} um, cold_arm_width: "
        f"{wc:.3f} um, flexure_length: {lf:.3f} um, flexure_width: {wf:.3f} um, gap: "
        f"{gap:.3f} um, tip_length: {lt:.3f} um}}"
    )

    def one(name: str, direction: str, mode: str) -> str:
        return f"""
  - name: {name}
    intended_mode: {mode}
    impact_direction: "{direction}"
    head:
      {head}
    contact: {{impact_angle: {th:.4f} deg, friction: {rng.uniform(0.2, 0.6):.3f}}}
    actuator:
      vertical_resonance: {rng.uniform(2, 20):.4g} kHz
      horizontal_resonance: {rng.uniform(2, 20):.4g} kHz
      amplitude: {rng.uniform(0.05, 0.3):.3g} um
      {geo}
    drive: {{waveform: ac, frequency: {rng.uniform(0.5, 10):.4g} kHz}}"""

    sets = one("a", "+x", "push") + (one("b", "-x", "pull") if two else "")
    return f"""name: random{i}
process: polymumps
slider:
  beam_length: {beam_l:.3f} um
  beam_width: {w:.3f} um
  beam_thickness: 2 um
  beam_count: {n}
  extra_mass: {rng.uniform(0, 0.01):.4g} ug
  travel_range: {rng.uniform(10, 100):.3f} um
actuator_sets:{sets}
"""


RANDOM = [_random_device(np.random.default_rng(2300 + i), i) for i in range(50)]


@pytest.mark.parametrize("i", range(50))
def test_round_trip_of_random_devices(i, tmp_path):
    spec = load_device_text(RANDOM[i], str(tmp_path / "r.yaml"))
    gds = tmp_path / "r.gds"
    write_layout(spec, gds)
    ex = extract(gds)
    by_mass = any(s.head.mass is not None for s in spec.actuator_sets)
    _same(_params(spec), _params(ex.spec), 1e-4 if by_mass else 1e-9)
    assert [r.id for r in ex.rules if not r.passed and r.severity == "error"] == []


def test_layout_is_deterministic_and_names_cells_by_their_parameters(tmp_path):
    spec = load_device(DEVICES / "shin2004.yaml")
    a, b = tmp_path / "a.gds", tmp_path / "b.gds"
    write_layout(spec, a)
    write_layout(spec, b)
    assert hashlib.sha256(a.read_bytes()).digest() == hashlib.sha256(b.read_bytes()).digest()
    names = {c.name for c in gdstk.read_gds(a).cells}
    assert "SLIDER_poly1_L170_W5_N2_G10_E10" in names
    assert any(re.fullmatch(r"ACT_poly1_L200_H2p5_C14_F40x2p5_G3_T10_A20_D99p1\d*", n)
               for n in names)  # fmt: skip
    assert "BETV_shin2004" in names


# --- an independent reader ----------------------------------------------------------------


def test_klayout_reads_the_expected_cells_layers_and_areas(tmp_path):
    kdb = pytest.importorskip("klayout.db")
    spec = load_device(DEVICES / "push_demo.yaml")
    gds = tmp_path / "p.gds"
    write_layout(spec, gds)
    ly = kdb.Layout()
    ly.read(str(gds))
    assert ly.dbu == pytest.approx(0.001)
    cells = {c.name: c for c in ly.each_cell()}
    slider = cells["SLIDER_poly1_L200_W10_N2_G10_E10"]
    poly1 = ly.layer(45, 0)
    areas = sorted(p.area() * ly.dbu**2 for p in slider.each_shape(poly1))
    # two beams 200 × 10 µm and two end pieces 10 × 30 µm
    assert areas == pytest.approx([300.0, 300.0, 2000.0, 2000.0])
    act = next(c for n, c in cells.items() if n.startswith("ACT_"))
    shapes = [s.polygon for s in act.each_shape(poly1)]
    disc = max(shapes, key=lambda p: p.num_points())
    r = 18.0  # 36 µm head: a 128-gon inscribed in its circle
    assert disc.area() * ly.dbu**2 == pytest.approx(64 * r * r * math.sin(2 * math.pi / 128),
                                                    rel=1e-4)  # fmt: skip
    holes = list(act.each_shape(ly.layer(44, 0)))
    assert holes and all(h.polygon.area() * ly.dbu**2 == pytest.approx(16.0) for h in holes)
    top = ly.top_cell()
    texts = [s.text_string for s in top.each_shape(ly.layer(63, 0)) if s.is_text()]
    assert texts.count("forward.lower.head") == 1 and texts.count("slider.beam") == 2
    assert "process = demo25" in texts  # a shipped process, by its name
    own = spec.model_copy(update={"process": spec.process.model_copy(update={"name": "mine"})})
    with pytest.raises(BetvError, match="not a shipped one"):
        write_layout(own, tmp_path / "q.gds")


def _klayout_findings(kdb, gds: Path, d_um: float) -> tuple[list, list]:
    ly = kdb.Layout()
    ly.read(str(gds))
    top = ly.top_cell()
    body = kdb.Region(top.begin_shapes_rec(ly.layer(45, 0)))
    body.merge()
    body -= kdb.Region(top.begin_shapes_rec(ly.layer(44, 0)))
    d = round(d_um / ly.dbu)
    # edges meeting at ~90° after a rotated cell is rounded to the grid are not violations
    args = (d, False, kdb.Region.Euclidian, 80)
    boxes = []
    for ep in (body.width_check(*args), body.space_check(*args)):
        boxes.append([e.bbox().transformed(kdb.CplxTrans(ly.dbu)) for e in ep.each()])
    return boxes[0], boxes[1]


def _near(box_k, viol, slack: float = 1.0) -> bool:
    x0, y0, x1, y1 = viol.bbox
    return not (box_k.right < x0 - slack or box_k.left > x1 + slack
                or box_k.top < y0 - slack or box_k.bottom > y1 + slack)  # fmt: skip


@pytest.mark.parametrize("seed", range(8))
def test_width_and_space_agree_with_klayout_on_deliberate_violations(seed, tmp_path):
    """Seeded violations drawn into a clean layout: a sliver narrower than the minimum
    width and a polygon closer than the minimum spacing to a stop. KLayout's own
    width/space checks and betv's find the same places; the clean layout has none."""
    kdb = pytest.importorskip("klayout.db")
    rng = np.random.default_rng(seed)
    spec = load_device(DEVICES / "shin2004.yaml")
    gds = tmp_path / "v.gds"
    write_layout(spec, gds)
    lib = gdstk.read_gds(gds)
    top = lib.top_level()[0]
    kw, ks = _klayout_findings(kdb, gds, 2.0)
    assert kw == [] and ks == []
    # a sliver 0.5–1.8 µm wide, far from everything (the minimum is 2 µm)
    w = rng.uniform(0.5, 1.8)
    x, y = rng.uniform(-300, 300), rng.uniform(320, 400)
    ang = rng.uniform(0, math.pi)
    sliver = gdstk.rectangle((0, 0), (30, w), layer=45)
    sliver.rotate(ang)
    sliver.translate(x, y)
    top.add(sliver)
    # a square 0.5–1.8 µm from the right stop (at x = 85 + 10 + 20 = 115 .. 135)
    g = rng.uniform(0.5, 1.8)
    top.add(gdstk.rectangle((135 + g, -5), (145 + g, 5), layer=45))
    lib.write_gds(gds)
    kw, ks = _klayout_findings(kdb, gds, 2.0)
    p = spec.process
    by: dict = {}
    for poly in top.get_polygons():
        by.setdefault((poly.layer, poly.datatype), []).append(poly)
    f = findings(gdstk, p, by)
    assert kw and ks and f.width and f.space
    assert extract(gds).notes == [
        "2 polygon(s) of a structural layer carry no label: not part of the model (the "
        "process rules check them all)"
    ]
    for kbox in kw:
        assert any(_near(kbox, v) for v in f.width), (kbox, f.width)
    for v in f.width:
        assert any(_near(kbox, v) for kbox in kw), (v, kw)
    for kbox in ks:
        assert any(_near(kbox, v) for v in f.space), (kbox, f.space)
    for v in f.space:
        assert any(_near(kbox, v) for kbox in ks), (v, ks)
    assert min(v.extent for v in f.width) == pytest.approx(w, abs=0.01)


# --- bad layouts --------------------------------------------------------------------------


@pytest.fixture
def shin_gds(tmp_path) -> Path:
    gds = tmp_path / "shin.gds"
    write_layout(load_device(DEVICES / "shin2004.yaml"), gds)
    return gds


def _edit(gds: Path, fn) -> Path:
    lib = gdstk.read_gds(gds)
    fn(lib.top_level()[0], lib)
    out = gds.with_name("edited.gds")
    lib.write_gds(out)
    return out


def _check_fails(path: Path, *expect: str) -> str:
    res = run("check", "--no-adequacy", str(path))
    assert res.exit_code == 2, res.output
    assert "Traceback" not in res.output
    for e in expect:
        assert re.search(e, res.stderr), (e, res.stderr)
    return res.stderr


def test_no_labels(shin_gds):
    def strip(top, lib):
        for lab in list(top.labels):
            if "=" not in lab.text:
                top.remove(lab)

    err = _check_fails(_edit(shin_gds, strip), "cell BETV_shin2004", "no element labels",
                       r"annotation layer betv_text \(63/0\)")  # fmt: skip
    assert str(shin_gds.with_name("edited.gds")) in err


def test_no_process_label(shin_gds):
    def strip(top, lib):
        for lab in list(top.labels):
            if lab.text.startswith("process"):
                top.remove(lab)

    _check_fails(_edit(shin_gds, strip), "no 'process = NAME' label")


def test_two_heads_for_one_set(shin_gds):
    def dup(top, lib):
        lab = next(lab for lab in top.labels if lab.text == "right.lower.head")
        other = next(lab for lab in top.labels if lab.text == "left.lower.head")
        other.text = "right.lower.head"
        assert lab is not other

    _check_fails(_edit(shin_gds, dup), r"two 'right.lower.head' labels", r"\(-?\d+\.\d{3}, ")


def test_a_beam_of_zero_width(shin_gds):
    def zero(top, lib):
        slider = next(c for c in lib.cells if c.name.startswith("SLIDER"))
        beam = next(p for p in slider.polygons if p.area() == pytest.approx(850.0))
        (x0, y0), (x1, _) = beam.bounding_box()
        slider.remove(beam)
        slider.add(gdstk.Polygon([(x0, y0), (x1, y0), (x1, y0), (x0, y0)], layer=45))

    _check_fails(_edit(shin_gds, zero), "label 'slider.beam' at", "lies on no polygon",
                 r"poly1 \(45/0\)")  # fmt: skip


def test_overlapping_elements(shin_gds):
    def overlap(top, lib):
        slider = next(c for c in lib.cells if c.name.startswith("SLIDER"))
        beams = [p for p in slider.polygons if p.area() == pytest.approx(850.0)]
        beams[0].translate(0, 4.0)  # 5 µm beams 10 µm apart: now 6 µm apart … and
        beams[1].translate(0, -12.0)  # this one crosses the first

    _check_fails(_edit(shin_gds, overlap), "overlap")


def test_a_huge_gds_is_refused_before_reading(tmp_path):
    big = tmp_path / "big.gds"
    with open(big, "wb") as fh:
        fh.truncate(2 * 1024**3)  # sparse: 2 GB on paper, nothing on disk
    err = _check_fails(big, r"2,147,483,648 bytes; the limit is", "BETV_MAX_GDS_BYTES")
    assert str(big) in err


def test_not_a_gds(tmp_path):
    f = tmp_path / "x.gds"
    f.write_bytes(b"\x00\x01garbage" * 10)
    _check_fails(f, "not a readable GDSII file|expected one top cell")


# --- the command line ---------------------------------------------------------------------


def test_layout_refuses_what_it_cannot_draw(tmp_path):
    text = (DEVICES / "shin2004.yaml").read_text().replace("process: polymumps", "")
    text = re.sub(r"\n *geometry:\n( {8}[a-z_]+: [^\n]*\n)+", "\n", text)
    text = text.replace("      # The drawn hot/cold-arm actuator (betv layout draws it). Its "
                        "springs are\n      # compared with the resonances above, which stay "
                        "the ones used.\n", "")  # fmt: skip
    f = tmp_path / "nogeo.yaml"
    f.write_text(text)
    out = tmp_path / "x.gds"
    res = run("layout", str(f), "-o", str(out))
    assert res.exit_code == 2 and "names no process" in res.stderr
    assert not out.exists()
    res = run("layout", str(DEVICES / "shin2004.yaml"), "-o", str(tmp_path / "x.txt"))
    assert res.exit_code == 2 and "must end in .gds" in res.stderr


def test_layout_refuses_a_thickness_the_layer_does_not_have(tmp_path):
    text = (DEVICES / "shin2004.yaml").read_text().replace("beam_thickness: 2 um",
                                                           "beam_thickness: 2.5 um")  # fmt: skip
    f = tmp_path / "thick.yaml"
    f.write_text(text)
    with pytest.raises(BetvError, match=r"beam_thickness 2\.5 µm is not poly1's 2 µm"):
        write_layout(load_device(f), tmp_path / "t.gds")


def test_check_gds_gives_the_yaml_verdict_with_layout_rules(tmp_path):
    f = DEVICES / "push_demo.yaml"
    gds = tmp_path / "push.gds"
    assert run("layout", str(f), "-o", str(gds), "--svg", str(tmp_path / "p.svg")).exit_code == 0
    assert (tmp_path / "p.svg").read_text().startswith("<?xml")
    a = run("check", "--json", "--no-adequacy", str(f))
    b = run("check", "--json", "--no-adequacy", str(gds))
    assert a.exit_code == b.exit_code == 0
    import json

    da, db = json.loads(a.stdout)["devices"][0], json.loads(b.stdout)["devices"][0]
    assert da["sets"][0]["params"] == db["sets"][0]["params"]
    ra = {r["id"]: r for r in da["rules"]}
    rb = {r["id"]: r for r in db["rules"]}
    assert set(ra) == set(rb)
    # the drawn holes release the head: a warning in the file, passed in the layout
    assert not ra["process.release"]["passed"] and rb["process.release"]["passed"]
    assert "cell BETV_push_demo" in rb["process.min-width"]["message"]


def test_process_path_is_rebased(tmp_path):
    """A device naming its own process file by a relative path: the layout's label and
    the extracted file's `process:` point at it from where they are written."""
    (tmp_path / "procs").mkdir()
    (tmp_path / "procs" / "mine.yaml").write_text(
        (SHIPPED_DIR / "polymumps.yaml").read_text().replace("name: polymumps", "name: mine")
    )
    dev = tmp_path / "dev.yaml"
    dev.write_text((DEVICES / "shin2004.yaml").read_text().replace(
        "process: polymumps", "process: procs/mine.yaml"))  # fmt: skip
    sub = tmp_path / "deep" / "er"
    sub.mkdir(parents=True)
    gds = sub / "shin.gds"
    assert run("layout", str(dev), "-o", str(gds)).exit_code == 0
    texts = [lab.text for lab in gdstk.read_gds(gds).top_level()[0].labels]
    assert 'process = "../../procs/mine.yaml"' in texts  # a YAML value, quoted
    out = tmp_path / "back.yaml"
    assert run("extract", str(gds), "-o", str(out)).exit_code == 0
    assert load_device(out).process.name == "mine"
    ref = re.search(r"\nprocess: (.*)\n", out.read_text()).group(1)
    assert ref == "procs/mine.yaml"


def test_shipped_process_dir_is_packaged():
    assert (SHIPPED_DIR / "polymumps.yaml").is_file()
    assert os.path.relpath(SHIPPED_DIR, Path(__file__).parents[1]).startswith("betvdesign")


def test_bad_data_label_is_located(shin_gds):
    def bad(top, lib):
        lab = next(lab for lab in top.labels if lab.text.startswith("right/drive.frequency"))
        lab.text = "right/drive.frequency = 500 apples"

    err = _check_fails(_edit(shin_gds, bad), "label 'right/drive.frequency = 500 apples'",
                       "cell BETV_shin2004")  # fmt: skip
    assert "actuator_sets[0].drive.frequency" in err


def test_extract_error_is_a_spec_error(shin_gds):
    def strip(top, lib):
        for lab in list(top.labels):
            if lab.text.endswith(".tip"):
                top.remove(lab)

    with pytest.raises(SpecError, match="no label for tip"):
        extract(_edit(shin_gds, strip))


@pytest.mark.slow
def test_api_check_of_a_gds_is_betv_check_of_it(tmp_path):
    """`betvdesign.check(FILE.gds)` is `betv check FILE.gds`: the same JSON (the layout's
    measured process rules, the extraction's notes, the advice's fix texts), the same
    verdict and exit code. shin2004 fails its frequency window, so the advice runs."""
    import json

    import betvdesign

    gds = tmp_path / "shin.gds"
    assert run("layout", str(DEVICES / "shin2004.yaml"), "-o", str(gds)).exit_code == 0
    cli = run("check", "--json", "--no-adequacy", str(gds))
    res = betvdesign.check(gds, adequacy=False)
    (dev,) = json.loads(cli.stdout)["devices"]
    assert res.view.as_json() == dev
    assert cli.exit_code == 1 and res.verdict == dev["verdict"] == "fail"
    assert dev["file"] == str(gds) and res.notes == dev["notes"]
    window = next(r for r in res.rules if r.id == "frequency-window")
    assert "drive.frequency" in window.fix  # the advice's text, not the rule's own
    assert "cell BETV_shin2004" in next(r for r in res.rules if r.id == "process.min-width").message


def test_extract_to_stdout(shin_gds, tmp_path):
    """Issue 32 item 13: `betv extract FILE.gds -o -` writes the device file to standard
    output (the notes to standard error), the same text `-o FILE` writes."""
    out = tmp_path / "back.yaml"
    assert run("extract", str(shin_gds), "-o", str(out)).exit_code == 0
    res = run("extract", str(shin_gds), "-o", "-")
    assert res.exit_code == 0, res.output
    assert res.stdout == out.read_text("utf-8")
    assert "wrote" not in res.output and not (tmp_path / "-").exists()
    assert load_device_text(res.stdout).name == load_device(out).name


def test_a_polygon_over_the_vertex_cap_is_refused_naming_file_and_layer(shin_gds):
    """A 10⁶-vertex disc on the structural layer: exit 2 before any geometry, the file,
    the layer and the polygon's place named (no traceback, no quadratic work)."""
    from betvdesign.layout.extract import MAX_POLYGON_VERTICES

    def big(top, lib):
        t = np.linspace(0, 2 * math.pi, 1_000_000, endpoint=False)
        top.add(gdstk.Polygon(np.c_[2000 + 100 * np.cos(t), 100 * np.sin(t)], layer=45))

    lib_path = shin_gds.with_name("big.gds")
    lib = gdstk.read_gds(shin_gds)
    big(lib.top_level()[0], lib)
    lib.write_gds(lib_path, max_points=0)
    err = _check_fails(
        lib_path, r"poly1 \(45/0\) at \(2000\.000, 0\.000\) µm has 1,000,000 vertices",
        f"at most {MAX_POLYGON_VERTICES:,} are read per polygon",
    )  # fmt: skip
    assert str(lib_path) in err


def test_a_layout_over_the_vertex_cap_is_refused(shin_gds):
    """Polygons each within the per-polygon cap but over the layout's together."""
    from betvdesign.layout.extract import MAX_LAYOUT_VERTICES, MAX_POLYGON_VERTICES

    def many(top, lib):
        t = np.linspace(0, 2 * math.pi, MAX_POLYGON_VERTICES, endpoint=False)
        for k in range(MAX_LAYOUT_VERTICES // MAX_POLYGON_VERTICES + 1):
            top.add(gdstk.Polygon(np.c_[3000 + 30 * k + 10 * np.cos(t), 10 * np.sin(t)],
                                  layer=61))  # fmt: skip

    err = _check_fails(_edit(shin_gds, many), r"vertices in the layout \(\d[\d,]* on layer 61/0\)")
    assert f"at most {MAX_LAYOUT_VERTICES:,} are read" in err
