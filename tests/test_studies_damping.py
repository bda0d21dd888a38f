"""Parameter-space studies with damping and restitution (issue 12: "every study accepts
the new terms"). Sources: the exact solver called directly (wiring), a long transient
from rest as a second method for the damped resonance (no shooting), the vertical-only
model for the regime diagram, the idealised study itself for the bit-identical default
path, and the store's resume contract for the cache keying."""

import json

import pytest

from betvdesign.dynamics import periodic_orbit, simulate, vertical_motion
from betvdesign.errors import UsageError
from betvdesign.model.params import ModelParams
from betvdesign.studies.engine.runner import run_study
from betvdesign.studies.lambda_scan import lambda_study, run_lambda_scan
from betvdesign.studies.points import periodic_point
from betvdesign.studies.pushpull import pushpull_study, run_pushpull
from betvdesign.studies.regime import regime_study, run_regime
from betvdesign.studies.terms import Terms

TERMS = {"zeta_v": 0.02, "zeta_h": 0.05, "restitution": 0.1}
#: On the free-flight tangential resonance α·ϖ² = 1 (ακ = 0.4 < 2: unbounded when undamped).
RESONANT = {"varpi": 1.0, "alpha": 1.0, "beta": 0.5, "kappa": 0.4}


def _task(**kw):
    return {"key": 0, **RESONANT, "tol": 1e-10, "max_cycles": None, **kw}


# -- wiring ------------------------------------------------------------------------
def test_damped_point_is_the_periodic_orbit_of_the_damped_params():
    row = periodic_point(_task(varpi=1.3, alpha=0.8, **TERMS))
    po = periodic_orbit(ModelParams(1.3, 0.8, 0.5, 0.4, **TERMS))
    assert row["converged"] and po.success
    assert row["delta_s"] == po.delta_s
    assert row["period_cycles"] == po.period_cycles
    assert row["residual"] == po.residual
    assert {k: row[k] for k in TERMS} == TERMS
    undamped = periodic_point(_task(varpi=1.3, alpha=0.8))
    assert undamped["delta_s"] != row["delta_s"]
    assert "zeta_v" not in undamped  # ModelParams.as_dict: the terms only when set


def test_zero_terms_give_the_idealised_study_bit_for_bit():
    grid = ([0.7, 1.0, 1.3], [0.5, 1.0], [0.5], [0.4])
    ideal, _ = pushpull_study(*grid, max_cycles=2000)
    zeros, _ = pushpull_study(*grid, max_cycles=2000, zeta_v=0.0, zeta_h=0.0, restitution=0.0)
    assert zeros.parameters == ideal.parameters
    assert dict(zeros.columns) == dict(ideal.columns)
    assert zeros.tasks == ideal.tasks
    assert run_study(zeros).rows == run_study(ideal).rows
    assert regime_study([1.0, 2.0], restitution=0.0).tasks == regime_study([1.0, 2.0]).tasks
    assert lambda_study([0.9], kappa=0.4, beta=0.5, alpha=1.0, zeta_h=0.0).parameters == (
        lambda_study([0.9], kappa=0.4, beta=0.5, alpha=1.0).parameters
    )


# -- physics that can fail on its own ----------------------------------------------
def test_resonance_is_unbounded_undamped_and_finite_with_tangential_damping():
    """α·ϖ² = 1: the idealised map lists the point as unbounded; with Q_h = 10 the map
    reports a finite Δs, equal to the last-cycle Δs of a long transient from rest (a
    second method: no shooting, no Newton)."""
    _, ideal = run_pushpull([1.0], [1.0], [0.5], [0.4])
    assert [u["status"] for u in ideal.unbounded] == ["unbounded"]
    zeta_h = 1 / (2 * 10.0)
    run, damped = run_pushpull([1.0], [1.0], [0.5], [0.4], zeta_h=zeta_h)
    row = run.rows[0]
    assert damped.unbounded == [] and damped.n_converged == 1
    assert row["status"] == "success" and abs(row["delta_s"]) < 1e3
    assert row["floquet_radius"] < 1.0
    tr = simulate(ModelParams(**RESONANT, zeta_h=zeta_h), 3000, log_events=False)
    assert tr.success
    assert tr.delta_s[-1] == pytest.approx(row["delta_s"], rel=1e-8)
    d = damped.as_dict()
    assert d["terms"] == {"zeta_v": 0.0, "zeta_h": zeta_h, "restitution": 0.0}
    assert "ζ_h = 0.05 (Q = 10)" in d["model"] and "idealised" in d["lambda_note"]


