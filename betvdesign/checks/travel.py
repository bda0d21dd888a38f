"""Which answer a verdict quotes: the periodic orbit, or the travel from rest (unit-free).

The periodic orbit is exact, and it is what the slider does once it has settled
(docs/MODEL.md, "Slider"). A designer's question is what the slider does over its
travel range. The two agree when the transient from rest settles early in the travel;
where it does not (κ → 0, β → 0, α·ϖ² → 1 without damping: settling ∝ 1/(1 − |μ|max)
cycles), the periodic answer is exact and irrelevant, and the travel is the answer:

====================  ===========================================================
``basis``             when, and what the verdict's mode and speed are
====================  ===========================================================
"periodic"            the orbit is determined and the transient settles within
                      :data:`SETTLE_SHARE` of the cycles it takes to cross the
                      travel: the periodic mode and Δs
"crossing"            it crosses the travel before that, or there is no periodic
                      answer (Δs not determined, no orbit found: not converged or
                      failed) and the transient from rest crosses: the mode and
                      mean Δs of the crossing from rest
"no-crossing"         the transient from rest does not cross the travel within the
                      simulated horizon (whatever the orbit says): no mode is shown
                      to hold over the travel; the design fails
"undetermined"        Δs not determined and no transient was run: the mode is
                      "undetermined"
"no-orbit"            no periodic orbit for a reason the travel cannot answer: the
                      slider is not driven (no contact, or contact below round-off:
                      it only coasts on its first kick), or the head's tangential
                      motion is unbounded (no bounded motion exists); or no
                      transient was run
====================  ===========================================================

The travel decides whenever there is no periodic answer (issue 29): a design with no
orbit (not converged, failed) or an undetermined Δs is judged by its transient from
rest, never failed for the orbit's sake when it crosses. Not driven and unbounded are
answers of the model itself, not of a solver, and a crossing from rest there would be
a coast or a growing vibration (:func:`travel_decides`).

:func:`travel_answer` is the one place that makes this choice, for the check, the fix
search, the explorer and the verdict map (:mod:`betvdesign.bench.verdictmap`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal

from betvdesign.model.domain import mode_of
from betvdesign.output.numbers import json_float

#: Settling may take at most this share of the cycles to cross the travel for the
#: periodic Δs to be the speed quoted [-].
SETTLE_SHARE = 0.25

Basis = Literal["periodic", "crossing", "no-crossing", "undetermined", "no-orbit"]


@dataclass(frozen=True)
class TravelAnswer:
    """The mode and per-cycle increment a verdict quotes for one design.

    Attributes
    ----------
    basis : {"periodic", "crossing", "no-crossing", "undetermined", "no-orbit"}
        Where the answer comes from (module docstring).
    mode : str or None
        "push", "pull", "stalled", "undetermined", or None (no orbit, see ``basis``).
    delta_s : float or None
        Increment per actuation cycle quoted [-] (units of u·cosθ): the periodic Δs or
        the crossing's mean s/m; None when there is none.
    delta_s_periodic : float or None
        The periodic orbit's Δs [-] (shown beside a crossing answer).
    cycles_to_cross : int or None
        Cycles from rest to cross the travel (None: not crossed, or not run).
    horizon_cycles : int or None
        Cycles simulated from rest (None: not run).
    reason : str
        Why this basis, in one sentence.
    fix : str
        What to change when the answer fails the verdict ("" when there is none here).
    """

    basis: Basis
    mode: str | None
    delta_s: float | None
    delta_s_periodic: float | None
    cycles_to_cross: int | None
    horizon_cycles: int | None
    reason: str
    fix: str = ""

    @property
    def moves(self) -> bool:
        """True when the quoted mode is push or pull."""
        return self.mode in ("push", "pull")

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready record (non-finite floats as None)."""
        return {
            "basis": self.basis,
            "mode": self.mode,
            "delta_s": json_float(self.delta_s),
            "delta_s_periodic": json_float(self.delta_s_periodic),
            "cycles_to_cross": self.cycles_to_cross,
            "horizon_cycles": self.horizon_cycles,
            "reason": self.reason,
            "fix": self.fix,
        }


