"""The methods report: work-precision chart, failure map and fidelity ladder (HTML/PDF).

``betv report --methods -o DIR`` writes ``methods.html`` (self-contained) and
``methods.pdf``. Built like the design reports: a plain-data model first
(:class:`MethodsReport`), rendered second by Jinja2 (autoescape) with the design
reports' CSS, WeasyPrint for the PDF, atomic writes. The work-precision rows are
measured now (quick study, unless rows are passed in, e.g. loaded from the JSON
that ``benchmarks/work_precision.py`` writes); the ladder's trust limits are the
measured ones the toolkit itself uses (``betvdesign/data/fidelity_measured.json``, read by
:func:`betvdesign.checks.fidelity.measured`).
The same rows give the same bytes.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from markupsafe import Markup

from betvdesign import plots
from betvdesign.bench.chart import work_precision_figure
from betvdesign.bench.failuremap import default_varpis, failure_map_figure, scan
from betvdesign.bench.failures import FAILURES, Failure
from betvdesign.bench.workprecision import DESIGNS, Row, summarise
from betvdesign.output.files import check_output_dir, write_group
from betvdesign.report.render import render_pdf, render_template

TEMPLATE = "methods.html.j2"
REGENERATE = "python benchmarks/work_precision.py && python benchmarks/work_precision.py --ladder"


@dataclass(frozen=True)
class RungRow:
    name: str
    model: str
    answers: str
    exact: str
    cost: str
    source: str


@dataclass(frozen=True)
class MethodsReport:
    """Plain data of the methods report (every number already formatted)."""

    title: str
    version: str
    level: str
    chart_svg: str
    designs: tuple[tuple[str, str, str], ...]
    ratios: tuple[dict[str, str], ...]
    failures: tuple[Failure, ...]
    rungs: tuple[RungRow, ...]
    lambda_summary: str
    lambda_bands: tuple[dict[str, Any], ...]
    lambda_svg: str
    failure_svg: str
    mispredictions: tuple[dict[str, str], ...]
    held_out_bands: tuple[tuple[str, str, str, str], ...]
    provenance: str
    sample_summary: str
    not_converged: str
    rigid_summary: str
    command: str


def _fmt(x: float | None, spec: str = ".2e") -> str:
    return "—" if x is None else format(x, spec)


def _lambda_figure(bands: Sequence[dict[str, Any]]) -> str:
    """Bar chart: points and mispredictions of the λ rule per |λ − 1| band."""
    with plots.figure_style():
        fig, ax = plots.new_figure(6.4, 2.6)
        labels = [f"{b['lo']:g}–{b['hi']:g}" if b["hi"] else f"≥ {b['lo']:g}" for b in bands]
        x = range(len(bands))
        ax.bar(x, [b["points"] for b in bands], color="#bbbbbb", label="points (converged)")
        ax.bar(x, [b["mispredicted"] for b in bands], color="#d62728", label="λ mispredicts")
        ax.set_xticks(list(x), labels)
        ax.set_xlabel("|λ − 1| [-]")
        ax.set_ylabel("grid points")
        ax.set_yscale("log")
        ax.legend(loc="upper right")
        return plots.figure_svg(fig, "lam")


def _ratio_rows(rows: Sequence[Row]) -> tuple[dict[str, str], ...]:
    """The speed table: per design the exact solver against its cheapest alternative.

    Parameters
    ----------
    rows : sequence of Row
        Work-precision rows.

    Returns
    -------
    tuple of dict
        Per design and metric: errors, times [s] and their ratio, as text.
    """
    return tuple(
        {
            "design": s["design"],
            "metric": s["metric"],
            "exact_error": _fmt(s["exact_error"], ".1e"),
            "exact_seconds": _fmt(s["exact_seconds"]),
            "alternative": s["cheapest_alternative"] or "none reaches 1e-6",
            "alternative_seconds": _fmt(s["alternative_seconds"]),
            "ratio": "—" if s["ratio"] is None else f"×{s['ratio']:.0f}",
        }
        for s in summarise(rows)
    )


def _rung_rows(costs: dict[str, float], full_cycles: int) -> tuple[RungRow, ...]:
    """The fidelity ladder's table: per rung its model, answers, exactness and cost.

    Parameters
    ----------
    costs : dict of str to float
        Measured CPU time per rung [s].
    full_cycles : int
        Cycles of the "full" rung's measured transient.

    Returns
    -------
    tuple of RungRow
        One row per rung.
    """
    from betvdesign.checks.fidelity import RUNG_INFO, RUNGS

    return tuple(
        RungRow(
            r,
            RUNG_INFO[r].model,
            ", ".join(sorted(RUNG_INFO[r].answers)),
            RUNG_INFO[r].exact,
            f"{costs[r]:.2e} s" + (f" ({full_cycles} cycles)" if r == "full" else ""),
            RUNG_INFO[r].source,
        )
        for r in RUNGS
    )


def _lambda_tables(lam: dict[str, Any]) -> dict[str, Any]:
    """The λ rule's section: its misprediction rates, in words and tables.

    Parameters
    ----------
    lam : dict
        The measured λ data (map and held-out sample).

    Returns
    -------
    dict
        :class:`MethodsReport`'s ``lambda_summary``, ``sample_summary``,
        ``mispredictions``, ``held_out_bands`` and ``not_converged``.
    """
    val = lam["held_out"]
    mis = tuple(
        {k: (f"{v:.4g}" if isinstance(v, float) else str(v)) for k, v in m.items()}
        for m in lam["mispredictions"]
    )
    nc: dict[str, int] = {}
    for r in lam["not_converged"]:
        key = f"{r['status']} at ϖ = {r['varpi']:g}"
        nc[key] = nc.get(key, 0) + 1
    return dict(
        lambda_summary=(
            f"On the push/pull map ({lam['points']} points, {lam['converged']} with a converged "
            f"periodic orbit) the λ rule names the wrong mode at {lam['mispredicted']} points "
            f"({100 * lam['rate']:.2f} %)."
        ),
        sample_summary=(
            f"On {val['points']} held-out seeded random designs (uniform in the window and "
            f"the fit range; {val['converged']} with a moving orbit) it is wrong at "
            f"{val['mispredicted']} ({100 * val['rate']:.2f} %, at most "
            f"{100 * val['upper_95']:.2f} % at 95 % confidence), "
            f"{sum(1 for m in val['mispredictions'] if abs(m['lam'] - 1) > 1)} of them with "
            "|λ − 1| > 1. So no verdict rests on λ: betv check and betv report always take "
            "the mode from the exact periodic orbit, and λ is shown beside it."
        ),
        mispredictions=mis,
        held_out_bands=tuple(
            (
                f"{b['lo']:g}–{b['hi']:g}" if b["hi"] is not None else f"≥ {b['lo']:g}",
                str(b["points"]),
                str(b["mispredicted"]),
                f"{100 * b['upper_95']:.2g} %",
            )
            for b in val["bands"]
        ),
        not_converged="; ".join(f"{n} {k}" for k, n in sorted(nc.items())) or "none",
    )


def build(
    rows: Sequence[Row], fm_rows: Sequence[dict[str, Any]], *, level: str = "quick"
) -> MethodsReport:
    """The report model from work-precision rows, the failure map along ϖ
    (:func:`betvdesign.bench.failuremap.scan` rows) and the measured ladder data."""
    from betvdesign import __version__
    from betvdesign.checks.fidelity import measured_document

    doc = measured_document()
    MEASURED = doc["measured"]
    lam = MEASURED["lambda"]
    rig = MEASURED["rigid"]
    fig = work_precision_figure(rows, tall=True)
    alphas = [s["alpha"] for s in rig["samples"]]
    return MethodsReport(
        title="betvdesign methods: speed, accuracy and model choice",
        version=__version__,
        level=level,
        chart_svg=plots.figure_svg(fig, "wp"),
        designs=tuple(
            (d.name, ", ".join(f"{k} = {v:g}" for k, v in d.params.as_dict().items()), d.why)
            for d in DESIGNS.values()
            if any(r.design == d.name for r in rows)
        ),
        ratios=_ratio_rows(rows),
        failures=FAILURES,
        rungs=_rung_rows(MEASURED["costs_cpu_s"], MEASURED["full_cycles"]),
        **_lambda_tables(lam),
        lambda_bands=tuple(lam["bands"]),
        lambda_svg=_lambda_figure(lam["bands"]),
        failure_svg=plots.figure_svg(failure_map_figure(fm_rows), "fm"),
        provenance=", ".join(f"{k}: {v}" for k, v in doc["provenance"].items()),
        rigid_summary=(
            f"relative Δs error of the α → 0 rigid limit ≤ {rig['coef']:.3g}·α^{rig['power']:.2f} "
            f"over {len(alphas)} samples (α from {min(alphas):g} "
            f"to {max(alphas):g}); its mode (always pull) disagrees "
            f"with the full model at {100 * lam['rigid_mode_disagreement']:.1f} % of the map"
        ),
        command=REGENERATE,
    )


def render_html(report: MethodsReport) -> str:
    """One self-contained HTML document (inline CSS and SVG)."""
    return render_template(TEMPLATE, r=report, svg=Markup)


def load_rows(path: str | Path) -> tuple[list[Row], list[dict[str, Any]] | None]:
    """Rows from the JSON that ``betv bench -o`` / the benchmark script writes, and the
    failure-map rows from ``failure_map.json`` next to it when present."""
    path = Path(path)
    doc = json.loads(path.read_text("utf-8"))
    rows = [
        Row(**{**r, "seconds": r["seconds"] if r["seconds"] is not None else float("nan")})
        for r in doc["rows"]
    ]
    fm_path = path.with_name("failure_map.json")
    fm = json.loads(fm_path.read_text("utf-8"))["rows"] if fm_path.is_file() else None
    return rows, fm


def write_methods_report(
    outdir: str | Path,
    *,
    rows: Sequence[Row] | None = None,
    fm_rows: Sequence[dict[str, Any]] | None = None,
    pdf: bool = True,
) -> list[Path]:
    """Write methods.html (and methods.pdf). Runs the quick work-precision study when
    ``rows`` is None and a 12-point failure-map scan when ``fm_rows`` is None."""
    from betvdesign.bench import workprecision as wp

    level = "loaded from file"
    if rows is None:
        rows, level = wp.run("quick"), "quick"
    if fm_rows is None:
        fm_rows = scan(default_varpis(8))
    out = check_output_dir(outdir)
    html = render_html(build(rows, fm_rows, level=level))
    files: dict[Path, str | bytes] = {out / "methods.html": html}
    if pdf:
        files[out / "methods.pdf"] = render_pdf(html)
    return write_group(files)  # HTML and PDF together, or neither
