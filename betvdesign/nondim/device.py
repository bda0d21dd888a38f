"""Device spec -> dimensionless model parameters, scales and a derivation record.

The only module that strips units. For each actuator set it computes
(docs/MODEL.md, "Physical quantities", "Device-to-parameter relations",
"Dimensionless model"):

- M = (n·ρ·L·w·t + m_extra)/2    half the slider mass [kg]
- m                               head mass, given or ρ_head·V_head [kg]
- k_v = m·(2π f_v)²               vertical contact stiffness [N/m]
- α = k_v/k_h or (f_v/f_h)² or given
- with a drawn actuator (``actuator.geometry``, :mod:`betvdesign.nondim.actuator`): the
  frame's K_nn, K_tt at the head; k_v = K_nn where the file gives no f_v (then
  f_v = √(k_v/m)/2π), k_h = K_tt where it gives no α, k_h or f_h; given values win and
  the geometry's are recorded beside them (f_v,geom, α_geom) for the check to compare
- f_act = 2 f_drive (AC, zero DC bias) or f_drive;  ω = 2π f_act
- u = amplitude or calibration(V); with a thermal cut-off f_c (or τ_th) this is u_cal
  and u = u_cal·H(f_act)/H(f_cal), H(f) = 1/sqrt(1 + (f/f_c)²) (:mod:`betvdesign.model.rolloff`)
- ζ_v, ζ_h: head damping ratios (given, or 1/(2Q)); e: restitution of normal impacts;
  with ζ_v > 0 the normal force's phase δ = atan(2ζ_v ϖ) and factor A = sqrt(1 + (2ζ_v ϖ)²)
  (:mod:`betvdesign.model.damping`; these terms and the roll-off are recorded by
  :mod:`betvdesign.nondim.terms`). All absent: the paper's model, recorded as before.
- ϖ = ω·sqrt(m/k_v) = f_act/f_v,  β = m/M,  κ = μ·tanθ,  λ (MODEL.md, "Push/pull criterion")
- scales: length u·cosθ [m], time sqrt(m/k_v) [s]

Every input, formula and intermediate value is kept as a :class:`DerivationStep`
so a report can show how each number was obtained.
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
import pint

from betvdesign.errors import Location, ParameterError, SpecError, SpecIssue
from betvdesign.model.params import ModelParams
from betvdesign.nondim import terms as nondim_terms
from betvdesign.nondim.actuator import head_springs
from betvdesign.nondim.record import (
    DERIVED_KEYS,
    DerivationStep,
    DeviceDerivation,
    FitComparison,
    HeadSprings,
    SampleDerivation,
    Scales,
    SetDerivation,
)
from betvdesign.nondim.record import Recorder as _Record
from betvdesign.nondim.record import cached_unit as _unit
from betvdesign.spec.loader import load_device
from betvdesign.spec.models import (
    ActuatorSet,
    BoxGeometry,
    DeviceSpec,
    DiscGeometry,
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
    "derive_samples",
    "derive_set",
]


def derive(spec: DeviceSpec) -> DeviceDerivation:
    """Derive the model parameters of every actuator set of ``spec``.

    Raises :class:`~betvdesign.errors.ParameterError` if the numbers give parameters
    the model cannot take (non-finite, non-positive).
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


#: Fields of an actuator set that name or orient it but do not enter the derivation.
_SET_IDENTITY = {"name", "intended_mode", "impact_direction"}


def derive_file(path: str | Path) -> DeviceDerivation:
    """Load a device file and derive it; every problem is a :class:`SpecError` naming the
    file (derived parameters the model cannot take, e.g. overflow, included)."""
    spec = load_device(path)
    try:
        return derive(spec)
    except ParameterError as exc:
        raise SpecError(
            [SpecIssue(Location(str(path)), "", f"derived parameters outside the model: {exc}")]
        ) from None


def _head_mass(rec: _Record, spec: DeviceSpec, aset: ActuatorSet) -> pint.Quantity:
    head = aset.head
    if head.mass is not None:
        return rec.spec("m", "impact head mass", "head.mass", head.mass.to(_unit("ug")))
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


