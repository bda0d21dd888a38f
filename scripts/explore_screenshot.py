"""The README's picture of ``betv explore`` (docs/img/explore.png), taken from the real page.

    python scripts/explore_screenshot.py                  # push_demo -> docs/img/explore.png
    python scripts/explore_screenshot.py -o /tmp/x.png    # elsewhere

Runs ``betv explore devices/push_demo.yaml --no-browser`` on a copy of the device (the
page shows its file name only), opens the page in Debian's chromium, headless, through
playwright (as ``tests/test_explore_browser.py`` does), waits until every stage of
``betv check`` has answered and the map is complete, and saves the browser's viewport
(:data:`VIEWPORT`) as PNG. Ctrl-C (SIGINT) then stops the server.
"""

from __future__ import annotations

import argparse
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BETV = [sys.executable, "-c", "from betvdesign.cli import main; main()"]
#: The browser's viewport [px]: the page's three columns side by side.
VIEWPORT = {"width": 1650, "height": 1000}
#: How long the server's start and the page's stages may take [s].
WAIT_S = 300
#: Chromium headless in a container, offline (the flags of tests/test_browser.py).
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


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _start(device: Path, workdir: Path) -> tuple[subprocess.Popen[str], str]:
    """``betv explore`` on a copy of ``device`` in ``workdir``: the process and its URL."""
    shutil.copy(device, workdir / device.name)
    port = _free_port()
    proc = subprocess.Popen(
        [*BETV, "explore", device.name, "--no-browser", "--port", str(port)],
        cwd=workdir,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
    )
    ready = threading.Event()

    def read() -> None:
        assert proc.stdout is not None
        for line in proc.stdout:
            sys.stderr.write(line)
            if "http://127.0.0.1:" in line:
                ready.set()

    threading.Thread(target=read, daemon=True).start()
    if not ready.wait(WAIT_S):
        proc.kill()
        raise SystemExit("betv explore did not start")
    return proc, f"http://127.0.0.1:{port}/"


def shoot(device: Path, out: Path, chromium: str) -> None:
    """Save the explore page of ``device`` as PNG at ``out``."""
    from playwright.sync_api import sync_playwright

    with tempfile.TemporaryDirectory() as tmp:
        proc, url = _start(device, Path(tmp))
        try:
            with sync_playwright() as pw:
                browser = pw.chromium.launch(
                    executable_path=chromium, args=CHROMIUM_ARGS, headless=True
                )
                page = browser.new_page(viewport=VIEWPORT)
                page.goto(url)
                wait = WAIT_S * 1000
                page.locator("[data-stage='full']").first.wait_for(timeout=wait)
                page.locator(
                    ".betv-map-status .betv-status-text", has_text="exact orbits"
                ).wait_for(timeout=wait)
                page.wait_for_timeout(1000)  # the last redraws
                out.parent.mkdir(parents=True, exist_ok=True)
                page.screenshot(path=str(out))
                browser.close()
        finally:
            proc.send_signal(signal.SIGINT)
            proc.wait(60)
    print(f"wrote {out}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--device", type=Path, default=ROOT / "devices" / "push_demo.yaml")
    ap.add_argument("-o", "--out", type=Path, default=ROOT / "docs" / "img" / "explore.png")
    ap.add_argument("--chromium", default="/usr/bin/chromium")
    args = ap.parse_args()
    shoot(args.device, args.out, args.chromium)


if __name__ == "__main__":
    main()
