"""Tolerance analysis: Monte Carlo over fabrication and operating variation.

Tolerances are given per spec field, as a dotted path into the device file
(``slider.beam_width``, ``head.mass``, ``contact.friction``,
``contact.impact_angle``, ``actuator.vertical_resonance``, ``actuator.alpha``,
``actuator.calibration.gain``, ``drive.frequency``, ``drive.voltage``, ...).
Paths below an actuator set (``head.``, ``contact.``, ``actuator.``,
``drive.``) apply to every set: one draw per field and sample is shared by all
sets (global process/operating variation, fully correlated; state it if you
read per-set results together).

Distributions: ``normal`` (σ) or ``uniform`` (half-width), each relative
(``2%``) or absolute (``0.2 um``, or a plain number for unit-less fields).
Command-line form ``--spread FIELD=[normal|uniform:]AMOUNT``; file form (YAML)::

    tolerances:
      slider.beam_width: {dist: normal, sigma: 0.2 um}
      contact.friction: {dist: uniform, half_width: 10%}

Samples are drawn in spec space with a seeded ``numpy.random.Generator``
(fields in the order given), each sample goes through ``nondim.derive_set``
(the only place units are stripped), then through the chosen rung:
``periodic`` (the reference: exact periodic orbit, gives the simulated mode
and speed) or ``lambda`` (closed-form fit only; P(push) from λ, no speed).

Results: P(push), P(pull), P(not converged), P(outside the 0.5 ≤ ϖ < 2
window), P(wrong mode: the opposite of the intended one), speed percentiles
(signed along the impact direction, + push, − pull, as every output of the toolkit:
``speed_um_s_percentiles``; and along the intended direction of travel, + the intended
way, − the wrong way, so that p5 is the slowest 5 % for a push and a pull device alike:
``intended_speed_um_s_percentiles``), and sensitivities as Spearman rank correlations
of each input with speed (periodic) and λ.
"""

from __future__ import annotations

import functools
import math
import os
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal

import numpy as np

from betvdesign.checks.coupled import DECOUPLED_WARNING
from betvdesign.errors import BetvError, UsageError
from betvdesign.model.damping import term_range
from betvdesign.model.domain import in_window
from betvdesign.spec import limits
from betvdesign.spec.paths import with_values
from betvdesign.studies.engine.runner import Study, StudyRun, run_study, split_run_args
from betvdesign.studies.fixrules import spread_rules
from betvdesign.studies.points import (
    MODEL_STATEMENT,
    Fidelity,
    require_fidelity,
    rung_reason,
    solver_error,
)
from betvdesign.studies.sampling import (
    check_sample,
    derive_all,
    draw,
    nominal_values,
    params_of,
    passes_spread_rules,
)

Dist = Literal["normal", "uniform"]
#: Distributions a tolerance may name (lower case; names are case-insensitive).
DISTRIBUTIONS: tuple[str, ...] = ("normal", "uniform")
PERCENTILES = (5.0, 25.0, 50.0, 75.0, 95.0)


@dataclass(frozen=True)
class Tolerance:
    """One field's variation: relative (fraction) or absolute (string with unit)."""

    field: str
    dist: Dist
    relative: float | None = None
    absolute: str | None = None
    source: str = "command line"
    dist_given: bool = True

    def describe(self) -> str:
        """The spread as used, its distribution always stated.

        The spread as used, its distribution always stated (the default named as
        such): ``slider.beam_width: normal σ 5 % (normal: the default)``.
        """
        width = "σ" if self.dist == "normal" else "half-width"
        amount = f"{100 * self.relative:.3g} %" if self.relative is not None else self.absolute
        default = "" if self.dist_given else " (normal: the default)"
        return f"{self.field}: {self.dist} {width} {amount}{default}"

    def as_dict(self) -> dict[str, Any]:
        """The tolerance as plain data.

        Returns
        -------
        dict
            ``field``, ``dist``, ``relative`` [-] and ``absolute`` (text with its unit).
        """
        return {
            "field": self.field,
            "dist": self.dist,
            "relative": self.relative,
            "absolute": self.absolute,
        }


