"""Device specification models (pydantic v2, frozen, extra fields forbidden).

A :class:`DeviceSpec` is what a device YAML file holds (see devices/*.yaml and
``betv schema``). Every dimensional value is a pint quantity of
:data:`betvdesign.spec.units.ureg`; bare numbers are rejected where a unit is due.
The physical meaning of each field is in docs/MODEL.md, "Physical quantities"
and "Device-to-parameter relations".
"""

from __future__ import annotations

import itertools
from typing import Annotated, Any, Literal

import numpy as np
import pint
from pydantic import Field, field_validator, model_validator

from betvdesign.errors import ParameterError
from betvdesign.model import damping
from betvdesign.model.rolloff import calibration_problem
from betvdesign.model.rolloff import cutoff_from_time_constant as cutoff_hz
from betvdesign.spec import limits
from betvdesign.spec.process import MIN_DRAWN, Modulus, Process, StrictModel
from betvdesign.spec.units import (
    Density,
    Duration,
    Frequency,
    ImpactAngle,
    Length,
    LinearGain,
    Mass,
    NonNegativeLength,
    NonNegativeMass,
    NonNegativeVoltage,
    QuadraticGain,
    Stiffness,
    Voltage,
    format_quantity,
    parse_quantity,
    ureg,
)

Mode = Literal["push", "pull"]

#: Dry-friction coefficients accepted for μ: (0, MU_MAX]. Measured values for
#: polysilicon on polysilicon lie around 0.2–0.8 (MODEL.md uses 0.4); a value above
#: 1.5 is far outside anything reported and almost certainly a typo.
MU_MAX = 1.5


def at(path: str, message: str) -> ValueError:
    """A cross-field error that belongs to a sub-field of the model raising it.

    The loader moves the error's file position to that field; read directly, the
    message says ``@path: message``.

    Parameters
    ----------
    path : str
        The sub-field, relative to the model (``"points[1].voltage"``).
    message : str
        What is wrong.

    Returns
    -------
    ValueError
        To raise from a model validator.
    """
    return ValueError(f"@{path}: {message}")


class Material(StrictModel):
    """A structural material [density in mass/length³]."""

    name: str = Field(min_length=1, max_length=limits.MAX_NAME_CHARS)
    """Material name (free text)."""
    density: Density
    """Density ρ, e.g. '2330 kg/m^3'."""


#: Named materials a file can refer to by name (``material: polysilicon``).
MATERIALS: dict[str, Material] = {
    "polysilicon": Material(name="polysilicon", density=parse_quantity("2330 kg/m^3")),
}
POLYSILICON = MATERIALS["polysilicon"]


def _lower(value: Any) -> Any:
    """Lower-case enum words before validation (files are case-insensitive).

    Enum words are case-insensitive in files (``AC``, ``Push``, ``+X``): lower-cased
    before validation, so the model holds the canonical spelling.
    """
    return value.strip().lower() if isinstance(value, str) else value


def _lower_tag(tag: str) -> Any:
    """A before-validator lower-casing the discriminator ``tag`` of a mapping."""

    def fix(value: Any) -> Any:
        if isinstance(value, dict) and isinstance(value.get(tag), str):
            return {**value, tag: _lower(value[tag])}
        return value

    return fix


def _named_material(value: Any) -> Any:
    if isinstance(value, str):
        if value not in MATERIALS:
            known = ", ".join(sorted(MATERIALS))
            raise ValueError(
                f"unknown material {value!r}; known: {known} "
                "(or give {name: ..., density: '... kg/m^3'})"
            )
        return MATERIALS[value]
    return value


def _drawable(value: Any) -> Any:
    """Check a drawn dimension against the layout database unit.

    A drawn dimension of at least :data:`~betvdesign.spec.process.MIN_DRAWN` (1 nm, the
    layout database unit): below it nothing can be drawn or fabricated.
    """
    if isinstance(value, pint.Quantity) and value < MIN_DRAWN:
        raise ValueError(
            f"{format_quantity(value)} is below {format_quantity(MIN_DRAWN)}, the smallest "
            "length a layout can draw: not a dimension a device can have"
        )
    return value


def drawable(*fields: str) -> Any:
    """Validator: the named length fields are drawable (see :func:`_drawable`)."""
    return field_validator(*fields)(_drawable)


