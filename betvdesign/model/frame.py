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
Q = [[−sinθ, cosθ], [cosθ, sinθ]]. The model's springs are k_v = K_nn, k_h = K_tt; the
coupling ρ = K_nt/√(K_nn·K_tt) is reported (the model has none).

Every function takes floats or numpy arrays (broadcast), SI units.
"""

from __future__ import annotations

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
    "RHO_MAX",
    "FrameGeometry",
    "FrameStiffness",
    "Rect",
    "arm_modal_mass",
    "beam_tip_compliance",
    "frame_stiffness",
    "head_covers_tip",
    "head_disc_diameter",
    "head_radius_min",
    "random_geometries",
    "shape",
    "slider_springs",
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


def slider_springs(k: FrameStiffness, theta_rad: Any) -> tuple[Any, Any, Any]:
    """(K_nn, K_tt, K_nt) [N/m] in the slider's frame at impact angle θ (module doc)."""
    s, c = np.sin(theta_rad), np.cos(theta_rad)
    k_tt = s * s * k.k_xx + c * c * k.k_yy - 2 * s * c * k.k_xy
    k_nn = c * c * k.k_xx + s * s * k.k_yy + 2 * s * c * k.k_xy
    k_nt = -s * c * k.k_xx + s * c * k.k_yy + (c * c - s * s) * k.k_xy
    return k_nn, k_tt, k_nt


def _gauss(n: int = 24) -> tuple[np.ndarray, np.ndarray]:
    x, w = np.polynomial.legendre.leggauss(n)
    return (x + 1) / 2, w / 2


def arm_modal_mass(g: FrameGeometry, density: Any, direction: tuple[Any, Any]) -> Any:
    """The arms' share of the first mode's mass at the head [kg] (Rayleigh estimate).

    The head moves along ``direction`` (a unit vector in the actuator's (x, y)) under a
    load there; the frame's static shape (rigid tip; each arm clamped at its root, its
    transverse deflection the cubic of its tip displacement and rotation, its axial one
    linear) gives the arms' kinetic energy ½·Σ ρ·A ∫ (u² + v²) dx per unit head velocity
    squared along ``direction``, i.e. the mass they add to the head's. The tip connector
    moves with the head (rigid) and counts fully.
    """
    t = g.thickness
    xp, yp = g.head_centre
    dx, dy = direction
    # the rigid tip's (u, v, φ) at P under a unit force along `direction`
    hot = beam_tip_compliance([(g.length, t * g.hot_width, t * g.hot_width**3 / 12)],
                              g.youngs_modulus)  # fmt: skip
    cold = beam_tip_compliance(
        [
            (g.flexure_length, t * g.flexure_width, t * g.flexure_width**3 / 12),
            (g.length - g.flexure_length, t * g.cold_width, t * g.cold_width**3 / 12),
        ],
        g.youngs_modulus,
    )
    Ts = [_transfer(g.length, yb, xp, yp) for yb in (0.0, g.d)]
    K = sum(
        np.swapaxes(T, -1, -2) @ np.linalg.inv(C) @ T for C, T in zip((hot, cold), Ts, strict=True)
    )
    f = np.stack(np.broadcast_arrays(dx, dy, 0.0 * dx), axis=-1)[..., None]
    q = np.linalg.solve(K, f)  # (…, 3, 1)
    along = (q[..., 0, 0] * dx + q[..., 1, 0] * dy) ** 2  # head displacement² along it
    s, w = _gauss()
    total = 0.0
    L = np.asarray(g.length, dtype=float)[..., None]
    for T, widths in (
        (Ts[0], [(0.0, g.length, g.hot_width)]),
        (
            Ts[1],
            [(0.0, g.flexure_length, g.flexure_width), (g.flexure_length, g.length, g.cold_width)],
        ),
    ):
        b = T @ q  # the arm tip's (u, v, φ)
        ub, vb, pb = (b[..., k, 0][..., None] for k in range(3))
        for a0, a1, width in widths:
            a0_, a1_ = (np.asarray(v, dtype=float)[..., None] for v in (a0, a1))
            xi = (a0_ + (a1_ - a0_) * s) / L
            u = ub * xi
            v = vb * (3 * xi**2 - 2 * xi**3) + pb * L * (xi**3 - xi**2)
            seg = np.sum((u**2 + v**2) * w, axis=-1) * (np.asarray(a1) - np.asarray(a0))
            total = total + density * t * width * seg
    tip = density * t * g.tip_length * (g.hot_width + g.gap + g.cold_width)
    return total / along + tip


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
