"""``sorgui analyze --each-line``: JSON Lines in input order, one object per line whatever the
line holds, worker processes, a results file that survives ``kill -9``, progress and summary."""

from __future__ import annotations

import io
import json
import os
import pty
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest

from sorgui.batch import LineReader, equations, line_hash

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


def test_comments_of_singular_matlab_and_latex_are_comments() -> None:
    """A library exported from Singular (``//``), MATLAB or LaTeX (``%``), its statements read
    as their equations."""
    text = "// Singular\npoly f = x2+y2-z; // a paraboloid\n% MATLAB\nx^2 + y^2 - 1 % a cylinder\n"
    assert equations(text) == [(2, "poly f = x2+y2-z;"), (4, "x^2 + y^2 - 1")]


def test_a_line_is_refused_whole_when_it_is_too_long_or_not_text() -> None:
    """Each line gives one object; a line over the limit is refused however it ends, a line that
    is not UTF-8 too, and a NUL byte stops the reading."""
    data = b"x^2+y^2-1" + b" " * 30 + b"+x^3\n" + b" " * 100 + b"x\n\xff\xfe z\r\nx + y\r\nz^2\x00x\nx\n"
    reader = LineReader(io.BytesIO(data), 40)
    lines = list(reader)
    assert [line.number for line in lines] == [1, 2, 3, 4, 5]
    assert "too long (more than 40 characters)" in str(lines[0].refusal)
    assert "too long" in str(lines[1].refusal) and lines[1].equation.endswith("…")
    assert "not UTF-8" in str(lines[2].refusal)
    assert lines[3].refusal is None and lines[3].equation == "x + y" and lines[3].digest == line_hash(b"x + y")
    assert "NUL" in str(lines[4].refusal) and reader.stopped == "line 5 holds a NUL byte: this is not a text file"


def without_timings(data: Any) -> Any:
    """An output object without the seconds it took (which differ from run to run)."""
    if isinstance(data, dict):
        return {k: without_timings(v) for k, v in data.items() if k != "timings"}
    if isinstance(data, list):
        return [without_timings(v) for v in data]
    return data


def rows_of(text: str) -> list[Any]:
    return [without_timings(json.loads(line)) for line in text.splitlines()]


def run_batch(tmp_path: Path, *args: str, lines: str = LINES) -> subprocess.CompletedProcess[str]:
    path = tmp_path / "lines.txt"
    path.write_text(lines, encoding="utf-8")
    return subprocess.run([*SORGUI, "--each-line", *args, "-f", str(path)], capture_output=True, text=True, timeout=300)


def test_json_lines_in_input_order_with_an_error_object_for_the_bad_line(tmp_path: Path) -> None:
    outputs = []
    for jobs in ("1", "2"):
        out = run_batch(tmp_path, "--jobs", jobs)
        assert out.returncode == 2, out.stderr  # one line was not a polynomial
        rows = [json.loads(line) for line in out.stdout.splitlines()]
        assert [row["line"] for row in rows] == [2, 4, 5, 6]
        assert [row.get("is_sor") for row in rows] == [True, None, True, False]
        error = rows[1]["error"]
        assert "sin" in error["message"] and error["position"] == 6 and rows[1]["input"] == "x^2 + sin(y)"
        assert error["exit_status"] == 2
        assert rows[1]["line_hash"] == line_hash(LINES.splitlines()[3].encode())
        assert rows[0]["rationality"] is not None  # the whole analysis, Singular included
        assert out.stderr == ""  # stderr is not a terminal: no progress, no summary
        outputs.append(rows_of(out.stdout))
    assert outputs[0] == outputs[1]


