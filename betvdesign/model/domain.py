"""The design space of the BETV model: one home for its limits and for the mode of a Δs.

Unit-free, below every solver and rule (imports only :mod:`betvdesign.model.params`):

- the design window 0.5 ≤ ϖ < 2, its edges to round-off (:func:`window_position`, the
  one comparison of ϖ with the window) and where impulsive hits end (docs/MODEL.md,
  "Vertical motion");
- the round-off scale below which a force or a contact of the model is not resolved
  (:data:`ROUND_OFF_SCALE`: a contact that short does not drive the slider);
- the parameter range the λ fit was made on (docs/MODEL.md, "Push/pull criterion");
- the tangential-resonance detuning the rules ask for, and the sub-resonances
  α·ϖ² = 1/n² (f_act = f_h/n) that sweeps mark and the margin rule names;
- :func:`mode_of`, the *only* place that turns a periodic increment Δs into a mode
  ("push", "pull", or "stalled" when |Δs| is at the solver's round-off: a slider that
  does not move is neither).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Literal

from betvdesign.model.params import ModelParams

#: Design window of the normalised frequency ϖ [-]: one hit per cycle, finite contact.
VARPI_WINDOW: tuple[float, float] = (0.5, 2.0)
#: Above the window, hits stay impulsive (zero contact) up to about this ϖ [-].
VARPI_IMPULSIVE_END = 2.6
#: Relative distance [-] within which ϖ counts as *at* an edge of the window: the lower
#: edge is inside, the upper edge outside. ϖ = f_act/f_v reaches the solver through
#: about 20 float64 operations and unit conversions (each within 1.1e-16), so a
#: design drawn at an edge (f_act = f_v/2 or 2·f_v exactly) arrives within a few ulp
#: of it (measured: 22 of 36 (f_v, m) pairs 1 ulp off, issue 29); 1e-12 bounds that
#: with a factor of ~500 and is far below any fabrication spread. Derived designs are
#: set to the edge exactly (:func:`snap_to_window_edge`), so the dynamics see the same ϖ.
WINDOW_EDGE_RTOL = 1e-12
#: A force, or a contact's share of a cycle, below this fraction of the model's unit
#: scale is not resolved in float64 [-]: event times are resolved to ~1e-16·τ with τ up to
#: ~1e4 over a transient, so a friction force or a contact duration of relative size
#: < 1e-12 changes nothing resolvable (:mod:`betvdesign.dynamics.determination` names such
#: forces; a periodic contact that short leaves the slider coasting, "not driven").
ROUND_OFF_SCALE = 1e-12
#: Parameter ranges of the simulations the λ fit was made on (Shin et al. 2004, Fig. 7).
FIT_RANGE: dict[str, tuple[float, float]] = {
    "alpha": (0.1, 4.0),
    "beta": (0.1, 1.5),
    "kappa": (0.1, 0.4),
}
#: Relative tolerance at the fit-range edges (κ = 0.4·tan 45° = 0.39999...).
FIT_EDGE_RTOL = 1e-9
#: Minimum |a·ϖ² − 1| for a = α and a = α(1 + 1/β) (tangential resonance) [-].
TANGENTIAL_DETUNING = 0.1
#: Orders n of the sub-resonances α·ϖ² = 1/n² marked and named (n = 1 … this) [-]: the
#: contact force is a rectified sine, so its n-th harmonic n·ϖ meets the head's free
#: tangential frequency 1/√α there, i.e. f_act = f_h/n (n = 1: the tangential resonance).
SUBRESONANCE_ORDERS = 8
#: A value of α·ϖ² counts as near the sub-resonance 1/n² within this ratio [-] (1.25 in
#: α·ϖ² is 12 % in f_act; below the ratio 1.306 of the levels n = 7, 8, so at most two
#: orders can be near and the nearer is named).
SUBRESONANCE_NEAR = 1.25
#: |Δs| per cycle [-] at or below which the slider counts as stalled. The periodic
#: orbit is accepted at a section residual ≤ 1e-10, so a Δs within 10× of that is
#: not distinguishable from zero; in length it is < 1e-9·u·cosθ per cycle.
DELTA_S_STALL = 1e-9
#: A push/pull Δs counts as determined when its error (:mod:`betvdesign.dynamics.
#: determination`) is at most this fraction of |Δs| [-]: the speed is then known to 1 %,
#: the tolerance the settling rule also uses.
DETERMINED_RTOL = 0.01

#: Cycles the transient from rest may take to cross the travel range [-] before the
#: check calls the design not shown to work (``betv check --horizon`` raises it): 2·10⁵
#: cycles, about 0.2 s of the exact solver and 33 s of a 6 kHz actuation.
TRAVEL_HORIZON = 200_000

Mode = Literal["push", "pull", "stalled", "undetermined"]


def mode_of(delta_s: float | None, *, error: float = 0.0) -> Mode | None:
    """Mode of a periodic increment per cycle Δs [-] (MODEL.md, "Slider").

    Parameters
    ----------
    delta_s : float or None
        Slider increment per actuation cycle [-] (units of u·cosθ).
    error : float, optional
        Its estimated absolute error [-] (:func:`betvdesign.dynamics.determination.
        determine`); 0 (the default) reads Δs as exact.

    Returns
    -------
    str or None
        "push" (Δs > 0: the slider moves with the impact direction), "pull" (Δs < 0),
        "stalled" (|Δs| + error ≤ :data:`DELTA_S_STALL`), "undetermined" (the sign, or
        |Δs| to :data:`DETERMINED_RTOL`, is not determined by ``error``); None when Δs
        is missing or not finite.
    """
    if delta_s is None:
        return None
    d = float(delta_s)
    if not math.isfinite(d):
        return None
    e = float(error)
    if not e >= 0.0:  # nan: nothing is determined
        return "undetermined"
    if abs(d) + e <= DELTA_S_STALL:
        return "stalled"
    if abs(d) <= DELTA_S_STALL:
        return "undetermined"  # at the stall threshold, but not within it with its error
    if abs(d) - e <= DELTA_S_STALL or e > DETERMINED_RTOL * abs(d):
        return "undetermined"
    return "push" if d > 0 else "pull"


WindowPosition = Literal["below", "lower-edge", "inside", "upper-edge", "above", "far-above"]


def window_position(varpi: float) -> WindowPosition:
    """Where ϖ lies against the design window 0.5 ≤ ϖ < 2: the one comparison.

    Parameters
    ----------
    varpi : float
        Normalised actuation frequency ϖ = f_act/f_v [-].

    Returns
    -------
    str
        "lower-edge" (within :data:`WINDOW_EDGE_RTOL` of 0.5: inside), "inside",
        "upper-edge" (within the same tolerance of 2: outside, contact vanishes there),
        "below", "above" (up to :data:`VARPI_IMPULSIVE_END`: impulsive hits) or
        "far-above". A non-finite ϖ is "far-above" when +inf, else "below".

    References
    ----------
    MODEL.md, "What the model shows: Vertical motion" (Shin et al., J. Appl. Phys. 96,
    7603 (2004)): one hit per cycle and finite contact for 0.5 ≤ ϖ < 2.
    """
    lo, hi = VARPI_WINDOW
    w = float(varpi)
    if not math.isfinite(w):
        return "far-above" if w > 0 else "below"
    if abs(w - lo) <= WINDOW_EDGE_RTOL * lo:
        return "lower-edge"
    if abs(w - hi) <= WINDOW_EDGE_RTOL * hi:
        return "upper-edge"
    if w < lo:
        return "below"
    if w < hi:
        return "inside"
    return "above" if w < VARPI_IMPULSIVE_END else "far-above"


def in_window(varpi: float) -> bool:
    """0.5 ≤ ϖ < 2 (the design window), edges to round-off (:func:`window_position`).

    Parameters
    ----------
    varpi : float
        Normalised actuation frequency [-].

    Returns
    -------
    bool
        True for "lower-edge" and "inside"; False otherwise (the upper edge included).
    """
    return window_position(varpi) in ("lower-edge", "inside")


def snap_to_window_edge(varpi: float) -> float:
    """ϖ set exactly to the window edge it is at to round-off, else unchanged.

    Parameters
    ----------
    varpi : float
        Derived normalised actuation frequency [-].

    Returns
    -------
    float
        0.5 or 2.0 when within :data:`WINDOW_EDGE_RTOL` of that edge; ``varpi`` otherwise.
        A device drawn at an edge (f_act = f_v/2 or 2·f_v exactly) is then solved and
        judged at the edge itself, never one ulp to either side.
    """
    pos = window_position(varpi)
    if pos == "lower-edge":
        return VARPI_WINDOW[0]
    if pos == "upper-edge":
        return VARPI_WINDOW[1]
    return float(varpi)


def outside_fit_range(p: ModelParams) -> list[str]:
    """The parameters (of α, β, κ) outside the range the λ fit was made on (edges with
    round-off); [] when λ is not an extrapolation."""
    return [
        k
        for k, (lo, hi) in FIT_RANGE.items()
        if not lo * (1 - FIT_EDGE_RTOL) <= getattr(p, k) <= hi * (1 + FIT_EDGE_RTOL)
    ]


def subresonance_level(n: int) -> float:
    """α·ϖ² [-] of the sub-resonance of order ``n`` ≥ 1: 1/n² (f_act = f_h/n)."""
    return 1.0 / (n * n)


def nearest_subresonance(a_varpi2: Sequence[float]) -> int | None:
    """The sub-resonance a span of α·ϖ² values lies near.

    Parameters
    ----------
    a_varpi2 : sequence of float
        Values of α·ϖ² [-] (positive): the first is the design's, the others where its
        mode changes (e.g. the margin corners that flip).

    Returns
    -------
    int or None
        The order n ≤ :data:`SUBRESONANCE_ORDERS` whose level 1/n² lies within the span
        of the values widened by the ratio :data:`SUBRESONANCE_NEAR`, the nearest to the
        first value in ratio; None when no level does.
    """
    vals = [float(v) for v in a_varpi2 if v > 0.0 and math.isfinite(v)]
    if not vals:
        return None
    lo, hi = min(vals) / SUBRESONANCE_NEAR, max(vals) * SUBRESONANCE_NEAR
    near = [n for n in range(1, SUBRESONANCE_ORDERS + 1) if lo <= subresonance_level(n) <= hi]
    if not near:
        return None
    return min(near, key=lambda n: abs(math.log(vals[0] / subresonance_level(n))))


def resonance_detuning(p: ModelParams) -> tuple[str, float]:
    """The tangential resonance closest to ϖ: (label, min |a·ϖ² − 1|) over
    a = α (free flight) and a = α(1 + 1/β) (stick) [-]."""
    w2 = p.varpi**2
    cases = {"free flight a = α": p.alpha, "stick a = α(1 + 1/β)": p.alpha * (1 + 1 / p.beta)}
    return min(((k, abs(a * w2 - 1.0)) for k, a in cases.items()), key=lambda t: t[1])
