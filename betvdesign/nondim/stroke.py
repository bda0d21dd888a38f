"""The drawn actuator's stroke at the drive, predicted from the drawing and the process.

A device file that gives neither ``actuator.amplitude`` nor ``actuator.calibration`` but
a drawn ``actuator.geometry`` (:attr:`betvdesign.spec.models.Actuator.drawn_stroke`) gets
its stroke u from the electrothermal model of the drawn hot/cold-arm actuator
(:mod:`betvdesign.model.electrothermal`): the drive voltage V across the anchors, the
process's electrothermal data of the actuator's layer (sheet resistance, its temperature
coefficient, conductivities, specific heat, expansion law, the gap to the substrate),
the geometry the springs use (:func:`betvdesign.nondim.actuator.frame_geometry`). Every
step is recorded with its formula and basis.

The stroke at the actuation frequency is the half swing of the head's motion (the model's
amplitude u) at the heating frequency of the waveform
(:func:`betvdesign.model.electrothermal.stroke_amplitude`): AC with zero DC heats at 2f
(P ∝ V²·sin²ωt = V²/2·(1 − cos 2ωt): u = u_static(V)/2·|H(2f)|), unipolar and
DC-biased drives at f. The roll-off |H| comes from the same drawing's thermal modes: no
fitted cut-off.

References
----------
docs/MODEL.md, "From the drawn actuator to the head's springs"; issue 31.
"""

from __future__ import annotations

import functools
import math
from typing import Any

import pint

from betvdesign.errors import ParameterError
from betvdesign.model.electrothermal import electrothermal, modal_gain, stroke_amplitude
from betvdesign.nondim.actuator import frame_geometry
from betvdesign.nondim.record import DrawnStroke, Recorder
from betvdesign.spec.models import ActuatorSet, DeviceSpec
from betvdesign.spec.units import ureg

__all__ = ["DrawnStroke", "drawn_stroke"]


@functools.lru_cache(maxsize=256)
def _electrothermal(g: Any, mat: Any, volts: float) -> Any:
    """Solve :func:`electrothermal` once per drawing, material and voltage.

    A study that changes no drawn dimension, layer or voltage (``betv fix``'s drive
    frequency, slider or contact candidates) solves the actuator once: the inputs are
    frozen dataclasses of floats.
    """
    return electrothermal(g, mat, volts)


def thermal_material(spec: DeviceSpec, aset: ActuatorSet) -> Any:
    """The process's electrothermal data of the actuator's layer (a clear error if none).

    Parameters
    ----------
    spec : DeviceSpec
        The device (its process).
    aset : ActuatorSet
        The actuator set (its drawn actuator's layer).

    Returns
    -------
    ThermalMaterial
        Float SI data.

    Raises
    ------
    ParameterError
        Without a process, or when the process lacks the layer's electrothermal data
        (naming the missing section).
    """
    geo = aset.actuator.geometry
    if spec.process is None:
        raise ParameterError(
            "the stroke is predicted from the drawing (no "
            "actuator.amplitude or actuator.calibration), which needs a process file with the "
            "actuator layer's electrothermal data: give 'process:' (e.g. polymumps)"
        )
    try:
        return spec.process.thermal_material(None if geo is None else geo.layer)
    except ValueError as exc:
        raise ParameterError(str(exc)) from None


