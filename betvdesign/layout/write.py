"""``betv layout``: a device file drawn as a GDS mask layout on its process's layers.

The drawing (µm, 1 nm grid; :mod:`betvdesign.layout.convention` for the labels):

- the slider, centred on the origin along x: ``beam_count`` beams of the file's length
  and width, :func:`~betvdesign.layout.convention.beam_gap` apart, joined at both ends by
  end pieces :data:`~betvdesign.layout.convention.END_LENGTH` long; two anchored stops
  beyond the ends, each half the travel range away;
- per actuator set, two actuators mirrored about the slider's axis (``lower``,
  ``upper``), each the drawn actuator of :func:`betvdesign.model.frame.shape` (arms,
  flexure, tip, head, anchors with their anchor openings and metal pads) placed so that
  its stroke makes the impact angle with the slider and points along the impact
  direction, its head the process's minimum spacing from the slider (the model takes the
  head touching the slider at rest; the process cannot draw a smaller gap). Sets that
  strike toward +x stand at +x, the others at −x, so their bodies point away from
  each other;
- release holes in every released feature wider than the process frees without them
  (a square lattice at the pitch that leaves no point farther than half that width from
  an edge, :func:`betvdesign.checks.process_rules.release_pitch`), verified by erosion;
- a label naming every element and data labels for what the drawing cannot show.

One cell per distinct actuator (placed by references at the impact angle), one for the
slider; cell names encode the drawn parameters. Same input, same bytes (a fixed
timestamp). A head given by its mass is drawn as the disc of that mass in the layer.
"""

from __future__ import annotations

import datetime
import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from betvdesign.checks.process_rules import release_pitch
from betvdesign.errors import BetvError
from betvdesign.layout.convention import (
    ANCHOR_ENCLOSURE_FACTOR,
    END_LENGTH,
    STOP_SIZE,
    ElementLabel,
    beam_gap,
    cell_token,
    check_set_name,
    data_labels,
)
from betvdesign.model.frame import DISC_VERTICES, FrameGeometry, Rect, contact_offset, shape
from betvdesign.nondim.actuator import frame_geometry
from betvdesign.output.files import atomic_path
from betvdesign.spec.models import DeviceSpec
from betvdesign.spec.process import Process, ProcessLayer

__all__ = [
    "TIMESTAMP",
    "Placement",
    "build_library",
    "gdstk_module",
    "write_layout",
]

#: The timestamp written into every GDS (same input, same bytes).
TIMESTAMP = datetime.datetime(2004, 1, 1)
_UM = 1e6


def gdstk_module():
    """The gdstk module, or a clear error naming the extra to install.

    Returns
    -------
    module
        gdstk.

    Raises
    ------
    BetvError
        When gdstk is not installed.
    """
    try:
        import gdstk
    except ImportError:
        raise BetvError("layouts need gdstk: pip install 'betvdesign[layout]'") from None
    return gdstk


def _um(q: Any) -> float:
    return float(q.to("um").magnitude)


def _g(x: float) -> float:
    """A coordinate on the 1 nm grid [µm]."""
    return round(x, 3) + 0.0


@dataclass(frozen=True)
class Placement:
    """Where one actuator stands: local (x, y) [µm] -> M·(x, y) + t.

    Where one actuator stands: local (x, y) [µm] -> M·(x, y) + t; ``rotation`` [rad] and
    ``x_reflection`` are the same map as a GDS reference.
    """

    set_name: str
    side: str
    matrix: tuple[tuple[float, float], tuple[float, float]]
    t: tuple[float, float]
    rotation: float
    x_reflection: bool

    def apply(self, x: float, y: float) -> tuple[float, float]:
        """Map the local point (x, y) [µm] to the layout: M·(x, y) + t [µm]."""
        (a, b), (c, d) = self.matrix
        return (a * x + b * y + self.t[0], c * x + d * y + self.t[1])


