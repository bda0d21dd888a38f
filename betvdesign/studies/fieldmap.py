"""The exact-mode map of two device fields, in the fields' own units.

A designer asks "where is the edge?" in the quantities they draw and drive:
``drive.frequency`` against ``slider.beam_width``, not ϖ against α. Every point of the
map is the device with the two fields changed (:func:`betvdesign.spec.paths.with_values`
semantics: a field below an actuator set changes in every set that has it), derived by
the derivation's own formulas on arrays (:func:`betvdesign.studies.sampling.derive_all`,
each point on its own where a point cannot be derived that way) and solved by the exact
periodic orbit (:func:`betvdesign.dynamics.periodic_orbit`). The mode of a point is
the settled orbit's, as ``betv check`` finds it for a set (:func:`point_mode`): "push",
"pull", "stalled", "not driven" (no contact recurs), "unbounded" (exact tangential
resonance), "no orbit" (not converged within the budget) or "invalid" (the device cannot
take the values). Where the slider does not settle early in its travel, ``betv check``'s
verdict quotes the crossing of the travel from rest instead
(:func:`betvdesign.checks.travel.travel_answer`); the map does not run that transient
(nor the determination of Δs) per point, so there it shows the periodic mode.

Rows can be computed one chunk at a time (:func:`map_rows`) so a caller can show
progress and drop a stale map; :func:`mode_map` computes them all.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from betvdesign.errors import BetvError, ParameterError
from betvdesign.model.domain import mode_of
from betvdesign.model.params import ModelParams

__all__ = [
    "MAP_MODES",
    "FieldAxis",
    "FieldMap",
    "MapRows",
    "map_rows",
    "mode_map",
    "point_mode",
]

#: Every mode a map point can have, in legend order.
MAP_MODES: tuple[str, ...] = (
    "push",
    "pull",
    "stalled",
    "not driven",
    "unbounded",
    "no orbit",
    "invalid",
)
#: Cycle budget of each point's periodic orbit (the report's sweeps use the same).
MAX_CYCLES = 20_000


@dataclass(frozen=True)
class FieldAxis:
    """One axis of a map: a dotted device field, its unit and its values [unit].

    ``log``: the values are (and the axis is drawn) log-spaced.
    """

    field: str
    unit: str
    values: tuple[float, ...]
    log: bool = True

    @classmethod
    def spanning(
        cls, field: str, unit: str, lo: float, hi: float, points: int, *, log: bool = True
    ) -> FieldAxis:
        """``points`` values from ``lo`` to ``hi`` [unit], log-spaced when ``log``."""
        if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi and points >= 2):
            raise ParameterError(f"{field}: need LO < HI and at least 2 points")
        if log and lo <= 0:
            raise ParameterError(f"{field}: a log-spaced axis needs LO > 0 (got {lo:g})")
        xs = np.geomspace(lo, hi, points) if log else np.linspace(lo, hi, points)
        return cls(field, unit, tuple(float(x) for x in xs), log)

    def quantity(self, x: Any) -> Any:
        """``x`` [unit] as the device file's value (a pint quantity, or a float)."""
        from betvdesign.spec.units import ureg

        return ureg.Quantity(x, self.unit) if self.unit else x

    def edges(self) -> np.ndarray:
        """Cell edges around the values (geometric midpoints on a log axis) [unit]."""
        v = np.asarray(self.values, dtype=float)
        t = np.log(v) if self.log else v
        mid = 0.5 * (t[1:] + t[:-1])
        e = np.concatenate([[2 * t[0] - mid[0]], mid, [2 * t[-1] - mid[-1]]])
        return np.exp(e) if self.log else e


@dataclass(frozen=True)
class MapRows:
    """Rows ``rows`` (indices of the y axis) of a map: per point its mode, Δs [-] per
    cycle, speed [m/s] along the impact direction (NaN without an orbit), ϖ [-] (NaN
    where the device cannot take the values) and, for points without a mode, the
    reason."""

    rows: tuple[int, ...]
    mode: list[list[str]]
    delta_s: list[list[float]]
    speed_m_s: list[list[float]]
    varpi: list[list[float]]
    reasons: dict[tuple[int, int], str] = field(default_factory=dict)


@dataclass
class FieldMap:
    """The exact-mode map of actuator set ``set_name``: ``mode[j][i]`` at
    (x.values[i], y.values[j]); ``speed_m_s`` along the set's impact direction [m/s];
    ``varpi`` the normalised frequency ϖ [-] of each point (the design window's test)."""

    x: FieldAxis
    y: FieldAxis
    set_name: str
    mode: np.ndarray
    delta_s: np.ndarray
    speed_m_s: np.ndarray
    varpi: np.ndarray
    reasons: dict[tuple[int, int], str] = field(default_factory=dict)
    done: np.ndarray = field(default=None)  # type: ignore[assignment]

    @classmethod
    def empty(cls, x: FieldAxis, y: FieldAxis, set_name: str) -> FieldMap:
        shape = (len(y.values), len(x.values))
        return cls(
            x,
            y,
            set_name,
            np.full(shape, "", dtype=object),
            np.full(shape, math.nan),
            np.full(shape, math.nan),
            np.full(shape, math.nan),
            {},
            np.zeros(shape[0], dtype=bool),
        )

    def fill(self, part: MapRows) -> None:
        """Enter computed rows."""
        for k, j in enumerate(part.rows):
            self.mode[j, :] = part.mode[k]
            self.delta_s[j, :] = part.delta_s[k]
            self.speed_m_s[j, :] = part.speed_m_s[k]
            self.varpi[j, :] = part.varpi[k]
            self.done[j] = True
        self.reasons.update(part.reasons)

    @property
    def complete(self) -> bool:
        return bool(self.done.all())


