"""Render a :class:`~betvdesign.report.model.Report` to HTML and PDF, write atomically.

HTML: one self-contained file (inline CSS, inline SVG, no scripts, no external
references), from a Jinja2 template with autoescape on. PDF: WeasyPrint renders
the same HTML and CSS with each figure as the PNG matplotlib drew from the same
figure (:func:`report_pdf`). Both are byte-reproducible for the same report: no date
is written unless the report carries one (``betv report --timestamp``), and
WeasyPrint's PDF is deterministic for the same HTML and fonts.
"""

from __future__ import annotations

import contextlib
import io
import logging
import os
import sys
from importlib import resources
from types import ModuleType

import jinja2
from markupsafe import Markup

from betvdesign.output.files import write_atomic
from betvdesign.report.model import Report

__all__ = ["render_html", "render_pdf", "render_template", "report_pdf", "write_atomic"]

_TEMPLATE = "report.html.j2"
_CSS = "report.css"


#: The timestamp [s since 1970] written into the PDF's embedded font subsets when the
#: environment gives no SOURCE_DATE_EPOCH: 2024-01-01T00:00:00Z (any fixed value does).
PDF_EPOCH = 1_704_067_200


def _environment() -> jinja2.Environment:
    return jinja2.Environment(
        loader=jinja2.PackageLoader("betvdesign.report", "templates"),
        autoescape=True,
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
    )


def _css() -> str:
    return resources.files("betvdesign.report").joinpath("templates", _CSS).read_text("utf-8")


def render_template(name: str, **context: object) -> str:
    """One of the package's HTML templates rendered with the shared stylesheet.

    Parameters
    ----------
    name
        File name of the template in ``betvdesign/report/templates``.
    **context
        Template variables; ``css`` (the stylesheet, inlined) is added.

    Returns
    -------
    str
        The self-contained HTML document.
    """
    return _environment().get_template(name).render(css=Markup(_css()), **context)


def render_html(report: Report, *, raster: bool = False) -> str:
    """The report as one self-contained HTML document.

    Parameters
    ----------
    report : Report
        The report model.
    raster : bool
        Show each figure as its PNG (:attr:`~betvdesign.report.model.FigureBlock.png`)
        instead of its inline SVG: the document :func:`report_pdf` renders.

    Returns
    -------
    str
        The HTML document.
    """
    return render_template(_TEMPLATE, r=report, raster=raster)


def report_pdf(report: Report) -> bytes:
    """PDF bytes of ``report``: :func:`render_pdf` of its HTML with the figures as PNG
    (drawn once by matplotlib; WeasyPrint drawing inline SVG took most of its time)."""
    return render_pdf(render_html(report, raster=True))


def _no_search(name: str) -> None:
    """A ``ctypes.util.find_library`` that finds nothing, without running a program."""
    return None


def _import_weasyprint() -> ModuleType:
    """Import WeasyPrint without its search for libraries by running programs.

    WeasyPrint opens pango, gobject, harfbuzz... through cffi, trying several names for
    each; cffi sends a name it cannot open directly to ``ctypes.util.find_library``, which
    runs ``ldconfig``, ``gcc`` and ``ld`` (about 50 programs, 0.2 s). Every list also
    holds the file name that the dynamic loader opens directly (``libpango-1.0.so.0``,
    ``libpango-1.0.dylib``), so the import is tried first with a ``find_library`` that
    finds nothing; where that fails (a system that needs the search) WeasyPrint is
    imported again as it ships.

    Returns
    -------
    ModuleType
        The ``weasyprint`` module.
    """
    if "weasyprint" in sys.modules:
        return sys.modules["weasyprint"]
    import ctypes.util

    find = ctypes.util.find_library
    ctypes.util.find_library = _no_search
    try:
        # a failed first try prints WeasyPrint's installation advice: not shown, the
        # second import prints it again if the libraries are really missing
        with contextlib.redirect_stdout(io.StringIO()):
            import weasyprint
    except OSError:
        for name in [m for m in sys.modules if m.split(".")[0] == "weasyprint"]:
            del sys.modules[name]
    else:
        return weasyprint
    finally:
        ctypes.util.find_library = find
    import weasyprint

    return weasyprint


def render_pdf(html: str) -> bytes:
    """PDF bytes of ``html`` rendered by WeasyPrint (A4, fonts embedded).

    Nothing outside the document is fetched: the HTML is self-contained (its images
    are ``data:`` URIs) and the URL fetcher refuses every other scheme.
    """
    weasyprint = _import_weasyprint()  # heavy import, only when a PDF is wanted

    fetcher: object
    if hasattr(weasyprint.urls, "URLFetcher"):  # newer WeasyPrint: a fetcher object
        fetcher = weasyprint.urls.URLFetcher(allowed_protocols={"data"}, fail_on_errors=True)
    else:  # pragma: no cover - older WeasyPrint: a function

        def fetcher(url: str, *args: object, **kwargs: object) -> object:
            if not url.startswith("data:"):
                raise ValueError(f"report references an external resource {url!r}")
            return weasyprint.default_url_fetcher(url, *args, **kwargs)

    # Inline SVG style attributes (fill, stroke...) reach WeasyPrint's HTML cascade,
    # which warns that they are unknown CSS properties before the SVG renderer uses
    # them; those warnings are noise, anything worse is still reported.
    logger = logging.getLogger("weasyprint")
    level = logger.level
    logger.setLevel(logging.ERROR)
    # The embedded font subsets carry a "modified" timestamp (fontTools' head table):
    # the time of writing unless SOURCE_DATE_EPOCH is set (reproducible-builds.org), so
    # two runs a second apart wrote different bytes. The report's PDF is byte-reproducible:
    # the timestamp is pinned for the write (a caller's own SOURCE_DATE_EPOCH wins).
    pinned = "SOURCE_DATE_EPOCH" not in os.environ
    if pinned:
        os.environ["SOURCE_DATE_EPOCH"] = str(PDF_EPOCH)
    try:
        doc = weasyprint.HTML(string=html, base_url=None, url_fetcher=fetcher)
        return doc.write_pdf()
    finally:
        logger.setLevel(level)
        if pinned:
            del os.environ["SOURCE_DATE_EPOCH"]
