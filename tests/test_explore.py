"""``betv explore`` without a browser: the design being edited, its saved YAML, the
controls' fields, the staged check (against ``betv check``'s own JSON), the field map
and the worker jobs.

Source: the device file's validation and ``betv check`` itself (every expected value
is computed by the check path the page must reproduce; nothing is hand-copied).
"""

from __future__ import annotations

import difflib
import itertools
import json
import math
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import DEVICES
from typer.testing import CliRunner

from betvdesign.checks.checker import check_derivation
from betvdesign.cli import app
from betvdesign.errors import SpecError
from betvdesign.explore.compute import evaluate
from betvdesign.explore.design import Design, free_name, set_path
from betvdesign.explore.fields import SLIDER_STEPS, current_value, designer_fields
from betvdesign.nondim.device import derive, derive_refusing
from betvdesign.output.presentation import MODE_COLORS
from betvdesign.spec.limits import MAX_BEAM_COUNT
from betvdesign.spec.loader import load_device, load_device_text
from betvdesign.studies.fieldmap import MAP_MODES, FieldAxis, map_rows, mode_map

#: The command line, as the user runs it (the console script's entry point).
BETV = [sys.executable, "-c", "from betvdesign.cli import main; main()"]


def _changed_lines(a: str, b: str) -> list[str]:
    return [
        line
        for line in difflib.unified_diff(a.splitlines(), b.splitlines(), lineterm="", n=0)
        if line[:1] in "+-" and not line.startswith(("+++", "---"))
    ]


# --- the design and its file -------------------------------------------------------------


@pytest.mark.parametrize("name", [p.stem for p in sorted(DEVICES.glob("*.yaml"))])
def test_edited_file_changes_only_the_changed_lines(name: str) -> None:
    """Every shipped device: a drive-frequency change rewrites exactly the frequency
    line(s) (one per set giving it), and the text reads back as the edited spec."""
    d = Design.from_file(DEVICES / f"{name}.yaml")
    freq = current_value(d.original, 0, "drive.frequency")
    d.apply({"drive.frequency": f"{float(freq.magnitude) * 1.05:.4g} {freq.units:~}"})
    text = d.yaml_text()
    assert load_device_text(text) == d.spec
    changed = _changed_lines(d.text, text)
    assert len(changed) == 2 * len(d.original.actuator_sets), changed
    assert all("frequency" in line for line in changed), changed


def test_flow_mappings_per_set_edits_and_added_fields() -> None:
    """bidir_demo writes its sets as flow mappings: a per-set change touches one line,
    an added optional value (Q, e) goes beside its siblings, comments stay."""
    d = Design.from_file(DEVICES / "bidir_demo.yaml")
    d.apply(
        {
            set_path("contact.friction", "west"): 0.3,
            "actuator.quality_factor_normal": 30.0,
            "contact.restitution": 0.1,
        }
    )
    text = d.yaml_text()
    back = load_device_text(text)
    assert back == d.spec
    east, west = back.actuator_sets
    assert (east.contact.friction, west.contact.friction) == (0.35, 0.3)
    assert east.actuator.quality_factor_normal == 30.0 and west.contact.restitution == 0.1
    assert [c for c in d.text.splitlines() if "#" in c] == [
        c for c in text.splitlines() if "#" in c and "quality_factor" not in c
    ]
    assert len(_changed_lines(d.text, text)) == 2 + 2 + 2  # contact lines, new Q lines


def test_refused_value_keeps_the_design_and_gives_the_loaders_message() -> None:
    d = Design.from_file(DEVICES / "push_demo.yaml")
    d.apply({"drive.frequency": "3.2 kHz"})
    before = d.spec
    with pytest.raises(SpecError) as exc:
        d.apply({"contact.friction": 7.0})
    with pytest.raises(SpecError) as direct:
        load_device(DEVICES / "push_demo.yaml").replace("contact.friction", 7.0)
    assert exc.value.issues[0].message == direct.value.issues[0].message
    assert "outside the physical range" in exc.value.issues[0].message
    assert d.spec == before and "contact.friction" not in d.edits
    with pytest.raises(SpecError, match="missing unit"):
        d.apply({"drive.frequency": "3.2"})


