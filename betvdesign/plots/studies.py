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

from betvdesign.output.presentation import MODE_COLORS
from betvdesign.plots.figure import STYLE, axes_or_new, figure_style, new_figure
from betvdesign.plots.pushpull import lambda_one_curve
from betvdesign.studies.terms import Terms

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
    for mode in ("push", "pull"):
        color = MODE_COLORS[mode]
        if simulated:
            m = np.array([r["converged"] and r["mode"] == mode for r in sel], dtype=bool)
            ax.scatter(x[m], y[m], s=14, color=color, label=f"{mode} (simulated)", zorder=3)
        else:
            m = np.array([r["lambda_mode"] == mode for r in sel], dtype=bool)
            ax.scatter(
                x[m], y[m], s=14, facecolors="none", edgecolors=color, label=f"{mode} (λ fit)"
            )
    if simulated:
        bad = np.array([not r["converged"] for r in sel], dtype=bool)
        if bad.any():
            ax.scatter(x[bad], y[bad], s=18, marker="x", color="black", label="not converged")
        dis = np.array([r["converged"] and r["mode"] != r["lambda_mode"] for r in sel], dtype=bool)
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
        ax.plot(xs, curve, color="black", lw=1.2, label="λ = 1 (fit boundary)")
        label_lambda_one(ax, xs, curve)
        if y.min() > 0 and y.max() / y.min() > 20:  # α spanning decades: log axis
            ax.set_yscale("log")
            ax.set_ylim(y.min() / 1.5, y.max() * 1.5)
        else:
            ax.set_ylim(min(0.0, y.min()) - 0.05 * np.ptp(y), y.max() * 1.1 + 1e-12)
    ax.set_title(f"κ = {kappa:g}, β = {beta:g}")
    ax.set_xlabel("1/ϖ²  [-]")
    ax.set_ylabel("1/(ακ)  [-]")
    return ax


#: Smallest size of the map figure [inches]: one panel is still readable (6.4 × 4.8 in,
#: 960 × 720 px at the PNG resolution below).
MIN_FIGSIZE = (6.4, 4.8)
#: PNG resolution [dots per inch].
PNG_DPI = 150


def label_lambda_one(ax: Axes, xs: np.ndarray, curve: np.ndarray) -> None:
    """Write "λ = 1" on the boundary curve itself (at its middle point in view)."""
    i = len(xs) // 2
    ax.annotate(
        "λ = 1",
        (float(xs[i]), float(curve[i])),
        xytext=(4, 4),
        textcoords="offset points",
        fontsize=8,
        fontweight="bold",
        bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.8},
    )


def pushpull_figure(rows: Sequence[Row]) -> Figure:
    """One panel per (κ, β): rows κ, columns β; legend below the panels (never clipped);
    the damping and restitution of a map made with them as its title."""
    kappas = sorted({r["kappa"] for r in rows})
    betas = sorted({r["beta"] for r in rows})
    with figure_style():
        fig, axes = new_figure(
            max(MIN_FIGSIZE[0], 3.2 * len(betas) + 0.6),
            max(MIN_FIGSIZE[1], 2.8 * len(kappas) + 1.0),
            nrows=len(kappas),
            ncols=len(betas),
        )
        axes = np.asarray(axes, dtype=object).reshape(len(kappas), len(betas))
        for i, kappa in enumerate(kappas):
            for j, beta in enumerate(betas):
                pushpull_panel(rows, kappa=kappa, beta=beta, ax=axes[i][j])
        seen: dict[str, Any] = {}
        for ax in axes.flat:  # every label once, from whichever panel has it
            for h, lab in zip(*ax.get_legend_handles_labels(), strict=True):
                seen.setdefault(lab, h)
        fig.legend(
            list(seen.values()),
            list(seen),
            loc="outside lower center",
            ncols=min(3, max(1, len(seen))),
        )
        terms = Terms.of(rows[0]) if rows else Terms()  # a damped map's rows carry them
        if not terms.ideal:
            fig.suptitle(f"{terms.statement()} (λ: the idealised fit)")
    return fig


def save_figure(fig: Figure, path: str | os.PathLike[str]) -> None:
    """Write ``fig`` (SVG/PNG/PDF by suffix) reproducibly, via a temporary file."""
    p = Path(path)
    fmt = p.suffix.lower().lstrip(".")
    tmp = p.with_name(f".{p.name}.tmp")
    meta: dict[str, Any] = {"svg": {"Date": None}, "pdf": {"CreationDate": None, "ModDate": None}}
    meta["png"] = {"Software": None}
    with matplotlib.rc_context(rc={**STYLE, "svg.hashsalt": "betvdesign-studies"}):
        fig.savefig(tmp, format=fmt, metadata=meta[fmt], dpi=PNG_DPI)
    os.replace(tmp, p)


def save_pushpull_figure(rows: Sequence[Row], path: str | os.PathLike[str]) -> None:
    """The map figure of ``rows`` (push/pull study rows) written to ``path``."""
    save_figure(pushpull_figure(rows), path)
