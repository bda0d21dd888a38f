"""Exact event-driven solver and periodic shooting (sources: the model's own rules in
docs/MODEL.md, long brute-force iteration as a second method for the periodic state,
and the α → 0 design knowledge "rigid tangential contact always pulls")."""

import math

import numpy as np
import pytest

from betvdesign.dynamics import periodic_orbit, simulate
from betvdesign.dynamics.contact import decide_phase
from betvdesign.dynamics.flows import SLIP, STICK, phase_table
from betvdesign.errors import ParameterError
from betvdesign.model.params import ModelParams

PULL = ModelParams(1.2, 0.5, 1.0, 0.4)
PUSH = ModelParams(1.5, 1.0, 0.2, 0.2)


def test_simulate_result_contract():
    tr = simulate(PULL, 20)
    assert tr.success and tr.status == "success"
    assert tr.n_cycles == 20 and tr.section.shape == (21, 6) and tr.delta_s.shape == (20,)
    assert tr.s == pytest.approx(tr.section[0, 4] + tr.delta_s.sum(), abs=1e-12)
    assert tr.n_events == len(tr.events) > 0 and tr.n_root_evals > 0 and tr.elapsed_s > 0
    kinds = {e.kind for e in tr.events}
    assert {"impact", "separation"} <= kinds
    assert tr.events[0].tau == 0.0 and tr.events[0].kind == "impact"


def test_initial_contact_phase_from_the_band_limit():
    """At τ = 0 (sin = 0, state at rest) the band is decided on first derivatives:
    ζ' = 0 < (1 − b)ϖ → slip when b < 1; (1 − b)ϖ < 0 < (1 + b)ϖ → stick when b > 1."""
    k = phase_table(ModelParams(1.0, 0.5, 1.0, 0.4))[0]  # b = 0.4
    assert decide_phase(k, 0.0, 0.0, 0.0, 0.0, 1.0, -1) == SLIP
    k = phase_table(ModelParams(1.0, 2.0, 1.0, 0.4))[0]  # b = 1.6
    assert decide_phase(k, 0.0, 0.0, 0.0, 0.0, 1.0, -1) == STICK
    assert simulate(ModelParams(1.0, 2.0, 1.0, 0.4), 1).events[0].phase_after == "stick"


@pytest.mark.parametrize("p", [PULL, PUSH], ids=["pull", "push"])
def test_periodic_orbit_matches_long_brute_force(p):
    """Second method: brute-force iteration from rest, long enough for |μ|^n < 1e-14."""
    po = periodic_orbit(p)
    assert po.success, po.message
    assert po.residual <= 1e-10 and po.stable and po.period_cycles == 1
    n = int(math.log(1e-14) / math.log(po.floquet_moduli[0])) + 10
    tr = simulate(p, n, log_events=False)
    assert abs(tr.delta_s[-1] - po.delta_s) <= 1e-9
    assert np.allclose(tr.section[-1, [2, 3, 5]], po.state[[2, 3, 5]], atol=1e-9)


def test_periodic_modes_of_reference_designs():
    assert periodic_orbit(PULL).mode == "pull"
    assert periodic_orbit(PUSH).mode == "push"


@pytest.mark.parametrize("alpha", [1e-3, 1e-2])
def test_rigid_limit_pulls(alpha):
    """MODEL.md: α → 0 (rigid tangential contact) always gives pull mode."""
    po = periodic_orbit(ModelParams(1.5, alpha, 0.2, 0.2))
    assert po.success, po.message
    assert po.mode == "pull"


def test_not_driven_beyond_the_window():
    po = periodic_orbit(ModelParams(2.3, 1.0, 1.0, 0.4))
    assert not po.success and po.status == "not_driven"
    assert "not driven" in po.message


@pytest.mark.parametrize(
    "kwargs",
    [
        {"cycles": -1},
        {"cycles": 2.5},
        {"cycles": 3, "state0": [0, 0, 0, math.nan, 0, 0]},
        {"cycles": 3, "state0": [-1e-3, 0, 0, 0, 0, 0]},
        {"cycles": 3, "state0": [0, 0, 0]},
    ],
)
def test_bad_arguments_rejected(kwargs):
    with pytest.raises(ParameterError):
        simulate(PULL, **kwargs)


def test_bad_parameters_rejected():
    for bad in (0.0, -1.0, math.nan, math.inf):
        with pytest.raises(ParameterError, match="varpi"):
            simulate(ModelParams(bad, 1.0, 1.0, 1.0), 1)
    with pytest.raises(ParameterError):
        periodic_orbit(PULL, tol=-1.0)


def test_dense_output_hits_section_states():
    tr = simulate(PUSH, 4, dense=True)
    T = 2 * math.pi / PUSH.varpi
    st = tr.sample(np.arange(4) * T)
    assert np.allclose(st, tr.section[:4], atol=1e-12)
    with pytest.raises(ValueError):
        simulate(PUSH, 2).sample(1.0)


