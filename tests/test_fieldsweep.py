"""`betv sweep FILE --vary FIELD=LO:HI`: studies of a device's own fields.

Independent truths: each point's exact mode is that of `betv check` on the device file
with the field set to that value (the check's own path, not the sweep's vectorised
derivation); a flip located by bisection has the two modes on either side by the check;
the CSV resumes (a second run computes nothing).
"""

from __future__ import annotations

import csv
import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from betvdesign.checks.checker import check_derivation
from betvdesign.cli import app
from betvdesign.nondim.device import derive
from betvdesign.spec.loader import load_device

ROOT = Path(__file__).resolve().parents[1]
DESIGNER = ROOT / "tests/data/designer_pull.yaml"


def run(*args):
    return CliRunner().invoke(app, [str(a) for a in args])


def _check(path: Path, field: str, value: str):
    """``betv check``'s answer over the travel for one value (a map cell's basis: the
    check without its determination re-solves)."""
    spec = load_device(path).replace(field, value)
    res = check_derivation(derive(spec), margin=False, determine=False, adequacy=False)
    return res.sets[0]


def _check_mode(path: Path, field: str, value: str) -> str:
    """The check's mode in the map's words ("no crossing" where the check says the
    slider does not cross its travel within the horizon)."""
    sc = _check(path, field, value)
    return "no crossing" if sc.travel.basis == "no-crossing" else sc.verdict_mode


def test_one_field_speed_modes_and_flips(tmp_path):
    out, fig = tmp_path / "f.csv", tmp_path / "f.svg"
    r = run(
        "sweep",
        DESIGNER,
        "--vary",
        "drive.frequency=1.8kHz:2.2kHz",
        "-n",
        "5",
        "-x",
        "serial",
        "-q",
        "--out",
        out,
        "--figure",
        fig,
        "--json",
    )
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert doc["study"] == "fieldsweep" and doc["points"] == 5
    assert doc["fields"][0]["unit"] == "kHz" and doc["fields"][0]["device_value"] == 2.0
    rows = list(csv.DictReader(out.open()))
    assert [float(r["drive.frequency"]) for r in rows] == pytest.approx([1.8, 1.9, 2.0, 2.1, 2.2])
    for row in rows[::2]:
        assert row["exact_mode"] == _check_mode(
            DESIGNER, "drive.frequency", f"{row['drive.frequency']} kHz"
        )
        if row["exact_mode"] in ("push", "pull"):
            sc = _check(DESIGNER, "drive.frequency", f"{row['drive.frequency']} kHz")
            assert row["basis"] == sc.travel.basis and float(row["speed_m_s"]) != 0.0
            assert float(row["speed_m_s"]) == pytest.approx(sc.speed_m_s, rel=1e-12)
    # push below ~1.923 kHz, pull above ~1.925 kHz: between them the speed passes through
    # zero and the slider does not cross its travel within the horizon (every change
    # located, each bracket 0.1 % of the range wide: 0.4 Hz)
    flips = doc["flips"]
    assert [f["below"] for f in flips] == ["push", "no crossing"]
    assert [f["above"] for f in flips] == ["no crossing", "pull"]
    for flip in flips:
        lo, hi = flip["bracket"]
        assert 1.9 < lo < flip["at"] < hi < 2.0 and hi - lo <= 1e-3 * (2.2 - 1.8)
        assert _check_mode(DESIGNER, "drive.frequency", f"{lo!r} kHz") == flip["below"]
        assert _check_mode(DESIGNER, "drive.frequency", f"{hi!r} kHz") == flip["above"]
    assert fig.read_text().startswith("<?xml")
    again = run(
        "sweep",
        DESIGNER,
        "--vary",
        "drive.frequency=1.8kHz:2.2kHz",
        "-n",
        "5",
        "-x",
        "serial",
        "-q",
        "--out",
        out,
        "--json",
    )
    assert json.loads(again.stdout)["computed"] == 0  # resumed


def test_two_fields_map_in_the_fields_units(tmp_path):
    fig = tmp_path / "m.png"
    r = run(
        "sweep",
        DESIGNER,
        "--vary",
        "drive.frequency=1k:4k",
        "--vary",
        "slider.beam_width=5um:45um",
        "-n",
        "4",
        "-x",
        "serial",
        "-q",
        "--figure",
        fig,
        "--json",
    )
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert doc["points"] == 16 and [f["unit"] for f in doc["fields"]] == ["kHz", "µm"]
    assert sum(doc["modes"].values()) == 16 and fig.stat().st_size > 0


@pytest.mark.parametrize(
    ("vary", "words"),
    [
        ("drive.frequency=1:4", "missing unit"),
        ("drive.frequency=4kHz:1kHz", "LO < HI"),
        ("drive.frequency=1kg:2kg", "drive.frequency"),
        ("drive.nonsense=1:2", "not a numeric field"),
        ("drive.frequency", "FIELD=LO:HI"),
    ],
)
def test_bad_input_exit_2(vary, words):
    r = run("sweep", DESIGNER, "--vary", vary, "-x", "serial", "-q")
    assert r.exit_code == 2, r.output
    assert words in r.stderr and "Traceback" not in r.output


def test_dimensionless_sweeps_stay():
    r = run("sweep", "pushpull", "--help")
    assert r.exit_code == 0 and "--varpi" in r.stdout
