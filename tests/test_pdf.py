"""The PDF report, checked with poppler-utils (an independent PDF implementation).

pdfinfo: A4 pages, page count; pdffonts: every font embedded; pdftotext: the
verdict and the derived parameters are in the text layer; pdftoppm: every page
renders to a non-blank image. Skips only outside CI when poppler-utils is
missing (reason printed); under CI=1 it fails.
"""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest
from conftest import device_files, require_program

from betvdesign.nondim.device import derive
from betvdesign.report.build import fmt_num
from betvdesign.spec.loader import load_device

pytestmark = [pytest.mark.pdf, pytest.mark.slow]  # the reports of every device: ~1 min


def run(*args: str) -> str:
    return subprocess.run(args, capture_output=True, text=True, check=True, timeout=120).stdout


@pytest.mark.parametrize("device", device_files(), ids=lambda p: p.stem)
def test_pdf_pages_fonts_text(reports_dir: Path, device: Path) -> None:
    pdfinfo = require_program("pdfinfo")
    pdffonts = require_program("pdffonts")
    pdftotext = require_program("pdftotext")
    pdf = reports_dir / f"{device.stem}.pdf"
    info = run(pdfinfo, str(pdf))
    pages = int(re.search(r"^Pages:\s+(\d+)", info, re.M).group(1))
    assert 3 <= pages <= 30
    size = re.search(r"^Page size:\s+([\d.]+) x ([\d.]+) pts", info, re.M)
    assert (round(float(size.group(1))), round(float(size.group(2)))) == (595, 842)  # A4
    assert re.search(r"^Title:\s+BETV design report", info, re.M)
    assert not re.search(r"^(CreationDate|ModDate):", info, re.M)  # no timestamp by default
    fonts = run(pdffonts, str(pdf)).splitlines()[2:]
    assert fonts, "no fonts in the PDF"
    for line in fonts:
        cols = line.split()
        assert cols[-5] == "yes", f"font not embedded: {line}"  # the 'emb' column
    text = re.sub(r"\s+", " ", run(pdftotext, "-layout", str(pdf), "-"))
    assert re.search(r"Device verdict: (PASS|FAIL)", text)
    for s in derive(load_device(device)).sets:
        assert f"ϖ = {fmt_num(s.params.varpi)}" in text
        assert f"β = {fmt_num(s.params.beta)}" in text
    assert text.count("Model:") >= 6


def test_pdf_every_page_renders(reports_dir: Path, tmp_path: Path) -> None:
    """pdftoppm renders every page of shin2004.pdf; no page is blank."""
    pdfinfo = require_program("pdfinfo")
    pdftoppm = require_program("pdftoppm")
    pdf = reports_dir / "shin2004.pdf"
    pages = int(re.search(r"^Pages:\s+(\d+)", run(pdfinfo, str(pdf)), re.M).group(1))
    run(pdftoppm, "-r", "40", "-gray", str(pdf), str(tmp_path / "p"))
    images = sorted(tmp_path.glob("p-*.pgm"))
    assert len(images) == pages
    for img in images:
        data = img.read_bytes()
        # PGM: header "P5\nW H\n255\n" then one byte per pixel; a blank page is all 255.
        pixels = data[data.index(b"255\n") + 4 :]
        inked = sum(1 for b in pixels if b < 200)
        assert inked > 200, f"{img.name} looks blank ({inked} inked pixels)"


def test_timestamp_only_on_request(tmp_path: Path) -> None:
    """--timestamp prints the generation time and run times in the HTML and puts a
    creation date into the PDF metadata; by default neither has one (checked above)."""
    from betvdesign.report import ReportOptions, build_report, prepare, render_html, render_pdf
    from betvdesign.report.model import Report

    pdfinfo = require_program("pdfinfo")
    stamp = "2026-01-02T03:04:05+00:00"
    report = build_report(
        prepare(device_files()[0]),
        generated=stamp,
        options=ReportOptions(regime_points=5, robustness_points=8),
    )
    html = render_html(report)
    assert f"generated {stamp}" in html and "Run time: periodic" in html
    # The PDF metadata comes from the page head alone: a report model without sets
    # (plain data) is enough to check it, in a fraction of the time.
    bare = Report(
        "T", "d", "", "d.yaml", "pass", (), (), "betv report d.yaml", "0", generated=stamp
    )
    out = tmp_path / "t.pdf"
    out.write_bytes(render_pdf(render_html(bare)))
    assert re.search(r"^CreationDate:.*2026", run(pdfinfo, str(out)), re.M)
