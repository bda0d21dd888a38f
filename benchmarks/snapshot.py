"""Numbers of the exact solver, saved and compared (did a change move any number?).

    .venv/bin/python benchmarks/snapshot.py save DIR        # before a change
    .venv/bin/python benchmarks/snapshot.py save DIR2       # after it
    .venv/bin/python benchmarks/snapshot.py compare DIR DIR2

Designs: the 26 of bench_solver.py, every actuator set of the shipped devices and seven
special ones (exact free-flight and stick resonance, near resonance, multi-impact,
impulsive-only, period 2, near stick resonance). Saved per design: sections of 2000
cycles (no log), sections, event times and dense samples (997 times) of 40 cycles with
log and dense output; event kinds/phases, phase pieces, counters and the periodic orbit
(status, Δs, state, Floquet multipliers, residual, cycles, Newton iterations).
``compare`` prints every array that is not bit-identical with its largest relative
difference (|a − b| / max(1, |a|)) and every other mismatch.
"""

from __future__ import annotations

import math
import pickle
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_solver import NAMED, window_sets

from betvdesign.dynamics import periodic_orbit, simulate
from betvdesign.model.params import ModelParams

ROOT = Path(__file__).resolve().parents[1]
SPECIAL = {
    "res-free": ModelParams(1.0, 1.0, 1.0, 0.4),
    "res-stick": ModelParams(1.0, 0.5, 1.0, 0.4),
    "multihit": ModelParams(0.3, 0.5, 1.0, 0.4),
    "near-res": ModelParams(1.05, 0.95, 1.0, 0.4),
    "impulsive": ModelParams(2.3, 0.5, 1.0, 0.3),
    "near-stick-res": ModelParams(0.7, 1.0, 1.0, 0.3),
    "period2": ModelParams(0.2, 0.3, 2.0, 0.2),
}


def designs() -> dict[str, ModelParams]:
    from betvdesign.nondim.device import derive_file

    out = {**NAMED, **window_sets()}
    for f in sorted((ROOT / "devices").glob("*.yaml")):
        for i, s in enumerate(derive_file(f).sets):
            # the paper's model only: a snapshot compares it across a change, and designs
            # with damping/restitution (devices/damped_demo.yaml) have no counterpart in
            # code before the damped kernel ("dynamics: damping and restitution ...")
            if s.params.ideal:
                out[f"{f.stem}-{i}"] = s.params
    return out | SPECIAL


def save(out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    meta = {}
    for name, p in designs().items():
        tr = simulate(p, 2000, log_events=False)
        np.save(out / f"{name}_sec2000.npy", tr.section)
        tr2 = simulate(p, 40, log_events=True, dense=True)
        T = 2 * math.pi / p.varpi
        taus = np.linspace(0, 39.999 * T, 997)
        np.save(out / f"{name}_sec40.npy", tr2.section)
        np.save(out / f"{name}_sample.npy", tr2.sample(taus))
        np.save(out / f"{name}_events.npy", np.array([e.tau for e in tr2.events]))
        po = periodic_orbit(p)
        meta[name] = dict(
            status=tr.status,
            msg=tr.message,
            nev=tr.n_events,
            nre=tr.n_root_evals,
            nev2=tr2.n_events,
            kinds=[tuple(e)[1:] for e in tr2.events],
            phases=tr2.phases,
            po_status=po.status,
            po_ds=po.delta_s,
            po_state=po.state,
            po_floq=po.floquet,
            po_res=po.residual,
            po_ncyc=po.n_cycles,
            po_newton=po.n_newton,
        )
    (out / "meta.pkl").write_bytes(pickle.dumps(meta))
    print(f"{len(meta)} designs saved in {out}")


def _same(a: object, b: object) -> bool:
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.array_equal(np.asarray(a), np.asarray(b), equal_nan=True)
    return a == b or (a != a and b != b)


def compare(a: Path, b: Path) -> int:
    worst: dict[str, float] = {}
    bad = 0
    for f in sorted(a.glob("*.npy")):
        x, y = np.load(f), np.load(b / f.name)
        if x.shape != y.shape:
            print("shape differs", f.name, x.shape, y.shape)
            bad += 1
        elif not np.array_equal(x, y, equal_nan=True):
            d = float(np.nanmax(np.abs(x - y) / np.maximum(1.0, np.abs(x))))
            kind = f.stem.rsplit("_", 1)[-1]
            worst[kind] = max(worst.get(kind, 0.0), d)
            print("differs", f.name, f"{d:.3g}")
    ma, mb = (pickle.loads((d / "meta.pkl").read_bytes()) for d in (a, b))
    for name, row in ma.items():
        for key, va in row.items():
            if key in mb[name] and not _same(va, mb[name][key]):
                print("differs", name, key, str(va)[:100], "|", str(mb[name][key])[:100])
                bad += 1
    n = len(list(a.glob("*.npy")))
    print(
        f"{n} arrays and {len(ma)} designs compared: largest relative difference per kind "
        f"{worst or 'none (bit-identical)'}; other mismatches: {bad}"
    )
    return 1 if bad or worst else 0


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "save":
        save(Path(sys.argv[2]))
    elif len(sys.argv) == 4 and sys.argv[1] == "compare":
        sys.exit(compare(Path(sys.argv[2]), Path(sys.argv[3])))
    else:
        sys.exit(__doc__)
