"""The hot/cold-arm actuator as a frame: its drawn shape and the head's springs (closed form).

MODEL.md, "From the drawn actuator to the head's springs". The actuator, in its own
frame (x along the arms from the anchors at x = 0 to the tip, y across them toward
the cold arm, which is also the stroke direction):

- hot arm: x ∈ [0, L], y ∈ [−w_h/2, w_h/2];
- flexure: x ∈ [0, L_f], centred on y = d, width w_f;
- cold arm: x ∈ [L_f, L], centred on y = d, width w_c, with d = w_h/2 + g + w_c/2;
- tip connector: x ∈ [L, L + l_tip], y ∈ [−w_h/2, d + w_c/2] (height H = w_h + g + w_c),
  spanning both arms (rigid in the closed form);
- head: its centre at P = (L + l_tip/2 + r_x, y_m), r_x its half-extent along x and
  y_m the connector's mid-height, so it overlaps half of the connector; a disc of
  radius r ≥ (H²/4 + l_tip²/4)/l_tip covers the connector's end, so the drawn outline
  has no acute notch there (:func:`head_covers_tip`); rigid, and carries the load;
- anchors: squares of side a at x ∈ [−a, 0], the hot arm's reaching outward from its
  outer edge (y ≤ w_h/2), the flexure's from its inner edge (y ≥ d − w_f/2), so the two
  stay apart by the flexure's gap.

**Closed form** (flexibility / unit-load method, as for the two-beam thermal actuator of
Lobontiu & Garcia, *Mechanics of Microelectromechanical Systems*, Springer 2005,
ch. 4, doi:10.1007/b100026; matrix form as in Przemieniecki, *Theory of Matrix
Structural Analysis*, 1968): each arm is an Euler–Bernoulli beam (E, I = t·w³/12,
A = t·w per segment) clamped at x = 0. Its tip compliance in (axial u, transverse v,
rotation φ), with M(x) = F·(L − x) + M_tip,

    C_uu = Σ l_i/(E A_i),   C_vv = ∫ (L − x)²/(E I) dx,   C_vφ = ∫ (L − x)/(E I) dx,
    C_φφ = ∫ 1/(E I) dx     (exact integrals over the uniform segments),

plus, at each joint where an arm's end enters a wider body (the hot arm and the cold arm
into the tip, the flexure into the cold arm), the axial compliance c_j/(E·t) of the load
spreading into that body (Saint-Venant; c_j = :data:`JOINT_AXIAL`, from plane-stress FE
of a beam entering a block: the joint acts as about 1.2 widths of extra arm), is
inverted and carried to the head centre P by the rigid tip, T = [[1, 0, −(y_B − y_P)],
[0, 1, x_B − x_P], [0, 0, 1]]: K_P = Σ Tᵀ K_arm T. The head takes forces only, so the
rotation is condensed out: K = ((K_P⁻¹)[:2, :2])⁻¹, a 2×2 stiffness in (x, y).

**Slider frame**: the stroke y makes the impact angle θ with the slider (its normal part
is u·sinθ, as the dimensionless scales ξ = x_v/(u sinθ) say); the arms point toward the
slider at θ from its normal. With t along the slider (impact direction) and n its normal
(toward the slider): y = cosθ·t + sinθ·n, x = −sinθ·t + cosθ·n, and K_tn = Q·K·Qᵀ with
Q = [[−sinθ, cosθ], [cosθ, sinθ]]. The model's springs are the head's compliance in each
direction with the other free, C = K⁻¹ (:func:`head_compliance`), with the slider beam's
own compliance in series (:func:`slider_point_compliance`), and their effective masses
and the first modes in and out of the plane come from Rayleigh–Ritz over the frame's
static shapes (:func:`rayleigh_matrices`, :func:`first_mode`,
:func:`out_of_plane_first_mode`; MODAL_RTOL against the modal FE).

Every function takes floats or numpy arrays (broadcast), SI units.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = [
    "ARM_MASS_SHARE_MAX",
    "CLOSED_FORM_RTOL",
    "COVER_MARGIN",
    "DISC_VERTICES",
    "JOINT_AXIAL",
    "MODAL_RTOL",
    "RHO_MAX",
    "FrameGeometry",
    "FrameStiffness",
    "Rect",
    "beam_tip_compliance",
    "contact_offset",
    "directional_mass",
    "first_mode",
    "frame_stiffness",
    "head_compliance",
    "head_covers_tip",
    "head_disc_diameter",
    "head_radius_min",
    "out_of_plane_first_mode",
    "random_geometries",
    "rayleigh_matrices",
    "shape",
    "slider_point_compliance",
    "slider_springs",
    "thermal_displacement",
    "torsion_constant",
]

#: Axial compliance of a joint, in widths of the arm entering a wider body (see above).
JOINT_AXIAL = 1.2
#: |ρ| above this: the decoupled springs misdescribe the head (model-adequacy finding).
RHO_MAX = 0.3
#: Arms whose first-mode share of mass exceeds this share of the head's: said so.
ARM_MASS_SHARE_MAX = 0.1
#: Largest relative error of the closed form's k_v, k_h and α against the mesh-converged
#: plane-stress FE (:mod:`betvdesign.model.frame_fe`) on the shipped actuators and the 50
#: seeded random ones of :func:`random_geometries` (arms of L/w ≥ 10, heads covering the
#: tip): measured 2.8 % (k_v), 2.6 % (k_h), 1.0 % (α), median 0.6 %
#: (benchmarks/bench_layout.py, benchmarks/README.md). Below the ±5 % on ϖ (±10 % on k_v)
#: and ±10 % on α the mode-margin rule probes, so the check uses the closed form.
CLOSED_FORM_RTOL = 0.03
#: Largest relative error of the Rayleigh–Ritz first in-plane mode
#: (:func:`rayleigh_matrices`, :func:`first_mode`) against the modal plane-stress FE
#: (:func:`betvdesign.model.frame_fe.frame_modes`) on the shipped actuators and the seeded
#: random ones (benchmarks/bench_modal.py, benchmarks/README.md).
MODAL_RTOL = 0.05


@dataclass(frozen=True)
class Rect:
    """An axis-aligned rectangle of the actuator's own frame [m]: (x0, y0)–(x1, y1)."""

    name: str
    x0: float
    y0: float
    x1: float
    y1: float

    @property
    def area(self) -> float:
        return (self.x1 - self.x0) * (self.y1 - self.y0)


