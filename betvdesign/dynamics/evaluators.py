"""The model's event functions, as evaluators for the certified search (unit-free).

docs/MODEL.md, "Impacts and separation" and the stick/slip rules. An
:class:`Evaluator` holds one phase's event functions (one or two) in closed form:

- gap (no contact): f = ξ with ξ'' + ξ = −sin φ; the head hits when f reaches 0.
- slip (σ = +1) / reverse slip (σ = −1): f = σ(ζ' − s'), f' = σ(q sin φ − ζ)/α with
  q = 1 − σb; it ends (ζ' = s') when f reaches 0.
- stick: g_lo = ζ − (1 − b) sin φ and g_hi = (1 + b) sin φ − ζ; stick ends when one
  reaches 0 (below: slip, above: reverse slip).

Away from resonance (``fast``: |1 − aϖ²| ≥ 0.1) the oscillator is split into its forced
part P sin φ and a free oscillation of constant energy E_h, which gives cheap exact
values and f'', tight derivative bounds (|P − q|ϖʲ + w0^(j−1) E_h), slow envelopes and a
whole-window clearance test. Near resonance (exact resonance included: P is NaN) the
uniform closed form (:func:`flows.oscillator`) and energy-growth bounds are used, over
windows of one radian of the fastest frequency.

``start`` holds each function's first four Taylor coefficients at the phase start and
``noise`` their round-off floors (a phase entered *on* its event surface, e.g. slip at
ζ' = s', starts from the first non-vanishing one); ``m2s`` bounds |f''| for the first step.
"""

from __future__ import annotations

import math
from typing import NamedTuple

from betvdesign.dynamics._jit import kernel
from betvdesign.dynamics.bounds import (
    cos_range_prep,
    cos_range_to,
    derivative_bound,
    envelope_at,
    envelope_prep,
    local_m2,
)
from betvdesign.dynamics.flows import SLIP, PhaseTable, oscillator, slider

#: evaluator kinds
SLIP_KIND, STICK_KIND, GAP_KIND = 0, 1, 2

T2 = tuple[float, float]


class Evaluator(NamedTuple):
    """One phase's event functions f_i, i < n, on the window h ∈ [0, H] (see module doc).

    Start state (ζ, ζ', s, s') = (z, zd, s, sd) (gap: (ξ, ξ') in z, zd), forcing phase
    φ0 (sin, cos) = (sp0, cp0); oscillator y'' + w0² y = F sin φ, φ = φ0 + ϖh (wf = ϖ).
    Split (fast mode): y = P sin φ + ac cos w0h + as_ sin w0h, energy E_h = ``Eh``.
    Per function i: ``q`` band coefficient, ``m2b``/``m3b`` global bounds on |f''|/|f'''|,
    ``env_*`` slow envelope, ``K`` envelope amplitude, ``scale`` round-off scale,
    ``start``/``noise`` Taylor coefficients 0..3 (entries 4i..4i+3), ``m2s`` first-step
    |f''| bound. Clearance: min σ(K cos(φ − ``off``) − ``cc``) > ``ct`` on [h, H].
    Start bounds: |f⁽ʲ⁾| from :func:`start_bound` with j = order + ``bj``, / ``bdiv``.
    """

    kind: int
    n: int
    H: float
    W: float
    fast: bool
    clearable: bool
    phi0: float
    off: float
    wf: float
    w0: float
    F: float
    sp0: float
    cp0: float
    P: float
    ac: float
    as_: float
    pwf: float
    sdc: float
    ds: float
    sig: float
    al: float
    z: float
    zd: float
    s: float
    sd: float
    Eh: float
    R0: float
    bdiv: float
    bj: int
    cc: float
    ct: float
    w02: float
    wf2: float
    q: T2
    qw: T2
    m2b: T2
    m3b: T2
    m2s: T2
    env_mode: tuple[int, int]
    env_acos: T2
    K: T2
    scale: T2
    start: tuple[float, float, float, float, float, float, float, float]
    noise: tuple[float, float, float, float, float, float, float, float]


