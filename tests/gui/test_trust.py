"""The window one can trust: results stage by stage, never a stale verdict shown as current,
a viewport without VTK's own keys, standard views, zoom, Help, prompts, a small window.

Real window, real VTK render window (Mesa under Xvfb), real worker processes. A ``Singular``
that never answers makes the slow stage as slow as we like.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PySide6.QtCore import QPoint, Qt
from PySide6.QtGui import QCursor
from PySide6.QtWidgets import QMessageBox

from sorgui.examples import example_text
from sorgui.gui.formula_view import FormulaView
from sorgui.gui.help import TOPICS
from sorgui.session import StageState

pytestmark = pytest.mark.gui


SLOW_MS = 300_000
"""Time allowed to an analysis that runs every stage (the canal stage asks Singular too)."""


def stage_state(window, name: str) -> StageState:  # noqa: ANN001
    return window.session.run.stages[name].state


def test_verdict_while_singular_runs_and_no_old_verdict_ever(
    make_window, qtbot, run_analysis, monkeypatch, hanging_singular, artifacts
) -> None:
    window = make_window(prestart_worker=False)  # each job starts its own process
    run_analysis(window, example_text("ellipsoid"), timeout_ms=SLOW_MS)
    assert "Not a surface of revolution" in window.results.banner.text()

    monkeypatch.setenv("SORGUI_SINGULAR", str(hanging_singular))  # for the next worker process
    window.set_equation(example_text("paper-example-1"))
    assert window.analyze()
    # At once: nothing of the ellipsoid is left, neither in the pane nor in the 3D view.
    assert "Not a surface" not in window.results.banner.text()
    assert "Analysing" in window.results.banner.text()
    assert "surface" not in window.viewport.actor_names()
    assert window.viewport.caption.text().startswith("Analysing")

    # The verdict, the axis and the mesh arrive while Singular still runs.
    qtbot.waitUntil(lambda: window.viewport.scene is not None, timeout=60_000)
    qtbot.waitUntil(lambda: "Surface of revolution" in window.results.banner.text(), timeout=30_000)
    qtbot.waitUntil(lambda: stage_state(window, "rationality") is StageState.RUNNING, timeout=30_000)
    assert window.worker.is_busy
    assert stage_state(window, "recognition") is StageState.DONE
    assert "(3/5, -4/5, 0)" in window.results.plain_text()
    assert "being decided" in _pane_text(window)
    assert "surface" in window.viewport.actor_names() and "axis" in window.viewport.actor_names()
    assert window.viewport.caption.text().startswith("f = ")
    assert window.run_panel.progress_bar.isVisible()
    qtbot.waitUntil(lambda: window.run_panel.progress_bar.value() > 0, timeout=1000)  # at the panel's next tick
    assert window.run_panel.progress_bar.value() < window.run_panel.progress_bar.maximum()
    qtbot.wait(300)
    window.save_screenshots(artifacts / "running-window.png", artifacts / "running-viewport.png")

    # Editing makes everything visibly out of date.
    window.editor.text_edit.moveCursor(window.editor.text_edit.textCursor().MoveOperation.End)
    qtbot.keyClicks(window.editor.text_edit, " + 1")
    assert window.session.stale
    assert window.run_panel.notice_kind == "stale" and "previous equation" in window.run_panel.notice.text()
    assert not window.results.widget().isEnabled(), "greyed out"
    assert window.viewport.stale and "Previous equation" in window.viewport.caption.text()

    # Cancel keeps what was done and marks the rest cancelled; nothing is shown as current.
    with qtbot.waitSignal(window.worker.cancelled, timeout=10_000):
        window.cancel()
    assert stage_state(window, "recognition") is StageState.DONE
    assert stage_state(window, "rationality") is StageState.CANCELLED
    assert stage_state(window, "parametrizations") is StageState.CANCELLED
    assert window.run_panel.notice_kind == "stale", "still the previous equation's results"
    window.editor.set_text(example_text("paper-example-1"))
    assert not window.session.stale and window.results.widget().isEnabled()
    assert window.run_panel.notice_kind == "cancelled"


def test_analyze_during_a_run_supersedes_it(make_window, qtbot, monkeypatch, hanging_singular) -> None:
    window = make_window(prestart_worker=False)  # each job starts its own process
    monkeypatch.setenv("SORGUI_SINGULAR", str(hanging_singular))
    window.set_equation(example_text("paper-example-1"))
    assert window.analyze()
    qtbot.waitUntil(lambda: stage_state(window, "rationality") is StageState.RUNNING, timeout=60_000)
    first = window.worker.current_pid
    monkeypatch.delenv("SORGUI_SINGULAR")  # the next process finds the real Singular

    window.set_equation(example_text("cone"))
    with qtbot.waitSignal(window.result_shown, timeout=SLOW_MS) as blocker:
        assert window.analyze()
        assert "replaces it" in window.statusBar().currentMessage()
        assert "(3/5, -4/5, 0)" not in window.results.plain_text()
    assert blocker.args[0].analysis.recognition.axis.direction == ("1", "0", "1")
    assert window.session.run.text == example_text("cone")
    assert "(3/5, -4/5, 0)" not in window.results.plain_text() and "(1, 0, 1)" in window.results.plain_text()
    qtbot.waitUntil(
        lambda: (
            not Path(f"/proc/{first}").exists()
            or "Z" in Path(f"/proc/{first}/stat").read_text().rsplit(")", 1)[1].split()[0]
        ),
        timeout=10_000,
    )  # the superseded process is gone (or a zombie until reaped)


def _pane_text(window) -> str:  # noqa: ANN001
    from PySide6.QtWidgets import QLabel

    return "\n".join(label.text() for label in window.results.widget().findChildren(QLabel))


def test_input_error_is_said_at_the_top_and_clears_the_view(window, run_analysis, qtbot) -> None:
    run_analysis(window, example_text("torus"))
    window.set_equation("x^2 + (y")
    assert window.analyze() is False
    assert window.run_panel.notice_kind == "error"
    assert "Not a polynomial" in window.results.banner.text()
    reason = window.editor.error.message
    assert reason in window.results.banner.text() and reason in window.editor.status_label.text()
    assert reason not in window.run_panel.notice.text() and "Correct the equation" in window.run_panel.notice.text()
    assert "surface" not in window.viewport.actor_names()


def test_a_statement_pasted_from_singular_is_analysed_and_named_by_its_equation(window, run_analysis) -> None:
    """``poly f = x2+y2-z2-1;`` (Singular's print of a hyperboloid) is its equation; the caption
    of the drawn surface is that equation, without the label or the ';'."""
    run_analysis(window, "poly f = x2+y2-z2-1;")
    assert "Surface of revolution" in window.results.banner.text()
    assert window.viewport.caption.text() == "f = x2+y2-z2-1"
    run_analysis(window, "$$ x^2 + y^2 = z $$")
    assert window.viewport.caption.text() == "x^2 + y^2 = z"


def test_vtk_keys_change_nothing_and_close_nothing(window, run_analysis, qtbot) -> None:
    """VTK's interactor style: 3 stereo, w/s wireframe/surface, e/q quit, f fly to, r reset,
    j/t joystick/trackball, u user; pyvista: v, b, C, +, -, arrows. None of them does anything."""
    run_analysis(window, example_text("torus"))
    viewport = window.viewport
    renderer = viewport.plotter.renderer
    before = (renderer.GetViewProps().GetNumberOfItems(), viewport.actor_names(), viewport.camera_state())
    for key in ("3", "w", "s", "e", "q", "f", "r", "j", "t", "u", "v", "b", "C", "+", "-"):
        qtbot.keyClick(viewport.plotter, key)
        qtbot.wait(20)
        assert window.isVisible() and viewport.plotter.isVisible(), key
        assert not viewport.plotter.ren_win.GetStereoRender(), key
        assert renderer.actors["surface"].prop.style.lower() == "surface", key
        after = (renderer.GetViewProps().GetNumberOfItems(), viewport.actor_names(), viewport.camera_state())
        assert after == before, key


def test_p_picks_under_the_mouse_without_a_bounding_box(window, run_analysis, qtbot) -> None:
    """P picks where the pointer is now, also when it has not moved over this render window (P
    read the interactor's last move, and Qt sends no move to where the pointer already is: the
    test run twice in one process failed 7 times of 8)."""
    run_analysis(window, example_text("torus"))
    viewport = window.viewport
    viewport.set_view("z")
    renderer = viewport.plotter.renderer
    props = renderer.GetViewProps().GetNumberOfItems()
    renderer.SetWorldPoint(2.0, 0.0, 1.0, 1.0)  # the top of the tube
    renderer.WorldToDisplay()
    x, y, _ = renderer.GetDisplayPoint()
    ratio = viewport.plotter.devicePixelRatioF()
    where = QPoint(int(round(x / ratio)), int(round(viewport.plotter.height() - y / ratio)))
    QCursor.setPos(viewport.plotter.mapToGlobal(where))  # no move event needed: P reads the pointer
    with qtbot.waitSignal(viewport.picked, timeout=5000) as blocker:
        qtbot.keyClick(viewport.plotter, "p")
    assert blocker.args[0].meets_axis is True
    added = renderer.GetViewProps().GetNumberOfItems() - props
    # the normal, the circle and the point, and (a torus is a canal surface) the touching
    # spheres and their characteristic circles: no red box
    assert added == 5 and {"pick_sphere", "pick_canal_circle"} <= viewport.actor_names()


def test_standard_views_projection_wireframe_and_section(window, run_analysis) -> None:
    run_analysis(window, example_text("paper-example-1"))
    viewport = window.viewport
    camera = viewport.plotter.renderer.GetActiveCamera()
    direction = window.session.run.analysis.recognition.axis.direction
    axis = np.array([float(v) for v in direction])
    axis /= np.linalg.norm(axis)
    viewport.view_actions["along"].trigger()
    assert abs(abs(np.dot(np.asarray(camera.GetDirectionOfProjection()), axis)) - 1) < 1e-9
    viewport.view_actions["across"].trigger()
    assert abs(np.dot(np.asarray(camera.GetDirectionOfProjection()), axis)) < 1e-9
    assert abs(abs(np.dot(np.asarray(camera.GetViewUp()), axis)) - 1) < 1e-9
    viewport.view_actions["x"].trigger()
    assert np.allclose(camera.GetDirectionOfProjection(), (-1, 0, 0))
    viewport.view_actions["parallel"].trigger()
    assert camera.GetParallelProjection()
    viewport.view_actions["wireframe"].trigger()
    assert viewport.plotter.renderer.actors["surface"].prop.style.lower() == "wireframe"
    viewport.view_actions["wireframe"].trigger()
    viewport.view_actions["clip"].trigger()
    assert viewport.plotter.renderer.actors["surface"].GetMapper().GetClippingPlanes().GetNumberOfItems() == 1
    viewport.view_actions["clip"].trigger()
    assert viewport.plotter.renderer.actors["surface"].GetMapper().GetClippingPlanes().GetNumberOfItems() == 0
    viewport.view_actions["reset"].trigger()
    view_menu = next(a.menu() for a in window.menuBar().actions() if a.text() == "&View")
    assert viewport.view_actions["along"] in view_menu.actions()


def test_camera_is_restored_on_the_next_start_for_the_same_equation(make_window, run_analysis) -> None:
    first = make_window()
    run_analysis(first, example_text("torus"))
    first.viewport.set_view("x")
    first.viewport.set_parallel_projection(True)
    saved = first.viewport.camera_state()
    first.close()
    second = make_window()
    run_analysis(second, example_text("torus"))
    restored = second.viewport.camera_state()
    assert np.allclose(restored.position, saved.position) and restored.parallel
    second.close()
    third = make_window()  # another equation first: its surface is framed afresh
    run_analysis(third, example_text("cone"))
    framed = third.viewport.camera_state()
    assert not framed.parallel and not np.allclose(framed.position, saved.position)


def test_formulas_zoom_with_keys_and_copy_in_every_language(window, run_analysis, qtbot) -> None:
    from PySide6.QtGui import QGuiApplication

    from tests.gui.conftest import typeset_all

    run_analysis(window, example_text("cone"))
    typeset_all(window, qtbot)
    height = _formula_height(window, "(1, 0, 1)")
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow, timeout=5000)
    with _refreshed(window, qtbot):
        qtbot.keyClick(window.results, Qt.Key.Key_Plus, Qt.KeyboardModifier.ControlModifier)
    assert window.zoom > 1.0
    assert _formula_height(window, "(1, 0, 1)") > height
    view = next(v for v in window.results.findChildren(FormulaView) if v.formula.plain == "(1, 0, 1)")
    texts = {}
    for action in view.copy_menu.actions():
        action.trigger()
        texts[action.text()] = QGuiApplication.clipboard().text()
    assert texts["Copy as text"] == "(1, 0, 1)"
    assert texts["Copy as LaTeX"] == r"\left(1, 0, 1\right)"
    assert texts["Copy as Maple"] == "[1, 0, 1]"
    assert texts["Copy as Mathematica"] == "{1, 0, 1}"
    assert texts["Copy as Python"] == "(1, 0, 1)"
    with _refreshed(window, qtbot):
        _ctrl_wheel(window.results.viewport(), -120)  # Ctrl+wheel down over the results: zoom out
    assert window.zoom == 1.0 and _formula_height(window, "(1, 0, 1)") == height
    with _refreshed(window, qtbot):
        _ctrl_wheel(window.results.viewport(), 120)
    assert window.zoom > 1.0 and _formula_height(window, "(1, 0, 1)") > height
    with _refreshed(window, qtbot):
        window.zoom_reset_action.trigger()
    assert window.zoom == 1.0 and _formula_height(window, "(1, 0, 1)") == height


def _ctrl_wheel(widget, delta: int) -> None:  # noqa: ANN001
    """One notch of the mouse wheel with Ctrl held, over the middle of ``widget``."""
    from PySide6.QtCore import QPointF
    from PySide6.QtGui import QWheelEvent
    from PySide6.QtWidgets import QApplication

    centre = QPointF(widget.width() / 2, widget.height() / 2)
    event = QWheelEvent(
        centre,
        widget.mapToGlobal(centre),
        QPoint(0, 0),
        QPoint(0, delta),
        Qt.MouseButton.NoButton,
        Qt.KeyboardModifier.ControlModifier,
        Qt.ScrollPhase.NoScrollPhase,
        False,
    )
    QApplication.sendEvent(widget, event)


class _refreshed:  # noqa: N801 (a context manager used like qtbot.waitSignal)
    """Wait until the formulas are typeset again (in the new zoom's style)."""

    def __init__(self, window, qtbot) -> None:  # noqa: ANN001
        self.window, self.qtbot = window, qtbot

    def __enter__(self) -> None:
        pass

    def __exit__(self, *exc: object) -> None:
        from tests.gui.conftest import typeset_all

        self.qtbot.wait(100)
        typeset_all(self.window, self.qtbot)
        self.qtbot.wait(50)


def _formula_height(window, plain: str) -> int:  # noqa: ANN001
    view = next(v for v in window.results.findChildren(FormulaView) if v.formula.plain == plain)
    return view.content.pixmap().height()


def test_long_formulas_are_folded_with_show_all(window, run_analysis) -> None:
    from benchmarks.gui_heartbeat import sor_in_general_position

    text = sor_in_general_position(8)
    run_analysis(window, text)
    view = next(
        v
        for v in window.results.findChildren(FormulaView)
        if v.formula.plain.startswith(window.session.run.analysis.recognition.polynomial[:20])
    )
    assert view.folded and "show all" in view.show_all_button.text()
    view.show_all()
    assert not view.folded


def test_help_menu_has_every_topic(window, qtbot) -> None:
    help_menu = next(a.menu() for a in window.menuBar().actions() if a.text() == "&Help")
    titles = [a.text() for a in help_menu.actions()]
    for title, _page in TOPICS.values():
        assert title in titles
    window.show_help("syntax")
    syntax = window.help_dialog.browser.toPlainText()
    assert window.help_dialog.isVisible() and "Input syntax" in syntax
    assert "Parametrizations" in syntax and "x = X, y = Y, z = Z" in syntax and "(X, Y, Z)" in syntax
    window.show_help("paper")
    assert "Vršek" in window.help_dialog.browser.toPlainText()
    window.show_help("keys")
    assert "Ctrl+Alt+A" in window.help_dialog.browser.toPlainText()
    window.show_help("canal")
    canal = window.help_dialog.browser.toPlainText()
    assert "characteristic circle" in canal and "r²" in canal and "witness line" in canal and "spine" in canal
    window.show_help("colours")
    colours = window.help_dialog.browser.toPlainText()
    assert "the axis of revolution" in colours and "spine of a canal surface" in colours
    window.help_dialog.close()


def test_every_example_of_the_input_syntax_page_is_read_as_what_it_shows() -> None:
    """The page's examples are input the editor accepts: equations, and parametrizations where
    the page says so (README, "Parametrizations as input")."""
    from sorgui.engine.parametric_parsing import ParsedParametrization, parse_input
    from sorgui.gui.help import SYNTAX_EXAMPLES

    for text, shows in SYNTAX_EXAMPLES:
        assert isinstance(parse_input(text), ParsedParametrization) == ("parametrization" in shows), text


def test_caption_tooltips_on_results(window, run_analysis) -> None:
    from PySide6.QtWidgets import QLabel

    run_analysis(window, example_text("torus"))
    captions = [
        label
        for label in window.results.widget().findChildren(QLabel)
        if label.objectName() == "caption" and label.text()
    ]
    assert captions
    assert [label.text() for label in captions if not label.toolTip()] == []
    table = window.results.table  # every row of Table 1 says what it means; the torus's is row 1
    tips = [table.item(r, 0).toolTip() for r in range(table.rowCount())]
    assert all(tip.startswith(f"Row {r + 1}. ") for r, tip in enumerate(tips))
    assert "row of this surface" in tips[0] and not any("row of this surface" in tip for tip in tips[1:])


def test_a_no_is_explained(window, run_analysis) -> None:
    run_analysis(window, "(x^2 + y^2 - 1)((x - 3)^2 + z^2 - 1)", timeout_ms=SLOW_MS)  # crossed cylinders
    text = _pane_text(window)
    assert "Why it is not a surface of revolution" in text
    assert "Factor 1: a cylinder of revolution" in text and "Factor 2: a cylinder of revolution" in text
    assert "different axes" in text
    assert "factor_axes" in window.viewport.actor_names()
    run_analysis(window, "x^2 + 2y^2 - 1", timeout_ms=SLOW_MS)
    assert "extrusion" in _pane_text(window)
    run_analysis(
        window, example_text("non-coaxial-blend"), timeout_ms=SLOW_MS
    )  # irreducible: its typed components explain
    text = _pane_text(window)
    assert "Component 1, x^2 + y^2 + (z - 1)^2 - 4: a sphere" in text
    assert "Component 2, (x - z)^2/2 + y^2 - 1: a cylinder of revolution" in text and "no axis in common" in text
    assert "factor_axes" in window.viewport.actor_names()
    lines = window.viewport.plotter.renderer.actors["factor_axes"].GetMapper().GetInput().GetNumberOfLines()
    assert lines == 2, "the cylinder's axis and the parallel through the sphere's centre"


def test_unsaved_text_is_never_discarded_without_asking(make_window, qtbot, monkeypatch) -> None:
    window = make_window(prestart_worker=False)
    window.set_equation("x^2 + y^2 - z")
    qtbot.keyClicks(window.editor.text_edit, " + 1")
    assert window.isWindowModified()
    answers = [QMessageBox.StandardButton.Cancel]
    monkeypatch.setattr(window, "ask_to_save", lambda name: answers[0])
    typed = window.editor.text()
    example = window.examples_menu.example_actions()[1]
    example.trigger()
    assert window.editor.text() == typed, "Cancel keeps the text"
    window.new_action.trigger()
    assert window.editor.text() == typed
    assert window.close() is False and window.isVisible(), "Cancel keeps the window open"
    answers[0] = QMessageBox.StandardButton.Discard
    window.new_action.trigger()
    assert window.editor.text() == ""
    assert "*" in window.windowTitle() or window.windowTitle().startswith("Untitled")


def test_the_window_works_at_800_by_560(window, run_analysis, qtbot, artifacts) -> None:
    window.resize(700, 500)
    qtbot.wait(100)
    assert (window.width(), window.height()) == (800, 560), "the minimum size"
    run_analysis(window, example_text("paper-example-1"))
    results = window.results
    # the pane is laid out after the result is shown (a loaded machine takes longer)
    qtbot.waitUntil(lambda: results.verticalScrollBar().maximum() > 0, timeout=10_000)
    page = results.widget()
    copy = page.findChildren(FormulaView)[0].copy_button
    right = copy.mapTo(page, QPoint(copy.width(), 0)).x()
    assert right <= page.width(), "the copy buttons are inside the page"
    reachable = page.width() <= results.viewport().width() or results.horizontalScrollBar().maximum() > 0
    assert reachable, "what does not fit can be scrolled to"
    assert window.analyze_button.isVisible() and window.viewport.plotter.isVisible()
    window.grab().save(str(artifacts / "small-window.png"))


def test_a_degree_12_equation_too_long_to_typeset_is_echoed_as_people_write_it(window, run_analysis) -> None:
    """A surface of revolution of degree 12 in general position has hundreds of terms: its
    equation is shown as Unicode text (``x¹²``, not Python's ``**``), folded, and copied exactly."""
    from benchmarks.gui_heartbeat import sor_in_general_position

    run_analysis(window, sor_in_general_position(12))
    polynomial = window.session.run.analysis.recognition.polynomial
    view = window.results.views["polynomial"]
    assert not view.formula.pieces and view.formula.plain == polynomial
    shown = view.content.text()
    assert "**" not in shown and "*" not in shown and "¹²" in shown and view.folded
    view.copy_plain()
    from PySide6.QtGui import QGuiApplication

    assert QGuiApplication.clipboard().text() == polynomial


def test_analysing_the_same_equation_again_keeps_its_results_until_they_are_replaced(
    window, run_analysis, qtbot
) -> None:
    """Analyse pressed again on the shown equation: its results and its mesh stay on screen
    (the 3D header says it is being analysed again) until the new run's replace them; another
    equation's results are cleared at once."""
    from sorgui.examples import example_text

    run_analysis(window, example_text("torus"))
    assert "axis.direction" in window.results.views and window.viewport.scene is not None
    started: list[bool] = []
    window.session.events.run_started.connect(
        lambda run: started.append("axis.direction" in window.results.views and window.viewport.scene is not None)
    )
    run_analysis(window)
    assert started == [True], "the torus's results stayed while it was analysed again"
    assert "Analysing again" not in window.viewport.caption.text() and window.session.run.outcome == "finished"
    seen: list[bool] = []
    window.session.events.run_started.connect(lambda run: seen.append(window.viewport.scene is None))
    run_analysis(window, example_text("ellipsoid"))
    assert seen == [True], "another equation starts from an empty view"


def test_at_1024_by_700_every_view_control_is_on_screen_and_the_header_is_elided(window, run_analysis, qtbot) -> None:
    """The view's buttons and check boxes wrap onto more lines instead of hiding behind »,
    and a header too long for the width ends in "…" with the whole text as its tooltip."""
    from PySide6.QtWidgets import QToolButton

    window.resize(1024, 700)
    qtbot.waitUntil(lambda: window.width() <= 1100, timeout=5000)
    long_text = " + ".join(f"{k}*x^2*y^{k % 3}" for k in range(1, 40)) + " - z"
    run_analysis(window, long_text)
    viewport = window.viewport
    qtbot.wait(200)
    buttons = viewport.toolbar.findChildren(QToolButton)
    assert {b.defaultAction().iconText() for b in buttons} >= {"Section", "Reset"}
    for widget in (*buttons, viewport.deviation_box, viewport.radius_box, viewport.canal_box):
        assert widget.isVisible(), widget
        corner = widget.mapTo(viewport, widget.rect().bottomRight())
        assert 0 <= corner.x() <= viewport.width() and 0 <= corner.y() <= viewport.height(), widget
    caption = viewport.caption
    assert caption.text().startswith("f = ") and caption.toolTip() == caption.text()
    assert caption.fontMetrics().horizontalAdvance(caption.text()) > caption.width(), "long enough to be elided"
    assert caption.width() <= viewport.width()


def test_a_rebuilt_pane_is_laid_out_before_it_is_shown(window, run_analysis) -> None:
    """A page's new blocks are laid out as they are put on it: right after a rebuild, before the
    event loop turns, its rows already stand one below the other (built on screen, every row sat
    at the top over the others until the next turn)."""
    from PySide6.QtWidgets import QLabel

    run_analysis(window, example_text("cone"))
    window.results.show_message("Another page", "nothing kept from the last one")
    window.view.refresh_pane()
    page = window.results.widget()

    def span(label: QLabel) -> tuple[int, int]:
        top = label.mapTo(page, label.rect().topLeft()).y()
        return top, top + label.height() - 1

    captions = [label for label in page.findChildren(QLabel) if label.objectName() == "caption" and label.text()]
    rows = sorted(span(label) for label in captions)
    assert len(rows) > 5
    assert all(below[0] > above[1] for above, below in zip(rows, rows[1:])), rows


def _report(tmp_path: Path, text: str, *options: str) -> Path:
    """A report written by ``sorgui analyze`` (another process, as a colleague's would be)."""
    import subprocess
    import sys

    path = tmp_path / "colleague.sorgui.json"
    done = subprocess.run(
        [sys.executable, "-m", "sorgui.cli", "analyze", *options, text, "-o", str(path)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr
    return path


def test_a_lying_report_is_refused_by_the_window_naming_the_field(window, qtbot, tmp_path, monkeypatch) -> None:
    """A torus's report whose equation was changed: the window refuses it in one line (it used
    to draw the torus and export it headed with the other equation), once the process reading
    it has checked its claims."""
    import json

    shown: list[str] = []
    monkeypatch.setattr(window, "_show_error", lambda title, message: shown.append(f"{title}: {message}"))
    path = _report(tmp_path, example_text("torus"))
    data = json.loads(path.read_text(encoding="utf-8"))
    data["input"], data["polynomial"] = "x^3+y^3+z^3-1", "x**3 + y**3 + z**3 - 1"
    path.write_text(json.dumps(data), encoding="utf-8")
    with qtbot.waitSignal(window.report_reader.refused, timeout=120_000):
        assert window.open_file(str(path))
    assert len(shown) == 1 and "refused: its degree is 4" in shown[0] and "\n" not in shown[0]


def test_a_reports_export_runs_in_a_process_the_window_kills_at_its_time_limit(
    window, qtbot, tmp_path, monkeypatch
) -> None:
    """File → Export of an opened report, as the window runs it: in the export process; a STEP
    file of a degree-60 profile (a fit of seconds) is stopped at the window's time limit, here
    half a second (the process is not even started and Open CASCADE not imported by then), its
    process killed, the old file kept, and the window stays responsive; a JSON export of the same
    report then goes through a new process and is written."""
    pytest.importorskip("OCP")
    report = _report(tmp_path, "(x^2+y^2)^30+z^60-1", "--recognition-only")
    with qtbot.waitSignal(window.result_shown, timeout=120_000):
        assert window.open_file(str(report))
    failures: list[str] = []
    monkeypatch.setattr(window, "_show_error", lambda title, message: failures.append(f"{title}: {message}"))
    step = tmp_path / "part.step"
    step.write_text("the old file\n", encoding="ascii")
    monkeypatch.setattr(window, "ask_export_path", lambda _suffix: str(step))
    window.time_limit = 0.5
    with qtbot.waitSignal(window.cad_export.failed, timeout=60_000):
        window._export_results()
        assert window.cad_export.busy
        pid = window.cad_export.pid
        assert pid is not None and pid != __import__("os").getpid()
        qtbot.wait(200)
        assert window.isEnabled()  # the window answers while the file is written
    assert failures and "not written within the time limit of 0.5 s" in failures[0]
    assert not Path(f"/proc/{pid}").exists() or "Z" in Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1][:3]
    assert step.read_text(encoding="ascii") == "the old file\n"
    assert [p for p in tmp_path.iterdir() if ".tmp" in p.name] == []
    again = tmp_path / "again.json"
    window.time_limit = 120.0
    monkeypatch.setattr(window, "ask_export_path", lambda _suffix: str(again))
    with qtbot.waitSignal(window.cad_export.written, timeout=120_000):
        window._export_results()
    assert again.exists() and not window.cad_export.busy


def test_an_endless_device_opened_as_an_equation_is_refused_in_one_line(window, monkeypatch) -> None:
    """File → Open of ``/dev/zero``: its size says 0 and it never ends; read only up to the limit
    (it was read whole: a MemoryError)."""
    if not Path("/dev/zero").exists():
        pytest.skip("no /dev/zero")
    shown: list[str] = []
    monkeypatch.setattr(window, "_show_error", lambda title, message: shown.append(f"{title}: {message}"))
    assert not window.open_file("/dev/zero")
    assert len(shown) == 1 and "too large" in shown[0] and "\n" not in shown[0]
