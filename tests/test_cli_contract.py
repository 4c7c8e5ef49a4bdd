"""The command line's contract, tried as a user would: real ``sorgui`` processes.

Arguments (an equation may start with ``-``; every error is one line, or an ``error`` object
with ``--json``), bounded input, ``-o`` checked before the analysis, output errors in one line,
the text report's final newline, and the one time limit of the whole analysis.
"""

from __future__ import annotations

import argparse
import json
import multiprocessing
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from sorgui import cli

SORGUI = [sys.executable, "-m", "sorgui.cli"]
DATA = Path(__file__).resolve().parent / "data"


def sorgui(*args: str, timeout: float = 120, **kwargs) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*SORGUI, *args], capture_output=True, text=True, timeout=timeout, **kwargs)


def one_line(stderr: str) -> str:
    """The single line of ``stderr`` (asserting there is exactly one, and no traceback)."""
    assert stderr.count("\n") == 1 and stderr.endswith("\n"), stderr
    assert "Traceback" not in stderr and "usage:" not in stderr
    return stderr.strip()


def test_an_equation_may_start_with_a_minus_sign() -> None:
    out = sorgui("analyze", "--recognition-only", "-x^2-y^2+z^2-1")
    assert out.returncode == 0, out.stderr
    assert "surface of revolution: YES" in out.stdout
    data = json.loads(sorgui("analyze", "--json", "--recognition-only", "-x^2-y^2+z^2-1").stdout)
    assert data["polynomial"] == "-x**2 - y**2 + z**2 - 1" and data["is_sor"] is True


@pytest.mark.parametrize(
    "args, words",
    [
        (["--timeout", "nan", "x^2+y^2-z"], "positive number of seconds"),
        (["--timeout", "0", "x^2+y^2-z"], "positive number of seconds"),
        (["--timeout", "-5", "x^2+y^2-z"], "positive number of seconds"),
        (["--timeout", "inf", "x^2+y^2-z"], "positive number of seconds"),
        (["--timeout", "soon", "x^2+y^2-z"], "not a number of seconds"),
        (["--method", "guess", "x^2+y^2-z"], "invalid choice"),
        (["--frobnicate", "x^2+y^2-z"], "unrecognized arguments"),
        (["x^2+y^2-z", "x^2"], "unrecognized arguments"),
        (["-f", "missing-file.txt"], "cannot read missing-file.txt"),
        (["--jobs", "0", "-"], "must be at least 1"),
        (["--region", "1:0,0:1,0:1", "x^2+y^2-z"], "from low to high"),
        (["--region", "0,0,0,-1", "x^2+y^2-z"], "radius must be positive"),
        (["--region", "1,2", "x^2+y^2-z"], "not a region"),
        (["--region", "1 2", "x^2+y^2-z"], "not a region"),  # it was read as 12
        (["--region", "nan", "x^2+y^2-z"], "must be finite"),
        (["--region", "-2", "x^2+y^2-z"], "radius must be positive"),
        (["--region", "0:0,0:1,0:1", "x^2+y^2-z"], "from low to high"),
        (["--region", "inf", "x^2+y^2-z"], "must be finite"),
        (["--cap", "x^2+y^2-z"], "--cap applies to -o files: give -o FILE"),
        (["--units", "cm", "x^2+y^2-z"], "--units applies to -o files"),
        # --cap left a mesh or a patch uncapped without a word
        (["--cap", "x^2+y^2-z", "-o", "p.stl"], "--cap applies to CAD files of the surface"),
        (["--cap", "x^2+y^2-z", "-o", "p.patch.step"], "--cap applies to CAD files of the surface"),
        (["--cap", "--format", "patch.step", "x^2+y^2-z", "-o", "p.out"], "--cap applies to CAD files"),
        (["--each-line", "--fit-tolerance", "1e-6", "-"], "not to --each-line"),
        (["--each-line", "-", "-o", "results.txt"], "not a .txt file: name the results file results.jsonl"),
        (["--each-line", "-", "-o", "results.step"], "not a .step file"),
    ],
)
def test_every_argument_error_is_one_line_and_an_error_object(args: list[str], words: str) -> None:
    plain = sorgui("analyze", *args)
    assert plain.returncode == 2 and plain.stdout == ""
    assert words in one_line(plain.stderr)
    as_json = sorgui("analyze", "--json", *args)
    assert as_json.returncode == 2
    assert words in json.loads(as_json.stdout)["error"]["message"]
    one_line(as_json.stderr)