def test_a_line_s_object_is_the_report_of_json_with_its_line_in_front(tmp_path: Path) -> None:
    """Every field of ``sorgui analyze --json`` (its ``sorgui_version`` first) after ``line``,
    ``line_hash`` and ``options``; a results file of an older sorgui, whose lines have no
    ``sorgui_version`` and no ``options``, is still resumed."""
    from sorgui import __version__

    out = run_batch(tmp_path, "--recognition-only")
    rows = [json.loads(line) for line in out.stdout.splitlines()]
    single = subprocess.run(
        [*SORGUI, "--json", "--recognition-only", "x^2 + y^2 - z"], capture_output=True, text=True, timeout=120
    )
    report = json.loads(single.stdout)
    assert list(rows[0]) == ["line", "line_hash", "options", *report] and list(report)[0] == "sorgui_version"
    assert rows[0]["options"] == {"method": "symmetry", "recognition_only": True, "tolerance": None, "timeout": 120.0}
    bookkeeping = ("line", "line_hash", "options")
    assert without_timings({k: v for k, v in rows[0].items() if k not in bookkeeping}) == without_timings(report)
    assert [row.get("sorgui_version") for row in rows] == [__version__, None, __version__, __version__]

    results = tmp_path / "results.jsonl"
    older = [json.dumps({k: v for k, v in row.items() if k not in ("sorgui_version", "options")}) for row in rows[:2]]
    results.write_text("\n".join(older) + "\n", encoding="utf-8")
    resumed = run_batch(tmp_path, "--recognition-only", "-o", str(results), "--resume")
    # its kept line 4 was not a polynomial (an error with a position): the exit status says so
    assert (
        resumed.returncode == out.returncode == 2 and resumed.stdout == "" and "(2 kept from before)" in resumed.stderr
    )
    lines = [json.loads(line) for line in results.read_text(encoding="utf-8").splitlines()]
    assert [row["line"] for row in lines] == [2, 4, 5, 6]
    assert "sorgui_version" not in lines[0] and lines[2]["sorgui_version"] == __version__


