"""The presentation vocabulary: one colour per exact mode, one word per rule status.

Every place that shows a mode or a rule's status takes it from here: the figures
(:mod:`betvdesign.plots`, the report's SVGs), the report's rule table, the explore page
(its map, legend and rule list) and ``betv check``'s text and HTML
(:mod:`betvdesign.checks.view`). So the same mode is painted the same colour, and the
same rule result is called the same word, everywhere.

Mode colours: the Okabe–Ito palette (M. Okabe and K. Ito, "Color Universal Design",
2002; B. Wong, Nature Methods 8, 441 (2011), doi:10.1038/nmeth.1618), chosen to stay
distinguishable under the common colour-vision deficiencies (protanopia, deuteranopia,
tritanopia), with its neutral grey for the mode that does not move the slider through
contact and white for an invalid point. Push (bluish green) and pull (reddish purple)
also differ in lightness, so they stay apart in grey print.
"""

from __future__ import annotations

from typing import Literal

__all__ = [
    "MODE_COLORS",
    "MODE_DIRECTION",
    "PENDING_COLOR",
    "STATUS_COLORS",
    "STATUS_STYLES",
    "Status",
    "rule_status",
]

#: Which way each moving mode drives the slider. A speed is a magnitude everywhere the
#: package shows one (``speed_m_s`` in JSON, CSV and figures); its mode says the way, in
#: these words (Δs per cycle keeps its sign: + along the impacts, push).
MODE_DIRECTION: dict[str, str] = {"push": "along the impacts", "pull": "against the impacts"}

#: Colour of every exact mode (:data:`betvdesign.studies.fieldmap.MAP_MODES`), Okabe–Ito
#: (module doc): push and pull first (in this order: figures that colour only the two
#: moving modes iterate over the first two).
MODE_COLORS: dict[str, str] = {
    "push": "#009e73",  # bluish green
    "pull": "#cc79a7",  # reddish purple
    "stalled": "#e69f00",  # orange
    "not driven": "#999999",  # grey
    "unbounded": "#d55e00",  # vermillion
    "not converged": "#56b4e9",  # sky blue
    "no crossing": "#0072b2",  # blue: moves, but does not cross its travel in time
    "invalid": "#ffffff",  # white
}

#: Colour of a point whose mode is not computed yet (the explore page's map).
PENDING_COLOR = "#fafafa"

#: The word for a rule's status.
Status = Literal["pass", "FAIL", "warning", "info"]

#: Colour [hex] of each status word (HTML: the explore page, ``betv check``'s HTML).
STATUS_COLORS: dict[str, str] = {
    "pass": "#1a7f37",
    "FAIL": "#cf222e",
    "warning": "#9a6700",
    "info": "#57606a",
}

#: Terminal style (rich markup) of each status word (``betv check``'s text).
STATUS_STYLES: dict[str, str] = {
    "pass": "green",
    "FAIL": "bold red",
    "warning": "yellow",
    "info": "dim",
}


def rule_status(passed: bool, severity: str) -> Status:
    """The one word for a rule's result.

    Parameters
    ----------
    passed : bool
        The rule holds.
    severity : {"error", "warning", "info"}
        The rule's severity.

    Returns
    -------
    str
        ``"pass"`` when it holds; else ``"FAIL"`` for an error (the device fails),
        ``"warning"`` or ``"info"`` (the severity: the device does not fail on it).

    Raises
    ------
    ValueError
        For an unknown severity.
    """
    if severity not in ("error", "warning", "info"):
        raise ValueError(f"unknown rule severity {severity!r} (error, warning or info)")
    if passed:
        return "pass"
    return "FAIL" if severity == "error" else severity  # type: ignore[return-value]
