"""The drawn actuator -> the head's springs k_v, k_h, every step in the derivation record.

MODEL.md, "From the drawn actuator to the head's springs". The closed form is
:func:`betvdesign.model.frame.frame_stiffness` (Euler–Bernoulli frame, flexibility
method; its stated error against the plane-stress FE of :mod:`betvdesign.model.frame_fe`
is :data:`betvdesign.model.frame.CLOSED_FORM_RTOL`); here the spec's quantities go in
and the record gets:

- the inputs: E, t (the process layer's, or the geometry's own), the drawn lengths and
  widths, the head's half-extent r_x (its disc's radius; for a head given by its mass,
  the disc of that mass in the layer: d = sqrt(4m/(π ρ t)));
- K_xx, K_yy, K_xy: the 2×2 stiffness at the head in the actuator's axes;
- K_nn, K_tt, K_nt: in the slider's frame at the impact angle θ; ρ_K = K_nt/√(K_nn·K_tt);
- m_arm: the arms' first-mode mass at the head (Rayleigh, along the softest direction).

:func:`head_springs` is called by :mod:`betvdesign.nondim.device`, which decides which of
k_v = K_nn and k_h = K_tt it uses (the file's resonances win where given) through the
steps here: :func:`drawn_springs` (θ, then :func:`head_springs`),
:func:`drawn_vertical_stiffness` or :func:`drawn_resonance_beside`,
:func:`drawn_compliance_ratio` or :func:`drawn_alpha_beside`, and :func:`springs_data`
(the plain data the rules read).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pint

from betvdesign.model.frame import (
    FrameGeometry,
    arm_modal_mass,
    frame_stiffness,
    head_disc_diameter,
    slider_springs,
)
from betvdesign.nondim.record import HeadSprings, Recorder, cached_unit, mag
from betvdesign.spec.models import Actuator, ActuatorSet, BoxGeometry, DeviceSpec, DiscGeometry
from betvdesign.spec.units import ureg

__all__ = [
    "ActuatorInputs",
    "actuator_inputs",
    "alpha_given",
    "drawn_alpha_beside",
    "drawn_compliance_ratio",
    "drawn_resonance_beside",
    "drawn_springs",
    "drawn_vertical_stiffness",
    "frame_geometry",
    "head_springs",
    "springs_data",
]

#: Poisson's ratio used by the FE check when neither the geometry nor the process gives one
#: (polysilicon, Sharpe et al. 1997).
DEFAULT_POISSON = 0.22


class ActuatorInputs:
    """The quantities the actuator's springs use, with the spec path each comes from."""

    def __init__(self, spec: DeviceSpec, aset: ActuatorSet):
        geo = aset.actuator.geometry
        assert geo is not None
        self.geometry = geo
        p = spec.process
        g = "actuator.geometry"
        if p is not None:
            name = p.structural_name(geo.layer)
            lay = p.structural(name)
            self.layer = name
            t_path = f"process {p.name}: layers.{name}.thickness"
            e_path = f"process {p.name}: layers.{name}.youngs_modulus"
            self.thickness = geo.thickness if geo.thickness is not None else lay.thickness
            self.youngs = (
                geo.youngs_modulus if geo.youngs_modulus is not None else lay.youngs_modulus
            )
            nu = geo.poisson_ratio if geo.poisson_ratio is not None else lay.poisson_ratio
            self.t_path = f"{g}.thickness" if geo.thickness is not None else t_path
            self.e_path = f"{g}.youngs_modulus" if geo.youngs_modulus is not None else e_path
        else:
            self.layer = None
            self.thickness, self.youngs = geo.thickness, geo.youngs_modulus
            nu = geo.poisson_ratio
            self.t_path, self.e_path = f"{g}.thickness", f"{g}.youngs_modulus"
        self.poisson = DEFAULT_POISSON if nu is None else float(nu)
        self.density = (aset.head.material or spec.material).density
        self.arm_density = spec.material.density
        head = aset.head.geometry
        if isinstance(head, DiscGeometry):
            self.head_shape = "disc"
            self.head_x = head.diameter / 2
            self.head_y = head.diameter / 2
        elif isinstance(head, BoxGeometry):
            self.head_shape = "box"
            self.head_x = head.length / 2
            self.head_y = head.width / 2
        else:
            self.head_shape = "disc"
            assert aset.head.mass is not None
            d = head_disc_diameter(
                aset.head.mass.to("kg").magnitude,
                self.density.to("kg/m^3").magnitude,
                self.thickness.to("m").magnitude,
            )
            self.head_x = self.head_y = ureg.Quantity(d / 2, "m").to("um")


