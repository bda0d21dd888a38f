"""The verdict at the window's edges and where no orbit exists (issue 29).

Every case compares with a truth the checked code does not produce:

- the window's edges: exact rational arithmetic on the decimal inputs of the file
  (``fractions.Fraction``), never the derivation's float64;
- contact at the upper edge: the closed-form free flight of the head after a contact
  ends (MODEL.md, "No contact": ξ'' + ξ = −sin ϖτ from ξ = ξ' = 0 at sin ϖτ = 0), its
  landing found in 50-digit arithmetic (mpmath);
- the slider's motion from rest: the independent ``solve_ivp`` integrator with events
  (:mod:`betvdesign.dynamics.reference`, written from MODEL.md; it imports nothing of the
  exact solver).
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from fractions import Fraction
from pathlib import Path

import mpmath
import numpy as np
import pytest
from typer.testing import CliRunner

from betvdesign.checks.checker import check_derivation
from betvdesign.cli import app
from betvdesign.dynamics import periodic_orbit, vertical_motion
from betvdesign.dynamics.reference import simulate as reference
from betvdesign.model.params import ModelParams
from betvdesign.nondim.device import derive_file

ROOT = Path(__file__).resolve().parents[1]
PUSH = (ROOT / "devices" / "push_demo.yaml").read_text()


def _device(tmp_path: Path, name: str, **edits: str) -> Path:
    """push_demo.yaml with lines replaced (key: old value -> new value)."""
    text = PUSH
    for old, new in edits.items():
        assert old in text, old
        text = text.replace(old, new, 1)
    path = tmp_path / f"{name}.yaml"
    path.write_text(text)
    return path


def _check_json(path: Path, *extra: str) -> dict:
    res = CliRunner().invoke(app, ["check", "--json", "-v", "--no-adequacy", *extra, str(path)])
    assert res.exit_code in (0, 1), res.output
    return json.loads(res.output)


def _rules(doc: dict) -> dict[str, dict]:
    """The first set's rules and the device's rules by id."""
    dev = doc["devices"][0]
    return {r["id"]: r for r in [*dev["rules"], *dev["sets"][0]["rules"]]}


# --- 1. the window's edges, exact in the user's units ------------------------------------


def _exact_position(f_drive: str, f_v: str) -> str:
    """Window position of ϖ = 2·f_drive/f_v (AC doubling) by rational arithmetic."""

    def hz(text: str) -> Fraction:
        value, unit = text.split()
        return Fraction(value) * {"Hz": 1, "kHz": 1000}[unit]

    w = 2 * hz(f_drive) / hz(f_v)
    if w == Fraction(1, 2):
        return "lower-edge"
    if w == 2:
        return "upper-edge"
    return "inside" if Fraction(1, 2) < w < 2 else "outside"


EDGE_PAIRS = [
    (f"{fv} kHz", f"{d} um")
    for fv in ("2.94", "3.3", "4.1", "5", "6.7", "7.3")
    for d in ("20", "27", "33", "36", "41", "47")
]


@pytest.mark.parametrize(("f_v", "diameter"), EDGE_PAIRS)
def test_window_edges_are_exact(tmp_path: Path, f_v: str, diameter: str) -> None:
    """f_act = f_v/2 is inside, f_act = 2·f_v outside, for every (f_v, m) pair (36): the
    derivation's float64 round-off never decides (22 of 36 were 1 ulp off before)."""
    from betvdesign.model.domain import in_window, window_position

    value = Fraction(f_v.split()[0]) * 1000
    lo_drive, hi_drive = f"{float(value / 4)!r} Hz", f"{float(value)!r} Hz"
    for drive, want in ((lo_drive, "lower-edge"), (hi_drive, "upper-edge")):
        assert _exact_position(drive, f_v) == want
        path = _device(
            tmp_path,
            "edge",
            **{
                "vertical_resonance: 5 kHz": f"vertical_resonance: {f_v}",
                "diameter: 36 um": f"diameter: {diameter}",
                "frequency: 3 kHz": f"frequency: {drive}",
            },
        )
        (s,) = derive_file(path).sets
        assert window_position(s.params.varpi) == want
        assert s.params.varpi == (0.5 if want == "lower-edge" else 2.0)  # solved at the edge
        assert in_window(s.params.varpi) is (want == "lower-edge")


