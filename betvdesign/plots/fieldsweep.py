"""Figures of a device's own fields (``betv sweep FILE --vary ...``), in physical units.

1-D: the speed (a magnitude) against the field, the exact mode as coloured bands with
every flip located by bisection, the device's value marked. 2-D: the exact-mode map in
the two fields' units, the device marked, the paper's λ = 1 curve drawn over it (a fit,
for comparison only). Both hatch what lies outside the design window 0.5 ≤ ϖ < 2, draw
the sub-resonances α·ϖ² = 1/n² (f_act = f_h/n: the mode flips cluster just below them)
and, for an undamped head, cross-hatch the tangential resonance |α·ϖ² − 1| < 0.1 where
the idealised speed is not the device's.
"""

from __future__ import annotations

import itertools
import os
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from matplotlib.colors import ListedColormap
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from betvdesign.model.domain import (
    SUBRESONANCE_ORDERS,
    TANGENTIAL_DETUNING,
    VARPI_WINDOW,
    subresonance_level,
)
from betvdesign.output.presentation import MODE_COLORS, MODE_DIRECTION
from betvdesign.plots.figure import DEVICE_COLOR, legend_below, new_figure
from betvdesign.plots.marks import (
    OUTSIDE_HATCH,
    OUTSIDE_LABEL,
    RESONANCE_HATCH,
    RESONANCE_LABEL,
    SUBRES_COLOR,
    SUBRES_LABEL,
    mark_resonance,
    mark_subresonances,
    mark_window,
    speed_scale,
)
from betvdesign.plots.studies import save_figure

__all__ = [
    "fieldsweep_figure",
    "mode_map",
    "save_fieldsweep_figure",
    "speed_with_modes",
]


def _label(ax_info: Mapping[str, Any]) -> str:
    unit = ax_info["unit"]
    return f"{ax_info['field']} [{unit}]" if unit else ax_info["field"]


def _column(ax_info: Mapping[str, Any]) -> str:
    """The rows' column of a field (``drive.frequency [kHz]``; older rows: the field)."""
    return str(ax_info.get("column", ax_info["field"]))


def _num(x: Any) -> float:
    return float("nan") if x is None or x == "" else float(x)


def fieldsweep_figure(rows: Sequence[Mapping[str, Any]], summary: Mapping[str, Any]) -> Figure:
    """The figure of a field sweep.

    Parameters
    ----------
    rows : sequence of mapping
        The sweep's rows in grid order (:mod:`betvdesign.studies.fieldsweep`).
    summary : mapping
        Its summary (``fields``: field, unit, device value, points; ``flips`` and
        ``marks`` for 1-D).

    Returns
    -------
    Figure
        1-D: the speed [µm/s] against the field with mode bands; 2-D: the exact-mode map;
        both with the design window, the sub-resonances and the legend below the axes.
    """
    if len(summary["fields"]) == 1:
        fig, ax = new_figure(6.8, 4.6)
        speed_with_modes(rows, summary, ax=ax)
    else:
        fig, ax = new_figure(6.8, 5.6)
        mode_map(rows, summary, ax=ax)
    return fig


