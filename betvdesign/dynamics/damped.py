"""Event functions of the damped model for the certified search (unit-free, compiled).

docs/damping.md and MODEL.md "Beyond the paper's idealisation". With damping every phase
is y'' + 2g y' + w0² y = F sin φ + G cos φ (:func:`flows.forced`; kernel time, the
contact normal force N ∝ A sin φ). The event functions are those of :mod:`evaluators`
written in general form:

- gap (no contact): f = ξ (ξ'' + 2ζ_v ξ' + ξ = −A sin φ); the head hits when f reaches 0.
- slip (σ = +1) / reverse slip (σ = −1): f = σ(ζ' − s'), f' = σ(ζ'' − ds sin φ),
  ds = σβκA; it ends (ζ' = s') when f reaches 0.
- stick: with R = α(1 + 1/β) ζ'' (the spring and damper force the friction must hold,
  ζ'' of the stick flow), g_lo = bA sin φ − R and g_hi = bA sin φ + R; stick ends when one
  reaches 0 (below: slip, above: reverse slip). Undamped this is ζ − (1 ∓ b) sin φ.

There is no split into a forced part and a free oscillation of constant energy (the
undamped fast mode): values come from the closed form and bounds from the energy radius
R = sqrt(y'² + w0² y²) + |(F, G)|·W, which bounds the radius over a window of length W
because d/dh sqrt(y'² + w0² y²) ≤ |F sin φ + G cos φ| when g ≥ 0 (damping only removes
energy); then |y⁽ᵏ⁾| ≤ B_k with B_0 = R/w0, B_1 = R,
B_k = |(F, G)|ϖ^(k−2) + 2g B_(k−1) + w0² B_(k−2) (:func:`derivative_bounds`), sharpened
at each point from the exact f'' (:func:`bounds.local_m2`). Windows are :data:`WINDOW`
radians of the fastest rate (ϖ, w0, 2g). Unlike the undamped fast mode there is no slow
envelope or whole-window clearance yet: a damped cycle costs 1–4× an undamped one
(benchmarks/bench_damped.py).
"""

from __future__ import annotations

import math

from betvdesign.dynamics._jit import kernel
from betvdesign.dynamics.bounds import NOISE, local_m2
from betvdesign.dynamics.evaluators import GAP_KIND, SLIP_KIND, STICK_KIND, _store
from betvdesign.dynamics.flows import REVERSE, SLIP, STICK, PhaseTable, forced, rotate

#: search window [rad of the fastest rate ϖ, w0, 2g]: long enough for few steps, short
#: enough for the energy radius R = E + |(F, G)|·W to stay tight (root evaluations per
#: cycle of the published fit with Q = 30: 49, 44, 58, 70 for 0.25, 0.5, 2, 4)
WINDOW = 0.5


@kernel
def derivative_bounds(w0: float, g: float, Af: float, wf: float, R: float, j: int) -> float:
    """B_j ≥ |y⁽ʲ⁾| on a window of energy radius R (module doc) [-]."""
    b0, b1 = R / w0, R
    if j == 0:
        return b0
    for k in range(2, j + 1):
        bk = Af * wf ** float(k - 2) + 2.0 * g * b1 + w0 * w0 * b0
        b0, b1 = b1, bk
    return b1


@kernel
def taylor(w0, g, wf, F, G, y, yd, sp, cp, k: int) -> tuple[float, float]:
    """(y⁽ᵏ⁾, its round-off scale) at a point, k ≤ 6, from the equation of motion."""
    ys = (y, yd)
    ns = (abs(y), abs(yd))
    a0, a1 = y, yd
    n0, n1 = abs(y), abs(yd)
    if k < 2:
        return ys[k], ns[k]
    fs = F * sp + G * cp
    fc = F * cp - G * sp
    fsa = abs(F * sp) + abs(G * cp)
    fca = abs(F * cp) + abs(G * sp)
    for m in range(2, k + 1):
        j = m - 2
        w = wf ** float(j)
        r = j % 4
        f = (fs, fc, -fs, -fc)[r] * w
        fa = (fsa, fca, fsa, fca)[r] * w
        a2 = f - 2.0 * g * a1 - w0 * w0 * a0
        n2 = fa + 2.0 * g * n1 + w0 * w0 * n0
        a0, a1, n0, n1 = a1, a2, n1, n2
    return a1, n1


@kernel
def _window(H: float, w0: float, wf: float, g: float) -> float:
    return min(H, WINDOW / max(w0, wf, 2.0 * g))


@kernel
def _general(e, g, G, Af, bA, ast) -> None:
    e["gen"] = True
    e["g"], e["G"], e["Af"], e["bA"], e["ast"] = g, G, Af, bA, ast