def test_the_window_command_line_errors_are_one_line_too() -> None:
    out = sorgui("--frobnicate")
    assert out.returncode == 2 and "unrecognized arguments" in one_line(out.stderr)


def test_input_is_read_only_up_to_the_limit() -> None:
    start = time.monotonic()
    endless = subprocess.Popen(["yes", "x^2 + y^2 - z"], stdout=subprocess.PIPE)
    try:
        out = sorgui("analyze", "-", stdin=endless.stdout, timeout=60)
    finally:
        endless.kill()
        endless.wait()
        endless.stdout.close()
    assert out.returncode == 2 and "standard input is too long (more than 1,000,000 characters)" in one_line(out.stderr)
    assert time.monotonic() - start < 40  # gigabytes would take minutes


def test_a_file_with_a_nul_byte_is_said_not_to_be_text() -> None:
    """``-f /dev/zero`` was "too long (more than 1,000,000 characters)", where ``--each-line``
    says what it is."""
    out = sorgui("analyze", "-f", "/dev/zero", timeout=60)
    assert out.returncode == 2
    assert one_line(out.stderr) == "sorgui: cannot read /dev/zero: byte 1 is a NUL byte: this is not a text file"
    with open("/dev/zero", "rb") as zeros:
        out = sorgui("analyze", "-", stdin=zeros, timeout=60)
    assert out.returncode == 2 and "standard input: byte 1 is a NUL byte" in one_line(out.stderr)


def test_the_input_limit_is_the_parsers() -> None:
    from sorgui.engine.parsing import MAX_LENGTH
    from sorgui.export.formats import FORMATS

    assert cli.MAX_INPUT == MAX_LENGTH
    assert set(cli.EXPORT_SUFFIXES) == set(FORMATS)


def test_numbers_of_more_than_4300_digits_are_analysed() -> None:
    for text, symmetry in [
        ("10^4300*x+y^2-z", "extrusion"),  # the example: a parabolic cylinder
        ("1" + "0" * 4400 + "*(x^2+y^2)-z", "revolution"),
    ]:
        out = sorgui("analyze", "--json", "--recognition-only", text)
        assert out.returncode == 0, out.stderr
        data = json.loads(out.stdout)
        assert data["symmetry"] == symmetry and len(data["polynomial"]) > 4300


def test_bom_function_name_and_latex_are_accepted(tmp_path: Path) -> None:
    path = tmp_path / "eq.txt"
    path.write_bytes("\ufeffx^2 + y^2 - z\n".encode())
    assert json.loads(sorgui("analyze", "--json", "--recognition-only", "-f", str(path)).stdout)["is_sor"]
    for text in ("f(x,y,z) = x^2 + y^2 - z", r"\left( x \right)^{2} + y^{2} - \frac{1}{2} \cdot z"):
        out = sorgui("analyze", "--json", "--recognition-only", text)
        assert out.returncode == 0, out.stderr
        assert json.loads(out.stdout)["symmetry"] == "revolution"


def test_the_text_report_ends_with_one_newline() -> None:
    out = sorgui("analyze", "--recognition-only", "x^2+y^2-z")
    assert out.stdout.endswith("\n") and not out.stdout.endswith("\n\n")


def test_outputs_are_checked_before_the_analysis(tmp_path: Path) -> None:
    slow = str(DATA / "slow-singular.txt")
    for target, words in [
        (tmp_path / "missing" / "r.json", "does not exist"),
        (tmp_path / "r.doc", "unknown export format"),
        (tmp_path, "unknown export format"),
    ]:
        start = time.monotonic()
        out = sorgui("analyze", "-o", str(target), "-f", slow, timeout=60)
        assert out.returncode == 2 and str(target) in one_line(out.stderr) and words in out.stderr
        assert out.stdout == "" and time.monotonic() - start < 30  # no minute-long analysis first
    folder = tmp_path / "locked"
    folder.mkdir()
    folder.chmod(0o500)
    if not os.access(folder, os.W_OK):  # root may write anywhere
        out = sorgui("analyze", "-o", str(folder / "r.json"), "x^2+y^2-z")
        assert out.returncode == 2 and "permission denied" in one_line(out.stderr)


def test_a_binary_file_is_said_not_to_be_text(tmp_path: Path) -> None:
    path = tmp_path / "program"
    path.write_bytes(b"\x7fELF\x02\x01\x01\x00" + b"\x00" * 16 + b"\xd0a")
    out = sorgui("analyze", "-f", str(path))
    assert out.returncode == 2, out.stderr
    said = one_line(out.stderr)
    assert said == f"sorgui: cannot read {path}: it is not UTF-8 text (byte 25 is 0xd0): an equation is text"


