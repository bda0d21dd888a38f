"""The model's event functions, as evaluators for the certified search (unit-free).

docs/MODEL.md, "Impacts and separation" and the stick/slip rules; with damping
docs/damping.md and MODEL.md "Beyond the paper's idealisation". An evaluator (a record
of :data:`EVALUATOR_DTYPE`) holds one phase's event functions (one or two) in closed
form. One builder per kind of phase (:func:`slip_evaluator`, :func:`stick_evaluator`,
:func:`gap_evaluator`) writes it in one of two forms, chosen by the parameter set:

*Paper's model* (no damping; the phase table's ``damped`` False):

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

*General form* (damping, or restitution for the gap; ``gen`` True in the record). Every
phase is y'' + 2g y' + w0² y = F sin φ + G cos φ (:func:`flows.forced`; kernel time, the
contact normal force N ∝ A sin φ), and the same event functions read:

- gap: f = ξ (ξ'' + 2ζ_v ξ' + ξ = −A sin φ).
- slip / reverse slip: f = σ(ζ' − s'), f' = σ(ζ'' − ds sin φ), ds = σβκA.
- stick: with R = α(1 + 1/β) ζ'' (the spring and damper force the friction must hold,
  ζ'' of the stick flow), g_lo = bA sin φ − R and g_hi = bA sin φ + R (undamped this is
  ζ − (1 ∓ b) sin φ).

Fast mode (:func:`_split`, used when it does not cancel, |(a, b)| w0² ≤ 10 |(F, G)|):
y = a sin φ + b cos φ + y_h with y_h a free damped oscillation whose energy radius
E_h = sqrt(y_h'² + w0² y_h²) never grows (d/dh E_h² = −4g y_h'²), so |y_h⁽ᵏ⁾| ≤ c_k E_h for
every h ≥ 0. Each event function is a slow sinusoid K cos(φ − off) − cc plus a fast part
bounded by a multiple of E_h: global |f''|, |f'''| bounds, slow envelopes and the
whole-window clearance test, as undamped. Otherwise (near resonance with light damping,
tiny chattering flights): values from the closed form and bounds from the energy radius
R = sqrt(y'² + w0² y²) + |(F, G)|·W, which bounds the radius over a window of length W
because d/dh sqrt(y'² + w0² y²) ≤ |F sin φ + G cos φ| when g ≥ 0; then |y⁽ᵏ⁾| ≤ B_k with
B_0 = R/w0, B_1 = R, B_k = |(F, G)|ϖ^(k−2) + 2g B_(k−1) + w0² B_(k−2)
(:func:`derivative_bound_general`), sharpened at each point from the exact f''
(:func:`bounds.local_m2`), on windows of :data:`WINDOW` radians of the fastest rate (ϖ,
w0, 2g). Cost: a damped cycle ≈ 1.3× an undamped one (median of the 26 benchmark
designs, benchmarks/bench_damped.py).

The two forms are two implementations of the same events: at zero damping they agree
to round-off (``flows.phase_table(p, general=True)``, tests/test_dynamics_damped.py),
and the paper's model keeps its own closed form (tighter bounds, its numbers pinned by
benchmarks/snapshot.py). Values and bounds at a point: :mod:`values`.

``start`` holds each function's first four Taylor coefficients at the phase start and
``noise`` their round-off floors (a phase entered *on* its event surface, e.g. slip at
ζ' = s', starts from the first non-vanishing one); ``m2s`` bounds |f''| for the first step.
"""

from __future__ import annotations

import math

import numpy as np

from betvdesign.dynamics.bounds import envelope_prep
from betvdesign.dynamics.flows import SLIP, PhaseTable
from betvdesign.dynamics.jit import kernel

#: evaluator kinds
SLIP_KIND, STICK_KIND, GAP_KIND = 0, 1, 2

