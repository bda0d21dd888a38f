"""Unit-free dynamics of the BETV impact/stick-slip model (docs/MODEL.md).

- :func:`simulate`: exact event-driven transient (:mod:`solver`).
- :func:`periodic_orbit`: periodic state by Newton shooting (:mod:`periodic`).
- :func:`vertical_motion`: vertical-only fast path (:mod:`vertical`).
- :mod:`reference`: the same model with scipy ``solve_ivp`` and its own switching rules
  (cross-checks, studies); it shares no code with the exact solver.
- :mod:`coupled`: the coupled head (symmetric 2×2 stiffness, MODEL.md "Coupled head"),
  exact and compiled: each phase's flow exp(A·δ) on the state augmented with the forcing,
  events refined on the exact flow; its stable periodic orbit (``coupled_orbit``); at
  ρ = 0 the exact decoupled solver's answers unchanged.
- :mod:`coupled_reference`: the same coupled model with scipy ``solve_ivp``, written from
  MODEL.md alone (the tests' truth, the benchmark's baseline).
- :mod:`result`: what every answer carries (:class:`SolverResult`: ``status`` from a
  documented vocabulary per kind of answer, ``success``, ``message``, counters,
  ``elapsed_s``); a cycle that cannot be advanced raises :class:`solver.CycleFailure`
  inside the solvers, which turn it into a "failed" answer.

Where each piece of MODEL.md lives (one function each; all compiled by numba, one
implementation, the same source runs as Python under ``NUMBA_DISABLE_JIT=1``):

==============================================  ========================================
MODEL.md                                        function
==============================================  ========================================
no contact, ξ'' + ξ = −sin ϖτ                   :func:`flows.vertical_flight`
no contact, α ζ'' + ζ = sin ϖτ, s'' = 0          :func:`flows.free_flight`
slip / reverse slip (ζ' ≷ s')                    :func:`flows.slip_flow`
stick, α(1 + 1/β) ζ'' + ζ = sin ϖτ, s'' = ζ''    :func:`flows.stick_flow`
closed form of y'' + w0² y = F sin ϖτ            :func:`flows.oscillator` (resonance exact)
s'' = ds sin ϖτ                                  :func:`flows.slider`
common velocity on entering stick                :func:`flows.stick_velocity`
stick / slip / reverse-slip rule (band b)        :func:`contact.decide_phase`
plastic hit ξ' → 0                               :func:`schedule.plastic_hit`
contact while sin ϖτ ≥ 0, ends at (2j+1)π/ϖ;     :func:`schedule.vertical_run`
impulsive hits when sin ϖτ < 0
event functions (hit, ζ' = s', band exits)       :mod:`evaluators` (values: :mod:`values`)
first event of a phase, certified                :func:`search.first_root`
cycles of contact and free flight; Δs_m          :func:`contact.run_cycles`
periodic orbit, Floquet multipliers              :func:`periodic.periodic_orbit`
                                                 (compiled: :func:`shooting.orbit`)
unbounded growth at α·ϖ² = 1                     :func:`periodic.resonance_growth_bound`
*Beyond the paper* (docs/damping.md)
kernel time: N ∝ A sin ϖτ, δ = atan(2ζ_v ϖ)        :func:`flows.normal_force_phase`
damped phases, y'' + 2g y' + w0² y = F sin + G cos  :func:`flows.forced` (table:
                                                 :func:`flows.phase_table`, ``damped``)
damped event functions, stick band with damper   :mod:`evaluators`, general form (values:
                                                 :mod:`values`)
damped stick / slip rule                         :func:`contact.decide_phase`
restitution ξ' → −e ξ'                           :func:`schedule.rebound`
chattering accumulation (Budd & Dux)             :func:`schedule.accumulation`
==============================================  ========================================
"""

from betvdesign.dynamics.periodic import periodic_orbit
from betvdesign.dynamics.result import Event, PeriodicResult, SolverResult, Trajectory
from betvdesign.dynamics.solver import simulate
from betvdesign.dynamics.vertical import VerticalResult, vertical_motion

__all__ = [
    "Event",
    "PeriodicResult",
    "SolverResult",
    "Trajectory",
    "VerticalResult",
    "periodic_orbit",
    "simulate",
    "vertical_motion",
]
