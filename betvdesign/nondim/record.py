"""What a derivation produces (plain data).

What a derivation produces (plain data): the record of every step, the scales, the
comparison with a published fit, the derivation of one actuator set and of a device;
and the :class:`Recorder` that builds the record.

Computed by :mod:`betvdesign.nondim.device` (the only module that strips units); read by
rules, studies, reports and the CLI.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pint

from betvdesign.errors import ParameterError
from betvdesign.model import rolloff
from betvdesign.model.params import ModelParams
from betvdesign.spec.models import ActuatorSet, DeviceSpec, Mode
from betvdesign.spec.units import format_quantity, ureg

#: ASCII keys for JSON output of the symbols that are not ASCII already.
_ASCII = {
    "ρ": "rho",
    "ρ_head": "rho_head",
    "α": "alpha",
    "ω": "omega",
    "θ": "theta",
    "μ": "mu",
    "ϖ": "varpi",
    "β": "beta",
    "κ": "kappa",
    "λ": "lambda",
    "t_s": "time_scale",
    "ℓ": "length_scale",
    "τ_th": "tau_th",
    "H(f_act)": "H_act",
    "H(f_cal)": "H_cal",
    "ζ_v": "zeta_v",
    "ζ_h": "zeta_h",
    "δ": "delta",
}
#: Keys of the dimensional values :meth:`SetDerivation.derived` reports.
DERIVED_KEYS = (
    "M",
    "m",
    "k_v",
    "k_h",
    "f_act",
    "omega",
    "u_cal",
    "f_c",
    "f_cal",
    "u",
    "time_scale",
    "length_scale",
)


@dataclass(frozen=True)
class DerivationStep:
    """One number of the derivation: an input from the spec or a computed value.

    Attributes
    ----------
    symbol : str
        E.g. ``"k_v"``.
    description : str
        What it is, in words.
    formula : str
        ``"m·(2π·f_v)²"``, or ``"spec: actuator.vertical_resonance"`` for inputs.
    value : pint.Quantity
        In the engineering unit it is best read in.
    inputs : tuple of str
        Symbols the formula uses.
    key : str
        ASCII key for JSON output (the symbol, spelled out where it is not ASCII).
    """

    symbol: str
    description: str
    formula: str
    value: pint.Quantity
    inputs: tuple[str, ...] = ()
    key: str = ""

    def __post_init__(self) -> None:
        """Default the ASCII key from the symbol."""
        if not self.key:
            object.__setattr__(self, "key", _ASCII.get(self.symbol, self.symbol))

    @property
    def value_str(self) -> str:
        """The value as a short string with units, e.g. ``"0.0184 ug"`` (4 digits)."""
        return format_quantity(self.value, ".4g")

    @property
    def magnitude(self) -> float:
        """The value's magnitude in its recorded unit."""
        return float(self.value.magnitude)


@dataclass(frozen=True)
class Scales:
    """Scales of the dimensionless model, float SI (MODEL.md, "Dimensionless model").

    Attributes
    ----------
    length_m : float
        ℓ = u·cosθ [m], the scale of ζ and s.
    time_s : float
        sqrt(m/k_v) [s] (τ = t/time_s).
    f_act_hz : float
        Actuation frequency [Hz].
    omega_rad_s : float
        2π·f_act [rad/s].
    u_m : float
        Amplitude at f_act [m] (after the thermal roll-off).
    theta_rad : float
        Impact angle [rad].
    cutoff_hz : float
        Thermal cut-off f_c [Hz] (inf: no roll-off).
    calibration_hz : float or None
        Actuation frequency f_cal of the amplitude calibration [Hz] (None without a
        cut-off).
    """

    length_m: float
    time_s: float
    f_act_hz: float
    omega_rad_s: float
    u_m: float
    theta_rad: float
    cutoff_hz: float = math.inf
    calibration_hz: float | None = None
    #: A stroke predicted from the drawing: its thermal modes ((τ_i [s], a_i [-]), the
    #: roll-off u(f) ∝ gain(f) of :func:`betvdesign.model.electrothermal.modal_gain`) and
    #: the drive's waveform; () for a stroke the file gives.
    thermal_modes: tuple[tuple[float, float], ...] = ()
    waveform: str = "ac"

    @property
    def has_rolloff(self) -> bool:
        """True when the device gives a thermal cut-off."""
        return math.isfinite(self.cutoff_hz)

    def amplitude_m(self, f_act_hz: Any) -> Any:
        """The stroke at another actuation frequency: u·H(f)/H(f_act).

        Parameters
        ----------
        f_act_hz : float or numpy.ndarray
            Actuation frequency f [Hz].

        Returns
        -------
        float or numpy.ndarray
            Stroke [m]; u itself without a cut-off (MODEL.md, "Thermal roll-off of the
            actuator"); for a stroke predicted from the drawing, its thermal modes' gain
            (the heating frequency is f_act for every waveform).
        """
        if self.thermal_modes:  # the drawing's own roll-off (heating at f_act)
            from betvdesign.model.electrothermal import modal_gain

            g = modal_gain(self.thermal_modes, f_act_hz, self.waveform)
            return self.u_m * g / modal_gain(self.thermal_modes, self.f_act_hz, self.waveform)
        return self.u_m * rolloff.ratio(f_act_hz, self.f_act_hz, self.cutoff_hz)

    @property
    def rolloff_factor(self) -> float:
        """The roll-off factor H(f_act)/H(f_cal) [-].

        H(f_act)/H(f_cal) [-]: the stroke at f_act relative to the calibrated one
        (1 without a cut-off).
        """
        if self.calibration_hz is None:
            return 1.0
        return float(rolloff.ratio(self.f_act_hz, self.calibration_hz, self.cutoff_hz))

    def speed_m_s(self, delta_s: float) -> float:
        """Mean slider speed of a dimensionless per-cycle increment: Δs·u·cosθ·f_act.

        Parameters
        ----------
        delta_s : float
            Δs per cycle [-].

        Returns
        -------
        float
            Speed [m/s].

        References
        ----------
        MODEL.md, "Dimensionless model" (displacement per cycle); Shin et al., J. Appl.
        Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
        """
        return delta_s * self.length_m * self.f_act_hz


