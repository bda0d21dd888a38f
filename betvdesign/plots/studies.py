"""Figures of the design-space studies (``betvdesign.studies``): the simulated
push/pull map, one panel per (κ, β) in the (1/ϖ², 1/(ακ)) plane with the fit's
λ = 1 curve (docs/MODEL.md, "Push/pull criterion").

Object-oriented matplotlib only; panel functions take ``ax=``. Files are written
byte-reproducibly (fixed SVG hash salt, no dates) through a temporary file.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import matplotlib
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from betvdesign.plots._figure import MODE_COLORS, STYLE, axes_or_new, figure_style, new_figure
from betvdesign.plots.pushpull import lambda_one_curve

Row = Mapping[str, Any]


def pushpull_panel(
    rows: Sequence[Row], *, kappa: float, beta: float, ax: Axes | None = None
) -> Axes:
    """Map points of one (κ, β) at (1/ϖ², 1/(ακ)) [-], coloured by mode.

    Filled markers: simulated periodic mode; hollow: λ-fit prediction only (no
    simulation); black ×: not converged; red ring: simulation disagrees with λ.
    """
    ax = axes_or_new(ax)
    sel = [r for r in rows if r["kappa"] == kappa and r["beta"] == beta]
    x = np.array([1.0 / r["varpi"] ** 2 for r in sel])
    y = np.array([1.0 / (r["alpha"] * kappa) for r in sel])
    simulated = any(r["status"] != "lambda-only" for r in sel)
    for mode, color in MODE_COLORS.items():
        if simulated:
            m = np.array([r["converged"] and r["mode"] == mode for r in sel], dtype=bool)
            ax.scatter(x[m], y[m], s=14, color=color, label=f"{mode} (simulated)", zorder=3)
        else:
            m = np.array([r["mode_predicted"] == mode for r in sel], dtype=bool)
            ax.scatter(
                x[m], y[m], s=14, facecolors="none", edgecolors=color, label=f"{mode} (λ fit)"
            )
    if simulated:
        bad = np.array([not r["converged"] for r in sel], dtype=bool)
        if bad.any():
            ax.scatter(x[bad], y[bad], s=18, marker="x", color="black", label="not converged")
        dis = np.array(
            [r["converged"] and r["mode"] != r["mode_predicted"] for r in sel], dtype=bool
        )
        if dis.any():
            ax.scatter(
                x[dis],
                y[dis],
                s=60,
                facecolors="none",
                edgecolors="#d62728",
                lw=1.0,
                label="λ disagrees",
                zorder=4,
            )
    if x.size:
        xs = np.linspace(x.min() * 0.9, x.max() * 1.1, 300)
        curve = lambda_one_curve(xs, kappa, beta)
        ax.plot(xs, curve, color="black", lw=1.2, label="λ = 1")
        if y.min() > 0 and y.max() / y.min() > 20:  # α spanning decades: log axis
            ax.set_yscale("log")
            ax.set_ylim(y.min() / 1.5, y.max() * 1.5)
        else:
            ax.set_ylim(min(0.0, y.min()) - 0.05 * np.ptp(y), y.max() * 1.1 + 1e-12)
    ax.set_title(f"κ = {kappa:g}, β = {beta:g}")
    ax.set_xlabel("1/ϖ²  [-]")
    ax.set_ylabel("1/(ακ)  [-]")
    return ax


def pushpull_figure(rows: Sequence[Row]) -> Figure:
    """One panel per (κ, β): rows κ, columns β."""
    kappas = sorted({r["kappa"] for r in rows})
    betas = sorted({r["beta"] for r in rows})
    with figure_style():
        fig, axes = new_figure(
            3.0 * len(betas) + 0.6,
            2.6 * len(kappas) + 0.4,
            nrows=len(kappas),
            ncols=len(betas),
        )
        axes = np.asarray(axes, dtype=object).reshape(len(kappas), len(betas))
        for i, kappa in enumerate(kappas):
            for j, beta in enumerate(betas):
                pushpull_panel(rows, kappa=kappa, beta=beta, ax=axes[i][j])
        handles, labels = axes[0][0].get_legend_handles_labels()
        fig.legend(handles, labels, loc="outside lower center", ncols=max(1, len(labels)))
    return fig


def save_figure(fig: Figure, path: str | os.PathLike[str]) -> None:
    """Write ``fig`` (SVG/PNG/PDF by suffix) reproducibly, via a temporary file."""
    p = Path(path)
    fmt = p.suffix.lower().lstrip(".")
    tmp = p.with_name(f".{p.name}.tmp")
    meta: dict[str, Any] = {"svg": {"Date": None}, "pdf": {"CreationDate": None, "ModDate": None}}
    meta["png"] = {"Software": None}
    with matplotlib.rc_context(rc={**STYLE, "svg.hashsalt": "betvdesign-studies"}):
        fig.savefig(tmp, format=fmt, metadata=meta[fmt])
    os.replace(tmp, p)


def save_pushpull_figure(rows: Sequence[Row], path: str | os.PathLike[str]) -> None:
    """The map figure of ``rows`` (push/pull study rows) written to ``path``."""
    save_figure(pushpull_figure(rows), path)
