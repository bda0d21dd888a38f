"""Every study states the fidelity rung it used and why, with the rung names of
:data:`betvdesign.checks.fidelity.RUNGS`; a rung a study does not offer is exit 2 naming the
ladder's rungs (source: typer CliRunner runs of the real commands, serial executor,
tiny grids; the regime rung against :func:`betvdesign.checks.fidelity.choose_rung`)."""

import json

import pytest
from typer.testing import CliRunner

from betvdesign.checks.fidelity import RUNGS, choose_rung
from betvdesign.cli import app
from betvdesign.model.params import ModelParams

MAP = ["sweep", "pushpull", "--alpha", "1", "--beta", "0.5", "--kappa", "0.4", "-x", "serial"]
LAMBDA = ["sweep", "lambda", "--kappa", "0.4", "--beta", "0.5", "--alpha", "1", "-x", "serial"]
TOL = ["tolerance", "devices/push_demo.yaml", "--spread", "drive.frequency=2%", "-n", "2"]


def _run(*args):
    return CliRunner().invoke(app, list(args))


@pytest.mark.parametrize(
    ("args", "rung"),
    [
        ([*MAP, "--varpi", "1.2", "--fidelity", "lambda"], "lambda"),
        ([*MAP, "--varpi", "1.2"], "periodic"),
        ([*LAMBDA, "--lambda", "0.9,1.1"], "periodic"),
        (["sweep", "regime", "--varpi", "0.5:1.5:0.5", "-x", "serial"], "vertical"),
        ([*TOL, "-x", "serial", "--fidelity", "lambda"], "lambda"),
    ],
)
def test_summary_and_listing_state_the_rung(args, rung):
    """JSON: "fidelity" is a ladder rung with a "fidelity_reason"; the human listing
    starts with the same statement."""
    r = _run(*args, "--json")
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["fidelity"] == rung and rung in RUNGS
    assert d["fidelity_reason"] and d["model"]
    if rung == "vertical":  # the regime diagram uses the ladder's own rung for "regime"
        assert choose_rung(ModelParams(1.0, 1.0, 0.5, 0.4), "regime").rung == rung
    human = _run(*args, "-q")
    assert human.exit_code == 0, human.output
    assert human.stdout.splitlines()[0] == f"fidelity rung {rung}: {d['fidelity_reason']}"


@pytest.mark.parametrize("rung", ["rigid", "guess"])
def test_unoffered_rung_exit_2_names_the_ladder(rung):
    for args in ([*MAP, "--varpi", "1"], [*TOL, "-x", "serial"]):
        r = _run(*args, "--fidelity", rung)
        assert r.exit_code == 2 and r.stdout == ""
        assert "offers periodic or lambda" in r.stderr
        assert ", ".join(RUNGS) in r.stderr
        assert ("unknown fidelity" in r.stderr) == (rung == "guess")
