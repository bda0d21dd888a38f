"""Fidelity ladder upward: is the idealised model adequate (betvdesign.adequacy)?

Independent truths: the restitution / quality factor at which a device's mode flips is
found again by brute force, a fine grid of exact periodic orbits solved directly
(``dynamics.periodic_orbit`` + ``domain.mode_of``, no bisection, no study code); the
unbounded growth at α·ϖ² = 1 without damping is the periodic solver's proven status
(MODEL.md, last design note) and the damped orbit there is finite; a device far from
any flip (shin2004 driven at 300 Hz, ϖ ≈ 0.2) keeps its mode at the ends of both
plausible ranges, checked by direct orbits.
"""

from __future__ import annotations

import json
import math
from dataclasses import replace

import numpy as np
import pytest
from conftest import DEVICES

import betvdesign
from betvdesign.checks.adequacy import (
    DEFAULT_QUALITY,
    DEFAULT_RESTITUTION,
    LIKELY_QUALITY,
    LIKELY_RESTITUTION,
    QUALITY_RANGE,
    RESTITUTION_RANGE,
    adequacy,
    assess_set,
)
from betvdesign.checks.rules import adequacy_rule
from betvdesign.dynamics import periodic_orbit
from betvdesign.errors import ParameterError, SpecError
from betvdesign.model.damping import zeta_from_quality
from betvdesign.model.domain import mode_of
from betvdesign.nondim.device import derive
from betvdesign.spec.loader import load_device


def _mode(p) -> str | None:
    r = periodic_orbit(p, max_cycles=20_000)
    if r.success:
        return mode_of(r.delta_s)
    return "none" if r.status == "not_driven" else None


def _z(q: float) -> float:
    return float(zeta_from_quality(q))


def test_restitution_flip_matches_a_brute_force_grid():
    """push_demo (ϖ = 1.2) with the default Q = 30: the exact orbits on a grid of step
    0.002 in e give the first e at which push is lost; the bisected flip lies in that
    grid cell, and direct orbits on either side of the bracket confirm it."""
    res = adequacy(DEVICES / "push_demo.yaml").sets[0]
    assert res.source == "default" and res.reference == "push"
    p = replace(
        derive(load_device(DEVICES / "push_demo.yaml")).sets[0].params,
        zeta_v=_z(DEFAULT_QUALITY),
        zeta_h=_z(DEFAULT_QUALITY),
    )
    grid = np.arange(0.0, 0.4001, 0.002)
    modes = [_mode(replace(p, restitution=float(e))) for e in grid]
    k = next(i for i, m in enumerate(modes) if m != "push")
    assert k > 0
    flip = res.flip_restitution
    assert flip is not None and flip.mode_low == "push" and flip.mode_high == modes[k]
    assert grid[k - 1] - 1e-12 <= flip.low < flip.high <= grid[k] + 1e-12
    assert flip.high - flip.low < 1e-4
    assert _mode(replace(p, restitution=flip.low)) == "push"
    assert _mode(replace(p, restitution=flip.high)) != "push"
    assert res.status == "mode-flips" and not res.adequate
    assert f"e ≈ {flip.at:.4g}"[:8] in res.message


def test_quality_flip_matches_a_brute_force_grid():
    """pull_demo with a softer tangential contact (α ≈ 1.2): pull at low damping, push
    when heavily damped. A log grid of 400 quality factors (e = 0.1, the default) gives
    the largest Q at which pull is lost; the bisected flip lies in that cell."""
    spec = load_device(DEVICES / "pull_demo.yaml").replace(
        "actuator.horizontal_stiffness", "0.00265 N/m"
    )
    res = adequacy(spec).sets[0]
    assert res.ideal.mode == "pull" and res.reference == "pull"
    p = replace(derive(spec).sets[0].params, restitution=DEFAULT_RESTITUTION)
    grid = np.geomspace(*QUALITY_RANGE, 400)
    modes = [_mode(replace(p, zeta_v=_z(q), zeta_h=_z(q))) for q in grid]
    k = max(i for i, m in enumerate(modes) if m != "pull")
    assert k < len(grid) - 1 and modes[k] == "push"
    flip = res.flip_quality
    assert flip is not None and flip.mode_low == "push" and flip.mode_high == "pull"
    assert grid[k] * (1 - 1e-12) <= flip.low < flip.high <= grid[k + 1] * (1 + 1e-12)
    assert flip.high / flip.low - 1 < 1e-3
    assert 1.5 < flip.at < 100  # inside the plausible range, not at an edge
    likely = LIKELY_QUALITY[0] <= flip.at <= LIKELY_QUALITY[1]
    assert res.status == ("mode-flips" if likely else "flips-beyond") or (
        not likely and res.status == "speed-differs"
    )


