"""The window ends cleanly on ``SIGTERM``, ``SIGHUP`` (a session's logout) and ``SIGINT``: a real
``sorgui`` process with its window under the test's X server, showing an analysis or a saved
report. It exits with ``128 + signal`` within seconds, prints no traceback, and leaves no worker
process behind."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.test_cli_signals import dead, descendants, wait_for

pytestmark = [pytest.mark.gui, pytest.mark.slow]


def start_window(args: list[str], home: Path) -> subprocess.Popen[str]:
    env = {**os.environ, "HOME": str(home), "XDG_CONFIG_HOME": str(home / "config")}
    proc = subprocess.Popen(
        [sys.executable, "-m", "sorgui.cli", *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env
    )
    wait_for(lambda: descendants(proc.pid) or proc.poll() is not None, 60)  # its worker process started
    time.sleep(4)  # the window is up and analysing
    assert proc.poll() is None, proc.communicate()
    return proc


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGHUP, signal.SIGINT])
def test_the_window_ends_on_a_signal(tmp_path: Path, signum: int) -> None:
    proc = start_window([], tmp_path)
    children = descendants(proc.pid)
    sent = time.monotonic()
    proc.send_signal(signum)
    _out, err = proc.communicate(timeout=30)
    assert time.monotonic() - sent < 5
    assert proc.returncode == 128 + signum and "Traceback" not in err, err
    wait_for(lambda: all(dead(pid) for pid in children), 10)


def test_a_signal_while_the_window_starts_ends_it_and_its_worker(tmp_path: Path) -> None:
    """SIGTERM as soon as the worker process exists, while the window is still being built (a
    logout during start-up): sorgui ends with 143, and no worker keeps its output open."""
    env = {**os.environ, "HOME": str(tmp_path), "XDG_CONFIG_HOME": str(tmp_path / "config")}
    proc = subprocess.Popen(
        [sys.executable, "-m", "sorgui.cli"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env
    )
    wait_for(lambda: descendants(proc.pid) or proc.poll() is not None, 60)
    children = descendants(proc.pid)
    proc.send_signal(signal.SIGTERM)
    _out, err = proc.communicate(timeout=30)
    assert proc.returncode == 128 + signal.SIGTERM and "Traceback" not in err, (proc.returncode, err)
    wait_for(lambda children=children: all(dead(pid) for pid in children), 10)


def test_the_window_showing_a_report_ends_on_sigterm(tmp_path: Path) -> None:
    report = tmp_path / "torus.sorgui.json"
    done = subprocess.run(
        [sys.executable, "-m", "sorgui.cli", "analyze", "--json", "(x^2+y^2+z^2+3)^2-16(x^2+y^2)"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    report.write_text(done.stdout, encoding="utf-8")
    assert json.loads(done.stdout)["is_sor"]
    proc = start_window(["open", str(report)], tmp_path)
    sent = time.monotonic()
    proc.send_signal(signal.SIGTERM)
    _out, err = proc.communicate(timeout=30)
    assert time.monotonic() - sent < 5
    assert proc.returncode == 128 + signal.SIGTERM and "Traceback" not in err, err
