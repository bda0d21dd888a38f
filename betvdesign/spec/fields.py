"""The fields a designer changes: the one list.

A designer sets drive frequencies, beam widths, head sizes, resonances and contact
surfaces, not ϖ, α, β or κ. :data:`FIELDS` lists those fields of a device file, each with
what it moves in the model and how it is set, in the order that ranks them:
operating (drive) settings first, then the drawing, the head's suspension, the impact
angle, the drawn actuator's dimensions (in place of the suspension where the file gives
none), the contact's friction. Read by

- ``betv fix`` (:mod:`betvdesign.studies.fixfields`): the fields the designer chooses
  (:attr:`DesignField.chosen`) are varied by default, within :attr:`DesignField.bounds`;
  ties between equally small changes go to the earlier field;
- the report's robustness figure (:mod:`betvdesign.report.variants`): per physical
  quantity (:attr:`DesignField.quantity`) the first field the device gives, of those
  that move a model parameter (a change of the stroke alone scales the speed and
  cannot flip the mode);
- anything else that offers a designer these knobs (e.g. an explorer).

The physical quantities and relations are those of MODEL.md, "Physical quantities" and
"Device-to-parameter relations" (Shin et al., J. Appl. Phys. 96, 7603 (2004),
doi:10.1063/1.1809773): ϖ = ω·sqrt(m/k_v) = f_act/f_v, α = k_v/k_h, β = m/M,
κ = μ·tanθ and the length scale ℓ = u·cosθ.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

#: How a field is set: at the bench (drive setting), in the layout (drawn dimension), by
#: the foundry's structural layer (layer thickness), by the head's suspension
#: (resonance: its resonances, stiffness or α) or by the surfaces that meet (material).
Kind = Literal["drive setting", "drawn dimension", "layer thickness", "resonance", "material"]

#: The kinds a designer chooses; the others come with the process and the surfaces.
CHOSEN_KINDS: tuple[Kind, ...] = ("drive setting", "drawn dimension", "resonance")

#: The model's dimensionless parameters (MODEL.md, "Dimensionless model"); a field that
#: moves none of them moves only the length scale ℓ (the speed, not the mode).
MODEL_PARAMETERS = ("ϖ", "α", "β", "κ")

#: Bounds of a search: factors (low, high) on the current value, or absolute
#: (low, high, unit).
Bounds = tuple[float, float] | tuple[float, float, str]


@dataclass(frozen=True)
class DesignField:
    """One field a designer changes.

    Attributes
    ----------
    path : str
        Dotted path as in the device file (:mod:`betvdesign.spec.paths`); a path inside
        an actuator set addresses that field in every set.
    what : str
        What it is, in words.
    quantity : str
        The physical quantity it gives (MODEL.md, "Physical quantities"): ``ω`` [rad/s],
        ``u`` [m], ``M``, ``m`` [kg], ``k_v`` [N/m], ``α`` [-] (= k_v/k_h), ``θ`` [rad],
        ``μ`` [-]. Fields with the same quantity are alternatives or give it together
        (``head.mass`` or the head's geometry; the head's resonance or the drawn
        actuator's dimensions, which give k_v and k_h together).
    moves : tuple of str
        What a change of it moves, the other fields kept: of the model parameters ϖ, α,
        β, κ and the length scale ℓ = u·cosθ (as written for the usual device: f_v moves
        α unless α is given directly; m moves α too when k_h is given).
    kind : Kind
        How it is set.
    bounds : Bounds
        Default search bounds (``betv fix --vary`` without bounds, the range to explore).
    """

    path: str
    what: str
    quantity: str
    moves: tuple[str, ...]
    kind: Kind
    bounds: Bounds = (0.5, 2.0)

    @property
    def chosen(self) -> bool:
        """True when the designer chooses it (``betv fix`` varies it by default)."""
        return self.kind in CHOSEN_KINDS

    @property
    def moves_model(self) -> bool:
        """True when it moves one of ϖ, α, β, κ (so it can flip the mode)."""
        return any(p in MODEL_PARAMETERS for p in self.moves)


#: The fields a designer changes, in ranking order (see the module docstring).
# fmt: off
FIELDS: tuple[DesignField, ...] = (
    DesignField("drive.frequency", "drive frequency", "ω", ("ϖ",), "drive setting", (0.25, 4.0)),
    DesignField("drive.voltage", "drive voltage (through u(V): calibration or drawn model)", "u",
                ("ℓ",), "drive setting"),
    DesignField("actuator.amplitude", "actuator amplitude", "u", ("ℓ",), "drive setting"),
    DesignField("slider.beam_width", "slider beam width", "M", ("β",), "drawn dimension",
                (0.5, 4.0)),
    DesignField("slider.beam_length", "slider beam length", "M", ("β",), "drawn dimension"),
    DesignField("head.mass", "impact head mass", "m", ("β",), "drawn dimension", (0.25, 4.0)),
    DesignField("head.geometry.diameter", "head diameter (disc)", "m", ("β",),
                "drawn dimension"),
    DesignField("head.geometry.length", "head length (box)", "m", ("β",), "drawn dimension"),
    DesignField("head.geometry.width", "head width (box)", "m", ("β",), "drawn dimension"),
    DesignField("head.geometry.thickness", "head thickness (structural layer)", "m", ("β",),
                "layer thickness"),
    DesignField("slider.beam_thickness", "slider beam thickness (structural layer)", "M",
                ("β",), "layer thickness"),
    DesignField("actuator.vertical_resonance", "head vertical resonance f_v", "k_v",
                ("ϖ", "α"), "resonance"),
    DesignField("actuator.horizontal_resonance", "head tangential resonance f_h", "α",
                ("α",), "resonance"),
    DesignField("actuator.horizontal_stiffness", "tangential contact stiffness k_h", "α",
                ("α",), "resonance", (0.25, 4.0)),
    DesignField("actuator.alpha", "relative impact compliance α (given)", "α", ("α",),
                "resonance", (0.25, 4.0)),
    DesignField("contact.impact_angle", "impact angle", "θ", ("κ", "ℓ"), "drawn dimension",
                (15.0, 75.0, "deg")),
    # the drawn actuator (actuator.geometry): its springs give k_v and k_h where the file
    # gives no resonance or α (betv fix leaves them out where the file's are used)
    DesignField("actuator.geometry.length", "actuator hot-arm length", "k_v", ("ϖ", "α"),
                "drawn dimension"),
    DesignField("actuator.geometry.flexure_length", "actuator flexure length", "k_v",
                ("ϖ", "α"), "drawn dimension"),
    DesignField("actuator.geometry.flexure_width", "actuator flexure width", "k_v",
                ("ϖ", "α"), "drawn dimension", (0.5, 4.0)),
    DesignField("actuator.geometry.hot_arm_width", "actuator hot-arm width", "k_v",
                ("ϖ", "α"), "drawn dimension", (0.5, 4.0)),
    DesignField("actuator.geometry.cold_arm_width", "actuator cold-arm width", "k_v",
                ("ϖ", "α"), "drawn dimension"),
    DesignField("actuator.geometry.gap", "actuator hot-to-cold arm gap", "k_v", ("ϖ", "α"),
                "drawn dimension", (0.5, 4.0)),
    DesignField("contact.friction", "friction coefficient of head on slider", "μ", ("κ",),
                "material"),
)
# fmt: on

#: :data:`FIELDS` by path.
BY_PATH: dict[str, DesignField] = {f.path: f for f in FIELDS}


def bounds(path: str) -> Bounds:
    """Default search bounds of a field path.

    Parameters
    ----------
    path : str
        A dotted field path.

    Returns
    -------
    Bounds
        The field's :attr:`DesignField.bounds`; (0.5, 2.0) (factors on the current value)
        for a field not in :data:`FIELDS`.
    """
    known = BY_PATH.get(path)
    return known.bounds if known is not None else (0.5, 2.0)


def describe_change(path: str, old: float, new: float) -> str:
    """What a change of a file's resonance or stiffness means for the head's suspension.

    What a change of a field means physically (the suspension's stiffness, the head's
    mass kept); "" for fields that are drawn or set directly. The drawn dimensions that
    give it come from the frame model, where the device has a drawing
    (:func:`betvdesign.studies.drawnchange.in_drawing`), never from a power law.

    Parameters
    ----------
    path : str
        Dotted field path.
    old, new : float
        The value before and after, in the same unit.

    Returns
    -------
    str
        E.g. for a resonance f → r·f: "the head's vertical suspension 62% softer
        (k ×0.378, head mass kept)" (k ∝ f² at a fixed mass).
    """
    if old <= 0 or new <= 0:
        return ""
    r = new / old
    if path in ("actuator.vertical_resonance", "actuator.horizontal_resonance"):
        which = "vertical" if "vertical" in path else "tangential"
        k = r**2
    elif path == "actuator.horizontal_stiffness":
        which, k = "tangential", r
    elif path == "actuator.alpha":  # α = k_v/k_h: k_h × 1/r
        which, k = "tangential", 1.0 / r
    else:
        return ""
    soft = "stiffer" if k > 1 else "softer"
    return f"the head's {which} suspension {abs(k - 1):.0%} {soft} (k ×{k:.3g}, head mass kept)"
