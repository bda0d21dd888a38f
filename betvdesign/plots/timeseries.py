"""Slider motion against time: velocity settling and displacement over the travel range."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from matplotlib.axes import Axes

from betvdesign.plots._figure import DEVICE_COLOR, axes_or_new


def slider_velocity(
    t_cycles: Sequence[float],
    ds: Sequence[float],
    *,
    cycle_mean: tuple[Sequence[float], Sequence[float]] | None = None,
    periodic_mean: float | None = None,
    logx: bool = False,
    ax: Axes | None = None,
) -> Axes:
    """Slider velocity s' [-] against time [actuation cycles].

    logx: logarithmic time axis (t = 0 is then left out), to show the first
    cycles and a long settling in one panel.

    cycle_mean: (cycle index m, mean velocity Δs_m·ϖ/(2π)) per cycle [-], drawn
    as dots at the cycle mid-points; periodic_mean: the periodic orbit's mean
    velocity Δs·ϖ/(2π) [-], drawn as a dashed line (the settled state).
    """
    ax = axes_or_new(ax)
    t = np.asarray(t_cycles, float)
    v = np.asarray(ds, float)
    if logx:
        ax.set_xscale("log")
        t, v = t[t > 0], v[t > 0]
    ax.plot(t, v, color="#1f77b4", lw=0.7, label="s'(τ)")
    if cycle_mean is not None:
        m, v = (np.asarray(a, float) for a in cycle_mean)
        ax.plot(
            m + 0.5, v, ls="none", marker="o", ms=2.5, color="black", label="cycle mean Δsₘ·ϖ/2π"
        )
    if periodic_mean is not None:
        ax.axhline(
            periodic_mean,
            color=DEVICE_COLOR,
            ls="--",
            lw=1.1,
            label=f"periodic state {periodic_mean:.3g}",
        )
    ax.axhline(0.0, color="#7f7f7f", lw=0.5)
    ax.set_xlabel("t / T_act  [cycles]")
    ax.set_ylabel("s'  [-]")
    ax.legend(loc="best", framealpha=0.9)
    return ax


def slider_displacement(
    t_ms: Sequence[float],
    x_um: Sequence[float],
    *,
    travel_um: float | None = None,
    extrapolated: tuple[Sequence[float], Sequence[float]] | None = None,
    ax: Axes | None = None,
) -> Axes:
    """Slider displacement [µm] against time [ms], with the travel range marked.

    travel_um: the end of the travel range [µm], signed in the direction of motion.

    extrapolated: optional (t_ms, x_um) continuation at the periodic speed,
    drawn dashed and labelled as such (never blended into the simulated curve).
    """
    ax = axes_or_new(ax)
    ax.plot(
        np.asarray(t_ms, float),
        np.asarray(x_um, float),
        color="black",
        lw=1.2,
        label="simulated (exact model)",
    )
    if extrapolated is not None:
        te, xe = (np.asarray(a, float) for a in extrapolated)
        ax.plot(te, xe, color="#7f7f7f", lw=1.2, ls="--", label="continued at periodic speed")
    if travel_um is not None:
        ax.axhline(
            travel_um,
            color=DEVICE_COLOR,
            lw=0.9,
            ls=":",
            label=f"travel range {abs(travel_um):g} µm",
        )
    ax.set_xlabel("t  [ms]")
    ax.set_ylabel("slider displacement  [µm]")
    ax.legend(loc="best", framealpha=0.9)
    return ax
