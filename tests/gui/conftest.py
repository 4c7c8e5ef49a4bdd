"""Fixtures of the GUI tests: a real window with a real VTK render window, and leak checks.

Tests marked ``gui`` need a display. Without one they are skipped, except in CI (``CI`` set),
where ``.ci/run`` always starts Xvfb: there a missing display fails them instead of hiding them.
Qt must use the ``xcb`` platform: ``QT_QPA_PLATFORM=offscreen`` gives VTK no OpenGL context.
Every test gets its own settings folder, so no test reads or writes the user's settings.
"""

from __future__ import annotations

import gc
import multiprocessing
import os
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

ARTIFACTS = Path(__file__).resolve().parents[2] / "artifacts"
"""Screenshots taken by the tests (git-ignored), kept for people to look at."""


def display_available() -> bool:
    """Whether a window can be opened here (an X display on Linux; always elsewhere)."""
    if not sys.platform.startswith("linux"):
        return True
    return bool(os.environ.get("DISPLAY"))


if sys.platform.startswith("linux"):
    os.environ["QT_QPA_PLATFORM"] = "xcb"  # VTK renders through GLX (Xvfb in CI)


def pytest_runtest_setup(item: pytest.Item) -> None:
    """Before any fixture (a QApplication without a display would abort the whole run)."""
    if item.get_closest_marker("gui") is None or display_available():
        return
    if os.environ.get("CI"):
        pytest.fail("CI must run the GUI tests under Xvfb, but DISPLAY is not set")
    pytest.skip("no display: run under xvfb-run (see .ci/run)")


@pytest.fixture(autouse=True)
def settings_folder(tmp_path: Path) -> Path:
    """A fresh QSettings location for each test (never the user's ``~/.config``)."""
    from PySide6.QtCore import QSettings

    folder = tmp_path / "settings"
    folder.mkdir()
    for scope in (QSettings.Scope.UserScope, QSettings.Scope.SystemScope):
        QSettings.setPath(QSettings.Format.IniFormat, scope, str(folder))
    return folder


def _worker_processes() -> list[multiprocessing.Process]:
    names = ("sorgui-analysis", "sorgui-typesetting")
    return [p for p in multiprocessing.active_children() if p.name in names]


@pytest.fixture(autouse=True)
def no_leaks(request: pytest.FixtureRequest) -> Iterator[None]:
    """Fail a GUI test that leaves a window, a render window or a worker process behind.

    Autouse, so it is set up before (and torn down after) the ``window`` fixture.
    """
    yield
    if request.node.get_closest_marker("gui") is None or not display_available():
        return
    from PySide6.QtCore import QCoreApplication, QEvent
    from PySide6.QtWidgets import QApplication
    from pyvista.plotting.plotter import _ALL_PLOTTERS

    app = QApplication.instance()
    if app is not None:
        QCoreApplication.sendPostedEvents(None, QEvent.Type.DeferredDelete)
        app.processEvents()
        visible = [w for w in QApplication.topLevelWidgets() if w.isVisible()]
        assert not visible, f"windows left open: {visible}"
    assert not _ALL_PLOTTERS, f"render windows left open: {list(_ALL_PLOTTERS)}"
    assert gc.isenabled(), "the cycle collector was left disabled (the window's import thread)"
    assert not _worker_processes(), f"worker processes left running: {_worker_processes()}"


@pytest.fixture
def make_window(qtbot):  # noqa: ANN001, ANN201
    """A factory of shown main windows, each closed (worker killed, render window released)
    and deleted at the end of the test."""
    from PySide6.QtCore import QCoreApplication, QEvent

    from sorgui.gui.app import create_application
    from sorgui.gui.main_window import MainWindow

    create_application([])
    windows = []
    stuck = _DialogWatch()

    def make(prestart_worker: bool = True) -> MainWindow:
        window = MainWindow(prestart_worker=prestart_worker)
        window.resize(1400, 860)
        window.show()
        qtbot.waitExposed(window)
        windows.append(window)
        return window

    yield make
    stuck.stop()
    app = QCoreApplication.instance()
    for window in windows:
        window.setWindowModified(False)  # no unsaved-changes question at the end of a test
        window.close()
    app.processEvents()  # what closing posted runs while the windows still exist
    # The garbage made so far goes while every Qt object it may point to exists: a collection
    # after the windows' deletion crashed once in a suite run (SIGSEGV in gc.collect, not seen
    # again in 10 runs of the GUI tests; .ci/run now prints the native stack of such a crash).
    gc.collect()
    for window in windows:
        window.deleteLater()
    QCoreApplication.sendPostedEvents(None, QEvent.Type.DeferredDelete)
    gc.collect()
    if stuck.closed:
        pytest.fail(f"a modal dialog was left open for {DIALOG_PATIENCE:g} s and closed: {stuck.closed}")