def test_a_long_line_is_refused_whole_and_the_batch_goes_on(tmp_path: Path) -> None:
    """Issue 32: an equation padded with a million spaces is not read as its first megabyte, a line
    of 3 MB of spaces and then an equation gets its object, and memory stays bounded."""
    path = tmp_path / "long.txt"
    path.write_text(
        "x^2+y^2+z^2-1"
        + " " * 1_000_000
        + "+x^3*y\n"
        + " " * 3_000_000
        + "x^2+y^2-z\n"
        + " " * 60_000_000
        + "\nx^2+y^2-z\n",
        encoding="utf-8",
    )
    measured = (  # the largest memory of sorgui and its worker, in a process of its own
        "import resource, subprocess, sys\n"
        "done = subprocess.run(sys.argv[1:], capture_output=True, text=True)\n"
        "sys.stdout.write(done.stdout)\n"
        "sys.exit(0 if resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss < 150_000 else 99)\n"
    )
    command = [sys.executable, "-c", measured, *SORGUI, "--each-line", "--recognition-only", "-f", str(path)]
    out = subprocess.run(command, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, "sorgui held more than 150 MB"  # the 60 MB line was never held whole
    rows = [json.loads(line) for line in out.stdout.splitlines()]
    assert [row["line"] for row in rows] == [1, 2, 3, 4]
    for row in rows[:3]:
        assert row["error"]["message"] == "the line is too long (more than 1,000,000 characters)"
        assert len(row["input"]) <= 61
    assert rows[3]["is_sor"] is True


def test_dev_zero_ends_with_a_clear_error() -> None:
    out = subprocess.run(
        [*SORGUI, "--each-line", "--recognition-only", "-f", "/dev/zero"], capture_output=True, text=True, timeout=120
    )
    assert out.returncode == 2
    (row,) = [json.loads(line) for line in out.stdout.splitlines()]
    assert row["line"] == 1 and "NUL byte" in row["error"]["message"]
    assert "sorgui: stopped reading /dev/zero: line 1 holds a NUL byte: this is not a text file" in out.stderr


def test_a_progress_line_and_a_summary_on_a_terminal(tmp_path: Path) -> None:
    path = tmp_path / "lines.txt"
    path.write_text("x^2+y^2-z\n# comment\nx^2+y^2+z^2-1\n", encoding="utf-8")
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
    assert b"1/3 lines" in shown and b"lines/s" in shown
    assert b"sorgui: 2 lines: 2 surfaces of revolution, 0 not, 0 errors, 0 unfinished" in shown


def shown_on_a_terminal(raw: bytes) -> list[str]:
    """The lines a terminal shows for ``raw``: each carriage return writes over its line."""
    lines = []
    for line in raw.decode().split("\n"):
        shown = ""
        for part in line.split("\r"):
            shown = part + shown[len(part) :]
        lines.append(shown.rstrip())
    return [line for line in lines if line]


def test_the_output_lines_on_the_terminal_of_the_progress_line_are_json_lines(tmp_path: Path) -> None:
    """The lines and the progress line on one terminal: the progress line was left in front of
    the next output line, which a user copying the lines got as bad JSON."""
    path = tmp_path / "lines.txt"
    path.write_text("x^2+y^2-z\nx^2+y^2+z^2-1\nx^3+y*z\nx^2-y^2+z^2-1\n", encoding="utf-8")
    master, slave = pty.openpty()
    try:
        proc = subprocess.Popen(
            [*SORGUI, "--each-line", "--recognition-only", "-f", str(path)], stdout=slave, stderr=slave
        )
        os.close(slave)
        proc.wait(timeout=120)
        raw = b""
        while True:
            try:
                chunk = os.read(master, 4096)
            except OSError:
                break
            if not chunk:
                break
            raw += chunk
    finally:
        os.close(master)
    assert proc.returncode == 0 and b"lines/s" in raw
    shown = shown_on_a_terminal(raw)
    assert [json.loads(line)["line"] for line in shown[:-1]] == [1, 2, 3, 4]
    assert shown[-1].startswith("sorgui: 4 lines: 3 surfaces of revolution, 1 not")


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


# --- a results file that survives a crash ----------------------------------------------------


def many_lines(count: int) -> str:
    """Small equations, surfaces of revolution and not, a bad line now and then."""
    out = []
    for i in range(1, count + 1):
        if i % 17 == 0:
            out.append(f"x^2 + cos(y) + {i}")
        elif i % 3 == 0:
            out.append(f"x^2 + {i}*y^2 + z^2 - {i}")
        else:
            out.append(f"(x - {i})^2 + (y + 1)^2 - {i}*z")
        if i % 50 == 0:
            out.append("# a comment")
    return "\n".join(out) + "\n"


def test_a_batch_killed_and_resumed_writes_the_file_of_one_uninterrupted_run(tmp_path: Path) -> None:
    lines = tmp_path / "lines.txt"
    lines.write_text(many_lines(400), encoding="utf-8")
    batch = [*SORGUI, "--each-line", "--recognition-only", "--jobs", "2", "-f", str(lines)]
    whole = subprocess.run(batch, capture_output=True, text=True, timeout=300)
    assert whole.returncode == 2 and len(whole.stdout.splitlines()) == 400

    results = tmp_path / "results.jsonl"
    proc = subprocess.Popen([*batch, "-o", str(results)], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 120
    while (not results.exists() or results.read_bytes().count(b"\n") < 40) and time.monotonic() < deadline:
        time.sleep(0.005)
    proc.send_signal(signal.SIGKILL)
    proc.communicate(timeout=60)
    data = results.read_bytes()
    done = data.count(b"\n")
    assert 40 <= done < 400
    results.write_bytes(data[: len(data) - 25])  # the last line cut short, as a power cut leaves it

    refused = subprocess.run([*batch, "-o", str(results)], capture_output=True, text=True, timeout=60)
    assert refused.returncode == 2 and "already exists and is not empty: add --resume" in refused.stderr
    assert results.read_bytes() == data[: len(data) - 25]  # untouched

    resumed = subprocess.run([*batch, "-o", str(results), "--resume"], capture_output=True, text=True, timeout=300)
    assert resumed.stdout == "" and f"({done - 1:,} kept from before)" in resumed.stderr
    assert rows_of(results.read_text(encoding="utf-8")) == rows_of(whole.stdout)
    assert resumed.stderr.startswith("sorgui: 400 lines (") and "23 errors" in resumed.stderr

    again = subprocess.run([*batch, "-o", str(results), "--resume"], capture_output=True, text=True, timeout=120)
    assert again.returncode == whole.returncode and "(400 kept from before)" in again.stderr  # the kept errors count
    assert rows_of(results.read_text(encoding="utf-8")) == rows_of(whole.stdout)


@pytest.mark.parametrize(("signum", "status"), [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_an_interrupted_batch_says_what_its_results_file_holds(tmp_path: Path, signum: int, status: int) -> None:
    """Ctrl+C during a batch into a results file said only "interrupted" (a signal, nothing):
    how many lines the file holds and that ``--resume`` goes on are said."""
    lines = tmp_path / "lines.txt"
    lines.write_text(many_lines(2000), encoding="utf-8")
    results = tmp_path / "results.jsonl"
    batch = [*SORGUI, "--each-line", "--recognition-only", "-f", str(lines), "-o", str(results)]
    proc = subprocess.Popen(batch, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while (not results.exists() or results.read_bytes().count(b"\n") < 20) and time.monotonic() < deadline:
        time.sleep(0.005)
    proc.send_signal(signum)
    _, err = proc.communicate(timeout=60)
    held = results.read_bytes().count(b"\n")
    assert proc.returncode == status and 20 <= held < 2000, err
    assert f"sorgui: {results} holds {held:,} lines; the same command with --resume goes on from there" in err


def test_a_kept_failure_gives_the_exit_status_of_the_run_that_wrote_it(tmp_path: Path) -> None:
    """A line whose analysis failed (exit status 1) in the first run, kept by ``--resume``: the
    resumed run, which analyses nothing that fails, still exits with 1."""
    good = "x^2 + y^2 - z\nx^2 + y^2 + z^2 - 1\n"
    first = run_batch(tmp_path, "--recognition-only", lines=good)
    rows = first.stdout.splitlines()
    failed = json.dumps(
        {**json.loads(rows[0]), "error": {"message": "the analysis failed", "position": None, "exit_status": 1}}
    )
    results = tmp_path / "results.jsonl"
    results.write_text(failed + "\n", encoding="utf-8")
    resumed = run_batch(tmp_path, "--recognition-only", "-o", str(results), "--resume", lines=good)
    assert first.returncode == 0 and resumed.returncode == 1, resumed.stderr
    assert "(1 kept from before)" in resumed.stderr and "1 error" in resumed.stderr


def test_resume_refuses_a_file_that_is_not_this_inputs(tmp_path: Path) -> None:
    lines = tmp_path / "lines.txt"
    lines.write_text(many_lines(5), encoding="utf-8")
    results = tmp_path / "results.jsonl"
    batch = [*SORGUI, "--each-line", "--recognition-only", "-f", str(lines), "-o", str(results)]
    first = subprocess.run(batch, capture_output=True, text=True, timeout=120)
    assert first.returncode == 0 and first.stdout == "" and results.read_text().count("\n") == 5
    before = results.read_bytes()
    lines.write_text(many_lines(5).replace("- 3", "- 4"), encoding="utf-8")  # line 3 edited
    edited = subprocess.run([*batch, "--resume"], capture_output=True, text=True, timeout=120)
    assert edited.returncode == 2 and "its line 3 is not the input's line 3 as it is now" in edited.stderr
    lines.write_text("x^2+y^2-z\n", encoding="utf-8")  # shorter than the file
    shorter = subprocess.run([*batch, "--resume"], capture_output=True, text=True, timeout=120)
    assert shorter.returncode == 2 and "cannot resume" in shorter.stderr
    assert results.read_bytes() == before
    assert edited.stderr.count("\n") == shorter.stderr.count("\n") == 1
    lines.write_text(many_lines(5), encoding="utf-8")  # the input of ``before`` again
    # whole lines, and a last line without a newline that is no start of sorgui's (it was taken
    # for a line cut short by a crash and the notes replaced)
    others = (b"my precious notes\n", b'{"a": 1}\n', before + b"a note\n" + before, b'{"my": "notes"}')
    others += (before + b"note",)
    for other in others:
        results.write_bytes(other)  # one whole line that is not sorgui's was taken for a cut-short one
        kept = subprocess.run([*batch, "--resume"], capture_output=True, text=True, timeout=120)
        assert kept.returncode == 2 and "is not a line of sorgui's output in order" in kept.stderr, kept.stderr
        assert results.read_bytes() == other
    for debris in (b"\0" * 40, b'{"li', before.splitlines(keepends=True)[0][:30] + b"\0" * 8):
        results.write_bytes(before + debris)  # zeros of a power cut, or a line of ours cut short: redone
        again = subprocess.run([*batch, "--resume"], capture_output=True, text=True, timeout=120)
        assert again.returncode == 0 and results.read_bytes() == before

    plain = tmp_path / "lines"
    plain.write_text(many_lines(5), encoding="utf-8")
    unusable = [
        ([*SORGUI, "--each-line", "-f", str(lines), "--resume"], "--resume continues a results file"),
        ([*batch, "-o", str(tmp_path / "two.jsonl")], "give -o once"),
        ([*SORGUI, "--each-line", "-f", str(plain), "-o", str(plain)], "refusing to overwrite the input file"),
        ([*SORGUI, "--each-line", "-f", str(lines), "-o", str(lines)], "not a .txt file"),
        ([*SORGUI, "--each-line", "-f", str(lines), "-o", str(tmp_path)], "it is a folder"),
        ([*SORGUI, "--each-line", "-f", str(lines), "--jobs", "2", "--scheduler", "tcp://x:1"], "exclude each other"),
    ]
    for command, words in unusable:
        out = subprocess.run(command, capture_output=True, text=True, timeout=60)
        assert out.returncode == 2 and words in out.stderr and out.stderr.count("\n") == 1, (command, out.stderr)


def test_the_summary_counts_rounded_surfaces_that_are_nearly_of_revolution(tmp_path: Path) -> None:
    """A parts library of rounded equations: those within their rounding of a surface of
    revolution are counted apart, not only as "not"."""
    source = tmp_path / "rounded.txt"
    source.write_text("x^2+y^2-1\nx^2+1.0000001*y^2-z\nx^3+y^2*z+1\n", encoding="utf-8")
    done = subprocess.run(
        [*SORGUI, "--each-line", "-f", str(source), "-o", str(tmp_path / "out.jsonl")],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr
    assert "3 lines: 1 surface of revolution, 2 not (1 of them nearly: rounded input within its rounding), " in (
        done.stderr
    )


def test_a_batch_into_a_report_file_name_is_refused(tmp_path: Path) -> None:
    """``.json`` is a report that ``sorgui open`` reads; JSON Lines go to ``.jsonl``."""
    source = tmp_path / "one.txt"
    source.write_text("x^2+y^2-1\n", encoding="utf-8")
    target = tmp_path / "results.json"
    done = subprocess.run(
        [*SORGUI, "--each-line", "-f", str(source), "-o", str(target)], capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 2 and "name the results file results.jsonl" in done.stderr and not target.exists()


def test_a_results_file_is_resumed_only_with_the_options_it_was_written_with(tmp_path: Path) -> None:
    """A batch resumed with other options (``--recognition-only`` added, another ``--timeout``)
    would mix answers of two kinds in one file: it is refused, before anything is changed."""
    results = tmp_path / "results.jsonl"
    good = "x^2 + y^2 - z\nx^2 + y^2 + z^2 - 1\n"
    first = run_batch(tmp_path, "--recognition-only", "-o", str(results), lines=good)
    assert first.returncode == 0, first.stderr
    kept = results.read_bytes()[: results.read_bytes().index(b"\n") + 1]
    results.write_bytes(kept)
    for options in (["--timeout", "60"], []):
        other = run_batch(tmp_path, *options, "-o", str(results), "--resume", lines=good)
        assert other.returncode == 2 and results.read_bytes() == kept, other.stderr
        assert (
            "line 1 was analysed with --method symmetry --recognition-only --timeout 120, this run has" in other.stderr
        )
    same = run_batch(tmp_path, "--recognition-only", "-o", str(results), "--resume", lines=good)
    assert same.returncode == 0 and "(1 kept from before)" in same.stderr


def test_a_line_counts_by_its_verdict_when_only_a_later_stage_is_unfinished() -> None:
    """The summary said '0 not, 4 unfinished' of lines whose answer was a decided no, with only
    the canal stage past the time limit: a line is unfinished when its verdict is."""
    from sorgui.batch.answers import NOT_SURFACE_OF_REVOLUTION, SURFACE_OF_REVOLUTION, UNFINISHED, kind_of

    assert kind_of({"is_sor": False, "symmetry": "none", "unfinished": ["canal"]}) == NOT_SURFACE_OF_REVOLUTION
    assert kind_of({"is_sor": True, "symmetry": "revolution", "unfinished": ["rationality"]}) == SURFACE_OF_REVOLUTION
    assert kind_of({"is_sor": False, "symmetry": "undecided", "unfinished": ["recognition"]}) == UNFINISHED
