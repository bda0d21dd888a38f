"""``betv check FILE...``: device files -> design verdict (compact text, ``--verbose``
tables, ``--quiet`` for CI, or versioned ``--json``; presentation in
:mod:`betvdesign.checks.view`).

Thin: every file is checked by the one pipeline, :func:`betvdesign.api.run_check` (the
device file or layout read, the rules, the advice), and only rendered here. A repeated
check of unchanged inputs prints the stored answer (:mod:`betvdesign.output.answers`;
``--no-cache`` checks afresh).

Exit codes: 0 every error-severity rule passes, 1 a rule fails, 2 bad input or usage.
"""

from __future__ import annotations

import contextlib
import io
import sys
from pathlib import Path
from typing import TYPE_CHECKING, TextIO

import typer
from rich.console import Console
from rich.markup import escape as esc
from rich.table import Table

from betvdesign.api import HORIZON_RANGE
from betvdesign.cli import app
from betvdesign.cli.common import EXIT_OK, EXIT_RULE_FAILED, int_option, user_errors
from betvdesign.cli.config import load_config
from betvdesign.errors import UsageError, each_or_issues
from betvdesign.model.domain import TRAVEL_HORIZON

if TYPE_CHECKING:  # the heavy layers load when a check runs, not for `betv --help`
    from betvdesign.checks.checker import CheckResult
    from betvdesign.checks.rule import RuleResult

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
    files: list[Path] = typer.Argument(
        ..., help="Device YAML files (see devices/) or GDS layouts labelled as `betv layout` does."
    ),
    as_json: bool = typer.Option(
        False, "--json", help="Print JSON (one versioned shape; `betv schema check`)."
    ),
    verbose: bool = typer.Option(
        False, "--verbose", "-v", help="Every rule in a table, and the derivation of every set."
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
    target_speed: str | None = typer.Option(
        None,
        "--target-speed",
        metavar="Q",
        help="Required slider speed with its unit, e.g. '1 mm/s' (adds the error rule "
        "target-speed).",
    ),
    adequacy: bool = typer.Option(
        True,
        "--adequacy/--no-adequacy",
        help="Judge the idealised model (rule model-adequacy: exact orbits with and without "
        "damping and restitution, Q and e scanned; about 0.2–0.7 s per set). "
        "--no-adequacy skips it.",
    ),
    horizon: int = typer.Option(
        TRAVEL_HORIZON,
        "--horizon",
        metavar="CYCLES",
        callback=int_option(*HORIZON_RANGE, why="cycles of the transient from rest"),
        help="Cycles the transient from rest may take to cross the travel range; a slider "
        "that does not cross within them fails the mode rule (raise it for long travels; "
        "about 1 µs per cycle).",
    ),
    advice: bool = typer.Option(
        True,
        "--advice/--no-advice",
        help="For a failing check (or a mode that flips within the margin), search the "
        "nearest passing value of the fields that move what fails (the search of `betv "
        "fix`, a few seconds) and quote it as the rules' fix. --no-advice skips it.",
    ),
    cache: bool = typer.Option(
        True,
        "--cache/--no-cache",
        help="Print the stored answer of an identical earlier check (the same bytes of "
        "every file read, process files included, the same options, betvdesign code and "
        "installed packages; under ~/.cache/betvdesign/answers, or $BETV_ANSWER_CACHE, "
        "'off' to turn it off). --no-cache checks afresh and stores nothing. The compact "
        "text on a terminal and --verbose (run times) are never cached.",
    ),
    show_derivation: bool = typer.Option(False, "--derivation", hidden=True),
) -> None:
    """Check device files: design window, push/pull mode, speed, margin, resonance, settling.

    Prints one compact block per device: the verdict; per actuator set its mode, speed
    and margin (from the exact periodic orbit; the paper's λ fit beside it) and the
    failing rules, each with what to change: the nearest passing value of the fields
    that move what fails, from the same search as `betv fix FILE`.
    Defaults for --select, --ignore and --target-speed may be set in a [tool.betv] table
    of pyproject.toml.

    Exit 0 pass, 1 an error rule fails, 2 bad input/usage.

    \f
    Over 80 lines on purpose (not in ``--help``: click stops the help at the form
    feed): a typer command, most of it the declaration of its options
    (one Annotated block each); its body reads the sources and renders the one pipeline's
    results (:func:`betvdesign.api.run_check`).
    """
    from betvdesign.output import answers

    verbose = verbose or show_derivation
    with user_errors():
        if quiet and verbose:
            raise UsageError("--quiet and --verbose exclude each other")
        cfg = load_config()
    settings = {
        "json": as_json,
        "verbose": verbose,
        "quiet": quiet,
        "select": list(select if select else cfg.select),
        "ignore": list(ignore if ignore else cfg.ignore),
        "target_speed": target_speed if target_speed is not None else cfg.target_speed,
        "horizon": horizon,
        "adequacy": adequacy,
        "advice": advice,
    }
    # uncached: the compact text on a terminal (colour, its width) and --verbose (it
    # prints the solver's run times)
    key = (
        answers.answer_key("check", settings, files)
        if cache and not verbose and (as_json or quiet or not sys.stdout.isatty())
        else None
    )
    if key is None:
        raise typer.Exit(_answer(files, settings))
    hit = answers.lookup(key)
    if hit is not None:
        sys.stdout.write(hit.stdout)
        sys.stderr.write(hit.stderr)
        raise typer.Exit(hit.exit_code)
    # stdout and the command's own warnings are kept; notes on stderr while it runs (a
    # kernel compile, a usage error's message) are printed as they come and not kept
    out, err = io.StringIO(), io.StringIO()
    try:
        with answers.recording() as reads, contextlib.redirect_stdout(out):
            code = _answer(files, settings, warnings_to=err)
    finally:  # printed whatever happens (an interruption)
        sys.stdout.write(out.getvalue())
        sys.stderr.write(err.getvalue())
    answers.store(key, answers.Answer(out.getvalue(), err.getvalue(), code), reads)
    raise typer.Exit(code)