@pytest.mark.parametrize("rel", [-1e-9, -1e-6, 1e-9, 1e-6])
def test_window_near_edges_follows_exact_arithmetic(tmp_path: Path, rel: float) -> None:
    """Off the edges by 1e-9 or 1e-6 the derived position is the rational one."""
    from betvdesign.model.domain import in_window

    f_v = "5 kHz"
    for edge_drive in (Fraction(1250), Fraction(5000)):
        drive = edge_drive * (1 + Fraction(rel))
        text = f"{float(drive)!r} Hz"
        want = _exact_position(text, f_v)
        path = _device(tmp_path, "near", **{"frequency: 3 kHz": f"frequency: {text}"})
        (s,) = derive_file(path).sets
        assert in_window(s.params.varpi) is (want == "inside")


@pytest.mark.slow
def test_window_message_agrees_with_its_vertical_motion(tmp_path: Path) -> None:
    """At f_act = f_v/2 the rule passes, says so, and quotes one hit per cycle (it said
    "below the window: several hits" beside "1 hit(s) per cycle"); at f_act = 2·f_v it
    fails and quotes no recurring contact."""
    lo = _device(tmp_path, "lo", **{"frequency: 3 kHz": "frequency: 1.25 kHz"})
    rule = _rules(_check_json(lo))["frequency-window"]
    assert rule["passed"] and "lower edge (inside)" in rule["message"]
    assert "1 hit(s) per cycle (0 impulsive)" in rule["message"]
    hi = _device(tmp_path, "hi", **{"frequency: 3 kHz": "frequency: 5 kHz"})
    doc = _check_json(hi)
    rule = _rules(doc)["frequency-window"]
    assert not rule["passed"] and "upper edge (outside)" in rule["message"]
    assert doc["devices"][0]["sets"][0]["mode"] == "not driven"


# --- 2. a margin on the window -----------------------------------------------------------


def test_window_margin_warns_and_fix_needs_it(tmp_path: Path) -> None:
    """ϖ = 0.5 passes the window but not its ±5 % margin: the check warns with the
    distance, and ``betv fix`` proposes a drive frequency whose ϖ·0.95 ≥ 0.5 by exact
    arithmetic (it said "nothing to fix" before)."""
    path = _device(
        tmp_path,
        "lo",
        **{
            "frequency: 3 kHz": "frequency: 1.25 kHz",
            "intended_mode: push": "intended_mode: pull",
        },
    )
    rules = _rules(_check_json(path))
    assert rules["frequency-window"]["passed"]
    margin = rules["window-margin"]
    assert not margin["passed"] and "0.00% from the window's lower edge" in margin["message"]
    res = CliRunner().invoke(
        app, ["fix", "--json", str(path), "--vary", "drive.frequency=1kHz:3kHz"]
    )
    assert res.exit_code in (0, 1), res.output
    doc = json.loads(res.output)
    assert doc["status"] == "fixed" and "nothing to fix" not in json.dumps(doc)
    (change,) = doc["candidates"][0]["changes"]
    assert change["field"] == "drive.frequency"
    f = Fraction(1250) * (1 + Fraction(change["relative_change"]))
    w = 2 * f / 5000  # ϖ = 2·f_drive / f_v, f_v = 5 kHz
    assert w * Fraction(95, 100) >= Fraction(1, 2)
    assert w * Fraction(105, 100) < 2


# --- 3. a coasting slider is not driven --------------------------------------------------


def _contact_share_closed_form(varpi: float) -> mpmath.mpf:
    """Share of a cycle in contact of the period-1 vertical motion near ϖ = 2 (50 digits).

    After a contact ends at sin ϖτ = 0 (ξ = ξ' = 0) the head flies:
    ξ(t) = (sin ϖt − ϖ sin t)/(1 − ϖ²) (MODEL.md "No contact", t from the end); it lands
    at the first root t* > 0 and stays in contact while sin ϖτ ≥ 0, i.e. until the phase
    ϖ(t*)+π reaches the next multiple of 2π + π.
    """
    mpmath.mp.dps = 50
    w = mpmath.mpf(varpi)

    def xi(t: mpmath.mpf) -> mpmath.mpf:
        return (mpmath.sin(w * t) - w * mpmath.sin(t)) / (1 - w**2)

    # for ϖ slightly below 2 the landing lies just before t = π (ξ > 0 on (0, π − δ))
    t_star = mpmath.findroot(
        xi, (mpmath.pi * (1 - mpmath.mpf("1e-3")), mpmath.pi), solver="anderson"
    )
    phase = (w * t_star + mpmath.pi) % (2 * mpmath.pi)  # phase of ϖτ at the landing
    assert phase <= mpmath.pi  # sin ϖτ ≥ 0: contact begins
    return (mpmath.pi - phase) / (2 * mpmath.pi)


