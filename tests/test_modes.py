"""The drawn actuator's modes and the model's springs from it (issue 30).

Independent truths: a point mass on a massless spring, √(k/m); the Rayleigh quotient of
a cantilever's static tip-load shape, effective mass 33/140 of the beam's (Rayleigh's
textbook value); the cantilever's first mode β₁L = 1.8751 (Euler–Bernoulli) against the
plane-stress modal FE; the fixed–fixed beam under a point load a³b³/(3EIL³) against the
guided/cantilever superposition; the modal FE of the drawn actuators against the
Rayleigh–Ritz closed form within MODAL_RTOL.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

from betvdesign.model.frame import (
    MODAL_RTOL,
    FrameGeometry,
    Rect,
    _segmented_shape,
    beam_tip_compliance,
    first_mode,
    frame_stiffness,
    head_compliance,
    out_of_plane_first_mode,
    random_geometries,
    rayleigh_matrices,
    slider_point_compliance,
    slider_springs,
    torsion_constant,
)
from betvdesign.nondim.device import derive
from betvdesign.spec.loader import load_device_text

DEVICES = Path(__file__).resolve().parents[1] / "devices"
E, T, RHO = 160e9, 2e-6, 2330.0
SHIN = FrameGeometry(200e-6, 2.5e-6, 14e-6, 40e-6, 2.5e-6, 3e-6, 10e-6, T, E, 13.75e-6)


def test_point_mass_on_a_massless_spring():
    """Massless arms and tip, a point head: the first mode is √(k_min/m), k_min the
    head's softest stiffness, to round-off."""
    g = FrameGeometry(200e-6, 2.5e-6, 14e-6, 40e-6, 2.5e-6, 3e-6, 10e-6, T, E, 1e-12)
    m = 1e-12
    C, M = rayleigh_matrices(g, 0.0, m)
    f, _ = first_mode(C, M)
    k = frame_stiffness(g)
    k_min = np.linalg.eigvalsh(np.array([[k.k_xx, k.k_xy], [k.k_xy, k.k_yy]], dtype=float))[0]
    assert float(f) == pytest.approx(math.sqrt(k_min / m) / (2 * math.pi), rel=1e-9)


@pytest.mark.parametrize("cut", [None, 0.3])
def test_cantilever_static_shape_gives_rayleighs_33_over_140(cut):
    """The static shape of a cantilever under a tip load: ∫v² dx = (33/140)·L·v_tip²."""
    L, w = 150e-6, 3e-6
    A, inertia = T * w, T * w**3 / 12
    segs = (
        [(0.0, L, A, inertia)]
        if cut is None
        else [(0.0, cut * L, A, inertia), (cut * L, L, A, inertia)]
    )
    C = beam_tip_compliance([(L, A, inertia)], E)
    tip = C @ np.array([0.0, 1.0, 0.0])  # the tip's (u, v, φ) under a unit transverse load
    from betvdesign.model.frame import _gauss

    _, wq = _gauss()
    total = sum(np.sum(v**2 * wq) * (x1 - x0) for x0, x1, _, v in _segmented_shape(segs, L, tip, E))
    assert total == pytest.approx(33 / 140 * L * tip[1] ** 2, rel=1e-12)


def test_fixed_fixed_point_load_is_the_superposition():
    """Roark 8.1 1d against an independent derivation: the fixed–fixed beam is the two
    cantilevers a and b meeting at the load, their ends' deflection and slope equal."""
    L, w, a = 170e-6, 5e-6, 40e-6
    inertia = T * w**3 / 12
    c_n, c_t = slider_point_compliance(L, w, T, E, a, 2)
    Ca = beam_tip_compliance([(a, T * w, inertia)], E)[1:, 1:]
    Cb = beam_tip_compliance([(L - a, T * w, inertia)], E)[1:, 1:]
    Cb = Cb * np.array([[1, -1], [-1, 1]])  # the second one points the other way
    # the load point (v, φ) is held by both: stiffnesses add
    K = np.linalg.inv(Ca) + np.linalg.inv(Cb)
    assert c_n == pytest.approx(np.linalg.inv(K)[0, 0], rel=1e-12)
    assert c_t == pytest.approx(1 / (E * T * w / a + E * T * w / (L - a)), rel=1e-12)
    assert slider_point_compliance(L, w, T, E, a, 1)[0] == 0.0


