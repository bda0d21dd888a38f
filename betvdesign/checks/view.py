"""What a designer reads of a design check: one compact block per device, JSON v3, HTML.

Built only from the public attributes of :class:`betvdesign.checks.checker.CheckResult`
(its sets, rules, derivations and periodic orbits), so the check itself stays in
:mod:`betvdesign.checks.checker`; this module does not import it (annotations say ``Any``), so
``CheckResult`` may render itself through it (``__repr__``, ``_repr_html_``).
Quantities are written by :func:`betvdesign.output.siformat.format_si`
(text) or as SI floats under unit-named keys (JSON).

The JSON shape (``betv check --json``, :data:`JSON_SCHEMA_VERSION`) is the same for
one or many files: ``{"schema": "betv-check", "version": 4, "verdict": ...,
"devices": [...]}``; its JSON schema is :func:`check_json_schema` (``betv schema
check``). ``--verbose`` adds fields to each set (:data:`VERBOSE_SET_FIELDS`) and repeats
none. Fields may be added in a minor change; removing or renaming one bumps the version.
"""

from __future__ import annotations

import difflib
import html
import json
import math
import textwrap
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field

from betvdesign.checks.adequacy import AdequacyOut, adequacy_line
from betvdesign.checks.rule import RuleResult, no_crossing, travel_axis
from betvdesign.checks.window import format_varpi
from betvdesign.model.domain import mode_of
from betvdesign.output.numbers import RULE as NUMBER_RULE
from betvdesign.output.numbers import json_float
from betvdesign.output.presentation import STATUS_COLORS, STATUS_STYLES, rule_status
from betvdesign.output.siformat import format_dimensionless as fmt_x
from betvdesign.output.siformat import format_si, si_key

JSON_SCHEMA_VERSION = 4
#: What each version changed (``betv schema check``, ``x-betv-changes``; README).
VERSION_CHANGES = {
    2: "non-finite numbers are null (a rule value of inf was the string 'inf'); per set "
    "basis and delta_s_error (how well Δs is determined; the mode may be 'undetermined'); "
    "details: mode_predicted -> mode (the verdict's mode), lambda_mode (λ's)",
    3: "one shape: the untyped --verbose 'details' record is gone (its device, file, "
    "verdict, notes, rules, params, derived, mode, margin, adequacy and speed repeated "
    "the typed fields); --verbose adds to each set mode_source (worded from basis, no "
    "longer always 'exact periodic orbit'), simulation, vertical, settling, "
    "determination, travel, published_fit and record",
    4: "a speed is a magnitude beside its mode everywhere: adequacy ideal/richer speed_m_s "
    "(were signed along the impacts); derived.drawn adds the stroke predicted from the "
    "drawing (stroke_m, u_static_m, t_max_k, power_w, current_a, resistance_ohm, "
    "f_thermal_hz, f_heat_hz, stroke_status; null when the file gives the stroke); rules "
    "thermal.peak-temperature, thermal.bandwidth, thermal.power, thermal.sources",
}

#: The set fields that only ``--verbose`` writes (:func:`output_json`).
VERBOSE_SET_FIELDS = (
    "mode_source",
    "simulation",
    "vertical",
    "settling",
    "determination",
    "travel",
    "published_fit",
    "record",
)

#: What the mode and speed of a set quote, in words, by the travel answer's basis
#: (:class:`betvdesign.checks.travel.TravelAnswer`).
MODE_SOURCE = {
    "periodic": "exact periodic orbit (it settles early in the travel)",
    "crossing": "transient from rest: the crossing of the travel (the orbit has not "
    "settled by then, or its Δs is not determined)",
    "no-crossing": "transient from rest: no crossing of the travel within the horizon",
    "undetermined": "neither a determined periodic orbit nor a crossing of the travel",
    "no-orbit": "no exact periodic orbit (its status decides)",
}


def rule_unit(r: RuleResult) -> str:
    """SI unit of a rule's value.

    Parameters
    ----------
    r : RuleResult
        A rule's outcome.

    Returns
    -------
    str
        The rule's own ``unit`` ("" when dimensionless).
    """
    return r.unit


