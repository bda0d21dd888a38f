"""docs/tutorial.md is executed: every ```sh and ```python block, in order, in one empty
directory, with this environment's `betv` and `python3` first on PATH. A block's fence
may say `exit=N` (expected exit status, default 0) and `requires=fix` (skipped, and
said so, while `betv fix` does not exist yet). Key results of the session are checked
against what the tutorial's text claims (the failing rule, the fixed verdict, P(push))."""

import csv
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

TUTORIAL = Path(__file__).resolve().parents[1] / "docs" / "tutorial.md"
BLOCK = re.compile(r"^```(sh|python)([^\n]*)\n(.*?)^```", re.S | re.M)


def blocks() -> list[tuple[str, dict[str, str], str]]:
    out = []
    for lang, info, body in BLOCK.findall(TUTORIAL.read_text(encoding="utf-8")):
        attrs = dict(a.split("=", 1) for a in info.split() if "=" in a)
        out.append((lang, attrs, body))
    return out


def test_tutorial_blocks_are_found():
    found = blocks()
    assert len(found) >= 8
    assert {lang for lang, _, _ in found} == {"sh", "python"}
    assert any(a.get("requires") == "fix" for _, a, _ in found)


@pytest.mark.slow
def test_tutorial_runs(tmp_path):
    bindir = str(Path(sys.executable).parent)
    env = {**os.environ, "PATH": bindir + os.pathsep + os.environ.get("PATH", "")}
    env.pop("COLUMNS", None)
    has_fix = (
        subprocess.run(["betv", "fix", "--help"], env=env, capture_output=True).returncode == 0
    )
    outputs: list[str] = []
    skipped = 0
    for i, (lang, attrs, body) in enumerate(blocks()):
        if attrs.get("requires") == "fix" and not has_fix:
            skipped += 1
            outputs.append("")
            continue
        cmd = (
            ["bash", "-e", "-o", "pipefail", "-c", body]
            if lang == "sh"
            else [sys.executable, "-c", body]
        )
        r = subprocess.run(cmd, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600)
        want = int(attrs.get("exit", "0"))
        assert r.returncode == want, f"block {i + 1} ({lang}) exit {r.returncode}:\n{body}\n" + (
            r.stdout + r.stderr
        )
        assert "Traceback" not in r.stderr, r.stderr
        outputs.append(r.stdout)
    text = "\n".join(outputs)
    # what the tutorial's prose says happens
    assert "my_motor: FAIL" in text and "FAIL frequency-window" in text
    assert "pull instead of push" in text
    assert "fail ['frequency-window', 'mode']" in text
    assert "my_motor.yaml: FAIL frequency-window, mode" in text  # --quiet
    assert re.search(r"^3 kHz pass push$", text, re.M)
    assert "my_motor: PASS" in text
    if has_fix:
        assert (
            "drive.frequency: 1 kHz ->" in text and "my_motor: PASS  (my_motor_fixed.yaml)" in text
        )
    assert re.search(r"P\(push\) 1\.000", text)
    assert (tmp_path / "reports" / "my_motor.html").is_file()
    # section 6: the idealised model's verdict depends on e; the measured terms
    assert "warning model-adequacy: mode-flips" in text and "e ≈ 0.166 (→ not driven)" in text
    assert "my_motor: PASS  (my_motor_measured.yaml)" in text and "roll-off ×0.136" in text
    assert "Q_v 40 Q_h 25 e" in text and "e ≈ 0.165 (→ not driven)" in text
    assert len(re.findall(r"P\(push\) 1\.000", text)) == 2
    assert skipped == (0 if has_fix else 1)
    # section 7: the layout, read back, edited in KLayout
    assert "my_motor: PASS  (my_motor_poly.yaml)" in text and "(my_motor.gds)" in text
    assert "wrote my_motor_back.yaml" in text and "my_motor_edited.gds): PASS" in text
    assert re.search(r"w_flex .* 4 µm", text)
    assert "my_motor_edited.gds: already passes `betv check` with its mode margin" in text
    # section 8: the springs from the drawing; a drawn change moves the verdict
    assert re.search(r"f_v,geom .* 121\.2 kHz", text)
    assert "length 240 µm -> 867.4 µm brings ϖ 0.0495 to the window's edge 0.5" in " ".join(
        text.split()
    )
    with (tmp_path / "drawn_sweep.csv").open() as fh:
        varpi = [round(float(r["varpi"]), 3) for r in csv.DictReader(fh)]
    assert varpi == [0.05, 0.1, 0.168, 0.253, 0.354, 0.471, 0.604]
    assert "drawn900.yaml: FAIL mode" in text
    # section 8: nothing measured: the stroke predicted from the drawing
    assert re.search(r"T_max .* 1518 K", text) and re.search(r"u_static .* 13\.3 µm", text)
    assert "38.4% of the static stroke is left" in " ".join(text.split())
