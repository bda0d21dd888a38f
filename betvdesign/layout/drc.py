"""The process's rules on drawn polygons (``betv check FILE.gds``).

Per structural layer, on the union of its polygons (holes of its hole layer removed):

- **width** and **spacing**: pairs of boundary edges closer than the minimum across
  material (width) or across empty space (spacing: between polygons, notches, holes),
  with KLayout's semantics for all-angle layouts: Euclidean distance, edges meeting at
  :data:`IGNORE_ANGLE_DEG` or more are not a pair (a rounded 90° corner is not a
  violation, an acute notch is);
- **release**: points of the released part farther than half the widest unreleased
  feature from every edge (erosion by a disc, round joins) need etch holes; points within
  that distance of an anchor opening are held by it.

Slivers of the grid's size that the release erosion leaves are dropped (a region
survives only if an erosion by two grid steps leaves something). The results replace the
device file's ``process.min-width``, ``process.min-spacing`` and ``process.release`` rules
(:mod:`betvdesign.checks.process_rules`), located by layer and position; KLayout's own
width and space checks are the tests' independent reference.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from betvdesign.checks.process_rules import process_rules
from betvdesign.checks.rule import RuleResult
from betvdesign.layout.shapes import min_box
from betvdesign.spec.models import DeviceSpec
from betvdesign.spec.process import Process

__all__ = ["Violation", "layout_rules", "space_violations", "unreleased", "width_violations"]

_GRID = 1e-3  # µm


@dataclass(frozen=True)
class Violation:
    """One region breaking a rule: its layer, bounding box [µm] and narrowest extent."""

    layer: str
    gds: str
    bbox: tuple[float, float, float, float]
    extent: float

    @property
    def where(self) -> str:
        """The layer and the centre of the finding's box [µm], in words."""
        x0, y0, x1, y1 = self.bbox
        return f"{self.layer} ({self.gds}) at ({(x0 + x1) / 2:.3f}, {(y0 + y1) / 2:.3f}) µm"


def _real(gdstk: Any, polys: list) -> list:
    return [
        p
        for p in polys
        if gdstk.offset([p], -2 * _GRID, join="miter", precision=_GRID, use_union=True)
    ]


def _violations(gdstk: Any, polys: list, layer: str, gds: str) -> list[Violation]:
    out = []
    for p in _real(gdstk, polys):
        pts = np.asarray(p.points)
        (x0, y0), (x1, y1) = p.bounding_box()
        out.append(Violation(layer, gds, (x0, y0, x1, y1), min_box(pts).width))
    return sorted(out, key=lambda v: v.bbox)


def _off(gdstk: Any, polys: list, d: float, join: str = "miter") -> list:
    """Offset after a union of the input (a hole stays a hole, never a cut)."""
    if not polys:
        return []
    kw = {"tolerance": 64} if join == "round" else {}
    return gdstk.offset(polys, d, join=join, precision=_GRID, use_union=True, **kw)


def _not(gdstk: Any, a: list, b: list) -> list:
    if not a:
        return []
    return gdstk.boolean(a, b, "not", precision=_GRID) if b else gdstk.boolean(a, [], "or")


#: Edge pairs meeting at this angle or more are not checked (as KLayout's ``ignore_angle``):
#: a corner of about 90° is no violation, an acute one is.
IGNORE_ANGLE_DEG = 80.0


def _edges(gdstk: Any, polys: list) -> np.ndarray:
    """Boundary edges (n, 4) of the union of ``polys``.

    Boundary edges (n, 4) of the union of ``polys``, material on each edge's left; the
    zero-width cuts by which a polygon with holes is written are dropped.
    """
    out = []
    for p in gdstk.boolean(polys, [], "or", precision=_GRID) if polys else []:
        pts = np.asarray(p.points, dtype=float)
        x, y = pts[:, 0], pts[:, 1]
        if float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))) < 0:
            pts = pts[::-1]
        nxt = np.roll(pts, -1, axis=0)
        out.append(np.column_stack([pts, nxt]))
    if not out:
        return np.zeros((0, 4))
    e = np.concatenate(out)
    e = e[np.hypot(e[:, 2] - e[:, 0], e[:, 3] - e[:, 1]) > 1e-9]
    k = np.ascontiguousarray(np.round(e * 1e6).astype(np.int64))
    fwd = k.view(np.dtype((np.void, 32))).ravel()
    back = np.ascontiguousarray(k[:, [2, 3, 0, 1]]).view(np.dtype((np.void, 32))).ravel()
    return e[~np.isin(back, fwd)]


