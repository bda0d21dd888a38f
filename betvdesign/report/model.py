"""The report model: plain, already-formatted data that templates only lay out.

Built first (:mod:`betvdesign.report.build`), rendered second
(:mod:`betvdesign.report.render`). Every value here is a string or a number that
came from the device file, the nondimensional derivation, the design rules or
a solver result; nothing is computed in a template. A value that could not be
computed is never replaced by a number: the field carries the reason instead
(:attr:`FigureBlock.unavailable`, :attr:`SetReport.notes`).
"""

from __future__ import annotations

import html
from dataclasses import dataclass, field
from typing import Literal

from betvdesign.output.presentation import rule_status

Verdict = Literal["pass", "fail", "unknown"]


@dataclass(frozen=True)
class InputRow:
    """One leaf of the device file as written: dotted field path, text, line."""

    path: str
    value: str
    line: int | None


@dataclass(frozen=True)
class DerivationRow:
    """One derived quantity with the formula that gives it (nondim record)."""

    symbol: str
    description: str
    formula: str
    value: str
    inputs: str


@dataclass(frozen=True)
class RuleRow:
    """One design rule result (rules are data: id, severity, value, threshold...)."""

    id: str
    severity: str
    value: str
    threshold: str
    passed: bool
    message: str
    source: str
    fix: str = ""

    @property
    def status(self) -> str:
        """The rule's status word (:func:`betvdesign.output.presentation.rule_status`)."""
        return rule_status(self.passed, self.severity)


@dataclass(frozen=True)
class FigureBlock:
    """A numbered figure: inline SVG (and the same figure as a PNG data URI, ``png``,
    which the PDF shows), or the reason it could not be drawn.

    model: the model that produced the data ("λ fit", "vertical-only exact
    model", "exact event-driven model"...), stated in the caption; rung: the
    rung(s) of the fidelity ladder (:data:`betvdesign.checks.fidelity.RUNGS`, "+" between
    two) and rung_reason why that rung, also in the caption.
    """

    key: str
    title: str
    caption: str
    model: str
    svg: str | None = None
    unavailable: str | None = None
    rung: str = ""
    rung_reason: str = ""
    png: str | None = None


@dataclass(frozen=True)
class KeyValue:
    """A labelled value (verdict box, provenance)."""

    label: str
    value: str


@dataclass(frozen=True)
class VerdictBox:
    """What a reviewer reads first for one actuator set.

    rung / rung_reason: the rung of the fidelity ladder that decided the predicted mode
    (and so the verdict's mode rule) and why (``betv report --fidelity`` forces it).
    """

    verdict: Verdict
    verdict_reason: str
    intended_mode: str
    predicted_mode: str
    predicted_by: str
    lam: str
    fit_mode: str
    speed: str
    crossing_time: str
    vertical: str
    warnings: tuple[str, ...]
    rung: str = ""
    rung_reason: str = ""


@dataclass(frozen=True)
class AdequacyBlock:
    """Section "Model adequacy" of one set: status, a verdict sentence, labelled rows
    and its figures (mode/speed against Q and e; speed against frequency with roll-off)."""

    status: str
    verdict: str
    rows: tuple[KeyValue, ...]
    figures: tuple[FigureBlock, ...]


@dataclass(frozen=True)
class SetReport:
    """Everything the report says about one actuator set."""

    name: str
    intended_mode: str
    params: tuple[KeyValue, ...]
    verdict: VerdictBox
    derivation: tuple[DerivationRow, ...]
    rules: tuple[RuleRow, ...]
    figures: tuple[FigureBlock, ...]
    provenance: tuple[KeyValue, ...]
    same_as: str | None = None
    notes: tuple[str, ...] = ()
    adequacy: AdequacyBlock | None = None


@dataclass(frozen=True, repr=False)
class Report:
    """A whole device report (``repr``: a few lines; ``_repr_html_``: a notebook summary;
    the full page is :func:`betvdesign.report.render_html`)."""

    title: str
    device_name: str
    description: str
    source_file: str
    verdict: Verdict
    inputs: tuple[InputRow, ...]
    sets: tuple[SetReport, ...]
    reproduce: str
    version: str
    device_rules: tuple[RuleRow, ...] = ()
    generated: str | None = None
    notes: tuple[str, ...] = field(default_factory=tuple)

    def figures(self) -> list[FigureBlock]:
        """All figures of the report in reading order (section 4, then the model-adequacy
        section)."""
        adequacy = [f for s in self.sets if s.adequacy for f in s.adequacy.figures]
        return [f for s in self.sets for f in s.figures] + adequacy

    def _set_lines(self) -> list[tuple[str, str]]:
        return [
            (
                s.name,
                f"{s.verdict.verdict.upper()}: {s.verdict.predicted_mode} "
                f"(intended {s.intended_mode}), {s.verdict.speed}",
            )
            for s in self.sets
        ]

    def __repr__(self) -> str:
        head = (
            f"<Report {self.device_name}: {self.verdict.upper()}, {len(self.sets)} set(s), "
            f"{len(self.figures())} figure(s), from {self.source_file or '?'}>"
        )
        return "\n".join([head, *(f"  {n}: {t}" for n, t in self._set_lines())])

    def _repr_html_(self) -> str:
        e = html.escape
        rows = "".join(f"<tr><th>{e(n)}</th><td>{e(t)}</td></tr>" for n, t in self._set_lines())
        return (
            f"<div><b>{e(self.title)}</b>: {e(self.verdict.upper())} "
            f"<small>({e(self.source_file)}; {len(self.figures())} figures)</small>"
            f"<table>{rows}</table></div>"
        )
