"""The report answers the designer first (issue 21): the exact-mode map of two fields,
the robustness flips located exactly, the speed-against-frequency figure of every
device.

Truths: ``betv check`` of the device file with the field changed (the verdict the
designer reads, through the check's own determination and travel answer, not the
report's sweep), and the check's quoted speed.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from betvdesign.api import check
from betvdesign.report import build_report, prepare
from betvdesign.report.analysis import ReportOptions, robustness
from betvdesign.report.modemap import choose_fields, compute
from betvdesign.report.variants import field_variants, locate_flips, relative_changes
from betvdesign.spec.loader import load_device
from betvdesign.spec.paths import given, in_set

ROOT = Path(__file__).resolve().parents[1]
PULL = ROOT / "devices" / "pull_demo.yaml"
PUSH = ROOT / "devices" / "push_demo.yaml"


def _check_mode(spec, path: str, factor: float) -> str:
    """The mode ``betv check`` gives the device with ``path`` scaled by ``factor``."""
    value = given(spec, path)[0]
    view = check(spec.replace(path, value * factor), advice=False)
    (s,) = view.out.sets
    return s.mode


@pytest.fixture(scope="module")
def pull_sweep():
    prep = prepare(PULL)
    spec = prep.derivation.spec
    opts = ReportOptions()
    sweep = robustness(field_variants(spec, 0, relative_changes(7, 0.3)), opts)
    return spec, locate_flips(spec, 0, sweep, opts)


def test_robustness_flips_agree_with_the_check_on_both_sides(pull_sweep):
    spec, sweep = pull_sweep
    assert sweep.flips, "pull_demo's sweep crosses push islands (head length, k_h)"
    for fl in sweep.flips:
        assert fl.hi - fl.lo <= 1.001e-3
        if "no orbit" in (fl.below, fl.above):
            continue
        path = in_set(fl.field, 0)
        below = _check_mode(spec, path, 1.0 + fl.lo - 2e-3)
        above = _check_mode(spec, path, 1.0 + fl.hi + 2e-3)
        assert (below, above) == (fl.below, fl.above), fl


def test_the_map_names_the_nearest_flip_and_agrees_with_the_check(pull_sweep):
    spec, sweep = pull_sweep
    chosen, why = choose_fields(spec, 0, sweep)
    nearest = min(sweep.flips, key=lambda f: abs(f.at))
    assert [f for f, _ in chosen] == ["drive.frequency", nearest.field]
    assert nearest.field in why
    opts = ReportOptions(map_points=5)
    sd = prepare(PULL).derivation.sets[0]
    from betvdesign.report.analysis import Piece

    m = compute(spec, 0, sd.params.varpi, Piece(value=sweep), opts)
    assert m.summary["points"] == 25 == len(m.rows)
    fa, fb = (a["field"] for a in m.summary["fields"])
    cols = [a["column"] for a in m.summary["fields"]]  # "field [unit]"
    units = [a["unit"] for a in m.summary["fields"]]
    seen = set()
    for row in m.rows[::3]:
        if row["exact_mode"] not in ("push", "pull"):
            continue
        changed = spec
        for f, c, u in zip((fa, fb), cols, units, strict=True):
            changed = changed.replace(in_set(f, 0), _quantity(row[c], u))
        (s,) = check(changed, advice=False).out.sets
        # the map is the periodic orbit's; the check quotes the travel's answer when
        # the slider settles slowly (basis "crossing"), compare where it quotes the orbit
        if s.basis != "periodic":
            continue
        assert s.mode == row["exact_mode"], (row[cols[0]], row[cols[1]])
        seen.add(row["exact_mode"])
    assert seen


def _quantity(x: float, unit: str):
    from betvdesign.spec.units import ureg

    return ureg.Quantity(x, unit) if unit else x


def test_report_figures_order_and_frequency_figure_without_rolloff():
    rep = build_report(prepare(PUSH))
    (s,) = rep.sets
    assert s.figures[0].key == "s1-modemap" and s.figures[0].svg
    assert "exact-mode map" in s.figures[0].title
    freq = [f for f in s.adequacy.figures if f.key.endswith("frequency")]
    assert len(freq) == 1 and freq[0].svg and not freq[0].unavailable
    assert "no thermal cut-off" in freq[0].caption


def test_frequency_sweep_speed_is_the_checks_speed_at_that_drive_frequency():
    from betvdesign.report.analysis import Piece, periodic
    from betvdesign.report.frequency import frequency_sweep, speeds

    sd = prepare(PUSH).derivation.sets[0]
    opts = ReportOptions(frequency_points=7)
    per = Piece(value=periodic(sd.params, opts))
    sweep = frequency_sweep(sd.params, sd.scales.f_act_hz, per, opts)
    rolled, _ = speeds(sd, sweep)
    spec = load_device(PUSH)
    f_drive = given(spec, "actuator_sets.0.drive.frequency")[0]
    ratio = f_drive.to("Hz").magnitude / sd.scales.f_act_hz  # 1/2 with AC doubling
    compared = 0
    for f_act, v in zip(sweep.f_act_hz, rolled, strict=True):
        if v is None:
            continue
        changed = spec.replace(
            "actuator_sets.0.drive.frequency", _quantity(float(f_act) * ratio, "Hz")
        )
        (cs,) = check(changed, advice=False).out.sets
        if cs.basis != "periodic":
            continue
        # the check quotes the magnitude with the mode (README: sign convention)
        assert math.isclose(cs.speed_m_s, abs(v), rel_tol=1e-6), f_act
        assert cs.mode == ("push" if v > 0 else "pull"), f_act
        compared += 1
    assert compared >= 3


def test_report_quotes_the_checks_concrete_advice(tmp_path: Path) -> None:
    """Issue 32 item 11: a margin warning's fix in the report is the one ``betv check``
    gives (a concrete change of a field), not a generic pointer to ``betv fix``.

    pull_demo driven at 2 kHz: ϖ = f_act/f_v = 2/4 = 0.5 sits on the window's lower edge;
    a 5 % spread of ϖ needs ϖ·0.95 ≥ 0.5, i.e. f_act ≥ 4 kHz·0.5/0.95 = 2.105 kHz (by
    hand), so the quoted frequency must lie above that.
    """
    text = PULL.read_text("utf-8").replace("frequency: 3.2 kHz", "frequency: 2 kHz")
    dev = tmp_path / "pull2k.yaml"
    dev.write_text(text, "utf-8")
    small = ReportOptions(regime_points=5, robustness_points=5, map_points=5, frequency_points=5)
    report = build_report(prepare(dev), options=small)
    shown = {r.id: r.fix for r in report.sets[0].rules if r.fix}
    checked = {r.id: r.fix for r in check(dev).out.sets[0].rules if r.fix and not r.passed}
    assert shown == checked
    fix = shown["window-margin"]
    assert "raise drive.frequency 2 kHz -> " in fix, fix
    quoted = float(fix.split("-> ")[1].split(" kHz")[0])
    assert quoted >= 4.0 * 0.5 / 0.95
