"""Failure map "growth": a·ϖ² = 1 with weak friction, tangential motion unbounded.

Sources: the exact transient (secular growth of ζ, checked against solve_ivp DOP853
over the first cycles) and the documented contract of periodic_orbit (status
"unbounded" with a message, never a mode); the design rule on tangential resonance.
"""

from __future__ import annotations

import numpy as np
import pytest

from betvdesign.dynamics import periodic_orbit, reference, simulate
from betvdesign.model.params import ModelParams

P = ModelParams(1.2, 1.0 / 1.2**2, 0.5, 0.1)  # α·ϖ² = 1 exactly


def test_exact_follows_secular_growth():
    """|ζ| at the sections grows without bound (roughly linearly); solve_ivp agrees."""
    tr = simulate(P, 400, log_events=False)
    amp = np.abs(tr.section[:, 2])
    assert amp[200:].max() > 1.5 * amp[:200].max()
    assert amp[-1] > 100
    ref = reference.simulate(P, 20, method="DOP853", rtol=1e-11, atol=1e-13)
    assert tr.section[20, 2] == pytest.approx(ref.section[-1, 2], rel=1e-7)


def test_periodic_orbit_reports_unbounded_growth():
    """No periodic state exists (proven bound, tests/test_dynamics_growth.py): status
    "unbounded" within a few hundred cycles, not the whole budget; no mode, no Δs; the
    message names the resonance and the measured growth rate."""
    po = periodic_orbit(P, max_cycles=3000)
    assert not po.success
    assert po.status == "unbounded"
    assert po.transient_cycles < 300
    assert po.mode is None and po.delta_s is None
    assert "a·ϖ² = 1" in po.message and "per cycle" in po.message
