"""Design rules as data: each check of a derived design gives a :class:`RuleResult`.

The rules turn docs/MODEL.md, "What the model shows", into checks a designer can act
on. **The mode and the speed always come from the exact periodic orbit** (an object
with ``success``, ``status``, ``message``, ``delta_s``, ``period_cycles``,
``floquet_moduli``, as :class:`betvdesign.dynamics.PeriodicResult`); the paper's λ
fit is shown beside it ("agrees"/"disagrees"), never used for a verdict. Each failed
rule carries a ``fix``: what to change, in the designer's quantities.

Thresholds (one home: :mod:`betvdesign.model.domain`, except the two below):

- frequency window 0.5 ≤ ϖ < 2 (one hit per cycle, finite contact);
- mode: the intended one, |Δs| above round-off (else "stalled");
- mode margin: the exact orbit keeps its mode at ϖ·(1 ± 5 %) and α·(1 ± 10 %)
  (:data:`MARGIN_CORNERS`: ±5 % on the resonance frequency or ±10 % on the tangential
  compliance is a typical fabrication spread);
- tangential resonance |a·ϖ² − 1| ≥ 0.1 for a = α and a = α(1 + 1/β);
- settling: from rest the slider is within 1 % of its periodic Δs before
  :data:`SETTLE_SHARE` of the cycles that cross the travel range are spent;
- speed ≥ the target, when one is given;
- published fit: computed parameters within 10 % of a published value.
"""

from __future__ import annotations

from typing import Any

from betvdesign.checks.ruledata import (
    MARGIN_CORNERS,
    PUBLISHED_RTOL,
    SETTLE_SHARE,
    SRC_LAMBDA,
    SRC_MARGIN,
    SRC_PUBLISHED,
    SRC_SOLVER,
    SRC_TANG,
    SRC_WINDOW,
    OrbitLike,
    RuleResult,
    orbit_mode,
    verdict,
)
from betvdesign.checks.rules_adequacy import adequacy_rule
from betvdesign.checks.rules_motion import format_speed, format_time, speed_rules
from betvdesign.model.domain import (
    FIT_RANGE,
    TANGENTIAL_DETUNING,
    VARPI_IMPULSIVE_END,
    VARPI_WINDOW,
    mode_of,
    outside_fit_range,
    resonance_detuning,
)
from betvdesign.nondim.device import DeviceDerivation, SetDerivation
from betvdesign.output.siformat import format_si

__all__ = [
    "MARGIN_CORNERS",
    "SETTLE_SHARE",
    "RuleResult",
    "evaluate",
    "evaluate_device",
    "format_speed",
    "format_time",
    "mode_hint",
    "orbit_mode",
    "travel_direction",
    "verdict",
]


# --- per-set rules -----------------------------------------------------------------------


def evaluate(
    s: SetDerivation,
    *,
    orbit: OrbitLike | None = None,
    vertical: Any | None = None,
    settling: Any | None = None,
    margin: dict[str, str | None] | None = None,
    target_speed_m_s: float | None = None,
    adequacy: Any | None = None,
) -> list[RuleResult]:
    """Every rule for one actuator set (see the module docstring for thresholds).

    orbit: exact periodic orbit (decides the mode, gives the speed); vertical: exact
    vertical motion (quoted by the window rule); settling: a
    :class:`betvdesign.dynamics.settling.Settling` from rest; margin: mode of the exact
    orbit at each perturbed corner (label -> mode or None); target_speed_m_s: the
    speed the design must reach [m/s] (adds an error rule); adequacy: a
    :class:`betvdesign.checks.adequacy_data.SetAdequacy` (adds ``model-adequacy``).
    """
    out = [
        _frequency_window(s, vertical),
        _mode(s, orbit),
        _lambda(s, orbit),
        *([_margin(s, orbit, margin)] if margin is not None else []),
        _tangential_resonance(s),
        *_published(s),
        *speed_rules(s, orbit, settling, target_speed_m_s),
        *([adequacy_rule(adequacy)] if adequacy is not None else []),
    ]
    return [_with_set(r, s.name) for r in out]


def _with_set(r: RuleResult, name: str) -> RuleResult:
    return RuleResult(
        r.id, r.severity, r.passed, r.value, r.threshold, r.message, r.source, name, r.fix, r.unit
    )


