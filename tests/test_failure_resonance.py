"""Failure map "resonance": ϖ = 1 and a·ϖ² = 1 (a = α, α(1 + 1/β)) handled exactly.

Sources: solve_ivp DOP853 with event location (rtol 1e-12) as the independent method
at the exact resonance; continuity of s across the resonance (no 1/(1 − ϖ²) blow-up).
"""

from __future__ import annotations

import pytest

from betvdesign.dynamics import reference, simulate
from betvdesign.model.params import ModelParams

CYCLES = 8


def _cases():
    beta, kappa = 0.5, 0.4
    return {
        "varpi=1": ModelParams(1.0, 0.8, beta, kappa),
        "alpha*varpi^2=1": ModelParams(1.25, 1 / 1.25**2, beta, kappa),
        "stick a*varpi^2=1": ModelParams(0.9, 1 / (0.9**2 * (1 + 1 / beta)), beta, kappa),
    }


@pytest.mark.parametrize("name", list(_cases()))
def test_exact_at_resonance_matches_reference(name):
    p = _cases()[name]
    ex = simulate(p, CYCLES, log_events=False)
    ref = reference.simulate(p, CYCLES, method="DOP853", rtol=1e-12, atol=1e-14)
    assert ex.success and ref.success
    assert ex.s == pytest.approx(ref.s, rel=1e-8, abs=1e-9)


@pytest.mark.parametrize("name", list(_cases()))
def test_continuous_across_resonance(name):
    """s at the resonance and at ±1e-9 relative detuning differ by O(1e-9) only."""
    p = _cases()[name]
    base = simulate(p, CYCLES, log_events=False).s
    for f in (1 - 1e-9, 1 + 1e-9):
        q = ModelParams(p.varpi * f, p.alpha, p.beta, p.kappa)
        assert simulate(q, CYCLES, log_events=False).s == pytest.approx(base, rel=1e-6, abs=1e-6)
