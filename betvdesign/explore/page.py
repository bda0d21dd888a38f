"""One browser session of ``betv explore``: the Bokeh document and how a change flows.

Flow of a change (the latest value wins, stale work is dropped):

1. a control moves (browser -> websocket -> a Bokeh callback on the server's loop): the
   change is queued on the session and the callback returns at once;
2. the server's compute thread drains the queue: every queued change is applied at once
   through the device file's validation (:meth:`Design.apply`; a refused value gives its
   control the loader's message and leaves the design as it was), then the "orbit"
   stage is computed (:func:`betvdesign.explore.compute.evaluate`) and handed back to the
   loop, which redraws the verdict and the orbit; "undo" and "reset to the file" are
   steps of the same queue, in the order they were asked
   (:meth:`~betvdesign.explore.design.Design.undo`, one undo step per change, the
   positions of one slider drag together);
3. once the design has been still for :data:`SETTLE_MS`, the slow stages (how well Δs
   is determined and the settling from rest, model adequacy, then the fix search when
   the verdict fails) and, when a field off the map's axes changed, the map go to the
   worker processes (:class:`betvdesign.explore.jobs.Workers`) and arrive
   progressively; the page lists what is still computing.

The controls are :mod:`~betvdesign.explore.controls`, the map
:mod:`~betvdesign.explore.mapview`, the HTML :mod:`~betvdesign.explore.views`.
"""

from __future__ import annotations

import contextlib
import functools
import math
import secrets
import threading
import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import Any

from bokeh.layouts import column, row
from bokeh.models import Button, ColumnDataSource, CustomJS, Div, Select, TextInput
from bokeh.plotting import figure

from betvdesign.errors import BetvError, SpecError
from betvdesign.explore import jobs
from betvdesign.explore.compute import STAGES, Evaluation, evaluate
from betvdesign.explore.controls import ARIA_JS, ControlPanel
from betvdesign.explore.design import Design, free_name
from betvdesign.explore.mapview import MapView
from betvdesign.explore.views import (
    basis_html,
    fixes_html,
    mode_decided,
    model_note_html,
    no_orbit_html,
    status_html,
    verdict_html,
)

#: Quiet time after the last change before the slow stages start [ms].
SETTLE_MS = 250
#: Longest wait for the browser to draw a page served with its verdict before the slow
#: stages start their worker processes anyway [ms] (they would compete with the drawing).
PAINT_WAIT_MS = 3000
#: Fix candidates listed (each with an "apply" button).
MAX_FIXES = 4
ALL_SETS = "all sets"
#: Widths of the page's three columns [px] (controls, verdict and orbit, map and
#: actions); on a narrow screen the map column goes below.
COLUMNS = (370, 730, 470)
#: Height of the verdict box [px] (it scrolls when a device has many rules).
VERDICT_HEIGHT = 470
#: Changes of the same fields closer than this are one undo step (a slider drag) [s].
UNDO_MERGE_S = 0.6
#: In the set of fields a step applied: every control (after an undo or a reset).
EVERY_FIELD = "*"

#: A step of the queue: changes (edit path -> (file value, fields)) or "undo" / "reset".
Step = dict[str, tuple[Any, frozenset[str]]] | str

__all__ = ["ALL_SETS", "MAX_FIXES", "SETTLE_MS", "ExploreApp", "ExplorePage"]


