"""Measurements behind the fidelity ladder (:mod:`betvdesign.checks.fidelity`).

* :func:`lambda_disagreement`: the λ < 1 rule against the simulated periodic mode on
  the push/pull map (issue 5's grid by default, run by
  :func:`betvdesign.studies.pushpull.run_pushpull`): rate and every misprediction;
* :func:`validation_sample` / :func:`sample_summary`: the same on a held-out seeded
  random sample, with a Clopper–Pearson bound (the rate ``--fidelity lambda`` states);
* :func:`rigid_envelope`: relative Δs error of the α → 0 rigid limit against the
  full model's periodic orbit, over α, and an envelope C·α^q bounding it.
* :func:`rung_costs`: CPU time of each rung on sample designs (median).

:func:`write_measured` stores the numbers the ladder relies on as the generated
package data ``betvdesign/data/fidelity_measured.json`` with its provenance (regenerate
with ``python benchmarks/work_precision.py --ladder``; :func:`betvdesign.checks.fidelity.stale`
says when the stored numbers no longer match the solver).
"""

from __future__ import annotations

import itertools
import json
import math
import statistics
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from betvdesign.model.params import ModelParams

#: The push/pull map of issue 5: κ × β × α × ϖ = 2 × 4 × 9 × 16 = 1152 points.
MAP_GRID: dict[str, list[float]] = {
    "kappa": [0.1, 0.4],
    "beta": [0.1, 0.5, 1.0, 1.5],
    "alpha": [0.1, *[round(0.5 * k, 1) for k in range(1, 9)]],
    "varpi": [round(0.5 + 0.1 * k, 1) for k in range(16)],
}


def lambda_disagreement(
    grid: dict[str, Sequence[float]] | None = None, *, executor: Any = None
) -> dict[str, Any]:
    """λ rule vs simulated mode over ``grid`` (default :data:`MAP_GRID`)."""
    from betvdesign.studies.pushpull import run_pushpull

    g = grid or MAP_GRID
    run, summary = run_pushpull(g["varpi"], g["alpha"], g["beta"], g["kappa"], executor=executor)
    rows = run.rows
    conv = [r for r in rows if r.get("converged") and r.get("mode") in ("push", "pull")]
    wrong = [r for r in conv if r["lambda_mode"] != r["mode"]]
    keys = ("kappa", "beta", "alpha", "varpi", "lam", "mode", "delta_s")
    wrong_list = sorted(
        ({k: r[k] for k in keys} for r in wrong), key=lambda d: abs(d["lam"] - 1.0), reverse=True
    )
    margin = max((abs(r["lam"] - 1.0) for r in wrong), default=0.0)
    by_beta = {
        str(b): max((abs(r["lam"] - 1.0) for r in wrong if r["beta"] == b), default=0.0)
        for b in g["beta"]
    }
    bands = []
    edges = [0.0, 0.1, 0.2, 0.5, 1.0, 2.0, math.inf]
    for lo, hi in itertools.pairwise(edges):
        inside = [r for r in conv if lo <= abs(r["lam"] - 1.0) < hi]
        bad = [r for r in inside if r["lambda_mode"] != r["mode"]]
        top = hi if math.isfinite(hi) else None  # None: open band (JSON/Python-literal safe)
        bands.append({"lo": lo, "hi": top, "points": len(inside), "mispredicted": len(bad)})
    return {
        "grid": {k: list(v) for k, v in g.items()},
        "points": len(rows),
        "converged": len(conv),
        "not_converged": [
            {k: r[k] for k in ("kappa", "beta", "alpha", "varpi", "status", "message")}
            for r in rows
            if r not in conv
        ],
        "mispredicted": len(wrong),
        "rate": len(wrong) / len(conv) if conv else None,
        "mispredictions": wrong_list,
        "trust_margin": margin,
        "trust_margin_by_beta": by_beta,
        "bands": bands,
        "rigid_mode_disagreement": sum(1 for r in conv if r["mode"] == "push") / max(len(conv), 1),
        "agreement_reported_by_study": summary.agreement,
        "elapsed_s": run.elapsed_s,
    }