def derive_set(spec: DeviceSpec, aset: ActuatorSet) -> SetDerivation:
    """Derivation of one actuator set (see the module docstring for the formulas).

    Raises :class:`ParameterError` (naming the set) when a derived value is not finite
    and positive, or the arithmetic overflows.
    """
    try:
        return _derive_set(spec, aset)
    except (ZeroDivisionError, OverflowError, FloatingPointError) as exc:
        raise ParameterError(
            f"set {aset.name!r}: arithmetic failed ({exc}); check for extreme values"
        ) from None
    except ParameterError as exc:
        raise ParameterError(f"set {aset.name!r}: {exc}") from None


def _cos(x: Any) -> Any:
    return math.cos(x) if np.ndim(x) == 0 else np.cos(x)


def _tan(x: Any) -> Any:
    return math.tan(x) if np.ndim(x) == 0 else np.tan(x)


def derive_samples(spec: DeviceSpec, aset: ActuatorSet) -> SampleDerivation:
    """The derivation of :func:`derive_set` (the same code) for a spec whose numeric
    fields hold numpy arrays of samples (Monte Carlo studies): vectorised, so a
    10⁴-sample study derives in milliseconds. Raises :class:`ParameterError` when any
    sample gives values the model cannot take (the caller then derives one by one)."""
    out = _derive_set(spec, aset, samples=True)
    assert isinstance(out, SampleDerivation)
    return out


