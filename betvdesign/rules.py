"""Design rules as data: each check of a derived design gives a :class:`RuleResult`.

The rules turn docs/MODEL.md, "What the model shows", into checks a designer can act
on. They use the closed-form knowledge (design window, λ criterion and its fit range,
tangential resonance) and, when given, the exact periodic orbit of the solver
(``periodic``: an object with ``success``, ``message``, ``delta_s``, ``mode``), which
decides the mode and gives the speed.

Defaults (module constants, all stated in the rule messages):

- frequency window 0.5 ≤ ϖ < 2 (one hit per cycle, finite contact); 2 ≤ ϖ < 2.6
  impulsive hits; ϖ ≥ 2.6 period doubling / aperiodic.
- λ margin: |λ − 1| ≥ 0.2. λ ∝ 1/ϖ² and its leading term ∝ 1/(αϖ²), so ±5 % on
  the resonance frequency or ±10 % on the tangential compliance (typical
  fabrication spread) each move λ by about 10 %; 0.2 covers both together.
  Where the mode rests on λ alone, the margin is at least the *measured* trust
  margin of the fidelity ladder at the design's (ϖ, β)
  (:func:`betvdesign.fidelity.lambda_trust_margin`, measured by
  ``benchmarks/work_precision.py --ladder``): below ϖ ≈ 0.9 the λ fit was seen to
  mispredict even at λ ≈ 4–18, so 0.2 is not enough there.
- tangential resonance: |a·ϖ² − 1| ≥ 0.1 for a = α (free flight) and
  a = α(1 + 1/β) (stick).
- λ fit range: α 0.1–4, β 0.1–1.5, κ 0.1–0.4; outside it λ is an extrapolation.
- published fit: computed parameters within 10 % of a published value.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any, Literal, Protocol

from betvdesign import fidelity
from betvdesign.nondim import DeviceDerivation, SetDerivation

Severity = Literal["error", "warning", "info"]

VARPI_WINDOW = (0.5, 2.0)
VARPI_IMPULSIVE_END = 2.6
DEFAULT_LAMBDA_MARGIN = 0.2
TANGENTIAL_DETUNING = 0.1
FIT_RANGE: dict[str, tuple[float, float]] = {
    "alpha": (0.1, 4.0),
    "beta": (0.1, 1.5),
    "kappa": (0.1, 0.4),
}
PUBLISHED_RTOL = 0.1
#: |Δs| below this [-] counts as "the slider does not move" for speed purposes.
DELTA_S_ZERO = 1e-9
_FIT_TOL = 1e-9  # relative tolerance at the fit-range edges (κ = 0.4·tan45° = 0.39999...)

SRC_WINDOW = "MODEL.md, What the model shows: Vertical motion (Shin et al. 2004)"
SRC_LAMBDA = "MODEL.md, Push/pull criterion (empirical fit, Shin et al. 2004)"
SRC_TANG = "MODEL.md, What the model shows: tangential vibration undamped off contact"
SRC_SPEED = "MODEL.md, Displacement per cycle: speed = Δs·u·cosθ·f_act"
SRC_PUBLISHED = "device file: published_fit"
SRC_SOLVER = "betvdesign.dynamics.periodic_orbit (exact event-driven solver)"
SRC_TRUST = (
    "λ trust margin per (ϖ, β) measured against the exact periodic orbit "
    "(benchmarks/work_precision.py --ladder -> betvdesign/fidelity_measured.py)"
)


class PeriodicLike(Protocol):
    success: bool
    message: str
    delta_s: float
    mode: str


@dataclass(frozen=True)
class RuleResult:
    """Outcome of one design rule.

    value: the number checked (None when the rule could not be evaluated);
    threshold: the pass condition in words/maths; set_name: the actuator set
    ("" for device-level rules).
    """

    id: str
    severity: Severity
    passed: bool
    value: float | None
    threshold: str
    message: str
    source: str
    set_name: str = ""

    def as_dict(self) -> dict[str, Any]:
        d = asdict(self)
        if d["value"] is not None and not math.isfinite(d["value"]):
            d["value"] = str(d["value"])  # JSON has no inf/nan
        return d


def verdict(results: list[RuleResult]) -> Literal["pass", "fail"]:
    """ "fail" when any error-severity rule fails, else "pass"."""
    return "fail" if any(r.severity == "error" and not r.passed for r in results) else "pass"


# --- closed-form decidability ------------------------------------------------------------


def undecided_reasons(
    s: SetDerivation, *, lambda_margin: float = DEFAULT_LAMBDA_MARGIN
) -> list[str]:
    """Why the closed-form λ criterion cannot decide the mode ([] when it can).

    λ decides only when |λ − 1| ≥ ``lambda_margin`` (fabrication spread), every
    parameter lies in the fit range, and the fidelity ladder
    (:func:`betvdesign.fidelity.choose_rung`, question "mode") accepts the λ rung:
    inside the design window and beyond the measured trust margin at (ϖ, β).
    """
    reasons = []
    if abs(s.lam - 1.0) < lambda_margin:
        reasons.append(f"λ = {s.lam:.3g} lies within ±{lambda_margin:g} of 1")
    for name, (lo, hi) in FIT_RANGE.items():
        v = getattr(s.params, name)
        if not _in_range(v, lo, hi):
            reasons.append(f"{name} = {v:.3g} outside the λ fit range {lo:g}–{hi:g}")
    if not reasons:
        choice = fidelity.choose_rung(s.params, "mode")
        if choice.rung != "lambda":
            reasons.append(choice.reason)
    return reasons


def required_lambda_margin(
    s: SetDerivation, *, lambda_margin: float = DEFAULT_LAMBDA_MARGIN
) -> float:
    """|λ − 1| the mode needs when it rests on λ alone [-]: the larger of
    ``lambda_margin`` and the measured trust margin at (ϖ, β) (where one was measured)."""
    trust = fidelity.lambda_trust_margin(s.params.varpi, s.params.beta)
    return max(lambda_margin, trust) if math.isfinite(trust) else lambda_margin


def _in_range(v: float, lo: float, hi: float) -> bool:
    return lo * (1 - _FIT_TOL) <= v <= hi * (1 + _FIT_TOL)


# --- per-set rules -----------------------------------------------------------------------


def evaluate(
    derivation_set: SetDerivation,
    *,
    lambda_margin: float = DEFAULT_LAMBDA_MARGIN,
    periodic: PeriodicLike | None = None,
    vertical: Any | None = None,
    mode_answer: fidelity.Answer | None = None,
) -> list[RuleResult]:
    """Every rule for one actuator set (see the module docstring for thresholds).

    periodic: exact periodic orbit (decides the mode, gives the speed); vertical: the
    exact vertical motion (``dynamics.vertical_motion``), quoted by the window rule;
    mode_answer: the mode from another rung of the fidelity ladder ("rigid" or "full",
    forced with ``--fidelity``), used when there is no periodic orbit.
    """
    s = derivation_set
    decided = _decided_by(periodic, mode_answer)
    out = [
        _frequency_window(s, vertical),
        *_mode_rules(s, periodic, lambda_margin, mode_answer),
        _tangential_resonance(s),
        *_fit_range(s, simulated=decided is not None),
        *_published(s),
        *_speed(s, periodic),
    ]
    return [_with_set(r, s.name) for r in out]


def _decided_by(periodic: PeriodicLike | None, answer: Any | None) -> str | None:
    """The solver rung that decided the mode ("periodic", "rigid", "full") or None (λ)."""
    if periodic is not None and getattr(periodic, "success", False):
        return "periodic"
    if answer is not None and answer.success and answer.mode in ("push", "pull"):
        return str(answer.choice.rung)
    return None


def _with_set(r: RuleResult, name: str) -> RuleResult:
    return RuleResult(r.id, r.severity, r.passed, r.value, r.threshold, r.message, r.source, name)


def _frequency_window(s: SetDerivation, vertical: Any | None = None) -> RuleResult:
    v = s.params.varpi
    lo, hi = VARPI_WINDOW
    thr = f"{lo:g} <= varpi < {hi:g}"
    if v < lo:
        msg = (
            f"ϖ = {v:.3g} below the window: the head hits several times per cycle; "
            f"raise f_act/f_v (f_act = {s.scales.f_act_hz:.4g} Hz)"
        )
    elif v < hi:
        msg = f"ϖ = {v:.3g} inside the window: one hit per cycle, finite contact"
    elif v < VARPI_IMPULSIVE_END:
        msg = (
            f"ϖ = {v:.3g} above the window: contact is impulsive (zero duration), "
            "the slider is not driven; lower f_act/f_v"
        )
    else:
        msg = (
            f"ϖ = {v:.3g} far above the window: period doubling or aperiodic hits; lower f_act/f_v"
        )
    if vertical is not None and getattr(vertical, "success", False):
        msg += (
            f" [exact vertical motion: {vertical.regime}, {vertical.hits_per_cycle:g} hit(s) "
            f"per cycle ({vertical.impulsive_per_cycle:g} impulsive), in contact "
            f"{vertical.contact_fraction:.0%} of the time]"
        )
    elif vertical is not None:
        msg += f" [exact vertical motion: {getattr(vertical, 'message', '')}]"
    return RuleResult("frequency-window", "error", lo <= v < hi, v, thr, msg, SRC_WINDOW)


def _mode_rules(
    s: SetDerivation,
    periodic: PeriodicLike | None,
    margin: float,
    answer: fidelity.Answer | None = None,
) -> list[RuleResult]:
    lam = s.lam
    lam_mode = "push" if lam < 1.0 else "pull"
    out: list[RuleResult] = []
    decided = _decided_by(periodic, answer)
    sim_ok = decided == "periodic"
    want = f"intended {s.intended_mode}: Δs {'> 0' if s.intended_mode == 'push' else '< 0'}"
    if sim_ok:
        ds = float(periodic.delta_s)
        mode = "push" if ds > 0 else "pull"
        out.append(
            RuleResult(
                "mode",
                "error",
                mode == s.intended_mode,
                ds,
                want,
                f"exact periodic orbit: Δs = {ds:.4g} per cycle -> {mode} mode "
                f"(intended {s.intended_mode})",
                SRC_SOLVER,
            )
        )
        out.append(
            RuleResult(
                "lambda-vs-simulation",
                "info",
                mode == lam_mode,
                lam,
                "λ fit and exact orbit agree",
                f"λ = {lam:.3g} predicts {lam_mode}, the exact orbit gives {mode}",
                SRC_LAMBDA,
            )
        )
    elif decided is not None:  # another rung, forced with --fidelity
        info = fidelity.RUNG_INFO[answer.choice.rung]
        value = answer.value if isinstance(answer.value, int | float) else None
        shown = f"Δs = {value:.4g} -> " if value is not None else ""
        out.append(
            RuleResult(
                "mode",
                "error",
                answer.mode == s.intended_mode,
                value,
                want,
                f"{info.model}: {shown}{answer.mode} mode (intended {s.intended_mode}); "
                f"{info.exact}",
                info.source,
            )
        )
    else:
        reasons = undecided_reasons(s, lambda_margin=margin)
        caveat = f" (closed form cannot decide: {'; '.join(reasons)})" if reasons else ""
        out.append(
            RuleResult(
                "mode",
                "error",
                lam_mode == s.intended_mode,
                lam,
                f"intended {s.intended_mode}: λ {'< 1' if s.intended_mode == 'push' else '> 1'}",
                f"λ = {lam:.3g} predicts {lam_mode} mode (intended {s.intended_mode}){caveat}",
                SRC_LAMBDA,
            )
        )
    if sim_ok and getattr(periodic, "stable", None) is not None:
        stable = bool(periodic.stable)
        out.append(
            RuleResult(
                "orbit-stability",
                "warning",
                stable,
                None,
                "all Floquet multipliers |μ| < 1",
                "the periodic orbit is stable: the slider settles to it"
                if stable
                else "the periodic orbit is unstable (a Floquet multiplier |μ| >= 1): the "
                "slider may never settle to this Δs",
                SRC_SOLVER,
            )
        )
    failed: tuple[str, str, str] | None = None  # (threshold, message, source)
    severity = "warning"
    if periodic is not None and not sim_ok:
        msg = getattr(periodic, "message", "")
        failed = (
            "exact periodic orbit found",
            f"exact solver did not find the periodic orbit: {msg}",
            SRC_SOLVER,
        )
        if getattr(periodic, "status", "") == "unbounded":  # proven: no steady motion at all
            severity = "error"
            failed = ("bounded tangential motion", f"no periodic orbit exists: {msg}", SRC_SOLVER)
    elif answer is not None and decided is None:
        info = fidelity.RUNG_INFO[answer.choice.rung]
        failed = (
            f"{answer.choice.rung} rung gives a mode",
            f"{info.model} gave no mode ({answer.status}): {answer.message}",
            info.source,
        )
    if failed is not None:
        out.append(RuleResult("simulation", severity, False, None, *failed))
    out.append(_lambda_margin(s, margin, decided))
    return out


def _lambda_margin(s: SetDerivation, margin: float, decided: str | None) -> RuleResult:
    """|λ − 1| against the fabrication margin and, where the mode rests on λ alone
    (``decided`` None), the measured trust margin of the λ rung at (ϖ, β)."""
    p = s.params
    d = abs(s.lam - 1.0)
    trust = fidelity.lambda_trust_margin(p.varpi, p.beta)
    need = margin if decided else required_lambda_margin(s, lambda_margin=margin)
    where = f"near ϖ = {p.varpi:.3g}, β = {p.beta:.3g}"
    if d < margin:
        msg = "near the push/pull boundary: fabrication spread can flip the mode"
    elif d < need:
        msg = (
            f"the λ fit was measured to mispredict the mode this far from λ = 1 {where} "
            f"(trust margin {trust:.3g}): λ alone cannot decide; run with --simulate"
        )
    elif decided and d < trust:
        msg = (
            f"enough margin to λ = 1 for fabrication spread; λ itself is not trusted {where} "
            f"(measured trust margin {trust:.3g}), so the {decided} rung decided the mode"
        )
    else:
        msg = "enough margin to the push/pull boundary"
    measured = need > margin
    return RuleResult(
        "lambda-margin",
        "warning",
        d >= need,
        d,
        f"|λ − 1| >= {need:.3g}" + (f" (measured trust margin {where})" if measured else ""),
        f"|λ − 1| = {d:.3g}: {msg}",
        f"{SRC_LAMBDA}; {SRC_TRUST}",
    )


def _tangential_resonance(s: SetDerivation) -> RuleResult:
    p = s.params
    w2 = p.varpi**2
    cases = {"free flight a = α": p.alpha, "stick a = α(1 + 1/β)": p.alpha * (1 + 1 / p.beta)}
    worst_label, worst = min(((k, abs(a * w2 - 1.0)) for k, a in cases.items()), key=lambda t: t[1])
    ok = worst >= TANGENTIAL_DETUNING
    msg = f"min |a·ϖ² − 1| = {worst:.3g} ({worst_label}): " + (
        "tangential head vibration is off resonance"
        if ok
        else "near tangential resonance: the head's tangential vibration is undamped off "
        "contact and can grow without bound; change α or ϖ"
    )
    return RuleResult(
        "tangential-resonance",
        "warning",
        ok,
        worst,
        f"|a·ϖ² − 1| >= {TANGENTIAL_DETUNING:g}",
        msg,
        SRC_TANG,
    )


def _fit_range(s: SetDerivation, *, simulated: bool = False) -> list[RuleResult]:
    out = []
    for name, (lo, hi) in FIT_RANGE.items():
        v = getattr(s.params, name)
        ok = _in_range(v, lo, hi)
        msg = (
            f"{name} = {v:.3g} inside the λ fit range"
            if ok
            else f"{name} = {v:.3g} outside the λ fit range {lo:g}–{hi:g}: λ is an "
            + (
                "extrapolation; the exact orbit decided the mode"
                if simulated
                else "extrapolation, confirm with --simulate"
            )
        )
        out.append(
            RuleResult(
                f"fit-range.{name}",
                "warning",
                ok,
                v,
                f"{lo:g} <= {name} <= {hi:g}",
                msg,
                SRC_LAMBDA,
            )
        )
    return out


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
            )
        )
    return out


def _speed(s: SetDerivation, periodic: PeriodicLike | None) -> list[RuleResult]:
    if periodic is None or not getattr(periodic, "success", False):
        return [
            RuleResult(
                "speed",
                "info",
                True,
                None,
                "needs the periodic Δs",
                "speed and time to cross need the exact periodic Δs: run with --simulate",
                SRC_SPEED,
            )
        ]
    ds = float(periodic.delta_s)
    v = s.scales.speed_m_s(ds)
    if abs(ds) < DELTA_S_ZERO:
        return [
            RuleResult(
                "speed",
                "info",
                False,
                v,
                f"|Δs| >= {DELTA_S_ZERO:g}",
                f"Δs = {ds:.3g}: the slider does not move",
                SRC_SPEED,
            )
        ]
    t_cross = s.travel_range_m / abs(v)
    return [
        RuleResult(
            "speed",
            "info",
            True,
            v,
            "Δs·u·cosθ·f_act [m/s]",
            f"mean speed {format_speed(abs(v))} toward {_travel_direction(s, ds)} "
            f"({'with' if ds > 0 else 'against'} the impact direction "
            f"{s.actuator_set.impact_direction}), crosses the {s.travel_range_m * 1e6:.4g} um "
            f"travel range in {format_time(t_cross)}",
            SRC_SPEED,
        )
    ]


def _travel_direction(s: SetDerivation, delta_s: float) -> str:
    """Direction the slider travels: Δs is along the set's impact direction."""
    return "+x" if s.impact_sign * (1 if delta_s > 0 else -1) > 0 else "-x"


