"""Coupled head, exact compiled solver (docs/MODEL.md "Coupled head (K_nt ≠ 0)").

The head with a symmetric 2×2 stiffness in the slider's frame (coupling ρ, χ = √α·tanθ:
:class:`~betvdesign.model.params.HeadCoupling`), the paper's ideal model otherwise
(undamped, plastic impacts, Coulomb stick/slip). Every phase (free flight, slip, reverse
slip, stick) is a linear time-invariant system once the state is augmented with the
forcing (p, q) = (sin ϖτ, cos ϖτ): z = (ξ, ξ', ζ, ζ', s, s', p, q), z' = A_phase·z with
A_phase constant per phase type (:func:`phase_matrices`). The state therefore evolves
*exactly* as exp(A_phase·δ)·z:

- stepping: exp(A·h) for one step h is computed once per phase type (:func:`expm`,
  scaling and squaring of the Taylor series) and a step is an 8×8 mat-vec; (p, q) are set
  to sin ϖτ, cos ϖτ of the step's end time after each step (no drift of the forcing);
- the step resolves the fastest rate: h = min(T/:data:`STEPS_DRIVE`,
  2π/|λ|max/:data:`STEPS_FAST`) over the eigenvalues λ of every phase's matrix (the stiff
  mode √λ₊ and a negative slip stiffness's growth rate included), T = 2π/ϖ;
- events are linear functionals g·z falling through 0 (the hit ξ = 0 in free flight, the
  separation n = 0, the band edges R = ±b·n in stick, ζ' = s' in slip; :func:`event_table`):
  detected by a sign change between steps, or by a minimum of g inside a step (a sign
  change of g' = (g·A)·z, then g at its root, unless the cubic Hermite interpolant's
  minimum exceeds its error bound: a double crossing within one step is not skipped), and
  refined by Brent's method on the exact flow g·exp(A·δ)·z_step to
  round-off of τ;
- the automaton's rules are MODEL.md's (as the independent reference
  :mod:`coupled_reference` writes them from MODEL.md): a hit sets ξ' = 0 and opens
  contact where n > 0 (or n = 0 rising), else is impulsive; entering stick the common
  velocity conserves ζ' + s'/β; the phase at a contact start or at ζ' = s' comes from the
  band tested :data:`LOOKAHEAD` of a cycle ahead on the exact stick flow; an event
  already at 0 where a phase starts is watched from :data:`MASK` of a cycle on (a first
  short step): an event there only where it is clearly past 0 (beyond the round-off of
  the state), else watched on from there.

At ρ = 0 exactly the coupled model is the paper's (MODEL.md, reduction):
:func:`simulate_coupled` and :func:`coupled_periodic_orbit` call the exact closed-form
solver (:func:`~betvdesign.dynamics.simulate`, :func:`~betvdesign.dynamics.periodic_orbit`)
and return its answers unchanged (bit-identical to the decoupled solver).

Cost: about T/h steps per cycle (an 8×8 mat-vec and a few dot products each), growing
like √λ₊/ϖ as the clamped direction stiffens, and some thirty 8×8 matrix exponentials
per event (benchmarks/README.md "Coupled head").

References
----------
Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773 (the decoupled model).
Moler & Van Loan, SIAM Review 45, 3 (2003), doi:10.1137/S00361445024180 (scaling and
squaring). Brent, *Algorithms for Minimization without Derivatives* (1973), ch. 4.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import replace

import numpy as np

from betvdesign.dynamics.inputs import check_cycles, check_state0
from betvdesign.dynamics.jit import compile_note, kernel
from betvdesign.dynamics.result import Event, PeriodicResult, Trajectory
from betvdesign.dynamics.settling import Settling
from betvdesign.errors import ParameterError
from betvdesign.model.domain import mode_of
from betvdesign.model.params import HeadCoupling, ModelParams

#: phase codes (index of :func:`phase_matrices`)
FREE, SLIP, STICK, REVERSE = 0, 1, 2, 3
PHASE_NAMES = ("free", "slip", "stick", "reverse")
#: event kinds of the log
IMPACT, IMPULSIVE, SEPARATION, VELOCITY_MATCH, BAND_EXIT = 0, 1, 2, 3, 4
KIND_NAMES = ("impact", "impulsive", "separation", "velocity-match", "band-exit")
#: event functionals' kinds (:func:`event_table`)
EV_GAP, EV_SEP, EV_MATCH, EV_BAND = 0, 1, 2, 3
#: :func:`run_coupled` codes: done; too many switches in a cycle; a root search did not
#: converge; non-finite state; event log full (grow it and go on from the cycle returned)
OK, CHATTER, ROOT_FAILED, NON_FINITE, BUFFER_FULL = 0, 1, 2, 3, 4

#: steps per drive period at least [-]
STEPS_DRIVE = 64
#: steps per period 2π/|λ| of the fastest rate of any phase at least [-]
STEPS_FAST = 32
#: relative velocity |ζ' − s'| below which ζ' = s' is taken as reached (scaled)
VTOL = 1e-9
#: look-ahead [fraction of a cycle] at which the stick band is tested
LOOKAHEAD = 1e-6
#: an event already at 0 where a phase starts is first tested MASK·(2π/ϖ) later
MASK = 1e-9
#: phase switches in one cycle before it is declared chattering (a failure)
MAX_SWITCHES = 2000
#: Brent iterations at most
MAX_ROOT_ITER = 200
#: restarts of Newton after ``transient`` iterations of the map, when no step helps
MAX_RESTARTS = 3


# -- linear algebra --------------------------------------------------------------------------


@kernel
def _matmul(x: np.ndarray, y: np.ndarray, out: np.ndarray) -> None:
    """The product x·y of square matrices into out (distinct from x and y)."""
    n = x.shape[0]
    for i in range(n):
        for j in range(n):
            acc = 0.0
            for k in range(n):
                acc += x[i, k] * y[k, j]
            out[i, j] = acc


@kernel
def _matvec(m: np.ndarray, v: np.ndarray, out: np.ndarray) -> None:
    """The product m·v into out (distinct from v)."""
    n = m.shape[0]
    for i in range(n):
        acc = 0.0
        for k in range(n):
            acc += m[i, k] * v[k]
        out[i] = acc


@kernel
def _dot(c: np.ndarray, v: np.ndarray) -> float:
    acc = 0.0
    for k in range(v.size):
        acc += c[k] * v[k]
    return acc


@kernel
def expm(m: np.ndarray) -> np.ndarray:
    """Matrix exponential by scaling and squaring of the Taylor series.

    m/2^j with ‖m/2^j‖∞ ≤ 1/2, its Taylor series summed until a term is below 1e-17 of
    the sum (at most 30 terms; 0.5^k/k! < 1e-17 from k = 14), squared j times.

    Parameters
    ----------
    m : numpy.ndarray
        Square matrix [-], shape (n, n).

    Returns
    -------
    numpy.ndarray
        exp(m), shape (n, n).
    """
    n = m.shape[0]
    nrm = 0.0
    for i in range(n):
        r = 0.0
        for j in range(n):
            r += abs(m[i, j])
        nrm = max(nrm, r)
    sq = 0
    scale = 1.0
    while nrm * scale > 0.5:
        scale *= 0.5
        sq += 1
    x = m * scale
    e = np.eye(n)
    term = np.eye(n)
    tmp = np.empty((n, n))
    for k in range(1, 31):
        _matmul(term, x, tmp)
        big = 0.0
        tot = 0.0
        for i in range(n):
            for j in range(n):
                term[i, j] = tmp[i, j] / k
                e[i, j] += term[i, j]
                big = max(big, abs(term[i, j]))
                tot = max(tot, abs(e[i, j]))
        if big <= 1e-17 * tot:
            break
    for _ in range(sq):
        _matmul(e, e, tmp)
        e[:, :] = tmp
    return e


# -- the model's matrices -----------------------------------------------------------------


@kernel
def phase_matrices(
    w: float, al: float, be: float, ka: float, a: float, cn: float, ct: float
) -> np.ndarray:
    """The four phases' matrices A on the augmented state z = (ξ, ξ', ζ, ζ', s, s', p, q).

    MODEL.md "Coupled head": with p = sin ϖτ, q = cos ϖτ (p' = ϖq, q' = −ϖp),
    n = a·cn·ζ + a(1 − cn)·p and R = a·ζ + a(ct − 1)·p at ξ = 0:

    - free: ξ'' = −a(ξ + p + cn(ζ − p)), α ζ'' = −a(ct(ξ + p) + ζ − p), s'' = 0;
    - slip (σ = +1) / reverse (σ = −1): α ζ'' = −R − σακn, s'' = σβκn, ξ ≡ 0;
    - stick: α(1 + 1/β) ζ'' = −R, s'' = ζ'', ξ ≡ 0.

    Parameters
    ----------
    w, al, be, ka : float
        ϖ, α, β, κ [-].
    a, cn, ct : float
        a = 1/(1 − ρ²), cn = ρ/χ, ct = ρχ [-].

    Returns
    -------
    numpy.ndarray
        Shape (4, 8, 8), indexed by :data:`FREE`, :data:`SLIP`, :data:`STICK`,
        :data:`REVERSE`.
    """
    out = np.zeros((4, 8, 8))
    for k in range(4):
        out[k, 6, 7] = w
        out[k, 7, 6] = -w
    f = out[FREE]
    f[0, 1] = 1.0
    f[2, 3] = 1.0
    f[4, 5] = 1.0
    f[1, 0] = -a
    f[1, 2] = -a * cn
    f[1, 6] = -a * (1.0 - cn)
    f[3, 0] = -a * ct / al
    f[3, 2] = -a / al
    f[3, 6] = -a * (ct - 1.0) / al
    for k in (SLIP, REVERSE):
        sig = 1.0 if k == SLIP else -1.0
        m = out[k]
        m[2, 3] = 1.0
        m[4, 5] = 1.0
        # α ζ'' = −R − σακn
        m[3, 2] = (-a - sig * al * ka * a * cn) / al
        m[3, 6] = (-a * (ct - 1.0) - sig * al * ka * a * (1.0 - cn)) / al
        m[5, 2] = sig * be * ka * a * cn
        m[5, 6] = sig * be * ka * a * (1.0 - cn)
    s = out[STICK]
    big_a = al * (1.0 + 1.0 / be)
    s[2, 3] = 1.0
    s[4, 5] = 1.0
    s[3, 2] = -a / big_a
    s[3, 6] = -a * (ct - 1.0) / big_a
    s[5, 2] = s[3, 2]
    s[5, 6] = s[3, 6]
    return out


def event_table(
    a: float, cn: float, ct: float, b: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The event functionals of each phase: every event is g·z falling through 0.

    - free: the gap ξ (a hit);
    - slip / reverse: the separation n, and σ(ζ' − s') (ζ' = s' reached);
    - stick: n, R + b·n (→ slip) and b·n − R (→ reverse).

    Parameters
    ----------
    a, cn, ct : float
        a = 1/(1 − ρ²), cn = ρ/χ, ct = ρχ [-].
    b : float
        ακ(1 + β) [-].

    Returns
    -------
    g : numpy.ndarray
        Shape (4, 3, 8): phase, event, functional.
    count : numpy.ndarray
        Events per phase, shape (4,).
    kind : numpy.ndarray
        :data:`EV_GAP`, :data:`EV_SEP`, :data:`EV_MATCH` or :data:`EV_BAND`, shape (4, 3).
    """
    g = np.zeros((4, 3, 8))
    kind = np.zeros((4, 3), dtype=np.int64)
    count = np.array([1, 2, 3, 2], dtype=np.int64)
    n_row = np.zeros(8)
    n_row[2], n_row[6] = a * cn, a * (1.0 - cn)
    r_row = np.zeros(8)
    r_row[2], r_row[6] = a, a * (ct - 1.0)
    g[FREE, 0, 0] = 1.0
    kind[FREE, 0] = EV_GAP
    for k, sig in ((SLIP, 1.0), (REVERSE, -1.0)):
        g[k, 0] = n_row
        kind[k, 0] = EV_SEP
        g[k, 1, 3], g[k, 1, 5] = sig, -sig
        kind[k, 1] = EV_MATCH
    g[STICK, 0] = n_row
    g[STICK, 1] = r_row + b * n_row
    g[STICK, 2] = b * n_row - r_row
    kind[STICK] = (EV_SEP, EV_BAND, EV_BAND)
    return g, count, kind


