"""Vertical regime diagram (sources: interval bookkeeping on hand-made rows; the
closed-form free flight after a contact end as a second method; MODEL.md regimes)."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from betvdesign.studies.regime import intervals, regime_point, run_regime, summarise


def _rows(labels):
    return [
        {"key": i, "varpi": 0.1 * (i + 1), "label": lab, "status": "success", "message": ""}
        for i, lab in enumerate(labels)
    ]


def test_intervals_are_contiguous_runs_in_varpi_order():
    rows = _rows(["multi-hit", "multi-hit", "period-1", "period-1", "period-1", "impulsive"])
    got = [(i.label, round(i.lo, 9), round(i.hi, 9), i.points) for i in intervals(rows[::-1])]
    assert got == [
        ("multi-hit", 0.1, 0.2, 2),
        ("period-1", 0.3, 0.5, 3),
        ("impulsive", 0.6, 0.6, 1),
    ]
    s = summarise(rows)
    assert s["counts"] == {"multi-hit": 2, "period-1": 3, "impulsive": 1}
    assert s["errors"] == []


# -- with the exact vertical solver ------------------------------------------------


def _first_hit_phase(varpi: float) -> float:
    """Second method: free flight from rest at the contact end (phase π) in closed form,
    ξ(t') = (sin ϖt' − ϖ sin t')/(1 − ϖ²); the first root located on a fine scan and
    refined by brentq. Returns the hit's phase ϖτ mod 2π."""
    xi = lambda t: (np.sin(varpi * t) - varpi * np.sin(t)) / (1.0 - varpi**2)  # noqa: E731
    ts = np.linspace(1e-2, 3.0 * math.pi / varpi, 400_001)  # ξ ≈ ϖt³/6 > 0 before
    v = xi(ts)
    i = np.flatnonzero(np.sign(v[1:]) != np.sign(v[:-1]))[0]
    t_hit = brentq(xi, ts[i], ts[i + 1], xtol=1e-15)
    return (math.pi + varpi * t_hit) % (2.0 * math.pi)


@pytest.mark.parametrize("varpi", [0.3, 0.8, 1.5, 1.9])
def test_window_is_period_one_with_the_closed_form_contact_fraction(varpi):
    """Inside 0.5 ≤ ϖ < 2 (and at 0.3): one hit per cycle; contact lasts from the hit to
    phase π, so the contact fraction is (π − φ_hit)/(2π)."""
    phase = _first_hit_phase(varpi)
    assert 0.0 <= phase <= math.pi  # hit with sin ϖτ ≥ 0: a contact starts
    row = regime_point({"key": 0, "varpi": varpi, "max_cycles": 200})
    assert row["label"] == "period-1" and row["period_cycles"] == 1
    assert row["contact_fraction"] == pytest.approx((math.pi - phase) / (2 * math.pi), abs=1e-9)


def test_small_varpi_hit_in_tension_gives_several_hits_per_cycle():
    """ϖ = 0.4: the closed-form first hit after the contact end falls where sin ϖτ < 0, so it
    is impulsive and the head hits again before contact: several hits per cycle."""
    phase = _first_hit_phase(0.4)
    assert math.pi < phase < 2 * math.pi
    row = regime_point({"key": 0, "varpi": 0.4, "max_cycles": 200})
    assert row["label"] == "multi-hit" and row["hits_per_cycle"] >= 2
    assert row["impulsive_per_cycle"] >= 1


def _hits_from_rest(varpi: float, cycles: int) -> tuple[list[float], bool]:
    """Second method, every hit by hand from MODEL.md over ``cycles``: the first contact
    ends at τ = π/ϖ; each flight starts from ξ = ξ' = 0 at τ0 (a contact end, or a hit in
    tension: ξ' → 0 and the head lifts off at once), so ξ(τ0 + t) = [sin ϖτ0·cos t +
    ϖ cos ϖτ0·sin t − sin ϖ(τ0 + t)]/(1 − ϖ²); its first zero (fine scan, brentq) is the
    next hit. Returns the hit times and whether any hit opened a contact (sin ϖτ ≥ 0)."""
    w = varpi
    period = 2 * math.pi / w
    tau, hits = math.pi / w, []
    ts = np.linspace(1e-3, 4 * period, 40_001)
    while tau < cycles * period:
        a, b = math.sin(w * tau) / (1 - w * w), w * math.cos(w * tau) / (1 - w * w)

        def xi(t, tau=tau, a=a, b=b):
            return a * np.cos(t) + b * np.sin(t) - np.sin(w * (tau + t)) / (1 - w * w)

        v = xi(ts)
        assert v[0] > 0
        i = int(np.flatnonzero(v < 0)[0])
        tau += brentq(xi, ts[i - 1], ts[i], xtol=1e-14)
        hits.append(tau)
        if math.sin(w * tau) >= 0:
            return hits, True
    return hits, False


@pytest.mark.parametrize("varpi", [2.1, 2.3, 2.5])
def test_between_2_and_2_6_hits_are_impulsive(varpi):
    """MODEL.md: beyond ϖ ≈ 2, up to about 2.6, the hits are impulsive (no contact): over
    300 cycles from rest, every hit worked out by hand lands where sin ϖτ < 0, one per
    cycle once settled, as the regime study says."""
    hits, contact = _hits_from_rest(varpi, 300)
    assert not contact
    period = 2 * math.pi / varpi
    late = sum(100 * period <= t < 300 * period for t in hits) / 200
    row = regime_point({"key": 0, "varpi": varpi, "max_cycles": 200})
    assert row["label"] == "impulsive"
    assert row["contact_fraction"] == 0.0
    assert row["hits_per_cycle"] == row["impulsive_per_cycle"] == pytest.approx(late, abs=0.01)


def test_diagram_reports_the_window_and_higher_regimes_as_intervals():
    run, s = run_regime(np.round(np.arange(0.1, 3.51, 0.1), 12), max_cycles=200)
    labels = {iv["label"] for iv in s["overview"]}
    assert {"period-1", "impulsive", "period-2"} <= labels
    window = next(iv for iv in s["overview"] if iv["from"] <= 1.0 <= iv["to"])
    assert window["label"] == "period-1" and window["from"] <= 0.5 and window["to"] >= 1.9
    assert sum(iv["points"] for iv in s["intervals"]) == len(run.rows) == 35
    assert s["errors"] == []
