"""A change of the head's springs said in drawn dimensions, through the frame.

``betv fix`` may move a resonance or α that the device file gives. Where the device has
a drawn actuator (``actuator.geometry``), what that change means in the drawing is found
through the same frame model that gives the drawn springs (:mod:`betvdesign.model.frame`,
via :func:`betvdesign.nondim.device.derive`), never through power laws such as
k ∝ w³ (for the drawn U-shaped actuator the flexure width moves k_v far less than w³
says: the arms' bending and the flexure act in series). The file's resonance is measured
and the drawing's prediction may differ from it, so the *ratio* is carried over: a file
f_v × r asks for the drawing's f_v × r.

Each drawn dimension (a lever, :data:`LEVERS`) is searched only within the process's
rules: no width below the structural layer's ``min_width``, no gap below its
``min_spacing`` (:func:`floor`), and within a factor :data:`REACH` of the drawn value.
A dimension that cannot give the change within them says so, with the nearest value it
reaches.

:func:`drawn_reach` answers the other question of a drawn device whose ϖ comes from the
drawing: can any drawn dimension bring ϖ into the design window 0.5 ≤ ϖ < 2 within the
process's rules, and if not, what is the nearest ϖ and what would have to change.

References
----------
docs/MODEL.md, "From the drawn actuator to the head's springs"; issue 30, item 6.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from betvdesign.errors import BetvError, ParameterError
from betvdesign.model.domain import VARPI_WINDOW
from betvdesign.spec.paths import with_values

VARPI_MIN, VARPI_MAX = VARPI_WINDOW

__all__ = ["LEVERS", "REACH", "LeverAnswer", "drawn_reach", "floor", "in_drawing"]

#: The drawn dimensions searched, in the order they are proposed: the flexure first
#: (it sets the head's suspension most directly), then the arms.
LEVERS = (
    "actuator.geometry.flexure_length",
    "actuator.geometry.flexure_width",
    "actuator.geometry.length",
    "actuator.geometry.hot_arm_width",
    "actuator.geometry.cold_arm_width",
)
#: A lever is searched between its drawn value / REACH and × REACH [-] (and above the
#: process's minimum).
REACH = 4.0
#: Geometric grid points [-] on which a lever is scanned before its root is bracketed.
GRID = 7
#: Relative tolerance [-] of the value found for a lever.
XTOL = 1e-4

#: The file's fields whose change :func:`in_drawing` translates, and the drawn quantity
#: each one scales (its ratio is carried over to the drawing).
QUANTITY: dict[str, tuple[str, str]] = {
    "actuator.vertical_resonance": ("f_v", "drawn f_v"),
    "actuator.horizontal_resonance": ("f_h", "drawn f_h"),
    "actuator.alpha": ("alpha", "drawn α"),
    "actuator.horizontal_stiffness": ("k_h", "drawn k_h"),
}


def _quantity(st: Any, which: str) -> float:
    """A drawn quantity of a derived set ``st``: f_v, f_h [Hz], α [-], k_h [N/m] or ϖ [-]."""
    if which == "varpi":
        return float(st.params.varpi)
    springs = st.springs
    if which == "f_v":
        return float(springs.f_v_hz)
    if which == "f_h":
        return float(springs.f_h_hz)
    if which == "alpha":
        return float((springs.f_v_hz / springs.f_h_hz) ** 2)
    return float(springs.k_h)


def floor(spec: Any, lever: str) -> tuple[float, str] | None:
    """The process's lower limit of a drawn dimension [µm] and the rule that sets it.

    Parameters
    ----------
    spec : DeviceSpec
        The device (its process and its first drawn actuator's layer).
    lever : str
        A field of :data:`LEVERS` (or ``actuator.geometry.gap``).

    Returns
    -------
    tuple of (float, str) or None
        The limit [µm] and its words ("the process's minimum width 2 µm"), or None when
        the device has no process or the process gives no such rule.
    """
    p = spec.process
    geo = next((s.actuator.geometry for s in spec.actuator_sets if s.actuator.geometry), None)
    if p is None or geo is None:
        return None
    layer = p.layers.get(p.structural_name(geo.layer))
    if layer is None:
        return None
    if lever.endswith("_width"):
        q, what = layer.min_width, "minimum width"
    elif lever.endswith(".gap"):
        q, what = layer.min_spacing, "minimum spacing"
    else:
        return None
    if q is None:
        return None
    x = float(q.to("um").magnitude)
    return x, f"{p.name}'s {what} {x:.3g} µm"


def _current_um(spec: Any, lever: str) -> float | None:
    geo = next((s.actuator.geometry for s in spec.actuator_sets if s.actuator.geometry), None)
    if geo is None:
        return None
    q = getattr(geo, lever.rsplit(".", 1)[1], None)
    return None if q is None else float(q.to("um").magnitude)


def _sets_at(spec: Any, lever: str | None, x_um: float | None) -> list[Any] | None:
    """The derived sets with ``lever`` at ``x_um`` [µm] (None: not derivable)."""
    from betvdesign.nondim.device import derive
    from betvdesign.spec.units import ureg

    s = spec if lever is None else with_values(spec, {lever: x_um * ureg.um})
    try:
        d = derive(s)
    except (BetvError, ParameterError, ValueError, ArithmeticError):
        return None
    return list(d.sets)


@dataclass(frozen=True)
class LeverAnswer:
    """The value of one drawn dimension that gives a drawn quantity, or why none does.

    Attributes
    ----------
    lever : str
        The field (``actuator.geometry.…``).
    x0 : float
        Its drawn value [µm].
    x : float or None
        The value giving the target [µm]; None when none within the limits does.
    lo, hi : float
        The limits searched [µm].
    reached : tuple of (float, float)
        The lever's value [µm] and the quantity's ratio to today's at the end of its
        range nearest the target (meaningful when ``x`` is None).
    limit : str
        The rule that set ``lo`` ("" when it is the :data:`REACH` factor).
    """

    lever: str
    x0: float
    x: float | None
    lo: float
    hi: float
    reached: tuple[float, float]
    limit: str = ""

    @property
    def name(self) -> str:
        """The lever's words ("flexure length")."""
        return self.lever.rsplit(".", 1)[1].replace("_", " ")

    def text(self) -> str:
        """The answer in words, with its numbers."""
        if self.x is not None:
            return f"{self.name} {self.x0:.4g} µm -> {self.x:.4g} µm"
        at, ratio = self.reached
        why = f" ({self.limit})" if self.limit and math.isclose(at, self.lo) else ""
        return f"{self.name} cannot: at {at:.4g} µm{why} it reaches ×{ratio:.3g}"


def _solve(
    q_of: Callable[[float], float | None], target: float, x0: float, lo: float, hi: float
) -> tuple[float | None, tuple[float, float]]:
    """Where q(x) = target on [lo, hi] (log grid, then Brent), or the nearest end."""
    xs = sorted({x0, *(lo * (hi / lo) ** (i / (GRID - 1)) for i in range(GRID))})
    pts = [(x, q) for x in xs if (q := q_of(x)) is not None]
    if not pts:
        return None, (x0, math.nan)
    f = [(x, math.log(q / target)) for x, q in pts]
    # the bracket nearest the drawn value: the smallest change
    best: tuple[float, float, float, float] | None = None
    for (xa, fa), (xb, fb) in itertools.pairwise(f):
        if fa == 0.0:
            return xa, (xa, target)
        if fa * fb < 0:
            d = min(abs(math.log(xa / x0)), abs(math.log(xb / x0)))
            if best is None or d < best[0]:
                best = (d, xa, xb, 0.0)
    if f[-1][1] == 0.0:
        return f[-1][0], (f[-1][0], target)
    if best is None:
        x_near, q_near = min(pts, key=lambda p: abs(math.log(p[1] / target)))
        return None, (x_near, q_near)

    def g(lx: float) -> float:
        q = q_of(math.exp(lx))
        return math.nan if q is None else math.log(q / target)

    from scipy.optimize import brentq  # here: the module's floors need no scipy (explore)

    lx = brentq(g, math.log(best[1]), math.log(best[2]), xtol=XTOL)
    return math.exp(lx), (math.exp(lx), target)


def _lever(spec: Any, lever: str, which: str, q0: float, target_ratio: float) -> LeverAnswer | None:
    """Search ``lever`` for the drawn quantity ``which`` at ``target_ratio``·``q0``."""
    x0 = _current_um(spec, lever)
    if x0 is None:
        return None
    lo, hi = x0 / REACH, x0 * REACH
    limit = ""
    fl = floor(spec, lever)
    if fl is not None and fl[0] > lo:
        lo, limit = fl[0], fl[1]
    if lo >= hi:
        return None

    def q_of(x: float) -> float | None:
        sets = _sets_at(spec, lever, x)
        return None if not sets or sets[0].springs is None else _quantity(sets[0], which) / q0

    x, (at, ratio) = _solve(q_of, target_ratio, x0, lo, hi)
    return LeverAnswer(lever, x0, x, lo, hi, (at, ratio), limit)


def in_drawing(spec: Any, field: str, old: float, new: float) -> str:
    """What a change of a file's resonance, α or k_h means in the drawn dimensions.

    Parameters
    ----------
    spec : DeviceSpec
        The device (with a drawn actuator, ``actuator.geometry``).
    field : str
        A field of :data:`QUANTITY` (``actuator.vertical_resonance``, …).
    old, new : float
        The file's value before and after, in the same unit.

    Returns
    -------
    str
        E.g. "in the drawing (frame model; drawn f_v 61.6 kHz ×0.615): flexure length
        50 µm -> 91.3 µm or length 200 µm -> 276 µm; flexure width cannot: at 2 µm
        (polymumps's minimum width 2 µm) it reaches ×0.83"; "" without a drawing or
        for another field.
    """
    if field not in QUANTITY or old <= 0 or new <= 0:
        return ""
    if not any(s.actuator.geometry for s in spec.actuator_sets):
        return ""
    base = _sets_at(spec, None, None)
    if not base or base[0].springs is None:
        return ""
    which, words = QUANTITY[field]
    r = new / old
    q0 = _quantity(base[0], which)
    answers = [a for lv in LEVERS if (a := _lever(spec, lv, which, q0, r)) is not None]
    if not answers:
        return ""
    shown = {"f_v": f"{q0 / 1e3:.3g} kHz", "f_h": f"{q0 / 1e3:.3g} kHz", "k_h": f"{q0:.3g} N/m"}
    head = f"in the drawing (frame model; {words} {shown.get(which, f'{q0:.3g}')} ×{r:.3g})"
    can = [a.text() for a in answers if a.x is not None]
    cannot = [a.text() for a in answers if a.x is None]
    parts = []
    if can:
        parts.append(" or ".join(can[:3]))
    if cannot:
        parts.append("; ".join(cannot))
    if not can:
        parts.insert(0, "no single drawn dimension gives it within the process's rules")
    return f"{head}: " + "; ".join(parts)


def drawn_reach(check: Any) -> str:
    """Whether drawn dimensions can bring ϖ into the window, within the process's rules.

    Only for a device whose first set's vertical spring comes from the drawing (no file
    f_v) and whose ϖ lies outside 0.5 ≤ ϖ < 2: each lever of :data:`LEVERS` is searched
    within its limits for the window's nearest edge (ϖ = ω·sqrt(m/k_v), derived).

    Parameters
    ----------
    check : CheckResult
        The check (its derivation's spec and sets).

    Returns
    -------
    str
        "" when nothing is to say; else the drawn change that reaches the window's edge,
        or the nearest ϖ reachable and what would have to change (the actuation
        frequency, or the head's mass: ϖ ∝ f_act·sqrt(m)).
    """
    sets = check.derivation.sets
    if not sets or sets[0].springs is None or sets[0].springs.used.get("k_v") != "geometry":
        return ""
    st = sets[0]
    varpi = float(st.params.varpi)
    if VARPI_MIN <= varpi < VARPI_MAX:
        return ""
    edge = VARPI_MIN if varpi < VARPI_MIN else VARPI_MAX * (1 - 1e-3)
    spec = check.derivation.spec
    nearest: tuple[float, LeverAnswer] | None = None
    for lv in LEVERS:
        a = _lever(spec, lv, "varpi", varpi, edge / varpi)
        if a is None:
            continue
        if a.x is not None:
            return (
                f"in the drawing (frame model): {a.name} {a.x0:.4g} µm -> {a.x:.4g} µm "
                f"brings ϖ {varpi:.3g} to the window's edge {edge:.3g} (`betv fix FILE --vary "
                f"{lv}={min(a.x0, a.x):.4g}um:{max(a.x0, a.x) * 1.25:.4g}um` adds the margin)"
            )
        v = varpi * a.reached[1]
        if math.isfinite(v):
            d = abs(math.log(v / edge))
            if nearest is None or d < nearest[0]:
                nearest = (d, a)
    if nearest is None:
        return ""
    a = nearest[1]
    at, ratio = a.reached
    v = varpi * ratio
    limit = f" ({a.limit})" if a.limit and math.isclose(at, a.lo) else ""
    f_edge = st.scales.f_act_hz * edge / varpi  # ϖ ∝ f_act at today's drawing
    m_ratio = (edge / v) ** 2  # ϖ ∝ sqrt(m), at the nearest drawing
    names = ", ".join(x.rsplit(".", 1)[1].replace("_", " ") for x in LEVERS)
    return (
        f"no drawn dimension brings ϖ = {varpi:.3g} into the window within the process's "
        f"rules ({names}, each ×{1 / REACH:g} to ×{REACH:g}, frame model): the nearest is "
        f"ϖ = {v:.3g} with {a.name} {at:.4g} µm{limit}; the window needs f_act "
        f"{'≥' if varpi < VARPI_MIN else '<'} {f_edge / 1e3:.4g} kHz at today's drawing, or "
        f"a head ×{m_ratio:.3g} as heavy at the nearest"
    )
