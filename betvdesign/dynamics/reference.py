"""Reference solver: the same model integrated by scipy ``solve_ivp`` (unit-free).

docs/MODEL.md, "Dimensionless model". An independent second method for tests
and the baseline of the work-precision study: the full state (ξ, ξ', ζ, ζ', s, s')
is integrated numerically (no closed form), event functions are located by
``solve_ivp``'s own root finding, and the hybrid automaton (contact / free,
slip / reverse / stick) is driven by the model's switching rules, written here
again from docs/MODEL.md (:func:`choose_phase`); nothing of the exact solver is
imported (no shared phase rule, closed form or event search).

Friction models:

- ``"exact"``: Coulomb friction with switching (slip, reverse slip, stick; events
  ζ' − s' = 0 and stick-band exits).
- ``"tanh"``: regularised friction sgn(v) → tanh(v/ε) during contact (no stick
  phase, no horizontal events; stiff for small ε: use Radau or LSODA).

Impacts, impulsive hits and contact ends are handled identically in both
(contact ends are integrated up to the known time (2j+1)π/ϖ). Sections are
integration boundaries, so ``section`` holds exact-time states. The result is a
:class:`~betvdesign.dynamics.result.Trajectory` with ``n_fev`` counting
right-hand-side evaluations; a failed integration returns status "failed" with
the scipy message and the cycles completed so far.
"""

from __future__ import annotations

import math
import time
from typing import Literal, NamedTuple

import numpy as np
from scipy.integrate import solve_ivp

from betvdesign.dynamics.inputs import check_cycles, check_state0
from betvdesign.dynamics.result import Event, Trajectory
from betvdesign.errors import ParameterError
from betvdesign.params import ModelParams

Method = Literal["RK45", "DOP853", "Radau", "LSODA", "BDF", "RK23"]
METHODS = ("RK45", "DOP853", "Radau", "LSODA", "BDF", "RK23")
FRICTION = ("exact", "tanh")
FREE, SLIP, STICK, REVERSE = "free", "slip", "stick", "reverse"
TANH = "slip-tanh"  # horizontal mode during contact with regularised friction
#: relative velocity |ζ' − s'| below which ζ' = s' is taken as reached (scaled)
VTOL = 1e-9
#: look-ahead [fraction of a cycle] at which the stick band is tested when ζ' = s'
LOOKAHEAD = 1e-6


class _K(NamedTuple):
    alpha: float
    beta: float
    kappa: float
    varpi: float
    b: float
    a_stick: float


def _constants(p: ModelParams) -> _K:
    """MODEL.md: b = ακ(1 + β) stick-band half-width, α(1 + 1/β) stick inertia."""
    al, be, ka = p.alpha, p.beta, p.kappa
    return _K(al, be, ka, p.varpi, al * ka * (1.0 + be), al * (1.0 + 1.0 / be))


def choose_phase(k: _K, tau: float, z: float, zd: float, sd: float, matched: bool) -> str:
    """MODEL.md stick/slip rules: the sign of ζ' − s' when they differ (slip if ζ' > s',
    reverse slip if ζ' < s'); when ζ' = s' (``matched``, or equal within VTOL) the
    friction band (1 − b) sin ϖτ ≤ ζ ≤ (1 + b) sin ϖτ decides: stick inside, slip below,
    reverse slip above. The band is tested a short look-ahead δ after τ on the stick
    flow α(1 + 1/β) ζ'' + ζ = sin ϖτ (third-order Taylor), which settles the cases
    where ζ sits on an edge (a band exit, or sin ϖτ = 0 at a contact opening)."""
    v = zd - sd
    if not matched and abs(v) > VTOL * (1.0 + abs(zd) + abs(sd)):
        return SLIP if v > 0.0 else REVERSE
    w, A = k.varpi, k.a_stick
    vs = (zd + sd / k.beta) / (1.0 + 1.0 / k.beta)
    d = LOOKAHEAD * 2.0 * math.pi / w
    z2 = (math.sin(w * tau) - z) / A
    z3 = (w * math.cos(w * tau) - vs) / A
    zn = z + vs * d + z2 * d * d / 2.0 + z3 * d**3 / 6.0
    sn = math.sin(w * (tau + d))
    if zn < (1.0 - k.b) * sn:
        return SLIP
    if zn > (1.0 + k.b) * sn:
        return REVERSE
    return STICK


