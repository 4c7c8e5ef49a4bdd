"""File → Open of a saved report reads and checks it in a process of its own: the window keeps
answering meanwhile (it froze for seconds on a report of megabytes), says what it is doing, and
then shows the report as saved; a refused report is one line, and the shown results stay."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest
from PySide6.QtCore import QTimer

from benchmarks.window import rounded_degree_12

pytestmark = pytest.mark.gui

HEARTBEAT_MS = 10
LONGEST_GAP_S = 0.5
"""The promise: the window never stops answering while a report is read (room for a loaded
machine; reading this report on the GUI thread held it for the whole reading, 1-4 s)."""


def _report(tmp_path: Path) -> Path:
    """The report of the rounded degree-12 surface (its nearest exact surface's 40-digit
    rationals), written by ``sorgui analyze`` in another process, as a colleague's would be."""
    equation = tmp_path / "degree12.txt"
    equation.write_text(rounded_degree_12(), encoding="utf-8")
    path = tmp_path / "degree12.sorgui.json"
    done = subprocess.run(
        [sys.executable, "-m", "sorgui.cli", "analyze", "-f", str(equation), "-o", str(path)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr
    return path


def test_a_large_report_is_read_while_the_window_keeps_answering(window, qtbot, tmp_path) -> None:
    report = _report(tmp_path)
    ticks: list[float] = []
    heartbeat = QTimer(window)
    heartbeat.setInterval(HEARTBEAT_MS)
    heartbeat.timeout.connect(lambda: ticks.append(time.monotonic()))
    heartbeat.start()
    read_at: list[float] = []
    window.report_reader.read.connect(lambda *_: read_at.append(time.monotonic()))
    started = time.monotonic()
    with qtbot.waitSignal(window.result_shown, timeout=180_000):
        assert window.open_file(str(report))
        assert window.report_reader.busy and window.report_reader.pid not in (None, os.getpid())
        assert "Reading the report degree12.sorgui.json" in window.statusBar().currentMessage()
    heartbeat.stop()
    assert read_at, "the report was shown without being read"
    reading = [t for t in ticks if t <= read_at[0]]
    gaps = [b - a for a, b in zip([started, *reading], reading)]
    assert reading and max(gaps) < LONGEST_GAP_S, (max(gaps, default=None), read_at[0] - started)
    assert window.session.run.analysis.approximate is not None  # the rounded surface, as saved
    assert window.editor.text() == window.session.run.analysis.input
    assert "not analysed again" in window.statusBar().currentMessage()
    assert not window.report_reader.busy


def test_a_report_that_is_no_report_is_refused_in_one_line_and_the_results_stay(
    window, run_analysis, qtbot, tmp_path, monkeypatch
) -> None:
    run_analysis(window, "x^2+y^2-z^2-1")
    shown: list[str] = []
    monkeypatch.setattr(window, "_show_error", lambda title, message: shown.append(f"{title}: {message}"))
    broken = tmp_path / "broken.json"
    broken.write_text('{"input": "x^2", "is_sor": tru', encoding="utf-8")
    with qtbot.waitSignal(window.report_reader.refused, timeout=120_000):
        assert window.open_file(str(broken))
    assert len(shown) == 1 and "is not a JSON report" in shown[0] and "\n" not in shown[0]
    assert window.editor.text() == "x^2+y^2-z^2-1" and window.session.run.outcome == "finished"


def test_analysing_an_equation_drops_the_report_being_read(window, run_analysis, qtbot, tmp_path) -> None:
    report = _report(tmp_path)
    assert window.open_file(str(report))
    assert window.report_reader.busy
    run_analysis(window, "x^2+y^2+z^2-1")
    assert not window.report_reader.busy
    qtbot.wait(500)
    assert window.editor.text() == "x^2+y^2+z^2-1" and window.session.run.text == "x^2+y^2+z^2-1"
    assert "Reading the report" not in window.statusBar().currentMessage()  # it stayed there for good
