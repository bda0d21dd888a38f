"""Studies of a device's own fields, in physical units (``betv sweep FILE --vary ...``).

A designer asks "what does the drive frequency do to my device?" or "where does the
mode flip between beam width and frequency?", in the file's own units. One or two
fields of the device file (any numeric field, :mod:`betvdesign.spec.paths`) are varied
over a grid in physical units; every point is the device with those values, derived
(:func:`betvdesign.nondim.device.derive_samples`, all points at once, the same
formulas as ``betv check``) and solved to its exact periodic orbit
(:func:`betvdesign.studies.points.periodic_point`).

API (fields in physical units in, rows out; shared with other front ends):

* :func:`parse_axis` -> :class:`FieldAxis` (``"drive.frequency=1kHz:4kHz"``);
* :func:`fieldsweep_study` -> a resumable, parallel :class:`~betvdesign.studies.engine.
  runner.Study`; :func:`run_fieldsweep` runs it;
* rows: the fields' values [their units] (columns ``field [unit]``), ϖ, α, β, κ,
  λ [-], the ``exact_mode`` (push, pull, stalled, not driven, unbounded, not
  converged, no crossing), Δs [-],
  ``speed_m_s`` (|Δs|·u·cosθ·f_act [m/s], a magnitude: the mode says which way) and
  its ``basis``:
  each point's answer is ``betv check``'s travel answer
  (:func:`betvdesign.checks.checker.answer_over_travel`: the periodic orbit when it
  settles early in the travel, the crossing mean from rest when it does not or when no
  orbit is found, "no crossing" when it does not cross within the horizon), without the
  check's determination re-solves (which matter only at round-off edges: the map names
  its basis, so a cell and ``betv check`` of the same design say the same);
  ``model``: "coupled" where the check's verdict of the point is the drawn head's coupled
  model (a drawn head without measured resonances:
  :func:`betvdesign.checks.checker.coupled_head`; the point derived as the check derives
  it and answered by :func:`betvdesign.checks.checker.coupled_over_travel`, the check's
  own), "decoupled" otherwise (docs/MODEL.md "Coupled head");
* :func:`locate_flips` (1-D): every change of the exact mode between neighbouring
  points, bisected in the field to :data:`FLIP_RTOL`;
* :func:`sweep_marks` (1-D): where along the field the design window 0.5 ≤ ϖ < 2 lies,
  where the sub-resonances α·ϖ² = 1/n² (f_act = f_h/n) fall, and, for an undamped head,
  the band |α·ϖ² − 1| < 0.1 around the tangential resonance where the idealised speed is
  not physical.

Speeds are magnitudes [m/s] with the mode beside them (``exact_mode``), as everywhere in
the package's outputs (:mod:`betvdesign.output.siformat`); Δs stays signed (+ push).

The mode and the speed are the travel answer's, never λ's (λ = 1 is drawn beside it
as the paper's fit).
"""

from __future__ import annotations

import hashlib
import itertools
import math
from collections import Counter
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pint

from betvdesign.errors import BetvError, ParameterError, UsageError
from betvdesign.model.bisection import bisect
from betvdesign.model.domain import (
    SUBRESONANCE_ORDERS,
    TANGENTIAL_DETUNING,
    VARPI_WINDOW,
    mode_of,
    nearest_subresonance,
    subresonance_level,
)
from betvdesign.spec.paths import with_values
from betvdesign.studies.engine.runner import Study, StudyRun, run_study, split_run_args
from betvdesign.studies.fixfields import current_value
from betvdesign.studies.points import COLUMNS, orbit_row, periodic_solve, point_row, task_params

__all__ = [
    "FLIP_RTOL",
    "MODES",
    "FieldAxis",
    "Flip",
    "exact_mode",
    "field_map",
    "field_tasks",
    "fieldsweep_study",
    "grid_points",
    "locate_flips",
    "parse_axis",
    "run_fieldsweep",
    "summarise",
    "sweep_marks",
]

#: The exact modes a point can have (the map's categories).
MODES = ("push", "pull", "stalled", "not driven", "unbounded", "not converged", "no crossing")
#: Relative width [-] to which a mode flip is bisected along its field.
FLIP_RTOL = 1e-3
#: Points per axis by default.
DEFAULT_POINTS = 40
#: Most points per axis.
MAX_POINTS = 400


