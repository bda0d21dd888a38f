"""Advice against fix, and fix against a dense scan (issue 21).

    python benchmarks/bench_advice.py consistency -n 200   # shipped + 200 seeded failing designs
    python benchmarks/bench_advice.py boundary -n 50       # 50 seeded single-field cases

consistency: for every shipped device and ``n`` seeded random failing designs (shipped
devices with 2-3 of their fields moved log-uniformly by up to ×/÷ 2.5), ``betv check``'s
advice (:func:`betvdesign.studies.fix.advise`) is applied field by field — the hint's
direction by the amount it gives, which is ``betv fix --vary FIELD``'s value — and the
design re-checked by ``check_derivation`` (the independent truth: verdict PASS and the
rule mode-margin passes). A contradiction: a hint that does not pass when applied, a
failing rule whose fix text is not the advice, or ``betv fix --vary FIELD`` giving
another value or direction.

boundary: seeded (device, field) cases; ``betv fix --vary FIELD`` gives the boundary b
and the value b·(1 ± 5 %); a dense scan outward from the current value in 0.5 % steps
(alternating sides, the check itself) finds the nearest passing value p; the case is
within tolerance when |ln(b/p)| ≤ 1 % and the value lies 5 % beyond b on the passing
side. Writes benchmarks/out/advice_*.json.
"""

from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
DEVICES = sorted((ROOT / "devices").glob("*.yaml"))
SEED = 2026_21
FIELDS = (
    "drive.frequency",
    "slider.beam_width",
    "slider.beam_length",
    "head.geometry.diameter",
    "head.geometry.length",
    "head.mass",
    "actuator.vertical_resonance",
    "actuator.horizontal_resonance",
    "actuator.alpha",
    "contact.impact_angle",
)


def passes(spec) -> bool:
    """The independent truth: betv check's verdict PASS and the mode held at the margin
    corners."""
    from betvdesign.checks.checker import check_derivation
    from betvdesign.errors import BetvError
    from betvdesign.nondim.device import derive

    try:
        res = check_derivation(derive(spec), adequacy=False)
    except BetvError:
        return False
    margin_ok = all(r.passed for r in res.rules if r.id == "mode-margin")
    return res.verdict == "pass" and margin_ok


def random_design(seed: int):
    """The first failing design drawn by a generator seeded with ``seed`` (see
    :func:`random_designs`); each seed gives one design, so workers draw in parallel."""
    return random_designs(1, seed)[0]


def random_designs(n: int, seed: int = SEED, *, failing: bool = True):
    """``n`` seeded designs: a shipped device with 2-3 of its fields moved by ×/÷ up to 2.5
    (impact angle within 15-70°); only failing ones when ``failing``."""
    from betvdesign.checks.checker import check_derivation
    from betvdesign.errors import BetvError
    from betvdesign.nondim.device import derive
    from betvdesign.spec.loader import load_device
    from betvdesign.spec.units import ureg
    from betvdesign.studies.fix import outcome_of
    from betvdesign.studies.fixfields import current_value

    rng = np.random.default_rng(seed)
    specs = [load_device(p) for p in DEVICES]
    out, attempts = [], 0
    while len(out) < n:
        spec = specs[rng.integers(len(specs))]
        have = [f for f in FIELDS if current_value(spec, f) is not None]
        k = int(rng.integers(2, 4))
        chosen = rng.choice(have, size=min(k, len(have)), replace=False)
        changes: list[tuple[str, object]] = []
        for f in chosen:
            x0, unit = current_value(spec, f)
            if f == "contact.impact_angle":
                x = float(rng.uniform(15, 70))
            else:
                x = x0 * math.exp(rng.uniform(-math.log(2.5), math.log(2.5)))
            changes.append((str(f), ureg.Quantity(x, unit) if unit else x))
        attempts += 1
        if attempts > 100 * n:
            raise RuntimeError(f"no {n} failing designs in {attempts} draws")
        try:
            s = spec.replace(*changes[0], *changes[1:])
            res = check_derivation(derive(s), adequacy=False)
        except (BetvError, ValueError):
            continue
        if failing and outcome_of(res).passed:
            continue
        out.append((s, res))
    return out


