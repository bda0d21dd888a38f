"""Build the report model of one device file (data first, rendering later).

load (spec) -> derive (nondim) -> analyse each distinct actuator set (dynamics)
-> the design check (the pipeline of ``betv check``, :func:`betvdesign.api.run_check`, fed
the periodic orbits and vertical motions already computed; the exact orbit decides the
mode) -> format
everything into a :class:`~betvdesign.report.model.Report`. Bad input raises the loader's
:class:`~betvdesign.errors.SpecError` before anything is computed or written.
"""

from __future__ import annotations

import math
from importlib import metadata
from typing import Any

import pint

from betvdesign import __version__
from betvdesign.api import CheckOptions, run_check
from betvdesign.checks.checker import CheckResult, SetCheck
from betvdesign.checks.coupled import DECOUPLED_WARNING
from betvdesign.checks.rule import RuleResult, verdict
from betvdesign.checks.view import rule_unit
from betvdesign.dynamics import periodic_orbit
from betvdesign.dynamics.result import PeriodicResult
from betvdesign.nondim.record import DeviceDerivation, SetDerivation
from betvdesign.output.siformat import format_q, format_si
from betvdesign.report import adequacy, figures, frequency, modemap, thermal
from betvdesign.report.analysis import (
    FULL_ONLY,
    Piece,
    ReportOptions,
    SetAnalysis,
    analyse_set,
    attempt,
)
from betvdesign.report.inputs import PreparedDevice
from betvdesign.report.model import (
    DerivationRow,
    FigureBlock,
    KeyValue,
    Report,
    RuleRow,
    SetReport,
    VerdictBox,
)
from betvdesign.report.variants import field_variants, locate_flips, relative_changes

MAX_WARNINGS = 5
#: The note under a set's figures in the default (short) report.
SHORT_NOTE = (
    "Drawn with betv report --full only: "
    + ", ".join(t.lower() if i else t for i, t in enumerate(FULL_ONLY))
    + " (the model's diagnostics; the verdict, the mode, the speed and the margins above "
    "do not rest on them)."
)
#: The note under the figures of a set whose verdict is the coupled head's (the check's
#: ``model``): the report's orbit, robustness, voltage and frequency figures still solve
#: the paper's decoupled springs; its mode map is the sweep's (the check's answer).
COUPLED_NOTE = (
    f"{DECOUPLED_WARNING}: the verdict, the mode, the speed, the margins and the exact-mode "
    'map above are the coupled head\'s (docs/MODEL.md, "Coupled head"); the displacement, '
    "speed-against-voltage, robustness, speed-against-frequency and orbit figures solve the "
    "paper's decoupled springs and can disagree with them."
)
_SEVERITY_ORDER = {"error": 0, "warning": 1, "info": 2}


# --------------------------------------------------------------------------- formatting


def fmt_num(x: float | None, digits: int = 4) -> str:
    """A float with ``digits`` significant digits; "—" for None."""
    if x is None:
        return "—"
    if isinstance(x, float) and not math.isfinite(x):
        return str(x)
    return f"{x:.{digits}g}"


def fmt_quantity(q: pint.Quantity) -> str:
    """A quantity with 4 significant digits and an SI prefix by magnitude (µ, not u):
    :func:`betvdesign.output.siformat.format_q`."""
    return format_q(q, digits=4)


# --------------------------------------------------------------------------- sections


def derivation_rows(sd: SetDerivation) -> tuple[DerivationRow, ...]:
    return tuple(
        DerivationRow(
            st.symbol, st.description, st.formula, fmt_quantity(st.value), ", ".join(st.inputs)
        )
        for st in sd.record
    )


def rule_rows(results: list[RuleResult]) -> tuple[RuleRow, ...]:
    return tuple(
        RuleRow(
            r.id,
            r.severity,
            format_si(r.value, rule_unit(r), digits=4)
            if r.value is not None and rule_unit(r)
            else fmt_num(r.value),
            r.threshold,
            r.passed,
            r.message,
            r.source,
            "" if r.passed else r.fix,
        )
        for r in results
    )


def top_warnings(results: list[RuleResult]) -> tuple[str, ...]:
    failed = sorted(
        (r for r in results if not r.passed), key=lambda r: _SEVERITY_ORDER.get(r.severity, 3)
    )
    return tuple(f"{r.severity} {r.id}: {r.message}" for r in failed[:MAX_WARNINGS])


