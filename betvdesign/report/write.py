"""Write reports of device files: ``NAME.html`` and ``NAME.pdf`` per file (NAME = file stem).

Every input is loaded and validated before anything is computed or written, so
bad input leaves no file behind; the output directory is checked for writability
first, and each device's HTML and PDF are written as a pair (both or neither).
"""

from __future__ import annotations

import dataclasses
import datetime as _dt
import json
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from betvdesign.errors import UsageError, each_or_issues
from betvdesign.output import answers
from betvdesign.output.files import check_output_dir, write_group
from betvdesign.report.analysis import ReportOptions
from betvdesign.report.inputs import PreparedDevice, prepare
from betvdesign.report.render import render_html, report_pdf


@dataclass(frozen=True)
class Written:
    """Files written for one device and its verdict."""

    source: Path
    html: Path
    pdf: Path | None
    verdict: str
    figures: int


def write_reports(
    paths: Sequence[str | Path],
    outdir: str | Path,
    *,
    pdf: bool = True,
    timestamp: bool = False,
    options: ReportOptions | None = None,
    progress: Callable[[int, int], None] | None = None,
    cache: bool = False,
) -> list[Written]:
    """Report every device file in ``paths`` into ``outdir``.

    ``progress(done, total)`` is called after each step (per device: analysis and
    figures, HTML, PDF), once inputs are valid; a report takes seconds per device.
    ``cache``: write the stored HTML and PDF of an identical earlier report (the same
    bytes of every file read, options, code and installed packages:
    :mod:`betvdesign.output.answers`) and store new ones; never with ``timestamp``.

    Raises :class:`~betvdesign.errors.SpecError` (bad device file) or
    :class:`~betvdesign.errors.UsageError` (no files, clashing names, unusable
    output directory) before
    writing anything.
    """
    if not paths:
        raise UsageError("give at least one device file")
    check_output_dir(outdir, create=False)  # before any work: nothing is made yet
    stems: dict[str, Path] = {}
    for p in map(Path, paths):
        if p.stem in stems and stems[p.stem] != p:
            raise UsageError(f"{stems[p.stem]} and {p} would both write {p.stem}.html")
        stems[p.stem] = p
    reads: dict[Path, list[str]] = {}

    def prepare_noted(path: Path) -> PreparedDevice:
        with answers.recording() as log:
            dev = prepare(path)
        reads[path] = log
        return dev

    prepared = each_or_issues(prepare_noted, stems.values())  # every file's issues at once
    out = check_output_dir(outdir)
    generated = _dt.datetime.now(_dt.UTC).replace(microsecond=0).isoformat() if timestamp else None
    written: list[Written] = []
    steps, done = len(prepared) * (3 if pdf else 2), 0

    def step() -> None:
        nonlocal done
        done += 1
        if progress is not None:
            progress(done, steps)

    if progress is not None:
        progress(0, steps)
    full = options is not None and options.full
    settings = {
        "pdf": pdf,
        "options": dataclasses.asdict(options or ReportOptions()),
    }
    for dev in prepared:
        html_path = out / f"{dev.path.stem}.html"
        pdf_path = out / f"{dev.path.stem}.pdf" if pdf else None
        key = (
            answers.answer_key("report", settings, [dev.path]) if cache and not generated else None
        )
        hit = answers.lookup(key) if key is not None else None
        if hit is not None and set(hit.files) == {p.name for p in (html_path, pdf_path) if p}:
            for _ in range(3 if pdf else 2):
                step()
            write_group({p: hit.files[p.name] for p in (html_path, pdf_path) if p is not None})
            meta = json.loads(hit.stdout)
            written.append(Written(dev.path, html_path, pdf_path, meta["verdict"], meta["figures"]))
            continue
        from betvdesign.report.build import build_report  # figures, solver: only to build

        with answers.recording() as log:
            report = build_report(
                dev,
                options=options,
                generated=generated,
                reproduce=f"betv report {dev.path} -o DIR" + (" --full" if full else ""),
            )
        step()
        html = render_html(report)
        files: dict[Path, str | bytes] = {html_path: html}
        step()
        if pdf_path is not None:
            files[pdf_path] = report_pdf(report)
            step()
        write_group(files)  # HTML and PDF together, or neither
        w = Written(dev.path, html_path, pdf_path, report.verdict, len(report.figures()))
        written.append(w)
        if key is not None:
            meta = json.dumps({"verdict": w.verdict, "figures": w.figures})
            data = {
                p.name: d.encode("utf-8") if isinstance(d, str) else d for p, d in files.items()
            }
            answers.store(key, answers.Answer(meta, "", 0, data), reads[dev.path] + log)
    return written
