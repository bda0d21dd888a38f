"""The page's controls: a slider and a text box per designer field, in the field's unit.

A slider moves over the range of :func:`betvdesign.explore.fields.designer_fields`
(in log10 of the value where that range spans decades); the text box beside it shows the
value as the device file writes it and takes any typed value, which the device file's
validation then judges (its message appears under the control, and the refused text
stays in its box marked in red, class ``betv-refused``, until a value applies). Every
change is handed to ``on_change(changes, fields)`` with ``changes`` = {edit path: file
value}.

A slider speaks the field's unit, never its log10 position: the tooltip over the handle
while it moves and the handle's ``aria-valuetext`` (what a screen reader says) read
"3 kHz", through one formatter (:func:`slider_format`, the JavaScript twin of
:meth:`~betvdesign.explore.fields.FieldControl.shown`); the handle's ``aria-label`` is the
field's label (:data:`ARIA_JS`, run when the page is ready and whenever the controls are
rebuilt).
"""

from __future__ import annotations

import contextlib
import html
import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from functools import partial
from typing import Any

from bokeh.layouts import column, row
from bokeh.models import (
    CustomJS,
    CustomJSTickFormatter,
    Div,
    InlineStyleSheet,
    Select,
    Slider,
    TextInput,
)

from betvdesign.explore.design import set_path
from betvdesign.explore.fields import (
    SLIDER_STEPS,
    FieldControl,
    current_value,
    designer_fields,
)
from betvdesign.explore.views import error_html

#: The class of a text box whose value was refused, and how it looks.
REFUSED = "betv-refused"
REFUSED_CSS = f":host(.{REFUSED}) input {{border: 2px solid #cf222e; background-color: #fff0f0}}"

#: A slider position as people read it: ``%.4g`` of the value (10**position on a log
#: slider) and the unit, as :meth:`FieldControl.shown` writes it in Python.
FORMAT_JS = """
const x = log ? Math.pow(10, tick) : tick;
if (integer) { return String(Math.round(x)); }
function g4(v) {
  if (v === 0 || !isFinite(v)) { return String(v); }
  const strip = (t) => t.includes(".") ? t.replace(/0+$/, "").replace(/[.]$/, "") : t;
  const [m, e] = v.toExponential(3).split("e");
  const k = Number(e);
  if (k < -4 || k >= 4) {
    return strip(m) + "e" + (k < 0 ? "-" : "+") + String(Math.abs(k)).padStart(2, "0");
  }
  return strip(v.toFixed(3 - k));
}
return unit ? g4(x) + " " + unit : g4(x);
"""

#: Gives every slider handle of the page its ``aria-valuetext`` in the field's unit (the
#: slider's own formatter) and its ``aria-label``, now and after each move; retried
#: until the sliders' views exist (they are built after a rebuild's change arrives).
ARIA_JS = """
function install(tries) {
  for (const view of Bokeh.index.all_views()) {
    const s = view._noUiSlider;
    const tags = view.model.tags || [];
    if (s == null || view._betv_aria || !tags.includes("betv-slider")) { continue; }
    const handle = view.slider_el && view.slider_el.querySelector(".noUi-handle");
    if (handle == null) { continue; }
    view._betv_aria = true;
    const label = tags.find((t) => t.startsWith("label:"));
    if (label) { handle.setAttribute("aria-label", label.slice(6)); }
    const say = () => handle.setAttribute("aria-valuetext", view.pretty(view.model.value));
    // after noUiSlider's own listener, which writes the raw position
    s.on("update.betvaria", () => queueMicrotask(say));
    say();
  }
  if (tries > 0) { setTimeout(() => install(tries - 1), 200); }
}
install(15);
"""

__all__ = [
    "ARIA_JS",
    "FORMAT_JS",
    "REFUSED",
    "SLIDER_STEPS",
    "Control",
    "ControlPanel",
    "css_name",
    "slider_format",
]


def slider_format(c: FieldControl) -> CustomJSTickFormatter:
    """The formatter of ``c``'s slider (tooltip and screen reader): see :data:`FORMAT_JS`."""
    return CustomJSTickFormatter(
        args={"log": c.log, "integer": c.kind == "integer", "unit": c.shown_unit},
        code=FORMAT_JS,
    )


OnChange = Callable[[dict[str, Any], frozenset[str]], None]


def css_name(field: str) -> str:
    """The CSS class of a field's widgets (``betv-field-drive-frequency``)."""
    return "betv-field-" + field.replace(".", "-").replace("_", "-")


@dataclass
class Control:
    """The widgets of one field: a slider (or a select for a choice), the text box
    (None for a choice) and the message under them."""

    spec: FieldControl
    widget: Any
    text: TextInput | None
    message: Div


def _slider_value(c: FieldControl, x: Any) -> float:
    try:
        x = float(x)
    except (TypeError, ValueError):
        return math.nan
    if c.log:
        return math.log10(x) if x > 0 else math.nan
    return x