#: Record symbols reported as SI floats: (record symbol, JSON name, SI unit).
_DERIVED_SI: tuple[tuple[str, str, str], ...] = (
    ("M", "slider_mass", "kg"),
    ("m", "head_mass", "kg"),
    ("k_v", "k_v", "N/m"),
    ("k_h", "k_h", "N/m"),
    ("f_v", "f_v", "Hz"),
    ("f_act", "f_act", "Hz"),
    ("u_cal", "calibrated_amplitude", "m"),
    ("f_c", "thermal_cutoff", "Hz"),
    ("f_cal", "calibration_frequency", "Hz"),
    ("u", "amplitude", "m"),
    ("t_s", "time_scale", "s"),
    ("ℓ", "length_scale", "m"),
)


# --- the JSON contract (pydantic models: validated output and its schema) -----------------


class _Out(BaseModel):
    model_config = ConfigDict(extra="forbid")


class RuleOut(_Out):
    """One design rule's outcome."""

    id: str
    severity: Literal["error", "warning", "info"]
    passed: bool
    value: float | None = Field(description="the number checked, in value_unit (SI)")
    value_unit: str = Field(description="SI unit of value; '' when dimensionless")
    threshold: str
    message: str
    fix: str = Field(description="what to change to pass ('' when none is known)")
    source: str


class LambdaOut(_Out):
    """The paper's λ criterion beside the exact answer (never decisive)."""

    value: float
    predicts: Literal["push", "pull"]
    agrees: bool | None = Field(description="λ's mode equals the exact one (None: no mode)")


class MarginOut(_Out):
    """Whether the exact mode survives fabrication spread (rule mode-margin)."""

    holds: bool | None = Field(description="same mode at every corner (None: not computed)")
    corners: dict[str, str | None] = Field(description="exact mode at each perturbed corner")


class SimulationOut(_Out):
    """The exact periodic orbit of a set (:func:`simulation_summary`)."""

    status: str
    success: bool
    message: str
    mode: str | None = Field(description="Δs's mode (None without an orbit)")
    delta_s: float | None = Field(description="periodic slider increment per cycle [-]")
    residual: float | None = Field(description="shooting residual [-]")
    impacts_per_cycle: float | None
    contact_fraction: float | None = Field(description="share of a cycle in contact [-]")
    elapsed_s: float | None = Field(description="solver time [s]")
    period_cycles: int | None = Field(None, description="cycles per period (None: unknown)")
    n_cycles: int | None = Field(None, description="cycles simulated (None: unknown)")
    transient_cycles: int | None = Field(None, description="(None: unknown)")
    mu_max: float | None = Field(None, description="slowest Floquet modulus |μ| [-]")


class VerticalOut(_Out):
    """The exact vertical motion of a set (:func:`betvdesign.dynamics.vertical_motion`)."""

    success: bool
    message: str
    regime: str | None = None
    hits_per_cycle: float | None = None
    impulsive_per_cycle: float | None = None
    contact_fraction: float | None = Field(None, description="[-]")


class PublishedFitOut(_Out):
    """One model parameter against the paper's published fit."""

    param: str
    computed: float
    published: list[float] = Field(description="the published value or range")
    rel_diff: float | None


class RecordStepOut(_Out):
    """One step of a set's derivation (:class:`betvdesign.nondim.record.DerivationStep`)."""

    symbol: str
    key: str
    description: str
    formula: str
    value: str = Field(description="the value with its unit, as text")
    inputs: list[str]


