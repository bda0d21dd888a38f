"""Compiled (numba) kernel of the contact loop: whole cycles of the exact solver.

The same algorithm as :class:`solver._Cycle` driving :func:`events.first_root` on
:class:`events.SlipEvent` / :class:`events.StickEvent` in their fast mode (docs/MODEL.md,
"Dimensionless model"; the event search and its certificates are described in
:mod:`events`), with the same floating-point operations in the same order, written
over flat float64 arrays so that numba can compile it. The scalar pieces (closed-form
flows, safe steps, curvature bounds, envelopes, the phase rule) are *not* copied:
they are the functions of :mod:`flows` and :mod:`events` marked ``@jitable``.

Used whenever nothing but the states is asked for (no event log, no dense output):
studies, periodic shooting, benchmarks; with an event log or dense output the
pure-Python path runs. Both modes of the events are compiled: the split form away from
tangential resonance and the uniform form with energy-growth bounds near it
(|1 − aϖ²| < 0.1, exact resonance included). Both paths are tested against each other
(tests/test_dynamics_kernels.py); with ``NUMBA_DISABLE_JIT=1`` this module runs as plain
Python. ``BETV_KERNELS=0`` switches the kernel off (the pure-Python path everywhere).

Compiled code is cached on disk (``cache=True``) in a directory named after a hash of
this module, :mod:`flows` and :mod:`events`, so that an edit of a shared helper can
never leave a stale compiled kernel in use.
"""

from __future__ import annotations

import hashlib
import math
import os
from pathlib import Path

import numba
import numpy as np
from numba.extending import register_jitable

from betvdesign.dynamics import _jit, events, flows
from betvdesign.dynamics.events import (
    EPS,
    MAX_STEPS,
    NOISE,
    SlipEvent,
    StickEvent,
    cos_range_prep,
    cos_range_to,
    decide_phase_core,
    envelope_at,
    envelope_prep,
    local_m2,
    safe_step,
)
from betvdesign.dynamics.flows import FREE, REVERSE, SLIP, STICK, PhaseConstants, oscillator, slider
from betvdesign.dynamics.solver import MAX_SWITCHES, MAX_ZERO_LENGTH

for _fn in _jit.JITABLE:
    register_jitable(_fn)

#: Status codes returned by :func:`run_cycles`.
OK, SEARCH_FAILED, CHATTER, NON_FINITE = 0, 1, 2, 3

# -- layout of the per-parameter-set constants (kc) ---------------------------------
KC_WF, KC_AL, KC_BETA, KC_B, KC_A, KC_WFREE, KC_FFREE = range(7)
KC_SLIP, KC_REV, KC_STICK = 7, 16, 25  # slip: sig q w0 F ds P apq K fast; stick: 13
KC_SIZE = 38

# -- layout of one event evaluator (e) ------------------------------------------------
E_KIND, E_N, E_H, E_PHI0, E_OFF = 0, 1, 2, 3, 4
E_WF, E_W0, E_SP0, E_CP0, E_P, E_AC, E_AS, E_PWF, E_EH, E_F = range(5, 15)
E_SCALE, E_SD, E_D = 15, 17, 25  # 2; 2×4 noise floors; 2×4 start Taylor coefficients
E_M2B, E_M3B, E_ENVM, E_ENVA, E_CK = 33, 35, 37, 39, 41  # 2 each
E_CC, E_CT, E_END, E_ENDSET = 43, 44, 45, 48  # E_END: 3
E_Q, E_QW = 49, 51  # 2 each
E_SDC, E_DS, E_SIG, E_AL, E_W02, E_WF2, E_R0, E_BDIV, E_BJ = range(53, 62)
E_FAST, E_W, E_Z, E_ZD, E_S, E_SDV, E_M2S = range(62, 69)  # E_M2S: 2
E_SIZE = 72


