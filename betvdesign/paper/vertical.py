"""Validation of the paper's vertical-motion figures (Figs 3–6) with the exact model.

The head's vertical motion does not depend on the slider, so everything here uses
the vertical regime study (:mod:`betvdesign.studies.regime`) and, for the drawn
trajectories, the exact solver's dense output. Every qualitative statement of the
paper is turned into ϖ intervals computed on a grid whose edges are refined by
bisection (:func:`~betvdesign.paper.common.refine_edge`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from betvdesign.dynamics import simulate
from betvdesign.model.params import ModelParams
from betvdesign.paper.common import (
    AS_PUBLISHED,
    Comparison,
    fmt_intervals,
    refine_edge,
    true_intervals,
)
from betvdesign.studies.regime import LONG_PERIOD, regime_point, run_regime

#: Horizon of the regime grid [cycles] (the paper used 30 and 100 impacts).
MAX_CYCLES = 400
#: The longer horizon the paper used for Fig. 4 [impacts from rest].
PAPER_HORIZON = 100
#: ϖ of the drawn vertical trajectories of Fig. 5 and what the paper calls them.
FIG5 = ((2.0, "periodic"), (2.9, "period doubling"), (4.8, "aperiodic"))
#: ϖ of the phase portrait (Fig. 3): the paper's fitted device value.
FIG3_VARPI = 0.9
#: The regime grid is fine up to this ϖ and COARSE_FACTOR times coarser beyond [-].
FINE_TOP = 3.0
COARSE_FACTOR = 4
#: Width to which interval edges are bisected [-].
EDGE_TOL = 1e-5
#: Slider parameters for runs whose vertical motion only is used (it does not depend
#: on them): α, β, κ.
_ANY_SLIDER = (1.0, 1.0, 0.4)


@dataclass
class VerticalPart:
    """Computed side of Figs 3–6 (rows: one regime row per grid ϖ)."""

    rows: list[dict[str, Any]]
    comparisons: list[Comparison]
    fig3: dict[str, np.ndarray]
    fig5: list[dict[str, Any]]
    edges: dict[str, float] = field(default_factory=dict)


def _point(varpi: float) -> dict[str, Any]:
    return regime_point({"key": 0, "varpi": float(varpi), "max_cycles": MAX_CYCLES})


def _point_h(varpi: float, horizon: int) -> dict[str, Any]:
    return regime_point({"key": 0, "varpi": float(varpi), "max_cycles": horizon})


def _near(edge: float, step: float = 0.005) -> np.ndarray:
    """Grid of spacing ``step`` from 0.2 below ``edge`` to just above it."""
    return np.arange(round((edge - 0.2) / step), round(edge / step) + 2) * step


def one_hit_per_cycle(row: dict[str, Any]) -> bool:
    """Impact period equal to the actuation period: periodic with period 1 cycle and
    exactly one hit (contact-opening or impulsive) per cycle."""
    return row["period_cycles"] == 1 and row["hits_per_cycle"] == 1.0


def finite_contact(row: dict[str, Any]) -> bool:
    """A contact of finite duration recurs (contact fraction > 0)."""
    return (row["contact_fraction"] or 0.0) > 0.0


def _edges(rows: list[dict[str, Any]], pred, lo: float, hi: float) -> list[float]:
    """Grid edges of ``pred`` between ``lo`` and ``hi``, each refined by bisection."""
    w = [r["varpi"] for r in rows]
    flags = [pred(r) for r in rows]
    out = []
    for i in range(1, len(w)):
        if flags[i] != flags[i - 1] and lo <= w[i] <= hi:
            out.append(refine_edge(lambda v: pred(_point(v)), w[i - 1], w[i], EDGE_TOL))
    return out


def _trajectory(varpi: float, cycles: int, n_per_cycle: int = 200) -> dict[str, np.ndarray]:
    tr = simulate(ModelParams(varpi, *_ANY_SLIDER), cycles, dense=True, log_events=False)
    T = 2.0 * math.pi / varpi
    tau = np.linspace(0.0, cycles * T, cycles * n_per_cycle + 1)
    x = tr.sample(tau)
    return {"cycles": tau / T, "xi": x[:, 0], "dxi": x[:, 1]}


def regime_grid(step: float, top: float) -> np.ndarray:
    """ϖ grid on (0, ``top``]: spacing ``step`` up to :data:`FINE_TOP` (where every edge
    the paper states lies), ``COARSE_FACTOR``·``step`` beyond [-]."""
    fine_top = min(FINE_TOP, top)
    fine = np.arange(1, round(fine_top / step) + 1) * step
    coarse_step = COARSE_FACTOR * step
    coarse = fine_top + np.arange(1, round((top - fine_top) / coarse_step) + 1) * coarse_step
    return np.concatenate([fine, coarse])


def _fig3() -> tuple[Comparison, dict[str, np.ndarray]]:
    """Fig. 3: one impact period of the head is a closed orbit.

    The vertical motion is periodic after the first contact end at τ = π/ϖ.

    Returns
    -------
    comparison : Comparison
        The claim against the exact dense output at :data:`FIG3_VARPI`.
    fig3 : dict of str to numpy.ndarray
        ``tau``, ``xi``, ``dxi`` [-] over one impact period, for the figure.
    """
    comps: list[Comparison] = []
    T3 = 2.0 * math.pi / FIG3_VARPI
    tr = simulate(ModelParams(FIG3_VARPI, *_ANY_SLIDER), 3, dense=True, log_events=False)
    a, b = tr.sample(np.array([T3 / 2.0, 1.5 * T3]))[:, :2]
    gap = float(np.max(np.abs(a - b)))
    tau = np.linspace(T3 / 2.0, 1.5 * T3, 601)
    s3 = tr.sample(tau)
    fig3 = {"tau": tau, "xi": s3[:, 0], "dxi": s3[:, 1]}
    comps.append(
        Comparison(
            "3",
            "phase portrait (τ, ξ, ξ') of one impact period of the head",
            "closed orbit: flight, plastic hit (ξ' → 0), contact until sin ϖτ < 0",
            f"closed to {gap:.1e} (max-norm of (ξ, ξ') one period apart) at ϖ = {FIG3_VARPI:g}",
            "holds",
            f"exact dense output over τ ∈ [π/ϖ, 3π/ϖ] at ϖ = {FIG3_VARPI:g} (the paper's "
            "fitted value; the restatement gives no ϖ for this figure)",
            "every contact ends at τ = (2j+1)π/ϖ with ξ = ξ' = 0, so the motion repeats "
            "exactly from the first contact end",
        )
    )
    return comps[0], fig3


def _fig4_main(
    rows: list[dict[str, Any]], w: np.ndarray, step: float
) -> tuple[list[Comparison], float, float, list[tuple[float, float]]]:
    """Fig. 4: the interval of one hit per cycle around ϖ = 1, its edges against 0.5, 2.6.

    Parameters
    ----------
    rows : list of dict
        The regime grid's rows.
    w : numpy.ndarray
        Their ϖ [-].
    step : float
        The grid's fine step [-].

    Returns
    -------
    comparisons : list of Comparison
        The lower and the upper edge against the paper's.
    lo_edge, hi_edge : float
        The interval's bisected edges [-].
    others : list of (float, float)
        The other grid intervals with one hit per cycle [-].
    """
    comps: list[Comparison] = []
    one = [one_hit_per_cycle(r) for r in rows]
    ivs = true_intervals(list(w), one)
    main = next(iv for iv in ivs if iv[0] <= 1.0 <= iv[1])
    lo_edge = _edges(rows, one_hit_per_cycle, main[0] - 2 * step, main[0])[0]
    hi_edge = _edges(rows, one_hit_per_cycle, main[1], main[1] + 2 * step)[0]
    others = [iv for iv in ivs if iv != main]
    comps.append(
        Comparison(
            "4",
            "impact period equal to the actuation period from ϖ = 0.5",
            "ϖ = 0.5",
            f"ϖ = {lo_edge:.5f}",
            "reproduced" if abs(lo_edge - 0.5) < 5e-3 else "differs",
            f"lower edge of the interval containing ϖ = 1 where the motion has period 1 "
            f"with one hit per cycle (grid step {step:g} up to ϖ = {FINE_TOP:g}, "
            f"{COARSE_FACTOR * step:g} beyond; edges bisected to {EDGE_TOL:g})",
            "below it two hits per cycle (see next row)",
            0.5,
            lo_edge,
        )
    )
    short = [_point_h(v, PAPER_HORIZON) for v in _near(hi_edge)]
    hi_short = max((r["varpi"] for r in short if one_hit_per_cycle(r)), default=math.nan)
    comps.append(
        Comparison(
            "4",
            "impact period equal to the actuation period up to ϖ = 2.6",
            "ϖ = 2.6",
            f"ϖ = {hi_edge:.5f} ({MAX_CYCLES} cycles); ϖ = {hi_short:.3f} with the paper's "
            f"{PAPER_HORIZON} impacts",
            "reproduced" if abs(hi_edge - 2.6) < 0.01 else "differs",
            "upper edge of the same interval, bisected; beyond 2 the single hit per cycle "
            "is impulsive (no finite contact, Fig. 6). Repeated on a 0.005 grid with a "
            f"horizon of {PAPER_HORIZON} cycles",
            f"the horizon: within {PAPER_HORIZON} cycles the slowly settling hits between "
            f"{hi_short:.3f} and {hi_edge:.3f} have not yet locked to one per cycle and read "
            f"as aperiodic, which puts the edge at {hi_short:.3f} "
            + (
                f"({hi_short - 2.6:+.3f} from the paper's 2.6): the paper's horizon explains it"
                if abs(hi_short - 2.6) <= 0.02
                else f"(still {hi_short - 2.6:+.3f} from the paper's 2.6)"
            ),
            2.6,
            hi_edge,
        )
    )
    return comps, lo_edge, hi_edge, others


def _fig4_elsewhere(
    rows: list[dict[str, Any]],
    w: np.ndarray,
    step: float,
    edges: tuple[float, float],
    others: list[tuple[float, float]],
) -> list[Comparison]:
    """Fig. 4: one hit per cycle "only" in [0.5, 2.6], and two hits per cycle below 0.5.

    Parameters
    ----------
    rows : list of dict
        The regime grid's rows.
    w : numpy.ndarray
        Their ϖ [-].
    step : float
        The grid's fine step [-].
    edges : (float, float)
        The main interval's edges (:func:`_fig4_main`) [-].
    others : list of (float, float)
        The other grid intervals with one hit per cycle [-].

    Returns
    -------
    list of Comparison
        The "only" claim and the two-hit regions.
    """
    lo_edge, hi_edge = edges
    comps: list[Comparison] = []
    low = [iv for iv in others if iv[1] < 0.5]
    fr_low = [
        r["contact_fraction"]
        for r in rows
        if r["varpi"] < 0.5 and one_hit_per_cycle(r) and r["contact_fraction"] is not None
    ] or [math.nan]
    comps.append(
        Comparison(
            "4",
            "impact period equal to the actuation period only for 0.5 ≤ ϖ ≤ 2.6",
            "no other ϖ interval",
            f"[{lo_edge:.5f}, {hi_edge:.5f}] and {len(others)} other interval(s): "
            f"{fmt_intervals(others, 3)}",
            "partly holds" if others else "holds",
            "every grid interval of period 1 with one hit per cycle",
            f"{len(low)} of them below ϖ = 0.5, alternating with the two-hit regions, "
            f"{sum(b - a + step for a, b in low):.3g} wide in all (grid estimate); contact "
            f"fraction there {min(fr_low):.3g}–{max(fr_low):.3g}: single impacts with "
            "finite contact, so the paper's “only” does not hold below 0.5"
            if low
            else "none found",
        )
    )
    two = [
        r["varpi"] < 0.5 and r["period_cycles"] == 1 and r["hits_per_cycle"] == 2.0 for r in rows
    ]
    more = [r["varpi"] < 0.5 and (r["hits_per_cycle"] or 0) > 2.0 for r in rows]
    ivs2 = true_intervals(list(w), two)
    comps.append(
        Comparison(
            "4",
            "0 < ϖ < 1/2: regions with two impacts per actuation cycle",
            "regions with two impacts per cycle (called period doubling)",
            f"{len(ivs2)} interval(s) with exactly two hits per cycle, widest "
            f"{fmt_intervals([max(ivs2, key=lambda iv: iv[1] - iv[0])], 3) if ivs2 else '—'}; "
            f"{sum(more)} grid point(s) with more than two",
            "holds" if ivs2 else "does not hold",
            "period 1 with hits_per_cycle = 2 on the grid below ϖ = 0.5",
            "two hits per cycle of the same period; the paper's 'period doubling' names "
            "the count of hits, not a period of two cycles",
        )
    )
    return comps


def _fig5() -> tuple[list[Comparison], list[dict[str, Any]]]:
    """Fig. 5: the three published trajectories, periodic, period doubling, aperiodic.

    Returns
    -------
    comparisons : list of Comparison
        Each trajectory's kind against the paper's.
    fig5 : list of dict
        Per trajectory its ϖ, the published kind, the regime row and 30 cycles of
        (ξ, ξ') for the figure.
    """
    comps: list[Comparison] = []
    fig5 = []
    for v, said in FIG5:
        r = _point(v)
        traj = _trajectory(v, 30)
        fig5.append({"varpi": v, "published": said, "row": r, **traj})
        k = r["period_cycles"]
        found = (
            "period-1 (one impulsive hit per cycle)"
            if k == 1
            else (f"period-{k}" if k is not None else "aperiodic (no period ≤ 64 hits)")
        )
        agree = {
            "periodic": k == 1,
            "period doubling": k == 2,
            "aperiodic": k is None or k > LONG_PERIOD,
        }[said]
        comps.append(
            Comparison(
                "5",
                f"vertical trajectory at ϖ = {v:g} is {said}",
                said,
                f"{found}; {r['hits_per_cycle']:.3g} hits per cycle, contact fraction "
                f"{r['contact_fraction']:.3g}",
                ("holds" if k is None or k <= LONG_PERIOD else "partly holds")
                if agree
                else "differs",
                f"hit phases over cycles {MAX_CYCLES // 2}–{MAX_CYCLES} compared to 1e-9 of a "
                "cycle (studies.regime)",
                f"a period longer than {LONG_PERIOD} cycles cannot be told from aperiodic on "
                "a plot (studies.regime shows it as aperiodic in its overview)"
                if k is not None and k > LONG_PERIOD
                else AS_PUBLISHED,
            )
        )
    return comps, fig5


def _fig6(rows: list[dict[str, Any]], w: np.ndarray, step: float) -> tuple[list[Comparison], float]:
    """Fig. 6: finite contact only below ϖ ≈ 2.

    Parameters
    ----------
    rows : list of dict
        The regime grid's rows.
    w : numpy.ndarray
        Their ϖ [-].
    step : float
        The grid's fine step [-].

    Returns
    -------
    comparisons : list of Comparison
        The edge of finite contact, and finite contacts above it.
    edge : float
        The bisected upper edge of the first interval with finite contact [-].
    """
    comps: list[Comparison] = []
    fc = [finite_contact(r) for r in rows]
    fivs = true_intervals(list(w), fc)
    first = fivs[0]
    edge2 = _edges(rows, finite_contact, first[1], first[1] + 2 * step)[0]
    near = [r for r in rows if 1.95 <= r["varpi"] < 2.0 and finite_contact(r)]
    gap = np.array([2.0 - r["varpi"] for r in near])
    frac = np.array([r["contact_fraction"] for r in near])
    slope = float(gap @ frac / (gap @ gap)) if near else math.nan
    beyond = [iv for iv in fivs[1:] if iv[0] > 2.0]
    ks = sorted(
        {
            r["period_cycles"]
            for r in rows
            if r["varpi"] > 2.0 and finite_contact(r) and r["period_cycles"] is not None
        }
    )
    ks = ks if len(ks) <= 6 else [*ks[:5], "…"]
    comps.append(
        Comparison(
            "6",
            "finite contact duration only below ϖ ≈ 2",
            "ϖ ≈ 2",
            f"ϖ = {edge2:.5f}",
            "reproduced" if abs(edge2 - 2.0) < 5e-3 else "differs",
            "upper edge of the first interval with contact fraction > 0 (bisected)",
            f"the contact fraction falls to 0 as ϖ → 2, ≈ {slope:.3g}·(2 − ϖ) over the last "
            "0.05 (least squares): the hit moves to the end of the compression half-cycle, "
            "where the contact window [hit, π/ϖ] closes",
            2.0,
            edge2,
        )
    )
    comps.append(
        Comparison(
            "6",
            "no finite contact above ϖ ≈ 2",
            "none",
            f"finite contacts recur on {len(beyond)} intervals: {fmt_intervals(beyond[:4], 3)}"
            f"{' ∪ …' if len(beyond) > 4 else ''} (largest fraction "
            f"{max((r['contact_fraction'] or 0) for r in rows if r['varpi'] > 2.05):.3g})",
            "partly holds" if beyond else "holds",
            "grid intervals above ϖ = 2 with contact fraction > 0",
            f"above ϖ = 2 finite contacts recur from ϖ = {beyond[0][0]:.3g} in motions of "
            f"period {', '.join(str(k) for k in ks)} cycles (one contact every k cycles); "
            "the paper's statement holds for the period-1 motion only"
            if beyond
            else AS_PUBLISHED,
        )
    )
    return comps, edge2


def vertical_part(step: float = 0.005, top: float = 10.0) -> VerticalPart:
    """Regime grid (:func:`regime_grid`) on (0, ``top``], the claims of Figs 3–6.

    Parameters
    ----------
    step : float
        Fine grid step [-].
    top : float
        Largest ϖ of the grid [-].

    Returns
    -------
    VerticalPart
        The grid's rows, the comparisons figure by figure, the figures' data and the
        bisected edges.
    """
    grid = regime_grid(step, top)
    run, _ = run_regime(grid, max_cycles=MAX_CYCLES)
    rows = run.rows
    w = np.array([r["varpi"] for r in rows])
    comp3, fig3 = _fig3()
    comps4, lo_edge, hi_edge, others = _fig4_main(rows, w, step)
    comps4 += _fig4_elsewhere(rows, w, step, (lo_edge, hi_edge), others)
    comps5, fig5 = _fig5()
    comps6, edge2 = _fig6(rows, w, step)
    return VerticalPart(
        rows=rows,
        comparisons=[comp3, *comps4, *comps5, *comps6],
        fig3=fig3,
        fig5=fig5,
        edges={"one_hit_lo": lo_edge, "one_hit_hi": hi_edge, "contact_end": edge2},
    )


__all__ = ["VerticalPart", "finite_contact", "one_hit_per_cycle", "vertical_part"]
