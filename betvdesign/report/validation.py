"""The validation page: the paper's Figs 3–12 recomputed, published vs computed.

``betv report --validation -o DIR`` writes ``validation.html`` (self-contained),
``validation.pdf``, ``validation.md`` (the same table for a repository browser) and
``figures/fig*.svg``. Built like the other reports: a plain-data model first
(:class:`ValidationReport`, every number formatted), rendered second by Jinja2
(autoescape) with the design reports' CSS, WeasyPrint for the PDF, atomic writes;
the same study gives the same bytes.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from markupsafe import Markup

from betvdesign import plots
from betvdesign.output.files import write_atomic
from betvdesign.output.siformat import scale_for
from betvdesign.paper.common import STOP_RTOL, Comparison
from betvdesign.paper.maps import FIG12_ALPHA
from betvdesign.paper.study import ValidationStudy, run_validation
from betvdesign.paper.vertical import FIG3_VARPI, MAX_CYCLES
from betvdesign.plots import validation as vplots
from betvdesign.report.render import render_pdf, render_template
from betvdesign.studies.regime import LONG_PERIOD

TEMPLATE = "validation.html.j2"
#: Δs range drawn in Fig. 12 (near the resonance |Δs| grows far beyond it).
FIG12_YLIM = (-40.0, 60.0)
COMMAND = "betv report --validation --no-pdf -o docs/validation"


@dataclass(frozen=True)
class Row:
    """One formatted comparison row."""

    fig: str
    statement: str
    published: str
    computed: str
    rel_diff: str
    verdict: str
    check: str
    explanation: str


@dataclass(frozen=True)
class FigureEntry:
    """One recomputed figure: its number, what the paper shows, the SVG and caption."""

    key: str
    number: str
    title: str
    paper: str
    caption: str
    svg: str


@dataclass(frozen=True)
class ValidationReport:
    """Plain data of the validation page."""

    title: str
    version: str
    paper: str
    device: str
    counts: tuple[tuple[str, int], ...]
    rows: tuple[Row, ...]
    variants: tuple[dict[str, str], ...]
    figures: tuple[FigureEntry, ...]
    stop_rtol: str
    command: str


def _row(c: Comparison) -> Row:
    rd = c.rel_diff
    return Row(
        c.fig,
        c.statement,
        c.published,
        c.computed,
        "—" if rd is None or not math.isfinite(rd) else f"{100 * rd:+.3g} %",
        c.verdict,
        c.check,
        c.explanation,
    )


def _figure(key: str, size: tuple[float, float], draw: Callable[[Any], None], **grid: Any):
    with plots.figure_style():
        fig, axes = plots.new_figure(*size, **grid)
        draw(axes)
    return fig, plots.figure_svg(fig, key)


def _fig3(st: ValidationStudy, axes: Any) -> None:
    d = st.vertical.fig3
    ax0, ax1 = axes
    ax0.plot(d["tau"], d["xi"], color="black", label="ξ")
    ax0.plot(d["tau"], d["dxi"], color="#1f77b4", lw=0.9, label="ξ'")
    ax0.set_xlabel("τ  [-]")
    ax0.set_ylabel("ξ, ξ'  [-]")
    ax0.legend(loc="best")
    plots.vertical_phase_portrait(d["xi"], d["dxi"], ax=ax1)


def _clip_period(rows: list[dict[str, Any]]) -> list[int | None]:
    return [
        r["period_cycles"]
        if r["period_cycles"] is not None and r["period_cycles"] <= LONG_PERIOD
        else None
        for r in rows
    ]


def _fig4(st: ValidationStudy, ax: Any) -> None:
    rows = st.vertical.rows
    w = [r["varpi"] for r in rows]
    plots.impact_period_strip(
        w, _clip_period(rows), hits_per_cycle=[r["hits_per_cycle"] for r in rows], ax=ax
    )
    ax.set_xlabel("ϖ  [-]")
    e = st.vertical.edges
    for x in (e["one_hit_lo"], e["one_hit_hi"]):
        ax.axvline(x, color="black", lw=0.8, ls=":")
    vplots.published_lines(ax, [0.5, 2.6], "published edges 0.5, 2.6")


def _fig5(st: ValidationStudy, ax: Any) -> None:
    traces = []
    for f in st.vertical.fig5:
        sel = f["cycles"] >= 20.0
        traces.append((f"ϖ = {f['varpi']:g} ({f['published']})", f["cycles"][sel], f["xi"][sel]))
    vplots.vertical_trajectories(traces, ax=ax)


def _fig6(st: ValidationStudy, ax: Any) -> None:
    rows = st.vertical.rows
    plots.contact_fraction_strip(
        [r["varpi"] for r in rows], [r["contact_fraction"] for r in rows], ax=ax
    )
    vplots.published_lines(ax, [2.0], "published: finite contact below ϖ ≈ 2")


def _fig7(st: ValidationStudy, axes: Any) -> None:
    for ax, pan in zip(np.ravel(axes), st.maps.fig7, strict=True):
        rows = pan["rows"]
        vplots.pushpull_points(
            pan["kappa"],
            pan["beta"],
            [r["varpi"] for r in rows],
            [r["alpha"] for r in rows],
            [r["mode"] if r["converged"] else None for r in rows],
            ax=ax,
        )


def _fig8(st: ValidationStudy, ax: Any) -> None:
    d = st.maps.fig8
    vplots.section_velocities(d["cycles"], d["traces"], d["separation"], ax=ax)


def _fig9(st: ValidationStudy, axes: Any) -> None:
    for ax, f in zip(axes, st.slider.fig9, strict=True):
        plots.orbit_plane(f["dzeta"], f["ds"], f["phases"], ax=ax)
        ax.set_title(f"Fig. {f['label']}: Δs = {f['delta_s']:.4f} (published {f['published']:g})")


def _fig10(st: ValidationStudy, axes: Any) -> None:
    d = st.slider.fig10
    ax0, ax1 = axes
    n = 61
    cyc = d["cycles"][:n]
    cos = d["unit_um"]
    u = cos * math.sqrt(2.0)  # u = (u·cosθ)/cos 45°
    lines = {}
    for b in (0.9, 9.0):
        s = np.abs(d["s"][b][:n])
        lines[f"β = {b:g}, unit u·cosθ"] = s * cos
        lines[f"β = {b:g}, unit u"] = s * u
    vplots.travel(cyc, lines, (30.0, 40.0), ax=ax0)
    dev = {}
    stops = {}
    for b in (0.9, 9.0):
        label = f"β = {b:g}"
        dev[label] = np.abs(d["delta_s"][b] - d["periodic"][b]) / abs(d["periodic"][b])
        stop = d["stop"][b]
        stops[label] = stop.cycle if stop else None
    vplots.settling(np.arange(1, len(dev["β = 0.9"]) + 1), dev, stops, 300.0, ax=ax1)


def _fig11(st: ValidationStudy, ax: Any) -> None:
    d = st.slider.fig11
    speed_m_s = np.asarray(d["speed_um_s"], float) * 1e-6  # the plot takes SI [m/s]
    plots.speed_vs_voltage(d["voltage"], speed_m_s, ax=ax)
    k, _ = scale_for(float(np.abs(speed_m_s).max()), "m/s")  # the prefix the plot chose
    ax.plot(
        d["voltage"],
        np.asarray(d["travel_um_s"], float) * 1e-6 * k,
        ls="none",
        marker="s",
        ms=4,
        mfc="none",
        color="#1f77b4",
        label="40 µm / travel time from rest",
    )
    ax.legend(loc="best", framealpha=0.9)


def _fig12(st: ValidationStudy, ax: Any) -> None:
    rows = st.maps.fig12
    plots.robustness_vs_lambda(
        [r["lam"] for r in rows], [r["delta_s"] if r["converged"] else None for r in rows], ax=ax
    )
    ax.set_ylim(*FIG12_YLIM)


#: (key, number, title, what the paper shows, size, grid, draw, caption)
_FIGURES: tuple[tuple[str, str, str, str, tuple[float, float], dict, Callable, str], ...] = (
    (
        "fig3",
        "3",
        "Head phase portrait",
        "phase portrait (τ, ξ, ξ') of one impact period",
        (7.0, 2.8),
        {"ncols": 2},
        _fig3,
        f"One impact period from the first contact end, ϖ = {FIG3_VARPI:g}. Model: exact "
        "vertical motion.",
    ),
    (
        "fig4",
        "4",
        "Impact period against ϖ",
        "period 1 only for 0.5 ≤ ϖ ≤ 2.6; two impacts per cycle in regions below 0.5",
        (7.0, 3.0),
        {},
        _fig4,
        f"Impact period (dots; periods > {LONG_PERIOD} cycles drawn as crosses on top) and hits "
        f"per cycle (squares) on the ϖ grid, {MAX_CYCLES} cycles "
        "from rest. Dotted: computed "
        "edges of the period-1 interval; dashed: published. Model: exact vertical motion.",
    ),
    (
        "fig5",
        "5",
        "Vertical trajectories",
        "periodic at ϖ = 2, period doubling at 2.9, aperiodic at 4.8",
        (7.0, 3.2),
        {},
        _fig5,
        "Gap ξ over cycles 20–30 from rest. Model: exact vertical motion (dense output).",
    ),
    (
        "fig6",
        "6",
        "Contact duration against ϖ",
        "finite contact only below ϖ ≈ 2",
        (7.0, 2.8),
        {},
        _fig6,
        "Share of the cycle in contact on the ϖ grid. Model: exact vertical motion.",
    ),
    (
        "fig7",
        "7",
        "Push/pull maps",
        "all push modes left of the λ = 1 curve",
        (7.0, 5.6),
        {"nrows": 2, "ncols": 2},
        _fig7,
        "Mode of the exact periodic orbit at every grid point; curve: λ = 1 of the fit.",
    ),
    (
        "fig8",
        "8",
        "Rigid limit α → 0, βκ/ϖ² = 1",
        "both starts reach the same periodic motion; separation velocity −ϖ",
        (7.0, 3.0),
        {},
        _fig8,
        "Slider velocity after each cycle from the two published starts. Model: exact rigid "
        "limit (dynamics.rigid).",
    ),
    (
        "fig9",
        "9",
        "Periodic orbits of Figs 9a/9b",
        "Δs = 1.1796 (push) and −3.5512 (pull)",
        (7.0, 3.2),
        {"ncols": 2},
        _fig9,
        "One cycle of the exact periodic orbit in the (ζ', s') plane, coloured by contact phase.",
    ),
    (
        "fig10",
        "10",
        "Published device transient",
        "40 µm after 30 impacts; ≥ 300 impacts to periodic motion",
        (7.0, 3.2),
        {"ncols": 2},
        _fig10,
        "Left: |travel| from rest for both quoted β and both length units (u = 0.11 µm). "
        "Right: distance of each cycle's Δs to the exact periodic Δs; dots: where the paper's "
        "successive-Δs rule stops. Model: exact transient from rest, periodic orbit.",
    ),
    (
        "fig11",
        "11",
        "Speed against voltage",
        "speed rises with voltage, about proportionally",
        (7.0, 3.0),
        {},
        _fig11,
        "β = 9, ϖ = 0.9, u proportional to V through the device's calibration, f_act from the "
        "device file (values in the table row). Model: exact periodic orbit.",
    ),
    (
        "fig12",
        "12",
        "Δs against λ",
        "Δs changes sign at λ = 1 (κ = 0.4, β = 1.5)",
        (7.0, 3.0),
        {},
        _fig12,
        f"Periodic Δs, ϖ varied at α = {FIG12_ALPHA:g} (y axis clipped to "
        f"[{FIG12_YLIM[0]:g}, {FIG12_YLIM[1]:g}]). Model: exact periodic "
        "orbit.",
    ),
)


def build(st: ValidationStudy) -> tuple[ValidationReport, dict[str, str]]:
    """The page model and the figures as SVG strings keyed by file stem."""
    from betvdesign import __version__

    figs = []
    svgs = {}
    for key, num, title, paper, size, grid, draw, caption in _FIGURES:
        _, svg = _figure(key, size, lambda ax, d=draw: d(st, ax), **grid)
        svgs[key] = svg
        figs.append(FigureEntry(key, num, title, paper, caption, svg))
    comps = st.comparisons
    counts: dict[str, int] = {}
    for c in comps:
        counts[c.verdict] = counts.get(c.verdict, 0) + 1
    variants = tuple(
        {
            "beta": f"{r['beta']:g}",
            "unit": r["unit"],
            "cycles": str(r["cycles"]),
            "s_um": f"{r['s_um']:.2f}",
            "rel": f"{100 * r['rel']:+.1f} %",
        }
        for r in st.slider.fig10_table
    )
    rep = ValidationReport(
        title="Validation against the published paper",
        version=__version__,
        paper=st.paper,
        device=st.device.name,
        counts=tuple(sorted(counts.items())),
        rows=tuple(_row(c) for c in comps),
        variants=variants,
        figures=tuple(figs),
        stop_rtol=f"{STOP_RTOL:g}",
        command=COMMAND,
    )
    return rep, svgs


def render_html(report: ValidationReport) -> str:
    """One self-contained HTML document (inline CSS and SVG)."""
    return render_template(TEMPLATE, r=report, svg=Markup)


def _md_cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def render_markdown(report: ValidationReport) -> str:
    """The comparison table and figure links as Markdown (for docs/)."""
    out = [
        f"# {report.title}",
        "",
        f"{report.paper}, recomputed with betvdesign {report.version} (exact model, the "
        f"paper's parameters, rest at τ = 0). Generated by `{report.command}`, which also "
        "writes the self-contained page `validation.html` (and `validation.pdf` without "
        "`--no-pdf`).",
        "",
        "Verdicts: " + ", ".join(f"{k} {n}" for k, n in report.counts) + ".",
        "",
        "| Fig | Statement | Published | Computed | Rel. diff | Verdict | Explanation (measured) |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in report.rows:
        cells = (r.fig, r.statement, r.published, r.computed, r.rel_diff, r.verdict, r.explanation)
        out.append("| " + " | ".join(_md_cell(c) for c in cells) + " |")
    out += ["", "## Figures", ""]
    for f in report.figures:
        out += [
            f"### Fig. {f.number}: {f.title}",
            "",
            f"Paper: {f.paper}.",
            "",
            f"![Fig. {f.number}](figures/{f.key}.svg)",
            "",
            f.caption,
            "",
        ]
    return "\n".join(out)


def write_validation_report(
    outdir: str | Path, *, device: str | Path | None = None, pdf: bool = True
) -> list[Path]:
    """Run the study and write validation.html, .md, figures/*.svg (and .pdf)."""
    st = run_validation(device)
    rep, svgs = build(st)
    out = Path(outdir)
    (out / "figures").mkdir(parents=True, exist_ok=True)
    html = render_html(rep)
    written = [write_atomic(out / "validation.html", html)]
    written.append(write_atomic(out / "validation.md", render_markdown(rep)))
    for key, svg in svgs.items():
        doc = '<?xml version="1.0" encoding="utf-8"?>\n' + svg + "\n"
        written.append(write_atomic(out / "figures" / f"{key}.svg", doc))
    if pdf:
        written.append(write_atomic(out / "validation.pdf", render_pdf(html)))
    return written