class Slider(StrictModel):
    """The slider: parallel beams joined at both ends.

    Half the slider mass (the model's M) is (beam_count·ρ·L·w·t + extra_mass)/2
    (MODEL.md, "Physical quantities"): with two beams, one beam plus half the extra.
    """

    beam_length: Length
    """Length L of one slider beam."""
    beam_width: Length
    """Width w of one slider beam."""
    beam_thickness: Length
    """Thickness t of one slider beam (structural layer)."""
    beam_count: int = Field(default=2, ge=1, le=limits.MAX_BEAM_COUNT)
    """Number of parallel beams (2 for the usual BETV slider)."""
    extra_mass: NonNegativeMass = Field(default_factory=lambda: parse_quantity("0 ug"))
    """Mass of connectors/extras on top of the beams; '0 ug' by default."""
    travel_range: Length
    """Distance the slider can travel; used for the time-to-cross estimate."""
    layer: str | None = Field(default=None, max_length=limits.MAX_NAME_CHARS)
    """Structural layer of the device's process the slider is made in (the process's
    default structural layer when absent; only with ``process``)."""

    _drawn = drawable("beam_length", "beam_width", "beam_thickness", "travel_range")


class DiscGeometry(StrictModel):
    """A round impact head (a disc) [lengths]."""

    shape: Literal["disc"]
    diameter: Length
    thickness: Length

    _drawn = drawable("diameter", "thickness")


class BoxGeometry(StrictModel):
    """A rectangular impact head [lengths]."""

    shape: Literal["box"]
    length: Length
    width: Length
    thickness: Length

    _drawn = drawable("length", "width", "thickness")


HeadGeometry = Annotated[DiscGeometry | BoxGeometry, Field(discriminator="shape")]


class ImpactHead(StrictModel):
    """The impact head on the actuator's cold arm.

    The impact head on the actuator's cold arm: its mass m, given directly or by
    geometry (+ material, the device material by default).
    """

    mass: Mass | None = None
    """Head mass m, e.g. '0.036 ug' (or give geometry)."""
    geometry: HeadGeometry | None = None
    """Head shape and size (disc or box) when the mass is not given."""
    material: Material | None = None
    """Head material with geometry; the device material by default."""

    _material = field_validator("material", mode="before")(_named_material)
    _shape = field_validator("geometry", mode="before")(_lower_tag("shape"))

    @model_validator(mode="after")
    def _one_source(self) -> ImpactHead:
        if (self.mass is None) == (self.geometry is None):
            raise ValueError("give exactly one of 'mass' or 'geometry' for the impact head")
        if self.mass is not None and self.material is not None:
            raise at("material", "'material' only applies with 'geometry' (mass is given)")
        return self


class Contact(StrictModel):
    """Head/slider contact: impact angle, friction and restitution.

    Head/slider contact: impact angle θ in (0°, 90°), Coulomb friction μ [-] and the
    coefficient of restitution e [-] of normal impacts (optional, 0 by default). e lives
    here, beside μ, because like μ it is a property of the pair of surfaces that meet
    (head and slider), not of the actuator's springs and dampers (MODEL.md "Beyond the
    paper's idealisation").
    """

    impact_angle: ImpactAngle
    """Impact angle θ between the head's stroke and the slider normal, in (0°, 90°)."""
    friction: float = Field(
        description=f"Coulomb friction coefficient μ [-], {limits.MIN_FRICTION:g} <= μ <= {MU_MAX}"
    )
    restitution: damping.Restitution = damping.restitution_field()

    @field_validator("friction")
    @classmethod
    def _physical_mu(cls, v: float) -> float:
        if not (0.0 < v <= MU_MAX):
            raise ValueError(
                f"friction coefficient μ = {v:g} outside the physical range (0, {MU_MAX:g}] "
                "(polysilicon on polysilicon ≈ 0.4; μ = 0 gives κ = 0, outside the model)"
            )
        if v < limits.MIN_FRICTION:
            raise ValueError(
                f"friction coefficient μ = {v:g} is below {limits.MIN_FRICTION:g}, the smallest "
                "the model computes with (κ = μ·tanθ would underflow toward 0)"
            )
        return v


class LinearCalibration(StrictModel):
    """u = gain·V."""

    law: Literal["linear"]
    gain: LinearGain


class QuadraticCalibration(StrictModel):
    """u = gain·V² (Joule heating: deflection ∝ power ∝ V²)."""

    law: Literal["quadratic"]
    gain: QuadraticGain


