"""Design reports: a plain-data report model rendered to self-contained HTML and PDF.

Python use::

    from betvdesign.report import write_reports
    write_reports(["devices/shin2004.yaml"], "reports/")

See :mod:`betvdesign.report.build` (model), :mod:`~betvdesign.report.render`
(Jinja2 + WeasyPrint) and :mod:`~betvdesign.report.write` (files).
"""

from betvdesign.report.analysis import ReportOptions
from betvdesign.report.build import PreparedDevice, build_report, prepare
from betvdesign.report.model import Report
from betvdesign.report.render import render_html, render_pdf, report_pdf
from betvdesign.report.write import write_reports

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