# -- the kernel ----------------------------------------------------------------------------


@kernel
def _flow_g(amat: np.ndarray, zb: np.ndarray, c: np.ndarray, d: float, tmp: np.ndarray) -> float:
    """c·exp(A·d)·zb (exact flow of the phase) [-]."""
    e = expm(amat * d)
    _matvec(e, zb, tmp)
    return _dot(c, tmp)


@kernel
def _brent(
    amat: np.ndarray,
    zb: np.ndarray,
    c: np.ndarray,
    lo: float,
    hi: float,
    flo: float,
    fhi: float,
    xtol: float,
    tmp: np.ndarray,
) -> tuple[float, int, bool]:
    """Root of f(δ) = c·exp(A δ)·zb in [lo, hi], f(lo) > 0 ≥ f(hi) (Brent's zeroin).

    Returns (δ, evaluations, converged); δ is the bracket's end where f ≤ 0, so that the
    event has happened at the state returned.
    """
    a, b, fa, fb = lo, hi, flo, fhi
    c_, fc = a, fa
    d = b - a
    e = d
    nev = 0
    for _ in range(MAX_ROOT_ITER):
        if (fb > 0.0 and fc > 0.0) or (fb <= 0.0 and fc <= 0.0):
            c_, fc = a, fa
            d = b - a
            e = d
        if abs(fc) < abs(fb):
            a, b, c_ = b, c_, b
            fa, fb, fc = fb, fc, fb
        tol1 = 2.0 * 2.2e-16 * abs(b) + 0.5 * xtol
        xm = 0.5 * (c_ - b)
        if abs(xm) <= tol1 or fb == 0.0:
            # the side where f ≤ 0
            if fb <= 0.0:
                return b, nev, True
            return c_, nev, True
        if abs(e) >= tol1 and abs(fa) > abs(fb):
            s = fb / fa
            if a == c_:
                p = 2.0 * xm * s
                q = 1.0 - s
            else:
                q = fa / fc
                r = fb / fc
                p = s * (2.0 * xm * q * (q - r) - (b - a) * (r - 1.0))
                q = (q - 1.0) * (r - 1.0) * (s - 1.0)
            if p > 0.0:
                q = -q
            else:
                p = -p
            if 2.0 * p < min(3.0 * xm * q - abs(tol1 * q), abs(e * q)):
                e = d
                d = p / q
            else:
                d = xm
                e = d
        else:
            d = xm
            e = d
        a, fa = b, fb
        if abs(d) > tol1:
            b += d
        else:
            b += tol1 if xm > 0.0 else -tol1
        fb = _flow_g(amat, zb, c, b, tmp)
        nev += 1
    return b, nev, False


