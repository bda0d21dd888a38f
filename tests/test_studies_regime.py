"""Vertical regime diagram (sources: interval bookkeeping on hand-made rows)."""

from betvdesign.studies.regime import intervals, summarise


def _rows(labels):
    return [
        {"key": i, "varpi": 0.1 * (i + 1), "label": lab, "status": "success", "message": ""}
        for i, lab in enumerate(labels)
    ]


def test_intervals_are_contiguous_runs_in_varpi_order():
    rows = _rows(["multi-hit", "multi-hit", "period-1", "period-1", "period-1", "impulsive"])
    got = [(i.label, round(i.lo, 9), round(i.hi, 9), i.points) for i in intervals(rows[::-1])]
    assert got == [
        ("multi-hit", 0.1, 0.2, 2),
        ("period-1", 0.3, 0.5, 3),
        ("impulsive", 0.6, 0.6, 1),
    ]
    s = summarise(rows)
    assert s["counts"] == {"multi-hit": 2, "period-1": 3, "impulsive": 1}
    assert s["errors"] == []