def verdict_box(
    sd: SetDerivation, an: SetAnalysis, results: list[RuleResult], sc: SetCheck | None = None
) -> VerdictBox:
    """The verdict box of one set; ``sc`` (its design check) gives the predicted mode and
    the fidelity rung that decided it (without it: the periodic orbit, else λ)."""
    v = verdict(results)
    errors = [r for r in results if r.severity == "error" and not r.passed]
    reason = (
        "every error-severity design rule passes"
        if v == "pass"
        else f"{len(errors)} error-severity rule(s) fail: " + ", ".join(r.id for r in errors)
    )
    per = an.periodic.value
    predicted = sc.verdict_mode if sc is not None else "unknown"
    rung, rung_reason = "periodic", "the verdict always rests on the exact periodic orbit"
    speed_rule = next((r for r in results if r.id == "speed"), None)
    v_m_s = speed_rule.value if speed_rule is not None else None
    if per is not None and v_m_s:
        by = "exact periodic orbit"
        direction = sd.impact_sign * (1 if float(per.delta_s) > 0 else -1)
        speed = f"{format_si(abs(v_m_s), 'm/s')} toward {'+x' if direction > 0 else '−x'}"
        basis = speed_rule.message.rsplit("[", 1)[-1].rstrip("]") if speed_rule else ""
        crossing = (
            format_si(sc.time_to_cross_s if sc is not None else sd.travel_range_m / abs(v_m_s), "s")
            + f" for the {format_si(sd.travel_range_m, 'm')} travel range ({basis})"
        )
    elif per is not None:
        by = "exact periodic orbit"
        speed = crossing = "the slider does not move (stalled)"
    else:
        by = "exact periodic orbit not available: " + str(an.periodic.reason)
        speed = crossing = f"not available ({an.periodic.reason})"
    vr = an.vertical.value
    vertical = (
        f"{vr.regime}: {vr.hits_per_cycle:g} hit(s) per cycle "
        f"({vr.impulsive_per_cycle:g} impulsive), in contact {vr.contact_fraction:.0%} of the time"
        if vr is not None and vr.success
        else f"no periodic contact: {vr.message}"
        if vr is not None
        else f"not available ({an.vertical.reason})"
    )
    return VerdictBox(
        verdict=v,
        vertical=vertical,
        verdict_reason=reason,
        intended_mode=sd.intended_mode,
        predicted_mode=predicted,
        predicted_by=by,
        lam=fmt_num(sd.lam),
        fit_mode=sd.params.lambda_mode,
        speed=speed,
        crossing_time=crossing,
        warnings=top_warnings(results),
        rung=rung,
        rung_reason=rung_reason,
    )


def _versions() -> str:
    parts = [f"betvdesign {__version__}"]
    for dist in ("numpy", "scipy", "matplotlib", "weasyprint"):
        try:
            parts.append(f"{dist} {metadata.version(dist)}")
        except metadata.PackageNotFoundError:  # pragma: no cover
            parts.append(f"{dist} (not installed)")
    return ", ".join(parts)


def provenance(an: SetAnalysis, opts: ReportOptions, timings: bool) -> tuple[KeyValue, ...]:
    rows: list[KeyValue] = [
        KeyValue(
            "Solver",
            "exact event-driven model (closed-form phases, certified event search; "
            "betvdesign.dynamics); periodic orbit by shooting from rest "
            f"(dynamics.periodic_orbit): tol {opts.periodic_tol:g}, budget "
            f"{opts.periodic_max_cycles} cycles ({opts.sweep_max_cycles} per λ-sweep orbit)",
        )
    ]
    per = an.periodic
    if per.ok:
        r = per.value
        rows.append(KeyValue("Periodic orbit", f"{r.status}: {r.message}"))
        for label, val in (
            ("Period [cycles]", r.period_cycles),
            ("Periodic residual", r.residual),
            ("Impacts per cycle", r.impacts_per_cycle),
            ("Contact fraction", r.contact_fraction),
            ("Cycles simulated (orbit search)", r.n_cycles),
            ("Cycles before shooting", r.transient_cycles),
            ("Newton iterations", r.n_newton),
            ("Stable (all |μ| < 1)", r.stable),
            ("Events", r.n_events),
            ("Root evaluations", r.n_root_evals),
        ):
            rows.append(KeyValue(label, fmt_num(val, 3) if isinstance(val, float) else str(val)))
        if r.floquet is not None:
            mults = ", ".join(f"{abs(complex(m)):.3g}" for m in r.floquet)
            rows.append(KeyValue("Floquet multipliers |μ|", mults))
    else:
        rows.append(KeyValue("Periodic orbit", f"not available: {per.reason}"))
    tr = an.transient.value
    if tr is not None:
        counts = ", ".join(f"{k} {v}" for k, v in tr.counters.items())
        rows.append(KeyValue("Run from rest", f"{tr.n_cycles} cycles ({counts})"))
    if an.regime.ok:
        g = an.regime.value.varpi
        rows.append(KeyValue("Regime strip", f"{len(g)} values of ϖ in [{g[0]:.3g}, {g[-1]:.3g}]"))
    if an.robustness.ok:
        sweep = an.robustness.value
        rows.append(
            KeyValue(
                "Robustness sweep",
                f"{sweep.n_orbits} periodic orbits over {', '.join(sweep.fields)}",
            )
        )
    if an.frequency.ok:
        fs = an.frequency.value
        rows.append(
            KeyValue(
                "Speed-frequency sweep",
                f"{fs.n_orbits} periodic orbits, f_act {format_si(fs.f_act_hz[0], 'Hz')} to "
                f"{format_si(fs.f_act_hz[-1], 'Hz')} (thermal roll-off of the stroke)",
            )
        )
    if an.stroke.ok:
        st = an.stroke.value
        rows.append(
            KeyValue(
                "Predicted stroke",
                f"{st.solves} electrothermal solutions (u(V) over {len(st.volts)} voltages, "
                f"0 to {st.volts[-1]:.4g} V; melting voltage bisected to a relative "
                f"{thermal.MELTING_RTOL:g}); u(f) from the device's thermal modes",
            )
        )
    if timings:
        pieces: dict[str, Piece[Any]] = {
            "periodic": an.periodic,
            "vertical": an.vertical,
            "regime": an.regime,
            "transient": an.transient,
            "orbit": an.orbit,
            "robustness": an.robustness,
        }
        if an.frequency.ok:
            pieces["frequency"] = an.frequency
        if an.stroke.ok:
            pieces["predicted stroke"] = an.stroke
        for name, piece in pieces.items():
            rows.append(KeyValue(f"Run time: {name}", f"{piece.elapsed_s:.3g} s"))
    else:
        rows.append(
            KeyValue(
                "Run times",
                "omitted so the report is byte-reproducible "
                "(betv report --timestamp includes them)",
            )
        )
    rows.append(KeyValue("Software", _versions()))
    return tuple(rows)


