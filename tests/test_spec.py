"""Spec models from Python and the amplitude calibration (source: hand-computed
u = g·V, u = g·V², linear interpolation of measured points)."""

import numpy as np
import pint
import pytest
from pydantic import ValidationError

from betvdesign.errors import ParameterError
from betvdesign.spec.models import MATERIALS, POLYSILICON, ActuatorSet, DeviceSpec, amplitude_at
from betvdesign.spec.models import amplitude_at as amplitude_at_nondim
from betvdesign.spec.units import ureg

SET = {
    "name": "a",
    "intended_mode": "push",
    "head": {"mass": "0.02 ug"},
    "contact": {"impact_angle": "30 deg", "friction": 0.3},
    "actuator": {"vertical_resonance": "10 kHz", "alpha": 2.0, "amplitude": "0.2 um"},
    "drive": {"waveform": "ac", "frequency": "5 kHz", "voltage": "8 V"},
}


def _set(calibration=None, voltage="8 V", **actuator):
    act = {"vertical_resonance": "10 kHz", "alpha": 2.0, **actuator}
    if calibration is not None:
        act["calibration"] = calibration
    return ActuatorSet.model_validate(
        {**SET, "actuator": act, "drive": {**SET["drive"], "voltage": voltage}}
    )


def test_linear_calibration():
    s = _set({"law": "linear", "gain": "0.01375 um/V"})
    assert amplitude_at(s).to("um").magnitude == pytest.approx(0.11)  # 0.01375·8
    assert amplitude_at(s, "4 V").to("nm").magnitude == pytest.approx(55.0)


def test_quadratic_calibration():
    s = _set({"law": "quadratic", "gain": "0.002 um/V^2"})
    assert amplitude_at(s).to("um").magnitude == pytest.approx(0.128)  # 0.002·64
    assert amplitude_at(s, ureg.Quantity(5000, "mV")).to("um").magnitude == pytest.approx(0.05)


def test_measured_calibration_interpolates_and_refuses_extrapolation():
    pts = [
        {"voltage": "0 V", "amplitude": "0 um"},
        {"voltage": "4 V", "amplitude": "0.03 um"},
        {"voltage": "8 V", "amplitude": "0.11 um"},
    ]
    s = _set({"law": "measured", "points": pts}, voltage="6 V")
    assert amplitude_at(s).to("um").magnitude == pytest.approx(0.07)  # midway 0.03..0.11
    volts = ureg.Quantity(np.array([0.0, 2.0, 8.0]), "V")
    np.testing.assert_allclose(amplitude_at(s, volts).to("um").magnitude, [0, 0.015, 0.11])
    with pytest.raises(ParameterError, match="outside the measured calibration range"):
        amplitude_at(s, "9 V")


def test_amplitude_given_directly():
    s = ActuatorSet.model_validate(SET)
    assert amplitude_at(s).to("um").magnitude == pytest.approx(0.2)
    with pytest.raises(ParameterError, match="gives its amplitude directly"):
        amplitude_at(s, "5 V")
    assert amplitude_at_nondim is amplitude_at  # the contract: spec/nondim expose it


@pytest.mark.parametrize("bad", ["5 um", "-1 V", "nan V"])
def test_amplitude_bad_voltage(bad):
    s = _set({"law": "linear", "gain": "0.01 um/V"})
    with pytest.raises(ParameterError):
        amplitude_at(s, bad)


def test_python_api_accepts_quantities_and_is_frozen():
    d = {**SET, "head": {"mass": ureg.Quantity(2e-11, "kg")}}
    s = ActuatorSet.model_validate(d)
    assert s.head.mass.to("ug").magnitude == pytest.approx(0.02)
    with pytest.raises(ValidationError):
        s.name = "b"  # frozen
    with pytest.raises(ValidationError, match="another pint registry"):
        ActuatorSet.model_validate({**SET, "head": {"mass": pint.UnitRegistry().Quantity(1, "ug")}})


def test_extra_fields_forbidden_and_default_material():
    spec = DeviceSpec.model_validate(
        {
            "name": "x",
            "slider": {
                "beam_length": "100 um",
                "beam_width": "5 um",
                "beam_thickness": "2 um",
                "travel_range": "10 um",
            },
            "actuator_sets": [SET],
        }
    )
    assert spec.material == POLYSILICON == MATERIALS["polysilicon"]
    assert POLYSILICON.density.to("kg/m**3").magnitude == 2330
    assert spec.slider.beam_count == 2 and spec.slider.extra_mass.magnitude == 0
    with pytest.raises(ValidationError, match="Extra inputs"):
        DeviceSpec.model_validate({**spec.model_dump(), "colour": "red"})


def test_travel_sign():
    push = ActuatorSet.model_validate(SET)
    assert push.travel_sign == 1
    pull_minus = ActuatorSet.model_validate(
        {**SET, "intended_mode": "pull", "impact_direction": "-x"}
    )
    assert pull_minus.travel_sign == 1
    assert ActuatorSet.model_validate({**SET, "intended_mode": "pull"}).travel_sign == -1


def test_field_descriptions_on_demand_match_pydantics_attribute_docstrings():
    """describe_fields (docstrings attached when a schema is asked for) gives the schema
    pydantic's own use_attribute_docstrings gives, built in a fresh process with it on."""
    import json
    import subprocess
    import sys

    from betvdesign.spec.fielddocs import describe_fields

    code = (
        "import json, pydantic._internal._config as c\n"
        "c.config_defaults['use_attribute_docstrings'] = True\n"
        "from betvdesign.spec.models import DeviceSpec\n"
        "print(json.dumps(DeviceSpec.model_json_schema(mode='validation')))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    want = json.loads(out.stdout)
    describe_fields(DeviceSpec)
    got = DeviceSpec.model_json_schema(mode="validation")
    assert json.dumps(want).count('"description"') > 100
    assert got == want
