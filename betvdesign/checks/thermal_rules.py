"""Rules on a stroke predicted from the drawing (sets without amplitude or calibration).

- ``thermal.peak-temperature`` (error): the actuator's peak temperature at the drive
  voltage below the layer's onset of plastic deformation (process file:
  ``electrothermal.deformation_onset``, with its source; polysilicon creeps and the hot
  arm bends back, "back-bending", well below its melting point: PolyMUMPs' 1063 K is
  63 % of the melting point, Tuck et al., J. Eng. Mater. Technol. 127 (2005) 90); a
  warning within :data:`TEMPERATURE_MARGIN` of it. A peak at or above the melting point
  fails as melting, with the temperature; a model that reports no convergence fails with
  its own words. A process without the onset is checked against the melting point alone,
  and the check says the onset is NOT sourced (it invents none).
- ``thermal.bandwidth`` (warning): the drive heats at f_heat (2f for AC with zero DC); the
  stroke left there, |H(f_heat)|, at least :data:`BANDWIDTH_GAIN_MIN`. Far above the
  thermal cut-off most of the static stroke is lost and the electrical power goes into
  heat that does not move the head.
- ``thermal.power`` (info): the electrical power, current and resistance per actuator at
  the drive voltage (what a supply must give), with the model that gives them.

References
----------
docs/MODEL.md; :mod:`betvdesign.model.electrothermal`; issue 31.
"""

from __future__ import annotations

from typing import Any

from betvdesign.checks.rule import RuleResult
from betvdesign.nondim.record import SetDerivation
from betvdesign.output.siformat import format_si

__all__ = ["BANDWIDTH_GAIN_MIN", "TEMPERATURE_MARGIN", "thermal_rules"]

#: A peak temperature within this fraction [-] below the limit (in kelvin) warns.
TEMPERATURE_MARGIN = 0.10
#: The stroke fraction |H(f_heat)| [-] below which the drive is called far above the
#: thermal cut-off (half the static stroke lost).
BANDWIDTH_GAIN_MIN = 0.5
SRC = "betvdesign.model.electrothermal (1-D fins, Joule heat, substrate loss; issue 31)"


def thermal_rules(s: SetDerivation, process: Any = None) -> list[RuleResult]:
    """The rules of the module doc for one set (none unless its stroke is predicted).

    Parameters
    ----------
    s : SetDerivation
        The set's derivation.
    process : Process, optional
        The device's process (its list of unsourced values).

    Returns
    -------
    list of RuleResult
        ``thermal.peak-temperature``, ``thermal.bandwidth``, ``thermal.power`` and
        ``thermal.sources``.
    """
    st = s.stroke
    if st is None:
        return []
    return [_peak(s, process), _bandwidth(s), _power(s), _sources(s, process)]


def _sources(s: SetDerivation, process: Any) -> RuleResult:
    """``thermal.sources`` (warning): every process value the stroke used has a source."""
    geo = s.actuator_set.actuator.geometry
    used: list[str] = []
    if process is not None and geo is not None:
        key = process.structural_name(geo.layer)
        prefix = (f"layers.{key}.electrothermal", f"layers.{key}.thickness",
                  f"layers.{key}.density", f"layers.{key}.youngs_modulus")  # fmt: skip
        used = [u for u in process.unsourced if u.startswith(prefix)]
    msg = (
        "the predicted stroke uses process values that are NOT sourced: " + ", ".join(used)
        if used
        else "every process value the predicted stroke uses has a source"
    )
    return RuleResult("thermal.sources", "warning", not used, float(len(used)),
                      "no unsourced process value", msg,
                      "process file (its 'unsourced' list)", s.name,
                      "" if not used else "measure them, or give their source in the process "
                      "file", "")  # fmt: skip


def _onset_basis(s: SetDerivation, process: Any) -> str:
    """Where the onset of plastic deformation comes from, in words."""
    geo = s.actuator_set.actuator.geometry
    if process is None or geo is None:
        return "process file"
    path = f"layers.{process.structural_name(geo.layer)}.electrothermal.deformation_onset"
    if path in process.unsourced:
        return f"process {process.name}: {path}, NOT sourced"
    return f"process {process.name}: {path}, with its source"


