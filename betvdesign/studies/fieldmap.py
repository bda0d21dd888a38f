"""The exact-mode map of two device fields, a few rows at a time.

The exact-mode map of two device fields, in the fields' own units, computed a few
rows at a time (``betv explore``'s map: progress shown, a stale map dropped).

The points are those of :mod:`betvdesign.studies.fieldsweep` (one implementation: its
:class:`~betvdesign.studies.fieldsweep.FieldAxis`, its tasks
(:func:`~betvdesign.studies.fieldsweep.field_tasks`: the device with the two fields
changed, derived by the derivation's own formulas on arrays) and its solve of one point
(:func:`~betvdesign.studies.fieldsweep.fieldsweep_point`: the exact periodic orbit, the
exact mode of :data:`~betvdesign.studies.fieldsweep.MODES` or "invalid", the speed
Δs·u·cosθ·f_act [m/s] along the impacts)). This module only holds the grid: which rows
are done, and the rows as the page draws them. Every point is ``betv check``'s answer
over the travel (:func:`betvdesign.checks.travel.travel_answer`: the periodic orbit when
the slider settles early in its travel, else the crossing of the travel from rest), and
its ``basis`` says which; only the determination re-solves of Δs (round-off edges) are
left to the check.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from betvdesign.errors import ParameterError
from betvdesign.studies.fieldsweep import MODES, FieldAxis, field_tasks, fieldsweep_point

__all__ = ["MAP_MODES", "FieldAxis", "FieldMap", "MapRows", "map_rows", "mode_map"]

#: Every mode a map point can have, in legend order.
MAP_MODES: tuple[str, ...] = (*MODES, "invalid")
#: Cycle budget of each point's periodic orbit (the report's sweeps use the same).
MAX_CYCLES = 20_000
#: Fixed-point residual of each point's periodic orbit [-].
TOL = 1e-10


@dataclass(frozen=True)
class MapRows:
    """Rows ``rows`` (indices of the y axis) of a map.

    Rows ``rows`` (indices of the y axis) of a map: per point its mode, Δs [-] per
    cycle, speed [m/s] along the impact direction (NaN without an orbit), ϖ [-] (NaN
    where the device cannot take the values) and, for points without a mode, the
    reason.
    """

    rows: tuple[int, ...]
    mode: list[list[str]]
    delta_s: list[list[float]]
    speed_m_s: list[list[float]]
    varpi: list[list[float]]
    reasons: dict[tuple[int, int], str] = field(default_factory=dict)
    basis: list[list[str]] = field(default_factory=list)


@dataclass
class FieldMap:
    """The exact-mode map of actuator set ``set_name``.

    The exact-mode map of actuator set ``set_name``: ``mode[j][i]`` at
    (x.values[i], y.values[j]); ``speed_m_s`` along the set's impact direction [m/s];
    ``varpi`` the normalised frequency ϖ [-] of each point (the design window's test).
    """

    x: FieldAxis
    y: FieldAxis
    set_name: str
    mode: np.ndarray
    delta_s: np.ndarray
    speed_m_s: np.ndarray
    varpi: np.ndarray
    reasons: dict[tuple[int, int], str] = field(default_factory=dict)
    done: np.ndarray = field(default=None)  # type: ignore[assignment]
    #: The answer each point quotes (:mod:`betvdesign.checks.travel`'s basis; "" none).
    basis: np.ndarray = field(default=None)  # type: ignore[assignment]

    def __post_init__(self) -> None:
        """An empty basis grid when none is given."""
        if self.basis is None:
            self.basis = np.full(self.mode.shape, "", dtype=object)

    @classmethod
    def empty(cls, x: FieldAxis, y: FieldAxis, set_name: str) -> FieldMap:
        """A map of ``x`` by ``y`` with no row computed yet."""
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
        """Enter computed rows.

        Parameters
        ----------
        part : MapRows
            Rows computed by :func:`map_rows`.
        """
        for k, j in enumerate(part.rows):
            self.mode[j, :] = part.mode[k]
            self.delta_s[j, :] = part.delta_s[k]
            self.speed_m_s[j, :] = part.speed_m_s[k]
            self.varpi[j, :] = part.varpi[k]
            if part.basis:
                self.basis[j, :] = part.basis[k]
            self.done[j] = True
        self.reasons.update(part.reasons)

    @property
    def complete(self) -> bool:
        """Whether every row has been computed."""
        return bool(self.done.all())


def _num(x: Any) -> float:
    return math.nan if x is None else float(x)


def map_rows(
    spec: Any,
    set_index: int,
    x: FieldAxis,
    y: FieldAxis,
    rows: Sequence[int],
    *,
    max_cycles: int = MAX_CYCLES,
) -> MapRows:
    """Rows ``rows`` of the exact-mode map of set ``set_index`` of ``spec``.

    Rows ``rows`` of the exact-mode map of set ``set_index`` of ``spec`` (a
    :class:`~betvdesign.spec.models.DeviceSpec`).

    Raises
    ------
    ParameterError
        ``set_index`` or a row index out of range.

    Parameters
    ----------
    spec : DeviceSpec
        The device.
    set_index : int
        The actuator set.
    x, y : FieldAxis
        The map's axes.
    rows : sequence of int
        Indices of the y axis.
    max_cycles : int
        Budget of each periodic orbit [cycles].

    Returns
    -------
    MapRows
        Per point its mode, Δs, speed, ϖ and the reason when it has no mode.
    """
    if not 0 <= set_index < len(spec.actuator_sets):
        raise ParameterError(f"no actuator set {set_index}")
    rows = tuple(int(j) for j in rows)
    if any(not 0 <= j < len(y.values) for j in rows):
        raise ParameterError(f"row out of range 0..{len(y.values) - 1}")
    # the y rows first: tasks come row-major (the first axis slowest), x fastest
    y_rows = FieldAxis(y.field, y.unit, tuple(y.values[j] for j in rows), y.log, y.x0)
    tasks = field_tasks(spec, [y_rows, x], set_index, TOL)
    nx = len(x.values)
    mode = [["invalid"] * nx for _ in rows]
    ds = [[math.nan] * nx for _ in rows]
    speed = [[math.nan] * nx for _ in rows]
    varpi = [[math.nan] * nx for _ in rows]
    basis = [[""] * nx for _ in rows]
    reasons: dict[tuple[int, int], str] = {}
    for k, task in enumerate(tasks):
        r, i = divmod(k, nx)
        row = fieldsweep_point({**task, "max_cycles": max_cycles})
        mode[r][i] = row["exact_mode"]
        basis[r][i] = row.get("basis") or ""
        varpi[r][i] = _num(row.get("varpi"))
        ds[r][i] = _num(row.get("delta_s")) if row["converged"] else math.nan
        speed[r][i] = _num(row.get("speed_m_s"))
        if row["exact_mode"] not in ("push", "pull", "stalled"):
            why = row.get("message") or "the device cannot take these values"
            reasons[(rows[r], i)] = str(why).splitlines()[0]
    return MapRows(rows, mode, ds, speed, varpi, reasons, basis)


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
    """The whole map, ``chunk`` rows at a time (``progress(rows done, rows)`` after each).

    Parameters
    ----------
    spec : DeviceSpec
        The device.
    set_index : int
        The actuator set.
    x, y : FieldAxis
        The map's axes.
    chunk : int
        Rows per step.
    progress : callable, optional
        Called with (rows done, rows).
    max_cycles : int
        Budget of each periodic orbit [cycles].

    Returns
    -------
    FieldMap
        The whole map.
    """
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