class ControlPanel:
    """The controls of one actuator set (rebuilt by :meth:`build` when the set changes).

    ``set_name()`` is the set the edits go to (None: every set); ``guard(fn)`` wraps
    every widget callback (the page shows an error instead of losing it).
    """

    def __init__(
        self,
        on_change: OnChange,
        set_name: Callable[[], str | None],
        guard: Callable[[Callable[..., None]], Callable[..., None]] = lambda fn: fn,
    ) -> None:
        self.on_change = on_change
        self.guard = guard
        self.set_name = set_name
        self.controls: dict[str, Control] = {}
        self.box = column()
        self.box.js_on_change("children", CustomJS(code=ARIA_JS))
        self.quiet = False
        # one stylesheet for every text box and one formatter per kind of slider: fewer
        # models for the page to build, send and lay out (models of this page's own)
        self.sheet = InlineStyleSheet(css=REFUSED_CSS)
        self.formats: dict[tuple[bool, bool, str], CustomJSTickFormatter] = {}

    @contextlib.contextmanager
    def quietly(self) -> Iterator[None]:
        """Widget changes made by the server inside this block are not user changes."""
        was, self.quiet = self.quiet, True
        try:
            yield
        finally:
            self.quiet = was

    def build(self, spec: Any, set_index: int) -> None:
        """The controls of set ``set_index`` with ranges from ``spec`` (the user's file)."""
        self.controls = {}
        boxes: list[Any] = []
        group = ""
        for c in designer_fields(spec, set_index):
            if c.group != group:
                group = c.group
                boxes.append(Div(text=f"<b>{group}</b>", margin=(8, 5, 0, 5)))
            boxes.append(self._control(c))
        self.box.children = boxes

    def _format(self, c: FieldControl) -> CustomJSTickFormatter:
        """:func:`slider_format` of ``c``, shared by the sliders that format alike."""
        key = (c.log, c.kind == "integer", c.shown_unit)
        if key not in self.formats:
            self.formats[key] = slider_format(c)
        return self.formats[key]

    def _control(self, c: FieldControl) -> Any:
        css = ["betv-control", css_name(c.field)]
        message = Div(text="", width=350, css_classes=["betv-message", css[1]], margin=(0, 5, 4, 5))
        if c.kind == "choice":
            widget = Select(
                title=c.label,
                options=list(c.choices),
                value=str(c.value),
                width=200,
                css_classes=css,
            )
            widget.on_change("value", self.guard(partial(self._on_choice, c)))
            self.controls[c.field] = Control(c, widget, None, message)
            return column(widget, message)
        lo, hi = (math.log10(c.lo), math.log10(c.hi)) if c.log else (c.lo, c.hi)
        # the label on a line of its own, over slider and text box (the designer fields'
        # descriptions are longer than a slider is wide)
        label = Div(text=html.escape(c.label), width=350, margin=(4, 5, 0, 5))
        widget = Slider(
            title=None,
            start=lo,
            end=hi,
            value=_slider_value(c, c.value if c.value is not None else c.lo),
            step=1.0 if c.kind == "integer" else (hi - lo) / SLIDER_STEPS,
            show_value=False,
            format=self._format(c),
            tags=["betv-slider", f"label:{c.label}"],
            width=215,
            css_classes=[*css, "betv-slider"],
        )
        text = TextInput(
            value=c.text(c.value),
            width=115,
            css_classes=[*css, "betv-text"],
            stylesheets=[self.sheet],
        )
        widget.on_change("value", self.guard(partial(self._on_slider, c)))
        text.on_change("value", self.guard(partial(self._on_text, c)))
        self.controls[c.field] = Control(c, widget, text, message)
        return column(label, row(widget, text), message)

    # --- user changes (the server's loop) ----------------------------------------------

    def _send(self, c: FieldControl, value: Any) -> None:
        self.on_change({set_path(c.field, self.set_name()): value}, frozenset([c.field]))

    def _on_slider(self, c: FieldControl, attr: str, old: Any, new: Any) -> None:
        if self.quiet:
            return
        x = 10.0**new if c.log else float(new)
        text = c.text(round(x) if c.kind == "integer" else x)
        with self.quietly():
            self.controls[c.field].text.value = text  # type: ignore[union-attr]
        self._send(c, c.file_value(text))

    def _on_text(self, c: FieldControl, attr: str, old: Any, new: Any) -> None:
        if not self.quiet:
            self._send(c, c.file_value(new))

    def _on_choice(self, c: FieldControl, attr: str, old: Any, new: Any) -> None:
        if not self.quiet:
            self._send(c, new)

    # --- showing the design -------------------------------------------------------------

    def show_messages(self, errors: dict[str, str], ok: set[str]) -> None:
        """The loader's message under each refused field, its text box marked
        (:data:`REFUSED`); both cleared where a value applied."""
        for f, msg in errors.items():
            if f in self.controls:
                self.controls[f].message.text = error_html(msg)
                _mark(self.controls[f].text, True)
        for f in ok:
            if f in self.controls and f not in errors:
                self.controls[f].message.text = ""
                _mark(self.controls[f].text, False)

    def sync(self, spec: Any, set_index: int, only: set[str] | None = None) -> None:
        """Controls (all, or those in ``only``) show ``spec``'s values (after a map click,
        a fix, a set change). A slider within half a step of the value stays where the
        user put it; a value outside its range leaves the slider at its end."""
        with self.quietly():
            for f, ctl in self.controls.items():
                if only is not None and f not in only:
                    continue
                v = current_value(spec, set_index, f)
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
                sv = _slider_value(c, v)
                if math.isfinite(sv):
                    sv = min(max(sv, ctl.widget.start), ctl.widget.end)
                    if abs(ctl.widget.value - sv) > 0.5 * ctl.widget.step:
                        ctl.widget.value = sv


def _mark(box: TextInput | None, refused: bool) -> None:
    """Mark a text box as holding a refused value (or clear the mark)."""
    if box is None:
        return
    classes = [c for c in box.css_classes if c != REFUSED]
    if refused:
        classes.append(REFUSED)
    if classes != list(box.css_classes):
        box.css_classes = classes
