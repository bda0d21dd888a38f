"""Time of a 40 × 40 sweep of a device's own fields (issue 21 target: ≤ 10 s on 2 cores).

    python benchmarks/bench_fieldsweep.py            # best of 3 fresh processes

Runs ``betv sweep tests/data/designer_pull.yaml --vary drive.frequency=1k:4k --vary
slider.beam_width=5um:45um -n 40 -x process -j 2`` as a user would (a fresh process,
warm compile cache, no --out) and reports the wall time of the whole command and the
study's own elapsed time (the points only). Writes benchmarks/out/fieldsweep.json.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CMD = [
    "sweep",
    str(ROOT / "tests/data/designer_pull.yaml"),
    "--vary", "drive.frequency=1k:4k",
    "--vary", "slider.beam_width=5um:45um",
    "-n", "40", "-x", "process", "-j", "2", "-q", "--json",
]  # fmt: skip


def main() -> None:
    code = "import sys; sys.argv[0] = 'betv'; from betvdesign.cli import main; main()"
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    runs = []
    for _ in range(3):
        t0 = time.perf_counter()
        p = subprocess.run(
            [sys.executable, "-c", code, *CMD], capture_output=True, text=True, env=env
        )
        wall = time.perf_counter() - t0
        doc = json.loads(p.stdout)
        runs.append({"wall_s": wall, "study_s": doc["elapsed_s"], "points": doc["points"]})
    out = {
        "command": "betv " + " ".join(CMD),
        "runs": runs,
        "best_wall_s": min(r["wall_s"] for r in runs),
        "best_study_s": min(r["study_s"] for r in runs),
        "load_average": os.getloadavg(),
    }
    path = ROOT / "benchmarks/out/fieldsweep.json"
    path.parent.mkdir(exist_ok=True)
    path.write_text(json.dumps(out, indent=1))
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
