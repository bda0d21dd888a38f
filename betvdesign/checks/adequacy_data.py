"""Is the paper's idealised model enough for a device? The answer as data.

The results of :mod:`betvdesign.checks.adequacy` (plain, frozen dataclasses) and the
constants it works with: the plausible head damping and restitution assumed when a
device gives none, and the plausible ranges scanned for a change of mode. Text for
a designer: :meth:`SetAdequacy.line`, :meth:`DeviceAdequacy.text`.

Modes (one place turns Δs into a mode: :func:`betvdesign.model.domain.mode_of`): "push",
"pull", "stalled" (|Δs| at round-off), and "none" when no contact recurs (status
``not_driven``: the slider is not driven at all). A point without a periodic orbit
(``unbounded``, ``not_converged``, ``failed``) has no mode (None) and says why.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal

from betvdesign.output.siformat import format_dimensionless as fmt_x
from betvdesign.output.siformat import format_si

#: Quality factor Q [-] assumed in both directions when a device gives no damping.
#: Source: MODEL.md "Beyond the paper's idealisation" (shared): MEMS heads in air show
#: quality factors of order 10–100 (squeeze-film and structural damping); 30 is the
#: geometric middle of that decade and the value issue 12 asks a verdict to survive.
DEFAULT_QUALITY = 30.0
#: Coefficient of restitution e [-] assumed when a device gives none. Source: the same
#: section ("impacts that rebound a little") and issue 12 ("does my verdict survive
#: Q = 30 and e = 0.1?"); polysilicon micro-impacts with a soft contact layer are
#: strongly dissipative, so a small e is the plausible default.
DEFAULT_RESTITUTION = 0.1
#: Plausible range of Q [-] scanned for a change of mode (heavily damped in air to
#: near vacuum); applied to the normal and the tangential direction alike.
QUALITY_RANGE: tuple[float, float] = (1.0, 1000.0)
#: Plausible range of e [-] scanned for a change of mode (plastic to very elastic).
RESTITUTION_RANGE: tuple[float, float] = (0.0, 0.9)
#: Likely bands [-] within which a change of mode makes the idealised verdict
#: inadequate (a warning): Q of order 10–100 for MEMS heads in air and impacts that
#: "rebound a little" (shared MODEL.md, "Beyond the paper's idealisation"; e ≤ 0.3 for
#: polysilicon micro-impacts, whose contact layers dissipate most of the impact energy).
#: A flip only beyond them (still within the scanned ranges) is reported, not warned.
LIKELY_QUALITY: tuple[float, float] = (10.0, 100.0)
LIKELY_RESTITUTION: tuple[float, float] = (0.0, 0.3)
#: Grid points of the scans (log-spaced in Q, even in e: steps of 0.05).
QUALITY_POINTS = 25
RESTITUTION_POINTS = 19
#: Bisection steps on a bracketed change of mode (bracket 2⁻¹² of a grid step: about
#: 7e-5 relative in Q, 1.2e-5 in e).
BISECT_STEPS = 12
#: Cycle budget of each scan orbit (the device's own points get the solver's default).
SCAN_MAX_CYCLES = 20_000
#: Relative speed change [-] above which the idealised speed is called inadequate even
#: when the mode holds (the designer should quote the richer speed).
SPEED_RTOL = 0.1

Status = Literal["adequate", "flips-beyond", "speed-differs", "mode-flips", "ideal-fails", "failed"]
Axis = Literal["quality", "restitution"]
#: Statuses for which the idealised model's mode can be trusted.
ADEQUATE: tuple[str, ...] = ("adequate", "flips-beyond", "speed-differs")


def shown_mode(mode: str | None) -> str:
    """A scan point's mode as a designer reads it: "none" is "not driven" (no contact
    recurs), None "no orbit"."""
    return {"none": "not driven", None: "no orbit"}.get(mode, str(mode))


@dataclass(frozen=True)
class Point:
    """One exact periodic orbit of the study.

    quality: Q_v, the normal quality factor [-] (inf: undamped); quality_tangential: Q_h
    [-]; restitution: e [-]; status: the periodic solver's; delta_s: Δs per cycle [-]
    (None without an orbit); mode: "push", "pull", "stalled", "none" (not driven) or
    None; speed_m_s: Δs·u·cosθ·f_act [m/s] with the device's stroke (its thermal roll-off
    included); message: the solver's.
    """

    quality: float
    quality_tangential: float
    restitution: float
    status: str
    delta_s: float | None
    mode: str | None
    speed_m_s: float | None
    message: str = ""

    @property
    def answer(self) -> str:
        """``push at 2.35 mm/s``, ``none (not driven)``, ``no periodic orbit (unbounded)``."""
        if self.mode in ("push", "pull"):
            return f"{self.mode} at {format_si(abs(self.speed_m_s or 0.0), 'm/s')}"
        if self.mode == "none":
            return "none (not driven: no contact recurs)"
        if self.mode == "stalled":
            return "stalled (Δs at round-off)"
        return f"no periodic orbit ({self.status})"

    @property
    def terms(self) -> str:
        """``Q 30, e 0.1`` (``Q ∞`` when undamped; ``Q_v 30, Q_h 50`` when they differ)."""
        q_v, q_h = (_q(q) for q in (self.quality, self.quality_tangential))
        q = f"Q {q_v}" if q_v == q_h else f"Q_v {q_v}, Q_h {q_h}"
        return f"{q}, e {fmt_x(self.restitution)}"


def _finite(x: float) -> float | None:
    return x if math.isfinite(x) else None


def _q(q: float) -> str:
    return "∞" if math.isinf(q) else fmt_x(q)


def speed_change(ideal: Point, richer: Point) -> float | None:
    """(v_richer − v_ideal)/v_ideal [-] of the signed speeds: the relative change of the
    speed when both move the same way (below −1 when they move opposite ways); None
    without both speeds."""
    a, b = ideal.speed_m_s, richer.speed_m_s
    if a is None or b is None or a == 0.0:
        return None
    return (b - a) / a


@dataclass(frozen=True)
class Crossing:
    """A change of mode along a scan, bracketed by bisection: between ``low`` and
    ``high`` (axis values, low < high) the mode goes from ``mode_low`` to ``mode_high``;
    ``at`` is the estimate (geometric mean for Q, arithmetic for e)."""

    axis: Axis
    low: float
    high: float
    mode_low: str | None
    mode_high: str | None

    @property
    def at(self) -> float:
        if self.axis == "quality":
            return math.sqrt(self.low * self.high)
        return 0.5 * (self.low + self.high)

    @property
    def text(self) -> str:
        sym = "Q" if self.axis == "quality" else "e"
        return (
            f"{sym} ≈ {fmt_x(self.at, 4)} ({shown_mode(self.mode_low)} below, "
            f"{shown_mode(self.mode_high)} above)"
        )


@dataclass(frozen=True)
class Scan:
    """Orbits along one axis with the other term held at the device's value (``fixed``,
    in words): ``points`` ascending in the axis, every change of mode bisected in
    ``crossings``."""

    axis: Axis
    fixed: str
    points: tuple[Point, ...]
    crossings: tuple[Crossing, ...]

    @property
    def values(self) -> list[float]:
        return [p.quality if self.axis == "quality" else p.restitution for p in self.points]


@dataclass(frozen=True)
class SetAdequacy:
    """Adequacy of the idealised model for one actuator set.

    ideal: the paper's model (undamped, plastic; speed with the device's stroke);
    richer: the device's damping and restitution (or the defaults, ``source``
    "default"); reference: the mode flips are measured against (the ideal one, or the
    richer one when the ideal model has no orbit); flip_quality / flip_restitution:
    where the mode first leaves the reference, going from the idealised end of each
    scan (large Q, small e), None when it does not within the plausible range;
    rolloff_factor: H(f_act)/H(f_cal) of the stroke (1 without a cut-off).
    """

    name: str
    intended_mode: str
    status: Status
    message: str
    ideal: Point
    richer: Point
    source: Literal["device", "default"]
    quality_normal: float
    quality_tangential: float
    reference: str | None
    quality_scan: Scan
    restitution_scan: Scan
    flip_quality: Crossing | None
    flip_restitution: Crossing | None
    rolloff_factor: float = 1.0

    @property
    def adequate(self) -> bool:
        """The idealised model's mode holds (speed may still differ: ``status``)."""
        return self.status in ADEQUATE

    @property
    def speed_change(self) -> float | None:
        """(v_richer − v_ideal)/v_ideal [-] of the signed speeds at the device (the relative
        speed change when both move the same way), None without both speeds."""
        return speed_change(self.ideal, self.richer)

    @property
    def flips(self) -> list[Crossing]:
        """Every change of mode found in the plausible ranges (both scans)."""
        return [*self.quality_scan.crossings, *self.restitution_scan.crossings]

    def as_dict(self) -> dict[str, Any]:
        """JSON-safe record (``betv check --json``): infinite Q (undamped) as None."""

        def pt(p: Point) -> dict[str, Any]:
            return {
                "quality_normal": _finite(p.quality),
                "quality_tangential": _finite(p.quality_tangential),
                "restitution": p.restitution,
                "status": p.status,
                "mode": p.mode,
                "delta_s": p.delta_s,
                "speed_m_s": p.speed_m_s,
            }

        def flip(c: Crossing | None) -> float | None:
            return None if c is None else c.at

        return {
            "status": self.status,
            "adequate": self.adequate,
            "message": self.message,
            "summary": self.summary(),
            "source": self.source,
            "reference_mode": self.reference,
            "ideal": pt(self.ideal),
            "richer": pt(self.richer),
            "speed_change": self.speed_change,
            "flip_quality": flip(self.flip_quality),
            "flip_restitution": flip(self.flip_restitution),
            "crossings": [
                {
                    "axis": c.axis,
                    "at": c.at,
                    "low": c.low,
                    "high": c.high,
                    "mode_low": c.mode_low,
                    "mode_high": c.mode_high,
                }
                for c in self.flips
            ],
            "quality_range": list(QUALITY_RANGE),
            "restitution_range": list(RESTITUTION_RANGE),
        }

    def line(self) -> str:
        """One line for ``betv check``: status, both answers, where the mode flips."""
        return f"model adequacy: {self.status}: {self.summary()}"

    def summary(self) -> str:
        """Short form of :attr:`message`: both answers and the flips (or their absence)."""
        src = " (defaults)" if self.source == "default" else ""
        change = self.speed_change
        pct = f" ({change:+.0%})" if change is not None and change > -1.0 else ""
        text = f"idealised {self.ideal.answer}; {self.richer.terms}{src}: {self.richer.answer}{pct}"
        flips = [f for f in (self.flip_quality, self.flip_restitution) if f is not None]
        if flips:
            text += "; mode flips at " + ", ".join(
                f"{'Q' if f.axis == 'quality' else 'e'} ≈ {fmt_x(f.at)} (→ "
                f"{shown_mode(f.mode_low if f.axis == 'quality' else f.mode_high)})"
                for f in flips
            )
        elif self.status == "mode-flips":
            text += "; the mode differs within the plausible ranges"
        else:
            text += (
                f"; no mode flip for Q {fmt_x(QUALITY_RANGE[0])}–{fmt_x(QUALITY_RANGE[1])}, "
                f"e {fmt_x(RESTITUTION_RANGE[0])}–{fmt_x(RESTITUTION_RANGE[1])}"
            )
        return text


@dataclass(frozen=True)
class DeviceAdequacy:
    """Adequacy of the idealised model for every actuator set of a device."""

    device: str
    sets: tuple[SetAdequacy, ...]

    @property
    def adequate(self) -> bool:
        return all(s.adequate for s in self.sets)

    @property
    def status(self) -> Status:
        """The worst status of the sets."""
        order = ("failed", "ideal-fails", "mode-flips", "speed-differs", "flips-beyond", "adequate")
        return min((s.status for s in self.sets), key=order.index)

    @property
    def message(self) -> str:
        return "; ".join(f"{s.name}: {s.message}" for s in self.sets)

    def text(self) -> str:
        lines = [f"{self.device}: the idealised model is {self._word()}"]
        lines += [f"  {s.name}: {s.status}: {s.message}" for s in self.sets]
        return "\n".join(lines)

    def _word(self) -> str:
        if self.adequate:
            return "adequate for the mode" + {
                "adequate": "",
                "flips-beyond": " (it flips only beyond the likely Q and e)",
            }.get(self.status, " (not for the speed)")
        return "not adequate" if self.status != "failed" else "undecided (no exact answer)"

    def __repr__(self) -> str:
        return self.text()