class CalibrationPoint(StrictModel):
    """One measured point of the actuator: drive voltage and stroke amplitude."""

    voltage: NonNegativeVoltage
    amplitude: NonNegativeLength


class MeasuredCalibration(StrictModel):
    """Measured (V, u) points, linearly interpolated; no extrapolation."""

    law: Literal["measured"]
    points: list[CalibrationPoint] = Field(min_length=2, max_length=limits.MAX_CALIBRATION_POINTS)

    @model_validator(mode="after")
    def _increasing(self) -> MeasuredCalibration:
        volts = [p.voltage.to("V").magnitude for p in self.points]
        for i, (a, b) in enumerate(itertools.pairwise(volts)):
            if b <= a:
                raise at(
                    f"points[{i + 1}].voltage",
                    "calibration points must have strictly increasing voltages",
                )
        return self

    @property
    def voltage_range(self) -> tuple[pint.Quantity, pint.Quantity]:
        """The lowest and highest measured voltage [V] (no extrapolation beyond)."""
        return self.points[0].voltage, self.points[-1].voltage


Calibration = Annotated[
    LinearCalibration | QuadraticCalibration | MeasuredCalibration, Field(discriminator="law")
]


class ActuatorGeometry(StrictModel):
    """The drawn hot/cold-arm electrothermal actuator.

    The drawn hot/cold-arm electrothermal actuator (MODEL.md, "From the drawn actuator
    to the head's springs"). In its own frame x runs along the arms from the anchors
    (x = 0) to the tip, y across them toward the cold arm (the stroke direction):

    - hot arm: x in [0, length], centred on y = 0, ``hot_arm_width`` wide;
    - cold arm (the wide impact element): x in [flexure_length, length], centred on
      y = d = hot_arm_width/2 + gap + cold_arm_width/2;
    - flexure (narrow part of the cold arm at its anchor): x in [0, flexure_length],
      centred on y = d, ``flexure_width`` wide;
    - tip: a connector x in [length, length + tip_length] joining both arms;
    - head: the impact head's disc (or box) beyond the tip at the connector's
      mid-height, overlapping half of the connector;
    - anchors: squares of ``anchor_size`` at x < 0 at the roots of the hot arm and the
      flexure, reaching away from each other.

    Thickness, Young's modulus and Poisson's ratio are the structural layer's when the
    device names a process (``layer``: the process's default structural layer when
    absent); without a process give ``thickness`` and ``youngs_modulus``.
    """

    length: Length
    """Hot-arm length, from the anchor edge to the tip connector, e.g. '200 um'."""
    hot_arm_width: Length
    """Width of the (narrow, current-heated) hot arm."""
    cold_arm_width: Length
    """Width of the wide cold arm (the impact element)."""
    flexure_length: Length
    """Length of the narrow flexure between the cold arm and its anchor."""
    flexure_width: Length
    """Width of the flexure."""
    gap: Length
    """Edge-to-edge gap between the hot arm and the cold arm."""
    tip_length: Length = Field(default_factory=lambda: parse_quantity("10 um"))
    """Length of the connector that joins both arms at the tip; '10 um' by default."""
    anchor_size: Length = Field(default_factory=lambda: parse_quantity("20 um"))
    """Side of the square anchor pads; '20 um' by default."""
    layer: str | None = Field(default=None, max_length=limits.MAX_NAME_CHARS)
    """Structural layer of the device's process (its default one when absent)."""
    thickness: Length | None = None
    """Film thickness (the process layer's when the device names a process)."""
    youngs_modulus: Modulus | None = None
    """Young's modulus E (the process layer's when the device names a process)."""
    poisson_ratio: float | None = Field(default=None, ge=0.0, lt=0.5)
    """Poisson's ratio ν [-] for the finite-element check (the layer's, or 0.22)."""

    _drawn = drawable(
        "length",
        "hot_arm_width",
        "cold_arm_width",
        "flexure_length",
        "flexure_width",
        "gap",
        "tip_length",
        "anchor_size",
        "thickness",
    )

    @model_validator(mode="after")
    def _flexure_shorter(self) -> ActuatorGeometry:
        if self.flexure_length >= self.length:
            raise at(
                "flexure_length",
                f"must be shorter than the hot arm (length {format_quantity(self.length)}): "
                "the cold arm runs from the flexure to the tip",
            )
        return self


