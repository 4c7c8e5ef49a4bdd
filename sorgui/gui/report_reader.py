"""File → Open of a saved report off the GUI thread.

The report is read and its claims checked by the child process of
:class:`~sorgui.session.report_process.ReportReading` (seconds for a report of megabytes; a
thread would hold the interpreter's lock and freeze the window just the same); the window polls
it and, once the analysis has come, shows it as saved. The child is killed at the window's time
limit (Analysis → Time Limit), when another report is opened or an equation analysed instead,
and when the window quits.
"""

from __future__ import annotations

import multiprocessing
import time

from PySide6.QtCore import QObject, QTimer, Signal

from sorgui.session.report_process import ReportNotRead, ReportRead, ReportReading

POLL_MS = 50
"""How often the window looks whether the report is read."""


class ReportReader(QObject):
    """One report at a time: :attr:`read` with its path and
    :class:`~sorgui.engine.results.Analysis`, or :attr:`refused` with its path and the reason in
    one line."""

    read = Signal(str, object)
    refused = Signal(str, str)

    def __init__(self, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self._reading = ReportReading(multiprocessing.get_context("spawn"))
        self._timer = QTimer(self)
        self._timer.setInterval(POLL_MS)
        self._timer.timeout.connect(self._poll)

    @property
    def busy(self) -> bool:
        return self._reading.busy

    @property
    def pid(self) -> int | None:
        """The reading process's id, while there is one."""
        child = self._reading.child
        return child.pid if child is not None else None

    def start(self, path: str, timeout: float | None = None, line: int | None = None) -> None:
        """Read the report ``path`` (of a batch's results file, the result of input ``line``; the
        one being read is dropped), killed after ``timeout`` seconds."""
        self._reading.limit = timeout
        self._reading.give(path, None if timeout is None else time.monotonic() + timeout, line)
        self._timer.start()

    def cancel(self) -> None:
        """Drop the report being read, if any (nothing is emitted for it)."""
        self._timer.stop()
        self._reading.cancel()

    def _poll(self) -> None:
        match self._reading.collect():
            case ReportRead(path, analysis):
                self._timer.stop()
                self.read.emit(path, analysis)
            case ReportNotRead(path, message):
                self._timer.stop()
                self.refused.emit(path, message)
            case None if not self._reading.busy:
                self._timer.stop()

    def shutdown(self) -> None:
        """End the reading process (on quit)."""
        self._timer.stop()
        self._reading.close()
