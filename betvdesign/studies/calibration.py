"""Calibration: fit the amplitude u (or α) of one actuator set to measurements.

Data (CSV, header cells ``name [unit]``):

* speed against drive voltage: ``voltage [V], speed [um/s]`` and optionally
  ``sigma [um/s]`` (1σ of each speed);
* displacement against time (one drive voltage, slider starting at rest):
  ``time [ms], displacement [um]`` and optionally ``sigma [um]``.

Model (docs/MODEL.md, "Displacement per cycle"): the dimensionless motion does
not depend on u, so

* mean speed      v(V) = Δs · u(V) · cosθ · f_act,
* displacement    x(t) = s(t / t_s) · u · cosθ   (transient from rest),

with Δs from the exact periodic orbit and s(τ) from the exact transient.

Direction. A lab records how fast and how far the slider moved, and which way. By
default (``signed=False``) speeds and displacements are *magnitudes* (>= 0) of motion
in the set's direction of travel: ``direction`` ("+x"/"-x"), by default the direction
the set is designed to move the slider (its intended mode and impact direction). With
``signed=True`` they are signed along the set's impact direction, the way the model's
s counts (pull mode gives negative values). Either way the amplitude cannot change the
sign of the motion: when the model (Δs, or s(t) at the last data time) moves the
slider the other way, :class:`CalibrationMismatch` says so instead of fitting a
vanishing gain.

Fitted parameters (``scipy.optimize.least_squares``):

* ``law="per-voltage"``: one u per distinct voltage (a ``measured`` calibration);
* ``law="linear"`` / ``"quadratic"``: the gain g of u = g·V or u = g·V²;
* ``law="fixed"`` with ``fit_alpha=True``: u from the device, fit α only;
* ``fit_alpha=True`` adds α (k_v/k_h, the phenomenological compliance) to the fit
  (each residual evaluation then re-solves the periodic orbit).

Uncertainty: covariance (JᵀJ)⁻¹ from the Jacobian at the optimum, scaled by the
residual variance SSR/(n − p) unless σ is given; with no σ and no spare data
points (n = p) the uncertainty is unknown and reported as None, not invented.

Goodness of fit: R² = 1 − SSR/SST (SST about the mean of the data; None when the
data do not vary), χ²/dof with σ given, and the residual rms; ``warnings`` lists
what a designer should not overlook (a poor fit, a parameter at its bound 0, an
unknown uncertainty), and ``status`` is "at_bound" when a fitted value sits on 0.
"""

from __future__ import annotations

import dataclasses
import math
import os
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from betvdesign.errors import BetvError, UsageError
from betvdesign.studies.measurements import Kind, Measurements

#: R² below which a fit is flagged as poor.
POOR_FIT_R2 = 0.9
#: Condition number of the fit's Jacobian above which its parameters are not told apart
#: by the data (no uncertainty is quoted; the warning says which cannot be separated).
MAX_CONDITION = 1e8


class CalibrationMismatch(BetvError):
    """Data and model disagree on the direction of motion: no amplitude can fit them."""


Law = Literal["per-voltage", "linear", "quadratic", "fixed"]


@dataclass
class CalibrationResult:
    """Fitted values with 1σ uncertainties, fit quality and the YAML snippet."""

    set_name: str
    kind: Kind
    law: Law
    names: list[str]
    values: list[float]
    stderr: list[float] | None
    units: list[str]
    residual_rms: float
    n_data: int
    delta_s: float | None
    status: str
    message: str
    nfev: int
    snippet: str = ""
    r_squared: float | None = None
    chi2_reduced: float | None = None
    direction: str = ""
    signed: bool = False
    warnings: list[str] = dataclasses.field(default_factory=list)

    def as_dict(self) -> dict[str, Any]:
        """The result as plain data.

        Returns
        -------
        dict
            Every field, and ``parameters``: name, value, 1σ and SI unit of each fitted
            parameter.
        """
        d = dataclasses.asdict(self)
        d["parameters"] = [
            {"name": n, "value": v, "stderr": None if self.stderr is None else s, "unit": u}
            for n, v, s, u in zip(
                self.names,
                self.values,
                self.stderr or [None] * len(self.names),
                self.units,
                strict=True,
            )
        ]
        return d


