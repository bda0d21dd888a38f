"""Process files: a surface-micromachining process as data.

A process file (YAML, validated like a device file, with ``file:line:col`` messages by
:func:`betvdesign.spec.loader.load_process`) lists the process's layers with their GDS
layer/datatype numbers and what each is for (``role``); for the structural layers the
thickness, Young's modulus, Poisson's ratio and density, and the design rules the checks
apply (minimum width and spacing, the widest feature the release etch frees without
etch holes, the holes' size and pitch); the anchor layer of each structural layer; the
drawing grid; and the annotation layer ``betv layout`` writes its labels on.

Every value names its source (``source`` of the file and of each layer); a value that
could not be sourced is listed in ``unsourced`` (its dotted path), and the checks say
so where they use it. A user's own process file (any path) replaces the shipped one:
a device file names its process by shipped name (``process: polymumps``) or by path
(relative to the device file).
"""

from __future__ import annotations

import os
import re
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any, Literal

import pint
from pydantic import BaseModel, ConfigDict, Field, field_validator, model_validator

from betvdesign.spec import limits
from betvdesign.spec.units import (
    Density,
    Length,
    NonNegativeLength,
    QuantitySpec,
    format_quantity,
    ureg,
)

if TYPE_CHECKING:
    from betvdesign.model.electrothermal import ThermalMaterial

__all__ = [
    "MIN_DRAWN",
    "SHIPPED_DIR",
    "Electrothermal",
    "GdsLayer",
    "Modulus",
    "Process",
    "ProcessLayer",
    "ReleaseHoles",
    "StrictModel",
    "process_ref",
    "rebase",
    "shipped_process_path",
    "shipped_processes",
]

#: Young's modulus (pressure) [Pa], e.g. '160 GPa'.
Modulus = Annotated[pint.Quantity, QuantitySpec("[pressure]", "Pa", "160 GPa", gt=0.0)]

#: Sheet resistance of a film [Ω per square], e.g. '10 ohm'.
SheetResistance = Annotated[pint.Quantity, QuantitySpec("[resistance]", "ohm", "10 ohm", gt=0.0)]
#: A coefficient per kelvin [1/K] (resistance's or expansion's), e.g. '1.25e-3 K^-1'.
PerKelvin = Annotated[pint.Quantity, QuantitySpec("1/[temperature]", "1/K", "1.25e-3 K^-1")]
#: Thermal conductivity [W/(m·K)], e.g. '32 W/m/K'.
Conductivity = Annotated[pint.Quantity, QuantitySpec("[power]/[length]/[temperature]", "W/m/K",
                                                     "32 W/m/K", gt=0.0)]  # fmt: skip
#: Specific heat [J/(kg·K)], e.g. '712 J/kg/K'.
SpecificHeat = Annotated[pint.Quantity, QuantitySpec("[energy]/[mass]/[temperature]", "J/kg/K",
                                                     "712 J/kg/K", gt=0.0)]  # fmt: skip
#: An absolute temperature [K], e.g. '1687 K'.
Temperature = Annotated[pint.Quantity, QuantitySpec("[temperature]", "K", "1687 K", gt=0.0)]

#: The smallest drawn length any layout can hold: 1 nm, the database unit of the GDS
#: files ``betv layout`` writes. A drawn dimension below it cannot be drawn at all.
MIN_DRAWN = ureg.Quantity(1, "nm")

#: Where the shipped process files live (``<name>.yaml``).
SHIPPED_DIR = Path(__file__).resolve().parents[1] / "data" / "processes"

LayerRole = Literal["structural", "anchor", "hole", "via", "dimple", "metal", "annotation", "other"]

_GDS = re.compile(r"^\s*(\d{1,5})\s*/\s*(\d{1,5})\s*$")


class StrictModel(BaseModel):
    """The base of every model read from a file.

    The base of every model read from a file (device and process files): unknown keys
    refused, frozen, strict types, each field's docstring its description (attached when
    a JSON schema is asked for: :func:`betvdesign.spec.fielddocs.describe_fields`).
    """

    model_config = ConfigDict(
        extra="forbid",
        frozen=True,
        strict=True,
        arbitrary_types_allowed=True,
    )


