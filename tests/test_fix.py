"""``betv fix``: every suggested fix, written out and re-run through ``betv check``, passes.

Independent truths: the written file goes through the loader and ``betv check`` as a
user's file would; the window edges are the closed form ϖ = f_act/f_v ∈ [0.5, 2)
(computed by hand for shin2004: f_v = 2.94 kHz, AC drive, so f_drive ≥ 735 Hz plus the
5 % margin); the target speed is checked on the written file's own check.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from betvdesign.cli import app
from betvdesign.spec.loader import load_device
from betvdesign.studies.fix import FIELD_MARGIN, find_fixes
from betvdesign.studies.fixfields import parse_vary

DEVICES = Path(__file__).resolve().parents[1] / "devices"
SHIN = DEVICES / "shin2004.yaml"


def run(*args):
    return CliRunner().invoke(app, [str(a) for a in args])


def _variant(tmp_path: Path, name: str, device: str, old: str, new: str) -> Path:
    """A shipped device with one text replaced, written as tmp_path/name."""
    src = tmp_path / name
    text = (DEVICES / device).read_text()
    assert old in text
    src.write_text(text.replace(old, new))
    return src


def _check_passes(path: Path) -> dict:
    """`betv check --json` on the file passes; its device entry."""
    r = run("check", path, "--json")
    assert r.exit_code == 0, r.stdout
    (dev,) = json.loads(r.stdout)["devices"]
    return dev


@pytest.mark.slow
def test_shin2004_fix_writes_a_file_that_passes(tmp_path):
    out = tmp_path / "shin_fixed.yaml"
    r = run("fix", SHIN, "--vary", "drive.frequency", "-o", out)
    assert r.exit_code == 0, r.output
    assert "drive.frequency: 500 Hz -> " in r.stdout and "frequency-window" in r.stdout
    d = _check_passes(out)
    f_drive = load_device(out).actuator_sets[0].drive.frequency.to("Hz").magnitude
    # the window with its ±5 % margin: ϖ·0.95 = 0.5 with ϖ = 2·f_drive/f_v
    edge = 0.5 * 2940.0 / (2 * 0.95)
    assert edge * (1 + FIELD_MARGIN) * 0.999 <= f_drive <= edge * (1 + FIELD_MARGIN) * 1.01
    assert all(s["mode"] == "pull" for s in d["sets"])
    text = out.read_text()
    assert "betv fix: was 500 Hz" in text and "# two parallel beams" in text  # comments kept


def test_default_fields_rank_operating_changes_first():
    """Raising f_drive and lowering f_v change ϖ by the same factor: the drive frequency
    (no redesign) ranks first."""
    spec = load_device(SHIN)
    res = find_fixes(spec, parse_vary(spec, ["drive.frequency", "actuator.vertical_resonance"]))
    assert res.status == "fixed"
    assert list(res.best.changes) == ["drive.frequency"]
    sizes = [round(c.size, 2) for c in res.candidates if c.passed]
    assert sizes == sorted(sizes)


@pytest.mark.slow
def test_wrong_mode_device_is_fixed_by_the_exact_orbit(tmp_path):
    """push_demo marked intended pull fails its mode rule; the fix found makes the
    exact orbit pull, confirmed by `betv check` on the written file."""
    src = _variant(tmp_path, "push_as_pull.yaml", "push_demo.yaml", "mode: push", "mode: pull")
    assert run("check", src).exit_code == 1
    out = tmp_path / "fixed.yaml"
    r = run("fix", src, "--vary", "drive.frequency", "-o", out)
    assert r.exit_code == 0, r.output
    assert "fixes mode" in r.stdout
    d = _check_passes(out)
    assert d["sets"][0]["mode"] == "pull"
    f_new = load_device(out).actuator_sets[0].drive.frequency.to("kHz").magnitude
    assert f_new < 3.0  # lower ϖ favours pull (MODEL.md), the way the fix went


def test_target_speed_fix_reaches_the_speed(tmp_path):
    out = tmp_path / "fast.yaml"
    r = run(
        "fix",
        DEVICES / "push_demo.yaml",
        "--target-speed",
        "2.5 mm/s",
        "--vary",
        "actuator.horizontal_resonance",
        "-o",
        out,
        "--json",
    )
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert doc["status"] == "fixed" and doc["output"] == str(out)
    d = _check_passes(out)
    assert abs(d["sets"][0]["speed_m_s"]) >= 2.5e-3


def test_passing_device_needs_no_fix():
    r = run("fix", DEVICES / "pull_demo.yaml", "--vary", "drive.frequency")
    assert r.exit_code == 0 and "already passes" in r.stdout


def test_no_fix_within_bounds_is_exit_1_and_names_the_blocking_rule(tmp_path):
    out = tmp_path / "never.yaml"
    r = run("fix", SHIN, "--vary", "slider.beam_width=4um:6um", "-o", out)
    assert r.exit_code == 1
    assert "blocked most by frequency-window" in r.stdout
    assert not out.exists()


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--vary", "slider.nonsense"], "not a numeric field"),
        (["--vary", "drive.frequency=1kHz:200Hz"], "need 0 < LO < HI"),
        (["--vary", "drive.frequency=abc:2kHz"], "--vary drive.frequency=abc:2kHz"),
        (["--vary", "drive.frequency=1kg:2kg"], "--vary drive.frequency"),
        (["--vary", "drive.frequency=100Hz"], "LO:HI"),
        (["--vary", "actuator.horizontal_resonance"], "not a numeric field"),  # shin has α
        (["--target-speed", "fast"], "--target-speed"),
        (["--spread", "slider.nonsense=normal:1%"], "slider.nonsense"),
        (["-o", "/nonexistent-dir/x.yaml"], "does not exist"),
        (["-o", "/proc/x.yaml"], "/proc/x.yaml"),
    ],
)
def test_bad_input_is_exit_2_without_traceback(args, words):
    r = run("fix", SHIN, *args)
    assert r.exit_code == 2, r.output
    assert words in r.stderr and "Traceback" not in r.output


def test_robust_fix_meets_the_pass_probability():
    """With a spread on the beam width, the best fix keeps P(pass) ≥ p_min, measured by
    its own Monte Carlo of exact orbits that counts every error rule."""
    r = run(
        "fix",
        SHIN,
        "--vary",
        "drive.frequency",
        "--spread",
        "slider.beam_width=normal:5%",
        "-n",
        "60",
        "--p-min",
        "0.95",
        "--json",
    )
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    best = next(c for c in doc["candidates"] if c["passed"])
    assert best["p_pass"] >= 0.95
    assert "frequency window, tangential resonance, exact mode and target speed" in doc["spread"]


@pytest.mark.slow
def test_unbounded_resonant_device_is_fixed(tmp_path):
    """α·ϖ² = 1 exactly (α = 1 given, f_act = f_v = 5 kHz with a DC-biased drive): no
    periodic orbit exists (the mode rule fails, status unbounded); the fix detunes it,
    and the written file passes betv check."""
    text = (DEVICES / "push_demo.yaml").read_text()
    text = text.replace("horizontal_resonance: 3.5 kHz   # α = (5/3.5)² ≈ 2.04", "alpha: 1.0")
    text = text.replace("waveform: ac ", "waveform: dc-biased ").replace(
        "frequency: 3 kHz", "frequency: 5 kHz"
    )
    src = tmp_path / "resonant.yaml"
    src.write_text(text)
    r = run("check", src, "--json")
    assert r.exit_code == 1
    (dev,) = json.loads(r.stdout)["devices"]
    mode = next(x for x in dev["sets"][0]["rules"] if x["id"] == "mode")
    assert "unbounded" in mode["message"]
    out = tmp_path / "detuned.yaml"
    r = run("fix", src, "--vary", "drive.frequency", "-o", out)
    assert r.exit_code == 0, r.output
    _check_passes(out)


@pytest.mark.slow
def test_damped_rolled_off_device_is_fixed_end_to_end(tmp_path):
    """damped_demo (Q = 30 both ways, e = 0.1, thermal cut-off) marked intended pull: the
    fix found changes the drive frequency; the written file keeps damping, restitution
    and roll-off, passes `betv check`, and its speed is Δs·u(f)·cosθ·f_act with the stroke
    rolled off at the new frequency by the closed form u_cal·H(f)/H(f_cal) (by hand)."""
    import math

    src = _variant(tmp_path, "damped_as_pull.yaml", "damped_demo.yaml", "mode: push", "mode: pull")
    assert run("check", src).exit_code == 1
    out = tmp_path / "fixed.yaml"
    r = run("fix", src, "--vary", "drive.frequency", "-o", out)
    assert r.exit_code == 0, r.output
    d = _check_passes(out)
    (s,) = d["sets"]
    assert s["mode"] == "pull"
    assert s["params"]["zeta_v"] == s["params"]["zeta_h"] == 1 / 60
    assert s["params"]["restitution"] == 0.1
    act = load_device(out).actuator_sets[0]
    assert act.actuator.thermal_time_constant is not None
    f_act = 2 * act.drive.frequency.to("Hz").magnitude  # AC: twice the drive frequency
    f_c = 1 / (2 * math.pi * 0.2e-3)
    h = lambda f: 1 / math.sqrt(1 + (f / f_c) ** 2)  # noqa: E731
    u_cal = 0.11e-6 + (9 - 8) / (10 - 8) * (0.17e-6 - 0.11e-6)  # measured points, 9 V
    length = u_cal * h(f_act) / h(200.0) * math.cos(math.radians(20.56))
    assert s["speed_m_s"] == pytest.approx(abs(s["delta_s"]) * length * f_act, rel=1e-9)


@pytest.mark.parametrize(
    ("vary", "words"),
    [
        ("contact.restitution=0.01:1.5", "outside what the model takes (< 1)"),
        ("contact.restitution=0.01:1", "outside what the model takes (< 1)"),
        ("contact.restitution=0:0.15", "LO = 0.001"),
        ("actuator.quality_factor_normal=0.001:1e6", "need 0.05 ≤ LO < HI"),
        ("actuator.quality_factor_normal=10:1e6", "outside what the model takes (≤ 5000)"),
    ],
)
def test_fix_bounds_of_the_optional_physics_are_the_models(vary, words):
    """e ∈ [0, 1) (the search is log-spaced, so LO > 0), Q in [1/(2ζ_max), 1/(2ζ_min)] =
    [0.05, 5000]: bounds outside are refused with exit 2, not searched."""
    r = run("fix", DEVICES / "damped_demo.yaml", "--vary", vary)
    assert r.exit_code == 2 and words in r.output, r.output


def test_fix_finds_the_restitution_that_restores_the_drive(tmp_path):
    """damped_demo with e = 0.2 is not driven; varying e alone finds a passing e below the
    flip (e ≈ 0.166, tests/test_adequacy.py), confirmed by the written file's check."""
    src = _variant(
        tmp_path, "e02.yaml", "damped_demo.yaml", "restitution: 0.1 ", "restitution: 0.2 "
    )
    out = tmp_path / "fixed.yaml"
    r = run("fix", src, "--vary", "contact.restitution=0.001:0.19", "-o", out)
    assert r.exit_code == 0, r.output
    e = load_device(out).actuator_sets[0].contact.restitution
    assert 0.001 <= e < 0.166
    assert _check_passes(out)["sets"][0]["mode"] == "push"


