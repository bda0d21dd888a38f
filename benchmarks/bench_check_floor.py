"""`betv check -q` against the import floor of its own dependencies (issue 33), side by side.

    python benchmarks/bench_check_floor.py -n 5                     # this checkout
    python benchmarks/bench_check_floor.py -n 5 --baseline /tmp/old  # and older code

Each round times, as whole processes started from a folder outside the checkouts (so
that ``PYTHONPATH`` picks the code): the floor (``import numpy, scipy.optimize, pint,
pydantic, numba, typer``), ``betv check -q DEVICE`` of this checkout with its answer
cache warm (the stored answer, :mod:`betvdesign.output.answers`), the same with
``--no-cache`` (the check run afresh, solver kernels loaded from numba's cache), and with
``--baseline DIR`` the check of the code in DIR. The commands alternate within a round,
so all see the same machine load. Wall and CPU (user + system of the child) seconds,
median over the rounds, and the ratio of each check's CPU median to the floor's.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FLOOR = "import numpy, scipy.optimize, pint, pydantic, numba, typer"
CLI = "import sys; from betvdesign.cli import main; sys.argv[0] = 'betv'; main()"


def timed(cmd: list[str], env: dict[str, str], cwd: str) -> tuple[float, float]:
    """(wall, CPU) seconds of one child process running ``cmd``."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(cmd, env=env, cwd=cwd, capture_output=True, check=False)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("device", nargs="?", default="devices/push_demo.yaml")
    ap.add_argument("-n", type=int, default=5, help="rounds (after one warm-up round)")
    ap.add_argument("--baseline", type=Path, help="a checkout of older code")
    args = ap.parse_args()
    outside = tempfile.mkdtemp(prefix="betv-floor-")
    cache = Path(outside) / "answers"
    device = str((ROOT / args.device).resolve())
    py = sys.executable
    base_env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    mine = {**base_env, "PYTHONPATH": str(ROOT), "BETV_ANSWER_CACHE": str(cache)}
    commands: dict[str, tuple[list[str], dict[str, str]]] = {
        "floor": ([py, "-c", FLOOR], base_env),
        "check (cached answer)": ([py, "-c", CLI, "check", "-q", device], mine),
        "check --no-cache": ([py, "-c", CLI, "check", "-q", "--no-cache", device], mine),
    }
    if args.baseline is not None:
        old = {**base_env, "PYTHONPATH": str(args.baseline.resolve())}
        old_device = str((args.baseline / args.device).resolve())
        commands["check (baseline)"] = ([py, "-c", CLI, "check", "-q", old_device], old)
    times: dict[str, list[tuple[float, float]]] = {k: [] for k in commands}
    for rnd in range(args.n + 1):
        for name, (cmd, env) in commands.items():
            t = timed(cmd, env, outside)
            if rnd:
                times[name].append(t)
    floor_cpu = statistics.median(c for _, c in times["floor"])
    rows = {}
    for name, ts in times.items():
        wall = statistics.median(w for w, _ in ts)
        cpu = statistics.median(c for _, c in ts)
        rows[name] = {"wall_s": wall, "cpu_s": cpu, "cpu_over_floor": cpu / floor_cpu}
        print(f"{name:24s} wall {wall:6.2f} s  CPU {cpu:5.2f} s  CPU/floor {cpu / floor_cpu:4.2f}")
    print(f"load average {os.getloadavg()[0]:.2f}")
    out = ROOT / "benchmarks" / "out"
    out.mkdir(exist_ok=True)
    (out / "check_floor.json").write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
