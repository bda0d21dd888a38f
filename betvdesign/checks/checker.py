"""The whole design check of a device: the exact answer for every set, then the rules.

A design-rule tool must never say PASS for a device that moves the wrong way, so the
verdict never rests on a fit: every actuator set gets

1. its exact vertical motion (:func:`betvdesign.dynamics.vertical_motion`, quoted by
   the window rule);
2. its exact periodic orbit (:func:`betvdesign.dynamics.periodic_orbit`), which gives
   the mode (push, pull, or stalled when |Δs| is at round-off: one place,
   :func:`betvdesign.model.domain.mode_of`) and the speed; period-k orbits give their mean
   drift per actuation cycle; ``not_converged``, ``unbounded`` and ``not_driven``
   fail with their reason;
3. with ``margin=True``, the exact orbits at ϖ·(1 ± 5 %) and α·(1 ± 10 %)
   (the mode-margin rule);
4. with ``settle=True``, the transient from rest
   (:func:`betvdesign.dynamics.settling.settling`): cycles to settle and to cross the
   travel range, and the speed a designer sees when it does not settle in time.

The paper's λ fit is shown beside the exact mode ("agrees"/"disagrees") and never
decides. Identical parameter sets (mirrored actuator sets) are solved once.
:class:`CheckResult` is what ``betv check`` prints; ``CheckResult.as_dict()`` is its
JSON contract.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any, Literal

from betvdesign.checks.actuator_rules import actuator_rules
from betvdesign.checks.process_rules import process_rules
from betvdesign.checks.rules import (
    MARGIN_CORNERS,
    RuleResult,
    evaluate_device,
    format_speed,
    format_time,
    orbit_mode,
    verdict,
)
from betvdesign.model.domain import mode_of
from betvdesign.model.params import ModelParams
from betvdesign.nondim.device import DeviceDerivation, SetDerivation


@dataclass
class SetCheck:
    """Check outcome of one actuator set (``periodic`` is the exact orbit)."""

    derivation: SetDerivation
    rules: list[RuleResult]
    periodic: Any | None = None
    vertical: Any | None = None
    settling: Any | None = None
    margin: dict[str, str | None] | None = None
    adequacy: Any | None = None

    @property
    def mode(self) -> str | None:
        """Exact mode: "push", "pull", "stalled", or None when no orbit was found."""
        return orbit_mode(self.periodic)

    @property
    def mode_predicted(self) -> str:
        """The mode the check reports: the exact one, "not driven" when no contact
        recurs (the slider is not moved), "unknown" without an orbit."""
        if self.mode is None and getattr(self.periodic, "status", None) == "not_driven":
            return "not driven"
        return self.mode or "unknown"

    @property
    def lambda_mode(self) -> str:
        """The paper's λ prediction (shown beside the exact mode, never decisive)."""
        return self.derivation.mode_predicted

    @property
    def speed_m_s(self) -> float | None:
        """Speed the speed rule reports [m/s] (signed along the impact direction)."""
        r = next((r for r in self.rules if r.id == "speed"), None)
        return None if r is None else r.value


@dataclass
class CheckResult:
    """Everything ``betv check`` reports for one device."""

    derivation: DeviceDerivation
    sets: list[SetCheck]
    rules: list[RuleResult]
    notes: list[str] = field(default_factory=list)
    source_file: str = ""

    @property
    def verdict(self) -> Literal["pass", "fail"]:
        return verdict(self.rules)

    def as_dict(self) -> dict[str, Any]:
        """The JSON contract of ``betv check --json`` for one device."""
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

    def __repr__(self) -> str:
        modes = ", ".join(f"{sc.derivation.name}: {sc.mode_predicted}" for sc in self.sets)
        return f"<CheckResult {self.derivation.name!r}: {self.verdict.upper()} ({modes})>"

    def _repr_html_(self) -> str:
        """The check block for notebooks (:class:`~betvdesign.checks.view.DeviceView`)."""
        from betvdesign.checks.view import DeviceView

        return DeviceView(self)._repr_html_()


