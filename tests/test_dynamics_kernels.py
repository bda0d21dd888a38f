"""The compiled kernel (betvdesign/dynamics/kernels.py) against the pure-Python path
(source: a second implementation of the same algorithm, solver._Cycle with the event
classes of events.py; the kernel is written to perform the same floating-point
operations, so the two agree to the last bit on this machine and to round-off anywhere),
and the kernel's own source run as plain Python (NUMBA_DISABLE_JIT=1, a subprocess)."""

import json
import os
import subprocess
import sys

import numpy as np
import pytest
from conftest import WINDOW_SETS
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from betvdesign.dynamics import kernels, periodic_orbit, simulate, solver
from betvdesign.dynamics.flows import PhaseConstants
from betvdesign.dynamics.vertical import VerticalSchedule
from betvdesign.params import ModelParams

#: the window designs (tests/conftest.py) plus the named benchmark ones
DESIGNS = [
    *WINDOW_SETS,
    ModelParams(0.9, 0.1, 0.9, 0.4),
    ModelParams(1.5, 1.0, 0.2, 0.2),
    ModelParams(1.2, 0.5, 1.0, 0.4),
    ModelParams(0.9, 0.1, 9.0, 0.4),
    ModelParams(1.0, 2.0, 1.0, 0.4),
    ModelParams(0.34, 0.1, 9.09, 0.4),  # multi-impact (shin2004's computed ϖ)
]


def _both(p, cycles, monkeypatch, **kw):
    """(kernel run, pure-Python run) of the same transient."""
    a = simulate(p, cycles, log_events=False, **kw)
    with monkeypatch.context() as mp:
        mp.setenv("BETV_KERNELS", "0")
        b = simulate(p, cycles, log_events=False, **kw)
    return a, b


def _assert_same(a, b):
    scale = max(1.0, float(np.abs(b.section).max()))
    np.testing.assert_allclose(a.section, b.section, rtol=0, atol=1e-13 * scale)
    assert (a.status, a.n_cycles, a.n_events) == (b.status, b.n_cycles, b.n_events)
    assert a.n_root_evals == b.n_root_evals


def test_designs_cover_both_modes_of_the_events():
    """The window designs include phases near resonance (the events' slow mode) and
    away from it (fast mode), so the comparisons below exercise both."""
    flags = (kernels.KC_SLIP + 8, kernels.KC_REV + 8, kernels.KC_STICK + 12)
    fast = [min(kernels.constants(PhaseConstants.from_params(p))[list(flags)]) for p in DESIGNS]
    assert 0.0 in fast and 1.0 in fast


@pytest.mark.parametrize("p", DESIGNS, ids=lambda p: f"{p.varpi:.2f}-{p.alpha:.2g}")
def test_kernel_matches_python_path(p, monkeypatch):
    a, b = _both(p, 150, monkeypatch)
    assert (a.engine, b.engine) == ("compiled", "python")
    assert a.success, a.message
    _assert_same(a, b)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    st.builds(
        ModelParams,
        varpi=st.floats(0.3, 2.2),
        alpha=st.floats(0.02, 4.0),
        beta=st.floats(0.05, 20.0),
        kappa=st.floats(0.02, 1.0),
    ).filter(lambda p: abs(p.alpha * p.kappa * (1 + p.beta) - 1) > 1e-9),
    st.lists(st.floats(-2.0, 2.0), min_size=4, max_size=4),
)
def test_kernel_matches_python_path_random(p, st4):
    """Random designs (inside and outside the window) from random tangential states."""
    state0 = (0.0, 0.0, *st4)
    a = simulate(p, 40, log_events=False, state0=state0)
    os.environ["BETV_KERNELS"] = "0"
    try:
        b = simulate(p, 40, log_events=False, state0=state0)
    finally:
        del os.environ["BETV_KERNELS"]
    _assert_same(a, b)


def test_periodic_orbit_same_on_both_paths(monkeypatch):
    for p in DESIGNS[:6]:
        a = periodic_orbit(p)
        with monkeypatch.context() as mp:
            mp.setenv("BETV_KERNELS", "0")
            b = periodic_orbit(p)
        assert a.status == b.status == "success", (a.message, b.message)
        assert a.delta_s == pytest.approx(b.delta_s, rel=1e-12, abs=1e-14)
        assert a.n_cycles == b.n_cycles and a.n_root_evals == b.n_root_evals


@pytest.mark.parametrize(
    "p",
    [
        ModelParams(1.0, 0.5, 1.0, 0.4),  # ϖ = 1: vertical free flight resonant
        ModelParams(1.25, 0.64, 1.0, 0.4),  # αϖ² = 1 exactly (no split: energy bounds)
        ModelParams(1.25, 0.32, 1.0, 0.4),  # α(1+1/β)ϖ² = 1: stick resonant
        ModelParams(1.25, 0.62, 1.0, 0.4),  # |1 − αϖ²| < 0.1: near resonance
        ModelParams(1.2, 0.33, 1.0, 0.4),  # stick phase near resonance
    ],
    ids=["varpi1", "slip-res", "stick-res", "slip-near", "stick-near"],
)
def test_kernel_matches_python_path_at_resonances(p, monkeypatch):
    """Near and at tangential resonance the events switch to the uniform closed form
    with energy-growth bounds; the kernel compiles that mode too."""
    k = PhaseConstants.from_params(p)
    kernels.constants(k)
    a, b = _both(p, 60, monkeypatch)
    assert a.engine == "compiled"
    _assert_same(a, b)


