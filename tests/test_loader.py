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


def _positions(data, out):
    """Every mapping's and sequence's line, column and item positions, in order."""
    if hasattr(data, "lc"):
        out.append((type(data).__name__, data.lc.line, data.lc.col, dict(data.lc.data or {})))
    items = data.values() if isinstance(data, dict) else data if isinstance(data, list) else ()
    for v in items:
        _positions(v, out)
    return out


ROOT = DEVICES.parent
#: Every YAML file of the repository that decodes (not_utf8.yaml is refused before parsing).
YAML_FILES = sorted(
    p.relative_to(ROOT)
    for folder in ("devices", "betvdesign/data", "tests/data")
    for p in (ROOT / folder).rglob("*.yaml")
    if p.name != "not_utf8.yaml"
)


@pytest.mark.parametrize("path", YAML_FILES, ids=str)
def test_one_parse_gives_ruamels_load(path):
    """safeyaml.load (one parse, events checked as composed) gives ruamel's own round-trip
    load: the same data and the same positions, or the same error."""
    import warnings

    from ruamel.yaml import YAML
    from ruamel.yaml.error import YAMLError, YAMLWarning

    from betvdesign.spec import safeyaml
    from betvdesign.spec.loader import _plain

    text = safeyaml.read_text(ROOT / path)
    yaml = YAML(typ="rt")
    yaml.allow_duplicate_keys = True
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", YAMLWarning)
            want = yaml.load(text)
    except YAMLError as exc:
        with pytest.raises(type(exc)):
            safeyaml.load(text, str(path), allow_duplicate_keys=True)
        return
    _, got = safeyaml.load(text, str(path), allow_duplicate_keys=True)
    assert _plain(got) == _plain(want)
    assert _positions(got, []) == _positions(want, [])


def test_a_device_and_its_process_are_parsed_once_each(monkeypatch):
    """load_device reads the device file and the process file it names: two parses."""
    from ruamel.yaml.main import YAML

    from betvdesign.spec import loader

    parses = []
    original = YAML.get_constructor_parser

    def counting(self, stream):
        parses.append(stream[:40])
        return original(self, stream)

    monkeypatch.setattr(YAML, "get_constructor_parser", counting)
    loader._PROCESSES.clear()  # the process file is read afresh
    spec = loader.load_device(DEVICES / "push_demo.yaml")
    assert spec.process is not None
    assert len(parses) == 2
