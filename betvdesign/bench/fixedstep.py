"""A fixed-step integrator of the full model: classical RK4 with event post-detection.

This is the method a user would write first, kept here as a comparison point for
the work-precision study (never used for answers). docs/MODEL.md, "Dimensionless
model": the phase right-hand sides are integrated with RK4 at a constant step h;
events are detected *after* a step (ξ < 0, sin ϖτ < 0, sign change of ζ' − s',
band exit) and acted on at the step's end, without locating them inside the step,
so the method is first order in h however accurate RK4 is between events, and it
misses an event whose sign change starts and ends inside one step (a graze).

State y = (ξ, ξ', ζ, ζ', s, s'); phases "free", "slip", "reverse", "stick".
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import ClassVar, get_args

import numpy as np

from betvdesign.dynamics.result import SolverResult, TrajectoryStatus
from betvdesign.model.params import ModelParams

FREE, SLIP, STICK, REVERSE = "free", "slip", "stick", "reverse"


@dataclass(frozen=True, kw_only=True)
class FixedStepResult(SolverResult):
    """Transient from rest over ``n_cycles`` cycles by fixed-step RK4.

    Attributes
    ----------
    status : TrajectoryStatus
        "success" or "failed" (a non-finite state: the step is too large); with the other
        fields of :class:`SolverResult` (``n_events``: the post-detected events;
        ``n_root_evals`` stays 0: no event is located).
    s : float
        Final slider position [-, units of u·cosθ] (NaN when failed).
    delta_s : numpy.ndarray
        Per-cycle increments [-].
    section : numpy.ndarray
        States (ξ, ξ', ζ, ζ', s, s') [-] at τ = 2mπ/ϖ, shape (n_cycles + 1, 6).
    n_steps : int
        RK4 steps taken [-].
    n_fev : int
        Right-hand-side evaluations [-] (4 per step).
    n_contacts : int
        Contacts opened [-].
    n_impulsive : int
        Impulsive hits [-].
    """

    STATUSES: ClassVar[tuple[str, ...]] = get_args(TrajectoryStatus)

    status: TrajectoryStatus
    s: float
    delta_s: np.ndarray
    section: np.ndarray
    n_steps: int
    n_fev: int
    n_contacts: int = 0
    n_impulsive: int = 0


def _accel(phase: str, tau: float, y: list[float], p: ModelParams) -> tuple[float, float, float]:
    """(ξ'', ζ'', s'') of a phase at τ (docs/MODEL.md phase equations)."""
    sn = math.sin(p.varpi * tau)
    a, k, b = p.alpha, p.kappa, p.beta
    if phase == FREE:
        return -y[0] - sn, (sn - y[2]) / a, 0.0
    if phase == SLIP:
        return 0.0, ((1.0 - a * k) * sn - y[2]) / a, b * k * sn
    if phase == REVERSE:
        return 0.0, ((1.0 + a * k) * sn - y[2]) / a, -b * k * sn
    zdd = (sn - y[2]) / (a * (1.0 + 1.0 / b))
    return 0.0, zdd, zdd


def _rk4(phase: str, tau: float, y: list[float], h: float, p: ModelParams) -> list[float]:
    def f(t: float, u: list[float]) -> list[float]:
        xdd, zdd, sdd = _accel(phase, t, u, p)
        return [u[1], xdd, u[3], zdd, u[5], sdd]

    k1 = f(tau, y)
    k2 = f(tau + h / 2, [y[i] + h / 2 * k1[i] for i in range(6)])
    k3 = f(tau + h / 2, [y[i] + h / 2 * k2[i] for i in range(6)])
    k4 = f(tau + h, [y[i] + h * k3[i] for i in range(6)])
    return [y[i] + h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]) for i in range(6)]


def _band_phase(y: list[float], sn: float, p: ModelParams) -> str:
    """Phase at ζ' = s' from the friction band (docs/MODEL.md, b = ακ(1+β))."""
    b = p.alpha * p.kappa * (1.0 + p.beta)
    if y[2] < (1.0 - b) * sn:
        return SLIP
    if y[2] > (1.0 + b) * sn:
        return REVERSE
    return STICK


def _contact_phase(y: list[float], sn: float, p: ModelParams) -> str:
    v = y[3] - y[5]
    if v > 0.0:
        return SLIP
    if v < 0.0:
        return REVERSE
    return _band_phase(y, sn, p)


def _to_stick(y: list[float], p: ModelParams) -> None:
    """Common velocity conserving ζ' + s'/β (the post-detected crossing overshoots)."""
    v = (y[3] + y[5] / p.beta) / (1.0 + 1.0 / p.beta)
    y[3] = y[5] = v


def rk4_post(
    p: ModelParams, cycles: int, steps_per_cycle: int, *, state0: object = None
) -> FixedStepResult:
    """RK4 at h = 2π/(ϖ·steps_per_cycle) with events post-detected at step ends.

    state0: (ξ, ξ', ζ, ζ', s, s') at τ = 0, default all zero (a contact start).
    """
    t0 = time.perf_counter()
    h = 2.0 * math.pi / (p.varpi * steps_per_cycle)
    y = [0.0] * 6 if state0 is None else [float(v) for v in np.asarray(state0).reshape(6)]
    # at τ = 0, sin ϖτ = 0: a naive band test at the contact start
    phase = FREE if (y[0] > 0.0 or y[1] > 0.0) else _contact_phase(y, 0.0, p)
    section = [list(y)]
    n_events = n_con = n_imp = 0
    for m in range(cycles):
        for j in range(steps_per_cycle):
            tau = (m * steps_per_cycle + j) * h
            y = _rk4(phase, tau, y, h, p)
            tn = tau + h
            sn = math.sin(p.varpi * tn)
            if phase == FREE:
                if y[0] < 0.0:  # impact detected after the fact
                    y[0] = y[1] = 0.0
                    n_events += 1
                    n_imp += sn < 0.0
                    if sn >= 0.0:
                        n_con += 1
                        phase = _contact_phase(y, sn, p)
                        if phase == STICK:
                            _to_stick(y, p)
                continue
            if sn < 0.0:  # contact end post-detected
                phase = FREE
                n_events += 1
                continue
            if (phase == SLIP and y[3] <= y[5]) or (phase == REVERSE and y[3] >= y[5]):
                phase = _band_phase(y, sn, p)
                if phase == STICK:
                    _to_stick(y, p)
                n_events += 1
            elif phase == STICK:
                new = _band_phase(y, sn, p)
                if new != STICK:
                    phase = new
                    n_events += 1
        section.append(list(y))
        if not all(math.isfinite(v) for v in y):
            arr = np.asarray(section)
            return FixedStepResult(
                status="failed",
                message=f"non-finite state in cycle {m} (step too large for the stiff "
                f"tangential oscillator 1/sqrt(α) = {1 / math.sqrt(p.alpha):.3g}?)",
                s=float("nan"),
                delta_s=np.diff(arr[:-1, 4]),
                section=arr[:-1],
                n_cycles=m,
                n_steps=(m + 1) * steps_per_cycle,
                n_fev=4 * (m + 1) * steps_per_cycle,
                n_events=n_events,
                elapsed_s=time.perf_counter() - t0,
                n_contacts=n_con,
                n_impulsive=n_imp,
            )
    arr = np.asarray(section)
    n = cycles * steps_per_cycle
    return FixedStepResult(
        status="success",
        message=f"{cycles} cycles, {n} RK4 steps, {n_events} post-detected events",
        s=float(arr[-1, 4]),
        delta_s=np.diff(arr[:, 4]),
        section=arr,
        n_cycles=cycles,
        n_steps=n,
        n_fev=4 * n,
        n_events=n_events,
        elapsed_s=time.perf_counter() - t0,
        n_contacts=n_con,
        n_impulsive=n_imp,
    )
