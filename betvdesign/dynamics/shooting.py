"""Newton shooting on the exact section map, compiled (unit-free).

docs/MODEL.md, "Slider"; the algorithm is described in :mod:`periodic`. The section map
Φⁿ: x = (ζ, ζ', s') at the first periodic cycle → n cycles later is the contact loop
(:func:`contact.run_cycles`); here, compiled with it, are its residual
‖Φⁿ(x) − x‖∞, its finite-difference Jacobian, the damped Newton iteration, the
Anderson-accelerated start, the Floquet multipliers and the whole search from rest
(:func:`orbit`), so that a periodic solve crosses from Python into compiled code once.
The map's functions take its arguments :data:`SHOT` first.
"""

from __future__ import annotations

import math

import numpy as np
from numba import types
from numba.extending import overload
from numba.np.linalg import _LAPACK, ensure_lapack

from betvdesign.dynamics.contact import LOG_DTYPE, OK, SEG_DTYPE, run_cycles
from betvdesign.dynamics.jit import kernel
from betvdesign.dynamics.schedule import cycle_rows

#: forward-difference step of the Jacobian (relative to max(1, |x_i|))
FD_STEP = 1e-7
#: Newton iterations at most
MAX_NEWTON = 25
#: trust region: steps at most TRUST·(1 + ‖x‖∞)
TRUST = 2.0


#: The map's arguments, in this order (one design, one period n, built by
#: :func:`orbit`): ``table`` (:func:`flows.phase_table`); the vertical schedule's
#: ``tab`` and ``imp`` and the rows ``idx`` of the n cycles from cycle ``m0``; empty
#: ``rows``, ``log`` and ``segs`` buffers; ``count`` = [cycles, events, evaluations]
#: (accumulated). Plain arrays: handing them to compiled code costs little.
SHOT = ("table", "tab", "idx", "imp", "m0", "rows", "log", "segs", "count")


@kernel
def section_map(table, tab, idx, imp, m0, rows, log, segs, count, x):
    """The section map Φⁿ over n cycles.

    Parameters
    ----------
    table, tab, idx, imp, m0, rows, log, segs, count
        The map's arguments (:data:`SHOT`): n = idx.size cycles from cycle m0; ``count``
        accumulates [cycles, events, evaluations].
    x : numpy.ndarray
        Section state (ζ, ζ', s') [-].

    Returns
    -------
    tuple of (bool, numpy.ndarray, float)
        (ok, Φⁿ(x) = (ζ, ζ', s') after n cycles [-], slider increment s [-]); ok False
        when a contact could not be advanced.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
    """
    run = run_cycles(
        table, tab, idx, imp, m0, x[0], x[1], 0.0, x[2], rows, False, log, -1, segs, -1
    )
    count[1] += run.events
    count[2] += run.evals
    y = np.empty(3)
    y[0], y[1], y[2] = run.z, run.zd, run.sd
    s = run.s
    if run.code != OK:
        return False, y, s
    count[0] += idx.size
    return True, y, s


@kernel
def residual(table, tab, idx, imp, m0, rows, log, segs, count, x):
    """The fixed-point residual of the section map.

    Parameters
    ----------
    table, tab, idx, imp, m0, rows, log, segs, count
        The map's arguments (:data:`SHOT`): n = idx.size cycles from cycle m0; ``count``
        accumulates [cycles, events, evaluations].
    x : numpy.ndarray
        Section state (ζ, ζ', s') [-].

    Returns
    -------
    tuple of (float, numpy.ndarray, float)
        (‖Φⁿ(x) − x‖∞ [-], Φⁿ(x), s [-]); (inf, x, NaN) when the map fails, inf when the
        state is non-finite.
    """
    ok, y, s = section_map(table, tab, idx, imp, m0, rows, log, segs, count, x)
    if not ok:
        return math.inf, x, math.nan
    r = 0.0
    for i in range(3):
        g = abs(y[i] - x[i])
        if g != g:
            return math.inf, y, s
        if g > r:
            r = g
    return (r if r < math.inf else math.inf), y, s


