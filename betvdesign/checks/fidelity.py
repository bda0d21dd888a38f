"""The fidelity ladder: model no more than a scene needs, and say which model answered.

Rungs, cheapest first (docs/MODEL.md sections in brackets):

1. ``lambda``   closed-form λ rule ["Push/pull criterion"]: mode only, an empirical
   fit; only ever used when forced (``--fidelity lambda`` on sweeps and tolerance
   studies), and then its held-out error rate is stated;
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
is refused when the forced rung cannot answer the question at all. A *mode* is never
chosen from a fit: the question "mode" is answered by the periodic orbit (about 1 ms).
The one exception is the full model's chatter limit α·ϖ² < :data:`CHATTER_Q`
(:func:`below_chatter_limit`, measured): there its stick/slip switching chatters from
the first contact and neither the periodic nor the full rung can run, so for an ideal
design in the window "mode" and "delta_s" are answered by the rigid limit, with its
error stated (as exceeding tol when it does); a rung that must run the full model there
says so in its reason, with what to try. What the ladder states about the cheaper rungs
(the λ fit's misprediction rate on a held-out random sample with its 95 % bound, the
rigid limit's error envelope over α, indicative costs) is *measured* by
``benchmarks/work_precision.py --ladder`` and stored as package data
``betvdesign/data/fidelity_measured.json`` with its provenance; :func:`stale` says
when the stored numbers no longer match the solver.

References
----------
.. [1] Shin, Pai, Lin, Hui and Tien, J. Appl. Phys. 96, 7603 (2004),
   doi:10.1063/1.1809773 (the λ criterion, eq. 9; the vertical motion; the model).
"""

from __future__ import annotations

import functools
import json
import math
import time
from dataclasses import dataclass, field
from typing import Any, Literal

from betvdesign.errors import UsageError
from betvdesign.model import domain
from betvdesign.model.params import ModelParams

Rung = Literal["lambda", "vertical", "rigid", "full", "periodic"]
Question = Literal["mode", "regime", "delta_s", "transient", "stability"]

#: Rungs, cheapest first.
RUNGS: tuple[Rung, ...] = ("lambda", "vertical", "rigid", "full", "periodic")
QUESTIONS: tuple[Question, ...] = ("mode", "regime", "delta_s", "transient", "stability")

WINDOW = domain.VARPI_WINDOW


@dataclass(frozen=True)
class RungInfo:
    """What a rung is, what it answers and where it comes from.

    Parameters
    ----------
    name : Rung
        The rung.
    model : str
        The model it solves, in words.
    answers : frozenset of str
        The questions it answers (:data:`QUESTIONS`).
    exact : str
        How exact its answer is.
    source : str
        Where it comes from (MODEL.md section, module).
    """

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
    """The rung chosen for a question, and why (printed with every answer).

    Parameters
    ----------
    rung : Rung
        The rung that answers.
    question : Question
        The question asked.
    reason : str
        Why this rung.
    forced : bool
        Chosen by ``--fidelity`` rather than by :func:`choose_rung`.
    """

    rung: Rung
    question: Question
    reason: str
    forced: bool = False

    def as_dict(self) -> dict[str, Any]:
        """JSON record of the choice.

        Returns
        -------
        dict
            ``rung``, ``question``, ``reason``, ``forced`` and the rung's ``model``.
        """
        return {
            "rung": self.rung,
            "question": self.question,
            "reason": self.reason,
            "forced": self.forced,
            "model": RUNG_INFO[self.rung].model,
        }


@dataclass
class Answer:
    """A rung's answer.

    Parameters
    ----------
    choice : Choice
        The rung and why.
    status, message : str
        The rung's status and explanation.
    success : bool
        The rung answered.
    value : Any
        The answer: Δs per cycle [-], λ [-], Floquet moduli [-], a regime dict or the
        slider positions [-] of a transient.
    mode : str or None
        "push", "pull", "stalled", or None.
    seconds : float
        Time taken [s].
    extra : dict
        Anything else the rung reports.
    """

    choice: Choice
    status: str
    success: bool
    message: str
    value: Any
    mode: str | None
    seconds: float
    extra: dict[str, Any] = field(default_factory=dict)


