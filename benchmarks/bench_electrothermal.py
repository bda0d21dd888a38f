"""The electrothermal stroke: closed form against FE, and against measurements (issue 31).

    python benchmarks/bench_electrothermal.py fe           # closed form vs plane FE
    python benchmarks/bench_electrothermal.py validation   # vs published measurements

``fe``: the 1-D closed form (:mod:`betvdesign.model.electrothermal`) against the plane FE
(:mod:`betvdesign.model.electrothermal_fe`) on the shipped drawn actuators (their
process's data) and ``-n`` seeded random ones (:func:`betvdesign.model.frame.random_geometries`,
PolyMUMPs Poly1's material), each at the voltage where the closed form's peak is
``--t-peak`` K. Reference: the FE at mesh levels 1 and 2 Richardson-extrapolated (p = 2)
for current, power, stroke and peak temperature; the FE's first thermal eigenvalue and
its transient's 63.2 % rise time of the stroke (level 1, backward Euler) for the
dynamics. Prints the table, writes ``benchmarks/out/electrothermal.json`` and the
work-precision chart ``benchmarks/out/electrothermal_wp.png``.

``validation``: the closed form, untuned, against published measured hot/cold-arm
polysilicon actuators (the table in benchmarks/README.md).
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "benchmarks" / "out"
sys.path.insert(0, str(ROOT))

KEYS = ("current", "power", "u_static", "t_rise_k")


def _shipped():
    from betvdesign.nondim.actuator import actuator_inputs, frame_geometry
    from betvdesign.spec.loader import load_device

    out, seen = [], set()
    for f in sorted((ROOT / "devices").glob("*.yaml")):
        spec = load_device(f)
        for s in spec.actuator_sets:
            if s.actuator.geometry is None or spec.process is None:
                continue
            g = frame_geometry(spec, s)
            mat = spec.process.thermal_material(actuator_inputs(spec, s).layer)
            key = repr(g)
            if key not in seen:
                seen.add(key)
                out.append((f"{f.stem}/{s.name}", g, mat))
    return out


def _voltage_for(g, mat, t_peak: float) -> float:
    """The voltage at which the closed form's peak temperature is ``t_peak`` [K]."""
    from betvdesign.model.electrothermal import electrothermal

    lo, hi = 0.0, 1.0
    while electrothermal(g, mat, hi).t_max < t_peak:
        lo, hi = hi, 2 * hi
    for _ in range(40):
        mid = (lo + hi) / 2
        if electrothermal(g, mat, mid).t_max < t_peak:
            lo = mid
        else:
            hi = mid
    return (lo + hi) / 2


def _values(r, T0: float) -> dict:
    return {
        "current": r.current,
        "power": r.power,
        "u_static": r.u_static,
        "t_rise_k": r.t_max - T0,
    }


def fe(n: int, t_peak: float, steps: int) -> dict:
    from betvdesign.model.electrothermal import electrothermal
    from betvdesign.model.electrothermal_fe import converged
    from betvdesign.model.frame import random_geometries
    from betvdesign.spec.loader import load_process
    from betvdesign.spec.process import shipped_process_path

    poly = load_process(shipped_process_path("polymumps")).thermal_material()
    cases = _shipped() + [
        (f"random {i}", g, dataclasses.replace(poly))
        for i, (g, _) in enumerate(random_geometries(n))
    ]
    rows = []
    for name, g, mat in cases:
        T0 = mat.substrate_temperature
        volts = _voltage_for(g, mat, t_peak)
        reps = 20
        t0 = time.perf_counter()
        for _ in range(reps):
            cf = electrothermal(g, mat, volts)
        t_cf = (time.perf_counter() - t0) / reps
        conv, f1, f2 = converged(g, mat, volts, transient=True, steps=steps)
        v1, v2 = _values(f1, T0), _values(f2, T0)
        ref = {**conv, "t_rise_k": conv["t_max"] - T0}

        def err(v, ref=ref):
            return {k: abs(v[k] / ref[k] - 1) for k in KEYS}

        row = {
            "case": name,
            "voltage": volts,
            "ref": ref,
            "closed_form": {"time_s": t_cf, "err": err(_values(cf, T0))},
            "fe1": {
                "time_s": f1.elapsed_s,
                "dofs": f1.dofs,
                "err": err(v1),
                "iterations": f1.iterations,
            },
            "fe2": {"time_s": f2.elapsed_s, "dofs": f2.dofs, "err": err(v2)},
            "tau": {
                "closed_form": cf.tau_thermal,
                "fe": f1.tau_first,
                "err": abs(cf.tau_thermal / f1.tau_first - 1),
            },
            "t_rise": {
                "closed_form": cf.t_rise,
                "fe": f1.t_rise,
                "err": abs(cf.t_rise / f1.t_rise - 1),
            },
            "f_cutoff_hz": cf.f_cutoff,
            "t_max_segment": cf.t_max_segment,
        }
        rows.append(row)
        e = row["closed_form"]["err"]
        print(
            f"{name:26s} {volts:6.2f} V  P {ref['power'] * 1e3:6.2f} mW  "
            f"u {ref['u_static'] * 1e6:6.2f} um | cf err I {e['current']:.2%} "
            f"P {e['power']:.2%} u {e['u_static']:.2%} "
            f"ΔT {e['t_rise_k']:.2%} τ1 {row['tau']['err']:.2%} t63 {row['t_rise']['err']:.2%}"
            f" | fe1 {f1.elapsed_s:.1f} s fe2 {f2.elapsed_s:.1f} s",
            flush=True,
        )
    summary = {}
    for meth in ("closed_form", "fe1", "fe2"):
        errs = {k: np.array([r[meth]["err"][k] for r in rows]) for k in KEYS}
        times = np.array([r[meth]["time_s"] for r in rows])
        summary[meth] = {
            **{f"max_err_{k}": float(v.max()) for k, v in errs.items()},
            **{f"median_err_{k}": float(np.median(v)) for k, v in errs.items()},
            "median_time_s": float(np.median(times)),
            "max_time_s": float(times.max()),
        }
    for key in ("tau", "t_rise"):
        errs = np.array([r[key]["err"] for r in rows])
        summary[key] = {"max_err": float(errs.max()), "median_err": float(np.median(errs))}
    return {"t_peak": t_peak, "rows": rows, "summary": summary}