@kernel
def jacobian(table, tab, idx, imp, m0, rows, log, segs, count, x, y, central):
    """Finite-difference Jacobian of Φⁿ at x (forward from y = Φⁿ(x), or central).

    Parameters
    ----------
    table, tab, idx, imp, m0, rows, log, segs, count
        The map's arguments (:data:`SHOT`): n = idx.size cycles from cycle m0; ``count``
        accumulates [cycles, events, evaluations].
    x, y : numpy.ndarray
        Section state (ζ, ζ', s') [-] and its image Φⁿ(x).
    central : bool
        Central differences (Floquet multipliers) instead of forward ones (Newton).

    Returns
    -------
    tuple of (bool, numpy.ndarray)
        (ok, J (3, 3) [-]); ok False when a contact could not be advanced.
    """
    J = np.empty((3, 3))
    for i in range(3):
        h = FD_STEP * max(1.0, abs(x[i]))
        xp = x.copy()
        xp[i] += h
        ok, yp, _ = section_map(table, tab, idx, imp, m0, rows, log, segs, count, xp)
        if not ok:
            return False, J
        if central:
            xm = x.copy()
            xm[i] -= h
            ok, ym, _ = section_map(table, tab, idx, imp, m0, rows, log, segs, count, xm)
            if not ok:
                return False, J
            for r in range(3):
                J[r, i] = (yp[r] - ym[r]) / (2.0 * h)
        else:
            for r in range(3):
                J[r, i] = (yp[r] - y[r]) / h
    return True, J


@kernel
def newton(table, tab, idx, imp, m0, rows, log, segs, count, x, tol, polish):
    """Newton on Φⁿ(x) − x = 0.

    Gives up after two iterations in a row that do not halve the residual (not in
    Newton's basin yet: more brute force is cheaper). Once the residual is ≤ tol it goes
    on while the residual keeps halving, down to ``polish``. Steps are limited to the
    trust region TRUST·(1 + ‖x‖∞) (a step far beyond the state's own size leaves the
    region where the linearisation holds) and halved until the residual falls.

    Parameters
    ----------
    table, tab, idx, imp, m0, rows, log, segs, count
        The map's arguments (:data:`SHOT`): n = idx.size cycles from cycle m0; ``count``
        accumulates [cycles, events, evaluations].
    x : numpy.ndarray
        Start (ζ, ζ', s') [-].
    tol : float
        Accepted residual [-].
    polish : float
        Residual [-] down to which a converging iteration goes on.

    Returns
    -------
    tuple of (numpy.ndarray, float, float, int)
        (x, residual [-], slider increment s [-], iterations).

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773 (the slider settles to a
    periodic motion).
    """
    r, y, s = residual(table, tab, idx, imp, m0, rows, log, segs, count, x)
    it = 0
    slow = 0
    while it < MAX_NEWTON and r > polish and r < math.inf and slow < 2:
        it += 1
        r_prev = r
        ok, J = jacobian(table, tab, idx, imp, m0, rows, log, segs, count, x, y, False)
        if not ok:
            break
        for i in range(3):
            J[i, i] -= 1.0
        try:
            dx = np.linalg.solve(J, x - y)
        except Exception:  # singular: as numpy's LinAlgError
            break
        size = 0.0
        xmax = 0.0
        for i in range(3):
            size = max(size, abs(dx[i]))
            xmax = max(xmax, abs(x[i]))
        lam = min(1.0, TRUST * (1.0 + xmax) / size) if size > 0 else 1.0
        moved = False
        for _ in range(12):
            xn = x + lam * dx
            rn, yn, sn = residual(table, tab, idx, imp, m0, rows, log, segs, count, xn)
            if rn < r:
                x, r, y, s = xn, rn, yn, sn
                moved = True
                break
            lam *= 0.5
        if not moved:
            break
        slow = slow + 1 if r > 0.5 * r_prev else 0
        if r <= tol and slow:
            break
    return x, r, s, it


#: Newton goes on while it keeps halving the residual, down to this [-].
POLISH = 1e-14
#: Anderson acceleration: differences kept, map evaluations allowed, evaluations without a
#: new best residual before giving up, residual at which Newton takes over.
ANDERSON_DEPTH = 5
ANDERSON_BUDGET = 600
ANDERSON_STALL = 24
ANDERSON_HANDOFF = 1e-8
#: Bisection steps on the slider velocity when Anderson stalls (:func:`bracket_slider`).
BRACKET_BISECT = 40

