"""``betv fix FILE``: the smallest change that makes a failing device pass.

Thin layer over :mod:`betvdesign.studies.fix` (search) and
:mod:`betvdesign.studies.fixfile` (the fixed device file). Exit 0 when a fix is found
(or the device already passes), 1 when none exists within the bounds (the blocking
rule is named), 2 on bad input.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Annotated

import typer

from betvdesign.cli import app
from betvdesign.cli.common import EXIT_OK, EXIT_RULE_FAILED, seed_option, user_errors
from betvdesign.output.files import check_output_file, write_atomic


@app.command("fix")
def fix_cmd(
    file: Annotated[Path, typer.Argument(help="Device YAML file.")],
    vary: Annotated[
        list[str] | None,
        typer.Option(
            "--vary",
            metavar="FIELD[=LO:HI]",
            help="A field to change, optionally with bounds in any unit of the field "
            "(drive.frequency=400Hz:3kHz). Repeatable. Default: drive frequency and "
            "voltage, beam width and length, head mass or geometry, vertical/horizontal "
            "resonance or alpha, impact angle (whichever the file has), with realistic "
            "bounds.",
        ),
    ] = None,
    target_speed: Annotated[
        str | None,
        typer.Option("--target-speed", metavar="Q", help="Required speed, e.g. '1 mm/s'."),
    ] = None,
    spread: Annotated[
        list[str] | None,
        typer.Option(
            "--spread",
            metavar="FIELD=DIST",
            help="Fabrication spread (as in `betv tolerance --spread`, e.g. "
            "slider.beam_width=normal:0.3um); the fix must keep P(intended mode) >= --p-min.",
        ),
    ] = None,
    p_min: Annotated[
        float, typer.Option("--p-min", min=0.5, max=0.9999, help="Required P(intended mode).")
    ] = 0.99,
    samples: Annotated[
        int,
        typer.Option("--samples", "-n", min=50, max=20000, help="Monte Carlo samples per fix."),
    ] = 400,
    seed: Annotated[
        int, typer.Option(callback=seed_option, help="Seed of the spreads' Generator.")
    ] = 0,
    output: Annotated[
        Path | None,
        typer.Option("-o", "--output", help="Write the device file with the best fix applied."),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help="Print JSON on stdout.")] = False,
) -> None:
    """Find the smallest change (one field, then pairs) that passes every error rule with
    margin; every candidate goes through the same exact check as `betv check`."""
    from betvdesign.spec.loader import load_device
    from betvdesign.spec.units import parse_speed
    from betvdesign.studies import fix as fx
    from betvdesign.studies.fixfile import fixed_text

    with user_errors():
        target = None if target_speed is None else parse_speed(target_speed, "--target-speed")
        spec = load_device(file)
        varies = fx.parse_vary(spec, vary or [])
        robust = None
        if spread:
            robust = fx.robust_probability(spec, list(spread), n=samples, seed=seed)
        if output is not None:
            check_output_file(output, suffixes=(".yaml", ".yml"))
        res = fx.find_fixes(spec, varies, target_speed_m_s=target, robust=robust, p_min=p_min)
        text = None
        if output is not None and res.best is not None:
            text = fixed_text(file, res, res.best)
    if as_json:
        doc = {"file": str(file), **res.as_dict()}
        if output is not None:
            doc["output"] = str(output) if text is not None else None
        typer.echo(json.dumps(doc, indent=2, ensure_ascii=False))
    else:
        _print(res, file)
    if text is not None and output is not None:
        write_atomic(output, text)
        if not as_json:
            typer.echo(f"wrote {output} (betv check {output} passes)")
    raise typer.Exit(EXIT_OK if res.status in ("fixed", "already_passes") else EXIT_RULE_FAILED)


def _print(res, file: Path) -> None:
    from betvdesign.checks.rule import format_speed

    if res.status == "already_passes":
        typer.echo(
            f"{file}: already passes every error rule; nothing to change "
            "(`betv check` lists its warnings)"
        )
        return
    typer.echo(f"{file}: {res.message} ({res.evaluations} exact checks)")
    rows = [c for c in res.candidates if c.passed][:6]
    if rows:
        typer.echo(f"{'#':>2} {'change':<58} {'mode':<6} {'speed':>11} {'margin':>7}")
        for i, c in enumerate(rows, 1):
            change = "; ".join(
                f"{f}: {res.varies[f].text(res.varies[f].x0)} -> {res.varies[f].text(x)}"
                for f, x in c.changes.items()
            )
            speed = "—" if c.speed_m_s is None else format_speed(c.speed_m_s)
            margin = f"{100 * c.margin:.0f} %" if c.margin else "—"
            typer.echo(f"{i:>2} {change:<58} {c.mode or '—':<6} {speed:>11} {margin:>7}")
            typer.echo(
                f"   why: {c.why}"
                + (f"; P(intended) = {c.p_intended:.3f}" if c.p_intended is not None else "")
            )
    for f, why in res.blocking.items():
        typer.echo(f"   {f}: no passing value within its bounds (blocked by {why})")
    if res.status == "none":
        print(
            f"{file}: no fix within the bounds; widen them with --vary FIELD=LO:HI", file=sys.stderr
        )
