"""Finite-element check of the head's springs: plane stress on the drawn polygons.

The independent model of :mod:`betvdesign.model.frame`'s closed form: the same drawn
shape (:func:`betvdesign.model.frame.shape`: arms, flexure, tip connector and head, in
the actuator's own frame) meshed on a tensor grid through every drawn edge, cells kept
where their centre lies in a drawn polygon (the head's disc is rasterised by them),
biquadratic Lagrange elements (Q2, 9 nodes; no shear locking), linear plane-stress
elasticity with the layer's E, ν and thickness t:

    σ = E/(1 − ν²)·((1 − ν)·ε + ν·tr(ε)·I),   t·∫ σ(u) : ε(v) dA = ∫_head f·v dA,

clamped on the arms' anchor edge x = 0. Each unit load is spread uniformly over the head
and the head's mean displacement is its work-conjugate, so the 2×2 compliance at the head
is C_ij = b_jᵀ K⁻¹ b_i (symmetric) and its inverse the stiffness compared with the closed
form. Nothing is assumed rigid here: the connector, the head, the arm roots and the
joints deform, and shear deformation is in; the difference from the closed form is the
error of its Euler–Bernoulli-frame assumptions plus the discretisation error, which
:func:`converged` removes by Richardson extrapolation over two meshes.

Requires scikit-fem (``pip install 'betvdesign[fe]'``), imported when a model is solved.
Internally lengths are in µm and forces in µN, so stiffnesses come out in N/m.
"""

from __future__ import annotations

import itertools
import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from betvdesign.errors import BetvError
from betvdesign.model.frame import FrameGeometry, FrameStiffness, Rect, shape

__all__ = [
    "FeModes",
    "FeResult",
    "converged",
    "frame_fe",
    "frame_modes",
    "plane_stress_modes",
    "plane_stress_stiffness",
]

_UM = 1e6


@dataclass(frozen=True)
class FeResult:
    """Stiffness at the load [N/m] in the actuator's frame, with the mesh's size."""

    stiffness: FrameStiffness
    cells: int
    dofs: int
    elapsed_s: float


def _skfem():
    try:
        import skfem
    except ImportError:
        raise BetvError(
            "the finite-element check needs scikit-fem: pip install 'betvdesign[fe]'"
        ) from None
    return skfem


def _breaks(
    edges: Sequence[float], h: float, fine: Sequence[tuple[float, float, float]] = ()
) -> np.ndarray:
    """Grid lines: every edge, each interval split into pieces no longer than h, or than
    the band's own size inside a ``fine`` band (lo, hi, size): the arms."""
    e = np.unique(np.round(np.asarray(edges, dtype=float), 9))
    out = [e[:1]]
    for a, b in itertools.pairwise(e):
        m = (a + b) / 2
        step = min([h] + [hb for lo, hi, hb in fine if lo <= m <= hi])
        n = max(1, math.ceil((b - a) / step - 1e-9))
        out.append(np.linspace(a, b, n + 1)[1:])
    return np.concatenate(out)


