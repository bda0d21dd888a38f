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


def _check_mode(path: Path, field: str, value: str) -> str:
    spec = load_device(path).replace(field, value)
    res = check_derivation(derive(spec), margin=False, settle=False, adequacy=False)
    return res.sets[0].verdict_mode


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
            assert row["basis"] == "periodic" and float(row["speed_m_s"]) != 0.0
    (flip, *_) = doc["flips"]  # pull below ~1.92 kHz is push (the check's ϖ×0.95 corner)
    at = flip["at"]
    assert 1.9 < at < 2.0
    assert _check_mode(DESIGNER, "drive.frequency", f"{at * 0.999} kHz") == flip["below"]
    assert _check_mode(DESIGNER, "drive.frequency", f"{at * 1.001} kHz") == flip["above"]
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