def test_save_never_overwrites_unasked(tmp_path: Path) -> None:
    src = tmp_path / "push_demo.yaml"
    shutil.copy(DEVICES / "push_demo.yaml", src)
    d = Design.from_file(src)
    d.apply({"slider.beam_width": "12 um"})
    first = d.save("mine.yaml")
    assert first.written and (tmp_path / "mine.yaml").is_file()
    again = d.save("mine.yaml")
    assert not again.written and "exists" in again.message
    assert not d.save(src.name).written  # the user's own file too
    assert src.read_text() == (DEVICES / "push_demo.yaml").read_text()
    d.apply({"slider.beam_width": "14 um"})
    assert d.save("mine.yaml", overwrite=True).written
    assert "14 um" in (tmp_path / "mine.yaml").read_text()
    assert not d.save("mine.txt").written
    assert free_name(tmp_path / "mine.yaml") == tmp_path / "mine-2.yaml"


@pytest.mark.slow
def test_saved_file_rechecks_to_the_page_verdict(tmp_path: Path) -> None:
    """`betv check --json` of the saved YAML gives the verdict, modes and speeds of
    the page's full stage."""
    src = tmp_path / "bidir_demo.yaml"
    shutil.copy(DEVICES / "bidir_demo.yaml", src)
    d = Design.from_file(src)
    d.apply({"drive.frequency": "3.3 kHz", "slider.beam_width": "10 um"})
    ev = evaluate(d.spec, "full", source_file=str(src))
    res = d.save("saved.yaml")
    assert res.written
    proc = subprocess.run(
        [*BETV, "check", "--json", str(res.path)], capture_output=True, text=True, check=False
    )
    assert proc.returncode in (0, 1), proc.stderr
    dev = json.loads(proc.stdout)["devices"][0]
    assert dev["verdict"] == ev.out["verdict"]
    for a, b in zip(dev["sets"], ev.out["sets"], strict=True):
        assert (a["name"], a["mode"]) == (b["name"], b["mode"])
        assert a["speed_m_s"] == pytest.approx(b["speed_m_s"], rel=1e-12)
        assert [r["id"] for r in a["rules"]] == [r["id"] for r in b["rules"]]
        assert [r["fix"] for r in a["rules"]] == [r["fix"] for r in b["rules"]]


# --- stages --------------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["push_demo", "shin2004"])
def test_stages_are_betv_checks_own(name: str) -> None:
    """Stage "full" is exactly ``betv check``'s device JSON; "orbit" has the same modes;
    "settling" the same answer (mode, basis, Δs error, speed); traces are in physical
    units."""
    spec = load_device(DEVICES / f"{name}.yaml")
    full = evaluate(spec, "full")
    cli = CliRunner().invoke(app, ["check", "--json", "--no-advice", str(DEVICES / f"{name}.yaml")])
    ref = json.loads(cli.stdout)["devices"][0]  # betv check's own JSON of the file
    assert full.out == {**ref, "file": ""}
    fast = evaluate(spec, "orbit", with_traces=True)
    assert [s["mode"] for s in fast.out["sets"]] == [s["mode"] for s in ref["sets"]]
    # how well Δs is determined and the travel from rest arrive with the settling stage:
    # from there on the answer quoted (its basis) is betv check's
    settled = evaluate(spec, "settling")
    keys = ("mode", "basis", "delta_s_error", "speed_m_s")
    assert [[s[k] for k in keys] for s in settled.out["sets"]] == [
        [s[k] for k in keys] for s in ref["sets"]
    ]
    assert all(s["delta_s_error"] is None for s in fast.out["sets"])
    assert not any(r["id"] in ("settling", "model-adequacy") for r in fast.out["rules"])
    tr = fast.traces[spec.actuator_sets[0].name]
    assert tr.reason == "" and len(tr.gap_um) > 50 and len(tr.t_ms) == len(tr.x_um)
    assert min(tr.gap_um) >= -1e-9 and max(tr.gap_um) < 1.0  # µm: a fraction of u sinθ


# --- controls -------------------------------------------------------------------------------