class _Model:
    """Predicts the measurements for a parameter vector (SI floats inside).

    Displacement data are taken at the set's drive voltage, so every point has
    the same u; speed data have one voltage per point.
    """

    def __init__(self, spec: Any, set_index: int, data: Measurements, law: Law, fit_alpha: bool):
        from betvdesign.nondim.device import derive_set

        self.aset = spec.actuator_sets[set_index]
        d = derive_set(spec, self.aset)
        self.params = d.params
        self.scales = d.scales
        self.data = data
        self.law = law
        self.fit_alpha = fit_alpha
        if data.kind == "speed":
            self.v = data.x
        else:
            v0 = self.aset.drive.voltage
            if v0 is None and law in ("linear", "quadratic"):
                raise UsageError("a gain needs the set's drive.voltage (the data's voltage)")
            self.v = np.full_like(data.y, 0.0 if v0 is None else float(v0.to("V").magnitude))
        self.voltages = np.unique(self.v)
        self._cache: dict[float | None, float] = {}
        self._tau_cache: dict[float | None, np.ndarray] = {}

    def _params(self, alpha: float | None) -> Any:
        p = self.params
        return p if alpha is None else dataclasses.replace(p, alpha=alpha)

    def delta_s(self, alpha: float | None) -> float:
        """Periodic Δs [-] (exact periodic orbit), cached per α."""
        from betvdesign.dynamics import periodic_orbit

        if alpha not in self._cache:
            res = periodic_orbit(self._params(alpha))
            if not res.success:
                raise BetvError(
                    f"periodic orbit failed at {self._params(alpha)}: {res.status}: {res.message}"
                )
            self._cache[alpha] = float(res.delta_s)
        return self._cache[alpha]

    def s_of_t(self, alpha: float | None) -> np.ndarray:
        """Dimensionless slider position s at the data times (exact transient from rest)."""
        from betvdesign.dynamics import simulate

        if alpha not in self._tau_cache:
            tau = self.data.x / self.scales.time_s
            cycles = math.ceil(tau.max() * self.params.varpi / (2 * math.pi)) + 1
            traj = simulate(self._params(alpha), cycles, dense=True)
            if not traj.success:
                raise BetvError(f"simulation failed: {traj.status}: {traj.message}")
            self._tau_cache[alpha] = np.asarray(traj.sample(tau))[:, 4]
        return self._tau_cache[alpha]

    def amplitude(self, theta: np.ndarray) -> np.ndarray:
        """U [m] at each data point."""
        if self.law == "per-voltage":
            return theta[np.searchsorted(self.voltages, self.v)]
        if self.law in ("linear", "quadratic"):
            return theta[0] * self.v ** _power(self.law)
        return np.full_like(self.data.y, self.scales.u_m)

    def predict(self, theta: np.ndarray) -> np.ndarray:
        alpha = float(theta[-1]) if self.fit_alpha else None
        c = math.cos(self.scales.theta_rad)
        if self.data.kind == "speed":
            return self.delta_s(alpha) * self.amplitude(theta) * c * self.scales.f_act_hz
        return self.s_of_t(alpha) * self.amplitude(theta) * c


def _set_up(
    device: str | os.PathLike[str],
    data: Measurements,
    law: Law,
    fit_alpha: bool,
    set_name: str | None,
    signed: bool,
    direction: str | None,
) -> tuple[_Model, Any, Measurements, str]:
    """Load the device and build the model the fit evaluates (arguments of :func:`calibrate`).

    Returns
    -------
    model : _Model
        The prediction of ``data`` as a function of the fitted values.
    aset : ActuatorSet
        The set calibrated.
    data : Measurements
        The data signed along the set's impact direction.
    direction : str
        The observed direction of travel.

    Raises
    ------
    UsageError
        For an unknown set or law, or ``fixed`` without ``fit_alpha``.
    """
    from betvdesign.spec.loader import load_device

    spec = load_device(device)
    names = [s.name for s in spec.actuator_sets]
    if set_name is None:
        set_name = names[0]
    if set_name not in names:
        raise UsageError(f"{device}: no actuator set {set_name!r} (sets: {', '.join(names)})")
    if law not in ("per-voltage", "linear", "quadratic", "fixed"):
        raise UsageError(f"unknown law {law!r} (per-voltage, linear, quadratic or fixed)")
    if law == "fixed" and not fit_alpha:
        raise UsageError("law 'fixed' keeps u from the device: fit alpha (--fit-alpha) then")
    aset = spec.actuator_sets[names.index(set_name)]
    data, direction = _along_impacts(data, aset, signed, direction)
    model = _Model(spec, names.index(set_name), data, law, fit_alpha)
    return model, aset, data, direction


