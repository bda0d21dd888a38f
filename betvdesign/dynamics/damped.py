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

Fast mode (:func:`_split`, the damped analogue of the undamped split; used when it does
not cancel, |(a, b)| w0² ≤ 10 |(F, G)|): y = a sin φ + b cos φ + y_h with y_h a free
damped oscillation whose energy radius E_h = sqrt(y_h'² + w0² y_h²) never grows
(d/dh E_h² = −4g y_h'²), so |y_h⁽ᵏ⁾| ≤ c_k E_h for every h ≥ 0. Each event function is a
slow sinusoid K cos(φ − off) − cc plus a fast part bounded by a multiple of E_h: global
|f''|, |f'''| bounds, slow envelopes and the whole-window clearance test, as undamped.
Otherwise (near resonance with light damping, tiny chattering flights): values from the
closed form and bounds from the energy radius R = sqrt(y'² + w0² y²) + |(F, G)|·W, which
bounds the radius over a window of length W because d/dh sqrt(y'² + w0² y²) ≤
|F sin φ + G cos φ| when g ≥ 0; then |y⁽ᵏ⁾| ≤ B_k with B_0 = R/w0, B_1 = R,
B_k = |(F, G)|ϖ^(k−2) + 2g B_(k−1) + w0² B_(k−2) (:func:`derivative_bounds`), sharpened
at each point from the exact f'' (:func:`bounds.local_m2`), on windows of :data:`WINDOW`
radians of the fastest rate (ϖ, w0, 2g). Values and bounds at a point:
:mod:`damped_values`. Cost: a damped cycle ≈ 1.3× an undamped one (median of the 26
benchmark designs, benchmarks/bench_damped.py).
"""

from __future__ import annotations

import math

from betvdesign.dynamics.bounds import (
    NOISE,
    envelope_prep,
)
from betvdesign.dynamics.evaluators import (
    GAP_KIND,
    SLIP_KIND,
    STICK_KIND,
    init_record,
    put_forcing,
    put_start,
)
from betvdesign.dynamics.flows import (
    REVERSE,
    SLIP,
    STICK,
    PhaseTable,
)
from betvdesign.dynamics.jit import kernel

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
def taylor(w0, g, wf, F, G, y, yd, sp, cp) -> tuple:
    """The derivatives of orders 2 to 5 at a point from the equation of motion, then
    the round-off scale of each (sums of the magnitudes of their terms), in one pass."""
    fs, fc = F * sp + G * cp, F * cp - G * sp
    fsa = abs(F * sp) + abs(G * cp)
    fca = abs(F * cp) + abs(G * sp)
    g2, w2 = 2.0 * g, w0 * w0
    y2 = fs - g2 * yd - w2 * y
    n2 = fsa + g2 * abs(yd) + w2 * abs(y)
    y3 = wf * fc - g2 * y2 - w2 * yd
    n3 = wf * fca + g2 * n2 + w2 * abs(yd)
    y4 = -wf * wf * fs - g2 * y3 - w2 * y2
    n4 = wf * wf * fsa + g2 * n3 + w2 * n2
    y5 = -(wf**3) * fc - g2 * y4 - w2 * y3
    n5 = wf**3 * fca + g2 * n4 + w2 * n3
    return y2, y3, y4, y5, n2, n3, n4, n5


@kernel
def _window(H: float, w0: float, wf: float, g: float) -> float:
    return min(H, WINDOW / max(w0, wf, 2.0 * g))


@kernel
def _general(e, g, G, Af, bA, ast) -> None:
    e["gen"] = True
    e["g"], e["G"], e["Af"], e["bA"], e["ast"] = g, G, Af, bA, ast


@kernel
def _coeffs(w0: float, g: float, k: int) -> float:
    """c_k with |y_h⁽ᵏ⁾| ≤ c_k E_h for a free damped oscillation of energy radius E_h:
    c_0 = 1/w0, c_1 = 1, c_k = 2g c_(k−1) + w0² c_(k−2)."""
    c0, c1 = 1.0 / w0, 1.0
    if k == 0:
        return c0
    for _ in range(2, k + 1):
        c0, c1 = c1, 2.0 * g * c1 + w0 * w0 * c0
    return c1


@kernel
def _split(e, w0, g, wf, F, G, y, yd, sp0, cp0, kind: int, sig: float, ds: float, sd: float):
    """The fast mode of the general form (the damped analogue of the undamped split):
    y = a sin φ + b cos φ + y_h with y_h a free damped oscillation whose energy radius
    E_h = sqrt(y_h'² + w0² y_h²) never grows (d/dh E_h² = −4g y_h'²). Each event function
    is then K_i cos(φ − off_i) − cc plus a fast part bounded by ct (a multiple of E_h):
    global |f''|, |f'''| bounds (the whole window is one step range), slow envelopes and
    the whole-window clearance test. Used when the split does not cancel:
    |(a, b)| w0² ≤ 10 |(F, G)| (as the undamped |1 − aϖ²| ≥ 0.1)."""
    dl = (w0 - wf) * (w0 + wf)
    gw = 2.0 * g * wf
    den = dl * dl + gw * gw
    if den == 0.0:
        return
    a = (dl * F + gw * G) / den
    b = (dl * G - gw * F) / den
    if math.hypot(a, b) * w0 * w0 > 10.0 * math.hypot(F, G):
        return
    yh = y - (a * sp0 + b * cp0)
    yhd = yd - wf * (a * cp0 - b * sp0)
    Eh = math.sqrt(yhd * yhd + w0 * w0 * yh * yh)
    if kind == GAP_KIND and math.hypot(a, b) + Eh / w0 > 8.0 * e["scale"][0]:
        return  # a tiny flight (chattering): the split's terms would swamp the gap
    w2, w3 = wf * wf, wf * wf * wf
    if kind == SLIP_KIND:
        kc, ks = sig * (wf * a + ds / wf), -sig * wf * b
        K0 = math.hypot(kc, ks)
        e["offs"][0] = math.atan2(ks, kc)
        e["K"][0] = K0
        cc = sig * (sd + ds * cp0 / wf)
        ct = Eh
        e["m2b"][0] = K0 * w2 + _coeffs(w0, g, 3) * Eh
        e["m3b"][0] = K0 * w3 + _coeffs(w0, g, 4) * Eh
    elif kind == STICK_KIND:
        bA, ast = e["bA"], e["ast"]
        kl = (ast * w2 * b, bA + ast * w2 * a)
        kh = (-ast * w2 * b, bA - ast * w2 * a)
        cc = 0.0
        ct = ast * _coeffs(w0, g, 2) * Eh
        for i in range(2):
            kc, ks = kl if i == 0 else kh
            Ki = math.hypot(kc, ks)
            e["offs"][i] = math.atan2(ks, kc)
            e["K"][i] = Ki
            e["m2b"][i] = Ki * w2 + ast * _coeffs(w0, g, 4) * Eh
            e["m3b"][i] = Ki * w3 + ast * _coeffs(w0, g, 5) * Eh
    else:
        K0 = math.hypot(a, b)
        e["offs"][0] = math.atan2(a, b)
        e["K"][0] = K0
        cc = 0.0
        ct = Eh / w0
        e["m2b"][0] = K0 * w2 + _coeffs(w0, g, 2) * Eh
        e["m3b"][0] = K0 * w3 + _coeffs(w0, g, 3) * Eh
    e["P"], e["pwf"], e["ac"], e["as_"] = a, b, yh, yhd + g * yh  # for evaluate
    e["fast"] = True
    e["clearable"] = True
    e["W"] = e["H"]
    e["cc"], e["ct"], e["Eh"] = cc, ct, Eh
    for i in range(e["n"]):
        e["m2s"][i] = e["m2b"][i]
        e["env_mode"][i], e["env_acos"][i] = envelope_prep(e["K"][i], -cc, ct)


@kernel
def slip_evaluator(
    c: PhaseTable, phase: int, z, zd, s, sd, sp0, cp0, H: float, from_edge: bool, e
) -> None:
    """Evaluator of f = σ(ζ' − s') with damping in slip (σ = +1) or reverse slip (σ = −1).

    The phase ends (ζ' = s') where f reaches 0.

    Parameters
    ----------
    c : PhaseTable
        The constants of the parameter set (a record of :func:`phase_table`).
    phase : int
        ``SLIP`` or ``REVERSE``.
    z, zd, s, sd : float
        ζ, ζ', s, s' at the window start [-].
    sp0, cp0 : float
        sin φ0, cos φ0 [-] of the forcing phase at the start.
    H : float
        Window length [-].
    from_edge : bool
        Entered at a band edge, where f' = σ(R − σbA sin φ)/α is 0 exactly.
    e : numpy.void
        The evaluator filled (a record of :data:`evaluators.EVALUATOR_DTYPE`), by field name.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
    """
    ph = c.slip if phase == SLIP else c.reverse
    sig, w0, F, G, g, ds = ph.sig, ph.w0, ph.F, ph.G, ph.g, ph.ds
    wf = c.varpi
    Af = math.hypot(F, G)
    W = _window(H, w0, wf, g)
    E0 = math.sqrt(zd * zd + w0 * w0 * z * z)
    R0 = E0 + Af * W
    y2, y3, y4, _, n2, n3, n4, _ = taylor(w0, g, wf, F, G, z, zd, sp0, cp0)
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
    init_record(e, SLIP_KIND, H, W)
    put_forcing(e, wf, w0, F, sp0, cp0)
    put_start(e, start, noise)
    e["R0"], e["bj"] = R0, 0
    e["z"], e["zd"], e["s"], e["sd"] = z, zd, s, sd
    e["ds"], e["sig"], e["al"] = ds, sig, c.alpha
    e["q"][0], e["m2s"][0] = ph.q, m2
    e["scale"][0] = r + abs(sd) + abs(zd) + 1e-300
    _general(e, g, G, Af, c.bA, c.a_stick)
    _split(e, w0, g, wf, F, G, z, zd, sp0, cp0, SLIP_KIND, sig, ds, sd)


@kernel
def stick_evaluator(c: PhaseTable, z, zd, sp0, cp0, H: float, on_edge: int, e) -> None:
    """Evaluator of the stick-band distances g_lo, g_hi with damping.

    Stick ends where one reaches 0: below the band slip, above it reverse slip (module
    doc).

    Parameters
    ----------
    c : PhaseTable
        The constants of the parameter set (a record of :func:`phase_table`).
    z, zd : float
        ζ, ζ' (= s') at the window start [-].
    sp0, cp0 : float
        sin φ0, cos φ0 [-] of the forcing phase at the start.
    H : float
        Window length [-].
    on_edge : int
        Stick re-entered on that edge (0 lower, 1 upper), whose distance is 0 exactly; −1
        none.
    e : numpy.void
        The evaluator filled (a record of :data:`evaluators.EVALUATOR_DTYPE`), by field name.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
    """
    st = c.stick
    w0, F, G, g = st.w0, st.F, st.G, st.g
    wf, bA, ast = c.varpi, c.bA, c.a_stick
    Af = math.hypot(F, G)
    W = _window(H, w0, wf, g)
    E0 = math.sqrt(zd * zd + w0 * w0 * z * z)
    R0 = E0 + Af * W
    sj = (sp0, wf * cp0, -wf * wf * sp0, -(wf**3) * cp0)
    y2, y3, y4, y5, n2, n3, n4, n5 = taylor(w0, g, wf, F, G, z, zd, sp0, cp0)
    b0, b1, b2, b3 = bA * sj[0], bA * sj[1], bA * sj[2], bA * sj[3]
    start = (
        0.0 if on_edge == 0 else b0 - ast * y2,
        b1 - ast * y3,
        b2 - ast * y4,
        b3 - ast * y5,
        0.0 if on_edge == 1 else b0 + ast * y2,
        b1 + ast * y3,
        b2 + ast * y4,
        b3 + ast * y5,
    )
    n0, n1 = abs(b0) + ast * n2, abs(b1) + ast * n3
    n2, n3 = abs(b2) + ast * n4, abs(b3) + ast * n5
    noise = (n0, n1, n2, n3, n0, n1, n2, n3)
    m2 = bA * wf * wf + ast * derivative_bounds(w0, g, Af, wf, R0, 4)
    r = E0 + Af * H
    sc = bA + ast * ((2.0 * g + w0) * r + Af)
    init_record(e, STICK_KIND, H, W)
    put_forcing(e, wf, w0, F, sp0, cp0)
    put_start(e, start, noise)
    e["R0"], e["z"], e["zd"] = R0, z, zd
    e["q"][0], e["q"][1] = st.q[0], st.q[1]
    e["m2s"][0], e["m2s"][1] = m2, m2
    e["scale"][0], e["scale"][1] = sc, sc
    _general(e, g, G, Af, bA, ast)
    _split(e, w0, g, wf, F, G, z, zd, sp0, cp0, STICK_KIND, 1.0, 0.0, 0.0)


@kernel
def gap_evaluator(wf, zv, A, xi, xid, sp0, cp0, H: float, e) -> None:
    """Evaluator of the gap ξ in damped free flight (ξ'' + 2ζ_v ξ' + ξ = −A sin φ).

    Also used undamped with restitution: its round-off scale follows the window, so the
    tiny flights of a chattering sequence are located to their own precision.

    Parameters
    ----------
    wf : float
        ϖ [-].
    zv : float
        Normal damping ratio ζ_v [-].
    A : float
        Normal-force amplitude [-].
    xi, xid : float
        ξ, ξ' at the window start [-].
    sp0, cp0 : float
        sin φ0, cos φ0 [-] of the forcing phase at the start.
    H : float
        Window length [-].
    e : numpy.void
        The evaluator filled (a record of :data:`evaluators.EVALUATOR_DTYPE`), by field name.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
    Budd & Dux, Phil. Trans. R. Soc. A 347 (1994), doi:10.1098/rsta.1994.0044.
    """
    w0, g, F = 1.0, zv, -A
    W = _window(H, w0, wf, g)
    E0 = math.sqrt(xid * xid + xi * xi)
    R0 = E0 + A * W
    sc = abs(xi) + E0 + A * H + 1e-300  # |ξ| reachable on the window: its round-off scale
    y2, y3, _, _, _, _, _, _ = taylor(w0, g, wf, F, 0.0, xi, xid, sp0, cp0)
    start = (xi, xid, y2, y3, 0.0, 0.0, 0.0, 0.0)
    noise = (sc, sc, sc, sc, 0.0, 0.0, 0.0, 0.0)
    m2 = derivative_bounds(w0, g, A, wf, R0, 2)
    init_record(e, GAP_KIND, H, W)
    put_forcing(e, wf, w0, F, sp0, cp0)
    put_start(e, start, noise)
    e["R0"], e["z"], e["zd"] = R0, xi, xid
    e["m2s"][0], e["scale"][0] = m2, sc
    _general(e, g, 0.0, A, 0.0, 0.0)
    _split(e, w0, g, wf, F, 0.0, xi, xid, sp0, cp0, GAP_KIND, 1.0, 0.0, 0.0)


@kernel
def decide_band(c: PhaseTable, z: float, vs: float, sp: float, cp: float, on: int) -> int:
    """The stick-band rule of :func:`contact.decide_phase` with damping.

    g_lo, g_hi (module doc) are compared lexicographically on their Taylor coefficients
    under the damped stick flow from (ζ, common velocity vs): stick inside, slip below,
    reverse slip above.

    Parameters
    ----------
    c : PhaseTable
        The constants of the parameter set (a record of :func:`phase_table`).
    z : float
        ζ [-].
    vs : float
        The common velocity ζ' = s' [-].
    sp, cp : float
        sin φ, cos φ [-] now.
    on : int
        1 / 2 when on the lower / upper edge (its distance 0 exactly), else 0 or −1.

    Returns
    -------
    int
        ``SLIP``, ``STICK`` or ``REVERSE``.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773 (the band; damping:
    docs/damping.md).
    """
    st = c.stick
    w0, F, G, g = st.w0, st.F, st.G, st.g
    wf, bA, ast = c.varpi, c.bA, c.a_stick
    sj = (sp, wf * cp, -wf * wf * sp, -(wf**3) * cp)
    y2, y3, y4, y5, n2, n3, n4, n5 = taylor(w0, g, wf, F, G, z, vs, sp, cp)
    ys = (y2, y3, y4, y5)
    ns = (n2, n3, n4, n5)
    for edge in range(1, 3):
        sig, phase = (-1.0, SLIP) if edge == 1 else (1.0, REVERSE)
        for j in range(4):
            yj, nj = ys[j], ns[j]
            dj = 0.0 if j == 0 and on == edge else bA * sj[j] + sig * ast * yj
            nz = NOISE * (abs(bA * sj[j]) + ast * nj)
            if dj > nz:
                break  # leaves the band on the admissible side: not this edge
            if dj < -nz:
                return phase
    return STICK
