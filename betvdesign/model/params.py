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

#: Supported damping ratios ζ (besides 0): below ZETA_MIN (Q > 5000) the damped closed
#: form's particular/homogeneous split cancels up to 1/(2ζ) near resonance (more than 4
#: digits); above ZETA_MAX (Q < 0.05) the head is so overdamped that the impact model
#: (a hit at finite velocity) no longer describes it.
ZETA_MIN = 1e-4
ZETA_MAX = 10.0

#: Empirical constant of the push/pull fit (docs/MODEL.md, "Push/pull criterion").
LAMBDA_FIT_CONSTANT = 22.0


@dataclass(frozen=True, slots=True)
class ModelParams:
    """Governing parameters of the dimensionless model [all dimensionless].

    varpi: normalised actuation frequency, ϖ = ω·sqrt(m/k_v)
    alpha: relative impact compliance, α = k_v/k_h
    beta:  relative mass, β = m/M
    kappa: normalised friction, κ = μ·tanθ

    Optional terms beyond the paper (MODEL.md "Beyond the paper's idealisation"; all 0:
    the paper's model, to the last bit):

    zeta_v: damping ratio ζ_v of the head's normal (vertical) oscillator, Q_v = 1/(2ζ_v)
    zeta_h: damping ratio ζ_h of the head's tangential oscillator, Q_h = 1/(2ζ_h)
    restitution: coefficient of restitution e ∈ [0, 1) of normal impacts (0: plastic)

    A damping ratio is 0 or within [:data:`ZETA_MIN`, :data:`ZETA_MAX`].
    Raises :class:`ParameterError` for non-finite or non-positive values.
    """

    varpi: float
    alpha: float
    beta: float
    kappa: float
    zeta_v: float = 0.0
    zeta_h: float = 0.0
    restitution: float = 0.0

    def __post_init__(self) -> None:
        for name in ("zeta_v", "zeta_h", "restitution"):
            value = getattr(self, name)
            try:
                v = float(value)
            except (TypeError, ValueError):
                raise ParameterError(f"{name} must be a number, got {value!r}") from None
            if not math.isfinite(v) or v < 0.0:
                raise ParameterError(f"{name} must be finite and ≥ 0, got {v!r}")
            if name == "restitution" and v >= 1.0:
                raise ParameterError(f"restitution must be < 1 (e ∈ [0, 1)), got {v!r}")
            if name != "restitution" and v != 0.0 and not ZETA_MIN <= v <= ZETA_MAX:
                raise ParameterError(
                    f"{name} = {v:g} is outside the supported damping range: 0 (undamped) "
                    f"or {ZETA_MIN:g} ≤ ζ ≤ {ZETA_MAX:g} (Q from {1 / (2 * ZETA_MAX):g} to "
                    f"{1 / (2 * ZETA_MIN):g}); below {ZETA_MIN:g} the damped closed form "
                    "loses more than 4 digits near resonance: use 0 (Q = ∞)"
                )
            object.__setattr__(self, name, v)
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
    def lambda_mode(self) -> Mode:
        """Mode predicted by the λ fit: push when λ < 1, pull otherwise."""
        return "push" if self.lam < 1.0 else "pull"

    @property
    def mode_predicted(self) -> Mode:
        """Deprecated name of :attr:`lambda_mode` (removed in the next release)."""
        import warnings

        warnings.warn(
            "ModelParams.mode_predicted is now lambda_mode (the λ fit's mode, never the exact one)",
            DeprecationWarning,
            stacklevel=2,
        )
        return self.lambda_mode

    @property
    def ideal(self) -> bool:
        """The paper's idealised model: no damping, plastic impacts."""
        return self.zeta_v == 0.0 and self.zeta_h == 0.0 and self.restitution == 0.0

    def as_dict(self) -> dict[str, float]:
        """The parameters by name; the optional terms only when one of them is set."""
        d = {"varpi": self.varpi, "alpha": self.alpha, "beta": self.beta, "kappa": self.kappa}
        if not self.ideal:
            d |= {"zeta_v": self.zeta_v, "zeta_h": self.zeta_h, "restitution": self.restitution}
        return d


