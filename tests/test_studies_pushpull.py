"""Push/pull map with the exact periodic solver (sources: long brute-force
simulation as a second method, the α → 0 pull limit of MODEL.md, summary
bookkeeping invariants, byte-reproducible figures)."""

import numpy as np
import pytest

from betvdesign.dynamics import simulate
from betvdesign.model.params import ModelParams
from betvdesign.plots.studies import save_pushpull_figure
from betvdesign.studies.points import periodic_point
from betvdesign.studies.pushpull import pushpull_study, run_pushpull, summarise


def _task(varpi, alpha, beta=0.5, kappa=0.4, **kw):
    return {
        "key": 0,
        "varpi": varpi,
        "alpha": alpha,
        "beta": beta,
        "kappa": kappa,
        "tol": 1e-10,
        "max_cycles": None,
        **kw,
    }


def test_periodic_delta_s_matches_long_brute_force():
    """A strongly contracting point (Floquet radius ~0.15): the last per-cycle Δs of a
    300-cycle transient from rest equals the shooting result to 1e-9."""
    row = periodic_point(_task(1.3, 4.0))
    assert row["converged"] and row["floquet_radius"] < 0.5 and row["period_cycles"] == 1
    traj = simulate(ModelParams(1.3, 4.0, 0.5, 0.4), 300)
    assert traj.success
    assert traj.delta_s[-1] == pytest.approx(row["delta_s"], abs=1e-9)
    assert row["mode"] == ("push" if row["delta_s"] > 0 else "pull")


@pytest.mark.parametrize("varpi", [0.7, 1.2, 1.8])
def test_rigid_limit_gives_pull(varpi):
    """MODEL.md: α → 0 (rigid tangential contact) always gives pull mode."""
    row = periodic_point(_task(varpi, 0.02, beta=1.0, kappa=0.4))
    assert row["converged"] and row["mode"] == "pull" and row["delta_s"] < 0


def test_summary_accounts_for_every_point_and_lists_failures():
    """A budget of 64 cycles cannot settle the resonant α·ϖ² = 1 point (α = 4, ϖ = 0.5):
    it must be listed as not converged, never dropped or given a mode."""
    run, s = run_pushpull([0.5, 1.3], [1.0, 4.0], [0.5], [0.4], max_cycles=64)
    rows = run.rows
    assert s.n_points == 4
    assert s.n_converged + len(s.not_converged) == 4
    assert s.n_agree + len(s.disagreements) == s.n_converged
    assert s.n_push + s.n_pull == s.n_converged
    failed = [r for r in rows if not r["converged"]]
    assert [f["key"] for f in s.not_converged] == [r["key"] for r in failed]
    assert all(r["mode"] is None and r["delta_s"] is None for r in failed)
    assert all(f["message"] for f in s.not_converged)
    dis = [r for r in rows if r["converged"] and r["mode"] != r["lambda_mode"]]
    assert [d["key"] for d in s.disagreements] == [r["key"] for r in dis]


def test_disagreement_is_reported():
    """Hand-made rows: a converged point whose simulated mode contradicts λ is listed."""
    rows = [
        {
            "key": 0,
            "varpi": 1.0,
            "alpha": 1.0,
            "beta": 0.5,
            "kappa": 0.4,
            "lam": 0.8,
            "lambda_mode": "push",
            "mode": "pull",
            "delta_s": -0.1,
            "converged": True,
        },
        {
            "key": 1,
            "varpi": 1.0,
            "alpha": 2.0,
            "beta": 0.5,
            "kappa": 0.4,
            "lam": 0.4,
            "lambda_mode": "push",
            "mode": "push",
            "delta_s": 0.2,
            "converged": True,
        },
    ]
    s = summarise(rows)
    assert s.n_agree == 1 and [d["key"] for d in s.disagreements] == [0]
    assert s.agreement == 0.5


def test_map_figure_is_byte_reproducible(tmp_path):
    run, _ = run_pushpull([0.9, 1.3], [1.0, 4.0], [0.5, 1.0], [0.4])
    a, b = tmp_path / "a.svg", tmp_path / "b.svg"
    save_pushpull_figure(run.rows, a)
    save_pushpull_figure(run.rows, b)
    text = a.read_text()
    assert a.read_bytes() == b.read_bytes()
    assert text.count('<g id="axes_') == 2  # one panel per (κ, β): κ = 0.4, β ∈ {0.5, 1}
    assert "<svg" in text and "Date" not in text
    assert np.isfinite([r["delta_s"] for r in run.rows]).all()


def test_vertical_precheck_gives_the_solvers_own_not_driven_answer():
    """At ϖ = 2.2 no contact recurs: the per-ϖ vertical pre-check must answer exactly what
    a full periodic solve answers (status, no mode, hits per cycle)."""
    study, _ = pushpull_study([1.2, 2.2], [1.0], [0.5], [0.4])
    pre = {t["varpi"]: t["not_driven"] for t in study.tasks}
    assert pre[1.2] is None and pre[2.2] is not None
    fast = periodic_point(study.tasks[1])
    full = periodic_point({**study.tasks[1], "not_driven": None})
    for col in ("status", "converged", "mode", "delta_s", "period_cycles", "impacts_per_cycle"):
        assert fast[col] == full[col], col
    assert full["status"] == "not_driven"


def test_a_solver_crash_is_listed_not_fatal(monkeypatch):
    """If the solver raises at one point, that point is an 'error' row listed with its
    parameters; the other points are still solved."""
    import betvdesign.dynamics as dyn

    real = dyn.periodic_orbit

    def crashing(p, **kw):
        if p.varpi == 1.3:
            raise ZeroDivisionError("float division by zero")
        return real(p, **kw)

    monkeypatch.setattr(dyn, "periodic_orbit", crashing)
    run, s = run_pushpull([0.9, 1.3], [1.0], [0.5], [0.4])
    bad = [r for r in run.rows if r["status"] == "error"]
    assert len(bad) == 1 and bad[0]["varpi"] == 1.3 and bad[0]["mode"] is None
    assert "ZeroDivisionError" in bad[0]["message"]
    assert [d["varpi"] for d in s.not_converged] == [1.3] and s.n_converged == 1


def test_resonant_points_are_named_in_the_summary():
    """α = 4, ϖ = 0.5 sits exactly on α·ϖ² = 1 (free-flight tangential resonance)."""
    from betvdesign.studies.pushpull import tangential_resonance

    assert tangential_resonance({"varpi": 0.5, "alpha": 4.0, "beta": 0.5}) == "alpha"
    assert tangential_resonance({"varpi": 0.5, "alpha": 4 / 3, "beta": 0.5}) == "stick"
    assert tangential_resonance({"varpi": 0.6, "alpha": 4.0, "beta": 0.5}) is None
    _, s = run_pushpull([0.5], [4.0], [0.5], [0.4], max_cycles=64)
    assert [d["resonance"] for d in s.not_converged] == ["alpha"]
