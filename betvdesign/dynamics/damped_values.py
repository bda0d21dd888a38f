"""Values and bounds of the damped (general-form) event functions at a point (compiled).

The evaluators are built by :mod:`damped` (see its module doc for the functions, the
fast-mode split and the bounds); here they are evaluated for the certified search
(:mod:`search`, through :mod:`values`): values with f' and f'' (:func:`evaluate`), a
search step's local |f''| bounds and envelope lengths (:func:`m2_bound`), the
whole-window clearance test (:func:`clear`) and the derivative bound of a phase started
on its event surface (:func:`start_bound`).
"""

from __future__ import annotations

import math

from betvdesign.dynamics.bounds import cos_range_prep, cos_range_to, envelope_at, local_m2
from betvdesign.dynamics.damped import derivative_bounds
from betvdesign.dynamics.evaluators import GAP_KIND, SLIP_KIND
from betvdesign.dynamics.flows import decaying_basis, forced, rotate
from betvdesign.dynamics.jit import kernel


@kernel(inline=True)
def evaluate(e, h: float, out) -> tuple[float, float]:
    """General-form values (f_i, f_i', f_i'') at h into out[0:2], out[2:4], out[4:6];
    returns (y, y')."""
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
def m2_bound(e, h: float, y: float, yd: float, out) -> None:
    """Local bounds on the second derivatives of the event functions (from their exact
    values and a bound on the third over the next window, :func:`bounds.local_m2`), from
    the point (y, y'), into out[4:6]; no envelope (out[6:8] = 0)."""
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
        m2 = derivative_bounds(w0, g, Af, wf, r, 2)
        m3 = derivative_bounds(w0, g, Af, wf, r, 3)
    elif kind == SLIP_KIND:
        ads = abs(e["ds"])
        m2 = derivative_bounds(w0, g, Af, wf, r, 3) + ads * wf
        m3 = derivative_bounds(w0, g, Af, wf, r, 4) + ads * wf * wf
    else:
        bA, ast = e["bA"], e["ast"]
        m2 = bA * wf * wf + ast * derivative_bounds(w0, g, Af, wf, r, 4)
        m3 = bA * wf**3 + ast * derivative_bounds(w0, g, Af, wf, r, 5)
    for i in range(e["n"]):
        out[4 + i] = local_m2(out[i], out[2 + i], out[4 + i], m2, m3)
    out[6] = out[7] = 0.0


@kernel
def start_bound(e, order: int) -> float:
    """Bound on |f⁽ᵒʳᵈᵉʳ⁺¹⁾| over the window (general form, either function)."""
    j = order + 1
    w0, g, Af, wf, R = e["w0"], e["g"], e["Af"], e["wf"], e["R0"]
    kind = e["kind"]
    if kind == GAP_KIND:
        return derivative_bounds(w0, g, Af, wf, R, j)
    if kind == SLIP_KIND:
        return derivative_bounds(w0, g, Af, wf, R, j + 1) + abs(e["ds"]) * wf ** float(j - 1)
    return e["bA"] * wf ** float(j) + e["ast"] * derivative_bounds(w0, g, Af, wf, R, j + 2)


@kernel(inline=True)
def clear(e, h: float) -> bool:
    """Every function provably positive on [h, H] (fast mode: the slow part's least value
    over the phase range minus the fast part's bound ct)."""
    wf, H = e["wf"], e["H"]
    for i in range(e["n"]):
        off = e["offs"][i]
        cb, f1, f2 = cos_range_prep(e["phi0"] + wf * H - off)
        lo, _ = cos_range_to(e["phi0"] + wf * h - off, cb, f1, f2)
        if not e["K"][i] * lo - e["cc"] > e["ct"]:
            return False
    return True
