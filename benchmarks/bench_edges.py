"""The verdict at its own edges: a seeded sweep of designs at and around ϖ = 0.5 and 2.

    .venv/bin/python benchmarks/bench_edges.py -n 1000 -j 2   # -> benchmarks/out/edges.json

Each design is push_demo's derivation (scales, travel, drive) with its parameters
replaced: ϖ at an edge (0.5 or 2) moved by 0, ±1, ±2, ±4 ulp, ±1e-9 or ±1e-6
(relative), α, β, κ drawn log-uniformly over the λ fit's ranges, undamped or Q = 30 in
both directions (seed 29). Every design goes through the check (``check_derivation``,
adequacy off) and every line that quotes its motion is read back. A contradiction is
any of:

- the window rule's verdict against :func:`betvdesign.model.domain.window_position`,
  or its message's word (inside / below / above / lower edge / upper edge) against it;
- the message says "one hit per cycle" while the vertical motion it quotes has several
  hits, or "several times" while it has one, or an inside window with no recurring
  contact above round-off;
- a moving mode (push/pull) quoted for an orbit the solver calls not driven, or for
  a contact below round-off;
- the headline mode, the mode rule and the mode-margin rule's reference on different
  bases or with different modes; a speed whose sign is not the mode's;
- a PASS with a failing window or mode rule; a passing window margin for a ϖ whose
  ±5 % corners leave the window (exact rational arithmetic on the float's value);
- the time to cross in the JSON against the transient's own crossing.

The result (counts per family, every contradiction with its design) is written to
``benchmarks/out/edges.json`` with its provenance (seed, command, commit).
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import replace
from fractions import Fraction
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
OFFSETS = (
    "0",
    "-1ulp",
    "+1ulp",
    "-2ulp",
    "+2ulp",
    "-4ulp",
    "+4ulp",
    "-1e-9",
    "+1e-9",
    "-1e-6",
    "+1e-6",
)


def _move(edge: float, offset: str) -> float:
    if offset == "0":
        return edge
    if offset.endswith("ulp"):
        k = int(offset[1:-3])
        w = edge
        for _ in range(k):
            w = math.nextafter(w, math.inf if offset[0] == "+" else -math.inf)
        return w
    return edge * (1.0 + float(offset))


def designs(n: int, seed: int = 29) -> list[dict]:
    """``n`` seeded designs at and around the window's edges (module docstring)."""
    rng = np.random.default_rng(seed)
    out = []
    for i in range(n):
        edge = (0.5, 2.0)[i % 2]
        offset = OFFSETS[(i // 2) % len(OFFSETS)]
        q = None if (i // (2 * len(OFFSETS))) % 2 == 0 else 30.0
        alpha = float(np.exp(rng.uniform(np.log(0.1), np.log(4.0))))
        beta = float(np.exp(rng.uniform(np.log(0.1), np.log(1.5))))
        kappa = float(np.exp(rng.uniform(np.log(0.1), np.log(0.4))))
        out.append(
            dict(
                i=i,
                edge=edge,
                offset=offset,
                q=q,
                varpi=_move(edge, offset),
                alpha=alpha,
                beta=beta,
                kappa=kappa,
            )
        )
    return out


def _expected_position(w: float) -> str:
    """The window position by exact rational arithmetic on the float's value, with the
    stated edge tolerance (1e-12 relative)."""
    x = Fraction(w)
    for edge, name in ((Fraction(1, 2), "lower-edge"), (Fraction(2), "upper-edge")):
        if abs(x - edge) <= Fraction(1, 10**12) * edge:
            return name
    if x < Fraction(1, 2):
        return "below"
    if x < 2:
        return "inside"
    return "above" if x < Fraction(26, 10) else "far-above"


def judge(d: dict) -> dict:
    """Check one design and list its contradictions."""
    from betvdesign.checks.checker import check_derivation
    from betvdesign.model.domain import ROUND_OFF_SCALE, VARPI_WINDOW, mode_of
    from betvdesign.model.params import ModelParams
    from betvdesign.nondim.device import derive_file

    base = derive_file(ROOT / "devices" / "push_demo.yaml")
    zeta = 0.0 if d["q"] is None else 1.0 / (2.0 * d["q"])
    p = ModelParams(d["varpi"], d["alpha"], d["beta"], d["kappa"], zeta_v=zeta, zeta_h=zeta)
    s0 = base.sets[0]
    s = replace(s0, params=p)
    dev = replace(base, sets=[s])
    t0 = time.perf_counter()
    res = check_derivation(dev, adequacy=False)
    (sc,) = res.sets
    bad: list[str] = []
    rules = {r.id: r for r in sc.rules}
    win = rules["frequency-window"]
    pos = _expected_position(d["varpi"])
    inside = pos in ("lower-edge", "inside")
    if win.passed is not inside:
        bad.append(f"window rule {win.passed} but exact position {pos}")
    word = {
        "below": "below the window",
        "lower-edge": "lower edge (inside)",
        "inside": "inside the window",
        "upper-edge": "upper edge (outside)",
        "above": "above the window",
        "far-above": "far above",
    }[pos]
    if word not in win.message:
        bad.append(f"window message without '{word}': {win.message[:120]}")
    v = sc.vertical
    if v is not None and v.success:
        if "one hit per cycle" in win.message and v.hits_per_cycle != 1:
            bad.append(f"'one hit per cycle' beside {v.hits_per_cycle} hits")
        if "hits several times per cycle" in win.message and v.hits_per_cycle == 1:
            if "still hits once" not in win.message:
                bad.append("'several times per cycle' beside 1 hit")
        if inside and v.contact_fraction <= ROUND_OFF_SCALE and d["q"] is None:
            bad.append(f"inside the window with contact {v.contact_fraction:.2g}")
    mode = sc.verdict_mode
    po = sc.periodic
    if mode in ("push", "pull") and "slider is not driven" in win.message:
        bad.append(f"window says not driven beside {mode}")
    if mode in ("push", "pull"):
        if po is not None and po.status == "not_driven":
            bad.append(f"{mode} quoted for a not-driven orbit")
        if po is not None and po.contact_fraction is not None and po.success:
            if po.contact_fraction <= ROUND_OFF_SCALE:
                bad.append(f"{mode} for contact {po.contact_fraction:.2g}")
        speed = sc.speed_m_s
        if speed is None or speed == 0 or (speed > 0) is not (mode == "push"):
            bad.append(f"speed {speed} against mode {mode}")
    mode_rule = rules["mode"]
    if sc.travel is not None and sc.travel.mode in ("push", "pull"):
        if mode_rule.passed is not (sc.travel.mode == sc.derivation.intended_mode):
            bad.append("mode rule against the travel's mode")
        if "mode-margin" in rules:
            m = rules["mode-margin"].message
            if f"the {sc.travel.mode} mode" not in m and "changes" not in m:
                bad.append(f"margin on another mode: {m[:100]}")
            basis = "crossing from rest" if sc.travel.basis == "crossing" else "periodic orbit"
            if basis not in m:
                bad.append(f"margin basis {m[-40:]} against headline {sc.travel.basis}")
    if res.verdict == "pass" and not (win.passed and mode_rule.passed):
        bad.append("PASS with a failing window or mode rule")
    wm = rules.get("window-margin")
    if inside:
        lo, hi = (Fraction(x) for x in VARPI_WINDOW)
        x = Fraction(d["varpi"])
        corners_in = lo <= x * Fraction(95, 100) and x * Fraction(105, 100) < hi
        if wm is None or wm.passed is not corners_in:
            bad.append(f"window-margin {None if wm is None else wm.passed} against {corners_in}")
    t = sc.time_to_cross_s
    if t is not None and sc.travel is not None and sc.travel.cycles_to_cross is not None:
        if abs(t - sc.travel.cycles_to_cross / s.scales.f_act_hz) > 1e-12:
            bad.append("time to cross not the transient's")
    if po is not None and po.success and mode_of(po.delta_s) is None:
        bad.append("successful orbit without a mode")
    return dict(
        d,
        verdict=res.verdict,
        mode=mode,
        basis=None if sc.travel is None else sc.travel.basis,
        orbit=None if po is None else po.status,
        window=win.passed,
        contradictions=bad,
        seconds=time.perf_counter() - t0,
    )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-n", type=int, default=1000)
    ap.add_argument("-j", type=int, default=2)
    ap.add_argument("--out", type=Path, default=ROOT / "benchmarks" / "out" / "edges.json")
    a = ap.parse_args()
    ds = designs(a.n)
    t0 = time.perf_counter()
    with ProcessPoolExecutor(a.j) as ex:
        rows = list(ex.map(judge, ds, chunksize=4))
    wall = time.perf_counter() - t0
    bad = [r for r in rows if r["contradictions"]]
    fam: dict[str, dict[str, int]] = {}
    for r in rows:
        k = f"ϖ={r['edge']:g} {r['offset']} {'undamped' if r['q'] is None else 'Q=30'}"
        f = fam.setdefault(k, {"n": 0, "contradictions": 0})
        f["n"] += 1
        f["contradictions"] += bool(r["contradictions"])
    commit = subprocess.run(
        ["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True
    ).stdout.strip()
    summary = {
        "provenance": {
            "command": " ".join(["python", "benchmarks/bench_edges.py", *sys.argv[1:]]),
            "seed": 29,
            "commit": commit,
            "wall_s": wall,
            "workers": a.j,
        },
        "n": len(rows),
        "contradictions": len(bad),
        "verdicts": {k: sum(r["verdict"] == k for r in rows) for k in ("pass", "fail")},
        "modes": {m: sum(r["mode"] == m for r in rows) for m in sorted({r["mode"] for r in rows})},
        "families": fam,
        "bad": bad,
        "rows": rows,
    }
    a.out.parent.mkdir(parents=True, exist_ok=True)
    a.out.write_text(json.dumps(summary, indent=1, default=str))
    print(f"{len(rows)} designs, {len(bad)} with contradictions, {wall:.0f} s -> {a.out}")
    for r in bad[:20]:
        print(r["i"], r["edge"], r["offset"], r["q"], r["contradictions"])


if __name__ == "__main__":
    main()
