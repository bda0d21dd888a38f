"""Process pool against dask.distributed on the same tolerance study (issue 33).

    .venv/bin/python benchmarks/bench_dask.py --workers 1 2 4 8 16 --samples 200000
    .venv/bin/python benchmarks/bench_dask.py --workers 1 2 --samples 5000 20000
    options: --dask-chunksize N (e.g. 32: the chunking before issue 33), --repeat R,
             --budget S (skip what would start after S seconds), --device FILE

For each sample count and each worker count n it times, on this machine:

* ``pool``: :class:`ProcessExecutor` with n workers (forkserver), and
* ``dask``: a ``distributed.LocalCluster`` of n single-thread worker processes and its
  scheduler, through :class:`DaskExecutor`,

each running the same tolerance study of ``devices/push_demo.yaml`` (seven fields spread,
periodic rung). The time is the study's own (``run_study``), after one small warm-up
run on the same pool or cluster (fork server and kernels loaded, cluster started and
its kernels warmed); cluster start-up is printed apart. With ``--repeat R`` the two
alternate R times (pool, dask, pool, ...) and the best of each is kept (a loaded
machine's load changes between runs; the idle cluster's scheduler and nanny stay up
while the pool runs). Target: dask ≥ 80 % of the
pool's throughput (the ``dask/pool`` column, throughput ratio = pool s / dask s). The
rows of both are compared (identical floats). One line per measurement is printed as
soon as it is known, and ``benchmarks/out/bench_dask.json`` is rewritten after each;
the most workers run first, so that a run cut short by ``--budget`` (or Ctrl-C) has
the largest counts.

Needs only the repository and its virtual environment (dask is the ``dask`` extra).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "benchmarks" / "out"
DEVICE = ROOT / "devices" / "push_demo.yaml"

#: Fabrication and operating variation of push_demo: every field derives vectorised
#: (``nondim.derive_samples``), so the workers run the solver, not pint.
TOLERANCES = [
    "slider.beam_width=normal:0.3 um",
    "slider.beam_thickness=normal:3%",
    "contact.friction=uniform:25%",
    "contact.impact_angle=normal:1 deg",
    "actuator.vertical_resonance=normal:3%",
    "actuator.horizontal_resonance=normal:5%",
    "drive.frequency=normal:1%",
]

#: Samples of the warm-up run on each pool or cluster (above the pool's small-study size).
WARMUP_SAMPLES = 400


def _study(device: Path, samples: int, seed: int = 0):
    from betvdesign.studies.tolerance import parse_tolerance, tolerance_study

    tols = [parse_tolerance(t) for t in TOLERANCES]
    return tolerance_study(device, tols, samples=samples, seed=seed)


def _timed(study, executor) -> tuple[float, list]:
    from betvdesign.studies.engine.runner import run_study

    t0 = time.perf_counter()
    rows = run_study(study, executor).rows
    return time.perf_counter() - t0, rows


def _load() -> str:
    try:
        return "/".join(f"{v:.1f}" for v in os.getloadavg())
    except OSError:  # pragma: no cover - not on Linux
        return "?"


def main(argv: list[str] | None = None) -> int:
    """Run the comparison; the exit status."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--samples", type=int, nargs="+", default=[20_000])
    ap.add_argument("--dask-chunksize", type=int, default=None)
    ap.add_argument(
        "--repeat", type=int, default=1, help="timed runs per backend, alternated; best kept"
    )
    ap.add_argument("--budget", type=float, default=230.0, help="seconds (default 230)")
    ap.add_argument("--device", type=Path, default=DEVICE)
    args = ap.parse_args(argv)

    import distributed

    from betvdesign.studies.engine.executors import DaskExecutor, ProcessExecutor

    t_start = time.perf_counter()
    OUT.mkdir(parents=True, exist_ok=True)
    out_path = OUT / "bench_dask.json"
    result: dict = {
        "machine": {
            "cpus": os.cpu_count(),
            "load_at_start": _load(),
            "python": platform.python_version(),
            "distributed": distributed.__version__,
        },
        "device": str(args.device),
        "tolerances": TOLERANCES,
        "dask_chunksize": args.dask_chunksize or "default (8 chunks per worker, <= 2048)",
        "runs": [],
    }
    print(
        f"# {os.cpu_count()} CPUs, load {_load()} (1/5/15 min), dask {distributed.__version__}, "
        f"dask chunk size {result['dask_chunksize']}",
        flush=True,
    )
    print(
        f"{'samples':>8} {'workers':>7} {'pool s':>8} {'dask s':>8} {'dask/pool':>9} "
        f"{'pool /s':>9} {'dask /s':>9} {'cluster s':>9} {'rows':>5}",
        flush=True,
    )
    warm_study = _study(args.device, WARMUP_SAMPLES, seed=1)
    studies = {}
    for n in args.samples:
        t0 = time.perf_counter()
        studies[n] = _study(args.device, n)
        print(f"# study of {n} samples built in {time.perf_counter() - t0:.2f} s", flush=True)
    skipped = []
    for n in args.samples:
        for w in sorted(set(args.workers), reverse=True):  # the most workers first
            if time.perf_counter() - t_start > args.budget:
                skipped.append((n, w))
                continue
            pool = ProcessExecutor(workers=w)
            _timed(warm_study, pool)  # fork server and kernels (once per process)
            t0 = time.perf_counter()
            with (
                distributed.LocalCluster(
                    n_workers=w,
                    threads_per_worker=1,
                    processes=True,
                    dashboard_address=":0",
                ) as cluster,
                distributed.Client(cluster) as client,
            ):
                t_cluster = time.perf_counter() - t0
                dask = DaskExecutor(client=client, chunksize=args.dask_chunksize)
                _timed(warm_study, dask)  # the workers' kernels (the warm-up plugin)
                # alternated, so that a change of the machine's load hits both alike
                pool_times, dask_times = [], []
                for _ in range(max(1, args.repeat)):
                    t, rows_pool = _timed(studies[n], pool)
                    pool_times.append(t)
                    t, rows_dask = _timed(studies[n], dask)
                    dask_times.append(t)
            t_pool, t_dask = min(pool_times), min(dask_times)
            same = rows_pool == rows_dask
            run = {
                "samples": n,
                "workers": w,
                "pool_s": round(t_pool, 3),
                "dask_s": round(t_dask, 3),
                "pool_runs_s": [round(t, 3) for t in pool_times],
                "dask_runs_s": [round(t, 3) for t in dask_times],
                "dask_throughput_vs_pool": round(t_pool / t_dask, 3),
                "cluster_start_s": round(t_cluster, 2),
                "rows_identical": same,
                "load": _load(),
            }
            result["runs"].append(run)
            out_path.write_text(json.dumps(result, indent=2) + "\n")
            print(
                f"{n:>8} {w:>7} {t_pool:>8.2f} {t_dask:>8.2f} {t_pool / t_dask:>9.2f} "
                f"{n / t_pool:>9.0f} {n / t_dask:>9.0f} {t_cluster:>9.1f} "
                f"{'same' if same else 'DIFF':>5}",
                flush=True,
            )
    result["machine"]["load_at_end"] = _load()
    result["skipped_over_budget"] = skipped
    result["total_s"] = round(time.perf_counter() - t_start, 1)
    out_path.write_text(json.dumps(result, indent=2) + "\n")
    if skipped:
        print(f"# over the {args.budget:.0f} s budget, skipped (samples, workers): {skipped}")
    print(f"# total {result['total_s']} s, load {_load()}; wrote {out_path}", flush=True)
    return 0 if all(r["rows_identical"] for r in result["runs"]) else 1


if __name__ == "__main__":
    sys.exit(main())
