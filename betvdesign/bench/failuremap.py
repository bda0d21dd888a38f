"""Failure map along ϖ: each method's error across the frequency window, one figure.

For a fixed (α, β, κ) every method of a small set (exact, solve_ivp RK45 at rtol 1e-6,
tanh friction at ε = 1e-3, fixed-step RK4 with post-detected events) integrates N
cycles from rest at each ϖ; the error is relative to the exact solver's s (the exact
solver's own row is its distance to DOP853 at rtol 1e-13). The figure marks where
the model is delicate: the resonance ϖ = 1, a·ϖ² = 1 for a = α and α(1 + 1/β), and
the window edge ϖ → 2 (grazing contacts). Only errors are plotted (deterministic),
so the figure is byte-reproducible.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from betvdesign.bench.chart import ERROR_FLOOR, STYLES, save_chart
from betvdesign.bench.workprecision import Method, reference_runner, rk4_runner, run_exact
from betvdesign.model.params import ModelParams
from betvdesign.plots.figure import figure_style, new_figure

BASE = {"alpha": 0.5, "beta": 0.5, "kappa": 0.4}
CYCLES = 10


def default_varpis(n: int = 16, base: dict[str, float] | None = None) -> list[float]:
    """n points over the window plus the delicate frequencies themselves."""
    b = base or BASE
    special = [
        1.0,
        1 / math.sqrt(b["alpha"]),
        1 / math.sqrt(b["alpha"] * (1 + 1 / b["beta"])),
        1.99,
    ]
    grid = [round(x, 6) for x in np.linspace(0.52, 1.95, n)]
    return sorted(set(grid + [w for w in special if 0.5 <= w < 2.0]))


def scan_methods() -> list[Method]:
    """The methods compared along ϖ (one typical setting each)."""
    return [
        Method("solve_ivp-RK45", "rtol=1e-06", reference_runner("RK45", 1e-6, "exact", None)),
        Method("tanh-LSODA", "eps=1e-03", reference_runner("LSODA", 1e-10, "tanh", 1e-3)),
        Method("rk4-post", "h=T/200", rk4_runner(200)),
    ]


def scan(
    varpis: Sequence[float], *, cycles: int = CYCLES, base: dict[str, float] | None = None
) -> list[dict[str, Any]]:
    """Relative error in s after ``cycles`` cycles, per method and ϖ."""
    b = base or BASE
    best = reference_runner("DOP853", 1e-13, "exact", None)
    rows: list[dict[str, Any]] = []
    for w in varpis:
        p = ModelParams(float(w), b["alpha"], b["beta"], b["kappa"])
        ref = run_exact(p, cycles, None)
        s_ref = float(ref.s_section[-1])
        indep = best(p, cycles, None)
        runs = [("exact", "closed-form events", indep)]
        runs += [(m.method, m.setting, _safe(m, p, cycles)) for m in scan_methods()]
        for method, setting, out in runs:
            err = None
            if out.status == "success" and len(out.s_section) == cycles + 1:
                err = abs(float(out.s_section[-1]) - s_ref) / max(abs(s_ref), 1e-300)
            rows.append(
                {
                    "method": method,
                    "setting": setting,
                    "varpi": float(w),
                    "error": err,
                    "status": out.status,
                    "exact_status": ref.status,
                }
            )
    return rows


def _safe(m: Method, p: ModelParams, cycles: int):
    from betvdesign.bench.workprecision import RunOut

    try:
        return m.run(p, cycles, None)
    except Exception as exc:  # a crashing method is a measured outcome
        return RunOut(np.zeros(0), "failed", f"{type(exc).__name__}: {exc}")


def failure_map_axes(ax: Axes, rows: Sequence[dict[str, Any]], base: dict[str, float]) -> None:
    """Error against ϖ per method, with the delicate frequencies marked."""
    for method in dict.fromkeys(r["method"] for r in rows):
        pts = sorted(
            (r["varpi"], max(r["error"], ERROR_FLOOR))
            for r in rows
            if r["method"] == method and r["error"] is not None
        )
        if pts:
            x, y = np.array(pts).T
            ax.semilogy(x, y, label=method, **{"marker": ".", **STYLES.get(method, {})})
        failed = [r["varpi"] for r in rows if r["method"] == method and r["error"] is None]
        if failed:
            ax.semilogy(failed, [1.0] * len(failed), "k|", markersize=12)
    a, be = base["alpha"], base["beta"]
    marks = [
        (1.0, "ϖ = 1"),
        (1 / math.sqrt(a), "αϖ² = 1"),
        (1 / math.sqrt(a * (1 + 1 / be)), "stick aϖ² = 1"),
    ]
    lo, hi = min(r["varpi"] for r in rows), max(r["varpi"] for r in rows)
    for x, label in marks:
        if lo <= x <= hi:
            ax.axvline(x, color="0.4", linewidth=0.7, linestyle="--")
            ax.annotate(
                label,
                (x, 0.97),
                xycoords=ax.get_xaxis_transform(),
                rotation=90,
                fontsize=6.5,
                va="top",
                ha="right",
                bbox={"fc": "white", "ec": "none", "alpha": 0.8, "pad": 0.5},
            )
    ax.axvspan(1.9, max(hi, 2.0), color="#fff3d6", zorder=0, label="ϖ → 2: grazing")
    ax.set_xlabel("ϖ [-]")
    ax.set_ylabel("relative error in s after N cycles [-]")
    ax.set_title(f"α = {a:g}, β = {be:g}, κ = {base['kappa']:g}")


def failure_map_figure(
    rows: Sequence[dict[str, Any]], base: dict[str, float] | None = None
) -> Figure:
    with figure_style():
        fig, ax = new_figure(6.4, 3.8)
        failure_map_axes(ax, rows, base or BASE)
        fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", ncols=5)
    return fig


def write_failure_map(rows: Sequence[dict[str, Any]], out_dir: Any, stem: str = "failure_map"):
    """Write ``stem``.png/.svg/.json (atomically) into ``out_dir``; returns the paths."""
    import json
    from pathlib import Path

    from betvdesign.output.files import write_atomic

    out = Path(out_dir)
    paths = save_chart(failure_map_figure(rows), out, stem)
    doc = {"base": BASE, "cycles": CYCLES, "rows": list(rows)}
    paths.append(write_atomic(out / f"{stem}.json", json.dumps(doc, indent=1) + "\n"))
    return paths
