"""How well an exact periodic answer is determined in float64 (unit-free).

The periodic orbit is exact in the sense that every phase is a closed form and every
event a certified root; its slider increment Δs is still computed in float64. Inside
the usual design ranges it is determined to ~1e-12 (the perturbed re-solves below move
it by that much); at the edges of the parameter space it is not, and a verdict read from
it would be noise (docs/MODEL.md, "Slider": settling takes ∝ 1/κ cycles; issue 24):

- κ → 0 (friction vanishing): the slider's velocity is fixed by the balance of friction
  impulses of size ∝ βκ per cycle, while the map is evaluated with round-off ~1e-16;
  below κ ≈ 1e-10 (at β ≈ 0.5) the Newton fixed point is a different one for every
  1e-12 change of a parameter (measured: Δs = 15.0, −2.69, 5.86 for κ = 7e-15, 1e-12,
  1e-10 where the limit κ → 0 of the true orbit is Δs ≈ 1.949);
- β → 0 (a heavy slider), α·ϖ² → 1 without damping: the slowest Floquet multiplier
  tends to 1 and Δs is determined less and less well.

Two checks, cheapest first:

1. :func:`degeneracy` (before solving): an input that makes a force of the model vanish
   below round-off of the unit normal force: friction κ < :data:`ROUND_OFF_SCALE`, or
   the slider's acceleration scale βκ < :data:`ROUND_OFF_SCALE` (the slider equation
   s'' = ±βκ sin ϖτ, MODEL.md "Contact"). Named, never solved.
2. :func:`determine` (after a successful solve): the orbit is solved again with each
   parameter (ϖ, α, β, κ, and the optional terms that are set) multiplied by
   1 + 1e-12 and by 1 − 1e-10 (:data:`PERTURBATIONS`); ``delta_s_error`` is the largest
   change of Δs. A true
   change of Δs under such a perturbation is |∂Δs/∂ln p|·1e-12, ≲ 1e-9 everywhere the
   answer means something; a change of the order of Δs means the answer is noise.
   The mode is then read by :func:`betvdesign.model.domain.mode_of` with that error:
   "undetermined" when the sign, or the speed to :data:`~betvdesign.model.domain.
   DETERMINED_RTOL`, is not determined.

Validated against brute force (long transients from rest and re-solves with other
perturbation sizes) on a seeded sample, ``benchmarks/bench_determination.py``.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Literal

from betvdesign.model.domain import DETERMINED_RTOL, ROUND_OFF_SCALE, mode_of
from betvdesign.model.params import ModelParams
from betvdesign.output.numbers import json_float

#: Relative perturbations of each parameter for the re-solves [-], one re-solve each: far
#: above the round-off of a parameter (1.1e-16) so the perturbed problem is a different
#: one, far below any fabrication spread so its true answer differs by at most
#: |∂Δs/∂ln p|·1e-10; both signs and two sizes, because a one-sided 1e-12 missed 2 of 196
#: held-out designs that a ±1e-10 brute force calls undetermined
#: (``benchmarks/bench_determination.py validate``).
PERTURBATIONS = (1e-12, -1e-10)
__all__ = ["PERTURBATIONS", "ROUND_OFF_SCALE", "Determination", "degeneracy", "determine"]

Status = Literal["determined", "undetermined", "degenerate", "not_solved"]


@dataclass(frozen=True, kw_only=True)
class Determination:
    """How well the periodic increment Δs of one design is determined.

    Attributes
    ----------
    status : {"determined", "undetermined", "degenerate", "not_solved"}
        "determined": the mode (and Δs to :data:`DETERMINED_RTOL`) holds under the
        perturbed re-solves; "undetermined": it does not (``reason`` says how);
        "degenerate": an input makes a force vanish below round-off (not solved);
        "not_solved": the orbit itself failed (its own status says why).
    delta_s : float or None
        Δs of the orbit [-] (per actuation cycle, units of u·cosθ).
    delta_s_error : float or None
        Largest change of Δs under the perturbed re-solves [-]; inf when a perturbed
        re-solve failed where the orbit was found; None when not assessed.
    mode : str or None
        :func:`~betvdesign.model.domain.mode_of` of Δs with that error: "push",
        "pull", "stalled" or "undetermined".
    reason : str
        One sentence for a designer: what is (not) determined, and why.
    fix : str
        What to change when it is not determined ("" otherwise).
    perturbed : tuple of float
        Δs of each re-solve [-] (nan for a failed one), in the order of ``fields``.
    fields : tuple of str
        The parameter perturbed in each re-solve.
    n_solves : int
        Re-solves run.
    elapsed_s : float
        Wall time of the assessment [s].
    """

    status: Status
    delta_s: float | None
    delta_s_error: float | None
    mode: str | None
    reason: str
    fix: str = ""
    perturbed: tuple[float, ...] = ()
    fields: tuple[str, ...] = ()
    n_solves: int = 0
    elapsed_s: float = 0.0

    @property
    def determined(self) -> bool:
        """True when the mode (and the speed to 1 %) is determined."""
        return self.status == "determined"

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready record (non-finite floats as None)."""
        return {
            "status": self.status,
            "mode": self.mode,
            "delta_s": json_float(self.delta_s),
            "delta_s_error": json_float(self.delta_s_error),
            "reason": self.reason,
            "fix": self.fix,
            "perturbations": list(PERTURBATIONS),
            "fields": list(self.fields),
            "perturbed": [json_float(v) for v in self.perturbed],
            "n_solves": self.n_solves,
            "elapsed_s": json_float(self.elapsed_s),
        }