#: One phase's event functions f_i, i < n, on the window h ∈ [0, H] (see module doc).
#:
#: Start state (ζ, ζ', s, s') = (z, zd, s, sd) (gap: (ξ, ξ') in z, zd), forcing phase
#: φ0 (sin, cos) = (sp0, cp0); oscillator y'' + w0² y = F sin φ, φ = φ0 + ϖh (wf = ϖ).
#: Split (fast mode): y = P sin φ + ac cos w0h + as_ sin w0h, energy E_h = ``Eh``.
#: Per function i: ``q`` band coefficient, ``m2b``/``m3b`` global bounds on |f''|/|f'''|,
#: ``env_*`` slow envelope, ``K`` envelope amplitude, ``scale`` round-off scale,
#: ``start``/``noise`` Taylor coefficients 0..3 (entries 4i..4i+3), ``m2s`` first-step
#: |f''| bound. Clearance: min σ(K cos(φ − ``off``) − ``cc``) > ``ct`` on [h, H].
#: Start bounds: |f⁽ʲ⁾| from :func:`start_bound` with j = order + ``bj``, / ``bdiv``.
#: One record per search, reused (kernels: ``e = ws.ev[0]``; fields by name, ``e["w0"]``).
EVALUATOR_DTYPE = np.dtype(
    [
        ("kind", np.int64),
        ("n", np.int64),
        ("H", np.float64),
        ("W", np.float64),
        ("fast", np.bool_),
        ("clearable", np.bool_),
        ("phi0", np.float64),
        ("off", np.float64),
        ("wf", np.float64),
        ("w0", np.float64),
        ("F", np.float64),
        ("sp0", np.float64),
        ("cp0", np.float64),
        ("P", np.float64),
        ("ac", np.float64),
        ("as_", np.float64),
        ("pwf", np.float64),
        ("sdc", np.float64),
        ("ds", np.float64),
        ("sig", np.float64),
        ("al", np.float64),
        ("z", np.float64),
        ("zd", np.float64),
        ("s", np.float64),
        ("sd", np.float64),
        ("Eh", np.float64),
        ("R0", np.float64),
        ("bdiv", np.float64),
        ("bj", np.int64),
        ("cc", np.float64),
        ("ct", np.float64),
        ("w02", np.float64),
        ("wf2", np.float64),
        ("q", np.float64, (2,)),
        ("qw", np.float64, (2,)),
        ("m2b", np.float64, (2,)),
        ("m3b", np.float64, (2,)),
        ("m2s", np.float64, (2,)),
        ("env_mode", np.int64, (2,)),
        ("env_acos", np.float64, (2,)),
        ("K", np.float64, (2,)),
        ("scale", np.float64, (2,)),
        ("start", np.float64, (8,)),
        ("noise", np.float64, (8,)),
        ("gen", np.bool_),  # general (damped) form (module doc)
        ("g", np.float64),
        ("G", np.float64),
        ("Af", np.float64),
        ("bA", np.float64),
        ("ast", np.float64),
        ("offs", np.float64, (2,)),  # per-function phase of the slow part (general form)
    ]
)


@kernel(inline=True)
def init_record(e, kind: int, H: float, W: float) -> None:
    """Start the evaluator e of ``kind`` on the window [0, H], searched by windows W [-].

    Sets ``kind``, ``n`` (2 for stick, else 1), ``H``, ``W`` and ``off`` (the phase of
    the slow part's cosine: 0 for slip, π/2 for stick and the gap), and every other
    field to its neutral value, so that each kind then writes, by name, only what it
    has: no split (``fast``, ``clearable`` False, ``P`` NaN, ``Eh`` inf, ``ac``, ``as_``,
    ``pwf``, ``sdc``, ``cc``, ``ct``, ``w02``, ``wf2`` 0), no slider (``ds``, ``s``,
    ``sd`` 0), ``sig`` = ``al`` = ``bdiv`` = 1, ``bj`` = 1, per-function entries 0
    but ``m2b`` inf (no global bound), Taylor coefficients 0 and the undamped form
    (``gen`` False, ``g``, ``G``, ``Af``, ``bA``, ``ast``, ``offs`` 0: the general
    form's builders write it after this).
    """
    n = 2 if kind == STICK_KIND else 1
    e["kind"], e["n"], e["H"], e["W"] = kind, n, H, W
    e["off"] = 0.0 if kind == SLIP_KIND else 0.5 * math.pi
    e["fast"], e["clearable"] = False, False
    e["P"], e["Eh"] = math.nan, math.inf
    e["ac"], e["as_"], e["pwf"], e["sdc"] = 0.0, 0.0, 0.0, 0.0
    e["cc"], e["ct"], e["w02"], e["wf2"] = 0.0, 0.0, 0.0, 0.0
    e["ds"], e["s"], e["sd"] = 0.0, 0.0, 0.0
    e["sig"], e["al"], e["bdiv"], e["bj"] = 1.0, 1.0, 1.0, 1
    for i in range(2):
        e["q"][i], e["qw"][i], e["m3b"][i], e["m2s"][i] = 0.0, 0.0, 0.0, 0.0
        e["env_mode"][i], e["env_acos"][i], e["K"][i], e["scale"][i] = 0, 0.0, 0.0, 0.0
        e["m2b"][i] = math.inf if i < n else 0.0
        e["offs"][i] = 0.0
    for k in range(8):
        e["start"][k], e["noise"][k] = 0.0, 0.0
    e["gen"] = False
    e["g"], e["G"], e["Af"], e["bA"], e["ast"] = 0.0, 0.0, 0.0, 0.0, 0.0


