"""The model-adequacy study's coupled rung: the paper's decoupled springs against the drawn head.

docs/MODEL.md, "Coupled head (K_nt ≠ 0)". A drawn head (``SetDerivation.springs``) has a
coupling ρ = C_nt/√(C_nn·C_tt) that the paper's model leaves out. For such a set this rung
solves the periodic orbit of

1. the decoupled model (the paper's, ρ = 0): the exact solver
   (:func:`betvdesign.dynamics.periodic_orbit`);
2. the coupled model with the drawn ρ and χ = √α·tanθ: the exact compiled solver's
   stable orbit (:func:`betvdesign.dynamics.coupled.coupled_orbit`: Newton shooting on the
   exact section map started from the decoupled orbit, else from the transient from rest
   once its last sections repeat, with that period). Where it finds no stable orbit, the
   check's coupled crossing of the travel when given, else the mean Δs of cycles
   :data:`MEAN_CYCLES` to 2·:data:`MEAN_CYCLES` from rest with its half-spread as the
   error (the sign then decides the mode only when it exceeds the spread).

Both for the paper's idealised terms (no damping, plastic impacts: the coupled model
has no others) and the set's ϖ, α, β, κ as used (the file's measured resonances where
given, the drawn ones otherwise).

Statuses: "coupled-agrees" (same mode, speeds within :data:`SPEED_RTOL`),
"coupled-differs" (the decoupled springs give another mode, or a speed off by more than
:data:`SPEED_RTOL`), "coupled-undetermined" (the coupled model gives no mode: no orbit and
a mean whose sign its spread does not decide), "failed" (no decoupled answer).

``uses`` says which answer a verdict should take: "coupled" when the file gives no
measured resonances (the set's k_v and α come from the drawing: the drawn head is the
only model of it), "decoupled" when the file's measured resonances win (the coupled
answer is then a finding). In a check (:func:`betvdesign.checks.checker.check_derivation`)
the rule ``coupled-head`` (:func:`coupled_rule`) is on by default for the sets whose
verdict is the coupled answer (:func:`uses_coupled`: their rules ``mode`` and ``speed``
then quote the coupled orbit and say so), and for every drawn set with
``CheckOptions(coupled=True)`` (a finding where the file's resonances win); cost per set:
benchmarks/README.md "Coupled head".
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Literal

import numpy as np

from betvdesign.checks.adequacy import SPEED_RTOL
from betvdesign.checks.rule import RuleResult
from betvdesign.dynamics.result import PeriodicResult
from betvdesign.dynamics.settling import Settling
from betvdesign.errors import ParameterError
from betvdesign.model.domain import mode_of
from betvdesign.model.params import HeadCoupling, ModelParams
from betvdesign.nondim.record import SetDerivation
from betvdesign.output.siformat import format_si

CoupledStatus = Literal["coupled-agrees", "coupled-differs", "coupled-undetermined", "failed"]
#: cycles from rest before, and over which, the coupled Δs is averaged without an orbit
MEAN_CYCLES = 100
#: Newton's accepted residual on the exact coupled map: Δs to about 1e-8 relative, far
#: below the 10 % that is decided
NEWTON_TOL = 1e-8
#: a transient whose Δs spread is below this fraction of its mean has settled
SETTLED = 1e-6


@dataclass(frozen=True)
class Answer:
    """One model's answer at the set.

    Parameters
    ----------
    status : str
        The solver's status ("success", "mean" for the coupled transient mean, or why not).
    delta_s : float or None
        Δs per cycle [-] (units of u·cosθ).
    error : float
        Its error [-]: 0 on an orbit, the half-spread of the cycles averaged otherwise.
    mode : str or None
        :func:`betvdesign.model.domain.mode_of` (with ``error``).
    speed_m_s : float or None
        Δs·u·cosθ·f_act [m/s], signed along the impacts.
    state : numpy.ndarray or None
        (ξ, ξ', ζ, ζ', s, s') [-] at τ = 0 on the orbit (None without one).
    period : int
        The orbit's period [cycles].
    """

    status: str
    delta_s: float | None
    error: float
    mode: str | None
    speed_m_s: float | None
    state: np.ndarray | None = None
    period: int = 1

    @property
    def text(self) -> str:
        """``push at 2.3 mm/s`` or why there is no mode."""
        if self.mode in ("push", "pull"):
            how = ""
            if self.status == "mean" and self.error <= SETTLED * abs(self.delta_s or 0.0):
                how = " (a transient settled to it; Newton did not converge)"
            elif self.status == "mean":
                how = f" (mean of cycles ± {self.error:.2g} in Δs: no periodic orbit found)"
            elif self.status == "crossing":
                how = " (mean over the travel from rest: no stable orbit)"
            return f"{self.mode} at {format_si(abs(self.speed_m_s or 0.0), 'm/s')}{how}"
        if self.mode is not None:
            return str(self.mode)
        return f"no answer ({self.status})"


@dataclass(frozen=True)
class CoupledRung:
    """The coupled rung of one actuator set (module docstring).

    Parameters
    ----------
    name : str
        The actuator set.
    status : CoupledStatus
        The verdict.
    rho, chi : float
        The drawn coupling ρ and χ = √α·tanθ [-].
    stiffness : float
        a = 1/(1 − ρ²) = K_nn/k_v [-]: how much stiffer the clamped directions are.
    decoupled, coupled : Answer
        The two answers.
    uses : {"coupled", "decoupled"}
        Which answer a verdict takes (module docstring).
    message : str
        The verdict in words.
    """

    name: str
    status: CoupledStatus
    rho: float
    chi: float
    stiffness: float
    decoupled: Answer
    coupled: Answer
    uses: Literal["coupled", "decoupled"]
    message: str

    @property
    def speed_change(self) -> float | None:
        """Relative change of the signed speed from the decoupled to the coupled head.

        (v_coupled − v_decoupled)/v_decoupled [-] (below −1 when they move opposite ways,
        as :func:`betvdesign.checks.adequacy.speed_change`); None without both speeds.
        """
        a, b = self.decoupled.speed_m_s, self.coupled.speed_m_s
        if a is None or b is None or a == 0.0:
            return None
        return (b - a) / a

    @property
    def answer(self) -> Answer:
        """The answer a verdict takes (``uses``)."""
        return self.coupled if self.uses == "coupled" else self.decoupled


def coupling_of(sd: SetDerivation) -> HeadCoupling | None:
    """The drawn head's coupling (ρ, χ = √α·tanθ) of a set; None without a drawing.

    Parameters
    ----------
    sd : SetDerivation
        The derived set.

    Returns
    -------
    HeadCoupling or None
        From ``sd.springs.rho``, the set's α and its impact angle.
    """
    if sd.springs is None:
        return None
    return HeadCoupling.from_angle(float(sd.springs.rho), sd.params.alpha, sd.scales.theta_rad)


def _speed(sd: SetDerivation, ds: float | None) -> float | None:
    return None if ds is None else ds * sd.scales.length_m * sd.scales.f_act_hz


def uses_coupled(sd: SetDerivation) -> bool:
    """Whether a verdict takes the coupled head's answer for this set.

    Parameters
    ----------
    sd : SetDerivation
        The derived set.

    Returns
    -------
    bool
        True for a drawn head whose k_v comes from the drawing (the file gives no measured
        resonances) in the idealised model (the coupled model has no damping or
        restitution): the drawn head is then the only model of the device.
    """
    return drawn_only(sd) and sd.params.ideal


def drawn_only(sd: SetDerivation) -> bool:
    """Whether a set's head is drawn and its k_v comes from the drawing.

    Parameters
    ----------
    sd : SetDerivation
        The derived set.

    Returns
    -------
    bool
        True for a drawn head whose file gives no measured resonances (a property of the
        file: varying its fields does not change it).
    """
    return sd.springs is not None and sd.springs.used.get("k_v") == "geometry"


def coupled_rung(
    sd: SetDerivation, *, orbit: PeriodicResult | None = None, crossing: Settling | None = None
) -> CoupledRung | None:
    """The coupled rung of one set (module docstring); None when the set has no drawing.

    Parameters
    ----------
    sd : SetDerivation
        The derived set.
    orbit : PeriodicResult, optional
        The coupled orbit when already solved (the check's verdict:
        :func:`betvdesign.dynamics.coupled.coupled_orbit` of the idealised set).
    crossing : Settling, optional
        Without a stable orbit, the coupled transient across the travel when already run
        (the check's, :func:`betvdesign.dynamics.coupled.coupled_crossing`): its mean Δs
        is the coupled answer instead of the mean of cycles 100–200.

    Returns
    -------
    CoupledRung or None
        Both answers, the verdict and which answer to use.

    Raises
    ------
    ParameterError
        When ``sd`` is not a SetDerivation.
    """
    from betvdesign.dynamics import periodic_orbit
    from betvdesign.dynamics.coupled import coupled_orbit, simulate_coupled

    if not isinstance(sd, SetDerivation):
        raise ParameterError(f"expected a SetDerivation, got {type(sd).__name__}")
    cpl = coupling_of(sd)
    if cpl is None:
        return None
    p: ModelParams = replace(sd.params, zeta_v=0.0, zeta_h=0.0, restitution=0.0)
    ex = periodic_orbit(p)
    ok = ex.status == "success"
    dec = Answer(
        ex.status, ex.delta_s, 0.0, ex.mode if ok else None, _speed(sd, ex.delta_s), ex.state,
        ex.period_cycles or 1,
    )  # fmt: skip
    orb = orbit if orbit is not None else coupled_orbit(p, cpl, decoupled=ex, tol=NEWTON_TOL)
    if orb.status == "success":
        cou = Answer(
            "success", orb.delta_s, 0.0, orb.mode, _speed(sd, orb.delta_s), orb.state,
            int(orb.period_cycles or 1),
        )  # fmt: skip
    elif crossing is not None and crossing.crossing_delta_s is not None:  # the check's
        c = float(crossing.crossing_delta_s)
        cou = Answer("crossing", c, 0.0, mode_of(c), _speed(sd, c))
    else:  # no stable orbit: the mean of the transient's last cycles
        run = simulate_coupled(p, cpl, 2 * MEAN_CYCLES, log_events=False)
        tail = run.delta_s[MEAN_CYCLES:]
        if run.status != "success" or tail.size == 0:
            cou = Answer(f"failed: {run.message}", None, math.inf, None, None)
        else:
            mean = float(np.mean(tail))
            err = 0.5 * float(np.max(tail) - np.min(tail))
            cou = Answer("mean", mean, err, mode_of(mean, error=err), _speed(sd, mean))
    rung = CoupledRung(
        name=sd.name,
        status=_status(dec, cou),
        rho=cpl.rho,
        chi=cpl.chi,
        stiffness=cpl.a,
        decoupled=dec,
        coupled=cou,
        uses="coupled" if uses_coupled(sd) else "decoupled",
        message="",
    )
    return replace(rung, message=_message(rung))


def _status(dec: Answer, cou: Answer) -> CoupledStatus:
    if dec.mode is None:
        return "failed"
    if cou.mode not in ("push", "pull", "stalled", "none"):
        return "coupled-undetermined"
    if cou.mode != dec.mode:
        return "coupled-differs"
    a, b = dec.speed_m_s, cou.speed_m_s
    if a and b is not None and abs(b - a) > SPEED_RTOL * abs(a):
        return "coupled-differs"
    return "coupled-agrees"


def _message(r: CoupledRung) -> str:
    change = r.speed_change
    pct = f" ({change:+.0%})" if change is not None and change > -1.0 else ""
    head = (
        f"decoupled springs (the paper's): {r.decoupled.text}; drawn head coupled "
        f"(ρ = {r.rho:.4g}, χ = {r.chi:.4g}, clamped stiffness ×{r.stiffness:.3g}): "
        f"{r.coupled.text}{pct}"
    )
    verdict = {
        "coupled-agrees": "the decoupled springs are adequate here",
        "coupled-differs": (
            f"the decoupled springs give another mode or a speed off by more than {SPEED_RTOL:.0%}"
        ),
        "coupled-undetermined": "the coupled model gives no mode (no periodic orbit)",
        "failed": "the decoupled model gives no periodic orbit",
    }[r.status]
    use = (
        "the verdict uses the coupled answer (the file gives no measured resonances)"
        if r.uses == "coupled"
        else "the file's measured resonances win; the coupled answer is a finding"
    )
    return f"{head}; {verdict}; {use}"


#: What a face says where it computes a set's answers with the paper's decoupled springs
#: although ``betv check``'s verdict of that set is the coupled head's
#: (:func:`betvdesign.checks.checker.coupled_head`): the explorer's orbit plots, ``betv
#: tolerance``'s samples.
DECOUPLED_WARNING = "decoupled model: betv check uses the coupled head for this set"

#: Where the rule ``coupled-head`` comes from.
SRC_COUPLED = "MODEL.md, Coupled head (K_nt ≠ 0) (betvdesign.dynamics.coupled)"


def coupled_rule(r: CoupledRung) -> RuleResult:
    """The rule ``coupled-head`` of one set's coupled rung (opt-in: ``CheckOptions.coupled``).

    Parameters
    ----------
    r : CoupledRung
        The set's rung (:func:`coupled_rung`).

    Returns
    -------
    RuleResult
        Info when the decoupled springs give the coupled head's mode and speed within
        :data:`SPEED_RTOL`; warning otherwise (another mode, a speed off by more, or no
        coupled mode). Value: (v_coupled − v_decoupled)/v_decoupled [-], None without both
        speeds.
    """
    ok = r.status == "coupled-agrees"
    change = r.speed_change
    fix = (
        ""
        if ok
        else "the drawn head is one elastic body, not two independent springs: measure the "
        "device's speed, or align the actuator's principal axes with the slider; "
        "`betvdesign.checks.coupled.coupled_rung` gives both answers"
    )
    return RuleResult(
        "coupled-head",
        "info" if ok else "warning",
        ok,
        None if change is None else float(change),
        f"the decoupled springs give the drawn (coupled) head's mode and its speed within "
        f"{SPEED_RTOL:.0%}",
        f"{r.status}: {r.message}",
        SRC_COUPLED,
        set_name=r.name,
        fix=fix,
    )


def coupled_rules(
    sets: list[SetDerivation],
    *,
    orbits: dict[str, PeriodicResult] | None = None,
    crossings: dict[str, Settling] | None = None,
) -> list[RuleResult]:
    """The rule ``coupled-head`` of every drawn set (sets with one model solved once).

    Parameters
    ----------
    sets : list of SetDerivation
        The device's sets; those without a drawing give no rule.
    orbits, crossings : dict, optional
        Set name -> its coupled orbit, and its coupled crossing of the travel, when already
        solved (the check's verdict).

    Returns
    -------
    list of RuleResult
        One per drawn set, in the device's order.
    """
    orbits, crossings = orbits or {}, crossings or {}
    done: dict[tuple, CoupledRung] = {}
    out = []
    for sd in sets:
        if sd.springs is None:
            continue
        key = (sd.params, sd.springs.rho, sd.scales, sd.springs.used.get("k_v"))
        if key not in done:
            done[key] = coupled_rung(sd, orbit=orbits.get(sd.name), crossing=crossings.get(sd.name))
        out.append(coupled_rule(replace(done[key], name=sd.name)))
    return out
