"""``betv fix`` and the check's advice: the nearest passing value of each field.

One search answers both ``betv fix`` and the ``fix`` text of every failing rule of
``betv check`` (:func:`advise`, attached by the check pipeline,
:func:`betvdesign.api.run_check`): there is no second source of advice that could point
another way.

**Passing** is what ``betv check`` calls PASS (every error rule: frequency window,
mode, target speed when given) with the mode also held at the margin corners
ϖ·(1 ± 5 %) and α·(1 ± 10 %) (the rule ``mode-margin``) and the design window at
ϖ·(1 ± 5 %) (the rule ``window-margin``), and a stroke predicted from the drawing kept
within the actuator's thermal bandwidth (the rule ``thermal.bandwidth``): "nothing to
fix" only when these hold. Warnings that do not fail the
check (slow settling, tangential resonance, model adequacy) do not block a fix; they are
listed with the fix. Every candidate goes through
:func:`betvdesign.checks.checker.check_derivation`, the same path as ``betv check``.

**Screen, then verify.** The search judges candidates by the check without the
transient from rest where a determined orbit answers (``settle="undecided"``,
:meth:`Evaluator.screen`): the same outcome as the full check wherever that quotes the
periodic orbit, for a fraction of the cost (the transient runs up to the horizon of
2·10⁵ cycles, for the design and its four margin corners). Every value proposed is
verified by the full check; the boundary and the scan are the screen's. When the
screen passes the current design that the full check fails (a slider that does not
cross its travel, or crosses it in another mode than its orbit's), the screen cannot see
the failure: the field's first proposal is verified and the field says so
(:attr:`FieldAnswer.unseen`), and the pairs stop at their first failing verification.

**Search, one field at a time.** From the current value x0 the field is stepped outward
in both directions (interleaved, nearest first) in log steps of :data:`SCAN_STEP`
within its bounds; at the first passing step the boundary is bisected to
:data:`BISECT_RTOL`, and the value proposed is :data:`FIELD_MARGIN` (relative) inside
it, on the passing side (re-checked; if that point fails, the island is narrower than
the margin and the scan goes on). A field with no passing value within its bounds says
so with the bounds tried and the rule that blocks it. Only when no single field
fixes the device are pairs searched (:data:`PAIR_FIELDS` fields, coarse grid).

**Ranking.** The designer's own fields first (a drive setting or a drawn dimension,
:mod:`betvdesign.spec.fields`), then resonances, stiffnesses and materials (shown with
what the change means physically); within each, the smallest change |ln(x/x0)|.

With spreads (``--spread``), a candidate must also keep P(pass) ≥ ``p_min`` in a
seeded Monte Carlo that counts every error rule: the frequency window, the tangential
resonance, the exact mode and the target speed (:func:`robust_probability`).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from betvdesign.errors import BetvError, ParameterError
from betvdesign.model.bisection import bisect
from betvdesign.spec.fields import BY_PATH, describe_change
from betvdesign.spec.paths import with_values
from betvdesign.studies.fixfields import DEFAULT_BOUNDS, Vary, parse_vary

__all__ = [
    "BISECT_RTOL",
    "DEFAULT_BOUNDS",
    "FIELD_MARGIN",
    "SCAN_STEP",
    "FieldAnswer",
    "FixResult",
    "Vary",
    "advise",
    "find_fixes",
    "parse_vary",
    "robust_probability",
    "with_advice",
]

#: Relative distance [-] the proposed value keeps inside the passing boundary of its
#: field (x = boundary·(1 ± FIELD_MARGIN), on the passing side).
FIELD_MARGIN = 0.05
#: Relative outward step [-] of the scan of a field (log-spaced from the current value).
SCAN_STEP = 0.05
#: Relative width [-] to which a boundary is bisected.
BISECT_RTOL = 0.002
PAIR_POINTS = 9
#: Pairs are searched among this many fields, those that came closest on their own.
PAIR_FIELDS = 4
#: The rules a fix must pass besides the error rules: the mode at the margin corners, the
#: window at ϖ·(1 ± 5 %), and, for a stroke predicted from the drawing, the drive within
#: the actuator's thermal bandwidth (a drive far above it spends its power on heat).
REQUIRED_WARNINGS = ("mode-margin", "window-margin", "thermal.bandwidth")
#: At most this many fields are searched for the advice of ``betv check``, and the
#: search stops after this many fixes (:func:`advise`).
ADVICE_FIELDS = 3
ADVICE_FIXES = 2

#: The failure counted for a value outside the device's measured calibration (not a
#: rule: the value cannot be checked, the calibration is never extrapolated).
OUTSIDE_CALIBRATION = "outside-calibration"

MARGIN_TEXT = (
    f"margin: the value proposed lies {FIELD_MARGIN:.0%} inside the boundary where the "
    "check starts to pass (bisected to 0.2 %), and the mode also holds at ϖ·(1 ± 5 %) and "
    "α·(1 ± 10 %), and the design window at ϖ·(1 ± 5 %)"
)


# --- evaluation ------------------------------------------------------------------------


@dataclass(frozen=True)
class Outcome:
    """One exact check of a candidate.

    One exact check of a candidate: passes, the failing rules (error rules and
    :data:`REQUIRED_WARNINGS`), the warnings that fail but do not block, the check.
    """

    passed: bool
    failing: tuple[str, ...]
    warnings: tuple[str, ...]
    check: Any


class Evaluator:
    """Checks candidate specs through the same path as ``betv check`` (cached).

    Calling it runs the full check (:func:`~betvdesign.checks.checker.check_derivation`,
    adequacy aside); :meth:`screen` runs the search's screen, the same check with the
    transient from rest only where the orbit gives no periodic answer
    (``settle="undecided"``).
    """

    def __init__(
        self,
        spec: Any,
        varies: Sequence[Vary],
        target_speed_m_s: float | None,
        horizon: int | None = None,
    ):
        self.spec = spec
        self.varies = {v.field: v for v in varies}
        self.target = target_speed_m_s
        self.horizon = horizon
        self.cache: dict[tuple[tuple[str, float], ...], Outcome] = {}
        self.screened: dict[tuple[tuple[str, float], ...], Outcome] = {}
        self.evaluations = 0

    def spec_at(self, changes: dict[str, float]) -> Any:
        return with_values(self.spec, {f: self.varies[f].quantity(x) for f, x in changes.items()})

    def __call__(self, changes: dict[str, float]) -> Outcome:
        key = tuple(sorted(changes.items()))
        if key not in self.cache:
            self.cache[key] = self._run(changes, True)
        return self.cache[key]

    def screen(self, changes: dict[str, float], known: bool = True) -> Outcome:
        """The search's screen of a candidate (with ``known``, the full check's if known).

        The check without the transient from rest where a determined orbit answers:
        the same outcome as the full check whenever that quotes the periodic orbit (the
        transient settles early in the travel); a slider slower to cross its travel than
        to settle, or one that does not cross it, is seen only by the full check.
        """
        key = tuple(sorted(changes.items()))
        if known and key in self.cache:
            return self.cache[key]
        if key not in self.screened:
            self.screened[key] = self._run(changes, "undecided")
        return self.screened[key]

    def _run(self, changes: dict[str, float], settle: bool | str) -> Outcome:
        from betvdesign.checks.checker import check_derivation
        from betvdesign.model.domain import in_window
        from betvdesign.nondim.device import derive
        from betvdesign.studies.sampling import check_sample

        for f, x in changes.items():  # not checked: no extrapolation of the points
            cal = self.varies[f].calibrated
            if cal is not None and not cal[0] <= x <= cal[1]:
                return Outcome(False, (OUTSIDE_CALIBRATION,), (), None)
        self.evaluations += 1
        try:
            check_sample({f: (x, self.varies[f].unit) for f, x in changes.items()})
            d = derive(self.spec_at(changes))
            if not all(in_window(s.params.varpi) for s in d.sets):  # no orbit needed
                return Outcome(False, ("frequency-window",), (), None)
            kw = {} if self.horizon is None else {"horizon": self.horizon}
            res = check_derivation(
                d, target_speed_m_s=self.target, adequacy=False, settle=settle, **kw
            )
        except (ParameterError, BetvError, ValueError) as exc:
            return Outcome(False, (f"invalid: {exc}",), (), None)
        return outcome_of(res)


def outcome_of(res: Any) -> Outcome:
    """The fix's verdict on a :class:`~betvdesign.checks.checker.CheckResult`."""
    failing = sorted(
        {
            r.id
            for r in res.rules
            if not r.passed and (r.severity == "error" or r.id in REQUIRED_WARNINGS)
        }
    )
    warnings = sorted(
        {
            r.id
            for r in res.rules
            if not r.passed and r.severity == "warning" and r.id not in REQUIRED_WARNINGS
        }
    )
    return Outcome(not failing, tuple(failing), tuple(warnings), res)


