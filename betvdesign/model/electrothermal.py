"""The hot/cold-arm actuator's steady electrothermal stroke, power, temperature and roll-off.

MODEL.md, "From the drawn actuator to the head's springs" (last item) and issue 31: the
stroke u(V, f) from Joule heating of the drawn actuator (:class:`FrameGeometry`, the
geometry the springs use), unit-free SI floats.

**Electrical and thermal path.** The current runs from the hot arm's anchor along the hot
arm (length L, width w_h), across the tip connector (from the hot arm's axis to the cold
arm's, length d = w_h/2 + g + w_c/2, cross-section l_tip·t), back along the cold arm
(L − L_f, w_c) and the flexure (L_f, w_f) to the flexure's anchor: one chain of
segments, each a 1-D fin (Lin & Chiao 1996; Huang & Lee 1999; Mankame &
Ananthasuresh 2001) with temperature rise θ = T − T_0 above the substrate T_0:

    k·A·θ'' − G'·θ + (I²·ρ_0/A)·(1 + ξ·θ) = 0,

k the film's thermal conductivity, A = t·w the cross-section, ρ(T) = ρ_0·(1 + ξ·θ) the
resistivity with its linear temperature coefficient ξ, and G' the conductance to the
substrate per unit length through the air gap t_v and the nitride t_n in series, with the
shape factor S of Lin & Chiao (Sens. Actuators A 55 (1996) 35–41), S·w = w + t +
2·t_v for a line of width w and thickness t:

    G' = S·w·g_s,    S = (t/w)·(2·t_v/t + 1) + 1,    g_s = 1/(t_v/k_air + t_n/k_n)  [W/(m²K)]

(Huang & Lee, J. Micromech. Microeng. 9 (1999) 64–70, with the nitride in
series). The same loss is, per unit area, g_s under the film plus g_s·(t/2 + t_v) per unit
length of each free edge: the form the FE check (:mod:`betvdesign.model.electrothermal_fe`)
uses on the drawn outline. The tip connector (whose edges are mostly joints) loses heat
through its area only; the head (outside the current path) is a lumped node at the tip's
middle with its area's and outline's conductance and its heat capacity (its Biot number
across it is small: it stays nearly isothermal). The anchors are at T_0.

For a given current I the equation is linear in θ: on each segment
θ'' − m²·θ = −s_0 with m² = (G' − I²ρ_0ξ/A)/(kA), s_0 = I²ρ_0/(A·kA), whose exact
solution through the end temperatures θ_1, θ_2 is

    θ(x) = θ_1·sinh(m(l − x))/sinh(ml) + θ_2·sinh(mx)/sinh(ml)
           + s_0·2·sinh(m(l − x)/2)·sinh(mx/2)/(m²·cosh(ml/2))

(cosh → cos where m² < 0: a segment heating faster than it loses heat). Heat balance at
the four joints is a 4×4 symmetric system (the segments' exact "dynamic stiffness"); the
operator is positive definite below the thermal runaway current, which is detected
exactly (every segment with |m|·l < π where m² < 0, and the joints' matrix positive
definite). The drive is a voltage V across the anchors: the current solves
V = I·R(I), R(I) = Σ ρ_0/A·(l + ξ·∫θ ds), monotone in I for ξ ≥ 0 up to runaway; it is
found by Brent's method (bisection first where the bracket reaches past the runaway), with a
bounded number of steps (:data:`MAX_ITERATIONS`); its failure is reported.

**Expansion.** The free thermal strain at temperature T is
ε_th(T) = ∫_{T_0}^{T} α(T') dT' with α(T) of Okada & Tokumaru (J. Appl. Phys. 56 (1984)
314–320) for silicon, 120–1500 K,

    α(T) = (3.725·(1 − exp(−5.88·10⁻³·(T − 124))) + 5.548·10⁻⁴·T)·10⁻⁶  [1/K],

integrated in closed form, or a constant α. Each arm's free elongation ∫ε_th dx (Gauss–
Legendre on the exact profile) loads the frame of :mod:`betvdesign.model.frame`
(:func:`betvdesign.model.frame.thermal_displacement`): the head's stroke u_y.

**Dynamics.** The same chain discretised by linear finite elements (the heat capacity
ρ·c·A per unit length lumped at the nodes, the head's at its node; conduction and
substrate loss consistent) gives C·θ' + K·θ = q; its generalized eigenproblem
K·φ = λ·C·φ gives the thermal modes τ_i = 1/λ_i, the first one the thermal time
constant τ_1 (of the whole chain: often the wide cold arm's and the head's, which carry
little of the stroke; the stroke's own measures are its rise time
:attr:`ElectrothermalResult.t_rise` and its −3 dB heating frequency
:attr:`ElectrothermalResult.f_cutoff`). The small-signal stroke response to a heating at
frequency f is H(f) = Σ a_i/(1 + j·2πf·τ_i), a_i the modes' shares of the static stroke (their
participation in wᵀK⁻¹q, w the stroke per node temperature, Σ a_i = 1 over all modes);
the first :data:`MODES_KEPT` modes are kept and the rest lumped into one with the next
mode's time constant (the largest of theirs). The
electrical feedback of ξ on the transient is left out (the passive thermal operator).
At zero current the source is a uniform heating per unit volume.

**Stroke at a drive.** :func:`stroke_amplitude`: the half swing of the head's oscillation
(the model's u: cart displacement u·sin ωt). A zero-DC sinusoid V·sin(2πft) heats as
P_V·(1 − cos 4πft)/2, P_V the power at V: the stroke swings about its mean with
amplitude (u_static(V)/2)·|H(2f)|. Unipolar square pulses 0/V at 50 % duty heat at f:
the half swing of a first-order response to a square wave is
(u_static(V)/2)·tanh(1/(4fτ)) (its modal sum here). A DC-biased drive is taken as a
sinusoid swinging 0..V at f: (u_static(V)/2)·|H(f)|.

**Limits.** Constant k, c and air conductivity (their rise or fall with temperature is not
modelled); no radiation or convection; the tip connector and the head are rigid in the
frame; transverse expansion of the arms and the tip is left out (the FE check has them);
small displacements (linear elasticity); V is across the actuator's anchors (no pad or
wiring resistance). The peak temperature is the DC one at V: for an AC drive of
amplitude V it is the slow-drive peak, an upper bound (well above the cut-off the
temperature settles near its mean, that of V/√2).
Non-physical results are reported by :attr:`ElectrothermalResult.status`, never NaN:
``melts`` above the melting point, ``not_converged`` if the search for the current fails.
"""