def normal_force_phase(zeta_v: float, varpi: float) -> tuple[float, float]:
    """(δ [rad], A [-]) of the contact normal force with the normal damper:
    sin ϖτ_o + 2ζ_v ϖ cos ϖτ_o = A sin(ϖτ_o + δ), δ = atan(2ζ_v ϖ), A = sqrt(1 + (2ζ_v ϖ)²)
    (docs/damping.md). The solver's time is τ = τ_o + δ/ϖ (N ∝ A sin ϖτ). Its one home,
    here so that the solver (:mod:`betvdesign.dynamics.flows`) and the derivation record
    (:mod:`betvdesign.nondim.terms`) share it."""
    d = 2.0 * zeta_v * varpi
    return math.atan(d), math.hypot(1.0, d)


def lambda_criterion(varpi: float, alpha: float, beta: float, kappa: float) -> float:
    """Empirical push/pull criterion [-].

    λ = (κ/ϖ²)·(1/(ακ) − (1/β − β)/(22(κ + 1)));  λ < 1 push, λ > 1 pull.
    Works elementwise on numpy arrays too.
    """
    return (kappa / varpi**2) * (1.0 / (alpha * kappa) - fit_offset(kappa, beta))


def fit_offset(kappa: float, beta: float) -> float:
    """D = (1/β − β)/(22(κ + 1)) [-], the mass term of the λ fit (λ = (κ/ϖ²)(1/(ακ) − D))."""
    return (1.0 / beta - beta) / (LAMBDA_FIT_CONSTANT * (kappa + 1.0))


@dataclass(frozen=True, slots=True)
class HeadCoupling:
    """The coupled head's two extra parameters (docs/MODEL.md, "Coupled head") [-].

    rho: the coupling ρ = C_nt/√(C_nn·C_tt) of the head's compliance in the slider's frame
        (n toward the slider, t along it in the impact direction; ``model/frame.py``),
        −1 < ρ < 1; 0 is the paper's decoupled head.
    chi: χ = √α·tanθ > 0, the ratio of the head's compliance lengths √(C_tt/C_nn) to the
        stroke's cotθ (α = k_v/k_h = C_tt/C_nn).

    With them the dimensionless spring forces are F_n = a(y_n + (ρ/χ) y_t) and
    R = a(ρχ y_n + y_t), a = 1/(1 − ρ²). Raises :class:`ParameterError` out of range.
    """

    rho: float
    chi: float

    def __post_init__(self) -> None:
        for name in ("rho", "chi"):
            value = getattr(self, name)
            try:
                v = float(value)
            except (TypeError, ValueError):
                raise ParameterError(f"{name} must be a number, got {value!r}") from None
            if not math.isfinite(v):
                raise ParameterError(f"{name} must be finite, got {v!r}")
            object.__setattr__(self, name, v)
        if not -1.0 < self.rho < 1.0:
            raise ParameterError(
                f"rho must be in (−1, 1) (a positive definite head), got {self.rho!r}"
            )
        if self.chi <= 0.0:
            raise ParameterError(f"chi = √α·tanθ must be > 0, got {self.chi!r}")

    @classmethod
    def from_angle(cls, rho: float, alpha: float, theta_rad: float) -> HeadCoupling:
        """The coupling of a head with ρ, the model's α and the impact angle θ [rad]."""
        if not 0.0 < theta_rad < 0.5 * math.pi:
            raise ParameterError(f"impact angle must be in (0, π/2) rad, got {theta_rad!r}")
        return cls(rho, math.sqrt(alpha) * math.tan(theta_rad))

    @property
    def decoupled(self) -> bool:
        """ρ = 0: the paper's head."""
        return self.rho == 0.0

    @property
    def a(self) -> float:
        """a = 1/(1 − ρ²) = K_nn/k_v = K_tt/k_h [-]."""
        return 1.0 / ((1.0 - self.rho) * (1.0 + self.rho))