def test_controls_cover_the_designers_fields_with_ranges_the_spec_accepts() -> None:
    spec = load_device(DEVICES / "push_demo.yaml")
    fields = {c.field: c for c in designer_fields(spec, 0)}
    for f in (
        "drive.frequency",
        "drive.voltage",
        "drive.waveform",
        "slider.beam_width",
        "slider.beam_length",
        "slider.beam_thickness",
        "slider.beam_count",
        "head.geometry.diameter",
        "contact.impact_angle",
        "contact.friction",
        "actuator.vertical_resonance",
        "actuator.horizontal_resonance",
        "actuator.quality_factor_normal",
        "actuator.quality_factor_tangential",
        "contact.restitution",
    ):
        assert f in fields, f
    # push_demo draws its actuator but its file gives f_v and f_h (used): the drawn
    # dimensions change no verdict, so the page leaves them out as betv fix does
    assert not any(f.startswith("actuator.geometry.") for f in fields)
    for c in fields.values():
        if c.kind == "choice":
            for choice in c.choices:
                spec.replace(c.field, choice)
            continue
        assert c.lo <= (c.value if c.value is not None else c.lo) <= c.hi, c
        for x in (c.lo, c.hi):
            value = c.file_value(c.text(x))
            spec.replace(c.field, value)  # raises when the spec refuses the slider's end
    # the voltage slider spans the measured calibration, 0 V to 10 V (the file's points),
    # from its first position above 0 V (the spec takes only V > 0)
    volt = fields["drive.voltage"]
    assert volt.hi == 10.0 and not volt.log
    assert 0.0 < volt.lo <= (volt.hi - 0.0) / SLIDER_STEPS * (1 + 1e-12)
    derive_refusing(spec.replace("drive.voltage", volt.file_value(volt.text(volt.lo))), "x")
    assert fields["slider.beam_count"].hi == MAX_BEAM_COUNT  # the spec's own limit
    assert fields["drive.frequency"].log and not fields["contact.impact_angle"].log


def test_damping_given_as_ratio_shows_the_ratio() -> None:
    spec = load_device(DEVICES / "damped_demo.yaml")
    spec = spec.replace("actuator.quality_factor_normal", None).replace(
        "actuator.damping_ratio_normal", 0.02
    )
    fields = {c.field for c in designer_fields(spec, 0)}
    assert "actuator.damping_ratio_normal" in fields
    assert "actuator.quality_factor_normal" not in fields
    assert "actuator.quality_factor_tangential" in fields


# --- the field map ---------------------------------------------------------------------------


def test_map_point_at_the_device_has_the_checks_mode() -> None:
    spec = load_device(DEVICES / "push_demo.yaml")
    x = FieldAxis.spanning("drive.frequency", "kHz", 2.0, 4.5, 5)
    y = FieldAxis("slider.beam_width", "um", (6.0, 10.0, 14.0), log=True)
    fmap = mode_map(spec, 0, x, y, chunk=2)
    assert fmap.complete
    i = 2
    spec_i = spec.replace("drive.frequency", f"{x.values[i]!r} kHz").replace(
        "slider.beam_width", "10 um"
    )
    exact = check_derivation(derive(spec_i), margin=False, settle=False, adequacy=False)
    assert fmap.mode[1, i] == exact.sets[0].verdict_mode
    assert fmap.varpi[1, i] == pytest.approx(exact.sets[0].derivation.params.varpi, rel=1e-12)
    v = exact.sets[0].speed_m_s
    assert fmap.speed_m_s[1, i] == pytest.approx(v, rel=1e-12)
    rows = map_rows(spec, 0, x, y, [2])
    assert rows.mode[0] == list(fmap.mode[2])
    edges = x.edges()
    assert all(a < b for a, b in itertools.pairwise(edges))
    assert edges[0] < x.values[0] and edges[-1] > x.values[-1]


def test_map_marks_values_the_device_cannot_take() -> None:
    """push_demo's calibration is measured up to 10 V: the map says "invalid" above
    it (no extrapolation), and why."""
    spec = load_device(DEVICES / "push_demo.yaml")
    x = FieldAxis("drive.voltage", "V", (8.0, 12.0), log=False)
    y = FieldAxis("slider.beam_width", "um", (10.0, 12.0), log=False)
    part = map_rows(spec, 0, x, y, [0, 1])
    assert [m[1] for m in part.mode] == ["invalid", "invalid"]
    assert part.mode[0][0] in ("push", "pull")
    assert "calibration" in part.reasons[(0, 1)]
    assert math.isnan(part.varpi[0][1])


