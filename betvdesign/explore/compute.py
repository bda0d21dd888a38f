"""What the page computes for a design point, in stages, through ``betv check``'s own path.

Every stage is the check pipeline, :func:`betvdesign.api.run_check`, on
:func:`betvdesign.nondim.device.derive` of the design's spec with the stage's
:class:`~betvdesign.api.CheckOptions` (no advice: the page runs ``betv fix`` itself),
shown through :class:`betvdesign.checks.view.DeviceView` (the ``betv check --json``
shape); nothing here judges a design:

- ``"orbit"``: exact periodic orbits, vertical motion and the mode-margin corners (the
  part that fits in a frame of a slider drag);
- ``"settling"``: plus how well each Δs is determined in float64
  (:mod:`betvdesign.dynamics.determination`: 8 to 14 re-solves per set, as long as the
  rest of the orbit stage together, so not on the interactive path) and the transient
  from rest (settling and crossing): with them the answer the verdict quotes
  (:func:`betvdesign.checks.travel.travel_answer`: the orbit, the crossing of the
  travel from rest, or "undetermined");
- ``"full"``: plus the model-adequacy scan over Q and e: exactly ``betv check``.

:func:`traces` samples the periodic orbit for the page's two time plots in physical
units (head gap and its rate; slider position against time).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np

Stage = Literal["orbit", "settling", "full"]

#: Stages in the order they arrive, with what the page says while each is computed.
STAGES: dict[str, str] = {
    "orbit": "exact orbit, verdict and mode-margin corners",
    "settling": "how well Δs is determined, settling from rest",
    "full": "model-adequacy scan over Q and e",
}
#: Samples of the plotted orbit: per cycle of the phase portrait's period, per cycle of
#: the slider motion after it; cycles of slider motion plotted.
PORTRAIT_SAMPLES = 120
MOTION_SAMPLES = 20
PLOT_CYCLES = 4

__all__ = ["PLOT_CYCLES", "STAGES", "Evaluation", "SetTraces", "evaluate", "traces"]


@dataclass(frozen=True)
class SetTraces:
    """One actuator set's periodic motion in physical units (empty with ``reason``).

    gap_um, gap_rate_mm_s: the head's normal gap [µm] and its rate [mm/s] over one
    period of the orbit; t_ms, x_um: the slider position along the device's x [µm]
    against time [ms] over :data:`PLOT_CYCLES` periods, from the orbit's section.
    note: a warning shown over the plots (:data:`~betvdesign.checks.coupled.
    DECOUPLED_WARNING` where the check's verdict is the coupled head's: the plots are the
    decoupled springs' motion).
    """

    gap_um: list[float] = field(default_factory=list)
    gap_rate_mm_s: list[float] = field(default_factory=list)
    t_ms: list[float] = field(default_factory=list)
    x_um: list[float] = field(default_factory=list)
    reason: str = ""
    note: str = ""


@dataclass
class Evaluation:
    """One stage's answer for the design: ``out`` is the ``betv check --json`` device
    object; ``settling`` per set (:meth:`Settling.as_dict` plus ``f_act_hz``) when that
    stage ran; ``traces`` per set name (stage "orbit"); ``elapsed_s`` [s]."""

    stage: str
    out: dict[str, Any]
    settling: dict[str, dict[str, Any] | None] = field(default_factory=dict)
    traces: dict[str, SetTraces] = field(default_factory=dict)
    elapsed_s: float = 0.0

    @property
    def verdict(self) -> str:
        return str(self.out["verdict"])


def evaluate(
    spec: Any,
    stage: Stage,
    *,
    target_speed_m_s: float | None = None,
    select: tuple[str, ...] = (),
    ignore: tuple[str, ...] = (),
    source_file: str = "",
    with_traces: bool | str = False,
) -> Evaluation:
    """Check ``spec`` (a DeviceSpec) up to ``stage`` (see the module docstring);
    ``select``/``ignore`` as ``betv check --select/--ignore``; ``with_traces``: sample
    the orbit of every set (True) or of the set of that name."""
    from betvdesign.api import CheckOptions, DeviceSource, run_check
    from betvdesign.nondim.device import derive

    t0 = time.perf_counter()
    options = CheckOptions(
        select=select,
        ignore=ignore,
        target_speed=target_speed_m_s,
        adequacy=stage == "full",
        advice=False,
        settle=stage != "orbit",
        determine=stage != "orbit",
    )
    res = run_check(DeviceSource(derive(spec), source_file), options)
    out = res.view.as_json()
    settling: dict[str, dict[str, Any] | None] = {}
    tr: dict[str, SetTraces] = {}
    for sc in res.sets:
        name = sc.derivation.name
        st = sc.settling
        if stage != "orbit":
            settling[name] = (
                {**st.as_dict(), "f_act_hz": sc.derivation.scales.f_act_hz}
                if st is not None and hasattr(st, "as_dict")
                else None
            )
        if with_traces is True or with_traces == name:
            tr[name] = traces(sc.derivation, sc.periodic, model=sc.model)
    return Evaluation(stage, out, settling, tr, time.perf_counter() - t0)


def traces(sd: Any, periodic: Any, *, model: str = "decoupled") -> SetTraces:
    """The periodic orbit of one set (a SetDerivation and its
    :class:`~betvdesign.dynamics.result.PeriodicResult`, None when none was computed)
    sampled for the page (see :class:`SetTraces`).

    The samples are the paper's decoupled model's motion
    (:func:`betvdesign.dynamics.simulate`) from the orbit's state; where the check's
    verdict is the coupled head's (``model`` "coupled", :class:`~betvdesign.checks.
    checker.SetCheck`), they are not its orbit, and ``note`` says so
    (:data:`~betvdesign.checks.coupled.DECOUPLED_WARNING`)."""
    from betvdesign.checks.coupled import DECOUPLED_WARNING
    from betvdesign.dynamics import simulate

    if periodic is None or not periodic.success or periodic.state is None:
        why = "" if periodic is None else periodic.message
        return SetTraces(reason=(why or "no periodic orbit").splitlines()[0])
    p = sd.params
    sc = sd.scales
    k = periodic.period_cycles or 1
    n = k * PLOT_CYCLES
    try:
        run = simulate(p, n, dense=True, state0=np.asarray(periodic.state, dtype=float))
    except Exception as exc:  # shown in the page, never a crash
        return SetTraces(reason=f"{type(exc).__name__}: {exc}")
    if not run.success:
        return SetTraces(reason=str(run.message).splitlines()[0])
    period = 2.0 * math.pi / p.varpi
    first = np.linspace(0.0, k * period, k * PORTRAIT_SAMPLES + 1)
    rest = np.linspace(k * period, n * period, (n - k) * MOTION_SAMPLES + 1)[1:]
    tau = np.concatenate([first, rest])
    states = np.asarray(run.sample(tau), dtype=float)
    one = slice(0, len(first))
    gap_m = sc.u_m * math.sin(sc.theta_rad)  # ξ = gap/(u sinθ), MODEL.md
    rate = gap_m / sc.time_s  # [m/s] per unit ξ'
    x = sd.impact_sign * (states[:, 4] - states[0, 4]) * sc.length_m
    note = ""
    if model == "coupled":
        note = f"{DECOUPLED_WARNING}: these plots are the decoupled springs' motion"
    return SetTraces(
        gap_um=(states[one, 0] * gap_m * 1e6).tolist(),
        gap_rate_mm_s=(states[one, 1] * rate * 1e3).tolist(),
        t_ms=(tau * sc.time_s * 1e3).tolist(),
        x_um=(x * 1e6).tolist(),
        note=note,
    )
