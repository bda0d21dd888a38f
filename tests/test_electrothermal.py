"""The electrothermal stroke (issue 31): textbook closed forms, conservation, the FE check.

Truths used: the fin equation's closed forms (cosh profile, parabola, cos profile), the
free bar's elongation α·ΔT·L, numerical quadrature of α(T), energy conservation of the
steady state, the plane FE of the same physics (:mod:`betvdesign.model.electrothermal_fe`).
"""

from __future__ import annotations

import itertools
import math
import warnings

import numpy as np
import pytest
from scipy.integrate import quad

from betvdesign.model.electrothermal import (
    OKADA_TOKUMARU,
    ThermalMaterial,
    electrothermal,
    expansion_coefficient,
    fin_profile,
    head_node,
    segments,
    stroke_amplitude,
    temperature_profile,
    thermal_gain,
    thermal_strain,
)
from betvdesign.model.frame import FrameGeometry, thermal_displacement
from betvdesign.spec.loader import load_process
from betvdesign.spec.process import shipped_process_path

UM = 1e-6
#: push_demo's drawn actuator (devices/push_demo.yaml) in the demo25 film.
PUSH = FrameGeometry(240 * UM, 3 * UM, 16 * UM, 50 * UM, 3 * UM, 3 * UM, 10 * UM, 2.5 * UM,
                     169e9, 18 * UM)  # fmt: skip


def _material(name: str = "demo25") -> ThermalMaterial:
    path = shipped_process_path(name)
    assert path is not None
    return load_process(path).thermal_material()


# --- textbook closed forms --------------------------------------------------------------
@pytest.mark.parametrize("m2", [4e8, 1e-9, -2e8])
def test_fin_profile_is_the_closed_form(m2):
    """θ'' − m²θ = −s0, θ(0) = θ(l) = 0: s0/m²·(1 − cosh(m(x − l/2))/cosh(ml/2)) (the
    cosh profile), the parabola s0·x(l − x)/2 as m² → 0, the cos profile for m² < 0."""
    length, s0 = 200 * UM, 3e10
    x = np.linspace(0, length, 41)
    got = fin_profile(x, length, m2, s0, 0.0, 0.0)
    if m2 > 1e-3:
        m = math.sqrt(m2)
        want = s0 / m2 * (1 - np.cosh(m * (x - length / 2)) / math.cosh(m * length / 2))
    elif m2 < 0:
        mu = math.sqrt(-m2)
        want = s0 / m2 * (1 - np.cos(mu * (x - length / 2)) / math.cos(mu * length / 2))
    else:
        want = s0 * x * (length - x) / 2
    np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-12 * np.max(np.abs(want)))


def test_fin_profile_end_values_and_equation():
    """End values are kept and the ODE holds (finite differences of the closed form)."""
    length, m2, s0 = 150 * UM, 2.5e8, 1e10
    assert fin_profile(0.0, length, m2, s0, 3.0, 7.0) == pytest.approx(3.0, rel=1e-14)
    assert fin_profile(length, length, m2, s0, 3.0, 7.0) == pytest.approx(7.0, rel=1e-14)
    h = length / 2000
    x = np.linspace(0.2 * length, 0.8 * length, 7)
    th = [fin_profile(x + k * h, length, m2, s0, 3.0, 7.0) for k in (-1, 0, 1)]
    d2 = (th[0] - 2 * th[1] + th[2]) / h**2
    np.testing.assert_allclose(d2 - m2 * th[1], -s0, rtol=1e-6)


def test_free_bar_elongates_alpha_dT_L():
    """A uniformly heated bar: ε = α·ΔT; equal elongations of both arms translate the
    head along the arms by α·ΔT·L with no stroke and no rotation."""
    alpha, dT, L = 2.6e-6, 150.0, PUSH.length
    eps = thermal_strain(300.0 + dT, 300.0, alpha)
    delta = eps * L
    assert delta == pytest.approx(alpha * dT * L, rel=1e-15)
    ux, uy, phi = thermal_displacement(PUSH, delta, delta)
    assert float(ux) == pytest.approx(delta, rel=1e-12)
    assert abs(float(uy)) < 1e-12 * delta
    assert abs(float(phi)) < 1e-12 * delta / PUSH.length