from __future__ import annotations

import cmath
import functools
import math
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from betvdesign.model.frame import FrameGeometry, thermal_displacement

__all__ = [
    "MAX_ITERATIONS",
    "MODES_KEPT",
    "OKADA_TOKUMARU",
    "ElectrothermalResult",
    "Segment",
    "ThermalMaterial",
    "electrothermal",
    "expansion_coefficient",
    "fin_profile",
    "head_node",
    "segments",
    "stroke_amplitude",
    "temperature_profile",
    "thermal_gain",
    "thermal_strain",
]

#: The name of Okada & Tokumaru's α(T) for silicon (J. Appl. Phys. 56 (1984) 314).
OKADA_TOKUMARU = "okada-tokumaru-1984"
#: Steps of the search for the current at most (bisection would reach round-off from any
#: start in 200; Brent's method takes about 10).
MAX_ITERATIONS = 200
#: Thermal modes kept in H(f) (the rest lumped into one).
MODES_KEPT = 8
#: Linear elements per arm segment in the modal model (tip halves: a quarter of it).
ELEMENTS = 96
#: Relative residual |I·R(I) − V|/V accepted as converged.
VOLTAGE_RTOL = 1e-9


@dataclass(frozen=True)
class ThermalMaterial:
    """The film's and the gap's electrical and thermal data, SI.

    Attributes
    ----------
    resistivity : float
        ρ_0 at the substrate temperature [Ω·m] (sheet resistance × thickness).
    tcr : float
        ξ, linear temperature coefficient of the resistivity [1/K].
    conductivity : float
        k, the film's thermal conductivity [W/(m·K)].
    density : float
        ρ_m [kg/m³].
    heat_capacity : float
        c, specific heat [J/(kg·K)].
    expansion : str or float
        :data:`OKADA_TOKUMARU` for α(T) of silicon, or a constant α [1/K].
    air_conductivity : float
        k_air [W/(m·K)].
    air_gap : float
        t_v, the film's height above the substrate's top layer [m].
    nitride_thickness : float
        t_n, insulating layer on the substrate [m] (0 for none).
    nitride_conductivity : float
        k_n [W/(m·K)].
    substrate_temperature : float
        T_0 [K].
    melting_temperature : float
        T_melt [K]: a peak above it is reported as ``melts``.
    deformation_temperature : float or None
        The onset of plastic deformation (creep, back-bending) [K], below T_melt, or None
        when not known. The model does not use it: it is the limit of the check's
        ``thermal.peak-temperature`` (:mod:`betvdesign.checks.thermal_rules`).
    """

    resistivity: float
    tcr: float
    conductivity: float
    density: float
    heat_capacity: float
    expansion: str | float
    air_conductivity: float
    air_gap: float
    nitride_thickness: float
    nitride_conductivity: float
    substrate_temperature: float = 300.0
    melting_temperature: float = 1687.0
    deformation_temperature: float | None = None

    @property
    def substrate_conductance(self) -> float:
        """g_s = 1/(t_v/k_air + t_n/k_n) [W/(m²·K)]: per unit area, air gap and nitride
        in series."""
        r = self.air_gap / self.air_conductivity
        if self.nitride_thickness > 0:
            r += self.nitride_thickness / self.nitride_conductivity
        return 1.0 / r


