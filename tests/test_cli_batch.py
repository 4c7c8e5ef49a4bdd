"""``sorgui analyze --each-line``: JSON Lines, worker processes, bad lines, a progress bar."""

from __future__ import annotations

import json
import os
import pty
import subprocess
import sys
from pathlib import Path

from sorgui.batch import equations

SORGUI = [sys.executable, "-m", "sorgui.cli", "analyze"]
LINES = """# a small batch
x^2 + y^2 - z

x^2 + sin(y)          # not a polynomial: an error object, and the batch goes on
-x^2-y^2+z^2-1        # a hyperboloid, starting with a minus sign
x^2 + 2y^2 + 3z^2 - 1
"""


def test_lines_comments_and_blank_lines() -> None:
    assert equations(LINES) == [
        (2, "x^2 + y^2 - z"),
        (4, "x^2 + sin(y)"),
        (5, "-x^2-y^2+z^2-1"),
        (6, "x^2 + 2y^2 + 3z^2 - 1"),
    ]


def run_batch(tmp_path: Path, *args: str) -> subprocess.CompletedProcess[str]:
    path = tmp_path / "lines.txt"
    path.write_text(LINES, encoding="utf-8")
    return subprocess.run([*SORGUI, "--each-line", *args, "-f", str(path)], capture_output=True, text=True, timeout=300)


def test_json_lines_in_input_order_with_an_error_object_for_the_bad_line(tmp_path: Path) -> None:
    for jobs in ("1", "2"):
        out = run_batch(tmp_path, "--jobs", jobs)
        assert out.returncode == 2, out.stderr  # one line was not a polynomial
        rows = [json.loads(line) for line in out.stdout.splitlines()]
        assert [row["line"] for row in rows] == [2, 4, 5, 6]
        assert [row.get("is_sor") for row in rows] == [True, None, True, False]
        error = rows[1]["error"]
        assert "sin" in error["message"] and error["position"] == 6 and rows[1]["input"] == "x^2 + sin(y)"
        assert rows[0]["rationality"] is not None  # the whole analysis, Singular included
        assert out.stderr == ""  # stderr is not a terminal: no progress bar


def test_a_progress_bar_on_a_terminal(tmp_path: Path) -> None:
    path = tmp_path / "lines.txt"
    path.write_text("x^2+y^2-z\nx^2+y^2+z^2-1\n", encoding="utf-8")
    master, slave = pty.openpty()
    try:
        proc = subprocess.Popen(
            [*SORGUI, "--each-line", "--recognition-only", "-f", str(path)],
            stdout=subprocess.PIPE,
            stderr=slave,
            text=True,
        )
        os.close(slave)
        out, _ = proc.communicate(timeout=120)
        shown = b""
        while True:
            try:
                chunk = os.read(master, 4096)
            except OSError:  # the terminal's other side is closed: all read
                break
            if not chunk:
                break
            shown += chunk
    finally:
        os.close(master)
    assert proc.returncode == 0 and len(out.splitlines()) == 2
    assert b"] 1/2" in shown and b"] 2/2" in shown and b"#" in shown


def test_each_line_needs_a_file_or_standard_input() -> None:
    out = subprocess.run([*SORGUI, "--each-line"], capture_output=True, text=True, timeout=60)
    assert out.returncode == 2 and out.stderr.count("\n") == 1 and "--each-line reads" in out.stderr
    piped = subprocess.run(
        [*SORGUI, "--each-line", "--recognition-only", "-"],
        input="x^2+y^2-z\n",
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert piped.returncode == 0 and json.loads(piped.stdout)["symmetry"] == "revolution"


def test_the_warm_up_is_a_surface_of_revolution_and_loads_no_sympy() -> None:
    """The pool's warm-up equation is what it says (a torus about the axis along (1, 2, 2)), and
    warming up keeps a recognition-only batch free of sympy."""
    code = (
        "import sys\n"
        "from sorgui.batch import WARM_UP, warm_up\n"
        "from sorgui.engine import analyze\n"
        "warm_up()\n"
        "a = analyze(WARM_UP, recognition_only=True)\n"
        "print(a.recognition.symmetry, a.recognition.axis.direction, 'sympy' in sys.modules)\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=True)
    assert done.stdout.split() == ["revolution", "('1',", "'2',", "'2')", "False"]