MEASURED_DATA = "data/fidelity_measured.json"


@functools.lru_cache(maxsize=1)
def measured_document() -> dict[str, Any]:
    """The stored measurements with their provenance.

    Returns
    -------
    dict
        The package data :data:`MEASURED_DATA` (JSON): ``measured`` and its provenance.
    """
    from importlib.resources import files

    text = files("betvdesign").joinpath(MEASURED_DATA).read_text("utf-8")
    return json.loads(text)


def measured() -> dict[str, Any]:
    """The stored measurements the ladder states (without their provenance).

    Returns
    -------
    dict
        ``lambda`` (held-out misprediction rate), ``rigid`` (error fit over α),
        ``fingerprint`` (periodic Δs of reference designs), ``full_cycles`` and
        ``costs_cpu_s`` (indicative costs [s]).
    """
    return measured_document()["measured"]


def lambda_error() -> dict[str, Any]:
    """The λ rule's measured misprediction rate on the held-out random sample.

    Returns
    -------
    dict
        ``n`` (converged designs), ``mispredicted``, ``rate`` [-], ``upper_95`` [-] (one-sided
        95 % Clopper–Pearson bound) and ``bands`` (the same per |λ − 1| band).
    """
    h = measured()["lambda"]["held_out"]
    return {
        "n": h["converged"],
        "mispredicted": h["mispredicted"],
        "rate": h["rate"],
        "upper_95": h["upper_95"],
        "bands": h["bands"],
    }


def lambda_error_statement() -> str:
    """One sentence a study prints when it answers "mode" with λ.

    Returns
    -------
    str
        The held-out misprediction count, rate and 95 % bound, in words.
    """
    e = lambda_error()
    return (
        f"the λ fit named the wrong mode for {e['mispredicted']} of {e['n']} held-out random "
        f"designs ({100 * e['rate']:.2f} %, ≤ {100 * e['upper_95']:.2f} % at 95 % confidence)"
    )


def stale(rtol: float = 1e-9) -> list[str]:
    """Why the stored measurements no longer describe the current solver.

    Parameters
    ----------
    rtol : float
        Relative tolerance [-] on the periodic Δs of each fingerprint design.

    Returns
    -------
    list of str
        One line per fingerprint design whose Δs, recomputed now, differs from the
        stored one; [] when they all agree.
    """
    from betvdesign import dynamics

    out = []
    for f in measured().get("fingerprint", []):
        p = ModelParams(f["varpi"], f["alpha"], f["beta"], f["kappa"])
        now = dynamics.periodic_orbit(p).delta_s
        old = f["delta_s"]
        if now is None or old is None or abs(now - old) > rtol * max(abs(old), 1e-300):
            out.append(f"Δs at {p.as_dict()}: stored {old}, now {now}")
    return out


#: rungs that solve the idealised model only (no damping, plastic impacts); the vertical
#: rung takes ζ_v and e (the vertical motion does not depend on ζ_h or the slider)
IDEAL_ONLY = ("lambda", "rigid")


def rigid_error_estimate(alpha: float) -> float:
    """Measured estimate of the rigid limit's relative Δs error.

    Parameters
    ----------
    alpha : float
        Tangential compliance ratio α [-].

    Returns
    -------
    float
        The measured fit coef·α^power [-] of the relative Δs error (fitted on three
        designs, β 0.5–1.5; not a bound elsewhere: near the chatter limit it was
        exceeded up to 169×, see :func:`below_chatter_limit`).
    """
    fit = measured()["rigid"]
    return float(fit["coef"] * alpha ** fit["power"])


#: q = α·ϖ² [-] below which the full model's stick/slip switching can chatter, so that
#: neither the periodic nor the full rung answers (measured; :func:`below_chatter_limit`).
CHATTER_Q = 3e-6
#: Largest relative Δs error [-] of the rigid limit against the periodic orbit measured
#: near :data:`CHATTER_Q` (α·ϖ² from 3e-7 to 4.2e-6; :func:`below_chatter_limit`).
RIGID_ERROR_NEAR_LIMIT = 0.36


