"""CLI smoke test: the console script is wired (source: typer CliRunner)."""

from typer.testing import CliRunner

from betvdesign import __version__
from betvdesign.cli import app


def test_version_command_prints_package_version():
    result = CliRunner().invoke(app, ["version"])
    assert result.exit_code == 0
    assert result.stdout.strip() == __version__
