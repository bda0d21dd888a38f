"""Certified location of the first event of a phase (unit-free).

docs/MODEL.md, "Impacts and separation" and the stick/slip rules. Every event
function f of the model (gap ξ, signed relative velocity ±(ζ' − s'), distances
to the stick band ±(ζ − (1 ∓ b) sin ϖτ)) is a closed-form combination of
sinusoids whose derivatives are bounded on the search window by the smaller of
an energy-growth bound (:func:`flows.energy_radius`, valid through resonance) and
the split "forced part P sin φ + free oscillation of constant energy"
(:func:`band_bounds`), and locally from the exact second derivative plus a bound
on the third (:func:`local_m2`). From a point where f > 0,

    f(l + x) ≥ f(l) + f'(l) x − M2 x²/2,

so f cannot vanish before the smallest positive root x* of that quadratic: the
search advances by x* ("safe step"), which can never jump over a crossing, even
a grazing one, and converges quadratically onto a simple root. Where the slow
(forced) part minus the free oscillation's amplitude stays positive, longer
certified steps are taken (:func:`envelope_time`), and a whole remaining window
is cleared at once when that minimum is positive (``clear``). A bracket is
accepted once f' provably keeps its sign on it (4·M2·d ≤ |f'| with d the Newton
step): then [l, l + 2d] holds exactly one root, refined by safeguarded Newton
to round-off (Newton/Halley). A phase that starts *on* its event surface (f = 0, e.g. slip
entered at ζ' = s') is started with the first non-vanishing Taylor coefficient
and the matching derivative bound (``start``, ``bounds``).

An evaluator (:class:`Evaluator`) exposes ``n`` event functions, noise scales,
``eval(h) -> (f, f', M2)`` lists, the Taylor coefficients at the start, bounds,
``clear`` and ``free_len``; :class:`GapEvent`, :class:`SlipEvent` and
:class:`StickEvent` are the model's three.
"""

from __future__ import annotations

import math
from typing import Protocol

from betvdesign.dynamics._jit import jitable
from betvdesign.dynamics.flows import (
    REVERSE,
    SLIP,
    STICK,
    PhaseConstants,
    derivative_bounds,
    energy_radius,
    oscillator,
    slider,
)

EPS = 2.220446049250313e-16
TWO_PI = 2.0 * math.pi
NOISE = 64.0 * EPS
MAX_STEPS = 5000
_cos, _sin = math.cos, math.sin


class EventSearchError(RuntimeError):
    """The certified search did not terminate (a degenerate, non-isolated event)."""


class Evaluator(Protocol):
    n: int
    W: float
    scale: list[float]
    scale_derivs: list[list[float]]

    def eval(self, h: float, bounds: bool = True) -> tuple[list[float], list[float], list[float]]:
        """(f, f', M2) lists at h; with bounds=False (f, f', f'') where f'' is exact and
        cheap (fast mode), else (f, f', []): the refinement then takes Newton steps."""
        ...

    def start(self) -> list[list[float]]: ...

    def m2_start(self, i: int) -> float: ...

    def bounds(self, i: int, n: int = 4) -> list[float]: ...

    def clear(self, h: float) -> bool: ...

    def free_len(self, h: float, i: int) -> float: ...

    def probe(self, h: float) -> tuple[list[float], list[float], list[float], list[float]]: ...


def probe(ev: Evaluator, h: float) -> tuple[list[float], list[float], list[float], list[float]]:
    """eval(h) plus every function's free_len(h): one search step's look at h."""
    fs, fps, m2s = ev.eval(h)
    return fs, fps, m2s, [ev.free_len(h, i) for i in range(ev.n)]


@jitable
def safe_step(f: float, fp: float, m2: float) -> float:
    """Smallest x > 0 with f + f'x − M2 x²/2 = 0 (f > 0), written without cancellation."""
    if m2 <= 0.0:
        return math.inf if fp >= 0.0 else f / -fp
    root = math.sqrt(fp * fp + 2.0 * m2 * f)
    if fp > 0.0:
        return (fp + root) / m2
    return 2.0 * f / (root - fp)