def _answer(files: list[Path], settings: dict, warnings_to: TextIO | None = None) -> int:
    """Check ``files`` with the parsed ``settings`` of :func:`check_cmd`, print the answer
    and return the exit status (0 pass, 1 a rule fails; bad input exits 2 through
    :func:`~betvdesign.cli.common.user_errors`).

    Parameters
    ----------
    files : list of Path
        The device files or layouts.
    settings : dict
        ``json``, ``verbose``, ``quiet``, ``select``, ``ignore``, ``target_speed`` (text
        or None), ``horizon``, ``adequacy``, ``advice``: the options with the
        ``[tool.betv]`` defaults applied.
    warnings_to : TextIO or None
        Where the warnings about ``--select``/``--ignore`` go (None: stderr).

    Returns
    -------
    int
        The exit status.
    """
    from betvdesign.api import CheckOptions, read_source, run_check
    from betvdesign.checks.view import compact_lines, output_json, quiet_line
    from betvdesign.spec.units import parse_speed

    verbose, quiet = settings["verbose"], settings["quiet"]
    with user_errors():
        speed_text = settings["target_speed"]
        target = None if speed_text is None else parse_speed(speed_text, "--target-speed")
        options = CheckOptions(
            select=tuple(settings["select"]),
            ignore=tuple(settings["ignore"]),
            target_speed=target,
            horizon=settings["horizon"],
            adequacy=settings["adequacy"],
            advice=settings["advice"],
        )
        sources = each_or_issues(read_source, files)  # every file's issues at once
        results = [run_check(src, options) for src in sources]
    flt = results[0].rule_filter
    for warning in flt.unmatched(results):
        print(f"warning: {warning}", file=warnings_to or sys.stderr)
    views = [r.view for r in results]
    if settings["json"]:
        typer.echo(output_json(views, verbose=verbose))
    elif quiet:
        for v in views:
            line = quiet_line(v)
            if line is not None:
                typer.echo(line)
    else:
        console = Console(soft_wrap=True, highlight=False)
        width = min(100, console.width) if console.is_terminal else 100
        for i, v in enumerate(views):
            if verbose:
                wide = Console(soft_wrap=False, width=None if console.is_terminal else 100)
                render(v.result, wide, derivation=True)
                continue
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
    return EXIT_RULE_FAILED if failed else EXIT_OK


def render(result: CheckResult, console: Console, *, derivation: bool = False) -> None:
    """Rich tables for one device: per set parameters, derived values, rules; then notes."""
    from betvdesign.checks.view import simulation_summary
    from betvdesign.nondim.record import DERIVED_KEYS
    from betvdesign.output.siformat import format_q

    colour = "green" if result.verdict == "pass" else "red"
    console.rule(
        f"[bold]{esc(result.derivation.name)}[/] ({esc(result.source_file)}): "
        f"[bold {colour}]{result.verdict.upper()}[/]"
    )
    for sc in result.sets:
        s = sc.derivation
        p = s.params
        orbit = "exact coupled-head orbit" if sc.model == "coupled" else "exact orbit"
        console.print(
            f"[bold]set {esc(s.name)}[/]: intended {s.intended_mode}, impacts "
            f"{s.actuator_set.impact_direction}; ϖ = {p.varpi:.4g}, α = {p.alpha:.4g}, "
            f"β = {p.beta:.4g}, κ = {p.kappa:.4g} -> {orbit}: [bold]{sc.verdict_mode}[/] "
            f"(λ = {s.lam:.4g} predicts {sc.lambda_mode})"
        )
        derived = [st for st in s.record if st.key in DERIVED_KEYS]
        console.print(
            "  " + esc(", ".join(f"{st.symbol} = {format_q(st.value)}" for st in derived)),
            highlight=False,
        )
        if sc.periodic is not None:
            sim = simulation_summary(sc.periodic).model_dump()
            for k in ("period_cycles", "n_cycles", "transient_cycles", "mu_max"):
                if sim[k] is None:  # unknown: not shown
                    del sim[k]
            extra = ", ".join(
                f"{k} = {v:.4g}" if isinstance(v, float) else f"{k} = {v}"
                for k, v in sim.items()
                if k not in ("success", "message")
            )
            console.print(esc(f"  {orbit}: {extra}"), highlight=False)
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
    from betvdesign.checks.view import rule_unit
    from betvdesign.output.siformat import format_si

    t = Table(pad_edge=False, expand=False)
    for col in ("", "severity", "rule", "value"):
        t.add_column(col, no_wrap=True)
    t.add_column("threshold", overflow="fold")
    for r in rules:
        unit = rule_unit(r)
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
            if r.fix and not r.passed:
                console.print(f"      [cyan]fix:[/] {esc(r.fix)}", highlight=False)


def _record_table(sc) -> Table:
    from betvdesign.output.siformat import format_q

    t = Table(title=f"derivation of set {esc(sc.derivation.name)}", pad_edge=False)
    for col in ("symbol", "description", "formula", "value"):
        t.add_column(col, overflow="fold")
    for st in sc.derivation.record:
        value = format_q(st.value, digits=4)
        t.add_row(*(esc(x) for x in (st.symbol, st.description, st.formula, value)))
    return t
