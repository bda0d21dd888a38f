"""``betv simulate``: the exact solver from the command line (thin layer).

Parameters come either from a device file (``betv simulate devices/x.yaml
[--set NAME]``: loaded and made dimensionless by :func:`betvdesign.nondim.device.derive_file`,
so results are also given in physical units: SI prefixes by magnitude in text, SI
floats under unit-named keys in JSON) or directly as
``--varpi --alpha --beta --kappa`` (with the optional physics ``--quality-normal``/
``--zeta-v``, ``--quality-tangential``/``--zeta-h``, ``--restitution``; a device file
carries its own). ``--cycles N`` runs a transient of N cycles
from rest (:func:`betvdesign.dynamics.simulate`); ``--periodic`` solves for the
periodic state (:func:`betvdesign.dynamics.periodic_orbit`).

``--json`` prints one object on stdout (contract in docs/ARCHITECTURE.md):
``params, status, message, cycles, s, delta_s, mode, period_cycles, residual,
floquet, impacts_per_cycle, contact_fraction`` (+ ``device``, ``set`` and
``physical`` when a device file gives the scales). Exit codes: 0 solved,
1 the solver did not succeed (the message says why and what to try), 2 bad input.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import typer

from betvdesign.cli import app
from betvdesign.cli.common import (
    EXIT_OK,
    EXIT_RULE_FAILED,
    float_option,
    int_option,
    interruptible,
    renamed_option,
    user_errors,
)
from betvdesign.cli.physics import (
    QualityNormalOpt,
    QualityTangentialOpt,
    RestitutionOpt,
    ZetaHOpt,
    ZetaVOpt,
    given_options,
    physics_terms,
)
from betvdesign.errors import UsageError
from betvdesign.model.params import ModelParams
from betvdesign.output.numbers import json_float
from betvdesign.output.siformat import format_si
from betvdesign.spec import limits


def _params_from_options(
    file: Path | None,
    set_name: str | None,
    opts: dict[str, float | None],
    physics: dict[str, float | None] | None = None,
) -> tuple[ModelParams, Any, dict[str, Any]]:
    """(params, scales or None, identification) from a device file or the four options
    (and the optional physics options ``physics``, see :mod:`betvdesign.cli.physics`)."""
    physics = physics or {}
    given = [k for k, v in opts.items() if v is not None]
    if file is not None:
        extra = given_options(physics)
        if extra:
            raise UsageError(
                f"{', '.join(extra)}: a device file carries its own damping and restitution "
                f"(fields of its actuator set, see `betv schema`); give them with "
                "--varpi --alpha --beta --kappa instead of a file"
            )
        if given:
            raise UsageError(
                f"give either a device file or --{'/--'.join(opts)}, not both "
                f"(got {file} and --{', --'.join(given)})"
            )
        from betvdesign.nondim.device import derive_file

        der = derive_file(file)
        names = [s.name for s in der.sets]
        if set_name is None:
            chosen = der.sets[0]
        else:
            matches = [s for s in der.sets if s.name == set_name]
            if not matches:
                raise UsageError(f"{file}: no actuator set {set_name!r} (sets: {', '.join(names)})")
            chosen = matches[0]
        ident = {
            "device": der.name,
            "set": chosen.name,
            "impact_direction": "+x" if chosen.impact_sign > 0 else "-x",
        }
        return chosen.params, chosen.scales, ident
    if set_name is not None:
        raise UsageError("--set needs a device file")
    missing = [k for k, v in opts.items() if v is None]
    if missing:
        raise UsageError(
            "give a device file or all of --varpi --alpha --beta --kappa "
            f"(missing: --{', --'.join(missing)})"
        )
    terms = physics_terms(**physics)
    return ModelParams(**opts, **terms), None, {}  # type: ignore[arg-type]


def _physical(
    scales: Any, s: float, delta_s: float | None, cycles: int, impact_direction: str
) -> dict[str, Any]:
    """Dimensional values as SI floats under unit-named keys, from the device scales.

    MODEL.md "Displacement per cycle": length u·cosθ, speed |Δs|·u·cosθ·f_act. As in
    every output (README "Versioned outputs"), displacements keep the sign of Δs (along
    the impact direction: + push, − pull) while the speed is a magnitude beside the
    device direction the slider travels (``travel_direction``: "+x", "-x", or None when
    it does not move); ``impact_direction`` is the device direction of +Δs.
    """
    out: dict[str, Any] = {
        "length_scale_m": scales.length_m,
        "f_act_hz": scales.f_act_hz,
        "cycle_s": 1.0 / scales.f_act_hz,
        "time_s": cycles / scales.f_act_hz,
        "s_m": s * scales.length_m,
        "delta_s_m": None,
        "speed_m_s": None,
        "travel_direction": None,
    }
    if delta_s is not None:
        out["delta_s_m"] = delta_s * scales.length_m
        out["speed_m_s"] = abs(delta_s) * scales.length_m * scales.f_act_hz
        if delta_s != 0.0:
            flip = {"+x": "-x", "-x": "+x"}
            out["travel_direction"] = impact_direction if delta_s > 0 else flip[impact_direction]
    return out


def _periodic_answer(p: ModelParams, tol: float, max_cycles: int) -> tuple[dict[str, Any], bool]:
    """The periodic state of ``p`` as ``betv simulate --periodic`` reports it, and success."""
    from betvdesign.dynamics import periodic_orbit

    po = periodic_orbit(p, tol=tol, max_cycles=max_cycles)
    out: dict[str, Any] = {
        "params": p.as_dict(),
        "status": po.status,
        "message": po.message,
        "cycles": po.transient_cycles,
        "s": po.transient_s,
        "delta_s": json_float(po.delta_s),
        "mode": po.mode,
        "period_cycles": po.period_cycles,
        "residual": json_float(po.residual),
        "floquet": po.floquet_moduli,
        "impacts_per_cycle": po.impacts_per_cycle,
        "contact_fraction": po.contact_fraction,
    }
    return out, po.success


def _transient_answer(p: ModelParams, cycles: int) -> tuple[dict[str, Any], bool]:
    """The transient of ``cycles`` cycles from rest as ``betv simulate`` reports it, and success."""
    from betvdesign.dynamics import simulate
    from betvdesign.model.domain import mode_of

    tr = simulate(p, cycles, log_events=False)
    last = float(tr.delta_s[-1]) if len(tr.delta_s) else None
    out: dict[str, Any] = {
        "params": p.as_dict(),
        "status": tr.status,
        "message": tr.message,
        "cycles": tr.n_cycles,
        "s": tr.s,
        "delta_s": last,
        "mode": mode_of(last) if tr.driven else "not driven",
        "period_cycles": None,
        "residual": None,
        "floquet": None,
        "impacts_per_cycle": tr.impacts_per_cycle,
        "contact_fraction": tr.contact_fraction,
    }
    return out, tr.success


@app.command("simulate")
def simulate_cmd(
    file: Path | None = typer.Argument(None, help="Device YAML file (see devices/)."),
    set_name: str | None = typer.Option(
        None, "--set", help="Actuator set of the device file (default: the first)."
    ),
    varpi: float | None = typer.Option(
        None, "--varpi", help="ϖ = ω·sqrt(m/k_v) [-].", callback=float_option(gt=0.0)
    ),
    alpha: float | None = typer.Option(
        None, "--alpha", help="α = k_v/k_h [-].", callback=float_option(gt=0.0)
    ),
    beta: float | None = typer.Option(
        None, "--beta", help="β = m/M [-].", callback=float_option(gt=0.0)
    ),
    kappa: float | None = typer.Option(
        None, "--kappa", help="κ = μ·tanθ [-].", callback=float_option(gt=0.0)
    ),
    cycles: int = typer.Option(
        100,
        "--cycles",
        help=f"Transient cycles from rest (1 to {limits.MAX_CYCLES:,}).",
        callback=int_option(1, limits.MAX_CYCLES, why="about 3 µs and 100 bytes per cycle"),
    ),
    periodic: bool = typer.Option(
        False, "--periodic", help="Solve for the periodic state (Newton shooting)."
    ),
    residual_tol: float = typer.Option(
        1e-10,
        "--residual-tol",
        help="Periodic residual accepted [-], in (0, 0.1].",
        callback=float_option(gt=0.0, le=0.1),
    ),
    max_cycles: int = typer.Option(
        100_000,
        "--max-cycles",
        help=f"Brute-force budget of --periodic [cycles, 1 to {limits.MAX_CYCLES:,}].",
        callback=int_option(1, limits.MAX_CYCLES),
    ),
    _tol: str | None = typer.Option(
        None,
        "--tol",
        hidden=True,
        callback=renamed_option("--residual-tol", "the periodic solver's residual"),
    ),
    quality_normal: QualityNormalOpt = None,
    zeta_v: ZetaVOpt = None,
    quality_tangential: QualityTangentialOpt = None,
    zeta_h: ZetaHOpt = None,
    restitution: RestitutionOpt = None,
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object on stdout."),
) -> None:
    """Simulate one design exactly: a transient (--cycles) or the periodic state (--periodic)."""
    opts = {"varpi": varpi, "alpha": alpha, "beta": beta, "kappa": kappa}
    with user_errors(), interruptible(resumable=False):
        physics = {
            "quality_normal": quality_normal,
            "zeta_v": zeta_v,
            "quality_tangential": quality_tangential,
            "zeta_h": zeta_h,
            "restitution": restitution,
        }
        p, scales, ident = _params_from_options(file, set_name, opts, physics)
        if periodic:
            out, success = _periodic_answer(p, residual_tol, max_cycles)
        else:
            out, success = _transient_answer(p, cycles)
    out.update(ident)
    if scales is not None:
        out["physical"] = _physical(
            scales, out["s"], out["delta_s"], out["cycles"], out["impact_direction"]
        )
    if as_json:
        typer.echo(json.dumps(out, indent=2, ensure_ascii=False))
    else:
        _print_text(out, periodic)
    raise typer.Exit(EXIT_OK if success else EXIT_RULE_FAILED)


def _print_text(out: dict[str, Any], periodic: bool) -> None:
    pr = out["params"]
    head = f"{out['device']} / set {out['set']}: " if "device" in out else ""
    typer.echo(
        f"{head}ϖ = {pr['varpi']:.6g}, α = {pr['alpha']:.6g}, β = {pr['beta']:.6g}, "
        f"κ = {pr['kappa']:.6g}"
        + "".join(  # damping and restitution, when the parameters have them
            f", {sym} = {pr[k]:.6g}"
            for k, sym in (("zeta_v", "ζ_v"), ("zeta_h", "ζ_h"), ("restitution", "e"))
            if k in pr
        )
    )
    typer.echo(f"status: {out['status']} — {out['message']}")
    ph = out.get("physical")
    ds = out["delta_s"]
    what = "periodic Δs" if periodic else "last-cycle Δs"
    if ds is not None:
        line = f"{what} = {ds:.10g} per cycle [u·cosθ]"
        if ph:
            line += f" = {format_si(ph['delta_s_m'], 'm', digits=4)}"
            toward = ph["travel_direction"]
            if toward is not None:
                line += (
                    f"; mean speed {format_si(ph['speed_m_s'], 'm/s', digits=4)} toward {toward}"
                )
        if out["mode"] == "not driven":
            line += (
                " -> not driven: no contact recurs, the slider coasts at the velocity of "
                "its first contacts"
            )
        elif out["mode"]:
            line += f" -> {out['mode']}"
        typer.echo(line)
    line = f"s after {out['cycles']} cycles = {out['s']:.10g} [u·cosθ]"
    if ph:
        line += (
            f" = {format_si(ph['s_m'], 'm', digits=4)} in {format_si(ph['time_s'], 's', digits=4)}"
        )
    typer.echo(line)
    if periodic and out["period_cycles"] is not None:
        fl = ", ".join(f"{m:.6g}" for m in out["floquet"] or [])
        typer.echo(
            f"period {out['period_cycles']} cycle(s), residual {out['residual']:.2e}, "
            f"|Floquet multipliers| {fl}"
        )
    typer.echo(
        f"impacts per cycle {out['impacts_per_cycle']:.4g}, "
        f"contact fraction {out['contact_fraction']:.4g}"
    )
