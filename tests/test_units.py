"""Quantity parsing and field types (source: hand-computed SI conversions; hypothesis
round trip of format/parse)."""

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st
from pydantic import BaseModel, ValidationError

from betvdesign.spec.units import (
    Frequency,
    ImpactAngle,
    Length,
    Mass,
    Voltage,
    format_quantity,
    parse_quantity,
    ureg,
)


class _M(BaseModel):
    length: Length | None = None
    mass: Mass | None = None
    freq: Frequency | None = None
    angle: ImpactAngle | None = None
    volt: Voltage | None = None


@pytest.mark.parametrize(
    ("field", "text", "unit", "expected"),
    [
        ("length", "5 um", "m", 5e-6),
        ("length", "170 um", "m", 1.7e-4),
        ("length", "0.11 um", "nm", 110.0),
        ("mass", "0.036 ug", "kg", 3.6e-11),
        ("mass", "36 pg", "kg", 3.6e-14),
        ("freq", "2.94 kHz", "Hz", 2940.0),
        ("freq", "500 Hz", "kHz", 0.5),
        ("angle", "45 deg", "rad", math.pi / 4),
        ("angle", "0.5 rad", "deg", 0.5 * 180 / math.pi),
        ("volt", "8 V", "mV", 8000.0),
    ],
)
def test_conversion_hand_values(field, text, unit, expected):
    q = getattr(_M(**{field: text}), field)
    assert q.to(unit).magnitude == pytest.approx(expected, rel=1e-12)


def test_density_hand_value():
    assert parse_quantity("2330 kg/m^3").to("g/cm**3").magnitude == pytest.approx(2.33)


@pytest.mark.parametrize("field", ["length", "mass", "freq", "angle", "volt"])
@pytest.mark.parametrize("bare", [5, 5.0, "5"])
def test_bare_numbers_rejected(field, bare):
    with pytest.raises(ValidationError, match="missing unit"):
        _M(**{field: bare})


@pytest.mark.parametrize(
    ("field", "text"),
    [
        ("length", "5 kHz"),
        ("mass", "5 um"),
        ("freq", "3 m"),
        ("volt", "2 A"),
        ("angle", "3 m"),
        ("angle", "3 percent"),
    ],
)
def test_wrong_dimension_rejected(field, text):
    with pytest.raises(ValidationError, match="wrong dimension"):
        _M(**{field: text})


@pytest.mark.parametrize(
    ("field", "text", "match"),
    [
        ("length", "-5 um", "must be > 0"),
        ("length", "0 um", "must be > 0"),
        ("mass", "nan ug", "finite"),
        ("angle", "0 deg", "must be > 0"),
        ("angle", "90 deg", "must be < 90"),
        ("angle", "1.6 rad", "must be < 90"),
        ("length", "5 furlongz", "unknown unit"),
        ("length", "5 um +", "cannot read"),
    ],
)
def test_bounds_and_garbage(field, text, match):
    with pytest.raises(ValidationError, match=match):
        _M(**{field: text})


def test_serialises_back_to_string():
    m = _M(length="5 um", mass="0.036 ug", angle="45 deg")
    data = m.model_dump(mode="json", exclude_none=True)
    assert data == {"length": "5 um", "mass": "0.036 ug", "angle": "45 deg"}
    assert _M(**data) == m


@given(
    st.floats(min_value=1e-12, max_value=1e12, allow_nan=False, allow_infinity=False),
    st.sampled_from(["um", "nm", "m", "ug", "kHz", "kg/m**3", "um/V**2", "N/m"]),
)
def test_format_parse_round_trip(x, unit):
    q = ureg.Quantity(x, unit)
    back = parse_quantity(format_quantity(q))
    assert back.units == q.units
    assert back.magnitude == x
