"""Verdict errors: the mode `betv check` reports against brute force, on held-out designs.

    python benchmarks/bench_verdict.py            # 5000 designs (4000 in the λ fit range,
                                                  # 1000 far outside it), 2 processes
    python benchmarks/bench_verdict.py -n 500     # a quicker subset

For every design the check's mode (``checker.check_derivation`` on a derivation with
those parameters: the exact periodic orbit, ``domain.mode_of``) is compared with brute
force: the transient from rest (``dynamics.simulate``), extended until the mean
increment over the last 500 cycles agrees with the 500 before to 0.1 % (up to
400 000 cycles); its sign is the brute-force mode. The λ fit's mode is counted beside
it. Seeds differ from every sample the toolkit was measured on (held out).
"""

from __future__ import annotations

import argparse
import dataclasses
import functools
import json
import math
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
SEED = 20261124
WINDOW = 500
MAX_CYCLES = 400_000


def designs(n: int, seed: int = SEED) -> list[tuple[float, float, float, float, str]]:
    """4/5 uniform in the window and the λ fit range, 1/5 log-uniform far outside it."""
    rng = np.random.default_rng(seed)
    n_fit = (4 * n) // 5
    out = []
    for _ in range(n_fit):
        out.append(
            (
                rng.uniform(0.5, 2.0),
                rng.uniform(0.1, 4.0),
                rng.uniform(0.1, 1.5),
                rng.uniform(0.1, 0.4),
                "fit range",
            )
        )
    for _ in range(n - n_fit):
        out.append(
            (
                rng.uniform(0.5, 2.0),
                math.exp(rng.uniform(math.log(0.01), math.log(10.0))),
                math.exp(rng.uniform(math.log(0.05), math.log(20.0))),
                math.exp(rng.uniform(math.log(0.02), math.log(1.0))),
                "wide",
            )
        )
    return [tuple(float(v) if isinstance(v, float) else v for v in d) for d in out]


def brute_force(p) -> tuple[str | None, float | None, int]:
    """Sign of the settled mean increment from rest (None: did not settle)."""
    from betvdesign.dynamics import simulate
    from betvdesign.model.domain import mode_of

    state, n, ds = None, 0, []
    chunk = 4_000
    while n < MAX_CYCLES:
        tr = simulate(p, chunk, state0=state, log_events=False)
        if not tr.success:
            return None, None, n
        ds.append(tr.delta_s)
        state = tr.section[-1].copy()
        n += chunk
        d = np.concatenate(ds)[-2 * WINDOW :]
        last, before = d[WINDOW:].mean(), d[:WINDOW].mean()
        if abs(last - before) <= 1e-3 * max(abs(last), 1e-12):
            return mode_of(last), float(last), n
        chunk = n  # double
    return None, None, n


@functools.cache
def _base():
    """A device derivation whose one set's parameters each design replaces."""
    from betvdesign.nondim.device import derive
    from betvdesign.spec.loader import load_device

    return derive(load_device(ROOT / "devices" / "pull_demo.yaml"))


def one(design: tuple[float, float, float, float, str]) -> dict:
    from betvdesign.checks.checker import check_derivation
    from betvdesign.model.params import ModelParams

    w, a, b, k, family = design
    p = ModelParams(w, a, b, k)
    base = _base()
    s = dataclasses.replace(base.sets[0], params=p, lam=p.lam, published=[])
    t0 = time.perf_counter()
    res = check_derivation(dataclasses.replace(base, sets=[s]), margin=False, settle=False)
    t_check = time.perf_counter() - t0
    mode = res.sets[0].mode
    bf, bf_ds, cycles = brute_force(p)
    return {
        "varpi": w,
        "alpha": a,
        "beta": b,
        "kappa": k,
        "family": family,
        "lam": p.lam,
        "check_mode": mode,
        "status": getattr(res.sets[0].periodic, "status", None),
        "delta_s": getattr(res.sets[0].periodic, "delta_s", None),
        "brute_mode": bf,
        "brute_delta_s": bf_ds,
        "brute_cycles": cycles,
        "lambda_mode": p.lambda_mode,
        "check_s": t_check,
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("-n", type=int, default=5000)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("-o", "--output", type=Path, default=ROOT / "reports" / "bench_verdict.json")
    args = ap.parse_args()
    t0 = time.perf_counter()
    with ProcessPoolExecutor(args.workers) as ex:
        rows = list(ex.map(one, designs(args.n), chunksize=16))
    compared = [r for r in rows if r["check_mode"] and r["brute_mode"]]
    wrong = [r for r in compared if r["check_mode"] != r["brute_mode"]]
    lam_cmp = [r for r in compared if r["brute_mode"] in ("push", "pull")]
    lam_wrong = [r for r in lam_cmp if r["lambda_mode"] != r["brute_mode"]]
    no_orbit = [r for r in rows if not r["check_mode"]]
    unsettled = [r for r in rows if r["check_mode"] and not r["brute_mode"]]
    summary = {
        "designs": len(rows),
        "seed": SEED,
        "compared": len(compared),
        "verdict_mode_errors": len(wrong),
        "errors": wrong,
        "check_without_orbit": {
            s: sum(r["status"] == s for r in no_orbit)
            for s in sorted({r["status"] for r in no_orbit})
        },
        "brute_force_not_settled": len(unsettled),
        "lambda_mode_errors": len(lam_wrong),
        "lambda_error_rate": len(lam_wrong) / max(len(lam_cmp), 1),
        "median_check_s": float(np.median([r["check_s"] for r in rows])),
        "wall_s": time.perf_counter() - t0,
        "command": f"python benchmarks/bench_verdict.py -n {args.n}",
    }
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps({"summary": summary, "rows": rows}, indent=1))
    print(json.dumps({k: v for k, v in summary.items() if k != "errors"}, indent=1))
    for r in wrong:
        print("  ERROR", r)


if __name__ == "__main__":
    main()
