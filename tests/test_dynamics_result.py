"""The one result contract of the solvers (betvdesign.dynamics.result): every answer's
status is a word of its documented vocabulary, success follows from it, a failure is
built once, the counters are the solver's own."""

from dataclasses import FrozenInstanceError
from typing import get_args

import pytest

from betvdesign.bench.fixedstep import FixedStepResult, rk4_post
from betvdesign.dynamics import (
    PeriodicResult,
    SolverResult,
    Trajectory,
    periodic_orbit,
    reference,
    simulate,
)
from betvdesign.dynamics.result import (
    PeriodicStatus,
    RigidStatus,
    SettlingStatus,
    TrajectoryStatus,
    VerticalStatus,
)
from betvdesign.dynamics.rigid import RigidPeriodic, RigidTrajectory, rigid_periodic
from betvdesign.dynamics.settling import Settling, settling
from betvdesign.dynamics.solver import CycleFailure
from betvdesign.dynamics.vertical import VerticalResult, vertical_motion_schedule
from betvdesign.model.params import ModelParams

PULL = ModelParams(1.2, 0.5, 1.0, 0.4)

KINDS = [
    (Trajectory, TrajectoryStatus, "success"),
    (PeriodicResult, PeriodicStatus, "success"),
    (VerticalResult, VerticalStatus, "success"),
    (RigidTrajectory, TrajectoryStatus, "success"),
    (RigidPeriodic, RigidStatus, "success"),
    (Settling, SettlingStatus, "settled"),
    (FixedStepResult, TrajectoryStatus, "success"),
]


@pytest.mark.parametrize(("cls", "status", "word"), KINDS)
def test_every_answer_shares_the_contract(cls, status, word):
    assert issubclass(cls, SolverResult)
    assert cls.STATUSES == get_args(status) and cls.SUCCESS == word
    assert word in cls.STATUSES


def test_status_words_are_the_published_strings():
    """JSON, CSV and the snapshot carry the words: they stay these plain strings."""
    assert get_args(PeriodicStatus) == (
        "success",
        "unbounded",
        "not_converged",
        "not_driven",
        "failed",
    )
    assert get_args(TrajectoryStatus) == ("success", "failed")
    assert get_args(VerticalStatus) == ("success", "not_periodic", "failed")
    assert get_args(RigidStatus) == ("success", "no_contact")
    assert get_args(SettlingStatus) == ("settled", "not_settled", "failed")


def test_a_word_outside_the_vocabulary_is_refused():
    with pytest.raises(ValueError, match="not_periodic"):
        PeriodicResult(params=PULL, status="not_periodic", message="")


def test_periodic_failure_is_built_once_with_nothing_it_does_not_have():
    r = PeriodicResult.failure(PULL, "not_driven", "why", n_root_evals=7, elapsed_s=0.5)
    assert r.status == "not_driven" and not r.success and r.message == "why"
    assert (r.delta_s, r.mode, r.period_cycles, r.floquet, r.state, r.stable) == (None,) * 6
    assert r.floquet_moduli is None and (r.n_cycles, r.n_root_evals) == (0, 7)
    with pytest.raises(ValueError):
        PeriodicResult.failure(PULL, "success", "a success is not a failure")


def test_answers_are_frozen():
    tr = simulate(PULL, 3)
    with pytest.raises(FrozenInstanceError):
        tr.status = "failed"


def test_success_follows_the_status_of_every_solver():
    po = periodic_orbit(PULL)
    assert po.success and po.status == "success" and po.delta_s < 0.0
    not_driven = periodic_orbit(ModelParams(2.3, 0.5, 1.0, 0.3))
    assert not not_driven.success and not_driven.status == "not_driven"
    for tr in (simulate(PULL, 4), reference.simulate(PULL, 2), rk4_post(PULL, 2, 400)):
        assert tr.success and tr.status == "success" and tr.n_cycles == len(tr.delta_s)
    rp = rigid_periodic(ModelParams(2.2, 0.5, 1.0, 0.3))
    assert rp.status == "no_contact" and not rp.success
    st = settling(PULL, po.delta_s, travel_s=300.0)
    assert st.status == "settled" and st.success and st.settled
    assert st.simulated_cycles == st.n_cycles > 0 and st.n_events > 0
    assert st.as_dict()["simulated_cycles"] == st.n_cycles


def test_settling_reports_the_tolerance_it_was_given():
    po = periodic_orbit(PULL)
    assert settling(PULL, po.delta_s, rtol=0.05).rtol == 0.05


@pytest.mark.parametrize("w", [0.9, 0.3, 2.3])
def test_vertical_counters_are_those_of_the_cycles_computed(w):
    r, vs = vertical_motion_schedule(w)
    assert r.n_cycles == len(vs.table)
    hits = int(vs.table["imp_count"].sum()) + int((vs.table["tc"] == vs.table["tc"]).sum())
    assert r.n_events == hits > 0


def test_a_cycle_that_cannot_be_advanced_is_a_cycle_failure():
    exc = CycleFailure("chatter", 12)
    assert isinstance(exc, RuntimeError) and exc.cycle == 12 and str(exc) == "chatter"