def _derive_set(
    spec: DeviceSpec, aset: ActuatorSet, *, samples: bool = False
) -> SetDerivation | SampleDerivation:
    rec = _Record()
    sl = spec.slider
    act = aset.actuator

    rho = rec.spec(
        "ρ", f"slider density ({spec.material.name})", "material.density", spec.material.density
    )
    L = rec.spec("L", "beam length", "slider.beam_length", sl.beam_length)
    w = rec.spec("w", "beam width", "slider.beam_width", sl.beam_width)
    t = rec.spec("t", "beam thickness", "slider.beam_thickness", sl.beam_thickness)
    n = rec.spec("n", "beam count", "slider.beam_count", ureg.Quantity(sl.beam_count, _unit("")))
    m_x = rec.spec(
        "m_extra", "extra slider mass", "slider.extra_mass", sl.extra_mass.to(_unit("ug"))
    )
    M = rec.add(
        "M",
        "half the slider mass (the model's M)",
        "(n·ρ·L·w·t + m_extra)/2",
        (n * rho * L * w * t + m_x) / 2,
        ("n", "ρ", "L", "w", "t", "m_extra"),
        "ug",
    )
    m = _head_mass(rec, spec, aset)

    springs = None
    if act.geometry is not None:  # the frame's springs use θ: recorded before them
        rec.spec("θ", "impact angle", "contact.impact_angle", aset.contact.impact_angle)
        springs = head_springs(rec, spec, aset, m)
    if act.vertical_resonance is not None:
        f_v = rec.spec(
            "f_v",
            "head vertical resonance",
            "actuator.vertical_resonance",
            act.vertical_resonance.to(_unit("kHz")),
        )
        k_v = rec.add(
            "k_v",
            "vertical contact stiffness",
            "m·(2π·f_v)²",
            m * (2 * math.pi * f_v) ** 2,
            ("m", "f_v"),
            "N/m",
        )
        if springs is not None:
            rec.add(
                "f_v,geom",
                "head vertical resonance of the drawn actuator (not used: the file gives f_v)",
                "√(K_nn/m)/2π",
                (springs["k_nn"] / m) ** 0.5 / (2 * math.pi),
                ("K_nn", "m"),
                "kHz",
            )
    else:
        assert springs is not None
        k_v = rec.add(
            "k_v",
            "vertical contact stiffness: the drawn actuator's K_nn",
            "K_nn",
            springs["k_nn"],
            ("K_nn",),
            "N/m",
        )
        f_v = rec.add(
            "f_v",
            "head vertical resonance (drawn actuator)",
            "√(k_v/m)/2π",
            (k_v / m) ** 0.5 / (2 * math.pi),
            ("k_v", "m"),
            "kHz",
        )
    if act.alpha is not None:
        alpha = rec.spec(
            "α",
            "relative impact compliance k_v/k_h",
            "actuator.alpha",
            ureg.Quantity(act.alpha, _unit("")),
        )
    elif act.horizontal_stiffness is not None:
        k_h = rec.spec(
            "k_h",
            "tangential contact stiffness",
            "actuator.horizontal_stiffness",
            act.horizontal_stiffness.to(_unit("N/m")),
        )
        alpha = rec.add("α", "relative impact compliance", "k_v/k_h", k_v / k_h, ("k_v", "k_h"), "")
    elif act.horizontal_resonance is not None:
        f_h = rec.spec(
            "f_h",
            "head tangential resonance",
            "actuator.horizontal_resonance",
            act.horizontal_resonance.to(_unit("kHz")),
        )
        alpha = rec.add(
            "α", "relative impact compliance", "(f_v/f_h)²", (f_v / f_h) ** 2, ("f_v", "f_h"), ""
        )
    else:
        assert springs is not None
        k_h = rec.add(
            "k_h",
            "tangential contact stiffness: the drawn actuator's K_tt",
            "K_tt",
            springs["k_tt"],
            ("K_tt",),
            "N/m",
        )
        alpha = rec.add("α", "relative impact compliance", "k_v/k_h", k_v / k_h, ("k_v", "k_h"), "")
    if springs is not None and _alpha_given(act):
        rec.add(
            "α_geom",
            "relative impact compliance of the drawn actuator (not used: the file gives it)",
            "K_nn/K_tt",
            springs["k_nn"] / springs["k_tt"],
            ("K_nn", "K_tt"),
            "",
        )

    f_d = rec.spec(
        "f_drive",
        f"drive frequency ({aset.drive.waveform})",
        "drive.frequency",
        aset.drive.frequency.to(_unit("Hz")),
    )
    if aset.drive.doubled:
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
            f"actuation frequency ({aset.drive.waveform} drive: not doubled)",
            "f_drive",
            f_d,
            ("f_drive",),
            "Hz",
        )
    omega = rec.add(
        "ω", "angular actuation frequency", "2π·f_act", 2 * math.pi * f_act, ("f_act",), "rad/s"
    )

    rolled = act.thermal_cutoff is not None or act.thermal_time_constant is not None
    sym, at_cal = ("u_cal", " at the calibration frequency") if rolled else ("u", "")
    if act.amplitude is not None:
        u = rec.spec(
            sym, "actuator amplitude" + at_cal, "actuator.amplitude", act.amplitude.to(_unit("um"))
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
    roll: dict[str, float] = {}
    if rolled:
        u, roll = nondim_terms.rolloff(rec, act, f_act, u, samples)
    theta = next((st.value for st in rec.steps if st.symbol == "θ"), None)
    if theta is None:
        theta = rec.spec("θ", "impact angle", "contact.impact_angle", aset.contact.impact_angle)
    mu = rec.spec(
        "μ",
        "Coulomb friction coefficient",
        "contact.friction",
        ureg.Quantity(aset.contact.friction, _unit("")),
    )

    t_s = rec.add(
        "t_s", "time scale sqrt(m/k_v)", "sqrt(m/k_v)", (m / k_v) ** 0.5, ("m", "k_v"), "us"
    )
    l_s = rec.add(
        "ℓ",
        "length scale u·cosθ (slider, tangential)",
        "u·cosθ",
        u * _cos(theta.to(_unit("rad")).magnitude),
        ("u", "θ"),
        "nm",
    )
    varpi = rec.add(
        "ϖ", "normalised actuation frequency", "ω·sqrt(m/k_v)", omega * t_s, ("ω", "t_s"), ""
    )
    beta = rec.add("β", "relative mass m/M", "m/M", m / M, ("m", "M"), "")
    kappa = rec.add(
        "κ",
        "normalised friction μ·tanθ",
        "μ·tanθ",
        mu * _tan(theta.to(_unit("rad")).magnitude),
        ("μ", "θ"),
        "",
    )
    zeta_v, zeta_h, e = nondim_terms.damping_terms(rec, aset, nondim_terms.mag(varpi, ""))

    if samples:

        def arr(q: pint.Quantity, unit: str) -> np.ndarray:
            return np.asarray(q.to(_unit(unit)).magnitude, dtype=float)

        cols = [arr(q, "") for q in (varpi, alpha, beta, kappa)]
        cols += [arr(l_s, "m"), arr(f_act, "Hz")]
        cols += [np.asarray(x, dtype=float) for x in (zeta_v, zeta_h, e)]
        return SampleDerivation(*(np.array(c) for c in np.broadcast_arrays(*cols)))
    params = ModelParams(
        varpi=float(varpi.to(_unit("")).magnitude),
        alpha=float(alpha.to(_unit("")).magnitude),
        beta=float(beta.to(_unit("")).magnitude),
        kappa=float(kappa.to(_unit("")).magnitude),
        zeta_v=zeta_v,
        zeta_h=zeta_h,
        restitution=e,
    )
    lam = params.lam
    rec.add(
        "λ",
        "push/pull criterion (λ < 1 push, λ > 1 pull)",
        "(κ/ϖ²)·(1/(ακ) − (1/β − β)/(22(κ+1)))",
        ureg.Quantity(lam, _unit("")),
        ("ϖ", "α", "β", "κ"),
    )
    published = _compare(params, spec.published_fit)
    _record_published(rec, published, spec.published_fit)
    scales = Scales(
        length_m=float(l_s.to(_unit("m")).magnitude),
        time_s=float(t_s.to(_unit("s")).magnitude),
        f_act_hz=float(f_act.to(_unit("Hz")).magnitude),
        omega_rad_s=float(omega.to(_unit("rad/s")).magnitude),
        u_m=float(u.to(_unit("m")).magnitude),
        theta_rad=float(theta.to(_unit("rad")).magnitude),
        **roll,
    )
    return SetDerivation(
        springs=None if springs is None else _springs(springs, m, f_v, alpha, act),
        name=aset.name,
        intended_mode=aset.intended_mode,
        params=params,
        lam=lam,
        scales=scales,
        record=rec.steps,
        actuator_set=aset,
        travel_range_m=float(sl.travel_range.to(_unit("m")).magnitude),
        published=published,
    )


def _alpha_given(act: Any) -> bool:
    return any(
        getattr(act, n) is not None
        for n in ("alpha", "horizontal_stiffness", "horizontal_resonance")
    )


def _springs(
    s: dict[str, Any], m: pint.Quantity, f_v: pint.Quantity, alpha: pint.Quantity, act: Any
) -> HeadSprings:
    """The drawn actuator's springs as plain data for the rules (record.HeadSprings)."""
    file_fv = act.vertical_resonance is not None
    file_alpha = _alpha_given(act)
    return HeadSprings(
        k_nn=float(s["k_nn"].to(_unit("N/m")).magnitude),
        k_tt=float(s["k_tt"].to(_unit("N/m")).magnitude),
        k_nt=float(s["k_nt"]),
        rho=float(s["rho"]),
        m_arm_kg=float(s["m_arm"]),
        m_head_kg=float(m.to(_unit("kg")).magnitude),
        used={
            "k_v": "file" if file_fv else "geometry",
            "alpha": "file" if file_alpha else "geometry",
        },
        file_f_v_hz=float(f_v.to(_unit("Hz")).magnitude) if file_fv else None,
        file_alpha=float(alpha.to(_unit("")).magnitude) if file_alpha else None,
    )


def _compare(params: ModelParams, fit: PublishedFit | None) -> list[FitComparison]:
    if fit is None:
        return []
    out = []
    for name in ("varpi", "alpha", "beta", "kappa"):
        vals = fit.values(name)
        if vals:
            out.append(FitComparison(name, getattr(params, name), tuple(vals)))
    return out


_SYMBOL = {"varpi": "ϖ", "alpha": "α", "beta": "β", "kappa": "κ"}


def _record_published(
    rec: _Record, published: list[FitComparison], fit: PublishedFit | None
) -> None:
    """Published fit values go into the record next to the computed ones, with the gap."""
    source = f" ({fit.source})" if fit is not None and fit.source else ""
    for c in published:
        sym = _SYMBOL[c.name]
        for i, v in enumerate(c.published):
            suffix = f"[{i}]" if len(c.published) > 1 else ""
            gap = abs(c.computed - v) / abs(v)
            rec.steps.append(
                DerivationStep(
                    f"{sym}_pub{suffix}",
                    f"published fit{source}; computed {sym} = {c.computed:.4g} is {gap:.0%} away",
                    f"spec: published_fit.{c.name}" + suffix,
                    ureg.Quantity(v, _unit("")),
                    (),
                    f"{c.name}_pub{suffix}",
                )
            )
