"""Figure functions of betvdesign.plots: geometry, reproducible SVG, no global state.

Sources: the λ = 1 curve is checked against the independent closed form
:func:`betvdesign.model.params.lambda_criterion` (MODEL.md, "Push/pull criterion");
SVG reproducibility and id hygiene are invariants checked on real output.
"""

from __future__ import annotations

import itertools
import re
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from matplotlib.axes import Axes

from betvdesign import plots
from betvdesign.model.params import lambda_criterion
from betvdesign.plots.phase import phase_runs

pos = st.floats(min_value=0.05, max_value=5.0, allow_nan=False)


@settings(max_examples=60, deadline=None)
@given(kappa=pos, beta=pos, varpi=st.floats(min_value=0.3, max_value=3.0))
def test_lambda_one_curve_is_lambda_equal_one(kappa: float, beta: float, varpi: float) -> None:
    """Points on the drawn boundary have λ = 1 by the independent λ formula."""
    y = float(plots.lambda_one_curve(np.array([1.0 / varpi**2]), kappa, beta)[0])
    if y <= 0:  # no positive α on the boundary there; nothing to draw
        return
    alpha = 1.0 / (y * kappa)
    assert lambda_criterion(varpi, alpha, beta, kappa) == pytest.approx(1.0, rel=1e-9)


def _svg_of(draw, key: str = "t1") -> str:
    with plots.figure_style():
        fig, ax = plots.new_figure()
        draw(ax)
        return plots.figure_svg(fig, key)


def _pushpull(ax: Axes) -> None:
    plots.pushpull_map(kappa=0.4, beta=0.9, points=[("dev", 0.9, 0.1)], ax=ax)


def test_svg_is_byte_reproducible_and_dateless() -> None:
    """The same figure twice gives identical bytes, without a date or XML prolog."""
    a, b = _svg_of(_pushpull), _svg_of(_pushpull)
    assert a == b
    assert a.startswith("<svg")
    assert "<dc:date>" not in a and "<?xml" not in a and "DOCTYPE" not in a


def test_svg_ids_prefixed_and_references_resolve() -> None:
    """Every id carries the figure key and every #reference points to an id of the SVG,
    so several figures can be inlined into one HTML page without collisions."""
    a = _svg_of(_pushpull, "figA")
    b = _svg_of(_pushpull, "figB")
    ids_a = set(re.findall(r'\bid="([^"]+)"', a))
    ids_b = set(re.findall(r'\bid="([^"]+)"', b))
    assert ids_a and all(i.startswith("figA-") for i in ids_a)
    assert not ids_a & ids_b
    refs = set(re.findall(r'(?:href="|url\()#([^")]+)', a))
    assert refs and refs <= ids_a


def test_bad_key_rejected() -> None:
    with pytest.raises(ValueError, match="identifier"):
        _svg_of(_pushpull, "bad key")


def test_pushpull_marks_device_and_curve() -> None:
    """The device lands at (1/ϖ², 1/(ακ)) inside the axes limits."""
    _fig, ax = plots.new_figure()
    plots.pushpull_map(kappa=0.4, beta=9.0, points=[("d", 0.34, 0.1)], ax=ax)
    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    assert x0 <= 1 / 0.34**2 <= x1 and y0 <= 1 / 0.04 <= y1
    markers = [ln for ln in ax.get_lines() if ln.get_marker() == "o"]
    assert len(markers) == 1
    np.testing.assert_allclose(markers[0].get_xydata()[0], [1 / 0.34**2, 25.0])


@settings(max_examples=50, deadline=None)
@given(st.lists(st.sampled_from(["free", "slip", "reverse", "stick"]), min_size=1, max_size=40))
def test_phase_runs_partition(labels: list[str]) -> None:
    """Runs cover every sample in order, are constant and maximal."""
    runs = phase_runs(labels)
    covered = []
    for start, stop, label in runs:
        assert stop > start and all(x == label for x in labels[start:stop])
        covered.extend(range(start, stop))
    assert covered == list(range(len(labels)))
    assert all(a[2] != b[2] for a, b in itertools.pairwise(runs))


