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

from betvdesign.dynamics.jit import jit_enabled, kernel
from betvdesign.model.params import ModelParams, normal_force_phase

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
        ("g", np.float64),
        ("G", np.float64),
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
        ("g", np.float64),
        ("G", np.float64),
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
        ("damped", np.bool_),
        ("g_free", np.float64),
        ("G_free", np.float64),
        ("zeta_v", np.float64),
        ("A", np.float64),
        ("bA", np.float64),
        ("e", np.float64),
    ]
)
#: a record of :data:`TABLE_DTYPE` (``phase_table(p)[0]``), as the kernels see it
PhaseTable = np.void


@kernel
def _forced_amplitude(w0: float, F: float, wf: float) -> float:
    """P = F/(w0² − ϖ²) of the forced response P sin φ; NaN at exact resonance."""
    den = w0 * w0 - wf * wf
    return math.nan if den == 0.0 else F / den


@kernel
def _split_ok(P: float, w0: float, F: float) -> bool:
    """The split "P sin φ + free oscillation" is free of cancellation: |1 − aϖ²| ≥ 0.1."""
    return P == P and abs(P) * w0 * w0 <= 10.0 * abs(F)


@kernel
def _slip_fields(r, sig: float, b: float, w0: float, F: float, wf: float, ds: float) -> None:
    """Write the fields of :data:`SLIP_DTYPE` of the undamped slip (σ = +1) or reverse slip."""
    P = _forced_amplitude(w0, F, wf)
    fast = _split_ok(P, w0, F)
    r["sig"], r["q"], r["w0"], r["F"], r["ds"], r["P"] = sig, 1.0 - sig * b, w0, F, ds, P
    r["apq"] = 0.0 if P != P else abs(P - (1.0 - sig * b)) * wf
    r["K"] = sig * (P * wf + ds / wf) if fast else 0.0
    r["fast"], r["g"], r["G"] = fast, 0.0, 0.0


@kernel
def _damped_slip_fields(r, sig: float, b: float, al: float, be: float, ka: float, zh: float,
                        A: float, Fs: float, Gc: float) -> None:  # fmt: skip
    """Write the fields of :data:`SLIP_DTYPE` of a damped slip (σ = +1) or reverse slip."""
    r["sig"], r["q"], r["w0"] = sig, 1.0 - sig * b, 1.0 / math.sqrt(al)
    r["F"], r["ds"] = (Fs - sig * al * ka * A) / al, sig * be * ka * A
    r["P"], r["apq"], r["K"], r["fast"] = math.nan, 0.0, 0.0, False
    r["g"], r["G"] = zh * math.sqrt(al) / al, Gc / al


