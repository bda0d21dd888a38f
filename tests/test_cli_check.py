"""`betv check` and `betv schema` through typer's CliRunner (source: the shipped devices,
hand-computed shin2004 parameters, the issue's JSON contract)."""

import json
import math
from pathlib import Path

import pytest
from conftest import orbit_stand_in
from typer.testing import CliRunner

from betvdesign.checks import checker
from betvdesign.checks.view import VERBOSE_SET_FIELDS
from betvdesign.cli import app
from betvdesign.spec.loader import load_device
from betvdesign.spec.models import DeviceSpec

DEVICES = Path(__file__).resolve().parents[1] / "devices"
SHIN = str(DEVICES / "shin2004.yaml")
OWN = ["push_demo", "pull_demo", "bidir_demo", "rolloff_demo", "damped_demo"]


@pytest.fixture
def no_solver(monkeypatch):
    """A stand-in solver (Δs = ±1 per cycle, with the sign λ predicts) instead of the exact
    one: the CLI's presentation is tested apart from the dynamics."""

    def orbit(p):
        return orbit_stand_in(1.0 if p.lam < 1 else -1.0)

    monkeypatch.setattr(checker, "periodic_orbit", orbit)
    monkeypatch.setattr("betvdesign.checks.checker._settling", lambda p, po, travel, horizon: None)


def run(*args):
    return CliRunner().invoke(app, list(args))


@pytest.mark.slow
def test_shin2004_fails_the_window_and_shows_fit_mismatch(no_solver):
    r = run("check", SHIN)
    assert r.exit_code == 1, r.output
    out = r.stdout
    assert "FAIL" in out and "frequency-window" in out
    assert "below the window" in out
    assert "published-fit.varpi" in out and "disagree" in out
    assert "fix:" in out and "drive.frequency" in out
    assert "extrapolates" in run("check", "--verbose", SHIN).stdout  # β = 9.09 outside


def _device(stdout: str) -> dict:
    d = json.loads(stdout)
    assert (d["schema"], d["version"]) == ("betv-check", 4)
    assert len(d["devices"]) == 1
    return d["devices"][0]


@pytest.mark.slow
def test_shin2004_json_contract(no_solver):
    """Version 2: SI floats under unit-named keys; hand-computed shin2004 parameters."""
    r = run("check", SHIN, "--json")
    assert r.exit_code == 1
    d = _device(r.stdout)
    assert d["device"] == "shin2004" and d["verdict"] == "fail"
    assert d["failed"] == ["frequency-window"]
    s = d["sets"][0]
    assert set(s["params"]) == {"varpi", "alpha", "beta", "kappa"}
    assert s["params"]["varpi"] == pytest.approx(1000 / 2940)
    assert s["params"]["beta"] == pytest.approx(3.6e-11 / (2330 * 170e-6 * 5e-6 * 2e-6))
    assert s["derived"]["f_act_hz"] == pytest.approx(1000.0)
    assert s["derived"]["head_mass_kg"] == pytest.approx(3.6e-11)  # 0.036 ug
    assert s["derived"]["amplitude_m"] == pytest.approx(0.11e-6)
    # the drawn actuator's mechanics (issue 30): kHz, never MHz; f_v = √(k_v/m_eff)/2π
    drawn = s["derived"]["drawn"]
    assert 1e3 < drawn["f_oop_hz"] < drawn["f_1_hz"] < 2e5 and 1e3 < drawn["f_v_hz"] < 2e5
    assert drawn["f_v_hz"] == pytest.approx(
        (drawn["k_v_n_m"] / drawn["m_eff_kg"]) ** 0.5 / (2 * math.pi), rel=1e-9
    )
    assert s["travel_range_m"] == pytest.approx(40e-6)
    assert s["mode"] == "pull" and s["lambda"]["predicts"] == "pull"
    for rule in s["rules"]:
        assert set(rule) == {
            "id",
            "severity",
            "passed",
            "value",
            "value_unit",
            "threshold",
            "message",
            "fix",
            "source",
        }
        assert rule["severity"] in ("error", "warning", "info")
    win = [x for x in s["rules"] if x["id"] == "frequency-window"]
    assert win and not any(x["passed"] for x in win) and "drive.frequency" in win[0]["fix"]
    assert "details" not in d and not set(VERBOSE_SET_FIELDS) & set(s)
    full = _device(run("check", SHIN, "--json", "--verbose").stdout)
    fit = full["sets"][0]["published_fit"]
    assert {f["param"] for f in fit} == {"varpi", "alpha", "beta", "kappa"}
    assert next(f for f in full["sets"][0]["record"] if f["symbol"] == "f_act")["formula"] == (
        "2·f_drive"
    )


