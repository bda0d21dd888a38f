"""Exact event-driven solver of the BETV impact/stick-slip model (unit-free).

docs/MODEL.md, "Dimensionless model". The vertical motion is computed once,
exactly (:mod:`vertical`); it fixes in every cycle the contact window
[t_c, π/ϖ] (local time t = τ − 2mπ/ϖ). Horizontally, free flight has no event
and is one closed-form step; a contact is a sequence of slip / reverse slip /
stick phases, each advanced in closed form (:mod:`flows`) to its first event
located with a certified search (:mod:`events`): ζ' = s' in slip, a stick-band
exit in stick, or the contact end at t = π/ϖ (known exactly).

Phase choice at a contact start and whenever ζ' = s' (:func:`decide_phase`):
the sign of ζ' − s' when it is not zero; otherwise the friction band
(1 − b) sin ϖτ ≤ ζ ≤ (1 + b) sin ϖτ, compared lexicographically on Taylor
coefficients under the stick flow, which also settles the limit sin ϖτ → 0⁺ at a
contact opening at τ = 0. Entering stick, the common velocity is the one that
conserves the momentum ζ' + s'/β (the round-off gap between ζ' and s' at the
event is removed without a momentum error).

Time is carried as (cycle m, local t ∈ [0, 2π/ϖ]) so that no phase loses digits
over 10⁵ cycles.

Two implementations of the cycle loop, one algorithm: :meth:`_Cycle.run` (pure Python,
with event log and dense output) and the compiled kernel :func:`kernels.run_cycles`
(numba), which :meth:`_Cycle.run_many` uses whenever only states are wanted
(``Trajectory.engine`` says which ran; tests/test_dynamics_kernels.py holds them equal).
"""

from __future__ import annotations

import bisect
import functools
import math
import os
import time
import warnings

import numpy as np

from betvdesign.dynamics.events import (
    EPS,
    SlipEvent,
    StickEvent,
    decide_phase_core,
    first_root,
    search_failure_message,
)
from betvdesign.dynamics.flows import (
    FREE,
    PHASE_NAMES,
    STICK,
    PhaseConstants,
    flow,
    oscillator,
)
from betvdesign.dynamics.result import Event, Trajectory
from betvdesign.dynamics.vertical import VerticalCycle, VerticalSchedule
from betvdesign.errors import ParameterError
from betvdesign.params import ModelParams

#: Zero-length phases in a row before a contact is declared chattering.
MAX_ZERO_LENGTH = 8
#: Phase switches within one contact before it is declared chattering (Zeno).
MAX_SWITCHES = 1000


class SolverFailure(RuntimeError):
    """A contact could not be advanced (chattering or a non-terminating event search)."""


class CycleFailure(SolverFailure):
    """Cycle ``cycle`` could not be advanced (:meth:`_Cycle.run_many`); the message says why."""

    def __init__(self, message: str, cycle: int):
        super().__init__(message)
        self.cycle = cycle


def chatter_message(tau: float, m: int, n_switch: int) -> str:
    """What a chattering contact (a Zeno point) at τ [-] in cycle m reports."""
    return (
        f"contact phases of (near) zero length repeat at τ = {tau:.12g} "
        f"(cycle {m}, {n_switch} switches in this contact): the stick/slip "
        "switching chatters (a Zeno point of the model); try other parameters"
    )


def _kernels():
    """The compiled kernel module, or None when switched off (``BETV_KERNELS=0``) or
    numba is missing (then the pure-Python path runs; results are the same)."""
    if os.environ.get("BETV_KERNELS", "1") == "0":
        return None
    return _import_kernels()


@functools.cache
def _import_kernels():
    """Import :mod:`kernels` once per process; None (with a warning naming the cause)
    when numba cannot be used here, e.g. not installed or no writable cache."""
    try:
        from betvdesign.dynamics import kernels
    except Exception as exc:  # any numba set-up failure: same results, slower
        warnings.warn(
            f"compiled kernels unavailable ({type(exc).__name__}: {exc}); "
            "the exact solver runs its pure-Python path (same results, slower)",
            RuntimeWarning,
            stacklevel=3,
        )
        return None
    return kernels


def decide_phase(
    k: PhaseConstants, z: float, zd: float, sd: float, sp: float, cp: float, on: int = -1
) -> int:
    """Contact phase at a contact start or at ζ' = s' (MODEL.md stick/slip rules):
    :func:`events.decide_phase_core` with k's constants.

    ``on``: the event just located (0: ζ' = s' in slip, 1: lower band edge, 2: upper
    band edge); that event function is zero by construction, whatever its round-off.
    """
    return decide_phase_core(k.a_stick, k.varpi, k.b, k.beta, z, zd, sd, sp, cp, on)


