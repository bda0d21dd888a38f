"""Phase-plane figures: the head's vertical portrait and the periodic orbit in (ζ', s').

Inputs are dimensionless model states (docs/MODEL.md, "Dimensionless model"):
ξ, ξ' vertical gap and velocity, ζ' head tangential velocity, s' slider velocity.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from matplotlib.axes import Axes

from betvdesign.plots.figure import (
    PHASE_COLORS,
    Scale,
    axes_or_new,
    dimensionless_twin,
    legend_below,
)

#: Legend text per contact phase.
PHASE_LABELS: dict[str, str] = {
    "free": "no contact",
    "slip": "slip (ζ' > s')",
    "reverse": "reverse slip (ζ' < s')",
    "stick": "stick (ζ' = s')",
}


def phase_runs(phases: Sequence[str]) -> list[tuple[int, int, str]]:
    """Maximal runs of equal labels as (start, stop, label), stop exclusive."""
    runs: list[tuple[int, int, str]] = []
    start = 0
    for i in range(1, len(phases) + 1):
        if i == len(phases) or phases[i] != phases[start]:
            runs.append((start, i, phases[start]))
            start = i
    return runs


def vertical_phase_portrait(
    xi: Sequence[float],
    dxi: Sequence[float],
    *,
    steady_from: int = 0,
    gap_scale: Scale | None = None,
    rate_scale: Scale | None = None,
    ax: Axes | None = None,
) -> Axes:
    """The head's vertical phase portrait ξ' against ξ [-].

    gap_scale, rate_scale: (physical units per unit ξ / ξ', label): draw the gap and its
    rate in those units (nm, mm/s), with ξ and ξ' on secondary axes.

    Samples before ``steady_from`` (the transient) are drawn light; the rest dark.
    The contact line ξ = 0 is marked.
    """
    ax = axes_or_new(ax, 4.2, 3.4)
    kx, xlabel = gap_scale or (1.0, "ξ = gap / (u sinθ)  [-]")
    kv, ylabel = rate_scale or (1.0, "ξ' = dξ/dτ  [-]")
    x = np.asarray(xi, dtype=float) * kx
    v = np.asarray(dxi, dtype=float) * kv
    if steady_from > 0:
        ax.plot(
            x[: steady_from + 1], v[: steady_from + 1], color="#bdbdbd", lw=0.8, label="transient"
        )
    ax.plot(
        x[steady_from:],
        v[steady_from:],
        color="black",
        lw=1.1,
        label="settled cycles" if steady_from > 0 else "trajectory",
    )
    ax.axvline(0.0, color="#d62728", lw=1.0, ls=":", label="contact (gap 0)")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if gap_scale is not None:
        dimensionless_twin(ax, "x", kx, "ξ = gap / (u sinθ)  [-]")
    if rate_scale is not None:
        dimensionless_twin(ax, "y", kv, "ξ'  [-]")
    ax.legend(loc="upper right", framealpha=0.9)
    return ax


def orbit_plane(
    dzeta: Sequence[float],
    ds: Sequence[float],
    phases: Sequence[str],
    *,
    velocity_scale: Scale | None = None,
    ax: Axes | None = None,
) -> Axes:
    """Periodic orbit in the (ζ', s') plane, segments coloured by contact phase.

    velocity_scale: (physical units per unit velocity, unit label such as "mm/s"): both
    velocities in that unit (ζ and s share the scale u·cosθ), ζ', s' on secondary axes.

    phases: one of "free", "slip", "reverse", "stick" per sample.
    The diagonal ζ' = s' (where stick happens) is drawn for reference.
    """
    ax = axes_or_new(ax, 4.2, 3.4)
    k, unit = velocity_scale or (1.0, "-")
    z = np.asarray(dzeta, dtype=float) * k
    s = np.asarray(ds, dtype=float) * k
    if not (len(z) == len(s) == len(phases)):
        raise ValueError("dzeta, ds and phases must have the same length")
    unknown = set(phases) - set(PHASE_COLORS)
    if unknown:
        raise ValueError(f"unknown phase labels {sorted(unknown)}")
    seen: set[str] = set()
    for start, stop, label in phase_runs(phases):
        stop = stop + 1  # share the boundary sample with the next run so segments join
        lw = 2.2 if label != "free" else 1.0
        ax.plot(
            z[start:stop],
            s[start:stop],
            color=PHASE_COLORS[label],
            lw=lw,
            label=PHASE_LABELS[label] if label not in seen else None,
        )
        seen.add(label)
    lo = float(min(z.min(), s.min())) if z.size else -1.0
    hi = float(max(z.max(), s.max())) if z.size else 1.0
    ax.plot([lo, hi], [lo, hi], color="#7f7f7f", lw=0.6, ls="--", label="ζ' = s'")
    ax.set_xlabel(f"head tangential velocity  [{unit}]")
    ax.set_ylabel(f"slider velocity  [{unit}]")
    if velocity_scale is not None:
        dimensionless_twin(ax, "x", k, "ζ'  [-]")
        dimensionless_twin(ax, "y", k, "s'  [-]")
    legend_below(ax)
    return ax
