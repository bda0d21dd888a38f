"""Fidelity ladder upward: is the paper's idealised model adequate for a device?

The idealised model (MODEL.md) is undamped with plastic impacts. For every actuator
set this study solves the exact periodic orbit (:func:`betvdesign.dynamics.periodic_orbit`)

1. of the idealised model (ζ_v = ζ_h = e = 0);
2. with the device's head damping and restitution, or, when the device gives none, the
   plausible defaults :data:`~betvdesign.checks.adequacy_data.DEFAULT_QUALITY` (Q = 30,
   normal and tangential) and :data:`~betvdesign.checks.adequacy_data.DEFAULT_RESTITUTION`
   (e = 0.1);
3. along Q over :data:`~betvdesign.checks.adequacy_data.QUALITY_RANGE` (both directions,
   e held at its value of 2) and along e over
   :data:`~betvdesign.checks.adequacy_data.RESTITUTION_RANGE` (damping held), every
   change of mode bracketed on the grid and bisected
   (:data:`~betvdesign.checks.adequacy_data.BISECT_STEPS`).

The mode of an orbit is :func:`betvdesign.model.domain.mode_of` (the one place), "none" when no
contact recurs. Verdicts (``SetAdequacy.status``): "adequate" (same mode everywhere in the
plausible ranges, speed within :data:`~betvdesign.checks.adequacy_data.SPEED_RTOL`),
"speed-differs" (mode holds, speed does not), "mode-flips" (the mode at the device or
somewhere in the ranges differs from the idealised one), "ideal-fails" (the idealised
model has no periodic orbit, e.g. unbounded tangential growth at α·ϖ² = 1, while the
richer one gives a finite answer, which is then reported), "failed" (no answer).
Speeds are Δs·u·cosθ·f_act with the device's stroke (thermal roll-off included).
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from dataclasses import replace
from typing import Any

import numpy as np

from betvdesign.checks.adequacy_data import (
    BISECT_STEPS,
    DEFAULT_QUALITY,
    DEFAULT_RESTITUTION,
    LIKELY_QUALITY,
    LIKELY_RESTITUTION,
    QUALITY_POINTS,
    QUALITY_RANGE,
    RESTITUTION_POINTS,
    RESTITUTION_RANGE,
    SCAN_MAX_CYCLES,
    SPEED_RTOL,
    Axis,
    Crossing,
    DeviceAdequacy,
    Point,
    Scan,
    SetAdequacy,
    Status,
    speed_change,
)
from betvdesign.errors import ParameterError
from betvdesign.model.damping import quality_from_zeta, zeta_from_quality
from betvdesign.model.domain import mode_of
from betvdesign.model.params import ModelParams
from betvdesign.nondim.record import DeviceDerivation, SetDerivation
from betvdesign.output.siformat import format_dimensionless as fmt_x
from betvdesign.output.siformat import format_si

Solver = Callable[..., Any]

#: Changes of mode bisected per scan; further ones keep their grid bracket.
MAX_BISECTED = 6


class _Orbits:
    """Periodic orbits of one set, each parameter set solved once (mirrored sets and
    the device's own point on a scan grid are reused)."""

    def __init__(self, sd: SetDerivation, solver: Solver | None):
        if solver is None:
            from betvdesign.dynamics import periodic_orbit

            solver = periodic_orbit
        self.solver, self.sd = solver, sd
        self.cache: dict[ModelParams, Point] = {}

    def point(self, p: ModelParams, max_cycles: int | None = SCAN_MAX_CYCLES) -> Point:
        """The orbit of ``p`` (``max_cycles`` None: the solver's default budget; the
        device's own points are solved first, with it, and reused on the scans)."""
        if p not in self.cache:
            self.cache[p] = self._solve(p, max_cycles)
        return self.cache[p]

    def _solve(self, p: ModelParams, max_cycles: int | None) -> Point:
        kw = {} if max_cycles is None else {"max_cycles": max_cycles}
        try:
            res = self.solver(p, **kw)
        except Exception as exc:  # a solver defect is a point without an answer
            status, ds, msg = "failed", None, f"solver raised {type(exc).__name__}: {exc}"
        else:
            status, msg = str(getattr(res, "status", "failed")), str(getattr(res, "message", ""))
            ok = bool(getattr(res, "success", False))
            ds = float(res.delta_s) if ok and res.delta_s is not None else None
        mode = mode_of(ds) if ds is not None else ("none" if status == "not_driven" else None)
        speed = self.sd.scales.speed_m_s(ds) if ds is not None else None
        return Point(
            _quality(p.zeta_v), _quality(p.zeta_h), p.restitution, status, ds, mode, speed, msg
        )


def _quality(zeta: float) -> float:
    return math.inf if zeta == 0.0 else float(quality_from_zeta(zeta))


def _zeta(q: float) -> float:
    return 0.0 if math.isinf(q) else float(zeta_from_quality(q))


def _with_quality(p: ModelParams, q: float) -> ModelParams:
    z = _zeta(q)
    return replace(p, zeta_v=z, zeta_h=z)


def _grid(axis: Axis, device_value: float | None) -> np.ndarray:
    if axis == "quality":
        g = np.geomspace(*QUALITY_RANGE, QUALITY_POINTS)
        lo, hi = QUALITY_RANGE
    else:
        g = np.linspace(*RESTITUTION_RANGE, RESTITUTION_POINTS)
        lo, hi = RESTITUTION_RANGE
    if device_value is not None and lo <= device_value <= hi:
        g = np.unique(np.append(g, device_value))
    return g


def _scan(orbits: _Orbits, base: ModelParams, axis: Axis, device_value: float | None) -> Scan:
    """Orbits along ``axis`` from ``base`` (the other term as ``base`` has it), every
    change of mode between grid neighbours bisected."""

    def at(x: float) -> Point:
        if axis == "quality":
            return orbits.point(_with_quality(base, x))
        return orbits.point(replace(base, restitution=x))

    values = _grid(axis, device_value)
    points = [at(float(x)) for x in values]
    crossings = []
    for i in range(len(points) - 1):
        a, b = points[i], points[i + 1]
        if a.mode == b.mode:
            continue
        lo, hi, m_hi = float(values[i]), float(values[i + 1]), b.mode
        if len(crossings) < MAX_BISECTED:
            for _ in range(BISECT_STEPS):
                mid = math.sqrt(lo * hi) if axis == "quality" else 0.5 * (lo + hi)
                pm = at(mid)
                if pm.mode == a.mode:
                    lo = mid
                else:
                    hi, m_hi = mid, pm.mode
        crossings.append(Crossing(axis, lo, hi, a.mode, m_hi))
    if axis == "quality":
        fixed = f"e = {fmt_x(base.restitution)}"
    else:
        q_v, q_h = _quality(base.zeta_v), _quality(base.zeta_h)
        fixed = f"Q = {_qtext(q_v)}" if q_v == q_h else f"Q_v = {_qtext(q_v)}, Q_h = {_qtext(q_h)}"
    return Scan(axis, fixed, tuple(points), tuple(crossings))


def _qtext(q: float) -> str:
    return "∞" if math.isinf(q) else fmt_x(q)


def _first_flip(scan: Scan, reference: str | None) -> tuple[Crossing | None, bool]:
    """(crossing where the mode first leaves ``reference`` going from the idealised end
    of the scan, whether it already differs at that end)."""
    pts = list(scan.points)
    order = range(len(pts) - 1, -1, -1) if scan.axis == "quality" else range(len(pts))
    idx = [i for i in order if pts[i].mode != reference]
    if not idx:
        return None, False
    i = idx[0]
    if i == order[0]:
        return None, True
    j = i + 1 if scan.axis == "quality" else i - 1
    lo_v, hi_v = sorted((scan.values[i], scan.values[j]))
    for c in scan.crossings:
        if lo_v <= c.low and c.high <= hi_v:
            return c, False
    return None, True  # pragma: no cover - every differing neighbour pair has a crossing


def assess_set(sd: SetDerivation, *, solver: Solver | None = None) -> SetAdequacy:
    """Adequacy of the idealised model for one actuator set (module docstring).

    Parameters
    ----------
    sd : SetDerivation
        The derived set (its ``params`` may carry ζ_v, ζ_h, e from the device file).
    solver : callable, optional
        ``periodic_orbit(p, max_cycles=...)`` stand-in (tests); default the exact solver.
    """
    if not isinstance(sd, SetDerivation):
        raise ParameterError(f"expected a SetDerivation, got {type(sd).__name__}")
    orbits = _Orbits(sd, solver)
    p = sd.params
    ideal_p = replace(p, zeta_v=0.0, zeta_h=0.0, restitution=0.0)
    source = "default" if p.ideal else "device"
    rich_p = (
        replace(
            p,
            zeta_v=_zeta(DEFAULT_QUALITY),
            zeta_h=_zeta(DEFAULT_QUALITY),
            restitution=DEFAULT_RESTITUTION,
        )
        if p.ideal
        else p
    )
    ideal = orbits.point(ideal_p, None)
    richer = orbits.point(rich_p, None)
    q_v, q_h = _quality(rich_p.zeta_v), _quality(rich_p.zeta_h)
    # The device's own point lies on the Q scan when both directions share one Q.
    q_scan = _scan(orbits, rich_p, "quality", q_v if q_v == q_h else None)
    e_scan = _scan(orbits, rich_p, "restitution", rich_p.restitution)
    reference = ideal.mode if ideal.mode is not None else richer.mode
    flip_q, q_end = _first_flip(q_scan, reference)
    flip_e, e_end = _first_flip(e_scan, reference)
    status = _status(ideal, richer, reference, q_scan, e_scan)
    msg = _message(
        sd,
        status,
        ideal,
        richer,
        source,
        reference,
        q_scan,
        e_scan,
        (flip_q, q_end),
        (flip_e, e_end),
    )
    return SetAdequacy(
        name=sd.name,
        intended_mode=sd.intended_mode,
        status=status,
        message=msg,
        ideal=ideal,
        richer=richer,
        source=source,
        quality_normal=q_v,
        quality_tangential=q_h,
        reference=reference,
        quality_scan=q_scan,
        restitution_scan=e_scan,
        flip_quality=flip_q,
        flip_restitution=flip_e,
        rolloff_factor=sd.scales.rolloff_factor,
    )


def _status(
    ideal: Point, richer: Point, reference: str | None, q_scan: Scan, e_scan: Scan
) -> Status:
    if reference is None:
        return "failed"
    if ideal.mode is None:
        return "ideal-fails"
    if richer.mode != reference or _flips_within(reference, q_scan, e_scan, likely=True):
        return "mode-flips"
    change = speed_change(ideal, richer)
    if change is not None and abs(change) > SPEED_RTOL:
        return "speed-differs"
    if _flips_within(reference, q_scan, e_scan, likely=False):
        return "flips-beyond"
    return "adequate"


def _flips_within(reference: str, q_scan: Scan, e_scan: Scan, *, likely: bool) -> bool:
    """Does the mode leave ``reference`` anywhere on the scans (``likely``: only within
    LIKELY_QUALITY and LIKELY_RESTITUTION, by grid point or bisected crossing)?"""
    for scan, band in ((q_scan, LIKELY_QUALITY), (e_scan, LIKELY_RESTITUTION)):
        lo, hi = band if likely else (-math.inf, math.inf)
        if any(
            pt.mode != reference and lo <= v <= hi
            for pt, v in zip(scan.points, scan.values, strict=True)
        ):
            return True
        if any(lo <= c.at <= hi for c in scan.crossings):
            return True
    return False


def _message(
    sd: SetDerivation,
    status: Status,
    ideal: Point,
    richer: Point,
    source: str,
    reference: str | None,
    q_scan: Scan,
    e_scan: Scan,
    flip_q: tuple[Crossing | None, bool],
    flip_e: tuple[Crossing | None, bool],
) -> str:
    terms = richer.terms + (
        " (plausible defaults: the device gives none)" if source == "default" else " (the device's)"
    )
    head = f"idealised {ideal.answer}; with {terms}: {richer.answer}"
    if ideal.speed_m_s and richer.speed_m_s and ideal.mode in ("push", "pull"):
        head += f" ({speed_change(ideal, richer):+.0%})"
    parts = [head]
    if status == "ideal-fails":
        parts.append(
            f"the idealised model has no periodic orbit ({ideal.status}"
            + (": unbounded tangential growth at α·ϖ² = 1" if ideal.status == "unbounded" else "")
            + f"); the richer model's finite answer holds: {richer.answer}"
        )
    elif status == "failed":
        parts.append("neither model gives a periodic orbit")
    ranges = (
        (q_scan, flip_q, f"Q {fmt_x(QUALITY_RANGE[0])}–{fmt_x(QUALITY_RANGE[1])}"),
        (e_scan, flip_e, f"e {fmt_x(RESTITUTION_RANGE[0])}–{fmt_x(RESTITUTION_RANGE[1])}"),
    )
    for scan, (flip, at_end), rng in ranges:
        where = f"{rng} ({scan.fixed})"
        if reference is None:
            continue
        if flip is not None:
            parts.append(f"the {reference} mode flips at {flip.text} within {where}")
        elif at_end:
            end = "Q = " + fmt_x(QUALITY_RANGE[1]) if scan.axis == "quality" else "e = 0"
            parts.append(f"already at {end} the mode is not {reference} ({where})")
        else:
            parts.append(f"{reference} over the whole range {where}")
    if sd.scales.has_rolloff:
        f = sd.scales.rolloff_factor
        parts.append(
            f"the thermal roll-off already scales every speed by ×{f:.3g} at f_act "
            f"{format_si(sd.scales.f_act_hz, 'Hz')} (mode unchanged)"
        )
    return "; ".join(parts)


def assess(derivation: DeviceDerivation, *, solver: Solver | None = None) -> DeviceAdequacy:
    """Adequacy of the idealised model for every set of a derived device (sets with
    identical parameters and scales are assessed once)."""
    done: dict[Any, SetAdequacy] = {}
    out = []
    for sd in derivation.sets:
        key = (sd.params, sd.scales)
        if key not in done:
            done[key] = assess_set(sd, solver=solver)
        out.append(replace(done[key], name=sd.name, intended_mode=sd.intended_mode))
    return DeviceAdequacy(derivation.name, tuple(out))


def adequacy(device: Any, *, solver: Solver | None = None) -> DeviceAdequacy:
    """Is the paper's idealised model adequate for ``device``? (module docstring)

    Parameters
    ----------
    device : str, pathlib.Path, DeviceSpec or DeviceDerivation
        A device YAML file, a loaded spec (e.g. ``spec.replace(...)``) or a derivation.
    solver : callable, optional
        Stand-in for :func:`betvdesign.dynamics.periodic_orbit` (tests).

    Returns
    -------
    DeviceAdequacy
        Per set: status, message, the idealised and the richer answer (mode, Δs [-],
        speed [m/s]), the Q and e scans and where the mode flips.
    """
    from betvdesign.nondim.device import derive, derive_file
    from betvdesign.spec.models import DeviceSpec

    if isinstance(device, DeviceDerivation):
        d = device
    elif isinstance(device, str | os.PathLike):
        d = derive_file(device)
    elif isinstance(device, DeviceSpec):
        d = derive(device)
    else:
        raise ParameterError(
            "adequacy() takes a device file path, a DeviceSpec or a DeviceDerivation, got "
            f"{type(device).__name__}"
        )
    return assess(d, solver=solver)