def test_fixed_file_differs_only_in_the_changed_lines(tmp_path):
    """`-o` edits the changed values in place: a line diff of the file shows exactly the
    lines that hold drive.frequency (both sets), each with its comment, nothing else."""
    import difflib

    out = tmp_path / "shin_fixed.yaml"
    r = run("fix", SHIN, "--vary", "drive.frequency", "-o", out)
    assert r.exit_code == 0, r.output
    before, after = SHIN.read_text().splitlines(), out.read_text().splitlines()
    assert len(before) == len(after)
    changed = [
        line
        for line in difflib.unified_diff(before, after, lineterm="", n=0)
        if line[:1] in "+-" and not line.startswith(("+++", "---"))
    ]
    assert len(changed) == 4, changed  # two sets: two lines out, two in
    assert all("frequency:" in line for line in changed)
    assert all("betv fix: was 500 Hz" in line for line in changed if line.startswith("+"))


def test_blocked_fields_give_bounds_and_rule_in_json():
    r = run("fix", SHIN, "--vary", "slider.beam_width=4um:6um", "--json")
    assert r.exit_code == 1
    doc = json.loads(r.stdout)
    b = doc["blocking"]["slider.beam_width"]
    assert b["rule"] == "frequency-window"
    assert b["bounds_tried"] == ["4 µm", "6 µm"]
    assert "5%" in doc["margin"]["meaning"] or "5 %" in doc["margin"]["meaning"]