def expansion_coefficient(temperature: Any, model: str | float = OKADA_TOKUMARU) -> Any:
    """α(T) [1/K] at ``temperature`` [K]: Okada & Tokumaru's (module doc) or a constant.

    Parameters
    ----------
    temperature : float or array
        T [K].
    model : str or float
        :data:`OKADA_TOKUMARU` or a constant α [1/K].

    Returns
    -------
    float or array
        α [1/K].
    """
    T = np.asarray(temperature, dtype=float)
    if not isinstance(model, str):
        return np.full_like(T, float(model))
    _check_model(model)
    return (3.725 * (1 - np.exp(-5.88e-3 * (T - 124.0))) + 5.548e-4 * T) * 1e-6


def _check_model(model: str) -> None:
    if model != OKADA_TOKUMARU:
        raise ValueError(f"unknown expansion model {model!r} (known: {OKADA_TOKUMARU!r})")


def _eps_abs(T: Any) -> Any:
    """An antiderivative of Okada & Tokumaru's α(T) [-]."""
    c = 5.88e-3
    return (3.725 * (T + np.exp(-c * (T - 124.0)) / c) + 5.548e-4 * T * T / 2) * 1e-6


def thermal_strain(temperature: Any, reference: float, model: str | float = OKADA_TOKUMARU) -> Any:
    """ε_th = ∫_{T_ref}^{T} α(T') dT' [-] (closed form for Okada & Tokumaru).

    Parameters
    ----------
    temperature : float or array
        T [K].
    reference : float
        T_ref [K], where the film is strain-free.
    model : str or float
        :data:`OKADA_TOKUMARU` or a constant α [1/K].

    Returns
    -------
    float or array
        The free thermal strain [-].
    """
    T = np.asarray(temperature, dtype=float)
    if not isinstance(model, str):
        return float(model) * (T - reference)
    _check_model(model)
    return _eps_abs(T) - _eps_abs(reference)


# --- the exact fin functions, even in z = m·l (complex for m² < 0) ---------------------
def _shc(y: Any) -> Any:
    """sinh(y)/y (complex), by its series near 0."""
    y = np.asarray(y, dtype=complex)
    small = np.abs(y) < 1e-4
    ys = np.where(small, 1.0, y)
    return np.where(small, 1 + y * y / 6, np.sinh(ys) / ys)


def _shc1(y: complex) -> complex:
    """sinh(y)/y of one complex number."""
    return 1 + y * y / 6 if abs(y) < 1e-4 else cmath.sinh(y) / y


def _zroot(z2: Any) -> Any:
    return np.sqrt(np.asarray(z2, dtype=complex))


def _fc(z2: float) -> float:
    """z·coth z."""
    z = cmath.sqrt(z2)
    return (cmath.cosh(z) / _shc1(z)).real


def _fs(z2: float) -> float:
    """z/sinh z."""
    return (1 / _shc1(cmath.sqrt(z2))).real


def _ft(z2: float) -> float:
    """tanh(z/2)/(z/2)."""
    z = cmath.sqrt(z2)
    return (_shc1(z / 2) / cmath.cosh(z / 2)).real


def _gt(z2: float) -> float:
    """(1 − tanh(z/2)/(z/2))/z², by its series near 0."""
    if abs(z2) < 1e-3:
        x2 = z2 / 4
        return 1 / 12 - x2 / 30 + 17 * x2 * x2 / 1260
    return (1 - _ft(z2)) / z2


def fin_profile(x: Any, length: float, m2: float, s0: float, t1: float, t2: float) -> Any:
    """The exact solution of θ'' − m²θ = −s_0 on [0, l] with θ(0) = θ_1, θ(l) = θ_2.

    θ(x) = θ_1·sinh(m(l − x))/sinh(ml) + θ_2·sinh(mx)/sinh(ml)
    + s_0·2·sinh(m(l − x)/2)·sinh(mx/2)/(m²·cosh(ml/2)), written through sinh(y)/y so
    that it is exact for m² → 0 (the parabola s_0·x(l − x)/2) and for m² < 0.

    Parameters
    ----------
    x : float or array
        Position along the segment [m].
    length : float
        l [m].
    m2 : float
        m² [1/m²].
    s0 : float
        Source s_0 [K/m²].
    t1, t2 : float
        End values θ_1, θ_2 [K].

    Returns
    -------
    float or array
        θ(x) [K].
    """
    x = np.asarray(x, dtype=float)
    m = _zroot(m2)
    lx = length - x
    den = _shc(m * length) * length
    a = t1 * lx * _shc(m * lx) / den + t2 * x * _shc(m * x) / den
    p = lx * x / 2 * _shc(m * lx / 2) * _shc(m * x / 2) / np.cosh(m * length / 2)
    return np.real(a + s0 * p)


@dataclass(frozen=True)
class Segment:
    """One segment of the current's path (a 1-D fin).

    Attributes
    ----------
    name : str
        'hot arm', 'tip', 'cold arm' or 'flexure'.
    length : float
        l [m].
    width : float
        Width across the current [m] (cross-section width·t).
    loss : float
        G', conductance to the substrate per unit length [W/(m·K)].
    start, end : tuple of float
        (x, y) of its ends in the actuator's frame [m] (path from the hot anchor).
    arm : str or None
        'hot' or 'cold' for the segments whose elongation moves the tip, else None.
    """

    name: str
    length: float
    width: float
    loss: float
    start: tuple[float, float]
    end: tuple[float, float]
    arm: str | None


