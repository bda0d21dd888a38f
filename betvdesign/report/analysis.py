"""The computations behind one actuator set's report: solver runs, small sweeps.

Unit-free except where explicitly suffixed (``_um``, ``_ms``, ``_v``...); the
dimensional conversion uses only the :class:`~betvdesign.nondim.device.Scales` of the
derivation (MODEL.md, "Displacement per cycle": x = s·u·cosθ, t = τ·sqrt(m/k_v)).

Model rungs, cheapest that answers each question (the captions say which):
- push/pull map: the λ fit only, no simulation;
- regime strip: the vertical-only model (the head's vertical motion does not
  depend on the slider), one call per ϖ;
- everything about the slider: the exact event-driven model
  (:func:`betvdesign.dynamics.simulate`, :func:`~betvdesign.dynamics.periodic_orbit`);
- speed against voltage: one periodic orbit. Every displacement of the model
  scales with u and ϖ, α, β, κ do not depend on u, so Δs is voltage-independent
  and speed(V) = Δs·u(V)·cosθ·f_act with u(V) from the amplitude calibration
  (times the thermal roll-off at f_act when the device gives a cut-off);
- speed against actuation frequency (devices with a thermal cut-off): one periodic
  orbit per frequency (:mod:`betvdesign.report.frequency`);
- a stroke predicted from the drawing: u(V) to the melting voltage and u(f), electrothermal
  solutions only, no orbit (:mod:`betvdesign.report.thermal`).

Each piece is a :class:`Piece`: its value, or the reason it is missing (upstream
API not available, solver failure with its message). Nothing is invented.
"""

from __future__ import annotations

import functools
import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Generic, TypeVar

import numpy as np

from betvdesign.errors import BetvError
from betvdesign.model.domain import VARPI_WINDOW, mode_of
from betvdesign.model.params import ModelParams

if TYPE_CHECKING:
    from betvdesign.dynamics import PeriodicResult, Trajectory, VerticalResult

T = TypeVar("T")
#: A solver result that says whether it succeeded (periodic orbit or transient run).
R = TypeVar("R", "PeriodicResult", "Trajectory")

#: Names of the contact phases used by the figures (plots.PHASE_COLORS keys).
PHASES = ("free", "slip", "reverse", "stick")

#: Titles of the figures drawn only with ``ReportOptions(full=True)`` (``betv report
#: --full``): the model's diagnostics, on which no verdict, mode, speed or margin rests.
FULL_ONLY = (
    "Push/pull map",
    "Vertical regime strip",
    "Vertical phase portrait of the head",
    "Slider velocity settling and periodic orbit",
)
#: Why a piece only the full report draws is not computed.
NOT_IN_SHORT = "drawn in the full report only (betv report --full)"


@dataclass(frozen=True)
class ReportOptions:
    """Sizes of the report's computations (kept small: a report takes seconds).

    regime_points: ϖ values of the vertical regime strip;
    regime_range: (ϖ_min, ϖ_max) of the strip, widened to include the device;
    robustness_points: values per designer field of the robustness sweep (relative
    changes spread evenly over ±robustness_span, one periodic orbit each);
    dense_cycles: cycles sampled densely for the velocity and phase portrait;
    samples_per_cycle: dense samples per actuation cycle, or per natural period 2π of
    the head (τ units) when ϖ < 1 makes a cycle hold several of them;
    max_transient_cycles: cap of the exact run used for the displacement figure;
    voltage_points: drive voltages of the speed-voltage figure (no solver runs);
    frequency_points: actuation frequencies of the speed-frequency figure of a device with
    a thermal cut-off (one periodic orbit each, :mod:`betvdesign.report.frequency`);
    map_points: values per field of the exact-mode map (:mod:`betvdesign.report.modemap`,
    over the same ±robustness_span; map_points² periodic orbits);
    periodic_tol: fixed-point residual accepted for a periodic orbit [-];
    periodic_max_cycles: cycle budget of the device's periodic orbit (settling can take
    ~10⁵ cycles, MODEL.md "Slider"); sweep_max_cycles: the same for each λ-sweep orbit;
    full: every figure, the model's diagnostics included (:data:`FULL_ONLY`: the push/pull
    map of the λ fit, the vertical regime strip, the head's vertical phase portrait, the
    slider's settling and its periodic orbit); False (the default of ``betv report``): the
    figures the design decision rests on (exact-mode map, displacement over the travel
    range, speed against voltage, robustness, model adequacy, speed against frequency),
    each the same drawing as in the full report.
    """

    regime_points: int = 111
    regime_range: tuple[float, float] = (0.2, 2.95)
    robustness_points: int = 7
    robustness_span: float = 0.3
    dense_cycles: int = 30
    samples_per_cycle: int = 64
    max_transient_cycles: int = 4000
    voltage_points: int = 41
    frequency_points: int = 21
    map_points: int = 15
    periodic_tol: float = 1e-10
    periodic_max_cycles: int = 100_000
    sweep_max_cycles: int = 20_000
    full: bool = False


