"""One line for every fault, and the right exit status (real ``sorgui analyze`` processes)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

SORGUI = [sys.executable, "-m", "sorgui.cli", "analyze"]
EQUATION = "x^2 + y^2 - z"


def shell(command: str, env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    """``command`` in a shell, where ``sorgui`` is this Python's command line."""
    line = " ".join(SORGUI)
    return subprocess.run(
        ["bash", "-c", command.replace("SORGUI", line)],
        capture_output=True,
        text=True,
        timeout=300,
        env={**os.environ, **(env or {})},
    )


def one_line(err: str) -> str:
    assert err.count("\n") == 1 and err.startswith("sorgui: ") and "Traceback" not in err, err
    return err


def test_closed_standard_streams() -> None:
    closed_in = shell("SORGUI - <&-")  # was "the input is empty"
    assert closed_in.returncode == 2 and "standard input is closed" in one_line(closed_in.stderr)
    closed_lines = shell("SORGUI --each-line - <&-")
    assert closed_lines.returncode == 2 and "standard input is closed" in one_line(closed_lines.stderr)
    empty = shell("SORGUI - </dev/null")
    assert empty.returncode == 2 and "the input is empty" in one_line(empty.stderr)
    closed_out = shell(f"SORGUI --recognition-only '{EQUATION}' >&-")
    assert closed_out.returncode == 1 and "standard output is closed" in one_line(closed_out.stderr)
    closed_err = shell(f"SORGUI --recognition-only '{EQUATION}' 2>&-")
    assert closed_err.returncode == 0 and "surface of revolution: YES" in closed_err.stdout


@pytest.mark.parametrize("env", [{"LC_ALL": "C", "PYTHONUTF8": "0"}, {"PYTHONIOENCODING": "ascii"}])
def test_an_ascii_locale_gets_the_report_escaped(env: dict[str, str]) -> None:
    done = shell(f"SORGUI --recognition-only '{EQUATION}'", env)
    assert done.returncode == 0 and done.stderr == "" and "t\\xb7(0, 0, 1)" in done.stdout


def test_file_names_and_option_values_give_one_line(tmp_path: Path) -> None:
    newline = subprocess.run([*SORGUI, "-f", str(tmp_path / "a\nb.txt")], capture_output=True, text=True, timeout=60)
    assert newline.returncode == 2 and "a\\nb.txt" in one_line(newline.stderr)
    long_name = subprocess.run([*SORGUI, "-f", str(tmp_path / ("a" * 300))], capture_output=True, text=True, timeout=60)
    assert long_name.returncode == 2 and "too long" in one_line(long_name.stderr)
    empty_format = subprocess.run(
        [*SORGUI, "--format", "", EQUATION, "-o", str(tmp_path / "x.txt")], capture_output=True, text=True, timeout=60
    )
    assert empty_format.returncode == 2 and "--format needs" in one_line(empty_format.stderr)


def test_an_enormous_time_limit_is_no_limit() -> None:
    done = subprocess.run(
        [*SORGUI, "--json", "--timeout", "1e10", EQUATION], capture_output=True, text=True, timeout=300
    )
    assert done.returncode == 0 and done.stderr == ""
    assert json.loads(done.stdout)["rationality"]["table_row"] == 3