def speed_with_modes(
    rows: Sequence[Mapping[str, Any]], summary: Mapping[str, Any], *, ax: Any
) -> None:
    """1-D: the speed [µm/s] against the field on ``ax``.

    The travel answer's speed (a magnitude; the mode's band says which way) against the
    field, the exact mode as coloured bands between the bisected flips, the device's value
    dashed; from ``summary["marks"]`` (:func:`betvdesign.studies.fieldsweep.sweep_marks`)
    the range outside the design window hatched, the sub-resonances α·ϖ² = 1/n² as lines
    labelled f_h/n, and an undamped head's tangential-resonance band hatched with its
    speeds grey and left out of the axis range. The speed axis is symmetric-logarithmic
    when resonance spikes would flatten the operating region
    (:func:`betvdesign.plots.marks.speed_scale`).

    Over 80 lines on purpose: one axes, its bands, marks and curve drawn in order (the
    bands under the curve, the limits from the curve); splitting it would pass the axes'
    state between pieces.
    """
    (f,) = summary["fields"]
    marks = summary.get("marks") or {}
    x = np.array([float(r[_column(f)]) for r in rows])
    v = np.array([np.nan if r["speed_m_s"] is None else 1e6 * abs(r["speed_m_s"]) for r in rows])
    edges = [x[0], *[fl["at"] for fl in summary.get("flips", [])], x[-1]]
    modes = [rows[0]["exact_mode"], *[fl["above"] for fl in summary.get("flips", [])]]
    for (a, b), m in zip(itertools.pairwise(edges), modes, strict=True):
        ax.axvspan(a, b, color=MODE_COLORS.get(m, "#ffffff"), alpha=0.18, lw=0)
    for fl in summary.get("flips", []):
        ax.axvline(fl["at"], color="0.3", lw=0.6, ls=":")
    handles: list[Any] = []
    if marks.get("window") is not None:
        handles += mark_window(ax, float(x[0]), float(x[-1]), marks["window"])
    grey, more = mark_resonance(ax, marks.get("undamped_resonance", []), x)
    handles += more
    shown = np.where(grey, np.nan, v)
    ax.plot(x, shown, color="k", marker=".", ms=3)
    if grey.any():
        ax.plot(x[grey], v[grey], color="0.6", marker=".", ms=3, lw=0.8)
    speed_scale(ax, shown)
    at = [(m["n"], m["at"]) for m in marks.get("subresonances", [])]
    handles += mark_subresonances(ax, at, float(x[-1] - x[0]))
    ax.axvline(f["device_value"], color=DEVICE_COLOR, lw=1.0, ls="--")
    ax.set_xlim(float(x[0]), float(x[-1]))
    ax.set_xlabel(_label(f))
    ax.set_ylabel("speed |v| (travel answer) [µm/s]")
    ax.set_title(f"{summary.get('name', '')} speed and exact mode against {f['field']}")
    seen = dict.fromkeys(modes)
    mode_handles = [
        Patch(
            color=MODE_COLORS.get(m, "#fff"),
            alpha=0.4,
            label=f"{m} ({MODE_DIRECTION[m]})" if m in MODE_DIRECTION else m,
        )
        for m in seen
    ]
    device = Patch(color=DEVICE_COLOR, label=f"device ({f['device_value']:g} {f['unit']})")
    legend_below(ax, handles=[*mode_handles, *handles, device], fontsize=6.5)


def mode_map(rows: Sequence[Mapping[str, Any]], summary: Mapping[str, Any], *, ax: Any) -> None:
    """2-D: the exact-mode map on ``ax`` in the two fields' units.

    The device starred, the paper's λ = 1 curve dashed over it (or where λ lies if it
    does not cross), and, where the rows carry ϖ and α, the design window's edges with the
    outside hatched, the sub-resonances α·ϖ² = 1/n² as dash-dotted lines labelled f_h/n,
    and an undamped head's tangential-resonance band |α·ϖ² − 1| < 0.1 cross-hatched.

    Over 80 lines on purpose: one axes and its layers drawn in order; splitting it would
    pass the axes' state between pieces.
    """
    fa, fb = summary["fields"]
    na, nb = fa["points"], fb["points"]
    xa = np.array([float(r[_column(fa)]) for r in rows]).reshape(na, nb)[:, 0]
    xb = np.array([float(r[_column(fb)]) for r in rows]).reshape(na, nb)[0, :]
    names = list(MODE_COLORS)
    code = np.array([names.index(r["exact_mode"]) for r in rows]).reshape(na, nb)
    lam = np.array([np.nan if r.get("lam") is None else r["lam"] for r in rows]).reshape(na, nb)
    cmap = ListedColormap([MODE_COLORS[n] for n in names])
    ax.pcolormesh(xa, xb, code.T, cmap=cmap, vmin=-0.5, vmax=len(names) - 0.5, shading="nearest")
    crosses = bool(np.isfinite(lam).any() and np.nanmin(lam) < 1.0 < np.nanmax(lam))
    if crosses:
        ax.contour(xa, xb, lam.T, levels=[1.0], colors="k", linewidths=1.0, linestyles="--")
    lam_label = (
        "λ = 1 (paper's fit)"
        if crosses
        else f"λ {'>' if np.nanmin(lam) > 1 else '<'} 1 everywhere (fit: "
        f"{'pull' if np.nanmin(lam) > 1 else 'push'})"
    )
    varpi = np.array([_num(r.get("varpi")) for r in rows]).reshape(na, nb).T
    q = varpi**2 * np.array([_num(r.get("alpha")) for r in rows]).reshape(na, nb).T
    marks: list[Any] = []
    if min(na, nb) >= 2 and np.isfinite(varpi).sum() >= 4:
        marks = _map_marks(ax, xa, xb, varpi, q, rows)
    ax.plot(
        fa["device_value"],
        fb["device_value"],
        marker="*",
        ms=12,
        color=DEVICE_COLOR,
        markeredgecolor="k",
        ls="none",
    )
    ax.set_xlabel(_label(fa))
    ax.set_ylabel(_label(fb))
    ax.grid(False)
    present = [n for n in names if (code == names.index(n)).any()]
    handles = [Patch(color=MODE_COLORS[n], label=n) for n in present]
    handles.append(Patch(facecolor="none", edgecolor="k", ls="--", label=lam_label))
    handles += marks
    handles.append(Patch(color=DEVICE_COLOR, label="device"))
    legend_below(ax, handles=handles, fontsize=6.5)
    ax.set_title(f"{summary.get('name', '')} exact mode (travel answer)")