def _amount(text: str, field: str, source: str) -> tuple[float | None, str | None]:
    t = str(text).strip()
    if t.endswith("%"):
        try:
            rel = float(t[:-1]) / 100.0
        except ValueError:
            raise UsageError(f"{source}: {field}: bad percentage {t!r}") from None
        if not (math.isfinite(rel) and rel > 0):
            raise UsageError(f"{source}: {field}: tolerance must be > 0, got {t!r}")
        return rel, None
    if not t:
        raise UsageError(f"{source}: {field}: empty tolerance")
    return None, t


def parse_tolerance(text: str, source: str = "command line") -> Tolerance:
    """Parse one tolerance of the command line.

    Parameters
    ----------
    text : str
        ``FIELD=[normal|uniform:]AMOUNT``, AMOUNT ``2%`` (relative), ``0.2 um`` (absolute,
        any unit of the field) or ``0.05`` (a unit-less field); normal by default.
    source : str
        Where the text comes from (named in errors).

    Returns
    -------
    Tolerance
        The field's variation.

    Raises
    ------
    UsageError
        Text of another form, an unknown distribution or an amount not > 0.
    """
    m = re.fullmatch(r"\s*([A-Za-z_][\w.]*)\s*=\s*(?:([A-Za-z_]\w*)\s*:)?\s*(.+?)\s*", text)
    if m and m.group(2) and m.group(2).lower() not in DISTRIBUTIONS:
        raise UsageError(
            f"{source}: {m.group(1)}: unknown distribution {m.group(2)!r}; use "
            f"{', '.join(DISTRIBUTIONS)} (e.g. {m.group(1)}=normal:{m.group(3)})"
        )
    if not m:
        raise UsageError(
            f"{source}: tolerance {text!r} must read FIELD=[normal|uniform:]AMOUNT, "
            "e.g. slider.beam_width=normal:0.2um or contact.friction=uniform:10%"
        )
    field, dist, amount = m.group(1), (m.group(2) or "normal").lower(), m.group(3)
    rel, absolute = _amount(amount, field, source)
    return Tolerance(
        field,
        dist,
        rel,
        absolute,
        source,
        dist_given=m.group(2) is not None,  # type: ignore[arg-type]
    )


def load_tolerances(path: str | os.PathLike[str]) -> list[Tolerance]:
    """Read a ``tolerances:`` mapping from YAML (see module doc).

    Parameters
    ----------
    path : path
        The YAML file: ``tolerances: {FIELD: {dist: normal, sigma: AMOUNT}, ...}``
        (uniform: ``half_width``).

    Returns
    -------
    list of Tolerance
        The fields' variations in the file's order (each naming its file and line).

    Raises
    ------
    UsageError
        Not valid or not safe YAML, another top-level key, an unknown distribution or a
        bad amount (the message names file and line).
    """
    from ruamel.yaml import YAMLError

    from betvdesign.errors import SpecError
    from betvdesign.spec import safeyaml

    p = Path(path)
    try:
        text = safeyaml.read_text(p)  # size, encoding, nesting and alias limits
        _, data = safeyaml.load(text, str(p))
    except SpecError as exc:
        raise UsageError(str(exc)) from None
    except YAMLError as exc:
        raise UsageError(f"{p}: not valid YAML: {exc}") from None
    if not isinstance(data, Mapping) or set(data) != {"tolerances"}:
        raise UsageError(f"{p}: expected one top-level key 'tolerances'")
    entries = data["tolerances"]
    if not isinstance(entries, Mapping) or not entries:
        raise UsageError(f"{p}: 'tolerances' must map field paths to distributions")
    out = []
    for field, spec in entries.items():
        line = entries.lc.key(field)[0] + 1 if hasattr(entries, "lc") else None
        where = f"{p}:{line}" if line else str(p)
        if not isinstance(spec, Mapping):
            raise UsageError(f"{where}: {field}: expected {{dist: ..., sigma|half_width: ...}}")
        dist = spec.get("dist", "normal")
        dist = dist.lower() if isinstance(dist, str) else dist
        key = "sigma" if dist == "normal" else "half_width"
        if dist not in DISTRIBUTIONS:
            raise UsageError(
                f"{where}: {field}: unknown distribution {dist!r}; use {', '.join(DISTRIBUTIONS)}"
            )
        unknown = set(spec) - {"dist", key}
        if unknown or key not in spec:
            raise UsageError(f"{where}: {field}: {dist} needs exactly '{key}' (and 'dist')")
        rel, absolute = _amount(spec[key], field, where)
        out.append(Tolerance(str(field), dist, rel, absolute, where))
    return out