class GdsLayer(StrictModel):
    """A GDS layer/datatype pair (both 0–65535), written ``"45/0"`` in files."""

    layer: int = Field(ge=0, le=65535)
    datatype: int = Field(default=0, ge=0, le=65535)

    def __str__(self) -> str:
        """``layer/datatype``, as GDS tools write it."""
        return f"{self.layer}/{self.datatype}"

    @property
    def pair(self) -> tuple[int, int]:
        """(layer, datatype)."""
        return (self.layer, self.datatype)


def _gds(value: Any) -> Any:
    if isinstance(value, str):
        m = _GDS.match(value)
        if not m:
            raise ValueError(f"GDS layer {value!r}: write LAYER/DATATYPE, e.g. '45/0'")
        return {"layer": int(m.group(1)), "datatype": int(m.group(2))}
    if isinstance(value, int) and not isinstance(value, bool):
        return {"layer": value, "datatype": 0}
    return value


class ReleaseHoles(StrictModel):
    """Etch holes a wide feature needs to be released.

    Etch holes a wide feature needs to be released: drawn on ``layer``, squares of
    ``size``, centres at most ``pitch`` apart.
    """

    layer: str = Field(min_length=1, max_length=limits.MAX_NAME_CHARS)
    """Name of the hole layer in this process (e.g. 'hole1')."""
    size: Length
    """Side of a square etch hole."""
    pitch: Length
    """Largest centre-to-centre distance of neighbouring holes."""


class Electrothermal(StrictModel):
    """A structural film's electrical and thermal data and its gap to the substrate.

    What the electrothermal stroke (:mod:`betvdesign.model.electrothermal`) needs: the
    film's sheet resistance and its temperature coefficient, thermal conductivity,
    specific heat, expansion (a named α(T) law or a constant), melting point; the air gap
    under the film, the air's conductivity and the insulating layer on the substrate.
    ``source`` names where the values come from; a value no source was found for is
    listed in the process's ``unsourced``.
    """

    sheet_resistance: SheetResistance
    """Sheet resistance R_s at the substrate temperature (resistivity ρ_0 = R_s·t)."""
    tcr: PerKelvin
    """Linear temperature coefficient ξ of the resistivity: ρ = ρ_0·(1 + ξ·(T − T_0))."""
    thermal_conductivity: Conductivity
    """Thermal conductivity k of the film."""
    specific_heat: SpecificHeat
    """Specific heat c of the film."""
    expansion_law: Literal["okada-tokumaru-1984"] | None = None  # = OKADA_TOKUMARU
    """α(T) by name: 'okada-tokumaru-1984' (silicon, 120–1500 K)."""
    expansion_coefficient: PerKelvin | None = None
    """A constant α instead of ``expansion_law``."""
    melting_point: Temperature
    """Melting point of the film: a peak temperature above it melts the arm."""
    deformation_onset: Temperature | None = None
    """Onset of plastic deformation (creep, back-bending) of the film, below the melting
    point: ``thermal.peak-temperature`` fails above it and warns within 10 % of it.
    Without it the rule checks the melting point alone and says the onset is NOT
    sourced."""
    substrate_temperature: Temperature = Field(default_factory=lambda: ureg.Quantity(300.0, "K"))
    """Substrate (and anchor) temperature T_0 (default 300 K)."""
    air_gap: Length
    """Height of the released film above the substrate's top layer (t_v)."""
    air_conductivity: Conductivity
    """Thermal conductivity of the air in the gap."""
    nitride_thickness: NonNegativeLength
    """Insulating layer on the substrate (t_n; 0 um for none)."""
    nitride_conductivity: Conductivity
    """Its thermal conductivity."""
    source: str = Field(min_length=1, max_length=limits.MAX_STRING_CHARS)
    """Where these values come from."""

    @model_validator(mode="after")
    def _one_expansion(self) -> Electrothermal:
        if (self.expansion_law is None) == (self.expansion_coefficient is None):
            raise ValueError("give 'expansion_law' or 'expansion_coefficient' (one of them)")
        if self.deformation_onset is not None and not (
            self.deformation_onset.to("K").magnitude < self.melting_point.to("K").magnitude
        ):
            raise ValueError(
                f"deformation_onset ({self.deformation_onset:~P}) must lie below "
                f"melting_point ({self.melting_point:~P})"
            )
        return self


