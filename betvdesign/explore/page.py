"""One browser session of ``betv explore``: the Bokeh document and what its controls do.

Flow of a change (the latest value wins, stale work is dropped):

1. a control moves (browser -> websocket -> a Bokeh callback on the server's loop): the
   change is queued on the session and the callback returns at once;
2. one thread per server drains the queue: every queued change is applied at once
   through the device file's validation (:meth:`Design.apply`; a refused value gives its
   control the loader's message and leaves the design as it was), then the "orbit"
   stage is computed (:func:`betvdesign.explore.compute.evaluate`) and handed back to the
   loop, which redraws the verdict and the orbit;
3. once the design has been still for :data:`SETTLE_MS`, the slow stages (settling,
   model adequacy, and the fix search when the verdict fails) and, when a field off the
   map's axes changed, the map go to the worker processes
   (:class:`betvdesign.explore.jobs.Workers`) and arrive progressively; the page lists
   what is still computing.
"""

from __future__ import annotations

import contextlib
import math
import secrets
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import Any

from bokeh.events import Tap
from bokeh.layouts import column, row
from bokeh.models import (
    Button,
    ColumnDataSource,
    Div,
    HoverTool,
    Select,
    Slider,
    TextInput,
)
from bokeh.plotting import figure

from betvdesign.errors import BetvError, SpecError
from betvdesign.explore import jobs
from betvdesign.explore.compute import STAGES, Evaluation, evaluate
from betvdesign.explore.design import Design, free_name, set_path
from betvdesign.explore.fields import FieldControl, designer_fields
from betvdesign.explore.views import (
    MAP_COLUMNS,
    error_html,
    legend_html,
    map_cells,
    status_html,
    verdict_html,
)
from betvdesign.studies.fieldmap import FieldAxis, FieldMap, MapRows

#: Quiet time after the last change before the slow stages start [ms].
SETTLE_MS = 250
#: Map resolution (points per axis) and rows per worker job.
MAP_POINTS = 24
MAP_CHUNK = 3
#: Fix candidates listed (each with an "apply" button).
MAX_FIXES = 4
#: Slider positions per control.
SLIDER_STEPS = 200
#: Default map axes: x, then the first y the set gives.
MAP_X = ("drive.frequency",)
MAP_Y = (
    "slider.beam_width",
    "actuator.horizontal_resonance",
    "actuator.horizontal_stiffness",
    "actuator.alpha",
)
ALL_SETS = "all sets"


@dataclass
class ExploreApp:
    """What every session of one ``betv explore`` server shares.

    text, filename: the device file; options: ``target_speed_m_s``, ``select``,
    ``ignore`` (as ``betv check``); workers: the job lanes; reports: finished report
    HTML by token (served by the server's report handler); compute: the thread that
    computes the orbit stage.
    """

    text: str
    filename: str
    options: dict[str, Any]
    workers: jobs.Workers
    reports: dict[str, tuple[str, str]] = field(default_factory=dict)
    compute: ThreadPoolExecutor = field(
        default_factory=lambda: ThreadPoolExecutor(1, thread_name_prefix="betv-explore")
    )

    def __call__(self, doc: Any) -> None:
        """Bokeh's application hook: a new page."""
        ExplorePage(doc, self)


def _on_axis(axis: FieldControl, values: dict[str, Any], current: float) -> float:
    """A fix's value of the field on ``axis`` (in the axis unit), else ``current``."""
    from betvdesign.spec.units import ureg

    if axis.field not in values:
        return current
    x, unit = values[axis.field]
    return float(ureg.Quantity(x, unit).to(axis.unit).magnitude) if unit else float(x)


def _spec_message(exc: SpecError) -> str:
    return "; ".join(f"{i.field}: {i.message}" if i.field else i.message for i in exc.issues)


@dataclass
class _Control:
    """The widgets of one field."""

    spec: FieldControl
    widget: Any  # Slider or Select
    text: TextInput | None
    message: Div
    box: Any


