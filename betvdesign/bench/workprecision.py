"""Work-precision study: error against CPU time for the exact solver and its alternatives.

Designs (:data:`DESIGNS`): push, pull, near λ = 1, small α, near grazing ϖ → 2.
Methods: ``exact`` (betvdesign.dynamics.simulate), ``solve_ivp`` with event location
(RK45, DOP853, Radau, LSODA) at several rtol, regularised friction tanh(v/ε) at
several ε (through ``betvdesign.dynamics.reference``), and ``rk4-post`` (fixed-step
RK4 with event post-detection, :mod:`betvdesign.bench.fixedstep`).

Two errors, both relative, both against the exact solver as reference:

* ``s_N``: slider position after N cycles from rest (MODEL.md "Initial state");
* ``delta_s``: displacement per cycle averaged over K cycles started on the exact
  periodic orbit (every method gets the same, favourable start: no settling cost is
  charged to the alternatives).

The exact solver's own rows cannot be measured against itself: their error is its
distance to the most accurate independent solution (DOP853, rtol 1e-13, exact
events), i.e. an upper bound valid as long as that solution is the better of the
two. CPU time is ``time.process_time`` (min over repeats for runs under 0.2 s).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import asdict, dataclass
from typing import Any, Literal

import numpy as np

from betvdesign.model.params import ModelParams
from betvdesign.output.numbers import json_float

Level = Literal["quick", "full"]


@dataclass(frozen=True)
class Design:
    """A representative design of the study and why it is there."""

    name: str
    params: ModelParams
    why: str


DESIGNS: dict[str, Design] = {
    d.name: d
    for d in (
        Design("push", ModelParams(1.5, 2.0, 0.5, 0.1), "push mode, λ well below 1"),
        Design("pull", ModelParams(0.9, 0.1, 0.9, 0.4), "published fit (pull), λ ≈ 12"),
        Design("near-lambda-1", ModelParams(1.2, 0.66, 1.0, 0.4), "λ ≈ 1.05: mode boundary"),
        Design("small-alpha", ModelParams(1.2, 0.01, 0.5, 0.4), "α = 0.01: stiff tangential"),
        Design("near-grazing", ModelParams(1.97, 1.0, 0.5, 0.1), "ϖ → 2: contact ~1% of cycle"),
    )
}


@dataclass
class RunOut:
    """What one method run returns: s over the cycles (section values) and its status."""

    s_section: np.ndarray
    status: str
    message: str


#: One method run: (parameters, cycles, start state or None) -> :class:`RunOut`.
Runner = Callable[[ModelParams, int, Any], RunOut]


@dataclass(frozen=True)
class Method:
    """One method at one setting; ``run(p, cycles, state0)`` -> :class:`RunOut`."""

    method: str
    setting: str
    run: Runner


@dataclass
class Row:
    """One measurement: the ``betv bench --json`` row (plus metric and message)."""

    method: str
    setting: str
    design: str
    metric: str
    error: float | None
    seconds: float
    status: str
    message: str

    def as_dict(self) -> dict[str, Any]:
        """JSON-safe: non-finite numbers become None."""
        d = asdict(self)
        for k in ("error", "seconds"):
            d[k] = json_float(d[k])
        return d


# ---------------------------------------------------------------- method adapters
def run_exact(p: ModelParams, cycles: int, state0: Any) -> RunOut:
    """The exact solver's run (:func:`betvdesign.dynamics.simulate`, no event log).

    Parameters
    ----------
    p
        Model parameters (ϖ, α, β, κ and the optional terms) [-].
    cycles
        Actuation cycles to run.
    state0
        Section state (ξ, ξ', ζ, ζ', s, s') [-] to start from; None: from rest.

    Returns
    -------
    RunOut
        Slider position s [-] at every section, status and message.
    """
    from betvdesign.dynamics import simulate

    tr = simulate(p, cycles, state0=state0, log_events=False)
    return RunOut(tr.section[:, 4], tr.status, tr.message)


def reference_runner(method: str, rtol: float, friction: str, eps: float | None) -> Runner:
    """A run of the ``solve_ivp`` reference (:mod:`betvdesign.dynamics.reference`).

    Parameters
    ----------
    method
        ``solve_ivp`` method ("RK45", "DOP853", "Radau", "LSODA").
    rtol
        Relative tolerance [-] (absolute tolerance: ``rtol`` × 10⁻²).
    friction
        "exact" (event-located switching) or "tanh" (regularised friction).
    eps
        Regularisation width ε [-] of tanh(v/ε); None: the reference's default.

    Returns
    -------
    Runner
        ``run(p, cycles, state0) -> RunOut``, as :func:`run_exact`.
    """

    def run(p: ModelParams, cycles: int, state0: Any) -> RunOut:
        from betvdesign.dynamics import reference

        kw = {"eps": eps} if eps is not None else {}
        tr = reference.simulate(
            p,
            cycles,
            method=method,
            rtol=rtol,
            atol=rtol * 1e-2,
            friction=friction,
            state0=state0,
            **kw,
        )
        return RunOut(tr.section[:, 4], tr.status, tr.message)

    return run


def rk4_runner(steps: int) -> Runner:
    """A run of fixed-step RK4 with event post-detection (:mod:`betvdesign.bench.fixedstep`).

    Parameters
    ----------
    steps
        Steps per actuation cycle (h = T/steps).

    Returns
    -------
    Runner
        ``run(p, cycles, state0) -> RunOut``, as :func:`run_exact`.
    """

    def run(p: ModelParams, cycles: int, state0: Any) -> RunOut:
        from betvdesign.bench.fixedstep import rk4_post

        r = rk4_post(p, cycles, steps, state0=state0)
        return RunOut(r.section[:, 4], r.status, r.message)

    return run


#: Independent method used to bound the exact solver's own error.
BEST_INDEPENDENT = ("DOP853", 1e-13)


def methods(level: Level = "quick") -> list[Method]:
    """Methods and settings of a run; "quick" is a small subset (seconds)."""
    out = [Method("exact", "closed-form events", run_exact)]
    if level == "quick":
        rtols = {"RK45": [1e-6], "DOP853": [1e-8, 1e-11], "Radau": [1e-6], "LSODA": [1e-6]}
        epss = [1e-3]
        steps = [200]
    else:
        rtols = {
            "RK45": [1e-4, 1e-6, 1e-8, 1e-10],
            "DOP853": [1e-4, 1e-6, 1e-8, 1e-10, 1e-12],
            "Radau": [1e-4, 1e-6, 1e-8, 1e-10],
            "LSODA": [1e-4, 1e-6, 1e-8, 1e-10],
        }
        epss = [1e-2, 1e-3, 1e-4, 1e-5]
        steps = [100, 300, 1000, 3000]
    for name, tols in rtols.items():
        for rt in tols:
            out.append(
                Method(
                    f"solve_ivp-{name}", f"rtol={rt:.0e}", reference_runner(name, rt, "exact", None)
                )
            )
    for eps in epss:
        out.append(
            Method("tanh-LSODA", f"eps={eps:.0e}", reference_runner("LSODA", 1e-10, "tanh", eps))
        )
    for n in steps:
        out.append(Method("rk4-post", f"h=T/{n}", rk4_runner(n)))
    return out


# ---------------------------------------------------------------- measurement
def _timed(fn: Callable[[], RunOut], budget: float = 0.2, repeats: int = 5) -> tuple[RunOut, float]:
    """Run ``fn``; repeat short runs and keep the minimum CPU time [s]."""
    best = math.inf
    out = None
    spent = 0.0
    for _ in range(repeats):
        t0 = time.process_time()
        out = fn()
        dt = time.process_time() - t0
        best = min(best, dt)
        spent += dt
        if spent >= budget:
            break
    assert out is not None
    return out, best


def _rel(x: float, ref: float) -> float | None:
    if not math.isfinite(x):
        return None
    return abs(x - ref) / max(abs(ref), 1e-300)


@dataclass
class Case:
    """Reference data of one design: s_N from rest, the periodic state and Δs."""

    design: Design
    cycles: int
    s_ref: float
    orbit_state: np.ndarray | None
    orbit_cycles: int
    delta_ref: float | None


def prepare(design: Design, cycles: int, orbit_repeats: int) -> Case:
    """Exact references: s after ``cycles`` from rest, periodic orbit state and Δs."""
    from betvdesign.dynamics import periodic_orbit, simulate

    tr = simulate(design.params, cycles, log_events=False)
    po = periodic_orbit(design.params)
    state = None
    k = 0
    delta = None
    if po.success and po.state is not None:
        state = np.asarray(po.state, dtype=float)
        k = int(po.period_cycles or 1) * orbit_repeats
        delta = float(po.delta_s)
    return Case(design, cycles, tr.s, state, k, delta)


def measure(case: Case, m: Method) -> list[Row]:
    """Both metrics of one method on one design."""
    p, name = case.design.params, case.design.name
    rows = []
    out, sec = _guarded(lambda: m.run(p, case.cycles, None))
    err = None
    if out.status == "success" and len(out.s_section) == case.cycles + 1:
        err = _rel(float(out.s_section[-1]), case.s_ref)
    rows.append(Row(m.method, m.setting, name, "s_N", err, sec, out.status, out.message))
    if case.orbit_state is not None and case.delta_ref is not None:
        k = case.orbit_cycles
        out, sec = _guarded(lambda: m.run(p, k, case.orbit_state))
        err = None
        if out.status == "success" and len(out.s_section) == k + 1:
            err = _rel(float(out.s_section[-1] - out.s_section[0]) / k, case.delta_ref)
        rows.append(Row(m.method, m.setting, name, "delta_s", err, sec, out.status, out.message))
    return rows


def _guarded(fn: Callable[[], RunOut]) -> tuple[RunOut, float]:
    try:
        return _timed(fn)
    except Exception as exc:  # a method that crashes is a measured outcome, not a bench crash
        return RunOut(np.zeros(0), "failed", f"{type(exc).__name__}: {exc}"), math.nan


def bound_exact_error(rows: list[Row], cases: Sequence[Case]) -> None:
    """Set the exact rows' error to the distance to :data:`BEST_INDEPENDENT` (in place)."""
    best = Method(
        f"solve_ivp-{BEST_INDEPENDENT[0]}",
        f"rtol={BEST_INDEPENDENT[1]:.0e}",
        reference_runner(BEST_INDEPENDENT[0], BEST_INDEPENDENT[1], "exact", None),
    )
    for case in cases:
        indep = {r.metric: r for r in measure(case, best)}
        for r in rows:
            if r.method == "exact" and r.design == case.design.name and r.metric in indep:
                e = indep[r.metric].error
                r.error = e
                r.message += f"; error bounded by distance to {best.method} {best.setting}"


def run(
    level: Level = "quick",
    *,
    designs: Iterable[str] | None = None,
    only: Iterable[str] | None = None,
    progress: Callable[[str], None] | None = None,
) -> list[Row]:
    """Run the study; ``only`` filters methods by name (e.g. {"exact", "rk4-post"})."""
    cycles, repeats = (10, 2) if level == "quick" else (50, 5)
    names = list(designs) if designs is not None else list(DESIGNS)
    ms = [m for m in methods(level) if only is None or m.method in set(only)]
    cases = [prepare(DESIGNS[n], cycles, repeats) for n in names]
    rows: list[Row] = []
    for case in cases:
        for m in ms:
            if progress:
                progress(f"{case.design.name}: {m.method} {m.setting}")
            rows.extend(measure(case, m))
    if any(m.method == "exact" for m in ms):
        bound_exact_error(rows, cases)
    return rows


def summarise(rows: Sequence[Row], target: float = 1e-6) -> list[dict[str, Any]]:
    """Per design and metric: exact's error and time, the cheapest alternative whose
    error ≤ ``target`` and the cost ratio (alternative seconds / exact seconds)."""
    out = []
    keys = sorted({(r.design, r.metric) for r in rows})
    for design, metric in keys:
        sel = [r for r in rows if r.design == design and r.metric == metric]
        ex = next((r for r in sel if r.method == "exact"), None)
        alts = [
            r
            for r in sel
            if r.method != "exact"
            and r.error is not None
            and r.error <= target
            and r.status == "success"
        ]
        cheapest = min(alts, key=lambda r: r.seconds) if alts else None
        out.append(
            {
                "design": design,
                "metric": metric,
                "exact_error": ex.error if ex else None,
                "exact_seconds": ex.seconds if ex else None,
                "cheapest_alternative": f"{cheapest.method} {cheapest.setting}"
                if cheapest
                else None,
                "alternative_error": cheapest.error if cheapest else None,
                "alternative_seconds": cheapest.seconds if cheapest else None,
                "ratio": (cheapest.seconds / ex.seconds)
                if (cheapest and ex and ex.seconds)
                else None,
            }
        )
    return out
