"""`betv check` and `betv schema` through typer's CliRunner (source: the shipped devices,
hand-computed shin2004 parameters, the issue's JSON contract)."""

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from betvdesign import checker
from betvdesign.cli import app
from betvdesign.loader import load_device
from betvdesign.spec import DeviceSpec

DEVICES = Path(__file__).resolve().parents[1] / "devices"
SHIN = str(DEVICES / "shin2004.yaml")
OWN = ["push_demo", "pull_demo", "bidir_demo"]


@pytest.fixture
def no_solver(monkeypatch):
    """Closed form only, whether or not the exact solver is installed."""
    monkeypatch.setattr(checker, "load_solver", lambda: None)


def run(*args):
    return CliRunner().invoke(app, list(args))


def test_shin2004_fails_the_window_and_shows_fit_mismatch(no_solver):
    r = run("check", SHIN)
    assert r.exit_code == 1, r.output
    out = r.stdout
    assert "FAIL" in out and "frequency-window" in out
    assert "below the window" in out
    assert "published-fit.varpi" in out and "disagree" in out
    r = run("check", "--verbose", SHIN)
    assert "cannot decide" in r.stdout  # β = 9.09 outside the λ fit range


def _device(stdout: str) -> dict:
    d = json.loads(stdout)
    assert (d["schema"], d["version"]) == ("betv-check", 1)
    assert len(d["devices"]) == 1
    return d["devices"][0]


def test_shin2004_json_contract(no_solver):
    """Version 1: SI floats under unit-named keys; hand-computed shin2004 parameters."""
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
    assert s["travel_range_m"] == pytest.approx(40e-6)
    assert s["lambda"]["predicts"] == "pull" and s["mode"] == "pull"
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
    assert win and not any(x["passed"] for x in win)
    assert "details" not in d
    full = _device(run("check", SHIN, "--json", "--verbose").stdout)["details"]
    fit = full["sets"][0]["published_fit"]
    assert {f["param"] for f in fit} == {"varpi", "alpha", "beta", "kappa"}
    assert next(f for f in full["sets"][0]["record"] if f["symbol"] == "f_act")["formula"] == (
        "2·f_drive"
    )


def test_json_conforms_to_its_published_schema():
    """Every device's --json output validates against `betv schema check` (a generic
    draft-2020-12 walk of the schema written by hand below, not pydantic itself)."""
    schema = json.loads(run("schema", "check").stdout)
    assert schema["properties"]["version"]["const"] == 1
    r = run("check", "--json", *(str(p) for p in sorted(DEVICES.glob("*.yaml"))))
    doc = json.loads(r.stdout)
    assert [x["device"] for x in doc["devices"]] == [
        "bidir_demo",
        "pull_demo",
        "push_demo",
        "shin2004",
    ]
    assert doc["verdict"] == "fail" and r.exit_code == 1
    _assert_conforms(doc, schema, schema)


@pytest.mark.parametrize("name", OWN)
def test_own_designs_pass(name):
    """Every rule passes; λ decides push_demo and bidir_demo (ϖ ≥ 0.9, beyond the measured
    trust margin), while pull_demo (ϖ = 0.8, β = 1.2, λ = 5.2) lies within the measured
    margin there (λ mispredicted at ϖ = 0.78, β = 1.2, λ = 4.4), so the fidelity ladder
    sends it to the periodic orbit."""
    r = run("check", str(DEVICES / f"{name}.yaml"), "--json", "--verbose")
    assert r.exit_code == 0, r.stdout
    d = _device(r.stdout)
    assert d["verdict"] == "pass" and d["failed"] == []
    full = d["details"]
    assert all(x["passed"] for x in full["rules"] if x["severity"] != "info"), full["rules"]
    for s, sfull in zip(d["sets"], full["sets"], strict=True):
        assert s["mode"] == s["intended_mode"] and s["passed"]
        assert s["lambda"]["margin"] >= 0.5  # "clear" designs
        rung = "periodic" if name == "pull_demo" else "lambda"
        assert sfull["fidelity"]["rung"] == sfull["fidelity"]["chosen"] == rung
        assert "measured" in sfull["fidelity"]["reason"]


