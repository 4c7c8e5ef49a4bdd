"""File → Export of the formats that take seconds (STEP, IGES, BRep), off the GUI thread.

Writing a CAD file imports Open CASCADE (1–4 s) and may fit a profile; Open CASCADE's calls
hold the interpreter's lock, so a thread would still freeze the window. The file is written
in a process of its own (spawned, like the analysis worker), from the shown analysis and the
drawn scene, both plain data; the window polls it and says when it is done or why it failed.
"""

from __future__ import annotations

import multiprocessing
from concurrent.futures import Future, ProcessPoolExecutor
from pathlib import Path
from typing import Any

from PySide6.QtCore import QObject, QTimer, Signal

from sorgui.engine.results import Analysis
from sorgui.export.files import export_file

POLL_MS = 100
"""How often the window looks whether the file is written."""


def _write(analysis: Analysis, path: str, scene: Any) -> tuple[Path, str]:
    """The file written and what it holds (the CAD route and faces, or ``""``)."""
    return export_file(analysis, path, scene=scene)


class BackgroundExport(QObject):
    """One export at a time in a child process: :attr:`written` with the path and what the file
    holds, or :attr:`failed` with the reason (the error's message, as the synchronous exports
    show it)."""

    written = Signal(object, str)
    failed = Signal(str)

    def __init__(self, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self._pool: ProcessPoolExecutor | None = None
        self._future: Future[tuple[Path, str]] | None = None
        self._timer = QTimer(self)
        self._timer.setInterval(POLL_MS)
        self._timer.timeout.connect(self._poll)

    @property
    def busy(self) -> bool:
        return self._future is not None

    def start(self, analysis: Analysis, path: str | Path, scene: Any) -> None:
        if self._pool is None:
            self._pool = ProcessPoolExecutor(max_workers=1, mp_context=multiprocessing.get_context("spawn"))
        self._future = self._pool.submit(_write, analysis, str(path), scene)
        self._timer.start()

    def _poll(self) -> None:
        future = self._future
        if future is None or not future.done():
            return
        self._timer.stop()
        self._future = None
        try:
            self.written.emit(*future.result())
        except (OSError, ValueError) as exc:
            self.failed.emit(str(exc))
        except Exception as exc:  # the process died, or an error Open CASCADE raised
            self.failed.emit(f"{type(exc).__name__}: {exc}")

    def shutdown(self) -> None:
        """End the export process (on quit): a file half written is never renamed into place."""
        self._timer.stop()
        if self._pool is not None:
            self._pool.shutdown(wait=False, cancel_futures=True)
            self._pool = None
        self._future = None