# -- the worker ------------------------------------------------------------------
@functools.lru_cache(maxsize=8)
def _device(path: str, mtime_ns: int) -> Any:
    from betvdesign.spec.loader import load_device

    return load_device(path)


def _perturbed(task: Mapping[str, Any]) -> Any:
    from betvdesign.spec.units import ureg

    spec = _device(task["device"], task["mtime_ns"])
    check_sample(task["values"])
    for field, (mag, unit) in task["values"].items():
        value = ureg.Quantity(mag, unit) if unit else float(mag)
        spec = with_values(spec, {field: value})
    return spec


def tolerance_point(task: Mapping[str, Any]) -> dict[str, Any]:
    """One (sample, actuator set): perturb, derive (units stripped), solve.

    Tasks built by :func:`tolerance_study` usually carry the sample's derived
    parameters already (``derived``: the whole sample derived at once by
    :func:`betvdesign.nondim.device.derive_samples`, the same formulas vectorised); otherwise
    the sample is derived here with :func:`betvdesign.nondim.device.derive_set`.

    Parameters
    ----------
    task : mapping
        A task of :func:`tolerance_study`: key, sample, set, sampled ``values``
        (magnitude, unit per field), rung, ``tol`` [-], columns and ``derived`` (or None).

    Returns
    -------
    dict
        One row: the sample's inputs, ϖ, α, β, κ, λ [-] (fit of Shin et al. [1]_) and the
        mode it predicts, intended mode, whether ϖ is in the design window, and on the
        periodic rung the simulated mode, Δs [-] and the speed Δs·u·cosθ·f_act [um/s];
        status "invalid-sample" for a sample the spec or the model cannot take.

    References
    ----------
    .. [1] K. Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773
    """
    row: dict[str, Any] = {c: None for c in task["columns"]}
    row.update(key=task["key"], sample=task["sample"], set=task["set_name"])
    for field, (mag, _) in task["values"].items():
        row[f"in:{field}"] = mag
    derived = task.get("derived")
    try:
        if derived is None:
            from betvdesign.nondim.device import derive_set

            spec = _perturbed(task)
            d = derive_set(spec, spec.actuator_sets[task["set_index"]])
            p, intended = d.params, d.intended_mode
            length_m, f_act = d.scales.length_m, d.scales.f_act_hz
        else:
            check_sample(task["values"])
            p = params_of(derived)
            intended, length_m, f_act = task["intended"], derived["length_m"], derived["f_act_hz"]
    except BetvError as exc:
        row.update(status="invalid-sample", converged=False, message=str(exc))
        return row
    row.update(
        **p.as_dict(),
        lam=p.lam,
        lambda_mode=p.lambda_mode,
        intended=intended,
        in_window=in_window(p.varpi),
    )
    if task["fidelity"] == "lambda":
        row.update(status="lambda-only", converged=False, message="closed-form λ fit only")
        return row
    from betvdesign.dynamics import periodic_orbit

    try:
        res = periodic_orbit(p, tol=task["tol"])
    except Exception as exc:  # recorded and counted as not converged, never fatal
        row.update(status="error", converged=False, message=solver_error(exc))
        return row
    row.update(status=str(res.status), converged=bool(res.success), message=str(res.message))
    ds = None
    if res.success and res.delta_s is not None and math.isfinite(res.delta_s):
        ds = float(res.delta_s)
        row.update(mode=res.mode, delta_s=ds, speed_um_s=ds * length_m * f_act * 1e6)
    row["passes"] = passes_spread_rules(p, ds, intended)
    return row


