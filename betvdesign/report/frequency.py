"""Speed against actuation frequency (report figure of every device), with the
actuator's thermal roll-off for a device that gives a thermal cut-off or whose stroke is
predicted from the drawing (its own thermal modes' roll-off,
:func:`betvdesign.model.electrothermal.modal_gain`).

Only ϖ = f_act/f_v depends on the actuation frequency; α, β and κ do not, and every
displacement scales with the stroke u (MODEL.md, "Displacement per cycle"). So one
periodic orbit per frequency gives Δs(ϖ), and the speed is
v(f) = Δs(f/f_v)·u(f)·cosθ·f with u(f) = u·H(f)/H(f_act) from
:meth:`betvdesign.nondim.record.Scales.amplitude_m` (the roll-off of
:mod:`betvdesign.model.rolloff`, as derived by :mod:`betvdesign.nondim.device`); the idealised model
keeps the calibrated stroke u_cal = u(f_cal) at every frequency.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from betvdesign import dynamics, plots
from betvdesign.model.domain import VARPI_WINDOW
from betvdesign.model.params import ModelParams
from betvdesign.nondim.record import SetDerivation
from betvdesign.output.siformat import format_si
from betvdesign.report.analysis import Missing, Piece, ReportOptions
from betvdesign.report.figures import figure_block, ladder
from betvdesign.report.model import FigureBlock

if TYPE_CHECKING:
    from betvdesign.dynamics import PeriodicResult

#: Largest ϖ of the sweep relative to the window's upper edge (ϖ < 2: finite contact).
_TOP = 0.98


@dataclass(frozen=True)
class FrequencySweep:
    """Periodic Δs [-] per cycle at actuation frequencies ``f_act_hz`` [Hz] (None: no
    periodic orbit, ``reasons``); ``n_orbits`` periodic orbits were solved."""

    f_act_hz: np.ndarray
    delta_s: list[float | None]
    reasons: list[str]
    n_orbits: int


def frequency_grid(varpi: float, points: int) -> np.ndarray:
    """ϖ values of the sweep: ``points`` evenly over the design window (widened to the
    device's ϖ), the device's own ϖ included exactly."""
    lo = min(VARPI_WINDOW[0], 0.9 * varpi)
    hi = max(_TOP * VARPI_WINDOW[1], 1.1 * varpi)
    grid = np.linspace(lo, hi, max(points, 3))
    return np.unique(np.append(grid, varpi))


def frequency_sweep(
    p: ModelParams, f_act_hz: float, per: Piece[PeriodicResult], opts: ReportOptions
) -> FrequencySweep:
    """Periodic Δs over :func:`frequency_grid` (α, β, κ fixed); the device's own orbit
    ``per`` is reused."""
    periodic_orbit = dynamics.periodic_orbit
    f_v = f_act_hz / p.varpi
    grid = frequency_grid(p.varpi, opts.frequency_points)
    delta_s: list[float | None] = []
    reasons: list[str] = []
    n = 0
    for w in grid:
        if w == p.varpi:
            if not per.ok:
                raise Missing(f"no periodic orbit at the device's own frequency: {per.reason}")
            res = per.value
        else:
            res = periodic_orbit(
                replace(p, varpi=float(w)),  # damping and restitution kept
                tol=opts.periodic_tol,
                max_cycles=opts.sweep_max_cycles,
            )
            n += 1
        ok = res.success and res.delta_s is not None
        delta_s.append(float(res.delta_s) if ok else None)
        reasons.append("" if ok else f"{res.status}: {res.message}")
    return FrequencySweep(grid * f_v, delta_s, reasons, n)


def _missing_text(sweep: FrequencySweep) -> str:
    """The swept frequencies without a periodic orbit, grouped by status: each status
    once, with its frequencies and the first one's message (the others say the same
    at their own ϖ)."""
    groups: dict[str, list[tuple[float, str]]] = {}
    for f, r in zip(sweep.f_act_hz, sweep.reasons, strict=True):
        if r:
            status, _, message = r.partition(": ")
            groups.setdefault(status, []).append((float(f), message))
    parts = []
    for status, rows in groups.items():
        freqs = ", ".join(format_si(f, "Hz") for f, _ in rows)
        parts.append(f"{status} at {freqs} (at {format_si(rows[0][0], 'Hz')}: {rows[0][1]})")
    return (" No periodic orbit: " + "; ".join(parts) + ".") if parts else ""


def speeds(sd: SetDerivation, sweep: FrequencySweep) -> tuple[list[float | None], ...]:
    """(velocity with the roll-off, with the calibrated stroke held constant) [m/s]
    signed along the impact direction (+ push) at each swept frequency (None where Δs is
    missing); the figure draws their magnitudes, coloured by mode."""
    sc = sd.scales
    cos = math.cos(sc.theta_rad)
    u_f = sc.amplitude_m(sweep.f_act_hz)
    u_cal = sc.amplitude_m(sc.calibration_hz) if sc.calibration_hz is not None else sc.u_m
    rolled, constant = [], []
    for f, u, ds in zip(sweep.f_act_hz, u_f, sweep.delta_s, strict=True):
        rolled.append(None if ds is None else ds * float(u) * cos * float(f))
        constant.append(None if ds is None else ds * u_cal * cos * float(f))
    return rolled, constant


def speed_frequency(
    key: str, sd: SetDerivation, piece: Piece[FrequencySweep], tol: float
) -> FigureBlock:
    """The figure block (see the module docstring)."""
    sc, p = sd.scales, sd.params
    f_v = sc.f_act_hz / p.varpi
    head = (
        "Mean slider speed (a magnitude; each point in its mode's colour: push moves the "
        "slider along the impacts, pull against them) against the actuation frequency "
        f"f_act (top axis ϖ = f_act/f_v, f_v = {format_si(f_v, 'Hz')}; outside the design "
        "window hatched; dash-dotted: the sub-resonances α·ϖ² = 1/n², f_act = f_h/n with "
        f"f_h = f_v/√α = {format_si(f_v / math.sqrt(p.alpha), 'Hz')}"
        + (
            "; cross-hatched, speeds grey: the undamped head's tangential resonance "
            "|α·ϖ² − 1| < 0.1, where the idealised speed is not the device's). "
            if p.zeta_h == 0.0
            else "). "
        )
    )
    drawn = sd.stroke is not None and bool(sc.thermal_modes)
    rolls = sc.has_rolloff or drawn
    cutoff = sd.stroke.f_cutoff_hz if drawn and sd.stroke is not None else sc.cutoff_hz
    if drawn:
        caption = head + _drawn_caption(sd)
    elif sc.has_rolloff:
        caption = head + (
            "Solid: with the stroke's first-order thermal roll-off "
            f"u(f) = u_cal·H(f)/H(f_cal), H(f) = 1/sqrt(1 + (f/f_c)²), f_c = "
            f"{format_si(sc.cutoff_hz, 'Hz')}, f_cal = "
            f"{format_si(sc.calibration_hz or 0.0, 'Hz')}; dashed: the calibrated stroke u_cal "
            "at every frequency (no roll-off; the device's damping and restitution in both "
            f"curves). At the device's f_act = {format_si(sc.f_act_hz, 'Hz')} the stroke is "
            f"{sc.rolloff_factor:.3g} × u_cal ({format_si(sc.u_m, 'm')})."
        )
    else:
        caption = head + (
            f"The stroke u = {format_si(sc.u_m, 'm')} at every frequency: the device gives no "
            "thermal cut-off (an electrothermal stroke falls above its thermal cut-off; give "
            "actuator.thermal_cutoff to see it). The drive frequency is half of f_act with "
            "AC doubling."
        )
    rolled: list[float | None] = []
    constant: list[float | None] = []
    if piece.ok:
        sweep = piece.value
        rolled, constant = speeds(sd, sweep)
        caption += f" {len(sweep.f_act_hz)} frequencies, one periodic orbit each (α, β, κ fixed)."
        sign = 1.0 if sd.intended_mode == "push" else -1.0
        curves = (("with roll-off", rolled), ("without", constant)) if rolls else (("", rolled),)
        for label, vals in curves:
            best = max(
                ((sign * v, f) for v, f in zip(vals, sweep.f_act_hz, strict=True) if v is not None),
                default=None,
            )
            if best is not None and best[0] > 0:
                caption += (
                    f" Fastest swept frequency in the intended direction{' ' * bool(label)}"
                    f"{label}: "
                    f"{format_si(float(best[1]), 'Hz')} ({format_si(best[0], 'm/s')})."
                )
        caption += _missing_text(sweep)

    def draw(ax: Any) -> None:
        plots.speed_vs_frequency(
            piece.value.f_act_hz,
            rolled,
            constant,
            f_v_hz=f_v,
            cutoff_hz=cutoff if rolls else None,
            rolloff=rolls,
            operating=(sc.f_act_hz, sc.speed_m_s(_device_ds(piece.value, p.varpi, f_v))),
            alpha=p.alpha,
            undamped=p.zeta_h == 0.0,
            ax=ax,
            **({"constant_label": "stroke held at its f_act value (no roll-off)"} if drawn else {}),
        )

    model = (
        "periodic orbits of the exact model, one per frequency; Δs does not depend on u, "
        "so the roll-off enters through the stroke (length scale) only"
    )
    rung = ladder(p, "delta_s", "periodic", tol=tol)
    return figure_block(
        key,
        "Mean speed against actuation frequency" + (", with thermal roll-off" if rolls else ""),
        caption,
        model,
        rung,
        piece,
        draw,
    )


def _drawn_caption(sd: SetDerivation) -> str:
    """The caption's roll-off sentences for a stroke predicted from the drawing.

    Parameters
    ----------
    sd : SetDerivation
        A set whose stroke is predicted (its :attr:`~SetDerivation.stroke` and the
        thermal modes in its scales).

    Returns
    -------
    str
        What the solid and the dashed curves hold.
    """
    sc, st = sd.scales, sd.stroke
    assert st is not None
    return (
        "Solid: with the drawing's thermal roll-off u(f) = u·G(f)/G(f_act), G the gain of "
        "the drawn actuator's thermal modes at the heating frequency f (f_act for every "
        f"waveform; the electrothermal model at the device's {st.voltage_v:.4g} V, nothing "
        f"fitted), thermal cut-off f_c = {format_si(st.f_cutoff_hz, 'Hz')}, first thermal "
        f"mode {format_si(st.f_thermal_hz, 'Hz')}; dashed: the stroke held at its f_act "
        f"value u = {format_si(sc.u_m, 'm')} at every frequency (no roll-off; the device's "
        "damping and restitution in both curves). The drive frequency is half of f_act "
        "with AC doubling."
    )


def _device_ds(sweep: FrequencySweep, varpi: float, f_v: float) -> float:
    """Δs at the device's own frequency (in the sweep by construction)."""
    i = int(np.argmin(np.abs(sweep.f_act_hz / f_v - varpi)))
    ds = sweep.delta_s[i]
    return float(ds) if ds is not None else math.nan


def figures(
    key: str, sd: SetDerivation, piece: Piece[FrequencySweep], tol: float
) -> list[FigureBlock]:
    """The speed-against-frequency figure of a set (with the roll-off when it gives a
    thermal cut-off or its stroke is predicted from the drawing)."""
    return [speed_frequency(key, sd, piece, tol)]