class ExplorePage:
    """One page (see the module docstring)."""

    def __init__(self, doc: Any, app: ExploreApp) -> None:
        self.doc = doc
        self.app = app
        self.design = Design(app.text, app.filename)
        self.dlock = threading.RLock()  # the design (compute thread and loop)
        self.qlock = threading.Lock()  # the queue of changes
        self.queue: dict[str, tuple[Any, frozenset[str]]] = {}
        self.running = False
        self.since = math.inf  # when the oldest queued change arrived [perf_counter s]
        self.timing: tuple[float, float] = (math.nan, math.nan)
        self.closed = False
        self.seq = 0
        self.slot = app.workers.slot()
        self.quiet = False
        self.slow_timer: Any = None
        self.pending: dict[str, str] = {}
        self.last: Evaluation | None = None
        self.settling: dict[str, Any] = {}
        self.map_key: Any = None
        self.fmap: FieldMap | None = None
        self.fixes: list[dict[str, Any]] = []
        self.fix_seq = -1
        names = [s.name for s in self.design.original.actuator_sets]
        self.set_names = names
        self.set_select = Select(
            title="actuator set",
            options=([ALL_SETS] if len(names) > 1 else []) + names,
            value=ALL_SETS if len(names) > 1 else names[0],
            width=200,
        )
        self.set_select.on_change("value", self._on_set)
        self.controls: dict[str, _Control] = {}
        self.controls_box = column()
        self._build_controls()
        self._build_views()
        self._build_map()
        self._build_actions()
        doc.title = f"betv explore: {self.design.original.name}"
        header = Div(
            text=f"<b style='font-size:18px'>betv explore</b> · {self.design.original.name} "
            f"<span style='color:#57606a'>({Path(app.filename).name})</span>",
            width=900,
        )
        left = column(self.set_select, self.controls_box, width=390)
        middle = column(self.verdict, self.status, row(self.phase_fig, self.disp_fig), width=760)
        right = column(
            self.map_fig,
            self.map_axes,
            self.legend,
            self.map_status,
            self.fix_box,
            self.save_box,
            self.report_box,
            width=470,
        )
        doc.add_root(column(header, row(left, middle, right)))
        doc.on_session_destroyed(self._destroyed)
        self._request({}, frozenset())

    # --- widgets -----------------------------------------------------------------------

    @property
    def set_index(self) -> int:
        v = self.set_select.value
        return self.set_names.index(v) if v in self.set_names else 0

    @property
    def set_name(self) -> str | None:
        v = self.set_select.value
        return (
            v if v in self.set_names else (self.set_names[0] if len(self.set_names) == 1 else None)
        )

    def _build_controls(self) -> None:
        self.controls = {}
        boxes: list[Any] = []
        group = ""
        for c in designer_fields(self.design.original, self.set_index):
            if c.group != group:
                group = c.group
                boxes.append(Div(text=f"<b>{group}</b>", margin=(8, 5, 0, 5)))
            boxes.append(self._control(c))
        self.controls_box.children = boxes
        self._sync_controls()

    def _control(self, c: FieldControl) -> Any:
        css = ["betv-control", "betv-field-" + c.field.replace(".", "-").replace("_", "-")]
        message = Div(
            text="", width=360, css_classes=["betv-message", *css[1:]], margin=(0, 5, 4, 5)
        )
        if c.kind == "choice":
            widget = Select(
                title=c.label,
                options=list(c.choices),
                value=str(c.value),
                width=200,
                css_classes=css,
            )
            widget.on_change("value", partial(self._on_choice, c))
            box = column(widget, message)
            self.controls[c.field] = _Control(c, widget, None, message, box)
            return box
        lo, hi = (math.log10(c.lo), math.log10(c.hi)) if c.log else (c.lo, c.hi)
        step = 1.0 if c.kind == "integer" else (hi - lo) / SLIDER_STEPS
        v = self._slider_value(c, c.value if c.value is not None else c.lo)
        widget = Slider(
            title=c.label,
            start=lo,
            end=hi,
            value=v,
            step=step,
            show_value=False,
            width=230,
            css_classes=[*css, "betv-slider"],
        )
        text = TextInput(value=c.text(c.value), width=120, css_classes=[*css, "betv-text"])
        widget.on_change("value", partial(self._on_slider, c))
        text.on_change("value", partial(self._on_text, c))
        box = column(row(widget, text), message)
        self.controls[c.field] = _Control(c, widget, text, message, box)
        return box

    @staticmethod
    def _slider_value(c: FieldControl, x: Any) -> float:
        try:
            x = float(x)
        except (TypeError, ValueError):
            return math.nan
        if c.log:
            return math.log10(x) if x > 0 else math.nan
        return x

    def _build_views(self) -> None:
        self.verdict = Div(
            text="<i>computing the exact orbit…</i>", width=740, css_classes=["betv-verdict-box"]
        )
        self.status = Div(text="", width=740, css_classes=["betv-status"])
        self.phase_src = ColumnDataSource(data={"x": [], "y": []})
        self.disp_src = ColumnDataSource(data={"x": [], "y": []})
        self.phase_fig = figure(
            width=370,
            height=300,
            title="Head gap and its rate (one period)",
            x_axis_label="head gap [µm]",
            y_axis_label="gap rate [mm/s]",
            toolbar_location=None,
        )
        self.phase_fig.line("x", "y", source=self.phase_src, line_width=2, color="#d95f02")
        self.disp_fig = figure(
            width=370,
            height=300,
            title="Slider position on the periodic orbit",
            x_axis_label="time [ms]",
            y_axis_label="slider x [µm]",
            toolbar_location=None,
        )
        self.disp_fig.line("x", "y", source=self.disp_src, line_width=2, color="#1b9e77")

    def _axis_options(self) -> list[str]:
        return [
            f
            for f, c in self.controls.items()
            if c.spec.kind in ("quantity", "number") and not c.spec.optional
        ]

    def _build_map(self) -> None:
        opts = self._axis_options()
        x = next((f for f in MAP_X if f in opts), opts[0])
        y = next((f for f in MAP_Y if f in opts and f != x), next(f for f in opts if f != x))
        self.map_x = Select(title="map x", options=opts, value=x, width=220)
        self.map_y = Select(title="map y", options=opts, value=y, width=220)
        self.map_x.on_change("value", partial(self._on_axes, self.map_x))
        self.map_y.on_change("value", partial(self._on_axes, self.map_y))
        self.map_axes = row(self.map_x, self.map_y)
        self.map_src = ColumnDataSource(data={k: [] for k in MAP_COLUMNS})
        self.dev_src = ColumnDataSource(data={"x": [], "y": []})
        self.fix_src = ColumnDataSource(data={"x": [], "y": [], "x0": [], "y0": [], "label": []})
        self.legend = Div(text=legend_html(), width=460)
        self.map_status = Div(text="", width=460, css_classes=["betv-map-status"])
        self.map_fig = Div()  # replaced by _new_map_figure
        self._new_map_figure()

    def _new_map_figure(self) -> None:
        cx, cy = self.controls[self.map_x.value].spec, self.controls[self.map_y.value].spec
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
            source=self.map_src,
            fill_color="color",
            line_color=None,
            hatch_pattern="hatch",
            hatch_color="#444444",
            hatch_alpha=0.35,
            hatch_scale=8,
        )
        fig.add_tools(
            HoverTool(
                renderers=[quads],
                tooltips=[
                    ("mode", "@mode"),
                    ("speed", "@speed"),
                    ("ϖ", "@varpi"),
                    ("x", "@xv"),
                    ("y", "@yv"),
                ],
            )
        )
        fig.segment(
            "x0",
            "y0",
            "x",
            "y",
            source=self.fix_src,
            line_color="#0969da",
            line_dash="dashed",
            line_width=2,
        )
        fig.scatter(
            "x",
            "y",
            source=self.fix_src,
            marker="diamond",
            size=14,
            fill_color="#0969da",
            line_color="white",
        )
        fig.scatter(
            "x",
            "y",
            source=self.dev_src,
            marker="star",
            size=18,
            fill_color="#cf222e",
            line_color="black",
        )
        fig.on_event(Tap, self._on_tap)
        self.map_fig = fig

    def _build_actions(self) -> None:
        self.fix_div = Div(text="", width=460, css_classes=["betv-fixes"])
        self.fix_buttons = []
        for k in range(MAX_FIXES):
            b = Button(
                label=f"apply fix {k + 1}",
                visible=False,
                width=140,
                css_classes=["betv-apply-fix", f"betv-apply-fix-{k + 1}"],
            )
            b.on_click(partial(self._on_apply_fix, k))
            self.fix_buttons.append(b)
        self.fix_box = column(self.fix_div, row(*self.fix_buttons[:2]), row(*self.fix_buttons[2:]))
        original = Path(self.app.filename)
        default = free_name(
            original.with_name(f"{original.stem}-explored{original.suffix or '.yaml'}")
        )
        self.save_name = TextInput(
            title="save as (beside the device file)",
            value=default.name,
            width=300,
            css_classes=["betv-save-name"],
        )
        self.save_button = Button(
            label="Save YAML", button_type="primary", width=110, css_classes=["betv-save"]
        )
        self.overwrite_button = Button(
            label="Overwrite",
            button_type="danger",
            width=110,
            visible=False,
            css_classes=["betv-overwrite"],
        )
        self.save_msg = Div(text="", width=460, css_classes=["betv-save-message"])
        self.save_button.on_click(lambda: self._on_save(False))
        self.overwrite_button.on_click(lambda: self._on_save(True))
        self.save_box = column(
            row(self.save_name, self.save_button), self.overwrite_button, self.save_msg
        )
        self.report_button = Button(
            label="Build report (HTML)", width=180, css_classes=["betv-report"]
        )
        self.report_msg = Div(text="", width=460, css_classes=["betv-report-link"])
        self.report_button.on_click(self._on_report)
        self.report_box = column(self.report_button, self.report_msg)

    # --- control callbacks (on the server's loop) ---------------------------------------

    def _on_slider(self, c: FieldControl, attr: str, old: Any, new: Any) -> None:
        if self.quiet:
            return
        x = 10.0**new if c.log else float(new)
        text = c.text(round(x) if c.kind == "integer" else x)
        ctl = self.controls[c.field]
        with self._quietly():
            ctl.text.value = text  # type: ignore[union-attr]
        self._request({set_path(c.field, self.set_name): c.file_value(text)}, frozenset([c.field]))

    def _on_text(self, c: FieldControl, attr: str, old: Any, new: Any) -> None:
        if self.quiet:
            return
        self._request({set_path(c.field, self.set_name): c.file_value(new)}, frozenset([c.field]))

    def _on_choice(self, c: FieldControl, attr: str, old: Any, new: Any) -> None:
        if self.quiet:
            return
        self._request({set_path(c.field, self.set_name): new}, frozenset([c.field]))

    def _on_set(self, attr: str, old: Any, new: Any) -> None:
        self._build_controls()
        self.map_key = None
        if self.last is not None:
            self._show_traces(self.last)
        self._schedule_slow()

    def _on_axes(self, widget: Select, attr: str, old: Any, new: Any) -> None:
        if self.map_x.value == self.map_y.value:  # one field on both axes: swap them
            other = self.map_y if widget is self.map_x else self.map_x
            other.value = old
            return
        self._new_map_figure()
        self._relayout()
        self.map_key = None
        self._show_device()
        self._show_fixes()
        self._schedule_slow(0)

    def _relayout(self) -> None:
        right = self.doc.roots[0].children[1].children[2]
        right.children = [self.map_fig, *right.children[1:]]

    def _on_tap(self, event: Any) -> None:
        cx, cy = self.controls[self.map_x.value].spec, self.controls[self.map_y.value].spec
        if event.x is None or event.y is None:
            return
        x = min(max(float(event.x), cx.lo), cx.hi)
        y = min(max(float(event.y), cy.lo), cy.hi)
        self._request(
            {
                set_path(cx.field, self.set_name): cx.file_value(cx.text(x)),
                set_path(cy.field, self.set_name): cy.file_value(cy.text(y)),
            },
            frozenset([cx.field, cy.field]),
        )

    def _on_apply_fix(self, k: int) -> None:
        if k >= len(self.fixes):
            return
        values = self.fixes[k]["file_values"]
        self._request({f: v for f, v in values.items()}, frozenset(values))

    def _on_save(self, overwrite: bool) -> None:
        name = self.save_name.value.strip()
        try:
            with self.dlock:
                res = self.design.save(name, overwrite=overwrite)
        except BetvError as exc:
            self.save_msg.text = status_html(f"not saved: {exc}", busy=False)
            return
        self.overwrite_button.visible = not res.written and res.path.exists()
        self.save_msg.text = status_html(res.message, busy=False)
        if res.written:
            self.save_msg.text += f'<span class="betv-saved" data-path="{res.path}"></span>'

    def _on_report(self) -> None:
        with self.dlock:
            try:
                text = self.design.yaml_text()
            except BetvError as exc:
                self.report_msg.text = status_html(f"no report: {exc}", busy=False)
                return
        target = Path(self.app.filename).with_name(self.save_name.value.strip() or "design.yaml")
        self.report_msg.text = status_html("building the report (about 10 s)…", busy=True)
        self.report_button.disabled = True
        gen = self.app.workers.bump("report", self.slot)
        self.app.workers.submit(
            "report",
            self.slot,
            gen,
            jobs.report_job,
            (text, self.app.filename, str(target)),
            self._later(self._show_report, target.stem),
            self._later(self._job_failed, "report"),
        )

    # --- the queue of changes ------------------------------------------------------------

    @contextlib.contextmanager
    def _quietly(self) -> Any:
        was, self.quiet = self.quiet, True
        try:
            yield
        finally:
            self.quiet = was

    def _request(self, changes: dict[str, Any], fields: frozenset[str]) -> None:
        with self.qlock:
            now = time.perf_counter()
            for path, value in changes.items():
                self.queue.pop(path, None)
                self.queue[path] = (value, fields)
            self.since = min(self.since, now)
            if self.running:
                return
            self.running = True
        self.app.compute.submit(self._drain)

    def _drain(self) -> None:
        """The compute thread: apply every queued change, then the orbit stage."""
        ok: set[str] = set()
        errors: dict[str, str] = {}
        try:
            while not self.closed:
                with self.qlock:
                    batch, self.queue = self.queue, {}
                    since, self.since = self.since, math.inf
                    if not batch and self.seq > 0:
                        self.running = False
                        return
                t0 = time.perf_counter()
                failed = self._apply(batch)
                errors.update(failed)
                done = {f for _, fs in batch.values() for f in fs} - set(failed)
                ok = (ok | done) - set(failed)
                for f in done:
                    errors.pop(f, None)
                with self.qlock:
                    if self.queue and not failed:  # the latest value wins: skip a stale point
                        self.since = min(self.since, since)
                        continue
                with self.dlock:
                    spec = self.design.spec
                    self.seq += 1
                    seq = self.seq
                ev = evaluate(
                    spec,
                    "orbit",
                    source_file=self.app.filename,
                    with_traces=True,
                    **self.app.options,
                )
                timing = (since, time.perf_counter() - t0)
                self._later(self._show_orbit, seq, ev, dict(errors), set(ok), timing)()
                ok, errors = set(), {}
        except Exception as exc:  # the server never dies: say it in the page
            self._later(self._crashed, f"{type(exc).__name__}: {exc}")()
            with self.qlock:
                self.running = False

    def _apply(self, batch: dict[str, tuple[Any, frozenset[str]]]) -> dict[str, str]:
        if not batch:
            return {}
        changes = {p: v for p, (v, _) in batch.items()}
        with self.dlock:
            try:
                self.design.apply(changes)
                return {}
            except SpecError:
                pass
            errors: dict[str, str] = {}
            for path, (value, fields) in batch.items():  # which change was refused
                try:
                    self.design.apply({path: value})
                except SpecError as exc:
                    for f in fields:
                        errors[f] = _spec_message(exc)
            return errors

    def _later(self, fn: Any, *args: Any) -> Any:
        """A callable that runs ``fn(*args, *more)`` on the page's loop (from any thread)."""

        def call(*more: Any) -> None:
            if self.closed:
                return
            with contextlib.suppress(Exception):  # the session may be gone
                self.doc.add_next_tick_callback(partial(self._guard, fn, *args, *more))

        return call

    def _guard(self, fn: Any, *args: Any) -> None:
        if self.closed:
            return
        try:
            fn(*args)
        except Exception as exc:  # never a dead page: say what went wrong
            self._crashed(f"{type(exc).__name__}: {exc}")

    def _crashed(self, why: str) -> None:
        self.status.text = status_html(f"internal error (the page still works): {why}", busy=False)

    # --- showing results (on the loop) -----------------------------------------------------

    def _show_orbit(
        self,
        seq: int,
        ev: Evaluation,
        errors: dict[str, str],
        ok: set[str],
        timing: tuple[float, float],
    ) -> None:
        for f, msg in errors.items():
            if f in self.controls:
                self.controls[f].message.text = error_html(msg)
        for f in ok:
            if f in self.controls:
                self.controls[f].message.text = ""
        self._sync_controls(only=ok)
        if seq < self.seq:
            return
        self.last = ev
        self.settling = {}
        self.pending = {k: v for k, v in STAGES.items() if k != "orbit"}
        since, compute_s = timing
        self.timing = (time.perf_counter() - since, compute_s)
        self._show_verdict(seq, ev)
        self._show_traces(ev)
        self._show_device()
        self._schedule_slow()

    def _show_verdict(self, seq: int, ev: Evaluation) -> None:
        pending = list(self.pending.values())
        self.verdict.text = verdict_html(
            ev.out,
            seq=seq,
            stage=ev.stage,
            settling=self.settling,
            pending=pending,
            timing={"server-ms": 1e3 * self.timing[0], "compute-ms": 1e3 * self.timing[1]},
        )
        self._status()

    def _status(self) -> None:
        waiting = list(self.pending.values())
        if self.fmap is not None and not self.fmap.complete:
            waiting.append("map")
        text = "still computing: " + ", ".join(waiting) if waiting else "up to date"
        self.status.text = status_html(text, busy=bool(waiting))

    def _show_traces(self, ev: Evaluation) -> None:
        name = self.set_name or self.set_names[0]
        tr = ev.traces.get(name)
        if tr is None:
            return
        self.phase_src.data = {"x": tr.gap_um, "y": tr.gap_rate_mm_s}
        self.disp_src.data = {"x": tr.t_ms, "y": tr.x_um}
        self.phase_fig.title.text = "Head gap and its rate (one period)" + (
            f": {tr.reason}" if tr.reason else ""
        )

    def _axis_value(self, c: FieldControl) -> float | None:
        from betvdesign.explore.fields import current_value

        v = current_value(self.design.spec, self.set_index, c.field)
        if v is None:
            return None
        if hasattr(v, "units"):
            return float(v.to(c.unit).magnitude)
        return float(v)

    def _show_device(self) -> None:
        cx, cy = self.controls[self.map_x.value].spec, self.controls[self.map_y.value].spec
        with self.dlock:
            x, y = self._axis_value(cx), self._axis_value(cy)
        self.dev_src.data = {"x": [] if x is None else [x], "y": [] if y is None else [y]}

    def _sync_controls(self, only: set[str] | None = None) -> None:
        """Controls (all, or those in ``only``) show the design's values (after a map
        click, a fix, a set change). A slider within half a step of the value is left
        where the user put it."""
        from betvdesign.explore.fields import current_value

        with self.dlock:
            spec = self.design.spec
        with self._quietly():
            for f, ctl in self.controls.items():
                if only is not None and f not in only:
                    continue
                v = current_value(spec, self.set_index, f)
                c = ctl.spec
                if c.kind == "choice":
                    if ctl.widget.value != str(v):
                        ctl.widget.value = str(v)
                    continue
                if hasattr(v, "units"):
                    v = float(v.to(c.unit).magnitude)
                text = c.text(v)
                if ctl.text is not None and c.file_value(ctl.text.value) != c.file_value(text):
                    ctl.text.value = text
                sv = self._slider_value(c, v)
                if (
                    math.isfinite(sv)
                    and ctl.widget.start <= sv <= ctl.widget.end
                    and abs(ctl.widget.value - sv) > 0.5 * ctl.widget.step
                ):
                    ctl.widget.value = sv

    # --- slow stages, map, fixes -----------------------------------------------------------

    def _schedule_slow(self, delay_ms: int = SETTLE_MS) -> None:
        if self.slow_timer is not None:
            with contextlib.suppress(ValueError):
                self.doc.remove_timeout_callback(self.slow_timer)
        self.slow_timer = self.doc.add_timeout_callback(self._start_slow, max(1, delay_ms))

    def _start_slow(self) -> None:
        self.slow_timer = None
        with self.qlock:
            if self.queue or self.running:  # still moving: wait until it is still
                self._schedule_slow()
                return
        with self.dlock:
            seq = self.seq
            try:
                text = self.design.yaml_text()
            except BetvError as exc:
                self._crashed(str(exc))
                return
        w = self.app.workers
        if self.pending:
            gen = w.bump("check", self.slot)
            for stage in ("settling", "full"):
                w.submit(
                    "check",
                    self.slot,
                    gen,
                    jobs.check_job,
                    (text, self.app.filename, stage, self.app.options),
                    self._later(self._show_stage, seq),
                    self._later(self._job_failed, stage),
                )
        self._maybe_map(text)

    def _show_stage(self, seq: int, result: dict[str, Any] | None) -> None:
        if result is None or seq != self.seq:
            return  # stale: the design moved on
        stage = result["stage"]
        self.settling = result["settling"] or self.settling
        self.pending.pop(stage, None)
        if stage == "full":
            self.pending.clear()
        ev = Evaluation(
            stage, result["out"], result["settling"], self.last.traces if self.last else {}
        )
        self.last = ev
        self._show_verdict(seq, ev)
        if stage == "full":
            if ev.verdict == "fail" and self.fix_seq != seq:
                self._start_fixes(seq)
            elif ev.verdict == "pass":
                self.fixes = []
                self._show_fixes()

    def _job_failed(self, what: str, exc: BaseException) -> None:
        self.pending.pop(what, None)
        self._status()
        msg = status_html(f"{what} failed: {type(exc).__name__}: {exc}", busy=False)
        if what == "report":
            self.report_button.disabled = False
            self.report_msg.text = msg
        elif what == "map":
            self.map_status.text = msg
        else:
            self.status.text = msg

    def _start_fixes(self, seq: int) -> None:
        with self.dlock:
            text = self.design.yaml_text()
        self.fix_seq = seq
        self.pending["fix"] = "fix search (betv fix)"
        self._status()
        self.fix_div.text = status_html(
            "searching the smallest change that passes (betv fix)…", busy=True
        )
        gen = self.app.workers.bump("check", self.slot)
        self.app.workers.submit(
            "check",
            self.slot,
            gen,
            jobs.fix_job,
            (text, self.app.filename, self.app.options.get("target_speed_m_s")),
            self._later(self._got_fixes, seq),
            self._later(self._job_failed, "fix"),
        )

    def _got_fixes(self, seq: int, result: dict[str, Any] | None) -> None:
        if result is None or seq != self.seq:
            return
        self.pending.pop("fix", None)
        self._status()
        cands = [c for c in result.get("candidates", []) if c.get("passed")]
        self.fixes = cands[:MAX_FIXES]
        self.fix_message = result.get("message", "")
        self._show_fixes()

    def _show_fixes(self) -> None:
        for b in self.fix_buttons:
            b.visible = False
        if not self.fixes:
            self.fix_div.text = (
                ""
                if self.last is None or self.last.verdict == "pass"
                else status_html(
                    f"betv fix: {getattr(self, 'fix_message', '') or 'no change found'}", busy=False
                )
            )
            self.fix_src.data = {"x": [], "y": [], "x0": [], "y0": [], "label": []}
            return
        items, pts = [], {"x": [], "y": [], "x0": [], "y0": [], "label": []}
        cx, cy = self.controls[self.map_x.value].spec, self.controls[self.map_y.value].spec
        with self.dlock:
            x0, y0 = self._axis_value(cx), self._axis_value(cy)
        for k, c in enumerate(self.fixes):
            change = "; ".join(f"{ch['field']} {ch['from']} → {ch['to']}" for ch in c["changes"])
            line = status_html(f"{change}: {c['why']}", busy=False)
            items.append(f'<li class="betv-fix-item">{line}</li>')
            self.fix_buttons[k].visible = True
            values = c["values"]
            if set(values) <= {cx.field, cy.field} and x0 is not None and y0 is not None:
                pts["x"].append(_on_axis(cx, values, x0))
                pts["y"].append(_on_axis(cy, values, y0))
                pts["x0"].append(x0)
                pts["y0"].append(y0)
                pts["label"].append(str(k + 1))
        self.fix_div.text = (
            "<b>betv fix finds (drawn on the map when on its axes):</b><ol style='margin:2px 0;padding-left:18px'>"
            + "".join(items)
            + "</ol>"
        )
        self.fix_src.data = pts

    def _map_key(self) -> Any:
        fx, fy = self.map_x.value, self.map_y.value
        with self.dlock:
            edits = tuple(
                (p, str(v))
                for p, v in self.design.edits.items()
                if p.split(".", 2)[-1] not in (fx, fy) and p not in (fx, fy)
            )
        return (self.set_index, fx, fy, edits)

    def _maybe_map(self, text: str) -> None:
        key = self._map_key()
        if key == self.map_key:
            return
        self.map_key = key
        cx, cy = self.controls[self.map_x.value].spec, self.controls[self.map_y.value].spec
        x = FieldAxis.spanning(cx.field, cx.unit, cx.lo, cx.hi, MAP_POINTS, log=cx.log)
        y = FieldAxis.spanning(cy.field, cy.unit, cy.lo, cy.hi, MAP_POINTS, log=cy.log)
        fresh = self.fmap is None or (self.fmap.x.field, self.fmap.y.field) != (x.field, y.field)
        self.fmap = FieldMap.empty(x, y, self.set_names[self.set_index])
        if fresh:
            self.map_src.data = map_cells(self.fmap)
        gen = self.app.workers.bump("map", self.slot)
        self.map_status.text = status_html(f"map: 0/{MAP_POINTS} rows", busy=True)
        self._status()
        for start in range(0, MAP_POINTS, MAP_CHUNK):
            rows = list(range(start, min(MAP_POINTS, start + MAP_CHUNK)))
            self.app.workers.submit(
                "map",
                self.slot,
                gen,
                jobs.map_job,
                (text, self.app.filename, self.set_index, x, y, rows),
                self._later(self._got_rows, self.fmap),
                self._later(self._job_failed, "map"),
            )

    def _got_rows(self, fmap: FieldMap, result: dict[str, Any] | None) -> None:
        if result is None or fmap is not self.fmap:
            return
        part = MapRows(
            tuple(result["rows"]),
            result["mode"],
            result["delta_s"],
            result["speed_m_s"],
            result["varpi"],
            {(j, i): r for j, i, r in result["reasons"]},
        )
        fmap.fill(part)
        nx = len(fmap.x.values)
        cells = map_cells(fmap)
        patch: dict[str, list[tuple[int, Any]]] = {
            k: [] for k in ("color", "mode", "speed", "hatch", "varpi")
        }
        for j in part.rows:
            for i in range(nx):
                k = j * nx + i
                for name in patch:
                    patch[name].append((k, cells[name][k]))
        if len(self.map_src.data["color"]) == len(cells["color"]):
            self.map_src.patch(patch)
        else:
            self.map_src.data = cells
        done = int(fmap.done.sum())
        total = len(fmap.y.values)
        self.map_status.text = status_html(
            f"map: {done}/{total} rows"
            if done < total
            else f"map of set {fmap.set_name}: {total}×{nx} exact orbits",
            busy=done < total,
        )
        self._status()

    def _show_report(self, stem: str, html: str | None) -> None:
        self.report_button.disabled = False
        if html is None:
            return
        token = secrets.token_hex(8)
        self.app.reports[token] = (f"{stem}.html", html)
        self.report_msg.text = (
            f'<a class="betv-report-download" href="report/{token}" download="{stem}.html">'
            f"download report {stem}.html</a> (the HTML of betv report)"
        )

    def _destroyed(self, context: Any) -> None:
        self.closed = True
        for lane in jobs.LANES:
            self.app.workers.bump(lane, self.slot)