@kernel
def _may_dip(
    g0: float,
    g1: float,
    d0: float,
    d1: float,
    h: float,
    g4: np.ndarray,
    z0: np.ndarray,
    z1: np.ndarray,
) -> bool:
    """Whether g, positive at both ends of a step with g' < 0 < g' there, may reach 0.

    The cubic Hermite interpolant of (g, g') at the ends is within h⁴/384·max|g⁗| of g on
    the step; g⁗ = (g·A⁴)·z is taken at the ends, times 2 (it changes little over a step,
    a small fraction of the fastest period). False only when the interpolant's minimum
    exceeds that error: no crossing is possible and the exact search is skipped.
    """
    a1 = h * d0
    a2 = 3.0 * (g1 - g0) - h * (2.0 * d0 + d1)
    a3 = 2.0 * (g0 - g1) + h * (d0 + d1)
    lo, hi = 0.0, 1.0
    for _ in range(60):  # the root of H' (negative at 0, positive at 1)
        mid = 0.5 * (lo + hi)
        if a1 + mid * (2.0 * a2 + 3.0 * a3 * mid) < 0.0:
            lo = mid
        else:
            hi = mid
    s = 0.5 * (lo + hi)
    hmin = g0 + s * (a1 + s * (a2 + s * a3))
    d4 = max(abs(_dot(g4, z0)), abs(_dot(g4, z1)))
    err = 2.0 * h**4 / 384.0 * d4 + 1e-13 * (abs(g0) + abs(g1))
    return hmin - err <= 0.0


@kernel
def _decide(
    z: np.ndarray, matched: bool, be: float, look: np.ndarray, gst: np.ndarray, tmp: np.ndarray
) -> int:
    """Contact phase at a contact start or at ζ' = s' (MODEL.md "Phase conditions").

    Sets the common velocity (conserving ζ' + s'/β) when the phase is stick or when ζ' = s'
    was reached. ``look`` = exp(A_stick·LOOKAHEAD·T); ``gst`` the stick events.
    """
    v = z[3] - z[5]
    if not matched and abs(v) > VTOL * (1.0 + abs(z[3]) + abs(z[5])):
        return SLIP if v > 0.0 else REVERSE
    vs = (z[3] + z[5] / be) / (1.0 + 1.0 / be)
    z3, z5 = z[3], z[5]
    z[3] = vs
    z[5] = vs
    _matvec(look, z, tmp)
    mode = STICK
    if _dot(gst[1], tmp) < 0.0:
        mode = SLIP
    elif _dot(gst[2], tmp) < 0.0:
        mode = REVERSE
    if mode != STICK and not matched:
        z[3] = z3
        z[5] = z5
    return mode


@kernel
def _hit(
    z: np.ndarray,
    w: float,
    a: float,
    cn: float,
    be: float,
    look: np.ndarray,
    gst: np.ndarray,
    tmp: np.ndarray,
) -> int:
    """A hit: ξ = ξ' = 0; the phase that follows (FREE: impulsive)."""
    z[0] = 0.0
    z[1] = 0.0
    n = _dot(gst[0], z)
    if abs(n) > 1e-13 * a * (1.0 + abs(z[2])):
        opens = n > 0.0
    else:
        opens = a * ((1.0 - cn) * w * z[7] + cn * z[3]) > 0.0
    if not opens:
        return FREE
    return _decide(z, False, be, look, gst, tmp)