def travel_decides(orbit: Any) -> bool:
    """True when the orbit gives no periodic answer but the transient from rest can.

    Parameters
    ----------
    orbit : PeriodicResult or None
        The exact periodic orbit.

    Returns
    -------
    bool
        True for a failed orbit whose status is "not_converged" or "failed" (no orbit
        found by the solver: the slider's motion from rest is still well defined);
        False for a successful orbit, for "not_driven" (no contact, or contact below
        round-off: the slider is not driven, a crossing would be a coast on the first
        kick) and for "unbounded" (no bounded motion exists).
    """
    return orbit is not None and not orbit.success and orbit.status in ("not_converged", "failed")


def travel_answer(orbit: Any, determination: Any, settling: Any) -> TravelAnswer:
    """Choose the answer a verdict quotes (module docstring).

    Parameters
    ----------
    orbit : PeriodicResult or None
        The exact periodic orbit (:func:`betvdesign.dynamics.periodic_orbit`).
    determination : Determination or None
        How well its Δs is determined (:func:`betvdesign.dynamics.determination.
        determine`); None reads the orbit's Δs as exact.
    settling : Settling or None
        The transient from rest against the travel range (:func:`betvdesign.dynamics.
        settling.settling`); None when it was not run (the periodic answer stands).

    Returns
    -------
    TravelAnswer
        Basis, mode, quoted Δs [-] and why.
    """
    solved = orbit is not None and orbit.success and orbit.delta_s is not None
    ds = float(orbit.delta_s) if solved else None
    if determination is not None and determination.mode is not None:
        mode = determination.mode
    else:
        mode = mode_of(ds) if solved else None
    ran = settling is not None and settling.status != "failed"
    cross = settling.cycles_to_cross if ran else None
    horizon = settling.simulated_cycles if ran else None
    crossed = cross is not None and settling.crossing_delta_s is not None

    def crossing(why: str) -> TravelAnswer:
        c = float(settling.crossing_delta_s)
        return TravelAnswer("crossing", mode_of(c), c, ds, cross, horizon, why)

    def not_crossing(why: str) -> TravelAnswer:
        return TravelAnswer("no-crossing", mode, None, ds, None, horizon, why)

    if mode == "undetermined" or not solved:  # no periodic answer: the travel decides
        status = orbit.status if orbit is not None else "not solved"
        why = determination.reason if determination is not None else "Δs not determined"
        if mode == "undetermined":
            told, detail = "the periodic Δs is not determined", f" ({why})"
        else:
            told, detail = f"no periodic orbit ({status})", ""
        if mode == "undetermined" or travel_decides(orbit):
            if crossed:
                return crossing(
                    f"{told}; the transient from rest crosses the travel in {cross} cycles"
                )
            if ran:
                return not_crossing(
                    f"{told}{detail} and the transient from rest does not cross the travel "
                    f"within {horizon} cycles"
                )
        if mode == "undetermined":
            fix = determination.fix if determination is not None else ""
            return TravelAnswer("undetermined", "undetermined", None, ds, cross, horizon, why, fix)
        return TravelAnswer("no-orbit", None, None, None, cross, horizon, f"no orbit: {status}")
    if not ran:
        return TravelAnswer("periodic", mode, ds, ds, None, None, "periodic orbit")
    if mode not in ("push", "pull"):
        return TravelAnswer("periodic", mode, ds, ds, cross, horizon, f"periodic orbit: {mode}")
    if not crossed:
        return not_crossing(
            f"the transient from rest does not cross the travel within {horizon} cycles"
        )
    share = settling.settle_cycles / cross if cross else math.inf
    if share <= SETTLE_SHARE:
        return TravelAnswer(
            "periodic",
            mode,
            ds,
            ds,
            cross,
            horizon,
            f"settles within {share:.0%} of the {cross} cycles to cross the travel",
        )
    return crossing(
        f"not settled within {SETTLE_SHARE:.0%} of the {cross} cycles to cross the travel"
    )
