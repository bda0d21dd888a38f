"""Damping and restitution terms of the solve_ivp reference (unit-free).

Written from shared MODEL.md "Beyond the paper's idealisation" for :mod:`reference`
(docs/damping.md); like it, nothing of the exact solver is imported.

**Damping** (ζ_v, ζ_h > 0). The equations are MODEL.md's, transcribed literally in the
cart phase ψ = ϖτ_o: free flight ξ'' = −sin ψ − 2ζ_v(ξ' + ϖ cos ψ) − ξ; with the force of
the cart's spring and damper on the head P = sin ψ − ζ − 2ζ_h√α(ζ' − ϖ cos ψ),
α ζ'' = P (free), α ζ'' = P ∓ ακN, s'' = ±βκN (slip / reverse slip),
α(1 + 1/β) ζ'' = P = α(1 + 1/β) s'' (stick), with the contact normal force
N = sin ψ + 2ζ_v ϖ cos ψ. Stick holds while |P| ≤ bN, b = ακ(1 + β) (docs/damping.md:
the friction stick needs is P/(α(1 + β)), at most κN); the events are bN − P = 0 (→ slip)
and bN + P = 0 (→ reverse slip). Time origin: the cycles of the damped model start where
N rises through 0 (the initial state at rest is a contact start, as in the paper),
i.e. τ = τ_o + δ/ϖ with tan δ = 2ζ_vϖ (δ = 0 undamped); then N vanishes again, and the
contact ends, at τ = (2j+1)π/ϖ, where the contact end is integrated to (the phase lead δ
is computed here from its definition; that N = 0 there is checked by the tests). A hit
opens a contact only where N ≥ 0, else it is impulsive.

**Restitution** (e > 0). A hit reverses the normal velocity, ξ' → −e ξ' (the horizontal
velocities do not jump). Every rebound flight is integrated and its hit located like any
other event (max_step a fraction of the flight's own estimate 2v/a, v the rebound
velocity, a = N + 2ζ_v v the pull at ξ = 0, so that tiny flights stay resolved). A
chattering sequence (hits in contact conditions, N ≥ 0, flights shrinking by about e) is
followed hit by hit until the next flight's estimate 2v/a is at most :data:`FLIGHT_TOL`;
its remaining flights are then summed as the geometric tail S = 2v/(a(1 − e)), over
which the tangential motion stays free, and the contact starts at the accumulation time
τ + S (only if that is before the contact would end; else the head bounces on). Error
bound (docs/damping.md): over the tail the pull differs from a by at most ρa, ρ = (AϖS +
4ζ_v v + v²/a)/a (A = √(1 + (2ζ_vϖ)²) bounds |N'|/ϖ; the damper term 2ζ_vξ' moves by at
most 4ζ_v v as |ξ'| ≤ v; the spring by the apex height v²/(2a)), which changes each
flight and each rebound ratio by a relative O(ρ), so the tail is S(1 ± 3ρ/(1 − e)) to
first order: the contact start is off by at most 3ρS/(1 − e) ≤ 3(Aϖ/a + 2ζ_v + S)·S²/(1
− e) (t_f ≤ S, v = a·t_f/2). The tail is closed only when that bound is at most
:data:`TAIL_TOL` (1e-12; it falls as S², so a few more hits always reach it while a > 0;
a flight below solve_ivp's time resolution, 1e-12·max(1, τ), is closed whatever its
bound); the largest bound met is reported in ``message``. Even without the tail the
start would be off by at most S(1 + 3ρ/(1 − e)) ≈ FLIGHT_TOL/(1 − e). A sequence is
never followed for ever: at most :data:`reference.MAX_HITS` hits per cycle, else status "failed".
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from betvdesign.model.params import ModelParams

FREE, SLIP, STICK, REVERSE = "free", "slip", "stick", "reverse"
TANH = "slip-tanh"  # horizontal mode during contact with regularised friction
#: a chattering sequence is closed once the next flight's estimate 2v/a is below [-]
FLIGHT_TOL = 1e-9
#: ... and the first-order error bound of its geometric tail is below [-]
TAIL_TOL = 1e-12
#: rebound flights shorter than this fraction of a cycle get max_step = flight/4
SHORT_FLIGHT = 0.05


class K(NamedTuple):
    """The constants of the reference flows of one parameter set (:func:`constants`)."""

    alpha: float
    beta: float
    kappa: float
    varpi: float
    b: float
    a_stick: float
    zv: float = 0.0  # ζ_v
    dv: float = 0.0  # 2ζ_v ϖ: the damper's share of N
    ch: float = 0.0  # 2ζ_h √α: tangential damper coefficient
    lead: float = 0.0  # δ, tan δ = 2ζ_v ϖ: N rises through 0 at τ = 0
    e: float = 0.0
    damped: bool = False


def constants(p: ModelParams) -> K:
    """Constants of the reference flows (MODEL.md).

    MODEL.md: b = ακ(1 + β) stick-band half-width, α(1 + 1/β) stick inertia; damper
    coefficients 2ζ_vϖ (normal force) and 2ζ_h√α (tangential); the time origin's lead δ.

    Parameters
    ----------
    p : ModelParams
        The model.

    Returns
    -------
    K
        The constants.
    """
    al, be, ka = p.alpha, p.beta, p.kappa
    dv = 2.0 * p.zeta_v * p.varpi
    return K(
        al,
        be,
        ka,
        p.varpi,
        al * ka * (1.0 + be),
        al * (1.0 + 1.0 / be),
        p.zeta_v,
        dv,
        2.0 * p.zeta_h * math.sqrt(al),
        math.atan2(dv, 1.0),
        p.restitution,
        p.zeta_v != 0.0 or p.zeta_h != 0.0,
    )


def normal_force(k: K, tau: float) -> float:
    """Contact normal force N [-] at τ.

    Contact normal force N = sin ψ + 2ζ_v ϖ cos ψ [-] at τ (cart phase ψ = ϖτ − δ);
    sin ϖτ undamped.

    Parameters
    ----------
    k : K
        The flows' constants.
    tau : float
        Time [-].

    Returns
    -------
    float
        N [-].
    """
    if not k.damped:
        return math.sin(k.varpi * tau)
    psi = k.varpi * tau - k.lead
    return math.sin(psi) + k.dv * math.cos(psi)


def push(k: K, psi: float, z: float, zd: float) -> float:
    """P = sin ψ − ζ − 2ζ_h√α(ζ' − ϖ cos ψ): the cart's spring and damper on the head.

    Parameters
    ----------
    k : K
        The flows' constants.
    psi : float
        Cart phase ψ [rad].
    z, zd : float
        ζ and ζ' [-].

    Returns
    -------
    float
        P [-].
    """
    return math.sin(psi) - z - k.ch * (zd - k.varpi * math.cos(psi))


def band_damped(k: K, tau: float, z: float, vs: float, d: float) -> str:
    """The damped stick band tested a look-ahead after τ.

    The damped band |P| ≤ bN a look-ahead d after τ, on the stick flow
    α(1 + 1/β) ζ'' = P from (ζ, common velocity vs) (Taylor to third order in ζ).

    Parameters
    ----------
    k : K
        The flows' constants.
    tau : float
        Time [-].
    z : float
        ζ [-].
    vs : float
        The common velocity ζ' = s' [-].
    d : float
        The look-ahead [-].

    Returns
    -------
    str
        STICK inside the band, SLIP below it, REVERSE above.
    """
    w, A = k.varpi, k.a_stick
    psi = w * tau - k.lead
    z2 = push(k, psi, z, vs) / A
    z3 = (w * math.cos(psi) - vs - k.ch * (z2 + w * w * math.sin(psi))) / A
    zn = z + vs * d + z2 * d * d / 2.0 + z3 * d**3 / 6.0
    vn = vs + z2 * d + z3 * d * d / 2.0
    P, N = push(k, psi + w * d, zn, vn), normal_force(k, tau + d)
    if P > k.b * N:
        return SLIP
    if P < -k.b * N:
        return REVERSE
    return STICK


def rhs_damped(k: K, contact: bool, hmode: str, eps: float):
    """MODEL.md "Beyond the paper's idealisation", literally (module doc).

    Parameters
    ----------
    k : K
        The flows' constants.
    contact : bool
        Head in contact with the slider.
    hmode : str
        The tangential phase (FREE, SLIP, REVERSE, STICK or TANH).
    eps : float
        Width of the tanh regularisation [-].

    Returns
    -------
    callable
        ``rhs(t, y)`` of the state (ξ, ξ', ζ, ζ', s, s') [-].
    """
    al, be, ka, w, A = k.alpha, k.beta, k.kappa, k.varpi, k.a_stick
    zv, dv, ch, lead = k.zv, k.dv, k.ch, k.lead

    def rhs(t: float, y: np.ndarray) -> list[float]:
        psi = w * t - lead
        sn, cs = math.sin(psi), math.cos(psi)
        xdd = 0.0 if contact else -sn - 2.0 * zv * (y[1] + w * cs) - y[0]
        P = sn - y[2] - ch * (y[3] - w * cs)
        N = sn + dv * cs
        if hmode == FREE:
            zdd, sdd = P / al, 0.0
        elif hmode == SLIP:
            zdd, sdd = P / al - ka * N, be * ka * N
        elif hmode == REVERSE:
            zdd, sdd = P / al + ka * N, -be * ka * N
        elif hmode == STICK:
            zdd = P / A
            sdd = zdd
        else:  # TANH
            fr = ka * N * math.tanh((y[3] - y[5]) / eps)
            zdd, sdd = P / al - fr, be * fr
        return [y[1] if not contact else 0.0, xdd, y[3], zdd, y[5], sdd]

    return rhs


def stick_events(k: K) -> list:
    """Damped stick-band exits and their slopes along the flow.

    Damped stick-band exits: bN − P = 0 (friction at its limit, → slip) and
    bN + P = 0 (→ reverse slip), both falling; ``slope(t, y, f)``: their derivatives
    along the flow f (N' = ϖ(cos ψ − 2ζ_vϖ sin ψ), P' = ϖ cos ψ − ζ' − 2ζ_h√α(ζ'' + ϖ² sin ψ)).

    Parameters
    ----------
    k : K
        The flows' constants.

    Returns
    -------
    list of callable
        The two events, terminal and falling, each with its ``slope``.
    """
    w, b = k.varpi, k.b

    def lo(t: float, y: np.ndarray) -> float:
        return b * normal_force(k, t) - push(k, w * t - k.lead, y[2], y[3])

    def hi(t: float, y: np.ndarray) -> float:
        return b * normal_force(k, t) + push(k, w * t - k.lead, y[2], y[3])

    def rates(t: float, y: np.ndarray, f) -> tuple[float, float]:
        psi = w * t - k.lead
        sn, cs = math.sin(psi), math.cos(psi)
        dN = w * (cs - k.dv * sn)
        dP = w * cs - y[3] - k.ch * (f[3] + w * w * sn)
        return b * dN, dP

    lo.terminal, lo.direction = True, -1
    hi.terminal, hi.direction = True, -1
    lo.slope = lambda t, y, f: (lambda r: r[0] - r[1])(rates(t, y, f))
    hi.slope = lambda t, y, f: (lambda r: r[0] + r[1])(rates(t, y, f))
    return [lo, hi]


class Hit(NamedTuple):
    """What a hit does (:func:`apply_hit`).

    What a hit does (:func:`apply_hit`): ``kind`` "contact", "impulsive" (plastic, N < 0),
    "rebound" (restitution; ``step``: max_step for the flight) or "tail" (a chattering
    sequence closed: contact at τ + ``tail``, first-order error bound ``bound``).
    """

    kind: str
    step: float = math.inf
    tail: float = 0.0
    bound: float = 0.0


def apply_hit(k: K, tau: float, y: np.ndarray, t_close: float) -> Hit:
    """Apply a hit at τ to the state y.

    Apply a hit at τ to y (ξ = 0, ξ' → 0 or −e ξ'); t_close: when a contact opened now
    would end. Module doc: contact where N ≥ 0, restitution and its chattering closure.

    Parameters
    ----------
    k : K
        The flows' constants.
    tau : float
        Time of the hit [-].
    y : numpy.ndarray
        The state (ξ, ξ', ζ, ζ', s, s') [-], changed in place.
    t_close : float
        When a contact opened now would end [-].

    Returns
    -------
    Hit
        What the hit does.
    """
    N = normal_force(k, tau)
    y[0] = 0.0
    vin = min(float(y[1]), 0.0)
    if k.e == 0.0 or vin == 0.0:
        y[1] = 0.0
        return Hit("contact" if N >= 0.0 else "impulsive")
    v = -k.e * vin
    y[1] = v
    a = N + 2.0 * k.zv * v  # pull back towards the slider at ξ = 0
    if not a > 0.0:
        return Hit("rebound")
    tf = 2.0 * v / a
    T = 2.0 * math.pi / k.varpi
    step = tf / 4.0 if tf < SHORT_FLIGHT * T else math.inf
    if N >= 0.0 and tf <= FLIGHT_TOL:
        S = tf / (1.0 - k.e)
        amp = math.hypot(1.0, k.dv)
        rho = (amp * k.varpi * S + 4.0 * k.zv * v + v * v / a) / a
        bound = 3.0 * rho * S / (1.0 - k.e)
        tiny = tf <= 1e-12 * max(1.0, abs(tau))  # below solve_ivp's time resolution
        if tau + S < t_close and (bound <= TAIL_TOL or tiny):
            return Hit("tail", step, S, bound)
    return Hit("rebound", step)
