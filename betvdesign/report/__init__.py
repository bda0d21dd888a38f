"""Design reports: a plain-data report model rendered to self-contained HTML and PDF.

Python use::

    from betvdesign.report import write_reports
    write_reports(["devices/shin2004.yaml"], "reports/")

See :mod:`betvdesign.report.build` (model), :mod:`~betvdesign.report.render`
(Jinja2 + WeasyPrint) and :mod:`~betvdesign.report.write` (files).
"""

from typing import TYPE_CHECKING, Any

from betvdesign.report.analysis import ReportOptions
from betvdesign.report.inputs import PreparedDevice, prepare
from betvdesign.report.model import Report
from betvdesign.report.render import render_html, render_pdf, report_pdf
from betvdesign.report.write import write_reports

if TYPE_CHECKING:
    from betvdesign.report.build import build_report


def __getattr__(name: str) -> Any:
    """``build_report`` on first use: the figures (matplotlib) and the solver (numba) load
    then, not for a report written from the store (:mod:`betvdesign.output.answers`)."""
    if name == "build_report":
        from betvdesign.report.build import build_report

        return build_report
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "PreparedDevice",
    "Report",
    "ReportOptions",
    "build_report",
    "prepare",
    "render_html",
    "render_pdf",
    "report_pdf",
    "write_reports",
]
