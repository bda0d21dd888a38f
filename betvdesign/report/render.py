"""Render a :class:`~betvdesign.report.model.Report` to HTML and PDF, write atomically.

HTML: one self-contained file (inline CSS, inline SVG, no scripts, no external
references), from a Jinja2 template with autoescape on. PDF: WeasyPrint renders
the same HTML and CSS. Both are byte-reproducible for the same report: no date
is written unless the report carries one (``betv report --timestamp``), and
WeasyPrint's PDF is deterministic for the same HTML and fonts.
"""

from __future__ import annotations

import logging
from importlib import resources

import jinja2
from markupsafe import Markup

from betvdesign.output.files import write_atomic
from betvdesign.report.model import Report

__all__ = ["render_html", "render_pdf", "render_template", "write_atomic"]

_TEMPLATE = "report.html.j2"
_CSS = "report.css"


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


def render_html(report: Report) -> str:
    """The report as one self-contained HTML document [str]."""
    return render_template(_TEMPLATE, r=report)


def render_pdf(html: str) -> bytes:
    """PDF bytes of ``html`` rendered by WeasyPrint (A4, fonts embedded).

    Nothing outside the document is fetched: the HTML is self-contained and the
    URL fetcher refuses every request.
    """
    import weasyprint  # heavy import, only when a PDF is wanted

    def no_fetch(url: str, *args: object, **kwargs: object) -> dict[str, object]:
        raise ValueError(f"report references an external resource {url!r}")

    # Inline SVG style attributes (fill, stroke...) reach WeasyPrint's HTML cascade,
    # which warns that they are unknown CSS properties before the SVG renderer uses
    # them; those warnings are noise, anything worse is still reported.
    logger = logging.getLogger("weasyprint")
    level = logger.level
    logger.setLevel(logging.ERROR)
    try:
        doc = weasyprint.HTML(string=html, base_url=None, url_fetcher=no_fetch)
        return doc.write_pdf()
    finally:
        logger.setLevel(level)
