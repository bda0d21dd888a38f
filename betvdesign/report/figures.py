"""The report's figures for one actuator set: data from the analysis, drawn by plots.

Each builder returns a :class:`FigureBlock` whose caption says what is shown,
which model made it and which rung of the fidelity ladder that is, and why
(:func:`betvdesign.checks.fidelity.choose_rung`'s reason where the ladder picks the same
rung for the figure's question); when its data are missing the block carries the
reason instead of an SVG (never an invented curve).
"""

from __future__ import annotations

import base64
import contextlib
import dataclasses
import math
import multiprocessing
import os
import threading
from collections.abc import Callable, Iterator
from typing import Any, TypeVar

import numpy as np

from betvdesign import plots
from betvdesign.checks import fidelity
from betvdesign.model.domain import VARPI_WINDOW
from betvdesign.nondim.record import SetDerivation
from betvdesign.output.presentation import MODE_DIRECTION
from betvdesign.output.siformat import format_si, scale_for
from betvdesign.report.analysis import REGIME_LONG_HORIZON, Piece, SetAnalysis
from betvdesign.report.model import FigureBlock
from betvdesign.spec.models import amplitude_at
from betvdesign.spec.units import ureg
from betvdesign.studies.regime import LONG_PERIOD

EXACT = "exact event-driven impact model (closed-form phases, MODEL.md)"


#: Resolution of the figures' PNG in the PDF report [dots per inch].
PDF_DPI = 150.0


def _render(
    key: str, draw: Callable[[Any], None], *, size=(6.4, 3.4), **grid: Any
) -> tuple[str, str]:
    """One figure drawn once, exported twice: (inline SVG for the HTML, PNG data URI for
    the PDF, where WeasyPrint would spend seconds drawing the SVG)."""
    with plots.figure_style():
        fig, axes = plots.new_figure(*size, **grid)
        draw(axes)
        svg, png = plots.figure_svg_png(fig, key, dpi=PDF_DPI)
    return svg, "data:image/png;base64," + base64.b64encode(png).decode("ascii")


_Task = tuple[str, Callable[[Any], None], dict[str, Any]]
_M = TypeVar("_M")

#: Per thread, ``tasks``: the figures recorded while a :func:`batch` is open (absent or
#: None: each figure is drawn at once).
_LOCAL = threading.local()
#: The batch being drawn, read by the forked workers (:func:`_draw_task`).
_DRAWING: list[_Task] = []


def _draw_task(i: int) -> tuple[str, str]:
    """Worker: draw figure ``i`` of the batch (inherited from the parent by fork)."""
    key, draw, layout = _DRAWING[i]
    return _render(key, draw, **layout)


#: Fewest usable processors for drawing in parallel by default: on 2 processors shared
#: with other work, 2 forked workers drew push_demo's 10 figures slower than one
#: process (4.4-5.9 s against 3.7-4.1 s, load 4-5; benchmarks/README.md).
MIN_PARALLEL_CPUS = 4
#: Most worker processes by default (10-16 figures per report).
MAX_WORKERS = 8


def _workers(n_tasks: int, workers: int | None) -> int:
    """Processes to draw ``n_tasks`` figures with: ``workers``, else one per usable
    processor (at most :data:`MAX_WORKERS`) where there are at least
    :data:`MIN_PARALLEL_CPUS`; 1 (in this process) where fork is not available, in a
    daemonic worker process (which may have no children: the explorer's jobs) or off the
    main thread (forking a process whose other threads hold locks)."""
    if (
        "fork" not in multiprocessing.get_all_start_methods()
        or multiprocessing.current_process().daemon
        or threading.current_thread() is not threading.main_thread()
    ):
        return 1
    if workers is None:
        try:
            cpus = len(os.sched_getaffinity(0))
        except AttributeError:  # pragma: no cover - no sched_getaffinity (macOS)
            cpus = os.cpu_count() or 1
        workers = min(cpus, MAX_WORKERS) if cpus >= MIN_PARALLEL_CPUS else 1
    return max(1, min(workers, n_tasks))


