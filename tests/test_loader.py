"""YAML loading of shipped devices (source: the files in devices/, MODEL.md values)."""

from pathlib import Path

import pytest

from betvdesign.errors import SpecError
from betvdesign.spec.loader import load_device, load_device_text

DEVICES = Path(__file__).resolve().parents[1] / "devices"


@pytest.mark.parametrize("path", sorted(DEVICES.glob("*.yaml")), ids=lambda p: p.name)
def test_shipped_devices_load(path):
    spec = load_device(path)
    assert spec.name == path.stem
    assert len(spec.actuator_sets) >= 1
    for s in spec.actuator_sets:
        assert s.intended_mode in ("push", "pull")


def test_shin2004_values_as_published():
    spec = load_device(DEVICES / "shin2004.yaml")
    sl = spec.slider
    assert sl.beam_width.to("um").magnitude == 5
    assert sl.beam_length.to("um").magnitude == 170
    assert sl.beam_thickness.to("um").magnitude == 2
    assert sl.travel_range.to("um").magnitude == 40
    assert spec.material.density.to("kg/m**3").magnitude == 2330
    for s in spec.actuator_sets:
        assert s.head.mass.to("ug").magnitude == pytest.approx(0.036)
        assert s.actuator.vertical_resonance.to("kHz").magnitude == pytest.approx(2.94)
        assert s.drive.waveform == "ac" and s.drive.frequency.to("Hz").magnitude == 500
        assert s.contact.impact_angle.to("deg").magnitude == 45
        assert s.contact.friction == 0.4
        assert s.actuator.alpha == 0.1
    assert {s.impact_direction for s in spec.actuator_sets} == {"+x", "-x"}


def test_yaml_12_semantics_yes_is_a_string():
    # YAML 1.1 would read `yes` as true; in 1.2 it is the string "yes" -> a mode error
    text = (
        (DEVICES / "shin2004.yaml")
        .read_text()
        .replace("intended_mode: pull", "intended_mode: yes", 1)
    )
    with pytest.raises(SpecError) as exc:
        load_device_text(text, "x.yaml")
    assert "'push' or 'pull'" in str(exc.value)
