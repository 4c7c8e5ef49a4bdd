"""What the window says (issue 30), each in a real window with a real VTK render window, a real
worker process and the real typesetting process: stages ticked only when finished, rounded input
shown as typed, one deviation figure, the canal section of rounded input, r²(t), errors after
rounded input, a time limit met, a report opened, the drawn ball and its box, rows typeset in
place, the whole of a bounded surface in the ball, readable base curves, the export formats by
name, and formulas readable before they are typeset, the visible ones typeset first."""

from __future__ import annotations

import math
import time
from pathlib import Path

import numpy as np
import pytest
from PySide6.QtWidgets import QApplication, QFileDialog

from benchmarks.window import rounded_degree_12, three_tori, turned_torus
from sorgui.examples import example_text
from sorgui.session.model import StageState
from tests.gui.conftest import export_through_window, typeset_all
from tests.gui.test_canal import pane_text

pytestmark = pytest.mark.gui

SLOW_MS = 300_000
"""A loaded test machine must not cut an analysis short."""


def test_the_rounded_torus_ticks_a_stage_only_when_it_is_done_and_its_times_agree(
    window, run_analysis, qtbot, artifacts
) -> None:
    """While the rounded torus runs, no ticked stage runs again or has its time grow, the run is
    never all ticked before it ends, and at the end the Timings section, the stage line and
    "Done in" give the same figures. Screenshots before, during and after its run."""
    text = turned_torus()
    window.set_equation(text)
    qtbot.wait(200)
    window.grab().save(str(artifacts / "rounded-torus-before.png"))
    ticked: dict[str, float] = {}
    problems: list[str] = []
    grabbed: list[bool] = []

    def seen(_name: str, _state: StageState) -> None:
        run = window.session.run
        for stage in run.stage_list():
            if stage.state is StageState.DONE:
                if stage.name in ticked and abs(ticked[stage.name] - stage.seconds) > 1e-9:
                    problems.append(f"{stage.name}: {ticked[stage.name]} → {stage.seconds}")
                ticked[stage.name] = stage.seconds
        done, total = run.progress
        if run.running and done == total:
            problems.append("all stages ticked while running")
        if run.running and not grabbed and run.scene is not None:
            grabbed.append(True)
            window.grab().save(str(artifacts / "rounded-torus-during.png"))

    window.session.events.state_changed.connect(seen)
    run_analysis(window, text, timeout_ms=SLOW_MS)
    qtbot.waitUntil(lambda: window.session.run.outcome is not None, timeout=SLOW_MS)
    assert problems == []
    run = window.session.run
    assert "Typesetting" not in window.run_panel.stage_line.text()
    typeset_all(window, qtbot)
    qtbot.wait(300)
    window.grab().save(str(artifacts / "rounded-torus-after.png"))
    done = {s.name: s.seconds for s in run.stage_list() if s.state is StageState.DONE}
    timings = _section_rows(window, "Timings")
    from sorgui.gui.stages import seconds_text

    for name, seconds in done.items():
        assert timings[name] == seconds_text(seconds), name
        assert f"{seconds_text(seconds)}" in window.run_panel.stage_line.text()
    assert timings["wall time"] == seconds_text(run.elapsed())
    assert window.stage_label.text().startswith(f"Done in {run.elapsed():.2f} s")


def _section_rows(window, heading: str) -> dict[str, str]:  # noqa: ANN001
    """The caption → text rows of one section of the results pane."""
    from PySide6.QtWidgets import QGridLayout, QLabel

    for block in window.results.page.blocks:
        title = block.widget.findChild(QLabel, "sectionHeading")
        if title is None or title.text() != heading:
            continue
        grid = block.widget.findChild(QGridLayout)
        rows = {}
        for row in range(grid.rowCount()):
            caption, value = grid.itemAtPosition(row, 0), grid.itemAtPosition(row, 1)
            if caption is not None and value is not None and isinstance(value.widget(), QLabel):
                rows[caption.widget().text()] = value.widget().text()
        return rows
    raise AssertionError(f"no section {heading!r}")