def _draw_all(tasks: list[_Task], workers: int | None) -> list[tuple[str, str]]:
    """(SVG, PNG data URI) of every task, in order: in forked processes when more than
    one is used (the figures' data and drawing functions are inherited, nothing is
    pickled but the results; matplotlib draws the same bytes in any process)."""
    global _DRAWING
    n = _workers(len(tasks), workers)
    if n == 1:
        return [_render(key, draw, **layout) for key, draw, layout in tasks]
    _DRAWING = tasks
    try:
        with multiprocessing.get_context("fork").Pool(n) as pool:
            return pool.map(_draw_task, range(len(tasks)), chunksize=1)
    finally:
        _DRAWING = []


def _fill(model: _M, drawn: dict[str, tuple[str, str]]) -> _M:
    """``model`` (a report model: dataclasses, tuples) with every recorded figure block
    given its drawing."""
    if isinstance(model, FigureBlock):
        if model.key in drawn and model.unavailable is None and model.svg is None:
            svg, png = drawn[model.key]
            return dataclasses.replace(model, svg=svg, png=png)  # type: ignore[return-value]
        return model
    if isinstance(model, tuple):
        return type(model)(_fill(m, drawn) for m in model)  # type: ignore[return-value]
    if dataclasses.is_dataclass(model) and not isinstance(model, type):
        changes = {}
        for f in dataclasses.fields(model):
            old = getattr(model, f.name)
            new = _fill(old, drawn)
            if new is not old:
                changes[f.name] = new
        return dataclasses.replace(model, **changes) if changes else model
    return model


@contextlib.contextmanager
def batch(workers: int | None = None) -> Iterator[Callable[[_M], _M]]:
    """Record the figures of :func:`figure_block` instead of drawing each at once; the
    function yielded draws them all, in parallel processes where the system forks
    (``workers``: how many; None: one per usable processor, at most one per figure),
    and returns the report model it is given with every figure filled in.

    The figures are byte-identical to those drawn one by one (each is drawn from the
    same data by the same code, in a process forked from this one).
    """
    outer = getattr(_LOCAL, "tasks", None)
    tasks: list[_Task] = []
    _LOCAL.tasks = tasks

    def fill(model: _M) -> _M:
        keys = [key for key, _, _ in tasks]
        if len(set(keys)) != len(keys):  # pragma: no cover - keys are unique in a page
            raise ValueError("figure keys must be unique within a batch")
        drawn = dict(zip(keys, _draw_all(tasks, workers), strict=True))
        tasks.clear()
        return _fill(model, drawn)

    try:
        yield fill
    finally:
        _LOCAL.tasks = outer


def _scale(max_abs: float, unit: str, per_unit: float, what: str) -> tuple[float, str]:
    """(factor, axis label) turning dimensionless data into ``what [prefixed unit]``:
    ``per_unit`` is the SI value of one dimensionless unit, ``max_abs`` the largest SI
    value shown (it picks the prefix)."""
    factor, label = scale_for(max_abs, unit)
    return per_unit * factor, f"{what}  [{label}]"


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


def figure_block(
    key: str,
    title: str,
    caption: str,
    model: str,
    rung: tuple[str, str],
    piece: Piece[Any],
    draw: Callable[[Any], None],
    **layout: Any,
) -> FigureBlock:
    """A report figure, or the reason it is not drawn.

    Parameters
    ----------
    key
        Figure key (prefix of the SVG's ids).
    title, caption, model
        Title, caption and the model statement shown with the figure.
    rung
        (fidelity rung, why that rung) of the figure.
    piece
        The computation the figure draws; when it failed its reason replaces the figure.
    draw
        Draws the figure on the axes it is given.
    **layout
        Figure size and subplot grid (``size=(w, h)`` [inches], ``nrows``, ``ncols``).

    Returns
    -------
    FigureBlock
        The drawn figure (inline SVG) or the unavailable block.
    """
    if not piece.ok:
        return FigureBlock(
            key, title, caption, model, unavailable=piece.reason, rung=rung[0], rung_reason=rung[1]
        )
    pending = getattr(_LOCAL, "tasks", None)
    if pending is not None:  # drawn later with the whole batch (:func:`batch`)
        pending.append((key, draw, layout))
        return FigureBlock(key, title, caption, model, rung=rung[0], rung_reason=rung[1])
    svg, png = _render(key, draw, **layout)
    return FigureBlock(
        key, title, caption, model, svg=svg, png=png, rung=rung[0], rung_reason=rung[1]
    )