def _assemble(
    rects: Sequence[Rect],
    discs: Sequence[tuple[float, float, float]],
    youngs_modulus: float,
    poisson_ratio: float,
    thickness: float,
    h_across: float,
    h_along: float,
    fine: Sequence[tuple[float, float, float]] | None,
) -> tuple:
    """The mesh of the drawn body (module doc), its Q2 vector basis and stiffness matrix."""
    skfem = _skfem()
    from skfem.helpers import ddot, sym_grad, trace

    xs_e = [r.x0 for r in rects] + [r.x1 for r in rects]
    ys_e = [r.y0 for r in rects] + [r.y1 for r in rects]
    for cx, cy, r in discs:
        xs_e += [cx - r, cx + r]
        ys_e += [cy - r, cy + r]
    xs = _breaks(np.array(xs_e) * _UM, h_along * _UM)
    if fine is None:
        ys = _breaks(np.array(ys_e) * _UM, h_across * _UM)
    else:
        bands = [(lo * _UM, hi * _UM, hb * _UM) for lo, hi, hb in fine]
        ys = _breaks(np.array(ys_e) * _UM, h_along * _UM, bands)
    mesh = skfem.MeshQuad.init_tensor(xs, ys)
    c = mesh.p[:, mesh.t].mean(axis=1)
    inside = np.zeros(c.shape[1], dtype=bool)
    for r in rects:
        inside |= (
            (c[0] > r.x0 * _UM) & (c[0] < r.x1 * _UM) & (c[1] > r.y0 * _UM) & (c[1] < r.y1 * _UM)
        )
    for cx, cy, r in discs:
        inside |= (c[0] - cx * _UM) ** 2 + (c[1] - cy * _UM) ** 2 < (r * _UM) ** 2
    mesh = mesh.remove_elements(np.nonzero(~inside)[0])
    e = skfem.ElementVector(skfem.ElementQuad2())
    basis = skfem.Basis(mesh, e, intorder=4)
    E = youngs_modulus / 1e6  # µN/µm²
    nu = poisson_ratio
    t = thickness * _UM

    @skfem.BilinearForm
    def stiffness(u, v, w):
        eu, ev = sym_grad(u), sym_grad(v)
        sig = E / (1 - nu**2) * ((1 - nu) * eu + nu * trace(eu) * np.eye(2)[:, :, None, None])
        return t * ddot(sig, ev)

    K = stiffness.assemble(basis)
    return mesh, basis, K


def plane_stress_stiffness(
    rects: Sequence[Rect],
    discs: Sequence[tuple[float, float, float]],
    *,
    youngs_modulus: float,
    poisson_ratio: float,
    thickness: float,
    load: Callable[[np.ndarray, np.ndarray], np.ndarray] | None,
    clamp_x: float = 0.0,
    traction_x: float | None = None,
    guided: bool = False,
    h_across: float,
    h_along: float,
    fine: Sequence[tuple[float, float, float]] | None = None,
) -> FeResult:
    """The 2×2 stiffness [N/m] at a loaded region of a plane-stress body (module doc).

    rects, discs: the body, in m (discs as (cx, cy, r)); load: a predicate on cell
    centres (µm) choosing the loaded cells (body load, mean displacement), or None to
    load the end face x = ``traction_x`` [m] with a uniform traction instead (the
    textbook cantilever); guided: that end face also keeps u_x = 0 (a guided end);
    clamp_x: the clamped edge [m]; h_across / h_along: largest cell size across (y) and
    along (x) [m]; fine: y-bands (lo, hi, size) [m] with their own cell size across
    (h_across everywhere when None; outside the bands cells are h_along square).
    """
    skfem = _skfem()
    from scipy.sparse.linalg import splu

    t0 = time.perf_counter()
    mesh, basis, K = _assemble(rects, discs, youngs_modulus, poisson_ratio, thickness,
                               h_across, h_along, fine)  # fmt: skip
    e = basis.elem
    clamped = basis.get_dofs(lambda x: np.isclose(x[0], clamp_x * _UM, atol=1e-6)).all()
    fixed = [clamped]
    if load is None:
        assert traction_x is not None
        xe = traction_x * _UM
        facets = mesh.facets_satisfying(lambda x: np.isclose(x[0], xe, atol=1e-6))
        fb = skfem.FacetBasis(mesh, e, facets=facets, intorder=4)
        area = float(np.sum(fb.dx))
        loads = [skfem.LinearForm(lambda v, w, k=k: v[k]).assemble(fb) / area for k in (0, 1)]
        if guided:
            end = basis.get_dofs(lambda x: np.isclose(x[0], xe, atol=1e-6))
            fixed.append(end.all(["u^1"]))
    else:
        cc = mesh.p[:, mesh.t].mean(axis=1)
        head = np.nonzero(load(cc[0], cc[1]))[0]
        if head.size == 0:
            raise BetvError("finite-element model: no mesh cell in the loaded region")
        hb = skfem.Basis(mesh, e, elements=head, intorder=4)
        area = float(np.sum(hb.dx))
        loads = [skfem.LinearForm(lambda v, w, k=k: v[k]).assemble(hb) / area for k in (0, 1)]
    fixed_dofs = np.unique(np.concatenate(fixed))
    free = np.setdiff1d(np.arange(basis.N), fixed_dofs)
    lu = splu(K[free][:, free].tocsc())
    C = np.empty((2, 2))
    for i in range(2):
        u = lu.solve(loads[i][free])
        for j in range(2):
            C[j, i] = loads[j][free] @ u
    if guided:  # the end cannot move along x: only the transverse stiffness exists
        Kh = np.array([[math.nan, 0.0], [0.0, 1.0 / C[1, 1]]])
    else:
        Kh = np.linalg.inv(0.5 * (C + C.T))
    return FeResult(
        FrameStiffness(float(Kh[0, 0]), float(Kh[1, 1]), float(Kh[0, 1])),
        int(mesh.t.shape[1]),
        int(basis.N),
        time.perf_counter() - t0,
    )


