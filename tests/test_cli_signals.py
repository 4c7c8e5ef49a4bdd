"""Singular dies with sorgui, whatever ends it: real processes, real signals, real Singular.

Each test starts ``sorgui analyze`` on ``tests/data/slow-singular.txt`` (its rationality stage
keeps Singular busy for minutes), waits until Singular runs, ends sorgui, and checks that no
Singular process is left (a zombie waiting for its new parent to reap it counts as dead).
Singular reads its script from standard input, so no temporary file or folder exists at all.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

pytestmark = [pytest.mark.slow, pytest.mark.skipif(not Path("/proc").is_dir(), reason="reads /proc")]

SLOW = str(Path(__file__).resolve().parent / "data" / "slow-singular.txt")
ANALYZE = [sys.executable, "-m", "sorgui.cli", "analyze", "--timeout", "600"]


def _stat(pid: int) -> tuple[str, int] | None:
    """(state, parent pid) of ``pid``, or ``None`` when it is gone."""
    try:
        text = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return None
    fields = text.rsplit(")", 1)[1].split()
    return fields[0], int(fields[1])


def descendants(pid: int) -> list[int]:
    parents: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit() and (stat := _stat(int(entry.name))) is not None:
            parents.setdefault(stat[1], []).append(int(entry.name))
    found, stack = [], [pid]
    while stack:
        for child in parents.get(stack.pop(), []):
            found.append(child)
            stack.append(child)
    return found


def singular_processes(pid: int) -> list[int]:
    out = []
    for child in descendants(pid):
        try:
            if Path(f"/proc/{child}/comm").read_text().strip() == "Singular":
                out.append(child)
        except OSError:
            pass
    return out


def dead(pid: int) -> bool:
    stat = _stat(pid)
    return stat is None or stat[0] in ("Z", "X")


def wait_for(condition: Callable[[], object], seconds: float) -> object:
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        value = condition()
        if value:
            return value
        time.sleep(0.1)
    raise AssertionError(f"not within {seconds} s")


STARTED: list[subprocess.Popen[str]] = []


@pytest.fixture(autouse=True)
def _no_process_outlives_its_test() -> Iterator[None]:
    """A failing test must not leave sorgui (and its Singular) running."""
    yield
    while STARTED:
        proc = STARTED.pop()
        if proc.poll() is None:
            proc.terminate()
            try:
                proc.communicate(timeout=30)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.communicate()


def launch(args: list[str]) -> subprocess.Popen[str]:
    """Start ``args`` as a terminal starts a command: with the default action for ``SIGINT``.
    A job that a non-interactive shell put in the background inherits ``SIGINT`` ignored (so
    that Ctrl+C spares it), and Python, like every program, then keeps ignoring it; the suite
    run that way (``bash .ci/run &``) must still see what a user at a terminal sees."""
    proc = subprocess.Popen(
        args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, preexec_fn=_default_interrupt
    )
    STARTED.append(proc)
    return proc


def _default_interrupt() -> None:
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def start(*args: str, command: list[str] | None = None) -> tuple[subprocess.Popen[str], list[int]]:
    """Start sorgui on the slow input; return it and its running Singular processes."""
    proc = launch([*(command or []), *ANALYZE, *args, "-f", SLOW])
    singulars = wait_for(lambda: singular_processes(proc.pid), 120)
    for pid in singulars:
        cmdline = Path(f"/proc/{pid}/cmdline").read_bytes().split(b"\0")
        assert all(arg.startswith(b"-") for arg in cmdline[1:] if arg), cmdline  # no script file
    return proc, singulars


def finish(proc: subprocess.Popen[str]) -> tuple[int, str]:
    _out, err = proc.communicate(timeout=60)
    return proc.returncode, err


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGHUP])
def test_sigterm_and_sighup_end_sorgui_and_singular(signum: int) -> None:
    proc, singulars = start()
    proc.send_signal(signum)
    status, err = finish(proc)
    assert status == 128 + signum and "Traceback" not in err
    wait_for(lambda: all(dead(pid) for pid in singulars), 10)


def test_sigint_prints_one_line_and_exits_130() -> None:
    proc, singulars = start()
    proc.send_signal(signal.SIGINT)
    status, err = finish(proc)
    assert status == 130 and err == "sorgui: interrupted\n"
    wait_for(lambda: all(dead(pid) for pid in singulars), 10)


def test_kill_9_of_sorgui_kills_singular() -> None:
    proc, singulars = start()
    proc.kill()
    finish(proc)
    wait_for(lambda: all(dead(pid) for pid in singulars), 10)


def test_the_timeout_command_ends_singular_too() -> None:
    started = time.monotonic()
    proc, singulars = start(command=["timeout", "40"])
    status, err = finish(proc)
    assert status == 124 and "Traceback" not in err  # timeout's own status after its SIGTERM
    assert time.monotonic() - started < 70
    wait_for(lambda: all(dead(pid) for pid in singulars), 10)


def test_singular_has_a_cpu_limit() -> None:
    proc, singulars = start()
    try:
        limits = Path(f"/proc/{singulars[0]}/limits").read_text()
        line = next(line for line in limits.splitlines() if line.startswith("Max cpu time"))
        soft = line.split()[3]
        assert soft.isdigit() and int(soft) <= 600 + 10
    finally:
        proc.kill()
        finish(proc)


def test_batch_workers_and_their_singular_end_with_sorgui(tmp_path: Path) -> None:
    lines = tmp_path / "lines.txt"
    equation = Path(SLOW).read_text(encoding="utf-8").strip()
    lines.write_text(f"{equation}\n{equation}\n", encoding="utf-8")
    proc = launch([*ANALYZE, "--each-line", "--jobs", "2", "-f", str(lines)])
    singulars = wait_for(lambda: singular_processes(proc.pid), 120)
    workers = [pid for pid in descendants(proc.pid) if pid not in singulars]
    proc.send_signal(signal.SIGTERM)
    status, err = finish(proc)
    assert status == 128 + signal.SIGTERM and "Traceback" not in err
    wait_for(lambda: all(dead(pid) for pid in singulars + workers), 15)


def test_a_batch_survives_a_worker_that_dies(tmp_path: Path) -> None:
    lines = tmp_path / "lines.txt"
    equation = Path(SLOW).read_text(encoding="utf-8").strip()
    # the other lines are not surfaces of revolution: only the first line runs Singular
    lines.write_text(f"{equation}\nx^2 + 2y^2 - z\nx^2 + 2y^2 + 3z^2 - 1\n", encoding="utf-8")
    proc = launch([*ANALYZE, "--each-line", "--jobs", "2", "-f", str(lines)])
    singular = wait_for(lambda: singular_processes(proc.pid), 120)[0]
    worker = _stat(singular)[1]
    os.kill(worker, signal.SIGKILL)  # as the kernel's out-of-memory killer would
    out, err = proc.communicate(timeout=120)
    assert proc.returncode == 1 and "Traceback" not in err, (out, err)
    rows = [json.loads(line) for line in out.splitlines()]
    assert [row["line"] for row in rows] == [1, 2, 3]
    assert "the analysis process died (signal 9)" in rows[0]["error"]["message"], rows[0]
    assert rows[1]["is_sor"] is False and rows[2]["is_sor"] is False
    wait_for(lambda: dead(singular), 10)


def test_ctrl_c_while_the_command_line_loads_prints_one_line_and_exits_130() -> None:
    """A Ctrl+C in the first 40 ms, while ``sorgui.cli`` was imported, printed a
    ``KeyboardInterrupt`` traceback and the process died by the signal: the console script's
    entry point (``sorgui.launcher``) answers it as ``sorgui.cli.main`` does. The interrupt is
    raised by an import hook at the import of ``sorgui.cli``, where a real one would land."""
    code = (
        "import sys\n"
        "class Interrupt:\n"
        "    def find_spec(self, name, path=None, target=None):\n"
        "        if name == 'sorgui.cli':\n"
        "            raise KeyboardInterrupt\n"
        "sys.meta_path.insert(0, Interrupt())\n"
        "from sorgui.launcher import main\n"
        "sys.exit(main())\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code, "analyze", "x^2+y^2-z"], capture_output=True, text=True, timeout=60
    )
    assert out.returncode == 130 and out.stderr == "sorgui: interrupted\n"


def test_the_console_script_runs_the_launcher() -> None:
    from importlib.metadata import entry_points

    scripts = {e.name: e.value for e in entry_points(group="console_scripts") if e.name == "sorgui"}
    assert scripts == {"sorgui": "sorgui.launcher:main"}