def test_minimal_period_and_trust_region():
    """A design near ϖ = 2 whose transient guess sits where s' is neutral (all reverse
    slip): shooting must still find the period-1 orbit (not report it as period 4), and
    agree with brute force."""
    p = ModelParams(1.8711431350358352, 0.7328458411511358, 3.935443208849082, 0.1124640256281036)
    po = periodic_orbit(p)
    assert po.success and po.period_cycles == 1, po.message
    # the transient leaves the all-reverse region only after ~10³ cycles: brute force 3000
    assert abs(simulate(p, 3000, log_events=False).delta_s[-1] - po.delta_s) <= 1e-9


def test_within_round_off_of_both_resonances():
    """ϖ = 1 − 1e-16 with α = 1: vertical and tangential free flight resonant to round-off;
    the event search must not use the split form there (second method: solve_ivp)."""
    from betvdesign.dynamics import reference

    p = ModelParams(0.9999999999999999, 1.0, 1.0, 1.0)
    ex = simulate(p, 4)
    rf = reference.simulate(p, 4, rtol=1e-12, atol=1e-13)
    assert ex.success and rf.success, ex.message
    assert abs(ex.s - rf.s) <= 1e-8 * max(1.0, abs(ex.s))


def test_band_edge_near_one_at_the_first_contact():
    """b = ακ(1+β) = 1 − 1e-5: at τ = 0 the lower band edge (1 − b) sin ϖτ is almost flat;
    the start from rest must slip cleanly, not chatter (MODEL.md initial state)."""
    tr = simulate(ModelParams(1.5, 0.5, 1.0, 0.99999), 4)
    assert tr.success, tr.message
    assert tr.events[0].phase_after == "slip"


def test_degenerate_band_fails_loudly():
    """b = 1 to round-off at τ = 0 is a Zeno point of the switching rules: the solver
    stops with a message, never a silent or NaN result."""
    tr = simulate(ModelParams(1.5, 0.5, 1.0, 0.9999999999999999), 4)
    assert not tr.success and tr.status == "failed" and "chatters" in tr.message
    assert np.all(np.isfinite(tr.section))


def test_degenerate_band_fails_the_periodic_orbit_with_the_transients_reason():
    """The compiled periodic search only knows that a contact could not be advanced; the
    answer still says why, in the words of the transient from rest (simulate) of the same
    cycles: status "failed", nothing counted as the periodic map's."""
    p = ModelParams(1.5, 0.5, 1.0, 0.9999999999999999)
    po = periodic_orbit(p)
    why = simulate(p, 4).message.split("; results up to")[0]
    assert po.status == "failed" and po.message == f"transient from rest failed: {why}"
    assert po.n_cycles == 0 and po.delta_s is None


def test_same_source_runs_as_python():
    """NUMBA_DISABLE_JIT=1 runs the kernels' source as plain Python (debugging, coverage):
    same numbers as the compiled code, to round-off."""
    import json
    import os
    import subprocess
    import sys

    code = (
        "import json; from betvdesign.dynamics import simulate; "
        "from betvdesign.model.params import ModelParams; "
        "tr = simulate(ModelParams(0.9, 0.1, 0.9, 0.4), 3, dense=True); "
        "print(json.dumps([tr.engine, tr.section.tolist(), tr.n_events]))"
    )
    env = dict(os.environ, NUMBA_DISABLE_JIT="1")
    res = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    engine, section, n_events = json.loads(res.stdout)
    tr = simulate(ModelParams(0.9, 0.1, 0.9, 0.4), 3)
    assert engine == "python" and tr.engine == "compiled" and n_events == tr.n_events
    np.testing.assert_allclose(section, tr.section, rtol=0, atol=1e-13)


def test_long_logs_and_dense_output_grow_their_buffers():
    """Thousands of events and segments (buffers grown while running): the log holds every
    counted event in time order, and dense output reproduces the sections at the end."""
    p = ModelParams(0.3401, 0.5, 0.5, 0.2)  # multi-impact: ~3 events per cycle
    n = 400
    tr = simulate(p, n, dense=True)
    assert tr.success and tr.n_events == len(tr.events) > 3 * n
    taus = [e.tau for e in tr.events]
    assert taus == sorted(taus)
    T = 2 * math.pi / p.varpi
    np.testing.assert_allclose(tr.sample(np.array([T * (n - 1)])), tr.section[[n - 1]], atol=1e-9)


def test_a_call_that_compiles_says_so_on_stderr(monkeypatch, capsys):
    """No silent compile: when a call compiles kernels (numba's cache misses grow while it
    runs), one line on stderr says what and how long; a call that compiles nothing is
    silent."""
    import time

    from betvdesign.dynamics import jit

    count = [0]
    monkeypatch.setattr(jit, "_misses", lambda: count[0])
    monkeypatch.setattr(jit, "_ready", set())

    def compiling():
        count[0] += 1
        time.sleep(0.6)
        return 7

    assert jit.compile_note("demo", compiling) == 7
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "compiling the solver kernels for demo" in err
    assert "done in" in err
    assert jit.compile_note("demo", lambda: 8) == 8  # loaded, nothing compiled
    assert capsys.readouterr().err == ""
