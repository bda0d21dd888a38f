"""`betv check` states which rung of the fidelity ladder decided each set's mode, honours
the measured λ trust margins, and `--fidelity` forces a rung.

Sources: the measured mispredictions of the λ rule stored in
betvdesign/fidelity_measured.py (benchmarks/work_precision.py --ladder), the trust margin
restated from :func:`betvdesign.fidelity.lambda_trust_margin` and the design window /
fit range of docs/MODEL.md; forced rungs against a direct call of the rung's own solver
(second path); CLI runs through typer's CliRunner.
"""

import dataclasses
import json
import math
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from betvdesign import checker
from betvdesign.checker import check_derivation
from betvdesign.cli import app
from betvdesign.errors import UsageError
from betvdesign.fidelity import lambda_trust_margin, rigid_error_estimate
from betvdesign.fidelity_measured import MEASURED
from betvdesign.nondim import derive_file
from betvdesign.params import ModelParams
from betvdesign.rules import DEFAULT_LAMBDA_MARGIN, FIT_RANGE, evaluate, undecided_reasons

DEVICES = Path(__file__).resolve().parents[1] / "devices"
PULL = str(DEVICES / "pull_demo.yaml")
PUSH = str(DEVICES / "push_demo.yaml")
BASE = derive_file(DEVICES / "push_demo.yaml").sets[0]


def _set(varpi, alpha, beta, kappa, intended="push"):
    p = ModelParams(varpi, alpha, beta, kappa)
    return dataclasses.replace(BASE, params=p, lam=p.lam, intended_mode=intended, published=[])


def _rule(results, rid):
    (r,) = [r for r in results if r.id == rid]
    return r


def run(*args):
    return CliRunner().invoke(app, list(args))


def _in_fit(p: ModelParams) -> bool:
    return all(
        lo * (1 - 1e-9) <= getattr(p, k) <= hi * (1 + 1e-9) for k, (lo, hi) in FIT_RANGE.items()
    )


def test_no_measured_misprediction_is_decided_by_lambda():
    """At every point where the λ rule was measured to name the wrong mode (push/pull map
    and the random off-grid sample), the check does not let λ decide: the λ-margin rule
    fails without a solver, and undecided_reasons is not empty (-> auto-simulation)."""
    lam = MEASURED["lambda"]
    cases = lam["mispredictions"] + lam["sample"]["mispredictions"]
    assert len(cases) >= 40  # the 24 map points and 27 sample points
    for m in cases:
        s = _set(m["varpi"], m["alpha"], m["beta"], m["kappa"])
        assert undecided_reasons(s), m
        margin = _rule(evaluate(s), "lambda-margin")
        assert not margin.passed, m
        assert "work_precision.py --ladder" in margin.source


@settings(max_examples=200, deadline=None)
@given(
    varpi=st.floats(0.4, 2.2),
    alpha=st.floats(0.08, 4.5),
    beta=st.floats(0.08, 1.6),
    kappa=st.floats(0.08, 0.45),
)
def test_lambda_decides_exactly_where_measured_trust_allows(varpi, alpha, beta, kappa):
    """Invariant: λ alone decides ⇔ |λ − 1| ≥ max(0.2, measured trust margin at (ϖ, β)),
    0.5 ≤ ϖ < 2 and every parameter in the fit range; the λ-margin rule (no solver)
    passes ⇔ |λ − 1| reaches that margin (the fabrication margin where none was measured)."""
    s = _set(varpi, alpha, beta, kappa)
    p = s.params
    d = abs(p.lam - 1)
    trust = lambda_trust_margin(varpi, beta)
    need = max(DEFAULT_LAMBDA_MARGIN, trust)
    decides = d >= need and 0.5 <= varpi < 2.0 and _in_fit(p)
    assert (undecided_reasons(s) == []) == decides
    r = _rule(evaluate(s), "lambda-margin")
    need_rule = need if math.isfinite(trust) else DEFAULT_LAMBDA_MARGIN
    assert r.passed == (d >= need_rule)
    assert r.value == pytest.approx(d)


