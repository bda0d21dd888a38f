"""Design reports (betv report): content, self-containment, reproducibility, CLI.

Sources: the derived parameters are checked against :func:`betvdesign.nondim.device.derive`
(the report must show the derivation's numbers); shin2004's verdict against
docs/MODEL.md, "The published device" (its dimensional data give ϖ ≈ 0.34, below
the 0.5 ≤ ϖ < 2 window: a failing design); push_demo's predicted mode against a
transient run of the exact solver (Δs > 0 after settling: push); self-containment
by parsing the HTML; reproducibility by two independent runs; the CLI with
typer's CliRunner.
"""

from __future__ import annotations

import math
import re
from html.parser import HTMLParser
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from conftest import DEVICES, device_files
from typer.testing import CliRunner

from betvdesign import dynamics
from betvdesign.cli import app
from betvdesign.nondim.device import derive
from betvdesign.output.files import write_atomic
from betvdesign.report import ReportOptions, build_report, prepare, render_html, write_reports
from betvdesign.report import analysis as report_analysis
from betvdesign.report.analysis import FULL_ONLY
from betvdesign.report.build import fmt_num
from betvdesign.report.variants import shown_fields
from betvdesign.spec.loader import load_device

#: Section 4's figures per distinct set of the full report (the exact-mode map first),
#: plus the model-adequacy and the speed-against-frequency figures (section 5).
FIGURES_PER_SET = 1 + 7 + 2
#: The same in the default report: the four diagnostics are drawn with --full only.
SHORT_FIGURES_PER_SET = FIGURES_PER_SET - len(FULL_ONLY)
#: Small sweeps for tests about rendering (every figure), not about the numbers.
SMALL = ReportOptions(regime_points=5, robustness_points=8, full=True)


