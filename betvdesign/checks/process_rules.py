"""The process's design rules, applied to a device file.

The process's design rules, applied to a device file (``betv check``; the same rule ids
come from the drawn polygons when a GDS layout is checked, :mod:`betvdesign.layout.drc`).

Rules (each a :class:`~betvdesign.checks.rule.RuleResult` with its source in the
process file and a fix; device-level, the message names the element):

- ``process.thickness`` (error): every drawn element's thickness is that of its
  structural layer (the slider's ``slider.layer``, a set's ``actuator.geometry.layer``,
  the process's default structural layer otherwise);
- ``process.material`` (warning): the device material's density is the layer's;
- ``process.min-width`` (error): every drawn width is at least the layer's minimum;
- ``process.min-spacing`` (error): every drawn gap (the actuators' arm gaps) is at
  least the layer's minimum spacing;
- ``process.release`` (warning): a feature wider than the widest the release etch frees
  needs etch holes; a device file cannot show them, ``betv layout`` draws them; their
  share of the mass is stated (the model does not count it);
- ``geometry.beam-aspect`` (warning): slider beams at least :data:`SLIDER_ASPECT_MIN`
  times as long as wide (the model's slider is beams joined at both ends; shorter ones
  are plates) and actuator arms at least :data:`ARM_ASPECT_MIN` (the stiffness closed
  form is Euler–Bernoulli beam theory, :mod:`betvdesign.model.frame`).

Devices without ``process`` get the note ``process`` (a warning: the process's rules were
not checked) and the geometry rule, only with an actuator geometry.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from betvdesign.checks.rule import RuleResult
from betvdesign.model.frame import head_covers_tip, head_radius_min
from betvdesign.nondim.actuator import actuator_inputs, frame_geometry
from betvdesign.output.siformat import format_si
from betvdesign.spec.models import ActuatorSet, BoxGeometry, DeviceSpec, DiscGeometry
from betvdesign.spec.process import Process, ProcessLayer

__all__ = [
    "ARM_ASPECT_MIN",
    "SLIDER_ASPECT_MIN",
    "Feature",
    "Gap",
    "drawn_features",
    "drawn_gaps",
    "hole_share",
    "process_rules",
    "release_pitch",
    "rules_from_measurements",
]

#: Slider beams shorter than this many widths are plates, not the model's beams (the
#: published device's widest beams, 45 µm at 170 µm long, have L/w = 3.8).
SLIDER_ASPECT_MIN = 3.0
#: Actuator arms shorter than this many widths leave Euler–Bernoulli beam theory (the
#: closed-form stiffness) by more than its stated error (shear and root compliance grow
#: as (w/L)²  and w/L; benchmarks/bench_layout.py measures it).
ARM_ASPECT_MIN = 10.0
_REL = 1e-9


@dataclass(frozen=True)
class Feature:
    """A drawn element of the device file.

    A drawn element of the device file: ``path`` (field path), ``what`` (words),
    structural ``layer``, ``width`` and ``length`` [m] (length 0 when not a beam),
    ``thickness`` [m] (None when the file gives none), ``aspect_min`` (the smallest
    length/width the model needs, 0 for none) and ``anchored`` (fixed to the substrate:
    no release needed).
    """

    path: str
    what: str
    layer: str
    width: float
    length: float = 0.0
    thickness: float | None = None
    aspect_min: float = 0.0
    anchored: bool = False


@dataclass(frozen=True)
class Gap:
    """A drawn gap between two elements of one layer [m]."""

    path: str
    what: str
    layer: str
    gap: float


def _m(q) -> float:
    return float(q.to("m").magnitude)


def _layer(process: Process | None, name: str | None) -> str:
    if process is None:
        return name or ""
    return process.structural_name(name)


def _head_feature(spec: DeviceSpec, s: ActuatorSet, where: str, layer: str) -> Feature | None:
    """The head of actuator set ``s`` as a drawn element (None when nothing is drawn).

    Parameters
    ----------
    spec : DeviceSpec
        The device.
    s : ActuatorSet
        The set.
    where : str
        The set's field path (``actuator_sets[i]``).
    layer : str
        Its structural layer's name.

    Returns
    -------
    Feature or None
        A disc or box head as drawn; a head given by its mass as the disc of that mass
        when the actuator is drawn; else None.
    """
    head = s.head.geometry
    geo = s.actuator.geometry
    if isinstance(head, DiscGeometry):
        return Feature(
            f"{where}.head.geometry.diameter",
            f"set {s.name}: head (disc)",
            layer,
            _m(head.diameter),
            0.0,
            _m(head.thickness),
        )
    if isinstance(head, BoxGeometry):
        return Feature(
            f"{where}.head.geometry.width",
            f"set {s.name}: head (box)",
            layer,
            min(_m(head.width), _m(head.length)),
            0.0,
            _m(head.thickness),
        )
    if geo is not None:  # a head given by its mass is drawn as the disc of that mass
        r = _m(actuator_inputs(spec, s).head_x)
        return Feature(f"{where}.head.mass", f"set {s.name}: head (disc of its mass)", layer, 2 * r)
    return None


def drawn_features(spec: DeviceSpec) -> list[Feature]:
    """Every drawn element of the device file with its width, length and thickness.

    Parameters
    ----------
    spec : DeviceSpec
        The device.

    Returns
    -------
    list of Feature
        Its slider beams and actuator parts, widths and lengths [m].
    """
    p = spec.process
    sl = spec.slider
    out = [
        Feature(
            "slider.beam_width",
            "slider beam",
            _layer(p, sl.layer),
            _m(sl.beam_width),
            _m(sl.beam_length),
            _m(sl.beam_thickness),
            SLIDER_ASPECT_MIN,
        )
    ]
    seen: set[tuple] = set()
    for i, s in enumerate(spec.actuator_sets):
        geo = s.actuator.geometry
        layer = _layer(p, geo.layer if geo is not None else None)
        feats: list[Feature] = []
        where = f"actuator_sets[{i}]"
        head = _head_feature(spec, s, where, layer)
        if head is not None:
            feats.append(head)
        if geo is not None:
            t = None if geo.thickness is None else _m(geo.thickness)
            g = f"{where}.actuator.geometry"
            L, Lf = _m(geo.length), _m(geo.flexure_length)
            feats += [
                Feature(f"{g}.hot_arm_width", f"set {s.name}: hot arm", layer,
                        _m(geo.hot_arm_width), L, t, ARM_ASPECT_MIN),
                Feature(f"{g}.cold_arm_width", f"set {s.name}: cold arm", layer,
                        _m(geo.cold_arm_width), L - Lf, t),
                Feature(f"{g}.flexure_width", f"set {s.name}: flexure", layer,
                        _m(geo.flexure_width), Lf, t, ARM_ASPECT_MIN),
                Feature(f"{g}.anchor_size", f"set {s.name}: anchor", layer,
                        _m(geo.anchor_size), 0.0, t, anchored=True),
            ]  # fmt: skip
        for f in feats:  # mirrored sets draw the same elements: listed once
            key = (f.what.split(":", 1)[1], f.layer, f.width, f.length, f.thickness)
            if key not in seen:
                seen.add(key)
                out.append(f)
    return out


def drawn_gaps(spec: DeviceSpec) -> list[Gap]:
    """The drawn gaps of the device file (between the arms of each actuator).

    Parameters
    ----------
    spec : DeviceSpec
        The device.

    Returns
    -------
    list of Gap
        The gaps [m].
    """
    p = spec.process
    out: list[Gap] = []
    seen: set[tuple] = set()
    for i, s in enumerate(spec.actuator_sets):
        geo = s.actuator.geometry
        if geo is None:
            continue
        layer = _layer(p, geo.layer)
        g = f"actuator_sets[{i}].actuator.geometry.gap"
        arm = _m(geo.gap)
        flex = arm + (_m(geo.cold_arm_width) - _m(geo.flexure_width)) / 2
        for what, gap in (("hot arm to cold arm", arm), ("hot arm to flexure", flex)):
            key = (what, layer, gap)
            if key not in seen:
                seen.add(key)
                out.append(Gap(g, f"set {s.name}: {what}", layer, gap))
    return out


def _fmt(x: float) -> str:
    return format_si(x, "m")


def _per_layer(p: Process, drawn: Sequence[Feature | Gap], field: str) -> tuple[str, str]:
    """The process's ``field`` of each structural layer ``drawn`` lies on.

    The process's ``field`` of each structural layer ``drawn`` lies on: as words
    ("name: value, ...", by layer name) and as a rule's source (their citations).
    """
    layers = sorted({d.layer for d in drawn})
    text = ", ".join(f"{n}: {_fmt(_m(getattr(p.structural(n), field)))}" for n in layers)
    return text, "; ".join(p.cite(f"layers.{n}.{field}") for n in layers)


def process_rules(spec: DeviceSpec) -> list[RuleResult]:
    """The process rules for a device file.

    The rules of the module docstring for a device file (empty without a process and
    without an actuator geometry).

    Parameters
    ----------
    spec : DeviceSpec
        The device.

    Returns
    -------
    list of RuleResult
        The rules' results.
    """
    feats = drawn_features(spec)
    has_geometry = any(s.actuator.geometry is not None for s in spec.actuator_sets)
    out: list[RuleResult] = []
    if spec.process is not None:
        p = spec.process
        out += [_thickness(p, feats), _material(spec, p), _min_width(p, feats)]
        out += [_min_spacing(p, drawn_gaps(spec)), _release(p, feats)]
    else:
        out.append(_unchecked())
    if spec.process is not None or has_geometry:
        out.append(_aspect(feats))
    if has_geometry:
        out.append(_head_tip(spec))
    return out


def _unchecked() -> RuleResult:
    """The note of a device that names no process.

    The note of a device that names no process: its design rules were not checked (a
    warning, so that every output shows it; it never fails the verdict).
    """
    return RuleResult(
        "process",
        "warning",
        False,
        None,
        "the device names its fabrication process",
        "no process named: the process's design rules (layer thickness, minimum width and "
        "spacing, release) were not checked",
        "device file (process)",
        fix="name the device's process (process: polymumps, a shipped name, or the path of a "
        "process file) so that betv check applies its rules",
    )


def rules_from_measurements(
    spec: DeviceSpec, widths: list[Feature], gaps: list[Gap]
) -> list[RuleResult]:
    """The process rules on measured elements (a layout's polygons).

    The same rules on measured elements (a layout's polygons), for the rule ids the
    measurements replace (:mod:`betvdesign.layout.drc` adds its own width, spacing and
    release findings).

    Parameters
    ----------
    spec : DeviceSpec
        The device extracted from the layout.
    widths : list of Feature
        The measured elements [m].
    gaps : list of Gap
        The measured gaps [m].

    Returns
    -------
    list of RuleResult
        The rules' results.
    """
    assert spec.process is not None
    p = spec.process
    return [
        _thickness(p, widths),
        _material(spec, p),
        _min_width(p, widths),
        _min_spacing(p, gaps),
        _aspect(widths),
    ]


def _thickness_path(f: Feature) -> str:
    """The field giving a drawn element's thickness.

    The field giving a drawn element's thickness (``slider.beam_thickness``,
    ``...head.geometry.thickness``, ``...actuator.geometry.thickness``).
    """
    if f.path.startswith("slider."):
        return "slider.beam_thickness"
    return f"{f.path.rsplit('.', 1)[0]}.thickness"


def _thickness(p: Process, feats: list[Feature]) -> RuleResult:
    bad: list[str] = []
    fixes: list[str] = []
    worst = 0.0
    for f in feats:
        if f.thickness is None:
            continue
        want = _m(p.structural(f.layer).thickness)
        d = abs(f.thickness - want)
        worst = max(worst, d)
        if d > _REL * want:
            bad.append(f"{f.what} {_fmt(f.thickness)} ({_thickness_path(f)})")
            fixes.append(f"set {_thickness_path(f)} to {_fmt(want)} ({f.layer})")
    want_txt, source = _per_layer(p, feats, "thickness")
    ok = not bad
    msg = (
        f"every drawn element has its layer's thickness ({want_txt})"
        if ok
        else f"thickness differs from the layer's ({want_txt}): {'; '.join(bad)}"
    )
    return RuleResult(
        "process.thickness",
        "error",
        ok,
        worst,
        f"thickness = the structural layer's ({want_txt})",
        msg,
        source,
        fix=""
        if ok
        else "; ".join(fixes) + " (the process's film: a deposited layer cannot be thinned), "
        "or draw the element on the layer whose thickness it has (slider.layer, "
        "actuator.geometry.layer)",
        unit="m",
    )


def _material(spec: DeviceSpec, p: Process) -> RuleResult:
    name = p.structural_name(spec.slider.layer)
    want = p.structural(name).density
    have = spec.material.density
    ratio = float((have / want).to("").magnitude)
    ok = abs(ratio - 1.0) <= 1e-6
    w, h = (f"{float(q.to('kg/m^3').magnitude):g} kg/m³" for q in (want, have))
    return RuleResult(
        "process.material",
        "warning",
        ok,
        ratio,
        f"material density / layer {name}'s ({w}) = 1",
        f"material {spec.material.name} has density {h}; layer {name}: {w}"
        + ("" if ok else ": the masses use the material's"),
        p.cite(f"layers.{name}.density"),
        fix="" if ok else f"give material.density {w} (the process's film)",
    )


@dataclass(frozen=True)
class _Minimum:
    """A process minimum checked on drawn elements.

    A process minimum checked on drawn elements: its rule id, the elements' measure
    (``width`` of a :class:`Feature`, ``gap`` of a :class:`Gap`), the rule's words, what
    to change for one element below it (``advice(element, minimum)``) and the reason
    that closes the fix.
    """

    rule: str
    measure: str
    limit: str
    extreme: str
    below: str
    advice: Callable[[Any, float], str]
    why: str


def _widen_line(f: Feature, mn: float) -> str:
    """What to change for one drawn element narrower than the process allows."""
    if f.path.endswith(".head.mass"):
        return f"give {f.path} a head whose disc is ≥ {_fmt(mn)} wide (process.min-width)"
    return f"widen {f.path} to ≥ {_fmt(mn)} (process.min-width)"


def _widen_gap(g: Gap, mn: float) -> str:
    """What to change for one drawn gap narrower than the process's spacing."""
    return f"widen {g.path} by ≥ {_fmt(mn - g.gap)} ({g.what} to ≥ {_fmt(mn)}; process.min-spacing)"


_MINIMA = {
    "min_width": _Minimum(
        "process.min-width",
        "width",
        "minimum",
        "narrowest",
        "below the process's minimum width",
        _widen_line,
        ": the process cannot define narrower lines (`betv fix FILE --vary FIELD=LO:HI` "
        "keeps the design passing while you do)",
    ),
    "min_spacing": _Minimum(
        "process.min-spacing",
        "gap",
        "minimum spacing",
        "smallest",
        "gaps below the process's minimum spacing",
        _widen_gap,
        ": narrower gaps do not open in the process",
    ),
}


def _at_least_minimum(p: Process, drawn: Sequence[Feature | Gap], field: str) -> RuleResult:
    """The rule of the layer's minimum ``field`` on ``drawn``.

    The rule of the layer's minimum ``field`` (a key of :data:`_MINIMA`) on ``drawn``
    (not empty), with what to change for each element below it.
    """
    m = _MINIMA[field]
    bad, ratio, fixes = [], [], []
    for d in drawn:
        have, mn = getattr(d, m.measure), _m(getattr(p.structural(d.layer), field))
        ratio.append((have / mn, d))
        if have < mn * (1 - _REL):
            bad.append(f"{d.what} {_fmt(have)} < {_fmt(mn)} ({d.path})")
            fixes.append(m.advice(d, mn))
    _, worst = min(ratio, key=lambda x: x[0])  # the nearest its minimum (first of equals)
    mins, source = _per_layer(p, drawn, field)
    size = getattr(worst, m.measure)
    ok = not bad
    msg = (
        f"every drawn {m.measure} is at least the {m.limit} ({mins}); {m.extreme}: "
        f"{worst.what} {_fmt(size)}"
        if ok
        else f"{m.below}: {'; '.join(bad)}"
    )
    return RuleResult(
        m.rule,
        "error",
        ok,
        size,
        f"{m.measure} >= {m.limit} ({mins})",
        msg,
        source,
        fix="" if ok else "; ".join(fixes) + m.why,
        unit="m",
    )


def _min_width(p: Process, feats: list[Feature]) -> RuleResult:
    return _at_least_minimum(p, feats, "min_width")


def _min_spacing(p: Process, gaps: list[Gap]) -> RuleResult:
    if not gaps:
        return RuleResult(
            "process.min-spacing",
            "error",
            True,
            None,
            "gap >= minimum spacing",
            "no drawn gaps in the device file (give actuator.geometry; the layout check "
            "measures every gap)",
            p.source,
            unit="m",
        )
    return _at_least_minimum(p, gaps, "min_spacing")


def release_pitch(layer: ProcessLayer) -> float:
    """Hole pitch [µm] a layout draws on ``layer``.

    Hole pitch [µm] a layout draws on ``layer``: the process's pitch, or less so that no
    point of a square lattice lies farther than half the widest unreleased feature from a
    hole: (pitch − size)/√2 ≤ w_max/2.

    Parameters
    ----------
    layer : ProcessLayer
        A structural layer with release holes.

    Returns
    -------
    float
        The pitch [µm].
    """
    h = layer.release_holes
    assert h is not None and layer.max_unreleased_width is not None
    size = float(h.size.to("um").magnitude)
    w_max = float(layer.max_unreleased_width.to("um").magnitude)
    return min(float(h.pitch.to("um").magnitude), size + w_max / math.sqrt(2) - 0.01)


def hole_share(p: Process, layer: str) -> float:
    """The share of a feature's area its release holes take [-].

    The share of a feature's area its release holes take [-]: size²/pitch² at the
    pitch :func:`release_pitch` draws.

    Parameters
    ----------
    p : Process
        The process.
    layer : str
        The structural layer (one with release holes).

    Returns
    -------
    float
        size²/pitch² [-].
    """
    lay = p.structural(layer)
    h = lay.release_holes
    assert h is not None
    return (float(h.size.to("um").magnitude) / release_pitch(lay)) ** 2


def _release(p: Process, feats: list[Feature]) -> RuleResult:
    wide = []
    for f in feats:
        lay = p.structural(f.layer)
        mx = _m(lay.max_unreleased_width)
        if not f.anchored and f.width > mx * (1 + _REL):
            h = lay.release_holes
            wide.append(
                f"{f.what} {_fmt(f.width)} > {_fmt(mx)} ({_fmt(_m(h.size))} holes at "
                f"{release_pitch(lay):.3g} µm pitch take {hole_share(p, f.layer):.1%} of its "
                "mass, not in the model)"
            )
    widest = max((f for f in feats if not f.anchored), key=lambda f: f.width)
    mx, source = _per_layer(p, feats, "max_unreleased_width")
    ok = not wide
    msg = (
        f"every released feature is narrower than the widest the release etch frees without "
        f"holes ({mx}); widest: {widest.what} {_fmt(widest.width)}"
        if ok
        else "needs etch holes: " + "; ".join(wide)
    )
    return RuleResult(
        "process.release",
        "warning",
        ok,
        widest.width,
        f"width <= {mx} or etch holes",
        msg,
        source,
        fix="" if ok else "`betv layout` draws the holes; or narrow it below the limit",
        unit="m",
    )


def _head_tip(spec: DeviceSpec) -> RuleResult:
    """Each drawn head covers its actuator's tip connector end (no notch at the joint)."""
    bad, seen = [], set()
    for s in spec.actuator_sets:
        if s.actuator.geometry is None:
            continue
        g = frame_geometry(spec, s)
        key = repr(g)
        if key in seen or bool(head_covers_tip(g)):
            seen.add(key)
            continue
        seen.add(key)
        if g.head_shape == "box":
            need = f"a box at least {_fmt(float(g.tip_height))} wide"
        else:
            need = f"a disc at least {_fmt(2 * float(head_radius_min(g)))} across"
        bad.append(f"set {s.name}: {need} covers the tip (H = {_fmt(float(g.tip_height))})")
    ok = not bad
    return RuleResult(
        "geometry.head-tip",
        "warning",
        ok,
        None,
        "the head covers the tip connector's end",
        "every head covers its tip connector's end: the outline meets it at obtuse angles"
        if ok
        else "the head leaves the tip's end exposed; the outline has acute notches there that "
        "spacing rules flag and the etch rounds: " + "; ".join(bad),
        "betvdesign.model.frame (the drawn actuator's convention)",
        fix=""
        if ok
        else "a larger head, a longer tip (actuator.geometry.tip_length) or a narrower tip "
        "(cold arm, gap, hot arm)",
    )


def _aspect(feats: list[Feature]) -> RuleResult:
    bad = []
    worst = None
    for f in feats:
        if f.aspect_min <= 0 or f.length <= 0:
            continue
        r = f.length / f.width
        if worst is None or r / f.aspect_min < worst[0]:
            worst = (r / f.aspect_min, r, f)
        if r < f.aspect_min:
            bad.append(f"{f.what} L/w = {r:.3g} < {f.aspect_min:g}")
    ok = not bad
    value = None if worst is None else worst[1]
    msg = (
        "beams are long against their width"
        + ("" if worst is None else f" (lowest: {worst[2].what}, L/w = {worst[1]:.3g})")
        if ok
        else "too short for a beam: " + "; ".join(bad)
    )
    return RuleResult(
        "geometry.beam-aspect",
        "warning",
        ok,
        value,
        f"L/w >= {SLIDER_ASPECT_MIN:g} (slider beams), >= {ARM_ASPECT_MIN:g} (actuator arms)",
        msg,
        "MODEL.md: the slider is beams joined at both ends; the head's springs are "
        "Euler–Bernoulli beam theory (betvdesign.model.frame)",
        fix="" if ok else "lengthen the beam or narrow it (the model's assumptions then hold)",
    )
