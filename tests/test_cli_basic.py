"""CLI smoke test: the console script is wired (source: typer CliRunner)."""

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