def below_chatter_limit(p: ModelParams) -> bool:
    """Whether ``p`` is where the full model can chatter from its first contact.

    At small α the head's tangential oscillation (period 2π√α) is so fast that one
    contact, at most π/ϖ long, holds more stick/slip switches than the exact solver
    follows (``betvdesign.dynamics.contact.MAX_SWITCHES`` = 1000 per contact): it stops
    with "the stick/slip switching chatters" (at ϖ = 0.6, α = 1e-6 in the very first
    contact, 1001 switches), and neither the periodic nor the full rung answers. The
    switches go as 1/(ϖ√α), so the limit is one of q = α·ϖ² [-] (the squared ratio of the
    actuation to the tangential angular frequency).

    Measured with ``python benchmarks/chatter_limit.py`` (the periodic orbit from rest on
    585 ideal designs, ϖ 0.5–1.9 × β 0.05–100 × κ 0.02–1, at 24 values of q from 3e-7 to
    4.2e-6): it chattered at q ≤ 2.38e-6 and never at q ≥ 2.67e-6; at q = 3e-7 in 97 %
    of the designs, at 9.5e-7 in 36 %, at 2.4e-6 in 1 % (only β ≥ 10 chattered above
    q = 9.5e-7). :data:`CHATTER_Q` = 3e-6 lies one grid step (12 %) above the first q at
    which none chattered. Where the periodic orbit did answer (8834 of the 14040 runs),
    the rigid limit, which the ladder takes instead below the limit, named the same mode
    on every design, with a relative Δs error up to :data:`RIGID_ERROR_NEAR_LIMIT` = 0.36
    (ϖ = 0.5, β = 0.05, κ = 0.02; it grows as β·κ falls: ≤ 0.05 for β ≥ 0.3, ≤ 0.015 for
    β ≥ 0.9), up to 169× the stored :func:`rigid_error_estimate` (4.5× or more somewhere
    for every β ≤ 1.5 and κ): that estimate is a fit, not a bound. One run took 273 s on
    2 shared cores (2026-11-23).

    Parameters
    ----------
    p : ModelParams
        The design's dimensionless parameters (the measurement is of the idealised
        model; damping and restitution change where contacts chatter).

    Returns
    -------
    bool
        α·ϖ² < :data:`CHATTER_Q`.
    """
    return p.alpha * p.varpi**2 < CHATTER_Q


def _chatter_note(p: ModelParams) -> str:
    """The caution a full-model rung's reason carries below the chatter limit ("" above).

    Parameters
    ----------
    p : ModelParams
        The design's dimensionless parameters.

    Returns
    -------
    str
        "; α·ϖ² = … < CHATTER_Q: …" naming the limit and what to try, or "".
    """
    if not below_chatter_limit(p):
        return ""
    rigid = p.ideal and domain.in_window(p.varpi)
    return (
        f"; caution: α·ϖ² = {p.alpha * p.varpi**2:.2g} < {CHATTER_Q:g}, where the full "
        "model's stick/slip switching can chatter from the first contact (measured, "
        "benchmarks/chatter_limit.py): if it stops there, raise α to at least "
        f"{CHATTER_Q / p.varpi**2:.2g} at this ϖ"
        + (", or ask for mode or delta_s, which the rigid limit answers there" if rigid else "")
    )


