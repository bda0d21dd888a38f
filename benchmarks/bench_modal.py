"""The drawn actuator's first in-plane mode: Rayleigh–Ritz closed form against modal FE
(issue 30).

    python benchmarks/bench_modal.py            # in-plane: the table of benchmarks/README.md
    python benchmarks/bench_modal.py oop 10     # out of plane: shipped + 10 seeded, 3-D FE

The closed form (:func:`betvdesign.model.frame.rayleigh_matrices`,
:func:`~betvdesign.model.frame.first_mode`: the frame's flexibility-method compliance and
the Rayleigh–Ritz mass of its static shapes, arms + tip + head) against the plane-stress
modal FE of the same drawn polygons (:func:`betvdesign.model.frame_fe.frame_modes`, Q2,
consistent mass, the head's cells carrying the head's mass) at mesh levels 1 and 2 and
their Richardson extrapolation (p = 2, the reference), on the shipped actuators (each
with its head) and the 50 seeded random ones of
:func:`betvdesign.model.frame.random_geometries` (film density 2330 kg/m³; heads: the
drawn disc or box of that film, so the head's mass is its area × t × ρ). Writes
``benchmarks/out/modal.json`` and prints the Markdown table of benchmarks/README.md.

``oop N``: the first out-of-plane mode of
:func:`betvdesign.model.frame.out_of_plane_first_mode` against the 3-D solid FE
(:func:`betvdesign.model.frame_fe.frame_modes_3d`, level 1: one 27-node hexahedron through
the film) on the shipped actuators and the first N seeded ones; the FE's first mode with
more than half its kinetic energy out of the plane is the reference. Writes
``benchmarks/out/modal_oop.json``.
"""

from __future__ import annotations

import json
import math
import statistics
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "benchmarks" / "out"
sys.path.insert(0, str(ROOT))

RHO = 2330.0


def _cases() -> list[tuple[str, object, float, float]]:
    """(name, geometry, head mass [kg], ν) of every actuator benchmarked."""
    from betvdesign.model.frame import random_geometries
    from betvdesign.nondim.actuator import actuator_inputs, frame_geometry
    from betvdesign.nondim.device import derive
    from betvdesign.spec.loader import load_device

    out, seen = [], set()
    for f in sorted((ROOT / "devices").glob("*.yaml")):
        spec = load_device(f)
        d = derive(spec)
        for s, sd in zip(spec.actuator_sets, d.sets, strict=True):
            if s.actuator.geometry is None:
                continue
            g = frame_geometry(spec, s)
            m = sd.step("m").value.to("kg").magnitude
            key = (repr(g), m)
            if key not in seen:
                seen.add(key)
                out.append((f"{f.stem}/{s.name}", g, float(m), actuator_inputs(spec, s).poisson))
    for i, (g, _) in enumerate(random_geometries(50)):
        hy = g.head_x if g.head_y is None else g.head_y
        area = math.pi * g.head_x**2 if g.head_shape == "disc" else 4 * g.head_x * hy
        out.append((f"random{i}", g, float(area * g.thickness * RHO), 0.22))
    return out


def main() -> None:
    from betvdesign.model.frame import first_mode, rayleigh_matrices
    from betvdesign.model.frame_fe import frame_modes

    rows = []
    for name, g, m, nu in _cases():
        C, M = rayleigh_matrices(g, RHO, m)
        f_cf = float(first_mode(C, M)[0])
        a = frame_modes(g, density=RHO, head_mass=m, poisson_ratio=nu, level=1)
        b = frame_modes(g, density=RHO, head_mass=m, poisson_ratio=nu, level=2)
        fa, fb = a.frequencies_hz[0], b.frequencies_hz[0]
        ref = fb + (fb - fa) / 3
        rows.append({"name": name, "f_closed_hz": f_cf, "f_fe1_hz": fa, "f_fe2_hz": fb,
                     "f_ref_hz": ref, "err_closed": f_cf / ref - 1, "err_fe1": fa / ref - 1,
                     "t_fe1_s": a.elapsed_s, "t_fe2_s": b.elapsed_s})  # fmt: skip
        print(f"{name}: closed {f_cf:.6g} Hz, FE {fa:.6g} / {fb:.6g} Hz, "
              f"err {f_cf / ref - 1:+.3%}", flush=True)  # fmt: skip
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "modal.json").write_text(json.dumps(rows, indent=1) + "\n")
    errs = [abs(r["err_closed"]) for r in rows]
    shipped = [r for r in rows if not r["name"].startswith("random")]
    print()
    print("| actuator | f_1 closed form | f_1 FE level 1 | f_1 FE level 2 | FE extrapolated | "
          "closed form error |")  # fmt: skip
    print("|---|---|---|---|---|---|")
    for r in shipped:
        print(f"| {r['name']} | {r['f_closed_hz'] / 1e3:.2f} kHz | {r['f_fe1_hz'] / 1e3:.2f} kHz "
              f"| {r['f_fe2_hz'] / 1e3:.2f} kHz | {r['f_ref_hz'] / 1e3:.2f} kHz | "
              f"{r['err_closed']:+.2%} |")  # fmt: skip
    rnd = [r for r in rows if r["name"].startswith("random")]
    fr = sorted(r["f_ref_hz"] for r in rnd)
    print(
        f"| 50 seeded random ({fr[0] / 1e3:.1f}–{fr[-1] / 1e3:.1f} kHz) | | | | | max "
        f"{max(abs(r['err_closed']) for r in rnd):.2%}, median "
        f"{statistics.median(abs(r['err_closed']) for r in rnd):.2%} |"
    )
    print()
    print(
        f"all {len(rows)}: max |error| {max(errs):.2%}, median {statistics.median(errs):.2%}; "
        f"FE level 1 against the extrapolation: max "
        f"{max(abs(r['err_fe1']) for r in rows):.2%}; FE cost median "
        f"{statistics.median(r['t_fe1_s'] for r in rows):.2f} s (level 1), "
        f"{statistics.median(r['t_fe2_s'] for r in rows):.2f} s (level 2)"
    )


def oop(n: int) -> None:
    from betvdesign.model.frame import out_of_plane_first_mode
    from betvdesign.model.frame_fe import frame_modes_3d

    cases = _cases()
    cases = [c for c in cases if not c[0].startswith("random")] + [
        c for c in cases if c[0].startswith("random")
    ][:n]
    rows = []
    for name, g, m, nu in cases:
        f_cf = float(out_of_plane_first_mode(g, RHO, m, nu))
        modes, shares = frame_modes_3d(g, density=RHO, head_mass=m, poisson_ratio=nu, count=3)
        f_fe = next(f for f, z in zip(modes.frequencies_hz, shares, strict=True) if z > 0.5)
        rows.append({"name": name, "f_closed_hz": f_cf, "f_fe_hz": f_fe,
                     "err_closed": f_cf / f_fe - 1, "t_fe_s": modes.elapsed_s,
                     "dofs": modes.dofs})  # fmt: skip
        print(f"| {name} | {f_cf / 1e3:.2f} kHz | {f_fe / 1e3:.2f} kHz | {f_cf / f_fe - 1:+.2%} | "
              f"{modes.elapsed_s:.0f} s |", flush=True)  # fmt: skip
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "modal_oop.json").write_text(json.dumps(rows, indent=1) + "\n")
    errs = [abs(r["err_closed"]) for r in rows]
    print(f"all {len(rows)}: max |error| {max(errs):.2%}, median {statistics.median(errs):.2%}")


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "oop":
        oop(int(sys.argv[2]) if len(sys.argv) > 2 else 10)
    else:
        main()
