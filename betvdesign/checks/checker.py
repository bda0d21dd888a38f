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

For a set with a drawn head and no measured resonances (k_v from the drawing, idealised
model: :func:`betvdesign.checks.coupled.uses_coupled`) the orbit of step 2 and the margin
corners of step 3 are the coupled head's (:func:`betvdesign.dynamics.coupled.coupled_orbit`,
docs/MODEL.md "Coupled head"): the drawn head is the only model of such a device, and the
paper's decoupled springs misdescribe it (ρ ≈ 0.96–0.99); without a stable coupled orbit
the coupled transient from rest across the travel
(:func:`betvdesign.dynamics.coupled.coupled_crossing`) is quoted instead. The rules
``mode`` and ``speed`` say so, the rule ``coupled-head`` gives the decoupled answer beside
it, and the Δs determination (a decoupled solver's) is not run for it.

The paper's λ fit is shown beside the exact mode ("agrees"/"disagrees") and never
decides. Identical parameter sets (mirrored actuator sets) are solved once.
:class:`CheckResult` is what ``betv check`` prints (through
:mod:`betvdesign.checks.view`, which also writes its JSON). The check of a device file, a
GDS layout or a spec, with the advice, is :func:`betvdesign.api.run_check`: it calls
:func:`check_derivation` and adds the source, notes and advice as new frozen results,
never by mutation.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any, Literal

from betvdesign.checks.actuator_rules import actuator_rules
from betvdesign.checks.adequacy import DeviceAdequacy, SetAdequacy, assess
from betvdesign.checks.coupled import SRC_COUPLED, coupled_rules, coupling_of, uses_coupled
from betvdesign.checks.process_rules import process_rules
from betvdesign.checks.rule import RuleResult, orbit_mode, verdict
from betvdesign.checks.rules import (
    MARGIN_CORNERS,
    corner_label,
    evaluate_device,
    time_to_cross_s,
)
from betvdesign.checks.thermal_rules import thermal_rules
from betvdesign.checks.travel import TravelAnswer, travel_answer, travel_decides
from betvdesign.checks.view import DeviceView, RuleFilter
from betvdesign.dynamics import periodic_orbit, vertical_motion
from betvdesign.dynamics.determination import Determination
from betvdesign.dynamics.determination import determine as determine_delta_s
from betvdesign.dynamics.result import PeriodicResult
from betvdesign.dynamics.settling import Settling, settling
from betvdesign.dynamics.vertical import VerticalResult
from betvdesign.errors import ParameterError
from betvdesign.model.domain import TRAVEL_HORIZON
from betvdesign.model.params import ModelParams
from betvdesign.nondim.record import DeviceDerivation, SetDerivation

#: Whether transients from rest run: always, never, or "undecided" (only where the orbit
#: gives no periodic answer; :func:`check_derivation`).
Settle = bool | Literal["undecided"]


@dataclass(frozen=True)
class SetCheck:
    """Check outcome of one actuator set.

    Parameters
    ----------
    derivation : SetDerivation
        The derived set.
    rules : list of RuleResult
        Its rules (device-level rules are in :attr:`CheckResult.rules` only).
    periodic : PeriodicResult, optional
        Its exact periodic orbit (status "failed" with the error when the solver raised).
    vertical : VerticalResult, optional
        Its exact vertical motion.
    settling : Settling, optional
        The transient from rest (only for a moving orbit and ``settle=True``).
    margin : dict, optional
        Mode of the exact orbit at each perturbed corner (label -> mode or None).
    adequacy : SetAdequacy, optional
        Is the idealised model enough (:mod:`betvdesign.checks.adequacy`).
    determination : Determination, optional
        How well the orbit's Δs is determined
        (:func:`betvdesign.dynamics.determination.determine`).
    travel : TravelAnswer, optional
        The answer the verdict quotes: the orbit, or the crossing of the travel from
        rest (:func:`betvdesign.checks.travel.travel_answer`).
    model : {"decoupled", "coupled"}
        Whose orbit ``periodic`` is: the paper's decoupled springs, or the drawn head's
        coupled model (:func:`betvdesign.checks.coupled.uses_coupled`).
    """

    derivation: SetDerivation
    rules: list[RuleResult]
    periodic: PeriodicResult | None = None
    vertical: VerticalResult | None = None
    settling: Settling | None = None
    margin: dict[str, str | None] | None = None
    adequacy: SetAdequacy | None = None
    determination: Determination | None = None
    travel: TravelAnswer | None = None
    model: Literal["decoupled", "coupled"] = "decoupled"

    @property
    def mode(self) -> str | None:
        """The mode the verdict quotes.

        The mode the verdict quotes: "push", "pull", "stalled", "undetermined" (Δs not
        determined and no crossing of the travel), or None when no orbit was found; the
        crossing's mode when the slider crosses its travel before it settles.
        """
        if self.travel is not None:
            return self.travel.mode
        return orbit_mode(self.periodic)

    @property
    def verdict_mode(self) -> str:
        """The mode the check reports, in words.

        The mode the check reports: the exact one, "not driven" when no contact
        recurs (the slider is not moved), "unknown" without an orbit.
        """
        not_driven = self.periodic is not None and self.periodic.status == "not_driven"
        if self.mode is None and not_driven:
            return "not driven"
        return self.mode or "unknown"

    @property
    def lambda_mode(self) -> str:
        """The paper's λ prediction (shown beside the exact mode, never decisive)."""
        return self.derivation.lambda_mode

    @property
    def speed_m_s(self) -> float | None:
        """Speed the speed rule reports [m/s] (signed along the impact direction)."""
        r = next((r for r in self.rules if r.id == "speed"), None)
        return None if r is None else r.value

    @property
    def time_to_cross_s(self) -> float | None:
        """Time to cross the travel range [s].

        Time to cross the travel range [s] (:func:`~betvdesign.checks.rules.
        time_to_cross_s`: the transient's own crossing whenever it ran; None when the
        slider does not move).
        """
        v = self.speed_m_s
        if not v:
            return None
        if self.travel is not None:
            return time_to_cross_s(self.derivation, self.travel)
        return self.derivation.travel_range_m / abs(v)


@dataclass(frozen=True)
class CheckResult:
    """Everything ``betv check`` reports for one device.

    Everything ``betv check`` reports for one device (frozen: built whole, by
    :func:`check_derivation` and :func:`betvdesign.api.run_check`, never edited after).

    Parameters
    ----------
    derivation : DeviceDerivation
        The derived device.
    sets : list of SetCheck
        One per actuator set, in the device's order.
    rules : list of RuleResult
        Every rule: each set's, then the device-level ones (the advice's fix texts in
        them when the check was advised).
    notes : list of str
        Remarks of the check (e.g. a mirrored set reused, what a layout's extraction
        assumed).
    source_file : str
        The device file or layout ("" when checked from a spec).
    rule_filter : RuleFilter
        The rules that count (``--select``/``--ignore``; all by default).
    """

    derivation: DeviceDerivation
    sets: list[SetCheck]
    rules: list[RuleResult]
    notes: list[str] = field(default_factory=list)
    source_file: str = ""
    rule_filter: RuleFilter = field(default_factory=RuleFilter)

    @property
    def view(self) -> DeviceView:
        """The check as a designer reads it.

        The check as a designer reads it (text, JSON, HTML;
        :class:`~betvdesign.checks.view.DeviceView`).
        """
        return DeviceView(self, self.rule_filter)

    @property
    def verdict(self) -> Literal["pass", "fail"]:
        """The verdict: "fail" when any counted error-severity rule fails, else "pass"."""
        return verdict([r for r in self.rules if self.rule_filter.keeps(r.id)])

    @property
    def failed(self) -> list[str]:
        """Ids of the counted error-severity rules that fail (each once)."""
        return self.view.failed

    @property
    def out(self) -> Any:
        """The JSON of this device (:class:`~betvdesign.checks.view.DeviceOut`)."""
        return self.view.out

    def text(self, width: int = 100) -> str:
        """The compact block of ``betv check`` in plain text.

        Parameters
        ----------
        width : int
            Columns to wrap at.

        Returns
        -------
        str
            :func:`~betvdesign.checks.view.compact_lines` without markup.
        """
        return self.view.text(width)

    def __repr__(self) -> str:
        """The compact block (:meth:`text`): verdict, a few lines per set, what fails."""
        return self.text()

    def _repr_html_(self) -> str:
        """The check block for notebooks (:class:`~betvdesign.checks.view.DeviceView`)."""
        return self.view._repr_html_()


def _guarded_orbit(solver: Callable[[ModelParams], Any], p: ModelParams) -> PeriodicResult:
    """The orbit of ``p``, or a failed one saying why the solver raised.

    ``solver(p)``, or a failed :class:`~betvdesign.dynamics.PeriodicResult` saying why
    when it raised (a failing solver must not crash the check: the mode rule fails).
    """
    try:
        return solver(p)
    except Exception as exc:
        return PeriodicResult.failure(p, "failed", f"{type(exc).__name__}: {exc}")


def _guarded_vertical(vertical: Callable[..., Any], p: ModelParams) -> VerticalResult | None:
    """The vertical motion of ``p``, or a failed one saying why.

    The vertical motion of ``p`` (None when a stand-in has none), or a failed
    :class:`~betvdesign.dynamics.VerticalResult` saying why when it raised.
    """
    try:
        return vertical(p.varpi, zeta_v=p.zeta_v, restitution=p.restitution)
    except Exception as exc:
        return VerticalResult.failure(p.varpi, f"{type(exc).__name__}: {exc}")


def corner_params(p: ModelParams) -> dict[str, ModelParams]:
    """The perturbed parameter sets of the mode-margin rule.

    Parameters
    ----------
    p : ModelParams
        The set's parameters.

    Returns
    -------
    dict
        Label (``ϖ×0.95``, ``α×1.1``, ...) -> ``p`` with ϖ and α scaled by
        :data:`~betvdesign.checks.rules.MARGIN_CORNERS` (damping and restitution kept).
    """
    out = {}
    for fw, fa in MARGIN_CORNERS:
        out[corner_label(fw, fa)] = replace(p, varpi=p.varpi * fw, alpha=p.alpha * fa)
    return out


def corner_modes(
    p: ModelParams,
    answer: TravelAnswer,
    travel_s: float,
    *,
    solver: Callable[[ModelParams], Any],
    settle: Settle = True,
    horizon: int = TRAVEL_HORIZON,
) -> dict[str, str | None]:
    """The mode at each margin corner, read on the basis of the design's own answer.

    Parameters
    ----------
    p : ModelParams
        The design [-].
    answer : TravelAnswer
        Its quoted answer (:func:`~betvdesign.checks.travel.travel_answer`).
    travel_s : float
        Travel range in units of u·cosθ [-].
    solver : callable
        ``solver(params) -> PeriodicResult`` (the check's cached exact solver).
    settle : bool
        Whether transients from rest may be run (the check's ``settle``).
    horizon : int
        Cycles a corner's transient may take to cross the travel [-].

    Returns
    -------
    dict
        Corner label (:func:`corner_params`) -> mode: the corner's periodic mode when the
        design's answer is periodic; its own travel answer's mode (the crossing from rest
        whenever that is what it quotes, issue 29) when the design's answer is a crossing,
        so the margin never compares a crossing with an orbit.
    """
    corners = corner_params(p)
    if answer.basis == "periodic" or not settle:
        return {k: orbit_mode(solver(q)) for k, q in corners.items()}
    out: dict[str, str | None] = {}
    for k, q in corners.items():
        _, _, ans = answer_over_travel(
            q, solver(q), travel_s, solver=solver, determine=False, horizon=horizon
        )
        out[k] = ans.mode
    return out


def check_derivation(
    derivation: DeviceDerivation,
    *,
    solver: Callable[[ModelParams], Any] | None = None,
    vertical: Callable[..., Any] | None = None,
    margin: bool = True,
    settle: Settle = True,
    target_speed_m_s: float | None = None,
    adequacy: DeviceAdequacy | bool | None = None,
    determine: bool | None = None,
    horizon: int = TRAVEL_HORIZON,
    layout_rules: list[RuleResult] | None = None,
    coupled: bool | Literal["verdict"] | None = None,
) -> CheckResult:
    """Check every actuator set with its exact orbit (see the module docstring).

    Parameters
    ----------
    derivation : DeviceDerivation
        The derived device.
    solver : callable, optional
        Stand-in for :func:`betvdesign.dynamics.periodic_orbit` (tests, studies, the
        report's own orbits); returns a PeriodicResult.
    vertical : callable, optional
        Stand-in for :func:`betvdesign.dynamics.vertical_motion`; may return None.
    margin : bool
        Run the mode-margin corners (:func:`corner_params`).
    settle : bool or "undecided"
        Run the transient from rest (:func:`betvdesign.dynamics.settling.settling`);
        "undecided": only where the orbit gives no periodic answer (Δs not determined,
        no orbit found), the fix search's screen (:mod:`betvdesign.studies.fix`): a
        moving orbit is then quoted as the transient from rest would quote it whenever
        it settles early in the travel.
    target_speed_m_s : float, optional
        A required speed [m/s] (adds the error rule ``target-speed``).
    adequacy : DeviceAdequacy or bool, optional
        Is the idealised model enough (:mod:`betvdesign.checks.adequacy`, rule
        ``model-adequacy``): None runs it with the exact solver unless ``solver`` is
        given, True always (with ``solver``), False never; or an already computed
        :class:`~betvdesign.checks.adequacy.DeviceAdequacy`.
    determine : bool, optional
        Assess how well each orbit's Δs is determined in float64
        (:func:`betvdesign.dynamics.determination.determine`: re-solves with every
        parameter moved by 1e-12; an undetermined Δs fails the mode rule unless the
        slider crosses its travel from rest): None runs it with the exact solver unless
        ``solver`` is given, True always, False never.
    horizon : int
        Cycles the transient from rest may run to cross the travel range [-]; a slider
        that does not cross within them fails the mode rule (raise it for long travels).
    layout_rules : list of RuleResult, optional
        The process rules measured on a drawn layout (:mod:`betvdesign.layout.drc`),
        used instead of those of the device file
        (:func:`betvdesign.checks.process_rules.process_rules`).
    coupled : bool, optional
        The drawn head's coupled model (:mod:`betvdesign.checks.coupled`, rule
        ``coupled-head``): None (default) for the sets whose verdict it gives (drawn head,
        no measured resonances: :func:`~betvdesign.checks.coupled.uses_coupled`), unless
        ``solver`` is given; "verdict" for those sets even with a ``solver`` (one that
        answers the same decoupled orbits, as the report's store of them does); True also
        as a finding for the drawn sets whose file resonances win (their verdict stays the
        decoupled one); False never (every verdict decoupled).

    Returns
    -------
    CheckResult
        The sets with their orbits and rules, every rule, the verdict.

    References
    ----------
    .. [1] Shin, Pai, Lin, Hui and Tien, J. Appl. Phys. 96, 7603 (2004),
       doi:10.1063/1.1809773.

    Over 80 lines on purpose: most of it is this docstring of the check's stages and
    options; the body solves the sets (:func:`_solve_sets`), judges them
    (:func:`~betvdesign.checks.rules.evaluate_device`) and assembles the result.
    """
    custom = solver is not None
    orbit = _Orbits(solver or periodic_orbit)
    vertical = vertical or vertical_motion
    if determine is None:
        determine = not custom
    on = (not custom) if coupled is None else bool(coupled)
    by_coupled = _coupled_sets(derivation, on)
    got = _solve_sets(
        derivation,
        orbit,
        vertical,
        margin=margin,
        settle=settle,
        determine=determine,
        horizon=horizon,
        coupled=by_coupled,
    )
    adq = _adequacy(derivation, adequacy, (lambda p, **_: orbit(p)) if custom else None)
    rules = evaluate_device(
        derivation,
        orbits=got.orbits,
        vertical=got.verticals,
        settling=got.settlings,
        margins=got.margins if margin else None,
        target_speed_m_s=target_speed_m_s,
        adequacy=adq,
        travel=got.answers,
    )
    rules += [r for s in derivation.sets for r in actuator_rules(s)]
    proc = derivation.spec.process
    rules += [r for s in derivation.sets for r in thermal_rules(s, proc)]
    rules += process_rules(derivation.spec) if layout_rules is None else layout_rules
    rules = [_coupled_basis(r, by_coupled.get(r.set_name)) for r in rules]
    if on:
        drawn = [s for s in derivation.sets if coupled is True or s.name in by_coupled]
        solved = {k: c.orbit_of_set() for k, c in by_coupled.items()}
        crossed = {k: v for k, v in got.settlings.items() if k in by_coupled}
        rules += coupled_rules(drawn, orbits=solved, crossings=crossed)
    return CheckResult(derivation, got.set_checks(derivation, rules, adq), rules, got.notes)


def _coupled_sets(derivation: DeviceDerivation, on: bool) -> dict[str, _CoupledOrbits]:
    """The sets whose verdict is the coupled head's (:func:`coupled_head`), by name."""
    out: dict[str, _CoupledOrbits] = {}
    for s in derivation.sets if on else []:
        head = coupled_head(s)
        if head is not None:
            out[s.name] = _CoupledOrbits(*head, s.params)
    return out


def coupled_head(sd: SetDerivation) -> tuple[float, float] | None:
    """Which model answers a set's verdict: the coupled head's drawn (ρ, θ), else None.

    The one decision every face takes it from (``betv check``, ``betv sweep``): the
    coupled head (:func:`betvdesign.dynamics.coupled.coupled_orbit`) answers a set with a
    drawn head and no measured resonances in the idealised model
    (:func:`~betvdesign.checks.coupled.uses_coupled`); a drawing whose coupling cannot be
    formed (no valid ρ or angle) keeps the decoupled verdict (the rule
    ``actuator.coupling`` already names the drawing's problem).

    Parameters
    ----------
    sd : SetDerivation
        The derived set.

    Returns
    -------
    tuple of float or None
        (ρ [-], the impact angle θ [rad]) when the verdict is the coupled head's; None
        when it is the paper's decoupled springs'.
    """
    if not uses_coupled(sd):
        return None
    try:
        cpl = coupling_of(sd)
    except (ParameterError, AssertionError):
        return None
    return None if cpl is None else (float(cpl.rho), float(sd.scales.theta_rad))


class _CoupledOrbits:
    """The coupled head's stable orbit of a set's designs (its own and its margin corners).

    χ = √α·tanθ follows the design's α (a corner's too); each design is solved once,
    guarded as :func:`_guarded_orbit`; the idealised model (:func:`uses_coupled`).
    """

    def __init__(self, rho: float, theta: float, params: ModelParams) -> None:
        """Keep the drawn ρ [-], the impact angle θ [rad] and the set's own design."""
        self.rho, self.theta, self.params = rho, theta, params
        self.solved: dict[ModelParams, Any] = {}

    def __call__(self, p: ModelParams) -> Any:
        """The coupled orbit of ``p`` (solved on first use)."""
        from betvdesign.dynamics.coupled import coupled_orbit
        from betvdesign.model.params import HeadCoupling

        if p not in self.solved:

            def solve(q: ModelParams) -> Any:
                return coupled_orbit(q, HeadCoupling.from_angle(self.rho, q.alpha, self.theta))

            self.solved[p] = _guarded_orbit(solve, p)
        return self.solved[p]

    def orbit_of_set(self) -> Any:
        """The set's own coupled orbit."""
        return self(self.params)


def _coupled_basis(r: RuleResult, co: _CoupledOrbits | None) -> RuleResult:
    """The rules ``mode`` and ``speed`` of a set whose verdict is the coupled head's, saying so."""
    if co is None or r.id not in ("mode", "speed"):
        return r
    chi = math.sqrt(co.params.alpha) * math.tan(co.theta)
    head = (
        f"coupled head (drawn, no measured resonances: ρ = {co.rho:.4g}, χ = {chi:.4g}; "
        "rule coupled-head gives the paper's decoupled springs' answer): "
    )
    return replace(r, message=head + r.message, source=f"{r.source}; {SRC_COUPLED}")


class _Orbits:
    """The exact orbit of a design, each design solved once per check.

    Guarded: a raising solver gives a failed result (:func:`_guarded_orbit`).
    """

    def __init__(self, solver: Callable[[ModelParams], Any]) -> None:
        """Cache the answers of ``solver`` [a PeriodicResult per design]."""
        self.solver = solver
        self.solved: dict[ModelParams, Any] = {}

    def __call__(self, p: ModelParams) -> Any:
        """The orbit of ``p`` (solved on first use)."""
        if p not in self.solved:
            self.solved[p] = _guarded_orbit(self.solver, p)
        return self.solved[p]


@dataclass
class _Solved:
    """The exact answers of every set of a check, by set name (:func:`_solve_sets`)."""

    orbits: dict[str, Any] = field(default_factory=dict)
    verticals: dict[str, Any] = field(default_factory=dict)
    settlings: dict[str, Settling] = field(default_factory=dict)
    margins: dict[str, dict[str, str | None]] = field(default_factory=dict)
    determinations: dict[str, Determination] = field(default_factory=dict)
    answers: dict[str, TravelAnswer] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    coupled: set[str] = field(default_factory=set)

    def set_checks(
        self, derivation: DeviceDerivation, rules: list[RuleResult], adq: dict[str, SetAdequacy]
    ) -> list[SetCheck]:
        """One :class:`SetCheck` per set, in the device's order, with its own rules.

        Parameters
        ----------
        derivation : DeviceDerivation
            The derived device.
        rules : list of RuleResult
            Every rule of the check.
        adq : dict
            Set name -> its adequacy.

        Returns
        -------
        list of SetCheck
            The sets' outcomes.
        """
        return [
            SetCheck(
                s,
                [r for r in rules if r.set_name == s.name],
                self.orbits.get(s.name),
                self.verticals.get(s.name),
                self.settlings.get(s.name),
                self.margins.get(s.name),
                adq.get(s.name),
                self.determinations.get(s.name),
                self.answers.get(s.name),
                "coupled" if s.name in self.coupled else "decoupled",
            )
            for s in derivation.sets
        ]


def _solve_sets(
    derivation: DeviceDerivation,
    orbit: Callable[[ModelParams], Any],
    vertical: Callable[..., Any],
    *,
    margin: bool,
    settle: Settle,
    determine: bool,
    horizon: int,
    coupled: dict[str, _CoupledOrbits] | None = None,
) -> _Solved:
    """The exact answers of every set: orbit, vertical motion, travel, margin corners.

    Identical parameter sets (mirrored sets) are solved once and said so; each set's
    answer over its travel is :func:`answer_over_travel`, its corners
    :func:`corner_modes`.

    Parameters
    ----------
    derivation : DeviceDerivation
        The derived device.
    orbit : callable
        The check's cached exact orbit of a design.
    vertical : callable
        The exact vertical motion (or a stand-in).
    margin, determine : bool
        Run the margin corners, the determination.
    settle : bool or "undecided"
        Run the transient from rest (:func:`check_derivation`).
    horizon : int
        Cycles the transient may take to cross the travel [-].
    coupled : dict, optional
        Set name -> the coupled head's orbit of a design, for the sets whose verdict is
        the coupled head's: their orbit and corners, no determination nor transient.

    Returns
    -------
    _Solved
        The answers by set name, and the notes.
    """
    out = _Solved()
    seen: set[ModelParams] = set()
    answered: dict[tuple[ModelParams, float], tuple[Any, Any, TravelAnswer]] = {}
    vert_of: dict[tuple[float, float, float], Any] = {}
    coupled = coupled or {}
    for s in derivation.sets:
        p = s.params
        if s.name in coupled:
            _solve_coupled(out, s, coupled[s.name], margin=margin, horizon=horizon)
            continue
        if p in seen:
            out.notes.append(f"set {s.name}: same parameters as an already solved set, reused")
        seen.add(p)
        out.orbits[s.name] = po = orbit(p)
        vkey = (p.varpi, p.zeta_v, p.restitution)
        if vkey not in vert_of:
            vert_of[vkey] = _guarded_vertical(vertical, p)
        if vert_of[vkey] is not None:
            out.verticals[s.name] = vert_of[vkey]
        key = (p, s.travel_range_m / s.scales.length_m)
        if key not in answered:
            answered[key] = answer_over_travel(
                p, po, key[1], solver=orbit, determine=determine, settle=settle, horizon=horizon
            )
        det, st, out.answers[s.name] = answered[key]
        if det is not None:
            out.determinations[s.name] = det
        if st is not None:
            out.settlings[s.name] = st
        if margin and out.answers[s.name].moves:
            out.margins[s.name] = corner_modes(
                p, out.answers[s.name], key[1], solver=orbit, settle=settle, horizon=horizon
            )
    return out


def _solve_coupled(
    out: _Solved,
    s: SetDerivation,
    orbit: _CoupledOrbits,
    *,
    margin: bool,
    horizon: int,
) -> None:
    """A set whose verdict is the coupled head's: its orbit, answer and corners into ``out``.

    The answer is :func:`coupled_over_travel`'s; the margin corners only for a periodic
    answer. The vertical motion is not the decoupled one (hits depend on ζ) and is not
    recorded.
    """
    p = s.params
    po, st, ans = _coupled_travel(p, orbit, s.travel_range_m / s.scales.length_m, horizon)
    out.orbits[s.name] = po
    out.coupled.add(s.name)
    if st is not None:
        out.settlings[s.name] = st
    out.answers[s.name] = ans
    out.notes.append(
        f"set {s.name}: mode and speed from the coupled head (drawn head, no measured "
        'resonances; docs/MODEL.md "Coupled head"): '
        + ("its exact stable orbit" if st is None else "its transient from rest (no stable orbit)")
        + "; Δs determination not run for it"
    )
    if margin and ans.moves and ans.basis == "periodic":
        out.margins[s.name] = {k: orbit_mode(orbit(q)) for k, q in corner_params(p).items()}


def coupled_over_travel(
    p: ModelParams,
    head: tuple[float, float],
    travel_s: float,
    *,
    horizon: int = TRAVEL_HORIZON,
) -> tuple[PeriodicResult, Settling | None, TravelAnswer]:
    """What the check says one design does over its travel with the coupled head (unit-free).

    The coupled counterpart of :func:`answer_over_travel`, for a set whose verdict is the
    coupled head's (:func:`coupled_head`): its exact stable orbit
    (:func:`betvdesign.dynamics.coupled.coupled_orbit`), and where it has none that the
    travel can answer for (:func:`~betvdesign.checks.travel.travel_decides`), its
    transient from rest across the travel
    (:func:`betvdesign.dynamics.coupled.coupled_crossing`). No Δs determination (a
    decoupled solver's). The check's and the field sweep's answer of such a design.

    Parameters
    ----------
    p : ModelParams
        The design [-] (idealised).
    head : tuple of float
        The drawn ρ [-] and impact angle θ [rad] (:func:`coupled_head`).
    travel_s : float
        Travel range in units of u·cosθ [-].
    horizon : int
        Cycles the transient may take to cross the travel [-] (at most
        :data:`~betvdesign.dynamics.coupled.CROSSING_HORIZON`).

    Returns
    -------
    tuple
        (the coupled :class:`~betvdesign.dynamics.result.PeriodicResult`, guarded: a
        failed one when the solver raised; :class:`~betvdesign.dynamics.settling.Settling`
        or None; :class:`~betvdesign.checks.travel.TravelAnswer`).
    """
    return _coupled_travel(p, _CoupledOrbits(*head, p), travel_s, horizon)


def _coupled_travel(
    p: ModelParams, orbit: _CoupledOrbits, travel_s: float, horizon: int
) -> tuple[PeriodicResult, Settling | None, TravelAnswer]:
    """:func:`coupled_over_travel` with the check's cache of the set's coupled orbits."""
    from betvdesign.dynamics.coupled import CROSSING_HORIZON, coupled_crossing
    from betvdesign.model.params import HeadCoupling

    po = orbit(p)
    st = None
    if travel_decides(po):
        cpl = HeadCoupling.from_angle(orbit.rho, p.alpha, orbit.theta)
        try:
            st = coupled_crossing(p, cpl, travel_s, max_cycles=min(horizon, CROSSING_HORIZON))
        except Exception as exc:  # reported, never a crash
            st = Settling(
                status="failed", message=f"coupled crossing: {type(exc).__name__}: {exc}",
                cycles_to_settle=None, cycles_to_cross=None, crossing_delta_s=None,
            )  # fmt: skip
    return po, st, travel_answer(po, None, st)


def _adequacy(
    derivation: DeviceDerivation,
    want: DeviceAdequacy | bool | None,
    custom: Callable[..., Any] | None,
) -> dict[str, SetAdequacy]:
    """Adequacy results by set name ({} when not wanted; see :func:`check_derivation`)."""
    if want is False or (want is None and custom is not None):
        return {}
    if want is None or want is True:
        want = assess(derivation, solver=custom)
    return {a.name: a for a in want.sets}


def answer_over_travel(
    p: ModelParams,
    po: PeriodicResult,
    travel_s: float,
    *,
    solver: Callable[[ModelParams], Any] | None = None,
    determine: bool = True,
    settle: Settle = True,
    horizon: int = TRAVEL_HORIZON,
) -> tuple[Determination | None, Settling | None, TravelAnswer]:
    """What the check says one design does over its travel (unit-free).

    The one sequence behind every verdict's mode and speed (the check, the verdict map of
    :mod:`betvdesign.bench.verdictmap`): how well Δs is determined, the transient from
    rest when the orbit moves, is not determined or does not exist for a reason the
    travel can answer (:func:`~betvdesign.checks.travel.travel_decides`), and the
    answer quoted.

    Parameters
    ----------
    p : ModelParams
        The design [-].
    po : PeriodicResult
        Its periodic orbit.
    travel_s : float
        Travel range in units of u·cosθ [-].
    solver : callable, optional
        ``solver(params) -> PeriodicResult`` for the re-solves (default: the exact one).
    determine : bool
        Run the determination.
    settle : bool or "undecided"
        Run the transient from rest; "undecided": only where the orbit gives no periodic
        answer (not for a determined moving orbit).
    horizon : int
        Cycles the transient may take to cross the travel [-].

    Returns
    -------
    tuple
        (:class:`~betvdesign.dynamics.determination.Determination` or None,
        :class:`~betvdesign.dynamics.settling.Settling` or None,
        :class:`~betvdesign.checks.travel.TravelAnswer`).
    """
    det = determine_delta_s(p, po, solver=solver) if determine else None
    unsure = det is not None and det.status in ("undetermined", "degenerate")
    st = None
    moving = settle is True and orbit_mode(po) in ("push", "pull")
    if settle and (moving or unsure or travel_decides(po)):
        st = _settling(p, po, travel_s, horizon)
    return det, st, travel_answer(po, det, st)


def _settling(p: ModelParams, po: PeriodicResult, travel_s: float, horizon: int) -> Settling:
    """The transient from rest against the orbit ``po``.

    The transient from rest against the orbit ``po`` over at most ``horizon`` cycles
    (a failure stand-in if it raised).
    """
    moduli = po.floquet_moduli if po.success else None
    ds = float(po.delta_s) if po.success and po.delta_s is not None else None
    try:
        return settling(
            p,
            ds,
            period_cycles=1
            if not po.success or po.period_cycles is None
            else int(po.period_cycles),
            travel_s=travel_s,
            mu_max=max(moduli) if moduli else None,
            max_cycles=horizon,
        )
    except Exception as exc:  # reported, never a crash
        return Settling(
            status="failed",
            message=f"settling: {type(exc).__name__}: {exc}",
            cycles_to_settle=None,
            cycles_to_cross=None,
            crossing_delta_s=None,
        )
