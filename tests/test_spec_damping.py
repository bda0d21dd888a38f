"""Spec side of head damping and restitution (issue 12; shared MODEL.md, "Beyond the
paper's idealisation"; DAMPING.md): device fields ``actuator.damping_ratio_*`` |
``actuator.quality_factor_*`` (normal, tangential) and ``contact.restitution``.

Independent truths: Q = 1/(2ζ) and the normal force N ∝ A·sin(ϖτ_o + δ),
δ = atan(2ζ_v ϖ), A = sqrt(1 + (2ζ_v ϖ)²) written out here (math.sqrt; the package uses
hypot), pairs chosen so both sides are exact (ζ = 0.0125 ↔ Q = 40, ζ = 0.5 ↔ Q = 1);
ϖ = f_act/f_v = 6 kHz/5 kHz of devices/damped_demo.yaml; the supported range from
betvdesign.model.params (its one home); file:line:col positions read off the texts below by
hand; derive_set one sample at a time against derive_samples on arrays.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from betvdesign.cli import app
from betvdesign.errors import SpecError
from betvdesign.model.params import ZETA_MAX, ZETA_MIN, ModelParams
from betvdesign.nondim.device import derive, derive_file, derive_samples, derive_set
from betvdesign.spec.loader import load_device, load_device_text
from betvdesign.spec.paths import with_values
from betvdesign.spec.units import ureg
from betvdesign.studies.sampling import derive_all, nominal_values, params_of
from betvdesign.studies.tolerance import parse_tolerance

TESTS = Path(__file__).resolve().parent
DEVICES = TESTS.parent / "devices"
DEMO = DEVICES / "damped_demo.yaml"
BASE = (TESTS / "data" / "specs" / "valid_base.yaml").read_text("utf-8")
ACT = "      alpha: 0.1\n"  # line 18 of valid_base.yaml: actuator lines start at 19
CONTACT = "      friction: 0.4\n"  # line 15: contact lines start at 16
A = "actuator_sets[0].actuator."
C = "actuator_sets[0].contact."
NEW = ("ζ_v", "ζ_h", "Q_v", "Q_h", "e", "δ", "A")


def spec_with(actuator: str = "", contact: str = "", name: str = "d.yaml"):
    return load_device_text(_text(actuator, contact), name)


def _text(actuator: str = "", contact: str = "") -> str:
    def lines(s: str) -> str:
        return "".join(f"      {ln}\n" for ln in s.splitlines())

    return BASE.replace(ACT, ACT + lines(actuator)).replace(CONTACT, CONTACT + lines(contact))


def params(actuator: str = "", contact: str = "") -> ModelParams:
    return derive(spec_with(actuator, contact)).sets[0].params


def run(*args):
    return CliRunner().invoke(app, [str(a) for a in args])


# --- parsing, both forms, equivalence -------------------------------------------------


@pytest.mark.parametrize(
    ("zeta", "q"), [(0.0125, 40.0), (0.5, 1.0), (ZETA_MIN, 5000.0), (ZETA_MAX, 0.05)]
)
def test_quality_factor_and_damping_ratio_give_the_same_model(zeta, q):
    """Q and ζ = 1/(2Q) are two spellings of one damper: the same ModelParams, per
    direction (the range edges included)."""
    by_q = params(f"quality_factor_normal: {q!r}\nquality_factor_tangential: {q!r}")
    by_z = params(f"damping_ratio_normal: {zeta!r}\ndamping_ratio_tangential: {zeta!r}")
    assert by_q == by_z
    assert by_q.zeta_v == by_q.zeta_h == zeta
    assert not by_q.ideal and by_q.restitution == 0.0


def test_directions_and_restitution_are_independent():
    p = params("quality_factor_normal: 40\ndamping_ratio_tangential: 0.5", "restitution: 0.25")
    assert (p.zeta_v, p.zeta_h, p.restitution) == (0.0125, 0.5, 0.25)
    p = params("", "restitution: 0.25")
    assert (p.zeta_v, p.zeta_h, p.restitution) == (0.0, 0.0, 0.25)
    p = params("damping_ratio_tangential: 0.5")
    assert (p.zeta_v, p.zeta_h, p.restitution) == (0.0, 0.5, 0.0)


def test_integers_are_plain_numbers_too():
    spec = spec_with("quality_factor_normal: 40", "restitution: 0")
    assert spec.actuator_sets[0].actuator.quality_factor_normal == 40.0
    assert spec.actuator_sets[0].contact.restitution == 0.0


def test_defaults_are_the_papers_model():
    """No field, or every term at 0, gives ModelParams.ideal and the same parameters; with
    no field the record holds none of the new quantities (the bit-identical derivation
    of every earlier device is tests/test_rolloff.py's baseline test)."""
    plain = derive(spec_with()).sets[0]
    assert plain.params.ideal and plain.params.as_dict().keys() == {
        "varpi",
        "alpha",
        "beta",
        "kappa",
    }
    assert not {s.symbol for s in plain.record} & set(NEW)
    zeros = derive(
        spec_with("damping_ratio_normal: 0\ndamping_ratio_tangential: 0", "restitution: 0")
    ).sets[0]
    assert zeros.params.ideal and zeros.params == plain.params and zeros.lam == plain.lam
    assert zeros.scales == plain.scales
    rows = {s.symbol: s for s in zeros.record}
    assert rows["ζ_v"].formula == "spec: actuator.damping_ratio_normal"
    assert "Q_v" not in rows and "δ" not in rows  # Q = ∞ and δ = 0 are not shown
    for name in ("push_demo", "rolloff_demo", "shin2004", "bidir_demo", "pull_demo"):
        assert all(sd.params.ideal for sd in derive_file(DEVICES / f"{name}.yaml").sets)


def test_damping_leaves_the_four_parameters_and_scales_alone():
    plain = derive(spec_with()).sets[0]
    damped = derive(spec_with("quality_factor_normal: 30", "restitution: 0.1")).sets[0]
    for k in ("varpi", "alpha", "beta", "kappa"):
        assert getattr(damped.params, k) == getattr(plain.params, k)
    assert damped.scales == plain.scales and damped.lam == plain.lam


# --- the derivation record ------------------------------------------------------------


def test_record_of_the_demo_by_hand():
    """damped_demo: Q_v = Q_h = 30 -> ζ = 1/60; ϖ = 6 kHz/5 kHz = 1.2 -> 2ζ_vϖ = 0.04,
    δ = atan(0.04) = 0.0399787 rad = 2.2906°, A = sqrt(1.0016) = 1.00079968."""
    sd = derive_file(DEMO).sets[0]
    p = sd.params
    assert p.varpi == pytest.approx(1.2, rel=1e-15)
    assert p.zeta_v == p.zeta_h == 1 / 60 and p.restitution == 0.1
    rows = {s.symbol: s for s in sd.record}
    for sub, word in (("v", "normal"), ("h", "tangential")):
        q, z = rows[f"Q_{sub}"], rows[f"ζ_{sub}"]
        assert q.formula == f"spec: actuator.quality_factor_{word}" and q.magnitude == 30.0
        assert z.formula == f"1/(2·Q_{sub})" and z.inputs == (f"Q_{sub}",)
        assert z.magnitude == 1 / 60 and z.key == f"zeta_{sub}"
    assert rows["e"].formula == "spec: contact.restitution" and rows["e"].magnitude == 0.1
    x = 2 * (1 / 60) * p.varpi
    delta, amp = rows["δ"], rows["A"]
    assert delta.inputs == amp.inputs == ("ζ_v", "ϖ")
    assert delta.value.to("rad").magnitude == pytest.approx(math.atan(x), rel=1e-15)
    assert delta.value.to("rad").magnitude == pytest.approx(0.0399786871, rel=1e-9)
    assert "2.291°" in delta.description and delta.key == "delta"
    assert amp.magnitude == pytest.approx(math.sqrt(1 + x * x), rel=1e-15)
    assert amp.magnitude == pytest.approx(1.00079968, rel=1e-8)
    order = [s.symbol for s in sd.record]
    assert order.index("ϖ") < order.index("δ") < order.index("λ")
    # roll-off as well: the demo carries every optional term
    assert sd.scales.has_rolloff and sd.scales.rolloff_factor == pytest.approx(0.135567, 1e-5)


def test_record_from_a_damping_ratio_shows_its_quality_factor():
    sd = derive(spec_with("damping_ratio_normal: 0.0125")).sets[0]
    rows = {s.symbol: s for s in sd.record}
    assert rows["ζ_v"].formula == "spec: actuator.damping_ratio_normal"
    assert rows["Q_v"].formula == "1/(2·ζ_v)" and rows["Q_v"].magnitude == 40.0
    assert "ζ_h" not in rows and "e" not in rows
    # ϖ = 2 × 500 Hz / 2.94 kHz
    x = 2 * 0.0125 * (1000 / 2940)
    assert rows["δ"].value.to("rad").magnitude == pytest.approx(math.atan(x), rel=1e-14)


def test_tangential_damping_alone_has_no_normal_force_phase():
    rows = {s.symbol for s in derive(spec_with("quality_factor_tangential: 30")).sets[0].record}
    assert {"Q_h", "ζ_h"} <= rows and not {"δ", "A", "ζ_v"} & rows


# --- bad input: file:line:col, field, exit 2 ------------------------------------------

RANGE = f"{ZETA_MIN:g} ≤ ζ ≤ {ZETA_MAX:g}, i.e. {1 / (2 * ZETA_MAX):g} ≤ Q ≤ {1 / (2 * ZETA_MIN):g}"

#: name -> (actuator lines, contact lines, line, col, field, fragment)
BAD = {
    "q_zero": ("quality_factor_normal: 0", "", 19, 30, A + "quality_factor_normal", "> 0"),
    "q_negative": (
        "quality_factor_tangential: -30",
        "",
        19,
        34,
        A + "quality_factor_tangential",
        "quality factor Q must be > 0, got -30",
    ),
    "zeta_negative": (
        "damping_ratio_normal: -0.01",
        "",
        19,
        29,
        A + "damping_ratio_normal",
        "damping ratio ζ must be ≥ 0",
    ),
    "zeta_negative_tangential": (
        "damping_ratio_tangential: -1e-3",
        "",
        19,
        33,
        A + "damping_ratio_tangential",
        "must be ≥ 0",
    ),
    "both_normal": (
        "damping_ratio_normal: 0.01\nquality_factor_normal: 50",
        "",
        20,
        30,
        A + "quality_factor_normal",
        "give 'damping_ratio_normal' or this, not both",
    ),
    "both_tangential": (
        "quality_factor_tangential: 50\ndamping_ratio_tangential: 0.01",
        "",
        19,
        34,
        A + "quality_factor_tangential",
        "give 'damping_ratio_tangential' or this, not both",
    ),
    "zeta_below_range": (
        f"damping_ratio_normal: {ZETA_MIN / 2!r}",
        "",
        19,
        29,
        A + "damping_ratio_normal",
        RANGE,
    ),
    "zeta_above_range": (
        f"damping_ratio_tangential: {ZETA_MAX * 1.05!r}",
        "",
        19,
        33,
        A + "damping_ratio_tangential",
        RANGE,
    ),
    "q_above_range": (
        f"quality_factor_normal: {1.2 / (2 * ZETA_MIN)!r}",
        "",
        19,
        30,
        A + "quality_factor_normal",
        RANGE,
    ),
    "q_below_range": (
        f"quality_factor_tangential: {0.8 / (2 * ZETA_MAX)!r}",
        "",
        19,
        34,
        A + "quality_factor_tangential",
        RANGE,
    ),
    "q_infinite": (
        "quality_factor_normal: .inf",
        "",
        19,
        30,
        A + "quality_factor_normal",
        "finite",
    ),
    "zeta_nan": ("damping_ratio_normal: .nan", "", 19, 29, A + "damping_ratio_normal", "finite"),
    "q_with_unit": (
        "quality_factor_normal: 30 Hz",
        "",
        19,
        30,
        A + "quality_factor_normal",
        "expected a number",
    ),
    "zeta_boolean": (
        "damping_ratio_tangential: true",
        "",
        19,
        33,
        A + "damping_ratio_tangential",
        "expected a number",
    ),
    "e_one": ("", "restitution: 1", 16, 20, C + "restitution", "e = 1 is outside [0, 1)"),
    "e_above_one": ("", "restitution: 1.5", 16, 20, C + "restitution", "outside [0, 1)"),
    "e_negative": ("", "restitution: -0.1", 16, 20, C + "restitution", "outside [0, 1)"),
    "e_infinite": ("", "restitution: .inf", 16, 20, C + "restitution", "finite"),
    "e_nan": ("", "restitution: .nan", 16, 20, C + "restitution", "finite"),
}


def _bad_file(tmp_path: Path, name: str) -> Path:
    act, contact = BAD[name][:2]
    f = tmp_path / f"{name}.yaml"
    f.write_text(_text(act, contact), "utf-8")
    return f


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_input_names_file_line_and_field(name, tmp_path):
    f = _bad_file(tmp_path, name)
    line, col, field, fragment = BAD[name][2:]
    with pytest.raises(SpecError) as exc:
        load_device(f)
    (issue,) = exc.value.issues
    assert issue.location.file == str(f)
    assert (issue.location.line, issue.location.col) == (line, col), str(issue)
    assert issue.field == field and fragment in issue.message, str(issue)


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_input_is_exit_2_at_file_line_through_the_cli(name, tmp_path):
    f = _bad_file(tmp_path, name)
    line, col, field, fragment = BAD[name][2:]
    r = run("check", f)
    assert r.exit_code == 2, r.output
    assert r.stdout == "" and "Traceback" not in r.stderr
    head = f"error: {f}:{line}:{col}: {field}: "
    assert r.stderr.startswith(head) and fragment in r.stderr, r.stderr


@pytest.mark.parametrize(
    ("path", "value", "fragment"),
    [
        ("actuator_sets.0.actuator.quality_factor_normal", -3, "must be > 0"),
        ("actuator_sets.0.actuator.damping_ratio_tangential", -0.2, "must be ≥ 0"),
        ("actuator_sets.0.contact.restitution", 1.0, "outside [0, 1)"),
        ("actuator_sets.0.actuator.quality_factor_normal", math.inf, "finite"),
    ],
)
def test_bad_values_from_python_name_the_field(path, value, fragment):
    """A what-if edit in Python gets the device file's own validation and message."""
    spec = load_device(DEMO)
    with pytest.raises(SpecError) as exc:
        spec.replace(path, value)
    (issue,) = exc.value.issues
    assert issue.field == path.replace("sets.0", "sets[0]") and fragment in issue.message


def test_python_what_if_both_forms_is_an_error_and_swap_works():
    spec = load_device(DEMO)
    with pytest.raises(SpecError, match="not both"):
        spec.replace("actuator_sets.0.actuator.damping_ratio_normal", 0.0125)
    swapped = spec.replace(
        "actuator_sets.0.actuator.quality_factor_normal",
        None,
        ("actuator_sets.0.actuator.damping_ratio_normal", 0.0125),
    )
    assert derive(swapped).sets[0].params.zeta_v == 0.0125


def test_model_params_agree_with_the_spec_range():
    """What the spec accepts at the edges, ModelParams accepts; just outside, both refuse."""
    for z in (ZETA_MIN, ZETA_MAX):
        assert ModelParams(1, 1, 1, 1, zeta_v=z).zeta_v == z
    for text in (f"damping_ratio_normal: {ZETA_MIN * 0.999!r}", "quality_factor_normal: 5001"):
        with pytest.raises(SpecError, match="outside the supported range"):
            spec_with(text)


# --- the vectorised derivation and spec paths of studies -------------------------------


@pytest.mark.parametrize("form", ["quality_factor", "damping_ratio"])
def test_derive_samples_equals_derive_set_on_a_damped_spec(form):
    """Arrays of Q (or ζ), restitution and drive frequency through derive_samples equal
    derive_set of each sample alone (a validated what-if copy), every ModelParams field
    and the length scale bit for bit."""
    spec = load_device(DEMO)
    if form == "damping_ratio":
        spec = spec.replace(
            "actuator_sets.0.actuator.quality_factor_normal",
            None,
            ("actuator_sets.0.actuator.quality_factor_tangential", None),
            ("actuator_sets.0.actuator.damping_ratio_normal", 0.02),
            ("actuator_sets.0.actuator.damping_ratio_tangential", 0.03),
        )
    damping = np.array(
        [10.0, 25.0, 60.0, 100.0] if form == "quality_factor" else [0.005, 0.02, 0.1, 0.5]
    )
    e = np.array([0.0, 0.05, 0.3, 0.9])
    f = np.array([2.0e3, 2.5e3, 3.0e3, 3.5e3])
    fields = [f"actuator.{form}_normal", f"actuator.{form}_tangential", "contact.restitution"]
    columns = [damping, damping[::-1].copy(), e]
    arrays = with_values(
        spec, {"drive.frequency": ureg.Quantity(f, "Hz"), **dict(zip(fields, columns, strict=True))}
    )
    many = derive_samples(arrays, arrays.actuator_sets[0])
    for i in range(len(f)):
        one = spec.replace(
            "actuator_sets.0.drive.frequency",
            f"{float(f[i])!r} Hz",
            *((f"actuator_sets.0.{k}", float(c[i])) for k, c in zip(fields, columns, strict=True)),
        )
        sd = derive_set(one, one.actuator_sets[0])
        got = ModelParams(
            *(float(getattr(many, k)[i]) for k in ("varpi", "alpha", "beta", "kappa")),
            zeta_v=float(many.zeta_v[i]),
            zeta_h=float(many.zeta_h[i]),
            restitution=float(many.restitution[i]),
        )
        assert got == sd.params and not got.ideal
        assert many.length_m[i] == sd.scales.length_m
        want = [1 / (2 * c[i]) if form == "quality_factor" else c[i] for c in columns[:2]]
        assert [many.zeta_v[i], many.zeta_h[i], many.restitution[i]] == [*want, e[i]]


def test_derive_samples_of_an_undamped_spec_gives_zero_columns():
    spec = load_device(DEVICES / "push_demo.yaml")
    arrays = with_values(spec, {"contact.friction": np.array([0.3, 0.4, 0.5])})
    many = derive_samples(arrays, arrays.actuator_sets[0])
    for k in ("zeta_v", "zeta_h", "restitution"):
        np.testing.assert_array_equal(getattr(many, k), np.zeros(3))


def test_spread_of_a_quality_factor_reaches_the_model_parameters():
    """`--spread actuator.quality_factor_normal=normal:20%`: each sample's ζ_v is
    1/(2Q) of its drawn Q, through the vectorised path the tolerance study uses."""
    spec = load_device(DEMO)
    tols = [
        parse_tolerance("actuator.quality_factor_normal=normal:20%"),
        parse_tolerance("contact.restitution=uniform:0.05"),
    ]
    nominal = nominal_values(spec, tols)
    assert nominal == {
        "actuator.quality_factor_normal": (30.0, ""),
        "contact.restitution": (0.1, ""),
    }
    x = np.array([[24.0, 0.06], [30.0, 0.1], [36.0, 0.14]])
    derived = derive_all(spec, tols, nominal, x, 0)
    assert derived is not None
    for j, (q, e) in enumerate(x):
        p = params_of(derived, j)
        assert p.zeta_v == 1 / (2 * q) and p.restitution == e and p.zeta_h == 1 / 60
        single = params_of({k: v[j] for k, v in derived.items()})
        assert single == p


def test_fix_can_vary_a_quality_factor():
    from betvdesign.studies.fixfields import parse_vary

    (v,) = parse_vary(load_device(DEMO), ["actuator.quality_factor_normal=10:100"])
    assert (v.x0, v.lo, v.hi, v.unit) == (30.0, 10.0, 100.0, "")


# --- betv schema ----------------------------------------------------------------------


def test_schema_documents_the_fields():
    schema = json.loads(run("schema").stdout)
    act = schema["$defs"]["Actuator"]["properties"]
    for word, sym in (("normal", "v"), ("tangential", "h")):
        zd = act[f"damping_ratio_{word}"]["description"]
        qd = act[f"quality_factor_{word}"]["description"]
        assert f"ζ_{sym}" in zd and f"{ZETA_MIN:g} ≤ ζ ≤ {ZETA_MAX:g}" in zd
        assert f"Q_{sym} = 1/(2ζ)" in qd and f"{1 / (2 * ZETA_MAX):g} ≤ Q ≤ " in qd
        assert f"{1 / (2 * ZETA_MIN):g}" in qd
    assert "quality_factor_*" in schema["$defs"]["Actuator"]["description"]
    contact = schema["$defs"]["Contact"]
    assert "0 ≤ e < 1" in contact["properties"]["restitution"]["description"]
    assert "pair of surfaces" in contact["description"]


# --- betv check shows the terms -------------------------------------------------------


@pytest.mark.slow
def test_check_shows_damping_and_restitution(monkeypatch, tmp_path):
    """With a stand-in solver (the damped kernel is not this test's subject): the JSON
    params carry ζ_v = ζ_h = 1/(2·30) and e, the text line Q and e; ζ_h = 0 reads Q_h ∞;
    an undamped device keeps its four parameters only."""
    from types import SimpleNamespace

    from betvdesign.checks import checker

    def orbit(p):
        return SimpleNamespace(
            status="success", success=True, message="stand-in", delta_s=1.0, period_cycles=1
        )

    monkeypatch.setattr(checker, "periodic_orbit", orbit)
    monkeypatch.setattr("betvdesign.checks.checker._settling", lambda p, po, travel, horizon: None)
    (s,) = json.loads(run("check", DEMO, "--json").stdout)["devices"][0]["sets"]
    assert s["params"]["zeta_v"] == s["params"]["zeta_h"] == 1 / 60
    assert s["params"]["restitution"] == 0.1
    assert "Q_v 30 Q_h 30 e 0.1" in " ".join(run("check", DEMO).stdout.split())
    normal_only = tmp_path / "normal_only.yaml"
    line = "      quality_factor_tangential: 30    # Q_h: ζ_h = 1/(2 Q_h) ≈ 0.0167\n"
    assert line in DEMO.read_text("utf-8")
    normal_only.write_text(DEMO.read_text("utf-8").replace(line, ""), "utf-8")
    assert "Q_v 30 Q_h ∞ e 0.1" in " ".join(run("check", normal_only).stdout.split())
    plain = tmp_path / "plain.yaml"
    plain.write_text(_text(), "utf-8")
    (s,) = json.loads(run("check", plain, "--json").stdout)["devices"][0]["sets"]
    assert set(s["params"]) == {"varpi", "alpha", "beta", "kappa"}
    assert " Q_v " not in run("check", plain).stdout


# --- parameters derived from a device's keep its damping and restitution ----------------


def test_margin_corners_keep_damping_and_restitution():
    """The mode-margin corners scale ϖ and α only: ζ_v, ζ_h, e are the device's."""
    from betvdesign.checks.checker import corner_params
    from betvdesign.checks.rules import MARGIN_CORNERS

    p = derive_file(DEMO).sets[0].params
    corners = corner_params(p)
    assert len(corners) == len(MARGIN_CORNERS)
    for (fw, fa), c in zip(MARGIN_CORNERS, corners.values(), strict=True):
        assert (c.varpi, c.alpha) == (p.varpi * fw, p.alpha * fa)
        assert (c.beta, c.kappa, c.zeta_v, c.zeta_h, c.restitution) == (
            p.beta,
            p.kappa,
            1 / 60,
            1 / 60,
            0.1,
        )


def test_speed_frequency_sweep_keeps_damping_and_restitution(monkeypatch):
    """The report's speed-against-frequency orbits vary ϖ only (recorded by a stand-in
    periodic_orbit): every other parameter is the device's."""
    from types import SimpleNamespace

    import betvdesign.dynamics as dyn
    from betvdesign.report.analysis import Piece, ReportOptions
    from betvdesign.report.frequency import frequency_sweep

    seen: list[ModelParams] = []

    def orbit(p, **_):
        seen.append(p)
        return SimpleNamespace(success=True, delta_s=0.5, status="success", message="")

    monkeypatch.setattr(dyn, "periodic_orbit", orbit)
    sd = derive_file(DEMO).sets[0]
    own = Piece(value=SimpleNamespace(success=True, delta_s=0.5))
    frequency_sweep(sd.params, sd.scales.f_act_hz, own, ReportOptions(frequency_points=5))
    assert seen and all(q.varpi != sd.params.varpi for q in seen)
    p = sd.params
    for q in seen:
        assert (q.alpha, q.beta, q.kappa) == (p.alpha, p.beta, p.kappa)
        assert (q.zeta_v, q.zeta_h, q.restitution) == (1 / 60, 1 / 60, 0.1)


def test_tolerance_study_spreads_a_quality_factor(tmp_path):
    """`betv tolerance --spread actuator.quality_factor_normal=normal:20%` (exact periodic
    rung: the λ fit is refused for a damped device): each row's ζ_v is 1/(2Q) of its
    drawn Q; ζ_h and e stay the device's; a device of the paper's model has no such
    columns."""
    import csv

    out = tmp_path / "t.csv"
    spread = "actuator.quality_factor_normal=normal:20%"
    common = ["-n", 6, "--fidelity", "periodic", "-x", "serial", "-q"]
    r = run("tolerance", DEMO, "--spread", spread, *common, "-o", out)
    assert r.exit_code == 0, r.output
    rows = list(csv.DictReader(out.open(encoding="utf-8")))
    assert len(rows) == 6
    qs = {float(row["in:actuator.quality_factor_normal"]) for row in rows}
    assert len(qs) == 6  # drawn, not the nominal 30
    for row in rows:
        q = float(row["in:actuator.quality_factor_normal"])
        assert float(row["zeta_v"]) == pytest.approx(1 / (2 * q), rel=1e-15)
        assert float(row["zeta_h"]) == 1 / 60 and float(row["restitution"]) == 0.1
    plain = tmp_path / "p.csv"
    r = run(
        "tolerance",
        DEVICES / "push_demo.yaml",
        "--spread",
        "contact.friction=normal:5%",
        *common,
        "-o",
        plain,
    )
    assert r.exit_code == 0, r.output
    header = plain.read_text("utf-8").splitlines()[0].split(",")
    assert not {"zeta_v", "zeta_h", "restitution"} & set(header)


def test_spread_quality_factor_reaches_the_exact_solver(tmp_path):
    """Exact periodic rung: each row's Δs is the periodic orbit of that sample's device
    derived one by one (what-if copy with the drawn Q), so the spread Q reaches the
    solver; different Q give different Δs."""
    import csv

    from betvdesign.dynamics import periodic_orbit

    out = tmp_path / "t.csv"
    spread = "actuator.quality_factor_normal=normal:30%"
    r = run("tolerance", DEMO, "--spread", spread, "-n", 3, "-x", "serial", "-q", "-o", out)
    assert r.exit_code == 0, r.output
    rows = list(csv.DictReader(out.open(encoding="utf-8")))
    assert all(row["status"] == "success" for row in rows), rows
    spec = load_device(DEMO)
    for row in rows:
        q = float(row["in:actuator.quality_factor_normal"])
        one = spec.replace("actuator_sets.0.actuator.quality_factor_normal", q)
        p = derive_set(one, one.actuator_sets[0]).params
        assert p.zeta_v == pytest.approx(1 / (2 * q), rel=1e-15)
        assert float(row["delta_s"]) == pytest.approx(periodic_orbit(p).delta_s, rel=1e-9)
    assert len({round(float(row["delta_s"]), 9) for row in rows}) == 3


def test_simulate_names_the_terms():
    first = run("simulate", DEMO, "--cycles", 3).stdout.splitlines()[0]
    assert first.endswith("ζ_v = 0.0166667, ζ_h = 0.0166667, e = 0.1")
    plain = run("simulate", DEVICES / "push_demo.yaml", "--cycles", 3).stdout.splitlines()[0]
    assert "ζ_v" not in plain and " e = " not in plain
