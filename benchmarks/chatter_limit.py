"""Where the full model cannot be run at small α: the fidelity ladder's chatter limit.

    .venv/bin/python benchmarks/chatter_limit.py            # a few minutes

At small α the head's tangential oscillation (period 2π√α, normalised) is so fast that
the stick/slip switching in one contact exceeds the exact solver's budget of
``betvdesign.dynamics.contact.MAX_SWITCHES`` switches per contact, and the solver stops
with "the stick/slip switching chatters" from the first contact on. A contact lasts at
most π/ϖ and the switches come about every half fast period π√α, so the number of
switches goes as 1/(ϖ√α): the limit is one of q = α·ϖ² = (ω/ω_h)² (actuation over
tangential angular frequency, squared), whatever β and κ.

The periodic orbit from rest (``periodic_orbit``, the ladder's periodic rung) is run on
a grid of ideal designs in the window (ϖ × β × κ) at values of q around the limit, and
the largest q at which it chatters and the smallest q from which on it never did are
printed. Where it does answer, the rigid limit (``rigid_periodic``, what the ladder uses
instead below the limit) is compared with it: its mode, and its relative Δs error
against the stored error estimate ``fidelity.rigid_error_estimate``.
``betvdesign.checks.fidelity.CHATTER_Q`` states the result. Writes
benchmarks/out/chatter_limit.json.
"""

from __future__ import annotations

import itertools
import json
import math
import time
from pathlib import Path

from betvdesign.checks.fidelity import rigid_error_estimate
from betvdesign.dynamics import periodic_orbit
from betvdesign.dynamics.rigid import rigid_periodic
from betvdesign.model.params import ModelParams

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "benchmarks" / "out"

VARPIS = (0.5, 0.55, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.25, 1.4, 1.6, 1.8, 1.9)
BETAS = (0.05, 0.1, 0.3, 0.9, 1.5, 3.0, 10.0, 30.0, 100.0)
KAPPAS = (0.02, 0.1, 0.2, 0.4, 1.0)
#: q = α·ϖ² [-], 3e-7 to 4.2e-6 in steps of 10^(1/20) (≈ 12 %)
QS = tuple(3e-7 * 10 ** (i / 20) for i in range(24))


def main() -> None:
    rows = []
    t0 = time.perf_counter()
    for w, b, k, q in itertools.product(VARPIS, BETAS, KAPPAS, QS):
        p = ModelParams(w, q / w**2, b, k)
        po = periodic_orbit(p)
        row = {"varpi": w, "beta": b, "kappa": k, "q": q, "status": po.status,
               "chatter": "chatters" in po.message}  # fmt: skip
        if po.success:
            r = rigid_periodic(p)
            err = abs(r.delta_s - po.delta_s) / abs(po.delta_s)
            row.update(mode=po.mode, rigid_mode=r.mode, rigid_error=err,
                       estimate=rigid_error_estimate(p.alpha))  # fmt: skip
        rows.append(row)
    sec = time.perf_counter() - t0
    chat = [r["q"] for r in rows if r["chatter"]]
    q_max = max(chat)
    clean_from = min(q for q in QS if q > q_max)
    below = [r for r in rows if r["q"] <= q_max]
    other = sorted({r["status"] for r in rows if not r["chatter"] and r["status"] != "success"})
    print(f"{len(rows)} periodic orbits ({len(VARPIS)} ϖ × {len(BETAS)} β × {len(KAPPAS)} κ × "
          f"{len(QS)} q) in {sec:.0f} s")  # fmt: skip
    print(f"chatter at q = α·ϖ² ≤ {q_max:.3g} ({len(chat)} runs); none at q ≥ {clean_from:.3g}")
    for q in QS:
        at = [r for r in rows if r["q"] == q]
        n = sum(r["chatter"] for r in at)
        print(f"  q = {q:.3g}: chatter in {n} of {len(at)} ({100 * n / len(at):.0f} %)")
    print(
        f"at q ≤ {q_max:.3g}: {sum(r['status'] == 'success' for r in below)} of {len(below)} "
        f"succeeded; other failures anywhere: {other or 'none'}"
    )
    ok = [r for r in rows if "rigid_error" in r]
    worst = max(ok, key=lambda r: r["rigid_error"])
    over = max(ok, key=lambda r: r["rigid_error"] / r["estimate"])
    print(
        f"rigid limit where the periodic orbit answered ({len(ok)} designs): mode differs in "
        f"{sum(r['mode'] != r['rigid_mode'] for r in ok)}; relative Δs error up to "
        f"{worst['rigid_error']:.3g} (ϖ = {worst['varpi']}, β = {worst['beta']}, κ = "
        f"{worst['kappa']}, q = {worst['q']:.3g}); up to "
        f"{over['rigid_error'] / over['estimate']:.3g}× the stored estimate (ϖ = "
        f"{over['varpi']}, β = {over['beta']}, κ = {over['kappa']}, q = {over['q']:.3g})"
    )
    OUT.mkdir(parents=True, exist_ok=True)
    path = OUT / "chatter_limit.json"
    doc = {"q_max_chatter": q_max, "q_clean_from": clean_from, "seconds": sec, "rows": rows}
    path.write_text(json.dumps(doc, indent=1, allow_nan=False, default=float), "utf-8")
    print(f"wrote {path} (log10 step of q: {math.log10(QS[1] / QS[0]):.3f})")


if __name__ == "__main__":
    main()
