"""The whole design check of a device: rules, plus the exact solver where it is needed.

"Model no more than a scene needs": the closed-form rules (:mod:`betvdesign.rules`)
decide unless λ is within the margin of 1, the parameters lie outside the λ fit
range, or the fidelity ladder (:func:`betvdesign.fidelity.choose_rung`, question
"mode") does not trust λ there (outside the window, or within the measured trust
margin at (ϖ, β)); only then (or when asked) is the exact periodic orbit computed
(``betvdesign.dynamics.periodic_orbit``, imported lazily). ``fidelity=`` (``betv
check --fidelity RUNG``) forces the rung that decides the mode. Every set records
which rung answered and why (:class:`ModeFidelity`). :class:`CheckResult` is what
``betv check`` prints, and ``CheckResult.as_dict()`` is its JSON contract.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Literal

from betvdesign import fidelity as fid
from betvdesign.errors import UsageError
from betvdesign.nondim import DeviceDerivation, SetDerivation
from betvdesign.rules import (
    DEFAULT_LAMBDA_MARGIN,
    RuleResult,
    evaluate_device,
    format_speed,
    format_time,
    undecided_reasons,
    verdict,
)

# --- the whole check: rules + (optional) exact solver --------------------------------------

SimulateWhen = Literal["auto", "always", "never"]


@dataclass(frozen=True)
class ModeFidelity:
    """Which rung of the fidelity ladder answered "which mode?" for a set, and why.

    rung: the rung whose answer was used; chosen: the rung the ladder (or
    ``--fidelity``/``--simulate``) chose; they differ when the chosen solver could not
    run or failed and λ's guess stands in (the reason then says so).
    """

    rung: fid.Rung
    reason: str
    chosen: fid.Rung
    forced: bool = False

    def as_dict(self) -> dict[str, Any]:
        return {
            "question": "mode",
            "rung": self.rung,
            "reason": self.reason,
            "chosen": self.chosen,
            "forced": self.forced,
            "model": fid.RUNG_INFO[self.rung].model,
        }


@dataclass
class SetCheck:
    """Check outcome of one actuator set."""

    derivation: SetDerivation
    rules: list[RuleResult]
    periodic: Any | None = None
    simulated_because: str = ""
    vertical: Any | None = None
    fidelity: ModeFidelity | None = None
    mode_answer: fid.Answer | None = None

    @property
    def mode_predicted(self) -> str:
        p, a = self.periodic, self.mode_answer
        if p is not None and getattr(p, "success", False):
            return "push" if float(p.delta_s) > 0 else "pull"
        if a is not None and a.success and a.mode in ("push", "pull"):
            return str(a.mode)
        return self.derivation.mode_predicted

    @property
    def mode_source(self) -> str:
        """ "simulation" when a solver rung decided the mode, else "lambda"."""
        rung = self.fidelity.rung if self.fidelity is not None else None
        if rung is None:  # built by hand: infer from the results
            p = self.periodic
            return "simulation" if p is not None and getattr(p, "success", False) else "lambda"
        return "lambda" if rung == "lambda" else "simulation"


@dataclass
class CheckResult:
    """Everything ``betv check`` reports for one device."""

    derivation: DeviceDerivation
    sets: list[SetCheck]
    rules: list[RuleResult]
    notes: list[str]
    source_file: str = ""

    @property
    def verdict(self) -> Literal["pass", "fail"]:
        return verdict(self.rules)

    def as_dict(self) -> dict[str, Any]:
        """The JSON contract of ``betv check --json`` (issue 2): top-level ``params``,
        ``derived`` and ``mode_predicted`` describe the first actuator set; ``sets``
        has every set in full, with its derivation record."""
        sets = [_set_dict(sc) for sc in self.sets]
        first = sets[0]
        return {
            "device": self.derivation.name,
            "file": self.source_file,
            "params": first["params"],
            "derived": first["derived"],
            "mode_predicted": first["mode_predicted"],
            "fidelity": first["fidelity"],
            "rules": [r.as_dict() for r in self.rules],
            "verdict": self.verdict,
            "notes": list(self.notes),
            "sets": sets,
        }


def load_solver() -> Any | None:
    """The exact solver's ``periodic_orbit`` or None while it is not available (lazy import)."""
    try:
        from betvdesign.dynamics import periodic_orbit  # type: ignore[attr-defined]
    except ImportError:
        return None
    return periodic_orbit


def load_vertical() -> Any | None:
    """The exact vertical-motion fast path ``dynamics.vertical_motion`` or None."""
    try:
        from betvdesign.dynamics import vertical_motion  # type: ignore[attr-defined]
    except ImportError:
        return None
    return vertical_motion


def _vertical(fn: Any, varpi: float) -> Any:
    try:
        return fn(varpi)
    except Exception as exc:  # reported in the window rule, never a crash
        return SolverFailure(f"{type(exc).__name__}: {exc}")