def _fit(
    model: _Model, data: Measurements, x0: np.ndarray, sign: tuple[Any, str, bool], fit_alpha: bool
) -> tuple[Any, np.ndarray, list[float] | None, float | None]:
    """Fit the model to the data, weighted by their σ (or their scale).

    The direction of motion is checked against the data's before the fit (without α,
    the amplitude cannot change it) or at the optimum (α can flip the mode).

    Parameters
    ----------
    model : _Model
        The prediction.
    data : Measurements
        The data.
    x0 : numpy.ndarray
        The start [the fitted values' units]; the fit runs on values scaled by it.
    sign : tuple
        The set, the observed direction and whether the data are signed
        (:func:`_check_sign`).
    fit_alpha : bool
        Whether α is fitted (the last value).

    Returns
    -------
    res : OptimizeResult
        scipy's least_squares result (on the scaled values).
    theta : numpy.ndarray
        The fitted values [their units].
    stderr : list of float or None
        Their 1σ, None where the fit's Jacobian cannot tell them apart.
    alpha : float or None
        The fitted α [-] (None when not fitted).

    Raises
    ------
    UsageError
        For fewer data points than values.
    CalibrationMismatch
        When the model moves the slider the other way than the data.
    """
    from scipy.optimize import least_squares

    n, p = len(data.y), len(x0)
    aset, direction, signed = sign
    if n < p:
        raise UsageError(f"{data.source}: {n} data points cannot determine {p} parameters")
    if not fit_alpha:  # the sign of the motion does not depend on u: check before fitting
        _check_sign(model, data, None, aset, direction, signed)
    w = 1.0 / data.sigma if data.sigma is not None else np.full(n, 1.0 / _yscale(data))
    scale = np.abs(x0)

    def residual(z: np.ndarray) -> np.ndarray:
        return (model.predict(z * scale) - data.y) * w

    res = least_squares(residual, np.ones_like(x0), bounds=(0.0, np.inf))
    theta = res.x * scale
    stderr: list[float] | None = None
    jac = res.jac / scale[None, :]
    if data.sigma is not None or n > p:
        s2 = 1.0 if data.sigma is not None else float(2.0 * res.cost / (n - p))
        try:
            cov = np.linalg.inv(jac.T @ jac) * s2
            var = np.diag(cov)
            # a singular or ill-conditioned fit gives no usable uncertainty: say None
            identifiable = np.all(var >= 0) and np.linalg.cond(res.jac) < MAX_CONDITION
            stderr = [float(x) for x in np.sqrt(var)] if identifiable else None
        except np.linalg.LinAlgError:
            stderr = None
    alpha = float(theta[-1]) if fit_alpha else None
    if fit_alpha:  # α can flip the mode: check the optimum
        _check_sign(model, data, alpha, aset, direction, signed)
    return res, theta, stderr, alpha


def _goodness(
    model: _Model, data: Measurements, res: Any, theta: np.ndarray
) -> tuple[float, float | None, float | None]:
    """How well the fitted model explains the data.

    Parameters
    ----------
    model : _Model
        The prediction.
    data : Measurements
        The data.
    res : OptimizeResult
        scipy's result.
    theta : numpy.ndarray
        The fitted values.

    Returns
    -------
    rms : float
        Residual rms [m/s or m].
    r_squared : float or None
        R² [-] (None for data without spread).
    chi2_reduced : float or None
        χ²/dof [-] (None without σ or degrees of freedom).
    """
    n, p = len(data.y), len(theta)
    resid = model.predict(theta) - data.y
    rms = float(np.sqrt(np.mean(resid**2)))
    sst = float(np.sum((data.y - data.y.mean()) ** 2))
    r2 = 1.0 - float(np.sum(resid**2)) / sst if sst > 0 else None
    chi2 = float(2.0 * res.cost / (n - p)) if data.sigma is not None and n > p else None
    return rms, r2, chi2


