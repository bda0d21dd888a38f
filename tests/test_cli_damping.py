"""The optional-physics options of the commands that take raw parameters (source: typer
CliRunner runs of the real commands, checked against the Python API they wrap; bad
values get one message naming the option and exit 2, never a traceback)."""

import json
import re

import pytest
from typer.testing import CliRunner

from betvdesign.cli import app
from betvdesign.dynamics import periodic_orbit
from betvdesign.model.params import ModelParams

runner = CliRunner()
POINT = ["--varpi", "1", "--alpha", "1", "--beta", "0.5", "--kappa", "0.4"]
COMMANDS = {
    "pushpull": ["sweep", "pushpull", *POINT, "-x", "serial", "-q"],
    "lambda": "sweep lambda --kappa 0.4 --beta 0.5 --alpha 1 --lambda 1 -x serial -q".split(),
    "regime": ["sweep", "regime", "--varpi", "1", "-x", "serial", "-q"],
    "ladder": ["ladder", "mode", *POINT],
    "simulate": ["simulate", *POINT, "--periodic"],
}
NORMAL_ONLY = ("regime",)


def _run(args):
    return runner.invoke(app, args)


def _flat(text):
    """Message text without rich's box and line wrapping."""
    return " ".join(re.sub(r"[│╭╮╰╯─]", " ", text).split())


def _bad(r, *fragments):
    assert r.exit_code == 2, r.output
    assert "Traceback" not in r.output
    assert r.exception is None or isinstance(r.exception, SystemExit)
    for f in fragments:
        assert f in _flat(r.stderr), r.stderr
    assert r.stdout == ""


BAD_VALUES = [
    (["--quality-normal", "-5"], ("--quality-normal", "must be > 0")),
    (["--quality-normal", "0"], ("--quality-normal", "must be > 0")),
    (["--quality-normal", "1e6"], ("--quality-normal", "outside the supported range")),
    (["--zeta-v", "-0.1"], ("--zeta-v", "≥ 0")),
    (["--zeta-v", "nan"], ("--zeta-v", "finite")),
    (["--restitution", "1"], ("--restitution", "outside [0, 1)")),
    (["--restitution", "1.5"], ("--restitution", "outside [0, 1)")),
    (["--restitution", "-0.1"], ("--restitution", "outside [0, 1)")),
    (["--quality-normal", "30", "--zeta-v", "0.01"], ("--quality-normal or --zeta-v",)),
    (["--quality-tangential", "-1"], ("--quality-tangential", "must be > 0")),
    (["--zeta-h", "20"], ("--zeta-h", "outside the supported range")),
    (["--quality-tangential", "30", "--zeta-h", "0.01"], ("--quality-tangential or --zeta-h",)),
]


def _tangential(extra):
    return any(a in ("--zeta-h", "--quality-tangential") for a in extra)


@pytest.mark.parametrize(
    ("command", "extra", "fragments"),
    [
        (c, extra, fragments)
        for c in COMMANDS
        for extra, fragments in BAD_VALUES
        if not (c in NORMAL_ONLY and _tangential(extra))  # regime: normal terms only
    ],
)
def test_bad_values_exit_2_naming_the_option(command, extra, fragments):
    _bad(_run([*COMMANDS[command], *extra]), *fragments)


def test_regime_refuses_tangential_damping():
    r = _run([*COMMANDS["regime"], "--quality-tangential", "30"])
    assert r.exit_code == 2 and "--quality-tangential" in r.stderr


def test_lambda_fidelity_refused_with_terms():
    r = _run([*COMMANDS["pushpull"], "--fidelity", "lambda", "--restitution", "0.1"])
    _bad(r, "fidelity 'lambda'", "--fidelity periodic")
    r = _run([*COMMANDS["ladder"], "--fidelity", "lambda", "--quality-normal", "30"])
    _bad(r, "fidelity 'lambda'", "use periodic or full")


def test_simulate_refuses_terms_with_a_device_file():
    r = _run(["simulate", "devices/shin2004.yaml", "--restitution", "0.1"])
    _bad(r, "--restitution", "device file carries its own")


