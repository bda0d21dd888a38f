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
- K_nn, K_tt, K_nt: in the slider's frame at the impact angle θ;
- C_nn, C_tt, C_nt: the head's compliance there, C = K⁻¹ (each direction with the other
  free: MODEL.md, "What the model's springs mean"; K_nn alone has the tangential motion
  clamped and reads the arms' axial stiffness);
- C_s,n, C_s,t: the slider beam's own compliance at the contact (bending, both ends
  fixed, Roark Table 8.1 case 1d; axial), in series: k_v,geom = 1/(C_nn + C_s,n),
  k_h,geom = 1/(C_tt + C_s,t); the coupling ρ = C_nt/√(C_nn,tot·C_tt,tot);
- m_v, m_h: Rayleigh effective masses of the frame's static shapes under a normal and a
  tangential load (arms, tip and head: :func:`betvdesign.model.frame.rayleigh_matrices`),
  f_v,geom = √(k_v,geom/m_v)/2π, f_h,geom = √(k_h,geom/m_h)/2π; f_1 the actuator's first
  in-plane mode (Rayleigh–Ritz; within 5 % of the modal FE of
  :mod:`betvdesign.model.frame_fe`, benchmarks/bench_modal.py);
- m_arm: the arms' and tip's share of the first mode's mass at the head.

