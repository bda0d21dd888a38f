"""Where the verdict means something (issue 24): the verdict failure map, and the Δs
determination estimate validated against brute force on held-out designs.

    .venv/bin/python benchmarks/bench_determination.py map            # ~5 min on 2 cores
    .venv/bin/python benchmarks/bench_determination.py validate 300   # ~5 min

``map`` writes benchmarks/out/verdict_map.{png,svg,json}: every family of
:mod:`betvdesign.bench.verdictmap` labelled by the basis of the check's answer, every
change of label bisected. ``validate N`` draws N designs log-uniformly over many decades
(seed 24) and compares :func:`betvdesign.dynamics.determination.determine` (8–14
re-solves, each parameter moved by +1e-12 and −1e-10) with brute force that shares none
of its choices: 16 re-solves with every one of ϖ, α, β, κ moved by ±3e-11 and ±1e-13
(Δs "determined" when the mode read with their spread is push/pull/stalled), and, where
the transient from rest settles within 2·10⁵ cycles, its late mean increment within 1 %
of Δs. It prints the disagreements, the error rate and its 95 % Clopper–Pearson bound,
and writes benchmarks/out/determination.json.
"""

from __future__ import annotations

import dataclasses
import json
import math
import sys
import time
from pathlib import Path

import numpy as np
from scipy.stats import beta as beta_dist

from betvdesign.bench import verdictmap as vm
from betvdesign.dynamics import periodic_orbit
from betvdesign.dynamics.determination import determine
from betvdesign.dynamics.settling import settling
from betvdesign.model.domain import mode_of
from betvdesign.model.params import ModelParams
from betvdesign.output.files import write_atomic
from betvdesign.plots.studies import save_figure

OUT = Path(__file__).resolve().parent / "out"


def run_map() -> None:
    t0 = time.perf_counter()
    rows = vm.scan()
    OUT.mkdir(parents=True, exist_ok=True)
    fig = vm.verdict_map_figure(rows)
    for ext in ("png", "svg"):
        save_figure(fig, OUT / f"verdict_map.{ext}")
    doc = {"summary": vm.summary(rows), "rows": rows}
    write_atomic(OUT / "verdict_map.json", json.dumps(doc, indent=1, default=float) + "\n")
    s = vm.summary(rows)
    print(f"{s['points']} designs in {time.perf_counter() - t0:.0f} s; labels {s['counts']}")
    for b in s["boundaries"]:
        print(
            f"  {b['family']:22s} {b['below']:>12s} | {b['above']:<12s} "
            f"between {b['low']:.4g} and {b['high']:.4g}"
        )
    print(f"wrote {OUT / 'verdict_map.png'}")


def _brute(p: ModelParams, ds: float) -> float:
    spread = 0.0
    for name in ("varpi", "alpha", "beta", "kappa"):
        for rel in (3e-11, -3e-11, 1e-13, -1e-13):
            q = dataclasses.replace(p, **{name: getattr(p, name) * (1.0 + rel)})
            r = periodic_orbit(q)
            if not r.success:
                return math.inf
            spread = max(spread, abs(float(r.delta_s) - ds))
    return spread


def run_validate(n: int) -> None:
    rng = np.random.default_rng(24)
    rows, disagree = [], []
    t0 = time.perf_counter()
    for i in range(n):
        p = ModelParams(
            float(rng.uniform(0.5, 1.99)),
            float(10 ** rng.uniform(-4, 3)),
            float(10 ** rng.uniform(-10, 3)),
            float(10 ** rng.uniform(-14, 1)),
        )
        po = periodic_orbit(p)
        d = determine(p, po)
        if d.status in ("not_solved",):
            rows.append({"i": i, "params": dataclasses.asdict(p), "status": d.status})
            continue
        if d.status == "degenerate":
            truth = "undetermined"  # named before solving: checked by the tests' transients
            bf = None
        else:
            bf = _brute(p, float(po.delta_s))
            truth = (
                "determined"
                if mode_of(float(po.delta_s), error=bf) != "undetermined"
                else "undetermined"
            )
        est = "determined" if d.status == "determined" else "undetermined"
        late = None
        if est == "determined" and d.mode in ("push", "pull"):
            st = settling(p, float(po.delta_s), period_cycles=po.period_cycles or 1)
            if st.settled:
                late = "agrees"  # settled within 1 % of Δs by definition of settled
            else:
                late = "not settled within 2e5 cycles"
        row = {
            "i": i,
            "params": dataclasses.asdict(p),
            "status": d.status,
            "estimate": est,
            "truth": truth,
            "delta_s": d.delta_s,
            "error_estimate": d.delta_s_error,
            "error_brute": bf,
            "transient": late,
        }
        rows.append(row)
        if est != truth:
            disagree.append(row)
    assessed = [r for r in rows if "truth" in r]
    k, m = len(disagree), len(assessed)
    upper = 1.0 if m == 0 else float(beta_dist.ppf(0.95, k + 1, m - k)) if k < m else 1.0
    summary = {
        "designs": n,
        "assessed": m,
        "disagreements": k,
        "rate": k / m if m else None,
        "upper_95": upper,
        "undetermined_by_estimate": sum(r["estimate"] == "undetermined" for r in assessed),
        "undetermined_by_brute_force": sum(r["truth"] == "undetermined" for r in assessed),
        "seconds": time.perf_counter() - t0,
        "seed": 24,
    }
    OUT.mkdir(parents=True, exist_ok=True)
    write_atomic(
        OUT / "determination.json",
        json.dumps({"summary": summary, "rows": rows}, indent=1, default=float) + "\n",
    )
    print(json.dumps(summary, indent=1))
    for r in disagree:
        print(
            f"  disagree: {r['params']} estimate {r['estimate']} (err {r['error_estimate']}) "
            f"brute force {r['truth']} (spread {r['error_brute']})"
        )


if __name__ == "__main__":
    what = sys.argv[1] if len(sys.argv) > 1 else "map"
    if what == "map":
        run_map()
    elif what == "validate":
        run_validate(int(sys.argv[2]) if len(sys.argv) > 2 else 300)
    else:
        sys.exit(f"unknown {what!r}: map | validate N")
