"""Design rules on both sides of each threshold (source: MODEL.md "What the model shows",
the λ formula evaluated by hand; speed = Δs·u·cosθ·f_act computed by hand; orbits are
stand-ins with chosen Δs, so every rule's logic is tested apart from the solver)."""

import dataclasses
import json
import math
from fractions import Fraction
from pathlib import Path
from types import SimpleNamespace

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from betvdesign.checks.checker import check_derivation
from betvdesign.checks.rule import RuleResult, verdict
from betvdesign.checks.rules import evaluate, evaluate_device
from betvdesign.model.domain import DELTA_S_STALL, mode_of
from betvdesign.model.params import ModelParams
from betvdesign.nondim.device import derive
from betvdesign.spec.loader import load_device

DEVICES = Path(__file__).resolve().parents[1] / "devices"
SHIN = derive(load_device(DEVICES / "shin2004.yaml"))
PUSH = (1.5, 2.0, 0.5, 0.2)  # λ = (0.2/2.25)(1/0.4 − 1.5/26.4) ≈ 0.217: push, in fit range


def _set(varpi, alpha, beta, kappa, intended="push", base=SHIN.sets[0]):
    p = ModelParams(varpi, alpha, beta, kappa)
    return dataclasses.replace(base, params=p, lam=p.lam, intended_mode=intended, published=[])


def _orbit(ds, status="success", k=1):
    return SimpleNamespace(
        success=status == "success",
        status=status,
        message=f"stand-in {status}",
        delta_s=ds,
        period_cycles=k,
    )


def _rule(results, rid):
    (r,) = [r for r in results if r.id == rid]
    return r


@pytest.mark.parametrize(
    ("varpi", "passed", "words"),
    [
        (0.49, False, "several times per cycle"),
        (0.5, True, "one hit per cycle"),
        (1.99, True, "one hit per cycle"),
        (2.0, False, "impulsive"),
        (2.59, False, "impulsive"),
        (2.6, False, "period doubling"),
    ],
)
def test_frequency_window(varpi, passed, words):
    r = _rule(evaluate(_set(varpi, 2.0, 0.5, 0.2)), "frequency-window")
    assert r.passed is passed and r.severity == "error" and r.value == varpi
    assert words in r.message
    assert bool(r.fix) is (not passed)


def test_window_fix_names_the_drive_frequency_range_with_ac_doubling():
    """Shin's device: f_v = 2.94 kHz, AC drive: the window 0.5 ≤ f_act/f_v < 2 is
    f_drive = f_act/2 ∈ [735 Hz, 2.94 kHz) (computed by hand)."""
    r = _rule(evaluate(SHIN.sets[0]), "frequency-window")
    assert "735 Hz–2.94 kHz" in r.fix and "AC" in r.fix


def test_mode_is_the_exact_orbit_not_lambda():
    """λ says pull (λ ≫ 1) but the orbit pushes: the mode rule follows the orbit."""
    s = _set(0.8, 0.3, 1.2, 0.3, intended="pull")
    assert s.lam > 1
    push = _orbit(+0.7)
    r = _rule(evaluate(s, orbit=push), "mode")
    assert not r.passed and r.severity == "error" and r.value == 0.7 and "push" in r.message
    # no direction table: the direction and amount come from the search (studies.fix)
    assert "betv fix" in r.fix and "toward" not in r.fix and "lower ϖ" not in r.fix
    lam = _rule(evaluate(s, orbit=push), "lambda")
    assert lam.severity == "info" and not lam.passed and "disagrees" in lam.message
    assert _rule(evaluate(s, orbit=_orbit(-0.7)), "mode").passed
    assert "agrees" in _rule(evaluate(s, orbit=_orbit(-0.7)), "lambda").message


def test_no_orbit_fails_the_mode_rule():
    r = _rule(evaluate(_set(*PUSH)), "mode")
    assert not r.passed and r.value is None


@pytest.mark.parametrize(
    ("status", "words"),
    [
        ("unbounded", "grows without bound"),
        ("not_converged", "no periodic orbit"),
        ("not_driven", "not driven"),
        ("failed", "failed"),
    ],
)
def test_solver_statuses_fail_with_their_reason(status, words):
    r = _rule(evaluate(_set(*PUSH), orbit=_orbit(None, status)), "mode")
    assert not r.passed and r.severity == "error" and words in r.message and status in r.message
    assert r.fix


def test_stalled_is_neither_push_nor_pull():
    assert mode_of(0.5 * DELTA_S_STALL) == "stalled" and mode_of(-DELTA_S_STALL) == "stalled"
    assert mode_of(2 * DELTA_S_STALL) == "push" and mode_of(-2 * DELTA_S_STALL) == "pull"
    assert mode_of(math.nan) is None and mode_of(None) is None
    for intended in ("push", "pull"):
        res = evaluate(_set(*PUSH, intended=intended), orbit=_orbit(1e-12))
        r = _rule(res, "mode")
        assert not r.passed and "does not move" in r.message
        assert verdict(res) == "fail"


