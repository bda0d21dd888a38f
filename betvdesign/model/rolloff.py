"""Thermal roll-off of an electrothermal actuator's stroke (unit-free, float or arrays).

MODEL.md, "Thermal roll-off of the actuator": the oscillating part of the stroke
follows a first-order low-pass, u(V, f) = u_cal(V)·H(f)/H(f_cal) with
H(f) = 1/sqrt(1 + (f/f_c)²), f the actuation frequency (after AC doubling), f_c the
thermal cut-off (= 1/(2π τ_th)) and f_cal the actuation frequency of the calibration.

The one implementation of H and of the amplitude ratio; :mod:`betvdesign.nondim.device` calls
it on magnitudes in hertz (it strips the units), figures on the scales it produced.
``hypot`` keeps H exact to round-off for any f/f_c (no overflow of (f/f_c)²).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

#: Largest f_cal/f_c accepted [-]: a calibration taken where the first-order low-pass has
#: already cut the stroke by ~100× (H < 0.01) would be scaled back up by that factor and
#: more at lower actuation frequencies; far beyond what a first-order law can be trusted
#: for (and a calibration measured there is mostly noise). The spec refuses it.
MAX_CALIBRATION_RATIO = 100.0


def calibration_problem(f_cal_hz: float, cutoff_hz: float) -> str | None:
    """Why a calibration frequency f_cal [Hz] cannot be used with the cut-off f_c [Hz]
    (beyond :data:`MAX_CALIBRATION_RATIO`), None when it can."""
    if f_cal_hz <= MAX_CALIBRATION_RATIO * cutoff_hz:
        return None
    return (
        f"{f_cal_hz:g} Hz is {f_cal_hz / cutoff_hz:.3g}× the thermal cut-off {cutoff_hz:.4g} "
        f"Hz: the stroke measured there is rolled off below 1/{MAX_CALIBRATION_RATIO:g} and "
        "the first-order law cannot scale it back; give the actuation frequency at which the "
        f"amplitude was measured (≤ {MAX_CALIBRATION_RATIO:g} f_c)"
    )


def cutoff_from_time_constant(tau_s: Any) -> Any:
    """Cut-off frequency f_c = 1/(2π τ_th) [Hz] of a first-order thermal time constant
    τ_th [s] (float or array)."""
    return 1.0 / (2.0 * math.pi * tau_s)


def gain(f_hz: Any, cutoff_hz: Any) -> Any:
    """H(f) = 1/sqrt(1 + (f/f_c)²) [-] of the first-order low-pass (float or array);
    ``cutoff_hz`` = inf gives exactly 1."""
    x = f_hz / cutoff_hz
    if np.ndim(x) == 0:
        return 1.0 / math.hypot(1.0, float(x))
    return 1.0 / np.hypot(1.0, x)


def ratio(f_hz: Any, ref_hz: Any, cutoff_hz: Any) -> Any:
    """H(f)/H(f_ref) [-]: the stroke at actuation frequency ``f_hz`` relative to the
    stroke at ``ref_hz`` (e.g. the calibration frequency); 1 exactly when f = f_ref or
    the cut-off is infinite."""
    return gain(f_hz, cutoff_hz) / gain(ref_hz, cutoff_hz)
