"""HTML and plot data of the explore page, from plain data (no Bokeh here).

The verdict block is built from the ``betv check --json`` device object
(:class:`betvdesign.checks.view.DeviceOut`, as :class:`~betvdesign.explore.compute.Evaluation`
carries it): the same verdict, modes, speeds, rules and fix texts as ``betv check``.
Machine-readable ``data-`` attributes (verdict, stage, mode, speed) let tests compare
the page with ``betv check --json``.
"""

from __future__ import annotations

import html
import math
from typing import Any

from betvdesign.checks.rule import no_crossing
from betvdesign.explore.compute import STAGES
from betvdesign.model.domain import VARPI_WINDOW, in_window
from betvdesign.output.presentation import MODE_COLORS, PENDING_COLOR, STATUS_COLORS, rule_status
from betvdesign.output.siformat import format_si
from betvdesign.studies.fieldmap import MAP_MODES, FieldMap

_CELL = "font-weight:bold;padding-right:6px;vertical-align:top"

#: The first stage whose answer decides the modes (how well Δs is determined and the
#: travel from rest: an orbit's mode may still become "undetermined" or the crossing's);
#: before it the page shows no mode, no speed and no verdict, only "computing".
MODE_STAGE = "settling"


def mode_decided(stage: str) -> bool:
    """Whether the answer of ``stage`` (:data:`betvdesign.explore.compute.STAGES`) decides
    the modes, speeds and verdict (:data:`MODE_STAGE` or a later stage)."""
    order = list(STAGES)
    return order.index(stage) >= order.index(MODE_STAGE)


__all__ = [
    "basis_html",
    "error_html",
    "fixes_html",
    "legend_html",
    "map_cells",
    "mode_decided",
    "no_orbit_html",
    "status_html",
    "verdict_html",
]


def _e(x: Any) -> str:
    return html.escape(str(x), quote=True)


def _motion(s: dict[str, Any], settling: dict[str, Any] | None) -> str:
    mode = s["mode"]
    if mode in ("push", "pull"):
        head = (
            f"{mode} as intended"
            if mode == s["intended_mode"]
            else f"{mode}, intended {s['intended_mode']}"
        )
    else:
        head = f"{mode} (intended {s['intended_mode']})"
    v = s.get("speed_m_s")
    parts = [f"<b>{_e(head)}</b>"]
    if v:
        travel = format_si(s["travel_range_m"], "m")
        cross = format_si(s["time_to_cross_s"], "s")
        speed = format_si(v, "m/s")
        parts.append(
            f"{_e(speed)} toward {_e(s['travel_direction'])}; {_e(travel)} travel in {_e(cross)}"
        )
    elif v == 0.0:
        parts.append("the slider does not move")
    basis = s.get("basis")  # which answer the verdict quotes (checks.travel)
    if basis == "crossing":
        parts.append("over the travel from rest (not settled by then)")
    elif basis == "no-crossing":
        cycles = (settling or {}).get("simulated_cycles")
        f_act = (settling or {}).get("f_act_hz")
        parts.append(
            f"the slider {no_crossing(s['travel_range_m'], int(cycles), f_act)}"
            if cycles and f_act
            else "the slider does not cross its travel range"
        )
    elif basis == "undetermined":
        parts.append("Δs not determined in float64 (see the mode rule)")
    if settling:
        f_act = settling.get("f_act_hz") or math.nan
        n = settling.get("cycles_to_settle")
        if n is not None:
            parts.append(f"settles in {n} cycles ({_e(format_si(n / f_act, 's'))})")
        else:
            parts.append(f"not settled after {settling.get('simulated_cycles')} cycles")
        c = settling.get("cycles_to_cross")
        if c is not None:
            parts.append(
                f"crosses the travel range after {c} cycles ({_e(format_si(c / f_act, 's'))})"
            )
    margin = s.get("margin") or {}
    if margin.get("holds") is True:
        parts.append("mode holds at ϖ ±5 %, α ±10 %")
    elif margin.get("holds") is False:
        flips = [k for k, m in (margin.get("corners") or {}).items() if m != mode]
        parts.append(f"<b>mode flips at {_e(', '.join(flips))}</b>")
    return "; ".join(parts)