def test_flip_only_beyond_the_likely_band_is_stated_not_warned():
    """pull_demo: pull with the defaults; its mode is lost only at e ≈ 0.37 (> 0.3, the
    likely band's edge) and at Q ≈ 1 (< 10). Direct orbits at the band's corners are
    pull; the rule is info and its message names both flips."""
    res = adequacy(DEVICES / "pull_demo.yaml").sets[0]
    assert res.adequate and res.status in ("flips-beyond", "speed-differs")
    assert res.flip_restitution is not None and res.flip_restitution.at > LIKELY_RESTITUTION[1]
    p = derive(load_device(DEVICES / "pull_demo.yaml")).sets[0].params
    for q in LIKELY_QUALITY:
        for e in LIKELY_RESTITUTION:
            assert _mode(replace(p, zeta_v=_z(q), zeta_h=_z(q), restitution=e)) == "pull"
    rule = adequacy_rule(res)
    assert rule.severity == "info" and rule.passed
    assert "e ≈ 0.37" in rule.message and "Q ≈ 1.01" in rule.message


def test_adequate_far_from_any_flip():
    """shin2004 driven at 300 Hz (ϖ ≈ 0.2): pull with and without the defaults and at
    the corners of the plausible ranges (direct orbits); speed within 10 %."""
    spec = load_device(DEVICES / "shin2004.yaml").replace("drive.frequency", "300 Hz")
    res = adequacy(spec)
    assert res.adequate and res.status == "adequate"
    for s in res.sets:
        assert s.ideal.mode == s.richer.mode == "pull"
        assert s.flip_quality is None and s.flip_restitution is None and not s.flips
        assert abs(s.speed_change) <= 0.1
        assert "pull over the whole range Q 1–1000" in s.message
    p = derive(spec).sets[0].params
    for q in QUALITY_RANGE:
        assert _mode(replace(p, zeta_v=_z(q), zeta_h=_z(q), restitution=0.1)) == "pull"
    for e in RESTITUTION_RANGE:
        assert _mode(replace(p, zeta_v=_z(30), zeta_h=_z(30), restitution=e)) == "pull"


def test_ideal_unbounded_at_resonance_reports_the_finite_damped_answer():
    """push_demo with f_h = f_act = 6 kHz: α·ϖ² = (f_act/f_h)² = 1. The idealised
    solver proves unbounded growth; with Q = 30 the orbit is finite and is reported."""
    spec = load_device(DEVICES / "push_demo.yaml").replace("actuator.horizontal_resonance", "6 kHz")
    p = derive(spec).sets[0].params
    assert p.alpha * p.varpi**2 == pytest.approx(1.0, abs=1e-12)
    res = adequacy(spec).sets[0]
    assert res.ideal.status == "unbounded" and res.ideal.mode is None
    assert res.status == "ideal-fails" and not res.adequate
    direct = periodic_orbit(
        replace(p, zeta_v=_z(30), zeta_h=_z(30), restitution=DEFAULT_RESTITUTION)
    )
    assert direct.success and res.richer.delta_s == direct.delta_s
    assert math.isfinite(res.richer.speed_m_s) and res.richer.mode == mode_of(direct.delta_s)
    assert "unbounded" in res.message and res.richer.answer in res.message


def test_defaults_when_the_device_gives_none_and_the_devices_own_terms_otherwise():
    plain = adequacy(DEVICES / "push_demo.yaml").sets[0]
    assert plain.source == "default"
    assert plain.richer.quality == plain.richer.quality_tangential == DEFAULT_QUALITY
    assert plain.richer.restitution == DEFAULT_RESTITUTION
    assert math.isinf(plain.ideal.quality) and plain.ideal.restitution == 0.0
    assert "plausible defaults" in plain.message
    own = adequacy(DEVICES / "damped_demo.yaml").sets[0]
    assert own.source == "device" and "the device's" in own.message
    assert own.richer.quality == pytest.approx(30.0) and own.richer.restitution == 0.1
    # damped_demo is rolloff_demo + the same terms as the defaults: the same numbers.
    roll = adequacy(DEVICES / "rolloff_demo.yaml").sets[0]
    assert roll.richer.delta_s == pytest.approx(own.richer.delta_s, rel=1e-12)
    assert roll.ideal.delta_s == own.ideal.delta_s
    assert own.rolloff_factor == pytest.approx(0.136, abs=1e-3)
    # the speed is the check's: Δs·u·cosθ·f_act with the rolled-off stroke
    check = betvdesign.check(DEVICES / "damped_demo.yaml")
    assert check.out.sets[0].speed_m_s == pytest.approx(abs(own.richer.speed_m_s), rel=1e-9)