def _cache_dir() -> str:
    """Per-source cache directory of the compiled kernels [path]."""
    h = hashlib.sha256()
    for mod_file in (__file__, flows.__file__, events.__file__, _jit.__file__):
        h.update(Path(mod_file).read_bytes())
    h.update(numba.__version__.encode())
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "betvdesign", "numba", h.hexdigest()[:16])


_user_cache = numba.config.CACHE_DIR
if not _user_cache:
    numba.config.CACHE_DIR = _cache_dir()  # read when a cached function is decorated
try:
    _jit_cached = numba.njit(cache=True, nogil=True)

    @register_jitable
    def _slip_init(kc, phase, z, zd, s, sd, sp0, cp0, H, from_edge, e):
        """events.SlipEvent.__init__ + start() in fast mode, into e."""
        b0 = KC_SLIP if phase == SLIP else KC_REV
        sig, q, w0, F = kc[b0], kc[b0 + 1], kc[b0 + 2], kc[b0 + 3]
        ds, P, apq, K = kc[b0 + 4], kc[b0 + 5], kc[b0 + 6], kc[b0 + 7]
        fast = kc[b0 + 8] != 0.0
        wf, al = kc[KC_WF], kc[KC_AL]
        e[E_KIND], e[E_N], e[E_H], e[E_FAST] = 0.0, 1.0, H, 1.0 if fast else 0.0
        e[E_PHI0], e[E_OFF] = math.atan2(sp0, cp0), 0.0
        e[E_WF], e[E_W0], e[E_SP0], e[E_CP0], e[E_P], e[E_F] = wf, w0, sp0, cp0, P, F
        e[E_Z], e[E_ZD], e[E_S], e[E_SDV] = z, zd, s, sd
        e[E_Q], e[E_QW] = q, q * wf
        e[E_DS], e[E_SIG], e[E_AL] = ds, sig, al
        yh = yhd = 0.0
        if P != P:  # exact resonance: no split (P is None in events)
            Eh = m2b = math.inf
            W = min(H, 1.0 / max(w0, wf))
        else:
            yh, yhd = z - P * sp0, zd - P * wf * cp0
            Eh = math.sqrt(yhd * yhd + w0 * w0 * yh * yh)
            m2b = (apq + Eh) / al
            W = H if fast else min(H, 1.0 / max(w0, wf))  # events.window
        e[E_EH], e[E_M2B], e[E_W] = Eh, m2b, W
        if fast:
            as_ = yhd / w0
            sdc = sd + ds * cp0 / wf
            e[E_AC], e[E_AS], e[E_PWF] = yh, as_, P * wf
            e[E_M3B] = (apq * wf + w0 * Eh) / al
            ssdc = sig * sdc
            mode, acs = envelope_prep(K, -ssdc, Eh)
            e[E_ENVM], e[E_ENVA] = mode, acs
            e[E_CK], e[E_CC], e[E_CT], e[E_ENDSET] = K, ssdc, Eh, 0.0
            e[E_SDC] = sdc
        azd, asd = abs(zd), abs(sd)
        r = math.sqrt(zd * zd + w0 * w0 * z * z) + abs(F) * H  # energy_radius
        e[E_SCALE] = r + asd + azd + 1e-300
        aq = abs(q)
        e[E_SD] = azd + asd
        e[E_SD + 1] = (aq * abs(sp0) + abs(z)) / al
        e[E_SD + 2] = (aq * wf * abs(cp0) + azd) / al
        e[E_SD + 3] = (aq * wf * wf * abs(sp0) + abs(F * sp0 - w0 * w0 * z)) / al
        zdd = F * sp0 - w0 * w0 * z
        e[E_D] = sig * (zd - sd)
        e[E_D + 1] = 0.0 if from_edge else sig * (q * sp0 - z) / al
        e[E_D + 2] = sig * (q * wf * cp0 - zd) / al
        e[E_D + 3] = sig * (-q * wf * wf * sp0 - zdd) / al
        R0 = math.sqrt(zd * zd + w0 * w0 * z * z) + abs(F) * W  # energy_radius over W
        e[E_R0], e[E_BDIV], e[E_BJ] = R0, al, 0.0
        e[E_M2S] = m2b if fast else min((abs(q) * wf + R0) / al, m2b)

    @register_jitable
    def _stick_init(kc, z, zd, sp0, cp0, H, on_edge, e):
        """events.StickEvent.__init__ + start() in fast mode, into e."""
        b0 = KC_STICK
        w0, F, ql, qh, P = kc[b0], kc[b0 + 1], kc[b0 + 2], kc[b0 + 3], kc[b0 + 4]
        wf = kc[KC_WF]
        w3 = kc[b0 + 11]
        fast = kc[b0 + 12] != 0.0
        e[E_KIND], e[E_N], e[E_H], e[E_FAST] = 1.0, 2.0, H, 1.0 if fast else 0.0
        e[E_PHI0], e[E_OFF] = math.atan2(sp0, cp0), 0.5 * math.pi
        e[E_WF], e[E_W0], e[E_SP0], e[E_CP0], e[E_P], e[E_F] = wf, w0, sp0, cp0, P, F
        e[E_Z], e[E_ZD] = z, zd
        e[E_Q], e[E_Q + 1], e[E_QW], e[E_QW + 1] = ql, qh, ql * wf, qh * wf
        yh = yhd = 0.0
        if P != P:  # exact resonance: no split (P is None in events)
            Eh = math.inf
            W = min(H, 1.0 / max(w0, wf))
            m2b0 = m2b1 = math.inf
        else:
            yh, yhd = z - P * sp0, zd - P * wf * cp0
            Eh = math.sqrt(yhd * yhd + w0 * w0 * yh * yh)
            W = H if fast else min(H, 1.0 / max(w0, wf))  # events.window
            wE = w0 * Eh
            m2b0, m2b1 = kc[b0 + 5] + wE, kc[b0 + 6] + wE
        e[E_EH], e[E_W], e[E_M2B], e[E_M2B + 1] = Eh, W, m2b0, m2b1
        if fast:
            e[E_AC], e[E_AS], e[E_PWF] = yh, yhd / w0, P * wf
            wwE = w0 * w0 * Eh
            e[E_M3B], e[E_M3B + 1] = kc[b0 + 7] + wwE, kc[b0 + 8] + wwE
            eh = Eh / w0
            for i in range(2):
                K = kc[b0 + 9 + i]
                mode, acs = envelope_prep(K, 0.0, eh)
                e[E_ENVM + i], e[E_ENVA + i], e[E_CK + i] = mode, acs, K
            e[E_CC], e[E_CT], e[E_ENDSET] = 0.0, eh, 0.0
            e[E_W02], e[E_WF2] = w0 * w0, wf * wf
        r = math.sqrt(zd * zd + w0 * w0 * z * z) + abs(F) * H  # energy_radius
        e[E_SCALE], e[E_SCALE + 1] = r / w0 + abs(ql), r / w0 + abs(qh)
        za0, za1 = abs(z), abs(zd)
        za2, za3 = abs(F * sp0 - w0 * w0 * z), abs(F * wf * cp0 - w0 * w0 * zd)
        n0, n1, n2, n3 = sp0, wf * cp0, wf * wf * sp0, w3 * cp0
        z2, z3 = F * sp0 - w0 * w0 * z, F * wf * cp0 - w0 * w0 * zd
        s1, s2, s3 = wf * cp0, -wf * wf * sp0, -w3 * cp0
        for i in range(2):
            q = ql if i == 0 else qh
            o = E_SD + 4 * i
            e[o] = za0 + abs(q * n0)
            e[o + 1] = za1 + abs(q * n1)
            e[o + 2] = za2 + abs(q * n2)
            e[o + 3] = za3 + abs(q * n3)
        e[E_D], e[E_D + 1] = z - ql * sp0, zd - ql * s1
        e[E_D + 2], e[E_D + 3] = z2 - ql * s2, z3 - ql * s3
        e[E_D + 4], e[E_D + 5] = -(z - qh * sp0), -(zd - qh * s1)
        e[E_D + 6], e[E_D + 7] = -(z2 - qh * s2), -(z3 - qh * s3)
        if on_edge == 0:
            e[E_D] = 0.0
        elif on_edge == 1:
            e[E_D + 4] = 0.0
        R0 = math.sqrt(zd * zd + w0 * w0 * z * z) + abs(F) * W  # energy_radius over W
        e[E_R0], e[E_BDIV], e[E_BJ] = R0, 1.0, 1.0
        for i in range(2):
            m2b = e[E_M2B + i]
            qi = ql if i == 0 else qh
            e[E_M2S + i] = m2b if fast else min(w0 * R0 + abs(F) + abs(qi) * wf * wf, m2b)

    @register_jitable
    def _eval_slow(e, h, out):
        """The events' eval(h, False) near resonance (uniform closed form, no f'': 0)."""
        wf, w0, sp0, cp0 = e[E_WF], e[E_W0], e[E_SP0], e[E_CP0]
        y, yd, sp, cp = oscillator(w0, wf, e[E_F], e[E_Z], e[E_ZD], sp0, cp0, h)
        out[4] = out[5] = 0.0
        if e[E_KIND] == 0.0:
            _, sdn = slider(e[E_DS], wf, e[E_S], e[E_SDV], sp0, cp0, sp, cp, h)
            sig = e[E_SIG]
            out[0] = sig * (yd - sdn)
            out[2] = sig * (e[E_Q] * sp - y) / e[E_AL]
            return y, yd
        ql, qh = e[E_Q], e[E_Q + 1]
        out[0], out[1] = y - ql * sp, qh * sp - y
        out[2], out[3] = yd - e[E_QW] * cp, e[E_QW + 1] * cp - yd
        return y, yd

    @register_jitable
    def _eval(e, h, out):
        """(f_i, f_i', f_i'') at h into out[0:2], out[2:4], out[4:6]: the events'
        eval(h, False); returns (y, y') of the oscillator."""
        if e[E_FAST] == 0.0:
            return _eval_slow(e, h, out)
        wf, w0, sp0, cp0 = e[E_WF], e[E_W0], e[E_SP0], e[E_CP0]
        P, ac, as_ = e[E_P], e[E_AC], e[E_AS]
        cw, sw = math.cos(wf * h), math.sin(wf * h)
        sp, cp = sp0 * cw + cp0 * sw, cp0 * cw - sp0 * sw
        c0, s0 = math.cos(w0 * h), math.sin(w0 * h)
        y = P * sp + ac * c0 + as_ * s0
        yd = e[E_PWF] * cp + w0 * (as_ * c0 - ac * s0)
        if e[E_KIND] == 0.0:
            sig, al = e[E_SIG], e[E_AL]
            sdn = e[E_SDC] - e[E_DS] * cp / wf
            out[0] = sig * (yd - sdn)
            out[2] = sig * (e[E_Q] * sp - y) / al
            out[4] = sig * (e[E_QW] * cp - yd) / al
            return y, yd
        ql, qh = e[E_Q], e[E_Q + 1]
        out[0], out[1] = y - ql * sp, qh * sp - y
        out[2], out[3] = yd - e[E_QW] * cp, e[E_QW + 1] * cp - yd
        ydd = e[E_F] * sp - e[E_W02] * y
        w2sp = e[E_WF2] * sp
        out[4], out[5] = ydd + ql * w2sp, -ydd - qh * w2sp
        return y, yd

    @register_jitable
    def _probe(e, h, out):
        """One search step's look at h: f, f', the local |f''| bound and the envelope's
        free length of each function into out[0:2], [2:4], [4:6], [6:8] (probe())."""
        y, yd = _eval(e, h, out)
        wf = e[E_WF]
        if e[E_FAST] == 0.0:  # energy-growth bounds (events' probe near resonance)
            w0, F = e[E_W0], e[E_F]
            r = math.sqrt(yd * yd + w0 * w0 * y * y) + abs(F) * e[E_W]  # energy_radius
            if e[E_KIND] == 0.0:
                out[4] = min((abs(e[E_Q]) * wf + r) / e[E_AL], e[E_M2B])
            else:
                bzz = w0 * r + abs(F)
                w2 = wf * wf
                out[4] = min(bzz + abs(e[E_Q]) * w2, e[E_M2B])
                out[5] = min(bzz + e[E_Q + 1] * w2, e[E_M2B + 1])
            out[6] = out[7] = 0.0
            return
        th = e[E_PHI0] + wf * h - e[E_OFF]
        for i in range(int(e[E_N])):
            out[4 + i] = local_m2(out[i], out[2 + i], out[4 + i], e[E_M2B + i], e[E_M3B + i])
            out[6 + i] = envelope_at((int(e[E_ENVM + i]), e[E_ENVA + i]), th, wf)

    @register_jitable
    def _clear(e, h):
        """Every function provably positive on [h, H] (the events' clear())."""
        if e[E_FAST] == 0.0:
            return False
        wf = e[E_WF]
        if e[E_ENDSET] == 0.0:
            c, f1, f2 = cos_range_prep(e[E_PHI0] + wf * e[E_H] - e[E_OFF])
            e[E_END], e[E_END + 1], e[E_END + 2], e[E_ENDSET] = c, f1, f2, 1.0
        end = (e[E_END], int(e[E_END + 1]), int(e[E_END + 2]))
        lo, hi = cos_range_to(e[E_PHI0] + wf * h - e[E_OFF], end)
        for i in range(int(e[E_N])):
            K = e[E_CK + i]
            if not (K * lo if K >= 0.0 else K * hi) - e[E_CC] > e[E_CT]:
                return False
        return True

    @register_jitable
    def _start_bound(e, i, order):
        """events' bounds(i, order + 1)[order + 1]: band_bounds at j = order (+1 in stick)."""
        j = order + int(e[E_BJ])
        w0, F, wf, q = e[E_W0], e[E_F], e[E_WF], e[E_Q + i]
        R = e[E_R0]
        b0, b1 = R / w0, R
        bj = b0 if j == 0 else b1
        for k in range(2, j + 1):  # flows.derivative_bounds
            bk = w0 * w0 * b0 + abs(F) * wf ** float(k - 2)
            b0, b1 = b1, bk
            bj = bk
        ba = bj + abs(q) * wf ** float(j)
        P = e[E_P]
        if P == P:  # the split bound exists (not at exact resonance)
            bb = abs(P - q) * wf ** float(j) + w0 ** float(j - 1) * e[E_EH]
            ba = min(ba, bb)
        return ba / e[E_BDIV]

    @register_jitable
    def _refine(e, i, lo, hi, flo, fplo, fhi, has_hi, tmp):
        """events._refine in fast mode: (root, evaluations)."""
        x, f, fp, fpp = lo, flo, fplo, 0.0
        f_lo, f_hi = flo, fhi
        secant = True
        tol = 4.0 * EPS * max(1.0, abs(hi))
        floor = 4.0 * EPS * e[E_SCALE + i]
        n = 0
        for _ in range(200):
            if fp != 0.0:
                dn = f / fp
                den = 1.0 - 0.5 * dn * fpp / fp
                xn = x - (dn / den if den > 0.5 else dn)
            else:
                xn = 0.5 * (lo + hi)
            if not lo < xn < hi:
                xn = 0.5 * (lo + hi)
                if secant and has_hi:
                    xs = lo + (hi - lo) * (f_lo / (f_lo - f_hi))
                    if lo < xs < hi:
                        xn = xs
                secant = not secant
            if abs(xn - x) <= tol:
                return xn, n
            x = xn
            n += 1
            _eval(e, x, tmp)
            f, fp, fpp = tmp[i], tmp[2 + i], tmp[4 + i]
            if abs(f) <= floor:
                return x, n
            if f > 0.0:
                lo, f_lo = x, f
            else:
                hi, f_hi, has_hi = x, f, True
            if hi - lo <= tol:
                return hi, n
        return x, n

    @register_jitable
    def _first_root(e, H, out, tmp, steps, act):
        """events.first_root in fast mode: (code, h, index, evaluations); code 0 none,
        1 root at (h, index), −1 the search did not terminate."""
        n = int(e[E_N])
        W = e[E_W]
        x = H if H < W else W
        for i in range(n):
            o = E_D + 4 * i
            order = -1
            for j in range(4):
                if abs(e[o + j]) > NOISE * e[E_SD + 4 * i + j]:
                    order = j
                    break
            if order < 0 or e[o + order] < 0.0:
                return 1, 0.0, i, 0
            if order == 0:
                xi = safe_step(e[o], e[o + 1], e[E_M2S + i])
            else:
                xi = 0.5 * (order + 1) * e[o + order] / _start_bound(e, i, order)
            if xi < x:
                x = xi
        if x >= H or _clear(e, 0.0):
            return 0, 0.0, -1, 0
        x0 = x
        cand_h, cand_i = 0.0, -1
        evals = 0
        for i in range(n):
            act[i] = True
        for _ in range(MAX_STEPS):
            evals += 1
            _probe(e, x0, out)
            best_end = math.inf
            best_i = -1
            for i in range(n):
                if not act[i]:
                    continue
                f, fp = out[i], out[2 + i]
                if f <= 0.0 or (f <= NOISE * e[E_SCALE + i] and fp <= 0.0):
                    return 1, x0, i, evals
                m2 = out[4 + i]
                if m2 <= 0.0:
                    xi = math.inf if fp >= 0.0 else f / -fp
                else:
                    root = math.sqrt(fp * fp + 2.0 * m2 * f)
                    xi = (fp + root) / m2 if fp > 0.0 else 2.0 * f / (root - fp)
                li = out[6 + i]
                steps[i] = xi if xi > li else li
                if fp < 0.0:
                    d = f / -fp
                    if 4.0 * m2 * d <= -fp and 2.0 * d <= W and x0 + 2.0 * d < best_end:
                        best_end, best_i = x0 + 2.0 * d, i
            if best_i >= 0:
                i = best_i
                act[i] = False
                clipped = best_end > H
                hi = H if clipped else best_end
                f_hi = -1.0
                if clipped:
                    evals += 1
                    _eval(e, hi, tmp)
                    f_hi = tmp[i]
                if f_hi <= 0.0:
                    r, k = _refine(e, i, x0, hi, out[i], out[2 + i], f_hi, clipped, tmp)
                    evals += k
                    cand_h, cand_i, H = r, i, r
            step = H - x0
            if W < step:
                step = W
            n_act = 0
            for i in range(n):
                if act[i]:
                    n_act += 1
                    if steps[i] < step:
                        step = steps[i]
            if n_act == 0 or x0 + step >= H:
                return (0 if cand_i < 0 else 1), cand_h, cand_i, evals
            x0 += step
            if cand_i < 0 and _clear(e, x0):
                return 0, 0.0, -1, evals
        return -1, H, -1, evals

    @register_jitable
    def _free(kc, z, zd, s, sd, cp0, h):
        """solver._Cycle._free: free flight over h from a forcing phase 0 or π (cp0 = ±1)."""
        w0 = kc[KC_WFREE]
        y0, v0, _, _ = oscillator(w0, kc[KC_WF], kc[KC_FFREE], 0.0, 0.0, 0.0, cp0, h)
        c0, s0 = math.cos(w0 * h), math.sin(w0 * h)
        return z * c0 + zd / w0 * s0 + y0, -z * w0 * s0 + zd * c0 + v0, s + sd * h, sd

    @register_jitable
    def _flow(kc, phase, z, zd, s, sd, sp0, cp0, h):
        """flows.flow: (ζ, ζ', s, s') after h in ``phase``."""
        wf = kc[KC_WF]
        if phase == STICK:
            zn, zdn, _, _ = oscillator(kc[KC_STICK], wf, kc[KC_STICK + 1], z, zd, sp0, cp0, h)
            return zn, zdn, s + (zn - z), zdn
        b0 = KC_SLIP if phase == SLIP else KC_REV
        zn, zdn, sp, cp = oscillator(kc[b0 + 2], wf, kc[b0 + 3], z, zd, sp0, cp0, h)
        sn, sdn = slider(kc[b0 + 4], wf, s, sd, sp0, cp0, sp, cp, h)
        return zn, zdn, sn, sdn

    @register_jitable
    def _contact(kc, tc, z, zd, s, sd, e, out, tmp, steps, act):
        """solver._Cycle.run from the contact-opening hit at local time tc to the free
        flight's end: (code, ζ, ζ', s, s', events, evaluations, a, b) with code 0, or
        SEARCH_FAILED (a: window) or CHATTER (a: local time, b: switches)."""
        wf, beta = kc[KC_WF], kc[KC_BETA]
        te = math.pi / wf
        if tc > 0.0:
            z, zd, s, sd = _free(kc, z, zd, s, sd, 1.0, tc)
            sp, cp = math.sin(wf * tc), math.cos(wf * tc)
        else:
            sp, cp = 0.0, 1.0
        t = tc
        A, b = kc[KC_A], kc[KC_B]
        phase = decide_phase_core(A, wf, b, beta, z, zd, sd, sp, cp, -1)
        if phase == STICK:
            zd = sd = (zd + sd / beta) / (1.0 + 1.0 / beta)
        nev, evals = 1, 0
        zero_len, n_switch, on_edge, from_edge = 0, 0, -1, False
        while True:
            H = te - t
            if phase == STICK:
                _stick_init(kc, z, zd, sp, cp, H, on_edge, e)
                on_edge = -1
            else:
                _slip_init(kc, phase, z, zd, s, sd, sp, cp, H, from_edge, e)
            from_edge = False
            code, hr, idx, k = _first_root(e, H, out, tmp, steps, act)
            evals += k
            if code < 0:
                return SEARCH_FAILED, z, zd, s, sd, nev, evals, hr, 0
            h = H if code == 0 else hr
            z, zd, s, sd = _flow(kc, phase, z, zd, s, sd, sp, cp, h)
            if code == 0:
                break
            t += h
            sp, cp = math.sin(wf * t), math.cos(wf * t)
            on = 1 + idx if phase == STICK else 0
            new = decide_phase_core(A, wf, b, beta, z, zd, sd, sp, cp, on)
            if phase != STICK:
                zd = sd = (zd + sd / beta) / (1.0 + 1.0 / beta)
            elif new == STICK:
                on_edge = idx
            else:
                from_edge = True
            nev += 1
            zero_len = zero_len + 1 if h <= 64.0 * EPS * max(1.0, t) else 0
            n_switch += 1
            if zero_len > MAX_ZERO_LENGTH or n_switch > MAX_SWITCHES:
                return CHATTER, z, zd, s, sd, nev, evals, t, n_switch
            phase = new
        z, zd, s, sd = _free(kc, z, zd, s, sd, -1.0, te)
        return OK, z, zd, s, sd, nev + 1, evals, 0.0, 0

    @_jit_cached
    def run_cycles(kc, tcs, nimp, z, zd, s, sd, rows, check_finite):
        """Cycles j = 0..n−1 (n = tcs.size) of the exact solver from (ζ, ζ', s, s').

        kc: :func:`constants`; tcs[j]: local time [-] of the contact-opening hit of cycle
        j, NaN for none; nimp[j]: its impulsive hits. rows (n + 1, 4) receives the state
        at the start of every cycle and at the end when rows.shape[0] > 0. Returns
        (code, cycle, events, evaluations, a, b, ζ, ζ', s, s'): code OK, SEARCH_FAILED,
        CHATTER or NON_FINITE (non-finite state, with check_finite) in ``cycle``; the
        state is the one reached (at the failing cycle's start on failure).
        """
        e = np.zeros(E_SIZE)
        out = np.zeros(8)
        tmp = np.zeros(6)
        steps = np.zeros(2)
        act = np.zeros(2, dtype=np.bool_)
        T = 2.0 * math.pi / kc[KC_WF]
        keep = rows.shape[0] > 0
        nev, evals = 0, 0
        n = tcs.size
        for m in range(n):
            if keep:
                rows[m, 0], rows[m, 1], rows[m, 2], rows[m, 3] = z, zd, s, sd
            nev += nimp[m]
            tc = tcs[m]
            if tc != tc:  # NaN: no contact in this cycle
                z, zd, s, sd = _free(kc, z, zd, s, sd, 1.0, T)
            else:
                code, z1, zd1, s1, sd1, k, ev, a, b = _contact(
                    kc, tc, z, zd, s, sd, e, out, tmp, steps, act
                )
                nev += k
                evals += ev
                if code != OK:
                    return code, m, nev, evals, a, b, z, zd, s, sd
                z, zd, s, sd = z1, zd1, s1, sd1
            if check_finite and (z - z) + (zd - zd) + (s - s) + (sd - sd) != 0.0:
                return NON_FINITE, m, nev, evals, 0.0, 0, z, zd, s, sd
        if keep:
            rows[n, 0], rows[n, 1], rows[n, 2], rows[n, 3] = z, zd, s, sd
        return OK, n, nev, evals, 0.0, 0, z, zd, s, sd

