"""The fidelity ladder: model no more than a scene needs, and say which model answered.

Rungs, cheapest first (docs/MODEL.md sections in brackets):

1. ``lambda``   closed-form λ rule ["Push/pull criterion"]: mode only, an empirical
   fit, trustworthy only away from λ = 1 and inside the window and fit range;
2. ``vertical`` vertical-only impact map ["Vertical motion"]: hits per cycle, contact
   fraction, regime; exact, because the head's vertical motion ignores the slider;
3. ``rigid``    α → 0 rigid tangential contact (:mod:`betvdesign.dynamics.rigid`):
   exact closed form of the limit; its mode is always pull and its Δs is the
   small-α limit of the full model's;
4. ``full``     full stick-slip model, transient (:func:`betvdesign.dynamics.simulate`):
   s after N cycles, trajectories;
5. ``periodic`` periodic-orbit shooting (:func:`betvdesign.dynamics.periodic_orbit`):
   periodic Δs, mode, period, Floquet stability, to a residual ≤ 1e-10.

:func:`choose_rung` picks the cheapest rung that answers a question to the accuracy
asked and returns the reason; ``force=`` (the CLI's ``--fidelity``) overrides it, and
is refused when the forced rung cannot answer the question at all. The trust limits
used (how far from λ = 1 the λ rule never mispredicted, how the rigid limit's error
grows with α, what each rung costs) are *measured* by ``benchmarks/work_precision.py
--ladder`` and stored in :mod:`betvdesign.fidelity_measured`.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, Literal

from betvdesign.errors import UsageError
from betvdesign.params import ModelParams

Rung = Literal["lambda", "vertical", "rigid", "full", "periodic"]
Question = Literal["mode", "regime", "delta_s", "transient", "stability"]

#: Rungs, cheapest first.
RUNGS: tuple[Rung, ...] = ("lambda", "vertical", "rigid", "full", "periodic")
QUESTIONS: tuple[Question, ...] = ("mode", "regime", "delta_s", "transient", "stability")

#: Design window of the frequency (docs/MODEL.md "Vertical motion").
WINDOW = (0.5, 2.0)


@dataclass(frozen=True)
class RungInfo:
    """What a rung is, what it answers and where it comes from."""

    name: Rung
    model: str
    answers: frozenset[str]
    exact: str
    source: str


RUNG_INFO: dict[Rung, RungInfo] = {
    "lambda": RungInfo(
        "lambda",
        "closed-form λ rule (empirical fit)",
        frozenset({"mode"}),
        "a fit: wrong near λ = 1 and outside its fit range",
        'docs/MODEL.md "Push/pull criterion"',
    ),
    "vertical": RungInfo(
        "vertical",
        "vertical-only impact map",
        frozenset({"regime"}),
        "exact (the vertical motion does not depend on the slider)",
        'docs/MODEL.md "Vertical motion"',
    ),
    "rigid": RungInfo(
        "rigid",
        "α → 0 rigid tangential contact, closed form",
        frozenset({"mode", "delta_s", "regime"}),
        "exact for α → 0; error grows with α (measured)",
        "betvdesign.dynamics.rigid (limit of docs/MODEL.md as α → 0)",
    ),
    "full": RungInfo(
        "full",
        "full stick-slip model, exact event-driven transient",
        frozenset({"transient", "regime", "delta_s", "mode"}),
        "exact to round-off for the cycles simulated (Δs only once settled)",
        'docs/MODEL.md "Dimensionless model"',
    ),
    "periodic": RungInfo(
        "periodic",
        "periodic-orbit shooting on the full model",
        frozenset({"mode", "delta_s", "stability", "regime"}),
        "exact periodic state, residual ≤ 1e-10",
        'docs/MODEL.md "Slider"',
    ),
}


@dataclass(frozen=True)
class Choice:
    """The rung chosen for a question, and why (printed with every answer)."""

    rung: Rung
    question: Question
    reason: str
    forced: bool = False

    def as_dict(self) -> dict[str, Any]:
        return {
            "rung": self.rung,
            "question": self.question,
            "reason": self.reason,
            "forced": self.forced,
            "model": RUNG_INFO[self.rung].model,
        }


@dataclass
class Answer:
    """A rung's answer: ``value`` (Δs, mode, regime dict...), status and timing [s]."""

    choice: Choice
    status: str
    success: bool
    message: str
    value: Any
    mode: str | None
    seconds: float
    extra: dict[str, Any] = field(default_factory=dict)