def test_contact_closed_form_matches_vertical_motion() -> None:
    """The closed form agrees with the exact vertical motion where contact is resolved."""
    for gap in (1e-2, 1e-4, 1e-6):
        w = 2.0 - gap
        exact = float(_contact_share_closed_form(w))
        assert vertical_motion(w).contact_fraction == pytest.approx(exact, rel=1e-6)


def test_coasting_slider_is_not_driven() -> None:
    """At ϖ = 2 − 1 ulp the contact lasts ~7e-17 of a cycle (closed form, 50 digits):
    below round-off, so the orbit is "not driven" for 50 random designs (18 of 50 were
    "successful" push/pull orbits of a coasting slider before); at 2 − 1e-9 the contact
    (2.5e-10 of a cycle) is resolved and the orbit is not called not driven."""
    w = math.nextafter(2.0, 0.0)
    assert float(_contact_share_closed_form(w)) < 1e-12
    rng = np.random.default_rng(29)
    for _ in range(50):
        a, b, k = rng.uniform(0.1, 4.0), rng.uniform(0.1, 1.5), rng.uniform(0.1, 0.4)
        r = periodic_orbit(ModelParams(w, a, b, k))
        assert r.status == "not_driven", (a, b, k, r.status, r.message)
        assert "below round-off" in r.message
    w9 = 2.0 - 1e-9
    assert float(_contact_share_closed_form(w9)) > 1e-12
    r = periodic_orbit(ModelParams(w9, 2.04, 0.509, 0.15))
    assert r.status != "not_driven"


# --- 4. no orbit, but the slider crosses: the travel decides ------------------------------


@pytest.mark.slow
def test_no_orbit_design_that_crosses_gets_the_crossing(tmp_path: Path) -> None:
    """push_demo at ϖ = 1.9999 has no periodic orbit (not converged); the independent
    integrator moves the slider with a clear sign across its travel, so the check quotes
    that crossing (it failed as "no orbit" before)."""
    path = _device(
        tmp_path,
        "w19999",
        **{
            "frequency: 3 kHz": "frequency: 4.99975 kHz",
            "travel_range: 50 um": "travel_range: 5 um",
        },
    )
    (s,) = derive_file(path).sets
    p = s.params
    assert p.varpi == pytest.approx(1.9999, rel=1e-12)
    assert periodic_orbit(p).status == "not_converged"
    travel = s.travel_range_m / s.scales.length_m
    tr = reference(p, 400)
    sec = tr.section[:, 4]
    crossed = np.nonzero(np.abs(sec) >= travel)[0]
    assert len(crossed), "the reference does not cross in 400 cycles"
    n_ref = int(crossed[0])
    doc = _check_json(path)
    dev = doc["devices"][0]
    sc = dev["details"]["sets"][0] if "details" in dev else dev["sets"][0]
    travel_json = sc["travel"]
    assert travel_json["basis"] == "crossing"
    assert travel_json["mode"] == ("push" if sec[n_ref] > 0 else "pull")
    assert abs(travel_json["cycles_to_cross"] - n_ref) <= 1
    assert dev["verdict"] in ("pass", "fail")
    assert _rules(doc)["mode"]["passed"] is (travel_json["mode"] == "push")


# --- 5 and 6. one basis for every line ----------------------------------------------------


def _crossing_mode(p: ModelParams, travel: float, cycles: int) -> tuple[str, int]:
    tr = reference(p, cycles)
    sec = tr.section[:, 4]
    hit = np.nonzero(np.abs(sec) >= travel)[0]
    assert len(hit), f"no crossing within {cycles} cycles"
    return ("push" if sec[hit[0]] > 0 else "pull"), int(hit[0])


