"""Figures of a stroke predicted from the drawing: u(V) with the peak temperature, u(f) with
the drawing's thermal roll-off (:mod:`betvdesign.report.thermal` computes the data)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from matplotlib.axes import Axes

from betvdesign.model.domain import VARPI_WINDOW
from betvdesign.output.presentation import MODE_COLORS
from betvdesign.output.siformat import format_si, scale_for
from betvdesign.plots.figure import DEVICE_COLOR, axes_or_new, dimensionless_twin

__all__ = ["stroke_vs_frequency", "stroke_vs_voltage"]

#: Colour of the peak temperature (its twin axis and curve).
TEMPERATURE_COLOR = "#ff7f0e"
#: Colour of the thermal corner frequencies.
THERMAL_COLOR = "#1f77b4"


def stroke_vs_voltage(
    volts: Sequence[float],
    stroke_m: Sequence[float],
    static_m: Sequence[float],
    t_max_k: Sequence[float],
    *,
    device_v: float,
    device_stroke_m: float,
    melting_v: float,
    melting_k: float,
    onset_v: float | None = None,
    onset_k: float | None = None,
    ax: Axes | None = None,
) -> Axes:
    """The stroke at the drive and the static stroke against the drive voltage, T_max twinned.

    Parameters
    ----------
    volts : sequence of float
        Drive voltage amplitudes V [V], increasing.
    stroke_m : sequence of float
        The head's half swing u at the drive's frequency and waveform [m].
    static_m : sequence of float
        The steady stroke u_static at a DC voltage V [m].
    t_max_k : sequence of float
        The actuator's peak temperature at a DC voltage V [K] (right axis).
    device_v, device_stroke_m : float
        The device's drive voltage [V] and its stroke there [m] (marked).
    melting_v : float
        The voltage where the peak temperature reaches the melting point [V] (marked).
    melting_k : float
        The melting point [K] (drawn on the temperature axis).
    onset_v, onset_k : float, optional
        The voltage where the peak temperature reaches the onset of plastic deformation
        [V] and that onset [K] (marked dash-dotted when given).
    ax : matplotlib.axes.Axes, optional
        Axes to draw on (a new figure when None).

    Returns
    -------
    matplotlib.axes.Axes
        The stroke's axes (the temperature's is its twin).
    """
    ax = axes_or_new(ax)
    v = np.asarray(volts, float)
    u = np.asarray(stroke_m, float)
    us = np.asarray(static_m, float)
    k, unit = scale_for(float(max(np.abs(us).max(initial=0.0), np.abs(u).max(initial=0.0))), "m")
    ax.plot(v, us * k, color="#7f7f7f", ls="--", label="static stroke u_static (DC)")
    ax.plot(v, u * k, color="black", label="stroke u at the drive frequency")
    ax.plot(
        [device_v],
        [device_stroke_m * k],
        marker="o",
        ms=7,
        ls="none",
        color=DEVICE_COLOR,
        label=f"the device: {device_v:.4g} V, {format_si(device_stroke_m, 'm')}",
    )
    ax.axvline(
        melting_v,
        color=TEMPERATURE_COLOR,
        ls=":",
        lw=1.2,
        label=f"T_max reaches the melting point: {melting_v:.4g} V",
    )
    if onset_v is not None and onset_k is not None:
        ax.axvline(
            onset_v,
            color=TEMPERATURE_COLOR,
            ls="-.",
            lw=1.0,
            label=f"T_max reaches the onset of plastic deformation ({onset_k:.4g} K): "
            f"{onset_v:.4g} V",
        )
    hi = float(v.max()) if v.size else melting_v
    if hi > melting_v:
        ax.axvspan(melting_v, hi, color=TEMPERATURE_COLOR, alpha=0.08, lw=0)
    ax.set_xlim(0.0, hi)
    ax.set_ylim(bottom=0.0)
    ax.set_xlabel("drive voltage V  [V]")
    ax.set_ylabel(f"stroke  [{unit}]")
    tw = ax.twinx()
    tw.plot(v, np.asarray(t_max_k, float), color=TEMPERATURE_COLOR, lw=1.0)
    tw.axhline(melting_k, color=TEMPERATURE_COLOR, ls=":", lw=0.8)
    if onset_v is not None and onset_k is not None:
        tw.axhline(onset_k, color=TEMPERATURE_COLOR, ls="-.", lw=0.8)
    tw.set_ylabel("peak temperature T_max  [K]", color=TEMPERATURE_COLOR)
    tw.tick_params(axis="y", colors=TEMPERATURE_COLOR)
    lines, labels = ax.get_legend_handles_labels()
    lines += tw.plot([], [], color=TEMPERATURE_COLOR, lw=1.0)
    labels.append(f"T_max (right; melting point {melting_k:.4g} K dotted)")
    ax.legend(lines, labels, loc="upper left", framealpha=0.9, fontsize=7)
    return ax


def stroke_vs_frequency(
    f_act_hz: Sequence[float],
    stroke_m: Sequence[float],
    *,
    f_v_hz: float,
    cutoff_hz: float,
    operating: tuple[float, float],
    static_half_m: float | None = None,
    thermal_hz: float | None = None,
    ax: Axes | None = None,
) -> Axes:
    """The stroke against the actuation frequency with the thermal roll-off (log-log).

    Parameters
    ----------
    f_act_hz : sequence of float
        Actuation frequencies f_act [Hz] (the heating frequency), increasing, > 0.
    stroke_m : sequence of float
        The stroke u(f_act) [m] (the drawing's modal roll-off).
    f_v_hz : float
        The head's vertical resonance f_v [Hz]: top axis ϖ = f_act/f_v, the design
        window 0.5 ≤ ϖ < 2 shaded.
    cutoff_hz : float
        The thermal cut-off f_c [Hz] (|H| = 1/√2), marked.
    operating : tuple of float
        (f_act [Hz], u [m]) of the device, marked.
    static_half_m : float, optional
        u_static/2 [m], the low-frequency limit of the half swing (drawn dashed).
    thermal_hz : float, optional
        The first thermal mode's corner 1/(2π·τ_th) [Hz], marked.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on (a new figure when None).

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    ax = axes_or_new(ax)
    f = np.asarray(f_act_hz, float)
    u = np.asarray(stroke_m, float)
    k, unit = scale_for(float(np.abs(u).max(initial=0.0)), "m")
    ax.loglog(f, u * k, color="black", label="stroke u(f_act), the drawing's thermal roll-off")
    if static_half_m is not None:
        ax.axhline(static_half_m * k, color="#7f7f7f", ls="--", lw=0.8, label="u_static/2 (f → 0)")
    ax.plot(
        [operating[0]],
        [operating[1] * k],
        marker="o",
        ms=7,
        ls="none",
        color=DEVICE_COLOR,
        label=f"the device: {format_si(operating[0], 'Hz')}, {format_si(operating[1], 'm')}",
    )
    lo, hi = float(f.min()), float(f.max())
    band = (max(lo, VARPI_WINDOW[0] * f_v_hz), min(hi, VARPI_WINDOW[1] * f_v_hz))
    if band[0] < band[1]:
        ax.axvspan(*band, color=MODE_COLORS["push"], alpha=0.10, lw=0,
                   label="design window 0.5 ≤ ϖ < 2")  # fmt: skip
    ax.axvline(
        cutoff_hz,
        color=THERMAL_COLOR,
        ls=":",
        lw=1.2,
        label=f"thermal cut-off f_c = {format_si(cutoff_hz, 'Hz')}",
    )
    if thermal_hz is not None:
        ax.axvline(
            thermal_hz,
            color=THERMAL_COLOR,
            ls="-.",
            lw=0.8,
            label=f"first thermal mode {format_si(thermal_hz, 'Hz')}",
        )
    ax.set_xlim(lo, hi)
    ax.set_xlabel("actuation frequency f_act  [Hz]")
    ax.set_ylabel(f"stroke u  [{unit}]")
    dimensionless_twin(ax, "x", f_v_hz, "ϖ = f_act/f_v  [-]")
    ax.legend(loc="lower left", framealpha=0.9, fontsize=7)
    return ax