@dataclass
class ExploreApp:
    """What every session of one ``betv explore`` server shares.

    text, filename: the device file; options: ``target_speed_m_s``, ``select``,
    ``ignore`` (as ``betv check``); workers: the job lanes; reports: finished report
    HTML by token (served by the server's report route); compute: the thread that
    computes the orbit stage; first: the "orbit" stage of the file's design as the
    compute thread computes it (with every set's traces), computed before the server
    starts: a new page is served with its verdict (None: the page asks the compute
    thread, as for every change); warmed: the compute thread has computed (the first
    page drawn with ``first`` has it compute its orbit once, which loads the compiled
    kernels before the first change needs them).
    """

    text: str
    filename: str
    options: dict[str, Any]
    workers: jobs.Workers
    reports: dict[str, tuple[str, str]] = field(default_factory=dict)
    compute: ThreadPoolExecutor = field(
        default_factory=lambda: ThreadPoolExecutor(1, thread_name_prefix="betv-explore")
    )
    first: Evaluation | None = None
    warmed: bool = False

    def __call__(self, doc: Any) -> None:
        """Bokeh's application hook: a new page."""
        ExplorePage(doc, self)


#: The page: every part a root of its own (Bokeh lays out a root whole whenever one of
#: its texts changes, so a new verdict must not lay out the controls and the map).
PAGE = """{% extends base %}
{% block contents %}
<div>{{ embed(roots.header) }}</div>
<div style="display:flex;flex-wrap:wrap;align-items:flex-start;column-gap:8px">
  <div style="width:{{ widths[0] }}px">{{ embed(roots.controls) }}</div>
  <div style="width:{{ widths[1] }}px">{{ embed(roots.verdict) }}{{ embed(roots.status) }}
    {{ embed(roots.plots) }}</div>
  <div style="width:{{ widths[2] }}px">{{ embed(roots.map) }}{{ embed(roots.map_status) }}
    {{ embed(roots.actions) }}</div>
</div>
{% endblock %}
"""


def _template() -> Any:
    from jinja2 import Template

    return Template(PAGE)


def _spec_message(exc: SpecError) -> str:
    return "; ".join(f"{i.field}: {i.message}" if i.field else i.message for i in exc.issues)


