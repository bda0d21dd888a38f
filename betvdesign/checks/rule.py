"""A design rule's result as data, and what every rule shares.

:class:`RuleResult` (id, severity, passed, value, unit, threshold, message, source,
fix) is the contract of every design rule (:mod:`betvdesign.checks.rules`,
:mod:`betvdesign.checks.adequacy`); :func:`verdict` reads a list of them; the
formats and directions below are what rules write their values and messages in.
:class:`OrbitLike` is what a rule reads of a periodic-orbit result.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any, Literal, Protocol

from betvdesign.model.domain import mode_of
from betvdesign.nondim.record import SetDerivation
from betvdesign.output.numbers import json_float
from betvdesign.output.siformat import format_si

#: The fix text of a mode rule before the search has run: no direction is claimed
#: here (a direction table cannot know which way the nearest passing design lies); the
#: check's callers replace it with the search's answer (:func:`betvdesign.studies.fix.
#: advise`, the same search as ``betv fix``).
SEARCH_HINT = (
    "`betv fix FILE` finds the nearest passing value of each field (`betv check` names "
    "it unless run with --no-advice)"
)

Severity = Literal["error", "warning", "info"]


class OrbitLike(Protocol):
    """What the rules read of any periodic-orbit result, a failed one included.

    A :class:`betvdesign.dynamics.PeriodicResult`, or a stand-in for a solver that failed
    (``success`` False, ``status`` and ``message`` saying why). A successful orbit is a
    ``PeriodicResult`` and also gives ``period_cycles`` [-].

    Attributes
    ----------
    success : bool
        A periodic orbit was found.
    status : str
        The solver's status ("success", "unbounded", "not_driven", "not_converged", ...).
    message : str
        The solver's explanation.
    delta_s : float or None
        Slider increment per actuation cycle on the orbit [-] (in units of u·cosθ).
    """

    success: bool
    status: str
    message: str
    delta_s: float | None


@dataclass(frozen=True)
class RuleResult:
    """Outcome of one design rule.

    Parameters
    ----------
    id : str
        Rule id (``mode``, ``frequency-window``, ``published-fit.alpha``, ...).
    severity : {"error", "warning", "info"}
        A failed error fails the verdict; warnings and infos do not.
    passed : bool
        The rule's condition holds.
    value : float or None
        The number checked, in ``unit`` (SI, or [-] when ``unit`` is ""); None when the
        rule could not be evaluated.
    threshold : str
        The pass condition in words and maths.
    message : str
        What was found, in the designer's quantities.
    source : str
        Where the rule comes from (MODEL.md section, solver, device file).
    set_name : str
        The actuator set ("" for device-level rules).
    fix : str
        What to change when the rule fails ("" when it passes or no change is known).
    unit : str
        SI unit of ``value`` ("" when dimensionless).
    """

    id: str
    severity: Severity
    passed: bool
    value: float | None
    threshold: str
    message: str
    source: str
    set_name: str = ""
    fix: str = ""
    unit: str = ""

    def as_dict(self) -> dict[str, Any]:
        """JSON-safe record of the rule.

        Returns
        -------
        dict
            Every field by name; a non-finite ``value`` as None
            (:func:`betvdesign.output.numbers.json_float`).
        """
        d = asdict(self)
        d["value"] = json_float(d["value"])
        return d


def verdict(results: list[RuleResult]) -> Literal["pass", "fail"]:
    """The verdict of a list of rule results.

    Parameters
    ----------
    results : list of RuleResult
        The rules of a set or a device.

    Returns
    -------
    {"pass", "fail"}
        "fail" when any error-severity rule fails, else "pass".
    """
    return "fail" if any(r.severity == "error" and not r.passed for r in results) else "pass"


def orbit_mode(orbit: OrbitLike | None) -> str | None:
    """Mode of a successful exact orbit.

    Parameters
    ----------
    orbit : OrbitLike or None
        An exact periodic-orbit result (None: none was computed).

    Returns
    -------
    str or None
        "push", "pull" or "stalled" (:func:`betvdesign.model.domain.mode_of` of its Δs);
        None without a successful orbit.
    """
    if orbit is None or not orbit.success:
        return None
    return mode_of(orbit.delta_s)


def format_speed(v_m_s: float) -> str:
    """A speed with its SI prefix.

    Parameters
    ----------
    v_m_s : float
        Speed [m/s].

    Returns
    -------
    str
        E.g. ``"38.9 µm/s"`` (:func:`betvdesign.output.siformat.format_si`).
    """
    return format_si(v_m_s, "m/s")


def format_time(t_s: float) -> str:
    """A duration with its SI prefix.

    Parameters
    ----------
    t_s : float
        Duration [s].

    Returns
    -------
    str
        E.g. ``"1.03 s"`` (:func:`betvdesign.output.siformat.format_si`).
    """
    return format_si(t_s, "s")


def travel_direction(s: SetDerivation, mode: str) -> int:
    """Direction of slider travel for a set working in ``mode``.

    Parameters
    ----------
    s : SetDerivation
        The actuator set (its impact direction).
    mode : {"push", "pull"}
        Push moves the slider along the impacts, pull against them (MODEL.md, Slider).

    Returns
    -------
    int
        +1 (toward +x) or −1 (toward −x).
    """
    return s.impact_sign if mode == "push" else -s.impact_sign


def travel_axis(s: SetDerivation, delta_s: float) -> Literal["+x", "-x"]:
    """Direction the slider travels for a signed increment (or speed) along the impacts.

    Parameters
    ----------
    s : SetDerivation
        The actuator set (its impact direction).
    delta_s : float
        Δs per cycle [-], or the signed speed [m/s]: positive along the set's impacts;
        nonzero.

    Returns
    -------
    {"+x", "-x"}
        The direction of travel.
    """
    return "+x" if travel_direction(s, "push" if delta_s > 0 else "pull") > 0 else "-x"


def no_crossing(travel_m: float, cycles: int, f_act_hz: float) -> str:
    """The one wording of a slider that does not cross its travel range from rest.

    Parameters
    ----------
    travel_m : float
        Travel range [m].
    cycles : int
        Cycles simulated from rest [-].
    f_act_hz : float
        Actuation frequency [Hz] (the horizon in time is cycles / f_act).

    Returns
    -------
    str
        "does not cross its 50 µm travel within 200000 cycles (33.3 s)".
    """
    return (
        f"does not cross its {format_si(travel_m, 'm')} travel within {cycles} cycles "
        f"({format_time(cycles / f_act_hz)})"
    )
