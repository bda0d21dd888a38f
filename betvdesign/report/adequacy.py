"""The report section "Model adequacy": is the paper's idealised model enough here?

Data: :func:`betvdesign.checks.adequacy.assess` (exact periodic orbits without and with
head damping and restitution, Q and e scanned, mode flips bisected), computed once per
device (the same result feeds the design check's rule ``model-adequacy``). Per distinct
actuator set the section states the verdict, the idealised and the richer answer in
physical units and where the mode flips, with one figure of mode and speed against Q and
against e around the device, and, for a device with a thermal cut-off, the
speed-against-frequency figure of :mod:`betvdesign.report.frequency` (with and without
the roll-off; built there, placed here).
"""

from __future__ import annotations

import math
from typing import Any

from betvdesign import plots
from betvdesign.checks.adequacy import (
    DEFAULT_QUALITY,
    DEFAULT_RESTITUTION,
    LIKELY_QUALITY,
    LIKELY_RESTITUTION,
    QUALITY_RANGE,
    RESTITUTION_RANGE,
    SPEED_RTOL,
    DeviceAdequacy,
    SetAdequacy,
    assess,
)
from betvdesign.nondim.record import DeviceDerivation, SetDerivation
from betvdesign.output.siformat import format_dimensionless as fmt_x
from betvdesign.output.siformat import format_si, scale_for
from betvdesign.report.analysis import Piece, attempt
from betvdesign.report.figures import figure_block, ladder
from betvdesign.report.model import AdequacyBlock, FigureBlock, KeyValue

_VERDICT = {
    "adequate": "The idealised model is adequate: the same mode with and without damping "
    "and restitution and over their whole plausible ranges, speed within {rtol:.0%}.",
    "speed-differs": "The idealised model is adequate for the mode, not for the speed "
    "(more than {rtol:.0%} apart): quote the richer model's speed.",
    "flips-beyond": "The idealised model is adequate for the mode within the likely Q and e "
    "(Q {q0:g}–{q1:g}, e ≤ {e1:g}); the mode changes only beyond them (see the flips below), speed "
    "within {rtol:.0%}.",
    "mode-flips": "The idealised model is not adequate: the mode changes with damping or "
    "restitution within their likely values (Q {q0:g}–{q1:g}, e ≤ {e1:g}) or at the device's.",
    "ideal-fails": "The idealised model gives no periodic orbit here; the richer model's "
    "finite answer is the one to use.",
    "failed": "Neither model gives a periodic orbit: adequacy cannot be judged.",
}


def compute(der: DeviceDerivation) -> Piece[DeviceAdequacy]:
    """The adequacy of every set, or why it is missing (solver unavailable)."""
    return attempt(lambda: assess(der))


def section(
    key: str,
    sd: SetDerivation,
    piece: Piece[DeviceAdequacy],
    extra: tuple[FigureBlock, ...] = (),
    tol: float = 1e-10,
) -> AdequacyBlock:
    """The section of set ``sd`` (``extra``: further figures placed here, the roll-off)."""
    a = _of_set(piece, sd.name)
    sets_piece: Piece[SetAdequacy] = Piece(a, piece.reason, piece.elapsed_s)
    fig = figure(f"{key}-adequacy", sd, sets_piece, tol)
    if a is None:
        return AdequacyBlock("unavailable", f"Not assessed: {piece.reason}", (), (fig, *extra))
    verdict = _VERDICT[a.status].format(
        rtol=SPEED_RTOL, q0=LIKELY_QUALITY[0], q1=LIKELY_QUALITY[1], e1=LIKELY_RESTITUTION[1]
    )
    return AdequacyBlock(a.status, verdict, rows(a), (fig, *extra))


def _of_set(piece: Piece[DeviceAdequacy], name: str) -> SetAdequacy | None:
    if not piece.ok:
        return None
    return next((s for s in piece.value.sets if s.name == name), None)


