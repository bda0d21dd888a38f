"""A corpus of hostile device files and command-line arguments (issue 15).

Each :class:`Case` is one run of ``betv``: its arguments, the content of the
device file it reads (``{f}``), the exit codes allowed, a fragment the message must
hold, whether the message must point into the file (``{f}:line:col``) and which
output files may exist afterwards (none, unless the case is meant to succeed).

``tests/test_hostile_corpus.py`` runs every case in-process (CliRunner) under a
30 s timeout. Run as a script, this module runs the corpus as subprocesses against
any checkout and prints the table by category (used for the before/after table of
the issue)::

    python tests/hostile_corpus.py                      # this checkout
    PYTHONPATH=/path/to/old/checkout python tests/hostile_corpus.py --legacy

``--legacy`` spells the Monte Carlo spread ``--tol`` as older versions did.
"""

from __future__ import annotations

import codecs
import os
import re
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
BASE = (REPO / "devices" / "push_demo.yaml").read_text(encoding="utf-8")
BIDIR = REPO / "devices" / "bidir_demo.yaml"
#: Every case must end within this many seconds (issue 15).
TIME_LIMIT_S = 30

Content = str | bytes | Callable[[Path], None] | None


@dataclass(frozen=True)
class Case:
    """One hostile run of ``betv`` (see module doc)."""

    id: str
    category: str
    args: tuple[str, ...]
    content: Content = None  # written to {f} (a callable writes it itself)
    exits: tuple[int, ...] = (2,)
    expect: str | None = None  # regex searched in stderr (stdout too for exit 0/1)
    where: bool = False  # the message names {f}:line:col
    outputs: tuple[str, ...] = ()  # paths (relative to the case's dir) allowed afterwards


def _sub(old: str, new: str, text: str = BASE) -> str:
    assert old in text, old
    return text.replace(old, new, 1)


def _lol(levels: int = 9, width: int = 9, at_top: bool = False) -> str:
    """The billion-laughs alias bomb (9^9 strings once expanded)."""
    lines = [f"l0: &l0 [{', '.join(['lol'] * width)}]"]
    for i in range(1, levels):
        lines.append(f"l{i}: &l{i} [{', '.join([f'*l{i - 1}'] * width)}]")
    if at_top:
        return "\n".join(lines) + f"\nname: *l{levels - 1}\n"
    body = "\n".join("  " + ln for ln in lines)
    return _sub("description:", f"x-bombs:\n{body}\ndescription:") + f"\nname2: *l{levels - 1}\n"


def _sets(n: int) -> str:
    head = BASE.split("actuator_sets:\n")[0]
    one = (
        "  - {{name: s{i}, intended_mode: push, head: {{mass: 0.006 ug}}, "
        "contact: {{impact_angle: 20 deg, friction: 0.4}}, actuator: {{vertical_resonance: "
        "5 kHz, alpha: 2, amplitude: 0.14 um}}, drive: {{waveform: ac, frequency: 3 kHz}}}}\n"
    )
    return head + "actuator_sets:\n" + "".join(one.format(i=i) for i in range(n))


def _points(n: int) -> str:
    """A measured calibration of ``n`` points (1 mV apart), driven at 1 V."""
    pts = "".join(f"          - {{voltage: {i} mV, amplitude: {i} pm}}\n" for i in range(n))
    start = BASE.index("        points:\n") + len("        points:\n")
    end = BASE.index("    drive:")
    return BASE[:start] + pts + BASE[end:].replace("voltage: 9 V", "voltage: 1 V")


