"""The damped / restitution solver: limits, brute force and loud failures (issue 12).

Independent truths used here: the undamped model's own fast path (a different set of
event functions and bounds) for the general form at zero damping; continuity of the
model in ζ → 0 and e → 0 (the physics is continuous there); brute-force transients for
periodic orbits; an explicit closed-form free fall for a single chattering sequence. The
solve_ivp reference and mpmath checks are in test_damped_reference.py,
test_damped_closed_forms.py and test_chattering.py.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from betvdesign.dynamics import flows, periodic_orbit, simulate, solver
from betvdesign.dynamics.vertical import VerticalSchedule
from betvdesign.errors import ParameterError
from betvdesign.model.params import ZETA_MIN, ModelParams


def _designs(n: int, seed: int) -> list[ModelParams]:
    rng = np.random.default_rng(seed)
    return [
        ModelParams(
            float(rng.uniform(0.55, 1.9)),
            float(10 ** rng.uniform(-1.3, 0.3)),
            float(10 ** rng.uniform(-1, 1)),
            float(rng.uniform(0.1, 1.0)),
        )
        for _ in range(n)
    ]


def test_general_form_at_zero_damping_reproduces_the_undamped_fast_path(monkeypatch):
    """The event functions, bounds and stick-band rule in their general (damped) form
    (dynamics.evaluators, values, contact) with g = G = 0 against the undamped closed
    form (split, envelopes, clearance): a different implementation of the same events,
    so 100 cycles agree to round-off."""
    designs = _designs(8, 11)
    ideal = [simulate(p, 100, log_events=False).section for p in designs]

    monkeypatch.setattr(solver, "phase_table", lambda p: flows.phase_table(p, general=True))
    for p, a in zip(designs, ideal, strict=True):
        b = simulate(p, 100, log_events=False)
        assert b.success, b.message
        err = np.max(np.abs(a - b.section) / np.maximum(1.0, np.abs(a)))
        assert err < 1e-11, (p, err)


@pytest.mark.parametrize("p", _designs(4, 5))
def test_damping_and_restitution_vanish_continuously(p):
    """ζ = ZETA_MIN and e = 1e-6 stay within O(ζ·cycles) and O(e) of the paper's model
    over 50 cycles (the damped closed form and the chattering closure at their limits)."""
    a = simulate(p, 50, log_events=False).section
    damped = simulate(replace(p, zeta_v=ZETA_MIN, zeta_h=ZETA_MIN), 50, log_events=False)
    bouncy = simulate(replace(p, restitution=1e-6), 50, log_events=False)
    scale = np.maximum(1.0, np.abs(a))
    assert np.max(np.abs(damped.section - a) / scale) < 0.05
    assert np.max(np.abs(bouncy.section - a) / scale) < 1e-3


@pytest.mark.parametrize(
    "kw",
    [
        {"zeta_h": 0.02},
        {"zeta_v": 0.03, "zeta_h": 0.05},
        {"zeta_v": 0.05, "zeta_h": 0.05, "restitution": 0.1},
        {"zeta_v": 1.0, "zeta_h": 1.0},  # critically damped head
        {"zeta_v": 0.02, "zeta_h": 3.0},  # overdamped tangentially
    ],
)
def test_periodic_orbit_matches_brute_force(kw):
    """The shooting answer of the damped model is the state a long transient settles to
    (the published fit, with damping and restitution)."""
    p = ModelParams(0.9, 0.1, 0.9, 0.4, **kw)
    po = periodic_orbit(p)
    assert po.success, po.message
    tr = simulate(p, 4000, log_events=False)
    ds = np.diff(tr.section[:, 4])
    assert abs(ds[-1] - po.delta_s) <= 1e-7 * max(1.0, abs(po.delta_s))


def test_tangential_resonance_is_finite_with_damping():
    """α·ϖ² = 1: the idealised model grows without bound (proof in periodic.py); any
    tangential damping gives a finite periodic orbit, the state a transient reaches."""
    ideal = periodic_orbit(ModelParams(1.0, 1.0, 1.0, 0.4))
    assert ideal.status == "unbounded"
    p = ModelParams(1.0, 1.0, 1.0, 0.4, zeta_h=0.02)
    po = periodic_orbit(p)
    assert po.success and math.isfinite(po.delta_s)
    tr = simulate(p, 3000, log_events=False)
    assert abs(np.diff(tr.section[:, 4])[-1] - po.delta_s) <= 1e-7 * abs(po.delta_s)


def test_chattering_sequence_follows_the_geometric_law():
    """Near its accumulation point a chattering sequence sees a constant pull a, so its
    flights 2v_k/a shrink by exactly e per hit (Budd & Dux 1994) and the time left after
    the last hit is the geometric tail flight·e/(1 − e). (Before the flight-sized
    round-off scale, tiny flights were cut short by the gap's O(1) round-off floor: the
    ratio fell to 0.42 and the contact start moved by 1e-6.)"""
    e = 0.5
    vs = VerticalSchedule(0.3, horizon=20, restitution=e)
    rows = [r for r in vs.table if r["imp_count"] >= 6 and r["tc"] == r["tc"]]
    assert rows, "expected a chattering cycle at ϖ = 0.3"
    r = rows[0]
    hits = vs.impulsive[r["imp_start"] : r["imp_start"] + r["imp_count"]]
    hits = hits[hits < r["tc"]]
    flights = np.diff(hits)[-4:]
    ratios = flights[1:] / flights[:-1]
    assert np.allclose(ratios, e, rtol=1e-3)  # late flights: constant pull, ratio e
    # the remainder after the last hit is the geometric tail of the last flight
    tail = r["tc"] - hits[-1]
    assert tail == pytest.approx(flights[-1] * e / (1 - e), rel=1e-3)


@pytest.mark.parametrize(
    "kw",
    [
        {"zeta_v": -0.1},
        {"zeta_h": 1e-6},
        {"zeta_h": 11.0},
        {"restitution": 1.0},
        {"zeta_v": math.nan},
    ],
)
def test_bad_optional_terms_are_refused(kw):
    with pytest.raises(ParameterError):
        ModelParams(0.9, 0.1, 0.9, 0.4, **kw)


def test_schedule_refuses_bad_terms():
    with pytest.raises(ParameterError):
        VerticalSchedule(0.9, restitution=1.2)


def test_vertical_failure_is_a_failed_result_not_a_traceback(monkeypatch):
    """A vertical motion that cannot be computed (e.g. a chattering sequence that never
    accumulates) comes back as status "failed" with the reason."""
    from betvdesign.dynamics import periodic
    from betvdesign.dynamics.vertical import VerticalSearchError

    def boom(*a, **k):
        raise VerticalSearchError("a chattering sequence did not accumulate")

    monkeypatch.setattr(periodic, "VerticalSchedule", boom)
    po = periodic.periodic_orbit(ModelParams(0.9, 0.1, 0.9, 0.4, restitution=0.3))
    assert po.status == "failed" and not po.success
    assert "did not accumulate" in po.message
