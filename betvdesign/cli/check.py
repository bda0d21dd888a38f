"""``betv check FILE...``: device files -> design verdict (compact text, ``--verbose``
tables, ``--quiet`` for CI, or versioned ``--json``; presentation in
:mod:`betvdesign.checkview`).

Thin: loading is :func:`betvdesign.loader.load_device`, numbers are
:func:`betvdesign.nondim.derive`, rules and the optional exact solver are
:func:`betvdesign.checker.check_derivation`.

Exit codes: 0 every error-severity rule passes, 1 a rule fails, 2 bad input or usage.
"""

from __future__ import annotations

import sys
from pathlib import Path

import typer
from rich.console import Console
from rich.markup import escape as esc
from rich.table import Table

from betvdesign import fidelity as fid
from betvdesign.checker import CheckResult, check_derivation, simulation_summary
from betvdesign.checkview import (
    RULE_VALUE_UNITS,
    DeviceView,
    RuleFilter,
    compact_lines,
    output_json,
    quiet_line,
)
from betvdesign.cli import app
from betvdesign.cli.common import EXIT_BAD_INPUT, EXIT_OK, EXIT_RULE_FAILED, user_errors
from betvdesign.cli.config import load_config
from betvdesign.errors import SpecError
from betvdesign.nondim import DERIVED_KEYS, derive_file
from betvdesign.rules import DEFAULT_LAMBDA_MARGIN, RuleResult
from betvdesign.siformat import format_q, format_si

_STATUS = {
    (True, "error"): "[green]ok[/]",
    (True, "warning"): "[green]ok[/]",
    (True, "info"): "[blue]info[/]",
    (False, "error"): "[bold red]FAIL[/]",
    (False, "warning"): "[yellow]warn[/]",
    (False, "info"): "[dim]note[/]",
}


@app.command("check")
def check_cmd(
    files: list[Path] = typer.Argument(..., help="Device YAML files (see devices/)."),
    as_json: bool = typer.Option(
        False, "--json", help="Print JSON (one versioned shape; `betv schema check`)."
    ),
    verbose: bool = typer.Option(
        False, "--verbose", "-v", help="Full rule table, fidelity and derivation of every set."
    ),
    quiet: bool = typer.Option(
        False, "--quiet", "-q", help="CI: print only failing devices, one line each."
    ),
    select: list[str] | None = typer.Option(
        None, "--select", metavar="RULE", help="Only these rules count (repeatable; prefix ok)."
    ),
    ignore: list[str] | None = typer.Option(
        None, "--ignore", metavar="RULE", help="These rules do not count (repeatable)."
    ),
    simulate: bool = typer.Option(
        False, "--simulate", help="Run the exact periodic-orbit solver for every actuator set."
    ),
    closed_form_only: bool = typer.Option(
        False,
        "--closed-form-only",
        help="Never run the solver, even where the closed form cannot decide.",
    ),
    lambda_margin: float | None = typer.Option(
        None,
        "--lambda-margin",
        min=0.0,
        help=f"Required |λ − 1| (default {DEFAULT_LAMBDA_MARGIN:g}: ±5 % on f_v or ±10 % on α "
        "move λ ~10 %).",
    ),
    show_derivation: bool = typer.Option(False, "--derivation", hidden=True),
    fidelity: str | None = typer.Option(
        None,
        "--fidelity",
        metavar="RUNG",
        help="Force the rung that decides the mode: lambda, rigid, full or periodic "
        "(default: the cheapest the fidelity ladder trusts; see `betv ladder`).",
    ),
) -> None:
    """Check device files: design window, push/pull mode, speed, margin, resonance.

    Prints one compact block per device (verdict; per actuator set its mode, speed and
    margin; the failing rules with their fix). Defaults for --select, --ignore and
    --lambda-margin may be set in a [tool.betv] table of pyproject.toml.

    Exit 0 pass, 1 an error rule fails, 2 bad input/usage.
    """
    if simulate and closed_form_only:
        print("error: --simulate and --closed-form-only exclude each other", file=sys.stderr)
        raise typer.Exit(EXIT_BAD_INPUT)
    if quiet and (verbose or show_derivation):
        print("error: --quiet and --verbose exclude each other", file=sys.stderr)
        raise typer.Exit(EXIT_BAD_INPUT)
    mode = "always" if simulate else ("never" if closed_form_only else "auto")
    with user_errors():
        cfg = load_config()
        flt = RuleFilter(
            tuple(select if select else cfg.select), tuple(ignore if ignore else cfg.ignore)
        )
        margin = lambda_margin if lambda_margin is not None else cfg.lambda_margin
        derivations, issues = [], []
        for f in files:  # collect the issues of every file before giving up
            try:
                derivations.append((f, derive_file(f)))
            except SpecError as exc:
                issues.extend(exc.issues)
        if issues:
            raise SpecError(issues)
        results = []
        for f, d in derivations:
            res = check_derivation(
                d,
                simulate=mode,
                lambda_margin=margin,
                fidelity=fidelity,  # type: ignore[arg-type]  # validated: UsageError
            )
            res.source_file = str(f)
            results.append(res)
        flt.validate(results)
    views = [DeviceView(r, flt) for r in results]
    if as_json:
        typer.echo(output_json(views, details=verbose or show_derivation))
    elif quiet:
        for v in views:
            line = quiet_line(v)
            if line is not None:
                typer.echo(line)
    else:
        console = Console(soft_wrap=True, highlight=False)
        width = min(100, console.width) if console.is_terminal else 100
        for i, v in enumerate(views):
            if verbose or show_derivation:
                render(v.result, Console(soft_wrap=False), derivation=True)
            else:
                if i:
                    console.print()
                for line in compact_lines(v, width=width):
                    console.print(line)
        if len(views) > 1:
            failed_names = [v.result.derivation.name for v in views if v.verdict == "fail"]
            console.print(
                f"[bold]summary:[/] {len(views) - len(failed_names)} pass, "
                f"{len(failed_names)} fail"
                + (f" ({esc(', '.join(failed_names))})" if failed_names else "")
            )
    failed = any(v.verdict == "fail" for v in views)
    raise typer.Exit(EXIT_RULE_FAILED if failed else EXIT_OK)