BASE_COLUMNS: dict[str, type] = {
    "key": int,
    "sample": int,
    "set": str,
    "status": str,
    "converged": bool,
    "varpi": float,
    "alpha": float,
    "beta": float,
    "kappa": float,
    "lam": float,
    "lambda_mode": str,
    "intended": str,
    "in_window": bool,
    "mode": str,
    "delta_s": float,
    "speed_um_s": float,
    "passes": bool,
    "message": str,
}


def _beyond_columns(spec: Any) -> dict[str, type]:
    """Columns zeta_v, zeta_h, restitution [-] of a damped nominal device.

    Columns zeta_v, zeta_h, restitution [-] (ModelParams.as_dict's) when the nominal
    device gives damping or restitution; none for the paper's model.
    """
    from betvdesign.nondim.device import derive

    try:
        ideal = all(sd.params.ideal for sd in derive(spec).sets)
    except BetvError:  # the nominal device does not derive: its samples say why
        ideal = True
    return {} if ideal else dict.fromkeys(("zeta_v", "zeta_h", "restitution"), float)


def _refuse_lambda_beyond_ideal(
    device: str | os.PathLike[str],
    spec: Any,
    chosen: Sequence[str],
    tolerances: Sequence[Tolerance],
) -> None:
    """Refuse the λ rung for a device with damping or restitution.

    UsageError when the λ rung is asked of a device (or a spread) with damping or
    restitution: λ is a fit to the idealised model and knows neither.
    """
    from betvdesign.nondim.device import derive_set

    spread = [t.field for t in tolerances if term_range(t.field) is not None]
    damped = [
        s.name
        for s in spec.actuator_sets
        if s.name in chosen and not derive_set(spec, s).params.ideal
    ]
    if spread or damped:
        names = ", ".join(damped or spread)
        what = f"set(s) {names} give" if damped else f"{names} spread(s) give"
        raise UsageError(
            f"{device}: --fidelity lambda is a fit to the idealised model (undamped, plastic "
            f"impacts) and {what} damping or restitution; use --fidelity periodic (the default)"
        )


def _chosen_sets(
    device: str | os.PathLike[str],
    spec: Any,
    tolerances: Sequence[Tolerance],
    request: tuple[int, int, Fidelity],
    sets: Sequence[str] | None,
) -> list[str]:
    """Check a tolerance study's request; the actuator sets it analyses.

    Parameters
    ----------
    device : path
        The device file, for messages.
    spec : DeviceSpec
        The device.
    tolerances : sequence of Tolerance
        The fields' variations.
    request : tuple
        The samples, the seed and the rung asked for.
    sets : sequence of str, optional
        The sets asked for (None: every set).

    Returns
    -------
    list of str
        The sets' names.

    Raises
    ------
    UsageError
        As :func:`tolerance_study`.
    """
    samples, seed, fidelity = request
    if not 1 <= samples <= limits.MAX_SAMPLES:
        raise UsageError(f"--samples must be >= 1 and <= {limits.MAX_SAMPLES:,}, got {samples}")
    limits.check_seed(seed)
    require_fidelity(fidelity)
    if not tolerances:
        raise UsageError("give at least one tolerance (--spread FIELD=AMOUNT or --tolerances FILE)")
    names = [s.name for s in spec.actuator_sets]
    chosen = list(sets) if sets else names
    for name in chosen:
        if name not in names:
            raise UsageError(f"{device}: no actuator set {name!r} (sets: {', '.join(names)})")
    if fidelity == "lambda":
        _refuse_lambda_beyond_ideal(device, spec, chosen, tolerances)
    return chosen


