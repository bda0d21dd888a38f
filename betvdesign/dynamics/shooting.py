"""Newton shooting on the exact section map, compiled (unit-free).

docs/MODEL.md, "Slider"; the algorithm is described in :mod:`periodic`. The section map
Φⁿ: x = (ζ, ζ', s') at the first periodic cycle → n cycles later is the contact loop
(:func:`contact.run_cycles`); here, compiled with it, are its residual
‖Φⁿ(x) − x‖∞, its finite-difference Jacobian and the damped Newton iteration, so that a
periodic solve crosses from Python into compiled code a handful of times instead of once
per map evaluation. Every function takes the map's arguments :data:`SHOT` first.
"""

from __future__ import annotations

import math

import numpy as np

from betvdesign.dynamics.contact import OK, run_cycles
from betvdesign.dynamics.jit import kernel

#: forward-difference step of the Jacobian (relative to max(1, |x_i|))
FD_STEP = 1e-7
#: Newton iterations at most
MAX_NEWTON = 25
#: trust region: steps at most TRUST·(1 + ‖x‖∞)
TRUST = 2.0


#: The map's arguments, in this order (one design, one period n, built by
#: :class:`periodic._Map`): ``table`` (:func:`flows.phase_table`); the vertical schedule's
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