def pushpull(key: str, sd: SetDerivation) -> FigureBlock:
    p = sd.params
    f_act = sd.scales.f_act_hz
    f_v = f_act / p.varpi
    f_h = f_v / math.sqrt(p.alpha)
    caption = (
        f"The device (f_act = {format_si(f_act, 'Hz')}, f_h = f_v/√α = {format_si(f_h, 'Hz')}) "
        f"against the λ = 1 boundary of the fit for its f_v = {format_si(f_v, 'Hz')}, "
        f"κ = {p.kappa:.3g}, β = {p.beta:.3g}: f_h² = f_act² + κ·c·f_v² with "
        "c = (1/β − β)/(22(κ+1)) (MODEL.md, eq. 9 rewritten in frequencies). "
        f"λ = {p.lam:.4g} predicts {p.lambda_mode} mode. Below the curve λ < 1 (push), "
        "above λ > 1 (pull); hatched: outside the vertical design window 0.5 ≤ ϖ < 2 (top "
        "axis: ϖ = f_act/f_v); dash-dotted: the sub-resonances α·ϖ² = 1/n², the lines "
        "f_h = n·f_act (n = 1 to 4), where the exact mode can flip against the fit."
    )

    def draw(ax: Any) -> None:
        plots.pushpull_map_frequencies(
            f_v_hz=f_v, kappa=p.kappa, beta=p.beta, points=[(sd.name, f_act, f_h)], ax=ax
        )

    return figure_block(
        key,
        "Push/pull map",
        caption,
        "λ fit of Shin et al. (2004), no simulation",
        ("lambda", "the figure places the device against the λ fit's own boundary"),
        Piece(value=True),
        draw,
        size=(6.4, 4.0),  # the legend below the axes
    )


