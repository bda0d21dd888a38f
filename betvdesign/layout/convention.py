"""The layout convention: how a GDS layout names its elements and carries the device data.

A designer who draws a vibromotor by hand (in KLayout, say) labels it the same way
``betv layout`` does, and ``betv check FILE.gds`` reads it (docs/layout.md):

**Element labels** (text on the process's ``annotation`` layer, e.g. 63/0 for
PolyMUMPs, placed *inside* the polygon they name, on the element's structural layer):

- ``slider.beam`` on every slider beam (their number is the beam count);
- ``slider.end`` on the two pieces joining the beams at their ends;
- ``slider.stop`` on the two anchored stops; the gaps between the ends and the stops,
  along the slider, add up to the travel range;
- ``SET.SIDE.PART`` for each actuator: SET the actuator set's name, SIDE ``lower`` or
  ``upper`` (the two symmetric actuators of a set), PART one of ``hot_arm``,
  ``cold_arm``, ``flexure``, ``tip``, ``head``, ``anchor_hot``, ``anchor_cold``.

**Data labels** ``PATH = VALUE`` anywhere on the annotation layer carry what a drawing
cannot show: ``process = polymumps`` (the process that gives the layers), ``name = …``,
``sets = [right, left]`` (the set order), device fields by their file path
(``slider.extra_mass = 0 ug``, ``published_fit.beta = [0.9, 9]``) and set fields as
``SET/PATH`` (``right/drive.frequency = 500 Hz``). VALUE is YAML (a quantity string, a
number, a list or mapping in flow style).

Drawn, never labelled: the beams' length, width, count and thickness (the layer's),
the travel range, each set's impact angle and direction, the head's size (a disc, or a
box) and the actuator's geometry (:class:`betvdesign.spec.models.ActuatorGeometry`).
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass
from typing import Any

from betvdesign.errors import BetvError

__all__ = [
    "ACTUATOR_PARTS",
    "ANCHOR_ENCLOSURE_FACTOR",
    "END_LENGTH",
    "SIDES",
    "SLIDER_PARTS",
    "STOP_SIZE",
    "DataLabel",
    "ElementLabel",
    "beam_gap",
    "cell_token",
    "data_labels",
    "flow",
    "parse_label",
]

SIDES = ("lower", "upper")
ACTUATOR_PARTS = ("hot_arm", "cold_arm", "flexure", "tip", "head", "anchor_hot", "anchor_cold")
SLIDER_PARTS = ("beam", "end", "stop")

#: Length of the slider's end pieces along the slider [µm] (they join the beams).
END_LENGTH = 10.0
#: Side of the slider's square travel stops [µm] (anchored).
STOP_SIZE = 20.0
#: An anchor opening is inset from its structural square by this many minimum widths.
ANCHOR_ENCLOSURE_FACTOR = 1.0


def beam_gap(min_spacing_um: float) -> float:
    """Gap between neighbouring slider beams [µm].

    10 µm, or the process's minimum spacing if larger (not in the device file: the
    model's M does not depend on it).

    Parameters
    ----------
    min_spacing_um : float
        The process's minimum spacing on the slider's layer [µm].

    Returns
    -------
    float
        The gap [µm].
    """
    return max(10.0, min_spacing_um)


@dataclass(frozen=True)
class ElementLabel:
    """``slider.PART`` (set_name None) or ``SET.SIDE.PART``."""

    set_name: str | None
    side: str | None
    part: str

    @property
    def text(self) -> str:
        """The element's label text as drawn in the layout."""
        if self.set_name is None:
            return f"slider.{self.part}"
        return f"{self.set_name}.{self.side}.{self.part}"


@dataclass(frozen=True)
class DataLabel:
    """``PATH = VALUE``: set_name None for device fields."""

    set_name: str | None
    path: str
    value: str

    @property
    def text(self) -> str:
        """The data label's text: ``set/path = value``."""
        where = f"{self.set_name}/" if self.set_name is not None else ""
        return f"{where}{self.path} = {self.value}"


_ELEMENT = re.compile(r"^(?:(?P<set>.+)\.(?P<side>lower|upper)|slider)\.(?P<part>[a-z_]+)$")
_DATA = re.compile(r"^(?:(?P<set>[^/=]+)/)?(?P<path>[A-Za-z_][A-Za-z0-9_.\[\]]*)\s*=\s*(?P<v>.*)$")