@dataclass(frozen=True)
class FitComparison:
    """A computed parameter against the value(s) a publication fitted."""

    name: str
    computed: float
    published: tuple[float, ...]

    @property
    def rel_diff(self) -> float:
        """Smallest relative difference |computed − published|/published [-]."""
        return min(abs(self.computed - p) / abs(p) for p in self.published)

    def matches(self, rtol: float = 0.1) -> bool:
        """Whether the computed value lies within ``rtol`` [-] (relative) of a published one.

        Parameters
        ----------
        rtol : float
            Relative tolerance [-].

        Returns
        -------
        bool
            True when :attr:`rel_diff` <= ``rtol``.
        """
        return self.rel_diff <= rtol


@dataclass(frozen=True)
class HeadSprings:
    """The head's springs from the drawn actuator, float SI.

    The head's springs from the drawn actuator (:mod:`betvdesign.nondim.actuator`),
    float SI: k_nn, k_tt, k_nt [N/m] the frame's stiffness in the slider's frame; k_v, k_h
    [N/m] the model's springs (each direction with the other free, the slider's compliance
    in series), m_v, m_h [kg] their Rayleigh effective masses, f_v, f_h [Hz] the drawn
    resonances, f_1, f_oop [Hz] the actuator's first in-plane and out-of-plane modes; the
    coupling ρ [-]; the
    arms' first-mode mass m_arm [kg] against the head's m [kg]; ``used``: for "k_v" and
    "alpha", "geometry" when the drawn actuator gave it, "file" when the device file's
    value was used (then ``file_f_v_hz``/``file_alpha`` hold it for comparison).
    """

    k_nn: float
    k_tt: float
    k_nt: float
    rho: float
    m_arm_kg: float
    m_head_kg: float
    k_v: float
    k_h: float
    m_v_kg: float
    m_h_kg: float
    f_v_hz: float
    f_h_hz: float
    f_1_hz: float
    f_oop_hz: float
    used: dict[str, str]
    file_f_v_hz: float | None = None
    file_alpha: float | None = None

    @property
    def alpha(self) -> float:
        """The geometry's α = (f_v/f_h)² [-]."""
        return (self.f_v_hz / self.f_h_hz) ** 2


