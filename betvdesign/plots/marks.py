"""What a speed sweep marks along its axis, drawn alike on every 1-D figure.

The design window 0.5 ≤ ϖ < 2 (the range outside it hatched), the sub-resonances
α·ϖ² = 1/n² (f_act = f_h/n: the contact force's n-th harmonic meets the head's tangential
resonance; mode flips cluster just below them) as dash-dotted lines labelled f_h/n, an
undamped head's tangential-resonance band |α·ϖ² − 1| < 0.1 (the idealised speed there
is not the device's: cross-hatched, its speeds grey) and a speed axis that stays readable
when resonance spikes would flatten the operating region (symmetric-logarithmic above
it). Used by ``betv sweep FILE`` (:mod:`betvdesign.plots.fieldsweep`) and the report's
speed-against-frequency figure (:func:`betvdesign.plots.sweeps.speed_vs_frequency`); the
2-D maps draw the same marks as contours.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from betvdesign.model.domain import TANGENTIAL_DETUNING

__all__ = [
    "OUTSIDE_HATCH",
    "OUTSIDE_LABEL",
    "RESONANCE_HATCH",
    "RESONANCE_LABEL",
    "SUBRES_COLOR",
    "SUBRES_LABEL",
    "complement",
    "mark_resonance",
    "mark_subresonances",
    "mark_window",
    "speed_scale",
]

#: Hatching of what lies outside the design window 0.5 ≤ ϖ < 2, and its legend text.
OUTSIDE_HATCH = "///"
OUTSIDE_LABEL = "outside the design window 0.5 ≤ ϖ < 2"
#: Colour of the sub-resonance lines α·ϖ² = 1/n² (f_act = f_h/n), and their legend text.
SUBRES_COLOR = "#404040"
SUBRES_LABEL = "sub-resonance α·ϖ² = 1/n² (f_act = f_h/n)"
#: Hatching of an undamped head's tangential resonance band, and its legend text.
RESONANCE_HATCH = "xx"
RESONANCE_LABEL = (
    f"undamped head at |α·ϖ² − 1| < {TANGENTIAL_DETUNING:g}: idealised speed not physical"
)
#: The speed axis turns symmetric-logarithmic when its largest speed exceeds this many
#: times the operating region's (the median of the speeds shown) [-].
SYMLOG_RATIO = 10.0
#: Least distance [share of the axis] between two sub-resonance labels (deep orders crowd).
LABEL_GAP = 0.05


def complement(lo: float, hi: float, parts: Sequence[Sequence[float]]) -> list[tuple[float, float]]:
    """The parts of [lo, hi] outside the sorted, disjoint intervals ``parts``."""
    out, at = [], float(lo)
    for a, b in parts:
        if a > at:
            out.append((at, float(a)))
        at = max(at, float(b))
    if at < hi:
        out.append((at, float(hi)))
    return out


def mark_window(ax: Any, lo: float, hi: float, inside: Sequence[Sequence[float]]) -> list[Any]:
    """Hatch the parts of the axis range [lo, hi] outside the design window (``inside``:
    the parts within it, in the axis's units); the legend handle, if any is hatched."""
    outside = complement(lo, hi, inside)
    for a, b in outside:
        ax.axvspan(a, b, facecolor="none", edgecolor="0.55", hatch=OUTSIDE_HATCH, lw=0)
    if not outside:
        return []
    return [Patch(facecolor="none", edgecolor="0.55", hatch=OUTSIDE_HATCH, label=OUTSIDE_LABEL)]


def mark_resonance(ax: Any, parts: Sequence[Sequence[float]], x: np.ndarray) -> tuple[Any, Any]:
    """Cross-hatch an undamped head's tangential-resonance band(s) ``parts``.

    Returns
    -------
    tuple
        (which of the points ``x`` lie in a band: to draw grey and leave out of the speed
        axis, the legend handles).
    """
    grey = np.zeros(len(x), dtype=bool)
    for a, b in parts:
        ax.axvspan(a, b, facecolor="0.92", edgecolor="0.45", hatch=RESONANCE_HATCH, lw=0)
        grey |= (x >= a) & (x <= b)
    if not len(parts):
        return grey, []
    handle = Patch(facecolor="0.92", edgecolor="0.45", hatch=RESONANCE_HATCH)
    handle.set_label(RESONANCE_LABEL + " (grey)")
    return grey, [handle]


def mark_subresonances(ax: Any, at: Sequence[tuple[int, float]], span: float) -> list[Any]:
    """Dash-dotted lines at the sub-resonances ``at`` ((n, position) in the axis's
    units), labelled f_h/n at the top unless a higher one is labelled within
    :data:`LABEL_GAP` of the axis ``span``; the legend handle, if any is drawn."""
    labelled = -np.inf
    for n, x in sorted(at, key=lambda t: -t[1]):
        ax.axvline(x, color=SUBRES_COLOR, lw=0.7, ls="-.")
        if abs(labelled - x) < LABEL_GAP * (span or 1.0):
            continue  # the deeper orders crowd toward low frequency: lines only
        labelled = x
        ax.annotate(
            "f_h" if n == 1 else f"f_h/{n}",
            (x, 1.0),
            xycoords=("data", "axes fraction"),
            xytext=(2, -2),
            textcoords="offset points",
            ha="left",
            va="top",
            fontsize=6.5,
            color=SUBRES_COLOR,
        )
    if not at:
        return []
    return [Line2D([], [], color=SUBRES_COLOR, lw=0.7, ls="-.", label=SUBRES_LABEL)]


def speed_scale(ax: Any, v: np.ndarray) -> None:
    """A speed axis from 0 for the magnitudes ``v`` (nan: not shown).

    Linear, or symmetric-logarithmic (linear up to twice the median) when the largest
    speed is more than :data:`SYMLOG_RATIO` times the median: a few resonance spikes then
    no longer flatten the speeds of the operating region.
    """
    known = np.asarray(v, float)
    known = known[np.isfinite(known)]
    if known.size == 0:
        return
    top, median = float(known.max()), float(np.median(known))
    if median > 0.0 and top > SYMLOG_RATIO * median:
        ax.set_yscale("symlog", linthresh=2.0 * median, linscale=2.0)
        ax.set_ylim(0.0, top * 1.5)
    else:
        ax.set_ylim(0.0, top * 1.08 if top > 0 else 1.0)
