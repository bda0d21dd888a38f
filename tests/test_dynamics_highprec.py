"""Event times of the exact solver against high precision (mpmath, 40 digits).

Source: the phase equations of docs/MODEL.md solved by hand in closed form here (not the
solver's formulas: general solution y = P sin ϖτ + C cos w(τ − τ0) + D sin w(τ − τ0) of
y'' + w² y = F sin ϖτ in absolute time, and the secular one at ϖ = 1), evaluated in
40-digit arithmetic, and their event functions' roots found by ``mpmath.findroot``:
the head's contact-opening hit after a contact end (from ξ = ξ' = 0 at τ = π/ϖ), and
every ζ' = s' (end of slip) and stick-band exit of a few cycles, started from the
solver's own state at the start of the phase (the check is on the event time given the
phase's start, to round-off).
"""

from __future__ import annotations

import math
from itertools import pairwise

import mpmath as mp
import numpy as np
import pytest

from betvdesign.dynamics import simulate, vertical_motion
from betvdesign.model.params import ModelParams

mp.mp.dps = 40


def _gap_after_contact_end(varpi: float):
    """ξ(σ), σ = τ − π/ϖ, from ξ = ξ' = 0 at the contact end: ξ'' + ξ = sin ϖσ."""
    w = mp.mpf(varpi)
    if w == 1:
        return lambda s: (mp.sin(s) - s * mp.cos(s)) / 2
    return lambda s: (mp.sin(w * s) - w * mp.sin(s)) / (1 - w * w)


@pytest.mark.parametrize("varpi", [0.55, 0.8, 0.9, 1.0, 1.3, 1.7, 1.95])
def test_contact_opening_hit_phase(varpi):
    """The phase ϖτ of the hit that opens every periodic contact (single impact)."""
    v = vertical_motion(varpi)
    assert v.regime == "single-impact"
    gap = _gap_after_contact_end(varpi)
    # first sign change of the gap after the contact end, bracketed on a grid
    grid = np.linspace(1e-3, 4 * math.pi / varpi, 40001)
    vals = [float(gap(mp.mpf(x))) for x in grid[::10]]
    i = next(k for k, g in enumerate(vals) if g < 0)
    root = mp.findroot(gap, (mp.mpf(grid[10 * (i - 1)]), mp.mpf(grid[10 * i])), solver="anderson")
    phase = mp.fmod(mp.pi + mp.mpf(varpi) * root, 2 * mp.pi)
    assert v.contact_phase == pytest.approx(float(phase), rel=0, abs=1e-13)


def _phase_solution(p: ModelParams, phase: str, t0, z0, zd0, sd0):
    """(ζ(τ), ζ'(τ), s'(τ)) of one contact phase from (ζ, ζ', s') at τ0 (MODEL.md)."""
    al, be, ka, w = (mp.mpf(x) for x in (p.alpha, p.beta, p.kappa, p.varpi))
    a = al * (1 + 1 / be) if phase == "stick" else al
    c = {"slip": 1 - al * ka, "reverse": 1 + al * ka, "stick": mp.mpf(1)}[phase]
    ds = {"slip": be * ka, "reverse": -be * ka, "stick": None}[phase]
    w0 = 1 / mp.sqrt(a)
    F = c / a
    P = F / (w0 * w0 - w * w)
    C = z0 - P * mp.sin(w * t0)
    D = (zd0 - P * w * mp.cos(w * t0)) / w0

    def z(t):
        return P * mp.sin(w * t) + C * mp.cos(w0 * (t - t0)) + D * mp.sin(w0 * (t - t0))

    def zd(t):
        return P * w * mp.cos(w * t) + w0 * (D * mp.cos(w0 * (t - t0)) - C * mp.sin(w0 * (t - t0)))

    def sd(t):
        if ds is None:
            return zd(t)
        return sd0 + ds * (mp.cos(w * t0) - mp.cos(w * t)) / w

    return z, zd, sd


DESIGNS = [
    ModelParams(0.9, 0.1, 0.9, 0.4),
    ModelParams(1.5, 1.0, 0.2, 0.2),
    ModelParams(1.2, 0.5, 1.0, 0.4),
    ModelParams(0.6, 0.5, 1.5, 0.4),
    ModelParams(1.0, 2.0, 1.0, 0.4),
]


@pytest.mark.parametrize("p", DESIGNS, ids=lambda p: f"{p.varpi}-{p.alpha}-{p.beta}")
def test_slip_and_stick_event_times(p):
    """Each velocity-match and band-exit of 24 cycles at the 40-digit root of its event
    function, from the state where its phase began."""
    tr = simulate(p, 24, dense=True)
    ev = [e for e in tr.events if e.kind != "impulsive"]
    b = mp.mpf(p.alpha) * mp.mpf(p.kappa) * (1 + mp.mpf(p.beta))
    w = mp.mpf(p.varpi)
    checked = 0
    for start, end in pairwise(ev):
        if end.kind not in ("velocity-match", "band-exit") or start.phase_after == "free":
            continue
        phase = start.phase_after
        t0 = start.tau
        st = tr.sample(np.array([t0]))[0]
        z, zd, sd = _phase_solution(p, phase, mp.mpf(t0), st[2], st[3], st[5])
        if phase == "stick":
            q = 1 - b if end.phase_after == "slip" else 1 + b
            fns = (z, lambda t, q=q: q * mp.sin(w * t))
        else:
            fns = (zd, sd)
        root = mp.findroot(
            lambda t, fns=fns: fns[0](t) - fns[1](t), mp.mpf(end.tau), tol=mp.mpf(10) ** -35
        )
        assert abs(float(root) - end.tau) <= 1e-11 * max(1.0, end.tau), (start, end)
        checked += 1
    assert checked >= 3