#: :func:`orbit` outcomes: a stable orbit accepted; the cycle budget spent; the proven
#: resonant growth measured; the transient from rest, a brute-force chunk or the Floquet
#: Jacobian could not be advanced; the state became non-finite.
FOUND, NOT_CONVERGED, UNBOUNDED, REST_FAILED, CHUNK_FAILED, FLOQUET_FAILED, NON_FINITE = range(7)


def real_eigvals(J):
    """Eigenvalues of a real square matrix by LAPACK ``dgeev``: (real parts, imaginary parts).

    As Python this is :func:`numpy.linalg.eigvals` (numpy's ``dgeev``); compiled, the same
    LAPACK routine is called through numba's own binding (:func:`_real_eigvals_compiled`),
    because numba's ``eigvals`` of a real matrix refuses complex eigenvalues. Both give the
    same bits (measured on 2·10⁵ random 3×3 matrices).

    Parameters
    ----------
    J : numpy.ndarray
        (n, n) real matrix, finite.

    Returns
    -------
    tuple of numpy.ndarray
        Real and imaginary parts of the eigenvalues [-], in LAPACK's order (a complex pair
        with the positive imaginary part first).

    Raises
    ------
    numpy.linalg.LinAlgError
        For a non-finite matrix, or when ``dgeev`` does not converge.
    """
    w = np.linalg.eigvals(J)
    return w.real.copy(), np.imag(w).copy()


@overload(real_eigvals)
def _real_eigvals_compiled(J):
    """Compiled :func:`real_eigvals`: numba's binding of LAPACK ``dgeev`` (no eigenvectors).

    The matrix is copied in Fortran order and ``dgeev`` called with a workspace query,
    as numpy does.
    """
    ensure_lapack()
    rgeev = _LAPACK().numba_ez_rgeev(types.float64)
    kind, no = ord("d"), ord("N")  # constants here: no string handling compiled

    def impl(J):
        n = J.shape[0]
        a = np.empty((n, n)).T  # Fortran order, as LAPACK reads it
        for i in range(n):
            for j in range(n):
                v = J[i, j]
                if not math.isfinite(v):
                    raise np.linalg.LinAlgError("Array must not contain infs or NaNs")
                a[i, j] = v
        wr, wi = np.empty(n), np.empty(n)
        vl, vr = np.empty(1), np.empty(1)  # not referenced (no eigenvectors)
        info = rgeev(kind, no, no, n, a.ctypes, n, wr.ctypes, wi.ctypes, vl.ctypes, 1, vr.ctypes, 1)
        if info != 0:
            raise np.linalg.LinAlgError("Eigenvalues did not converge")
        return wr, wi

    return impl


@kernel
def floquet(J):
    """Floquet multipliers of a section map's Jacobian, by decreasing modulus.

    Parameters
    ----------
    J : numpy.ndarray
        (3, 3) Jacobian of Φⁿ at the fixed point [-].

    Returns
    -------
    tuple of numpy.ndarray
        Real and imaginary parts of the multipliers [-], ordered as
        ``mu[np.argsort(-np.abs(mu))]`` orders them (a stable sort: ties, such as a complex
        pair, keep LAPACK's order), and their moduli [-].
    """
    wr, wi = real_eigvals(J)
    n = wr.size
    mod = np.empty(n)
    for i in range(n):
        mod[i] = math.hypot(wr[i], wi[i])
    for i in range(1, n):  # insertion sort on −|μ|, stable
        a, b, m = wr[i], wi[i], mod[i]
        k = i
        while k > 0 and -mod[k - 1] > -m:
            wr[k], wi[k], mod[k] = wr[k - 1], wi[k - 1], mod[k - 1]
            k -= 1
        wr[k], wi[k], mod[k] = a, b, m
    return wr, wi, mod


@kernel
def _max_abs(a, b):
    """The largest |a − b| over the elements; NaN when any difference is (as ``np.max``)."""
    far = 0.0
    for i in range(a.size):
        d = abs(a[i] - b[i])
        if d != d or d > far:
            far = d
    return far