MAX_ZERO_LENGTH = 20
#: After an event at the very start of a phase (round-off), event detection is
#: masked over MASK·(2π/ϖ) so that solve_ivp can leave the switching surface.
MASK = 1e-9


def _rhs_factory(k: _K, contact: bool, hmode: str, eps: float):
    al, be, ka, w, A = k.alpha, k.beta, k.kappa, k.varpi, k.a_stick

    def rhs(t: float, y: np.ndarray) -> list[float]:
        sn = math.sin(w * t)
        if contact:
            xdd = 0.0
        else:
            xdd = -sn - y[0]
        if hmode == FREE:
            zdd, sdd = (sn - y[2]) / al, 0.0
        elif hmode == SLIP:
            zdd, sdd = ((1.0 - al * ka) * sn - y[2]) / al, be * ka * sn
        elif hmode == REVERSE:
            zdd, sdd = ((1.0 + al * ka) * sn - y[2]) / al, -be * ka * sn
        elif hmode == STICK:
            zdd = (sn - y[2]) / A
            sdd = zdd
        else:  # TANH
            fr = ka * sn * math.tanh((y[3] - y[5]) / eps)
            zdd, sdd = (sn - y[2]) / al - fr, be * fr
        return [y[1] if not contact else 0.0, xdd, y[3], zdd, y[5], sdd]

    return rhs


def _events(k: _K, contact: bool, hmode: str) -> list:
    w, b = k.varpi, k.b
    evs = []
    if not contact:

        def gap(t: float, y: np.ndarray) -> float:
            return y[0]

        gap.terminal, gap.direction = True, -1
        evs.append(gap)
        return evs
    if hmode in (SLIP, REVERSE):

        def vel(t: float, y: np.ndarray) -> float:
            return y[3] - y[5]

        vel.terminal, vel.direction = True, -1 if hmode == SLIP else 1
        evs.append(vel)
    elif hmode == STICK:

        def lo(t: float, y: np.ndarray) -> float:
            return y[2] - (1.0 - b) * math.sin(w * t)

        def hi(t: float, y: np.ndarray) -> float:
            return (1.0 + b) * math.sin(w * t) - y[2]

        lo.terminal, lo.direction = True, -1
        hi.terminal, hi.direction = True, -1
        evs += [lo, hi]
    return evs


