"""``betv extract FILE.gds -o FILE.yaml``: a GDS layout read back into a device file
(``-o -``: written to standard output, the notes to standard error).

Thin layer over :func:`betvdesign.layout.extract.extract` (what is measured and how the
layout must be labelled: :mod:`betvdesign.layout.convention`, docs/layout.md). Exit 0
when written, 2 when the layout cannot be read (each problem names the file, cell, layer
and label).
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from betvdesign.cli import app
from betvdesign.cli.common import user_errors
from betvdesign.output.files import check_output_file, write_atomic


@app.command("extract")
def extract_cmd(
    file: Annotated[Path, typer.Argument(help="GDS layout labelled as `betv layout` does.")],
    output: Annotated[
        Path,
        typer.Option("-o", "--output", help="The device file to write ('-': standard output)."),
    ],
    process: Annotated[
        str | None,
        typer.Option("--process", help="Process name or file, if the layout has no label."),
    ] = None,
) -> None:
    """Measure the labelled elements (beams, travel range, arms, head, impact angle) and
    write the device file they make, with the data the layout's labels carry."""
    from betvdesign.layout.extract import extract

    to_stdout = str(output) == "-"
    with user_errors():
        if not to_stdout:
            check_output_file(output, suffixes=(".yaml", ".yml"))
        ex = extract(file, process=process)
        # on standard output the process path is relative to the working directory
        text = retarget(ex.text, ex.process_ref, file, Path("stdout.yaml") if to_stdout else output)
    if to_stdout:  # the device file alone on stdout (to pipe it), the notes on stderr
        typer.echo(text, nl=False)
        for note in ex.notes:
            typer.echo(f"note: {note}", err=True)
        return
    write_atomic(output, text)
    for note in ex.notes:
        typer.echo(f"note: {note}")
    typer.echo(f"wrote {output}")


def retarget(text: str, ref: str, source: Path, out: Path) -> str:
    """The extracted text with its process path re-based from the layout's directory to
    the output file's."""
    from betvdesign.spec.process import rebase

    new = rebase(ref, source.parent, out)
    if new == ref:
        return text
    return text.replace(f"\nprocess: {ref}\n", f"\nprocess: {new}\n", 1)
