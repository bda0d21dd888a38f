"""Design reports state the fidelity rung of every figure and of every verdict, and
`betv report --fidelity RUNG` forces the rung that decides the mode.

Sources: :func:`betvdesign.fidelity.choose_rung` (the ladder's reasons, restated per
figure question); the verdict and rule outcomes against ``betv check --fidelity``
(:func:`betvdesign.checker.check_derivation`, second path that solves for itself);
pull_demo (ϖ = 0.8, β = 1.2, λ = 5.2) lies within the measured λ trust margin, so a
forced λ rung must show the λ-margin warning. One small device only (reports are slow).
"""

from __future__ import annotations

import re
from pathlib import Path

from conftest import DEVICES
from test_report import SMALL, text_of
from typer.testing import CliRunner

from betvdesign.checker import check_derivation
from betvdesign.cli import app
from betvdesign.fidelity import RUNGS, choose_rung
from betvdesign.nondim import derive_file
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
    assert box.rung == "periodic" and "figures" in box.rung_reason
    assert box.predicted_mode == "pull"
    text = text_of(render_html(report))
    assert text.count("Fidelity rung: ") == len(figs)
    assert "Decided by (fidelity rung) periodic" in text


def test_cli_fidelity_forces_the_verdict_rung(tmp_path: Path) -> None:
    """--fidelity lambda: the verdict box says λ decided (forced) and the rule outcomes
    equal `betv check --fidelity lambda`'s, including the measured λ-margin warning; a
    rung that cannot tell the mode is exit 2 with nothing written."""
    runner = CliRunner()
    bad = runner.invoke(
        app, ["report", str(PULL), "-o", str(tmp_path / "x"), "--fidelity", "vertical"]
    )
    assert bad.exit_code == 2 and "cannot answer 'mode'" in bad.output
    assert not (tmp_path / "x").exists()
    out = tmp_path / "o"
    res = runner.invoke(
        app, ["report", str(PULL), "-o", str(out), "--no-pdf", "--fidelity", "lambda"]
    )
    assert res.exit_code == 0, res.output
    html = (out / "pull_demo.html").read_text("utf-8")
    text = text_of(html)
    assert "Decided by (fidelity rung) lambda (forced by --fidelity lambda" in text
    check = check_derivation(derive_file(PULL), fidelity="lambda")
    rows = re.findall(
        r"<tr class=\"[^\"]*\"><td><code>([^<]+)</code></td><td>(\w+)</td>"
        r"<td class=\"num\">[^<]*</td><td>[^<]*</td><td>(pass|FAIL)</td>",
        html,
    )
    shown = sorted((rid, sev, res == "pass") for rid, sev, res in rows)
    assert shown == sorted((r.id, r.severity, r.passed) for r in check.rules)
    assert ("lambda-margin", "warning", False) in shown
