"""Every bad-input case of issue 2: message names file:line:col and field, all issues of a
file are collected, `betv check` exits 2 without a traceback (source: the fixtures in
tests/data/specs/, whose positions were read off the files by hand)."""

from pathlib import Path

import pytest
from typer.testing import CliRunner

from betvdesign.cli import app
from betvdesign.errors import SpecError
from betvdesign.nondim.device import derive_file
from betvdesign.spec.loader import load_device, load_device_text

SPECS = Path(__file__).resolve().parent / "data" / "specs"

# file -> [(line, col, field path, fragment of the message)], in report order
CASES: dict[str, list[tuple[int | None, int | None, str, str]]] = {
    "missing_unit.yaml": [(5, 15, "slider.beam_width", "missing unit")],
    "wrong_dimension.yaml": [
        (22, 18, "actuator_sets[0].drive.frequency", "wrong dimension: 500 um has [length]")
    ],
    "unknown_unit.yaml": [(4, 16, "slider.beam_length", "unknown unit in '170 umm'")],
    "unknown_field.yaml": [
        (4, 3, "slider.beam_lenght", "unknown field; did you mean 'beam_length'?"),
        (4, 3, "slider.beam_length", "missing required field"),
    ],
    "duplicate_keys.yaml": [
        (6, 3, "slider.beam_width", "duplicate key (first given on line 5)"),
        (17, 7, "actuator_sets[0].contact.friction", "duplicate key (first given on line 16)"),
    ],
    "negative_mass.yaml": [(12, 13, "actuator_sets[0].head.mass", "must be > 0 kg")],
    "zero_length.yaml": [(6, 19, "slider.beam_thickness", "must be > 0 m, got 0 um")],
    "angle_90.yaml": [(14, 21, "actuator_sets[0].contact.impact_angle", "must be < 90 deg")],
    "angle_0.yaml": [(14, 21, "actuator_sets[0].contact.impact_angle", "must be > 0 deg")],
    "angle_no_unit.yaml": [(14, 21, "actuator_sets[0].contact.impact_angle", "missing unit")],
    "friction_high.yaml": [
        (15, 17, "actuator_sets[0].contact.friction", "outside the physical range (0, 1.5]")
    ],
    "friction_zero.yaml": [
        (15, 17, "actuator_sets[0].contact.friction", "μ = 0 outside the physical range")
    ],
    "missing_field.yaml": [(4, 3, "slider.travel_range", "missing required field")],
    "bad_mode.yaml": [(10, 20, "actuator_sets[0].intended_mode", "'push' or 'pull'")],
    "bad_waveform.yaml": [(21, 17, "actuator_sets[0].drive.waveform", "'ac', 'dc-biased'")],
    "two_compliances.yaml": [
        (17, 7, "actuator_sets[0].actuator", "got alpha, horizontal_resonance")
    ],
    "no_amplitude.yaml": [(17, 7, "actuator_sets[0].actuator", "'amplitude' or 'calibration'")],
    "unknown_material.yaml": [(3, 11, "material", "unknown material 'unobtainium'")],
    "calibration_unsorted.yaml": [
        (
            23,
            23,
            "actuator_sets[0].actuator.calibration.points[1].voltage",
            "strictly increasing voltages",
        )
    ],
    "voltage_outside_calibration.yaml": [
        (27, 16, "actuator_sets[0].drive.voltage", "outside the measured calibration range")
    ],
    "calibration_no_voltage.yaml": [
        (21, 7, "actuator_sets[0].drive.voltage", "required when the actuator gives a calib")
    ],
    "bool_beam_count.yaml": [(8, 15, "slider.beam_count", "expected an integer, got the boolean")],
    "duplicate_set_names.yaml": [(15, 11, "actuator_sets[1].name", "must be unique")],
    "many_issues.yaml": [
        (5, 15, "slider.beam_width", "missing unit"),
        (14, 21, "actuator_sets[0].contact.impact_angle", "must be < 90 deg"),
        (18, 7, "actuator_sets[0].actuator.alfa", "did you mean 'alpha'?"),
        (22, 18, "actuator_sets[0].drive.frequency", "wrong dimension"),
    ],
    "malformed.yaml": [(5, 14, "", "invalid YAML: expected ',' or '}'")],
    "bad_indent.yaml": [(5, 14, "", "invalid YAML: mapping values are not allowed")],
    "tab_indent.yaml": [(4, 1, "", "invalid YAML: found character '\\t'")],
    "top_level_list.yaml": [(1, 1, "", "expected a mapping at the top level, got a list")],
    "empty.yaml": [(None, None, "", "empty file")],
    "not_utf8.yaml": [(2, 10, "", "not UTF-8 text")],
    "merge_key_error.yaml": [
        (12, 38, "actuator_sets[0].drive.frequency", "wrong dimension"),
        (12, 38, "actuator_sets[1].drive.frequency", "wrong dimension"),
    ],
    # fields whose ratio would overflow (ϖ = f_act/f_v = inf): refused at load, each at
    # its own position (limits.QUANTITY_RANGE)
    "overflow_params.yaml": [
        (17, 27, "actuator_sets[0].actuator.vertical_resonance", "1e-300 Hz is outside 0.001 Hz"),
        (22, 18, "actuator_sets[0].drive.frequency", "1e+300 Hz is outside 0.001 Hz to 1e+12 Hz"),
    ],
    # valid fields, but the derived parameters are outside the model (nondim.derive_file)
    "zero_amplitude.yaml": [(None, None, "", "u = interp(V; measured points) = 0.0")],
}
DERIVED = {"zero_amplitude.yaml"}