def _head_area_perimeter(g: FrameGeometry) -> tuple[float, float]:
    """The head's area outside the tip connector [m²] and its free outline [m]."""
    hx = float(g.head_x)
    hy = float(g.head_x if g.head_y is None else g.head_y)
    H, lt = float(g.tip_height), float(g.tip_length)
    if g.head_shape == "disc":
        area, perim = math.pi * hx * hx, 2 * math.pi * hx
    else:
        area, perim = 4 * hx * hy, 4 * (hx + hy)
    return max(area - H * lt / 2, 0.0), max(perim - H, 0.0)


def head_node(g: FrameGeometry, mat: ThermalMaterial) -> tuple[float, float]:
    """The head's lumped conductance to the substrate [W/K] and heat capacity [J/K].

    Its area outside the tip connector A_h (a disc π·r², a box 4·a·b, less the half of
    the connector it covers) and its free outline P_h (less the connector's width H):
    G_h = g_s·(A_h + P_h·(t/2 + t_v)), C_h = ρ_m·c·t·A_h (module doc).

    Parameters
    ----------
    g : FrameGeometry
        The drawn actuator.
    mat : ThermalMaterial
        The material.

    Returns
    -------
    tuple of float
        (G_h [W/K], C_h [J/K]).
    """
    t = float(g.thickness)
    area, perim = _head_area_perimeter(g)
    conductance = mat.substrate_conductance * (area + perim * (t / 2 + mat.air_gap))
    return conductance, mat.density * mat.heat_capacity * t * area


def segments(g: FrameGeometry, mat: ThermalMaterial) -> list[Segment]:
    """The path's segments from the hot anchor to the flexure's anchor (module doc).

    Parameters
    ----------
    g : FrameGeometry
        The drawn actuator (floats).
    mat : ThermalMaterial
        The material (for the substrate loss).

    Returns
    -------
    list of Segment
        hot arm, tip (two halves, the head at their joint), cold arm, flexure.
    """
    t, gs = float(g.thickness), mat.substrate_conductance
    L, Lf, lt = float(g.length), float(g.flexure_length), float(g.tip_length)
    wh, wc, wf, d = float(g.hot_width), float(g.cold_width), float(g.flexure_width), float(g.d)
    tv = mat.air_gap

    def arm_loss(w: float) -> float:
        return (w + t + 2 * tv) * gs  # S·w·g_s (Lin & Chiao)

    xt = L + lt / 2
    return [
        Segment("hot arm", L, wh, arm_loss(wh), (0.0, 0.0), (L, 0.0), "hot"),
        Segment("tip", d / 2, lt, lt * gs, (xt, 0.0), (xt, d / 2), None),
        Segment("tip", d / 2, lt, lt * gs, (xt, d / 2), (xt, d), None),
        Segment("cold arm", L - Lf, wc, arm_loss(wc), (L, d), (Lf, d), "cold"),
        Segment("flexure", Lf, wf, arm_loss(wf), (Lf, d), (0.0, d), "cold"),
    ]


@dataclass(frozen=True)
class ElectrothermalResult:
    """The actuator at a DC voltage (module doc), SI.

    Attributes
    ----------
    status : str
        'ok'; 'melts' (peak above the melting point: the other numbers are those of the
        model, not of a device); 'not_converged' (the search for the current failed).
    message : str
        Why, in words ('' when ok).
    voltage : float
        V across the anchors [V].
    current : float
        I [A].
    resistance : float
        R = V/I at the operating temperature [Ω].
    resistance_cold : float
        R_0 at the substrate temperature [Ω].
    power : float
        P = V·I [W].
    u_static : float
        The head's steady displacement along the stroke (toward the cold arm) [m].
    u_axial : float
        The head's steady displacement along the arms [m].
    t_max : float
        Peak temperature [K].
    t_max_segment : str
        The segment where it lies.
    t_max_position : tuple of float
        (x, y) in the actuator's frame [m].
    t_max_path : float
        Its distance along the current's path from the hot anchor [m].
    t_head : float
        The head's (and tip's middle) temperature [K].
    hot_elongation, cold_elongation : float
        The arms' free thermal elongations [m].
    tau_thermal : float
        The first thermal mode's time constant [s].
    modes : tuple of (float, float)
        (τ_i [s], a_i [-]) of H(f) (module doc), the shares summing to 1.
    iterations : int
        Steps of the search for the current.
    """

    status: Literal["ok", "melts", "not_converged"]
    message: str
    voltage: float
    current: float
    resistance: float
    resistance_cold: float
    power: float
    u_static: float
    u_axial: float
    t_max: float
    t_max_segment: str
    t_max_position: tuple[float, float]
    t_max_path: float
    t_head: float
    hot_elongation: float
    cold_elongation: float
    tau_thermal: float
    modes: tuple[tuple[float, float], ...]
    iterations: int

    @property
    def f_thermal(self) -> float:
        """1/(2π τ_thermal) [Hz], the first mode's corner."""
        return 1.0 / (2 * math.pi * self.tau_thermal)

    @property
    def t_rise(self) -> float:
        """The stroke's 63.2 % rise time after a step of heating [s]: the root of
        1 − Σ a_i·exp(−t/τ_i) = 1 − 1/e (bisection; the kept modes)."""

        def response(time_s: float) -> float:
            return 1 - sum(a * math.exp(-time_s / tau) for tau, a in self.modes)

        target = 1 - math.exp(-1)
        lo, hi = 0.0, 50 * max(tau for tau, _ in self.modes)
        for _ in range(200):
            mid = (lo + hi) / 2
            if response(mid) < target:
                lo = mid
            else:
                hi = mid
            if hi - lo <= 1e-12 * hi:
                break
        return (lo + hi) / 2

    @property
    def f_cutoff(self) -> float:
        """The heating frequency where |H| = 1/√2 [Hz] (all kept modes)."""
        lo, hi = 1e-3 * self.f_thermal, 1e3 * self.f_thermal
        for _ in range(200):
            mid = math.sqrt(lo * hi)
            if thermal_gain(self, mid) > 1 / math.sqrt(2):
                lo = mid
            else:
                hi = mid
            if hi / lo < 1 + 1e-12:
                break
        return math.sqrt(lo * hi)