@dataclass(frozen=True)
class DrawnStroke:
    """The drawn actuator at the drive, float SI (``betv check --json``: ``derived.drawn``).

    Attributes
    ----------
    status : str
        'ok', 'melts' (peak temperature above the melting point) or 'not_converged'.
    message : str
        Why, in words ('' when ok).
    voltage_v : float
        Drive voltage amplitude V [V].
    stroke_m : float
        The head's half swing u at the drive [m] (the model's amplitude).
    u_static_m : float
        Steady stroke at a DC voltage V [m].
    t_max_k : float
        Peak temperature at a DC voltage V [K] (the AC peak's, at its crest).
    t_max_where : str
        The segment where it lies.
    melting_k : float
        The layer's melting point [K] (process file).
    power_w, current_a, resistance_ohm : float
        At a DC voltage V: electrical power [W], current [A], resistance [Ω].
    f_thermal_hz : float
        The first thermal mode's corner 1/(2π τ_th) [Hz].
    f_cutoff_hz : float
        Heating frequency where |H| = 1/√2 (all kept modes) [Hz].
    f_heat_hz : float
        The drive's heating frequency [Hz].
    gain : float
        |H(f_heat)| [-].
    modes : tuple of (float, float)
        The thermal modes (τ_i [s], a_i [-]) of the roll-off.
    deformation_k : float or None
        The layer's onset of plastic deformation [K] (process file), None when the
        process gives none.
    """

    status: str
    message: str
    voltage_v: float
    stroke_m: float
    u_static_m: float
    t_max_k: float
    t_max_where: str
    melting_k: float
    power_w: float
    current_a: float
    resistance_ohm: float
    f_thermal_hz: float
    f_cutoff_hz: float
    f_heat_hz: float
    gain: float
    modes: tuple[tuple[float, float], ...] = ()
    deformation_k: float | None = None


@dataclass(frozen=True)
class SetDerivation:
    """Model parameters and scales of one actuator set, with their derivation."""

    name: str
    intended_mode: Mode
    params: ModelParams
    lam: float
    scales: Scales
    record: list[DerivationStep]
    actuator_set: ActuatorSet
    travel_range_m: float
    published: list[FitComparison] = field(default_factory=list)
    springs: HeadSprings | None = None
    #: The stroke predicted from the drawing (None when the file gives u or a calibration).
    stroke: DrawnStroke | None = None

    def step(self, symbol: str) -> DerivationStep:
        """The record entry of a symbol.

        Parameters
        ----------
        symbol : str
            E.g. ``"k_v"``.

        Returns
        -------
        DerivationStep
            The first entry with that symbol.

        Raises
        ------
        KeyError
            The record has no such symbol.
        """
        for s in self.record:
            if s.symbol == symbol:
                return s
        raise KeyError(symbol)

    @property
    def lambda_mode(self) -> Mode:
        """The mode the λ criterion predicts (λ < 1 push)."""
        return self.params.lambda_mode

    @property
    def impact_sign(self) -> int:
        """+1 when the heads strike toward +x, −1 toward −x."""
        return 1 if self.actuator_set.impact_direction == "+x" else -1

    def derived(self) -> dict[str, str]:
        """Key dimensional values as strings with units.

        Returns
        -------
        dict of str to str
            ``{"M": "0.003961 ug", ...}``, keyed by :data:`DERIVED_KEYS` (those the
            record holds).
        """
        by_key = {s.key: s for s in self.record}
        return {k: by_key[k].value_str for k in DERIVED_KEYS if k in by_key}

    def drawn(self) -> dict[str, Any]:
        """The drawn actuator's mechanics for ``betv check --json``.

        The drawn actuator's mechanics for ``betv check --json`` (``derived.drawn``),
        float SI, each None without a drawing: f_v_hz, f_h_hz (the drawn resonances),
        k_v_n_m, k_h_n_m (the head's springs, each direction with the other free, slider
        in series), m_eff_kg (the normal spring's Rayleigh effective mass), coupling (ρ),
        f_1_hz and f_oop_hz (the actuator's first in-plane and out-of-plane modes); and
        where the stroke is predicted from the drawing (:class:`DrawnStroke`): stroke_m
        (the half swing at the drive), u_static_m, t_max_k, power_w, current_a,
        resistance_ohm (at a DC voltage V), f_thermal_hz (the stroke's thermal cut-off,
        |H| = 1/√2), f_heat_hz and stroke_status.
        """
        sp = self.springs
        keys = ("f_v_hz", "f_h_hz", "k_v_n_m", "k_h_n_m", "m_eff_kg", "coupling", "f_1_hz",
                "f_oop_hz")  # fmt: skip
        out: dict[str, Any] = dict.fromkeys(keys)
        if sp is not None:
            vals = (sp.f_v_hz, sp.f_h_hz, sp.k_v, sp.k_h, sp.m_v_kg, sp.rho, sp.f_1_hz,
                    sp.f_oop_hz)  # fmt: skip
            out = {k: float(v) for k, v in zip(keys, vals, strict=True)}
        st = self.stroke
        heat = ("stroke_m", "u_static_m", "t_max_k", "power_w", "current_a", "resistance_ohm",
                "f_thermal_hz", "f_heat_hz")  # fmt: skip
        out.update(dict.fromkeys(heat))
        out["stroke_status"] = None
        if st is not None:
            out.update({k: float(getattr(st, k)) for k in heat})
            out["f_thermal_hz"] = float(st.f_cutoff_hz)  # the stroke's cut-off, not τ₁'s
            out["stroke_status"] = st.status
        return out