@dataclass(frozen=True)
class FrameGeometry:
    """The drawn actuator (see the module doc), SI floats or arrays.

    head_x: the head's half-extent along x [m] (disc: its radius; box: half its length);
    head_y: its half-extent along y [m]; head_shape: "disc" or "box".
    """

    length: Any
    hot_width: Any
    cold_width: Any
    flexure_length: Any
    flexure_width: Any
    gap: Any
    tip_length: Any
    thickness: Any
    youngs_modulus: Any
    head_x: Any
    head_y: Any = None
    head_shape: str = "disc"
    anchor_size: Any = 20e-6

    @property
    def d(self) -> Any:
        """y of the cold arm's (and flexure's) axis [m]."""
        return self.hot_width / 2 + self.gap + self.cold_width / 2

    @property
    def tip_height(self) -> Any:
        """H: the tip connector's extent across the arms [m]."""
        return self.hot_width + self.gap + self.cold_width

    @property
    def head_centre(self) -> tuple[Any, Any]:
        """(x, y) of the head's centre P [m]: half the connector inside the head, at the
        connector's mid-height."""
        y_mid = (self.d + self.cold_width / 2 - self.hot_width / 2) / 2
        return (self.length + self.tip_length / 2 + self.head_x, y_mid)


#: Vertices of a drawn disc (a regular polygon inscribed in the circle, one vertex on each
#: axis: its extent is the diameter; its sides lie r·(1 − cos(π/N)) inside the circle).
DISC_VERTICES = 128
#: How far inside the drawn head the tip's end corners must lie [m] (grid rounding).
COVER_MARGIN = 10e-9


def head_covers_tip(g: FrameGeometry) -> Any:
    """True where the head covers the tip connector's end corners with a margin (a disc:
    the corners inside its drawn polygon, whose sides lie r·cos(π/N) from its centre, by
    :data:`COVER_MARGIN`; about r ≥ (H²/4 + l_tip²/4)/l_tip; a box at least H wide): the
    drawn outline then meets the connector's sides at obtuse angles, with no notch a
    spacing rule would flag."""
    if g.head_shape == "box":
        return 2 * (g.head_y if g.head_y is not None else g.head_x) >= g.tip_height
    r = g.head_x
    corner = np.hypot(r - g.tip_length / 2, g.tip_height / 2)
    return corner <= r * math.cos(math.pi / DISC_VERTICES) - COVER_MARGIN


def head_radius_min(g: FrameGeometry) -> Any:
    """The smallest disc radius that covers the tip (:func:`head_covers_tip`) [m]."""
    c = math.cos(math.pi / DISC_VERTICES)
    a, b, m = g.tip_length / 2, g.tip_height / 2, COVER_MARGIN
    # (r − a)² + b² = (c·r − m)²  ->  (1 − c²) r² − 2(a − c·m) r + a² + b² − m² = 0
    qa, qb, qc = 1 - c * c, -2 * (a - c * m), a * a + b * b - m * m
    return qc / (-qb / 2 + np.sqrt(qb * qb / 4 - qa * qc))  # the smaller root, stably


def head_disc_diameter(mass_kg: Any, density: Any, thickness: Any) -> Any:
    """Diameter [m] of the disc of ``mass_kg`` in a film of ``density`` [kg/m³] and
    ``thickness`` [m]: sqrt(4m/(π ρ t))."""
    return np.sqrt(4 * mass_kg / (math.pi * density * thickness))


