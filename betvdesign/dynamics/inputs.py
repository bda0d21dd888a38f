"""Validation of the inputs every transient solver takes (unit-free state, cycle count)."""

from __future__ import annotations

import numpy as np

from betvdesign.errors import ParameterError


def check_state0(state0: object) -> tuple[float, ...]:
    """(ξ, ξ', ζ, ζ', s, s') from a user's state0 (None: all zero) or ParameterError.

    Parameters
    ----------
    state0 : sequence of 6 floats or None
        The state asked for [-].

    Returns
    -------
    tuple of float
        (ξ, ξ', ζ, ζ', s, s') [-].

    Raises
    ------
    ParameterError
        For anything but six finite numbers (or None), or a negative gap ξ.
    """
    if state0 is None:
        return (0.0,) * 6
    try:
        arr = np.asarray(state0, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise ParameterError(f"state0 must be 6 numbers, got {state0!r}") from None
    if arr.shape != (6,) or not np.all(np.isfinite(arr)):
        raise ParameterError(f"state0 must be 6 finite numbers (ξ, ξ', ζ, ζ', s, s'), got {arr}")
    if arr[0] < 0.0:
        raise ParameterError(f"state0: the gap ξ must be ≥ 0, got {arr[0]}")
    return tuple(float(x) for x in arr)


def check_cycles(cycles: object) -> int:
    """A non-negative cycle count or ParameterError.

    Parameters
    ----------
    cycles : int
        The cycle count asked for [-].

    Returns
    -------
    int
        The count.

    Raises
    ------
    ParameterError
        For a negative or non-integer count.
    """
    if isinstance(cycles, bool) or not isinstance(cycles, (int, np.integer)) or cycles < 0:
        raise ParameterError(f"cycles must be a non-negative integer, got {cycles!r}")
    return int(cycles)