@kernel
def table_record(al, be, ka, wf, e, damped, zv, zh, delta, A):
    """The phase table's record (:func:`phase_table`), compiled: one call, no dicts.

    Parameters
    ----------
    al, be, ka, wf : float
        α, β, κ, ϖ [-].
    e : float
        Coefficient of restitution [-].
    damped : bool
        Every phase in its general (damped) form.
    zv, zh : float
        Damping ratios ζ_v, ζ_h [-] (read when ``damped``).
    delta, A : float
        Phase δ [rad] and amplitude A [-] of the normal force
        (:func:`~betvdesign.model.params.normal_force_phase`; read when ``damped``).

    Returns
    -------
    numpy.ndarray
        One record of :data:`TABLE_DTYPE`.
    """
    t = np.zeros(1, TABLE_DTYPE)
    c = t[0]
    a_st = al * (1.0 + 1.0 / be)
    w_free = 1.0 / math.sqrt(al)
    w_st = 1.0 / math.sqrt(a_st)
    b = al * ka * (1.0 + be)
    F_st = 1.0 / a_st
    q0, q1 = 1.0 - b, 1.0 + b
    c["varpi"], c["alpha"], c["beta"], c["kappa"], c["b"] = wf, al, be, ka, b
    c["a_stick"], c["w_free"], c["e"] = a_st, w_free, e
    st = c["stick"]
    q, a2, a3, K = st["q"], st["a2"], st["a3"], st["K"]
    q[0], q[1] = q0, q1
    st["w3"] = math.pow(wf, 3.0)  # as Python's wf**3 (libm pow)
    if not damped:
        c["F_free"] = 1.0 / al
        _slip_fields(c["slip"], 1.0, b, w_free, (1.0 - al * ka) / al, wf, be * ka)
        _slip_fields(c["reverse"], -1.0, b, w_free, (1.0 + al * ka) / al, wf, -be * ka)
        P = _forced_amplitude(w_st, F_st, wf)
        fast = _split_ok(P, w_st, F_st)
        if P == P:
            a2[0], a2[1] = abs(P - q0) * wf * wf, abs(P - q1) * wf * wf
        if fast:
            a3[0], a3[1] = abs(P - q0) * math.pow(wf, 3.0), abs(P - q1) * math.pow(wf, 3.0)
            K[0], K[1] = P - q0, -1.0 * (P - q1)
        st["w0"], st["F"], st["P"], st["fast"] = w_st, F_st, P, fast
        c["damped"], c["zeta_v"], c["A"], c["bA"] = False, 0.0, 1.0, b
        return t
    cd, sd = math.cos(delta), math.sin(delta)
    D = 2.0 * zh * math.sqrt(al) * wf
    # G = D cos δ − sin δ = 2ϖ cos δ (ζ_h√α − ζ_v) (tan δ = 2ζ_vϖ): in this form it is
    # exactly 0 when the tangential and normal dampers balance (ζ_h√α = ζ_v), not ±1e-18
    Fs, Gc = cd + D * sd, 2.0 * wf * cd * (zh * math.sqrt(al) - zv)
    c["F_free"] = Fs / al
    _damped_slip_fields(c["slip"], 1.0, b, al, be, ka, zh, A, Fs, Gc)
    _damped_slip_fields(c["reverse"], -1.0, b, al, be, ka, zh, A, Fs, Gc)
    st["w0"], st["F"], st["P"], st["fast"] = 1.0 / math.sqrt(a_st), Fs / a_st, math.nan, False
    st["g"], st["G"] = zh * math.sqrt(al) / a_st, Gc / a_st
    c["damped"], c["g_free"], c["G_free"] = True, zh * math.sqrt(al) / al, Gc / al
    c["zeta_v"], c["A"], c["bA"] = zv, A, b * A
    return t


def phase_table(p: ModelParams, *, general: bool = False) -> np.ndarray:
    """The constants of every phase of one parameter set (MODEL.md phase table).

    Undamped, the forced amplitudes P = F/(w0² − ϖ²) and the fast split's constants of
    every phase; with damping (docs/damping.md, kernel time φ = ϖτ, N ∝ A sin φ) every
    phase is y'' + 2g y' + w0² y = F sin φ + G cos φ with inertia a (α, or α(1 + 1/β) in
    stick): w0 = 1/sqrt(a), g = ζ_h sqrt(α)/a, F = (cos δ + D sin δ − σακA)/a,
    G = (D cos δ − sin δ)/a = 2ϖ cos δ (ζ_h√α − ζ_v)/a, D = 2ζ_h sqrt(α) ϖ; the slider
    s'' = σβκA sin φ; the undamped fast-path constants (P, K, ...) are not used
    (``damped``: every evaluator takes its general form). Computed by the compiled
    :func:`table_record`.

    Parameters
    ----------
    p : ModelParams
        The model, with its optional damping (then every phase takes its general form).
    general : bool
        Every phase in its general (damped) form even without damping: a second
        implementation of the same events, which must agree with the undamped one at
        zero damping (tests).

    Returns
    -------
    numpy.ndarray
        A one-record array of :data:`TABLE_DTYPE` (w0 = 1/sqrt(a), F = c/a per phase);
        a record array (attribute access in plain Python) when the kernels run as Python
        (``NUMBA_DISABLE_JIT=1``).

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
    """
    damped = general or p.zeta_v != 0.0 or p.zeta_h != 0.0
    delta, A = normal_force_phase(p.zeta_v, p.varpi) if damped else (0.0, 1.0)
    table = table_record(
        p.alpha, p.beta, p.kappa, p.varpi, p.restitution, damped, p.zeta_v, p.zeta_h, delta, A
    )
    return table if jit_enabled() else table.view(np.recarray)


@kernel
def sinc(x: float) -> float:
    """sin(x)/x with the removable singularity filled in (Taylor for |x| < 1e-3).

    Parameters
    ----------
    x : float
        The argument [-].

    Returns
    -------
    float
        sin(x)/x (1 at 0).
    """
    if -1e-3 < x < 1e-3:
        x2 = x * x
        return 1.0 - x2 / 6.0 * (1.0 - x2 / 20.0)
    return math.sin(x) / x