def _forced_rung(p: ModelParams, question: Question, force: Rung) -> Choice:
    """The rung ``--fidelity`` forces, if it can answer ``question`` for ``p``.

    Parameters
    ----------
    p : ModelParams
        The design's dimensionless parameters.
    question : Question
        What is asked.
    force : Rung
        The rung named.

    Returns
    -------
    Choice
        The forced rung, its reason naming the measured error of a λ or rigid rung and
        the chatter limit of the full model.

    Raises
    ------
    UsageError
        For an unknown rung, or one that cannot answer (or is of the idealised model
        while ``p`` has damping or restitution).
    """
    if force not in RUNGS:
        raise UsageError(f"unknown fidelity {force!r}; one of {', '.join(RUNGS)}")
    info = RUNG_INFO[force]
    if question not in info.answers:
        able = [
            r
            for r in RUNGS
            if question in RUNG_INFO[r].answers and (p.ideal or r not in IDEAL_ONLY)
        ]
        raise UsageError(
            f"fidelity {force!r} ({info.model}) cannot answer {question!r}; "
            f"use one of {', '.join(able)}"
        )
    if not p.ideal and force in IDEAL_ONLY:
        raise UsageError(
            f"fidelity {force!r} ({info.model}) is a rung of the idealised model (no "
            "damping, plastic impacts) and this device has damping or restitution; use "
            "periodic or full"
        )
    why = f"forced by --fidelity {force} ({info.exact})"
    if force == "lambda":
        why += f"; {lambda_error_statement()}"
    elif force == "rigid" and question in ("mode", "delta_s"):
        why += (
            f"; measured relative Δs error ≈ {rigid_error_estimate(p.alpha):.2g} at "
            f"α = {p.alpha:.3g} (an estimate), and its mode is always pull"
        )
    elif force in ("full", "periodic"):
        why += _chatter_note(p)
    return Choice(force, question, why, True)


def _chatter_limit(p: ModelParams) -> str:
    """The sentence naming the chatter limit α·ϖ² < :data:`CHATTER_Q` for ``p``."""
    return (
        f"α·ϖ² = {p.alpha * p.varpi**2:.2g} < {CHATTER_Q:g}, the measured limit below which "
        "the full model's stick/slip switching chatters from the first contact and the "
        "periodic orbit cannot be computed (measured in 97 % of the designs at α·ϖ² = "
        "3e-7, 36 % at 9.5e-7, a few up to 2.4e-6: benchmarks/chatter_limit.py); it runs "
        "from α = "
        f"{CHATTER_Q / p.varpi**2:.2g} at this ϖ"
    )


def _mode_rung(p: ModelParams, question: Question, chatter: bool, note: str) -> Choice:
    """The rung answering "mode" in the window (``chatter``: below the chatter limit).

    Parameters
    ----------
    p : ModelParams
        The design's dimensionless parameters.
    question : Question
        "mode".
    chatter : bool
        Whether ``p`` is below the chatter limit (the rigid limit answers then).
    note : str
        The chatter caution a full-model rung's reason carries.

    Returns
    -------
    Choice
        The periodic orbit, or the rigid limit below the chatter limit.
    """
    limit = _chatter_limit(p)
    if chatter:
        return Choice(
            "rigid",
            question,
            f"{limit}; the rigid limit (α → 0) answers instead: its mode, always pull, "
            "was the periodic orbit's on every design measured near the limit (its "
            f"relative Δs error there at most {RIGID_ERROR_NEAR_LIMIT:g}, below 1)",
        )
    return Choice(
        "periodic",
        question,
        "a mode is taken from the exact periodic orbit (≈ 1 ms); the λ fit "
        f"is a prediction ({lambda_error_statement()}), never a verdict" + note,
    )


