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

import numpy as np

from betvdesign.dynamics._jit import jit_enabled, kernel
from betvdesign.params import ModelParams

# Phase codes (ints: they sit in the inner loops).
FREE = 2
SLIP = 1
STICK = 0
REVERSE = -1

PHASE_NAMES = {FREE: "free", SLIP: "slip", STICK: "stick", REVERSE: "reverse"}


#: Constants of slip (σ = +1) or reverse slip (σ = −1) for one parameter set:
#: α ζ'' + ζ = (1 − σακ) sin ϖτ, i.e. ζ'' + w0² ζ = F sin ϖτ; s'' = ds sin ϖτ with
#: ds = σβκ. ``q`` = 1 − σb: the stick-band edge whose derivative f' = σ(q sin φ − ζ)/α
#: the event ζ' = s' has. ``P`` [-]: amplitude of the forced part P sin φ (NaN at exact
#: resonance), ``fast``: |1 − αϖ²| ≥ 0.1 (the split bounds of :mod:`evaluators` hold);
#: ``apq`` = |P − q|ϖ and ``K`` = σ(Pϖ + ds/ϖ): the slow envelope of ζ' − s'.
SLIP_DTYPE = np.dtype(
    [
        ("sig", np.float64),
        ("q", np.float64),
        ("w0", np.float64),
        ("F", np.float64),
        ("ds", np.float64),
        ("P", np.float64),
        ("apq", np.float64),
        ("K", np.float64),
        ("fast", np.bool_),
    ]
)
#: Constants of stick: α(1 + 1/β) ζ'' + ζ = sin ϖτ, band edges q = (1 − b, 1 + b);
#: ``a2``, ``a3`` = |P − q|ϖ², |P − q|ϖ³ per edge (bounds), ``K`` = ±(P − q) (slow
#: envelopes of the band distances), ``w3`` = ϖ³.
STICK_DTYPE = np.dtype(
    [
        ("w0", np.float64),
        ("F", np.float64),
        ("q", np.float64, (2,)),
        ("P", np.float64),
        ("a2", np.float64, (2,)),
        ("a3", np.float64, (2,)),
        ("K", np.float64, (2,)),
        ("w3", np.float64),
        ("fast", np.bool_),
    ]
)
#: Everything the contact loop needs of one parameter set (MODEL.md phase table), one
#: record: ``b`` = ακ(1 + β) half-width of the stick band, ``a_stick`` = α(1 + 1/β) stick
#: inertia, ``w_free``, ``F_free``: free flight ζ'' + w² ζ = F sin ϖτ; per contact phase
#: ``slip``, ``reverse`` (:data:`SLIP_DTYPE`) and ``stick`` (:data:`STICK_DTYPE`).
#: A record array (cheap to hand to compiled code); kernels read it as ``c = table[0]``.
TABLE_DTYPE = np.dtype(
    [
        ("varpi", np.float64),
        ("alpha", np.float64),
        ("beta", np.float64),
        ("kappa", np.float64),
        ("b", np.float64),
        ("a_stick", np.float64),
        ("w_free", np.float64),
        ("F_free", np.float64),
        ("slip", SLIP_DTYPE),
        ("reverse", SLIP_DTYPE),
        ("stick", STICK_DTYPE),
    ]
)
#: a record of :data:`TABLE_DTYPE` (``phase_table(p)[0]``), as the kernels see it
PhaseTable = np.void


def _forced_amplitude(w0: float, F: float, wf: float) -> float:
    """P = F/(w0² − ϖ²) of the forced response P sin φ; NaN at exact resonance."""
    den = w0 * w0 - wf * wf
    return math.nan if den == 0.0 else F / den


def _split_ok(P: float, w0: float, F: float) -> bool:
    """The split "P sin φ + free oscillation" is free of cancellation: |1 − aϖ²| ≥ 0.1."""
    return P == P and abs(P) * w0 * w0 <= 10.0 * abs(F)


def _slip_phase(sig: float, b: float, w0: float, F: float, wf: float, ds: float) -> tuple:
    q = 1.0 - sig * b
    P = _forced_amplitude(w0, F, wf)
    fast = _split_ok(P, w0, F)
    apq = 0.0 if P != P else abs(P - q) * wf
    K = sig * (P * wf + ds / wf) if fast else 0.0
    return (sig, q, w0, F, ds, P, apq, K, fast)