def drawn_stroke(
    rec: Recorder, spec: DeviceSpec, aset: ActuatorSet
) -> tuple[pint.Quantity, DrawnStroke]:
    """Record the drawn actuator's electrothermal steps and its stroke u at the drive.

    Parameters
    ----------
    rec : Recorder
        The record being built.
    spec : DeviceSpec
        The device (its process's electrothermal data).
    aset : ActuatorSet
        The set (its drawn actuator, its drive: voltage, frequency, waveform).

    Returns
    -------
    tuple
        u [um] and the :class:`DrawnStroke` data.

    Raises
    ------
    ParameterError
        Missing process data, or a stroke that is not finite and > 0.
    """
    mat = thermal_material(spec, aset)
    g = frame_geometry(spec, aset)
    drive = aset.drive
    v = drive.voltage
    assert v is not None  # the spec requires it for a drawn stroke
    volts = float(v.to("V").magnitude)
    f_drive = float(drive.frequency.to("Hz").magnitude)
    rec.spec("V", "drive voltage (amplitude)", "drive.voltage", v)
    res = _electrothermal(g, mat, volts)
    if not (math.isfinite(res.u_static) and math.isfinite(res.t_max)):
        raise ParameterError(f"the electrothermal model gave no finite answer: {res.message}")
    src = "electrothermal model of the drawing (MODEL.md; Huang & Lee 1999, Lin & Chiao 1996)"
    ins = ("V",)
    rec.add("R", f"actuator resistance at V ({src})", "V/I, ρ(T) = ρ_0·(1 + ξ·θ)",
            ureg.Quantity(res.resistance, "ohm"), ins, "ohm")  # fmt: skip
    rec.add("I", "actuator current at V", "V = I·R(I) (bisection)",
            ureg.Quantity(res.current, "A"), ins, "mA")  # fmt: skip
    rec.add("P", "electrical power at V", "V·I", ureg.Quantity(res.power, "W"), ("V", "I"), "mW")
    rec.add("T_max", f"peak temperature at V (in the {res.t_max_segment})",
            "1-D fins with Joule heat and substrate loss (exact)",
            ureg.Quantity(res.t_max, "K"), ins, "K")  # fmt: skip
    rec.add("u_static", "steady stroke of the head at a DC voltage V",
            "frame loaded by the arms' thermal elongation ∫ε_th(T) dx",
            ureg.Quantity(res.u_static, "m"), ("T_max",), "um")  # fmt: skip
    rec.add("f_th", "thermal corner of the actuator's first thermal mode", "1/(2π·τ_th)",
            ureg.Quantity(res.f_thermal, "Hz"), (), "Hz")  # fmt: skip
    rec.add("f_c,th", "thermal cut-off of the stroke (|H| = 1/√2)",
            "|Σ a_i/(1 + j·2π·f·τ_i)| = 1/√2", ureg.Quantity(res.f_cutoff, "Hz"), ("f_th",),
            "Hz")  # fmt: skip
    u_m, f_heat = stroke_amplitude(res, f_drive, drive.waveform)
    gain = float(modal_gain(res.modes, f_heat, drive.waveform))
    heat = {"ac": "2·f_drive (AC, zero DC)", "unipolar": "f_drive (unipolar)",
            "dc-biased": "f_drive (DC-biased)"}[drive.waveform]  # fmt: skip
    rec.add("f_heat", "heating frequency of the drive", heat, ureg.Quantity(f_heat, "Hz"), (), "Hz")
    form = ("Σ a_i·tanh(1/(4·f_heat·τ_i)) (square wave)" if drive.waveform == "unipolar"
            else "|Σ a_i/(1 + j·2π·f_heat·τ_i)|")  # fmt: skip
    rec.add("|H|", "thermal roll-off of the stroke at f_heat", form, gain, ("f_heat", "f_th"))
    half = {"ac": "u_static/2·|H|", "dc-biased": "u_static/2·|H|",
            "unipolar": "u_static/2·Σ a_i·tanh(1/(4f·τ_i))"}[drive.waveform]  # fmt: skip
    u = rec.add("u", "actuator amplitude at the drive (predicted from the drawing)", half,
                ureg.Quantity(u_m, "m"), ("u_static", "|H|"), "um")  # fmt: skip
    data = DrawnStroke(
        status=res.status,
        message=res.message,
        voltage_v=volts,
        stroke_m=u_m,
        u_static_m=res.u_static,
        t_max_k=res.t_max,
        t_max_where=res.t_max_segment,
        melting_k=float(mat.melting_temperature),
        power_w=res.power,
        current_a=res.current,
        resistance_ohm=res.resistance,
        f_thermal_hz=res.f_thermal,
        f_cutoff_hz=res.f_cutoff,
        f_heat_hz=f_heat,
        gain=gain,
        modes=tuple(res.modes),
        deformation_k=mat.deformation_temperature,
    )
    return u, data
