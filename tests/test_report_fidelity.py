"""Design reports state the fidelity rung of every figure and of every verdict; the
verdict's mode is always the exact periodic orbit's (no rung can be forced for it).

Sources: :func:`betvdesign.checks.fidelity.choose_rung` (the ladder's reasons, restated per
figure question); the verdict against ``betv check`` (:func:`betvdesign.checks.checker.
check_derivation`, a second path that solves for itself). One small device only.
"""

from __future__ import annotations

from pathlib import Path

from conftest import DEVICES
from test_report import SMALL, text_of
from typer.testing import CliRunner

from betvdesign.checks.checker import check_derivation
from betvdesign.checks.fidelity import RUNGS, choose_rung
from betvdesign.cli import app
from betvdesign.nondim.device import derive_file
from betvdesign.report import build_report, prepare, render_html

PULL = DEVICES / "pull_demo.yaml"


def test_every_figure_and_verdict_states_its_rung() -> None:
    """Each figure names a ladder rung and why (the ladder's own reason for regime and
    trajectory questions); the verdict's mode comes from the report's periodic orbit."""
    report = build_report(prepare(PULL), options=SMALL)
    p = derive_file(PULL).sets[0].params
    figs = report.figures()
    assert figs and all(f.rung and f.rung_reason for f in figs)
    for f in figs:
        assert set(f.rung.split(" + ")) <= set(RUNGS), f.rung
    by_key = {f.key.split("-", 1)[1]: f for f in figs}
    assert by_key["pushpull"].rung == "lambda"
    assert by_key["regime"].rung_reason == choose_rung(p, "regime").reason
    assert by_key["displacement"].rung_reason == choose_rung(p, "transient").reason
    assert by_key["speed"].rung_reason == choose_rung(p, "delta_s", tol=1e-10).reason
    box = report.sets[0].verdict
    assert box.rung == "periodic" and "exact periodic orbit" in box.rung_reason
    assert box.predicted_mode == "pull"
    text = text_of(render_html(report))
    assert text.count("Fidelity rung: ") == len(figs)
    assert "Decided by (fidelity rung) periodic" in text


def test_report_verdict_equals_the_check_and_refuses_a_forced_rung(tmp_path: Path) -> None:
    """The report's rules (fed its own orbits) equal `betv check`'s (solving for itself);
    `--fidelity` no longer exists on `betv report` (exit 2, nothing written)."""
    report = build_report(prepare(PULL), options=SMALL)
    check = check_derivation(derive_file(PULL))
    shown = {r.id: (r.severity, r.passed, r.message) for r in report.sets[0].rules}
    solved = {r.id: (r.severity, r.passed, r.message) for r in check.sets[0].rules}
    assert shown == solved  # messages carry the numbers: Δs, speed, λ, margins
    text = text_of(render_html(report))
    for r in check.sets[0].rules:
        assert r.id in text and r.message in text
    assert report.sets[0].verdict.verdict == check.verdict
    bad = CliRunner().invoke(
        app, ["report", str(PULL), "-o", str(tmp_path / "x"), "--fidelity", "lambda"]
    )
    assert bad.exit_code == 2 and not (tmp_path / "x").exists()
