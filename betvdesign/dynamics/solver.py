"""Exact event-driven solver of the BETV impact/stick-slip model (unit-free).

docs/MODEL.md, "Dimensionless model". The vertical motion is computed once, exactly
(:mod:`vertical`); the tangential motion cycle by cycle by the compiled contact loop
(:func:`contact.run_cycles`, the only implementation of it), which fills the event log
and the dense-output segments when asked. Time is carried as (cycle m, local
t ∈ [0, 2π/ϖ]) so that no phase loses digits over 10⁵ cycles.
"""

from __future__ import annotations

import math
import time

import numpy as np

from betvdesign.dynamics import contact
from betvdesign.dynamics.flows import PHASE_NAMES, phase_table
from betvdesign.dynamics.inputs import check_cycles, check_state0
from betvdesign.dynamics.jit import compile_note, jit_enabled
from betvdesign.dynamics.result import Event, Trajectory
from betvdesign.dynamics.search import search_failure_message
from betvdesign.dynamics.vertical import VerticalSchedule
from betvdesign.errors import ParameterError
from betvdesign.model.params import ModelParams


class CycleFailure(RuntimeError):
    """Raised when a cycle cannot be advanced.

    Raised when a cycle cannot be advanced: a chattering contact (a Zeno point), a
    non-terminating event search or a non-finite state; the message says which.

    Parameters
    ----------
    message : str
        What failed and where.
    cycle : int
        The cycle that could not be advanced [-] (0-based; the ones before it are done).
    """

    def __init__(self, message: str, cycle: int):
        super().__init__(message)
        self.cycle = cycle


def chatter_message(tau: float, m: int, n_switch: int) -> str:
    """What a chattering contact (a Zeno point) reports.

    Parameters
    ----------
    tau : float
        Time of the chattering switches τ [-].
    m : int
        Its cycle [-].
    n_switch : int
        Phase switches counted in this contact [-].

    Returns
    -------
    str
        The message of the :class:`CycleFailure`.
    """
    return (
        f"contact phases of (near) zero length repeat at τ = {tau:.12g} "
        f"(cycle {m}, {n_switch} switches in this contact): the stick/slip "
        "switching chatters (a Zeno point of the model); try other parameters"
    )