def test_orbit_plane_colours_phases_and_rejects_unknown() -> None:
    tau = np.linspace(0, 2 * np.pi, 200)
    phases = ["free"] * 80 + ["slip"] * 50 + ["stick"] * 40 + ["reverse"] * 30
    ax = plots.orbit_plane(np.sin(tau), 0.5 * np.sin(tau), phases)
    labels = {ln.get_label() for ln in ax.get_lines()}
    assert {"no contact", "slip (ζ' > s')", "stick (ζ' = s')", "reverse slip (ζ' < s')"} <= labels
    with pytest.raises(ValueError, match="unknown phase"):
        plots.orbit_plane([0.0, 1.0], [0.0, 1.0], ["free", "flying"])
    with pytest.raises(ValueError, match="same length"):
        plots.orbit_plane([0.0, 1.0], [0.0], ["free", "free"])


def test_every_figure_function_draws_on_given_axes() -> None:
    """Each function draws on the ax it is given and returns it; None entries are
    drawn as markers, never silently dropped."""
    w = np.linspace(0.2, 3.0, 12)
    period = [1.0] * 10 + [None, None]
    frac = [0.4] * 10 + [None, None]
    cases = [
        lambda ax: plots.impact_period_strip(w, period, device_varpi=0.9, ax=ax),
        lambda ax: plots.contact_fraction_strip(w, frac, device_varpi=0.9, ax=ax),
        lambda ax: plots.vertical_phase_portrait(np.sin(w), np.cos(w), steady_from=5, ax=ax),
        lambda ax: plots.slider_velocity(
            w, np.sin(w), cycle_mean=([0, 1], [0.1, 0.2]), periodic_mean=0.15, ax=ax
        ),
        lambda ax: plots.slider_displacement(
            w, w**2, travel_um=4.0, extrapolated=([3, 4], [9, 16]), ax=ax
        ),
        lambda ax: plots.speed_vs_voltage(
            w, 2 * w, operating_v=1.0, operating_speed_m_s=2e-3, ax=ax
        ),
        lambda ax: plots.speed_vs_field_change(
            [("drive.frequency", w, [1e-3] * 11 + [None], [False] * 11 + [True])], ax=ax
        ),
        lambda ax: plots.pushpull_map_frequencies(
            f_v_hz=5e3, kappa=0.15, beta=0.5, points=[("d", 6e3, 3.5e3)], ax=ax
        ),
        lambda ax: plots.slider_velocity(
            w, w, time_scale=(0.1, "t [ms]"), velocity_scale=(2.0, "v [mm/s]"), ax=ax
        ),
        lambda ax: plots.orbit_plane(w, w, ["slip"] * 12, velocity_scale=(2.0, "mm/s"), ax=ax),
    ]
    for draw in cases:
        _fig, ax = plots.new_figure()
        assert draw(ax) is ax
        assert ax.get_lines(), draw
    ax = plots.impact_period_strip(w, period)
    crosses = [ln for ln in ax.get_lines() if ln.get_marker() == "x"]
    assert len(crosses) == 1 and len(crosses[0].get_xdata()) == 2