@pytest.mark.slow
def test_json_conforms_to_its_published_schema(no_solver):
    """Every device's --json output validates against `betv schema check` (a generic
    draft-2020-12 walk of the schema, written below, not pydantic itself)."""
    schema = json.loads(run("schema", "check").stdout)
    assert schema["properties"]["version"]["const"] == 4
    r = run("check", "--json", *(str(p) for p in sorted(DEVICES.glob("*.yaml"))))
    doc = json.loads(r.stdout)
    assert [x["device"] for x in doc["devices"]] == [
        "bidir_demo",
        "damped_demo",
        "pull_demo",
        "push_demo",
        "rolloff_demo",
        "shin2004",
    ]
    assert doc["verdict"] == "fail" and r.exit_code == 1
    _assert_conforms(doc, schema, schema)


@pytest.mark.slow
def test_json_v3_fields_and_types_and_verbose_only_adds(no_solver):
    """Version 3: one typed shape. The schema declares the verbose set fields with their
    types and no untyped 'details'; the --verbose document validates against it, and
    with the verbose fields taken out it is the plain document: -v adds, never repeats."""
    schema = json.loads(run("schema", "check").stdout)
    assert schema["properties"]["version"]["const"] == 4 and "4" in schema["x-betv-changes"]
    defs = schema["$defs"]
    assert "details" not in defs["DeviceOut"]["properties"]
    props = defs["SetOut"]["properties"]
    required = set(defs["SetOut"]["required"])
    assert not set(VERBOSE_SET_FIELDS) & required

    def kinds(sch):  # the JSON types a property admits ($ref by name)
        alts = sch.get("anyOf", [sch])
        return {a.get("type") or a["$ref"].split("/")[-1] for a in alts}

    assert kinds(props["mode_source"]) == {"string", "null"}
    assert kinds(props["simulation"]) == {"SimulationOut", "null"}
    assert kinds(props["vertical"]) == {"VerticalOut", "null"}
    for name in ("settling", "determination", "travel"):
        assert kinds(props[name]) == {"object", "null"}
    assert props["record"]["anyOf"][0]["items"]["$ref"].endswith("/RecordStepOut")
    assert props["published_fit"]["anyOf"][0]["items"]["$ref"].endswith("/PublishedFitOut")
    sim = defs["SimulationOut"]["properties"]
    assert kinds(sim["delta_s"]) == {"number", "null"} and kinds(sim["n_cycles"]) == {
        "integer",
        "null",
    }
    assert defs["RecordStepOut"]["properties"]["value"]["type"] == "string"
    files = [str(DEVICES / f"{n}.yaml") for n in ("push_demo", "shin2004")]
    plain = json.loads(run("check", "--json", *files).stdout)
    full = json.loads(run("check", "--json", "-v", *files).stdout)
    _assert_conforms(full, schema, schema)
    for dp, dv in zip(plain["devices"], full["devices"], strict=True):
        for sp, sv in zip(dp["sets"], dv["sets"], strict=True):
            assert set(sv) - set(sp) == set(VERBOSE_SET_FIELDS)
            assert {k: v for k, v in sv.items() if k not in VERBOSE_SET_FIELDS} == sp
            assert [st["symbol"] for st in sv["record"]][:2] and sv["simulation"]["success"]
        assert {k: v for k, v in dv.items() if k != "sets"} == {
            k: v for k, v in dp.items() if k != "sets"
        }