@dataclass(frozen=True)
class FieldAxis:
    """One field of the device varied over a grid.

    Attributes
    ----------
    field : str
        Dotted field path (as in the device file).
    unit : str
        The field's unit as the device file gives it ("" for a number).
    values : tuple of float
        The grid [``unit``], ascending.
    log : bool
        The values are (and the axis is drawn) log-spaced.
    x0 : float or None
        The device's value [``unit``] (None: not recorded).
    """

    field: str
    unit: str
    values: tuple[float, ...]
    log: bool = False
    x0: float | None = None

    @classmethod
    def spanning(
        cls,
        field: str,
        unit: str,
        lo: float,
        hi: float,
        points: int,
        *,
        log: bool = True,
        x0: float | None = None,
    ) -> FieldAxis:
        """``points`` values from ``lo`` to ``hi`` [unit], log-spaced when ``log``.

        Parameters
        ----------
        field : str
            The field's path.
        unit : str
            Its unit.
        lo, hi : float
            The range [unit].
        points : int
            Number of values.
        log : bool
            Log-spaced.
        x0 : float, optional
            The device's own value [unit].

        Returns
        -------
        FieldAxis
            The axis.
        """
        if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi and points >= 2):
            raise ParameterError(f"{field}: need LO < HI and at least 2 points")
        if log and lo <= 0:
            raise ParameterError(f"{field}: a log-spaced axis needs LO > 0 (got {lo:g})")
        xs = np.geomspace(lo, hi, points) if log else np.linspace(lo, hi, points)
        return cls(field, unit, tuple(float(x) for x in xs), log, x0)

    @classmethod
    def scaled(cls, field: str, value: Any, factors: Sequence[float]) -> FieldAxis:
        """The axis of a field's value as the device file gives it, scaled.

        The axis of a field's value as the device file gives it (a quantity or a
        number) times each of ``factors`` [-], in the value's own unit.

        Parameters
        ----------
        field : str
            The field's path.
        value : Any
            Its value as the device file gives it.
        factors : sequence of float
            Relative values [-].

        Returns
        -------
        FieldAxis
            The axis, in the value's unit.
        """
        if isinstance(value, pint.Quantity):
            x0, unit = float(value.magnitude), f"{value.units:~}"
        else:
            x0, unit = float(value), ""
        return cls(field, unit, tuple(x0 * float(f) for f in factors), x0=x0)

    @property
    def label(self) -> str:
        """The axis label: ``field [unit]``."""
        return f"{self.field} [{self.unit}]" if self.unit else self.field

    def quantity(self, x: Any) -> Any:
        """``x`` [unit] as the device file's value (a pint quantity, or a float).

        Parameters
        ----------
        x : float
            A value [unit].

        Returns
        -------
        Any
            A pint quantity, or a float for a unit-less field.
        """
        from betvdesign.spec.units import ureg

        return ureg.Quantity(x, self.unit) if self.unit else x

    def edges(self) -> np.ndarray:
        """Cell edges around the values (geometric midpoints on a log axis) [unit]."""
        v = np.asarray(self.values, dtype=float)
        t = np.log(v) if self.log else v
        mid = 0.5 * (t[1:] + t[:-1])
        e = np.concatenate([[2 * t[0] - mid[0]], mid, [2 * t[-1] - mid[-1]]])
        return np.exp(e) if self.log else e


def _bound(text: str, field: str, unit: str) -> float:
    """One bound in the field's unit.

    One bound in the field's unit: a quantity ("2 kHz"), or a number with an SI prefix
    alone ("2k" = 2 k of the field's SI unit); a bare number only for a unit-less field.
    """
    import pint

    from betvdesign.spec.units import parse_quantity, range_problem, ureg

    t = text.strip()
    try:
        if unit and t and t[-1] in "kMGmunµp" and _is_number(t[:-1]):
            named = next(
                (
                    n
                    for n in _NAMED_UNITS
                    if ureg.Quantity(1.0, n).check(ureg.Quantity(1.0, unit).dimensionality)
                ),
                None,
            )
            if named is None:
                raise ValueError(f"give the unit (the field is in {unit})")
            q = parse_quantity(f"{t[:-1]} {t[-1].replace('µ', 'u')}{named}")
        else:
            q = parse_quantity(t)
        if not isinstance(q, pint.Quantity) or q.dimensionless:
            mag = float(q.magnitude if isinstance(q, pint.Quantity) else q)
            if unit and not ureg.Quantity(1.0, unit).dimensionless:
                raise UsageError(
                    f"--vary {field}: missing unit in {text!r} (the field is in {unit}; "
                    f"write e.g. '{mag:g} {unit}')"
                )
            return mag
        problem = range_problem(q)
        if problem is not None:  # what a device file could not give either
            raise UsageError(f"--vary {field}: {problem}")
        return float(q.to(unit).magnitude) if unit else float(q.to("dimensionless").magnitude)
    except (ValueError, pint.PintError) as exc:
        raise UsageError(f"--vary {field}={text}: {exc}") from None


#: SI units an SI prefix alone refers to, by the field's dimension ("2k" = 2 kHz).
_NAMED_UNITS = ("Hz", "m", "g", "V", "s", "N/m")


def _is_number(s: str) -> bool:
    try:
        float(s)
    except ValueError:
        return False
    return True


