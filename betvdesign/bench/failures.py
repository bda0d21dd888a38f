"""The failure map: where each method breaks, and what the exact solver does there.

Data, not prose: the methods report and the README render this table; each entry
names the test that reproduces the failure on purpose (tests/test_failure_*.py)
and asserts that the exact solver either handles it exactly or reports it.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any


@dataclass(frozen=True)
class Failure:
    """One failure mode: which methods, where, the symptom, our handling, the test."""

    id: str
    title: str
    methods: str
    where: str
    symptom: str
    ours: str
    test: str

    def as_dict(self) -> dict[str, Any]:
        return asdict(self)


FAILURES: tuple[Failure, ...] = (
    Failure(
        "grazing",
        "Missed impacts and late band exits near grazing",
        "fixed-step integration with events post-detected at step ends (rk4-post)",
        "ϖ → 2, where a contact lasts less than one step (0.2 % of the cycle at ϖ = 1.99)",
        "a contact that starts and ends inside one step is taken for an impulsive hit: "
        "the slider is not driven in that cycle; s drifts by percents",
        "contact end at (2j+1)π/ϖ in closed form, hits located with a certified "
        "derivative bound: exactly one contact per cycle, s to round-off",
        "tests/test_failure_grazing.py",
    ),
    Failure(
        "tanh-creep",
        "Chattering and creep with regularised friction",
        "friction sgn(v) → tanh(v/ε) (any integrator)",
        "every stick phase",
        "stick is never exact: the slider creeps at a small relative velocity, s is off "
        "by O(ε) (1e-2 relative at ε = 1e-2), and small ε makes the problem stiff",
        "stick is a phase of its own with ζ' = s' exactly, entered at located "
        "velocity-match events and left at band exits",
        "tests/test_failure_friction.py",
    ),
    Failure(
        "stiffness",
        "Stiffness as α → 0",
        "explicit integrators (RK45, DOP853, fixed-step RK4)",
        "small α: tangential frequency 1/√α",
        "step count of explicit methods grows like 1/√α; fixed-step RK4 blows up once h > 2.8√α",
        "closed-form flows have no stability limit; the result converges to the exact "
        "α → 0 rigid limit (betvdesign.dynamics.rigid); the fixed-step method reports "
        "status 'failed' instead of returning NaN",
        "tests/test_failure_stiffness.py",
    ),
    Failure(
        "resonance",
        "Resonances ϖ = 1 and a·ϖ² = 1",
        "closed forms dividing by 1 − ϖ² or 1 − aϖ², or nudging the parameter",
        "ϖ = 1 (vertical), a·ϖ² = 1 with a = α (free, slip) or α(1 + 1/β) (stick)",
        "0/0 at resonance, all digits lost next to it",
        "divided-difference forms that reduce exactly to the secular solutions: "
        "continuous across the resonance and equal to solve_ivp",
        "tests/test_failure_resonance.py",
    ),
    Failure(
        "early-stop",
        "Wrong mode from early stopping",
        "brute-force iteration stopped when two successive Δs agree to 1e-4",
        "slow or non-monotone settling, e.g. ϖ = 1.6, α = 0.1, β = 0.5, κ = 0.1",
        "stops after one cycle with Δs > 0 (push) while the periodic orbit is pull (Δs ≈ −7.7)",
        "periodic_orbit accepts only a fixed point of the whole section state to a "
        "residual ≤ 1e-10 (Newton shooting)",
        "tests/test_failure_early_stop.py",
    ),
    Failure(
        "growth",
        "Unbounded tangential growth",
        "any method that reports a Δs from a finite run",
        "a·ϖ² = 1 with little friction damping (e.g. α = 1/ϖ², ϖ = 1.2)",
        "ζ grows without bound; there is no periodic state, so any Δs is meaningless",
        "simulate follows the secular growth exactly (or fails loudly when the event "
        "search cannot terminate); periodic_orbit reports status 'unbounded' within a few "
        "hundred cycles (proven: ζ falls ≥ π(1 − ακ/2) per cycle when ακ < 2) with the "
        "measured rate and no mode; the design rule on tangential resonance flags the design",
        "tests/test_failure_growth.py",
    ),
)
