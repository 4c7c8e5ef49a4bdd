"""The time limit and the ending signals hold whatever the analysis is doing.

A Python signal handler cannot interrupt one long C call, so sorgui runs each analysis in a
child process that it kills. The most stuck an analysis can be is a process that runs nothing
at all: each test here freezes sorgui's analysis process with ``SIGSTOP`` (neither Python nor
C code runs in it any more) and checks that ``--timeout T`` still answers within ``T + 1`` s,
with the stages it finished, and that ``SIGTERM``, ``SIGINT`` and ``SIGHUP`` end sorgui within
a second, its analysis process and Singular with it. The last test does the same with the
sphere envelope whose verification once sat in one flint composition for 20 minutes.
"""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.test_cli_signals import (
    dead,
    descendants,
    launch,
    singular_processes,
    wait_for,
)

pytestmark = [pytest.mark.slow, pytest.mark.skipif(not Path("/proc").is_dir(), reason="reads /proc")]

DATA = Path(__file__).resolve().parent / "data"
SLOW = str(DATA / "slow-singular.txt")
TORUS = "(x^2+y^2+z^2+21)^2-100(x^2+y^2)"
ANALYZE = [sys.executable, "-m", "sorgui.cli", "analyze"]


def analysis_processes(pid: int) -> list[int]:
    """sorgui's analysis processes: its descendants that are Python, not Singular."""
    singular = set(singular_processes(pid))
    return [child for child in descendants(pid) if child not in singular]


def freeze_analysis(proc: subprocess.Popen[str]) -> list[int]:
    """Wait for sorgui's analysis process and stop it dead (``SIGSTOP``)."""
    children = wait_for(lambda proc=proc: analysis_processes(proc.pid), 60)
    for child in children:
        signal_quietly(child, signal.SIGSTOP)
    return children


def signal_quietly(pid: int, signum: int) -> None:
    try:
        import os

        os.kill(pid, signum)
    except ProcessLookupError:
        pass


@pytest.fixture(autouse=True)
def _nothing_left_stopped() -> Iterator[None]:
    yield
    for pid in [int(p.name) for p in Path("/proc").iterdir() if p.name.isdigit()]:
        try:
            cmdline = Path(f"/proc/{pid}/cmdline").read_bytes()
        except OSError:
            continue
        if b"sorgui.cli" in cmdline and b"analyze" in cmdline:
            signal_quietly(pid, signal.SIGCONT)


def test_the_time_limit_holds_when_the_analysis_is_frozen() -> None:
    timeout = 4.0
    started = time.monotonic()
    proc = launch([*ANALYZE, "--json", "--timeout", str(timeout), TORUS])
    children = freeze_analysis(proc)
    out, err = proc.communicate(timeout=60)
    elapsed = time.monotonic() - started
    assert proc.returncode in (0, 1) and "Traceback" not in err, err
    assert elapsed < timeout + 1.0, elapsed
    wait_for(lambda children=children: all(dead(pid) for pid in children), 5)
    data = json.loads(out)
    if proc.returncode == 0:  # the equation had been read: the stages done, the rest unfinished
        assert data["unfinished"] and data["symmetry"] in ("undecided", "revolution")
        assert data["is_sor"] is (None if data["symmetry"] == "undecided" else True)
    else:  # frozen while still reading the equation
        assert "did not finish within the time limit of 4 s" in data["error"]["message"]


def test_the_time_limit_keeps_the_finished_stages() -> None:
    """Frozen while Singular decides the rationality: the recognition is kept, the rest is unfinished."""
    timeout = 8.0
    started = time.monotonic()
    proc = launch([*ANALYZE, "--json", "--timeout", str(timeout), "-f", SLOW])
    singulars = wait_for(lambda: singular_processes(proc.pid), 60)
    children = freeze_analysis(proc)
    out, err = proc.communicate(timeout=60)
    assert time.monotonic() - started < timeout + 1.0
    assert proc.returncode == 0 and "Traceback" not in err, err
    data = json.loads(out)
    assert data["is_sor"] is True and "rationality" in data["unfinished"]
    assert "recognition" in data["timings"] and "factors" in data["timings"]
    assert data["rationality"]["status"].startswith("undecided: the analysis did not finish within")
    wait_for(lambda: all(dead(pid) for pid in children + singulars), 5)


def test_an_analysis_that_used_up_its_time_keeps_its_report_files(tmp_path: Path) -> None:
    """Frozen in Singular until the limit: the JSON and text reports of the stages done are
    written all the same (they were lost with the files that need the export process, whose
    time was used up), the text one as the terminal shows it; the LaTeX file is said unwritten."""
    files = [tmp_path / name for name in ("r.json", "r.txt", "r.tex")]
    proc = launch([*ANALYZE, "--timeout", "8", "-f", SLOW, *(a for f in files for a in ("-o", str(f)))])
    wait_for(lambda: singular_processes(proc.pid), 60)
    freeze_analysis(proc)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 1 and "Traceback" not in err, err
    assert f"cannot write {files[2]}: not written within the time limit of 8 s" in err
    data = json.loads(files[0].read_text(encoding="utf-8"))
    assert data["is_sor"] is True and "rationality" in data["unfinished"]
    assert files[1].read_text(encoding="utf-8") == out and "surface of revolution: YES" in out
    assert not files[2].exists()