def test_map_mode_names_are_the_field_sweeps() -> None:
    """One vocabulary of a point's exact mode (studies.fieldsweep.exact_mode)."""
    from betvdesign.studies.fieldsweep import exact_mode

    assert exact_mode({"converged": True, "delta_s": 1.0}) == "push"
    assert exact_mode({"converged": True, "delta_s": -1.0}) == "pull"
    assert exact_mode({"converged": True, "delta_s": 0.0}) == "stalled"
    assert exact_mode({"status": "not_driven"}) == "not driven"
    assert exact_mode({"status": "unbounded"}) == "unbounded"
    assert exact_mode({"status": "not_converged"}) == "not converged"
    assert set(MAP_MODES) <= set(MODE_COLORS)


def test_map_draws_the_design_and_on_axis_fixes_inside_its_axes() -> None:
    """The star and the fixes are on the map's overlay layer (not clipped to the frame):
    only points inside the axes are drawn; a fix that changes a field off the axes is
    listed, not drawn."""
    pytest.importorskip("bokeh")
    from betvdesign.explore.mapview import MapView

    spec = load_device(DEVICES / "push_demo.yaml")
    controls = {c.field: c for c in designer_fields(spec, 0)}
    view = MapView(lambda: controls, lambda: None, lambda *a: None, lambda: None)
    assert (view.x_select.value, view.y_select.value) == ("drive.frequency", "slider.beam_width")
    view.show_design(spec, 0)
    assert view.device.data == {"x": [3.0], "y": [10.0]}  # kHz, um
    fixes = [
        {"values": {"drive.frequency": [4000.0, "Hz"]}},  # on the x axis: drawn
        {"values": {"contact.friction": [0.3, ""]}},  # off the axes: not drawn
        {"values": {"drive.frequency": [50.0, "kHz"]}},  # beyond the axis: not drawn
        {"values": {"drive.frequency": [2.5, "kHz"], "slider.beam_width": [12.0, "um"]}},
    ]
    view.show_fixes(fixes, spec, 0)
    assert view.fixes.data["label"] == ["1", "4"]
    assert view.fixes.data["x"] == [pytest.approx(4.0), pytest.approx(2.5)]
    assert view.fixes.data["y"] == [10.0, pytest.approx(12.0)]
    assert view.fixes.data["x0"] == [3.0, 3.0]
    outside = spec.replace("drive.frequency", "20 kHz")  # beyond the slider's 12 kHz
    view.show_design(outside, 0)
    assert view.device.data == {"x": [], "y": []}
    view.show_fixes(fixes, outside, 0)
    assert view.fixes.data["label"] == []
    levels = {r.level for r in view.fig.renderers[1:]}
    assert levels == {"overlay"}


# --- worker jobs (run here, in-process) ---------------------------------------------------


@pytest.mark.slow
def test_jobs_in_process_and_stale_jobs_dropped(monkeypatch: pytest.MonkeyPatch) -> None:
    from betvdesign.explore import jobs

    text = (DEVICES / "shin2004.yaml").read_text()
    out = jobs.check_job(0, 0, text, "shin2004.yaml", "settling", {})
    assert out is not None and out["stage"] == "settling"
    assert out["settling"]["right"]["cycles_to_settle"] is not None
    x = FieldAxis.spanning("drive.frequency", "Hz", 400.0, 900.0, 3)
    y = FieldAxis.spanning("slider.beam_width", "um", 4.0, 6.0, 2)
    part = jobs.map_job(0, 0, text, "shin2004.yaml", 0, x, y, [0, 1])
    assert part is not None and len(part["mode"]) == 2
    fixes = jobs.fix_job(0, 0, text, "shin2004.yaml", None)
    assert fixes is not None and fixes["status"] == "fixed"
    best = next(c for c in fixes["candidates"] if c["passed"])
    d = Design(text, "shin2004.yaml")
    d.apply(best["file_values"])
    assert evaluate(d.spec, "full").verdict == "pass"
    monkeypatch.setattr(jobs, "_GEN", [5])
    assert jobs.check_job(0, 4, text, "x.yaml", "full", {}) is None
    assert jobs.map_job(0, 4, text, "x.yaml", 0, x, y, [0]) is None


# --- the command -----------------------------------------------------------------------------