def _set_key(sd: SetDerivation) -> tuple[Any, ...]:
    """Sets with equal keys give identical computations and figures (up to direction)."""
    a = sd.actuator_set
    return (
        tuple(sd.params.as_dict().values()),
        sd.scales.length_m,
        sd.scales.time_s,
        sd.scales.f_act_hz,
        sd.travel_range_m,
        repr(a.actuator.calibration),
        str(a.drive.voltage),
    )


def design_check(
    der: DeviceDerivation,
    per_set: list[tuple[SetDerivation, SetAnalysis, str | None]],
    opts: ReportOptions,
    adequacy_result: Any = False,
) -> CheckResult:
    """The design check of ``betv check``, fed the report's periodic orbits and vertical
    motions instead of solving them again (the mode-margin corners are solved here), and
    the report's model-adequacy study (``adequacy_result``: a DeviceAdequacy, or False),
    with the check's advice (the fix texts of ``betv check``)."""
    orbits = {sd.params: an.periodic for sd, an, _ in per_set}
    verticals = {
        (sd.params.varpi, sd.params.zeta_v, sd.params.restitution): an.vertical
        for sd, an, _ in per_set
    }

    def solver(p: Any) -> Any:
        piece = orbits.get(p)
        if piece is None:
            return periodic_orbit(p)
        return piece.value if piece.ok else PeriodicResult.failure(p, "failed", str(piece.reason))

    def vertical(varpi: float, *, zeta_v: float = 0.0, restitution: float = 0.0) -> Any:
        piece = verticals[(varpi, zeta_v, restitution)]
        return piece.value if piece.ok else None

    # The advice of ``betv check`` (studies.fix.advise): the report's fix texts are the
    # check's, a concrete change ("raise drive.frequency 2 kHz -> 2.149 kHz").
    # ``coupled="verdict"``: the sets whose check verdict is the coupled head's get it here
    # too (the solver above only stores the decoupled orbits; the coupled ones are the
    # check's own), so the report's verdict is ``betv check``'s.
    options = CheckOptions(advice=True, adequacy=adequacy_result is not False, coupled="verdict")
    return run_check(
        der,
        options,
        solver=solver,
        vertical=vertical,
        adequacy_result=None if adequacy_result is False else adequacy_result,
    )


