"""The report's figures for one actuator set: data from the analysis, drawn by plots.

Each builder returns a :class:`FigureBlock` whose caption says what is shown,
which model made it and which rung of the fidelity ladder that is, and why
(:func:`betvdesign.fidelity.choose_rung`'s reason where the ladder picks the same
rung for the figure's question); when its data are missing the block carries the
reason instead of an SVG (never an invented curve).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from betvdesign import fidelity, plots
from betvdesign.nondim import SetDerivation
from betvdesign.report.analysis import REGIME_HORIZON, Piece, SetAnalysis, lambda_floor
from betvdesign.report.model import FigureBlock
from betvdesign.spec import amplitude_at
from betvdesign.units import ureg

EXACT = "exact event-driven impact model (closed-form phases, MODEL.md)"


def _svg(key: str, draw: Callable[[Any], None], *, size=(6.4, 3.4), **grid: Any) -> str:
    with plots.figure_style():
        fig, axes = plots.new_figure(*size, **grid)
        draw(axes)
        return plots.figure_svg(fig, key)


def ladder(
    p: Any, question: fidelity.Question, rung: str, *, tol: float = 1e-6, why: str = ""
) -> tuple[str, str]:
    """(rung, reason) of a figure answering ``question`` with ``rung``: the fidelity
    ladder's own reason when it picks that rung, else ``why`` (and what it would pick)."""
    c = fidelity.choose_rung(p, question, tol=tol)
    if c.rung == rung:
        return rung, c.reason
    return rung, why or (
        f"the figure needs the {rung} rung (for {question!r} alone the ladder would use "
        f"{c.rung}: {c.reason})"
    )


def _block(
    key: str,
    title: str,
    caption: str,
    model: str,
    rung: tuple[str, str],
    piece: Piece[Any],
    draw: Callable[[Any], None],
    **layout: Any,
) -> FigureBlock:
    if not piece.ok:
        return FigureBlock(
            key, title, caption, model, unavailable=piece.reason, rung=rung[0], rung_reason=rung[1]
        )
    return FigureBlock(
        key,
        title,
        caption,
        model,
        svg=_svg(key, draw, **layout),
        rung=rung[0],
        rung_reason=rung[1],
    )


def pushpull(key: str, sd: SetDerivation) -> FigureBlock:
    p = sd.params
    caption = (
        f"Device point (1/ϖ², 1/(ακ)) = ({1 / p.varpi**2:.3g}, {1 / (p.alpha * p.kappa):.3g}) "
        f"against the λ = 1 boundary 1/(ακ) = ϖ²/κ + (1/β − β)/(22(κ+1)) for the device's "
        f"κ = {p.kappa:.3g}, β = {p.beta:.3g}; λ = {p.lam:.4g} predicts {p.mode_predicted} mode. "
        "Below the curve λ < 1 (push), above λ > 1 (pull); the dash-dotted lines bound the "
        "vertical design window 0.5 ≤ ϖ < 2."
    )

    def draw(ax: Any) -> None:
        plots.pushpull_map(kappa=p.kappa, beta=p.beta, points=[(sd.name, p.varpi, p.alpha)], ax=ax)

    return _block(
        key,
        "Push/pull map",
        caption,
        "λ fit of Shin et al. (2004), no simulation",
        ("lambda", "the figure places the device against the λ fit's own boundary"),
        Piece(value=True),
        draw,
    )


def regime(key: str, sd: SetDerivation, an: SetAnalysis) -> FigureBlock:
    p = sd.params
    data = an.regime.value
    n = len(data.varpi) if data is not None else 0
    caption = (
        f"Impact period (actuation cycles per period of the head's vertical motion), mean hits "
        f"per cycle (impulsive included; above 1: multi-impact) and share "
        f"of the cycle in contact, against ϖ ({n} values, from rest; crosses: no contact "
        f"recurring within {REGIME_HORIZON} cycles, hits impulsive only); design window "
        f"0.5 ≤ ϖ < 2 shaded, device ϖ = {p.varpi:.3g} dashed."
    )

    def draw(axes: Any) -> None:
        plots.impact_period_strip(
            data.varpi,
            data.period_cycles,
            device_varpi=p.varpi,
            hits_per_cycle=data.hits_per_cycle,
            ax=axes[0],
        )
        plots.contact_fraction_strip(
            data.varpi, data.contact_fraction, device_varpi=p.varpi, ax=axes[1]
        )

    model = "vertical-only exact model (the head's vertical motion does not depend on the slider)"
    return _block(
        key,
        "Vertical regime strip",
        caption,
        model,
        ladder(p, "regime", "vertical"),
        an.regime,
        draw,
        size=(6.4, 4.0),
        nrows=2,
        sharex=True,
    )