@kernel(inline=True)
def anderson(table, tab, idx, imp, m0, rows, log, segs, count, x, budget):
    """A start for Newton from iterate ``x``: Anderson-accelerated iteration of Φⁿ.

    Plain iteration settles at the rate |μ|max per period (≥ 0.99 near ϖ → 2: thousands of
    cycles), and Newton fails far from the orbit because the map is only piecewise smooth
    (far out a whole contact slips one way: s' is then neutral and J − I singular).
    Anderson mixing (type II, depth :data:`ANDERSON_DEPTH`) extrapolates from the last
    iterates; every extrapolated point must stay in the trust region around the starting
    iterate (Newton's) — else the history is dropped and the plain image taken.
    This keeps it off the round-off "fixed points" at |s'| ~ 1e14, where a whole contact
    slips one way and the slider's increment falls below the ulp of s'.
    Never accepts anything itself: Newton's residual test decides.

    Parameters
    ----------
    table, tab, idx, imp, m0, rows, log, segs, count
        The map's arguments (:data:`SHOT`): n = idx.size cycles from cycle m0; ``count``
        accumulates [cycles, events, evaluations].
    x : numpy.ndarray
        The iterate to start from (ζ, ζ', s') [-].
    budget : int
        Map evaluations allowed [cycles] (:data:`ANDERSON_BUDGET`).

    Returns
    -------
    tuple of (bool, numpy.ndarray)
        (found, the best point): its residual ≤ :data:`ANDERSON_HANDOFF`, or the stalled
        best point moved by :func:`bracket_slider`; found False when there is none.
    """
    n = idx.size
    depth = ANDERSON_DEPTH + 1
    X = np.empty((depth, 3))  # the last iterates and their steps f = Φⁿ(x) − x
    F = np.empty((depth, 3))
    k = 0
    best, best_r, since = x, math.inf, 0
    x0, radius = x, TRUST * (1.0 + _max_abs(x, np.zeros(3)))
    eps = np.finfo(np.float64).eps
    for _ in range(budget // n):
        r, y, _ = residual(table, tab, idx, imp, m0, rows, log, segs, count, x)
        if not math.isfinite(r):
            return False, x
        if r < best_r:
            best, best_r, since = x, r, 0
            if r <= ANDERSON_HANDOFF:
                return True, best
        else:
            since += n
            if since > ANDERSON_STALL:
                break
        f = y - x
        if k == depth:  # drop the oldest
            for j in range(depth - 1):
                X[j], F[j] = X[j + 1], F[j + 1]
            k -= 1
        X[k], F[k] = x, f
        k += 1
        xn = y
        if k > 1:
            m = k - 1
            dFt, Mt = np.empty((m, 3)), np.empty((m, 3))  # their transposes: Fortran order
            for j in range(m):
                for i in range(3):
                    dFt[j, i] = F[j + 1, i] - F[j, i]
                    Mt[j, i] = (X[j + 1, i] - X[j, i]) + dFt[j, i]
            try:
                g = np.linalg.lstsq(dFt.T, f, rcond=eps * max(3, m))[0]
                xn = y - Mt.T @ g  # as numpy's (dX + dF) @ g: the same BLAS gemv
            except Exception:  # as numpy's LinAlgError
                xn = y
            if not (_max_abs(xn, x0) <= radius):
                k, xn = 0, y
        x = xn
    if best_r == math.inf:
        return False, x
    return bracket_slider(table, tab, idx, imp, m0, rows, log, segs, count, best, radius)


@kernel(inline=True)
def bracket_slider(table, tab, idx, imp, m0, rows, log, segs, count, x, radius):
    """Move s' alone to where its increment over n cycles changes sign (bisection).

    Where a whole contact slips one way the slider's velocity s' does not act on the head
    (ζ, ζ'), so Anderson stalls with ζ, ζ' settled and a constant s' increment c ≠ 0.
    A periodic orbit needs the friction to change sign within the contact, i.e. s' inside
    the range of ζ' there: s' is walked (doubling steps, within ``radius``) in the
    direction of c until the increment changes sign, then bisected on that sign
    (:data:`BRACKET_BISECT` steps).

    Parameters
    ----------
    table, tab, idx, imp, m0, rows, log, segs, count
        The map's arguments (:data:`SHOT`).
    x : numpy.ndarray
        The stalled point (ζ, ζ', s') [-].
    radius : float
        The trust region's radius [-].

    Returns
    -------
    tuple of (bool, numpy.ndarray)
        (found, the point moved); found False when no sign change lies within ``radius``
        or the map fails.
    """
    r, y, _ = residual(table, tab, idx, imp, m0, rows, log, segs, count, x)
    if not math.isfinite(r):
        return False, x
    c = y[2] - x[2]
    if c == 0.0:
        return True, x
    lo, hi, bracketed = x[2], 0.0, False
    step = 0.01 * (1.0 + abs(x[1]))
    while step <= radius:
        xt = x.copy()
        xt[2] = lo + math.copysign(step, c)
        rt, yt, _ = residual(table, tab, idx, imp, m0, rows, log, segs, count, xt)
        if not math.isfinite(rt):
            return False, x
        if (yt[2] - xt[2]) * c <= 0.0:
            hi, bracketed = xt[2], True
            break
        step *= 2.0
    if not bracketed:
        return False, x
    lo = hi - math.copysign(step, c) if step > 0.01 * (1.0 + abs(x[1])) else lo
    for _ in range(BRACKET_BISECT):
        mid = 0.5 * (lo + hi)
        xt = x.copy()
        xt[2] = mid
        rt, yt, _ = residual(table, tab, idx, imp, m0, rows, log, segs, count, xt)
        if not math.isfinite(rt):
            return False, x
        if (yt[2] - xt[2]) * c > 0.0:
            lo = mid
        else:
            hi = mid
    x = x.copy()
    x[2] = 0.5 * (lo + hi)
    return True, x


@kernel(inline=True)
def measure_growth(table, tab, imp, m0, kv, rows, log, segs, count, x, bound, window):
    """Check a proven per-cycle fall of ζ by iterating the map.

    Iterate about ``window`` cycles (at least ``kv``) from ``x`` in steps of the vertical
    period ``kv``, while every step's fall of ζ is at least ``kv`` times the proven
    per-cycle ``bound`` (up to round-off); else the bound is not borne out (e.g. a solver
    defect: then the normal search decides).

    Parameters
    ----------
    table, tab, imp, m0, rows, log, segs, count
        The map's arguments (:data:`SHOT`), its cycles from m0 (the first periodic one).
    kv : int
        The vertical period [cycles].
    x : numpy.ndarray
        The section state (ζ, ζ', s') [-] to start from.
    bound : float
        The proven fall of ζ per cycle [-] (:func:`periodic.resonance_growth_bound`).
    window : int
        Cycles to measure over [-].

    Returns
    -------
    tuple of (bool, float, int, float, float)
        (borne out, mean fall of ζ per cycle [-], cycles, final amplitude
        sqrt(ζ² + (ζ'/ϖ)²) [-], s gained [-]).
    """
    varpi = table[0].varpi
    z0 = x[0]
    steps = max(1, window // kv)
    s_total = 0.0
    idx = cycle_rows(np.arange(m0, m0 + kv), m0, kv)
    for _ in range(steps):
        z_prev = x[0]
        ok, x, s = section_map(table, tab, idx, imp, m0, rows, log, segs, count, x)
        if not ok:
            return False, 0.0, 0, 0.0, 0.0
        s_total += s
        if z_prev - x[0] < kv * bound - 1e-9 * max(1.0, abs(z_prev)):
            return False, 0.0, 0, 0.0, 0.0
    for i in range(3):
        if not math.isfinite(x[i]):
            return False, 0.0, 0, 0.0, 0.0
    n = steps * kv
    return True, (z0 - x[0]) / n, n, math.hypot(x[0], x[1] / varpi), s_total


@kernel(inline=True)
def newton_period(table, tab, idx, imp, m0, rows, log, segs, count, x, tol, accelerate, budget):
    """Newton for a fixed point of Φⁿ from ``x``, restarted from Anderson when asked.

    Parameters
    ----------
    table, tab, idx, imp, m0, rows, log, segs, count
        The map's arguments (:data:`SHOT`): the period tried n = idx.size [cycles].
    x : numpy.ndarray
        The start (ζ, ζ', s') [-].
    tol : float
        The residual asked [-].
    accelerate : bool
        Restart from :func:`anderson` when Newton alone does not reach ``tol`` (once per
        period: the caller asks once).
    budget : int
        :func:`anderson`'s map evaluations [cycles].

    Returns
    -------
    tuple of (numpy.ndarray, float, float, int, bool)
        The state [-], its residual [-], the travel over n cycles [-], the Newton
        iterations and whether Anderson ran.
    """
    xs, r, s, it = newton(table, tab, idx, imp, m0, rows, log, segs, count, x.copy(), tol, POLISH)
    ran = False
    if r > tol and accelerate:
        ran = True
        ok, xa = anderson(table, tab, idx, imp, m0, rows, log, segs, count, x.copy(), budget)
        if ok:
            xs, r, s, it2 = newton(
                table, tab, idx, imp, m0, rows, log, segs, count, xa, tol, POLISH
            )
            it += it2
    return xs, r, s, it, ran


@kernel
def orbit(table, tab, imp, m0, kv, tol, max_cycles, max_period, transient, bound, window, budget):
    """The periodic orbit's whole search, from rest (:func:`periodic.periodic_orbit`).

    The transient from rest to the first periodic cycle m0 of the vertical motion; where
    ``bound`` is given (the proven growth at the free-flight resonance), a window of
    growth measured (:func:`measure_growth`); then chunks of brute-force iteration
    (``transient`` cycles, doubling up to ``max_cycles``), each followed by Newton for
    every period j·kv, j ≤ ``max_period`` (:func:`newton_period`, restarted once per period
    from :func:`anderson`); a fixed point is reduced to its shortest period and accepted
    only when stable (Floquet multipliers of the central-difference Jacobian,
    :func:`floquet`) and periodic to ``tol`` in full, vertical state included.

    Parameters
    ----------
    table : numpy.ndarray
        :func:`flows.phase_table`.
    tab, imp : numpy.ndarray
        The vertical schedule's cycles (a prefix of m0 rows, then one period of ``kv``)
        and impulsive-hit times [-].
    m0 : int
        The first cycle of the vertical period.
    kv : int
        The vertical period [cycles].
    tol : float
        The residual asked [-].
    max_cycles, max_period, transient : int
        As :func:`periodic.periodic_orbit`'s.
    bound : float
        The proven fall of ζ per cycle [-] at the resonance, NaN where none is proven.
    window : int
        Cycles over which that growth is measured [-].
    budget : int
        :func:`anderson`'s map evaluations [cycles].

    Returns
    -------
    tuple
        (outcome, state, multipliers, floats, ints, count): the outcome (:data:`FOUND`,
        :data:`NOT_CONVERGED`, :data:`UNBOUNDED`, :data:`REST_FAILED`,
        :data:`CHUNK_FAILED`, :data:`FLOQUET_FAILED`, :data:`NON_FINITE`); the fixed
        point (ζ, ζ', s') [-] (the start of the map that failed, for the failures); the
        multipliers' real parts, imaginary parts and moduli, by decreasing modulus, (3, 3)
        [-]; floats: [residual, travel over the period, travel of the transient, vertical
        section state ξ, ξ', growth per cycle, amplitude, travel in the growth window] [-];
        ints: [period, Newton iterations, transient cycles, period of the best residual,
        cycles measured for growth / of the map that failed, Anderson restarts]; the map's
        counters [cycles, events, root evaluations].

    Notes
    -----
    Over 80 lines on purpose: the one compiled entry point of the periodic search (the
    Python glue around six kernel calls cost twice the kernels), carrying the state,
    the best residual, the counters and the periods already accelerated through it; its
    numbers are pinned bit for bit by ``benchmarks/snapshot.py``.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773 (the slider settles to a
    periodic motion of the actuator's period).
    """
    rows = np.empty((0, 4))
    log = np.empty(0, LOG_DTYPE)
    segs = np.empty(0, SEG_DTYPE)
    count = np.zeros(3, np.int64)  # cycles, events, evaluations of the periodic map
    mu = np.zeros((3, 3))
    fo = np.zeros(8)
    io = np.zeros(6, np.int64)
    # from rest to the first periodic cycle (its own counters, not the map's)
    x = np.zeros(3)
    idx = cycle_rows(np.arange(0, m0), m0, kv)
    rest = np.zeros(3, np.int64)
    ok, xr, s_total = section_map(table, tab, idx, imp, 0, rows, log, segs, rest, x)
    if not ok:
        io[4] = m0
        return REST_FAILED, x, mu, fo, io, count
    x = xr
    if bound == bound:
        grown, rate, n, amp, s_win = measure_growth(
            table, tab, imp, m0, kv, rows, log, segs, count, x.copy(), bound, window
        )
        if grown:
            fo[2], fo[5], fo[6], fo[7] = s_total, rate, amp, s_win
            io[4] = n
            return UNBOUNDED, x, mu, fo, io, count
    brute = m0
    chunk = max(kv, (transient // kv) * kv)
    n_newton = 0
    accelerated = np.zeros(max_period + 1, np.bool_)
    best_r, best_n = math.inf, kv
    while True:
        idx = cycle_rows(np.arange(m0, m0 + chunk), m0, kv)
        ok, y, s_chunk = section_map(table, tab, idx, imp, m0, rows, log, segs, count, x)
        if not ok:
            fo[2] = s_total
            io[2], io[4] = brute, chunk
            return CHUNK_FAILED, x, mu, fo, io, count
        x = y
        s_total += s_chunk
        brute += chunk
        if not (math.isfinite(x[0]) and math.isfinite(x[1]) and math.isfinite(x[2])):
            io[2] = brute
            return NON_FINITE, x, mu, fo, io, count
        for j in range(1, max_period + 1):
            n = j * kv
            idx = cycle_rows(np.arange(m0, m0 + n), m0, kv)
            xs, r, s, it, ran = newton_period(
                table, tab, idx, imp, m0, rows, log, segs, count, x, tol, not accelerated[j],
                budget,
            )  # fmt: skip
            accelerated[j] = accelerated[j] or ran
            n_newton += it
            if r < best_r:
                best_r, best_n = r, n
            if r > tol:
                continue
            for d in range(1, j):  # a period-n fixed point may have a shorter period
                if j % d == 0:
                    idd = cycle_rows(np.arange(m0, m0 + d * kv), m0, kv)
                    xd, rd, sd, itd = newton(
                        table, tab, idd, imp, m0, rows, log, segs, count, xs.copy(), tol, POLISH
                    )
                    n_newton += itd
                    if rd <= tol and _max_abs(xd, xs) <= 1e3 * tol:
                        xs, r, s, n, idx = xd, rd, sd, d * kv, idd
                        break
            ok, J = jacobian(table, tab, idx, imp, m0, rows, log, segs, count, xs, xs, True)
            if not ok:
                io[1] = n_newton
                return FLOQUET_FAILED, xs, mu, fo, io, count
            wr, wi, mod = floquet(J)
            if mod[0] >= 1.0:
                continue  # an unstable orbit: not where the device settles
            r_final, _, s = residual(table, tab, idx, imp, m0, rows, log, segs, count, xs)
            ends = cycle_rows(np.array([m0, m0 + n]), m0, kv)
            a, b = tab[ends[0]], tab[ends[1]]
            vert = abs(b["xi0"] - a["xi0"]) + abs(b["xid0"] - a["xid0"])
            if vert > r_final:
                r_final = vert
            if r_final > tol:
                continue
            mu[0], mu[1], mu[2] = wr, wi, mod
            fo[0], fo[1], fo[2], fo[3], fo[4] = r_final, s, s_total, a["xi0"], a["xid0"]
            io[0], io[1], io[2] = n, n_newton, brute
            return FOUND, xs, mu, fo, io, count
        if brute >= max_cycles:
            fo[0], fo[2] = best_r, s_total
            io[1], io[2], io[3] = n_newton, brute, best_n
            return NOT_CONVERGED, x, mu, fo, io, count
        chunk = min(2 * chunk, max(kv, ((max_cycles - brute) // kv) * kv))
