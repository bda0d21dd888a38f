"""Design rules as data: each check of a derived design gives a :class:`RuleResult`.

The rules turn docs/MODEL.md, "What the model shows", into checks a designer can act
on. **The mode and the speed always come from the exact periodic orbit** (a
:class:`betvdesign.dynamics.PeriodicResult`, or the checker's failure stand-in, which
has ``success`` False and says why); the paper's λ fit is shown beside it
("agrees"/"disagrees"), never used for a verdict. Each failed rule carries a ``fix``:
what to change, in the designer's quantities.

Thresholds (one home: :mod:`betvdesign.model.domain`, except the ones defined here):

- frequency window 0.5 ≤ ϖ < 2 (one hit per cycle, finite contact), its edges to
  round-off (the lower inside, the upper outside:
  :func:`~betvdesign.model.domain.window_position`);
- window margin (warning): the window holds at ϖ·(1 ± 5 %) (:data:`WINDOW_MARGIN`, the
  spread of the mode's corners), else the distance to the edge is named;
- mode: the intended one, |Δs| above round-off (else "stalled"); from the answer the
  travel quotes (:mod:`betvdesign.checks.travel`: the orbit, or the crossing from rest
  whenever there is no periodic answer or it is not reached over the travel);
- mode margin: the quoted mode holds at ϖ·(1 ± 5 %) and α·(1 ± 10 %)
  (:data:`MARGIN_CORNERS`: ±5 % on the resonance frequency or ±10 % on the tangential
  compliance is a typical fabrication spread), each corner read on the same basis as
  the headline (its orbit, or its crossing from rest); a flip near a sub-resonance
  α·ϖ² = 1/n² (f_act = f_h/n) names it;
- tangential resonance |a·ϖ² − 1| ≥ 0.1 for a = α and a = α(1 + 1/β);
- speed Δs·u·cosθ·f_act from the exact orbit (MODEL.md, "Displacement per cycle"), or
  the mean over the crossing of the travel range from rest when the slider has not
  settled by then (:mod:`betvdesign.dynamics.settling`);
- settling: from rest the slider is within 1 % of its periodic Δs before
  :data:`SETTLE_SHARE` of the cycles that cross the travel range are spent;
- speed ≥ the target, when one is given;
- published fit: computed parameters within :data:`PUBLISHED_RTOL` (10 %) of a published
  value;
- model adequacy (:func:`adequacy_rule`, from :mod:`betvdesign.checks.adequacy`): info
  when the idealised model's mode holds with the device's (or plausible default) head
  damping and restitution and throughout the likely bands of Q and e; warning when the
  mode flips within them, or when the idealised model has no periodic orbit while the
  richer one has (e.g. unbounded tangential growth at α·ϖ² = 1 without damping);
- device: two or more sets move the slider both ways (``bidirectional``).

References
----------
.. [1] Shin, Pai, Lin, Hui and Tien, J. Appl. Phys. 96, 7603 (2004),
   doi:10.1063/1.1809773 (the window 0.5 ≤ ϖ < 2, the λ criterion of eq. 9, the
   displacement per cycle).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from betvdesign.checks.adequacy import LIKELY_QUALITY, LIKELY_RESTITUTION, SetAdequacy
from betvdesign.checks.rule import (
    SEARCH_HINT,
    OrbitLike,
    RuleResult,
    format_speed,
    format_time,
    no_crossing,
    orbit_mode,
    travel_axis,
    travel_direction,
)
from betvdesign.checks.travel import SETTLE_SHARE, TravelAnswer, travel_answer
from betvdesign.checks.window import (
    SRC_WINDOW,
    WINDOW_MARGIN,
    format_varpi,
    frequency_window,
    window_margin,
)
from betvdesign.model.domain import (
    FIT_RANGE,
    TANGENTIAL_DETUNING,
    mode_of,
    nearest_subresonance,
    outside_fit_range,
    resonance_detuning,
)
from betvdesign.nondim.record import DeviceDerivation, SetDerivation
from betvdesign.output.siformat import format_si

if TYPE_CHECKING:
    from betvdesign.dynamics import VerticalResult
    from betvdesign.dynamics.settling import Settling

__all__ = [
    "MARGIN_CORNERS",
    "PUBLISHED_RTOL",
    "SEARCH_HINT",
    "SETTLE_SHARE",
    "SRC_ADEQUACY",
    "SRC_DETERMINATION",
    "SRC_LAMBDA",
    "SRC_MARGIN",
    "SRC_PUBLISHED",
    "SRC_SETTLE",
    "SRC_SOLVER",
    "SRC_SPEED",
    "SRC_TANG",
    "SRC_WINDOW",
    "WINDOW_MARGIN",
    "adequacy_rule",
    "evaluate",
    "evaluate_device",
    "format_varpi",
    "speed_rules",
    "time_to_cross_s",
]

#: Relative distance [-] within which a computed parameter matches a published one.
PUBLISHED_RTOL = 0.1
#: Relative perturbations of (ϖ, α) the mode must survive (fabrication spread).
MARGIN_CORNERS: tuple[tuple[float, float], ...] = (
    (1.0 - WINDOW_MARGIN, 1.0),
    (1.0 + WINDOW_MARGIN, 1.0),
    (1.0, 0.9),
    (1.0, 1.1),
)


def corner_label(f_varpi: float, f_alpha: float) -> str:
    """The label of a margin corner (``ϖ×0.95``, ``α×1.1``) from its factors [-]."""
    return f"ϖ×{f_varpi:g}" if f_alpha == 1.0 else f"α×{f_alpha:g}"


SRC_LAMBDA = "MODEL.md, Push/pull criterion (empirical fit, Shin et al. 2004, eq. 9)"
SRC_TANG = "MODEL.md, What the model shows: tangential vibration undamped off contact"
SRC_SPEED = "MODEL.md, Displacement per cycle: speed = Δs·u·cosθ·f_act"
SRC_PUBLISHED = "device file: published_fit"
SRC_SOLVER = "betvdesign.dynamics.periodic_orbit (exact event-driven solver, shooting)"
SRC_SETTLE = "betvdesign.dynamics.settling (exact transient from rest, MODEL.md: Slider)"
SRC_DETERMINATION = (
    "betvdesign.dynamics.determination (periodic re-solves with every parameter moved by "
    "1e-12; forces below round-off named before solving)"
)
#: What to change when the slider does not cross its travel within the horizon.
NO_CROSSING_FIX = (
    "choose a design that moves and settles faster (friction κ and the mass ratio β not near "
    "0, |α·ϖ² − 1| not small without damping), or raise the horizon (`betv check --horizon "
    "N`) if the travel really takes that long"
)
SRC_MARGIN = "exact periodic orbits at ϖ·(1 ± 5 %) and α·(1 ± 10 %) (fabrication spread)"
SRC_ADEQUACY = (
    "betvdesign.checks.adequacy: exact periodic orbits without and with head damping and "
    "restitution, Q and e scanned (MODEL.md, Beyond the paper's idealisation)"
)


# --- per-set rules -----------------------------------------------------------------------


def evaluate(
    s: SetDerivation,
    *,
    orbit: OrbitLike | None = None,
    vertical: VerticalResult | None = None,
    settling: Settling | None = None,
    margin: dict[str, str | None] | None = None,
    target_speed_m_s: float | None = None,
    adequacy: SetAdequacy | None = None,
    travel: TravelAnswer | None = None,
) -> list[RuleResult]:
    """Every rule for one actuator set (the module docstring gives the thresholds).

    Parameters
    ----------
    s : SetDerivation
        The derived actuator set.
    orbit : OrbitLike, optional
        Its exact periodic orbit (decides the mode, gives the speed).
    vertical : VerticalResult, optional
        Its exact vertical motion (quoted by the window rule), or a failure stand-in
        (``success`` False, ``message``).
    settling : Settling, optional
        The transient from rest (:func:`betvdesign.dynamics.settling.settling`), or a
        failure stand-in with ``status`` "failed" (then ignored).
    margin : dict, optional
        Mode of the exact orbit at each perturbed corner (label -> mode or None); adds
        the rule ``mode-margin``.
    target_speed_m_s : float, optional
        The speed the design must reach [m/s]; adds the error rule ``target-speed``.
    adequacy : SetAdequacy, optional
        The set's model adequacy (:mod:`betvdesign.checks.adequacy`); adds the rule
        ``model-adequacy``.
    travel : TravelAnswer, optional
        The answer the verdict quotes (:func:`betvdesign.checks.travel.travel_answer`:
        the orbit, or the crossing of the travel from rest, or none); None chooses it
        from ``orbit`` and ``settling`` with Δs read as exact.

    Returns
    -------
    list of RuleResult
        In a fixed order: window, window margin (inside the window only), mode, λ,
        margin, tangential resonance, published fit,
        speed, settling, target speed, model adequacy; ``set_name`` is ``s.name``.

    References
    ----------
    .. [1] Shin, Pai, Lin, Hui and Tien, J. Appl. Phys. 96, 7603 (2004),
       doi:10.1063/1.1809773.
    """
    margin_of_window = window_margin(s)
    out = [
        frequency_window(s, vertical),
        *([margin_of_window] if margin_of_window is not None else []),
        _mode(s, orbit, travel),
        _lambda(s, orbit),
        *([_margin(s, orbit, margin, travel)] if margin is not None else []),
        _tangential_resonance(s),
        *_published(s),
        *speed_rules(s, orbit, settling, target_speed_m_s, travel),
        *([adequacy_rule(adequacy)] if adequacy is not None else []),
    ]
    return [_with_set(r, s.name) for r in out]


def _with_set(r: RuleResult, name: str) -> RuleResult:
    return RuleResult(
        r.id, r.severity, r.passed, r.value, r.threshold, r.message, r.source, name, r.fix, r.unit
    )


def _near_subresonance(s: SetDerivation, flips: dict[str, str | None]) -> str:
    """The sub-resonance a margin flip sits near, as a clause of the rule's message.

    ``; near the sub-resonance α·ϖ² = 1/4 (f_act = f_h/2 = 3.65 kHz)`` when the design
    and its flipping corners lie near one (:func:`~betvdesign.model.domain.
    nearest_subresonance`), else "".
    """
    p = s.params
    q0 = p.alpha * p.varpi**2
    at = {corner_label(fw, fa): fa * fw * fw for fw, fa in MARGIN_CORNERS}
    n = nearest_subresonance([q0, *(q0 * at[k] for k in flips if k in at)])
    if n is None:
        return ""
    f = s.scales.f_act_hz / (n * math.sqrt(q0))
    if n == 1:
        return f"; near the tangential resonance α·ϖ² = 1 (f_act = f_h = {format_si(f, 'Hz')})"
    return f"; near the sub-resonance α·ϖ² = 1/{n * n} (f_act = f_h/{n} = {format_si(f, 'Hz')})"


def _margin_cause(flips: dict[str, str | None]) -> str:
    """The corners where the mode changes (read off the check, no advice)."""
    return ", ".join(f"{k} gives {v or 'no orbit'}" for k, v in flips.items())


_STATUS_FIX = {
    "unbounded": "detune the tangential resonance (|α·ϖ² − 1| ≥ 0.1: change the drive "
    "frequency or the horizontal resonance), or give the head's measured damping "
    "(actuator.quality_factor_*): a damped head stays bounded and the rule model-adequacy "
    "gives that finite answer",
    "not_driven": "bring ϖ into 0.5–2 (the head does not stay in contact beyond ϖ ≈ 2)",
    "not_converged": "move away from the window edges or the tangential resonance; "
    "`betv simulate FILE --cycles N` shows the transient",
}


def _mode(s: SetDerivation, orbit: OrbitLike | None, travel: TravelAnswer | None) -> RuleResult:
    want = f"intended {s.intended_mode}: Δs {'> 0' if s.intended_mode == 'push' else '< 0'}"
    if travel is not None and travel.basis in ("undetermined", "no-crossing", "crossing"):
        return _travel_mode(s, travel, want)
    if orbit is None:
        return RuleResult(
            "mode", "error", False, None, want, "no exact periodic orbit was computed", SRC_SOLVER
        )
    if not orbit.success:
        status = str(orbit.status)
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
            "mode",
            "error",
            False,
            None,
            want,
            f"{what} ({status}): {orbit.message}",
            SRC_SOLVER,
            fix=fix,
        )
    ds = float(orbit.delta_s)
    mode = mode_of(ds)
    k = 1 if orbit.period_cycles is None else orbit.period_cycles  # a PeriodicResult
    per = f" (mean of a {k}-cycle orbit)" if k > 1 else ""
    if mode == "stalled":
        msg = f"exact periodic orbit: Δs = {ds:.3g} per cycle{per}: the slider does not move"
        fix = SEARCH_HINT
        return RuleResult("mode", "error", False, ds, want, msg, SRC_SOLVER, fix=fix)
    ok = mode == s.intended_mode
    msg = (
        f"exact periodic orbit: Δs = {ds:.4g} per cycle{per} -> {mode} mode "
        f"(intended {s.intended_mode})"
    )
    fix = "" if ok else SEARCH_HINT
    return RuleResult("mode", "error", ok, ds, want, msg, SRC_SOLVER, fix=fix)


def _travel_mode(s: SetDerivation, ans: TravelAnswer, want: str) -> RuleResult:
    """The mode rule when the periodic orbit is not the answer.

    The mode rule when the periodic orbit is not the answer (:mod:`betvdesign.checks.
    travel`): Δs undetermined, no crossing of the travel, or the crossing from rest.
    """
    travel = format_si(s.travel_range_m, "m")
    f = s.scales.f_act_hz
    periodic = ans.delta_s_periodic
    if ans.basis == "undetermined":
        return RuleResult(
            "mode",
            "error",
            False,
            None,
            want,
            f"mode undetermined: {ans.reason}",
            SRC_DETERMINATION,
            fix=ans.fix,
        )
    if ans.basis == "no-crossing":
        n = ans.horizon_cycles or 0
        if ans.mode == "undetermined":
            shown = "the periodic Δs is not determined"
        elif periodic is not None:
            shown = (
                f"periodic orbit: Δs = {periodic:.4g} per cycle ({mode_of(periodic)}), not "
                "reached over the travel"
            )
        else:
            shown = ans.reason.split(" and the transient")[0]  # "no periodic orbit (…)"

        return RuleResult(
            "mode",
            "error",
            False,
            None,
            want,
            f"{no_crossing(s.travel_range_m, n, f)} from rest ({shown})",
            SRC_SETTLE,
            fix=NO_CROSSING_FIX,
        )
    ds = float(ans.delta_s)
    mode = ans.mode
    ok = mode == s.intended_mode
    if periodic is not None and mode_of(periodic) in ("push", "pull"):
        shown = f"periodic orbit Δs = {periodic:.4g}, not settled by then"
    elif periodic is None and ans.reason.startswith("no periodic orbit"):
        shown = ans.reason.split(";")[0]
    else:
        shown = "periodic Δs not determined"
    msg = (
        f"transient from rest crosses the {travel} travel in {ans.cycles_to_cross} cycles, "
        f"mean Δs = {ds:.4g} per cycle -> {mode} mode (intended {s.intended_mode}; {shown})"
    )
    fix = "" if ok else SEARCH_HINT
    return RuleResult("mode", "error", ok, ds, want, msg, SRC_SETTLE, fix=fix)


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
    s: SetDerivation,
    orbit: OrbitLike | None,
    corners: dict[str, str | None],
    travel: TravelAnswer | None = None,
) -> RuleResult:
    """The rule ``mode-margin``: the quoted mode at every corner.

    The rule ``mode-margin``: the quoted mode (the travel answer's, else the orbit's)
    at every corner, each corner read on the same basis (the checker's
    ``corner_modes``).
    """
    mode = travel.mode if travel is not None else orbit_mode(orbit)
    thr = "same mode at ϖ·(1 ± 5 %) and α·(1 ± 10 %)"
    if mode not in ("push", "pull"):
        return RuleResult(
            "mode-margin", "warning", False, None, thr, "no exact mode to perturb", SRC_MARGIN
        )
    flips = {k: v for k, v in corners.items() if v != mode}
    ok = not flips
    listing = ", ".join(f"{k}: {v or 'no orbit'}" for k, v in flips.items())
    basis = (
        " [each corner's crossing from rest]"
        if travel is not None and travel.basis == "crossing"
        else " [each corner's periodic orbit]"
    )
    msg = (
        f"the {mode} mode holds at every corner ({', '.join(corners)}){basis}"
        if ok
        else f"the mode changes within fabrication spread ({listing}){basis}"
    )
    if flips:
        msg += _near_subresonance(s, flips)
    fix = "" if ok else f"move away from the flip ({_margin_cause(flips)}); {SEARCH_HINT}"
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


# --- motion along the travel: speed, settling from rest, target speed ---------------------


def speed_rules(
    s: SetDerivation,
    orbit: OrbitLike | None,
    settling: Settling | None,
    target: float | None,
    travel: TravelAnswer | None = None,
) -> list[RuleResult]:
    """The rules about motion along the travel range.

    Parameters
    ----------
    s : SetDerivation
        The derived actuator set (scales, travel range).
    orbit : OrbitLike or None
        Its exact periodic orbit.
    settling : Settling or None
        The transient from rest; a failure stand-in (``status`` "failed") is ignored.
    target : float or None
        The speed the design must reach [m/s] (adds ``target-speed``).
    travel : TravelAnswer, optional
        The answer the verdict quotes (:func:`betvdesign.checks.travel.travel_answer`);
        None chooses it from ``orbit`` and ``settling`` (Δs read as exact).

    Returns
    -------
    list of RuleResult
        ``speed`` (info; value [m/s], signed along the impacts): Δs·u·cosθ·f_act of the
        quoted answer — the orbit, or the crossing mean from rest when the slider has not
        settled within :data:`SETTLE_SHARE` of the crossing; none when it does not cross
        its travel within the horizon; ``settling`` (warning; value: settling time
        [s]) when a transient is given; ``target-speed`` (error) when a target is given.

    References
    ----------
    .. [1] Shin, Pai, Lin, Hui and Tien, J. Appl. Phys. 96, 7603 (2004),
       doi:10.1063/1.1809773 (displacement per cycle).
    """
    ans = travel if travel is not None else travel_answer(orbit, None, settling)
    if ans.basis in ("no-crossing", "undetermined", "no-orbit") or not ans.moves:
        return _no_speed(s, ans, settling, target)
    periodic = ans.delta_s_periodic
    travel_m = s.travel_range_m
    out = []
    if settling is not None and settling.status != "failed" and periodic is not None:
        if mode_of(periodic) in ("push", "pull") and ans.basis in ("periodic", "crossing"):
            out.append(_settling_rule(s, settling, ok=ans.basis == "periodic"))
    ds = float(ans.delta_s)
    v = s.scales.speed_m_s(ds)
    if ans.basis == "crossing":
        if periodic is not None and mode_of(periodic) in ("push", "pull"):
            shown = format_speed(abs(s.scales.speed_m_s(periodic)))
        else:
            shown = "not determined"
        basis = f"transient from rest over the travel range (periodic: {shown})"
    else:
        basis = "periodic orbit"
    if abs(v) > 0:
        t_cross = time_to_cross_s(s, ans)
        how = "from rest " if ans.cycles_to_cross is not None else ""
        msg = (
            f"mean speed {format_speed(abs(v))} toward {travel_axis(s, ds)} "
            f"({'with' if ds > 0 else 'against'} the impact direction "
            f"{s.actuator_set.impact_direction}), crosses the {format_si(travel_m, 'm')} "
            f"travel range {how}in {format_time(t_cross)} [{basis}]"
        )
    else:
        msg = "the slider does not advance over the travel range"
    speed = RuleResult("speed", "info", True, v, "Δs·u·cosθ·f_act", msg, SRC_SPEED, unit="m/s")
    out.insert(0, speed)
    if target is not None:
        out.append(_target(abs(v), target, ""))
    return out


def _no_speed(
    s: SetDerivation, ans: TravelAnswer, settling: Settling | None, target: float | None
) -> list[RuleResult]:
    """The speed rules of an answer that does not move the slider over its travel.

    Parameters
    ----------
    s : SetDerivation
        The derived set.
    ans : TravelAnswer
        Its answer (no crossing, undetermined, no orbit, or stalled).
    settling : Settling, optional
        The transient from rest.
    target : float, optional
        The target speed [m/s].

    Returns
    -------
    list of RuleResult
        ``speed`` (failed, saying why), the ``settling`` line when the orbit moves but the
        travel is not crossed, ``target-speed`` when a target is given.
    """
    if ans.basis == "no-crossing":
        why = f"the slider does not cross its travel range: {ans.reason}"
    elif ans.basis == "undetermined":
        why = "the periodic Δs is not determined and the slider does not cross its travel"
    elif ans.mode == "stalled":
        why = "the slider does not move"
    else:
        why = "no exact periodic orbit"
    out = [RuleResult("speed", "info", False, None, "needs a moving orbit", why, SRC_SPEED)]
    if ans.basis == "no-crossing" and settling is not None and ans.delta_s_periodic is not None:
        out.append(_settling_rule(s, settling, ok=False))
    if target is not None:
        out.append(_target(None, target, why))
    return out


def time_to_cross_s(s: SetDerivation, ans: TravelAnswer) -> float | None:
    """Time for the slider to cross its travel range [s]: one definition for every line.

    Parameters
    ----------
    s : SetDerivation
        The derived set (travel range, actuation frequency, scales).
    ans : TravelAnswer
        The answer the verdict quotes.

    Returns
    -------
    float or None
        The transient from rest's own crossing, ``cycles_to_cross / f_act`` (to within
        one cycle), whenever it was run and crossed, whatever the basis of the speed:
        the periodic speed is the settled one, and the slider starts from rest;
        else travel / |speed| of the quoted Δs; None when nothing moves.
    """
    if ans.cycles_to_cross is not None:
        return ans.cycles_to_cross / s.scales.f_act_hz
    if ans.delta_s is None or ans.delta_s == 0.0:
        return None
    return s.travel_range_m / abs(s.scales.speed_m_s(float(ans.delta_s)))


def _settling_rule(s: SetDerivation, settling: Settling, *, ok: bool) -> RuleResult:
    """The rule ``settling``: settling from rest against the cycles to cross the travel."""
    f = s.scales.f_act_hz
    n_cross = settling.cycles_to_cross
    n_settle = settling.settle_cycles  # a lower bound when not settled
    settle_txt = (
        f"{n_settle:.4g} cycles ({format_time(n_settle / f)})"
        if settling.cycles_to_settle is not None
        else f"more than {settling.simulated_cycles} cycles (not settled)"
    )
    travel = format_si(s.travel_range_m, "m")
    if n_cross:
        cross_txt = (
            f"crosses the {travel} travel range after {n_cross} cycles ({format_time(n_cross / f)})"
        )
    else:
        cross_txt = no_crossing(s.travel_range_m, settling.simulated_cycles, f)
    if ok:
        tail, fix = "", ""
    elif n_cross:
        tail = ": the periodic speed is not what the travel shows"
        fix = (
            "quote the crossing speed from rest (the speed rule does), or choose a design "
            "that settles faster (slowest Floquet multiplier |μ| further below 1; near ϖ → 2 "
            "settling slows sharply)"
        )
    else:
        tail = ": no speed is shown over the travel"
        fix = NO_CROSSING_FIX
    return RuleResult(
        "settling",
        "warning",
        ok,
        n_settle / f,
        f"settling ≤ {SETTLE_SHARE:.0%} of the cycles to cross the travel range",
        f"from rest: within {settling.rtol:.0%} of the periodic Δs after {settle_txt}; "
        f"{cross_txt}{tail}",
        SRC_SETTLE,
        fix=fix,
        unit="s",
    )


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
        else "the speed is proportional to the stroke u (drive voltage); `betv fix FILE "
        "--target-speed Q` finds the nearest passing value of each field",
        unit="m/s",
    )


# --- model adequacy: is the paper's idealised model enough here? --------------------------

_ADEQUACY_FIX = {
    "mode-flips": "give the measured Q and e (actuator.quality_factor_*, contact.restitution) "
    "and stay clear of the flip; ",
    "ideal-fails": "give the head's damping (actuator.quality_factor_*) so the check uses the "
    "finite damped orbit, or detune the tangential resonance; ",
    "failed": "`betv simulate FILE --periodic` shows why no orbit was found; ",
}


def adequacy_rule(a: SetAdequacy) -> RuleResult:
    """The rule ``model-adequacy`` of one set's adequacy result.

    Parameters
    ----------
    a : SetAdequacy
        The set's adequacy (:func:`betvdesign.checks.adequacy.assess_set`); its long
        ``message`` is in the JSON and the report, the rule quotes ``summary()``.

    Returns
    -------
    RuleResult
        Info when the idealised model's mode holds with the device's (or plausible
        default) head damping and restitution and throughout the likely bands
        :data:`~betvdesign.checks.adequacy.LIKELY_QUALITY` and
        :data:`~betvdesign.checks.adequacy.LIKELY_RESTITUTION` (a flip only beyond them
        is stated in the message); warning otherwise. Value: the relative speed change
        (v_richer − v_ideal)/v_ideal [-], None without both speeds.
    """
    status = str(a.status)
    ok = bool(a.adequate)
    thr = (
        f"same mode without and with damping/restitution, and for {LIKELY_QUALITY[0]:g} ≤ Q ≤ "
        f"{LIKELY_QUALITY[1]:g}, {LIKELY_RESTITUTION[0]:g} ≤ e ≤ {LIKELY_RESTITUTION[1]:g}"
    )
    change = a.speed_change
    head = _ADEQUACY_FIX.get(status, "")
    if status == "mode-flips" and a.source == "device":
        head = (
            "the file's Q and e are given, but the mode flips within their likely range: "
            "check how sure they are (`betv tolerance FILE --spread "
            "contact.restitution=uniform:0.05`) and keep clear of the flip (a lower ϖ "
            "tolerates a larger e); "
        )
    fix = "" if ok else head + "`betv report FILE` draws mode and speed against Q and e"
    return RuleResult(
        "model-adequacy",
        "info" if ok else "warning",
        ok,
        None if change is None else float(change),
        thr,
        f"{status}: {a.summary()}",
        SRC_ADEQUACY,
        fix=fix,
    )


# --- device-level ------------------------------------------------------------------------


def evaluate_device(
    derivation: DeviceDerivation,
    *,
    orbits: dict[str, OrbitLike] | None = None,
    vertical: dict[str, VerticalResult] | None = None,
    settling: dict[str, Settling] | None = None,
    margins: dict[str, dict[str, str | None]] | None = None,
    target_speed_m_s: float | None = None,
    adequacy: dict[str, SetAdequacy] | None = None,
    travel: dict[str, TravelAnswer] | None = None,
) -> list[RuleResult]:
    """Rules of every set, then the device rule ``bidirectional``.

    Parameters
    ----------
    derivation : DeviceDerivation
        The derived device.
    orbits, vertical, settling, margins, adequacy, travel : dict, optional
        Per set name, what :func:`evaluate` takes as ``orbit``, ``vertical``,
        ``settling``, ``margin``, ``adequacy`` and ``travel`` (a set not in a dict gets
        None).
    target_speed_m_s : float, optional
        The speed every set must reach [m/s].

    Returns
    -------
    list of RuleResult
        The rules of each set in order, then, for two or more sets, ``bidirectional``
        (warning: the sets must move the slider both ways).
    """
    orbits, vertical, adequacy = orbits or {}, vertical or {}, adequacy or {}
    settling, margins, answers = settling or {}, margins or {}, travel or {}
    out: list[RuleResult] = []
    directions: dict[str, int | None] = {}
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
                travel=answers.get(s.name),
            )
        )
        ans = answers.get(s.name)
        mode = ans.mode if ans is not None else orbit_mode(orbit)
        directions[s.name] = travel_direction(s, mode) if mode in ("push", "pull") else None
    if len(derivation.sets) >= 2:
        dirs = set(directions.values())
        listing = ", ".join(
            f"{k}: {'none' if v is None else '+x' if v > 0 else '-x'}"
            for k, v in directions.items()
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