def test_rounded_input_is_shown_in_decimals_as_typed_and_long_equations_are_folded(window, run_analysis, qtbot) -> None:
    """The rounded torus's equation in decimals, not in the exact rationals read off them; a
    rounded degree-12 equation folded behind "show all" like an exact one."""
    run_analysis(window, turned_torus(), timeout_ms=SLOW_MS)
    view = window.results.views["polynomial"]
    shown = view.content.text() if not view.shows_typeset else view.formula.text
    assert "4.979408572x²" in shown and "/" not in shown and "2236446019" not in shown
    run_analysis(window, rounded_degree_12(), timeout_ms=SLOW_MS)
    view = window.results.views["polynomial"]
    assert view.folded and "show all" in view.show_all_button.text()
    assert view.height() < 300, "folded to a few lines, not a column of fractions"


def test_the_nearest_surface_has_one_axis_point_a_normalised_axis_and_one_deviation_figure(
    window, run_analysis, qtbot
) -> None:
    """The approximate axis and the nearest axis in decimals are unit vectors; in the nearest
    exact surface's view the axis point is its profile frame's point, and the frame's ``a`` has
    the axis direction's sign; the same torus is as far from a surface of revolution with the
    automatic tolerance as with 1e-14 (one figure, to two digits)."""
    text = turned_torus()
    run_analysis(window, text, timeout_ms=SLOW_MS)
    qtbot.waitUntil(lambda: window.session.nearest_analysis is not None, timeout=SLOW_MS)
    for key in ("approximate.axis", "approximate.nearest.axis.decimal"):
        plain = window.results.views[key].formula.plain
        direction = [float(v) for v in plain.split("+ t*")[1].strip("()").split(",")]
        assert math.isclose(np.linalg.norm(direction), 1.0, rel_tol=1e-9), plain
    nearest = window.session.nearest_analysis.recognition
    assert nearest.axis.point == nearest.profile.frame_point
    from fractions import Fraction

    axis = [Fraction(v) for v in nearest.axis.direction]
    frame = [Fraction(v) for v in nearest.profile.frame_direction]
    assert sum(a * b for a, b in zip(axis, frame)) > 0
    auto = window.session.run.analysis.approximate.relative_distance
    window.tolerance = 1e-14
    run_analysis(window, text, timeout_ms=SLOW_MS)
    given = window.session.run.analysis.approximate
    assert not given.near_sor and f"{given.relative_distance:.2g}" == f"{auto:.2g}"
    assert f"{auto:.2g} away" in window.results.banner.text() or f"{auto:.2g}" in pane_text(window)


def test_the_canal_section_of_rounded_input_opens_with_the_nearest_surfaces_verdict(
    window, run_analysis, qtbot
) -> None:
    run_analysis(window, turned_torus(), timeout_ms=SLOW_MS)
    qtbot.waitUntil(lambda: "not exactly canal, but nearly" in pane_text(window), timeout=SLOW_MS)
    rows = _section_rows(window, "Canal surface")
    assert list(rows)[0] == "canal" and rows["canal"].startswith("not exactly canal, but nearly")
    assert rows["exactly"].startswith("not a canal surface")


def test_a_squared_radius_that_varies_is_r_squared_of_t(window, run_analysis, qtbot) -> None:
    """The quadric cone's and the torus's second family's squared radius is r²(t), not ρ(t)."""
    from PySide6.QtWidgets import QLabel

    for name in ("cone", "torus"):
        run_analysis(window, example_text(name))
        captions = {label.text() for label in window.results.widget().findChildren(QLabel, "caption")}
        assert "r²(t)" in captions and "ρ(t)" not in captions, name
        radius = [k for k in window.results.views if k.endswith(".radius") and k.startswith("canal.")]
        assert radius and all(window.results.views[k].formula.text.startswith("r²(t) =") for k in radius)


