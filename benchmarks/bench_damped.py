"""Cost of the optional physics (issue 12): damping and restitution against the ideal model.

    .venv/bin/python benchmarks/bench_damped.py [--q 30] [--e 0.1]

The 26 designs of bench_solver.py (named + window draws), each solved side by side in one
run as the paper's model, with damping (Q = --q normal and tangential) and with damping
and restitution (e = --e): CPU per simulated cycle (best of 5 runs of 2000 cycles) and
warm periodic solve from rest (median of 7). Targets (issue 12): damped per-cycle cost
within 1.5× of undamped (median ratio); damped periodic orbit median ≤ 0.3 ms.
Writes benchmarks/out/bench_damped.json.
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import sys
import time
from dataclasses import replace
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_solver import NAMED, OUT, ROOT, window_sets

from betvdesign.dynamics import periodic_orbit, simulate
from betvdesign.model.params import ModelParams


def _per_cycle_us(p: ModelParams, n: int = 2000) -> float:
    simulate(p, 3, log_events=False)
    best = math.inf
    for _ in range(5):
        c0 = time.process_time()
        simulate(p, n, log_events=False)
        best = min(best, time.process_time() - c0)
    return best / n * 1e6


def _periodic_ms(p: ModelParams) -> tuple[float, str]:
    po = periodic_orbit(p)
    ts = []
    for _ in range(7):
        c0 = time.process_time()
        periodic_orbit(p)
        ts.append(time.process_time() - c0)
    return statistics.median(ts) * 1e3, po.status


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--q", type=float, default=30.0, help="quality factor, both directions")
    ap.add_argument("--e", type=float, default=0.1, help="coefficient of restitution")
    args = ap.parse_args(argv)
    z = 1.0 / (2.0 * args.q)
    variants = {
        "ideal": {},
        f"Q={args.q:g}": {"zeta_v": z, "zeta_h": z},
        f"Q={args.q:g},e={args.e:g}": {"zeta_v": z, "zeta_h": z, "restitution": args.e},
    }
    rows = []
    for name, p in {**NAMED, **window_sets()}.items():
        row: dict = {"design": name, **p.as_dict()}
        for v, kw in variants.items():
            q = replace(p, **kw)
            row[f"{v} us/cycle"] = _per_cycle_us(q)
            row[f"{v} periodic ms"], row[f"{v} status"] = _periodic_ms(q)
        rows.append(row)
        print(
            f"  {name:16s} "
            + "  ".join(
                f"{v}: {row[f'{v} us/cycle']:5.2f} µs {row[f'{v} periodic ms']:6.2f} ms "
                f"{row[f'{v} status']}"
                for v in variants
            )
        )
    summary = {}
    for v in variants:
        per = [r[f"{v} us/cycle"] for r in rows]
        ok = [r[f"{v} periodic ms"] for r in rows if r[f"{v} status"] == "success"]
        summary[v] = {
            "us_per_cycle_median": statistics.median(per),
            "periodic_ms_median": statistics.median(ok) if ok else None,
            "periodic_ms_max": max(ok) if ok else None,
            "solved": f"{len(ok)}/{len(rows)}",
        }
        if v != "ideal":
            ratios = [r[f"{v} us/cycle"] / r["ideal us/cycle"] for r in rows]
            summary[v]["cost_ratio_median"] = statistics.median(ratios)
            summary[v]["cost_ratio_max"] = max(ratios)
    for v, s in summary.items():
        print(f"{v:14s} {json.dumps(s)}")
    OUT.mkdir(parents=True, exist_ok=True)
    path = OUT / "bench_damped.json"
    path.write_text(json.dumps({"rows": rows, "summary": summary}, indent=1))
    print(f"wrote {path.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
