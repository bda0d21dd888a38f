"""``betv sweep FILE|pushpull|regime|lambda|atlas``: design-space sweeps (thin layer over
``betvdesign.studies``).

Every sweep takes the execution options (``--executor serial|process|dask``,
``--workers``, ``--chunksize``, ``--scheduler tcp://host:port``), streams rows to
``--out results.csv`` (+ ``results.json`` sidecar) as they finish, resumes an
interrupted output when run again with the same arguments, shows a rich
progress bar on stderr and prints a JSON summary on stdout with ``--json``.

The optional physics (``--quality-normal``/``--zeta-v``, ``--quality-tangential``/
``--zeta-h``, ``--restitution``; :mod:`betvdesign.cli.physics`) is fixed over a sweep;
absent, the sweep is of the paper's model. ``regime`` takes the normal terms only (the
vertical motion does not depend on ζ_h).

``betv sweep atlas`` (:mod:`betvdesign.studies.atlas`) is the sweep for grids of
millions of points: ``--out`` is a directory of chunk files instead of one CSV, ``-x
dask`` without ``--scheduler`` starts a local cluster of ``-j`` workers, and the merged
table is ``table.npz`` (``--csv``: also ``table.csv``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

import typer
from typer.core import TyperGroup

from betvdesign.cli import app
from betvdesign.cli.common import (
    ChunkOpt,
    Execution,
    ExecutorOpt,
    FidelityOpt,
    JsonOpt,
    MaxCyclesOpt,
    OutOpt,
    OverwriteOpt,
    QuietOpt,
    ResidualTolOpt,
    RetiredTolOpt,
    SchedulerOpt,
    WorkersOpt,
    emit,
    float_option,
    int_option,
    interruptible,
    output_file,
    run_block,
    user_errors,
)
from betvdesign.cli.physics import (
    QualityNormalOpt,
    QualityTangentialOpt,
    RestitutionOpt,
    ZetaHOpt,
    ZetaVOpt,
    physics_terms,
)
from betvdesign.errors import UsageError
from betvdesign.output.files import atomic_path
from betvdesign.spec import limits
from betvdesign.studies.terms import SYMBOLS

#: Disagreements/failures printed in the human summary (--json lists all).
MAX_LISTED = 40


class _SweepGroup(TyperGroup):
    """``betv sweep FILE --vary ...`` is ``betv sweep device FILE --vary ...``: a first
    argument that is not a sub-command (a device file) goes to ``device``."""

    def parse_args(self, ctx: typer.Context, args: list[str]) -> list[str]:
        if args and not args[0].startswith("-") and args[0] not in self.commands:
            args = ["device", *args]
        return super().parse_args(ctx, args)


sweep_app = typer.Typer(
    name="sweep",
    cls=_SweepGroup,
    help="Sweeps: a device file's own fields in physical units (`betv sweep FILE --vary "
    "FIELD=LO:HI`), and the dimensionless push/pull map, regime diagram and Δs against λ.",
    no_args_is_help=True,
)
app.add_typer(sweep_app, name="sweep")


def axis(text: str, name: str) -> list[float]:
    from betvdesign.studies.engine.grid import parse_range

    values = parse_range(text, name)
    return [float(v) for v in values]


@sweep_app.command("pushpull")
def pushpull_cmd(
    varpi: Annotated[str, typer.Option(help="ϖ range, e.g. 0.5:2:0.1 or 0.5,1,1.5.")],
    alpha: Annotated[str, typer.Option(help="α range.")],
    beta: Annotated[str, typer.Option(help="β range.")],
    kappa: Annotated[str, typer.Option(help="κ range.")],
    fidelity: FidelityOpt = "periodic",
    residual_tol: ResidualTolOpt = 1e-10,
    max_cycles: MaxCyclesOpt = None,
    quality_normal: QualityNormalOpt = None,
    zeta_v: ZetaVOpt = None,
    quality_tangential: QualityTangentialOpt = None,
    zeta_h: ZetaHOpt = None,
    restitution: RestitutionOpt = None,
    _tol: RetiredTolOpt = None,
    figure: Annotated[
        Path | None, typer.Option("--figure", help="Write the map figure (SVG/PNG/PDF).")
    ] = None,
    out: OutOpt = None,
    overwrite: OverwriteOpt = False,
    executor: ExecutorOpt = "process",
    workers: WorkersOpt = None,
    chunksize: ChunkOpt = None,
    scheduler: SchedulerOpt = None,
    as_json: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Push/pull map over ϖ, α, β, κ, each point solved to its periodic state.

    \f
    Over 80 lines on purpose (not in ``--help``: click stops the help at the form
    feed): a typer command, most of it the declaration of its options
    (the four parameter ranges and the shared study options).
    """
    from betvdesign.studies.pushpull import run_pushpull

    with user_errors(), interruptible(out):
        terms = physics_terms(quality_normal, zeta_v, quality_tangential, zeta_h, restitution)
        axes = {n: axis(t, n) for n, t in (("varpi", varpi), ("alpha", alpha))}
        axes |= {n: axis(t, n) for n, t in (("beta", beta), ("kappa", kappa))}
        if figure is not None:
            output_file(figure, suffixes=(".svg", ".png", ".pdf"))
        execution = Execution(executor, workers, chunksize, scheduler, out, overwrite, quiet)
        run, summary = execution.run(
            "push/pull map",
            run_pushpull,
            **axes,
            fidelity=fidelity.lower(),
            tol=residual_tol,
            max_cycles=max_cycles,
            **terms,
        )
        if figure is not None:
            from betvdesign.plots.studies import save_pushpull_figure

            with atomic_path(figure) as tmp:  # a whole figure or none
                save_pushpull_figure(run.rows, tmp)
        data = {"study": "pushpull", **run_block(run), **summary.as_dict()}
        data["figure"] = str(figure) if figure else None

        def human() -> None:
            agree = summary.agreement
            if not summary.terms.ideal:
                typer.echo(f"with {summary.terms.statement()} (λ: the idealised fit)")
            typer.echo(
                f"{summary.n_points} points, {summary.n_converged} converged "
                f"({summary.n_push} push, {summary.n_pull} pull)"
            )
            typer.echo(
                f"λ fit predicts push at {summary.n_predicted_push}/{summary.n_points} points"
            )
            if agree is not None:
                typer.echo(
                    f"λ rule agrees at {summary.n_agree}/{summary.n_converged} "
                    f"({100 * agree:.1f} %)"
                )
            lines = [
                f"  disagrees: ϖ={d['varpi']:g} α={d['alpha']:g} β={d['beta']:g} "
                f"κ={d['kappa']:g} λ={d['lam']:.4g} simulated {d['mode']} Δs={d['delta_s']:.4g}"
                for d in summary.disagreements
            ]
            lines += [
                f"  {'unbounded' if d['status'] == 'unbounded' else 'not converged'}: "
                f"ϖ={d['varpi']:g} α={d['alpha']:g} β={d['beta']:g} "
                f"κ={d['kappa']:g}: {d['status']}"
                + (f" (on the resonance a·ϖ² = 1, a = {d['resonance']})" if d["resonance"] else "")
                + f": {d['message']}"
                for d in summary.not_converged
            ]
            for line in lines[:MAX_LISTED]:
                typer.echo(line)
            if len(lines) > MAX_LISTED:
                typer.echo(f"  ... and {len(lines) - MAX_LISTED} more (--json lists every point)")
            typer.echo(f"{run.computed} computed, {run.resumed} resumed in {run.elapsed_s:.2f} s")

        emit(data, as_json, human)