def test_cli_bad_file_and_missing_extra(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from typer.testing import CliRunner

    from betvdesign.cli import app

    runner = CliRunner()
    bad = tmp_path / "bad.yaml"
    bad.write_text((DEVICES / "push_demo.yaml").read_text().replace("0.4", "7"))
    r = runner.invoke(app, ["explore", str(bad), "--no-browser"])
    assert r.exit_code == 2 and "outside the physical range" in r.output
    r = runner.invoke(app, ["explore", str(tmp_path / "none.yaml"), "--no-browser"])
    assert r.exit_code == 2 and "no such file" in r.output
    monkeypatch.setitem(sys.modules, "bokeh", None)
    r = runner.invoke(app, ["explore", str(DEVICES / "push_demo.yaml"), "--no-browser"])
    assert r.exit_code == 2 and "pip install 'betvdesign[explore]'" in r.output
    assert "Traceback" not in r.output


@pytest.mark.slow
def test_worker_lanes_drop_stale_jobs_survive_a_dead_worker_and_close() -> None:
    """Jobs run on a worker process; a job queued for an older generation returns None
    at once; a killed worker fails its job (never hangs the page) and the next job
    starts a new one; close() stops it."""
    import threading

    from betvdesign.explore import jobs

    w = jobs.Workers()
    results: list[object] = []
    got = threading.Event()

    def done(value: object) -> None:
        results.append(value)
        got.set()

    def failed(exc: BaseException) -> None:
        results.append(exc)
        got.set()

    text = (DEVICES / "push_demo.yaml").read_text()
    try:
        gen = w.bump("check", 3)
        w.submit("check", 3, gen - 1, jobs.check_job, (text, "p.yaml", "orbit", {}), done, failed)
        assert got.wait(300) and results == [None]
        got.clear()
        w.submit("check", 3, gen, jobs.check_job, (text, "p.yaml", "orbit", {}), done, failed)
        assert got.wait(300) and results[-1]["out"]["verdict"] == "pass"
        lane = w.lanes["check"]
        got.clear()
        lane.proc.kill()
        w.submit("check", 3, gen, jobs.check_job, (text, "p.yaml", "full", {}), done, failed)
        assert got.wait(300)
        got.clear()
        w.submit("check", 3, gen, jobs.check_job, (text, "p.yaml", "orbit", {}), done, failed)
        assert got.wait(300) and results[-1]["stage"] == "orbit"
        proc = lane.proc
    finally:
        w.close()
    assert not proc.is_alive()


def test_drawn_dimensions_are_controls_where_the_drawing_gives_the_springs() -> None:
    """Without f_v and f_h in the file the drawing gives the head's springs: its
    dimensions move the verdict and are controls (as they are betv fix's fields)."""
    import re

    from betvdesign.spec.loader import load_device_text

    text = (DEVICES / "push_demo.yaml").read_text()
    text = re.sub(r"\n *vertical_resonance: [^\n]*", "", text)
    text = re.sub(r"\n *horizontal_resonance: [^\n]*", "", text)
    spec = load_device_text(text, str(DEVICES / "x.yaml"))
    fields = {c.field for c in designer_fields(spec, 0)}
    assert {"actuator.geometry.length", "actuator.geometry.flexure_width"} <= fields


# --- values the model cannot take (issue 32, items 1 and 2) --------------------------------


def _check_stderr(path: Path) -> tuple[int, str]:
    proc = subprocess.run([*BETV, "check", str(path)], capture_output=True, text=True, check=False)
    return proc.returncode, proc.stderr


@pytest.mark.parametrize(
    ("path", "line", "value"),
    [
        ("drive.frequency", "frequency: 3 kHz", "1e-300 Hz"),
        ("drive.voltage", "voltage: 9 V", "5e-324 V"),
        ("contact.impact_angle", "impact_angle: 20.56 deg", "1e-300 deg"),
    ],
)
def test_a_value_betv_check_refuses_is_refused_by_the_control(
    path: str, line: str, value: str, tmp_path: Path
) -> None:
    """The page refuses what `betv check` refuses in a file, with its message; the last
    good design stays and is what Save writes."""
    src = tmp_path / "push_demo.yaml"
    shutil.copy(DEVICES / "push_demo.yaml", src)
    d = Design.from_file(src)
    d.apply({"slider.beam_width": "12 um"})
    good = d.spec
    with pytest.raises(SpecError) as exc:
        d.apply({path: value})
    assert d.spec == good and path not in d.edits
    bad = tmp_path / "bad.yaml"
    assert line in d.text
    bad.write_text(d.text.replace(line, f"{line.split(':')[0]}: {value}", 1))
    rc, err = _check_stderr(bad)
    assert rc == 2 and "Traceback" not in err
    assert exc.value.issues[0].message in err
    saved = d.save("saved.yaml")
    assert saved.written and load_device(saved.path) == good


def test_a_value_whose_derivation_fails_is_refused_as_betv_check_refuses_the_file(
    tmp_path: Path,
) -> None:
    """A voltage where the measured calibration gives no stroke loads, but the model
    cannot take it: `betv check` refuses the file (exit 2), so the control refuses the
    value with the same message, and the design stays."""
    base = (Path(__file__).parent / "data" / "specs" / "zero_amplitude.yaml").read_text()
    good = tmp_path / "good.yaml"
    good.write_text(base.replace("      voltage: 1 V", "      voltage: 2 V"))
    d = Design.from_file(good)
    before = d.spec
    with pytest.raises(SpecError) as exc:
        d.apply({"drive.voltage": "1 V"})
    assert d.spec == before and not d.edits
    bad = tmp_path / "bad.yaml"
    bad.write_text(base)
    rc, err = _check_stderr(bad)
    assert rc == 2
    message = exc.value.issues[0].message
    assert message.startswith("derived parameters outside the model") and message in err
    with pytest.raises(SpecError, match="derived parameters outside the model"):
        Design.from_file(bad)  # the server does not start on it either


def test_no_mode_before_the_stage_that_decides_it() -> None:
    """The orbit stage shows "computing" for the verdict, the modes and speeds; the
    settling stage shows `betv check`'s own (here with a mode the orbit alone got)."""
    from betvdesign.explore.views import verdict_html

    spec = load_device(DEVICES / "push_demo.yaml")
    orbit = evaluate(spec, "orbit")
    assert orbit.out["sets"][0]["mode"] == "push"  # what the orbit alone says
    html = verdict_html(orbit.out, seq=1, stage="orbit")
    assert 'data-mode="computing"' in html and 'data-verdict="computing"' in html
    assert "push" not in html and "PASS" not in html and 'data-speed-m-s=""' in html
    settled = evaluate(spec, "settling")
    html = verdict_html(settled.out, seq=1, stage="settling")
    mode = settled.out["sets"][0]["mode"]
    assert f'data-mode="{mode}"' in html and f'data-verdict="{settled.out["verdict"]}"' in html


# --- signals (issue 32, item 4) --------------------------------------------------------------


@pytest.mark.slow
def test_ctrl_c_while_a_worker_starts_is_no_traceback(capfd: pytest.CaptureFixture[str]) -> None:
    """A SIGINT that reaches a worker while it starts (the whole process group gets a
    Ctrl-C) neither kills it nor prints a KeyboardInterrupt traceback: it answers."""
    import os
    import signal
    import threading

    from betvdesign.explore import jobs

    w = jobs.Workers()
    results: list[object] = []
    got = threading.Event()

    def done(value: object) -> None:
        results.append(value)
        got.set()

    def failed(exc: BaseException) -> None:
        results.append(exc)
        got.set()

    lane = w.lanes["check"]
    try:
        with lane.lock:
            lane._ensure()
        os.kill(lane.proc.pid, signal.SIGINT)  # still starting: importing, before _init
        gen = w.bump("check", 5)
        w.submit("check", 5, gen - 1, jobs.check_job, ("", "p.yaml", "orbit", {}), done, failed)
        assert got.wait(300) and results == [None], results  # a stale job: None, answered
        got.clear()
        os.kill(lane.proc.pid, signal.SIGINT)  # started: ignored as well
        w.submit("check", 5, gen - 1, jobs.check_job, ("", "p.yaml", "orbit", {}), done, failed)
        assert got.wait(300) and results == [None, None], results
    finally:
        w.close()
    err = capfd.readouterr().err
    assert "KeyboardInterrupt" not in err and "Traceback" not in err, err


def test_a_server_started_in_the_background_stops_on_sigint(tmp_path: Path) -> None:
    """`betv explore FILE &` from a script inherits SIGINT ignored (a shell without job
    control does that); `kill -INT` must still stop it cleanly."""
    import signal
    import time

    from conftest import require_module

    require_module("bokeh", extra="explore")
    import socket

    shutil.copy(DEVICES / "push_demo.yaml", tmp_path / "push_demo.yaml")
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = str(s.getsockname()[1])
    proc = subprocess.Popen(
        [*BETV, "explore", "push_demo.yaml", "--no-browser", "--port", port],
        cwd=tmp_path,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_IGN),
    )
    try:
        assert proc.stdout is not None
        line = proc.stdout.readline()  # the URL: the server listens
        assert "http://127.0.0.1:" in line, line + proc.stderr.read()
        t0 = time.monotonic()
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=60)
        assert time.monotonic() - t0 < 30
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert proc.returncode == 0, err
    assert "stopped" in out and "Traceback" not in err, err


