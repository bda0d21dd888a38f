"""A GDS layout back to a device file: ``betv check FILE.gds`` and ``betv extract``.

Reads the layout's top cell flattened (a file larger than :func:`max_gds_bytes` is
refused before reading), finds the ``process = …`` label (or takes ``process`` from the
caller), then reads the elements by their labels on the process's annotation layer
(:mod:`betvdesign.layout.convention`) and measures them:

- slider: the beams' length and width (every ``slider.beam`` the same rectangle), their
  number and layer (its thickness), the slider's axis; the travel range as the gaps along
  the axis between the two ``slider.end`` pieces and the two ``slider.stop`` posts;
- per set and side: the hot arm (its length is the actuator's, its long axis points
  to the tip), the flexure and cold arm (parallel, their lengths adding up to the hot
  arm's), the gap between the arms, the tip's length along the arms, the anchors' size,
  the head (a box if it fills its smallest rectangle, else a disc whose diameter is its
  extent); the stroke (across the arms toward the cold arm) gives the impact angle
  against the slider's axis and the impact direction; both sides of a set must agree.

Lengths are rounded to the process's grid, the angle to 1 µ°. The data labels supply
the rest; the result is validated as a device file, and every problem names the layout,
its cell, the layer and the label or element where it is.
"""

from __future__ import annotations

import itertools
import math
import os
from collections import defaultdict
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from pydantic import ValidationError
from ruamel.yaml import YAML

from betvdesign.errors import Location, ParameterError, SpecError, SpecIssue
from betvdesign.layout.convention import (
    ACTUATOR_PARTS,
    DataLabel,
    ElementLabel,
    parse_label,
)
from betvdesign.layout.drc import findings, layout_rules
from betvdesign.layout.shapes import Box, centroid, extent, min_box, span_along
from betvdesign.layout.write import gdstk_module
from betvdesign.model.frame import FrameGeometry
from betvdesign.nondim.device import derive
from betvdesign.nondim.record import DeviceDerivation
from betvdesign.spec.loader import load_device_text, resolve_process
from betvdesign.spec.models import DeviceSpec
from betvdesign.spec.process import Process

__all__ = ["GDS_BYTES_ENV", "Extracted", "derive_gds", "extract", "max_gds_bytes"]

GDS_BYTES_ENV = "BETV_MAX_GDS_BYTES"
#: Largest GDS file read by default (a vibromotor's layout is a few tens of kB).
MAX_GDS_BYTES = 50_000_000
#: Most polygons read from the flattened top cell.
MAX_POLYGONS = 200_000
#: Most vertices of one polygon read: the GDSII format's own limit (gdstk writes more).
#: The width and space checks are O(n log n), but the release check's inward offset
#: (Clipper, round joins) grows faster than n² with a polygon's vertices: 0.25 s CPU at
#: 5 500, 1.6 s at 11 000, 21 s at 22 000.
MAX_POLYGON_VERTICES = 8_190
#: Most vertices read from the flattened top cell, all layers together.
MAX_LAYOUT_VERTICES = 200_000
_REQUIRED = ("hot_arm", "cold_arm", "flexure", "tip", "head")
_TOL = 2.5e-3  # µm: lengths that must agree, agree to a few grid steps


def max_gds_bytes() -> int:
    """The GDS size limit [bytes] (``BETV_MAX_GDS_BYTES`` overrides it).

    Returns
    -------
    int
        The limit [bytes].
    """
    raw = os.environ.get(GDS_BYTES_ENV)
    try:
        return int(raw) if raw else MAX_GDS_BYTES
    except ValueError:
        return MAX_GDS_BYTES


