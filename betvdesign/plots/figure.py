"""Figure creation and reproducible SVG export shared by every plot family.

Object-oriented matplotlib only (``matplotlib.figure.Figure``, never pyplot): no
global state is touched, so figures can be built concurrently and the caller's
own matplotlib set-up is left alone.

Reproducibility: :func:`figure_svg` fixes ``svg.hashsalt`` (per figure, so the
ids of several SVGs inlined into one HTML page cannot collide), drops the SVG
date metadata, keeps text as ``<text>`` in DejaVu Sans (searchable; the viewer's
installed font, never a download) and prefixes every ``id`` with the figure's key;
:func:`figure_png` writes a PNG without metadata (the same bytes for the same figure);
:func:`figure_svg_png` gives both from one layout.

Speed: tick labels are plain text (:data:`STYLE` turns mathtext off and
:func:`plain_log_ticks` gives logarithmic axes "10³" instead of mathtext): parsing
mathtext for every tick label was half the time of drawing a report's figures.
"""

from __future__ import annotations

import contextlib
import io
import re
from collections.abc import Iterator, Sequence
from typing import Any

import matplotlib
import numpy as np
import PIL.Image
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.ticker import Formatter, LogFormatterMathtext

#: rcParams pinned for every figure of the package, independent of the user's
#: matplotlibrc, so the same inputs give the same bytes on every machine.
STYLE: dict[str, Any] = {
    "font.family": "DejaVu Sans",
    "font.size": 8.5,
    "axes.titlesize": 9.0,
    "axes.labelsize": 8.5,
    "legend.fontsize": 7.5,
    "xtick.labelsize": 7.5,
    "ytick.labelsize": 7.5,
    "lines.linewidth": 1.2,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "grid.linewidth": 0.5,
    # Text stays <text> (DejaVu Sans): a third of the SVG size and WeasyPrint time of
    # glyph paths, selectable/searchable in HTML and PDF; no font file is referenced.
    "svg.fonttype": "none",
    "svg.image_inline": True,
    "path.simplify": True,
    # Plain-text tick labels ("1e−6" offsets, "10³" on log axes via plain_log_ticks):
    # mathtext parsing cost ~20 ms per distinct label.
    "axes.formatter.use_mathtext": False,
    "mathtext.fontset": "dejavusans",
}

#: Colours of the slider/head contact phases (docs/MODEL.md, "Contact").
PHASE_COLORS: dict[str, str] = {
    "free": "#9e9e9e",
    "slip": "#d62728",
    "reverse": "#1f77b4",
    "stick": "#2ca02c",
}

DEVICE_COLOR = "#d62728"


@contextlib.contextmanager
def figure_style() -> Iterator[None]:
    """Context in which figures are built: the package's pinned rcParams."""
    with matplotlib.rc_context(rc=STYLE):
        yield


def new_figure(
    width_in: float = 6.4, height_in: float = 3.4, *, nrows: int = 1, ncols: int = 1, **kw: Any
) -> tuple[Figure, Any]:
    """A constrained-layout :class:`Figure` [inches] and its axes (array if several)."""
    fig = Figure(figsize=(width_in, height_in), layout="constrained")
    axes = fig.subplots(nrows, ncols, squeeze=True, **kw)
    return fig, axes


def axes_or_new(ax: Axes | None, width_in: float = 6.4, height_in: float = 3.4) -> Axes:
    """``ax`` itself, or a fresh single-axes figure when ``ax`` is None."""
    if ax is not None:
        return ax
    _, new_ax = new_figure(width_in, height_in)
    return new_ax


#: A physical axis: (physical units per dimensionless unit, axis label with the unit).
Scale = tuple[float, str]


def legend_below(ax: Axes, *, ncol: int = 2, **kw: Any) -> Any:
    """The axes' legend below them, in ``ncol`` columns, without a frame.

    Inside the axes a legend covers data whatever its place (issue 32: labels over the
    curves); below them the constrained layout makes room for it and for the x label.
    """
    return ax.legend(
        loc="upper center",
        bbox_to_anchor=(0.5, -0.16),
        ncol=ncol,
        frameon=False,
        fontsize=kw.pop("fontsize", 7),
        **kw,
    )


def known_values(values: Sequence[float | None]) -> tuple[np.ndarray, np.ndarray]:
    """Where a series with gaps is known, and its values.

    Parameters
    ----------
    values : sequence of float or None
        The series; None where nothing was found (no periodic orbit, no period).

    Returns
    -------
    known : numpy.ndarray of bool
        True where the entry is a number.
    value : numpy.ndarray of float
        The entries, 0.0 in the gaps (where the figures draw their crosses on zero).
    """
    known = np.array([v is not None for v in values], dtype=bool)
    return known, np.array([v if v is not None else 0.0 for v in values], dtype=float)


def dimensionless_twin(ax: Axes, which: str, factor: float, label: str) -> Any:
    """Secondary axis (top for "x", right for "y") giving the dimensionless value of a
    physical primary axis whose data were multiplied by ``factor`` (physical first,
    dimensionless second)."""

    def fwd(v: Any) -> Any:
        return v / factor

    def inv(v: Any) -> Any:
        return v * factor

    if which == "x":
        sec = ax.secondary_xaxis("top", functions=(fwd, inv))
        sec.set_xlabel(label, fontsize=7.5, color="#555555")
    else:
        sec = ax.secondary_yaxis("right", functions=(fwd, inv))
        sec.set_ylabel(label, fontsize=7.5, color="#555555")
    sec.tick_params(labelsize=7, colors="#555555")
    return sec


