"""``sorgui open``: a saved report shown in the window, or with ``-o`` written to files without
it; and the window's command line (real ``sorgui`` processes)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from sorgui import __version__, cli

SORGUI = [sys.executable, "-m", "sorgui.cli"]
TORUS = "(x^2+y^2+z^2+3)^2-16(x^2+y^2)"


def sorgui(*args: str, timeout: float = 300, **kwargs) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*SORGUI, *args], capture_output=True, text=True, timeout=timeout, **kwargs)


def one_line(stderr: str) -> str:
    assert stderr.count("\n") == 1 and stderr.startswith("sorgui: ") and "Traceback" not in stderr, stderr
    return stderr.strip()


@pytest.fixture(scope="module")
def torus_report(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("report") / "torus.sorgui.json"
    done = sorgui("analyze", TORUS, "-o", str(path))
    assert done.returncode == 0, done.stderr
    return path


def test_version_and_help_are_answered_at_once() -> None:
    version = sorgui("--version", timeout=60)
    assert version.returncode == 0 and version.stdout == f"sorgui {__version__}\n" and version.stderr == ""
    helped = sorgui("open", "--help", timeout=60)
    assert helped.returncode == 0 and "usage: sorgui open" in helped.stdout and helped.stderr == ""
    assert "-o OUTPUT" in helped.stdout and "--timeout" in helped.stdout


@pytest.mark.parametrize(
    "environment",
    [
        {"QT_QPA_PLATFORM": "offscreen"},
        {"QT_QPA_PLATFORM": "minimal"},
        {"DISPLAY": None},
        {"DISPLAY": ":98765", "QT_QPA_PLATFORM": None},  # no X server there: Qt aborted, exit 134
    ],
)
def test_the_window_without_a_display_is_one_line(torus_report: Path, environment: dict[str, str | None]) -> None:
    """Qt offscreen has no OpenGL window for the 3D view, and Qt without X aborts: said, exit 1."""
    env = {k: v for k, v in {**os.environ, **environment}.items() if v is not None}
    for args in (["open", str(torus_report)], [], [str(torus_report)]):
        done = sorgui(*args, env=env, timeout=120)
        assert done.returncode == 1 and "the window needs a display" in one_line(done.stderr), done.stderr


def test_display_problem_names_what_is_missing() -> None:
    assert cli.display_problem({"DISPLAY": ":0"}, "linux", opens=lambda display: True) is None
    refused = cli.display_problem({"DISPLAY": ":99"}, "linux", opens=lambda display: False)
    assert refused is not None and "DISPLAY=:99 cannot be opened" in refused  # Qt aborted there: exit 134
    assert cli.display_problem({"QT_QPA_PLATFORM": "wayland", "WAYLAND_DISPLAY": "w"}, "linux") is None
    assert "DISPLAY is not set" in cli.display_problem({}, "linux")
    assert "offscreen" in cli.display_problem({"QT_QPA_PLATFORM": "offscreen", "DISPLAY": ":0"}, "linux")
    assert cli.display_problem({}, "win32") is None


def test_open_writes_the_files_of_a_report_without_the_window(torus_report: Path, tmp_path: Path) -> None:
    """The same writers as ``sorgui analyze -o``: the JSON reads back the same, a STEP file holds
    the torus, a mesh and a Markdown report with its picture are written; no display is needed."""
    env = {k: v for k, v in os.environ.items() if k != "DISPLAY"}
    targets = [tmp_path / name for name in ("again.json", "torus.stl", "torus.md", "torus.py")]
    done = sorgui("open", str(torus_report), *[a for t in targets for a in ("-o", str(t))], env=env)
    assert done.returncode == 0 and done.stderr == "", done.stderr
    assert json.loads(targets[0].read_text(encoding="utf-8")) == json.loads(torus_report.read_text(encoding="utf-8"))
    assert targets[1].stat().st_size > 10_000 and (tmp_path / "torus.png").exists()
    assert "check()" in targets[3].read_text(encoding="utf-8")


def test_open_writes_a_cad_file_and_says_what_it_holds(torus_report: Path, tmp_path: Path) -> None:
    pytest.importorskip("OCP")
    step = tmp_path / "torus.step"
    done = sorgui("open", str(torus_report), "-o", str(step), "--units", "cm")
    assert done.returncode == 0 and one_line(done.stderr).startswith(f"sorgui: wrote {step}: an analytic surface")
    text = step.read_text(encoding="ascii")
    assert "TOROIDAL_SURFACE" in text and "SI_UNIT(.CENTI.,.METRE.)" in text


def test_open_refuses_what_it_cannot_do_in_one_line(torus_report: Path, tmp_path: Path) -> None:
    itself = sorgui("open", str(torus_report), "-o", str(torus_report), timeout=60)
    assert itself.returncode == 2 and "refusing to overwrite the input file" in one_line(itself.stderr)
    no_output = sorgui("open", str(torus_report), "--region", "2", timeout=60)
    assert no_output.returncode == 2 and "give -o FILE" in one_line(no_output.stderr)
    for option in (["--cap"], ["--units", "cm"]):  # the window opened, the option ignored
        no_output = sorgui("open", str(torus_report), *option, timeout=60)
        assert no_output.returncode == 2 and f"{option[0]} applies to -o files" in one_line(no_output.stderr)
    uncapped = sorgui("open", str(torus_report), "--cap", "-o", str(tmp_path / "t.stl"), timeout=60)
    assert uncapped.returncode == 2 and "--cap applies to CAD files" in one_line(uncapped.stderr)
    assert not (tmp_path / "t.stl").exists()
    missing = sorgui("open", str(tmp_path / "missing.json"), "-o", str(tmp_path / "x.txt"), timeout=60)
    assert missing.returncode == 2 and "cannot read" in one_line(missing.stderr)
    assert not (tmp_path / "x.txt").exists()


def test_a_lying_report_is_refused_before_anything_is_written(torus_report: Path, tmp_path: Path) -> None:
    """The torus's report with another equation: refused in one line naming the field, status 2,
    no file written (it used to export a STEP torus headed x**3 + y**3 + z**3 - 1 = 0)."""
    data = json.loads(torus_report.read_text(encoding="utf-8"))
    data["input"], data["polynomial"] = "x^3+y^3+z^3-1", "x**3 + y**3 + z**3 - 1"
    lying = tmp_path / "lying.json"
    lying.write_text(json.dumps(data), encoding="utf-8")
    step = tmp_path / "out.step"
    done = sorgui("open", str(lying), "-o", str(step), "-o", str(tmp_path / "out.stl"), timeout=120)
    assert done.returncode == 2 and "refused: its degree is 4" in one_line(done.stderr)
    assert not step.exists() and not (tmp_path / "out.stl").exists()
    window = sorgui("open", str(lying), timeout=120)
    assert window.returncode == 2 and "refused" in one_line(window.stderr)


def test_a_result_of_a_batch_opens_by_its_input_line(tmp_path: Path) -> None:
    """A results file of ``--each-line`` holds one object per input line: ``--line N`` opens the
    one of line N (its bookkeeping keys set aside), a file of one such object opens as it is,
    and the whole file, an error line or a missing line are refused in one line each."""
    lines = tmp_path / "lines.txt"
    lines.write_text("x^2 + y^2 - z\nx^2 + y^2 + z^2 - 1\nx y z + (\n", encoding="utf-8")
    results = tmp_path / "results.jsonl"
    batch = sorgui("analyze", "--each-line", "--recognition-only", "-f", str(lines), "-o", str(results))
    assert batch.returncode == 2, batch.stderr  # line 3 is not a polynomial
    sphere = tmp_path / "sphere.txt"
    done = sorgui("open", str(results), "--line", "2", "-o", str(sphere))
    assert done.returncode == 0, done.stderr
    assert sphere.read_text(encoding="utf-8").startswith("f = x**2 + y**2 + z**2 - 1\n")
    single = tmp_path / "one.json"
    single.write_text(results.read_text(encoding="utf-8").splitlines()[0] + "\n", encoding="utf-8")
    assert sorgui("open", str(single), "-o", str(tmp_path / "one.md")).returncode == 0
    for args, words in (
        ([], "holds the results of a batch (JSON Lines, one object per line of its input): give --line N"),
        (["--line", "3"], "line 3 of"),
        (["--line", "7"], "holds no result of input line 7"),
    ):
        refused = sorgui("open", str(results), *args, "-o", str(tmp_path / "x.txt"))
        assert refused.returncode == 2 and words in one_line(refused.stderr)
    assert not (tmp_path / "x.txt").exists()
    report = tmp_path / "sphere.json"
    assert sorgui("open", str(results), "--line", "2", "-o", str(report)).returncode == 0
    refused = sorgui("open", str(report), "--line", "1", "-o", str(tmp_path / "x.txt"))
    assert refused.returncode == 2 and "is not a results file of --each-line" in one_line(refused.stderr)