def test_passing_file_says_what_it_would_still_improve():
    r = run("fix", DEVICES / "push_demo.yaml", "--vary", "drive.frequency")
    assert r.exit_code == 0
    assert "already passes" in r.stdout and "model-adequacy" in r.stdout


def test_fix_help_explains_the_margin():
    r = run("fix", "--help")
    assert "5 %" in r.stdout and "margin" in r.stdout


def test_slow_settling_does_not_block_a_fix():
    """shin2004's fix still warns `settling` (the crossing speed is quoted): it passes."""
    spec = load_device(SHIN)
    res = find_fixes(spec, parse_vary(spec, ["drive.frequency"]))
    assert res.status == "fixed"
    assert "settling" in res.best.why


def test_designer_fields_rank_before_resonances():
    spec = load_device(SHIN)
    res = find_fixes(spec, parse_vary(spec, ["actuator.vertical_resonance", "drive.frequency"]))
    fields = [next(iter(c.changes)) for c in res.candidates if c.passed]
    assert fields[0] == "drive.frequency" and "actuator.vertical_resonance" in fields
    d = res.as_dict()
    meaning = next(
        ch["meaning"]
        for c in d["candidates"]
        for ch in c["changes"]
        if ch["field"] == "actuator.vertical_resonance"
    )
    assert "softer" in meaning and "k ∝ w³" not in meaning
    assert "in the drawing (frame model" in meaning and "flexure length" in meaning


