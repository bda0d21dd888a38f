"""The check's verdict on a drawn head without measured resonances is the coupled head's.

Independent truths: the speed the check quotes is the coupled reference's (solve_ivp) Δs
over one cycle from the orbit's state, scaled; with the coupled model off the verdict is
the exact decoupled orbit's; a file with measured resonances keeps its decoupled verdict
whether or not the coupled finding is asked for.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from betvdesign.api import CheckOptions, run_check
from betvdesign.checks.coupled import coupling_of, uses_coupled
from betvdesign.dynamics import periodic_orbit
from betvdesign.dynamics.coupled_reference import simulate_coupled as reference

ROOT = Path(__file__).resolve().parents[1]


def _drawn_only(tmp_path: Path, stem: str = "push_demo") -> Path:
    """A shipped file without its measured resonances (k_v and α from the drawing)."""
    lines = (ROOT / "devices" / f"{stem}.yaml").read_text().splitlines()
    keep = [ln for ln in lines if "_resonance:" not in ln and "horizontal_stiffness:" not in ln]
    out = tmp_path / f"{stem}_drawn_only.yaml"
    out.write_text("\n".join(keep) + "\n")
    return out


@pytest.fixture(scope="module")
def drawn(tmp_path_factory):
    src = _drawn_only(tmp_path_factory.mktemp("drawn"))
    opts = CheckOptions(advice=False, adequacy=False)
    return run_check(src, opts), run_check(src, replace(opts, coupled=False))


def test_drawn_only_verdict_is_the_coupled_heads(drawn):
    res, _ = drawn
    sc = res.sets[0]
    sd = sc.derivation
    assert uses_coupled(sd) and sc.model == "coupled"
    assert res.out.sets[0].model == "coupled"
    mode = next(r for r in sc.rules if r.id == "mode")
    speed = next(r for r in sc.rules if r.id == "speed")
    assert mode.message.startswith("coupled head (drawn, no measured resonances")
    assert "coupled" in speed.source
    assert any(r.id == "coupled-head" and "verdict uses the coupled" in r.message for r in sc.rules)
    # the reference's cycle from the orbit's state gives the quoted speed
    po = sc.periodic
    assert po.success and po.stable
    p = replace(sd.params, zeta_v=0.0, zeta_h=0.0, restitution=0.0)
    run = reference(p, coupling_of(sd), int(po.period_cycles), state0=po.state)
    ds = float(run.section[-1, 4]) / po.period_cycles
    assert speed.value == pytest.approx(sd.scales.speed_m_s(ds), rel=1e-7)


def test_coupled_off_is_the_decoupled_verdict(drawn):
    res, off = drawn
    sc = off.sets[0]
    assert sc.model == "decoupled"
    assert not any(r.id == "coupled-head" for r in off.rules)
    ex = periodic_orbit(sc.derivation.params)
    speed = next(r for r in sc.rules if r.id == "speed")
    assert speed.value == pytest.approx(sc.derivation.scales.speed_m_s(ex.delta_s), rel=1e-12)
    # the two verdicts differ here (the drawn head is far from two independent springs)
    on = next(r for r in res.sets[0].rules if r.id == "speed").value
    assert abs(on - speed.value) > 0.1 * abs(speed.value)


def test_file_resonances_keep_the_decoupled_verdict():
    src = ROOT / "devices" / "shin2004.yaml"
    opts = CheckOptions(advice=False, adequacy=False, margin=False)
    plain = run_check(src, opts)
    asked = run_check(src, replace(opts, coupled=True))
    assert not any(r.id == "coupled-head" for r in plain.rules)
    found = [r for r in asked.rules if r.id == "coupled-head"]
    assert found and all("finding" in r.message for r in found)
    for a, b in zip(plain.sets, asked.sets, strict=True):
        assert a.model == b.model == "decoupled"
        va = next(r for r in a.rules if r.id == "speed").value
        vb = next(r for r in b.rules if r.id == "speed").value
        assert va == vb