def test_the_input_file_is_never_overwritten(tmp_path: Path) -> None:
    path = tmp_path / "eq.txt"
    path.write_text("x^2+y^2-z\n", encoding="utf-8")
    out = sorgui("analyze", "-f", str(path), "-o", str(tmp_path / "." / "eq.txt"))
    assert out.returncode == 2 and "refusing to overwrite the input file" in one_line(out.stderr)
    assert path.read_text(encoding="utf-8") == "x^2+y^2-z\n"


def test_a_closed_pipe_and_a_full_disk_give_one_line() -> None:
    proc = subprocess.Popen(
        [*SORGUI, "analyze", "--json", "--recognition-only", "x^2+y^2-z"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    proc.stdout.close()  # like `| head` having exited
    err = proc.stderr.read()
    proc.stderr.close()
    assert proc.wait(timeout=120) == 1
    assert "cannot write the output" in one_line(err)
    with open("/dev/full", "w") as full:
        out = subprocess.run(
            [*SORGUI, "analyze", "--recognition-only", "x^2+y^2-z"],
            stdout=full,
            stderr=subprocess.PIPE,
            text=True,
            timeout=120,
        )
    assert out.returncode == 1 and "No space left on device" in one_line(out.stderr)


def test_write_errors_name_the_file(tmp_path: Path) -> None:
    target = tmp_path / "r.json"
    target.mkdir()  # a folder named like the file: refused before the analysis, with its name
    out = sorgui("analyze", "-o", str(target), "x^2+y^2-z")
    assert out.returncode == 2 and f"cannot write {target}" in one_line(out.stderr)


def test_the_time_limit_bounds_the_whole_analysis_and_keeps_what_is_done() -> None:
    start = time.monotonic()
    out = sorgui("analyze", "--json", "--timeout", "4", "-f", str(DATA / "slow-singular.txt"))
    elapsed = time.monotonic() - start
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert data["is_sor"] is True and data["axis"] is not None  # recognition: done and kept
    assert data["unfinished"][0] == "rationality"
    assert data["rationality"]["status"].startswith("undecided")
    assert elapsed < 4 + 15  # the limit plus starting Python and importing, on a busy machine
    text = sorgui("analyze", "--timeout", "4", "-f", str(DATA / "slow-singular.txt")).stdout
    assert "not finished within the time limit (undecided): rationality" in text


def test_the_command_line_loads_the_engine_only_to_analyse() -> None:
    code = (
        "import sys; from sorgui.cli import main; status = main(['analyze', '--timeout', '0']); "
        "print(status, sorted({m.split('.')[0] for m in sys.modules} & {'sympy', 'flint', 'numpy'}))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert out.stdout.strip() == "2 []", out.stdout + out.stderr


def test_a_failed_write_names_the_file(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """An OSError without a file name (a full disk in the middle of an atomic write) still names
    the target; it used to say "cannot write None"."""
    import errno

    import sorgui.export.files as files
    from sorgui.engine import analyze
    from sorgui.session import export_process

    def full_disk(*_args, **_kwargs):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    import sorgui.export.atomic as atomic

    monkeypatch.setattr(files, "export_analysis", full_disk)
    # the export child must be forked for the patch to reach it (a test process with threads spawns)
    monkeypatch.setattr(export_process, "quick_context", lambda: multiprocessing.get_context("fork"))
    target = tmp_path / "r.tex"
    with pytest.raises(cli._OutputError, match=f"cannot write {target}: No space left on device"):
        cli.write_outputs(analyze("x^2+y^2-z", recognition_only=True), [target])
    # a JSON or text report is written by this process itself
    monkeypatch.setattr(atomic, "atomic_write_text", full_disk)
    target = tmp_path / "r.json"
    with pytest.raises(cli._OutputError, match=f"cannot write {target}: No space left on device"):
        cli.write_outputs(analyze("x^2+y^2-z", recognition_only=True), [target])


@pytest.mark.parametrize("ground_types", ["python", "gmpy"])
def test_a_users_sympy_ground_types_do_not_break_the_engine(ground_types: str) -> None:
    """The engine hands flint's rationals to sympy's domains: sorgui sets sympy's ground types."""
    env = {**os.environ, "SYMPY_GROUND_TYPES": ground_types}
    out = sorgui("analyze", "--json", "x^2 + y^2 - sqrt(2) z", env=env)
    assert out.returncode == 0, out.stderr
    assert json.loads(out.stdout)["is_sor"]


def test_a_region_is_a_radius_a_ball_or_a_box_and_may_start_with_a_minus_sign() -> None:
    assert cli.region_value("2.5") == cli.UserRegion(radius=2.5)
    assert cli.region_value("1, 2, 3, 1.5e-3") == cli.UserRegion(radius=1.5e-3, center=(1.0, 2.0, 3.0))
    box = cli.UserRegion(bounds=(-1.0, 1.0, -2.0, 2.0, 0.0, 3.0))
    assert cli.region_value("-1:1,-2:2,0:3") == box
    assert cli.region_value(" -1 : 1, -2:2 ,0:3 ") == box
    args = cli.parse_arguments(cli.analyze_parser(), ["--region", "-1:1,-2:2,0:3", "-x^2-y^2+z"])
    assert args.region == box and args.expression == "-x^2-y^2+z"


def test_a_regions_numbers_may_be_fractions_as_an_equations_are() -> None:
    """``--region=1/3,-2/7,5,1/3`` was "not a region", though the equation it frames is written
    with fractions."""
    assert cli.region_value("1/3,-2/7,5,1/3") == cli.UserRegion(radius=1 / 3, center=(1 / 3, -2 / 7, 5.0))
    assert cli.region_value("-1/2:1/2, 0:1, -3:3") == cli.UserRegion(bounds=(-0.5, 0.5, 0.0, 1.0, -3.0, 3.0))
    for bad in ("1/0", "1/3/4", "1 /3"):
        with pytest.raises(argparse.ArgumentTypeError, match="not a region"):
            cli.region_value(bad)


def test_a_box_cuts_the_mesh_it_writes(tmp_path: Path) -> None:
    import numpy as np
    import pyvista

    out = sorgui("analyze", "x^2+y^2-z", "--region", "-1:0.5,-1:1,0:0.8", "-o", str(tmp_path / "p.stl"))
    assert out.returncode == 0, out.stderr
    low, high = np.array([-1, -1, 0]), np.array([0.5, 1, 0.8])
    points = pyvista.read(tmp_path / "p.stl").points
    assert len(points) > 100 and np.all(points >= low - 1e-9) and np.all(points <= high + 1e-9)
    assert points[:, 0].max() > 0.45 and points[:, 2].max() > 0.75, "the mesh reaches the box's sides"


def test_a_file_given_as_the_expression_says_how_to_read_it(tmp_path: Path) -> None:
    """``sorgui analyze part.txt`` (the file's name where the equation goes): the parse error,
    and how to read the file, in one line."""
    part = tmp_path / "part.txt"
    part.write_text("x^2+y^2-z\n", encoding="utf-8")
    done = sorgui("analyze", str(part))
    [line] = done.stderr.strip().splitlines()
    assert done.returncode == 2 and line.endswith(f"; {part} is a file: give -f {part} to read the equation in it")
    assert sorgui("analyze", "-f", str(part)).returncode == 0


def test_options_and_words_that_would_be_ignored_are_refused_in_one_line() -> None:
    """Batch options without ``--each-line``, and a word that is neither a command nor a file
    (not "the window needs a display"), are usage errors; no equation at all analyses the
    paper's Example 1 and says so."""
    for option in (["--jobs", "2"], ["--resume"], ["--scheduler", "tcp://127.0.0.1:1"]):
        done = sorgui("analyze", *option, "x + y")
        assert done.returncode == 2 and "applies to --each-line only" in one_line(done.stderr), done.stderr
    done = sorgui("bogus")
    assert done.returncode == 2 and "no such file or command: bogus" in one_line(done.stderr)
    done = sorgui("analyze", "--recognition-only", stdin=subprocess.DEVNULL)
    assert done.returncode == 0 and "no equation given: the paper's Example 1" in one_line(done.stderr)
    assert "surface of revolution: YES" in done.stdout


@pytest.mark.parametrize("each_line", [False, True])
def test_dash_f_dash_reads_standard_input(each_line: bool) -> None:
    """``-f -`` reads standard input, as ``-`` does (it said "cannot read -: No such file")."""
    options = ["--each-line"] if each_line else []
    done = sorgui("analyze", "--json", "--recognition-only", *options, "-f", "-", input="x^2 + y^2 - z\n")
    assert done.returncode == 0, done.stderr
    answer = json.loads(done.stdout.splitlines()[0] if each_line else done.stdout)
    assert answer["is_sor"] is True
    assert answer["input"] == "x^2 + y^2 - z"  # without the line break that ends the text
