"""The design rule ``model-adequacy``: is the paper's idealised model enough here?

Built from a :class:`betvdesign.checks.adequacy_data.SetAdequacy` (duck-typed: ``status``,
``adequate``, ``summary()``, ``speed_change``; its long ``message`` is in the JSON and the
report): info when the idealised model's
mode holds with the device's (or plausible default) head damping and restitution and
throughout the likely bands of Q and e (``LIKELY_QUALITY``, ``LIKELY_RESTITUTION``; a flip
only beyond them, within the scanned ranges, is stated in the message); warning when the
mode flips within them, or when
the idealised model has no periodic orbit while the richer one has (e.g. unbounded
tangential growth at α·ϖ² = 1 without damping: the finite damped answer is reported).
"""

from __future__ import annotations

from typing import Any

from betvdesign.checks.adequacy_data import LIKELY_QUALITY, LIKELY_RESTITUTION
from betvdesign.checks.ruledata import RuleResult

SRC_ADEQUACY = (
    "betvdesign.checks.adequacy: exact periodic orbits without and with head damping and "
    "restitution, Q and e scanned (MODEL.md, Beyond the paper's idealisation)"
)

_FIX = {
    "mode-flips": "give the measured Q and e (actuator.quality_factor_*, contact.restitution) "
    "and stay clear of the flip; ",
    "ideal-fails": "give the head's damping (actuator.quality_factor_*) so the check uses the "
    "finite damped orbit, or detune the tangential resonance; ",
    "failed": "`betv simulate FILE --periodic` shows why no orbit was found; ",
}


def adequacy_rule(a: Any) -> RuleResult:
    """The ``model-adequacy`` rule of one set's adequacy result (module docstring)."""
    status = str(a.status)
    ok = bool(a.adequate)
    thr = (
        f"same mode without and with damping/restitution, and for {LIKELY_QUALITY[0]:g} ≤ Q ≤ "
        f"{LIKELY_QUALITY[1]:g}, {LIKELY_RESTITUTION[0]:g} ≤ e ≤ {LIKELY_RESTITUTION[1]:g}"
    )
    change = a.speed_change
    head = _FIX.get(status, "")
    if status == "mode-flips" and getattr(a, "source", None) == "device":
        head = (
            "the file's Q and e are given, but the mode flips within their likely range: "
            "check how sure they are (`betv tolerance FILE --spread "
            "contact.restitution=uniform:0.05`) and keep clear of the flip (a lower ϖ "
            "tolerates a larger e); "
        )
    fix = "" if ok else head + "`betv report FILE` draws mode and speed against Q and e"
    return RuleResult(
        "model-adequacy",
        "info" if ok else "warning",
        ok,
        None if change is None else float(change),
        thr,
        f"{status}: {a.summary()}",
        SRC_ADEQUACY,
        fix=fix,
    )