@kernel
def run_coupled(
    amats: np.ndarray,
    emats: np.ndarray,
    look: np.ndarray,
    g: np.ndarray,
    gd: np.ndarray,
    g4: np.ndarray,
    count: np.ndarray,
    kind: np.ndarray,
    h: float,
    w: float,
    a: float,
    cn: float,
    be: float,
    z: np.ndarray,
    mode_io: np.ndarray,
    m0: int,
    m1: int,
    start: bool,
    sec: np.ndarray,
    log_t: np.ndarray,
    log_k: np.ndarray,
    log_pb: np.ndarray,
    log_pa: np.ndarray,
    counters: np.ndarray,
) -> tuple[int, int, float]:
    """Cycles m0..m1 − 1 of the coupled automaton (module docstring), exact piecewise.

    Parameters
    ----------
    amats, emats : numpy.ndarray
        Phase matrices A (:func:`phase_matrices`) and exp(A·h), shape (4, 8, 8).
    look : numpy.ndarray
        exp(A_stick·LOOKAHEAD·T), shape (8, 8).
    g, gd, g4 : numpy.ndarray
        Event functionals (:func:`event_table`), their derivatives g·A and fourth
        derivatives g·A⁴ along the flow, (4, 3, 8).
    count, kind : numpy.ndarray
        Events per phase, and their kinds.
    h : float
        Step [-].
    w, a, cn, be : float
        ϖ, a, ρ/χ, β [-].
    z : numpy.ndarray
        Augmented state at τ = 2·m0·π/ϖ (in), at the last cycle done (out), shape (8,).
    mode_io : numpy.ndarray
        The phase (in and out), shape (1,).
    m0, m1 : int
        Cycles to run.
    start : bool
        Decide the phase from the state at m0 first (ξ = 0, ξ' ≤ 0: a hit).
    sec : numpy.ndarray
        Sections: row m + 1 gets (ξ, ξ', ζ, ζ', s, s') at the end of cycle m.
    log_t, log_k, log_pb, log_pa : numpy.ndarray
        Event log (τ, kind, phase before, after); size 0: no log.
    counters : numpy.ndarray
        [events, root evaluations, steps] (added to), shape (3,).

    Returns
    -------
    tuple
        (cycle reached, code :data:`OK` … :data:`BUFFER_FULL`, τ of a failure).
    """
    T = 2.0 * math.pi / w
    tmp = np.empty(8)
    zb = np.empty(8)
    zn = np.empty(8)
    gv = np.empty(3)
    gdv = np.empty(3)
    masked = np.zeros(3, dtype=np.bool_)
    cap = log_t.size
    nlog = int(counters[0]) if cap > 0 else 0
    mode = int(mode_io[0])
    gst = g[STICK]
    eps = MASK * T
    if start:
        t = m0 * T
        z[6] = math.sin(w * t)
        z[7] = math.cos(w * t)
        if z[0] == 0.0 and z[1] <= 0.0:
            mode = _hit(z, w, a, cn, be, look, gst, tmp)
            if mode != FREE:
                if cap > 0:
                    log_t[nlog] = t
                    log_k[nlog] = IMPACT
                    log_pb[nlog] = FREE
                    log_pa[nlog] = mode
                    nlog += 1
                counters[0] += 1
        else:
            mode = FREE
    for m in range(m0, m1):
        if cap > 0 and nlog + MAX_SWITCHES + 2 > cap:
            mode_io[0] = mode
            return m, BUFFER_FULL, m * T
        t = m * T
        t1 = (m + 1) * T
        switches = 0
        while t < t1:
            # a piece of one phase from t: step to its first event or to t1
            z[6] = math.sin(w * t)
            z[7] = math.cos(w * t)
            am = amats[mode]
            em = emats[mode]
            ne = count[mode]
            scale = 1e-12 * (1.0 + a * (1.0 + abs(z[2])) + abs(z[3]) + abs(z[5]))
            first = False
            for i in range(ne):
                gv[i] = _dot(g[mode, i], z)
                gdv[i] = _dot(gd[mode, i], z)
                masked[i] = abs(gv[i]) <= scale
                if masked[i]:
                    first = True
            tb = t
            for k in range(8):
                zb[k] = z[k]
            found = -1
            dfound = 0.0
            while True:
                step = eps if first else h
                last = False
                if tb + step >= t1:
                    step = t1 - tb
                    last = True
                if step == h:
                    _matvec(em, zb, zn)
                else:
                    _matvec(expm(am * step), zb, zn)
                counters[2] += 1
                xtol = 4.4e-16 * max(1.0, abs(tb + step))
                for i in range(ne):
                    gn = _dot(g[mode, i], zn)
                    gdn = _dot(gd[mode, i], zn)
                    if first and masked[i]:
                        # at 0 where the piece starts: an event only if clearly past it
                        # after MASK of a cycle (a phase rule contradicted), else watched
                        # on from here as on its positive side
                        if gn < -scale and (found < 0 or step < dfound):
                            found, dfound = i, step
                        gv[i], gdv[i] = max(gn, 1e-300), gdn
                        continue
                    d = -1.0
                    if gv[i] > 0.0 and gn <= 0.0:
                        d, k_ev, ok = _brent(am, zb, g[mode, i], 0.0, step, gv[i], gn, xtol, tmp)
                        counters[1] += k_ev
                        if not ok:
                            mode_io[0] = mode
                            return m, ROOT_FAILED, tb
                    elif (
                        gv[i] > 0.0
                        and gn > 0.0
                        and gdv[i] < 0.0
                        and gdn > 0.0
                        and _may_dip(gv[i], gn, gdv[i], gdn, step, g4[mode, i], zb, zn)
                    ):
                        # a minimum inside the step that may reach 0: g at the root of g'
                        dm, k_ev, ok = _brent(
                            am, zb, -gd[mode, i], 0.0, step, -gdv[i], -gdn, xtol, tmp
                        )
                        counters[1] += k_ev + 1
                        if not ok:
                            mode_io[0] = mode
                            return m, ROOT_FAILED, tb
                        gm = _flow_g(am, zb, g[mode, i], dm, tmp)
                        if gm <= 0.0:
                            d, k_ev, ok = _brent(am, zb, g[mode, i], 0.0, dm, gv[i], gm, xtol, tmp)
                            counters[1] += k_ev
                            if not ok:
                                mode_io[0] = mode
                                return m, ROOT_FAILED, tb
                    if d >= 0.0 and (found < 0 or d < dfound):
                        found, dfound = i, d
                    gv[i], gdv[i] = gn, gdn
                if found >= 0:
                    _matvec(expm(am * dfound), zb, z)
                    t = tb + dfound
                    break
                first = False
                tb = t1 if last else tb + step
                for k in range(6):
                    zb[k] = zn[k]
                zb[6] = math.sin(w * tb)
                zb[7] = math.cos(w * tb)
                if last:
                    break
            if found < 0:
                for k in range(8):
                    z[k] = zb[k]
                t = t1
                break
            # the event at t
            switches += 1
            counters[0] += 1
            if switches > MAX_SWITCHES:
                mode_io[0] = mode
                return m, CHATTER, t
            z[6] = math.sin(w * t)
            z[7] = math.cos(w * t)
            before = mode
            ek = kind[mode, found]
            if ek == EV_GAP:
                mode = _hit(z, w, a, cn, be, look, gst, tmp)
                lk = IMPACT if mode != FREE else IMPULSIVE
            elif ek == EV_SEP:
                z[0] = 0.0
                z[1] = 0.0
                mode = FREE
                lk = SEPARATION
            elif ek == EV_MATCH:
                mode = _decide(z, True, be, look, gst, tmp)
                lk = VELOCITY_MATCH
            else:
                mode = _decide(z, True, be, look, gst, tmp)
                lk = BAND_EXIT
            if mode != FREE:
                z[0] = 0.0
                z[1] = 0.0
            if cap > 0:
                log_t[nlog] = t
                log_k[nlog] = lk
                log_pb[nlog] = before
                log_pa[nlog] = mode
                nlog += 1
        for k in range(6):
            if not math.isfinite(z[k]):
                mode_io[0] = mode
                return m, NON_FINITE, t
            sec[m + 1, k] = z[k]
    mode_io[0] = mode
    return m1, OK, m1 * T