class SetOut(_Out):
    """One actuator set: mode, speed and parameters."""

    name: str
    intended_mode: Literal["push", "pull"]
    impact_direction: Literal["+x", "-x"]
    mode: str = Field(
        description="push, pull, stalled, undetermined (Δs not determined in float64 and "
        "no crossing of the travel), not driven (no contact recurs) or unknown (no exact "
        "orbit); the crossing's mode when basis is crossing"
    )
    passed: bool = Field(description="every error-severity rule of the set passes")
    delta_s: float | None = Field(description="periodic slider increment per cycle [-]")
    delta_s_error: float | None = Field(
        None,
        description="how well delta_s is determined: its largest change under re-solves "
        "with every parameter moved by 1e-12 [-] (None: not assessed or not finite)",
    )
    basis: str | None = Field(
        None,
        description="what the mode and speed quote: periodic (the settled orbit), crossing "
        "(the transient from rest over the travel, not settled by then), no-crossing (does "
        "not cross the travel within the horizon: fails), undetermined (Δs not determined "
        "in float64: fails) or no-orbit",
    )
    model: Literal["decoupled", "coupled"] = Field(
        "decoupled",
        description="whose orbit mode and speed quote: the paper's decoupled springs, or the "
        "drawn head's coupled model (a drawn head and no measured resonances; docs/MODEL.md "
        "'Coupled head')",
    )
    speed_m_s: float | None = Field(
        description="mean slider speed magnitude [m/s] (the speed rule's: periodic, or "
        "from rest over the travel range when it has not settled by then)"
    )
    travel_direction: Literal["+x", "-x"] | None
    time_to_cross_s: float | None = Field(description="time to cross travel_range_m [s]")
    travel_range_m: float
    params: dict[str, float] = Field(
        description="varpi, alpha, beta, kappa [-]; zeta_v, zeta_h, restitution [-] too when "
        "the device gives damping or restitution"
    )
    lambda_: LambdaOut = Field(alias="lambda")
    margin: MarginOut
    adequacy: AdequacyOut | None = Field(None, description="model adequacy (rule of that name)")
    derived: dict[str, Any] = Field(
        description="SI floats, unit-named keys (f_act_hz, ...); 'drawn': the drawn "
        "actuator's f_v_hz, f_h_hz, k_v_n_m, k_h_n_m, m_eff_kg, coupling, f_1_hz, f_oop_hz "
        "(each null without a drawing)"
    )
    rules: list[RuleOut]
    # --verbose only (VERBOSE_SET_FIELDS): the solvers' answers and the derivation
    mode_source: str | None = Field(
        None, description="--verbose: what mode and speed quote, in words (from basis)"
    )
    simulation: SimulationOut | None = Field(
        None, description="--verbose: the exact periodic orbit (None: not solved)"
    )
    vertical: VerticalOut | None = Field(
        None, description="--verbose: the exact vertical motion (None: not solved)"
    )
    settling: dict[str, Any] | None = Field(
        None,
        description="--verbose: the transient from rest (Settling.as_dict: status, message, "
        "cycles_to_settle, cycles_to_cross, crossing_delta_s, ...; None: not run or failed)",
    )
    determination: dict[str, Any] | None = Field(
        None,
        description="--verbose: how well Δs is determined (Determination.as_dict; None: "
        "not assessed)",
    )
    travel: dict[str, Any] | None = Field(
        None,
        description="--verbose: the answer quoted (TravelAnswer.as_dict: basis, mode, "
        "delta_s, delta_s_periodic, cycles_to_cross, horizon_cycles, reason, fix)",
    )
    published_fit: list[PublishedFitOut] | None = Field(
        None, description="--verbose: the device's parameters against the published fit"
    )
    record: list[RecordStepOut] | None = Field(
        None, description="--verbose: the derivation, step by step"
    )


class DeviceOut(_Out):
    """One device file."""

    device: str
    file: str
    verdict: Literal["pass", "fail"]
    failed: list[str] = Field(description="ids of failing error-severity rules")
    sets: list[SetOut]
    rules: list[RuleOut] = Field(description="device-level rules (not tied to a set)")
    ignored: list[str] = Field(description="rule ids left out by --select/--ignore")
    notes: list[str]


class CheckOutput(_Out):
    """``betv check --json``: one object for one or many files."""

    schema_: Literal["betv-check"] = Field("betv-check", alias="schema")
    version: Literal[4] = JSON_SCHEMA_VERSION
    betvdesign: str = Field(description="betvdesign version that wrote this")
    verdict: Literal["pass", "fail"] = Field(description="fail when any device fails")
    devices: list[DeviceOut]


def check_json_schema() -> dict[str, Any]:
    """JSON schema of ``betv check --json`` (``betv schema check``).

    Returns
    -------
    dict
        The draft 2020-12 schema of :class:`CheckOutput`, version
        :data:`JSON_SCHEMA_VERSION`.
    """
    schema = CheckOutput.model_json_schema(by_alias=True, mode="serialization")
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    schema["title"] = f"betv check --json, version {JSON_SCHEMA_VERSION} (betvdesign)"
    schema["x-betv-numbers"] = NUMBER_RULE
    schema["x-betv-changes"] = VERSION_CHANGES
    return schema


# --- rule selection (--select/--ignore, [tool.betv]) -------------------------------------