def _delta_s_rung(p: ModelParams, question: Question, tol: float, chatter: bool) -> Choice:
    """The rung answering "delta_s" of an ideal design in the window, to ``tol``.

    Parameters
    ----------
    p : ModelParams
        The design's dimensionless parameters.
    question : Question
        "delta_s".
    tol : float
        Relative accuracy asked [-].
    chatter : bool
        Whether ``p`` is below the chatter limit.

    Returns
    -------
    Choice
        The rigid limit when its measured error is within ``tol`` or the full model
        cannot run, else the periodic orbit.
    """
    est = rigid_error_estimate(p.alpha)
    limit = _chatter_limit(p)
    if est <= tol:
        why = f"α = {p.alpha:.3g}: measured rigid-limit error ≈ {est:.2g} ≤ tol {tol:.2g}"
        if chatter:
            why += (
                f"; an estimate, not a bound: here α·ϖ² = {p.alpha * p.varpi**2:.2g} < "
                f"{CHATTER_Q:g}, below the measured limit where the full model runs to check "
                f"it, and near that limit the rigid error was measured up to "
                f"{RIGID_ERROR_NEAR_LIMIT:g} (largest at small β·κ)"
            )
        return Choice("rigid", question, why)
    if chatter:
        return Choice(
            "rigid",
            question,
            f"{limit}; the rigid limit (α → 0) is the closest answer there, but its error "
            f"estimate ≈ {est:.2g} exceeds tol {tol:.2g} (and near the limit its error was "
            f"measured up to {RIGID_ERROR_NEAR_LIMIT:g}, largest at small β·κ): the accuracy "
            "asked cannot be had at this α",
        )
    return Choice(
        "periodic",
        question,
        f"rigid limit error ≈ {est:.2g} > tol {tol:.2g} at α = {p.alpha:.3g}: "
        "the periodic orbit of the full model is needed",
    )


def choose_rung(
    p: ModelParams,
    question: Question,
    *,
    tol: float = 1e-6,
    force: Rung | None = None,
) -> Choice:
    """Cheapest rung answering ``question`` for ``p`` to the accuracy ``tol``.

    Parameters
    ----------
    p : ModelParams
        The design's dimensionless parameters.
    question : Question
        "mode" (push or pull), "regime" (hits and contact), "delta_s" (periodic
        displacement per cycle), "transient" (s over N cycles) or "stability" (Floquet
        multipliers).
    tol : float
        Relative accuracy [-] asked of "delta_s" (a mode is the periodic orbit's, or the
        rigid limit's below the chatter limit).
    force : Rung, optional
        A rung name (``--fidelity``), used instead of the cheapest.

    Returns
    -------
    Choice
        The rung and why (with the measured error of a forced λ or rigid rung). Below
        the chatter limit α·ϖ² < :data:`CHATTER_Q` (:func:`below_chatter_limit`), where
        the full model cannot be run: "mode" and "delta_s" of an ideal design in the
        window go to the rigid limit, whose reason names the limit and states its error
        estimate, as exceeding ``tol`` when it does (the closest answer there, not one
        to ``tol``); any rung that runs the full model carries a caution naming the
        limit and the α from which it runs.

    Raises
    ------
    UsageError
        For an unknown question or rung, or a forced rung that cannot answer.

    References
    ----------
    .. [1] Shin, Pai, Lin, Hui and Tien, J. Appl. Phys. 96, 7603 (2004),
       doi:10.1063/1.1809773 (the λ criterion and the window 0.5 ≤ ϖ < 2).
    """
    if question not in QUESTIONS:
        raise UsageError(f"unknown question {question!r}; one of {', '.join(QUESTIONS)}")
    if force is not None:
        return _forced_rung(p, question, force)
    in_window = domain.in_window(p.varpi)
    note = _chatter_note(p)
    if not p.ideal and question == "delta_s":
        return Choice(
            "periodic",
            question,
            "damping or restitution present: the rigid and λ rungs are of the idealised "
            "model; the exact periodic orbit includes them" + note,
        )
    if question == "regime":
        return Choice("vertical", question, "the vertical motion does not depend on the slider")
    if question == "transient":
        return Choice("full", question, "only the full model gives the trajectory itself" + note)
    if question == "stability":
        return Choice("periodic", question, "Floquet multipliers need the periodic orbit" + note)
    if not in_window:
        return Choice(
            "periodic",
            question,
            f"ϖ = {p.varpi:.3g} outside the window {WINDOW[0]}–{WINDOW[1]}: the λ fit and "
            "the rigid limit do not apply there" + note,
        )
    chatter = p.ideal and below_chatter_limit(p)
    if question == "mode":
        return _mode_rung(p, question, chatter, note)
    return _delta_s_rung(p, question, tol, chatter)


