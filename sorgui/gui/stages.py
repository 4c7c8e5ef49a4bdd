"""The run panel above the results: what is being analysed, how far it is, and whether the
results below belong to the equation in the editor.

It renders the :class:`~sorgui.session.model.Run` of the session: one line per stage with
its state and time (the running one with an elapsed-time counter), a determinate progress bar
over the stages, and a notice at the top for everything the user must not miss: results that
belong to the previous equation, an input error, a failed stage, a cancelled run. It also holds
the switch between the equation as typed and the nearest exact surface (rounded input).
"""

from __future__ import annotations

import html
import time

from PySide6.QtCore import QObject, QRectF, Qt, QTimer, Signal
from PySide6.QtGui import QPainter, QPaintEvent
from PySide6.QtWidgets import (
    QButtonGroup,
    QHBoxLayout,
    QLabel,
    QRadioButton,
    QVBoxLayout,
    QWidget,
)

from sorgui.session.model import Run, StageState

TICK_MS = 200
"""The elapsed-time counter of the running stage is redrawn this often."""


class Ticker(QObject):
    """One clock for the window's animations (the running stage's time, the status bar's spinner).

    Their repaints fall in the same turn of the event loop, so the window is composed once for
    all of them: each composition of a window with a 3D view costs 15-30 ms of the GUI thread in
    software OpenGL, and two clocks of their own composed it about 13 times a second (issue 30).
    The clock runs while at least one widget wants it.
    """

    tick = Signal()

    def __init__(self, parent: QObject | None = None, interval_ms: int = TICK_MS) -> None:
        super().__init__(parent)
        self._timer = QTimer(self)
        self._timer.setInterval(interval_ms)
        self._timer.timeout.connect(self.tick)
        self._users: set[int] = set()

    def want(self, user: object, on: bool) -> None:
        """Whether ``user`` needs the clock now."""
        if on:
            self._users.add(id(user))
        else:
            self._users.discard(id(user))
        if not self._users:
            self._timer.stop()
        elif not self._timer.isActive():
            self._timer.start()

    def wanted_by(self, user: object) -> bool:
        """Whether ``user`` said it needs the clock (and has not said otherwise since)."""
        return id(user) in self._users


SYMBOLS = {
    StageState.PENDING: ("○", "#90a4ae"),
    StageState.RUNNING: ("◔", "#1565c0"),
    StageState.DONE: ("✓", "#2e7d32"),
    StageState.FAILED: ("✗", "#c62828"),
    StageState.CANCELLED: ("⊘", "#8d6e63"),
    StageState.SKIPPED: ("–", "#b0bec5"),
    StageState.UNFINISHED: ("◌", "#e65100"),
}

NOTICE_STYLE = {
    "stale": "background: #fff8e1; color: #6d4c00; border: 1px solid #ffe082;",
    "error": "background: #fdecea; color: #b71c1c; border: 1px solid #ef9a9a;",
    "cancelled": "background: #efebe9; color: #4e342e; border: 1px solid #d7ccc8;",
    "limit": "background: #fff3e0; color: #8a3b00; border: 1px solid #ffcc80;",
    "report": "background: #eef2f7; color: #263238; border: 1px solid #cfd8dc;",
}


class StageBar(QWidget):
    """A determinate progress bar over the stages, "k of n stages".

    Painted like any widget, at the next paint event: ``QProgressBar.setValue`` repaints the
    window at once, which costs tens of milliseconds under software OpenGL.
    """

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self._value, self._maximum = 0, 1
        self.setFixedHeight(16)

    def setRange(self, minimum: int, maximum: int) -> None:  # noqa: N802 (QProgressBar's names)
        self._maximum = max(1, maximum - minimum)
        self.update()

    def setValue(self, value: int) -> None:  # noqa: N802
        self._value = value
        self.update()

    def value(self) -> int:
        return self._value

    def maximum(self) -> int:
        return self._maximum

    def text(self) -> str:
        return f"{self._value} of {self._maximum} stages"

    def paintEvent(self, event: QPaintEvent) -> None:  # noqa: N802 (Qt override)
        painter = QPainter(self)
        palette = self.palette()
        rect = QRectF(self.rect()).adjusted(0.5, 0.5, -0.5, -0.5)
        painter.setPen(palette.mid().color())
        painter.setBrush(palette.base())
        painter.drawRoundedRect(rect, 3, 3)
        done = QRectF(rect)
        done.setWidth(rect.width() * min(1.0, self._value / self._maximum))
        painter.setBrush(palette.highlight())
        painter.drawRoundedRect(done, 3, 3)
        painter.setPen(palette.text().color())
        painter.drawText(rect, Qt.AlignmentFlag.AlignCenter, self.text())


def seconds_text(seconds: float) -> str:
    """``"34 ms"``, ``"1.2 s"``: short enough for a stage line."""
    return f"{seconds * 1000:.0f} ms" if seconds < 1.0 else f"{seconds:.1f} s"