def _placement(
    set_name: str, side: str, theta: float, sx: int, head: tuple[float, float],
    h_max: float, slider_half: float, clearance: float, x_head: float,
) -> Placement:  # fmt: skip
    """The map of one actuator (module doc).

    The map of one actuator (module doc): its stroke (local y) at θ from the slider,
    along the impact direction sx, toward the slider from the lower (sy = +1) or upper
    (sy = −1) side; its highest point (toward the slider) ``clearance`` from it.
    """
    sy = 1 if side == "lower" else -1
    s, c = math.sin(theta), math.cos(theta)
    m = ((sx * -s, sx * c), (sy * c, sy * s))
    rot = math.atan2(m[1][0], m[0][0])
    refl = sx * sy > 0  # det M = −sx·sy < 0: a reflection
    px, py = head
    ty = -sy * (slider_half + clearance + h_max)
    tx = x_head - (m[0][0] * px + m[0][1] * py)
    return Placement(set_name, side, m, (_g(tx), _g(ty)), rot, refl)


def _toward(c: float, v: np.ndarray) -> np.ndarray:
    """Coordinates c + v rounded to the 1 nm grid toward c."""
    x = (c + v) * 1000
    return np.where(v > 0, np.floor(x + 1e-6), np.ceil(x - 1e-6)) / 1000


def _disc(cx: float, cy: float, r: float) -> np.ndarray:
    """A disc whose extent (centre ± r) lies on the grid.

    A disc whose extent (centre ± r) lies on the grid: the vertices on the axes exact,
    every other rounded toward the centre (none outside the circle: the drawn diameter is
    the extent).
    """
    a = 2 * math.pi * np.arange(DISC_VERTICES) / DISC_VERTICES
    dx, dy = r * np.cos(a), r * np.sin(a)
    dx[np.abs(dx) < 1e-12] = 0.0
    dy[np.abs(dy) < 1e-12] = 0.0
    return np.column_stack([_toward(cx, dx), _toward(cy, dy)])


def _rect(x0: float, y0: float, x1: float, y1: float) -> np.ndarray:
    return np.round(np.array([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], dtype=float), 3)


def _shared_vertices(polys: list[np.ndarray]) -> list[np.ndarray]:
    """Insert into each polygon the vertices of the others on its edges.

    Each polygon with the vertices of the others that lie on its edges inserted, so that
    abutting elements share their boundary vertex for vertex: a reader that rounds a
    rotated cell to its grid then rounds both sides alike (no sliver between them).
    """
    every = np.concatenate(polys)
    out = []
    for p in polys:
        pts: list[np.ndarray] = []
        for a, b in zip(p, np.roll(p, -1, axis=0), strict=True):
            pts.append(a)
            ab = b - a
            n2 = float(ab @ ab)
            rel = every - a
            t = rel @ ab / n2
            cross = np.abs(rel[:, 0] * ab[1] - rel[:, 1] * ab[0]) / math.sqrt(n2)
            on = (t > 1e-9) & (t < 1 - 1e-9) & (cross < 1e-9)
            for k in np.argsort(t[on]):
                q = every[on][k]
                if not pts or np.any(np.abs(q - pts[-1]) > 1e-12):
                    pts.append(q)
        out.append(np.array(pts))
    return out


def _inside_convex(points: np.ndarray, poly: np.ndarray) -> np.ndarray:
    """Points (n, 2) inside a counter-clockwise convex polygon (boundary counts)."""
    e = np.roll(poly, -1, axis=0) - poly
    rel = points[:, None, :] - poly[None, :, :]
    cross = e[None, :, 0] * rel[:, :, 1] - e[None, :, 1] * rel[:, :, 0]
    return np.all(cross >= -1e-9, axis=1)


