"""Invariant (hypothesis): whatever the text, the loader returns a spec or raises SpecError
whose every issue names the file — never another exception (no traceback for users)."""

from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from betvdesign.errors import BetvError, SpecError
from betvdesign.nondim.device import derive
from betvdesign.spec.loader import load_device_text

BASE = (Path(__file__).resolve().parent / "data" / "specs" / "valid_base.yaml").read_text()
LINES = BASE.splitlines()

values = st.one_of(
    st.text(max_size=12),
    st.sampled_from(
        [
            "",
            "-",
            "[",
            "{a: 1}",
            "[1, 2]",
            "null",
            "true",
            "1e999 um",
            "0 Hz",
            "&a x",
            "*a",
            "<<: *a",
            "'5 um'",
            "5 um/s",
            "-3 deg",
            "nan kHz",
        ]
    ),
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
)


@st.composite
def mutated(draw):
    lines = list(LINES)
    for _ in range(draw(st.integers(1, 4))):
        i = draw(st.integers(0, len(lines) - 1))
        op = draw(st.sampled_from(["value", "delete", "duplicate", "indent", "insert"]))
        line = lines[i]
        if op == "value" and ":" in line:
            key = line.split(":", 1)[0]
            lines[i] = f"{key}: {draw(values)}"
        elif op == "delete":
            del lines[i]
        elif op == "duplicate":
            lines.insert(i, line)
        elif op == "indent":
            lines[i] = " " * draw(st.integers(0, 6)) + line.lstrip()
        else:
            lines.insert(i, f"{draw(st.text(max_size=8))}: {draw(values)}")
        if not lines:
            break
    return "\n".join(lines) + "\n"


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(mutated())
def test_mutated_files_never_crash(text):
    try:
        spec = load_device_text(text, "fuzz.yaml")
    except SpecError as exc:
        assert exc.issues
        assert all(str(i).startswith("fuzz.yaml") for i in exc.issues)
        return
    try:
        derive(spec)
    except BetvError:
        pass


@settings(max_examples=100, deadline=None)
@given(st.text(max_size=200))
def test_arbitrary_text_never_crashes(text):
    try:
        load_device_text(text, "any.yaml")
    except SpecError as exc:
        assert all(str(i).startswith("any.yaml") for i in exc.issues)
