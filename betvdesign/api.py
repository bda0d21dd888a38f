"""The one check pipeline, and the notebook and script entry points.

``betvdesign.check`` is :func:`check`: a device file (YAML), a drawn layout (GDS), a
loaded spec or a derivation in, one :class:`~betvdesign.checks.checker.CheckResult` out,
under one :class:`CheckOptions`. ``betv check``, ``betv explore``, ``betv report`` and the
notebook all go through :func:`run_check` and only render what it returns (text, JSON,
HTML: :mod:`betvdesign.checks.view`); none assembles a check of its own or edits the
result. ``betvdesign.adequacy`` is :func:`adequacy`: is the paper's idealised model enough
for the device?

Layer: above ``layout`` (a GDS source is read by :mod:`betvdesign.layout.extract`) and
``studies`` (the advice is :func:`betvdesign.studies.fix.advise`), below ``report``,
``explore`` and ``cli``, which call it.
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Callable
from dataclasses import dataclass, fields, replace
from typing import TYPE_CHECKING, Any, Literal

from betvdesign.errors import UsageError
from betvdesign.model.domain import TRAVEL_HORIZON
from betvdesign.spec.limits import MAX_CYCLES

if TYPE_CHECKING:
    from betvdesign.checks.adequacy import DeviceAdequacy
    from betvdesign.checks.checker import CheckResult
    from betvdesign.nondim.record import DeviceDerivation
    from betvdesign.spec.models import DeviceSpec

#: The cycles the transient from rest may be given to cross the travel (``--horizon``).
HORIZON_RANGE = (1000, MAX_CYCLES)

__all__ = [
    "HORIZON_RANGE",
    "CheckOptions",
    "DeviceSource",
    "adequacy",
    "check",
    "read_source",
    "run_check",
]


@dataclass(frozen=True)
class CheckOptions:
    """How a device is checked (``betv check``'s options; every caller's one set).

    Parameters
    ----------
    select, ignore : tuple of str
        Rule ids (or dotted prefixes) that count / do not count (``--select/--ignore``).
    target_speed : str or float, optional
        Required slider speed: text with its unit (``"1 mm/s"``) or a float [m/s] (adds
        the error rule ``target-speed``).
    horizon : int
        Cycles the transient from rest may take to cross the travel range [-]
        (``--horizon``; also the advice's).
    adequacy : bool
        Run the model-adequacy study (rule ``model-adequacy``; ``--adequacy``).
    advice : bool
        For a failing check (or a mode that flips within the margin), quote the nearest
        passing value of the fields that move what fails as the rules' fix (the search of
        ``betv fix``, :func:`betvdesign.studies.fix.advise`; ``--advice``).
    margin : bool
        Solve the mode-margin corners (rule ``mode-margin``).
    settle, determine : bool
        Run the transient from rest / judge how well Δs is determined in float64 (with
        both off, the verdict quotes the periodic orbit alone: the explorer's first
        stage).
    coupled : bool, optional
        The drawn head's coupled model (:mod:`betvdesign.checks.coupled`, rule
        ``coupled-head``): None (default) gives the verdict of the sets with a drawn head
        and no measured resonances from it; True also reports it as a finding for the drawn
        sets whose file resonances win; False keeps every verdict decoupled; "verdict" gives
        the verdict of those sets even when a ``solver`` is passed to :func:`run_check`
        (:func:`betvdesign.checks.checker.check_derivation`).

    Raises
    ------
    UsageError
        A ``target_speed`` that is not a speed, a ``horizon`` outside
        :data:`HORIZON_RANGE`.
    """

    select: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()
    target_speed: str | float | None = None
    horizon: int = TRAVEL_HORIZON
    adequacy: bool = True
    advice: bool = True
    margin: bool = True
    settle: bool = True
    determine: bool = True
    coupled: bool | Literal["verdict"] | None = None

    def __post_init__(self) -> None:
        """Freeze the selectors as tuples and refuse bad values before any solve."""
        object.__setattr__(self, "select", tuple(self.select))
        object.__setattr__(self, "ignore", tuple(self.ignore))
        _ = self.target_speed_m_s  # a bad speed is refused now
        lo, hi = HORIZON_RANGE
        if not lo <= self.horizon <= hi:
            raise UsageError(f"horizon: must be {lo:,} to {hi:,} cycles, got {self.horizon:,}")

    @property
    def target_speed_m_s(self) -> float | None:
        """The required speed [m/s], or None."""
        t = self.target_speed
        if t is None or isinstance(t, int | float):
            return None if t is None else float(t)
        from betvdesign.spec.units import parse_speed

        return parse_speed(t, "target_speed")


def run_check(
    source: str | os.PathLike[str] | DeviceSpec | DeviceDerivation | DeviceSource,
    options: CheckOptions | None = None,
    *,
    solver: Callable[..., Any] | None = None,
    vertical: Callable[..., Any] | None = None,
    adequacy_result: DeviceAdequacy | None = None,
) -> CheckResult:
    """The check of one device: the pipeline every caller shares.

    Reads the source (a ``.gds`` layout through :func:`betvdesign.layout.extract.derive_gds`:
    its process rules are the ones measured on the drawing, its notes what the extraction
    assumed), checks the derivation
    (:func:`betvdesign.checks.checker.check_derivation`) and, with ``options.advice``,
    attaches the advice's fix texts (:func:`betvdesign.studies.fix.with_advice`).

    Parameters
    ----------
    source : str, pathlib.Path, DeviceSpec, DeviceDerivation or DeviceSource
        A device file (YAML), a layout (``.gds``), a loaded spec, a derivation, or any
        of them already read (:func:`read_source`).
    options : CheckOptions, optional
        How to check (default :class:`CheckOptions`).
    solver, vertical : callable, optional
        Stand-ins for the exact periodic orbit and vertical motion (the report passes the
        orbits it has already solved; see ``check_derivation``).
    adequacy_result : DeviceAdequacy, optional
        An already computed model-adequacy study (the report's), used instead of running
        it.

    Returns
    -------
    CheckResult
        Frozen; ``source_file`` is the path given ("" for a spec or a derivation).

    Raises
    ------
    SpecError
        The device file, layout or spec is invalid (file, line and field named).
    """
    from betvdesign.checks.checker import check_derivation
    from betvdesign.checks.view import RuleFilter

    opts = options or CheckOptions()
    src = read_source(source)
    layout = src.layout
    if adequacy_result is not None:
        adq: DeviceAdequacy | bool | None = adequacy_result
    else:
        adq = None if opts.adequacy else False
    target = opts.target_speed_m_s
    res = check_derivation(
        src.derivation,
        solver=solver,
        vertical=vertical,
        margin=opts.margin,
        settle=opts.settle,
        target_speed_m_s=target,
        adequacy=adq,
        determine=opts.determine,
        horizon=opts.horizon,
        layout_rules=None if layout is None else layout.rules,
        coupled=opts.coupled,
    )
    notes = res.notes + ([] if layout is None else list(layout.notes))
    res = replace(
        res,
        notes=notes,
        source_file=src.file,
        rule_filter=RuleFilter(opts.select, opts.ignore),
    )
    if opts.advice:
        from betvdesign.studies.fix import advise, with_advice

        full = (
            solver is None
            and vertical is None
            and opts.margin
            and opts.settle is True
            and opts.determine in (None, True)
            and layout is None
        )  # the search's own full check: its outcome is the search's current design
        answers = advise(res, target_speed_m_s=target, horizon=opts.horizon, full=full)
        res = with_advice(res, answers)
    return res


@dataclass(frozen=True)
class DeviceSource:
    """A device read for the check (:func:`read_source`).

    Parameters
    ----------
    derivation : DeviceDerivation
        The derived device.
    file : str
        The file it was read from ("" for a spec or a derivation).
    layout : ExtractedLayout, optional
        For a ``.gds`` file, what :func:`betvdesign.layout.extract.extract` found: the
        process rules measured on the drawing and the notes of the extraction.
    """

    derivation: DeviceDerivation
    file: str = ""
    layout: Any = None


def read_source(
    source: str | os.PathLike[str] | DeviceSpec | DeviceDerivation | DeviceSource,
) -> DeviceSource:
    """Read and derive a device for :func:`run_check` (nothing solved yet).

    Parameters
    ----------
    source : str, pathlib.Path, DeviceSpec, DeviceDerivation or DeviceSource
        A device file (YAML), a layout (``.gds``), a loaded spec or a derivation.

    Returns
    -------
    DeviceSource
        The derivation, the file and, for a layout, its extraction.

    Raises
    ------
    SpecError
        The file, layout or spec is invalid.
    """
    from betvdesign.nondim.device import derive, derive_file
    from betvdesign.nondim.record import DeviceDerivation

    if isinstance(source, DeviceSource):
        return source
    if isinstance(source, DeviceDerivation):
        return DeviceSource(source)
    if isinstance(source, str | os.PathLike):
        if os.fspath(source).lower().endswith(".gds"):
            from betvdesign.layout.extract import derive_gds

            der, layout = derive_gds(source)
            return DeviceSource(der, str(source), layout)
        return DeviceSource(derive_file(source), str(source))
    return DeviceSource(derive(source))


def check(
    device: str | os.PathLike[str] | DeviceSpec | DeviceDerivation,
    options: CheckOptions | None = None,
    **changes: Any,
) -> CheckResult:
    """Check a device the way ``betv check`` does (:func:`run_check`).

    Parameters
    ----------
    device : str, pathlib.Path, DeviceSpec or DeviceDerivation
        A device YAML file, a layout (``.gds``, as ``betv check FILE.gds``) or an already
        loaded (e.g. ``spec.replace(...)``) spec.
    options : CheckOptions, optional
        How to check (default :class:`CheckOptions`: every rule, adequacy and advice).
    **changes
        Fields of :class:`CheckOptions` to change, e.g. ``ignore=["settling"]``,
        ``target_speed="1 mm/s"``, ``advice=False``.

    Returns
    -------
    CheckResult
        ``repr`` is the compact block of ``betv check``, ``_repr_html_`` a notebook
        table, ``.verdict``/``.failed`` count only the selected rules, ``.out`` the JSON
        (:class:`~betvdesign.checks.view.DeviceOut`), ``.sets`` and ``.rules`` the whole
        check.

    Raises
    ------
    SpecError
        The device file or spec is invalid (the message names file, line and field).
    UsageError
        A ``target_speed`` that is not a speed.

    Warns
    -----
    UserWarning
        A ``select``/``ignore`` entry that matches no rule of the device.

    Notes
    -----
    The rules judge the model of Shin et al. [1]_: the push/pull fit
    λ = (κ/ϖ²)(1/(ακ) − (1/β − β)/(22(κ+1))) [-], the exact periodic orbit's Δs [-] and
    the speed Δs·u·cosθ·f_act [m/s].

    References
    ----------
    .. [1] K. Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773
    """
    opts = options or CheckOptions()
    if changes:
        known = [f.name for f in fields(CheckOptions)]
        unknown = sorted(set(changes) - set(known))
        if unknown:
            raise TypeError(
                f"check(): no option {', '.join(unknown)} (CheckOptions: {', '.join(known)})"
            )
        opts = replace(opts, **changes)
    res = run_check(device, opts)
    for message in res.rule_filter.unmatched([res]):
        warnings.warn(message, stacklevel=2)
    return res


def adequacy(device: str | os.PathLike[str] | DeviceSpec) -> DeviceAdequacy:
    """Assess whether the paper's idealised model is adequate for a device.

    The model is undamped with plastic impacts.

    Compares the exact periodic orbit of the model of Shin et al. [1]_ for every actuator
    set without and with head damping and restitution (the device's, or Q = 30 and e = 0.1
    when it gives none) and scans Q over 1–1000 and e over 0–0.9 for a change of mode
    (:mod:`betvdesign.checks.adequacy`).

    Parameters
    ----------
    device : str, pathlib.Path or DeviceSpec
        A device YAML file or an already loaded spec.

    Returns
    -------
    DeviceAdequacy
        ``status`` ("adequate", "speed-differs", "mode-flips", "ideal-fails", "failed"),
        ``adequate``, ``message``, ``text()``; per set (``sets``) the idealised and the
        richer answer (mode, Δs [-], speed [m/s]) and the Q / e at which the mode flips.

    Raises
    ------
    SpecError
        The device file or spec is invalid.

    References
    ----------
    .. [1] K. Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773
    """
    from betvdesign.checks.adequacy import adequacy as _adequacy

    return _adequacy(device)
