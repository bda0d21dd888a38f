"""Layouts and the head's springs: how fast, how accurate (issue 23).

    python benchmarks/bench_layout.py stiffness      # closed form vs FE: error and cost
    python benchmarks/bench_layout.py layout         # betv layout / check GDS vs YAML

``stiffness``: the closed form (:mod:`betvdesign.model.frame`) against the plane-stress
FE (:mod:`betvdesign.model.frame_fe`) on the shipped actuators and the 50 seeded random
ones (:func:`betvdesign.model.frame.random_geometries`): the FE at mesh levels 1 and 2
and their Richardson extrapolation (the reference), the error of k_v = K_nn, k_h = K_tt
and α = K_nn/K_tt of each method against the reference, and each method's cost; a
work-precision chart (cost against error) like the solver's goes to
``benchmarks/out/stiffness_wp.png`` and the numbers to ``benchmarks/out/stiffness.json``.

``layout``: wall time of ``betv layout`` per shipped device (in process, warm), and of
``betv check FILE.gds`` against ``betv check FILE.yaml`` (the same device, in process,
``--no-adequacy``; median of 3).
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "benchmarks" / "out"
sys.path.insert(0, str(ROOT))


def _shipped():
    from betvdesign.nondim.actuator import frame_geometry
    from betvdesign.spec.loader import load_device

    out, seen = [], set()
    for f in sorted((ROOT / "devices").glob("*.yaml")):
        spec = load_device(f)
        for s in spec.actuator_sets:
            if s.actuator.geometry is None:
                continue
            g = frame_geometry(spec, s)
            th = float(s.contact.impact_angle.to("rad").magnitude)
            key = (repr(g), th)
            if key not in seen:
                seen.add(key)
                out.append((f"{f.stem}/{s.name}", g, th))
    return out


def _springs(k, theta):
    from betvdesign.model.frame import slider_springs

    nn, tt, _ = slider_springs(k, theta)
    return float(nn), float(tt), float(nn) / float(tt)


def stiffness(n: int, levels: int) -> dict:
    from betvdesign.model.frame import frame_stiffness, random_geometries
    from betvdesign.model.frame_fe import frame_fe
    from betvdesign.output.numbers import json_float

    cases = _shipped() + [(f"random {i}", g, th) for i, (g, th) in enumerate(random_geometries(n))]
    rows = []
    for name, g, th in cases:
        t0 = time.perf_counter()
        reps = 200
        for _ in range(reps):
            k_cf = frame_stiffness(g)
        t_cf = (time.perf_counter() - t0) / reps
        fe = [frame_fe(g, level=lv) for lv in range(1, levels + 1)]
        a, b = fe[-2].stiffness, fe[-1].stiffness
        ref = [y + (y - x) / 3 for x, y in ((a.k_xx, b.k_xx), (a.k_yy, b.k_yy), (a.k_xy, b.k_xy))]
        from betvdesign.model.frame import FrameStiffness

        kref = FrameStiffness(*ref)
        r = _springs(kref, th)

        def err(k, th=th, r=r):
            s = _springs(k, th)
            return [abs(x / y - 1) for x, y in zip(s, r, strict=True)]

        row = {
            "case": name,
            "theta_deg": math.degrees(th),
            "L_over_w": float(min(g.length / g.hot_width, g.flexure_length / g.flexure_width)),
            "ref": {"k_v": r[0], "k_h": r[1], "alpha": r[2]},
            "closed_form": {"time_s": t_cf, "err": err(k_cf)},
        }
        for lv, res in enumerate(fe, 1):
            row[f"fe{lv}"] = {"time_s": res.elapsed_s, "dofs": res.dofs, "err": err(res.stiffness)}
        rows.append(row)
        print(
            f"{name:28s} θ={row['theta_deg']:5.1f}° L/w={row['L_over_w']:5.1f} "
            f"cf err k_v {row['closed_form']['err'][0]:.3%} k_h {row['closed_form']['err'][1]:.3%} "
            f"α {row['closed_form']['err'][2]:.3%} | fe1 {row['fe1']['err'][0]:.3%} "
            f"{row['fe1']['time_s']:.2f} s, fe{levels} {row[f'fe{levels}']['time_s']:.2f} s",
            flush=True,
        )
    summary = {}
    for meth in ["closed_form"] + [f"fe{lv}" for lv in range(1, levels + 1)]:
        errs = np.array([r[meth]["err"] for r in rows])
        times = np.array([r[meth]["time_s"] for r in rows])
        summary[meth] = {
            "max_err_k_v": float(errs[:, 0].max()),
            "max_err_k_h": float(errs[:, 1].max()),
            "max_err_alpha": float(errs[:, 2].max()),
            "median_err_k_v": float(np.median(errs[:, 0])),
            "median_time_s": float(np.median(times)),
            "max_time_s": float(times.max()),
        }
        shipped = [r for r in rows if not r["case"].startswith("random")]
        summary[meth]["shipped_max_err"] = json_float(
            max(max(r[meth]["err"]) for r in shipped) if shipped else None
        )
    return {"rows": rows, "summary": summary}


def chart(doc: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for meth, mark in (("closed_form", "o"), ("fe1", "s"), ("fe2", "^")):
        if meth not in doc["rows"][0]:
            continue
        t = [r[meth]["time_s"] for r in doc["rows"]]
        e = [max(max(r[meth]["err"][:2]), 1e-7) for r in doc["rows"]]
        ax.loglog(t, e, mark, alpha=0.6, label=meth.replace("_", " "))
    ax.set_xlabel("cost per actuator [s]")
    ax.set_ylabel("max relative error of k_v, k_h vs converged FE [-]")
    ax.set_title("Head springs: closed form against plane-stress FE")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def layout(reps: int = 3) -> dict:
    import tempfile

    from betvdesign.checks.checker import check_derivation
    from betvdesign.layout.extract import derive_gds
    from betvdesign.layout.write import write_layout
    from betvdesign.nondim.device import derive_file
    from betvdesign.spec.loader import load_device

    out = {}
    tmp = Path(tempfile.mkdtemp())
    for f in sorted((ROOT / "devices").glob("*.yaml")):
        spec = load_device(f)
        gds = tmp / f"{f.stem}.gds"
        t_lay = []
        for _ in range(reps):
            t0 = time.perf_counter()
            write_layout(spec, gds)
            t_lay.append(time.perf_counter() - t0)
        t_yaml, t_gds = [], []
        for _ in range(reps):
            t0 = time.perf_counter()
            check_derivation(derive_file(f), adequacy=False)
            t_yaml.append(time.perf_counter() - t0)
            t0 = time.perf_counter()
            d, ex = derive_gds(gds)
            check_derivation(d, adequacy=False, layout_rules=ex.rules)
            t_gds.append(time.perf_counter() - t0)
        out[f.stem] = {
            "layout_s": statistics.median(t_lay),
            "check_yaml_s": statistics.median(t_yaml),
            "check_gds_s": statistics.median(t_gds),
        }
        r = out[f.stem]
        print(
            f"{f.stem:14s} layout {r['layout_s']:.3f} s, check YAML {r['check_yaml_s']:.3f} s, "
            f"GDS {r['check_gds_s']:.3f} s (+{r['check_gds_s'] - r['check_yaml_s']:.3f} s)",
            flush=True,
        )
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("what", choices=["stiffness", "layout"])
    ap.add_argument("-n", type=int, default=50, help="random actuators (stiffness)")
    ap.add_argument("--levels", type=int, default=2, help="FE mesh levels (stiffness)")
    args = ap.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    if args.what == "stiffness":
        doc = stiffness(args.n, args.levels)
        (OUT / "stiffness.json").write_text(json.dumps(doc, indent=1, allow_nan=False))
        chart(doc, OUT / "stiffness_wp.png")
        print(json.dumps(doc["summary"], indent=1))
    else:
        doc = layout()
        (OUT / "layout.json").write_text(json.dumps(doc, indent=1, allow_nan=False))


if __name__ == "__main__":
    main()
