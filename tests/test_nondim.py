"""Spec -> (ϖ, α, β, κ), λ, scales (source: hand computation of MODEL.md's relations
for the published device, docs/MODEL.md "The published device")."""

import math
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from betvdesign.model.params import lambda_criterion
from betvdesign.nondim.device import derive
from betvdesign.spec.loader import load_device, load_device_text

DEVICES = Path(__file__).resolve().parents[1] / "devices"

# ρ·L·w·t of one beam [kg]
M_SHIN = 2330 * 170e-6 * 5e-6 * 2e-6
m_SHIN = 0.036e-9  # 0.036 ug [kg]


def test_shin2004_hand_values():
    d = derive(load_device(DEVICES / "shin2004.yaml"))
    assert [s.name for s in d.sets] == ["right", "left"]
    s = d.sets[0]
    p = s.params
    assert p.varpi == pytest.approx(1000 / 2940, rel=1e-12)  # 2×500 Hz / 2.94 kHz
    assert p.beta == pytest.approx(m_SHIN / M_SHIN, rel=1e-12)
    assert p.beta == pytest.approx(9.0886, rel=1e-4)
    assert p.alpha == 0.1
    assert p.kappa == pytest.approx(0.4, rel=1e-12)
    assert s.lam == pytest.approx(lambda_criterion(1000 / 2940, 0.1, m_SHIN / M_SHIN, 0.4))
    assert s.intended_mode == "pull"
    k_v = m_SHIN * (2 * math.pi * 2940) ** 2
    assert s.step("k_v").value.to("N/m").magnitude == pytest.approx(k_v, rel=1e-12)
    assert s.step("M").value.to("kg").magnitude == pytest.approx(M_SHIN, rel=1e-12)
    sc = s.scales
    assert sc.f_act_hz == pytest.approx(1000.0)
    assert sc.omega_rad_s == pytest.approx(2 * math.pi * 1000)
    assert sc.time_s == pytest.approx(math.sqrt(m_SHIN / k_v), rel=1e-12)
    assert sc.u_m == pytest.approx(0.11e-6, rel=1e-12)
    assert sc.length_m == pytest.approx(0.11e-6 * math.cos(math.pi / 4), rel=1e-12)
    assert sc.theta_rad == pytest.approx(math.pi / 4)
    derived = s.derived()
    assert derived["f_act"] == "1000 Hz"
    assert derived["M"] == "0.003961 ug"
    assert derived["u"] == "0.11 um"


def test_published_fit_comparison_shows_mismatch():
    s = derive(load_device(DEVICES / "shin2004.yaml")).sets[0]
    cmp = {c.name: c for c in s.published}
    assert not cmp["varpi"].matches()  # 0.34 computed vs 0.9 published
    assert cmp["varpi"].rel_diff == pytest.approx(abs(1000 / 2940 - 0.9) / 0.9)
    assert cmp["beta"].published == (0.9, 9.0)
    assert cmp["beta"].matches()  # 9.09 is within 10 % of the quoted 9
    assert cmp["alpha"].matches() and cmp["kappa"].matches()


BASE = """
name: t
slider: {beam_length: 100 um, beam_width: 10 um, beam_thickness: 2 um, travel_range: 50 um}
actuator_sets:
  - name: a
    intended_mode: push
    head: HEAD
    contact: {impact_angle: 30 deg, friction: 0.3}
    actuator: ACT
    drive: DRIVE
"""


def _derive(
    head="{mass: 0.02 ug}",
    act="{vertical_resonance: 10 kHz, alpha: 2, amplitude: 0.2 um}",
    drive="{waveform: ac, frequency: 5 kHz}",
):
    text = BASE.replace("HEAD", head).replace("ACT", act).replace("DRIVE", drive)
    return derive(load_device_text(text, "t.yaml")).sets[0]


@pytest.mark.parametrize(
    ("waveform", "f_act"), [("ac", 10e3), ("dc-biased", 5e3), ("unipolar", 5e3)]
)
def test_ac_doubling(waveform, f_act):
    s = _derive(drive=f"{{waveform: {waveform}, frequency: 5 kHz}}")
    assert s.scales.f_act_hz == pytest.approx(f_act)
    assert s.params.varpi == pytest.approx(f_act / 10e3)


def test_alpha_from_horizontal_resonance_and_stiffness():
    s = _derive(act="{vertical_resonance: 10 kHz, horizontal_resonance: 5 kHz, amplitude: 1 um}")
    assert s.params.alpha == pytest.approx(4.0)
    m = 0.02e-9
    k_v = m * (2 * math.pi * 1e4) ** 2
    s = _derive(
        act=f"{{vertical_resonance: 10 kHz, horizontal_stiffness: {k_v / 2} N/m, amplitude: 1 um}}"
    )
    assert s.params.alpha == pytest.approx(2.0, rel=1e-9)


def test_head_mass_from_geometry():
    s = _derive(head="{geometry: {shape: disc, diameter: 20 um, thickness: 2 um}}")
    m = 2330 * math.pi * (20e-6) ** 2 / 4 * 2e-6
    assert s.step("m").value.to("kg").magnitude == pytest.approx(m, rel=1e-12)
    M = 2330 * 100e-6 * 10e-6 * 2e-6
    assert s.params.beta == pytest.approx(m / M, rel=1e-12)
    s = _derive(
        head="{geometry: {shape: box, length: 10 um, width: 5 um, thickness: 2 um}, "
        "material: {name: nickel, density: 8900 kg/m^3}}"
    )
    assert s.step("m").value.to("kg").magnitude == pytest.approx(8900 * 1e-16, rel=1e-12)