@pytest.mark.parametrize("name", OWN)
def test_own_designs_pass(name):
    """Every error and warning rule passes with the exact solver; the mode is the
    exact orbit's, and the λ fit agrees for these clear designs."""
    r = run("check", str(DEVICES / f"{name}.yaml"), "--json", "--verbose")
    assert r.exit_code == 0, r.stdout
    d = _device(r.stdout)
    assert d["verdict"] == "pass" and d["failed"] == []
    every = [x for s in d["sets"] for x in s["rules"]] + d["rules"]
    # model-adequacy judges the paper's idealised model, not the design: at ϖ ≥ 0.5 every
    # design loses its drive at some restitution e < 0.9 (the rebounds leave no finite
    # contact), so it warns here by design (tests/test_adequacy.py).
    # process.release: a 36 µm head needs etch holes in the process; a device file cannot
    # show them, `betv layout` draws them (issue 23)
    # actuator.geometry: the demo files' phenomenological resonances (2.9–6 kHz) are 20–30×
    # below their drawn actuators' first in-plane mode; the file's values win and the rule
    # warns with the likely cause (issue 30, item 5)
    skip = ("model-adequacy", "process.release", "actuator.geometry")
    kept = [x for x in every if x["severity"] != "info" and x["id"] not in skip]
    assert all(x["passed"] for x in kept), every
    assert all(s["adequacy"]["reference_mode"] == s["mode"] for s in d["sets"])
    for s in d["sets"]:
        assert s["mode"] == s["intended_mode"] and s["passed"] and s["lambda"]["agrees"]
        assert s["settling"]["status"] == "settled"
        assert s["basis"] == "periodic" and s["mode_source"].startswith("exact periodic orbit")
        assert s["margin"]["holds"] and set(s["margin"]["corners"].values()) == {s["mode"]}


@pytest.mark.slow
def test_several_files_give_one_shape_and_worst_exit(no_solver):
    r = run("check", "--json", str(DEVICES / "push_demo.yaml"), SHIN)
    assert r.exit_code == 1
    d = json.loads(r.stdout)
    assert [x["device"] for x in d["devices"]] == ["push_demo", "shin2004"]
    assert d["verdict"] == "fail"
    r = run("check", "--json", *(str(DEVICES / f"{n}.yaml") for n in OWN))
    assert r.exit_code == 0 and len(json.loads(r.stdout)["devices"]) == len(OWN)


def test_tables_and_derivation(no_solver):
    r = run("check", "--verbose", str(DEVICES / "bidir_demo.yaml"))
    assert r.exit_code == 0
    assert "PASS" in r.stdout and "set east" in r.stdout and "set west" in r.stdout
    assert "derivation of set east" in r.stdout and "(f_v/f_h)²" in r.stdout


def test_usage_errors_exit_2():
    assert run("check").exit_code == 2
    for gone in ("--simulate", "--closed-form-only", "--fidelity"):  # no verdict from a fit
        assert run("check", gone, SHIN).exit_code == 2
    r = run("check", "--target-speed", "3 kg", SHIN)
    assert r.exit_code == 2 and "--target-speed" in r.stderr and "Traceback" not in r.output
    assert run("check", "--target-speed", "-1 mm/s", SHIN).exit_code == 2


def test_bad_file_exit_2_names_file_line_field(tmp_path, no_solver):
    bad = tmp_path / "bad.yaml"
    bad.write_text(Path(SHIN).read_text().replace("beam_width: 5 um", "beam_width: 5", 1))
    r = run("check", str(bad), SHIN)
    assert r.exit_code == 2
    assert f"{bad}:" in r.stderr and "slider.beam_width: missing unit" in r.stderr
    assert r.stdout == ""  # nothing half-reported
    missing = run("check", str(tmp_path / "nope.yaml"))
    assert missing.exit_code == 2 and "file not found" in missing.stderr