class ProcessLayer(StrictModel):
    """One mask layer of the process."""

    gds: GdsLayer
    """GDS layer/datatype, e.g. '45/0'."""
    role: LayerRole
    """structural (released, carries the device), anchor, hole, via, dimple, metal,
    annotation (labels only, no mask) or other."""
    description: str | None = Field(default=None, max_length=limits.MAX_STRING_CHARS)
    """Free text."""
    thickness: Length | None = None
    """Deposited thickness (structural and metal layers)."""
    youngs_modulus: Modulus | None = None
    """Young's modulus E of the film (structural layers)."""
    poisson_ratio: float | None = Field(default=None, ge=0.0, lt=0.5)
    """Poisson's ratio ν [-] of the film (structural layers; the FE check uses it)."""
    density: Density | None = None
    """Density of the film (structural layers)."""
    min_width: Length | None = None
    """Smallest drawn width of a feature on this layer."""
    min_spacing: Length | None = None
    """Smallest drawn gap between two features on this layer."""
    max_unreleased_width: Length | None = None
    """Widest feature the release etch frees without etch holes (structural layers): a
    point farther than half of it from every edge needs holes."""
    release_holes: ReleaseHoles | None = None
    """Etch holes for wider features (structural layers)."""
    anchor: str | None = Field(default=None, max_length=limits.MAX_NAME_CHARS)
    """Name of the layer that anchors this structural layer to the substrate."""
    electrothermal: Electrothermal | None = None
    """Electrical and thermal data (structural layers; the drawn actuator's stroke)."""
    source: str | None = Field(default=None, max_length=limits.MAX_STRING_CHARS)
    """Where the values of this layer come from."""

    _gds = field_validator("gds", mode="before")(_gds)


#: Fields a structural layer must give (the checks and the stiffness need them).
_STRUCTURAL = (
    "thickness",
    "youngs_modulus",
    "poisson_ratio",
    "density",
    "min_width",
    "min_spacing",
    "max_unreleased_width",
    "release_holes",
)