def _fit_warnings(
    res: Any,
    theta: np.ndarray,
    x0: np.ndarray,
    labels: list[str],
    fit: tuple[float | None, float | None, list[float] | None],
    data: Measurements,
    fit_alpha: bool,
) -> tuple[str, list[str]]:
    """The fit's status and what a user should know about its quality.

    Parameters
    ----------
    res : OptimizeResult
        scipy's result.
    theta, x0 : numpy.ndarray
        The fitted values and the start [their units].
    labels : list of str
        Their names.
    fit : tuple
        R², χ²/dof (None when unknown) and the 1σ of the values.
    data : Measurements
        The data.
    fit_alpha : bool
        Whether α was fitted.

    Returns
    -------
    status : str
        "converged", "failed" or "at_bound".
    warnings : list of str
        Values at their bound, a poor R², χ²/dof far from 1, unknown uncertainty.
    """
    r2, chi2, stderr = fit
    n, p = len(data.y), len(x0)
    warns: list[str] = []
    status = "converged" if res.success else "failed"
    at_bound = [lab for lab, t, x in zip(labels, theta, x0, strict=True) if t <= 1e-9 * abs(x)]
    if at_bound:
        status = "at_bound"
        warns.append(f"{', '.join(at_bound)} at the lower bound 0: the fit is not usable")
    if r2 is not None and r2 < POOR_FIT_R2:
        warns.append(f"R² = {r2:.3g} < {POOR_FIT_R2:g}: the model explains the data poorly")
    if chi2 is not None and not 0.2 < chi2 < 5.0:
        warns.append(f"χ²/dof = {chi2:.3g}: residuals and the given σ do not match")
    if stderr is None and data.sigma is None and n <= p:
        warns.append(f"uncertainty unknown: {n} points for {p} parameters and no sigma column")
    elif stderr is None:
        hint = (
            " (the speed scales with the stroke's gain and depends on α through Δs alike "
            "over these data: measure u(V) separately, or give α and fit the gain)"
            if fit_alpha
            else ""
        )
        warns.append(
            f"uncertainty unknown: {', '.join(labels)} cannot be told apart from these "
            f"data (the fit's Jacobian is singular or ill-conditioned){hint}"
        )
    return status, warns


def calibrate(
    device: str | os.PathLike[str],
    data: Measurements,
    *,
    law: Law = "linear",
    fit_alpha: bool = False,
    set_name: str | None = None,
    signed: bool = False,
    direction: str | None = None,
) -> CalibrationResult:
    """Fit the amplitude law (and optionally α) of one actuator set to ``data``.

    Parameters
    ----------
    device : path
        Device YAML file.
    data : Measurements
        Speeds [m/s] against voltage [V], or displacements [m] against time [s].
    law : {"linear", "quadratic", "per-voltage", "fixed"}
        Amplitude law fitted: u = g·V [m/V], u = g·V² [m/V²], one u [m] per voltage,
        or u from the device (``fixed``, with ``fit_alpha``).
    fit_alpha : bool
        Also fit α = k_v/k_h [-] (re-solves the periodic orbit per step).
    set_name : str, optional
        Actuator set (default: the first).
    signed : bool
        False (default): the data are magnitudes (>= 0) of motion toward ``direction``;
        True: signed along the set's impact direction (the model's s).
    direction : {"+x", "-x"}, optional
        Observed direction of travel for magnitudes (default: the set's intended one).

    Returns
    -------
    CalibrationResult
        Fitted values with 1σ, R², χ²/dof, residual rms [m/s or m], warnings, snippet.

    Raises
    ------
    CalibrationMismatch
        The model moves the slider the other way than the data (amplitude cannot fix a
        sign).
    UsageError
        Bad arguments or data (negative magnitudes, unknown set or law, too few points).

    Notes
    -----
    Mean speed v(V) = Δs·u(V)·cosθ·f_act and displacement x(t) = s(t/t_s)·u·cosθ, with
    Δs and s(τ) from the exact model of Shin et al. [1]_.

    References
    ----------
    .. [1] K. Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773
    """
    model, aset, data, travel = _set_up(device, data, law, fit_alpha, set_name, signed, direction)
    x0, labels, units = _start(model, law, fit_alpha)
    res, theta, stderr, alpha = _fit(model, data, x0, (aset, travel, signed), fit_alpha)
    rms, r2, chi2 = _goodness(model, data, res, theta)
    status, warns = _fit_warnings(res, theta, x0, labels, (r2, chi2, stderr), data, fit_alpha)
    out = CalibrationResult(
        set_name=aset.name,
        kind=data.kind,
        law=law,
        names=labels,
        values=[float(t) for t in theta],
        stderr=stderr,
        units=units,
        residual_rms=rms,
        n_data=len(data.y),
        delta_s=model.delta_s(alpha) if data.kind == "speed" else None,
        status=status,
        message=str(res.message),
        nfev=int(res.nfev),
        r_squared=r2,
        chi2_reduced=chi2,
        direction=travel,
        signed=signed,
        warnings=warns,
    )
    out.snippet = snippet(out, data)
    return out