def test_compliance_is_the_inverse_of_the_slider_frame_stiffness():
    th = math.radians(30)
    c = np.array(head_compliance(frame_stiffness(SHIN), th), dtype=float)
    k = np.array(slider_springs(frame_stiffness(SHIN), th), dtype=float)
    C = np.array([[c[0], c[2]], [c[2], c[1]]])
    K = np.array([[k[0], k[2]], [k[2], k[1]]])
    np.testing.assert_allclose(C @ K, np.eye(2), atol=1e-9)
    # each direction with the other free is far softer than with it clamped (|ρ| ≈ 1)
    assert 1 / c[0] < k[0] / 100


def test_torsion_constant_is_roarks_square_and_thin_strip():
    """A square: J = 0.1406·a⁴ (Roark Table 10.7 case 4; Timoshenko & Goodier 0.1406); a
    thin strip h·k³/3 as k/h → 0."""
    assert torsion_constant(1.0, 1.0) == pytest.approx(0.1406, abs=3e-4)
    assert torsion_constant(1e4, 1.0) / (1e4 / 3) == pytest.approx(1.0, rel=1e-4)
    assert torsion_constant(2.0, 5.0) == torsion_constant(5.0, 2.0)


def test_out_of_plane_point_mass_on_the_frame():
    """Massless arms and tip, a point head: √(k_z/m) with k_z the frame's out-of-plane
    stiffness at the head, here two cantilevers bending out of plane (3EI/L³ each, t ≪ w
    so torsion and the tip's lever barely matter): within 2 % of 2·3EI/L³."""
    w = 20e-6
    g = FrameGeometry(300e-6, w, w, 150e-6, w, 2e-6, 1e-9, 0.5e-6, E, 1e-12)
    m = 1e-12
    f = float(out_of_plane_first_mode(g, 0.0, m))
    k = 2 * 3 * E * (w * 0.5e-6**3 / 12) / 300e-6**3
    assert f == pytest.approx(math.sqrt(k / m) / (2 * math.pi), rel=0.02)


fe = pytest.importorskip("betvdesign.model.frame_fe")
pytest.importorskip("skfem")


def test_fe_cantilever_first_mode_is_beta1L():
    """A slender plane-stress cantilever (L/w = 50, ν = 0): β₁L = 1.87510 of
    Euler–Bernoulli, up to shear and rotary inertia (Timoshenko: relative (w/L)² ≈ 4e-4)
    and the mesh."""
    L, w = 100e-6, 2e-6
    res = fe.plane_stress_modes([Rect("beam", 0.0, -w / 2, L, w / 2)], [], youngs_modulus=E,
                                poisson_ratio=0.0, thickness=T, density=RHO, h_across=w / 4,
                                h_along=w, count=1)  # fmt: skip
    inertia = w**3 / 12
    omega = 2 * math.pi * res.frequencies_hz[0]
    beta_l = (omega**2 * RHO * w / (E * inertia)) ** 0.25 * L
    assert beta_l == pytest.approx(1.8751040687, rel=1e-3)
    assert beta_l < 1.8751040687  # shear and rotary inertia only soften it


SHIPPED = [("shin2004", 49.59e-6, 0.036e-9), ("bidir_demo", 13.75e-6, 2.77e-12)]
CASES = [(f"{n}", FrameGeometry(200e-6, 2.5e-6, 14e-6, 40e-6, 2.5e-6, 3e-6, 10e-6, T, E, r), m)
         for n, r, m in SHIPPED]  # fmt: skip
