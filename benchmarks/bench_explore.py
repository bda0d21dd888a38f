"""Latency of `betv explore` (issue 22): server update, browser redraw, page start.

    python benchmarks/bench_explore.py                 # all: 200 updates, 50 key presses
    python benchmarks/bench_explore.py --only server   # the server-side update only
    python benchmarks/bench_explore.py -n 50 --keys 20 # quicker

1. **Server update** (in this process, no browser): a random designer field of a shipped
   device is moved within its slider range and the page's update is timed: the change
   through the device file's validation (``Design.apply``) and the "orbit" stage
   (``explore.compute.evaluate``: derivation, exact periodic orbit and vertical motion,
   the four mode-margin corners, the rules, the ``betv check --json`` view, the orbit
   sampled for the two plots). Targets: ≤ 30 ms median, ≤ 100 ms p95.
2. **Browser** (Debian's chromium via playwright, as tests/test_browser.py launches it):
   ``betv explore devices/push_demo.yaml`` as a user starts it; the drive-frequency slider
   is moved by the keyboard 50 times (each press after the previous redraw) and the time
   from the key press to the redrawn verdict and orbit (the page's ``data-seq``) is
   measured; the page's own ``data-server-ms`` (change received -> redraw sent) and
   ``data-compute-ms`` are recorded beside it. Target: ≤ 150 ms median.
3. **Page start**, warm (compiled kernels cached): from starting the command to the
   first full page (verdict, orbit and map axes drawn) in the browser, and to every
   stage of ``betv check`` shown. Target: ≤ 5 s.

Numbers go to ``benchmarks/out/explore.json``; the load average is recorded with them
(the machine is shared: every figure is inflated by other work).
"""

from __future__ import annotations

import argparse
import json
import os
import random
import shutil
import socket
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DEVICES = ROOT / "devices"
OUT = ROOT / "benchmarks" / "out"
BETV = [sys.executable, "-c", "from betvdesign.cli import main; main()"]
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
SEED = 20261125


def _stats(xs: list[float]) -> dict[str, float]:
    s = sorted(xs)
    return {
        "n": len(s),
        "median": statistics.median(s),
        "p95": s[min(len(s) - 1, round(0.95 * (len(s) - 1)))],
        "min": s[0],
        "max": s[-1],
    }


def server_updates(n: int) -> dict[str, object]:
    """Median/p95 [ms] of apply + orbit stage for random moves on each device."""
    from betvdesign.explore.compute import evaluate
    from betvdesign.explore.design import Design
    from betvdesign.explore.fields import designer_fields

    rng = random.Random(SEED)
    out: dict[str, object] = {}
    for name in ("push_demo", "bidir_demo", "shin2004", "damped_demo"):
        d = Design.from_file(DEVICES / f"{name}.yaml")
        shown = d.original.actuator_sets[0].name  # the page samples the set it shows
        evaluate(d.spec, "orbit", with_traces=shown)  # kernels loaded
        fields = [
            c
            for c in designer_fields(d.original, 0)
            if c.kind in ("quantity", "number") and not c.optional
        ]
        apply_ms, eval_ms, total_ms, cpu_ms = [], [], [], []
        for _ in range(n):
            c = rng.choice(fields)
            x = c.lo * (c.hi / c.lo) ** rng.random() if c.log else rng.uniform(c.lo, c.hi)
            c0, t0 = time.process_time(), time.perf_counter()
            d.apply({c.field: c.file_value(c.text(x))})
            t1 = time.perf_counter()
            evaluate(d.spec, "orbit", with_traces=shown)
            t2, c2 = time.perf_counter(), time.process_time()
            apply_ms.append(1e3 * (t1 - t0))
            eval_ms.append(1e3 * (t2 - t1))
            total_ms.append(1e3 * (t2 - t0))
            cpu_ms.append(1e3 * (c2 - c0))
            d.reset()
        out[name] = {
            "total_ms": _stats(total_ms),
            "total_cpu_ms": _stats(cpu_ms),
            "validate_ms": _stats(apply_ms),
            "orbit_stage_ms": _stats(eval_ms),
        }
        wall, cpu = out[name]["total_ms"], out[name]["total_cpu_ms"]
        print(
            f"server {name:12s} update median {wall['median']:6.1f} ms, p95 {wall['p95']:6.1f} ms;"
            f" CPU median {cpu['median']:5.1f} ms, p95 {cpu['p95']:5.1f} ms (wall: validation "
            f"{statistics.median(apply_ms):.1f} ms, orbit stage "
            f"{statistics.median(eval_ms):.1f} ms)"
        )
    return out


