"""The report's first figure: the exact-mode map of the two designer fields that matter
most around the device, in the fields' own units, the device marked.

Which two: the drive frequency (the designer's knob at the bench; it alone moves ϖ),
and of the other fields of the robustness sweep (:mod:`betvdesign.report.variants`) the
one whose change flips the exact mode nearest to the device (the bisected flips of
:func:`betvdesign.report.variants.locate_flips`), else the one that changes the speed
most over the sweep's span. Each point of the map is the device with the two values,
derived like the device itself and solved to its exact periodic orbit
(:func:`betvdesign.studies.fieldsweep.field_map`, the same rows as ``betv sweep FILE
--vary A --vary B``); the λ = 1 curve of the paper's fit is drawn over it for
comparison only.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from betvdesign.model.domain import VARPI_WINDOW
from betvdesign.nondim.record import SetDerivation
from betvdesign.report.analysis import FieldSweep, Missing, Piece, ReportOptions
from betvdesign.report.figures import EXACT, figure_block
from betvdesign.report.model import FigureBlock
from betvdesign.report.variants import shown_fields
from betvdesign.spec.models import DeviceSpec
from betvdesign.studies.fieldsweep import FieldAxis, field_map

#: The field always on the map's first axis (when the device gives it).
FIRST_FIELD = "drive.frequency"
#: Relative range [-] of the map's second field around the device (± MAP_SPAN).
MAP_SPAN = 0.5
#: Top of the frequency axis relative to the window's upper edge ϖ < 2 (finite contact).
MAP_TOP = 0.98


@dataclass(frozen=True)
class ModeMap:
    """The map's rows (grid order, first axis slowest), its summary
    (:func:`betvdesign.studies.fieldsweep.summarise`) and why its second field was
    chosen."""

    rows: list[dict[str, Any]]
    summary: dict[str, Any]
    why: str


def choose_fields(
    spec: DeviceSpec, set_index: int, sweep: FieldSweep | None
) -> tuple[list[tuple[str, Any]], str]:
    """The two fields of the map with their values, and why the second was chosen.

    Parameters
    ----------
    spec : DeviceSpec
        The device.
    set_index : int
        Index of the actuator set.
    sweep : FieldSweep or None
        The set's robustness sweep with its flips (None: not computed).

    Returns
    -------
    tuple of (list of (str, value), str)
        ((field, value) × 2, the reason in words).
    """
    fields = shown_fields(spec, set_index)
    if len(fields) < 2:
        raise Missing("the device gives fewer than two designer fields that move the model")
    first = next((f for f in fields if f[0] == FIRST_FIELD), fields[0])
    others = [f for f in fields if f[0] != first[0]]
    flips = [fl for fl in (sweep.flips if sweep else ()) if fl.field != first[0]]
    if flips:
        near = min(flips, key=lambda fl: abs(fl.at))
        second = next(f for f in others if f[0] == near.field)
        why = (
            f"{near.field} is the field whose change flips the exact mode nearest to the "
            f"device ({near.below} → {near.above} at {100 * near.at:+.1f} %)"
        )
        return [first, second], why
    spans: dict[str, float] = {}
    if sweep is not None:
        for f, _ in others:
            v = [p.speed_m_s for p in sweep.points if p.field == f and p.speed_m_s is not None]
            spans[f] = (max(v) - min(v)) if v else 0.0
    second = max(others, key=lambda f: spans.get(f[0], 0.0))
    why = (
        f"no other field flips the mode within the robustness sweep; {second[0]} changes "
        "the speed most over it"
    )
    return [first, second], why


def axis(field: str, value: Any, lo: float, hi: float, points: int) -> FieldAxis:
    """The field's axis: ``points`` values from ``lo`` to ``hi`` times its value, in the
    unit the device file gives it."""
    return FieldAxis.scaled(field, value, np.linspace(lo, hi, max(points, 3)))


def factors(field: str, varpi: float, span: float) -> tuple[float, float]:
    """The range of the map along ``field`` as factors on its value: the drive frequency
    over the whole design window (ϖ ∝ f; widened to hold the device's ϖ), any other
    field over 1 ± ``span``."""
    if field == FIRST_FIELD:
        lo = min(VARPI_WINDOW[0], 0.9 * varpi)
        hi = max(MAP_TOP * VARPI_WINDOW[1], 1.1 * varpi)
        return lo / varpi, hi / varpi
    return 1.0 - span, 1.0 + span


def compute(
    spec: DeviceSpec,
    set_index: int,
    varpi: float,
    sweep: Piece[FieldSweep],
    opts: ReportOptions,
) -> ModeMap:
    """The map of set ``set_index`` (ϖ [-] the device's): :data:`ReportOptions.map_points`
    per axis, the ranges of :func:`factors` (the second field over ±
    :data:`MAP_SPAN`)."""
    chosen, why = choose_fields(spec, set_index, sweep.value)
    axes = [axis(f, v, *factors(f, varpi, MAP_SPAN), opts.map_points) for f, v in chosen]
    rows, summary = field_map(spec, axes, set_index, tol=opts.periodic_tol)
    return ModeMap(rows, summary, why)


def figure(key: str, sd: SetDerivation, piece: Piece[ModeMap]) -> FigureBlock:
    """The figure block (see the module docstring)."""
    caption = (
        "Exact mode of the periodic orbit (push, pull, stalled, not driven, unbounded, "
        "not converged) when two designer fields change together and every other stays "
        f"as specified (the drive frequency over the design window {VARPI_WINDOW[0]:g} ≤ ϖ "
        f"< {VARPI_WINDOW[1]:g}, the second field over ±{100 * MAP_SPAN:.0f} %); the star "
        f"is the device ({sd.intended_mode} intended). Dashed: "
        "where the paper's λ fit puts the push/pull boundary (λ = 1), for comparison only: "
        "the verdict reads the exact orbit. Dash-dotted: the sub-resonances α·ϖ² = 1/n² "
        "(f_act = f_h/n), where the exact mode's flips cluster; hatched: outside the design "
        "window; cross-hatched: an undamped head's tangential resonance |α·ϖ² − 1| < 0.1, "
        "where the idealised model is not the device."
    )
    if piece.ok:
        m = piece.value
        counts = ", ".join(f"{k} {v}" for k, v in m.summary["modes"].items())
        caption += f" Second field: {m.why}. {m.summary['points']} periodic orbits ({counts})."

    def draw(ax: Any) -> None:
        from betvdesign.plots.fieldsweep import mode_map

        mode_map(piece.value.rows, piece.value.summary, ax=ax)

    rung = (
        "periodic",
        "a map of where the mode flips needs the exact periodic orbit at every point (λ "
        "cannot check itself)",
    )
    return figure_block(
        key,
        "Where the mode holds: exact-mode map of the two fields that matter most",
        caption,
        f"periodic orbits of the {EXACT}, one per changed device (spec -> nondim -> orbit)",
        rung,
        piece,
        draw,
        size=(6.4, 4.2),
    )
