"""Validation study: the paper's Figs 3–12 recomputed with the exact model.

``run_validation()`` recomputes every figure of Shin et al. (2004) listed in the
restatement of its results, with the paper's parameters and initial conditions
(rest at τ = 0, a contact start), and returns one
:class:`~betvdesign.paper.common.Comparison` per published statement:
the published value, the computed one, the relative difference and the measured
explanation. The comparison is data: nothing here asserts that the paper is right,
and nothing is tuned to its numbers.

Parts: :mod:`~betvdesign.paper.vertical` (Figs 3–6), :mod:`~betvdesign.paper.maps`
(Figs 7, 8, 12), :mod:`~betvdesign.paper.slider` (Figs 9–11 and the device's dimensionless values).
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

from betvdesign.paper.common import PAPER, Comparison
from betvdesign.paper.maps import MapsPart, maps_part
from betvdesign.paper.slider import SliderPart, slider_part
from betvdesign.paper.vertical import VerticalPart, vertical_part

#: The published device shipped with the toolkit (relative to the repository root).
DEVICE_FILE = Path("devices") / "shin2004.yaml"

_FIG_ORDER = ("3", "4", "5", "6", "7", "8", "9a", "9b", "10", "11", "12", "device")


@dataclass
class ValidationStudy:
    """Everything the validation page shows (computed side only; plain data)."""

    paper: str
    device: Path
    vertical: VerticalPart
    maps: MapsPart
    slider: SliderPart
    elapsed_s: float

    @property
    def comparisons(self) -> list[Comparison]:
        """Every comparison row, in the paper's figure order."""
        rows = self.vertical.comparisons + self.maps.comparisons + self.slider.comparisons
        return sorted(rows, key=lambda c: _FIG_ORDER.index(c.fig))


def default_device() -> Path:
    """``devices/shin2004.yaml`` of the current directory, else of the source checkout."""
    here = Path.cwd() / DEVICE_FILE
    if here.is_file():
        return here
    return Path(__file__).resolve().parents[2] / DEVICE_FILE


def run_validation(device: str | Path | None = None, *, step: float = 0.005) -> ValidationStudy:
    """Recompute the paper's figures. ``device``: the published device's YAML (default
    :func:`default_device`); ``step``: ϖ spacing of the Figs 4/6 grid [-]."""
    path = Path(device) if device is not None else default_device()
    t0 = time.perf_counter()
    slider = slider_part(path)  # loads the device first: bad input fails before compute
    vertical = vertical_part(step)
    maps = maps_part()
    return ValidationStudy(PAPER, path, vertical, maps, slider, time.perf_counter() - t0)
