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


def test_spreads_state_their_distribution_in_fix_and_tolerance():
    from betvdesign.studies.tolerance import parse_tolerance

    assert parse_tolerance("slider.beam_width=5%").describe() == (
        "slider.beam_width: normal σ 5 % (normal: the default)"
    )
    assert (
        parse_tolerance("slider.beam_width=uniform:5%").describe()
        == "slider.beam_width: uniform half-width 5 %"
    )
    r = run(
        "tolerance", DESIGNER, "--spread", "slider.beam_width=5%", "-n", "8", "--executor", "serial"
    )
    assert r.exit_code in (0, 1), r.stderr
    assert "spread slider.beam_width: normal σ 5 % (normal: the default)" in r.stdout
