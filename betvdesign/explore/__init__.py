"""``betv explore FILE``: the device live in the browser, on the exact solver.

A local Bokeh server (127.0.0.1 only) whose page has a control per designer field
(:mod:`~betvdesign.explore.fields`), the verdict of ``betv check`` recomputed as a
control moves (:mod:`~betvdesign.explore.compute`), the head's phase portrait and the
slider's motion, the exact-mode map of two fields
(:mod:`betvdesign.studies.fieldmap`) with ``betv fix``'s changes drawn on it, save to
YAML (only the changed lines, :mod:`~betvdesign.explore.design`) and the report.

Needs the optional extra: ``pip install 'betvdesign[explore]'`` (Bokeh). Import
:func:`serve` from :mod:`betvdesign.explore.server`; this package imports nothing heavy.
"""

from __future__ import annotations

__all__ = ["serve"]


def serve(*args: object, **kwargs: object) -> None:
    """See :func:`betvdesign.explore.server.serve`."""
    from betvdesign.explore.server import serve as _serve

    _serve(*args, **kwargs)  # type: ignore[arg-type]