def _joint_system(
    segs: list[Segment], mat: ThermalMaterial, t: float, current: float, g_head: float
) -> tuple[np.ndarray, np.ndarray, list[tuple[float, float]]] | None:
    """The joints' 4×4 system A·θ = b at ``current`` and each segment's (m², s_0); None
    past the thermal runaway (module doc)."""
    k, rho0, xi = mat.conductivity, mat.resistivity, mat.tcr
    A = np.zeros((6, 6))
    b = np.zeros(6)
    ms = []
    for i, s in enumerate(segs):
        area = t * s.width
        ka = k * area
        m2 = (s.loss - current**2 * rho0 * xi / area) / ka
        s0 = current**2 * rho0 / (area * ka)
        z2 = m2 * s.length**2
        if z2 <= -(math.pi**2) * (1 - 1e-12):
            return None
        ms.append((m2, s0))
        a, c = ka / s.length * _fc(z2), ka / s.length * _fs(z2)
        load = ka * s0 * s.length / 2 * _ft(z2)
        A[i : i + 2, i : i + 2] += np.array([[a, -c], [-c, a]])
        b[i : i + 2] += load
    A[2, 2] += g_head
    Ar, br = A[1:5, 1:5], b[1:5]
    if np.linalg.eigvalsh(Ar)[0] <= 0:
        return None
    return Ar, br, ms


def _integral(s: Segment, m2: float, s0: float, t1: float, t2: float) -> float:
    """∫θ ds over a segment (exact)."""
    z2 = m2 * s.length**2
    return (t1 + t2) * s.length / 2 * _ft(z2) + s0 * s.length**3 * _gt(z2)


def _state(
    segs: list[Segment], mat: ThermalMaterial, t: float, current: float, g_head: float
) -> tuple[float, np.ndarray, list[tuple[float, float]]] | None:
    """(R, joint temperatures θ_0…θ_5, (m², s_0) per segment) at ``current``."""
    sys_ = _joint_system(segs, mat, t, current, g_head)
    if sys_ is None:
        return None
    Ar, br, ms = sys_
    th = np.zeros(6)
    th[1:5] = np.linalg.solve(Ar, br)
    R = 0.0
    for i, (s, (m2, s0)) in enumerate(zip(segs, ms, strict=True)):
        integ = _integral(s, m2, s0, th[i], th[i + 1])
        R += mat.resistivity / (t * s.width) * (s.length + mat.tcr * integ)
    if not (R > 0 and np.all(np.isfinite(th))):
        return None
    return R, th, ms


def _bisect_current(
    segs: list[Segment], mat: ThermalMaterial, t: float, voltage: float, g_head: float, r0: float
) -> tuple[float, int, bool]:
    """The current I with I·R(I) = V (module doc): (I, steps, converged)."""

    def excess(current: float) -> float:
        st = _state(segs, mat, t, current, g_head)
        return math.inf if st is None else current * st[0] - voltage

    from scipy.optimize import brentq

    lo, hi = 0.0, voltage / r0
    steps = 0
    while excess(hi) < 0 and steps < MAX_ITERATIONS:  # negative ξ: R falls with T
        lo, hi = hi, 2 * hi
        steps += 1
    # past the runaway the excess is +inf: halve toward lo until hi is finite
    while math.isinf(e_hi := excess(hi)) and steps < MAX_ITERATIONS:
        mid = (lo + hi) / 2
        e_mid = excess(mid)
        if e_mid < 0:
            lo = mid
        else:
            hi = mid
        steps += 1
    if not (e_hi >= 0 and math.isfinite(e_hi)):
        return lo, steps, False
    if e_hi == 0:
        return hi, steps, True
    root, info = brentq(excess, lo, hi, xtol=1e-300, rtol=4 * np.finfo(float).eps,
                        maxiter=max(MAX_ITERATIONS - steps, 1), full_output=True,
                        disp=False)  # fmt: skip
    steps += info.iterations
    st = _state(segs, mat, t, root, g_head)
    ok = st is not None and abs(root * st[0] - voltage) <= VOLTAGE_RTOL * voltage
    return root, steps, ok


