"""``betv tolerance`` and ``betv calibrate``: device-level studies (thin layer over
``betvdesign.studies.tolerance`` and ``betvdesign.studies.calibration``)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

import typer

from betvdesign.cli import app
from betvdesign.cli.common import (
    EXIT_RULE_FAILED,
    ChunkOpt,
    Execution,
    ExecutorOpt,
    FidelityOpt,
    JsonOpt,
    OutOpt,
    OverwriteOpt,
    QuietOpt,
    SchedulerOpt,
    WorkersOpt,
    emit,
    int_option,
    interruptible,
    output_file,
    renamed_option,
    run_block,
    seed_option,
    user_errors,
)
from betvdesign.errors import UsageError
from betvdesign.spec import limits


def _print_tolerance(
    device: Path, samples: int, seed: int, fidelity: str, tols: list, summary: dict[str, Any]
) -> None:
    """The human listing of ``betv tolerance``: per set its probabilities, speeds, ranks."""
    typer.echo(f"{device}: {samples} samples, seed {seed}, mode from {fidelity}")
    for t in tols:
        typer.echo(f"  spread {t.describe()}")
    for name, s in summary["sets"].items():
        typer.echo(
            f"  set {name} (intended {s['intended_mode']}): "
            f"P(push) {s['p_push']:.3f}  P(pull) {s['p_pull']:.3f}  "
            f"P(outside window) {s['p_outside_window']:.3f}  "
            f"P(wrong mode) {s['p_wrong_mode']:.3f}"
        )
        if s.get("warning"):
            typer.echo(f"    WARNING: {s['warning']} (these samples are not its verdict's)")
        if s["p_not_converged"]:
            typer.echo(f"    P(not converged) {s['p_not_converged']:.3f}")
        if s.get("p_not_driven"):
            typer.echo(f"    P(not driven: no contact recurs) {s['p_not_driven']:.3f}")
        if s["invalid_samples"]:
            typer.echo(f"    invalid samples: {s['invalid_samples']}")
        pct = s["intended_speed_um_s_percentiles"]
        if pct:
            typer.echo(
                f"    speed in the intended {s['intended_mode']} direction [µm/s] "
                "(− the wrong way; p5 slowest) " + "  ".join(f"{k} {v:.4g}" for k, v in pct.items())
            )
        ranked = ", ".join(
            f"{e['field']} ({e[s['ranked_by']]:+.2f})"
            for e in s["sensitivities"]
            if e[s["ranked_by"]] is not None
        )
        typer.echo(f"    most sensitive ({s['ranked_by']}): {ranked}")
    if summary.get("p_pass") is not None:
        typer.echo(f"  P(pass) {summary['p_pass']:.3f}: {summary['p_pass_rules']}")


@app.command("tolerance")
def tolerance_cmd(
    device: Annotated[Path, typer.Argument(help="Device YAML file.")],
    spread: Annotated[
        list[str] | None,
        typer.Option(
            "--spread",
            help="Monte Carlo spread of one field: FIELD=[normal|uniform:]AMOUNT, e.g. "
            "slider.beam_width=normal:0.2um, contact.friction=uniform:10%. Repeatable.",
        ),
    ] = None,
    _tol: Annotated[
        list[str] | None,
        typer.Option(
            "--tol",
            hidden=True,
            callback=renamed_option(
                "--spread FIELD=[normal|uniform:]AMOUNT",
                "the Monte Carlo spread; a solver residual is `--residual-tol`",
            ),
        ),
    ] = None,
    tolerances: Annotated[
        Path | None, typer.Option("--tolerances", help="YAML file with a 'tolerances:' map.")
    ] = None,
    samples: Annotated[
        int,
        typer.Option(
            "--samples",
            "-n",
            help=f"Monte Carlo samples (1 to {limits.MAX_SAMPLES:,}).",
            callback=int_option(1, limits.MAX_SAMPLES),
        ),
    ] = 1000,
    seed: Annotated[
        int,
        typer.Option(help="Seed of the numpy Generator, 0 <= seed < 2**128.", callback=seed_option),
    ] = 0,
    fidelity: FidelityOpt = "periodic",
    sets: Annotated[
        list[str] | None, typer.Option("--set", help="Actuator set(s) to study (default: all).")
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
    """Monte Carlo over fabrication and operating variation of one device."""
    from betvdesign.studies.tolerance import load_tolerances, parse_tolerance, run_tolerance

    with user_errors(), interruptible(out):
        tols = [parse_tolerance(t) for t in spread or []]
        if tolerances is not None:
            tols += load_tolerances(tolerances)
        execution = Execution(executor, workers, chunksize, scheduler, out, overwrite, quiet)
        run, summary = execution.run(
            "tolerance Monte Carlo",
            run_tolerance,
            device,
            tols,
            samples=samples,
            seed=seed,
            fidelity=fidelity.lower(),
            sets=sets,
        )
        data = {"study": "tolerance", "device": str(device), "seed": seed, **run_block(run)}
        data |= summary

        emit(
            data,
            as_json,
            lambda: _print_tolerance(device, samples, seed, fidelity, tols, summary),
        )


def _emit_calibration(
    device: Path, data: Path, out: Path | None, result: Any, as_json: bool
) -> None:
    """Print a calibration (its snippet, or JSON) and its warnings; exit 1 unless converged."""
    payload = {"study": "calibration", "device": str(device), "data": str(data)}
    payload |= result.as_dict()
    payload["out"] = str(out) if out else None
    emit(payload, as_json, lambda: typer.echo(result.snippet, nl=False))
    for w in result.warnings:
        typer.echo(f"warning: {w}", err=True)
    if result.status == "failed":
        typer.echo(f"error: fit did not converge: {result.message}", err=True)
    if result.status != "converged":
        raise typer.Exit(EXIT_RULE_FAILED)


@app.command("calibrate")
def calibrate_cmd(
    device: Annotated[Path, typer.Argument(help="Device YAML file.")],
    data: Annotated[
        Path, typer.Argument(help="Measurements CSV, header cells 'name \\[unit]' (see below).")
    ],
    kind: Annotated[
        str, typer.Option(help="speed (voltage, speed) or displacement (time, displacement).")
    ] = "speed",
    law: Annotated[
        str, typer.Option(help="per-voltage, linear (u = g·V), quadratic (u = g·V²) or fixed.")
    ] = "linear",
    fit_alpha: Annotated[
        bool, typer.Option("--fit-alpha", help="Also fit α = k_v/k_h (re-solves per step).")
    ] = False,
    set_name: Annotated[
        str | None, typer.Option("--set", help="Actuator set (default: the first).")
    ] = None,
    signed: Annotated[
        bool,
        typer.Option(
            "--signed", help="Values are signed along the set's impact direction (not magnitudes)."
        ),
    ] = False,
    direction: Annotated[
        str | None,
        typer.Option(
            "--direction",
            metavar="+x|-x",
            help="Direction the slider moved (magnitude data; default: the set's intended one).",
        ),
    ] = None,
    out: Annotated[
        Path | None, typer.Option("--out", "-o", help="Write the device-file snippet (YAML).")
    ] = None,
    as_json: JsonOpt = False,
) -> None:
    """Fit the amplitude u (per voltage, or a law's gain) and optionally α to measurements.

    CSV: a header row of 'name \\[unit]' cells, one row per measurement, # comments.

    --kind speed: voltage \\[V], speed \\[um/s], optional sigma \\[um/s] (1σ).

    --kind displacement: time \\[ms], displacement \\[um], optional sigma \\[um].

    Any unit of the right dimension works (mm/s, nm, s ...).

    Values are magnitudes (>= 0) toward --direction (default: the set's intended travel).

    --signed: values signed along the set's impact direction instead.

    Data moving the other way than the model: error (exit 2), never a vanishing gain.

    Prints R², χ²/dof, 1σ and warnings; exit 1 if the fit fails or sits at bound 0.
    """
    from betvdesign.output.files import write_atomic
    from betvdesign.studies.calibration import calibrate
    from betvdesign.studies.measurements import read_measurements

    with user_errors(), interruptible(resumable=False):
        kind, law = kind.lower(), law.lower()
        if kind not in ("speed", "displacement"):
            raise UsageError(f"--kind must be speed or displacement, not {kind!r}")
        if out is not None:
            output_file(out)
        measured = read_measurements(data, kind)  # type: ignore[arg-type]
        result = calibrate(
            device,
            measured,
            law=law,  # type: ignore[arg-type]
            fit_alpha=fit_alpha,
            set_name=set_name,
            signed=signed,
            direction=direction,
        )
        if out is not None:
            write_atomic(out, result.snippet)
        _emit_calibration(device, data, out, result, as_json)