@dataclass
class Piece(Generic[T]):
    """A computed value, or why there is none (``reason``)."""

    value: T | None = None
    reason: str | None = None
    elapsed_s: float = 0.0

    @property
    def ok(self) -> bool:
        return self.value is not None


class Missing(Exception):
    """A piece cannot be computed; the message goes into the report verbatim."""


def attempt(fn: Callable[[], T]) -> Piece[T]:
    """Run ``fn``; a :class:`Missing` or user-level error becomes a reason, not a crash."""
    t0 = time.perf_counter()
    try:
        value = fn()
    except Missing as exc:
        return Piece(reason=str(exc), elapsed_s=time.perf_counter() - t0)
    except (BetvError, ArithmeticError, ValueError, RuntimeError) as exc:
        return Piece(
            reason=f"computation failed: {type(exc).__name__}: {exc}",
            elapsed_s=time.perf_counter() - t0,
        )
    return Piece(value=value, elapsed_s=time.perf_counter() - t0)


def require_success(result: R, what: str) -> R:
    """``result`` if its ``success`` is true, else :class:`Missing` with its status/message."""
    if not result.success:
        message = result.message or "no message"
        raise Missing(f"{what} did not succeed (status {result.status}): {message}")
    return result


# --------------------------------------------------------------------------- data


@dataclass(frozen=True)
class RegimeData:
    """Vertical-only sweep over ϖ [-]: impact period [cycles] and contact fraction [-]."""

    varpi: np.ndarray
    period_cycles: list[float | None]
    contact_fraction: list[float | None]
    hits_per_cycle: list[float | None]
    labels: list[str]


