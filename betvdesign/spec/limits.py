"""Input limits: the one home of every bound the toolkit enforces on what it is given.

A design tool runs in CI pipelines and on files from colleagues and foundries, so
it bounds its work before the work grows: a device file is refused before it is
parsed when it is too large, before it is composed when its YAML nests too deep,
expands too far through aliases, holds an over-long string or a number of too many
digits, and before it is validated when it has too many actuator sets; a study is
refused before it starts when it would not finish in reasonable time. Every refusal
names the field (or option) and the limit. README ("Limits") and ``betv schema``
(``x-betv-limits``) list these values; :func:`describe` is what both show.

Nothing here imports from the rest of the package except :mod:`betvdesign.errors`.
"""

from __future__ import annotations

import os
from typing import Any

from betvdesign.errors import UsageError

#: Environment variable that raises (or lowers) :data:`MAX_FILE_BYTES`.
FILE_BYTES_ENV = "BETV_MAX_FILE_BYTES"
#: Largest device or tolerance file read [bytes] (a shipped device file is ~2 kB).
MAX_FILE_BYTES = 1_000_000
#: Deepest YAML nesting of mappings and sequences (a device file nests 6 deep).
MAX_YAML_DEPTH = 32
#: Most YAML nodes a file may hold once aliases are expanded (a device file has ~150).
MAX_YAML_NODES = 20_000
#: Longest string (YAML scalar) [characters]; also bounds a description.
MAX_STRING_CHARS = 10_000
#: Longest name (device, actuator set, material) [characters].
MAX_NAME_CHARS = 200
#: Most actuator sets in one device (a bidirectional device has 2).
MAX_ACTUATOR_SETS = 64
#: Most measured calibration points of one actuator.
MAX_CALIBRATION_POINTS = 1_000
#: Longest quantity string such as "2330 kg/m^3" [characters].
MAX_QUANTITY_CHARS = 100
#: Most digits of a number written in a file or an option (a YAML integer or float, the
#: number of a quantity string): far below Python's 4300-digit limit of ``int()``.
MAX_NUMBER_DIGITS = 100
#: Largest |exponent| of a unit in a quantity string (m^3, V^-2, ...).
MAX_UNIT_EXPONENT = 12
#: Most unit factors in one quantity string ("kg/m^3" has 2).
MAX_UNIT_FACTORS = 8
#: Parallel slider beams (a BETV slider has 2; more than 16 is not a slider).
MAX_BEAM_COUNT = 16
#: Range of every quantity a device or process file gives, by the unit its field is
#: checked in [magnitude in that unit, both ends inclusive]; 0 stays allowed where the
#: field allows 0 (a calibration point at 0 V). Each range reaches at least six decades
#: beyond any MEMS device either way, and inside it every value the derivation forms
#: from the inputs (products and quotients of at most ~10 of them: ρ·L·w·t,
#: E·w·t³/L³, m·(2π·f)²) stays far inside float64's normal range (1e-308 to 1e308): a
#: subnormal input (5e-324 V) or an overflowing one (1e300 m) would turn a derived value
#: into 0, inf or a division by zero, where the model's arithmetic means nothing.
QUANTITY_RANGE: dict[str, tuple[float, float, str]] = {
    "m": (1e-12, 1.0, "a length"),
    "kg": (1e-24, 1.0, "a mass"),
    "Hz": (1e-3, 1e12, "a frequency"),
    "s": (1e-12, 1e3, "a duration"),
    "V": (1e-6, 1e6, "a voltage"),
    "kg/m**3": (1.0, 1e5, "a density"),
    "N/m": (1e-9, 1e9, "a stiffness"),
    "Pa": (1e3, 1e13, "a Young's modulus"),
    "deg": (1e-6, 90.0 - 1e-6, "an angle"),
    "m/V": (1e-18, 1.0, "a calibration gain"),
    "m/V**2": (1e-18, 1.0, "a calibration gain"),
    # the process's electrothermal data (a drawn stroke, issue 31)
    "K": (1.0, 1e4, "an absolute temperature"),
    "1/K": (1e-9, 1.0, "a coefficient per kelvin (its magnitude)"),
    "W/m/K": (1e-4, 1e4, "a thermal conductivity"),
    "J/kg/K": (1.0, 1e5, "a specific heat"),
    "ohm": (1e-6, 1e9, "a (sheet) resistance"),
}
#: Smallest dry-friction coefficient μ [-] (polysilicon on polysilicon ≈ 0.4): with the
#: smallest impact angle it keeps κ = μ·tanθ ≥ 1e-14, far from an underflow.
MIN_FRICTION = 1e-6
#: Cycles of one transient (``simulate --cycles``) and cycle budget of a periodic solve.
MAX_CYCLES = 1_000_000
#: Monte Carlo samples of one tolerance study.
MAX_SAMPLES = 1_000_000
#: Points of one study (grid points, or samples × sets).
MAX_STUDY_POINTS = 10_000_000
#: Worker processes of one study.
MAX_WORKERS = 1_024
#: Points per chunk sent to a worker.
MAX_CHUNKSIZE = 100_000
#: numpy's ``SeedSequence`` takes any integer 0 <= seed < 2**128 here.
SEED_BOUND = 2**128
#: Environment variable that raises (or lowers) :data:`MAX_STUDY_HOURS`.
STUDY_HOURS_ENV = "BETV_MAX_STUDY_HOURS"
#: Estimated wall time above which a study is refused up front [h].
MAX_STUDY_HOURS = 12.0
#: Conservative cost of one study point by what it solves [s on one core] (the
#: benchmarks give a periodic-orbit median of ~1.2 ms; tails and loading are added).
POINT_COST_S = {"periodic": 5e-3, "lambda": 2e-4, "regime": 5e-3, "tolerance": 6e-3}
#: Horizon [cycles] the regime cost above is quoted for.
REGIME_CYCLES = 400