def verdict_html(
    out: dict[str, Any],
    *,
    seq: int,
    stage: str,
    settling: dict[str, dict[str, Any] | None] | None = None,
    pending: list[str] | None = None,
    timing: dict[str, float] | None = None,
) -> str:
    """The verdict block: overall verdict, one line per set, every rule with its fix;
    ``timing`` (name -> value) goes into ``data-`` attributes (benchmarks read them).
    Before the stage that decides the modes (:func:`mode_decided`) it shows "computing"
    in place of the verdict, the modes, the speeds and the rules."""
    decided = mode_decided(stage)
    verdict = out["verdict"] if decided else "computing"
    colour = {"pass": STATUS_COLORS["pass"], "fail": STATUS_COLORS["FAIL"]}.get(
        verdict, STATUS_COLORS["info"]
    )
    rows = []
    for s in out["sets"]:
        speed = "" if s.get("speed_m_s") is None or not decided else repr(float(s["speed_m_s"]))
        mode = s["mode"] if decided else "computing"
        motion = (
            _motion(s, (settling or {}).get(s["name"]))
            if decided
            else "<b>computing the mode…</b> (decided once Δs is determined and the "
            "travel from rest is simulated)"
        )
        rows.append(
            f'<tr class="betv-set" data-set="{_e(s["name"])}" data-mode="{_e(mode)}" '
            f'data-speed-m-s="{speed}" data-direction="{_e(s.get("travel_direction") or "")}">'
            f'<th style="text-align:left;padding-right:8px">{_e(s["name"])}</th>'
            f"<td>{motion}</td></tr>"
        )
    rules = []
    for s in out["sets"] if decided else ():
        rules += [(s["name"], r) for r in s["rules"]]
    rules += [("", r) for r in out.get("rules", [])] if decided else []
    several = len(out["sets"]) > 1
    lines = []
    for set_name, r in rules:
        tag = rule_status(r["passed"], r["severity"])
        col = STATUS_COLORS[tag]
        where = f" [{_e(set_name)}]" if several and set_name else ""
        fix = (
            f'<div class="betv-fix" style="color:#0969da">fix: {_e(r["fix"])}</div>'
            if r["fix"] and not r["passed"]
            else ""
        )
        passed = str(r["passed"]).lower()
        lines.append(
            f'<tr class="betv-rule" data-rule="{_e(r["id"])}" data-passed="{passed}">'
            f'<td style="color:{col};{_CELL}">{tag}</td>'
            f'<td style="vertical-align:top"><code>{_e(r["id"])}</code>{where}: '
            f"{_e(r['message'])}{fix}</td></tr>"
        )
    if pending:
        waiting = f"still computing: {_e(', '.join(pending))}…"
        waiting = f'<div class="betv-pending" style="color:#9a6700">{waiting}</div>'
    elif not decided:  # the deciding stage failed (the status says why)
        waiting = (
            '<div class="betv-pending" style="color:#cf222e">the stage that decides the '
            "modes did not answer (see the status line)</div>"
        )
    else:
        waiting = (
            '<div class="betv-pending" style="color:#57606a">every stage of betv check done</div>'
        )

    extra = "".join(f' data-{_e(k)}="{v:.3f}"' for k, v in (timing or {}).items())
    return (
        f'<div class="betv-verdict" data-verdict="{_e(verdict)}" data-seq="{seq}" '
        f'data-stage="{_e(stage)}"{extra}>'
        f'<div style="font-size:22px;font-weight:bold;color:{colour}">{verdict.upper()}'
        f'<span style="font-size:13px;color:#57606a;font-weight:normal"> design #{seq}</span></div>'
        f"{waiting}"
        f'<table style="border-collapse:collapse;margin:4px 0">{"".join(rows)}</table>'
        f'<table style="border-collapse:collapse;font-size:12px">{"".join(lines)}</table></div>'
    )


def status_html(text: str, *, busy: bool) -> str:
    """A one-line status (the map's progress, a save or report message)."""
    colour = "#9a6700" if busy else "#57606a"
    return f'<span class="betv-status-text" style="color:{colour}">{_e(text)}</span>'


def fixes_html(fixes: list[dict[str, Any]], message: str) -> str:
    """The changes ``betv fix`` found (its JSON candidates), numbered as the apply
    buttons; ``message``: what ``betv fix`` said when it found none."""
    if not fixes:
        return status_html(f"betv fix: {message}", busy=False) if message else ""
    items = []
    for c in fixes:
        change = "; ".join(f"{ch['field']} {ch['from']} → {ch['to']}" for ch in c["changes"])
        items.append(f'<li class="betv-fix-item">{_e(change)}: {_e(c["why"])}</li>')
    return (
        "<b>betv fix finds (drawn on the map when on its axes):</b>"
        f'<ol style="margin:2px 0;padding-left:18px">{"".join(items)}</ol>'
    )


#: What the orbit plots are beside the verdict, by the verdict's basis
#: (:mod:`betvdesign.checks.travel`); None: not decided yet.
PLOT_BASIS = {
    None: "The plots show the periodic orbit; which answer the verdict quotes is decided "
    "with the settling from rest.",
    "periodic": "The plots show the periodic orbit, the answer the verdict quotes.",
    "crossing": "Basis: the verdict quotes the crossing of the travel from rest (the "
    "slider has not settled by then), not this periodic orbit; its speed is the "
    "crossing's.",
    "no-crossing": "Basis: the verdict quotes the travel from rest, which does not cross "
    "the travel range; the plots show the periodic orbit it would settle to.",
    "undetermined": "Basis: Δs is not determined in float64; the plots show the orbit "
    "the solver found, which decides nothing.",
}