class _Scan(HTMLParser):
    """Collect tags, attributes, ids and the visible text of a document."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.tags: list[tuple[str, dict[str, str | None]]] = []
        self.text: list[str] = []
        self._skip = 0

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        self.tags.append((tag, dict(attrs)))
        if tag in ("style", "svg"):
            self._skip += 1

    def handle_endtag(self, tag: str) -> None:
        if tag in ("style", "svg"):
            self._skip -= 1

    def handle_data(self, data: str) -> None:
        if not self._skip:
            self.text.append(data)


def scan(html: str) -> _Scan:
    s = _Scan()
    s.feed(html)
    return s


def text_of(html: str) -> str:
    return re.sub(r"\s+", " ", " ".join(scan(html).text))


def distinct_sets(path: Path) -> int:
    der = derive(load_device(path))
    keys = {(tuple(s.params.as_dict().values()), s.scales) for s in der.sets}
    return len(keys)


def expected_figures(path: Path, *, full: bool = True) -> int:
    """FIGURES_PER_SET (SHORT_FIGURES_PER_SET: the default report) per distinct set (every
    device has a speed-frequency figure, with or without a thermal cut-off), and u(V),
    u(f) per distinct set whose stroke is predicted from the drawing
    (:mod:`betvdesign.report.thermal`)."""
    der = derive(load_device(path))
    drawn = {(tuple(s.params.as_dict().values()), s.scales) for s in der.sets if s.stroke}
    per_set = FIGURES_PER_SET if full else SHORT_FIGURES_PER_SET
    return per_set * distinct_sets(path) + 2 * len(drawn)


@pytest.mark.slow
@pytest.mark.parametrize("device", device_files(), ids=lambda p: p.stem)
def test_report_content(reports_dir: Path, device: Path) -> None:
    """Verdict box, derived parameters (from nondim.derive), rules, every figure of the
    default report with a caption naming its model, the note naming the figures drawn
    with --full only, provenance and the reproduce command."""
    html = (reports_dir / f"{device.stem}.html").read_text("utf-8")
    assert (reports_dir / f"{device.stem}.pdf").stat().st_size > 10_000
    text = text_of(html)
    der = derive(load_device(device))
    assert re.search(r"Device verdict: (PASS|FAIL)", text)
    for s in der.sets:
        assert f"Actuator set “{s.name}”" in text
        assert f"Intended mode {s.intended_mode}" in text
        p = s.params
        for sym, val in (("ϖ", p.varpi), ("α", p.alpha), ("β", p.beta), ("κ", p.kappa)):
            assert f"{sym} = {fmt_num(val)}" in text, sym
        assert f"λ = {fmt_num(s.lam)}" in text
    for needle in (
        "1. Verdict",
        "2. Device inputs",
        "3. Design rules",
        "4. Figures",
        "5. Model adequacy",
        "6. Numerical provenance",
        f"betv report {device}",
    ):
        assert needle in text
    n_fig = expected_figures(device, full=False)
    figs = [a for t, a in scan(html).tags if t == "figure"]
    assert len(figs) == n_fig
    captions = re.findall(r"Figure (\d+)\. ([^.]+)\.", text)
    assert [int(n) for n, _ in captions] == list(range(1, n_fig + 1))
    assert text.count("Model: ") == n_fig
    for title in (
        "Where the mode holds: exact-mode map",
        "Mean speed against actuation frequency",
        "Slider displacement",
        "Mean speed against drive",
        "Robustness",
        "Model adequacy: mode and speed against damping and restitution",
    ):
        assert title in text
    for title in FULL_ONLY:
        assert f". {title}." not in text, title
    assert text.count("Drawn with betv report --full only: Push/pull map") == distinct_sets(device)
    # Every number shown for an input is the file's own text.
    assert "slider.travel_range" in text


@pytest.mark.slow
@pytest.mark.parametrize("device", device_files(), ids=lambda p: p.stem)
def test_verdict_and_rules_agree_with_betv_check(reports_dir: Path, device: Path) -> None:
    """Second path: ``betv check`` (checker.check_derivation, which runs the solver
    itself) gives the same verdict and the same rule outcomes as the report."""
    from betvdesign.checks.checker import check_derivation

    html = (reports_dir / f"{device.stem}.html").read_text("utf-8")
    check = check_derivation(derive(load_device(device)))
    assert f"Device verdict: <strong>{check.verdict.upper()}</strong>" in html
    rows = re.findall(
        r"<tr class=\"[^\"]*\"><td><code>([^<]+)</code></td><td>(\w+)</td>"
        r"<td class=\"num\">[^<]*</td><td>[^<]*</td><td>(pass|FAIL|warning|info)</td>",
        html,
    )
    shown = sorted((rid, sev, res == "pass") for rid, sev, res in rows)
    expected = sorted((r.id, r.severity, r.passed) for r in check.rules)
    assert shown == expected


@pytest.mark.slow
def test_shin2004_fails_with_reasons(reports_dir: Path) -> None:
    """MODEL.md: shin2004's data give ϖ ≈ 0.34 < 0.5, so the verdict is fail and the
    window rule is the first finding; the derivation shows where ϖ comes from."""
    text = text_of((reports_dir / "shin2004.html").read_text("utf-8"))
    assert "Device verdict: FAIL" in text
    assert "ϖ = 0.3401" in text and "ω·sqrt(m/k_v)" in text
    assert "frequency-window" in text
    assert "2·f_drive" in text  # AC doubling shown


@pytest.mark.slow
def test_push_demo_predicts_push(reports_dir: Path) -> None:
    """push_demo: the exact solver's transient settles to Δs > 0 (push); the report's
    predicted mode says push."""
    from betvdesign.dynamics.solver import simulate

    der = derive(load_device(DEVICES / "push_demo.yaml"))
    tr = simulate(der.sets[0].params, 300)
    assert tr.success and tr.delta_s[-1] > 0
    text = text_of((reports_dir / "push_demo.html").read_text("utf-8"))
    assert re.search(r"Predicted mode push", text)
    assert "uses the coupled head" not in text  # its file gives the resonances


@pytest.mark.slow
@pytest.mark.parametrize("device", device_files(), ids=lambda p: p.stem)
def test_html_is_self_contained(reports_dir: Path, device: Path) -> None:
    """No script, no external resource, unique ids, every #reference resolves."""
    html = (reports_dir / f"{device.stem}.html").read_text("utf-8")
    doc = scan(html)
    tags = {t for t, _ in doc.tags}
    assert not tags & {"script", "link", "iframe", "object", "embed", "img", "video", "audio"}
    ids = [a["id"] for _, a in doc.tags if a.get("id")]
    assert len(ids) == len(set(ids)), "duplicate ids"
    for _, attrs in doc.tags:
        for name in ("href", "xlink:href", "src"):
            ref = attrs.get(name)
            if ref is not None:
                assert ref.startswith("#") and ref[1:] in ids, ref
    for ref in re.findall(r"url\(([^)]*)\)", html):
        assert ref.startswith("#") and ref[1:] in ids, ref
    assert "http://" not in html.replace("http://www.w3.org/", "")
    assert "https://" not in html


