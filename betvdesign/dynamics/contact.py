"""The contact loop: whole actuation cycles of the exact solver (compiled, unit-free).

docs/MODEL.md, "Dimensionless model" and "Impacts and separation". The vertical motion
(:mod:`schedule`) fixes in every cycle the contact window [t_c, π/ϖ] (local time
t = τ − 2mπ/ϖ). Horizontally, free flight has no event and is one closed-form step
(:func:`flows.free_flight`); a contact is a sequence of slip / reverse slip / stick phases,
each advanced in closed form (:mod:`flows`) to its first event located by the certified
search (:mod:`search`): ζ' = s' in slip, a stick-band exit in stick, or the contact end
at t = π/ϖ (known exactly). The phase at a contact start and whenever ζ' = s' is
:func:`decide_phase`; entering stick, the common velocity is
:func:`flows.stick_velocity` (momentum-conserving).

This is the only implementation of the cycle loop. :func:`run_cycles` fills, when asked,
an event log (:data:`LOG_DTYPE`) and the phase segments of dense output
(:data:`SEG_DTYPE`); with ``NUMBA_DISABLE_JIT=1`` the same source runs as Python.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from betvdesign.dynamics.bounds import EPS, NOISE
from betvdesign.dynamics.evaluators import slip_evaluator, stick_evaluator, taylor_general
from betvdesign.dynamics.flows import (
    FREE,
    REVERSE,
    SLIP,
    STICK,
    PhaseTable,
    flow,
    free_flight,
    slip_flow,
    stick_flow,
    stick_velocity,
)
from betvdesign.dynamics.jit import kernel
from betvdesign.dynamics.search import ROOT, SEARCH_FAILED, first_root, workspace

#: Zero-length phases in a row before a contact is declared chattering.
MAX_ZERO_LENGTH = 8
#: Phase switches within one contact before it is declared chattering (Zeno).
MAX_SWITCHES = 1000

#: :func:`run_cycles` codes: done; a search did not terminate; chattering contact;
#: non-finite state; log or segment buffer full (grow it and go on from ``cycle``).
OK, SEARCH_FAILED_CODE, CHATTER, NON_FINITE, BUFFER_FULL = 0, 1, 2, 3, 4

#: event kinds of the log
IMPACT, IMPULSIVE, SEPARATION, VELOCITY_MATCH, BAND_EXIT = 0, 1, 2, 3, 4
KIND_NAMES = ("impact", "impulsive", "separation", "velocity-match", "band-exit")

#: one event: cycle m, local time t [-], kind, phase before and after
LOG_DTYPE = np.dtype(
    [
        ("cycle", np.int64),
        ("t", np.float64),
        ("kind", np.int64),
        ("before", np.int64),
        ("after", np.int64),
    ]
)
#: one closed-form piece: cycle m, local times [t0, t1], phase, state and (sin, cos) of the
#: forcing phase at t0
SEG_DTYPE = np.dtype(
    [
        ("cycle", np.int64),
        ("t0", np.float64),
        ("t1", np.float64),
        ("phase", np.int64),
        ("z", np.float64),
        ("zd", np.float64),
        ("s", np.float64),
        ("sd", np.float64),
        ("sp", np.float64),
        ("cp", np.float64),
    ]
)
#: log / segment entries one cycle can need beyond its impulsive hits
PER_CYCLE = MAX_SWITCHES + 4


class ContactEnd(NamedTuple):
    """What :func:`contact` returns.

    What :func:`contact` returns: ``code`` (OK, SEARCH_FAILED_CODE, CHATTER), the state
    (ζ, ζ', s, s') reached, events and root evaluations counted, ``where`` (the search
    window on SEARCH_FAILED_CODE, the local time on CHATTER), ``switches`` (CHATTER) and the
    log / segment counters.
    """

    code: int
    z: float
    zd: float
    s: float
    sd: float
    events: int
    evals: int
    where: float
    switches: int
    nlog: int
    nseg: int


class CyclesRun(NamedTuple):
    """What :func:`run_cycles` returns.

    What :func:`run_cycles` returns: ``code`` and the cycle offset ``j`` it refers to,
    events and root evaluations counted, ``where`` / ``switches`` as in
    :class:`ContactEnd`, the log / segment counters and the state (ζ, ζ', s, s') reached.
    """

    code: int
    j: int
    events: int
    evals: int
    where: float
    switches: int
    nlog: int
    nseg: int
    z: float
    zd: float
    s: float
    sd: float


@kernel
def decide_phase(
    c: PhaseTable, z: float, zd: float, sd: float, sp: float, cp: float, on: int
) -> int:
    """Contact phase at a contact start or at ζ' = s' (MODEL.md stick/slip rules).

    The sign of ζ' − s' decides when it is above round-off; otherwise the band
    (1 − b) sin ϖτ ≤ ζ ≤ (1 + b) sin ϖτ (b = ακ(1 + β)), compared lexicographically on
    the Taylor coefficients of ζ − q sin ϖτ under the stick flow α(1 + 1/β) ζ'' + ζ =
    sin ϖτ: stick inside, slip below, reverse slip above (this also settles the limit
    sin ϖτ → 0⁺ at a contact opening at τ = 0). With damping: :func:`_decide_band_general`.

    Parameters
    ----------
    c : PhaseTable
        The constants of the parameter set (a record of :func:`phase_table`).
    z, zd, sd : float
        ζ, ζ', s' [-].
    sp, cp : float
        sin ϖτ, cos ϖτ [-] now.
    on : int
        The event just located, zero by construction whatever its round-off: 0 ζ' = s'
        in slip, 1 the lower band edge, 2 the upper band edge; −1 at a contact start.

    Returns
    -------
    int
        ``SLIP``, ``STICK`` or ``REVERSE``.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
    """
    if on < 0:
        v = zd - sd
        nv = NOISE * (abs(zd) + abs(sd))
        if v > nv:
            return SLIP
        if v < -nv:
            return REVERSE
    vs = stick_velocity(zd, sd, c.beta)
    if c.damped:
        return _decide_band_general(c, z, vs, sp, cp, on)
    A, wf, b = c.a_stick, c.varpi, c.b
    zs = (z, vs, (sp - z) / A, (wf * cp - vs) / A)
    ss = (sp, wf * cp, -wf * wf * sp, -(wf * wf * wf) * cp)
    d_lo, n_lo = _edge_closed(1.0, 1.0 - b, zs, ss, on == 1)
    d_hi, n_hi = _edge_closed(-1.0, 1.0 + b, zs, ss, on == 2)
    return _band_verdict(d_lo, n_lo, d_hi, n_hi)


@kernel
def _edge_closed(sig: float, q: float, zs, ss, on: bool) -> tuple:
    """Taylor coefficients 0..3 of σ(ζ − q sin ϖτ) and their round-off floors.

    Parameters
    ----------
    sig : float
        +1 for the lower edge q = 1 − b, −1 for the upper edge q = 1 + b.
    q : float
        The edge's coefficient [-].
    zs, ss : tuple of 4 floats
        Taylor coefficients 0..3 of ζ under the stick flow and of sin ϖτ [-].
    on : bool
        On this edge: its distance (coefficient 0) is 0 exactly.

    Returns
    -------
    tuple of (tuple of 4 floats, tuple of 4 floats)
        The coefficients and their floors [-].
    """
    q0, q1, q2, q3 = q * ss[0], q * ss[1], q * ss[2], q * ss[3]
    d = (
        0.0 if on else sig * (zs[0] - q0),
        sig * (zs[1] - q1),
        sig * (zs[2] - q2),
        sig * (zs[3] - q3),
    )
    nz = (
        NOISE * (abs(zs[0]) + abs(q0)),
        NOISE * (abs(zs[1]) + abs(q1)),
        NOISE * (abs(zs[2]) + abs(q2)),
        NOISE * (abs(zs[3]) + abs(q3)),
    )
    return d, nz


@kernel
def _band_verdict(d_lo, n_lo, d_hi, n_hi) -> int:
    """The stick-band rule: stick inside, slip below, reverse slip above.

    Each band distance (positive inside) is compared lexicographically on its Taylor
    coefficients 0..3: the first one beyond its round-off floor tells on which side the
    motion goes; none beyond it, the distance stays (within round-off) on the edge.

    Parameters
    ----------
    d_lo, n_lo : tuple of 4 floats
        Coefficients of the distance to the lower edge and their floors [-].
    d_hi, n_hi : tuple of 4 floats
        The same for the upper edge [-].

    Returns
    -------
    int
        ``SLIP`` (leaves below), ``REVERSE`` (leaves above) or ``STICK``.
    """
    if _leaves(d_lo, n_lo):
        return SLIP
    if _leaves(d_hi, n_hi):
        return REVERSE
    return STICK


@kernel
def _leaves(d, nz) -> bool:
    """True when the first coefficient of d beyond its floor nz is negative."""
    for j in range(4):
        if d[j] > nz[j]:
            return False  # leaves the band on the admissible side: not this edge
        if d[j] < -nz[j]:
            return True
    return False


@kernel
def _decide_band_general(c: PhaseTable, z: float, vs: float, sp: float, cp: float, on: int) -> int:
    """The stick-band rule of :func:`decide_phase` in the general (damped) form.

    g_lo, g_hi (module doc) are compared lexicographically on their Taylor coefficients
    under the damped stick flow from (ζ, common velocity vs): stick inside, slip below,
    reverse slip above.

    Parameters
    ----------
    c : PhaseTable
        The constants of the parameter set (a record of :func:`phase_table`).
    z : float
        ζ [-].
    vs : float
        The common velocity ζ' = s' [-].
    sp, cp : float
        sin φ, cos φ [-] now.
    on : int
        1 / 2 when on the lower / upper edge (its distance 0 exactly), else 0 or −1.

    Returns
    -------
    int
        ``SLIP``, ``STICK`` or ``REVERSE``.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773 (the band; damping:
    docs/damping.md).
    """
    st = c.stick
    w0, F, G, g = st.w0, st.F, st.G, st.g
    wf, bA, ast = c.varpi, c.bA, c.a_stick
    sj = (sp, wf * cp, -wf * wf * sp, -(wf**3) * cp)
    y2, y3, y4, y5, n2, n3, n4, n5 = taylor_general(w0, g, wf, F, G, z, vs, sp, cp)
    ys = (y2, y3, y4, y5)
    ns = (n2, n3, n4, n5)
    d_lo, n_lo = _edge_general(-1.0, bA, ast, sj, ys, ns, on == 1)
    d_hi, n_hi = _edge_general(1.0, bA, ast, sj, ys, ns, on == 2)
    return _band_verdict(d_lo, n_lo, d_hi, n_hi)


@kernel
def _edge_general(sig: float, bA: float, ast: float, sj, ys, ns, on: bool) -> tuple:
    """Taylor coefficients 0..3 of bA sin φ + σR and their round-off floors (damped band).

    Parameters
    ----------
    sig : float
        −1 for the lower edge g_lo, +1 for the upper edge g_hi.
    bA : float
        Half-width of the band times the normal-force amplitude [-].
    ast : float
        Stick inertia α(1 + 1/β) [-].
    sj : tuple of 4 floats
        Taylor coefficients 0..3 of sin φ [-].
    ys, ns : tuple of 4 floats
        ζ's derivatives of orders 2..5 under the stick flow and their round-off scales [-].
    on : bool
        The motion is on this edge (g_lo or g_hi is 0 exactly at coefficient 0).

    Returns
    -------
    tuple
        (d, nz): the 4 coefficients of the edge distance and their round-off floors [-],
        as :func:`_band_verdict` takes them.
    """
    d = (
        0.0 if on else bA * sj[0] + sig * ast * ys[0],
        bA * sj[1] + sig * ast * ys[1],
        bA * sj[2] + sig * ast * ys[2],
        bA * sj[3] + sig * ast * ys[3],
    )
    nz = (
        NOISE * (abs(bA * sj[0]) + ast * ns[0]),
        NOISE * (abs(bA * sj[1]) + ast * ns[1]),
        NOISE * (abs(bA * sj[2]) + ast * ns[2]),
        NOISE * (abs(bA * sj[3]) + ast * ns[3]),
    )
    return d, nz


@kernel
def _log(log, k, m, t, kind, before, after) -> int:
    r = log[k]
    r["cycle"], r["t"], r["kind"], r["before"], r["after"] = m, t, kind, before, after
    return k + 1


@kernel
def _seg(segs, k, m, t0, t1, phase, z, zd, s, sd, sp, cp) -> int:
    r = segs[k]
    r["cycle"], r["t0"], r["t1"], r["phase"] = m, t0, t1, phase
    r["z"], r["zd"], r["s"], r["sd"], r["sp"], r["cp"] = z, zd, s, sd, sp, cp
    return k + 1


@kernel
def contact(c, m, tc, z, zd, s, sd, ws, log, nlog, segs, nseg):
    """Advance cycle m from its contact-opening hit to its contact end.

    Cycle m from the contact-opening hit at local time tc to the contact end π/ϖ
    (a :class:`ContactEnd`). Logs (nlog ≥ 0) and records segments (nseg ≥ 0) when those
    counters are not −1.
    """
    wf, beta = c.varpi, c.beta
    te = math.pi / wf
    if tc > 0.0:
        if nseg >= 0:
            nseg = _seg(segs, nseg, m, 0.0, tc, FREE, z, zd, s, sd, 0.0, 1.0)
        z, zd, s, sd = free_flight(c, z, zd, s, sd, 1.0, tc)
        sp, cp = math.sin(wf * tc), math.cos(wf * tc)
    else:
        sp, cp = 0.0, 1.0
    t = tc
    phase = decide_phase(c, z, zd, sd, sp, cp, -1)
    if phase == STICK:
        zd = sd = stick_velocity(zd, sd, beta)
    if nlog >= 0:
        nlog = _log(log, nlog, m, t, IMPACT, FREE, phase)
    nev, evals = 1, 0
    zero_len, n_switch, on_edge, from_edge = 0, 0, -1, False
    while True:
        H = te - t
        e = ws.ev[0]
        if phase == STICK:
            stick_evaluator(c, z, zd, sp, cp, H, on_edge, e)
            on_edge = -1
        else:
            slip_evaluator(c, phase, z, zd, s, sd, sp, cp, H, from_edge, e)
        from_edge = False
        code, hr, idx, k = first_root(e, H, ws)
        evals += k
        if code == SEARCH_FAILED:
            return ContactEnd(SEARCH_FAILED_CODE, z, zd, s, sd, nev, evals, hr, 0, nlog, nseg)
        h = hr if code == ROOT else H
        if nseg >= 0:
            nseg = _seg(segs, nseg, m, t, t + h, phase, z, zd, s, sd, sp, cp)
        if phase == STICK:
            z, zd, s, sd = stick_flow(c, z, zd, s, sp, cp, h)
        else:
            z, zd, s, sd = slip_flow(c, phase, z, zd, s, sd, sp, cp, h)
        if code != ROOT:
            break
        t += h
        sp, cp = math.sin(wf * t), math.cos(wf * t)
        new = decide_phase(c, z, zd, sd, sp, cp, 1 + idx if phase == STICK else 0)
        if phase != STICK:  # ζ' = s' exactly (momentum-conserving common velocity)
            zd = sd = stick_velocity(zd, sd, beta)
        elif new == STICK:
            on_edge = idx
        else:
            from_edge = True
        if nlog >= 0:
            kind = BAND_EXIT if phase == STICK else VELOCITY_MATCH
            nlog = _log(log, nlog, m, t, kind, phase, new)
        nev += 1
        zero_len = zero_len + 1 if h <= 64.0 * EPS * max(1.0, t) else 0
        n_switch += 1
        if zero_len > MAX_ZERO_LENGTH or n_switch > MAX_SWITCHES:
            return ContactEnd(CHATTER, z, zd, s, sd, nev, evals, t, n_switch, nlog, nseg)
        phase = new
    if nlog >= 0:
        nlog = _log(log, nlog, m, te, SEPARATION, phase, FREE)
    return ContactEnd(OK, z, zd, s, sd, nev + 1, evals, 0.0, 0, nlog, nseg)


@kernel
def run_cycles(table, tab, idx, imp, m0, z, zd, s, sd, rows, check_finite, log, nlog, segs, nseg):
    """Cycles m0 + j, j = 0..n−1 (n = idx.size) of the exact solver from (ζ, ζ', s, s').

    The only implementation of the cycle loop: free flight in one closed-form step, each
    contact as its sequence of phases to their certified events (:func:`contact`).

    Parameters
    ----------
    table : numpy.ndarray
        :func:`flows.phase_table` (one record).
    tab : numpy.ndarray
        The vertical schedule's distinct cycles (:data:`schedule.CYCLE_DTYPE`).
    idx : numpy.ndarray
        idx[j]: the row of ``tab`` of cycle m0 + j.
    imp : numpy.ndarray
        Impulsive-hit local times [-] (the rows of ``tab`` index them).
    m0 : int
        First cycle [-].
    z, zd, s, sd : float
        ζ, ζ', s, s' [-] at the start of cycle m0.
    rows : numpy.ndarray
        (n + 1, 4), when it has rows: receives the state at every cycle start and at the
        end.
    check_finite : bool
        Stop with NON_FINITE on a non-finite state.
    log, segs : numpy.ndarray
        Event log (:data:`LOG_DTYPE`) and dense-output pieces (:data:`SEG_DTYPE`).
    nlog, nseg : int
        Entries already in ``log`` / ``segs``; −1 to keep none.

    Returns
    -------
    CyclesRun
        ``code`` OK, SEARCH_FAILED_CODE, CHATTER or NON_FINITE in cycle m0 + j, or
        BUFFER_FULL (go on from cycle m0 + j with the state returned, the one at its
        start); the counters and the state reached.

    Notes
    -----
    Over 80 lines on purpose: the compiled cycle loop of the exact solver, carrying the
    state, counters and log rows from cycle to cycle; its numbers are pinned bit for bit
    by ``benchmarks/snapshot.py``.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
    """
    c = table[0]
    ws = workspace()
    wf = c.varpi
    T = 2.0 * math.pi / wf
    te = math.pi / wf
    keep = rows.shape[0] > 0
    nev, evals = 0, 0
    n = idx.size
    for j in range(n):
        v = tab[idx[j]]
        m = m0 + j
        tc, i0, ni = v["tc"], v["imp_start"], v["imp_count"]
        if (nlog >= 0 and nlog + ni + PER_CYCLE > log.shape[0]) or (
            nseg >= 0 and nseg + PER_CYCLE > segs.shape[0]
        ):
            return CyclesRun(BUFFER_FULL, j, nev, evals, 0.0, 0, nlog, nseg, z, zd, s, sd)
        if keep:
            rows[j, 0], rows[j, 1], rows[j, 2], rows[j, 3] = z, zd, s, sd
        nev += ni
        if nlog >= 0:  # impulsive hits before the contact, in time order
            for k in range(i0, i0 + ni):
                if tc != tc or imp[k] < tc:
                    nlog = _log(log, nlog, m, imp[k], IMPULSIVE, FREE, FREE)
        if tc != tc:  # NaN: no contact in this cycle
            if nseg >= 0:
                nseg = _seg(segs, nseg, m, 0.0, T, FREE, z, zd, s, sd, 0.0, 1.0)
            z, zd, s, sd = free_flight(c, z, zd, s, sd, 1.0, T)
        else:
            end = contact(c, m, tc, z, zd, s, sd, ws, log, nlog, segs, nseg)
            nev += end.events
            evals += end.evals
            nlog, nseg = end.nlog, end.nseg
            if end.code != OK:  # the state returned is the one at the cycle's start
                return CyclesRun(
                    end.code, j, nev, evals, end.where, end.switches, nlog, nseg, z, zd, s, sd
                )
            z, zd, s, sd = end.z, end.zd, end.s, end.sd
            if nlog >= 0:  # impulsive hits after the separation
                for k in range(i0, i0 + ni):
                    if imp[k] > te:
                        nlog = _log(log, nlog, m, imp[k], IMPULSIVE, FREE, FREE)
            if nseg >= 0:
                nseg = _seg(segs, nseg, m, te, T, FREE, z, zd, s, sd, 0.0, -1.0)
            z, zd, s, sd = free_flight(c, z, zd, s, sd, -1.0, te)
        if check_finite and (z - z) + (zd - zd) + (s - s) + (sd - sd) != 0.0:
            return CyclesRun(NON_FINITE, j, nev, evals, 0.0, 0, nlog, nseg, z, zd, s, sd)
    if keep:
        rows[n, 0], rows[n, 1], rows[n, 2], rows[n, 3] = z, zd, s, sd
    return CyclesRun(OK, n, nev, evals, 0.0, 0, nlog, nseg, z, zd, s, sd)


@kernel
def sample_segments(table, segs, which, h, out) -> None:
    """Dense output: tangential states at local offsets into closed-form segments.

    Parameters
    ----------
    table : numpy.ndarray
        :func:`flows.phase_table` (one record).
    segs : numpy.ndarray
        The segments (:data:`SEG_DTYPE`).
    which : numpy.ndarray
        Segment of each sample.
    h : numpy.ndarray
        Offset [-] of each sample into its segment.
    out : numpy.ndarray
        (n, 6): receives (ζ, ζ', s, s') [-] in out[k, 2:6].

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
    """
    c = table[0]
    for k in range(which.size):
        r = segs[which[k]]
        z, zd, s, sd = flow(c, r["phase"], r["z"], r["zd"], r["s"], r["sd"], r["sp"], r["cp"], h[k])
        out[k, 2], out[k, 3], out[k, 4], out[k, 5] = z, zd, s, sd
