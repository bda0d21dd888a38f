"""Sweep figures: slider speed against drive voltage, against actuation frequency (with the
actuator's thermal roll-off), and against changes of the designer's fields (robustness)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from matplotlib.axes import Axes

from betvdesign.model.domain import SUBRESONANCE_ORDERS, TANGENTIAL_DETUNING, VARPI_WINDOW
from betvdesign.output.presentation import MODE_COLORS, MODE_DIRECTION
from betvdesign.output.siformat import format_si, scale_for
from betvdesign.plots.figure import (
    DEVICE_COLOR,
    axes_or_new,
    dimensionless_twin,
    known_values,
    legend_below,
)
from betvdesign.plots.marks import mark_resonance, mark_subresonances, mark_window, speed_scale


def speed_vs_voltage(
    volts: Sequence[float],
    speed_m_s: Sequence[float],
    *,
    operating_v: float | None = None,
    operating_speed_m_s: float | None = None,
    mode: str | None = None,
    ax: Axes | None = None,
) -> Axes:
    """Mean slider speed [m/s, a magnitude, drawn with the SI prefix it calls for] against
    drive voltage [V], operating point marked; ``mode`` (push or pull) says which way
    the slider moves (in the legend)."""
    ax = axes_or_new(ax)
    v = np.asarray(speed_m_s, float)
    k, unit = scale_for(float(np.abs(v).max()) if v.size else 0.0, "m/s")
    label = (
        f"mean speed ({mode}: {MODE_DIRECTION[mode]})" if mode in MODE_DIRECTION else "mean speed"
    )
    ax.plot(np.asarray(volts, float), v * k, color="black", label=label)
    if operating_v is not None and operating_speed_m_s is not None:
        ax.plot(
            [operating_v],
            [operating_speed_m_s * k],
            marker="o",
            ms=6,
            color=DEVICE_COLOR,
            ls="none",
            label=f"operating point {operating_v:g} V, {format_si(operating_speed_m_s, 'm/s')}",
        )
    ax.axhline(0.0, color="#7f7f7f", lw=0.5)
    ax.set_xlabel("drive voltage  [V]")
    ax.set_ylabel(f"mean slider speed  [{unit}]")
    ax.legend(loc="best", framealpha=0.9)
    return ax


def speed_vs_frequency(
    f_act_hz: Sequence[float],
    velocity_m_s: Sequence[float | None],
    constant_stroke_m_s: Sequence[float | None],
    *,
    f_v_hz: float,
    cutoff_hz: float | None = None,
    rolloff: bool = True,
    operating: tuple[float, float] | None = None,
    alpha: float | None = None,
    undamped: bool = False,
    ax: Axes | None = None,
    constant_label: str = "calibrated stroke at every frequency (no roll-off)",
) -> Axes:
    """Mean slider speed [m/s, SI prefix by magnitude] against actuation frequency.

    The speed (a magnitude; each point's marker in its mode's colour says which way)
    against actuation frequency [Hz, drawn with its prefix], with the stroke's thermal
    roll-off (solid) and with the calibrated stroke held constant (dashed, the idealised
    model). ``velocity_m_s`` and ``constant_stroke_m_s`` are signed along the impacts
    (+ push, − pull); None: no periodic orbit there (crosses on zero). Top axis
    ϖ = f_act/f_v; outside the design window 0.5 ≤ ϖ < 2 hatched, the cut-off f_c drawn
    where it falls inside the plot; ``operating``: (f_act [Hz], velocity [m/s]) of the
    device. ``rolloff`` False: the device gives no cut-off, one solid curve (the stroke
    constant). ``alpha`` (α = k_v/k_h [-], fixed along the sweep): the sub-resonances
    f_act = f_h/n (f_h = f_v/√α) marked, and with ``undamped`` (ζ_h = 0) the band
    |α·ϖ² − 1| < 0.1 cross-hatched, its speeds grey and left out of the speed axis
    (:mod:`betvdesign.plots.marks`), which turns symmetric-logarithmic when spikes would
    flatten the operating region. ``constant_label``: the dashed curve's legend (a
    stroke predicted from the drawing holds its f_act value, not a calibrated one).

    Over 80 lines on purpose: one figure, its curves, bands, the design window, the roll-off
    and the device's marker drawn on one axes; splitting it would pass the axes' state
    between pieces.
    """
    ax = axes_or_new(ax)
    f = np.asarray(f_act_hz, float)
    ok, signed = known_values(velocity_m_s)
    v = np.abs(signed)
    v0 = np.abs(np.array([x if x is not None else np.nan for x in constant_stroke_m_s], float))
    kf, f_unit = scale_for(float(f.max()) if f.size else 0.0, "Hz")
    f_h = f_v_hz / math.sqrt(alpha) if alpha else None
    grey = np.zeros(len(f), dtype=bool)
    extra: list[Any] = []  # legend handles of the marks
    if f_h is not None and undamped:
        d = TANGENTIAL_DETUNING
        a, b = max(f_h * math.sqrt(1.0 - d), f.min()), min(f_h * math.sqrt(1.0 + d), f.max())
        grey, extra = mark_resonance(ax, [(a * kf, b * kf)] if a < b else [], f * kf)
    spikes = np.where(grey & ok, v, np.nan)
    v, v0 = np.where(grey, np.nan, v), np.where(grey, np.nan, v0)
    top = max(float(np.nanmax(v[ok], initial=0.0)), float(np.nanmax(v0, initial=0.0)))
    kv, v_unit = scale_for(top, "m/s")
    if grey.any():
        ax.plot(f * kf, spikes * kv, ls="none", marker="o", ms=3, color="0.6")
    if rolloff:
        ax.plot(
            f[ok] * kf,
            v0[ok] * kv,
            color="#7f7f7f",
            ls="--",
            marker="o",
            ms=2.5,
            label=constant_label,
        )
    ax.plot(
        f[ok] * kf,
        v[ok] * kv,
        color="black",
        label="with the thermal roll-off of the stroke" if rolloff else "stroke u constant",
    )
    for mode, side in (("push", signed > 0), ("pull", signed < 0)):
        if (ok & side & ~grey).any():
            ax.plot(
                f[ok & side & ~grey] * kf,
                v[ok & side & ~grey] * kv,
                ls="none",
                marker="o",
                ms=3.5,
                color=MODE_COLORS[mode],
                label=f"{mode} ({MODE_DIRECTION[mode]})",
            )
    if (~ok).any():
        ax.plot(
            f[~ok] * kf,
            v[~ok],
            ls="none",
            marker="x",
            ms=6,
            color="#7f7f7f",
            label="no periodic orbit",
        )
    if operating is not None:
        ax.plot(
            [operating[0] * kf],
            [abs(operating[1]) * kv],
            marker="o",
            ms=7,
            ls="none",
            color=DEVICE_COLOR,
            label=f"the device: {format_si(operating[0], 'Hz')}, "
            f"{format_si(abs(operating[1]), 'm/s')}",
        )
    lo, hi = ax.get_xlim()
    window = [(VARPI_WINDOW[0] * f_v_hz * kf, VARPI_WINDOW[1] * f_v_hz * kf)]
    extra += mark_window(ax, lo, hi, window)
    if f_h is not None:
        order = range(1, SUBRESONANCE_ORDERS + 1)
        at = [(n, f_h / n * kf) for n in order if lo <= f_h / n * kf <= hi]
        extra += mark_subresonances(ax, at, hi - lo)
    speed_scale(ax, np.concatenate([v[ok], v0[ok]]) * kv)
    if cutoff_hz is not None and lo <= cutoff_hz * kf <= hi:
        ax.axvline(
            cutoff_hz * kf,
            color="#1f77b4",
            ls=":",
            lw=1.2,
            label=f"thermal cut-off f_c = {format_si(cutoff_hz, 'Hz')}",
        )
    ax.set_xlim(lo, hi)
    ax.set_xlabel(f"actuation frequency f_act  [{f_unit}]")
    ax.set_ylabel(f"mean slider speed  [{v_unit}]")
    dimensionless_twin(ax, "x", f_v_hz * kf, "ϖ = f_act/f_v  [-]")
    legend_below(ax, handles=ax.get_legend_handles_labels()[0] + extra)
    return ax


def speed_vs_field_change(
    series: Sequence[tuple[str, Sequence[float], Sequence[float | None], Sequence[bool]]],
    *,
    unit: str = "m/s",
    flips: Sequence[tuple[str, float]] = (),
    wrong_mode: str = "",
    ax: Axes | None = None,
) -> Axes:
    """Mean slider speed against the relative change [%] of each designer field.

    series: per field (label, change [%], velocity [``unit``, positive: the intended
    direction of travel] or None where no periodic orbit exists, λ-fit miss flags). The
    speed is drawn as a magnitude (the package's convention) on an axis with the SI prefix
    it calls for; points where the slider runs the wrong way (the other mode) get a square
    in that mode's colour; None points are crosses on zero; points where the λ fit
    predicts the other mode are ringed. ``flips``: (label, change [%]) where a field's
    exact mode changes (bisected), drawn as a bar on zero in the field's colour.
    ``wrong_mode``: the mode of a wrong-way point (its square's colour and legend).
    """
    ax = axes_or_new(ax)
    vals = [abs(v) for _, _, ys, _ in series for v in ys if v is not None]
    factor, label_unit = scale_for(max(vals, default=0.0), unit)
    markers = "osD^v<>"
    missed = False
    wrong_way = False
    wrong_color = MODE_COLORS.get(wrong_mode, "#555555")
    colors: dict[str, str] = {}
    for k, (label, xs, ys, misses) in enumerate(series):
        x = np.asarray(xs, dtype=float)
        ok, y = known_values(ys)
        wrong = ok & (y < 0.0)
        y = np.abs(y) * factor
        (line,) = ax.plot(
            x[ok], y[ok], marker=markers[k % len(markers)], ms=3.5, lw=1.1, label=label
        )
        colors[label] = line.get_color()
        if (~ok).any():
            ax.plot(x[~ok], y[~ok], ls="none", marker="x", ms=6, color=line.get_color())
        if wrong.any():
            wrong_way = True
            ax.plot(x[wrong], y[wrong], ls="none", marker="s", ms=7, mfc="none", color=wrong_color)
        miss = ok & np.asarray(misses, dtype=bool)
        if miss.any():
            missed = True
            ax.plot(x[miss], y[miss], ls="none", marker="o", ms=9, mfc="none", color=DEVICE_COLOR)
    if missed:
        ax.plot(
            [],
            [],
            ls="none",
            marker="o",
            ms=9,
            mfc="none",
            color=DEVICE_COLOR,
            label="λ fit predicts the other mode",
        )
    if wrong_way:
        ax.plot(
            [],
            [],
            ls="none",
            marker="s",
            ms=7,
            mfc="none",
            color=wrong_color,
            label=f"wrong way ({wrong_mode}: {MODE_DIRECTION.get(wrong_mode, 'the other mode')})",
        )
    for k, (label, at) in enumerate(flips):
        ax.plot(
            [at],
            [0.0],
            ls="none",
            marker="|",
            ms=16,
            mew=2.0,
            color=colors.get(label, "k"),
            label="mode flips (bisected)" if k == 0 else None,
        )
    ax.axhline(0.0, color="#7f7f7f", lw=0.8)
    ax.axvline(0.0, color=DEVICE_COLOR, lw=1.0, ls=":", label="the device as specified")
    ax.set_ylim(bottom=0.0)
    ax.set_xlabel("change of the field from its specified value  [%]")
    ax.set_ylabel(f"mean slider speed  [{label_unit}]")
    legend_below(ax, ncol=3)
    return ax


def robustness_vs_lambda(
    lam: Sequence[float],
    delta_s: Sequence[float | None],
    *,
    device_lam: float | None = None,
    logx: bool = False,
    ax: Axes | None = None,
) -> Axes:
    """Periodic slider increment Δs per cycle [-] against the λ fit [-].

    The fit's mode boundary λ = 1 is drawn; Δs > 0 is push, Δs < 0 pull, so a
    point whose sign disagrees with its side of λ = 1 is a fit miss (ringed). None
    entries (no periodic orbit found) are drawn as crosses on Δs = 0.
    logx: logarithmic λ axis (for sweeps spanning decades).
    """
    ax = axes_or_new(ax)
    if logx:
        ax.set_xscale("log")
    x = np.asarray(lam, dtype=float)
    ok, y = known_values(delta_s)
    order = np.argsort(x[ok])
    ax.plot(
        x[ok][order],
        y[ok][order],
        color="black",
        lw=1.0,
        marker="o",
        ms=3,
        label="periodic Δs (exact model)",
    )
    miss = ok & (((x < 1.0) & (y < 0.0)) | ((x > 1.0) & (y > 0.0)))
    if miss.any():
        ax.plot(
            x[miss],
            y[miss],
            ls="none",
            marker="o",
            ms=8,
            mfc="none",
            color=DEVICE_COLOR,
            label="fit misses (sign of Δs ≠ side of λ = 1)",
        )
    if (~ok).any():
        ax.plot(
            x[~ok],
            y[~ok],
            ls="none",
            marker="x",
            ms=5,
            color="#7f7f7f",
            label="no periodic orbit found",
        )
    ax.axvline(1.0, color="black", ls="--", lw=1.0, label="λ = 1 (fit boundary)")
    ax.axhline(0.0, color="#7f7f7f", lw=0.5)
    if device_lam is not None:
        ax.axvline(
            device_lam, color=DEVICE_COLOR, lw=1.2, ls=":", label=f"device λ = {device_lam:.3g}"
        )
    lo, hi = ax.get_xlim()
    ax.axvspan(lo, 1.0, color=MODE_COLORS["push"], alpha=0.08, lw=0)
    ax.axvspan(1.0, hi, color=MODE_COLORS["pull"], alpha=0.08, lw=0)
    ax.set_xlim(lo, hi)
    ax.set_xlabel("λ  [-]")
    ax.set_ylabel("Δs per cycle  [-]")
    ax.legend(loc="best", framealpha=0.9)
