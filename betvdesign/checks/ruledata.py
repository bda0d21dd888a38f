"""Design-rule results as data, and the thresholds the rules share.

:class:`RuleResult` (id, severity, passed, value, unit, threshold, message, source,
fix), :func:`verdict`, and :func:`orbit_mode` (the mode of an exact orbit, via
:func:`betvdesign.model.domain.mode_of`). Used by :mod:`betvdesign.checks.rules` and
:mod:`betvdesign.checks.rules_motion`.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any, Literal, Protocol

from betvdesign.model.domain import mode_of

Severity = Literal["error", "warning", "info"]

PUBLISHED_RTOL = 0.1
#: Relative perturbations of (ϖ, α) the mode must survive (fabrication spread).
MARGIN_CORNERS: tuple[tuple[float, float], ...] = (
    (0.95, 1.0),
    (1.05, 1.0),
    (1.0, 0.9),
    (1.0, 1.1),
)
#: Settling may take at most this share of the cycles that cross the travel range.
SETTLE_SHARE = 0.25

SRC_WINDOW = "MODEL.md, What the model shows: Vertical motion (Shin et al. 2004)"
SRC_LAMBDA = "MODEL.md, Push/pull criterion (empirical fit, Shin et al. 2004, eq. 9)"
SRC_TANG = "MODEL.md, What the model shows: tangential vibration undamped off contact"
SRC_SPEED = "MODEL.md, Displacement per cycle: speed = Δs·u·cosθ·f_act"
SRC_PUBLISHED = "device file: published_fit"
SRC_SOLVER = "betvdesign.dynamics.periodic_orbit (exact event-driven solver, shooting)"
SRC_SETTLE = "betvdesign.dynamics.settling (exact transient from rest, MODEL.md: Slider)"
SRC_MARGIN = "exact periodic orbits at ϖ·(1 ± 5 %) and α·(1 ± 10 %) (fabrication spread)"


class OrbitLike(Protocol):
    success: bool
    status: str
    message: str
    delta_s: float | None


@dataclass(frozen=True)
class RuleResult:
    """Outcome of one design rule.

    value: the number checked, in ``unit`` (SI, or "" for dimensionless; None when
    the rule could not be evaluated); threshold: the pass condition in words/maths;
    set_name: the actuator set ("" for device-level rules); fix: what to change when
    the rule fails ("" when it passes or no change is known).
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
        d = asdict(self)
        if d["value"] is not None and not math.isfinite(d["value"]):
            d["value"] = str(d["value"])  # JSON has no inf/nan
        return d


def verdict(results: list[RuleResult]) -> Literal["pass", "fail"]:
    """ "fail" when any error-severity rule fails, else "pass"."""
    return "fail" if any(r.severity == "error" and not r.passed for r in results) else "pass"


def orbit_mode(orbit: OrbitLike | None) -> str | None:
    """Mode of a successful exact orbit ("push", "pull", "stalled"), else None."""
    if orbit is None or not getattr(orbit, "success", False):
        return None
    return mode_of(orbit.delta_s)