class Process(StrictModel):
    """A fabrication process: layers, materials, design rules (see the module doc)."""

    name: str = Field(min_length=1, max_length=limits.MAX_NAME_CHARS)
    """Process name, e.g. 'polymumps'."""
    description: str | None = Field(default=None, max_length=limits.MAX_STRING_CHARS)
    """Free text."""
    source: str = Field(min_length=1, max_length=limits.MAX_STRING_CHARS)
    """The document the values come from (edition, date)."""
    grid: Length
    """Drawing grid: every vertex lies on a multiple of it."""
    default_structural: str = Field(min_length=1, max_length=limits.MAX_NAME_CHARS)
    """The structural layer a device uses unless it names another (e.g. 'poly1')."""
    annotation: str = Field(min_length=1, max_length=limits.MAX_NAME_CHARS)
    """The layer ``betv layout`` writes its labels on (role annotation: no mask)."""
    layers: dict[str, ProcessLayer] = Field(min_length=1, max_length=256)
    """Layers by name."""
    unsourced: list[str] = Field(default_factory=list, max_length=1000)
    """Dotted paths of values no source could be found for (e.g.
    'layers.poly1.youngs_modulus'); the checks say so where they use them."""

    @field_validator("layers")
    @classmethod
    def _names(cls, v: dict[str, ProcessLayer]) -> dict[str, ProcessLayer]:
        for name in v:
            if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", name):
                raise ValueError(f"layer name {name!r}: use letters, digits and '_'")
        return v

    @model_validator(mode="after")
    def _consistent(self) -> Process:
        seen: dict[tuple[int, int], str] = {}
        for name, lay in self.layers.items():
            if lay.gds.pair in seen:
                raise ValueError(
                    f"@layers.{name}.gds: GDS {lay.gds} is also layer {seen[lay.gds.pair]!r}"
                )
            seen[lay.gds.pair] = name
            if lay.role == "structural":
                missing = [f for f in _STRUCTURAL if getattr(lay, f) is None]
                if missing:
                    raise ValueError(
                        f"@layers.{name}: a structural layer needs {', '.join(missing)}"
                    )
                holes = lay.release_holes
                assert holes is not None
                self._role(f"layers.{name}.release_holes.layer", holes.layer, "hole")
                if lay.anchor is not None:
                    self._role(f"layers.{name}.anchor", lay.anchor, "anchor")
                if holes.pitch <= holes.size:
                    raise ValueError(
                        f"@layers.{name}.release_holes.pitch: must exceed the hole size "
                        f"{format_quantity(holes.size)}"
                    )
        self._role("default_structural", self.default_structural, "structural")
        self._role("annotation", self.annotation, "annotation")
        for i, path in enumerate(self.unsourced):
            if not self._has(path):
                raise ValueError(f"@unsourced[{i}]: {path!r} is not a value of this file")
        return self

    def _role(self, path: str, name: str, role: str) -> None:
        lay = self.layers.get(name)
        if lay is None:
            known = ", ".join(n for n, x in self.layers.items() if x.role == role) or "none"
            raise ValueError(f"@{path}: no layer {name!r} (layers with role {role}: {known})")
        if lay.role != role:
            raise ValueError(f"@{path}: layer {name!r} has role {lay.role}, expected {role}")

    def _has(self, path: str) -> bool:
        node: Any = self
        for part in path.split("."):
            if isinstance(node, dict):
                node = node.get(part)
            elif isinstance(node, BaseModel) and part in type(node).model_fields:
                node = getattr(node, part)
            else:
                return False
            if node is None:
                return False
        return True

    # --- queries -----------------------------------------------------------------------
    def structural(self, name: str | None = None) -> ProcessLayer:
        """The structural layer ``name`` (the default one when None).

        The structural layer ``name`` (the default one when None); ValueError if the
        process has no such structural layer.

        Parameters
        ----------
        name : str, optional
            The layer's name.

        Returns
        -------
        ProcessLayer
            The layer.

        Raises
        ------
        ValueError
            If the process has no such structural layer.
        """
        key = name or self.default_structural
        lay = self.layers.get(key)
        if lay is None or lay.role != "structural":
            known = ", ".join(n for n, x in self.layers.items() if x.role == "structural")
            raise ValueError(f"process {self.name!r} has no structural layer {key!r} ({known})")
        return lay

    def structural_name(self, name: str | None = None) -> str:
        """The name of the structural layer ``name`` refers to (the default when None).

        Parameters
        ----------
        name : str, optional
            The layer's name.

        Returns
        -------
        str
            The structural layer's name.
        """
        self.structural(name)
        return name or self.default_structural

    def by_gds(self, pair: tuple[int, int]) -> str | None:
        """The name of the layer with this (layer, datatype), or None.

        Parameters
        ----------
        pair : tuple of (int, int)
            GDS layer and datatype.

        Returns
        -------
        str or None
            The layer's name.
        """
        for name, lay in self.layers.items():
            if lay.gds.pair == pair:
                return name
        return None

    def thermal_material(self, name: str | None = None) -> ThermalMaterial:
        """The electrothermal data of the structural layer ``name`` in SI floats.

        Parameters
        ----------
        name : str, optional
            The structural layer (the default one when None).

        Returns
        -------
        ThermalMaterial
            Its film's and gap's data (resistivity ρ_0 = R_s·t, the layer's density).

        Raises
        ------
        ValueError
            Naming the missing section (``layers.NAME.electrothermal``) when the process
            has no electrothermal data for that layer.
        """
        from betvdesign.model.electrothermal import ThermalMaterial

        key = self.structural_name(name)
        lay = self.structural(key)
        et = lay.electrothermal
        if et is None:
            raise ValueError(
                f"process {self.name!r}: layers.{key}.electrothermal is missing (sheet "
                "resistance, its temperature coefficient, thermal conductivity, specific heat, "
                "expansion, melting point and the gap to the substrate): the drawn actuator's "
                "stroke needs it"
            )
        assert lay.thickness is not None and lay.density is not None

        def si(q: pint.Quantity, unit: str) -> float:
            return float(q.to(unit).magnitude)

        expansion: str | float = (
            et.expansion_law if et.expansion_law is not None
            else si(et.expansion_coefficient, "1/K")  # type: ignore[arg-type]
        )  # fmt: skip
        return ThermalMaterial(
            resistivity=si(et.sheet_resistance, "ohm") * si(lay.thickness, "m"),
            tcr=si(et.tcr, "1/K"),
            conductivity=si(et.thermal_conductivity, "W/m/K"),
            density=si(lay.density, "kg/m**3"),
            heat_capacity=si(et.specific_heat, "J/kg/K"),
            expansion=expansion,
            air_conductivity=si(et.air_conductivity, "W/m/K"),
            air_gap=si(et.air_gap, "m"),
            nitride_thickness=si(et.nitride_thickness, "m"),
            nitride_conductivity=si(et.nitride_conductivity, "W/m/K"),
            substrate_temperature=si(et.substrate_temperature, "K"),
            melting_temperature=si(et.melting_point, "K"),
            deformation_temperature=(
                None if et.deformation_onset is None else si(et.deformation_onset, "K")
            ),
        )

    def cite(self, path: str) -> str:
        """Where the value at ``path`` comes from.

        Where the value at ``path`` comes from: the layer's or the file's source, and
        'not sourced' when the file lists it in ``unsourced``.

        Parameters
        ----------
        path : str
            A value's path in the process file.

        Returns
        -------
        str
            The source.
        """
        if path in self.unsourced:
            return f"process {self.name}: {path} (value NOT sourced; replace it by your foundry's)"
        parts = path.split(".")
        if len(parts) >= 2 and parts[0] == "layers" and parts[1] in self.layers:
            lay = self.layers[parts[1]]
            src = lay.source
            if len(parts) >= 3 and parts[2] == "electrothermal" and lay.electrothermal:
                src = lay.electrothermal.source
            if src:
                return f"process {self.name}: {path} ({src})"
        return f"process {self.name}: {path} ({self.source})"


