"""The Python face: betvdesign.ureg, spec.replace (what-if validated like a file),
betvdesign.check, concise reprs. Truths: the device files themselves (a what-if edit
must equal editing the YAML by hand) and the loader's own messages."""

from pathlib import Path

import pint
import pytest

import betvdesign as bd
from betvdesign.errors import SpecError
from betvdesign.nondim.device import derive
from betvdesign.spec.loader import load_device_text

DEVICES = Path(__file__).resolve().parents[1] / "devices"
PUSH = DEVICES / "push_demo.yaml"


def test_ureg_is_the_package_registry_and_foreign_quantities_are_refused():
    from betvdesign.spec import units

    assert bd.ureg is units.ureg and bd.Quantity is units.ureg.Quantity
    spec = bd.load_device(PUSH)
    foreign = pint.UnitRegistry().Quantity(6, "um")
    with pytest.raises(SpecError, match=r"another pint registry; use betvdesign\.ureg"):
        spec.replace("slider.beam_width", foreign)
    assert spec.replace("slider.beam_width", bd.ureg.Quantity(6, "um")).slider.beam_width == (
        bd.ureg.Quantity(6, "um")
    )


def test_replace_equals_editing_the_file_by_hand():
    """The what-if spec derives exactly like the same change made in the YAML text."""
    spec = bd.load_device(PUSH)
    text = PUSH.read_text()
    cases = [
        ("slider.beam_width", "6 um", ("beam_width: 10 um", "beam_width: 6 um")),
        ("drive.frequency", "2.5 kHz", ("frequency: 3 kHz", "frequency: 2.5 kHz")),
        ("actuator_sets.forward.contact.friction", 0.3, ("friction: 0.4", "friction: 0.3")),
        ("actuator_sets.0.drive.voltage", "8 V", ("voltage: 9 V", "voltage: 8 V")),
    ]
    for path, value, (old, new) in cases:
        assert text.count(old) == 1
        by_hand = load_device_text(text.replace(old, new), "edited.yaml")
        what_if = spec.replace(path, value)
        assert what_if == by_hand, path
        assert derive(what_if).sets[0].params == derive(by_hand).sets[0].params
    assert spec == bd.load_device(PUSH)  # the original is untouched (frozen)


def test_replace_validates_like_the_loader():
    spec = bd.load_device(PUSH)
    for path, value, old, new in [
        ("slider.beam_width", "6 kg", "beam_width: 10 um", "beam_width: 6 kg"),
        ("drive.voltage", "12 V", "voltage: 9 V", "voltage: 12 V"),  # outside calibration
        ("contact.friction", "high", "friction: 0.4", "friction: high"),
    ]:
        with pytest.raises(SpecError) as by_hand:
            load_device_text(PUSH.read_text().replace(old, new), "edited.yaml")
        with pytest.raises(SpecError) as what_if:
            spec.replace(path, value)
        assert [(i.field, i.message) for i in what_if.value.issues] == [
            (i.field, i.message) for i in by_hand.value.issues
        ], path
    with pytest.raises(SpecError) as exc:
        spec.replace("slider.beam_width", "6 kg")
    (issue,) = exc.value.issues
    assert issue.field == "slider.beam_width" and "wrong dimension" in issue.message
    assert issue.location.line is None  # no line numbers of a generated file
    with pytest.raises(SpecError, match="must be > 0 V"):
        spec.replace("drive.voltage", "-3 V")
    with pytest.raises(SpecError, match="did you mean 'beam_width'"):
        spec.replace("slider.beam_widht", "6 um")
    with pytest.raises(SpecError, match="did you mean 'slider'"):
        spec.replace("slidr.beam_width", "6 um")
    with pytest.raises(SpecError, match="no actuator set 'nope'"):
        spec.replace("actuator_sets.nope.drive.voltage", "1 V")
    with pytest.raises(SpecError, match=r"exactly one|both|either"):
        spec.replace("head.mass", "0.006 ug")  # the file gives geometry: not both
    swapped = spec.replace("head.geometry", None, ("head.mass", "0.006 ug"))
    assert derive(swapped).sets[0].params.beta == pytest.approx(6e-12 / 1.165e-11, rel=0.01)


def test_check_in_python_and_reprs():
    spec = bd.load_device(PUSH)
    view = bd.check(spec.replace("drive.frequency", "2.5 kHz"))  # ϖ = 5 kHz / 5 kHz = 1
    assert view.verdict == "pass"
    text = repr(view)
    assert "f_act 5 kHz" in text and "ϖ 1 " in text and len(text.splitlines()) <= 15
    assert "<table>" in view._repr_html_()
    slow = bd.check(spec.replace("drive.frequency", "1 kHz"))  # ϖ = 0.4: below the window
    assert slow.verdict == "fail" and "frequency-window" in slow.failed
    assert bd.check(PUSH, ignore=["tangential-resonance"]).verdict == "pass"
    assert bd.check(PUSH, target_speed="10 mm/s").failed == ["target-speed"]
    with pytest.warns(UserWarning, match="matches no rule"):
        bd.check(PUSH, select=["no-such-rule"])


def test_report_repr_is_short(tmp_path):
    from betvdesign.report.model import Report

    r = Report(
        title="t",
        device_name="d<x>",
        description="",
        source_file="f.yaml",
        verdict="fail",
        inputs=(),
        sets=(),
        reproduce="",
        version="0",
    )
    assert repr(r) == "<Report d<x>: FAIL, 0 set(s), 0 figure(s), from f.yaml>"
    assert "d&lt;x&gt;" not in r._repr_html_() and "<b>t</b>" in r._repr_html_()


def test_check_options_refuse_bad_values_before_any_solve():
    """CheckOptions is checked when made: a speed without a speed unit, a horizon outside
    the CLI's range, an option that does not exist (no device is solved for these)."""
    from betvdesign.api import HORIZON_RANGE, CheckOptions
    from betvdesign.errors import UsageError

    with pytest.raises(UsageError, match="target_speed"):
        CheckOptions(target_speed="3 kHz")
    with pytest.raises(UsageError, match="horizon"):
        CheckOptions(horizon=HORIZON_RANGE[0] - 1)
    assert CheckOptions(target_speed="1 mm/s").target_speed_m_s == pytest.approx(1e-3)
    assert CheckOptions(select=["mode"]).select == ("mode",)  # hashable, frozen
    with pytest.raises(TypeError, match="no option"):
        bd.check(PUSH, horizn=5000)
