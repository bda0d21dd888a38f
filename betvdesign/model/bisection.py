"""The one bisection of the package: where a classified quantity changes class.

A scalar x is classified (an exact mode, pass or fail, a predicate's truth). A bracket
[a, b] has one class at ``a`` and another at ``b``; each step classifies the midpoint
(arithmetic, or geometric for a positive quantity bisected in ratio) and keeps the half
whose ends still differ: the midpoint replaces ``a`` when it has ``a``'s class, else it
replaces ``b`` and its class becomes ``b``'s (a third class met inside the bracket ends
it there: the first change going from ``a`` is kept). Used by the mode flips of a field
sweep (:mod:`betvdesign.studies.fieldsweep`, the report's robustness variants), the
adequacy scans (:mod:`betvdesign.checks.adequacy`), the boundary of a fix
(:mod:`betvdesign.studies.fix`) and the paper's region edges
(:func:`betvdesign.paper.common.refine_edge`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Generic, TypeVar

__all__ = ["Bracket", "bisect"]

T = TypeVar("T")


@dataclass(frozen=True)
class Bracket(Generic[T]):
    """The bracket a bisection ends with.

    Parameters
    ----------
    a, b : float
        The ends [the quantity's unit]: ``a`` has the class the bisection started with
        at ``a``, ``b`` another one (``at_b``). ``a`` may lie above ``b``.
    at_b : object
        The class at ``b``.
    evaluations : int
        How many times the classifier was called.
    geometric : bool
        The midpoints were geometric means (else arithmetic).
    """

    a: float
    b: float
    at_b: T
    evaluations: int
    geometric: bool = False

    @property
    def mid(self) -> float:
        """The bracket's midpoint [the quantity's unit], the same mean as the steps'."""
        return _mean(self.a, self.b, self.geometric)


def _mean(a: float, b: float, geometric: bool) -> float:
    return math.sqrt(a * b) if geometric else 0.5 * (a + b)


def bisect(
    classify: Callable[[float], T],
    a: float,
    b: float,
    at_a: T,
    at_b: T,
    *,
    width: float | None = None,
    rtol: float | None = None,
    steps: int | None = None,
    geometric: bool = False,
) -> Bracket[T]:
    """Bisect the bracket [a, b] between the classes ``at_a`` and ``at_b``.

    Parameters
    ----------
    classify : callable
        The class of a value of the quantity (compared with ``==``).
    a, b : float
        The bracket's ends [the quantity's unit], in either order; positive when
        ``geometric``.
    at_a, at_b : object
        The classes at ``a`` and at ``b`` (different; not evaluated here).
    width : float, optional
        Stop when |b − a| ≤ ``width`` [the quantity's unit].
    rtol : float, optional
        Stop when |ln(a/b)| ≤ ``rtol`` [-].
    steps : int, optional
        Stop after exactly ``steps`` midpoints.
    geometric : bool
        Midpoints sqrt(a·b) (a quantity bisected in ratio) instead of (a + b)/2.

    Returns
    -------
    Bracket
        The final ends, the class at ``b`` and the number of evaluations (one per
        midpoint).

    Raises
    ------
    ValueError
        Unless exactly one of ``width``, ``rtol`` and ``steps`` is given, or when a
        geometric bracket is not positive.

    Notes
    -----
    A width stop takes ceil(log2(|b − a|/width)) evaluations, a ratio stop
    ceil(log2(|ln(a/b)|/rtol)) (0 when the bracket is already narrow enough).

    Examples
    --------
    >>> bisect(lambda x: x * x > 2.0, 1.0, 2.0, False, True, width=1e-6).mid  # √2
    1.4142136573791504
    """
    if sum(x is not None for x in (width, rtol, steps)) != 1:
        raise ValueError("bisect: give exactly one of width, rtol and steps")
    if geometric and not (a > 0.0 and b > 0.0):
        raise ValueError(f"bisect: a geometric bracket must be positive, not [{a:g}, {b:g}]")

    def more(k: int) -> bool:
        if steps is not None:
            return k < steps
        if width is not None:
            return abs(b - a) > width
        return abs(math.log(a / b)) > rtol  # type: ignore[operator]

    k = 0
    while more(k):
        mid = _mean(a, b, geometric)
        got = classify(mid)
        k += 1
        if got == at_a:
            a = mid
        else:
            b, at_b = mid, got
    return Bracket(a, b, at_b, k, geometric)
