"""The solvers' answers: one result contract for every solver (unit-free).

Every answer of a solver is a :class:`SolverResult`, in the spirit of scipy's
``OptimizeResult``: ``status``, a short machine word from the fixed vocabulary of its
kind of answer (a ``Literal`` of this module, every word documented), ``success`` (the
word is the kind's success word), ``message`` (what happened; on a failure what failed
and what to try), the counters ``n_cycles``, ``n_events``, ``n_root_evals`` and the
wall-clock ``elapsed_s`` [s]. Failures are never silent: arrays of a failed run are
truncated at the last valid cycle, never padded with NaN. The status words are plain
strings, so JSON, CSV and pickles carry them unchanged.

- :class:`Trajectory`: a transient (exact :func:`betvdesign.dynamics.simulate`, the
  reference :func:`betvdesign.dynamics.reference.simulate`), :data:`TrajectoryStatus`;
- :class:`PeriodicResult`: the periodic orbit
  (:func:`betvdesign.dynamics.periodic_orbit`), :data:`PeriodicStatus`;
- ``VerticalResult``: the vertical motion alone (:mod:`betvdesign.dynamics.vertical`),
  :data:`VerticalStatus`;
- ``RigidTrajectory`` (:data:`TrajectoryStatus`) and ``RigidPeriodic``
  (:data:`RigidStatus`): the rigid limit α → 0 (:mod:`betvdesign.dynamics.rigid`);
- ``Settling``: settling from rest (:mod:`betvdesign.dynamics.settling`),
  :data:`SettlingStatus`;
- ``FixedStepResult``: the fixed-step RK4 comparison (:mod:`betvdesign.bench.fixedstep`),
  :data:`TrajectoryStatus`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, ClassVar, Literal, NamedTuple, get_args

import numpy as np

from betvdesign.model.params import ModelParams

Mode = Literal["push", "pull", "stalled"]

#: How a transient run ends:
#:
#: - ``"success"``: every cycle asked for was computed;
#: - ``"failed"``: a cycle could not be advanced (exact solver: a chattering contact, a
#:   non-terminating event search or a non-finite state; reference solver: solve_ivp
#:   failed, events repeating without progress or rebounds that do not accumulate;
#:   fixed step: a non-finite state); the arrays hold the cycles before it and
#:   ``message`` names the cycle and the cause.
TrajectoryStatus = Literal["success", "failed"]

#: How a periodic-orbit search ends (only ``"success"`` carries Δs and a mode):
#:
#: - ``"success"``: a stable periodic orbit, fixed-point residual ≤ tol;
#: - ``"unbounded"``: no periodic orbit exists: the exact free-flight tangential
#:   resonance α·ϖ² = 1 with ακ < 2, where the head's tangential amplitude grows
#:   linearly (proven and measured, :mod:`betvdesign.dynamics.periodic`);
#: - ``"not_converged"``: no stable orbit of the periods tried within the cycle budget
#:   (quasi-periodic or slowly growing motion; ``residual`` is the best one reached);
#: - ``"not_driven"``: no contact recurs (the hits are impulsive only), or the recurring
#:   contact lasts at most :data:`~betvdesign.model.domain.ROUND_OFF_SCALE` of a cycle
#:   (the slider only coasts on its first contact from rest): the slider is not driven
#:   (MODEL.md, "Vertical motion");
#: - ``"failed"``: the vertical motion or a cycle could not be computed (``message``).
PeriodicStatus = Literal["success", "unbounded", "not_converged", "not_driven", "failed"]

#: How the vertical-only computation ends:
#:
#: - ``"success"``: the vertical motion is periodic (a contact recurs);
#: - ``"not_periodic"``: no contact recurred within the horizon: impulsive hits only,
#:   the slider is not driven;
#: - ``"failed"``: the vertical motion could not be computed (``message`` says why).
VerticalStatus = Literal["success", "not_periodic", "failed"]

#: How the rigid-limit periodic state ends:
#:
#: - ``"success"``: the fixed point of the slider's velocity map, to round-off;
#: - ``"no_contact"``: no finite-duration contact within the horizon (ϖ beyond the
#:   window: the model does not drive the slider).
RigidStatus = Literal["success", "no_contact"]

#: How settling from rest ends (its success word is ``"settled"``):
#:
#: - ``"settled"``: within ``rtol`` of the periodic Δs for the rest of the run;
#: - ``"not_settled"``: not within ``simulated_cycles`` (a lower bound on settling);
#: - ``"failed"``: the transient itself failed (``message`` says why).
SettlingStatus = Literal["settled", "not_settled", "failed"]


@dataclass(frozen=True, kw_only=True)
class SolverResult:
    """What every solver's answer carries (the fields every subclass shares).

    Attributes
    ----------
    status : str
        A word of the subclass's vocabulary (:attr:`STATUSES`, a ``Literal`` of this
        module with every word documented); any other word is refused on construction.
    message : str
        What happened; on a failure, what failed and what to try.
    n_cycles : int
        Actuation cycles computed [-].
    n_events : int
        Events located or applied (hits, phase switches, contact ends) [-].
    n_root_evals : int
        Evaluations of event functions by the certified root searches [-].
    elapsed_s : float
        Wall-clock time of the computation [s].

    A counter a solver does not keep stays 0.
    """

    #: the status words of this kind of answer
    STATUSES: ClassVar[tuple[str, ...]] = get_args(TrajectoryStatus)
    #: the status word that means success
    SUCCESS: ClassVar[str] = "success"

    status: str
    message: str
    n_cycles: int = 0
    n_events: int = 0
    n_root_evals: int = 0
    elapsed_s: float = 0.0

    def __post_init__(self) -> None:
        """Refuse a status outside :attr:`STATUSES`."""
        if self.status not in self.STATUSES:
            raise ValueError(
                f"{type(self).__name__}: status {self.status!r} is not one of {self.STATUSES}"
            )

    @property
    def success(self) -> bool:
        """True when ``status`` is this kind's success word (:attr:`SUCCESS`)."""
        return self.status == self.SUCCESS


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


