"""The analysis worker: cancel stops the worker process and every Singular it started.

The process checks use ``/proc`` (Linux), like the worker itself.
"""

from __future__ import annotations

import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from PySide6.QtCore import Qt

from sorgui.examples import example_text
from sorgui.session.child import descendants, kill_process_tree

linux_only = pytest.mark.skipif(not Path("/proc").is_dir(), reason="needs /proc")


def process_gone(pid: int) -> bool:
    """True when ``pid`` no longer runs (it does not exist, or is a zombie nobody reaped yet)."""
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return True
    return state in ("Z", "X")


def dense_polynomial(degree: int, seed: int = 5) -> str:
    """A dense polynomial in general position: its recognition keeps flint busy for seconds."""
    rng = random.Random(seed)
    terms = [
        f"{rng.choice([-1, 1]) * rng.randint(1, 99)}*x^{i}*y^{j}*z^{k}"
        for i in range(degree + 1)
        for j in range(degree + 1 - i)
        for k in range(degree + 1 - i - j)
    ]
    return "+".join(terms)


@pytest.fixture
def fake_singular(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A ``Singular`` that never finishes (set before the worker process starts): every call
    the engine makes hangs until it is killed, so cancelling always meets a running Singular."""
    script = tmp_path / "Singular"
    script.write_text("#!/bin/sh\nexec sleep 600\n")
    script.chmod(0o755)
    monkeypatch.setenv("SORGUI_SINGULAR", str(script))
    return script


@linux_only
@pytest.mark.gui
def test_cancel_kills_the_running_singular(make_window, qtbot, fake_singular: Path) -> None:
    window = make_window()
    stages: list[str] = []
    window.worker.progress.connect(stages.append)
    window.set_equation(example_text("paper-example-1"))
    assert window.analyze()
    pid = window.worker.current_pid
    qtbot.waitUntil(lambda: "rationality" in stages, timeout=60_000)
    qtbot.waitUntil(lambda: any("sleep" in _cmdline(p) for p, _ in descendants(pid)), timeout=10_000)
    singular = [p for p, _ in descendants(pid) if "sleep" in _cmdline(p)]
    assert singular, "the engine started Singular"
    started = time.monotonic()
    with qtbot.waitSignal(window.worker.cancelled, timeout=5000):
        qtbot.mouseClick(window.cancel_button, Qt.MouseButton.LeftButton)
    assert time.monotonic() - started < 2.0
    qtbot.waitUntil(lambda: process_gone(pid), timeout=5000)
    qtbot.waitUntil(lambda: all(process_gone(p) for p in singular), timeout=5000)
    assert not window.worker.is_busy and window.stage_label.text() == "Cancelled"
    # the mesh was drawn before Singular started: the cancelled run can still be redrawn
    assert window.session.run.scene is not None
    assert window.viewport.radius_box.isEnabled()
    radius = window.viewport.scene.region.radius
    with qtbot.waitSignal(window.session.events.refreshed, timeout=60_000) as refreshed:
        window.viewport.radius_requested.emit(2 * radius)
    assert refreshed.args[0] == "scene" and refreshed.args[1] is not None
    qtbot.waitUntil(lambda: abs(window.viewport.scene.region.radius - 2 * radius) < 1e-9, timeout=10_000)
    assert window.session.run.outcome == "cancelled", "redrawing does not pretend the run finished"


@linux_only
@pytest.mark.gui
@pytest.mark.slow
def test_cancel_kills_a_worker_busy_in_compiled_code(make_window, qtbot) -> None:
    """The recognition of a dense degree-40 surface runs in flint for seconds without looking
    at the cancel event: the worker is killed after the grace time, not waited for."""
    window = make_window()
    stages: list[str] = []
    window.worker.progress.connect(stages.append)
    window.set_equation(dense_polynomial(40))
    assert window.editor.is_valid is None  # too long to parse on the GUI thread
    assert window.analyze()
    pid = window.worker.current_pid
    qtbot.waitUntil(lambda: "recognition" in stages, timeout=60_000)
    started = time.monotonic()
    with qtbot.waitSignal(window.worker.cancelled, timeout=5000):
        window.cancel()
    assert time.monotonic() - started < 2.0
    qtbot.waitUntil(lambda: process_gone(pid), timeout=5000)
    assert stages[-1] == "recognition", "cancelled in the middle of the recognition"
    notice = window.run_panel.notice.text()  # the stages done before are not "nothing"
    assert "finished before the verdict was known" in notice and "nothing was finished" not in notice
    assert window.viewport.caption.text().startswith("Cancelled before the surface was drawn")


@pytest.mark.gui
def test_new_analysis_supersedes_the_running_one(window, qtbot, run_analysis) -> None:
    window.set_equation(dense_polynomial(30))
    assert window.analyze()
    first = window.worker.current_pid
    result = run_analysis(window, example_text("sphere"))
    assert result.analysis.recognition.symmetry == "sphere"
    assert window.worker.current_pid is None
    qtbot.waitUntil(lambda: process_gone(first), timeout=5000)


@pytest.mark.gui
def test_parse_errors_of_long_input_come_back_from_the_worker(window, qtbot) -> None:
    text = dense_polynomial(20) + "+*x"  # 28 000 characters: parsed by the worker
    window.set_equation(text)
    assert window.editor.is_valid is None
    with qtbot.waitSignal(window.worker.invalid, timeout=60_000):
        assert window.analyze()
    assert window.editor.error is not None and window.editor.error.position >= len(text) - 3
    assert len(window.editor.error_selections()) == 1
    assert "Not a polynomial" in window.results.banner.text()


@linux_only
def test_kill_process_tree_reaches_other_sessions(tmp_path: Path) -> None:
    """A child that starts a grandchild in a session of its own (as the engine starts
    Singular): killing the tree kills both."""
    code = (
        "import os, subprocess, sys, time\n"
        "os.setpgrp()\n"
        "p = subprocess.Popen(['sleep', '600'], start_new_session=True)\n"
        "print(p.pid, flush=True)\n"
        "time.sleep(600)\n"
    )
    child = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    try:
        grandchild = int(child.stdout.readline())
        assert (grandchild, grandchild) in descendants(child.pid)
        kill_process_tree(child.pid)
        child.wait(timeout=5)
        deadline = time.monotonic() + 5
        while not process_gone(grandchild) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert process_gone(grandchild)
    finally:
        if child.poll() is None:
            os.kill(child.pid, signal.SIGKILL)
        child.wait(timeout=5)
        child.stdout.close()


def _cmdline(pid: int) -> str:
    try:
        return Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode()
    except OSError:
        return ""


@linux_only
@pytest.mark.gui
def test_the_time_limit_holds_when_the_worker_is_stuck(make_window, qtbot, fake_singular: Path) -> None:
    """The worker process frozen (``SIGSTOP``: not even C code runs in it, the most stuck an
    analysis can be) while Singular runs: at the window's time limit the process is killed and
    the window shows what was finished, the rest as unfinished."""
    window = make_window()
    window.time_limit = 20.0  # Singular must start within it, also on a loaded machine
    window.set_equation("x^2+y^2-z^3")  # a cuspidal profile: its rationality asks Singular
    started = time.monotonic()
    with qtbot.waitSignal(window.worker.finished, timeout=30_000) as blocker:
        assert window.analyze()
        qtbot.waitUntil(
            lambda: any("sleep" in _cmdline(p) for p, _ in descendants(window.worker.current_pid or 0)), timeout=20_000
        )
        pid = window.worker.current_pid
        os.kill(pid, signal.SIGSTOP)
    assert time.monotonic() - started < 20.0 + 2.0
    analysis = blocker.args[0].analysis
    assert analysis.is_sor and "rationality" in analysis.unfinished
    qtbot.waitUntil(lambda: process_gone(pid), timeout=10_000)


@linux_only
@pytest.mark.gui
def test_cancel_stops_a_worker_inside_one_flint_factorization(make_window, qtbot) -> None:
    """Cancel while the worker is inside one flint factorization of 10 s or more (its factors
    stage): the process is killed after the grace time."""
    from tests.long_c_call import factored_product

    window = make_window()
    stages: list[str] = []
    window.worker.progress.connect(stages.append)
    window.set_equation(factored_product())
    assert window.analyze()
    pid = window.worker.current_pid
    qtbot.waitUntil(lambda: "factors" in stages, timeout=120_000)
    qtbot.wait(1000)  # well inside the factorization
    started = time.monotonic()
    with qtbot.waitSignal(window.worker.cancelled, timeout=5000):
        window.cancel()
    assert time.monotonic() - started < 2.0
    qtbot.waitUntil(lambda: process_gone(pid), timeout=5000)
    assert stages[-1] == "factors"
