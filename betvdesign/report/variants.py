"""The device with one designer field changed: the robustness sweep's inputs.

A designer sets drive frequencies, resonances, friction surfaces and beam widths, not
α or β. The fields are those of :data:`betvdesign.spec.fields.FIELDS` (the one list,
also ``betv fix``'s): per physical quantity the first field the actuator set gives, of
those that move ϖ, α, β or κ (:func:`shown_fields`). The variants of a field are the
points of a one-field sweep (:func:`betvdesign.studies.fieldsweep.field_tasks`: the spec
with the field changed, derived by :mod:`betvdesign.nondim.device`'s formulas on arrays,
the only place units are stripped); a value the model cannot take (e.g. an impact angle
past 90°, a voltage beyond a measured calibration) is kept with its reason, never dropped.
The flips between variants are bisected through the validated what-if path
(:meth:`betvdesign.spec.models.DeviceSpec.replace`).
"""

from __future__ import annotations

import itertools
from typing import Any

import numpy as np
import pint

from betvdesign import dynamics
from betvdesign.errors import BetvError
from betvdesign.model.bisection import bisect
from betvdesign.model.domain import mode_of
from betvdesign.model.params import ModelParams
from betvdesign.nondim.device import derive_set
from betvdesign.report.analysis import FieldFlip, FieldSweep, FieldVariant, ReportOptions
from betvdesign.spec.fields import FIELDS
from betvdesign.spec.models import DeviceSpec
from betvdesign.spec.paths import given, in_set, numeric
from betvdesign.spec.units import format_quantity
from betvdesign.studies.fieldsweep import FieldAxis, field_tasks
from betvdesign.studies.sampling import PARAM_FIELDS

#: Width [-] of the relative-change bracket to which a robustness flip is bisected.
FLIP_WIDTH = 1e-3


def shown_fields(spec: DeviceSpec, set_index: int) -> list[tuple[str, Any]]:
    """The fields the sweep varies in actuator set ``set_index`` and their values.

    Parameters
    ----------
    spec : DeviceSpec
        The device.
    set_index : int
        Index of the actuator set.

    Returns
    -------
    list of (str, value)
        Field path (as in :data:`~betvdesign.spec.fields.FIELDS`) and its value in the
        set, in the list's order: per quantity the first numeric field the set gives, of
        the fields that move a model parameter.
    """
    out: list[tuple[str, Any]] = []
    done: set[str] = set()
    for f in FIELDS:
        if not f.moves_model or f.quantity in done:
            continue
        values = given(spec, in_set(f.path, set_index))
        if values and numeric(values[0]):
            out.append((f.path, values[0]))
            done.add(f.quantity)
    return out


def relative_changes(points: int, span: float) -> np.ndarray:
    """``points`` relative changes evenly over [−span, +span], 0 (the device) included."""
    n = max(points, 3) | 1  # odd: the nominal device sits in the middle
    return np.linspace(-span, span, n)


def field_variants(spec: DeviceSpec, set_index: int, changes: np.ndarray) -> list[FieldVariant]:
    """Variants of actuator set ``set_index`` of ``spec``: each field of
    :func:`shown_fields` scaled by (1 + change).

    Each field's variants are derived at once, as the field sweeps derive their points
    (:func:`betvdesign.studies.fieldsweep.field_tasks`: the derivation's own formulas on
    arrays, a value the spec cannot take kept with its reason); the 0 % variant is the
    device's own derivation.
    """
    own = derive_set(spec, spec.actuator_sets[set_index])
    out: list[FieldVariant] = []
    for field, nominal in shown_fields(spec, set_index):
        shown = (
            format_quantity(nominal, ".4g")
            if isinstance(nominal, pint.Quantity)
            else f"{nominal:g}"
        )
        factors = [1.0 + float(r) for r in changes]
        axis = FieldAxis.scaled(in_set(field, set_index), nominal, factors)
        for r, task in zip(changes, field_tasks(spec, [axis], set_index), strict=True):
            if r == 0:
                speed_per_ds = own.scales.length_m * own.scales.f_act_hz
                out.append(FieldVariant(field, shown, 0.0, own.params, speed_per_ds))
            elif "invalid" in task:
                reason = str(task["invalid"]).splitlines()[0]
                out.append(FieldVariant(field, shown, float(r), None, reason=reason))
            else:
                params = ModelParams(**{k: task[k] for k in PARAM_FIELDS})
                speed_per_ds = task["length_m"] * task["f_act_hz"]
                out.append(FieldVariant(field, shown, float(r), params, speed_per_ds))
    return out


def mode_at_change(
    spec: DeviceSpec, set_index: int, field: str, change: float, opts: ReportOptions
) -> str:
    """The exact mode of the device with ``field`` of set ``set_index`` scaled by
    (1 + ``change``): the periodic orbit's Δs read by :func:`~betvdesign.model.domain.
    mode_of`, or "no orbit" (the spec refuses the value or the orbit does not converge).
    """
    path = in_set(field, set_index)
    nominal = given(spec, path)[0]
    try:
        changed = spec.replace(path, nominal * (1.0 + change))
        sd = derive_set(changed, changed.actuator_sets[set_index])
    except BetvError:
        return "no orbit"
    res = dynamics.periodic_orbit(
        sd.params, tol=opts.periodic_tol, max_cycles=opts.sweep_max_cycles
    )
    mode = mode_of(res.delta_s) if res.success else None
    return mode or "no orbit"


def locate_flips(
    spec: DeviceSpec, set_index: int, sweep: FieldSweep, opts: ReportOptions
) -> FieldSweep:
    """The sweep with every change of the exact mode between neighbouring changes of a
    field bisected to :data:`FLIP_WIDTH` (a third mode met inside a bracket ends it).

    Parameters
    ----------
    spec : DeviceSpec
        The device.
    set_index : int
        Index of the actuator set.
    sweep : FieldSweep
        The robustness sweep of that set (:func:`~betvdesign.report.analysis.robustness`).
    opts : ReportOptions
        The periodic orbit's tolerance and cycle budget.

    Returns
    -------
    FieldSweep
        ``sweep`` with its ``flips``.
    """
    flips: list[FieldFlip] = []
    for f in sweep.fields:
        pts = [p for p in sweep.points if p.field == f]
        for a, b in itertools.pairwise(pts):
            ma, mb = a.mode or "no orbit", b.mode or "no orbit"
            if ma == mb:
                continue
            br = bisect(
                lambda r, f=f: mode_at_change(spec, set_index, f, r, opts),
                a.change,
                b.change,
                ma,
                mb,
                width=FLIP_WIDTH,
            )
            half = 0.5 * FLIP_WIDTH
            flips.append(FieldFlip(f, br.mid - half, br.mid + half, ma, br.at_b))
    return FieldSweep(sweep.points, sweep.n_orbits, tuple(flips))