def test_a_maps_verdicts_are_not_listed_unfinished() -> None:
    """A bicubic map whose implicit equation takes more than the limit: its symmetry ("none",
    not of revolution) and its cone or cylinder come from the map and are decided; only the
    implicit equation's stages are unfinished (the recognition was listed too, beside
    ``is_sor: false``, which the README says is ``null`` when the recognition is unfinished)."""
    bicubic = (
        "x = u + 2*v^3 - u^2*v + 3*u^3*v^2, y = v - u^3 + 2*u*v^2 + u^2*v^3 - 1, z = u*v + u^3*v^3 - 2*v^2*u + 5*u^2"
    )
    done = subprocess.run([*ANALYZE, "--json", "--timeout", "3", bicubic], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    data = json.loads(done.stdout)
    assert data["input_kind"] == "parametrization" and data["is_sor"] is False and data["symmetry"] == "none"
    assert "implicit equation" in data["unfinished"] and data["conical"]["kind"] == "none"
    assert "recognition" not in data["unfinished"] and "conical" not in data["unfinished"]


def test_a_verdict_found_before_a_stuck_real_locus_is_kept() -> None:
    """The real locus of ``(x² + y² + z² + 10⁵⁰)¹⁰ − 10⁵⁰·x`` takes minutes; its analysis process
    frozen there (as inside one long C call) and ended at the limit: the verdict and the axis,
    found in milliseconds before it, are in the answer (it said "undecided")."""
    timeout = 6.0
    proc = launch([*ANALYZE, "--json", "--timeout", str(timeout), "(x^2+y^2+z^2+10^50)^10 - 10^50*x"])
    time.sleep(3.0)  # the recognition is done and the real locus started
    children = freeze_analysis(proc)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 0 and "Traceback" not in err, err
    data = json.loads(out)
    assert data["is_sor"] is True and data["axis"]["direction"] == ["1", "0", "0"]
    assert "real locus" in data["unfinished"] and len(data["factors"]) == 1
    wait_for(lambda: all(dead(pid) for pid in children), 5)


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT, signal.SIGHUP])
def test_a_signal_ends_sorgui_within_a_second_when_the_analysis_is_frozen(signum: int) -> None:
    proc = launch([*ANALYZE, "--timeout", "600", "-f", SLOW])
    singulars = wait_for(lambda: singular_processes(proc.pid), 60)
    children = freeze_analysis(proc)
    sent = time.monotonic()
    proc.send_signal(signum)
    _out, err = proc.communicate(timeout=60)
    assert time.monotonic() - sent < 1.0
    assert proc.returncode == (130 if signum == signal.SIGINT else 128 + signum) and "Traceback" not in err
    wait_for(lambda: all(dead(pid) for pid in children + singulars), 5)


def test_each_line_answers_a_frozen_line_at_its_time_limit(tmp_path: Path) -> None:
    lines = tmp_path / "lines.txt"
    lines.write_text(f"{Path(SLOW).read_text(encoding='utf-8').strip()}\nx^2 + 2y^2 - z\n", encoding="utf-8")
    started = time.monotonic()
    proc = launch([*ANALYZE, "--each-line", "--timeout", "6", "-f", str(lines)])
    wait_for(lambda: singular_processes(proc.pid), 60)
    freeze_analysis(proc)
    out, err = proc.communicate(timeout=60)
    assert time.monotonic() - started < 6 + 1.0 + 5  # the second line after the first's limit
    assert proc.returncode == 0 and "Traceback" not in err, err
    rows = [json.loads(line) for line in out.splitlines()]
    assert [row["line"] for row in rows] == [1, 2]
    assert rows[0]["is_sor"] is True and "rationality" in rows[0]["unfinished"]
    assert rows[1]["is_sor"] is False and not rows[1]["unfinished"]


def test_a_long_c_call_is_ended_at_the_time_limit() -> None:
    """The envelope of the spheres centred on ``(1, 2, -1) + t·(2, -1, 3)`` with radius ``1 + t²``."""
    text = (DATA / "sphere-envelope.txt").read_text(encoding="utf-8")
    started = time.monotonic()
    proc = subprocess.run([*ANALYZE, "--json", "--timeout", "3", text], capture_output=True, text=True, timeout=60)
    assert time.monotonic() - started < 3 + 1.0
    assert proc.returncode == 0 and "Traceback" not in proc.stderr
    data = json.loads(proc.stdout)
    assert data["is_sor"] is True and data["axis"]["direction"] == ["2", "-1", "3"]