@pytest.mark.slow
def test_margin_corners_on_the_crossing_basis(tmp_path: Path) -> None:
    """Q = 1000, α = 0.6875, ϖ = 1.2: the periodic orbit pulls (near α·ϖ² = 1) but the
    slider crosses its travel pushing. The margin compares each corner's crossing from
    rest (independent integrator) with the headline's push, not the periodic pull."""
    f_h = 5000 / math.sqrt(0.6875)
    path = _device(
        tmp_path,
        "q1000",
        **{
            "horizontal_resonance: 3.5 kHz": f"horizontal_resonance: {f_h!r} Hz\n"
            "      quality_factor_normal: 1000\n      quality_factor_tangential: 1000",
        },
    )
    (s,) = derive_file(path).sets
    travel = s.travel_range_m / s.scales.length_m
    res = check_derivation(derive_file(path), adequacy=False)
    (sc,) = res.sets
    assert sc.travel.basis == "crossing"
    assert mode_of_periodic(sc) == "pull"
    want, _ = _crossing_mode(s.params, travel, 200)
    assert sc.mode == want == "push"
    from betvdesign.checks.checker import corner_params

    for label, q in corner_params(s.params).items():
        ref_mode, _ = _crossing_mode(q, travel, 400)
        assert sc.margin[label] == ref_mode, label
    margin_rule = next(r for r in sc.rules if r.id == "mode-margin")
    assert "crossing from rest" in margin_rule.message


def mode_of_periodic(sc) -> str | None:
    from betvdesign.model.domain import mode_of

    return mode_of(sc.periodic.delta_s) if sc.periodic.success else None


def test_time_to_cross_is_the_transients(tmp_path: Path) -> None:
    """push_demo's headline, JSON and settling line give one time to cross: the
    independent integrator's crossing cycle / f_act (170 cycles, 28.3 ms; the headline
    said 27.2 ms from the periodic speed before)."""
    path = ROOT / "devices" / "push_demo.yaml"
    (s,) = derive_file(path).sets
    travel = s.travel_range_m / s.scales.length_m
    _, n_ref = _crossing_mode(s.params, travel, 220)
    t_ref = n_ref / s.scales.f_act_hz
    doc = _check_json(path)
    dev = doc["devices"][0]
    t_json = dev["sets"][0]["time_to_cross_s"]
    assert t_json == pytest.approx(t_ref, abs=1.0 / s.scales.f_act_hz)
    text = CliRunner().invoke(app, ["check", "--no-adequacy", str(path)]).output
    shown = f"{t_ref * 1e3:.3g} ms"
    assert f"50 µm in {shown}" in text  # the headline
    rules = _rules(doc)
    assert f"travel range from rest in {shown}" in rules["speed"]["message"]
    assert f"after {n_ref} cycles ({shown})" in rules["settling"]["message"]


# --- 7. the determination record ----------------------------------------------------------


def test_determination_json_fields_and_types(tmp_path: Path) -> None:
    """Each field where it belongs: ``fix`` a text, ``n_solves`` the 8 re-solves of an
    ideal design (ϖ, α, β, κ at +1e-12 and −1e-10), ``perturbed`` their 8 Δs near the
    orbit's, ``elapsed_s`` seconds (``fix`` printed the 8 Δs and ``n_solves`` the seconds
    before)."""
    doc = _check_json(ROOT / "devices" / "push_demo.yaml")
    dev = doc["devices"][0]
    sets = dev["details"]["sets"] if "details" in dev else dev["sets"]
    det = sets[0]["determination"]
    assert det["status"] == "determined"
    assert isinstance(det["fix"], str) and det["fix"] == ""
    assert isinstance(det["n_solves"], int) and det["n_solves"] == 8
    assert len(det["fields"]) == 8 and all(isinstance(f, str) for f in det["fields"])
    assert {f.split("×")[0] for f in det["fields"]} == {"varpi", "alpha", "beta", "kappa"}
    assert len(det["perturbed"]) == 8
    assert all(abs(v - det["delta_s"]) <= det["delta_s_error"] for v in det["perturbed"])
    assert isinstance(det["elapsed_s"], float) and 0.0 < det["elapsed_s"] < 60.0


# --- 8. an undetermined answer names what failed -------------------------------------------


def test_lost_orbit_names_the_resolve() -> None:
    """When a perturbed re-solve loses the orbit, the reason names that re-solve, its
    status and the parameter, and the fix names the parameter (it blamed "forces near
    round-off" for a re-solve that crossed ϖ = 2)."""
    from betvdesign.dynamics.determination import determine

    p = ModelParams(1.2, 2.04, 0.509, 0.15)
    base = periodic_orbit(p)

    def solver(q: ModelParams):
        if q.varpi != p.varpi:  # the re-solves of ϖ lose the orbit: a not-driven answer
            return periodic_orbit(replace(q, varpi=math.nextafter(2.0, 0.0)))
        return periodic_orbit(q)

    det = determine(p, base, solver=solver)
    assert det.status == "undetermined"
    assert "varpi×(1+1e-12) → not_driven" in det.reason
    assert "varpi×(1-1e-10) → not_driven" in det.reason
    assert "round-off" not in det.fix and "ϖ" in det.fix