# --- the text output (issue 32, item 9) --------------------------------------------------------


def test_each_row_quotes_its_own_numbers_and_none_is_dropped():
    """A robust search lists several values of one resonance: each row's "means:" line
    quotes that row's own stiffness factor k ∝ f² (from the row's own from -> to), and
    "N passing change(s)" stands above N rows."""
    import re

    r = run(
        "fix",
        SHIN,
        "--vary",
        "actuator.vertical_resonance",
        "--spread",
        "slider.beam_width=normal:5%",
        "-n",
        "50",
        "--p-min",
        "0.9",
    )
    assert r.exit_code == 0, r.output
    lines = r.stdout.splitlines()
    n = int(re.search(r"(\d+) passing change\(s\)", lines[0]).group(1))
    rows = [i for i, ln in enumerate(lines) if re.match(r"\s*\d+ actuator\.vertical_resonance", ln)]
    assert len(rows) == n >= 2
    factors = []
    for i in rows:
        f0, f1 = map(float, re.search(r": ([\d.]+) kHz -> ([\d.]+) kHz", lines[i]).groups())
        means = next(ln for ln in lines[i + 1 : i + 4] if "means:" in ln)
        k = float(re.search(r"k ×([\d.]+)", means).group(1))
        assert k == pytest.approx((f1 / f0) ** 2, rel=3e-3), (lines[i], means)
        factors.append(k)
    assert len(set(factors)) == len(factors)  # not one line copied to every row


def test_blocking_names_the_rule_with_its_counts_and_values_outside_the_calibration(tmp_path):
    """push_demo at 1 kHz (ϖ below the window), drive voltage varied 4.5 V to 18 V: the
    points above the measured 10 V are named as outside the calibration (not checked),
    as many as the 5 % scan puts there; the rule named is the one that fails most."""
    import math
    import re

    from betvdesign.studies.fix import SCAN_STEP

    text = (DEVICES / "push_demo.yaml").read_text().replace("frequency: 3 kHz", "frequency: 1 kHz")
    dev = tmp_path / "slow.yaml"
    dev.write_text(text)
    r = run("fix", dev, "--vary", "drive.voltage=4.5V:18V")
    j = run("fix", dev, "--vary", "drive.voltage=4.5V:18V", "--json")
    default = run("fix", dev, "--vary", "drive.voltage", "--json")
    assert r.exit_code == 1, r.output
    # the scan: 9 V·1.05^k up to 18 V (18 V itself last); above 10 V lie k = 3..14 and 18 V
    k_max = math.floor(math.log(18 / 9) / math.log1p(SCAN_STEP) - 1e-12)
    above = sum(9 * (1 + SCAN_STEP) ** k > 10 for k in range(1, k_max + 1)) + 1
    line = next(ln for ln in r.stdout.splitlines() if "drive.voltage: no passing value" in ln)
    assert f"{above} value(s) outside the measured calibration (0 V to 10 V; not checked)" in line
    counts = json.loads(j.stdout)["blocking"]["drive.voltage"]["failing_counts"]
    assert counts["outside-calibration"] == above
    rules = {k: n for k, n in counts.items() if k != "outside-calibration"}
    top = max(rules, key=rules.get)
    assert re.search(rf"blocked most by {top}: fails at {rules[top]} value", line), line
    # by default the voltage is only searched where the points were measured
    assert json.loads(default.stdout)["varied"]["drive.voltage"]["hi"] == "10 V"
