"""Imported by the process pool's fork server: loads the solver kernels once.

:class:`~betvdesign.studies.engine.executors.ProcessExecutor` names this module in the
fork server's preload list. The fork server imports it once; every worker is then
forked from a process that already holds the kernels' machine code, instead of each
worker loading them from the numba cache on its first task (about 0.5 s per worker).

The import never fails: a kernel that cannot be warmed here (a broken cache, say) is
loaded or compiled by the worker that first needs it, as without this module, and the
study reports its own error then. With ``NUMBA_DISABLE_JIT`` nothing is warmed.
"""

from __future__ import annotations

import contextlib

with contextlib.suppress(Exception):
    from betvdesign.dynamics.jit import jit_enabled
    from betvdesign.dynamics.warm import warm

    if jit_enabled():
        warm()
