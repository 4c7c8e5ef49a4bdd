"""File → Open of a CAD part (STEP, IGES, BRep): a window with the part, its recognised axes and
the report of its faces.

The part is read and its faces recognised in a process of its own (spawned,
:class:`~sorgui.session.part_job.PartWorker`: Open CASCADE holds the interpreter's lock, and a
cancelled or closed window kills it at once); the window polls it, shows the faces recognised so
far in its status line, and then draws the part's triangles coloured by kind, one line per axis
its faces share, and the text report (:func:`sorgui.cad.part_report.text_report`, the same lines
``sorgui analyze PART.step`` prints). Right-click (or P) on a face names it. File → Save
Canonical Part writes the part with its recognised faces on native surfaces (the analysis runs
again in the process, with the file asked for), Save Report its JSON or text.
"""

from __future__ import annotations

import gc
import json
import multiprocessing
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from PySide6.QtCore import QObject, Qt, QTimer, Signal
from PySide6.QtGui import QAction, QFontDatabase, QKeySequence
from PySide6.QtWidgets import QFileDialog, QMainWindow, QMessageBox, QPlainTextEdit, QSplitter, QWidget

from sorgui.cad.part_report import KIND_WORDS, PartReport, axis_words, face_words, text_report
from sorgui.render.plotting import forwarders
from sorgui.session.part_job import PART_SUFFIXES, PartAnswer, PartRequest, PartWorker

if TYPE_CHECKING:
    from sorgui.cad.tessellation import PartMesh
    from sorgui.gui.render_window import RenderWindow

POLL_MS = 100
"""How often the window looks for the part process's news."""
KIND_COLORS = {
    "plane": "#b0bec5",
    "sphere": "#ef9a9a",
    "cylinder": "#90caf9",
    "cone": "#ffcc80",
    "torus": "#ce93d8",
    "revolution": "#7fa7d6",
    "extrusion": "#a5d6a7",
    "cone-over-curve": "#fff59d",
    "none": "#8d6e63",
}
"""The colour of the faces of each kind."""
AXIS_COLOR = "#1f2a44"


