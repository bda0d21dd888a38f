"""Calibration data: measured speeds or displacements read from a CSV with units.

Header cells read ``name [unit]`` (any unit of the right dimension), one row per
measurement, ``#`` lines are comments:

* speed against drive voltage: ``voltage [V], speed [um/s]`` and optionally
  ``sigma [um/s]`` (1σ of each speed);
* displacement against time (from rest, at the set's drive voltage):
  ``time [ms], displacement [um]`` and optionally ``sigma [um]``.

Values are converted to SI floats here; their sign convention is the calibration's
(:mod:`betvdesign.studies.calibration`).
"""

from __future__ import annotations

import csv
import math
import os
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

import numpy as np
import pint

from betvdesign.errors import UsageError

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
    """Read a calibration CSV (see module doc).

    Parameters
    ----------
    path : path
        The CSV file (header cells ``name [unit]``).
    kind : {"speed", "displacement"}
        Speed [any speed unit] against drive voltage [any voltage unit], or displacement
        [any length unit] against time [any time unit].

    Returns
    -------
    Measurements
        The data in SI floats: x [V or s], y [m/s or m], sigma [as y] or None.

    Raises
    ------
    UsageError
        A bad header, unit, number or row; the message names file, line and column.
    """
    from betvdesign.spec.safeyaml import read_text
    from betvdesign.spec.units import parse_units, ureg

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
