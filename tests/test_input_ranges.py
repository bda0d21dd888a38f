"""Issue 32, items 7 and 8: every quantity a file gives is bounded at load time, where the
model's arithmetic stops meaning anything (spec/limits.py QUANTITY_RANGE), refused with
file:line:col and exit 2, never a traceback; and the quantity messages are cooked.

Truths: the line and column are counted in the text written, apart from the loader; the
arithmetic claim of the ranges is checked by brute force over every corner of them."""

import itertools
import math
import typing
from pathlib import Path

import pytest
from typer.testing import CliRunner

from betvdesign.cli import app
from betvdesign.nondim.device import derive
from betvdesign.spec import limits
from betvdesign.spec.loader import load_device
from betvdesign.spec.models import DeviceSpec
from betvdesign.spec.units import QuantitySpec

DEVICES = Path(__file__).resolve().parents[1] / "devices"
PUSH = (DEVICES / "push_demo.yaml").read_text()
SHIN = (DEVICES / "shin2004.yaml").read_text()

# (device text, the line as written, its replacement, the field path named)
A = "actuator_sets[0]."
CASES = {
    "frequency-1e-300": (PUSH, "frequency: 3 kHz", "frequency: 1e-300 Hz", A + "drive.frequency"),
    "voltage-5e-324": (PUSH, "voltage: 9 V", "voltage: 5e-324 V", A + "drive.voltage"),
    "voltage-1e-320": (PUSH, "voltage: 9 V", "voltage: 1e-320 V", A + "drive.voltage"),
    "angle-1e-300": (
        PUSH,
        "impact_angle: 20.56 deg",
        "impact_angle: 1e-300 deg",
        A + "contact.impact_angle",
    ),
    "head-mass-1e-300": (SHIN, "mass: 0.036 ug ", "mass: 1e-300 ug ", A + "head.mass"),
    "head-mass-1e300": (SHIN, "mass: 0.036 ug ", "mass: 1e300 kg ", A + "head.mass"),
    "extra-mass-subnormal": (
        PUSH,
        "  beam_count: 2\n",
        "  beam_count: 2\n  extra_mass: 1e-310 kg\n",
        "slider.extra_mass",
    ),
    "beam-length-1e-300": (
        PUSH,
        "beam_length: 200 um",
        "beam_length: 1e-300 um",
        "slider.beam_length",
    ),
    "diameter-1e300": (PUSH, "diameter: 36 um", "diameter: 1e300 m", A + "head.geometry.diameter"),
    "resonance-1e-300": (
        PUSH,
        "vertical_resonance: 5 kHz",
        "vertical_resonance: 1e-300 Hz",
        A + "actuator.vertical_resonance",
    ),
    "gain-1e-300": (
        SHIN,
        "gain: 0.01375 um/V",
        "gain: 1e-300 um/V",
        A + "actuator.calibration.gain",
    ),
    "friction-1e-300": (PUSH, "friction: 0.4", "friction: 1e-300", A + "contact.friction"),
}


def run(*args):
    return CliRunner().invoke(app, [str(a) for a in args])


def _position(text: str, new: str) -> tuple[int, int]:
    """1-based line and column of the value of the first line ``new`` starts, counted in
    the text itself."""
    start = text.index(new.lstrip("\n").strip())
    key_line = text[start:].split("\n", 1)[0]
    value_at = start + key_line.index(":") + 2
    line = text.count("\n", 0, value_at) + 1
    return line, value_at - text.rfind("\n", 0, value_at)


@pytest.mark.parametrize("name", sorted(CASES))
def test_a_value_outside_the_model_is_refused_at_its_line_with_exit_2(name, tmp_path):
    base, old, new, field = CASES[name]
    assert old in base
    text = base.replace(old, new, 1)
    f = tmp_path / "dev.yaml"
    f.write_text(text)
    res = run("check", f)
    assert res.exit_code == 2, res.output
    assert "Traceback" not in res.output and "Error:" not in res.stderr.replace("error:", "")
    line, col = _position(text, new.strip().split("\n")[-1])
    assert f"{f}:{line}:{col}: {field}: " in res.stderr, res.stderr
    assert "outside" in res.stderr or "below" in res.stderr


