"""Certified location of the first event of a phase (unit-free).

docs/MODEL.md, "Impacts and separation" and the stick/slip rules; the bounds are those
of :mod:`bounds`, the event functions those of :mod:`evaluators` (evaluated by
:mod:`values`). :func:`first_root` walks the window [0, H] by certified safe steps (or
longer envelope steps) and can never jump over a crossing, even a grazing one; a whole
remaining window is cleared at once when every function's slow part stays above its free
oscillation. A bracket is accepted once f' provably keeps its sign on it (4·M2·d ≤ |f'|
with d the Newton step): then [l, l + 2d] holds exactly one root, refined to round-off by
:func:`refine`. A phase that starts *on* its event surface (f = 0) is started from the
first Taylor coefficient above its round-off floor and the matching derivative bound.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from betvdesign.dynamics.bounds import EPS, MAX_STEPS, NOISE, safe_step
from betvdesign.dynamics.evaluators import EVALUATOR_DTYPE
from betvdesign.dynamics.jit import kernel
from betvdesign.dynamics.values import clear, evaluate, probe, start_bound

#: :func:`first_root` codes
NO_ROOT, ROOT, SEARCH_FAILED = 0, 1, -1


class Workspace(NamedTuple):
    """Scratch arrays of one search (allocated once per run, reused by every phase).

    ``look``: f, f', M2, envelope length per function (8); ``fine``: f, f', f'' of the
    refinement (6); ``steps``: certified step per function (2); ``active``: functions not
    yet settled (2); ``end``: the clearance test's window-end preparation (4); ``ev``: the
    current phase's evaluator, one record of :data:`evaluators.EVALUATOR_DTYPE`.
    """

    ev: np.ndarray
    look: np.ndarray
    fine: np.ndarray
    steps: np.ndarray
    active: np.ndarray
    end: np.ndarray


@kernel
def workspace() -> Workspace:
    """A fresh :class:`Workspace`.

    Returns
    -------
    Workspace
        Scratch arrays for :func:`first_root`.
    """
    return Workspace(
        np.zeros(1, dtype=EVALUATOR_DTYPE),
        np.zeros(8),
        np.zeros(6),
        np.zeros(2),
        np.zeros(2, dtype=np.bool_),
        np.zeros(4),
    )


def search_failure_message(H: float) -> str:
    """What a non-terminating search (code SEARCH_FAILED) on a window H [-] reports.

    Parameters
    ----------
    H : float
        The search window [-].

    Returns
    -------
    str
        The message.
    """
    return f"event search did not terminate within {MAX_STEPS} steps on a window of {H:.6g}"


@kernel
def refine(
    e,
    i: int,
    lo: float,
    hi: float,
    flo: float,
    fplo: float,
    fhi: float,
    has_hi: bool,
    fine: np.ndarray,
) -> tuple[float, int]:
    """Root of function i in (lo, hi], with the evaluations it took.

    Root of function i in (lo, hi]: f(lo) > 0, f decreasing, f(hi) ≤ 0: (root,
    evaluations).

    Safeguarded Newton to round-off: a step leaving the bracket is replaced by the
    false-position point of the bracket ends when both values are known (``has_hi``), by
    bisection otherwise and never twice in a row. Where the evaluator gives f'' (fast
    mode) the steps carry Halley's correction; the bracket, the stopping tests and hence
    the accuracy are those of Newton.

    Parameters
    ----------
    e : Evaluator
        The event functions.
    i : int
        The function's index.
    lo, hi : float
        The bracket [-].
    flo, fplo : float
        f and f' at ``lo``.
    fhi : float
        f at ``hi`` (when ``has_hi``).
    has_hi : bool
        Whether ``fhi`` is known.
    fine : numpy.ndarray
        Scratch for the evaluator's values.

    Returns
    -------
    tuple of (float, int)
        The root [-] and the evaluations it took.
    """
    x, f, fp, fpp = lo, flo, fplo, 0.0
    f_lo, f_hi = flo, fhi
    secant = True
    tol = 4.0 * EPS * max(1.0, abs(hi))
    floor = 4.0 * EPS * e["scale"][i]  # |f| at round-off level: converged
    n = 0
    for _ in range(200):
        if fp != 0.0:
            dn = f / fp
            den = 1.0 - 0.5 * dn * fpp / fp  # Halley's correction (fpp = 0: Newton)
            xn = x - (dn / den if den > 0.5 else dn)
        else:
            xn = 0.5 * (lo + hi)
        if not lo < xn < hi:
            xn = 0.5 * (lo + hi)
            if secant and has_hi:  # false position (f_lo > 0 ≥ f_hi)
                xs = lo + (hi - lo) * (f_lo / (f_lo - f_hi))
                if lo < xs < hi:
                    xn = xs
            secant = not secant
        if abs(xn - x) <= tol:
            return xn, n
        x = xn
        n += 1
        evaluate(e, x, fine)
        f, fp, fpp = fine[i], fine[2 + i], fine[4 + i]
        if abs(f) <= floor:
            return x, n
        if f > 0.0:
            lo, f_lo = x, f
        else:
            hi, f_hi, has_hi = x, f, True
        if hi - lo <= tol:
            return hi, n
    return x, n


@kernel
def first_root(e, H: float, ws: Workspace) -> tuple[int, float, int, int]:
    """First h in [0, H] where one of the evaluator's event functions reaches 0, certified.

    Walks the window by certified safe steps (never over a crossing, even a grazing one)
    and refines the bracket found to round-off (module docstring).

    Parameters
    ----------
    e : numpy.void
        The evaluator (a record of :data:`evaluators.EVALUATOR_DTYPE`).
    H : float
        Window length [-].
    ws : Workspace
        Scratch arrays (:func:`workspace`).

    Returns
    -------
    tuple of (int, float, int, int)
        (code, h [-], index of the function, evaluations): code NO_ROOT, ROOT at (h,
        index) or SEARCH_FAILED (no termination within MAX_STEPS steps).

    Notes
    -----
    Over 80 lines on purpose: the compiled inner loop of every event search (bracket,
    certify, refine) with its state in registers; its numbers are pinned bit for bit by
    ``benchmarks/snapshot.py``.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773 (the event functions).
    """
    look, steps, act = ws.look, ws.steps, ws.active
    ws.end[3] = 0.0
    n = e["n"]
    W = e["W"]
    x = H if H < W else W
    for i in range(n):
        order = -1
        for j in range(4):
            if abs(e["start"][4 * i + j]) > NOISE * e["noise"][4 * i + j]:
                order = j
                break
        if order < 0 or e["start"][4 * i + order] < 0.0:
            return ROOT, 0.0, i, 0  # vanishes to every order, or leaves at once
        if order == 0:
            xi = safe_step(e["start"][4 * i], e["start"][4 * i + 1], e["m2s"][i])
        else:
            xi = 0.5 * (order + 1) * e["start"][4 * i + order] / start_bound(e, i, order)
        if xi < x:
            x = xi
    if x >= H or clear(e, 0.0, ws.end):
        return NO_ROOT, 0.0, -1, 0
    x0 = x
    cand_h, cand_i = 0.0, -1  # a located root; others may still come first
    evals = 0
    for i in range(n):
        act[i] = True
    for _ in range(MAX_STEPS):
        evals += 1
        probe(e, x0, look)
        best_end = math.inf
        best_i = -1
        for i in range(n):
            if not act[i]:
                continue
            f, fp = look[i], look[2 + i]
            if f <= 0.0 or (f <= NOISE * e["scale"][i] and fp <= 0.0):
                return ROOT, x0, i, evals  # at the root to round-off, heading down
            m2 = look[4 + i]
            if m2 <= 0.0:  # safe_step(f, fp, m2), inlined (the hot path)
                xi = math.inf if fp >= 0.0 else f / -fp
            else:
                root = math.sqrt(fp * fp + 2.0 * m2 * f)
                xi = (fp + root) / m2 if fp > 0.0 else 2.0 * f / (root - fp)
            li = look[6 + i]
            steps[i] = xi if xi > li else li
            if fp < 0.0:
                d = f / -fp
                if 4.0 * m2 * d <= -fp and 2.0 * d <= W and x0 + 2.0 * d < best_end:
                    best_end, best_i = x0 + 2.0 * d, i
        if best_i >= 0:
            i = best_i
            act[i] = False
            # f_i(x0 + 2d) ≤ −f + 2·M2·d² < 0 by construction; only a clipped end needs a look
            clipped = best_end > H
            hi = H if clipped else best_end
            f_hi = -1.0
            if clipped:
                evals += 1
                evaluate(e, hi, ws.fine)
                f_hi = ws.fine[i]
            if f_hi <= 0.0:  # else f_i (monotone on the bracket) stays positive up to H
                r, k = refine(e, i, x0, hi, look[i], look[2 + i], f_hi, clipped, ws.fine)
                evals += k
                cand_h, cand_i, H = r, i, r  # the others are searched on [x0, r] only
        step = H - x0
        if W < step:
            step = W
        n_act = 0
        for i in range(n):
            if act[i]:
                n_act += 1
                if steps[i] < step:
                    step = steps[i]
        if n_act == 0 or x0 + step >= H:
            return (NO_ROOT if cand_i < 0 else ROOT), cand_h, cand_i, evals
        x0 += step
        if cand_i < 0 and clear(e, x0, ws.end):
            return NO_ROOT, 0.0, -1, evals
    return SEARCH_FAILED, H, -1, evals