@pytest.mark.slow
def test_reports_are_byte_reproducible(reports_dir: Path, tmp_path: Path) -> None:
    """A second, independent run writes byte-identical HTML and PDF (shin2004: the
    device with the most content: failing rules, two sets, every figure)."""
    again = write_reports([DEVICES / "shin2004.yaml"], tmp_path)
    for w in again:
        for suffix in (".html", ".pdf"):
            first = (reports_dir / f"{w.source.stem}{suffix}").read_bytes()
            second = (tmp_path / f"{w.source.stem}{suffix}").read_bytes()
            assert first == second, f"{w.source.stem}{suffix} differs between runs"


@pytest.mark.slow
def test_template_autoescapes_device_text(tmp_path: Path) -> None:
    """Text from the device file is escaped, never interpreted as HTML, in the page and
    in the figures' SVG text (the set name labels the push/pull map)."""
    src = (DEVICES / "push_demo.yaml").read_text("utf-8")
    src = re.sub(
        r"^description:.*$",
        "description: '<script>alert(1)</script> & <b>x</b>'",
        src,
        flags=re.M,
    )
    src = src.replace("name: forward", "name: '<i>fwd</i>'")
    f = tmp_path / "evil.yaml"
    f.write_text(src, "utf-8")
    html = render_html(build_report(prepare(f), options=SMALL))
    assert "<script>" not in html and "<b>x</b>" not in html and "<i>fwd" not in html
    assert "&lt;script&gt;alert(1)&lt;/script&gt; &amp; &lt;b&gt;x&lt;/b&gt;" in html
    assert "&lt;i&gt;fwd&lt;/i&gt;" in html


def test_write_atomic_leaves_no_partial_file(tmp_path: Path) -> None:
    """A failing write keeps the old file and removes its temporary file."""
    target = tmp_path / "r.html"
    write_atomic(target, "old")
    with pytest.raises(TypeError):
        write_atomic(target, object())  # type: ignore[arg-type]
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["r.html"]


def test_missing_solver_is_stated_not_invented(monkeypatch: pytest.MonkeyPatch) -> None:
    """Without the exact solver, the verdict box and the figures that rest on the
    report's own orbits say why; no speed is shown."""

    def unavailable(*args: object, **kwargs: object) -> None:
        raise report_analysis.Missing("the exact solver is not available (test)")

    for name in ("periodic_orbit", "vertical_motion", "simulate"):
        monkeypatch.setattr(dynamics, name, unavailable)
    # the transient from rest (which decides when there is no orbit) is the same solver
    from betvdesign.dynamics import settling as settling_module

    monkeypatch.setattr(settling_module, "simulate", unavailable)
    report_analysis._vertical.cache_clear()  # the regime strip caches per ϖ
    report = build_report(prepare(DEVICES / "push_demo.yaml"), options=ReportOptions(full=True))
    box = report.sets[0].verdict
    assert box.speed.startswith("not available") and "(test)" in box.speed
    assert "not available" in box.predicted_by and box.predicted_mode == "unknown"
    assert box.verdict == "fail"  # no verdict without the exact orbit
    figs = report.figures()
    # λ needs no solver; the mode map, the regime strip and the adequacy scan are studies
    # that solve their own points (a point whose solve raises is a failed point)
    drawn = [f.key for f in figs if f.svg is not None]
    assert drawn == ["s1-modemap", "s1-pushpull", "s1-regime", "s1-adequacy"]
    assert all("(test)" in (f.unavailable or "") for f in figs if f.svg is None)
    text = text_of(render_html(report))
    assert text.count("Not drawn:") == len(figs) - len(drawn)
    report_analysis._vertical.cache_clear()  # drop the failures cached for ϖ


