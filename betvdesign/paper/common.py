"""Shared pieces of the validation study against the published paper (unit-free).

One comparison row per published statement (:class:`Comparison`) and the small,
independently testable measurements the study is built from: the relative
difference, the paper's own stopping rule ("successive Δs agree"), the settling
cycle measured against the exact periodic value, and the ϖ intervals where a
predicate holds, with their edges refined by bisection.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np

from betvdesign.model.bisection import bisect

#: The validated publication.
PAPER = "Shin, Pai, Lin, Hui and Tien, J. Appl. Phys. 96 (2004)"

#: Tolerance of the paper's stopping rule as MODEL.md ("Slider") states it: two
#: successive Δs agree to 1e-4 (relative).
STOP_RTOL = 1e-4

#: Explanation of a row that agrees (replaced by "not explained" if the verdict does not).
AS_PUBLISHED = "as published"

Verdict = Literal["reproduced", "differs", "holds", "partly holds", "does not hold"]


@dataclass(frozen=True)
class Comparison:
    """One published statement against what the exact model computes.

    ``published`` / ``computed`` are display strings (units first where the paper has
    them); ``published_value`` / ``computed_value`` the numbers compared (None for a
    qualitative statement); ``rel_diff`` = (computed − published)/|published| [-];
    ``check`` what exactly was computed; ``explanation`` the measured reason for a
    difference (or what the check found).
    """

    fig: str
    statement: str
    published: str
    computed: str
    verdict: Verdict
    check: str
    explanation: str
    published_value: float | None = None
    computed_value: float | None = None

    def __post_init__(self) -> None:
        if self.explanation == AS_PUBLISHED and self.verdict not in ("reproduced", "holds"):
            object.__setattr__(self, "explanation", "not explained: no measured cause found")

    @property
    def rel_diff(self) -> float | None:
        if self.published_value is None or self.computed_value is None:
            return None
        return rel_diff(self.computed_value, self.published_value)


def rel_diff(computed: float, published: float) -> float:
    """(computed − published)/|published| [-]; NaN when ``published`` is 0."""
    if published == 0.0:
        return math.nan
    return (computed - published) / abs(published)


def numeric_verdict(computed: float, published: float, *, digits: int) -> Verdict:
    """ "reproduced" when ``computed`` rounds to ``published`` at the paper's last
    quoted digit (``digits`` after the decimal point), else "differs"."""
    return "reproduced" if abs(computed - published) <= 0.5 * 10.0**-digits else "differs"


@dataclass(frozen=True)
class Stop:
    """Where a stopping rule or a settling measurement ends: cycle m (1-based, the
    cycle whose Δs_m is returned) and that Δs_m [-]."""

    cycle: int
    delta_s: float


def successive_stop(delta_s: Sequence[float], rtol: float = STOP_RTOL) -> Stop | None:
    """The paper's rule: the first cycle m ≥ 2 with |Δs_m − Δs_(m−1)| ≤ rtol·|Δs_m|.

    Returns None when no two successive increments agree within ``delta_s``.
    """
    ds = np.asarray(delta_s, dtype=float)
    if ds.size < 2:
        return None
    ok = np.abs(np.diff(ds)) <= rtol * np.abs(ds[1:])
    if not ok.any():
        return None
    i = int(np.argmax(ok)) + 1
    return Stop(i + 1, float(ds[i]))


def settled_from(delta_s: Sequence[float], target: float, rtol: float) -> int | None:
    """First cycle m (1-based) from which every Δs_k, k ≥ m, is within rtol·|target| of
    ``target`` (the exact periodic Δs); None if the last increment is not."""
    ds = np.asarray(delta_s, dtype=float)
    bad = np.abs(ds - target) > rtol * abs(target)
    if ds.size == 0 or bad[-1]:
        return None
    idx = np.flatnonzero(bad)
    return int(idx[-1]) + 2 if idx.size else 1


def refine_edge(pred: Callable[[float], bool], lo: float, hi: float, tol: float) -> float:
    """Bisect an edge of ``pred`` on [lo, hi] (pred(lo) != pred(hi)) to width ``tol``;
    returns the midpoint of the final bracket."""
    pa, pb = pred(lo), pred(hi)
    if pa == pb:
        raise ValueError(f"no edge in [{lo:g}, {hi:g}]: the predicate is {pa} at both ends")
    return bisect(pred, lo, hi, pa, pb, width=tol).mid


def true_intervals(x: Sequence[float], flags: Sequence[bool]) -> list[tuple[float, float]]:
    """Maximal runs of consecutive grid points where ``flags`` is true, as (first, last)."""
    out: list[tuple[float, float]] = []
    start: float | None = None
    prev = math.nan
    for xi, f in zip(x, flags, strict=True):
        if f and start is None:
            start = xi
        if not f and start is not None:
            out.append((start, prev))
            start = None
        prev = xi
    if start is not None:
        out.append((start, prev))
    return out


def fmt_intervals(ivs: Sequence[tuple[float, float]], digits: int = 4) -> str:
    """ "[a, b] ∪ [c, d]" with ``digits`` significant digits."""
    return " ∪ ".join(f"[{a:.{digits}g}, {b:.{digits}g}]" for a, b in ivs) or "none"