def parse_axis(
    spec: Any,
    text: str,
    points: int = DEFAULT_POINTS,
    *,
    log: bool = False,
    max_points: int = MAX_POINTS,
) -> FieldAxis:
    """Parse ``FIELD=LO:HI`` into a :class:`FieldAxis`.

    ``FIELD=LO:HI`` in any unit of the field -> a :class:`FieldAxis` of ``points``
    values (linear, or log-spaced with ``log``).

    Parameters
    ----------
    spec : DeviceSpec
        The device.
    text : str
        E.g. ``"drive.frequency=1kHz:4kHz"``, ``"slider.beam_width=5um:45um"``,
        ``"drive.frequency=1k:4k"`` (an SI prefix alone: of the field's SI unit).
    points : int
        Grid points (2 to :data:`MAX_POINTS`).
    log : bool
        Log-spaced grid.
    max_points : int
        Most grid points (a sweep: :data:`MAX_POINTS`; an atlas allows more).

    Returns
    -------
    FieldAxis
        The axis, in the unit the device file gives the field.

    Raises
    ------
    UsageError
        An unknown or non-numeric field, unreadable, unit-less or inverted bounds.
    """
    name, sep, rng = text.partition("=")
    name = name.strip()
    if not 2 <= points <= max_points:
        raise UsageError(f"--points: need 2 to {max_points} (got {points})")
    cur = current_value(spec, name)
    if cur is None:
        from betvdesign.spec.fields import FIELDS

        known = ", ".join(f.path for f in FIELDS if current_value(spec, f.path) is not None)
        raise UsageError(
            f"--vary {name}: not a numeric field of device {spec.name!r}; it has {known}"
        )
    x0, unit = cur
    lo_s, sep2, hi_s = rng.partition(":")
    if not sep or not sep2:
        raise UsageError(f"--vary {text}: give FIELD=LO:HI, e.g. {name}=1kHz:4kHz")
    lo, hi = _bound(lo_s, name, unit), _bound(hi_s, name, unit)
    if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
        raise UsageError(f"--vary {text}: need LO < HI (got {lo:g} to {hi:g} {unit})".rstrip())
    if log and lo <= 0:
        raise UsageError(f"--vary {text}: a log-spaced axis needs LO > 0")
    return FieldAxis.spanning(name, unit, lo, hi, points, log=log, x0=x0)


def exact_mode(row: Mapping[str, Any]) -> str:
    """The exact mode of a point's row.

    The exact mode of a point's row: one of :data:`MODES` (the travel answer's when
    the row has one: ``basis`` and ``travel_mode``).
    """
    basis = row.get("basis")
    if basis == "no-crossing":
        return "no crossing"
    if basis in ("periodic", "crossing") and row.get("travel_mode") is not None:
        return str(row["travel_mode"])
    status = row.get("status")
    if row.get("converged") and row.get("delta_s") is not None:
        return mode_of(float(row["delta_s"]))
    if status == "not_driven":
        return "not driven"
    if status == "unbounded":
        return "unbounded"
    return "not converged"


def grid_points(axes: Sequence[FieldAxis], keys: Sequence[int] | None = None) -> np.ndarray:
    """The grid's points (row-major: the first axis slowest), or those of ``keys``.

    Parameters
    ----------
    axes : sequence of FieldAxis
        The axes.
    keys : sequence of int, optional
        Flat keys of the points wanted (None: every point, in key order).

    Returns
    -------
    numpy.ndarray
        Shape (points, fields) [the fields' units].
    """
    values = [np.asarray(a.values, dtype=float) for a in axes]
    if keys is None:
        mesh = np.meshgrid(*values, indexing="ij")
        return np.column_stack([m.ravel() for m in mesh])
    idx = np.unravel_index(np.asarray(keys, dtype=np.int64), tuple(len(v) for v in values))
    return np.column_stack([v[i] for v, i in zip(values, idx, strict=True)])


def _derive_grid(
    spec: Any, axes: Sequence[FieldAxis], set_index: int, keys: Sequence[int] | None = None
) -> tuple[np.ndarray, list[dict[str, Any] | str]]:
    """Every grid point (or those of ``keys``) derived at once.

    Every grid point (or those of ``keys``) derived at once: the points (n, fields)
    [units] and per point its parameters, length scale [m], f_act [Hz], or the reason it
    cannot be derived.
    """
    from betvdesign.nondim.device import derive_set
    from betvdesign.studies.sampling import PARAM_FIELDS, check_sample, derive_all

    x = grid_points(axes, keys)

    class _F:  # derive_all reads .field of each sampled field
        def __init__(self, f: str):
            self.field = f

    nominal = {a.field: (a.values[0] if a.x0 is None else a.x0, a.unit) for a in axes}
    arrays = None
    if np.all(x > 0):
        arrays = derive_all(spec, [_F(a.field) for a in axes], nominal, x, set_index)
    out: list[dict[str, Any] | str] = []
    for j, row in enumerate(x):
        try:
            check_sample({a.field: (float(v), a.unit) for a, v in zip(axes, row, strict=True)})
        except BetvError as exc:
            out.append(str(exc))
            continue
        if arrays is not None:
            rec = {k: float(arrays[k][j]) for k in (*PARAM_FIELDS, "length_m", "f_act_hz")}
            travel = {a.field: a.quantity(float(v)) for a, v in zip(axes, row, strict=True)}
            travel_q = travel.get("slider.travel_range", spec.slider.travel_range)
            rec["travel_s"] = float(travel_q.to("m").magnitude) / rec["length_m"]
        else:
            try:
                s = with_values(
                    spec, {a.field: a.quantity(float(v)) for a, v in zip(axes, row, strict=True)}
                )
                d = derive_set(s, s.actuator_sets[set_index])
            except (BetvError, ValueError) as exc:
                out.append(str(exc))
                continue
            rec = _record(d)
        if (
            not all(math.isfinite(v) for v in rec.values())
            or min(rec[k] for k in ("varpi", "alpha", "beta")) <= 0
        ):
            out.append("the model cannot take this point (a parameter not positive)")
            continue
        out.append(rec)
    return x, out


