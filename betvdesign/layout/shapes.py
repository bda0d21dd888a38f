"""Measuring drawn polygons (plain numpy on (n, 2) vertex arrays [µm]).

Measuring drawn polygons: area, centroid, the smallest enclosing rectangle (length,
width, direction), discs, projections. Plain numpy on (n, 2) vertex arrays [µm].
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Box", "area", "centroid", "extent", "min_box", "radius_about", "span_along"]


def area(p: np.ndarray) -> float:
    """Signed area (counter-clockwise positive) [µm²] (shoelace).

    Parameters
    ----------
    p : numpy.ndarray
        Vertices (n, 2) [µm].

    Returns
    -------
    float
        The area [µm²].
    """
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def centroid(p: np.ndarray) -> np.ndarray:
    """Area centroid of a simple polygon [µm].

    Parameters
    ----------
    p : numpy.ndarray
        Vertices (n, 2) [µm].

    Returns
    -------
    numpy.ndarray
        (x, y) [µm].
    """
    x, y = p[:, 0], p[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cr = x * yn - xn * y
    a = cr.sum() / 2
    if abs(a) < 1e-18:
        return p.mean(axis=0)
    return np.array([((x + xn) * cr).sum(), ((y + yn) * cr).sum()]) / (6 * a)


@dataclass(frozen=True)
class Box:
    """The smallest-area rectangle around a polygon.

    The smallest-area rectangle around a polygon: ``length`` ≥ ``width`` [µm], unit
    ``axis`` along the length, ``centre``, and ``fill`` = polygon area / box area (1 for a
    rectangle).
    """

    centre: np.ndarray
    length: float
    width: float
    axis: np.ndarray
    fill: float

    @property
    def normal(self) -> np.ndarray:
        """The unit vector across (axis turned +90°)."""
        return np.array([-self.axis[1], self.axis[0]])


def _hull(p: np.ndarray) -> np.ndarray:
    pts = sorted(map(tuple, np.round(p, 9)))
    if len(pts) <= 2:
        return np.array(pts)

    def half(points):
        out: list = []
        for q in points:
            while (
                len(out) >= 2
                and (
                    (out[-1][0] - out[-2][0]) * (q[1] - out[-2][1])
                    - (out[-1][1] - out[-2][1]) * (q[0] - out[-2][0])
                )
                <= 0
            ):
                out.pop()
            out.append(q)
        return out

    lower, upper = half(pts), half(pts[::-1])
    return np.array(lower[:-1] + upper[:-1])


def min_box(p: np.ndarray) -> Box:
    """The smallest-area rectangle around a polygon (rotating calipers).

    Parameters
    ----------
    p : numpy.ndarray
        Vertices (n, 2) [µm].

    Returns
    -------
    Box
        Its length, width, axis, centre and fill; the calipers run over the convex
        hull's edges.
    """
    h = _hull(p)
    best = None
    for i in _caliper_edges(h):
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
    ar, u, v, a, b = best
    la, lb = a.max() - a.min(), b.max() - b.min()
    c = u * (a.max() + a.min()) / 2 + v * (b.max() + b.min()) / 2
    if lb > la:
        u, la, lb = v, lb, la
    if u[0] < -1e-12 or (abs(u[0]) <= 1e-12 and u[1] < 0):
        u = -u
    return Box(c, float(la), float(lb), u, abs(area(p)) / ar if ar > 0 else 0.0)


def extent(p: np.ndarray) -> float:
    """The largest distance between two vertices [µm].

    A drawn disc's diameter: its vertices lie on the circle, opposite ones on each axis.

    Parameters
    ----------
    p : numpy.ndarray
        Vertices (n, 2) [µm].

    Returns
    -------
    float
        The distance [µm].
    """
    h = _hull(p)
    if len(h) <= _SMALL_HULL:
        d = h[:, None, :] - h[None, :, :]
        return float(np.sqrt(np.max(np.sum(d * d, axis=-1))))
    # rotating calipers: the farthest pair is antipodal, a vertex of an edge and a
    # vertex of the support opposite it (the supports between those of the edge's
    # neighbours, a window of _WINDOW more either side against round-off)
    j = _support(h, _edge_angles(h) + np.pi / 2)
    n = len(h)
    lo = np.roll(j, 1)  # the support of the previous edge
    lo = np.where(lo > j, lo - n, lo) - _WINDOW
    cnt = j + _WINDOW - lo + 1
    i = np.repeat(np.arange(n), cnt)
    k = (np.repeat(lo, cnt) + np.arange(cnt.sum()) - np.repeat(np.cumsum(cnt) - cnt, cnt)) % n
    best = 0.0
    for end in (i, (i + 1) % n):
        d = h[end] - h[k]
        best = max(best, float(np.max(np.sum(d * d, axis=-1))))
    return float(np.sqrt(best))


#: Hulls of at most this many vertices are measured over every pair or edge directly.
_SMALL_HULL = 512
#: Vertices either side of a caliper's support also compared (round-off near ties).
_WINDOW = 3


def _edge_angles(h: np.ndarray) -> np.ndarray:
    """Direction angles [rad] of the hull's edges, unwrapped (increasing, counter-clockwise)."""
    e = np.roll(h, -1, axis=0) - h
    return np.unwrap(np.arctan2(e[:, 1], e[:, 0]))


