"""The head's vertical motion, exactly, and the vertical-only fast path (unit-free).

docs/MODEL.md, "Impacts and separation" and "What the model shows". The vertical
motion does not depend on the slider: free flight ξ'' + ξ = −sin ϖτ (closed form,
resonant ϖ = 1 included), plastic hits (ξ' → 0), contact while sin ϖτ ≥ 0, and
impulsive hits (zero duration) when sin ϖτ < 0 at the hit.

Every contact ends at τ = (2j+1)π/ϖ with ξ = ξ' = 0, so whatever happened
before, the motion after a contact end is the same (shifted by whole cycles):
it is *exactly* periodic from the first contact end, with a period of k cycles
where k is the number of cycles between two contact ends. :class:`VerticalSchedule`
computes the prefix up to the first contact end and one period after it, and
answers "what happens vertically in cycle m" for any m without integrating
again. When no contact recurs within the horizon (only impulsive hits, large ϖ)
there is no period and the slider is not driven.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from betvdesign.dynamics.events import EPS, GapEvent, first_root
from betvdesign.dynamics.flows import oscillator
from betvdesign.errors import ParameterError

TWO_PI = 2.0 * math.pi


@dataclass(slots=True)
class VerticalCycle:
    """What the head does vertically during one actuation cycle [local time t ∈ [0, 2π/ϖ)].

    ``contact_start``: local time of the hit opening a contact (which lasts to π/ϖ),
    or None. ``impulsive``: local times of impulsive hits. ``free``: free-flight
    pieces (t_from, ξ, ξ', sin ϖt_from, cos ϖt_from) for dense output; ``xi0``,
    ``xid0``: state at t = 0 (the Poincaré section).
    """

    xi0: float
    xid0: float
    contact_start: float | None = None
    impulsive: list[float] = field(default_factory=list)
    free: list[tuple[float, float, float, float, float]] = field(default_factory=list)

    def gap(self, varpi: float, t: float) -> tuple[float, float]:
        """(ξ, ξ') at local time t (0 during contact)."""
        te = math.pi / varpi
        if self.contact_start is not None and self.contact_start <= t <= te:
            return 0.0, 0.0
        best = None
        for piece in self.free:
            if piece[0] <= t:
                best = piece
        if best is None:
            return 0.0, 0.0
        t0, xi, xid, sp, cp = best
        y, yd, _, _ = oscillator(1.0, varpi, -1.0, xi, xid, sp, cp, t - t0)
        return y, yd


class VerticalSchedule:
    """Exact vertical motion from (ξ0, ξ0') at τ = 0, cycle by cycle.

    ``prefix``: cycles 0..m1 (m1 = cycle of the first contact end); ``pattern``:
    the k cycles after it, repeated for ever; ``period`` = k or None when no contact
    recurred within the computed horizon (then ``prefix`` holds every computed cycle).
    """

    def __init__(self, varpi: float, xi0: float = 0.0, xid0: float = 0.0, horizon: int = 1000):
        if not (math.isfinite(xi0) and math.isfinite(xid0)) or xi0 < 0.0:
            raise ParameterError(f"vertical state must be finite with ξ ≥ 0, got ({xi0}, {xid0})")
        self.varpi = varpi
        self.T = TWO_PI / varpi
        self.te = math.pi / varpi
        self.prefix: list[VerticalCycle] = []
        self.pattern: list[VerticalCycle] = []
        self.first_end: int | None = None
        self.period: int | None = None
        self.n_root_evals = 0
        self._counter = [0]
        self._table: tuple[np.ndarray, ...] | None = None  # arrays(), built on first use
        self._run(xi0, xid0, horizon)

    # -- construction -------------------------------------------------------------
    def _run(self, xi: float, xid: float, horizon: int) -> None:
        wf, T, te = self.varpi, self.T, self.te
        cycles: list[VerticalCycle] = [VerticalCycle(xi, xid)]
        t, sp, cp = 0.0, 0.0, 1.0
        contact = xi == 0.0 and xid <= 0.0  # a hit at phase 0: contact starts
        if not contact:
            cycles[0].free.append((0.0, xi, xid, sp, cp))
        while True:
            cur = cycles[-1]
            m = len(cycles) - 1
            if contact:
                cur.contact_start = t
                t, xi, xid, sp, cp = te, 0.0, 0.0, 0.0, -1.0
                cur.free.append((te, 0.0, 0.0, 0.0, -1.0))
                contact = False
                if self.first_end is None:
                    self.first_end = m
                else:
                    # From this contact end on, cycle m repeats cycle first_end's
                    # post-contact flight (same state ξ = ξ' = 0 at π/ϖ): copy it, so
                    # the pattern holds the impulsive hits after the separation too.
                    ref = cycles[self.first_end]
                    cur.free.extend(seg for seg in ref.free if seg[0] > te)
                    cur.impulsive.extend(ti for ti in ref.impulsive if ti > te)
                    self.period = m - self.first_end
                    self.prefix = cycles[: self.first_end + 1]
                    self.pattern = cycles[self.first_end + 1 :]
                    break
            H = T - t
            res = first_root(GapEvent(wf, xi, xid, sp, cp, H), H, self._counter)
            if res is None:
                xi, xid, _, _ = oscillator(1.0, wf, -1.0, xi, xid, sp, cp, H)
                xi = max(xi, 0.0)
                limit = horizon if self.first_end is None else self.first_end + 1 + horizon
                if len(cycles) >= limit:
                    self.prefix = cycles
                    break
                cycles.append(VerticalCycle(xi, xid))
                t, sp, cp = 0.0, 0.0, 1.0
                if xi == 0.0 and xid <= 0.0:
                    contact = True
                else:
                    cycles[-1].free.append((0.0, xi, xid, sp, cp))
                continue
            t += res[0]
            if t >= T * (1.0 - 8.0 * EPS):  # hit at the section itself: contact from t = 0
                _, xid, _, _ = oscillator(1.0, wf, -1.0, xi, xid, sp, cp, res[0])
                cycles.append(VerticalCycle(0.0, min(xid, 0.0)))
                t, contact = 0.0, True
                continue
            if t < te:  # sin ϖt ≥ 0 at the hit: contact until π/ϖ
                contact = True
                continue
            sp, cp = math.sin(wf * t), math.cos(wf * t)
            cur.impulsive.append(t)
            xi, xid = 0.0, 0.0
            cur.free.append((t, 0.0, 0.0, sp, cp))
        self.n_root_evals = self._counter[0]

    # -- queries ------------------------------------------------------------------
    def cycle(self, m: int) -> VerticalCycle:
        """Vertical events of cycle m (0-based)."""
        if m < len(self.prefix):
            return self.prefix[m]
        if self.period is None:
            raise IndexError(f"cycle {m} beyond the computed vertical horizon")
        assert self.first_end is not None
        return self.pattern[(m - self.first_end - 1) % self.period]

    def arrays(self, m0: int, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Cycles m0..m0+n−1 as arrays: section state ξ0, ξ0' [-], contact-opening local
        time [-] (NaN: none) and number of impulsive hits; each distinct cycle (prefix
        and one period) is read once, the rest by index."""
        if self._table is None:
            cyc = self.prefix + self.pattern
            tc = [math.nan if c.contact_start is None else c.contact_start for c in cyc]
            self._table = (
                np.array([c.xi0 for c in cyc]),
                np.array([c.xid0 for c in cyc]),
                np.array(tc),
                np.array([len(c.impulsive) for c in cyc], dtype=np.int64),
            )
        m = np.arange(m0, m0 + n)
        k = len(self.prefix)
        if n and m[-1] >= k:
            if self.period is None:
                raise IndexError(f"cycle {m[-1]} beyond the computed vertical horizon")
            m = np.where(m < k, m, k + (m - k) % self.period)
        return tuple(col[m] for col in self._table)  # type: ignore[return-value]

    def hits_per_cycle(self) -> float:
        """Hits (contact starts + impulsive) per cycle over one period (or the horizon)."""
        cyc = self.pattern if self.period else self.prefix
        n = sum(len(c.impulsive) + (c.contact_start is not None) for c in cyc)
        return n / max(len(cyc), 1)

    def contact_fraction(self) -> float:
        """Fraction of time in contact over one period (or the computed horizon)."""
        cyc = self.pattern if self.period else self.prefix
        tc = sum(self.te - c.contact_start for c in cyc if c.contact_start is not None)
        return tc / (self.T * max(len(cyc), 1))


@dataclass(frozen=True, slots=True)
class VerticalResult:
    """Vertical-only answer (no slider): MODEL.md "Vertical motion".

    ``period_cycles``: cycles between contacts once periodic (None: no contact recurs
    within ``n_cycles``); ``hits_per_cycle`` counts contact-opening and impulsive hits;
    ``contact_fraction`` [-] of the time in contact; ``contact_phase`` [rad] ϖτ at the
    contact-opening hit; ``regime``: "single-impact" (the design window: one hit per
    cycle with finite contact), "multi-impact", "period-k", or "impulsive-only".
    """

    varpi: float
    status: str
    success: bool
    message: str
    regime: str
    period_cycles: int | None
    hits_per_cycle: float
    impulsive_per_cycle: float
    contact_fraction: float
    contact_phase: float | None
    n_cycles: int
    n_root_evals: int
    elapsed_s: float


def vertical_motion(varpi: float, *, max_cycles: int = 1000) -> VerticalResult:
    """Vertical motion from rest (the "model no more than a scene needs" fast path).

    varpi: ϖ [-] (> 0, finite); max_cycles: horizon within which a contact must recur.
    """
    return vertical_motion_schedule(varpi, max_cycles=max_cycles)[0]


def vertical_motion_schedule(
    varpi: float, *, max_cycles: int = 1000
) -> tuple[VerticalResult, VerticalSchedule]:
    """:func:`vertical_motion` and the schedule it was read from (for further analysis,
    e.g. the hit phases of impulsive-only motion, without computing it again)."""
    try:
        v = float(varpi)
    except (TypeError, ValueError):
        raise ParameterError(f"varpi must be a number, got {varpi!r}") from None
    if not math.isfinite(v) or v <= 0.0:
        raise ParameterError(f"varpi must be finite and > 0, got {varpi!r}")
    t0 = time.perf_counter()
    vs = VerticalSchedule(v, horizon=max_cycles)
    el = time.perf_counter() - t0
    if vs.period is None:
        imp = vs.hits_per_cycle()
        res = VerticalResult(
            v,
            "not_periodic",
            False,
            f"no contact recurred within {max_cycles} cycles: hits are impulsive only "
            "and the slider is not driven (MODEL.md: ϖ beyond about 2); "
            "increase max_cycles to look further",
            "impulsive-only",
            None,
            imp,
            imp,
            0.0,
            None,
            len(vs.prefix),
            vs.n_root_evals,
            el,
        )
        return res, vs
    k = vs.period
    imp = sum(len(c.impulsive) for c in vs.pattern) / k
    hits = vs.hits_per_cycle()
    if k > 1:
        regime = f"period-{k}"
    elif hits > 1.0:
        regime = "multi-impact"
    else:
        regime = "single-impact"
    tc = next(c.contact_start for c in vs.pattern if c.contact_start is not None)
    assert tc is not None
    res = VerticalResult(
        v,
        "success",
        True,
        f"vertical motion periodic with {k} cycle(s) per period",
        regime,
        k,
        hits,
        imp,
        vs.contact_fraction(),
        v * tc,
        (vs.first_end or 0) + 1 + k,
        vs.n_root_evals,
        el,
    )
    return res, vs