class _Cycle:
    """Advances the tangential state through whole cycles (no allocation per call)."""

    def __init__(
        self,
        k: PhaseConstants,
        vs: VerticalSchedule,
        log: list[Event] | None,
        segments: list | None,
    ):
        self.k = k
        self.vs = vs
        self.log = log
        self.segments = segments
        self.counter = [0]
        self.n_events = 0
        self.T = 2.0 * math.pi / k.varpi
        self.te = math.pi / k.varpi
        self._free_cache: dict[tuple[float, float], tuple[float, ...]] = {}
        #: compiled kernel and its constants, when it can serve (no log, no dense output)
        self._kern = _kernels() if log is None and segments is None else None
        self._kc = None if self._kern is None else self._kern.constants(k)
        self._sched: dict[tuple[int, int], tuple[np.ndarray, np.ndarray]] = {}
        self._norows = np.empty((0, 4))

    @property
    def engine(self) -> str:
        """ "compiled" when :meth:`run_many` uses the numba kernel, else "python"."""
        return "python" if self._kc is None else "compiled"

    def run_many(
        self,
        m0: int,
        n: int,
        z: float,
        zd: float,
        s: float,
        sd: float,
        rows: np.ndarray | None = None,
        check_finite: bool = True,
    ) -> tuple[float, float, float, float]:
        """State (ζ, ζ', s, s') after cycles m0..m0+n−1 from the state at m0's start.

        rows (n + 1, ≥ 4): receives in columns 0–3 the state at every cycle start and
        at the end. Raises :class:`CycleFailure` naming the cycle that failed (rows up
        to its start are filled). The compiled kernel runs when it can (see engine).
        """
        if self._kc is None:
            for j in range(n):
                m = m0 + j
                if rows is not None:
                    rows[j, :4] = (z, zd, s, sd)
                try:
                    z, zd, s, sd = self.run(m, z, zd, s, sd)
                except (SolverFailure, RuntimeError) as exc:
                    raise CycleFailure(str(exc), m) from exc
                if check_finite and (z - z) + (zd - zd) + (s - s) + (sd - sd) != 0.0:
                    raise CycleFailure(f"non-finite state in cycle {m}", m)
            if rows is not None:
                rows[n, :4] = (z, zd, s, sd)
            return z, zd, s, sd
        tcs, nimp = self._schedule(m0, n)
        buf = self._norows if rows is None else np.empty((n + 1, 4))
        kern = self._kern
        code, j, nev, evals, a, b, z, zd, s, sd = kern.run_cycles(
            self._kc, tcs, nimp, z, zd, s, sd, buf, check_finite
        )
        self.n_events += int(nev)
        self.counter[0] += int(evals)
        if rows is not None:
            rows[: j + 1, :4] = buf[: j + 1]
        if code == kern.OK:
            return z, zd, s, sd
        m = m0 + int(j)
        if code == kern.SEARCH_FAILED:
            msg = search_failure_message(a)
        elif code == kern.CHATTER:
            msg = chatter_message(m * self.T + a, m, int(b))
        else:
            msg = f"non-finite state in cycle {m}"
        raise CycleFailure(msg, m)

    def _schedule(self, m0: int, n: int) -> tuple[np.ndarray, np.ndarray]:
        """Contact-opening times (NaN: none) and impulsive-hit counts of cycles m0..m0+n−1."""
        key = (m0, n)
        got = self._sched.get(key)
        if got is None:
            got = self.vs.arrays(m0, n)[2:]
            if n <= 64:  # the periodic map's repeated calls; a long transient runs once
                self._sched[key] = got
        return got

    def _free(
        self, z: float, zd: float, s: float, sd: float, cp0: float, h: float
    ) -> tuple[float, float, float, float]:
        """flow(k, FREE, z, zd, s, sd, 0, cp0, h) for a forcing phase 0 or π (cp0 = ±1).

        Free flights start at the section or at a contact end and last a duration fixed
        by the (periodic) vertical motion: the oscillator's coefficients, which depend on
        h only, are computed once (:func:`flows.oscillator`, same operations).
        """
        key = (h, cp0)
        c = self._free_cache.get(key)
        if c is None:
            w0, F = self.k.w0[FREE], self.k.F[FREE]
            y0, v0, _, _ = oscillator(w0, self.k.varpi, F, 0.0, 0.0, 0.0, cp0, h)
            c = self._free_cache[key] = (math.cos(w0 * h), math.sin(w0 * h), w0, y0, v0)
        c0, s0, w0, A, B = c
        return z * c0 + zd / w0 * s0 + A, -z * w0 * s0 + zd * c0 + B, s + sd * h, sd

    def _event(self, m: int, t: float, kind: str, before: int, after: int) -> None:
        self.n_events += 1
        if self.log is not None:
            self.log.append(Event(m * self.T + t, kind, PHASE_NAMES[before], PHASE_NAMES[after]))

    def _seg(self, m: int, t0: float, t1: float, phase: int, st: tuple, sp: float, cp: float):
        if self.segments is not None:
            self.segments.append((m * self.T + t0, m, t0, t1, phase, st, sp, cp))

    def run(
        self, m: int, z: float, zd: float, s: float, sd: float, vc: VerticalCycle | None = None
    ) -> tuple[float, ...]:
        """State (ζ, ζ', s, s') at the end of cycle m from its start (vc: vs.cycle(m))."""
        k, te, T = self.k, self.te, self.T
        dense, logging = self.segments is not None, self.log is not None
        if vc is None:
            vc = self.vs.cycle(m)
        tc = vc.contact_start
        if logging:  # impulsive hits before the contact, in time order
            for ti in vc.impulsive:
                if tc is None or ti < tc:
                    self._event(m, ti, "impulsive", FREE, FREE)
        elif vc.impulsive:  # counted all the same (the whole cycle's, logged or not)
            self.n_events += len(vc.impulsive)
        if tc is None:
            if dense:
                self._seg(m, 0.0, T, FREE, (z, zd, s, sd), 0.0, 1.0)
            return self._free(z, zd, s, sd, 1.0, T)
        if tc > 0.0:
            if dense:
                self._seg(m, 0.0, tc, FREE, (z, zd, s, sd), 0.0, 1.0)
            z, zd, s, sd = self._free(z, zd, s, sd, 1.0, tc)
            sp, cp = math.sin(k.varpi * tc), math.cos(k.varpi * tc)
        else:
            sp, cp = 0.0, 1.0
        t = tc
        phase = decide_phase(k, z, zd, sd, sp, cp)
        if phase == STICK:
            zd = sd = (zd + sd / k.beta) / (1.0 + 1.0 / k.beta)
        if logging:
            self._event(m, t, "impact", FREE, phase)
        else:
            self.n_events += 1  # counted all the same
        zero_len = 0
        n_switch = 0
        on_edge = -1
        from_edge = False
        while True:
            H = te - t
            if phase == STICK:
                ev = StickEvent(k, z, zd, sp, cp, H, on_edge)
                on_edge = -1
            else:
                ev = SlipEvent(k, phase, z, zd, s, sd, sp, cp, H, from_edge)
            from_edge = False
            res = first_root(ev, H, self.counter)
            h = H if res is None else res[0]
            if dense:
                self._seg(m, t, t + h, phase, (z, zd, s, sd), sp, cp)
            z, zd, s, sd, _, _ = flow(k, phase, z, zd, s, sd, sp, cp, h)
            if res is None:
                break
            t += h
            sp, cp = math.sin(k.varpi * t), math.cos(k.varpi * t)
            new = decide_phase(k, z, zd, sd, sp, cp, 1 + res[1] if phase == STICK else 0)
            kind = "band-exit" if phase == STICK else "velocity-match"
            if phase != STICK:  # ζ' = s' exactly (momentum-conserving common velocity)
                zd = sd = (zd + sd / k.beta) / (1.0 + 1.0 / k.beta)
            elif new == STICK:
                on_edge = res[1]
            else:
                from_edge = True
            if logging:
                self._event(m, t, kind, phase, new)
            else:
                self.n_events += 1
            zero_len = zero_len + 1 if h <= 64.0 * EPS * max(1.0, t) else 0
            n_switch += 1
            if zero_len > MAX_ZERO_LENGTH or n_switch > MAX_SWITCHES:
                raise SolverFailure(chatter_message(m * T + t, m, n_switch))
            phase = new
        if logging:
            self._event(m, te, "separation", phase, FREE)
            for ti in vc.impulsive:  # impulsive hits after the separation
                if ti > te:
                    self._event(m, ti, "impulsive", FREE, FREE)
        else:
            self.n_events += 1
        if dense:
            self._seg(m, te, T, FREE, (z, zd, s, sd), 0.0, -1.0)
        return self._free(z, zd, s, sd, -1.0, te)