def degeneracy(p: ModelParams) -> tuple[str, str] | None:
    """Why the design's answer cannot be resolved in float64, before solving; or None.

    Parameters
    ----------
    p : ModelParams
        The design (ϖ, α, β, κ and the optional terms) [-].

    Returns
    -------
    tuple of str, or None
        (why: a sentence naming the vanishing force, fix: what to change), or None when
        no force of the model is below :data:`ROUND_OFF_SCALE`.

    Notes
    -----
    In contact the friction force is κ·N with N ∝ sin ϖτ of unit amplitude, and the
    slider obeys s'' = ±βκ sin ϖτ (Shin et al. 2004, Eqs. for slip; docs/MODEL.md
    "Contact"). When κ or βκ is below round-off of the unit force, friction neither
    drives the slider nor decides stick against slip in float64.

    References
    ----------
    W. P. Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773.
    """
    if p.kappa < ROUND_OFF_SCALE:
        return (
            f"friction κ = μ·tanθ = {p.kappa:.3g} is below round-off of the normal force "
            f"(< {ROUND_OFF_SCALE:g}): the slider is not driven in float64 and no mode "
            "can be computed",
            "raise the impact angle (κ = μ·tanθ) or the friction coefficient",
        )
    if p.beta * p.kappa < ROUND_OFF_SCALE:
        return (
            f"slider acceleration scale βκ = {p.beta * p.kappa:.3g} is below round-off "
            f"(< {ROUND_OFF_SCALE:g}): the slider is too heavy against the head (β = "
            f"{p.beta:.3g}) for its motion to be resolved",
            "use a lighter slider (narrower, shorter or fewer beams) or a heavier head, or a "
            "larger impact angle",
        )
    return None


def _perturbed(p: ModelParams) -> list[tuple[str, ModelParams]]:
    """The (field, design) of each re-solve.

    (field, design) of each re-solve: ϖ, α, β, κ and each optional term that is set,
    each moved by every one of :data:`PERTURBATIONS`.
    """
    out = []
    for name in ("varpi", "alpha", "beta", "kappa", "zeta_v", "zeta_h", "restitution"):
        value = getattr(p, name)
        if value == 0.0:
            continue
        for rel in PERTURBATIONS:
            moved = value * (1.0 + rel)
            if name == "restitution" and moved >= 1.0:
                moved = value * (1.0 - abs(rel))
            out.append((f"{name}×(1{rel:+.0e})", dataclasses.replace(p, **{name: moved})))
    return out


def determine(
    p: ModelParams,
    orbit: Any,
    *,
    solver: Callable[[ModelParams], Any] | None = None,
) -> Determination:
    """How well the periodic increment Δs of ``orbit`` is determined.

    Parameters
    ----------
    p : ModelParams
        The design the orbit was solved for [-].
    orbit : PeriodicResult
        Its periodic orbit (:func:`betvdesign.dynamics.periodic_orbit`); a failed one
        gives status "not_solved".
    solver : callable, optional
        ``solver(params) -> PeriodicResult`` for the re-solves (default
        :func:`~betvdesign.dynamics.periodic_orbit`; a check passes its own to reuse
        solved designs).

    Returns
    -------
    Determination
        Status, Δs, its error [-], the mode read with that error, and why.

    Notes
    -----
    Each parameter is multiplied by 1 + r for every r in :data:`PERTURBATIONS` and the
    orbit solved again from rest; the error is max |Δs_i − Δs|. The mode is determined when
    |Δs| − error > :data:`~betvdesign.model.domain.DELTA_S_STALL` and error ≤
    :data:`~betvdesign.model.domain.DETERMINED_RTOL`·|Δs| (push, pull), or when
    |Δs| + error ≤ DELTA_S_STALL (stalled).
    """
    t0 = time.perf_counter()
    unassessed = _unassessed(p, orbit)
    if unassessed is not None:
        return unassessed
    if solver is None:
        from betvdesign.dynamics.periodic import periodic_orbit

        solver = periodic_orbit
    ds = float(orbit.delta_s)
    fields, values, failures = _resolve(p, solver)
    errs = [abs(v - ds) for v in values if math.isfinite(v)]
    err = math.inf if failures else max(errs, default=0.0)
    mode = mode_of(ds, error=err)
    n = len(values)
    record = dict(
        delta_s=ds,
        delta_s_error=err,
        perturbed=tuple(values),
        fields=tuple(fields),
        n_solves=n,
        elapsed_s=time.perf_counter() - t0,
    )
    if mode != "undetermined":
        reason = (
            f"Δs = {ds:.6g} changes by at most {err:.2g} under {n} re-solves with a "
            "parameter moved by 1e-12 or 1e-10"
        )
        return Determination(status="determined", mode=mode, reason=reason, **record)
    if failures:
        reason, fix = _lost_orbit(p, ds, failures, n)
    else:
        reason, fix = _moved_orbit(orbit, ds, fields, values, err)
    return Determination(
        status="undetermined", mode="undetermined", reason=reason, fix=fix, **record
    )


