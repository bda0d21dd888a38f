"""The stored answer of ``betv check`` (betvdesign.output.answers): given again only for
the same inputs, and then byte for byte what the check prints afresh."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from conftest import DEVICES
from typer.testing import CliRunner

from betvdesign.cli import app
from betvdesign.cli import check as check_cli
from betvdesign.output import answers


@pytest.fixture
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> dict[str, int]:
    """The answer cache on, in ``tmp_path/answers``; ``runs["n"]`` counts the checks that
    really ran (the others were answered from the cache)."""
    monkeypatch.setenv(answers.CACHE_ENV, str(tmp_path / "answers"))
    runs = {"n": 0}
    real = check_cli._answer

    def counted(*args: object, **kwargs: object) -> int:
        runs["n"] += 1
        return real(*args, **kwargs)

    monkeypatch.setattr(check_cli, "_answer", counted)
    return runs


def _run(*args: str) -> tuple[int, str, str]:
    r = CliRunner().invoke(app, ["check", *args])
    return r.exit_code, r.stdout, r.stderr


@pytest.mark.parametrize(
    "args",
    [
        ("-q", "push_demo"),
        ("--json", "push_demo"),
        ("shin2004",),
        ("--json", "--select", "speed", "--select", "nope", "shin2004"),
    ],
    ids=["quiet-pass", "json-pass", "text-fail", "json-select-warning"],
)
def test_a_stored_answer_is_the_fresh_one_byte_for_byte(
    cache: dict[str, int], args: tuple[str, ...]
) -> None:
    """Uncached (--no-cache), first cached run (checks and stores), second (from the
    cache, no check run): the same stdout, stderr and exit status."""
    *opts, name = args
    argv = [*opts, str(DEVICES / f"{name}.yaml")]
    fresh = _run("--no-cache", *argv)
    assert cache["n"] == 1 and fresh[0] in (0, 1)
    first = _run(*argv)
    assert cache["n"] == 2
    again = _run(*argv)
    assert cache["n"] == 2  # answered from the cache
    assert fresh == first == again
    if "--select" in opts:
        assert "nope" in fresh[2]  # the warning on stderr is part of the answer


def test_any_changed_input_is_checked_afresh(
    cache: dict[str, int], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A changed byte of the device or of the process file it names, another option, a
    changed package file, --no-cache or the cache turned off: the check runs again; bad
    input (exit 2) is never stored."""
    proc = tmp_path / "myproc.yaml"
    shutil.copy(Path(answers.__file__).parents[1] / "data" / "processes" / "demo25.yaml", proc)
    text = (DEVICES / "push_demo.yaml").read_text("utf-8")
    dev = tmp_path / "dev.yaml"
    dev.write_text(text.replace("process: demo25", "process: myproc.yaml", 1), "utf-8")
    base = _run("-q", str(dev))
    assert base[0] == 0 and cache["n"] == 1
    assert _run("-q", str(dev)) == base and cache["n"] == 1
    proc.write_text(proc.read_text("utf-8") + "\n# a comment\n", "utf-8")
    assert _run("-q", str(dev)) == base and cache["n"] == 2
    dev.write_text(dev.read_text("utf-8") + "\n", "utf-8")
    assert _run("-q", str(dev)) == base and cache["n"] == 3
    assert _run("-q", "--no-advice", str(dev))[0] == 0 and cache["n"] == 4
    assert _run("-q", str(dev), "--no-cache") == base and cache["n"] == 5
    assert _run("-q", str(dev)) == base and cache["n"] == 5  # --no-cache stored nothing
    monkeypatch.setattr(answers, "_CODE", ["another version of the package"])
    assert _run("-q", str(dev)) == base and cache["n"] == 6
    monkeypatch.setenv(answers.CACHE_ENV, "off")
    assert _run("-q", str(dev)) == base and cache["n"] == 7
    assert _run("-q", str(dev)) == base and cache["n"] == 8
    monkeypatch.setenv(answers.CACHE_ENV, str(tmp_path / "answers"))
    stored = len(list((tmp_path / "answers").glob("*.json")))
    proc.write_text("layers: [", "utf-8")
    bad = _run("-q", str(dev))
    assert bad[0] == 2 and "myproc.yaml" in bad[2] and cache["n"] == 9
    assert _run("-q", str(dev)) == bad and cache["n"] == 10
    assert len(list((tmp_path / "answers").glob("*.json"))) == stored


def test_verbose_is_never_cached(cache: dict[str, int]) -> None:
    """--verbose prints the solver's run times: every run checks afresh, stores nothing."""
    argv = ["-v", "--no-advice", "--no-adequacy", str(DEVICES / "push_demo.yaml")]
    assert _run(*argv)[0] == 0 and _run(*argv)[0] == 0 and cache["n"] == 2
    assert not (Path(answers.cache_root()) / "x").parent.exists()