_SUPERSCRIPT = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")
_MATHTEXT_RE = re.compile(r"^\$\\mathdefault\{(.*)\}\$$")
_POWER_RE = re.compile(r"\^\{(-?\d+)\}")


class PlainLogFormatter(Formatter):
    """Tick labels of a logarithmic axis in plain text ("10³", "2×10⁻⁴", "0.1"): the
    labels ``inner`` (matplotlib's mathtext log formatter) chooses, written without
    mathtext (nothing to parse when the figure is drawn)."""

    def __init__(self, inner: LogFormatterMathtext) -> None:
        self.inner = inner

    def set_locs(self, locs: Any) -> None:
        self.inner.set_locs(locs)

    def __call__(self, x: float, pos: int | None = None) -> str:
        label = self.inner(x, pos)
        m = _MATHTEXT_RE.match(label)
        if m is None:
            return label
        body = m.group(1).replace("\\times", "×")
        body = _POWER_RE.sub(lambda e: e.group(1).translate(_SUPERSCRIPT), body)
        return body.replace("-", "−")  # the value's own sign (exponents are ⁻ already)


def plain_log_ticks(fig: Figure) -> None:
    """Give every logarithmic axis of ``fig`` (secondary axes included) plain-text tick
    labels (:class:`PlainLogFormatter` around matplotlib's mathtext formatter)."""
    pending = list(fig.axes)
    while pending:
        ax = pending.pop()
        pending.extend(ax.child_axes)
        for axis in (ax.xaxis, ax.yaxis):
            major, minor = axis.get_major_formatter(), axis.get_minor_formatter()
            if isinstance(major, LogFormatterMathtext):
                axis.set_major_formatter(PlainLogFormatter(major))
            if isinstance(minor, LogFormatterMathtext):
                axis.set_minor_formatter(PlainLogFormatter(minor))


def figure_png(fig: Figure, *, dpi: float = 150.0) -> bytes:
    """The figure as an RGB PNG at ``dpi`` [dots per inch], without metadata.

    Byte-reproducible (Agg draws the same pixels for the same figure; no software or
    date chunk). No alpha channel: the figure is opaque, and a PDF writer would split
    an alpha channel into a second image.
    """
    plain_log_ticks(fig)
    canvas = FigureCanvasAgg(fig)
    shown_dpi = fig.dpi
    with matplotlib.rc_context(rc=STYLE):
        try:
            fig.set_dpi(dpi)
            canvas.draw()
            rgba = np.asarray(canvas.buffer_rgba())
        finally:
            fig.set_dpi(shown_dpi)
    buf = io.BytesIO()
    PIL.Image.fromarray(np.ascontiguousarray(rgba[..., :3])).save(
        buf, format="PNG", compress_level=1
    )
    return buf.getvalue()


def figure_svg_png(fig: Figure, key: str, *, dpi: float = 150.0) -> tuple[str, bytes]:
    """The figure as inline SVG (:func:`figure_svg`) and PNG (:func:`figure_png`), its
    layout computed once: the layout engine runs once and is then switched off, so each
    export draws the figure once (a ``savefig`` with a layout engine draws it twice)."""
    plain_log_ticks(fig)
    engine = fig.get_layout_engine()
    if engine is not None:
        with matplotlib.rc_context(rc=STYLE):
            engine.execute(fig)
        fig.set_layout_engine("none")
    return figure_svg(fig, key), figure_png(fig, dpi=dpi)


_ID_RE = re.compile(r'\bid="([^"]+)"')


def _prefix_ids(svg: str, prefix: str) -> str:
    """Prefix every id of ``svg`` and every reference to it (href, url(#...))."""
    ids = set(_ID_RE.findall(svg))
    if not ids:
        return svg

    def sub_id(m: re.Match[str]) -> str:
        return f'id="{prefix}-{m.group(1)}"'

    def sub_ref(m: re.Match[str]) -> str:
        name = m.group(2)
        if name not in ids:
            return m.group(0)
        return f"{m.group(1)}#{prefix}-{name}{m.group(3)}"

    svg = _ID_RE.sub(sub_id, svg)
    return re.sub(r'(href="|url\()#([^")]+)([")])', sub_ref, svg)


def figure_svg(fig: Figure, key: str) -> str:
    """The figure as an ``<svg>`` element string, ready to inline into HTML.

    Byte-reproducible: hash salt fixed to ``key``, no date metadata, ids
    prefixed with ``key`` (a short [A-Za-z0-9_-] string unique within
    the page). The XML prolog, DOCTYPE and RDF metadata are dropped.
    """
    if not re.fullmatch(r"[A-Za-z][A-Za-z0-9_-]*", key):
        raise ValueError(f"figure key must be a simple identifier, got {key!r}")
    plain_log_ticks(fig)
    buf = io.StringIO()
    with matplotlib.rc_context(rc={**STYLE, "svg.hashsalt": f"betvdesign-{key}"}):
        fig.savefig(buf, format="svg", metadata={"Date": None, "Creator": None})
    text = buf.getvalue()
    start = text.find("<svg")
    if start < 0:  # pragma: no cover - matplotlib always writes an <svg> root
        raise RuntimeError("matplotlib produced no <svg> element")
    svg = text[start:].strip()
    # The RDF <metadata> block only names matplotlib and the image type; dropping it
    # leaves no namespace URI but the SVG/XLink ones in the page.
    svg = re.sub(r"\s*<metadata>.*?</metadata>", "", svg, flags=re.S)
    svg = re.sub(r'\s+xmlns:(?:dc|cc|rdf)="[^"]*"', "", svg)
    return _prefix_ids(svg, key)
