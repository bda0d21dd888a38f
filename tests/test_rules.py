"""Design rules on both sides of each threshold (source: MODEL.md "What the model shows"
and the λ formula evaluated by hand; speed = Δs·u·cosθ·f_act computed by hand)."""

import dataclasses
import json
import math
from pathlib import Path
from types import SimpleNamespace

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from betvdesign import checker
from betvdesign.checker import check_derivation
from betvdesign.errors import UsageError
from betvdesign.fidelity import lambda_trust_margin
from betvdesign.loader import load_device
from betvdesign.nondim import derive
from betvdesign.params import ModelParams
from betvdesign.rules import (
    DEFAULT_LAMBDA_MARGIN,
    RuleResult,
    evaluate,
    evaluate_device,
    undecided_reasons,
    verdict,
)

DEVICES = Path(__file__).resolve().parents[1] / "devices"
SHIN = derive(load_device(DEVICES / "shin2004.yaml"))
PUSH = (1.5, 2.0, 0.5, 0.2)  # λ = (0.2/2.25)(1/0.4 − 1.5/26.4) ≈ 0.217: push, in fit range


def _set(varpi, alpha, beta, kappa, intended="push", base=SHIN.sets[0]):
    p = ModelParams(varpi, alpha, beta, kappa)
    return dataclasses.replace(base, params=p, lam=p.lam, intended_mode=intended, published=[])


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


def test_mode_against_intended():
    s = _set(*PUSH, intended="push")
    assert s.lam == pytest.approx((0.2 / 2.25) * (1 / 0.4 - 1.5 / 26.4))
    assert _rule(evaluate(s), "mode").passed
    r = _rule(evaluate(_set(*PUSH, intended="pull")), "mode")
    assert not r.passed and r.severity == "error" and "predicts push" in r.message
    pull = _set(0.8, 0.3, 1.2, 0.3, intended="pull")
    assert pull.lam > 1 and _rule(evaluate(pull), "mode").passed


def test_lambda_margin_both_sides():
    s = _set(*PUSH)
    d = abs(s.lam - 1)
    assert _rule(evaluate(s, lambda_margin=d * 0.99), "lambda-margin").passed
    r = _rule(evaluate(s, lambda_margin=d * 1.01), "lambda-margin")
    assert not r.passed and r.severity == "warning" and "flip" in r.message
    assert r.value == pytest.approx(d)
    assert DEFAULT_LAMBDA_MARGIN == 0.2


def test_tangential_resonance_free_flight_and_stick():
    # free flight a = α: α·ϖ² = 1.05 -> within 0.1 of resonance
    r = _rule(evaluate(_set(1.0, 1.05, 0.5, 0.2)), "tangential-resonance")
    assert not r.passed and r.value == pytest.approx(0.05) and "free flight" in r.message
    # stick a = α(1 + 1/β): 0.25·(1 + 1/0.5)·ϖ² with ϖ² = 1.4 -> 1.05
    r = _rule(evaluate(_set(math.sqrt(1.4), 0.25, 0.5, 0.2)), "tangential-resonance")
    assert not r.passed and r.value == pytest.approx(0.05) and "stick" in r.message
    r = _rule(evaluate(_set(1.0, 1.2, 0.5, 0.2)), "tangential-resonance")  # 0.2 and 2.6
    assert r.passed and r.value == pytest.approx(0.2)


@pytest.mark.parametrize(
    ("name", "inside", "outside"),
    [
        ("alpha", [0.1, 4.0], [0.099, 4.01]),
        ("beta", [0.1, 1.5], [0.099, 1.51]),
        ("kappa", [0.1, 0.4], [0.099, 0.41]),
    ],
)
def test_fit_range(name, inside, outside):
    base = {"varpi": 1.5, "alpha": 2.0, "beta": 0.5, "kappa": 0.2}
    for v, ok in [(x, True) for x in inside] + [(x, False) for x in outside]:
        s = _set(**{**base, name: v})
        r = _rule(evaluate(s), f"fit-range.{name}")
        assert r.passed is ok, (name, v)
        assert r.severity == "warning"
        assert (not ok) == any(name in why for why in undecided_reasons(s))


def test_published_fit_mismatch_shown_for_shin2004():
    res = evaluate(SHIN.sets[0])
    r = _rule(res, "published-fit.varpi")
    assert not r.passed and "0.34" in r.message and "0.9" in r.message
    assert "disagree" in r.message
    assert _rule(res, "published-fit.beta").passed  # 9.09 vs the quoted 9
    assert verdict(res) == "fail"  # the frequency window error
    assert not _rule(res, "frequency-window").passed


def test_speed_and_time_to_cross_from_periodic_delta_s():
    s = SHIN.sets[0]
    orbit = SimpleNamespace(success=True, message="ok", delta_s=-0.5, mode="pull")
    r = _rule(evaluate(s, periodic=orbit), "speed")
    v = -0.5 * 0.11e-6 * math.cos(math.pi / 4) * 1000.0  # Δs·u·cosθ·f_act [m/s]
    assert r.value == pytest.approx(v, rel=1e-12)
    assert "38.89 um/s" in r.message  # |v| = 3.889e-5 m/s
    assert f"{40e-6 / abs(v):.4g} s" in r.message  # 40 um travel range
    mode = _rule(evaluate(s, periodic=orbit), "mode")
    assert mode.passed and mode.value == -0.5  # simulation decides: Δs < 0 -> pull


def test_speed_without_orbit_and_zero_motion():
    r = _rule(evaluate(SHIN.sets[0]), "speed")
    assert r.value is None and "--simulate" in r.message
    still = SimpleNamespace(success=True, message="ok", delta_s=0.0, mode="pull")
    r = _rule(evaluate(SHIN.sets[0], periodic=still), "speed")
    assert not r.passed and "does not move" in r.message