def parse_label(text: str) -> ElementLabel | DataLabel | None:
    """The meaning of a label's text.

    Parameters
    ----------
    text : str
        The label's text as drawn.

    Returns
    -------
    ElementLabel or DataLabel or None
        What it names (an element, or a data field and its value); None when it is not
        a betv label.
    """
    t = text.strip()
    m = _DATA.match(t)
    if m and "=" in t:
        return DataLabel(
            m.group("set").strip() if m.group("set") else None, m.group("path"), m.group("v")
        )
    m = _ELEMENT.match(t)
    if m:
        part = m.group("part")
        if m.group("set") is None:
            return ElementLabel(None, None, part) if part in SLIDER_PARTS else None
        if part in ACTUATOR_PARTS:
            return ElementLabel(m.group("set"), m.group("side"), part)
    return None


def check_set_name(name: str) -> None:
    """Check that a set name survives the labels.

    Parameters
    ----------
    name : str
        The actuator set's name.

    Raises
    ------
    BetvError
        For a name with '/', '=' or a newline, or the name 'slider'.
    """
    if any(c in name for c in "/=\n") or name.strip() != name or name == "slider":
        raise BetvError(
            f"actuator set name {name!r} cannot be written as a layout label: use one "
            "without '/', '=', line breaks or outer spaces, and not 'slider'"
        )


_PLAIN = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_ .+\-*/^()µ°]*$")


def flow(value: Any) -> str:
    """``value`` as one line of YAML (flow style): a data label's VALUE.

    Parameters
    ----------
    value : Any
        Plain data (a quantity as its string).

    Returns
    -------
    str
        One line of flow-style YAML.
    """
    if isinstance(value, bool):
        return "true" if value else "false"
    if value is None:
        return "null"
    if isinstance(value, int | float):
        return repr(value)
    if isinstance(value, str):
        plain = _PLAIN.match(value) and value.lower() not in ("true", "false", "null", "yes", "no")
        if plain and not re.fullmatch(r"[-+0-9.eE]+", value):
            return value
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k}: {flow(v)}" for k, v in value.items()) + "}"
    if isinstance(value, list | tuple):
        return "[" + ", ".join(flow(v) for v in value) + "]"
    raise TypeError(f"cannot write {type(value).__name__} in a label")


def _leaves(data: Any, path: str) -> list[tuple[str, Any]]:
    if isinstance(data, dict):
        out: list[tuple[str, Any]] = []
        for k, v in data.items():
            out += _leaves(v, f"{path}.{k}" if path else str(k))
        return out
    if isinstance(data, list) and data and all(isinstance(v, dict) for v in data):
        return [(f"{path}[{i}]", v) for i, v in enumerate(data)]
    return [(path, data)]


#: Fields the drawing gives (never labelled): device level, and below an actuator set.
DRAWN_DEVICE = {"slider.beam_length", "slider.beam_width", "slider.beam_thickness",
                "slider.beam_count", "slider.travel_range", "slider.layer", "process"}  # fmt: skip
DRAWN_SET = {"impact_direction", "head.mass", "head.geometry", "contact.impact_angle",
             "actuator.geometry"}  # fmt: skip


def _drawn(path: str, drawn: set[str]) -> bool:
    return any(path == d or path.startswith(d + ".") for d in drawn)


def data_labels(dump: dict[str, Any], process_ref: str) -> list[DataLabel]:
    """The data labels of a device: everything the drawing does not give.

    Parameters
    ----------
    dump : dict
        The device's ``model_dump(mode="json", exclude_unset=True)`` (quantities as
        strings).
    process_ref : str
        What the ``process = …`` label says.

    Returns
    -------
    list of DataLabel
        One label per field the drawing does not give.
    """
    out = [DataLabel(None, "process", flow(process_ref))]
    sets = dump.get("actuator_sets", [])
    out.append(DataLabel(None, "sets", flow([s["name"] for s in sets])))
    for path, v in _leaves({k: v for k, v in dump.items() if k != "actuator_sets"}, ""):
        if not _drawn(path, DRAWN_DEVICE):
            out.append(DataLabel(None, path, flow(v)))
    for s in sets:
        check_set_name(s["name"])
        for path, v in _leaves({k: v for k, v in s.items() if k != "name"}, ""):
            if not _drawn(path, DRAWN_SET):
                out.append(DataLabel(s["name"], path, flow(v)))
    return out


def cell_token(x_um: float) -> str:
    """A length for a cell name, to the nm: 2.5 -> '2p5', 170 -> '170'.

    Parameters
    ----------
    x_um : float
        The length [µm].

    Returns
    -------
    str
        The token (``p`` for the decimal point).
    """
    s = f"{round(x_um, 3):.3f}".rstrip("0").rstrip(".")
    return s.replace("-", "m").replace(".", "p")
