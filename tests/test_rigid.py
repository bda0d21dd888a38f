"""The α → 0 rigid-limit model (betvdesign.dynamics.rigid).

Sources: the free-flight closed form against scipy's solve_ivp on ξ'' + ξ = −sin ϖτ
(a second, independent method, including the resonance ϖ = 1); contact phases
against direct numerical integration of s'' = βκ sin ϖτ·sgn(ϖ cos ϖτ − s'); the
hit finder against a dense scan; the periodic state against a long transient (an
invariant of the fixed point); docs/MODEL.md's claim that α → 0 always gives pull
(hypothesis).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from betvdesign.dynamics import rigid
from betvdesign.params import ModelParams


@pytest.mark.parametrize("varpi", [0.5, 0.9, 1.0, 1.0 + 1e-9, 1.7, 3.0])
@pytest.mark.parametrize("phase0", [math.pi, 1.3 * math.pi])
def test_flight_closed_form_matches_ode(varpi, phase0):
    """Closed-form flight ξ(t), ξ'(t) vs solve_ivp (rtol 1e-12), also at ϖ = 1."""
    tau0 = phase0 / varpi
    f = rigid.Flight(tau0, varpi)
    t = np.linspace(0.0, 15.0, 301)
    sol = solve_ivp(
        lambda tt, y: [y[1], -y[0] - math.sin(varpi * (tau0 + tt))],
        (0.0, 15.0),
        [0.0, 0.0],
        t_eval=t,
        rtol=1e-12,
        atol=1e-14,
    )
    xi = np.array([f.xi(x) for x in t])
    dxi = np.array([f.dxi(x) for x in t])
    assert np.abs(xi - sol.y[0]).max() < 1e-9
    assert np.abs(dxi - sol.y[1]).max() < 1e-9


def test_flight_resonant_hand_value():
    """ϖ = 1 from τ₀ = π: ξ = (t/2)cos τ − (cos τ₀/2) sin t (secular term, by hand)."""
    f = rigid.Flight(math.pi, 1.0)
    for t in (0.3, 2.0, 7.5):
        assert f.xi(t) == pytest.approx(0.5 * t * math.cos(math.pi + t) + 0.5 * math.sin(t))


@pytest.mark.parametrize("varpi", [0.55, 0.8, 1.0, 1.6, 1.95, 2.3, 3.0])
def test_hits_match_dense_scan(varpi):
    """First hit = first sign change of ξ on a 1e-4 scan; none is missed before it."""
    f = rigid.Flight(math.pi / varpi, varpi)
    tau_hit, kind, _ = rigid.next_hit(f, horizon=60.0)
    t = np.arange(1e-3, tau_hit - f.tau0 + 0.01, 1e-4)
    xi = np.array([f.xi(x) for x in t])
    first_neg = t[np.argmax(xi <= 0.0)]
    assert tau_hit - f.tau0 == pytest.approx(first_neg, abs=2e-4)
    assert abs(f.xi(tau_hit - f.tau0)) < 1e-12
    expected = "contact" if math.sin(varpi * tau_hit) >= 0 else "impulsive"
    assert kind == expected


def test_window_edge_hit_is_a_contact_start():
    """ϖ = 0.5 (window edge): the head lands exactly at ϖτ = 2jπ; that is one contact
    start per cycle, not an impulsive hit followed by a contact."""
    cs, imp, _ = rigid.contact_schedule(0.5, 3 * 4 * math.pi)
    starts = [c.start * 0.5 / (2 * math.pi) for c in cs]
    assert starts[:3] == pytest.approx([0.0, 1.0, 2.0], abs=1e-9)
    assert imp == []


def test_degenerate_cubic_touch():
    """ϖ = 3 from τ₀ = π/3: ξ = sin³t / 2 (by hand), so ξ = ξ' = ξ'' = 0 at t = π.

    The hit at the triple root must be found there, not at a later crossing.
    """
    f = rigid.Flight(math.pi / 3.0, 3.0)
    for t in (0.4, 1.7, 2.9):
        assert f.xi(t) == pytest.approx(0.5 * math.sin(t) ** 3, abs=1e-15)
    tau, _, _ = rigid.next_hit(f, horizon=30.0)
    assert tau - f.tau0 == pytest.approx(math.pi, abs=1e-4)


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
    assert per.success and per.status == "ok"
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