@dataclass
class Extracted:
    """What a layout says: the device, notes and process rules.

    What a layout says: the device (``doc``, plain data as a device file holds it, and
    its validated ``spec``), notes (what was read but is not in the model), and the
    layout's process rules; :attr:`text` is the device file's text.
    """

    doc: dict
    spec: DeviceSpec
    process_ref: str
    cell: str
    path: Path
    notes: list[str] = field(default_factory=list)
    rules: list[Any] = field(default_factory=list)

    @property
    def text(self) -> str:
        """The device file (YAML) the layout makes."""
        return _yaml(self.doc, self.path)


class _Problems:
    def __init__(self, path: Path, cell: str = ""):
        self.path, self.cell, self.issues = path, cell, []

    def add(self, field_: str, message: str) -> None:
        where = f"cell {self.cell}: " if self.cell else ""
        self.issues.append(SpecIssue(Location(str(self.path)), field_, where + message))

    def raise_if_any(self) -> None:
        if self.issues:
            raise SpecError(self.issues)


def _xy(p: Any) -> str:
    return f"({p[0]:.3f}, {p[1]:.3f}) µm"


@dataclass
class _Element:
    label: ElementLabel
    at: tuple[float, float]
    layer: str
    gds: str
    points: np.ndarray

    @property
    def box(self) -> Box:
        return min_box(self.points)

    @property
    def where(self) -> str:
        return f"'{self.label.text}' at {_xy(self.at)} on {self.layer} ({self.gds})"


def _read(path: Path, probs: _Problems) -> Any:
    gdstk = gdstk_module()
    try:
        size = path.stat().st_size
    except OSError as exc:
        probs.add("", f"cannot read: {exc.strerror or exc}")
        probs.raise_if_any()
    cap = max_gds_bytes()
    if size > cap:
        probs.add("", f"{size:,} bytes; the limit is {cap:,} (set {GDS_BYTES_ENV} to raise it)")
        probs.raise_if_any()
    try:
        lib = gdstk.read_gds(str(path))
    except Exception as exc:  # gdstk raises plain errors on malformed streams
        probs.add("", f"not a readable GDSII file ({type(exc).__name__}: {exc})")
        probs.raise_if_any()
    tops = lib.top_level()
    if len(tops) != 1:
        names = ", ".join(sorted(c.name for c in tops)) or "none"
        probs.add("", f"expected one top cell, found {len(tops)} ({names})")
        probs.raise_if_any()
    return tops[0]


def _process(top: Any, labels: list, path: Path, given: str | None, probs: _Problems) -> tuple:
    refs = [(lab, parse_label(lab.text)) for lab in labels]
    found = [
        (lab, d) for lab, d in refs if isinstance(d, DataLabel) and d.set_name is None
        and d.path == "process"
    ]  # fmt: skip
    if given is None and not found:
        probs.add(
            "process",
            "no 'process = NAME' label in the layout (and no --process): label the layout "
            "with its process, e.g. 'process = polymumps', on its annotation layer",
        )
        probs.raise_if_any()
    ref = given if given is not None else str(YAML(typ="safe").load(found[0][1].value))
    try:
        proc = resolve_process(ref, path.parent)
    except SpecError as exc:
        probs.add("process", "; ".join(str(i) for i in exc.issues))
        probs.raise_if_any()
    return ref, proc


