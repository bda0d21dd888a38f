"""The coupled head (docs/MODEL.md "Coupled head"): accuracy, stiffness cost, adequacy rung.

    python benchmarks/bench_coupled.py accuracy    # -> benchmarks/out/coupled_accuracy.json
    python benchmarks/bench_coupled.py stiff       # -> benchmarks/out/coupled_stiff.json
    python benchmarks/bench_coupled.py adequacy    # -> benchmarks/out/coupled_adequacy.json

``accuracy``: the coupled reference (solve_ivp DOP853 with events, rtol 1e-12) against
(a) the exact solver at ρ = 0 (32 designs, 12 cycles) and (b) the exact-flow automaton of
tests/test_coupled_reference.py (matrix exponentials, ρ from −0.999 to 0.9, 32 designs,
4 cycles); the compiled exact coupled solver (:mod:`betvdesign.dynamics.coupled`) against
the reference and the exact-flow automaton on the same 32 designs: largest Δs and
section-state differences. ``stiff``: cost per cycle of the reference and of the kernel
as the clamped direction stiffens (ρ → 1). ``adequacy``: the coupled rung (kernel) on
every distinct shipped actuator set and a drawn-only one, timed against the reference
run as the rung ran it before (Newton from the decoupled orbit, else 200 cycles from rest
and Newton again). Prints markdown tables.
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
from betvdesign.dynamics.coupled import simulate_coupled as kernel_coupled  # noqa: E402
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
        t0 = time.perf_counter()
        ker = kernel_coupled(p, c, 4)
        dt = time.perf_counter() - t0
        for kind, other in (("kernel vs reference", ref.section),
                            ("kernel vs exact-flow automaton", truth)):  # fmt: skip
            rows.append(dict(kind=kind, rho=c.rho, chi=c.chi, **p.as_dict(),
                             d_ds=float(np.max(np.abs(np.diff(ker.section[:, 4])
                                                      - np.diff(other[:, 4])))),
                             d_state=_rel(ker.section, other), events=ker.n_events,
                             nfev=ker.n_fev, s=dt, cycles=4))  # fmt: skip
    for p in _designs(32, 3):
        ex = simulate(p, 12)
        ker = kernel_coupled(p, HeadCoupling(0.0, 0.7), 12)
        same = np.array_equal(ex.section, ker.section) and ex.solver == ker.solver
        rows.append(dict(kind="kernel at rho=0 vs exact solver", rho=0.0, chi=0.7,
                         **p.as_dict(), d_ds=0.0 if same else math.inf,
                         d_state=0.0 if same else math.inf, events=ker.n_events, nfev=0,
                         s=ker.elapsed_s, cycles=12))  # fmt: skip
    print(
        "| comparison | designs | ρ range | max abs ΔΔs | max rel state diff | events "
        "| s/cycle (median) |"
    )
    print("|---|---|---|---|---|---|---|")
    for kind in ("rho=0 vs exact solver", "coupled vs exact-flow automaton",
                 "kernel vs reference", "kernel vs exact-flow automaton",
                 "kernel at rho=0 vs exact solver"):  # fmt: skip
        r = [x for x in rows if x["kind"] == kind]
        rhos = [x["rho"] for x in r]
        print(f"| {kind} | {len(r)} | {min(rhos):.3f} … {max(rhos):.3f} | "
              f"{max(x['d_ds'] for x in r):.1e} | {max(x['d_state'] for x in r):.1e} | "
              f"{sum(x['events'] for x in r)} | "
              f"{np.median([x['s'] / x['cycles'] for x in r]):.2g} |")  # fmt: skip
    return {"rows": rows}


def stiff() -> dict:
    p = ModelParams(1.2, 2.04, 0.5, 0.15)
    rows = []
    kernel_coupled(p, HeadCoupling(0.5, 1.0), 2)  # compiled (or loaded) before timing
    simulate(p, 2)
    print("| ρ | a = 1/(1−ρ²) | √λ₊/ϖ | reference: RHS evals per cycle | reference: s per "
          "cycle | kernel: steps per cycle | kernel: cycles/s |")  # fmt: skip
    print("|---|---|---|---|---|---|---|")
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
        nk = 1000
        t0 = time.perf_counter()
        k = kernel_coupled(p, c, nk, log_events=False)
        dk = time.perf_counter() - t0
        row = dict(rho=rho, a=a, stiff_over_drive=math.sqrt(lam) / p.varpi, nfev=r.n_fev / n, s=dt,
                   status=r.status, kernel_steps=k.n_fev / nk, kernel_cycles_per_s=nk / dk,
                   kernel_status=k.status, kernel_solver=k.solver)  # fmt: skip
        rows.append(row)
        print(f"| {rho} | {a:.4g} | {row['stiff_over_drive']:.3g} | {row['nfev']:.0f} | {dt:.3f} "
              f"| {row['kernel_steps']:.0f} | {nk / dk:,.0f} |")  # fmt: skip
    return {"design": p.as_dict(), "rows": rows}


def _reference_rung(sd) -> tuple[float | None, float]:
    """The coupled Δs by the reference as the rung ran it before the kernel, and its time."""
    from betvdesign.checks.coupled import coupling_of
    from betvdesign.dynamics import periodic_orbit
    from betvdesign.dynamics.coupled_reference import coupled_periodic_orbit
    from betvdesign.dynamics.coupled_reference import simulate_coupled as ref_sim

    t0 = time.perf_counter()
    p = replace(sd.params, zeta_v=0.0, zeta_h=0.0, restitution=0.0)
    cpl = coupling_of(sd)
    ex = periodic_orbit(p)
    ok = ex.status == "success"
    per = ex.period_cycles if ok else 1
    kw = dict(rtol=1e-10, atol=1e-12, tol=1e-8)
    orb = coupled_periodic_orbit(p, cpl, guess=ex.state if ok else None, period=per, **kw)
    if orb.status != "success":
        run = ref_sim(p, cpl, 200, rtol=1e-10, atol=1e-12)
        if run.status == "success":
            orb = coupled_periodic_orbit(p, cpl, guess=run.section[-1], period=per, **kw)
    ds = orb.delta_s if orb.status == "success" else None
    return ds, time.perf_counter() - t0


def _drawn_only(stem: str, tmp: Path) -> Path:
    """A shipped file without its measured resonances and tangential stiffness."""
    text = (ROOT / "devices" / f"{stem}.yaml").read_text().splitlines()
    keep = [ln for ln in text if not ("_resonance:" in ln or "horizontal_stiffness:" in ln)]
    out = tmp / f"{stem}_drawn_only.yaml"
    out.write_text("\n".join(keep) + "\n")
    return out


def adequacy() -> dict:
    import tempfile

    from betvdesign.checks.coupled import coupled_rung
    from betvdesign.nondim.device import derive_file

    rows, seen = [], set()
    tmp = Path(tempfile.mkdtemp())
    files = sorted((ROOT / "devices").glob("*.yaml"))
    files += [_drawn_only(stem, tmp) for stem in ("pull_demo", "push_demo")]
    baseline = "--no-reference" not in sys.argv
    first = derive_file(files[0]).sets[0]
    coupled_rung(first)  # kernels compiled (or loaded) before timing
    print(
        "| device / set | ρ | χ | a | decoupled (exact) | coupled (kernel) | change "
        "| status | uses | rung s (kernel) | reference s (before) | |ΔΔs| kernel − reference |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for f in files:
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
            ref_ds, ref_s = _reference_rung(sd) if baseline else (None, math.nan)
            diff = (
                abs(ref_ds - r.coupled.delta_s)
                if ref_ds is not None and r.coupled.delta_s is not None
                else None
            )
            ch = r.speed_change
            rows.append(dict(device=f.stem, set=sd.name, rho=r.rho, chi=r.chi, a=r.stiffness,
                             decoupled=r.decoupled.text, decoupled_ds=r.decoupled.delta_s,
                             coupled=r.coupled.text, coupled_ds=r.coupled.delta_s,
                             change=ch, status=r.status, uses=r.uses, s=dt,
                             reference_s=ref_s, reference_ds=ref_ds, d_ds=diff,
                             message=r.message))  # fmt: skip
            chs = "—" if ch is None else ("opposite" if ch < -1.0 else f"{ch:+.0%}")
            ds = "—" if diff is None else f"{diff:.1e}"
            print(f"| {f.stem} / {sd.name} | {r.rho:.4f} | {r.chi:.3f} | {r.stiffness:.3g} "
                  f"| {r.decoupled.text} | {r.coupled.text} | {chs} | {r.status} | {r.uses} "
                  f"| {dt:.3f} | {ref_s:.1f} | {ds} |")  # fmt: skip
    return {"rows": rows}


def main() -> None:
    what = sys.argv[1] if len(sys.argv) > 1 else "accuracy"
    fn = {"accuracy": accuracy, "stiff": stiff, "adequacy": adequacy}[what]
    res = fn()
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / f"coupled_{what}.json").write_text(json.dumps(res, indent=1, default=str))


if __name__ == "__main__":
    main()
