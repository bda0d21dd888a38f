"""The process's design rules, applied to a device file (``betv check``; the same rule ids
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
from dataclasses import dataclass

from betvdesign.checks.rule import RuleResult
from betvdesign.model.frame import head_covers_tip, head_radius_min
from betvdesign.nondim.actuator import actuator_inputs, frame_geometry
from betvdesign.output.siformat import format_si
from betvdesign.spec.models import BoxGeometry, DeviceSpec, DiscGeometry
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
    """A drawn element of the device file: ``path`` (field path), ``what`` (words),
    structural ``layer``, ``width`` and ``length`` [m] (length 0 when not a beam),
    ``thickness`` [m] (None when the file gives none), ``aspect_min`` (the smallest
    length/width the model needs, 0 for none) and ``anchored`` (fixed to the substrate:
    no release needed)."""

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


def drawn_features(spec: DeviceSpec) -> list[Feature]:
    """Every drawn element of the device file with its width, length and thickness."""
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
        head = s.head.geometry
        feats: list[Feature] = []
        where = f"actuator_sets[{i}]"
        if isinstance(head, DiscGeometry):
            feats.append(
                Feature(
                    f"{where}.head.geometry.diameter",
                    f"set {s.name}: head (disc)",
                    layer,
                    _m(head.diameter),
                    0.0,
                    _m(head.thickness),
                )
            )
        elif isinstance(head, BoxGeometry):
            feats.append(
                Feature(
                    f"{where}.head.geometry.width",
                    f"set {s.name}: head (box)",
                    layer,
                    min(_m(head.width), _m(head.length)),
                    0.0,
                    _m(head.thickness),
                )
            )
        elif geo is not None:  # a head given by its mass is drawn as the disc of that mass
            r = _m(actuator_inputs(spec, s).head_x)
            feats.append(
                Feature(
                    f"{where}.head.mass", f"set {s.name}: head (disc of its mass)", layer, 2 * r
                )
            )
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
    """The drawn gaps of the device file (between the arms of each actuator)."""
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


def process_rules(spec: DeviceSpec) -> list[RuleResult]:
    """The rules of the module docstring for a device file (empty without a process and
    without an actuator geometry)."""
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
    """The note of a device that names no process: its design rules were not checked (a
    warning, so that every output shows it; it never fails the verdict)."""
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
    """The same rules on measured elements (a layout's polygons), for the rule ids the
    measurements replace (:mod:`betvdesign.layout.drc` adds its own width, spacing and
    release findings)."""
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
    """The field giving a drawn element's thickness (``slider.beam_thickness``,
    ``...head.geometry.thickness``, ``...actuator.geometry.thickness``)."""
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
    layers = sorted({f.layer for f in feats})
    want_txt = ", ".join(f"{n}: {_fmt(_m(p.structural(n).thickness))}" for n in layers)
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
        "; ".join(p.cite(f"layers.{n}.thickness") for n in layers),
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


def _min_width(p: Process, feats: list[Feature]) -> RuleResult:
    bad, ratio, fixes = [], [], []
    for f in feats:
        mn = _m(p.structural(f.layer).min_width)
        ratio.append((f.width / mn, f))
        if f.width < mn * (1 - _REL):
            bad.append(f"{f.what} {_fmt(f.width)} < {_fmt(mn)} ({f.path})")
            fixes.append(
                f"give {f.path} a head whose disc is ≥ {_fmt(mn)} wide (process.min-width)"
                if f.path.endswith(".head.mass")
                else f"widen {f.path} to ≥ {_fmt(mn)} (process.min-width)"
            )
    _, worst = min(ratio, key=lambda x: x[0])
    layers = sorted({f.layer for f in feats})
    mins = ", ".join(f"{n}: {_fmt(_m(p.structural(n).min_width))}" for n in layers)
    ok = not bad
    msg = (
        f"every drawn width is at least the minimum ({mins}); narrowest: {worst.what} "
        f"{_fmt(worst.width)}"
        if ok
        else f"below the process's minimum width: {'; '.join(bad)}"
    )
    return RuleResult(
        "process.min-width",
        "error",
        ok,
        worst.width,
        f"width >= minimum ({mins})",
        msg,
        "; ".join(p.cite(f"layers.{n}.min_width") for n in layers),
        fix=""
        if ok
        else "; ".join(fixes) + ": the process cannot define narrower lines "
        "(`betv fix FILE --vary FIELD=LO:HI` keeps the design passing while you do)",
        unit="m",
    )


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
    bad, fixes = [], []
    for g in gaps:
        mn = _m(p.structural(g.layer).min_spacing)
        if g.gap < mn * (1 - _REL):
            bad.append(f"{g.what} {_fmt(g.gap)} < {_fmt(mn)} ({g.path})")
            fixes.append(
                f"widen {g.path} by ≥ {_fmt(mn - g.gap)} ({g.what} to ≥ {_fmt(mn)}; "
                "process.min-spacing)"
            )
    worst = min(gaps, key=lambda g: g.gap / _m(p.structural(g.layer).min_spacing))
    layers = sorted({g.layer for g in gaps})
    mins = ", ".join(f"{n}: {_fmt(_m(p.structural(n).min_spacing))}" for n in layers)
    ok = not bad
    msg = (
        f"every drawn gap is at least the minimum spacing ({mins}); smallest: {worst.what} "
        f"{_fmt(worst.gap)}"
        if ok
        else f"gaps below the process's minimum spacing: {'; '.join(bad)}"
    )
    return RuleResult(
        "process.min-spacing",
        "error",
        ok,
        worst.gap,
        f"gap >= minimum spacing ({mins})",
        msg,
        "; ".join(p.cite(f"layers.{n}.min_spacing") for n in layers),
        fix="" if ok else "; ".join(fixes) + ": narrower gaps do not open in the process",
        unit="m",
    )


def release_pitch(layer: ProcessLayer) -> float:
    """Hole pitch [µm] a layout draws on ``layer``: the process's pitch, or less so that no
    point of a square lattice lies farther than half the widest unreleased feature from a
    hole: (pitch − size)/√2 ≤ w_max/2."""
    h = layer.release_holes
    assert h is not None and layer.max_unreleased_width is not None
    size = float(h.size.to("um").magnitude)
    w_max = float(layer.max_unreleased_width.to("um").magnitude)
    return min(float(h.pitch.to("um").magnitude), size + w_max / math.sqrt(2) - 0.01)


def hole_share(p: Process, layer: str) -> float:
    """The share of a feature's area its release holes take [-]: size²/pitch² at the
    pitch :func:`release_pitch` draws."""
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
    layers = sorted({f.layer for f in feats})
    mx = ", ".join(f"{n}: {_fmt(_m(p.structural(n).max_unreleased_width))}" for n in layers)
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
        "; ".join(p.cite(f"layers.{n}.max_unreleased_width") for n in layers),
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
