"""Start-up of `betv explore` (issue 33): command -> "ready" line, command -> first verdict.

    python benchmarks/bench_explore_start.py                      # this tree, 5 runs
    python benchmarks/bench_explore_start.py --tree /work/main --tree .  # side by side
    python benchmarks/bench_explore_start.py -n 8 --device shin2004

Each run starts ``betv explore devices/DEVICE.yaml --no-browser --port P`` as a user
does (a new process, the compiled kernels already in numba's cache) with the tree's
package first on ``PYTHONPATH``, and times from the start of the process to:

- **ready**: the line that prints the URL (the user's browser opens then);
- **verdict**: the verdict block (``.betv-verdict``) in Debian's chromium (headless, via
  playwright, launched once before the runs as a user's browser is already open), the
  page asked for as soon as the ready line arrives.

The trees are run alternately (run k of every tree, then run k+1), so a change of the
machine's load hits them alike. Median and max per tree [s] are printed with the load
average. Target: verdict <= 3 s, and the page answering when "ready" is printed.
"""

from __future__ import annotations

import argparse
import os
import signal
import socket
import statistics
import subprocess
import sys
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CHROMIUM = "/usr/bin/chromium"
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
#: Longest wait for a start [s] (a cold numba cache compiles for a minute).
TIMEOUT_S = 180


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def one_run(browser: object, tree: Path, device: str) -> tuple[float, float]:
    """(ready, verdict) [s] from the process start, of one ``betv explore`` of ``tree``."""
    port = _free_port()
    env = {**os.environ, "PYTHONPATH": str(tree)}
    cmd = [sys.executable, "-c", "from betvdesign.cli import main; main()"]
    cmd += ["explore", f"devices/{device}.yaml", "--no-browser", "--port", str(port)]
    t0 = time.perf_counter()
    proc = subprocess.Popen(
        cmd, cwd=tree, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True
    )
    ready = threading.Event()
    out: list[str] = []
    t_ready = [float("nan")]

    def read() -> None:
        assert proc.stdout is not None
        for line in proc.stdout:
            out.append(line)
            if "http://127.0.0.1:" in line and not ready.is_set():
                t_ready[0] = time.perf_counter() - t0
                ready.set()

    threading.Thread(target=read, daemon=True).start()
    try:
        if not ready.wait(TIMEOUT_S):
            raise RuntimeError(f"{tree}: betv explore did not start: {''.join(out)}")
        page = browser.new_page()  # type: ignore[attr-defined]
        try:
            page.goto(f"http://127.0.0.1:{port}/", timeout=TIMEOUT_S * 1000)
            page.locator(".betv-verdict").first.wait_for(timeout=TIMEOUT_S * 1000)
            t_verdict = time.perf_counter() - t0
        finally:
            page.close()
    finally:
        proc.send_signal(signal.SIGINT)
        try:
            proc.wait(timeout=30)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
    return t_ready[0], t_verdict


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-n", type=int, default=5, help="runs per tree (default 5)")
    ap.add_argument("--device", default="push_demo", help="shipped device (default push_demo)")
    ap.add_argument(
        "--tree",
        action="append",
        type=Path,
        help="source tree to run (repeatable; default: this one)",
    )
    args = ap.parse_args()
    trees = [t.resolve() for t in (args.tree or [ROOT])]
    from playwright.sync_api import sync_playwright

    res: dict[Path, list[tuple[float, float]]] = {t: [] for t in trees}
    load0 = os.getloadavg()[0]
    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS, headless=True)
        try:
            for t in trees:  # warm-up (the kernel cache, the OS file cache); not counted
                one_run(browser, t, args.device)
            for k in range(args.n):
                for t in trees:
                    r = one_run(browser, t, args.device)
                    res[t].append(r)
                    print(f"run {k + 1} {t}: ready {r[0]:.2f} s, verdict {r[1]:.2f} s", flush=True)
        finally:
            browser.close()
    load1 = os.getloadavg()[0]
    print(f"\n{os.cpu_count()} cores, load average {load0:.2f} -> {load1:.2f}; {args.n} runs")
    print(f"{'tree':40s} {'ready median/max [s]':>22s} {'verdict median/max [s]':>24s}")
    for t, rs in res.items():
        ready = [r[0] for r in rs]
        verdict = [r[1] for r in rs]
        print(
            f"{t!s:40s} {statistics.median(ready):10.2f} / {max(ready):5.2f}"
            f" {statistics.median(verdict):12.2f} / {max(verdict):5.2f}"
        )


if __name__ == "__main__":
    main()
