"""The page's controls: a slider and a text box per designer field, in the field's unit.

A slider moves over the range of :func:`betvdesign.explore.fields.designer_fields`
(in log10 of the value where that range spans decades); the text box beside it shows the
value as the device file writes it and takes any typed value, which the device file's
validation then judges (its message appears under the control). Every change is handed
to ``on_change(changes, fields)`` with ``changes`` = {edit path: file value}.
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
from bokeh.models import Div, Select, Slider, TextInput

from betvdesign.explore.design import set_path
from betvdesign.explore.fields import FieldControl, current_value, designer_fields
from betvdesign.explore.views import error_html

#: Slider positions per control.
SLIDER_STEPS = 200

__all__ = ["SLIDER_STEPS", "Control", "ControlPanel", "css_name"]

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
        self.quiet = False

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
            width=215,
            css_classes=[*css, "betv-slider"],
        )
        text = TextInput(value=c.text(c.value), width=115, css_classes=[*css, "betv-text"])
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
        """The loader's message under each refused field; cleared where a value applied."""
        for f, msg in errors.items():
            if f in self.controls:
                self.controls[f].message.text = error_html(msg)
        for f in ok:
            if f in self.controls and f not in errors:
                self.controls[f].message.text = ""

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