def shape(
    g: FrameGeometry, grid: float | None = None
) -> tuple[list[Rect], tuple[float, float, float, float, str]]:
    """The drawn polygons of one actuator in its own frame: rectangles (hot_arm, flexure,
    cold_arm, tip, anchor_hot, anchor_cold) and the head (cx, cy, half-x, half-y, shape).

    grid: with a drawing grid [m] (the lengths on it), the frame is shifted by at most
    half a step so that every edge lies on the grid and every width is exact (the
    flexure then sits up to half a step off the cold arm's axis, the head's extent starts
    on the grid)."""
    L, Lf, lt, a = (float(v) for v in (g.length, g.flexure_length, g.tip_length, g.anchor_size))
    wh, wc, wf = (float(v) for v in (g.hot_width, g.cold_width, g.flexure_width))

    def q(x: float) -> float:
        return x if grid is None else round(round(x / grid) * grid, 15)

    y0 = q(-wh / 2)  # the hot arm's outer edge
    y1 = y0 + wh
    c0 = y1 + float(g.gap)  # the cold arm
    c1 = c0 + wc
    f0 = q(c0 + (wc - wf) / 2)  # the flexure, centred on the cold arm's axis
    f1 = f0 + wf
    rects = [
        Rect("hot_arm", 0.0, y0, L, y1),
        Rect("flexure", 0.0, f0, Lf, f1),
        Rect("cold_arm", Lf, c0, L, c1),
        Rect("tip", L, y0, L + lt, c1),
        Rect("anchor_hot", -a, y1 - a, 0.0, y1),
        Rect("anchor_cold", -a, f0, 0.0, f0 + a),
    ]
    hx = float(g.head_x)
    hy = float(g.head_x if g.head_y is None else g.head_y)
    x_left = q(L + lt / 2)
    if grid is not None:  # the head's extent on the grid
        hx, hy = q(2 * hx) / 2, q(2 * hy) / 2
    cy = (y0 + c1) / 2
    if grid is not None:
        cy = q(cy - hy) + hy
    return rects, (x_left + hx, cy, hx, hy, g.head_shape)


def beam_tip_compliance(segments: list[tuple[Any, Any, Any]], youngs_modulus: Any) -> np.ndarray:
    """Tip compliance (…, 3, 3) of a beam clamped at its root, in (axial, transverse,
    rotation) at its tip: ``segments`` are (length, area, second moment) from root to
    tip [m, m², m⁴] (see the module doc for the integrals)."""
    total = sum(s[0] for s in segments)
    E = youngs_modulus
    c_uu = c_vv = c_vp = c_pp = 0.0
    a = 0.0
    for length, area, inertia in segments:
        b = a + length
        ra, rb = total - a, total - b  # distances to the tip
        c_uu = c_uu + length / (E * area)
        c_vv = c_vv + (ra**3 - rb**3) / (3 * E * inertia)
        c_vp = c_vp + (ra**2 - rb**2) / (2 * E * inertia)
        c_pp = c_pp + length / (E * inertia)
        a = b
    shp = np.broadcast(c_uu, c_vv, c_vp, c_pp).shape
    C = np.zeros((*shp, 3, 3))
    C[..., 0, 0] = c_uu
    C[..., 1, 1] = c_vv
    C[..., 1, 2] = C[..., 2, 1] = c_vp
    C[..., 2, 2] = c_pp
    return C


def _transfer(xb: Any, yb: Any, xp: Any, yp: Any) -> np.ndarray:
    shp = np.broadcast(xb, yb, xp, yp).shape
    T = np.zeros((*shp, 3, 3))
    T[..., 0, 0] = T[..., 1, 1] = T[..., 2, 2] = 1.0
    T[..., 0, 2] = -(yb - yp)
    T[..., 1, 2] = xb - xp
    return T


@dataclass(frozen=True)
class FrameStiffness:
    """The head's 2×2 stiffness in the actuator's frame [N/m]: k_xx (along the arms),
    k_yy (along the stroke), k_xy."""

    k_xx: Any
    k_yy: Any
    k_xy: Any


def _arms(g: FrameGeometry) -> tuple[np.ndarray, np.ndarray]:
    """The tip compliances of the hot arm and of the cold side (flexure + cold arm), with
    the joints' axial compliance (module doc)."""
    t, E = g.thickness, g.youngs_modulus

    def seg(length: Any, width: Any) -> tuple[Any, Any, Any]:
        return (length, t * width, t * width**3 / 12)

    hot = beam_tip_compliance([seg(g.length, g.hot_width)], E)
    cold = beam_tip_compliance(
        [seg(g.flexure_length, g.flexure_width), seg(g.length - g.flexure_length, g.cold_width)],
        E,
    )
    hot[..., 0, 0] += JOINT_AXIAL / (E * t)  # hot arm into the tip
    cold[..., 0, 0] += 2 * JOINT_AXIAL / (E * t)  # flexure into cold arm, cold arm into tip
    return hot, cold