@jitable
def local_m2(f: float, fp: float, fpp: float, m2: float, m3: float) -> float:
    """A bound on |f''| for :func:`first_root` at a point where f > 0, from f''(h) exactly.

    |f''(h + t)| ≤ |f''(h)| + M3·t. The value returned is valid over the longest
    interval it is used on: the safe step it produces (≤ the step under |f''(h)|), and
    the Newton bracket [h, h + 2f/|f'|] if it passes the bracket test; when it would pass
    that test without covering the bracket, it is raised just enough to fail it. Capped
    by the global bound ``m2`` (valid everywhere).
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


def lex_sign(derivs: list[float], noise: list[float]) -> int:
    """Sign of a function just after a point from its Taylor coefficients.

    Returns the sign of the first coefficient above its noise floor (+1/−1),
    0 when all are within round-off (the function vanishes to that order).
    """
    for d, nz in zip(derivs, noise, strict=False):
        if d > nz:
            return 1
        if d < -nz:
            return -1
    return 0


@jitable
def decide_phase_core(
    A: float,
    wf: float,
    b: float,
    beta: float,
    z: float,
    zd: float,
    sd: float,
    sp: float,
    cp: float,
    on: int,
) -> int:
    """Contact phase at a contact start or at ζ' = s' (MODEL.md stick/slip rules).

    A = α(1 + 1/β) [-] stick inertia, wf = ϖ, b = ακ(1 + β) stick-band half-width;
    (ζ, ζ', s', sin ϖτ, cos ϖτ) the state. The sign of ζ' − s' decides when it is
    above round-off; otherwise the band (1 − b) sin ϖτ ≤ ζ ≤ (1 + b) sin ϖτ, compared
    lexicographically on Taylor coefficients under the stick flow (:func:`lex_sign`,
    inlined). ``on``: the event just located (0: ζ' = s' in slip, 1: lower band edge,
    2: upper band edge), whose function is zero by construction whatever its round-off.
    """
    if on < 0:
        v = zd - sd
        nv = NOISE * (abs(zd) + abs(sd))
        if v > nv:
            return SLIP
        if v < -nv:
            return REVERSE
    vs = (zd + sd / beta) / (1.0 + 1.0 / beta)
    z2 = (sp - z) / A
    z3 = (wf * cp - vs) / A
    s1 = wf * cp
    s2 = -wf * wf * sp
    s3 = -(wf * wf * wf) * cp
    for edge in range(1, 3):
        sig, q, phase = (1.0, 1.0 - b, SLIP) if edge == 1 else (-1.0, 1.0 + b, REVERSE)
        for j in range(4):
            if j == 0:
                zj, sj = z, sp
            elif j == 1:
                zj, sj = vs, s1
            elif j == 2:
                zj, sj = z2, s2
            else:
                zj, sj = z3, s3
            qs = q * sj
            dj = 0.0 if j == 0 and on == edge else sig * (zj - qs)
            nz = NOISE * (abs(zj) + abs(qs))
            if dj > nz:
                break  # leaves the band on the admissible side: not this edge
            if dj < -nz:
                return phase
    return STICK


def first_root(ev: Evaluator, H: float, counter: list[int]) -> tuple[float, int] | None:
    """First h in [0, H] where one of ev's functions reaches 0 (certified).

    Returns (h, index) or None when none of them vanishes on [0, H]. ``counter[0]``
    is incremented by the number of function evaluations.
    """
    W = ev.W
    x = H if H < W else W
    for i, derivs in enumerate(ev.start()):
        nz = ev.scale_derivs[i]
        order = 0
        for order in range(len(derivs)):
            if abs(derivs[order]) > NOISE * nz[order]:
                break
        else:
            return 0.0, i  # vanishes to every order checked: an event here
        if derivs[order] < 0.0:
            return 0.0, i  # leaves its admissible side at once: zero-length phase
        if order == 0:
            xi = safe_step(derivs[0], derivs[1], ev.m2_start(i))
        else:
            xi = 0.5 * (order + 1) * derivs[order] / ev.bounds(i, order + 1)[order + 1]
        if xi < x:
            x = xi
    if x >= H or ev.clear(0.0):
        return None
    scale = ev.scale
    evaluate, look, clear = ev.eval, ev.probe, ev.clear
    sqrt = math.sqrt
    x0 = x
    cand: tuple[float, int] | None = None  # a located root; others may still come first
    active = list(range(ev.n))  # functions not yet settled on [x0, H]
    steps = [0.0] * ev.n
    for _ in range(MAX_STEPS):
        counter[0] += 1
        fs, fps, m2s, lens = look(x0)
        best_end = math.inf
        best_i = -1
        for i in active:
            f = fs[i]
            fp = fps[i]
            if f <= 0.0 or (f <= NOISE * scale[i] and fp <= 0.0):
                return x0, i  # at the root to round-off, heading down (or a graze)
            m2 = m2s[i]
            # xi = safe_step(f, fp, m2), inlined (the hot path)
            if m2 <= 0.0:
                xi = math.inf if fp >= 0.0 else f / -fp
            else:
                root = sqrt(fp * fp + 2.0 * m2 * f)
                xi = (fp + root) / m2 if fp > 0.0 else 2.0 * f / (root - fp)
            li = lens[i]
            steps[i] = xi if xi > li else li
            if fp < 0.0:
                d = f / -fp
                if 4.0 * m2 * d <= -fp and 2.0 * d <= W and x0 + 2.0 * d < best_end:
                    best_end, best_i = x0 + 2.0 * d, i
        if best_i >= 0:
            i = best_i
            active.remove(i)
            # f_i(x0 + 2d) ≤ −f + 2·M2·d² < 0 by construction; only a clipped end needs a look
            clipped = best_end > H
            hi = H if clipped else best_end
            f_hi = -1.0
            if clipped:
                counter[0] += 1
                f_hi = evaluate(hi, False)[0][i]
            if f_hi <= 0.0:  # else f_i (monotone on the bracket) stays positive up to H
                r = _refine(ev, i, x0, hi, fs[i], fps[i], counter, f_hi if clipped else None)
                cand, H = (r, i), r  # the others are searched on [x0, r] only
        step = H - x0
        if W < step:
            step = W
        for i in active:
            if steps[i] < step:
                step = steps[i]
        if not active or x0 + step >= H:
            return cand
        x0 += step
        if cand is None and clear(x0):
            return None
    raise EventSearchError(search_failure_message(H))


def search_failure_message(H: float) -> str:
    """What :class:`EventSearchError` says for a search window H [-]."""
    return f"event search did not terminate within {MAX_STEPS} steps on a window of {H:.6g}"


def _refine(
    ev: Evaluator,
    i: int,
    lo: float,
    hi: float,
    flo: float,
    fplo: float,
    counter: list[int],
    fhi: float | None = None,
) -> float:
    """Root of ev's function i in (lo, hi]: f(lo) > 0, f decreasing, f(hi) ≤ 0.

    Safeguarded Newton, to round-off: a step that leaves the bracket is replaced by the
    false-position point of the bracket ends when both values are known (``fhi``: f(hi)
    if evaluated), by bisection otherwise and never twice in a row, so the bracket still
    at least halves every second fallback. When the evaluator returns f'' with
    eval(x, False) (fast mode), the steps after the first carry Halley's correction
    (cubic convergence: about one evaluation less per root); the bracket, the stopping
    tests and hence the accuracy are those of Newton.
    """
    x, f, fp, fpp = lo, flo, fplo, 0.0
    f_lo, f_hi = flo, fhi  # f at the bracket ends, when known
    secant = True
    tol = 4.0 * EPS * max(1.0, abs(hi))
    floor = 4.0 * EPS * ev.scale[i]  # |f| at round-off level: converged
    evaluate = ev.eval
    for _ in range(200):
        if fp != 0.0:
            dn = f / fp
            den = 1.0 - 0.5 * dn * fpp / fp  # Halley's correction (fpp = 0: Newton)
            xn = x - (dn / den if den > 0.5 else dn)
        else:
            xn = 0.5 * (lo + hi)
        if not lo < xn < hi:
            xn = 0.5 * (lo + hi)
            if secant and f_hi is not None:  # false position (f_lo > 0 ≥ f_hi)
                xs = lo + (hi - lo) * (f_lo / (f_lo - f_hi))
                if lo < xs < hi:
                    xn = xs
            secant = not secant
        if abs(xn - x) <= tol:
            return xn
        x = xn
        counter[0] += 1
        fs, fps, fpps = evaluate(x, False)
        f, fp = fs[i], fps[i]
        fpp = fpps[i] if fpps else 0.0
        if abs(f) <= floor:
            return x
        if f > 0.0:
            lo, f_lo = x, f
        else:
            hi, f_hi = x, f
        if hi - lo <= tol:
            return hi
    return x


def cos_range(pa: float, pb: float) -> tuple[float, float]:
    """(min, max) of cos over the phase interval [pa, pb] [rad], exactly."""
    ca, cb = math.cos(pa), math.cos(pb)
    lo, hi = (ca, cb) if ca < cb else (cb, ca)
    if math.floor((pb - math.pi) / TWO_PI) >= math.ceil((pa - math.pi) / TWO_PI):
        lo = -1.0  # contains an odd multiple of π
    if math.floor(pb / TWO_PI) >= math.ceil(pa / TWO_PI):
        hi = 1.0  # contains a multiple of 2π
    return lo, hi


def amp_cos_min(K: float, pa: float, pb: float) -> float:
    """min of K·cos φ over φ ∈ [pa, pb]."""
    lo, hi = cos_range(pa, pb)
    return K * lo if K >= 0.0 else K * hi


def envelope_time(K: float, E: float, a: float, th0: float, wf: float) -> float:
    """First t ≥ 0 with K cos(θ0 + ϖt) + E ≤ a (0: already; inf: never).

    With f = K cos θ + E + (free oscillation of amplitude ≤ a), f > 0 until then: a
    certified no-root length that does not shrink with a loose |f''| bound.
    """
    return envelope_at(envelope_prep(K, E, a), th0, wf)


@jitable
def envelope_prep(K: float, E: float, a: float) -> tuple[int, float]:
    """The part of :func:`envelope_time` that does not depend on θ0: (mode, acos c).

    mode 0: the threshold is already reached for every θ0 (time 0); 1: never (inf);
    2: K > 0, cos θ ≤ c on [acos c, 2π − acos c]; 3: K < 0, cos θ ≥ c on
    [0, acos c] ∪ [2π − acos c, 2π), with c = (a − E)/K.
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