class Actuator(StrictModel):
    """An electrothermal actuator with its head's contact compliance and amplitude.

    Vertical stiffness from ``vertical_resonance`` f_v: k_v = m·(2π f_v)².
    Tangential compliance: exactly one of ``alpha`` (α = k_v/k_h, the published
    devices' phenomenological value), ``horizontal_stiffness`` k_h or
    ``horizontal_resonance`` f_h (α = (f_v/f_h)²).
    With a drawn ``geometry`` the head's springs k_v, k_h come from the actuator frame
    (:mod:`betvdesign.nondim.actuator`) where the file gives no resonance, stiffness or α:
    each given one is used (and compared with the geometry's), each missing one is the
    geometry's.
    Amplitude u: exactly one of ``amplitude`` or ``calibration`` (law of the drive voltage),
    or neither with a drawn ``geometry``: the stroke is then predicted from the drawing and
    the process's electrothermal data at the drive (:attr:`drawn_stroke`).
    Thermal roll-off (optional, MODEL.md "Thermal roll-off of the actuator"): at most one of
    ``thermal_cutoff`` f_c or ``thermal_time_constant`` τ_th (f_c = 1/(2π τ_th)), then
    ``calibration_frequency`` f_cal is required and u(f) = u·H(f)/H(f_cal) with
    H(f) = 1/sqrt(1 + (f/f_c)²) at the actuation frequency f. Absent: u does not depend on f.
    Head damping (optional, MODEL.md "Beyond the paper's idealisation"): dampers parallel to
    the head's springs, per direction (normal ζ_v, tangential ζ_h) at most one of
    ``damping_ratio_*`` ζ or ``quality_factor_*`` Q = 1/(2ζ); absent: undamped.
    """

    vertical_resonance: Frequency | None = None
    """Head vertical resonance f_v: sqrt(k_v/m) = 2π·f_v (optional with a geometry)."""
    geometry: ActuatorGeometry | None = None
    """The drawn actuator (optional): gives k_v and k_h where the file does not."""
    alpha: float | None = Field(default=None, gt=0.0)
    """α = k_v/k_h [-] given directly (phenomenological, e.g. from a published fit)."""
    horizontal_stiffness: Stiffness | None = None
    """Tangential contact stiffness k_h; α = k_v/k_h."""
    horizontal_resonance: Frequency | None = None
    """Tangential resonance f_h; α = (f_v/f_h)²."""
    amplitude: NonNegativeLength | None = None
    """Actuator deflection amplitude u at the drive voltage (or give a calibration)."""
    calibration: Calibration | None = None
    """u as a function of the drive voltage: linear, quadratic or measured points."""
    thermal_cutoff: Frequency | None = None
    """Thermal cut-off f_c of the stroke (first-order low-pass), e.g. '1.5 kHz'; optional."""
    thermal_time_constant: Duration | None = None
    """Thermal time constant τ_th, e.g. '0.2 ms' (f_c = 1/(2π τ_th)); or give thermal_cutoff."""
    calibration_frequency: Frequency | None = None
    """Actuation frequency (2 × drive frequency for AC) at which the amplitude or calibration
    was measured; required with a thermal cut-off."""
    damping_ratio_normal: damping.DampingRatio = damping.ratio_field("ζ_v", "normal")
    quality_factor_normal: damping.QualityFactor = damping.quality_field("Q_v", "normal")
    damping_ratio_tangential: damping.DampingRatio = damping.ratio_field("ζ_h", "tangential")
    quality_factor_tangential: damping.QualityFactor = damping.quality_field("Q_h", "tangential")

    _law = field_validator("calibration", mode="before")(_lower_tag("law"))

    @property
    def drawn_stroke(self) -> bool:
        """True when the stroke is predicted from the drawing (no amplitude, no calibration).

        The drawn actuator's electrothermal model then gives u at the drive
        (:mod:`betvdesign.model.electrothermal`; the process must carry the layer's
        electrothermal data).
        """
        return self.amplitude is None and self.calibration is None

    @model_validator(mode="after")
    def _exactly_one(self) -> Actuator:
        sources = (
            ("alpha", self.alpha),
            ("horizontal_stiffness", self.horizontal_stiffness),
            ("horizontal_resonance", self.horizontal_resonance),
        )
        given = [n for n, v in sources if v is not None]
        if self.geometry is None and len(given) != 1:
            raise ValueError(
                "give exactly one of 'alpha', 'horizontal_stiffness' or 'horizontal_resonance'"
                + (f" (got {', '.join(given)})" if given else " (or a drawn 'geometry')")
            )
        if len(given) > 1:
            raise ValueError(
                "give at most one of 'alpha', 'horizontal_stiffness' or "
                f"'horizontal_resonance' (got {', '.join(given)})"
            )
        if self.vertical_resonance is None and self.geometry is None:
            raise ValueError("give 'vertical_resonance' (or a drawn 'geometry')")
        if self.amplitude is not None and self.calibration is not None:
            raise ValueError("give exactly one of 'amplitude' or 'calibration', not both")
        if self.drawn_stroke:
            if self.geometry is None:
                raise ValueError(
                    "give exactly one of 'amplitude' or 'calibration' (or a drawn 'geometry' "
                    "whose process has electrothermal data: the stroke is then predicted)"
                )
            if self.thermal_cutoff is not None or self.thermal_time_constant is not None:
                which = (
                    "thermal_cutoff" if self.thermal_cutoff is not None else "thermal_time_constant"
                )
                raise at(
                    which,
                    "a drawn stroke (no 'amplitude' or 'calibration') derives its own thermal "
                    "roll-off from the drawing; give a measured amplitude or calibration with "
                    "a measured cut-off instead",
                )
        if self.amplitude is not None and self.amplitude.to("m").magnitude <= 0:
            raise at("amplitude", "amplitude must be > 0")
        if self.thermal_cutoff is not None and self.thermal_time_constant is not None:
            raise at("thermal_time_constant", "give 'thermal_cutoff' or this, not both")
        rolloff = self.thermal_cutoff is not None or self.thermal_time_constant is not None
        if rolloff and self.calibration_frequency is None:
            raise at(
                "thermal_cutoff" if self.thermal_cutoff is not None else "thermal_time_constant",
                "needs 'calibration_frequency' too (the actuation frequency at which the "
                "amplitude or calibration was measured)",
            )
        if rolloff and self.calibration_frequency is not None:
            tc, tau = self.thermal_cutoff, self.thermal_time_constant
            f_c = tc.to("Hz").magnitude if tc is not None else cutoff_hz(tau.to("s").magnitude)
            bad = calibration_problem(self.calibration_frequency.to("Hz").magnitude, f_c)
            if bad:
                raise at("calibration_frequency", bad)
        if not rolloff and self.calibration_frequency is not None:
            raise at(
                "calibration_frequency",
                "only applies with 'thermal_cutoff' or 'thermal_time_constant'",
            )
        for d, ratio, quality in (
            ("normal", self.damping_ratio_normal, self.quality_factor_normal),
            ("tangential", self.damping_ratio_tangential, self.quality_factor_tangential),
        ):
            if ratio is not None and quality is not None:
                raise at(f"quality_factor_{d}", f"give 'damping_ratio_{d}' or this, not both")
        return self