def test_mirrored_sets_are_solved_once():
    calls = []

    def counting(p, **kw):
        calls.append(p)
        return periodic_orbit(p, **kw)

    der = derive(load_device(DEVICES / "bidir_demo.yaml"))
    from betvdesign.checks.adequacy import assess

    two = assess(der, solver=counting)
    n_two = len(calls)
    calls.clear()
    assess_set(der.sets[0], solver=counting)
    assert n_two == len(calls) and len(set(calls)) == len(calls)
    assert [s.name for s in two.sets] == [s.name for s in der.sets]


def test_a_failing_solver_gives_status_failed_not_a_crash():
    def broken(p, **kw):
        raise RuntimeError("boom")

    sd = derive(load_device(DEVICES / "push_demo.yaml")).sets[0]
    res = assess_set(sd, solver=broken)
    assert res.status == "failed" and not res.adequate
    assert res.ideal.status == "failed" and "boom" in res.ideal.message
    assert "neither model" in res.message


def test_bad_input():
    with pytest.raises(ParameterError, match="device file path"):
        adequacy(42)
    with pytest.raises(SpecError):
        adequacy(DEVICES / "no_such_device.yaml")
    with pytest.raises(ParameterError, match="SetDerivation"):
        assess_set("push_demo")


def test_public_api_and_text():
    res = betvdesign.adequacy(str(DEVICES / "push_demo.yaml"))
    text = repr(res)
    assert text.startswith("push_demo: the idealised model is not adequate")
    assert "forward: mode-flips" in text and ("µm/s" in text or "mm/s" in text)
    assert res.sets[0].line().startswith("model adequacy: mode-flips: idealised push at ")


# --- the design rule and betv check -------------------------------------------------------


def _rule(view, rule_id):
    return next(r for r in view.rules if r.id == rule_id)


def test_check_rule_info_when_adequate_and_line_in_the_block():
    spec = load_device(DEVICES / "shin2004.yaml").replace("drive.frequency", "300 Hz")
    view = betvdesign.check(spec)
    r = _rule(view, "model-adequacy")
    assert r.severity == "info" and r.passed and r.message.startswith("adequate: ")
    assert "model adequacy: adequate: idealised pull at" in view.text()
    out = view.out.sets[0].adequacy
    assert out is not None and out.adequate and out.flip_quality is None


def test_check_rule_warns_where_the_mode_flips_with_the_studys_numbers():
    view = betvdesign.check(DEVICES / "push_demo.yaml")
    r = _rule(view, "model-adequacy")
    assert r.severity == "warning" and not r.passed and r.fix
    study = adequacy(DEVICES / "push_demo.yaml").sets[0]
    assert r.value == pytest.approx(study.speed_change, rel=1e-12)
    out = view.out.sets[0].adequacy
    assert out.status == "mode-flips" and out.flip_restitution == study.flip_restitution.at
    assert out.richer.mode == "push" and out.ideal.quality_normal is None  # undamped: null
    text = view.text()
    assert "warning model-adequacy: mode-flips" in text and "e ≈ 0.166 (→ not driven)" in text
    from betvdesign.checks.view import output_json

    doc = json.loads(output_json([view.view]))
    assert doc["devices"][0]["sets"][0]["adequacy"]["source"] == "default"


def test_check_at_resonance_with_damping_uses_the_finite_damped_orbit():
    """push_demo at α·ϖ² = 1 with Q = 30 given: the check's mode and speed are the finite
    damped orbit's; the idealised model alone would be unbounded (status ideal-fails);
    the resonance rule says the damping keeps the motion bounded."""
    spec = load_device(DEVICES / "push_demo.yaml").replace(
        "actuator.horizontal_resonance",
        "6 kHz",
        ("actuator.quality_factor_normal", 30),
        ("actuator.quality_factor_tangential", 30),
    )
    view = betvdesign.check(spec)
    sc = view.sets[0]
    p = sc.derivation.params
    direct = periodic_orbit(p)
    assert direct.success and sc.periodic.delta_s == direct.delta_s
    assert _rule(view, "mode").passed == (mode_of(direct.delta_s) == "push")
    res = _rule(view, "tangential-resonance")
    assert not res.passed and "keeps it bounded" in res.message
    r = _rule(view, "model-adequacy")
    assert r.message.startswith("ideal-fails: idealised no periodic orbit (unbounded)")
    assert sc.adequacy.richer.delta_s == direct.delta_s


# --- the report -----------------------------------------------------------------------------