@dataclass
class SolverFailure:
    """Stands in for a solver result when the solver raised: success False, with why."""

    message: str
    success: bool = False
    status: str = "failed"
    delta_s: float = math.nan
    mode: str = ""


def load_solver() -> Callable[[ModelParams], Any]:
    """The exact solver's ``periodic_orbit`` (imported lazily)."""
    from betvdesign.dynamics import periodic_orbit

    return periodic_orbit


def load_vertical() -> Callable[..., Any]:
    """The exact vertical-motion fast path ``dynamics.vertical_motion`` (lazy import)."""
    from betvdesign.dynamics import vertical_motion

    return vertical_motion


def _guarded(fn: Callable[..., Any], arg: Any, **kw: Any) -> Any:
    try:
        return fn(arg, **kw)
    except Exception as exc:  # a failing solver must not crash the check: a failed rule
        return SolverFailure(f"{type(exc).__name__}: {exc}")


def corner_params(p: ModelParams) -> dict[str, ModelParams]:
    """The perturbed parameter sets of the mode-margin rule, by label (damping and
    restitution kept)."""
    out = {}
    for fw, fa in MARGIN_CORNERS:
        label = f"ϖ×{fw:g}" if fa == 1.0 else f"α×{fa:g}"
        out[label] = replace(p, varpi=p.varpi * fw, alpha=p.alpha * fa)
    return out


def check_derivation(
    derivation: DeviceDerivation,
    *,
    solver: Callable[[ModelParams], Any] | None = None,
    vertical: Callable[..., Any] | None = None,
    margin: bool = True,
    settle: bool = True,
    target_speed_m_s: float | None = None,
    adequacy: Any = None,
    layout_rules: list[RuleResult] | None = None,
) -> CheckResult:
    """Check every actuator set with its exact orbit (see the module docstring).

    solver / vertical: override ``dynamics.periodic_orbit`` / ``dynamics.vertical_motion``
    (tests, studies); margin: run the mode-margin corners; settle: run the transient
    from rest; target_speed_m_s: a required speed [m/s] (adds the error rule
    ``target-speed``); adequacy: is the idealised model enough
    (:mod:`betvdesign.checks.adequacy`, rule ``model-adequacy``): None runs it with the
    exact solver unless ``solver`` is given, True always (with ``solver``), False never,
    or an already computed :class:`~betvdesign.checks.adequacy_data.DeviceAdequacy`;
    layout_rules: the process rules measured on a drawn layout
    (:mod:`betvdesign.layout.drc`), used instead of those of the device file
    (:func:`betvdesign.checks.process_rules.process_rules`).
    """
    custom = solver is not None
    solver = solver or load_solver()
    vertical = vertical or load_vertical()
    solved: dict[ModelParams, Any] = {}

    def orbit(p: ModelParams) -> Any:
        if p not in solved:
            solved[p] = _guarded(solver, p)
        return solved[p]

    notes: list[str] = []
    orbits, verticals, settlings, margins = {}, {}, {}, {}
    settled: dict[Any, Any] = {}
    vert_of: dict[tuple[float, float, float], Any] = {}
    for s in derivation.sets:
        p = s.params
        seen = p in solved
        orbits[s.name] = po = orbit(p)
        if seen:
            notes.append(f"set {s.name}: same parameters as an already solved set, reused")
        vkey = (p.varpi, p.zeta_v, p.restitution)
        if vkey not in vert_of:
            vert_of[vkey] = _guarded(vertical, p.varpi, zeta_v=p.zeta_v, restitution=p.restitution)
        if vert_of[vkey] is not None:
            verticals[s.name] = vert_of[vkey]
        if margin and orbit_mode(po) in ("push", "pull"):
            margins[s.name] = {k: orbit_mode(orbit(q)) for k, q in corner_params(p).items()}
        if settle and orbit_mode(po) in ("push", "pull"):
            key = (p, s.travel_range_m / s.scales.length_m)
            if key not in settled:
                settled[key] = _settling(p, po, key[1])
            settlings[s.name] = settled[key]
    adq = _adequacy(derivation, adequacy, (lambda p, **_: orbit(p)) if custom else None)
    rules = evaluate_device(
        derivation,
        orbits=orbits,
        vertical=verticals,
        settling=settlings,
        margins=margins if margin else None,
        target_speed_m_s=target_speed_m_s,
        adequacy=adq,
    )
    rules += [r for s in derivation.sets for r in actuator_rules(s)]
    rules += process_rules(derivation.spec) if layout_rules is None else layout_rules
    sets = [
        SetCheck(
            s,
            [r for r in rules if r.set_name == s.name],
            orbits.get(s.name),
            verticals.get(s.name),
            settlings.get(s.name),
            margins.get(s.name),
            adq.get(s.name),
        )
        for s in derivation.sets
    ]
    return CheckResult(derivation, sets, rules, notes)