def test_after_rounded_input_an_error_hides_the_view_switch_and_says_its_reason(window, run_analysis, qtbot) -> None:
    run_analysis(window, turned_torus(), timeout_ms=SLOW_MS)
    qtbot.waitUntil(lambda: window.run_panel.view_row.isVisible(), timeout=SLOW_MS)
    window.set_equation("x^200")
    assert not window.analyze()
    assert not window.run_panel.view_row.isVisible()
    assert "degree" in window.viewport.caption.text() and "not a polynomial" not in window.viewport.caption.text()
    window.set_equation("")
    assert not window.analyze()
    assert window.viewport.caption.text() == "No surface: there is no equation"
    assert not window.run_panel.view_row.isVisible()


def test_a_time_limit_met_is_said_and_not_taken_for_a_finished_analysis(window, qtbot) -> None:
    """Analysis → Time Limit… 3 s on an equation whose Singular stages take longer: the stages
    cut short say so, a notice says the limit was met, the status line does not say "Done", and
    the canal section says it is undecided."""
    slow = (Path(__file__).resolve().parents[1] / "data" / "slow-singular.txt").read_text(encoding="utf-8").strip()
    window.set_equation(slow)
    window.time_limit = 3.0
    done: list[object] = []
    window.result_shown.connect(done.append)
    window.worker.failed.connect(done.append)
    assert window.analyze()
    qtbot.waitUntil(lambda: window.session.run.outcome is not None, timeout=60_000)
    run = window.session.run
    assert run.outcome == "finished" and run.limited, run.message
    unfinished = run.unfinished()
    assert unfinished
    line = window.run_panel.stage_line.text()
    assert all(f"{stage.title}" in line for stage in unfinished) and "not finished within 3 s" in line
    assert window.run_panel.notice_kind == "limit" and "time limit of 3 s" in window.run_panel.notice.text()
    assert not window.stage_label.text().startswith("Done") and "time limit" in window.stage_label.text()
    assert "so far" not in window.stage_label.text()  # the verdict of a finished recognition is final
    if "canal" in {s.name for s in unfinished}:
        assert "not finished within the time limit of 3 s" in pane_text(window)


def test_a_time_limit_met_before_the_recognition_shows_the_equation_as_undecided(window) -> None:
    """A limit met while the equation is still being recognised leaves the analysis the process
    sent once the equation was read (no factor yet): the pane shows it as undecided, neither
    "not a surface of revolution" nor "dim L = 0", with no factor section (it indexed the first
    factor: IndexError, the pane left at "Analysing…", seen under load with a limit of 3 s)."""
    from sorgui.engine.parsing import parse_polynomial
    from sorgui.engine.timelimit import skeleton, unfinished_analysis
    from sorgui.session.job import JobRequest
    from sorgui.session.model import Run

    text = "x^2 + y^2 + z^4 - 1"
    start = skeleton(parse_polynomial(text).polynomial, text=text, method="symmetry")
    assert start.factors == ()
    window.results.show_analysis(start, unfinished={"recognition", "canal"}, limit=3.0)
    text_shown = pane_text(window)
    assert "Analysing" not in text_shown and "Factor" not in text_shown
    assert ">Undecided within the time limit<" in window.results.banner.text()
    assert "not a surface of revolution" not in text_shown.lower() and "dim L" not in text_shown
    assert "not finished within the time limit of 3 s" in text_shown
    limited = unfinished_analysis(
        start, recognition=None, latest=None, timings=(), current="recognition", message="", recognition_only=False
    )
    run = Run(text, JobRequest(text, singular_timeout=3.0), analysis=limited, outcome="finished")
    window.view._on_run_finish_change(run)
    status = window.stage_label.text()
    assert status.startswith("Stopped at the time limit of 3 s") and "not a surface" not in status, status
    assert "undecided whether it is a surface of revolution" in status, status


