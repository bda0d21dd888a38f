"""Exact solver against the independent solve_ivp reference (source: a second method —
numerical integration of the full state with scipy's own event location, MODEL.md
switching rules), including the exactly resonant cases; and the reference's own options."""

import math

import numpy as np
import pytest
from conftest import WINDOW_SETS

from betvdesign.dynamics import reference, simulate
from betvdesign.errors import ParameterError
from betvdesign.model.params import ModelParams

CYCLES = 30


@pytest.mark.parametrize("p", WINDOW_SETS, ids=lambda p: f"{p.varpi:.2f}-{p.alpha:.2g}")
def test_exact_agrees_with_reference(p):
    ex = simulate(p, CYCLES)
    rf = reference.simulate(p, CYCLES, method="DOP853", rtol=1e-12, atol=1e-13)
    assert ex.success and rf.success, (ex.message, rf.message)
    assert abs(ex.s - rf.s) <= 1e-8 * max(1.0, abs(ex.s))
    assert np.allclose(ex.section, rf.section, atol=1e-7 * max(1.0, np.abs(ex.section).max()))
    assert [e.kind for e in ex.events] == [e.kind for e in rf.events]


@pytest.mark.parametrize(
    "p,what",
    [
        (ModelParams(1.0, 0.5, 1.0, 0.4), "ϖ = 1: vertical free flight resonant"),
        (ModelParams(1.25, 0.64, 1.0, 0.4), "αϖ² = 1: tangential free flight resonant"),
        (ModelParams(1.25, 0.32, 1.0, 0.4), "α(1+1/β)ϖ² = 1: stick resonant"),
    ],
)
def test_resonant_cases_against_reference(p, what):
    """Exact resonance is the secular closed form, never a nudged parameter."""
    ex = simulate(p, 15)
    rf = reference.simulate(p, 15, rtol=1e-12, atol=1e-13)
    assert ex.success and rf.success
    assert abs(ex.s - rf.s) <= 1e-8 * max(1.0, abs(ex.s)), what


def test_tanh_friction_approaches_exact_switching():
    """Regularised friction converges to Coulomb switching as ε → 0 (Radau, stiff)."""
    p = ModelParams(1.2, 0.5, 1.0, 0.4)
    ex = simulate(p, 5)
    errs = [
        abs(
            reference.simulate(
                p, 5, method="Radau", rtol=1e-8, atol=1e-10, friction="tanh", eps=eps
            ).s
            - ex.s
        )
        for eps in (1e-2, 1e-3)
    ]
    assert errs[1] < errs[0] < 0.5


@pytest.mark.parametrize("method", ["RK45", "DOP853", "Radau", "LSODA"])
def test_reference_methods_report_counters(method):
    p = ModelParams(1.5, 1.0, 0.2, 0.2)
    rf = reference.simulate(p, 3, method=method, rtol=1e-8, atol=1e-10)
    assert rf.success and rf.n_fev > 0 and rf.elapsed_s > 0 and rf.n_cycles == 3
    assert rf.solver == f"solve_ivp:{method}/exact"
    assert abs(rf.s - simulate(p, 3).s) < 1e-4


def test_reference_dense_output_matches_sections():
    p = ModelParams(1.5, 1.0, 0.2, 0.2)
    rf = reference.simulate(p, 2, dense=True)
    T = 2 * math.pi / p.varpi
    assert np.allclose(rf.sample([T, 2 * T]), rf.section[1:], atol=1e-9)


@pytest.mark.parametrize(
    "kw",
    [
        {"method": "Euler"},
        {"friction": "viscous"},
        {"rtol": 0.0},
        {"eps": -1.0},
        {"atol": math.nan},
    ],
)
def test_reference_rejects_bad_options(kw):
    with pytest.raises(ParameterError):
        reference.simulate(ModelParams(1.2, 0.5, 1.0, 0.4), 2, **kw)


def test_reference_shares_no_code_with_the_exact_solver():
    """The reference is a second method only if it is written separately: it (and its
    damping/restitution terms, reference_terms) imports nothing of the exact solver
    (flows, phase rule, search, kernels, chattering closure), only the shared input
    checks and result types (house rule: independent truths in tests)."""
    import ast
    from pathlib import Path

    from betvdesign.dynamics import reference_terms

    for mod in (reference, reference_terms):
        src = Path(mod.__file__).read_text()
        mods = {
            node.module
            for node in ast.walk(ast.parse(src))
            if isinstance(node, ast.ImportFrom) and node.module
        }
        mods |= {
            alias.name
            for node in ast.walk(ast.parse(src))
            if isinstance(node, ast.Import)
            for alias in node.names
        }
        ours = {m for m in mods if m.startswith("betvdesign.dynamics")}
        allowed = {
            "betvdesign.dynamics.inputs",
            "betvdesign.dynamics.result",
            "betvdesign.dynamics.reference_terms",
        }
        assert ours <= allowed, (mod.__name__, ours)
        assert "normal_force_phase" not in src  # the exact solver's time shift, not shared