def check_derivation(
    derivation: DeviceDerivation,
    *,
    simulate: SimulateWhen = "auto",
    lambda_margin: float = DEFAULT_LAMBDA_MARGIN,
    solver: Any | None = None,
    fidelity: fid.Rung | None = None,
    vertical: Callable[[float], Any] | None = None,
    simulate_reason: str = "requested (--simulate)",
) -> CheckResult:
    """Evaluate every rule of a device ("Model no more than a scene needs").

    simulate: "never" closed form only; "always" run the exact periodic orbit for
    every set (``simulate_reason`` says why); "auto" (default) run it only where the
    closed form cannot decide (:func:`betvdesign.rules.undecided_reasons`: λ within
    the margin of 1, parameters outside the λ fit range, or a rung other than λ chosen
    by :func:`betvdesign.fidelity.choose_rung`) and the solver exists.
    fidelity: force the rung that decides the mode ("lambda", "rigid", "full",
    "periodic"; ``betv check --fidelity``). ``solver`` overrides the lazily imported
    ``periodic_orbit``; ``vertical`` the lazily imported ``vertical_motion`` (ϖ ->
    result, or None to leave it out). Raises :class:`~betvdesign.errors.UsageError`
    for an unknown rung, a rung that cannot tell the mode, a rung contradicting
    ``simulate``, or a periodic orbit required without a solver.
    """
    if fidelity is not None:
        fid.choose_rung(derivation.sets[0].params, "mode", force=fidelity)  # validates
        clash = {"always": ("periodic", "--simulate"), "never": ("lambda", "--closed-form-only")}
        if simulate in clash and fidelity != clash[simulate][0]:
            raise UsageError(f"--fidelity {fidelity} contradicts {clash[simulate][1]}")
    needs_orbit = simulate == "always" or fidelity == "periodic"
    if solver is None and (needs_orbit or (simulate == "auto" and fidelity is None)):
        solver = load_solver()
    if needs_orbit and solver is None:
        raise UsageError(
            "--simulate needs the exact solver (betvdesign.dynamics.periodic_orbit), which is "
            "not available in this installation yet; run `betv check` without --simulate"
        )
    notes: list[str] = []
    periodic: dict[str, Any] = {}
    answers: dict[str, fid.Answer] = {}
    why: dict[str, str] = {}
    used: dict[str, ModeFidelity] = {}
    solved: dict[Any, Any] = {}
    for s in derivation.sets:
        reasons = undecided_reasons(s, lambda_margin=lambda_margin)
        cannot = f"the closed form cannot decide ({'; '.join(reasons)})"
        if fidelity is not None:
            choice = fid.choose_rung(s.params, "mode", force=fidelity)
            if fidelity == "lambda" and reasons:
                notes.append(f"set {s.name}: --fidelity lambda forced although {cannot}")
            elif fidelity == "rigid":
                est = fid.rigid_error_estimate(s.params.alpha)
                notes.append(
                    f"set {s.name}: --fidelity rigid: measured bound on the α → 0 limit's "
                    f"relative Δs error at α = {s.params.alpha:.3g}: {est:.2g}; its mode is "
                    "always pull (MODEL.md)"
                )
        elif simulate == "always":
            choice = fid.Choice("periodic", "mode", simulate_reason, forced=True)
        elif reasons:
            because = "the closed form cannot decide: " + "; ".join(reasons)
            choice = fid.Choice("periodic", "mode", because)
        else:
            choice = fid.choose_rung(s.params, "mode")  # the λ rung, with its measured reason
        used[s.name] = ModeFidelity(choice.rung, choice.reason, choice.rung, choice.forced)
        if choice.rung == "lambda":
            continue
        if choice.rung != "periodic":  # rigid or full, forced
            key = (s.params, choice.rung)
            if key not in solved:
                solved[key] = fid.evaluate(s.params, choice)
            answers[s.name] = ans = solved[key]
            if not (ans.success and ans.mode in ("push", "pull")):
                used[s.name] = _fallback(choice, f"the {choice.rung} rung gave no mode")
            continue
        if simulate == "never":
            notes.append(f"set {s.name}: {cannot}; run with --simulate")
            used[s.name] = _fallback(choice, "--closed-form-only")
            continue
        if solver is None:
            notes.append(
                f"set {s.name}: {cannot}; the exact solver is not available yet, so the "
                "mode is λ's guess"
            )
            used[s.name] = _fallback(choice, "the exact solver is not available")
            continue
        why[s.name] = choice.reason
        if s.params in solved:  # mirrored sets share parameters: solve once
            periodic[s.name] = solved[s.params]
            notes.append(f"set {s.name}: same parameters as an already solved set, reused")
        else:
            periodic[s.name] = solved[s.params] = _run_solver(solver, s)
            notes.append(f"set {s.name}: ran the exact solver ({why[s.name]})")
        if not getattr(periodic[s.name], "success", False):
            unbounded = getattr(periodic[s.name], "status", "") == "unbounded"
            what = (
                "no periodic orbit exists (the head's tangential motion grows without bound)"
                if unbounded
                else "the periodic orbit was not found"
            )
            used[s.name] = _fallback(choice, what)
    vertical_of: dict[str, Any] = {}
    vm = vertical if vertical is not None else (load_vertical() if simulate != "never" else None)
    if vm is not None:  # cheap (closed-form vertical schedule): quoted by the window rule
        for s in derivation.sets:
            v = _vertical(vm, s.params.varpi)
            if v is not None:
                vertical_of[s.name] = v
    rules = evaluate_device(
        derivation,
        lambda_margin=lambda_margin,
        periodic=periodic,
        vertical=vertical_of,
        mode_answers=answers,
    )
    sets = [
        SetCheck(
            s,
            [r for r in rules if r.set_name == s.name],
            periodic.get(s.name),
            why.get(s.name, ""),
            vertical_of.get(s.name),
            used[s.name],
            answers.get(s.name),
        )
        for s in derivation.sets
    ]
    return CheckResult(derivation, sets, rules, notes)