def _tasks(
    spec: Any,
    tolerances: Sequence[Tolerance],
    nominal: dict[str, tuple[float, str]],
    x: np.ndarray,
    chosen: list[str],
    common: dict[str, Any],
) -> list[dict[str, Any]]:
    """One task per (sample, set), in plain floats.

    Parameters
    ----------
    spec : DeviceSpec
        The nominal device.
    tolerances : sequence of Tolerance
        The fields' variations.
    nominal : dict
        Each field's nominal magnitude and unit.
    x : numpy.ndarray
        The drawn values (samples, fields) [the fields' units].
    chosen : list of str
        The sets analysed.
    common : dict
        ``path``, ``mtime``, ``fidelity``, ``tol`` and ``columns`` of the study.

    Returns
    -------
    list of dict
        The tasks of :func:`tolerance_point`.
    """
    path, mtime, fidelity, tol, columns = (
        common[k] for k in ("path", "mtime", "fidelity", "tol", "columns")
    )
    names = [s.name for s in spec.actuator_sets]
    samples = len(x)
    derived = {name: derive_all(spec, tolerances, nominal, x, names.index(name)) for name in chosen}
    intended = {s.name: s.intended_mode for s in spec.actuator_sets}
    # Python floats once per column (``tolist``), not one ``float()`` per element
    xs = x.tolist()
    columns_of = {
        name: None if arrays is None else {k: v.tolist() for k, v in arrays.items()}
        for name, arrays in derived.items()
    }
    units = [nominal[t.field][1] for t in tolerances]
    tasks = []
    for i in range(samples):
        values = {t.field: (xs[i][j], units[j]) for j, t in enumerate(tolerances)}
        for name in chosen:
            arrays = columns_of[name]
            tasks.append(
                {
                    "key": len(tasks),
                    "sample": i,
                    "set_name": name,
                    "set_index": names.index(name),
                    "device": path,
                    "mtime_ns": mtime,
                    "values": values,
                    "fidelity": fidelity,
                    "tol": tol,
                    "columns": tuple(columns),
                    "intended": intended[name],
                    "derived": None if arrays is None else {k: v[i] for k, v in arrays.items()},
                }
            )
    return tasks


def tolerance_study(
    device: str | os.PathLike[str],
    tolerances: Sequence[Tolerance],
    *,
    samples: int,
    seed: int,
    fidelity: Fidelity = "periodic",
    tol: float = 1e-10,
    sets: Sequence[str] | None = None,
) -> Study:
    """Draw the samples and build the study (tasks carry plain floats only).

    Parameters
    ----------
    device : path
        Device YAML file (the nominal design).
    tolerances : sequence of Tolerance
        The fields' variations (:func:`parse_tolerance`, :func:`load_tolerances`).
    samples : int
        Number of Monte Carlo samples (1 to :data:`betvdesign.spec.limits.MAX_SAMPLES`).
    seed : int
        Seed of the draw.
    fidelity : {"periodic", "lambda"}
        The rung: the exact periodic orbit per sample (the reference) or the λ fit only.
    tol : float
        Fixed-point residual accepted for a periodic orbit [-].
    sets : sequence of str, optional
        Actuator sets analysed (None: every set).

    Returns
    -------
    Study
        One task per (sample, set), worker :func:`tolerance_point`.

    Raises
    ------
    UsageError
        Bad counts, seed, rung or set, no tolerance, the λ rung for a device or spread
        with damping or restitution, or a study over the time budget.
    """
    from betvdesign.spec.loader import load_device

    path = str(Path(device).resolve())
    spec = load_device(path)
    chosen = _chosen_sets(device, spec, tolerances, (samples, seed, fidelity), sets)
    limits.refuse_long_study("tolerance", samples * len(chosen), 0.0, 1)  # before drawing
    nominal = nominal_values(spec, tolerances)
    x = draw(tolerances, nominal, samples, seed)
    columns = dict(BASE_COLUMNS) | _beyond_columns(spec)
    columns |= {f"in:{t.field}": float for t in tolerances}
    mtime = os.stat(path).st_mtime_ns
    common = {"path": path, "mtime": mtime, "fidelity": fidelity, "tol": tol, "columns": columns}
    tasks = _tasks(spec, tolerances, nominal, x, chosen, common)
    params = {
        "device": path,
        "device_mtime_ns": mtime,
        "tolerances": [t.as_dict() for t in tolerances],
        "nominal": {k: list(v) for k, v in nominal.items()},
        "samples": samples,
        "sets": chosen,
        "fidelity": fidelity,
        "tol": tol,
    }
    return Study("tolerance", columns, params, tasks, tolerance_point, seed=seed)


