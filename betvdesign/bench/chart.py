"""Work-precision chart (log-log error against CPU time) and the CSV/JSON table.

Object-oriented matplotlib (:func:`work_precision_axes` draws on the ``ax`` it is
given); files are written atomically (temp file + rename, the plots' and report's
helpers) and the SVG/PNG carry no date, so the same rows give the same bytes.
"""

from __future__ import annotations

import csv
import io
import json
import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from betvdesign.bench.workprecision import Row
from betvdesign.output.files import write_atomic
from betvdesign.plots.figure import figure_style, new_figure
from betvdesign.plots.studies import save_figure

#: Plotted in place of a zero error (exact agreement) so it stays on a log axis.
ERROR_FLOOR = 1e-17

STYLES: dict[str, dict[str, Any]] = {
    "exact": {"color": "#d62728", "marker": "*", "markersize": 11, "zorder": 5},
    "solve_ivp-RK45": {"color": "#1f77b4", "marker": "o"},
    "solve_ivp-DOP853": {"color": "#ff7f0e", "marker": "s"},
    "solve_ivp-Radau": {"color": "#2ca02c", "marker": "^"},
    "solve_ivp-LSODA": {"color": "#9467bd", "marker": "v"},
    "tanh-LSODA": {"color": "#8c564b", "marker": "D"},
    "rk4-post": {"color": "#7f7f7f", "marker": "x"},
}

METRIC_LABEL = {"s_N": "s after N cycles", "delta_s": "periodic Δs"}


def work_precision_axes(ax: Axes, rows: Sequence[Row], design: str, metric: str) -> None:
    """One panel: relative error against CPU seconds, one curve per method."""
    sel = [r for r in rows if r.design == design and r.metric == metric]
    for method in dict.fromkeys(r.method for r in sel):
        pts = sorted(
            (r.seconds, max(r.error, ERROR_FLOOR))
            for r in sel
            if r.method == method and r.error is not None and math.isfinite(r.seconds)
        )
        if not pts:
            continue
        x, y = np.array(pts).T
        style = {"marker": ".", **STYLES.get(method, {})}
        ax.loglog(x, y, label=method, linestyle="-" if len(x) > 1 else "none", **style)
    ax.axhline(1e-6, color="0.5", linewidth=0.6, linestyle=":")
    ax.axhline(1e-10, color="#d62728", linewidth=0.6, linestyle=":")
    ax.set_title(f"{design}: {METRIC_LABEL.get(metric, metric)}")
    ax.set_xlabel("CPU time [s]")
    ax.set_ylabel("relative error [-]")


def work_precision_figure(rows: Sequence[Row], *, tall: bool = False) -> Figure:
    """All designs × metrics on one figure, shared legend: designs as columns (wide, for
    screens) or, with ``tall``, as rows (fits a portrait page)."""
    designs = list(dict.fromkeys(r.design for r in rows))
    metrics = [m for m in ("s_N", "delta_s") if any(r.metric == m for r in rows)]
    nd, nm = len(designs), len(metrics)
    with figure_style():
        if tall:
            fig, axes = new_figure(6.4, 1.7 * nd + 0.6, nrows=nd, ncols=nm)
            axes = np.asarray(axes).reshape(nd, nm).T
        else:
            fig, axes = new_figure(2.6 * nd + 0.6, 2.5 * nm + 0.5, nrows=nm, ncols=nd)
            axes = np.asarray(axes).reshape(nm, nd)
        for i, metric in enumerate(metrics):
            for j, design in enumerate(designs):
                work_precision_axes(axes[i][j], rows, design, metric)
        handles, labels = {}, {}
        for ax in np.ravel(axes):
            for h, lab in zip(*ax.get_legend_handles_labels(), strict=True):
                handles.setdefault(lab, h)
                labels[lab] = lab
        ncols = 4 if tall else 7
        fig.legend(list(handles.values()), list(labels), loc="outside lower center", ncols=ncols)
    return fig


def save_chart(fig: Figure, out_dir: Path, stem: str) -> list[Path]:
    """Write a bench chart as ``stem``.png and ``stem``.svg into ``out_dir``.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The chart.
    out_dir : pathlib.Path
        The folder (made when missing).
    stem : str
        The files' name without suffix.

    Returns
    -------
    list of pathlib.Path
        The PNG and the SVG, written reproducibly (no date, the same bytes for the same
        figure).
    """
    out_dir.mkdir(parents=True, exist_ok=True)
    written = [out_dir / f"{stem}.png", out_dir / f"{stem}.svg"]
    for path in written:
        save_figure(fig, path)
    return written


def write_outputs(rows: Sequence[Row], out_dir: Path, stem: str = "work_precision") -> list[Path]:
    """Write ``stem``.png/.svg (chart), .csv and .json (rows + summary) into ``out_dir``."""
    from betvdesign.bench.workprecision import summarise

    out_dir = Path(out_dir)
    written = save_chart(work_precision_figure(rows), out_dir, stem)
    text = io.StringIO()
    fields = list(rows[0].as_dict()) if rows else list(Row.__dataclass_fields__)
    w = csv.DictWriter(text, fieldnames=fields, lineterminator="\n")
    w.writeheader()
    for r in rows:
        w.writerow(r.as_dict())
    written.append(write_atomic(out_dir / f"{stem}.csv", text.getvalue()))
    doc = {"rows": [r.as_dict() for r in rows], "summary": summarise(rows)}
    text = json.dumps(doc, indent=1, allow_nan=False) + "\n"
    written.append(write_atomic(out_dir / f"{stem}.json", text))
    return written
