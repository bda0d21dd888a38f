"""The layout check's width and space rules at scale (issue 33).

    python benchmarks/bench_drc.py make DIR     # DIR/head5k.gds and DIR/mega.gds
    python benchmarks/bench_drc.py scaling      # -> benchmarks/out/drc.json

``make`` writes two layouts of shin2004 (``betv layout``): ``head5k.gds`` with its head
discs drawn with 5 500 vertices (a legal layout: ``betv check`` passes its layout rules
on it), and ``mega.gds``, the shipped layout plus one unlabelled 10⁶-vertex disc on the
structural layer (beyond the vertex cap: ``betv check`` must refuse it, exit 2, naming
the file and the layer). Time them as whole processes::

    /usr/bin/time -v betv check --no-adequacy --no-advice DIR/head5k.gds
    /usr/bin/time -v betv check --no-adequacy --no-advice DIR/mega.gds

``scaling``: the width and space search alone (:func:`betvdesign.layout.drc.findings`'s
edge search, :func:`~betvdesign.layout.drc.edge_violations`) on a disc of n vertices with
a 1 µm slot (one space violation), n from 10³ to 10⁶, wall time and peak traced memory
(tracemalloc), and the number of candidate pairs per edge (linear growth: O(n log n)).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
import tracemalloc
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "benchmarks" / "out"
sys.path.insert(0, str(ROOT))


def make(out_dir: Path) -> None:
    import gdstk

    from betvdesign.layout import write
    from betvdesign.spec.loader import load_device

    out_dir.mkdir(parents=True, exist_ok=True)
    spec = load_device(ROOT / "devices" / "shin2004.yaml")
    keep = write.DISC_VERTICES
    try:
        write.DISC_VERTICES = 5500
        write.write_layout(spec, out_dir / "head5k.gds")
    finally:
        write.DISC_VERTICES = keep
    write.write_layout(spec, out_dir / "mega.gds")
    lib = gdstk.read_gds(str(out_dir / "mega.gds"))
    top = lib.top_level()[0]
    layer = spec.process.layers[spec.process.default_structural].gds.pair
    t = np.linspace(0, 2 * math.pi, 1_000_000, endpoint=False)
    disc = np.column_stack([2000 + 100 * np.cos(t), 100 * np.sin(t)])
    top.add(gdstk.Polygon(disc, layer=layer[0], datatype=layer[1]))
    lib.write_gds(str(out_dir / "mega.gds"), max_points=0)
    for f in ("head5k.gds", "mega.gds"):
        print(out_dir / f)


def scaling() -> dict:
    import gdstk

    from betvdesign.layout import drc

    rows = []
    for n in (1_000, 10_000, 100_000, 1_000_000):
        t = np.linspace(0, 2 * math.pi, n, endpoint=False)
        r = 18.0 * max(1.0, n / 20_000)  # edges no shorter than about 5 nm
        disc = gdstk.Polygon(np.column_stack([r * np.cos(t), r * np.sin(t)]))
        body = gdstk.boolean(disc, gdstk.rectangle((-r / 2, -0.5), (r / 2, 0.5)), "not")
        e = drc._edges(gdstk, body)
        tracemalloc.start()
        t0 = time.perf_counter()
        space = drc.edge_violations(gdstk, body, 2.0, "space", edges=e)
        width = drc.edge_violations(gdstk, body, 2.0, "width", edges=e)
        wall = time.perf_counter() - t0
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        i, _ = drc._candidates(e, 2.0)
        rows.append(
            {
                "vertices": n,
                "edges": len(e),
                "wall_s": round(wall, 4),
                "peak_mb": round(peak / 2**20, 1),
                "candidates_per_edge": round(len(i) / len(e), 2),
                "space_violations": len(space),
                "width_violations": len(width),
            }
        )
        print(rows[-1], flush=True)
    return {"command": "python benchmarks/bench_drc.py scaling", "rows": rows}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="what", required=True)
    m = sub.add_parser("make")
    m.add_argument("dir", type=Path)
    sub.add_parser("scaling")
    a = ap.parse_args()
    if a.what == "make":
        make(a.dir)
    else:
        OUT.mkdir(exist_ok=True)
        res = scaling()
        (OUT / "drc.json").write_text(json.dumps(res, indent=1) + "\n")


if __name__ == "__main__":
    main()
