"""Rules on the head's springs from a drawn actuator (sets with ``actuator.geometry``).

- ``actuator.geometry``: which springs the check used. When the file gives the head's
  resonances (or α) too, the measured values win and the check states how far the
  drawing's prediction is from them: a note within :data:`PREDICTION_FACTOR` ×, a
  warning beyond it with the likely cause; otherwise the drawn actuator's f_v and α are
  used (information, with the closed form's stated error against FE).
- ``actuator.coupling``: the head's coupling ρ = C_nt/√(C_nn·C_tt) within
  ±:data:`betvdesign.model.frame.RHO_MAX`; beyond it the model's decoupled springs
  misdescribe the head (a model-adequacy finding, MODEL.md).
- ``actuator.arm-mass``: the arms' first-mode mass at most
  :data:`betvdesign.model.frame.ARM_MASS_SHARE_MAX` of the head's; the model's m is the
  head alone in the impacts' momentum, so the message states the effective mass.

Severity of the last two: warning where the drawing's springs are used; information where
the file's resonances and α are (the verdict does not rest on them).
"""

from __future__ import annotations

from betvdesign.checks.rule import RuleResult
from betvdesign.model.frame import ARM_MASS_SHARE_MAX, CLOSED_FORM_RTOL, MODAL_RTOL, RHO_MAX
from betvdesign.nondim.record import HeadSprings, SetDerivation
from betvdesign.output.siformat import format_si

__all__ = ["PREDICTION_FACTOR", "actuator_rules"]

#: The drawn prediction within this factor of the file's measured value: a note; beyond
#: it, a warning with the likely cause (issue 30, item 5).
PREDICTION_FACTOR = 2.0
SRC = "MODEL.md, From the drawn actuator to the head's springs (betvdesign.model.frame)"


def actuator_rules(s: SetDerivation) -> list[RuleResult]:
    """The three rules of the module doc for one set (none without a drawn actuator).

    Parameters
    ----------
    s : SetDerivation
        The set's derivation.

    Returns
    -------
    list of RuleResult
        The rules' results.
    """
    sp = s.springs
    if sp is None:
        return []
    out = [_coupling(s), _arm_mass(s)]
    if set(sp.used.values()) == {"file"}:
        note = "the file's resonances are used, not the drawing's: "
        out = [
            RuleResult(r.id, "info", r.passed, r.value, r.threshold, note + r.message,
                       r.source, r.set_name, r.fix, r.unit)
            for r in out
        ]  # fmt: skip
    return [_geometry(s), *out]


def _times(a: float, b: float) -> str:
    r = a / b
    return f"{r:.3g}×" if r >= 1 else f"1/{1 / r:.3g}"


def _far(a: float, b: float) -> float:
    """How many times apart a and b are (≥ 1)."""
    return max(a / b, b / a)


def _cause(sp: HeadSprings, which: str) -> str:
    """The likely cause of a drawn prediction far from the file's measured value."""
    if which == "α":
        return f"α: the drawn head is one mode along its stroke (ρ {sp.rho:.2g}, α ≈ 1)"
    if sp.file_f_v_hz is not None and sp.f_v_hz > sp.file_f_v_hz:
        return (
            "another mode measured (the drawn first in-plane mode is "
            f"{format_si(sp.f_1_hz, 'Hz')}), a heavier head, or not the drawn device"
        )
    return "the drawing stiffer or lighter than the device (widths, lengths, E, t)"