def _elements(
    top: Any, proc: Process, labels: list, probs: _Problems, gdstk: Any
) -> tuple[list[_Element], list[DataLabel], dict]:
    ann = proc.layers[proc.annotation].gds.pair
    structural = {
        lay.gds.pair: name for name, lay in proc.layers.items() if lay.role == "structural"
    }
    polys = top.get_polygons()
    if len(polys) > MAX_POLYGONS:
        probs.add("", f"{len(polys):,} polygons; at most {MAX_POLYGONS:,} are read")
        probs.raise_if_any()
    by_layer: dict[tuple[int, int], list] = defaultdict(list)
    for p in polys:
        by_layer[(p.layer, p.datatype)].append(p)
    _vertex_caps(by_layer, proc, probs)
    struct = [(structural[k], k, p) for k, ps in by_layer.items() if k in structural for p in ps]
    elements, data = [], []
    ann_txt = f"{ann[0]}/{ann[1]}"
    on_ann = [lab for lab in labels if (lab.layer, lab.texttype) == ann]
    if not any(isinstance(parse_label(lab.text), ElementLabel) for lab in on_ann):
        probs.add(
            "",
            f"no element labels on the annotation layer {proc.annotation} ({ann_txt}): label "
            "the slider's beams, ends and stops and each actuator's parts (docs/layout.md)",
        )
        probs.raise_if_any()
    pts_all = [np.asarray(p.points) for _, _, p in struct]
    used: dict[int, str] = {}
    for lab in on_ann:
        meaning = parse_label(lab.text)
        if isinstance(meaning, DataLabel):
            data.append(meaning)
            continue
        if meaning is None:
            continue
        at = (float(lab.origin[0]), float(lab.origin[1]))
        hits = [
            i for i, (_, _, p) in enumerate(struct) if gdstk.inside([at], p)[0]
        ]  # fmt: skip
        what = f"label '{lab.text}' at {_xy(at)} on {proc.annotation} ({ann_txt})"
        if not hits:
            layers = ", ".join(f"{n} ({a}/{b})" for (a, b), n in structural.items())
            probs.add("", f"{what} lies on no polygon of a structural layer ({layers})")
            continue
        if len(hits) > 1:
            lay = ", ".join(f"{struct[i][0]}" for i in hits)
            probs.add("", f"{what} lies on {len(hits)} overlapping polygons ({lay}): overlapping "
                      "elements")  # fmt: skip
            continue
        i = hits[0]
        if i in used:
            probs.add("", f"{what} names the polygon already labelled '{used[i]}'")
            continue
        used[i] = lab.text
        name, k, _ = struct[i]
        elements.append(_Element(meaning, at, name, f"{k[0]}/{k[1]}", pts_all[i]))
    seen: dict[str, _Element] = {}
    for e in elements:  # one polygon per actuator part (slider parts repeat)
        if e.label.set_name is not None and e.label.text in seen:
            probs.add(
                f"actuator_sets.{e.label.set_name}",
                f"two '{e.label.text}' labels ({seen[e.label.text].where} and at {_xy(e.at)}):"
                f" one {e.label.part} per actuator",
            )
        seen.setdefault(e.label.text, e)
    probs.raise_if_any()
    _overlaps(elements, probs, gdstk)
    probs.raise_if_any()
    free = len(struct) - len(used)
    if free:
        data.append(DataLabel(None, "_unlabelled", str(free)))
    return elements, data, by_layer


def _vertex_caps(by_layer: dict[tuple[int, int], list], proc: Process, probs: _Problems) -> None:
    """Refuse a polygon or a layout with too many vertices, before any geometry runs.

    A polygon over :data:`MAX_POLYGON_VERTICES` or a layout over
    :data:`MAX_LAYOUT_VERTICES` vertices is refused, naming its layer (and the polygon's
    place): the checks are O(n log n), but the layer's boolean operations and the
    extraction's measures still grow with it.
    """
    names = {lay.gds.pair: name for name, lay in proc.layers.items()}

    def layer(k: tuple[int, int]) -> str:
        return f"{names[k]} ({k[0]}/{k[1]})" if k in names else f"layer {k[0]}/{k[1]}"

    per_layer = {}
    for k, ps in sorted(by_layer.items()):
        sizes = [len(p.points) for p in ps]
        per_layer[k] = sum(sizes)
        worst = max(range(len(ps)), key=lambda i: sizes[i])
        if sizes[worst] > MAX_POLYGON_VERTICES:
            (x0, y0), (x1, y1) = ps[worst].bounding_box()
            probs.add(
                "",
                f"a polygon on {layer(k)} at ({(x0 + x1) / 2:.3f}, {(y0 + y1) / 2:.3f}) µm has "
                f"{sizes[worst]:,} vertices; at most {MAX_POLYGON_VERTICES:,} are read per "
                "polygon (the GDSII format's limit): split it or draw it with fewer vertices",
            )
    total = sum(per_layer.values())
    if total > MAX_LAYOUT_VERTICES:
        most = max(per_layer, key=lambda k: per_layer[k])
        probs.add(
            "",
            f"{total:,} vertices in the layout ({per_layer[most]:,} on {layer(most)}); at most "
            f"{MAX_LAYOUT_VERTICES:,} are read",
        )
    probs.raise_if_any()


