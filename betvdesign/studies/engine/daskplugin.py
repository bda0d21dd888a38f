"""A dask worker plugin that loads the solver kernels once per worker.

Imported only by :class:`~betvdesign.studies.engine.executors.DaskExecutor` (dask is an
optional extra). Registered on the cluster before a study's chunks are submitted, it
runs :func:`betvdesign.dynamics.warm.warm` once in every worker, present or joining
later, so that no chunk pays the kernels' load (about 0.5 s per worker from the numba
cache, minutes on a cold cache) and the chunks' times are the solver's.
"""

from __future__ import annotations

import asyncio
import contextlib
from typing import Any

from distributed import WorkerPlugin

#: The plugin's name on the cluster (registering it again replaces it).
NAME = "betvdesign-warm-kernels"


def _warm() -> None:
    """Warm the kernels; a failure is left to the first task, which reports it."""
    with contextlib.suppress(Exception):
        from betvdesign.dynamics.jit import jit_enabled
        from betvdesign.dynamics.warm import warm

        if jit_enabled():
            warm()


class WarmKernels(WorkerPlugin):
    """Loads (or compiles) every solver kernel when a worker starts or joins."""

    name = NAME

    async def setup(self, worker: Any) -> None:
        """Warm the kernels in a thread, keeping the worker's event loop responsive.

        Parameters
        ----------
        worker : distributed.Worker
            The worker.
        """
        await asyncio.to_thread(_warm)