@dataclass(frozen=True)
class TransientData:
    """The exact model run from rest (MODEL.md, "Initial state").

    Dense part (first cycles): t_cycles [cycles], states (n, 6) [-].
    Sections: s at τ = 2mπ/ϖ for m = 0..n_cycles [-]; delta_s per cycle [-].
    """

    t_cycles: np.ndarray
    states: np.ndarray
    section_s: np.ndarray
    delta_s: np.ndarray
    n_cycles: int
    counters: dict[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class OrbitData:
    """One period of the periodic orbit: ζ', s' [-] and the contact phase per sample."""

    dzeta: np.ndarray
    ds: np.ndarray
    phases: list[str]
    period_cycles: int


# --------------------------------------------------------------------------- pieces


def periodic(p: ModelParams, opts: ReportOptions) -> PeriodicResult:
    """The periodic orbit of the exact model at ``p`` (succeeded), else :class:`Missing`."""
    from betvdesign import dynamics  # the solver loads with the first solve

    res = dynamics.periodic_orbit(p, tol=opts.periodic_tol, max_cycles=opts.periodic_max_cycles)
    return require_success(res, "periodic_orbit")


#: Horizon [cycles] within which a contact must recur for the regime strip (beyond
#: it the ϖ is drawn as "aperiodic / not found").
REGIME_HORIZON = 200
#: Horizon [cycles] of the second look at a ϖ whose impulsive hits did not repeat within
#: REGIME_HORIZON (long transients next to a period doubling, e.g. ϖ ≈ 2.7).
REGIME_LONG_HORIZON = 2000


@functools.lru_cache(maxsize=4096)
def _vertical(
    varpi: float, zeta_v: float = 0.0, restitution: float = 0.0
) -> tuple[float | None, float | None, float | None, str]:
    """(impact period [cycles], contact fraction [-], hits per cycle, label) of the
    vertical-only model, classified by :func:`betvdesign.studies.regime.regime_point` (the
    one classification: impulsive-only motion that repeats every k cycles has period k, not
    "aperiodic"); period None only where no period is found within the horizon."""
    from betvdesign.studies.regime import LONG_PERIOD, regime_point

    task = {"key": 0, "varpi": varpi, "zeta_v": zeta_v, "restitution": restitution}
    row = regime_point({**task, "max_cycles": REGIME_HORIZON})
    if row["period_cycles"] is None and row["label"] == "aperiodic":
        # near a period doubling the transient outlasts the short horizon: look longer
        row = regime_point({**task, "max_cycles": REGIME_LONG_HORIZON})
    k = row["period_cycles"]
    if k is not None and k > LONG_PERIOD:  # shown as aperiodic, as in the regime study
        k = None
    if row["status"] == "error":
        return None, None, None, str(row["label"])
    return (
        None if k is None else float(k),
        None if k is None else float(row["contact_fraction"]),
        None if row["hits_per_cycle"] is None else float(row["hits_per_cycle"]),
        str(row["label"]),
    )


def vertical(p: ModelParams) -> VerticalResult:
    """The exact vertical motion at the device's ϖ, ζ_v, e (full default horizon)."""
    from betvdesign import dynamics  # the solver loads with the first solve

    return dynamics.vertical_motion(p.varpi, zeta_v=p.zeta_v, restitution=p.restitution)


def regime_strip(p: ModelParams, opts: ReportOptions) -> RegimeData:
    """Vertical-only sweep of ϖ over the options' range widened to the device's ϖ, with
    its ζ_v and e (results cached per point: the strip is shared by the devices of a run)."""
    varpi_device = p.varpi
    lo = min(opts.regime_range[0], 0.8 * varpi_device)
    hi = max(opts.regime_range[1], 1.15 * varpi_device, VARPI_WINDOW[1] * 1.2)
    grid = np.linspace(lo, hi, opts.regime_points)
    rows = [_vertical(float(w), p.zeta_v, p.restitution) for w in grid]
    return RegimeData(
        grid,
        [r[0] for r in rows],
        [r[1] for r in rows],
        [r[2] for r in rows],
        [r[3] for r in rows],
    )


def samples_per_cycle(p: ModelParams, opts: ReportOptions) -> int:
    """Dense samples per actuation cycle: the options' count per cycle or per natural
    period of the head (a cycle spans 1/ϖ of those), whichever is more."""
    return math.ceil(opts.samples_per_cycle * max(1.0, 1.0 / p.varpi))


def transient(p: ModelParams, n_cycles: int, opts: ReportOptions) -> TransientData:
    """Exact run from rest: dense over the first cycles, sections over ``n_cycles``."""
    from betvdesign import dynamics  # the solver loads with the first solve

    simulate = dynamics.simulate
    dense_n = min(opts.dense_cycles, n_cycles)
    head = require_success(simulate(p, dense_n, dense=True), "simulate (dense)")
    period = 2.0 * math.pi / p.varpi
    t_cycles = np.linspace(0.0, dense_n, dense_n * samples_per_cycle(p, opts) + 1)
    states = np.asarray(head.sample(t_cycles * period), dtype=float)
    full = head if n_cycles == dense_n else require_success(simulate(p, n_cycles), "simulate")
    section = np.asarray(full.section, dtype=float)
    delta_s = np.asarray(full.delta_s, dtype=float)
    if not (np.all(np.isfinite(states)) and np.all(np.isfinite(section))):
        raise Missing("simulate returned non-finite states")
    counters = {
        "n_events": full.n_events,
        "n_cycles": full.n_cycles,
        "n_root_evals": full.n_root_evals,
    }
    return TransientData(t_cycles, states, section[:, 4], delta_s, n_cycles, counters)


def _phase_name(raw: str) -> str:
    """Map a solver phase label to one of :data:`PHASES`."""
    text = raw.lower()
    if "rev" in text:
        return "reverse"
    if "stick" in text:
        return "stick"
    if "slip" in text:
        return "slip"
    return "free"


def orbit(p: ModelParams, per: PeriodicResult, opts: ReportOptions) -> OrbitData:
    """Sample one period of the periodic orbit with its contact phases."""
    from betvdesign import dynamics  # the solver loads with the first solve

    simulate = dynamics.simulate
    n = per.period_cycles if per.period_cycles is not None else 1
    state0 = np.asarray(per.state, dtype=float)
    traj = require_success(simulate(p, n, dense=True, state0=state0), "simulate (orbit)")
    period = 2.0 * math.pi / p.varpi
    tau = np.linspace(0.0, n * period, n * samples_per_cycle(p, opts) * 2 + 1)
    states = np.asarray(traj.sample(tau), dtype=float)
    events = sorted(traj.events, key=lambda e: e.tau)
    phases: list[str] = []
    j = 0
    current = _phase_name(events[0].phase_before) if events else "free"
    for t in tau:
        while j < len(events) and events[j].tau <= t:
            current = _phase_name(events[j].phase_after)
            j += 1
        phases.append(current)
    return OrbitData(states[:, 3], states[:, 5], phases, n)


@dataclass(frozen=True)
class FieldVariant:
    """The device with one designer field changed by a relative amount.

    field: dotted spec path ("drive.frequency"); nominal: its value as the file gives it;
    change: relative change [-]; params: the model parameters of the changed device
    (None when the spec rejects the value: ``reason``); speed_per_ds: ℓ·f_act [m/s per
    unit Δs] of the changed device (MODEL.md, "Displacement per cycle").
    """

    field: str
    nominal: str
    change: float
    params: ModelParams | None
    speed_per_ds: float = math.nan
    reason: str = ""


@dataclass(frozen=True)
class FieldPoint:
    """One point of the robustness sweep: speed [m/s] along the impact direction (None: no
    periodic orbit, ``reason``) and λ of the changed device."""

    field: str
    nominal: str
    change: float
    speed_m_s: float | None
    lam: float | None
    reason: str = ""
    mode: str | None = None


@dataclass(frozen=True)
class FieldFlip:
    """A change of the exact mode along one designer field: between the relative
    changes ``lo`` and ``hi`` [-] (bisected) the mode goes from ``below`` to ``above``."""

    field: str
    lo: float
    hi: float
    below: str
    above: str

    @property
    def at(self) -> float:
        """The flip's relative change [-] (the bracket's middle)."""
        return 0.5 * (self.lo + self.hi)


@dataclass(frozen=True)
class FieldSweep:
    """Periodic speed as each designer field varies around the device (others fixed);
    ``flips``: where the exact mode changes, bisected (:mod:`betvdesign.report.variants`)."""

    points: list[FieldPoint]
    n_orbits: int
    flips: tuple[FieldFlip, ...] = ()

    @property
    def fields(self) -> list[str]:
        return list(dict.fromkeys(p.field for p in self.points))

    @property
    def failures(self) -> list[str]:
        return [
            f"{p.field} {p.change:+.0%}: {p.reason}" for p in self.points if p.speed_m_s is None
        ]


def robustness(variants: list[FieldVariant], opts: ReportOptions) -> FieldSweep:
    """Periodic speed of every variant (one periodic orbit per distinct parameter set)."""
    if not variants:
        raise Missing("the device has none of the designer fields the sweep varies")
    from betvdesign import dynamics  # the solver loads with the first solve

    periodic_orbit = dynamics.periodic_orbit
    solved: dict[ModelParams, PeriodicResult] = {}
    points: list[FieldPoint] = []
    for v in variants:
        if v.params is None:
            points.append(FieldPoint(v.field, v.nominal, v.change, None, None, v.reason))
            continue
        if v.params not in solved:
            solved[v.params] = periodic_orbit(
                v.params, tol=opts.periodic_tol, max_cycles=opts.sweep_max_cycles
            )
        res = solved[v.params]
        if res.success and res.delta_s is not None:
            speed = float(res.delta_s) * v.speed_per_ds
            points.append(
                FieldPoint(
                    v.field, v.nominal, v.change, speed, v.params.lam, mode=mode_of(res.delta_s)
                )
            )
        else:
            why = f"{res.status}: {res.message}"
            points.append(FieldPoint(v.field, v.nominal, v.change, None, v.params.lam, why))
    return FieldSweep(points, len(solved))


# --------------------------------------------------------------------------- one set


@dataclass
class SetAnalysis:
    """Every computed piece for one actuator set (see the module docstring)."""

    params: ModelParams
    periodic: Piece[PeriodicResult]
    vertical: Piece[VerticalResult]
    regime: Piece[RegimeData]
    transient: Piece[TransientData]
    orbit: Piece[OrbitData]
    robustness: Piece[FieldSweep]
    frequency: Piece[Any] = field(
        default_factory=lambda: Piece(reason="not computed (a set with the same parameters)")
    )
    mode_map: Piece[Any] = field(
        default_factory=lambda: Piece(reason="not computed (a set with the same parameters)")
    )
    #: The predicted stroke's u(V) and u(f) (:mod:`betvdesign.report.thermal`; sets whose
    #: stroke is predicted from the drawing).
    stroke: Piece[Any] = field(
        default_factory=lambda: Piece(reason="the stroke is not predicted from the drawing")
    )


def transient_cycles(
    per: Piece[PeriodicResult], travel_m: float, length_m: float, opts: ReportOptions
) -> int:
    """Cycles of the exact run: enough to cross the travel range at the periodic
    speed (+10 %), at least the dense cycles, at most the options' cap."""
    ds = per.value.delta_s if per.value is not None else None
    if ds is None or ds == 0.0:
        return opts.max_transient_cycles
    per_cycle_m = abs(float(ds)) * length_m
    n_cross = math.ceil(1.1 * travel_m / per_cycle_m)
    return int(min(max(n_cross, opts.dense_cycles), opts.max_transient_cycles))


def analyse_set(
    p: ModelParams,
    travel_m: float,
    length_m: float,
    opts: ReportOptions,
    variants: list[FieldVariant] | None = None,
) -> SetAnalysis:
    """Run every computation of one set's report (seconds, not minutes); ``variants``:
    the device with designer fields changed (:mod:`betvdesign.report.variants`)."""
    per = attempt(lambda: periodic(p, opts))
    n = transient_cycles(per, travel_m, length_m, opts)
    orb: Piece[OrbitData] = (
        Piece(reason=NOT_IN_SHORT)
        if not opts.full
        else attempt(lambda: orbit(p, per.value, opts))
        if per.ok
        else Piece(reason=f"no periodic orbit: {per.reason}")
    )
    return SetAnalysis(
        params=p,
        periodic=per,
        vertical=attempt(lambda: vertical(p)),
        regime=attempt(lambda: regime_strip(p, opts)) if opts.full else Piece(reason=NOT_IN_SHORT),
        transient=attempt(lambda: transient(p, n, opts)),
        orbit=orb,
        robustness=attempt(lambda: robustness(variants or [], opts)),
    )