class Drive(StrictModel):
    """Electrical drive.

    waveform: ``ac`` (zero DC bias: heats on both half waves, actuation frequency
    = 2 × drive frequency, MODEL.md "AC doubling"), ``dc-biased`` or ``unipolar``
    (actuation frequency = drive frequency).
    """

    waveform: Literal["ac", "dc-biased", "unipolar"]
    """'ac' (zero DC bias: f_act = 2·frequency), 'dc-biased' or 'unipolar' (f_act = frequency)."""
    frequency: Frequency
    """Electrical drive frequency."""
    voltage: Voltage | None = None
    """Drive voltage amplitude; required with a calibration."""

    _waveform = field_validator("waveform", mode="before")(_lower)

    @property
    def doubled(self) -> bool:
        """True when the actuation frequency is twice the drive frequency."""
        return self.waveform == "ac"


class ActuatorSet(StrictModel):
    """One set of symmetric actuators driving the slider one way.

    impact_direction: the direction (+x/−x) the heads strike along the slider; a push
    set moves the slider that way, a pull set the other way.
    """

    name: str = Field(min_length=1, max_length=limits.MAX_NAME_CHARS)
    """Name of the set (unique in the device)."""
    intended_mode: Mode
    """The mode the design relies on: 'push' (slider moves with the impacts) or 'pull'."""
    impact_direction: Literal["+x", "-x"] = "+x"
    """Direction along the slider in which the heads strike."""
    head: ImpactHead
    contact: Contact
    actuator: Actuator
    drive: Drive

    _enums = field_validator("intended_mode", "impact_direction", mode="before")(_lower)

    @model_validator(mode="after")
    def _drive_matches_calibration(self) -> ActuatorSet:
        cal = self.actuator.calibration
        if cal is not None and self.drive.voltage is None:
            raise at("drive.voltage", "required when the actuator gives a calibration")
        if self.actuator.drawn_stroke and self.drive.voltage is None:
            raise at(
                "drive.voltage",
                "required when the stroke is predicted from the drawing (no amplitude or "
                "calibration)",
            )
        if isinstance(cal, MeasuredCalibration) and self.drive.voltage is not None:
            lo, hi = cal.voltage_range
            v = self.drive.voltage
            if not (lo <= v <= hi):
                raise at(
                    "drive.voltage",
                    f"drive.voltage {format_quantity(v)} lies outside the measured calibration "
                    f"range {format_quantity(lo)} to {format_quantity(hi)}; no extrapolation",
                )
        return self

    @property
    def travel_sign(self) -> int:
        """+1/−1: direction the slider moves if the set works in its intended mode."""
        s = 1 if self.impact_direction == "+x" else -1
        return s if self.intended_mode == "push" else -s