def _measured() -> dict[str, Any]:
    from betvdesign import fidelity_measured

    return fidelity_measured.MEASURED


def _bin(x: float, edges: list[float]) -> int | None:
    for i in range(len(edges) - 1):
        last = i == len(edges) - 2
        if edges[i] * (1 - 1e-9) <= x < edges[i + 1] or (last and x <= edges[i + 1] * (1 + 1e-9)):
            return i
    return None


def lambda_trust_margin(varpi: float, beta: float) -> float:
    """|λ − 1| beyond which the λ rule is trusted at this (ϖ, β) [-]; inf: never.

    Measured (``benchmarks/work_precision.py --ladder``): the largest |λ − 1| at which
    the rule mispredicted, on the push/pull map and on a seeded random off-grid sample,
    per (ϖ, β) bin, times a safety factor; never below the same quantity taken over
    all mispredictions within |λ − 1| < 0.5 (the boundary band everywhere).
    Outside the measured bins: inf.
    """
    lam = _measured()["lambda"]
    i, j = _bin(varpi, lam["varpi_bins"]), _bin(beta, lam["beta_bins"])
    if i is None or j is None:
        return math.inf
    every = lam["mispredictions"] + lam["sample"]["mispredictions"]
    near = [abs(m["lam"] - 1.0) for m in every if abs(m["lam"] - 1.0) < 0.5]
    floor = lam["safety"] * max(near, default=0.0)
    return float(max(lam["trust_table"][i][j], floor))


def rigid_error_estimate(alpha: float) -> float:
    """Measured bound on the rigid limit's relative Δs error at this α [-]."""
    fit = _measured()["rigid"]
    return float(fit["coef"] * alpha ** fit["power"])


def _in_fit_range(p: ModelParams) -> bool:
    from betvdesign.rules import FIT_RANGE

    return all(
        lo * (1 - 1e-9) <= getattr(p, k) <= hi * (1 + 1e-9) for k, (lo, hi) in FIT_RANGE.items()
    )


def choose_rung(
    p: ModelParams,
    question: Question,
    *,
    tol: float = 1e-6,
    force: Rung | None = None,
) -> Choice:
    """Cheapest rung answering ``question`` for ``p`` to the accuracy ``tol``.

    question: "mode" (push or pull), "regime" (hits and contact), "delta_s" (periodic
    displacement per cycle, relative accuracy ``tol``), "transient" (s over N cycles),
    "stability" (Floquet multipliers). For "mode", ``tol`` is the misprediction rate
    accepted; the λ rule is used only where it never mispredicted on the measured map.
    force: a rung name (``--fidelity``); refused with :class:`UsageError` when that
    rung cannot answer the question.
    """
    if question not in QUESTIONS:
        raise UsageError(f"unknown question {question!r}; one of {', '.join(QUESTIONS)}")
    if force is not None:
        if force not in RUNGS:
            raise UsageError(f"unknown fidelity {force!r}; one of {', '.join(RUNGS)}")
        info = RUNG_INFO[force]
        if question not in info.answers:
            able = [r for r in RUNGS if question in RUNG_INFO[r].answers]
            raise UsageError(
                f"fidelity {force!r} ({info.model}) cannot answer {question!r}; "
                f"use one of {', '.join(able)}"
            )
        return Choice(force, question, f"forced by --fidelity {force} ({info.exact})", True)
    in_window = WINDOW[0] <= p.varpi < WINDOW[1]
    if question == "regime":
        return Choice("vertical", question, "the vertical motion does not depend on the slider")
    if question == "transient":
        return Choice("full", question, "only the full model gives the trajectory itself")
    if question == "stability":
        return Choice("periodic", question, "Floquet multipliers need the periodic orbit")
    if not in_window:
        return Choice(
            "periodic",
            question,
            f"ϖ = {p.varpi:.3g} outside the window {WINDOW[0]}–{WINDOW[1]}: the λ fit and "
            "the rigid limit do not apply there",
        )
    if question == "mode":
        margin = lambda_trust_margin(p.varpi, p.beta)
        dist = abs(p.lam - 1.0)
        if not _in_fit_range(p) or math.isinf(margin):
            return Choice(
                "periodic", question, "parameters outside the λ fit range / the measured map"
            )
        if dist >= margin:
            return Choice(
                "lambda",
                question,
                f"|λ − 1| = {dist:.3g} ≥ {margin:.3g}: beyond the largest misprediction "
                f"distance measured near ϖ = {p.varpi:.3g}, β = {p.beta:.3g} (push/pull map "
                "and random sample, with a safety factor)",
            )
        return Choice(
            "periodic",
            question,
            f"|λ − 1| = {dist:.3g} < {margin:.3g}: the λ rule was measured to mispredict "
            f"this far from λ = 1 near ϖ = {p.varpi:.3g}, β = {p.beta:.3g}, so the periodic "
            "orbit decides",
        )
    # delta_s
    est = rigid_error_estimate(p.alpha)
    if est <= tol:
        return Choice(
            "rigid",
            question,
            f"α = {p.alpha:.3g}: measured rigid-limit error ≈ {est:.2g} ≤ tol {tol:.2g}",
        )
    return Choice(
        "periodic",
        question,
        f"rigid limit error ≈ {est:.2g} > tol {tol:.2g} at α = {p.alpha:.3g}: "
        "the periodic orbit of the full model is needed",
    )


