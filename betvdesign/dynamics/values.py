"""Values and bounds of the event functions of an evaluator, at a point (unit-free).

The evaluator (:mod:`evaluators`, one record of :data:`evaluators.EVALUATOR_DTYPE`)
holds one phase's event functions in closed form, in the paper's model's form or in the
general (damped) form (``gen``); here they are evaluated for the certified search
(:mod:`search`), each in the evaluator's form: values with f' (and f'' in fast mode,
always in the general form) (:func:`evaluate`), a search step's look with local |f''|
bounds and envelope lengths (:func:`probe`), the whole-window clearance test
(:func:`clear`) and the derivative bound of a phase started on its event surface
(:func:`start_bound`).
"""

from __future__ import annotations

import math

from betvdesign.dynamics.bounds import (
    cos_range_prep,
    cos_range_to,
    derivative_bound,
    envelope_at,
    local_m2,
)
from betvdesign.dynamics.evaluators import (
    GAP_KIND,
    SLIP_KIND,
    STICK_KIND,
    derivative_bound_general,
)
from betvdesign.dynamics.flows import decaying_basis, forced, oscillator, rotate, slider
from betvdesign.dynamics.jit import kernel


@kernel(inline=True)
def _evaluate_uniform(e, h: float, out) -> tuple[float, float]:
    """:func:`evaluate` near resonance (uniform closed form; f'' not given: 0)."""
    wf, sp0, cp0 = e["wf"], e["sp0"], e["cp0"]
    y, yd, sp, cp = oscillator(e["w0"], wf, e["F"], e["z"], e["zd"], sp0, cp0, h)
    out[4] = out[5] = 0.0
    if e["kind"] == SLIP_KIND:
        _, sdn = slider(e["ds"], wf, e["s"], e["sd"], sp0, cp0, sp, cp, h)
        out[0] = e["sig"] * (yd - sdn)
        out[2] = e["sig"] * (e["q"][0] * sp - y) / e["al"]
    elif e["kind"] == STICK_KIND:
        ql, qh = e["q"]
        out[0], out[1] = y - ql * sp, qh * sp - y
        out[2], out[3] = yd - e["qw"][0] * cp, e["qw"][1] * cp - yd
    else:
        out[0], out[2] = y, yd
    return y, yd


@kernel(inline=True)
def evaluate(e, h: float, out) -> tuple[float, float]:
    """The event functions' values and derivatives at h.

    (f_i, f_i', f_i'') at h into out[0:2], out[2:4], out[4:6]; returns (y, y') of the
    oscillator.
    """
    if e["gen"]:
        return _evaluate_general(e, h, out)
    if not e["fast"]:
        return _evaluate_uniform(e, h, out)
    wf, w0, sp0, cp0 = e["wf"], e["w0"], e["sp0"], e["cp0"]
    P, ac, as_ = e["P"], e["ac"], e["as_"]
    cw, sw = math.cos(wf * h), math.sin(wf * h)
    sp, cp = sp0 * cw + cp0 * sw, cp0 * cw - sp0 * sw
    c0, s0 = math.cos(w0 * h), math.sin(w0 * h)
    y = P * sp + ac * c0 + as_ * s0
    yd = e["pwf"] * cp + w0 * (as_ * c0 - ac * s0)
    if e["kind"] == SLIP_KIND:
        sig, al = e["sig"], e["al"]
        sdn = e["sdc"] - e["ds"] * cp / wf
        out[0] = sig * (yd - sdn)
        out[2] = sig * (e["q"][0] * sp - y) / al
        out[4] = sig * (e["qw"][0] * cp - yd) / al
        return y, yd
    ql, qh = e["q"]
    out[0], out[1] = y - ql * sp, qh * sp - y
    out[2], out[3] = yd - e["qw"][0] * cp, e["qw"][1] * cp - yd
    ydd = e["F"] * sp - e["w02"] * y
    w2sp = e["wf2"] * sp
    out[4], out[5] = ydd + ql * w2sp, -ydd - qh * w2sp
    return y, yd


