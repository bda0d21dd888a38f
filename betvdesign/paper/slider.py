"""Validation of the paper's slider results (Figs 9–11, the device's values).

Every published number is recomputed with the exact model and put next to the
measurements that could explain a difference: the paper's own stopping rule
("successive Δs agree"), the transient from rest, both quoted β, and u versus
u·cosθ as the length unit. Nothing is tuned to the published value.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np

from betvdesign.dynamics import periodic_orbit, reference, simulate
from betvdesign.model.params import ModelParams
from betvdesign.nondim.device import derive
from betvdesign.nondim.record import Scales, SetDerivation
from betvdesign.paper.common import (
    AS_PUBLISHED,
    STOP_RTOL,
    Comparison,
    numeric_verdict,
    rel_diff,
    settled_from,
    successive_stop,
)
from betvdesign.spec.loader import load_device

#: Fig. 9: label, parameters, published Δs, published contact phases.
FIG9 = (
    ("9a", ModelParams(1.5, 2.5, 1.5, 0.4), 1.1796, "starts in reverse slip, then stick"),
    ("9b", ModelParams(0.6, 0.5, 1.5, 0.4), -3.5512, "starts in slip, ends in reverse slip"),
)


@dataclass(frozen=True)
class Fit:
    """The paper's fit of Figs 10–11, read from the device file's ``published_fit``:
    ϖ, α, κ and the two quoted β (the first is Fig. 10's, the last Fig. 11's) [-]."""

    varpi: float
    alpha: float
    kappa: float
    beta10: float
    beta11: float

    @classmethod
    def of(cls, sd: SetDerivation) -> Fit:
        pub = {c.name: c.published for c in sd.published}
        missing = {"varpi", "alpha", "beta", "kappa"} - set(pub)
        if missing:
            raise ValueError(f"the device file has no published_fit for {sorted(missing)}")
        return cls(
            pub["varpi"][0], pub["alpha"][0], pub["kappa"][0], pub["beta"][0], pub["beta"][-1]
        )

    @property
    def betas(self) -> tuple[float, float]:
        return (self.beta10, self.beta11)

    def params(self, beta: float) -> ModelParams:
        return ModelParams(self.varpi, self.alpha, beta, self.kappa)


#: Fig. 10: slider travel published after 30 impacts [µm] and the impact counts.
FIG10_UM, FIG10_IMPACTS, FIG10_SETTLE = 40.0, 30, 300
#: Transient length used for settling measurements [cycles].
LONG_RUN = 5000
#: Fig. 11 voltages [V].
VOLTAGES = tuple(float(v) for v in range(2, 11))


@dataclass
class SliderPart:
    """Computed side of Figs 9–11 and the device values."""

    comparisons: list[Comparison]
    fig9: list[dict[str, Any]]
    fig10: dict[str, Any]
    fig11: dict[str, Any]
    fig10_table: list[dict[str, Any]]


def phase_sequence(p: ModelParams, state: np.ndarray) -> list[tuple[str, float]]:
    """Contact phases of one cycle from ``state`` (free flight left out), in order, each
    with its duration as a fraction of the cycle [-]."""
    tr = simulate(p, 1, state0=state, dense=True)
    T = 2.0 * math.pi / p.varpi
    out: list[tuple[str, float]] = []
    for a, b, ph in tr.phases:
        if ph == "free":
            continue
        if out and out[-1][0] == ph:
            out[-1] = (ph, out[-1][1] + (b - a) / T)
        else:
            out.append((ph, (b - a) / T))
    return out


def _orbit_samples(p: ModelParams, state: np.ndarray, n: int = 800) -> dict[str, Any]:
    tr = simulate(p, 1, state0=state, dense=True)
    T = 2.0 * math.pi / p.varpi
    tau = np.linspace(0.0, T, n)
    x = tr.sample(tau)
    labels = []
    for t in tau:
        lab = "free"
        for a, b, ph in tr.phases:
            if a <= t <= b:
                lab = ph
                break
        labels.append(lab)
    return {"tau": tau, "dzeta": x[:, 3], "ds": x[:, 5], "phases": labels}


def _fig9(label: str, p: ModelParams, pub: float, pub_phases: str, theta: float):
    orb = periodic_orbit(p)
    ds = float(orb.delta_s)
    ref = reference.simulate(p, 1, state0=orb.state)
    tr = simulate(p, LONG_RUN, log_events=False)
    stop = successive_stop(tr.delta_s)
    settle = settled_from(tr.delta_s, ds, 1e-6)
    closest = int(np.argmin(np.abs(tr.delta_s - pub)))
    cos_t = math.cos(theta)
    looser, looser_stops = [], []
    for rtol in (1e-2, 1e-3):
        st = successive_stop(tr.delta_s, rtol)
        if st:
            looser.append(f"{rtol:g}: cycle {st.cycle}, {st.delta_s:.4f}")
            looser_stops.append(st)
    stop_txt = (
        f"the paper's rule (successive Δs agree to {STOP_RTOL:g}) stops at cycle "
        f"{stop.cycle} returning {stop.delta_s:.4f} ({100 * rel_diff(stop.delta_s, pub):+.1f} %"
        " from the published value)"
        if stop
        else "the paper's rule never stops"
    ) + (f" (looser, {'; '.join(looser)})" if looser else "")
    expl = (
        f"{stop_txt}; the transient from rest is within 1e-6 of the orbit from cycle "
        f"{settle}; the closest transient Δs is {tr.delta_s[closest]:.4f} at cycle "
        f"{closest + 1}; Δs·cosθ (length unit u instead of u·cosθ) = {ds * cos_t:.4f} "
        f"({100 * rel_diff(ds * cos_t, pub):+.1f} %); solve_ivp DOP853 from the orbit state "
        f"gives {float(ref.delta_s[0]):.6f}. "
    )
    candidates = {
        "the stopping rule": [st.delta_s for st in (stop, *looser_stops) if st],
        "a transient cycle": [float(x) for x in tr.delta_s[:100]],
        "the length unit u": [ds * cos_t],
    }
    hits = [
        k
        for k, vals in candidates.items()
        if any(numeric_verdict(v, pub, digits=4) == "reproduced" for v in vals)
    ]
    expl += (
        f"{', '.join(hits)} reproduces {pub:g} to its digits"
        if hits
        else f"None of these reproduces {pub:g} to its digits: the difference is not the "
        "settling criterion nor the length unit"
    )
    pieces = phase_sequence(p, orb.state)
    seq = [ph for ph, _ in pieces]
    comps = [
        Comparison(
            label,
            f"periodic Δs at ϖ = {p.varpi:g}, α = {p.alpha:g}, β = {p.beta:g}, κ = {p.kappa:g}",
            f"{pub:g}",
            f"{ds:.4f}",
            numeric_verdict(ds, pub, digits=4),
            f"periodic orbit (Newton shooting, residual {orb.residual:.1e}, Floquet |μ|max "
            f"{max(orb.floquet_moduli or [0]):.3f}); {LONG_RUN}-cycle transient from rest",
            expl,
            pub,
            ds,
        ),
        Comparison(
            label,
            f"contact phases of the orbit: {pub_phases}",
            pub_phases,
            " → ".join(seq),
            "holds" if _phases_match(pub_phases, seq) else "does not hold",
            "phase pieces of one cycle of the exact orbit (dense output)",
            "share of the cycle: " + ", ".join(f"{ph} {100 * d:.3g} %" for ph, d in pieces),
        ),
    ]
    fig = {"label": label, "params": p, "delta_s": ds, "published": pub}
    fig.update(_orbit_samples(p, orb.state))
    return comps, fig


def _phases_match(pub: str, seq: list[str]) -> bool:
    if pub.startswith("starts in reverse slip, then stick"):
        return seq[:2] == ["reverse", "stick"]
    return bool(seq) and seq[0] == "slip" and seq[-1] == "reverse"


def _s_um(delta_s: np.ndarray, n: int, unit_m: float) -> float:
    return abs(float(np.sum(delta_s[:n]))) * unit_m * 1e6


def _fig10_runs(fit: Fit) -> dict[float, tuple[ModelParams, Any, Any]]:
    """The exact runs Figs 10-11 read, per β of the fit.

    Parameters
    ----------
    fit : Fit
        The published fit.

    Returns
    -------
    dict of float to tuple
        Per β: the parameters, the :data:`LONG_RUN`-cycle transient from rest and the
        periodic orbit.
    """
    runs = {}
    for b in fit.betas:
        p = fit.params(b)
        runs[b] = (p, simulate(p, LONG_RUN, log_events=False), periodic_orbit(p))
    return runs


def _fig10_travel(
    fit: Fit, runs: dict, units: tuple, f_act: float, f_drive: float
) -> tuple[Comparison, list[dict]]:
    """Fig. 10: the travel after 30 impacts, in every reading of the published figure.

    Parameters
    ----------
    fit : Fit
        The published fit.
    runs : dict
        :func:`_fig10_runs`.
    units : tuple of (str, float)
        The length units the figure may use, by name [m].
    f_act : float
        Actuation frequency [Hz].
    f_drive : float
        Input frequency [Hz].

    Returns
    -------
    comparison : Comparison
        The 40 µm claim against the restated fit.
    table : list of dict
        |s| [µm] for each β, unit and cycle count, with its difference from 40 µm.
    """
    u = units[1][1]
    b10, _ = fit.betas
    table = []
    for b in fit.betas:
        for name, unit in units:
            for n in (FIG10_IMPACTS, 2 * FIG10_IMPACTS):
                s = _s_um(runs[b][1].delta_s, n, unit)
                table.append(
                    {"beta": b, "unit": name, "cycles": n, "s_um": s, "rel": rel_diff(s, FIG10_UM)}
                )
    best = min(table, key=lambda r: abs(r["rel"]))
    main = next(
        r for r in table if r["beta"] == b10 and r["unit"] == "u·cosθ" and r["cycles"] == 30
    )
    comp = Comparison(
        "10",
        f"the slider moves 40 µm after 30 impacts (ϖ = {fit.varpi:g}, α = {fit.alpha:g}, "
        f"β = {b10:g}, κ = {fit.kappa:g}, "
        f"u = {u * 1e6:.3g} µm)",
        f"{FIG10_UM:g} µm",
        f"{main['s_um']:.2f} µm (|s| = {main['s_um'] / (units[0][1] * 1e6):.2f} u·cosθ)",
        numeric_verdict(main["s_um"], FIG10_UM, digits=0),
        f"exact transient from rest, 30 cycles (one impact per cycle at ϖ = {fit.varpi:g}), "
        "|s|·u·cosθ; both β, both length units and 60 cycles in the table below",
        f"nearest of the {len(table)} variants: β = {best['beta']:g}, unit {best['unit']}, "
        f"{best['cycles']} cycles: {best['s_um']:.1f} µm ({100 * best['rel']:+.1f} %); "
        f"{2 * FIG10_IMPACTS} actuation cycles are {FIG10_IMPACTS} periods of the "
        f"{f_drive:g} Hz input when each heats twice (f_act/f_drive = "
        f"{f_act / f_drive:g}). The "
        f"restated fit (β = {b10:g}, u·cosθ, 30 impacts) gives {main['s_um'] / FIG10_UM:.2f} "
        "of the published travel",
        FIG10_UM,
        main["s_um"],
    )
    return comp, table


def _fig10_settling(fit: Fit, runs: dict) -> tuple[list[Comparison], dict]:
    """Fig. 10: how long the transient takes to become periodic.

    Parameters
    ----------
    fit : Fit
        The published fit.
    runs : dict
        :func:`_fig10_runs`.

    Returns
    -------
    comparisons : list of Comparison
        "not yet periodic after 30 impacts" and "at least 300 impacts".
    settle : dict
        Per β: the paper's stop, the cycles settled to 1e-3 and 1e-6, the offsets at 30
        and 300 cycles [-], the slowest Floquet multiplier and the periodic Δs [-].
    """
    b10, b11 = fit.betas
    comps: list[Comparison] = []
    settle = {}
    for b in fit.betas:
        _, tr, orb = runs[b]
        target = float(orb.delta_s)
        stop = successive_stop(tr.delta_s)
        settle[b] = {
            "stop": stop,
            "1e-3": settled_from(tr.delta_s, target, 1e-3),
            "1e-6": settled_from(tr.delta_s, target, 1e-6),
            "at30": rel_diff(float(tr.delta_s[FIG10_IMPACTS - 1]), target),
            "floquet": max(orb.floquet_moduli or [0.0]),
            "dev300": float(np.max(np.abs(tr.delta_s[FIG10_SETTLE - 1 :] - target)) / abs(target)),
            "delta_s": target,
        }
    s09, s9 = settle[b10], settle[b11]
    comps.append(
        Comparison(
            "10",
            "not yet periodic after 30 impacts",
            "not periodic",
            "; ".join(
                f"β = {b:g}: Δs₃₀ is {100 * abs(settle[b]['at30']):.2f} % off the periodic Δs"
                for b in fit.betas
            ),
            "holds" if all(abs(settle[b]["at30"]) > 1e-3 for b in fit.betas) else "partly holds",
            "Δs of cycle 30 against the exact periodic Δs",
            "the transient is still visible at 30 cycles for both β"
            if all(abs(settle[b]["at30"]) > 1e-3 for b in fit.betas)
            else "Δs is within 1e-3 of the periodic value at cycle 30 for at least one β",
        )
    )
    comps.append(
        Comparison(
            "10",
            f"at least 300 impacts to reach periodic motion (β = {b10:g})",
            f"≥ {FIG10_SETTLE}",
            f"{s09['1e-6']} cycles to 1e-6 ({s09['1e-3']} to 1e-3); β = {b11:g}: "
            f"{s9['1e-6']} ({s9['1e-3']})",
            "holds" if (s09["1e-6"] or 0) >= FIG10_SETTLE else "does not hold",
            "first cycle after which every Δs stays within 1e-6 (1e-3) of the exact "
            f"periodic Δs, relative ({LONG_RUN}-cycle exact transient)",
            (
                "true for a tight criterion, not for a loose one"
                if (s09["1e-3"] or 0) < FIG10_SETTLE <= (s09["1e-6"] or 0)
                else "the count depends on the tolerance"
            )
            + f": at cycle {FIG10_SETTLE} Δs is still "
            f"{s09['dev300']:.1e} off (β = {b10:g}); the slowest Floquet multiplier is "
            f"{s09['floquet']:.4f} ({s9['floquet']:.4f} for β = {b11:g}); the paper's own "
            f"rule stops at cycle {s09['stop'].cycle if s09['stop'] else '—'} for β = {b10:g} "
            f"with Δs = {s09['stop'].delta_s if s09['stop'] else math.nan:.4f} "
            f"({100 * rel_diff(s09['stop'].delta_s, s09['delta_s']) if s09['stop'] else 0:+.2f}"
            " % off the periodic value)"
            + (": far too early" if s09["stop"] and s09["stop"].cycle < FIG10_SETTLE else ""),
            float(FIG10_SETTLE),
            float(s09["1e-6"] or math.nan),
        )
    )
    return comps, settle


def _fig11(
    fit: Fit, runs: dict, ds9: float, scales: Scales, v_op: float, f_drive: float
) -> tuple[Comparison, dict]:
    """Fig. 11: speed against voltage, β = 9, u ∝ V (the device's calibration).

    Parameters
    ----------
    fit : Fit
        The published fit.
    runs : dict
        :func:`_fig10_runs`.
    ds9 : float
        The periodic Δs [-] at the second β.
    scales : Scales
        The device's scales.
    v_op : float
        The device's drive voltage [V].
    f_drive : float
        Its input frequency [Hz].

    Returns
    -------
    comparison : Comparison
        Speed proportional to voltage.
    fig11 : dict
        The figure's data: voltages [V], speeds and travel speeds [µm/s], the gain.
    """
    u, th, f_act = scales.u_m, scales.theta_rad, scales.f_act_hz
    _, b11 = fit.betas
    comps: list[Comparison] = []
    gain = u / v_op  # the device's linear calibration u = gain·V
    speeds = [abs(ds9) * gain * v * math.cos(th) * f_act * 1e6 for v in VOLTAGES]
    tr9 = runs[b11][1]
    travel = []
    for v in VOLTAGES:
        s_um = np.abs(tr9.section[:, 4]) * gain * v * math.cos(th) * 1e6
        k = int(np.argmax(s_um >= FIG10_UM))
        travel.append(FIG10_UM * f_act / k if s_um[-1] >= FIG10_UM else math.nan)
    ratio = np.array(speeds) / np.array(VOLTAGES)
    i_op = int(np.argmin(np.abs(np.array(VOLTAGES) - v_op)))
    comps.append(
        Comparison(
            "11",
            f"average speed rises with voltage, about proportionally (β = {b11:g}, u ∝ V)",
            "rises ∝ V",
            f"{speeds[i_op]:.0f} µm/s at {v_op:g} V (periodic, |Δs| = {abs(ds9):.4f} "
            "per cycle); 40 µm / travel time "
            f"{travel[i_op]:.0f} µm/s; speed/V constant to "
            f"{float(np.ptp(ratio) / ratio.mean()):.1e}",
            "holds",
            f"periodic |Δs|·u(V)·cosθ·f_act with f_act = {f_act:g} Hz (AC doubling of the "
            f"{f_drive:g} Hz input) and u = {gain * 1e6:.4g} µm/V·V; travel time to 40 µm "
            "from the exact transient",
            "in the model Δs does not depend on u, so the speed is exactly proportional to "
            "u, hence to V under the linear calibration: the check confirms the model, the "
            "measured speeds are not restated",
        )
    )
    fig11 = {
        "voltage": np.array(VOLTAGES),
        "speed_um_s": np.array(speeds),
        "travel_um_s": np.array(travel),
        "gain_um_per_v": gain * 1e6,
        "v_op": v_op,
        "f_act_hz": f_act,
    }
    return comps[0], fig11


def _fig10_11(
    fit: Fit, scales: Scales, v_op: float, f_drive: float
) -> tuple[list[Comparison], dict, dict, list[dict]]:
    """Figs 10-11: travel, settling and speed against voltage.

    Parameters
    ----------
    fit : Fit
        The published fit.
    scales : Scales
        The device's scales.
    v_op : float
        The device's drive voltage [V].
    f_drive : float
        Its input frequency [Hz].

    Returns
    -------
    comparisons : list of Comparison
        Fig. 10's and Fig. 11's claims.
    fig10, fig11 : dict
        The figures' data.
    table : list of dict
        Fig. 10's travel in every reading (:func:`_fig10_travel`).
    """
    u, th, f_act = scales.u_m, scales.theta_rad, scales.f_act_hz
    units = (("u·cosθ", u * math.cos(th)), ("u", u))
    runs = _fig10_runs(fit)
    comp10, table = _fig10_travel(fit, runs, units, f_act, f_drive)
    comps10, settle = _fig10_settling(fit, runs)
    fig10 = {
        "cycles": np.arange(LONG_RUN + 1),
        "s": {b: runs[b][1].section[:, 4] for b in fit.betas},
        "delta_s": {b: runs[b][1].delta_s for b in fit.betas},
        "periodic": {b: settle[b]["delta_s"] for b in fit.betas},
        "stop": {b: settle[b]["stop"] for b in fit.betas},
        "unit_um": units[0][1] * 1e6,
        "f_act_hz": f_act,
    }
    comp11, fig11 = _fig11(fit, runs, settle[fit.betas[1]]["delta_s"], scales, v_op, f_drive)
    return [comp10, *comps10, comp11], fig10, fig11, table


def _device_rows(sd: SetDerivation, fit: Fit) -> list[Comparison]:
    p, sc = sd.params, sd.scales
    f_v = sc.f_act_hz / p.varpi
    f_drive = float(sd.step("f_drive").value.to("Hz").magnitude)
    no_doubling = p.varpi * f_drive / sc.f_act_hz  # ϖ if f_act were the drive frequency
    m_step = sd.step("M")
    m_ug = float(m_step.value.to("ug").magnitude)
    comps = [
        Comparison(
            "device",
            "ϖ of the fit (Figs 10–11)",
            f"{fit.varpi:g}",
            f"{p.varpi:.4f} (f_act = {sc.f_act_hz:g} Hz = {sc.f_act_hz / f_drive:g}·f_drive); "
            f"{no_doubling:.4f} with f_act = f_drive",
            "differs",
            f"ϖ = f_act/f_v from the listed f_v = {f_v / 1e3:.3g} kHz and the "
            f"{f_drive:g} Hz AC input",
            f"ϖ = {fit.varpi:g} would need f_act = {fit.varpi * f_v / 1e3:.3g} kHz (input "
            f"{fit.varpi * f_v * f_drive / sc.f_act_hz / 1e3:.3g} kHz) or f_v = "
            f"{sc.f_act_hz / fit.varpi / 1e3:.3g} kHz: the fit is not the listed device",
            fit.varpi,
            p.varpi,
        ),
        Comparison(
            "device",
            "β = m/M of the fit for Fig. 11",
            f"{fit.beta11:g}",
            f"{p.beta:.4f}",
            numeric_verdict(p.beta, fit.beta11, digits=0),
            f"β = m/M, M = {m_ug * 1e3:.4g}·10⁻³ µg (one beam, ρ·L·w·t), m = "
            f"{sd.step('m').value_str}",
            f"the listed masses give {p.beta:.3g}: the quoted {fit.beta11:g} to its digits"
            if numeric_verdict(p.beta, fit.beta11, digits=0) == "reproduced"
            else f"the listed masses give {p.beta:.3g}",
            fit.beta11,
            p.beta,
        ),
        Comparison(
            "device",
            "β = m/M of the fit for Fig. 10",
            f"{fit.beta10:g}",
            f"{p.beta:.4f}",
            numeric_verdict(p.beta, fit.beta10, digits=1),
            "as above",
            f"{p.beta / fit.beta10:.3g} times the quoted {fit.beta10:g}"
            + (
                ": a misplaced decimal point (the two quotes differ by a factor of 10)"
                if abs(fit.beta11 / fit.beta10 - 10.0) < 1e-9
                else ""
            ),
            fit.beta10,
            p.beta,
        ),
        Comparison(
            "device",
            "M = 3.96·10⁻³ µg (half the slider)",
            "3.96·10⁻³ µg",
            f"{m_ug * 1e3:.4g}·10⁻³ µg",
            numeric_verdict(m_ug * 1e3, 3.96, digits=2),
            "ρ·L·w·t of one 170 × 5 × 2 µm polysilicon beam",
            AS_PUBLISHED,
            3.96e-3,
            m_ug,
        ),
        Comparison(
            "device",
            "κ = μ·tanθ of the fit",
            f"{fit.kappa:g}",
            f"{p.kappa:.4f}",
            "reproduced" if abs(p.kappa - fit.kappa) < 1e-9 else "differs",
            "μ = 0.4, θ = 45°",
            AS_PUBLISHED,
            fit.kappa,
            p.kappa,
        ),
    ]
    return comps


def slider_part(device: str | Path) -> SliderPart:
    """Figs 9–11 and the device values; ``device`` is the published device's YAML."""
    sd = derive(load_device(device)).sets[0]
    comps: list[Comparison] = []
    fig9 = []
    for label, p, pub, phases in FIG9:
        c, f = _fig9(label, p, pub, phases, sd.scales.theta_rad)
        comps += c
        fig9.append(f)
    ratios = {f["label"]: f["published"] / f["delta_s"] for f in fig9}
    note = (
        "; published/computed is "
        + " and ".join(f"{r:.3f} for {k}" for k, r in ratios.items())
        + ", so no common length scale explains both"
    )
    comps = [
        replace(c, explanation=c.explanation + note) if c.computed_value is not None else c
        for c in comps
    ]
    v_op = float(sd.step("V").value.to("V").magnitude)
    f_drive = float(sd.step("f_drive").value.to("Hz").magnitude)
    fit = Fit.of(sd)
    c10, fig10, fig11, table = _fig10_11(fit, sd.scales, v_op, f_drive)
    comps += c10
    comps += _device_rows(sd, fit)
    return SliderPart(comps, fig9, fig10, fig11, table)