def test_pushpull_json_records_the_terms_and_solves_the_damped_model(tmp_path):
    out = tmp_path / "m.csv"
    r = _run([*COMMANDS["pushpull"], "--quality-tangential", "10", "--json", "-o", str(out)])
    assert r.exit_code == 0, r.stderr
    data = json.loads(r.stdout)
    assert data["terms"] == {"zeta_v": 0.0, "zeta_h": 0.05, "restitution": 0.0}
    assert data["converged"] == 1 and data["unbounded"] == []
    assert json.loads(out.with_suffix(".json").read_text())["parameters"]["zeta_h"] == 0.05
    # the same path without the terms is a different study: refused, not resumed
    r = _run([*COMMANDS["pushpull"], "-o", str(out)])
    _bad(r, "different 'parameters'")


def test_simulate_and_ladder_with_quality_factors_match_the_api():
    p = ModelParams(1.0, 1.0, 0.5, 0.4, zeta_v=1 / 60, zeta_h=0.05, restitution=0.1)
    terms = ["--quality-normal", "30", "--zeta-h", "0.05", "--restitution", "0.1"]
    r = _run([*COMMANDS["simulate"], *terms, "--json"])
    assert r.exit_code == 0, r.stderr
    data = json.loads(r.stdout)
    assert data["params"] == p.as_dict()
    assert data["delta_s"] == periodic_orbit(p).delta_s
    r = _run([*COMMANDS["ladder"], *terms, "--json"])
    assert r.exit_code == 0, r.stderr
    ans = json.loads(r.stdout)
    assert ans["rung"] == "periodic" and ans["value"] == periodic_orbit(p).delta_s
    assert ans["params"] == p.as_dict()


def test_regime_and_lambda_sweeps_take_the_terms():
    r = _run([*COMMANDS["regime"], "--restitution", "0.3", "--zeta-v", "0.02", "--json"])
    assert r.exit_code == 0, r.stderr
    assert json.loads(r.stdout)["terms"] == {"zeta_v": 0.02, "restitution": 0.3}
    r = _run([*COMMANDS["lambda"], "--quality-tangential", "20", "--json"])
    assert r.exit_code == 0, r.stderr
    assert json.loads(r.stdout)["terms"]["zeta_h"] == 0.025


@pytest.mark.slow
def test_not_driven_by_restitution_is_said_so_with_the_right_fix(tmp_path):
    """damped_demo with e = 0.2 (above its flip at e ≈ 0.166): `betv check` calls the set
    "not driven" (not "unknown") and its fix names restitution and a lower ϖ, not the
    design window it is already inside (ϖ = 1.2)."""
    from pathlib import Path

    src = Path(__file__).resolve().parents[1] / "devices" / "damped_demo.yaml"
    dev = tmp_path / "e02.yaml"
    dev.write_text(src.read_text().replace("restitution: 0.1 ", "restitution: 0.2 "))
    r = runner.invoke(app, ["check", str(dev), "--no-adequacy"])
    assert r.exit_code == 1, r.output
    text = " ".join(r.output.split())
    assert "forward: not driven (intended push)" in text
    assert "restitution e = 0.2" in text and "lower ϖ" in text
    assert "bring ϖ into 0.5–2" not in text


def test_transient_of_a_not_driven_design_is_not_called_push():
    """From rest the first contact gives the slider a velocity it then keeps (no contact
    recurs with e = 0.5 at ϖ = 1.2): the transient's last Δs is coasting, not a mode."""
    args = ["--varpi", "1.2", "--alpha", "2.04", "--beta", "0.5", "--kappa", "0.15"]
    r = runner.invoke(app, ["simulate", *args, "--restitution", "0.5", "--cycles", "50"])
    assert r.exit_code == 0, r.output
    assert "-> not driven" in r.output and "-> push" not in r.output
    r = runner.invoke(app, ["simulate", *args, "--restitution", "0.5", "--cycles", "50", "--json"])
    assert json.loads(r.output)["mode"] == "not driven"
