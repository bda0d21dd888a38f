"""Speed of the design-space studies (issue 5 targets), measured, not asserted.

    .venv/bin/python benchmarks/bench_studies.py              # everything
    .venv/bin/python benchmarks/bench_studies.py map           # 1152-point map only
    .venv/bin/python benchmarks/bench_studies.py tolerance     # 10^4-sample tolerance only
    .venv/bin/python benchmarks/bench_studies.py regime        # 2000-point regime diagram
    options: --max-cycles N (map budget), --no-scaling, --fidelity lambda|periodic

Targets (2 cores): the 2 κ × 4 β × 9 α × 16 ϖ push/pull map to periodic states
in ≤ 60 s wall (goal ≤ 10 s); a 10⁴-sample tolerance study of one device in
≤ 60 s. Also reports how time grows with grid size (¼, ½, 1 of the map) and
with cycles-to-settle (per-point solve time against the solver's cycle count).
Writes benchmarks/out/bench_studies.json.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

import numpy as np

from betvdesign.studies.engine.executors import ProcessExecutor, SerialExecutor
from betvdesign.studies.engine.runner import run_study
from betvdesign.studies.points import periodic_point
from betvdesign.studies.pushpull import pushpull_study, summarise
from betvdesign.studies.regime import run_regime
from betvdesign.studies.tolerance import parse_tolerance, run_tolerance

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "benchmarks" / "out"

KAPPA = [0.1, 0.4]
BETA = [0.1, 0.5, 1.0, 1.5]
ALPHA = [0.1, *np.arange(0.5, 4.0001, 0.5).round(12).tolist()]
VARPI = np.round(np.arange(0.5, 2.0001, 0.1), 12).tolist()

#: Fabrication and operating variation of devices/push_demo.yaml (the benchmark device).
TOLERANCES = [
    "slider.beam_width=normal:0.3 um",
    "slider.beam_thickness=normal:3%",
    "head.geometry.diameter=normal:1 um",
    "contact.friction=uniform:25%",
    "contact.impact_angle=normal:1 deg",
    "actuator.vertical_resonance=normal:3%",
    "actuator.horizontal_resonance=normal:5%",
    "drive.frequency=normal:1%",
]


def bench_map(workers: int, max_cycles: int | None, scaling: bool) -> dict:
    """The 1152-point map on local processes, plus scaling and per-point costs."""
    assert len(KAPPA) * len(BETA) * len(ALPHA) * len(VARPI) == 1152
    res: dict = {"workers": workers, "max_cycles": max_cycles or "solver default (100000)"}
    sizes = (("third", ALPHA[::3]), ("two-thirds", ALPHA[:6]), ("full", ALPHA))
    for frac, alphas in sizes if scaling else sizes[-1:]:
        t0 = time.perf_counter()
        study, grid = pushpull_study(VARPI, alphas, BETA, KAPPA, max_cycles=max_cycles)
        out = OUT / f"map_{frac}.csv"  # rows kept for inspection (status, message)
        run = run_study(study, ProcessExecutor(workers), out=out, overwrite=True)
        wall = time.perf_counter() - t0
        status: dict[str, int] = {}
        for r in run.rows:
            status[r["status"]] = status.get(r["status"], 0) + 1
        summ = summarise(run.rows)
        res[frac] = {
            "points": grid.size,
            "wall_s": round(wall, 3),
            "status": status,
            "lambda_agreement": summ.agreement,
            "unbounded": len(summ.unbounded),
            "failed_on_resonance": sum(
                bool(d["resonance"]) for d in summ.not_converged if d not in summ.unbounded
            ),
        }
        print(
            f"map {frac:>10}: {grid.size:5d} points  {wall:7.2f} s wall on {workers} workers "
            f"{status}",
            file=sys.stderr,
        )
    # Per-point cost against cycles-to-settle, serially on a sample of the map.
    study, _ = pushpull_study(VARPI[::3], ALPHA[::2], BETA, KAPPA, max_cycles=max_cycles)
    costs = []
    for task in study.tasks:
        t0 = time.perf_counter()
        row = periodic_point(task)
        costs.append((time.perf_counter() - t0, row["cycles"] or 0, row["converged"]))
    t = np.array([c[0] for c in costs])
    cyc = np.array([c[1] for c in costs], dtype=float)
    res["per_point_serial"] = {
        "points": len(costs),
        "median_ms": round(1e3 * float(np.median(t)), 3),
        "p90_ms": round(1e3 * float(np.percentile(t, 90)), 3),
        "max_ms": round(1e3 * float(t.max()), 3),
        "cycles_median": float(np.median(cyc)),
        "cycles_max": float(cyc.max()),
        "ms_per_cycle_fit": (
            round(1e3 * float(np.polyfit(cyc, t, 1)[0]), 5) if np.ptp(cyc) > 0 else None
        ),
    }
    print(f"per point (serial): {res['per_point_serial']}", file=sys.stderr)
    return res


def bench_regime(workers: int) -> dict:
    """The vertical regime diagram on the CLI's default grid (2000 points, ϖ ∈ (0, 10])."""
    varpi = np.round(np.arange(0.005, 10.0001, 0.005), 12)
    t0 = time.perf_counter()
    _, summary = run_regime(varpi, executor=ProcessExecutor(workers))
    wall = time.perf_counter() - t0
    print(f"regime: {len(varpi)} points {wall:7.2f} s wall", file=sys.stderr)
    return {
        "points": len(varpi),
        "wall_s": round(wall, 3),
        "counts": summary["counts"],
        "overview_intervals": len(summary["overview"]),
        "errors": len(summary["errors"]),
    }