# -- the model set up once per parameter set ----------------------------------------------


class CoupledModel:
    """The compiled automaton's tables for one parameter set (module docstring).

    Parameters
    ----------
    p : ModelParams
        ϖ, α, β, κ (ideal: no damping, plastic impacts).
    coupling : HeadCoupling
        ρ and χ.

    Attributes
    ----------
    step : float
        The step h [-].
    fastest : float
        |λ|max over every phase's matrix [-] (the stiff mode's √λ₊ or a growth rate).

    Raises
    ------
    ParameterError
        For a ``p`` or ``coupling`` of the wrong type, or damping / restitution in ``p``.
    """

    def __init__(self, p: ModelParams, coupling: HeadCoupling) -> None:
        if not isinstance(p, ModelParams):
            raise ParameterError(f"p must be a ModelParams, got {type(p).__name__}")
        if not isinstance(coupling, HeadCoupling):
            raise ParameterError(f"coupling must be a HeadCoupling, got {type(coupling).__name__}")
        if not p.ideal:
            raise ParameterError(
                "the coupled solver solves the ideal model only (no damping, plastic "
                f"impacts); got zeta_v={p.zeta_v}, zeta_h={p.zeta_h}, e={p.restitution}"
            )
        self.p, self.coupling = p, coupling
        w, al, be, ka = p.varpi, p.alpha, p.beta, p.kappa
        rho, chi = coupling.rho, coupling.chi
        self.a = 1.0 / ((1.0 - rho) * (1.0 + rho))
        self.cn, self.ct = rho / chi, rho * chi
        b = al * ka * (1.0 + be)
        self.T = 2.0 * math.pi / w
        self.amats = phase_matrices(w, al, be, ka, self.a, self.cn, self.ct)
        self.g, self.count, self.kind = event_table(self.a, self.cn, self.ct, b)
        self.gd = np.einsum("kej,kjl->kel", self.g, self.amats)
        a4 = np.stack([np.linalg.matrix_power(m, 4) for m in self.amats])
        self.g4 = np.einsum("kej,kjl->kel", self.g, a4)
        lam = max(float(np.max(np.abs(np.linalg.eigvals(m)))) for m in self.amats)
        self.fastest = max(lam, w)
        self.step = min(self.T / STEPS_DRIVE, 2.0 * math.pi / self.fastest / STEPS_FAST)
        self.emats = np.stack([expm(m * self.step) for m in self.amats])
        self.look = expm(self.amats[STICK] * (LOOKAHEAD * self.T))

    def run(
        self,
        z: np.ndarray,
        mode: np.ndarray,
        m0: int,
        m1: int,
        start: bool,
        sec: np.ndarray,
        log: tuple[np.ndarray, ...],
        counters: np.ndarray,
    ) -> tuple[int, int, float]:
        """:func:`run_coupled` with this model's tables."""
        return run_coupled(
            self.amats, self.emats, self.look, self.g, self.gd, self.g4, self.count, self.kind,
            self.step, self.p.varpi, self.a, self.cn, self.p.beta, z, mode, m0, m1, start,
            sec, *log, counters,
        )  # fmt: skip


_MESSAGES = {
    CHATTER: "more than {n} phase switches in cycle {m} near τ = {t:.6g} (chattering contact)",
    ROOT_FAILED: "an event's root search did not converge in cycle {m} near τ = {t:.6g}",
    NON_FINITE: "the state became non-finite in cycle {m} (τ ≤ {t:.6g})",
}


def _empty_log() -> tuple[np.ndarray, ...]:
    return (np.empty(0), np.empty(0, np.int64), np.empty(0, np.int64), np.empty(0, np.int64))


def _new_log(cap: int) -> tuple[np.ndarray, ...]:
    return (
        np.empty(cap),
        np.empty(cap, np.int64),
        np.empty(cap, np.int64),
        np.empty(cap, np.int64),
    )


def simulate_coupled(
    p: ModelParams,
    coupling: HeadCoupling,
    cycles: int,
    *,
    state0: object = None,
    log_events: bool = True,
) -> Trajectory:
    """Exact transient of ``cycles`` actuation cycles of the coupled model from ``state0``.

    At ρ = 0 exactly the exact decoupled solver's answer
    (:func:`betvdesign.dynamics.simulate`), unchanged.

    Parameters
    ----------
    p : ModelParams
        ϖ, α, β, κ (ideal: no damping, plastic impacts).
    coupling : HeadCoupling
        ρ and χ.
    cycles : int
        Actuation cycles [-] (≥ 0).
    state0 : sequence of 6 floats, optional
        (ξ, ξ', ζ, ζ', s, s') [-] at τ = 0, ξ ≥ 0; default all zero (a contact start
        where n rises).
    log_events : bool
        Keep the event log (the counters are kept either way).

    Returns
    -------
    Trajectory
        ``solver`` "coupled-exact" (or "exact" at ρ = 0); status "success", or "failed"
        with the cycles before the one that could not be advanced and why.

    Raises
    ------
    ParameterError
        For invalid parameters, cycles or state0.
    """
    from betvdesign.dynamics.solver import simulate

    if not isinstance(coupling, HeadCoupling):
        raise ParameterError(f"coupling must be a HeadCoupling, got {type(coupling).__name__}")
    if coupling.rho == 0.0:
        return simulate(p, cycles, state0=state0, log_events=log_events)
    mdl = CoupledModel(p, coupling)
    n = check_cycles(cycles)
    st = check_state0(state0)
    return compile_note(  # type: ignore[return-value]
        "simulate_coupled", lambda: _simulate(mdl, n, np.array(st, dtype=float), log_events)
    )