def _hz(f: float) -> str:
    return format_si(f, "Hz")


def _drive_range(s: SetDerivation, lo_varpi: float, hi_varpi: float) -> str:
    """Drive frequencies giving lo ≤ ϖ < hi (ϖ = f_act/f_v; AC doubling applied)."""
    f_v = s.scales.f_act_hz / s.params.varpi
    k = 2.0 if s.actuator_set.drive.doubled else 1.0
    note = " (AC drive: f_act = 2·f_drive)" if k == 2.0 else ""
    return f"{_hz(lo_varpi * f_v / k)}–{_hz(hi_varpi * f_v / k)}{note}"


def _frequency_window(s: SetDerivation, vertical: Any | None = None) -> RuleResult:
    v = s.params.varpi
    lo, hi = VARPI_WINDOW
    f_v = s.scales.f_act_hz / v
    fix = ""
    if v < lo:
        msg = f"ϖ = {v:.3g} below the window: the head hits several times per cycle"
    elif v < hi:
        msg = f"ϖ = {v:.3g} inside the window: one hit per cycle, finite contact"
    elif v < VARPI_IMPULSIVE_END:
        msg = f"ϖ = {v:.3g} above the window: impulsive hits, the slider is not driven"
    else:
        msg = f"ϖ = {v:.3g} far above the window: period doubling or aperiodic hits"
    if not lo <= v < hi:
        fix = (
            f"set drive.frequency within {_drive_range(s, lo, hi)}, or move the head's "
            f"vertical resonance (now {_hz(f_v)}) to {_hz(s.scales.f_act_hz / hi)}–"
            f"{_hz(s.scales.f_act_hz / lo)}; `betv fix` finds the smallest change"
        )
    if vertical is not None and getattr(vertical, "success", False):
        msg += (
            f" [exact vertical motion: {vertical.regime}, {vertical.hits_per_cycle:g} hit(s) "
            f"per cycle ({vertical.impulsive_per_cycle:g} impulsive), in contact "
            f"{vertical.contact_fraction:.0%} of the time]"
        )
    elif vertical is not None:
        msg += f" [exact vertical motion: {getattr(vertical, 'message', '')}]"
    thr = f"{lo:g} <= varpi < {hi:g}"
    return RuleResult("frequency-window", "error", lo <= v < hi, v, thr, msg, SRC_WINDOW, fix=fix)


def mode_hint(intended: str) -> str:
    """Which way to move the designer's fields for ``intended`` (MODEL.md: larger ϖ and
    α favour push; larger β and κ favour pull)."""
    if intended == "push":
        return (
            "toward push: raise ϖ (higher drive frequency, or a lower head vertical resonance) "
            "or α (softer tangential contact), lower β (lighter head, wider or longer slider "
            "beams) or κ (smaller impact angle)"
        )
    return (
        "toward pull: lower ϖ (lower drive frequency) or α (stiffer tangential contact), "
        "raise β (heavier head, narrower or shorter beams) or κ (larger impact angle)"
    )


_STATUS_FIX = {
    "unbounded": "detune the tangential resonance (|α·ϖ² − 1| ≥ 0.1: change the drive "
    "frequency or the horizontal resonance), or give the head's measured damping "
    "(actuator.quality_factor_*): a damped head stays bounded and the rule model-adequacy "
    "gives that finite answer",
    "not_driven": "bring ϖ into 0.5–2 (the head does not stay in contact beyond ϖ ≈ 2)",
    "not_converged": "move away from the window edges or the tangential resonance; "
    "`betv simulate FILE --cycles N` shows the transient",
}