def test_verdict_map_reports_interleaving_bands(monkeypatch: pytest.MonkeyPatch) -> None:
    """Where labels interleave the map reports a band with its pattern, not a bisected
    point (a bisection there lands on one of many changes: "boundary 8.65e-10" at
    κ ≈ 3e-10 … 3e-9 was not a boundary); a single change is still bisected. The labels
    here are a known function of x, so the truth does not come from the map."""
    from betvdesign.bench import verdictmap as vm

    def label(x: float) -> str:
        if x < 0.4:
            return "periodic"
        if x > 0.6:
            return "crossing"
        return ("undetermined", "crossing")[int(x * 200) % 2]  # flips every 0.005

    def classify(p: ModelParams, travel_s: float = vm.TRAVEL_S) -> dict:
        return {"label": label(p.kappa - 1e-3), "mode": None, "status": "success"}

    monkeypatch.setattr(vm, "classify", classify)
    fam = vm.Family("κ", 0.0, 1.0, False, lambda k: replace(vm.BASE, kappa=k + 1e-3))
    found = vm.boundaries(vm.scan_family(fam, points=11, bisect=12))
    bands = [b for b in found if b["kind"] == "band"]
    points = [b for b in found if b["kind"] == "boundary"]
    assert bands and all(0.3 <= b["low"] and b["high"] <= 0.7 for b in bands)
    assert all(len(set(b["pattern"])) > 1 for b in bands)
    # the single change periodic -> its neighbour at 0.4 is bisected to 2^-12 of 0.1
    edge = [b for b in points if b["below"] == "periodic"]
    assert len(edge) == 1 and edge[0]["low"] < 0.4 <= edge[0]["high"]
    assert edge[0]["high"] - edge[0]["low"] <= 0.1 / 2**11
    assert not any(0.41 < b["low"] < 0.59 for b in points)


def test_one_basis_for_every_line(tmp_path: Path) -> None:
    """push_demo driven at 1.842 kHz: its periodic orbit is not what the travel shows
    (it has not settled when it crosses), so every line quotes the crossing from rest:
    the headline, the JSON speed and time, the mode rule, the mode-margin corners, the
    settling line and the map cell of the same design; the independent integrator gives
    the crossing's sign and cycle."""
    from betvdesign.spec.loader import load_device
    from betvdesign.studies.fieldsweep import field_map, parse_axis

    path = _device(tmp_path, "f1842", **{"frequency: 3 kHz": "frequency: 1.842 kHz"})
    (s,) = derive_file(path).sets
    travel = s.travel_range_m / s.scales.length_m
    ref_mode, n_ref = _crossing_mode(s.params, travel, 200)
    doc = _check_json(path)
    st = doc["devices"][0]["sets"][0]
    rules = _rules(doc)
    assert st["basis"] == "crossing" and st["mode"] == ref_mode
    f = s.scales.f_act_hz
    assert abs(st["time_to_cross_s"] - n_ref / f) <= 1.0 / f
    assert "transient from rest crosses" in rules["mode"]["message"]
    assert "[each corner's crossing from rest]" in rules["mode-margin"]["message"]
    assert "transient from rest over the travel range" in rules["speed"]["message"]
    assert not rules["settling"]["passed"]  # it says the periodic speed is not shown
    text = CliRunner().invoke(app, ["check", "--no-adequacy", str(path)]).output
    assert f"{ref_mode} as intended" in text and "crossing mean from rest" in text
    spec = load_device(path)
    axis = parse_axis(spec, "drive.frequency=1.842kHz:1.9kHz", points=2)
    rows, _ = field_map(spec, [axis])
    cell = rows[0]
    assert cell["drive.frequency [kHz]"] == pytest.approx(1.842)
    assert cell["basis"] == "crossing" and cell["exact_mode"] == st["mode"]
    assert cell["speed_m_s"] == pytest.approx(st["speed_m_s"], rel=1e-9)