def _holes(poly: np.ndarray, layer: ProcessLayer, gdstk: Any) -> list[np.ndarray]:
    """Square etch holes in a convex feature so that it is released (module doc)."""
    h = layer.release_holes
    assert h is not None and layer.min_width is not None
    w_max = _um(layer.max_unreleased_width)
    size, margin = _um(h.size), _um(layer.min_width)
    if _released([poly], [], w_max, gdstk):
        return []
    pitch = release_pitch(layer)
    lo, hi = poly.min(axis=0), poly.max(axis=0)
    centre = (lo + hi) / 2
    for _ in range(8):
        nx = int((hi[0] - lo[0]) / pitch) + 2
        ny = int((hi[1] - lo[1]) / pitch) + 2
        out = []
        for j in range(-ny, ny + 1):
            for i in range(-nx, nx + 1):
                x, y = centre[0] + i * pitch, centre[1] + j * pitch
                k = size / 2 + margin
                corners = np.array([(x - k, y - k), (x + k, y - k), (x + k, y + k), (x - k, y + k)])
                if np.all(_inside_convex(corners, poly)):
                    out.append(_rect(x - size / 2, y - size / 2, x + size / 2, y + size / 2))
        if _released([poly], out, w_max, gdstk):
            return out
        pitch *= 0.85
    raise BetvError(
        f"cannot place release holes in a feature {hi[0] - lo[0]:.3g} × {hi[1] - lo[1]:.3g} µm "
        "(too narrow for holes with the minimum width around them, too wide to release)"
    )


def _fill_release(
    polys: list[np.ndarray], holes: list[np.ndarray], anchors: list[np.ndarray],
    layer: ProcessLayer, gdstk: Any,
) -> list[np.ndarray]:  # fmt: skip
    """More release holes where joined elements still leave unreleased points.

    More holes where the joined elements (a beam and its end piece, a head and its tip)
    still leave a point farther than half the widest unreleased feature from every edge:
    a hole at the middle of each such region, until none is left.
    """
    from betvdesign.layout.drc import unreleased

    h = layer.release_holes
    assert h is not None and layer.min_width is not None
    w_max, size, margin = _um(layer.max_unreleased_width), _um(h.size), _um(layer.min_width)
    body = gdstk.boolean([gdstk.Polygon(p) for p in polys], [], "or", precision=1e-3)
    out = list(holes)
    for _ in range(50):
        left = unreleased(gdstk, [gdstk.Polygon(p) for p in polys],
                          [gdstk.Polygon(p) for p in out],
                          [gdstk.Polygon(p) for p in anchors], w_max)  # fmt: skip
        if not left:
            return out
        for v in left:
            x0, y0, x1, y1 = v.bbox
            cx, cy = _g((x0 + x1) / 2), _g((y0 + y1) / 2)
            k = size / 2 + margin
            grown = gdstk.rectangle((cx - k, cy - k), (cx + k, cy + k))
            inside = gdstk.boolean(grown, body, "not", precision=1e-3)
            clash = gdstk.boolean(grown, [gdstk.Polygon(p) for p in out], "and", precision=1e-3)
            if inside or clash:
                raise BetvError(
                    f"cannot release the feature around ({cx:.3f}, {cy:.3f}) µm with etch holes "
                    f"of {size:g} µm (no room for one with {margin:g} µm around it)"
                )
            out.append(_rect(cx - size / 2, cy - size / 2, cx + size / 2, cy + size / 2))
    raise BetvError("release holes: no layout found that releases every feature")


def _released(polys: list[np.ndarray], holes: list[np.ndarray], w_max: float, gdstk: Any) -> bool:
    """No point of polys − holes farther than w_max/2 from an edge (erosion by a disc)."""
    body = gdstk.boolean([gdstk.Polygon(p) for p in polys], [gdstk.Polygon(p) for p in holes],
                         "not", precision=1e-3)  # fmt: skip
    if not body:
        return True
    return not gdstk.offset(body, -(w_max / 2 - 1e-3), join="round", tolerance=64,
                            precision=1e-3)  # fmt: skip