@functools.cache
def _gauss64() -> tuple[np.ndarray, np.ndarray]:
    """64-point Gauss–Legendre nodes and weights on [−1, 1]."""
    return np.polynomial.legendre.leggauss(64)


def _modal(
    segs: list[Segment],
    mat: ThermalMaterial,
    t: float,
    g_head: float,
    c_head: float,
    q_of: Any,
    w_of: Any,
) -> tuple[float, tuple[tuple[float, float], ...]]:
    """The chain's thermal modes by linear elements (module doc): (τ_1, modes of H)."""
    from scipy.linalg import eigh_tridiagonal, solve_banded

    rc = mat.density * mat.heat_capacity
    cond, lossh, cap, qe, we = [], [], [], [], []
    head = 0  # the node after the first tip half: the head's
    for k, s in enumerate(segs):
        ne = ELEMENTS if s.name != "tip" else max(ELEMENTS // 4, 4)
        area = t * s.width
        xs = np.linspace(0.0, s.length, ne + 1)
        h = np.diff(xs)
        xm = (xs[:-1] + xs[1:]) / 2
        cond.append(mat.conductivity * area / h)  # element conductance [W/K]
        lossh.append(s.loss * h / 6)  # consistent substrate loss, off-diagonal [W/K]
        cap.append(rc * area * h / 2)  # lumped heat capacity per end [J/K]
        qe.append(q_of(s, xm) * h / 2)  # source per end [W]
        we.append(w_of(s, xm) * h / 2)  # stroke per kelvin per end [m/K]
        if k <= 1:
            head += ne
    c, lo, cp, qh, wh = (np.concatenate(v) for v in (cond, lossh, cap, qe, we))
    N = c.size + 1
    dg = np.zeros(N)
    dg[:-1] += c + 2 * lo
    dg[1:] += c + 2 * lo
    off = -c + lo  # K[i, i+1] of the chain (tridiagonal in path order)
    Cd = np.zeros(N)
    Cd[:-1] += cp
    Cd[1:] += cp
    q = np.zeros(N)
    q[:-1] += qh
    q[1:] += qh
    w = np.zeros(N)
    w[:-1] += wh
    w[1:] += wh
    dg[head] += g_head
    Cd[head] += c_head
    # the anchors (first and last node) are held at T_0
    kd, ko, Cf, qf, wf = dg[1:-1], off[1:-1], Cd[1:-1], q[1:-1], w[1:-1]
    # C diagonal: C^(-1/2)·K·C^(-1/2) is symmetric tridiagonal
    r = 1 / np.sqrt(Cf)
    sd, so = kd * r * r, ko * r[:-1] * r[1:]
    count = min(MODES_KEPT + 1, Cf.size)
    lam, psi = eigh_tridiagonal(sd, so, select="i", select_range=(0, count - 1))
    phi = psi * r[:, None]  # C-orthonormal modes
    share = (wf @ phi) * (phi.T @ qf) / lam
    ab = np.zeros((3, kd.size))
    ab[0, 1:], ab[1], ab[2, :-1] = ko, kd, ko
    total = float(wf @ solve_banded((1, 1), ab, qf))  # wᵀK⁻¹q: every mode
    tau = 1 / lam
    if not (total != 0 and np.isfinite(total)):
        return float(tau[0]), ((float(tau[0]), 1.0),)
    a = share / total
    kept = [(float(tau[i]), float(a[i])) for i in range(count - 1)]
    kept.append((float(tau[count - 1]), float(1 - a[: count - 1].sum())))
    return float(tau[0]), tuple(kept)


def electrothermal(g: FrameGeometry, mat: ThermalMaterial, voltage: float) -> ElectrothermalResult:
    """The actuator ``g`` at a DC ``voltage`` across its anchors (module doc).

    Parameters
    ----------
    g : FrameGeometry
        The drawn actuator (scalar floats; the geometry the springs use).
    mat : ThermalMaterial
        The film's and gap's data.
    voltage : float
        V [V], ≥ 0.

    Returns
    -------
    ElectrothermalResult
        Current, resistance, power, peak temperature and where, the stroke, the thermal
        modes; ``status`` says when the result is not physical.

    Raises
    ------
    ValueError
        For a negative or non-finite voltage or non-positive material data.
    """
    if not (math.isfinite(voltage) and voltage >= 0):
        raise ValueError(f"voltage must be finite and ≥ 0, got {voltage!r}")
    for name in ("resistivity", "conductivity", "density", "heat_capacity", "air_conductivity",
                 "air_gap", "substrate_temperature"):  # fmt: skip
        v = getattr(mat, name)
        if not (math.isfinite(v) and v > 0):
            raise ValueError(f"material {name} must be finite and > 0, got {v!r}")
    t = float(g.thickness)
    T0 = mat.substrate_temperature
    segs = segments(g, mat)
    g_head, c_head = head_node(g, mat)
    r0 = sum(mat.resistivity * s.length / (t * s.width) for s in segs)
    if voltage == 0:
        current, steps, ok = 0.0, 0, True
    else:
        current, steps, ok = _bisect_current(segs, mat, t, voltage, g_head, r0)
    st = _state(segs, mat, t, current, g_head)
    assert st is not None  # the search keeps the current below the runaway
    R, th, ms = st
    # the peak: a scan of each segment's exact profile, refined twice around its maximum
    best = (-math.inf, 0, 0.0)
    for i, (s, (m2, s0)) in enumerate(zip(segs, ms, strict=True)):
        a, b = 0.0, s.length
        for _ in range(4):
            xs = np.linspace(a, b, 129)
            prof = fin_profile(xs, s.length, m2, s0, th[i], th[i + 1])
            j = int(np.argmax(prof))
            a, b = xs[max(j - 1, 0)], xs[min(j + 1, xs.size - 1)]
        if prof[j] > best[0]:
            best = (float(prof[j]), i, float(xs[j]))
    tmax_rise, iseg, xpos = best
    s = segs[iseg]
    frac = xpos / s.length
    pos = (s.start[0] + frac * (s.end[0] - s.start[0]), s.start[1] + frac * (s.end[1] - s.start[1]))
    path = sum(x.length for x in segs[:iseg]) + xpos
    # elongations: Gauss–Legendre on the exact profile
    gx, gw = _gauss64()
    elong = {"hot": 0.0, "cold": 0.0}
    for i, (sg, (m2, s0)) in enumerate(zip(segs, ms, strict=True)):
        if sg.arm is None:
            continue
        xq = (gx + 1) / 2 * sg.length
        prof = fin_profile(xq, sg.length, m2, s0, th[i], th[i + 1])
        eps = thermal_strain(T0 + prof, T0, mat.expansion)
        elong[sg.arm] += float(np.sum(eps * gw) * sg.length / 2)
    ux, uy, _ = thermal_displacement(g, elong["hot"], elong["cold"])
    # modes: the source at the operating point, the stroke per kelvin at its temperature
    ah = thermal_displacement(g, 1.0, 0.0)[1]
    ac = thermal_displacement(g, 0.0, 1.0)[1]
    seg_index = {id(x): i for i, x in enumerate(segs)}

    def q_of(sg: Segment, x: np.ndarray) -> np.ndarray:
        if current == 0:  # no source: H of a uniform heating
            return np.full_like(x, 1.0 / (t * sg.width))
        i = seg_index[id(sg)]
        m2, s0 = ms[i]
        prof = fin_profile(x, sg.length, m2, s0, th[i], th[i + 1])
        return current**2 * mat.resistivity / (t * sg.width) * (1 + mat.tcr * prof)

    def w_of(sg: Segment, x: np.ndarray) -> np.ndarray:
        if sg.arm is None:
            return np.zeros_like(x)
        i = seg_index[id(sg)]
        m2, s0 = ms[i]
        prof = fin_profile(x, sg.length, m2, s0, th[i], th[i + 1])
        alpha = expansion_coefficient(T0 + prof, mat.expansion)
        return alpha * (float(ah) if sg.arm == "hot" else float(ac))

    tau1, modes = _modal(segs, mat, t, g_head, c_head, q_of, w_of)
    t_max = T0 + tmax_rise
    status: Literal["ok", "melts", "not_converged"] = "ok"
    message = ""
    if not ok:
        status = "not_converged"
        message = (
            f"the search for the current did not reach |I·R − V| ≤ {VOLTAGE_RTOL:g}·V in "
            f"{MAX_ITERATIONS} steps"
        )
    if t_max > mat.melting_temperature:
        status = "melts"
        message = (
            f"peak temperature {t_max:.4g} K above the melting point "
            f"{mat.melting_temperature:.4g} K ({s.name}) at {voltage:g} V"
        )
    return ElectrothermalResult(
        status=status,
        message=message,
        voltage=float(voltage),
        current=float(current),
        resistance=float(R),
        resistance_cold=float(r0),
        power=float(current * current * R),
        u_static=float(uy),
        u_axial=float(ux),
        t_max=float(t_max),
        t_max_segment=s.name,
        t_max_position=(float(pos[0]), float(pos[1])),
        t_max_path=float(path),
        t_head=float(T0 + th[2]),
        hot_elongation=elong["hot"],
        cold_elongation=elong["cold"],
        tau_thermal=tau1,
        modes=modes,
        iterations=steps,
    )


def temperature_profile(
    g: FrameGeometry, mat: ThermalMaterial, res: ElectrothermalResult, points: int = 101
) -> dict[str, np.ndarray]:
    """The exact temperature along the current's path at the operating point of ``res``.

    Parameters
    ----------
    g : FrameGeometry
        The actuator ``res`` was computed for.
    mat : ThermalMaterial
        Its material.
    res : ElectrothermalResult
        The operating point (its current).
    points : int
        Points per segment (both ends included).

    Returns
    -------
    dict
        ``s`` (distance along the path from the hot anchor [m]), ``x``, ``y`` (position in
        the actuator's frame [m]), ``t`` (temperature [K]), ``segment`` (index into
        :func:`segments`), each an array; and ``head`` (the head's temperature rise [K]).
    """
    t = float(g.thickness)
    segs = segments(g, mat)
    g_head, _ = head_node(g, mat)
    st = _state(segs, mat, t, res.current, g_head)
    if st is None:
        raise ValueError("the operating point lies past the thermal runaway")
    _, th, ms = st
    out: dict[str, list] = {"s": [], "x": [], "y": [], "t": [], "segment": []}
    s0_path = 0.0
    for i, (sg, (m2, s0)) in enumerate(zip(segs, ms, strict=True)):
        xs = np.linspace(0.0, sg.length, points)
        frac = xs / sg.length
        out["s"].append(s0_path + xs)
        out["x"].append(sg.start[0] + frac * (sg.end[0] - sg.start[0]))
        out["y"].append(sg.start[1] + frac * (sg.end[1] - sg.start[1]))
        out["t"].append(mat.substrate_temperature + fin_profile(xs, sg.length, m2, s0, th[i],
                                                                th[i + 1]))  # fmt: skip
        out["segment"].append(np.full(points, i))
        s0_path += sg.length
    prof = {k: np.concatenate(v) for k, v in out.items()}
    prof["head"] = np.array(th[2])
    return prof


def modal_gain(modes: Any, frequency: Any, waveform: str = "ac") -> Any:
    """The stroke's gain at a heating frequency from the thermal modes (module doc).

    Parameters
    ----------
    modes : sequence of (float, float)
        (τ_i [s], a_i [-]) of :attr:`ElectrothermalResult.modes`.
    frequency : float or numpy.ndarray
        f [Hz]: the heating power's oscillation (sinusoidal waveforms) or the square
        wave's repetition (``unipolar``).
    waveform : str
        'ac' or 'dc-biased' (a sinusoidal power: |H(f)| = |Σ a_i/(1 + j·2πf·τ_i)|), or
        'unipolar' (a 0/1 square wave of 50 % duty: half swing over the static one,
        Σ a_i·tanh(1/(4f·τ_i))).

    Returns
    -------
    float or numpy.ndarray
        The gain [-] (1 at f → 0).
    """
    f = np.asarray(frequency, dtype=float)
    if waveform == "unipolar":
        out = sum(a * np.tanh(1 / (4 * f * tau)) if tau > 0 else a + 0 * f for tau, a in modes)
    else:
        w = 2 * math.pi * f
        out = np.abs(sum(a / (1.0 + 1j * w * tau) for tau, a in modes))
    return float(out) if np.ndim(out) == 0 else out


def thermal_gain(res: ElectrothermalResult, heating_frequency: float) -> float:
    """|H(f)| = |Σ a_i/(1 + j·2πf·τ_i)| [-] at the heating frequency f [Hz] (module doc).

    Parameters
    ----------
    res : ElectrothermalResult
        The operating point (its modes).
    heating_frequency : float
        f [Hz] of the heating power's oscillation.

    Returns
    -------
    float
        The stroke's small-signal gain relative to DC.
    """
    return float(modal_gain(res.modes, heating_frequency, "ac"))


def _square_gain(res: ElectrothermalResult, frequency: float) -> float:
    """Half swing / half the static swing of the modal response to a 0/1 square wave of
    50 % duty at ``frequency``: Σ a_i·tanh(1/(4fτ_i))."""
    return float(modal_gain(res.modes, frequency, "unipolar"))


def stroke_amplitude(
    res: ElectrothermalResult, drive_frequency: float, waveform: str
) -> tuple[float, float]:
    """The stroke's half swing at a drive (module doc, "Stroke at a drive").

    Parameters
    ----------
    res : ElectrothermalResult
        The actuator at the drive's voltage amplitude V.
    drive_frequency : float
        The electrical drive frequency f [Hz].
    waveform : str
        'ac' (zero DC: heats at 2f), 'unipolar' (square 0/V pulses, 50 % duty, heat at
        f) or 'dc-biased' (a sinusoid swinging 0..V at f).

    Returns
    -------
    tuple of float
        (u [m], f_heat [Hz]): the half swing of the head's stroke and the heating
        frequency.
    """
    if waveform == "ac":
        f_heat = 2 * drive_frequency
        return res.u_static / 2 * thermal_gain(res, f_heat), f_heat
    if waveform == "unipolar":
        return res.u_static / 2 * _square_gain(res, drive_frequency), drive_frequency
    if waveform == "dc-biased":
        return res.u_static / 2 * thermal_gain(res, drive_frequency), drive_frequency
    raise ValueError(f"unknown waveform {waveform!r} (ac, unipolar, dc-biased)")
