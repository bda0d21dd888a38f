"""Range parsing and grids (source: hand-written ranges and hypothesis invariants)."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from betvdesign.errors import UsageError
from betvdesign.studies.engine.grid import Grid, parse_range


def test_colon_range_includes_stop_on_the_lattice():
    """0.5:2:0.1 has 16 points, 0.5 ... 2.0, each start + i*step (no accumulation)."""
    v = parse_range("0.5:2:0.1", "varpi")
    assert v.size == 16
    assert v[0] == 0.5 and v[-1] == 2.0
    assert np.array_equal(v[:-1], 0.5 + 0.1 * np.arange(15))


def test_colon_range_stop_off_lattice_is_not_exceeded():
    v = parse_range("0:1:0.3", "alpha")
    assert np.allclose(v, [0.0, 0.3, 0.6, 0.9])


def test_list_and_single_value():
    assert parse_range("0.1, 0.5,1", "beta").tolist() == [0.1, 0.5, 1.0]
    assert parse_range("0.4", "kappa").tolist() == [0.4]


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("", "empty range"),
        ("   ", "empty range"),
        ("2:1:0.1", "inverted range"),
        ("1:2:0", "step must be > 0"),
        ("1:2:-0.1", "step must be > 0"),
        ("1:2", "three fields"),
        ("a:2:0.1", "not a number"),
        ("0.1,,0.2", "empty item"),
        ("0.1,x", "not a number"),
        ("nan", "not finite"),
        ("0.1,0.1", "duplicate"),
        ("0:1:1e-9", "points"),
    ],
)
def test_bad_ranges_name_the_parameter(text, fragment):
    with pytest.raises(UsageError) as exc:
        parse_range(text, "varpi")
    assert str(exc.value).startswith("varpi:")
    assert fragment in str(exc.value)


@given(
    start=st.floats(-100, 100),
    span=st.floats(0, 50),
    step=st.floats(1e-3, 10),
)
def test_range_invariants(start, span, step):
    """Points start at start, are spaced by step, never pass stop by more than round-off."""
    stop = start + span
    v = parse_range(f"{start!r}:{stop!r}:{step!r}", "x")
    assert v[0] == start
    assert v[-1] <= stop + 1e-9 * max(abs(stop), step)
    assert stop - v[-1] < step * (1 + 1e-9) + 1e-12
    assert v.size == 1 or np.allclose(np.diff(v), step, rtol=1e-6, atol=1e-9 * abs(start))


def test_grid_keys_are_c_order_and_point_lookup_matches_iteration():
    g = Grid({"a": [1.0, 2.0], "b": [10.0, 20.0, 30.0]})
    pts = list(g)
    assert g.size == 6 == len(pts) == math.prod(g.shape)
    assert [p.key for p in pts] == list(range(6))
    assert pts[1].values == {"a": 1.0, "b": 20.0}
    assert all(g.point(p.key) == p for p in pts)
    with pytest.raises(UsageError):
        Grid({"a": []})