def rows(a: SetAdequacy) -> tuple[KeyValue, ...]:
    """Labelled lines: both answers, the terms and their source, the flips."""
    src = (
        f"the plausible defaults (the device gives none): Q = {fmt_x(DEFAULT_QUALITY)} normal "
        f"and tangential, e = {fmt_x(DEFAULT_RESTITUTION)}"
        if a.source == "default"
        else "the device file's"
    )
    change = a.speed_change
    out = [
        KeyValue("Idealised model (undamped, plastic impacts)", _answer(a.ideal)),
        KeyValue(f"With {a.richer.terms}", _answer(a.richer)),
        KeyValue("Damping and restitution", src),
    ]
    if change is not None and change > -1.0:
        out.append(KeyValue("Speed change", f"{change:+.1%} (threshold ±{SPEED_RTOL:.0%})"))
    for label, flip, scan in (
        ("Mode flip in Q", a.flip_quality, a.quality_scan),
        ("Mode flip in e", a.flip_restitution, a.restitution_scan),
    ):
        rng = (
            f"Q {fmt_x(QUALITY_RANGE[0])}–{fmt_x(QUALITY_RANGE[1])}"
            if scan.axis == "quality"
            else f"e {fmt_x(RESTITUTION_RANGE[0])}–{fmt_x(RESTITUTION_RANGE[1])}"
        )
        others = [c for c in scan.crossings if c is not flip]
        text = (
            f"at {flip.text}, {scan.fixed}"
            if flip is not None
            else f"none from the idealised end over {rng} ({scan.fixed})"
        )
        if others:
            text += "; further changes at " + ", ".join(c.text for c in others)
        out.append(KeyValue(label, text))
    out.append(KeyValue("In full", a.message))
    return tuple(out)


def _answer(p: Any) -> str:
    if p.delta_s is None:
        return f"{p.answer}: {p.message}" if p.message else p.answer
    return f"{p.answer} (Δs = {p.delta_s:.4g} per cycle)"


def figure(key: str, sd: SetDerivation, piece: Piece[SetAdequacy], tol: float) -> FigureBlock:
    """Mode and mean speed against Q (left) and e (right) around the device."""
    a = piece.value
    caption = (
        "Mean slider speed (a magnitude; the colour gives the mode: push along the impacts, "
        "pull against them) of the exact periodic orbit against the head's quality factor "
        "Q (left; one Q for the normal and the tangential direction, log scale) and "
        "against the coefficient of restitution e "
        "(right); each point coloured by its mode (grey: none, the slider is not driven "
        "because no contact recurs; crosses: no periodic orbit). Dashed: the idealised "
        "model (Q = ∞, e = 0); star: the device; dotted: where the mode flips (bisected)."
    )
    if a is not None:
        caption += (
            f" Left: {len(a.quality_scan.points)} orbits with {a.quality_scan.fixed}; right: "
            f"{len(a.restitution_scan.points)} with {a.restitution_scan.fixed}"
            + (
                " (the plausible defaults: the device gives none)."
                if a.source == "default"
                else " (the device's values)."
            )
        )
        flips = [c.text for c in a.flips]
        caption += " Mode flips at " + "; ".join(flips) + "." if flips else " No change of mode."
        if sd.scales.has_rolloff:
            caption += (
                f" Speeds with the thermally rolled-off stroke at f_act "
                f"({sd.scales.rolloff_factor:.3g} × u_cal)."
            )
        elif sd.stroke is not None:
            caption += (
                f" Speeds with the stroke predicted from the drawing at f_act "
                f"(u = {format_si(sd.scales.u_m, 'm')}, {sd.stroke.gain:.3g} of u_static/2: "
                "the drawing's thermal roll-off)."
            )

    def draw(axes: Any) -> None:
        top = max(
            [
                abs(p.speed_m_s)
                for s in (a.quality_scan, a.restitution_scan)
                for p in s.points
                if p.speed_m_s is not None
            ]
            + [abs(a.ideal.speed_m_s or 0.0)]
        )
        scale = scale_for(top, "m/s")
        for ax, scan, x_dev, label, logx in (
            (axes[0], a.quality_scan, a.quality_normal, "quality factor Q  [-]", True),
            (axes[1], a.restitution_scan, a.richer.restitution, "restitution e  [-]", False),
        ):
            same_q = a.quality_normal == a.quality_tangential
            dev = (x_dev, a.richer.speed_m_s) if (scan.axis != "quality" or same_q) else None
            plots.mode_speed_scan(
                scan.values,
                [p.speed_m_s for p in scan.points],
                [p.mode for p in scan.points],
                xlabel=label,
                logx=logx,
                device=dev if dev and dev[1] is not None and math.isfinite(dev[0]) else None,
                ideal_m_s=a.ideal.speed_m_s,
                flips=[c.at for c in scan.crossings],
                speed_scale=scale,
                ax=ax,
            )

    model = (
        "exact periodic orbits of the damped impact model with restitution (MODEL.md, "
        "Beyond the paper's idealisation), one per point"
    )
    return figure_block(
        key,
        "Model adequacy: mode and speed against damping and restitution",
        caption,
        model,
        ladder(sd.params, "delta_s", "periodic", tol=tol),
        piece,
        draw,
        size=(7.0, 3.8),  # the legends below the panels
        ncols=2,
    )