def ranks(a: np.ndarray) -> np.ndarray:
    """Ranks 1..n of ``a``, ties given the mean of the ranks they span.

    Parameters
    ----------
    a : numpy.ndarray
        One-dimensional values (any unit).

    Returns
    -------
    numpy.ndarray
        The rank of each value [-], in ``a``'s order (ties averaged, as
        ``scipy.stats.rankdata``'s default).
    """
    a = np.asarray(a)
    order = np.argsort(a, kind="mergesort")
    s = a[order]
    first = np.r_[True, s[1:] != s[:-1]]  # where each run of equal values starts
    starts = np.flatnonzero(first)
    ends = np.r_[starts[1:], a.size]  # one past each run's end
    mean_rank = (starts + ends + 1) / 2.0  # mean of starts+1 .. ends
    out = np.empty(a.size, dtype=float)
    out[order] = mean_rank[np.cumsum(first) - 1]
    return out


def spearman(x: np.ndarray, y: np.ndarray) -> float | None:
    """Spearman rank correlation of the finite pairs of ``x`` and ``y``.

    The Pearson correlation of the ranks (:func:`ranks`, ties averaged), with numpy
    only: importing ``scipy.stats`` for it cost 0.45-0.6 s per summary (issue 33).

    Parameters
    ----------
    x, y : numpy.ndarray
        Paired values (any units); pairs with a non-finite member are left out.

    Returns
    -------
    float or None
        ρ in [-1, 1] [-]; None for fewer than three pairs or a constant side.
    """
    ok = np.isfinite(x) & np.isfinite(y)
    if ok.sum() < 3 or np.ptp(x[ok]) == 0 or np.ptp(y[ok]) == 0:
        return None
    # [1, 0] as scipy.stats.spearmanr reads it (the two divide in another order)
    return float(np.corrcoef(ranks(x[ok]), ranks(y[ok]))[1, 0])


def intended_sign(intended: str | None) -> float:
    """Sign of a set's travel: +1 for push, −1 for pull.

    +1 for a push set, −1 for a pull set: times a speed signed along the impact
    direction it gives the speed along the intended direction of travel.

    Parameters
    ----------
    intended : str or None
        The set's intended mode ("push" or "pull").

    Returns
    -------
    float
        +1 or −1.
    """
    return -1.0 if intended == "pull" else 1.0