@pytest.mark.slow
def test_amplitude_without_calibration_says_why_no_voltage_curve(tmp_path: Path) -> None:
    """u given directly: the speed-voltage figure is not drawn and says it needs u(V);
    the other figures are drawn."""
    src = (DEVICES / "pull_demo.yaml").read_text("utf-8")
    src = re.sub(r"calibration:\n\s+law: linear\n\s+gain: [^\n]*\n", "amplitude: 0.09 um\n", src)
    assert "amplitude: 0.09 um" in src
    f = tmp_path / "amp.yaml"
    f.write_text(src, "utf-8")
    figs = build_report(prepare(f), options=SMALL).figures()
    speed = [x for x in figs if x.title.startswith("Mean speed against drive voltage")]
    assert len(speed) == 1 and speed[0].svg is None
    assert "not a calibration u(V)" in (speed[0].unavailable or "")
    assert sum(x.svg is not None for x in figs) == len(figs) - 1


def test_robustness_varies_designer_fields_through_the_spec() -> None:
    """The robustness sweep changes fields a designer sets (spec.fields, the list betv fix
    uses too), each through spec -> nondim: +10 % drive frequency is ϖ·1.1 (ϖ =
    2·f_drive/f_v), +10 % vertical resonance is ϖ/1.1 and α·1.21, +10 % tangential
    resonance is α/1.21 (α = (f_v/f_h)²), +10 % beam width is β/1.1 (β = m/M, M ∝ w
    without extra mass), +10 % head diameter is β·1.21 (m ∝ d²), friction κ·1.1 and the
    impact angle κ = μ·tan(1.1·θ) (κ = μ·tanθ); the 0 % point is the device itself. The
    drive voltage (it moves the stroke only), the beam length (the same quantity M as the
    width, listed later) and the head thickness (m, after the diameter) are left out."""
    from betvdesign.nondim.device import derive
    from betvdesign.report.variants import field_variants, relative_changes
    from betvdesign.spec.loader import load_device

    spec = load_device(DEVICES / "push_demo.yaml")
    p = derive(spec).sets[0].params
    changes = relative_changes(5, 0.2)
    assert list(changes) == pytest.approx([-0.2, -0.1, 0.0, 0.1, 0.2])
    vs = {(v.field, round(v.change, 3)): v for v in field_variants(spec, 0, changes)}
    assert list(dict.fromkeys(f for f, _ in vs)) == [
        "drive.frequency",
        "slider.beam_width",
        "head.geometry.diameter",
        "actuator.vertical_resonance",
        "actuator.horizontal_resonance",
        "contact.impact_angle",
        "contact.friction",
    ]
    assert vs[("drive.frequency", 0.1)].params.varpi == pytest.approx(1.1 * p.varpi, rel=1e-12)
    fv = vs[("actuator.vertical_resonance", 0.1)].params
    assert (fv.varpi, fv.alpha) == pytest.approx((p.varpi / 1.1, p.alpha * 1.21), rel=1e-12)
    assert vs[("actuator.horizontal_resonance", 0.1)].params.alpha == pytest.approx(
        p.alpha / 1.21, rel=1e-12
    )
    assert vs[("slider.beam_width", 0.1)].params.beta == pytest.approx(p.beta / 1.1, rel=1e-12)
    assert vs[("head.geometry.diameter", 0.1)].params.beta == pytest.approx(
        p.beta * 1.21, rel=1e-12
    )
    assert vs[("contact.friction", 0.1)].params.kappa == pytest.approx(1.1 * p.kappa, rel=1e-12)
    theta = math.radians(20.56)
    assert vs[("contact.impact_angle", 0.1)].params.kappa == pytest.approx(
        0.4 * math.tan(1.1 * theta), rel=1e-12
    )
    assert vs[("head.geometry.diameter", 0.0)].params == p
    assert vs[("drive.frequency", 0.0)].nominal == "3 kHz"