@dataclass(frozen=True)
class FeModes:
    """The lowest in-plane natural frequencies [Hz] of a plane-stress body, with the
    mesh's size."""

    frequencies_hz: tuple[float, ...]
    cells: int
    dofs: int
    elapsed_s: float


def _lump_mass(
    M: Any,
    mass: Any,
    mesh: Any,
    basis: Any,
    region: Callable[[np.ndarray, np.ndarray], np.ndarray],
    lumped_mass: float,
    density: float,
    what: str,
) -> Any:
    """M with the mass of the cells whose centres lie in ``region`` replaced.

    The consistent mass of those cells (``density`` per unit area or volume of the mesh,
    kg/µm² or kg/µm³) becomes ``lumped_mass`` [kg] spread uniformly over them; ``what``
    names the region in the error raised when no cell lies in it.
    """
    skfem = _skfem()
    cc = mesh.p[:, mesh.t].mean(axis=1)
    cells = np.nonzero(region(cc[0], cc[1]))[0]
    if cells.size == 0:
        raise BetvError(f"finite-element model: no mesh cell in {what}")
    hb = skfem.Basis(mesh, basis.elem, elements=cells, intorder=4)
    measure = float(np.sum(hb.dx))
    return M + mass.assemble(hb) * (lumped_mass / measure - density)


def plane_stress_modes(
    rects: Sequence[Rect],
    discs: Sequence[tuple[float, float, float]],
    *,
    youngs_modulus: float,
    poisson_ratio: float,
    thickness: float,
    density: float,
    lumped: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None,
    lumped_mass: float = 0.0,
    clamp_x: float = 0.0,
    h_across: float,
    h_along: float,
    fine: Sequence[tuple[float, float, float]] | None = None,
    count: int = 1,
) -> FeModes:
    """The ``count`` lowest natural frequencies [Hz] of the plane-stress body of
    :func:`plane_stress_stiffness` (same mesh, elements and clamp), from K·φ = ω²·M·φ with
    the consistent mass matrix M = ρ·t·∫ φ·ψ dA (shift-invert Lanczos about 0).

    density: the body's [kg/m³]; lumped, lumped_mass: the cells (a predicate on their
    centres, µm) whose mass is replaced by ``lumped_mass`` [kg] spread uniformly over
    them (the head: its mass the model's m, whatever the film's density)."""
    skfem = _skfem()
    from scipy.sparse.linalg import eigsh
    from skfem.helpers import dot

    t0 = time.perf_counter()
    mesh, basis, K = _assemble(rects, discs, youngs_modulus, poisson_ratio, thickness,
                               h_across, h_along, fine)  # fmt: skip
    t = thickness * _UM
    rho = density * 1e-18  # kg/µm³

    @skfem.BilinearForm
    def mass(u, v, w):
        return dot(u, v)

    M = mass.assemble(basis) * (rho * t)
    if lumped is not None:
        M = _lump_mass(M, mass, mesh, basis, lumped, lumped_mass, rho * t, "the lumped-mass region")
    clamped = basis.get_dofs(lambda x: np.isclose(x[0], clamp_x * _UM, atol=1e-6)).all()
    free = np.setdiff1d(np.arange(basis.N), clamped)
    w2 = eigsh(K[free][:, free].tocsc(), k=count, M=M[free][:, free].tocsc(), sigma=0.0,
               which="LM", return_eigenvectors=False)  # fmt: skip
    f = tuple(float(x) for x in np.sort(np.sqrt(np.abs(w2)) / (2 * math.pi)))
    return FeModes(f, int(mesh.t.shape[1]), int(basis.N), time.perf_counter() - t0)