def rigid_envelope(
    bases: Sequence[tuple[float, float, float]] = (
        (0.9, 0.9, 0.4),
        (1.5, 0.5, 0.1),
        (0.6, 1.5, 0.4),
    ),
    alphas: Sequence[float] = (1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4),
) -> dict[str, Any]:
    """Relative Δs error of the rigid limit vs the full periodic orbit, and its envelope.

    bases: (ϖ, β, κ) triples; the envelope C·α^q has q from a least-squares fit of
    log error on log α and C the smallest constant that bounds every sample.
    """
    from betvdesign.dynamics import periodic_orbit
    from betvdesign.dynamics.rigid import rigid_periodic

    samples = []
    for varpi, beta, kappa in bases:
        rig = rigid_periodic(ModelParams(varpi, 1.0, beta, kappa))
        for a in alphas:
            po = periodic_orbit(ModelParams(varpi, a, beta, kappa))
            if not (po.success and rig.success):
                continue
            err = abs(float(po.delta_s) - rig.delta_s) / abs(float(po.delta_s))
            samples.append({"varpi": varpi, "beta": beta, "kappa": kappa, "alpha": a, "error": err})
    la = np.log([s["alpha"] for s in samples])
    le = np.log([max(s["error"], 1e-16) for s in samples])
    q = float(np.polyfit(la, le, 1)[0])
    coef = float(max(s["error"] / s["alpha"] ** q for s in samples))
    return {"power": q, "coef": coef, "samples": samples}


def _median_cpu(fn, n: int = 5) -> float:
    out = []
    for _ in range(n):
        t0 = time.process_time()
        fn()
        out.append(time.process_time() - t0)
    return statistics.median(out)


def rung_costs(designs: Sequence[ModelParams], cycles: int = 100) -> dict[str, float]:
    """Median CPU seconds of each rung over ``designs`` (``full``: ``cycles`` cycles)."""
    from betvdesign import dynamics
    from betvdesign.dynamics.rigid import rigid_periodic

    runs = {
        "lambda": lambda p: p.lam,
        "vertical": lambda p: dynamics.vertical_motion(p.varpi),
        "rigid": rigid_periodic,
        "full": lambda p: dynamics.simulate(p, cycles, log_events=False),
        "periodic": dynamics.periodic_orbit,
    }
    return {
        name: statistics.median(_median_cpu(lambda fn=fn, p=p: fn(p), 3) for p in designs)
        for name, fn in runs.items()
    }


def _periodic_row(args: tuple[float, float, float, float]) -> dict[str, Any]:
    from betvdesign.dynamics import periodic_orbit
    from betvdesign.model.domain import mode_of

    p = ModelParams(*args)
    po = periodic_orbit(p)
    return {
        **p.as_dict(),
        "lam": p.lam,
        "lambda_mode": p.lambda_mode,
        "status": po.status,
        "mode": mode_of(po.delta_s) if po.success else None,
        "delta_s": po.delta_s if po.success else None,
    }


#: Seed of the held-out sample: never used for anything the toolkit decides with.
HELD_OUT_SEED = 20261123
HELD_OUT_N = 5000


def validation_sample(
    n: int = HELD_OUT_N, seed: int = HELD_OUT_SEED, workers: int = 2
) -> list[dict[str, Any]]:
    """Periodic mode at ``n`` seeded random designs, uniform in the window and the λ fit
    range (ϖ ∈ [0.5, 2), α ∈ [0.1, 4], β ∈ [0.1, 1.5], κ ∈ [0.1, 0.4]), off the map's
    grid. Held out: the λ fit (the paper's) was not made on them, and no threshold of
    the toolkit is tuned on them."""
    from concurrent.futures import ProcessPoolExecutor

    rng = np.random.default_rng(seed)
    pts = [
        (float(w), float(a), float(b), float(k))
        for w, a, b, k in zip(
            rng.uniform(0.5, 2.0, n),
            rng.uniform(0.1, 4.0, n),
            rng.uniform(0.1, 1.5, n),
            rng.uniform(0.1, 0.4, n),
            strict=True,
        )
    ]
    with ProcessPoolExecutor(max_workers=workers) as ex:
        return list(ex.map(_periodic_row, pts, chunksize=64))


def upper_bound(errors: int, n: int, confidence: float = 0.95) -> float:
    """One-sided Clopper–Pearson upper confidence bound on a rate from ``errors``/``n``."""
    from scipy.stats import beta

    if n == 0:
        return 1.0
    if errors >= n:
        return 1.0
    return float(beta.ppf(confidence, errors + 1, n - errors))


