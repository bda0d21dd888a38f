"""The failure map (betvdesign.bench.failures) and its tests stay in step.

Source: the repository itself: every catalogued failure names an existing test file
that reproduces it, and every tests/test_failure_*.py reproduces a catalogued one.
"""

from __future__ import annotations

from pathlib import Path

from betvdesign.bench.failures import FAILURES

ROOT = Path(__file__).resolve().parent.parent


def test_every_failure_has_its_test():
    ids = [f.id for f in FAILURES]
    assert len(ids) == len(set(ids))
    for f in FAILURES:
        path = ROOT / f.test
        assert path.is_file(), f"{f.id}: {f.test} missing"
        assert "def test_" in path.read_text()
        assert all([f.title, f.methods, f.where, f.symptom, f.ours])


def test_every_failure_test_is_catalogued():
    named = {f.test for f in FAILURES}
    files = {f"tests/{p.name}" for p in (ROOT / "tests").glob("test_failure_*.py")}
    files.discard("tests/test_failure_catalogue.py")
    assert files == named
