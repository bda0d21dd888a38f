"""Tolerance study of a device with damping and restitution (issue 12).

Independent truths: the reference solver (scipy solve_ivp, docs/damping.md) for a
sample the study calls "not driven" (no contact in any cycle: the slider never moves),
and the λ rung refused where its model (the idealised one) is not the device's.
"""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from betvdesign.cli import app
from betvdesign.dynamics import reference
from betvdesign.errors import UsageError
from betvdesign.model.params import ModelParams
from betvdesign.studies.tolerance import parse_tolerance, run_tolerance

DAMPED = "devices/damped_demo.yaml"


def test_lambda_rung_refused_for_a_damped_device():
    tols = [parse_tolerance("actuator.vertical_resonance=3%")]
    with pytest.raises(UsageError, match="fit to the idealised model"):
        run_tolerance(DAMPED, tols, samples=5, seed=0, fidelity="lambda")


def test_lambda_rung_refused_for_a_restitution_spread():
    tols = [parse_tolerance("contact.friction=3%"), parse_tolerance("contact.restitution=0.05")]
    with pytest.raises(UsageError, match=r"contact\.restitution spread"):
        run_tolerance("devices/push_demo.yaml", tols, samples=5, seed=0, fidelity="lambda")


def test_lambda_refusal_is_exit_2_from_the_cli():
    args = ["tolerance", DAMPED, "--spread", "actuator.vertical_resonance=3%"]
    r = CliRunner().invoke(app, [*args, "--fidelity", "lambda"])
    assert r.exit_code == 2
    assert r.exception is None or isinstance(r.exception, SystemExit)
    assert "--fidelity periodic" in r.output


def test_not_driven_samples_are_counted_apart_and_are_not_driven():
    """A restitution spread across the mode's flip (e ≈ 0.17 for damped_demo): samples
    above it are not driven (counted as such, not as 'not converged'); the reference
    solver confirms for one of them that no contact ever recurs."""
    tols = [parse_tolerance("contact.restitution=uniform:0.1")]  # e ∈ [0, 0.2]
    run, summary = run_tolerance(DAMPED, tols, samples=40, seed=3)
    s = summary["sets"]["forward"]
    assert s["p_not_driven"] > 0.05 and s["p_not_converged"] == 0.0
    idle = [r for r in run.rows if r["status"] == "not_driven"]
    moving = [r for r in run.rows if r["status"] == "success"]
    assert min(r["restitution"] for r in idle) > max(r["restitution"] for r in moving)
    r = max(idle, key=lambda r: r["restitution"])
    p = ModelParams(
        r["varpi"],
        r["alpha"],
        r["beta"],
        r["kappa"],
        r["zeta_v"],
        r["zeta_h"],
        r["restitution"],
    )
    rf = reference.simulate(p, 30, rtol=1e-10, atol=1e-12)
    assert rf.success, rf.message
    late = [
        e for e in rf.events if e.kind == "impact" and e.tau > 20 * 2 * 3.141592653589793 / p.varpi
    ]
    assert late == []  # no contact start in the last 10 cycles: impulsive hits only
    # no force on the slider: it keeps whatever velocity the first cycles gave it
    assert abs(rf.section[-1][5] - rf.section[-11][5]) < 1e-12
