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


# --- the registry's disk cache (spec.units.unit_registry) ----------------------------------


def _registry_facts(reg, names):
    """Each unit's root units (factor and unit) and dimensionality, and a few parses."""
    facts = {}
    for name in names:
        try:
            factor, root = reg.get_root_units(name)
            facts[name] = (factor, str(root), str(reg.get_dimensionality(name)))
        except Exception as exc:  # "%", "‰", "R_∞": names pint's parser does not take alone
            facts[name] = type(exc).__name__
    for text in ("5 um", "2.94 kHz", "0.036 ug", "2330 kg/m^3", "45 deg", "12 N/m", "1 mm/s"):
        q = reg.Quantity(text).to_base_units()
        facts[text] = (q.magnitude, str(q.units))
    return facts


def test_unit_registry_cache_gives_the_uncached_registry(tmp_path):
    """Cold cache (written), warm cache (read) and no cache: the same units, to the bit."""
    from betvdesign.spec.units import unit_registry

    plain = unit_registry(None)
    # every unit the plain build holds (a cached build adds prefixed ones on first use)
    names = sorted(plain._units)
    truth = _registry_facts(plain, names)
    cold = unit_registry(str(tmp_path))
    assert list(tmp_path.glob("*.pickle")), "the cold build wrote no cache"
    warm = unit_registry(str(tmp_path))
    assert len(names) > 1000
    assert _registry_facts(cold, names) == truth
    assert _registry_facts(warm, names) == truth


def test_unit_registry_survives_a_damaged_cache(tmp_path):
    """A cache file cut short (another process still writing it) is skipped, not fatal."""
    from betvdesign.spec.units import unit_registry

    unit_registry(str(tmp_path))
    for f in tmp_path.glob("*.pickle"):
        f.write_bytes(f.read_bytes()[: f.stat().st_size // 2])
    plain = unit_registry(None)
    names = sorted(plain._units)
    assert _registry_facts(unit_registry(str(tmp_path)), names) == _registry_facts(plain, names)
