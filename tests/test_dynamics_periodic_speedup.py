"""Accelerated start of the periodic solve (Anderson mixing + slider-velocity bracket).

Sources: long brute-force iteration from rest (a second method: n cycles with
|μ|maxⁿ < 1e-14) for the Δs and section state of the hard designs near ϖ → 2; the
unaccelerated solver (brute force + Newton only, the fallback path, by setting the
acceleration budget to 0) for the Floquet moduli, period and counters; the model's
necessary condition for a slider orbit (MODEL.md "Contact": a net-zero slider impulse
per cycle needs the friction to change sign or stick within the contact) for the
round-off "fixed points" at huge |s'| that the acceleration must never hand over.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from betvdesign.dynamics import contact, periodic_orbit, shooting, simulate
from betvdesign.dynamics.flows import phase_table
from betvdesign.dynamics.vertical import VerticalSchedule
from betvdesign.model.params import ModelParams

#: Window designs (benchmarks/bench_solver.py draw, seed 20041) whose transient from rest
#: takes hundreds to ~10⁵ cycles (near ϖ → 2).
HARD = {
    "w14": ModelParams(
        1.9154180469268849, 0.20382786257394497, 0.14569786872377327, 0.1447646069398345
    ),
    "w12": ModelParams(
        1.8711431350358352, 0.7328458411511358, 3.935443208849082, 0.1124640256281036
    ),
    "w13": ModelParams(
        1.7377800638661298, 0.13817201431889722, 2.3880965745560054, 0.08831371547706637
    ),
    "w00": ModelParams(
        1.8085018435162556, 1.8285564459679067, 0.23820580746354814, 0.30567585044676665
    ),
}


def _unaccelerated(p: ModelParams, monkeypatch: pytest.MonkeyPatch):
    with monkeypatch.context() as m:
        m.setattr(shooting, "ANDERSON_BUDGET", 0)
        return periodic_orbit(p)


@pytest.mark.parametrize("name", list(HARD))
def test_hard_designs_match_long_brute_force(name):
    """Δs and section state equal those of brute force from rest: the transient (w14: s'
    drifts ~8.5e-5 per cycle to the orbit's −7.56, ~95 000 cycles; the others leave the
    one-way-slip region within ~2000) plus n with |μ|maxⁿ < 1e-14."""
    p = HARD[name]
    po = periodic_orbit(p)
    assert po.success and po.stable and po.residual <= 1e-10, po.message
    n = (100_000 if name == "w14" else 3000) + int(math.log(1e-14) / math.log(po.floquet_moduli[0]))
    tr = simulate(p, n, log_events=False)
    assert tr.success
    assert abs(tr.delta_s[-1] - po.delta_s) <= 1e-9
    assert np.allclose(tr.section[-1, [2, 3, 5]], po.state[[2, 3, 5]], atol=1e-9)


@pytest.mark.parametrize("name", list(HARD))
def test_same_orbit_as_the_fallback_in_fewer_cycles(name, monkeypatch):
    """The fallback (brute force + Newton, no acceleration) finds the same orbit, period and
    Floquet moduli (finite differences at round-off-close points: ≤ 1e-7), in more cycles."""
    p = HARD[name]
    fast, slow = periodic_orbit(p), _unaccelerated(p, monkeypatch)
    assert fast.success and slow.success
    assert fast.period_cycles == slow.period_cycles == 1
    assert abs(fast.delta_s - slow.delta_s) <= 1e-11
    assert np.allclose(fast.floquet_moduli, slow.floquet_moduli, atol=1e-7)
    assert fast.n_cycles < slow.n_cycles
    assert fast.transient_cycles < slow.transient_cycles


def _shot(p: ModelParams) -> tuple:
    """The one-cycle section map's arguments (:data:`shooting.SHOT`) of a period-1 design."""
    vs = VerticalSchedule(p.varpi, horizon=1000)
    assert vs.period == 1 and vs.first_end is not None
    m0 = vs.first_end + 1
    return (
        phase_table(p),
        vs.table,
        vs.row(np.arange(m0, m0 + 1)),
        vs.impulsive,
        m0,
        np.empty((0, 4)),
        np.empty(0, contact.LOG_DTYPE),
        np.empty(0, contact.SEG_DTYPE),
        np.zeros(3, np.int64),
    )