def _check_state0(state0: object) -> tuple[float, ...]:
    if state0 is None:
        return (0.0,) * 6
    try:
        arr = np.asarray(state0, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise ParameterError(f"state0 must be 6 numbers, got {state0!r}") from None
    if arr.shape != (6,) or not np.all(np.isfinite(arr)):
        raise ParameterError(f"state0 must be 6 finite numbers (ξ, ξ', ζ, ζ', s, s'), got {arr}")
    if arr[0] < 0.0:
        raise ParameterError(f"state0: the gap ξ must be ≥ 0, got {arr[0]}")
    return tuple(float(x) for x in arr)


def _check_cycles(cycles: object) -> int:
    if isinstance(cycles, bool) or not isinstance(cycles, (int, np.integer)) or cycles < 0:
        raise ParameterError(f"cycles must be a non-negative integer, got {cycles!r}")
    return int(cycles)


def simulate(
    p: ModelParams,
    cycles: int,
    *,
    dense: bool = False,
    state0: object = None,
    log_events: bool = True,
) -> Trajectory:
    """Exact transient of ``cycles`` actuation cycles from ``state0`` at τ = 0.

    p: parameters; state0: (ξ, ξ', ζ, ζ', s, s') at τ = 0, default all zero (MODEL.md
    "Initial state"); dense: keep the phase segments for :meth:`Trajectory.sample`;
    log_events: keep the event log (counters are kept either way).
    """
    if not isinstance(p, ModelParams):
        raise ParameterError(f"p must be a ModelParams, got {type(p).__name__}")
    n = _check_cycles(cycles)
    st = _check_state0(state0)
    t0 = time.perf_counter()
    k = PhaseConstants.from_params(p)
    vs = VerticalSchedule(p.varpi, st[0], st[1], horizon=max(1000, n + 1))
    log: list[Event] | None = [] if log_events else None
    segs: list | None = [] if dense else None
    cyc = _Cycle(k, vs, log, segs)
    section = np.empty((n + 1, 6))
    z, zd, s, sd = st[2:]
    status, message, done = "success", f"{n} cycles simulated", n
    try:
        cyc.run_many(0, n, z, zd, s, sd, section[:, 2:])
    except CycleFailure as exc:
        status, message, done = "failed", f"{exc}; results up to cycle {exc.cycle} kept", exc.cycle
        section = section[: done + 1]
    section[:, 0], section[:, 1] = vs.arrays(0, done + 1)[:2]
    delta = np.diff(section[:, 4])
    sampler = _make_sampler(k, vs, segs) if dense else None
    return Trajectory(
        params=p,
        solver="exact",
        status=status,
        success=status == "success",
        message=message,
        s=float(section[-1, 4]),
        delta_s=delta,
        section=section,
        events=log or [],
        n_events=cyc.n_events,
        n_cycles=done,
        n_root_evals=cyc.counter[0] + vs.n_root_evals,
        elapsed_s=time.perf_counter() - t0,
        impacts_per_cycle=vs.hits_per_cycle(),
        contact_fraction=vs.contact_fraction(),
        phases=[(sg[0], sg[0] + sg[3] - sg[2], PHASE_NAMES[sg[4]]) for sg in segs or []],
        engine=cyc.engine,
        _sampler=sampler,
    )


def _make_sampler(k: PhaseConstants, vs: VerticalSchedule, segs: list):
    starts = [sg[0] for sg in segs]
    T = 2.0 * math.pi / k.varpi

    def sample(tau: np.ndarray) -> np.ndarray:
        out = np.empty((tau.size, 6))
        for j, ta in enumerate(tau):
            i = bisect.bisect_right(starts, ta) - 1
            if i < 0 or ta > segs[-1][0] + (segs[-1][3] - segs[-1][2]) * (1 + 1e-12):
                raise ValueError(f"τ = {ta} outside the simulated span")
            _, m, t0, _, phase, (z, zd, s, sd), sp, cp = segs[i]
            h = ta - m * T - t0
            zn, zdn, sn, sdn, _, _ = flow(k, phase, z, zd, s, sd, sp, cp, h)
            xi, xid = vs.cycle(m).gap(k.varpi, t0 + h)
            out[j] = (xi, xid, zn, zdn, sn, sdn)
        return out

    return sample