@kernel(inline=True)
def put_forcing(e, wf: float, w0: float, F: float, sp0: float, cp0: float) -> None:
    """Set the oscillator and its forcing phase of an evaluator.

    The oscillator y'' + w0² y = F sin φ of the evaluator e, φ = φ0 + ϖh (ϖ = wf), and
    its forcing phase at the window start: (sin φ0, cos φ0) = (sp0, cp0) and φ0 [rad].
    """
    e["wf"], e["w0"], e["F"] = wf, w0, F
    e["sp0"], e["cp0"], e["phi0"] = sp0, cp0, math.atan2(sp0, cp0)


@kernel(inline=True)
def put_start(e, start, noise) -> None:
    """Set the Taylor coefficients and round-off floors at the window start.

    The Taylor coefficients 0..3 of each event function at the window start (entries
    4i..4i+3 of the 8-tuple ``start``) and their round-off floors (``noise``).
    """
    for k in range(8):
        e["start"][k] = start[k]
        e["noise"][k] = noise[k]


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
    e,
) -> None:
    """Evaluator of f = σ(ζ' − s') in slip (σ = +1) or reverse slip (σ = −1).

    The phase ends (ζ' = s') where f reaches 0. In the general form when the parameter
    set is damped (``c.damped``), else in the paper's model's closed form (module doc).

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
        Entered at a band edge, where f' is 0 exactly (undamped σ(q sin φ − ζ)/α,
        damped σ(R − σbA sin φ)/α).
    e : numpy.void
        The evaluator filled (a record of :data:`EVALUATOR_DTYPE`), by field name.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
    """
    if c.damped:
        _slip_general(c, phase, z, zd, s, sd, sp0, cp0, H, from_edge, e)
    else:
        _slip_closed(c, phase, z, zd, s, sd, sp0, cp0, H, from_edge, e)


@kernel
def stick_evaluator(
    c: PhaseTable, z: float, zd: float, sp0: float, cp0: float, H: float, on_edge: int, e
) -> None:
    """Evaluator of the stick-band distances g_lo, g_hi.

    Stick ends where one reaches 0: below the band slip, above it reverse slip. In the
    general form when the parameter set is damped (``c.damped``), else in the paper's
    model's closed form (module doc).

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
        The evaluator filled (a record of :data:`EVALUATOR_DTYPE`), by field name.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
    """
    if c.damped:
        _stick_general(c, z, zd, sp0, cp0, H, on_edge, e)
    else:
        _stick_closed(c, z, zd, sp0, cp0, H, on_edge, e)


@kernel
def gap_evaluator(
    wf: float,
    zv: float,
    A: float,
    xi: float,
    xid: float,
    sp0: float,
    cp0: float,
    H: float,
    general: bool,
    e,
) -> None:
    """Evaluator of the gap ξ in free flight.

    Evaluator of the gap ξ in free flight (ξ'' + 2ζ_v ξ' + ξ = −A sin φ): the head
    hits where ξ = 0.

    Parameters
    ----------
    wf : float
        ϖ [-].
    zv : float
        Normal damping ratio ζ_v [-] (0 in the closed form).
    A : float
        Normal-force amplitude [-] (1 in the closed form).
    xi, xid : float
        ξ, ξ' at the window start [-].
    sp0, cp0 : float
        sin φ0, cos φ0 [-] of the forcing phase at the start.
    H : float
        Window length [-].
    general : bool
        The general form (with damping, and undamped with restitution: its round-off
        scale follows the window, so the tiny flights of a chattering sequence are
        located to their own precision); else the closed form ξ'' + ξ = −sin φ.
    e : numpy.void
        The evaluator filled (a record of :data:`EVALUATOR_DTYPE`), by field name.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
    Budd & Dux, Phil. Trans. R. Soc. A 347 (1994), doi:10.1098/rsta.1994.0044.
    """
    if general:
        _gap_general(wf, zv, A, xi, xid, sp0, cp0, H, e)
    else:
        _gap_closed(wf, xi, xid, sp0, cp0, H, e)


# --- the paper's model: closed form ------------------------------------------------------