def test_a_damaged_entry_is_a_miss(cache: dict[str, int], tmp_path: Path) -> None:
    """An entry cut short or naming another key is not trusted: the check runs."""
    argv = ["-q", str(DEVICES / "push_demo.yaml")]
    base = _run(*argv)
    (entry,) = (tmp_path / "answers").glob("*.json")
    entry.write_text(entry.read_text("utf-8")[:40], "utf-8")
    assert _run(*argv) == base and cache["n"] == 2
    (entry,) = (tmp_path / "answers").glob("*.json")
    entry.write_text(entry.read_text("utf-8").replace(entry.stem, "0" * 64), "utf-8")
    assert _run(*argv) == base and cache["n"] == 3


def test_a_stored_report_is_the_fresh_one_byte_for_byte(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """``write_reports(cache=True)``: the first report is built and stored, the second
    written from the store, both byte-identical to a report built without the cache (HTML
    and PDF); other options, a changed process file or --timestamp build afresh."""
    from betvdesign.report import ReportOptions, write_reports
    from betvdesign.report import build as report_build

    monkeypatch.setenv(answers.CACHE_ENV, str(tmp_path / "answers"))
    builds = {"n": 0}
    real = report_build.build_report

    def counted(*args: object, **kwargs: object) -> object:
        builds["n"] += 1
        return real(*args, **kwargs)

    monkeypatch.setattr(report_build, "build_report", counted)
    proc = tmp_path / "myproc.yaml"
    shutil.copy(Path(answers.__file__).parents[1] / "data" / "processes" / "demo25.yaml", proc)
    text = (DEVICES / "push_demo.yaml").read_text("utf-8")
    dev = tmp_path / "dev.yaml"
    dev.write_text(text.replace("process: demo25", "process: myproc.yaml", 1), "utf-8")
    opts = ReportOptions(regime_points=5, robustness_points=3, map_points=3, frequency_points=5)

    def report(name: str, **kw: object) -> tuple[object, ...]:
        (w,) = write_reports([dev], tmp_path / name, **{"options": opts, **kw})
        pdf = w.pdf.read_bytes() if w.pdf is not None else None
        return w.html.read_bytes(), pdf, w.verdict, w.figures

    fresh = report("fresh")
    assert builds["n"] == 1
    assert report("first", cache=True) == fresh and builds["n"] == 2
    assert report("again", cache=True) == fresh and builds["n"] == 2  # from the store
    small = report("no-pdf", cache=True, pdf=False)
    assert small[0] == fresh[0] and small[1] is None and builds["n"] == 3
    proc.write_text(proc.read_text("utf-8") + "\n# a comment\n", "utf-8")
    assert report("changed", cache=True) == fresh and builds["n"] == 4
    stamped = report("stamped", cache=True, timestamp=True, pdf=False)
    assert stamped[0] != fresh[0] and builds["n"] == 5
    assert report("stamped-again", cache=True, timestamp=True, pdf=False)[0] != fresh[0]
    assert builds["n"] == 6


def test_notes_printed_while_checking_are_not_kept(
    cache: dict[str, int], monkeypatch: pytest.MonkeyPatch
) -> None:
    """A note on stderr while the check runs (numba compiling the kernels) is printed as it
    comes and is not part of the stored answer."""
    import sys

    real = check_cli._answer

    def noisy(*args: object, **kwargs: object) -> int:
        print("betv: compiling the solver kernels (test)", file=sys.stderr)
        return real(*args, **kwargs)

    monkeypatch.setattr(check_cli, "_answer", noisy)
    argv = ["-q", str(DEVICES / "push_demo.yaml")]
    first = _run(*argv)
    assert "compiling" in first[2]
    again = _run(*argv)
    assert cache["n"] == 1 and again == (first[0], first[1], "")


@pytest.mark.slow
def test_cli_report_uses_the_store_unless_told_not_to(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """``betv report`` writes a repeated report from the store (the same HTML); with
    --no-cache it builds again."""
    from betvdesign.report import build as report_build

    monkeypatch.setenv(answers.CACHE_ENV, str(tmp_path / "answers"))
    builds = {"n": 0}
    real = report_build.build_report

    def counted(*args: object, **kwargs: object) -> object:
        builds["n"] += 1
        return real(*args, **kwargs)

    monkeypatch.setattr(report_build, "build_report", counted)
    pages = []
    for i, extra in enumerate(([], [], ["--no-cache"])):
        out = tmp_path / f"out{i}"
        argv = ["report", str(DEVICES / "push_demo.yaml"), "-o", str(out), "--no-pdf", "-q"]
        r = CliRunner().invoke(app, [*argv, *extra])
        assert r.exit_code == 0, r.output
        pages.append((out / "push_demo.html").read_bytes())
    assert builds["n"] == 2 and pages[0] == pages[1] == pages[2]
