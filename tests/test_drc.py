"""The layout's width and space checks (betvdesign.layout.drc) against brute force.

Independent truth: the all-pairs code the check used before its candidate search
(every edge pair compared, O(n²) memory), kept here verbatim as the reference, and the
all-pairs weld (every vertex against every edge of every overlapping polygon). On many
seeded random layouts (rotated rectangles, stars, many-sided discs with holes, slivers
and abutting tiles) the fast check finds exactly the same violations, and the weld the
same polygons. KLayout's own checks are the second reference (tests/test_layout.py).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

gdstk = pytest.importorskip("gdstk")

from betvdesign.layout import drc  # noqa: E402

# --- the reference: all edge pairs (the code before the sweep, unchanged) ------------------


def _all_pairs(e: np.ndarray, d: float, kind: str) -> list[tuple]:
    n = len(e)
    if n < 2:
        return []
    a, b = e[:, :2], e[:, 2:]
    u = (b - a) / np.hypot(*(b - a).T)[:, None]
    left = np.column_stack([-u[:, 1], u[:, 0]])
    side = left if kind == "width" else -left
    i, j = np.triu_indices(n, 1)
    cos = -np.sum(u[i] * u[j], axis=1)
    ok = cos > np.cos(np.radians(drc.IGNORE_ANGLE_DEG))
    i, j = i[ok], j[ok]
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    near = np.all((lo[i] - d < hi[j]) & (lo[j] - d < hi[i]), axis=1)
    i, j = i[near], j[near]
    if i.size == 0:
        return []

    def ahead(k, m):
        s1 = np.sum((a[m] - a[k]) * side[k], axis=1)
        s2 = np.sum((b[m] - a[k]) * side[k], axis=1)
        return np.maximum(s1, s2) > 1e-9

    facing = ahead(i, j) & ahead(j, i)
    i, j = i[facing], j[facing]

    def seg(p0, p1, p):
        ab = p1 - p0
        t = np.clip(np.sum((p - p0) * ab, -1) / np.maximum(np.sum(ab * ab, -1), 1e-300), 0, 1)
        q = p0 + t[..., None] * ab
        return np.hypot(*(p - q).T)

    dist = np.minimum.reduce(
        [seg(a[i], b[i], a[j]), seg(a[i], b[i], b[j]), seg(a[j], b[j], a[i]), seg(a[j], b[j], b[i])]
    )
    bad = dist < d - 1e-6
    return sorted(zip(i[bad].tolist(), j[bad].tolist(), dist[bad].tolist(), strict=True))


def _all_clusters(boxes: list[tuple]) -> list[tuple]:
    groups: list[list[float]] = []
    for x0, y0, x1, y1, dd in sorted(boxes):
        for g in groups:
            if x0 <= g[2] + 1e-3 and x1 >= g[0] - 1e-3 and y0 <= g[3] + 1e-3 and y1 >= g[1] - 1e-3:
                g[:4] = [min(g[0], x0), min(g[1], y0), max(g[2], x1), max(g[3], y1)]
                g[4] = min(g[4], dd)
                break
        else:
            groups.append([x0, y0, x1, y1, dd])
    return [tuple(g) for g in groups]


def _all_weld(polys: list) -> list[np.ndarray]:
    pts = [np.asarray(p.points, dtype=float) for p in polys]
    if len(polys) < 2:
        return pts
    lo = np.array([q.min(axis=0) for q in pts]) - 1e-6
    hi = np.array([q.max(axis=0) for q in pts]) + 1e-6
    out = []
    for k, q in enumerate(pts):
        near = np.nonzero(np.all((lo <= hi[k]) & (hi >= lo[k]), axis=1))[0]
        others = [pts[m] for m in near if m != k]
        if not others:
            out.append(q)
            continue
        cand = np.concatenate(others)
        a, b = q, np.roll(q, -1, axis=0)
        ab = b - a
        n2 = np.maximum(np.sum(ab * ab, axis=1), 1e-300)
        rel = cand[None, :, :] - a[:, None, :]
        t = np.einsum("epk,ek->ep", rel, ab) / n2[:, None]
        cross = rel[:, :, 0] * ab[:, None, 1] - rel[:, :, 1] * ab[:, None, 0]
        on = (t > 1e-9) & (t < 1 - 1e-9) & (np.abs(cross) < 1e-6 * np.sqrt(n2)[:, None])
        e_idx, p_idx = np.nonzero(on)
        key = np.concatenate([np.arange(len(q), dtype=float), e_idx + t[e_idx, p_idx]])
        pts_all = np.concatenate([q, a[e_idx] + t[e_idx, p_idx][:, None] * ab[e_idx]])
        out.append(pts_all[np.argsort(key, kind="stable")])
    return out


# --- seeded random layouts -------------------------------------------------------------------


def _layout(rng: np.random.Generator) -> list:
    """A random layer: rotated rectangles, stars, a many-sided ring, slivers, tiles."""
    polys = []
    for _ in range(rng.integers(2, 7)):
        w, h = rng.uniform(0.3, 20, 2)
        r = gdstk.rectangle((0, 0), (w, h))
        r.rotate(rng.uniform(0, math.pi))
        r.translate(*rng.uniform(-30, 30, 2))
        polys.append(r)
    for _ in range(rng.integers(0, 3)):  # stars: acute notches and spikes
        m = int(rng.integers(3, 12))
        t = np.sort(rng.uniform(0, 2 * math.pi, 2 * m))
        rad = np.where(np.arange(2 * m) % 2, rng.uniform(1, 4), rng.uniform(5, 15))
        c = rng.uniform(-30, 30, 2)
        polys.append(gdstk.Polygon(np.c_[c[0] + rad * np.cos(t), c[1] + rad * np.sin(t)]))
    if rng.uniform() < 0.5:  # a many-sided disc with a hole (a head with an etch hole)
        n = int(rng.integers(64, 600))
        t = np.linspace(0, 2 * math.pi, n, endpoint=False)
        c, r0 = rng.uniform(-20, 20, 2), rng.uniform(5, 20)
        disc = gdstk.Polygon(np.c_[c[0] + r0 * np.cos(t), c[1] + r0 * np.sin(t)])
        hole = gdstk.rectangle(c - rng.uniform(0.5, 3), c + rng.uniform(0.5, 3))
        polys += gdstk.boolean(disc, hole, "not")
    if rng.uniform() < 0.5:  # tiles abutting along rotated edges (welded)
        ang, c = rng.uniform(0, math.pi), rng.uniform(-30, 30, 2)
        x = 0.0
        for _ in range(int(rng.integers(2, 5))):
            w = rng.uniform(1, 8)
            r = gdstk.rectangle((x, 0), (x + w, rng.uniform(1, 9)))
            r.rotate(ang, (0, 0))
            r.translate(*c)
            polys.append(r)
            x += w
    return polys


@pytest.mark.parametrize("seed", range(60))
def test_width_and_space_are_the_all_pairs_check(seed: int) -> None:
    rng = np.random.default_rng(seed)
    body = drc.material(gdstk, _layout(rng), [])
    e = drc._edges(gdstk, body)
    for d in (0.5, 2.0, rng.uniform(0.2, 8.0)):
        for kind in ("width", "space"):
            ref = _all_pairs(e, d, kind)
            i, j = drc._candidates(e, d)
            assert set(zip(i.tolist(), j.tolist(), strict=True)) >= {(p, q) for p, q, _ in ref}
            got = drc.edge_violations(gdstk, body, d, kind, edges=e)
            a, b = e[:, :2], e[:, 2:]
            boxes = [
                (
                    min(a[k, 0], b[k, 0], a[m, 0], b[m, 0]),
                    min(a[k, 1], b[k, 1], a[m, 1], b[m, 1]),
                    max(a[k, 0], b[k, 0], a[m, 0], b[m, 0]),
                    max(a[k, 1], b[k, 1], a[m, 1], b[m, 1]),
                    dd,
                )
                for k, m, dd in ref
            ]
            assert [(*v.bbox, v.extent) for v in got] == _all_clusters(boxes)


@pytest.mark.parametrize("seed", range(30))
def test_weld_is_the_all_pairs_weld(seed: int) -> None:
    polys = _layout(np.random.default_rng(1000 + seed))
    got = drc.weld(gdstk, polys)
    ref = _all_weld(polys)
    assert len(got) == len(ref)
    for g, r in zip(got, ref, strict=True):
        assert np.array_equal(np.asarray(g.points), r)


def test_a_many_sided_disc_is_checked_without_comparing_every_pair() -> None:
    """A 20 000-sided disc of radius 18 µm with a 1 µm slot: one width violation (the
    slot's sides are 1 µm apart) and a candidate count linear in the edges."""
    t = np.linspace(0, 2 * math.pi, 20_000, endpoint=False)
    disc = gdstk.Polygon(np.c_[18 * np.cos(t), 18 * np.sin(t)])
    body = gdstk.boolean(disc, gdstk.rectangle((-10, -0.5), (10, 0.5)), "not")
    e = drc._edges(gdstk, body)
    i, _ = drc._candidates(e, 2.0)
    assert len(i) < 20 * len(e)
    space = drc.edge_violations(gdstk, body, 2.0, "space")
    assert len(space) == 1 and space[0].extent == pytest.approx(1.0, abs=1e-6)
    assert drc.edge_violations(gdstk, body, 2.0, "width") == []


# --- the hull's measures: rotating calipers against every pair and every edge ---------------


def _all_pairs_extent(h: np.ndarray) -> float:
    d = h[:, None, :] - h[None, :, :]
    return float(np.sqrt(np.max(np.sum(d * d, axis=-1))))


def _all_edges_box(h: np.ndarray) -> tuple:
    best = None
    for i in range(len(h)):
        e = h[(i + 1) % len(h)] - h[i]
        n = math.hypot(*e)
        if n == 0:
            continue
        u = e / n
        v = np.array([-u[1], u[0]])
        a, b = h @ u, h @ v
        ar = (a.max() - a.min()) * (b.max() - b.min())
        if best is None or ar < best[0] - 1e-12:
            best = (ar, u, v, a, b)
    assert best is not None
    return best[1], (best[3].max() - best[3].min()) * (best[4].max() - best[4].min())


@pytest.mark.parametrize("seed", range(40))
def test_large_hulls_extent_and_box_are_every_pairs(seed: int) -> None:
    """Hulls of 513 to 3000 vertices (ellipses, regular polygons on the grid, point
    discs): the diameter and the smallest box are bit for bit those of all pairs."""
    from betvdesign.layout import shapes

    rng = np.random.default_rng(seed)
    n = int(rng.integers(600, 3000))
    if seed % 3 == 0:
        t = np.sort(rng.uniform(0, 2 * math.pi, n))
        r = rng.uniform(1, 50)
        p = np.c_[r * np.cos(t), rng.uniform(0.05, 1) * r * np.sin(t)]
    elif seed % 3 == 1:
        a = 2 * math.pi * np.arange(n) / n
        r = rng.uniform(10, 30)
        p = np.round(np.c_[r * np.cos(a), r * np.sin(a)], 3)
    else:
        t = rng.uniform(0, 2 * math.pi, 2 * n)
        r = rng.uniform(1, 100) * (1 - 1e-5 * rng.uniform(size=2 * n))
        p = np.c_[r * np.cos(t), r * np.sin(t)] + rng.uniform(-100, 100, 2)
    th = rng.uniform(0, math.pi)
    p = p @ np.array([[math.cos(th), -math.sin(th)], [math.sin(th), math.cos(th)]]).T
    h = shapes._hull(p)
    assert len(h) > shapes._SMALL_HULL
    assert shapes.extent(p) == _all_pairs_extent(h)
    box = shapes.min_box(p)
    u, ar = _all_edges_box(h)
    assert box.length * box.width == pytest.approx(ar, rel=1e-15, abs=0)
    assert abs(abs(float(np.dot(box.axis, u))) - 1) < 1e-15 or abs(np.dot(box.axis, u)) < 1e-15
