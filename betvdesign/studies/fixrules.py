"""The error rules a sample must pass under fabrication spread, in words.

Kept apart from :mod:`betvdesign.studies.sampling` and :mod:`betvdesign.studies.fix`
(which import the spec, pint and numpy) so ``betv fix --help`` can quote them without
loading the search.
"""

from __future__ import annotations

__all__ = ["SPREAD_RULES", "spread_rules"]


def spread_rules(target: bool = True) -> str:
    """The error rules a sample's set must pass to count in P(pass), in words.

    ``betv tolerance`` and ``betv fix --spread`` count it alike
    (:func:`betvdesign.studies.sampling.passes_spread_rules`).

    Parameters
    ----------
    target : bool
        With the target speed (``betv fix --target-speed``; ``betv tolerance`` takes
        none).

    Returns
    -------
    str
        E.g. "frequency window, tangential resonance, exact mode and target speed".
    """
    names = ["frequency window", "tangential resonance", "exact mode"]
    names += ["target speed"] if target else []
    return ", ".join(names[:-1]) + " and " + names[-1]


#: :func:`spread_rules` with the target speed.
SPREAD_RULES = spread_rules()