@jitable
def envelope_at(prep: tuple[int, float], th0: float, wf: float) -> float:
    """:func:`envelope_time` from its preparation :func:`envelope_prep` at θ0."""
    mode, al = prep
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


@jitable
def cos_range_prep(pb: float) -> tuple[float, float, float]:
    """The part of :func:`cos_range` that depends on the interval's end pb only."""
    return math.cos(pb), math.floor((pb - math.pi) / TWO_PI), math.floor(pb / TWO_PI)


@jitable
def cos_range_to(pa: float, end: tuple[float, float, float]) -> tuple[float, float]:
    """:func:`cos_range` (pa, pb) with pb's part prepared by :func:`cos_range_prep`."""
    ca = math.cos(pa)
    cb, f1, f2 = end
    lo, hi = (ca, cb) if ca < cb else (cb, ca)
    if f1 >= math.ceil((pa - math.pi) / TWO_PI):
        lo = -1.0  # contains an odd multiple of π
    if f2 >= math.ceil(pa / TWO_PI):
        hi = 1.0  # contains a multiple of 2π
    return lo, hi


def forced_split(w0: float, F: float, wf: float, y: float, yd: float, sp: float, cp: float):
    """Particular amplitude P and free-oscillation energy radius E_h of a phase.

    y = P sin φ + y_h with P = F/(w0² − ϖ²); y_h is a free oscillation, so
    E_h = sqrt(y_h'² + w0² y_h²) is constant over the phase. Returns (P, E_h), or
    (None, inf) at exact resonance (no such split; the energy bound is used).
    """
    den = w0 * w0 - wf * wf
    if den == 0.0:
        return None, math.inf
    P = F / den
    yh, yhd = y - P * sp, yd - P * wf * cp
    return P, math.sqrt(yhd * yhd + w0 * w0 * yh * yh)


