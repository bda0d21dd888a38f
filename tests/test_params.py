"""ModelParams validation and λ (source: hand-computed values of MODEL.md's formula)."""

import math

import pytest

from betvdesign.errors import ParameterError
from betvdesign.model.params import ModelParams, lambda_criterion


def test_lambda_hand_value():
    # ϖ=0.9, α=0.1, β=0.9, κ=0.4: (0.4/0.81)·(1/0.04 − (1/0.9−0.9)/(22·1.4))
    expected = (0.4 / 0.81) * (25.0 - (1 / 0.9 - 0.9) / 30.8)
    assert lambda_criterion(0.9, 0.1, 0.9, 0.4) == pytest.approx(expected, rel=1e-15)
    p = ModelParams(0.9, 0.1, 0.9, 0.4)
    assert p.lam == pytest.approx(expected, rel=1e-15)
    assert p.lambda_mode == "pull"


def test_push_when_lambda_below_one():
    p = ModelParams(varpi=1.5, alpha=2.0, beta=0.5, kappa=0.1)
    assert p.lam < 1.0
    assert p.lambda_mode == "push"


@pytest.mark.parametrize("bad", [0.0, -1.0, math.nan, math.inf, "x"])
@pytest.mark.parametrize("field", ["varpi", "alpha", "beta", "kappa"])
def test_bad_parameters_rejected(field, bad):
    kw = {"varpi": 1.0, "alpha": 1.0, "beta": 1.0, "kappa": 0.4}
    kw[field] = bad
    with pytest.raises(ParameterError, match=field):
        ModelParams(**kw)
