"""The page's exact-mode map of two fields: its figure, its computation and what is on it.

``box`` (figure, axis choices, legend) and ``status`` (the progress line) are separate
roots of the page, so a progress line does not lay the figure out again.

The map (:mod:`betvdesign.studies.fieldmap`) is computed on the "map" worker lane a few
rows per job and drawn as the rows arrive; it is recomputed only when a field off its
axes changes (the key of :meth:`MapView.key`). On it: the design (a star), the changes
``betv fix`` finds that lie in the map's plane (diamonds, dashed from the design), and
paler colours where the design window 0.5 ≤ ϖ < 2 is left. A click hands the clicked point
to ``on_move(changes, fields)``.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from typing import Any

from bokeh.events import Tap
from bokeh.layouts import column, row
from bokeh.models import ColumnDataSource, Div, HoverTool, Select
from bokeh.plotting import figure

from betvdesign.explore import jobs
from betvdesign.explore.design import set_path
from betvdesign.explore.fields import FieldControl, current_value
from betvdesign.explore.views import MAP_COLUMNS, legend_html, map_cells, status_html
from betvdesign.studies.fieldmap import FieldAxis, FieldMap, MapRows

#: Points per axis and rows per worker job.
MAP_POINTS = 24
MAP_CHUNK = 3
#: Default axes: x, then the first y the set gives.
MAP_X = ("drive.frequency",)
MAP_Y = (
    "slider.beam_width",
    "actuator.horizontal_resonance",
    "actuator.horizontal_stiffness",
    "actuator.alpha",
)
_FIX_COLUMNS = ("x", "y", "x0", "y0", "label")

__all__ = ["MAP_CHUNK", "MAP_POINTS", "MapView"]


def axis_value(spec: Any, set_index: int, c: FieldControl) -> float | None:
    """The design's value of a control's field in the control's unit (None: absent)."""
    v = current_value(spec, set_index, c.field)
    if v is None:
        return None
    return float(v.to(c.unit).magnitude) if hasattr(v, "units") else float(v)


def _inside(c: FieldControl, v: float | None) -> bool:
    """Whether ``v`` lies on the map's axis of control ``c`` (its slider range)."""
    return v is not None and c.lo <= v <= c.hi


def _fix_value(axis: FieldControl, values: dict[str, Any], current: float) -> float:
    """A fix's value of the field on ``axis`` (in the axis unit), else ``current``."""
    from betvdesign.spec.units import ureg

    if axis.field not in values:
        return current
    x, unit = values[axis.field]
    return float(ureg.Quantity(x, unit).to(axis.unit).magnitude) if unit else float(x)