def test_several_files_give_one_shape_and_worst_exit(no_solver):
    r = run("check", "--json", str(DEVICES / "push_demo.yaml"), SHIN)
    assert r.exit_code == 1
    d = json.loads(r.stdout)
    assert [x["device"] for x in d["devices"]] == ["push_demo", "shin2004"]
    assert d["verdict"] == "fail"
    r = run("check", "--json", *(str(DEVICES / f"{n}.yaml") for n in OWN))
    assert r.exit_code == 0 and len(json.loads(r.stdout)["devices"]) == 3


def test_tables_and_derivation(no_solver):
    r = run("check", "--verbose", str(DEVICES / "bidir_demo.yaml"))
    assert r.exit_code == 0
    assert "PASS" in r.stdout and "set east" in r.stdout and "set west" in r.stdout
    assert "derivation of set east" in r.stdout and "(f_v/f_h)²" in r.stdout


def test_simulate_without_solver_is_exit_2(no_solver):
    r = run("check", "--simulate", SHIN)
    assert r.exit_code == 2
    assert "exact solver" in r.stderr and "Traceback" not in r.output


def test_usage_errors_exit_2():
    assert run("check").exit_code == 2
    assert run("check", "--simulate", "--closed-form-only", SHIN).exit_code == 2
    assert run("check", "--lambda-margin", "-1", SHIN).exit_code == 2


def test_bad_file_exit_2_names_file_line_field(tmp_path, no_solver):
    bad = tmp_path / "bad.yaml"
    bad.write_text(Path(SHIN).read_text().replace("beam_width: 5 um", "beam_width: 5", 1))
    r = run("check", str(bad), SHIN)
    assert r.exit_code == 2
    assert f"{bad}:" in r.stderr and "slider.beam_width: missing unit" in r.stderr
    assert r.stdout == ""  # nothing half-reported
    missing = run("check", str(tmp_path / "nope.yaml"))
    assert missing.exit_code == 2 and "file not found" in missing.stderr


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


def test_simulated_check_reports_orbit_speed_and_json(monkeypatch):
    """With a solver (here a test double returning Δs = 0.25), --simulate takes the mode
    from the orbit and derives the speed Δs·u·cosθ·f_act (push_demo: u = 0.14 um,
    θ = 20.56°, f_act = 6 kHz)."""
    import math
    from types import SimpleNamespace

    orbit = SimpleNamespace(
        status="converged",
        success=True,
        message="ok",
        delta_s=0.25,
        mode="push",
        period_cycles=1,
        residual=1e-12,
        stable=True,
        n_cycles=300,
        elapsed_s=0.01,
    )
    monkeypatch.setattr(checker, "load_solver", lambda: lambda p: orbit)
    path = str(DEVICES / "push_demo.yaml")
    r = run("check", "--simulate", "--verbose", path)
    assert r.exit_code == 0, r.stdout
    assert "exact orbit (requested (--simulate))" in r.stdout
    assert "from simulation" in r.stdout
    v = 0.25 * 0.14e-6 * math.cos(math.radians(20.56)) * 6000.0  # [m/s] = 196.6 µm/s
    r = run("check", "--simulate", path)
    assert "197 µm/s toward +x, 50 µm in 254 ms" in r.stdout  # 50 µm / v = 0.2543 s
    d = _device(run("check", "--simulate", "--json", path).stdout)
    s = d["sets"][0]
    assert s["mode_source"] == "exact periodic orbit" and s["delta_s"] == 0.25
    assert s["speed_m_s"] == pytest.approx(v, rel=1e-12)
    assert s["time_to_cross_s"] == pytest.approx(50e-6 / v, rel=1e-12)
    assert s["travel_direction"] == "+x"
    speed = next(x for x in s["rules"] if x["id"] == "speed")
    assert speed["value_unit"] == "m/s" and speed["value"] == pytest.approx(v)