@kernel
def slip_evaluator(
    c: PhaseTable,
    phase: int,
    z: float,
    zd: float,
    s: float,
    sd: float,
    sp0: float,
    cp0: float,
    H: float,
    from_edge: bool,
) -> Evaluator:
    """f = σ(ζ' − s') in slip/reverse slip from (ζ, ζ', s, s') at φ0, window H.
    ``from_edge``: entered at a band edge, where f' = σ(q sin φ − ζ)/α is 0 exactly."""
    ph = c.slip if phase == SLIP else c.reverse
    sig, q, w0, F, ds = ph.sig, ph.q, ph.w0, ph.F, ph.ds
    P, apq, K, fast = ph.P, ph.apq, ph.K, ph.fast
    wf, al = c.varpi, c.alpha
    yh = yhd = 0.0
    if P != P:  # exact resonance: no split
        Eh = m2b = math.inf
        W = min(H, 1.0 / max(w0, wf))
    else:
        yh, yhd = z - P * sp0, zd - P * wf * cp0
        Eh = math.sqrt(yhd * yhd + w0 * w0 * yh * yh)
        m2b = (apq + Eh) / al
        W = H if fast else min(H, 1.0 / max(w0, wf))
    ac = as_ = pwf = m3b = sdc = cc = ct = acs = 0.0
    mode = 0
    if fast:
        ac, as_, pwf = yh, yhd / w0, P * wf
        sdc = sd + ds * cp0 / wf
        m3b = (apq * wf + w0 * Eh) / al
        cc, ct = sig * sdc, Eh
        mode, acs = envelope_prep(K, -cc, Eh)
    azd, asd, aq = abs(zd), abs(sd), abs(q)
    r = math.sqrt(zd * zd + w0 * w0 * z * z) + abs(F) * H  # energy radius over H
    zdd = F * sp0 - w0 * w0 * z
    noise = (
        azd + asd,
        (aq * abs(sp0) + abs(z)) / al,
        (aq * wf * abs(cp0) + azd) / al,
        (aq * wf * wf * abs(sp0) + abs(F * sp0 - w0 * w0 * z)) / al,
        0.0,
        0.0,
        0.0,
        0.0,
    )
    start = (
        sig * (zd - sd),
        0.0 if from_edge else sig * (q * sp0 - z) / al,
        sig * (q * wf * cp0 - zd) / al,
        sig * (-q * wf * wf * sp0 - zdd) / al,
        0.0,
        0.0,
        0.0,
        0.0,
    )
    R0 = math.sqrt(zd * zd + w0 * w0 * z * z) + abs(F) * W  # energy radius over W
    m2s = m2b if fast else min((abs(q) * wf + R0) / al, m2b)
    return Evaluator(
        SLIP_KIND,
        1,
        H,
        W,
        fast,
        fast,
        math.atan2(sp0, cp0),
        0.0,
        wf,
        w0,
        F,
        sp0,
        cp0,
        P,
        ac,
        as_,
        pwf,
        sdc,
        ds,
        sig,
        al,
        z,
        zd,
        s,
        sd,
        Eh,
        R0,
        al,
        0,
        cc,
        ct,
        0.0,
        0.0,
        (q, 0.0),
        (q * wf, 0.0),
        (m2b, 0.0),
        (m3b, 0.0),
        (m2s, 0.0),
        (mode, 0),
        (acs, 0.0),
        (K, 0.0),
        (r + asd + azd + 1e-300, 0.0),
        start,
        noise,
    )