@dataclass(frozen=True)
class RuleFilter:
    """Which rules count: ``select`` minus ``ignore``.

    A selector matches a rule id exactly or as a dotted prefix (``fit-range`` matches
    ``fit-range.beta``).

    Parameters
    ----------
    select : tuple of str
        Rules that count (empty: all).
    ignore : tuple of str
        Rules left out.
    """

    select: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()

    def keeps(self, rule_id: str) -> bool:
        """Whether a rule counts.

        Parameters
        ----------
        rule_id : str
            The rule's id.

        Returns
        -------
        bool
            Selected (or no selection) and not ignored.
        """
        if self.select and not any(self._hit(rule_id, s) for s in self.select):
            return False
        return not any(self._hit(rule_id, s) for s in self.ignore)

    def unmatched(self, results: Sequence[Any]) -> list[str]:
        """Selectors that match no rule.

        Selectors that match no rule (a typo, or a rule these devices do not have, e.g.
        published-fit without a published fit).

        Parameters
        ----------
        results : sequence of CheckResult
            The checked devices.

        Returns
        -------
        list of str
            A warning per such selector, with the closest rule id.
        """
        ids = sorted({r.id for res in results for r in res.rules})
        known = sorted(set(ids) | {i.split(".")[0] for i in ids})
        out = []
        for opt, sels in (("--select", self.select), ("--ignore", self.ignore)):
            for s in sels:
                if not any(self._hit(i, s) for i in ids):
                    close = difflib.get_close_matches(s, known, n=1)
                    hint = f"; did you mean {close[0]!r}?" if close else ""
                    out.append(f"{opt} {s}: matches no rule of these devices{hint}")
        return out

    @staticmethod
    def _hit(rule_id: str, sel: str) -> bool:
        return rule_id == sel or rule_id.startswith(sel + ".")


# --- the view of one device ---------------------------------------------------------------


@dataclass
class DeviceView:
    """A checked device as a designer reads it (``repr`` one screen, ``_repr_html_``).

    Parameters
    ----------
    result : CheckResult
        The full :class:`~betvdesign.checks.checker.CheckResult` (not imported here: the
        checker renders itself through this module).
    rule_filter : RuleFilter
        The rules that count (``--select``/``--ignore``; ``CheckResult.view`` passes
        the result's own).
    """

    result: Any  # betvdesign.checks.checker.CheckResult
    rule_filter: RuleFilter = field(default_factory=RuleFilter)

    @property
    def rules(self) -> list[RuleResult]:
        """The rules that count under ``rule_filter``."""
        return [r for r in self.result.rules if self.rule_filter.keeps(r.id)]

    @property
    def verdict(self) -> Literal["pass", "fail"]:
        """The verdict: "fail" when a counted error-severity rule fails."""
        return "fail" if self.failed else "pass"

    @property
    def failed(self) -> list[str]:
        """Ids of the counted error-severity rules that fail (each once)."""
        return _unique(r.id for r in self.rules if r.severity == "error" and not r.passed)

    @property
    def out(self) -> DeviceOut:
        """The JSON of this device (:meth:`as_out` without the verbose fields)."""
        return self.as_out()

    def as_out(self, *, verbose: bool = False) -> DeviceOut:
        """The JSON of this device.

        Parameters
        ----------
        verbose : bool
            Fill each set's :data:`VERBOSE_SET_FIELDS` (``--verbose``).

        Returns
        -------
        DeviceOut
            Verdict, failing rules, sets (SI floats under unit-named keys), rules, notes.
        """
        res = self.result
        return DeviceOut(
            device=res.derivation.name,
            file=res.source_file,
            verdict=self.verdict,
            failed=self.failed,
            sets=[_set_out(sc, self.rule_filter, verbose) for sc in res.sets],
            rules=[_rule_out(r) for r in self.rules if not r.set_name],
            ignored=_unique(r.id for r in res.rules if not self.rule_filter.keeps(r.id)),
            notes=list(res.notes),
        )

    def as_json(self, *, verbose: bool = False) -> dict[str, Any]:
        """The JSON object of this device, as ``betv check --json`` writes it.

        Parameters
        ----------
        verbose : bool
            With each set's :data:`VERBOSE_SET_FIELDS` (``--verbose``).

        Returns
        -------
        dict
            :meth:`as_out` dumped (aliases, JSON numbers; the verbose fields only with
            ``verbose``).
        """
        exclude = None if verbose else {"sets": {"__all__": set(VERBOSE_SET_FIELDS)}}
        return self.as_out(verbose=verbose).model_dump(mode="json", by_alias=True, exclude=exclude)

    def text(self, width: int = 100) -> str:
        """The compact block in plain text.

        Parameters
        ----------
        width : int
            Columns to wrap at.

        Returns
        -------
        str
            :func:`compact_lines` without markup.
        """
        return "\n".join(compact_lines(self, width=width, markup=False))

    def __repr__(self) -> str:
        """The compact text block (:meth:`text`)."""
        return self.text()

    def _repr_html_(self) -> str:
        return device_html(self)