def _frame_matrix(g: FrameGeometry) -> np.ndarray:
    """The 3×3 stiffness of the frame at the head centre (rotation not condensed)."""
    hot, cold = _arms(g)
    xp, yp = g.head_centre
    K = np.zeros((*np.broadcast(hot[..., 0, 0], cold[..., 0, 0], xp, yp).shape, 3, 3))
    for C, yb in ((hot, 0.0), (cold, g.d)):
        T = _transfer(g.length, yb, xp, yp)
        K = K + np.swapaxes(T, -1, -2) @ np.linalg.inv(C) @ T
    return K


def frame_stiffness(g: FrameGeometry) -> FrameStiffness:
    """The closed form of the module doc: the head's stiffness in the actuator's frame."""
    K = _frame_matrix(g)
    C2 = np.linalg.inv(K)[..., :2, :2]
    K2 = np.linalg.inv(C2)
    return FrameStiffness(K2[..., 0, 0], K2[..., 1, 1], K2[..., 0, 1])


def thermal_displacement(
    g: FrameGeometry, hot_elongation: Any, cold_elongation: Any
) -> tuple[Any, Any, Any]:
    """The head's displacement under the arms' free thermal elongations, no external load.

    Each arm's end moves by its elastic part plus its free elongation δ along x, so the
    force it puts on the rigid tip is K_arm·(T·q − (δ, 0, 0)) with q = (u, v, φ) at the
    head centre P and T the transfer of :func:`frame_stiffness`. Equilibrium of the tip
    and head (no load on either) gives

        K_P·q = Σ_arms Tᵀ·K_arm·(δ, 0, 0)ᵀ,

    the frame's own 3×3 stiffness K_P loaded by the thermal strain (the flexibility
    method's thermal load; Przemieniecki, Theory of Matrix Structural Analysis, 1968).
    The hot arm is at y = 0, the cold side (flexure and cold arm in series, their
    elongations added) at y = d: a longer hot arm turns the tip toward the cold arm, +y.

    Parameters
    ----------
    g : FrameGeometry
        The drawn actuator.
    hot_elongation : float or array
        Free thermal elongation of the hot arm, ∫ε_th dx [m].
    cold_elongation : float or array
        Free thermal elongation of the flexure plus the cold arm [m].

    Returns
    -------
    tuple
        (u_x, u_y, φ): the head centre's displacement along the arms and along the
        stroke [m] and the tip's rotation [rad].
    """
    hot, cold = _arms(g)
    xp, yp = g.head_centre
    K = _frame_matrix(g)
    f = 0.0
    for C, yb, delta in ((hot, 0.0, hot_elongation), (cold, g.d, cold_elongation)):
        T = _transfer(g.length, yb, xp, yp)
        d = np.zeros((*np.shape(delta), 3))
        d[..., 0] = delta
        f = f + (np.swapaxes(T, -1, -2) @ np.linalg.solve(C, d[..., None]))[..., 0]
    q = np.linalg.solve(K, np.asarray(f)[..., None])[..., 0]
    return q[..., 0], q[..., 1], q[..., 2]


def slider_springs(k: FrameStiffness, theta_rad: Any) -> tuple[Any, Any, Any]:
    """(K_nn, K_tt, K_nt) [N/m] in the slider's frame at impact angle θ (module doc)."""
    s, c = np.sin(theta_rad), np.cos(theta_rad)
    k_tt = s * s * k.k_xx + c * c * k.k_yy - 2 * s * c * k.k_xy
    k_nn = c * c * k.k_xx + s * s * k.k_yy + 2 * s * c * k.k_xy
    k_nt = -s * c * k.k_xx + s * c * k.k_yy + (c * c - s * s) * k.k_xy
    return k_nn, k_tt, k_nt


@functools.lru_cache(maxsize=8)
def _gauss(n: int = 24) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Legendre nodes and weights on [0, 1] (cached, read-only)."""
    x, w = np.polynomial.legendre.leggauss(n)
    x, w = (x + 1) / 2, w / 2
    x.flags.writeable = w.flags.writeable = False
    return x, w


def head_compliance(k: FrameStiffness, theta_rad: Any) -> tuple[Any, Any, Any]:
    """(C_nn, C_tt, C_nt) [m/N]: the head's compliance in the slider's frame, C = K⁻¹ of
    :func:`slider_springs`'s 2×2 (each direction with the other free: MODEL.md, "What the
    model's springs mean")."""
    k_nn, k_tt, k_nt = slider_springs(k, theta_rad)
    det = k_nn * k_tt - k_nt * k_nt
    return k_tt / det, k_nn / det, -k_nt / det