def _simulate(mdl: CoupledModel, n: int, y0: np.ndarray, log_events: bool) -> Trajectory:
    t_start = time.perf_counter()
    z = np.zeros(8)
    z[:6] = y0
    sec = np.empty((n + 1, 6))
    sec[0] = y0
    mode = np.array([FREE], dtype=np.int64)
    counters = np.zeros(3)
    log = _new_log(4 * MAX_SWITCHES) if log_events else _empty_log()
    m, start = 0, True
    while True:
        m, code, tf = mdl.run(z, mode, m, n, start, sec, log, counters)
        start = False
        if code != BUFFER_FULL:
            break
        grown = _new_log(2 * log[0].size)
        k = int(counters[0])
        for old, new in zip(log, grown, strict=True):
            new[:k] = old[:k]
        log = grown
    nev = int(counters[0])
    events = []
    if log_events:
        events = [
            Event(float(t), KIND_NAMES[k], PHASE_NAMES[b], PHASE_NAMES[a])
            for t, k, b, a in zip(*(x[:nev] for x in log), strict=True)
        ]
    ok = code == OK
    msg = (
        f"{n} cycles of the coupled model (ρ = {mdl.coupling.rho:.6g}, χ = "
        f"{mdl.coupling.chi:.6g}), step {mdl.step:.3g}"
        if ok
        else _MESSAGES[code].format(n=MAX_SWITCHES, m=m, t=tf) + "; the sections before it are kept"
    )
    sec = sec[: m + 1].copy()
    return Trajectory(
        status="success" if ok else "failed",
        message=msg,
        n_cycles=m,
        n_events=nev,
        n_root_evals=int(counters[1]),
        elapsed_s=time.perf_counter() - t_start,
        params=mdl.p,
        solver="coupled-exact",
        s=float(sec[-1, 4]),
        delta_s=np.diff(sec[:, 4]),
        section=sec,
        events=events,
        n_fev=int(counters[2]),
        engine="compiled" if _jit() else "python",
    )


def _jit() -> bool:
    from betvdesign.dynamics.jit import jit_enabled

    return jit_enabled()


def section_map(
    mdl: CoupledModel, x: np.ndarray, period: int, counters: np.ndarray
) -> tuple[np.ndarray, float, str]:
    """The section map over ``period`` cycles of x = (ξ, ξ', ζ, ζ', s').

    Parameters
    ----------
    mdl : CoupledModel
        The model.
    x : numpy.ndarray
        (ξ, ξ', ζ, ζ', s') [-] at τ = 0 (s = 0).
    period : int
        Cycles [-].
    counters : numpy.ndarray
        [events, root evaluations, steps], added to.

    Returns
    -------
    tuple
        (map(x), Δs per cycle [-], error message or "").
    """
    z = np.zeros(8)
    z[[0, 1, 2, 3, 5]] = x
    sec = np.empty((period + 1, 6))
    mode = np.array([FREE], dtype=np.int64)
    m, code, tf = mdl.run(z, mode, 0, period, True, sec, _empty_log(), counters)
    if code != OK:
        return x, math.nan, _MESSAGES[code].format(n=MAX_SWITCHES, m=m, t=tf)
    return z[[0, 1, 2, 3, 5]].copy(), float(z[4]) / period, ""


def coupled_periodic_orbit(
    p: ModelParams,
    coupling: HeadCoupling,
    *,
    guess: object = None,
    period: int = 1,
    transient: int = 40,
    tol: float = 1e-10,
    max_newton: int = 30,
    restarts: int = MAX_RESTARTS,
) -> PeriodicResult:
    """Periodic orbit of the coupled model: Newton shooting on the exact section map.

    The unknown is x = (ξ, ξ', ζ, ζ', s') at τ = 0 (the slider position drifts); the
    residual map(x) − x over ``period`` cycles (:func:`section_map`), its Jacobian by
    forward differences (steps 1e-7·max(1, |x_i|), ξ stepped upward), the step by least
    squares (the plastic impact makes the map flat in ξ'), halved while the residual
    grows; when no step helps, ``transient`` iterations of the map and Newton again (at
    most ``restarts`` times). Converged when ‖map(x) − x‖∞ ≤ tol; accepted
    ("success") only when stable: the Floquet multipliers, eigenvalues of the map's
    Jacobian at the fixed point (over the five unknowns), all of modulus below 1, as the
    exact decoupled orbit (an unstable orbit: "not_converged" saying so, with its
    multipliers). At ρ = 0 exactly: :func:`betvdesign.dynamics.periodic_orbit` (the exact
    decoupled orbit), unchanged.

    Parameters
    ----------
    p, coupling
        The model (as :func:`simulate_coupled`).
    guess : sequence of 6 floats, optional
        (ξ, ξ', ζ, ζ', s, s') [-] to start Newton from (e.g. the decoupled orbit's
        state); default: the state after ``transient`` cycles from rest.
    period : int
        Period [cycles] (≥ 1).
    transient : int
        Cycles from rest before Newton when no guess is given [-], and map iterations
        before a restart.
    tol : float
        Accepted residual [-].
    max_newton : int
        Newton iterations at most [-].
    restarts : int
        Restarts after ``transient`` map iterations at most [-].

    Returns
    -------
    PeriodicResult
        "success" with Δs, mode, state and multipliers; "not_converged" or "failed" with
        the reason (``residual``: the best reached).

    Raises
    ------
    ParameterError
        For invalid parameters, period, transient or guess.
    """
    from betvdesign.dynamics.periodic import periodic_orbit

    if not isinstance(coupling, HeadCoupling):
        raise ParameterError(f"coupling must be a HeadCoupling, got {type(coupling).__name__}")
    if coupling.rho == 0.0:
        return periodic_orbit(p, tol=tol)
    mdl = CoupledModel(p, coupling)
    if isinstance(period, bool) or not isinstance(period, (int, np.integer)) or period < 1:
        raise ParameterError(f"period must be an integer ≥ 1, got {period!r}")
    check_cycles(transient)
    if guess is not None:
        g = np.array(guess, dtype=float).reshape(-1)
        if g.shape != (6,) or not np.all(np.isfinite(g)) or g[0] < 0.0:
            raise ParameterError(f"guess must be 6 finite numbers with ξ ≥ 0, got {guess!r}")
        guess = g
    return compile_note(  # type: ignore[return-value]
        "coupled_periodic_orbit",
        lambda: _orbit(mdl, guess, int(period), int(transient), tol, max_newton, restarts),
    )