def _cpu_s(pid: int) -> float:
    """User + system CPU time [s] of process ``pid`` so far (Linux /proc)."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


class _Server:
    def __init__(self, device: str, workdir: Path):
        shutil.copy(DEVICES / f"{device}.yaml", workdir / f"{device}.yaml")
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            self.port = s.getsockname()[1]
        self.t0 = time.perf_counter()
        self.proc = subprocess.Popen(
            [*BETV, "explore", f"{device}.yaml", "--no-browser", "--port", str(self.port)],
            cwd=workdir,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
        )
        self.ready = threading.Event()
        self.lines: list[str] = []
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        for line in self.proc.stdout:  # type: ignore[union-attr]
            self.lines.append(line)
            if "http://127.0.0.1:" in line:
                self.ready.set()

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}/"

    def stop(self) -> None:
        self.proc.send_signal(2)
        try:
            self.proc.wait(timeout=60)
        except subprocess.TimeoutExpired:
            self.proc.kill()


def browser(keys: int) -> dict[str, object]:
    """Page start (warm) and key press -> redraw latency in chromium."""
    from playwright.sync_api import sync_playwright

    out: dict[str, object] = {}
    with tempfile.TemporaryDirectory() as tmp, sync_playwright() as pw:
        b = pw.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS, headless=True)
        starts = []
        for run in range(2):  # the first run may still fill the compile cache
            server = _Server("push_demo", Path(tmp))
            try:
                server.ready.wait(300)
                t_ready = time.perf_counter() - server.t0
                page = b.new_page(viewport={"width": 1650, "height": 1100})
                page.goto(server.url)
                page.locator("[data-seq='1']").first.wait_for(timeout=300_000)
                page.locator(".betv-map canvas").first.wait_for(timeout=300_000)
                t_page = time.perf_counter() - server.t0
                cpu_page = _cpu_s(server.proc.pid)
                page.locator("[data-seq='1'][data-stage='full']").first.wait_for(timeout=300_000)
                t_full = time.perf_counter() - server.t0
                starts.append(
                    {
                        "listening_s": t_ready,
                        "first_page_s": t_page,
                        "server_cpu_at_first_page_s": cpu_page,
                        "all_stages_s": t_full,
                    }
                )
                print(
                    f"page start run {run + 1}: listening {t_ready:.2f} s, first full page "
                    f"{t_page:.2f} s (server CPU {cpu_page:.2f} s), every stage of betv check "
                    f"{t_full:.2f} s"
                )
                if run == 1:
                    out["latency"] = _keys(page, keys)
                page.close()
            finally:
                server.stop()
        out["page_start_warm"] = starts[-1]
        out["page_start_first"] = starts[0]
        b.close()
    return out


def _metrics(cdp) -> dict[str, float]:
    return {m["name"]: m["value"] for m in cdp.send("Performance.getMetrics")["metrics"]}


def _keys(page, keys: int) -> dict[str, object]:
    cdp = page.context.new_cdp_session(page)
    cdp.send("Performance.enable")
    before = _metrics(cdp)
    seq = int(page.locator(".betv-verdict").first.get_attribute("data-seq"))
    page.locator(".betv-field-drive-frequency.betv-slider .noUi-handle").first.focus()
    browser_ms, server_ms, compute_ms, cpu_ms = [], [], [], []
    for k in range(keys):
        t0 = time.perf_counter()
        page.keyboard.press("ArrowRight" if (k // 10) % 2 == 0 else "ArrowLeft")
        seq += 1
        el = page.locator(f"[data-seq='{seq}']").first
        el.wait_for(timeout=60_000)
        browser_ms.append(1e3 * (time.perf_counter() - t0))
        server_ms.append(float(el.get_attribute("data-server-ms")))
        compute_ms.append(float(el.get_attribute("data-compute-ms")))
        cpu_ms.append(float(el.get_attribute("data-compute-cpu-ms")))
        time.sleep(0.05)
    after = _metrics(cdp)
    res: dict[str, object] = {
        "key_to_redraw_ms": _stats(browser_ms),
        "server_change_to_redraw_ms": _stats(server_ms),
        "server_compute_ms": _stats(compute_ms),
        "server_compute_cpu_ms": _stats(cpu_ms),
    }
    for name, st in list(res.items()):
        print(f"browser {name:28s} median {st['median']:7.1f} ms, p95 {st['p95']:7.1f} ms")
    # the page's main thread, per change (CPU work in the renderer, not waiting)
    per = {
        k: 1e3 * (after[k] - before[k]) / keys
        for k in ("TaskDuration", "ScriptDuration", "LayoutDuration", "RecalcStyleDuration")
    }
    res["renderer_main_thread_ms_per_change"] = per
    print(
        "browser renderer main thread per change: "
        + ", ".join(f"{k.removesuffix('Duration').lower()} {v:.1f} ms" for k, v in per.items())
    )
    return res


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-n", type=int, default=200, help="server updates per device")
    ap.add_argument("--keys", type=int, default=50, help="key presses in the browser")
    ap.add_argument("--only", choices=("server", "browser"), default=None)
    args = ap.parse_args()
    report: dict[str, object] = {
        "when": time.strftime("%Y-%m-%d %H:%M:%S %Z"),
        "load_average": os.getloadavg(),
        "cpus": os.cpu_count(),
    }
    if args.only in (None, "server"):
        report["server_update"] = server_updates(args.n)
    if args.only in (None, "browser"):
        report["browser"] = browser(args.keys)
    report["load_average_after"] = os.getloadavg()
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "explore.json").write_text(json.dumps(report, indent=2))
    print(f"load average before {report['load_average']}, after {report['load_average_after']}")
    print(f"written {OUT / 'explore.json'}")


if __name__ == "__main__":
    main()