def _along_impacts(
    data: Measurements, aset: Any, signed: bool, direction: str | None
) -> tuple[Measurements, str]:
    """The data signed along the set's impact direction, and its direction.

    The data signed along the set's impact direction (the model's s), and the
    observed travel direction ("+x"/"-x"; for signed data, the one the data show).
    """
    impact = 1 if aset.impact_direction == "+x" else -1
    if signed:
        if direction is not None:
            raise UsageError("--direction is for magnitudes; signed data carry their sign")
        mean = float(np.mean(data.y))
        return data, ("+x" if impact * mean > 0 else "-x") if mean else ""
    if direction is None:
        direction = "+x" if aset.travel_sign > 0 else "-x"
    if direction not in ("+x", "-x"):
        raise UsageError(f"direction must be +x or -x, not {direction!r}")
    neg = np.flatnonzero(data.y < 0)
    if neg.size:
        raise UsageError(
            f"{data.source}: {data.kind} must be a magnitude (>= 0) with the direction given "
            f"separately; row {int(neg[0]) + 1} of the data is negative (for values signed "
            "along the impact direction use --signed)"
        )
    along = 1 if (direction == "+x") == (impact > 0) else -1
    return dataclasses.replace(data, y=data.y * along), direction


def _check_sign(
    model: _Model,
    data: Measurements,
    alpha: float | None,
    aset: Any,
    direction: str,
    signed: bool,
) -> None:
    """Raise :class:`CalibrationMismatch` when the model moves the slider against the data."""
    if data.kind == "speed":
        ds = model.delta_s(alpha)
        shown = f"Δs = {ds:.3g} per cycle"
    else:
        ds = float(model.s_of_t(alpha)[int(np.argmax(data.x))])
        shown = f"s = {ds:.3g} at the last data time"
    want = float(np.sum(data.y))
    if want == 0.0 or ds * want > 0:
        return
    impact = 1 if aset.impact_direction == "+x" else -1
    model_dir = "+x" if impact * ds > 0 else "-x"
    mode = "push" if ds > 0 else "pull"
    told = "signed data" if signed else "the given direction"
    raise CalibrationMismatch(
        f"{data.source}: data and model disagree in sign: the slider moved {direction} "
        f"({told}), the model of set {aset.name!r} moves it {model_dir} ({mode} mode, "
        f"{shown}); no amplitude can fit that. Check the direction (--direction, --signed), "
        "the actuator set (--set) or the device parameters"
        + ("" if alpha is None else f" (fitted α = {alpha:.3g})")
    )


def _power(law: str) -> int:
    return {"linear": 1, "quadratic": 2}.get(law, 0)


def _yscale(data: Measurements) -> float:
    return float(np.max(np.abs(data.y))) or 1.0