def slider_point_compliance(
    length: Any, width: Any, thickness: Any, youngs_modulus: Any, offset: Any, beam_count: int
) -> tuple[Any, Any]:
    """(C_s,n, C_s,t) [m/N]: the slider's own compliance where a head strikes it, normal
    to the slider (bending) and along it (axial).

    The two actuators of a set strike the two outer beams at the same x, mirrored about
    the slider's axis, so the rigid end pieces neither turn nor move across it: each outer
    beam is a beam with both ends fixed under a point load at ``offset`` = a from its
    nearer end (b = L − a). Deflection under the load (Roark's Formulas for Stress and
    Strain, 7th ed., Table 8.1 case 1d; Gere, Mechanics of Materials, fixed-end beam with
    a concentrated load): C_s,n = a³b³/(3·E·I·L³), I = t·w³/12. Along the slider, the
    beam fixed at both ends carries the load to both ends in parallel (Gere, statically
    indeterminate bar): C_s,t = a·b/(E·A·L), A = w·t. One beam: the two heads press its
    opposite faces at the same point, so it does not bend (C_s,n = 0).
    """
    a = offset
    b = length - offset
    inertia = thickness * width**3 / 12
    c_n = np.where(
        np.asarray(beam_count) < 2, 0.0, a**3 * b**3 / (3 * youngs_modulus * inertia * length**3)
    )
    c_t = a * b / (youngs_modulus * width * thickness * length)
    return c_n, c_t


def contact_offset(beam_length: Any, head_radius: Any, clearance: Any, index: int) -> Any:
    """Distance [m] of a set's contact point from the slider's centre, as ``betv layout``
    draws it: max(L/4, r + c) for the first set striking one way, each next one
    2·(r + c) further (r the head's half-extent, c the drawn clearance)."""
    return np.maximum(beam_length / 4, head_radius + clearance) + index * (
        2 * head_radius + 2 * clearance
    )


def _segmented_shape(
    segments: list[tuple[Any, Any, Any, Any]], length: Any, tip: np.ndarray, E: Any
) -> list[tuple[Any, Any, np.ndarray, np.ndarray]]:
    """The static shape of a cantilever of ``segments`` (x0, x1, area, inertia) under the
    tip loads that give it the tip displacement ``tip`` (…, 3) = (u, v, φ): per segment,
    (x0, x1, u(x), v(x)) at the Gauss points (exact: u = N·∫dx/EA, v'' = M(x)/EI with
    M = V·(L − x) + M_tip; the joints' axial compliance left out of u)."""
    C = beam_tip_compliance([(s[1] - s[0], s[2], s[3]) for s in segments], E)
    C[..., 0, 0] = sum((s[1] - s[0]) / (E * s[2]) for s in segments)
    f = np.linalg.solve(C, tip[..., None])[..., 0]
    N, V, Mt = (f[..., k][..., None] for k in range(3))
    s_, _ = _gauss()
    out = []
    u_a = v_a = th_a = 0.0
    for x0, x1, area, inertia in segments:
        x0_, x1_, A_, I_ = (np.asarray(v, dtype=float)[..., None] for v in (x0, x1, area, inertia))
        L_ = np.asarray(length, dtype=float)[..., None]
        ma = V * (L_ - x0_) + Mt
        sx = (x1_ - x0_) * s_
        u = u_a + N * sx / (E * A_)
        v = v_a + th_a * sx + (ma * sx**2 / 2 - V * sx**3 / 6) / (E * I_)
        out.append((x0, x1, u, v))
        d = x1_ - x0_
        u_a = u_a + N * d / (E * A_)
        v_a = v_a + th_a * d + (ma * d**2 / 2 - V * d**3 / 6) / (E * I_)
        th_a = th_a + (ma * d - V * d**2 / 2) / (E * I_)
    return out


