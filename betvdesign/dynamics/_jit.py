"""Marks the scalar helpers that the compiled kernels (:mod:`kernels`) share with the
pure-Python path, without importing numba here.

:func:`jitable` returns the function unchanged (so the Python path calls it at full
interpreter speed and numba is imported only when a kernel is first needed) and records
it; :mod:`kernels` registers every recorded function with
``numba.extending.register_jitable`` before compiling, so one source serves both paths.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TypeVar

F = TypeVar("F", bound=Callable)

#: functions marked with :func:`jitable`, in definition order
JITABLE: list[Callable] = []


def jitable(fn: F) -> F:
    """Record ``fn`` as callable from compiled kernels; return it unchanged."""
    JITABLE.append(fn)
    return fn
