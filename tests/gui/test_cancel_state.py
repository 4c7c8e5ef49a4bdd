"""What the window says after Esc: the 3D header, the banner, the notice, the ball-radius box
and the results pane agree with what was done before the analysis was stopped. Real window,
real worker processes; a ``Singular`` that never answers, or one long flint factorization,
keeps the analysis running until it is cancelled."""

from __future__ import annotations

import pytest
from PySide6.QtWidgets import QLabel

from sorgui.examples import example_text
from sorgui.session import StageState

pytestmark = pytest.mark.gui


def _pane_text(window) -> str:  # noqa: ANN001
    return "\n".join(label.text() for label in window.results.widget().findChildren(QLabel))


def test_cancel_after_the_verdict_keeps_it_and_says_what_stopped(
    make_window, qtbot, monkeypatch, hanging_singular, artifacts
) -> None:
    window = make_window(prestart_worker=False)
    monkeypatch.setenv("SORGUI_SINGULAR", str(hanging_singular))
    window.set_equation(example_text("paper-example-1"))
    assert window.analyze()
    qtbot.waitUntil(lambda: window.viewport.scene is not None, timeout=60_000)
    qtbot.waitUntil(lambda: window.session.run.stages["rationality"].state is StageState.RUNNING, timeout=60_000)
    with qtbot.waitSignal(window.worker.cancelled, timeout=10_000):
        window.cancel()
    qtbot.wait(200)
    assert window.viewport.caption.text().startswith("f = "), "the drawn surface is named, not 'Analysing'"
    assert window.viewport.radius_box.isEnabled(), "the drawn ball can still be changed"
    assert "Surface of revolution" in window.results.banner.text()
    notice = window.run_panel.notice.text()
    assert window.run_panel.notice_kind == "cancelled" and "what was done is shown" in notice
    assert "nothing was finished" not in notice
    text = _pane_text(window)
    assert "being decided" not in text, "no stage is said to be still coming"
    assert "(3/5, -4/5, 0)" in window.results.plain_text()
    window.save_screenshots(artifacts / "cancelled-window.png", artifacts / "cancelled-viewport.png")


def test_cancel_before_anything_is_drawn_leaves_no_analysing_header(make_window, qtbot) -> None:
    from tests.long_c_call import factored_product

    window = make_window()
    stages: list[str] = []
    window.worker.progress.connect(stages.append)
    window.set_equation(factored_product())
    assert window.analyze()
    qtbot.waitUntil(lambda: "factors" in stages, timeout=120_000)
    with qtbot.waitSignal(window.worker.cancelled, timeout=10_000):
        window.cancel()
    qtbot.wait(200)
    assert not window.viewport.caption.text().startswith("Analysing"), window.viewport.caption.text()
    assert "cancelled" in window.viewport.caption.text().lower(), window.viewport.caption.text()
    assert not window.viewport.radius_box.isEnabled(), "no ball is drawn"
    assert ">Cancelled<" in window.results.banner.text()
    done = sum(1 for s in window.session.run.stage_list() if s.state is StageState.DONE)
    notice = window.run_panel.notice.text()
    assert ("nothing was finished" in notice) is (done == 0)
    assert window.stage_label.text() == "Cancelled"