def _adequacy(
    derivation: DeviceDerivation, want: Any, custom: Callable[..., Any] | None
) -> dict[str, Any]:
    """Adequacy results by set name ({} when not wanted; see :func:`check_derivation`)."""
    if want is False or (want is None and custom is not None):
        return {}
    if want is None or want is True:
        from betvdesign.checks.adequacy import assess

        want = assess(derivation, solver=custom)
    return {a.name: a for a in want.sets}


def _settling(p: ModelParams, po: Any, travel_s: float) -> Any:
    from betvdesign.dynamics.settling import settling

    moduli = getattr(po, "floquet_moduli", None)
    try:
        return settling(
            p,
            float(po.delta_s),
            period_cycles=int(getattr(po, "period_cycles", 1) or 1),
            travel_s=travel_s,
            mu_max=max(moduli) if moduli else None,
        )
    except Exception as exc:  # reported, never a crash
        return SolverFailure(f"settling: {type(exc).__name__}: {exc}")


def _set_dict(sc: SetCheck) -> dict[str, Any]:
    s = sc.derivation
    params = {**s.params.as_dict(), "lambda": s.lam}
    derived = s.derived()
    v = sc.speed_m_s
    if v is not None and v != 0:
        derived["speed"] = format_speed(abs(v))
        derived["time_to_cross"] = format_time(s.travel_range_m / abs(v))
    p = sc.periodic
    st = sc.settling
    return {
        "name": s.name,
        "intended_mode": s.intended_mode,
        "impact_direction": s.actuator_set.impact_direction,
        "params": params,
        "derived": derived,
        "mode_predicted": sc.mode_predicted,
        "mode_source": "exact periodic orbit",
        "lambda_mode": sc.lambda_mode,
        "lambda_agrees": sc.mode in (None, "stalled") or sc.mode == sc.lambda_mode,
        "speed_m_s": v,
        "simulation": None if p is None else simulation_summary(p),
        "settling": None if st is None or not hasattr(st, "as_dict") else st.as_dict(),
        "margin": sc.margin,
        "adequacy": None if sc.adequacy is None else sc.adequacy.as_dict(),
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
        "mode": mode_of(getattr(p, "delta_s", None)) if getattr(p, "success", False) else None,
    }
    for name in ("delta_s", "residual", "impacts_per_cycle", "contact_fraction", "elapsed_s"):
        if hasattr(p, name):
            out[name] = _json_float(getattr(p, name))
    for name in ("period_cycles", "n_cycles", "transient_cycles"):
        v = getattr(p, name, None)
        if v is not None:
            out[name] = int(v)
    moduli = getattr(p, "floquet_moduli", None)
    if moduli:
        out["mu_max"] = float(max(moduli))
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