def simulate(
    p: ModelParams,
    cycles: int,
    *,
    method: str = "DOP853",
    rtol: float = 1e-10,
    atol: float = 1e-12,
    friction: str = "exact",
    eps: float = 1e-3,
    max_step: float = math.inf,
    state0: object = None,
    dense: bool = False,
) -> Trajectory:
    """Integrate ``cycles`` actuation cycles with ``solve_ivp`` (see module docstring).

    method: a solve_ivp method; rtol, atol: its tolerances [-]; friction: "exact"
    (switching Coulomb) or "tanh" (regularised, width ``eps`` [-] in relative velocity);
    max_step: solve_ivp's max_step [-]; state0 as in :func:`solver.simulate`.
    """
    if not isinstance(p, ModelParams):
        raise ParameterError(f"p must be a ModelParams, got {type(p).__name__}")
    n = check_cycles(cycles)
    st = np.array(check_state0(state0))
    if method not in METHODS:
        raise ParameterError(f"method must be one of {', '.join(METHODS)}, got {method!r}")
    if friction not in FRICTION:
        raise ParameterError(f"friction must be 'exact' or 'tanh', got {friction!r}")
    for name, v in (("rtol", rtol), ("atol", atol), ("eps", eps), ("max_step", max_step)):
        if not (isinstance(v, (int, float)) and v > 0 and not math.isnan(v)):
            raise ParameterError(f"{name} must be > 0, got {v!r}")
    t_start = time.perf_counter()
    k = _constants(p)
    w = p.varpi
    T = 2.0 * math.pi / w
    tau, y = 0.0, st.copy()
    contact = y[0] == 0.0 and y[1] <= 0.0  # hit at phase 0: contact opens
    hmode = FREE
    events: list[Event] = []
    pieces: list = []
    section = np.empty((n + 1, 6))
    section[0] = y
    nfev = 0
    zero_len = 0
    status, message, m = "success", f"{n} cycles integrated", 0

    def open_contact(y: np.ndarray, on: int = -1) -> str:
        if friction == "tanh":
            return TANH
        ph = choose_phase(k, tau, y[2], y[3], y[5], on >= 0)
        if ph == STICK or on == 0:
            y[3] = y[5] = (y[3] + y[5] / p.beta) / (1.0 + 1.0 / p.beta)
        return ph

    if contact:
        y[1] = 0.0
        hmode = open_contact(y)
        events.append(Event(0.0, "impact", "free", hmode))
    while m < n:
        t_sec = (m + 1) * T
        t_end = t_sec
        if contact:
            t_end = min(t_sec, (2.0 * math.floor(tau / T + 1e-12) + 1.0) * math.pi / w)
            if t_end <= tau:  # contact end reached exactly at tau
                t_end = tau
        evs = _events(k, contact, hmode)
        if zero_len:  # an event fired where the phase started: step past it unmasked
            t_end = min(t_end, tau + MASK * T)
            evs = []
        if t_end > tau:
            sol = solve_ivp(
                _rhs_factory(k, contact, hmode, eps),
                (tau, t_end),
                y,
                method=method,
                rtol=rtol,
                atol=atol,
                events=evs or None,
                max_step=max_step,
                dense_output=dense,
            )
            nfev += sol.nfev
            if sol.status == -1:
                status, message = (
                    "failed",
                    f"solve_ivp ({method}) failed in cycle {m}: {sol.message}",
                )
                break
            if dense:
                pieces.append((tau, sol.t[-1], sol.sol))
            hit = [i for i, te in enumerate(sol.t_events or []) if len(te)]
        else:
            sol, hit = None, []
        if hit:
            i = hit[0]
            t_new = float(sol.t_events[i][0])
            y = np.array(sol.y_events[i][0], dtype=float)
            if t_new - tau <= 1e-14 * max(1.0, tau):
                zero_len += 1
                if zero_len > MAX_ZERO_LENGTH:
                    status = "failed"
                    message = f"events repeat without progress at τ = {t_new:.12g}"
                    break
                continue  # masked step next
            zero_len = 0
            tau = t_new
            before = hmode
            if not contact:
                y[0], y[1] = 0.0, 0.0
                if math.sin(w * tau) >= 0.0:
                    contact = True
                    hmode = open_contact(y)
                    events.append(Event(tau, "impact", "free", hmode))
                else:
                    events.append(Event(tau, "impulsive", "free", "free"))
            elif hmode == STICK:
                hmode = open_contact(y, 1 + i)
                events.append(Event(tau, "band-exit", "stick", hmode))
            else:
                hmode = open_contact(y, 0)
                events.append(Event(tau, "velocity-match", before, hmode))
            continue
        if sol is not None:
            y = np.array(sol.y[:, -1], dtype=float)
        tau = t_end
        if zero_len:
            zero_len = 0
            if t_end < t_sec and not (contact and _is_contact_end(tau, w)):
                continue
        if (contact and t_end < t_sec) or (contact and t_end == t_sec and _is_contact_end(tau, w)):
            events.append(Event(tau, "separation", hmode, "free"))
            contact, hmode = False, FREE
            y[0], y[1] = 0.0, 0.0
        if t_end == t_sec:
            m += 1
            section[m] = y
    section = section[: m + 1]
    sampler = _sampler(pieces) if dense else None
    return Trajectory(
        params=p,
        solver=f"solve_ivp:{method}/{friction}",
        status=status,
        success=status == "success",
        message=message,
        s=float(section[-1, 4]),
        delta_s=np.diff(section[:, 4]),
        section=section,
        events=events,
        n_events=len(events),
        n_cycles=m,
        n_root_evals=0,
        elapsed_s=time.perf_counter() - t_start,
        n_fev=nfev,
        _sampler=sampler,
    )


def _is_contact_end(tau: float, w: float) -> bool:
    ph = (w * tau / math.pi) % 2.0
    return abs(ph - 1.0) < 1e-12


def _sampler(pieces: list):
    def sample(tau: np.ndarray) -> np.ndarray:
        out = np.empty((tau.size, 6))
        for j, t in enumerate(tau):
            for a, b, solf in pieces:
                if a <= t <= b:
                    out[j] = solf(t)
                    break
            else:
                raise ValueError(f"τ = {t} outside the integrated span")
        return out

    return sample