def basis_html(basis: str | None, mode: str | None = None) -> str:
    """The line over the orbit plots saying which answer they show beside the verdict's
    basis (``data-basis``: that basis, "" before it is decided)."""
    text = PLOT_BASIS.get(basis, PLOT_BASIS[None] if basis is None else f"Basis: {basis}.")
    colour = "#9a6700" if basis in ("crossing", "no-crossing", "undetermined") else "#57606a"
    return (
        f'<div class="betv-orbit-basis" data-basis="{_e(basis or "")}" '
        f'style="color:{colour};font-size:12px">{_e(text)}</div>'
    )


def model_note_html(text: str) -> str:
    """A warning over the orbit plots (e.g. that they are not the verdict's model's)."""
    return (
        '<div class="betv-model-note" style="color:#cf222e;font-size:12px">'
        f"<b>warning</b>: {_e(text)}</div>"
    )


def no_orbit_html(reason: str, *, computing: bool = False) -> str:
    """What stands in place of the orbit plots when there are none: "no periodic orbit:
    REASON" (or that the orbit is being computed)."""
    if computing:
        return '<div class="betv-no-orbit" data-computing="true"><i>computing the orbit…</i></div>'
    return (
        '<div class="betv-no-orbit" style="color:#cf222e;font-size:14px;padding:8px 0">'
        f"<b>no periodic orbit</b>: {_e(reason)}</div>"
    )


def error_html(text: str) -> str:
    """A refused value's message, beside its control."""
    return f'<span class="betv-error" style="color:#cf222e">{_e(text)}</span>'


#: Columns of the map's data source (see :func:`map_cells`).
MAP_COLUMNS = (
    "left",
    "right",
    "bottom",
    "top",
    "color",
    "mode",
    "speed",
    "xv",
    "yv",
    "window",
    "varpi",
    "basis",
)


def _pale(colour: str) -> str:
    """``colour`` (#rrggbb) mixed half and half with white."""
    rgb = [int(colour[k : k + 2], 16) for k in (1, 3, 5)]
    return "#" + "".join(f"{(c + 255) // 2:02x}" for c in rgb)


def map_cells(fmap: FieldMap) -> dict[str, list[Any]]:
    """Quads of the map (edges in the fields' units), colour and hover text per cell."""
    xe, ye = fmap.x.edges(), fmap.y.edges()
    data: dict[str, list[Any]] = {k: [] for k in MAP_COLUMNS}
    for j in range(len(fmap.y.values)):
        for i in range(len(fmap.x.values)):
            data["left"].append(float(xe[i]))
            data["right"].append(float(xe[i + 1]))
            data["bottom"].append(float(ye[j]))
            data["top"].append(float(ye[j + 1]))
            m = str(fmap.mode[j, i])
            w = fmap.varpi[j, i]
            outside = math.isfinite(w) and not in_window(float(w))
            colour = MODE_COLORS.get(m, PENDING_COLOR)
            data["color"].append(_pale(colour) if outside else colour)
            data["mode"].append(m or "computing")
            v = fmap.speed_m_s[j, i]
            data["speed"].append("" if not math.isfinite(v) else format_si(abs(v), "m/s"))
            data["window"].append("(outside the design window)" if outside else "")
            data["varpi"].append("" if not math.isfinite(w) else f"{w:.3g}")
            data["basis"].append(BASIS_WORDS.get(str(fmap.basis[j, i]), ""))
            data["xv"].append(f"{fmap.x.values[i]:.4g} {fmap.x.unit}".strip())
            data["yv"].append(f"{fmap.y.values[j]:.4g} {fmap.y.unit}".strip())
    return data


#: What a map cell's answer rests on (:mod:`betvdesign.checks.travel`'s basis), as the
#: tooltip says it.
BASIS_WORDS = {
    "periodic": "periodic orbit (settles early in the travel)",
    "crossing": "crossing of the travel from rest (not settled by then)",
    "no-crossing": "does not cross the travel from rest within the horizon",
    "no-orbit": "no periodic orbit",
}


def legend_html() -> str:
    """The map's colour legend: each swatch with its word on one line (never split
    between lines), then what pale cells and the cells' basis mean."""
    items = [
        '<span class="betv-legend-item" style="white-space:nowrap;display:inline-block;'
        'margin:0 8px 2px 0"><span style="display:inline-block;width:10px;height:10px;'
        f'background:{MODE_COLORS[m]};border:1px solid #888;margin-right:3px"></span>'
        f"{_e(m)}</span>"
        for m in MAP_MODES
    ]
    lo, hi = VARPI_WINDOW
    notes = [
        f"pale: outside the design window {lo:g} ≤ ϖ < {hi:g}",
        "each cell is betv check's answer over the travel: the periodic orbit, or the "
        "crossing from rest where the slider has not settled (hover: basis)",
    ]
    return (
        f'<div class="betv-legend" style="font-size:12px;line-height:1.4">{"".join(items)}'
        + "".join(f"<div>{_e(n)}</div>" for n in notes)
        + "</div>"
    )