class PartRunner(QObject):
    """One part analysis at a time in a spawned :class:`PartWorker`: :attr:`progress` after each
    face, then :attr:`finished` with the :class:`PartAnswer` (its ``error`` set on failure)."""

    progress = Signal(int, int)
    finished = Signal(object)

    def __init__(self, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self._worker: PartWorker | None = None
        self._timer = QTimer(self)
        self._timer.setInterval(POLL_MS)
        self._timer.timeout.connect(self._poll)
        self._done = -1

    @property
    def busy(self) -> bool:
        return self._timer.isActive()

    def start(self, request: PartRequest) -> None:
        self.cancel()
        try:
            self._worker = PartWorker(multiprocessing.get_context("spawn"))
        except OSError as exc:
            self.finished.emit(PartAnswer(error=f"the part's process could not be started: {exc.strerror or exc}"))
            return
        self._worker.give(request)
        self._done = -1
        self._timer.start()

    def _poll(self) -> None:
        worker = self._worker
        if worker is None:
            self._timer.stop()
            return
        answer = worker.collect()
        if worker.log.done != self._done and worker.log.total:
            self._done = worker.log.done
            self.progress.emit(worker.log.done, worker.log.total)
        if answer is not None:
            self._timer.stop()
            self._end()
            self.finished.emit(answer)

    def cancel(self) -> None:
        """Kill the running analysis, if any (nothing is emitted)."""
        self._timer.stop()
        self._end()

    def _end(self) -> None:
        if self._worker is not None:
            self._worker.close(wait=0.5)
            self._worker = None


class PartWindow(QMainWindow):
    """The window of one part: the 3D view on the left, the report on the right."""

    shown = Signal(object)
    """The :class:`PartReport` once it is drawn (or ``None`` when the analysis failed)."""

    def __init__(self, path: str | Path, parent: QWidget | None = None) -> None:
        super().__init__(parent, Qt.WindowType.Window)
        self.setAttribute(Qt.WidgetAttribute.WA_DeleteOnClose)
        self.path = Path(path)
        self.report: PartReport | None = None
        self.mesh: PartMesh | None = None
        self.setWindowTitle(f"{self.path.name} — sorgui")
        self.runner = PartRunner(self)
        self.runner.progress.connect(self._on_progress_change)
        self.runner.finished.connect(self._on_finished)
        self.text = QPlainTextEdit(self)
        self.text.setReadOnly(True)
        self.text.setLineWrapMode(QPlainTextEdit.LineWrapMode.NoWrap)
        self.text.setFont(QFontDatabase.systemFont(QFontDatabase.SystemFont.FixedFont))
        self.text.setPlainText(f"Reading {self.path} …")
        from sorgui.gui.render_window import RenderWindow

        self.splitter = QSplitter(self)
        self.plotter: RenderWindow = RenderWindow(self.splitter, auto_update=False, multi_samples=0)
        forwarders(self.plotter).set_background("#fbfcfe", top="#d9e2ee")
        forwarders(self.plotter).add_axes(line_width=3, labels_off=False)
        forwarders(self.plotter).enable_surface_point_picking(
            callback=self._pick, show_message=False, show_point=False, left_clicking=False
        )
        self.splitter.addWidget(self.plotter)
        self.splitter.addWidget(self.text)
        self.splitter.setSizes([620, 580])
        self.setCentralWidget(self.splitter)
        self._build_menu()
        self.resize(1200, 760)
        self.statusBar().showMessage(f"Reading {self.path.name} (Open CASCADE)…")
        self.runner.start(PartRequest(str(self.path), mesh=True))

    def _build_menu(self) -> None:
        menu = self.menuBar().addMenu("&File")
        self.save_canonical_action = QAction("Save &Canonical Part…", self)
        self.save_canonical_action.setEnabled(False)
        self.save_canonical_action.triggered.connect(self._ask_canonical)
        self.save_report_action = QAction("Save &Report…", self)
        self.save_report_action.setEnabled(False)
        self.save_report_action.triggered.connect(self._ask_report)
        close = QAction("&Close", self)
        close.setShortcut(QKeySequence.StandardKey.Close)
        close.triggered.connect(self.close)
        for action in (self.save_canonical_action, self.save_report_action, close):
            menu.addAction(action)

    # --- the analysis ---

    def _on_progress_change(self, done: int, total: int) -> None:
        self.statusBar().showMessage(f"Recognising the faces of {self.path.name}: {done} of {total}…")

    def _on_finished(self, answer: PartAnswer) -> None:
        if answer.files:
            self._write_canonical(answer)
            return
        if answer.report is None:
            self.text.setPlainText(answer.error or "The part could not be analysed.")
            self.statusBar().showMessage(answer.error or "The part could not be analysed.")
            self.shown.emit(None)
            return
        self.report, self.mesh = answer.report, answer.mesh
        self.text.setPlainText(text_report(answer.report))
        self._draw()
        self.save_canonical_action.setEnabled(True)
        self.save_report_action.setEnabled(True)
        counts = ", ".join(f"{n} {kind}" for kind, n in answer.report.counts().items())
        groups = len(answer.report.groups)
        self.statusBar().showMessage(
            f"{len(answer.report.faces)} faces ({counts}); {groups} axis{'es' if groups != 1 else ''} "
            f"shared; {answer.report.seconds:.1f} s. Right-click a face (or press P) to name it."
        )
        self.shown.emit(answer.report)

    def _draw(self) -> None:
        """The part's triangles coloured by kind, and a line along each shared axis across it."""
        import pyvista

        assert self.report is not None
        mesh = self.mesh
        if mesh is None or len(mesh.triangles) == 0:
            return
        cells = np.hstack([np.full((len(mesh.triangles), 1), 3), mesh.triangles]).ravel()
        surface = pyvista.PolyData(mesh.points, cells)
        kinds = {f.face: f.kind for f in self.report.faces}
        colors = np.array([_rgb(KIND_COLORS[kinds.get(int(k), "none")]) for k in mesh.faces], dtype=np.uint8)
        surface.cell_data["colors"] = colors
        self.plotter.add_mesh(surface, scalars="colors", rgb=True, name="part", smooth_shading=False)
        low, high = mesh.points.min(axis=0), mesh.points.max(axis=0)
        centre, size = (low + high) / 2, float(np.linalg.norm(high - low)) / 2 or 1.0
        for number, group in enumerate(self.report.groups, start=1):
            point, direction = np.array(group.axis.point), np.array(group.axis.direction)
            foot = point + ((centre - point) @ direction) * direction
            line = pyvista.Line(foot - 1.2 * size * direction, foot + 1.2 * size * direction)
            self.plotter.add_mesh(line, color=AXIS_COLOR, line_width=3, name=f"axis-{number}")
        legend = [(KIND_WORDS[k].removeprefix("a ").removeprefix("an "), KIND_COLORS[k]) for k in self.report.counts()]
        forwarders(self.plotter).add_legend(legend, bcolor="white", face="rectangle", size=(0.2, 0.035 * len(legend)))
        self._look_across(centre, size)
        self.plotter.render()

    def _look_across(self, centre: np.ndarray, size: float) -> None:
        """Point the camera at the part from across its first shared axis, a little from above
        (along the axis it would be seen end on), else from the default corner."""
        assert self.report is not None
        camera = self.plotter.camera
        if self.report.groups:
            axis = np.array(self.report.groups[0].axis.direction)
            side = np.cross(axis, np.eye(3)[int(np.argmin(np.abs(axis)))])
            side /= np.linalg.norm(side)
            camera.position = tuple(centre + 4 * size * (side + 0.35 * axis))
            camera.focal_point = tuple(centre)
            camera.up = tuple(axis)
        forwarders(self.plotter).reset_camera()

    def _pick(self, point: Any) -> None:  # noqa: ANN401 - a point as pyvista hands it
        """Name the face under a picked point (the nearest triangle's face)."""
        if self.mesh is None or self.report is None or point is None:
            return
        corners = self.mesh.points[self.mesh.triangles].mean(axis=1)
        nearest = int(np.argmin(np.linalg.norm(corners - np.asarray(point), axis=1)))
        number = int(self.mesh.faces[nearest])
        face = self.report.faces[number - 1]
        self.statusBar().showMessage(f"face {number} ({face.type_in_file}): {face_words(face)}")
        group = next((g for g in self.report.groups if number in g.faces), None)
        if group is not None:
            self.text.setToolTip(f"face {number} shares the axis {axis_words(group.axis)}")

    # --- saving ---

    def _ask_canonical(self) -> None:
        suggestion = str(self.path.with_name(self.path.stem + ".canonical.step"))
        path, _ = QFileDialog.getSaveFileName(
            self, "Save Canonical Part", suggestion, "STEP (*.step *.stp);;IGES (*.iges *.igs);;BRep (*.brep)"
        )
        if path:
            self.save_canonical(path)

    def save_canonical(self, path: str | Path) -> None:
        """Write the canonical part to ``path`` (in the part process: the analysis runs again)."""
        if Path(path).suffix.lower() not in PART_SUFFIXES:
            self._show_error(f"{path}: a canonical part is written as {', '.join(PART_SUFFIXES)}")
            return
        self.statusBar().showMessage(f"Writing {Path(path).name} (the faces on native surfaces)…")
        self.save_canonical_action.setEnabled(False)
        self.runner.start(PartRequest(str(self.path), canonical=(str(path),)))

    def _write_canonical(self, answer: PartAnswer) -> None:
        from sorgui.export.atomic import atomic_write_bytes

        self.save_canonical_action.setEnabled(True)
        for file in answer.files:
            try:
                atomic_write_bytes(file.path, file.data)
            except OSError as exc:
                self._show_error(f"cannot write {file.path}: {exc.strerror or exc}")
                return
            self.statusBar().showMessage(f"Wrote {file.path}: {file.holds}")

    def _ask_report(self) -> None:
        suggestion = str(self.path.with_name(self.path.stem + ".faces.json"))
        path, _ = QFileDialog.getSaveFileName(self, "Save Report", suggestion, "JSON (*.json);;Text (*.txt)")
        if path:
            self.save_report(path)

    def save_report(self, path: str | Path) -> None:
        """Write the report as JSON (``.json``) or text (anything else)."""
        from sorgui.export.atomic import atomic_write_text

        assert self.report is not None
        text = (
            json.dumps(self.report.to_json(), indent=1)
            if str(path).lower().endswith(".json")
            else text_report(self.report)
        )
        try:
            atomic_write_text(path, text + "\n")
        except OSError as exc:
            self._show_error(f"cannot write {path}: {exc.strerror or exc}")
            return
        self.statusBar().showMessage(f"Wrote {path}")

    def _show_error(self, message: str) -> None:
        QMessageBox.warning(self, "sorgui", message)

    def closeEvent(self, event: Any) -> None:  # noqa: N802, ANN401 (Qt override)
        """Kill the part process and release the render window while it still exists."""
        self.runner.cancel()
        self.plotter.close()
        self.plotter.deep_clean()
        gc.collect()
        super().closeEvent(event)


def _rgb(color: str) -> tuple[int, int, int]:
    value = color.lstrip("#")
    return int(value[0:2], 16), int(value[2:4], 16), int(value[4:6], 16)


def open_part(parent: QWidget, path: str | Path) -> PartWindow:
    """Open the window of the part ``path`` (it reads the part in the background)."""
    window = PartWindow(path, parent)
    window.show()
    return window