def _speed(check: Any) -> float | None:
    speeds = [abs(v) for sc in check.sets if (v := sc.speed_m_s) is not None]
    return min(speeds) if speeds else None


def _mode(check: Any) -> str | None:
    modes = {sc.verdict_mode for sc in check.sets}
    return modes.pop() if len(modes) == 1 else ", ".join(sorted(str(m) for m in modes))


# --- one field: the nearest passing value --------------------------------------------


@dataclass
class FieldAnswer:
    """The nearest passing value of one field, or why there is none.

    Attributes
    ----------
    field : str
        Dotted field path.
    x0, lo, hi : float
        Current value and the bounds tried [``unit``].
    unit : str
        The field's unit as the device file gives it.
    value : float or None
        The value proposed: :data:`FIELD_MARGIN` inside ``boundary`` [``unit``].
    boundary : float or None
        Where the check starts to pass along the field, bisected [``unit``].
    blocking : str
        Without a value: the rule that fails most often over the values tried.
    blocking_counts : dict of str to int
        Without a value: per failure, the values tried where it fails (a rule id,
        :data:`OUTSIDE_CALIBRATION`, or "invalid: ..." for a value the model cannot take).
    calibrated : tuple of float or None
        The range the measured calibration covers [``unit``] (:attr:`Vary.calibrated`).
    evaluations : int
        Exact checks spent on the field.
    """

    field: str
    x0: float
    lo: float
    hi: float
    unit: str
    value: float | None = None
    boundary: float | None = None
    blocking: str = ""
    blocking_counts: dict[str, int] = field(default_factory=dict)
    evaluations: int = 0
    outcome: Outcome | None = None
    calibrated: tuple[float, float] | None = None
    #: What the proposed change means physically, in drawn dimensions where the device
    #: has a drawing (:func:`change_meaning`); set with ``value``.
    meaning: str = ""
    #: Without a value: the rules the full check fails at the value the search proposed
    #: (``proposed``) while the search's screen passes there and at the current value
    #: alike (the transient from rest decides them); the search then stops.
    unseen: tuple[str, ...] = ()
    proposed: float | None = None

    @property
    def direction(self) -> int:
        """+1 raise, -1 lower, 0 no value."""
        if self.value is None:
            return 0
        return 1 if self.value > self.x0 else -1

    @property
    def size(self) -> float:
        """The change's size |ln(x/x0)| [-] (inf without a value)."""
        return math.inf if self.value is None else abs(math.log(self.value / self.x0))

    @property
    def kind(self) -> str:
        """What kind of field it is (drive setting, drawn dimension, ...)."""
        known = BY_PATH.get(self.field)
        return known.kind if known is not None else "drawn dimension"

    @property
    def designer_field(self) -> bool:
        """A drive setting or a drawn dimension (what the designer sets directly)."""
        return self.kind in ("drive setting", "drawn dimension")

    def text(self, x: float) -> str:
        """A value of the field with its unit."""
        return f"{x:.4g} {self.unit}".strip()

    def tried(self) -> str:
        """The bounds the search tried."""
        return f"{self.text(self.lo)} to {self.text(self.hi)}"

    def advice(self) -> str:
        """The change in words: direction, amount, boundary and physical meaning."""
        if self.value is None and self.unseen and self.proposed is not None:
            return (
                f"{self.field}: no passing value found from {self.tried()} (the search, "
                f"which judges a moving orbit without its transient from rest, passes "
                f"{self.text(self.x0)} and proposes {self.text(self.proposed)}; the check "
                f"fails it: {', '.join(self.unseen)})"
            )
        if self.value is None:
            return f"{self.field}: no passing value from {self.tried()} ({self.blocked()})"
        if self.boundary is None:
            return f"keep {self.field} at {self.text(self.x0)} (passes)"
        verb = "raise" if self.direction > 0 else "lower"
        meaning = self.meaning
        return (
            f"{verb} {self.field} {self.text(self.x0)} -> {self.text(self.value)} "
            f"(passes from {self.text(self.boundary)}; {FIELD_MARGIN:.0%} margin)"
            + (f" [{meaning}]" if meaning else "")
        )

    def blocked(self) -> str:
        """What blocked the values tried, with the counts.

        What blocked the values tried, with the counts: the rule that failed at the
        most values first, then the others; values outside the measured calibration
        (not checked) and values the model cannot take are named as such.
        """
        c = self.blocking_counts
        if not self.blocking:
            return "blocked at every value tried"
        ranked = sorted(
            ((k, n) for k, n in c.items() if _is_rule(k)), key=lambda kv: (-kv[1], kv[0])
        )
        parts = [f"blocked most by {self.blocking}: fails at {c.get(self.blocking, 0)} value(s)"]
        parts += [f"{k} at {n}" for k, n in ranked if k != self.blocking]
        out = c.get(OUTSIDE_CALIBRATION, 0)
        if out and self.calibrated is not None:
            lo, hi = self.calibrated
            parts.append(
                f"{out} value(s) outside the measured calibration "
                f"({self.text(lo)} to {self.text(hi)}; not checked)"
            )
        invalid = sum(n for k, n in c.items() if k.startswith("invalid"))
        if invalid:
            parts.append(f"{invalid} value(s) the model cannot take")
        return "; ".join(parts)

    def as_dict(self) -> dict[str, Any]:
        """The JSON-ready record."""
        return {
            "field": self.field,
            "kind": self.kind,
            "from": self.text(self.x0),
            "to": None if self.value is None else self.text(self.value),
            "boundary": None if self.boundary is None else self.text(self.boundary),
            "direction": {1: "raise", -1: "lower", 0: None}[self.direction],
            "relative_change": None if self.value is None else self.value / self.x0 - 1.0,
            "meaning": None if self.value is None else self.meaning,
            "bounds_tried": [self.text(self.lo), self.text(self.hi)],
            "blocking": self.blocking or None,
            "unseen": list(self.unseen) or None,
            "evaluations": self.evaluations,
        }