class MapView:
    """The map panel (see the module docstring); ``controls()`` gives the current
    :class:`~betvdesign.explore.fields.FieldControl` by field, ``set_name()`` the set
    edits go to; ``guard(fn)`` wraps every widget callback."""

    def __init__(
        self,
        controls: Callable[[], dict[str, FieldControl]],
        set_name: Callable[[], str | None],
        on_move: Callable[[dict[str, Any], frozenset[str]], None],
        on_axes: Callable[[], None],
        guard: Callable[[Callable[..., None]], Callable[..., None]] = lambda fn: fn,
    ) -> None:
        self.guard = guard
        self.controls = controls
        self.set_name = set_name
        self.on_move = on_move
        self.on_axes = on_axes
        self.fmap: FieldMap | None = None
        self.computed_key: Any = None
        opts = self.options()
        x = next((f for f in MAP_X if f in opts), opts[0])
        y = next((f for f in MAP_Y if f in opts and f != x), next(f for f in opts if f != x))
        self.x_select = Select(title="map x", options=opts, value=x, width=220)
        self.y_select = Select(title="map y", options=opts, value=y, width=220)
        self.x_select.on_change("value", guard(partial(self._on_axis, self.x_select)))
        self.y_select.on_change("value", guard(partial(self._on_axis, self.y_select)))
        self.cells = ColumnDataSource(data={k: [] for k in MAP_COLUMNS})
        self.device = ColumnDataSource(data={"x": [], "y": []})
        self.fixes = ColumnDataSource(data={k: [] for k in _FIX_COLUMNS})
        self.status = Div(text="", width=460, height=20, css_classes=["betv-map-status"])
        self.fig = self._figure()
        self.box = column(
            self.fig, row(self.x_select, self.y_select), Div(text=legend_html(), width=460)
        )

    def options(self) -> list[str]:
        return [
            f
            for f, c in self.controls().items()
            if c.kind in ("quantity", "number") and not c.optional
        ]

    def axes(self) -> tuple[FieldControl, FieldControl]:
        ctl = self.controls()
        return ctl[self.x_select.value], ctl[self.y_select.value]

    def rebuild(self) -> None:
        """After the controls changed (another set): keep axes the set has."""
        opts = self.options()
        for sel, default in ((self.x_select, opts[0]), (self.y_select, opts[1])):
            sel.options = opts
            if sel.value not in opts:
                sel.value = default
        self.computed_key = None

    def _on_axis(self, widget: Select, attr: str, old: Any, new: Any) -> None:
        if self.x_select.value == self.y_select.value:  # one field on both axes: swap
            other = self.y_select if widget is self.x_select else self.x_select
            other.value = old
            return
        self.fig = self._figure()
        self.box.children = [self.fig, *self.box.children[1:]]
        self.computed_key = None
        self.fmap = None
        self.on_axes()

    def _figure(self) -> Any:
        cx, cy = self.axes()
        fig = figure(
            width=460,
            height=400,
            title="Exact mode (click to move the design there)",
            x_axis_type="log" if cx.log else "linear",
            y_axis_type="log" if cy.log else "linear",
            x_axis_label=f"{cx.field} [{cx.unit or '-'}]",
            y_axis_label=f"{cy.field} [{cy.unit or '-'}]",
            x_range=(cx.lo, cx.hi),
            y_range=(cy.lo, cy.hi),
            tools="tap",
            toolbar_location=None,
            css_classes=["betv-map"],
        )
        quads = fig.quad(
            "left",
            "right",
            "top",
            "bottom",
            source=self.cells,
            fill_color="color",
            line_color=None,
            nonselection_fill_alpha=1.0,  # a click moves the design, it selects nothing
        )
        tips = [
            ("mode", "@mode"),
            ("speed", "@speed"),
            ("basis", "@basis"),
            ("ϖ", "@varpi @window"),
            ("x", "@xv"),
            ("y", "@yv"),
        ]
        fig.add_tools(HoverTool(renderers=[quads], tooltips=tips))
        # the design and the fixes are on the plot's overlay canvas: moving them repaints
        # that layer only, not the map's cells and axes (Bokeh repaints its primary canvas
        # only for a change below level "overlay"); that layer is not clipped to the
        # frame, so only points inside the axes are drawn (:func:`_inside`)
        fig.segment(
            "x0",
            "y0",
            "x",
            "y",
            source=self.fixes,
            line_color="#0969da",
            line_dash="dashed",
            line_width=2,
            level="overlay",
        )
        fig.scatter(
            "x",
            "y",
            source=self.fixes,
            marker="diamond",
            size=14,
            fill_color="#0969da",
            line_color="white",
            level="overlay",
        )
        fig.scatter(
            "x",
            "y",
            source=self.device,
            marker="star",
            size=18,
            fill_color="#cf222e",
            line_color="black",
            level="overlay",
        )
        for r in fig.renderers[1:]:
            r.nonselection_glyph = r.glyph
        fig.on_event(Tap, self.guard(self._on_tap))
        return fig

    def _on_tap(self, event: Any) -> None:
        if event.x is None or event.y is None:
            return
        cx, cy = self.axes()
        x = min(max(float(event.x), cx.lo), cx.hi)
        y = min(max(float(event.y), cy.lo), cy.hi)
        name = self.set_name()
        self.on_move(
            {
                set_path(cx.field, name): cx.file_value(cx.text(x)),
                set_path(cy.field, name): cy.file_value(cy.text(y)),
            },
            frozenset([cx.field, cy.field]),
        )

    # --- the design and the fixes on the map -----------------------------------------------

    def show_design(self, spec: Any, set_index: int) -> None:
        cx, cy = self.axes()
        x, y = axis_value(spec, set_index, cx), axis_value(spec, set_index, cy)
        shown = _inside(cx, x) and _inside(cy, y)
        self.device.data = {"x": [x] if shown else [], "y": [y] if shown else []}

    def show_fixes(self, fixes: list[dict[str, Any]], spec: Any, set_index: int) -> None:
        """Draw the fixes whose changed fields are on the map's axes."""
        cx, cy = self.axes()
        x0, y0 = axis_value(spec, set_index, cx), axis_value(spec, set_index, cy)
        pts: dict[str, list[Any]] = {k: [] for k in _FIX_COLUMNS}
        for k, c in enumerate(fixes):
            values = c["values"]
            if set(values) <= {cx.field, cy.field} and _inside(cx, x0) and _inside(cy, y0):
                x, y = _fix_value(cx, values, x0), _fix_value(cy, values, y0)  # type: ignore[arg-type]
                if not (_inside(cx, x) and _inside(cy, y)):
                    continue
                pts["x"].append(x)
                pts["y"].append(y)
                pts["x0"].append(x0)
                pts["y0"].append(y0)
                pts["label"].append(str(k + 1))
        self.fixes.data = pts

    # --- computing the map -------------------------------------------------------------------

    def key(self, edits: dict[str, Any], set_index: int) -> Any:
        """What the map depends on: the set, the axes and every edit off the axes."""
        fx, fy = self.x_select.value, self.y_select.value
        off = tuple((p, str(v)) for p, v in edits.items() if not _on(p, (fx, fy)))
        return (set_index, fx, fy, off)

    @property
    def busy(self) -> bool:
        return self.fmap is not None and not self.fmap.complete

    def start(
        self,
        key: Any,
        text: str,
        filename: str,
        set_index: int,
        set_label: str,
        submit: Callable[..., None],
    ) -> bool:
        """Queue the map for ``key`` (unless it is the one shown): ``submit(fn, args,
        done)`` puts a job on the map lane. True when a new map was started."""
        if key == self.computed_key:
            return False
        self.computed_key = key
        cx, cy = self.axes()
        x = FieldAxis.spanning(cx.field, cx.unit, cx.lo, cx.hi, MAP_POINTS, log=cx.log)
        y = FieldAxis.spanning(cy.field, cy.unit, cy.lo, cy.hi, MAP_POINTS, log=cy.log)
        fresh = self.fmap is None or (self.fmap.x, self.fmap.y) != (x, y)
        self.fmap = FieldMap.empty(x, y, set_label)
        if fresh:
            self.cells.data = map_cells(self.fmap)
        self.status.text = status_html(f"map: 0/{MAP_POINTS} rows", busy=True)
        for start in range(0, MAP_POINTS, MAP_CHUNK):
            rows = list(range(start, min(MAP_POINTS, start + MAP_CHUNK)))
            submit(jobs.map_job, (text, filename, set_index, x, y, rows), self.fmap)
        return True

    def add_rows(self, fmap: FieldMap, result: dict[str, Any] | None) -> None:
        """Draw rows a map job returned (ignored when that map is no longer shown)."""
        if result is None or fmap is not self.fmap:
            return
        part = MapRows(
            tuple(result["rows"]),
            result["mode"],
            result["delta_s"],
            result["speed_m_s"],
            result["varpi"],
            {(j, i): r for j, i, r in result["reasons"]},
            result.get("basis") or [],
        )
        fmap.fill(part)
        nx = len(fmap.x.values)
        cells = map_cells(fmap)
        if len(self.cells.data["color"]) == len(cells["color"]):
            names = ("color", "mode", "speed", "window", "varpi", "basis")
            ks = [j * nx + i for j in part.rows for i in range(nx)]
            self.cells.patch({n: [(k, cells[n][k]) for k in ks] for n in names})
        else:
            self.cells.data = cells
        done, total = int(fmap.done.sum()), len(fmap.y.values)
        self.status.text = status_html(
            f"map: {done}/{total} rows"
            if done < total
            else f"map of set {fmap.set_name}: {total}×{nx} exact orbits",
            busy=done < total,
        )

    def failed(self, message: str) -> None:
        self.status.text = status_html(message, busy=False)


def _on(path: str, fields: tuple[str, ...]) -> bool:
    """An edit path that sets one of ``fields`` (for every set or for one)."""
    if path in fields:
        return True
    parts = path.split(".", 2)
    return parts[0] == "actuator_sets" and len(parts) == 3 and parts[2] in fields