def _set_summary(rs: list[Mapping[str, Any]], fidelity: str) -> dict[str, Any]:
    """The probabilities and speed percentiles of one set's rows.

    Parameters
    ----------
    rs : list of mapping
        The set's rows.
    fidelity : {"periodic", "lambda"}
        The rung the rows were made on.

    Returns
    -------
    dict
        Samples, P(push), P(pull), P(not converged), P(not driven), P(outside the window),
        P(wrong mode) [-] and the speed percentiles [um/s] (:func:`summarise`).
    """
    n = len(rs)
    valid = [r for r in rs if r["status"] != "invalid-sample"]
    mode_key = "mode" if fidelity == "periodic" else "lambda_mode"
    decided = [r for r in valid if r[mode_key] is not None]
    speeds = np.array([r["speed_um_s"] for r in valid if r["speed_um_s"] is not None])
    intended = rs[0]["intended"] if valid else None
    s: dict[str, Any] = {
        "samples": n,
        "invalid_samples": n - len(valid),
        "mode_from": "periodic orbit" if fidelity == "periodic" else "λ fit (stated rung)",
        "p_push": sum(r[mode_key] == "push" for r in decided) / n,
        "p_pull": sum(r[mode_key] == "pull" for r in decided) / n,
        "p_not_converged": (
            sum(not r["converged"] and r["status"] != "not_driven" for r in valid) / n
            if fidelity == "periodic"
            else None
        ),
        # a definite answer, not a failure: no contact recurs, the slider stays put
        "p_not_driven": (
            sum(r["status"] == "not_driven" for r in valid) / n if fidelity == "periodic" else None
        ),
        "p_outside_window": sum(not r["in_window"] for r in valid) / n,
        "intended_mode": intended,
        # the opposite of the intended mode (not converged counts separately)
        "p_wrong_mode": sum(r[mode_key] is not None and r[mode_key] != intended for r in valid) / n,
        # signed along the impact direction (+ push, − pull): README "Versioned outputs"
        "speed_um_s_percentiles": (
            {f"p{q:g}": float(np.percentile(speeds, q)) for q in PERCENTILES}
            if speeds.size
            else None
        ),
        # along the intended travel (+ the intended way): p5 is the slowest 5 %
        "intended_speed_um_s_percentiles": (
            {
                f"p{q:g}": float(np.percentile(speeds * intended_sign(intended), q))
                for q in PERCENTILES
            }
            if speeds.size
            else None
        ),
    }
    return s


def _sensitivities(
    valid: list[Mapping[str, Any]], tolerances: Sequence[Tolerance], fidelity: str
) -> tuple[list[dict[str, Any]], str]:
    """Spearman rank correlations of each input with λ and the speed, strongest first.

    Parameters
    ----------
    valid : list of mapping
        The set's rows of valid samples.
    tolerances : sequence of Tolerance
        The sampled fields.
    fidelity : {"periodic", "lambda"}
        The rung (the speed ranks on "periodic", λ on "lambda").

    Returns
    -------
    sensitivities : list of dict
        Per field its ρ with λ and with the speed [-].
    ranked_by : str
        The key they are ranked by.
    """
    sens = []
    for t in tolerances:
        xin = np.array([r[f"in:{t.field}"] for r in valid], dtype=float)
        lam = np.array([r["lam"] for r in valid], dtype=float)
        spd = np.array(
            [np.nan if r["speed_um_s"] is None else r["speed_um_s"] for r in valid], float
        )
        sens.append(
            {
                "field": t.field,
                "rho_lambda": spearman(xin, lam),
                "rho_speed": spearman(xin, spd),
            }
        )
    key = "rho_speed" if fidelity == "periodic" else "rho_lambda"
    sens.sort(key=lambda e: -abs(e[key] or 0.0))
    return sens, key