def _is_rule(failure: str) -> bool:
    """Whether a failure counted by the scan is a rule's.

    A failure counted by the scan is a rule's, not a value that could not be checked
    (outside the calibration) or that the model cannot take ("invalid: ...").
    """
    return failure != OUTSIDE_CALIBRATION and not failure.startswith("invalid")


def _bisect(
    judge: Callable[[dict[str, float]], Outcome], name: str, good: float, bad: float
) -> float:
    """The last passing value between ``good`` and ``bad``.

    The last value ``judge`` passes between a passing ``good`` and a failing ``bad``
    one, bisected in ratio to :data:`BISECT_RTOL`
    (:func:`betvdesign.model.bisection.bisect`).
    """
    return bisect(
        lambda x: judge({name: x}).passed, good, bad, True, False, rtol=BISECT_RTOL, geometric=True
    ).a


def _steps(v: Vary) -> list[tuple[float, float]]:
    """Scan points as (previous, point), nearest first, alternating up and down."""
    step = math.log1p(SCAN_STEP)
    sides = []
    for sign, end in ((1, v.hi), (-1, v.lo)):
        pts, prev, k = [], v.x0, 1
        while True:
            x = v.x0 * math.exp(sign * k * step)
            if (sign > 0 and x >= end) or (sign < 0 and x <= end):
                if abs(math.log(end / prev)) > 1e-9 and (end - v.x0) * sign > 0:
                    pts.append((prev, end))
                break
            pts.append((prev, x))
            prev, k = x, k + 1
        sides.append(pts)
    out = []
    for a, b in itertools.zip_longest(*sides):
        out.extend(p for p in (a, b) if p is not None)
    out.sort(key=lambda t: abs(math.log(t[1] / v.x0)))
    return out