def test_the_time_limit_and_the_signals_hold_inside_one_flint_factorization(tmp_path: Path) -> None:
    """The factors stage of a product of three dense polynomials is one flint call of 10 s or more."""
    from tests.long_c_call import factored_product

    equation = tmp_path / "product.txt"
    equation.write_text(factored_product(), encoding="utf-8")
    started = time.monotonic()
    done = subprocess.run(
        [*ANALYZE, "--json", "--timeout", "8", "-f", str(equation)], capture_output=True, text=True, timeout=120
    )
    assert time.monotonic() - started < 8 + 1.0
    data = json.loads(done.stdout)
    assert done.returncode == 0 and "factors" in data["unfinished"], data["unfinished"]
    for signum in (signal.SIGTERM, signal.SIGINT):
        proc = launch([*ANALYZE, "--timeout", "600", "-f", str(equation)])
        children = wait_for(lambda proc=proc: analysis_processes(proc.pid), 60)
        time.sleep(6)  # reading and recognising the equation: then inside the factorization
        sent = time.monotonic()
        proc.send_signal(signum)
        proc.communicate(timeout=60)
        assert time.monotonic() - sent < 1.0
        assert proc.returncode == (130 if signum == signal.SIGINT else 128 + signum)
        wait_for(lambda children=children: all(dead(pid) for pid in children), 5)


def test_a_limit_met_in_the_flint_paths_factorization_names_that_stage(tmp_path: Path) -> None:
    """``--recognition-only`` runs on flint alone; the factors stage of the same product is one
    flint call of 10 s or more there too. Ended in it at the limit, the answer names that stage
    and keeps the recognition: it said the analysis had stopped "while reading the equation"."""
    from tests.long_c_call import factored_product

    equation = tmp_path / "product.txt"
    equation.write_text(factored_product(), encoding="utf-8")
    done = subprocess.run(
        [*ANALYZE, "--json", "--recognition-only", "--timeout", "8", "-f", str(equation)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0 and "Traceback" not in done.stderr, done.stderr
    data = json.loads(done.stdout)
    assert data["unfinished"] == ["factors", "canal"]
    assert data["symmetry"] == "none" and data["is_sor"] is False
    assert list(data["timings"]) == ["parse", "recognition"]


def test_each_line_loses_no_line_when_a_worker_is_killed(tmp_path: Path) -> None:
    """The worker of the slow first line is killed (SIGKILL) while the next line waits behind it in
    its pipe: the first line says its analysis process died, and the others are analysed by a
    new worker, once each, in input order."""
    lines = tmp_path / "lines.txt"
    lines.write_text(f"{Path(SLOW).read_text(encoding='utf-8').strip()}\nx^2 + 2y^2 - z\n{TORUS}\n", encoding="utf-8")
    proc = launch([*ANALYZE, "--each-line", "--jobs", "1", "--timeout", "120", "-f", str(lines)])
    wait_for(lambda: singular_processes(proc.pid), 60)
    for child in analysis_processes(proc.pid):
        signal_quietly(child, signal.SIGKILL)
    out, err = proc.communicate(timeout=120)
    rows = [json.loads(line) for line in out.splitlines()]
    assert [row["line"] for row in rows] == [1, 2, 3], err
    assert "died" in rows[0]["error"]["message"]
    assert rows[1]["is_sor"] is False and rows[2]["is_sor"] is True
    assert proc.returncode == 1


def test_the_time_limit_holds_while_the_input_is_read(tmp_path: Path) -> None:
    """``--timeout`` counts reading the input: a named pipe with no writer hung sorgui forever
    (its open blocks, which no signal handler interrupts), and a standard input that writes
    nothing was waited for in full before the limit was said to be used up."""
    import os

    fifo = tmp_path / "equation.fifo"
    os.mkfifo(fifo)
    start = time.monotonic()
    done = subprocess.run([*ANALYZE, "--timeout", "2", "-f", str(fifo)], capture_output=True, text=True, timeout=30)
    assert time.monotonic() - start < 3 + 1  # the limit, and a second to answer
    assert done.returncode == 1
    assert "within the time limit of 2 s (while reading the equation from" in done.stderr
    start = time.monotonic()
    silent = subprocess.Popen(
        [*ANALYZE, "--timeout", "2", "-"], stdin=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    try:
        silent.wait(timeout=30)  # its standard input stays open and empty
    finally:
        silent.kill()
        assert silent.stdin is not None and silent.stderr is not None
        silent.stdin.close()
        err = silent.stderr.read()
        silent.stderr.close()
    assert time.monotonic() - start < 3 + 1 and silent.returncode == 1
    assert "while reading the equation from standard input" in err


def test_standard_input_that_is_not_text_is_refused_as_a_file_is(tmp_path: Path) -> None:
    """A UTF-16 file on standard input said "unexpected character '\\udcff'", a binary one
    "unmatched ')'"; with -f both said they are not UTF-8 text."""
    data = "x^2+y^2-1".encode("utf-16")
    path = tmp_path / "utf16.txt"
    path.write_bytes(data)
    piped = subprocess.run([*ANALYZE, "-"], input=data, capture_output=True, timeout=60)
    named = subprocess.run([*ANALYZE, "-f", str(path)], capture_output=True, timeout=60)
    assert piped.returncode == named.returncode == 2
    for done in (piped, named):
        assert b"it is not UTF-8 text (byte 1 is 0xff)" in done.stderr