def test_okada_tokumaru_strain_is_the_integral_of_alpha():
    """ε_th(T) in closed form = ∫α(T')dT' by adaptive quadrature; α at 300 K ≈ 2.6e-6/K
    (Okada & Tokumaru's room-temperature value)."""
    for T in (350.0, 800.0, 1400.0):
        want, _ = quad(lambda x: float(expansion_coefficient(x, OKADA_TOKUMARU)), 300.0, T,
                       epsabs=0, epsrel=1e-13)  # fmt: skip
        assert float(thermal_strain(T, 300.0)) == pytest.approx(want, rel=1e-11)
    assert float(expansion_coefficient(300.0)) == pytest.approx(2.59e-6, rel=0.01)


def test_hot_arm_elongation_turns_the_head_toward_the_cold_arm():
    _ux, uy, phi = thermal_displacement(PUSH, 1e-7, 0.0)
    assert float(uy) > 0 and float(phi) > 0


# --- the steady model -------------------------------------------------------------------
def test_energy_is_conserved():
    """Joule power I²R = loss to the substrate along the path + the head's loss + the
    conduction into both anchors (a finite-difference slope of the exact profile)."""
    mat = _material()
    res = electrothermal(PUSH, mat, 5.0)
    prof = temperature_profile(PUSH, mat, res, points=4001)
    segs = segments(PUSH, mat)
    t = float(PUSH.thickness)
    loss = 0.0
    for i, sg in enumerate(segs):
        sel = prof["segment"] == i
        th = prof["t"][sel] - mat.substrate_temperature
        loss += sg.loss * np.trapezoid(th, prof["s"][sel])
    g_head, _ = head_node(PUSH, mat)
    loss += g_head * float(prof["head"])

    def slope(s, th):  # second-order one-sided difference at the first point
        h = s[1] - s[0]
        return (-3 * th[0] + 4 * th[1] - th[2]) / (2 * h)

    th = prof["t"] - mat.substrate_temperature
    first, last = prof["segment"] == 0, prof["segment"] == len(segs) - 1
    k = mat.conductivity
    q0 = k * t * segs[0].width * slope(prof["s"][first], th[first])
    q1 = k * t * segs[-1].width * slope(-prof["s"][last][::-1], th[last][::-1])
    conducted = q0 + q1
    assert res.power == pytest.approx(loss + conducted, rel=2e-5)


def test_voltage_current_resistance_and_peak():
    mat = _material()
    res = electrothermal(PUSH, mat, 4.0)
    assert res.status == "ok"
    assert res.voltage == pytest.approx(res.current * res.resistance, rel=1e-9)
    assert res.power == pytest.approx(res.voltage * res.current, rel=1e-9)
    assert res.resistance > res.resistance_cold  # positive TCR
    prof = temperature_profile(PUSH, mat, res, points=2001)
    assert res.t_max == pytest.approx(prof["t"].max(), rel=1e-6)
    assert res.t_max_segment == "hot arm"
    assert 0 < res.t_max_position[0] < PUSH.length


def test_zero_volts_is_rest():
    res = electrothermal(PUSH, _material(), 0.0)
    assert res.status == "ok"
    assert res.u_static == 0.0 and res.power == 0.0
    assert res.t_max == pytest.approx(300.0)
    assert res.tau_thermal > 0


def test_stroke_grows_with_voltage():
    mat = _material()
    u = [electrothermal(PUSH, mat, v).u_static for v in (1.0, 2.0, 3.0, 4.0)]
    assert all(b > a > 0 for a, b in itertools.pairwise(u))


@pytest.mark.parametrize("volts", [12.0, 100.0, 1e4])
def test_melting_is_reported_never_nan(volts):
    mat = _material()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        res = electrothermal(PUSH, mat, volts)
    assert res.status == "melts"
    assert "melting point" in res.message
    for v in (res.u_static, res.power, res.current, res.t_max, res.tau_thermal):
        assert math.isfinite(v)
    assert res.t_max > mat.melting_temperature


def test_bad_voltage_is_refused():
    with pytest.raises(ValueError, match="voltage"):
        electrothermal(PUSH, _material(), -1.0)
    with pytest.raises(ValueError, match="voltage"):
        electrothermal(PUSH, _material(), math.nan)


