"""The predicted stroke's figures (sets whose stroke comes from the drawing): u(V) and u(f).

A set without ``actuator.amplitude`` or ``actuator.calibration`` but with a drawn
actuator gets its stroke from the electrothermal model of the drawing and the process
(:mod:`betvdesign.nondim.stroke`, :mod:`betvdesign.model.electrothermal`). The report
shows what that model says around the device:

- **u(V)**: the stroke at the drive (its frequency and waveform:
  :func:`~betvdesign.model.electrothermal.stroke_amplitude`) and the static stroke at a
  DC voltage V, from 0 up to the voltage where the actuator's peak temperature reaches
  the layer's melting point (:func:`melting_voltage`, bisected on
  :func:`~betvdesign.model.electrothermal.electrothermal`'s T_max), with T_max itself;
- **u(f)**: the stroke against the actuation frequency with the drawing's own thermal
  roll-off (:meth:`betvdesign.nondim.record.Scales.amplitude_m`, the thermal modes of the
  device's operating point through
  :func:`~betvdesign.model.electrothermal.modal_gain`), the thermal cut-off and the
  design window's band 0.5·f_v ≤ f_act < 2·f_v marked.

Nothing is fitted: every number comes from the drawing and the process file.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from betvdesign import plots
from betvdesign.model.domain import VARPI_WINDOW
from betvdesign.model.electrothermal import electrothermal, stroke_amplitude
from betvdesign.nondim.actuator import frame_geometry
from betvdesign.nondim.record import SetDerivation
from betvdesign.nondim.stroke import thermal_material
from betvdesign.output.siformat import format_si
from betvdesign.report.analysis import Missing, Piece
from betvdesign.report.figures import figure_block
from betvdesign.report.model import FigureBlock
from betvdesign.spec.models import DeviceSpec

__all__ = ["StrokeSweep", "figures", "melting_voltage", "stroke_sweep"]

#: Drive voltages of the u(V) curve (the device's own and the melting voltage added).
VOLTAGE_POINTS = 41
#: Actuation frequencies of the u(f) curve (log-spaced; the device's own added).
FREQUENCY_POINTS = 121
#: Relative width [-] of the melting voltage's final bracket.
MELTING_RTOL = 1e-9
#: Doublings of the voltage allowed to bracket the melting point, and bisection steps.
MAX_DOUBLINGS = 60
MAX_BISECTIONS = 100

MODEL = (
    "electrothermal model of the drawn hot/cold-arm actuator (1-D fins with Joule heat, "
    "ρ(T), substrate loss through the air gap; α(T) integrated along the arms; the frame's "
    "stiffness loaded by their elongation; thermal modes of the same chain), no fit; the "
    "slider's motion is not solved (no rung of the fidelity ladder)"
)


@dataclass(frozen=True)
class StrokeSweep:
    """The predicted stroke around the device, float SI.

    Attributes
    ----------
    volts : numpy.ndarray
        Drive voltages V [V], 0 to max(melting voltage, the device's).
    stroke_m, static_m, t_max_k : numpy.ndarray
        At each V: the stroke at the drive [m], the static stroke [m], the peak
        temperature [K] (both at a DC voltage V).
    device_v, melting_v, melting_k : float
        The device's voltage [V], where T_max reaches the melting point [V], and that
        melting point [K].
    onset_v, onset_k : float or None
        Where T_max reaches the layer's onset of plastic deformation [V] (bisected like
        the melting voltage), and that onset [K]; None when the process gives no onset.
    f_act_hz, stroke_f_m : numpy.ndarray
        Actuation frequencies [Hz] and the stroke there [m] (the drawing's roll-off).
    solves : int
        Electrothermal solutions computed.
    """

    volts: np.ndarray
    stroke_m: np.ndarray
    static_m: np.ndarray
    t_max_k: np.ndarray
    device_v: float
    melting_v: float
    melting_k: float
    f_act_hz: np.ndarray
    stroke_f_m: np.ndarray
    solves: int
    onset_v: float | None = None
    onset_k: float | None = None

    @property
    def device_index(self) -> int:
        """The index of the device's voltage in :attr:`volts` (there exactly)."""
        return int(np.flatnonzero(self.volts == self.device_v)[0])


def melting_voltage(
    t_max_at: Any, melting_k: float, start_v: float, *, rtol: float = MELTING_RTOL
) -> tuple[float, int]:
    """The voltage where the peak temperature reaches a temperature (the melting point), bisected.

    Parameters
    ----------
    t_max_at : callable
        V [V] -> the peak temperature T_max [K] at a DC voltage V (increasing in V).
    melting_k : float
        The melting point [K].
    start_v : float
        A first guess [V] (> 0): doubled until T_max reaches the melting point.
    rtol : float
        Relative width [-] of the final bracket.

    Returns
    -------
    tuple
        (V_melt [V], the upper end of the final bracket: T_max(V_melt) ≥ the melting
        point, T_max(V_melt·(1 − rtol)) below it; the number of T_max evaluations).

    Raises
    ------
    Missing
        When no voltage below 2^60·start_v reaches the melting point, or T_max is not
        finite.
    """
    lo, hi, n = 0.0, max(float(start_v), 1e-3), 0
    for _ in range(MAX_DOUBLINGS):
        t = t_max_at(hi)
        n += 1
        if not math.isfinite(t):
            raise Missing(f"the peak temperature at {hi:.4g} V is not finite")
        if t >= melting_k:
            break
        lo, hi = hi, 2 * hi
    else:
        raise Missing(f"the peak temperature stays below the melting point up to {hi:.4g} V")
    for _ in range(MAX_BISECTIONS):
        if hi - lo <= rtol * hi:
            break
        mid = 0.5 * (lo + hi)
        t = t_max_at(mid)
        n += 1
        if not math.isfinite(t):
            raise Missing(f"the peak temperature at {mid:.4g} V is not finite")
        lo, hi = (mid, hi) if t < melting_k else (lo, mid)
    return hi, n


def stroke_sweep(spec: DeviceSpec, sd: SetDerivation) -> StrokeSweep:
    """The u(V) and u(f) data of a set whose stroke is predicted (module doc).

    Parameters
    ----------
    spec : DeviceSpec
        The device (its process).
    sd : SetDerivation
        The set's derivation (its :attr:`~SetDerivation.stroke` not None).

    Returns
    -------
    StrokeSweep
        The curves.

    Raises
    ------
    Missing
        For a set whose stroke the file gives, or an electrothermal solution that
        failed.
    """
    st = sd.stroke
    if st is None:
        raise Missing("the stroke is given by the device file, not predicted from the drawing")
    aset = sd.actuator_set
    g = frame_geometry(spec, aset)
    mat = thermal_material(spec, aset)
    drive_hz = float(aset.drive.frequency.to("Hz").magnitude)
    waveform = aset.drive.waveform

    def solve(v: float) -> Any:
        res = electrothermal(g, mat, v)
        if res.status == "not_converged":
            raise Missing(f"the electrothermal model at {v:.4g} V: {res.message}")
        return res

    melt_v, n = melting_voltage(lambda v: solve(v).t_max, st.melting_k, st.voltage_v)
    onset_v = None
    if st.deformation_k is not None:
        onset_v, n_onset = melting_voltage(lambda v: solve(v).t_max, st.deformation_k, st.voltage_v)
        n += n_onset
    top = max(melt_v, st.voltage_v)
    extra = [st.voltage_v, melt_v] + ([] if onset_v is None else [onset_v])
    volts = np.unique(np.concatenate([np.linspace(0.0, top, VOLTAGE_POINTS), extra]))
    rows = [solve(float(v)) for v in volts]
    n += len(rows)
    stroke = np.array([stroke_amplitude(r, drive_hz, waveform)[0] for r in rows])
    sc = sd.scales
    f_v = sc.f_act_hz / sd.params.varpi
    marks = [sc.f_act_hz, st.f_cutoff_hz, st.f_thermal_hz, VARPI_WINDOW[0] * f_v,
             VARPI_WINDOW[1] * f_v]  # fmt: skip
    lo, hi = min(marks) / 10, max(marks) * 10
    f = np.unique(np.append(np.geomspace(lo, hi, FREQUENCY_POINTS), sc.f_act_hz))
    return StrokeSweep(
        volts=volts,
        stroke_m=stroke,
        static_m=np.array([r.u_static for r in rows]),
        t_max_k=np.array([r.t_max for r in rows]),
        device_v=st.voltage_v,
        melting_v=melt_v,
        melting_k=st.melting_k,
        f_act_hz=f,
        stroke_f_m=np.asarray(sc.amplitude_m(f), dtype=float),
        solves=n,
        onset_v=onset_v,
        onset_k=st.deformation_k,
    )


def _process_text(spec: DeviceSpec, sd: SetDerivation) -> str:
    """The process and layer whose data the model used, in words."""
    geo = sd.actuator_set.actuator.geometry
    process = spec.process
    name = getattr(process, "name", None) or "the process file"
    layer = process.structural_name(geo.layer) if process is not None and geo is not None else ""
    return f"process {name}" + (f", layer {layer}" if layer else "")


def stroke_voltage(
    key: str, spec: DeviceSpec, sd: SetDerivation, piece: Piece[StrokeSweep]
) -> FigureBlock:
    """The u(V) figure block (module doc).

    Parameters
    ----------
    key : str
        Figure key.
    spec : DeviceSpec
        The device (its process, named in the caption).
    sd : SetDerivation
        The set (its predicted stroke).
    piece : Piece of StrokeSweep
        The data, or why there are none.

    Returns
    -------
    FigureBlock
        The figure or the reason it is missing.
    """
    st = sd.stroke
    assert st is not None
    aset = sd.actuator_set
    heat = {"ac": "2·f_drive (AC, zero DC)", "unipolar": "f_drive (unipolar square)",
            "dc-biased": "f_drive (DC-biased)"}[aset.drive.waveform]  # fmt: skip
    half = ("u = u_static/2·Σ a_i·tanh(1/(4f·τ_i))" if aset.drive.waveform == "unipolar"
            else "u = u_static/2·|H|")  # fmt: skip
    caption = (
        "The stroke predicted from the drawing against the drive voltage amplitude V: solid, "
        f"the head's half swing u at the drive ({format_si(st.f_heat_hz, 'Hz')} heating, "
        f"{heat}: {half}, the roll-off of the drawing's thermal modes at V); "
        "dashed, the static stroke u_static at a DC voltage V; right axis, the actuator's "
        f"peak temperature T_max at a DC voltage V (the AC crest's). Data: the drawn "
        f"actuator and the electrothermal data of {_process_text(spec, sd)} (sheet "
        "resistance and its temperature coefficient, thermal conductivities, expansion "
        "law, gap to the substrate, melting point); nothing is fitted."
    )
    s = piece.value
    if s is not None:
        i = s.device_index
        caption += (
            f" The device at {s.device_v:.4g} V: u = {format_si(float(s.stroke_m[i]), 'm')}, "
            f"u_static = {format_si(float(s.static_m[i]), 'm')}, T_max = "
            f"{float(s.t_max_k[i]):.4g} K. T_max reaches the melting point "
            f"{s.melting_k:.4g} K at {s.melting_v:.4g} V (bisected; dotted)"
            + (
                f": the device's voltage is {s.device_v / s.melting_v:.3g}× that."
                if s.device_v > s.melting_v
                else f", {s.melting_v / s.device_v:.3g}× the device's."
            )
            + (
                ""
                if s.onset_v is None
                else f" It reaches the onset of plastic deformation {s.onset_k:.4g} K at "
                f"{s.onset_v:.4g} V (dash-dotted; the rule thermal.peak-temperature's error "
                "threshold)."
            )
            + f" {len(s.volts)} voltages."
        )

    def draw(ax: Any) -> None:
        i = s.device_index
        plots.stroke_vs_voltage(
            s.volts,
            s.stroke_m,
            s.static_m,
            s.t_max_k,
            device_v=s.device_v,
            device_stroke_m=float(s.stroke_m[i]),
            melting_v=s.melting_v,
            melting_k=s.melting_k,
            onset_v=s.onset_v,
            onset_k=s.onset_k,
            ax=ax,
        )

    return figure_block(
        key,
        "Predicted stroke against drive voltage",
        caption,
        MODEL,
        ("", ""),  # no rung: the slider's motion is not solved (module doc)
        piece,
        draw,
    )


def stroke_frequency(
    key: str, spec: DeviceSpec, sd: SetDerivation, piece: Piece[StrokeSweep]
) -> FigureBlock:
    """The u(f) figure block (module doc).

    Parameters
    ----------
    key : str
        Figure key.
    spec : DeviceSpec
        The device (its process, named in the caption).
    sd : SetDerivation
        The set (its predicted stroke, its scales).
    piece : Piece of StrokeSweep
        The data, or why there are none.

    Returns
    -------
    FigureBlock
        The figure or the reason it is missing.
    """
    st = sd.stroke
    assert st is not None
    sc = sd.scales
    f_v = sc.f_act_hz / sd.params.varpi
    g = 1.0 / math.sqrt(2.0)
    caption = (
        "The stroke predicted from the drawing against the actuation frequency f_act at the "
        f"device's voltage {st.voltage_v:.4g} V: u(f) = u_static/2·G(f), G the gain of the "
        "drawn actuator's thermal modes (their time constants and shares of the static "
        "stroke at that voltage) at the heating frequency, which is f_act for every "
        "waveform (2·f_drive for AC). Dotted: the thermal cut-off f_c = "
        f"{format_si(st.f_cutoff_hz, 'Hz')} (|H| = {g:.3g}); dash-dotted: the first thermal "
        f"mode {format_si(st.f_thermal_hz, 'Hz')}; shaded: the design window's actuation "
        f"frequencies 0.5·f_v ≤ f_act < 2·f_v (f_v = {format_si(f_v, 'Hz')}, top axis "
        f"ϖ = f_act/f_v). Data: the drawn actuator and the electrothermal data of "
        f"{_process_text(spec, sd)}; nothing is fitted. At the device's f_act = "
        f"{format_si(sc.f_act_hz, 'Hz')}: u = {format_si(sc.u_m, 'm')}, "
        f"{st.gain:.3g} of u_static/2."
    )
    s = piece.value
    if s is not None:
        caption += f" {len(s.f_act_hz)} frequencies."

    def draw(ax: Any) -> None:
        plots.stroke_vs_frequency(
            s.f_act_hz,
            s.stroke_f_m,
            f_v_hz=f_v,
            cutoff_hz=st.f_cutoff_hz,
            operating=(sc.f_act_hz, sc.u_m),
            static_half_m=st.u_static_m / 2,
            thermal_hz=st.f_thermal_hz,
            ax=ax,
        )

    return figure_block(
        key,
        "Predicted stroke against actuation frequency",
        caption,
        MODEL,
        ("", ""),  # no rung: the slider's motion is not solved (module doc)
        piece,
        draw,
    )


def figures(
    key: str, spec: DeviceSpec, sd: SetDerivation, piece: Piece[StrokeSweep]
) -> list[FigureBlock]:
    """The u(V) and u(f) figures of a set whose stroke is predicted (none otherwise).

    Parameters
    ----------
    key : str
        Prefix of the figures' keys.
    spec : DeviceSpec
        The device.
    sd : SetDerivation
        The set.
    piece : Piece of StrokeSweep
        :func:`stroke_sweep`'s data, or why there are none.

    Returns
    -------
    list of FigureBlock
        Two figures, or none for a stroke the file gives.
    """
    if sd.stroke is None:
        return []
    return [
        stroke_voltage(f"{key}-uv", spec, sd, piece),
        stroke_frequency(f"{key}-uf", spec, sd, piece),
    ]
