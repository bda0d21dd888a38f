"""The α → 0 rigid-limit model (betvdesign.dynamics.rigid).

Sources: the contact schedule's hits against scipy's solve_ivp events on
ξ'' + ξ = −sin ϖτ (a second, independent method, including ϖ = 1); contact phases
against Moreau time stepping of s'' = βκ sin ϖτ·sgn(ϖ cos ϖτ − s'); the periodic
state against a long transient (an invariant of the fixed point); docs/MODEL.md's
claim that α → 0 always gives pull (hypothesis).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from betvdesign.dynamics import rigid
from betvdesign.model.params import ModelParams


@pytest.mark.parametrize("varpi", [0.55, 0.8, 1.0, 1.6, 1.95, 2.3, 2.9])
def test_schedule_first_hit_matches_ode(varpi):
    """First hit after the first contact end = solve_ivp event on ξ'' + ξ = −sin ϖτ."""
    t0 = math.pi / varpi
    cs, imp, _ = rigid.contact_schedule(varpi, t0 + 80.0, max_contacts=2)
    after = sorted([c.start for c in cs[1:]] + imp)
    assert after, "no hit found"

    def hit(t, y):
        return y[0]

    hit.terminal, hit.direction = True, -1
    sol = solve_ivp(
        lambda t, y: [y[1], -y[0] - math.sin(varpi * t)],
        (t0 + 1e-6, t0 + 80.0),
        [varpi * 1e-18 / 6, 0.0],  # ξ ≈ ϖt³/6 just after lift-off
        events=hit,
        rtol=1e-12,
        atol=1e-15,
    )
    assert after[0] == pytest.approx(sol.t_events[0][0], abs=1e-6)
    kind = "contact" if cs[1:] and after[0] == cs[1].start else "impulsive"
    assert kind == ("contact" if math.sin(varpi * after[0]) >= -1e-9 else "impulsive")


def test_window_edge_hit_is_a_contact_start():
    """ϖ = 0.5 (window edge): the head lands exactly at ϖτ = 2jπ; that is one contact
    start per cycle, not an impulsive hit followed by a contact."""
    cs, imp, _ = rigid.contact_schedule(0.5, 3 * 4 * math.pi)
    starts = [c.start * 0.5 / (2 * math.pi) for c in cs]
    assert starts[:3] == pytest.approx([0.0, 1.0, 2.0], abs=1e-9)
    assert imp == []


def _contact_numeric(c, v0, p, n=40_000):
    """Moreau-type time stepping (friction impulse clipped, so stick is exact): O(h)."""
    wv, bk = p.varpi, p.beta * p.kappa
    taus = np.linspace(c.start, c.end, n + 1)
    impulse = bk / wv * np.abs(np.diff(np.cos(wv * taus)))
    head = wv * np.cos(wv * taus)
    s, v = 0.0, v0
    h = taus[1] - taus[0]
    for k in range(n):
        v_new = min(max(head[k + 1], v - impulse[k]), v + impulse[k])
        s += 0.5 * (v + v_new) * h
        v = v_new
    return s, v


@pytest.mark.parametrize(
    "params",
    [(0.9, 0.5, 0.4), (0.5, 1.5, 0.4), (1.5, 4.0, 1.0), (1.2, 0.1, 0.1)],
    ids=["slip-reverse", "stick", "stick-strong", "weak"],
)
@pytest.mark.parametrize("v0", [-2.0, -0.6, 0.0, 0.4, 2.0])
def test_contact_flow_matches_integration(params, v0):
    """Closed-form contact (slip/reverse/stick) vs Moreau time stepping (O(h), h ≈ 1e-4)."""
    varpi, beta, kappa = params
    p = ModelParams(varpi, 0.1, beta, kappa)
    c = rigid.Contact(2 * math.pi / varpi + 0.3, 3 * math.pi / varpi)
    s, v = rigid._contact_flow(c, 0.0, v0, p, None)
    s_num, v_num = _contact_numeric(c, v0, p)
    assert s == pytest.approx(s_num, abs=5e-4)
    assert v == pytest.approx(v_num, abs=5e-4)


def test_stick_exits_at_head_velocity():
    """With ϖ² ≤ βκ the slider sticks and leaves the contact at ζ' = ϖ cos π = −ϖ."""
    p = ModelParams(0.5, 0.1, 1.5, 0.4)
    log: list = []
    c = rigid.Contact(0.0, math.pi / 0.5)
    _, v = rigid._contact_flow(c, 0.0, 0.0, p, log)
    assert v == pytest.approx(-0.5, abs=1e-15)
    assert [e[1:] for e in log] == [
        ("contact_start", "free", "slip"),
        ("velocity_match", "slip", "stick"),
        ("contact_end", "stick", "free"),
    ]


@pytest.mark.parametrize("params", [(0.9, 0.5, 0.4), (1.0, 1.5, 0.4), (1.5, 4.0, 1.0)])
def test_periodic_is_limit_of_transient(params):
    """Fixed point of the velocity map = last Δs of a long exact transient."""
    varpi, beta, kappa = params
    p = ModelParams(varpi, 0.1, beta, kappa)
    per = rigid.rigid_periodic(p)
    assert per.success and per.status == "success"
    assert per.residual < 1e-13
    tr = rigid.rigid_simulate(p, 400)
    assert tr.delta_s[-1] == pytest.approx(per.delta_s, rel=1e-10)


def test_beyond_window_reports_no_contact():
    """ϖ = 2.2: impulsive hits only (docs/MODEL.md) -> status no_contact, not a number."""
    res = rigid.rigid_periodic(ModelParams(2.2, 0.1, 0.5, 0.4), max_cycles=60)
    assert not res.success
    assert res.status == "no_contact"
    assert "outside the window" in res.message
    assert res.mode is None


def test_simulate_counts_and_log():
    """Event log is time-ordered; counters match the log; cycles must be positive."""
    p = ModelParams(0.9, 0.1, 0.5, 0.4)
    tr = rigid.rigid_simulate(p, 5, log=True)
    taus = [e[0] for e in tr.events]
    assert taus == sorted(taus)
    assert tr.n_events == sum(1 for e in tr.events if e[1] != "velocity_match")
    assert len(tr.delta_s) == 5
    assert tr.s == pytest.approx(tr.delta_s.sum(), abs=1e-12)
    with pytest.raises(ValueError, match="cycles"):
        rigid.rigid_simulate(p, 0)


@settings(max_examples=40, deadline=None)
@given(
    varpi=st.floats(0.5, 1.99),
    beta=st.floats(0.05, 5.0),
    kappa=st.floats(0.05, 2.0),
)
def test_rigid_limit_always_pull(varpi, beta, kappa):
    """docs/MODEL.md: α → 0 (rigid tangential contact) always gives pull mode."""
    res = rigid.rigid_periodic(ModelParams(varpi, 1.0, beta, kappa))
    assert res.success, res.message
    assert res.delta_s < 0.0
    assert res.mode == "pull"
