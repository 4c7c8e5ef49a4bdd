"""The main window end to end: typing, analysing, invalid input, examples, files, screenshots.

Real Qt widgets, a real VTK render window (Mesa under Xvfb in CI) and real worker processes
running the exact engine and Singular; nothing is mocked.
"""

from __future__ import annotations

import numpy as np
import pytest
from PySide6.QtCore import Qt
from PySide6.QtGui import QGuiApplication, QImage, QTextCharFormat

from sorgui.examples import EXAMPLES, example_text

pytestmark = pytest.mark.gui

EXPECTED_SOR = {
    "paper-example-1": True,
    "paper-cubic": True,
    "torus": True,
    "cone": True,
    "sphere": True,
    "cylinder": True,
    "coaxial-blend": True,
    "non-coaxial-blend": False,
    "ellipsoid": False,
    "rolling-ball-blend": False,
    "pipe-twisted-cubic": False,
    "dupin-cyclide": False,
}


def test_typed_equation_is_analysed_and_drawn(window, qtbot) -> None:
    editor = window.editor.text_edit
    qtbot.mouseClick(editor.viewport(), Qt.MouseButton.LeftButton)
    editor.clear()
    qtbot.keyClicks(editor, "(x^2 + y^2 + z^2 + 3)^2 - 16(x^2 + y^2)")
    qtbot.waitUntil(lambda: window.editor.is_valid is True, timeout=5000)
    assert window.analyze_button.isEnabled()
    with qtbot.waitSignal(window.result_shown, timeout=90_000) as blocker:
        with qtbot.waitSignal(window.worker.busy_changed, timeout=5000):
            qtbot.mouseClick(window.analyze_button, Qt.MouseButton.LeftButton)
        assert window.cancel_button.isEnabled() and window.busy_indicator.isVisible()
    analysis = blocker.args[0].analysis
    assert analysis.is_sor and analysis.recognition.symmetry == "revolution"
    assert analysis.recognition.axis.direction == ("0", "0", "1")

    text = window.results.plain_text()
    assert "surface of revolution: YES" in text
    assert "(0, 0, 0) + t·(0, 0, 1)" in text
    assert "Surface of revolution" in window.results.banner.text()
    assert {"surface", "axis", "profile"} <= window.viewport.actor_names()
    assert not window.cancel_button.isEnabled() and not window.busy_indicator.isVisible()
    assert window.stage_label.text().startswith("Done")


def test_table_1_highlights_the_row_of_the_surface(window, run_analysis) -> None:
    result = run_analysis(window, example_text("paper-example-1"))
    assert result.analysis.rationality.table_row == 4
    table = window.results.table
    highlighted = {
        row for row in range(table.rowCount()) if table.item(row, 0).background().color().name() == "#ffe08a"
    }
    assert highlighted == {3}  # rows are numbered 1-5 in the paper, 0-4 in Qt
    assert [table.item(3, c).text() for c in range(5)] == ["4", ">0", "0", "rational", "depends on #components"]


def test_formulas_are_typeset_and_copyable(window, qtbot, run_analysis) -> None:
    from sorgui.gui.formula_view import FormulaView
    from tests.gui.conftest import typeset_all

    run_analysis(window, example_text("cone"))
    typeset_all(window, qtbot)
    views = window.results.findChildren(FormulaView)
    assert len(views) >= 8
    assert all(view.shows_typeset for view in views), "every formula is typeset by mathtext"
    direction = next(v for v in views if v.formula.plain == "(1, 0, 1)")
    qtbot.mouseClick(direction.copy_button, Qt.MouseButton.LeftButton)
    assert QGuiApplication.clipboard().text() == "(1, 0, 1)"
    direction.copy_latex()
    assert QGuiApplication.clipboard().text() == r"\left(1, 0, 1\right)"


