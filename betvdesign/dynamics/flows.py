"""Closed-form flows of every phase of the BETV model (unit-free, scalar float64).

docs/MODEL.md, "Dimensionless model". Every phase is a linear oscillator under
sinusoidal forcing,

    y'' + w0² y = F sin φ(h),   φ(h) = φ0 + ϖ h,   h = τ − τ0 [-],

plus a slider law that is a polynomial in trigonometric functions. The forced
response is written with the two "responses from rest"

    C(h) = (cos ϖh − cos w0 h)/(w0² − ϖ²)      (to cos ϖh),
    S(h) = (sin ϖh − (ϖ/w0) sin w0 h)/(w0² − ϖ²) (to sin ϖh),

evaluated in a divided-difference form (products of sines and sinc(δh/2) with
δ = w0 − ϖ) that has no cancellation near resonance and reduces *exactly* to the
secular solutions at resonance (δ = 0): C = h sin ϖh/(2ϖ),
S = (sin ϖh − ϖh cos ϖh)/(2ϖ²). No parameter is ever nudged.

The forcing phase is carried as the pair (sin φ0, cos φ0) so that phases known
exactly (φ = 0 at a section, φ = π at a contact end) stay exact; local times are
measured inside one actuation cycle so that sin ϖτ never loses digits to a
large τ.

Phase table (docs/MODEL.md): with y = ζ (tangential head position) or ξ (gap),

=========  ================  =========================  ====================
phase      oscillator         forcing amplitude c         slider s''
=========  ================  =========================  ====================
free       α ζ'' + ζ          1                           0
slip       α ζ'' + ζ          1 − ακ                      +βκ sin ϖτ
reverse    α ζ'' + ζ          1 + ακ                      −βκ sin ϖτ
stick      α(1+1/β) ζ'' + ζ   1                           ζ''  (s − ζ constant)
vertical   ξ'' + ξ            −1 (free flight only)       —
=========  ================  =========================  ====================

so w0 = 1/sqrt(a) and F = c/a for a ζ'' + ζ = c sin ϖτ.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from betvdesign.dynamics._jit import jitable
from betvdesign.params import ModelParams

# Phase codes (ints: they sit in the inner loops).
FREE = 2
SLIP = 1
STICK = 0
REVERSE = -1

PHASE_NAMES = {FREE: "free", SLIP: "slip", STICK: "stick", REVERSE: "reverse"}


@jitable
def sinc(x: float) -> float:
    """sin(x)/x with the removable singularity filled in (Taylor for |x| < 1e-3)."""
    if -1e-3 < x < 1e-3:
        x2 = x * x
        return 1.0 - x2 / 6.0 * (1.0 - x2 / 20.0)
    return math.sin(x) / x


@jitable
def oscillator(
    w0: float, wf: float, F: float, y0: float, v0: float, sp0: float, cp0: float, h: float
) -> tuple[float, float, float, float]:
    """State after time h of y'' + w0² y = F sin(φ0 + wf h) [all dimensionless].

    Starts from (y0, v0) at h = 0 with sin φ0 = sp0, cos φ0 = cp0. Returns
    (y, y', sin φ, cos φ) at h. Uniformly valid through resonance (w0 = wf).
    """
    c0 = math.cos(w0 * h)
    s0 = math.sin(w0 * h)
    cw = math.cos(wf * h)
    sw = math.sin(wf * h)
    sg = w0 + wf
    hs = h * sinc(0.5 * (w0 - wf) * h)  # 2 sin(δh/2)/δ
    half = 0.5 * sg * h
    ch = math.cos(half)
    C = math.sin(half) / sg * hs
    S = (s0 - w0 * ch * hs) / (w0 * sg)
    Cp = (w0 * ch * hs + sw) / sg
    Sp = wf * C
    y = y0 * c0 + v0 / w0 * s0 + F * (sp0 * C + cp0 * S)
    yd = -y0 * w0 * s0 + v0 * c0 + F * (sp0 * Cp + cp0 * Sp)
    return y, yd, sp0 * cw + cp0 * sw, cp0 * cw - sp0 * sw


def split_eval(
    P: float, ac: float, as_: float, w0: float, wf: float, sp0: float, cp0: float, h: float
) -> tuple[float, float, float, float]:
    """(y, y', sin φ, cos φ) at h from the split y = P sin φ + a_c cos w0h + a_s sin w0h.

    The cheap form of :func:`oscillator` away from resonance (no cancellation there);
    a_c = y0 − P sin φ0, a_s = (y0' − Pϖ cos φ0)/w0.
    """
    cw, sw = math.cos(wf * h), math.sin(wf * h)
    sp, cp = sp0 * cw + cp0 * sw, cp0 * cw - sp0 * sw
    c0, s0 = math.cos(w0 * h), math.sin(w0 * h)
    return P * sp + ac * c0 + as_ * s0, P * wf * cp + w0 * (as_ * c0 - ac * s0), sp, cp


def energy_radius(w0: float, F: float, y: float, yd: float, H: float) -> float:
    """Bound R on sqrt(y'² + w0² y²) over the next H [-] of forcing |F sin| ≤ |F|.

    d/dh (y'² + w0²y²) = 2 y' F sin φ ≤ 2|F| sqrt(E), hence sqrt(E(h)) ≤ sqrt(E0) + |F| h.
    """
    return math.sqrt(yd * yd + w0 * w0 * y * y) + abs(F) * H


def derivative_bounds(w0: float, F: float, wf: float, R: float, n: int) -> list[float]:
    """Bounds [|y|, |y'|, ..., |y^(n)|] over a window with energy radius R.

    From y^(k) = −w0² y^(k−2) + F wf^(k−2) sin^(k−2)(φ): |y^(k)| ≤ w0²|y^(k−2)| + |F| wf^(k−2).
    """
    b = [R / w0, R]
    for k in range(2, n + 1):
        b.append(w0 * w0 * b[k - 2] + abs(F) * wf ** (k - 2))
    return b


@dataclass(frozen=True, slots=True)
class PhaseConstants:
    """Oscillator constants of every phase for one parameter set (MODEL.md table).

    For phase P: ``w0[P]`` [-] natural frequency, ``F[P]`` [-] forcing amplitude of
    y'' + w0² y = F sin ϖτ, ``ds[P]`` slider forcing (s'' = ds sin ϖτ; stick: s = ζ + c).
    ``b`` = ακ(1+β) is the half-width of the stick band.
    """

    varpi: float
    alpha: float
    beta: float
    kappa: float
    b: float
    a_stick: float
    w0: dict[int, float]
    F: dict[int, float]
    ds: dict[int, float]
    #: per-phase constants of the event searches (:mod:`events`), filled on first use
    cache: dict = field(default_factory=dict, compare=False, repr=False)

    @classmethod
    def from_params(cls, p: ModelParams) -> PhaseConstants:
        al, be, ka = p.alpha, p.beta, p.kappa
        a_st = al * (1.0 + 1.0 / be)
        w_free = 1.0 / math.sqrt(al)
        w_st = 1.0 / math.sqrt(a_st)
        return cls(
            varpi=p.varpi,
            alpha=al,
            beta=be,
            kappa=ka,
            b=al * ka * (1.0 + be),
            a_stick=a_st,
            w0={FREE: w_free, SLIP: w_free, REVERSE: w_free, STICK: w_st},
            F={
                FREE: 1.0 / al,
                SLIP: (1.0 - al * ka) / al,
                REVERSE: (1.0 + al * ka) / al,
                STICK: 1.0 / a_st,
            },
            ds={FREE: 0.0, SLIP: be * ka, REVERSE: -be * ka, STICK: 0.0},
        )


@jitable
def slider(
    ds: float,
    wf: float,
    s0: float,
    sd0: float,
    sp0: float,
    cp0: float,
    sp: float,
    cp: float,
    h: float,
) -> tuple[float, float]:
    """Slider (s, s') after h under s'' = ds·sin(φ0 + wf h) (free, slip, reverse).

    s' = s0' + ds (cos φ0 − cos φ)/wf,  s = s0 + s0' h + ds (h cos φ0 − (sin φ − sin φ0)/wf)/wf.
    (sp0, cp0) and (sp, cp) are sin/cos of the phase at the start and at h.
    """
    if ds == 0.0:
        return s0 + sd0 * h, sd0
    sd = sd0 + ds * (cp0 - cp) / wf
    s = s0 + sd0 * h + ds * (h * cp0 - (sp - sp0) / wf) / wf
    return s, sd


def flow(
    k: PhaseConstants,
    phase: int,
    z: float,
    zd: float,
    s: float,
    sd: float,
    sp0: float,
    cp0: float,
    h: float,
) -> tuple[float, float, float, float, float, float]:
    """Tangential state (ζ, ζ', s, s') and (sin φ, cos φ) after h in ``phase``.

    In stick, s − ζ stays constant and s' = ζ' (the caller enters stick with ζ' = s').
    """
    wf = k.varpi
    zn, zdn, sp, cp = oscillator(k.w0[phase], wf, k.F[phase], z, zd, sp0, cp0, h)
    if phase == STICK:
        return zn, zdn, s + (zn - z), zdn, sp, cp
    sn, sdn = slider(k.ds[phase], wf, s, sd, sp0, cp0, sp, cp, h)
    return zn, zdn, sn, sdn, sp, cp
