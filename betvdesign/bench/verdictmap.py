"""Where the verdict means something: the verdict failure map (unit-free).

The solver's own failure map (:mod:`betvdesign.bench.failuremap`) charts where the
integrators fail; this module charts where the *verdict* stops meaning something.
From a base design, one family of designs per axis pushes a parameter to the edge of
the parameter space over many decades (κ → 0, β → 0 and → ∞, α → 0 and → ∞, ϖ over and
beyond the window, α·ϖ² → 1 with and without head damping, e → 1). Every point goes
through the check's own path (exact periodic orbit, then :func:`betvdesign.checks.
checker.answer_over_travel`: determination, transient from rest, the answer quoted)
and is labelled by the basis of its answer:

- "periodic": determined, and settled early in the travel (the periodic answer holds);
- "crossing": slow to settle (or Δs undetermined) but the slider crosses its travel:
  the verdict quotes the crossing from rest;
- "no-crossing": the slider does not cross its travel within the horizon (fails);
- "undetermined": neither (e.g. a force below round-off);
- "no-orbit": not driven, unbounded or failed (the orbit's status is the answer).

Every change of label along an axis is first probed (:data:`PROBES` points evenly
inside the coarse interval): where the labels change more than once there (they
interleave, e.g. undetermined and crossing at κ ≈ 3e-10 … 3e-9) the interval is a
*band*, reported with its pattern, never bisected into a point that is not a boundary;
a single change is bisected (:data:`BISECT_STEPS` steps in the axis's own coordinate,
log10 for the decades). Deterministic: the same rows every run.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from betvdesign.checks.checker import answer_over_travel
from betvdesign.dynamics.periodic import periodic_orbit
from betvdesign.model.bisection import bisect as bisect_bracket
from betvdesign.model.params import ModelParams
from betvdesign.plots.figure import figure_style, new_figure

#: Base design (the push demo's ϖ, α, β, κ) and its travel range in units of u·cosθ
#: (50 µm at u·cosθ = 0.131 µm).
BASE = ModelParams(1.2, 2.04, 0.509, 0.15)
TRAVEL_S = 380.0
#: Bisection steps on each change of label.
BISECT_STEPS = 10
#: Points probed evenly inside a coarse interval whose ends differ, before bisecting:
#: more than one change of label among them makes the interval a band.
PROBES = 7
#: Labels in the order of the figure's legend, with their colours.
LABELS: dict[str, str] = {
    "periodic": "#2ca02c",
    "crossing": "#ffbf00",
    "no-crossing": "#d62728",
    "undetermined": "#7f7f7f",
    "no-orbit": "#1f77b4",
}


@dataclass(frozen=True)
class Family:
    """One axis of the map: a parameter pushed over a range from :data:`BASE`.

    Attributes
    ----------
    name : str
        Axis label (ASCII-free Unicode allowed), e.g. "κ".
    lo, hi : float
        Range in the axis coordinate (log10 of the value when ``log``).
    log : bool
        True: the coordinate is log10 of the value.
    design : callable
        value -> ModelParams.
    """

    name: str
    lo: float
    hi: float
    log: bool
    design: Callable[[float], ModelParams]

    def value(self, x: float) -> float:
        """The parameter value at axis coordinate ``x``."""
        return 10.0**x if self.log else x


def _with(**kw: float) -> Callable[[float], ModelParams]:
    (name,) = kw
    return lambda v: dataclasses.replace(BASE, **{name: v})


def _resonance(zeta: float) -> Callable[[float], ModelParams]:
    """α·ϖ² = 1 + d at ϖ = 1 (free-flight tangential resonance), damped by ζ."""

    def design(d: float) -> ModelParams:
        return ModelParams(1.0, 1.0 + d, 1.0, 0.4, zeta_v=zeta, zeta_h=zeta)

    return design


FAMILIES: tuple[Family, ...] = (
    Family("κ", -16.0, 0.0, True, _with(kappa=0.0)),
    Family("β", -14.0, 4.0, True, _with(beta=0.0)),
    Family("α", -8.0, 4.0, True, _with(alpha=0.0)),
    Family("ϖ", 0.3, 2.6, False, _with(varpi=0.0)),
    Family("α·ϖ² − 1 (undamped)", -12.0, -1.0, True, _resonance(0.0)),
    Family("α·ϖ² − 1 (Q = 100)", -12.0, -1.0, True, _resonance(0.005)),
    Family("e", 0.0, 0.98, False, lambda e: dataclasses.replace(BASE, restitution=e)),
)


def classify(p: ModelParams, travel_s: float = TRAVEL_S) -> dict[str, Any]:
    """The check's answer for one design, as a row.

    Parameters
    ----------
    p : ModelParams
        The design [-].
    travel_s : float
        Travel range in units of u·cosθ [-].

    Returns
    -------
    dict
        ``label`` (the answer's basis), ``mode``, ``delta_s`` (quoted) and
        ``delta_s_periodic`` [-], ``delta_s_error`` [-], ``status`` (of the orbit),
        ``cycles_to_cross``, ``reason``.
    """
    try:
        orbit = periodic_orbit(p)
    except Exception as exc:  # a crash is a measured outcome, shown as such
        return {"label": "no-orbit", "mode": None, "status": "failed", "reason": str(exc)}
    det, _, ans = answer_over_travel(p, orbit, travel_s)
    return {
        "label": ans.basis,
        "mode": ans.mode,
        "delta_s": ans.delta_s,
        "delta_s_periodic": ans.delta_s_periodic,
        "delta_s_error": det.delta_s_error,
        "status": orbit.status,
        "cycles_to_cross": ans.cycles_to_cross,
        "reason": ans.reason,
    }


def scan_family(
    fam: Family, *, points: int = 17, bisect: int = BISECT_STEPS, travel_s: float = TRAVEL_S
) -> list[dict[str, Any]]:
    """Label ``points`` evenly spaced designs of one family and bisect every change.

    Returns
    -------
    list of dict
        Rows of :func:`classify` plus ``family``, ``x`` (axis coordinate), ``value`` and
        ``edge`` (True for the two points that bracket a bisected boundary), sorted by x.
    """
    memo: dict[float, dict[str, Any]] = {}

    def row(x: float) -> dict[str, Any]:
        if x not in memo:
            r = classify(fam.design(fam.value(x)), travel_s)
            memo[x] = {"family": fam.name, "x": x, "value": fam.value(x), "edge": False, **r}
        return memo[x]

    xs = list(np.linspace(fam.lo, fam.hi, points))
    base = [row(float(x)) for x in xs]
    bands = 0
    for a, b in itertools.pairwise(base):
        lo, hi = a, b
        if lo["label"] == hi["label"]:
            continue
        inner = [row(float(x)) for x in np.linspace(a["x"], b["x"], PROBES + 2)[1:-1]]
        run = [a, *inner, b]
        if sum(p["label"] != q["label"] for p, q in itertools.pairwise(run)) > 1:
            bands += 1
            for r in run:  # the labels interleave: a band, not a boundary
                r["band"] = bands
            continue
        lo = max((r for r in run if r["label"] == a["label"]), key=lambda r: r["x"])
        hi = min((r for r in run if r["label"] == b["label"]), key=lambda r: r["x"])
        br = bisect_bracket(
            lambda x: row(x)["label"], lo["x"], hi["x"], lo["label"], hi["label"], steps=bisect
        )
        lo, hi = row(br.a), row(br.b)
        lo["edge"] = hi["edge"] = True
    return sorted(memo.values(), key=lambda r: r["x"])


def scan(
    families: Sequence[Family] = FAMILIES, *, points: int = 17, bisect: int = BISECT_STEPS
) -> list[dict[str, Any]]:
    """:func:`scan_family` over every family (rows of all of them)."""
    return [r for f in families for r in scan_family(f, points=points, bisect=bisect)]


def boundaries(rows: Sequence[dict[str, Any]]) -> list[dict[str, Any]]:
    """The boundaries and bands of each family.

    Returns
    -------
    list of dict
        Per change of label: ``kind`` "boundary" (a single change, bisected: family,
        labels ``below`` and ``above``, the bracketing values ``low`` and ``high``) or
        "band" (labels interleave over ``low`` … ``high``: ``below`` and ``above`` the
        labels at its ends and ``pattern`` the labels' first letters in order, e.g.
        "UUUDDUD").
    """
    out = []
    for fam in dict.fromkeys(r["family"] for r in rows):
        rs = [r for r in rows if r["family"] == fam]
        for band in dict.fromkeys(r["band"] for r in rs if r.get("band")):
            members = [r for r in rs if r.get("band") == band]
            out.append(
                {
                    "family": fam,
                    "kind": "band",
                    "below": members[0]["label"],
                    "above": members[-1]["label"],
                    "low": members[0]["value"],
                    "high": members[-1]["value"],
                    "pattern": "".join(_letter(r["label"]) for r in members),
                }
            )
        for a, b in itertools.pairwise(rs):
            if a["label"] != b["label"] and not (a.get("band") and a.get("band") == b.get("band")):
                out.append(
                    {
                        "family": fam,
                        "kind": "boundary",
                        "below": a["label"],
                        "above": b["label"],
                        "low": a["value"],
                        "high": b["value"],
                    }
                )
    return sorted(
        out,
        key=lambda b: (list(dict.fromkeys(r["family"] for r in rows)).index(b["family"]), b["low"]),
    )


def _letter(label: str) -> str:
    """One letter per label for a band's pattern (U undetermined, N no-orbit, X
    no-crossing, C crossing, P periodic)."""
    return {"undetermined": "U", "no-orbit": "N", "no-crossing": "X", "crossing": "C"}.get(
        label, "P"
    )


def verdict_map_figure(rows: Sequence[dict[str, Any]]) -> Figure:
    """One strip per family, coloured by label; bisected boundaries as ticks.

    Returns
    -------
    matplotlib.figure.Figure
        Object-oriented figure (no pyplot state).
    """
    fams = list(dict.fromkeys(r["family"] for r in rows))
    with figure_style():
        fig, axes = new_figure(6.4, 0.62 * len(fams) + 0.9, nrows=len(fams))
        axes = np.atleast_1d(axes)
        for ax, fam in zip(axes, fams, strict=True):
            rs = [r for r in rows if r["family"] == fam]
            xs = [r["x"] for r in rs]
            for i, r in enumerate(rs):
                left = xs[i] if i == 0 else 0.5 * (xs[i - 1] + xs[i])
                right = xs[i] if i == len(rs) - 1 else 0.5 * (xs[i] + xs[i + 1])
                ax.axvspan(left, right, color=LABELS[r["label"]], linewidth=0)
            for b in boundaries(rs):
                x = next(r["x"] for r in rs if r["value"] == b["high"])
                if b["kind"] == "band":
                    x0 = next(r["x"] for r in rs if r["value"] == b["low"])
                    ax.axvspan(
                        x0, x, facecolor="none", edgecolor="black", hatch="///", linewidth=0.6
                    )
                else:
                    ax.axvline(x, color="black", linewidth=0.6)
            log = any(r["value"] != r["x"] for r in rs)
            ax.set_xlim(min(xs), max(xs))
            ax.set_yticks([])
            ax.set_ylabel(fam, rotation=0, ha="right", va="center", fontsize=7)
            ax.tick_params(axis="x", labelsize=6.5)
            if log:
                ax.set_xlabel("log10 of the value", fontsize=6.5, labelpad=1)
        handles = [_patch(c, label) for label, c in LABELS.items()]
        fig.legend(handles=handles, loc="outside lower center", ncols=len(LABELS), fontsize=7)
    return fig


def _patch(color: str, label: str) -> Any:
    from matplotlib.patches import Patch

    return Patch(color=color, label=label)


def summary(rows: Sequence[dict[str, Any]]) -> dict[str, Any]:
    """Counts per label and the list of boundaries (JSON-ready)."""
    counts: dict[str, int] = {k: 0 for k in LABELS}
    for r in rows:
        counts[r["label"]] += 1
    return {
        "base": dataclasses.asdict(BASE),
        "travel_s": TRAVEL_S,
        "counts": counts,
        "boundaries": [
            {**b, "low": float(b["low"]), "high": float(b["high"])} for b in boundaries(rows)
        ],
        "points": len(rows),
        "finite": all(r.get("delta_s") is None or math.isfinite(r["delta_s"]) for r in rows),
    }
