"""Push/pull map in the (1/ϖ², 1/(ακ)) plane (docs/MODEL.md, "Push/pull criterion").

With X = 1/ϖ² and Y = 1/(ακ) the fit reads λ = κ·X·(Y − c), c = (1/β − β)/(22(κ+1)),
so for fixed (κ, β) the boundary λ = 1 is the hyperbola Y = c + 1/(κ·X), i.e.
1/(ακ) = ϖ²/κ + c. It is a straight line only against ϖ² (not 1/ϖ²); the map uses
the issue's axes and draws the curve. Below it (smaller 1/(ακ)) λ < 1: push.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.lines import Line2D

from betvdesign.model.domain import VARPI_WINDOW
from betvdesign.model.params import fit_offset
from betvdesign.output.presentation import MODE_COLORS
from betvdesign.plots.figure import (
    DEVICE_COLOR,
    axes_or_new,
    dimensionless_twin,
    legend_below,
)
from betvdesign.plots.marks import SUBRES_COLOR, SUBRES_LABEL, mark_window


def lambda_one_curve(inv_varpi2: np.ndarray, kappa: float, beta: float) -> np.ndarray:
    """1/(ακ) on the λ = 1 boundary at the given 1/ϖ² [-] (for fixed κ, β)."""
    x = np.asarray(inv_varpi2, dtype=float)
    return fit_offset(kappa, beta) + 1.0 / (kappa * x)


def pushpull_map(
    *,
    kappa: float,
    beta: float,
    points: Sequence[tuple[str, float, float]],
    ax: Axes | None = None,
) -> Axes:
    """Draw the push/pull map for fixed (κ, β) and mark design points.

    points: (label, ϖ, α) per design point [-]; each is placed at (1/ϖ², 1/(ακ)).
    The vertical design window 0.5 ≤ ϖ < 2 is shaded on the 1/ϖ² axis.
    """
    ax = axes_or_new(ax)
    xs = [1.0 / varpi**2 for _, varpi, _ in points]
    ys = [1.0 / (alpha * kappa) for _, _, alpha in points]
    c = fit_offset(kappa, beta)
    w_lo, w_hi = 1.0 / VARPI_WINDOW[1] ** 2, 1.0 / VARPI_WINDOW[0] ** 2
    x_max = max([w_hi * 1.15, *(1.25 * x for x in xs)])
    x = np.linspace(x_max / 400.0, x_max, 400)
    curve = lambda_one_curve(x, kappa, beta)
    y_dev = max([0.0, *ys])
    y_curve_ref = float(lambda_one_curve(np.array([w_lo]), kappa, beta)[0])
    y_max = 1.3 * max(y_dev, y_curve_ref, 2.0 * abs(c), 1e-12)
    y_min = min(0.0, c) - 0.03 * y_max
    lower = np.full_like(x, y_min)
    upper = np.full_like(x, y_max)
    clipped = np.clip(curve, y_min, y_max)
    ax.fill_between(x, lower, clipped, color=MODE_COLORS["push"], alpha=0.13, lw=0)
    ax.fill_between(x, clipped, upper, color=MODE_COLORS["pull"], alpha=0.13, lw=0)
    ax.plot(x, curve, color="black", lw=1.4, label=f"λ = 1  (κ = {kappa:.3g}, β = {beta:.3g})")
    for edge, label in ((w_lo, "design window 0.5 ≤ ϖ < 2"), (w_hi, None)):
        ax.axvline(edge, color="#b8860b", lw=1.0, ls="-.", label=label)
    _devices_and_sides(ax, points, xs, ys, 0.97)
    ax.set_xlim(0.0, x_max)
    ax.set_ylim(y_min, y_max)
    ax.set_xlabel("1/ϖ²  [-]")
    ax.set_ylabel("1/(ακ)  [-]")
    ax.legend(loc="upper center", framealpha=0.9)
    return ax


#: Sub-resonance orders drawn on the frequency map (the lines f_h = n·f_act) [-].
MAP_ORDERS = 4


def pushpull_map_frequencies(
    *,
    f_v_hz: float,
    kappa: float,
    beta: float,
    points: Sequence[tuple[str, float, float]],
    ax: Axes | None = None,
) -> Axes:
    """The push/pull map in the frequencies a designer sets, for fixed f_v, κ, β.

    x: actuation frequency f_act [kHz]; y: tangential resonance f_h = f_v/√α [kHz]
    (α = (f_v/f_h)², so the map holds for a device given by α or k_h too). With
    X = 1/ϖ² = (f_v/f_act)² and Y = 1/(ακ) = f_h²/(κ f_v²), λ < 1 (push) reads
    f_h² < f_act² + κ·c·f_v² (c: :func:`betvdesign.model.params.fit_offset`): push lies below
    the curve f_h = sqrt(f_act² + κ c f_v²). Secondary axes: ϖ = f_act/f_v (top) and α
    (right). points: (label, f_act [Hz], f_h [Hz]). Outside the design window hatched; the
    sub-resonances α·ϖ² = 1/n² are the lines f_h = n·f_act (dash-dotted; n ≤
    :data:`MAP_ORDERS`, the steeper ones crowd at the origin).
    """
    ax = axes_or_new(ax)
    c = fit_offset(kappa, beta)
    fv = f_v_hz / 1e3
    xs = [f / 1e3 for _, f, _ in points]
    ys = [f / 1e3 for _, _, f in points]
    x_max = max([VARPI_WINDOW[1] * fv * 1.15, *(1.25 * x for x in xs)])
    x = np.linspace(0.0, x_max, 400)
    arg = x**2 + kappa * c * fv**2
    curve = np.sqrt(np.clip(arg, 0.0, None))
    y_max = 1.3 * max([*ys, float(curve[np.searchsorted(x, VARPI_WINDOW[1] * fv)]), 1e-9])
    clipped = np.where(arg > 0, np.minimum(curve, y_max), 0.0)
    ax.fill_between(x, 0.0, clipped, color=MODE_COLORS["push"], alpha=0.13, lw=0)
    ax.fill_between(x, clipped, y_max, color=MODE_COLORS["pull"], alpha=0.13, lw=0)
    real = arg > 0
    ax.plot(
        x[real],
        curve[real],
        color="black",
        lw=1.4,
        label=f"λ = 1  (κ = {kappa:.3g}, β = {beta:.3g}, f_v = {fv:.3g} kHz)",
    )
    i = int(np.flatnonzero(real)[len(np.flatnonzero(real)) // 2]) if real.any() else None
    if i is not None and curve[i] < y_max:
        ax.annotate(
            "λ = 1",
            (x[i], curve[i]),
            xytext=(4, -12),
            textcoords="offset points",
            fontsize=8,
            fontweight="bold",
        )
    marks = mark_window(ax, 0.0, x_max, [(VARPI_WINDOW[0] * fv, VARPI_WINDOW[1] * fv)])
    for n in range(1, MAP_ORDERS + 1):  # α·ϖ² = 1/n²: the lines f_h = n·f_act
        ax.plot([0.0, x_max], [0.0, n * x_max], color=SUBRES_COLOR, lw=0.7, ls="-.")
        if y_max / n < x_max:
            ax.annotate(
                "f_h" if n == 1 else f"f_h/{n}",
                (y_max / n, y_max),
                xytext=(2, -2),
                textcoords="offset points",
                ha="left",
                va="top",
                fontsize=6.5,
                color=SUBRES_COLOR,
            )
    marks.append(Line2D([], [], color=SUBRES_COLOR, lw=0.7, ls="-.", label=SUBRES_LABEL))
    _devices_and_sides(ax, points, xs, ys, 0.98)
    ax.set_xlim(0.0, x_max)
    ax.set_ylim(0.0, y_max)
    ax.set_xlabel("actuation frequency f_act  [kHz]")
    ax.set_ylabel("tangential resonance f_h = f_v/√α  [kHz]")
    dimensionless_twin(ax, "x", fv, "ϖ = f_act/f_v  [-]")
    legend_below(ax, handles=ax.get_legend_handles_labels()[0] + marks)
    return ax


def _devices_and_sides(ax: Axes, points: Any, xs: Any, ys: Any, x_text: float) -> None:
    """The devices as labelled dots, and the push/pull side labels of the λ = 1 map."""
    for (label, _, _), px, py in zip(points, xs, ys, strict=True):
        ax.plot([px], [py], marker="o", ms=6, color=DEVICE_COLOR, zorder=5)
        ax.annotate(label, (px, py), xytext=(6, 4), textcoords="offset points", fontsize=7.5)
    for text, y, va, mode in (
        ("push (λ < 1)", 0.04, "bottom", "push"),
        ("pull (λ > 1)", 0.95, "top", "pull"),
    ):
        ax.text(
            x_text,
            y,
            text,
            transform=ax.transAxes,
            ha="right",
            va=va,
            color=MODE_COLORS[mode],
            fontweight="bold",
        )