def _one(args) -> dict:
    """Consistency of one design (a worker of :func:`consistency`)."""
    from betvdesign.checks.checker import check_derivation
    from betvdesign.nondim.device import derive
    from betvdesign.studies.fix import advice_text, advise, find_fixes, outcome_of, with_advice
    from betvdesign.studies.fixfields import parse_vary

    label, spec, compare = args
    t0 = time.perf_counter()
    if isinstance(spec, int):  # a seed: draw the design here
        spec = random_design(spec)[0]
    else:  # a path: load it here (quantities of this process's registry)
        from betvdesign.spec.loader import load_device

        spec = load_device(spec)
    res = check_derivation(derive(spec), adequacy=False)
    answers = advise(res)
    text = advice_text(answers) if answers else ""
    res = with_advice(res, answers)
    bad, hints = [], 0
    for r in res.rules:
        if not r.passed and (r.severity == "error" or r.id == "mode-margin") and r.fix != text:
            bad.append(f"{r.id}: fix text is not the advice")
    for a in answers:
        if a.value is None:
            continue
        hints += 1
        v = parse_vary(spec, [a.field])[0]
        if not passes(spec.replace(a.field, v.quantity(a.value))):
            bad.append(f"{a.field} -> {a.text(a.value)} does not pass")
        if compare:  # betv fix --vary FIELD: the same value
            best = find_fixes(spec, [v], pairs=False).best
            if best is None or abs(math.log(best.changes[a.field] / a.value)) > 1e-9:
                bad.append(f"{a.field}: betv fix gives {best and best.changes}")
    return {
        "design": label,
        "failing": list(outcome_of(res).failing),
        "advice": [a.as_dict() for a in answers],
        "hints": hints,
        "contradictions": bad,
        "seconds": time.perf_counter() - t0,
    }


def consistency(n: int, workers: int = 1, compare: int = 20) -> dict:
    from concurrent.futures import ProcessPoolExecutor, as_completed

    jobs = [(p.stem, str(p), True) for p in DEVICES]
    jobs += [(f"random-{i}", SEED * 1000 + i, i < compare) for i in range(n)]
    t0 = time.perf_counter()
    rows = []
    with ProcessPoolExecutor(workers) as pool:
        futures = [pool.submit(_one, j) for j in jobs]
        for k, fut in enumerate(as_completed(futures), 1):
            r = fut.result()
            rows.append(r)
            print(
                f"{k}/{len(jobs)} {r['design']} hints {r['hints']} "
                f"contradictions {len(r['contradictions'])} {r['seconds']:.1f} s",
                flush=True,
            )
    return {
        "designs": len(rows),
        "shipped": len(DEVICES),
        "random_failing": n,
        "hints_applied": sum(r["hints"] for r in rows),
        "designs_with_a_fix_hint": sum(r["hints"] > 0 for r in rows),
        "contradictions": sum(bool(r["contradictions"]) for r in rows),
        "fix_compared": len(DEVICES) + min(compare, n),
        "seconds": time.perf_counter() - t0,
        "rows": rows,
    }


def dense_nearest(spec, v, limit: float, step: float = 0.005) -> float | None:
    """Nearest passing value of field ``v`` within |ln(x/x0)| ≤ limit, by the check."""
    k = 1
    while k * step <= limit:
        for sign in (1, -1):
            x = v.x0 * math.exp(sign * k * step)
            if v.lo <= x <= v.hi and passes(spec.replace(v.field, v.quantity(x))):
                return x
        k += 1
    return None


def boundary(n: int) -> dict:
    from betvdesign.studies.fix import FIELD_MARGIN, find_fixes
    from betvdesign.studies.fixfields import parse_vary

    rng = np.random.default_rng(SEED + 1)
    rows, ok = [], 0
    t0 = time.perf_counter()
    pool = random_designs(4 * n, SEED + 2)
    for spec, _ in pool:
        if len(rows) >= n:
            break
        have = [f for f in FIELDS if f in {x.field for x in parse_vary(spec, [])}]
        f = str(rng.choice(have))
        v = parse_vary(spec, [f])[0]
        res = find_fixes(spec, [v], pairs=False)
        best = res.best
        if best is None:
            continue
        (a,) = best.answers
        if a.boundary is None:
            continue
        dist = abs(math.log(a.boundary / v.x0))
        p = dense_nearest(spec, v, dist + 0.02)
        err = None if p is None else abs(math.log(a.boundary / p))
        sign = 1 if a.boundary > v.x0 else -1
        margin_ok = math.isclose(a.value, a.boundary * (1 + FIELD_MARGIN) ** sign, rel_tol=1e-9)
        good = err is not None and err <= 0.01 and margin_ok
        ok += good
        rows.append(
            {
                "device": spec.name,
                "field": f,
                "x0": v.x0,
                "boundary_fix": a.boundary,
                "value_fix": a.value,
                "nearest_dense": p,
                "rel_error": err,
                "within": good,
            }
        )
    return {
        "cases": len(rows),
        "within_1pct": ok,
        "seconds": time.perf_counter() - t0,
        "rows": rows,
    }


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("what", choices=["consistency", "boundary"])
    ap.add_argument("-n", type=int, default=200)
    ap.add_argument("-j", type=int, default=1, help="worker processes (consistency)")
    args = ap.parse_args()
    out = consistency(args.n, args.j) if args.what == "consistency" else boundary(args.n)
    path = ROOT / "benchmarks" / "out" / f"advice_{args.what}.json"
    path.parent.mkdir(exist_ok=True)
    path.write_text(json.dumps(out, indent=1, default=float))
    print({k: v for k, v in out.items() if k != "rows"})


if __name__ == "__main__":
    main()