def render(result: CheckResult, console: Console, *, derivation: bool = False) -> None:
    """Rich tables for one device: per set parameters, derived values, rules; then notes."""
    colour = "green" if result.verdict == "pass" else "red"
    console.rule(
        f"[bold]{esc(result.derivation.name)}[/] ({esc(result.source_file)}): "
        f"[bold {colour}]{result.verdict.upper()}[/]"
    )
    for sc in result.sets:
        s = sc.derivation
        p = s.params
        console.print(
            f"[bold]set {esc(s.name)}[/]: intended {s.intended_mode}, impacts "
            f"{s.actuator_set.impact_direction}; ϖ = {p.varpi:.4g}, α = {p.alpha:.4g}, "
            f"β = {p.beta:.4g}, κ = {p.kappa:.4g}, λ = {s.lam:.4g} -> predicted "
            f"[bold]{sc.mode_predicted}[/] (from {sc.mode_source})"
        )
        if sc.fidelity is not None:
            f = sc.fidelity
            forced = ", forced" if f.forced else ""
            console.print(
                esc(
                    f"  fidelity: rung {f.rung}{forced} ({fid.RUNG_INFO[f.rung].model}): {f.reason}"
                ),
                highlight=False,
            )
        derived = [st for st in s.record if st.key in DERIVED_KEYS]
        console.print(
            "  " + esc(", ".join(f"{st.symbol} = {format_q(st.value)}" for st in derived)),
            highlight=False,
        )
        if sc.periodic is not None:
            sim = simulation_summary(sc.periodic)
            extra = ", ".join(
                f"{k} = {v:.4g}" if isinstance(v, float) else f"{k} = {v}"
                for k, v in sim.items()
                if k not in ("success", "message")
            )
            console.print(esc(f"  exact orbit ({sc.simulated_because}): {extra}"), highlight=False)
        if derivation:
            console.print(_record_table(sc))
        _print_rules(sc.rules, console)
    device_rules = [r for r in result.rules if not r.set_name]
    if device_rules:
        console.print("[bold]device[/]")
        _print_rules(device_rules, console)
    for note in result.notes:
        console.print(f"[cyan]note:[/] {esc(note)}", highlight=False)


def _rules_table(rules: list[RuleResult]) -> Table:
    """Compact table (status, severity, rule, value, threshold); messages follow it."""
    t = Table(pad_edge=False, expand=False)
    for col in ("", "severity", "rule", "value"):
        t.add_column(col, no_wrap=True)
    t.add_column("threshold", overflow="fold")
    for r in rules:
        unit = RULE_VALUE_UNITS.get(r.id, "")
        value = "" if r.value is None else (format_si(r.value, unit) if unit else f"{r.value:.4g}")
        t.add_row(_STATUS[(r.passed, r.severity)], r.severity, r.id, value, esc(r.threshold))
    return t


def _print_rules(rules: list[RuleResult], console: Console) -> None:
    """The table, then the message of every failed or informational rule."""
    console.print(_rules_table(rules))
    for r in rules:
        if not r.passed or r.severity == "info":
            console.print(
                f"  {_STATUS[(r.passed, r.severity)]} {r.id}: {esc(r.message)}", highlight=False
            )


def _record_table(sc) -> Table:
    t = Table(title=f"derivation of set {esc(sc.derivation.name)}", pad_edge=False)
    for col in ("symbol", "description", "formula", "value"):
        t.add_column(col, overflow="fold")
    for st in sc.derivation.record:
        t.add_row(
            *(esc(x) for x in (st.symbol, st.description, st.formula, format_q(st.value, digits=4)))
        )
    return t