@kernel
def stick_evaluator(
    c: PhaseTable, z: float, zd: float, sp0: float, cp0: float, H: float, on_edge: int
) -> Evaluator:
    """Stick-band distances g_lo, g_hi from (ζ, ζ') at φ0, window H. ``on_edge``: stick
    re-entered on that edge (0 lower, 1 upper), whose distance is 0 exactly."""
    st = c.stick
    w0, F, P, fast, w3 = st.w0, st.F, st.P, st.fast, st.w3
    ql, qh = st.q[0], st.q[1]
    wf = c.varpi
    yh = yhd = 0.0
    if P != P:  # exact resonance: no split
        Eh = math.inf
        W = min(H, 1.0 / max(w0, wf))
        m2b0 = m2b1 = math.inf
    else:
        yh, yhd = z - P * sp0, zd - P * wf * cp0
        Eh = math.sqrt(yhd * yhd + w0 * w0 * yh * yh)
        W = H if fast else min(H, 1.0 / max(w0, wf))
        wE = w0 * Eh
        m2b0, m2b1 = st.a2[0] + wE, st.a2[1] + wE
    ac = as_ = pwf = m3b0 = m3b1 = ct = acs0 = acs1 = w02 = wf2 = 0.0
    mode0 = mode1 = 0
    if fast:
        ac, as_, pwf = yh, yhd / w0, P * wf
        wwE = w0 * w0 * Eh
        m3b0, m3b1 = st.a3[0] + wwE, st.a3[1] + wwE
        ct = Eh / w0
        mode0, acs0 = envelope_prep(st.K[0], 0.0, ct)
        mode1, acs1 = envelope_prep(st.K[1], 0.0, ct)
        w02, wf2 = w0 * w0, wf * wf
    r = math.sqrt(zd * zd + w0 * w0 * z * z) + abs(F) * H  # energy radius over H
    za0, za1 = abs(z), abs(zd)
    za2, za3 = abs(F * sp0 - w0 * w0 * z), abs(F * wf * cp0 - w0 * w0 * zd)
    n0, n1, n2, n3 = sp0, wf * cp0, wf * wf * sp0, w3 * cp0
    z2, z3 = F * sp0 - w0 * w0 * z, F * wf * cp0 - w0 * w0 * zd
    s1, s2, s3 = wf * cp0, -wf * wf * sp0, -w3 * cp0
    noise = (
        za0 + abs(ql * n0),
        za1 + abs(ql * n1),
        za2 + abs(ql * n2),
        za3 + abs(ql * n3),
        za0 + abs(qh * n0),
        za1 + abs(qh * n1),
        za2 + abs(qh * n2),
        za3 + abs(qh * n3),
    )
    start = (
        0.0 if on_edge == 0 else z - ql * sp0,
        zd - ql * s1,
        z2 - ql * s2,
        z3 - ql * s3,
        0.0 if on_edge == 1 else -(z - qh * sp0),
        -(zd - qh * s1),
        -(z2 - qh * s2),
        -(z3 - qh * s3),
    )
    R0 = math.sqrt(zd * zd + w0 * w0 * z * z) + abs(F) * W  # energy radius over W
    if fast:
        m2s0, m2s1 = m2b0, m2b1
    else:
        m2s0 = min(w0 * R0 + abs(F) + abs(ql) * wf * wf, m2b0)
        m2s1 = min(w0 * R0 + abs(F) + abs(qh) * wf * wf, m2b1)
    return Evaluator(
        STICK_KIND,
        2,
        H,
        W,
        fast,
        fast,
        math.atan2(sp0, cp0),
        0.5 * math.pi,
        wf,
        w0,
        F,
        sp0,
        cp0,
        P,
        ac,
        as_,
        pwf,
        0.0,
        0.0,
        1.0,
        1.0,
        z,
        zd,
        0.0,
        0.0,
        Eh,
        R0,
        1.0,
        1,
        0.0,
        ct,
        w02,
        wf2,
        (ql, qh),
        (ql * wf, qh * wf),
        (m2b0, m2b1),
        (m3b0, m3b1),
        (m2s0, m2s1),
        (mode0, mode1),
        (acs0, acs1),
        (st.K[0], st.K[1]),
        (r / w0 + abs(ql), r / w0 + abs(qh)),
        start,
        noise,
    )