def rayleigh_matrices(
    g: FrameGeometry, arm_density: Any, head_mass: Any
) -> tuple[np.ndarray, np.ndarray]:
    """(C, M): the head's 2×2 compliance [m/N] and the Rayleigh–Ritz mass matrix [kg·m²/N²]
    of the frame's static shapes, both in the actuator's (x, y) per unit load at the head.

    The shape under a load f (2-vector) at the head is the frame's static one: the rigid
    tip and head move by (u, v, φ) = K_P⁻¹·(f, 0) at P; each arm, clamped at its root,
    takes the exact static shape of its segments under the tip loads that give its end
    that motion (:func:`_segmented_shape`). Its kinetic energy per ω² is ½·fᵀ·M·f with

        M = Σ_arms ρ·t·∫ w(x)·(φ_u φ_uᵀ + φ_v φ_vᵀ) dx + Σ_{tip, head} (m·φ_c φ_cᵀ + J·φ_φ φ_φᵀ),

    φ_c the velocity of each rigid body's centroid and J its moment of inertia (tip:
    m(l² + H²)/12; a disc head: m r²/2; a box: m(a² + b²)/3 with a, b its half-extents).
    Rayleigh's quotient of the shape under f is ω² = fᵀCf / fᵀMf (the strain energy of a
    unit static load is ½ fᵀCf); its minimum, the smallest eigenvalue of C·u = ω²·M·u, is
    the Rayleigh–Ritz first in-plane mode (Meirovitch, *Fundamentals of Vibrations*,
    2001, §8.5)."""
    t, E = g.thickness, g.youngs_modulus
    K = _frame_matrix(g)
    Kinv = np.linalg.inv(K)
    C = Kinv[..., :2, :2]
    xp, yp = g.head_centre
    M = np.zeros((*C.shape[:-2], 2, 2))
    _, w_ = _gauss()
    arms = (
        (0.0, [(0.0, g.length, t * g.hot_width, t * g.hot_width**3 / 12)]),
        (
            g.d,
            [
                (0.0, g.flexure_length, t * g.flexure_width, t * g.flexure_width**3 / 12),
                (g.flexure_length, g.length, t * g.cold_width, t * g.cold_width**3 / 12),
            ],
        ),
    )
    for yb, segs in arms:
        T = _transfer(g.length, yb, xp, yp)
        shapes = [_segmented_shape(segs, g.length, (T @ Kinv[..., :, j : j + 1])[..., 0], E)
                  for j in range(2)]  # fmt: skip
        for i in range(2):
            for j in range(2):
                for (x0, x1, ui, vi), (_, _, uj, vj), seg in zip(
                    shapes[i], shapes[j], segs, strict=True
                ):
                    dx = np.asarray(x1) - np.asarray(x0)
                    integral = np.sum((ui * uj + vi * vj) * w_, axis=-1) * dx
                    M[..., i, j] = M[..., i, j] + arm_density * seg[2] * integral
    # the rigid tip and head: (u, v, φ) at P of each unit load
    H = g.tip_height
    m_tip = arm_density * t * g.tip_length * H
    J_tip = m_tip * (g.tip_length**2 + H**2) / 12
    tip_c = (g.length + g.tip_length / 2, (g.d + g.cold_width / 2 - g.hot_width / 2) / 2)
    hy = g.head_x if g.head_y is None else g.head_y
    J_head = (
        head_mass * g.head_x**2 / 2
        if g.head_shape == "disc"
        else head_mass * (g.head_x**2 + hy**2) / 3
    )
    for m_b, J_b, (cx, cy) in ((m_tip, J_tip, tip_c), (head_mass, J_head, (xp, yp))):
        vel = []
        for j in range(2):
            u, v, ph = (Kinv[..., k, j] for k in range(3))
            vel.append((u - ph * (cy - yp), v + ph * (cx - xp), ph))
        for i in range(2):
            for j in range(2):
                a, b = vel[i], vel[j]
                M[..., i, j] = M[..., i, j] + m_b * (a[0] * b[0] + a[1] * b[1]) + J_b * a[2] * b[2]
    return C, M


def first_mode(C: np.ndarray, M: np.ndarray) -> tuple[Any, np.ndarray]:
    """The Rayleigh–Ritz first mode of a compliance C and mass M in load coordinates
    (:func:`rayleigh_matrices`, :func:`out_of_plane_first_mode`): (f_1 [Hz], the unit
    load (…, n) whose static shape it is). ω² = min fᵀCf/fᵀMf, taken as 1/max of
    fᵀMf/fᵀCf through the Cholesky factor of C (positive definite for a connected frame;
    M may be singular, e.g. a point head on massless arms)."""
    Lc = np.linalg.cholesky(C)
    Li = np.linalg.inv(Lc)
    S = Li @ M @ np.swapaxes(Li, -1, -2)
    lam, vec = np.linalg.eigh(S)
    f = np.swapaxes(Li, -1, -2) @ vec[..., :, -1:]
    f = f[..., 0] / np.linalg.norm(f[..., 0], axis=-1, keepdims=True)
    return 1 / np.sqrt(lam[..., -1]) / (2 * math.pi), f


def directional_mass(C: np.ndarray, M: np.ndarray, direction: np.ndarray) -> tuple[Any, Any]:
    """(k, m_eff): the stiffness 1/(dᵀCd) [N/m] and Rayleigh effective mass
    dᵀMd/(dᵀCd)² [kg] of the static shape under a load along the unit vector d (…, 2):
    √(k/m_eff) is that shape's Rayleigh frequency [rad/s]."""
    d = np.asarray(direction, dtype=float)
    c = np.einsum("...i,...ij,...j->...", d, C, d)
    m = np.einsum("...i,...ij,...j->...", d, M, d)
    return 1 / c, m / (c * c)


def torsion_constant(a: Any, b: Any) -> Any:
    """Saint-Venant torsion constant J [m⁴] of an a × b rectangle (any order): with
    h ≥ k its sides, J = h·k³·(1/3 − 0.21·(k/h)·(1 − k⁴/(12·h⁴))) (Roark, Formulas for
    Stress and Strain, 7th ed., Table 10.7 case 4; within 4 % for every aspect ratio)."""
    h, k = np.maximum(a, b), np.minimum(a, b)
    return h * k**3 * (1 / 3 - 0.21 * (k / h) * (1 - k**4 / (12 * h**4)))


