"""Derivation steps of the optional terms beyond the paper's idealisation (MODEL.md):
the thermal roll-off of the stroke, head damping and the restitution of normal impacts.

Part of the nondim layer (:mod:`betvdesign.nondim.device` calls it; like it, it strips units):
every input and computed value goes into the derivation record with the spec field it
comes from. Absent fields record nothing, so a device without them derives exactly as
before they existed. Works on floats and on arrays of samples alike
(:func:`betvdesign.nondim.device.derive_samples`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pint

from betvdesign.model import damping
from betvdesign.model import rolloff as _rolloff
from betvdesign.model.params import normal_force_phase
from betvdesign.nondim.record import Recorder, cached_unit
from betvdesign.spec.models import Actuator, ActuatorSet
from betvdesign.spec.units import ureg


def rolloff(
    rec: Recorder, act: Actuator, f_act: pint.Quantity, u_cal: pint.Quantity, samples: bool
) -> tuple[pint.Quantity, dict[str, float]]:
    """u = u_cal·H(f_act)/H(f_cal) (MODEL.md, "Thermal roll-off of the actuator"), every
    quantity recorded; also the cut-off and calibration frequency [Hz] for the scales."""
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
            ureg.Quantity(_rolloff.cutoff_from_time_constant(mag(tau, "s")), cached_unit("Hz")),
            ("τ_th",),
            "Hz",
        )
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
            _rolloff.gain(mag(f, "Hz"), fc_hz),
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


def mag(q: pint.Quantity, unit: str) -> Any:
    """Magnitude of ``q`` in ``unit``: a float, or an array of samples."""
    m = q.to(cached_unit(unit)).magnitude
    return float(m) if np.ndim(m) == 0 else np.asarray(m, dtype=float)


def _number(x: Any) -> pint.Quantity:
    return ureg.Quantity(x, cached_unit(""))


def damping_terms(rec: Recorder, aset: ActuatorSet, varpi: Any) -> tuple[Any, Any, Any]:
    """ζ_v, ζ_h [-] of the head's normal and tangential oscillators and the restitution
    e [-] of normal impacts (0 where the spec gives none), each recorded with its spec
    field: a quality factor Q with ζ = 1/(2Q), a damping ratio ζ > 0 with Q = 1/(2ζ); with
    ζ_v > 0 also the contact normal force's phase δ = atan(2ζ_v ϖ) and amplitude factor
    A = sqrt(1 + (2ζ_v ϖ)²) (N ∝ A·sin(ϖτ_o + δ); MODEL.md, "Beyond the paper's
    idealisation"). ``varpi``: ϖ [-], a float or an array of samples."""
    act = aset.actuator
    zetas = []
    for sub, word in (("v", "normal"), ("h", "tangential")):
        what = f"of the head's {word} oscillator"
        z_sym, q_sym = f"ζ_{sub}", f"Q_{sub}"
        q_given = getattr(act, f"quality_factor_{word}")
        z_given = getattr(act, f"damping_ratio_{word}")
        if q_given is not None:
            q = rec.spec(
                q_sym, f"quality factor {what}", f"actuator.quality_factor_{word}", _number(q_given)
            )
            z = rec.add(
                z_sym,
                f"damping ratio {what}",
                f"1/(2·{q_sym})",
                damping.zeta_from_quality(mag(q, "")),
                (q_sym,),
                "",
            )
        elif z_given is not None:
            z = rec.spec(
                z_sym, f"damping ratio {what}", f"actuator.damping_ratio_{word}", _number(z_given)
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
        zetas.append(mag(z, ""))
    zeta_v, zeta_h = zetas
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
