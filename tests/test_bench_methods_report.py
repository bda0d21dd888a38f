"""The methods report (betvdesign.report.methods, ``betv report --methods``).

Sources: the rendered HTML parsed back (sections, failure-map rows = the catalogue,
inline SVG figures, no external references), byte-reproducibility of two renders of
the same rows, the PDF read back with pypdf (pages, text), CLI runs (CliRunner), and
a real browser (chromium, headless) loading the HTML from file://.
"""

from __future__ import annotations

import json
import re

import pytest
from pypdf import PdfReader
from test_browser import browser  # noqa: F401 - the chromium fixture, shared
from typer.testing import CliRunner

from betvdesign.bench.chart import write_outputs
from betvdesign.bench.failuremap import scan, write_failure_map
from betvdesign.bench.failures import FAILURES
from betvdesign.bench.workprecision import Row
from betvdesign.cli import app
from betvdesign.report.methods import build, render_html, write_methods_report


def _rows() -> list[Row]:
    """Measured-looking rows for two methods (the report only lays them out)."""
    out = []
    for metric in ("s_N", "delta_s"):
        out.append(Row("exact", "closed-form events", "pull", metric, 1e-12, 1e-3, "success", ""))
        for rt, err, sec in ((1e-8, 1e-7, 4e-2), (1e-11, 1e-10, 6e-2)):
            out.append(
                Row("solve_ivp-DOP853", f"rtol={rt:.0e}", "pull", metric, err, sec, "success", "")
            )
    return out


@pytest.fixture(scope="module")
def fm():
    """A real (tiny) failure-map scan: two frequencies, two cycles."""
    return scan([0.9, 1.5], cycles=2)


@pytest.fixture(scope="module")
def html(fm):
    return render_html(build(_rows(), fm))


def test_sections_and_failure_map(html):
    for sec in ("work-precision", "failure-map", "ladder", "reproduce"):
        assert f'<section id="{sec}">' in html
    for f in FAILURES:
        assert f'id="failure-{f.id}"' in html
    assert html.count("<svg") == 3  # chart, failure map along ϖ, λ disagreement bars
    assert "×40" in html and "×60" not in html  # ratio: DOP853 1e-8 (4e-2 s) / exact 1e-3 s


def test_self_contained_and_reproducible(html, fm):
    assert not re.search(r'(src|href)="(https?:)?//', html)
    assert "<script" not in html
    assert render_html(build(_rows(), fm)) == html


def test_pdf_and_cli(tmp_path, fm):
    written = write_methods_report(tmp_path / "a", rows=_rows(), fm_rows=fm)
    pdf = PdfReader(str(written[1]))
    text = "".join(p.extract_text() for p in pdf.pages)
    assert len(pdf.pages) >= 3
    assert "Failure map" in text and "Fidelity ladder" in text
    write_outputs(_rows(), tmp_path / "wp")
    write_failure_map(fm, tmp_path / "wp")  # found beside the rows: no live scan
    res = CliRunner().invoke(
        app,
        [
            "report",
            "--methods",
            str(tmp_path / "wp" / "work_precision.json"),
            "-o",
            str(tmp_path / "b"),
            "--no-pdf",
        ],
    )
    assert res.exit_code == 0, res.output
    assert (tmp_path / "b" / "methods.html").read_text() == written[0].read_text()


def test_cli_bad_rows_file(tmp_path):
    bad = tmp_path / "rows.json"
    bad.write_text(json.dumps({"nope": 1}))
    res = CliRunner().invoke(app, ["report", "--methods", str(bad), "-o", str(tmp_path / "o")])
    assert res.exit_code == 2
    assert "not a work-precision JSON" in res.stderr
    assert not (tmp_path / "o" / "methods.html").exists()


@pytest.mark.browser
def test_methods_report_in_chromium(browser, html, tmp_path):  # noqa: F811
    """Real browser (chromium via playwright, from file://): no console errors, no
    network requests, all three figures laid out with a real size."""
    path = tmp_path / "methods.html"
    path.write_text(html)
    page = browser.new_page(viewport={"width": 1100, "height": 900})
    errors: list[str] = []
    foreign: list[str] = []
    page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.on(
        "request", lambda r: None if re.match(r"(file|data):", r.url) else foreign.append(r.url)
    )
    page.goto(path.resolve().as_uri(), wait_until="load")
    figures = page.locator("figure.fig")
    assert figures.count() == 3
    for i in range(3):
        box = figures.nth(i).locator("svg").first.bounding_box()
        assert box is not None and box["width"] > 200 and box["height"] > 120, (i, box)
    page.screenshot(path=str(tmp_path / "methods.png"), full_page=True)
    page.close()
    assert errors == [] and foreign == []