# --- saving (issue 32, item 5) -----------------------------------------------------------------


def test_save_writes_beside_the_device_file_or_says_why_not(tmp_path: Path) -> None:
    """An empty name, an absolute path, `~`, `..` or a folder are refused with a message
    naming the device file's folder; nothing is written anywhere; only an existing file
    offers an overwrite."""
    import uuid

    folder = tmp_path / "dev"
    folder.mkdir()
    src = folder / "push_demo.yaml"
    shutil.copy(DEVICES / "push_demo.yaml", src)
    d = Design.from_file(src)
    d.apply({"slider.beam_width": "12 um"})
    unique = f"betv-{uuid.uuid4().hex}.yaml"
    elsewhere = tmp_path / "elsewhere" / unique
    elsewhere.parent.mkdir()
    names = ["", "   ", str(elsewhere), f"~/{unique}", f"../{unique}", f"sub/{unique}", ".."]
    for name in names:
        res = d.save(name)
        assert not res.written and not res.exists, name
        assert str(folder) in res.message, res.message
    home = Path("~").expanduser() / unique
    assert not elsewhere.exists() and not home.exists() and not (tmp_path / unique).exists()
    assert sorted(p.name for p in folder.iterdir()) == ["push_demo.yaml"]
    res = d.save(unique)
    assert res.written and res.path == folder / unique
    again = d.save(unique)
    assert not again.written and again.exists
    assert load_device(folder / unique) == d.spec