def split_ok(P: float | None, w0: float, F: float) -> bool:
    """The split y = P sin φ + free oscillation is free of cancellation: |1 − aϖ²| ≥ 0.1."""
    return P is not None and abs(P) * w0 * w0 <= 10.0 * abs(F)


def window(H: float, w0: float, wf: float, P: float | None, F: float) -> float:
    """Length over which the energy-growth bound is taken (steps never exceed it).

    Away from resonance (|1 − aϖ²| ≥ 0.1) the split bound, valid on any length, is
    the tight one: the whole interval H. Near resonance: one radian of the fastest
    frequency, so that the secular growth |F|·W stays small.
    """
    if split_ok(P, w0, F):
        return H
    return min(H, 1.0 / max(w0, wf))


def band_bounds(
    w0: float, F: float, wf: float, q: float, R: float, P: float | None, Eh: float, n: int
) -> list[float]:
    """Bounds on |dʲ/dhʲ (y − q sin φ)|, j = 0..n, over a window of energy radius R.

    The smaller of (a) the energy growth bound (:func:`flows.derivative_bounds`) plus
    |q|ϖʲ and (b) the split y = P sin φ + y_h: |P − q| ϖʲ + w0^(j−1) E_h. (b) is tight
    when the head follows the forcing (small α), (a) near resonance.
    """
    a = derivative_bounds(w0, F, wf, R, n)
    out = []
    for j in range(n + 1):
        ba = a[j] + abs(q) * wf**j
        if P is not None:
            bb = abs(P - q) * wf**j + w0 ** (j - 1) * Eh
            ba = min(ba, bb)
        out.append(ba)
    return out


class GapEvent:
    """Event ξ → 0 in free flight: ξ'' + ξ = −sin φ (MODEL.md "No contact")."""

    n = 1

    def __init__(self, wf: float, xi: float, xid: float, sp0: float, cp0: float, H: float):
        self.wf, self.xi, self.xid, self.sp0, self.cp0, self.H = wf, xi, xid, sp0, cp0, H
        self.P, self.Eh = forced_split(1.0, -1.0, wf, xi, xid, sp0, cp0)
        self.phi0 = math.atan2(sp0, cp0)
        self.W = window(H, 1.0, wf, self.P, -1.0)
        self.m2b = math.inf if self.P is None else abs(self.P) * wf * wf + self.Eh
        r = energy_radius(1.0, 1.0, xi, xid, H)
        self.scale = [abs(xi) + r + 1.0]
        self.scale_derivs = [[self.scale[0]] * 4]

    def eval(self, h: float, bounds: bool = True) -> tuple[list[float], list[float], list[float]]:
        y, yd, _, _ = oscillator(1.0, self.wf, -1.0, self.xi, self.xid, self.sp0, self.cp0, h)
        if not bounds:
            return [y], [yd], []  # no f'' here: the refinement takes Newton steps
        r = energy_radius(1.0, 1.0, y, yd, self.W)
        return [y], [yd], [min(r + 1.0, self.m2b)]

    def start(self) -> list[list[float]]:
        wf, y, yd, sp, cp = self.wf, self.xi, self.xid, self.sp0, self.cp0
        return [[y, yd, -sp - y, -wf * cp - yd]]

    def m2_start(self, i: int) -> float:
        return min(energy_radius(1.0, 1.0, self.xi, self.xid, self.W) + 1.0, self.m2b)

    def clear(self, h: float) -> bool:
        """ξ = P sin φ + ξ_h, |ξ_h| ≤ E_h: positive on [h, H] when min P sin φ > E_h."""
        if not split_ok(self.P, 1.0, -1.0):
            return False
        a = self.phi0 + self.wf * h - 0.5 * math.pi
        return amp_cos_min(self.P, a, self.phi0 + self.wf * self.H - 0.5 * math.pi) > self.Eh

    def free_len(self, h: float, i: int) -> float:
        return 0.0

    def probe(self, h: float) -> tuple[list[float], list[float], list[float], list[float]]:
        return probe(self, h)

    def bounds(self, i: int, n: int = 4) -> list[float]:
        """Bounds on |ξ|, |ξ'|, ..., |ξ⁽ⁿ⁾| over the window."""
        r = energy_radius(1.0, 1.0, self.xi, self.xid, self.W)
        return band_bounds(1.0, -1.0, self.wf, 0.0, r, self.P, self.Eh, n)


