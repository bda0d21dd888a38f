"""The coupled head (docs/MODEL.md "Coupled head"): accuracy, stiffness cost, adequacy rung.

    python benchmarks/bench_coupled.py accuracy    # -> benchmarks/out/coupled_accuracy.json
    python benchmarks/bench_coupled.py stiff       # -> benchmarks/out/coupled_stiff.json
    python benchmarks/bench_coupled.py adequacy    # -> benchmarks/out/coupled_adequacy.json

``accuracy``: the coupled reference (solve_ivp DOP853 with events, rtol 1e-12) against
(a) the exact solver at ρ = 0 (32 designs, 12 cycles) and (b) the exact-flow automaton of
tests/test_coupled_reference.py (matrix exponentials, ρ from −0.999 to 0.9, 32 designs,
4 cycles): largest Δs and section-state differences. ``stiff``: cost per cycle as the
clamped direction stiffens (ρ → 1). ``adequacy``: the coupled rung on every distinct
shipped actuator set. Prints markdown tables.
"""

from __future__ import annotations

import json
import math
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "benchmarks" / "out"
sys.path.insert(0, str(ROOT / "tests"))

from test_coupled_reference import _coupled_designs, _designs, _Exact  # noqa: E402

from betvdesign.dynamics import simulate  # noqa: E402
from betvdesign.dynamics.coupled_reference import simulate_coupled  # noqa: E402
from betvdesign.model.params import HeadCoupling, ModelParams  # noqa: E402


def _rel(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.abs(a - b) / np.maximum(1.0, np.abs(b))))


def accuracy() -> dict:
    rows = []
    for p in _designs(32, 3):
        t0 = time.perf_counter()
        ref = simulate_coupled(p, HeadCoupling(0.0, 0.7), 12)
        dt = time.perf_counter() - t0
        ex = simulate(p, 12)
        rows.append(dict(kind="rho=0 vs exact solver", rho=0.0, chi=0.7, **p.as_dict(),
                         d_ds=float(np.max(np.abs(ref.delta_s - ex.delta_s))),
                         d_state=_rel(ref.section, ex.section), events=len(ref.events),
                         nfev=ref.n_fev, s=dt, cycles=12))  # fmt: skip
    for p, c in _coupled_designs():
        truth = _Exact(p, c).run(4)
        t0 = time.perf_counter()
        ref = simulate_coupled(p, c, 4)
        dt = time.perf_counter() - t0
        rows.append(dict(kind="coupled vs exact-flow automaton", rho=c.rho, chi=c.chi,
                         **p.as_dict(),
                         d_ds=float(np.max(np.abs(ref.delta_s - np.diff(truth[:, 4])))),
                         d_state=_rel(ref.section, truth), events=len(ref.events),
                         nfev=ref.n_fev, s=dt, cycles=4))  # fmt: skip
    print(
        "| comparison | designs | ρ range | max abs ΔΔs | max rel state diff | events "
        "| s/cycle (median) |"
    )
    print("|---|---|---|---|---|---|---|")
    for kind in ("rho=0 vs exact solver", "coupled vs exact-flow automaton"):
        r = [x for x in rows if x["kind"] == kind]
        rhos = [x["rho"] for x in r]
        print(f"| {kind} | {len(r)} | {min(rhos):.3f} … {max(rhos):.3f} | "
              f"{max(x['d_ds'] for x in r):.1e} | {max(x['d_state'] for x in r):.1e} | "
              f"{sum(x['events'] for x in r)} | "
              f"{np.median([x['s'] / x['cycles'] for x in r]):.3f} |")  # fmt: skip
    return {"rows": rows}


def stiff() -> dict:
    p = ModelParams(1.2, 2.04, 0.5, 0.15)
    rows = []
    print("| ρ | a = 1/(1−ρ²) | √λ₊/ϖ | RHS evals per cycle | s per cycle |")
    print("|---|---|---|---|---|")
    for rho in (0.0, 0.9, 0.99, 0.999, 0.9999):
        c = HeadCoupling.from_angle(rho, p.alpha, math.pi / 4)
        a = c.a
        lam = (
            a
            * ((1 + p.alpha) + math.sqrt((1 + p.alpha) ** 2 - 4 * p.alpha * (1 - rho**2)))
            / (2 * p.alpha)
        )
        n = 10
        t0 = time.perf_counter()
        r = simulate_coupled(p, c, n)
        dt = (time.perf_counter() - t0) / n
        row = dict(rho=rho, a=a, stiff_over_drive=math.sqrt(lam) / p.varpi, nfev=r.n_fev / n, s=dt,
                   status=r.status)  # fmt: skip
        rows.append(row)
        print(f"| {rho} | {a:.4g} | {row['stiff_over_drive']:.3g} | {row['nfev']:.0f} | {dt:.3f} |")
    return {"design": p.as_dict(), "rows": rows}


def adequacy() -> dict:
    from betvdesign.checks.coupled import coupled_rung
    from betvdesign.nondim.device import derive_file

    rows, seen = [], set()
    print(
        "| device / set | ρ | χ | a | decoupled (exact) | coupled (reference) | change "
        "| status | s |"
    )
    print("|---|---|---|---|---|---|---|---|---|")
    for f in sorted((ROOT / "devices").glob("*.yaml")):
        for sd in derive_file(f).sets:
            key = (
                replace(sd.params, zeta_v=0.0, zeta_h=0.0, restitution=0.0),
                sd.springs and sd.springs.rho,
            )
            if sd.springs is None or key in seen:
                continue
            seen.add(key)
            t0 = time.perf_counter()
            r = coupled_rung(sd)
            dt = time.perf_counter() - t0
            ch = r.speed_change
            rows.append(dict(device=f.stem, set=sd.name, rho=r.rho, chi=r.chi, a=r.stiffness,
                             decoupled=r.decoupled.text, decoupled_ds=r.decoupled.delta_s,
                             coupled=r.coupled.text, coupled_ds=r.coupled.delta_s,
                             change=ch, status=r.status, s=dt, message=r.message))  # fmt: skip
            chs = "—" if ch is None else ("opposite" if ch < -1.0 else f"{ch:+.0%}")
            print(f"| {f.stem} / {sd.name} | {r.rho:.4f} | {r.chi:.3f} | {r.stiffness:.3g} "
                  f"| {r.decoupled.text} | {r.coupled.text} | {chs} | {r.status} "
                  f"| {dt:.1f} |")  # fmt: skip
    return {"rows": rows}


def main() -> None:
    what = sys.argv[1] if len(sys.argv) > 1 else "accuracy"
    fn = {"accuracy": accuracy, "stiff": stiff, "adequacy": adequacy}[what]
    res = fn()
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / f"coupled_{what}.json").write_text(json.dumps(res, indent=1, default=str))


if __name__ == "__main__":
    main()