def test_results_are_exported_to_files(window, run_analysis, qtbot, tmp_path, monkeypatch) -> None:
    import json

    from tests.gui.conftest import export_through_window

    run_analysis(window, example_text("cone"))
    written = export_through_window(window, qtbot, tmp_path / "cone.json")
    data = json.loads(written.read_text(encoding="utf-8"))
    assert data["symmetry"] == "revolution" and data["rationality"]["table_row"] == 1
    tex = export_through_window(window, qtbot, tmp_path / "cone.tex")
    assert "\\documentclass" in tex.read_text(encoding="utf-8")
    shown: list[str] = []
    monkeypatch.setattr(window, "_show_error", lambda _title, message: shown.append(message))
    window.export_in_background(tmp_path / "cone.xyz")  # a name typed with a suffix of no format
    assert shown and "unknown export format" in shown[0] and not window.cad_export.busy


def test_invalid_equation_is_underlined_and_starts_no_worker(make_window, qtbot) -> None:
    window = make_window(prestart_worker=False)
    editor = window.editor
    editor.text_edit.clear()
    qtbot.keyClicks(editor.text_edit, "x^2+*y")
    qtbot.waitUntil(lambda: editor.error is not None, timeout=5000)
    selections = editor.error_selections()
    assert len(selections) == 1
    fmt = selections[0].format
    assert fmt.underlineStyle() == QTextCharFormat.UnderlineStyle.WaveUnderline
    cursor = selections[0].cursor
    assert cursor.selectionStart() == editor.error.position
    assert cursor.selectionEnd() >= cursor.selectionStart() + 1
    assert editor.error.message in editor.status_label.text()
    assert not window.analyze_button.isEnabled()

    assert window.analyze() is False
    assert not window.worker.is_busy and window.worker.current_pid is None
    assert "Not a polynomial" in window.results.banner.text()

    editor.text_edit.clear()
    qtbot.keyClicks(editor.text_edit, "x^2+y")
    qtbot.waitUntil(lambda: editor.is_valid is True, timeout=5000)
    assert editor.error_selections() == [] and window.analyze_button.isEnabled()


def test_keyboard_analyses_and_cancels(window, qtbot) -> None:
    window.set_equation(example_text("torus"))
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow, timeout=5000)  # shortcuts go to the active window
    window.editor.text_edit.setFocus()
    with qtbot.waitSignal(window.worker.busy_changed, timeout=5000):
        qtbot.keyClick(window.editor.text_edit, Qt.Key.Key_Return, Qt.KeyboardModifier.ControlModifier)
    assert window.worker.is_busy
    with qtbot.waitSignal(window.worker.cancelled, timeout=5000):
        qtbot.keyClick(window.editor.text_edit, Qt.Key.Key_Escape)
    assert window.stage_label.text() == "Cancelled"
    assert not window.worker.is_busy


@pytest.mark.slow
def test_examples_menu_loads_and_analyses_each_example(window, qtbot) -> None:
    actions = window.examples_menu.example_actions()
    assert [a.data() for a in actions] == [e.name for e in EXAMPLES]
    for action in actions:
        with qtbot.waitSignal(window.result_shown, timeout=90_000) as blocker:
            action.trigger()
        analysis = blocker.args[0].analysis
        assert window.editor.text() == example_text(action.data())
        assert analysis.is_sor is EXPECTED_SOR[action.data()], action.data()
        banner = window.results.banner.text()
        assert ("Not a surface" in banner) is not EXPECTED_SOR[action.data()]
        assert "surface" in window.viewport.actor_names()


def test_startup_loads_and_analyses_example_1_and_screenshots(window, qtbot, artifacts) -> None:
    with qtbot.waitSignal(window.result_shown, timeout=90_000) as blocker:
        window.load_startup_equation(None)
    analysis = blocker.args[0].analysis
    assert window.editor.text() == example_text("paper-example-1")
    assert analysis.recognition.axis.point == ("3/5", "-4/5", "0")
    window.viewport.patch_box.setChecked(True)
    assert {"surface", "axis", "profile", "patch"} <= window.viewport.actor_names()
    qtbot.wait(300)

    window_png, viewport_png = artifacts / "main-window.png", artifacts / "viewport.png"
    window.save_screenshots(window_png, viewport_png)
    for path, minimum in ((window_png, (1200, 700)), (viewport_png, (600, 500))):
        image = QImage(str(path))
        assert image.width() >= minimum[0] and image.height() >= minimum[1], path
    # The image is kept while its pixels are read: constBits() views its memory without owning it.
    grey = QImage(str(viewport_png)).convertToFormat(QImage.Format.Format_Grayscale8)
    pixels = np.frombuffer(grey.constBits(), dtype=np.uint8, count=grey.sizeInBytes()).copy()
    assert pixels.std() > 10, "the render window shows something"


