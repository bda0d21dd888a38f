"""Certified bounds of the event search (unit-free, scalar float64).

docs/MODEL.md, "Impacts and separation" and the stick/slip rules. Every event function f
of the model (gap ξ, signed relative velocity ±(ζ' − s'), distances to the stick band
±(ζ − (1 ∓ b) sin ϖτ)) is a closed-form combination of sinusoids. From a point where
f > 0 with |f''| ≤ M2 on the step,

    f(l + x) ≥ f(l) + f'(l) x − M2 x²/2,

so f cannot vanish before the smallest positive root of that quadratic (:func:`safe_step`):
the search (:mod:`search`) advances by it, never jumping over a crossing, even a grazing
one. :func:`local_m2` sharpens M2 locally from the exact f'' and a bound on f''';
:func:`envelope_prep` / :func:`envelope_at` give longer certified steps where the slow
(forced) part of f minus the free oscillation's amplitude stays positive, and
:func:`cos_range_prep` / :func:`cos_range_to` the exact range of cos over an interval
(a whole remaining window cleared at once).
"""

from __future__ import annotations

import math

from betvdesign.dynamics.jit import kernel

EPS = 2.220446049250313e-16
TWO_PI = 2.0 * math.pi
#: relative round-off floor of an event function or of a Taylor coefficient
NOISE = 64.0 * EPS
#: steps of one certified search before it is declared non-terminating
MAX_STEPS = 5000


@kernel
def safe_step(f: float, fp: float, m2: float) -> float:
    """Smallest x > 0 with f + f'x − M2 x²/2 = 0 (f > 0), written without cancellation.

    Parameters
    ----------
    f, fp : float
        f > 0 and f' at the point.
    m2 : float
        A bound on |f''| over the step.

    Returns
    -------
    float
        The step [-] within which f cannot reach 0.
    """
    if m2 <= 0.0:
        return math.inf if fp >= 0.0 else f / -fp
    root = math.sqrt(fp * fp + 2.0 * m2 * f)
    if fp > 0.0:
        return (fp + root) / m2
    return 2.0 * f / (root - fp)


@kernel
def local_m2(f: float, fp: float, fpp: float, m2: float, m3: float) -> float:
    """A bound on |f''| at a point where f > 0, from f''(h) exactly.

    |f''(h + t)| ≤ |f''(h)| + M3·t. The value returned is valid over the longest
    interval it is used on: the safe step it produces (≤ the step under |f''(h)|), and
    the Newton bracket [h, h + 2f/|f'|] if it passes the bracket test; when it would pass
    that test without covering the bracket, it is raised just enough to fail it. Capped
    by the global bound ``m2`` (valid everywhere).

    Parameters
    ----------
    f, fp, fpp : float
        f > 0, f' and f'' at the point.
    m2 : float
        The global bound on |f''|.
    m3 : float
        A bound on the third derivative |f⁽³⁾|.

    Returns
    -------
    float
        The bound on |f''|.
    """
    if f <= 0.0:
        return m2
    a = abs(fpp)
    if a <= 0.0:  # L = safe_step(f, fp, a), inlined
        L = math.inf if fp >= 0.0 else f / -fp
    else:
        root = math.sqrt(fp * fp + 2.0 * a * f)
        L = (fp + root) / a if fp > 0.0 else 2.0 * f / (root - fp)
    m = a + m3 * L
    if fp < 0.0:
        d = f / -fp
        if 2.0 * d > L:
            mb = a + m3 * 2.0 * d
            if 4.0 * mb * d <= -fp:
                m = mb  # covers the bracket; its step is still ≤ L ≤ 2d
            elif 4.0 * m * d <= -fp:
                m = -fp / (4.0 * d) * (1.0 + 1e-9)
    return m if m < m2 else m2