class ExplorePage:
    """One page (see the module docstring)."""

    def __init__(self, doc: Any, app: ExploreApp) -> None:
        self.doc = doc
        self.app = app
        self.design = Design(app.text, app.filename)
        self.dlock = threading.RLock()  # the design (compute thread and loop)
        self.qlock = threading.Lock()  # the queue of changes
        self.queue: list[Step] = []
        self.last_edit: tuple[frozenset[str], float] = (frozenset(), -math.inf)
        self.running = False
        self.again = False  # recompute without changes
        self.since = math.inf  # when the oldest queued change arrived [perf_counter s]
        # (change received -> redraw sent, compute wall, compute CPU) [s] of the last update
        self.timing: tuple[float, float, float] = (math.nan, math.nan, math.nan)
        self.closed = False
        self.painted = True  # False until the browser draws a page served with its verdict
        self.seq = 0
        self.slot = app.workers.slot()
        self.slow_timer: Any = None
        self.pending: dict[str, str] = {}
        self.last: Evaluation | None = None
        self.settling: dict[str, Any] = {}
        self.fixes: list[dict[str, Any]] = []
        self.fix_seq = -1
        self.fix_message = ""
        self.set_names = [s.name for s in self.design.original.actuator_sets]
        several = len(self.set_names) > 1
        self.set_select = Select(
            title="actuator set (edits go to this set, or to all)",
            options=([ALL_SETS] if several else []) + self.set_names,
            value=ALL_SETS if several else self.set_names[0],
            width=300,
            css_classes=["betv-set-select"],
        )
        self.set_select.on_change("value", self._safe(self._on_set))
        self.panel = ControlPanel(self._request, lambda: self.set_name, self._safe)
        self.panel.build(self.design.original, self.set_index)
        self.panel.sync(self.design.spec, self.set_index)
        self.map = MapView(
            lambda: {f: c.spec for f, c in self.panel.controls.items()},
            lambda: self.set_name,
            self._request,
            self._on_axes,
            self._safe,
        )
        self._build_views()
        self._build_history()
        self._build_actions()
        doc.title = f"betv explore: {self.design.original.name}"
        header = Div(
            text=f"<b style='font-size:18px'>betv explore</b> · {self.design.original.name} "
            f"<span style='color:#57606a'>({Path(app.filename).name})</span>",
            width=900,
        )
        roots = {
            "header": header,
            "controls": column(self.set_select, self.history_box, self.panel.box, width=COLUMNS[0]),
            "verdict": self.verdict,
            "status": self.status,
            "plots": column(self.orbit_note, row(self.phase_fig, self.disp_fig)),
            "map": self.map.box,
            "map_status": self.map.status,
            "actions": column(self.fix_box, self.save_box, self.report_box, width=COLUMNS[2]),
        }
        for name, model in roots.items():
            model.name = name
            doc.add_root(model)
        doc.template = _template()
        doc.template_variables["widths"] = COLUMNS
        doc.on_session_destroyed(self._destroyed)
        doc.js_on_event("document_ready", CustomJS(code=ARIA_JS))
        if app.first is None:
            self._request({}, frozenset())
        else:  # served with the verdict; the slow stages once the browser has drawn it
            self.painted = False
            doc.on_event("document_ready", self._safe(self._on_document_ready))
            self.paint_timer = doc.add_timeout_callback(self._on_painted, PAINT_WAIT_MS)
            self.seq = 1
            now = time.perf_counter()
            self._show_orbit(
                1, app.first, {}, set(), (now, app.first.elapsed_s, app.first.elapsed_s)
            )

    @property
    def set_index(self) -> int:
        v = self.set_select.value
        return self.set_names.index(v) if v in self.set_names else 0

    @property
    def set_name(self) -> str | None:
        """The set edits go to (None: every set)."""
        v = self.set_select.value
        if v in self.set_names:
            return v
        return self.set_names[0] if len(self.set_names) == 1 else None

    # --- widgets -----------------------------------------------------------------------

    def _build_views(self) -> None:
        # fixed sizes: a new verdict redraws this box, not the page's layout
        self.verdict = Div(
            text="<i>computing the exact orbit…</i>",
            width=COLUMNS[1] - 10,
            height=VERDICT_HEIGHT,
            styles={"overflow-y": "auto"},
        )
        self.status = Div(text="", width=COLUMNS[1] - 10, height=20, css_classes=["betv-status"])
        self.phase_src = ColumnDataSource(data={"x": [], "y": []})
        self.disp_src = ColumnDataSource(data={"x": [], "y": []})
        # what the plots show (or why there are none): no plot is drawn without an orbit
        self.orbit_note = Div(
            text=no_orbit_html("", computing=True), width=COLUMNS[1] - 10, min_height=20
        )
        common = {
            "width": COLUMNS[1] // 2 - 5,
            "height": 300,
            "toolbar_location": None,
            "visible": False,
            "css_classes": ["betv-orbit-plot"],
        }
        self.phase_fig = figure(
            title="Head gap and its rate (one period)",
            x_axis_label="head gap [µm]",
            y_axis_label="gap rate [mm/s]",
            **common,
        )
        self.phase_fig.line("x", "y", source=self.phase_src, line_width=2, color="#d95f02")
        self.disp_fig = figure(
            title="Slider position on the periodic orbit",
            x_axis_label="time [ms]",
            y_axis_label="slider x [µm]",
            **common,
        )
        self.disp_fig.line("x", "y", source=self.disp_src, line_width=2, color="#1b9e77")

    def _build_history(self) -> None:
        self.undo_button = Button(label="Undo", width=110, disabled=True, css_classes=["betv-undo"])
        self.reset_button = Button(
            label="Reset to the file", width=150, disabled=True, css_classes=["betv-reset"]
        )
        self.undo_button.on_click(self._safe(partial(self._request_op, "undo")))
        self.reset_button.on_click(self._safe(partial(self._request_op, "reset")))
        self.history_box = row(self.undo_button, self.reset_button)

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
            b.on_click(self._safe(partial(self._on_apply_fix, k)))
            self.fix_buttons.append(b)
        self.fix_box = column(self.fix_div, row(*self.fix_buttons[:2]), row(*self.fix_buttons[2:]))
        original = Path(self.app.filename)
        suffix = original.suffix or ".yaml"
        default = free_name(original.with_name(f"{original.stem}-explored{suffix}"))
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
        self.save_button.on_click(self._safe(partial(self._on_save, False)))
        self.overwrite_button.on_click(self._safe(partial(self._on_save, True)))
        self.save_box = column(
            row(self.save_name, self.save_button), self.overwrite_button, self.save_msg
        )
        self.report_button = Button(
            label="Build report (HTML)", width=180, css_classes=["betv-report"]
        )
        self.report_msg = Div(text="", width=460, css_classes=["betv-report-link"])
        self.report_button.on_click(self._safe(self._on_report))
        self.report_box = column(self.report_button, self.report_msg)

    # --- user actions (on the server's loop) ------------------------------------------------

    def _on_set(self, attr: str, old: Any, new: Any) -> None:
        self.panel.build(self.design.original, self.set_index)
        with self.dlock:
            self.panel.sync(self.design.spec, self.set_index)
        self.map.rebuild()
        self._request({}, frozenset())  # the orbit of this set
        self._on_axes()

    def _on_axes(self) -> None:
        with self.dlock:
            spec = self.design.spec
        self.map.show_design(spec, self.set_index)
        self.map.show_fixes(self.fixes, spec, self.set_index)
        self._schedule_slow(1)

    def _on_apply_fix(self, k: int) -> None:
        if k < len(self.fixes):
            values = self.fixes[k]["file_values"]
            self._request(dict(values), frozenset(values))

    def _on_save(self, overwrite: bool) -> None:
        name = self.save_name.value.strip()
        try:
            with self.dlock:
                res = self.design.save(name, overwrite=overwrite)
        except (BetvError, OSError, ValueError) as exc:
            self.save_msg.text = status_html(f"not saved: {exc}", busy=False)
            return
        self.overwrite_button.visible = res.exists
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
        target = Path(self.app.filename).parent / (self.save_name.value.strip() or "design.yaml")
        self.report_msg.text = status_html("building the report (about 10 s)…", busy=True)
        self.report_button.disabled = True
        self._submit(
            "report",
            jobs.report_job,
            (text, self.app.filename, str(target)),
            self._later(self._show_report, target.stem),
            "report",
        )

    # --- the queue of changes ------------------------------------------------------------

    def _request(self, changes: dict[str, Any], fields: frozenset[str]) -> None:
        """Queue ``changes`` (edit path -> file value) made through ``fields``; no
        changes: compute the design again (another set shown)."""
        with self.qlock:
            self.again = self.again or not changes
            if changes:
                if not self.queue or isinstance(self.queue[-1], str):
                    self.queue.append({})
                step = self.queue[-1]
                assert isinstance(step, dict)
                for path, value in changes.items():
                    step.pop(path, None)
                    step[path] = (value, fields)
        self._kick()

    def _request_op(self, op: str) -> None:
        """Queue "undo" or "reset" (after the changes queued before it)."""
        with self.qlock:
            self.queue.append(op)
        self._kick()

    def _kick(self) -> None:
        with self.qlock:
            self.since = min(self.since, time.perf_counter())
            if self.running:
                return
            self.running = True
        self.app.compute.submit(self._drain)

    def _drain(self) -> None:
        """The compute thread: apply every queued step, then the orbit stage."""
        ok: set[str] = set()
        errors: dict[str, str] = {}
        try:
            while not self.closed:
                with self.qlock:
                    steps, self.queue = self.queue, []
                    since, self.since = self.since, math.inf
                    if not steps and self.seq > 0 and not self.again:
                        self.running = False
                        return
                    self.again = False
                t0, c0 = time.perf_counter(), time.thread_time()
                failed: dict[str, str] = {}
                for step in steps:
                    if isinstance(step, str):  # undo / reset: every control shows the design
                        with self.dlock:
                            if step == "undo":
                                self.design.undo()
                            else:
                                self.design.reset()
                        self.last_edit = (frozenset(), -math.inf)
                        ok, errors, failed = {EVERY_FIELD}, {}, {}
                        continue
                    bad = self._apply(step)
                    done = {f for _, fs in step.values() for f in fs} - set(bad)
                    errors = {f: m for f, m in errors.items() if f not in done} | bad
                    ok = (ok | done) - set(bad)
                    failed |= bad
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
                timing = (since, time.perf_counter() - t0, time.thread_time() - c0)
                self._later(self._show_orbit, seq, ev, errors, ok, timing)()
                ok, errors = set(), {}
        except Exception as exc:  # the server never dies: say it in the page
            self._later(self._crashed, f"{type(exc).__name__}: {exc}")()
            with self.qlock:
                self.running = False

    def _apply(self, batch: dict[str, tuple[Any, frozenset[str]]]) -> dict[str, str]:
        """Apply a batch of changes (all at once, else one by one to find the refused):
        one undo step, merged with the step before when it moved the same fields less
        than :data:`UNDO_MERGE_S` ago (a slider drag)."""
        if not batch:
            return {}
        fields = frozenset(f for _, fs in batch.values() for f in fs)
        now = time.monotonic()
        merge = fields == self.last_edit[0] and now - self.last_edit[1] < UNDO_MERGE_S
        self.last_edit = (fields, now)
        with self.dlock:
            try:
                self.design.apply({p: v for p, (v, _) in batch.items()}, merge=merge)
                return {}
            except SpecError:
                pass
            errors: dict[str, str] = {}
            for path, (value, fs) in batch.items():
                try:
                    self.design.apply({path: value}, merge=merge)
                    merge = True  # the rest of the batch: the same step
                except SpecError as exc:
                    errors.update(dict.fromkeys(fs, _spec_message(exc)))
            return errors

    def _safe(self, fn: Callable[..., None]) -> Callable[..., None]:
        """``fn`` as a widget callback that never loses an error: it shows in the page
        (``fn``'s signature kept: Bokeh checks it)."""

        @functools.wraps(fn)
        def call(*args: Any) -> None:
            self._guard(fn, *args)

        return call

    def _later(self, fn: Callable[..., None], *args: Any) -> Callable[..., None]:
        """A callable that runs ``fn(*args, *more)`` on the page's loop (from any thread)."""

        def call(*more: Any) -> None:
            if self.closed:
                return
            with contextlib.suppress(Exception):  # the session may be gone
                self.doc.add_next_tick_callback(partial(self._guard, fn, *args, *more))

        return call

    def _guard(self, fn: Callable[..., None], *args: Any) -> None:
        if self.closed:
            return
        try:
            fn(*args)
        except Exception as exc:  # never a dead page: say what went wrong
            self._crashed(f"{type(exc).__name__}: {exc}")

    def _crashed(self, why: str) -> None:
        self.status.text = status_html(f"internal error (the page still works): {why}", busy=False)

    def _submit(
        self, lane: str, fn: Callable[..., Any], args: tuple[Any, ...], done: Any, what: str
    ) -> None:
        gen = self.app.workers.bump(lane, self.slot)
        self.app.workers.submit(
            lane, self.slot, gen, fn, args, done, self._later(self._job_failed, what)
        )

    # --- showing results (on the loop) -----------------------------------------------------

    def _show_orbit(
        self,
        seq: int,
        ev: Evaluation,
        errors: dict[str, str],
        ok: set[str],
        timing: tuple[float, float, float],
    ) -> None:
        if EVERY_FIELD in ok:
            ok = set(self.panel.controls) - set(errors)
        self.panel.show_messages(errors, ok)
        with self.dlock:
            spec = self.design.spec
            self.undo_button.disabled = not self.design.history
            self.reset_button.disabled = not self.design.edits
        self.panel.sync(spec, self.set_index, only=ok)
        if seq < self.seq:
            return
        self.last = ev
        self.settling = {}
        self.pending = {k: v for k, v in STAGES.items() if k != "orbit"}
        since, compute_s, cpu_s = timing
        self.timing = (time.perf_counter() - since, compute_s, cpu_s)
        self._show_verdict(seq, ev)
        self._show_traces(ev)
        self.map.show_design(spec, self.set_index)
        self._schedule_slow()

    def _show_verdict(self, seq: int, ev: Evaluation) -> None:
        self.verdict.text = verdict_html(
            ev.out,
            seq=seq,
            stage=ev.stage,
            settling=self.settling,
            pending=list(self.pending.values()),
            timing={
                "server-ms": 1e3 * self.timing[0],
                "compute-ms": 1e3 * self.timing[1],
                "compute-cpu-ms": 1e3 * self.timing[2],
            },
        )
        self._show_basis(ev)
        self._status()

    def _show_basis(self, ev: Evaluation) -> None:
        """Say which answer the orbit plots are, beside the verdict's basis (the orbit,
        or the crossing of the travel from rest: :mod:`betvdesign.checks.travel`)."""
        name = self.set_names[self.set_index]
        s = next((s for s in ev.out["sets"] if s["name"] == name), None)
        tr = ev.traces.get(name)
        if s is None or tr is None or tr.reason:
            return  # no plots: the note says why
        basis = s.get("basis") if mode_decided(ev.stage) else None
        self.orbit_note.text = basis_html(basis, s.get("mode"))
        if tr.note:
            self.orbit_note.text += model_note_html(tr.note)
        self.disp_fig.title.text = (
            "Periodic orbit (verdict: crossing from rest)"
            if basis == "crossing"
            else "Slider position on the periodic orbit"
        )

    def _status(self) -> None:
        waiting = list(self.pending.values()) + (["map"] if self.map.busy else [])
        text = "still computing: " + ", ".join(waiting) if waiting else "up to date"
        self.status.text = status_html(text, busy=bool(waiting))

    def _show_traces(self, ev: Evaluation) -> None:
        """The orbit's plots, or in their place why there is no periodic orbit."""
        tr = ev.traces.get(self.set_names[self.set_index])
        if tr is None:
            return
        shown = not tr.reason and bool(tr.t_ms)
        if shown:
            self.phase_src.data = {"x": tr.gap_um, "y": tr.gap_rate_mm_s}
            self.disp_src.data = {"x": tr.t_ms, "y": tr.x_um}
        else:
            self.orbit_note.text = no_orbit_html(tr.reason or "no samples")
        self.phase_fig.visible = self.disp_fig.visible = shown

    # --- slow stages, map, fixes -----------------------------------------------------------

    def _on_document_ready(self, event: Any) -> None:
        with contextlib.suppress(ValueError):
            self.doc.remove_timeout_callback(self.paint_timer)
        self._on_painted()

    def _on_painted(self) -> None:
        """The browser has drawn the first page (or :data:`PAINT_WAIT_MS` passed): the
        slow stages may start their worker processes now."""
        if not self.painted:
            self.painted = True
            if not self.app.warmed:  # the first verdict came from elsewhere (the server)
                self.app.warmed = True
                with self.dlock:
                    spec = self.design.spec
                self.app.compute.submit(  # the compiled kernels load now, not at a change
                    evaluate,
                    spec,
                    "orbit",
                    source_file=self.app.filename,
                    with_traces=True,
                    **self.app.options,
                )
            self._schedule_slow(1)

    def _schedule_slow(self, delay_ms: int = SETTLE_MS) -> None:
        if not self.painted:  # the first paint comes first (_on_painted schedules them)
            return
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
            edits = dict(self.design.edits)
            try:
                text = self.design.yaml_text()
            except BetvError as exc:
                self._crashed(str(exc))
                return
        if self.pending and "fix" not in self.pending:
            gen = self.app.workers.bump("check", self.slot)
            for stage in ("settling", "full"):
                self.app.workers.submit(
                    "check",
                    self.slot,
                    gen,
                    jobs.check_job,
                    (text, self.app.filename, stage, self.app.options),
                    self._later(self._show_stage, seq),
                    self._later(self._job_failed, stage),
                )
        key = self.map.key(edits, self.set_index)
        if key != self.map.computed_key:
            gen = self.app.workers.bump("map", self.slot)

            def submit(fn: Callable[..., Any], args: tuple[Any, ...], fmap: Any) -> None:
                self.app.workers.submit(
                    "map",
                    self.slot,
                    gen,
                    fn,
                    args,
                    self._later(self._map_rows, fmap),
                    self._later(self._job_failed, "map"),
                )

            label = self.set_names[self.set_index]
            self.map.start(key, text, self.app.filename, self.set_index, label, submit)
        self._status()

    def _map_rows(self, fmap: Any, result: dict[str, Any] | None) -> None:
        self.map.add_rows(fmap, result)
        self._status()

    def _show_stage(self, seq: int, result: dict[str, Any] | None) -> None:
        if result is None or seq != self.seq:
            return  # stale: the design moved on
        stage = result["stage"]
        self.settling = result["settling"] or self.settling
        self.pending.pop(stage, None)
        if stage == "full":
            self.pending.pop("settling", None)
        traces = self.last.traces if self.last else {}
        ev = Evaluation(stage, result["out"], result["settling"], traces)
        self.last = ev
        if stage == "full" and ev.verdict == "fail" and self.fix_seq != seq:
            self._start_fixes(seq)
        elif stage == "full" and ev.verdict == "pass":
            self.fixes, self.fix_message = [], ""
            self._show_fixes()
        self._show_verdict(seq, ev)

    def _job_failed(self, what: str, exc: BaseException) -> None:
        self.pending.pop(what, None)
        if what == "full":
            self.pending.pop("settling", None)
        if self.last is not None:
            self._show_verdict(self.seq, self.last)
        msg = status_html(f"{what} failed: {type(exc).__name__}: {exc}", busy=False)
        if what == "report":
            self.report_button.disabled = False
            self.report_msg.text = msg
        elif what == "map":
            self.map.failed(msg)
        else:
            self.status.text = msg

    def _start_fixes(self, seq: int) -> None:
        with self.dlock:
            text = self.design.yaml_text()
        self.fix_seq = seq
        self.pending["fix"] = "fix search (betv fix)"
        self.fix_div.text = status_html(
            "searching the smallest change that passes (betv fix)…", busy=True
        )
        target = self.app.options.get("target_speed_m_s")
        self._submit(
            "check",
            jobs.fix_job,
            (text, self.app.filename, target),
            self._later(self._got_fixes, seq),
            "fix",
        )

    def _got_fixes(self, seq: int, result: dict[str, Any] | None) -> None:
        if result is None or seq != self.seq:
            return
        self.pending.pop("fix", None)
        if self.last is not None:
            self._show_verdict(seq, self.last)
        self.fixes = [c for c in result.get("candidates", []) if c.get("passed")][:MAX_FIXES]
        self.fix_message = str(result.get("message", ""))
        self._show_fixes()

    def _show_fixes(self) -> None:
        for k, b in enumerate(self.fix_buttons):
            b.visible = k < len(self.fixes)
        failing = self.last is not None and self.last.verdict == "fail"
        self.fix_div.text = fixes_html(self.fixes, self.fix_message if failing else "")
        with self.dlock:
            spec = self.design.spec
        self.map.show_fixes(self.fixes, spec, self.set_index)

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