def test_undo_goes_back_step_by_step_and_reset_is_a_step() -> None:
    """Each applied change is one undo step (the design read from the file with the
    changes before it, an independent path); ``merge`` joins a change to the step before
    it; a refused change is no step; reset goes back to the file and can be undone."""
    path = DEVICES / "push_demo.yaml"
    d = Design.from_file(path)
    file_spec = load_device(path)
    d.apply({"drive.frequency": "3.2 kHz"})
    d.apply({"slider.beam_width": "12 um"})
    with pytest.raises(SpecError):
        d.apply({"contact.friction": 7.0})
    assert d.undo()
    assert d.spec == file_spec.replace("drive.frequency", "3.2 kHz")
    assert d.edits == {"drive.frequency": "3.2 kHz"}
    assert d.undo() and d.spec == file_spec and not d.edits
    assert not d.undo() and d.spec == file_spec
    d.apply({"contact.friction": 0.3})
    d.apply({"contact.friction": 0.31}, merge=True)  # one drag
    d.apply({"contact.friction": 0.32}, merge=True)
    assert d.spec == file_spec.replace("contact.friction", 0.32)
    d.reset()
    assert d.spec == file_spec and d.yaml_text() == path.read_text()
    assert d.undo() and d.spec == file_spec.replace("contact.friction", 0.32)
    assert d.undo() and d.spec == file_spec and not d.undo()


def test_host_rule_refuses_every_name_but_the_local_ones() -> None:
    """The server's host pattern (Tornado adds the end anchor and matches the Host
    header's name): only 127.0.0.1, localhost and [::1] pass."""
    import re

    from betvdesign.explore.server import FOREIGN_HOST

    foreign = re.compile(FOREIGN_HOST + "$")
    for host in ("127.0.0.1", "localhost", "[::1]"):
        assert not foreign.match(host), host
    for host in ("evil.example", "127.0.0.1.evil.example", "localhost.evil", "127.0.0.2", ""):
        assert foreign.match(host), host


def test_slider_values_read_in_the_fields_units() -> None:
    """What the slider's tooltip and a screen reader say: the file's value and unit,
    µ written as such (push_demo: 3 kHz, 10 um)."""
    fields = {c.field: c for c in designer_fields(load_device(DEVICES / "push_demo.yaml"), 0)}
    freq, width = fields["drive.frequency"], fields["slider.beam_width"]
    assert freq.shown(freq.value) == "3 kHz" and freq.log
    assert width.shown(width.value) == "10 µm" and width.text(width.value) == "10 um"
    assert fields["contact.friction"].shown(0.4) == "0.4"
    assert fields["slider.beam_count"].shown(2) == "2"