class SlipEvent:
    """Event ζ' − s' → 0 in slip (σ = +1) or reverse slip (σ = −1).

    f = σ(ζ' − s'), f' = σ((1 − σb) sin φ − ζ)/α (MODEL.md contact equations):
    f⁽ʲ⁾ = −σ g⁽ʲ⁻¹⁾/α with g = ζ − (1 − σb) sin φ, bounded by :func:`band_bounds`.
    """

    n = 1

    def __init__(
        self,
        k: PhaseConstants,
        phase: int,
        z: float,
        zd: float,
        s: float,
        sd: float,
        sp0: float,
        cp0: float,
        H: float,
        from_edge: bool = False,
    ):
        self.k, self.phase = k, phase
        self.from_edge = from_edge  # entered at a band edge: f' = −σg/α is 0 there
        c = k.cache.get(phase)
        if c is None:  # per-phase constants, once per parameter set
            sig = 1.0 if phase == SLIP else -1.0
            q = 1.0 - sig * k.b
            w0, F, wf, ds = k.w0[phase], k.F[phase], k.varpi, k.ds[phase]
            P = forced_split(w0, F, wf, 0.0, 0.0, 0.0, 1.0)[0]
            fast = split_ok(P, w0, F)
            apq = 0.0 if P is None else abs(P - q) * wf
            K = sig * (P * wf + ds / wf) if fast else 0.0  # type: ignore[operator]
            c = k.cache[phase] = (sig, q, w0, F, wf, k.alpha, ds, P, fast, apq, K)
        sig, q, w0, F, wf, al, ds, P, fast, apq, K = c
        self.sig, self.q, self.w0, self.F, self.P, self.fast = sig, q, w0, F, P, fast
        self.state = (z, zd, s, sd, sp0, cp0)
        self.H = H
        if P is None:
            self.Eh = Eh = math.inf
            self.m2b = math.inf
            self.W = window(H, w0, wf, P, F)
        else:  # forced_split, inlined: y_h = ζ − P sin φ0, y_h' = ζ' − Pϖ cos φ0
            yh, yhd = z - P * sp0, zd - P * wf * cp0
            self.Eh = Eh = math.sqrt(yhd * yhd + w0 * w0 * yh * yh)
            self.m2b = (apq + Eh) / al
            self.W = H if fast else window(H, w0, wf, P, F)
        self.phi0 = math.atan2(sp0, cp0)
        if fast:  # y = P sin φ + a_c cos w0h + a_s sin w0h (no cancellation here)
            self.ac = yh
            self.as_ = yhd / w0
            self.sdc = sd + ds * cp0 / wf
            self.m3b = (apq * wf + w0 * Eh) / al
            # constants of eval/clear/free_len (same floating-point operations)
            self._c = (wf, w0, sp0, cp0, P, yh, self.as_, P * wf, self.sdc, ds, sig, q, al, q * wf)
            self.K = K
            self.ssdc = sig * self.sdc
            self.env = envelope_prep(K, -self.ssdc, Eh)
            self._end: tuple[float, float, float] | None = None  # cos_range_prep, on demand
        azd, asd = abs(zd), abs(sd)
        r = math.sqrt(zd * zd + w0 * w0 * z * z) + abs(F) * H  # energy_radius
        self.scale = [r + asd + azd + 1e-300]
        # noise floors of the Taylor coefficients, as in solver.decide_phase: |terms|
        aq = abs(q)
        self.scale_derivs = [
            [
                azd + asd,
                (aq * abs(sp0) + abs(z)) / al,
                (aq * wf * abs(cp0) + azd) / al,
                (aq * wf * wf * abs(sp0) + abs(F * sp0 - w0 * w0 * z)) / al,
            ]
        ]

    def _core(self, h: float) -> tuple[float, float, float]:
        """(f, f', f'') at h in fast mode: split_eval and the slider law, inlined."""
        wf, w0, sp0, cp0, P, ac, as_, Pwf, sdc, ds, sig, q, al, qwf = self._c
        cw, sw = _cos(wf * h), _sin(wf * h)
        sp, cp = sp0 * cw + cp0 * sw, cp0 * cw - sp0 * sw
        c0, s0 = _cos(w0 * h), _sin(w0 * h)
        y = P * sp + ac * c0 + as_ * s0
        yd = Pwf * cp + w0 * (as_ * c0 - ac * s0)
        sdn = sdc - ds * cp / wf
        return sig * (yd - sdn), sig * (q * sp - y) / al, sig * (qwf * cp - yd) / al

    def eval(self, h: float, bounds: bool = True) -> tuple[list[float], list[float], list[float]]:
        if not self.fast:
            return self._eval_slow(h, bounds)
        f, fp, fpp = self._core(h)
        if not bounds:
            return [f], [fp], [fpp]
        return [f], [fp], [local_m2(f, fp, fpp, self.m2b, self.m3b)]

    def probe(self, h: float) -> tuple[list[float], list[float], list[float], list[float]]:
        """eval(h) and free_len(h, 0) in one call (the search's hot path)."""
        if not self.fast:
            return probe(self, h)
        f, fp, fpp = self._core(h)
        wf = self.k.varpi
        li = envelope_at(self.env, self.phi0 + wf * h, wf)
        return [f], [fp], [local_m2(f, fp, fpp, self.m2b, self.m3b)], [li]

    def _eval_slow(
        self, h: float, bounds: bool = True
    ) -> tuple[list[float], list[float], list[float]]:
        k = self.k
        z, zd, s, sd, sp0, cp0 = self.state
        wf = k.varpi
        y, yd, sp, cp = oscillator(self.w0, wf, self.F, z, zd, sp0, cp0, h)
        _, sdn = slider(k.ds[self.phase], wf, s, sd, sp0, cp0, sp, cp, h)
        sig = self.sig
        if not bounds:  # no f'' here: the refinement takes Newton steps
            return [sig * (yd - sdn)], [sig * (self.q * sp - y) / k.alpha], []
        r = energy_radius(self.w0, self.F, y, yd, self.W)
        m2 = min((abs(self.q) * wf + r) / k.alpha, self.m2b)
        return [sig * (yd - sdn)], [sig * (self.q * sp - y) / k.alpha], [m2]

    def start(self) -> list[list[float]]:
        k = self.k
        z, zd, _, sd, sp, cp = self.state
        wf, al, q, sig = k.varpi, k.alpha, self.q, self.sig
        zdd = self.F * sp - self.w0**2 * z
        d = [
            sig * (zd - sd),
            sig * (q * sp - z) / al,
            sig * (q * wf * cp - zd) / al,
            sig * (-q * wf * wf * sp - zdd) / al,
        ]
        if self.from_edge:
            d[1] = 0.0
        return [d]

    def clear(self, h: float) -> bool:
        """f = σ(K cos φ − c) + σ ζ_h', K = Pϖ + ds/ϖ, c = s'-constant, |ζ_h'| ≤ E_h:
        positive on [h, H] when min σ(K cos φ − c) > E_h."""
        if not self.fast:
            return False
        if self._end is None:
            self._end = cos_range_prep(self.phi0 + self.k.varpi * self.H)
        lo, hi = cos_range_to(self.phi0 + self.k.varpi * h, self._end)
        K = self.K
        return (K * lo if K >= 0.0 else K * hi) - self.ssdc > self.Eh

    def free_len(self, h: float, i: int) -> float:
        """Length from h on which f > 0 is certified by its slow envelope (fast mode)."""
        if not self.fast:
            return 0.0
        wf = self.k.varpi
        return envelope_at(self.env, self.phi0 + wf * h, wf)

    def m2_start(self, i: int) -> float:
        if self.fast:
            return self.m2b
        z, zd = self.state[0], self.state[1]
        r = energy_radius(self.w0, self.F, z, zd, self.W)
        return min((abs(self.q) * self.k.varpi + r) / self.k.alpha, self.m2b)

    def bounds(self, i: int, n: int = 4) -> list[float]:
        """Bounds on |f⁽ʲ⁾|, j = 0..n (j = 0 not used: 0)."""
        z, zd = self.state[0], self.state[1]
        r = energy_radius(self.w0, self.F, z, zd, self.W)
        gb = band_bounds(self.w0, self.F, self.k.varpi, self.q, r, self.P, self.Eh, n - 1)
        return [0.0] + [g / self.k.alpha for g in gb]