for i, (g, _) in enumerate(random_geometries(50)[:3]):
    hy = g.head_x if g.head_y is None else g.head_y
    area = math.pi * g.head_x**2 if g.head_shape == "disc" else 4 * g.head_x * hy
    CASES.append((f"random{i}", g, float(area * g.thickness * RHO)))


@pytest.mark.parametrize(("name", "g", "m"), CASES, ids=[c[0] for c in CASES])
def test_first_mode_against_modal_fe(name, g, m):
    """The Rayleigh–Ritz first in-plane mode within MODAL_RTOL of the modal FE (level 1;
    benchmarks/bench_modal.py gives all 50 seeded ones and the converged FE)."""
    C, M = rayleigh_matrices(g, RHO, m)
    f_cf = float(first_mode(C, M)[0])
    f_fe = fe.frame_modes(g, density=RHO, head_mass=m, level=1).frequencies_hz[0]
    assert abs(f_cf / f_fe - 1) <= MODAL_RTOL


def _without_resonances(text: str) -> str:
    text = re.sub(r"\n *vertical_resonance: [^\n]*", "", text)
    return re.sub(r"\n *(alpha|horizontal_resonance|horizontal_stiffness): [^\n]*", "", text)


@pytest.mark.parametrize("stem", ["shin2004", "push_demo"])
def test_drawn_resonances_are_the_structures_kilohertz(stem):
    """Without the file's resonances the drawn f_v is of the order of the actuator's own
    first mode (kHz to about 200 kHz, never MHz) and within 10 % of it (|ρ| ≈ 1: one
    mode)."""
    text = _without_resonances((DEVICES / f"{stem}.yaml").read_text())
    for d in derive(load_device_text(text, f"{stem}.yaml")).sets:
        sp = d.springs
        assert 1e3 < sp.f_v_hz < 2e5 and 1e3 < sp.f_h_hz < 2e5
        assert sp.f_v_hz == pytest.approx(sp.f_1_hz, rel=0.1)
        assert d.step("f_v").value.to("Hz").magnitude == pytest.approx(sp.f_v_hz, rel=1e-12)


def _with_resonances(f_v: str, alpha: str) -> str:
    text = (DEVICES / "shin2004.yaml").read_text()
    text = text.replace("vertical_resonance: 2.94 kHz", f"vertical_resonance: {f_v}")
    return re.sub(r"alpha: 0\.1 ", f"alpha: {alpha} ", text)


def test_measured_values_win_with_a_note_within_2x_and_a_warning_beyond():
    from betvdesign.checks.actuator_rules import PREDICTION_FACTOR, actuator_rules

    base = derive(load_device_text(_with_resonances("2.94 kHz", "0.1"), "s.yaml")).sets[0]
    sp = base.springs
    # within 2× of the drawn values: a note (info, passed)
    near = _with_resonances(f"{sp.f_v_hz / 1.9 / 1e3:.6g} kHz", f"{sp.alpha * 1.9:.6g}")
    d = derive(load_device_text(near, "s.yaml")).sets[0]
    r = {x.id: x for x in actuator_rules(d)}["actuator.geometry"]
    assert r.passed and r.severity == "info" and "note" in r.message
    assert d.params.varpi == pytest.approx(1e3 / (sp.f_v_hz / 1.9), rel=1e-5)  # the file's
    # beyond 2×: a warning naming the likely cause
    far = _with_resonances(f"{sp.f_v_hz / 2.1 / 1e3:.6g} kHz", f"{sp.alpha:.6g}")
    r = {x.id: x for x in actuator_rules(derive(load_device_text(far, "s.yaml")).sets[0])}
    g = r["actuator.geometry"]
    assert not g.passed and g.severity == "warning" and "Likely cause: another mode" in g.message
    assert PREDICTION_FACTOR == 2.0