@dataclass(frozen=True, kw_only=True)
class Trajectory(SolverResult):
    """A transient run of ``n_cycles`` actuation cycles from ``section[0]``.

    Time origin: every time of the exact solver (``section``, ``events``, ``phases``) is
    the kernel time τ_k = τ + δ/ϖ, where τ is the drive's phase time and δ =
    atan(2ζ_v·ϖ) the phase of the normal force N ∝ sin(ϖτ + δ) (docs/MODEL.md,
    "Damping"); without head damping δ = 0 and τ_k = τ. The drive-phase time is
    τ = τ_k − δ/ϖ.

    Attributes
    ----------
    params : ModelParams
        The model solved.
    solver : str
        "exact" or the reference method (e.g. "solve_ivp:DOP853/exact").
    status : TrajectoryStatus
        "success" or "failed" (:data:`TrajectoryStatus`); with the other fields of
        :class:`SolverResult` (``n_cycles``: cycles computed, those before a failure).
    s : float
        Final slider position [-, units of u·cosθ].
    delta_s : numpy.ndarray
        Per-cycle increments [-], length ``n_cycles``.
    section : numpy.ndarray
        States (ξ, ξ', ζ, ζ', s, s') [-] at τ = 2mπ/ϖ, m = 0..n_cycles, shape
        (n_cycles + 1, 6).
    events : list of Event
        The event log (empty when it was not kept).
    n_fev : int
        Right-hand-side evaluations [-] (reference solvers; 0 for the exact one).
    impacts_per_cycle : float
        Hits per cycle of the periodic vertical motion [-] (exact solver; NaN else).
    contact_fraction : float
        Fraction of the time in contact [-] (exact solver; NaN else).
    driven : bool or None
        True when contact recurs (the vertical motion is periodic with contacts), False
        when the hits are impulsive only within the horizon: the slider is not driven and
        the last Δs is coasting (exact solver; None for the reference solvers).
    phases : list of (float, float, str)
        (τ_start [-], τ_end [-], tangential phase) pieces of the exact solution, each one
        closed-form expression (filled when ``dense=True``).
    engine : str
        How the exact solver's one implementation ran: "compiled" (numba,
        :mod:`betvdesign.dynamics.contact`) or "python" (its source run uncompiled under
        ``NUMBA_DISABLE_JIT=1``).
    """

    STATUSES: ClassVar[tuple[str, ...]] = get_args(TrajectoryStatus)

    status: TrajectoryStatus
    params: ModelParams
    solver: str
    s: float
    delta_s: np.ndarray
    section: np.ndarray
    events: list[Event]
    n_fev: int = 0
    impacts_per_cycle: float = float("nan")
    contact_fraction: float = float("nan")
    driven: bool | None = None
    phases: list[tuple[float, float, str]] = field(default_factory=list, repr=False)
    engine: str = "python"
    _sampler: Callable[[np.ndarray], np.ndarray] | None = field(default=None, repr=False)

    def sample(self, tau: np.ndarray | float) -> np.ndarray:
        """Dense output: the states at the times τ.

        Parameters
        ----------
        tau : float or numpy.ndarray
            Times τ [-] within the simulated span.

        Returns
        -------
        numpy.ndarray
            States (ξ, ξ', ζ, ζ', s, s') [-], shape (n, 6).

        Raises
        ------
        ValueError
            Without dense output (run the solver with ``dense=True``), or for a τ outside
            the simulated span.
        """
        if self._sampler is None:
            raise ValueError("no dense output: run the solver with dense=True")
        t = np.atleast_1d(np.asarray(tau, dtype=float))
        return self._sampler(t)


