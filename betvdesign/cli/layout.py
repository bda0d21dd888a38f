"""``betv layout FILE.yaml -o FILE.gds``: a device file drawn as a GDS mask layout.

Thin layer over :func:`betvdesign.layout.write.write_layout` (the drawing and its
conventions are documented there and in :mod:`betvdesign.layout.convention`). Exit 0 on
success, 2 when the file cannot be read or drawn (no process, no actuator geometry, a
thickness that is not the layer's); nothing is written then.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from betvdesign.cli import app
from betvdesign.cli.common import user_errors
from betvdesign.output.files import check_output_file


@app.command("layout")
def layout_cmd(
    file: Annotated[Path, typer.Argument(help="Device YAML file with process and geometry.")],
    output: Annotated[Path, typer.Option("-o", "--output", help="The GDS file to write.")],
    svg: Annotated[
        Path | None, typer.Option("--svg", help="Also write an SVG preview of the layout.")
    ] = None,
) -> None:
    """Draw the device on its process's layers: slider with ends and stops, both actuator
    sets at the impact angle with heads, anchors and pads, release holes, and a label on
    every element (read back by `betv check FILE.gds` and `betv extract`)."""
    from betvdesign.layout.write import write_layout
    from betvdesign.spec.loader import load_device
    from betvdesign.spec.process import process_ref, rebase

    with user_errors():
        check_output_file(output, suffixes=(".gds",))
        if svg is not None:
            check_output_file(svg, suffixes=(".svg",))
        spec = load_device(file)
        ref = process_ref(file)
        ref = None if ref is None else rebase(ref, file.parent, output)
        write_layout(spec, output, process_ref=ref, svg=svg)
    typer.echo(f"wrote {output}" + (f" and {svg}" if svg is not None else ""))
    p = spec.process
    gds = [u.split(".")[1] for u in p.unsourced if u.startswith("layers.") and u.endswith(".gds")]
    if gds:
        levels = ", ".join(f"{n} {p.layers[n].gds.pair[0]}/{p.layers[n].gds.pair[1]}" for n in gds)
        typer.echo(
            f"note: process {p.name}: GDS levels NOT verified against a source: {levels}; "
            "check them against your foundry's handbook"
        )