def test_zero_stays_allowed_where_the_field_allows_it(tmp_path):
    """A calibration point at 0 V / 0 µm and an extra mass of 0 are not 'tiny' values."""
    text = PUSH.replace("  beam_count: 2\n", "  beam_count: 2\n  extra_mass: 0 ug\n", 1)
    f = tmp_path / "dev.yaml"
    f.write_text(text)
    spec = load_device(f)
    assert spec.slider.extra_mass.magnitude == 0
    points = spec.actuator_sets[0].actuator.calibration.points
    assert points[0].voltage.magnitude == 0 and points[0].amplitude.magnitude == 0


def _quantity_units(model: type, seen: set) -> set[str]:
    """The units of every quantity field reachable from a pydantic model."""
    units: set[str] = set()
    if model in seen:
        return units
    seen.add(model)
    for info in model.model_fields.values():
        stack = [info.annotation, *info.metadata]
        while stack:
            tp = stack.pop()
            if isinstance(tp, QuantitySpec):
                units.add(tp.unit)
                continue
            if isinstance(tp, type) and hasattr(tp, "model_fields"):
                units |= _quantity_units(tp, seen)
                continue
            stack += typing.get_args(tp)
            stack += getattr(tp, "__metadata__", ())
    return units


def test_every_quantity_of_a_device_has_a_range():
    units = _quantity_units(DeviceSpec, set())
    assert {"m", "kg", "Hz", "V", "deg", "Pa", "kg/m**3"} <= units  # the walk finds them
    assert units <= set(limits.QUANTITY_RANGE), units - set(limits.QUANTITY_RANGE)


def test_every_corner_of_the_ranges_derives_finite_parameters():
    """The ranges' claim, by brute force: with the inputs at any combination of their range
    ends (2⁸ devices), every model parameter is finite and > 0, and λ finite."""
    spec = load_device(DEVICES / "shin2004.yaml")
    r = limits.QUANTITY_RANGE
    ends = {
        "drive.frequency": [f"{x} Hz" for x in r["Hz"][:2]],
        "actuator.vertical_resonance": [f"{x} Hz" for x in r["Hz"][:2]],
        "head.mass": [f"{x} kg" for x in r["kg"][:2]],
        "drive.voltage": [f"{x} V" for x in r["V"][:2]],
        "actuator.calibration.gain": [f"{x} m/V" for x in r["m/V"][:2]],
        "slider.beam_length": ["1 nm", f"{r['m'][1]} m"],  # 1 nm: the smallest drawn
        "contact.impact_angle": [f"{x!r} deg" for x in r["deg"][:2]],
        "contact.friction": [limits.MIN_FRICTION, 1.5],
    }
    for combo in itertools.product(*ends.values()):
        edits = list(zip(ends, combo, strict=True))
        d = derive(spec.replace(*edits[0], *edits[1:]))
        for s in d.sets:
            values = s.params.as_dict().values()
            assert all(math.isfinite(v) and v > 0 for v in values), (combo, s.params)
            assert math.isfinite(s.lam), (combo, s.params)  # a fit: any sign


@pytest.mark.parametrize(
    ("value", "fragment"),
    [
        ('"-5"', "missing unit in '-5': write it with units, e.g. '8 V'"),
        ('"V"', "missing number in 'V'"),
    ],
)
def test_the_quantity_messages_are_cooked(value, fragment, tmp_path):
    """Issue 32 item 8: 'missing unit in {text!r}' reached the user uncooked."""
    f = tmp_path / "dev.yaml"
    f.write_text(PUSH.replace("voltage: 9 V", f"voltage: {value}", 1))
    res = run("check", f)
    assert res.exit_code == 2
    assert fragment in res.stderr, res.stderr
    assert "{" not in res.stderr and "!r" not in res.stderr


@pytest.mark.parametrize(
    ("command", "bound"),
    [
        ("sweep", "drive.frequency=1e-300Hz:1kHz"),
        ("fix", "drive.frequency=1e-300Hz:1kHz"),
        ("sweep", "slider.beam_width=1um:1e300um"),
    ],
)
def test_vary_bounds_outside_the_model_are_bad_input(command, bound, tmp_path):
    """A --vary bound a device file could not give is refused the same way (exit 2), not
    a ZeroDivisionError in a worker."""
    f = tmp_path / "dev.yaml"
    f.write_text(SHIN)
    res = run(command, f, "--vary", bound)
    assert res.exit_code == 2, res.output
    assert "is outside" in res.stderr and "the range of" in res.stderr
    assert "Traceback" not in res.output