def format_speed(v_m_s: float) -> str:
    """Speed in engineering units: um/s below 1 mm/s, else mm/s."""
    if abs(v_m_s) < 1e-3:
        return f"{v_m_s * 1e6:.4g} um/s"
    return f"{v_m_s * 1e3:.4g} mm/s"


def format_time(t_s: float) -> str:
    """Duration in engineering units (us, ms, s)."""
    if t_s < 1e-3:
        return f"{t_s * 1e6:.4g} us"
    if t_s < 1.0:
        return f"{t_s * 1e3:.4g} ms"
    return f"{t_s:.4g} s"


# --- device-level ------------------------------------------------------------------------


def travel_direction(s: SetDerivation, mode: str) -> int:
    """+1/−1: slider travel for a set working in ``mode`` (push: along its impacts)."""
    return s.impact_sign if mode == "push" else -s.impact_sign


def evaluate_device(
    derivation: DeviceDerivation,
    *,
    lambda_margin: float = DEFAULT_LAMBDA_MARGIN,
    periodic: dict[str, PeriodicLike] | None = None,
    vertical: dict[str, Any] | None = None,
    mode_answers: dict[str, fidelity.Answer] | None = None,
) -> list[RuleResult]:
    """Rules of every set (``periodic``, ``vertical``, ``mode_answers`` keyed by set name)
    plus device rules."""
    periodic = periodic or {}
    vertical = vertical or {}
    mode_answers = mode_answers or {}
    out: list[RuleResult] = []
    predicted: dict[str, int] = {}
    for s in derivation.sets:
        per, ans = periodic.get(s.name), mode_answers.get(s.name)
        out.extend(
            evaluate(
                s,
                lambda_margin=lambda_margin,
                periodic=per,
                vertical=vertical.get(s.name),
                mode_answer=ans,
            )
        )
        decided = _decided_by(per, ans)
        if decided == "periodic":
            mode = "push" if float(per.delta_s) > 0 else "pull"
        elif decided is not None:
            mode = str(ans.mode)
        else:
            mode = s.mode_predicted
        predicted[s.name] = travel_direction(s, mode)
    if len(derivation.sets) >= 2:
        dirs = set(predicted.values())
        listing = ", ".join(f"{k}: {'+x' if v > 0 else '-x'}" for k, v in predicted.items())
        ok = dirs == {1, -1}
        out.append(
            RuleResult(
                "bidirectional",
                "warning",
                ok,
                None,
                "the sets move the slider both ways",
                f"predicted travel per set ({listing})"
                + ("" if ok else ": every set moves the slider the same way"),
                "MODEL.md: opposing actuator sets give the two directions of travel",
            )
        )
    return out
