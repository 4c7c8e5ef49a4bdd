"""Starting the desktop application: ``run_gui(path)`` is what ``sorgui [FILE]`` calls.

The ``QApplication`` gets sorgui's names (which also place its settings file), icon and a
consistent style; the window opens with ``FILE``, or else with the last session's equation, or
on a first start with the paper's Example 1, and analyses it at once.
"""

from __future__ import annotations

import contextlib
import faulthandler
import multiprocessing
import os
import signal
import socket
import sys
import threading
from importlib import resources
from typing import TYPE_CHECKING, cast

from PySide6.QtCore import QSocketNotifier, QTimer
from PySide6.QtGui import QIcon
from PySide6.QtWidgets import QApplication

from sorgui import __version__
from sorgui.gui.settings import APPLICATION, ORGANIZATION

if TYPE_CHECKING:
    from sorgui.engine.results import Analysis
    from sorgui.gui.main_window import MainWindow

ICON = "sorgui.svg"
"""The application icon, package data in ``sorgui/resources``."""


def application_icon() -> QIcon:
    """sorgui's icon (a profile curve revolving about its axis)."""
    return QIcon(str(resources.files("sorgui") / "resources" / ICON))


def create_application(argv: list[str] | None = None) -> QApplication:
    """The ``QApplication`` (the existing one, if any) with sorgui's names and icon."""
    existing = QApplication.instance()  # typed QCoreApplication; sorgui's is a QApplication
    if existing is not None:
        app = cast(QApplication, existing)
    else:
        if sys.platform.startswith("linux") and "QT_QPA_PLATFORM" not in os.environ:
            os.environ["QT_QPA_PLATFORM"] = "xcb"  # VTK renders through GLX, also under Wayland
        app = QApplication(list(argv if argv is not None else sys.argv))
    app.setOrganizationName(ORGANIZATION)
    app.setApplicationName(APPLICATION)
    app.setApplicationDisplayName("sorgui")
    app.setApplicationVersion(__version__)
    app.setDesktopFileName("org.sorgui.Sorgui")  # resources/org.sorgui.Sorgui.desktop: the launcher
    app.setWindowIcon(application_icon())
    if app.style().name().lower() not in ("fusion", "breeze"):
        app.setStyle("Fusion")
    return app


def open_main_window(path: str | None = None, report: Analysis | None = None, line: int | None = None) -> MainWindow:
    """Show the main window at once; once it is drawn, start analysing the startup equation
    (``path``, the last session's or Example 1), or show ``report``, the analysis of the report
    ``path`` read already (``sorgui open``; of its input ``line``, for a batch's results file),
    and then create the 3D view's render window.

    In that order the window appears before pyvista and VTK's rendering are imported (a second,
    on a thread), and the worker process analyses while they are. The worker process itself is
    started first of all, so that it loads the engine while the window loads Qt's widgets.
    """
    from sorgui.gui.worker import AnalysisWorker
    from sorgui.session.process import STARTUP_NICENESS

    worker = AnalysisWorker(first_niceness=STARTUP_NICENESS)
    from sorgui.gui.main_window import MainWindow

    window = MainWindow(worker=worker)
    window.show()

    def when_drawn() -> None:
        handle = window.windowHandle()
        if handle is not None and not handle.isExposed() and window.isVisible():
            QTimer.singleShot(10, when_drawn)
            return
        if report is not None and path is not None:
            window.show_report(path, report, line)
        else:
            window.load_startup_equation(path)
        window.viewport.start_rendering_soon()

    QTimer.singleShot(0, when_drawn)
    return window


ENDING_DEADLINE_S = 0.6
"""After an ending signal, the process exits this soon even if the event loop is busy (the
promise: window and process gone within a second)."""


def _exit_late(status: int) -> None:
    """The watchdog's end of sorgui: the worker processes killed first (they would die with it,
    but might first find their pipe closed and say so), what was printed flushed, then exit
    without any teardown."""
    from sorgui.session.child import kill_process_tree

    for child in multiprocessing.active_children():
        if child.pid is not None:
            with contextlib.suppress(OSError):
                kill_process_tree(child.pid)
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(OSError, ValueError, AttributeError):
            stream.flush()
    os._exit(status)


ENDING_SIGNALS = tuple(getattr(signal, name) for name in ("SIGTERM", "SIGHUP", "SIGINT") if hasattr(signal, name))


