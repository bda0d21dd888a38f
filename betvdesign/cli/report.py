"""``betv report FILE... -o DIR``: a self-contained HTML and a PDF design report per device.

Thin: everything is :func:`betvdesign.report.write_reports`. The default report draws the
figures a design decision rests on; ``--full`` adds the model's diagnostics. A repeated
report of unchanged inputs is written from the store (:mod:`betvdesign.output.answers`;
``--no-cache`` builds afresh).

Exit codes: 0 the reports were written (also for a device whose verdict is
"fail": that is when a report is most needed); with ``--strict``, 1 when a
device's verdict is "fail"; 2 bad input or usage, including an output directory
that cannot be written (no file is written); 130 interrupted (Ctrl-C, SIGTERM:
each device's HTML and PDF are written together or not at all).
"""

from __future__ import annotations

from pathlib import Path

import typer

from betvdesign.cli import app
from betvdesign.cli.common import (
    EXIT_OK,
    EXIT_RULE_FAILED,
    QuietOpt,
    interruptible,
    progress_bar,
    user_errors,
)


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
    quiet: QuietOpt = False,
    full: bool = typer.Option(
        False,
        "--full",
        help="Also draw the model's diagnostics: the push/pull map of the λ fit, the "
        "vertical regime strip, the head's phase portrait, the slider's settling and "
        "periodic orbit (the other figures are the same either way).",
    ),
    cache: bool = typer.Option(
        True,
        "--cache/--no-cache",
        help="Write the stored HTML and PDF of an identical earlier report (the same bytes "
        "of every file read, the same options, betvdesign code and installed packages; "
        "under ~/.cache/betvdesign/answers, or $BETV_ANSWER_CACHE, 'off' to turn it off). "
        "--no-cache builds afresh and stores nothing. Never with --timestamp.",
    ),
    methods: bool = typer.Option(
        False,
        "--methods",
        help="Write the methods report (speed/accuracy chart, failure map, fidelity ladder) "
        "instead; FILE may then be a work-precision JSON from `betv bench -o`.",
    ),
    validation: bool = typer.Option(
        False,
        "--validation",
        help="Write the validation page against the published paper (Figs 3-12 recomputed) "
        "instead; FILE may then be the published device (default devices/shin2004.yaml).",
    ),
) -> None:
    """Write NAME.html (self-contained) and NAME.pdf for every device file.

    The verdict always rests on the exact periodic orbit of every set; every figure
    caption states which model drew it and why.
    """
    from betvdesign.report import ReportOptions, write_reports

    if validation:
        from betvdesign.cli.validation import validation_report

        other = {"--methods": methods, "--strict": strict, "--timestamp": timestamp}
        raise typer.Exit(validation_report(files or [], outdir, pdf=pdf, other=other))
    if methods:
        from betvdesign.cli.bench import methods_report

        raise typer.Exit(methods_report(files or [], outdir, pdf=pdf))

    with (
        user_errors(),
        interruptible(resumable=False),
        progress_bar("writing reports", quiet) as progress,
    ):
        options = ReportOptions(full=full)
        written = write_reports(
            files,
            outdir,
            pdf=pdf,
            timestamp=timestamp,
            options=options,
            progress=progress,
            cache=cache,
        )
    for w in written:
        outputs = ", ".join(str(p) for p in (w.html, w.pdf) if p is not None)
        typer.echo(f"{w.source}: verdict {w.verdict}, {w.figures} figures -> {outputs}")
    failed = [w for w in written if w.verdict != "pass"]
    raise typer.Exit(EXIT_RULE_FAILED if strict and failed else EXIT_OK)