def change_meaning(spec: Any, field: str, old: float, new: float) -> str:
    """What a proposed change means physically, in drawn dimensions where there are some.

    The suspension's stiffness (:func:`betvdesign.spec.fields.describe_change`) and,
    where the device has a drawn actuator, the drawn dimensions that give the same
    relative change through the frame model
    (:func:`betvdesign.studies.drawnchange.in_drawing`, within the process's rules).

    Parameters
    ----------
    spec : DeviceSpec
        The device.
    field : str
        The field changed.
    old, new : float
        Its value before and after, in the field's unit.

    Returns
    -------
    str
        The meaning ("" for a field set directly).
    """
    from betvdesign.studies.drawnchange import in_drawing

    parts = [describe_change(field, old, new), in_drawing(spec, field, old, new)]
    return "; ".join(p for p in parts if p)


def nearest(ev: Evaluator, v: Vary) -> FieldAnswer:
    """The nearest passing value of field ``v`` (see the module docstring)."""
    start = ev.evaluations
    ans = FieldAnswer(v.field, v.x0, v.lo, v.hi, v.unit, calibrated=v.calibrated)
    counts: dict[str, int] = {}
    if v.x0 < v.lo or v.x0 > v.hi:  # current value outside the bounds: scan them
        v = replace(v, x0=min(max(v.x0, v.lo), v.hi))
    base = ev({})
    if base.passed:  # already passing: the current value (a robust search goes on)
        ans.value, ans.outcome, ans.evaluations = v.x0, base, ev.evaluations - start
        return ans
    blind = ev.screen({}, known=False).passed  # the screen passes what the check fails
    for prev, x in _steps(v):
        out = ev.screen({v.field: x})
        if not out.passed:
            for rid in out.failing:
                counts[rid] = counts.get(rid, 0) + 1
            continue
        prev_ok = ev.screen({v.field: prev}).passed if prev != v.x0 else blind
        b = x if prev_ok else _bisect(ev.screen, v.field, x, prev)
        sign = 1 if x > v.x0 else -1
        y = b * (1 + FIELD_MARGIN) ** sign
        y = min(max(y, v.lo), v.hi)
        oy = ev({v.field: y})  # the full check verifies the value proposed
        if oy.passed:
            ans.value, ans.boundary, ans.outcome = y, b, oy
            ans.meaning = change_meaning(ev.spec, v.field, v.x0, y)
            break
        if blind:  # the screen cannot see what fails: no search along this field
            ans.unseen, ans.proposed = oy.failing, y
            for rid in oy.failing:
                counts[rid] = counts.get(rid, 0) + 1
            break
    ans.blocking_counts = counts
    if ans.value is None and counts:
        rules = {k: n for k, n in counts.items() if _is_rule(k)} or counts
        ans.blocking = max(rules, key=lambda k: (rules[k], k))
    ans.evaluations = ev.evaluations - start
    return ans


# --- the result ----------------------------------------------------------------------


@dataclass
class Candidate:
    """One proposed change and what the exact check says of it."""

    changes: dict[str, float]
    size: float
    mode: str | None
    speed_m_s: float | None
    why: str
    passed: bool = False
    check: Any = None
    p_pass: float | None = None
    blocking: list[str] = field(default_factory=list)
    answers: list[FieldAnswer] = field(default_factory=list)

    def meaning_of(self, f: str, x: float, varies: dict[str, Vary]) -> str:
        """What the change of field ``f`` to ``x`` means (its answer's, else the stiffness)."""
        for a in self.answers:
            if a.field == f and a.value == x and a.meaning:
                return a.meaning
        return describe_change(f, varies[f].x0, x)

    def as_dict(self, varies: dict[str, Vary]) -> dict[str, Any]:
        return {
            "changes": [
                {
                    "field": f,
                    "kind": BY_PATH[f].kind if f in BY_PATH else None,
                    "from": varies[f].text(varies[f].x0),
                    "to": varies[f].text(x),
                    "relative_change": x / varies[f].x0 - 1.0,
                    "meaning": self.meaning_of(f, x, varies),
                }
                for f, x in self.changes.items()
            ],
            "boundary": {a.field: a.text(a.boundary) for a in self.answers if a.boundary},
            "size": self.size,
            "mode": self.mode,
            "speed_m_s": self.speed_m_s,
            "p_pass": self.p_pass,
            "passed": self.passed,
            "why": self.why,
        }