@kernel
def slip_evaluator(
    c: PhaseTable, phase: int, z, zd, s, sd, sp0, cp0, H: float, from_edge: bool, e
) -> None:
    """f = σ(ζ' − s') of damped slip/reverse slip from (ζ, ζ', s, s') at φ0, window H;
    ``from_edge``: entered at a band edge, where f' = σ(R − σbA sin φ)/α is 0 exactly."""
    ph = c.slip if phase == SLIP else c.reverse
    sig, w0, F, G, g, ds = ph.sig, ph.w0, ph.F, ph.G, ph.g, ph.ds
    wf = c.varpi
    Af = math.hypot(F, G)
    W = _window(H, w0, wf, g)
    E0 = math.sqrt(zd * zd + w0 * w0 * z * z)
    R0 = E0 + Af * W
    y2, n2 = taylor(w0, g, wf, F, G, z, zd, sp0, cp0, 2)
    y3, n3 = taylor(w0, g, wf, F, G, z, zd, sp0, cp0, 3)
    y4, n4 = taylor(w0, g, wf, F, G, z, zd, sp0, cp0, 4)
    ads = abs(ds)
    start = (
        sig * (zd - sd),
        0.0 if from_edge else sig * (y2 - ds * sp0),
        sig * (y3 - ds * wf * cp0),
        sig * (y4 + ds * wf * wf * sp0),
        0.0,
        0.0,
        0.0,
        0.0,
    )
    noise = (
        abs(zd) + abs(sd),
        n2 + ads * abs(sp0),
        n3 + ads * wf * abs(cp0),
        n4 + ads * wf * wf * abs(sp0),
        0.0,
        0.0,
        0.0,
        0.0,
    )
    m2 = derivative_bounds(w0, g, Af, wf, R0, 3) + ads * wf
    r = E0 + Af * H
    _store(
        e,
        SLIP_KIND,
        1,
        H,
        W,
        False,
        False,
        math.atan2(sp0, cp0),
        0.0,
        wf,
        w0,
        F,
        sp0,
        cp0,
        math.nan,
        0.0,
        0.0,
        0.0,
        0.0,
        ds,
        sig,
        c.alpha,
        z,
        zd,
        s,
        sd,
        math.inf,
        R0,
        1.0,
        0,
        0.0,
        0.0,
        0.0,
        0.0,
        (ph.q, 0.0),
        (0.0, 0.0),
        (math.inf, 0.0),
        (0.0, 0.0),
        (m2, 0.0),
        (0, 0),
        (0.0, 0.0),
        (0.0, 0.0),
        (r + abs(sd) + abs(zd) + 1e-300, 0.0),
        start,
        noise,
    )
    _general(e, g, G, Af, c.bA, c.a_stick)


@kernel
def stick_evaluator(c: PhaseTable, z, zd, sp0, cp0, H: float, on_edge: int, e) -> None:
    """Damped stick-band distances g_lo, g_hi (module doc) from (ζ, ζ') at φ0, window H;
    ``on_edge``: stick re-entered on that edge (0 lower, 1 upper), its distance 0 exactly."""
    st = c.stick
    w0, F, G, g = st.w0, st.F, st.G, st.g
    wf, bA, ast = c.varpi, c.bA, c.a_stick
    Af = math.hypot(F, G)
    W = _window(H, w0, wf, g)
    E0 = math.sqrt(zd * zd + w0 * w0 * z * z)
    R0 = E0 + Af * W
    sj = (sp0, wf * cp0, -wf * wf * sp0, -(wf**3) * cp0)
    lo = [0.0] * 4
    hi = [0.0] * 4
    nn = [0.0] * 4
    for j in range(4):
        yj, nj = taylor(w0, g, wf, F, G, z, zd, sp0, cp0, j + 2)
        lo[j] = bA * sj[j] - ast * yj
        hi[j] = bA * sj[j] + ast * yj
        nn[j] = abs(bA * sj[j]) + ast * nj
    if on_edge == 0:
        lo[0] = 0.0
    elif on_edge == 1:
        hi[0] = 0.0
    start = (lo[0], lo[1], lo[2], lo[3], hi[0], hi[1], hi[2], hi[3])
    noise = (nn[0], nn[1], nn[2], nn[3], nn[0], nn[1], nn[2], nn[3])
    m2 = bA * wf * wf + ast * derivative_bounds(w0, g, Af, wf, R0, 4)
    r = E0 + Af * H
    sc = bA + ast * ((2.0 * g + w0) * r + Af)
    _store(
        e,
        STICK_KIND,
        2,
        H,
        W,
        False,
        False,
        math.atan2(sp0, cp0),
        0.5 * math.pi,
        wf,
        w0,
        F,
        sp0,
        cp0,
        math.nan,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        1.0,
        1.0,
        z,
        zd,
        0.0,
        0.0,
        math.inf,
        R0,
        1.0,
        1,
        0.0,
        0.0,
        0.0,
        0.0,
        (st.q[0], st.q[1]),
        (0.0, 0.0),
        (math.inf, math.inf),
        (0.0, 0.0),
        (m2, m2),
        (0, 0),
        (0.0, 0.0),
        (0.0, 0.0),
        (sc, sc),
        start,
        noise,
    )
    _general(e, g, G, Af, bA, ast)