def point_cost_s(study: str, parameters: dict[str, Any]) -> float:
    """Conservative cost of one point of a study, for estimates.

    Parameters
    ----------
    study : str
        ``"regime"``, ``"tolerance"``, or a periodic-orbit study.
    parameters : dict
        The study's parameters (``fidelity``, ``max_cycles``).

    Returns
    -------
    float
        Cost of one point [s on one core] (:data:`POINT_COST_S`; a regime point scaled
        by its cycles over :data:`REGIME_CYCLES`).
    """
    fidelity = parameters.get("fidelity")
    if study == "regime":
        cycles = parameters.get("max_cycles") or REGIME_CYCLES
        return POINT_COST_S["regime"] * max(1.0, cycles / REGIME_CYCLES)
    if fidelity == "lambda":
        return POINT_COST_S["lambda"]
    return POINT_COST_S["tolerance" if study == "tolerance" else "periodic"]


def max_file_bytes() -> int:
    """The largest input file read.

    Returns
    -------
    int
        :data:`MAX_FILE_BYTES` [bytes], or the value of ``$BETV_MAX_FILE_BYTES`` when set.

    Raises
    ------
    UsageError
        The variable is not a finite number > 0.
    """
    return _env_number(FILE_BYTES_ENV, MAX_FILE_BYTES, int)


def max_study_hours() -> float:
    """The longest estimated study run.

    Returns
    -------
    float
        :data:`MAX_STUDY_HOURS` [h], or the value of ``$BETV_MAX_STUDY_HOURS`` when set.

    Raises
    ------
    UsageError
        The variable is not a finite number > 0.
    """
    return _env_number(STUDY_HOURS_ENV, MAX_STUDY_HOURS, float)


def _env_number(name: str, default: Any, kind: type) -> Any:
    raw = os.environ.get(name)
    if raw is None or not raw.strip():
        return default
    if sum(ch.isdigit() for ch in raw) > MAX_NUMBER_DIGITS:
        raise UsageError(f"${name}: more than {MAX_NUMBER_DIGITS} digits")
    try:
        value = kind(raw)
    except ValueError:
        raise UsageError(f"${name}={raw!r} is not a number") from None
    if not value > 0 or value != value or value == float("inf"):
        raise UsageError(f"${name} must be a finite number > 0, got {raw!r}")
    return value


def format_duration(seconds: float) -> str:
    """A duration for estimates in messages: ``"3.2 h"``, ``"12 min"``, ``"40 s"``.

    Parameters
    ----------
    seconds : float
        The duration [s].

    Returns
    -------
    str
        In days, hours, minutes or seconds (3 significant digits).
    """
    if seconds >= 2 * 86400:
        return f"{seconds / 86400:.3g} days"
    if seconds >= 3600:
        return f"{seconds / 3600:.3g} h"
    if seconds >= 60:
        return f"{seconds / 60:.3g} min"
    return f"{seconds:.2g} s"


