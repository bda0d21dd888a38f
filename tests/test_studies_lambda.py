"""Δs against λ (sources: the closed-form λ fit inverted and re-evaluated)."""

import pytest
from hypothesis import given
from hypothesis import strategies as st

from betvdesign.errors import UsageError
from betvdesign.model.params import ModelParams
from betvdesign.studies.lambda_scan import params_for_lambda, summarise


@given(
    lam=st.floats(0.05, 5.0),
    kappa=st.floats(0.05, 1.0),
    beta=st.floats(0.1, 1.5),
    alpha=st.floats(0.05, 1.0),
)
def test_varying_varpi_hits_the_target_lambda(lam, kappa, beta, alpha):
    p = params_for_lambda(lam, kappa=kappa, beta=beta, vary="varpi", alpha=alpha, varpi=None)
    assert ModelParams(**p).lam == pytest.approx(lam, rel=1e-10)
    assert p["alpha"] == alpha and p["kappa"] == kappa and p["beta"] == beta


@given(lam=st.floats(0.05, 5.0), kappa=st.floats(0.05, 1.0), varpi=st.floats(0.5, 2.0))
def test_varying_alpha_hits_the_target_lambda(lam, kappa, varpi):
    p = params_for_lambda(lam, kappa=kappa, beta=0.5, vary="alpha", alpha=None, varpi=varpi)
    assert ModelParams(**p).lam == pytest.approx(lam, rel=1e-10)


def test_unreachable_lambda_is_a_usage_error():
    # β = 0.1, κ = 0.1: D = (10 − 0.1)/(22·1.1) ≈ 0.409; α = 40 gives 1/(ακ) = 0.25 < D.
    with pytest.raises(UsageError, match="no ϖ reaches"):
        params_for_lambda(1.0, kappa=0.1, beta=0.1, vary="varpi", alpha=40.0, varpi=None)
    with pytest.raises(UsageError, match="needs a fixed --alpha"):
        params_for_lambda(1.0, kappa=0.1, beta=0.1, vary="varpi", alpha=None, varpi=None)
    with pytest.raises(UsageError, match="--vary"):
        params_for_lambda(1.0, kappa=0.1, beta=0.1, vary="beta", alpha=1.0, varpi=1.0)


def test_sign_change_is_bracketed_between_converged_points():
    rows = [
        {"key": 0, "lam": 0.8, "converged": True, "delta_s": 0.3},
        {
            "key": 1,
            "lam": 0.9,
            "converged": False,
            "delta_s": None,
            "varpi": 1,
            "alpha": 1,
            "status": "max_cycles",
            "message": "x",
        },
        {"key": 2, "lam": 1.0, "converged": True, "delta_s": 0.1},
        {"key": 3, "lam": 1.2, "converged": True, "delta_s": -0.1},
    ]
    s = summarise(rows)
    assert s.crossings == [{"from": 1.0, "to": 1.2, "delta_s_from": 0.1, "delta_s_to": -0.1}]
    assert s.n_converged == 3 and [f["key"] for f in s.not_converged] == [1]
