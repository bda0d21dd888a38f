"""One presentation vocabulary (betvdesign.output.presentation): the report's figures and
the explore page paint a mode the same colour; the report, the explore page and
``betv check`` call a rule result the same word."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

import pytest
from conftest import DEVICES

from betvdesign.model.domain import VARPI_WINDOW
from betvdesign.output.presentation import MODE_COLORS, STATUS_COLORS, rule_status
from betvdesign.studies.fieldmap import MAP_MODES, FieldAxis, FieldMap

SVG = "{http://www.w3.org/2000/svg}"
#: four modes of a 2×2 map, in grid order (field a slow, field b fast)
GRID = ("push", "pull", "stalled", "not driven")


def _report_legend_colours() -> dict[str, str]:
    """The report's exact-mode map (plots.fieldsweep.mode_map, as report.modemap draws it)
    rendered to the report's inline SVG: each legend word and the fill of the patch
    drawn just before it."""
    from betvdesign.plots.fieldsweep import mode_map
    from betvdesign.plots.figure import figure_svg, new_figure

    rows = [
        {"a": float(i), "b": float(j), "exact_mode": GRID[2 * i + j], "lam": 0.5 + i}
        for i in range(2)
        for j in range(2)
    ]
    summary = {
        "fields": [
            {"field": "a", "unit": "", "points": 2, "device_value": 0.0},
            {"field": "b", "unit": "um", "points": 2, "device_value": 0.0},
        ]
    }
    fig, ax = new_figure()
    mode_map(rows, summary, ax=ax)
    root = ET.fromstring(figure_svg(fig, "t"))
    legend = next(g for g in root.iter(f"{SVG}g") if g.get("id", "").endswith("legend_1"))
    out: dict[str, str] = {}
    fill = None
    for el in legend.iter():
        if el.tag == f"{SVG}path":
            m = re.search(r"fill: (#[0-9a-f]{6})", el.get("style", ""))
            fill = m.group(1) if m else None
        elif el.tag == f"{SVG}text" and fill is not None:
            out[el.text or ""] = fill
    return out


def _explorer_cell_colours() -> dict[str, str]:
    """The explore page's map (its Bokeh ColumnDataSource, drawn as quads filled by
    ``color``) after a job returned the same four modes inside the design window."""
    pytest.importorskip("bokeh")
    from betvdesign.explore.fields import designer_fields
    from betvdesign.explore.mapview import MapView
    from betvdesign.spec.loader import load_device

    spec = load_device(DEVICES / "push_demo.yaml")
    controls = {c.field: c for c in designer_fields(spec, 0)}
    view = MapView(lambda: controls, lambda: None, lambda *a: None, lambda: None)
    fmap = FieldMap.empty(FieldAxis("b", "um", (0.0, 1.0)), FieldAxis("a", "", (0.0, 1.0)), "s")
    view.fmap = fmap
    inside = 0.5 * (VARPI_WINDOW[0] + VARPI_WINDOW[1])
    result = {
        "rows": [0, 1],
        "mode": [[GRID[0], GRID[1]], [GRID[2], GRID[3]]],
        "delta_s": [[0.1, -0.1], [0.0, float("nan")]],
        "speed_m_s": [[1e-3, -1e-3], [0.0, float("nan")]],
        "varpi": [[inside] * 2, [inside] * 2],
        "reasons": [],
    }
    view.add_rows(fmap, result)
    data = view.cells.data
    return {m: c.lower() for m, c in zip(data["mode"], data["color"], strict=True)}


def test_report_and_explorer_paint_each_mode_the_same_colour() -> None:
    report = _report_legend_colours()
    explorer = _explorer_cell_colours()
    assert set(report) >= set(GRID) and set(explorer) == set(GRID)
    for mode in GRID:
        assert report[mode] == explorer[mode], mode
    assert report["push"] != report["pull"]


def test_every_map_mode_has_a_distinct_colour() -> None:
    assert set(MAP_MODES) == set(MODE_COLORS)
    assert len(set(MODE_COLORS.values())) == len(MODE_COLORS)


@pytest.mark.parametrize(
    ("passed", "severity", "word"),
    [
        (True, "error", "pass"),
        (True, "info", "pass"),
        (False, "error", "FAIL"),
        (False, "warning", "warning"),
        (False, "info", "info"),
    ],
)
def test_rule_status_words(passed: bool, severity: str, word: str) -> None:
    assert rule_status(passed, severity) == word
    assert word in STATUS_COLORS


def test_unknown_severity_is_refused() -> None:
    with pytest.raises(ValueError, match="severity"):
        rule_status(False, "fatal")


def test_report_explorer_and_check_text_name_a_failing_warning_alike() -> None:
    """The same failing rule in the three renderings: the report's rule table, the
    explore page's rule list and ``betv check``'s text."""
    from betvdesign.checks.checker import check_derivation
    from betvdesign.checks.view import DeviceView
    from betvdesign.explore.views import verdict_html
    from betvdesign.nondim.device import derive
    from betvdesign.report.build import rule_rows
    from betvdesign.spec.loader import load_device

    view = DeviceView(check_derivation(derive(load_device(DEVICES / "shin2004.yaml"))))
    failing = [r for r in view.rules if not r.passed]
    assert failing, "shin2004 fails rules (the test needs one)"
    r = failing[0]
    word = rule_status(r.passed, r.severity)
    (row,) = [x for x in rule_rows([r])]
    assert row.status == word
    text = view.text()
    assert re.search(rf"^\s+{word} {re.escape(r.id)}\b", text, re.M), text
    html = verdict_html(view.out.model_dump(mode="json"), seq=1, stage="full")
    m = re.search(
        rf'data-rule="{re.escape(r.id)}"[^>]*>\s*<td style="color:([^;]+);[^>]*>(\w+)<', html
    )
    assert m is not None and m.group(2) == word and m.group(1) == STATUS_COLORS[word]
