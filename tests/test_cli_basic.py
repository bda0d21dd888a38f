"""CLI smoke test: the console script is wired (source: typer CliRunner)."""

import pytest
from typer.testing import CliRunner

from betvdesign import __version__
from betvdesign.cli import app


def test_version_command_prints_package_version():
    result = CliRunner().invoke(app, ["version"])
    assert result.exit_code == 0
    assert result.stdout.strip() == __version__


def test_cli_starts_without_the_test_extras():
    """`make demo` installs the runtime and the layout/explore extras only: the CLI must
    start without what only the test extras bring (click came with dask; typer vendors
    its own), so a module importing it fails the demo, not the tests."""
    import subprocess
    import sys

    code = (
        "import sys\n"
        "for m in ('click', 'dask', 'distributed', 'hypothesis', 'pytest', 'playwright',"
        " 'klayout', 'mpmath', 'pypdf'):\n"
        "    sys.modules[m] = None\n"
        "from betvdesign.cli import main\n"
        "sys.argv = ['betv', '--help']\n"
        "main()\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert "sweep" in r.stdout


@pytest.mark.parametrize(
    "args",
    [
        ["--version"],
        ["--help"],
        ["check", "--help"],
        ["sweep", "--help"],
        ["fix", "--help"],
        ["tolerance", "--help"],
        ["check"],  # a missing argument
        ["check", "--bogus", "x.yaml"],  # an unknown option
        ["sweep", "pushpull", "--varpi"],  # an option without its value
        ["simulate", "--restitution", "1.5"],  # a value out of range (a click callback)
    ],
    ids=" ".join,
)
def test_help_version_and_usage_errors_import_no_solver_stack(args):
    """`betv --version`, `--help` and argument errors are answered before any command
    runs: neither numba, scipy, pint nor numpy is imported (each command imports what it
    needs when it runs)."""
    import subprocess
    import sys

    code = (
        "import sys\n"
        "from betvdesign.cli import main\n"
        f"sys.argv = ['betv', *{args!r}]\n"
        "try:\n"
        "    main()\n"
        "except SystemExit:\n"
        "    pass\n"
        "heavy = [m for m in ('numba', 'scipy', 'pint', 'numpy') if m in sys.modules]\n"
        "print('imported:', *heavy, file=sys.stderr)\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.stderr.splitlines()[-1] == "imported:", r.stderr[-2000:]
    if args[-1] != "--help" and args != ["--version"]:
        assert "Usage" in r.stderr or "Error" in r.stderr or "Invalid" in r.stderr, r.stderr