def summarise(
    rows: Sequence[Mapping[str, Any]],
    tolerances: Sequence[Tolerance],
    fidelity: str,
    *,
    coupled: Sequence[str] = (),
) -> dict[str, Any]:
    """Per actuator set: probabilities, speed percentiles, sensitivities.

    Parameters
    ----------
    rows : sequence of mapping
        The study's rows (:func:`tolerance_point`).
    tolerances : sequence of Tolerance
        The sampled fields.
    fidelity : {"periodic", "lambda"}
        The rung the rows were made on.
    coupled : sequence of str
        The sets whose ``betv check`` verdict is the coupled head's
        (:func:`coupled_sets`): their samples are solved with the paper's decoupled
        springs all the same, and their summary says so (``warning``:
        :data:`betvdesign.checks.coupled.DECOUPLED_WARNING`).

    Returns
    -------
    dict
        Rung, model statement and why, and per set (``warning`` where ``coupled``):
        P(push), P(pull), P(not converged), P(not driven), P(outside the window),
        P(wrong mode) [-], speed percentiles [um/s] signed along the impact direction and
        along the intended travel, Spearman rank correlations [-] of each input with λ and
        speed, and the first 50 failures; on the periodic rung ``p_pass``, the share of
        samples in which every set studied passes as ``betv fix --spread`` counts it
        (:func:`_p_pass`).
    """
    out: dict[str, Any] = {
        "fidelity": fidelity,
        "model": MODEL_STATEMENT[fidelity]
        + "; every sample derived by nondim.derive_samples (derive_set's formulas, vectorised)",
        "fidelity_reason": rung_reason(fidelity),
        "sets": {},
    }
    for name in dict.fromkeys(r["set"] for r in rows):
        rs = [r for r in rows if r["set"] == name]
        s = _set_summary(rs, fidelity)
        valid = [r for r in rs if r["status"] != "invalid-sample"]
        s["sensitivities"], s["ranked_by"] = _sensitivities(valid, tolerances, fidelity)
        s["failures"] = [
            {k: r[k] for k in ("key", "sample", "status", "message")}
            for r in rs
            if r["status"] == "invalid-sample" or (fidelity == "periodic" and not r["converged"])
        ][:50]
        if name in coupled:
            s["warning"] = DECOUPLED_WARNING
        out["sets"][name] = s
    if fidelity == "periodic":
        out |= _p_pass(rows)
    return out


def _p_pass(rows: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """P(pass) as ``betv fix --spread`` counts it, and the rules it counts.

    The share of samples in which every set studied passes
    (:func:`~betvdesign.studies.sampling.passes_spread_rules`; an invalid sample fails).
    """
    ok: dict[int, bool] = {}
    for r in rows:
        ok[r["sample"]] = ok.get(r["sample"], True) and bool(r.get("passes"))
    return {
        "p_pass": sum(ok.values()) / len(ok) if ok else None,
        "p_pass_rules": f"every set studied passes {spread_rules(target=False)} "
        "(as betv fix --spread counts it; no target speed)",
    }


def run_tolerance(
    device: str | os.PathLike[str], tolerances: Sequence[Tolerance], **kwargs: Any
) -> tuple[StudyRun, dict[str, Any]]:
    """Draw, run and summarise a tolerance analysis.

    Parameters
    ----------
    device : path
        Device YAML file.
    tolerances : sequence of Tolerance
        The fields' variations.
    **kwargs
        Keywords of :func:`tolerance_study` and of
        :class:`~betvdesign.studies.engine.runner.RunArgs` (executor, out, overwrite,
        progress).

    Returns
    -------
    tuple of (StudyRun, dict)
        The run (its rows) and :func:`summarise`'s summary.
    """
    study_kw, run = split_run_args(kwargs)
    study = tolerance_study(device, tolerances, **study_kw)
    result = run_study(study, **run)
    from betvdesign.spec.loader import load_device

    coupled = coupled_sets(load_device(device))
    return result, summarise(result.rows, tolerances, study.parameters["fidelity"], coupled=coupled)


def coupled_sets(spec: Any) -> list[str]:
    """The sets whose ``betv check`` verdict is the coupled head's, by name.

    The check's decision (:func:`betvdesign.checks.checker.coupled_head`) on the nominal
    device: a drawn head without measured resonances. A tolerance analysis solves their
    samples with the paper's decoupled springs all the same (not the check's model) and
    says so.

    Parameters
    ----------
    spec : DeviceSpec
        The device.

    Returns
    -------
    list of str
        The sets' names (none when the device does not derive: its samples say why).
    """
    from betvdesign.checks.checker import coupled_head
    from betvdesign.nondim.device import derive

    try:
        return [s.name for s in derive(spec).sets if coupled_head(s) is not None]
    except BetvError:
        return []