def shipped_processes() -> list[str]:
    """Names of the shipped process files.

    Returns
    -------
    list of str
        The names, sorted.
    """
    return sorted(p.stem for p in SHIPPED_DIR.glob("*.yaml"))


def shipped_process_path(name: str) -> Path | None:
    """The file of the shipped process ``name`` (None if there is none).

    Parameters
    ----------
    name : str
        A process name.

    Returns
    -------
    Path or None
        The file.
    """
    if not re.fullmatch(r"[A-Za-z0-9_\-]+", name):
        return None
    p = SHIPPED_DIR / f"{name}.yaml"
    return p if p.is_file() else None


def rebase(ref: str, source_dir: str | Path, out: str | Path) -> str:
    """A device's ``process`` reference as written in a file next to ``out``.

    A device's ``process`` reference as written in a file next to ``out``: a shipped
    name as is, a path (relative to ``source_dir``, where it was read) re-based to ``out``'s
    directory.

    Parameters
    ----------
    ref : str
        The reference as read.
    source_dir : path
        Where it was read.
    out : path
        The file it is written to.

    Returns
    -------
    str
        The reference to write.
    """
    if shipped_process_path(ref) is not None:
        return ref
    p = Path(ref)
    p = p if p.is_absolute() else Path(source_dir) / p
    return os.path.relpath(p.resolve(), Path(out).resolve().parent)


def process_ref(path: str | Path) -> str | None:
    """The ``process`` value of a device file as written (None when it names none).

    Parameters
    ----------
    path : path
        The device file.

    Returns
    -------
    str or None
        The reference.
    """
    from ruamel.yaml import YAML

    try:
        data = YAML(typ="safe").load(Path(path).read_text("utf-8"))
    except Exception:  # the file was validated before; a second read failing is moot
        return None
    value = data.get("process") if isinstance(data, dict) else None
    return value if isinstance(value, str) else None