def _map_marks(
    ax: Any,
    xa: np.ndarray,
    xb: np.ndarray,
    varpi: np.ndarray,
    q: np.ndarray,
    rows: Sequence[Mapping[str, Any]],
) -> list[Any]:
    """The design window, the sub-resonances and an undamped head's resonance band on a
    map (``varpi``, ``q`` = α·ϖ² on the grid, transposed as drawn); their legend handles."""
    handles: list[Any] = []
    lo, hi = VARPI_WINDOW
    w = np.where(np.isfinite(varpi), varpi, np.nan)
    if np.nanmin(w) < lo or np.nanmax(w) >= hi:
        ax.contourf(
            xa,
            xb,
            w,
            levels=[-np.inf, lo, hi, np.inf],
            colors="none",
            hatches=[OUTSIDE_HATCH, None, OUTSIDE_HATCH],
        )
        ax.contour(xa, xb, w, levels=[lo, hi], colors="0.35", linewidths=0.8)
        handles.append(
            Patch(facecolor="none", edgecolor="0.35", hatch=OUTSIDE_HATCH, label=OUTSIDE_LABEL)
        )
    levels = [subresonance_level(n) for n in range(SUBRESONANCE_ORDERS, 0, -1)]
    inside = [lv for lv in levels if np.nanmin(q) < lv < np.nanmax(q)]
    if inside:
        cs = ax.contour(
            xa, xb, q, levels=inside, colors=SUBRES_COLOR, linewidths=0.7, linestyles="-."
        )
        names = {
            lv: ("f_h" if n == 1 else f"f_h/{n}")
            for n, lv in ((round(lv**-0.5), lv) for lv in inside)
        }
        ax.clabel(cs, fmt=names, fontsize=6.5, inline=True)
        handles.append(Line2D([], [], color=SUBRES_COLOR, lw=0.7, ls="-.", label=SUBRES_LABEL))
    undamped = any(not r.get("zeta_h") for r in rows if r.get("varpi") is not None)
    d = TANGENTIAL_DETUNING
    if undamped and np.nanmin(q) < 1.0 + d and np.nanmax(q) > 1.0 - d:
        ax.contourf(xa, xb, q, levels=[1.0 - d, 1.0 + d], colors="none", hatches=[RESONANCE_HATCH])
        handles.append(
            Patch(facecolor="none", edgecolor="0.45", hatch=RESONANCE_HATCH, label=RESONANCE_LABEL)
        )
    return handles


def save_fieldsweep_figure(
    rows: Sequence[Mapping[str, Any]], summary: Mapping[str, Any], path: str | os.PathLike[str]
) -> None:
    """:func:`fieldsweep_figure` written to ``path`` (SVG/PNG/PDF by suffix)."""
    save_figure(fieldsweep_figure(rows, summary), path)