def _overlaps(elements: list[_Element], probs: _Problems, gdstk: Any) -> None:
    """Check that labelled elements on one layer do not overlap.

    Two labelled elements on one layer may touch but not overlap, except an actuator's
    head and its tip (the head is drawn over half the tip).
    """
    boxes = [(e, e.points.min(axis=0), e.points.max(axis=0)) for e in elements]
    for i, (a, alo, ahi) in enumerate(boxes):
        for b, blo, bhi in boxes[i + 1 :]:
            if a.layer != b.layer or np.any(alo >= bhi) or np.any(blo >= ahi):
                continue
            la, lb = a.label, b.label
            same = la.set_name is not None and (la.set_name, la.side) == (lb.set_name, lb.side)
            if same and {la.part, lb.part} == {"head", "tip"}:
                continue
            inter = gdstk.boolean(
                gdstk.Polygon(a.points), gdstk.Polygon(b.points), "and", precision=1e-3
            )
            # deeper than two grid steps: not the rounding of two abutting edges
            inter = [p for p in inter if gdstk.offset([p], -2e-3, precision=1e-3)]
            ar = sum(abs(p.area()) for p in inter)
            if inter:
                c = centroid(np.asarray(inter[0].points))
                probs.add("", f"elements {a.where} and '{lb.text}' overlap ({ar:.3g} µm² at "
                          f"{_xy(c)}): draw them side by side")  # fmt: skip


def _g(x: float, grid: float) -> float:
    return round(round(x / grid) * grid, 9)


def _q(x_um: float, grid_um: float) -> str:
    return f"{_g(x_um, grid_um):.10g} um"


def _rect(e: _Element, probs: _Problems) -> Box:
    b = e.box
    if abs(b.fill - 1) > 1e-4:
        probs.add("", f"{e.where} is not a rectangle (it fills {b.fill:.1%} of its box)")
    if b.width <= 0:
        probs.add("", f"{e.where} has zero width")
    return b


def _slider(els: list[_Element], grid: float, probs: _Problems) -> dict:
    beams = [e for e in els if e.label.part == "beam"]
    ends = [e for e in els if e.label.part == "end"]
    stops = [e for e in els if e.label.part == "stop"]
    if not beams:
        probs.add("slider", "no 'slider.beam' label: label every slider beam")
        probs.raise_if_any()
    boxes = [_rect(e, probs) for e in beams]
    probs.raise_if_any()
    L, w = boxes[0].length, boxes[0].width
    for e, b in zip(beams[1:], boxes[1:], strict=True):
        if abs(b.length - L) > _TOL or abs(b.width - w) > _TOL:
            probs.add("slider", f"{e.where} is {b.length:.4g} × {b.width:.4g} µm, the first beam "
                      f"{L:.4g} × {w:.4g} µm: the model's beams are equal")  # fmt: skip
    axis = boxes[0].axis
    for e, b in zip(beams, boxes, strict=True):
        if abs(abs(float(b.axis @ axis)) - 1) > 1e-9:
            probs.add("slider", f"{e.where} is not parallel to the first beam")
    layers = {e.layer for e in beams}
    if len(layers) > 1:
        probs.add("slider.layer", f"slider beams on several layers ({', '.join(sorted(layers))})")
    if len(ends) != 2 or len(stops) != 2:
        probs.add(
            "slider.travel_range",
            f"found {len(ends)} 'slider.end' and {len(stops)} 'slider.stop' labels; the "
            "travel range is drawn by two ends and two stops",
        )
    probs.raise_if_any()
    centre = np.mean([b.centre for b in boxes], axis=0)
    travel = 0.0
    for st in stops:
        s_lo, s_hi = span_along(st.points, axis)
        near = min(ends, key=lambda e: abs(np.mean(span_along(e.points, axis)) - (s_lo + s_hi) / 2))
        e_lo, e_hi = span_along(near.points, axis)
        gap = s_lo - e_hi if (s_lo + s_hi) / 2 > (e_lo + e_hi) / 2 else e_lo - s_hi
        if gap <= 0:
            probs.add("slider.travel_range", f"stop {st.where} does not stand clear of the end "
                      f"{near.where}")  # fmt: skip
        travel += gap
    return {
        "beam_length": _q(L, grid),
        "beam_width": _q(w, grid),
        "beam_count": len(beams),
        "travel_range": _q(travel, grid),
        "_layer": beams[0].layer,
        "_axis": axis,
        "_centre": centre,
    }


