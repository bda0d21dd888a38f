"""A design-space atlas of 10⁵ or 10⁶ (ϖ, α, β, κ) points: pool and dask, resume (issue 33).

    .venv/bin/python benchmarks/bench_atlas.py --kappa-points 4 --workers 2     # 10⁵ points
    .venv/bin/python benchmarks/bench_atlas.py --kappa-points 40 --workers 16   # 10⁶ points
    options: --backends process dask, --chunksize N, --resume-at F (0: no resume run),
             --out DIR (atlases kept there; default a temporary directory)

Each run is the whole command ``betv sweep atlas --varpi ... --alpha ... --beta ...
--kappa ... -x BACKEND -j N -o DIR -q --json`` in its own process (start-up, pool or
local dask cluster start, kernels loaded, solves, chunk files, merge): the grid is
40 ϖ (0.3 to 3, linear) × 25 α (0.1 to 10, log) × 25 β (0.05 to 2, log) × K κ (0.05
to 0.6, linear; ``--kappa-points K``: 4 gives 10⁵ points, 40 gives 10⁶).

Per backend it prints and records in ``benchmarks/out/bench_atlas.json``:

* ``wall_s``: the command's wall time [s]; ``points_per_s`` = points / wall_s;
  ``compute_s`` (the chunks' part, from the command's JSON) and ``merge_s``;
* ``peak_rss_mb``: the largest sum of the resident memory of the command's process tree
  (its pool or cluster included), sampled every 0.2 s [MB];
* the resume overhead: the same command run again on the finished atlas
  (``rerun_s``: the manifest checked, every chunk found, the table merged again), and,
  with ``--resume-at F``, the command interrupted (SIGINT) once a fraction F of the
  chunks is on disk and run again: ``interrupted_s + resumed_s`` against ``wall_s``.

The tables of all backends (and of the resumed atlas) are compared byte for byte.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import psutil

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "benchmarks" / "out"


def grid_args(kappa_points: int) -> list[str]:
    """The grid options of the benchmark's atlas (40 × 25 × 25 × ``kappa_points``)."""

    def listed(values: np.ndarray) -> str:
        return ",".join(repr(float(v)) for v in values)

    return [
        "--varpi", listed(np.linspace(0.3, 3.0, 40)),
        "--alpha", listed(np.geomspace(0.1, 10.0, 25)),
        "--beta", listed(np.geomspace(0.05, 2.0, 25)),
        "--kappa", listed(np.linspace(0.05, 0.6, kappa_points)),
    ]  # fmt: skip


def _tree_rss(proc: psutil.Process) -> int:
    total = 0
    for p in [proc, *proc.children(recursive=True)]:
        try:
            total += p.memory_info().rss
        except psutil.Error:
            pass
    return total


def run(cmd: list[str], *, stop_at_chunks: int | None = None, chunks_dir: Path | None = None):
    """Run ``cmd``; return (wall [s], peak tree RSS [MB], return code, stdout).

    With ``stop_at_chunks``, send SIGINT once that many chunk files are in
    ``chunks_dir``.
    """
    t0 = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    ps = psutil.Process(proc.pid)
    peak = 0
    sent = False
    while proc.poll() is None:
        peak = max(peak, _tree_rss(ps))
        if stop_at_chunks and not sent and chunks_dir is not None and chunks_dir.exists():
            if sum(1 for p in chunks_dir.iterdir() if p.name[0].isdigit()) >= stop_at_chunks:
                proc.send_signal(signal.SIGINT)
                sent = True
        time.sleep(0.2)
    out, err = proc.communicate()
    wall = time.perf_counter() - t0
    if proc.returncode not in (0, 130):
        sys.exit(f"failed ({proc.returncode}): {' '.join(cmd[:6])} ...\n{err[-2000:]}")
    return wall, peak / 2**20, proc.returncode, out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--kappa-points", type=int, default=4)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--backends", nargs="+", default=["process", "dask"])
    ap.add_argument("--chunksize", type=int, default=None)
    ap.add_argument("--resume-at", type=float, default=0.5)
    ap.add_argument("--out", type=Path, default=None)
    a = ap.parse_args()
    base_dir = a.out or Path(tempfile.mkdtemp(prefix="bench_atlas_"))
    base_dir.mkdir(parents=True, exist_ok=True)
    betv = [sys.executable, "-c", "from betvdesign.cli import main; main()", "sweep", "atlas"]
    common = [*grid_args(a.kappa_points), "-j", str(a.workers), "-q", "--json"]
    if a.chunksize:
        common += ["--chunksize", str(a.chunksize)]
    points = 40 * 25 * 25 * a.kappa_points
    results: dict[str, object] = {
        "points": points,
        "workers": a.workers,
        "machine": f"{platform.node()} {os.cpu_count()} cores",
        "load_before": os.getloadavg(),
        "runs": [],
    }
    tables = {}
    for backend in a.backends:
        d = base_dir / backend
        shutil.rmtree(d, ignore_errors=True)
        cmd = [*betv, *common, "-x", backend, "-o", str(d)]
        wall, rss, _, out = run(cmd)
        data = json.loads(out)
        row = {
            "backend": backend,
            "wall_s": round(wall, 2),
            "points_per_s": round(points / wall, 1),
            "compute_s": data["elapsed_s"],
            "merge_s": data["merge_s"],
            "chunks": data["chunks"],
            "chunk_points": data["chunk_points"],
            "peak_rss_mb": round(rss, 1),
            "modes": data["modes"],
            "load": os.getloadavg()[0],
        }
        rerun, _, _, out2 = run(cmd)
        row["rerun_s"] = round(rerun, 2)
        row["rerun_computed_chunks"] = json.loads(out2)["computed_chunks"]
        tables[backend] = (d / "table.npz").read_bytes()
        if a.resume_at > 0:
            r = base_dir / f"{backend}-resumed"
            shutil.rmtree(r, ignore_errors=True)
            rcmd = [*betv, *common, "-x", backend, "-o", str(r)]
            stop = max(1, int(a.resume_at * data["chunks"]))
            w1, _, rc, _ = run(rcmd, stop_at_chunks=stop, chunks_dir=r / "chunks")
            w2, _, _, out3 = run(rcmd)
            d3 = json.loads(out3)
            row |= {
                "interrupted_rc": rc,
                "interrupted_s": round(w1, 2),
                "resumed_s": round(w2, 2),
                "resumed_chunks": d3["resumed_chunks"],
                "resume_overhead_s": round(w1 + w2 - wall, 2),
            }
            tables[f"{backend}-resumed"] = (r / "table.npz").read_bytes()
        results["runs"].append(row)  # type: ignore[union-attr]
        print(json.dumps(row), flush=True)
    same = len(set(tables.values())) == 1
    results["tables_identical"] = same
    print(f"tables identical across {sorted(tables)}: {same}")
    OUT.mkdir(exist_ok=True)
    (OUT / "bench_atlas.json").write_text(json.dumps(results, indent=2) + "\n")
    if not a.out:
        shutil.rmtree(base_dir, ignore_errors=True)


if __name__ == "__main__":
    main()