def evaluate(p: ModelParams, choice: Choice, *, cycles: int = 100) -> Answer:
    """Run the chosen rung and return its answer (``cycles`` for "transient")."""
    from betvdesign import dynamics
    from betvdesign.dynamics import rigid

    t0 = time.perf_counter()
    rung, q = choice.rung, choice.question
    if rung == "lambda":
        lam = p.lam
        mode = "push" if lam < 1.0 else "pull"
        return Answer(choice, "success", True, f"λ = {lam:.6g}", lam, mode, _dt(t0))
    if rung == "vertical" or (q == "regime" and rung != "periodic"):
        v = dynamics.vertical_motion(p.varpi)
        value = {
            "regime": v.regime,
            "hits_per_cycle": v.hits_per_cycle,
            "contact_fraction": v.contact_fraction,
            "period_cycles": v.period_cycles,
        }
        return Answer(choice, v.status, v.success, v.message, value, None, _dt(t0))
    if rung == "rigid":
        r = rigid.rigid_periodic(p)
        return Answer(choice, r.status, r.success, r.message, r.delta_s, r.mode, _dt(t0))
    if rung == "full":
        tr = dynamics.simulate(p, cycles, log_events=False)
        last = float(tr.delta_s[-1]) if len(tr.delta_s) else math.nan
        mode = None if not tr.success or last == 0 else ("push" if last > 0 else "pull")
        value = tr.s if q == "transient" else last
        msg = tr.message if q == "transient" else f"{tr.message}; Δs of the last cycle only"
        return Answer(choice, tr.status, tr.success, msg, value, mode, _dt(t0))
    po = dynamics.periodic_orbit(p)
    value: Any = po.delta_s
    if q == "stability":
        value = po.floquet_moduli
    elif q == "regime":
        value = {
            "impacts_per_cycle": po.impacts_per_cycle,
            "contact_fraction": po.contact_fraction,
            "period_cycles": po.period_cycles,
        }
    return Answer(choice, po.status, po.success, po.message, value, po.mode, _dt(t0))


def answer(
    p: ModelParams, question: Question, *, tol: float = 1e-6, force: Rung | None = None
) -> Answer:
    """Choose the cheapest adequate rung (or the forced one) and evaluate it."""
    return evaluate(p, choose_rung(p, question, tol=tol, force=force))


def _dt(t0: float) -> float:
    return time.perf_counter() - t0
