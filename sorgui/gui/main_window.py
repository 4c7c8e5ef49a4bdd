"""The main window: editor and results on the left, the 3D viewport on the right.

It wires the parts together and owns no mathematics: the editor validates the text, the
:class:`~sorgui.session.model.Session` owns the equation and the running analysis (through the
:class:`~sorgui.gui.worker.AnalysisWorker`, which runs it in another process), and the
:class:`~sorgui.gui.session_view.SessionView` renders the session into the run panel, the
results pane and the viewport as results arrive. Keyboard: Ctrl+Return analyses, Esc cancels,
Ctrl++/Ctrl+−/Ctrl+0 zoom the formulas. Typed text is never discarded without asking (Example,
Open, New, Quit); the window works down to 800×560 (the panes scroll).
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING

from PySide6.QtCore import QEvent, QObject, QSize, Qt, Signal
from PySide6.QtGui import (
    QAction,
    QCloseEvent,
    QDragEnterEvent,
    QDragMoveEvent,
    QDropEvent,
    QGuiApplication,
    QKeySequence,
    QPainter,
    QPaintEvent,
    QPen,
    QWheelEvent,
)
from PySide6.QtWidgets import (
    QDialog,
    QFileDialog,
    QHBoxLayout,
    QInputDialog,
    QLabel,
    QMainWindow,
    QMenu,
    QMessageBox,
    QPushButton,
    QSplitter,
    QVBoxLayout,
    QWidget,
)

from sorgui import __version__
from sorgui.engine.parsing import is_parametrization
from sorgui.engine.results import Analysis
from sorgui.examples import EXAMPLES, example_text
from sorgui.export.atomic import atomic_write_bytes
from sorgui.export.formats import format_of
from sorgui.gui.background_export import BackgroundExport
from sorgui.gui.camera import CameraState
from sorgui.gui.editor import EquationEditor
from sorgui.gui.examples import ExamplesMenu
from sorgui.gui.exporting import (
    CAD_CHOICES,
    REPORT_FILTER,
    PictureDialog,
    export_filters,
    filter_of_suffix,
    is_report_path,
    is_results_path,
    png_bytes,
    suffix_of_filter,
    viewport_image,
    with_suffix_of,
    without_export_suffix,
)
from sorgui.gui.flow_layout import ElidedLabel
from sorgui.gui.help import TOPICS, HelpDialog
from sorgui.gui.region_dialog import BoxDialog
from sorgui.gui.report_reader import ReportReader
from sorgui.gui.results import ResultsPane
from sorgui.gui.session_view import SessionView
from sorgui.gui.settings import (
    EQUATION_FILTER,
    EquationFileError,
    RecentFilesMenu,
    Settings,
    read_equation,
    write_equation,
)
from sorgui.gui.stages import RunPanel, Ticker
from sorgui.gui.typesetter import Typesetter
from sorgui.gui.viewport import Viewport
from sorgui.gui.wording import INVALID_NOTICE, invalid_heading, no_surface_caption
from sorgui.gui.worker import AnalysisWorker
from sorgui.session.model import Session
from sorgui.session.part_job import PART_SUFFIXES

if TYPE_CHECKING:
    from sorgui.render.picking import PickInfo

ZOOM_STEPS = (0.8, 0.9, 1.0, 1.15, 1.3, 1.5, 1.75, 2.0, 2.5)
"""The zoom factors of the formulas (Ctrl++ and Ctrl+− step through them)."""

MINIMUM_SIZE = (800, 560)
"""The window works down to this size: below it the panes scroll instead of cutting."""

DEFAULT_EXAMPLE = EXAMPLES[0].name
"""The paper's Example 1, loaded on a first start."""

REPORT_PICTURE_WIDTH = 1200
"""Width in pixels of the picture of the 3D view in Markdown and HTML reports."""