def _orbit(
    mdl: CoupledModel,
    guess: np.ndarray | None,
    period: int,
    transient: int,
    tol: float,
    max_newton: int,
    max_restarts: int,
) -> PeriodicResult:
    t_start = time.perf_counter()
    counters = np.zeros(3)
    cyc = [0]

    def fmap(x: np.ndarray) -> tuple[np.ndarray, float, str]:
        cyc[0] += period
        return section_map(mdl, x, period, counters)

    def fail(status: str, msg: str, res: float, it: int) -> PeriodicResult:
        return PeriodicResult.failure(
            mdl.p, status, msg, residual=res, n_newton=it, n_cycles=cyc[0],  # type: ignore[arg-type]
            n_events=int(counters[0]), n_root_evals=int(counters[1]),
            elapsed_s=time.perf_counter() - t_start,
        )  # fmt: skip

    if guess is None:
        z = np.zeros(8)
        sec = np.empty((transient + 1, 6))
        mode = np.array([FREE], dtype=np.int64)
        m, code, tf = mdl.run(z, mode, 0, transient, True, sec, _empty_log(), counters)
        cyc[0] += m
        if code != OK:
            return fail("failed", _MESSAGES[code].format(n=MAX_SWITCHES, m=m, t=tf), math.inf, 0)
        y0 = z[:6].copy()
    else:
        y0 = guess
    x = np.array([y0[0], y0[1], y0[2], y0[3], y0[5]])
    fx, ds, err = fmap(x)
    if err:
        return fail("failed", err, math.inf, 0)
    r = fx - x
    res = float(np.max(np.abs(r)))
    best, restarts = res, 0
    for it in range(1, max_newton + 1):
        if res <= tol:
            return _accept(mdl, x, ds, res, period, it - 1, fmap, fail, cyc, counters, t_start)
        J, err = _jacobian(fmap, x, r)
        if J is None:
            return fail("failed", err, best, it)
        dx = np.linalg.lstsq(J, -r, rcond=1e-12)[0]
        lam = 1.0
        for _ in range(12):
            xn = x + lam * dx
            if xn[0] < 0.0:
                xn[0] = 0.0
            fn, dsn, err = fmap(xn)
            if not err:
                rn = fn - xn
                resn = float(np.max(np.abs(rn)))
                if resn < res or resn <= tol:
                    break
            lam *= 0.5
        else:  # no step lowers the residual: iterate the map (a stable orbit attracts)
            if restarts >= max_restarts:
                return fail(
                    "not_converged", f"no Newton step lowers the residual {res:.2e}", best, it
                )
            restarts += 1
            for _ in range(transient):
                xn, dsn, err = fmap(x)
                if err:
                    return fail("failed", err, best, it)
                x = xn
            xn = x
            fx, dsn, err = fmap(xn)
            if err:
                return fail("failed", err, best, it)
            rn, resn = fx - xn, float(np.max(np.abs(fx - xn)))
        x, r, res, ds = xn, rn, resn, dsn
        best = min(best, res)
    if res <= tol:
        return _accept(mdl, x, ds, res, period, max_newton, fmap, fail, cyc, counters, t_start)
    return fail(
        "not_converged", f"residual {res:.2e} after {max_newton} Newton steps", best, max_newton
    )


def _jacobian(fmap: Callable, x: np.ndarray, r: np.ndarray) -> tuple[np.ndarray | None, str]:
    """Forward-difference Jacobian of map(x) − x (steps 1e-7·max(1, |x_i|)); or the error."""
    J = np.empty((5, 5))
    for i in range(5):
        h = 1e-7 * max(1.0, abs(x[i]))
        xi = x.copy()
        xi[i] += h
        fi, _, err = fmap(xi)
        if err:
            return None, err
        J[:, i] = ((fi - xi) - r) / h
    return J, ""


def _accept(
    mdl: CoupledModel,
    x: np.ndarray,
    ds: float,
    res: float,
    period: int,
    it: int,
    fmap: Callable,
    fail: Callable,
    cyc: list,
    counters: np.ndarray,
    t_start: float,
) -> PeriodicResult:
    """The converged fixed point x: its Floquet multipliers; "success" only when stable.

    The multipliers are the eigenvalues of the map's Jacobian at x (forward differences
    over the five unknowns); an unstable orbit (some |μ| ≥ 1) is no answer the device
    settles to: "not_converged", saying so.
    """
    fx, _, err = fmap(x)
    if err:
        return fail("failed", err, res, it)
    jac, err = _jacobian(fmap, x, fx - x)
    if jac is None:
        return fail("failed", err, res, it)
    mu = np.linalg.eigvals(jac + np.eye(5))
    floquet = mu[np.argsort(-np.abs(mu), kind="stable")]
    if not np.all(np.abs(mu) < 1.0):
        out = fail(
            "not_converged",
            f"the period-{period} orbit found (residual {res:.2e}, Δs {ds:.6g}) is unstable: "
            f"|μ|max = {abs(floquet[0]):.4g}; the motion settles elsewhere (another period, "
            "or none)",
            res,
            it,
        )
        return replace(out, floquet=floquet, stable=False)
    state = np.array([x[0], x[1], x[2], x[3], 0.0, x[4]])
    return PeriodicResult(
        status="success",
        message=f"coupled orbit: residual {res:.2e} after {it} Newton steps",
        params=mdl.p,
        delta_s=ds,
        mode=mode_of(ds),  # type: ignore[arg-type]
        period_cycles=period,
        residual=res,
        floquet=floquet,
        stable=True,
        state=state,
        n_newton=it,
        n_cycles=cyc[0],
        n_events=int(counters[0]),
        n_root_evals=int(counters[1]),
        elapsed_s=time.perf_counter() - t_start,
    )


#: cycles from rest before the periods are tried again (:func:`coupled_orbit`)
SETTLE_CYCLES = 150
#: its chunks: the transient stops at the first chunk whose last sections repeat
SETTLE_CHUNK = 50
#: periods [cycles] :func:`coupled_orbit` looks for in the transient's last sections
MAX_PERIOD = 4
#: Newton iterations of each :func:`coupled_orbit` attempt at most (the shipped and
#: drawn-only sets converge within 12)
ORBIT_NEWTON = 15
#: cycles :func:`coupled_crossing` simulates at most
CROSSING_HORIZON = 5000


def repeats(section: np.ndarray, max_period: int = MAX_PERIOD) -> int:
    """The smallest k ≤ max_period with which the last section states repeat (else 0).

    Parameters
    ----------
    section : numpy.ndarray
        Section states (ξ, ξ', ζ, ζ', s, s') [-], shape (m + 1, 6).
    max_period : int
        Periods tried [cycles].

    Returns
    -------
    int
        The period [cycles] the last states repeat with to 1e-6 (relative to max(1, |x|)),
        0 when none does.
    """
    last = section[-1][[0, 1, 2, 3, 5]]
    for k in range(1, min(max_period, len(section) - 1) + 1):
        back = section[-1 - k][[0, 1, 2, 3, 5]]
        if np.max(np.abs(last - back)) <= 1e-6 * max(1.0, float(np.max(np.abs(last)))):
            return k
    return 0