def chart(doc: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for meth, mark in (("closed_form", "o"), ("fe1", "s"), ("fe2", "^")):
        t = [r[meth]["time_s"] for r in doc["rows"]]
        e = [max(max(r[meth]["err"].values()), 1e-7) for r in doc["rows"]]
        ax.loglog(t, e, mark, alpha=0.6, label=meth.replace("_", " "))
    ax.set_xlabel("cost per actuator [s]")
    ax.set_ylabel("max relative error of I, P, u, ΔT_max vs converged FE [-]")
    ax.set_title("Electrothermal stroke: closed form against plane FE")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)


#: Published measured hot/cold-arm polysilicon actuators (benchmarks/README.md).
VALIDATION = [
    {
        "name": "Huang & Lee 1999",
        "source": (
            "Q.-A. Huang and N. K. S. Lee, 'Analysis and design of polysilicon thermal "
            "flexure actuator', J. Micromech. Microeng. 9 (1999) 64-70, "
            "doi:10.1088/0960-1317/9/1/308, abstract"
        ),
        # stated in the abstract: hot arm 240 um long, 2 um thick, 3 um wide; cold arm
        # 180 um long, 12 um wide; 12 um tip deflection at 5 V
        "geometry_um": {
            "length": 240,
            "hot_width": 3,
            "cold_width": 12,
            "flexure_length": 60,
            "thickness": 2,
        },
        # NOT stated in the abstract (assumed here): flexure as wide as the hot arm, the
        # 2 um minimum gap of a polysilicon surface process, a 10 um tip connector, no head
        "assumed_um": {"flexure_width": 3, "gap": 2, "tip_length": 10},
        "voltage": 5.0,
        "measured_um": 12.0,
    },
]


def validation() -> dict:
    from betvdesign.model.electrothermal import electrothermal
    from betvdesign.model.frame import FrameGeometry
    from betvdesign.spec.loader import load_process
    from betvdesign.spec.process import shipped_process_path

    proc = load_process(shipped_process_path("polymumps"))
    mat = proc.thermal_material()
    rows = []
    for case in VALIDATION:
        gm = {**case["geometry_um"], **case["assumed_um"]}
        um = 1e-6
        height = (gm["hot_width"] + gm["gap"] + gm["cold_width"]) * um
        g = FrameGeometry(
            length=gm["length"] * um,
            hot_width=gm["hot_width"] * um,
            cold_width=gm["cold_width"] * um,
            flexure_length=gm["flexure_length"] * um,
            flexure_width=gm["flexure_width"] * um,
            gap=gm["gap"] * um,
            tip_length=gm["tip_length"] * um,
            thickness=gm["thickness"] * um,
            youngs_modulus=169e9,
            head_x=0.0,
            head_y=height / 2,
            head_shape="box",
        )
        r = electrothermal(g, mat, case["voltage"])
        sens = {}
        for key, factor in (("flexure_width", 2 / 3), ("gap", 1.5)):
            g2 = dataclasses.replace(g, **{key: getattr(g, key) * factor})
            sens[f"{key} x{factor:.3g}"] = electrothermal(g2, mat, case["voltage"]).u_static
        row = {
            "name": case["name"],
            "voltage": case["voltage"],
            "measured_um": case["measured_um"],
            "model_um": r.u_static * 1e6,
            "power_mw": r.power * 1e3,
            "t_max_k": r.t_max,
            "resistance_ohm": r.resistance,
            "f_cutoff_hz": r.f_cutoff,
            "sensitivity_um": {k: v * 1e6 for k, v in sens.items()},
        }
        rows.append(row)
        print(
            f"{case['name']}: {case['voltage']} V  measured {case['measured_um']} um, model "
            f"{row['model_um']:.2f} um ({row['model_um'] / case['measured_um'] - 1:+.0%}), "
            f"P {row['power_mw']:.1f} mW, T_max {row['t_max_k']:.0f} K, R {r.resistance:.0f} ohm, "
            f"f_c {r.f_cutoff:.0f} Hz; "
            + ", ".join(f"{k}: {v:.2f} um" for k, v in row["sensitivity_um"].items()),
            flush=True,
        )
    return {"rows": rows}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("what", choices=["fe", "validation"])
    ap.add_argument("-n", type=int, default=30, help="random actuators (fe)")
    ap.add_argument("--t-peak", type=float, default=700.0, help="closed form's peak [K] (fe)")
    ap.add_argument("--steps", type=int, default=800, help="transient steps (fe)")
    args = ap.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    if args.what == "fe":
        doc = fe(args.n, args.t_peak, args.steps)
        (OUT / "electrothermal.json").write_text(json.dumps(doc, indent=1, allow_nan=False))
        chart(doc, OUT / "electrothermal_wp.png")
        print(json.dumps(doc["summary"], indent=1))
    else:
        doc = validation()
        (OUT / "electrothermal_validation.json").write_text(json.dumps(doc, indent=1))
    assert all(math.isfinite(r["ref"]["power"]) for r in doc.get("rows", []) if "ref" in r)


if __name__ == "__main__":
    main()
