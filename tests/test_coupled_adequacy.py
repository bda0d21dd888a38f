"""The adequacy study's coupled rung (betvdesign.checks.coupled).

Independent truths: at ρ = 0 the coupled reference's orbit is the exact solver's
(docs/MODEL.md "Coupled head", reduction); on the published device the coupled answer is
a fixed point of the coupled reference's own cycle map run as a plain transient (a
second use of the map, not of Newton); the verdict rules against hand-made answers.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from betvdesign.checks.coupled import Answer, _status, coupled_rung, coupling_of
from betvdesign.dynamics.coupled_reference import simulate_coupled
from betvdesign.errors import ParameterError
from betvdesign.nondim.device import derive_file

DEVICES = Path(__file__).resolve().parents[1] / "devices"


@pytest.fixture(scope="module")
def pull_set():
    return derive_file(DEVICES / "pull_demo.yaml").sets[0]


def test_decoupled_drawing_agrees_with_exact(pull_set):
    """ρ = 0: the coupled answer is the exact decoupled one (Δs to 1e-8), status agrees."""
    sd = replace(pull_set, springs=replace(pull_set.springs, rho=0.0))
    r = coupled_rung(sd)
    assert r.status == "coupled-agrees"
    assert r.coupled.status == "success"
    assert abs(r.coupled.delta_s - r.decoupled.delta_s) < 1e-8 * abs(r.decoupled.delta_s)
    assert r.uses == "decoupled"  # the file gives its resonances
    assert "finding" in r.message


def test_published_device_coupled_orbit_is_periodic():
    """shin2004 (ρ ≈ 0.988): the coupled orbit repeats under a plain transient of the map
    and its mode or speed differs from the decoupled springs' by more than 10 %."""
    sd = derive_file(DEVICES / "shin2004.yaml").sets[0]
    r = coupled_rung(sd)
    assert r.status == "coupled-differs"
    assert r.coupled.status == "success"
    run = simulate_coupled(replace(sd.params), coupling_of(sd), 3, state0=r.coupled.state)
    assert np.allclose(run.delta_s, r.coupled.delta_s, rtol=1e-7, atol=0)
    assert np.allclose(
        run.section[-1][[0, 1, 2, 3, 5]], r.coupled.state[[0, 1, 2, 3, 5]], atol=1e-7
    )
    change = r.speed_change
    assert r.coupled.mode != r.decoupled.mode or abs(change) > 0.1


def test_no_drawing_no_rung(pull_set):
    assert coupled_rung(replace(pull_set, springs=None)) is None
    assert coupling_of(replace(pull_set, springs=None)) is None


def test_geometry_resonances_use_the_coupled_answer(pull_set):
    sd = replace(
        pull_set,
        springs=replace(pull_set.springs, rho=0.0, used={"k_v": "geometry", "alpha": "geometry"}),
    )
    r = coupled_rung(sd)
    assert r.uses == "coupled"
    assert r.answer is r.coupled
    assert "uses the coupled answer" in r.message


def _a(mode, v):
    return Answer("success", v, 0.0, mode, v)


@pytest.mark.parametrize(
    ("dec", "cou", "status"),
    [
        (_a("push", 1.0), _a("push", 1.09), "coupled-agrees"),
        (_a("push", 1.0), _a("push", 1.11), "coupled-differs"),
        (_a("pull", -1.0), _a("pull", -0.85), "coupled-differs"),
        (_a("push", 1.0), _a("pull", -1.0), "coupled-differs"),
        (_a("push", 1.0), Answer("mean", 0.1, 0.5, "undetermined", 0.1), "coupled-undetermined"),
        (Answer("unbounded", None, 0.0, None, None), _a("push", 1.0), "failed"),
    ],
)
def test_status_rules(dec, cou, status):
    assert _status(dec, cou) == status


def test_bad_input():
    with pytest.raises(ParameterError, match="SetDerivation"):
        coupled_rung("devices/pull_demo.yaml")


def test_check_says_it_when_asked():
    """``check_derivation(coupled=True)``: rule coupled-head per drawn set (bidir_demo's
    two mirrored sets: two rules); a warning where the rung differs; absent by default."""
    from betvdesign.checks.checker import check_derivation

    d = derive_file(DEVICES / "bidir_demo.yaml")
    quick = dict(margin=False, settle=False, determine=False, adequacy=False)
    plain = check_derivation(d, **quick)
    assert not [r for r in plain.rules if r.id == "coupled-head"]
    res = check_derivation(d, coupled=True, **quick)
    rules = [r for r in res.rules if r.id == "coupled-head"]
    assert [r.set_name for r in rules] == [s.name for s in d.sets]
    assert all(r.severity == "warning" and not r.passed for r in rules)
    assert all("coupled-differs" in r.message and r.fix for r in rules)
    # the verdict's own rules are those of the plain check
    others = [r.as_dict() for r in res.rules if r.id != "coupled-head"]
    assert others == [r.as_dict() for r in plain.rules]
