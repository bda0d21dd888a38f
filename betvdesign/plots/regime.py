"""Vertical regime strip against ϖ (docs/MODEL.md, "What the model shows").

The head's vertical motion does not depend on the slider, so this strip is made
from the vertical-only model: impact period (actuation cycles per period of
the vertical motion) and contact fraction (share of a cycle in contact).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from matplotlib.axes import Axes

from betvdesign.model.domain import VARPI_WINDOW
from betvdesign.plots.figure import (
    DEVICE_COLOR,
    Scale,
    axes_or_new,
    dimensionless_twin,
    known_values,
)


def _strip_axes(
    ax: Axes | None,
    varpi: Sequence[float],
    device_varpi: float | None,
    varpi_scale: Scale | None,
) -> tuple[Axes, float, np.ndarray]:
    """A strip's axes (``ax`` or new) with the design window shaded and the device's ϖ
    marked; the scale's factor k and the x values ϖ·k (ϖ itself without a scale)."""
    ax = axes_or_new(ax)
    k = varpi_scale[0] if varpi_scale else 1.0
    lo, hi = VARPI_WINDOW
    ax.axvspan(lo * k, hi * k, color="#ffbf00", alpha=0.15, lw=0, label="design window")
    if device_varpi is not None:
        ax.axvline(
            device_varpi * k,
            color=DEVICE_COLOR,
            lw=1.2,
            ls="--",
            label=f"device ϖ = {device_varpi:.3g}",
        )
    return ax, k, np.asarray(varpi, dtype=float) * k


def impact_period_strip(
    varpi: Sequence[float],
    period_cycles: Sequence[float | None],
    *,
    device_varpi: float | None = None,
    hits_per_cycle: Sequence[float | None] | None = None,
    varpi_scale: Scale | None = None,
    ax: Axes | None = None,
) -> Axes:
    """Impact period [actuation cycles] against ϖ [-], optionally with the hits per cycle.

    ``period_cycles[i]`` is None where the vertical motion was found aperiodic
    (or no period was found within the search); those ϖ are drawn as crosses on
    the top edge, so a gap is never mistaken for a value. ``hits_per_cycle``
    (mean hits per actuation cycle, impulsive ones included) is drawn as open
    squares where known: more than one marks the multi-impact regime.
    varpi_scale: (physical units per unit ϖ, label), e.g. f_v in kHz: the x axis in
    actuation frequency with ϖ on a secondary (top) axis.
    """
    ax, k, w = _strip_axes(ax, varpi, device_varpi, varpi_scale)
    known, per = known_values(period_cycles)
    ax.plot(
        w[known], per[known], ls="none", marker="o", ms=2.5, color="black", label="impact period"
    )
    top = max(4.0, float(per[known].max()) + 1.0) if known.any() else 4.0
    if hits_per_cycle is not None:
        hk, hv = known_values(hits_per_cycle)
        ax.plot(
            w[hk],
            hv[hk],
            ls="none",
            marker="s",
            ms=2.5,
            mfc="none",
            color="#1f77b4",
            label="hits per cycle",
        )
        top = max(top, float(hv[hk].max()) + 1.0) if hk.any() else top
    if (~known).any():
        ax.plot(
            w[~known],
            np.full(int((~known).sum()), top),
            ls="none",
            marker="x",
            ms=3.5,
            color="#7f7f7f",
            label="aperiodic / not found",
        )
    ax.set_ylim(0.0, top + 0.6)
    ax.set_ylabel("impact period\n[cycles]")
    if varpi_scale is not None:
        dimensionless_twin(ax, "x", k, "ϖ = f_act/f_v  [-]")
    ax.legend(loc="upper left", framealpha=0.9, ncols=2)
    return ax


def contact_fraction_strip(
    varpi: Sequence[float],
    contact_fraction: Sequence[float | None],
    *,
    device_varpi: float | None = None,
    varpi_scale: Scale | None = None,
    ax: Axes | None = None,
) -> Axes:
    """Share of the actuation cycle spent in contact [-] against ϖ [-] (or the physical
    frequency of ``varpi_scale``, see :func:`impact_period_strip`).

    None entries (no periodic vertical motion found) are left out and drawn as
    crosses on the zero line.
    """
    ax, _, w = _strip_axes(ax, varpi, device_varpi, varpi_scale)
    known, frac = known_values(contact_fraction)
    ax.plot(
        w[known], frac[known], ls="-", marker="o", ms=2.0, color="black", label="contact fraction"
    )
    if (~known).any():
        ax.plot(
            w[~known], np.zeros(int((~known).sum())), ls="none", marker="x", ms=3.5, color="#7f7f7f"
        )
    ax.set_ylim(-0.03, max(0.6, float(frac.max()) * 1.15 if frac.size else 0.6))
    ax.set_xlabel(varpi_scale[1] if varpi_scale else "ϖ  [-]")
    ax.set_ylabel("contact\nfraction [-]")
    return ax