def actuator_inputs(spec: DeviceSpec, aset: ActuatorSet) -> ActuatorInputs:
    """The inputs of :func:`frame_geometry` for a set with a drawn actuator.

    Parameters
    ----------
    spec : DeviceSpec
        The device.
    aset : ActuatorSet
        The set.

    Returns
    -------
    ActuatorInputs
        Dimensions [m], modulus [Pa], density [kg/m³] and head mass [kg].
    """
    return ActuatorInputs(spec, aset)


def _si(q: Any, unit: str = "m") -> Any:
    return q.to(unit).magnitude


def frame_geometry(spec: DeviceSpec, aset: ActuatorSet) -> FrameGeometry:
    """The drawn actuator of ``aset`` in SI floats.

    The drawn actuator of ``aset`` in SI floats (or arrays, for sampled specs): the
    one geometry the closed form, the FE check and ``betv layout`` all use.

    Parameters
    ----------
    spec : DeviceSpec
        The device.
    aset : ActuatorSet
        The set.

    Returns
    -------
    FrameGeometry
        Arms, links and head [m].
    """
    a = ActuatorInputs(spec, aset)
    g = a.geometry
    return FrameGeometry(
        length=_si(g.length),
        hot_width=_si(g.hot_arm_width),
        cold_width=_si(g.cold_arm_width),
        flexure_length=_si(g.flexure_length),
        flexure_width=_si(g.flexure_width),
        gap=_si(g.gap),
        tip_length=_si(g.tip_length),
        thickness=_si(a.thickness),
        youngs_modulus=_si(a.youngs, "Pa"),
        head_x=_si(a.head_x),
        head_y=_si(a.head_y),
        head_shape=a.head_shape,
        anchor_size=_si(g.anchor_size),
    )


def _record_drawing(rec: Recorder, a: ActuatorInputs, aset: ActuatorSet) -> None:
    """Record the drawn actuator's inputs: film, arms, flexures, gap, tip and head size.

    Parameters
    ----------
    rec : Recorder
        The record being built.
    a : ActuatorInputs
        The set's drawn actuator.
    aset : ActuatorSet
        The set (its head: drawn, or a disc of its mass).
    """
    geo = a.geometry
    g = "actuator.geometry"
    rec.spec("E", "Young's modulus of the actuator's film", a.e_path, a.youngs.to("GPa"))
    rec.spec("t_a", "actuator film thickness", a.t_path, a.thickness.to("um"))
    rec.spec("L_a", "hot-arm length", f"{g}.length", geo.length.to("um"))
    rec.spec("w_hot", "hot-arm width", f"{g}.hot_arm_width", geo.hot_arm_width.to("um"))
    rec.spec("w_cold", "cold-arm width", f"{g}.cold_arm_width", geo.cold_arm_width.to("um"))
    rec.spec("L_flex", "flexure length", f"{g}.flexure_length", geo.flexure_length.to("um"))
    rec.spec("w_flex", "flexure width", f"{g}.flexure_width", geo.flexure_width.to("um"))
    rec.spec("g_a", "hot-to-cold arm gap", f"{g}.gap", geo.gap.to("um"))
    rec.spec("l_tip", "tip connector length", f"{g}.tip_length", geo.tip_length.to("um"))
    if aset.head.geometry is None:
        rec.add(
            "r_head",
            "head radius (the disc of mass m in the actuator's film)",
            "sqrt(m/(π·ρ_head·t_a))",
            a.head_x.to("um"),
            ("m", "t_a"),
            "um",
        )
    else:
        rec.spec("r_head", "head half-extent along the arms", "head.geometry", a.head_x.to("um"))


