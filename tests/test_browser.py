"""The HTML report in a real browser: Debian's chromium, headless, via playwright.

Source: the browser itself. The page is loaded from file://; any console error,
page error or request to something other than file:/data: fails the test; every
figure must be laid out with a non-trivial size; a full-page screenshot is saved
in the test's tmp dir. Skips only outside CI when chromium is missing (reason
printed); under CI=1 a missing chromium fails.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest
from conftest import require_program

pytestmark = [pytest.mark.browser, pytest.mark.slow]  # chromium and every report

CHROMIUM_ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]


@pytest.fixture(scope="module")
def browser():
    exe = require_program("chromium", candidates=("/usr/bin/chromium",))
    try:
        from playwright import sync_api
    except ImportError as exc:  # the test extra installs it; skipping is only for dev boxes
        if os.environ.get("CI"):
            pytest.fail(f"CI: playwright not importable: {exc}")
        pytest.skip(f"playwright not importable: {exc}")
    with sync_api.sync_playwright() as pw:
        b = pw.chromium.launch(executable_path=exe, args=CHROMIUM_ARGS, headless=True)
        try:
            yield b
        finally:
            b.close()


@pytest.mark.parametrize("name", ["shin2004", "push_demo"])
def test_report_in_chromium(browser, reports_dir: Path, tmp_path: Path, name: str) -> None:
    """No console errors, no network requests, every figure laid out with a real size."""
    page = browser.new_page(viewport={"width": 1100, "height": 900})
    errors: list[str] = []
    foreign: list[str] = []
    page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.on(
        "request",
        lambda r: None if re.match(r"(file|data):", r.url) else foreign.append(r.url),
    )
    url = (reports_dir / f"{name}.html").resolve().as_uri()
    page.goto(url, wait_until="load")
    page.wait_for_load_state("networkidle")
    assert page.title().startswith("BETV design report")
    figures = page.locator("figure.fig")
    n = figures.count()
    assert n >= 6
    for i in range(n):
        fig = figures.nth(i)
        svg = fig.locator("svg")
        assert svg.count() == 1, f"figure {i + 1} has no inline SVG"
        box = svg.first.bounding_box()
        assert box is not None and box["width"] > 200 and box["height"] > 120, (i, box)
        caption = fig.locator("figcaption").inner_text()
        assert f"Figure {i + 1}." in caption and "Model:" in caption
    verdict = page.locator(".overall").inner_text()
    assert re.search(r"Device verdict: (PASS|FAIL)", verdict)
    shot = tmp_path / f"{name}.png"
    page.screenshot(path=str(shot), full_page=True)
    assert shot.stat().st_size > 50_000
    page.close()
    assert errors == [], errors
    assert foreign == [], foreign


def test_missing_program_fails_under_ci_and_skips_elsewhere(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The rule of these tests: a missing chromium/poppler skips only outside CI."""
    monkeypatch.setenv("CI", "1")
    with pytest.raises(pytest.fail.Exception, match="CI: no-such-program-betv not found"):
        require_program("no-such-program-betv")
    monkeypatch.delenv("CI")
    with pytest.raises(pytest.skip.Exception, match="no-such-program-betv not found"):
        require_program("no-such-program-betv")