def test_several_bad_files_report_every_files_issues_in_order(tmp_path, no_solver):
    """Two bad files among good ones: one refusal holding the issues each file gives when
    checked alone, in the files' order, and no report."""
    a, b = tmp_path / "a.yaml", tmp_path / "b.yaml"
    a.write_text("name: x\nfoo: 1\n")
    b.write_text("name: [\n")
    alone = [run("check", str(f)) for f in (a, b)]
    both = run("check", str(a), SHIN, str(b))
    assert [r.exit_code for r in (*alone, both)] == [2, 2, 2]
    assert alone[0].stderr and alone[1].stderr
    assert both.stderr == alone[0].stderr + alone[1].stderr
    assert both.stdout == ""


def test_schema_round_trip(tmp_path):
    """The exported schema describes the shipped files; model -> JSON -> model is lossless."""
    r = run("schema")
    assert r.exit_code == 0
    schema = json.loads(r.stdout)
    assert schema["additionalProperties"] is False
    assert set(schema["required"]) == {"name", "slider", "actuator_sets"}
    out = tmp_path / "schema.json"
    assert run("schema", "-o", str(out)).exit_code == 0
    assert json.loads(out.read_text()) == schema
    for path in sorted(DEVICES.glob("*.yaml")):
        spec = load_device(path)
        data = json.loads(spec.model_dump_json(exclude_none=True))
        assert DeviceSpec.model_validate(data) == spec
        _assert_conforms(data, schema, schema)


def test_schema_output_dir_missing_is_exit_2(tmp_path):
    r = run("schema", "-o", str(tmp_path / "no" / "s.json"))
    assert r.exit_code == 2 and "does not exist" in r.stderr


def _assert_conforms(data, sch, root):
    """Minimal JSON-schema walker (properties, required, additionalProperties, $ref,
    anyOf/oneOf, items, type string/number/integer) — enough for this schema."""
    if "$ref" in sch:
        name = sch["$ref"].split("/")[-1]
        return _assert_conforms(data, root["$defs"][name], root)
    for key in ("anyOf", "oneOf"):
        if key in sch:
            errors = []
            for sub in sch[key]:
                try:
                    _assert_conforms(data, sub, root)
                    return None
                except AssertionError as exc:
                    errors.append(exc)
            raise AssertionError(f"{data!r} matches no alternative: {errors}")
    t = sch.get("type")
    if t == "object" or "properties" in sch:
        assert isinstance(data, dict)
        props = sch.get("properties", {})
        assert set(sch.get("required", [])) <= set(data)
        if sch.get("additionalProperties") is False:
            assert set(data) <= set(props), set(data) - set(props)
        for k, v in data.items():
            if k in props:
                _assert_conforms(v, props[k], root)
    elif t == "array":
        assert isinstance(data, list)
        for item in data:
            _assert_conforms(item, sch.get("items", {}), root)
    elif t == "string":
        assert isinstance(data, str)
        if "enum" in sch:
            assert data in sch["enum"]
        if "const" in sch:
            assert data == sch["const"]
    elif t == "integer":
        assert isinstance(data, int)
    elif t == "number":
        assert isinstance(data, int | float)
    elif t == "null":
        assert data is None
    return None


def test_check_reports_orbit_speed_and_json(monkeypatch):
    """With a stand-in solver returning Δs = 0.25, the mode is the orbit's and the speed
    is Δs·u·cosθ·f_act (push_demo: u = 0.14 um, θ = 20.56°, f_act = 6 kHz)."""
    import math

    orbit = orbit_stand_in(0.25, message="ok", residual=1e-12, n_cycles=300, elapsed_s=0.01)
    monkeypatch.setattr(checker, "periodic_orbit", lambda p: orbit)
    monkeypatch.setattr("betvdesign.checks.checker._settling", lambda p, po, travel, horizon: None)
    path = str(DEVICES / "push_demo.yaml")
    v = 0.25 * 0.14e-6 * math.cos(math.radians(20.56)) * 6000.0  # [m/s] = 196.6 µm/s
    r = run("check", path)
    assert r.exit_code == 0, r.stdout
    assert "push as intended, 197 µm/s toward +x, 50 µm in 254 ms" in r.stdout
    top = _device(run("check", "--json", "-v", path).stdout)
    s = top["sets"][0]
    assert s["simulation"]["delta_s"] == 0.25 and s["simulation"]["mode"] == "push"
    out = top["sets"][0]
    assert out["delta_s"] == 0.25 and out["speed_m_s"] == pytest.approx(v, rel=1e-9)
    assert out["time_to_cross_s"] == pytest.approx(50e-6 / v, rel=1e-9)
    assert out["travel_direction"] == "+x"
    speed = next(x for x in out["rules"] if x["id"] == "speed")
    assert speed["value_unit"] == "m/s" and speed["value"] == pytest.approx(v)