def test_event_log_and_dense_output_use_the_python_path():
    p = DESIGNS[0]
    assert simulate(p, 3).engine == "python"
    assert simulate(p, 3, log_events=False, dense=True).engine == "python"


def test_chatter_fails_loudly_on_both_paths(monkeypatch):
    """b = 1 to round-off (the Zeno point): the same failure, the same message, the same
    rows kept, compiled or not (tests/test_dynamics_solver.py for the logged run)."""
    p = ModelParams(1.5, 0.5, 1.0, 0.9999999999999999)
    a, b = _both(p, 4, monkeypatch)
    assert a.engine == "compiled"
    assert a.status == b.status == "failed"
    assert "chatters" in a.message and a.message == b.message
    _assert_same(a, b)
    assert np.all(np.isfinite(a.section))


class _StubKernel:
    """A kernel module whose run_cycles reports the given failure code in cycle 2."""

    OK, SEARCH_FAILED, CHATTER, NON_FINITE = (
        kernels.OK,
        kernels.SEARCH_FAILED,
        kernels.CHATTER,
        kernels.NON_FINITE,
    )

    def __init__(self, code, a=0.0, b=0):
        self.code, self.a, self.b = code, a, b

    def run_cycles(self, kc, tcs, nimp, z, zd, s, sd, rows, check_finite):
        if rows.shape[0]:
            rows[:3] = 0.0
        return self.code, 2, 5, 7, self.a, self.b, z, zd, s, sd


@pytest.mark.parametrize(
    "code,a,b,expect",
    [
        (kernels.SEARCH_FAILED, 0.5, 0, "event search did not terminate"),
        (kernels.CHATTER, 0.25, 1001, "1001 switches"),
        (kernels.NON_FINITE, 0.0, 0, "non-finite state in cycle 2"),
    ],
)
def test_kernel_failure_codes_become_cycle_failures(code, a, b, expect):
    """Every failure the kernel can report reaches the user as the Python path's message,
    naming the cycle; no failure passes as a result."""
    p = DESIGNS[0]
    k = PhaseConstants.from_params(p)
    cyc = solver._Cycle(k, VerticalSchedule(p.varpi), None, None)
    assert cyc.engine == "compiled"
    cyc._kern = _StubKernel(code, a, b)
    rows = np.full((6, 4), np.nan)
    with pytest.raises(solver.CycleFailure, match=expect) as info:
        cyc.run_many(0, 5, 0.0, 0.0, 0.0, 0.0, rows)
    assert info.value.cycle == 2
    assert np.all(rows[:3] == 0.0) and np.all(np.isnan(rows[3:]))


_SCRIPT = """
import json, sys
from betvdesign.dynamics import simulate
from betvdesign.params import ModelParams
out = []
for v in json.loads(sys.argv[1]):
    tr = simulate(ModelParams(*v), 12, log_events=False)
    out.append([tr.engine, tr.section.tolist(), tr.n_events, tr.n_root_evals])
print(json.dumps(out))
"""


def test_kernel_source_runs_as_plain_python():
    """NUMBA_DISABLE_JIT=1: the kernel module runs uncompiled (the pure-Python path of
    the kernel itself) and gives the compiled kernel's numbers."""
    picks = DESIGNS[:3] + DESIGNS[-1:]
    args = [[p.varpi, p.alpha, p.beta, p.kappa] for p in picks]
    env = dict(os.environ, NUMBA_DISABLE_JIT="1")
    env.pop("BETV_KERNELS", None)
    res = subprocess.run(
        [sys.executable, "-c", _SCRIPT, json.dumps(args)],
        capture_output=True,
        text=True,
        env=env,
        timeout=300,
    )
    assert res.returncode == 0, res.stderr
    for p, (engine, section, n_ev, n_re) in zip(picks, json.loads(res.stdout), strict=True):
        tr = simulate(p, 12, log_events=False)
        assert engine == "compiled"
        scale = max(1.0, float(np.abs(tr.section).max()))
        np.testing.assert_allclose(np.array(section), tr.section, rtol=0, atol=1e-13 * scale)
        assert (n_ev, n_re) == (tr.n_events, tr.n_root_evals)


def test_cache_dir_is_per_source(tmp_path, monkeypatch):
    """Compiled code is cached under the user's cache, in a directory named by a hash of
    the sources it was compiled from (an edited helper cannot run stale)."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    d = kernels._cache_dir()
    assert d.startswith(str(tmp_path / "betvdesign" / "numba"))
    assert len(os.path.basename(d)) == 16 and d == kernels._cache_dir()
    int(os.path.basename(d), 16)  # a hex digest


def test_unusable_numba_falls_back_loudly(monkeypatch):
    """When the kernel module cannot be imported (numba missing, no writable cache) the
    solver warns, naming the cause, and runs the pure-Python path: same numbers."""
    import builtins

    real_import = builtins.__import__

    def fake_import(name, globals=None, locals=None, fromlist=(), level=0):
        if name == "betvdesign.dynamics" and fromlist and "kernels" in fromlist:
            raise ImportError("No module named 'numba'")
        return real_import(name, globals, locals, fromlist, level)

    solver._import_kernels.cache_clear()
    monkeypatch.setattr(builtins, "__import__", fake_import)
    try:
        with pytest.warns(RuntimeWarning, match="compiled kernels unavailable.*numba"):
            tr = simulate(DESIGNS[0], 5, log_events=False)
    finally:
        monkeypatch.undo()
        solver._import_kernels.cache_clear()
    assert tr.engine == "python" and tr.success
    assert simulate(DESIGNS[0], 5, log_events=False).engine == "compiled"
