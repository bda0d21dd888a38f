"""The validation study against the published paper (betvdesign.paper.study*,
betvdesign.report.validation, ``betv report --validation``).

Only the computed side is pinned, and only against independent truths: brute-force
definitions of the stopping and settling measurements, closed forms (the vertical
edges ϖ = 1/2 and ϖ = 2, the rigid-limit starts and separation velocity, the
tangential resonance next to λ = 1, the device's β and ϖ from its listed numbers), the
brute-force transient instead of Newton shooting, and scipy solve_ivp
(dynamics.reference) instead of the closed-form solver. The published values are data
of the study; no test asserts that the paper is right.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from conftest import DEVICES
from typer.testing import CliRunner

from betvdesign.cli import app
from betvdesign.dynamics import reference, simulate
from betvdesign.dynamics.rigid import rigid_periodic, rigid_simulate
from betvdesign.model.params import ModelParams, lambda_criterion
from betvdesign.paper.common import (
    refine_edge,
    settled_from,
    successive_stop,
    true_intervals,
)
from betvdesign.paper.maps import FIG12_ALPHA, FIG12_BETA, FIG12_KAPPA, maps_part
from betvdesign.paper.slider import slider_part
from betvdesign.paper.vertical import finite_contact, one_hit_per_cycle
from betvdesign.studies.regime import regime_point

SHIN = DEVICES / "shin2004.yaml"


# ----------------------------------------------------------------- building blocks
def _stop_brute(ds, rtol):
    for m in range(1, len(ds)):
        if abs(ds[m] - ds[m - 1]) <= rtol * abs(ds[m]):
            return m + 1, ds[m]
    return None


def _settle_brute(ds, target, rtol):
    for m in range(len(ds)):
        if all(abs(x - target) <= rtol * abs(target) for x in ds[m:]):
            return m + 1 if m < len(ds) else None
    return None


@pytest.mark.parametrize("seed", range(20))
def test_stop_and_settle_match_their_definitions(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 60))
    # a settling sequence Δs_m = L(1 + c·q^m) with noise, as a transient looks
    q, c = rng.uniform(0.3, 0.99), rng.uniform(-1, 1)
    ds = -4.0 * (1 + c * q ** np.arange(n)) + rng.normal(0, 1e-7, n) * rng.integers(0, 2)
    for rtol in (1e-2, 1e-4, 1e-6):
        got = successive_stop(ds, rtol)
        want = _stop_brute(list(ds), rtol)
        assert (got is None) == (want is None)
        if got is not None:
            assert (got.cycle, got.delta_s) == want
        assert settled_from(ds, -4.0, rtol) == _settle_brute(list(ds), -4.0, rtol)


def test_refine_edge_and_intervals():
    assert refine_edge(lambda x: x * x > 2.0, 1.0, 2.0, 1e-10) == pytest.approx(math.sqrt(2), 1e-9)
    with pytest.raises(ValueError):
        refine_edge(lambda x: True, 0.0, 1.0, 1e-3)
    x = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]
    assert true_intervals(x, [True, True, False, True, False, True]) == [
        (0.1, 0.2),
        (0.4, 0.4),
        (0.6, 0.6),
    ]


def _row(v):
    return regime_point({"key": 0, "varpi": v, "max_cycles": 400})


def test_vertical_edges_are_the_closed_form_half_and_two():
    """After a contact end at τ₀ = π/ϖ (ξ = ξ' = 0) the flight is, with t = τ − τ₀,
    ξ(t) = (sin ϖt − ϖ sin t)/(1 − ϖ²) (MODEL.md free flight). At ϖ = 2 this is
    (2/3) sin t (1 − cos t): the next hit is at t = π, τ = 3π/ϖ, exactly where the
    compression window closes (zero contact). At ϖ = 1/2 it is (4/3) sin(t/2)(1 − cos(t/2)):
    the next hit is at t = 2π, τ = 4π = 2π/ϖ, where sin ϖτ = 0: exactly the start of
    the next window (the two-hit/one-hit boundary). So finite contact ends at ϖ = 2 and
    one hit per cycle starts at ϖ = 1/2."""
    e2 = refine_edge(lambda v: finite_contact(_row(v)), 1.99, 2.01, 1e-6)
    assert e2 == pytest.approx(2.0, abs=2e-6)
    e05 = refine_edge(lambda v: one_hit_per_cycle(_row(v)), 0.49, 0.51, 1e-6)
    assert e05 == pytest.approx(0.5, abs=2e-6)


# ----------------------------------------------------------------- maps (Figs 7, 8, 12)
@pytest.fixture(scope="module")
def maps():
    return maps_part()


def test_rigid_limit_starts_and_separation_velocity_closed_form(maps):
    """With βκ = ϖ² the relative velocity w = s' − ζ' is constant in reverse slip and
    grows by 2ϖ²·(2/ϖ) = 4ϖ over a slip contact (MODEL.md α → 0), so starts v₀ = ±3.5ϖ
    leave s'(π/ϖ) = ±1.5ϖ; the stick velocity ϖ cos ϖτ at the contact end π/ϖ is −ϖ."""
    f8 = maps.fig8
    p = f8["params"]
    w = p.varpi
    assert p.beta * p.kappa == pytest.approx(w * w, rel=1e-14)
    assert rigid_simulate(p, 1, state0=(0.0, 3.5 * w)).v == pytest.approx(1.5 * w, rel=1e-12)
    assert rigid_simulate(p, 1, state0=(0.0, -3.5 * w)).v == pytest.approx(-1.5 * w, rel=1e-12)
    assert sorted(t[0] for t in f8["traces"].values()) == pytest.approx([-1.5, 1.5], rel=1e-12)
    assert f8["separation"] == pytest.approx(-1.0, rel=1e-12)
    assert rigid_periodic(p).v_section == pytest.approx(-w, rel=1e-12)
    rows = {c.statement[:20]: c for c in maps.comparisons if c.fig == "8"}
    assert len(rows) == 3


def test_lambda_scan_sign_change_is_at_the_tangential_resonance(maps):
    """Closed form: at αϖ² = 1 no bounded orbit exists (MODEL.md); with α fixed the scan
    crosses it at λ(ϖ = 1/√α). Δs changes sign there, not at the fit's λ = 1."""
    lam_res = lambda_criterion(1 / math.sqrt(FIG12_ALPHA), FIG12_ALPHA, FIG12_BETA, FIG12_KAPPA)
    row = next(c for c in maps.comparisons if c.fig == "12")
    assert row.computed_value == pytest.approx(lam_res, abs=2e-4)
    assert len(maps.fig7) == 4 and all(len(p["rows"]) == 64 for p in maps.fig7)


# ----------------------------------------------------------------- slider (Figs 9-11)
@pytest.fixture(scope="module")
def slider():
    return slider_part(SHIN)


@pytest.mark.parametrize("label", ["9a", "9b"])
def test_fig9_delta_s_is_the_brute_force_and_solve_ivp_value(slider, label):
    """Independent of Newton shooting: the transient from rest after 3000 cycles, and
    scipy solve_ivp (DOP853) over one more cycle from that state."""
    row = next(c for c in slider.comparisons if c.fig == label and c.computed_value is not None)
    p = next(f["params"] for f in slider.fig9 if f["label"] == label)
    tr = simulate(p, 3000, log_events=False)
    assert tr.delta_s[-1] == pytest.approx(row.computed_value, rel=1e-9)
    ref = reference.simulate(p, 1, state0=tr.section[-1])
    assert float(ref.delta_s[0]) == pytest.approx(row.computed_value, rel=1e-7)


def test_fig10_travel_after_30_impacts_by_solve_ivp(slider):
    """|s| after 30 cycles from rest, solve_ivp instead of the closed-form solver, in µm
    with u = 0.11 µm and θ = 45° (the device file's values)."""
    p = ModelParams(0.9, 0.1, 0.9, 0.4)
    ref = reference.simulate(p, 30)
    want = abs(float(ref.section[-1, 4])) * 0.11 * math.cos(math.pi / 4)
    row = next(c for c in slider.comparisons if c.fig == "10" and c.published_value == 40.0)
    assert row.computed_value == pytest.approx(want, rel=1e-6)


def test_device_values_from_the_listed_numbers(slider):
    """β = m/(ρ·L·w·t) and ϖ = 2·f_drive/f_v from the published device data."""
    beta = 0.036e-9 / (2330 * 170e-6 * 5e-6 * 2e-6)
    varpi = 2 * 500 / 2940
    rows = {c.statement.split(" ")[0]: c for c in slider.comparisons if c.fig == "device"}
    assert rows["β"].computed_value == pytest.approx(beta, rel=1e-12)
    assert rows["ϖ"].computed_value == pytest.approx(varpi, rel=1e-12)


# ----------------------------------------------------------------- page and CLI
@pytest.mark.slow
def test_page_end_to_end(tmp_path, monkeypatch, maps, slider):
    """A coarse run written as a page: every comparison row in the HTML and Markdown,
    every figure inline and as a file, no external reference, no PDF when not asked."""
    import betvdesign.report.validation as rv
    from betvdesign.paper import study as sv

    def coarse(device=None):
        from betvdesign.paper.vertical import vertical_part

        return sv.ValidationStudy(
            "paper", SHIN, vertical_part(step=0.1, top=5.0), maps, slider, 0.0
        )

    monkeypatch.setattr(rv, "run_validation", coarse)
    written = rv.write_validation_report(tmp_path, pdf=False)
    names = {p.relative_to(tmp_path).as_posix() for p in written}
    assert {"validation.html", "validation.md"} <= names
    assert not (tmp_path / "validation.pdf").exists()
    figs = {n for n in names if n.startswith("figures/")}
    assert len(figs) == len(rv._FIGURES)
    html = (tmp_path / "validation.html").read_text("utf-8")
    study = coarse()
    assert html.count('<tbody class="comparison') == len(study.comparisons)
    assert html.count("<svg") == len(rv._FIGURES)
    assert not re.search(r'(src|href)="(https?:|//)', html)
    md = (tmp_path / "validation.md").read_text("utf-8")
    table = [ln for ln in md.splitlines() if ln.startswith("| ") and not ln.startswith("| Fig")]
    assert len(table) == len(study.comparisons)
    assert all(ln.count(" | ") == 6 for ln in table)  # '|' inside cells is escaped


def test_cli_bad_input_exits_2_and_writes_nothing(tmp_path):
    runner = CliRunner()
    out = tmp_path / "out"
    r = runner.invoke(app, ["report", "--validation", str(SHIN), str(SHIN), "-o", str(out)])
    assert r.exit_code == 2 and "at most one" in r.output
    f = tmp_path / "file"
    f.write_text("x")
    r = runner.invoke(app, ["report", "--validation", "-o", str(f)])
    assert r.exit_code == 2 and "not a directory" in r.output
    r = runner.invoke(app, ["report", "--validation", str(tmp_path / "nope.yaml"), "-o", str(out)])
    assert r.exit_code == 2 and "Traceback" not in r.output
    r = runner.invoke(app, ["report", "--validation", "--methods", "-o", str(out)])
    assert r.exit_code == 2 and "--methods" in r.output
    assert not out.exists()