def _record(d: Any) -> dict[str, float]:
    """A derived point's task record: its parameters [-], ℓ [m], f_act [Hz], travel [-]."""
    from betvdesign.studies.sampling import PARAM_FIELDS

    return {
        **{k: float(getattr(d.params, k)) for k in PARAM_FIELDS},
        "length_m": d.scales.length_m,
        "f_act_hz": d.scales.f_act_hz,
        "travel_s": _travel_s(d),
    }


def _head_record(d: Any) -> dict[str, float] | None:
    """A derived point's record when its verdict is the coupled head's, else None.

    :func:`_record` with the drawn ``rho`` ρ [-] and ``theta_rad`` θ [rad], when
    :func:`betvdesign.checks.checker.coupled_head` (the check's decision) gives the point
    the coupled head's verdict.
    """
    from betvdesign.checks.checker import coupled_head

    head = coupled_head(d)
    return None if head is None else {**_record(d), "rho": head[0], "theta_rad": head[1]}


def _with_heads(
    spec: Any,
    axes: Sequence[FieldAxis],
    set_index: int,
    x: np.ndarray,
    derived: list[dict[str, Any] | str],
) -> list[dict[str, Any] | str]:
    """The grid's records, those whose verdict is the coupled head's as the check has them.

    For a set whose drawn head gives k_v (no measured resonances:
    :func:`betvdesign.checks.coupled.drawn_only`), every valid point is derived as
    ``betv check`` derives it (:func:`betvdesign.nondim.device.derive_set` of the device
    with the values written in) and, where the check's decision gives it the coupled
    head's verdict, its record is :func:`_head_record`'s. Other sets' records are kept as
    they are (every verdict the decoupled springs').
    """
    from betvdesign.checks.coupled import drawn_only
    from betvdesign.nondim.device import derive_set

    try:
        own = derive_set(spec, spec.actuator_sets[set_index])
    except (BetvError, ValueError):
        return derived
    if not drawn_only(own):
        return derived
    out: list[dict[str, Any] | str] = []
    for pt, rec in zip(x, derived, strict=True):
        head = None
        if not isinstance(rec, str):
            values = {a.field: a.quantity(float(v)) for a, v in zip(axes, pt, strict=True)}
            try:
                s = with_values(spec, values)
                head = _head_record(derive_set(s, s.actuator_sets[set_index]))
            except (BetvError, ValueError):
                head = None
        out.append(rec if head is None else head)
    return out


def fieldsweep_point(task: Mapping[str, Any]) -> dict[str, Any]:
    """Worker: one grid point's exact periodic orbit, with its physical speed.

    Parameters
    ----------
    task : mapping
        ``key``, the fields' ``values`` [their units], ϖ, α, β, κ, ζ_v, ζ_h, e [-],
        ``length_m`` ℓ = u·cosθ [m], ``f_act_hz`` [Hz], ``tol`` [-]; or ``invalid`` (why
        the point cannot be derived).

    Returns
    -------
    dict
        One row of :func:`columns`: the values, the point's row of
        :data:`betvdesign.studies.points.COLUMNS`, ``exact_mode`` (:data:`MODES`),
        ``speed_m_s`` [m/s, a magnitude], ``basis`` and ``model`` (whose orbit:
        :func:`travel_point`).
    """
    values = dict(task["values"])
    if task.get("invalid"):
        row = dict.fromkeys(task["columns"])
        row.update(
            key=task["key"],
            **values,
            status="invalid",
            converged=False,
            message=task["invalid"],
            exact_mode="invalid",
            basis=None,
            model=None,
        )
        return row
    row = travel_point(task)
    row.update(values)
    row["exact_mode"] = exact_mode(row)
    ds = row.get("quoted_delta_s")
    ok = row["exact_mode"] in ("push", "pull", "stalled") and ds is not None
    row["speed_m_s"] = abs(float(ds)) * task["length_m"] * task["f_act_hz"] if ok else None
    return {c: row.get(c) for c in task["columns"]}