@dataclass
class FixResult:
    """Outcome of :func:`find_fixes`: ``status`` "already_passes", "fixed" or "none".

    ``blocking``: per field that cannot fix the device, the bounds tried and the rule
    that blocks it; ``improve``: for a passing device, what it would still improve
    (the warnings that fail, with their fix).
    """

    status: str
    message: str
    candidates: list[Candidate]
    varies: dict[str, Vary]
    blocking: dict[str, dict[str, Any]]
    evaluations: int
    best_spec: Any = None
    improve: list[dict[str, str]] = field(default_factory=list)
    spread_note: str = ""

    @property
    def best(self) -> Candidate | None:
        """The best passing candidate (None when none passes)."""
        return next((c for c in self.candidates if c.passed), None)

    def as_dict(self) -> dict[str, Any]:
        """The JSON-ready record."""
        return {
            "status": self.status,
            "message": self.message,
            "passing": "betv check PASS (every error rule) with the mode held at "
            "ϖ·(1 ± 5 %) and α·(1 ± 10 %), the window at ϖ·(1 ± 5 %) and a drawn "
            "stroke within its thermal bandwidth; other warnings do not block",
            "margin": {"relative": FIELD_MARGIN, "meaning": MARGIN_TEXT},
            "evaluations": self.evaluations,
            "varied": {
                f: {"from": v.text(v.x0), "lo": v.text(v.lo), "hi": v.text(v.hi)}
                for f, v in self.varies.items()
            },
            "candidates": [c.as_dict(self.varies) for c in self.candidates],
            "blocking": self.blocking,
            "improve": self.improve,
            "spread": self.spread_note or None,
        }


def _rank(c: Candidate) -> tuple[int, float, int]:
    order = {f: i for i, f in enumerate(DEFAULT_BOUNDS)}
    designer = all(
        (BY_PATH[f].kind if f in BY_PATH else "drawn dimension")
        in ("drive setting", "drawn dimension")
        for f in c.changes
    )
    return (0 if designer else 1, round(c.size, 3), min(order.get(f, 99) for f in c.changes))


def _why(before: Sequence[str], out: Outcome) -> str:
    """What a passing candidate does: the rules it fixes, its exact mode and speed."""
    from betvdesign.checks.rule import format_speed

    speed = _speed(out.check)
    parts = [f"fixes {', '.join(before)}" if before else "keeps every rule passing"]
    parts.append(f"exact mode {_mode(out.check)}")
    if speed is not None:
        parts.append(f"speed {format_speed(speed)}")
    if out.warnings:
        parts.append(f"still warns: {', '.join(out.warnings)}")
    return "; ".join(parts)


def _improve(out: Outcome) -> list[dict[str, str]]:
    """The failing warnings and infos of a passing check, with their fix text."""
    seen, items = set(), []
    for r in out.check.rules if out.check is not None else []:
        if r.passed or r.severity == "error" or (r.id, r.fix) in seen:
            continue
        seen.add((r.id, r.fix))
        items.append({"rule": r.id, "message": r.message, "fix": r.fix})
    return items