def _mode(s: SetDerivation, orbit: OrbitLike | None) -> RuleResult:
    want = f"intended {s.intended_mode}: Δs {'> 0' if s.intended_mode == 'push' else '< 0'}"
    if orbit is None:
        return RuleResult(
            "mode", "error", False, None, want, "no exact periodic orbit was computed", SRC_SOLVER
        )
    if not getattr(orbit, "success", False):
        status = str(getattr(orbit, "status", "failed"))
        msg = getattr(orbit, "message", "")
        what = {
            "unbounded": "no periodic orbit exists: the head's tangential motion grows "
            "without bound",
            "not_driven": "the slider is not driven: no contact recurs",
            "not_converged": "the exact solver found no periodic orbit within its budget",
        }.get(status, "the exact solver failed")
        fix = _STATUS_FIX.get(status, "report this design; `betv simulate` shows the transient")
        if status == "not_driven" and s.params.restitution > 0.0 and s.params.varpi < 2.0:
            fix = (
                f"with restitution e = {s.params.restitution:g} the rebounds never settle "
                "into contact: lower ϖ (drive frequency; the e the head tolerates rises as ϖ "
                "falls) or the restitution (a softer, more dissipative contact); "
                "`betv fix FILE` finds the change"
            )
        return RuleResult(
            "mode", "error", False, None, want, f"{what} ({status}): {msg}", SRC_SOLVER, fix=fix
        )
    ds = float(orbit.delta_s)
    mode = mode_of(ds)
    k = getattr(orbit, "period_cycles", 1) or 1
    per = f" (mean of a {k}-cycle orbit)" if k > 1 else ""
    if mode == "stalled":
        msg = f"exact periodic orbit: Δs = {ds:.3g} per cycle{per}: the slider does not move"
        fix = mode_hint(s.intended_mode) + "; `betv fix FILE` finds the smallest change"
        return RuleResult("mode", "error", False, ds, want, msg, SRC_SOLVER, fix=fix)
    ok = mode == s.intended_mode
    msg = (
        f"exact periodic orbit: Δs = {ds:.4g} per cycle{per} -> {mode} mode "
        f"(intended {s.intended_mode})"
    )
    fix = "" if ok else mode_hint(s.intended_mode) + "; `betv fix FILE` finds the smallest change"
    return RuleResult("mode", "error", ok, ds, want, msg, SRC_SOLVER, fix=fix)


def _lambda(s: SetDerivation, orbit: OrbitLike | None) -> RuleResult:
    """The paper's λ prediction beside the exact answer (information only)."""
    lam = s.lam
    lam_mode = "push" if lam < 1.0 else "pull"
    exact = orbit_mode(orbit)
    outside = [
        f"{k} = {getattr(s.params, k):.3g} outside {FIT_RANGE[k][0]:g}–{FIT_RANGE[k][1]:g}"
        for k in outside_fit_range(s.params)
    ]
    caveat = f"; λ extrapolates here ({', '.join(outside)})" if outside else ""
    if exact in ("push", "pull"):
        agrees = exact == lam_mode
        word = "agrees" if agrees else "disagrees"
        msg = f"λ = {lam:.3g} predicts {lam_mode}; the exact orbit gives {exact}: {word}{caveat}"
    else:
        agrees = True
        msg = f"λ = {lam:.3g} predicts {lam_mode}; no exact mode to compare{caveat}"
    return RuleResult(
        "lambda", "info", agrees, lam, "λ < 1 push, λ > 1 pull (a fit)", msg, SRC_LAMBDA
    )


def _margin(
    s: SetDerivation, orbit: OrbitLike | None, corners: dict[str, str | None]
) -> RuleResult:
    mode = orbit_mode(orbit)
    thr = "same mode at ϖ·(1 ± 5 %) and α·(1 ± 10 %)"
    if mode not in ("push", "pull"):
        return RuleResult(
            "mode-margin", "warning", False, None, thr, "no exact mode to perturb", SRC_MARGIN
        )
    flips = {k: v for k, v in corners.items() if v != mode}
    ok = not flips
    listing = ", ".join(f"{k}: {v or 'no orbit'}" for k, v in flips.items())
    msg = (
        f"the {mode} mode holds at every corner ({', '.join(corners)})"
        if ok
        else f"the mode changes within fabrication spread ({listing})"
    )
    fix = "" if ok else mode_hint(mode) + " to gain margin; `betv fix FILE` finds the change"
    return RuleResult(
        "mode-margin", "warning", ok, float(len(flips)), thr, msg, SRC_MARGIN, fix=fix
    )