def phase_table(p: ModelParams) -> np.ndarray:
    """The constants of parameters p, a one-record array of :data:`TABLE_DTYPE`
    (w0 = 1/sqrt(a), F = c/a per phase); a record array (attribute access in plain
    Python) when the kernels run as Python (``NUMBA_DISABLE_JIT=1``)."""
    if not p.ideal:
        from betvdesign.errors import ParameterError

        raise ParameterError("damping and restitution are not supported by this build yet")
    al, be, ka, wf = p.alpha, p.beta, p.kappa, p.varpi
    a_st = al * (1.0 + 1.0 / be)
    w_free = 1.0 / math.sqrt(al)
    w_st = 1.0 / math.sqrt(a_st)
    b = al * ka * (1.0 + be)
    slip = _slip_phase(1.0, b, w_free, (1.0 - al * ka) / al, wf, be * ka)
    reverse = _slip_phase(-1.0, b, w_free, (1.0 + al * ka) / al, wf, -be * ka)
    F_st = 1.0 / a_st
    qs = (1.0 - b, 1.0 + b)
    P = _forced_amplitude(w_st, F_st, wf)
    fast = _split_ok(P, w_st, F_st)
    a2 = (0.0, 0.0) if P != P else (abs(P - qs[0]) * wf * wf, abs(P - qs[1]) * wf * wf)
    a3 = (abs(P - qs[0]) * wf**3, abs(P - qs[1]) * wf**3) if fast else (0.0, 0.0)
    K = (P - qs[0], -1.0 * (P - qs[1])) if fast else (0.0, 0.0)
    stick = (w_st, F_st, qs, P, a2, a3, K, wf**3, fast)
    row = (wf, al, be, ka, b, a_st, w_free, 1.0 / al, slip, reverse, stick)
    table = np.array([row], dtype=TABLE_DTYPE)
    return table if jit_enabled() else table.view(np.recarray)


@kernel
def sinc(x: float) -> float:
    """sin(x)/x with the removable singularity filled in (Taylor for |x| < 1e-3)."""
    if -1e-3 < x < 1e-3:
        x2 = x * x
        return 1.0 - x2 / 6.0 * (1.0 - x2 / 20.0)
    return math.sin(x) / x


@kernel
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


@kernel
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


@kernel
def vertical_flight(
    wf: float, xi: float, xid: float, sp0: float, cp0: float, h: float
) -> tuple[float, float, float, float]:
    """No contact, vertical: ξ'' + ξ = −sin ϖτ over h: (ξ, ξ', sin φ, cos φ)."""
    return oscillator(1.0, wf, -1.0, xi, xid, sp0, cp0, h)


@kernel
def free_flight(
    c: PhaseTable, z: float, zd: float, s: float, sd: float, cp0: float, h: float
) -> tuple[float, float, float, float]:
    """No contact, tangential: α ζ'' + ζ = sin ϖτ, s'' = 0, over h from a forcing phase
    0 or π (cp0 = ±1: a section or a contact end): (ζ, ζ', s, s')."""
    w0 = c.w_free
    y0, v0, _, _ = oscillator(w0, c.varpi, c.F_free, 0.0, 0.0, 0.0, cp0, h)
    c0, s0 = math.cos(w0 * h), math.sin(w0 * h)
    return z * c0 + zd / w0 * s0 + y0, -z * w0 * s0 + zd * c0 + v0, s + sd * h, sd


@kernel
def slip_flow(
    c: PhaseTable,
    phase: int,
    z: float,
    zd: float,
    s: float,
    sd: float,
    sp0: float,
    cp0: float,
    h: float,
) -> tuple[float, float, float, float]:
    """Contact, slip (ζ' > s') or reverse slip (ζ' < s'): α ζ'' + ζ = (1 ∓ ακ) sin ϖτ,
    s'' = ±βκ sin ϖτ, over h: (ζ, ζ', s, s')."""
    ph = c.slip if phase == SLIP else c.reverse
    zn, zdn, sp, cp = oscillator(ph.w0, c.varpi, ph.F, z, zd, sp0, cp0, h)
    sn, sdn = slider(ph.ds, c.varpi, s, sd, sp0, cp0, sp, cp, h)
    return zn, zdn, sn, sdn


@kernel
def stick_flow(
    c: PhaseTable, z: float, zd: float, s: float, sp0: float, cp0: float, h: float
) -> tuple[float, float, float, float]:
    """Contact, stick (ζ' = s'): α(1 + 1/β) ζ'' + ζ = sin ϖτ, s'' = ζ'' (s − ζ constant),
    over h: (ζ, ζ', s, s')."""
    st = c.stick
    zn, zdn, _, _ = oscillator(st.w0, c.varpi, st.F, z, zd, sp0, cp0, h)
    return zn, zdn, s + (zn - z), zdn


@kernel
def stick_velocity(zd: float, sd: float, beta: float) -> float:
    """Common velocity on entering stick: the one conserving the momentum ζ' + s'/β."""
    return (zd + sd / beta) / (1.0 + 1.0 / beta)


@kernel
def flow(
    c: PhaseTable,
    phase: int,
    z: float,
    zd: float,
    s: float,
    sd: float,
    sp0: float,
    cp0: float,
    h: float,
) -> tuple[float, float, float, float]:
    """(ζ, ζ', s, s') after h in any ``phase`` from a forcing phase (sin, cos) =
    (sp0, cp0); free flight from any phase (dense output) through the general form."""
    if phase == STICK:
        return stick_flow(c, z, zd, s, sp0, cp0, h)
    if phase == FREE:
        zn, zdn, _, _ = oscillator(c.w_free, c.varpi, c.F_free, z, zd, sp0, cp0, h)
        return zn, zdn, s + sd * h, sd
    return slip_flow(c, phase, z, zd, s, sd, sp0, cp0, h)