@kernel
def gap_evaluator(wf: float, xi: float, xid: float, sp0: float, cp0: float, H: float) -> Evaluator:
    """The gap ξ in free flight (ξ'' + ξ = −sin φ) from (ξ, ξ') at φ0, window H."""
    w0, F = 1.0, -1.0
    den = w0 * w0 - wf * wf
    if den == 0.0:  # vertical resonance ϖ = 1: no split
        P, Eh = math.nan, math.inf
    else:
        P = F / den
        yh, yhd = xi - P * sp0, xid - P * wf * cp0
        Eh = math.sqrt(yhd * yhd + w0 * w0 * yh * yh)
    clearable = P == P and abs(P) * w0 * w0 <= 10.0 * abs(F)
    W = H if clearable else min(H, 1.0 / max(w0, wf))
    m2b = math.inf if P != P else abs(P) * wf * wf + Eh
    r = math.sqrt(xid * xid + w0 * w0 * xi * xi) + abs(F) * H  # energy radius over H
    sc = abs(xi) + r + 1.0
    R0 = math.sqrt(xid * xid + w0 * w0 * xi * xi) + abs(F) * W  # energy radius over W
    start = (xi, xid, -sp0 - xi, -wf * cp0 - xid, 0.0, 0.0, 0.0, 0.0)
    noise = (sc, sc, sc, sc, 0.0, 0.0, 0.0, 0.0)
    return Evaluator(
        GAP_KIND,
        1,
        H,
        W,
        False,
        clearable,
        math.atan2(sp0, cp0),
        0.5 * math.pi,
        wf,
        w0,
        F,
        sp0,
        cp0,
        P,
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
        Eh,
        R0,
        1.0,
        1,
        0.0,
        Eh,
        0.0,
        0.0,
        (0.0, 0.0),
        (0.0, 0.0),
        (m2b, 0.0),
        (0.0, 0.0),
        (min(R0 + 1.0, m2b), 0.0),
        (0, 0),
        (0.0, 0.0),
        (P, 0.0),
        (sc, 0.0),
        start,
        noise,
    )


@kernel
def _evaluate_uniform(e: Evaluator, h: float, out) -> tuple[float, float]:
    """:func:`evaluate` near resonance (uniform closed form; f'' not given: 0)."""
    wf, sp0, cp0 = e.wf, e.sp0, e.cp0
    y, yd, sp, cp = oscillator(e.w0, wf, e.F, e.z, e.zd, sp0, cp0, h)
    out[4] = out[5] = 0.0
    if e.kind == SLIP_KIND:
        _, sdn = slider(e.ds, wf, e.s, e.sd, sp0, cp0, sp, cp, h)
        out[0] = e.sig * (yd - sdn)
        out[2] = e.sig * (e.q[0] * sp - y) / e.al
    elif e.kind == STICK_KIND:
        ql, qh = e.q
        out[0], out[1] = y - ql * sp, qh * sp - y
        out[2], out[3] = yd - e.qw[0] * cp, e.qw[1] * cp - yd
    else:
        out[0], out[2] = y, yd
    return y, yd