class CycleRunner:
    """Advance the tangential state through whole cycles of one parameter set.

    Advances the tangential state through whole cycles of one parameter set with the
    compiled contact loop; keeps the event log / segments when asked.
    """

    def __init__(self, c: np.ndarray, vs: VerticalSchedule, log: bool = False, dense: bool = False):
        self.c = c
        self.vs = vs
        self.T = 2.0 * math.pi / float(c["varpi"][0])
        self.n_events = 0
        self.n_evals = 0
        self.log = np.empty(64 if log else 0, contact.LOG_DTYPE)
        self.segs = np.empty(64 if dense else 0, contact.SEG_DTYPE)
        self.nlog = 0 if log else -1
        self.nseg = 0 if dense else -1
        self._rows: dict[tuple[int, int], np.ndarray] = {}
        self._norows = np.empty((0, 4))

    def _idx(self, m0: int, n: int) -> np.ndarray:
        key = (m0, n)
        got = self._rows.get(key)
        if got is None:
            got = self.vs.row(np.arange(m0, m0 + n))
            if n <= 64:  # the periodic map's repeated calls; a long transient runs once
                self._rows[key] = got
        return got

    def run(
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

        Parameters
        ----------
        m0, n : int
            First cycle (0-based) and number of cycles.
        z, zd, s, sd : float
            (ζ, ζ', s, s') [-] at m0's start.
        rows : numpy.ndarray, optional
            (n + 1, 4): receives the state at every cycle start and at the end.
        check_finite : bool
            Fail on a non-finite state.

        Returns
        -------
        tuple of float
            (ζ, ζ', s, s') [-] at the end.

        Raises
        ------
        CycleFailure
            Naming the cycle that failed (rows up to its start filled).
        """
        idx = self._idx(m0, n)
        buf = self._norows if rows is None else rows
        vs = self.vs
        j0 = 0
        while True:
            run = contact.run_cycles(
                self.c,
                vs.table,
                idx[j0:],
                vs.impulsive,
                m0 + j0,
                z,
                zd,
                s,
                sd,
                buf[j0:] if rows is not None else buf,
                check_finite,
                self.log,
                self.nlog,
                self.segs,
                self.nseg,
            )
            self.nlog, self.nseg = int(run.nlog), int(run.nseg)
            self.n_events += int(run.events)
            self.n_evals += int(run.evals)
            z, zd, s, sd = run.z, run.zd, run.s, run.sd
            if run.code != contact.BUFFER_FULL:
                break
            j0 += int(run.j)
            if self.nlog >= 0 and self.nlog + contact.PER_CYCLE + 64 > self.log.size:
                self.log = _grown(self.log, self.nlog, 4 * (n - j0) + contact.PER_CYCLE)
            if self.nseg >= 0 and self.nseg + contact.PER_CYCLE + 64 > self.segs.size:
                self.segs = _grown(self.segs, self.nseg, 6 * (n - j0) + contact.PER_CYCLE)
        if run.code == contact.OK:
            return z, zd, s, sd
        m = m0 + j0 + int(run.j)
        if run.code == contact.SEARCH_FAILED_CODE:
            msg = search_failure_message(run.where)
        elif run.code == contact.CHATTER:
            msg = chatter_message(m * self.T + run.where, m, int(run.switches))
        else:
            msg = f"non-finite state in cycle {m}"
        raise CycleFailure(msg, m)

    def events(self) -> list[Event]:
        """The event log as :class:`~betvdesign.dynamics.result.Event` (τ = mT + t)."""
        T, names = self.T, contact.KIND_NAMES
        return [
            Event(int(r[0]) * T + float(r[1]), names[r[2]], PHASE_NAMES[r[3]], PHASE_NAMES[r[4]])
            for r in self.log[: max(self.nlog, 0)].tolist()
        ]


def _grown(buf: np.ndarray, used: int, extra: int) -> np.ndarray:
    new = np.empty(max(2 * buf.size, used + extra), buf.dtype)
    new[:used] = buf[:used]
    return new


def simulate(
    p: ModelParams,
    cycles: int,
    *,
    dense: bool = False,
    state0: object = None,
    log_events: bool = True,
) -> Trajectory:
    """Exact event-driven transient of ``cycles`` actuation cycles from ``state0`` at τ = 0.

    Time origin: τ here and in the returned :class:`Trajectory` is the kernel time
    τ_k = τ_drive + δ/ϖ, with δ = atan(2ζ_v·ϖ) the phase of the normal force (0 without
    head damping, when τ_k is the drive's phase time); sections are at ϖτ_k = 2mπ
    (docs/MODEL.md, "Damping"). Subtract δ/ϖ for the drive-phase time.

    Every phase is advanced in closed form to its next event, located by a certified
    search (MODEL.md "Dimensionless model"); the vertical motion is computed once
    (:class:`~betvdesign.dynamics.vertical.VerticalSchedule`), the tangential motion by
    the compiled contact loop (:func:`~betvdesign.dynamics.contact.run_cycles`).

    Parameters
    ----------
    p : ModelParams
        The model, with its optional damping and restitution.
    cycles : int
        Actuation cycles to simulate [-] (≥ 0).
    dense : bool
        Keep the closed-form phase pieces for :meth:`Trajectory.sample` and
        ``Trajectory.phases``.
    state0 : sequence of 6 floats, optional
        (ξ, ξ', ζ, ζ', s, s') [-] at τ = 0, with ξ ≥ 0; default all zero (MODEL.md
        "Initial state": a contact start).
    log_events : bool
        Keep the event log (the counters are kept either way).

    Returns
    -------
    Trajectory
        Status "success", or "failed" with the cycles before the one that could not be
        advanced (:data:`~betvdesign.dynamics.result.TrajectoryStatus`).

    Raises
    ------
    ParameterError
        For a ``p`` that is not a ModelParams, a negative or non-integer ``cycles`` or an
        invalid ``state0``.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773 (the model).
    Budd & Dux, Phil. Trans. R. Soc. A 347 (1994), doi:10.1098/rsta.1994.0044 (chattering, with
    restitution).
    """
    if not isinstance(p, ModelParams):
        raise ParameterError(f"p must be a ModelParams, got {type(p).__name__}")
    n = check_cycles(cycles)
    st = check_state0(state0)
    return compile_note("simulate", lambda: _simulate(p, n, st, dense, log_events))  # type: ignore[return-value]


def _simulate(p: ModelParams, n: int, st: tuple, dense: bool, log_events: bool) -> Trajectory:
    t0 = time.perf_counter()
    c = phase_table(p)
    vs = VerticalSchedule(
        p.varpi,
        st[0],
        st[1],
        horizon=max(1000, n + 1),
        zeta_v=p.zeta_v,
        restitution=p.restitution,
    )
    cyc = CycleRunner(c, vs, log_events, dense)
    rows = np.empty((n + 1, 4))  # contiguous: the kernel's one signature
    status, message, done = "success", f"{n} cycles simulated", n
    try:
        cyc.run(0, n, *st[2:], rows=rows)
    except CycleFailure as exc:
        status, message, done = "failed", f"{exc}; results up to cycle {exc.cycle} kept", exc.cycle
    section = np.empty((done + 1, 6))
    section[:, 2:] = rows[: done + 1]
    section[:, 0], section[:, 1] = vs.arrays(0, done + 1)[:2]
    segs = cyc.segs[: max(cyc.nseg, 0)]
    T = cyc.T
    starts = segs["cycle"] * T + segs["t0"]
    phases = [
        (a, a + t1 - t0, PHASE_NAMES[ph])
        for a, t0, t1, ph in zip(
            starts.tolist(),
            segs["t0"].tolist(),
            segs["t1"].tolist(),
            segs["phase"].tolist(),
            strict=True,
        )
    ]
    return Trajectory(
        params=p,
        solver="exact",
        status=status,
        message=message,
        s=float(section[-1, 4]),
        delta_s=np.diff(section[:, 4]),
        section=section,
        events=cyc.events(),
        n_events=cyc.n_events,
        n_cycles=done,
        n_root_evals=cyc.n_evals + vs.n_root_evals,
        elapsed_s=time.perf_counter() - t0,
        impacts_per_cycle=vs.hits_per_cycle(),
        contact_fraction=vs.contact_fraction(),
        driven=vs.period is not None,
        phases=phases,
        engine="compiled" if jit_enabled() else "python",
        _sampler=_Sampler(c, vs, segs, starts) if dense else None,
    )


class _Sampler:
    """Dense output: the closed form of the segment holding each τ."""

    def __init__(self, c: np.ndarray, vs: VerticalSchedule, segs: np.ndarray, starts: np.ndarray):
        self.c, self.vs, self.segs, self.starts = c, vs, segs, starts
        self.T = 2.0 * math.pi / float(c["varpi"][0])
        last = segs[-1] if segs.size else None
        self.end = (
            -1.0
            if last is None
            else float(starts[-1]) + (float(last["t1"]) - float(last["t0"])) * (1 + 1e-12)
        )

    def __call__(self, tau: np.ndarray) -> np.ndarray:
        i = np.searchsorted(self.starts, tau, side="right") - 1
        bad = (i < 0) | (tau > self.end)
        if bad.any():
            raise ValueError(f"τ = {tau[bad][0]} outside the simulated span")
        seg = self.segs[i]
        h = tau - seg["cycle"] * self.T - seg["t0"]
        out = np.empty((tau.size, 6))
        contact.sample_segments(self.c, self.segs, i, h, out)
        out[:, :2] = self.vs.gap(seg["cycle"], seg["t0"] + h)
        return out
