"""The four dimensionless parameters of the BETV impact model (unit-free).

Shared by every layer below ``nondim``: ``nondim`` produces :class:`ModelParams`,
``dynamics``, ``rules`` and ``studies`` consume them. See docs/MODEL.md,
"Dimensionless model".
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

from betvdesign.errors import ParameterError

Mode = Literal["push", "pull"]

#: Empirical constant of the push/pull fit (docs/MODEL.md, "Push/pull criterion").
LAMBDA_FIT_CONSTANT = 22.0


@dataclass(frozen=True, slots=True)
class ModelParams:
    """Governing parameters of the dimensionless model [all dimensionless].

    varpi: normalised actuation frequency, ϖ = ω·sqrt(m/k_v)
    alpha: relative impact compliance, α = k_v/k_h
    beta:  relative mass, β = m/M
    kappa: normalised friction, κ = μ·tanθ

    Raises :class:`ParameterError` for non-finite or non-positive values.
    """

    varpi: float
    alpha: float
    beta: float
    kappa: float

    def __post_init__(self) -> None:
        for name in ("varpi", "alpha", "beta", "kappa"):
            value = getattr(self, name)
            try:
                v = float(value)
            except (TypeError, ValueError):
                raise ParameterError(f"{name} must be a number, got {value!r}") from None
            if not math.isfinite(v):
                raise ParameterError(f"{name} must be finite, got {v!r}")
            if v <= 0.0:
                raise ParameterError(f"{name} must be > 0, got {v!r}")
            object.__setattr__(self, name, v)

    @property
    def lam(self) -> float:
        """Push/pull criterion λ [-] (docs/MODEL.md, "Push/pull criterion")."""
        return lambda_criterion(self.varpi, self.alpha, self.beta, self.kappa)

    @property
    def mode_predicted(self) -> Mode:
        """Mode predicted by the λ fit: push when λ < 1, pull otherwise."""
        return "push" if self.lam < 1.0 else "pull"

    def as_dict(self) -> dict[str, float]:
        return {"varpi": self.varpi, "alpha": self.alpha, "beta": self.beta, "kappa": self.kappa}


def lambda_criterion(varpi: float, alpha: float, beta: float, kappa: float) -> float:
    """Empirical push/pull criterion [-].

    λ = (κ/ϖ²)·(1/(ακ) − (1/β − β)/(22(κ + 1)));  λ < 1 push, λ > 1 pull.
    Works elementwise on numpy arrays too.
    """
    return (kappa / varpi**2) * (1.0 / (alpha * kappa) - fit_offset(kappa, beta))


def fit_offset(kappa: float, beta: float) -> float:
    """D = (1/β − β)/(22(κ + 1)) [-], the mass term of the λ fit (λ = (κ/ϖ²)(1/(ακ) − D))."""
    return (1.0 / beta - beta) / (LAMBDA_FIT_CONSTANT * (kappa + 1.0))