def head_springs(
    rec: Recorder, spec: DeviceSpec, aset: ActuatorSet, m: pint.Quantity
) -> dict[str, Any]:
    """Record the closed form's steps (module doc).

    Record the closed form's steps (module doc); returns the quantities K_nn, K_tt
    (``k_nn``, ``k_tt``) and the floats ``k_nt``, ``rho``, ``m_arm`` [SI].

    Parameters
    ----------
    rec : Recorder
        The record being built.
    spec : DeviceSpec
        The device.
    aset : ActuatorSet
        The set.
    m : pint.Quantity
        The head's mass [kg].

    Returns
    -------
    dict
        ``k_nn``, ``k_tt`` [N/m] as quantities; ``k_nt`` [N/m], ``rho`` [-], ``m_arm`` [kg].
    """
    a = ActuatorInputs(spec, aset)
    _record_drawing(rec, a, aset)
    fg = frame_geometry(spec, aset)
    k = frame_stiffness(fg)
    src = "Euler–Bernoulli frame, flexibility method, rigid tip (MODEL.md; Lobontiu & Garcia ch. 4)"
    ins = ("E", "t_a", "L_a", "w_hot", "w_cold", "L_flex", "w_flex", "g_a", "l_tip", "r_head")
    nm = cached_unit("N/m")
    rec.add("K_xx", f"head stiffness along the arms ({src})", "frame closed form",
            ureg.Quantity(k.k_xx, nm), ins, "N/m")  # fmt: skip
    rec.add("K_yy", "head stiffness along the stroke", "frame closed form",
            ureg.Quantity(k.k_yy, nm), ins, "N/m")  # fmt: skip
    rec.add("K_xy", "head stiffness, arms × stroke", "frame closed form",
            ureg.Quantity(k.k_xy, nm), ins, "N/m", signed=True)  # fmt: skip
    theta = aset.contact.impact_angle.to("rad").magnitude
    k_nn, k_tt, k_nt = slider_springs(k, theta)
    tn = ("K_xx", "K_yy", "K_xy", "θ")
    qkq = "Q·K·Qᵀ, Q = [[−sinθ, cosθ], [cosθ, sinθ]]"
    knn = rec.add("K_nn", "head stiffness normal to the slider", qkq + " (n, n)",
                  ureg.Quantity(k_nn, nm), tn, "N/m")  # fmt: skip
    ktt = rec.add("K_tt", "head stiffness along the slider", qkq + " (t, t)",
                  ureg.Quantity(k_tt, nm), tn, "N/m")  # fmt: skip
    rec.add("K_nt", "head stiffness coupling normal × along (the model has none)",
            qkq + " (n, t)", ureg.Quantity(k_nt, nm), tn, "N/m", signed=True)  # fmt: skip
    rho = k_nt / np.sqrt(k_nn * k_tt)
    rec.add("ρ_K", "spring coupling", "K_nt/√(K_nn·K_tt)", ureg.Quantity(rho, cached_unit("")),
            ("K_nt", "K_nn", "K_tt"), "", signed=True)  # fmt: skip
    # the softest direction of K: the first mode's
    kxx, kyy, kxy = (np.asarray(v, dtype=float) for v in (k.k_xx, k.k_yy, k.k_xy))
    ang = 0.5 * np.arctan2(2 * kxy, kxx - kyy) + math.pi / 2
    m_arm = arm_modal_mass(fg, _si(a.arm_density, "kg/m^3"), (np.cos(ang), np.sin(ang)))
    rec.add(
        "m_arm",
        "arms' share of the first mode's mass at the head (Rayleigh, softest direction); "
        "the model's m is the head alone",
        "ρ·Σ A∫(u² + v²)dx / δ²",
        ureg.Quantity(m_arm, "kg").to(cached_unit("ug")),
        ("E", "t_a", "L_a", "w_hot", "w_cold", "L_flex", "w_flex"),
        "ug",
    )
    return {"k_nn": knn, "k_tt": ktt, "k_nt": k_nt, "rho": rho, "m_arm": m_arm}


def drawn_springs(
    rec: Recorder, spec: DeviceSpec, aset: ActuatorSet, m: pint.Quantity
) -> dict[str, Any] | None:
    """The head's springs of a drawn actuator (``actuator.geometry``), recorded.

    The frame's springs are turned into the slider's frame at the impact angle θ, so θ is
    recorded first (:func:`betvdesign.nondim.device.impact_contact` then reuses it).

    Parameters
    ----------
    rec : Recorder
        The record being built.
    spec : DeviceSpec
        The device (its process: film thickness and Young's modulus).
    aset : ActuatorSet
        The actuator set (its actuator's geometry, its head, its contact's θ [deg]).
    m : pint.Quantity
        Head mass [kg].

    Returns
    -------
    dict or None
        As :func:`head_springs`; None without a drawn actuator (nothing recorded).

    References
    ----------
    MODEL.md, "From the drawn actuator to the head's springs".
    """
    if aset.actuator.geometry is None:
        return None
    rec.spec("θ", "impact angle", "contact.impact_angle", aset.contact.impact_angle)
    return head_springs(rec, spec, aset, m)