def travel_point(task: Mapping[str, Any]) -> dict[str, Any]:
    """One point's exact orbit and the travel answer ``betv check`` quotes for it.

    Parameters
    ----------
    task : mapping
        A point task (:func:`field_tasks`): its parameters [-], ``tol`` and
        ``travel_s``, the travel range in units of u·cosθ [-] (absent: the periodic
        orbit alone is the answer); with ``rho`` ρ [-] and ``theta_rad`` θ [rad] (and
        then ``travel_s``) for a point whose verdict is the coupled head's
        (:func:`betvdesign.checks.checker.coupled_head`).

    Returns
    -------
    dict
        The periodic point's row (:func:`betvdesign.studies.points.periodic_point`) with
        ``basis`` (:mod:`betvdesign.checks.travel`), ``travel_mode`` and
        ``quoted_delta_s`` [-] (the Δs the answer quotes), ``cycles_to_cross`` and
        ``model``: "decoupled" (the paper's springs: the exact orbit and
        :func:`betvdesign.checks.checker.answer_over_travel`) or "coupled" (the drawn
        head: :func:`betvdesign.checks.checker.coupled_over_travel`, ``betv check``'s
        answer of such a set; the coupled orbit's row, ``tol`` not used).
    """
    from betvdesign.checks.checker import answer_over_travel

    if task.get("rho") is not None:
        return _coupled_point(task)
    row, res = periodic_solve(task)
    row["model"] = "decoupled"
    travel_s = task.get("travel_s")
    if res is None:
        row.update(basis=None, travel_mode=None, quoted_delta_s=None, cycles_to_cross=None)
        return row
    if travel_s is None:
        ds = row.get("delta_s") if res.success else None
        row.update(
            basis="periodic" if res.success else None,
            travel_mode=mode_of(ds) if ds is not None else None,
            quoted_delta_s=ds,
            cycles_to_cross=None,
        )
        return row
    _, _, ans = answer_over_travel(task_params(task), res, float(travel_s), determine=False)
    row.update(
        basis=ans.basis,
        travel_mode=ans.mode,
        quoted_delta_s=ans.delta_s,
        cycles_to_cross=ans.cycles_to_cross,
    )
    return row


def _coupled_point(task: Mapping[str, Any]) -> dict[str, Any]:
    """:func:`travel_point` of a point whose verdict is the coupled head's."""
    from betvdesign.checks.checker import coupled_over_travel

    head = (float(task["rho"]), float(task["theta_rad"]))
    po, _, ans = coupled_over_travel(task_params(task), head, float(task["travel_s"]))
    row = orbit_row(point_row(task), po)
    row.update(
        model="coupled",
        basis=ans.basis,
        travel_mode=ans.mode,
        quoted_delta_s=ans.delta_s,
        cycles_to_cross=ans.cycles_to_cross,
    )
    return row


def columns(axes: Sequence[FieldAxis]) -> dict[str, type]:
    """The result columns: the fields, the point's columns, exact mode, speed, basis, model.

    A field's column is named with its unit, ``drive.frequency [kHz]``
    (:attr:`FieldAxis.label`): the CSV and JSON say what its numbers are in.
    """
    out: dict[str, type] = {"key": int}
    out |= {a.label: float for a in axes}
    out |= {k: t for k, t in COLUMNS.items() if k != "key"}
    out |= {"zeta_v": float, "zeta_h": float, "restitution": float}
    out |= {"exact_mode": str, "speed_m_s": float, "basis": str, "cycles_to_cross": int}
    out |= {"model": str}
    return out


def _travel_s(d: Any) -> float:
    """A derived set's travel range in units of u·cosθ [-]."""
    return d.travel_range_m / d.scales.length_m


def _set_index(spec: Any, set_name: str | None) -> tuple[int, str]:
    names = [s.name for s in spec.actuator_sets]
    if set_name is None:
        set_name = names[0]
    if set_name not in names:
        raise UsageError(f"--set {set_name}: the device has {', '.join(names)}")
    return names.index(set_name), set_name


def field_tasks(
    spec: Any,
    axes: Sequence[FieldAxis],
    set_index: int,
    tol: float = 1e-10,
    keys: Sequence[int] | None = None,
    *,
    max_fields: int = 2,
) -> list[dict[str, Any]]:
    """The grid's tasks for :func:`fieldsweep_point` (row-major, first axis slowest).

    Parameters
    ----------
    spec : DeviceSpec
        The loaded device.
    axes : sequence of FieldAxis
        One or two axes.
    set_index : int
        Index of the actuator set.
    tol : float
        Fixed-point residual accepted [-].
    keys : sequence of int, optional
        Flat keys of the points wanted (None: every point; the atlas builds its tasks a
        chunk at a time, :mod:`betvdesign.studies.atlas`).
    max_fields : int
        Most fields varied (a sweep: 2; an atlas: :data:`betvdesign.studies.atlas.MAX_FIELDS`).

    Returns
    -------
    list of dict
        One task per grid point: its values [the fields' units] and derived parameters,
        or ``invalid`` (why the point cannot be derived).
    """
    if not 1 <= len(axes) <= max_fields or len({a.field for a in axes}) != len(axes):
        what = "one or two" if max_fields == 2 else f"1 to {max_fields}"
        raise UsageError(f"--vary: give {what} different fields")
    x, derived = _derive_grid(spec, axes, set_index, keys)
    derived = _with_heads(spec, axes, set_index, x, derived)
    cols = columns(axes)
    order = range(len(x)) if keys is None else keys
    tasks = []
    for j, pt, rec in zip(order, x, derived, strict=True):
        values = {a.label: float(v) for a, v in zip(axes, pt, strict=True)}
        task: dict[str, Any] = {
            "key": int(j),
            "values": values,
            "tol": tol,
            "columns": list(cols),
        }
        if isinstance(rec, str):
            task["invalid"] = rec
        else:
            task.update(rec)
        tasks.append(task)
    return tasks


