"""Failure map "early-stop": "two successive Δs agree to 1e-4" names the wrong mode.

Sources: the exact transient (the naive criterion applied to it) against the periodic
orbit by Newton shooting (residual ≤ 1e-10), re-simulated from its state (fixed point),
and a long brute-force transient heading to the same Δs (a second route).
"""

from __future__ import annotations

import numpy as np
import pytest

from betvdesign.dynamics import periodic_orbit, simulate
from betvdesign.model.params import ModelParams


def naive_mode(delta_s: np.ndarray, tol: float = 1e-4) -> tuple[int, str]:
    """The criterion MODEL.md warns against: stop at the first |Δs_m − Δs_{m−1}| < tol."""
    m = int(np.nonzero(np.abs(np.diff(delta_s)) < tol)[0][0]) + 1
    return m, "push" if delta_s[m] > 0 else "pull"


@pytest.mark.parametrize(
    "params, long_cycles",
    [((1.6, 0.1, 0.5, 0.1), 1500), ((0.6, 2.0, 0.1, 0.1), 1500)],
    ids=["stops-at-cycle-1", "stops-at-cycle-17"],
)
def test_early_stopping_gives_wrong_mode(params, long_cycles):
    p = ModelParams(*params)
    tr = simulate(p, 60, log_events=False)
    m, mode = naive_mode(tr.delta_s)
    po = periodic_orbit(p)
    assert po.success and po.residual <= 1e-10
    assert po.mode != mode, f"naive criterion stopped at cycle {m} with the right mode"
    # the orbit is a fixed point of the exact map ...
    k = po.period_cycles
    on = simulate(p, k, state0=po.state, log_events=False)
    assert (on.s - on.section[0, 4]) / k == pytest.approx(po.delta_s, rel=1e-9)
    # ... and brute force from rest, run long enough, settles there
    long = simulate(p, long_cycles, log_events=False)
    assert long.delta_s[-1] == pytest.approx(po.delta_s, rel=1e-7)
