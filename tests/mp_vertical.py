"""High-precision (mpmath) head motion for the chattering tests: an independent truth.

Written from shared MODEL.md "Beyond the paper's idealisation", nothing of the solvers
used. Every free motion of the model is a linear oscillator under the cart's sinusoidal
forcing,

    y'' + p y' + q y = A sin ψ + B cos ψ,   ψ = ϖτ − δ  (tan δ = 2ζ_vϖ),

(vertical free flight: p = 2ζ_v, q = 1, A = −1, B = −2ζ_vϖ; tangential free flight:
p = 2ζ_h/√α, q = 1/α, A = 1/α, B = 2ζ_hϖ/√α), integrated here by its Taylor series
(derivatives from the equation, :data:`TERMS` terms, steps of at most :data:`HMAX`: the
remainder is below 1e-60 for ϖ < 2, q ≤ 25) in 50-digit arithmetic (:data:`DPS`, by
``mp.workdps``). Hits
(ξ = 0 from above) are the first sign change of ξ/h (ξ with its root at the step's start
divided out, so that tiny flights keep every digit), bracketed on a grid and refined by
``mp.findroot``. A chattering sequence is summed hit by hit, ξ' → −e ξ', until a flight is
shorter than :data:`FLIGHT_END` (1e-35): the flights left then sum to less than
1e-35/(1 − e), far below any double-precision comparison, so the accumulation time is
the sum itself (no closure formula).
"""

from __future__ import annotations

import functools

import mpmath as mp

#: working precision [decimal digits] of every function here (``mp.workdps``: the global
#: mp.mp.dps, which other test modules set at import, is left alone)
DPS = 50


def fifty_digits(f):
    """Run f at DPS digits whatever the global precision."""

    @functools.wraps(f)
    def run(*args, **kwargs):
        with mp.workdps(DPS):
            return f(*args, **kwargs)

    return run


TERMS = 40
HMAX = mp.mpf("0.25")
FLIGHT_END = mp.mpf("1e-35")
GRID = 48


def horner(c: list, h):
    """Σ c_j hʲ (ascending coefficients)."""
    acc = mp.mpf(0)
    for cj in reversed(c):
        acc = acc * h + cj
    return acc


def deriv(c: list) -> list:
    """Coefficients of the derivative of Σ c_j hʲ."""
    return [j * c[j] for j in range(1, len(c))]


class Oscillator:
    """y'' + p y' + q y = A sin ψ + B cos ψ, ψ = ϖτ − δ, in mpmath (module doc)."""

    @fifty_digits
    def __init__(self, varpi, zeta_v, p, q, A, B):
        self.w = mp.mpf(varpi)
        self.lead = mp.atan(2 * mp.mpf(zeta_v) * self.w)
        self.p, self.q, self.A, self.B = (mp.mpf(x) for x in (p, q, A, B))

    @fifty_digits
    def coeffs(self, t, y, v, n: int = TERMS) -> list:
        """Taylor coefficients c_j = y⁽ʲ⁾(t)/j!, j = 0..n, from the equation."""
        psi = self.w * t - self.lead
        sn, cs = mp.sin(psi), mp.cos(psi)
        d = [mp.mpf(y), mp.mpf(v)]
        wj = mp.mpf(1)
        # j-th derivative of A sin ψ + B cos ψ: ϖʲ (A sin(ψ + jπ/2) + B cos(ψ + jπ/2))
        rot = [(sn, cs), (cs, -sn), (-sn, -cs), (-cs, sn)]
        for j in range(n - 1):
            s_j, c_j = rot[j % 4]
            f = wj * (self.A * s_j + self.B * c_j)
            d.append(f - self.p * d[j + 1] - self.q * d[j])
            wj *= self.w
        out, fact = [], mp.mpf(1)
        for j, dj in enumerate(d):
            if j:
                fact *= j
            out.append(dj / fact)
        return out

    @fifty_digits
    def step(self, t, y, v, h) -> tuple:
        """(y, y') at t + h, |h| ≤ HMAX."""
        c = self.coeffs(t, y, v)
        return horner(c, h), horner(deriv(c), h)

    @fifty_digits
    def advance(self, t, y, v, H) -> tuple:
        """(y, y') at t + H in steps of at most HMAX."""
        n = int(mp.ceil(abs(H) / HMAX)) or 1
        h = mp.mpf(H) / n
        for _ in range(n):
            y, v = self.step(t, y, v, h)
            t += h
        return y, v