@dataclass
class _Layers:
    process: Process
    slider: str
    annotation: tuple[int, int]

    def gds(self, name: str) -> tuple[int, int]:
        return self.process.layers[name].gds.pair

    def structural(self, name: str) -> ProcessLayer:
        return self.process.structural(name)

    def anchor(self, name: str) -> tuple[int, int] | None:
        a = self.structural(name).anchor
        return None if a is None else self.gds(a)

    def holes(self, name: str) -> tuple[int, int]:
        h = self.structural(name).release_holes
        assert h is not None
        return self.gds(h.layer)

    def metal(self) -> tuple[int, int] | None:
        for lay in self.process.layers.values():
            if lay.role == "metal":
                return lay.gds.pair
        return None


def _refuse(spec: DeviceSpec) -> None:
    """A device the layout cannot draw faithfully: a clear error listing why."""
    p = spec.process
    if p is None:
        raise BetvError(
            f"device {spec.name!r} names no process: give 'process: polymumps' (or a process "
            "file) so the layout knows its layers"
        )
    why = []
    lay = p.structural_name(spec.slider.layer)
    t = _um(p.structural(lay).thickness)
    if abs(_um(spec.slider.beam_thickness) - t) > 5e-4:
        why.append(f"slider.beam_thickness {_um(spec.slider.beam_thickness):g} µm is not "
                   f"{lay}'s {t:g} µm")  # fmt: skip
    for s in spec.actuator_sets:
        check_set_name(s.name)
        geo = s.actuator.geometry
        if geo is None:
            why.append(f"set {s.name} has no actuator.geometry (the drawn actuator)")
            continue
        la = p.structural_name(geo.layer)
        ta = _um(p.structural(la).thickness)
        head_t = getattr(s.head.geometry, "thickness", None)
        for what, q in (
            ("actuator.geometry.thickness", geo.thickness),
            ("head.geometry.thickness", head_t),
        ):
            if q is not None and abs(_um(q) - ta) > 5e-4:
                why.append(f"set {s.name}: {what} {_um(q):g} µm is not {la}'s {ta:g} µm")
    if why:
        raise BetvError("cannot draw the layout: " + "; ".join(why) + " (betv check lists the "
                        "process rules; fix the file first)")  # fmt: skip


def _actuator_cell(g: FrameGeometry, layer: str, L: _Layers, gdstk: Any) -> Any:
    rects, (cx, cy, hx, hy, kind) = shape(g, grid=1e-9)
    r_um = [Rect(r.name, *(round(_UM * v, 9) for v in (r.x0, r.y0, r.x1, r.y1))) for r in rects]
    hx, hy, cx, cy = (round(_UM * v, 9) for v in (hx, hy, cx, cy))
    lay = L.structural(layer)
    name = (
        f"ACT_{layer}_L{cell_token(g.length * _UM)}_H{cell_token(g.hot_width * _UM)}"
        f"_C{cell_token(g.cold_width * _UM)}_F{cell_token(g.flexure_length * _UM)}"
        f"x{cell_token(g.flexure_width * _UM)}_G{cell_token(g.gap * _UM)}"
        f"_T{cell_token(g.tip_length * _UM)}_A{cell_token(g.anchor_size * _UM)}"
        + (
            f"_D{cell_token(2 * hx)}"
            if kind == "disc"
            else f"_B{cell_token(2 * hx)}x{cell_token(2 * hy)}"
        )
    )
    cell = gdstk.Cell(name)
    sl, sd = L.gds(layer)
    for poly in _shared_vertices([_rect(r.x0, r.y0, r.x1, r.y1) for r in r_um]):
        cell.add(gdstk.Polygon(poly, layer=sl, datatype=sd))
    head = _disc(cx, cy, hx) if kind == "disc" else _rect(cx - hx, cy - hy, cx + hx, cy + hy)
    cell.add(gdstk.Polygon(head, layer=sl, datatype=sd))
    enc = ANCHOR_ENCLOSURE_FACTOR * _um(lay.min_width)
    anchor, metal = L.anchor(layer), L.metal()
    for r in r_um:
        if r.name.startswith("anchor"):
            if anchor is not None:
                cell.add(gdstk.Polygon(_rect(r.x0 + enc, r.y0 + enc, r.x1 - enc, r.y1 - enc),
                                       layer=anchor[0], datatype=anchor[1]))  # fmt: skip
            if metal is not None:
                e2 = 2 * enc
                cell.add(gdstk.Polygon(_rect(r.x0 + e2, r.y0 + e2, r.x1 - e2, r.y1 - e2),
                                       layer=metal[0], datatype=metal[1]))  # fmt: skip
    hl, hd = L.holes(layer)
    released = [_rect(r.x0, r.y0, r.x1, r.y1) for r in r_um if not r.name.startswith("anchor")]
    fixed = [_rect(r.x0, r.y0, r.x1, r.y1) for r in r_um if r.name.startswith("anchor")]
    holes = _holes(head, lay, gdstk)
    for r in released:  # a wide cold arm is released through holes too
        holes += _holes(r, lay, gdstk)
    holes = _fill_release([*released, head, *fixed], holes, fixed, lay, gdstk)
    for hole in holes:
        cell.add(gdstk.Polygon(hole, layer=hl, datatype=hd))
    return cell