def vertical_portrait(key: str, sd: SetDerivation, an: SetAnalysis) -> FigureBlock:
    data = an.transient.value
    cycles = int(data.t_cycles[-1]) if data is not None else 0
    caption = (
        f"Head gap ξ and its rate ξ' at ϖ = {sd.params.varpi:.3g} over the first {cycles} "
        "actuation cycles from rest (light: first half, dark: second half); ξ = 0 is contact."
    )

    def draw(ax: Any) -> None:
        plots.vertical_phase_portrait(
            data.states[:, 0], data.states[:, 1], steady_from=len(data.t_cycles) // 2, ax=ax
        )

    return _block(
        key,
        "Vertical phase portrait of the head",
        caption,
        EXACT,
        ladder(sd.params, "transient", "full"),
        an.transient,
        draw,
        size=(5.0, 3.6),
    )


def settling(key: str, sd: SetDerivation, an: SetAnalysis) -> FigureBlock:
    p = sd.params
    tr, per, orb = an.transient.value, an.periodic.value, an.orbit.value
    both = (
        Piece(value=True)
        if an.transient.ok and an.orbit.ok
        else Piece(reason="; ".join(r for r in (an.transient.reason, an.orbit.reason) if r))
    )
    run = f"{tr.n_cycles}-cycle run" if tr is not None else "run"
    first = f"first {int(tr.t_cycles[-1])}" if tr is not None else "first"
    caption = (
        f"(a) Slider velocity s' over the {first} cycles from rest and the per-cycle mean "
        f"Δsₘ·ϖ/2π over the whole {run} (log time axis), settling toward the periodic "
        "state (dashed). "
        "(b) The periodic orbit in the (ζ', s') plane; colour marks no contact, slip, "
        "reverse slip and stick."
    )
    if per is not None:
        caption += f" Periodic Δs = {float(per.delta_s):.4g} per cycle ({per.mode} mode)."
        if tr is not None and len(tr.delta_s) and float(per.delta_s) != 0.0:
            k = int(per.period_cycles or 1)
            last = float(np.mean(tr.delta_s[-k:]))
            gap = abs(last / float(per.delta_s) - 1.0)
            caption += (
                f" After {len(tr.delta_s)} cycles from rest the mean Δsₘ of the last {k} "
                f"cycle(s) differs from it by a relative {gap:.2g}."
            )

    def draw(axes: Any) -> None:
        mean = tr.delta_s * p.varpi / (2 * math.pi)
        plots.slider_velocity(
            tr.t_cycles,
            tr.states[:, 5],
            cycle_mean=(np.arange(len(mean)), mean),
            periodic_mean=float(per.delta_s) * p.varpi / (2 * math.pi),
            logx=True,
            ax=axes[0],
        )
        plots.orbit_plane(orb.dzeta, orb.ds, orb.phases, ax=axes[1])

    return _block(
        key,
        "Slider velocity settling and periodic orbit",
        caption,
        EXACT,
        (
            "full + periodic",
            ladder(p, "transient", "full")[1] + "; the periodic state (dashed) and the orbit "
            "plane need the periodic orbit itself",
        ),
        both,
        draw,
        size=(7.0, 3.3),
        ncols=2,
    )


def displacement(key: str, sd: SetDerivation, an: SetAnalysis) -> FigureBlock:
    tr = an.transient.value
    sc = sd.scales
    travel_um = sd.travel_range_m * 1e6
    caption = (
        f"Slider position x = s·u·cosθ (ℓ = {sc.length_m * 1e9:.4g} nm) in the device's x "
        f"direction against time t = τ·sqrt(m/k_v), sampled once per actuation cycle "
        f"(f_act = {sc.f_act_hz:.4g} Hz), with the {travel_um:g} µm travel range."
    )
    ext_note = ""
    if tr is not None:
        caption += f" Exact run over {tr.n_cycles} cycles from rest."

    def draw(ax: Any) -> None:
        m = np.arange(len(tr.section_s))
        t_ms = m / sc.f_act_hz * 1e3
        x_um = sd.impact_sign * tr.section_s * sc.length_m * 1e6
        sign = 1.0 if x_um[-1] >= 0 else -1.0
        ext = None
        per = an.periodic.value
        if abs(x_um[-1]) < travel_um and per is not None and float(per.delta_s) != 0.0:
            step_um = sd.impact_sign * float(per.delta_s) * sc.length_m * 1e6
            n_more = math.ceil((sign * travel_um - x_um[-1]) / step_um)
            if n_more > 0:
                mm = np.array([m[-1], m[-1] + n_more])
                ext = (mm / sc.f_act_hz * 1e3, x_um[-1] + (mm - m[-1]) * step_um)
        plots.slider_displacement(t_ms, x_um, travel_um=sign * travel_um, extrapolated=ext, ax=ax)

    block = _block(
        key,
        "Slider displacement over the travel range",
        caption + ext_note,
        EXACT,
        ladder(sd.params, "transient", "full"),
        an.transient,
        draw,
    )
    return block


