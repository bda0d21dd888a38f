"""Notebook and script entry points: check a device file or an edited spec in one call.

``betvdesign.check`` is :func:`check`; the command line's ``betv check`` shows the same
view (:class:`betvdesign.checkview.DeviceView`).
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import Any

from betvdesign.checkview import DeviceView, RuleFilter


def check(
    device: Any,
    *,
    select: Sequence[str] = (),
    ignore: Sequence[str] = (),
    lambda_margin: float | None = None,
) -> DeviceView:
    """Check a device the way ``betv check`` does and return its view.

    Parameters
    ----------
    device : str, pathlib.Path or DeviceSpec
        A device YAML file or an already loaded (e.g. ``spec.replace(...)``) spec.
    select, ignore : sequence of str
        Rule ids (or dotted prefixes) that count / do not count (``--select/--ignore``).
    lambda_margin : float, optional
        Required |λ − 1| [-] (default: the rules' default).

    Returns
    -------
    DeviceView
        ``repr`` is the compact block, ``_repr_html_`` a notebook table, ``.out`` the
        JSON (:class:`DeviceOut`), ``.result`` the full :class:`CheckResult`.
    """
    from betvdesign.checker import check_derivation
    from betvdesign.nondim import derive, derive_file

    if isinstance(device, str | os.PathLike):
        d, source = derive_file(device), str(device)
    else:
        d, source = derive(device), ""
    kwargs = {} if lambda_margin is None else {"lambda_margin": lambda_margin}
    res = check_derivation(d, **kwargs)
    res.source_file = source
    flt = RuleFilter(tuple(select), tuple(ignore))
    flt.validate([res])
    return DeviceView(res, flt)