def test_drawn_json_fields_are_null_without_a_drawing():
    text = (DEVICES / "shin2004.yaml").read_text()
    plain = re.sub(r"\n *# The drawn hot/cold[^\n]*\n *# compared[^\n]*", "", text)
    plain = re.sub(r"\n *geometry:\n( {8,}[a-z_]+: [^\n]*\n?)+", "\n", plain)
    keys = {"f_v_hz", "f_h_hz", "k_v_n_m", "k_h_n_m", "m_eff_kg", "coupling", "f_1_hz",
            "f_oop_hz"}  # fmt: skip
    # the stroke predicted from a drawing (issue 31): null where the file gives the stroke
    stroke = {"stroke_m", "u_static_m", "t_max_k", "power_w", "current_a", "resistance_ohm",
              "f_thermal_hz", "f_heat_hz", "stroke_status"}  # fmt: skip
    none = derive(load_device_text(plain, "s.yaml")).sets[0].drawn()
    assert set(none) == keys | stroke and all(v is None for v in none.values())
    d = derive(load_device_text(text, "s.yaml")).sets[0]
    drawn = d.drawn()
    assert set(drawn) == keys | stroke
    assert all(isinstance(drawn[k], float) for k in keys)
    assert all(drawn[k] is None for k in stroke)  # shin2004 gives its amplitude
    assert 1e3 < drawn["f_oop_hz"] < drawn["f_1_hz"]  # the film is thinner than the arms
    assert drawn["f_v_hz"] == pytest.approx(
        math.sqrt(drawn["k_v_n_m"] / drawn["m_eff_kg"]) / (2 * math.pi), rel=1e-12
    )


def test_out_of_plane_mode_against_3d_fe():
    """The first out-of-plane mode within MODAL_RTOL of a 3-D solid FE (27-node
    hexahedra) of the same drawing; its first in-plane mode matches the plane-stress FE
    (a second method) to 0.5 %."""
    g = FrameGeometry(100e-6, 3e-6, 8e-6, 30e-6, 3e-6, 3e-6, 6e-6, T, E, 10e-6)
    m = math.pi * (10e-6) ** 2 * T * RHO
    modes, shares = fe.frame_modes_3d(g, density=RHO, head_mass=m, count=2)
    oop = next(f for f, z in zip(modes.frequencies_hz, shares, strict=True) if z > 0.5)
    inp = next(f for f, z in zip(modes.frequencies_hz, shares, strict=True) if z < 0.5)
    assert abs(float(out_of_plane_first_mode(g, RHO, m)) / oop - 1) <= MODAL_RTOL
    plane = fe.frame_modes(g, density=RHO, head_mass=m).frequencies_hz[0]
    assert inp == pytest.approx(plane, rel=5e-3)


def test_a_spread_head_diameter_derives_as_samples_like_one_by_one():
    """The out-of-plane body mass broadcasts per sample (a spread head diameter used to
    stop the vectorised derivation: shapes (n, 3) and (n,)); each sample equals its own
    scalar derivation."""
    from betvdesign.nondim.device import derive_samples
    from betvdesign.spec.loader import load_device
    from betvdesign.spec.paths import with_values
    from betvdesign.spec.units import ureg

    spec = load_device(DEVICES / "push_demo.yaml")
    ds = np.array([34.0, 35.0, 36.0, 37.0, 38.0])
    arrays = with_values(spec, {"head.geometry.diameter": ureg.Quantity(ds, "um")})
    got = derive_samples(arrays, arrays.actuator_sets[0])
    for j, x in enumerate(ds):
        one = derive(with_values(spec, {"head.geometry.diameter": x * ureg.um})).sets[0]
        assert got.beta[j] == pytest.approx(one.params.beta, rel=1e-12)
        assert got.varpi[j] == pytest.approx(one.params.varpi, rel=1e-12)