def regime(key: str, sd: SetDerivation, an: SetAnalysis) -> FigureBlock:
    p = sd.params
    data = an.regime.value
    n = len(data.varpi) if data is not None else 0
    f_v = sd.scales.f_act_hz / p.varpi
    k, unit = scale_for(VARPI_WINDOW[1] * f_v, "Hz")
    caption = (
        f"Impact period (actuation cycles per period of the head's vertical motion), mean hits "
        f"per cycle (impulsive included; above 1: multi-impact) and share of the cycle in "
        f"contact, against the actuation frequency f_act for this head (f_v = "
        f"{format_si(f_v, 'Hz')}; top axis ϖ = f_act/f_v; {n} values, from rest; crosses: no "
        f"period of at most {LONG_PERIOD} cycles found within {REGIME_LONG_HORIZON} cycles "
        "(aperiodic or a long period); impulsive-only hits that repeat "
        f"every k cycles have period k); design window 0.5 ≤ ϖ < 2 shaded, the device "
        f"(f_act = {format_si(sd.scales.f_act_hz, 'Hz')}, ϖ = {p.varpi:.3g}) dashed."
    )
    scale = (f_v * k, f"actuation frequency f_act  [{unit}]")

    def draw(axes: Any) -> None:
        plots.impact_period_strip(
            data.varpi,
            data.period_cycles,
            device_varpi=p.varpi,
            hits_per_cycle=data.hits_per_cycle,
            varpi_scale=scale,
            ax=axes[0],
        )
        plots.contact_fraction_strip(
            data.varpi, data.contact_fraction, device_varpi=p.varpi, varpi_scale=scale, ax=axes[1]
        )

    model = "vertical-only exact model (the head's vertical motion does not depend on the slider)"
    return figure_block(
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
        f"Head gap and its rate of change at f_act = {format_si(sd.scales.f_act_hz, 'Hz')} "
        f"(ϖ = {sd.params.varpi:.3g}) over the first {cycles} actuation cycles from rest "
        "(light: first half, dark: second half); gap 0 is contact. Secondary axes: the "
        "dimensionless ξ = gap/(u sinθ) and ξ' = dξ/dτ."
    )

    def draw(ax: Any) -> None:
        sc = sd.scales
        gap_m = sc.u_m * math.sin(sc.theta_rad)  # ξ = gap/(u sinθ), MODEL.md
        xi, dxi = data.states[:, 0], data.states[:, 1]
        plots.vertical_phase_portrait(
            xi,
            dxi,
            steady_from=len(data.t_cycles) // 2,
            gap_scale=_scale(float(np.abs(xi).max()) * gap_m, "m", gap_m, "head gap"),
            rate_scale=_scale(
                float(np.abs(dxi).max()) * gap_m / sc.time_s,
                "m/s",
                gap_m / sc.time_s,
                "gap rate",
            ),
            ax=ax,
        )

    return figure_block(
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
        f"(a) Slider velocity over the {first} cycles from rest and its mean over each cycle "
        f"of the whole {run} (log time axis), settling toward the periodic state (dashed). "
        "(b) The periodic orbit: slider against head tangential velocity; colour marks no "
        "contact, slip, reverse slip and stick. Secondary axes: cycles and the "
        "dimensionless velocities s', ζ' (velocity scale u·cosθ/t_s = "
        f"{format_si(sd.scales.length_m / sd.scales.time_s, 'm/s')})."
    )
    if per is not None:
        v = abs(sd.scales.speed_m_s(float(per.delta_s)))
        way = MODE_DIRECTION.get(str(per.mode), "")
        caption += (
            f" Periodic mean speed {format_si(v, 'm/s')} ({per.mode} mode"
            f"{': ' + way if way else ''}; Δs = {float(per.delta_s):.4g} per cycle)."
        )
        if tr is not None and len(tr.delta_s) and float(per.delta_s) != 0.0:
            k = int(per.period_cycles or 1)
            last = float(np.mean(tr.delta_s[-k:]))
            gap = abs(last / float(per.delta_s) - 1.0)
            caption += (
                f" After {len(tr.delta_s)} cycles from rest the mean Δsₘ of the last {k} "
                f"cycle(s) differs from it by a relative {gap:.2g}."
            )

    def draw(axes: Any) -> None:
        sc = sd.scales
        mean = tr.delta_s * p.varpi / (2 * math.pi)
        per_cycle_s = 1.0 / sc.f_act_hz
        v_unit = sc.length_m / sc.time_s  # [m/s] per unit s' (s = x/ℓ, τ = t/t_s)
        vmax = float(max(np.abs(tr.states[:, 5]).max(), np.abs(orb.ds).max(), 1e-300))
        velocity = _scale(vmax * v_unit, "m/s", v_unit, "slider velocity")
        plots.slider_velocity(
            tr.t_cycles,
            tr.states[:, 5],
            cycle_mean=(np.arange(len(mean)), mean),
            periodic_mean=float(per.delta_s) * p.varpi / (2 * math.pi),
            logx=True,
            time_scale=_scale(len(mean) * per_cycle_s, "s", per_cycle_s, "time from rest"),
            velocity_scale=velocity,
            ax=axes[0],
        )
        k, label = velocity
        plots.orbit_plane(
            orb.dzeta,
            orb.ds,
            orb.phases,
            velocity_scale=(k, label.split("[")[1][:-1]),
            ax=axes[1],
        )

    return figure_block(
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
        size=(7.0, 3.8),  # the legends below the panels
        ncols=2,
    )


