"""Unit-free dynamics of the BETV impact/stick-slip model (docs/MODEL.md).

- :func:`simulate`: exact event-driven transient (:mod:`solver`).
- :func:`periodic_orbit`: periodic state by Newton shooting (:mod:`periodic`).
- :func:`vertical_motion`: vertical-only fast path (:mod:`vertical`).
- :mod:`reference`: the same model with scipy ``solve_ivp`` (cross-checks, studies).
"""

from betvdesign.dynamics.periodic import periodic_orbit
from betvdesign.dynamics.result import Event, PeriodicResult, Trajectory
from betvdesign.dynamics.solver import simulate
from betvdesign.dynamics.vertical import VerticalResult, vertical_motion

__all__ = [
    "Event",
    "PeriodicResult",
    "Trajectory",
    "VerticalResult",
    "periodic_orbit",
    "simulate",
    "vertical_motion",
]
