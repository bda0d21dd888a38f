"""What a fix under fabrication spread counts as passing, in words.

Kept apart from :mod:`betvdesign.studies.fix` (which imports the spec, pint and numpy) so
``betv fix --help`` can quote it without loading the search.
"""

from __future__ import annotations

__all__ = ["SPREAD_RULES"]

#: The error rules every sample of :func:`betvdesign.studies.fix.robust_probability` must
#: pass (its docstring states them with their thresholds).
SPREAD_RULES = "frequency window, tangential resonance, exact mode and target speed"