@pytest.mark.slow
def test_robustness_figure_speaks_designer_units(monkeypatch: pytest.MonkeyPatch) -> None:
    """Speed at 0 % equals the device's periodic speed; the figure's axes are the field
    change in % and the speed with an SI prefix, never α or λ.

    The speed is read off the plotted points (the matplotlib figure the SVG is written
    from, in the unit its axis label names) and checked against Δs·u·cosθ·f_act worked
    out by hand from push_demo.yaml (MODEL.md, "Displacement per cycle"): f_act = 2·3 kHz
    (AC doubling), f_v = 5 kHz, f_h = 3.5 kHz, u = 0.14 µm (linear between the measured
    8 V and 10 V points, at 9 V), θ = 20.56°, μ = 0.4, a 36 µm × 2.5 µm disc head against
    one 200 × 10 × 2.5 µm beam; Δs from the periodic orbit of those parameters."""
    from betvdesign import plots
    from betvdesign.dynamics import periodic_orbit
    from betvdesign.model.params import ModelParams

    drawn: dict[str, Any] = {}
    real = plots.figure_svg_png

    def keep(fig: Any, key: str, **kw: Any) -> tuple[str, bytes]:
        drawn[key] = fig
        return real(fig, key, **kw)

    monkeypatch.setattr(plots, "figure_svg_png", keep)
    report = build_report(prepare(DEVICES / "push_demo.yaml"), options=SMALL)
    fig = next(f for f in report.figures() if f.key.endswith("robustness"))
    assert fig.svg is not None
    text = " ".join(re.findall(r">([^<]+)<", fig.svg))
    assert "change of the field from its specified value" in text and "mm/s" in text
    assert "drive.frequency" in text and "λ  [-]" not in text
    assert "Specified values: drive.frequency = 3 kHz" in fig.caption

    theta = math.radians(20.56)
    f_act, u = 2 * 3e3, 0.11e-6 + (0.17e-6 - 0.11e-6) * (9 - 8) / (10 - 8)
    beta = (math.pi / 4 * 36**2 * 2.5) / (200 * 10 * 2.5)
    po = periodic_orbit(ModelParams(6 / 5, (5 / 3.5) ** 2, beta, 0.4 * math.tan(theta)))
    assert po.success and po.delta_s > 0  # push, the intended mode: plotted positive
    speed = po.delta_s * u * math.cos(theta) * f_act  # [m/s]

    ax = drawn[fig.key].axes[0]
    unit = re.search(r"\[(\S+)/s\]", ax.get_ylabel())
    assert unit, ax.get_ylabel()
    per = {"m": 1.0, "mm": 1e-3, "µm": 1e-6, "nm": 1e-9}[unit.group(1)]
    at_zero = {}
    for line in ax.get_lines():  # one marked, labelled line per field (not the 0 % rule)
        x, y = (np.asarray(v, dtype=float) for v in line.get_data())
        if line.get_marker() != "None" and not line.get_label().startswith("_") and 0 in x:
            at_zero[line.get_label()] = float(y[x == 0.0][0]) * per
    # one line per field the report varies (spec.fields, the one list), each through 0 %
    spec = load_device(DEVICES / "push_demo.yaml")
    assert set(at_zero) == {f for f, _ in shown_fields(spec, 0)}
    assert {"drive.frequency", "actuator.horizontal_resonance", "slider.beam_width"} <= set(at_zero)
    for name, v in at_zero.items():
        assert v == pytest.approx(speed, rel=1e-8), name


