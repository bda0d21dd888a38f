"""The hostile-input corpus (issue 15): every case ends within 30 s with exit 0, 1 or
2, no traceback, the expected message (file:line:col when a file is involved) and no
output beyond what a successful run writes. The cases are in tests/hostile_corpus.py;
run that module as a script for the table by category."""

from __future__ import annotations

from pathlib import Path

import pytest
from hostile_corpus import TIME_LIMIT_S, Case, corpus, inputs, prepare, verdict
from typer.testing import CliRunner

from betvdesign.cli import app

CASES = corpus()


@pytest.mark.timeout(TIME_LIMIT_S)
@pytest.mark.parametrize("case", CASES, ids=[f"{c.category}:{c.id}" for c in CASES])
def test_hostile_case(case: Case, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    args = prepare(case, tmp_path)
    before = inputs(case, tmp_path)
    r = CliRunner().invoke(app, args, env={"COLUMNS": "200"})
    if r.exception is not None and not isinstance(r.exception, SystemExit):
        import traceback

        tb = "".join(traceback.format_exception(r.exception))
        pytest.fail(f"uncaught {type(r.exception).__name__}:\n{tb}")
    problems = verdict(case, tmp_path, before, r.exit_code, r.stdout, r.stderr)
    assert not problems, f"{problems}\nstdout: {r.stdout[-1500:]}\nstderr: {r.stderr[-1500:]}"


def test_corpus_covers_every_category() -> None:
    """The categories the issue names, each with a real number of cases."""
    counts: dict[str, int] = {}
    for c in CASES:
        counts[c.category] = counts.get(c.category, 0) + 1
    assert set(counts) == {"yaml", "units", "structure", "names", "cli-numbers", "cli-paths"}
    assert min(counts.values()) >= 5 and sum(counts.values()) >= 90