def _local_labels(g: FrameGeometry) -> dict[str, tuple[float, float]]:
    """A point inside each part of an actuator, in its own frame [µm]."""
    rects, (cx, cy, _hx, _hy, _k) = shape(g, grid=1e-9)
    out = {}
    for r in rects:
        out[r.name] = ((r.x0 + r.x1) / 2 * _UM, (r.y0 + r.y1) / 2 * _UM)
    tip = next(r for r in rects if r.name == "tip")
    out["tip"] = ((tip.x0 + (tip.x1 - tip.x0) / 4) * _UM, cy * _UM)  # outside the head
    out["head"] = (cx * _UM, cy * _UM)
    return out


def _draw_slider(
    spec: DeviceSpec, Ls: _Layers, lib: Any, top: Any, labels: list, gdstk: Any
) -> tuple[float, float]:
    """Draw the slider (its beams and end pieces, released) and its travel stops.

    Parameters
    ----------
    spec : DeviceSpec
        The device.
    Ls : _Layers
        Its process's layers.
    lib, top : gdstk.Library, gdstk.Cell
        The library the slider's cell is added to, and the top cell it is placed in.
    labels : list of (str, (float, float))
        Element labels and their positions [µm] (appended to).
    gdstk : module
        The gdstk module.

    Returns
    -------
    tuple of float
        The beams' length L and the slider's height H [µm].
    """
    sl = spec.slider
    lay_s = Ls.structural(Ls.slider)
    L, w, n = _um(sl.beam_length), _um(sl.beam_width), sl.beam_count
    gap = beam_gap(_um(lay_s.min_spacing))
    H = n * w + (n - 1) * gap
    scell = gdstk.Cell(
        f"SLIDER_{Ls.slider}_L{cell_token(L)}_W{cell_token(w)}_N{n}_G{cell_token(gap)}"
        f"_E{cell_token(END_LENGTH)}"
    )
    sg = Ls.gds(Ls.slider)
    hl = Ls.holes(Ls.slider)
    parts, holes = [], []
    xl = _g(-L / 2)  # every edge on the grid, every beam exactly L × w
    yb = _g(-H / 2)
    for i in range(n):
        y0 = yb + i * (w + gap)
        beam = _rect(xl, y0, xl + L, y0 + w)
        parts.append(beam)
        holes += _holes(beam, lay_s, gdstk)
        labels.append(("slider.beam", (_g(xl + L / 2), _g(y0 + w / 2))))
    for x0, x1 in ((xl - END_LENGTH, xl), (xl + L, xl + L + END_LENGTH)):
        end = _rect(x0, yb, x1, yb + H)
        parts.append(end)
        holes += _holes(end, lay_s, gdstk)
        labels.append(("slider.end", (_g((x0 + x1) / 2), 0.0)))
    for poly in _shared_vertices(parts):
        scell.add(gdstk.Polygon(poly, layer=sg[0], datatype=sg[1]))
    for hole in _fill_release(parts, holes, [], lay_s, gdstk):
        scell.add(gdstk.Polygon(hole, layer=hl[0], datatype=hl[1]))
    lib.add(scell)
    top.add(gdstk.Reference(scell))
    _draw_stops(spec, Ls, top, labels, (xl, L), gdstk)
    return L, H