def test_sorgui_opens_the_window_first_then_analyses_example_1(qtbot) -> None:
    """As ``sorgui`` starts: the window is drawn before the render window exists (pyvista and
    VTK's rendering load after it), then Example 1 is analysed and drawn."""
    from PySide6.QtCore import QCoreApplication, QEvent

    from sorgui.gui.app import create_application, open_main_window

    create_application([])
    window = open_main_window(None)
    try:
        assert window.isVisible() and not window.viewport.rendering
        qtbot.waitExposed(window)
        qtbot.waitUntil(lambda: window.viewport.rendering, timeout=60_000)
        qtbot.waitUntil(lambda: window.viewport.scene is not None, timeout=120_000)
        qtbot.waitUntil(lambda: "Surface of revolution" in window.results.banner.text(), timeout=10_000)
        assert window.session.run.text == example_text("paper-example-1")
        assert {"surface", "axis"} <= window.viewport.actor_names()
    finally:
        window.setWindowModified(False)
        window.close()
        window.deleteLater()
        QCoreApplication.sendPostedEvents(None, QEvent.Type.DeferredDelete)


def test_a_refused_equation_says_what_is_wrong_and_drops_the_old_stages(window, qtbot, run_analysis, artifacts) -> None:
    """After an analysis, an equation above the degree limit or an empty editor: the heading names
    the problem, and the stages of the previous equation are no longer shown."""
    run_analysis(window, "x^2 + 2y^2 + 3z^2 - 1")
    assert window.run_panel.stage_line.text()
    for text, heading in (
        ("x^200", "The degree is above sorgui's limit"),
        ("", "No equation"),
        ("x^2 + * y", "Not a polynomial in x, y, z"),
    ):
        window.set_equation(text)
        assert window.analyze() is False
        assert heading in window.results.banner.text(), window.results.banner.text()
        assert window.run_panel.stage_line.text() == "" and not window.run_panel.progress_bar.isVisible()
    window.save_screenshots(artifacts / "refused-window.png", artifacts / "refused-viewport.png")


def _close_answering(make_window, monkeypatch, answer: str):  # noqa: ANN001, ANN202
    """A window with a changed equation, closed with ``answer`` to the unsaved-changes question."""
    from PySide6.QtWidgets import QMessageBox

    window = make_window(prestart_worker=False)
    window.set_equation("x^2 + y^2 - 7")
    window.setWindowModified(True)
    monkeypatch.setattr(window, "ask_to_save", lambda _name: getattr(QMessageBox.StandardButton, answer))
    window.close()
    return window


def test_discard_on_quit_is_not_restored_at_the_next_start(make_window, monkeypatch) -> None:
    window = _close_answering(make_window, monkeypatch, "Discard")
    assert not window.isVisible()
    assert make_window(prestart_worker=False).settings.equation != "x^2 + y^2 - 7"


def test_cancel_on_quit_keeps_the_window(make_window, monkeypatch) -> None:
    window = _close_answering(make_window, monkeypatch, "Cancel")
    assert window.isVisible()


def test_undo_stays_within_the_loaded_document(make_window, qtbot) -> None:
    window = make_window(prestart_worker=False)
    window.set_equation(example_text("torus"))
    window.set_equation(example_text("cone"))
    edit = window.editor.text_edit
    edit.moveCursor(edit.textCursor().MoveOperation.End)
    qtbot.keyClicks(edit, " + 1")
    for _ in range(3):
        edit.undo()
    assert edit.toPlainText() == example_text("cone")