# --------------------------------------------------------------------------- CLI

runner = CliRunner()


@pytest.mark.slow
def test_cli_writes_reports_and_exit_codes(tmp_path: Path) -> None:
    """Exit 0 when written (even for a failing device); --strict turns a fail into 1."""
    shin = str(DEVICES / "shin2004.yaml")
    res = runner.invoke(app, ["report", shin, "-o", str(tmp_path / "a"), "--no-pdf"])
    assert res.exit_code == 0, res.output
    assert "verdict fail" in res.output
    assert "writing reports" in res.stderr and "2/2" in res.stderr  # progress: build, HTML
    assert (tmp_path / "a" / "shin2004.html").is_file()
    assert not (tmp_path / "a" / "shin2004.pdf").exists()
    res = runner.invoke(
        app, ["report", shin, "-o", str(tmp_path / "b"), "--no-pdf", "--strict", "-q"]
    )
    assert res.exit_code == 1 and "writing reports" not in res.stderr
    assert (tmp_path / "b" / "shin2004.html").is_file()  # written all the same


def test_cli_bad_input_writes_nothing(tmp_path: Path) -> None:
    """Bad input: the check's error (file:line: field), exit 2, no file written, even
    for the good file given alongside."""
    bad = tmp_path / "bad.yaml"
    src = (DEVICES / "push_demo.yaml").read_text("utf-8")
    bad.write_text(src.replace("beam_width: 10 um", "beam_width: -10 um"), "utf-8")
    out = tmp_path / "out"
    res = runner.invoke(app, ["report", str(DEVICES / "push_demo.yaml"), str(bad), "-o", str(out)])
    assert res.exit_code == 2
    assert re.search(r"bad\.yaml:\d+:\d+: slider\.beam_width", res.output), res.output
    assert "Traceback" not in res.output
    assert not out.exists() or not any(out.iterdir())


def test_cli_usage_errors(tmp_path: Path) -> None:
    clash = tmp_path / "sub"
    clash.mkdir()
    copy = clash / "push_demo.yaml"
    copy.write_text((DEVICES / "push_demo.yaml").read_text("utf-8"), "utf-8")
    res = runner.invoke(
        app, ["report", str(DEVICES / "push_demo.yaml"), str(copy), "-o", str(tmp_path / "o")]
    )
    assert res.exit_code == 2 and "would both write push_demo.html" in res.output
    res = runner.invoke(app, ["report", "-o", str(tmp_path / "o")])
    assert res.exit_code == 2 and "at least one device file" in res.output
    afile = tmp_path / "file"
    afile.write_text("x")
    res = runner.invoke(app, ["report", str(DEVICES / "push_demo.yaml"), "-o", str(afile)])
    assert res.exit_code == 2 and "not a directory" in res.output


def test_regime_strip_periods_follow_the_paper() -> None:
    """Report figure 2 classifies like the regime study (PAPER.md Figs 4, 5): the impact
    period equals the actuation period for 0.5 ≤ ϖ ≤ 2.6, impulsive hits included (they
    were drawn as "aperiodic" before); period doubling at ϖ = 2.9; aperiodic at ϖ = 4.8
    (no period of at most LONG_PERIOD cycles: a cross, never a dot at a long period)."""
    for w in (0.6, 1.5, 2.05, 2.3, 2.55):
        assert report_analysis._vertical(w)[0] == 1.0, w
    assert report_analysis._vertical(2.9)[0] == 2.0
    assert report_analysis._vertical(4.8)[0] is None