def _unassessed(p: ModelParams, orbit: Any) -> Determination | None:
    """The determination of a design that is not re-solved, or None.

    Parameters
    ----------
    p : ModelParams
        The design [-].
    orbit : PeriodicResult or None
        Its orbit.

    Returns
    -------
    Determination or None
        "degenerate" (a force below round-off, :func:`degeneracy`), "not_solved" (no
        orbit to assess), or None when the re-solves are to run.
    """
    degenerate = degeneracy(p)
    if degenerate is not None:
        why, fix = degenerate
        return Determination(
            status="degenerate",
            delta_s=None,
            delta_s_error=None,
            mode="undetermined",
            reason=why,
            fix=fix,
        )
    if orbit is None or not orbit.success or orbit.delta_s is None:
        return Determination(
            status="not_solved",
            delta_s=None,
            delta_s_error=None,
            mode=None,
            reason="no periodic orbit to assess",
        )
    return None


def _resolve(
    p: ModelParams, solver: Callable[[ModelParams], Any]
) -> tuple[list[str], list[float], list[tuple[str, Any]]]:
    """The perturbed re-solves of a design.

    Parameters
    ----------
    p : ModelParams
        The design [-].
    solver : callable
        ``solver(params) -> PeriodicResult``.

    Returns
    -------
    tuple
        (the field moved in each re-solve, its Δs [-] or nan when it failed, the failed
        re-solves as (field, result)).
    """
    fields: list[str] = []
    values: list[float] = []
    failures: list[tuple[str, Any]] = []
    for name, q in _perturbed(p):
        r = solver(q)
        fields.append(name)
        if r.success and r.delta_s is not None:
            values.append(float(r.delta_s))
        else:
            values.append(math.nan)
            failures.append((name, r))
    return fields, values, failures


def _moved_orbit(
    orbit: Any, ds: float, fields: list[str], values: list[float], err: float
) -> tuple[str, str]:
    """The (reason, fix) when every re-solve finds an orbit but Δs moves too much.

    Parameters
    ----------
    orbit : PeriodicResult
        The design's orbit.
    ds : float
        Its Δs [-].
    fields, values : list
        The field moved in each re-solve and its Δs [-].
    err : float
        The largest change of Δs [-].

    Returns
    -------
    tuple of str
        The re-solve that moved it most and by how much; what to change.
    """
    worst = max(range(len(values)), key=lambda i: abs(values[i] - ds))
    reason = (
        f"Δs = {ds:.4g} is not determined: the re-solve with {fields[worst]} gives "
        f"Δs = {values[worst]:.4g}, a change of {err:.3g} (> {DETERMINED_RTOL:.0%} of "
        "|Δs|, or across zero); the periodic answer here is round-off (slowest Floquet "
        f"multiplier |μ| = {max(orbit.floquet_moduli or [math.nan]):.12f})"
    )
    fix = (
        "move the design away from the edge of the parameter space where the slider's "
        "motion is set by forces near round-off (friction κ or the mass ratio β near 0, "
        "α·ϖ² near 1 without damping); `betv fix FILE` finds a change"
    )
    return reason, fix


def _lost_orbit(
    p: ModelParams, ds: float, failures: list[tuple[str, Any]], n: int
) -> tuple[str, str]:
    """The (reason, fix) when re-solves lose the orbit.

    (reason, fix) when re-solves lose the orbit: which re-solves, their status and
    message, and a fix that names the parameter whose move lost it (never a generic
    cause).
    """
    listed = "; ".join(
        f"{name} → {r.status} ({str(r.message).split(';')[0][:160]})" for name, r in failures
    )
    reason = (
        f"the periodic orbit (Δs = {ds:.4g}) is lost in {len(failures)} of {n} re-solves "
        f"with a parameter moved by at most 1e-10: {listed}"
    )
    moved = sorted({name.split("×")[0] for name, _ in failures})
    statuses = {str(r.status) for _, r in failures}
    if moved == ["varpi"] and "not_driven" in statuses:
        fix = (
            f"ϖ = {p.varpi:.12g} sits where contact vanishes (the window's upper edge ϖ = 2): "
            "lower ϖ into 0.5 ≤ ϖ < 2 with margin (drive frequency down or vertical "
            "resonance up); `betv fix FILE` finds the change"
        )
    else:
        fix = (
            f"move {', '.join(moved)} away from where the orbit changes kind "
            f"({', '.join(sorted(statuses))} a hair away); `betv fix FILE` finds a change"
        )
    return reason, fix