def point_mode(orbit: Any) -> str:
    """The map's mode of one exact periodic-orbit result (see the module docstring)."""
    status = str(getattr(orbit, "status", ""))
    if getattr(orbit, "success", False):
        return mode_of(orbit.delta_s) or "no orbit"
    if status == "not_driven":
        return "not driven"
    if status == "unbounded":
        return "unbounded"
    return "no orbit"


@dataclass(frozen=True)
class _Column:
    """A field as :func:`betvdesign.studies.sampling.derive_all` takes it."""

    field: str


def _solve(p: ModelParams, max_cycles: int) -> Any:
    from betvdesign.dynamics import periodic_orbit

    return periodic_orbit(p, max_cycles=max_cycles)


def _derived_points(
    spec: Any, set_index: int, x: FieldAxis, y: FieldAxis, xs: np.ndarray, ys: np.ndarray
) -> tuple[list[ModelParams | None], np.ndarray, list[str]]:
    """(params or None, speed per unit Δs [m/s], reason) of each point."""
    from betvdesign.nondim.device import derive_set
    from betvdesign.spec.paths import with_values
    from betvdesign.studies.sampling import check_sample, derive_all, params_of

    cols = [_Column(x.field), _Column(y.field)]
    nominal = {x.field: (float(xs[0]), x.unit), y.field: (float(ys[0]), y.unit)}
    n = len(xs)
    params: list[ModelParams | None] = [None] * n
    scale = np.full(n, math.nan)
    reasons = [""] * n
    bulk = derive_all(spec, cols, nominal, np.column_stack([xs, ys]), set_index)
    for k in range(n):
        values = {x.field: (float(xs[k]), x.unit), y.field: (float(ys[k]), y.unit)}
        try:
            check_sample(values)
            if bulk is not None:
                params[k] = params_of(bulk, k)
                scale[k] = float(bulk["length_m"][k]) * float(bulk["f_act_hz"][k])
                continue
            changed = with_values(
                spec, {f: FieldAxis(f, u, ()).quantity(v) for f, (v, u) in values.items()}
            )
            sd = derive_set(changed, changed.actuator_sets[set_index])
            params[k] = sd.params
            scale[k] = sd.scales.length_m * sd.scales.f_act_hz
        except (BetvError, ValueError, ArithmeticError) as exc:
            reasons[k] = str(exc).splitlines()[0]
    return params, scale, reasons


def map_rows(
    spec: Any,
    set_index: int,
    x: FieldAxis,
    y: FieldAxis,
    rows: Sequence[int],
    *,
    max_cycles: int = MAX_CYCLES,
) -> MapRows:
    """Rows ``rows`` of the exact-mode map of set ``set_index`` of ``spec`` (a
    :class:`~betvdesign.spec.models.DeviceSpec`); identical parameter sets are solved once.

    Raises
    ------
    ParameterError
        ``set_index`` or a row index out of range.
    """
    if not 0 <= set_index < len(spec.actuator_sets):
        raise ParameterError(f"no actuator set {set_index}")
    rows = tuple(int(j) for j in rows)
    if any(not 0 <= j < len(y.values) for j in rows):
        raise ParameterError(f"row out of range 0..{len(y.values) - 1}")
    xv = np.asarray(x.values, dtype=float)
    gx, gy = np.meshgrid(xv, np.asarray([y.values[j] for j in rows], dtype=float))
    params, scale, why = _derived_points(spec, set_index, x, y, gx.ravel(), gy.ravel())
    solved: dict[ModelParams, Any] = {}
    nx = len(xv)
    mode = [["invalid"] * nx for _ in rows]
    ds = [[math.nan] * nx for _ in rows]
    speed = [[math.nan] * nx for _ in rows]
    varpi = [[math.nan] * nx for _ in rows]
    reasons: dict[tuple[int, int], str] = {}
    for k, p in enumerate(params):
        r, i = divmod(k, nx)
        j = rows[r]
        if p is None:
            reasons[(j, i)] = why[k] or "the device cannot take these values"
            continue
        varpi[r][i] = p.varpi
        if p not in solved:
            try:
                solved[p] = _solve(p, max_cycles)
            except (BetvError, ValueError, ArithmeticError) as exc:
                solved[p] = exc
        res = solved[p]
        if isinstance(res, Exception):
            mode[r][i] = "no orbit"
            reasons[(j, i)] = str(res).splitlines()[0]
            continue
        mode[r][i] = point_mode(res)
        if getattr(res, "success", False):
            ds[r][i] = float(res.delta_s)
            speed[r][i] = float(res.delta_s) * float(scale[k])
        else:
            reasons[(j, i)] = f"{res.status}: {res.message}".splitlines()[0]
    return MapRows(rows, mode, ds, speed, varpi, reasons)


def mode_map(
    spec: Any,
    set_index: int,
    x: FieldAxis,
    y: FieldAxis,
    *,
    chunk: int = 4,
    progress: Callable[[int, int], None] | None = None,
    max_cycles: int = MAX_CYCLES,
) -> FieldMap:
    """The whole map, ``chunk`` rows at a time (``progress(rows done, rows)`` after each)."""
    out = FieldMap.empty(x, y, spec.actuator_sets[set_index].name)
    ny = len(y.values)
    for start in range(0, ny, max(1, chunk)):
        out.fill(
            map_rows(
                spec, set_index, x, y, range(start, min(ny, start + chunk)), max_cycles=max_cycles
            )
        )
        if progress is not None:
            progress(min(ny, start + chunk), ny)
    return out