@pytest.mark.parametrize(("zeta_v", "e"), [(0.0, 0.3), (0.05, 0.0), (0.05, 0.2)])
def test_regime_with_terms_agrees_with_the_vertical_model(zeta_v, e):
    grid = [0.6, 1.0, 1.5, 3.0]
    run0, _ = run_regime(grid, max_cycles=400)
    run, summary = run_regime(grid, max_cycles=400, zeta_v=zeta_v, restitution=e)
    assert summary["terms"] == {"zeta_v": zeta_v, "restitution": e}
    assert "ζ_h" not in summary["model"] and f"e = {e:g}" in summary["model"]
    changed = 0
    for r0, r in zip(run0.rows, run.rows, strict=True):
        assert (r["zeta_v"], r["restitution"]) == (zeta_v, e)
        v = vertical_motion(r["varpi"], zeta_v=zeta_v, restitution=e, max_cycles=400)
        assert r["status"] == v.status and r["regime"] == v.regime
        if v.period_cycles is not None:
            assert r["period_cycles"] == v.period_cycles
            assert r["hits_per_cycle"] == v.hits_per_cycle
            assert r["contact_fraction"] == v.contact_fraction
        changed += (r0["label"], r0["hits_per_cycle"], r0["contact_fraction"]) != (
            r["label"],
            r["hits_per_cycle"],
            r["contact_fraction"],
        )
    assert changed >= 1  # the terms reach the vertical model


def test_lambda_scan_with_terms_solves_the_damped_model():
    run, summary = run_lambda_scan([0.8, 1.2], kappa=0.4, beta=0.5, alpha=0.5, **TERMS)
    for r in run.rows:
        assert {k: r[k] for k in TERMS} == TERMS
        po = periodic_orbit(ModelParams(r["varpi"], r["alpha"], 0.5, 0.4, **TERMS))
        assert r["delta_s"] == po.delta_s
    assert summary.as_dict()["terms"] == TERMS


# -- the λ rung refuses the terms ------------------------------------------------------
@pytest.mark.parametrize("term", list(TERMS))
def test_lambda_fidelity_refused_with_any_term(term):
    with pytest.raises(UsageError, match="--fidelity periodic"):
        pushpull_study([1.0], [1.0], [0.5], [0.4], fidelity="lambda", **{term: TERMS[term]})
    pushpull_study([1.0], [1.0], [0.5], [0.4], fidelity="lambda")  # idealised: fine


def test_bad_terms_are_usage_errors_naming_the_term():
    with pytest.raises(UsageError, match="restitution"):
        pushpull_study([1.0], [1.0], [0.5], [0.4], restitution=1.0)
    with pytest.raises(UsageError, match="zeta_h"):
        lambda_study([1.0], kappa=0.4, beta=0.5, alpha=1.0, zeta_h=-0.1)
    with pytest.raises(UsageError, match="zeta_v"):
        regime_study([1.0], zeta_v=1e-6)  # below ZETA_MIN: 4 digits lost near resonance
    assert Terms.of({"zeta_v": None}).ideal


# -- the store keys on the terms -----------------------------------------------------
def _outputs(path):
    meta = json.loads(path.with_suffix(".json").read_text())
    return meta, path.read_text().splitlines()[0].split(",")


