"""Rules on the head's springs from a drawn actuator (sets with ``actuator.geometry``).

- ``actuator.geometry``: which springs the check used. When the file gives the head's
  resonances (or α) too, they are used and compared with the drawn actuator's (warning
  when more than :data:`GEOMETRY_RTOL` apart); otherwise the drawn actuator's are used
  (information, with the closed form's stated error against FE).
- ``actuator.coupling``: the frame's coupling ρ = K_nt/√(K_nn·K_tt) within
  ±:data:`betvdesign.model.frame.RHO_MAX`; beyond it the model's decoupled springs
  misdescribe the head (a model-adequacy finding, MODEL.md).
- ``actuator.arm-mass``: the arms' first-mode mass at most
  :data:`betvdesign.model.frame.ARM_MASS_SHARE_MAX` of the head's; the model's m is the
  head alone, so the message states the effective mass m + m_arm and the f_v it gives.

Severity: warning where the drawing's springs are used; information where the file's
resonances and α are (the comparison then says what the drawing would give, the verdict
does not rest on it).
"""

from __future__ import annotations

import math

from betvdesign.checks.rule import RuleResult
from betvdesign.model.frame import ARM_MASS_SHARE_MAX, CLOSED_FORM_RTOL, RHO_MAX
from betvdesign.nondim.record import SetDerivation
from betvdesign.output.siformat import format_si

__all__ = ["GEOMETRY_RTOL", "actuator_rules"]

#: The file's resonances and the drawn actuator's agree when within this (relative).
GEOMETRY_RTOL = 0.1
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
    out = [_geometry(s), _coupling(s), _arm_mass(s)]
    if set(sp.used.values()) == {"file"}:
        note = "the file's resonances are used, not the drawing's: "
        out = [
            RuleResult(r.id, "info", r.passed, r.value, r.threshold,
                       r.message if r.id == "actuator.geometry" else note + r.message,
                       r.source, r.set_name, r.fix, r.unit)
            for r in out
        ]  # fmt: skip
    return out


def _ratio_text(a: float, b: float) -> str:
    r = a / b
    return f"{r:.3g}× the file's" if r >= 1 else f"{1 / r:.3g}× below the file's"


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
            "k_v, k_h from the drawn actuator",
            f"the head's springs are the drawn actuator's ({geo_txt}; k_v = K_nn = "
            f"{format_si(sp.k_nn, 'N/m')}, k_h = K_tt = {format_si(sp.k_tt, 'N/m')}): closed "
            f"form, within {CLOSED_FORM_RTOL:.0%} of plane-stress FE for arms of L/w ≥ 10",
            SRC,
            set_name=s.name,
            unit="Hz",
        )
    parts, bad = [], []
    if sp.file_f_v_hz is not None:
        gap = abs(sp.f_v_hz / sp.file_f_v_hz - 1)
        parts.append(
            f"f_v {format_si(sp.f_v_hz, 'Hz')} ({_ratio_text(sp.f_v_hz, sp.file_f_v_hz)} "
            f"{format_si(sp.file_f_v_hz, 'Hz')})"
        )
        if gap > GEOMETRY_RTOL:
            bad.append("f_v")
    if sp.file_alpha is not None:
        gap = abs(sp.alpha / sp.file_alpha - 1)
        parts.append(f"α {sp.alpha:.3g} (the file's {sp.file_alpha:.3g})")
        if gap > GEOMETRY_RTOL:
            bad.append("α")
    which = " and ".join(
        "the file's " + ("f_v" if k == "k_v" else "α")
        if v == "file"
        else "the drawing's " + ("k_v" if k == "k_v" else "k_h")
        for k, v in used.items()
    )
    ok = not bad
    msg = f"the drawn actuator gives {'; '.join(parts)}; the check uses {which}"
    if not ok:
        msg += f": {', '.join(bad)} disagree by more than {GEOMETRY_RTOL:.0%}"
    return RuleResult(
        "actuator.geometry",
        "warning",
        ok,
        sp.f_v_hz,
        f"the drawn actuator's f_v and α within {GEOMETRY_RTOL:.0%} of the file's",
        msg,
        SRC,
        set_name=s.name,
        fix=""
        if ok
        else "measure the head's resonances again, or correct the drawing; remove the file's "
        "resonances (or α) to use the drawing's springs",
        unit="Hz",
    )


def _coupling(s: SetDerivation) -> RuleResult:
    sp = s.springs
    assert sp is not None
    ok = abs(sp.rho) <= RHO_MAX
    msg = f"ρ = K_nt/√(K_nn·K_tt) = {sp.rho:.3g} (K_nt = {format_si(sp.k_nt, 'N/m')}): " + (
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
    m_eff = sp.m_head_kg + sp.m_arm_kg
    f_v = s.scales.f_act_hz / s.params.varpi
    msg = (
        f"the arms' first-mode mass {format_si(sp.m_arm_kg * 1e3, 'g')} is {share:.0%} of the "
        f"head's {format_si(sp.m_head_kg * 1e3, 'g')}"
    )
    if not ok:
        msg += (
            f": not small; the model takes the head alone (m), with the effective mass "
            f"m + m_arm = {format_si(m_eff * 1e3, 'g')} f_v would be "
            f"{format_si(f_v / math.sqrt(1 + share), 'Hz')} instead of {format_si(f_v, 'Hz')}"
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