def field_map(
    spec: Any, axes: Sequence[FieldAxis], set_index: int = 0, tol: float = 1e-10
) -> tuple[list[dict[str, Any]], dict[str, Any]]:
    """The sweep of ``axes`` of a loaded device, solved in this process.

    The sweep of ``axes`` of a loaded device, solved in this process (no store, no
    workers): for a report's few hundred points, where starting workers costs more
    than the orbits.

    Parameters
    ----------
    spec : DeviceSpec
        The loaded device.
    axes : sequence of FieldAxis
        One or two axes.
    set_index : int
        Index of the actuator set.
    tol : float
        Fixed-point residual accepted [-].

    Returns
    -------
    tuple of (list of dict, dict)
        The rows in grid order and their summary (:func:`summarise`; with one axis the
        bisected flips).
    """
    rows = [fieldsweep_point(t) for t in field_tasks(spec, axes, set_index, tol)]
    summary = summarise(spec.actuator_sets[set_index].name, axes, rows)
    if len(axes) == 1:
        flips = locate_flips(spec, axes[0], rows, set_name=summary["set"], tol=tol)
        summary["flips"] = _with_subresonance(spec, axes[0], set_index, flips)
        summary["marks"] = sweep_marks(spec, axes[0], set_index, rows)
    return rows, summary


def fieldsweep_study(
    device: str | Path,
    axes: Sequence[FieldAxis],
    *,
    set_name: str | None = None,
    tol: float = 1e-10,
) -> Study:
    """The study of ``axes`` of the device file ``device`` (one or two fields).

    Parameters
    ----------
    device : path
        The device YAML file.
    axes : sequence of FieldAxis
        One or two axes (:func:`parse_axis`).
    set_name : str, optional
        The actuator set studied (default: the first).
    tol : float
        Fixed-point residual accepted [-].

    Returns
    -------
    Study
        Tasks in row-major order of the grid (the first axis slowest); its parameters
        (recorded for resume) name the file, its content hash, the set and the grids.
    """
    from betvdesign.spec.loader import load_device

    spec = load_device(device)
    index, set_name = _set_index(spec, set_name)
    tasks = field_tasks(spec, axes, index, tol)
    digest = hashlib.sha256(Path(device).read_bytes()).hexdigest()[:16]
    params = {
        "device": str(device),
        "device_sha256": digest,
        "set": set_name,
        "tol": tol,
        "axes": {a.field: {"unit": a.unit, "values": list(a.values)} for a in axes},
    }
    return Study("fieldsweep", columns(axes), params, tasks, fieldsweep_point)


@dataclass(frozen=True)
class Flip:
    """A change of the exact mode along one field, bisected.

    Attributes
    ----------
    field : str
        The field.
    at : float
        Where the mode changes [the field's unit] (to :data:`FLIP_RTOL`).
    below, above : str
        The exact mode below and above it.
    bracket : tuple of float, optional
        The bisection's last bracket [the field's unit]: ``below`` holds at its first
        end, ``above`` at its second (``at`` is its midpoint).
    """

    field: str
    at: float
    below: str
    above: str
    bracket: tuple[float, float] | None = None

    def as_dict(self) -> dict[str, Any]:
        """The crossing as JSON-friendly data."""
        out = {"field": self.field, "at": self.at, "below": self.below, "above": self.above}
        if self.bracket is not None:
            out["bracket"] = list(self.bracket)
        return out


def _mode_at(spec: Any, axis: FieldAxis, x: float, index: int, tol: float) -> str:
    from betvdesign.nondim.device import derive_set

    try:
        s = with_values(spec, {axis.field: axis.quantity(x)})
        d = derive_set(s, s.actuator_sets[index])
    except (BetvError, ValueError):
        return "invalid"
    task = {"key": 0, **d.params.as_dict(), "tol": tol, "travel_s": _travel_s(d)}
    head = _head_record(d)
    if head is not None:  # the check's verdict of this point is the coupled head's
        task = {"key": 0, **head, "tol": tol}
    return exact_mode(travel_point(task))


def locate_flips(
    device: Any,
    axis: FieldAxis,
    rows: Sequence[Mapping[str, Any]],
    *,
    set_name: str | None = None,
    tol: float = 1e-10,
) -> list[Flip]:
    """Every change of the exact mode along a 1-D sweep, bisected.

    Every change of the exact mode between neighbouring points of a 1-D sweep,
    bisected along the field to :data:`FLIP_RTOL` of the field's range.

    Parameters
    ----------
    device : path or DeviceSpec
        The device file the sweep was made of (or the loaded device).
    axis : FieldAxis
        The swept field.
    rows : sequence of mapping
        The sweep's rows, in grid order.
    set_name : str, optional
        The set swept (default: the first).
    tol : float
        Fixed-point residual accepted [-].

    Returns
    -------
    list of Flip
        In ascending order of the field.
    """
    from betvdesign.spec.loader import load_device

    spec = load_device(device) if isinstance(device, str | Path) else device
    index, _ = _set_index(spec, set_name)
    span = axis.values[-1] - axis.values[0]
    out = []
    width = FLIP_RTOL * span
    for a, b in itertools.pairwise(rows):
        lo, ma = float(a[axis.label]), a["exact_mode"]
        hi, mb = float(b[axis.label]), b["exact_mode"]
        # a third mode met in between ends a bracket: go on from it until ``b``'s mode
        # (e.g. push -> no crossing -> pull: the speed passes through zero), each change
        # located; at most a few modes lie between two grid points
        for _ in range(len(MODES) + 1):
            if ma == mb or abs(hi - lo) <= width:
                break
            br = bisect(lambda x: _mode_at(spec, axis, x, index, tol), lo, hi, ma, mb, width=width)
            out.append(Flip(axis.field, br.mid, ma, br.at_b, (br.a, br.b)))
            lo, ma = br.b, br.at_b
    return out


