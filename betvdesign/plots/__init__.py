"""Figures of the BETV toolkit: object-oriented matplotlib, one module per family.

Every function draws on the ``ax=`` it is given (or a fresh
:class:`matplotlib.figure.Figure` when None) from plain, unit-free or explicitly
unit-suffixed arrays; none computes physics. :func:`figure_svg` turns a figure
into byte-reproducible inline SVG, :func:`figure_png` into a reproducible PNG.
"""

from betvdesign.plots.adequacy import mode_speed_scan
from betvdesign.plots.figure import (
    figure_png,
    figure_style,
    figure_svg,
    figure_svg_png,
    new_figure,
)
from betvdesign.plots.phase import orbit_plane, vertical_phase_portrait
from betvdesign.plots.pushpull import lambda_one_curve, pushpull_map, pushpull_map_frequencies
from betvdesign.plots.regime import contact_fraction_strip, impact_period_strip
from betvdesign.plots.sweeps import (
    robustness_vs_lambda,
    speed_vs_field_change,
    speed_vs_frequency,
    speed_vs_voltage,
)
from betvdesign.plots.thermal import stroke_vs_frequency, stroke_vs_voltage
from betvdesign.plots.timeseries import slider_displacement, slider_velocity

__all__ = [
    "contact_fraction_strip",
    "figure_png",
    "figure_style",
    "figure_svg",
    "figure_svg_png",
    "impact_period_strip",
    "lambda_one_curve",
    "mode_speed_scan",
    "new_figure",
    "orbit_plane",
    "pushpull_map",
    "pushpull_map_frequencies",
    "robustness_vs_lambda",
    "slider_displacement",
    "slider_velocity",
    "speed_vs_field_change",
    "speed_vs_frequency",
    "speed_vs_voltage",
    "stroke_vs_frequency",
    "stroke_vs_voltage",
    "vertical_phase_portrait",
]