def displacement(key: str, sd: SetDerivation, an: SetAnalysis) -> FigureBlock:
    tr = an.transient.value
    sc = sd.scales
    travel_um = sd.travel_range_m * 1e6
    caption = (
        f"Slider position x = s·u·cosθ (ℓ = {format_si(sc.length_m, 'm')}) in the device's x "
        f"direction against time t = τ·sqrt(m/k_v), sampled once per actuation cycle "
        f"(f_act = {format_si(sc.f_act_hz, 'Hz')}), until the slider reaches the end of its "
        f"{format_si(sd.travel_range_m, 'm')} travel range (the end stop)."
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

    block = figure_block(
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
    if sd.stroke is not None:
        return _speed_voltage_drawn(key, sd, an, tol)
    if per.ok and cal is None:
        piece = Piece(
            reason="the device gives the amplitude u directly, not a calibration u(V); "
            "a speed-voltage curve needs one (linear, quadratic or measured)"
        )
    v0 = aset.drive.voltage.to("V").magnitude if aset.drive.voltage is not None else None
    law = cal.law if cal is not None else "none"
    mode = str(per.value.mode) if per.ok else ""
    way = f" ({mode} mode: {MODE_DIRECTION[mode]})" if mode in MODE_DIRECTION else ""
    caption = (
        f"Mean slider speed |Δs|·u(V)·cosθ·f_act{way} with u(V) from the {law} amplitude "
        "calibration; operating point marked."
    )
    if sc.has_rolloff:
        caption += (
            f" The calibrated stroke is scaled by the thermal roll-off H(f_act)/H(f_cal) = "
            f"{sc.rolloff_factor:.3g} (f_c = {format_si(sc.cutoff_hz, 'Hz')})."
        )

    def draw(ax: Any) -> None:
        if law == "measured":
            lo, hi = (q.to("V").magnitude for q in cal.voltage_range)
        else:
            lo, hi = 0.5 * v0, 1.5 * v0
        volts = np.linspace(lo, hi, points)
        u_m = amplitude_at(aset, ureg.Quantity(volts, "V")).to("m").magnitude
        u_m = np.asarray(u_m) * sc.rolloff_factor  # H(f_act)/H(f_cal): 1 without a cut-off
        ds = abs(float(per.value.delta_s))  # a speed is a magnitude; the mode says the way
        speed = ds * np.asarray(u_m) * math.cos(sc.theta_rad) * sc.f_act_hz  # [m/s]
        plots.speed_vs_voltage(
            volts, speed, operating_v=v0, operating_speed_m_s=sc.speed_m_s(ds), mode=mode, ax=ax
        )

    model = (
        "one periodic orbit of the exact model; Δs does not depend on u, so speed scales with u(V)"
    )
    rung = ladder(sd.params, "delta_s", "periodic", tol=tol)
    return figure_block(key, "Mean speed against drive voltage", caption, model, rung, piece, draw)


def _speed_voltage_drawn(key: str, sd: SetDerivation, an: SetAnalysis, tol: float) -> FigureBlock:
    """The speed-voltage figure of a set whose stroke is predicted from the drawing.

    Parameters
    ----------
    key : str
        Figure key.
    sd : SetDerivation
        The set (its predicted stroke).
    an : SetAnalysis
        Its periodic orbit and its u(V) (:mod:`betvdesign.report.thermal`).
    tol : float
        The periodic orbit's residual [-] (the ladder's reason).

    Returns
    -------
    FigureBlock
        Δs·u(V)·cosθ·f_act with u(V) the stroke at the drive, to the melting voltage.
    """
    sc = sd.scales
    per, sweep = an.periodic, an.stroke
    piece: Piece[Any] = per if not per.ok or sweep.ok else sweep
    caption = (
        "Mean slider speed Δs·u(V)·cosθ·f_act along the impact direction (negative: against "
        "it) with u(V) the stroke at the drive predicted from the drawing (the electrothermal "
        "model, nothing fitted; the figure of the predicted stroke against voltage), up to "
        "the voltage where the actuator's peak temperature reaches the melting point; "
        "operating point marked."
    )

    def draw(ax: Any) -> None:
        s = sweep.value
        ds = float(per.value.delta_s)
        speed = ds * s.stroke_m * math.cos(sc.theta_rad) * sc.f_act_hz  # [m/s]
        plots.speed_vs_voltage(
            s.volts, speed, operating_v=s.device_v, operating_speed_m_s=sc.speed_m_s(ds), ax=ax
        )

    model = (
        "one periodic orbit of the exact model; Δs does not depend on u, so speed scales with u(V)"
    )
    rung = ladder(sd.params, "delta_s", "periodic", tol=tol)
    return figure_block(key, "Mean speed against drive voltage", caption, model, rung, piece, draw)


def robustness(key: str, sd: SetDerivation, an: SetAnalysis) -> FigureBlock:
    data = an.robustness.value
    toward = "+x" if sd.actuator_set.travel_sign > 0 else "−x"
    other = "pull" if sd.intended_mode == "push" else "push"
    caption = (
        "Mean slider speed (a magnitude; periodic orbit of the exact model) when one "
        "designer field changes and every other stays as specified. The intended direction "
        f"is the {sd.intended_mode} mode's, toward {toward}; squares in the {other} colour: "
        f"the slider runs the wrong way ({other} mode). A line dipping to zero near 0 % "
        "means a fabrication or drive error of that size flips the mode. Ringed points: "
        "the λ fit predicts the other mode there."
    )
    if data is not None:
        nominal = "; ".join(
            f"{f} = {next(p.nominal for p in data.points if p.field == f)}" for f in data.fields
        )
        caption += f" Specified values: {nominal}. {data.n_orbits} periodic orbits."
        if data.flips:
            caption += (
                " The exact mode flips (bisected to 0.1 %; bars on zero): "
                + "; ".join(
                    f"{fl.field} {fl.below} → {fl.above} at {100 * fl.at:+.1f} %"
                    for fl in data.flips
                )
                + "."
            )
        else:
            caption += " The exact mode holds over the whole sweep."
        if data.failures:
            caption += " No periodic orbit or invalid value at: " + "; ".join(data.failures) + "."
    sign = 1.0 if sd.intended_mode == "push" else -1.0  # Δs > 0 is push

    def draw(ax: Any) -> None:
        series = []
        for f in data.fields:
            pts = [p for p in data.points if p.field == f]
            speeds = [None if p.speed_m_s is None else sign * p.speed_m_s for p in pts]
            misses = [
                p.speed_m_s is not None and p.lam is not None and (p.lam < 1.0) != (p.speed_m_s > 0)
                for p in pts
            ]
            series.append((f, [100.0 * p.change for p in pts], speeds, misses))
        flips = [(fl.field, 100.0 * fl.at) for fl in data.flips]
        plots.speed_vs_field_change(series, flips=flips, wrong_mode=other, ax=ax)

    model = f"periodic orbits of the {EXACT}, one per changed device (spec -> nondim -> orbit)"
    rung = (
        "periodic",
        "the sweep shows where the mode flips, so every point needs the exact periodic orbit "
        "(λ cannot check itself)",
    )
    return figure_block(
        key,
        "Robustness: speed when one designer field changes",
        caption,
        model,
        rung,
        an.robustness,
        draw,
        size=(6.4, 4.6),  # the legend below the axes
    )


def set_figures(
    prefix: str,
    sd: SetDerivation,
    an: SetAnalysis,
    voltage_points: int,
    tol: float = 1e-10,
    *,
    full: bool = True,
) -> list[FigureBlock]:
    """The figures of one actuator set, in reading order.

    Parameters
    ----------
    prefix : str
        Prefix of the figures' keys ("s1").
    sd : SetDerivation
        The set.
    an : SetAnalysis
        Its computations.
    voltage_points : int
        Voltages of the speed-voltage figure.
    tol : float
        The periodic orbit's residual [-], the accuracy the speed figure's Δs is asked for.
    full : bool
        All seven figures; False: without the model's diagnostics
        (:data:`betvdesign.report.analysis.FULL_ONLY`), the other figures unchanged.

    Returns
    -------
    list of FigureBlock
        Seven figures, or three without the diagnostics.
    """
    diagnostics = (
        [
            pushpull(f"{prefix}-pushpull", sd),
            regime(f"{prefix}-regime", sd, an),
            vertical_portrait(f"{prefix}-vphase", sd, an),
            settling(f"{prefix}-settling", sd, an),
        ]
        if full
        else []
    )
    return [
        *diagnostics,
        displacement(f"{prefix}-displacement", sd, an),
        speed_voltage(f"{prefix}-speed", sd, an, voltage_points, tol),
        robustness(f"{prefix}-robustness", sd, an),
    ]
