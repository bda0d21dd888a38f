"""Derivation steps of the optional terms beyond the paper's idealisation.

Derivation steps of the optional terms beyond the paper's idealisation (MODEL.md,
"Beyond the paper's idealisation"): the thermal roll-off of the stroke, head damping and
the restitution of normal impacts.

A concept of its own beside the paper's relations (:mod:`betvdesign.nondim.device`,
which calls these steps; like it, it strips units): the terms are optional, and absent
fields record nothing, so a device without them derives exactly as the paper's model.
Every input and computed value goes into the derivation record with the spec field it
comes from. Works on floats and on arrays of samples alike
(:func:`betvdesign.nondim.device.derive_samples`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pint

from betvdesign.model import damping
from betvdesign.model import rolloff as first_order
from betvdesign.model.params import normal_force_phase
from betvdesign.nondim.record import Recorder, cached_unit, mag
from betvdesign.spec.models import Actuator, ActuatorSet
from betvdesign.spec.units import ureg


def _cutoff(rec: Recorder, act: Actuator) -> pint.Quantity:
    """Record the thermal cut-off f_c [Hz]: given, or 1/(2π·τ_th) from the time constant.

    Parameters
    ----------
    rec : Recorder
        The record being built.
    act : Actuator
        The actuator (thermal cut-off [Hz] or time constant [s]).

    Returns
    -------
    pint.Quantity
        f_c [Hz].
    """
    if act.thermal_cutoff is not None:
        f_c = rec.spec(
            "f_c", "thermal cut-off of the stroke", "actuator.thermal_cutoff", act.thermal_cutoff
        )
    else:
        tau = rec.spec(
            "τ_th",
            "thermal time constant of the actuator",
            "actuator.thermal_time_constant",
            act.thermal_time_constant.to(cached_unit("ms")),
        )
        f_c = rec.add(
            "f_c",
            "thermal cut-off of the stroke",
            "1/(2π·τ_th)",
            ureg.Quantity(first_order.cutoff_from_time_constant(mag(tau, "s")), cached_unit("Hz")),
            ("τ_th",),
            "Hz",
        )
    return f_c


def rolloff(
    rec: Recorder, act: Actuator, f_act: pint.Quantity, u_cal: pint.Quantity, samples: bool
) -> tuple[pint.Quantity, dict[str, float]]:
    """The stroke at the actuation frequency: u = u_cal·H(f_act)/H(f_cal).

    H(f) = 1/sqrt(1 + (f/f_c)²) is the first-order thermal roll-off with cut-off f_c
    (given, or f_c = 1/(2π·τ_th)); f_cal is the actuation frequency the amplitude or
    calibration was measured at. Records f_c (τ_th), f_cal, H(f_act), H(f_cal) and u.

    Parameters
    ----------
    rec : Recorder
        The record being built.
    act : Actuator
        The actuator (thermal cut-off [Hz] or time constant [s], calibration
        frequency [Hz]).
    f_act : pint.Quantity
        Actuation frequency [Hz].
    u_cal : pint.Quantity
        Amplitude at the calibration frequency [m].
    samples : bool
        True for arrays of samples (then no frequencies are returned for the scales).

    Returns
    -------
    tuple
        u [um], and ``{"cutoff_hz": f_c, "calibration_hz": f_cal}`` [Hz] for the
        scales (empty for samples).

    References
    ----------
    MODEL.md, "Beyond the paper's idealisation" (thermal roll-off of the actuator).
    """
    f_c = _cutoff(rec, act)
    f_cal = rec.spec(
        "f_cal",
        "actuation frequency of the amplitude calibration",
        "actuator.calibration_frequency",
        act.calibration_frequency,
    )
    fc_hz = mag(f_c, "Hz")
    h_act, h_cal = (
        rec.add(
            f"H({name})",
            f"first-order thermal roll-off at {name}",
            f"1/sqrt(1 + ({name}/f_c)²)",
            first_order.gain(mag(f, "Hz"), fc_hz),
            (name, "f_c"),
            "",
        )
        for name, f in (("f_act", f_act), ("f_cal", f_cal))
    )
    u = rec.add(
        "u",
        "actuator amplitude at f_act (thermal roll-off)",
        "u_cal·H(f_act)/H(f_cal)",
        u_cal * (h_act / h_cal),
        ("u_cal", "H(f_act)", "H(f_cal)"),
        "um",
    )
    if samples:
        return u, {}
    return u, {"cutoff_hz": float(fc_hz), "calibration_hz": mag(f_cal, "Hz")}


def _number(x: Any) -> pint.Quantity:
    return ureg.Quantity(x, cached_unit(""))


def damping_ratio(
    rec: Recorder, sub: str, word: str, quality: float | None, ratio: float | None
) -> Any:
    """The damping ratio of one of the head's oscillators: ζ = 1/(2Q), or given.

    A quality factor Q is recorded with ζ = 1/(2Q); a given ζ > 0 with Q = 1/(2ζ).

    Parameters
    ----------
    rec : Recorder
        The record being built.
    sub : str
        ``"v"`` (normal) or ``"h"`` (tangential): the symbols' subscript.
    word : str
        ``"normal"`` or ``"tangential"``: the spec fields' suffix.
    quality : float or None
        The spec's ``quality_factor_<word>`` Q [-].
    ratio : float or None
        The spec's ``damping_ratio_<word>`` ζ [-].

    Returns
    -------
    float or numpy.ndarray
        ζ [-]; 0 when the spec gives neither.

    References
    ----------
    MODEL.md, "Beyond the paper's idealisation" (damping).
    """
    what = f"of the head's {word} oscillator"
    z_sym, q_sym = f"ζ_{sub}", f"Q_{sub}"
    if quality is not None:
        q = rec.spec(
            q_sym, f"quality factor {what}", f"actuator.quality_factor_{word}", _number(quality)
        )
        z = rec.add(
            z_sym,
            f"damping ratio {what}",
            f"1/(2·{q_sym})",
            damping.zeta_from_quality(mag(q, "")),
            (q_sym,),
            "",
        )
    elif ratio is not None:
        z = rec.spec(
            z_sym, f"damping ratio {what}", f"actuator.damping_ratio_{word}", _number(ratio)
        )
        if np.all(mag(z, "") > 0.0):
            rec.add(
                q_sym,
                f"quality factor {what}",
                f"1/(2·{z_sym})",
                damping.quality_from_zeta(mag(z, "")),
                (z_sym,),
                "",
            )
    else:
        z = _number(0.0)
    return mag(z, "")


def damping_terms(rec: Recorder, aset: ActuatorSet, varpi: Any) -> tuple[Any, Any, Any]:
    """The head's damping ratios ζ_v, ζ_h and the restitution e of normal impacts.

    Each is recorded with its spec field (:func:`damping_ratio`; e as given). With
    ζ_v > 0 also the contact normal force's phase δ = atan(2ζ_v·ϖ) and amplitude factor
    A = sqrt(1 + (2ζ_v·ϖ)²): N ∝ A·sin(ϖτ_o + δ) (not needed for samples).

    Parameters
    ----------
    rec : Recorder
        The record being built.
    aset : ActuatorSet
        The actuator set (its actuator's damping, its contact's restitution).
    varpi : float or numpy.ndarray
        ϖ [-].

    Returns
    -------
    tuple
        ζ_v, ζ_h, e [-] (floats or arrays of samples; 0 where the spec gives none).

    References
    ----------
    MODEL.md, "Beyond the paper's idealisation" (damping, restitution).
    """
    act = aset.actuator
    zeta_v = damping_ratio(rec, "v", "normal", act.quality_factor_normal, act.damping_ratio_normal)
    zeta_h = damping_ratio(
        rec, "h", "tangential", act.quality_factor_tangential, act.damping_ratio_tangential
    )
    e = 0.0
    if aset.contact.restitution is not None:
        e = mag(
            rec.spec(
                "e",
                "coefficient of restitution of normal impacts",
                "contact.restitution",
                _number(aset.contact.restitution),
            ),
            "",
        )
    if np.ndim(zeta_v) == np.ndim(varpi) == 0 and zeta_v > 0.0:  # not needed for samples
        delta, amplitude = normal_force_phase(zeta_v, varpi)
        deg = f" = {math.degrees(delta):.4g}°"
        rec.add(
            "δ",
            f"phase lead of the contact normal force N ∝ A·sin(ϖτ_o + δ){deg}",
            "atan(2·ζ_v·ϖ)",
            ureg.Quantity(delta, cached_unit("rad")),
            ("ζ_v", "ϖ"),
            "rad",
        )
        rec.add(
            "A",
            "amplitude factor of the contact normal force (1 undamped)",
            "sqrt(1 + (2·ζ_v·ϖ)²)",
            amplitude,
            ("ζ_v", "ϖ"),
            "",
        )
    return zeta_v, zeta_h, e
