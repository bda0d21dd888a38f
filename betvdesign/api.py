"""Notebook and script entry points: check a device file or an edited spec in one call.

``betvdesign.check`` is :func:`check`; the command line's ``betv check`` shows the same
view (:class:`betvdesign.checks.view.DeviceView`). ``betvdesign.adequacy`` is
:func:`adequacy`: is the paper's idealised model enough for the device?
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Sequence
from typing import TYPE_CHECKING

from betvdesign.checks.view import DeviceView, RuleFilter

if TYPE_CHECKING:
    from betvdesign.checks.adequacy import DeviceAdequacy
    from betvdesign.spec.models import DeviceSpec


def check(
    device: str | os.PathLike[str] | DeviceSpec,
    *,
    select: Sequence[str] = (),
    ignore: Sequence[str] = (),
    target_speed: str | None = None,
    advice: bool = True,
) -> DeviceView:
    """Check a device the way ``betv check`` does and return its view.

    Parameters
    ----------
    device : str, pathlib.Path or DeviceSpec
        A device YAML file or an already loaded (e.g. ``spec.replace(...)``) spec.
    select, ignore : sequence of str
        Rule ids (or dotted prefixes) that count / do not count (``--select/--ignore``).
    target_speed : str, optional
        Required slider speed with its unit, e.g. ``"1 mm/s"`` (adds the rule
        ``target-speed``).
    advice : bool
        For a failing check, quote the nearest passing value of the fields that move
        what fails as the rules' fix (the search of ``betv fix``;
        :func:`betvdesign.studies.fix.advise`).

    Returns
    -------
    DeviceView
        ``repr`` is the compact block, ``_repr_html_`` a notebook table, ``.out`` the
        JSON (:class:`~betvdesign.checks.view.DeviceOut`), ``.result`` the full
        :class:`~betvdesign.checks.checker.CheckResult`.

    Raises
    ------
    SpecError
        The device file or spec is invalid (the message names file, line and field).
    UsageError
        A ``target_speed`` that is not a speed.

    Notes
    -----
    The rules judge the model of Shin et al. [1]_: the push/pull fit
    λ = (κ/ϖ²)(1/(ακ) − (1/β − β)/(22(κ+1))) [-], the exact periodic orbit's Δs [-] and
    the speed Δs·u·cosθ·f_act [m/s].

    References
    ----------
    .. [1] K. Shin et al., J. Appl. Phys. 96, 7603 (2004), doi:10.1063/1.1809773
    """
    from betvdesign.checks.checker import check_derivation
    from betvdesign.nondim.device import derive, derive_file
    from betvdesign.spec.units import parse_speed

    if isinstance(device, str | os.PathLike):
        d, source = derive_file(device), str(device)
    else:
        d, source = derive(device), ""
    target = None if target_speed is None else parse_speed(target_speed, "target_speed")
    res = check_derivation(d, target_speed_m_s=target)
    if advice:
        from betvdesign.studies.fix import advise, with_advice

        res = with_advice(res, advise(res, target_speed_m_s=target))
    res.source_file = source
    flt = RuleFilter(tuple(select), tuple(ignore))
    for message in flt.unmatched([res]):
        warnings.warn(message, stacklevel=2)
    return DeviceView(res, flt)


def adequacy(device: str | os.PathLike[str] | DeviceSpec) -> DeviceAdequacy:
    """Is the paper's idealised model (undamped, plastic impacts) adequate for a device?

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
