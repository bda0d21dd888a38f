"""The house as data: betvdesign's packages in layer order, each with its job.

A package (or top-level module) may import only from itself and from the layers listed
before it; every import counts, at module level or inside a function, ``from``, relative
or ``importlib.import_module("...")``. ``tests/test_layers.py`` parses every module and
fails on an import that runs up this list (naming file:line), and checks that the table
of docs/ARCHITECTURE.md is :func:`markdown_table` (``python -m betvdesign.layers``
prints it).

The package root (``betvdesign/__init__.py``) is no layer: it holds ``__version__``,
which any module may read, and imports each public name (``check``, ``load_device``, …)
from its home on first use.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["LAYERS", "Layer", "layer_of", "markdown_table"]


@dataclass(frozen=True)
class Layer:
    """One row of the house: a package or top-level module and what it is for.

    Attributes
    ----------
    name : str
        The sub-package (``"model"``) or top-level module (``"errors"``) of
        ``betvdesign``.
    job : str
        What it is for, in Markdown (a cell of docs/ARCHITECTURE.md's table).
    """

    name: str
    job: str

    @property
    def shown(self) -> str:
        """How the table names it: ``model/`` for a package, ``errors.py`` for a module."""
        return f"`{self.name}.py`" if self.name in _MODULES else f"`{self.name}/`"


#: Top-level modules (the other rows are sub-packages).
_MODULES = frozenset({"layers", "errors", "api"})

#: The layers, lowest first: each imports only from the rows before it.
LAYERS: tuple[Layer, ...] = (
    Layer("layers", "this table (the house as data); imports nothing"),
    Layer(
        "errors",
        "the exceptions (`BetvError`, `SpecError` with file:line:col issues, "
        "`ParameterError`, `UsageError`)",
    ),
    Layer(
        "model",
        "unit-free facts: `params` (ModelParams ϖ, α, β, κ, ζ_v, ζ_h, e; λ), `domain` "
        "(design window and its edges to round-off, fit range, stall threshold, the "
        "round-off scale, the one `mode_of`, the travel horizon), `damping` (Q ↔ ζ, "
        "normal-force phase), `rolloff` (H(f)), `frame` (the drawn actuator's springs at "
        "the head: Euler–Bernoulli frame closed form), `frame_fe` (its plane-stress FE "
        "check, scikit-fem), `electrothermal` (the drawn actuator's stroke, power, peak "
        "temperature and thermal modes: 1-D fins, closed form), `electrothermal_fe` (its "
        "plane FE check), `bisection` (the one bisection: where a classified quantity "
        "changes class)",
    ),
    Layer(
        "output",
        "how results leave the program: `files` (checked paths, atomic writes, write "
        "groups), `siformat` (SI prefixes by magnitude), `numbers` (the one JSON number "
        "rule: non-finite → null), `presentation` (the mode colours and rule-status words "
        "of every figure, page and text), `answers` (a command's printed answer stored "
        "under its inputs' content: `betv check` answers again at once)",
    ),
    Layer(
        "spec",
        "device files: `units` (the one pint registry), `models` (pydantic DeviceSpec), "
        "`loader` + `safeyaml` (bounded YAML, file:line:col), `messages` (one wording of "
        "validation errors), `limits` (every input bound), `paths` (dotted spec paths: "
        "read, resolve, replace), `whatif` (validated `DeviceSpec.replace`), `fields` (the "
        "fields a designer changes, one list), `process` (process files: layers, "
        "materials, design rules; shipped in `data/processes/`)",
    ),
    Layer(
        "nondim",
        "spec → ModelParams + scales + derivation record: `device` (the paper's relations "
        "as named steps), `terms` (the optional terms), `actuator` (the drawn actuator's "
        "springs, every step recorded), `stroke` (a stroke predicted from the drawing: the "
        "electrothermal model at the drive, recorded), `record` (what a derivation "
        "produces); the only "
        "package that strips units",
    ),
    Layer(
        "dynamics",
        "the exact event-driven solver, unit-free float64 (numba kernels, one "
        "implementation: `contact`, `flows`, `search`, `bounds`, `evaluators` and "
        "`values` (the event functions, undamped and general form), "
        "`schedule`, `shooting`, `jit`), its answers (`result`: one contract), `solver` "
        "(`simulate`), `periodic` (`periodic_orbit`), `vertical` (`vertical_motion`), "
        "`settling` (transient from rest), `determination` (is Δs determined in float64), "
        "`reference` + `reference_terms` (solve_ivp, independent), `rigid` (α → 0), "
        "`coupled` (the coupled head's exact compiled solver: phase flows exp(A·δ), its "
        "stable orbit), `coupled_reference` (the coupled head, solve_ivp, independent)",
    ),
    Layer(
        "checks",
        "the verdict: `rule` (RuleResult: rules as data), `rules` (the design rules), "
        "`window` (the design window's rules: its edges, its margin), "
        "`travel` (which answer a verdict quotes: orbit or crossing of the travel), "
        "`adequacy` (is the idealised model enough: study, rule, JSON), `coupled` (its "
        "coupled rung: decoupled springs vs the drawn head, the verdict's model of a "
        "drawn set without measured resonances), `fidelity` (the "
        "ladder of models), `thermal_rules` (a predicted stroke: peak temperature, "
        "bandwidth, power, sources), `actuator_rules` (drawn actuator against the file's "
        "resonances), `process_rules` (the process's design rules on a device file), "
        "`checker` (the check of a device), `view` (text, versioned JSON, HTML)",
    ),
    Layer(
        "studies",
        "`engine/` (executors, runner, store, grid, `chunkstore` (an atlas's directory: "
        "a manifest, one file per chunk, the merged table), `preload` and `daskplugin`: "
        "kernels loaded once per worker), `points` (one design point of a "
        "study), maps (`pushpull`, `regime`, `lambda_scan`), device studies (`sampling`, "
        "`tolerance`, `calibration`, `measurements`, `fix` (the one search of advice: "
        "`betv fix` and the fix text of `betv check`), `fixfields`, `fixfile`, "
        "`drawnchange` (a change of the springs said in drawn dimensions, through the "
        "frame, within the process rules), "
        "`fieldsweep` (a device's own fields in physical units)), `fieldmap` (the "
        "exact-mode map of two device fields), `atlas` (a design-space atlas of up to "
        "millions of points, in chunks, resumable: `betv sweep atlas`), `terms` (the "
        "optional terms of a study)",
    ),
    Layer(
        "layout",
        "mask layouts (gdstk): `write` (`betv layout`), `extract` (a labelled GDS → "
        "device, `betv extract`, `betv check FILE.gds`), `drc` (width, spacing, release "
        "on the drawn polygons), `convention` (labels), `shapes`, `fixlayout` (a fix "
        "drawn and checked)",
    ),
    Layer(
        "paper",
        "the validation against the published paper (`study`, `vertical`, `slider`, "
        "`maps`, `common`)",
    ),
    Layer(
        "plots",
        "object-oriented matplotlib figures from plain arrays (`ax=`, never pyplot), "
        "`figure` (style, SVG); below everything that draws",
    ),
    Layer(
        "bench",
        "the speed-against-accuracy evidence: work-precision, failure map, ladder "
        "measurements, `verdictmap` (where the verdict means something), drawn with `plots`",
    ),
    Layer(
        "api",
        "the one check pipeline (`CheckOptions`, `read_source`, `run_check`: YAML, GDS or "
        "spec → `CheckResult`) and the notebook entry points `betvdesign.check`, "
        "`betvdesign.adequacy`; below `report`, `explore` and `cli`, which call it",
    ),
    Layer("report", "the report model → Jinja2 → HTML / PDF; methods and validation reports"),
    Layer(
        "explore",
        "`betv explore`: the Bokeh-server page (`server`, `page`, `controls`, `mapview`, "
        "`views`), the design edited in it (`design`: edits validated like the file, "
        "saved in place), its controls (`fields`: `spec.fields` plus waveform, beam "
        "count, Q/ζ, e), the staged check (`compute`) and the worker processes (`jobs`); "
        "the one package that imports Bokeh",
    ),
    Layer("cli", "typer, thin: one module per sub-command, shared options in `common`"),
)


def layer_of(name: str) -> int:
    """The layer number of a package or top-level module of ``betvdesign``.

    Parameters
    ----------
    name : str
        The first component below ``betvdesign`` (``"checks"``, ``"errors"``).

    Returns
    -------
    int
        Its index in :data:`LAYERS` (0 = lowest).

    Raises
    ------
    KeyError
        When the name is in no layer.
    """
    for i, layer in enumerate(LAYERS):
        if layer.name == name:
            return i
    raise KeyError(f"betvdesign.{name} is in no layer of betvdesign.layers.LAYERS")


def markdown_table() -> str:
    """docs/ARCHITECTURE.md's layer table, generated from :data:`LAYERS`.

    Returns
    -------
    str
        The Markdown table, one row per layer, ending with a newline.
    """
    lines = ["| layer | package | its job |", "|---|---|---|"]
    lines += [f"| {i} | {layer.shown} | {layer.job} |" for i, layer in enumerate(LAYERS)]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":  # pragma: no cover - prints the table for the document
    print(markdown_table(), end="")
