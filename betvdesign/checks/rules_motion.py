"""Rules about motion along the travel: speed, settling from rest, target speed.

The speed is Δs·u·cosθ·f_act from the exact periodic orbit (MODEL.md, "Displacement
per cycle"), or the mean over the crossing of the travel range from rest when the
slider has not settled by then (:mod:`betvdesign.dynamics.settling`).
"""

from __future__ import annotations

import math
from typing import Any

from betvdesign.checks.ruledata import (
    SETTLE_SHARE,
    SRC_SETTLE,
    SRC_SPEED,
    OrbitLike,
    RuleResult,
    orbit_mode,
)
from betvdesign.nondim.record import SetDerivation
from betvdesign.output.siformat import format_si


def speed_rules(
    s: SetDerivation,
    orbit: OrbitLike | None,
    settling: Any | None,
    target: float | None,
) -> list[RuleResult]:
    """Speed (from the orbit, or from the transient when it has not settled by the time
    it crosses the travel range), the settling rule and the optional target speed."""
    mode = orbit_mode(orbit)
    if mode not in ("push", "pull"):
        why = "the slider does not move" if mode == "stalled" else "no exact periodic orbit"
        out = [RuleResult("speed", "info", False, None, "needs a moving orbit", why, SRC_SPEED)]
        if target is not None:
            out.append(_target(None, target, why))
        return out
    ds = float(orbit.delta_s)
    v_orbit = s.scales.speed_m_s(ds)
    travel = s.travel_range_m
    f = s.scales.f_act_hz
    v, basis, out = v_orbit, "periodic orbit", []
    if settling is not None and getattr(settling, "status", "") != "failed":
        n_cross = settling.cycles_to_cross
        n_settle = settling.settle_cycles  # a lower bound when not settled
        share = n_settle / n_cross if n_cross else math.inf
        ok = share <= SETTLE_SHARE
        settle_txt = (
            f"{n_settle:.4g} cycles ({format_time(n_settle / f)})"
            if settling.cycles_to_settle is not None
            else f"more than {settling.simulated_cycles} cycles (not settled)"
        )
        cross_txt = (
            f"{n_cross} cycles ({format_time(n_cross / f)})"
            if n_cross
            else f"more than {settling.simulated_cycles} cycles"
        )
        out.append(
            RuleResult(
                "settling",
                "warning",
                ok,
                n_settle / f,
                f"settling ≤ {SETTLE_SHARE:.0%} of the cycles to cross the travel range",
                f"from rest: within {settling.rtol:.0%} of the periodic Δs after {settle_txt}; "
                f"crosses the {format_si(travel, 'm')} travel range after {cross_txt}"
                + ("" if ok else ": the periodic speed is not what the travel shows"),
                SRC_SETTLE,
                fix=""
                if ok
                else "quote the crossing speed from rest (the speed rule does), or choose a "
                "design that settles faster (slowest Floquet multiplier |μ| further below 1; "
                "near ϖ → 2 settling slows sharply)",
                unit="s",
            )
        )
        if not ok and settling.crossing_delta_s is not None:
            v = s.scales.speed_m_s(float(settling.crossing_delta_s))
            basis = (
                f"transient from rest over the travel range (periodic: "
                f"{format_speed(abs(v_orbit))})"
            )
    if abs(v) > 0:
        t_cross = travel / abs(v)
        msg = (
            f"mean speed {format_speed(abs(v))} toward {_travel_direction(s, ds)} "
            f"({'with' if ds > 0 else 'against'} the impact direction "
            f"{s.actuator_set.impact_direction}), crosses the {format_si(travel, 'm')} "
            f"travel range in {format_time(t_cross)} [{basis}]"
        )
    else:
        msg = "the slider does not advance over the travel range"
    speed = RuleResult("speed", "info", True, v, "Δs·u·cosθ·f_act", msg, SRC_SPEED, unit="m/s")
    out.insert(0, speed)
    if target is not None:
        out.append(_target(abs(v), target, ""))
    return out


def _target(v: float | None, target: float, why: str) -> RuleResult:
    ok = v is not None and v >= target
    msg = (
        f"speed {format_speed(v)} {'≥' if ok else '<'} target {format_speed(target)}"
        if v is not None
        else f"no speed ({why}); target {format_speed(target)}"
    )
    return RuleResult(
        "target-speed",
        "error",
        ok,
        v,
        f"speed >= {format_speed(target)}",
        msg,
        SRC_SPEED,
        fix=""
        if ok
        else "raise the drive voltage (stroke u) or frequency; `betv fix FILE "
        "--target-speed Q` finds the change",
        unit="m/s",
    )


def _travel_direction(s: SetDerivation, delta_s: float) -> str:
    """Direction the slider travels: Δs is along the set's impact direction."""
    return "+x" if s.impact_sign * (1 if delta_s > 0 else -1) > 0 else "-x"


def format_speed(v_m_s: float) -> str:
    """A speed [m/s] with its SI prefix (:func:`betvdesign.output.siformat.format_si`)."""
    return format_si(v_m_s, "m/s")


def format_time(t_s: float) -> str:
    """A duration [s] with its SI prefix (:func:`betvdesign.output.siformat.format_si`)."""
    return format_si(t_s, "s")
