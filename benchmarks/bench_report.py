"""Report speed: one device's HTML + PDF, warm, by stage (issue 21: ≤ 3 s per device).

    python benchmarks/bench_report.py                          # every shipped device
    python benchmarks/bench_report.py devices/push_demo.yaml -n 5
    python benchmarks/bench_report.py --baseline /tmp/old      # the same, side by side
                                                               # with the code in /tmp/old

"Warm" means the process has already written one report of the device (imports done,
solver kernels compiled and loaded, matplotlib's font cache read); each timed run then
builds the report model (``build_report``: analysis, check, figures), renders the HTML
and the PDF, as ``betv report`` does. Wall and CPU seconds per stage, best of ``-n``
runs. With ``--baseline DIR`` each device is also timed by the code in DIR (a checkout
of an older commit: ``git archive COMMIT | tar -x -C DIR``), alternating with this
checkout so that both see the same machine load. Results in
``benchmarks/out/report_speed.json``.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "benchmarks" / "out"


def measure(device: str, runs: int) -> dict[str, float]:
    """Best-of-``runs`` wall and CPU seconds per stage of one warm report of ``device``."""
    from betvdesign.report import build_report, prepare, render_html, render_pdf
    from betvdesign.report import render as render_module
    from betvdesign.report.write import write_reports

    def pdf_of(report: object) -> bytes:
        new = getattr(render_module, "report_pdf", None)  # older code: the HTML's SVG
        return new(report) if new is not None else render_pdf(render_html(report))

    with tempfile.TemporaryDirectory() as tmp:
        write_reports([device], tmp)  # warm-up: imports, kernels, font cache
    best: dict[str, float] = {}
    for _ in range(runs):
        stages: dict[str, float] = {}
        w0, c0 = time.perf_counter(), time.process_time()
        report = build_report(prepare(device))
        w1, c1 = time.perf_counter(), time.process_time()
        render_html(report)
        w2, c2 = time.perf_counter(), time.process_time()
        pdf_of(report)
        w3, c3 = time.perf_counter(), time.process_time()
        stages.update(
            build_wall=w1 - w0,
            build_cpu=c1 - c0,
            html_wall=w2 - w1,
            pdf_wall=w3 - w2,
            pdf_cpu=c3 - c2,
            total_wall=w3 - w0,
            total_cpu=c3 - c0,
        )
        for k, v in stages.items():
            best[k] = min(best.get(k, v), v)
    return best


def in_checkout(code: Path, device: str, runs: int) -> dict[str, float]:
    """:func:`measure` run by the package in ``code`` (a fresh process)."""
    env = {**os.environ, "PYTHONPATH": str(code)}
    cmd = [sys.executable, str(Path(__file__).resolve()), "--child", device, "-n", str(runs)]
    # its own device files (a device file of a newer version may not load in older code)
    out = subprocess.run(cmd, env=env, cwd=code, capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("devices", nargs="*", help="device files (default: devices/*.yaml)")
    ap.add_argument("-n", "--runs", type=int, default=3, help="timed runs per device")
    ap.add_argument("--baseline", type=Path, help="checkout of older code to time beside")
    ap.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        print(json.dumps(measure(args.devices[0], args.runs)))
        return
    devices = args.devices or [
        str(p.relative_to(ROOT)) for p in sorted(ROOT.glob("devices/*.yaml"))
    ]
    rows = []
    for dev in devices:
        row = {"device": dev, "now": in_checkout(ROOT, dev, args.runs)}
        if args.baseline is not None:
            row["before"] = in_checkout(args.baseline, dev, args.runs)
        rows.append(row)
        for label in ("before", "now"):
            if label in row:
                r = row[label]
                print(
                    f"{dev:28s} {label:6s} total {r['total_wall']:6.2f} s wall "
                    f"({r['total_cpu']:6.2f} CPU): build {r['build_wall']:5.2f}, "
                    f"html {r['html_wall']:4.2f}, pdf {r['pdf_wall']:5.2f}"
                )
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "report_speed.json").write_text(json.dumps(rows, indent=1) + "\n")


if __name__ == "__main__":
    main()