def _frame_body(
    g: FrameGeometry, level: int
) -> tuple[list[Rect], list, Callable[[np.ndarray, np.ndarray], np.ndarray], dict]:
    """The drawn actuator's polygons for the FE, the head's cells and the mesh sizes."""
    rects, (cx, cy, hx, hy, kind) = shape(g)
    body = [r for r in rects if not r.name.startswith("anchor")]
    w_min = float(min(g.hot_width, g.flexure_width, g.cold_width, g.gap))
    h = w_min / (4 * 2 ** (level - 1))
    if kind == "disc":
        discs = [(cx, cy, hx)]

        def head(x: np.ndarray, y: np.ndarray) -> np.ndarray:
            return (x - cx * _UM) ** 2 + (y - cy * _UM) ** 2 < (hx * _UM) ** 2

    else:
        discs = []
        box = Rect("head", cx - hx, cy - hy, cx + hx, cy + hy)
        body.append(box)

        def head(x: np.ndarray, y: np.ndarray) -> np.ndarray:
            return (x > box.x0 * _UM) & (x < box.x1 * _UM) & (y > box.y0 * _UM) & (y < box.y1 * _UM)

    sizes = {
        "h_across": h,
        "h_along": 4 * h,
        "fine": [
            (r.y0, r.y1, (r.y1 - r.y0) / (4 * 2 ** (level - 1)))
            for r in body
            if r.name in ("hot_arm", "flexure", "cold_arm")
        ],
    }
    return body, discs, head, sizes


def frame_modes(
    g: FrameGeometry,
    *,
    density: float,
    head_mass: float,
    poisson_ratio: float = 0.22,
    level: int = 1,
    count: int = 1,
) -> FeModes:
    """The drawn actuator's lowest in-plane natural frequencies [Hz] (plane stress, the
    mesh of :func:`frame_fe` at ``level``): the film of ``density`` [kg/m³], the head's
    cells carrying ``head_mass`` [kg], clamped at the anchors' edge x = 0."""
    body, discs, head, sizes = _frame_body(g, level)
    return plane_stress_modes(
        body,
        discs,
        youngs_modulus=float(g.youngs_modulus),
        poisson_ratio=poisson_ratio,
        thickness=float(g.thickness),
        density=density,
        lumped=head,
        lumped_mass=head_mass,
        count=count,
        **sizes,
    )


