"""Compile (or load) every solver kernel ahead of use: ``python -m betvdesign.dynamics.warm``.

``make demo`` runs it, so that no user command compiles silently later. It runs each
public entry point of the dynamics once on a small design (transient with event log and
dense output, transient without, periodic orbit, vertical motion, the coupled head's
transient and orbit), which compiles every
kernel they use and stores the machine code in the cache (:func:`jit.cache_dir`).
"""

from __future__ import annotations

import sys
import time


def warm() -> float:
    """Compile or load every kernel; returns the seconds it took."""
    from betvdesign.dynamics import periodic_orbit, simulate, vertical_motion
    from betvdesign.dynamics.coupled import coupled_periodic_orbit, simulate_coupled
    from betvdesign.model.params import HeadCoupling, ModelParams

    t0 = time.perf_counter()
    p = ModelParams(1.2, 0.5, 1.0, 0.4)
    simulate(p, 3, dense=True).sample(0.5)
    simulate(p, 3, log_events=False)
    periodic_orbit(p)
    vertical_motion(p.varpi)
    simulate_coupled(p, HeadCoupling(0.5, 1.0), 2)
    simulate_coupled(p, HeadCoupling(0.5, 1.0), 2, log_events=False)
    coupled_periodic_orbit(p, HeadCoupling(0.5, 1.0), transient=2, max_newton=1)
    return time.perf_counter() - t0


def main() -> int:
    """Compile every solver kernel into the cache (``make demo``); the exit status."""
    from betvdesign.dynamics.jit import cache_dir, jit_enabled

    if not jit_enabled():
        print("betv: NUMBA_DISABLE_JIT is set: the solver runs as plain Python, nothing to compile")
        return 0
    print(
        f"betv: compiling the solver kernels, or loading them (numba cache {cache_dir()})",
        flush=True,
    )
    dt = warm()
    print(f"betv: solver kernels ready in {dt:.1f} s", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