finally:
    numba.config.CACHE_DIR = _user_cache


def constants(k: PhaseConstants) -> np.ndarray:
    """The kernel's per-parameter-set constants (kc).

    Read from the events' own per-phase constants (``k.cache``, filled here by
    constructing one event of each phase), so both paths use the same numbers. P is NaN
    where the events have None (exact resonance); a phase's ``fast`` flag is 0 near
    resonance (|1 − aϖ²| < 0.1), where the events use energy-growth bounds.
    """
    SlipEvent(k, SLIP, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0)
    SlipEvent(k, REVERSE, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0)
    StickEvent(k, 0.0, 0.0, 0.0, 1.0, 1.0)
    kc = np.zeros(KC_SIZE)
    kc[:KC_SLIP] = (k.varpi, k.alpha, k.beta, k.b, k.a_stick, k.w0[FREE], k.F[FREE])
    nan = math.nan
    for phase, b0 in ((SLIP, KC_SLIP), (REVERSE, KC_REV)):
        sig, q, w0, F, _, _, ds, P, fast, apq, K = k.cache[phase]
        kc[b0 : b0 + 9] = (sig, q, w0, F, ds, nan if P is None else P, apq, K, float(fast))
    w0, F, _, qs, P, fast, a2, a3, K, w3 = k.cache[STICK]
    a3, K = (a3, K) if fast else ((0.0, 0.0), (0.0, 0.0))
    kc[KC_STICK:KC_SIZE] = (
        *(w0, F, qs[0], qs[1], nan if P is None else P),
        *(a2[0], a2[1], a3[0], a3[1], K[0], K[1], w3, float(fast)),
    )
    return kc
