"""Measurements behind the fidelity ladder (:mod:`betvdesign.fidelity`).

* :func:`lambda_disagreement`: the λ < 1 rule against the simulated periodic mode on
  the push/pull map (issue 5's grid by default, run by
  :func:`betvdesign.studies.pushpull.run_pushpull`): rate, every misprediction, and
  the trust margin (largest |λ − 1| at which it mispredicted).
* :func:`rigid_envelope`: relative Δs error of the α → 0 rigid limit against the
  full model's periodic orbit, over α, and an envelope C·α^q bounding it.
* :func:`rung_costs`: CPU time of each rung on sample designs (median).

:func:`write_measured` stores the numbers the ladder relies on as the generated
module ``betvdesign/fidelity_measured.py`` (regenerate with
``python benchmarks/work_precision.py --ladder``).
"""

from __future__ import annotations

import itertools
import json
import math
import pprint
import statistics
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from betvdesign.params import ModelParams

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
    wrong = [r for r in conv if r["mode_predicted"] != r["mode"]]
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
        bad = [r for r in inside if r["mode_predicted"] != r["mode"]]
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


#: Bins of the λ trust table: ϖ edges and β edges (mispredictions cluster at low ϖ).
VARPI_BINS = (0.5, 0.7, 0.9, 1.2, 1.6, 2.0)
BETA_BINS = (0.1, 0.3, 0.75, 1.25, 1.5)
#: Safety factor on the largest misprediction distance seen in a bin (a judgement,
#: stated in the reason the ladder prints).
SAFETY = 1.25


def _periodic_row(args: tuple[float, float, float, float]) -> dict[str, Any]:
    from betvdesign.dynamics import periodic_orbit

    p = ModelParams(*args)
    po = periodic_orbit(p)
    return {
        **p.as_dict(),
        "lam": p.lam,
        "mode_predicted": p.mode_predicted,
        "status": po.status,
        "mode": po.mode if po.success else None,
        "delta_s": po.delta_s if po.success else None,
    }


def validation_sample(
    n: int = 1500, seed: int = 20261122, workers: int = 2
) -> list[dict[str, Any]]:
    """Periodic mode at ``n`` seeded random designs in the window and the λ fit range
    (ϖ ∈ [0.5, 2), α ∈ [0.1, 4], β ∈ [0.1, 1.5], κ ∈ [0.1, 0.4]), off the map's grid."""
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
        return list(ex.map(_periodic_row, pts, chunksize=16))


def _bin(x: float, edges: Sequence[float]) -> int | None:
    for i, (lo, hi) in enumerate(itertools.pairwise(edges)):
        if lo * (1 - 1e-9) <= x < hi or (i == len(edges) - 2 and x <= hi * (1 + 1e-9)):
            return i
    return None


def trust_table(mispredictions: Sequence[dict[str, Any]]) -> list[list[float]]:
    """margin[i_ϖ][i_β] = SAFETY × largest |λ − 1| of a misprediction in that bin
    (0 where none was seen)."""
    table = [[0.0] * (len(BETA_BINS) - 1) for _ in range(len(VARPI_BINS) - 1)]
    for m in mispredictions:
        i, j = _bin(m["varpi"], VARPI_BINS), _bin(m["beta"], BETA_BINS)
        if i is not None and j is not None:
            table[i][j] = max(table[i][j], SAFETY * abs(m["lam"] - 1.0))
    return table


def sample_summary(rows: Sequence[dict[str, Any]]) -> dict[str, Any]:
    conv = [r for r in rows if r["mode"] in ("push", "pull")]
    wrong = [r for r in conv if r["mode"] != r["mode_predicted"]]
    keys = ("kappa", "beta", "alpha", "varpi", "lam", "mode", "delta_s")
    return {
        "points": len(rows),
        "converged": len(conv),
        "mispredicted": len(wrong),
        "rate": len(wrong) / len(conv) if conv else None,
        "mispredictions": sorted(
            ({k: r[k] for k in keys} for r in wrong), key=lambda d: -abs(d["lam"] - 1.0)
        ),
    }


def measure(
    *,
    executor: Any = None,
    grid: dict[str, Sequence[float]] | None = None,
    reuse_map: dict[str, Any] | None = None,
    sample: int = 1500,
) -> dict[str, Any]:
    """Everything :mod:`betvdesign.fidelity` relies on, measured now (``reuse_map``: a
    previous ``lambda`` entry, to skip re-solving the map)."""
    from betvdesign.bench.workprecision import DESIGNS

    lam = reuse_map or lambda_disagreement(grid, executor=executor)
    val = sample_summary(validation_sample(sample))
    lam = {
        **lam,
        "sample": val,
        "varpi_bins": list(VARPI_BINS),
        "beta_bins": list(BETA_BINS),
        "safety": SAFETY,
        "trust_table": trust_table(lam["mispredictions"] + val["mispredictions"]),
    }
    rig = rigid_envelope()
    costs = rung_costs([d.params for d in DESIGNS.values()])
    return {"lambda": lam, "rigid": rig, "costs_cpu_s": costs, "full_cycles": 100}


HEADER = '''"""Measured trust limits and costs of the fidelity ladder (GENERATED, do not edit).

Regenerate: ``python benchmarks/work_precision.py --ladder``
(betvdesign.bench.ladder.measure). Read by betvdesign.fidelity.
"""

# fmt: off
MEASURED = '''


def write_measured(measured: dict[str, Any], path: Path) -> None:
    """Write the generated module (atomically)."""
    from betvdesign.report.render import write_atomic

    plain = json.loads(json.dumps(measured, default=float))  # numpy scalars -> float
    text = HEADER + pprint.pformat(plain, width=99, sort_dicts=True) + "\n"
    write_atomic(Path(path), text)