@kernel(inline=True)
def probe(e, h: float, out) -> None:
    """One search step's look at h.

    One search step's look at h: f, f', a local |f''| bound and the envelope's
    certified no-root length of each function into out[0:2], [2:4], [4:6], [6:8].
    """
    y, yd = evaluate(e, h, out)
    if e["gen"]:
        _m2_general(e, h, y, yd, out)
        return
    wf = e["wf"]
    if not e["fast"]:  # energy-growth bounds
        w0, F = e["w0"], e["F"]
        r = math.sqrt(yd * yd + w0 * w0 * y * y) + abs(F) * e["W"]  # energy radius over W
        if e["kind"] == SLIP_KIND:
            out[4] = min((abs(e["q"][0]) * wf + r) / e["al"], e["m2b"][0])
        elif e["kind"] == STICK_KIND:
            bzz = w0 * r + abs(F)
            w2 = wf * wf
            out[4] = min(bzz + abs(e["q"][0]) * w2, e["m2b"][0])
            out[5] = min(bzz + e["q"][1] * w2, e["m2b"][1])
        else:
            out[4] = min(r + 1.0, e["m2b"][0])
        out[6] = out[7] = 0.0
        return
    th = e["phi0"] + wf * h - e["off"]
    for i in range(e["n"]):
        out[4 + i] = local_m2(out[i], out[2 + i], out[4 + i], e["m2b"][i], e["m3b"][i])
        out[6 + i] = envelope_at(e["env_mode"][i], e["env_acos"][i], th, wf)


@kernel(inline=True)
def clear(e, h: float, end) -> bool:
    """Whether every function is provably positive on [h, H].

    Every function provably positive on [h, H] (slow envelope minus the free
    oscillation's amplitude). ``end``: 4 floats, cos_range_prep of the window's end,
    filled on first use (end[3] = 1).
    """
    if not e["clearable"]:
        return False
    if e["gen"]:
        return _clear_general(e, h)
    wf = e["wf"]
    if end[3] == 0.0:
        end[0], end[1], end[2] = cos_range_prep(e["phi0"] + wf * e["H"] - e["off"])
        end[3] = 1.0
    lo, hi = cos_range_to(e["phi0"] + wf * h - e["off"], end[0], end[1], end[2])
    for i in range(e["n"]):
        K = e["K"][i]
        if not (K * lo if K >= 0.0 else K * hi) - e["cc"] > e["ct"]:
            return False
    return True


@kernel
def start_bound(e, i: int, order: int) -> float:
    """Bound on the next derivative of each function over the window.

    Bound on |f_i⁽ᵒʳᵈᵉʳ⁺¹⁾| over the window: the smaller of the energy-growth bound
    (plus |q|ϖʲ) and the split bound |P − q|ϖʲ + w0^(j−1) E_h (j = order + bj); the
    general form's bound (:func:`_start_bound_general`) with damping.
    """
    if e["gen"]:
        return _start_bound_general(e, order)
    j = order + e["bj"]
    w0, wf, q = e["w0"], e["wf"], e["q"][i]
    ba = derivative_bound(w0, e["F"], wf, e["R0"], j) + abs(q) * wf ** float(j)
    P = e["P"]
    if P == P:  # the split bound exists (not at exact resonance)
        bb = abs(P - q) * wf ** float(j) + w0 ** float(j - 1) * e["Eh"]
        ba = min(ba, bb)
    return ba / e["bdiv"]


# --- the general form (damping, restitution) ---------------------------------------------


@kernel(inline=True)
def _evaluate_general(e, h: float, out) -> tuple[float, float]:
    """General-form values and derivatives at h.

    General-form values (f_i, f_i', f_i'') at h into out[0:2], out[2:4], out[4:6];
    returns (y, y').
    """
    wf, w0, F, G, g = e["wf"], e["w0"], e["F"], e["G"], e["g"]
    sp0, cp0 = e["sp0"], e["cp0"]
    sp, cp = rotate(wf, sp0, cp0, h)
    if e["fast"]:  # the stored split: a sin φ + b cos φ plus the free damped part
        a, b, u0, ug = e["P"], e["pwf"], e["ac"], e["as_"]
        ec, es = decaying_basis(w0, g, h)
        u1 = ug - g * u0
        y = a * sp + b * cp + u0 * ec + ug * es
        yd = wf * (a * cp - b * sp) + u1 * ec - (w0 * w0 * u0 + g * u1) * es
    else:
        y, yd = forced(w0, g, wf, F, G, e["z"], e["zd"], sp0, cp0, h)
    w02 = w0 * w0
    fs, fc = F * sp + G * cp, F * cp - G * sp
    ydd = fs - 2.0 * g * yd - w02 * y
    kind = e["kind"]
    if kind == GAP_KIND:
        out[0], out[2], out[4] = y, yd, ydd
        return y, yd
    y3 = wf * fc - 2.0 * g * ydd - w02 * yd
    if kind == SLIP_KIND:
        sig, ds = e["sig"], e["ds"]
        sdn = e["sd"] + ds * (cp0 - cp) / wf
        out[0] = sig * (yd - sdn)
        out[2] = sig * (ydd - ds * sp)
        out[4] = sig * (y3 - ds * wf * cp)
        return y, yd
    bA, ast = e["bA"], e["ast"]
    y4 = -wf * wf * fs - 2.0 * g * y3 - w02 * ydd
    out[0], out[1] = bA * sp - ast * ydd, bA * sp + ast * ydd
    out[2], out[3] = bA * wf * cp - ast * y3, bA * wf * cp + ast * y3
    w2 = bA * wf * wf * sp
    out[4], out[5] = -w2 - ast * y4, -w2 + ast * y4
    return y, yd