def out_of_plane_first_mode(
    g: FrameGeometry, arm_density: Any, head_mass: Any, poisson_ratio: Any = 0.22
) -> Any:
    """The drawn actuator's first out-of-plane mode [Hz] (Rayleigh–Ritz, closed form).

    Each arm bends out of the plane (I = w·t³/12, the in-plane integrals of
    :func:`beam_tip_compliance` with it) and twists (G·J, G = E/(2(1 + ν)), J of
    :func:`torsion_constant`), clamped at its root; the rigid tip and head move by
    (w, θ_x, θ_y) at P, an arm's end at (Δx, Δy) from P by (w + θ_x·Δy − θ_y·Δx, slope
    −θ_y, twist θ_x). The static shapes under a force and two moments at P (each arm's
    exact static bending shape, linear twist) give the 3×3 compliance and Rayleigh–Ritz
    mass (arms' translation and twist inertia ρ·A·(w² + t²)/12, the tip's and head's
    translation and rotation about x and y; a disc head m·r²/4 about each, a box
    m·(2a)²/12 about the axis across a); the first mode is the smallest eigenvalue."""
    t, E = g.thickness, g.youngs_modulus
    G = E / (2 * (1 + poisson_ratio))
    xp, yp = g.head_centre
    arms = (
        (0.0, [(0.0, g.length, g.hot_width)]),
        (g.d, [(0.0, g.flexure_length, g.flexure_width), (g.flexure_length, g.length,
                                                          g.cold_width)]),
    )  # fmt: skip
    Kp = 0.0
    Ts, parts = [], []
    for yb, segs in arms:
        bend = [(x1 - x0, t * w, w * t**3 / 12) for x0, x1, w in segs]
        Cb = beam_tip_compliance(bend, E)[..., 1:, 1:]  # (w, slope)
        c_phi = sum((x1 - x0) / (G * torsion_constant(w, t)) for x0, x1, w in segs)
        shp = np.broadcast(Cb[..., 0, 0], c_phi).shape
        Ka = np.zeros((*shp, 3, 3))
        Ka[..., :2, :2] = np.linalg.inv(Cb)
        Ka[..., 2, 2] = 1 / c_phi
        dx, dy = g.length - xp, yb - yp
        T = np.zeros((*np.broadcast(dx, dy).shape, 3, 3))
        T[..., 0, 0] = 1.0
        T[..., 0, 1] = dy
        T[..., 0, 2] = -dx
        T[..., 1, 2] = -1.0
        T[..., 2, 1] = 1.0
        Kp = Kp + np.swapaxes(T, -1, -2) @ Ka @ T
        Ts.append(T)
        parts.append((segs, c_phi))
    C = np.linalg.inv(Kp)  # (w, θx, θy) per unit (F, Mx, My)
    M = np.zeros(C.shape)
    for T, (segs, c_phi) in zip(Ts, parts, strict=True):
        M = _oop_arm_mass(M, T @ C, segs, c_phi, g, arm_density, G)
    M = _oop_body_mass(M, C, g, arm_density, head_mass)
    return first_mode(C, M)[0]


def _oop_arm_mass(
    M: Any, ends: Any, segs: list, c_phi: Any, g: FrameGeometry, arm_density: Any, G: Any
) -> Any:
    """One arm's share of the out-of-plane Rayleigh–Ritz mass matrix.

    Parameters
    ----------
    M : array
        The mass matrix so far (…, 3, 3) [kg, kg·m, kg·m²].
    ends : array
        The arm end's (w, slope, twist) under each unit load at P (…, 3, 3).
    segs : list
        The arm's segments (x0, x1, width) [m].
    c_phi : array
        The arm's torsional compliance [1/(N·m)].
    g : FrameGeometry
        The frame (thickness, length).
    arm_density : float
        Density of the arms [kg/m³].
    G : float
        Shear modulus [Pa].

    Returns
    -------
    array
        ``M`` with the arm's bending (exact static shapes) and twist (linear in the
        torsional compliance) inertia added.
    """
    t, E = g.thickness, g.youngs_modulus
    _, wq = _gauss()
    bend_segs = [(x0, x1, t * w, w * t**3 / 12) for x0, x1, w in segs]
    shapes = []
    for j in range(3):
        tip = np.stack(np.broadcast_arrays(0.0 * ends[..., 0, j], ends[..., 0, j],
                                           ends[..., 1, j]), axis=-1)  # fmt: skip
        shapes.append(_segmented_shape(bend_segs, g.length, tip, E))
    for i in range(3):
        for j in range(3):
            for (x0, x1, _, vi), (_, _, _, vj), (_, _, w) in zip(
                shapes[i], shapes[j], segs, strict=True
            ):
                dxs = np.asarray(x1) - np.asarray(x0)
                M[..., i, j] += arm_density * t * w * np.sum(vi * vj * wq, axis=-1) * dxs
    # twist: linear in the torsional compliance along the arm, φ(x) = φ_B·c(x)/c_phi
    tw = ends[..., 2, :]  # (…, 3)
    acc = 0.0
    for x0, x1, w in segs:
        c0 = acc
        c1 = acc + (x1 - x0) / (G * torsion_constant(w, t))
        # ∫ (c(x)/c_phi)² dx over the segment, c linear from c0 to c1
        frac = (c0 * c0 + c0 * c1 + c1 * c1) / 3 / (c_phi * c_phi) * (x1 - x0)
        ip = arm_density * t * w * (w * w + t * t) / 12
        M = M + (ip * frac)[..., None, None] * (tw[..., :, None] * tw[..., None, :])
        acc = c1
    return M


