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
Speeds and displacements count positive in the direction the model's s
counts (along the impact direction); pull mode gives negative values.

Fitted parameters (``scipy.optimize.least_squares``):

* ``law="per-voltage"``: one u per distinct voltage (a ``measured`` calibration);
* ``law="linear"`` / ``"quadratic"``: the gain g of u = g·V or u = g·V²;
* ``law="fixed"`` with ``fit_alpha=True``: u from the device, fit α only;
* ``fit_alpha=True`` adds α (k_v/k_h, the phenomenological compliance) to the fit
  (each residual evaluation then re-solves the periodic orbit).

Uncertainty: covariance (JᵀJ)⁻¹ from the Jacobian at the optimum, scaled by the
residual variance SSR/(n − p) unless σ is given; with no σ and no spare data
points (n = p) the uncertainty is unknown and reported as None, not invented.
"""

from __future__ import annotations

import csv
import dataclasses
import math
import os
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal

import numpy as np
import pint

from betvdesign.errors import BetvError, UsageError

Law = Literal["per-voltage", "linear", "quadratic", "fixed"]
Kind = Literal["speed", "displacement"]

_COLUMNS: dict[Kind, tuple[tuple[str, str], tuple[str, str]]] = {
    "speed": (("voltage", "V"), ("speed", "um/s")),
    "displacement": (("time", "s"), ("displacement", "um")),
}


@dataclass(frozen=True)
class Measurements:
    """Measured data in SI floats: x (V or s), y (m/s or m), sigma (same as y) or None."""

    kind: Kind
    x: np.ndarray
    y: np.ndarray
    sigma: np.ndarray | None
    source: str


def read_measurements(path: str | os.PathLike[str], kind: Kind) -> Measurements:
    """Read a calibration CSV (see module doc); errors name file, line and column."""
    from betvdesign.safeyaml import read_text
    from betvdesign.units import parse_units, ureg

    p = Path(path)
    text = read_text(p)  # the input-size limit; errors name the file
    rows = [r for r in csv.reader(text.splitlines()) if r and not r[0].lstrip().startswith("#")]
    if len(rows) < 2:
        raise UsageError(f"{p}: needs a header and at least one data row")
    (xname, xunit), (yname, yunit) = _COLUMNS[kind]
    header: dict[str, tuple[int, pint.Unit]] = {}
    for j, cell in enumerate(rows[0]):
        m = re.fullmatch(r"\s*(\w+)\s*\[(.+)\]\s*", cell)
        if not m:
            raise UsageError(f"{p}:1: column {j + 1}: header {cell!r} must read 'name [unit]'")
        try:
            header[m.group(1)] = (j, parse_units(m.group(2)))  # bounded: no unit bombs
        except (pint.PintError, ValueError) as exc:
            raise UsageError(f"{p}:1: column {j + 1}: unknown unit {m.group(2)!r}: {exc}") from None
    expected = (xname, yname)
    if not set(expected) <= set(header) or not set(header) <= {*expected, "sigma"}:
        raise UsageError(
            f"{p}:1: {kind} data needs columns {xname} [{xunit}], {yname} [{yunit}] "
            f"and optionally sigma [{yunit}]; got {', '.join(header)}"
        )
    si = {xname: xunit, yname: yunit, "sigma": yunit}
    cols: dict[str, list[float]] = {name: [] for name in header}
    for lineno, cells in enumerate(rows[1:], start=2):
        if len(cells) != len(header):
            raise UsageError(f"{p}:{lineno}: expected {len(header)} fields, got {len(cells)}")
        for name, (j, unit) in header.items():
            try:
                value = float(cells[j])
                q = ureg.Quantity(value, unit).to(si[name])
            except ValueError:
                raise UsageError(f"{p}:{lineno}: {name}: {cells[j]!r} is not a number") from None
            except pint.DimensionalityError:
                raise UsageError(f"{p}:1: {name}: unit {unit} is not a {si[name]} unit") from None
            if not math.isfinite(q.magnitude):
                raise UsageError(f"{p}:{lineno}: {name}: not finite")
            cols[name].append(float(q.to_base_units().magnitude))
    x = np.array(cols[xname])
    sigma = np.array(cols["sigma"]) if "sigma" in cols else None
    if sigma is not None and np.any(sigma <= 0):
        raise UsageError(f"{p}: sigma must be > 0 on every row")
    if np.any(x < 0):
        raise UsageError(f"{p}: {xname} must be >= 0")
    return Measurements(kind, x, np.array(cols[yname]), sigma, str(p))


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

    def as_dict(self) -> dict[str, Any]:
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
        from betvdesign.nondim import derive_set

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
        """u [m] at each data point."""
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


def calibrate(
    device: str | os.PathLike[str],
    data: Measurements,
    *,
    law: Law = "linear",
    fit_alpha: bool = False,
    set_name: str | None = None,
) -> CalibrationResult:
    """Fit the amplitude law (and optionally α) of one actuator set to ``data``."""
    from scipy.optimize import least_squares

    from betvdesign.loader import load_device

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
    model = _Model(spec, names.index(set_name), data, law, fit_alpha)
    x0, labels, units = _start(model, law, fit_alpha)
    n, p = len(data.y), len(x0)
    if n < p:
        raise UsageError(f"{data.source}: {n} data points cannot determine {p} parameters")
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
            stderr = [float(x) for x in np.sqrt(var)] if np.all(var >= 0) else None
        except np.linalg.LinAlgError:
            stderr = None
    rms = float(np.sqrt(np.mean((model.predict(theta) - data.y) ** 2)))
    alpha = float(theta[-1]) if fit_alpha else None
    out = CalibrationResult(
        set_name=set_name,
        kind=data.kind,
        law=law,
        names=labels,
        values=[float(t) for t in theta],
        stderr=stderr,
        units=units,
        residual_rms=rms,
        n_data=n,
        delta_s=model.delta_s(alpha) if data.kind == "speed" else None,
        status="converged" if res.success else "failed",
        message=str(res.message),
        nfev=int(res.nfev),
    )
    out.snippet = snippet(out, data)
    return out


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
    """A device-file fragment (YAML) carrying the fitted calibration."""
    from betvdesign.units import ureg

    lines = [
        f"# betv calibrate: fitted to {data.source} ({data.kind}, {result.n_data} points), "
        f"actuator set {result.set_name!r}",
        f"# status {result.status}; residual rms {result.residual_rms:.4g} "
        + ("m/s" if data.kind == "speed" else "m"),
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
    """(value, 1σ) of a fitted parameter by name."""
    i = result.names.index(name)
    return result.values[i], None if result.stderr is None else result.stderr[i]