@kernel(inline=True)
def _m2_general(e, h: float, y: float, yd: float, out) -> None:
    """Local bounds on the second derivatives of the event functions.

    Local bounds on the second derivatives of the event functions (from their exact
    values and a bound on the third over the next window, :func:`bounds.local_m2`), from
    the point (y, y'), into out[4:6]; no envelope (out[6:8] = 0).
    """
    w0, g, Af, wf = e["w0"], e["g"], e["Af"], e["wf"]
    if e["fast"]:  # split: global bounds, slow envelopes
        for i in range(e["n"]):
            out[4 + i] = local_m2(out[i], out[2 + i], out[4 + i], e["m2b"][i], e["m3b"][i])
            th = e["phi0"] + wf * h - e["offs"][i]
            out[6 + i] = envelope_at(e["env_mode"][i], e["env_acos"][i], th, wf)
        return
    r = math.sqrt(yd * yd + w0 * w0 * y * y) + Af * e["W"]
    kind = e["kind"]
    if kind == GAP_KIND:
        m2 = derivative_bound_general(w0, g, Af, wf, r, 2)
        m3 = derivative_bound_general(w0, g, Af, wf, r, 3)
    elif kind == SLIP_KIND:
        ads = abs(e["ds"])
        m2 = derivative_bound_general(w0, g, Af, wf, r, 3) + ads * wf
        m3 = derivative_bound_general(w0, g, Af, wf, r, 4) + ads * wf * wf
    else:
        bA, ast = e["bA"], e["ast"]
        m2 = bA * wf * wf + ast * derivative_bound_general(w0, g, Af, wf, r, 4)
        m3 = bA * wf**3 + ast * derivative_bound_general(w0, g, Af, wf, r, 5)
    for i in range(e["n"]):
        out[4 + i] = local_m2(out[i], out[2 + i], out[4 + i], m2, m3)
    out[6] = out[7] = 0.0


@kernel
def _start_bound_general(e, order: int) -> float:
    """Bound on |f⁽ᵒʳᵈᵉʳ⁺¹⁾| over the window (general form, either function)."""
    j = order + 1
    w0, g, Af, wf, R = e["w0"], e["g"], e["Af"], e["wf"], e["R0"]
    kind = e["kind"]
    if kind == GAP_KIND:
        return derivative_bound_general(w0, g, Af, wf, R, j)
    if kind == SLIP_KIND:
        return derivative_bound_general(w0, g, Af, wf, R, j + 1) + abs(e["ds"]) * wf ** float(j - 1)
    return e["bA"] * wf ** float(j) + e["ast"] * derivative_bound_general(w0, g, Af, wf, R, j + 2)


@kernel(inline=True)
def _clear_general(e, h: float) -> bool:
    """Whether every function is provably positive on [h, H] (fast mode).

    Every function provably positive on [h, H] (fast mode: the slow part's least value
    over the phase range minus the fast part's bound ct).
    """
    wf, H = e["wf"], e["H"]
    for i in range(e["n"]):
        off = e["offs"][i]
        cb, f1, f2 = cos_range_prep(e["phi0"] + wf * H - off)
        lo, _ = cos_range_to(e["phi0"] + wf * h - off, cb, f1, f2)
        if not e["K"][i] * lo - e["cc"] > e["ct"]:
            return False
    return True
