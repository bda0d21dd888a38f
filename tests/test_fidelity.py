"""The fidelity ladder (betvdesign.checks.fidelity) and ``betv ladder``.

Sources: the stored measurements (betvdesign/data/fidelity_measured.json, regenerated
by benchmarks/work_precision.py --ladder) checked against a recount and a recomputation
(the staleness check); a Clopper–Pearson bound restated from the binomial distribution;
the rigid limit against the full model where the ladder picks it; CLI runs with typer's
CliRunner.
"""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from betvdesign.checks import fidelity
from betvdesign.cli import app
from betvdesign.dynamics import periodic_orbit
from betvdesign.errors import UsageError
from betvdesign.model.params import ModelParams

PULL = ModelParams(0.9, 0.1, 0.9, 0.4)  # λ ≈ 12.3
NEAR = ModelParams(1.2, 0.66, 1.0, 0.4)  # λ ≈ 1.05


@pytest.mark.parametrize(
    "p, question, rung",
    [
        (PULL, "mode", "periodic"),  # a mode never comes from a fit
        (NEAR, "mode", "periodic"),
        (PULL, "regime", "vertical"),
        (PULL, "transient", "full"),
        (PULL, "stability", "periodic"),
        (PULL, "delta_s", "periodic"),
        (ModelParams(2.3, 0.1, 0.9, 0.4), "mode", "periodic"),  # outside the window
        (ModelParams(0.9, 0.1, 0.05, 0.4), "mode", "periodic"),  # β outside the map
    ],
)
def test_cheapest_adequate_rung(p, question, rung):
    c = fidelity.choose_rung(p, question)
    assert c.rung == rung
    assert c.reason and not c.forced


def test_rigid_chosen_only_where_its_measured_error_fits():
    """delta_s at α = 1e-6: rigid when tol allows its measured error, else periodic;
    and where chosen, it agrees with the full periodic orbit within that tol."""
    p = ModelParams(0.6, 1e-6, 1.5, 0.4)
    est = fidelity.rigid_error_estimate(p.alpha)
    assert fidelity.choose_rung(p, "delta_s", tol=est / 2).rung == "periodic"
    c = fidelity.choose_rung(p, "delta_s", tol=2 * est)
    assert c.rung == "rigid"
    rig = fidelity.evaluate(p, c)
    full = periodic_orbit(ModelParams(0.6, 1e-4, 1.5, 0.4))  # cheaper α, larger error
    assert rig.success and rig.mode == "pull"
    assert abs(rig.value - full.delta_s) / abs(full.delta_s) <= fidelity.rigid_error_estimate(1e-4)


def test_forced_rung_and_refusals():
    c = fidelity.choose_rung(PULL, "mode", force="periodic")
    assert c.rung == "periodic" and c.forced and "--fidelity" in c.reason
    with pytest.raises(UsageError, match="cannot answer 'stability'"):
        fidelity.choose_rung(PULL, "stability", force="lambda")
    with pytest.raises(UsageError, match="unknown fidelity"):
        fidelity.choose_rung(PULL, "mode", force="exactest")  # type: ignore[arg-type]
    with pytest.raises(UsageError, match="unknown question"):
        fidelity.choose_rung(PULL, "speed")  # type: ignore[arg-type]


@pytest.mark.parametrize("rung", ["lambda", "rigid", "full", "periodic"])
def test_every_mode_rung_evaluates(rung):
    """Each rung that answers 'mode' runs and says so; the λ and periodic rungs agree
    on a design far from λ = 1."""
    ans = fidelity.answer(PULL, "mode", force=rung)
    assert ans.success, ans.message
    assert ans.choice.rung == rung and ans.seconds >= 0
    assert ans.mode == "pull"


def test_stored_measurement_is_consistent_and_not_stale():
    """The held-out λ statistics recount from their own rows, the bound is a real
    one-sided 95 % bound (binomial tail at the bound = 5 %, computed with scipy.stats
    .binom, not the beta quantile the code uses), the provenance names commit, date and
    command, and the solver still gives the stored fingerprint Δs."""
    from scipy.stats import binom

    doc = fidelity.measured_document()
    prov = doc["provenance"]
    assert prov["commit"] and prov["date"] and "--ladder" in prov["command"]
    h = doc["measured"]["lambda"]["held_out"]
    assert h["points"] >= 5000
    assert h["mispredicted"] == len(h["mispredictions"])
    assert sum(b["points"] for b in h["bands"]) == h["converged"]
    assert sum(b["mispredicted"] for b in h["bands"]) == h["mispredicted"]
    assert binom.cdf(h["mispredicted"], h["converged"], h["upper_95"]) == pytest.approx(0.05)
    assert fidelity.stale() == []
    err = fidelity.lambda_error()
    assert err["rate"] == pytest.approx(h["mispredicted"] / h["converged"])


def test_staleness_check_detects_a_changed_solver(monkeypatch):
    """A solver whose Δs differ from the stored fingerprint makes the data stale."""
    from types import SimpleNamespace

    from betvdesign import dynamics

    monkeypatch.setattr(dynamics, "periodic_orbit", lambda p: SimpleNamespace(delta_s=123.0))
    why = fidelity.stale()
    assert why and "stored" in why[0]


def test_forced_lambda_states_its_held_out_error_rate():
    c = fidelity.choose_rung(PULL, "mode", force="lambda")
    assert "held-out" in c.reason and "95 %" in c.reason
    ans = fidelity.evaluate(PULL, c)
    assert "held-out" in ans.message


def test_cli_ladder_json():
    """``betv ladder mode ... --json``: rung, reason, value; --fidelity forces."""
    args = ["ladder", "mode", "--varpi", "0.9", "--alpha", "0.1", "--beta", "0.9", "--kappa", "0.4"]
    res = CliRunner().invoke(app, [*args, "--json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert doc["rung"] == "periodic" and doc["mode"] == "pull" and doc["reason"]
    res = CliRunner().invoke(app, [*args, "--json", "--fidelity", "lambda"])
    doc = json.loads(res.stdout)
    assert doc["rung"] == "lambda" and doc["forced"] and "held-out" in doc["reason"]


@pytest.mark.parametrize(
    "extra, msg",
    [
        (["--fidelity", "lambda", "--json"], "cannot answer"),
        (["--alpha", "-1"], "alpha must be > 0"),
    ],
)
def test_cli_ladder_bad_input(extra, msg):
    base = ["ladder", "stability", "--varpi", "0.9", "--alpha", "0.1", "--beta", "0.9"]
    res = CliRunner().invoke(app, [*base, "--kappa", "0.4", *extra])
    assert res.exit_code == 2
    assert msg in res.stderr