def refuse_long_study(what: str, points: int, cost_s: float, workers: int) -> None:
    """Refuse a study that would run too long or has too many points.

    Parameters
    ----------
    what : str
        The study, as messages name it.
    points : int
        Points of the study.
    cost_s : float
        Cost of one point [s on one core] (:func:`point_cost_s`).
    workers : int
        Worker processes.

    Raises
    ------
    UsageError
        ``points`` exceeds :data:`MAX_STUDY_POINTS`, or ``points`` × ``cost_s`` /
        ``workers`` exceeds the study budget (:func:`max_study_hours`); the message gives
        the estimate and how to split the work.
    """
    if points > MAX_STUDY_POINTS:
        took = points * cost_s / max(1, workers)
        est = f" (≈ {format_duration(took)} on {workers} worker(s))" if took else ""
        raise UsageError(
            f"{what}: {points:,} points exceed the limit of {MAX_STUDY_POINTS:,} points per "
            f"study{est}; split it into smaller studies"
        )
    estimate = points * cost_s / max(1, workers)
    budget = max_study_hours() * 3600.0
    if estimate > budget:
        raise UsageError(
            f"{what}: {points:,} points at ≈ {format_duration(cost_s)} each on {workers} worker(s) "
            f"would take ≈ {format_duration(estimate)}, more than the "
            f"{format_duration(budget)} limit; use fewer points, more workers "
            f"(--workers or a dask --scheduler) or set ${STUDY_HOURS_ENV}"
        )


def check_seed(seed: Any) -> int:
    """A seed numpy's ``SeedSequence`` takes.

    Parameters
    ----------
    seed : Any
        The seed given.

    Returns
    -------
    int
        The seed, an integer 0 <= seed < 2**128.

    Raises
    ------
    UsageError
        Not an integer, or out of range.
    """
    if isinstance(seed, bool) or not hasattr(seed, "__index__"):
        raise UsageError(f"--seed must be an integer, got {seed!r}")
    if not 0 <= int(seed) < SEED_BOUND:
        raise UsageError(f"--seed must be an integer with 0 <= seed < 2**128, got {seed}")
    return int(seed)


def describe() -> dict[str, Any]:
    """Every limit with its value and what it bounds (``betv schema``, README "Limits").

    Returns
    -------
    dict
        Limit name -> ``{"value": ..., "what": "..."}``.
    """
    return {
        "file_bytes": {
            "value": MAX_FILE_BYTES,
            "what": f"size of a device or tolerance file [bytes]; ${FILE_BYTES_ENV} overrides",
        },
        "yaml_depth": {"value": MAX_YAML_DEPTH, "what": "nesting of YAML mappings/sequences"},
        "yaml_nodes": {
            "value": MAX_YAML_NODES,
            "what": "YAML nodes once aliases (&anchor/*alias, << merges) are expanded",
        },
        "string_chars": {"value": MAX_STRING_CHARS, "what": "characters of any YAML string"},
        "name_chars": {"value": MAX_NAME_CHARS, "what": "characters of a device/set name"},
        "actuator_sets": {"value": MAX_ACTUATOR_SETS, "what": "actuator sets of one device"},
        "calibration_points": {
            "value": MAX_CALIBRATION_POINTS,
            "what": "measured calibration points of one actuator",
        },
        "number_digits": {
            "value": MAX_NUMBER_DIGITS,
            "what": "digits of a number (a YAML integer or float, the number of a quantity)",
        },
        "quantity_chars": {
            "value": MAX_QUANTITY_CHARS,
            "what": "characters of a quantity string such as '2330 kg/m^3'",
        },
        "unit_factors": {
            "value": MAX_UNIT_FACTORS,
            "what": "unit factors of a quantity; one integer power each, no powers of powers",
        },
        "unit_exponent": {"value": MAX_UNIT_EXPONENT, "what": "|power| of one unit factor"},
        "quantity_range": {
            "value": {u: [lo, hi] for u, (lo, hi, _) in QUANTITY_RANGE.items()},
            "what": "magnitude of a quantity, in the unit shown (0 where the field allows 0)",
        },
        "friction": {"value": MIN_FRICTION, "what": "smallest contact.friction μ [-]"},
        "beam_count": {"value": MAX_BEAM_COUNT, "what": "slider.beam_count"},
        "cycles": {
            "value": MAX_CYCLES,
            "what": "simulate --cycles and every --max-cycles budget [cycles]",
        },
        "samples": {"value": MAX_SAMPLES, "what": "tolerance --samples"},
        "study_points": {"value": MAX_STUDY_POINTS, "what": "points of one sweep or tolerance"},
        "study_hours": {
            "value": MAX_STUDY_HOURS,
            "what": f"estimated wall time of a study [h]; ${STUDY_HOURS_ENV} overrides",
        },
        "workers": {"value": MAX_WORKERS, "what": "--workers"},
        "chunksize": {"value": MAX_CHUNKSIZE, "what": "--chunksize"},
        "seed": {"value": "0 <= seed < 2**128", "what": "--seed (numpy SeedSequence)"},
    }