class PublishedFit(StrictModel):
    """Dimensionless parameters a publication fitted for this device (optional).

    ``betv check`` compares them with the values computed from the dimensional data
    and shows the difference; several published values can be listed for one parameter.
    """

    varpi: float | list[float] | None = None
    """Published ϖ (a number or a list of the values quoted)."""
    alpha: float | list[float] | None = None
    """Published α."""
    beta: float | list[float] | None = None
    """Published β."""
    kappa: float | list[float] | None = None
    """Published κ."""
    source: str | None = None
    """Citation of the publication."""

    def values(self, name: str) -> list[float]:
        """The published values of one parameter.

        Parameters
        ----------
        name : str
            ``"varpi"``, ``"alpha"``, ``"beta"`` or ``"kappa"``.

        Returns
        -------
        list of float
            The values quoted (empty when the fit gives none).
        """
        v = getattr(self, name)
        if v is None:
            return []
        return [float(x) for x in (v if isinstance(v, list) else [v])]


class DeviceSpec(StrictModel):
    """A BETV device: material, slider, one or more actuator sets."""

    name: str = Field(min_length=1, max_length=limits.MAX_NAME_CHARS)
    """Device name (shipped files use the file stem)."""
    description: str | None = Field(default=None, max_length=limits.MAX_STRING_CHARS)
    """Free text."""
    material: Material = POLYSILICON
    """Slider (and default head) material: a name ('polysilicon') or {name, density}."""
    slider: Slider
    """The slider beams and travel range."""
    actuator_sets: list[ActuatorSet] = Field(min_length=1, max_length=limits.MAX_ACTUATOR_SETS)
    """One set per direction of travel (two opposing sets for a bidirectional device)."""
    published_fit: PublishedFit | None = None
    """Optional: parameters a publication fitted; `betv check` compares, never uses them."""
    process: Process | None = None
    """Optional: the fabrication process (a shipped name such as 'polymumps', or the path
    of a process file relative to this file): its layers, materials and design rules
    (``betv check`` applies them; ``betv layout`` draws on its layers)."""

    _material = field_validator("material", mode="before")(_named_material)

    @model_validator(mode="after")
    def _layers(self) -> DeviceSpec:
        """Check that named layers are the process's structural ones.

        Layers named must be the process's structural ones; a geometry without a
        process gives its own thickness and Young's modulus.
        """
        p = self.process
        if p is None and self.slider.layer is not None:
            raise at("slider.layer", "only applies with 'process'")
        if p is not None and self.slider.layer is not None:
            try:
                p.structural(self.slider.layer)
            except ValueError as exc:
                raise at("slider.layer", str(exc)) from None
        for i, s in enumerate(self.actuator_sets):
            geo = s.actuator.geometry
            if geo is None:
                continue
            where = f"actuator_sets[{i}].actuator.geometry"
            if p is None:
                drawn = (("thickness", geo.thickness), ("youngs_modulus", geo.youngs_modulus))
                missing = [f for f, v in drawn if v is None]
                if geo.layer is not None:
                    raise at(f"{where}.layer", "only applies with 'process'")
                if missing:
                    raise at(
                        where,
                        f"give {' and '.join(missing)} (or name the device's 'process', whose "
                        "structural layer gives them)",
                    )
            elif geo.layer is not None:
                try:
                    p.structural(geo.layer)
                except ValueError as exc:
                    raise at(f"{where}.layer", str(exc)) from None
        return self

    @model_validator(mode="after")
    def _unique_names(self) -> DeviceSpec:
        names = [s.name for s in self.actuator_sets]
        for i, n in enumerate(names):
            if n in names[:i]:
                raise at(
                    f"actuator_sets[{i}].name",
                    f"actuator set names must be unique; {n!r} is also set {names.index(n)}",
                )
        return self

    def replace(self, path: str, value: Any, *more: tuple[str, Any]) -> DeviceSpec:
        """What-if: a copy with a field changed, validated like a device file.

        Example: ``spec.replace("slider.beam_width", "6 um")``; see
        :func:`betvdesign.spec.whatif.replace`.

        Parameters
        ----------
        path : str
            Dotted field path, as in the device file (:mod:`betvdesign.spec.paths`).
        value : str, float, int, dict, pint.Quantity or None
            The new value as a device file gives it (None removes the field).
        *more : tuple of (str, value)
            Further edits, applied before the one validation.

        Returns
        -------
        DeviceSpec
            The edited, validated device (``self`` is unchanged).

        Raises
        ------
        SpecError
            An unknown path or a value the device file would reject (the loader's messages).
        """
        from betvdesign.spec.whatif import replace

        return replace(self, path, value, *more)