class StickEvent:
    """Stick-band exits: g_lo = ζ − (1 − b) sin φ ≥ 0 and g_hi = (1 + b) sin φ − ζ ≥ 0.

    In stick the pair moves with α(1 + 1/β) ζ'' + ζ = sin ϖτ (MODEL.md). g_lo → 0
    ends stick into slip, g_hi → 0 into reverse slip; bounds by :func:`band_bounds`.
    ``on_edge``: stick re-entered on that edge (0 lower, 1 upper), whose value is 0.
    """

    n = 2

    def __init__(
        self,
        k: PhaseConstants,
        z: float,
        zd: float,
        sp0: float,
        cp0: float,
        H: float,
        on_edge: int = -1,
    ):
        self.k = k
        c = k.cache.get(STICK)
        if c is None:  # per-parameter-set constants, once
            w0, F, wf = k.w0[STICK], k.F[STICK], k.varpi
            qs = (1.0 - k.b, 1.0 + k.b)
            P = forced_split(w0, F, wf, 0.0, 0.0, 0.0, 1.0)[0]
            fast = split_ok(P, w0, F)
            a2 = [0.0 if P is None else abs(P - q) * wf * wf for q in qs]
            a3 = [abs(P - q) * wf**3 for q in qs] if fast else []  # type: ignore[operator]
            K = (P - qs[0], -1.0 * (P - qs[1])) if fast else ()  # type: ignore[operator]
            c = k.cache[STICK] = (w0, F, wf, qs, P, fast, a2, a3, K, wf**3)
        w0, F, wf, qs, P, fast, a2, a3, K, w3 = c
        self.w0, self.F, self.q, self.P, self.fast = w0, F, qs, P, fast
        self.state = (z, zd, sp0, cp0)
        self.H = H
        self.on_edge = on_edge
        if P is None:
            self.Eh = Eh = math.inf
            self.W = window(H, w0, wf, P, F)
            self.m2b = [math.inf, math.inf]
        else:  # forced_split, inlined
            yh, yhd = z - P * sp0, zd - P * wf * cp0
            self.Eh = Eh = math.sqrt(yhd * yhd + w0 * w0 * yh * yh)
            self.W = H if fast else window(H, w0, wf, P, F)
            wE = w0 * Eh
            self.m2b = [a2[0] + wE, a2[1] + wE]
        self.phi0 = math.atan2(sp0, cp0)
        self._w3 = w3
        if fast:
            self.ac = yh
            self.as_ = yhd / w0
            self._c = (wf, w0, sp0, cp0, P, yh, self.as_, P * wf)
            self._qw = (qs[0] * wf, qs[1] * wf)
            self._w02, self._wf2 = w0 * w0, wf * wf
            wwE = w0 * w0 * Eh
            self.m3b = [a3[0] + wwE, a3[1] + wwE]
            self.K = K
            self.eh = eh = Eh / w0
            self.env = [envelope_prep(K[0], 0.0, eh), envelope_prep(K[1], 0.0, eh)]
            self._end: tuple[float, float, float] | None = None  # cos_range_prep, on demand
        r = math.sqrt(zd * zd + w0 * w0 * z * z) + abs(F) * H  # energy_radius
        q0, q1 = qs
        self.scale = [r / w0 + abs(q0), r / w0 + abs(q1)]
        # noise floors of the Taylor coefficients, as in solver.decide_phase: |terms|
        za = (abs(z), abs(zd), abs(F * sp0 - w0 * w0 * z), abs(F * wf * cp0 - w0 * w0 * zd))
        sine = (sp0, wf * cp0, wf * wf * sp0, w3 * cp0)
        self.scale_derivs = [
            [
                za[0] + abs(q0 * sine[0]),
                za[1] + abs(q0 * sine[1]),
                za[2] + abs(q0 * sine[2]),
                za[3] + abs(q0 * sine[3]),
            ],
            [
                za[0] + abs(q1 * sine[0]),
                za[1] + abs(q1 * sine[1]),
                za[2] + abs(q1 * sine[2]),
                za[3] + abs(q1 * sine[3]),
            ],
        ]

    def _split(self, h: float) -> tuple[float, float, float, float]:
        """(ζ, ζ', sin φ, cos φ) at h in fast mode: :func:`flows.split_eval`, inlined."""
        wf, w0, sp0, cp0, P, ac, as_, Pwf = self._c
        cw, sw = _cos(wf * h), _sin(wf * h)
        sp, cp = sp0 * cw + cp0 * sw, cp0 * cw - sp0 * sw
        c0, s0 = _cos(w0 * h), _sin(w0 * h)
        return P * sp + ac * c0 + as_ * s0, Pwf * cp + w0 * (as_ * c0 - ac * s0), sp, cp

    def eval(self, h: float, bounds: bool = True) -> tuple[list[float], list[float], list[float]]:
        if self.fast:
            if bounds:
                return self.probe(h)[:3]  # type: ignore[return-value]
            y, yd, sp, cp = self._split(h)
            ql, qh = self.q
            qlw, qhw = self._qw
            ydd = self.F * sp - self._w02 * y
            w2sp = self._wf2 * sp
            return (
                [y - ql * sp, qh * sp - y],
                [yd - qlw * cp, qhw * cp - yd],
                [ydd + ql * w2sp, -ydd - qh * w2sp],
            )
        z, zd, sp0, cp0 = self.state
        wf = self.k.varpi
        ql, qh = self.q
        y, yd, sp, cp = oscillator(self.w0, wf, self.F, z, zd, sp0, cp0, h)
        if not bounds:  # no f'' here: the refinement takes Newton steps
            return [y - ql * sp, qh * sp - y], [yd - ql * wf * cp, qh * wf * cp - yd], []
        r = energy_radius(self.w0, self.F, y, yd, self.W)
        bzz = self.w0 * r + abs(self.F)
        w2 = wf * wf
        return (
            [y - ql * sp, qh * sp - y],
            [yd - ql * wf * cp, qh * wf * cp - yd],
            [min(bzz + abs(ql) * w2, self.m2b[0]), min(bzz + qh * w2, self.m2b[1])],
        )

    def probe(self, h: float) -> tuple[list[float], list[float], list[float], list[float]]:
        """eval(h) and free_len(h, i) of both edges in one call (the search's hot path)."""
        if not self.fast:
            return probe(self, h)
        y, yd, sp, cp = self._split(h)
        ql, qh = self.q
        qlw, qhw = self._qw
        f0, f1 = y - ql * sp, qh * sp - y
        g0, g1 = yd - qlw * cp, qhw * cp - yd
        ydd = self.F * sp - self._w02 * y
        w2sp = self._wf2 * sp
        m2b, m3b = self.m2b, self.m3b
        wf = self._c[0]
        th = self.phi0 + wf * h - 0.5 * math.pi
        env = self.env
        return (
            [f0, f1],
            [g0, g1],
            [
                local_m2(f0, g0, ydd + ql * w2sp, m2b[0], m3b[0]),
                local_m2(f1, g1, -ydd - qh * w2sp, m2b[1], m3b[1]),
            ],
            [envelope_at(env[0], th, wf), envelope_at(env[1], th, wf)],
        )

    def start(self) -> list[list[float]]:
        z, zd, sp, cp = self.state
        wf = self.k.varpi
        w0, F = self.w0, self.F
        z2, z3 = F * sp - w0 * w0 * z, F * wf * cp - w0 * w0 * zd
        s1, s2, s3 = wf * cp, -wf * wf * sp, -self._w3 * cp
        q0, q1 = self.q
        d0 = [z - q0 * sp, zd - q0 * s1, z2 - q0 * s2, z3 - q0 * s3]  # σ = +1
        d1 = [-(z - q1 * sp), -(zd - q1 * s1), -(z2 - q1 * s2), -(z3 - q1 * s3)]  # σ = −1
        if self.on_edge == 0:
            d0[0] = 0.0
        elif self.on_edge == 1:
            d1[0] = 0.0
        return [d0, d1]

    def clear(self, h: float) -> bool:
        """g = σ(P − q) sin φ + σ ζ_h, |ζ_h| ≤ E_h/w0: both positive on [h, H] when
        min σ(P − q) sin φ > E_h/w0 for both edges."""
        if not self.fast:
            return False
        if self._end is None:
            self._end = cos_range_prep(self.phi0 + self.k.varpi * self.H - 0.5 * math.pi)
        lo, hi = cos_range_to(self.phi0 + self.k.varpi * h - 0.5 * math.pi, self._end)
        eh = self.eh
        for K in self.K:  # amp_cos_min(K, a, b) > eh for both edges
            if not (K * lo if K >= 0.0 else K * hi) > eh:
                return False
        return True

    def free_len(self, h: float, i: int) -> float:
        """Length from h on which g_i > 0 is certified by its slow envelope (fast mode)."""
        if not self.fast:
            return 0.0
        wf = self.k.varpi
        return envelope_at(self.env[i], self.phi0 + wf * h - 0.5 * math.pi, wf)

    def m2_start(self, i: int) -> float:
        if self.fast:
            return self.m2b[i]
        z, zd = self.state[0], self.state[1]
        r = energy_radius(self.w0, self.F, z, zd, self.W)
        wf = self.k.varpi
        return min(self.w0 * r + abs(self.F) + abs(self.q[i]) * wf * wf, self.m2b[i])

    def bounds(self, i: int, n: int = 4) -> list[float]:
        """Bounds on |g_i⁽ʲ⁾|, j = 0..n."""
        z, zd = self.state[0], self.state[1]
        r = energy_radius(self.w0, self.F, z, zd, self.W)
        return band_bounds(self.w0, self.F, self.k.varpi, self.q[i], r, self.P, self.Eh, n)
