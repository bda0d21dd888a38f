"""Slider motion against time: velocity settling and displacement over the travel range."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from matplotlib.axes import Axes

from betvdesign.plots.figure import (
    DEVICE_COLOR,
    Scale,
    axes_or_new,
    dimensionless_twin,
    legend_below,
)


def slider_velocity(
    t_cycles: Sequence[float],
    ds: Sequence[float],
    *,
    cycle_mean: tuple[Sequence[float], Sequence[float]] | None = None,
    periodic_mean: float | None = None,
    logx: bool = False,
    time_scale: Scale | None = None,
    velocity_scale: Scale | None = None,
    ax: Axes | None = None,
) -> Axes:
    """Slider velocity s' [-] against time [actuation cycles].

    time_scale, velocity_scale: (physical units per cycle / per unit s', label): draw
    time and velocity in those units (e.g. ms, mm/s) with the dimensionless values on
    secondary axes.

    logx: logarithmic time axis (t = 0 is then left out), to show the first
    cycles and a long settling in one panel.

    cycle_mean: (cycle index m, mean velocity Δs_m·ϖ/(2π)) per cycle [-], drawn
    as dots at the cycle mid-points; periodic_mean: the periodic orbit's mean
    velocity Δs·ϖ/(2π) [-], drawn as a dashed line (the settled state).
    """
    ax = axes_or_new(ax)
    kt, xlabel = time_scale or (1.0, "t / T_act  [cycles]")
    kv, ylabel = velocity_scale or (1.0, "s'  [-]")
    t = np.asarray(t_cycles, float)
    v = np.asarray(ds, float)
    if logx:
        ax.set_xscale("log")
        t, v = t[t > 0], v[t > 0]
    ax.plot(t * kt, v * kv, color="#1f77b4", lw=0.7, label="instantaneous")
    if cycle_mean is not None:
        m, v = (np.asarray(a, float) for a in cycle_mean)
        ax.plot(
            (m + 0.5) * kt,
            v * kv,
            ls="none",
            marker="o",
            ms=2.5,
            color="black",
            label="mean over each cycle",
        )
    if periodic_mean is not None:
        ax.axhline(
            periodic_mean * kv,
            color=DEVICE_COLOR,
            ls="--",
            lw=1.1,
            label=f"periodic state {periodic_mean * kv:.3g}"
            + (f" {ylabel.rsplit('[', 1)[1].rstrip(']')}" if velocity_scale else ""),
        )
    ax.axhline(0.0, color="#7f7f7f", lw=0.5)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if time_scale is not None:
        dimensionless_twin(ax, "x", kt, "t / T_act  [cycles]")
    if velocity_scale is not None:
        dimensionless_twin(ax, "y", kv, "s'  [-]")
    legend_below(ax)
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
    t, x = np.asarray(t_ms, float), np.asarray(x_um, float)
    stop: float | None = None
    if travel_um is not None:
        t, x, stop = _until_end_stop(t, x, travel_um)
    ax.plot(t, x, color="black", lw=1.2, label="simulated (exact model)")
    if extrapolated is not None and stop is None:
        te, xe = (np.asarray(a, float) for a in extrapolated)
        if travel_um is not None:
            te, xe, stop = _until_end_stop(te, xe, travel_um)
        ax.plot(te, xe, color="#7f7f7f", lw=1.2, ls="--", label="continued at periodic speed")
    if stop is not None:  # named in the legend: a label beside it crossed the curve
        ax.plot(
            [stop],
            [travel_um],
            marker="o",
            ms=6,
            ls="none",
            color=DEVICE_COLOR,
            zorder=5,
            label=f"end stop at {stop:.3g} ms",
        )
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


def _until_end_stop(
    t: np.ndarray, x: np.ndarray, travel: float
) -> tuple[np.ndarray, np.ndarray, float | None]:
    """The samples up to where x first reaches ``travel`` (crossing time interpolated
    linearly between the two samples around it) and that time [same unit as t], or the
    samples unchanged and None when x never reaches it."""
    beyond = np.flatnonzero(x * np.sign(travel) >= abs(travel))
    if beyond.size == 0:
        return t, x, None
    i = int(beyond[0])
    if i == 0:
        return t[:1], np.array([travel]), float(t[0])
    f = (travel - x[i - 1]) / (x[i] - x[i - 1])
    t_stop = float(t[i - 1] + f * (t[i] - t[i - 1]))
    return np.append(t[:i], t_stop), np.append(x[:i], travel), t_stop