def test_report_section_model_adequacy():
    """damped_demo: section 5 holds the verdict, the Q/e figure and the roll-off figure
    (moved from section 4, drawn once); the rule row equals betv check's; the caption
    names the flip the study found."""
    from betvdesign.report import ReportOptions, build_report, prepare, render_html

    opts = ReportOptions(regime_points=5, robustness_points=3, frequency_points=6)
    rep = build_report(prepare(DEVICES / "damped_demo.yaml"), options=opts)
    blk = rep.sets[0].adequacy
    study = adequacy(DEVICES / "damped_demo.yaml").sets[0]
    assert blk.status == study.status == "mode-flips"
    assert [f.key for f in blk.figures] == ["s1-adequacy", "s1-frequency"]
    assert all(f.svg for f in blk.figures)
    assert not any(f.key == "s1-frequency" for f in rep.sets[0].figures)
    assert f"e ≈ {study.flip_restitution.at:.4g}" in blk.figures[0].caption
    assert "the device" in blk.figures[0].svg and "not driven" in blk.figures[0].svg
    labels = {kv.label: kv.value for kv in blk.rows}
    assert labels["Damping and restitution"] == "the device file's"
    assert labels["Mode flip in e"].startswith(f"at {study.flip_restitution.text}")
    row = next(r for r in rep.sets[0].rules if r.id == "model-adequacy")
    assert row.severity == "warning" and not row.passed
    html = render_html(rep)
    assert '<section id="adequacy">' in html and "5. Model adequacy" in html
    assert html.index('id="fig-s1-adequacy"') > html.index('<section id="adequacy">')
    n = len(rep.figures())
    assert f"Figure {n}. Mean speed against actuation frequency" in html


def test_partial_terms_are_the_devices_and_undamped_q_is_null_in_json():
    """A device giving only e: compared as given (Q = ∞, no default damping added); the
    JSON writes the infinite Q as null."""
    spec = load_device(DEVICES / "push_demo.yaml").replace("contact.restitution", 0.05)
    view = betvdesign.check(spec)
    a = view.sets[0].adequacy
    assert a.source == "device" and math.isinf(a.richer.quality)
    assert a.richer.restitution == 0.05 and a.richer.terms == "Q ∞, e 0.05"
    out = view.out.sets[0].adequacy
    assert out.richer.quality_normal is None and out.richer.restitution == 0.05


def test_plot_mode_speed_scan_draws_on_the_given_axes():
    from matplotlib.figure import Figure

    from betvdesign.plots import mode_speed_scan

    ax = Figure().subplots()
    got = mode_speed_scan(
        [0.0, 0.1, 0.2, 0.3],
        [1e-3, 1.2e-3, None, None],
        ["push", "push", "none", None],
        xlabel="restitution e  [-]",
        device=(0.1, 1.2e-3),
        ideal_m_s=1e-3,
        flips=[0.15],
        ax=ax,
    )
    assert got is ax
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    for want in ("push", "not driven", "no periodic orbit", "the device", "mode flips"):
        assert want in labels
    assert ax.get_ylabel() == "mean slider speed  [mm/s]"
    assert isinstance(
        mode_speed_scan(
            [1, 10], [1e-6, 2e-6], ["pull", "pull"], xlabel="Q", logx=True
        ).get_xscale(),
        str,
    )


def test_check_can_skip_the_adequacy_study():
    """`betv check --no-adequacy`: no model-adequacy rule, JSON adequacy null, the other
    rules and the verdict unchanged."""
    from typer.testing import CliRunner

    from betvdesign.cli import app

    dev = str(DEVICES / "push_demo.yaml")
    runs = [CliRunner().invoke(app, ["check", dev, "--json", *x]) for x in ([], ["--no-adequacy"])]
    assert [r.exit_code for r in runs] == [0, 0]
    (full,), (lean,) = (json.loads(r.stdout)["devices"] for r in runs)
    assert lean["sets"][0]["adequacy"] is None and full["sets"][0]["adequacy"] is not None
    ids = [{r["id"] for r in d["sets"][0]["rules"]} for d in (full, lean)]
    assert ids[0] - ids[1] == {"model-adequacy"}
    assert full["verdict"] == lean["verdict"]


def test_json_speeds_are_magnitudes_with_the_mode_beside_them():
    """Issue 32 item 13: one convention in the JSON: a speed is a magnitude, the mode
    says the way. pull_demo's idealised orbit (Δs < 0, pull) is quoted at
    |Δs|·u·cosθ·f_act, recomputed here from the derivation, as the set's own speed is."""
    der = derive(load_device(DEVICES / "pull_demo.yaml"))
    out = betvdesign.check(der.spec, advice=False).out.sets[0]
    ideal = out.adequacy.ideal
    assert ideal.mode == "pull" and ideal.delta_s < 0
    assert ideal.speed_m_s == pytest.approx(abs(der.sets[0].scales.speed_m_s(ideal.delta_s)))
    assert ideal.speed_m_s > 0 and out.speed_m_s > 0 and out.mode == "pull"
    assert out.adequacy.richer.speed_m_s >= 0