def summarise(
    set_name: str, axes: Sequence[FieldAxis], rows: Sequence[Mapping[str, Any]]
) -> dict[str, Any]:
    """A sweep's summary.

    A sweep's summary: the set, each axis (field, unit, device value, range, points),
    the points and their count per exact mode and per model (``coupled``: the drawn
    head's, as ``betv check`` of such a set; ``decoupled``: the paper's springs), and
    what the speed is.

    Parameters
    ----------
    set_name : str
        The actuator set.
    axes : sequence of FieldAxis
        The swept fields.
    rows : sequence of mapping
        The sweep's rows.

    Returns
    -------
    dict
        JSON-friendly summary.
    """
    counts = {m: 0 for m in (*MODES, "invalid")}
    for r in rows:
        counts[r["exact_mode"]] = counts.get(r["exact_mode"], 0) + 1
    return {
        "set": set_name,
        "fields": [
            {
                "field": a.field,
                "column": a.label,
                "unit": a.unit,
                "device_value": a.x0,
                "lo": a.values[0],
                "hi": a.values[-1],
                "points": len(a.values),
            }
            for a in axes
        ],
        "points": len(rows),
        "modes": {k: v for k, v in counts.items() if v},
        "models": dict(sorted(Counter(r["model"] for r in rows if r.get("model")).items())),
        "speed": "the travel answer's |Δs|·u·cosθ·f_act [m/s]: a magnitude, the mode (push: "
        "along the impacts, pull: against them) says which way",
    }


def run_fieldsweep(
    device: str | Path,
    axes: Sequence[FieldAxis],
    **kwargs: Any,
) -> tuple[StudyRun, dict[str, Any]]:
    """Run :func:`fieldsweep_study` and summarise it.

    Run :func:`fieldsweep_study` (executor, ``out``, resume as every study) and
    summarise it.

    Parameters
    ----------
    device : path
        The device file.
    axes : sequence of FieldAxis
        One or two axes.
    **kwargs
        ``set_name``, ``tol``, and :class:`~betvdesign.studies.engine.runner.RunArgs`.

    Returns
    -------
    tuple of (StudyRun, dict)
        The run and its summary: counts per exact mode, the device's own point, and for
        one axis the flips (:func:`locate_flips`) and the marks (:func:`sweep_marks`).
    """
    study_kw, run_kw = split_run_args(kwargs)
    study = fieldsweep_study(device, axes, **study_kw)
    run = run_study(study, **run_kw)
    summary: dict[str, Any] = {
        "device": str(device),
        **summarise(study.parameters["set"], axes, run.rows),
    }
    if len(axes) == 1:
        flips = locate_flips(
            device,
            axes[0],
            run.rows,
            **{k: v for k, v in study_kw.items() if k in ("set_name", "tol")},
        )
        spec = _spec_of(device)
        index, _ = _set_index(spec, study.parameters["set"])
        summary["flips"] = _with_subresonance(spec, axes[0], index, flips)
        summary["marks"] = sweep_marks(spec, axes[0], index, run.rows)
    return run, summary


def _spec_of(device: Any) -> Any:
    from betvdesign.spec.loader import load_device

    return load_device(device) if isinstance(device, str | Path) else device


#: Points per bracket and rounds of the vectorised refinement of a level crossing
#: (:func:`_crossings`): a grid cell shrinks 32³ times, then linear interpolation.
_REFINE_POINTS = 33
_REFINE_ROUNDS = 3


def _a_varpi(spec: Any, axis: FieldAxis, index: int, xs: np.ndarray) -> np.ndarray:
    """ϖ and α·ϖ² [-] of the device at the field values ``xs`` [unit].

    Shape (n, 2); nan where the point cannot be derived (the derivation of the sweep's
    grid, :func:`_derive_grid`).
    """
    from dataclasses import replace

    _, recs = _derive_grid(spec, [replace(axis, values=tuple(float(x) for x in xs))], index)
    out = np.full((len(recs), 2), np.nan)
    for j, rec in enumerate(recs):
        if not isinstance(rec, str):
            out[j] = rec["varpi"], rec["alpha"] * rec["varpi"] ** 2
    return out


