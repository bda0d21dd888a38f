"""Figures of a device's own fields (``betv sweep FILE --vary ...``), in physical units.

1-D: the speed against the field, the exact mode as coloured bands with every flip
located by bisection, the device's value marked. 2-D: the exact-mode map in the two
fields' units, the device marked, the paper's λ = 1 curve drawn over it (a fit, for
comparison only).
"""

from __future__ import annotations

import itertools
import os
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from matplotlib.colors import ListedColormap
from matplotlib.figure import Figure
from matplotlib.patches import Patch

from betvdesign.output.presentation import MODE_COLORS
from betvdesign.plots.figure import DEVICE_COLOR, new_figure
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


def fieldsweep_figure(rows: Sequence[Mapping[str, Any]], summary: Mapping[str, Any]) -> Figure:
    """The figure of a field sweep.

    Parameters
    ----------
    rows : sequence of mapping
        The sweep's rows in grid order (:mod:`betvdesign.studies.fieldsweep`).
    summary : mapping
        Its summary (``fields``: field, unit, device value, points; ``flips`` for 1-D).

    Returns
    -------
    Figure
        1-D: speed [µm/s] against the field with mode bands; 2-D: the exact-mode map.
    """
    if len(summary["fields"]) == 1:
        fig, ax = new_figure(6.4, 3.4)
        speed_with_modes(rows, summary, ax=ax)
    else:
        fig, ax = new_figure(6.4, 4.4)
        mode_map(rows, summary, ax=ax)
    return fig


def speed_with_modes(
    rows: Sequence[Mapping[str, Any]], summary: Mapping[str, Any], *, ax: Any
) -> None:
    """1-D: the periodic speed [µm/s] against the field on ``ax``, the exact mode as
    coloured bands between the bisected flips, the device's value dashed."""
    (f,) = summary["fields"]
    x = np.array([float(r[f["field"]]) for r in rows])
    v = np.array([np.nan if r["speed_m_s"] is None else 1e6 * r["speed_m_s"] for r in rows])
    edges = [x[0], *[fl["at"] for fl in summary.get("flips", [])], x[-1]]
    modes = [rows[0]["exact_mode"], *[fl["above"] for fl in summary.get("flips", [])]]
    for (a, b), m in zip(itertools.pairwise(edges), modes, strict=True):
        ax.axvspan(a, b, color=MODE_COLORS.get(m, "#ffffff"), alpha=0.18, lw=0)
    for fl in summary.get("flips", []):
        ax.axvline(fl["at"], color="0.3", lw=0.6, ls=":")
    ax.plot(x, v, color="k", marker=".", ms=3)
    ax.axhline(0.0, color="0.5", lw=0.5)
    ax.axvline(f["device_value"], color=DEVICE_COLOR, lw=1.0, ls="--")
    ax.set_xlabel(_label(f))
    ax.set_ylabel("speed (periodic orbit) [µm/s]")
    ax.set_title(f"{summary.get('name', '')} speed and exact mode against {f['field']}")
    seen = dict.fromkeys(modes)
    handles = [Patch(color=MODE_COLORS.get(m, "#fff"), alpha=0.4, label=m) for m in seen]
    handles.append(Patch(color=DEVICE_COLOR, label=f"device ({f['device_value']:g} {f['unit']})"))
    ax.legend(handles=handles, loc="best")


def mode_map(rows: Sequence[Mapping[str, Any]], summary: Mapping[str, Any], *, ax: Any) -> None:
    """2-D: the exact-mode map on ``ax`` in the two fields' units, the device starred,
    the paper's λ = 1 curve dashed over it (or where λ lies if it does not cross)."""
    fa, fb = summary["fields"]
    na, nb = fa["points"], fb["points"]
    xa = np.array([float(r[fa["field"]]) for r in rows]).reshape(na, nb)[:, 0]
    xb = np.array([float(r[fb["field"]]) for r in rows]).reshape(na, nb)[0, :]
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
    handles.append(Patch(color=DEVICE_COLOR, label="device"))
    ax.legend(handles=handles, loc="best", framealpha=0.85)
    ax.set_title(f"{summary.get('name', '')} exact mode (periodic orbit)")


def save_fieldsweep_figure(
    rows: Sequence[Mapping[str, Any]], summary: Mapping[str, Any], path: str | os.PathLike[str]
) -> None:
    """:func:`fieldsweep_figure` written to ``path`` (SVG/PNG/PDF by suffix)."""
    save_figure(fieldsweep_figure(rows, summary), path)
