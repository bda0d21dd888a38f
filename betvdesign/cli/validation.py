"""``betv report --validation [DEVICE] -o DIR``: the validation page against the paper.

Thin: everything is :func:`betvdesign.report.validation.write_validation_report`.
"""

from __future__ import annotations

from pathlib import Path

import typer

from betvdesign.cli.common import EXIT_OK, user_errors
from betvdesign.errors import UsageError


def validation_report(
    files: list[Path], outdir: Path, *, pdf: bool = True, other: dict[str, bool] | None = None
) -> int:
    """Write the validation page; FILE is the published device's YAML (default
    devices/shin2004.yaml). ``other``: options of ``betv report`` given with it (flag →
    set), refused since the page does not use them. Returns the exit code (2 on bad
    input, nothing written)."""
    from betvdesign.report.validation import write_validation_report

    with user_errors():
        given = [name for name, on in (other or {}).items() if on]
        if given:
            raise UsageError(f"--validation does not take {', '.join(given)}")
        if len(files) > 1:
            raise UsageError("--validation takes at most one device file (the published device)")
        if outdir.exists() and not outdir.is_dir():
            raise UsageError(f"output path {outdir} exists and is not a directory")
        written = write_validation_report(outdir, device=files[0] if files else None, pdf=pdf)
    typer.echo("validation report -> " + ", ".join(str(p) for p in written[:2]) + ", …")
    return EXIT_OK