# --- with the exact solver (betvdesign.dynamics) ------------------------------------------


def test_auto_simulation_where_the_closed_form_cannot_decide():
    """shin2004: β = 9.09 lies outside the λ fit range, so `check` runs the exact solver by
    itself and says so; the speed is Δs·u·cosθ·f_act with Δs from periodic_orbit
    (u = 0.11 um, θ = 45°, f_act = 1 kHz)."""
    import math

    from betvdesign.dynamics import periodic_orbit
    from betvdesign.params import ModelParams

    r = run("check", "--json", "--verbose", SHIN)
    assert r.exit_code == 1  # still the frequency-window error
    dev = _device(r.stdout)
    d = dev["details"]
    assert any("ran the exact solver" in n and "beta" in n for n in d["notes"])
    s = d["sets"][0]
    assert s["simulated"] and s["mode_source"] == "simulation"
    assert "cannot decide" in s["simulated_because"]
    p = ModelParams(**{k: s["params"][k] for k in ("varpi", "alpha", "beta", "kappa")})
    orbit = periodic_orbit(p)
    assert orbit.success
    assert s["simulation"]["delta_s"] == pytest.approx(orbit.delta_s, rel=1e-12)
    v = orbit.delta_s * 0.11e-6 * math.cos(math.pi / 4) * 1000.0
    assert dev["sets"][0]["speed_m_s"] == pytest.approx(abs(v), rel=1e-12)
    assert dev["sets"][0]["mode"] == ("push" if orbit.delta_s > 0 else "pull")
    # the second, mirrored set reuses the orbit
    assert d["sets"][1]["simulation"] == s["simulation"]


def test_decided_design_is_not_simulated_unless_asked():
    """push_demo: λ = 0.33 inside the fit range -> closed form only; --simulate runs the
    solver, whose orbit agrees with λ (push) and with a plain transient from rest."""
    from betvdesign.dynamics import simulate
    from betvdesign.params import ModelParams

    path = str(DEVICES / "push_demo.yaml")
    d = _device(run("check", "--json", "-v", path).stdout)
    assert not d["details"]["sets"][0]["simulated"] and d["sets"][0]["speed_m_s"] is None
    r = run("check", "--json", "-v", "--simulate", path)
    assert r.exit_code == 0
    top = _device(r.stdout)
    s = top["details"]["sets"][0]
    assert s["mode_source"] == "simulation" and s["mode_predicted"] == "push"
    assert next(x for x in s["rules"] if x["id"] == "lambda-vs-simulation")["passed"]
    p = ModelParams(**{k: s["params"][k] for k in ("varpi", "alpha", "beta", "kappa")})
    transient = simulate(p, 400)  # second method: settle from rest, read the last cycle
    assert transient.success
    assert transient.delta_s[-1] == pytest.approx(s["simulation"]["delta_s"], rel=1e-6)
    assert top["sets"][0]["speed_m_s"] > 0


def test_check_quotes_vertical_motion_consistently():
    """The window rule quotes dynamics.vertical_motion(ϖ) for the set's own ϖ."""
    from betvdesign.dynamics import vertical_motion

    d = _device(run("check", "--json", "-v", SHIN).stdout)["details"]
    s = d["sets"][0]
    vm = vertical_motion(s["params"]["varpi"])
    assert s["vertical"]["regime"] == vm.regime
    win = next(x for x in s["rules"] if x["id"] == "frequency-window")
    assert f"exact vertical motion: {vm.regime}" in win["message"]
    d = _device(run("check", "--json", "-v", "--closed-form-only", SHIN).stdout)["details"]
    assert d["sets"][0]["vertical"] is None and d["sets"][0]["simulation"] is None


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
    assert "summary: 3 pass, 1 fail (shin2004)" in r.stdout
