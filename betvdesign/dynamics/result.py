"""Result objects of the dynamics solvers (unit-free), in the spirit of scipy's OdeResult.

Every result carries ``status`` (a short machine word), ``success``, ``message``
(what failed and what to try), counters and the wall-clock ``elapsed_s`` [s].
Failures are never silent: arrays of a failed run are truncated at the last
valid cycle, never padded with NaN.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Literal, NamedTuple

import numpy as np

from betvdesign.model.params import ModelParams

Mode = Literal["push", "pull", "stalled"]


class Event(NamedTuple):
    """One event of a trajectory: τ [-], kind, phase before and after.

    kinds: "impact" (contact opens), "impulsive" (zero-duration hit),
    "separation" (contact ends at sin ϖτ = 0), "velocity-match" (ζ' = s' reached
    in slip), "band-exit" (stick ends); phases: "free", "slip", "reverse", "stick".
    """

    tau: float
    kind: str
    phase_before: str
    phase_after: str


@dataclass
class Trajectory:
    """A transient run of ``n_cycles`` actuation cycles from ``section[0]``.

    ``s`` [-]: final slider position (units of u·cosθ); ``delta_s`` [-]: per-cycle
    increments (length n_cycles); ``section``: states (ξ, ξ', ζ, ζ', s, s') at
    τ = 2mπ/ϖ, m = 0..n_cycles, shape (n_cycles+1, 6); ``events``: the event log;
    ``solver``: "exact" or the reference method (e.g. "solve_ivp:DOP853/exact");
    ``n_fev``: right-hand-side evaluations (reference solvers; 0 for the exact one);
    ``phases``: (τ_start, τ_end, tangential phase) pieces of the exact solution, each one
    closed-form expression (filled when ``dense=True``); ``engine``: how the exact
    solver's one implementation ran: "compiled" (numba) or "python" (its source run
    uncompiled under ``NUMBA_DISABLE_JIT=1``).
    """

    params: ModelParams
    solver: str
    status: str
    success: bool
    message: str
    s: float
    delta_s: np.ndarray
    section: np.ndarray
    events: list[Event]
    n_events: int
    n_cycles: int
    n_root_evals: int
    elapsed_s: float
    n_fev: int = 0
    impacts_per_cycle: float = float("nan")
    contact_fraction: float = float("nan")
    #: True when contact recurs (the vertical motion is periodic with contacts), False
    #: when the hits are impulsive only within the horizon: the slider is not driven and
    #: the last Δs is coasting (exact solver; None for the reference solvers)
    driven: bool | None = None
    phases: list[tuple[float, float, str]] = field(default_factory=list, repr=False)
    #: "compiled" (numba, :mod:`betvdesign.dynamics.contact`) or "python" (uncompiled)
    engine: str = "python"
    _sampler: Callable[[np.ndarray], np.ndarray] | None = field(default=None, repr=False)

    def sample(self, tau: np.ndarray | float) -> np.ndarray:
        """Dense output: states (n, 6) at the times τ (requires ``dense=True``)."""
        if self._sampler is None:
            raise ValueError("no dense output: run the solver with dense=True")
        t = np.atleast_1d(np.asarray(tau, dtype=float))
        return self._sampler(t)


@dataclass
class PeriodicResult:
    """The periodic state the slider settles to (MODEL.md "Slider").

    ``status``: "success"; "unbounded" (no periodic orbit exists: at the exact
    tangential resonance α·ϖ² = 1 with ακ < 2 the head's tangential amplitude grows
    linearly, proven and measured, see :mod:`betvdesign.dynamics.periodic`);
    "not_converged"; "not_driven"; "failed". Only "success" carries Δs and a mode.

    ``state``: section state (ξ, ξ', ζ, ζ', s, s') at τ = 2m*π/ϖ on the orbit (s = 0);
    ``delta_s`` [-]: slider increment per actuation cycle on the orbit (the orbit's
    increment over ``period_cycles`` divided by it); ``mode``: "push" (Δs > 0), "pull"
    (Δs < 0) or "stalled" (|Δs| at round-off; :func:`betvdesign.model.domain.mode_of`);
    ``residual``: max-norm of (map(state) − state) over the whole
    section state, slider position excepted (it drifts by design); ``floquet``:
    multipliers of the section map (ζ, ζ', s'), complex, sorted by decreasing modulus;
    ``stable``: all |μ| < 1; ``transient_cycles``, ``transient_s``: cycles iterated from
    rest before the orbit was accepted and the slider position [-] they reached.
    """

    params: ModelParams
    status: str
    success: bool
    message: str
    delta_s: float | None
    mode: Mode | None
    period_cycles: int | None
    residual: float | None
    floquet: np.ndarray | None
    stable: bool | None
    state: np.ndarray | None
    impacts_per_cycle: float
    contact_fraction: float
    n_cycles: int
    n_newton: int
    n_events: int
    n_root_evals: int
    elapsed_s: float
    transient_cycles: int = 0
    transient_s: float = 0.0

    @property
    def floquet_moduli(self) -> list[float] | None:
        """|μ| of the Floquet multipliers, decreasing (JSON-friendly)."""
        if self.floquet is None:
            return None
        return [float(abs(m)) for m in self.floquet]