def amplitude_at(
    actuator_set: ActuatorSet, voltage: pint.Quantity | str | None = None
) -> pint.Quantity:
    """Actuator amplitude u at a drive voltage (MODEL.md: u grows with V).

    u = gain·V (linear), gain·V² (quadratic: Joule heating) or the measured points
    interpolated linearly, never extrapolated; the amplitude given directly at the set's
    own voltage.

    Parameters
    ----------
    actuator_set : ActuatorSet
        The set (its actuator's amplitude or calibration, its drive voltage).
    voltage : pint.Quantity, str or None
        Drive voltage [V] (an array gives an array of amplitudes, for sweeps); None: the
        set's drive voltage.

    Returns
    -------
    pint.Quantity
        u [um].

    Raises
    ------
    ParameterError
        The amplitude cannot be given at that voltage (given directly, or outside a
        measured range), or the voltage is not a finite quantity >= 0 V.

    References
    ----------
    MODEL.md, "Device-to-parameter relations"; Shin et al., J. Appl. Phys. 96, 7603 (2004),
    doi:10.1063/1.1809773 (u ≈ 0.11 µm at 8 V, roughly proportional to V).
    """
    act = actuator_set.actuator
    if voltage is None:
        if act.amplitude is not None:
            return act.amplitude.to("um")
        voltage = actuator_set.drive.voltage
    if isinstance(voltage, str):
        voltage = parse_quantity(voltage)
    try:
        v = voltage.to("V")
    except (pint.DimensionalityError, AttributeError):
        raise ParameterError(f"voltage must be a quantity in volts, got {voltage!r}") from None
    cal = act.calibration
    if cal is None:
        raise ParameterError(
            f"actuator set {actuator_set.name!r} gives its amplitude directly; "
            "give a calibration (linear, quadratic or measured) to evaluate other voltages"
        )
    vm = np.asarray(v.magnitude, dtype=float)
    if np.any(vm < 0) or not np.all(np.isfinite(vm)):
        raise ParameterError(f"voltage must be finite and >= 0 V, got {voltage}")
    if isinstance(cal, LinearCalibration):
        return (cal.gain * v).to("um")
    if isinstance(cal, QuadraticCalibration):
        return (cal.gain * v**2).to("um")
    xs = np.array([p.voltage.to("V").magnitude for p in cal.points], dtype=float)
    ys = np.array([p.amplitude.to("um").magnitude for p in cal.points], dtype=float)
    if np.any(vm < xs[0]) or np.any(vm > xs[-1]):
        raise ParameterError(
            f"voltage {voltage} outside the measured calibration range "
            f"{xs[0]:g} V to {xs[-1]:g} V of set {actuator_set.name!r}; no extrapolation"
        )
    out = np.interp(vm, xs, ys)
    return ureg.Quantity(float(out) if out.ndim == 0 else out, "um")
