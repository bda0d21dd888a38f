"""Device spec -> dimensionless model, scales and derivation record.

Device spec -> dimensionless model: (ϖ, α, β, κ) and the optional terms, the scales
back to SI and the record of every step. The only package that strips units.

- :mod:`~betvdesign.nondim.device`: :func:`derive`, :func:`derive_file`,
  :func:`derive_set`, :func:`derive_samples`, and the paper's relations one step each
  (MODEL.md "Device-to-parameter relations": slider and head mass, k_v, α, f_act, u,
  the scales, ϖ, β, κ, λ);
- :mod:`~betvdesign.nondim.terms`: the steps of the optional terms (thermal roll-off,
  damping, restitution; MODEL.md "Beyond the paper's idealisation");
- :mod:`~betvdesign.nondim.record`: what a derivation produces (plain data) and the
  :class:`~betvdesign.nondim.record.Recorder` every step writes to.

Named ``nondim`` rather than ``derive`` so that the package does not shadow the public
function :func:`betvdesign.derive`.
"""

from betvdesign.nondim.device import derive, derive_file, derive_samples, derive_set
from betvdesign.nondim.record import (
    DerivationStep,
    DeviceDerivation,
    FitComparison,
    SampleDerivation,
    Scales,
    SetDerivation,
)

__all__ = [
    "DerivationStep",
    "DeviceDerivation",
    "FitComparison",
    "SampleDerivation",
    "Scales",
    "SetDerivation",
    "derive",
    "derive_file",
    "derive_samples",
    "derive_set",
]