@dataclass(frozen=True, kw_only=True)
class PeriodicResult(SolverResult):
    """The periodic state the slider settles to (MODEL.md "Slider").

    Only a "success" carries Δs and a mode; every field an answer does not have is None
    (a failure is built by :meth:`failure`).

    Attributes
    ----------
    params : ModelParams
        The model solved.
    status : PeriodicStatus
        "success", "unbounded", "not_converged", "not_driven" or "failed"
        (:data:`PeriodicStatus`); with the other fields of :class:`SolverResult`
        (``n_cycles``, ``n_events``: of the periodic map's iterations, transient and
        Newton included; ``n_root_evals``: those and the vertical motion's).
    delta_s : float or None
        Slider increment per actuation cycle on the orbit [-, units of u·cosθ] (the
        orbit's increment over ``period_cycles`` divided by it).
    mode : {"push", "pull", "stalled"} or None
        "push" (Δs > 0), "pull" (Δs < 0) or "stalled" (|Δs| at round-off;
        :func:`betvdesign.model.domain.mode_of`).
    period_cycles : int or None
        The orbit's period [cycles].
    residual : float or None
        Max-norm of (map(state) − state) [-] over the whole section state, slider position
        excepted (it drifts by design); with "not_converged", the best one reached.
    floquet : numpy.ndarray or None
        Multipliers of the section map (ζ, ζ', s'), complex, by decreasing modulus.
    stable : bool or None
        All |μ| < 1.
    state : numpy.ndarray or None
        Section state (ξ, ξ', ζ, ζ', s, s') [-] at τ = 2m*π/ϖ on the orbit (s = 0).
    impacts_per_cycle : float
        Hits per cycle of the periodic vertical motion [-] (NaN: not computed).
    contact_fraction : float
        Fraction of the time in contact [-] (NaN: not computed).
    n_newton : int
        Newton iterations [-].
    transient_cycles : int
        Cycles iterated from rest before the orbit was accepted [-].
    transient_s : float
        Slider position they reached [-, units of u·cosθ].
    """

    STATUSES: ClassVar[tuple[str, ...]] = get_args(PeriodicStatus)

    status: PeriodicStatus
    params: ModelParams
    delta_s: float | None = None
    mode: Mode | None = None
    period_cycles: int | None = None
    residual: float | None = None
    floquet: np.ndarray | None = None
    stable: bool | None = None
    state: np.ndarray | None = None
    impacts_per_cycle: float = float("nan")
    contact_fraction: float = float("nan")
    n_newton: int = 0
    transient_cycles: int = 0
    transient_s: float = 0.0

    @classmethod
    def failure(
        cls, params: ModelParams, status: PeriodicStatus, message: str, **fields: Any
    ) -> PeriodicResult:
        """The answer when no periodic orbit is accepted.

        Parameters
        ----------
        params : ModelParams
            The model solved.
        status : PeriodicStatus
            Any word of :data:`PeriodicStatus` but "success".
        message : str
            What failed and what to try.
        **fields
            Any other field of the result: the counters and ``elapsed_s`` [s] of
            :class:`SolverResult`, ``impacts_per_cycle``, ``contact_fraction``,
            ``n_newton``, ``transient_cycles``, ``transient_s``, ``residual``.

        Returns
        -------
        PeriodicResult
            Without Δs, mode, period, Floquet multipliers or state.
        """
        if status == cls.SUCCESS:
            raise ValueError("a failure needs a status other than 'success'")
        return cls(params=params, status=status, message=message, **fields)

    @property
    def floquet_moduli(self) -> list[float] | None:
        """|μ| of the Floquet multipliers, decreasing (JSON-friendly)."""
        if self.floquet is None:
            return None
        return [float(abs(m)) for m in self.floquet]