@kernel
def envelope_prep(K: float, E: float, a: float) -> tuple[int, float]:
    """The θ0-free part of "first t ≥ 0 with K cos(θ0 + ϖt) + E ≤ a": (mode, acos c).

    With f = K cos θ + E + (free oscillation of amplitude ≤ a), f > 0 until then: a
    certified no-root length that does not shrink with a loose |f''| bound.
    mode 0: the threshold is already reached for every θ0 (time 0); 1: never (inf);
    2: K > 0, cos θ ≤ c on [acos c, 2π − acos c]; 3: K < 0, cos θ ≥ c on
    [0, acos c] ∪ [2π − acos c, 2π), with c = (a − E)/K.

    Parameters
    ----------
    K, E : float
        Amplitude and offset of the forced part.
    a : float
        The threshold.

    Returns
    -------
    tuple of (int, float)
        The mode and acos c [rad].
    """
    if K == 0.0:
        return (0, 0.0) if E <= a else (1, 0.0)
    c = (a - E) / K
    if K > 0.0:
        if c >= 1.0:
            return 0, 0.0
        if c < -1.0:
            return 1, 0.0
        return 2, math.acos(c)
    if c <= -1.0:
        return 0, 0.0
    if c > 1.0:
        return 1, 0.0
    return 3, math.acos(c)


@kernel
def envelope_at(mode: int, al: float, th0: float, wf: float) -> float:
    """The certified no-root length from phase θ0 [-] prepared by :func:`envelope_prep`.

    Parameters
    ----------
    mode : int
        From :func:`envelope_prep`.
    al : float
        acos c [rad], from :func:`envelope_prep`.
    th0 : float
        The phase θ0 [rad].
    wf : float
        ϖ [-].

    Returns
    -------
    float
        The length [-] (0 or inf in modes 0 and 1).
    """
    if mode == 0:
        return 0.0
    if mode == 1:
        return math.inf
    u = th0 % TWO_PI
    if mode == 2:
        if al <= u <= TWO_PI - al:
            return 0.0
        return ((al - u) if u < al else (TWO_PI + al - u)) / wf
    if u <= al or u >= TWO_PI - al:
        return 0.0
    return (TWO_PI - al - u) / wf


@kernel
def cos_range_prep(pb: float) -> tuple[float, float, float]:
    """The part of the range of cos over [pa, pb] that depends on the end pb only.

    Parameters
    ----------
    pb : float
        The interval's end [rad].

    Returns
    -------
    tuple of float
        cos pb and the counts of odd and even multiples of π below pb.
    """
    return math.cos(pb), math.floor((pb - math.pi) / TWO_PI), math.floor(pb / TWO_PI)


@kernel
def cos_range_to(pa: float, cb: float, f1: float, f2: float) -> tuple[float, float]:
    """Exact (min, max) of cos over the phase interval [pa, pb] [rad].

    (min, max) of cos over the phase interval [pa, pb] [rad], exactly, with pb's part
    (cb, f1, f2) from :func:`cos_range_prep`.

    Parameters
    ----------
    pa : float
        The interval's start [rad].
    cb, f1, f2 : float
        pb's part, from :func:`cos_range_prep`.

    Returns
    -------
    tuple of float
        (min, max) of cos.
    """
    ca = math.cos(pa)
    lo, hi = (ca, cb) if ca < cb else (cb, ca)
    if f1 >= math.ceil((pa - math.pi) / TWO_PI):
        lo = -1.0  # contains an odd multiple of π
    if f2 >= math.ceil(pa / TWO_PI):
        hi = 1.0  # contains a multiple of 2π
    return lo, hi


@kernel
def derivative_bound(w0: float, F: float, wf: float, R: float, j: int) -> float:
    """Bound on |y⁽ʲ⁾| of y'' + w0² y = F sin φ over a window of energy radius R.

    From y⁽ᵏ⁾ = −w0² y⁽ᵏ⁻²⁾ + F wf^(k−2) sin^(k−2)(φ): |y⁽ᵏ⁾| ≤ w0²|y⁽ᵏ⁻²⁾| + |F| wf^(k−2),
    with |y| ≤ R/w0, |y'| ≤ R (R ≥ sqrt(y'² + w0² y²) on the window).

    Parameters
    ----------
    w0 : float
        Angular frequency of the oscillator [-].
    F : float
        Forcing amplitude [-].
    wf : float
        Forcing frequency ϖ [-].
    R : float
        Energy radius of the window [-].
    j : int
        Order of the derivative.

    Returns
    -------
    float
        The bound.
    """
    b0, b1 = R / w0, R
    bj = b0 if j == 0 else b1
    for k in range(2, j + 1):
        bk = w0 * w0 * b0 + abs(F) * wf ** float(k - 2)
        b0, b1 = b1, bk
        bj = bk
    return bj