def _tangential_resonance(s: SetDerivation) -> RuleResult:
    label, worst = resonance_detuning(s.params)
    ok = worst >= TANGENTIAL_DETUNING
    zeta_h = s.params.zeta_h
    near = (
        "near tangential resonance: the head's tangential vibration is undamped off "
        "contact and can grow without bound"
        if zeta_h == 0.0
        else f"near tangential resonance: the head's damping (ζ_h = {zeta_h:.3g}, Q_h = "
        f"{1 / (2 * zeta_h):.3g}) keeps it bounded, the mode and speed are the finite "
        "damped orbit's, but its tangential amplitude grows about ∝ Q_h"
    )
    msg = f"min |a·ϖ² − 1| = {worst:.3g} ({label}): " + (
        "tangential head vibration is off resonance" if ok else near
    )
    fix = (
        ""
        if ok
        else "change the drive frequency by ≥ 10 % or the tangential compliance "
        "(actuator.alpha / horizontal resonance) so that |a·ϖ² − 1| ≥ 0.1"
    )
    return RuleResult(
        "tangential-resonance",
        "warning",
        ok,
        worst,
        f"|a·ϖ² − 1| >= {TANGENTIAL_DETUNING:g}",
        msg,
        SRC_TANG,
        fix=fix,
    )


def _published(s: SetDerivation) -> list[RuleResult]:
    out = []
    for c in s.published:
        pub = " or ".join(f"{p:g}" for p in c.published)
        ok = c.matches(PUBLISHED_RTOL)
        closest = min(c.published, key=lambda p: abs(c.computed - p))
        msg = (
            f"computed {c.name} = {c.computed:.3g}, published {pub} "
            f"(closest {closest:g}, {c.rel_diff:.0%} apart)"
        )
        if not ok:
            msg += ": the dimensional data and the published fit disagree"
        out.append(
            RuleResult(
                f"published-fit.{c.name}",
                "warning",
                ok,
                c.computed,
                f"within {PUBLISHED_RTOL:.0%} of {pub}",
                msg,
                SRC_PUBLISHED,
                fix="" if ok else "check the device data against the publication",
            )
        )
    return out


# --- device-level ------------------------------------------------------------------------


def travel_direction(s: SetDerivation, mode: str) -> int:
    """+1/−1: slider travel for a set working in ``mode`` (push: along its impacts)."""
    return s.impact_sign if mode == "push" else -s.impact_sign


def evaluate_device(
    derivation: DeviceDerivation,
    *,
    orbits: dict[str, OrbitLike] | None = None,
    vertical: dict[str, Any] | None = None,
    settling: dict[str, Any] | None = None,
    margins: dict[str, dict[str, str | None]] | None = None,
    target_speed_m_s: float | None = None,
    adequacy: dict[str, Any] | None = None,
) -> list[RuleResult]:
    """Rules of every set (dicts keyed by set name) plus the device rule
    ``bidirectional`` (two or more sets must move the slider both ways)."""
    orbits, vertical, adequacy = orbits or {}, vertical or {}, adequacy or {}
    settling, margins = settling or {}, margins or {}
    out: list[RuleResult] = []
    travel: dict[str, int | None] = {}
    for s in derivation.sets:
        orbit = orbits.get(s.name)
        out.extend(
            evaluate(
                s,
                orbit=orbit,
                vertical=vertical.get(s.name),
                settling=settling.get(s.name),
                margin=margins.get(s.name),
                target_speed_m_s=target_speed_m_s,
                adequacy=adequacy.get(s.name),
            )
        )
        mode = orbit_mode(orbit)
        travel[s.name] = travel_direction(s, mode) if mode in ("push", "pull") else None
    if len(derivation.sets) >= 2:
        dirs = set(travel.values())
        listing = ", ".join(
            f"{k}: {'none' if v is None else '+x' if v > 0 else '-x'}" for k, v in travel.items()
        )
        ok = dirs == {1, -1}
        out.append(
            RuleResult(
                "bidirectional",
                "warning",
                ok,
                None,
                "the sets move the slider both ways",
                f"exact travel per set ({listing})"
                + ("" if ok else ": the sets do not move the slider both ways"),
                "MODEL.md: opposing actuator sets give the two directions of travel",
                fix="" if ok else "give the opposing set the opposite impact direction or mode",
            )
        )
    return out
