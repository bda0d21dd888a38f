"""Numbers in JSON: one rule for every file and stream the toolkit writes.

JSON has no NaN and no ±inf. Everywhere betvdesign writes JSON (``betv check --json``,
``betv simulate --json``, study sidecars and rows, benchmark outputs, adequacy and
determination records) a float that is not finite is written as ``null``; what it meant
(unbounded, not computed, no orbit) is said by a status or message field beside it, never
by the number. Listed in ``betv schema check`` (``x-betv-numbers``).
"""

from __future__ import annotations

import math

#: The rule, as ``betv schema`` states it.
RULE = "non-finite floats (NaN, ±inf) are written as null; a status field says why"


def json_float(x: float | None) -> float | None:
    """A float for JSON: the value when finite, else None (written ``null``).

    Parameters
    ----------
    x : float or None
        Any number (numpy scalars included) or None.

    Returns
    -------
    float or None
        ``float(x)`` when finite; None for None, NaN and ±inf.
    """
    if x is None:
        return None
    v = float(x)
    return v if math.isfinite(v) else None
