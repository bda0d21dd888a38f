"""``betv explore FILE``: the device live in the browser (:mod:`betvdesign.explore`).

Thin: the rule options come from ``[tool.betv]`` as for ``betv check``, the server is
:func:`betvdesign.explore.server.serve`. Needs the optional extra ``explore``
(``pip install 'betvdesign[explore]'``); without it the command says so (exit 2).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Annotated

import typer

from betvdesign.cli import app
from betvdesign.cli.common import int_option, user_errors
from betvdesign.errors import UsageError

EXTRA_HINT = "betv explore needs the optional extra: pip install 'betvdesign[explore]' (Bokeh)"


@app.command("explore")
def explore_cmd(
    file: Annotated[Path, typer.Argument(help="Device YAML file (see devices/).")],
    port: Annotated[
        int | None,
        typer.Option(
            "--port",
            callback=int_option(1, 65535),
            help="Port on 127.0.0.1 (default 5006, or a free one when 5006 is busy).",
        ),
    ] = None,
    no_browser: Annotated[
        bool, typer.Option("--no-browser", help="Print the URL only; do not open a browser.")
    ] = False,
    target_speed: Annotated[
        str | None,
        typer.Option("--target-speed", metavar="Q", help="Required slider speed, e.g. '1 mm/s'."),
    ] = None,
) -> None:
    """Explore a device live in the browser: change drive, geometry and contact in their
    own units and see the verdict of `betv check`, the mode and speed, the head's phase
    portrait, the exact-mode map of two fields and the fixes of `betv fix` as you move
    them; save the design as YAML (only the changed lines) or build its report.

    Listens on 127.0.0.1 only and prints the URL; Ctrl-C stops it.
    """
    from betvdesign.cli.config import load_config
    from betvdesign.spec.units import parse_speed

    with user_errors():
        try:
            import bokeh  # noqa: F401
        except ImportError:
            raise UsageError(EXTRA_HINT) from None
        from betvdesign.explore.server import serve

        cfg = load_config()
        speed_text = target_speed if target_speed is not None else cfg.target_speed
        target = None if speed_text is None else parse_speed(speed_text, "--target-speed")
        if not file.is_file():
            raise UsageError(f"{file}: no such file")
        serve(
            file,
            port=port,
            open_browser=not no_browser,
            target_speed_m_s=target,
            select=tuple(cfg.select),
            ignore=tuple(cfg.ignore),
            say=typer.echo,
        )
    # stopped cleanly (port closed, workers ended, files written whole): leave now, not
    # after the interpreter has garbage-collected the solver's and Bokeh's heaps (seconds)
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(0)