def speed_voltage(
    key: str, sd: SetDerivation, an: SetAnalysis, points: int, tol: float = 1e-10
) -> FigureBlock:
    aset = sd.actuator_set
    sc = sd.scales
    cal = aset.actuator.calibration
    per = an.periodic
    piece: Piece[Any] = per
    if per.ok and cal is None:
        piece = Piece(
            reason="the device gives the amplitude u directly, not a calibration u(V); "
            "a speed-voltage curve needs one (linear, quadratic or measured)"
        )
    v0 = aset.drive.voltage.to("V").magnitude if aset.drive.voltage is not None else None
    law = getattr(cal, "law", "none")
    caption = (
        f"Mean slider speed Δs·u(V)·cosθ·f_act along the impact direction (negative: against "
        f"it) with u(V) from the {law} amplitude calibration; operating point marked."
    )

    def draw(ax: Any) -> None:
        if law == "measured":
            lo, hi = (q.to("V").magnitude for q in cal.voltage_range)
        else:
            lo, hi = 0.5 * v0, 1.5 * v0
        volts = np.linspace(lo, hi, points)
        u_m = amplitude_at(aset, ureg.Quantity(volts, "V")).to("m").magnitude
        ds = float(per.value.delta_s)
        speed = ds * np.asarray(u_m) * math.cos(sc.theta_rad) * sc.f_act_hz * 1e6
        plots.speed_vs_voltage(
            volts, speed, operating_v=v0, operating_speed_um_s=sc.speed_m_s(ds) * 1e6, ax=ax
        )

    model = (
        "one periodic orbit of the exact model; Δs does not depend on u, so speed scales with u(V)"
    )
    rung = ladder(sd.params, "delta_s", "periodic", tol=tol)
    return _block(key, "Mean speed against drive voltage", caption, model, rung, piece, draw)


def robustness(key: str, sd: SetDerivation, an: SetAnalysis) -> FigureBlock:
    data = an.robustness.value
    p = sd.params
    caption = (
        f"Periodic Δs per cycle against λ, varying α only (ϖ = {p.varpi:.3g}, β = {p.beta:.3g},"
        f" κ = {p.kappa:.3g} fixed); the fit's boundary λ = 1 dashed, device λ = {p.lam:.3g} "
        "dotted. Δs > 0 is push, Δs < 0 pull: where the sign disagrees with the side of λ = 1 "
        "the fit misses."
    )
    if data is not None:
        caption += f" {len(data.x)} periodic orbits."
        floor = lambda_floor(p)
        if data.skipped and floor is not None:
            caption += (
                f" {data.skipped} target(s) below λ = {floor:.3g} left out: with β > 1 the fit "
                "gives λ above that for every positive α (its limit α → ∞), so α alone cannot "
                "bring λ lower."
            )
        if data.failures:
            caption += " No periodic orbit at: " + "; ".join(data.failures) + "."

    def draw(ax: Any) -> None:
        logx = bool(data.x.max() / data.x.min() > 20)
        plots.robustness_vs_lambda(data.x, data.y, device_lam=p.lam, logx=logx, ax=ax)

    model = f"periodic orbits of the {EXACT}"
    rung = (
        "periodic",
        "the sweep checks where the λ fit misses the exact mode, so every point needs the "
        "periodic orbit (λ cannot check itself)",
    )
    return _block(
        key,
        "Robustness of the mode near the operating point",
        caption,
        model,
        rung,
        an.robustness,
        draw,
    )


def set_figures(
    prefix: str, sd: SetDerivation, an: SetAnalysis, voltage_points: int, tol: float = 1e-10
) -> list[FigureBlock]:
    """The seven figures of one actuator set, in reading order (``tol``: the periodic
    orbit's residual, the accuracy the speed figure's Δs is asked for)."""
    return [
        pushpull(f"{prefix}-pushpull", sd),
        regime(f"{prefix}-regime", sd, an),
        vertical_portrait(f"{prefix}-vphase", sd, an),
        settling(f"{prefix}-settling", sd, an),
        displacement(f"{prefix}-displacement", sd, an),
        speed_voltage(f"{prefix}-speed", sd, an, voltage_points, tol),
        robustness(f"{prefix}-robustness", sd, an),
    ]
