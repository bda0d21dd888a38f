"""The verdict always comes from the exact orbit (issue: "a verdict that is always exact").

Independent truths: brute force (the transient from rest over thousands of cycles, its
mean increment over the last cycles, a different method from Newton shooting), and the
settling/crossing counts recounted from that transient; the design of the issue
(ϖ = 1.024, α = 0.234, β = 1.31, κ = 0.249, λ = 4.08) where the λ fit says pull and the
slider pushes.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

from betvdesign.checks.checker import check_derivation
from betvdesign.dynamics import periodic_orbit, simulate
from betvdesign.dynamics.settling import settling
from betvdesign.model.params import ModelParams
from betvdesign.nondim.device import derive
from betvdesign.spec.loader import load_device

DEVICES = Path(__file__).resolve().parents[1] / "devices"
BASE = derive(load_device(DEVICES / "pull_demo.yaml"))
LIAR = ModelParams(1.024, 0.234, 1.31, 0.249)  # λ = 4.08 says pull; the slider pushes


def _device(p: ModelParams, intended: str):
    s = dataclasses.replace(BASE.sets[0], params=p, lam=p.lam, intended_mode=intended)
    return dataclasses.replace(BASE, sets=[s])


def _brute_force_delta_s(p: ModelParams, cycles: int = 6000, tail: int = 200) -> float:
    tr = simulate(p, cycles, log_events=False)
    assert tr.success, tr.message
    return float(np.mean(tr.delta_s[-tail:]))


def test_lambda_says_pull_the_slider_pushes_and_the_check_says_so():
    assert LIAR.lam == pytest.approx(4.08, abs=0.01) and LIAR.lambda_mode == "pull"
    brute = _brute_force_delta_s(LIAR)
    assert brute > 1.0  # push, by brute force (≈ +3.35)
    res = check_derivation(_device(LIAR, "pull"))
    sc = res.sets[0]
    assert sc.mode == "push" and res.verdict == "fail"
    mode = next(r for r in sc.rules if r.id == "mode")
    assert not mode.passed and sc.periodic.delta_s == pytest.approx(brute, rel=1e-6)
    # the value the mode rule quotes is the answer over the travel: the periodic Δs when
    # it settles early, else the crossing's mean from rest (recounted from a transient)
    if sc.travel.basis == "crossing":
        tr = simulate(LIAR, sc.travel.cycles_to_cross, log_events=False)
        assert mode.value == pytest.approx(tr.s / sc.travel.cycles_to_cross, rel=1e-12)
    else:
        assert mode.value == pytest.approx(brute, rel=1e-6)
    lam = next(r for r in sc.rules if r.id == "lambda")
    assert "disagrees" in lam.message
    assert check_derivation(_device(LIAR, "push")).sets[0].mode == "push"


@pytest.mark.parametrize("seed", range(12))
def test_check_mode_matches_brute_force_on_random_designs(seed):
    """Random designs in the window (seeded): the check's mode is the sign of the
    brute-force mean increment once the transient has settled."""
    rng = np.random.default_rng(1000 + seed)
    p = ModelParams(
        rng.uniform(0.55, 1.8), rng.uniform(0.1, 4.0), rng.uniform(0.1, 1.5), rng.uniform(0.1, 0.4)
    )
    po = periodic_orbit(p)
    if not po.success:
        pytest.skip(f"no periodic orbit at {p} ({po.status})")  # counted in benchmarks
    brute = _brute_force_delta_s(p, cycles=20000, tail=400)
    res = check_derivation(_device(p, "push"), margin=False, settle=False)
    expected = "push" if brute > 0 else "pull"
    assert res.sets[0].mode == expected, (p, brute, po.delta_s)
    assert po.delta_s == pytest.approx(brute, rel=1e-6, abs=1e-9)


def test_settling_counts_recounted_from_a_plain_transient():
    """cycles_to_cross is the first cycle with |s| ≥ travel; cycles_to_settle the first
    after which the per-cycle increment stays within 1 % of the periodic Δs."""
    p = ModelParams(0.8, 0.3, 1.2, 0.3)
    po = periodic_orbit(p)
    st = settling(p, po.delta_s, travel_s=300.0, mu_max=max(po.floquet_moduli))
    tr = simulate(p, 3000, log_events=False)
    s = tr.section[:, 4]
    assert st.cycles_to_cross == int(np.argmax(np.abs(s) >= 300.0))
    bad = np.nonzero(np.abs(tr.delta_s - po.delta_s) > 0.01 * abs(po.delta_s))[0]
    assert st.cycles_to_settle == int(bad[-1]) + 1
    assert st.crossing_delta_s == pytest.approx(s[st.cycles_to_cross] / st.cycles_to_cross)


def test_unsettled_transient_gives_a_lower_bound_not_an_extrapolation():
    """Near ϖ → 2 settling is slow (|μ| → 1): with a small cycle budget the result says
    "not_settled" and its settle_cycles is the budget, a lower bound of the true count
    (recounted with the full budget). The slowest Floquet multiplier alone would
    under-predict: ln(0.01)/ln|μ| is far below the measured count here."""
    p = ModelParams(1.95, 1.0, 0.5, 0.2)
    po = periodic_orbit(p)
    mu = max(po.floquet_moduli)
    short = settling(p, po.delta_s, travel_s=math.inf, mu_max=mu, max_cycles=2000)
    full = settling(p, po.delta_s, travel_s=math.inf, mu_max=mu)
    assert short.status == "not_settled" and short.settle_cycles == 2000
    assert full.status == "settled" and full.cycles_to_settle > short.settle_cycles
    assert math.log(0.01) / math.log(mu) < full.cycles_to_settle / 10


def test_check_result_reprs_are_short_and_name_the_exact_mode():
    res = check_derivation(_device(LIAR, "pull"), margin=False, settle=False)
    text = repr(res)  # the compact block of betv check
    assert text.startswith("pull_demo: FAIL\n  main: push instead of pull")
    assert len(text.splitlines()) <= 15
    html = res._repr_html_()
    assert "FAIL" in html and "push" in html and len(html) < 5000