def _support(h: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """Index of the hull vertex farthest along each direction ``phi`` [rad].

    Vertex k is the support of a direction whose angle + 90° lies between the angles
    of the edges k − 1 and k (a counter-clockwise hull).
    """
    th = _edge_angles(h)
    psi = th[0] + np.mod(phi + np.pi / 2 - th[0], 2 * np.pi)
    return np.searchsorted(th, psi, "left") % len(h)


def _caliper_edges(h: np.ndarray) -> list[int]:
    """The hull edges whose bounding box may be the smallest (rotating calipers).

    Every edge of a small hull; of a large one, the edges whose box, from the supports
    (:func:`_support`, with :data:`_WINDOW` neighbours), is within round-off of the
    smallest: the exact areas of :func:`min_box` then choose among them in order.
    """
    n = len(h)
    if n <= _SMALL_HULL:
        return list(range(n))
    th = _edge_angles(h)
    u = np.column_stack([np.cos(th), np.sin(th)])
    v = np.column_stack([-u[:, 1], u[:, 0]])
    w = np.arange(-_WINDOW, _WINDOW + 1)

    def reach(direction: np.ndarray, phi: np.ndarray) -> np.ndarray:
        idx = (_support(h, phi)[:, None] + w) % n
        return np.max(np.einsum("ewk,ek->ew", h[idx], direction), axis=1)

    la = reach(u, th) + reach(-u, th + np.pi)
    lb = reach(v, th + np.pi / 2) + reach(-v, th - np.pi / 2)
    ar = la * lb
    tol = 1e-12 + 64 * np.finfo(float).eps * float(ar.max())  # the estimate's round-off
    return [int(i) for i in np.nonzero(ar <= ar.min() + 2 * tol)[0]]


def radius_about(p: np.ndarray, c: np.ndarray) -> float:
    """Largest distance of a vertex from ``c`` [µm] (a drawn disc's radius).

    Parameters
    ----------
    p : numpy.ndarray
        Vertices (n, 2) [µm].
    c : numpy.ndarray
        The centre (x, y) [µm].

    Returns
    -------
    float
        The distance [µm].
    """
    return float(np.max(np.hypot(p[:, 0] - c[0], p[:, 1] - c[1])))


def span_along(p: np.ndarray, u: np.ndarray) -> tuple[float, float]:
    """(min, max) of the vertices' projections on ``u``.

    Parameters
    ----------
    p : numpy.ndarray
        Vertices (n, 2) [µm].
    u : numpy.ndarray
        A unit vector.

    Returns
    -------
    tuple of float
        The smallest and largest projection [µm].
    """
    s = p @ u
    return float(s.min()), float(s.max())