def find_fixes(
    spec: Any,
    varies: Sequence[Vary],
    *,
    target_speed_m_s: float | None = None,
    pairs: bool = True,
    robust: Callable[[Any], float] | None = None,
    p_min: float = 0.99,
    horizon: int | None = None,
) -> FixResult:
    """Search the nearest passing value of each field (see the module docstring).

    Parameters
    ----------
    spec : DeviceSpec
        The device.
    varies : sequence of Vary
        The fields and their bounds (:func:`parse_vary`).
    target_speed_m_s : float, optional
        Required speed [m/s] (the error rule ``target-speed``).
    pairs : bool
        Search pairs of fields when no single field fixes the device.
    robust : callable, optional
        spec -> P(pass) under the user's spreads (:func:`robust_probability`); a
        candidate must reach ``p_min``.
    p_min : float
        Required P(pass) [-].
    horizon : int, optional
        Cycles the transient may take to cross the travel (``betv check --horizon``).

    Returns
    -------
    FixResult
        Candidates ranked (designer's fields first, then the smallest change).

    Over 80 lines on purpose: the search's stages (single fields, deeper values for the
    spread, pairs only when no single field fixes it) share the evaluator, the candidates
    and the counts; its docstring is most of it.
    """
    ev = Evaluator(spec, varies, target_speed_m_s, horizon)
    vmap = {v.field: v for v in varies}
    base = ev({})
    if base.passed and robust is None:
        from betvdesign.checks.checker import check_derivation
        from betvdesign.nondim.device import derive

        kw = {} if horizon is None else {"horizon": horizon}
        whole = check_derivation(derive(spec), target_speed_m_s=target_speed_m_s, **kw)
        improve = _improve(outcome_of(whole))  # the check's own warnings, adequacy too
        msg = "the device already passes" + (
            "; it would still improve: " + ", ".join(i["rule"] for i in improve)
            if improve
            else "; every rule passes"
        )
        return FixResult("already_passes", msg, [], vmap, {}, ev.evaluations, spec, improve)
    cands: list[Candidate] = []
    answers: dict[str, FieldAnswer] = {}
    for v in varies:
        a = nearest(ev, v)
        answers[v.field] = a
        if a.value is not None:
            cands.append(_candidate({v.field: a.value}, a.size, a.outcome, base, [a]))
            if robust is not None:  # deeper into the passing side: the robust optimum
                cands.extend(_deeper(ev, v, a, base))
    blocking = {
        f: {
            "rule": a.blocking or None,
            "bounds_tried": [a.text(a.lo), a.text(a.hi)],
            "failing_counts": a.blocking_counts,
            "message": a.advice(),
        }
        for f, a in answers.items()
        if a.value is None
    }
    if pairs and not cands and len(varies) >= 2:
        near = sorted(varies, key=lambda v: _closeness(answers[v.field]))[:PAIR_FIELDS]
        cands = _pairs(ev, near, base)
    cands.sort(key=_rank)
    if robust is not None:
        for c in cands:
            c.p_pass = robust(ev.spec_at(c.changes))
            if c.p_pass < p_min:
                c.passed = False
                c.why += f"; P(pass) = {c.p_pass:.3f} < {p_min:g} under the spreads"
        cands.sort(key=lambda c: (not c.passed, *_rank(c)))
    best = next((c for c in cands if c.passed), None)
    if best is None:
        why = "; ".join(f"{f}: {b['rule']}" for f, b in blocking.items())
        if robust is not None and cands:
            why = "no passing change keeps P(pass) ≥ p_min under the spreads"
        return FixResult(
            "none",
            f"no change within the bounds passes ({why or 'no candidate'})",
            cands,
            vmap,
            blocking,
            ev.evaluations,
        )
    n = sum(c.passed for c in cands)
    return FixResult(
        "fixed",
        f"{n} passing change(s); best: "
        + ", ".join(f"{f} -> {vmap[f].text(x)}" for f, x in best.changes.items()),
        cands,
        vmap,
        blocking,
        ev.evaluations,
        ev.spec_at(best.changes),
    )


def _candidate(
    changes: dict[str, float],
    size: float,
    out: Outcome | None,
    base: Outcome,
    answers: list[FieldAnswer],
) -> Candidate:
    assert out is not None and out.passed
    return Candidate(
        changes,
        size,
        _mode(out.check),
        _speed(out.check),
        _why(base.failing, out),
        passed=True,
        check=out.check,
        answers=answers,
    )


def _deeper(ev: Evaluator, v: Vary, a: FieldAnswer, base: Outcome) -> list[Candidate]:
    """Passing values further from the boundary.

    Passing values further from the boundary (for the robust search): steps of
    :data:`FIELD_MARGIN` beyond the proposed value, both ways when already passing.
    """
    out = []
    signs = (1, -1) if a.direction == 0 else (a.direction,)
    for sign in signs:
        for k in (1, 2, 4, 8):
            assert a.value is not None
            x = a.value * (1 + FIELD_MARGIN) ** (sign * k)
            if not v.lo <= x <= v.hi:
                break
            o = ev({v.field: x})
            if o.passed:
                out.append(_candidate({v.field: x}, abs(math.log(x / v.x0)), o, base, [a]))
    return out


def _closeness(a: FieldAnswer) -> float:
    """How close a field came: the fewest rules failing at once (lower is closer)."""
    return min(a.blocking_counts.values(), default=0) / max(a.evaluations, 1)


def _pairs(ev: Evaluator, varies: Sequence[Vary], base: Outcome) -> list[Candidate]:
    """Coarse 2-D grids over every pair of fields: passing points, smallest change.

    Screened (:meth:`Evaluator.screen`), every point the screen passes verified by the
    full check; when the screen passes the current design the check fails, the first
    point it fails ends the search (the screen cannot see that failure).
    """
    out = []
    blind = ev.screen({}, known=False).passed and not base.passed
    for a, b in itertools.combinations(varies, 2):
        xa = np.geomspace(a.lo, a.hi, PAIR_POINTS)
        xb = np.geomspace(b.lo, b.hi, PAIR_POINTS)
        for x, y in itertools.product(xa, xb):
            ch = {a.field: float(x), b.field: float(y)}
            o = ev.screen(ch)
            if o.passed:  # the full check verifies what the screen passes
                o = ev(ch)
                if not o.passed and blind:  # the screen cannot see what fails
                    return out
            if o.passed:
                size = math.hypot(math.log(x / a.x0), math.log(y / b.x0))
                out.append(_candidate(ch, size, o, base, []))
    return out