def _seg_dist(a: np.ndarray, b: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Distance of points p (…, 2) from segments a→b (…, 2)."""
    ab = b - a
    t = np.clip(np.sum((p - a) * ab, -1) / np.maximum(np.sum(ab * ab, -1), 1e-300), 0, 1)
    q = a + t[..., None] * ab
    return np.hypot(*(p - q).transpose(-1, *range(p.ndim - 1)))


#: Direction sectors of the edge-pair search [-]: edges closer than 45° in direction are
#: never a pair (:data:`IGNORE_ANGLE_DEG`), so only sectors two or more apart are matched.
_SECTORS = 8


def _cells(xy: np.ndarray, h: float) -> np.ndarray:
    """Grid cells (…, 2) of side ``h`` [µm] holding the points ``xy`` [µm]."""
    return np.floor(xy / h).astype(np.int64)


def _grid_pairs(
    ca: np.ndarray, cb: np.ndarray, sa: np.ndarray, sb: np.ndarray, shifts: list[int]
) -> tuple[np.ndarray, np.ndarray]:
    """Index pairs (i, j) of items in neighbouring grid cells.

    Item i of A (cell ``ca[i]``, sector ``sa[i]``) and item j of B pair when their cells
    differ by at most one in x and in y and ``sb[j] - sa[i]`` is one of ``shifts``
    (mod :data:`_SECTORS`). Work and memory are linear in the items plus the pairs: the
    items of B are sorted by (sector, cell) once, and each occupied cell of A looks up
    its nine neighbours by bisection.
    """
    if len(ca) == 0 or len(cb) == 0:
        return np.zeros(0, np.int64), np.zeros(0, np.int64)
    lo = np.minimum(ca.min(axis=0), cb.min(axis=0)) - 1
    span = np.maximum(ca.max(axis=0), cb.max(axis=0)) + 2 - lo

    def key(c: np.ndarray, s: np.ndarray) -> np.ndarray:
        return (s * span[0] + (c[:, 0] - lo[0])) * span[1] + (c[:, 1] - lo[1])

    kb = key(cb, sb)
    order = np.argsort(kb, kind="stable")
    kb_sorted = kb[order]
    ka = key(ca, sa)
    _, first, inverse = np.unique(ka, return_index=True, return_inverse=True)
    members = np.argsort(inverse, kind="stable")  # A's items grouped by cell
    start_a = np.concatenate([[0], np.cumsum(np.bincount(inverse))])
    ia_out, jb_out = [], []
    c0, s0 = ca[first], sa[first]
    for shift in shifts:
        s1 = (s0 + shift) % _SECTORS
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                want = key(c0 + np.array([dx, dy]), s1)
                b0 = np.searchsorted(kb_sorted, want, "left")
                b1 = np.searchsorted(kb_sorted, want, "right")
                nb = b1 - b0
                na = start_a[1:] - start_a[:-1]
                rep = na * nb
                hit = np.nonzero(rep)[0]
                if hit.size == 0:
                    continue
                rep = rep[hit]
                total = int(rep.sum())
                k = np.repeat(np.arange(hit.size), rep)
                local = np.arange(total) - np.repeat(np.cumsum(rep) - rep, rep)
                nbk = nb[hit][k]
                ia_out.append(members[start_a[hit][k] + local // nbk])
                jb_out.append(order[b0[hit][k] + local % nbk])
    if not ia_out:
        return np.zeros(0, np.int64), np.zeros(0, np.int64)
    return np.concatenate(ia_out), np.concatenate(jb_out)


def edge_violations(
    gdstk: Any, polys: list, d: float, kind: str, layer: str = "", gds: str = "",
    edges: np.ndarray | None = None,
) -> list[Violation]:  # fmt: skip
    """Edge pairs of the union of ``polys`` closer than ``d`` [µm].

    Across material (``kind`` "width") or across space ("space"): each edge lies on the
    other's material (or empty) side, they meet at less than :data:`IGNORE_ANGLE_DEG`,
    and their Euclidean distance is below d (KLayout's width/space check with its
    Euclidean metric).

    Only pairs that can be close are compared, in O(n log n) for n edges: every edge
    is cut into pieces no longer than d, and pieces in neighbouring grid cells of side
    2·d whose directions lie two or more of :data:`_SECTORS` sectors apart are the
    candidates (two points closer than d lie on pieces whose midpoints are closer than
    2·d; edges within 45° of each other in direction never meet at less than
    :data:`IGNORE_ANGLE_DEG`). The candidates then get the exact test.

    Parameters
    ----------
    gdstk : module
        The gdstk module.
    polys : list
        The layer's polygons.
    d : float
        The distance checked [µm].
    kind : {"width", "space"}
        Across material or across space.
    layer, gds : str
        The layer's name and GDS pair, for the findings.
    edges : numpy.ndarray, optional
        The union's boundary if already computed (:func:`_edges`).

    Returns
    -------
    list of Violation
        One per region of close edges.
    """
    e = _edges(gdstk, polys) if edges is None else edges
    if len(e) < 2 or not d > 0:
        return []
    i, j = _candidates(e, d)
    return pair_violations(e, i, j, d, kind, layer, gds)


def _candidates(e: np.ndarray, d: float) -> tuple[np.ndarray, np.ndarray]:
    """Edge pairs (i < j, unique) that may lie closer than ``d`` [µm] and face each other.

    See :func:`edge_violations`: pieces of length at most d, grid cells of side 2·d,
    direction sectors two or more apart.
    """
    a, b = e[:, :2], e[:, 2:]
    length = np.hypot(*(b - a).T)
    pieces = np.maximum(np.ceil(length / d).astype(np.int64), 1)
    parent = np.repeat(np.arange(len(e)), pieces)
    k = np.arange(len(parent)) - np.repeat(np.cumsum(pieces) - pieces, pieces)
    t = (k + 0.5) / pieces[parent]
    mid = a[parent] + t[:, None] * (b - a)[parent]
    ang = np.arctan2(b[:, 1] - a[:, 1], b[:, 0] - a[:, 0])
    sector = (np.floor(ang / (2 * np.pi / _SECTORS)).astype(np.int64) % _SECTORS)[parent]
    cell = _cells(mid, 2 * d)
    p, q = _grid_pairs(cell, cell, sector, sector, [2, 3, 4, 5, 6])
    i, j = parent[p], parent[q]
    keep = i < j
    pair = np.unique(i[keep] * len(e) + j[keep])
    return pair // len(e), pair % len(e)


def pair_violations(
    e: np.ndarray, i: np.ndarray, j: np.ndarray, d: float, kind: str, layer: str = "",
    gds: str = "",
) -> list[Violation]:  # fmt: skip
    """The violations among the edge pairs (``i``, ``j``) of the boundary ``e``.

    The exact test of :func:`edge_violations` on the pairs given (i < j).

    Parameters
    ----------
    e : numpy.ndarray
        Boundary edges (n, 4) [µm], material on each edge's left (:func:`_edges`).
    i, j : numpy.ndarray
        The pairs to test (int, i < j).
    d : float
        The distance checked [µm].
    kind : {"width", "space"}
        Across material or across space.
    layer, gds : str
        The layer's name and GDS pair, for the findings.

    Returns
    -------
    list of Violation
        One per region of close edges.
    """
    a, b = e[:, :2], e[:, 2:]
    u = (b - a) / np.hypot(*(b - a).T)[:, None]
    left = np.column_stack([-u[:, 1], u[:, 0]])  # toward the material
    side = left if kind == "width" else -left
    # the angle between e_i and the reversed e_j
    cos = -np.sum(u[i] * u[j], axis=1)
    ok = cos > np.cos(np.radians(IGNORE_ANGLE_DEG))
    i, j = i[ok], j[ok]
    lo = np.minimum(a, b)
    hi = np.maximum(a, b)
    near = np.all((lo[i] - d < hi[j]) & (lo[j] - d < hi[i]), axis=1)
    i, j = i[near], j[near]
    if i.size == 0:
        return []

    def ahead(k: np.ndarray, m: np.ndarray) -> np.ndarray:  # e_m partly on e_k's side
        s1 = np.sum((a[m] - a[k]) * side[k], axis=1)
        s2 = np.sum((b[m] - a[k]) * side[k], axis=1)
        return np.maximum(s1, s2) > 1e-9

    facing = ahead(i, j) & ahead(j, i)
    i, j = i[facing], j[facing]
    dist = np.minimum.reduce([
        _seg_dist(a[i], b[i], a[j]), _seg_dist(a[i], b[i], b[j]),
        _seg_dist(a[j], b[j], a[i]), _seg_dist(a[j], b[j], b[i]),
    ])  # fmt: skip
    bad = dist < d - 1e-6
    i, j, dist = i[bad], j[bad], dist[bad]
    boxes = [
        (
            min(a[k, 0], b[k, 0], a[m, 0], b[m, 0]), min(a[k, 1], b[k, 1], a[m, 1], b[m, 1]),
            max(a[k, 0], b[k, 0], a[m, 0], b[m, 0]), max(a[k, 1], b[k, 1], a[m, 1], b[m, 1]),
            float(dd),
        )
        for k, m, dd in zip(i, j, dist, strict=True)
    ]  # fmt: skip
    return _clusters(boxes, layer, gds)


def _clusters(boxes: list[tuple], layer: str, gds: str) -> list[Violation]:
    """Overlapping edge-pair boxes as one violation each (the narrowest distance kept).

    Boxes in sorted order join the first group (in the order the groups were made) that
    they overlap. The boxes come by increasing left edge, so a group whose right edge
    lies more than a grid step left of the current box's can never be joined again and
    leaves the scan (a sweep line: the same groups as scanning them all).
    """
    groups: list[list[float]] = []
    active: list[list[float]] = []
    for x0, y0, x1, y1, dd in sorted(boxes):
        active = [g for g in active if x0 <= g[2] + _GRID]
        for g in active:
            if x1 >= g[0] - _GRID and y0 <= g[3] + _GRID and y1 >= g[1] - _GRID:
                g[0], g[1], g[2], g[3] = min(g[0], x0), min(g[1], y0), max(g[2], x1), max(g[3], y1)
                g[4] = min(g[4], dd)
                break
        else:
            groups.append([x0, y0, x1, y1, dd])
            active.append(groups[-1])
    return [Violation(layer, gds, (g[0], g[1], g[2], g[3]), g[4]) for g in groups]


def weld(gdstk: Any, polys: list) -> list:
    """Insert into each polygon the vertices of others lying on its edges.

    Every vertex of another polygon that lies on one of a polygon's edges (to 1e-6 µm)
    is inserted there: shapes that abut in a rotated cell, flattened in floating point,
    then share their boundary vertex for vertex and merge without the sub-grid slivers
    rounding would leave (a designer's edit in KLayout breaks the shared vertices
    ``betv layout`` draws).

    Parameters
    ----------
    gdstk : module
        The gdstk module.
    polys : list
        The polygons.

    Returns
    -------
    list
        The polygons with the shared vertices inserted.
    """
    if len(polys) < 2:
        return list(polys)
    pts = [np.asarray(p.points, dtype=float) for p in polys]
    n = np.array([len(q) for q in pts])
    owner = np.repeat(np.arange(len(pts)), n)
    v = np.concatenate(pts)  # every vertex, by polygon
    a = v
    b = np.concatenate([np.roll(q, -1, axis=0) for q in pts])  # edge k: v[k] -> b[k]
    # candidates: each edge against the vertices in the grid cells next to its midpoint's,
    # the cell side the power of two at or above the edge's length (a grid per length
    # class: a long edge meets every vertex near it, a short one only its neighbours)
    length = np.hypot(*(b - a).T)
    level = np.ceil(np.log2(np.maximum(length, 1e-5))).astype(np.int64)
    mid = (a + b) / 2
    zero = np.zeros(len(v), np.int64)
    pe_all, pv_all = [], []
    lo, hi = np.minimum(a, b) - 1e-6, np.maximum(a, b) + 1e-6
    for lv in np.unique(level):
        edges = np.nonzero(level == lv)[0]
        if len(edges) * len(v) <= 1 << 22:  # a few edges: their boxes against every vertex
            inside = np.all((v[None] >= lo[edges, None]) & (v[None] <= hi[edges, None]), axis=2)
            pe, pv = np.nonzero(inside)
        else:
            h = 2.0 ** float(lv)
            pe, pv = _grid_pairs(_cells(mid[edges], h), _cells(v, h), zero[edges], zero, [0])
        pe_all.append(edges[pe])
        pv_all.append(pv)
    edge = np.concatenate(pe_all)
    pv = np.concatenate(pv_all)
    other = owner[edge] != owner[pv]
    # each (edge, vertex) once, by edge then vertex
    pair = np.unique(edge[other] * len(v) + pv[other])
    e_idx, p_idx = pair // len(v), pair % len(v)
    ab = (b - a)[e_idx]
    n2 = np.maximum(np.sum(ab * ab, axis=1), 1e-300)
    rel = v[p_idx] - a[e_idx]
    t = np.sum(rel * ab, axis=1) / n2
    cross = rel[:, 0] * ab[:, 1] - rel[:, 1] * ab[:, 0]
    on = (t > 1e-9) & (t < 1 - 1e-9) & (np.abs(cross) < 1e-6 * np.sqrt(n2))
    e_idx, p_idx, t = e_idx[on], p_idx[on], t[on]
    first = np.concatenate([[0], np.cumsum(n)])
    bounds = np.searchsorted(owner[e_idx], np.arange(len(polys) + 1))  # hits by polygon
    out = []
    for m, (p, q) in enumerate(zip(polys, pts, strict=True)):
        sel = slice(bounds[m], bounds[m + 1])
        if bounds[m] == bounds[m + 1]:
            out.append(p)
            continue
        el, tl = e_idx[sel] - first[m], t[sel]
        qa, qab = q[el], (np.roll(q, -1, axis=0) - q)[el]
        key = np.concatenate([np.arange(len(q), dtype=float), el + tl])
        pts_all = np.concatenate([q, qa + tl[:, None] * qab])
        order = np.argsort(key, kind="stable")
        out.append(gdstk.Polygon(pts_all[order], layer=p.layer, datatype=p.datatype))
    return out


def material(gdstk: Any, polys: list, holes: list) -> list:
    """The layer's material: its polygons, welded (:func:`weld`), less its release holes.

    Parameters
    ----------
    gdstk : module
        The gdstk module.
    polys, holes : list
        The layer's polygons and its release holes.

    Returns
    -------
    list
        gdstk polygons of the material [µm].
    """
    return _not(gdstk, weld(gdstk, polys), holes)


def width_violations(
    gdstk: Any, polys: list, holes: list, w_min: float, layer: str = "", gds: str = ""
) -> list[Violation]:
    """Material narrower than ``w_min`` [µm]: :func:`edge_violations` across material.

    Parameters
    ----------
    gdstk : module
        The gdstk module.
    polys, holes : list
        The layer's polygons and its release holes.
    w_min : float
        The minimum width [µm].
    layer, gds : str
        The layer's name and GDS pair, for the findings.

    Returns
    -------
    list of Violation
        The narrow regions.
    """
    return edge_violations(gdstk, material(gdstk, polys, holes), w_min, "width", layer, gds)


def space_violations(
    gdstk: Any, polys: list, holes: list, s_min: float, layer: str = "", gds: str = ""
) -> list[Violation]:
    """Gaps narrower than ``s_min`` [µm].

    Gaps between polygons, notches of one, or holes: :func:`edge_violations` across
    space.

    Parameters
    ----------
    gdstk : module
        The gdstk module.
    polys, holes : list
        The layer's polygons and its release holes.
    s_min : float
        The minimum spacing [µm].
    layer, gds : str
        The layer's name and GDS pair, for the findings.

    Returns
    -------
    list of Violation
        The narrow gaps.
    """
    return edge_violations(gdstk, material(gdstk, polys, holes), s_min, "space", layer, gds)


def unreleased(
    gdstk: Any, polys: list, holes: list, anchors: list, w_max: float, layer: str = "",
    gds: str = "",
) -> list[Violation]:  # fmt: skip
    """Released regions farther than ``w_max``/2 [µm] from every edge.

    erode(B) = erode(A) − dilate(H), less what lies within w_max/2 of an anchor (module
    doc).

    Parameters
    ----------
    gdstk : module
        The gdstk module.
    polys, holes, anchors : list
        The layer's polygons, its release holes and the anchors.
    w_max : float
        The widest feature the etch releases [µm].
    layer, gds : str
        The layer's name and GDS pair, for the findings.

    Returns
    -------
    list of Violation
        The regions the etch does not release.
    """
    r = w_max / 2 - _GRID
    core = _not(gdstk, _off(gdstk, polys, -r, "round"), _off(gdstk, holes, r, "round"))
    if core and anchors:
        core = _not(gdstk, core, _off(gdstk, anchors, w_max / 2, "round"))
    return _violations(gdstk, core, layer, gds)


@dataclass(frozen=True)
class LayerFindings:
    """DRC findings of the structural layers (by rule)."""

    width: list[Violation]
    space: list[Violation]
    release: list[Violation]


def findings(gdstk: Any, process: Process, by_layer: dict[tuple[int, int], list]) -> LayerFindings:
    """Width, spacing and release findings of every structural layer.

    Parameters
    ----------
    gdstk : module
        The gdstk module.
    process : Process
        The process (its structural layers and their rules).
    by_layer : dict
        gdstk polygons by (layer, datatype), flattened.

    Returns
    -------
    LayerFindings
        The findings by rule.
    """
    width, space, release = [], [], []
    for name, lay in process.layers.items():
        if lay.role != "structural":
            continue
        polys = by_layer.get(lay.gds.pair, [])
        if not polys:
            continue
        h = lay.release_holes
        holes = by_layer.get(process.layers[h.layer].gds.pair, []) if h is not None else []
        anchors = by_layer.get(process.layers[lay.anchor].gds.pair, []) if lay.anchor else []
        um = lambda q: float(q.to("um").magnitude)  # noqa: E731
        g = str(lay.gds)
        body = material(gdstk, polys, holes)
        e = _edges(gdstk, body)
        width += edge_violations(gdstk, body, um(lay.min_width), "width", name, g, e)
        space += edge_violations(gdstk, body, um(lay.min_spacing), "space", name, g, e)
        release += unreleased(gdstk, polys, holes, anchors, um(lay.max_unreleased_width), name, g)
    return LayerFindings(width, space, release)


def _listing(vs: list[Violation], limit: int = 6) -> str:
    shown = "; ".join(f"{v.where} (≈ {v.extent:.3g} µm)" for v in vs[:limit])
    return shown + (f"; and {len(vs) - limit} more" if len(vs) > limit else "")


def layout_rules(spec: DeviceSpec, f: LayerFindings, cell: str) -> list[RuleResult]:
    """The device's process rules measured on the drawn polygons of ``cell``.

    Width, spacing and release are measured on the drawing instead of taken from the
    device file's fields.

    Parameters
    ----------
    spec : DeviceSpec
        The device extracted from the layout.
    f : LayerFindings
        The drawn polygons' findings (:func:`findings`).
    cell : str
        The top cell's name, for the messages.

    Returns
    -------
    list of RuleResult
        The process rules.
    """
    assert spec.process is not None
    p = spec.process
    # rule id: (findings, words when none, words before the listing, fix)
    measured = {
        "process.min-width": (
            f.width,
            "every drawn feature is at least the minimum width",
            "narrower than the minimum width",
            "widen the listed features to the minimum width",
        ),
        "process.min-spacing": (
            f.space,
            "every drawn gap is at least the minimum spacing",
            "gaps below the minimum spacing",
            "open the listed gaps to the minimum spacing",
        ),
    }
    out = []
    for r in process_rules(spec):
        if r.id in measured:
            found, none, listed, fix = measured[r.id]
            ok = not found
            r = RuleResult(
                r.id, "error", ok, None if ok else min(v.extent for v in found) * 1e-6,
                r.threshold,
                f"cell {cell}: {none}" if ok else f"cell {cell}: {listed}: {_listing(found)}",
                r.source, fix="" if ok else fix, unit="m",
            )  # fmt: skip
        elif r.id == "process.release":
            ok = not f.release
            r = RuleResult(
                r.id, "error", ok, None, r.threshold,
                f"cell {cell}: every released feature is within reach of the release etch"
                if ok else f"cell {cell}: not released (too far from an edge or etch hole): "
                f"{_listing(f.release)}",
                r.source + f"; {p.cite('layers.' + p.default_structural + '.release_holes')}",
                fix="" if ok else "add etch holes there (`betv layout` draws them)",
            )  # fmt: skip
        out.append(r)
    return out