def _analyse_sets(
    der: Any, opts: ReportOptions
) -> list[tuple[SetDerivation, SetAnalysis, str | None]]:
    """Analyse every actuator set once: orbits, robustness, mode map, frequency sweep.

    Parameters
    ----------
    der : DeviceDerivation
        The device's derivation.
    opts : ReportOptions
        The report's options.

    Returns
    -------
    list of tuple
        Per set its derivation, its analysis and the name of the earlier set with the
        same parameters whose analysis it shares (None: its own).
    """
    analyses: dict[tuple[Any, ...], tuple[str, SetAnalysis]] = {}
    per_set: list[tuple[SetDerivation, SetAnalysis, str | None]] = []
    changes = relative_changes(opts.robustness_points, opts.robustness_span)
    for i, sd in enumerate(der.sets):
        key = _set_key(sd)
        if key in analyses:
            first, an = analyses[key]
            per_set.append((sd, an, first))
            continue
        variants = field_variants(der.spec, i, changes)
        an = analyse_set(sd.params, sd.travel_range_m, sd.scales.length_m, opts, variants)
        if an.robustness.ok:
            an.robustness = attempt(
                lambda i=i, an=an: locate_flips(der.spec, i, an.robustness.value, opts)
            )
        an.mode_map = attempt(
            lambda i=i, sd=sd, an=an: modemap.compute(
                der.spec, i, sd.params.varpi, an.robustness, opts
            )
        )
        an.frequency = attempt(
            lambda sd=sd, an=an: frequency.frequency_sweep(
                sd.params, sd.scales.f_act_hz, an.periodic, opts
            )
        )
        if sd.stroke is not None:
            an.stroke = attempt(lambda sd=sd: thermal.stroke_sweep(der.spec, sd))
        analyses[key] = (sd.name, an)
        per_set.append((sd, an, None))
    return per_set


def build_report(
    prepared: PreparedDevice,
    *,
    options: ReportOptions | None = None,
    generated: str | None = None,
    reproduce: str | None = None,
    figure_workers: int | None = None,
) -> Report:
    """The full report model of one prepared device.

    generated: an ISO timestamp to print (None: no date anywhere, byte-reproducible;
    then run times are also left out). figure_workers: processes drawing the figures
    (:func:`betvdesign.report.figures.batch`; None: one per usable processor, 1: in
    this process); the figures are the same bytes either way.
    """
    with figures.batch(figure_workers) as draw_figures:
        return draw_figures(
            _build_report(prepared, options=options, generated=generated, reproduce=reproduce)
        )


def _build_report(
    prepared: PreparedDevice,
    *,
    options: ReportOptions | None,
    generated: str | None,
    reproduce: str | None,
) -> Report:
    """:func:`build_report` with its figures recorded, not yet drawn."""
    opts = options or ReportOptions()
    der = prepared.derivation
    per_set = _analyse_sets(der, opts)
    adq = adequacy.compute(der)
    check = design_check(der, per_set, opts, adq.value if adq.ok else False)
    results = check.rules
    sets: list[SetReport] = []
    for i, ((sd, an, same_as), sc) in enumerate(zip(per_set, check.sets, strict=True), start=1):
        mine = sc.rules
        figs: list[FigureBlock] = (
            []
            if same_as
            else [
                modemap.figure(f"s{i}-modemap", sd, an.mode_map),
                *figures.set_figures(
                    f"s{i}", sd, an, opts.voltage_points, opts.periodic_tol, full=opts.full
                ),
                *thermal.figures(f"s{i}-stroke", der.spec, sd, an.stroke),
            ]
        )
        adequate = (
            None
            if same_as
            else adequacy.section(
                f"s{i}",
                sd,
                adq,
                tuple(frequency.figures(f"s{i}-frequency", sd, an.frequency, opts.periodic_tol)),
                opts.periodic_tol,
            )
        )
        p = sd.params
        params = (
            KeyValue("ϖ", fmt_num(p.varpi)),
            KeyValue("α", fmt_num(p.alpha)),
            KeyValue("β", fmt_num(p.beta)),
            KeyValue("κ", fmt_num(p.kappa)),
            KeyValue("λ", fmt_num(sd.lam)),
        )
        sets.append(
            SetReport(
                name=sd.name,
                intended_mode=sd.intended_mode,
                params=params,
                verdict=verdict_box(sd, an, mine, sc),
                derivation=derivation_rows(sd),
                rules=rule_rows(mine),
                figures=tuple(figs),
                provenance=provenance(an, opts, timings=generated is not None),
                same_as=same_as,
                adequacy=adequate,
                notes=()
                if same_as
                else ((COUPLED_NOTE,) if sc.model == "coupled" else ())
                + (() if opts.full else (SHORT_NOTE,)),
            )
        )
    device_rules = [r for r in results if not r.set_name]
    spec = der.spec
    return Report(
        title=f"BETV design report: {spec.name}",
        device_name=spec.name,
        description=spec.description or "",
        source_file=str(prepared.path),
        verdict=verdict(results),
        inputs=tuple(prepared.inputs),
        sets=tuple(sets),
        device_rules=rule_rows(device_rules),
        reproduce=reproduce or f"betv report {prepared.path} -o DIR",
        version=__version__,
        generated=generated,
    )