def test_extra_mass_and_beam_count():
    text = (
        BASE.replace("HEAD", "{mass: 0.02 ug}")
        .replace("ACT", "{vertical_resonance: 10 kHz, alpha: 2, amplitude: 0.2 um}")
        .replace("DRIVE", "{waveform: ac, frequency: 5 kHz}")
        .replace(
            "travel_range: 50 um}", "travel_range: 50 um, beam_count: 3, extra_mass: 0.004 ug}"
        )
    )
    s = derive(load_device_text(text)).sets[0]
    M = (3 * 2330 * 100e-6 * 10e-6 * 2e-6 + 0.004e-9) / 2
    assert s.step("M").value.to("kg").magnitude == pytest.approx(M, rel=1e-12)


def test_record_lists_inputs_and_formulas():
    s = derive(load_device(DEVICES / "shin2004.yaml")).sets[0]
    symbols = [st.symbol for st in s.record]
    for sym in ("M", "m", "k_v", "f_act", "ω", "u", "ϖ", "α", "β", "κ", "λ"):
        assert sym in symbols
    assert s.step("f_act").formula == "2·f_drive"
    assert s.step("u").formula == "gain·V"
    # every input of every step is itself in the record, earlier
    seen: set[str] = set()
    for step in s.record:
        assert set(step.inputs) <= seen, step.symbol
        seen.add(step.symbol)


@settings(max_examples=25, deadline=None)
@given(
    f_v=st.floats(1.0, 50.0),
    ratio=st.floats(0.2, 3.0),
    mass=st.floats(0.001, 0.1),
)
def test_parameters_do_not_depend_on_units(f_v, ratio, mass):
    """Invariant: the same device written in other units gives the same (ϖ, α, β, κ)."""
    f_drive = f_v * ratio / 2  # kHz, AC drive -> ϖ = ratio
    a = _derive(
        head=f"{{mass: {mass} ug}}",
        act=f"{{vertical_resonance: {f_v} kHz, alpha: 2, amplitude: 0.2 um}}",
        drive=f"{{waveform: ac, frequency: {f_drive} kHz}}",
    )
    b = _derive(
        head=f"{{mass: {mass * 1e-9} kg}}",
        act=f"{{vertical_resonance: {f_v * 1e3} Hz, alpha: 2, amplitude: 200 nm}}",
        drive=f"{{waveform: ac, frequency: {f_drive * 1e-3} MHz}}",
    )
    assert a.params.varpi == pytest.approx(ratio, rel=1e-12)
    for name in ("varpi", "alpha", "beta", "kappa"):
        assert getattr(a.params, name) == pytest.approx(getattr(b.params, name), rel=1e-12)
    assert a.scales.length_m == pytest.approx(b.scales.length_m, rel=1e-12)
    assert a.lam == pytest.approx(b.lam, rel=1e-10)


@pytest.mark.parametrize("deg", [10.0, 30.0, 45.0, 60.0, 80.0])
def test_kappa_is_mu_tan_theta(deg):
    text = BASE.replace("30 deg", f"{deg} deg").replace("HEAD", "{mass: 0.02 ug}")
    text = text.replace("ACT", "{vertical_resonance: 10 kHz, alpha: 2, amplitude: 0.2 um}")
    s = derive(load_device_text(text.replace("DRIVE", "{waveform: ac, frequency: 5 kHz}")))
    assert s.sets[0].params.kappa == pytest.approx(0.3 * math.tan(math.radians(deg)), rel=1e-12)
    rad = text.replace(f"{deg} deg", f"{math.radians(deg)!r} rad")
    s2 = derive(load_device_text(rad.replace("DRIVE", "{waveform: ac, frequency: 5 kHz}")))
    assert s2.sets[0].params.kappa == pytest.approx(s.sets[0].params.kappa, rel=1e-12)


def test_published_values_in_record():
    s = derive(load_device(DEVICES / "shin2004.yaml")).sets[0]
    assert s.step("ϖ_pub").magnitude == 0.9
    assert "62% away" in s.step("ϖ_pub").description
    assert s.step("β_pub[0]").magnitude == 0.9 and s.step("β_pub[1]").magnitude == 9.0
    assert s.step("β_pub[1]").key == "beta_pub[1]"


def test_derive_samples_vectorises_derive_set_by_hand_formulas():
    """Monte Carlo path: β = m/M with M = (n·ρ·L·w·t)/2 and κ = μ·tanθ per sample,
    computed by hand with numpy, against nondim.derive_samples on array-valued fields."""
    import numpy as np

    from betvdesign.nondim.device import derive_samples
    from betvdesign.spec.paths import with_values
    from betvdesign.spec.units import ureg

    spec = load_device(DEVICES / "shin2004.yaml")
    w = np.array([4.0, 5.0, 6.5])  # um
    theta = np.array([30.0, 45.0, 60.0])  # deg
    s = with_values(
        spec,
        {
            "slider.beam_width": ureg.Quantity(w, "um"),
            "contact.impact_angle": ureg.Quantity(theta, "deg"),
        },
    )
    d = derive_samples(s, s.actuator_sets[0])
    M = 2 * 2330 * 170e-6 * w * 1e-6 * 2e-6 / 2  # kg
    np.testing.assert_allclose(d.beta, 3.6e-11 / M, rtol=1e-12)  # m = 0.036 ug
    np.testing.assert_allclose(d.kappa, 0.4 * np.tan(np.radians(theta)), rtol=1e-12)
    np.testing.assert_allclose(d.length_m, 0.11e-6 * np.cos(np.radians(theta)), rtol=1e-12)
    np.testing.assert_allclose(d.varpi, 1000 / 2940, rtol=1e-12)