def _crossings(
    spec: Any, axis: FieldAxis, index: int, column: int, levels: Sequence[float]
) -> list[tuple[int, float]]:
    """Where ϖ (``column`` 0) or α·ϖ² (1) crosses each of ``levels`` along the axis.

    Every grid cell whose ends lie on both sides of a level (one end below it, the other
    at or above it) is refined at once for all
    cells: :data:`_REFINE_ROUNDS` rounds of :data:`_REFINE_POINTS` points (one vectorised
    derivation each), then linear interpolation in the last sub-cell.

    Returns
    -------
    list of (int, float)
        (index of the level, the field's value there [unit]), ascending in the field.
    """
    xs = np.asarray(axis.values, dtype=float)
    ys = _a_varpi(spec, axis, index, xs)[:, column]
    cells = [
        (k, float(xs[i]), float(xs[i + 1]))
        for k, lv in enumerate(levels)
        for i in range(len(xs) - 1)
        if np.isfinite(ys[i]) and np.isfinite(ys[i + 1]) and (ys[i] >= lv) != (ys[i + 1] >= lv)
    ]
    if not cells:
        return []
    t = np.linspace(0.0, 1.0, _REFINE_POINTS)
    for _ in range(_REFINE_ROUNDS + 1):
        pts = np.concatenate([a + (b - a) * t for _, a, b in cells])
        vals = _a_varpi(spec, axis, index, pts)[:, column].reshape(len(cells), -1)
        nxt = []
        for (k, a, b), v in zip(cells, vals, strict=True):
            d = v - levels[k]
            i = int(np.flatnonzero((d[:-1] >= 0) != (d[1:] >= 0))[0])
            xa, xb = a + (b - a) * t[i], a + (b - a) * t[i + 1]
            nxt.append((k, xa, xb, d[i], d[i + 1]))
        cells = [(k, xa, xb) for k, xa, xb, _, _ in nxt]
    out = [(k, float(xa + (xb - xa) * da / (da - db))) for k, xa, xb, da, db in nxt]
    out = [(k, x) for k, x in out if math.isfinite(x)]  # a sub-cell the model cannot take
    return sorted(out, key=lambda kx: kx[1])


def _with_subresonance(
    spec: Any, axis: FieldAxis, index: int, flips: Sequence[Flip]
) -> list[dict[str, Any]]:
    """The flips as data, each with the sub-resonance it sits near.

    ``subresonance``: the order n of the sub-resonance α·ϖ² = 1/n² a flip sits near
    (:func:`~betvdesign.model.domain.nearest_subresonance`), or None.
    """
    out = [f.as_dict() for f in flips]
    if out:
        q = _a_varpi(spec, axis, index, np.array([f.at for f in flips]))[:, 1]
        for d, qi in zip(out, q, strict=True):
            d["subresonance"] = nearest_subresonance([float(qi)]) if np.isfinite(qi) else None
    return out


def _intervals(
    lo: float, hi: float, inside_at_lo: bool, edges: Sequence[float]
) -> list[list[float]]:
    """The parts of [lo, hi] inside a region entered or left at each of ``edges``."""
    out: list[list[float]] = []
    start, inside = float(lo), inside_at_lo
    for e in edges:
        if inside:
            out.append([start, float(e)])
        else:
            start = float(e)
        inside = not inside
    if inside:
        out.append([start, float(hi)])
    return out


def sweep_marks(
    spec: Any, axis: FieldAxis, index: int, rows: Sequence[Mapping[str, Any]]
) -> dict[str, Any]:
    """What a 1-D sweep's figure marks along its field, located in the field.

    Parameters
    ----------
    spec : DeviceSpec
        The device swept.
    axis : FieldAxis
        The swept field.
    index : int
        The actuator set's index.
    rows : sequence of mapping
        The sweep's rows (their ``zeta_h`` says whether the head is undamped).

    Returns
    -------
    dict
        ``window``: the parts of the range inside the design window 0.5 ≤ ϖ < 2, as
        [lo, hi] [unit]; ``subresonances``: ``{"n", "at"}`` where α·ϖ² = 1/n²
        (f_act = f_h/n; n ≤ :data:`~betvdesign.model.domain.SUBRESONANCE_ORDERS`);
        ``undamped_resonance``: for an undamped head (ζ_h = 0), the parts of the range
        where |α·ϖ² − 1| < :data:`~betvdesign.model.domain.TANGENTIAL_DETUNING` (there the
        idealised model's tangential motion barely stays bounded: its speed is not the
        device's), else [].
    """
    lo, hi = axis.values[0], axis.values[-1]
    first = _a_varpi(spec, axis, index, np.array([lo]))[0]
    edges = [x for _, x in _crossings(spec, axis, index, 0, VARPI_WINDOW)]
    in_window = bool(VARPI_WINDOW[0] <= first[0] < VARPI_WINDOW[1])
    levels = [subresonance_level(n) for n in range(1, SUBRESONANCE_ORDERS + 1)]
    subres = [{"n": k + 1, "at": x} for k, x in _crossings(spec, axis, index, 1, levels)]
    undamped = any(not r.get("zeta_h") for r in rows if r.get("status") != "invalid")
    band: list[list[float]] = []
    if undamped:
        d = TANGENTIAL_DETUNING
        near = [x for _, x in _crossings(spec, axis, index, 1, (1.0 - d, 1.0 + d))]
        band = _intervals(lo, hi, bool(abs(first[1] - 1.0) < d), near)
    return {
        "window": _intervals(lo, hi, in_window, edges),
        "subresonances": subres,
        "undamped_resonance": band,
    }
