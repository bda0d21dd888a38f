"""The design window's rules: ``frequency-window`` and ``window-margin``.

One concept: where ϖ = f_act/f_v lies against the window 0.5 ≤ ϖ < 2 (MODEL.md, "What
the model shows: Vertical motion"), read by the one comparison
(:func:`betvdesign.model.domain.window_position`: each edge to round-off, the lower one
inside, the upper one outside), what the exact vertical motion does there (quoted, and
never contradicted: a damped head's multi-hit and impulsive ranges move), and whether
the window survives the fabrication spread of f_v (±:data:`WINDOW_MARGIN`, the same
spread as the mode's margin corners).

References
----------
.. [1] Shin, Pai, Lin, Hui and Tien, J. Appl. Phys. 96, 7603 (2004),
   doi:10.1063/1.1809773 (the window 0.5 ≤ ϖ < 2).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from betvdesign.checks.rule import SEARCH_HINT, RuleResult
from betvdesign.model.domain import (
    ROUND_OFF_SCALE,
    VARPI_WINDOW,
    WINDOW_EDGE_RTOL,
    in_window,
    window_position,
)
from betvdesign.nondim.record import SetDerivation
from betvdesign.output.siformat import format_si

if TYPE_CHECKING:
    from betvdesign.dynamics import VerticalResult

__all__ = [
    "SRC_MARGIN_WINDOW",
    "SRC_WINDOW",
    "WINDOW_MARGIN",
    "format_varpi",
    "frequency_window",
    "window_margin",
]

SRC_WINDOW = "MODEL.md, What the model shows: Vertical motion (Shin et al. 2004)"
SRC_MARGIN_WINDOW = (
    "MODEL.md design window 0.5 ≤ ϖ < 2 at ϖ·(1 ± 5 %) (fabrication spread of f_v, the "
    "same spread as the mode's margin corners)"
)
#: The relative spread of ϖ = f_act/f_v the window must survive [-]: the ±5 % of the
#: mode's margin corners (:data:`betvdesign.checks.rules.MARGIN_CORNERS` are built from
#: it).
WINDOW_MARGIN = 0.05


def _hz(f: float) -> str:
    return format_si(f, "Hz")


def _drive_range(s: SetDerivation, lo_varpi: float, hi_varpi: float) -> str:
    """Drive frequencies giving lo ≤ ϖ < hi (ϖ = f_act/f_v; AC doubling applied)."""
    f_v = s.scales.f_act_hz / s.params.varpi
    k = 2.0 if s.actuator_set.drive.doubled else 1.0
    note = " (AC drive: f_act = 2·f_drive)" if k == 2.0 else ""
    return f"{_hz(lo_varpi * f_v / k)}–{_hz(hi_varpi * f_v / k)}{note}"


def frequency_window(s: SetDerivation, vertical: VerticalResult | None) -> RuleResult:
    """The rule ``frequency-window``: 0.5 ≤ ϖ < 2.

    The rule ``frequency-window``: 0.5 ≤ ϖ < 2, read by the one comparison
    (:func:`~betvdesign.model.domain.window_position`: the lower edge inside, the upper
    edge outside, each to :data:`~betvdesign.model.domain.WINDOW_EDGE_RTOL`).
    """
    v = s.params.varpi
    lo, hi = VARPI_WINDOW
    f_v = s.scales.f_act_hz / v
    pos = window_position(v)
    fix = ""
    w = format_varpi(v)
    where = {
        "below": "below the window",
        "lower-edge": "at the window's lower edge (inside)",
        "inside": "inside the window",
        "upper-edge": "at the window's upper edge (outside)",
        "above": "above the window",
        "far-above": "far above the window",
    }[pos]
    paper = {  # what the paper's model does there (MODEL.md, "Vertical motion")
        "below": "the head hits several times per cycle",
        "lower-edge": "one hit per cycle, finite contact",
        "inside": "one hit per cycle, finite contact",
        "upper-edge": "contact vanishes there (impulsive hits only from ϖ = 2 on), the "
        "slider is not driven",
        "above": "impulsive hits, the slider is not driven",
        "far-above": "period doubling or aperiodic hits",
    }[pos]
    if vertical is not None and vertical.success:  # e.g. a damped head: the ranges move
        if pos == "below" and vertical.hits_per_cycle == 1:
            paper = (
                "the paper's model hits several times per cycle there; this head's exact "
                "vertical motion still hits once"
            )
        elif pos in ("upper-edge", "above") and vertical.contact_fraction > ROUND_OFF_SCALE:
            paper = (
                "the paper's model has impulsive hits only there; this head's exact "
                "vertical motion still has contact (outside the window the model's "
                "design rules do not hold)"
            )
    msg = f"ϖ = {w} {where}: {paper}"
    ok = in_window(v)
    if not ok:
        fix = (
            f"set drive.frequency within {_drive_range(s, lo, hi)}, or move the head's "
            f"vertical resonance (now {_hz(f_v)}) to {_hz(s.scales.f_act_hz / hi)}–"
            f"{_hz(s.scales.f_act_hz / lo)}; {SEARCH_HINT}"
        )
    if vertical is not None and vertical.success:
        msg += (
            f" [exact vertical motion: {vertical.regime}, {vertical.hits_per_cycle:g} hit(s) "
            f"per cycle ({vertical.impulsive_per_cycle:g} impulsive), in contact "
            f"{_share(vertical.contact_fraction)} of the time]"
        )
    elif vertical is not None:
        msg += f" [exact vertical motion: {vertical.message}]"
    thr = f"{lo:g} <= varpi < {hi:g} (edges to {WINDOW_EDGE_RTOL:g} relative)"
    return RuleResult("frequency-window", "error", ok, v, thr, msg, SRC_WINDOW, fix=fix)


def format_varpi(v: float) -> str:
    """ϖ with the fewest digits (3 at least) that never read as a window edge it is not.

    Parameters
    ----------
    v : float
        Normalised actuation frequency [-].

    Returns
    -------
    str
        ``f"{v:.3g}"``, or more digits when that would print 0.5 or 2 for a ϖ that is
        not at the edge (ϖ = 1.9999 prints "1.9999", never "2").
    """
    edge = window_position(v) in ("lower-edge", "upper-edge")
    for digits in (3, 6, 9, 12, 17):
        text = f"{v:.{digits}g}"
        if edge or float(text) not in VARPI_WINDOW:
            return text
    return repr(v)


def _share(x: float) -> str:
    """A share of time as a percentage, with a tiny non-zero one shown as such."""
    return f"{x:.0%}" if x == 0.0 or x >= 0.005 else f"{x:.2g} (< 1 %)"


def window_margin(s: SetDerivation) -> RuleResult | None:
    """The rule ``window-margin`` (warning): the window at ϖ·(1 ± 5 %).

    The rule ``window-margin`` (warning): the window holds at ϖ·(1 ± 5 %), or the
    distance to the nearest edge is named; None when ϖ is outside the window (the
    window rule fails then).
    """
    v = s.params.varpi
    if not in_window(v):
        return None
    lo, hi = VARPI_WINDOW
    f = WINDOW_MARGIN
    corners = {f"ϖ×{1 - f:g}": v * (1 - f), f"ϖ×{1 + f:g}": v * (1 + f)}
    out = [k for k, w in corners.items() if not in_window(w)]
    to_lo, to_hi = v / lo - 1.0, 1.0 - v / hi
    near, dist = ("lower edge 0.5", to_lo) if to_lo <= to_hi else ("upper edge 2", to_hi)
    thr = f"{lo:g} <= varpi·(1 ± {f:.0%}) < {hi:g}"
    if not out:
        msg = (
            f"ϖ = {format_varpi(v)} stays in the window at ϖ·(1 ± {f:.0%}) ({dist:.1%} "
            f"from its {near})"
        )
        return RuleResult("window-margin", "warning", True, dist, thr, msg, SRC_MARGIN_WINDOW)
    f_act = s.scales.f_act_hz
    need = (
        f"ϖ ≥ {lo / (1 - f):.4g} (f_v ≤ {_hz(f_act * (1 - f) / lo)} at f_act {_hz(f_act)})"
        if to_lo <= to_hi
        else f"ϖ < {hi / (1 + f):.4g} (f_v > {_hz(f_act * (1 + f) / hi)} at f_act {_hz(f_act)})"
    )
    msg = (
        f"ϖ = {format_varpi(v)} is {dist:.2%} from the window's {near}: a {f:.0%} spread of "
        f"f_act/f_v leaves the window ({', '.join(out)}); the margin needs {need}"
    )
    return RuleResult(
        "window-margin", "warning", False, dist, thr, msg, SRC_MARGIN_WINDOW, fix=SEARCH_HINT
    )