@kernel
def gap_evaluator(wf, zv, A, xi, xid, sp0, cp0, H: float, e) -> None:
    """The gap ξ in damped free flight (ξ'' + 2ζ_v ξ' + ξ = −A sin φ) from (ξ, ξ') at φ0
    (also undamped with restitution: its round-off scale follows the window, so the tiny
    flights of a chattering sequence are located to their own precision)."""
    w0, g, F = 1.0, zv, -A
    W = _window(H, w0, wf, g)
    E0 = math.sqrt(xid * xid + xi * xi)
    R0 = E0 + A * W
    sc = abs(xi) + E0 + A * H + 1e-300  # |ξ| reachable on the window: its round-off scale
    y2, _ = taylor(w0, g, wf, F, 0.0, xi, xid, sp0, cp0, 2)
    y3, _ = taylor(w0, g, wf, F, 0.0, xi, xid, sp0, cp0, 3)
    start = (xi, xid, y2, y3, 0.0, 0.0, 0.0, 0.0)
    noise = (sc, sc, sc, sc, 0.0, 0.0, 0.0, 0.0)
    m2 = derivative_bounds(w0, g, A, wf, R0, 2)
    _store(
        e,
        GAP_KIND,
        1,
        H,
        W,
        False,
        False,
        math.atan2(sp0, cp0),
        0.5 * math.pi,
        wf,
        w0,
        F,
        sp0,
        cp0,
        math.nan,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        1.0,
        1.0,
        xi,
        xid,
        0.0,
        0.0,
        math.inf,
        R0,
        1.0,
        1,
        0.0,
        0.0,
        0.0,
        0.0,
        (0.0, 0.0),
        (0.0, 0.0),
        (math.inf, 0.0),
        (0.0, 0.0),
        (m2, 0.0),
        (0, 0),
        (0.0, 0.0),
        (0.0, 0.0),
        (sc, 0.0),
        start,
        noise,
    )
    _general(e, g, 0.0, A, 0.0, 0.0)


@kernel(inline=True)
def evaluate(e, h: float, out) -> tuple[float, float]:
    """General-form values (f_i, f_i', f_i'') at h into out[0:2], out[2:4], out[4:6];
    returns (y, y')."""
    wf, w0, F, G, g = e["wf"], e["w0"], e["F"], e["G"], e["g"]
    sp0, cp0 = e["sp0"], e["cp0"]
    y, yd = forced(w0, g, wf, F, G, e["z"], e["zd"], sp0, cp0, h)
    sp, cp = rotate(wf, sp0, cp0, h)
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
def m2_bound(e, y: float, yd: float, out) -> None:
    """Local bounds on the second derivatives of the event functions (from their exact
    values and a bound on the third over the next window, :func:`bounds.local_m2`), from
    the point (y, y'), into out[4:6]; no envelope (out[6:8] = 0)."""
    w0, g, Af, wf = e["w0"], e["g"], e["Af"], e["wf"]
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


@kernel
def decide_band(c: PhaseTable, z: float, vs: float, sp: float, cp: float, on: int) -> int:
    """The stick-band rule of :func:`contact.decide_phase` with damping: g_lo, g_hi
    (module doc) compared lexicographically on their Taylor coefficients under the damped
    stick flow from (ζ, common velocity vs): stick inside, slip below, reverse slip above.
    ``on``: 1 / 2 when on the lower / upper edge (its distance 0 exactly)."""
    st = c.stick
    w0, F, G, g = st.w0, st.F, st.G, st.g
    wf, bA, ast = c.varpi, c.bA, c.a_stick
    sj = (sp, wf * cp, -wf * wf * sp, -(wf**3) * cp)
    for edge in range(1, 3):
        sig, phase = (-1.0, SLIP) if edge == 1 else (1.0, REVERSE)
        for j in range(4):
            yj, nj = taylor(w0, g, wf, F, G, z, vs, sp, cp, j + 2)
            dj = 0.0 if j == 0 and on == edge else bA * sj[j] + sig * ast * yj
            nz = NOISE * (abs(bA * sj[j]) + ast * nj)
            if dj > nz:
                break  # leaves the band on the admissible side: not this edge
            if dj < -nz:
                return phase
    return STICK
