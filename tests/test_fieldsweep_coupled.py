"""`betv sweep FILE` of a drawn head without measured resonances: betv check's coupled answer.

Independent truths: at each point, `betv check --json` of the device file with that value
written in (the check's own derivation and verdict, a separate process path); the
decoupled exact orbit of the same point, which the rows must not quote (they would have
before the sweep took the check's model).
"""

from __future__ import annotations

import csv
import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from betvdesign.api import CheckOptions, run_check
from betvdesign.cli import app
from betvdesign.dynamics import periodic_orbit
from betvdesign.studies.points import task_params

ROOT = Path(__file__).resolve().parents[1]


def run(*args):
    return CliRunner().invoke(app, [str(a) for a in args])


def _drawn_only(tmp_path: Path, frequency: str = "3 kHz") -> Path:
    """push_demo without its measured resonances (k_v and α from the drawing)."""
    lines = (ROOT / "devices" / "push_demo.yaml").read_text().splitlines()
    keep = [ln for ln in lines if "_resonance:" not in ln and "horizontal_stiffness:" not in ln]
    text = "\n".join(keep) + "\n"
    assert "frequency: 3 kHz" in text
    out = tmp_path / f"drawn_only_{frequency.replace(' ', '')}.yaml"
    out.write_text(text.replace("frequency: 3 kHz", f"frequency: {frequency}"))
    return out


def test_sweep_rows_are_the_checks_coupled_answer(tmp_path):
    src, out = _drawn_only(tmp_path), tmp_path / "s.csv"
    r = run("sweep", src, "--vary", "drive.frequency=2.5kHz:3.5kHz", "-n", "3", "-x", "serial",
            "-q", "--out", out)  # fmt: skip
    assert r.exit_code == 0, r.output
    assert "coupled head (drawn, no measured resonances) at 3 of 3 points" in r.output
    again = run("sweep", src, "--vary", "drive.frequency=2.5kHz:3.5kHz", "-n", "3", "-x",
                "serial", "-q", "--out", out, "--json")  # fmt: skip
    assert json.loads(again.stdout)["models"] == {"coupled": 3}
    rows = list(csv.DictReader(out.open()))
    assert [float(x["drive.frequency [kHz]"]) for x in rows] == [2.5, 3.0, 3.5]
    differs = 0
    for row in rows:
        khz = row["drive.frequency [kHz]"]
        c = run("check", _drawn_only(tmp_path, f"{khz} kHz"), "--json", "--no-advice")
        assert c.exit_code in (0, 1), c.output
        s = json.loads(c.stdout)["devices"][0]["sets"][0]
        assert s["model"] == "coupled" and row["model"] == "coupled"
        assert row["exact_mode"] == s["mode"]
        assert row["basis"] == s["basis"]
        assert float(row["speed_m_s"]) == pytest.approx(abs(s["speed_m_s"]), rel=1e-12)
        # the paper's decoupled springs (the sweep's model before it took the check's)
        params = {k: float(row[k]) for k in ("varpi", "alpha", "beta", "kappa")}
        dec = periodic_orbit(task_params(params))
        ds = float(row["delta_s"])
        differs += dec.mode != row["exact_mode"] or abs(dec.delta_s - ds) > 0.1 * abs(ds)
    assert differs >= 1  # at 3 kHz they give a speed off by more than 10 %


def test_faces_still_on_the_decoupled_springs_say_so(tmp_path):
    """`betv tolerance` and the explorer's orbit plots solve with the decoupled springs:
    for a set whose check verdict is the coupled head's they warn, for a file with
    measured resonances they do not."""
    from betvdesign.checks.coupled import DECOUPLED_WARNING
    from betvdesign.explore.compute import evaluate
    from betvdesign.spec.loader import load_device

    drawn, measured = _drawn_only(tmp_path), ROOT / "devices" / "push_demo.yaml"
    for src, warned in ((drawn, True), (measured, False)):
        r = run("tolerance", src, "--spread", "drive.frequency=2%", "-n", "2", "-x", "serial",
                "--json")  # fmt: skip
        assert r.exit_code == 0, r.output
        s = json.loads(r.stdout)["sets"]["forward"]
        assert (s.get("warning") == DECOUPLED_WARNING) is warned
        text = run("tolerance", src, "--spread", "drive.frequency=2%", "-n", "2", "-x", "serial")
        assert ("WARNING: decoupled model" in text.output) is warned
        ev = evaluate(load_device(src), "orbit", with_traces=True)
        assert (ev.out["sets"][0]["model"] == "coupled") is warned
        assert ev.traces["forward"].note.startswith(DECOUPLED_WARNING) is warned


def test_coupled_flips_are_bracketed_by_the_checks_modes(tmp_path):
    """The flip along the impact angle (the coupled head pulls at shallow angles, pushes
    at steeper ones: ~45.8° here) is bisected on the check's modes: at its bracket's ends
    the check of the file with that angle written in (:func:`betvdesign.api.run_check`,
    no margin corners nor adequacy scan) gives the modes on either side."""
    src = _drawn_only(tmp_path)
    r = run("sweep", src, "--vary", "contact.impact_angle=44deg:45.9deg", "-n", "3", "-x",
            "serial", "-q", "--json")  # fmt: skip
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert doc["models"] == {"coupled": 3}
    flips = doc["flips"]
    assert [(f["below"], f["above"]) for f in flips] == [("pull", "push")]
    text = src.read_text()
    for flip in flips:
        lo, hi = flip["bracket"]
        assert 44 < lo < flip["at"] < hi < 45.9 and hi - lo <= 1e-3 * 1.9
        for angle, mode in ((lo, flip["below"]), (hi, flip["above"])):
            f = tmp_path / f"angle_{angle!r}.yaml"
            f.write_text(text.replace("impact_angle: 20.56 deg", f"impact_angle: {angle!r} deg"))
            sc = run_check(f, CheckOptions(advice=False, adequacy=False, margin=False)).sets[0]
            said = "no crossing" if sc.travel.basis == "no-crossing" else sc.verdict_mode
            assert sc.model == "coupled" and said == mode, (angle, said)