def bench_tolerance(workers: int, samples: int, fidelities: tuple[str, ...]) -> dict:
    device = ROOT / "devices" / "push_demo.yaml"
    tols = [parse_tolerance(t) for t in TOLERANCES]
    res: dict = {"workers": workers, "samples": samples, "device": str(device.name)}
    for fidelity in fidelities:
        t0 = time.perf_counter()
        _, summary = run_tolerance(
            device,
            tols,
            samples=samples,
            seed=1,
            fidelity=fidelity,
            sets=["forward"],
            executor=ProcessExecutor(workers),
        )
        wall = time.perf_counter() - t0
        s = summary["sets"]["forward"]
        res[fidelity] = {
            "wall_s": round(wall, 3),
            "p_push": s["p_push"],
            "p_pull": s["p_pull"],
            "p_not_converged": s["p_not_converged"],
            "p_outside_window": s["p_outside_window"],
            "speed_um_s_percentiles": s["speed_um_s_percentiles"],
            "most_sensitive": [e["field"] for e in s["sensitivities"][:3]],
        }
        print(f"tolerance {fidelity:>8}: {samples} samples {wall:7.2f} s wall", file=sys.stderr)
    return res


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument(
        "which", nargs="?", default="all", choices=("all", "map", "regime", "tolerance")
    )
    ap.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--samples", type=int, default=10_000)
    ap.add_argument("--max-cycles", type=int, default=None, help="cycle budget per solve")
    ap.add_argument("--no-scaling", action="store_true", help="full map only")
    ap.add_argument(
        "--fidelity", action="append", choices=("lambda", "periodic"), help="tolerance rung(s)"
    )
    args = ap.parse_args()
    args.fidelity = args.fidelity or ["lambda", "periodic"]
    out: dict = {"cpu_count": os.cpu_count()}
    # Warm-up: import and first-call costs outside the timings.
    run_study(pushpull_study([1.0], [1.0], [0.5], [0.4])[0], SerialExecutor())
    if args.which in ("all", "map"):
        out["map"] = bench_map(args.workers, args.max_cycles, not args.no_scaling)
    if args.which in ("all", "regime"):
        out["regime"] = bench_regime(args.workers)
    if args.which in ("all", "tolerance"):
        out["tolerance"] = bench_tolerance(args.workers, args.samples, tuple(args.fidelity))
    OUT.mkdir(parents=True, exist_ok=True)
    path = OUT / "bench_studies.json"  # merged: a partial run keeps the other parts
    old = json.loads(path.read_text()) if path.exists() else {}
    path.write_text(json.dumps(old | out, indent=2) + "\n")
    print(json.dumps(out, indent=2))


if __name__ == "__main__":
    main()