@kernel
def oscillator(
    w0: float, wf: float, F: float, y0: float, v0: float, sp0: float, cp0: float, h: float
) -> tuple[float, float, float, float]:
    """State after time h of y'' + w0² y = F sin(φ0 + wf h), uniformly valid through resonance.

    Closed form in divided differences (module docstring): no cancellation near w0 = wf
    and exactly the secular solution at w0 = wf.

    Parameters
    ----------
    w0 : float
        Natural angular frequency [-] (> 0).
    wf : float
        Forcing angular frequency ϖ [-] (> 0).
    F : float
        Forcing amplitude [-].
    y0, v0 : float
        y and y' at h = 0 [-].
    sp0, cp0 : float
        sin φ0, cos φ0 [-] of the forcing phase at the start.
    h : float
        Time advanced [-] (τ units).

    Returns
    -------
    tuple of 4 floats
        (y, y', sin φ, cos φ) at h [-].

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
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
def decaying_basis(w0: float, g: float, h: float) -> tuple[float, float]:
    """The basis of the free damped oscillation over a step h [-].

    (e^(−gh) cos(w_d h), e^(−gh) sin(w_d h)/w_d), w_d² = w0² − g² [-]: the basis of the
    free damped oscillation y'' + 2g y' + w0² y = 0, one expression for under-, critically
    and overdamped motion (cosh/sinh when w_d² < 0), with no cancellation near critical
    damping: a Taylor series in x = w_d² h² for |x| < 0.01 (9 terms: error < 1e-20
    relative), exponentials of −w0²h/(g + r) and −(g + r)h (r² = g² − w0²) when
    overdamped.

    Parameters
    ----------
    w0 : float
        Undamped angular frequency [-].
    g : float
        Decay rate [-].
    h : float
        Step [-].

    Returns
    -------
    tuple of float
        The two basis functions at h [-].
    """
    x = (w0 - g) * (w0 + g) * h * h
    eg = math.exp(-g * h) if g * h < 745.0 else 0.0
    if -0.01 < x < 0.01:
        c, sn, t = 1.0, 1.0, 1.0
        for k in range(1, 9):
            t = -t * x / ((2 * k - 1) * (2 * k))
            c += t
            sn += t / (2 * k + 1)
        return eg * c, eg * sn * h
    if x > 0.0:
        wd = math.sqrt((w0 - g) * (w0 + g))
        return eg * math.cos(wd * h), eg * math.sin(wd * h) / wd
    r = math.sqrt((g - w0) * (g + w0))
    e1 = math.exp(-w0 * w0 * h / (g + r))
    e2 = math.exp(-(g + r) * h)
    return 0.5 * (e1 + e2), 0.5 * (e1 - e2) / r


@kernel
def forced(
    w0: float,
    g: float,
    wf: float,
    F: float,
    G: float,
    y0: float,
    v0: float,
    sp0: float,
    cp0: float,
    h: float,
) -> tuple[float, float]:
    """State after time h of y'' + 2g y' + w0² y = F sin φ + G cos φ, φ = φ0 + wf h.

    g = 0: :func:`oscillator` (resonance exact; G through the rotated forcing). g > 0:
    the steady response a sin φ + b cos φ, (a, b) = (ΔF + 2gϖG, ΔG − 2gϖF)/(Δ² + 4g²ϖ²),
    Δ = w0² − ϖ², plus the free damped oscillation (:func:`decaying_basis`) of the
    remaining initial state. Near resonance the split cancels up to |a|/|y| ≲ 1/(2ζ)
    (≤ 4 digits for ζ ≥ params.ZETA_MIN).

    Parameters
    ----------
    w0 : float
        Natural angular frequency [-] (> 0).
    g : float
        Damping rate [-] (≥ 0).
    wf : float
        Forcing angular frequency ϖ [-] (> 0).
    F, G : float
        Amplitudes of the sine and cosine forcing [-].
    y0, v0 : float
        y and y' at h = 0 [-].
    sp0, cp0 : float
        sin φ0, cos φ0 [-] of the forcing phase at the start.
    h : float
        Time advanced [-] (τ units).

    Returns
    -------
    tuple of 2 floats
        (y, y') at h [-].

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773 (the undamped model; damping:
    docs/damping.md).
    """
    if g == 0.0:
        if G == 0.0:
            y, yd, _, _ = oscillator(w0, wf, F, y0, v0, sp0, cp0, h)
        else:
            y, yd, _, _ = oscillator(w0, wf, 1.0, y0, v0, F * sp0 + G * cp0, F * cp0 - G * sp0, h)
        return y, yd
    dl = (w0 - wf) * (w0 + wf)
    gw = 2.0 * g * wf
    den = dl * dl + gw * gw
    a = (dl * F + gw * G) / den
    b = (dl * G - gw * F) / den
    cw, sw = math.cos(wf * h), math.sin(wf * h)
    sp, cp = sp0 * cw + cp0 * sw, cp0 * cw - sp0 * sw
    u0 = y0 - (a * sp0 + b * cp0)
    u1 = v0 - wf * (a * cp0 - b * sp0)
    ec, es = decaying_basis(w0, g, h)
    y = a * sp + b * cp + u0 * ec + (u1 + g * u0) * es
    yd = wf * (a * cp - b * sp) + u1 * ec - (w0 * w0 * u0 + g * u1) * es
    return y, yd


@kernel
def rotate(wf: float, sp0: float, cp0: float, h: float) -> tuple[float, float]:
    """(sin φ, cos φ) at φ = φ0 + wf h from (sin φ0, cos φ0).

    Parameters
    ----------
    wf : float
        ϖ [-].
    sp0, cp0 : float
        sin φ0, cos φ0.
    h : float
        Step [-].

    Returns
    -------
    tuple of float
        sin φ, cos φ.
    """
    cw, sw = math.cos(wf * h), math.sin(wf * h)
    return sp0 * cw + cp0 * sw, cp0 * cw - sp0 * sw


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
    """Slider state after h under s'' = ds·sin(φ0 + wf h) (free flight, slip, reverse slip).

    s' = s0' + ds (cos φ0 − cos φ)/wf,  s = s0 + s0' h + ds (h cos φ0 − (sin φ − sin φ0)/wf)/wf.

    Parameters
    ----------
    ds : float
        Slider forcing amplitude [-] (±βκ in slip, 0 in free flight).
    wf : float
        ϖ [-].
    s0, sd0 : float
        s and s' at the start [-].
    sp0, cp0 : float
        sin φ0, cos φ0 [-] of the forcing phase at the start.
    sp, cp : float
        sin φ, cos φ [-] at h.
    h : float
        Time advanced [-] (τ units).

    Returns
    -------
    tuple of 2 floats
        (s, s') at h [-].

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
    """
    if ds == 0.0:
        return s0 + sd0 * h, sd0
    sd = sd0 + ds * (cp0 - cp) / wf
    s = s0 + sd0 * h + ds * (h * cp0 - (sp - sp0) / wf) / wf
    return s, sd


@kernel
def vertical_flight(
    wf: float, zv: float, A: float, xi: float, xid: float, sp0: float, cp0: float, h: float
) -> tuple[float, float, float, float]:
    """No contact, vertical: ξ'' + 2ζ_v ξ' + ξ = −A sin ϖτ over h (undamped: ξ'' + ξ = −sin ϖτ).

    Parameters
    ----------
    wf : float
        ϖ [-].
    zv : float
        Normal damping ratio ζ_v [-].
    A : float
        Normal-force amplitude [-] (1 undamped).
    xi, xid : float
        ξ and ξ' at the start [-].
    sp0, cp0 : float
        sin φ0, cos φ0 [-] of the forcing phase at the start.
    h : float
        Time advanced [-] (τ units).

    Returns
    -------
    tuple of 4 floats
        (ξ, ξ', sin φ, cos φ) at h [-].

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
    """
    y, yd = forced(1.0, zv, wf, -A, 0.0, xi, xid, sp0, cp0, h)
    sp, cp = rotate(wf, sp0, cp0, h)
    return y, yd, sp, cp


@kernel
def free_flight(
    c: PhaseTable, z: float, zd: float, s: float, sd: float, cp0: float, h: float
) -> tuple[float, float, float, float]:
    """No contact, tangential: α ζ'' + ζ = sin ϖτ, s'' = 0, over h.

    :func:`flow`'s free phase started at a forcing phase 0 or π (sin φ0 = 0).

    Parameters
    ----------
    c : PhaseTable
        The constants of the parameter set (a record of :func:`phase_table`).
    z, zd, s, sd : float
        ζ, ζ', s, s' at the start [-].
    cp0 : float
        cos φ0 = ±1 [-]: the flight starts at a forcing phase 0 (a section) or π (a contact
        end).
    h : float
        Time advanced [-] (τ units).

    Returns
    -------
    tuple of 4 floats
        (ζ, ζ', s, s') at h [-].

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
    """
    return flow(c, FREE, z, zd, s, sd, 0.0, cp0, h)


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
    """Contact, slip (ζ' > s') or reverse slip (ζ' < s'), over h.

    α ζ'' + ζ = (1 ∓ ακ) sin ϖτ, s'' = ±βκ sin ϖτ (with damping: docs/damping.md).

    Parameters
    ----------
    c : PhaseTable
        The constants of the parameter set (a record of :func:`phase_table`).
    phase : int
        ``SLIP`` or ``REVERSE``.
    z, zd, s, sd : float
        ζ, ζ', s, s' at the start [-].
    sp0, cp0 : float
        sin φ0, cos φ0 [-] of the forcing phase at the start.
    h : float
        Time advanced [-] (τ units).

    Returns
    -------
    tuple of 4 floats
        (ζ, ζ', s, s') at h [-].

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
    """
    ph = c.slip if phase == SLIP else c.reverse
    zn, zdn = forced(ph.w0, ph.g, c.varpi, ph.F, ph.G, z, zd, sp0, cp0, h)
    sp, cp = rotate(c.varpi, sp0, cp0, h)
    sn, sdn = slider(ph.ds, c.varpi, s, sd, sp0, cp0, sp, cp, h)
    return zn, zdn, sn, sdn


@kernel
def stick_flow(
    c: PhaseTable, z: float, zd: float, s: float, sp0: float, cp0: float, h: float
) -> tuple[float, float, float, float]:
    """Contact, stick (ζ' = s'), over h: α(1 + 1/β) ζ'' + ζ = sin ϖτ, s'' = ζ''.

    The slider and the head move together: s − ζ stays constant.

    Parameters
    ----------
    c : PhaseTable
        The constants of the parameter set (a record of :func:`phase_table`).
    z, zd, s : float
        ζ, ζ' (= s') and s at the start [-].
    sp0, cp0 : float
        sin φ0, cos φ0 [-] of the forcing phase at the start.
    h : float
        Time advanced [-] (τ units).

    Returns
    -------
    tuple of 4 floats
        (ζ, ζ', s, s') at h [-].

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
    """
    st = c.stick
    zn, zdn = forced(st.w0, st.g, c.varpi, st.F, st.G, z, zd, sp0, cp0, h)
    return zn, zdn, s + (zn - z), zdn


@kernel
def stick_velocity(zd: float, sd: float, beta: float) -> float:
    """Common velocity on entering stick: the one conserving the momentum ζ' + s'/β.

    Parameters
    ----------
    zd, sd : float
        ζ' and s' just before [-].
    beta : float
        β = m/M [-].

    Returns
    -------
    float
        The common velocity ζ' = s' [-].

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
    """
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
    """State after h in any phase (dense output), free flight from any forcing phase.

    Parameters
    ----------
    c : PhaseTable
        The constants of the parameter set (a record of :func:`phase_table`).
    phase : int
        ``FREE``, ``SLIP``, ``STICK`` or ``REVERSE``.
    z, zd, s, sd : float
        ζ, ζ', s, s' at the start [-].
    sp0, cp0 : float
        sin φ0, cos φ0 [-] of the forcing phase at the start.
    h : float
        Time advanced [-] (τ units).

    Returns
    -------
    tuple of 4 floats
        (ζ, ζ', s, s') at h [-].

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
    """
    if phase == STICK:
        return stick_flow(c, z, zd, s, sp0, cp0, h)
    if phase == FREE:
        zn, zdn = forced(c.w_free, c.g_free, c.varpi, c.F_free, c.G_free, z, zd, sp0, cp0, h)
        return zn, zdn, s + sd * h, sd
    return slip_flow(c, phase, z, zd, s, sd, sp0, cp0, h)