def test_period_k_orbit_reports_mean_drift():
    r = _rule(evaluate(_set(*PUSH), orbit=_orbit(0.25, k=3)), "mode")
    assert r.passed and "mean of a 3-cycle orbit" in r.message


def test_tangential_resonance_free_flight_and_stick():
    # free flight a = α: α·ϖ² = 1.05 -> within 0.1 of resonance
    r = _rule(evaluate(_set(1.0, 1.05, 0.5, 0.2)), "tangential-resonance")
    assert not r.passed and r.value == pytest.approx(0.05) and "free flight" in r.message
    assert r.fix
    # stick a = α(1 + 1/β): 0.25·(1 + 1/0.5)·ϖ² with ϖ² = 1.4 -> 1.05
    r = _rule(evaluate(_set(math.sqrt(1.4), 0.25, 0.5, 0.2)), "tangential-resonance")
    assert not r.passed and r.value == pytest.approx(0.05) and "stick" in r.message
    r = _rule(evaluate(_set(1.0, 1.2, 0.5, 0.2)), "tangential-resonance")  # 0.2 and 2.6
    assert r.passed and r.value == pytest.approx(0.2) and not r.fix


def test_lambda_rule_states_extrapolation_outside_the_fit_range():
    r = _rule(evaluate(_set(1.5, 2.0, 3.0, 0.2), orbit=_orbit(0.5)), "lambda")
    assert "extrapolates" in r.message and "beta = 3" in r.message
    r = _rule(evaluate(_set(*PUSH), orbit=_orbit(0.5)), "lambda")
    assert "extrapolates" not in r.message


def test_mode_margin_rule_both_sides():
    s = _set(*PUSH)
    same = {"ϖ×0.95": "push", "ϖ×1.05": "push", "α×0.9": "push", "α×1.1": "push"}
    assert _rule(evaluate(s, orbit=_orbit(0.5), margin=same), "mode-margin").passed
    flip = {**same, "α×0.9": "pull"}
    r = _rule(evaluate(s, orbit=_orbit(0.5), margin=flip), "mode-margin")
    assert not r.passed and r.severity == "warning" and "α×0.9: pull" in r.message
    assert r.value == 1.0 and r.fix


def test_published_fit_mismatch_shown_for_shin2004():
    res = evaluate(SHIN.sets[0])
    r = _rule(res, "published-fit.varpi")
    assert not r.passed and "0.34" in r.message and "0.9" in r.message
    assert "disagree" in r.message
    assert _rule(res, "published-fit.beta").passed  # 9.09 vs the quoted 9
    assert verdict(res) == "fail"
    assert not _rule(res, "frequency-window").passed


def test_speed_and_time_to_cross_from_periodic_delta_s():
    s = SHIN.sets[0]
    r = _rule(evaluate(s, orbit=_orbit(-0.5)), "speed")
    v = -0.5 * 0.11e-6 * math.cos(math.pi / 4) * 1000.0  # Δs·u·cosθ·f_act [m/s]
    assert r.value == pytest.approx(v, rel=1e-12) and r.unit == "m/s"
    assert "38.9 µm/s" in r.message  # |v| = 3.889e-5 m/s
    assert "1.03 s" in r.message  # 40 µm / 38.89 µm/s = 1.0285 s


def test_speed_from_the_transient_when_settling_is_slow():
    """Settling 400 of 500 crossing cycles: the speed is the crossing mean (Δs 0.3),
    not the periodic 0.5, and the settling rule warns."""
    s = _set(*PUSH)
    slow = SimpleNamespace(
        status="settled",
        cycles_to_cross=500,
        settle_cycles=400.0,
        cycles_to_settle=400,
        simulated_cycles=600,
        crossing_delta_s=0.3,
        rtol=0.01,
    )
    res = evaluate(s, orbit=_orbit(0.5), settling=slow)
    speed, settle = _rule(res, "speed"), _rule(res, "settling")
    assert speed.value == pytest.approx(s.scales.speed_m_s(0.3))
    assert "transient from rest" in speed.message
    assert not settle.passed and settle.severity == "warning" and settle.fix
    fast = SimpleNamespace(**{**vars(slow), "settle_cycles": 50.0, "cycles_to_settle": 50})
    res = evaluate(s, orbit=_orbit(0.5), settling=fast)
    assert _rule(res, "settling").passed
    assert _rule(res, "speed").value == pytest.approx(s.scales.speed_m_s(0.5))


def test_target_speed_rule():
    s = _set(*PUSH)
    v = s.scales.speed_m_s(0.5)
    assert _rule(evaluate(s, orbit=_orbit(0.5), target_speed_m_s=0.9 * v), "target-speed").passed
    r = _rule(evaluate(s, orbit=_orbit(0.5), target_speed_m_s=1.1 * v), "target-speed")
    assert not r.passed and r.severity == "error" and r.fix
    assert not _rule(evaluate(s, target_speed_m_s=v), "target-speed").passed


