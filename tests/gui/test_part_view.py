"""File → Open of a CAD part in the real window: the part drawn with its recognised axes, the
report beside it, a bad file said in the window, the canonical part and the report saved."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

pytest.importorskip("OCP")

from sorgui.cad.reading import read_part  # noqa: E402
from sorgui.cad.writers import WRITERS, CadHeader  # noqa: E402
from tests.cad import parts  # noqa: E402

pytestmark = pytest.mark.gui


def part_windows(window):  # noqa: ANN001, ANN201
    from sorgui.gui.part_view import PartWindow

    return [w for w in window.findChildren(PartWindow) if w.isVisible()]


@pytest.fixture
def boolean_step(tmp_path: Path) -> Path:
    path = tmp_path / "boolean.step"
    path.write_bytes(WRITERS[".step"](parts.boolean_part(), CadHeader("", ("test",), "0", path.name)))
    return path


def test_open_a_part(window, qtbot, boolean_step: Path, tmp_path: Path, artifacts: Path) -> None:
    assert window.open_file(str(boolean_step))
    (shown,) = part_windows(window)
    qtbot.waitExposed(shown)
    with qtbot.waitSignal(shown.shown, timeout=120_000) as blocker:
        pass
    report = blocker.args[0]
    assert report is not None and len(report.faces) == 9
    assert shown.text.toPlainText().startswith(f"{boolean_step}: STEP, 9 faces")
    assert "one surface of revolution about the axis" in shown.text.toPlainText()
    assert {"part", "axis-1"} <= set(shown.plotter.actors)
    assert "9 faces" in shown.statusBar().currentMessage()
    shown.plotter.screenshot(str(artifacts / "part-view.png"))
    window.grab().save(str(artifacts / "part-main-window.png"))
    shown.grab().save(str(artifacts / "part-window.png"))

    shown.save_report(tmp_path / "faces.json")
    assert json.loads((tmp_path / "faces.json").read_text())["faces"][8]["face"] == 9
    with qtbot.waitSignal(shown.runner.finished, timeout=120_000):
        shown.save_canonical(tmp_path / "canonical.step")
    assert "Wrote" in shown.statusBar().currentMessage()
    assert len(read_part(tmp_path / "canonical.step").faces) == 9
    shown.close()


def test_a_bad_part_is_said_in_its_window(window, qtbot, tmp_path: Path) -> None:
    bad = tmp_path / "bad.step"
    bad.write_text("not a part\n")
    assert window.open_file(str(bad))
    (shown,) = part_windows(window)
    with qtbot.waitSignal(shown.shown, timeout=120_000) as blocker:
        pass
    assert blocker.args[0] is None
    assert "is not a STEP file" in shown.text.toPlainText()
    shown.close()


def test_a_face_open_cascade_cannot_evaluate_is_one_line_of_the_window(window, qtbot, tmp_path, artifacts) -> None:  # noqa: ANN001
    """The part is drawn and reported; the face Open CASCADE cannot evaluate has its own line."""
    path = tmp_path / "broken.brep"
    path.write_bytes(WRITERS[".brep"](parts.unevaluable(), CadHeader("", (), "0", path.name)))
    assert window.open_file(str(path))
    (shown,) = part_windows(window)
    with qtbot.waitSignal(shown.shown, timeout=120_000) as blocker:
        pass
    assert blocker.args[0] is not None and len(blocker.args[0].faces) == 2
    text = shown.text.toPlainText()
    assert "cannot be evaluated: Open CASCADE raises Geom_Undefined" in text and "surface of revolution" in text
    shown.grab().save(str(artifacts / "part-window-unevaluable.png"))
    shown.close()


def test_closing_the_window_kills_its_process(window, qtbot, tmp_path: Path) -> None:
    path = tmp_path / "shaft.step"
    path.write_bytes(WRITERS[".step"](parts.turned_part(), CadHeader("", (), "0", path.name)))
    assert window.open_file(str(path))
    (shown,) = part_windows(window)
    assert shown.runner.busy
    shown.close()
    assert not shown.runner.busy