def _oop_body_mass(M: Any, C: Any, g: FrameGeometry, arm_density: Any, head_mass: Any) -> Any:
    """The rigid tip's and head's share of the out-of-plane mass matrix.

    Parameters
    ----------
    M : array
        The mass matrix so far (…, 3, 3).
    C : array
        The compliance at P (…, 3, 3): (w, θ_x, θ_y) per unit (F, M_x, M_y).
    g : FrameGeometry
        The frame (tip and head sizes, head shape and centre P).
    arm_density : float
        Density of the tip [kg/m³].
    head_mass : float
        The head's mass [kg].

    Returns
    -------
    array
        ``M`` with each body's translation and rotation about x and y (a disc head
        m·r²/4 about each, a box m·(2a)²/12 about the axis across a).
    """
    t = g.thickness
    xp, yp = g.head_centre
    H = g.tip_height
    m_tip = arm_density * t * g.tip_length * H
    tip_c = (g.length + g.tip_length / 2, (g.d + g.cold_width / 2 - g.hot_width / 2) / 2)
    hy = g.head_x if g.head_y is None else g.head_y
    if g.head_shape == "disc":
        jx = jy = head_mass * g.head_x**2 / 4
    else:
        jx, jy = head_mass * (2 * hy) ** 2 / 12, head_mass * (2 * g.head_x) ** 2 / 12
    bodies = (
        (m_tip, m_tip * H**2 / 12, m_tip * g.tip_length**2 / 12, tip_c),
        (head_mass, jx, jy, (xp, yp)),
    )

    def vec(x: Any) -> Any:  # a per-sample scalar against a (..., 3) row
        return np.asarray(x, dtype=float)[..., None]

    def mat(x: Any) -> Any:  # a per-sample scalar against a (..., 3, 3) matrix
        return np.asarray(x, dtype=float)[..., None, None]

    for m_b, j_x, j_y, (cx, cy) in bodies:
        w_c = C[..., 0, :] + C[..., 1, :] * vec(cy - yp) - C[..., 2, :] * vec(cx - xp)
        M = M + mat(m_b) * w_c[..., :, None] * w_c[..., None, :]
        M = M + mat(j_x) * C[..., 1, :, None] * C[..., 1, None, :]
        M = M + mat(j_y) * C[..., 2, :, None] * C[..., 2, None, :]
    return M


#: Seed of the random actuators the closed form's error is stated on.
RANDOM_SEED = 23


def random_geometries(n: int = 50, seed: int = RANDOM_SEED) -> list[tuple[FrameGeometry, float]]:
    """``n`` seeded random drawable actuators with their impact angle [rad]: the set
    :data:`CLOSED_FORM_RTOL` is measured on (tests and benchmarks/bench_layout.py).

    Uniform in: length 100–400 µm; hot arm and flexure 2–4 µm wide, flexure 10–40 % of
    the length but at least 10 widths (arms of L/w ≥ 10); cold arm 6–20 µm; gap 2–5 µm;
    tip 5–15 µm; film 1.5–3 µm, E 150–170 GPa; θ 15–75°; heads that cover the tip
    (:func:`head_covers_tip`, as ``betv layout`` draws them): discs of radius r_min to
    r_min + 25 µm, a fifth of them boxes as wide as the tip and 10–50 µm long.
    """
    rng = np.random.default_rng(seed)
    out = []
    um = 1e-6
    for _ in range(n):
        length = rng.uniform(100, 400) * um
        wh = rng.uniform(2, 4) * um
        wf = rng.uniform(2, 4) * um
        lf = max(rng.uniform(0.1, 0.4) * length, 10 * wf)
        box = rng.uniform() < 0.2
        wc, gap, lt = rng.uniform(6, 20) * um, rng.uniform(2, 5) * um, rng.uniform(5, 15) * um
        height = wh + gap + wc
        r_min = (height**2 / 4 + lt**2 / 4) / lt * 1.01 + 0.05 * um
        hx = rng.uniform(5, 25) * um if box else r_min + rng.uniform(0, 25) * um
        g = FrameGeometry(
            length=length,
            hot_width=wh,
            cold_width=wc,
            flexure_length=lf,
            flexure_width=wf,
            gap=gap,
            tip_length=lt,
            thickness=rng.uniform(1.5, 3) * um,
            youngs_modulus=rng.uniform(150, 170) * 1e9,
            head_x=hx,
            head_y=height / 2 if box else hx,
            head_shape="box" if box else "disc",
        )
        out.append((g, math.radians(rng.uniform(15, 75))))
    return out