def frame_modes_3d(
    g: FrameGeometry,
    *,
    density: float,
    head_mass: float,
    poisson_ratio: float = 0.22,
    level: int = 1,
    count: int = 4,
) -> tuple[FeModes, tuple[float, ...]]:
    """The drawn actuator's lowest natural frequencies [Hz] as a 3-D solid: the mesh of
    :func:`frame_modes` extruded through the film (one triquadratic hexahedron, 27
    nodes, through the thickness: bending through it is exact), isotropic linear
    elasticity, consistent mass, the head's cells carrying ``head_mass``, clamped at
    x = 0. Returns the modes and, for each, the share of its kinetic energy out of the
    plane (z): near 1 for an out-of-plane mode, near 0 for an in-plane one."""
    skfem = _skfem()
    from scipy.sparse.linalg import eigsh
    from skfem.helpers import ddot, dot, sym_grad, trace

    t0 = time.perf_counter()
    body, discs, head, sizes = _frame_body(g, level)
    mesh2, _, _ = _assemble(body, discs, float(g.youngs_modulus), poisson_ratio,
                            float(g.thickness), sizes["h_across"], sizes["h_along"],
                            sizes["fine"])  # fmt: skip
    t = float(g.thickness) * _UM
    xs = np.unique(mesh2.p[0])
    ys = np.unique(mesh2.p[1])
    mesh = skfem.MeshHex.init_tensor(xs, ys, np.array([0.0, t]))
    c3 = mesh.p[:, mesh.t].mean(axis=1)
    c2 = mesh2.p[:, mesh2.t].mean(axis=1)
    keep = {(round(a, 6), round(b, 6)) for a, b in zip(c2[0], c2[1], strict=True)}
    inside = np.array([(round(a, 6), round(b, 6)) in keep for a, b in zip(c3[0], c3[1],
                                                                       strict=True)])  # fmt: skip
    mesh = mesh.remove_elements(np.nonzero(~inside)[0])
    basis = skfem.Basis(mesh, skfem.ElementVector(skfem.ElementHex2()), intorder=4)
    E = float(g.youngs_modulus) / 1e6
    nu = poisson_ratio
    lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
    rho = density * 1e-18

    @skfem.BilinearForm
    def stiffness(u, v, w):
        eu, ev = sym_grad(u), sym_grad(v)
        return 2 * mu * ddot(eu, ev) + lam * trace(eu) * trace(ev)

    @skfem.BilinearForm
    def mass(u, v, w):
        return dot(u, v)

    K = stiffness.assemble(basis)
    M = mass.assemble(basis) * rho
    M = _lump_mass(M, mass, mesh, basis, head, head_mass, rho, "the head")
    clamped = basis.get_dofs(lambda x: np.isclose(x[0], 0.0, atol=1e-6)).all()
    free = np.setdiff1d(np.arange(basis.N), clamped)
    Mf = M[free][:, free].tocsc()
    w2, vec = eigsh(K[free][:, free].tocsc(), k=count, M=Mf, sigma=0.0, which="LM")
    order = np.argsort(w2)
    zdofs = np.zeros(basis.N, dtype=bool)
    zdofs[basis.nodal_dofs[2]] = True
    zdofs[basis.facet_dofs[2]] = True if basis.facet_dofs.size else False
    zdofs[basis.edge_dofs[2]] = True if basis.edge_dofs.size else False
    zdofs[basis.interior_dofs[2]] = True if basis.interior_dofs.size else False
    zf = zdofs[free]
    shares = []
    for k in order:
        v = vec[:, k]
        Mv = Mf @ v
        shares.append(float((v[zf] @ Mv[zf]) / (v @ Mv)))
    f = tuple(float(x) for x in np.sqrt(np.abs(w2[order])) / (2 * math.pi))
    modes = FeModes(f, int(mesh.t.shape[1]), int(basis.N), time.perf_counter() - t0)
    return modes, tuple(shares)


def frame_fe(g: FrameGeometry, *, poisson_ratio: float = 0.22, level: int = 1) -> FeResult:
    """The plane-stress FE stiffness of the actuator ``g`` at its head (module doc).

    level: mesh refinement; level 1 puts 4 cells across each arm and the flexure, cells
    along the arms (and everywhere else) at most 4 times the narrowest arm's cell; each
    level halves both.
    """
    body, discs, head, sizes = _frame_body(g, level)
    return plane_stress_stiffness(
        body,
        discs,
        youngs_modulus=float(g.youngs_modulus),
        poisson_ratio=poisson_ratio,
        thickness=float(g.thickness),
        load=head,
        **sizes,
    )


def converged(
    g: FrameGeometry, *, poisson_ratio: float = 0.22, levels: tuple[int, int] = (1, 2)
) -> tuple[FrameStiffness, FeResult, FeResult]:
    """Richardson extrapolation of :func:`frame_fe` over two mesh levels (h and h/2):
    K ≈ K_fine + (K_fine − K_coarse)/(2^p − 1) with p = 2 (the energy-norm order of Q2
    elements around the re-entrant corners' singularities is lower than their smooth 4;
    2 is the conservative choice). Returns the extrapolated stiffness and both runs."""
    a = frame_fe(g, poisson_ratio=poisson_ratio, level=levels[0])
    b = frame_fe(g, poisson_ratio=poisson_ratio, level=levels[1])
    f = 1.0 / (2**2 - 1)
    ka, kb = a.stiffness, b.stiffness
    k = FrameStiffness(
        kb.k_xx + (kb.k_xx - ka.k_xx) * f,
        kb.k_yy + (kb.k_yy - ka.k_yy) * f,
        kb.k_xy + (kb.k_xy - ka.k_xy) * f,
    )
    return k, a, b
