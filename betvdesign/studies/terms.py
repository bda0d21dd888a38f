"""The optional physics of a parameter-space study: ζ_v, ζ_h and e, fixed over a sweep.

docs/MODEL.md, "Beyond the paper's idealisation": head damping ratios ζ_v (normal) and
ζ_h (tangential), Q = 1/(2ζ), and a coefficient of restitution e ∈ [0, 1) of normal
impacts. A sweep over (ϖ, α, β, κ) holds them fixed; all 0 (the default) is the paper's
model, and then a study's tasks, parameters, columns and rows are exactly those of the
idealised study (bit-identical results, and an output written before these terms existed
still resumes).

Non-zero terms enter everywhere a result depends on them, following
:meth:`betvdesign.model.params.ModelParams.as_dict` (all three when one is set):

* the study's ``parameters`` (so a store of a damped sweep never resumes an undamped one
  and vice versa: :mod:`betvdesign.studies.engine.store` compares them),
* every task (the workers build ``ModelParams`` with them),
* the result columns and rows (:func:`columns_with`),
* the summary (``terms`` and the model statement).

The λ fit is a fit of the idealised model: :func:`require_ideal_rung` refuses it (and
every rung of :data:`betvdesign.checks.fidelity.IDEAL_ONLY`) when a term is set.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from betvdesign.errors import ParameterError, UsageError
from betvdesign.model.params import ModelParams

#: The optional terms, in the order of ``ModelParams`` (and of the result columns).
NAMES = ("zeta_v", "zeta_h", "restitution")
#: Their symbols in messages.
SYMBOLS = {"zeta_v": "ζ_v", "zeta_h": "ζ_h", "restitution": "e"}


@dataclass(frozen=True)
class Terms:
    """ζ_v, ζ_h [-] and e [-] of a study (0: the paper's model), validated.

    ζ_v, ζ_h [-] and e [-] of a study (0: the paper's model), validated as
    :class:`~betvdesign.model.params.ModelParams` validates them (a :class:`UsageError`
    naming the term otherwise).
    """

    zeta_v: float = 0.0
    zeta_h: float = 0.0
    restitution: float = 0.0

    def __post_init__(self) -> None:
        """Validate the terms as :class:`ModelParams` does."""
        try:
            p = ModelParams(1.0, 1.0, 1.0, 1.0, self.zeta_v, self.zeta_h, self.restitution)
        except ParameterError as exc:
            raise UsageError(str(exc)) from None
        for name in NAMES:
            object.__setattr__(self, name, getattr(p, name))

    @classmethod
    def of(cls, source: Mapping[str, Any]) -> Terms:
        """The terms a task, a row or a parameter mapping carries.

        Parameters
        ----------
        source : mapping
            A task, row or study parameters with ``zeta_v``, ``zeta_h``, ``restitution``
            [-] (absent or None: 0).

        Returns
        -------
        Terms
            The validated terms.
        """
        return cls(*(float(source.get(n) or 0.0) for n in NAMES))

    @property
    def ideal(self) -> bool:
        """No damping, plastic impacts: the paper's model."""
        return self.zeta_v == 0.0 and self.zeta_h == 0.0 and self.restitution == 0.0

    def as_dict(self) -> dict[str, float]:
        """The terms as plain data.

        Returns
        -------
        dict
            ``zeta_v``, ``zeta_h``, ``restitution`` [-] when one is set, else {} (as
            ``ModelParams.as_dict``).
        """
        return {} if self.ideal else {n: getattr(self, n) for n in NAMES}

    def params(self, varpi: float, alpha: float, beta: float, kappa: float) -> ModelParams:
        """The model parameters of one grid point with these terms.

        Parameters
        ----------
        varpi, alpha, beta, kappa : float
            ϖ, α, β, κ of the point [-].

        Returns
        -------
        ModelParams
            The point's parameters with ζ_v, ζ_h and e.
        """
        return ModelParams(varpi, alpha, beta, kappa, self.zeta_v, self.zeta_h, self.restitution)

    def statement(self, names: tuple[str, ...] = NAMES) -> str:
        """The terms in words, for a model statement.

        Parameters
        ----------
        names : tuple of str
            The terms to state (the regime study states ζ_v and e only).

        Returns
        -------
        str
            ``ζ_v = 0.01 (Q = 50), ζ_h = 0.02 (Q = 25), e = 0.1`` with the quality factor
            Q = 1/(2ζ) [-], or the paper's model.
        """
        if self.ideal:
            return "the paper's idealised model (undamped, plastic impacts)"
        parts = []
        for name in names:
            v = getattr(self, name)
            text = f"{SYMBOLS[name]} = {v:g}"
            if name != "restitution" and v > 0:
                text += f" (Q = {1 / (2 * v):g})"
            parts.append(text)
        return ", ".join(parts)


def columns_with(columns: Mapping[str, type], terms: Terms, after: str) -> dict[str, type]:
    """A study's result columns with the terms' columns.

    Parameters
    ----------
    columns : mapping of str to type
        The columns of the idealised study.
    terms : Terms
        The study's terms.
    after : str
        The column the terms' float columns follow.

    Returns
    -------
    dict of str to type
        ``columns`` with ``zeta_v``, ``zeta_h``, ``restitution`` after ``after`` when a term
        is set (``columns`` unchanged for the paper's model).
    """
    if terms.ideal:
        return dict(columns)
    out: dict[str, type] = {}
    for name, kind in columns.items():
        out[name] = kind
        if name == after:
            out |= dict.fromkeys(terms.as_dict(), float)
    return out


def model_statement(base: str, terms: Terms, names: tuple[str, ...] = NAMES) -> str:
    """A study's model statement, with the terms when one is set.

    Parameters
    ----------
    base : str
        The rung's statement.
    terms : Terms
        The study's terms.
    names : tuple of str
        The terms the study's model takes.

    Returns
    -------
    str
        ``base``, followed by :meth:`Terms.statement` when a term is set.
    """
    return base if terms.ideal else f"{base}; with {terms.statement(names)}"


def require_ideal_rung(fidelity: str, terms: Terms) -> None:
    """Refuse a rung of the idealised model only when a term is set.

    Parameters
    ----------
    fidelity : str
        The rung asked for.
    terms : Terms
        The study's terms.

    Raises
    ------
    UsageError
        ``fidelity`` is in :data:`betvdesign.checks.fidelity.IDEAL_ONLY` (the λ fit) and a
        term is set.
    """
    from betvdesign.checks.fidelity import IDEAL_ONLY

    if terms.ideal or fidelity not in IDEAL_ONLY:
        return
    raise UsageError(
        f"fidelity {fidelity!r} is a fit of the paper's idealised model (undamped, plastic "
        f"impacts) and cannot take damping or restitution ({terms.statement()}); use "
        "--fidelity periodic (the default: the exact periodic orbit includes them), or "
        "drop the terms to map the idealised model"
    )
