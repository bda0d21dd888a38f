"""``betv report FILE... -o DIR``: a self-contained HTML and a PDF design report per device.

Thin: everything is :func:`betvdesign.report.write_reports`.

Exit codes: 0 the reports were written (also for a device whose verdict is
"fail": that is when a report is most needed); with ``--strict``, 1 when a
device's verdict is "fail"; 2 bad input or usage (no file is written).
"""

from __future__ import annotations

from pathlib import Path

import typer

from betvdesign.cli import app
from betvdesign.cli.common import EXIT_OK, EXIT_RULE_FAILED, user_errors


@app.command("report")
def report_cmd(
    files: list[Path] = typer.Argument(None, help="Device YAML files (see devices/)."),
    outdir: Path = typer.Option(Path("reports"), "-o", "--output", help="Output directory."),
    pdf: bool = typer.Option(True, "--pdf/--no-pdf", help="Also write NAME.pdf (WeasyPrint)."),
    strict: bool = typer.Option(
        False, "--strict", help="Exit 1 when a device's verdict is fail (default: exit 0)."
    ),
    timestamp: bool = typer.Option(
        False,
        "--timestamp",
        help="Print the generation time and run times (reports then differ between runs).",
    ),
    fidelity: str | None = typer.Option(
        None,
        "--fidelity",
        metavar="RUNG",
        help="Force the rung that decides each set's mode for the verdict: lambda, rigid, "
        "full or periodic (default: the periodic orbit the figures need anyway).",
    ),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="No progress bar."),
    methods: bool = typer.Option(
        False,
        "--methods",
        help="Write the methods report (speed/accuracy chart, failure map, fidelity ladder) "
        "instead; FILE may then be a work-precision JSON from `betv bench -o`.",
    ),
) -> None:
    """Write NAME.html (self-contained) and NAME.pdf for every device file.

    Every figure caption and verdict box states its fidelity rung and why.
    """
    from betvdesign.report import ReportOptions, write_reports

    if methods:
        from betvdesign.cli.bench import methods_report

        raise typer.Exit(methods_report(files or [], outdir, pdf=pdf))

    from betvdesign.cli.sweep import progress_bar

    with user_errors(), progress_bar("writing reports", quiet) as progress:
        options = ReportOptions(fidelity=fidelity)
        written = write_reports(
            files, outdir, pdf=pdf, timestamp=timestamp, options=options, progress=progress
        )
    for w in written:
        outputs = ", ".join(str(p) for p in (w.html, w.pdf) if p is not None)
        typer.echo(f"{w.source}: verdict {w.verdict}, {w.figures} figures -> {outputs}")
    failed = [w for w in written if w.verdict != "pass"]
    raise typer.Exit(EXIT_RULE_FAILED if strict and failed else EXIT_OK)
