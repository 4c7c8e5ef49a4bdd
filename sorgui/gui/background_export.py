"""File → Export off the GUI thread, every format.

Writing a CAD file imports Open CASCADE (1–4 s) and may fit a profile; Open CASCADE's calls
hold the interpreter's lock, so a thread would still freeze the window, and one call can run for
minutes. The other formats print every formula with sympy: seconds for a large equation (25 s
for the LaTeX of a degree-60 one), and the same lock. The file is written by the export
process of :mod:`sorgui.session.export_process` (spawned, like the analysis worker), from the
shown analysis, the drawn scene and the view's picture, all plain data; the window polls it and
says when it is done or why it failed. The process is killed when the export passes its time
limit (the window's, Analysis → Time Limit) and when the window quits, so nothing it does can
hang the window, and what it had half written is removed (the old file is kept).
"""

from __future__ import annotations

import multiprocessing
import time
from pathlib import Path
from typing import Any

from PySide6.QtCore import QObject, QTimer, Signal

from sorgui.engine.results import Analysis
from sorgui.session.export_process import (
    ExportProcess,
    ExportRequest,
    ExportsDone,
    ExportTarget,
    FileFailed,
    FileWritten,
    ReportRefused,
)

POLL_MS = 100
"""How often the window looks whether the file is written."""


class BackgroundExport(QObject):
    """One export at a time in a child process: :attr:`written` with the path and what the file
    holds, or :attr:`failed` with the reason in one line (``cannot write FILE: …``)."""

    written = Signal(object, str)
    failed = Signal(str)

    def __init__(self, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self._process = ExportProcess(multiprocessing.get_context("spawn"))
        self._timer = QTimer(self)
        self._timer.setInterval(POLL_MS)
        self._timer.timeout.connect(self._poll)

    @property
    def busy(self) -> bool:
        return self._process.busy

    @property
    def pid(self) -> int | None:
        """The export process's id, while there is one."""
        child = self._process.child
        return child.pid if child is not None else None

    def start(
        self,
        analysis: Analysis,
        path: str | Path,
        scene: Any,  # noqa: ANN401 - a SceneData
        picture: bytes | None = None,
        timeout: float | None = None,
    ) -> None:
        """Write ``analysis`` to ``path`` (with the drawn ``scene`` and the view's ``picture``),
        killed after ``timeout`` seconds."""
        self._process.limit = timeout
        request = ExportRequest(targets=(ExportTarget(str(path)),), analysis=analysis, scene=scene, picture=picture)
        self._process.give(request, None if timeout is None else time.monotonic() + timeout)
        self._timer.start()

    def _poll(self) -> None:
        if not self._process.busy:
            self._timer.stop()
            return
        for message in self._process.collect():
            match message:
                case FileWritten(path, holds):
                    self.written.emit(Path(path), holds)
                case FileFailed(_, reason) | ReportRefused(reason):
                    self.failed.emit(reason)
                case ExportsDone():
                    self._timer.stop()

    def shutdown(self) -> None:
        """End the export process (on quit): a file half written is never renamed into place."""
        self._timer.stop()
        self._process.close()