def _big_file(size: int) -> Callable[[Path], None]:
    def write(path: Path) -> None:
        with open(path, "wb") as fh:
            fh.write(BASE.encode())
            line = b"# " + b"x" * 97 + b"\n"
            fh.write(line * (size // len(line) + 1))

    return write


def _symlink(target: str) -> Callable[[Path], None]:
    def write(path: Path) -> None:
        path.symlink_to(target)

    return write


def _dir(path: Path) -> None:
    path.mkdir()


CHECK = ("check", "{f}")
SIM = ("simulate", "--varpi", "1.2", "--alpha", "2", "--beta", "0.5", "--kappa", "0.15")
TOL = (
    "tolerance",
    str(REPO / "devices" / "push_demo.yaml"),
    "--fidelity",
    "lambda",
    "-x",
    "serial",
)
SPREAD = ("{spread}", "drive.frequency=2%")
MAP = (
    "sweep", "pushpull", "--varpi", "1", "--alpha", "2", "--beta", "0.5", "--kappa", "0.15",
    "--fidelity", "lambda", "-q",
)  # fmt: skip
ATLAS = (
    "sweep", "atlas", "--alpha", "2", "--beta", "0.5", "--kappa", "0.15", "--fidelity",
    "lambda", "-q", "-o", "{d}/atlas",
)  # fmt: skip
OUT = ("-o", "{d}/map.csv")
MAP_OUT = ("map.csv", "map.json")


def _yaml() -> list[Case]:
    c = "yaml"
    return [
        Case("syntax-unclosed-bracket", c, CHECK, _sub("beam_count: 2", "beam_count: [2"),
             expect="invalid YAML", where=True),
        Case("syntax-bad-indent", c, CHECK, _sub("  beam_width: 10 um", "      beam_width: 10 um"),
             expect="invalid YAML", where=True),
        Case("syntax-tab-indent", c, CHECK, _sub("  beam_width: 10 um", "\tbeam_width: 10 um"),
             expect="invalid YAML", where=True),
        Case("alias-bomb-in-field", c, CHECK, _lol(), expect="20,000 YAML nodes", where=True),
        Case("alias-bomb-top-level", c, CHECK, _lol(at_top=True), expect="YAML nodes",
             where=True),
        Case("alias-bomb-merge-keys", c, CHECK,
             "a: &a {x: 1, y: 2}\n" + "".join(
                 f"m{i}: &m{i} {{<<: [*{'a' if i == 0 else f'm{i - 1}'}], "
                 f"z{i}: [*{'a' if i == 0 else f'm{i - 1}'}, *{'a' if i == 0 else f'm{i - 1}'}]}}\n"
                 for i in range(30)), expect="YAML nodes", where=True),
        Case("nesting-flow-5000", c, CHECK, "name: " + "[" * 5000 + "]" * 5000 + "\n",
             expect="nested deeper than 32", where=True),
        Case("nesting-block-200", c, CHECK,
             "".join("  " * i + f"k{i}:\n" for i in range(200)) + "  " * 200 + "x: 1\n",
             expect="nested deeper than 32", where=True),
        Case("nesting-flow-map-100k", c, CHECK, "a: " + "{b: " * 100000 + "1" + "}" * 100000,
             expect="nested deeper", where=True),
        Case("tag-python-object", c, CHECK,
             _sub("name: push_demo", 'name: !!python/object/apply:os.system ["echo pwned"]'),
             expect="expected a string", where=True),
        Case("tag-custom", c, CHECK, _sub("beam_length: 200 um", "beam_length: !foo 200 um"),
             expect="beam_length", where=True),
        Case("tag-binary", c, CHECK, _sub("name: push_demo", "name: !!binary aGVsbG8="),
             where=True),
        Case("recursive-alias-list", c, CHECK, _sub("beam_count: 2", "beam_count: &r [*r]"),
             expect="recursive", where=True),
        Case("recursive-alias-map", c, CHECK, _sub("slider:\n", "slider: &s\n  self: *s\n"),
             expect="recursive", where=True),
        Case("undefined-alias", c, CHECK, _sub("beam_length: 200 um", "beam_length: *nope"),
             expect="undefined alias", where=True),
        Case("duplicate-keys", c, CHECK, _sub("beam_count: 2", "beam_count: 2\n  beam_count: 3"),
             expect="duplicate key", where=True),
        Case("multi-document", c, CHECK, BASE + "\n---\nname: again\n",
             expect="single document", where=True),
        Case("empty-file", c, CHECK, "", expect="empty file"),
        Case("only-comments", c, CHECK, "# nothing here\n", expect="empty file"),
        Case("top-level-scalar", c, CHECK, "just a string\n", expect="mapping at the top"),
        Case("top-level-list", c, CHECK, "- 1\n- 2\n", expect="mapping at the top"),
        Case("bom-utf8", c, CHECK, codecs.BOM_UTF8 + BASE.encode(), exits=(0, 1)),
        Case("crlf", c, CHECK, BASE.replace("\n", "\r\n").encode(), exits=(0, 1)),
        Case("utf16-bom", c, CHECK, BASE.encode("utf-16"), exits=(0, 1)),
        Case("utf16-no-bom", c, CHECK, BASE.encode("utf-16-le"), expect="UTF-8|control",
             where=True),
        Case("latin1", c, CHECK,
             _sub("description: ", "description: café ").encode("latin-1", "replace"),
             expect="not UTF-8", where=True),
        Case("nul-byte", c, CHECK, _sub("name: push_demo", "name: push\x00demo"),
             expect="control character", where=True),
        Case("size-50MB", c, CHECK, _big_file(50_000_000), expect="limit is 1,000,000 bytes"),
        Case("size-2MB", c, CHECK, _big_file(2_000_000), expect="BETV_MAX_FILE_BYTES"),
        Case("dev-zero", c, ("check", "/dev/zero"), expect="limit is"),
        Case("dev-null", c, ("check", "/dev/null"), expect="empty file"),
        Case("long-string-200k", c, CHECK, _sub("description: ", "description: " + "x" * 200_000),
             expect="string of 200,0\\d\\d characters", where=True),
        Case("flow-list-100k", c, CHECK, _sub("description: ", "x: [" + ", ".join(["1"] * 100_000)
             + "]\ndescription: "), expect="YAML nodes", where=True),
        Case("is-a-directory", c, CHECK, _dir, expect="is a directory"),
        Case("missing-file", c, ("check", "{d}/nope.yaml"), expect="file not found"),
        Case("symlink-loop", c, CHECK, _symlink("device.yaml"), expect="cannot read|not found"),
    ]  # fmt: skip


def _units() -> list[Case]:
    c = "units"

    def bl(value: str, **kw) -> Case:
        return Case(kw.pop("id"), c, CHECK, _sub("beam_length: 200 um", f"beam_length: {value}"),
                    where=True, **kw)  # fmt: skip

    return [
        bl("5 kg", id="wrong-dimension", expect="wrong dimension"),
        bl("5 V/um", id="wrong-dimension-compound", expect="wrong dimension"),
        bl("200 degC", id="offset-degC", expect="offset units"),
        Case("offset-degC-angle", c, CHECK,
             _sub("impact_angle: 20.56 deg", "impact_angle: 20 degC"),
             expect="offset units", where=True),
        bl("200 umm", id="typo-unit", expect="unknown unit"),
        bl("200", id="bare-number", expect="missing unit"),
        bl("um", id="bare-unit", expect="missing number"),
        bl('"200 um**9**9**9**9"', id="power-tower", expect="one power per unit"),
        bl('"200 um^99999999"', id="power-huge", expect="exceeds the limit"),
        bl('"200 ((((((um))))))"', id="parentheses", expect="no parentheses"),
        bl('"9**9**9**9 um"', id="number-tower", expect="cannot read"),
        bl('"200 um*um/um*um/um*um/um*um/um*um/um"', id="many-factors", expect="unit factors"),
        bl("1" + "0" * 500 + " um", id="long-number", expect="characters; the limit"),
        bl("nan um", id="nan", expect="finite"),
        bl("inf um", id="inf", expect="finite"),
        bl("-inf um", id="minus-inf", expect="finite|> 0"),
        bl("1e308 km", id="overflow-1e308", expect="finite"),
        bl("1e999 um", id="overflow-literal", expect="finite"),
        bl("-0 um", id="minus-zero", expect="> 0"),
        bl("-200 um", id="negative", expect="> 0"),
        bl("0x10 um", id="hex-number", expect="cannot read|unknown"),
        Case("micro-sign", c, CHECK, _sub("beam_length: 200 um", "beam_length: 200 µm"),
             exits=(0, 1)),
        Case("no-space", c, CHECK, _sub("beam_length: 200 um", "beam_length: 200um"),
             exits=(0, 1)),
        Case("tiny-1e-300", c, CHECK, _sub("beam_length: 200 um", "beam_length: 1e-300 um"),
             exits=(0, 1, 2)),
        Case("calibration-csv-unit-bomb", c, ("calibrate", str(BIDIR), "{f}"),
             "voltage [V**9**9**9],speed [um/s]\n5,10\n", expect="V\\*\\*9"),
        Case("friction-nan", c, CHECK, _sub("friction: 0.4", "friction: .nan"),
             expect="friction", where=True),
        Case("friction-inf", c, CHECK, _sub("friction: 0.4", "friction: .inf"),
             expect="friction", where=True),
    ]  # fmt: skip


def _structure() -> list[Case]:
    c = "structure"
    return [
        Case("list-for-map", c, CHECK, _sub("slider:\n", "slider: [1, 2]\nx_slider:\n"),
             expect="mapping", where=True),
        Case("map-for-list", c, CHECK, BASE.split("actuator_sets:")[0] + "actuator_sets: {a: 1}\n",
             expect="list", where=True),
        Case("unknown-field", c, CHECK, _sub("slider:", "slidr:"), expect="did you mean",
             where=True),
        Case("missing-field", c, CHECK, _sub("  travel_range: 50 um", ""),
             expect="missing required field", where=True),
        Case("duplicate-set-names", c, CHECK, _sets(2).replace("name: s1", "name: s0"),
             expect="unique", where=True),
        Case("no-sets", c, CHECK, BASE.split("actuator_sets:")[0] + "actuator_sets: []\n",
             expect="at least 1", where=True),
        Case("beam-count-1e30", c, CHECK, _sub("beam_count: 2", "beam_count: " + "1" + "0" * 30),
             expect="16", where=True),
        Case("beam-count-float", c, CHECK, _sub("beam_count: 2", "beam_count: 1e30"),
             expect="integer", where=True),
        Case("beam-count-negative", c, CHECK, _sub("beam_count: 2", "beam_count: -1"),
             expect="1", where=True),
        Case("beam-count-bool", c, CHECK, _sub("beam_count: 2", "beam_count: true"),
             expect="integer", where=True),
        Case("sets-65", c, CHECK, _sets(65), expect="65 items; the limit is 64", where=True),
        Case("sets-1000", c, CHECK, _sets(1000), expect="YAML nodes|limit", where=True),
        Case("sets-64-report", c, ("report", "{f}", "-o", "{d}/out", "--no-pdf"), _sets(64),
             exits=(0,), outputs=("out", "out/device.html")),
        Case("calibration-points-2000", c, CHECK, _points(2000), expect="limit", where=True),
        Case("name-300-chars", c, CHECK, _sub("name: push_demo", "name: " + "n" * 300),
             expect="string of 300 characters; the limit is 200", where=True),
        Case("name-empty", c, CHECK, _sub("name: push_demo", 'name: ""'), expect="at least 1",
             where=True),
        Case("name-number", c, CHECK, _sub("name: push_demo", "name: 12"), expect="string",
             where=True),
        Case("friction-string", c, CHECK, _sub("friction: 0.4", "friction: lots"),
             expect="number", where=True),
        Case("null-slider", c, CHECK, _sub("slider:\n", "slider:\nx_:\n"), expect="slider",
             where=True),
        Case("enum-case-AC", c, CHECK, _sub("waveform: ac", "waveform: AC").replace(
             "intended_mode: push", "intended_mode: Push"), exits=(0, 1)),
        Case("enum-bad", c, CHECK, _sub("waveform: ac", "waveform: sine"), expect="waveform",
             where=True),
    ]  # fmt: skip


NASTY = '<script>alert(1)</script> & "q" ../../../etc/passwd'


def _names() -> list[Case]:
    c = "names"
    rep = ("report", "{f}", "-o", "{d}/out", "--no-pdf")
    return [
        Case("html-in-device-name", c, rep, _sub("name: push_demo", f"name: '{NASTY}'"),
             exits=(0,), outputs=("out", "out/device.html")),
        Case("html-in-set-name", c, rep, _sub("name: forward", f"name: '{NASTY}'"),
             exits=(0,), outputs=("out", "out/device.html")),
        Case("html-in-description", c, ("report", "{f}", "-o", "{d}/out"),
             _sub("description: ", "description: <img src=x onerror=alert(1)> "),
             exits=(0,), outputs=("out", "out/device.html", "out/device.pdf")),
        Case("newline-in-name", c, CHECK, _sub("name: push_demo", 'name: "a\\nb\\u0000c"'),
             exits=(0, 1, 2)),
        Case("rtl-and-emoji-name", c, CHECK, _sub("name: push_demo", "name: 'ab\u202ecd 🚀'"),
             exits=(0, 1)),
    ]  # fmt: skip


def _cli_numbers() -> list[Case]:
    c = "cli-numbers"
    return [
        Case("simulate-cycles-1e12", c, (*SIM, "--cycles", "1000000000000"),
             expect="1,000,000"),
        Case("simulate-cycles-0", c, (*SIM, "--cycles", "0"), expect=">= 1"),
        Case("simulate-cycles-negative", c, (*SIM, "--cycles", "-5"), expect=">= 1"),
        Case("simulate-cycles-float", c, (*SIM, "--cycles", "1e3"), expect="integer|valid"),
        Case("simulate-varpi-nan", c, ("simulate", "--varpi", "nan", "--alpha", "2", "--beta",
             "0.5", "--kappa", "0.15"), expect="finite"),
        Case("simulate-varpi-inf", c, ("simulate", "--varpi", "inf", "--alpha", "2", "--beta",
             "0.5", "--kappa", "0.15"), expect="finite"),
        Case("simulate-varpi-negative", c, ("simulate", "--varpi", "-1", "--alpha", "2", "--beta",
             "0.5", "--kappa", "0.15"), expect="> 0"),
        Case("simulate-max-cycles-huge", c, (*SIM, "--periodic", "--max-cycles", "10000000000000"),
             expect="1,000,000"),
        Case("simulate-residual-nan", c, (*SIM, "--periodic", "--residual-tol", "nan"),
             expect="finite"),
        Case("simulate-old-tol", c, (*SIM, "--periodic", "--tol", "1e-8"),
             expect="--residual-tol"),
        Case("tolerance-n-1e12", c, (*TOL, *SPREAD, "-n", "1000000000000"),
             expect="1,000,000"),
        Case("tolerance-n-0", c, (*TOL, *SPREAD, "-n", "0"), expect=">= 1"),
        Case("tolerance-seed-negative", c, (*TOL, *SPREAD, "-n", "2", "--seed", "-1"),
             expect="2\\*\\*128"),
        Case("tolerance-seed-2^128", c, (*TOL, *SPREAD, "-n", "2", "--seed", str(2**128)),
             expect="2\\*\\*128"),
        Case("tolerance-seed-2^70", c, (*TOL, *SPREAD, "-n", "2", "--seed", str(2**70), "-q"),
             exits=(0,)),
        Case("tolerance-gauss", c, (*TOL, "{spread}", "slider.beam_width=gauss:0.3um", "-n", "2"),
             expect="unknown distribution 'gauss'; use normal, uniform"),
        Case("tolerance-old-tol", c, (*TOL, "--tol", "drive.frequency=2%", "-n", "2"),
             expect="--spread"),
        Case("tolerance-spread-nan", c, (*TOL, "{spread}", "drive.frequency=nan%", "-n", "2"),
             expect="> 0"),
        Case("tolerance-spread-bomb", c, (*TOL, "{spread}", "slider.beam_width=normal:1 um**9**9",
             "-n", "2"), expect="power|cannot read"),
        Case("tolerance-file-bomb", c, (*TOL, "--tolerances", "{f}", "-n", "2"),
             _lol(at_top=True).replace("name:", "tolerances:"), expect="YAML nodes"),
        Case("sweep-old-tol-nan", c, (*MAP, "--tol", "nan"), expect="--residual-tol"),
        Case("sweep-residual-nan", c, (*MAP, "--residual-tol", "nan"), expect="finite"),
        Case("sweep-residual-negative", c, (*MAP, "--residual-tol", "-1"), expect="finite"),
        Case("sweep-workers-0", c, (*MAP, "--workers", "0"), expect=">= 1"),
        Case("sweep-workers-1e6", c, (*MAP, "--workers", "1000000"), expect="<= 1,024"),
        Case("sweep-chunksize-0", c, (*MAP, "--chunksize", "0"), expect=">= 1"),
        Case("sweep-range-nan", c, ("sweep", "pushpull", "--varpi", "nan", "--alpha", "2",
             "--beta", "0.5", "--kappa", "0.15", "-q"), expect="not finite"),
        Case("sweep-grid-1e24", c, ("sweep", "pushpull", "--varpi", "0.001:1000:0.001",
             "--alpha", "0.001:1000:0.001", "--beta", "0.001:1000:0.001", "--kappa",
             "0.001:1000:0.001", "-q"), expect="points"),
        Case("sweep-regime-too-long", c, ("sweep", "regime", "--varpi", "0.001:10:0.001",
             "--max-cycles", "1000000", "-q", "-j", "2"), expect="would take"),
        Case("sweep-lambda-kappa-nan", c, ("sweep", "lambda", "--kappa", "nan", "--beta", "1",
             "-q"), expect="finite"),
        Case("sweep-regime-max-cycles-1", c, ("sweep", "regime", "--max-cycles", "1", "-q"),
             expect=">= 2"),
        Case("sweep-executor-unknown", c, (*MAP, "-x", "gpu"), expect="unknown executor"),
        Case("sweep-executor-uppercase", c, (*MAP, "-x", "SERIAL", "--json"), exits=(0,)),
        Case("atlas-range-nan", c, (*ATLAS, "--varpi", "nan"), expect="not finite"),
        Case("atlas-executor-unknown", c, (*ATLAS, "--varpi", "1", "-x", "gpu"),
             expect="unknown executor"),
        Case("atlas-no-out", c, ("sweep", "atlas", "--varpi", "1", "--alpha", "2", "--beta",
             "0.5", "--kappa", "0.15"), expect="--out DIR"),
        Case("atlas-device-and-grid", c, ("sweep", "atlas", str(REPO / "devices" /
             "push_demo.yaml"), "--varpi", "1", "-o", "{d}/atlas"),
             expect="not with a device FILE"),
    ]  # fmt: skip


def _cli_paths() -> list[Case]:
    c = "cli-paths"
    return [
        Case("sweep-out-proc", c, (*MAP, "-x", "serial", "-o", "/proc/x.csv"),
             expect="cannot write|cannot create"),
        Case("sweep-figure-proc", c, (*MAP, "-x", "serial", "--figure", "/proc/x.png"),
             expect="cannot write"),
        Case("sweep-figure-gif", c, (*MAP, "-x", "serial", "--figure", "{d}/x.gif"),
             expect=".svg"),
        Case("sweep-out-dev-null", c, (*MAP, "-x", "serial", "-o", "/dev/null"),
             expect="special file"),
        Case("sweep-out-is-dir", c, (*MAP, "-x", "serial", "-o", "{f}"), _dir,
             expect="is a directory"),
        Case("sweep-out-under-file", c, (*MAP, "-x", "serial", "-o", "{f}/sub/x.csv"), "x",
             expect="is a file"),
        Case("sweep-out-ok", c, (*MAP, "-x", "serial", *OUT), exits=(0,), outputs=MAP_OUT),
        Case("tolerance-out-proc", c, (*TOL, *SPREAD, "-n", "2", "-o", "/proc/t.csv"),
             expect="cannot"),
        Case("report-out-proc", c, ("report", str(BIDIR), "-o", "/proc/reports"),
             expect="cannot"),
        Case("report-out-is-file", c, ("report", str(BIDIR), "-o", "{f}"), "x",
             expect="not a directory"),
        Case("report-out-under-file", c, ("report", str(BIDIR), "-o", "{f}/sub"), "x",
             expect="is a file"),
        Case("schema-out-proc", c, ("schema", "-o", "/proc/s.json"), expect="cannot write"),
        Case("schema-out-is-dir", c, ("schema", "-o", "{f}"), _dir, expect="is a directory"),
        Case("calibrate-out-proc", c, ("calibrate", str(BIDIR), "{f}", "-o", "/proc/c.yaml"),
             "voltage [V],speed [um/s]\n5,10\n", expect="cannot write"),
        Case("check-proc-file", c, ("check", "/proc/self/status"),
             expect="invalid YAML|expected|unknown field"),
    ]  # fmt: skip


def corpus() -> list[Case]:
    """Every case, in category order."""
    cases = _yaml() + _units() + _structure() + _names() + _cli_numbers() + _cli_paths()
    ids = [c.id for c in cases]
    assert len(ids) == len(set(ids)), "case ids must be unique"
    return cases


def prepare(case: Case, workdir: Path, *, legacy: bool = False) -> list[str]:
    """Write the case's file into ``workdir`` and return its arguments."""
    f = workdir / ("device.yaml" if case.category != "cli-paths" else "target")
    if callable(case.content):
        case.content(f)
    elif isinstance(case.content, bytes):
        f.write_bytes(case.content)
    elif isinstance(case.content, str):
        f.write_bytes(case.content.encode("utf-8"))
    spread = "--tol" if legacy else "--spread"
    return [
        a.replace("{f}", str(f)).replace("{d}", str(workdir)).replace("{spread}", spread)
        for a in case.args
    ]


def inputs(case: Case, workdir: Path) -> set[Path]:
    """Paths that exist in ``workdir`` before the run."""
    return {p for p in workdir.rglob("*")} | ({workdir / "device.yaml", workdir / "target"})


def verdict(
    case: Case, workdir: Path, before: set[Path], code: int | None, out: str, err: str
) -> list[str]:
    """What is wrong with a finished run (empty: the case passes)."""
    problems = []
    if code is None:
        return ["did not end within the time limit"]
    if code not in case.exits:
        problems.append(f"exit {code}, expected {case.exits}")
    text = err + (out if code in (0, 1) else "")
    if "Traceback" in out + err:
        problems.append("traceback")
    if case.expect and not re.search(case.expect, text):
        problems.append(f"message lacks /{case.expect}/")
    if case.where:
        f = re.escape(str(workdir / "device.yaml"))
        if not re.search(rf"{f}:\d+:\d+", err):
            problems.append("message lacks file:line:col")
    allowed = {workdir / o for o in case.outputs}
    stray = sorted(
        str(p.relative_to(workdir)) for p in workdir.rglob("*") if p not in before | allowed
    )
    if stray:
        problems.append(f"stray output {stray[:3]}")
    for page in workdir.rglob("*.html"):  # names are escaped, never markup
        html = page.read_text(encoding="utf-8", errors="replace")
        if "<script>alert(" in html or "<img src=x" in html:
            problems.append(f"unescaped markup in {page.name}")
    missing = [o for o in case.outputs if not (workdir / o).exists()]
    if code == 0 and missing:
        problems.append(f"missing output {missing}")
    return problems


def _run_subprocess(
    case: Case, workdir: Path, legacy: bool, timeout: float = TIME_LIMIT_S
) -> tuple[list[str], float, float]:
    """Run one case as a subprocess: (problems, wall seconds, CPU seconds or nan)."""
    import subprocess
    import sys
    import time

    args = prepare(case, workdir, legacy=legacy)
    before = inputs(case, workdir)
    cpu_file = workdir.parent / f".{workdir.name}.cpu"
    code = (
        "import atexit, os, resource, sys\n"
        "def cpu():\n"
        "    r = [resource.getrusage(w)\n"
        "         for w in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN)]\n"
        "    with open(os.environ['BETV_CPU_FILE'], 'w') as fh:\n"
        "        fh.write(str(sum(u.ru_utime + u.ru_stime for u in r)))\n"
        "atexit.register(cpu)\n"
        "from betvdesign.cli import main\n"
        "sys.argv = ['betv', *sys.argv[1:]]\n"
        "main()\n"
    )
    t0 = time.perf_counter()
    try:
        r = subprocess.run(
            [sys.executable, "-c", code, *args],
            capture_output=True,
            text=True,
            errors="replace",
            timeout=timeout,
            cwd=workdir,
            env=os.environ | {"COLUMNS": "200", "BETV_CPU_FILE": str(cpu_file)},
        )
        res = verdict(case, workdir, before, r.returncode, r.stdout, r.stderr)
    except subprocess.TimeoutExpired:
        res = verdict(case, workdir, before, None, "", "")
    try:
        cpu = float(cpu_file.read_text())
        cpu_file.unlink()
    except (OSError, ValueError):
        cpu = float("nan")
    return res, time.perf_counter() - t0, cpu


def main() -> None:  # pragma: no cover - a reporting script
    import argparse
    import shutil
    import tempfile
    from concurrent.futures import ThreadPoolExecutor

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--legacy", action="store_true", help="spell --spread as --tol")
    ap.add_argument("-j", type=int, default=2)
    ap.add_argument("-k", default="", help="only cases whose id contains this")
    ap.add_argument("--timeout", type=float, default=TIME_LIMIT_S, help="wall-clock limit [s]")
    opts = ap.parse_args()
    cases = [c for c in corpus() if opts.k in c.id]

    def one(case: Case) -> tuple[Case, list[str], float, float]:
        d = Path(tempfile.mkdtemp(prefix="betv-hostile-"))
        try:
            problems, dt, cpu = _run_subprocess(case, d, opts.legacy, opts.timeout)
        finally:
            shutil.rmtree(d, ignore_errors=True)
        return case, problems, dt, cpu

    with ThreadPoolExecutor(opts.j) as pool:
        results = list(pool.map(one, cases))
    rows = []
    for case, problems, dt, cpu in results:
        status = "ok" if not problems else "; ".join(problems)
        rows.append((case.category, case.id, dt, status))
        print(f"{case.category:12} {case.id:32} {dt:6.1f} s  {status}  [cpu {cpu:.1f} s]")
    print()
    print(table(rows))


#: Columns of the table: what went wrong first, most serious first.
COLUMNS = ("cases", "pass", "timeout", "traceback", "wrong exit", "stray output", "message")


def classify(status: str) -> str:
    """The table column of one case's status line (see :data:`COLUMNS`)."""
    if status == "ok":
        return "pass"
    for key, col in (
        ("did not end", "timeout"),
        ("traceback", "traceback"),
        ("exit ", "wrong exit"),
        ("stray", "stray output"),
        ("unescaped", "stray output"),
        ("missing output", "stray output"),
    ):
        if key in status:
            return col
    return "message"  # right exit, but the message lacks the field, limit or position


def table(rows: list[tuple[str, str, float, str]]) -> str:
    """Markdown table by category from (category, id, seconds, status) rows."""
    import collections

    counts: dict[str, collections.Counter] = {}
    for cat, _, _, status in rows:
        c = counts.setdefault(cat, collections.Counter())
        c["cases"] += 1
        c[classify(status)] += 1
    total: collections.Counter = collections.Counter()
    lines = ["| category | " + " | ".join(COLUMNS) + " |", "|---" * (len(COLUMNS) + 1) + "|"]
    for cat, c in counts.items():
        total.update(c)
        lines.append(f"| {cat} | " + " | ".join(str(c[k]) for k in COLUMNS) + " |")
    lines.append("| **all** | " + " | ".join(str(total[k]) for k in COLUMNS) + " |")
    return "\n".join(lines)


if __name__ == "__main__":  # pragma: no cover
    main()
