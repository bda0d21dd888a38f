"""The whole design check of a device: rules, plus the exact solver where it is needed.

"Model no more than a scene needs": the closed-form rules (:mod:`betvdesign.rules`)
decide unless λ is within the margin of 1 or the parameters lie outside the λ fit
range; only then (or when asked) is the exact periodic orbit computed
(``betvdesign.dynamics.periodic_orbit``, imported lazily). :class:`CheckResult`
is what ``betv check`` prints, and ``CheckResult.as_dict()`` is its JSON contract.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal

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


@dataclass
class SetCheck:
    """Check outcome of one actuator set."""

    derivation: SetDerivation
    rules: list[RuleResult]
    periodic: Any | None = None
    simulated_because: str = ""
    vertical: Any | None = None

    @property
    def mode_predicted(self) -> str:
        p = self.periodic
        if p is not None and getattr(p, "success", False):
            return "push" if float(p.delta_s) > 0 else "pull"
        return self.derivation.mode_predicted

    @property
    def mode_source(self) -> str:
        p = self.periodic
        return "simulation" if p is not None and getattr(p, "success", False) else "lambda"


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
        return _SolverFailure(f"{type(exc).__name__}: {exc}")


def check_derivation(
    derivation: DeviceDerivation,
    *,
    simulate: SimulateWhen = "auto",
    lambda_margin: float = DEFAULT_LAMBDA_MARGIN,
    solver: Any | None = None,
) -> CheckResult:
    """Evaluate every rule of a device ("Model no more than a scene needs").

    simulate: "never" closed form only; "always" run the exact periodic orbit for
    every set; "auto" (default) run it only where the closed form cannot decide
    (λ within the margin of 1, or parameters outside the λ fit range) and the solver
    exists. ``solver`` overrides the lazily imported ``periodic_orbit``.
    Raises :class:`~betvdesign.errors.UsageError` for "always" without a solver.
    """
    if solver is None and simulate != "never":
        solver = load_solver()
    if simulate == "always" and solver is None:
        raise UsageError(
            "--simulate needs the exact solver (betvdesign.dynamics.periodic_orbit), which is "
            "not available in this installation yet; run `betv check` without --simulate"
        )
    notes: list[str] = []
    periodic: dict[str, Any] = {}
    why: dict[str, str] = {}
    solved: dict[Any, Any] = {}
    for s in derivation.sets:
        reasons = undecided_reasons(s, lambda_margin=lambda_margin)
        if simulate == "always":
            why[s.name] = "requested (--simulate)"
        elif simulate == "auto" and reasons:
            if solver is None:
                notes.append(
                    f"set {s.name}: the closed form cannot decide ({'; '.join(reasons)}); "
                    "the exact solver is not available yet, so the mode is λ's guess"
                )
                continue
            why[s.name] = "the closed form cannot decide: " + "; ".join(reasons)
        elif reasons:
            notes.append(
                f"set {s.name}: the closed form cannot decide ({'; '.join(reasons)}); "
                "run with --simulate"
            )
            continue
        else:
            continue
        if s.params in solved:  # mirrored sets share parameters: solve once
            periodic[s.name] = solved[s.params]
            notes.append(f"set {s.name}: same parameters as an already solved set, reused")
            continue
        periodic[s.name] = solved[s.params] = _run_solver(solver, s)
        notes.append(f"set {s.name}: ran the exact solver ({why[s.name]})")
    vertical: dict[str, Any] = {}
    vm = load_vertical() if simulate != "never" else None
    if vm is not None:  # cheap (closed-form vertical schedule): quoted by the window rule
        for s in derivation.sets:
            vertical[s.name] = _vertical(vm, s.params.varpi)
    rules = evaluate_device(
        derivation, lambda_margin=lambda_margin, periodic=periodic, vertical=vertical
    )
    sets = [
        SetCheck(
            s,
            [r for r in rules if r.set_name == s.name],
            periodic.get(s.name),
            why.get(s.name, ""),
            vertical.get(s.name),
        )
        for s in derivation.sets
    ]
    return CheckResult(derivation, sets, rules, notes)


@dataclass
class _SolverFailure:
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
        return _SolverFailure(f"{type(exc).__name__}: {exc}")


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