def test_verdict_only_errors_fail():
    mk = lambda sev, ok: RuleResult("x", sev, ok, 1.0, "t", "m", "s")  # noqa: E731
    assert verdict([mk("warning", False), mk("info", False), mk("error", True)]) == "pass"
    assert verdict([mk("error", False)]) == "fail"
    assert verdict([]) == "pass"


def test_bidirectional_rule():
    pull = {s.name: _orbit(-1.0) for s in SHIN.sets}
    r = _rule(evaluate_device(SHIN, orbits=pull), "bidirectional")
    assert r.passed  # opposing identical sets, both pull -> -x and +x
    same_way = dataclasses.replace(
        SHIN, sets=[SHIN.sets[0], dataclasses.replace(SHIN.sets[0], name="twin")]
    )
    orbits = {"right": _orbit(-1.0), "twin": _orbit(-1.0)}
    r = _rule(evaluate_device(same_way, orbits=orbits), "bidirectional")
    assert not r.passed and "both ways" in r.message and r.fix


def test_check_solves_each_distinct_set_once_and_survives_a_crashing_solver():
    calls = []

    def solver(p):
        calls.append(p)
        return _orbit(-0.01)

    res = check_derivation(SHIN, solver=solver, margin=False, settle=False)
    assert len(calls) == 1  # the mirrored sets share parameters: solved once
    assert res.sets[0].periodic is res.sets[1].periodic
    assert [sc.mode for sc in res.sets] == ["pull", "pull"]

    def boom(p):
        raise RuntimeError("solver exploded")

    res = check_derivation(SHIN, solver=boom, margin=False, settle=False)
    r = _rule(res.sets[0].rules, "mode")
    assert not r.passed and "RuntimeError: solver exploded" in r.message
    assert res.verdict == "fail"


@settings(max_examples=60, deadline=None)
@given(
    varpi=st.floats(0.05, 5.0),
    alpha=st.floats(0.01, 10.0),
    beta=st.floats(0.01, 20.0),
    kappa=st.floats(0.01, 2.0),
    ds=st.one_of(st.floats(-10, 10), st.none()),
    intended=st.sampled_from(["push", "pull"]),
)
def test_rule_invariants(varpi, alpha, beta, kappa, ds, intended):
    """Invariants: window ⇔ 0.5 ≤ ϖ < 2 with each edge to 1e-12 relative (the lower
    inside, the upper outside; rational arithmetic); mode ⇔ the orbit's Δs has the intended sign
    beyond round-off (λ plays no part); verdict fails exactly when one of those fails;
    a failed rule with severity error always says what to change; JSON-safe values."""
    s = _set(varpi, alpha, beta, kappa, intended=intended)
    res = evaluate(s, orbit=None if ds is None else _orbit(ds))
    window = _rule(res, "frequency-window").passed
    mode = _rule(res, "mode").passed
    x, tol = Fraction(varpi), Fraction(1, 10**12)
    assert window == (Fraction(1, 2) * (1 - tol) <= x < 2 * (1 - tol))
    want = 1 if intended == "push" else -1
    assert mode == (ds is not None and ds * want > DELTA_S_STALL)
    assert (verdict(res) == "pass") == (window and mode)
    assert all(r.fix for r in res if r.severity == "error" and not r.passed and r.value)
    json.dumps([r.as_dict() for r in res], allow_nan=False)


def test_window_rule_quotes_the_exact_vertical_motion():
    vm = SimpleNamespace(
        success=True,
        regime="multi-impact",
        hits_per_cycle=2.0,
        impulsive_per_cycle=1.0,
        contact_fraction=0.43,
        message="ok",
    )
    r = _rule(evaluate(_set(0.34, 2.0, 0.5, 0.2), vertical=vm), "frequency-window")
    assert not r.passed
    assert "exact vertical motion: multi-impact, 2 hit(s) per cycle (1 impulsive)" in r.message
    failed = SimpleNamespace(success=False, message="no contact recurred")
    r = _rule(evaluate(_set(2.3, 2.0, 0.5, 0.2), vertical=failed), "frequency-window")
    assert "impulsive" in r.message and "no contact recurred" in r.message


def test_speed_message_names_travel_direction():
    """Δs is along the impact direction: pull on a −x set travels toward +x (MODEL.md, Slider)."""
    sets = {s.name: s for s in SHIN.sets}
    right = _rule(evaluate(sets["right"], orbit=_orbit(-4.63)), "speed")
    left = _rule(evaluate(sets["left"], orbit=_orbit(-4.63)), "speed")
    assert "toward -x (against the impact direction +x)" in right.message
    assert "toward +x (against the impact direction -x)" in left.message
    assert right.value < 0 and left.value < 0  # value stays signed along the impact direction