def test_the_editor_wraps_a_rounded_equation_between_its_numbers(make_window, qtbot) -> None:
    """A pasted CAD equation was wrapped anywhere, "- 0." at the end of one line and "0618315" at
    the start of the next. It now wraps between terms; an equation too long for Qt to wrap that
    way quickly (a dense surface of degree 40, 200,000 characters) still wraps anywhere."""
    from benchmarks.gui_heartbeat import dense_surface
    from sorgui.gui.editor import WORD_WRAP_LIMIT

    window = make_window(prestart_worker=False)
    text = (
        "0.172059*z^2 + 0.196915*y*z + 0.125626*y^2 + 0.0489472*x*z - 0.0618315*x*y + 0.242315*x^2"
        " - 0.638162*z + 0.0429165*y - 1.61362*x + 2.08005"
    )
    window.set_equation(text)
    edit = window.editor.text_edit
    qtbot.waitUntil(lambda: edit.document().firstBlock().layout().lineCount() > 1, timeout=5000)
    layout = edit.document().firstBlock().layout()
    starts = [layout.lineAt(i).textStart() for i in range(1, layout.lineCount())]
    assert starts and all(text[start - 1] == " " for start in starts), [text[s - 5 : s + 5] for s in starts]
    dense = dense_surface(40)
    assert len(dense) > WORD_WRAP_LIMIT
    window.set_equation(dense)
    assert edit.wordWrapMode() == edit.wordWrapMode().WrapAnywhere
    window.set_equation(text)
    assert edit.wordWrapMode() == edit.wordWrapMode().WrapAtWordBoundaryOrAnywhere


@pytest.mark.parametrize("target", ["editor", "viewport"])
def test_a_dropped_equation_file_is_opened(window, qtbot, tmp_path, target: str) -> None:
    """A file dropped on the editor or on the 3D view opens (it is not pasted as ``file://``
    text, and the 3D view does not try to read it); anything else is refused."""
    from PySide6.QtCore import QEvent, QMimeData, QObject, QPointF, QUrl
    from PySide6.QtGui import QDropEvent
    from PySide6.QtWidgets import QApplication

    part = tmp_path / "part.sor"
    part.write_text("x^2 + y^2 - 4z^2 - 1\n", encoding="utf-8")
    mime = QMimeData()
    mime.setUrls([QUrl.fromLocalFile(str(part))])
    widget = window.editor.text_edit.viewport() if target == "editor" else window.viewport.plotter
    drop = QDropEvent(
        QPointF(10, 10), Qt.DropAction.CopyAction, mime, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier
    )
    # Qt delivers a drop only during a real drag (none can be made under Xvfb without a drag
    # source): the window's event filter is shown to watch the widget, then given the drop.
    watched: list[QObject] = []
    window_filter = window.eventFilter
    window.eventFilter = lambda obj, event: watched.append(obj) or window_filter(obj, event)
    QApplication.sendEvent(widget, QEvent(QEvent.Type.User))
    del window.eventFilter
    assert widget in watched
    assert window.eventFilter(widget, drop) is True
    assert window.editor.text() == "x^2 + y^2 - 4z^2 - 1"
    assert "file://" not in window.editor.text()
    qtbot.waitUntil(lambda: not window.worker.is_busy, timeout=120_000)
    picture = tmp_path / "photo.png"
    picture.write_bytes(b"not an equation")
    mime.setUrls([QUrl.fromLocalFile(str(picture))])
    other = QDropEvent(
        QPointF(10, 10), Qt.DropAction.CopyAction, mime, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier
    )
    assert window.eventFilter(widget, other) is True
    assert window.editor.text() == "x^2 + y^2 - 4z^2 - 1" and "reports (.json)" in window.statusBar().currentMessage()


def test_the_sphere_settles_with_its_centre_and_radius(window, run_analysis, artifacts) -> None:
    """A sphere has no rationality stage (no unique axis): once done, the pane says nothing is
    still being decided, and it gives the centre and the squared radius."""
    run_analysis(window, example_text("sphere"))
    from PySide6.QtWidgets import QLabel

    text = "\n".join(label.text() for label in window.results.widget().findChildren(QLabel))
    assert "being decided" not in text and "being computed" not in text
    assert "radius²" in text and "radius_squared" in window.results.views
    window.save_screenshots(artifacts / "sphere-window.png", artifacts / "sphere-viewport.png")