# --- the check's advice: the same search ----------------------------------------------

#: What each failing rule asks of a field: the model parameters it must move (the causal
#: choice of fields to search; the amount and direction come from the search).
_RULE_MOVES = {
    "frequency-window": ("ϖ",),
    "window-margin": ("ϖ",),
    "mode": ("ϖ", "α", "β", "κ"),
    "mode-margin": ("ϖ", "α", "β", "κ"),
    "target-speed": ("ℓ", "ϖ", "α", "β", "κ"),
}


#: Failing rules on what no model parameter carries (the drawn actuator's temperature
#: and thermal bandwidth): the fields that move it, searched in the fields' ranking order
#: (:data:`DEFAULT_BOUNDS`) with those the other failing rules need, when the device gives
#: them (the drive voltage heats it as V²; a longer arm loses more heat to
#: the substrate; a wider hot arm takes a smaller share of the voltage; the drive
#: frequency sets the heating frequency). The search decides which pass.
_RULE_FIELDS = {
    "thermal.peak-temperature": (
        "drive.voltage",
        "actuator.geometry.length",
        "actuator.geometry.hot_arm_width",
    ),
    # the heating frequency against the cut-off: the drive frequency, the arms' heat path
    "thermal.bandwidth": (
        "drive.frequency",
        "actuator.geometry.length",
        "actuator.geometry.hot_arm_width",
    ),
}


def advice_fields(check: Any) -> list[str]:
    """The designer fields a failing check's advice searches, in ranking order.

    Parameters
    ----------
    check : CheckResult
        The check.

    Returns
    -------
    list of str
        Fields of :data:`DEFAULT_BOUNDS` the device gives that move what a failing rule
        needs (:data:`_RULE_FIELDS` for the drawn actuator's temperature, then
        :data:`_RULE_MOVES`), designer's fields (drive, drawing) first.
    """
    from betvdesign.studies.fixfields import current_value

    need: set[str] = set()
    direct: list[str] = []
    for r in check.rules:
        if not r.passed and r.id in _RULE_MOVES:
            need.update(_RULE_MOVES[r.id])
        required = r.severity == "error" or r.id in REQUIRED_WARNINGS
        if not r.passed and required and r.id in _RULE_FIELDS:
            direct += [f for f in _RULE_FIELDS[r.id] if f not in direct]
    spec = check.derivation.spec
    out = [
        f
        for f in DEFAULT_BOUNDS
        if (set(BY_PATH[f].moves) & need or f in direct) and current_value(spec, f) is not None
    ]
    out.sort(key=lambda f: BY_PATH[f].kind not in ("drive setting", "drawn dimension"))
    return out


def advise(
    check: Any,
    *,
    target_speed_m_s: float | None = None,
    fields: Sequence[str] | None = None,
    horizon: int | None = None,
    full: bool = False,
) -> list[FieldAnswer]:
    """The advice of a failing check: the nearest passing value of its fields.

    The same search as ``betv fix`` (:func:`nearest`) over :func:`advice_fields`, until
    :data:`ADVICE_FIXES` fixes are found or :data:`ADVICE_FIELDS` fields are searched.

    Parameters
    ----------
    check : CheckResult
        A check whose verdict fails or one of whose :data:`REQUIRED_WARNINGS` fails.
    target_speed_m_s : float, optional
        The target speed the check was given [m/s].
    fields : sequence of str, optional
        The fields to search (default :func:`advice_fields`).
    horizon : int, optional
        ``betv check --horizon``.
    full : bool
        ``check`` was run as the search's full check runs a candidate (the exact
        solvers, margin corners, transients and determination, the device file's process
        rules; adequacy aside): its outcome is the search's current design, not re-run.

    Returns
    -------
    list of FieldAnswer
        The fields searched, in order ([] when the check passes with its margin).
    """
    if outcome_of(check).passed:
        return []
    spec = check.derivation.spec
    names = list(fields) if fields is not None else advice_fields(check)
    try:
        varies = parse_vary(spec, names[:ADVICE_FIELDS])
    except BetvError:
        return []
    ev = Evaluator(spec, varies, target_speed_m_s, horizon)
    if full:
        ev.cache[()] = outcome_of(check)
    out: list[FieldAnswer] = []
    for v in varies:
        out.append(nearest(ev, v))
        if sum(a.value is not None for a in out) >= ADVICE_FIXES:
            break
    return out


def advice_text(answers: Sequence[FieldAnswer]) -> str:
    """One line of advice from :func:`advise`: the fixes, then the fields that cannot."""
    fixes = [a.advice() for a in sorted(answers, key=_answer_rank) if a.value is not None]
    if not fixes:
        tried = "; ".join(a.advice() for a in answers)
        return (
            f"no single field fixes it ({tried}); `betv fix FILE` also tries pairs"
            if tried
            else "`betv fix FILE` searches the fields"
        )
    return " or ".join(fixes) + " (`betv fix FILE` lists every field)"