@dataclass
class _Actuator:
    geometry: dict
    theta_deg: float
    direction: str
    head: dict
    layer: str
    head_offset: float


def _actuator(
    set_name: str, side: str, parts: dict[str, _Element], slider: dict, grid: float,
    probs: _Problems,
) -> _Actuator | None:  # fmt: skip
    tag = f"set {set_name}, {side}"
    missing = [p for p in _REQUIRED if p not in parts]
    if missing:
        probs.add(f"actuator_sets.{set_name}", f"{tag}: no label for {', '.join(missing)} "
                  f"(label '{set_name}.{side}.PART' on each part)")  # fmt: skip
        return None
    layers = {e.layer for e in parts.values()}
    if len(layers) > 1:
        probs.add(f"actuator_sets.{set_name}", f"{tag}: parts on several layers "
                  f"({', '.join(sorted(layers))})")  # fmt: skip
        return None
    hot, flex, cold, tip = (
        _rect(parts[p], probs) for p in ("hot_arm", "flexure", "cold_arm", "tip")
    )
    if probs.issues:
        return None
    a = hot.axis if float((tip.centre - hot.centre) @ hot.axis) > 0 else -hot.axis
    s = np.array([-a[1], a[0]])
    if float((cold.centre - hot.centre) @ s) < 0:
        s = -s
    for name, b in (("flexure", flex), ("cold_arm", cold)):
        if abs(abs(float(b.axis @ a)) - 1) > 1e-9:
            probs.add(f"actuator_sets.{set_name}", f"{tag}: the {name} is not parallel to the "
                      "hot arm")  # fmt: skip
    L, Lf, Lc = hot.length, flex.length, cold.length
    if abs(Lf + Lc - L) > _TOL:
        probs.add(f"actuator_sets.{set_name}", f"{tag}: flexure ({Lf:.4g} µm) and cold arm "
                  f"({Lc:.4g} µm) do not add up to the hot arm ({L:.4g} µm)")  # fmt: skip
    gap = float((cold.centre - hot.centre) @ s) - (hot.width + cold.width) / 2
    lo, hi = span_along(parts["tip"].points, a)
    tip_len = hi - lo
    geo = {
        "length": _q(L, grid),
        "hot_arm_width": _q(hot.width, grid),
        "cold_arm_width": _q(cold.width, grid),
        "flexure_length": _q(Lf, grid),
        "flexure_width": _q(flex.width, grid),
        "gap": _q(gap, grid),
        "tip_length": _q(tip_len, grid),
    }
    anchors = [parts[p] for p in ("anchor_hot", "anchor_cold") if p in parts]
    if anchors:
        sizes = [max(_rect(e, probs).length, e.box.width) for e in anchors]
        geo["anchor_size"] = _q(max(sizes), grid)
    hp = parts["head"].points
    hb = min_box(hp)
    hc = centroid(hp)
    if abs(hb.fill - 1) <= 1e-4:
        along = abs(float(hb.axis @ a))
        hl, hw = (hb.length, hb.width) if along > 0.5 else (hb.width, hb.length)
        head = {"shape": "box", "length": _q(hl, grid), "width": _q(hw, grid)}
        r_x = hl / 2
    else:
        r = extent(hp) / 2
        head = {"shape": "disc", "diameter": _q(2 * r, grid)}
        r_x = r
    # the stroke against the slider
    u = slider["_axis"]
    n = np.array([-u[1], u[0]])
    if float((slider["_centre"] - hc) @ n) < 0:
        n = -n
    if float(s @ n) <= 0:
        probs.add(f"actuator_sets.{set_name}", f"{tag}: the stroke (across the arms toward the "
                  "cold arm) points away from the slider")  # fmt: skip
        return None
    cos_t = abs(float(s @ u))
    theta = math.degrees(math.acos(min(1.0, cos_t)))
    direction = "+x" if float(s @ u) > 0 else "-x"
    # the head's centre against betv's convention (it sets the springs)
    origin = hot.centre - a * (L / 2)
    x_l, y_l = float((hc - origin) @ a), float((hc - origin) @ s)
    g = FrameGeometry(L, hot.width, cold.width, Lf, flex.width, gap, tip_len, 1.0, 1.0, r_x)
    ex, ey = g.head_centre
    off = math.hypot(x_l - ex, y_l - ey)
    return _Actuator(geo, round(theta, 6), direction, head, parts["hot_arm"].layer, off)