def _unique(items: Iterable[str]) -> list[str]:
    return list(dict.fromkeys(items))


def _rule_out(r: RuleResult) -> RuleOut:
    v = r.value
    return RuleOut(
        id=r.id,
        severity=r.severity,
        passed=r.passed,
        value=None if v is None or not math.isfinite(v) else float(v),
        value_unit=rule_unit(r),
        threshold=r.threshold,
        message=r.message,
        fix=r.fix,
        source=r.source,
    )


def set_motion(sc: Any) -> tuple[float | None, float | None, str | None]:
    """How a set moves the slider.

    Parameters
    ----------
    sc : SetCheck
        A set of a :class:`~betvdesign.checks.checker.CheckResult`.

    Returns
    -------
    tuple
        (Δs [-] of its exact periodic orbit, speed magnitude [m/s] its speed rule
        reports, travel direction "+x"/"-x"); None where there is none (speed 0.0 when
        the slider does not advance).
    """
    p = sc.periodic
    ds = None
    if p is not None and p.success and p.delta_s is not None:
        ds = float(p.delta_s) if math.isfinite(float(p.delta_s)) else None
    v = sc.speed_m_s
    if v is None or not math.isfinite(v) or v == 0.0:
        return ds, (0.0 if v == 0.0 else None), None
    return ds, abs(float(v)), travel_axis(sc.derivation, v)


def _error(sc: Any) -> float | None:
    """The set's Δs error [-] when assessed and finite, else None."""
    d = sc.determination
    if d is None or d.delta_s_error is None or not math.isfinite(d.delta_s_error):
        return None
    return float(d.delta_s_error)


#: The margin's spread as the headline says it, with no-break spaces (U+00A0) so that a
#: wrapped line never splits "ϖ ±5 %" (textwrap and HTML break only at ordinary spaces).
MARGIN_SPREAD = "ϖ\u00a0±5\u00a0%, α\u00a0±10\u00a0%"


def _margin(sc: Any) -> tuple[bool | None, str]:
    """(holds, short text) of the set's mode-margin rule."""
    r = next((r for r in sc.rules if r.id == "mode-margin"), None)
    if r is None:
        return None, "margin not computed"
    if r.passed:
        return True, f"mode holds at {MARGIN_SPREAD}"
    flips = r.value if r.value is not None and math.isfinite(r.value) else None
    n = f"{flips:g} of 4 corners" if flips is not None else "some corners"
    return False, f"mode flips at {n} of {MARGIN_SPREAD}!"


def _set_out(sc: Any, flt: RuleFilter, verbose: bool = False) -> SetOut:
    s = sc.derivation
    ds, v, direction = set_motion(sc)
    derived: dict[str, Any] = {}
    for sym, name, unit in _DERIVED_SI:
        try:
            q = s.step(sym).value
        except KeyError:
            continue
        derived[si_key(name, unit)] = float(q.to(unit).magnitude)
    derived["drawn"] = s.drawn()  # issue 30: the drawn actuator's mechanics
    rules = [r for r in sc.rules if flt.keeps(r.id)]
    p = s.params
    lam_mode = "push" if s.lam < 1.0 else "pull"
    exact = sc.verdict_mode
    holds, _ = _margin(sc)
    return SetOut(
        name=s.name,
        intended_mode=s.intended_mode,
        impact_direction=s.actuator_set.impact_direction,
        mode=exact,
        passed=not any(r.severity == "error" and not r.passed for r in rules),
        delta_s=ds,
        delta_s_error=_error(sc),
        basis=None if sc.travel is None else sc.travel.basis,
        model=sc.model,
        speed_m_s=v,
        travel_direction=direction,  # type: ignore[arg-type]
        time_to_cross_s=sc.time_to_cross_s if v else None,
        travel_range_m=s.travel_range_m,
        params=p.as_dict(),
        **{
            "lambda": LambdaOut(
                value=s.lam,
                predicts=lam_mode,
                agrees=(lam_mode == exact) if exact in ("push", "pull") else None,
            )
        },
        margin=MarginOut(holds=holds, corners=dict(sc.margin or {})),
        adequacy=None if sc.adequacy is None else AdequacyOut.of(sc.adequacy),
        derived=derived,
        rules=[_rule_out(r) for r in rules],
        **(_verbose_fields(sc) if verbose else {}),
    )