@kernel
def _slip_closed(
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
    e,
) -> None:
    """Evaluator of f = σ(ζ' − s') in slip (σ = +1) or reverse slip (σ = −1)."""
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
    init_record(e, SLIP_KIND, H, W)
    put_forcing(e, wf, w0, F, sp0, cp0)
    put_start(e, start, noise)
    e["fast"], e["clearable"] = fast, fast
    e["P"], e["ac"], e["as_"], e["pwf"], e["Eh"], e["R0"] = P, ac, as_, pwf, Eh, R0
    e["z"], e["zd"], e["s"], e["sd"], e["sdc"] = z, zd, s, sd, sdc
    e["ds"], e["sig"], e["al"], e["bdiv"], e["bj"] = ds, sig, al, al, 0
    e["cc"], e["ct"] = cc, ct
    e["q"][0], e["qw"][0], e["K"][0] = q, q * wf, K
    e["m2b"][0], e["m3b"][0], e["m2s"][0] = m2b, m3b, m2s
    e["env_mode"][0], e["env_acos"][0] = mode, acs
    e["scale"][0] = r + asd + azd + 1e-300


@kernel
def _stick_closed(
    c: PhaseTable, z: float, zd: float, sp0: float, cp0: float, H: float, on_edge: int, e
) -> None:
    """Evaluator of the stick-band distances g_lo, g_hi."""
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
    init_record(e, STICK_KIND, H, W)
    put_forcing(e, wf, w0, F, sp0, cp0)
    put_start(e, start, noise)
    e["fast"], e["clearable"] = fast, fast
    e["P"], e["ac"], e["as_"], e["pwf"], e["Eh"], e["R0"] = P, ac, as_, pwf, Eh, R0
    e["z"], e["zd"] = z, zd
    e["ct"], e["w02"], e["wf2"] = ct, w02, wf2
    e["q"][0], e["q"][1], e["qw"][0], e["qw"][1] = ql, qh, ql * wf, qh * wf
    e["m2b"][0], e["m2b"][1], e["m3b"][0], e["m3b"][1] = m2b0, m2b1, m3b0, m3b1
    e["m2s"][0], e["m2s"][1] = m2s0, m2s1
    e["env_mode"][0], e["env_mode"][1] = mode0, mode1
    e["env_acos"][0], e["env_acos"][1] = acs0, acs1
    e["K"][0], e["K"][1] = st.K[0], st.K[1]
    e["scale"][0], e["scale"][1] = r / w0 + abs(ql), r / w0 + abs(qh)


@kernel
def _gap_closed(wf: float, xi: float, xid: float, sp0: float, cp0: float, H: float, e) -> None:
    """Evaluator of the gap ξ in free flight (ξ'' + ξ = −sin φ): the head hits where ξ = 0."""
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
    init_record(e, GAP_KIND, H, W)
    put_forcing(e, wf, w0, F, sp0, cp0)
    put_start(e, start, noise)
    e["clearable"] = clearable
    e["P"], e["Eh"], e["R0"], e["ct"] = P, Eh, R0, Eh
    e["z"], e["zd"] = xi, xid
    e["m2b"][0], e["m2s"][0] = m2b, min(R0 + 1.0, m2b)
    e["K"][0], e["scale"][0] = P, sc


# --- the general form (damping, restitution) ---------------------------------------------


#: search window [rad of the fastest rate ϖ, w0, 2g]: long enough for few steps, short
#: enough for the energy radius R = E + |(F, G)|·W to stay tight (root evaluations per
#: cycle of the published fit with Q = 30: 49, 44, 58, 70 for 0.25, 0.5, 2, 4)
WINDOW = 0.5


@kernel
def derivative_bound_general(w0: float, g: float, Af: float, wf: float, R: float, j: int) -> float:
    """B_j ≥ |y⁽ʲ⁾| on a window of energy radius R (module doc) [-]."""
    b0, b1 = R / w0, R
    if j == 0:
        return b0
    for k in range(2, j + 1):
        bk = Af * wf ** float(k - 2) + 2.0 * g * b1 + w0 * w0 * b0
        b0, b1 = b1, bk
    return b1


@kernel
def taylor_general(w0, g, wf, F, G, y, yd, sp, cp) -> tuple:
    """The derivatives of orders 2 to 5 at a point and their round-off scales.

    The derivatives of orders 2 to 5 at a point from the equation of motion, then
    the round-off scale of each (sums of the magnitudes of their terms), in one pass.
    """
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
    """Bounds c_k on the derivatives of a free damped oscillation.

    c_k with |y_h⁽ᵏ⁾| ≤ c_k E_h for a free damped oscillation of energy radius E_h:
    c_0 = 1/w0, c_1 = 1, c_k = 2g c_(k−1) + w0² c_(k−2).
    """
    c0, c1 = 1.0 / w0, 1.0
    if k == 0:
        return c0
    for _ in range(2, k + 1):
        c0, c1 = c1, 2.0 * g * c1 + w0 * w0 * c0
    return c1