def coupled_orbit(
    p: ModelParams,
    coupling: HeadCoupling,
    *,
    decoupled: PeriodicResult | None = None,
    tol: float = 1e-8,
    transient: int = SETTLE_CYCLES,
    max_period: int = MAX_PERIOD,
) -> PeriodicResult:
    """The stable periodic orbit the coupled head settles to (what a verdict quotes).

    Newton (:func:`coupled_periodic_orbit`, at most :data:`ORBIT_NEWTON` iterations) from
    the decoupled model's orbit (its state and period); where that gives no stable orbit,
    from the state at most ``transient`` cycles from rest (in chunks of
    :data:`SETTLE_CHUNK`, until the last sections of one repeat) with the period they
    repeat with (:func:`repeats`); a transient that repeats with no period up to ``max_period``
    has not settled onto one, and no orbit is given (Newton from it only when the decoupled
    model has no orbit to start from). One restart of each Newton. At ρ = 0 exactly: the
    decoupled orbit itself.

    Parameters
    ----------
    p : ModelParams
        ϖ, α, β, κ (ideal).
    coupling : HeadCoupling
        ρ and χ.
    decoupled : PeriodicResult, optional
        The decoupled orbit of ``p`` (:func:`betvdesign.dynamics.periodic_orbit`), solved
        here when not given.
    tol : float
        Newton's accepted residual [-].
    transient : int
        Cycles from rest before the periods are tried again [-].
    max_period : int
        Periods tried [cycles].

    Returns
    -------
    PeriodicResult
        "success" (stable) or the last attempt's failure, ``transient_cycles`` and
        ``transient_s`` the transient's when it ran.

    Raises
    ------
    ParameterError
        For invalid parameters.
    """
    from betvdesign.dynamics.periodic import periodic_orbit

    if not isinstance(coupling, HeadCoupling):
        raise ParameterError(f"coupling must be a HeadCoupling, got {type(coupling).__name__}")
    ex = decoupled if decoupled is not None else periodic_orbit(p)
    if coupling.rho == 0.0:
        return ex
    t0 = time.perf_counter()
    orb = None
    if ex.status == "success":
        orb = coupled_periodic_orbit(
            p, coupling, guess=ex.state, period=int(ex.period_cycles or 1), tol=tol,
            max_newton=ORBIT_NEWTON, restarts=1,
        )  # fmt: skip
        if orb.status == "success":
            return orb
    y, done, k = None, 0, 0
    while done < transient and not k:  # chunks, until the last sections repeat
        n = min(SETTLE_CHUNK, transient - done)
        run = simulate_coupled(p, coupling, n, state0=y, log_events=False)
        if run.status != "success":
            return PeriodicResult.failure(
                p, "failed", f"the transient from rest failed: {run.message}",
                elapsed_s=time.perf_counter() - t0, n_cycles=done + run.n_cycles,
            )  # fmt: skip
        y, done = run.section[-1], done + n
        k = repeats(run.section, max_period)
    transient = done
    if k or orb is None:
        orb = coupled_periodic_orbit(
            p, coupling, guess=y, period=k or 1, tol=tol, max_newton=ORBIT_NEWTON, restarts=1,
        )  # fmt: skip
    return replace(
        orb,
        transient_cycles=transient,
        transient_s=float(y[4]),
        elapsed_s=time.perf_counter() - t0,
        message=orb.message
        if orb.status == "success"
        else f"no stable coupled orbit from the decoupled orbit, and {transient} cycles from "
        f"rest repeat with no period up to {max_period} ({orb.message})"
        if not k
        else f"no stable coupled orbit from the decoupled orbit nor from {transient} cycles "
        f"from rest (period {k}: {orb.message})",
    )


def coupled_crossing(
    p: ModelParams,
    coupling: HeadCoupling,
    travel_s: float,
    *,
    max_cycles: int = CROSSING_HORIZON,
    chunk: int = 256,
) -> Settling:
    """The coupled head's transient from rest across the travel range.

    The answer a verdict quotes where the coupled model has no stable orbit: the first
    cycle at which |s| reaches ``travel_s`` and the mean increment s/m up to it (MODEL.md
    "Slider": the decoupled check's crossing, with the coupled model), simulated in chunks
    of ``chunk`` cycles.

    Parameters
    ----------
    p, coupling
        The model (as :func:`simulate_coupled`).
    travel_s : float
        Travel range [-, units of u·cosθ].
    max_cycles : int
        Cycles simulated at most [-].
    chunk : int
        Cycles per kernel call [-].

    Returns
    -------
    Settling
        "not_settled" (no settling is judged) with ``cycles_to_cross`` and
        ``crossing_delta_s`` when it crosses within ``max_cycles``, None there otherwise;
        "failed" when a cycle could not be advanced.
    """
    t0 = time.perf_counter()
    y = None
    s_prev, done, nev, nroot = 0.0, 0, 0, 0
    while done < max_cycles:
        n = min(chunk, max_cycles - done)
        run = simulate_coupled(p, coupling, n, state0=y, log_events=False)
        nev, nroot = nev + run.n_events, nroot + run.n_root_evals
        s = run.section[:, 4]
        hit = np.nonzero(np.abs(s[1:]) >= travel_s)[0]
        if hit.size:
            m = done + int(hit[0]) + 1
            return Settling(
                status="not_settled",
                message=f"the coupled transient from rest crosses the travel in {m} cycles",
                cycles_to_settle=None, cycles_to_cross=m, crossing_delta_s=float(s[hit[0] + 1]) / m,
                n_cycles=m, n_events=nev, n_root_evals=nroot,
                elapsed_s=time.perf_counter() - t0,
            )  # fmt: skip
        if run.status != "success":
            return Settling(
                status="failed", message=f"the coupled transient failed: {run.message}",
                cycles_to_settle=None, cycles_to_cross=None, crossing_delta_s=None,
                n_cycles=done + run.n_cycles, elapsed_s=time.perf_counter() - t0,
            )  # fmt: skip
        y, done, s_prev = run.section[-1], done + n, float(s[-1])
    return Settling(
        status="not_settled",
        message=f"the coupled transient from rest does not cross the travel within {done} "
        f"cycles (s = {s_prev:.4g} of {travel_s:.4g})",
        cycles_to_settle=None, cycles_to_cross=None, crossing_delta_s=None, n_cycles=done,
        n_events=nev, n_root_evals=nroot, elapsed_s=time.perf_counter() - t0,
    )  # fmt: skip