def test_a_report_is_shown_as_saved_and_its_stages_are_not_replayed(window, run_analysis, qtbot, tmp_path) -> None:
    run_analysis(window, example_text("torus"))
    report = export_through_window(window, qtbot, tmp_path / "torus.json")
    with qtbot.waitSignal(window.result_shown, timeout=120_000):
        assert window.open_report(str(report))
    qtbot.waitUntil(lambda: window.session.run.outcome == "finished", timeout=60_000)
    qtbot.wait(300)
    assert window.run_panel.notice_kind == "report"
    assert "not analysed again" in window.run_panel.notice.text()
    assert window.run_panel.stage_line.text() == "" and not window.run_panel.progress_bar.isVisible()
    assert "not analysed again" in window.stage_label.text() and not window.stage_label.text().startswith("Done")
    assert "recognition" not in window.session.run.stages


def test_the_ball_radius_is_not_a_number_before_a_ball_is_drawn_and_a_box_is_framed(window, qtbot) -> None:
    """During the first analysis the radius box says "automatic" (not "ball radius 0.001"); a
    box chosen with View → Cut to a Box is framed afresh."""
    window.set_equation(example_text("paper-example-1"))
    window.analyze()
    assert window.viewport.radius_box.text() == "ball radius: automatic"
    qtbot.waitUntil(lambda: window.session.run.outcome == "finished", timeout=SLOW_MS)
    qtbot.waitUntil(lambda: window.viewport.scene is not None, timeout=10_000)
    assert window.viewport.radius_box.text().startswith("ball radius 7.")
    before = window.viewport.camera_state()
    assert window.cut_to_box((0.0, 2.0, -1.0, 1.0, -1.0, 1.0))
    qtbot.waitUntil(lambda: window.viewport.scene is not None and window.viewport.scene.box is not None, timeout=60_000)
    qtbot.wait(200)
    after = window.viewport.camera_state()
    assert not np.allclose(before.position, after.position), "the view is zoomed onto the box"


def test_rows_grow_with_their_typeset_picture(window, run_analysis, qtbot, artifacts) -> None:
    """Every formula row is as tall as what it shows once typeset (not clipped to half a line),
    the axis "line" and "Plücker" rows too."""
    run_analysis(window, example_text("paper-example-1"))
    typeset_all(window, qtbot)
    qtbot.wait(200)
    for key, view in window.results.views.items():
        shown = view.content.sizeHint().height()
        assert view.height() >= shown, (key, view.height(), shown)
    window.grab().save(str(artifacts / "rows-typeset.png"))


def test_the_ball_holds_the_whole_of_three_coaxial_tori(window, run_analysis) -> None:
    """The exact product of three tori about the z-axis at heights −6, 0, 6, minus 1000: the
    automatic ball holds every torus (their points reach 8.06 from the centre), none cut open."""
    run_analysis(window, three_tori())
    scene = window.viewport.scene
    assert scene.region.radius > math.hypot(4, 7)
    heights = scene.surface.points[:, 2]
    assert heights.max() > 6.9 and heights.min() < -6.9


def test_base_curves_are_said_in_lengths_and_shapes(window, run_analysis) -> None:
    """A cylinder's section in unit axes, as an ellipse with its centre (a point of the section
    plane) and semi-axes; a cone's chart curve relative to its apex, with its opening."""
    run_analysis(window, "(x-y+1)^2 + (y - 2z)^2 - 3")
    rows = _section_rows(window, "Cone or cylinder")
    assert rows["section"].startswith("an ellipse, centre (-0.5556, 0.4444, 0.2222), semi-axes 1.33 and 0.7522")
    assert "are lengths along" in rows["in unit axes"]
    run_analysis(window, "(x-1)^2+(y-2)^2-4(z-3)^2")
    rows = _section_rows(window, "Cone or cylinder")
    assert "apex (1, 2, 3)" in rows["relative to the apex"]
    assert rows["at z = 1"] == "a circle, centre apex + (0, 0, 1), radius 2"
    assert "half-angle 63.43°" in rows["opening"]


