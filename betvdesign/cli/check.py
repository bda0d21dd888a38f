"""``betv check FILE...``: device files -> design verdict (tables, or ``--json``).

Thin: loading is :func:`betvdesign.loader.load_device`, numbers are
:func:`betvdesign.nondim.derive`, rules and the optional exact solver are
:func:`betvdesign.checker.check_derivation`.

Exit codes: 0 every error-severity rule passes, 1 a rule fails, 2 bad input or usage.
"""

from __future__ import annotations

import json
from pathlib import Path

import typer
from rich.console import Console
from rich.markup import escape as esc
from rich.table import Table

from betvdesign.checker import CheckResult, check_derivation, simulation_summary
from betvdesign.cli import app
from betvdesign.cli.common import EXIT_OK, EXIT_RULE_FAILED, user_errors
from betvdesign.errors import SpecError
from betvdesign.nondim import derive_file
from betvdesign.rules import RuleResult
from betvdesign.units import parse_speed

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
    as_json: bool = typer.Option(False, "--json", help="Print JSON on stdout (a list if >1 file)."),
    target_speed: str | None = typer.Option(
        None,
        "--target-speed",
        metavar="Q",
        help="Required slider speed with its unit, e.g. '1 mm/s' (adds the error rule "
        "target-speed).",
    ),
    show_derivation: bool = typer.Option(
        False, "--derivation", help="Also print every input, formula and intermediate value."
    ),
) -> None:
    """Check device files: design window, push/pull mode, margin, resonance, settling, speed.

    Every set's mode and speed come from its exact periodic orbit (and the transient
    from rest for settling); the paper's λ fit is shown beside it, never decisive.
    Each failed rule says what to change; `betv fix FILE` finds the smallest change.
    Exit 0 pass, 1 an error rule fails, 2 bad input/usage.
    """
    with user_errors():
        target = None if target_speed is None else parse_speed(target_speed, "--target-speed")
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
            res = check_derivation(d, target_speed_m_s=target)
            res.source_file = str(f)
            results.append(res)
    if as_json:
        payload = [r.as_dict() for r in results]
        out = payload[0] if len(payload) == 1 else payload
        typer.echo(json.dumps(out, indent=2, ensure_ascii=False))
    else:
        console = Console(soft_wrap=False)
        for r in results:
            render(r, console, derivation=show_derivation)
        if len(results) > 1:
            failed_names = [r.derivation.name for r in results if r.verdict == "fail"]
            console.print(
                f"[bold]summary:[/] {len(results) - len(failed_names)} pass, "
                f"{len(failed_names)} fail"
                + (f" ({esc(', '.join(failed_names))})" if failed_names else ""),
                highlight=False,
            )
    failed = any(r.verdict == "fail" for r in results)
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
            f"β = {p.beta:.4g}, κ = {p.kappa:.4g} -> exact orbit: [bold]{sc.mode_predicted}[/] "
            f"(λ = {s.lam:.4g} predicts {sc.lambda_mode})"
        )
        console.print(
            "  " + esc(", ".join(f"{k} = {v}" for k, v in s.derived().items())), highlight=False
        )
        if sc.periodic is not None:
            sim = simulation_summary(sc.periodic)
            extra = ", ".join(
                f"{k} = {v:.4g}" if isinstance(v, float) else f"{k} = {v}"
                for k, v in sim.items()
                if k not in ("success", "message")
            )
            console.print(esc(f"  exact orbit: {extra}"), highlight=False)
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
        value = "" if r.value is None else f"{r.value:.4g}"
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
            if r.fix and not r.passed:
                console.print(f"      [cyan]fix:[/] {esc(r.fix)}", highlight=False)


def _record_table(sc) -> Table:
    t = Table(title=f"derivation of set {esc(sc.derivation.name)}", pad_edge=False)
    for col in ("symbol", "description", "formula", "value"):
        t.add_column(col, overflow="fold")
    for st in sc.derivation.record:
        t.add_row(*(esc(x) for x in (st.symbol, st.description, st.formula, st.value_str)))
    return t