def test_pull_demo_without_solver_states_the_fallback(monkeypatch):
    """pull_demo lies within the measured margin: without a solver λ's guess stands in,
    the λ-margin warning cites the measurement, the error rules still pass."""
    monkeypatch.setattr(checker, "load_solver", lambda: None)
    r = run("check", "--json", "--verbose", PULL)
    assert r.exit_code == 0, r.stdout
    s = json.loads(r.stdout)["devices"][0]["details"]["sets"][0]
    f = s["fidelity"]
    assert (f["rung"], f["chosen"], f["forced"]) == ("lambda", "periodic", False)
    assert "not available" in f["reason"] and "mispredict" in f["reason"]
    margin = next(x for x in s["rules"] if x["id"] == "lambda-margin")
    assert not margin["passed"] and "measured" in margin["threshold"]
    assert "trust margin 4.29" in margin["message"]


def test_forced_rungs_answer_with_their_own_solver():
    """--fidelity rigid / full / periodic: the mode rule carries the rung's Δs, equal to a
    direct call of that rung (rigid_periodic; simulate over 100 cycles; periodic_orbit);
    --fidelity lambda runs nothing and says it was forced."""
    from betvdesign.dynamics import periodic_orbit, simulate
    from betvdesign.dynamics.rigid import rigid_periodic

    der = derive_file(PULL)
    p = der.sets[0].params
    expected = {
        "rigid": rigid_periodic(p).delta_s,
        "full": float(simulate(p, 100).delta_s[-1]),
        "periodic": periodic_orbit(p).delta_s,
    }
    for rung, ds in expected.items():
        res = check_derivation(der, fidelity=rung)
        sc = res.sets[0]
        assert sc.fidelity.rung == rung and sc.fidelity.forced
        assert f"--fidelity {rung}" in sc.fidelity.reason
        assert _rule(sc.rules, "mode").value == pytest.approx(ds, rel=1e-12)
        assert sc.mode_source == "simulation" and sc.mode_predicted == "pull"
        if rung == "rigid":
            est = f"{rigid_error_estimate(p.alpha):.2g}"  # measured bound, about 8 at α = 0.3
            assert any(f"relative Δs error at α = 0.3: {est}" in n for n in res.notes)
    res = check_derivation(der, fidelity="lambda")
    sc = res.sets[0]
    assert sc.periodic is None and sc.mode_answer is None
    assert (sc.fidelity.rung, sc.mode_source) == ("lambda", "lambda")
    assert any("--fidelity lambda forced although" in n for n in res.notes)


def test_fidelity_cli_table_json_and_usage_errors():
    """Table and JSON name the rung; bad rungs and contradicting flags exit 2 naming the
    rungs; nothing reaches stdout then."""
    r = run("check", "--verbose", "--fidelity", "full", PULL)
    assert r.exit_code == 0, r.output
    assert "fidelity: rung full, forced" in r.stdout
    d = json.loads(run("check", "--json", "-v", "--fidelity", "lambda", PUSH).stdout)
    d = d["devices"][0]["details"]
    assert d["fidelity"]["rung"] == "lambda" and d["fidelity"]["forced"]
    assert d["sets"][0]["simulation"] is None
    bad = run("check", "--fidelity", "exact", PUSH)
    assert bad.exit_code == 2 and bad.stdout == ""
    assert "lambda, vertical, rigid, full, periodic" in bad.stderr
    cannot = run("check", "--fidelity", "vertical", PUSH)
    assert cannot.exit_code == 2 and "use one of lambda, rigid, full, periodic" in cannot.stderr
    clash = run("check", "--simulate", "--fidelity", "rigid", PUSH)
    assert clash.exit_code == 2 and "contradicts --simulate" in clash.stderr
    clash = run("check", "--closed-form-only", "--fidelity", "periodic", PUSH)
    assert clash.exit_code == 2 and "contradicts --closed-form-only" in clash.stderr
    with pytest.raises(UsageError, match="contradicts"):
        check_derivation(derive_file(PUSH), simulate="never", fidelity="full")
