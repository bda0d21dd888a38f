"""Values and bounds of the event functions of an evaluator, at a point (unit-free).

The evaluator (:mod:`evaluators`, one record of :data:`evaluators.EVALUATOR_DTYPE`)
holds one phase's event functions in closed form; here they are evaluated for the
certified search (:mod:`search`): values with f' (and f'' in fast mode)
(:func:`evaluate`), a search step's look with local |f''| bounds and envelope lengths
(:func:`probe`), the whole-window clearance test (:func:`clear`) and the derivative bound
of a phase started on its event surface (:func:`start_bound`).
"""

from __future__ import annotations

import math

from betvdesign.dynamics import damped_values as damped
from betvdesign.dynamics.bounds import (
    cos_range_prep,
    cos_range_to,
    derivative_bound,
    envelope_at,
    local_m2,
)
from betvdesign.dynamics.evaluators import SLIP_KIND, STICK_KIND
from betvdesign.dynamics.flows import oscillator, slider
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
    """(f_i, f_i', f_i'') at h into out[0:2], out[2:4], out[4:6]; returns (y, y') of the
    oscillator."""
    if e["gen"]:
        return damped.evaluate(e, h, out)
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
    """One search step's look at h: f, f', a local |f''| bound and the envelope's
    certified no-root length of each function into out[0:2], [2:4], [4:6], [6:8]."""
    y, yd = evaluate(e, h, out)
    if e["gen"]:
        damped.m2_bound(e, h, y, yd, out)
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
    """Every function provably positive on [h, H] (slow envelope minus the free
    oscillation's amplitude). ``end``: 4 floats, cos_range_prep of the window's end,
    filled on first use (end[3] = 1)."""
    if not e["clearable"]:
        return False
    if e["gen"]:
        return damped.clear(e, h)
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
    """Bound on |f_i⁽ᵒʳᵈᵉʳ⁺¹⁾| over the window: the smaller of the energy-growth bound
    (plus |q|ϖʲ) and the split bound |P − q|ϖʲ + w0^(j−1) E_h (j = order + bj); the
    general form's bound (:func:`damped.start_bound`) with damping."""
    if e["gen"]:
        return damped.start_bound(e, order)
    j = order + e["bj"]
    w0, wf, q = e["w0"], e["wf"], e["q"][i]
    ba = derivative_bound(w0, e["F"], wf, e["R0"], j) + abs(q) * wf ** float(j)
    P = e["P"]
    if P == P:  # the split bound exists (not at exact resonance)
        bb = abs(P - q) * wf ** float(j) + w0 ** float(j - 1) * e["Eh"]
        ba = min(ba, bb)
    return ba / e["bdiv"]