def sample_summary(rows: Sequence[dict[str, Any]]) -> dict[str, Any]:
    """λ against the exact mode on a sample: rate, 95 % upper bound, per |λ − 1| band."""
    conv = [r for r in rows if r["mode"] in ("push", "pull")]
    wrong = [r for r in conv if r["mode"] != r["lambda_mode"]]
    keys = ("kappa", "beta", "alpha", "varpi", "lam", "mode", "delta_s")
    bands = []
    edges = [0.0, 0.2, 0.5, 1.0, 2.0, 5.0, math.inf]
    for lo, hi in itertools.pairwise(edges):
        inside = [r for r in conv if lo <= abs(r["lam"] - 1.0) < hi]
        bad = sum(1 for r in inside if r["lambda_mode"] != r["mode"])
        bands.append(
            {
                "lo": lo,
                "hi": hi if math.isfinite(hi) else None,
                "points": len(inside),
                "mispredicted": bad,
                "upper_95": upper_bound(bad, len(inside)),
            }
        )
    return {
        "points": len(rows),
        "converged": len(conv),
        "stalled": sum(1 for r in rows if r["mode"] == "stalled"),
        "mispredicted": len(wrong),
        "rate": len(wrong) / len(conv) if conv else None,
        "upper_95": upper_bound(len(wrong), len(conv)),
        "bands": bands,
        "mispredictions": sorted(
            ({k: r[k] for k in keys} for r in wrong), key=lambda d: -abs(d["lam"] - 1.0)
        ),
    }


#: Designs whose periodic Δs fingerprint the solver that produced the data.
FINGERPRINT = (
    (1.5, 2.5, 1.5, 0.4),
    (0.6, 0.5, 1.5, 0.4),
    (1.2, 2.0408163265306123, 0.5089380098815465, 0.1500314929875933),
    (0.8, 0.3, 1.2, 0.3),
    (1.024, 0.234, 1.31, 0.249),
)


def fingerprint() -> list[dict[str, float]]:
    """Periodic Δs of :data:`FINGERPRINT` with today's solver (the staleness check)."""
    from betvdesign.dynamics import periodic_orbit

    out = []
    for w, a, b, k in FINGERPRINT:
        po = periodic_orbit(ModelParams(w, a, b, k))
        out.append({"varpi": w, "alpha": a, "beta": b, "kappa": k, "delta_s": po.delta_s})
    return out


def measure(
    *,
    executor: Any = None,
    grid: dict[str, Sequence[float]] | None = None,
    reuse_map: dict[str, Any] | None = None,
    sample: int = HELD_OUT_N,
) -> dict[str, Any]:
    """Everything :mod:`betvdesign.checks.fidelity` relies on, measured now (``reuse_map``: a
    previous ``lambda`` entry, to skip re-solving the map)."""
    from betvdesign.bench.workprecision import DESIGNS

    lam = reuse_map or lambda_disagreement(grid, executor=executor)
    lam = {**lam, "held_out": sample_summary(validation_sample(sample))}
    rig = rigid_envelope()
    costs = rung_costs([d.params for d in DESIGNS.values()])
    return {
        "lambda": lam,
        "rigid": rig,
        "costs_cpu_s": costs,
        "full_cycles": 100,
        "fingerprint": fingerprint(),
    }


COMMAND = "python benchmarks/work_precision.py --ladder"


def provenance() -> dict[str, Any]:
    """Where the data come from: commit (and whether the tree was dirty), package
    version, date, command, library versions."""
    import datetime
    import platform
    import subprocess

    import numba
    import scipy

    from betvdesign import __version__

    root = Path(__file__).resolve().parents[2]

    def git(*args: str) -> str:
        try:
            return subprocess.run(
                ["git", *args], cwd=root, capture_output=True, text=True, timeout=10
            ).stdout.strip()
        except (OSError, subprocess.SubprocessError):
            return ""

    return {
        "commit": git("rev-parse", "HEAD") or "unknown",
        "dirty": bool(git("status", "--porcelain", "--untracked-files=no")),
        "betvdesign": __version__,
        "date": datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%dT%H:%M:%SZ"),
        "command": COMMAND,
        "python": platform.python_version(),
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "numba": numba.__version__,
        "note": "machine timings (costs_cpu_s) are indicative only; no decision uses them",
    }


def write_measured(measured: dict[str, Any], path: Path) -> None:
    """Write the package data (JSON, with provenance) atomically."""
    from betvdesign.output.files import write_atomic

    plain = json.loads(json.dumps(measured, default=float))  # numpy scalars -> float
    doc = {"provenance": provenance(), "measured": plain}
    write_atomic(Path(path), json.dumps(doc, indent=1, sort_keys=True) + "\n")