@fifty_digits
def vertical(varpi: float, zeta_v: float) -> Oscillator:
    """The head's gap in free flight: ξ'' + 2ζ_v(ξ' + ϖ cos ψ) + ξ = −sin ψ."""
    z = mp.mpf(zeta_v)
    return Oscillator(varpi, zeta_v, 2 * z, 1, -1, -2 * z * mp.mpf(varpi))


@fifty_digits
def tangential(varpi: float, zeta_v: float, alpha: float, zeta_h: float) -> Oscillator:
    """The head's tangential free flight: α ζ'' + 2ζ_h√α(ζ' − ϖ cos ψ) + ζ = sin ψ."""
    a, zh, w = mp.mpf(alpha), mp.mpf(zeta_h), mp.mpf(varpi)
    return Oscillator(varpi, zeta_v, 2 * zh / mp.sqrt(a), 1 / a, 1 / a, 2 * zh * w / mp.sqrt(a))


@fifty_digits
def normal_force(osc: Oscillator, zeta_v: float, t):
    """N = sin ψ + 2ζ_vϖ cos ψ at τ = t."""
    psi = osc.w * t - osc.lead
    return mp.sin(psi) + 2 * mp.mpf(zeta_v) * osc.w * mp.cos(psi)


@fifty_digits
def next_hit(osc: Oscillator, t, x, v, horizon) -> tuple | None:
    """(τ, ξ'⁻) of the first hit after t from (ξ, ξ') = (x, v), within ``horizon``.

    From ξ = 0 the root at the start is divided out (ξ/h), so the search sees the flight
    however short; the window of the first step is a few times the flight's estimate
    2v/a when that is short."""
    t, x, v = mp.mpf(t), mp.mpf(x), mp.mpf(v)
    end = t + horizon
    while t < end:
        c = osc.coeffs(t, x, v)
        H = min(HMAX, end - t)
        at_zero = x == 0
        if at_zero and c[2] < 0 and v > 0:
            H = min(H, 4 * v / (-2 * c[2]))  # flight ≈ 2v/a, a = −ξ'' = −2c_2
        if at_zero:
            q = c[1:]

            def g(h, q=q):
                return horner(q, h)
        else:

            def g(h, c=c):
                return horner(c, h)

        grid = [H * (i + 1) / GRID for i in range(GRID)]
        prev = (mp.mpf(0), g(mp.mpf(0)))
        for h in grid:
            gh = g(h)
            if prev[1] > 0 and gh <= 0:
                root = mp.findroot(g, (prev[0], h), solver="anderson")
                return t + root, horner(deriv(c), root)
            prev = (h, gh)
        x, v = horner(c, H), horner(deriv(c), H)
        t += H
    return None


@fifty_digits
def chattering(varpi: float, zeta_v: float, e: float, t0, horizon, x0=0, v0=0) -> dict:
    """Head motion from (ξ, ξ') = (x0, v0) at t0, hit by hit with ξ' → −e ξ', until a
    hit in contact conditions (N ≥ 0) accumulates (flights below FLIGHT_END) or
    ``horizon`` passes. Returns {"hits": hit times, "v_in": impact velocities,
    "contact": accumulation time or None}. With e = 0 the first hit where N ≥ 0 is the
    contact start (plastic), where N < 0 an impulsive stop."""
    osc = vertical(varpi, zeta_v)
    e = mp.mpf(e)
    t, x, v = mp.mpf(t0), mp.mpf(x0), mp.mpf(v0)
    end = t + horizon
    hits, vins = [], []
    while True:
        nh = next_hit(osc, t, x, v, end - t)
        if nh is None:
            return {"hits": hits, "v_in": vins, "contact": None}
        th, vin = nh
        if hits and th - hits[-1] < FLIGHT_END and normal_force(osc, zeta_v, th) >= 0:
            return {"hits": hits, "v_in": vins, "contact": th}
        hits.append(th)
        vins.append(vin)
        if e == 0 and normal_force(osc, zeta_v, th) >= 0:
            return {"hits": hits, "v_in": vins, "contact": th}
        t, x, v = th, mp.mpf(0), -e * vin