def _start(model: _Model, law: Law, fit_alpha: bool) -> tuple[np.ndarray, list[str], list[str]]:
    """Starting point (the device's own values), names and SI units of the parameters."""
    u0 = model.scales.u_m if model.scales.u_m > 0 else 1e-7
    x0: list[float] = []
    names: list[str] = []
    units: list[str] = []
    if law == "per-voltage":
        for v in model.voltages:
            x0.append(u0)
            names.append(f"u({v:g} V)")
            units.append("m")
    elif law in ("linear", "quadratic"):
        v0 = model.aset.drive.voltage
        volts = 1.0 if v0 is None else float(v0.to("V").magnitude)
        x0.append(u0 / volts ** _power(law))
        names.append("gain")
        units.append("m/V" if law == "linear" else "m/V^2")
    if fit_alpha:
        x0.append(model.params.alpha)
        names.append("alpha")
        units.append("")
    return np.array(x0), names, units


def snippet(result: CalibrationResult, data: Measurements) -> str:
    """A device-file fragment (YAML) carrying the fitted calibration.

    Parameters
    ----------
    result : CalibrationResult
        The fit.
    data : Measurements
        The data it was fitted to (named in the fragment's comment).

    Returns
    -------
    str
        YAML for the ``actuator:`` section: ``alpha`` [-], ``amplitude`` [um] or a
        ``calibration`` (gain [um/V or um/V²], or measured points), 1σ in comments.
    """
    from betvdesign.output.siformat import format_si
    from betvdesign.spec.units import ureg

    lines = [
        f"# betv calibrate: fitted to {data.source} ({data.kind}, {result.n_data} points), "
        f"actuator set {result.set_name!r}",
        f"# status {result.status}; residual rms "
        + format_si(result.residual_rms, "m/s" if data.kind == "speed" else "m")
        + ("" if result.r_squared is None else f"; R² {result.r_squared:.4g}")
        + ("" if result.chi2_reduced is None else f"; χ²/dof {result.chi2_reduced:.3g}"),
        *(f"# warning: {w}" for w in result.warnings),
        "actuator:",
    ]

    def fmt(value: float, unit: str, target: str, err: float | None) -> str:
        q = ureg.Quantity(value, unit).to(target)
        text = f"{q.magnitude:.6g} {target}"
        if err is not None:
            e = ureg.Quantity(err, unit).to(target).magnitude
            text += f"  # ± {e:.2g} {target} (1σ)"
        return text

    errs = result.stderr or [None] * len(result.values)
    by_name = dict(
        zip(result.names, zip(result.values, errs, result.units, strict=True), strict=True)
    )
    if "alpha" in by_name:
        a, ea, _ = by_name.pop("alpha")
        lines.append(f"  alpha: {a:.6g}" + (f"  # ± {ea:.2g} (1σ)" if ea is not None else ""))
    if result.law == "per-voltage":
        if len(by_name) < 2:
            u, e, unit = next(iter(by_name.values()))
            lines.append(f"  amplitude: {fmt(u, unit, 'um', e)}")
        else:
            lines += ["  calibration:", "    law: measured", "    points:"]
            for name, (u, e, unit) in by_name.items():
                volts = name[2:-1]
                lines.append(f"      - {{voltage: {volts}, amplitude: {fmt(u, unit, 'um', None)}}}")
                if e is not None:
                    lines[-1] += f"  # ± {ureg.Quantity(e, unit).to('um').magnitude:.2g} um"
    elif "gain" in by_name:
        g, e, unit = by_name["gain"]
        target = "um/V" if result.law == "linear" else "um/V^2"
        lines += [
            "  calibration:",
            f"    law: {result.law}",
            f"    gain: {fmt(g, unit, target, e)}",
        ]
    elif "u" in by_name:
        u, e, unit = by_name["u"]
        lines.append(f"  amplitude: {fmt(u, unit, 'um', e)}")
    return "\n".join(lines) + "\n"


def fitted(result: CalibrationResult, name: str) -> tuple[float, float | None]:
    """A fitted parameter by name.

    Parameters
    ----------
    result : CalibrationResult
        The fit.
    name : str
        The parameter: ``gain``, ``u(8 V)``, ``alpha``...

    Returns
    -------
    tuple of (float, float or None)
        Its value and 1σ, in its SI unit (``result.units``); 1σ None when unknown.
    """
    i = result.names.index(name)
    return result.values[i], None if result.stderr is None else result.stderr[i]