class RunPanel(QWidget):
    """The stages of the current run, its progress, a notice line and the view switch.

    :attr:`view_requested` carries ``"typed"`` or ``"nearest"`` when the user switches.
    """

    view_requested = Signal(str)

    def __init__(self, parent: QWidget | None = None, ticker: Ticker | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("runPanel")
        self._run: Run | None = None
        self.notice = QLabel(self)
        self.notice.setObjectName("runNotice")
        self.notice.setWordWrap(True)
        self.notice.setTextFormat(Qt.TextFormat.RichText)
        self.notice.setVisible(False)
        self.progress_bar = StageBar(self)
        self.progress_bar.setObjectName("stageProgress")
        self.stage_line = QLabel(self)
        self.stage_line.setObjectName("stageLine")
        self.stage_line.setWordWrap(True)
        self.stage_line.setTextFormat(Qt.TextFormat.RichText)
        self.stage_line.setToolTip(
            "The stages of the analysis as they finish: ✓ done, ◔ running, ○ pending, "
            "– not needed for this surface, ◌ not finished within the time limit, ⊘ cancelled, ✗ failed"
        )
        self.typed_button = QRadioButton("the equation as typed", self)
        self.typed_button.setObjectName("viewTyped")
        self.typed_button.setChecked(True)
        self.nearest_button = QRadioButton("the nearest exact surface", self)
        self.nearest_button.setObjectName("viewNearest")
        self.nearest_button.setToolTip(
            "The exact surface of revolution the rounded coefficients were meant to be: its own "
            "exact analysis (Table 1 row, parameterizations) and its picture"
        )
        group = QButtonGroup(self)
        group.addButton(self.typed_button)
        group.addButton(self.nearest_button)
        self.view_row = QWidget(self)
        row = QHBoxLayout(self.view_row)
        row.setContentsMargins(0, 0, 0, 0)
        row.addWidget(QLabel("Show:"))
        row.addWidget(self.typed_button)
        row.addWidget(self.nearest_button)
        row.addStretch(1)
        self.view_row.setVisible(False)
        self.typed_button.toggled.connect(self._show_chosen_view)

        layout = QVBoxLayout(self)
        layout.setContentsMargins(8, 2, 8, 2)
        layout.setSpacing(3)
        layout.addWidget(self.notice)
        layout.addWidget(self.progress_bar)
        layout.addWidget(self.stage_line)
        layout.addWidget(self.view_row)

        self.ticker = ticker or Ticker(self)
        """The clock of the running stage's time (the window's, shared with its spinner)."""
        self.ticker.tick.connect(self._tick)
        self.show_run(None)

    # --- public API ---

    def show_run(self, run: Run | None) -> None:
        """Show the stages of ``run`` (``None``: nothing analysed yet); while it runs, at the
        clock's next tick (a run reports each stage: a stage's every change composed the window)."""
        self._run = run
        if run is None or run.report:  # a report: nothing was analysed, the notice says so
            self.progress_bar.setVisible(False)
            self.stage_line.setText("")
            self.ticker.want(self, False)
            return
        if run.running and self.ticker.wanted_by(self):
            return  # the next tick shows it: one composition of the window for all the changes since the last
        self._show_progress(run)
        self.ticker.want(self, run.running)
        if not run.running:
            self.progress_bar.setVisible(False)

    def set_notice(self, kind: str | None, text: str = "") -> None:
        """Show a notice (``"stale"``, ``"error"``, ``"cancelled"``, ``"limit"``) or hide it (``None``)."""
        if kind is None:
            self.notice.setVisible(False)
            self.notice.setText("")
            return
        self.notice.setProperty("kind", kind)
        self.notice.setText(text)
        self.notice.setStyleSheet(f"QLabel {{ {NOTICE_STYLE[kind]} border-radius: 4px; padding: 4px 6px; }}")
        self.notice.setVisible(True)

    @property
    def notice_kind(self) -> str | None:
        return self.notice.property("kind") if self.notice.isVisible() else None

    def set_nearest_available(self, available: bool, view: str = "typed") -> None:
        """Offer the switch to the nearest exact surface (only when there is one)."""
        self.view_row.setVisible(available)
        self.typed_button.blockSignals(True)
        self.nearest_button.blockSignals(True)
        self.typed_button.setChecked(view == "typed")
        self.nearest_button.setChecked(view == "nearest")
        self.typed_button.blockSignals(False)
        self.nearest_button.blockSignals(False)

    # --- helpers ---

    def _stage_text(self, run: Run) -> str:
        now = time.monotonic()
        parts = []
        for stage in run.stage_list():
            symbol, color = SYMBOLS[stage.state]
            label = html.escape(stage.title)
            if stage.state is StageState.RUNNING:
                text = f"<b>{label}</b> {seconds_text(stage.elapsed(now))}…"
            elif stage.state is StageState.DONE or stage.note is not None:
                text = f"{label} {seconds_text(stage.seconds)}"
                if stage.note is not None:
                    text += f" <i>{html.escape(stage.note)}</i>"
            elif stage.state is StageState.UNFINISHED:
                text = f"{label} <i>not finished within {run.limit:g} s</i>"
            elif stage.state is StageState.PENDING and stage.seconds > 0:
                text = f"{label} {seconds_text(stage.seconds)} so far"
            else:
                text = f"{label} <i>{stage.state.value}</i>" if stage.state is not StageState.PENDING else label
            parts.append(f"<span style='color:{color}'>{symbol}</span>&nbsp;{text}")
        total = f"<span style='color:#546e7a'>total {seconds_text(run.elapsed())}</span>"
        return " · ".join(parts) + " · " + total

    def _show_progress(self, run: Run) -> None:
        self.progress_bar.setVisible(True)
        done, total = run.progress
        self.progress_bar.setRange(0, total)
        self.progress_bar.setValue(done)
        self.stage_line.setText(self._stage_text(run))

    def _tick(self) -> None:
        if self._run is not None and self.ticker.wanted_by(self):
            self._show_progress(self._run)

    def _show_chosen_view(self, typed: bool) -> None:
        self.view_requested.emit("typed" if typed else "nearest")