def _verbose_fields(sc: Any) -> dict[str, Any]:
    """The set's :data:`VERBOSE_SET_FIELDS` (``--verbose``)."""
    s = sc.derivation
    st = sc.settling
    basis = "periodic" if sc.travel is None else sc.travel.basis
    return {
        "mode_source": MODE_SOURCE.get(basis, basis),
        "simulation": None if sc.periodic is None else simulation_summary(sc.periodic),
        "vertical": None if sc.vertical is None else _vertical_out(sc.vertical),
        "settling": None if st is None or st.status == "failed" else st.as_dict(),
        "determination": None if sc.determination is None else sc.determination.as_dict(),
        "travel": None if sc.travel is None else sc.travel.as_dict(),
        "published_fit": [
            PublishedFitOut(
                param=c.name,
                computed=c.computed,
                published=list(c.published),
                rel_diff=c.rel_diff,
            )
            for c in s.published
        ],
        "record": [
            RecordStepOut(
                symbol=st.symbol,
                key=st.key,
                description=st.description,
                formula=st.formula,
                value=st.value_str,
                inputs=list(st.inputs),
            )
            for st in s.record
        ],
    }


def simulation_summary(p: Any) -> SimulationOut:
    """Summary of a periodic-orbit result (``--verbose`` JSON, ``betv check -v``).

    Parameters
    ----------
    p : PeriodicResult
        The exact orbit (a failed one included).

    Returns
    -------
    SimulationOut
        ``status``, ``success``, ``message``, ``mode`` (None without an orbit),
        ``delta_s`` [-], ``residual`` [-], ``impacts_per_cycle``, ``contact_fraction``
        [-], ``elapsed_s`` [s], the cycle counts (``period_cycles``, ``n_cycles``,
        ``transient_cycles``) and ``mu_max`` (slowest Floquet modulus |μ| [-]); None
        where unknown or not finite.
    """
    moduli = p.floquet_moduli

    def count(k: Any) -> int | None:
        return None if k is None else int(k)

    return SimulationOut(
        status=str(p.status),
        success=bool(p.success),
        message=str(p.message),
        mode=mode_of(p.delta_s) if p.success else None,
        delta_s=json_float(p.delta_s),
        residual=json_float(p.residual),
        impacts_per_cycle=json_float(p.impacts_per_cycle),
        contact_fraction=json_float(p.contact_fraction),
        elapsed_s=json_float(p.elapsed_s),
        period_cycles=count(p.period_cycles),
        n_cycles=count(p.n_cycles),
        transient_cycles=count(p.transient_cycles),
        mu_max=float(max(moduli)) if moduli else None,
    )


def _vertical_out(v: Any) -> VerticalOut:
    """The exact vertical motion (a VerticalResult) for the JSON."""
    if not v.success:
        return VerticalOut(success=False, message=str(v.message))
    return VerticalOut(
        success=True,
        message=str(v.message),
        regime=str(v.regime),
        hits_per_cycle=json_float(v.hits_per_cycle),
        impulsive_per_cycle=json_float(v.impulsive_per_cycle),
        contact_fraction=json_float(v.contact_fraction),
    )


# --- text ---------------------------------------------------------------------------------

#: How the quoted speed was obtained, by the travel answer's basis. The check's text
#: names the exception (a crossing from rest); a speed without a label is the periodic
#: orbit's, as the JSON's ``basis`` says.
SPEED_BASIS = {"periodic": "periodic orbit", "crossing": "crossing mean from rest"}


def _no_motion(sc: Any, mode: str, v: float | None) -> str:
    """Why a set shows no speed, in a few words (never contradicting its rules)."""
    ans = sc.travel
    s = sc.derivation
    if ans is not None and ans.basis == "no-crossing":
        return no_crossing(s.travel_range_m, ans.horizon_cycles or 0, s.scales.f_act_hz)
    if ans is not None and ans.basis == "undetermined":
        return "Δs not determined in float64 (see the mode rule)"
    if mode == "not driven":
        return "no periodic drive (impulsive hits only)"
    return "the slider does not move" if v == 0.0 else "no speed (no exact orbit)"


