"""Figures of the validation study against the published paper (unit-suffixed arrays in,
axes out; nothing here computes physics). Each function draws on the ``ax=`` it is
given, or on a fresh figure when None.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from matplotlib.axes import Axes

from betvdesign.output.presentation import MODE_COLORS
from betvdesign.plots.figure import DEVICE_COLOR, axes_or_new
from betvdesign.plots.pushpull import lambda_one_curve

#: Colour of published values drawn over computed ones.
PUBLISHED_COLOR = "#ff7f0e"


def published_lines(ax: Axes, xs: Sequence[float], label: str = "published") -> Axes:
    """Vertical dashed lines at published abscissae (e.g. interval edges)."""
    for i, x in enumerate(xs):
        ax.axvline(x, color=PUBLISHED_COLOR, ls="--", lw=1.2, label=label if i == 0 else None)
    ax.legend(loc="best", framealpha=0.9)
    return ax


def vertical_trajectories(
    traces: Sequence[tuple[str, Sequence[float], Sequence[float]]],
    *,
    ax: Axes | None = None,
) -> Axes:
    """Head gap ξ [-] against time [actuation cycles], one line per (label, t, ξ),
    offset by 0, −3, −6… so the traces do not overlap."""
    ax = axes_or_new(ax)
    for i, (label, t, xi) in enumerate(traces):
        off = -3.0 * i
        ax.plot(np.asarray(t, float), np.asarray(xi, float) + off, lw=0.8, label=label)
        ax.axhline(off, color="#7f7f7f", lw=0.4)
    ax.set_xlabel("time  [actuation cycles]")
    ax.set_ylabel("ξ (offset by −3 per trace)  [-]")
    ax.legend(loc="upper right", framealpha=0.9, fontsize=7)
    return ax


def pushpull_points(
    kappa: float,
    beta: float,
    varpi: Sequence[float],
    alpha: Sequence[float],
    mode: Sequence[str | None],
    *,
    ax: Axes | None = None,
) -> Axes:
    """Simulated modes on the (1/ϖ², 1/(ακ)) plane with the λ = 1 curve (Fig. 7):
    push filled, pull open, no periodic orbit a cross."""
    ax = axes_or_new(ax)
    x = 1.0 / np.asarray(varpi, float) ** 2
    y = 1.0 / (np.asarray(alpha, float) * kappa)
    m = np.array([str(v) for v in mode])
    xc = np.linspace(0.05, 1.1 * x.max(), 300)
    ax.plot(xc, lambda_one_curve(xc, kappa, beta), color="black", lw=1.2, label="λ = 1")
    for name, style in (("push", {}), ("pull", {"mfc": "none"})):
        sel = m == name
        ax.plot(
            x[sel],
            y[sel],
            ls="none",
            marker="o",
            ms=4,
            color=MODE_COLORS[name],
            label=name,
            **style,
        )
    bad = ~np.isin(m, ["push", "pull"])
    if bad.any():
        ax.plot(
            x[bad], y[bad], ls="none", marker="x", ms=5, color="#7f7f7f", label="no periodic orbit"
        )
    ax.set_ylim(0.0, 1.1 * y.max())
    ax.set_xlim(0.0, 1.1 * x.max())
    ax.set_title(f"κ = {kappa:g}, β = {beta:g}")
    ax.set_xlabel("1/ϖ²  [-]")
    ax.set_ylabel("1/(ακ)  [-]")
    ax.legend(loc="upper right", framealpha=0.9, fontsize=6.5)
    return ax


def section_velocities(
    cycles: Sequence[int],
    traces: Mapping[str, Sequence[float]],
    separation: float,
    *,
    ax: Axes | None = None,
) -> Axes:
    """Slider velocity after each cycle, in units of ϖ [-], per start (Fig. 8), with the
    periodic separation velocity as a dashed line."""
    ax = axes_or_new(ax)
    for label, v in traces.items():
        ax.plot(np.asarray(cycles), np.asarray(v, float), marker="o", ms=3, label=label)
    ax.axhline(
        separation,
        color=DEVICE_COLOR,
        ls="--",
        lw=1.0,
        label=f"periodic separation velocity {separation:.4g}ϖ",
    )
    ax.set_xlabel("cycle  [-]")
    ax.set_ylabel("s' after the cycle  [ϖ]")
    ax.legend(loc="best", framealpha=0.9)
    return ax


def travel(
    cycles: Sequence[float],
    s_um: Mapping[str, Sequence[float]],
    published: tuple[float, float],
    *,
    ax: Axes | None = None,
) -> Axes:
    """Slider travel [µm] against impacts, one line per variant, the published
    (impacts, µm) point marked (Fig. 10)."""
    ax = axes_or_new(ax)
    for label, s in s_um.items():
        ax.plot(np.asarray(cycles, float), np.asarray(s, float), lw=1.0, label=label)
    ax.plot(
        [published[0]],
        [published[1]],
        marker="*",
        ms=11,
        color=PUBLISHED_COLOR,
        ls="none",
        label=f"published: {published[1]:g} µm after {published[0]:g} impacts",
    )
    ax.set_xlabel("impacts (actuation cycles)  [-]")
    ax.set_ylabel("|slider travel|  [µm]")
    ax.legend(loc="upper left", framealpha=0.9, fontsize=6.5)
    return ax


def settling(
    cycles: Sequence[float],
    deviation: Mapping[str, Sequence[float]],
    stops: Mapping[str, int | None],
    published_cycles: float,
    *,
    ax: Axes | None = None,
) -> Axes:
    """|Δs_m − Δs_periodic|/|Δs_periodic| [-] against cycle (log), with where the paper's
    stopping rule stops (dots) and the published settling count (dashed)."""
    ax = axes_or_new(ax)
    for label, d in deviation.items():
        c = np.asarray(cycles, float)
        dv = np.maximum(np.asarray(d, float), 1e-17)
        (line,) = ax.plot(c, dv, lw=0.8, label=label)
        k = stops.get(label)
        if k is not None:
            ax.plot(
                [k],
                [dv[k - 1]],
                marker="o",
                ms=6,
                color=line.get_color(),
                ls="none",
                label=f"successive-Δs rule stops (cycle {k})",
            )
    ax.axvline(
        published_cycles,
        color=PUBLISHED_COLOR,
        ls="--",
        lw=1.2,
        label=f"published: ≥ {published_cycles:g} impacts",
    )
    ax.set_yscale("log")
    ax.set_xscale("log")
    ax.set_xlabel("cycle  [-]")
    ax.set_ylabel("relative distance of Δs to\nthe periodic value  [-]")
    ax.legend(loc="upper right", framealpha=0.9, fontsize=6.5)
    return ax
