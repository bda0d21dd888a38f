"""Monte Carlo samples in spec space.

Monte Carlo samples in spec space: nominal values, seeded draws, and every sample of
an actuator set derived at once.

Used by ``betv tolerance`` (:mod:`betvdesign.studies.tolerance`) and the robust search
of ``betv fix``. Samples are drawn with one seeded ``numpy.random.Generator``, fields in
the order given; :func:`derive_all` pushes them through
:func:`betvdesign.nondim.device.derive_samples` (the derivation's own formulas on arrays).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pint

from betvdesign.errors import BetvError, UsageError
from betvdesign.model.params import ModelParams
from betvdesign.spec import limits
from betvdesign.spec.paths import given, numeric, with_values


def nominal_values(spec: Any, tolerances: Sequence[Any]) -> dict[str, tuple[float, str]]:
    """Nominal magnitude and unit of each toleranced field (checked against the spec).

    Parameters
    ----------
    spec : DeviceSpec
        The nominal device.
    tolerances : sequence of Tolerance
        The toleranced fields (:class:`betvdesign.studies.tolerance.Tolerance`).

    Returns
    -------
    dict of str to (float, str)
        Per field path: its magnitude and unit as the device file gives it ("" for a
        unit-less field).

    Raises
    ------
    UsageError
        A field given twice, not numeric, or with different values in different sets.
    """
    out: dict[str, tuple[float, str]] = {}
    for tol in tolerances:
        if tol.field in out:
            raise UsageError(f"{tol.source}: {tol.field}: given twice")
        present = given(spec, tol.field)
        if not present or not all(numeric(v) for v in present):
            raise UsageError(
                f"{tol.source}: {tol.field}: not a numeric field of device {spec.name!r} "
                "(write it as in the device file, e.g. slider.beam_width, head.mass, "
                "contact.friction, actuator.vertical_resonance, drive.frequency)"
            )
        first = present[0]
        if any(v != first for v in present):
            raise UsageError(
                f"{tol.source}: {tol.field}: differs between actuator sets; "
                "tolerances apply to fields with one nominal value"
            )
        if isinstance(first, pint.Quantity):
            out[tol.field] = (float(first.magnitude), f"{first.units:~}")
        else:
            out[tol.field] = (float(first), "")
    return out


def draw(
    tolerances: Sequence[Any],
    nominal: Mapping[str, tuple[float, str]],
    n: int,
    seed: int,
) -> np.ndarray:
    """Sampled magnitudes in each field's nominal unit.

    One seeded ``Generator``; fields drawn in the order given: normal
    ``x0(1 + r·z)`` or ``x0 + a·z``; uniform with half-width r or a.

    Parameters
    ----------
    tolerances : sequence of Tolerance
        The fields' distributions: relative r [-] or absolute a [the field's unit].
    nominal : mapping of str to (float, str)
        :func:`nominal_values`.
    n : int
        Number of samples.
    seed : int
        Seed of the generator.

    Returns
    -------
    numpy.ndarray
        Shape (n, len(tolerances)) [each field's nominal unit].

    Raises
    ------
    UsageError
        An absolute tolerance not in the field's units, or not > 0.
    """
    from betvdesign.spec.units import parse_quantity

    rng = np.random.default_rng(limits.check_seed(seed))
    cols = []
    for tol in tolerances:
        x0, unit = nominal[tol.field]
        z = rng.standard_normal(n) if tol.dist == "normal" else rng.uniform(-1.0, 1.0, n)
        if tol.relative is not None:
            cols.append(x0 * (1.0 + tol.relative * z))
            continue
        try:
            q = parse_quantity(str(tol.absolute))  # bounded: no unit-expression bombs
            a = float(q.to(unit).magnitude) if unit else float(q.to("dimensionless").magnitude)
        except (pint.PintError, ValueError, TypeError, AttributeError) as exc:
            raise UsageError(
                f"{tol.source}: {tol.field}: absolute tolerance {tol.absolute!r} "
                f"not in units of {unit or 'a plain number'}: {exc}"
            ) from None
        if not (math.isfinite(a) and a > 0):
            raise UsageError(f"{tol.source}: {tol.field}: tolerance must be > 0")
        cols.append(x0 + a * z)
    return np.column_stack(cols) if cols else np.empty((n, 0))


def check_sample(values: Mapping[str, tuple[float, str]]) -> None:
    """Refuse a sample the spec cannot take.

    Parameters
    ----------
    values : mapping of str to (float, str)
        Sampled magnitude and unit per field path.

    Raises
    ------
    BetvError
        A non-positive value, or an impact angle ≥ 90° [deg].
    """
    for field, (mag, unit) in values.items():
        if mag <= 0.0:
            raise BetvError(f"{field} sampled non-positive ({mag:g} {unit})")
        if field == "contact.impact_angle":
            from betvdesign.spec.units import ureg

            if ureg.Quantity(mag, unit).to("deg").magnitude >= 90.0:
                raise BetvError(f"{field} sampled at or above 90° ({mag:g} {unit})")


def derive_all(
    spec: Any,
    tolerances: Sequence[Any],
    nominal: Mapping[str, tuple[float, str]],
    x: np.ndarray,
    set_index: int,
) -> dict[str, np.ndarray] | None:
    """Every sample of one set derived at once (nondim.derive_samples).

    Parameters
    ----------
    spec : DeviceSpec
        The nominal device.
    tolerances : sequence of Tolerance
        The sampled fields, in the columns' order of ``x``.
    nominal : mapping of str to (float, str)
        :func:`nominal_values`.
    x : numpy.ndarray
        :func:`draw`'s samples, shape (n, fields) [nominal units].
    set_index : int
        Index of the actuator set in ``spec.actuator_sets``.

    Returns
    -------
    dict of str to numpy.ndarray, or None
        Per sample: ϖ, α, β, κ, ζ_v, ζ_h, e [-], ``length_m`` ℓ = u·cosθ [m] and
        ``f_act_hz`` [Hz]; None when some sample cannot be derived that way (then each is
        derived on its own).
    """
    from betvdesign.nondim.device import derive_samples
    from betvdesign.spec.units import ureg

    values = {}
    for j, t in enumerate(tolerances):
        mag, unit = nominal[t.field][0], nominal[t.field][1]
        col = np.where(x[:, j] > 0, x[:, j], mag)  # invalid draws: rejected per task
        values[t.field] = ureg.Quantity(col, unit) if unit else col
    arrays = with_values(spec, values)
    try:
        with np.errstate(all="ignore"):
            d = derive_samples(arrays, arrays.actuator_sets[set_index])
    except (BetvError, ValueError, ArithmeticError):
        return None
    return {k: getattr(d, k) for k in (*PARAM_FIELDS, "length_m", "f_act_hz")}


#: The fields of :class:`ModelParams` (the derived columns :func:`params_of` reads).
PARAM_FIELDS = tuple(f.name for f in dataclasses.fields(ModelParams))


def params_of(derived: Mapping[str, Any], j: int | None = None) -> ModelParams:
    """The model parameters of one sample of :func:`derive_all`'s columns.

    Parameters
    ----------
    derived : mapping
        :func:`derive_all`'s columns, or one sample's floats.
    j : int, optional
        The sample's index (None: ``derived`` holds that sample's floats).

    Returns
    -------
    ModelParams
        The sample's parameters.

    Raises
    ------
    ParameterError
        Values the model cannot take (e.g. a sampled restitution ≥ 1).
    """
    pick = (lambda v: v) if j is None else (lambda v: v[j])
    return ModelParams(**{k: float(pick(derived[k])) for k in PARAM_FIELDS})


def passes_spread_rules(
    p: ModelParams,
    delta_s: float | None,
    intended: str,
    speed_m_s: float | None = None,
    target_speed_m_s: float | None = None,
) -> bool:
    """Whether one set of one Monte Carlo sample passes: the one count of P(pass).

    Parameters
    ----------
    p : ModelParams
        The sample's parameters [-].
    delta_s : float or None
        Δs of its exact periodic orbit [-] (None: no orbit).
    intended : str
        The set's intended mode.
    speed_m_s : float, optional
        Its speed [m/s] (needed with a target).
    target_speed_m_s : float, optional
        The target speed [m/s].

    Returns
    -------
    bool
        The frequency window 0.5 ≤ ϖ < 2 and the tangential resonance
        |a·ϖ² − 1| ≥ 0.1 hold, the exact mode is the intended one and, with a target,
        the speed reaches it (:data:`betvdesign.studies.fixrules.SPREAD_RULES`).
    """
    from betvdesign.model.domain import (
        TANGENTIAL_DETUNING,
        in_window,
        mode_of,
        resonance_detuning,
    )

    if not in_window(p.varpi) or resonance_detuning(p)[1] < TANGENTIAL_DETUNING:
        return False
    if delta_s is None or mode_of(delta_s) != intended:
        return False
    return target_speed_m_s is None or (
        speed_m_s is not None and abs(speed_m_s) >= target_speed_m_s
    )
