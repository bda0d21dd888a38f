"""The head's vertical motion, exactly, cycle by cycle (compiled, unit-free).

docs/MODEL.md, "Impacts and separation". The vertical motion does not depend on the
slider: free flight ξ'' + ξ = −sin ϖτ (:func:`flows.vertical_flight`, resonant ϖ = 1
included), hits located by the certified search on the gap (:mod:`search`,
:func:`evaluators.gap_evaluator`), plastic hits (:func:`plastic_hit`: ξ' → 0), contact
while sin ϖτ ≥ 0 and impulsive hits (zero duration) when sin ϖτ < 0 at the hit.

Every contact ends at τ = (2j+1)π/ϖ with ξ = ξ' = 0, so the motion after a contact end
is the same whatever happened before: it is exactly periodic from the first contact end,
with a period of k cycles between two contact ends. :func:`vertical_run` computes the
prefix up to the first contact end and one period after it (or ``horizon`` cycles when
no contact recurs) into a table of cycles (:data:`CYCLE_DTYPE`), their impulsive-hit
times and their free-flight pieces (:data:`PIECE_DTYPE`, for dense output).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from betvdesign.dynamics.bounds import EPS
from betvdesign.dynamics.evaluators import gap_evaluator
from betvdesign.dynamics.flows import vertical_flight
from betvdesign.dynamics.jit import kernel
from betvdesign.dynamics.search import NO_ROOT, ROOT, SEARCH_FAILED, first_root, workspace

#: one cycle: section state (ξ, ξ'), contact-opening local time (NaN: none), its
#: impulsive hits imp[imp_start : imp_start + imp_count] and free-flight pieces
CYCLE_DTYPE = np.dtype(
    [
        ("xi0", np.float64),
        ("xid0", np.float64),
        ("tc", np.float64),
        ("imp_start", np.int64),
        ("imp_count", np.int64),
        ("free_start", np.int64),
        ("free_count", np.int64),
    ]
)
#: one free-flight piece from local time t with state (ξ, ξ') and forcing (sin, cos)
PIECE_DTYPE = np.dtype(
    [
        ("t", np.float64),
        ("xi", np.float64),
        ("xid", np.float64),
        ("sp", np.float64),
        ("cp", np.float64),
    ]
)
#: :func:`vertical_run` codes
DONE, FULL, FAILED, CHATTERED = 0, 1, 2, 3
#: hits of one cycle before a chattering sequence that does not accumulate is reported
MAX_BOUNCES = 20000


class VerticalRun(NamedTuple):
    """What :func:`vertical_run` returns.

    What :func:`vertical_run` returns: ``code`` (DONE, FULL: a table is too small,
    enlarge and call again, FAILED: the gap search did not terminate on window ``H``),
    rows used in the tables (``cycles``, ``hits``: impulsive, ``pieces``), ``first_end``
    (cycle of the first contact end, −1: none), ``period`` (cycles between contact ends,
    −1: none recurred within the horizon) and root ``evals``.
    """

    code: int
    cycles: int
    first_end: int
    period: int
    hits: int
    pieces: int
    evals: int
    H: float


@kernel
def plastic_hit(xid: float) -> float:
    """Normal velocity just after a plastic hit: ξ' → 0.

    Normal velocity just after a hit: plastic impact, ξ' → 0 (MODEL.md "Impacts and
    separation": no rebound).

    Parameters
    ----------
    xid : float
        ξ' at the hit [-] (< 0).

    Returns
    -------
    float
        0.0.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
    """
    return 0.0


@kernel
def rebound(xid: float, e: float) -> float:
    """Normal velocity just after a hit with restitution e: −e ξ'.

    MODEL.md "Beyond the paper's idealisation"; e = 0 is :func:`plastic_hit`.

    Parameters
    ----------
    xid : float
        ξ' at the hit [-] (< 0).
    e : float
        Coefficient of restitution [-] (0 ≤ e < 1).

    Returns
    -------
    float
        ξ' just after the hit [-].

    References
    ----------
    Budd & Dux, Phil. Trans. R. Soc. A 347 (1994), doi:10.1098/rsta.1994.0044.
    """
    if e == 0.0:
        return plastic_hit(xid)
    return -e * xid


@kernel
def accumulation(wf: float, zv: float, A: float, e: float, t: float, v: float) -> float:
    """Time left until a chattering sequence accumulates, when it can be closed.

    After a hit at local time t in contact conditions (N ∝ A sin ϖt > 0) the head leaves
    at v = e|ξ'| and is pulled back by a ≈ A sin ϖt: flights of 2v_k/a with v_k = eᵏv
    sum to T = 2v/(a(1 − e)) (Budd & Dux 1994, leading order). Over T the acceleration
    changes by at most AϖT (forcing), 2ζ_v v (damper) and v²/a (spring at the apex): a
    relative change ρ, so the sum is T(1 ± 3ρ/(1 − e)) to first order. T is taken when
    that error, 3Tρ/(1 − e), is below EPS·π/ϖ and the sequence ends before contact
    would end (π/ϖ). docs/damping.md.

    Parameters
    ----------
    wf : float
        ϖ [-].
    zv : float
        Normal damping ratio ζ_v [-].
    A : float
        Normal-force amplitude [-].
    e : float
        Coefficient of restitution [-].
    t : float
        Local time of the hit [-].
    v : float
        Rebound velocity e|ξ'| [-].

    Returns
    -------
    float
        The time left T [-], or −1 when its error bound is not yet below the round-off of
        the contact time (go on bouncing).

    References
    ----------
    Budd & Dux, Phil. Trans. R. Soc. A 347 (1994), doi:10.1098/rsta.1994.0044.
    """
    if v == 0.0:
        return 0.0
    a = A * math.sin(wf * t)
    if not a > 0.0:
        return -1.0
    T = 2.0 * v / (a * (1.0 - e))
    rho = (A * wf * T + 2.0 * zv * v + v * v / a) / a
    te = math.pi / wf
    if 3.0 * T * rho / (1.0 - e) <= EPS * te and t + T < te:
        return T
    return -1.0


#: coefficients of the short-flight series (:func:`short_flight`)
SERIES_TERMS = 28
#: longest flight [-] given to the series (beyond it the certified gap search is used)
SERIES_HMAX = 0.25


@kernel
def short_flight(wf: float, zv: float, A: float, v: float, sp: float, cp: float, d=None):
    """Certified flight time and landing velocity of a rebound.

    Certified flight time h and landing velocity of a rebound from ξ = 0 with ξ' = v > 0
    at a phase with sin = sp > 0, cos = cp (kernel time), by its Taylor series; (−1, 0)
    when the series cannot certify it (long flight: use the gap search).

    Free flight in kernel time is ξ'' + 2ζ_v ξ' + ξ = −A sin ϖτ (docs/damping.md), so
    the derivatives at the hit follow d₀ = 0, d₁ = v,
    d_{k+2} = −2ζ_v d_{k+1} − d_k − A ϖᵏ sin(ϖt + kπ/2), and ξ(h) = Σ d_k hᵏ/k!. The
    closed form loses the gap's absolute round-off (~1e-16) against a flight of size
    ~v² — relative error 1e-16/v² — so the flights of a chattering sequence are taken
    from the series, whose round-off is relative to the flight itself.

    Certificate: |d_k| ≤ C ρᵏ beyond the computed terms (ρ = max(ϖ, ζ_v + √(ζ_v² + 1)) + 1,
    C from the last terms and A/(ρ² − 2ζ_vρ − 1), by induction on the recursion); with it
    G(h) = ξ(h)/h has G(0) = v > 0 and G' < 0 on [0, H] (so one root there), located by
    Newton and bracketed by a sign change of G at h(1 ∓ 64ε). ``d``: optional scratch
    array of SERIES_TERMS + 2 floats (reused along a chattering sequence).
    """
    a = A * sp + 2.0 * zv * v  # −ξ''(0)
    if not (v > 0.0 and a > 0.0):
        return -1.0, 0.0
    h = 2.0 * v / a
    if not h < SERIES_HMAX:
        return -1.0, 0.0
    K = SERIES_TERMS
    if d is None:
        d = np.empty(K + 2)
    d[0], d[1] = 0.0, v
    wk = 1.0
    for k in range(K):
        q = k % 4  # sin(x + kπ/2) = sin, cos, −sin, −cos
        f = sp if q == 0 else (cp if q == 1 else (-sp if q == 2 else -cp))
        d[k + 2] = -2.0 * zv * d[k + 1] - d[k] - A * wk * f
        wk *= wf
    rho = max(wf, zv + math.sqrt(zv * zv + 1.0)) + 1.0
    c_tail = A / (rho * rho - 2.0 * zv * rho - 1.0)
    C = max(abs(d[K]) / rho**K, abs(d[K + 1]) / rho ** (K + 1), c_tail)
    for _ in range(60):  # Newton on G(h) = Σ_{k≥1} d_k h^(k−1)/k!
        g, dg, term = 0.0, 0.0, 1.0  # term = h^(k−1)/k!
        for k in range(1, K + 2):
            g += d[k] * term / k
            if k >= 2:
                dg += d[k] * (k - 1) * term / (k * h)
            term *= h / k
        if not (dg < 0.0):
            return -1.0, 0.0
        step = g / dg
        h -= step
        if not (0.0 < h < SERIES_HMAX):
            return -1.0, 0.0
        if abs(step) <= 16.0 * EPS * h:
            break
    else:
        return -1.0, 0.0
    H = h * (1.0 + 64.0 * EPS)
    x = rho * H
    if x >= 1.0:
        return -1.0, 0.0
    # G' + a/2 on [0, H]: Σ_{k≥3} |d_k| (k−1) H^(k−2)/k!, computed terms plus the tail
    slope = 0.0
    term = H / 6.0  # H^(k−2)/k! at k = 3
    for k in range(3, K + 2):
        slope += abs(d[k]) * (k - 1) * term
        term *= H / (k + 1)
    slope += C * rho**2 * x**K * (K + 1) / math.gamma(K + 3) / (1.0 - x)
    if not slope < 0.5 * a:
        return -1.0, 0.0
    lo, hi = h * (1.0 - 64.0 * EPS), H
    glo, ghi = _series(d, K, lo), _series(d, K, hi)
    tail = C * x ** (K + 2) / math.gamma(K + 3) / (1.0 - x) / H
    if not (glo > tail and ghi < -tail):
        return -1.0, 0.0
    vl, term = 0.0, 1.0  # ξ'(h) = Σ d_{k+1} h^k/k!
    for k in range(K + 1):
        vl += d[k + 1] * term
        term *= h / (k + 1)
    return h, vl


@kernel
def _series(d, K, h):
    """G(h) = ξ(h)/h = Σ_{k=1}^{K+1} d_k h^(k−1)/k! (:func:`short_flight`)."""
    g, term = 0.0, 1.0
    for k in range(1, K + 2):
        g += d[k] * term / k
        term *= h / k
    return g


@kernel
def _new_cycle(cyc, n, xi, xid, ni, nf) -> int:
    r = cyc[n]
    r["xi0"], r["xid0"], r["tc"] = xi, xid, math.nan
    r["imp_start"], r["imp_count"], r["free_start"], r["free_count"] = ni, 0, nf, 0
    return n + 1


@kernel
def _piece(cyc, m, pieces, nf, t, xi, xid, sp, cp) -> int:
    r = pieces[nf]
    r["t"], r["xi"], r["xid"], r["sp"], r["cp"] = t, xi, xid, sp, cp
    cyc[m]["free_count"] += 1
    return nf + 1


@kernel
def vertical_run(wf, zv, A, e, xi, xid, horizon, cyc, imp, pieces):
    """Vertical motion from (ξ, ξ') at τ = 0 into the tables cyc, imp, pieces (module doc).

    With e > 0 a chattering sequence is followed hit by hit until :func:`accumulation`
    can close it (its hits count as impulsive), at most MAX_BOUNCES hits per cycle.

    Parameters
    ----------
    wf : float
        ϖ [-].
    zv : float
        Normal damping ratio ζ_v [-].
    A : float
        Normal-force amplitude [-] (1 undamped).
    e : float
        Coefficient of restitution [-].
    xi, xid : float
        ξ, ξ' at τ = 0 [-].
    horizon : int
        Cycles [-] within which a contact must recur.
    cyc, imp, pieces : numpy.ndarray
        The tables filled: cycles (:data:`CYCLE_DTYPE`), impulsive-hit local times [-],
        free-flight pieces (:data:`PIECE_DTYPE`).

    Returns
    -------
    VerticalRun
        ``code`` DONE, FULL (a table is too small: enlarge and call again), FAILED (the
        gap search did not terminate) or CHATTERED (a sequence did not accumulate); rows
        used, the first contact end, the period and the root evaluations.

    Notes
    -----
    Over 80 lines on purpose: a compiled kernel whose loop carries about a dozen scalars
    (time, state, table rows, counters) from one event to the next; split into
    functions it would pass and return them all at every event, and its numbers are
    pinned bit for bit by ``benchmarks/snapshot.py``.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773 (vertical motion).
    Budd & Dux, Phil. Trans. R. Soc. A 347 (1994), doi:10.1098/rsta.1994.0044 (chattering).
    """
    T = 2.0 * math.pi / wf
    te = math.pi / wf
    ws = workspace()
    dser = np.empty(SERIES_TERMS + 2)
    n, ni, nf, evals = 0, 0, 0, 0
    first_end, period = -1, -1
    n = _new_cycle(cyc, n, xi, xid, ni, nf)
    t, sp, cp = 0.0, 0.0, 1.0
    bounces = 0
    contact = xi == 0.0 and xid <= 0.0  # a hit at phase 0: contact starts
    if contact and e != 0.0 and xid < 0.0:  # ... or bounces
        contact, xid = False, rebound(xid, e)
    if not contact:
        nf = _piece(cyc, 0, pieces, nf, 0.0, xi, xid, sp, cp)
    while True:
        m = n - 1
        if ni + 2 > imp.size or nf + 3 > pieces.size:
            return VerticalRun(FULL, n, first_end, period, ni, nf, evals, 0.0)
        if contact:
            cyc[m]["tc"] = t
            t, xi, xid, sp, cp = te, 0.0, 0.0, 0.0, -1.0
            nf = _piece(cyc, m, pieces, nf, te, 0.0, 0.0, 0.0, -1.0)
            contact = False
            if first_end < 0:
                first_end = m
            else:
                # From this contact end on, cycle m repeats cycle first_end's
                # post-contact flight (same state ξ = ξ' = 0 at π/ϖ): copy it, so the
                # period holds the impulsive hits after the separation too.
                ref = cyc[first_end]
                need_f, need_i = ref["free_count"], ref["imp_count"]
                if nf + need_f > pieces.size or ni + need_i > imp.size:
                    return VerticalRun(FULL, n, first_end, period, ni, nf, evals, 0.0)
                for k in range(ref["free_start"], ref["free_start"] + need_f):
                    if pieces[k]["t"] > te:
                        p = pieces[k]
                        nf = _piece(cyc, m, pieces, nf, p["t"], p["xi"], p["xid"], p["sp"], p["cp"])
                for k in range(ref["imp_start"], ref["imp_start"] + need_i):
                    if imp[k] > te:
                        imp[ni] = imp[k]
                        ni += 1
                        cyc[m]["imp_count"] += 1
                period = m - first_end
                break
        H = Hcycle = T - t
        ev = ws.ev[0]
        hs, vland = -1.0, 0.0
        if e != 0.0 and xi == 0.0 and xid > 0.0 and sp > 0.0:
            # a rebound against the pull A sin ϖt: a short flight is taken from its
            # series (round-off relative to the flight: chattering stays exact)
            hs, vland = short_flight(wf, zv, A, xid, sp, cp, dser)
            if not t + hs < T * (1.0 - 8.0 * EPS):
                hs = -1.0
        if hs > 0.0:
            code, h, k = ROOT, hs, 1
        else:
            general = zv != 0.0 or e != 0.0
            if e != 0.0 and xi == 0.0 and xid > 0.0 and sp > 0.0:
                # ... else search a window of a few flights first (≈ 2ξ'/(A sin ϖt)),
                # so the gap's round-off scale is the flight's own
                H = min(Hcycle, 8.0 * xid / (A * sp))
            gap_evaluator(wf, zv, A, xi, xid, sp, cp, H, general, ev)
            code, h, _, k = first_root(ev, H, ws)
        evals += k
        if code == SEARCH_FAILED:
            return VerticalRun(FAILED, n, first_end, period, ni, nf, evals, h)
        if code == NO_ROOT and H < Hcycle:  # not back within the short window: go on
            xi, xid, _, _ = vertical_flight(wf, zv, A, xi, xid, sp, cp, H)
            t += H
            sp, cp = math.sin(wf * t), math.cos(wf * t)
            nf = _piece(cyc, m, pieces, nf, t, xi, xid, sp, cp)
            continue
        if code == NO_ROOT:
            xi, xid, _, _ = vertical_flight(wf, zv, A, xi, xid, sp, cp, H)
            if xi < 0.0:
                xi = 0.0
            limit = horizon if first_end < 0 else first_end + 1 + horizon
            if n >= limit:
                break
            if n >= cyc.size:
                return VerticalRun(FULL, n, first_end, period, ni, nf, evals, 0.0)
            n = _new_cycle(cyc, n, xi, xid, ni, nf)
            t, sp, cp = 0.0, 0.0, 1.0
            bounces = 0
            if xi == 0.0 and xid <= 0.0 and (e == 0.0 or xid == 0.0):
                contact = True
            else:
                if xi == 0.0 and xid < 0.0:  # a hit exactly at the section: it bounces
                    xid = rebound(xid, e)
                nf = _piece(cyc, n - 1, pieces, nf, 0.0, xi, xid, sp, cp)
            continue
        t += h
        if t >= T * (1.0 - 8.0 * EPS):  # hit at the section itself: contact from t = 0
            _, xid, _, _ = vertical_flight(wf, zv, A, xi, xid, sp, cp, h)
            if n >= cyc.size:
                return VerticalRun(FULL, n, first_end, period, ni, nf, evals, 0.0)
            n = _new_cycle(cyc, n, 0.0, 0.0 if 0.0 < xid else xid, ni, nf)
            t, sp, cp = 0.0, 0.0, 1.0
            bounces = 0
            if e == 0.0 or not xid < 0.0:
                contact = True
            else:
                xi, xid = 0.0, rebound(xid, e)
                nf = _piece(cyc, n - 1, pieces, nf, 0.0, xi, xid, sp, cp)
            continue
        if e != 0.0:  # restitution: the head bounces (and may chatter into contact)
            if hs > 0.0:
                xid = vland
            else:
                _, xid, _, _ = vertical_flight(wf, zv, A, xi, xid, sp, cp, h)
            v = rebound(xid if xid < 0.0 else 0.0, e)
            if t < te:
                rest = accumulation(wf, zv, A, e, t, v)
                if rest >= 0.0:
                    if rest > 0.0:
                        imp[ni] = t
                        ni += 1
                        cyc[m]["imp_count"] += 1
                    t += rest
                    contact = True
                    continue
            bounces += 1
            if bounces > MAX_BOUNCES:
                return VerticalRun(CHATTERED, n, first_end, period, ni, nf, evals, t)
            sp, cp = math.sin(wf * t), math.cos(wf * t)
            imp[ni] = t
            ni += 1
            cyc[m]["imp_count"] += 1
            xi, xid = 0.0, v
            nf = _piece(cyc, m, pieces, nf, t, 0.0, v, sp, cp)
            continue
        if t < te:  # sin ϖt ≥ 0 at the hit: contact until π/ϖ
            contact = True
            continue
        sp, cp = math.sin(wf * t), math.cos(wf * t)
        imp[ni] = t
        ni += 1
        cyc[m]["imp_count"] += 1
        xi, xid = 0.0, plastic_hit(xid)
        nf = _piece(cyc, m, pieces, nf, t, 0.0, 0.0, sp, cp)
    return VerticalRun(DONE, n, first_end, period, ni, nf, evals, 0.0)


@kernel
def gap_at(wf, zv, A, cyc_row_tc, pieces, start, count, t):
    """Normal state (ξ, ξ') at local time t of a cycle.

    (ξ, ξ') at local time t of a cycle with contact opening at cyc_row_tc (NaN: none)
    and free pieces pieces[start : start + count] (0 during contact).

    Parameters
    ----------
    wf, zv, A : float
        ϖ, ζ_v and the normal-force amplitude [-].
    cyc_row_tc : float
        The cycle's contact-opening local time [-] (NaN: none).
    pieces : numpy.ndarray
        The free-flight pieces (:data:`PIECE_DTYPE`).
    start, count : int
        The cycle's pieces.
    t : float
        Local time [-].

    Returns
    -------
    tuple of float
        (ξ, ξ') [-].
    """
    te = math.pi / wf
    if cyc_row_tc == cyc_row_tc and cyc_row_tc <= t <= te:
        return 0.0, 0.0
    best = -1
    for k in range(start, start + count):
        if pieces[k]["t"] <= t:
            best = k
    if best < 0:
        return 0.0, 0.0
    p = pieces[best]
    y, yd, _, _ = vertical_flight(wf, zv, A, p["xi"], p["xid"], p["sp"], p["cp"], t - p["t"])
    return y, yd


@kernel
def cycle_rows(m, n_prefix, period):
    """Rows of the vertical table (:data:`CYCLE_DTYPE`) of cycles m.

    The table holds the prefix (cycles 0..n_prefix−1) and one period after it: a cycle
    past the prefix maps into that period.

    Parameters
    ----------
    m : numpy.ndarray
        Cycles (int, 0-based, ≥ 0).
    n_prefix : int
        Rows of the prefix.
    period : int
        The period [cycles] (> 0 when any m ≥ n_prefix).

    Returns
    -------
    numpy.ndarray
        int64 rows, one per cycle.
    """
    idx = np.empty(m.size, np.int64)
    for j in range(m.size):
        k = m[j]
        idx[j] = k if k < n_prefix else n_prefix + (k - n_prefix) % period
    return idx


@kernel
def period_rates(tab, first, last, T, te):
    """Hits per cycle and fraction of time in contact over the rows tab[first:last].

    Parameters
    ----------
    tab : numpy.ndarray
        The vertical table (:data:`CYCLE_DTYPE`).
    first, last : int
        The rows of one period (or of the whole horizon when there is none).
    T, te : float
        The cycle 2π/ϖ and the contact end π/ϖ [-].

    Returns
    -------
    tuple of float
        Contact-opening and impulsive hits per cycle [-]; fraction of the time in
        contact [-] (the contacts' lengths te − t_c summed in row order).
    """
    hits, tc = 0, 0.0
    for i in range(first, last):
        t = tab[i]["tc"]
        hits += tab[i]["imp_count"] + (1 if t == t else 0)
        if t == t:
            tc += te - t
    n = max(last - first, 1)
    return hits / n, tc / (T * n)
