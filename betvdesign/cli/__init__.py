"""The ``betv`` command line: a thin layer over the Python API.

Each sub-command lives in its own module of this package and registers itself on
:data:`app` when imported; add the module's name to ``_COMMANDS``.

Exit codes: 0 success (and every error-severity rule passes), 1 a design rule
fails, 2 bad input or usage.
"""

from __future__ import annotations

import importlib

import typer

app = typer.Typer(
    name="betv",
    help="BETV design toolkit: check a layout, simulate, sweep, report, benchmark.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)


def _print_version(value: bool) -> None:
    if value:
        from betvdesign import __version__

        typer.echo(f"betvdesign {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: bool = typer.Option(
        False,
        "--version",
        is_eager=True,
        callback=_print_version,
        help="Print the betvdesign version and exit.",
    ),
) -> None:
    """BETV design toolkit: check a layout, simulate, sweep, report, benchmark."""


# Sub-command modules, imported for their side effect of registering on ``app``.
_COMMANDS: tuple[str, ...] = (
    "sweep",
    "studies",
    "check",
    "fix",
    "schema",
    "report",
    "bench",
    "simulate",
    "layout",
    "extract",
    "explore",
)

for _name in _COMMANDS:
    importlib.import_module(f"{__name__}.{_name}")


@app.command("version")
def version_cmd() -> None:
    """Print the betvdesign version."""
    from betvdesign import __version__

    typer.echo(__version__)


def main() -> None:
    """Console-script entry point. SIGTERM is handled like Ctrl-C from here on (the
    long commands then stop cleanly with exit 130, see ``common.interruptible``).
    Once the command has finished (or stopped cleanly), a late Ctrl-C or SIGTERM is
    ignored: it would otherwise interrupt the interpreter's own clean-up (worker pools,
    semaphores) with a traceback; SIGKILL still ends the process."""
    import signal

    from betvdesign.cli.common import raise_terminated

    signal.signal(signal.SIGTERM, raise_terminated)
    try:
        app()
    finally:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