def set_headline(sc: Any) -> tuple[str, str]:
    """Two short lines for a set (plain text).

    Parameters
    ----------
    sc : SetCheck
        A set of a :class:`~betvdesign.checks.checker.CheckResult`.

    Returns
    -------
    tuple of str
        Mode, speed [m/s], travel and margin; drive (f_act [Hz], stroke u [m]) and the
        dimensionless parameters with λ's prediction.
    """
    s = sc.derivation
    p = s.params
    _, v, direction = set_motion(sc)
    mode = sc.verdict_mode
    if mode in ("push", "pull"):
        agree = "as intended" if mode == s.intended_mode else f"instead of {s.intended_mode}"
        head = f"{mode} {agree}"
    else:
        head = f"{mode} (intended {s.intended_mode})"
    if v:
        basis = sc.travel.basis if sc.travel is not None else "periodic"
        label = "" if basis == "periodic" else f" ({SPEED_BASIS.get(basis, basis)})"
        motion = (
            f"{format_si(v, 'm/s')} toward {direction}{label}, "
            f"{format_si(s.travel_range_m, 'm')} in {format_si(sc.time_to_cross_s, 's')}"
        )
    else:
        motion = _no_motion(sc, mode, v)
    line1 = f"{head}, {motion}; {_margin(sc)[1]}"
    lam_mode = "push" if s.lam < 1.0 else "pull"
    word = "" if mode not in ("push", "pull") else (" agrees" if lam_mode == mode else " disagrees")
    sc_ = s.scales
    rolled = f" (roll-off ×{sc_.rolloff_factor:.3g})" if sc_.has_rolloff else ""
    line2 = (
        f"f_act {format_si(sc_.f_act_hz, 'Hz')}, u {format_si(sc_.u_m, 'm')}{rolled} | "
        f"ϖ {format_varpi(p.varpi)} α {fmt_x(p.alpha)} β {fmt_x(p.beta)} κ {fmt_x(p.kappa)}"
        f"{_beyond(p)} | λ {fmt_x(s.lam)} → {lam_mode}{word}"
    )
    return line1, line2


def _beyond(p: Any) -> str:
    """`` Q_v 30 Q_h ∞ e 0.1``: damping and restitution, when the device gives any."""
    if p.ideal:
        return ""
    from betvdesign.model.damping import quality_from_zeta

    q_v, q_h = ("∞" if z == 0 else fmt_x(quality_from_zeta(z)) for z in (p.zeta_v, p.zeta_h))
    return f" Q_v {q_v} Q_h {q_h} e {fmt_x(p.restitution)}"


def compact_lines(view: DeviceView, *, width: int = 100, markup: bool = True) -> list[str]:
    """The default ``betv check`` block.

    Parameters
    ----------
    view : DeviceView
        The checked device.
    width : int
        Columns to wrap at.
    markup : bool
        Rich colour tags (text escaped for rich).

    Returns
    -------
    list of str
        Verdict, two or three lines per set, the failing rules (grouped across sets) with
        their fix.
    """
    from rich.markup import escape

    esc = escape if markup else (lambda t: t)
    res = view.result
    colour = STATUS_STYLES["pass" if view.verdict == "pass" else "FAIL"]
    verdict = view.verdict.upper()
    head = f"{esc(res.derivation.name)}: " + (f"[{colour}]{verdict}[/]" if markup else verdict)
    if res.source_file:
        head += f"  ({esc(res.source_file)})"
    lines = [head]
    for sc in res.sets:
        l1, l2 = set_headline(sc)
        label = f"  {sc.derivation.name}: "
        lines += _wrap(label + l1, width, len(label), esc)
        lines += _wrap(" " * len(label) + l2, width, len(label), esc)
        if (l3 := adequacy_line(sc.adequacy)) is not None:
            lines += _wrap(" " * len(label) + l3, width, len(label), esc)
    groups: dict[tuple[str, str, str, str], list[str]] = {}
    for r in view.rules:
        if r.passed or r.severity == "info":
            continue
        key = (r.severity, r.id, r.message, r.fix)
        groups.setdefault(key, []).append(r.set_name)
    for (sev, rid, msg, fix), names in sorted(groups.items(), key=lambda kv: kv[0][0] != "error"):
        tag = rule_status(False, sev)
        several = len(res.sets) > 1
        where = f" [{', '.join(n for n in names if n)}]" if several and any(names) else ""
        tag_s = f"[{STATUS_STYLES[tag]}]{tag}[/]" if markup else tag
        text = f"{rid}{where}: {msg}"
        indent = len(tag) + 3  # continuation lines under the rule's text
        wrapped = _wrap("  " + tag + " " + text, width, indent, esc)
        wrapped[0] = wrapped[0].replace(tag, tag_s, 1)
        lines += wrapped
        if fix:
            lines += _wrap(" " * indent + "fix: " + fix, width, indent + 5, esc)
    if not groups:
        lines.append("  all rules pass")
    flt = view.rule_filter
    if flt.select:
        lines += _wrap("  only rules: " + ", ".join(flt.select), width, 4, esc)
    if flt.ignore:
        lines += _wrap("  ignored: " + ", ".join(flt.ignore), width, 4, esc)
    return lines