def test_jobs_are_bounded_by_the_machine(tmp_path: Path) -> None:
    lines = tmp_path / "lines.txt"
    lines.write_text("x^2+y^2-z\nx^2+2y^2-z\n", encoding="utf-8")
    done = subprocess.run(
        [*SORGUI, "--each-line", "--recognition-only", "--jobs", "1000", "-f", str(lines)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0 and len(done.stdout.splitlines()) == 2
    assert "--jobs 1000 lowered to" in one_line(done.stderr)


def test_a_process_limit_is_said_in_one_line() -> None:
    """With ``ulimit -u`` at the processes already running, no analysis process can start."""
    if os.geteuid() == 0:
        pytest.skip("root is not bound by RLIMIT_NPROC")
    done = shell(f"ulimit -u 1; SORGUI --recognition-only '{EQUATION}'")
    assert done.returncode == 1 and "could not be started" in one_line(done.stderr)


def test_a_home_that_cannot_be_written_gets_no_matplotlib_warning(tmp_path: Path) -> None:
    """The picture needs matplotlib's cache; with no writable home sorgui gives it its own folder."""
    env = {key: value for key, value in os.environ.items() if key not in ("MPLCONFIGDIR", "XDG_CONFIG_HOME")}
    env["HOME"] = "/proc/self/fdinfo"  # no folder can be made there, not even by root
    done = subprocess.run(
        [*SORGUI, "--recognition-only", EQUATION, "-o", str(tmp_path / "surface.png")],
        capture_output=True,
        text=True,
        timeout=300,
        env=env,
    )
    # the cache folder is built once: matplotlib says so the first time, which is no warning of trouble
    errors = [line for line in done.stderr.splitlines() if "building the font cache" not in line]
    assert done.returncode == 0 and errors == [], done.stderr
    assert (tmp_path / "surface.png").stat().st_size > 1000


def test_a_home_that_cannot_be_written_gets_private_caches_for_mesa_too() -> None:
    """Mesa's shader cache (the window, the pictures) would print 'Failed to create
    …/mesa_shader_cache' once per process; it gets the same private folder as matplotlib."""
    env = {k: v for k, v in os.environ.items() if k not in ("MPLCONFIGDIR", "XDG_CONFIG_HOME", "XDG_CACHE_HOME")}
    env.pop("MESA_SHADER_CACHE_DIR", None)
    env["HOME"] = "/proc/self/fdinfo"
    code = (
        "import os; from sorgui import cli; cli._writable_caches(); "
        "print(os.environ['MESA_SHADER_CACHE_DIR']); print(os.environ['MPLCONFIGDIR'])"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60, env=env)
    assert done.returncode == 0, done.stderr
    mesa, matplotlib = (Path(line) for line in done.stdout.split())
    assert mesa.parent == matplotlib and matplotlib.is_dir()
    assert matplotlib.stat().st_uid == os.getuid() and not matplotlib.stat().st_mode & 0o077
    only_mesa = "import os; from sorgui import cli; cli._writable_caches(); print(os.environ['MESA_SHADER_CACHE_DIR'])"
    kept = subprocess.run(
        [sys.executable, "-c", only_mesa],
        capture_output=True,
        text=True,
        timeout=60,
        env={**env, "HOME": str(matplotlib), "MESA_SHADER_CACHE_DIR": "/mine"},
    )
    assert kept.returncode == 0 and kept.stdout == "/mine\n"  # a user's own setting wins


def test_a_process_limit_in_a_batch_is_said_in_one_line(tmp_path: Path) -> None:
    """``ulimit -u 3`` with ``--jobs 3``: every line's error object, and one line on stderr (the
    status 1 came with nothing said)."""
    if os.geteuid() == 0:
        pytest.skip("root is not bound by RLIMIT_NPROC")
    lines = tmp_path / "lines.txt"
    lines.write_text("x^2+y^2-z\nx^2+2y^2-z\nx^2+y^2+z^2-1\n", encoding="utf-8")
    done = shell(f"ulimit -u 3; SORGUI --each-line --jobs 3 -f {lines}")
    assert done.returncode == 1 and "could not be started" in one_line(done.stderr)
    assert len(done.stdout.splitlines()) == 3


def test_a_batch_that_failed_says_how_many_lines_and_the_first_reason() -> None:
    from sorgui.batch.answers import ERROR, NOT_SURFACE_OF_REVOLUTION
    from sorgui.batch.progress import Progress

    progress = Progress(None, None)
    progress.done(1, NOT_SURFACE_OF_REVOLUTION)
    progress.done(2, ERROR, "the analysis process died")
    progress.done(5, ERROR, "out of memory")
    summary = progress.summary()
    assert summary.startswith("3 lines: 0 surfaces of revolution, 1 not, 2 errors, 0 unfinished; ")
    assert summary.endswith("; the first failure, line 2: the analysis process died")
