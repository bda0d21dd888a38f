"""The one bisection (betvdesign.model.bisection) against closed-form roots and counts."""

from __future__ import annotations

import math

import pytest

from betvdesign.model.bisection import bisect


def test_width_stop_brackets_the_closed_form_root_in_the_predicted_evaluations() -> None:
    calls: list[float] = []

    def above(x: float) -> bool:
        calls.append(x)
        return x * x > 2.0

    width = 1e-9
    br = bisect(above, 1.0, 2.0, False, True, width=width)
    assert br.a <= math.sqrt(2.0) <= br.b
    assert br.b - br.a <= width
    assert abs(br.mid - math.sqrt(2.0)) <= width / 2
    # each step halves the bracket: ceil(log2(1/width)) midpoints, each classified once
    assert br.evaluations == len(calls) == math.ceil(math.log2(1.0 / width))
    assert calls[:3] == [1.5, 1.25, 1.375]


def test_ratio_stop_with_geometric_midpoints_from_either_side() -> None:
    root = 10.0 ** (1.0 / 3.0)  # x³ = 10
    rtol = 1e-6
    up = bisect(lambda x: x**3 < 10.0, 1.0, 100.0, True, False, rtol=rtol, geometric=True)
    down = bisect(lambda x: x**3 > 10.0, 100.0, 1.0, True, False, rtol=rtol, geometric=True)
    for br in (up, down):
        assert abs(math.log(br.a / br.b)) <= rtol
        assert min(br.a, br.b) <= root <= max(br.a, br.b)
        # the bracket's log-width halves per step: ln(100)/2^k ≤ rtol
        assert br.evaluations == math.ceil(math.log2(math.log(100.0) / rtol))
        assert br.mid == pytest.approx(root, rel=rtol)
    assert up.a < root < down.a  # ``a`` keeps its class: below the root, and above it


def test_fixed_steps_and_a_third_class_ending_the_bracket() -> None:
    def mode(x: float) -> str:
        return "push" if x < 0.3 else ("stalled" if x < 0.31 else "pull")

    br = bisect(mode, 0.0, 1.0, "push", "pull", steps=20)
    assert br.evaluations == 20
    assert br.b - br.a == pytest.approx(2.0**-20)
    # the first change going from a is kept: push → stalled at 0.3, not stalled → pull
    assert br.a <= 0.3 <= br.b and br.at_b == "stalled"


def test_a_narrow_bracket_takes_no_evaluation() -> None:
    br = bisect(lambda x: pytest.fail("evaluated"), 1.0, 1.5, "a", "b", width=1.0)
    assert (br.a, br.b, br.at_b, br.evaluations, br.mid) == (1.0, 1.5, "b", 0, 1.25)


@pytest.mark.parametrize(
    "kw", [{}, {"width": 1.0, "steps": 3}, {"rtol": 0.1, "width": 1.0, "steps": 2}]
)
def test_exactly_one_stop_rule(kw: dict) -> None:
    with pytest.raises(ValueError, match="exactly one"):
        bisect(lambda x: x > 0.5, 0.0, 1.0, False, True, **kw)


def test_geometric_bracket_must_be_positive() -> None:
    with pytest.raises(ValueError, match="positive"):
        bisect(lambda x: x > 0.5, 0.0, 1.0, False, True, steps=3, geometric=True)