def drawn_vertical_stiffness(
    rec: Recorder, springs: dict[str, Any], m: pint.Quantity
) -> tuple[pint.Quantity, pint.Quantity]:
    """k_v = K_nn and f_v = √(k_v/m)/2π, where the file gives no vertical resonance.

    Parameters
    ----------
    rec : Recorder
        The record being built.
    springs : dict
        As :func:`head_springs`.
    m : pint.Quantity
        Head mass [kg].

    Returns
    -------
    tuple of pint.Quantity
        f_v [kHz] and k_v [N/m].
    """
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
    return f_v, k_v


def drawn_resonance_beside(rec: Recorder, springs: dict[str, Any], m: pint.Quantity) -> None:
    """Record the drawn actuator's √(K_nn/m)/2π beside the file's f_v.

    Record the drawn actuator's √(K_nn/m)/2π (``f_v,geom``) beside the file's f_v, which
    is the one used.

    Parameters
    ----------
    rec : Recorder
        The record being built.
    springs : dict
        As :func:`head_springs`.
    m : pint.Quantity
        Head mass [kg].
    """
    rec.add(
        "f_v,geom",
        "head vertical resonance of the drawn actuator (not used: the file gives f_v)",
        "√(K_nn/m)/2π",
        (springs["k_nn"] / m) ** 0.5 / (2 * math.pi),
        ("K_nn", "m"),
        "kHz",
    )


def drawn_compliance_ratio(
    rec: Recorder, springs: dict[str, Any], k_v: pint.Quantity
) -> pint.Quantity:
    """k_h = K_tt and α = k_v/k_h, where the file gives none of α, k_h, f_h.

    Parameters
    ----------
    rec : Recorder
        The record being built.
    springs : dict
        As :func:`head_springs`.
    k_v : pint.Quantity
        Vertical contact stiffness [N/m].

    Returns
    -------
    pint.Quantity
        α [-].
    """
    k_h = rec.add(
        "k_h",
        "tangential contact stiffness: the drawn actuator's K_tt",
        "K_tt",
        springs["k_tt"],
        ("K_tt",),
        "N/m",
    )
    return rec.add("α", "relative impact compliance", "k_v/k_h", k_v / k_h, ("k_v", "k_h"), "")


def drawn_alpha_beside(rec: Recorder, springs: dict[str, Any]) -> None:
    """Record the drawn actuator's K_nn/K_tt beside the file's α.

    Record the drawn actuator's K_nn/K_tt (``α_geom``) beside the file's α, which is the
    one used.

    Parameters
    ----------
    rec : Recorder
        The record being built.
    springs : dict
        As :func:`head_springs`.
    """
    rec.add(
        "α_geom",
        "relative impact compliance of the drawn actuator (not used: the file gives it)",
        "K_nn/K_tt",
        springs["k_nn"] / springs["k_tt"],
        ("K_nn", "K_tt"),
        "",
    )


def alpha_given(act: Actuator) -> bool:
    """True when the file gives α, k_h or f_h (then the drawn actuator's α is not used).

    Parameters
    ----------
    act : Actuator
        The actuator.

    Returns
    -------
    bool
        Whether the file gives the ratio.
    """
    return (
        act.alpha is not None
        or act.horizontal_stiffness is not None
        or act.horizontal_resonance is not None
    )


def springs_data(
    springs: dict[str, Any],
    m: pint.Quantity,
    f_v: pint.Quantity,
    alpha: pint.Quantity,
    act: Actuator,
) -> HeadSprings:
    """The drawn actuator's springs as plain data for the rules.

    Parameters
    ----------
    springs : dict
        As :func:`head_springs`.
    m : pint.Quantity
        Head mass [kg].
    f_v : pint.Quantity
        The vertical resonance used [Hz].
    alpha : pint.Quantity
        The α used [-].
    act : Actuator
        The actuator (which of f_v and α its file gives).

    Returns
    -------
    HeadSprings
        Float SI, with which values came from the file.
    """
    file_fv = act.vertical_resonance is not None
    file_alpha = alpha_given(act)
    return HeadSprings(
        k_nn=mag(springs["k_nn"], "N/m"),
        k_tt=mag(springs["k_tt"], "N/m"),
        k_nt=float(springs["k_nt"]),
        rho=float(springs["rho"]),
        m_arm_kg=float(springs["m_arm"]),
        m_head_kg=mag(m, "kg"),
        used={
            "k_v": "file" if file_fv else "geometry",
            "alpha": "file" if file_alpha else "geometry",
        },
        file_f_v_hz=mag(f_v, "Hz") if file_fv else None,
        file_alpha=mag(alpha, "") if file_alpha else None,
    )