def _geometry(s: SetDerivation) -> RuleResult:
    sp = s.springs
    assert sp is not None
    geo_txt = f"f_v = {format_si(sp.f_v_hz, 'Hz')}, α = {sp.alpha:.3g}"
    used = sp.used
    if used["k_v"] == "geometry" and used["alpha"] == "geometry":
        return RuleResult(
            "actuator.geometry",
            "info",
            True,
            sp.f_v_hz,
            "f_v, α from the drawn actuator",
            f"the head's springs are the drawn actuator's ({geo_txt}; k_v,geom = "
            f"{format_si(sp.k_v, 'N/m')}, k_h,geom = {format_si(sp.k_h, 'N/m')}, each with "
            f"the other direction free and the slider in series; effective masses "
            f"{format_si(sp.m_v_kg * 1e3, 'g')}, {format_si(sp.m_h_kg * 1e3, 'g')} (Rayleigh); "
            f"the actuator's first in-plane mode {format_si(sp.f_1_hz, 'Hz')}): frame closed "
            f"form within {CLOSED_FORM_RTOL:.0%} of plane-stress FE for arms of L/w ≥ 10, "
            f"its first mode within {MODAL_RTOL:.0%} of the modal FE",
            SRC,
            set_name=s.name,
            unit="Hz",
        )
    parts, far = [], []
    if sp.file_f_v_hz is not None:
        parts.append(
            f"f_v {format_si(sp.f_v_hz, 'Hz')} vs the file's {format_si(sp.file_f_v_hz, 'Hz')} "
            f"({_times(sp.f_v_hz, sp.file_f_v_hz)})"
        )
        if _far(sp.f_v_hz, sp.file_f_v_hz) > PREDICTION_FACTOR:
            far.append("f_v")
    if sp.file_alpha is not None:
        parts.append(f"α {sp.alpha:.3g} vs {sp.file_alpha:.3g}")
        if _far(sp.alpha, sp.file_alpha) > PREDICTION_FACTOR:
            far.append("α")
    which = (
        "the file's"
        if set(used.values()) == {"file"}
        else ", ".join(
            ("the file's " if v == "file" else "the drawing's ") + ("f_v" if k == "k_v" else "α")
            for k, v in used.items()
        )
    )
    ok = not far
    msg = f"drawn {', '.join(parts)}; {which} used"
    if ok:
        msg += f" (within {PREDICTION_FACTOR:g}×: a note)"
    else:
        msg += f". Likely cause: {_cause(sp, far[0])}"
    return RuleResult(
        "actuator.geometry",
        "info" if ok else "warning",
        ok,
        sp.f_v_hz,
        f"the drawn actuator's f_v and α within {PREDICTION_FACTOR:g}× of the file's "
        "(measured values win)",
        msg,
        SRC,
        set_name=s.name,
        fix="" if ok else "measure the resonances again or correct the drawing",
        unit="Hz",
    )


def _coupling(s: SetDerivation) -> RuleResult:
    sp = s.springs
    assert sp is not None
    ok = abs(sp.rho) <= RHO_MAX
    msg = f"ρ = C_nt/√(C_nn·C_tt) = {sp.rho:.3g} (the head's compliance, slider in series): " + (
        "the normal and tangential springs are nearly independent, as the model takes them"
        if ok
        else "the head's normal and tangential motions are coupled; the model's decoupled "
        "springs misdescribe the head (a model-adequacy finding)"
    )
    return RuleResult(
        "actuator.coupling",
        "warning",
        ok,
        sp.rho,
        f"|ρ| <= {RHO_MAX:g}",
        msg,
        SRC,
        set_name=s.name,
        fix=""
        if ok
        else "align the actuator's principal axes with the slider (impact angle toward 0° or "
        "90°) or make the arms' axial and bending stiffness comparable; the paper's model "
        "has no coupling term",
    )


def _arm_mass(s: SetDerivation) -> RuleResult:
    sp = s.springs
    assert sp is not None
    share = sp.m_arm_kg / sp.m_head_kg
    ok = share <= ARM_MASS_SHARE_MAX
    msg = (
        f"the arms' first-mode mass {format_si(sp.m_arm_kg * 1e3, 'g')} is {share:.0%} of the "
        f"head's {format_si(sp.m_head_kg * 1e3, 'g')}"
    )
    if not ok:
        msg += (
            ": not small; the drawn resonances include it (Rayleigh effective masses "
            f"m_v = {format_si(sp.m_v_kg * 1e3, 'g')}, m_h = {format_si(sp.m_h_kg * 1e3, 'g')}), "
            "but the model's impacts carry the head's m alone"
        )
    return RuleResult(
        "actuator.arm-mass",
        "warning",
        ok,
        share,
        f"m_arm/m <= {ARM_MASS_SHARE_MAX:g}",
        msg,
        SRC + " (Rayleigh estimate along the frame's softest direction)",
        set_name=s.name,
        fix="" if ok else "a heavier head or lighter (narrower) arms",
    )
