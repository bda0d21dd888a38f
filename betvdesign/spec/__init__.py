"""Device specs: units, models, loader, limits, paths and what-if edits.

Device specs: pint quantities and units, the pydantic models, the YAML loader with
file:line:col messages, input limits, spec paths (:mod:`~betvdesign.spec.paths`, the one
home of the idea) and validated what-if edits on them, and the one list of the fields a
designer changes (:mod:`~betvdesign.spec.fields`).

Above :mod:`betvdesign.model`; units live here and in :mod:`betvdesign.nondim`, which
strips them. Nothing below imports this package.
"""
