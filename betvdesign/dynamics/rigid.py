"""The α → 0 limit: rigid tangential contact, in exact closed form (unit-free).

docs/MODEL.md, "Dimensionless model". With α = k_v/k_h → 0 the head's tangential
equation α ζ'' + ζ = (1 ∓ ακ) sin ϖτ (every phase) degenerates to ζ = sin ϖτ: the
head's tangential position is slaved to the actuator and its velocity is
ζ' = ϖ cos ϖτ whatever the slider does. The slider then only feels Coulomb
friction from a head moving on a prescribed path:

- free flight:             s'' = 0
- contact, slip (s' < ζ'): s'' = +βκ sin ϖτ
- reverse slip (s' > ζ'):  s'' = −βκ sin ϖτ
- stick (s' = ζ'):         s' = ϖ cos ϖτ, possible only while the friction needed,
  |s''| = ϖ² sin ϖτ, is at most βκ sin ϖτ, i.e. ϖ² ≤ βκ (the α → 0 limit of the
  stick band (1 − b) sin ϖτ ≤ ζ ≤ (1 + b) sin ϖτ with b = ακ(1 + β)).

The relative velocity w = s' − ζ' is affine in cos ϖτ during a slip phase,
w = w₀ − (cos ϖτ − cos ϖτ₀)(ϖ + σβκ/ϖ), so the instant where slip ends is a closed
form arccos. Stick, once reached, lasts until the contact ends (the condition
ϖ² ≤ βκ does not depend on τ), so a contact has at most two phases.

The vertical motion (independent of the slider and of α) gives the contact
intervals; it is the full model's own exact vertical schedule
(:class:`betvdesign.dynamics.vertical.VerticalSchedule`). Because every contact ends at
τ = (2j+1)π/ϖ with ξ = ξ' = 0, the vertical motion is exactly periodic from the
first contact end, and the slider's periodic state is the fixed point of a
monotone scalar map of its velocity, found by bracketing.

The initial state differs from the full model's on purpose: in the rigid limit
ζ'(0) = ϖ (the full model starts with ζ'(0) = 0 and carries a fast tangential
oscillation that friction damps within a few cycles). Compare periodic states,
not transients.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import ClassVar, get_args

import numpy as np
from scipy.optimize import brentq

from betvdesign.dynamics.result import Mode, RigidStatus, SolverResult, TrajectoryStatus
from betvdesign.dynamics.vertical import VerticalSchedule
from betvdesign.errors import ParameterError
from betvdesign.model.domain import mode_of
from betvdesign.model.params import ModelParams

TWO_PI = 2.0 * math.pi


@dataclass(frozen=True, slots=True)
class Contact:
    """One contact interval [start, end] of the head on the slider [τ]."""

    start: float
    end: float


@dataclass(frozen=True, kw_only=True)
class RigidTrajectory(SolverResult):
    """Transient of the rigid-limit model over whole actuation cycles.

    Attributes
    ----------
    status : TrajectoryStatus
        Always "success": the closed form cannot fail (bad input raises); with the other
        fields of :class:`SolverResult` (``n_events``: contact starts and ends and
        impulsive hits; ``n_root_evals``: the vertical motion's).
    params : ModelParams
        The model (its α is not used: α → 0).
    s : float
        Final slider position [-, units of u·cosθ].
    v : float
        Final slider velocity [-].
    delta_s : numpy.ndarray
        Per-cycle increments s(2(m+1)π/ϖ) − s(2mπ/ϖ) [-].
    events : list of (float, str, str, str)
        The log of (τ [-], kind, phase before, phase after), when asked.
    """

    STATUSES: ClassVar[tuple[str, ...]] = get_args(TrajectoryStatus)

    status: TrajectoryStatus
    params: ModelParams
    s: float
    v: float
    delta_s: np.ndarray
    events: list[tuple[float, str, str, str]] = field(default_factory=list)


@dataclass(frozen=True, kw_only=True)
class RigidPeriodic(SolverResult):
    """Periodic state of the rigid-limit model.

    Attributes
    ----------
    status : RigidStatus
        "success" or "no_contact" (:data:`RigidStatus`); with the other fields of
        :class:`SolverResult` (``n_root_evals``: the vertical motion's).
    params : ModelParams
        The model (its α is not used: α → 0).
    delta_s : float
        Periodic increment per actuation cycle [-, units of u·cosθ] (0 with "no_contact").
    mode : {"push", "pull", "stalled"} or None
        "push" (Δs > 0), "pull" (Δs < 0), "stalled", or None (not driven).
    period_cycles : int
        The vertical period [cycles] (0 with "no_contact").
    v_section : float
        Slider velocity [-] at the contact end that starts the period.
    residual : float
        |F(v) − v| [-] of the velocity map at the fixed point.
    contacts : list of Contact
        The contacts the period was built from.
    impacts_per_cycle : float
        Hits per cycle [-].
    contact_fraction : float
        Fraction of the time in contact [-].
    """

    STATUSES: ClassVar[tuple[str, ...]] = get_args(RigidStatus)

    status: RigidStatus
    params: ModelParams
    delta_s: float
    mode: Mode | None
    period_cycles: int
    v_section: float
    residual: float
    contacts: list[Contact]
    impacts_per_cycle: float
    contact_fraction: float


# --------------------------------------------------------------------------- slider
def _slip_end(sigma: int, tau0: float, w0: float, tau1: float, p: ModelParams) -> float | None:
    """Instant in (τ₀, τ₁] where the relative velocity of a slip phase reaches 0, or None.

    w(τ) = w₀ − (cos ϖτ − cos ϖτ₀)(ϖ + σβκ/ϖ) (see module docstring); cos ϖτ is
    decreasing over a contact (ϖτ within [2jπ, (2j+1)π]).
    """
    wv, bk = p.varpi, p.beta * p.kappa
    rate = wv + sigma * bk / wv
    if rate == 0.0 or w0 == 0.0:
        return None
    c0 = math.cos(wv * tau0)
    c_star = c0 + w0 / rate
    if not c_star < c0:  # w moves away from 0
        return None
    if c_star < math.cos(wv * tau1):
        return None
    base = TWO_PI * math.floor(wv * tau0 / TWO_PI + 1e-12)
    return (base + math.acos(max(-1.0, min(1.0, c_star)))) / wv


def _advance_slip(sigma: int, tau0: float, s0: float, v0: float, tau: float, p: ModelParams):
    """Closed-form slip flow: s'' = σβκ sin ϖτ from (τ₀, s₀, v₀) to τ; returns (s, v)."""
    wv, bk = p.varpi, p.beta * p.kappa
    c0, sn0 = math.cos(wv * tau0), math.sin(wv * tau0)
    c, sn = math.cos(wv * tau), math.sin(wv * tau)
    v = v0 - sigma * bk / wv * (c - c0)
    s = s0 + (v0 + sigma * bk / wv * c0) * (tau - tau0) - sigma * bk / wv**2 * (sn - sn0)
    return s, v


def _contact_flow(c: Contact, s: float, v: float, p: ModelParams, log: list | None):
    """Slider state (s, v) after the contact ``c``, exactly (at most two phases)."""
    wv = p.varpi
    can_stick = wv * wv <= p.beta * p.kappa
    tau = c.start
    w = v - wv * math.cos(wv * tau)
    if w < 0.0:
        phase = "slip"
    elif w > 0.0 or not can_stick:
        phase = "reverse"
    else:
        phase = "stick"
    if log is not None:
        log.append((tau, "contact_start", "free", phase))
    # At most two phases: slip -> (stick | reverse), reverse -> stick (only if ϖ² ≤ βκ).
    if phase != "stick":
        sigma = 1 if phase == "slip" else -1
        t_hit = None
        if phase == "slip" or can_stick:
            t_hit = _slip_end(sigma, tau, w, c.end, p)
        if t_hit is None:
            return _end(c, *_advance_slip(sigma, tau, s, v, c.end, p), phase, log)
        s, v = _advance_slip(sigma, tau, s, v, t_hit, p)
        new = "stick" if can_stick else "reverse"
        if log is not None:
            log.append((t_hit, "velocity_match", phase, new))
        tau, phase = t_hit, new
        if phase == "reverse":  # w' = (ϖ² − βκ) sin ϖτ > 0: no further event
            return _end(c, *_advance_slip(-1, tau, s, v, c.end, p), phase, log)
    # stick until the contact ends: s' = ζ' = ϖ cos ϖτ
    s += math.sin(wv * c.end) - math.sin(wv * tau)
    v = wv * math.cos(wv * c.end)
    return _end(c, s, v, phase, log)


def _end(c: Contact, s: float, v: float, phase: str, log: list | None):
    if log is not None:
        log.append((c.end, "contact_end", phase, "free"))
    return s, v


# ------------------------------------------------------------------------ vertical
def contact_schedule(varpi: float, tau_end: float, *, max_contacts: int | None = None):
    """Contacts and impulsive hits of the vertical motion in [0, τ_end].

    From rest at a contact start at τ = 0 (docs/MODEL.md "Initial state"); the exact
    vertical motion is :class:`betvdesign.dynamics.vertical.VerticalSchedule` (the
    same one the full model uses).

    Parameters
    ----------
    varpi : float
        ϖ [-].
    tau_end : float
        End of the span τ_end [-].
    max_contacts : int, optional
        Stop after this many contacts.

    Returns
    -------
    contacts : list of Contact
        The finite-duration contacts [τ].
    impulsive : list of float
        Times of the impulsive hits [-].
    n_root_evals : int
        Evaluations of the gap by the hit search [-].
    """
    period = TWO_PI / varpi
    n_cyc = math.ceil(tau_end / period - 1e-12)
    vs = VerticalSchedule(varpi, horizon=max(n_cyc + 1, 2))
    contacts: list[Contact] = []
    impulsive: list[float] = []
    for m in range(n_cyc + 1):
        try:
            cyc = vs.cycle(m)
        except IndexError:  # no contact recurs: the computed horizon is all there is
            break
        base = m * period
        if cyc.contact_start is not None and base + cyc.contact_start <= tau_end:
            contacts.append(Contact(base + cyc.contact_start, base + math.pi / varpi))
            if max_contacts is not None and len(contacts) >= max_contacts:
                break
        impulsive.extend(base + t for t in cyc.impulsive if base + t <= tau_end)
    return contacts, impulsive, vs.n_root_evals


def _require_ideal(p: ModelParams) -> None:
    """Refuse a model with damping or restitution (the rigid limit is of the ideal one).

    Raises
    ------
    ParameterError
        For a ``p`` with damping or restitution.
    """
    if not p.ideal:
        raise ParameterError(
            "the rigid limit is a limit of the idealised model; this p has damping or "
            "restitution: use dynamics.periodic_orbit / simulate"
        )


def _sections(
    p: ModelParams, contacts: list[Contact], cycles: int, state0: tuple[float, float], events
) -> tuple[list[float], float, int]:
    """Carry the slider through free flight and the contacts, section by section.

    Parameters
    ----------
    p : ModelParams
        The model.
    contacts : list of Contact
        The finite-duration contacts (:func:`contact_schedule`).
    cycles : int
        Actuation cycles [-].
    state0 : tuple of 2 floats
        (s, s') [-] at τ = 0.
    events : list or None
        The event log, appended to (None: none kept).

    Returns
    -------
    sections : list of float
        s [-] at τ = 2mπ/ϖ, m = 0..cycles.
    v : float
        The final velocity s' [-].
    k : int
        The contacts passed.
    """
    period = TWO_PI / p.varpi
    s, v = state0
    tau = 0.0
    sections = [s]
    k = 0
    for m in range(1, cycles + 1):
        t_sec = m * period
        while k < len(contacts) and contacts[k].end <= t_sec + 1e-12 * period:
            c = contacts[k]
            s += v * (c.start - tau)
            s, v = _contact_flow(c, s, v, p, events)
            tau = c.end
            k += 1
        if k < len(contacts) and contacts[k].start < t_sec:  # contact spans the section
            raise AssertionError("contacts end at (2j+1)π/ϖ, never across a section")
        s += v * (t_sec - tau)
        tau = t_sec
        sections.append(s)
    return sections, v, k


def _no_contact(
    p: ModelParams,
    max_cycles: int,
    contacts: list[Contact],
    n_impulsive: int,
    n_evals: int,
    t0: float,
) -> RigidPeriodic:
    """The answer of :func:`rigid_periodic` when the head makes no two finite contacts.

    Parameters
    ----------
    p : ModelParams
        The model.
    max_cycles : int
        The horizon searched [cycles].
    contacts : list of Contact
        The contacts found (fewer than two).
    n_impulsive : int
        Impulsive hits within the horizon.
    n_evals : int
        Root evaluations of the vertical search.
    t0 : float
        :func:`time.perf_counter` at the start [s].

    Returns
    -------
    RigidPeriodic
        Status "no_contact".
    """
    wv = p.varpi
    return RigidPeriodic(
        status="no_contact",
        message=(
            f"no finite-duration contact within {max_cycles} cycles after the first: "
            f"ϖ = {wv:g} is outside the window where this model drives the slider"
        ),
        params=p,
        delta_s=0.0,
        mode=None,
        period_cycles=0,
        v_section=float("nan"),
        residual=float("nan"),
        contacts=contacts,
        impacts_per_cycle=n_impulsive / max_cycles,
        contact_fraction=0.0,
        n_root_evals=n_evals,
        elapsed_s=time.perf_counter() - t0,
    )


# ----------------------------------------------------------------------- public API
def rigid_simulate(
    p: ModelParams, cycles: int, *, state0: tuple[float, float] = (0.0, 0.0), log: bool = False
) -> RigidTrajectory:
    """Integrate the rigid-limit model over ``cycles`` actuation cycles, exactly.

    See the module docstring for the equations (docs/MODEL.md): the head's tangential
    motion is slaved to the actuator and the slider feels Coulomb friction only.

    Parameters
    ----------
    p : ModelParams
        The paper's model (no damping, no restitution); its α is ignored (α → 0).
    cycles : int
        Actuation cycles [-] (≥ 1).
    state0 : tuple of 2 floats
        (s, s') [-] at τ = 0 (a contact start).
    log : bool
        Keep the event log.

    Returns
    -------
    RigidTrajectory
        Always "success".

    Raises
    ------
    ParameterError
        For a ``p`` with damping or restitution.
    ValueError
        For ``cycles`` < 1.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773 (α → 0 always gives pull
    mode).
    """
    _require_ideal(p)
    t0 = time.perf_counter()
    if cycles < 1:
        raise ValueError(f"cycles must be >= 1, got {cycles}")
    wv = p.varpi
    period = TWO_PI / wv
    tau_end = cycles * period
    contacts, impulsive, n_evals = contact_schedule(wv, tau_end)
    events: list = [] if log else None  # type: ignore[assignment]
    for t in impulsive if log else ():
        events.append((t, "impulsive_hit", "free", "free"))
    sections, v, k = _sections(p, contacts, cycles, state0, events)
    s = sections[-1]
    if log:
        events.sort(key=lambda e: e[0])
    n_ev = 2 * k + len(impulsive)
    msg = f"{cycles} cycles, {k} contacts, {len(impulsive)} impulsive hits (rigid limit α → 0)"
    return RigidTrajectory(
        status="success",
        message=msg,
        params=p,
        n_cycles=cycles,
        s=s,
        v=v,
        delta_s=np.diff(np.asarray(sections)),
        events=events or [],
        n_events=n_ev,
        n_root_evals=n_evals,
        elapsed_s=time.perf_counter() - t0,
    )


def rigid_periodic(p: ModelParams, *, max_cycles: int = 200) -> RigidPeriodic:
    """Periodic state of the rigid-limit model, exactly (fixed point of the velocity map).

    The vertical period P (cycles between two contact ends) is found from the
    vertical motion; over one period the slider velocity map F is monotone
    non-decreasing with F(v) − v non-increasing, so its fixed point is bracketed
    and refined to round-off. ``delta_s`` is the displacement per cycle there.

    Parameters
    ----------
    p : ModelParams
        The paper's model (no damping, no restitution); its α is ignored (α → 0).
    max_cycles : int
        Horizon [cycles] within which two finite-duration contacts must occur.

    Returns
    -------
    RigidPeriodic
        "success", or "no_contact" when the head makes no finite-duration contact
        within ``max_cycles`` (ϖ beyond the window: the model does not drive the slider)
        (:data:`~betvdesign.dynamics.result.RigidStatus`).

    Raises
    ------
    ParameterError
        For a ``p`` with damping or restitution.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773 (α → 0 always gives pull
    mode).
    """
    _require_ideal(p)
    t0 = time.perf_counter()
    wv = p.varpi
    period = TWO_PI / wv
    contacts, impulsive, n_evals = contact_schedule(wv, max_cycles * period, max_contacts=2)
    if len(contacts) < 2:
        return _no_contact(p, max_cycles, contacts, len(impulsive), n_evals, t0)
    first, second = contacts[0], contacts[1]
    n_cyc = round((second.end - first.end) / period)
    cycle_contact = Contact(second.start, second.end)
    hits_in_period = 1 + sum(1 for t in impulsive if first.end < t < second.end)

    def one_period(v: float) -> tuple[float, float]:
        s = v * (cycle_contact.start - first.end)
        return _contact_flow(cycle_contact, s, v, p, None)

    def gap(v: float) -> float:
        return one_period(v)[1] - v

    bound = wv + 2.0 * p.beta * p.kappa / wv + 1.0
    v_star = brentq(gap, -bound, bound, xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200)
    ds_period, v_out = one_period(v_star)
    delta_s = ds_period / n_cyc
    mode = mode_of(delta_s)
    duration = cycle_contact.end - cycle_contact.start
    return RigidPeriodic(
        status="success",
        message=f"periodic (rigid limit α → 0), period {n_cyc} cycle(s), Δs = {delta_s:.12g}",
        params=p,
        delta_s=delta_s,
        mode=mode,
        period_cycles=n_cyc,
        v_section=v_star,
        residual=abs(v_out - v_star),
        contacts=[first, second],
        impacts_per_cycle=hits_in_period / n_cyc,
        contact_fraction=duration / (n_cyc * period),
        n_root_evals=n_evals,
        elapsed_s=time.perf_counter() - t0,
    )