def _draw_stops(
    spec: DeviceSpec, Ls: _Layers, top: Any, labels: list, beams: tuple[float, float], gdstk: Any
) -> None:
    """Draw the slider's two travel stops, anchored, half the travel range beyond its ends.

    Parameters
    ----------
    spec : DeviceSpec
        The device.
    Ls : _Layers
        Its process's layers.
    top : gdstk.Cell
        The top cell.
    labels : list of (str, (float, float))
        Element labels and their positions [µm] (appended to).
    beams : tuple of float
        The beams' left end xl and length L [µm].
    gdstk : module
        The gdstk module.
    """
    xl, L = beams
    lay_s = Ls.structural(Ls.slider)
    sg = Ls.gds(Ls.slider)
    tr = _um(spec.slider.travel_range)
    anchor = Ls.anchor(Ls.slider)
    enc = ANCHOR_ENCLOSURE_FACTOR * _um(lay_s.min_width)
    for x0, x1 in (
        (xl - END_LENGTH - tr / 2 - STOP_SIZE, xl - END_LENGTH - tr / 2),
        (xl + L + END_LENGTH + tr / 2, xl + L + END_LENGTH + tr / 2 + STOP_SIZE),
    ):
        x0, x1 = _g(x0), _g(x0) + (x1 - x0)
        top.add(gdstk.Polygon(_rect(x0, -STOP_SIZE / 2, x1, STOP_SIZE / 2), layer=sg[0],
                              datatype=sg[1]))  # fmt: skip
        if anchor is not None:
            top.add(gdstk.Polygon(_rect(x0 + enc, -STOP_SIZE / 2 + enc, x1 - enc,
                                        STOP_SIZE / 2 - enc), layer=anchor[0],
                                  datatype=anchor[1]))  # fmt: skip
        labels.append(("slider.stop", (_g((x0 + x1) / 2), 0.0)))


def _draw_actuators(
    spec: DeviceSpec, Ls: _Layers, lib: Any, top: Any, labels: list, slider: tuple, gdstk: Any
) -> None:
    """Draw each actuator set's cell once and place it on both sides of the slider.

    Parameters
    ----------
    spec : DeviceSpec
        The device.
    Ls : _Layers
        Its process's layers.
    lib, top : gdstk.Library, gdstk.Cell
        The library the cells are added to, and the top cell they are placed in.
    labels : list of (str, (float, float))
        Element labels and their positions [µm] (appended to).
    slider : tuple of float
        The beams' length L and the slider's height H [µm].
    gdstk : module
        The gdstk module.
    """
    p = Ls.process
    L, H = slider
    lay_s = Ls.structural(Ls.slider)
    cells: dict[tuple[str, str], Any] = {}
    placed: dict[int, int] = {1: 0, -1: 0}
    clearance = _um(lay_s.min_spacing) + 0.002  # two grid steps: rounding never eats the gap
    for s in spec.actuator_sets:
        g = frame_geometry(spec, s)
        layer = p.structural_name(s.actuator.geometry.layer)
        key = (repr(g), layer)
        if key not in cells:
            cells[key] = _actuator_cell(g, layer, Ls, gdstk)
            lib.add(cells[key])
        cell = cells[key]
        theta = float(s.contact.impact_angle.to("rad").magnitude)
        sx = 1 if s.impact_direction == "+x" else -1
        c, si = math.cos(theta), math.sin(theta)
        pts = np.concatenate([pl.points for pl in cell.polygons])
        h_max = float(np.max(c * pts[:, 0] + si * pts[:, 1]))
        r_head = float(g.head_x) * _UM
        x_head = sx * contact_offset(L, r_head, clearance, placed[sx])
        placed[sx] += 1
        _, (hcx, hcy, _hx, _hy, _k) = shape(g, grid=1e-9)
        head = (hcx * _UM, hcy * _UM)
        local = _local_labels(g)
        for side in ("lower", "upper"):
            pl = _placement(s.name, side, theta, sx, head, h_max, H / 2, clearance, x_head)
            top.add(gdstk.Reference(cell, pl.t, rotation=pl.rotation, x_reflection=pl.x_reflection))
            for part, (x, y) in local.items():
                gx, gy = pl.apply(x, y)
                labels.append((ElementLabel(s.name, side, part).text, (_g(gx), _g(gy))))