DIALOG_PATIENCE = 20.0
"""Seconds a modal dialog may stay open in a test before it is closed and the test failed."""


class _DialogWatch:
    """Close a modal dialog that nothing in the test answers (a dialog the test forgot to stub:
    its event loop would block the whole run until CI's own time limit), remembering its title."""

    def __init__(self) -> None:
        from PySide6.QtCore import QTimer

        self.closed: list[str] = []
        self._seen: dict[int, float] = {}
        self._timer = QTimer()
        self._timer.setInterval(500)
        self._timer.timeout.connect(self._check)
        self._timer.start()

    def _check(self) -> None:
        import time

        from PySide6.QtWidgets import QApplication, QDialog

        modal = QApplication.activeModalWidget()
        if modal is None:
            self._seen.clear()
            return
        first = self._seen.setdefault(id(modal), time.monotonic())
        if time.monotonic() - first >= DIALOG_PATIENCE:
            self.closed.append(modal.windowTitle() or type(modal).__name__)
            if isinstance(modal, QDialog):
                modal.reject()
            else:
                modal.close()

    def stop(self) -> None:
        self._timer.stop()


@pytest.fixture
def window(make_window):  # noqa: ANN001, ANN201
    """One shown main window with a warm worker process."""
    return make_window()


@pytest.fixture(scope="session")
def artifacts() -> Path:
    ARTIFACTS.mkdir(exist_ok=True)
    return ARTIFACTS


@pytest.fixture
def run_analysis(qtbot):  # noqa: ANN001, ANN201
    """``run_analysis(window, text=None)``: analyse (the given or the current text) and wait
    until the result is on screen; fails at once with the worker's message if it fails."""

    def run(window, text: str | None = None, timeout_ms: int = 90_000):  # noqa: ANN001, ANN202
        outcome: list[tuple[str, object]] = []
        connections = [
            (window.result_shown, lambda result: outcome.append(("shown", result))),
            (window.worker.failed, lambda message: outcome.append(("failed", message))),
            (window.worker.invalid, lambda message, *_: outcome.append(("invalid", message))),
        ]
        for signal, slot in connections:
            signal.connect(slot)
        try:
            if text is not None:
                window.set_equation(text)
            window.time_limit = timeout_ms / 1000  # a loaded machine must not cut the analysis short
            assert window.analyze(), window.editor.status_label.text()
            qtbot.waitUntil(lambda: bool(outcome), timeout=timeout_ms)
        finally:
            for signal, slot in connections:
                signal.disconnect(slot)
        kind, payload = outcome[0]
        assert kind == "shown", f"the analysis {kind}: {payload}"
        return payload

    return run


def typeset_all(window, qtbot, timeout_ms: int = 60_000) -> None:  # noqa: ANN001
    """Wait until the typesetting process has typeset every formula of the results pane that it
    can (scrolled through, so that the rows off screen are asked for too)."""
    results = window.results

    def done() -> bool:
        style = results.formula_style()
        return not window.typesetter.busy and all(
            view.typeset_style == style for view in results.views.values() if view.formula.pieces
        )

    results.ask_typesetter()
    qtbot.waitUntil(done, timeout=timeout_ms)


@pytest.fixture
def hanging_singular(tmp_path: Path) -> Path:
    """A ``Singular`` that never finishes (for worker processes started after it is set)."""
    script = tmp_path / "Singular"
    script.write_text("#!/bin/sh\nexec sleep 600\n")
    script.chmod(0o755)
    return script


def export_through_window(window, qtbot, path: Path) -> Path:  # noqa: ANN001
    """File → Export's writing of ``path``, in the export process as the menu runs it, waited
    for; the reason it failed (what the window would show) fails the test."""
    failures: list[str] = []
    window.cad_export.failed.connect(failures.append)
    try:
        window.export_in_background(path)
        qtbot.waitUntil(lambda: not window.cad_export.busy, timeout=120_000)
    finally:
        window.cad_export.failed.disconnect(failures.append)
    assert not failures and Path(path).exists(), failures
    return Path(path)