:func:`head_springs` is called by :mod:`betvdesign.nondim.device`, which decides which of
the drawn f_v and α it uses (the file's resonances win where given) through the steps
here: :func:`drawn_springs` (θ, then :func:`head_springs`),
:func:`drawn_vertical_stiffness`, :func:`drawn_compliance_ratio` or
:func:`drawn_alpha_beside`, and :func:`springs_data` (the plain data the rules read).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pint

from betvdesign.model.frame import (
    FrameGeometry,
    contact_offset,
    directional_mass,
    first_mode,
    frame_stiffness,
    head_compliance,
    head_disc_diameter,
    out_of_plane_first_mode,
    rayleigh_matrices,
    slider_point_compliance,
    slider_springs,
)
from betvdesign.nondim.record import HeadSprings, Recorder, cached_unit, mag
from betvdesign.spec.models import Actuator, ActuatorSet, BoxGeometry, DeviceSpec, DiscGeometry
from betvdesign.spec.units import ureg

__all__ = [
    "ActuatorInputs",
    "actuator_inputs",
    "alpha_given",
    "contact_stiffness",
    "drawn_alpha_beside",
    "drawn_compliance_ratio",
    "drawn_springs",
    "drawn_vertical_stiffness",
    "frame_geometry",
    "head_springs",
    "resonance_compliance_ratio",
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
        if geo.poisson_ratio is not None:
            self.nu_source = f"spec: {g}.poisson_ratio"
        elif nu is not None:
            self.nu_source = f"spec: process {p.name}: layers.{self.layer}.poisson_ratio"
        else:
            self.nu_source = "polysilicon, Sharpe et al. 1997 (the default)"
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
    """The inputs of :func:`frame_geometry` for a set with a drawn actuator."""
    return ActuatorInputs(spec, aset)


def _si(q: Any, unit: str = "m") -> Any:
    return q.to(unit).magnitude


def frame_geometry(spec: DeviceSpec, aset: ActuatorSet) -> FrameGeometry:
    """The drawn actuator of ``aset`` in SI floats (or arrays, for sampled specs).

    The drawn actuator of ``aset`` in SI floats (or arrays, for sampled specs): the
    one geometry the closed form, the FE check and ``betv layout`` all use.
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


def head_springs(
    rec: Recorder, spec: DeviceSpec, aset: ActuatorSet, m: pint.Quantity
) -> dict[str, Any]:
    """Record the closed form's steps of the drawn head's springs.

    Record the closed form's steps (module doc); returns the quantities K_nn, K_tt,
    k_v,geom, k_h,geom, m_v, m_h, f_v,geom, f_h,geom (``k_nn``, ``k_tt``, ``k_v``, ``k_h``,
    ``m_v``, ``m_h``, ``f_v``, ``f_h``) and the floats ``k_nt``, ``rho``, ``m_arm``,
    ``f_1`` [SI].
    """
    a = ActuatorInputs(spec, aset)
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
    return {"k_nn": knn, "k_tt": ktt, "k_nt": k_nt, **_modal_springs(rec, spec, aset, fg, a, m)}


def _slider_contact(spec: DeviceSpec, aset: ActuatorSet, head_x_m: Any) -> tuple[Any, ...]:
    """The slider beam the set's heads strike, and where.

    (L_s, w_s, t_s, E_s, a) [SI] of the slider beam the set's heads strike, a the
    contact's distance from the beam's nearer end as ``betv layout`` draws it
    (:func:`betvdesign.model.frame.contact_offset`).
    """
    sl = spec.slider
    p = spec.process
    if p is not None:
        lay = p.structural(p.structural_name(sl.layer))
        E = lay.youngs_modulus
        c = 0.0 if lay.min_spacing is None else _si(lay.min_spacing) + 2e-9
    else:
        E, c = aset.actuator.geometry.youngs_modulus, 0.0  # type: ignore[union-attr]
    E_s = _si(E, "Pa") if E is not None else _si(ActuatorInputs(spec, aset).youngs, "Pa")
    names = [s.name for s in spec.actuator_sets]  # a what-if copy of the set: by its name
    before = names.index(aset.name) if aset.name in names else len(names)
    k = [s.impact_direction for s in spec.actuator_sets][:before].count(aset.impact_direction)
    L = _si(sl.beam_length)
    x_c = contact_offset(L, head_x_m, c, k)
    return L, _si(sl.beam_width), _si(sl.beam_thickness), E_s, np.maximum(L / 2 - x_c, 0.0)


#: The record's symbols of the drawing's inputs a mode or a modal mass depends on.
_DRAWN_INPUTS = (
    "E",
    "t_a",
    "L_a",
    "w_hot",
    "w_cold",
    "L_flex",
    "w_flex",
    "g_a",
    "l_tip",
    "r_head",
    "m",
)


def _modal_springs(
    rec: Recorder,
    spec: DeviceSpec,
    aset: ActuatorSet,
    fg: FrameGeometry,
    a: ActuatorInputs,
    m: pint.Quantity,
) -> dict[str, Any]:
    """Record the model's springs of the drawn head.

    Record the model's springs of the drawn head (MODEL.md, "What the model's springs
    mean"): the head's compliance C = K⁻¹ in the slider's frame, the slider's in series
    (:func:`_series_springs`), the Rayleigh effective masses and resonances
    (:func:`_rayleigh_resonances`), the coupling and the first modes
    (:func:`_first_modes`).
    """
    theta = aset.contact.impact_angle.to("rad").magnitude
    kv, kh, rho, ctot_n, ctot_t = _series_springs(rec, spec, aset, fg, theta)
    m_kg = np.asarray(mag(m, "kg"), dtype=float)
    C, M, mv, mh, f_v, f_h = _rayleigh_resonances(rec, fg, a, m_kg, theta, kv, kh, ctot_n, ctot_t)
    f1, f_oop, m_arm = _first_modes(rec, fg, a, m_kg, C, M)
    return {"rho": rho, "m_arm": m_arm, "k_v": kv, "k_h": kh, "m_v": mv, "m_h": mh,
            "f_v": f_v, "f_h": f_h, "f_1": f1, "f_oop": f_oop}  # fmt: skip


def _series_springs(
    rec: Recorder, spec: DeviceSpec, aset: ActuatorSet, fg: FrameGeometry, theta: Any
) -> tuple[Any, Any, Any, Any, Any]:
    """Record the head's compliance, the slider's in series and the model's springs.

    Returns
    -------
    tuple
        (k_v,geom, k_h,geom [N/m quantities], the coupling ρ_C [-], the total normal and
        tangential compliances [m/N]).
    """
    theta = aset.contact.impact_angle.to("rad").magnitude
    k = frame_stiffness(fg)
    c_nn, c_tt, c_nt = head_compliance(k, theta)
    mn = cached_unit("m/N")
    inv = "C = K⁻¹ of the slider-frame 2×2 (each direction with the other free; MODEL.md)"
    kk = ("K_nn", "K_tt", "K_nt")
    rec.add("C_nn", "head compliance normal to the slider", inv + " (n, n)",
            ureg.Quantity(c_nn, mn), kk, "m/N")  # fmt: skip
    rec.add("C_tt", "head compliance along the slider", inv + " (t, t)",
            ureg.Quantity(c_tt, mn), kk, "m/N")  # fmt: skip
    rec.add("C_nt", "head compliance, normal × along", inv + " (n, t)",
            ureg.Quantity(c_nt, mn), kk, "m/N", signed=True)  # fmt: skip
    L_s, w_s, t_s, E_s, a_s = _slider_contact(spec, aset, fg.head_x)
    rec.add("a_s", "the contact's distance from the slider beam's nearer end (as betv layout "
            "draws it)", "L_s/2 − max(L_s/4, r_head + spacing) (+ 2(r_head + spacing) per "
            "earlier set striking the same way; 0 at or beyond the end piece)",
            ureg.Quantity(a_s, "m").to(cached_unit("um")), ("r_head",), "um",
            signed=True)  # fmt: skip
    cs_n, cs_t = slider_point_compliance(L_s, w_s, t_s, E_s, a_s, spec.slider.beam_count)
    cs_n = cs_n if np.ndim(cs_n) else float(cs_n)
    rec.add("C_s,n", "slider beam's bending compliance at the contact (both ends fixed by "
            "the mirrored pair of heads; none with one beam)",
            "a³b³/(3·E·I·L³), b = L − a, I = t·w³/12 (Roark, Formulas for Stress and Strain, "
            "Table 8.1 case 1d)", ureg.Quantity(cs_n, mn), ("a_s",), "m/N",
            signed=True)  # fmt: skip
    rec.add("C_s,t", "slider beam's axial compliance at the contact (both ends fixed)",
            "a·b/(E·A·L), A = w·t (Gere, Mechanics of Materials, statically indeterminate "
            "bar)", ureg.Quantity(cs_t, mn), ("a_s",), "m/N", signed=True)  # fmt: skip
    ctot_n, ctot_t = c_nn + cs_n, c_tt + cs_t
    nm = cached_unit("N/m")
    kv = rec.add("k_v,geom", "normal spring of the drawn head against the slider",
                 "1/(C_nn + C_s,n)", ureg.Quantity(1 / ctot_n, nm), ("C_nn", "C_s,n"),
                 "N/m")  # fmt: skip
    kh = rec.add("k_h,geom", "tangential spring of the drawn head against the slider",
                 "1/(C_tt + C_s,t)", ureg.Quantity(1 / ctot_t, nm), ("C_tt", "C_s,t"),
                 "N/m")  # fmt: skip
    rho = c_nt / np.sqrt(ctot_n * ctot_t)
    rec.add("ρ_C", "spring coupling (the model has none)", "C_nt/√((C_nn + C_s,n)(C_tt + C_s,t))",
            ureg.Quantity(rho, cached_unit("")), ("C_nt", "C_nn", "C_tt", "C_s,n", "C_s,t"),
            "", signed=True)  # fmt: skip
    return kv, kh, rho, ctot_n, ctot_t


def _rayleigh_resonances(
    rec: Recorder,
    fg: FrameGeometry,
    a: ActuatorInputs,
    m_kg: Any,
    theta: Any,
    kv: Any,
    kh: Any,
    ctot_n: Any,
    ctot_t: Any,
) -> tuple[Any, Any, Any, Any, Any, Any]:
    """Record the Rayleigh effective masses and the drawn resonances f_v, f_h.

    Returns
    -------
    tuple
        (the static shapes' compliance and mass matrices C, M, m_v, m_h [ug], f_v,geom,
        f_h,geom [kHz]).
    """
    C, M = rayleigh_matrices(fg, _si(a.arm_density, "kg/m^3"), m_kg)
    s, c = np.sin(theta), np.cos(theta)
    n_dir = np.stack(np.broadcast_arrays(c, s), axis=-1)  # n in the actuator's (x, y)
    t_dir = np.stack(np.broadcast_arrays(-s, c), axis=-1)
    ray = "Rayleigh, the frame's static shape under the load (arms, tip, head): "
    masses = {}
    for sym, d, c_tot in (("m_v", n_dir, ctot_n), ("m_h", t_dir, ctot_t)):
        kin = np.einsum("...i,...ij,...j->...", d, M, d)
        masses[sym] = kin / (c_tot * c_tot)
    ins = _DRAWN_INPUTS
    ug = cached_unit("ug")
    mv = rec.add("m_v", "effective mass of the normal spring (" + ray.rstrip(": ") + ")",
                 "dᵀM d/(C_nn + C_s,n)², d = n, M the static shapes' mass matrix",
                 ureg.Quantity(masses["m_v"], "kg").to(ug), ins, "ug")  # fmt: skip
    mh = rec.add("m_h", "effective mass of the tangential spring (" + ray.rstrip(": ") + ")",
                 "dᵀM d/(C_tt + C_s,t)², d = t", ureg.Quantity(masses["m_h"], "kg").to(ug),
                 ins, "ug")  # fmt: skip
    khz = cached_unit("kHz")
    f_v = rec.add("f_v,geom", "head vertical resonance of the drawn actuator (Rayleigh)",
                  "√(k_v,geom/m_v)/2π", ((kv / mv) ** 0.5 / (2 * math.pi)).to(khz),
                  ("k_v,geom", "m_v"), "kHz")  # fmt: skip
    f_h = rec.add("f_h,geom", "head tangential resonance of the drawn actuator (Rayleigh)",
                  "√(k_h,geom/m_h)/2π", ((kh / mh) ** 0.5 / (2 * math.pi)).to(khz),
                  ("k_h,geom", "m_h"), "kHz")  # fmt: skip
    return C, M, mv, mh, f_v, f_h


def _first_modes(
    rec: Recorder, fg: FrameGeometry, a: ActuatorInputs, m_kg: Any, C: Any, M: Any
) -> tuple[Any, Any, Any]:
    """Record the first in-plane and out-of-plane modes and the arms' modal mass.

    Returns
    -------
    tuple
        (f_1 [Hz], f_oop [Hz], m_arm [kg]).
    """
    ins = _DRAWN_INPUTS
    khz, ug = cached_unit("kHz"), cached_unit("ug")
    f1, d1 = first_mode(C, M)
    rec.add("f_1", "first in-plane mode of the drawn actuator with its head, free of the "
            "slider (Rayleigh–Ritz over the static shapes along x and y)",
            "min fᵀCf/fᵀMf", ureg.Quantity(f1, "Hz").to(khz), ins, "kHz")  # fmt: skip
    rec.add("ν", "Poisson's ratio of the actuator's film (torsion: G = E/(2(1 + ν)))",
            a.nu_source, ureg.Quantity(a.poisson, cached_unit("")), (), "")  # fmt: skip
    f_oop = out_of_plane_first_mode(fg, _si(a.arm_density, "kg/m^3"), m_kg, a.poisson)
    rec.add("f_oop", "first out-of-plane mode of the drawn actuator with its head "
            "(Rayleigh–Ritz over the static shapes under a force and two moments at the head; "
            "bending w·t³/12 and torsion G·J of the arms, Roark Table 10.7)",
            "min fᵀCf/fᵀMf (out of plane)", ureg.Quantity(f_oop, "Hz").to(khz),
            (*ins, "ν"), "kHz")  # fmt: skip
    # the arms' (and tip's) share of the first mode's mass at the head
    C0, M0 = rayleigh_matrices(fg, _si(a.arm_density, "kg/m^3"), 0.0 * m_kg)
    m_arm = directional_mass(C0, M0, d1)[1]
    rec.add(
        "m_arm",
        "arms' and tip's share of the first mode's mass at the head (Rayleigh); the model's "
        "m is the head alone",
        "dᵀM₀d/(dᵀCd)², d the first mode's load direction, M₀ without the head",
        ureg.Quantity(m_arm, "kg").to(ug),
        ins[:-1],
        "ug",
    )
    return f1, f_oop, m_arm


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


def contact_stiffness(
    rec: Recorder, m: pint.Quantity, f_v: pint.Quantity, description: str
) -> pint.Quantity:
    """Record k_v = m·(2π·f_v)², the spring that gives the head of mass m its resonance.

    Parameters
    ----------
    rec : Recorder
        The record being built.
    m : pint.Quantity
        Head mass [kg].
    f_v : pint.Quantity
        Vertical resonance used [Hz].
    description : str
        The record's description of k_v.

    Returns
    -------
    pint.Quantity
        k_v [N/m].
    """
    return rec.add(
        "k_v", description, "m·(2π·f_v)²", m * (2 * math.pi * f_v) ** 2, ("m", "f_v"), "N/m"
    )


def resonance_compliance_ratio(
    rec: Recorder, f_v: pint.Quantity, f_h: pint.Quantity
) -> pint.Quantity:
    """Record α = (f_v/f_h)², the relative impact compliance of two resonances.

    Parameters
    ----------
    rec : Recorder
        The record being built.
    f_v, f_h : pint.Quantity
        Vertical and tangential resonances [Hz].

    Returns
    -------
    pint.Quantity
        α [-].
    """
    return rec.add(
        "α", "relative impact compliance", "(f_v/f_h)²", (f_v / f_h) ** 2, ("f_v", "f_h"), ""
    )


def drawn_vertical_stiffness(
    rec: Recorder, springs: dict[str, Any], m: pint.Quantity
) -> tuple[pint.Quantity, pint.Quantity]:
    """f_v = f_v,geom and k_v = m·(2π·f_v)², where the file gives no vertical resonance.

    The drawn resonance plays the part of a measured one: the model's head of mass m gets
    the spring that gives it the drawn head's resonance (arms and tip included through
    the effective mass, :func:`head_springs`).

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
    f_v = rec.add(
        "f_v",
        "head vertical resonance: the drawn actuator's",
        "f_v,geom",
        springs["f_v"],
        ("f_v,geom",),
        "kHz",
    )
    return f_v, contact_stiffness(rec, m, f_v, "vertical contact stiffness on the head's mass")


def drawn_compliance_ratio(
    rec: Recorder, springs: dict[str, Any], f_v: pint.Quantity
) -> pint.Quantity:
    """f_h = f_h,geom and α = (f_v/f_h)², where the file gives none of α, k_h, f_h.

    Parameters
    ----------
    rec : Recorder
        The record being built.
    springs : dict
        As :func:`head_springs`.
    f_v : pint.Quantity
        Vertical resonance used [Hz].

    Returns
    -------
    pint.Quantity
        α [-].
    """
    f_h = rec.add(
        "f_h",
        "head tangential resonance: the drawn actuator's",
        "f_h,geom",
        springs["f_h"],
        ("f_h,geom",),
        "kHz",
    )
    return resonance_compliance_ratio(rec, f_v, f_h)


def drawn_alpha_beside(rec: Recorder, springs: dict[str, Any]) -> None:
    """Record the drawn actuator's α beside the file's α.

    Record the drawn actuator's (f_v,geom/f_h,geom)² (``α_geom``) beside the file's α,
    which is the one used.

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
        "(f_v,geom/f_h,geom)²",
        (springs["f_v"] / springs["f_h"]) ** 2,
        ("f_v,geom", "f_h,geom"),
        "",
    )


def alpha_given(act: Actuator) -> bool:
    """True when the file gives α, k_h or f_h (then the drawn actuator's α is not used)."""
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
        k_v=mag(springs["k_v"], "N/m"),
        k_h=mag(springs["k_h"], "N/m"),
        m_v_kg=mag(springs["m_v"], "kg"),
        m_h_kg=mag(springs["m_h"], "kg"),
        f_v_hz=mag(springs["f_v"], "Hz"),
        f_h_hz=mag(springs["f_h"], "Hz"),
        f_1_hz=float(springs["f_1"]),
        f_oop_hz=float(springs["f_oop"]),
    )
