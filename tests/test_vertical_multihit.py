"""Below the window (ϖ < 0.5) the head also hits impulsively after each contact.

Source: closed form of the free flight that follows a contact end. Contact ends at
τ_e = π/ϖ with ξ = ξ' = 0 (MODEL.md, "Impacts and separation"), so for ϖ ≠ 1 the
gap is ξ(σ) = (sin ϖσ − ϖ sin σ)/(1 − ϖ²) with σ = τ − τ_e. Its first root in
(0, π/ϖ) is an impulsive hit (sin ϖτ < 0) in every cycle of the periodic pattern.
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from betvdesign.dynamics import simulate, vertical_motion
from betvdesign.model.params import ModelParams


def _first_gap_root(varpi: float) -> float:
    def gap(sig: float) -> float:
        return (math.sin(varpi * sig) - varpi * math.sin(sig)) / (1.0 - varpi**2)

    grid = np.linspace(1e-6, math.pi / varpi, 20001)
    vals = np.array([gap(x) for x in grid])
    i = int(np.argmax(vals < 0.0))
    assert vals[i] < 0.0
    return brentq(gap, grid[i - 1], grid[i], xtol=1e-15)


@pytest.mark.parametrize("varpi", [0.3401, 0.4, 0.45])
def test_impulsive_hit_after_every_contact(varpi):
    vm = vertical_motion(varpi)
    assert vm.regime == "multi-impact"
    assert vm.hits_per_cycle == pytest.approx(2.0)
    assert vm.impulsive_per_cycle == pytest.approx(1.0)

    traj = simulate(ModelParams(varpi, 0.5, 0.5, 0.2), 4)
    taus = [e.tau for e in traj.events]
    assert taus == sorted(taus), "event log must be in time order"
    seps = [e.tau for e in traj.events if e.kind == "separation"]
    imps = [e.tau for e in traj.events if e.kind == "impulsive"]
    sigma = _first_gap_root(varpi)
    assert len(imps) == len(seps) == 4
    for t_sep, t_imp in zip(seps, imps, strict=True):
        assert t_imp - t_sep == pytest.approx(sigma, abs=1e-9)


def test_window_has_single_hit():
    for varpi in (0.5, 0.9, 1.5):
        vm = vertical_motion(varpi)
        assert vm.regime == "single-impact"
        assert vm.impulsive_per_cycle == 0.0


def test_event_counter_does_not_depend_on_logging():
    """n_events counts impulsive hits whether or not the event log is kept (invariant)."""
    p = ModelParams(0.3401, 0.5, 0.5, 0.2)
    logged = simulate(p, 6)
    silent = simulate(p, 6, log_events=False)
    assert logged.n_events == len(logged.events) == silent.n_events
    assert any(e.kind == "impulsive" for e in logged.events)
