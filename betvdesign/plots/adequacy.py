"""Model-adequacy figure: mode and mean speed against the head's quality factor Q and
against the coefficient of restitution e, around the device
(:mod:`betvdesign.checks.adequacy`). Plain arrays in, drawn on ``ax=``."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from matplotlib.axes import Axes

from betvdesign.output.presentation import MODE_COLORS
from betvdesign.output.siformat import scale_for
from betvdesign.plots.figure import DEVICE_COLOR, axes_or_new, known_values, legend_below


def mode_speed_scan(
    x: Sequence[float],
    speed_m_s: Sequence[float | None],
    modes: Sequence[str | None],
    *,
    xlabel: str,
    logx: bool = False,
    device: tuple[float, float] | None = None,
    ideal_m_s: float | None = None,
    flips: Sequence[float] = (),
    speed_scale: tuple[float, str] | None = None,
    ax: Axes | None = None,
) -> Axes:
    """Mean slider speed [m/s, a magnitude, SI prefix by magnitude] against ``x``.

    ``x`` is Q [-] or e [-]; each point is coloured by its mode ("push", "pull",
    "stalled", "none" = not driven, None = no periodic orbit: crosses on zero), which
    says the way (the speeds may be given signed along the impacts: drawn as |v|).

    device: (x, speed [m/s]) of the device with its (or the default) damping and
    restitution; ideal_m_s: the idealised model's speed [m/s] (dashed line); flips:
    x where the mode changes (dotted lines); speed_scale: (factor, unit) to share one
    speed axis between panels (default: from the data).
    """
    ax = axes_or_new(ax)
    if logx:
        ax.set_xscale("log")
    xs = np.asarray(x, float)
    _, v = known_values(speed_m_s)
    v = np.abs(v)  # a speed is a magnitude; the colour gives the mode
    top = max(float(np.abs(v).max(initial=0.0)), abs(ideal_m_s or 0.0))
    k, unit = speed_scale or scale_for(top, "m/s")
    moving = np.array([m in ("push", "pull", "stalled") for m in modes], bool)
    ax.plot(xs, np.where(moving, v * k, np.nan), color="black", lw=0.8, zorder=1)
    for mode in ("push", "pull", "stalled", "none", None):
        sel = np.array([m == mode for m in modes], bool)
        if not sel.any():
            continue
        if mode is None:
            ax.plot(
                xs[sel],
                v[sel] * 0.0,
                ls="none",
                marker="x",
                ms=6,
                color="#7f7f7f",
                label="no periodic orbit",
            )
            continue
        label = {"none": "not driven"}.get(mode, mode)
        color = MODE_COLORS[label]
        ax.plot(
            xs[sel], v[sel] * k, ls="none", marker="o", ms=3.5, color=color, label=label, zorder=2
        )
    if ideal_m_s is not None and math.isfinite(ideal_m_s):
        ax.axhline(
            abs(ideal_m_s) * k,
            color="black",
            ls="--",
            lw=1.0,
            label="idealised model (undamped, plastic)",
        )
    for i, f in enumerate(flips):
        ax.axvline(f, color="black", ls=":", lw=1.0, label="mode flips" if i == 0 else None)
    if device is not None and device[1] is not None and math.isfinite(device[0]):
        ax.plot(
            [device[0]],
            [abs(device[1]) * k],
            marker="*",
            ms=10,
            ls="none",
            color=DEVICE_COLOR,
            label="the device",
            zorder=3,
        )
    ax.axhline(0.0, color="#7f7f7f", lw=0.5)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(f"mean slider speed  [{unit}]")
    legend_below(ax)
    return ax