def test_file_export_offers_step_iges_and_brep_by_name(window, run_analysis, qtbot, tmp_path) -> None:
    """File → Export CAD File has STEP, IGES and BRep; in the Export dialog, choosing a file type
    changes the name's suffix with it."""
    run_analysis(window, example_text("torus"))
    names = [action.text() for action in window.cad_menu.actions()]
    assert names == ["STEP (.step)…", "IGES (.iges)…", "BRep (.brep)…"]
    chosen: list[str] = []

    def answer() -> None:
        dialog = QApplication.activeModalWidget()
        if not isinstance(dialog, QFileDialog):
            _later(answer)
            return
        chosen.append(dialog.selectedFiles()[0])
        iges = next(f for f in dialog.nameFilters() if f.startswith("IGES") and "*.iges" in f)
        dialog.selectNameFilter(iges)
        dialog.filterSelected.emit(iges)
        chosen.append(dialog.selectedFiles()[0])
        dialog.setDirectory(str(tmp_path))
        dialog.reject()

    _later(answer)
    assert window.ask_export_path(".step") is None
    assert chosen[0].endswith("sorgui-results.step") and chosen[1].endswith("sorgui-results.iges"), chosen


def _later(slot) -> None:  # noqa: ANN001
    from PySide6.QtCore import QTimer

    QTimer.singleShot(100, slot)


def test_every_formula_is_readable_before_it_is_typeset_and_the_visible_ones_are_typeset_first(
    window, run_analysis, qtbot, monkeypatch
) -> None:
    """Without the typesetting process every row reads as Unicode math; with it, the rows on
    screen are asked for first."""
    asked: list[list[tuple[str, ...]]] = []
    original = window.typesetter.request

    def request(formulas, style) -> None:  # noqa: ANN001
        asked.append(list(formulas))
        original(formulas, style)

    monkeypatch.setattr(window.typesetter, "request", request)
    window.typesetter._known.clear()
    run_analysis(window, example_text("paper-example-1"))
    results = window.results
    results.verticalScrollBar().setValue(results.verticalScrollBar().maximum())
    asked.clear()
    results.ask_typesetter()
    page = results.widget()
    seen = results.viewport().rect().translated(0, results.verticalScrollBar().value())
    from PySide6.QtCore import QRect

    untypeset = [v for v in results.views.values() if v.formula.pieces and not v.shows_typeset]
    visible = [
        v.formula.pieces for v in untypeset if QRect(v.mapTo(page, v.rect().topLeft()), v.size()).intersects(seen)
    ]
    if asked and visible:
        assert set(asked[-1][: len(visible)]) == set(visible)
    for view in results.views.values():
        if not view.shows_typeset:
            text = view.content.text()
            assert text and "**" not in text and "*" not in text, text
    start = time.monotonic()
    typeset_all(window, qtbot)
    assert time.monotonic() - start < 60


def test_a_note_holding_a_long_formula_wraps_in_a_narrow_window(window, run_analysis, qtbot) -> None:
    """A rationality note holds the map through T, 20-digit numbers times square roots: one
    word of 50 characters, and the pane scrolled sideways in a window 800 pixels wide."""
    window.resize(800, 900)
    qtbot.wait(200)
    text = "(x^2+y^2+z^2)-(12345*x+67891*y+23456*z)^2/(12345^2+67891^2+23456^2)-1/3"
    run_analysis(window, text, timeout_ms=SLOW_MS)
    assert any("map through T" in note for note in window.session.run.analysis.rationality.notes)
    qtbot.wait(500)  # laid out
    assert window.results.horizontalScrollBar().maximum() == 0
    assert "map through T" in pane_text(window).replace("\u200b", "")
