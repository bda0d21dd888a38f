"""``betv fix … --layout FIXED.gds``: the fix applied to the drawing.

The fixed device (the search's best candidate, :func:`betvdesign.studies.fix.find_fixes`)
is validated like a device file, drawn (:func:`betvdesign.layout.write.build_library`),
read back (:func:`betvdesign.layout.extract.derive_gds`) and checked with the layout's
own rules; only a layout that passes ``betv check`` is renamed into place (nothing is
written otherwise).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from betvdesign.errors import BetvError
from betvdesign.layout.extract import derive_gds
from betvdesign.layout.write import TIMESTAMP, build_library
from betvdesign.output.files import atomic_path
from betvdesign.spec.models import DeviceSpec

__all__ = ["write_fixed_layout"]


def write_fixed_layout(
    spec: DeviceSpec, res: Any, cand: Any, out: str | os.PathLike[str], *, process_ref: str
) -> Path:
    """Draw ``spec`` with ``cand``'s changes to ``out``, verified.

    The changes are written as a device file writes them
    (:func:`betvdesign.studies.fixfile.fixed_values`); the drawing is verified as the
    module doc says.

    Parameters
    ----------
    spec : DeviceSpec
        The device as the layout gives it.
    res : FixResult
        The fix search's answer.
    cand : Candidate
        The fix applied.
    out : path
        The GDS file written.
    process_ref : str
        What the ``process = …`` label says.

    Returns
    -------
    Path
        ``out``.

    Raises
    ------
    BetvError
        When the result does not pass.
    """
    from betvdesign.checks.checker import check_derivation
    from betvdesign.studies.fixfile import fixed_values

    items = list(fixed_values(res, cand).items())
    fixed = spec.replace(*items[0], *items[1:]) if items else spec
    lib = build_library(fixed, process_ref)
    out = Path(out)
    with atomic_path(out) as tmp:  # beside `out`: the process path resolves alike
        lib.write_gds(str(tmp), max_points=8190, timestamp=TIMESTAMP)
        d, ex = derive_gds(tmp)
        res = check_derivation(d, layout_rules=ex.rules)
        if res.verdict != "pass":
            failing = ", ".join(r.id for r in res.rules if r.severity == "error" and not r.passed)
            raise BetvError(f"the fixed layout does not pass betv check ({failing}); not written")
    return out