@kernel
def evaluate(e: Evaluator, h: float, out) -> tuple[float, float]:
    """(f_i, f_i', f_i'') at h into out[0:2], out[2:4], out[4:6]; returns (y, y') of the
    oscillator."""
    if not e.fast:
        return _evaluate_uniform(e, h, out)
    wf, w0, sp0, cp0 = e.wf, e.w0, e.sp0, e.cp0
    P, ac, as_ = e.P, e.ac, e.as_
    cw, sw = math.cos(wf * h), math.sin(wf * h)
    sp, cp = sp0 * cw + cp0 * sw, cp0 * cw - sp0 * sw
    c0, s0 = math.cos(w0 * h), math.sin(w0 * h)
    y = P * sp + ac * c0 + as_ * s0
    yd = e.pwf * cp + w0 * (as_ * c0 - ac * s0)
    if e.kind == SLIP_KIND:
        sig, al = e.sig, e.al
        sdn = e.sdc - e.ds * cp / wf
        out[0] = sig * (yd - sdn)
        out[2] = sig * (e.q[0] * sp - y) / al
        out[4] = sig * (e.qw[0] * cp - yd) / al
        return y, yd
    ql, qh = e.q
    out[0], out[1] = y - ql * sp, qh * sp - y
    out[2], out[3] = yd - e.qw[0] * cp, e.qw[1] * cp - yd
    ydd = e.F * sp - e.w02 * y
    w2sp = e.wf2 * sp
    out[4], out[5] = ydd + ql * w2sp, -ydd - qh * w2sp
    return y, yd


@kernel
def probe(e: Evaluator, h: float, out) -> None:
    """One search step's look at h: f, f', a local |f''| bound and the envelope's
    certified no-root length of each function into out[0:2], [2:4], [4:6], [6:8]."""
    y, yd = evaluate(e, h, out)
    wf = e.wf
    if not e.fast:  # energy-growth bounds
        w0, F = e.w0, e.F
        r = math.sqrt(yd * yd + w0 * w0 * y * y) + abs(F) * e.W  # energy radius over W
        if e.kind == SLIP_KIND:
            out[4] = min((abs(e.q[0]) * wf + r) / e.al, e.m2b[0])
        elif e.kind == STICK_KIND:
            bzz = w0 * r + abs(F)
            w2 = wf * wf
            out[4] = min(bzz + abs(e.q[0]) * w2, e.m2b[0])
            out[5] = min(bzz + e.q[1] * w2, e.m2b[1])
        else:
            out[4] = min(r + 1.0, e.m2b[0])
        out[6] = out[7] = 0.0
        return
    th = e.phi0 + wf * h - e.off
    for i in range(e.n):
        out[4 + i] = local_m2(out[i], out[2 + i], out[4 + i], e.m2b[i], e.m3b[i])
        out[6 + i] = envelope_at(e.env_mode[i], e.env_acos[i], th, wf)


@kernel
def clear(e: Evaluator, h: float, end) -> bool:
    """Every function provably positive on [h, H] (slow envelope minus the free
    oscillation's amplitude). ``end``: 4 floats, cos_range_prep of the window's end,
    filled on first use (end[3] = 1)."""
    if not e.clearable:
        return False
    wf = e.wf
    if end[3] == 0.0:
        end[0], end[1], end[2] = cos_range_prep(e.phi0 + wf * e.H - e.off)
        end[3] = 1.0
    lo, hi = cos_range_to(e.phi0 + wf * h - e.off, end[0], end[1], end[2])
    for i in range(e.n):
        K = e.K[i]
        if not (K * lo if K >= 0.0 else K * hi) - e.cc > e.ct:
            return False
    return True


@kernel
def start_bound(e: Evaluator, i: int, order: int) -> float:
    """Bound on |f_i⁽ᵒʳᵈᵉʳ⁺¹⁾| over the window: the smaller of the energy-growth bound
    (plus |q|ϖʲ) and the split bound |P − q|ϖʲ + w0^(j−1) E_h (j = order + bj)."""
    j = order + e.bj
    w0, wf, q = e.w0, e.wf, e.q[i]
    ba = derivative_bound(w0, e.F, wf, e.R0, j) + abs(q) * wf ** float(j)
    P = e.P
    if P == P:  # the split bound exists (not at exact resonance)
        bb = abs(P - q) * wf ** float(j) + w0 ** float(j - 1) * e.Eh
        ba = min(ba, bb)
    return ba / e.bdiv