def _answer_rank(a: FieldAnswer) -> tuple[int, float]:
    return (0 if a.designer_field else 1, round(a.size, 3))


def with_advice(check: Any, answers: Sequence[FieldAnswer]) -> Any:
    """A copy of ``check`` with the search's fix texts.

    A copy of ``check`` with the fix text of every failing error rule and
    :data:`REQUIRED_WARNINGS` rule (the margins, the thermal bandwidth) replaced by the
    search's answer (:func:`advice_text`), except the process's rules, whose own fix says
    which drawn dimension to set to what (the process decides it).

    Parameters
    ----------
    check : CheckResult
        The check advised (not changed).
    answers : sequence of FieldAnswer
        :func:`advise`'s answers.

    Returns
    -------
    CheckResult
        ``check`` itself when there is no answer, else a new result (its sets too).
    """
    if not answers:
        return check
    from betvdesign.studies.drawnchange import drawn_reach

    text = advice_text(answers)
    window_rule = next((r for r in check.rules if r.id == "frequency-window"), None)
    reach = drawn_reach(check) if window_rule is not None and not window_rule.passed else ""

    def fix(r: Any) -> Any:
        if r.passed or not (r.severity == "error" or r.id in REQUIRED_WARNINGS):
            return r
        if r.id.startswith("process."):  # the process dictates it: the rule's own geometry
            return r
        if r.id == "frequency-window" and reach:  # a drawn device: what its drawing reaches
            return replace(r, fix=f"{text}; {reach}")
        return replace(r, fix=text)

    sets = [replace(sc, rules=[fix(r) for r in sc.rules]) for sc in check.sets]
    return replace(check, rules=[fix(r) for r in check.rules], sets=sets)


# --- robustness under fabrication spread -------------------------------------------------


def robust_probability(
    spec: Any,
    items: Sequence[str],
    *,
    n: int = 400,
    seed: int = 0,
    target_speed_m_s: float | None = None,
) -> Callable[[Any], float]:
    """P(pass) under the spreads ``items``.

    P(pass) under the spreads ``items`` (``betv tolerance`` syntax): the share of a
    seeded Monte Carlo of ``n`` samples in which every set passes every error rule
    (:data:`betvdesign.studies.fixrules.SPREAD_RULES` names them) —
    the frequency window 0.5 ≤ ϖ < 2, the tangential resonance |a·ϖ² − 1| ≥ 0.1, the
    exact mode (the intended one) and the target speed when given
    (:func:`~betvdesign.studies.sampling.passes_spread_rules`, the count ``betv
    tolerance`` prints too). Validates the spreads against ``spec`` now
    (:class:`UsageError`).
    """
    from betvdesign.studies.sampling import draw, nominal_values
    from betvdesign.studies.tolerance import parse_tolerance

    tols = [parse_tolerance(t) for t in items]
    nominal_values(spec, tols)  # unknown or non-numeric fields: UsageError now

    def probability(candidate: Any) -> float:
        from betvdesign.dynamics import periodic_orbit as solver
        from betvdesign.studies.sampling import check_sample, derive_all, passes_spread_rules

        nominal = nominal_values(candidate, tols)
        x = draw(tols, nominal, n, seed)
        sets = candidate.actuator_sets
        arrays = [derive_all(candidate, tols, nominal, x, i) for i in range(len(sets))]
        good = 0
        for j, row in enumerate(x):
            values = {
                t.field: (float(v), nominal[t.field][1]) for t, v in zip(tols, row, strict=True)
            }
            try:
                check_sample(values)
                derived = [_sample_set(candidate, a, i, j, values) for i, a in enumerate(arrays)]
            except (ParameterError, BetvError, ValueError):
                continue  # an unphysical draw counts as a failure
            solved: dict[Any, Any] = {}  # mirrored sets: one orbit
            for (p, length_m, f_act), aset in zip(derived, sets, strict=True):
                if p not in solved:
                    solved[p] = solver(p)
                po = solved[p]
                ds = po.delta_s if po.success else None
                v = None if ds is None else ds * length_m * f_act
                if not passes_spread_rules(p, ds, aset.intended_mode, v, target_speed_m_s):
                    break
            else:
                good += 1
        return good / n

    return probability


def _sample_set(
    spec: Any, arrays: dict[str, Any] | None, i: int, j: int, values: dict[str, Any]
) -> tuple[Any, float, float]:
    """Model parameters and scales of set ``i`` at sample ``j``.

    Model parameters, length scale [m] and f_act [Hz] of set ``i`` at sample ``j``:
    from the vectorised derivation, or by deriving that sample alone.
    """
    from betvdesign.nondim.device import derive_set
    from betvdesign.spec.units import ureg
    from betvdesign.studies.sampling import params_of

    if arrays is not None:
        return params_of(arrays, j), float(arrays["length_m"][j]), float(arrays["f_act_hz"][j])
    q = {f: (ureg.Quantity(v, u) if u else v) for f, (v, u) in values.items()}
    s = with_values(spec, q)
    d = derive_set(s, s.actuator_sets[i])
    return d.params, d.scales.length_m, d.scales.f_act_hz