def _peak(s: SetDerivation, process: Any = None) -> RuleResult:
    st = s.stroke
    assert st is not None
    melt = st.melting_k
    onset = st.deformation_k
    t = st.t_max_k
    where = f"in the {st.t_max_where} " if st.t_max_where else ""
    at = f"{where}at {st.voltage_v:.3g} V"
    if onset is not None:
        limit = onset
        threshold = (
            f"T_max < {onset:.0f} K, the onset of plastic deformation (back-bending) of the "
            f"film ({_onset_basis(s, process)}); a warning above "
            f"{onset * (1 - TEMPERATURE_MARGIN):.0f} K; melting at {melt:.0f} K"
        )
    else:
        limit = melt
        threshold = (
            f"T_max < {melt:.0f} K, the melting point (process file); a warning above "
            f"{melt * (1 - TEMPERATURE_MARGIN):.0f} K; the onset of plastic deformation of "
            "polysilicon lies lower and is NOT sourced in the process file: not checked"
        )
    warn_at = limit * (1 - TEMPERATURE_MARGIN)
    source = SRC + "; limits: process file"
    cooler = (
        "lower drive.voltage, or lengthen the arms (more of the heat goes to the substrate); "
        "`betv fix FILE` finds the values"
    )
    if st.status == "not_converged":
        return RuleResult("thermal.peak-temperature", "error", False, None, threshold,
                          f"the electrothermal model did not converge: {st.message}",
                          source, s.name, "lower drive.voltage", "K")  # fmt: skip
    severity = "error"
    if st.status == "melts" or t >= melt:
        passed = False
        msg = f"peak temperature {t:.0f} K {at} reaches the melting point {melt:.0f} K: the "
        msg += "actuator burns out"
        fix = cooler
    elif t >= limit:
        passed = False
        msg = (
            f"peak temperature {t:.0f} K {at} is above the onset of plastic deformation "
            f"{limit:.0f} K (melting point {melt:.0f} K): the hot arm creeps and bends back, "
            "and the stroke drifts"
        )
        fix = cooler
    elif t >= warn_at:
        passed, severity = False, "warning"
        what = "onset of plastic deformation" if onset is not None else "melting point"
        msg = f"peak temperature {t:.0f} K {at} is within {TEMPERATURE_MARGIN:.0%} of the "
        msg += f"{what} {limit:.0f} K"
        fix = "lower drive.voltage"
    else:
        passed = True
        msg = f"peak temperature {t:.0f} K {at}"
        fix = ""
    return RuleResult("thermal.peak-temperature", severity, passed, t, threshold, msg.strip(),
                      source, s.name, fix, "K")  # fmt: skip


def _bandwidth(s: SetDerivation) -> RuleResult:
    st = s.stroke
    assert st is not None
    g = st.gain
    passed = g >= BANDWIDTH_GAIN_MIN
    msg = (
        f"the drive heats at {format_si(st.f_heat_hz, 'Hz')}, "
        f"{st.f_heat_hz / st.f_cutoff_hz:.3g}× the thermal cut-off "
        f"{format_si(st.f_cutoff_hz, 'Hz')} (first thermal mode "
        f"{format_si(st.f_thermal_hz, 'Hz')}): {g:.1%} of the static stroke is left"
    )
    fix = (
        ""
        if passed
        else "a lower drive frequency with a softer or heavier head (ϖ kept), or shorter, "
        "narrower arms (a higher cut-off); far above the cut-off the power heats the "
        "actuator for little motion"
    )
    return RuleResult("thermal.bandwidth", "warning", passed, g,
                      f"|H(f_heat)| ≥ {BANDWIDTH_GAIN_MIN:g}", msg, SRC, s.name, fix)  # fmt: skip


def _power(s: SetDerivation) -> RuleResult:
    st = s.stroke
    assert st is not None
    msg = (
        f"{format_si(st.power_w, 'W')} per actuator at {st.voltage_v:.3g} V "
        f"({format_si(st.current_a, 'A')}, {format_si(st.resistance_ohm, 'Ω')} hot; "
        "the AC crest's, its mean is half)"
    )
    return RuleResult("thermal.power", "info", True, st.power_w, "reported", msg, SRC,
                      s.name, "", "W")  # fmt: skip