def _set_path(data: dict, path: str, value: Any) -> None:
    """Put ``value`` at a dotted path with [i] indices into nested dicts/lists."""
    keys: list[Any] = []
    for part in path.split("."):
        name, _, rest = part.partition("[")
        keys.append(name)
        while rest:
            idx, _, rest = rest.partition("]")
            keys.append(int(idx))
            rest = rest.lstrip("[")
    node: Any = data
    for k, nxt in itertools.pairwise(keys):
        if isinstance(k, int):
            while len(node) <= k:
                node.append({} if not isinstance(nxt, int) else [])
            node = node[k]
        else:
            if k not in node:
                node[k] = [] if isinstance(nxt, int) else {}
            node = node[k]
    last = keys[-1]
    if isinstance(last, int):
        while len(node) <= last:
            node.append(None)
    node[last] = value


def _actuator_sets(
    elements: list[_Element], sl: dict, grid: float, probs: _Problems, notes: list[str]
) -> dict[str, _Actuator]:
    """Group the labelled actuator parts into sets, each measured on its first side.

    The two sides of a set must agree (the model's sets are symmetric).

    Parameters
    ----------
    elements : list of _Element
        The labelled elements of the layout.
    sl : dict
        The slider, measured (:func:`_slider`).
    grid : float
        The process's grid [µm].
    probs : _Problems
        The problems found (added to; raised when no actuator is labelled).
    notes : list of str
        Notes on what was read but is not in the model (added to).

    Returns
    -------
    dict of str to _Actuator
        The actuator of each set, by name.
    """
    groups: dict[str, dict[str, dict[str, _Element]]] = defaultdict(lambda: defaultdict(dict))
    for e in elements:
        lab = e.label
        if lab.set_name is None:
            continue
        groups[lab.set_name][lab.side][lab.part] = e
    if not groups:
        probs.add("actuator_sets", "no actuator labels ('SET.lower.hot_arm', …): label each "
                  f"actuator's parts {', '.join(ACTUATOR_PARTS)}")  # fmt: skip
        probs.raise_if_any()
    acts: dict[str, _Actuator] = {}
    for name, sides in groups.items():
        got = {side: _actuator(name, side, parts, sl, grid, probs) for side, parts in sides.items()}
        got = {k: v for k, v in got.items() if v is not None}
        if not got:
            continue
        first_side, first = next(iter(got.items()))
        for side, other in got.items():
            diff = [k for k in first.geometry if first.geometry[k] != other.geometry.get(k)]
            if first.head != other.head:
                diff.append("head")
            if abs(first.theta_deg - other.theta_deg) > 1e-6 or first.direction != other.direction:
                diff.append("impact angle or direction")
            if diff:
                probs.add(
                    f"actuator_sets.{name}",
                    f"set {name}: the {first_side} and {side} actuators differ "
                    f"({', '.join(diff)}); the model's sets are symmetric",
                )
        if first.head_offset > 10 * grid:
            notes.append(
                f"set {name}: the head's centre lies {first.head_offset:.3g} µm from where betv "
                "draws it (half the tip inside it, at the tip's mid-height); the springs use "
                "betv's position"
            )
        acts[name] = first
    return acts