def test_every_fixture_has_a_case():
    fixtures = {p.name for p in SPECS.glob("*.yaml")} - {"valid_base.yaml"}
    assert fixtures == set(CASES)


def test_base_fixture_is_valid():
    assert load_device(SPECS / "valid_base.yaml").name == "bad"


@pytest.mark.parametrize("name", sorted(CASES))
def test_issue_positions_and_messages(name):
    with pytest.raises(SpecError) as exc:
        derive_file(SPECS / name)
    if name not in DERIVED:  # the loader alone finds it
        with pytest.raises(SpecError):
            load_device(SPECS / name)
    issues = exc.value.issues
    expected = CASES[name]
    assert len(issues) == len(expected), [str(i) for i in issues]
    for issue, (line, col, field, fragment) in zip(issues, expected, strict=True):
        assert issue.location.file == str(SPECS / name)
        assert (issue.location.line, issue.location.col) == (line, col), str(issue)
        assert issue.field == field, str(issue)
        assert fragment in issue.message, str(issue)
        prefix = ":".join(str(x) for x in (SPECS / name, line, col) if x is not None)
        assert str(issue).startswith(f"{prefix}: {field + ': ' if field else ''}")


@pytest.mark.parametrize("name", sorted(CASES))
def test_cli_exit_2_without_traceback(name):
    r = CliRunner().invoke(app, ["check", str(SPECS / name)])
    assert r.exit_code == 2
    assert r.stdout == ""
    assert "Traceback" not in r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == len(CASES[name])
    assert all(ln.startswith(f"error: {SPECS / name}") for ln in lines)


def test_issues_from_several_files_reported_together():
    files = [str(SPECS / "missing_unit.yaml"), str(SPECS / "duplicate_keys.yaml")]
    r = CliRunner().invoke(app, ["check", "--json", *files])
    assert r.exit_code == 2 and r.stdout == ""
    assert len(r.stderr.strip().splitlines()) == 3


def test_missing_file_and_directory():
    with pytest.raises(SpecError, match="file not found"):
        load_device(SPECS / "does_not_exist.yaml")
    with pytest.raises(SpecError, match="is a directory"):
        load_device(SPECS)


def test_published_fit_wrong_type_one_issue():
    text = (SPECS / "valid_base.yaml").read_text() + "published_fit:\n  beta: nine\n"
    with pytest.raises(SpecError) as exc:
        load_device_text(text, "x.yaml")
    (issue,) = exc.value.issues
    assert issue.field == "published_fit.beta"
    assert (issue.location.line, issue.location.col) == (25, 9)


def test_head_mass_and_geometry_exclusive():
    text = (
        (SPECS / "valid_base.yaml")
        .read_text()
        .replace(
            "      mass: 0.036 ug\n",
            "      mass: 0.036 ug\n"
            "      geometry: {shape: disc, diameter: 20 um, thickness: 2 um}\n",
        )
    )
    with pytest.raises(SpecError, match="exactly one of 'mass' or 'geometry'") as exc:
        load_device_text(text, "x.yaml")
    assert exc.value.issues[0].field == "actuator_sets[0].head"


@pytest.mark.parametrize(
    ("text", "line", "col", "field", "message"),
    [
        (
            "name: x\nslider: 5\nactuator_sets: []\n",
            2,
            9,
            "slider",
            "expected a mapping of fields, got 5",
        ),
        (
            "name: x\nslider: {}\nactuator_sets: {}\n",
            3,
            16,
            "actuator_sets",
            "expected a list, got a mapping",
        ),
        ("name: 3\n", 1, 7, "name", "expected a string, got 3"),
    ],
)
def test_wrong_yaml_types(text, line, col, field, message):
    with pytest.raises(SpecError) as exc:
        load_device_text(text, "t.yaml")
    hits = [i for i in exc.value.issues if i.field == field]
    assert hits and (hits[0].location.line, hits[0].location.col) == (line, col)
    assert hits[0].message == message


