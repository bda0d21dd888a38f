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
from betvdesign.errors import UsageError
from betvdesign.output.files import check_output_file, write_atomic
from betvdesign.studies.fixrules import SPREAD_RULES

_FIX_HELP = (
    "Find the nearest passing value of each field: stepped outward from the current "
    "value, the boundary where the check starts to pass bisected to 0.2 %, then the "
    "value proposed FIELD_MARGIN (5 %) inside it. Passing means what `betv check` calls "
    "PASS (every error rule), with the mode also held at the margin corners ϖ·(1 ± 5 %) "
    "and α·(1 ± 10 %), the design window at ϖ·(1 ± 5 %) and a stroke predicted from the "
    "drawing within its thermal bandwidth; other warnings (slow settling, tangential "
    "resonance) do not block a fix and are listed. Fixes by a drive setting or a drawn "
    "dimension come first, resonances after (with what they mean for the suspension). "
    "Only when no single field fixes the device are pairs tried."
)


@app.command("fix", help=_FIX_HELP)
def fix_cmd(
    file: Annotated[
        Path,
        typer.Argument(help="Device YAML file, or a GDS layout labelled as `betv layout` does."),
    ],
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
            metavar="FIELD=DIST:AMOUNT",
            help="Fabrication spread with its distribution (as in `betv tolerance "
            "--spread`, e.g. slider.beam_width=normal:0.3um or =uniform:5%); the fix must "
            f"keep P(pass) >= --p-min, where pass counts every error rule ({SPREAD_RULES}).",
        ),
    ] = None,
    p_min: Annotated[
        float, typer.Option("--p-min", min=0.5, max=0.9999, help="Required P(pass).")
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
        typer.Option(
            "-o",
            "--output",
            help="Write the best fix: a device file (.yaml; only the changed lines differ, "
            "each with a comment) or, for a layout, its layout (.gds).",
        ),
    ] = None,
    layout: Annotated[
        Path | None,
        typer.Option("--layout", help="Also draw the fixed device as a GDS layout (verified)."),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help="Print JSON on stdout.")] = False,
) -> None:
    """The ``betv fix`` command (its help text is the decorator's).

    Over 80 lines on purpose: a typer command, most of it the declaration of its options
    (one Annotated block each, typer's way); its body only calls the search and renders it.
    """
    from betvdesign.spec.loader import load_device
    from betvdesign.spec.process import process_ref, rebase
    from betvdesign.spec.units import parse_speed
    from betvdesign.studies import fix as fx
    from betvdesign.studies.fixfile import fixed_text
    from betvdesign.studies.tolerance import parse_tolerance

    with user_errors():
        target = None if target_speed is None else parse_speed(target_speed, "--target-speed")
        is_gds = file.suffix.lower() == ".gds"
        if output is not None and output.suffix.lower() == ".gds":
            if layout is not None:
                raise UsageError("-o FILE.gds and --layout: give one layout output")
            output, layout = None, output
        if is_gds and output is not None:
            raise UsageError(
                f"-o {output}: a layout is fixed into a layout (-o FIXED.gds); "
                "`betv extract` writes its device file"
            )
        if layout is not None:
            check_output_file(layout, suffixes=(".gds",))
        if is_gds:
            from betvdesign.layout.extract import extract

            ex = extract(file)
            spec, ref = ex.spec, ex.process_ref
        else:
            spec, ref = load_device(file), process_ref(file)
        varies = fx.parse_vary(spec, vary or [])
        robust = None
        if spread:
            robust = fx.robust_probability(
                spec, list(spread), n=samples, seed=seed, target_speed_m_s=target
            )
        if output is not None:
            check_output_file(output, suffixes=(".yaml", ".yml"))
        res = fx.find_fixes(spec, varies, target_speed_m_s=target, robust=robust, p_min=p_min)
        if robust is not None:
            spreads = "; ".join(parse_tolerance(t).describe() for t in spread)
            res.spread_note = (
                f"P(pass) under the spreads ({spreads}; "
                f"{samples} samples, seed {seed}) counts every error rule: {SPREAD_RULES}"
            )
        text = None
        if output is not None and res.best is not None:
            text = fixed_text(file, res, res.best)
        drawn = None
        if layout is not None and res.best is not None:
            from betvdesign.layout.fixlayout import write_fixed_layout

            if ref is None:
                raise UsageError(f"--layout: {file} names no process to draw on")
            drawn = write_fixed_layout(
                spec, res, res.best, layout, process_ref=rebase(ref, file.parent, layout)
            )
    if as_json:
        doc = {"file": str(file), **res.as_dict()}
        if output is not None:
            doc["output"] = str(output) if text is not None else None
        if layout is not None:
            doc["layout"] = str(drawn) if drawn is not None else None
        typer.echo(json.dumps(doc, indent=2, ensure_ascii=False))
    else:
        _print(res, file)
    if text is not None and output is not None:
        write_atomic(output, text)
        if not as_json:
            typer.echo(f"wrote {output} (betv check {output} passes)")
    if drawn is not None and not as_json:
        typer.echo(f"wrote {drawn} (betv check {drawn} passes)")
    raise typer.Exit(EXIT_OK if res.status in ("fixed", "already_passes") else EXIT_RULE_FAILED)


def _print(res, file: Path) -> None:
    from betvdesign.checks.rule import format_speed
    from betvdesign.studies.fix import MARGIN_TEXT

    if res.status == "already_passes":
        typer.echo(f"{file}: already passes `betv check` with its mode margin; nothing to fix.")
        if res.improve:
            typer.echo("it would still improve:")
            for item in res.improve:
                typer.echo(f"  {item['rule']}: {item['message']}")
                if item["fix"]:
                    typer.echo(f"    fix: {item['fix']}")
        return
    typer.echo(f"{file}: {res.message} ({res.evaluations} exact checks)")
    rows = [c for c in res.candidates if c.passed]
    if rows:
        typer.echo(f"{'#':>2} {'change':<58} {'mode':<6} {'speed':>11}")
        for i, c in enumerate(rows, 1):
            change = "; ".join(
                f"{f}: {res.varies[f].text(res.varies[f].x0)} -> {res.varies[f].text(x)}"
                for f, x in c.changes.items()
            )
            speed = "—" if c.speed_m_s is None else format_speed(c.speed_m_s)
            typer.echo(f"{i:>2} {change:<58} {c.mode or '—':<6} {speed:>11}")
            boundary = {a.field: a.boundary for a in c.answers if a.boundary is not None}
            for f, x in c.changes.items():  # each row its own numbers
                v = res.varies[f]
                if f in boundary:
                    typer.echo(f"   passes from {v.text(boundary[f])} (boundary, bisected)")
                meaning = c.meaning_of(f, x, res.varies)
                if meaning:
                    typer.echo(f"   means: {meaning}")
            typer.echo(
                f"   why: {c.why}" + (f"; P(pass) = {c.p_pass:.3f}" if c.p_pass is not None else "")
            )
        typer.echo(MARGIN_TEXT)
    if res.spread_note:
        typer.echo(res.spread_note)
    for b in res.blocking.values():
        typer.echo(f"   {b['message']}")
    if res.status == "none":
        print(
            f"{file}: no fix within the bounds; widen them with --vary FIELD=LO:HI", file=sys.stderr
        )
