"""Finite-element check of the electrothermal model: the drawn plane, σ(T) iterated.

The independent model of :mod:`betvdesign.model.electrothermal` (1-D fins on the
current's path, closed form): the same drawn polygons and tensor mesh as the springs' FE
(:mod:`betvdesign.model.frame_fe`, biquadratic Lagrange elements), unknowns in the plane,
lengths in µm:

1. **electric potential** φ: ∇·(σ(T)·t·∇φ) = 0, σ = 1/(ρ_0·(1 + ξ·θ)), φ = V on the hot
   arm's anchor edge (x = 0), 0 on the flexure's;
2. **Joule heating** q = t·σ·|∇φ|² per unit area;
3. **heat**: −∇·(k·t·∇θ) + g_s·θ = q in the body, −k·t·∂θ/∂n = g_s·(t/2 + t_v)·θ on
   every free edge (the Lin & Chiao shape factor's fringe, per unit length of outline:
   the 1-D model's S·w = w + t + 2·t_v spread over the drawn outline), θ = 0 on the
   anchor edges; (1) → (3) repeated until the temperature changes by less than
   ``rtol`` (Picard; bounded, its failure reported);
4. **thermal strain** in plane stress: σ = D·(ε − ε_th·I), ε_th(T) of the material's
   α(T) (:func:`betvdesign.model.electrothermal.thermal_strain`), clamped at x = 0; the
   head's mean displacement is the stroke.

Nothing is one-dimensional or rigid here: the current crowds at the tip's corners, the
tip and the head conduct and deform, the arms expand across their width too.

**Transient.** With the source of the converged steady state held fixed and the
passive operator (as the 1-D modes), C·θ' + K·θ = q from θ = 0 (consistent heat
capacity ρ·c·t, backward Euler in ``steps`` steps of equal length): the stroke's step
response u(t) = wᵀθ(t) (w the stroke per nodal temperature at the steady α(T), from the
adjoint of the elastic problem) and its 63.2 % rise time; and the first generalized
eigenvalue K·φ = λ·C·φ (τ_1 = 1/λ_1).

Requires scikit-fem (``pip install 'betvdesign[fe]'``).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from betvdesign.errors import BetvError
from betvdesign.model.electrothermal import (
    ThermalMaterial,
    expansion_coefficient,
    thermal_strain,
)
from betvdesign.model.frame import FrameGeometry
from betvdesign.model.frame_fe import _assemble, _frame_body, _skfem

__all__ = ["ElectrothermalFe", "converged", "electrothermal_fe"]

_UM = 1e6


@dataclass(frozen=True)
class ElectrothermalFe:
    """The FE's answers (SI) with the mesh's size and the iteration's count.

    Attributes
    ----------
    current, power, resistance : float
        I [A], P [W], R = V/I [Ω].
    u_static : float
        The head's mean displacement along the stroke (+y) [m].
    t_max : float
        Largest nodal temperature [K]; t_max_position its (x, y) [m].
    tau_first : float
        1/λ_1 of the heat operator [s] (None when not asked).
    t_rise : float
        63.2 % rise time of the stroke's step response [s] (None when not asked).
    iterations : int
        Picard iterations.
    converged : bool
        Whether the Picard iteration met its tolerance.
    cells, dofs : int
        Mesh cells and scalar degrees of freedom.
    elapsed_s : float
        Wall time [s].
    """

    current: float
    power: float
    resistance: float
    u_static: float
    t_max: float
    t_max_position: tuple[float, float]
    tau_first: float | None
    t_rise: float | None
    iterations: int
    converged: bool
    cells: int
    dofs: int
    elapsed_s: float


def electrothermal_fe(
    g: FrameGeometry,
    mat: ThermalMaterial,
    voltage: float,
    *,
    poisson_ratio: float = 0.22,
    level: int = 1,
    transient: bool = False,
    steps: int = 800,
    rtol: float = 1e-10,
    max_iterations: int = 100,
) -> ElectrothermalFe:
    """The plane FE of the actuator ``g`` at a DC ``voltage`` [V] (module doc).

    Parameters
    ----------
    g : FrameGeometry
        The drawn actuator (scalar floats).
    mat : ThermalMaterial
        The film's and gap's data.
    voltage : float
        V across the anchors [V], > 0.
    poisson_ratio : float
        ν of the film [-].
    level : int
        Mesh level of :func:`betvdesign.model.frame_fe.frame_fe` (each level halves the
        cells).
    transient : bool
        Also the first thermal eigenvalue and the stroke's step response.
    steps : int
        Backward-Euler steps over 6 first-mode time constants.
    rtol : float
        Picard tolerance on the largest temperature change, relative to the peak rise.
    max_iterations : int
        Picard iterations at most.

    Returns
    -------
    ElectrothermalFe
        The FE's current, power, stroke, peak temperature (and the transient's).
    """
    skfem = _skfem()
    from scipy.sparse.linalg import splu
    from skfem.helpers import dot, grad

    t0 = time.perf_counter()
    body, discs, head, sizes = _frame_body(g, level)
    E, nu, t = float(g.youngs_modulus), poisson_ratio, float(g.thickness)
    mesh, vbasis, Kel = _assemble(body, discs, E, nu, t, sizes["h_across"], sizes["h_along"],
                                  sizes["fine"])  # fmt: skip
    sb = skfem.Basis(mesh, skfem.ElementQuad2(), intorder=4)
    tu = t * _UM
    k = mat.conductivity * 1e-6  # W/(µm·K)
    gs = mat.substrate_conductance * 1e-12  # W/(µm²·K)
    edge = gs * (t / 2 + mat.air_gap) * _UM  # W/(µm·K) per µm of outline
    rho0 = mat.resistivity * _UM  # Ω·µm
    T0 = mat.substrate_temperature

    wh, d, wf = float(g.hot_width), float(g.d), float(g.flexure_width)
    anchor = sb.get_dofs(lambda x: np.isclose(x[0], 0.0, atol=1e-6)).all()
    loc = sb.doflocs[:, anchor]
    hot = anchor[loc[1] < (wh / 2 + 1e-9) * _UM]
    cold = anchor[loc[1] > (d - wf / 2 - 1e-9) * _UM]
    if hot.size == 0 or cold.size == 0:
        raise BetvError("electrothermal FE: no anchor edge found at x = 0")
    free = np.setdiff1d(np.arange(sb.N), anchor)
    bf = mesh.boundary_facets()
    mid = mesh.p[:, mesh.facets[:, bf]].mean(axis=1)
    fb = skfem.FacetBasis(mesh, sb.elem, facets=bf[mid[0] > 1e-6], intorder=4)

    @skfem.BilinearForm
    def lap(u, v, w):
        return w.c * dot(grad(u), grad(v))

    @skfem.BilinearForm
    def mass(u, v, w):
        return u * v

    @skfem.LinearForm
    def source(v, w):
        return w.q * v

    Kth = lap.assemble(sb, c=k * tu) + gs * mass.assemble(sb) + edge * mass.assemble(fb)
    lu_th = splu(Kth[free][:, free].tocsc())
    theta = np.zeros(sb.N)
    ok = False
    it = 0
    for it in range(1, max_iterations + 1):  # noqa: B007
        th_q = np.asarray(sb.interpolate(theta))
        sigma = 1 / (rho0 * (1 + mat.tcr * th_q))
        if np.any(sigma <= 0):
            break
        Kv = lap.assemble(sb, c=sigma * tu)
        phi = np.zeros(sb.N)
        phi[hot] = voltage
        rhs = -Kv[free][:, hot] @ phi[hot]
        phi[free] = splu(Kv[free][:, free].tocsc()).solve(rhs)
        gphi = sb.interpolate(phi).grad
        q = sigma * tu * (gphi[0] ** 2 + gphi[1] ** 2)
        Q = source.assemble(sb, q=q)
        new = np.zeros(sb.N)
        new[free] = lu_th.solve(Q[free])
        change = np.max(np.abs(new - theta))
        theta = new
        if change <= rtol * max(np.max(np.abs(theta)), 1e-300):
            ok = True
            break
    power = float(np.sum(Q))  # ∫ q dA, W
    current = power / voltage
    # thermal strain in plane stress: f = ∫ t·E/(1 − ν)·ε_th·div v dA
    Eu = E / 1e6  # µN/µm²

    @skfem.LinearForm
    def thermal(v, w):
        return tu * Eu / (1 - nu) * w.eps * (v.grad[0][0] + v.grad[1][1])

    Tq = T0 + np.asarray(sb.interpolate(theta))
    eps = thermal_strain(Tq, T0, mat.expansion)
    fth = thermal.assemble(vbasis, eps=eps)
    clamped = vbasis.get_dofs(lambda x: np.isclose(x[0], 0.0, atol=1e-6)).all()
    vfree = np.setdiff1d(np.arange(vbasis.N), clamped)
    lu_el = splu(Kel[vfree][:, vfree].tocsc())
    u = np.zeros(vbasis.N)
    u[vfree] = lu_el.solve(fth[vfree])
    cc = mesh.p[:, mesh.t].mean(axis=1)
    cells = np.nonzero(head(cc[0], cc[1]))[0]
    hb = skfem.Basis(mesh, vbasis.elem, elements=cells, intorder=4)
    area = float(np.sum(hb.dx))
    by = skfem.LinearForm(lambda v, w: v[1]).assemble(hb) / area
    u_y = float(by @ u) / _UM
    imax = int(np.argmax(theta))
    tau_first = t_rise = None
    if transient:
        from scipy.sparse.linalg import eigsh

        C = mass.assemble(sb) * (mat.density * mat.heat_capacity * 1e-18 * tu)  # J/K
        Kf, Cf = Kth[free][:, free].tocsc(), C[free][:, free].tocsc()
        lam = eigsh(Kf, k=1, M=Cf, sigma=0.0, which="LM", return_eigenvectors=False)
        tau_first = float(1 / lam[0])
        # the stroke per nodal temperature at the steady α(T): w = Bᵀ·z, K_el·z = b_y

        @skfem.BilinearForm
        def coupling(th, v, w):
            return tu * Eu / (1 - nu) * w.alpha * th * (v.grad[0][0] + v.grad[1][1])

        alpha = expansion_coefficient(Tq, mat.expansion)
        B = coupling.assemble(sb, vbasis, alpha=alpha)  # rows: vector dofs
        z = np.zeros(vbasis.N)
        z[vfree] = lu_el.solve(by[vfree])
        wv = (B.T @ z)[free] / _UM
        dt = 6 * tau_first / steps
        lu_be = splu((Cf + dt * Kf).tocsc())
        Qf = Q[free]
        th = np.zeros(free.size)
        u_inf = float(wv @ lu_th.solve(Qf))
        prev_u, prev_t = 0.0, 0.0
        target = (1 - math.exp(-1)) * u_inf
        for n in range(1, steps + 1):
            th = lu_be.solve(Cf @ th + dt * Qf)
            un = float(wv @ th)
            if (un - target) * np.sign(u_inf) >= 0:
                t_rise = prev_t + (target - prev_u) / (un - prev_u) * dt
                break
            prev_u, prev_t = un, n * dt
    return ElectrothermalFe(
        current=current,
        power=power,
        resistance=voltage / current,
        u_static=u_y,
        t_max=float(T0 + theta[imax]),
        t_max_position=(float(sb.doflocs[0, imax] / _UM), float(sb.doflocs[1, imax] / _UM)),
        tau_first=tau_first,
        t_rise=t_rise,
        iterations=it,
        converged=ok,
        cells=int(mesh.t.shape[1]),
        dofs=int(sb.N),
        elapsed_s=time.perf_counter() - t0,
    )


def converged(
    g: FrameGeometry,
    mat: ThermalMaterial,
    voltage: float,
    *,
    poisson_ratio: float = 0.22,
    levels: tuple[int, int] = (1, 2),
    transient: bool = False,
    steps: int = 800,
) -> tuple[dict[str, float], ElectrothermalFe, ElectrothermalFe]:
    """Richardson extrapolation (p = 2, as :func:`betvdesign.model.frame_fe.converged`) of
    current, power, stroke and peak temperature over two mesh levels.

    Parameters
    ----------
    g, mat, voltage, poisson_ratio
        As :func:`electrothermal_fe`.
    levels : tuple of int
        The coarse and the fine level.
    transient, steps
        The coarse level's transient (:func:`electrothermal_fe`).

    Returns
    -------
    tuple
        ({'current', 'power', 'u_static', 't_max'}: extrapolated values, coarse, fine).
    """
    a = electrothermal_fe(g, mat, voltage, poisson_ratio=poisson_ratio, level=levels[0],
                          transient=transient, steps=steps)  # fmt: skip
    b = electrothermal_fe(g, mat, voltage, poisson_ratio=poisson_ratio, level=levels[1])
    f = 1.0 / 3.0
    out = {
        key: getattr(b, key) + (getattr(b, key) - getattr(a, key)) * f
        for key in ("current", "power", "u_static", "t_max")
    }
    return out, a, b
