"""Fuzzing the bounded parsers (issue 15): any text given as a quantity either parses
or raises the one user-facing ValueError, quickly, whatever pint would have made of
it; any YAML built from anchors, aliases and nesting is either loaded or refused with
a SpecError at a position — never another exception, never unbounded work."""

from __future__ import annotations

import time

import pint
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from betvdesign.errors import SpecError
from betvdesign.spec import limits
from betvdesign.spec.loader import load_device_text
from betvdesign.spec.units import parse_quantity

TOKENS = st.sampled_from(
    ["1", "9", "2.5e3", "nan", "-", "+", " ", "*", "**", "^", "/", "(", ")", "um", "m",
     "kHz", "V", "deg", "degC", "%", "µ", "e", "9e99", "kg", "_", "x"]
)  # fmt: skip


@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(TOKENS, max_size=40).map("".join) | st.text(max_size=60))
def test_parse_quantity_is_bounded_and_total(text: str) -> None:
    t0 = time.perf_counter()
    try:
        q = parse_quantity(text)
    except ValueError as exc:
        assert str(exc) and "Traceback" not in str(exc)
    else:
        assert isinstance(q, pint.Quantity)
        # what is accepted has the bounded shape: one power per factor, modest powers
        assert text.count("**") + text.count("^") <= limits.MAX_UNIT_FACTORS
    assert time.perf_counter() - t0 < 1.0


def _yaml(draw, depth: int = 0) -> str:
    kind = draw(st.sampled_from(["scalar", "alias", "list", "map"] if depth < 5 else ["scalar"]))
    if kind == "scalar":
        return draw(st.sampled_from(["1", "a", "'5 um'", "null", "[]", "{}"]))
    if kind == "alias":
        return draw(st.sampled_from(["*a", "*b", "*c"]))
    n = draw(st.integers(1, 4))
    items = [_yaml(draw, depth + 1) for _ in range(n)]
    anchor = draw(st.sampled_from(["", "&a ", "&b ", "&c "]))
    if kind == "list":
        return anchor + "[" + ", ".join(items) + "]"
    return anchor + "{" + ", ".join(f"k{i}: {v}" for i, v in enumerate(items)) + "}"


@st.composite
def yaml_docs(draw) -> str:
    return "name: x\nslider: " + _yaml(draw) + "\nactuator_sets: " + _yaml(draw) + "\n"


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(yaml_docs())
def test_loader_refuses_or_loads_any_anchor_nesting_mix(text: str) -> None:
    t0 = time.perf_counter()
    try:
        load_device_text(text, "fuzz.yaml")
    except SpecError as exc:
        assert all(str(i).startswith("fuzz.yaml") for i in exc.issues)
    assert time.perf_counter() - t0 < 5.0


@pytest.mark.parametrize("levels", [5, 6, 12])
def test_alias_bombs_of_any_depth_are_refused_fast(levels: int) -> None:
    lines = ["a0: &a0 [x, x, x, x, x, x, x, x, x, x]"]
    lines += [f"a{i}: &a{i} [{', '.join([f'*a{i - 1}'] * 10)}]" for i in range(1, levels)]
    t0 = time.perf_counter()
    with pytest.raises(SpecError, match=r"fuzz\.yaml:\d+:\d+: a\d+.*YAML nodes"):
        load_device_text("\n".join(lines) + "\n", "fuzz.yaml")
    assert time.perf_counter() - t0 < 2.0