def _fallback(choice: fid.Choice, what: str) -> ModeFidelity:
    """λ stands in for the chosen rung, which could not answer (``what``)."""
    return ModeFidelity(
        "lambda",
        f"{what}: λ's guess stands in for the {choice.rung} rung ({choice.reason})",
        choice.rung,
        choice.forced,
    )


@dataclass
class SolverFailure:
    """Stands in for a solver result when the solver raised: success False, with why."""

    message: str
    success: bool = False
    status: int = -1
    delta_s: float = math.nan
    mode: str = ""


def _run_solver(solver: Any, s: SetDerivation) -> Any:
    try:
        return solver(s.params)
    except Exception as exc:  # a failing solver must not crash the check; reported as a rule
        return SolverFailure(f"{type(exc).__name__}: {exc}")


def _set_dict(sc: SetCheck) -> dict[str, Any]:
    s = sc.derivation
    params = {**s.params.as_dict(), "lambda": s.lam}
    derived = s.derived()
    speed = next((r for r in sc.rules if r.id == "speed" and r.value is not None), None)
    if speed is not None and speed.passed:
        derived["speed"] = format_speed(speed.value)
        derived["time_to_cross"] = format_time(s.travel_range_m / abs(speed.value))
    p = sc.periodic
    return {
        "name": s.name,
        "intended_mode": s.intended_mode,
        "impact_direction": s.actuator_set.impact_direction,
        "params": params,
        "derived": derived,
        "mode_predicted": sc.mode_predicted,
        "mode_source": sc.mode_source,
        "fidelity": None if sc.fidelity is None else sc.fidelity.as_dict(),
        "simulated": p is not None,
        "simulated_because": sc.simulated_because,
        "simulation": None if p is None else simulation_summary(p),
        "vertical": None if sc.vertical is None else _vertical_summary(sc.vertical),
        "published_fit": [
            {
                "param": c.name,
                "computed": c.computed,
                "published": list(c.published),
                "rel_diff": c.rel_diff,
            }
            for c in s.published
        ],
        "record": [
            {
                "symbol": st.symbol,
                "key": st.key,
                "description": st.description,
                "formula": st.formula,
                "value": st.value_str,
                "inputs": list(st.inputs),
            }
            for st in s.record
        ],
        "rules": [r.as_dict() for r in sc.rules],
    }


def simulation_summary(p: Any) -> dict[str, Any]:
    """JSON-safe summary of a periodic-orbit result (fields the solver provides)."""
    out: dict[str, Any] = {
        "status": str(getattr(p, "status", "")),
        "success": bool(getattr(p, "success", False)),
        "message": str(getattr(p, "message", "")),
    }
    for name in ("delta_s", "residual", "impacts_per_cycle", "contact_fraction", "elapsed_s"):
        if hasattr(p, name):
            out[name] = _json_float(getattr(p, name))
    for name in ("period_cycles", "n_cycles", "transient_cycles"):
        v = getattr(p, name, None)
        if v is not None:
            out[name] = int(v)
    if getattr(p, "stable", None) is not None:
        out["stable"] = bool(p.stable)
    return out


def _vertical_summary(v: Any) -> dict[str, Any]:
    out: dict[str, Any] = {
        "success": bool(getattr(v, "success", False)),
        "message": str(getattr(v, "message", "")),
    }
    if out["success"]:
        out["regime"] = str(v.regime)
        for name in ("hits_per_cycle", "impulsive_per_cycle", "contact_fraction"):
            out[name] = _json_float(getattr(v, name, None))
    return out


def _json_float(x: Any) -> float | str | None:
    if x is None:
        return None
    x = float(x)
    return x if math.isfinite(x) else str(x)