# --- with the exact solver (betvdesign.dynamics) ------------------------------------------


@pytest.mark.slow
def test_shin2004_orbit_and_speed_from_the_exact_solver():
    """shin2004: the speed is Δs·u·cosθ·f_act with Δs from periodic_orbit (u = 0.11 um,
    θ = 45°, f_act = 1 kHz) unless settling takes a large share of the crossing, in
    which case it is the crossing mean from rest (checked against a plain transient)."""
    import math

    from betvdesign.dynamics import periodic_orbit, simulate
    from betvdesign.model.params import ModelParams

    r = run("check", "--json", "-v", SHIN)
    assert r.exit_code == 1  # the frequency-window error
    top = _device(r.stdout)
    s = top["sets"][0]
    p = ModelParams(**{k: s["params"][k] for k in ("varpi", "alpha", "beta", "kappa")})
    orbit = periodic_orbit(p)
    assert orbit.success
    assert s["simulation"]["delta_s"] == pytest.approx(orbit.delta_s, rel=1e-12)
    assert s["mode"] == ("push" if orbit.delta_s > 0 else "pull")
    length = 0.11e-6 * math.cos(math.pi / 4)
    n = s["settling"]["cycles_to_cross"]
    tr = simulate(p, n, log_events=False)  # second method: the transient from rest
    assert abs(tr.s) * length >= 40e-6 > abs(tr.section[-2, 4]) * length
    settle = next(x for x in s["rules"] if x["id"] == "settling")
    speed = s["speed_m_s"]  # its magnitude, toward travel_direction
    text = run("check", SHIN).stdout
    if settle["passed"]:
        assert s["basis"] == "periodic" and s["mode_source"].startswith("exact periodic")
        assert speed == pytest.approx(abs(orbit.delta_s) * length * 1000.0, rel=1e-9)
        assert "(crossing mean from rest)" not in text
    else:
        assert speed == pytest.approx(abs(tr.s) / n * length * 1000.0, rel=1e-9)
        # the text names the speed that is not the periodic orbit's
        assert top["sets"][0]["basis"] == "crossing" and "crossing" in s["mode_source"]
        assert "(crossing mean from rest)" in text
    assert top["sets"][1]["simulation"] == s["simulation"]  # the mirrored set reuses it


@pytest.mark.slow
def test_check_quotes_vertical_motion_consistently():
    """The window rule quotes dynamics.vertical_motion(ϖ) for the set's own ϖ."""
    from betvdesign.dynamics import vertical_motion

    s = _device(run("check", "--json", "-v", SHIN).stdout)["sets"][0]
    vm = vertical_motion(s["params"]["varpi"])
    assert s["vertical"]["regime"] == vm.regime
    win = next(x for x in s["rules"] if x["id"] == "frequency-window")
    assert f"exact vertical motion: {vm.regime}" in win["message"]


def test_markup_in_names_is_printed_literally(tmp_path, no_solver):
    f = tmp_path / "m.yaml"
    f.write_text(
        (DEVICES / "push_demo.yaml").read_text().replace("name: forward", "name: '[red]fwd'")
    )
    r = run("check", str(f))
    assert r.exit_code == 0 and "[red]fwd: push" in r.stdout
    assert "set [red]fwd" in run("check", "-v", str(f)).stdout


def test_summary_line_for_several_files(no_solver):
    r = run("check", *(str(p) for p in sorted(DEVICES.glob("*.yaml"))))
    assert r.exit_code == 1
    assert "summary: 5 pass, 1 fail (shin2004)" in r.stdout  # stand-in solver