def test_store_never_resumes_results_of_other_terms(tmp_path):
    """A finished undamped map at the same path must not be taken as the damped one
    (it would be, silently, computed = 0, if the terms did not key the store), nor one
    damped map as another with a different Q, nor a damped map as the undamped one."""
    out = tmp_path / "map.csv"
    grid = ([1.2], [0.5], [0.5], [0.4])
    first, _ = run_pushpull(*grid, out=out)
    assert first.computed == 1
    for terms in ({"zeta_h": 0.05}, {"restitution": 0.1}, {"zeta_v": 0.02}):
        with pytest.raises(UsageError, match="different 'parameters'"):
            run_pushpull(*grid, out=out, **terms)
    damped_out = tmp_path / "damped.csv"
    run, _ = run_pushpull(*grid, out=damped_out, zeta_h=0.05)
    meta, header = _outputs(damped_out)
    assert meta["parameters"]["zeta_h"] == 0.05 and header[5:8] == list(TERMS)
    again, _ = run_pushpull(*grid, out=damped_out, zeta_h=0.05)
    assert (again.computed, again.resumed) == (0, 1) and again.rows == run.rows
    with pytest.raises(UsageError, match="different 'parameters'"):
        run_pushpull(*grid, out=damped_out, zeta_h=0.06)
    with pytest.raises(UsageError, match="different 'parameters'"):
        run_pushpull(*grid, out=damped_out)
    meta, header = _outputs(out)
    assert "zeta_h" not in meta["parameters"] and "zeta_h" not in header


def test_regime_and_lambda_stores_key_on_the_terms(tmp_path):
    out = tmp_path / "reg.csv"
    run_regime([1.0], max_cycles=100, out=out)
    with pytest.raises(UsageError, match="different 'parameters'"):
        run_regime([1.0], max_cycles=100, out=out, restitution=0.2)
    out = tmp_path / "lam.csv"
    run_lambda_scan([1.2], kappa=0.4, beta=0.5, alpha=0.5, out=out, max_cycles=2000)
    with pytest.raises(UsageError, match="different 'parameters'"):
        run_lambda_scan(
            [1.2], kappa=0.4, beta=0.5, alpha=0.5, out=out, max_cycles=2000, zeta_v=0.02
        )


def test_regime_impulsive_period_with_rebounds_returns_the_section_state():
    """e > 0: a hit's phase no longer fixes the state after it, so an impulsive-only
    period k must also return (ξ, ξ') at the section k cycles later (checked here on the
    schedule itself) and carry an integer number of hits."""
    from betvdesign.dynamics.vertical import vertical_motion_schedule

    run, _ = run_regime([1.0, 1.5, 2.2], max_cycles=400, restitution=0.3)
    impulsive = [r for r in run.rows if r["label"] == "impulsive"]
    assert impulsive
    for r in impulsive:
        k = r["period_cycles"]
        assert k >= 1 and r["hits_per_cycle"] * k == pytest.approx(round(r["hits_per_cycle"] * k))
        _, vs = vertical_motion_schedule(r["varpi"], restitution=0.3, max_cycles=400)
        late = vs.prefix[-2 * k - 1 :]
        for a, b in zip(late, late[k:], strict=False):
            assert (b.xi0, b.xid0) == pytest.approx((a.xi0, a.xid0), abs=1e-8)


def test_map_figure_names_the_terms():
    from betvdesign.plots.studies import pushpull_figure

    damped, _ = run_pushpull([1.2], [0.5], [0.5], [0.4], zeta_h=0.05)
    ideal, _ = run_pushpull([1.2], [0.5], [0.5], [0.4])
    title = pushpull_figure(damped.rows)._suptitle
    assert title is not None and "ζ_h = 0.05 (Q = 10)" in title.get_text()
    assert pushpull_figure(ideal.rows)._suptitle is None