def test_figures_drawn_in_parallel_are_the_serial_bytes() -> None:
    """Figures drawn by forked worker processes (figures.batch) are byte-identical to
    the same figures drawn one by one in this process, HTML and PDF alike."""
    import multiprocessing

    from betvdesign.report.render import report_pdf

    if "fork" not in multiprocessing.get_all_start_methods():  # pragma: no cover
        pytest.skip("no fork on this system: figures are always drawn in-process")
    dev = prepare(DEVICES / "push_demo.yaml")
    serial = build_report(dev, options=SMALL, figure_workers=1)
    parallel = build_report(dev, options=SMALL, figure_workers=3)
    assert len(serial.figures()) == len(parallel.figures()) >= 8
    assert all(f.svg and f.png for f in serial.figures() if f.unavailable is None)
    assert render_html(parallel) == render_html(serial)
    assert report_pdf(parallel) == report_pdf(serial)


def test_weasyprint_import_runs_no_program(tmp_path: Path) -> None:
    """WeasyPrint is imported without ctypes' find_library running ldconfig/gcc (a
    fresh interpreter counts the programs started) and still renders a PDF."""
    import subprocess
    import sys

    script = (
        "import subprocess, sys\n"
        "runs = []\n"
        "real = subprocess.Popen.__init__\n"
        "def count(self, *a, **k):\n"
        "    runs.append(a[0] if a else k.get('args'))\n"
        "    real(self, *a, **k)\n"
        "subprocess.Popen.__init__ = count\n"
        "from betvdesign.report.render import render_pdf\n"
        "pdf = render_pdf('<p>x</p>')\n"
        "assert 'weasyprint' in sys.modules and pdf.startswith(b'%PDF'), pdf[:8]\n"
        "print(len(runs))\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, check=True, cwd=tmp_path
    )
    assert out.stdout.strip() == "0", out.stdout + out.stderr


def test_default_report_is_the_full_one_without_the_diagnostics() -> None:
    """The default report draws the full report's figures less the four diagnostics
    (FULL_ONLY), each the same SVG and PNG bytes under the same title and caption (no
    information of a kept figure is lost), with the same verdict and rules; the full
    report has exactly those four more."""
    dev = prepare(DEVICES / "pull_demo.yaml")
    small = {"regime_points": 5, "robustness_points": 3, "map_points": 3, "frequency_points": 5}
    short = build_report(dev, options=ReportOptions(**small))
    full = build_report(dev, options=ReportOptions(**small, full=True))
    kept = [f for f in full.figures() if f.title not in FULL_ONLY]
    assert sorted({f.title for f in full.figures()} - {f.title for f in kept}) == sorted(FULL_ONLY)
    assert [f.key for f in short.figures()] == [f.key for f in kept]
    for mine, theirs in zip(short.figures(), kept, strict=True):
        assert mine.svg and mine.png
        assert (mine.svg, mine.png, mine.title, mine.caption, mine.model) == (
            theirs.svg,
            theirs.png,
            theirs.title,
            theirs.caption,
            theirs.model,
        )
    for a, b in zip(short.sets, full.sets, strict=True):
        assert (a.verdict, a.rules, a.derivation, a.adequacy is None) == (
            b.verdict,
            b.rules,
            b.derivation,
            b.adequacy is None,
        )
        assert "--full" in a.notes[0] and not b.notes
    assert short.verdict == full.verdict


@pytest.mark.slow
def test_cli_full_draws_the_diagnostics(tmp_path: Path) -> None:
    """``betv report --full`` writes every figure and says so in its reproduce line;
    without it the four diagnostics are left out."""
    runner = CliRunner()
    for flag, n in (("--full", FIGURES_PER_SET), (None, SHORT_FIGURES_PER_SET)):
        out = tmp_path / (flag or "short")
        args = ["report", str(DEVICES / "push_demo.yaml"), "-o", str(out), "--no-pdf", "-q"]
        r = runner.invoke(app, [*args, *([flag] if flag else [])])
        assert r.exit_code == 0, r.output
        html = (out / "push_demo.html").read_text("utf-8")
        assert len(re.findall(r"<figure", html)) == n
        assert ("-o DIR --full" in html) == (flag is not None)
