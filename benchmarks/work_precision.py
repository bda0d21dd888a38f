"""Work-precision study and fidelity-ladder measurements (regenerates the README chart).

    python benchmarks/work_precision.py                 # full study + failure map along ϖ
                                                        # -> docs/img/, reports/bench/
    python benchmarks/work_precision.py --quick         # a subset, seconds to a minute
    python benchmarks/work_precision.py --ladder        # λ disagreement, rigid envelope, rung
                                                        # costs -> betvdesign/data/*.json

Prints the cost ratios (exact at ≤ 1e-10 vs the cheapest alternative reaching 1e-6) and
the ladder figures. CPU times depend on the machine and its load; errors do not.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def work_precision(level: str, out: Path, img: Path | None) -> None:
    from betvdesign.bench import workprecision as wp
    from betvdesign.bench.chart import write_outputs

    rows = wp.run(level, progress=lambda m: print(f"  {m}", file=sys.stderr, flush=True))
    for p in write_outputs(rows, out):
        print(f"wrote {p}")
    if img is not None:
        for p in write_outputs(rows, img):
            print(f"wrote {p}")
    from betvdesign.bench.failuremap import default_varpis, scan, write_failure_map

    fm = scan(default_varpis(30 if level == "full" else 10))
    for d in [out] + ([img] if img is not None else []):
        for p in write_failure_map(fm, d):
            print(f"wrote {p}")
    print("\nexact vs the cheapest alternative reaching 1e-6 (CPU seconds):")
    for s in wp.summarise(rows):
        alt = s["cheapest_alternative"] or "none reaches 1e-6"
        ratio = f"×{s['ratio']:.0f}" if s["ratio"] else "—"
        ex_err = "—" if s["exact_error"] is None else f"{s['exact_error']:.1e}"
        ex_s = "—" if s["exact_seconds"] is None else f"{s['exact_seconds']:.2e}"
        alt_s = "" if s["alternative_seconds"] is None else f" {s['alternative_seconds']:.2e} s"
        print(
            f"  {s['design']:14s} {s['metric']:8s} exact err {ex_err} in {ex_s} s; "
            f"{alt}{alt_s}  {ratio}"
        )


def ladder(out_path: Path, reuse_map: bool) -> None:
    from betvdesign.bench.ladder import measure, write_measured

    previous = None
    if reuse_map:
        from betvdesign.checks.fidelity import measured

        previous = {k: v for k, v in measured()["lambda"].items() if k != "held_out"}
    m = measure(reuse_map=previous)
    write_measured(m, out_path)
    lam = m["lambda"]
    print(f"wrote {out_path}")
    print(
        f"λ rule vs periodic orbit on {lam['points']} map points ({lam['converged']} converged): "
        f"{lam['mispredicted']} mispredicted ({100 * lam['rate']:.2f} %)"
    )
    print("  by |λ−1| band:", json.dumps(lam["bands"]))
    val = lam["held_out"]
    print(
        f"λ rule on {val['points']} held-out random designs ({val['converged']} with a moving "
        f"orbit, {val['stalled']} stalled): {val['mispredicted']} mispredicted "
        f"({100 * val['rate']:.2f} %, 95 % upper bound {100 * val['upper_95']:.2f} %)"
    )
    for band in val["bands"]:
        print("   ", band)
    for w in val["mispredictions"][:20]:
        print("  ", w)
    print(f"rigid limit: error ≈ {m['rigid']['coef']:.3g}·α^{m['rigid']['power']:.2f}")
    print(f"rigid limit mode disagreement on the map: {100 * lam['rigid_mode_disagreement']:.1f} %")
    print("rung cost (median CPU s):", json.dumps(m["costs_cpu_s"]))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="quick subset of the study")
    ap.add_argument("--ladder", action="store_true", help="measure the fidelity ladder instead")
    ap.add_argument(
        "--reuse-map", action="store_true", help="with --ladder: keep the stored push/pull map"
    )
    ap.add_argument("-o", "--output", type=Path, default=ROOT / "reports" / "bench")
    args = ap.parse_args()
    if args.ladder:
        ladder(ROOT / "betvdesign" / "data" / "fidelity_measured.json", args.reuse_map)
        return
    level = "quick" if args.quick else "full"
    work_precision(level, args.output, None if args.quick else ROOT / "docs" / "img")


if __name__ == "__main__":
    main()
