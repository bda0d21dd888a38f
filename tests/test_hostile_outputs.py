"""Outputs written whole or not at all, and output paths refused up front
(betvdesign.output.files); the limits' overrides and the study-time refusal
(betvdesign.spec.limits)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from betvdesign.errors import SpecError, UsageError
from betvdesign.output.files import (
    atomic_path,
    check_output_dir,
    check_output_file,
    write_atomic,
    write_group,
)
from betvdesign.spec import limits
from betvdesign.spec.loader import load_device

REPO = Path(__file__).resolve().parents[1]


def test_write_group_is_all_or_nothing(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A failure at the second rename leaves neither new file (the first is removed)."""
    html, pdf = tmp_path / "r.html", tmp_path / "r.pdf"
    real_replace = os.replace
    calls = []

    def flaky(src, dst):
        calls.append(dst)
        if len(calls) == 2:
            raise OSError(28, "No space left on device")
        real_replace(src, dst)

    monkeypatch.setattr(os, "replace", flaky)
    with pytest.raises(UsageError, match="No space left"):
        write_group({html: "<html>", pdf: b"%PDF"})
    monkeypatch.setattr(os, "replace", real_replace)
    assert sorted(p.name for p in tmp_path.iterdir()) == []
    assert write_group({html: "<html>", pdf: b"%PDF"}) == [html, pdf]
    assert html.read_text() == "<html>" and pdf.read_bytes() == b"%PDF"
    assert oct(html.stat().st_mode & 0o777) == "0o644"


def test_write_group_interrupted_while_writing_leaves_old_files(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Ctrl-C while the second member is being flushed: the old HTML stays, no
    temporary file is left."""
    html = tmp_path / "r.html"
    html.write_text("old")
    real_fsync = os.fsync
    calls = []

    def interrupted(fd):
        calls.append(fd)
        if len(calls) == 2:
            raise KeyboardInterrupt
        real_fsync(fd)

    monkeypatch.setattr(os, "fsync", interrupted)
    with pytest.raises(KeyboardInterrupt):
        write_group({html: "new", tmp_path / "r.pdf": b"%PDF"})
    assert html.read_text() == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.html"]


def test_atomic_path_keeps_the_old_file_on_error(tmp_path: Path) -> None:
    target = tmp_path / "fig.svg"
    target.write_text("old")
    with pytest.raises(RuntimeError), atomic_path(target) as tmp:
        assert tmp.suffix == ".svg" and tmp.parent == tmp_path
        tmp.write_text("half")
        raise RuntimeError("plot failed")
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["fig.svg"]
    write_atomic(target, "new")
    assert target.read_text() == "new"


@pytest.mark.parametrize(
    ("make", "path", "fragment"),
    [
        (None, "/proc/x.csv", "cannot write in /proc"),
        (None, "/dev/null", "special file"),
        ("dir", "{t}/d", "is a directory"),
        ("file", "{t}/f/sub/x.csv", "is a file, not a directory"),
        (None, "{t}/missing/x.csv", "does not exist"),
        (None, "{t}/x.gif", "must end in .svg"),
    ],
)
def test_unwritable_output_files_are_refused(tmp_path: Path, make, path, fragment) -> None:
    if make == "dir":
        (tmp_path / "d").mkdir()
    if make == "file":
        (tmp_path / "f").write_text("x")
    p = path.replace("{t}", str(tmp_path))
    with pytest.raises(UsageError, match=fragment):
        check_output_file(p, suffixes=(".svg", ".csv") if "gif" in p else None)
    assert sorted(q.name for q in tmp_path.iterdir()) in ([], ["d"], ["f"])


def test_output_dir_checked_without_being_created(tmp_path: Path) -> None:
    target = tmp_path / "a" / "b"
    assert check_output_dir(target, create=False) == target and not target.exists()
    assert check_output_dir(target).is_dir()
    with pytest.raises(UsageError, match="cannot write in /proc"):
        check_output_dir("/proc/reports")
    (tmp_path / "file").write_text("x")
    with pytest.raises(UsageError, match="not a directory"):
        check_output_dir(tmp_path / "file")


def test_file_size_limit_and_its_override(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    """A device file padded past the limit is refused with the size and the variable to
    set; raising the limit accepts the same file."""
    text = (REPO / "devices" / "push_demo.yaml").read_text() + "#" * 3000 + "\n"
    f = tmp_path / "padded.yaml"
    f.write_text(text)
    monkeypatch.setenv(limits.FILE_BYTES_ENV, "2000")
    with pytest.raises(SpecError, match=r"file is \d,\d{3} bytes; the limit is 2,000 bytes"):
        load_device(f)
    monkeypatch.setenv(limits.FILE_BYTES_ENV, "10000")
    assert load_device(f).name == "push_demo"
    monkeypatch.setenv(limits.FILE_BYTES_ENV, "-3")
    with pytest.raises(UsageError, match="finite number > 0"):
        load_device(f)


def test_study_time_refusal_gives_the_estimate(monkeypatch: pytest.MonkeyPatch) -> None:
    # 10⁶ points at 5 ms on 2 workers: 2500 s, under 12 h; at 1 h it is refused
    limits.refuse_long_study("pushpull", 10**6, 5e-3, 2)
    monkeypatch.setenv(limits.STUDY_HOURS_ENV, "0.5")
    with pytest.raises(UsageError, match=r"would take ≈ 41.7 min, more than the 30 min limit"):
        limits.refuse_long_study("pushpull", 10**6, 5e-3, 2)
    with pytest.raises(UsageError, match="exceed the limit of 10,000,000 points"):
        limits.refuse_long_study("pushpull", 10**7 + 1, 5e-3, 2)