def test_plots_and_report_never_import_pyplot() -> None:
    """Figures use matplotlib.figure.Figure only: no pyplot global state."""
    code = (
        "import sys, betvdesign.plots, betvdesign.report;"
        "from betvdesign import plots;"
        "fig, ax = plots.new_figure(); plots.pushpull_map(kappa=.4, beta=.9,"
        " points=[('d', .9, .1)], ax=ax); plots.figure_svg(fig, 'k');"
        "print('matplotlib.pyplot' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_robustness_rings_fit_misses_and_prefixes_the_speed() -> None:
    """Points flagged as λ-fit misses are ringed, others not; speeds in m/s are drawn with
    the prefix their magnitude calls for (1.2e-3 m/s -> 1.2 mm/s)."""
    change = [-20.0, -10.0, 0.0, 10.0, 20.0]
    speed = [1.2e-3, 1.0e-3, 0.8e-3, -0.1e-3, None]
    miss = [False, True, False, True, False]
    ax = plots.speed_vs_field_change([("drive.frequency", change, speed, miss)], wrong_mode="pull")
    rings = [ln for ln in ax.get_lines() if ln.get_marker() == "o" and ln.get_markersize() == 9]
    assert len(rings) == 2  # the rings and their legend entry
    np.testing.assert_allclose(sorted(rings[0].get_xdata()), [-10.0, 10.0])
    np.testing.assert_allclose(rings[0].get_ydata(), [1.0, 0.1])  # magnitudes
    # the wrong-way point (+10 %: −0.1 mm/s against the intended direction) is squared
    squares = [ln for ln in ax.get_lines() if ln.get_marker() == "s" and len(ln.get_xdata())]
    (sq,) = squares
    np.testing.assert_allclose(sq.get_xdata(), [10.0])
    np.testing.assert_allclose(sq.get_ydata(), [0.1])
    assert "[mm/s]" in ax.get_ylabel() and ax.get_ylim()[0] == 0.0


def test_pushpull_frequency_map_boundary_is_lambda_one() -> None:
    """The black curve f_h(f_act) of the frequency map is λ = 1 (λ from ModelParams with
    ϖ = f_act/f_v, α = (f_v/f_h)², an independent formula)."""
    from betvdesign.model.params import ModelParams

    f_v, kappa, beta = 5e3, 0.15, 0.5
    ax = plots.pushpull_map_frequencies(
        f_v_hz=f_v, kappa=kappa, beta=beta, points=[("d", 6e3, 3.5e3)]
    )
    curve = next(ln for ln in ax.get_lines() if ln.get_label().startswith("λ = 1"))
    x, y = curve.get_xdata(), curve.get_ydata()
    for i in (50, 200, 350):
        p = ModelParams(x[i] * 1e3 / f_v, (f_v / (y[i] * 1e3)) ** 2, beta, kappa)
        assert p.lam == pytest.approx(1.0, rel=1e-9)
    texts = [t.get_text() for t in ax.texts]
    assert "λ = 1" in texts and "push (λ < 1)" in texts
    assert ax.get_xlabel().endswith("[kHz]") and ax.get_ylabel().endswith("[kHz]")


def test_displacement_stops_at_the_end_stop() -> None:
    """x(t) = t µm/ms reaches the 4 µm travel at 4 ms: the curve ends there, marked."""
    t = np.linspace(0.0, 10.0, 11)
    ax = plots.slider_displacement(t, t, travel_um=4.0, extrapolated=([10, 12], [10, 12]))
    sim = next(ln for ln in ax.get_lines() if ln.get_label().startswith("simulated"))
    assert sim.get_xdata()[-1] == pytest.approx(4.0) and max(sim.get_ydata()) == 4.0
    assert not any(ln.get_label().startswith("continued") for ln in ax.get_lines())
    # named in the legend (a label beside the marker crossed the curve)
    assert any("end stop at 4 ms" in ln.get_label() for ln in ax.get_lines())
    ax = plots.slider_displacement(t, -t / 2, travel_um=-4.0, extrapolated=None)
    sim = next(ln for ln in ax.get_lines() if ln.get_label().startswith("simulated"))
    assert sim.get_xdata()[-1] == pytest.approx(8.0) and min(sim.get_ydata()) == -4.0


def test_study_map_figure_is_readable(tmp_path) -> None:
    """`sweep pushpull --figure` with one (κ, β): at least 960 × 720 px as PNG, the λ = 1
    curve named on the plot, and the legend inside the saved figure."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from betvdesign.plots.studies import pushpull_figure, save_figure

    rows = [
        {
            "kappa": 0.4,
            "beta": 0.5,
            "varpi": w,
            "alpha": a,
            "status": "ok",
            "converged": True,
            "mode": m,
            "lambda_mode": m,
        }
        for w, a, m in [(0.9, 0.1, "pull"), (1.3, 4.0, "push"), (1.3, 0.1, "pull")]
    ]
    fig = pushpull_figure(rows)
    FigureCanvasAgg(fig).draw()
    out = tmp_path / "map.png"
    save_figure(fig, out)
    from PIL import Image

    w, h = Image.open(out).size
    assert w >= 960 and h >= 720
    ax = fig.axes[0]
    assert any(t.get_text() == "λ = 1" for t in ax.texts)
    (legend,) = fig.legends
    renderer = fig.canvas.get_renderer()
    box, page = legend.get_window_extent(renderer), fig.bbox
    assert page.x0 <= box.x0 and box.x1 <= page.x1 and page.y0 <= box.y0 and box.y1 <= page.y1
    assert "λ = 1 (fit boundary)" in [t.get_text() for t in legend.get_texts()]


def test_speed_vs_voltage_takes_si_and_prefixes() -> None:
    """Speeds are given in m/s and drawn with the prefix their magnitude calls for."""
    ax = plots.speed_vs_voltage([4.0, 8.0], [1e-4, 3e-4], operating_v=6.0, operating_speed_m_s=2e-4)
    assert ax.get_ylabel() == "mean slider speed  [µm/s]"
    np.testing.assert_allclose(ax.get_lines()[0].get_ydata(), [100.0, 300.0])
    assert any("200 µm/s" in ln.get_label() for ln in ax.get_lines())


def test_speed_vs_frequency_draws_magnitudes_in_the_modes_colours() -> None:
    """Issue 32 item 13: one convention: a speed is a magnitude, its mode's colour says
    the way. Velocities +0.2 and −0.3 mm/s along the impacts are drawn at 200 and
    300 µm/s, the first in push's colour, the second in pull's."""
    from betvdesign.output.presentation import MODE_COLORS

    ax = plots.speed_vs_frequency(
        [1e3, 2e3], [2e-4, -3e-4], [2e-4, -3e-4], f_v_hz=2e3, rolloff=False, operating=(2e3, -3e-4)
    )
    by_colour = {ln.get_color(): ln for ln in ax.get_lines() if ln.get_linestyle() == "None"}
    np.testing.assert_allclose(by_colour[MODE_COLORS["push"]].get_ydata(), [200.0])
    np.testing.assert_allclose(by_colour[MODE_COLORS["pull"]].get_ydata(), [300.0])
    assert any("300 µm/s" in ln.get_label() for ln in ax.get_lines())
    assert "-300" not in " ".join(ln.get_label() for ln in ax.get_lines())


def _extents(fig):
    """The rendered extents [px] of the axes, their legends and every non-tick text."""
    from matplotlib.axis import Tick
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.text import Text

    FigureCanvasAgg(fig).draw()
    r = fig.canvas.get_renderer()
    ticks = {id(x) for tk in fig.findobj(Tick) for x in (tk.label1, tk.label2)}
    texts = [
        t.get_window_extent(r)
        for t in fig.findobj(Text)
        if id(t) not in ticks and t.get_visible() and t.get_text().strip()
    ]
    return r, texts


@pytest.mark.parametrize(
    "draw",
    [
        lambda ax: plots.speed_vs_field_change(
            [(f"field {k}", [-10, 0, 10], [1e-3, 2e-3, -1e-3], [False] * 3) for k in range(7)],
            flips=[("field 0", 5.0)],
            wrong_mode="pull",
            ax=ax,
        ),
        lambda ax: plots.slider_velocity(
            np.linspace(0, 30, 300),
            np.sin(np.linspace(0, 30, 300)),
            cycle_mean=([0, 10, 20], [0.1, 0.2, 0.15]),
            periodic_mean=0.15,
            ax=ax,
        ),
        lambda ax: plots.orbit_plane(
            np.sin(np.arange(12.0)), np.cos(np.arange(12.0)), ["slip", "stick"] * 6, ax=ax
        ),
        lambda ax: plots.slider_displacement(
            np.linspace(0, 5, 50), -(np.linspace(0, 5, 50) ** 1.1), travel_um=-4.0, ax=ax
        ),
    ],
)
def test_legends_and_labels_stay_off_the_data_and_inside_the_figure(draw) -> None:
    """Issue 32 item 13: no legend over the curves (the legend lies outside the axes, or,
    for a small one kept inside, covers none of the drawn points) and no text clipped
    by the figure's edge, measured on the rendered figure."""
    fig, ax = plots.new_figure(6.4, 4.4)
    draw(ax)
    r, texts = _extents(fig)
    page = fig.bbox
    for e in texts:
        assert page.x0 - 1 <= e.x0 and e.x1 <= page.x1 + 1 and page.y0 - 1 <= e.y0, e
        assert e.y1 <= page.y1 + 1, e
    legend = ax.get_legend().get_window_extent(r)
    for line in ax.get_lines():
        xy = line.get_xydata()
        if not len(xy):
            continue
        px = ax.transData.transform(np.asarray(xy, float))
        px = px[np.all(np.isfinite(px), axis=1)]
        inside = (
            (px[:, 0] > legend.x0)
            & (px[:, 0] < legend.x1)
            & (px[:, 1] > legend.y0)
            & (px[:, 1] < legend.y1)
        )
        assert not inside.any(), line.get_label()
