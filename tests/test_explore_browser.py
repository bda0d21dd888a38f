"""``betv explore`` in a real browser: Debian's chromium, headless, via playwright.

Source: ``betv check --json`` of the design the page saved (run as the user runs it)
and the device file's own validation. The server is the real command
(``betv explore FILE --no-browser --port P``) on a copy of a shipped device; the page is
driven by keyboard and mouse. Any console error or warning, page error or request to
anything but the local server fails a test. Skips only outside CI when chromium, playwright or the
``explore`` extra (Bokeh) is missing; under CI=1 each of those fails, as in
``tests/test_browser.py``.
"""

from __future__ import annotations

import difflib
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from conftest import DEVICES, require_module, require_program
from test_browser import CHROMIUM_ARGS

from betvdesign.spec.loader import load_device

pytestmark = pytest.mark.browser

BETV = [sys.executable, "-c", "from betvdesign.cli import main; main()"]
#: Generous waits [ms]: the first page of a server loads the compiled kernels in its
#: workers; a loaded CI machine is slow. Speed is measured in benchmarks/, not here.
START_S = 240
WAIT_MS = 240_000


@dataclass
class Server:
    """A running ``betv explore`` and what it printed."""

    proc: subprocess.Popen
    url: str
    workdir: Path
    out: list[str] = field(default_factory=list)
    err: list[str] = field(default_factory=list)

    def stop(self) -> int:
        """Ctrl-C (SIGINT to the server's process), as a user stops it."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)
            try:
                self.proc.wait(timeout=60)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        time.sleep(0.2)  # the reader threads finish
        return int(self.proc.returncode)


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _start(device: str, tmp: Path) -> Server:
    require_module("bokeh", extra="explore")
    shutil.copy(DEVICES / f"{device}.yaml", tmp / f"{device}.yaml")
    port = _free_port()
    proc = subprocess.Popen(
        [*BETV, "explore", f"{device}.yaml", "--no-browser", "--port", str(port)],
        cwd=tmp,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    server = Server(proc, f"http://127.0.0.1:{port}/", tmp)
    ready = threading.Event()

    def read(stream, sink: list[str]) -> None:
        for line in stream:
            sink.append(line)
            if "http://127.0.0.1:" in line:
                ready.set()

    for stream, sink in ((proc.stdout, server.out), (proc.stderr, server.err)):
        threading.Thread(target=read, args=(stream, sink), daemon=True).start()
    if not ready.wait(START_S):
        server.stop()
        pytest.fail(f"betv explore did not start: {''.join(server.out + server.err)}")
    assert f"127.0.0.1:{port}" in "".join(server.out)
    return server


@pytest.fixture(scope="module")
def browser():
    exe = require_program("chromium", candidates=("/usr/bin/chromium",))
    try:
        from playwright import sync_api
    except ImportError as exc:
        if os.environ.get("CI"):
            pytest.fail(f"CI: playwright not importable: {exc}")
        pytest.skip(f"playwright not importable: {exc}")
    with sync_api.sync_playwright() as pw:
        b = pw.chromium.launch(executable_path=exe, args=CHROMIUM_ARGS, headless=True)
        try:
            yield b
        finally:
            b.close()


@pytest.fixture(scope="module")
def push_server(tmp_path_factory: pytest.TempPathFactory, browser) -> Iterator[Server]:
    server = _start("push_demo", tmp_path_factory.mktemp("explore-push"))
    try:
        yield server
    finally:
        server.stop()


@pytest.fixture(scope="module")
def shin_server(tmp_path_factory: pytest.TempPathFactory, browser) -> Iterator[Server]:
    server = _start("shin2004", tmp_path_factory.mktemp("explore-shin"))
    try:
        yield server
    finally:
        server.stop()


class Page:
    """A page of the explore server, with its console errors and foreign requests."""

    def __init__(self, browser, server: Server):
        self.p = browser.new_page(viewport={"width": 1650, "height": 1100}, accept_downloads=True)
        self.errors: list[str] = []
        self.foreign: list[str] = []
        local = server.url.rstrip("/")
        self.p.on(
            "console",
            lambda m: (
                self.errors.append(f"{m.type}: {m.text}")
                if m.type in ("error", "warning")
                else None
            ),
        )
        self.p.on("pageerror", lambda e: self.errors.append(str(e)))
        self.p.on(
            "request",
            lambda r: None if r.url.startswith(local) else self.foreign.append(r.url),
        )
        self.p.goto(server.url)
        self.full(self.seq_now())

    def seq_now(self) -> int:
        v = self.p.locator(".betv-verdict").first
        v.wait_for(timeout=WAIT_MS)
        return int(v.get_attribute("data-seq"))

    def wait_seq(self, seq: int, stage: str | None = None) -> None:
        sel = f"[data-seq='{seq}']" + (f"[data-stage='{stage}']" if stage else "")
        self.p.locator(sel).first.wait_for(timeout=WAIT_MS)

    def full(self, seq: int) -> None:
        self.wait_seq(seq, "full")

    def shown(self) -> dict:
        """Verdict, and per set its mode and speed, as the page shows them."""
        v = self.p.locator(".betv-verdict").first
        sets = {}
        rows = self.p.locator("tr.betv-set")
        for i in range(rows.count()):
            r = rows.nth(i)
            speed = r.get_attribute("data-speed-m-s")
            sets[r.get_attribute("data-set")] = (
                r.get_attribute("data-mode"),
                None if not speed else float(speed),
            )
        return {"verdict": v.get_attribute("data-verdict"), "sets": sets}

    def text(self, field: str) -> str:
        return self.p.locator(f".betv-field-{field}.betv-text input").input_value()

    def close(self) -> None:
        self.p.close()
        assert self.errors == [], self.errors
        assert self.foreign == [], self.foreign


def _check_json(path: Path) -> dict:
    proc = subprocess.run(
        [*BETV, "check", "--json", str(path)], capture_output=True, text=True, check=False
    )
    assert proc.returncode in (0, 1), proc.stderr
    return json.loads(proc.stdout)["devices"][0]


def test_keyboard_moves_save_and_betv_check_agree(browser, push_server: Server) -> None:
    """Move the drive frequency by keyboard; the verdict, modes and speeds shown equal
    `betv check --json` of the design saved to YAML; only the changed lines differ."""
    page = Page(browser, push_server)
    seq = page.seq_now()
    before = page.text("drive-frequency")
    handle = page.p.locator(".betv-field-drive-frequency.betv-slider .noUi-handle").first
    handle.focus()
    for _ in range(3):
        page.p.keyboard.press("ArrowRight")
    deadline = time.monotonic() + WAIT_MS / 1e3
    while page.text("drive-frequency") == before and time.monotonic() < deadline:
        time.sleep(0.1)
    assert page.text("drive-frequency").endswith("kHz")
    # the latest value wins: wait for the design showing it, then its full check
    deadline = time.monotonic() + WAIT_MS / 1e3
    while time.monotonic() < deadline:
        s = page.seq_now()
        if s > seq and page.p.locator(f"[data-seq='{s}'][data-stage='full']").count():
            time.sleep(1.0)  # a later change may still arrive
            if page.seq_now() == s:
                break
        time.sleep(0.2)
    shown = page.shown()
    freq = page.text("drive-frequency")
    page.p.locator(".betv-save-name input").fill("moved.yaml")
    page.p.locator(".betv-save-name input").press("Enter")
    page.p.locator(".betv-save button").click()
    page.p.locator(".betv-saved").first.wait_for(state="attached", timeout=WAIT_MS)
    saved = push_server.workdir / "moved.yaml"
    dev = _check_json(saved)
    assert dev["verdict"] == shown["verdict"]
    assert {s["name"]: s["mode"] for s in dev["sets"]} == {
        k: v[0] for k, v in shown["sets"].items()
    }
    for s in dev["sets"]:
        assert shown["sets"][s["name"]][1] == pytest.approx(s["speed_m_s"], rel=1e-12)
    original = (push_server.workdir / "push_demo.yaml").read_text()
    diff = [
        line
        for line in difflib.unified_diff(original.splitlines(), saved.read_text().splitlines(), n=0)
        if line[:1] in "+-" and not line.startswith(("+++", "---"))
    ]
    assert diff == [
        "-      frequency: 3 kHz",
        f"+      frequency: {freq}",
    ]
    page.close()


def test_map_click_refused_value_and_the_server_still_answers(browser, push_server) -> None:
    page = Page(browser, push_server)
    seq = page.seq_now()
    freq, width = page.text("drive-frequency"), page.text("slider-beam-width")
    canvas = page.p.locator(".betv-map canvas").first
    canvas.scroll_into_view_if_needed()
    box = canvas.bounding_box()
    assert box is not None
    page.p.mouse.click(box["x"] + 0.7 * box["width"], box["y"] + 0.3 * box["height"])
    page.wait_seq(seq + 1)
    assert page.text("drive-frequency") != freq and page.text("slider-beam-width") != width
    friction = page.p.locator(".betv-field-contact-friction.betv-text input")
    friction.fill("7")
    friction.press("Enter")
    error = page.p.locator(".betv-error").first
    error.wait_for(timeout=WAIT_MS)
    assert "outside the physical range" in error.inner_text()
    seq = page.seq_now()
    page.p.locator(".betv-field-slider-beam-length.betv-slider .noUi-handle").first.focus()
    page.p.keyboard.press("ArrowLeft")
    page.wait_seq(seq + 1)  # still answering, the refused value left out
    assert page.p.locator(".betv-error").count() == 1
    friction.fill("0.35")
    friction.press("Enter")
    page.wait_seq(seq + 2)
    assert page.p.locator(".betv-error").count() == 0
    page.close()


def _verdict_now(page: Page) -> tuple[str, int, str, list[str]]:
    """Stage, design number, verdict and modes of the verdict block, read at once (one
    rendering: the block is replaced as a whole)."""
    stage, seq, verdict, modes = page.p.locator(".betv-verdict").first.evaluate(
        "el => [el.dataset.stage, el.dataset.seq, el.dataset.verdict,"
        " [...el.querySelectorAll('tr.betv-set')].map(r => r.dataset.mode)]"
    )
    return stage, int(seq), verdict, modes


def test_a_value_the_model_cannot_take_is_refused_at_the_control(browser, push_server) -> None:
    """Issue 32, items 1 and 2: 1e-300 Hz and 5e-324 V, which `betv check` refuses in a
    file (exit 2), are refused at the control with a message under it; the design shown
    stays the file's (verdict, modes, speeds), no "internal error" reaches the page, and
    Save writes the last good design. Before the stage that decides the modes, no mode
    and no verdict is shown ("computing")."""
    page = Page(browser, push_server)
    before = page.shown()
    for name, value in (("drive-frequency", "1e-300 Hz"), ("drive-voltage", "5e-324 V")):
        seq = page.seq_now()
        box = page.p.locator(f".betv-field-{name}.betv-text input")
        box.fill(value)
        box.press("Enter")
        error = page.p.locator(f".betv-message.betv-field-{name} .betv-error").first
        error.wait_for(timeout=WAIT_MS)
        assert f"{value} is outside" in error.inner_text()
        page.full(seq + 1)
        assert page.shown() == before
        status = page.p.locator(".betv-status").first.inner_text()
        assert "internal error" not in status and "failed" not in status, status
    page.p.locator(".betv-save-name input").fill("kept.yaml")
    page.p.locator(".betv-save-name input").press("Enter")
    page.p.locator(".betv-save button").click()
    page.p.locator(".betv-saved").first.wait_for(state="attached", timeout=WAIT_MS)
    kept = push_server.workdir / "kept.yaml"
    assert kept.read_text() == (push_server.workdir / "push_demo.yaml").read_text()
    dev = _check_json(kept)
    assert dev["verdict"] == before["verdict"]
    assert {s["name"]: s["mode"] for s in dev["sets"]} == {
        k: v[0] for k, v in before["sets"].items()
    }
    # an accepted value: every answer shown before the deciding stage shows no mode
    seq = page.seq_now()
    friction = page.p.locator(".betv-field-contact-friction.betv-text input")
    friction.fill("0.35")
    friction.press("Enter")
    seen = []
    deadline = time.monotonic() + WAIT_MS / 1e3
    while time.monotonic() < deadline:
        now = _verdict_now(page)
        if now[1] > seq:
            seen.append(now)
            if now[0] == "full":
                break
        time.sleep(0.02)
    assert seen and seen[-1][0] == "full", seen
    orbit = [x for x in seen if x[0] == "orbit"]
    assert orbit, seen  # shown for at least SETTLE_MS before the slow stages start
    assert all(v == "computing" and set(m) == {"computing"} for _, _, v, m in orbit), orbit
    assert "computing" not in seen[-1][3] and seen[-1][2] in ("pass", "fail")
    page.close()


def test_save_box_refuses_names_that_leave_the_device_folder(browser, push_server) -> None:
    """Issue 32 item 5: an empty name, an absolute path or `..` are refused with a
    message naming the folder, no Overwrite button, nothing written."""
    page = Page(browser, push_server)
    before = sorted(p.name for p in push_server.workdir.iterdir())
    box = page.p.locator(".betv-save-name input")
    for name in ("", "/tmp/betv-abs.yaml", "../up.yaml"):
        box.fill(name)
        box.press("Enter")
        page.p.locator(".betv-save button").click()
        msg = page.p.locator(".betv-save-message .betv-status-text").first  # the Div's content
        deadline = time.monotonic() + WAIT_MS / 1e3
        while str(push_server.workdir) not in msg.inner_text() and time.monotonic() < deadline:
            time.sleep(0.1)
        assert str(push_server.workdir) in msg.inner_text()
        assert not page.p.locator(".betv-overwrite button").is_visible()
    assert sorted(p.name for p in push_server.workdir.iterdir()) == before
    assert not Path("/tmp/betv-abs.yaml").exists()
    page.close()


def test_report_download_is_betv_reports_html(browser, push_server) -> None:
    """ "Build report" gives, byte for byte, the HTML `betv report` writes for the
    design saved under the name in the save box."""
    page = Page(browser, push_server)
    name = page.p.locator(".betv-save-name input").input_value()
    page.p.locator(".betv-report button").click()
    link = page.p.locator(".betv-report-download").first
    link.wait_for(timeout=WAIT_MS)
    with page.p.expect_download(timeout=WAIT_MS) as dl:
        link.click()
    assert dl.value.suggested_filename == Path(name).with_suffix(".html").name
    html = Path(dl.value.path()).read_text(encoding="utf-8")
    page.p.locator(".betv-save button").click()
    page.p.locator(".betv-saved").first.wait_for(state="attached", timeout=WAIT_MS)
    out = push_server.workdir / "reports"
    proc = subprocess.run(
        [*BETV, "report", name, "-o", str(out), "--no-pdf", "-q"],
        cwd=push_server.workdir,
        capture_output=True,
        text=True,
        check=False,
    )
    assert proc.returncode in (0, 1), proc.stderr
    assert html == (out / Path(name).with_suffix(".html").name).read_text(encoding="utf-8")
    page.close()


def test_failing_device_fix_is_listed_drawn_and_applied(browser, shin_server) -> None:
    """shin2004 fails the frequency window: betv fix's changes are listed (the drive
    frequency one drawn on the frequency map) and one click applies the first."""
    page = Page(browser, shin_server)
    assert page.shown()["verdict"] == "fail"
    seq = page.seq_now()
    page.p.locator(".betv-fix-item").first.wait_for(timeout=WAIT_MS)
    items = page.p.locator(".betv-fix-item").all_inner_texts()
    assert items and all("fixes" in t for t in items)
    page.p.locator(".betv-apply-fix-1 button").click()
    page.full(seq + 1)
    assert page.shown()["verdict"] == "pass"
    page.close()


def test_one_set_of_a_bidirectional_device(browser, shin_server) -> None:
    """With one set selected, a change goes to that set only (the saved file differs
    in that set's line)."""
    page = Page(browser, shin_server)
    seq = page.seq_now()
    page.p.locator(".betv-set-select select").select_option("left")
    page.wait_seq(seq + 1)  # the orbit of the set shown
    friction = page.p.locator(".betv-field-contact-friction.betv-text input")
    friction.fill("0.3")
    friction.press("Enter")
    page.wait_seq(seq + 2)
    page.p.locator(".betv-save-name input").fill("left-only.yaml")
    page.p.locator(".betv-save-name input").press("Enter")
    page.p.locator(".betv-save button").click()
    page.p.locator(".betv-saved").first.wait_for(state="attached", timeout=WAIT_MS)
    original = (shin_server.workdir / "shin2004.yaml").read_text().splitlines()
    saved = (shin_server.workdir / "left-only.yaml").read_text().splitlines()
    changed = [i for i, (a, b) in enumerate(zip(original, saved, strict=True)) if a != b]
    assert len(changed) == 1
    line = changed[0]
    assert saved[line].strip() == "friction: 0.3"
    assert original.index("  - name: left") < line
    page.close()


def _settled(page: Page, seq: int) -> int:
    """Wait for the full check of the first design after ``seq`` and for no later one to
    follow for a second; its design number."""
    deadline = time.monotonic() + WAIT_MS / 1e3
    while time.monotonic() < deadline:
        s = page.seq_now()
        if s > seq and page.p.locator(f"[data-seq='{s}'][data-stage='full']").count():
            time.sleep(1.0)
            if page.seq_now() == s:
                return s
        time.sleep(0.1)
    pytest.fail(f"no full check after design #{seq}")


def _type(page: Page, field: str, value: str) -> None:
    box = page.p.locator(f".betv-field-{field}.betv-text input")
    box.fill(value)
    box.press("Enter")


def _agrees(shown: dict, dev: dict) -> None:
    """The page's verdict, modes and speeds are `betv check --json`'s (``dev``)."""
    assert dev["verdict"] == shown["verdict"]
    assert {s["name"]: s["mode"] for s in dev["sets"]} == {
        k: v[0] for k, v in shown["sets"].items()
    }
    for s in dev["sets"]:
        speed = shown["sets"][s["name"]][1]
        assert (speed is None) == (s["speed_m_s"] is None)
        if speed is not None:
            assert speed == pytest.approx(s["speed_m_s"], rel=1e-12)


def test_undo_and_reset_to_the_file(browser, push_server) -> None:
    """Issue 32 item 6: Undo takes the last change back (the text box shows the file's
    value again and the verdict is `betv check --json` of the file); Reset goes back to
    the file from two changes (Save then writes the file's bytes); Undo after Reset
    brings the changes back."""
    page = Page(browser, push_server)
    original = push_server.workdir / "push_demo.yaml"
    file_dev = _check_json(original)
    undo = page.p.locator(".betv-undo button")
    reset = page.p.locator(".betv-reset button")
    assert undo.is_disabled() and reset.is_disabled()  # nothing changed yet
    friction = page.text("contact-friction")
    width = page.text("slider-beam-width")
    seq = page.seq_now()
    _type(page, "contact-friction", "0.05")
    seq = _settled(page, seq)
    assert page.text("contact-friction") == "0.05"
    assert not undo.is_disabled()
    undo.click()
    seq = _settled(page, seq)
    assert page.text("contact-friction") == friction
    _agrees(page.shown(), file_dev)
    assert undo.is_disabled() and reset.is_disabled()
    # two changes, then back to the file
    _type(page, "contact-friction", "0.3")
    seq = _settled(page, seq)
    _type(page, "slider-beam-width", "12 um")
    seq = _settled(page, seq)
    reset.click()
    seq = _settled(page, seq)
    assert (page.text("contact-friction"), page.text("slider-beam-width")) == (friction, width)
    _agrees(page.shown(), file_dev)
    page.p.locator(".betv-save-name input").fill("reset.yaml")
    page.p.locator(".betv-save-name input").press("Enter")
    page.p.locator(".betv-save button").click()
    page.p.locator(".betv-saved").first.wait_for(state="attached", timeout=WAIT_MS)
    assert (push_server.workdir / "reset.yaml").read_bytes() == original.read_bytes()
    undo.click()  # the reset is one step: both changes come back
    _settled(page, seq)
    assert (page.text("contact-friction"), page.text("slider-beam-width")) == ("0.3", "12 um")
    page.close()


def test_sliders_speak_the_fields_units(browser, push_server) -> None:
    """Issue 32 item 6: a screen reader hears the slider's value in the field's unit
    (aria-valuetext "3 kHz", the file's value, not the log10 position 0.48) and the
    field's name; a keyboard move says the new value as the text box writes it. The
    voltage slider spans the measured calibration: End is its last point (10 V), Home
    its first position above the first point (0 V: the spec takes V > 0)."""
    page = Page(browser, push_server)
    handle = page.p.locator(".betv-field-drive-frequency.betv-slider .noUi-handle").first
    assert handle.get_attribute("aria-valuetext") == "3 kHz"  # push_demo: frequency: 3 kHz
    assert handle.get_attribute("aria-label") == "drive frequency"
    width = page.p.locator(".betv-field-slider-beam-width.betv-slider .noUi-handle").first
    assert width.get_attribute("aria-valuetext") == "10 µm"  # beam_width: 10 um
    seq = page.seq_now()
    handle.focus()
    page.p.keyboard.press("ArrowRight")
    page.wait_seq(seq + 1)
    said = handle.get_attribute("aria-valuetext")
    assert said.endswith(" kHz") and said != "3 kHz"
    deadline = time.monotonic() + WAIT_MS / 1e3
    while page.text("drive-frequency") != said and time.monotonic() < deadline:
        time.sleep(0.1)
    assert page.text("drive-frequency") == said
    points = load_device(push_server.workdir / "push_demo.yaml").actuator_sets[0]
    first, last = (float(v.to("V").magnitude) for v in points.actuator.calibration.voltage_range)
    volt = page.p.locator(".betv-field-drive-voltage.betv-slider .noUi-handle").first
    for key, expect in (("End", last), ("Home", first)):
        seq = page.seq_now()
        volt.focus()
        page.p.keyboard.press(key)
        page.wait_seq(seq + 1)
        deadline = time.monotonic() + WAIT_MS / 1e3
        while not volt.get_attribute("aria-valuetext").endswith(" V"):
            assert time.monotonic() < deadline
            time.sleep(0.1)
        shown = float(volt.get_attribute("aria-valuetext").removesuffix(" V"))
        assert shown == pytest.approx(expect, abs=(last - first) / 200 * 1.001)
    assert page.p.locator(".betv-error").count() == 0  # both ends are taken
    page.close()


def test_a_refused_text_is_marked_in_its_box(browser, push_server) -> None:
    """Issue 32 item 6: a refused value stays in its box, marked red, until a value
    the file's validation takes replaces it."""
    page = Page(browser, push_server)
    seq = page.seq_now()
    _type(page, "contact-friction", "7")
    page.p.locator(".betv-message.betv-field-contact-friction .betv-error").first.wait_for(
        timeout=WAIT_MS
    )
    marked = page.p.locator(".betv-field-contact-friction.betv-text.betv-refused")
    marked.wait_for(timeout=WAIT_MS)
    box = page.p.locator(".betv-field-contact-friction.betv-text input")
    assert box.input_value() == "7"
    assert box.evaluate("e => getComputedStyle(e).borderTopColor") == "rgb(207, 34, 46)"
    _type(page, "contact-friction", "0.35")
    page.wait_seq(seq + 2)
    deadline = time.monotonic() + WAIT_MS / 1e3
    while marked.count() and time.monotonic() < deadline:
        time.sleep(0.1)
    assert marked.count() == 0
    assert box.evaluate("e => getComputedStyle(e).borderTopColor") != "rgb(207, 34, 46)"
    page.close()


def _get(url: str, host: str, path: str = "/") -> tuple[int, str]:
    import http.client
    from urllib.parse import urlsplit

    u = urlsplit(url)
    conn = http.client.HTTPConnection(u.hostname, u.port, timeout=60)
    try:
        conn.request("GET", path, headers={"Host": host})
        r = conn.getresponse()
        return r.status, r.read().decode("utf-8", "replace")
    finally:
        conn.close()


def test_foreign_host_headers_are_refused(push_server) -> None:
    """Issue 32 item 6 (DNS rebinding): a request naming another host gets 403 and no
    page, on every route; the local names are served (the browser tests open the page
    at 127.0.0.1; here a file of Bokeh's, so that no page session is left open)."""
    port = push_server.url.rstrip("/").rsplit(":", 1)[-1]
    static = "/static/js/bokeh.min.js"
    for host in ("evil.example", f"evil.example:{port}", f"127.0.0.1.evil.example:{port}"):
        for path in ("/", static, "/ws"):
            status, body = _get(push_server.url, host, path)
            assert status == 403, (host, path)
            assert "Bokeh" not in body and "refused" in body
    for host in (f"127.0.0.1:{port}", f"localhost:{port}", f"[::1]:{port}"):
        status, body = _get(push_server.url, host, static)
        assert status == 200, host
        assert "Bokeh" in body


def test_no_orbit_shows_why_in_place_of_the_plots(browser, push_server) -> None:
    """Issue 32 item 6: at 20 kHz push_demo has no periodic orbit (`betv check`: not
    driven): the page draws no plot and says "no periodic orbit: <reason>", with no
    console warning (Page.close); back at 3 kHz the plots return; the map legend's
    items each sit on one line and its last line is inside its box."""
    page = Page(browser, push_server)
    plots = page.p.locator(".betv-orbit-plot")
    assert plots.count() == 2 and all(plots.nth(k).is_visible() for k in range(2))
    seq = page.seq_now()
    _type(page, "drive-frequency", "20 kHz")
    seq = _settled(page, seq)
    note = page.p.locator(".betv-no-orbit").first
    assert note.inner_text().startswith("no periodic orbit: ")
    assert len(note.inner_text()) > len("no periodic orbit: ") + 10  # a reason
    assert not any(plots.nth(k).is_visible() for k in range(2))
    page.p.locator(".betv-save-name input").fill("fast.yaml")
    page.p.locator(".betv-save-name input").press("Enter")
    page.p.locator(".betv-save button").click()
    page.p.locator(".betv-saved").first.wait_for(state="attached", timeout=WAIT_MS)
    dev = _check_json(push_server.workdir / "fast.yaml")
    assert dev["sets"][0]["mode"] == "not driven" and dev["sets"][0]["speed_m_s"] is None
    _agrees(page.shown(), dev)
    _type(page, "drive-frequency", "3 kHz")
    _settled(page, seq)
    assert all(plots.nth(k).is_visible() for k in range(2))
    assert page.p.locator(".betv-no-orbit").count() == 0
    items = page.p.locator(".betv-legend-item")
    assert items.count() >= 6
    heights = [items.nth(k).bounding_box()["height"] for k in range(items.count())]
    assert max(heights) < 1.6 * min(heights), heights  # no item broken over two lines
    inside = page.p.locator(".betv-legend").first.evaluate(
        "el => { const h = el.getRootNode().host.getBoundingClientRect();"
        " const e = el.getBoundingClientRect(); return e.bottom <= h.bottom + 1; }"
    )
    assert inside
    page.close()


def test_the_orbit_plots_say_the_verdicts_basis(browser, push_server) -> None:
    """Issue 32 item 3: with friction 0.05 push_demo's verdict quotes the crossing of
    the travel from rest (`betv check --json`: basis "crossing"); the line over the orbit
    plots says so, as the map says its basis; at the file's friction (periodic basis)
    it says the plots are the verdict's answer."""
    page = Page(browser, push_server)
    basis = page.p.locator(".betv-orbit-basis").first
    file_dev = _check_json(push_server.workdir / "push_demo.yaml")
    assert basis.get_attribute("data-basis") == file_dev["sets"][0]["basis"] == "periodic"
    seq = page.seq_now()
    _type(page, "contact-friction", "0.05")
    _settled(page, seq)
    page.p.locator(".betv-save-name input").fill("slippery.yaml")
    page.p.locator(".betv-save-name input").press("Enter")
    page.p.locator(".betv-save button").click()
    page.p.locator(".betv-saved").first.wait_for(state="attached", timeout=WAIT_MS)
    dev = _check_json(push_server.workdir / "slippery.yaml")
    _agrees(page.shown(), dev)
    assert basis.get_attribute("data-basis") == dev["sets"][0]["basis"] == "crossing"
    assert "crossing of the travel from rest" in basis.inner_text()
    assert "not this periodic orbit" in basis.inner_text()
    page.close()


def test_ctrl_c_stops_cleanly(push_server: Server) -> None:
    assert push_server.stop() == 0
    err = "".join(push_server.err)
    assert "Traceback" not in err, err
    assert "stopped" in "".join(push_server.out)