# --- dynamics -----------------------------------------------------------------------------
def test_modes_shares_sum_to_one_and_gain_limits():
    res = electrothermal(PUSH, _material(), 3.0)
    assert sum(a for _, a in res.modes) == pytest.approx(1.0, abs=1e-12)
    assert thermal_gain(res, 1e-3) == pytest.approx(1.0, rel=1e-9)
    f = 1e3 * res.f_cutoff  # far above every kept mode: |H| ≈ Σ a_i/(ωτ_i)
    w = 2 * math.pi * f
    assert thermal_gain(res, f) == pytest.approx(abs(sum(a / (w * tau) for tau, a in res.modes)),
                                                 rel=1e-5)  # fmt: skip
    assert thermal_gain(res, res.f_cutoff) == pytest.approx(1 / math.sqrt(2), rel=1e-9)


def test_stroke_amplitude_at_low_and_high_frequency():
    res = electrothermal(PUSH, _material(), 3.0)
    for wf in ("ac", "unipolar", "dc-biased"):
        u, _ = stroke_amplitude(res, 1e-3, wf)
        assert u == pytest.approx(res.u_static / 2, rel=1e-6)
    u_ac, f_ac = stroke_amplitude(res, 3000.0, "ac")
    assert f_ac == 6000.0
    assert u_ac == pytest.approx(res.u_static / 2 * thermal_gain(res, 6000.0), rel=1e-12)
    u_uni, f_uni = stroke_amplitude(res, 3000.0, "unipolar")
    assert f_uni == 3000.0 and u_ac < u_uni < res.u_static / 2
    with pytest.raises(ValueError, match="waveform"):
        stroke_amplitude(res, 1.0, "square")


def test_rise_time_solves_its_equation():
    res = electrothermal(PUSH, _material(), 3.0)
    resp = 1 - sum(a * math.exp(-res.t_rise / tau) for tau, a in res.modes)
    assert resp == pytest.approx(1 - math.exp(-1), abs=1e-10)
    assert 0 < res.t_rise <= res.tau_thermal


# --- process data -----------------------------------------------------------------------
def test_process_data_and_sources():
    path = shipped_process_path("polymumps")
    assert path is not None
    proc = load_process(path)
    mat = proc.thermal_material()
    assert mat.resistivity == pytest.approx(10 * 2e-6)  # 10 ohm/sq at 2 um
    assert "NOT sourced" in proc.cite("layers.poly1.electrothermal.tcr")
    assert "Tai" in proc.cite("layers.poly1.electrothermal.thermal_conductivity")


def test_process_without_data_names_the_field(tmp_path):
    path = shipped_process_path("polymumps")
    assert path is not None
    text = path.read_text("utf-8")
    start = text.index("    electrothermal:")
    end = text.index("  hole1:")
    bare = tmp_path / "bare.yaml"
    text = text[:start] + text[end:]
    text = text.replace("  - layers.poly1.electrothermal.tcr\n", "")
    bare.write_text(text, "utf-8")
    proc = load_process(bare)
    with pytest.raises(ValueError, match=r"layers\.poly1\.electrothermal is missing"):
        proc.thermal_material()


# --- the FE check -------------------------------------------------------------------------
@pytest.mark.slow
def test_closed_form_within_ten_percent_of_fe():
    """push_demo's actuator at 4 V: current, power, stroke and peak temperature of the
    closed form against the plane FE (level 1), and the first thermal mode."""
    pytest.importorskip("skfem")
    from betvdesign.model.electrothermal_fe import electrothermal_fe

    mat = _material()
    res = electrothermal(PUSH, mat, 4.0)
    fe = electrothermal_fe(PUSH, mat, 4.0, level=1, transient=True, steps=400)
    assert fe.converged
    assert res.power == pytest.approx(fe.power, rel=0.10)
    assert res.u_static == pytest.approx(fe.u_static, rel=0.10)
    assert res.t_max - 300 == pytest.approx(fe.t_max - 300, rel=0.10)
    assert res.tau_thermal == pytest.approx(fe.tau_first, rel=0.15)
    assert res.t_rise == pytest.approx(fe.t_rise, rel=0.15)


def test_inverse_units_read_back():
    """A temperature coefficient written by format_quantity reads back (what-if copies of a
    device rewrite its process's quantities as text)."""
    from betvdesign.spec.units import format_quantity, parse_quantity

    for text in ("1.25e-3 K^-1", "2 m^-1*K^-1"):
        q = parse_quantity(text)
        back = parse_quantity(format_quantity(q))
        assert back.to(q.units).magnitude == pytest.approx(q.magnitude, rel=1e-15)
