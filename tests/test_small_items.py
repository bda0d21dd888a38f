"""Issue 21's small items: a bare number for a quantity option says "missing unit", a
unit in the wrong case gets a did-you-mean, `dir(betvdesign)` shows the lazy names,
`betv fix --spread` states the distribution it used."""

from __future__ import annotations

from pathlib import Path

from typer.testing import CliRunner

import betvdesign
from betvdesign.cli import app

DESIGNER = Path(__file__).resolve().parent / "data/designer_pull.yaml"


def run(*args):
    return CliRunner().invoke(app, [str(a) for a in args])


def test_bare_target_speed_is_a_missing_unit():
    r = run("check", DESIGNER, "--target-speed", "1")
    assert r.exit_code == 2 and "missing unit in '1'" in r.stderr
    assert "dimensionless" not in r.stderr


def test_unit_typo_gets_did_you_mean():
    r = run("fix", DESIGNER, "--vary", "drive.frequency", "--target-speed", "2 mm/S")
    assert r.exit_code == 2 and "did you mean '2 mm/s'" in r.stderr, r.stderr
    r = run("fix", DESIGNER, "--vary", "drive.frequency=1 khz:3 kHz")
    assert r.exit_code == 2 and "did you mean '1 kHz'" in r.stderr, r.stderr


def test_dir_shows_the_entry_points():
    names = dir(betvdesign)
    assert {"load_device", "check", "adequacy", "ureg"} <= set(names)


def test_fix_spread_states_its_distribution():
    from betvdesign.cli.fix import _spread_text

    assert _spread_text("slider.beam_width=5%") == (
        "slider.beam_width: normal σ 5 % (normal: the default)"
    )
    assert (
        _spread_text("slider.beam_width=uniform:5%") == "slider.beam_width: uniform half-width 5 %"
    )