def _wrap(text: str, width: int, indent: int, esc: Any) -> list[str]:
    out = textwrap.wrap(
        text, width=width, subsequent_indent=" " * indent, break_on_hyphens=False
    ) or [text]
    return [esc(line) for line in out]


def quiet_line(view: DeviceView) -> str | None:
    """One line for a failing device (``--quiet``).

    Parameters
    ----------
    view : DeviceView
        The checked device.

    Returns
    -------
    str or None
        ``FILE: FAIL rule, ...``; None when the device passes.
    """
    if view.verdict == "pass":
        return None
    return (
        f"{view.result.source_file or view.result.derivation.name}: FAIL {', '.join(view.failed)}"
    )


def output(views: Sequence[DeviceView], *, verbose: bool = False) -> CheckOutput:
    """The whole ``--json`` document.

    Parameters
    ----------
    views : sequence of DeviceView
        The checked devices.
    verbose : bool
        Fill each set's :data:`VERBOSE_SET_FIELDS` (``--verbose``).

    Returns
    -------
    CheckOutput
        One object for one or many files; its verdict fails when any device fails.
    """
    from betvdesign import __version__

    devices = [v.as_out(verbose=verbose) for v in views]
    worst = "fail" if any(d.verdict == "fail" for d in devices) else "pass"
    return CheckOutput(betvdesign=__version__, verdict=worst, devices=devices)


def output_json(views: Sequence[DeviceView], *, verbose: bool = False) -> str:
    """The text of ``betv check --json``.

    Parameters
    ----------
    views : sequence of DeviceView
        The checked devices.
    verbose : bool
        Add each set's :data:`VERBOSE_SET_FIELDS` (``--verbose``).

    Returns
    -------
    str
        :func:`output` as indented JSON (None fields kept; the verbose fields only with
        ``verbose``).
    """
    exclude = None if verbose else set_fields_excluded()
    doc = output(views, verbose=verbose).model_dump(mode="json", by_alias=True, exclude=exclude)
    return json.dumps(doc, indent=2, ensure_ascii=False)


def set_fields_excluded() -> dict[str, Any]:
    """The ``exclude`` that drops the verbose set fields.

    The ``exclude`` of ``model_dump`` that leaves out :data:`VERBOSE_SET_FIELDS` of
    every set of a :class:`CheckOutput`.
    """
    return {"devices": {"__all__": {"sets": {"__all__": set(VERBOSE_SET_FIELDS)}}}}


# --- HTML (notebooks) ---------------------------------------------------------------------


def device_html(view: DeviceView) -> str:
    """A small HTML table of the check (Jupyter ``_repr_html_``).

    Parameters
    ----------
    view : DeviceView
        The checked device.

    Returns
    -------
    str
        Verdict, a row per set and per failing rule; every text escaped.
    """
    e = html.escape
    res = view.result
    colour = STATUS_COLORS["pass" if view.verdict == "pass" else "FAIL"]
    rows = []
    for sc in res.sets:
        l1, l2 = set_headline(sc)
        l3 = adequacy_line(sc.adequacy)
        l2 += "" if l3 is None else "\n" + l3
        rows.append(
            f"<tr><th>{e(sc.derivation.name)}</th><td>{e(l1)}<br><small>"
            f"{e(l2).replace(chr(10), '<br>')}</small></td></tr>"
        )
    for r in view.rules:
        if r.passed or r.severity == "info":
            continue
        fix = r.fix
        where = f" [{e(r.set_name)}]" if r.set_name else ""
        tag = rule_status(r.passed, r.severity)
        rows.append(
            f"<tr><th>{e(tag)}</th><td><code>{e(r.id)}</code>{where}: "
            f"{e(r.message)}" + (f"<br><b>fix:</b> {e(fix)}" if fix else "") + "</td></tr>"
        )
    return (
        f"<div><b>{e(res.derivation.name)}</b>: "
        f"<b style='color:{colour}'>{view.verdict.upper()}</b>"
        f"<table>{''.join(rows)}</table></div>"
    )