@dataclass(frozen=True)
class DeviceDerivation:
    """Derivations of every actuator set of a device."""

    name: str
    spec: DeviceSpec
    sets: list[SetDerivation]


@dataclass(frozen=True)
class SampleDerivation:
    """The model parameters and scales of many samples at once.

    :func:`derive_samples`: the model parameters and scales of many samples at once
    (arrays of equal length, float SI; zeta_v, zeta_h, restitution 0 where the spec gives
    none).
    """

    varpi: np.ndarray
    alpha: np.ndarray
    beta: np.ndarray
    kappa: np.ndarray
    length_m: np.ndarray
    f_act_hz: np.ndarray
    zeta_v: np.ndarray
    zeta_h: np.ndarray
    restitution: np.ndarray


@functools.lru_cache(maxsize=64)
def cached_unit(text: str) -> pint.Unit:
    """A parsed unit of :data:`ureg` (parsing unit text dominates ``derive`` otherwise).

    Parameters
    ----------
    text : str
        A unit expression (``"um"``, ``"N/m"``, ``""`` for dimensionless).

    Returns
    -------
    pint.Unit
        The unit, parsed once per text.
    """
    return ureg.Unit(text)


def mag(q: pint.Quantity, unit: str) -> Any:
    """Magnitude of ``q`` in ``unit``: where a derivation step strips a unit.

    Parameters
    ----------
    q : pint.Quantity
        A recorded value (a float or an array of samples).
    unit : str
        The unit to express it in.

    Returns
    -------
    float or numpy.ndarray
        A float, or an array of samples.
    """
    m = q.to(cached_unit(unit)).magnitude
    return float(m) if np.ndim(m) == 0 else np.asarray(m, dtype=float)


class Recorder:
    """Build the record of a derivation.

    Builds the record of a derivation: every step checked (finite, > 0 unless an
    input or λ) and converted to the unit it is best read in.
    """

    def __init__(self) -> None:
        self.steps: list[DerivationStep] = []

    def add(
        self,
        symbol: str,
        description: str,
        formula: str,
        value: Any,
        inputs: tuple[str, ...] = (),
        unit: str | None = None,
        *,
        signed: bool = False,
    ) -> pint.Quantity:
        """Record a computed value (or, with a ``spec:`` formula, an input).

        Parameters
        ----------
        symbol : str
            Its symbol (``"k_v"``).
        description : str
            What it is, in words.
        formula : str
            How it is computed (``"m·(2π·f_v)²"``), or ``"spec: <field path>"``.
        value : pint.Quantity or float or numpy.ndarray
            The value; a plain number is dimensionless.
        inputs : tuple of str
            Symbols the formula uses.
        unit : str or None
            The unit it is best read in (None: as given).
        signed : bool
            The value may take either sign (e.g. a coupling stiffness): only finiteness
            is required.

        Returns
        -------
        pint.Quantity
            The value in ``unit``.

        Raises
        ------
        ParameterError
            A computed value (other than λ) that is not finite and > 0 (finite if
            ``signed``).
        """
        if not isinstance(value, pint.Quantity):
            value = ureg.Quantity(value, cached_unit(""))
        if unit is not None:
            value = value.to(cached_unit(unit))
        if not formula.startswith("spec:") and symbol != "λ":
            got = np.asarray(value.magnitude, dtype=float)
            if not np.all(np.isfinite(got) & ((got > 0.0) | signed)):
                shown = float(got) if got.ndim == 0 else "an invalid sample"
                raise ParameterError(
                    f"{symbol} = {formula} = {shown!r}: must be finite and > 0 "
                    "(check the inputs for extreme or zero values)"
                )
        self.steps.append(DerivationStep(symbol, description, formula, value, inputs))
        return value

    def spec(self, symbol: str, description: str, path: str, value: Any) -> pint.Quantity:
        """Record an input taken from the device spec.

        Parameters
        ----------
        symbol : str
            Its symbol (``"f_v"``).
        description : str
            What it is, in words.
        path : str
            The spec field it comes from (``"actuator.vertical_resonance"``).
        value : pint.Quantity or float or numpy.ndarray
            The value (a plain number is dimensionless).

        Returns
        -------
        pint.Quantity
            The value, as given.
        """
        return self.add(symbol, description, f"spec: {path}", value)

    def recorded(self, symbol: str) -> pint.Quantity | None:
        """The value recorded for ``symbol`` so far (the first), or None.

        Parameters
        ----------
        symbol : str
            Its symbol (``"θ"``).

        Returns
        -------
        pint.Quantity or None
            The value as recorded; None if no step has that symbol yet.
        """
        return next((st.value for st in self.steps if st.symbol == symbol), None)
