"""Failure map "tanh-creep": regularised friction tanh(v/ε) never sticks.

Sources: the exact solver's event log (stick phases entered at velocity-match events,
ζ' = s' held exactly) against the regularised model integrated by solve_ivp (LSODA,
rtol 1e-10) at three ε; the regularised error is first order in ε (creep), the
exact solver's is round-off against solve_ivp with switching friction.
"""

from __future__ import annotations

import numpy as np
import pytest

from betvdesign.dynamics import reference, simulate
from betvdesign.model.params import ModelParams

P = ModelParams(0.6, 0.5, 1.5, 0.4)  # sticks in every contact
CYCLES = 6


@pytest.fixture(scope="module")
def exact():
    return simulate(P, CYCLES, dense=True)


def test_exact_sticks_exactly(exact):
    """Stick phases exist and inside them ζ' = s' to round-off (dense output)."""
    ev = exact.events
    starts = [e.tau for e in ev if e.phase_after == "stick"]
    assert len(starts) >= CYCLES
    ends = [next(e.tau for e in ev if e.tau > t and e.phase_before == "stick") for t in starts]
    taus = np.concatenate([np.linspace(a, b, 7)[1:-1] for a, b in zip(starts, ends, strict=True)])
    st = exact.sample(taus)
    assert np.abs(st[:, 3] - st[:, 5]).max() < 1e-12
    sw = reference.simulate(P, CYCLES, method="DOP853", rtol=1e-11, atol=1e-13)
    assert exact.s == pytest.approx(sw.s, rel=1e-8)


def _stick_midpoints(exact) -> np.ndarray:
    ev = exact.events
    starts = [e.tau for e in ev if e.phase_after == "stick"]
    ends = [next(e.tau for e in ev if e.tau > t and e.phase_before == "stick") for t in starts]
    return np.array([0.5 * (a + b) for a, b in zip(starts, ends, strict=True)])


def test_tanh_creeps_with_error_of_order_eps(exact):
    """tanh(v/ε): where Coulomb friction sticks, the regularised head and slider still
    slide against each other (creep: |ζ' − s'| > 0, shrinking with ε), and s is off by
    ~ε; never at round-off."""
    errs, creep = [], []
    mid = _stick_midpoints(exact)
    for eps in (1e-2, 1e-3):
        r = reference.simulate(
            P,
            CYCLES,
            method="LSODA",
            rtol=1e-10,
            atol=1e-12,
            friction="tanh",
            eps=eps,
            dense=True,
        )
        assert r.success
        st = r.sample(mid)
        creep.append(float(np.median(np.abs(st[:, 3] - st[:, 5]))))
        errs.append(abs(r.s - exact.s) / abs(exact.s))
    assert creep[0] > creep[1] > 1e-7  # slides where the exact model sticks
    assert errs[0] > 1e-3
    assert errs[1] > 1e-4
    assert 3 < errs[0] / errs[1] < 30  # first order in ε