def extract(path: str | os.PathLike[str], *, process: str | None = None) -> Extracted:
    """Read a GDS layout into a device (module doc).

    Parameters
    ----------
    path : path
        The GDS file.
    process : str, optional
        A process (shipped name or file) instead of the one the layout's label names.

    Returns
    -------
    Extracted
        The device, the notes on what was read but is not in the model, and the
        layout's process rules.

    Raises
    ------
    SpecError
        Naming the file, cell, layer and label of every problem.
    """
    gdstk = gdstk_module()
    path = Path(path)
    probs = _Problems(path)
    top = _read(path, probs)
    probs.cell = top.name
    labels = top.get_labels()
    ref, proc = _process(top, labels, path, process, probs)
    grid = float(proc.grid.to("um").magnitude)
    elements, data, by_layer = _elements(top, proc, labels, probs, gdstk)
    notes: list[str] = []
    for d in [d for d in data if d.path == "_unlabelled"]:
        data.remove(d)
        notes.append(
            f"{d.value} polygon(s) of a structural layer carry no label: not part of the "
            "model (the process rules check them all)"
        )
    slider_els = [e for e in elements if e.label.set_name is None]
    sl = _slider(slider_els, grid, probs)
    acts = _actuator_sets(elements, sl, grid, probs, notes)
    probs.raise_if_any()
    doc, where = _document(data, sl, acts, proc, ref, path, probs)
    probs.raise_if_any()
    try:  # the common case without a round trip through YAML text
        spec = DeviceSpec.model_validate({**doc, "process": proc})
    except ValidationError:  # the device file's own messages, located in the layout
        try:
            load_device_text(_yaml(doc, path), str(path))
        except SpecError as exc:
            raise SpecError([_relocate(i, where, path, top.name) for i in exc.issues]) from None
        raise
    f = findings(gdstk, proc, by_layer)
    rules = layout_rules(spec, f, top.name)
    return Extracted(doc, spec, ref, top.name, path, notes, rules)


