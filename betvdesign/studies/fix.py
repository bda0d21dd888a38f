"""``betv fix``: the smallest change to a device file that makes it pass, with margin.

Every candidate goes through the same path as ``betv check``: spec (one field
changed) -> :func:`betvdesign.nondim.device.derive` -> exact periodic orbit -> rules
(:func:`betvdesign.checks.checker.check_derivation`). There is no separate model.

A candidate **passes** when every error-severity rule passes (window, intended mode,
target speed when given), the tangential-resonance distance holds and the slider
settles (within 1 % of its periodic Δs) before it has crossed its travel range; the
chosen value must also lie at least :data:`FIELD_MARGIN` (relative) inside the
passing interval of the field, and its full check must also pass the exact
mode-margin corners (ϖ ± 5 %, α ± 10 %).

Search: one field at a time (log-spaced scan over its bounds, passing intervals
refined by bisection, the point nearest the current value that keeps the margin),
then, only if no single field works, pairs of the :data:`PAIR_FIELDS` fields that
came closest, on a coarse 2-D grid. The change is measured as |ln(x/x0)| (in
quadrature for pairs); changes equal to 0.01 in that measure rank operating fields
(drive) before geometry (the order of :data:`DEFAULT_BOUNDS`). With tolerances
(``tol``), each passing candidate is also run through a Monte Carlo of the spreads
and must keep P(intended mode) ≥ ``p_min``; moving further into the passing
interval is tried before a candidate is given up (the robust optimum).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from betvdesign.errors import BetvError, ParameterError
from betvdesign.spec.paths import with_values
from betvdesign.studies.fixfields import DEFAULT_BOUNDS, Vary, parse_vary

__all__ = ["DEFAULT_BOUNDS", "FIELD_MARGIN", "Vary", "find_fixes", "parse_vary"]

#: Relative distance a chosen value keeps from the edge of its passing interval.
FIELD_MARGIN = 0.05
#: Scan points per field and bisection steps per interval edge.
SCAN_POINTS = 31
BISECT_STEPS = 9
PAIR_POINTS = 9
#: Pairs are searched among this many fields, those that came closest on their own.
PAIR_FIELDS = 4


@dataclass
class Candidate:
    """One proposed change and what the exact check says of it."""

    changes: dict[str, float]
    size: float
    mode: str | None
    speed_m_s: float | None
    margin: float
    why: str
    passed: bool = False
    check: Any = None
    p_intended: float | None = None
    blocking: list[str] = field(default_factory=list)

    def as_dict(self, varies: dict[str, Vary]) -> dict[str, Any]:
        return {
            "changes": [
                {
                    "field": f,
                    "from": varies[f].text(varies[f].x0),
                    "to": varies[f].text(x),
                    "relative_change": x / varies[f].x0 - 1.0,
                }
                for f, x in self.changes.items()
            ],
            "size": self.size,
            "mode": self.mode,
            "speed_m_s": self.speed_m_s,
            "margin": self.margin,
            "p_intended": self.p_intended,
            "passed": self.passed,
            "why": self.why,
        }


@dataclass
class FixResult:
    """Outcome of :func:`find_fixes`: ``status`` "already_passes", "fixed" or "none"."""

    status: str
    message: str
    candidates: list[Candidate]
    varies: dict[str, Vary]
    blocking: dict[str, str]
    evaluations: int
    best_spec: Any = None

    @property
    def best(self) -> Candidate | None:
        return next((c for c in self.candidates if c.passed), None)

    def as_dict(self) -> dict[str, Any]:
        return {
            "status": self.status,
            "message": self.message,
            "evaluations": self.evaluations,
            "varied": {
                f: {"from": v.text(v.x0), "lo": v.text(v.lo), "hi": v.text(v.hi)}
                for f, v in self.varies.items()
            },
            "candidates": [c.as_dict(self.varies) for c in self.candidates],
            "blocking": self.blocking,
        }


# --- evaluation ------------------------------------------------------------------------


class Evaluator:
    """Checks candidate specs through the same path as ``betv check`` (cached)."""

    def __init__(self, spec: Any, varies: Sequence[Vary], target_speed_m_s: float | None):
        self.spec = spec
        self.varies = {v.field: v for v in varies}
        self.target = target_speed_m_s
        self.cache: dict[tuple[tuple[str, float], ...], tuple[bool, list[str], Any]] = {}
        self.evaluations = 0

    def spec_at(self, changes: dict[str, float]) -> Any:
        return with_values(self.spec, {f: self.varies[f].quantity(x) for f, x in changes.items()})

    def quick(self, changes: dict[str, float]) -> tuple[bool, list[str], Any]:
        """(passes, failing rule ids, check) without the margin corners and settling
        (both are required of every candidate by :meth:`full`)."""
        key = tuple(sorted(changes.items()))
        if key not in self.cache:
            self.cache[key] = self._run(changes, full=False)
        return self.cache[key]

    def full(self, changes: dict[str, float]) -> tuple[bool, list[str], Any]:
        """The complete check; also requires the mode-margin, settling and
        tangential-resonance warnings to pass."""
        return self._run(changes, full=True)

    def _run(self, changes: dict[str, float], *, full: bool) -> tuple[bool, list[str], Any]:
        from betvdesign.checks.checker import check_derivation
        from betvdesign.nondim.device import derive
        from betvdesign.studies.sampling import check_sample

        self.evaluations += 1
        try:
            check_sample({f: (x, self.varies[f].unit) for f, x in changes.items()})
            res = check_derivation(
                derive(self.spec_at(changes)),
                margin=full,
                settle=full,
                target_speed_m_s=self.target,
                adequacy=False,  # not a criterion of the search (fixfile's check has it)
            )
        except (ParameterError, BetvError, ValueError) as exc:
            return False, [f"invalid: {exc}"], None
        need = {"tangential-resonance"} | ({"mode-margin"} if full else set())
        failing = [
            r.id for r in res.rules if not r.passed and (r.severity == "error" or r.id in need)
        ]
        for sc in res.sets:  # the slider must settle before it has crossed its travel
            st = sc.settling
            if st is not None and getattr(st, "cycles_to_cross", None):
                if st.cycles_to_settle is None or st.cycles_to_settle > st.cycles_to_cross:
                    failing.append("settling")
        return not failing, sorted(set(failing)), res


def _speed(check: Any) -> float | None:
    speeds = [abs(v) for sc in check.sets if (v := sc.speed_m_s) is not None]
    return min(speeds) if speeds else None


def _mode(check: Any) -> str | None:
    modes = {sc.mode for sc in check.sets}
    return modes.pop() if len(modes) == 1 else ", ".join(sorted(str(m) for m in modes))


# --- one field ---------------------------------------------------------------------------


def _intervals(xs: np.ndarray, ok: np.ndarray) -> list[tuple[int, int]]:
    """Index ranges [i, j] of consecutive passing scan points."""
    out, start = [], None
    for i, good in enumerate(ok):
        if good and start is None:
            start = i
        if not good and start is not None:
            out.append((start, i - 1))
            start = None
    if start is not None:
        out.append((start, len(ok) - 1))
    return out


def _edge(ev: Evaluator, name: str, good: float, bad: float) -> float:
    """Bisect (in log) between a passing and a failing value: the last passing one."""
    for _ in range(BISECT_STEPS):
        mid = math.sqrt(good * bad)
        if ev.quick({name: mid})[0]:
            good = mid
        else:
            bad = mid
    return good


def single_field(ev: Evaluator, v: Vary) -> tuple[list[tuple[float, float, float]], str, float]:
    """Passing intervals of one field as (lo, hi, chosen value nearest x0 with margin),
    nearest first; the rule that blocks most often where it fails; and how close the
    field came (the fewest failing rules over the scan, for choosing pairs)."""
    xs = np.geomspace(v.lo, v.hi, SCAN_POINTS)
    res = [ev.quick({v.field: float(x)}) for x in xs]
    ok = np.array([r[0] for r in res])
    fails = [rid for r in res if not r[0] for rid in r[1]]
    blocking = max(set(fails), key=fails.count) if fails else ""
    closest = min(len(r[1]) for r in res) + _shortfall(ev, res)
    out = []
    for i, j in _intervals(xs, ok):
        lo = xs[i] if i == 0 else _edge(ev, v.field, float(xs[i]), float(xs[i - 1]))
        hi = xs[j] if j == len(xs) - 1 else _edge(ev, v.field, float(xs[j]), float(xs[j + 1]))
        a, b = lo * (1 + FIELD_MARGIN), hi / (1 + FIELD_MARGIN)
        if a > b:  # narrower than twice the margin: no robust point
            continue
        x = min(max(v.x0, a), b)
        out.append((float(lo), float(hi), float(x)))
    out.sort(key=lambda t: abs(math.log(t[2] / v.x0)))
    return out, blocking, closest


def _shortfall(ev: Evaluator, res: list[tuple[bool, list[str], Any]]) -> float:
    """In [0, 1): how far the best scan point stays from the intended mode and the
    target speed (0: reached), as a tie-break between fields with equal rule counts."""
    best = 1.0
    for _, _, check in res:
        if check is None:
            continue
        worst = 0.0
        for sc in check.sets:
            ds = getattr(sc.periodic, "delta_s", None) if sc.mode else None
            if ds is None:
                worst = max(worst, 0.99)
                continue
            want = 1.0 if sc.derivation.intended_mode == "push" else -1.0
            worst = max(worst, 0.5 - 0.5 * math.tanh(want * ds))
        best = min(best, worst)
    return min(best, 0.999)


def _inward(x0: float, lo: float, hi: float, x: float) -> list[float]:
    """The nearest point with margin, then points a quarter and half way into the
    interval from that end (tried in turn when the full check, with its mode-margin
    corners and settling, rejects the nearer one)."""
    far = hi if abs(math.log(x / lo)) < abs(math.log(hi / x)) else lo
    out = [x]
    for frac in (0.25, 0.5):
        y = math.exp(math.log(x) + frac * (math.log(far) - math.log(x)))
        if all(abs(math.log(y / z)) > 1e-3 for z in out):
            out.append(y)
    return out


def _why(before: list[str], check: Any) -> str:
    """What a passing candidate does: the rules it fixes, its exact mode and speed."""
    from betvdesign.checks.rule import format_speed

    speed = _speed(check)
    parts = [f"fixes {', '.join(before)}" if before else "keeps every rule passing"]
    parts.append(f"exact mode {_mode(check)}")
    if speed is not None:
        parts.append(f"speed {format_speed(speed)}")
    return "; ".join(parts)


def find_fixes(
    spec: Any,
    varies: Sequence[Vary],
    *,
    target_speed_m_s: float | None = None,
    pairs: bool = True,
    robust: Callable[[Any], float] | None = None,
    p_min: float = 0.99,
    max_candidates: int = 12,
) -> FixResult:
    """Search the smallest passing change (see the module docstring).

    robust: spec -> P(intended mode) under the user's spreads (a Monte Carlo); a
    candidate must reach ``p_min``.
    """
    ev = Evaluator(spec, varies, target_speed_m_s)
    vmap = {v.field: v for v in varies}
    ok0, failing0, _ = ev.full({})
    if ok0 and robust is None:
        return FixResult("already_passes", "the device already passes", [], vmap, {}, 1, spec)
    cands: list[Candidate] = []
    blocking: dict[str, str] = {}
    closeness: dict[str, float] = {}
    for v in varies:
        intervals, block, closeness[v.field] = single_field(ev, v)
        if not intervals:
            blocking[v.field] = block or "no passing value within the bounds"
        for lo, hi, x in intervals:
            for x_try in _inward(v.x0, lo, hi, x):
                margin = min(math.log(x_try / lo), math.log(hi / x_try))
                cands.append(
                    Candidate({v.field: x_try}, abs(math.log(x_try / v.x0)), None, None, margin, "")
                )
    if pairs and not cands and len(varies) >= 2:
        near = sorted(varies, key=lambda v: closeness[v.field])[:PAIR_FIELDS]
        cands = _pairs(ev, near)
    order = {f: i for i, f in enumerate(DEFAULT_BOUNDS)}  # ties: operating fields first
    cands.sort(key=lambda c: (round(c.size, 2), min(order.get(f, 99) for f in c.changes)))
    verified: list[Candidate] = []
    for c in cands:
        if len(verified) >= max_candidates or (robust and sum(v.passed for v in verified) >= 2):
            break
        c = _verify(ev, c, failing0, robust, p_min)
        verified.append(c)
    verified.sort(
        key=lambda c: (not c.passed, round(c.size, 2), min(order.get(f, 99) for f in c.changes))
    )
    best = verified[0] if verified and verified[0].passed else None
    if best is None:
        why = "; ".join(f"{f}: {b}" for f, b in blocking.items()) or "no candidate verified"
        return FixResult(
            "none",
            f"no change within the bounds passes ({why})",
            verified,
            vmap,
            blocking,
            ev.evaluations,
        )
    return FixResult(
        "fixed",
        f"{len([c for c in verified if c.passed])} passing change(s); best: "
        + ", ".join(f"{f} -> {vmap[f].text(x)}" for f, x in best.changes.items()),
        verified,
        vmap,
        blocking,
        ev.evaluations,
        ev.spec_at(best.changes),
    )


def _verify(
    ev: Evaluator,
    c: Candidate,
    failing0: list[str],
    robust: Callable[[Any], float] | None,
    p_min: float,
) -> Candidate:
    ok, failing, check = ev.full(c.changes)
    c.passed, c.blocking, c.check = ok, failing, check
    if check is not None:
        c.mode, c.speed_m_s = _mode(check), _speed(check)
        c.why = _why(failing0, check)
    if not ok:
        c.why = f"fails the full check: {', '.join(failing)}"
        return c
    if robust is not None:
        c.p_intended = robust(ev.spec_at(c.changes))
        if c.p_intended < p_min:
            c.passed = False
            c.why += f"; P(intended mode) = {c.p_intended:.3f} < {p_min:g} under the spreads"
    return c


def _pairs(ev: Evaluator, varies: Sequence[Vary]) -> list[Candidate]:
    """Coarse 2-D grids over every pair of fields: passing points, smallest change."""
    out = []
    for a, b in itertools.combinations(varies, 2):
        xa = np.geomspace(a.lo, a.hi, PAIR_POINTS)
        xb = np.geomspace(b.lo, b.hi, PAIR_POINTS)
        for x, y in itertools.product(xa, xb):
            ch = {a.field: float(x), b.field: float(y)}
            if ev.quick(ch)[0]:
                size = math.hypot(math.log(x / a.x0), math.log(y / b.x0))
                out.append(Candidate(ch, size, None, None, 0.0, ""))
    return out


# --- robustness under fabrication spread -------------------------------------------------


def robust_probability(
    spec: Any, items: Sequence[str], *, n: int = 400, seed: int = 0
) -> Callable[[Any], float]:
    """P(every set in its intended mode) under the spreads ``items`` (``betv tolerance``
    syntax), by a seeded Monte Carlo of ``n`` exact orbits per candidate. Validates the
    spreads against ``spec`` now (:class:`UsageError`)."""
    from betvdesign.studies.sampling import draw, nominal_values
    from betvdesign.studies.tolerance import parse_tolerance

    tols = [parse_tolerance(t) for t in items]
    nominal_values(spec, tols)  # unknown or non-numeric fields: UsageError now

    def probability(candidate: Any) -> float:
        from betvdesign.checks.checker import load_solver
        from betvdesign.model.domain import mode_of
        from betvdesign.model.params import ModelParams
        from betvdesign.studies.sampling import check_sample, derive_all

        solver = load_solver()
        nominal = nominal_values(candidate, tols)
        x = draw(tols, nominal, n, seed)
        sets = candidate.actuator_sets
        # every sample of every set derived at once, as in `betv tolerance`
        arrays = [derive_all(candidate, tols, nominal, x, i) for i in range(len(sets))]
        good = 0
        for j, row in enumerate(x):
            values = {
                t.field: (float(v), nominal[t.field][1]) for t, v in zip(tols, row, strict=True)
            }
            try:
                check_sample(values)
                params = [_sample_params(candidate, a, i, j, values) for i, a in enumerate(arrays)]
            except (ParameterError, BetvError, ValueError):
                continue  # an unphysical draw counts as a failure
            solved: dict[ModelParams, str | None] = {}  # mirrored sets: one orbit
            for p, aset in zip(params, sets, strict=True):
                if p not in solved:
                    po = solver(p)
                    solved[p] = mode_of(po.delta_s) if po.success else None
                if solved[p] != aset.intended_mode:
                    break
            else:
                good += 1
        return good / n

    return probability


def _sample_params(
    spec: Any, arrays: dict[str, Any] | None, i: int, j: int, values: dict[str, Any]
) -> Any:
    """Model parameters of set ``i`` at sample ``j``: from the vectorised derivation, or
    (when it could not take every sample) by deriving that sample alone."""
    from betvdesign.nondim.device import derive_set
    from betvdesign.spec.units import ureg
    from betvdesign.studies.sampling import params_of

    if arrays is not None:
        return params_of(arrays, j)
    q = {f: (ureg.Quantity(v, u) if u else v) for f, (v, u) in values.items()}
    s = with_values(spec, q)
    return derive_set(s, s.actuator_sets[i]).params