def evaluate(p: ModelParams, choice: Choice, *, cycles: int = 100) -> Answer:
    """Run the chosen rung.

    Parameters
    ----------
    p : ModelParams
        The design's dimensionless parameters.
    choice : Choice
        The rung and question (:func:`choose_rung`).
    cycles : int
        Actuation cycles of the "full" rung's transient.

    Returns
    -------
    Answer
        The rung's answer (value, mode, status) and its time [s].

    References
    ----------
    .. [1] Shin, Pai, Lin, Hui and Tien, J. Appl. Phys. 96, 7603 (2004),
       doi:10.1063/1.1809773 (λ of the "lambda" rung, eq. 9).
    """
    from betvdesign import dynamics
    from betvdesign.dynamics import rigid

    t0 = time.perf_counter()
    rung, q = choice.rung, choice.question
    if rung == "lambda":
        lam = p.lam
        mode = "push" if lam < 1.0 else "pull"
        msg = f"λ = {lam:.6g} (a fit: {lambda_error_statement()})"
        return Answer(choice, "success", True, msg, lam, mode, _dt(t0))
    if rung == "vertical" or (q == "regime" and rung != "periodic"):
        v = dynamics.vertical_motion(p.varpi, zeta_v=p.zeta_v, restitution=p.restitution)
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
        return _full(p, choice, cycles, t0)
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
    mode = domain.mode_of(po.delta_s) if po.success else None
    return Answer(choice, po.status, po.success, po.message, value, mode, _dt(t0))


def answer(
    p: ModelParams, question: Question, *, tol: float = 1e-6, force: Rung | None = None
) -> Answer:
    """Choose the cheapest adequate rung (or the forced one) and evaluate it.

    Parameters
    ----------
    p : ModelParams
        The design's dimensionless parameters.
    question : Question
        The question (:func:`choose_rung`).
    tol : float
        Relative accuracy [-] asked of "delta_s".
    force : Rung, optional
        A rung name (``--fidelity``).

    Returns
    -------
    Answer
        :func:`evaluate` of :func:`choose_rung`'s choice.
    """
    return evaluate(p, choose_rung(p, question, tol=tol, force=force))


def _full(p: ModelParams, choice: Choice, cycles: int, t0: float) -> Answer:
    """The "full" rung: a transient of ``cycles`` cycles from rest.

    Parameters
    ----------
    p : ModelParams
        The design's dimensionless parameters.
    choice : Choice
        The rung ("full") and the question.
    cycles : int
        Actuation cycles [-] simulated.
    t0 : float
        :func:`time.perf_counter` at the start [s].

    Returns
    -------
    Answer
        For "transient": the slider position s [-] after ``cycles`` cycles. Otherwise
        the Δs [-] of the last cycle, and its mode by :func:`domain.mode_of`, unless no
        contact recurs (``Trajectory.driven`` False): that Δs is then the slider
        coasting on its first contacts, and the answer is the periodic rung's for that
        case, status "not_driven", no mode, the same verdict in the same words
        (:func:`betvdesign.dynamics.periodic.not_driven_message`), as ``betv simulate``
        says "not driven". A coasting transient still answers "transient" (s is exact),
        with no mode and the verdict in its message.
    """
    from betvdesign import dynamics
    from betvdesign.dynamics.periodic import not_driven_message

    tr = dynamics.simulate(p, cycles, log_events=False)
    last = float(tr.delta_s[-1]) if len(tr.delta_s) else math.nan
    coasting = tr.success and tr.driven is False
    mode = domain.mode_of(last) if tr.success and not coasting else None
    status, success, msg = tr.status, tr.success, tr.message
    if coasting:
        verdict = (
            f"{not_driven_message(p, tr.n_cycles)}; the last cycle's Δs = {last:.6g} is the "
            "slider coasting on its first contacts"
        )
        msg = f"{msg}; {verdict}"
        if choice.question != "transient":
            status, success = "not_driven", False
    elif choice.question != "transient":
        msg = f"{msg}; Δs of the last cycle only"
    value = tr.s if choice.question == "transient" else last
    return Answer(choice, status, success, msg, value, mode, _dt(t0))


def _dt(t0: float) -> float:
    return time.perf_counter() - t0