def _document(
    data: list[DataLabel], sl: dict, acts: dict[str, _Actuator], proc: Process, ref: str,
    path: Path, probs: _Problems,
) -> tuple[dict, dict[str, str]]:  # fmt: skip
    yaml = YAML(typ="safe")
    dev: dict[str, Any] = {}
    sets_data: dict[str, dict] = defaultdict(dict)
    where: dict[str, str] = {}
    order: list[str] | None = None
    for d in data:
        try:
            value = yaml.load(d.value) if d.value.strip() else None
        except Exception as exc:  # ruamel's YAML errors
            probs.add(d.path, f"label '{d.text}': its value is not YAML ({exc})".split("\n")[0])
            continue
        if d.set_name is None and d.path == "process":
            continue
        if d.set_name is None and d.path == "sets":
            order = [str(v) for v in value] if isinstance(value, list) else None
            continue
        target = dev if d.set_name is None else sets_data[d.set_name]
        try:
            _set_path(target, d.path, value)
        except (TypeError, IndexError, AttributeError):
            probs.add(d.path, f"label '{d.text}': its path clashes with another label")
            continue
        key = d.path if d.set_name is None else f"{d.set_name}/{d.path}"
        where[key] = f"label '{d.text}'"
    names = order or sorted(acts)
    unknown = [n for n in sets_data if n not in acts]
    for n in unknown:
        probs.add(f"actuator_sets.{n}", f"data labels for set {n!r}, which has no drawn actuator")
    missing = [n for n in acts if n not in names]
    names = [n for n in names if n in acts] + missing
    lay = proc.structural(sl["_layer"])
    t = lay.thickness
    slider = {k: v for k, v in sl.items() if not k.startswith("_")}
    slider["beam_thickness"] = f"{float(t.to('um').magnitude):.10g} um"
    if sl["_layer"] != proc.default_structural:
        slider["layer"] = sl["_layer"]
    slider.update(dev.pop("slider", {}))
    out: dict[str, Any] = {"name": dev.pop("name", path.stem)}
    out.update({k: v for k, v in dev.items() if k in ("description", "material")})
    out["process"] = ref
    out["slider"] = slider
    sets = []
    for n in names:
        a = acts[n]
        s = sets_data.get(n, {})
        tl = proc.structural(a.layer).thickness
        head = s.pop("head", {})
        head["geometry"] = {**a.head, "thickness": f"{float(tl.to('um').magnitude):.10g} um"}
        contact = s.pop("contact", {})
        contact["impact_angle"] = f"{a.theta_deg:.10g} deg"
        actuator = s.pop("actuator", {})
        geo = dict(a.geometry)
        if a.layer != proc.default_structural:
            geo["layer"] = a.layer
        actuator["geometry"] = geo
        entry = {"name": n, **{k: v for k, v in s.items() if k == "intended_mode"}}
        entry["impact_direction"] = a.direction
        entry.update({"head": head, "contact": contact, "actuator": actuator})
        entry.update({k: v for k, v in s.items() if k != "intended_mode"})
        sets.append(entry)
    out["actuator_sets"] = sets
    out.update({k: v for k, v in dev.items() if k not in ("description", "material")})
    return out, where


def _yaml(doc: dict, path: Path) -> str:
    import io

    yaml = YAML(typ="rt")
    yaml.width = 100
    buf = io.StringIO()
    yaml.dump(doc, buf)
    return f"# Extracted from {path.name} by `betv extract` (betvdesign)\n" + buf.getvalue()


def _relocate(issue: SpecIssue, where: dict[str, str], path: Path, cell: str) -> SpecIssue:
    """A validation issue of the extracted file, located in the layout."""
    f = issue.field
    best = ""
    for key in where:
        k = key.split("/", 1)[1] if "/" in key else key
        if f.endswith(k) and len(key) > len(best):
            best = key
    src = where.get(best, "the drawn elements")
    return SpecIssue(Location(str(path)), f, f"cell {cell}: {src}: {issue.message}")


def derive_gds(
    path: str | os.PathLike[str], *, process: str | None = None
) -> tuple[DeviceDerivation, Extracted]:
    """Extract a layout and derive it.

    As :func:`betvdesign.nondim.device.derive_file` does a device file.

    Parameters
    ----------
    path : path
        The GDS file.
    process : str, optional
        A process instead of the one the layout names.

    Returns
    -------
    tuple of (DeviceDerivation, Extracted)
        The derivation and what the layout says.

    Raises
    ------
    SpecError
        For every problem, naming the layout.
    """
    ex = extract(path, process=process)
    try:
        return derive(ex.spec), ex
    except ParameterError as exc:
        raise SpecError(
            [SpecIssue(Location(str(path)), "", f"derived parameters outside the model: {exc}")]
        ) from None