def test_anchors_and_merge_keys_build_mirrored_sets():
    text = (SPECS / "merge_key_error.yaml").read_text().replace("500 um", "500 Hz")
    spec = load_device_text(text, "m.yaml")
    right, left = spec.actuator_sets
    assert (right.name, left.name) == ("right", "left")
    assert left.impact_direction == "-x" and left.drive == right.drive


# --- numbers of too many digits (issue 24): refused at their line, before int() ---------

HUGE = "9" * 5000


@pytest.mark.parametrize(
    ("old", "new", "line", "col", "field", "digits"),
    [
        (
            "  travel_range: 40 um\n",
            f"  travel_range: 40 um\n  beam_count: {HUGE}\n",
            8,
            15,
            "slider.beam_count",
            5000,
        ),
        ("friction: 0.4", f"friction: {HUGE}", 15, 17, "actuator_sets[0].contact.friction", 5000),
        ("alpha: 0.1", f"alpha: 0.{HUGE}", 18, 14, "actuator_sets[0].actuator.alpha", 5001),
        ("alpha: 0.1", f'alpha: !!int "{HUGE}"', 18, 14, "actuator_sets[0].actuator.alpha", 5000),
    ],
    ids=["integer-beam_count", "integer-in-float-field", "float", "tagged-string"],
)
def test_number_of_too_many_digits_exits_2_at_its_line(
    tmp_path, old, new, line, col, field, digits
):
    """A 5000-digit number (Python's int() refuses more than 4300 digits with a
    ValueError) is refused by the YAML pre-pass at file:line:col, naming the field and
    the limit of spec.limits; the CLI exits 2 without a traceback."""
    from betvdesign.spec import limits

    text = (SPECS / "valid_base.yaml").read_text()
    assert old in text
    bad = tmp_path / "huge.yaml"
    bad.write_text(text.replace(old, new, 1))
    with pytest.raises(SpecError) as exc:
        load_device(bad)
    (issue,) = exc.value.issues
    assert (issue.location.line, issue.location.col, issue.field) == (line, col, field)
    assert issue.message == (
        f"number of {digits:,} digits; the limit is {limits.MAX_NUMBER_DIGITS} digits"
    )
    r = CliRunner().invoke(app, ["check", str(bad)])
    assert r.exit_code == 2 and r.stdout == ""
    assert "Traceback" not in r.stderr and "Exceeds the limit" not in r.stderr
    assert r.stderr.strip() == f"error: {bad}:{line}:{col}: {field}: {issue.message}"


def test_number_at_the_digit_limit_is_read():
    """A number of exactly the limit's digits is read as usual (then judged by its
    field: 100 digits of beam_count exceed 16)."""
    from betvdesign.spec import limits

    text = (SPECS / "valid_base.yaml").read_text()
    n = "0" * (limits.MAX_NUMBER_DIGITS - 1) + "2"
    spec = load_device_text(text.replace("  travel_range", f"  beam_count: {n}\n  travel_range"))
    assert spec.slider.beam_count == 2
    with pytest.raises(SpecError, match="less than or equal to 16"):
        load_device_text(
            text.replace("  travel_range", f"  beam_count: {'9' * 100}\n  travel_range")
        )


def test_quantity_number_digits_bounded(monkeypatch):
    """The number of a quantity string has the same digit limit (it binds when the
    quantity-string limit is raised above it)."""
    from betvdesign.spec import limits
    from betvdesign.spec.units import parse_quantity

    monkeypatch.setattr(limits, "MAX_QUANTITY_CHARS", 10_000)
    with pytest.raises(ValueError, match="number of 5,000 digits in a quantity"):
        parse_quantity(f"{HUGE} um")
    assert parse_quantity(f"{'1' * limits.MAX_NUMBER_DIGITS} um").magnitude > 0
    assert "number_digits" in limits.describe()


def test_limit_override_of_too_many_digits(monkeypatch):
    """$BETV_MAX_FILE_BYTES of 5000 digits: a UsageError naming the variable."""
    from betvdesign.errors import UsageError
    from betvdesign.spec import limits

    monkeypatch.setenv(limits.FILE_BYTES_ENV, HUGE)
    with pytest.raises(UsageError, match=r"BETV_MAX_FILE_BYTES: more than 100 digits"):
        limits.max_file_bytes()