def _phi(shot: tuple, x: np.ndarray) -> np.ndarray:
    ok, y, _ = shooting.section_map(*shot, np.asarray(x, dtype=float))
    assert ok
    return y


@pytest.mark.parametrize("name", ["w14", "w12"])
def test_round_off_fixed_points_exist_and_are_never_returned(name):
    """At |s'| = 1e15 a whole contact slips one way and the slider's increment
    (βκ∫sin ϖτ dτ ≠ 0) is below the ulp of s': Φ(x) − x passes the residual test though no
    orbit is there. The acceleration's start and the accepted orbit stay clear of it:
    ζ' − s' changes sign or sticks within the contact of the accepted orbit."""
    p = HARD[name]
    shot = _shot(p)
    po = periodic_orbit(p)
    x = po.state[[2, 3, 5]].copy()
    x[2] = 1e15
    for _ in range(3):  # (ζ, ζ') of the one-way-slip piece: Newton on them, s' held
        y = _phi(shot, x)
        J = np.empty((2, 2))
        for i in range(2):
            xp = x.copy()
            xp[i] += 1e-6
            J[:, i] = (_phi(shot, xp)[:2] - y[:2]) / 1e-6
        x[:2] += np.linalg.solve(J - np.eye(2), x[:2] - y[:2])
    assert np.max(np.abs(_phi(shot, x) - x)) <= 1e-10  # the trap is real
    start = po.state[[2, 3, 5]] + [0.5, 0.5, 0.5]
    found, start = shooting.anderson(*shot, start, shooting.ANDERSON_BUDGET)
    assert found and abs(start[2]) < 100.0
    # the accepted orbit: friction changes sign (or sticks) within its contact
    tr = simulate(p, 1, state0=po.state)
    kinds = {e.kind for e in tr.events} - {"impact", "separation", "impulsive"}
    assert kinds, [tuple(e) for e in tr.events]
    assert abs(po.state[5]) < 1e3


def test_unbounded_detection_and_not_driven_unchanged():
    """Exact resonance α·ϖ² = 1 (ακ < 2) still ends "unbounded"; beyond the window
    "not_driven" (the acceleration runs after both checks)."""
    assert periodic_orbit(ModelParams(1.0, 1.0, 0.5, 0.4)).status == "unbounded"
    assert periodic_orbit(ModelParams(2.3, 1.0, 1.0, 0.4)).status == "not_driven"


def test_the_compiled_search_runs_as_python():
    """NUMBA_DISABLE_JIT=1 runs the one compiled entry point (shooting.orbit: Anderson, the
    slider bracket, Newton, the Floquet multipliers by LAPACK dgeev) as plain Python: the
    same orbits, multipliers and counters as the compiled code, here bit for bit (numpy's
    and numba's dgeev, lstsq and gemv are the same LAPACK/BLAS calls)."""
    import json
    import os
    import subprocess
    import sys

    names = ["w13", "w12"]  # Anderson and the bracket run for both
    code = (
        "import json; from betvdesign.dynamics import periodic_orbit; "
        "from betvdesign.model.params import ModelParams as M; "
        f"ps = [M(*a) for a in {[list(HARD[n].as_dict().values())[:4] for n in names]!r}]; "
        "rs = [periodic_orbit(p) for p in ps]; "
        "print(json.dumps([[r.delta_s, r.state.tolist(), [[m.real, m.imag] for m in "
        "r.floquet.astype(complex)], r.n_cycles, r.n_events, r.n_newton] for r in rs]))"
    )
    env = dict(os.environ, NUMBA_DISABLE_JIT="1")
    res = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    for name, got in zip(names, json.loads(res.stdout), strict=True):
        po = periodic_orbit(HARD[name])
        mu = [[m.real, m.imag] for m in po.floquet.astype(complex)]
        assert got == [po.delta_s, po.state.tolist(), mu, po.n_cycles, po.n_events, po.n_newton]
