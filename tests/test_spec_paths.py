"""Spec paths (spec.paths, the one home of the idea) and the one list of the fields a
designer changes (spec.fields): the same path resolves alike in a spec, its plain data
and the YAML tree of its file; betv fix and the report's robustness sweep read one list."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import DEVICES
from ruamel.yaml import YAML

from betvdesign.errors import SpecError
from betvdesign.spec.fields import BY_PATH, FIELDS, bounds
from betvdesign.spec.loader import load_device
from betvdesign.spec.messages import known_fields
from betvdesign.spec.models import DeviceSpec
from betvdesign.spec.paths import (
    PathError,
    given,
    holder,
    in_set,
    replace,
    targets,
    value_at,
    with_values,
)
from betvdesign.spec.units import ureg
from betvdesign.studies.fixfields import DEFAULT_BOUNDS, parse_vary

BIDIR = DEVICES / "bidir_demo.yaml"


def _trees():
    spec = load_device(BIDIR)
    data = spec.model_dump(mode="json", exclude_unset=True, by_alias=True)
    yaml = YAML(typ="rt").load(BIDIR.read_text("utf-8"))
    return spec, data, yaml


@pytest.mark.parametrize(
    ("field", "expected"),
    [
        ("slider.beam_width", [("slider", "beam_width")]),
        (
            "drive.voltage",
            [("actuator_sets", 0, "drive", "voltage"), ("actuator_sets", 1, "drive", "voltage")],
        ),
        ("actuator_sets.west.drive.voltage", [("actuator_sets", 1, "drive", "voltage")]),
        (
            "actuator_sets.0.head.geometry.diameter",
            [("actuator_sets", 0, "head", "geometry", "diameter")],
        ),
        ("actuator_sets.north.drive.voltage", []),
        ("actuator_sets.7.drive.voltage", []),
        ("slider..beam_width", []),
        ("", []),
    ],
)
def test_targets_resolve_alike_in_spec_data_and_yaml(field, expected):
    """One resolution for the three trees a device takes: a set by index or name, a set
    field in every set; an unknown set or an empty part resolves to nothing."""
    for tree in _trees():
        assert targets(tree, field) == expected


def test_values_read_alike_in_spec_data_and_yaml():
    spec, data, yaml = _trees()
    assert given(spec, "drive.voltage") == [ureg.Quantity(7, "V")] * 2
    assert given(data, "drive.voltage") == ["7 V"] * 2 == given(yaml, "drive.voltage")
    assert given(spec, "contact.friction") == [0.35, 0.35] == given(yaml, "contact.friction")
    assert given(spec, "head.mass") == [] == given(yaml, "head.mass")  # geometry given
    assert given(spec, "material.density") == [ureg.Quantity(2330, "kg/m^3")]
    assert given(yaml, "material.density") == []  # the file names the material
    assert value_at(spec, ("actuator_sets", 5, "drive")) is None


def test_holder_names_the_missing_section():
    """The walk that edits plain data and YAML trees: a missing section is a PathError
    with the path to it and the closest section name."""
    _, data, yaml = _trees()
    node, key = holder(yaml, targets(yaml, "actuator_sets.west.drive.voltage")[0])
    assert (node, key) == (yaml["actuator_sets"][1]["drive"], "voltage")
    with pytest.raises(PathError, match="no section 'slidr' in this device; did you mean") as e:
        holder(data, ("slidr", "beam_width"))
    assert e.value.path == "slidr"
    with pytest.raises(PathError) as e:
        holder(data, targets(data, "head.geometri.diameter")[1])
    assert e.value.path == "actuator_sets.1.head.geometri"


def test_replace_and_with_values_copy_without_validation():
    """Unvalidated copies hold arrays of samples; a named set is changed alone."""
    spec = load_device(BIDIR)
    width = ureg.Quantity(np.array([7.0, 8.0, 9.0]), "um")
    wide = with_values(spec, {"slider.beam_width": width, "contact.friction": 0.3})
    assert wide.slider.beam_width is width and given(wide, "contact.friction") == [0.3, 0.3]
    west = with_values(spec, {"actuator_sets.west.contact.friction": 0.5})
    assert given(west, "contact.friction") == [0.35, 0.5]
    assert spec.actuator_sets[1].contact.friction == 0.35  # unchanged
    with pytest.raises(PathError):
        replace(spec, ("slider", "nope", "x"), 1.0)


def test_whatif_uses_the_same_paths():
    """DeviceSpec.replace (validated) resolves sets by name like studies do."""
    spec = load_device(BIDIR)
    assert given(spec.replace("actuator_sets.west.drive.voltage", "6 V"), "drive.voltage") == [
        ureg.Quantity(7, "V"),
        ureg.Quantity(6, "V"),
    ]
    with pytest.raises(SpecError, match=r"no actuator set 'north' \(sets: east, west\)"):
        spec.replace("actuator_sets.north.drive.voltage", "6 V")
    with pytest.raises(SpecError, match="empty field path"):
        spec.replace("slider..beam_width", "6 um")


def test_in_set():
    assert in_set("drive.frequency", 1) == "actuator_sets.1.drive.frequency"
    assert in_set("slider.beam_width", 1) == "slider.beam_width"


def test_the_field_list():
    """Every field of the list is a field of the device file; betv fix's defaults are
    the fields the designer chooses, in the list's order and with its bounds, and
    exactly the fields and bounds it had before the list was shared."""
    names = set(known_fields(DeviceSpec))
    for f in FIELDS:
        assert f.path.split(".")[-1] in names, f.path
        assert f.moves and set(f.moves) <= {"ϖ", "α", "β", "κ", "ℓ"}
        assert bounds(f.path) == f.bounds
    assert bounds("contact.restitution") == (0.5, 2.0)
    assert DEFAULT_BOUNDS == {
        "drive.frequency": (0.25, 4.0),
        "drive.voltage": (0.5, 2.0),
        "actuator.amplitude": (0.5, 2.0),
        "slider.beam_width": (0.5, 4.0),
        "slider.beam_length": (0.5, 2.0),
        "head.mass": (0.25, 4.0),
        "head.geometry.diameter": (0.5, 2.0),
        "head.geometry.length": (0.5, 2.0),
        "head.geometry.width": (0.5, 2.0),
        "actuator.vertical_resonance": (0.5, 2.0),
        "actuator.horizontal_resonance": (0.5, 2.0),
        "actuator.horizontal_stiffness": (0.25, 4.0),
        "actuator.alpha": (0.25, 4.0),
        "contact.impact_angle": (15.0, 75.0, "deg"),
    }
    assert list(DEFAULT_BOUNDS) == [f.path for f in FIELDS if f.chosen]
    assert not BY_PATH["contact.friction"].chosen and BY_PATH["contact.friction"].moves_model
    assert not BY_PATH["drive.voltage"].moves_model  # the stroke: speed, not the mode


def test_fix_vary_by_set_name():
    """``--vary actuator_sets.<name>.<field>`` reads the named set's value."""
    spec = load_device(BIDIR)
    (v,) = parse_vary(spec, ["actuator_sets.west.drive.frequency"])
    assert (v.x0, v.unit, v.lo, v.hi) == (3.9, "kHz", 1.95, 7.8)