@kernel
def _split(e, w0, g, wf, F, G, y, yd, sp0, cp0, kind: int, sig: float, ds: float, sd: float):
    """The fast mode of the general form.

    The fast mode of the general form (the damped analogue of the undamped split):
    y = a sin φ + b cos φ + y_h with y_h a free damped oscillation whose energy radius
    E_h = sqrt(y_h'² + w0² y_h²) never grows (d/dh E_h² = −4g y_h'²). Each event function
    is then K_i cos(φ − off_i) − cc plus a fast part bounded by ct (a multiple of E_h):
    global |f''|, |f'''| bounds (the whole window is one step range), slow envelopes and
    the whole-window clearance test. Used when the split does not cancel:
    |(a, b)| w0² ≤ 10 |(F, G)| (as the undamped |1 − aϖ²| ≥ 0.1).
    """
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
def _slip_general(
    c: PhaseTable, phase: int, z, zd, s, sd, sp0, cp0, H: float, from_edge: bool, e
) -> None:
    """Evaluator of f = σ(ζ' − s') with damping in slip (σ = +1) or reverse slip (σ = −1)."""
    ph = c.slip if phase == SLIP else c.reverse
    sig, w0, F, G, g, ds = ph.sig, ph.w0, ph.F, ph.G, ph.g, ph.ds
    wf = c.varpi
    Af = math.hypot(F, G)
    W = _window(H, w0, wf, g)
    E0 = math.sqrt(zd * zd + w0 * w0 * z * z)
    R0 = E0 + Af * W
    y2, y3, y4, _, n2, n3, n4, _ = taylor_general(w0, g, wf, F, G, z, zd, sp0, cp0)
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
    m2 = derivative_bound_general(w0, g, Af, wf, R0, 3) + ads * wf
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
def _stick_general(c: PhaseTable, z, zd, sp0, cp0, H: float, on_edge: int, e) -> None:
    """Evaluator of the stick-band distances g_lo, g_hi with damping."""
    st = c.stick
    w0, F, G, g = st.w0, st.F, st.G, st.g
    wf, bA, ast = c.varpi, c.bA, c.a_stick
    Af = math.hypot(F, G)
    W = _window(H, w0, wf, g)
    E0 = math.sqrt(zd * zd + w0 * w0 * z * z)
    R0 = E0 + Af * W
    sj = (sp0, wf * cp0, -wf * wf * sp0, -(wf**3) * cp0)
    y2, y3, y4, y5, n2, n3, n4, n5 = taylor_general(w0, g, wf, F, G, z, zd, sp0, cp0)
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
    m2 = bA * wf * wf + ast * derivative_bound_general(w0, g, Af, wf, R0, 4)
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
def _gap_general(wf, zv, A, xi, xid, sp0, cp0, H: float, e) -> None:
    """Evaluator of the gap ξ in damped free flight (ξ'' + 2ζ_v ξ' + ξ = −A sin φ)."""
    w0, g, F = 1.0, zv, -A
    W = _window(H, w0, wf, g)
    E0 = math.sqrt(xid * xid + xi * xi)
    R0 = E0 + A * W
    sc = abs(xi) + E0 + A * H + 1e-300  # |ξ| reachable on the window: its round-off scale
    y2, y3, _, _, _, _, _, _ = taylor_general(w0, g, wf, F, 0.0, xi, xid, sp0, cp0)
    start = (xi, xid, y2, y3, 0.0, 0.0, 0.0, 0.0)
    noise = (sc, sc, sc, sc, 0.0, 0.0, 0.0, 0.0)
    m2 = derivative_bound_general(w0, g, A, wf, R0, 2)
    init_record(e, GAP_KIND, H, W)
    put_forcing(e, wf, w0, F, sp0, cp0)
    put_start(e, start, noise)
    e["R0"], e["z"], e["zd"] = R0, xi, xid
    e["m2s"][0], e["scale"][0] = m2, sc
    _general(e, g, 0.0, A, 0.0, 0.0)
    _split(e, w0, g, wf, F, 0.0, xi, xid, sp0, cp0, GAP_KIND, 1.0, 0.0, 0.0)