class SignalEnding:
    """``SIGTERM``, ``SIGHUP`` (a session's logout) and ``SIGINT`` close the window at once and
    cleanly: the typed text is kept for the next start (nothing is asked, nothing lost), the
    worker processes are killed, and the event loop ends with status ``128 + signal``.

    Installed before the window is built, so that a signal sent while sorgui starts (its worker
    process already running) is not met by the default action, which would end the window and
    leave the worker behind; until then the signals wait (:func:`sorgui.cli.signals_held`). The
    handler never raises: PySide6 runs Python code inside its C++ (it makes an enum the first
    time one is used), where an exception would be swallowed, and the signal with it. Qt's
    event loop runs in C++, where Python's signal handlers wait: the handler only writes the
    signal to a socket (``signal.set_wakeup_fd``) that a ``QSocketNotifier`` watches, and the
    window is closed from the event loop, never from inside another slot; a signal met before
    the loop runs is answered by :meth:`pending`. When the event loop cannot answer within
    :data:`ENDING_DEADLINE_S` (the window still loading its modules, or a long call on the GUI
    thread), the process exits from a watchdog thread: the worker processes die with it (they
    die with their parent), and nothing typed is lost that was not already lost to the busy
    window."""

    def __init__(self, app: QApplication) -> None:
        self.app = app
        self.window: MainWindow | None = None
        self.received: int | None = None
        self.notifier: QSocketNotifier | None = None
        try:
            self._sockets = socket.socketpair()
        except OSError:
            return
        reading, writing = self._sockets
        for end in self._sockets:
            end.setblocking(False)
        signal.set_wakeup_fd(writing.fileno(), warn_on_full_buffer=False)
        for signum in ENDING_SIGNALS:
            signal.signal(signum, self._remember)
        self.notifier = QSocketNotifier(reading.fileno(), QSocketNotifier.Type.Read, app)
        self.notifier.activated.connect(self._end_on_signal)

    def _remember(self, signum: int, _frame: object) -> None:
        if self.received is None:
            self.received = signum
            watchdog = threading.Timer(ENDING_DEADLINE_S, _exit_late, (128 + signum,))
            watchdog.daemon = True
            watchdog.start()

    def pending(self) -> int | None:
        """The exit status of a signal received while the window was being built (then closed)."""
        if self.received is None:
            return None
        self._end(self.received)
        return 128 + self.received

    def _end_on_signal(self) -> None:
        try:
            received = self._sockets[0].recv(64)
        except OSError:
            return
        ending = [n for n in received if n in ENDING_SIGNALS]
        if ending:
            self._end(ending[0])
            self.app.exit(128 + ending[0])

    def close(self) -> None:
        """Give the signals back to Python and release the notifier and its sockets, before the
        interpreter ends: Qt objects and Python handlers left to the interpreter's finalization
        can crash it (a fatal error with the GIL released)."""
        for signum in ENDING_SIGNALS:
            signal.signal(signum, signal.SIG_DFL if signum != signal.SIGINT else signal.default_int_handler)
        signal.set_wakeup_fd(-1)
        if self.notifier is not None:
            self.notifier.setEnabled(False)
            self.notifier.activated.disconnect(self._end_on_signal)
            self.notifier.deleteLater()
            self.notifier = None
        for end in getattr(self, "_sockets", ()):
            end.close()
        self.window = None

    def _end(self, signum: int) -> None:
        if self.notifier is not None:
            self.notifier.setEnabled(False)
        if self.window is not None:
            self.window.end_at_once()  # the text is kept in the settings: nothing to ask


def run_gui(path: str | None = None, report: Analysis | None = None, line: int | None = None) -> int:
    """Open the main window (with ``path``, if given: an equation file, a report or a CAD part;
    ``report``: the analysis of the report ``path``, read already, of input ``line`` of a
    batch's results file) and run the event loop; the exit status.

    A crash in C++ (Qt, VTK, OpenGL) prints the Python stack of every thread to stderr
    (:mod:`faulthandler`), so that a report of it says where it happened."""
    faulthandler.enable()
    app = create_application()
    ending = SignalEnding(app)
    if hasattr(signal, "pthread_sigmask"):  # held while PySide6 loaded (sorgui.cli.signals_held)
        signal.pthread_sigmask(signal.SIG_UNBLOCK, ENDING_SIGNALS)
    try:
        ending.window = open_main_window(path, report, line)
        early = ending.pending()
        return early if early is not None else app.exec()
    finally:
        ending.close()
