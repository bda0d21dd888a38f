"""Device spec -> dimensionless model parameters, scales and a derivation record.

The only module that strips units (with :mod:`betvdesign.nondim.terms`, the optional
terms). The paper's relations (MODEL.md, "Physical quantities", "Device-to-parameter
relations", "Dimensionless model"; Shin et al., J. Appl. Phys. 96, 7603 (2004),
doi:10.1063/1.1809773) are one step each, in the order :func:`derive_set` takes them:

1. :func:`slider_mass`          M = (n·ρ·L·w·t + m_extra)/2
2. :func:`head_mass`            m given, or ρ_head·V_head; with a drawn actuator
   (``actuator.geometry``) θ, then the drawn head's springs, effective masses and
   resonances f_v,geom, f_h,geom (:mod:`betvdesign.nondim.actuator`)
3. :func:`vertical_stiffness`   k_v = m·(2π·f_v)², f_v the file's or, where it gives none,
   the drawn actuator's f_v,geom
4. :func:`compliance_ratio`     α given, k_v/k_h or (f_v/f_h)², or (f_v/f_h)² with the
   drawn actuator's f_h where the file gives none of them; given values win and the
   drawn actuator's are recorded beside them (f_v,geom, α_geom) for the check to compare
5. :func:`actuation_frequency`  f_act = 2·f_drive (AC, zero DC bias) or f_drive; ω = 2π·f_act
6. :func:`amplitude`            u given or from the calibration u(V); with a thermal cut-off
   this is u_cal and u = u_cal·H(f_act)/H(f_cal) (:func:`betvdesign.nondim.terms.rolloff`)
7. :func:`impact_contact`       θ (unless a drawn actuator recorded it), μ
8. :func:`model_scales`         t_s = sqrt(m/k_v), ℓ = u·cosθ
9. :func:`normalised_frequency` ϖ = ω·t_s;  :func:`mass_ratio` β = m/M;
   :func:`normalised_friction`  κ = μ·tanθ
10. the optional terms (:func:`betvdesign.nondim.terms.damping_terms`: ζ_v, ζ_h, e, δ, A;
    all absent: the paper's model, recorded as before)
11. :func:`push_pull`           λ (MODEL.md, "Push/pull criterion");
    :func:`published_fit`       the published values beside the computed ones

Every input, formula and intermediate value is kept as a :class:`DerivationStep`
so a report can show how each number was obtained. Each step works on floats and on
numpy arrays of samples alike (:func:`derive_samples`).
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
import pint

from betvdesign.errors import Location, ParameterError, SpecError, SpecIssue
from betvdesign.model.domain import WINDOW_EDGE_RTOL, snap_to_window_edge
from betvdesign.model.params import ModelParams
from betvdesign.nondim import actuator, stroke, terms
from betvdesign.nondim.record import (
    DERIVED_KEYS,
    DerivationStep,
    DeviceDerivation,
    DrawnStroke,
    FitComparison,
    Recorder,
    SampleDerivation,
    Scales,
    SetDerivation,
    cached_unit,
    mag,
)
from betvdesign.spec.loader import load_device
from betvdesign.spec.models import (
    Actuator,
    ActuatorSet,
    BoxGeometry,
    Contact,
    DeviceSpec,
    DiscGeometry,
    Drive,
    PublishedFit,
    amplitude_at,
)
from betvdesign.spec.units import ureg

__all__ = [
    "DERIVED_KEYS",
    "DerivationStep",
    "DeviceDerivation",
    "FitComparison",
    "SampleDerivation",
    "Scales",
    "SetDerivation",
    "amplitude_at",
    "derive",
    "derive_file",
    "derive_refusing",
    "derive_samples",
    "derive_set",
]

#: Fields of an actuator set that name or orient it but do not enter the derivation.
_SET_IDENTITY = {"name", "intended_mode", "impact_direction"}


def derive(spec: DeviceSpec) -> DeviceDerivation:
    """Derive the model parameters of every actuator set of ``spec``.

    Parameters
    ----------
    spec : DeviceSpec
        A validated device.

    Returns
    -------
    DeviceDerivation
        One :class:`SetDerivation` per actuator set; sets that differ only in name,
        intended mode or impact direction (mirrored sets) are
        derived once.

    Raises
    ------
    ParameterError
        The numbers give parameters the model cannot take (non-finite, non-positive).
    """
    sets: list[SetDerivation] = []
    done: list[tuple[dict, SetDerivation]] = []  # mirrored sets: derived once
    for aset in spec.actuator_sets:
        key = aset.model_dump(exclude=_SET_IDENTITY)
        same = next((d for k, d in done if k == key), None)
        if same is None:
            sets.append(derive_set(spec, aset))
            done.append((key, sets[-1]))
        else:
            sets.append(
                replace(same, name=aset.name, intended_mode=aset.intended_mode, actuator_set=aset)
            )
    return DeviceDerivation(name=spec.name, spec=spec, sets=sets)


def derive_file(path: str | Path) -> DeviceDerivation:
    """Load a device file and derive it.

    Parameters
    ----------
    path : str or Path
        The device YAML file.

    Returns
    -------
    DeviceDerivation
        As :func:`derive`.

    Raises
    ------
    SpecError
        Every problem, naming the file (derived parameters the model cannot take, e.g.
        overflow, included).
    """
    return derive_refusing(load_device(path), str(path))


def derive_refusing(spec: DeviceSpec, filename: str) -> DeviceDerivation:
    """Derive a device, refusing what the model cannot take as bad input.

    :func:`derive`, refusing a device whose derived parameters the model cannot take
    as bad input of its file: the one refusal ``betv check`` gives a file and
    ``betv explore`` a value typed into a control.

    Parameters
    ----------
    spec : DeviceSpec
        A validated device.
    filename : str
        Its file, for the message.

    Returns
    -------
    DeviceDerivation
        As :func:`derive`.

    Raises
    ------
    SpecError
        Naming the file: "derived parameters outside the model: ..." (the set and the
        derived value).
    """
    try:
        return derive(spec)
    except ParameterError as exc:
        raise SpecError(
            [SpecIssue(Location(filename), "", f"derived parameters outside the model: {exc}")]
        ) from None


def derive_set(spec: DeviceSpec, aset: ActuatorSet) -> SetDerivation:
    """Derivation of one actuator set (the steps of the module docstring).

    Parameters
    ----------
    spec : DeviceSpec
        The device (material, slider, published fit).
    aset : ActuatorSet
        One of its actuator sets.

    Returns
    -------
    SetDerivation
        Model parameters, scales and the record of every step.

    Raises
    ------
    ParameterError
        Naming the set, when a derived value is not finite and positive or the
        arithmetic overflows.

    References
    ----------
    Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
    """
    try:
        return _derive_set(spec, aset)
    except (ZeroDivisionError, OverflowError, FloatingPointError) as exc:
        raise ParameterError(
            f"set {aset.name!r}: arithmetic failed ({exc}); check for extreme values"
        ) from None
    except ParameterError as exc:
        raise ParameterError(f"set {aset.name!r}: {exc}") from None


def derive_samples(spec: DeviceSpec, aset: ActuatorSet) -> SampleDerivation:
    """The derivation of :func:`derive_set` for sampled specs.

    The derivation of :func:`derive_set` (the same steps) for a spec whose numeric
    fields hold numpy arrays of samples (Monte Carlo studies).

    Vectorised, so a 10⁴-sample study derives in milliseconds.

    Parameters
    ----------
    spec : DeviceSpec
        A device copied with arrays of samples (:func:`betvdesign.spec.paths.with_values`).
    aset : ActuatorSet
        One of its actuator sets.

    Returns
    -------
    SampleDerivation
        Model parameters and scales of every sample.

    Raises
    ------
    ParameterError
        Any sample gives values the model cannot take (the caller then derives one by
        one).
    """
    out = _derive_set(spec, aset, samples=True)
    assert isinstance(out, SampleDerivation)
    return out


def _derive_set(
    spec: DeviceSpec, aset: ActuatorSet, *, samples: bool = False
) -> SetDerivation | SampleDerivation:
    rec = Recorder()
    act = aset.actuator
    M = slider_mass(rec, spec)
    m = head_mass(rec, spec, aset)
    springs = actuator.drawn_springs(rec, spec, aset, m)
    f_v, k_v = vertical_stiffness(rec, act, m, springs)
    alpha = compliance_ratio(rec, act, f_v, k_v, springs)
    f_act, omega = actuation_frequency(rec, aset.drive)
    u, roll, stroke = amplitude(rec, spec, aset, f_act, samples)
    theta, mu = impact_contact(rec, aset.contact)
    t_s, l_s = model_scales(rec, m, k_v, u, theta)
    varpi = normalised_frequency(rec, omega, t_s)
    beta = mass_ratio(rec, m, M)
    kappa = normalised_friction(rec, mu, theta)
    zeta_v, zeta_h, e = terms.damping_terms(rec, aset, mag(varpi, ""))

    if samples:

        def arr(q: pint.Quantity, unit: str) -> np.ndarray:
            return np.asarray(q.to(cached_unit(unit)).magnitude, dtype=float)

        cols = [arr(q, "") for q in (varpi, alpha, beta, kappa)]
        cols += [arr(l_s, "m"), arr(f_act, "Hz")]
        cols += [np.asarray(x, dtype=float) for x in (zeta_v, zeta_h, e)]
        return SampleDerivation(*(np.array(c) for c in np.broadcast_arrays(*cols)))
    params = ModelParams(
        varpi=mag(varpi, ""),
        alpha=mag(alpha, ""),
        beta=mag(beta, ""),
        kappa=mag(kappa, ""),
        zeta_v=zeta_v,
        zeta_h=zeta_h,
        restitution=e,
    )
    lam = push_pull(rec, params)
    published = published_fit(rec, params, spec.published_fit)
    scales = Scales(
        length_m=mag(l_s, "m"),
        time_s=mag(t_s, "s"),
        f_act_hz=mag(f_act, "Hz"),
        omega_rad_s=mag(omega, "rad/s"),
        u_m=mag(u, "m"),
        theta_rad=mag(theta, "rad"),
        **roll,
    )
    return SetDerivation(
        springs=None if springs is None else actuator.springs_data(springs, m, f_v, alpha, act),
        name=aset.name,
        intended_mode=aset.intended_mode,
        params=params,
        lam=lam,
        scales=scales,
        record=rec.steps,
        actuator_set=aset,
        travel_range_m=mag(spec.slider.travel_range, "m"),
        published=published,
        stroke=stroke,
    )


# --- the steps -------------------------------------------------------------------------


def slider_mass(rec: Recorder, spec: DeviceSpec) -> pint.Quantity:
    """Half the slider mass, the model's M: M = (n·ρ·L·w·t + m_extra)/2.

    Records ρ, L, w, t, n, m_extra and M.

    Parameters
    ----------
    rec : Recorder
        The record being built.
    spec : DeviceSpec
        The device: its material's density ρ [kg/m³] and its slider (n beams of length
        L, width w, thickness t [m]; extra mass m_extra [kg]).

    Returns
    -------
    pint.Quantity
        M [ug].

    References
    ----------
    MODEL.md, "Physical quantities"; Shin et al., J. Appl. Phys. 96, 7603 (2004),
    doi:10.1063/1.1809773 (half the device is modelled, by symmetry).
    """
    sl = spec.slider
    rho = rec.spec(
        "ρ", f"slider density ({spec.material.name})", "material.density", spec.material.density
    )
    L = rec.spec("L", "beam length", "slider.beam_length", sl.beam_length)
    w = rec.spec("w", "beam width", "slider.beam_width", sl.beam_width)
    t = rec.spec("t", "beam thickness", "slider.beam_thickness", sl.beam_thickness)
    n = rec.spec(
        "n", "beam count", "slider.beam_count", ureg.Quantity(sl.beam_count, cached_unit(""))
    )
    m_x = rec.spec(
        "m_extra", "extra slider mass", "slider.extra_mass", sl.extra_mass.to(cached_unit("ug"))
    )
    return rec.add(
        "M",
        "half the slider mass (the model's M)",
        "(n·ρ·L·w·t + m_extra)/2",
        (n * rho * L * w * t + m_x) / 2,
        ("n", "ρ", "L", "w", "t", "m_extra"),
        "ug",
    )


def head_mass(rec: Recorder, spec: DeviceSpec, aset: ActuatorSet) -> pint.Quantity:
    """The impact head's mass m: given, or m = ρ_head·V_head.

    V_head = π·d²/4·t for a disc of diameter d, l·w·t for a box (thickness t [m]);
    ρ_head [kg/m³] is the head's material, the device's by default. Records the inputs,
    V_head and m.

    Parameters
    ----------
    rec : Recorder
        The record being built.
    spec : DeviceSpec
        The device (its material).
    aset : ActuatorSet
        The actuator set (its head).

    Returns
    -------
    pint.Quantity
        m [ug].

    References
    ----------
    MODEL.md, "Physical quantities".
    """
    head = aset.head
    if head.mass is not None:
        return rec.spec("m", "impact head mass", "head.mass", head.mass.to(cached_unit("ug")))
    geo = head.geometry
    mat = head.material or spec.material
    rho_h = rec.spec("ρ_head", f"head density ({mat.name})", "head.material", mat.density)
    if isinstance(geo, DiscGeometry):
        d = rec.spec("d_head", "head diameter", "head.geometry.diameter", geo.diameter)
        t = rec.spec("t_head", "head thickness", "head.geometry.thickness", geo.thickness)
        vol = rec.add(
            "V_head",
            "head volume",
            "π·d²/4·t",
            math.pi * d**2 / 4 * t,
            ("d_head", "t_head"),
            "um**3",
        )
    else:
        assert isinstance(geo, BoxGeometry)
        a = rec.spec("l_head", "head length", "head.geometry.length", geo.length)
        b = rec.spec("w_head", "head width", "head.geometry.width", geo.width)
        t = rec.spec("t_head", "head thickness", "head.geometry.thickness", geo.thickness)
        vol = rec.add(
            "V_head", "head volume", "l·w·t", a * b * t, ("l_head", "w_head", "t_head"), "um**3"
        )
    return rec.add(
        "m", "impact head mass", "ρ_head·V_head", rho_h * vol, ("ρ_head", "V_head"), "ug"
    )


def vertical_stiffness(
    rec: Recorder, act: Actuator, m: pint.Quantity, springs: dict[str, Any] | None = None
) -> tuple[pint.Quantity, pint.Quantity]:
    """The head's vertical (normal) contact stiffness: k_v = m·(2π·f_v)².

    From the head's vertical resonance f_v, sqrt(k_v/m) = 2π·f_v. Records f_v and k_v.
    Where the file gives no f_v, f_v is the drawn actuator's (``f_v,geom``, recorded by
    :func:`betvdesign.nondim.actuator.drawn_springs` either way) and k_v = m·(2π·f_v)².

    Parameters
    ----------
    rec : Recorder
        The record being built.
    act : Actuator
        The actuator (its vertical resonance f_v [Hz]).
    m : pint.Quantity
        Head mass [kg].
    springs : dict or None
        The drawn actuator's springs (:func:`betvdesign.nondim.actuator.drawn_springs`).

    Returns
    -------
    tuple of pint.Quantity
        f_v [kHz] and k_v [N/m].

    References
    ----------
    MODEL.md, "Device-to-parameter relations"; Shin et al., J. Appl. Phys. 96, 7603
    (2004), doi:10.1063/1.1809773.
    """
    if act.vertical_resonance is None:
        assert springs is not None
        return actuator.drawn_vertical_stiffness(rec, springs, m)
    f_v = rec.spec(
        "f_v",
        "head vertical resonance",
        "actuator.vertical_resonance",
        act.vertical_resonance.to(cached_unit("kHz")),
    )
    return f_v, actuator.contact_stiffness(rec, m, f_v, "vertical contact stiffness")


def compliance_ratio(
    rec: Recorder,
    act: Actuator,
    f_v: pint.Quantity,
    k_v: pint.Quantity,
    springs: dict[str, Any] | None = None,
) -> pint.Quantity:
    """The relative impact compliance α = k_v/k_h [-].

    Phenomenological: given directly, through the tangential stiffness k_h
    (α = k_v/k_h), or through a tangential resonance f_h (α = (f_v/f_h)²). Records the
    input and α. Where the file gives none of them, α = (f_v/f_h)² with the drawn
    actuator's f_h; where it gives one, the drawn actuator's (f_v,geom/f_h,geom)² is
    recorded beside it (``α_geom``, not used).

    Parameters
    ----------
    rec : Recorder
        The record being built.
    act : Actuator
        The actuator (at most one of α, k_h [N/m], f_h [Hz]; none only with a drawn
        actuator).
    f_v : pint.Quantity
        Vertical resonance [Hz].
    k_v : pint.Quantity
        Vertical contact stiffness [N/m].
    springs : dict or None
        The drawn actuator's springs (:func:`betvdesign.nondim.actuator.drawn_springs`).

    Returns
    -------
    pint.Quantity
        α [-].

    References
    ----------
    MODEL.md, "Device-to-parameter relations"; Shin et al., J. Appl. Phys. 96, 7603
    (2004), doi:10.1063/1.1809773.
    """
    if not actuator.alpha_given(act):
        assert springs is not None
        return actuator.drawn_compliance_ratio(rec, springs, f_v)
    if act.alpha is not None:
        alpha = rec.spec(
            "α",
            "relative impact compliance k_v/k_h",
            "actuator.alpha",
            ureg.Quantity(act.alpha, cached_unit("")),
        )
    elif act.horizontal_stiffness is not None:
        k_h = rec.spec(
            "k_h",
            "tangential contact stiffness",
            "actuator.horizontal_stiffness",
            act.horizontal_stiffness.to(cached_unit("N/m")),
        )
        alpha = rec.add("α", "relative impact compliance", "k_v/k_h", k_v / k_h, ("k_v", "k_h"), "")
    else:
        assert act.horizontal_resonance is not None
        f_h = rec.spec(
            "f_h",
            "head tangential resonance",
            "actuator.horizontal_resonance",
            act.horizontal_resonance.to(cached_unit("kHz")),
        )
        alpha = actuator.resonance_compliance_ratio(rec, f_v, f_h)
    if springs is not None:
        actuator.drawn_alpha_beside(rec, springs)
    return alpha


def actuation_frequency(rec: Recorder, drive: Drive) -> tuple[pint.Quantity, pint.Quantity]:
    """The actuation frequency f_act and ω = 2π·f_act.

    A pure AC drive with zero DC bias heats on both half waves: f_act = 2·f_drive (AC
    doubling); a DC-biased or unipolar drive: f_act = f_drive. Records f_drive, f_act
    and ω.

    Parameters
    ----------
    rec : Recorder
        The record being built.
    drive : Drive
        The electrical drive (waveform, frequency f_drive [Hz]).

    Returns
    -------
    tuple of pint.Quantity
        f_act [Hz] and ω [rad/s].

    References
    ----------
    MODEL.md, "Device-to-parameter relations"; Shin et al., J. Appl. Phys. 96, 7603
    (2004), doi:10.1063/1.1809773.
    """
    f_d = rec.spec(
        "f_drive",
        f"drive frequency ({drive.waveform})",
        "drive.frequency",
        drive.frequency.to(cached_unit("Hz")),
    )
    if drive.doubled:
        f_act = rec.add(
            "f_act",
            "actuation frequency: AC with zero DC bias heats on both half waves (AC doubling)",
            "2·f_drive",
            2 * f_d,
            ("f_drive",),
            "Hz",
        )
    else:
        f_act = rec.add(
            "f_act",
            f"actuation frequency ({drive.waveform} drive: not doubled)",
            "f_drive",
            f_d,
            ("f_drive",),
            "Hz",
        )
    omega = rec.add(
        "ω", "angular actuation frequency", "2π·f_act", 2 * math.pi * f_act, ("f_act",), "rad/s"
    )
    return f_act, omega


def amplitude(
    rec: Recorder, spec: DeviceSpec, aset: ActuatorSet, f_act: pint.Quantity, samples: bool
) -> tuple[pint.Quantity, dict[str, float], DrawnStroke | None]:
    """The actuator amplitude u at the actuation frequency.

    u is given, or follows from the drive voltage V through the calibration (gain·V,
    gain·V² or interpolated measured points). With a thermal cut-off that value is u_cal,
    at the calibration frequency, and u = u_cal·H(f_act)/H(f_cal)
    (:func:`betvdesign.nondim.terms.rolloff`). Records the inputs and u (u_cal). Without
    either, u is predicted from the drawing at the drive
    (:func:`betvdesign.nondim.stroke.drawn_stroke`).

    Parameters
    ----------
    rec : Recorder
        The record being built.
    spec : DeviceSpec
        The device (its process, for a drawn stroke).
    aset : ActuatorSet
        The actuator set (its actuator and drive voltage V [V]).
    f_act : pint.Quantity
        Actuation frequency [Hz].
    samples : bool
        True for arrays of samples (then no cut-off is returned for the scales).

    Returns
    -------
    tuple
        u [um]; the thermal cut-off and calibration frequency [Hz] for :class:`Scales`
        (empty without a cut-off); the drawn stroke's data (None unless predicted).

    Raises
    ------
    ParameterError
        A drawn stroke for arrays of samples (each sample is then derived on its own), or
        without the process's electrothermal data.

    References
    ----------
    MODEL.md, "Device-to-parameter relations" and "Thermal roll-off of the actuator".
    """
    act = aset.actuator
    if act.drawn_stroke:
        if samples:
            raise ParameterError("a drawn stroke is derived one sample at a time")
        u, data = stroke.drawn_stroke(rec, spec, aset)
        return u, {"thermal_modes": data.modes, "waveform": aset.drive.waveform}, data
    rolled = act.thermal_cutoff is not None or act.thermal_time_constant is not None
    sym, at_cal = ("u_cal", " at the calibration frequency") if rolled else ("u", "")
    if act.amplitude is not None:
        u = rec.spec(
            sym,
            "actuator amplitude" + at_cal,
            "actuator.amplitude",
            act.amplitude.to(cached_unit("um")),
        )
    else:
        rec.spec("V", "drive voltage", "drive.voltage", aset.drive.voltage)
        law = act.calibration.law
        formula = {
            "linear": "gain·V",
            "quadratic": "gain·V²",
            "measured": "interp(V; measured points)",
        }[law]
        u = rec.add(
            sym,
            f"actuator amplitude ({law} calibration){at_cal}",
            formula,
            amplitude_at(aset),
            ("V",),
            "um",
        )
    if not rolled:
        return u, {}, None
    return (*terms.rolloff(rec, act, f_act, u, samples), None)


def impact_contact(rec: Recorder, contact: Contact) -> tuple[pint.Quantity, pint.Quantity]:
    """The contact's impact angle θ and Coulomb friction coefficient μ (inputs).

    θ is recorded once: a drawn actuator's springs record it first
    (:func:`betvdesign.nondim.actuator.drawn_springs`).

    Parameters
    ----------
    rec : Recorder
        The record being built.
    contact : Contact
        The head/slider contact: θ [deg], μ [-].

    Returns
    -------
    tuple of pint.Quantity
        θ [deg] and μ [-].

    References
    ----------
    MODEL.md, "Physical quantities".
    """
    theta = rec.recorded("θ")
    if theta is None:
        theta = rec.spec("θ", "impact angle", "contact.impact_angle", contact.impact_angle)
    mu = rec.spec(
        "μ",
        "Coulomb friction coefficient",
        "contact.friction",
        ureg.Quantity(contact.friction, cached_unit("")),
    )
    return theta, mu


def model_scales(
    rec: Recorder, m: pint.Quantity, k_v: pint.Quantity, u: pint.Quantity, theta: pint.Quantity
) -> tuple[pint.Quantity, pint.Quantity]:
    """The scales of the dimensionless model: t_s = sqrt(m/k_v), ℓ = u·cosθ.

    τ = t/t_s; the slider and the head's tangential motion are in units of ℓ. Records
    t_s and ℓ.

    Parameters
    ----------
    rec : Recorder
        The record being built.
    m : pint.Quantity
        Head mass [kg].
    k_v : pint.Quantity
        Vertical contact stiffness [N/m].
    u : pint.Quantity
        Actuator amplitude at f_act [m].
    theta : pint.Quantity
        Impact angle [rad].

    Returns
    -------
    tuple of pint.Quantity
        t_s [us] and ℓ [nm].

    References
    ----------
    MODEL.md, "Dimensionless model"; Shin et al., J. Appl. Phys. 96, 7603 (2004),
    doi:10.1063/1.1809773.
    """
    t_s = rec.add(
        "t_s", "time scale sqrt(m/k_v)", "sqrt(m/k_v)", (m / k_v) ** 0.5, ("m", "k_v"), "us"
    )
    l_s = rec.add(
        "ℓ",
        "length scale u·cosθ (slider, tangential)",
        "u·cosθ",
        u * _cos(theta.to(cached_unit("rad")).magnitude),
        ("u", "θ"),
        "nm",
    )
    return t_s, l_s


def normalised_frequency(rec: Recorder, omega: pint.Quantity, t_s: pint.Quantity) -> pint.Quantity:
    """The normalised actuation frequency ϖ = ω·sqrt(m/k_v) = ω·t_s (= f_act/f_v).

    Parameters
    ----------
    rec : Recorder
        The record being built.
    omega : pint.Quantity
        Angular actuation frequency [rad/s].
    t_s : pint.Quantity
        Time scale sqrt(m/k_v) [s].

    Returns
    -------
    pint.Quantity
        ϖ [-]; within :data:`~betvdesign.model.domain.WINDOW_EDGE_RTOL` of a window
        edge it is that edge exactly (:func:`~betvdesign.model.domain.
        snap_to_window_edge`: f_act = f_v/2 gives 0.5, f_act = 2·f_v gives 2), and the
        record's formula says so.

    References
    ----------
    MODEL.md, "Dimensionless model"; Shin et al., J. Appl. Phys. 96, 7603 (2004),
    doi:10.1063/1.1809773.
    """
    raw = (omega * t_s).to("").magnitude
    if np.ndim(raw) == 0:
        snapped = snap_to_window_edge(float(raw))
        formula = "ω·sqrt(m/k_v)"
        if snapped != float(raw):  # the derivation's round-off, not the design
            formula += (
                f" = {float(raw)!r}, at the window edge {snapped:g} to round-off "
                f"(|ϖ − {snapped:g}| ≤ {WINDOW_EDGE_RTOL:g}·{snapped:g}): set to {snapped:g}"
            )
        value: Any = snapped
    else:
        value = np.vectorize(snap_to_window_edge, otypes=[float])(np.asarray(raw, float))
        formula = "ω·sqrt(m/k_v) (edges of the window to round-off set exactly)"
    return rec.add("ϖ", "normalised actuation frequency", formula, value, ("ω", "t_s"), "")


def mass_ratio(rec: Recorder, m: pint.Quantity, M: pint.Quantity) -> pint.Quantity:
    """The relative mass β = m/M.

    Parameters
    ----------
    rec : Recorder
        The record being built.
    m : pint.Quantity
        Head mass [kg].
    M : pint.Quantity
        Half the slider mass [kg].

    Returns
    -------
    pint.Quantity
        β [-].

    References
    ----------
    MODEL.md, "Dimensionless model"; Shin et al., J. Appl. Phys. 96, 7603 (2004),
    doi:10.1063/1.1809773.
    """
    return rec.add("β", "relative mass m/M", "m/M", m / M, ("m", "M"), "")


def normalised_friction(rec: Recorder, mu: pint.Quantity, theta: pint.Quantity) -> pint.Quantity:
    """The normalised friction κ = μ·tanθ.

    Parameters
    ----------
    rec : Recorder
        The record being built.
    mu : pint.Quantity
        Coulomb friction coefficient [-].
    theta : pint.Quantity
        Impact angle [rad].

    Returns
    -------
    pint.Quantity
        κ [-].

    References
    ----------
    MODEL.md, "Dimensionless model"; Shin et al., J. Appl. Phys. 96, 7603 (2004),
    doi:10.1063/1.1809773.
    """
    return rec.add(
        "κ",
        "normalised friction μ·tanθ",
        "μ·tanθ",
        mu * _tan(theta.to(cached_unit("rad")).magnitude),
        ("μ", "θ"),
        "",
    )


def push_pull(rec: Recorder, params: ModelParams) -> float:
    """The push/pull criterion λ = (κ/ϖ²)·(1/(ακ) − (1/β − β)/(22(κ+1))).

    λ < 1 predicts push, λ > 1 pull (the paper's fit). Recorded, never checked for sign.

    Parameters
    ----------
    rec : Recorder
        The record being built.
    params : ModelParams
        ϖ, α, β, κ [-].

    Returns
    -------
    float
        λ [-].

    References
    ----------
    MODEL.md, "Push/pull criterion"; Shin et al., J. Appl. Phys. 96, 7603 (2004),
    doi:10.1063/1.1809773.
    """
    lam = params.lam
    rec.add(
        "λ",
        "push/pull criterion (λ < 1 push, λ > 1 pull)",
        "(κ/ϖ²)·(1/(ακ) − (1/β − β)/(22(κ+1)))",
        ureg.Quantity(lam, cached_unit("")),
        ("ϖ", "α", "β", "κ"),
    )
    return lam


#: Model parameter -> its symbol in the record.
_SYMBOL = {"varpi": "ϖ", "alpha": "α", "beta": "β", "kappa": "κ"}


def published_fit(
    rec: Recorder, params: ModelParams, fit: PublishedFit | None
) -> list[FitComparison]:
    """The published fit's values beside the computed ones, with the gap.

    Each published value goes into the record as ``<symbol>_pub`` (``[i]`` when several
    are quoted), described with the computed value and the relative gap.

    Parameters
    ----------
    rec : Recorder
        The record being built.
    params : ModelParams
        The computed ϖ, α, β, κ [-].
    fit : PublishedFit or None
        What a publication fitted for the device.

    Returns
    -------
    list of FitComparison
        One per parameter the fit gives (empty without a fit).

    References
    ----------
    MODEL.md, "The published device".
    """
    if fit is None:
        return []
    out = [
        FitComparison(name, value, tuple(fit.values(name)))
        for name, value in (
            ("varpi", params.varpi),
            ("alpha", params.alpha),
            ("beta", params.beta),
            ("kappa", params.kappa),
        )
        if fit.values(name)
    ]
    source = f" ({fit.source})" if fit.source else ""
    for c in out:
        sym = _SYMBOL[c.name]
        for i, v in enumerate(c.published):
            suffix = f"[{i}]" if len(c.published) > 1 else ""
            gap = abs(c.computed - v) / abs(v)
            rec.steps.append(
                DerivationStep(
                    f"{sym}_pub{suffix}",
                    f"published fit{source}; computed {sym} = {c.computed:.4g} is {gap:.0%} away",
                    f"spec: published_fit.{c.name}" + suffix,
                    ureg.Quantity(v, cached_unit("")),
                    (),
                    f"{c.name}_pub{suffix}",
                )
            )
    return out


def _cos(x: Any) -> Any:
    return math.cos(x) if np.ndim(x) == 0 else np.cos(x)


def _tan(x: Any) -> Any:
    return math.tan(x) if np.ndim(x) == 0 else np.tan(x)