def test_the_wheel_over_a_long_formula_scrolls_the_pane(qtbot) -> None:
    """A vertical turn of the wheel over a formula row with its own horizontal scroll bar goes on
    to the results pane; a horizontal one (or Shift+wheel) scrolls the row."""
    from PySide6.QtCore import QPoint, QPointF
    from PySide6.QtGui import QWheelEvent
    from PySide6.QtWidgets import QLabel

    from sorgui.gui.formula_view import RowScroll

    row = RowScroll()
    row.setWidget(QLabel("x" * 3000))
    row.resize(300, 60)
    qtbot.addWidget(row)
    row.show()
    qtbot.waitExposed(row)

    def wheel(dx: int, dy: int) -> QWheelEvent:
        return QWheelEvent(
            QPointF(10, 10),
            QPointF(row.mapToGlobal(QPoint(10, 10))),
            QPoint(0, 0),
            QPoint(dx, dy),
            Qt.MouseButton.NoButton,
            Qt.KeyboardModifier.NoModifier,
            Qt.ScrollPhase.NoScrollPhase,
            False,
        )

    vertical = wheel(0, -120)
    row.wheelEvent(vertical)
    assert not vertical.isAccepted() and row.horizontalScrollBar().value() == 0
    row.wheelEvent(wheel(-120, 0))
    assert row.horizontalScrollBar().value() > 0


def test_a_dropped_block_leaves_the_page_at_once_and_qt_deletes_it(window) -> None:
    """A block the page no longer shows is hidden, out of the page, and deleted by Qt on the
    GUI thread, never
    handed to Python without a parent (which left it to the cycle collector, on any thread,
    and crashed PySide6 once combined with deleteLater)."""
    import shiboken6
    from PySide6.QtCore import QCoreApplication, QEvent

    page = window.results.page
    page.begin()
    page.section("First", [("caption", "a text")], lambda *_: None, str)
    page.end()
    old = page.blocks[-1].widget
    page.begin()
    page.section("Second", [("caption", "another text")], lambda *_: None, str)
    page.end()
    assert old.isHidden() and old not in page.findChildren(type(old))
    QCoreApplication.sendPostedEvents(None, QEvent.Type.DeferredDelete)
    assert not shiboken6.isValid(old)


@pytest.mark.parametrize(
    ("equation", "words"),
    [
        ("x^2 + y^2 + z^2 + 1", "The surface has no real points: there is nothing to draw, in any region."),
        ("(x^2 + y^2 + z^2 - 4)^2 + z^2", "real points are a curve (a circle about the axis), not a surface: there is"),
    ],
)
def test_an_empty_view_says_what_the_real_points_are(window, run_analysis, qtbot, equation: str, words: str) -> None:
    """A surface without a surface of real points: the empty 3D view says so under the equation,
    and so does the status line (both told the user to give a region, "(--region)", a flag of the
    command line)."""
    run_analysis(window, equation)
    qtbot.waitUntil(lambda: not window.session.run.running, timeout=120_000)
    qtbot.waitUntil(lambda: words in window.viewport.caption.text(), timeout=60_000)
    assert "--region" not in window.viewport.caption.text() and words in window.stage_label.text()


def test_tab_goes_from_the_equation_to_analyze_and_cancel(window) -> None:
    """Analyze sits above the editor but came last in the tab order, after the 3D view, and
    Cancel was never reached (it is when a run makes it enabled)."""

    def tabbed_from(widget):  # noqa: ANN001, ANN202
        following = widget.nextInFocusChain()
        while not (following.focusPolicy() & Qt.FocusPolicy.TabFocus) or not following.isEnabled():
            following = following.nextInFocusChain()
        return following

    window.cancel_button.setEnabled(True)
    try:
        assert tabbed_from(window.editor.text_edit) is window.analyze_button
        assert tabbed_from(window.analyze_button) is window.cancel_button
    finally:
        window.cancel_button.setEnabled(False)


def test_a_long_status_line_is_elided_and_whole_in_its_tooltip(window, run_analysis, qtbot) -> None:
    """The status line was cut at the window's edge ("… give a smaller one (--regi"), with no
    way to read the rest: it now ends in "…" where it does not fit, and its tooltip holds it whole."""
    window.resize(700, 600)
    run_analysis(window, "x^2 + y^2 + z^2 + 1")
    qtbot.waitUntil(lambda: not window.session.run.running, timeout=60_000)
    label = window.stage_label
    assert label.toolTip() == label.text() and label.text()
    assert label.fontMetrics().horizontalAdvance(label.text()) > label.width()  # too long to show whole