def build_library(spec: DeviceSpec, process_ref: str) -> Any:
    """The layout of ``spec`` as a gdstk Library (module doc).

    Parameters
    ----------
    spec : DeviceSpec
        The device, with its process.
    process_ref : str
        What the ``process = …`` label says (a shipped name, or a path relative to the
        GDS file).

    Returns
    -------
    gdstk.Library
        The slider's and the actuators' cells and the top cell, with the element and
        data labels.
    """
    gdstk = gdstk_module()
    _refuse(spec)
    p = spec.process
    assert p is not None
    ann = p.layers[p.annotation].gds.pair
    Ls = _Layers(p, p.structural_name(spec.slider.layer), ann)
    lib = gdstk.Library("BETVDESIGN", unit=1e-6, precision=1e-9)
    top_name = "BETV_" + "".join(ch if ch.isalnum() or ch in "_-" else "_" for ch in spec.name)
    top = gdstk.Cell(top_name[:120])
    labels: list[tuple[str, tuple[float, float]]] = []

    L, H = _draw_slider(spec, Ls, lib, top, labels, gdstk)
    _draw_actuators(spec, Ls, lib, top, labels, (L, H), gdstk)
    for text, xy in labels:
        top.add(gdstk.Label(text, xy, layer=ann[0], texttype=ann[1]))
    _, (x1, y1) = top.bounding_box()
    dump = spec.model_dump(mode="json", exclude_unset=True)
    for i, lab in enumerate(data_labels(dump, process_ref)):
        top.add(gdstk.Label(lab.text, (_g(x1 + 20), _g(y1 - 8 * i)), layer=ann[0],
                            texttype=ann[1]))  # fmt: skip
    lib.add(top)
    return lib


def _is_shipped(p: Process) -> bool:
    from betvdesign.spec.loader import load_process
    from betvdesign.spec.process import shipped_process_path

    path = shipped_process_path(p.name)
    return path is not None and load_process(path) == p


def write_layout(
    spec: DeviceSpec, path: str | os.PathLike[str], *, process_ref: str | None = None,
    svg: str | os.PathLike[str] | None = None,
) -> Path:  # fmt: skip
    """Write the layout of ``spec`` to ``path`` (GDSII) and an SVG preview.

    Parameters
    ----------
    spec : DeviceSpec
        The device, with its process.
    path : path
        The GDS file, written whole or not at all.
    process_ref : str, optional
        What the ``process = …`` label says (the shipped process's name by default).
    svg : path, optional
        An SVG preview to write as well.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    BetvError
        When the device cannot be drawn.
    """
    p = spec.process
    if process_ref is None:
        _refuse(spec)
        assert p is not None
        process_ref = p.name
        if not _is_shipped(p):
            raise BetvError(
                f"process {p.name!r} is not a shipped one: give process_ref, the path of its "
                "file relative to the GDS file (`betv layout` does)"
            )
    lib = build_library(spec, process_ref)
    with atomic_path(path) as tmp:
        lib.write_gds(str(tmp), max_points=8190, timestamp=TIMESTAMP)
    if svg is not None:
        with atomic_path(svg) as tmp:
            lib.top_level()[0].write_svg(str(tmp), scaling=2, background="#ffffff")
    return Path(path)