@sweep_app.command("lambda")
def lambda_cmd(
    kappa: Annotated[float, typer.Option(help="Fixed κ.", callback=float_option(gt=0.0))],
    beta: Annotated[float, typer.Option(help="Fixed β.", callback=float_option(gt=0.0))],
    lam: Annotated[
        str, typer.Option("--lambda", help="λ targets, e.g. 0.5:1.5:0.05.")
    ] = "0.5:1.5:0.05",
    vary: Annotated[
        str, typer.Option(help="Parameter moved to reach λ: varpi or alpha.")
    ] = "varpi",
    alpha: Annotated[
        float | None, typer.Option(help="Fixed α (when varying ϖ).", callback=float_option(gt=0.0))
    ] = None,
    varpi: Annotated[
        float | None, typer.Option(help="Fixed ϖ (when varying α).", callback=float_option(gt=0.0))
    ] = None,
    residual_tol: ResidualTolOpt = 1e-10,
    max_cycles: MaxCyclesOpt = None,
    quality_normal: QualityNormalOpt = None,
    zeta_v: ZetaVOpt = None,
    quality_tangential: QualityTangentialOpt = None,
    zeta_h: ZetaHOpt = None,
    restitution: RestitutionOpt = None,
    _tol: RetiredTolOpt = None,
    out: OutOpt = None,
    overwrite: OverwriteOpt = False,
    executor: ExecutorOpt = "process",
    workers: WorkersOpt = None,
    chunksize: ChunkOpt = None,
    scheduler: SchedulerOpt = None,
    as_json: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Δs against λ for fixed (κ, β), across the push/pull boundary."""
    from betvdesign.studies.lambda_scan import run_lambda_scan

    with user_errors(), interruptible(out):
        terms = physics_terms(quality_normal, zeta_v, quality_tangential, zeta_h, restitution)
        targets = axis(lam, "lambda")
        execution = Execution(executor, workers, chunksize, scheduler, out, overwrite, quiet)
        run, summary = execution.run(
            "Δs against λ",
            run_lambda_scan,
            targets,
            kappa=kappa,
            beta=beta,
            vary=vary.lower(),
            alpha=alpha,
            varpi=varpi,
            tol=residual_tol,
            max_cycles=max_cycles,
            **terms,
        )
        rows = [
            {k: r[k] for k in ("lam", "varpi", "alpha", "status", "mode", "delta_s")}
            for r in run.rows
        ]
        data = {"study": "lambda", **run_block(run), **summary.as_dict(), "rows": rows}

        def human() -> None:
            if not summary.terms.ideal:
                typer.echo(f"with {summary.terms.statement()} (λ: the idealised fit)")
            typer.echo(f"{'λ':>8} {'ϖ':>8} {'α':>8} {'Δs':>12}  mode / status")
            for r in rows:
                ds = "—" if r["delta_s"] is None else f"{r['delta_s']:.5g}"
                typer.echo(
                    f"{r['lam']:8.4g} {r['varpi']:8.4g} {r['alpha']:8.4g} {ds:>12}  "
                    f"{r['mode'] or r['status']}"
                )
            where = (
                ", ".join(
                    f"between λ = {c['from']:.4g} and {c['to']:.4g}" for c in summary.crossings
                )
                or "nowhere in the range"
            )
            typer.echo(f"Δs changes sign {where} (the fit puts the boundary at λ = 1)")

        emit(data, as_json, human)


@sweep_app.command("regime")
def regime_cmd(
    varpi: Annotated[
        str, typer.Option(help="ϖ grid in (0, 10], e.g. 0.005:10:0.005.")
    ] = "0.005:10:0.005",
    max_cycles: Annotated[
        int,
        typer.Option(
            help=f"Horizon [cycles, 2 to {limits.MAX_CYCLES:,}]; the second half is analysed.",
            callback=int_option(2, limits.MAX_CYCLES),
        ),
    ] = 400,
    quality_normal: QualityNormalOpt = None,
    zeta_v: ZetaVOpt = None,
    restitution: RestitutionOpt = None,
    out: OutOpt = None,
    overwrite: OverwriteOpt = False,
    executor: ExecutorOpt = "process",
    workers: WorkersOpt = None,
    chunksize: ChunkOpt = None,
    scheduler: SchedulerOpt = None,
    as_json: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Vertical regime diagram: impact period and contact fraction over ϖ."""
    from betvdesign.studies.regime import LONG_PERIOD, run_regime

    with user_errors(), interruptible(out):
        terms = physics_terms(quality_normal, zeta_v, restitution=restitution)
        del terms["zeta_h"]  # the vertical motion does not depend on it
        grid = axis(varpi, "varpi")
        execution = Execution(executor, workers, chunksize, scheduler, out, overwrite, quiet)
        run, summary = execution.run(
            "vertical regimes", run_regime, grid, max_cycles=max_cycles, **terms
        )
        data = {"study": "regime", **run_block(run), **summary}

        def human() -> None:
            if "terms" in summary:
                typer.echo(
                    "with "
                    + ", ".join(f"{SYMBOLS[k]} = {v:g}" for k, v in summary["terms"].items())
                )
            for iv in summary["overview"]:
                typer.echo(
                    f"ϖ {iv['from']:8.4g} – {iv['to']:<8.4g} {iv['label']:<14} "
                    f"({iv['points']} points)"
                )
            for e in summary["errors"]:
                typer.echo(f"  error at ϖ={e['varpi']:g}: {e['message']}")
            typer.echo(
                f"(overview: periods > {LONG_PERIOD} cycles shown as aperiodic; "
                "--json lists every interval)"
            )

        emit(data, as_json, human)


@sweep_app.command("device")
def device_cmd(
    file: Annotated[Path, typer.Argument(help="Device YAML file.")],
    vary: Annotated[
        list[str],
        typer.Option(
            "--vary",
            metavar="FIELD=LO:HI",
            help="A field of the file and its range in any unit of the field "
            "(drive.frequency=1kHz:4kHz, slider.beam_width=5um:45um; an SI prefix alone "
            "means the field's SI unit: drive.frequency=1k:4k). Once (speed against the "
            "field) or twice (the exact-mode map).",
        ),
    ],
    points: Annotated[
        int,
        typer.Option(
            "--points", "-n", help="Points per field (2 to 400).", callback=int_option(2, 400)
        ),
    ] = 40,
    log: Annotated[bool, typer.Option("--log", help="Log-spaced grid.")] = False,
    set_name: Annotated[
        str | None, typer.Option("--set", help="Actuator set (default: the first).")
    ] = None,
    residual_tol: ResidualTolOpt = 1e-10,
    figure: Annotated[
        Path | None, typer.Option("--figure", help="Write the figure (SVG/PNG/PDF).")
    ] = None,
    out: OutOpt = None,
    overwrite: OverwriteOpt = False,
    executor: ExecutorOpt = "process",
    workers: WorkersOpt = None,
    chunksize: ChunkOpt = None,
    scheduler: SchedulerOpt = None,
    as_json: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """Sweep a device file's own fields in physical units: 1-D, the speed against the
    field with the exact mode's bands and every mode flip bisected; 2-D, the exact-mode
    map (push/pull/stalled/not driven/unbounded) with the device marked and the paper's
    λ = 1 curve over it. Every point is the device with those values through the same
    derivation as `betv check` and its answer over the travel (mode and speed: the
    periodic orbit, or the crossing from rest where the slider has not settled by then;
    each row names its basis)."""
    from betvdesign.spec.loader import load_device
    from betvdesign.studies.fieldsweep import parse_axis, run_fieldsweep

    with user_errors(), interruptible(out):
        if not 1 <= len(vary) <= 2:
            raise UsageError("--vary: give one or two fields")
        spec = load_device(file)
        axes = [parse_axis(spec, v, points, log=log) for v in vary]
        if figure is not None:
            output_file(figure, suffixes=(".svg", ".png", ".pdf"))
        execution = Execution(executor, workers, chunksize, scheduler, out, overwrite, quiet)
        run, summary = execution.run(
            "field sweep", run_fieldsweep, file, axes, set_name=set_name, tol=residual_tol
        )
        summary["name"] = spec.name
        if figure is not None:
            from betvdesign.plots.fieldsweep import save_fieldsweep_figure

            with atomic_path(figure) as tmp:
                save_fieldsweep_figure(run.rows, summary, tmp)
        data = {"study": "fieldsweep", **run_block(run), **summary}
        data["figure"] = str(figure) if figure else None
        emit(data, as_json, lambda: _print_fieldsweep(spec.name, summary, run))


def _fh(n: int) -> str:
    """``f_h`` or ``f_h/n``: where the sub-resonance of order ``n`` lies."""
    return "f_h" if n == 1 else f"f_h/{n}"


def _print_fieldsweep(name: str, summary: dict[str, Any], run: Any) -> None:
    """The text of ``betv sweep FILE``: the fields, the modes' counts, the flips."""
    fields = " × ".join(
        f"{f['field']} {f['lo']:.4g}–{f['hi']:.4g} {f['unit']}".rstrip() for f in summary["fields"]
    )
    typer.echo(f"{name} [{summary['set']}]: {fields}, {summary['points']} points")
    typer.echo("exact modes: " + ", ".join(f"{k} {v}" for k, v in summary["modes"].items()))
    n_coupled = summary.get("models", {}).get("coupled", 0)
    if n_coupled:
        typer.echo(
            f"coupled head (drawn, no measured resonances) at {n_coupled} of "
            f"{summary['points']} points: their mode and speed are betv check's, the coupled "
            'model\'s (docs/MODEL.md "Coupled head"; column model)'
        )
    f0 = summary["fields"][0]
    marks = summary.get("marks") or {}
    where = {m["n"]: m["at"] for m in marks.get("subresonances", [])}
    for fl in summary.get("flips", []):
        n = fl.get("subresonance")
        near = f" (near f_act = {_fh(n)}, at {where[n]:.5g})" if n in where else ""
        typer.echo(
            f"  mode flips at {f0['field']} = {fl['at']:.5g} {f0['unit']}: "
            f"{fl['below']} below, {fl['above']} above{near}"
        )
    if "window" in marks:
        parts = ", ".join(f"{a:.5g}–{b:.5g}" for a, b in marks["window"]) or "nowhere"
        typer.echo(f"design window 0.5 ≤ ϖ < 2 at {f0['field']}: {parts} {f0['unit']}")
    if where:
        at = ", ".join(f"{_fh(n)} {x:.5g}" for n, x in sorted(where.items()))
        typer.echo(
            f"sub-resonances α·ϖ² = 1/n² (f_act = f_h/n) at {f0['field']}: {at} {f0['unit']}"
        )
    for a, b in marks.get("undamped_resonance", []):
        typer.echo(
            f"undamped head near the tangential resonance ({a:.5g}–{b:.5g} {f0['unit']}): "
            "the idealised speed there is not physical (give actuator.quality_factor_*)"
        )
    typer.echo(f"{run.computed} computed, {run.resumed} resumed in {run.elapsed_s:.2f} s")


@sweep_app.command("atlas")
def atlas_cmd(
    file: Annotated[
        Path | None,
        typer.Argument(help="Device YAML file (with --vary); absent: the (ϖ, α, β, κ) grid."),
    ] = None,
    out: Annotated[
        Path | None,
        typer.Option(
            "--out",
            "-o",
            help="Atlas directory: a manifest, one file per finished chunk, then table.npz "
            "and the summary. The same command again resumes it.",
        ),
    ] = None,
    varpi: Annotated[str | None, typer.Option(help="ϖ range, e.g. 0.5:2:0.05.")] = None,
    alpha: Annotated[str | None, typer.Option(help="α range.")] = None,
    beta: Annotated[str | None, typer.Option(help="β range.")] = None,
    kappa: Annotated[str | None, typer.Option(help="κ range.")] = None,
    vary: Annotated[
        list[str] | None,
        typer.Option(
            "--vary",
            metavar="FIELD=LO:HI",
            help="A field of FILE and its range, as `betv sweep FILE` takes it; 1 to 4 times.",
        ),
    ] = None,
    points: Annotated[
        int,
        typer.Option(
            "--points",
            "-n",
            help="Points per field (2 to 1,000,000).",
            callback=int_option(2, 1_000_000),
        ),
    ] = 40,
    log: Annotated[bool, typer.Option("--log", help="Log-spaced field grids.")] = False,
    set_name: Annotated[
        str | None, typer.Option("--set", help="Actuator set (default: the first).")
    ] = None,
    fidelity: FidelityOpt = "periodic",
    residual_tol: ResidualTolOpt = 1e-10,
    max_cycles: MaxCyclesOpt = None,
    quality_normal: QualityNormalOpt = None,
    zeta_v: ZetaVOpt = None,
    quality_tangential: QualityTangentialOpt = None,
    zeta_h: ZetaHOpt = None,
    restitution: RestitutionOpt = None,
    csv: Annotated[bool, typer.Option("--csv", help="Also write table.csv.")] = False,
    overwrite: OverwriteOpt = False,
    executor: ExecutorOpt = "process",
    workers: WorkersOpt = None,
    chunksize: Annotated[
        int | None,
        typer.Option(
            "--chunksize",
            help="Points per chunk (one task, one file; default: up to 1000). Fixed when "
            f"the atlas is made (1 to {limits.MAX_CHUNKSIZE:,}).",
            callback=int_option(1, limits.MAX_CHUNKSIZE),
        ),
    ] = None,
    scheduler: Annotated[
        str | None,
        typer.Option(
            "--scheduler",
            help="dask.distributed scheduler tcp://host:port (-x dask without it: a local "
            "cluster of -j workers).",
        ),
    ] = None,
    as_json: JsonOpt = False,
    quiet: QuietOpt = False,
) -> None:
    """A design-space atlas: up to millions of points in chunks, on the process pool or a
    dask cluster, each finished chunk kept; the same command again resumes it, another
    command into the same directory is refused. Over (ϖ, α, β, κ) (the push/pull map's
    rows) or over 1 to 4 fields of a device file (the field sweep's rows)."""
    from betvdesign.cli.common import progress_bar
    from betvdesign.cli.physics import given_options

    with user_errors(), interruptible(out):
        if out is None:
            raise UsageError("--out DIR: give the atlas's directory (new, or the atlas to resume)")
        dimensionless = {"varpi": varpi, "alpha": alpha, "beta": beta, "kappa": kappa}
        if file is None:
            from betvdesign.studies.atlas import pushpull_atlas

            missing = [f"--{k}" for k, v in dimensionless.items() if v is None]
            if missing or vary:
                raise UsageError(
                    "give a device FILE with --vary, or the grid --varpi --alpha --beta "
                    f"--kappa{' (missing ' + ', '.join(missing) + ')' if missing else ''}"
                )
            terms = physics_terms(quality_normal, zeta_v, quality_tangential, zeta_h, restitution)
            axes = {k: axis(v, k) for k, v in dimensionless.items() if v is not None}
            atlas = pushpull_atlas(
                **axes, fidelity=fidelity.lower(), tol=residual_tol, max_cycles=max_cycles, **terms
            )
        else:
            from betvdesign.spec.loader import load_device
            from betvdesign.studies.atlas import MAX_FIELDS, device_atlas
            from betvdesign.studies.fieldsweep import parse_axis

            given = [f"--{k}" for k, v in dimensionless.items() if v is not None]
            given += given_options(
                {
                    "quality_normal": quality_normal,
                    "zeta_v": zeta_v,
                    "quality_tangential": quality_tangential,
                    "zeta_h": zeta_h,
                    "restitution": restitution,
                }
            )
            if max_cycles is not None or fidelity.lower() != "periodic":
                given.append("--max-cycles" if max_cycles is not None else "--fidelity")
            if given:
                raise UsageError(
                    f"{', '.join(given)}: not with a device FILE (its own fields give every "
                    "parameter); vary them with --vary FIELD=LO:HI"
                )
            if not vary or not 1 <= len(vary) <= MAX_FIELDS:
                raise UsageError(f"--vary: give 1 to {MAX_FIELDS} fields of {file}")
            spec = load_device(file)
            fields = [parse_axis(spec, v, points, log=log, max_points=1_000_000) for v in vary]
            atlas = device_atlas(file, fields, set_name=set_name, tol=residual_tol)
        from betvdesign.studies.atlas import run_atlas

        with progress_bar("atlas", quiet) as progress:
            run = run_atlas(
                atlas,
                out,
                backend=executor,
                workers=workers,
                scheduler=scheduler,
                chunk_points=chunksize,
                overwrite=overwrite,
                csv=csv,
                progress=progress,
            )
        data = {"study": "atlas", **run.as_dict()}

        def human() -> None:
            rate = run.computed_points / run.elapsed_s if run.computed_points else 0.0
            typer.echo(
                f"atlas of {run.total:,} points in {run.chunks:,} chunks of {run.chunk_points:,}: "
                f"{run.computed:,} computed, {run.resumed:,} resumed in {run.elapsed_s:.2f} s"
                + (f" (≈ {rate:,.0f} points/s)" if rate else "")
                + f"; merged in {run.merge_s:.2f} s"
            )
            typer.echo("modes: " + ", ".join(f"{k} {v:,}" for k, v in run.summary["modes"].items()))
            if "lambda_agrees" in run.summary:
                typer.echo(
                    f"λ rule agrees at {run.summary['lambda_agrees']:,}/"
                    f"{run.summary['converged']:,} converged points"
                )
            typer.echo(f"table: {run.path / 'table.npz'}" + (" and table.csv" if csv else ""))

        emit(data, as_json, human)
