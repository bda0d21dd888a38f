"""``betv bench``: work-precision study of the exact solver against the alternatives.

Thin: everything is :func:`betvdesign.bench.workprecision.run` and
:func:`betvdesign.bench.chart.write_outputs`. ``--json`` prints the rows
``{"method", "setting", "design", "error", "seconds", "status", ...}`` on stdout
(our solver's rows have method ``"exact"``); ``-o DIR`` also writes the chart
(PNG, SVG) and the table (CSV, JSON). ``--quick`` (default) takes seconds to a
minute; ``--full`` is the study of the README chart (minutes).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import typer

from betvdesign.cli import app
from betvdesign.cli.common import user_errors
from betvdesign.cli.physics import (
    QualityNormalOpt,
    QualityTangentialOpt,
    RestitutionOpt,
    ZetaHOpt,
    ZetaVOpt,
    physics_terms,
)
from betvdesign.errors import UsageError


@app.command("bench")
def bench_cmd(
    full: bool = typer.Option(False, "--full/--quick", help="Full study (minutes) or quick."),
    as_json: bool = typer.Option(False, "--json", help="Print the rows as JSON on stdout."),
    outdir: Path | None = typer.Option(
        None, "-o", "--output", help="Write work_precision.{png,svg,csv,json} here."
    ),
    design: list[str] = typer.Option(
        [], "--design", help="Design(s) to run (default all): push, pull, near-lambda-1, ..."
    ),
    method: list[str] = typer.Option(
        [], "--method", help="Method(s) to run (default all): exact, solve_ivp-DOP853, ..."
    ),
) -> None:
    """Chart error against CPU time for the exact solver and the alternatives."""
    from betvdesign.bench import workprecision as wp

    with user_errors():
        level = "full" if full else "quick"
        unknown = [d for d in design if d not in wp.DESIGNS]
        if unknown:
            raise UsageError(f"unknown design {', '.join(unknown)}; one of {', '.join(wp.DESIGNS)}")
        known = {m.method for m in wp.methods(level)}
        bad = [m for m in method if m not in known]
        if bad:
            raise UsageError(f"unknown method {', '.join(bad)}; one of {', '.join(sorted(known))}")
        if outdir is not None and outdir.exists() and not outdir.is_dir():
            raise UsageError(f"{outdir}: not a directory")

        def progress(msg: str) -> None:
            print(f"bench: {msg}", file=sys.stderr)

        rows = wp.run(
            level,
            designs=design or None,
            only=method or None,
            progress=None if as_json else progress,
        )
        written = []
        if outdir is not None:
            from betvdesign.bench.chart import write_outputs

            try:
                written = write_outputs(rows, outdir)
            except OSError as exc:
                raise UsageError(f"{outdir}: cannot write ({exc.strerror or exc})") from None
    if as_json:
        typer.echo(json.dumps([r.as_dict() for r in rows], indent=1, allow_nan=False))
        return
    for r in rows:
        err = "—" if r.error is None else f"{r.error:.2e}"
        sec = "—" if r.as_dict()["seconds"] is None else f"{r.seconds:.4f}"
        typer.echo(
            f"{r.design:14s} {r.metric:8s} {r.method:18s} {r.setting:20s} "
            f"err {err:>9s}  cpu {sec:>8s} s  {r.status}"
        )
    for s in wp.summarise(rows):
        if s["ratio"] is not None and s["exact_error"] is not None:
            typer.echo(
                f"{s['design']} {s['metric']}: exact {s['exact_error']:.1e} in "
                f"{s['exact_seconds']:.4f} s; cheapest ≤1e-6: {s['cheapest_alternative']} "
                f"{s['alternative_seconds']:.4f} s (×{s['ratio']:.0f})"
            )
    for p in written:
        typer.echo(f"wrote {p}")


def methods_report(files: list[Path], outdir: Path, *, pdf: bool = True) -> int:
    """``betv report --methods [ROWS.json] -o DIR``: the methods report; exit code.

    Without a file the quick work-precision study runs now; with one, its rows (the
    JSON written by ``betv bench -o`` or ``benchmarks/work_precision.py``) are used,
    and the failure map from ``failure_map.json`` beside it when present.
    """
    from betvdesign.report.methods import load_rows, write_methods_report

    with user_errors():
        if len(files) > 1:
            raise UsageError("--methods takes at most one work-precision JSON file")
        if outdir.exists() and not outdir.is_dir():
            raise UsageError(f"output path {outdir} exists and is not a directory")
        rows = fm = None
        if files:
            try:
                rows, fm = load_rows(files[0])
            except (OSError, ValueError, KeyError, TypeError) as exc:
                raise UsageError(f"{files[0]}: not a work-precision JSON ({exc})") from None
        written = write_methods_report(outdir, rows=rows, fm_rows=fm, pdf=pdf)
    typer.echo("methods report -> " + ", ".join(str(p) for p in written))
    return 0


@app.command("ladder")
def ladder_cmd(
    question: str = typer.Argument(..., help="mode | regime | delta_s | transient | stability"),
    varpi: float = typer.Option(..., "--varpi", help="ϖ [-]"),
    alpha: float = typer.Option(..., "--alpha", help="α [-]"),
    beta: float = typer.Option(..., "--beta", help="β [-]"),
    kappa: float = typer.Option(..., "--kappa", help="κ [-]"),
    tol: float = typer.Option(1e-6, "--tol", help="Accuracy asked (relative, for delta_s)."),
    fidelity: str | None = typer.Option(
        None, "--fidelity", help="Force a rung: lambda, vertical, rigid, full, periodic."
    ),
    quality_normal: QualityNormalOpt = None,
    zeta_v: ZetaVOpt = None,
    quality_tangential: QualityTangentialOpt = None,
    zeta_h: ZetaHOpt = None,
    restitution: RestitutionOpt = None,
    as_json: bool = typer.Option(False, "--json", help="Print the answer as JSON."),
) -> None:
    """Answer a question with the cheapest adequate model, and say which and why
    (with damping or restitution: --quality-normal/--zeta-v, --quality-tangential/
    --zeta-h, --restitution; the λ and rigid rungs then refuse)."""
    from betvdesign.checks import fidelity as fid
    from betvdesign.model.params import ModelParams

    with user_errors():
        terms = physics_terms(quality_normal, zeta_v, quality_tangential, zeta_h, restitution)
        p = ModelParams(varpi, alpha, beta, kappa, **terms)
        ans = fid.answer(p, question, tol=tol, force=fidelity)  # type: ignore[arg-type]
    doc = {
        **ans.choice.as_dict(),
        "status": ans.status,
        "message": ans.message,
        "value": ans.value,
        "mode": ans.mode,
        "seconds": ans.seconds,
        "params": p.as_dict(),  # with ζ_v, ζ_h, e when one is set
    }
    if as_json:
        typer.echo(json.dumps(doc, allow_nan=False, default=float))
        return
    if not p.ideal:
        typer.echo(f"with ζ_v = {p.zeta_v:g}, ζ_h = {p.zeta_h:g}, e = {p.restitution:g}")
    typer.echo(f"{question}: {ans.value!r} (mode {ans.mode}) [{ans.status}] {ans.message}")
    typer.echo(f"model: {doc['model']} (rung {ans.choice.rung}); why: {ans.choice.reason}")
