"""Parameter ranges and rectangular grids for design-space studies.

A range is written ``start:stop:step`` (stop included when it lies on the
step, to round-off), a comma list ``0.1,0.5,1``, or a single number. Bad
ranges raise :class:`~betvdesign.errors.UsageError` naming the parameter:
empty, inverted, zero or negative step, non-numeric, non-finite, or more
points than :data:`MAX_POINTS_PER_AXIS`.

A :class:`Grid` is an ordered product of named axes. Every point has a flat
integer key (C order, last axis fastest) that identifies it in streamed
results, so a resumed run knows which points are finished.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from betvdesign.errors import UsageError
from betvdesign.spec.limits import MAX_STUDY_POINTS

#: Largest number of points one axis may have (guards against typos like ``0:10:1e-9``).
MAX_POINTS_PER_AXIS = 1_000_000

#: Relative slack used to decide whether ``stop`` lies on the step lattice.
_ON_LATTICE_RTOL = 1e-9


def _number(text: str, name: str, what: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise UsageError(f"{name}: {what} {text.strip()!r} is not a number") from None
    if not math.isfinite(value):
        raise UsageError(f"{name}: {what} {text.strip()!r} is not finite")
    return value


def parse_range(text: str, name: str = "value") -> np.ndarray:
    """Parse ``start:stop:step``, ``a,b,c`` or ``a`` into a float64 array.

    ``start:stop:step`` gives start, start+step, ... up to stop inclusive
    (points are computed as start + i·step, not by accumulation, so they are
    reproducible). Lists keep the order given; duplicates are rejected.

    Parameters
    ----------
    text : str
        The range or list (values in the axis's own unit, [-] for ϖ, α, β, κ, λ).
    name : str
        The axis (named in errors).

    Returns
    -------
    numpy.ndarray
        The values, float64.

    Raises
    ------
    UsageError
        Not a number, not finite, a step <= 0, an inverted range, more than
        :data:`MAX_POINTS_PER_AXIS` points, or duplicates.
    """
    raw = text.strip()
    if not raw:
        raise UsageError(f"{name}: empty range (give start:stop:step, a list a,b,c or a number)")
    if ":" in raw:
        parts = raw.split(":")
        if len(parts) != 3:
            raise UsageError(f"{name}: range {raw!r} must be start:stop:step (three fields)")
        start, stop, step = (
            _number(p, name, w) for p, w in zip(parts, ("start", "stop", "step"), strict=True)
        )
        if step <= 0.0:
            raise UsageError(f"{name}: step must be > 0 in {raw!r}")
        if stop < start:
            raise UsageError(
                f"{name}: inverted range {raw!r} (stop {stop:g} < start {start:g}); "
                "write it with start <= stop"
            )
        span = (stop - start) / step
        n_float = math.floor(span + _ON_LATTICE_RTOL * max(1.0, span)) + 1
        if n_float > MAX_POINTS_PER_AXIS:
            raise UsageError(
                f"{name}: range {raw!r} has {n_float} points (more than {MAX_POINTS_PER_AXIS})"
            )
        values = start + step * np.arange(int(n_float), dtype=np.float64)
        # Snap a last point that lies on stop to round-off onto stop exactly.
        if values.size > 1 and abs(values[-1] - stop) <= _ON_LATTICE_RTOL * max(abs(stop), step):
            values[-1] = stop
        return values
    items = [p for p in raw.split(",")]
    if any(not p.strip() for p in items):
        raise UsageError(f"{name}: empty item in list {raw!r}")
    values = np.array([_number(p, name, "item") for p in items], dtype=np.float64)
    if len(np.unique(values)) != len(values):
        raise UsageError(f"{name}: duplicate values in list {raw!r}")
    return values


def require_positive(values: np.ndarray, name: str) -> np.ndarray:
    """Reject non-positive entries (the model parameters ϖ, α, β, κ are all > 0).

    Parameters
    ----------
    values : numpy.ndarray
        An axis [-].
    name : str
        The axis (named in errors).

    Returns
    -------
    numpy.ndarray
        ``values`` itself.

    Raises
    ------
    UsageError
        An entry <= 0 or NaN.
    """
    bad = values[~(values > 0.0)]
    if bad.size:
        raise UsageError(f"{name}: values must be > 0, got {bad[0]:g}")
    return values


@dataclass(frozen=True)
class GridPoint:
    """One point of a :class:`Grid`: its flat key and its coordinates."""

    key: int
    values: dict[str, float]


class Grid:
    """Ordered product of named 1-D axes; points keyed by flat C-order index."""

    def __init__(self, axes: Mapping[str, Sequence[float] | np.ndarray]):
        if not axes:
            raise UsageError("a grid needs at least one axis")
        self.axes: dict[str, np.ndarray] = {}
        for name, values in axes.items():
            arr = np.asarray(values, dtype=np.float64).reshape(-1)
            if arr.size == 0:
                raise UsageError(f"{name}: empty axis")
            self.axes[name] = arr
        size = math.prod(a.size for a in self.axes.values())
        if size > MAX_STUDY_POINTS:
            shape = " × ".join(f"{a.size:,}" for a in self.axes.values())
            raise UsageError(
                f"grid of {shape} = {size:,} points exceeds the limit of "
                f"{MAX_STUDY_POINTS:,} points per study; use coarser or fewer axes"
            )

    @property
    def names(self) -> tuple[str, ...]:
        """The axes' names, in grid order."""
        return tuple(self.axes)

    @property
    def shape(self) -> tuple[int, ...]:
        """Points per axis."""
        return tuple(a.size for a in self.axes.values())

    @property
    def size(self) -> int:
        """Number of points."""
        return math.prod(self.shape)

    def __len__(self) -> int:
        """The number of grid points."""
        return self.size

    def point(self, key: int) -> GridPoint:
        """The point with flat index ``key``.

        Parameters
        ----------
        key : int
            Flat C-order index, 0 to ``size`` − 1.

        Returns
        -------
        GridPoint
            Its key and coordinates.

        Raises
        ------
        IndexError
            ``key`` outside the grid.
        """
        if not 0 <= key < self.size:
            raise IndexError(f"grid key {key} outside 0..{self.size - 1}")
        idx = np.unravel_index(key, self.shape)
        return GridPoint(
            key, {n: float(a[i]) for (n, a), i in zip(self.axes.items(), idx, strict=True)}
        )

    def __iter__(self) -> Iterator[GridPoint]:
        """Every grid point in key order."""
        names = self.names
        for key, combo in enumerate(itertools.product(*self.axes.values())):
            yield GridPoint(key, {n: float(v) for n, v in zip(names, combo, strict=True)})

    def as_dict(self) -> dict[str, list[float]]:
        """JSON-friendly description (exact floats survive a JSON round trip).

        Returns
        -------
        dict of str to list of float
            Every axis's values, in grid order.
        """
        return {n: [float(v) for v in a] for n, a in self.axes.items()}