class BusyIndicator(QWidget):
    """A small spinning arc for the status bar, turned at each tick of the window's clock.

    Cheaper than an indeterminate ``QProgressBar``, whose animation repaints continuously and
    costs most of a core under software rendering (Xvfb); on the window's :class:`Ticker` its
    repaints fall in the same turns as the running stage's time (one composition of the window).
    """

    def __init__(self, ticker: Ticker, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setFixedSize(16, 16)
        self._angle = 0
        self._ticker = ticker
        ticker.tick.connect(self._tick)

    def set_busy(self, busy: bool) -> None:
        self.setVisible(busy)
        self._ticker.want(self, busy)

    def _tick(self) -> None:
        if self._ticker.wanted_by(self):
            self._angle = (self._angle - 45) % 360
            self.update()

    def paintEvent(self, event: QPaintEvent) -> None:  # noqa: N802 (Qt override)
        painter = QPainter(self)
        painter.setRenderHint(QPainter.RenderHint.Antialiasing)
        pen = QPen(self.palette().highlight().color(), 2.2)
        pen.setCapStyle(Qt.PenCapStyle.RoundCap)
        painter.setPen(pen)
        painter.drawArc(self.rect().adjusted(2, 2, -2, -2), self._angle * 16, 270 * 16)


DROPPED_SUFFIXES = (".sor", ".poly", ".txt", ".json", ".jsonl", *PART_SUFFIXES)
"""The files a drop on the window opens: equation files, reports and CAD parts."""

OPENABLE_FILTER = (
    "Equations, reports and CAD parts (*.txt *.sor *.poly *.json *.jsonl *.step *.stp *.iges *.igs *.brep)"
)
"""The Open dialog's first filter: everything sorgui opens, reports and parts included."""

_DROP_EVENTS = (QEvent.Type.DragEnter, QEvent.Type.DragMove, QEvent.Type.Drop)

DEFAULT_TIME_LIMIT = 60.0
"""The window's time limit of one analysis, in seconds."""


EQUATION_LABEL = "<b>f(x, y, z) = 0</b>"
PARAMETRIZATION_LABEL = "<b>x, y, z: a rational map</b>"


def input_label_text(text: str) -> str:
    """The heading over the editor: the equation ``f(x, y, z) = 0``, or the rational map the text
    has the form of (:func:`~sorgui.engine.parsing.is_parametrization`, cheap on every keystroke)."""
    return PARAMETRIZATION_LABEL if is_parametrization(text) else EQUATION_LABEL


def parse_tolerance(text: str) -> float | None | bool:
    """``None`` for ``auto`` (or nothing), the tolerance for a number strictly between 0 and 1,
    ``False`` for anything else."""
    word = text.strip().lower()
    if word in ("", "auto"):
        return None
    try:
        value = float(word)
    except ValueError:
        return False
    return value if 0.0 < value < 1.0 else False


class MainWindow(QMainWindow):
    """sorgui's window. ``prestart_worker`` keeps a warm worker process ready (off in tests
    that never analyse). :attr:`result_shown` is emitted once a result is on screen (results
    pane and scene), with the :class:`~sorgui.session.job.JobResult`."""

    result_shown = Signal(object)

    def __init__(
        self, settings: Settings | None = None, prestart_worker: bool = True, worker: AnalysisWorker | None = None
    ) -> None:
        super().__init__()
        self.settings = settings or Settings(self)
        if worker is None:
            worker = AnalysisWorker(prestart=prestart_worker)
        worker.setParent(self)
        self.worker = worker
        self.session = Session(runner=self.worker)
        self._discarded = False
        """Whether the last unsaved-changes question was answered Discard."""
        self.time_limit = self.settings.time_limit or DEFAULT_TIME_LIMIT
        """Seconds for each whole analysis (Analysis → Time Limit…, ``--timeout`` of the command line)."""
        self.tolerance = self.settings.tolerance
        """The relative tolerance of rounded input; ``None``: from the printed digits (``--tolerance``)."""
        """Seconds for each whole analysis (the stages not finished by then are shown as such)."""
        self.worker.message.connect(self.session.handle)
        self.cad_export = BackgroundExport(self)
        self.cad_export.written.connect(self._cad_written)
        self.cad_export.failed.connect(self._cad_failed)
        self.report_reader = ReportReader(self)
        self.report_reader.read.connect(self.show_report)
        self.report_reader.refused.connect(self._report_refused)
        self.editor = EquationEditor(self)
        self.typesetter = Typesetter(self, start=False)
        self.results = ResultsPane(self, self.typesetter)
        self.ticker = Ticker(self)
        self._pick_message = ""
        self.run_panel = RunPanel(self, self.ticker)
        self.viewport = Viewport(self)
        self.help_dialog: HelpDialog | None = None
        self._file: str | None = None
        self._report: str | None = None
        """The report shown (File → Open of a ``.json``), when the editor holds its equation."""
        self._report_line: int | None = None
        """The input line of the batch result being read or shown (File → Open of a ``.jsonl``)."""
        self._zoom = 1.0

        self.input_label = QLabel(EQUATION_LABEL)
        """What the editor holds: an equation, or a parametrization (:func:`input_label_text`)."""
        self.analyze_button = QPushButton("Analyze")
        self.analyze_button.setObjectName("analyzeButton")
        self.analyze_button.setDefault(True)
        self.analyze_button.setToolTip("Analyse the equation (Ctrl+Return)")
        self.cancel_button = QPushButton("Cancel")
        self.cancel_button.setObjectName("cancelButton")
        self.cancel_button.setToolTip("Stop the running analysis (Esc)")
        self.cancel_button.setEnabled(False)
        self._build_layout()
        self._build_actions()
        self._build_status_bar()
        self.view = SessionView(
            self.session, self.editor, self.run_panel, self.results, self.viewport, self.stage_label
        )
        self.view.shown.connect(self.result_shown)
        self.viewport.software_guess = self.settings.software_rendering is not False
        camera = self.settings.camera
        if camera is not None:
            self.view.restore_camera = (camera[0], CameraState.from_dict(camera[1]))

        self.analyze_button.clicked.connect(self.analyze)
        self.cancel_button.clicked.connect(self.cancel)
        self.editor.text_changed.connect(self._on_text_change)
        self.editor.validity_changed.connect(self._on_validity_change)
        self.worker.busy_changed.connect(self._on_busy_change)
        self.viewport.radius_requested.connect(self._on_radius_change)
        self.viewport.picked.connect(self._show_pick)
        self.viewport.pick_cleared.connect(self._clear_pick_message)
        # Ctrl+wheel over the results; files dropped on the widgets that take drops themselves
        # (the editor would paste them as text, the render window read them as meshes, a spin
        # box take their names). Not one filter on the whole application: a Python call for
        # every event of every widget, which also crashed PySide6 when it raised while Qt made
        # a child widget.
        self.results.viewport().installEventFilter(self)
        for widget in self.findChildren(QWidget):
            if widget.acceptDrops():
                widget.installEventFilter(self)
        self.viewport.filter_drops(self)  # and its render window, made later
        self.setAcceptDrops(True)
        self._restore_layout()
        self._update_title()

    # --- layout ---

    def _build_layout(self) -> None:
        buttons = QHBoxLayout()
        buttons.addWidget(self.input_label)
        buttons.addStretch(1)
        buttons.addWidget(self.cancel_button)
        buttons.addWidget(self.analyze_button)
        top = QWidget()
        top_layout = QVBoxLayout(top)
        top_layout.setContentsMargins(8, 8, 8, 4)
        top_layout.addLayout(buttons)
        top_layout.addWidget(self.editor)
        bottom = QWidget()
        bottom_layout = QVBoxLayout(bottom)
        bottom_layout.setContentsMargins(0, 0, 0, 0)
        bottom_layout.setSpacing(0)
        bottom_layout.addWidget(self.run_panel)
        bottom_layout.addWidget(self.results, 1)
        top.setMinimumHeight(110)
        bottom.setMinimumSize(300, 200)
        self.viewport.setMinimumSize(300, 260)
        self.left_splitter = QSplitter(Qt.Orientation.Vertical)
        self.left_splitter.addWidget(top)
        self.left_splitter.addWidget(bottom)
        self.left_splitter.setChildrenCollapsible(False)
        self.left_splitter.setStretchFactor(1, 1)
        self.left_splitter.setSizes([190, 610])
        self.splitter = QSplitter(Qt.Orientation.Horizontal)
        self.splitter.addWidget(self.left_splitter)
        self.splitter.addWidget(self.viewport)
        self.splitter.setStretchFactor(1, 1)
        self.splitter.setSizes([560, 840])
        self.splitter.setChildrenCollapsible(False)
        self.setCentralWidget(self.splitter)
        self.setMinimumSize(*MINIMUM_SIZE)
        self.resize(*_initial_size(self.screen().availableGeometry().size()))
        # Tab from the equation to the button that runs it (it sits just above), then Cancel,
        # then the results: Qt's order of creation put Analyze last, after the 3D view.
        QWidget.setTabOrder(self.editor.text_edit, self.analyze_button)
        QWidget.setTabOrder(self.analyze_button, self.cancel_button)
        QWidget.setTabOrder(self.cancel_button, self.results)

    def _build_actions(self) -> None:
        menu = self.menuBar()
        file_menu = menu.addMenu("&File")
        self.new_action = self._action(file_menu, "&New", self._new_document, QKeySequence.StandardKey.New)
        self.open_action = self._action(file_menu, "&Open…", self._open_file, QKeySequence.StandardKey.Open)
        self.recent_menu = RecentFilesMenu(self.settings, self)
        self.recent_menu.file_chosen.connect(self._open_recent)
        file_menu.addMenu(self.recent_menu)
        self.save_action = self._action(file_menu, "&Save", self._save, QKeySequence.StandardKey.Save)
        self.save_as_action = self._action(file_menu, "Save &As…", self._save_as, QKeySequence.StandardKey.SaveAs)
        file_menu.addSeparator()
        self.copy_report_action = self._action(file_menu, "&Copy Report", self._copy_report, "Ctrl+Shift+C")
        self.export_action = self._action(file_menu, "&Export Results…", self._export_results, "Ctrl+E")
        self.cad_menu = file_menu.addMenu("Export &CAD File")
        self.cad_actions = {
            suffix: self._action(self.cad_menu, f"{name} ({suffix})…", partial(self._export_results, suffix))
            for suffix, name in CAD_CHOICES
        }
        self.screenshot_action = self._action(file_menu, "Save Screens&hot…", self._save_screenshot, "Ctrl+Shift+P")
        file_menu.addSeparator()
        self._action(file_menu, "&Quit", self.close, QKeySequence.StandardKey.Quit)

        analysis_menu = menu.addMenu("&Analysis")
        self.analyze_action = self._action(analysis_menu, "&Analyze", self.analyze, "Ctrl+Return")
        self.analyze_action.setShortcuts([QKeySequence("Ctrl+Return"), QKeySequence("Ctrl+Enter")])
        self.cancel_action = self._action(analysis_menu, "&Cancel", self.cancel, "Esc")
        self.cancel_action.setEnabled(False)
        analysis_menu.addSeparator()
        self._action(analysis_menu, "&Time Limit…", self.ask_time_limit)
        self._action(analysis_menu, "&Rounding Tolerance…", self.ask_tolerance)

        self.examples_menu = ExamplesMenu(self)
        self.examples_menu.example_chosen.connect(self._load_example)
        menu.addMenu(self.examples_menu)

        view_menu = menu.addMenu("&View")
        for name in ("along", "across", "x", "y", "z", "reset", None, "parallel", "wireframe", "clip"):
            if name is None:
                view_menu.addSeparator()
            else:
                view_menu.addAction(self.viewport.view_actions[name])
        view_menu.addSeparator()
        self.box_action = self._action(view_menu, "Cut to a &Box…", self.choose_box)
        self.ball_action = self._action(view_menu, "&Whole Ball", self.whole_ball)
        view_menu.addSeparator()
        self.zoom_in_action = self._action(
            view_menu, "Zoom &In Formulas", lambda: self.zoom_formulas(+1), QKeySequence.StandardKey.ZoomIn
        )
        self.zoom_in_action.setShortcuts([QKeySequence("Ctrl++"), QKeySequence("Ctrl+=")])
        self.zoom_out_action = self._action(
            view_menu, "Zoom &Out Formulas", lambda: self.zoom_formulas(-1), QKeySequence.StandardKey.ZoomOut
        )
        self.zoom_reset_action = self._action(view_menu, "&Normal Size", lambda: self.zoom_formulas(0), "Ctrl+0")

        help_menu = menu.addMenu("&Help")
        self.help_actions = {
            topic: self._action(help_menu, title, partial(self.show_help, topic))
            for topic, (title, _page) in TOPICS.items()
        }
        self.help_actions["syntax"].setShortcut(QKeySequence.StandardKey.HelpContents)
        help_menu.addSeparator()
        self._action(help_menu, "&About sorgui", self._show_about)

    def _action(
        self,
        menu: QMenu,
        text: str,
        slot: Callable[[], object],
        shortcut: QKeySequence | QKeySequence.StandardKey | str | None = None,
    ) -> QAction:
        """A menu entry that calls ``slot`` (with its keyboard shortcut, if any)."""
        action = QAction(text, self)
        if shortcut is not None:
            action.setShortcut(QKeySequence(shortcut))
        action.triggered.connect(lambda _checked=False: slot())
        menu.addAction(action)
        return action

    def _build_status_bar(self) -> None:
        self.stage_label = ElidedLabel("Ready")  # a long message ends in "…", whole in its tooltip
        self.stage_label.setObjectName("stageLabel")
        self.stage_label.setMinimumWidth(50)
        self.busy_indicator = BusyIndicator(self.ticker)
        self.busy_indicator.set_busy(False)
        self.statusBar().addWidget(self.stage_label, 1)
        # Permanent (at the right): a normal widget shown again while a temporary message is up
        # was drawn over the message's first letter.
        self.statusBar().addPermanentWidget(self.busy_indicator)

    # --- public API ---

    def set_equation(self, text: str, file: str | None = None) -> None:
        """Put ``text`` into the editor as a new document (``file``: where it came from, or
        ``None``): it starts a fresh undo history, so Undo never brings back another document."""
        self.editor.set_text(text)
        self.editor.text_edit.document().clearUndoRedoStacks()
        self._file = file
        self._report = None
        self.setWindowModified(False)
        self._update_title()

    def load_example(self, name: str) -> None:
        """Load the bundled example ``name`` and analyse it."""
        self.set_equation(example_text(name))
        self.analyze()

    def confirm_discard(self) -> bool:
        """Whether the typed text may be replaced: asks to save it first if it was changed.

        ``True`` after Save (and a successful save) or Discard, ``False`` after Cancel.
        """
        if not self.isWindowModified() or not self.editor.text().strip():
            return True
        name = Path(self._file).name if self._file else "the typed equation"
        answer = self.ask_to_save(name)
        if answer == QMessageBox.StandardButton.Save:
            self._save()
            return not self.isWindowModified()
        self._discarded = answer == QMessageBox.StandardButton.Discard
        return self._discarded

    def ask_to_save(self, name: str) -> QMessageBox.StandardButton:
        """The unsaved-changes question (Save, Discard or Cancel)."""
        buttons = (
            QMessageBox.StandardButton.Save | QMessageBox.StandardButton.Discard | QMessageBox.StandardButton.Cancel
        )
        return QMessageBox.question(
            self, "Unsaved changes", f"Save the changes to {name}?", buttons, QMessageBox.StandardButton.Save
        )

    def new_equation(self) -> bool:
        """An empty editor (after asking about unsaved changes)."""
        if not self.confirm_discard():
            return False
        self.set_equation("")
        return True

    def zoom_formulas(self, step: int) -> None:
        """Zoom the results' text and formulas one step in (+1), out (-1) or back to normal (0)."""
        if step == 0:
            zoom = 1.0
        else:
            index = min(range(len(ZOOM_STEPS)), key=lambda i: abs(ZOOM_STEPS[i] - self._zoom)) + step
            zoom = ZOOM_STEPS[max(0, min(len(ZOOM_STEPS) - 1, index))]
        if zoom == self._zoom:
            return
        self._zoom = zoom
        self.results.set_zoom(zoom)
        self.view.refresh_pane()
        self.statusBar().showMessage(f"Formulas at {zoom:.0%}", 2000)

    @property
    def zoom(self) -> float:
        return self._zoom

    def show_help(self, topic: str) -> None:
        """Open the Help window on ``topic`` (a key of :data:`sorgui.gui.help.TOPICS`)."""
        if self.help_dialog is None:
            self.help_dialog = HelpDialog(self)
        self.help_dialog.show_topic(topic)

    def load_startup_equation(self, path: str | None) -> None:
        """What the window shows first: ``path``, else the last session's text, else Example 1."""
        if path is not None:
            self.open_file(path)
            return
        text = self.settings.equation
        if text:
            self.set_equation(text, self.settings.current_file)
            self.setWindowModified(False)
            self.analyze()
        else:
            self.load_example(DEFAULT_EXAMPLE)

    def open_file(self, path: str) -> bool:
        """Read an equation file into the editor and analyse it (a ``.json`` report is shown as
        saved, see :meth:`open_report`; a CAD part in a window of its own, :mod:`sorgui.gui.part_view`)."""
        if Path(path).suffix.lower() in PART_SUFFIXES:
            from sorgui.gui.part_view import open_part

            open_part(self, path)
            self.settings.add_recent_file(path)
            return True
        if is_report_path(path):
            return self.open_report(path)
        try:
            text = read_equation(path)
        except EquationFileError as exc:
            if not Path(path).exists():
                self.settings.remove_recent_file(path)
            self._show_error("Cannot open file", str(exc))
            return False
        self.set_equation(text, str(Path(path).resolve()))
        self.settings.add_recent_file(path)
        self.analyze()
        return True

    def open_report(self, path: str, line: int | None = None) -> bool:
        """Read the JSON report ``path`` and check its claims in a process of its own
        (:mod:`sorgui.gui.report_reader`; the window stays responsive), then show it with
        :meth:`show_report`, or say in one line why not. A batch's results file (``.jsonl``)
        gives the report of its input ``line``, asked for when not given (:meth:`ask_result_line`).
        ``True``: the reading has started."""
        if line is None and is_results_path(path):
            line = self.ask_result_line(path)
            if line is None:
                return False
        self._report_line = line
        self.report_reader.start(path, timeout=self.time_limit, line=line)
        which = "" if line is None else f", input line {line},"
        self.statusBar().showMessage(f"Reading the report {Path(path).name}{which} and checking its claims…")
        return True

    def ask_result_line(self, path: str) -> int | None:
        """The input line whose result to show from the batch's results file ``path`` (``None``: cancelled)."""
        line, ok = QInputDialog.getInt(
            self,
            "Open a result of a batch",
            f"{Path(path).name} holds one result per line of the batch's input.\nShow the result of input line:",
            1,
            1,
            2**31 - 1,
        )
        return line if ok else None

    def _report_refused(self, _path: str, message: str) -> None:
        self.statusBar().clearMessage()
        self._show_error("Cannot open report", message)

    def show_report(self, path: str, analysis: Analysis, line: int | None = None) -> None:
        """Show ``analysis``, read from the report ``path`` (the result of input ``line`` of a
        batch's results file, when given; else the line File → Open asked for), without
        analysing it again (only its scene and formulas are drawn)."""
        self.set_equation(analysis.input)
        self._report = path
        if line is not None:
            self._report_line = line
        self._update_title()
        self.settings.add_recent_file(path)
        self.session.analyze(analysis.input, analysis=analysis, resolution=self.viewport.mesh_resolution())
        self.statusBar().showMessage(f"Report {Path(path).name}: shown as saved, not analysed again", 6000)

    def save_file(self, path: str) -> bool:
        """Write the editor's text to ``path``."""
        try:
            write_equation(path, self.editor.text())
        except EquationFileError as exc:
            self._show_error("Cannot save file", str(exc))
            return False
        self._file = str(Path(path).resolve())
        self.settings.add_recent_file(path)
        self.setWindowModified(False)
        self._update_title()
        self.statusBar().showMessage(f"Saved {path}", 4000)
        return True

    def analyze(self) -> bool:
        """Validate the equation and, if it is a polynomial, analyse it in the worker (a running
        analysis is superseded, and the status bar says so)."""
        if self.editor.check() is False:
            error = self.editor.error
            self._show_invalid(str(error) if error is not None else "The editor is empty.")
            return False
        superseded = self.worker.is_busy
        if self.report_reader.busy:  # this equation replaces a report still being read
            self.report_reader.cancel()
            self.statusBar().clearMessage()  # "Reading the report …"
        self.session.analyze(
            self.editor.text(),
            resolution=self.viewport.mesh_resolution(),
            singular_timeout=self.time_limit,
            tolerance=self.tolerance,
        )
        if superseded:
            self.statusBar().showMessage("The running analysis was stopped: this one replaces it", 5000)
        return True

    def cancel(self) -> None:
        """Stop the running analysis (the process is killed if it does not stop at once)."""
        if self.worker.is_busy:
            self.stage_label.setText("Cancelling…")
            self.session.cancel()

    def save_screenshots(self, window_png: str | Path, viewport_png: str | Path) -> None:
        """Save the whole window and the render window as PNG images."""
        self.grab().save(str(window_png))
        self.viewport.screenshot(viewport_png)

    # --- handlers ---

    def _on_text_change(self) -> None:
        self.setWindowModified(True)
        self.input_label.setText(input_label_text(self.editor.text()))
        self.session.set_equation(self.editor.text())

    def _on_validity_change(self, valid: object) -> None:
        self.analyze_button.setEnabled(valid is not False and bool(self.editor.text().strip()))

    def _on_busy_change(self, busy: bool) -> None:
        self.cancel_button.setEnabled(busy)
        self.cancel_action.setEnabled(busy)
        self.busy_indicator.set_busy(busy)
        self.viewport.radius_box.setEnabled(not busy and self.session.can_redo)

    def _show_invalid(self, message: str) -> None:
        heading = invalid_heading(message)
        self.results.show_message(heading, message, "error")
        self.run_panel.show_run(None)  # the previous equation's stages are not this one's
        self.run_panel.set_nearest_available(False)  # nor its nearest exact surface
        self.run_panel.set_notice("error", INVALID_NOTICE)
        self.viewport.clear(caption=no_surface_caption(message))
        self.stage_label.setText("Fix the equation to analyse it")

    def choose_box(self) -> None:
        """Ask for the box the view, the meshes and the CAD files are cut to (View → Cut to a Box)."""
        scene = self.viewport.scene
        if scene is None or self.worker.is_busy:
            self.statusBar().showMessage("A box can be chosen once the surface is drawn", 4000)
            return
        c, r = scene.region.center, scene.region.radius
        start = scene.box.bounds if scene.box is not None else tuple(v for k in range(3) for v in (c[k] - r, c[k] + r))
        dialog = BoxDialog(start, self)
        if dialog.exec() == QDialog.DialogCode.Accepted:
            self.cut_to_box(dialog.bounds())

    def cut_to_box(self, bounds: tuple[float, float, float, float, float, float]) -> bool:
        """Rebuild the scene cut to ``bounds`` (no new analysis); ``False`` if it cannot be now."""
        return self.session.remesh(resolution=self.viewport.mesh_resolution(), box=bounds)

    def whole_ball(self) -> bool:
        """Draw the whole automatic ball again (View → Whole Ball)."""
        return self.session.remesh(resolution=self.viewport.mesh_resolution())

    def _on_radius_change(self, radius: float) -> None:
        if not self.worker.is_busy:
            self.session.remesh(radius if radius > 0 else None, self.viewport.mesh_resolution())  # 0: automatic

    def _finished_analysis(self) -> Analysis | None:
        """The analysis of the finished current run (the one shown), if any."""
        run = self.session.run
        return run.analysis if run is not None and run.outcome == "finished" else None

    def _show_pick(self, info: PickInfo) -> None:
        self._pick_message = info.summary()
        self.statusBar().showMessage(self._pick_message, 15000)

    def _clear_pick_message(self) -> None:
        """The picked point is gone (a new scene): so is its line in the status bar."""
        if self._pick_message and self.statusBar().currentMessage() == self._pick_message:
            self.statusBar().clearMessage()
        self._pick_message = ""

    def _load_example(self, title: str, text: str) -> None:
        if not self.confirm_discard():
            return
        self.set_equation(text)
        self.statusBar().showMessage(f"Example: {title}", 4000)
        self.analyze()

    def _open_file(self) -> None:
        if not self.confirm_discard():
            return
        start = str(Path(self._file).parent) if self._file else ""
        path, _ = QFileDialog.getOpenFileName(
            self, "Open equation or report", start, f"{OPENABLE_FILTER};;{EQUATION_FILTER};;{REPORT_FILTER}"
        )
        if path:
            self.open_file(path)

    def _open_recent(self, path: str) -> None:
        if self.confirm_discard():
            self.open_file(path)

    def _new_document(self) -> None:
        self.new_equation()

    def _save(self) -> None:
        if self._file is None:
            self._save_as()
        else:
            self.save_file(self._file)

    def _save_as(self) -> None:
        path, _ = QFileDialog.getSaveFileName(self, "Save equation", self._file or "equation.txt", EQUATION_FILTER)
        if path:
            self.save_file(path)

    def _copy_report(self) -> None:
        QGuiApplication.clipboard().setText(self.results.plain_text())
        self.statusBar().showMessage("Report copied to the clipboard", 3000)

    def ask_time_limit(self) -> None:
        """Analysis → Time Limit…: the seconds one analysis may take (kept for the next start)."""
        seconds, ok = QInputDialog.getDouble(
            self,
            "Time limit",
            "Seconds for one analysis (the stages not finished by then are shown as such):",
            self.time_limit,
            1.0,
            86_400.0,
            0,
        )
        if ok:
            self.time_limit = seconds
            self.settings.time_limit = seconds
            self.statusBar().showMessage(f"Time limit: {seconds:g} s from the next analysis", 5000)

    def ask_tolerance(self) -> None:
        """Analysis → Rounding Tolerance…: ``auto`` (from the printed digits) or a relative tolerance."""
        current = "auto" if self.tolerance is None else f"{self.tolerance:g}"
        text, ok = QInputDialog.getText(
            self,
            "Rounding tolerance",
            "Relative tolerance for rounded input: 'auto' reads it off the printed digits, "
            "or a number between 0 and 1 such as 1e-8:",
            text=current,
        )
        if not ok:
            return
        tolerance = parse_tolerance(text)
        if tolerance is False:
            self._show_error("Not a tolerance", f"{text!r} is neither 'auto' nor a number between 0 and 1.")
            return
        self.tolerance = tolerance
        self.settings.tolerance = tolerance
        self.statusBar().showMessage(f"Rounding tolerance: {text.strip() or 'auto'} from the next analysis", 5000)

    def confirm_replace(self, side: Path) -> bool:
        """Whether the picture a Markdown report writes beside itself may replace ``side``, which
        exists (the file dialog asked only about the report)."""
        answer = QMessageBox.question(
            self,
            "Replace the picture?",
            f"The Markdown report writes its picture as {side.name}, which exists already. Replace it?",
            QMessageBox.StandardButton.Yes | QMessageBox.StandardButton.Cancel,
            QMessageBox.StandardButton.Cancel,
        )
        return answer == QMessageBox.StandardButton.Yes

    def save_picture(self, path: str | Path, width: int | None = None, transparent: bool = False) -> Path:
        """Save the 3D view as a PNG ``width`` pixels wide (default: as on screen), optionally
        with a transparent background (written atomically)."""
        return atomic_write_bytes(path, png_bytes(viewport_image(self.viewport, width, transparent)))

    def ask_export_path(self, suffix: str) -> str | None:
        """The Export dialog, on the format of ``suffix``: choosing another file type there
        changes the name's suffix with it (typing a suffix of one's own also chooses the format)."""
        dialog = QFileDialog(self, "Export results")
        dialog.setAcceptMode(QFileDialog.AcceptMode.AcceptSave)
        dialog.setNameFilters(export_filters().split(";;"))
        dialog.selectNameFilter(filter_of_suffix(suffix))
        stem = Path(self._file).stem if self._file else "sorgui-results"
        dialog.selectFile(stem + suffix)

        def retype(chosen: str) -> None:
            name = Path(next(iter(dialog.selectedFiles()), "") or stem).name
            dialog.selectFile(without_export_suffix(name) + suffix_of_filter(chosen))

        dialog.filterSelected.connect(retype)
        if dialog.exec() != QDialog.DialogCode.Accepted or not dialog.selectedFiles():
            return None
        return with_suffix_of(dialog.selectedFiles()[0], dialog.selectedNameFilter())

    def _export_results(self, suffix: str = ".json") -> None:
        if self._finished_analysis() is None:
            self.statusBar().showMessage("Analyse an equation first", 4000)
            return
        path = self.ask_export_path(suffix)
        if not path:
            return
        picture = Path(path).with_suffix(".png")
        if Path(path).suffix.lower() == ".md" and picture.exists() and not self.confirm_replace(picture):
            return
        self.export_in_background(path)

    def export_in_background(self, path: str | Path) -> None:
        """Write the shown analysis to ``path`` in a process of its own, killed at the time limit:
        every format, since any may take seconds (a CAD file; the LaTeX of a degree-60 equation
        took 25 s of sympy's printing, the window frozen meanwhile when it was written here)."""
        analysis = self._finished_analysis()
        if analysis is None or self.cad_export.busy:
            self.statusBar().showMessage("A file is still being written" if analysis else "Nothing to export", 4000)
            return
        try:
            suffix = format_of(path).suffix
        except ValueError as exc:  # a name typed in the dialog with a suffix of no format
            self._show_error("Export failed", str(exc))
            return
        picture = None
        if suffix in (".md", ".html", ".png"):
            picture = png_bytes(viewport_image(self.viewport, REPORT_PICTURE_WIDTH, inspection=False))
        self.cad_export.start(analysis, path, self.viewport.scene, picture, timeout=self.time_limit)
        self.statusBar().showMessage(f"Writing {path}…")

    def _cad_written(self, path: Path, holds: str) -> None:
        self.statusBar().showMessage(f"Exported {path}: {holds}" if holds else f"Exported {path}", 8000)

    def _cad_failed(self, reason: str) -> None:
        self.statusBar().clearMessage()
        self._show_error("Export failed", reason)

    def _save_screenshot(self) -> None:
        dialog = PictureDialog(int(self.viewport.plotter.window_size[0]), self)
        if dialog.exec() != PictureDialog.DialogCode.Accepted:
            return
        path, _ = QFileDialog.getSaveFileName(self, "Save picture", "sorgui.png", "PNG images (*.png)")
        if not path:
            return
        try:
            self.save_picture(path, dialog.width_box.value(), dialog.transparent_box.isChecked())
        except OSError as exc:
            self._show_error("Cannot save the picture", f"cannot write {path}: {exc.strerror or exc}")
            return
        self.statusBar().showMessage(f"Saved {path}", 4000)

    def _show_about(self) -> None:
        QMessageBox.about(
            self,
            "About sorgui",
            f"<b>sorgui {__version__}</b><p>Decides exactly whether an algebraic surface "
            "f(x, y, z) = 0 is a surface of revolution, after J. Vršek and M. Lávička, "
            "<i>Determining surfaces of revolution from their implicit equations</i>.</p>"
            f"<p>Settings: {self.settings.file_name}</p>",
        )

    # --- helpers ---

    def _show_error(self, title: str, message: str) -> None:
        self.statusBar().showMessage(message, 8000)
        QMessageBox.warning(self, title, message)

    def _update_title(self) -> None:
        """The window's title: the equation file, the report shown, or Untitled."""
        report, line = self._report, "" if self._report_line is None else f", line {self._report_line}"
        name = f"{Path(report).name}{line} (report)" if report else "Untitled"
        name = Path(self._file).name if self._file else name
        self.setWindowTitle(f"{name}[*] — sorgui")

    def _restore_layout(self) -> None:
        for name, widget in (("window", self), ("splitter", self.splitter), ("left", self.left_splitter)):
            state = self.settings.layout(name)
            if state is None:
                continue
            if widget is self:
                self.restoreGeometry(state)
            else:
                widget.restoreState(state)

    def _save_layout(self) -> None:
        self.settings.save_layout("window", self.saveGeometry())
        self.settings.save_layout("splitter", self.splitter.saveState())
        self.settings.save_layout("left", self.left_splitter.saveState())

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:  # noqa: N802 (Qt override)
        """Ctrl+wheel over the results zooms the formulas; a file dropped anywhere on the window
        (the editor, the 3D view) is opened, never pasted as ``file://`` text or handed to the
        3D view."""
        if (
            event.type() in _DROP_EVENTS
            and isinstance(event, QDropEvent)
            and isinstance(watched, QWidget)
            and watched.window() is self
        ):
            return self._open_dropped(event)
        if (
            isinstance(event, QWheelEvent)
            and watched is self.results.viewport()
            and event.modifiers() & Qt.KeyboardModifier.ControlModifier
        ):
            delta = event.angleDelta().y()
            if delta:
                self.zoom_formulas(1 if delta > 0 else -1)
            return True
        return super().eventFilter(watched, event)

    def dragEnterEvent(self, event: QDragEnterEvent) -> None:  # noqa: N802 (Qt override)
        self._open_dropped(event)

    def dragMoveEvent(self, event: QDragMoveEvent) -> None:  # noqa: N802 (Qt override)
        self._open_dropped(event)

    def dropEvent(self, event: QDropEvent) -> None:  # noqa: N802 (Qt override)
        """A file dropped where no widget takes drops (the status bar, the stage list, …)."""
        self._open_dropped(event)

    def _open_dropped(self, event: QDropEvent) -> bool:
        """Take a drag of files: an equation file (``.sor``, ``.poly``, ``.txt``) or a report
        (``.json``) is opened; anything else is refused with a word in the status bar."""
        mime = event.mimeData()
        if not mime.hasUrls():
            return False
        paths = [url.toLocalFile() for url in mime.urls() if url.isLocalFile()]
        openable = [p for p in paths if Path(p).suffix.lower() in DROPPED_SUFFIXES]
        if event.type() != QEvent.Type.Drop:
            if openable:
                event.acceptProposedAction()
            else:
                event.ignore()
            return True
        if not openable:
            self.statusBar().showMessage(
                "sorgui opens equation files (.sor, .poly, .txt), reports (.json), batch results (.jsonl) "
                "and CAD parts",
                6000,
            )
            event.ignore()
            return True
        event.acceptProposedAction()
        if self.confirm_discard():
            self.open_file(openable[0])
        return True

    def _kept_text(self) -> str:
        """The text the next start restores: the editor's, unless the user chose Discard (then the
        saved file's text, or nothing: the next start shows Example 1)."""
        if not self._discarded:
            return self.editor.text()
        if self._file:
            try:
                return read_equation(self._file)
            except EquationFileError:
                return ""
        return ""

    def closeEvent(self, event: QCloseEvent) -> None:  # noqa: N802 (Qt override)
        """Ask about unsaved changes; then remember the text, layout and camera, kill the worker
        processes and release the render window."""
        self._discarded = False
        if not self.confirm_discard():
            event.ignore()
            return
        self._remember()
        self.view.close()
        self.worker.shutdown()
        self.typesetter.shutdown()
        self.cad_export.shutdown()
        self.report_reader.shutdown()
        self.viewport.close_plotter()
        super().closeEvent(event)

    def end_at_once(self) -> None:
        """A signal ends sorgui (``SIGTERM``, a logout): the window goes at once, the typed text,
        the layout and the camera are kept as on Quit, the worker processes are killed without
        waiting for them. Nothing else is released: the process exits right after, without the
        interpreter's teardown (:func:`sorgui.cli.main`), so no VTK object outlives its window."""
        self.hide()
        self._discarded = False
        self._remember()
        self.view.close()
        self.worker.shutdown(wait=0.0)
        self.typesetter.shutdown(wait=0.0)
        self.cad_export.shutdown()
        self.report_reader.shutdown()

    def _remember(self) -> None:
        """Keep what the next start restores: the text, the file, the layout, the camera."""
        self.settings.equation = self._kept_text()
        self.settings.current_file = self._file
        if self.viewport.detected_software is not None:
            self.settings.software_rendering = self.viewport.detected_software
        run = self.session.run
        camera = self.viewport.camera_state() if run is not None and self.viewport.scene is not None else None
        if run is not None and camera is not None and camera.framed:
            self.settings.set_camera(run.text, camera.to_dict())
        else:
            self.settings.forget_camera()
        self._save_layout()
        self.settings.sync()


PREFERRED_SIZE = (1400, 860)
"""The window's first size, where the screen has room for it."""


def _initial_size(available: QSize) -> tuple[int, int]:
    """:data:`PREFERRED_SIZE`, shrunk to 95% of the screen's available area (a 1280×720 laptop
    screen), never below :data:`MINIMUM_SIZE`."""
    width = max(MINIMUM_SIZE[0], min(PREFERRED_SIZE[0], int(0.95 * available.width())))
    height = max(MINIMUM_SIZE[1], min(PREFERRED_SIZE[1], int(0.95 * available.height())))
    return width, height