def test_failed_solver_is_a_warning_and_lambda_decides():
    bad = SimpleNamespace(
        success=False, message="no convergence after 10 cycles", delta_s=math.nan, mode=""
    )
    res = evaluate(_set(*PUSH), periodic=bad)
    r = _rule(res, "simulation")
    assert not r.passed and r.severity == "warning" and "no convergence" in r.message
    assert _rule(res, "mode").value == pytest.approx(_set(*PUSH).lam)


def test_verdict_only_errors_fail():
    mk = lambda sev, ok: RuleResult("x", sev, ok, 1.0, "t", "m", "s")  # noqa: E731
    assert verdict([mk("warning", False), mk("info", False), mk("error", True)]) == "pass"
    assert verdict([mk("error", False)]) == "fail"
    assert verdict([]) == "pass"


def test_bidirectional_rule():
    shin = evaluate_device(SHIN)
    r = _rule(shin, "bidirectional")
    assert r.passed  # opposing identical sets, both pull -> -x and +x
    same_way = dataclasses.replace(
        SHIN, sets=[SHIN.sets[0], dataclasses.replace(SHIN.sets[0], name="twin")]
    )
    r = _rule(evaluate_device(same_way), "bidirectional")
    assert not r.passed and "same way" in r.message


def test_check_simulate_always_without_solver_is_usage_error(monkeypatch):
    monkeypatch.setattr(checker, "load_solver", lambda: None)
    with pytest.raises(UsageError, match="--simulate needs the exact solver"):
        check_derivation(SHIN, simulate="always")
    res = check_derivation(SHIN, simulate="auto")
    assert all(sc.periodic is None for sc in res.sets)
    assert any("cannot decide" in n and "not available" in n for n in res.notes)


def test_check_auto_simulates_only_undecided_sets():
    calls = []

    def solver(p):
        calls.append(p)
        return SimpleNamespace(success=True, message="ok", delta_s=-0.01, mode="pull")

    decided = dataclasses.replace(SHIN, sets=[_set(*PUSH)])
    res = check_derivation(decided, solver=solver)
    assert calls == [] and res.sets[0].mode_source == "lambda"
    res = check_derivation(SHIN, solver=solver)  # β = 9.09 outside the fit range
    assert len(calls) == 1  # the mirrored sets share parameters: solved once
    assert [sc.mode_source for sc in res.sets] == ["simulation", "simulation"]
    assert res.sets[0].periodic is res.sets[1].periodic
    assert any("ran the exact solver" in n and "cannot decide" in n for n in res.notes)
    res = check_derivation(SHIN, solver=solver, simulate="never")
    assert len(calls) == 1 and any("run with --simulate" in n for n in res.notes)


def test_solver_exception_becomes_failed_simulation():
    def boom(p):
        raise RuntimeError("solver exploded")

    res = check_derivation(SHIN, solver=boom, simulate="always")
    r = _rule(res.sets[0].rules, "simulation")
    assert not r.passed and "RuntimeError: solver exploded" in r.message


@settings(max_examples=60, deadline=None)
@given(
    varpi=st.floats(0.05, 5.0),
    alpha=st.floats(0.01, 10.0),
    beta=st.floats(0.01, 20.0),
    kappa=st.floats(0.01, 2.0),
    intended=st.sampled_from(["push", "pull"]),
)
def test_rule_invariants(varpi, alpha, beta, kappa, intended):
    """Invariants: window ⇔ 0.5 ≤ ϖ < 2; mode ⇔ (λ < 1) matches intent; verdict fails
    exactly when one of those two error rules fails; λ decides only where the measured
    trust margin allows; every value is JSON-safe."""
    s = _set(varpi, alpha, beta, kappa, intended=intended)
    res = evaluate(s)
    window = _rule(res, "frequency-window").passed
    mode = _rule(res, "mode").passed
    assert window == (0.5 <= varpi < 2.0)
    assert mode == ((s.lam < 1.0) == (intended == "push"))
    assert (verdict(res) == "pass") == (window and mode)
    # λ decides only beyond the larger of the fabrication margin and the measured trust
    # margin of the fidelity ladder at (ϖ, β), inside the window and the fit range
    assert (undecided_reasons(s) == []) == (
        abs(s.lam - 1) >= max(DEFAULT_LAMBDA_MARGIN, lambda_trust_margin(varpi, beta))
        and window
        and all(_rule(res, f"fit-range.{n}").passed for n in ("alpha", "beta", "kappa"))
    )
    json.dumps([r.as_dict() for r in res], allow_nan=False)


def test_orbit_stability_rule_both_sides():
    for stable in (True, False):
        orbit = SimpleNamespace(success=True, message="ok", delta_s=0.2, mode="push", stable=stable)
        r = _rule(evaluate(_set(*PUSH), periodic=orbit), "orbit-stability")
        assert r.passed is stable and r.severity == "warning"
    assert not [r for r in evaluate(_set(*PUSH)) if r.id == "orbit-stability"]


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
    from pathlib import Path
    from types import SimpleNamespace

    from betvdesign.loader import load_device
    from betvdesign.nondim import derive
    from betvdesign.rules import _speed

    shin = Path(__file__).resolve().parents[1] / "devices" / "shin2004.yaml"
    sets = {s.name: s for s in derive(load_device(shin)).sets}
    pull = SimpleNamespace(success=True, delta_s=-4.63)
    right = _speed(sets["right"], pull)[0]
    left = _speed(sets["left"], pull)[0]
    assert "toward -x (against the impact direction +x)" in right.message
    assert "toward +x (against the impact direction -x)" in left.message
    assert right.value < 0 and left.value < 0  # value stays signed along the impact direction
