"""File → Export in every format, File → Open of a saved report, and Save Picture, in the real window."""

from __future__ import annotations

import dataclasses
import json
import subprocess
import sys

import numpy as np
import pytest
import pyvista
from PySide6.QtGui import QImage

from sorgui.engine import analyze
from sorgui.export.formats import FORMATS
from sorgui.export.reports import read_report
from tests.gui.conftest import export_through_window

pytestmark = pytest.mark.gui

TORUS = "(x^2 + y^2 + z^2 + 8)^2 - 36(x^2 + y^2)"


def test_every_format_is_exported_from_the_window(window, run_analysis, qtbot, tmp_path) -> None:
    run_analysis(window, TORUS)
    for suffix in FORMATS:
        export_through_window(window, qtbot, tmp_path / f"{'report' if suffix == '.md' else 'torus'}{suffix}")
    assert read_report(tmp_path / "torus.json").recognition.polynomial == analyze(TORUS).recognition.polynomial
    # the drawn ball meshed on the command line's grid (the window draws coarser in software
    # OpenGL, and its STL had a third of the command line's triangles)
    from sorgui.session.scene_data import build_scene

    scene = window.viewport.scene
    command_line = build_scene(window.session.run.analysis, region=scene.region).surface
    assert pyvista.read(tmp_path / "torus.stl").n_cells == command_line.n_faces >= scene.surface.n_faces
    export_through_window(window, qtbot, tmp_path / "torus.patch.ply")
    assert pyvista.read(tmp_path / "torus.patch.ply").n_cells > 100
    markdown = (tmp_path / "report.md").read_text(encoding="utf-8")
    assert "![The surface and its axis](report.png)" in markdown  # the view's picture beside it
    assert QImage(str(tmp_path / "report.png")).width() == 1200
    assert QImage(str(tmp_path / "torus.png")).width() == 1200  # .png itself: the view, as for the reports
    assert 'src="data:image/png;base64,' in (tmp_path / "torus.html").read_text(encoding="utf-8")
    assert "def X1(s, t):" in (tmp_path / "torus.py").read_text(encoding="utf-8")


def test_saved_report_opens_without_analysing_again(window, qtbot, tmp_path) -> None:
    """The report's own timings come back unchanged: a new analysis would have measured new ones."""
    analysis = dataclasses.replace(analyze(TORUS), timings=(("recorded", 123.25),))
    path = tmp_path / "torus.sorgui.json"
    path.write_text(json.dumps(analysis.to_json()), encoding="utf-8")
    with qtbot.waitSignal(window.result_shown, timeout=90_000):
        assert window.open_file(str(path))
    shown = window.session.run.analysis
    assert shown == analysis and shown.timings == (("recorded", 123.25),)
    assert window.editor.text() == analysis.input
    assert window.viewport.scene is not None and window.viewport.scene.surface.n_faces > 1000
    assert "Surface of revolution" in window.results.plain_text() or analysis.is_sor
    assert window.windowTitle().startswith("torus.sorgui.json (report)")
    assert str(path.resolve()) in window.settings.recent_files


def test_a_file_that_is_not_a_report_is_refused_with_a_dialog(window, qtbot, tmp_path, monkeypatch) -> None:
    shown: list[str] = []
    monkeypatch.setattr(window, "_show_error", lambda title, message: shown.append(f"{title}: {message}"))
    bad = tmp_path / "notes.json"
    bad.write_text("[1, 2", encoding="utf-8")
    with qtbot.waitSignal(window.report_reader.refused, timeout=120_000):
        assert window.open_file(str(bad))  # read in a process of its own, which refuses it
    assert shown and shown[0].startswith("Cannot open report:") and "notes.json" in shown[0]


def test_a_batch_results_file_opens_the_result_of_the_line_asked_for(window, qtbot, tmp_path, monkeypatch) -> None:
    """File → Open of a ``.jsonl`` asks for the input line; a line the file lacks is refused in
    one line, and a cancelled question reads nothing."""
    lines = tmp_path / "lines.txt"
    lines.write_text("x^2 + y^2 - z\n# a comment\n" + TORUS + "\n", encoding="utf-8")
    results = tmp_path / "results.jsonl"
    batch = [sys.executable, "-m", "sorgui.cli", "analyze", "--each-line", "-f", str(lines), "-o", str(results)]
    assert subprocess.run(batch, capture_output=True, timeout=300).returncode == 0
    asked: list[int | None] = [None]
    monkeypatch.setattr(window, "ask_result_line", lambda path: asked[0])
    assert not window.open_file(str(results)) and not window.report_reader.busy  # cancelled
    asked[0] = 3
    with qtbot.waitSignal(window.result_shown, timeout=120_000):
        assert window.open_file(str(results))
    assert window.editor.text() == TORUS and window.session.run.analysis.is_sor
    assert window.windowTitle().startswith("results.jsonl, line 3 (report)")
    shown: list[str] = []
    monkeypatch.setattr(window, "_show_error", lambda title, message: shown.append(message))
    asked[0] = 2
    with qtbot.waitSignal(window.report_reader.refused, timeout=120_000):
        assert window.open_file(str(results))
    assert shown == [f"{results} holds no result of input line 2"]
    with qtbot.waitSignal(window.result_shown, timeout=120_000):  # as sorgui open RESULTS.jsonl --line 1 shows it
        window.show_report(str(results), read_report(results, 1), 1)
    assert window.windowTitle().startswith("results.jsonl, line 1 (report)") and window.editor.text() == "x^2 + y^2 - z"


def pixels(path) -> np.ndarray:  # noqa: ANN001
    image = QImage(str(path)).convertToFormat(QImage.Format.Format_RGBA8888)
    data = np.frombuffer(image.constBits(), dtype=np.uint8, count=image.sizeInBytes())
    return data.reshape(image.height(), image.bytesPerLine() // 4, 4)[:, : image.width()].copy()  # own the pixels


def count_color(image: np.ndarray, color: str, tolerance: int = 40) -> int:
    rgb = np.array([int(color[i : i + 2], 16) for i in (1, 3, 5)])
    return int((np.abs(image[..., :3].astype(int) - rgb).max(axis=-1) <= tolerance).sum())


def test_picture_has_the_chosen_width_a_transparent_background_and_only_visible_actors(
    window, run_analysis, tmp_path, artifacts
) -> None:
    from sorgui.gui.viewport import PATCH_COLOR

    run_analysis(window, TORUS)
    window.viewport.patch_box.setChecked(True)
    with_patch = window.save_picture(tmp_path / "patch.png", width=1500, transparent=True)
    image = pixels(with_patch)
    assert image.shape[1] == 1500
    assert image[0, 0, 3] == 0 and image[-1, -1, 3] == 0  # transparent corners
    assert image[..., 3].max() == 255  # the surface itself is opaque
    window.viewport.patch_box.setChecked(False)
    without = pixels(window.save_picture(tmp_path / "plain.png", width=1500, transparent=True))
    assert count_color(image, PATCH_COLOR) > 20 * max(1, count_color(without, PATCH_COLOR))
    opaque = pixels(window.save_picture(artifacts / "torus-picture.png", width=1600))
    assert opaque.shape[1] == 1600 and opaque[0, 0, 3] == 255


def test_export_dialog_offers_every_format_and_the_patches() -> None:
    from sorgui.gui.exporting import export_filters, suffix_of_filter

    filters = export_filters().split(";;")
    assert len(filters) == len(FORMATS) + sum(form.has_patch for form in FORMATS.values())
    assert suffix_of_filter("STEP AP242 (B-rep), parametric patch (*.patch.step)") == ".patch.step"
    assert suffix_of_filter("STL mesh (binary), parametric patch (*.patch.stl)") == ".patch.stl"
    assert suffix_of_filter("STL mesh (binary) (*.stl)") == ".stl"
    assert suffix_of_filter("Python module (NumPy and SymPy) (*.py)") == ".py"


def test_exporting_markdown_asks_before_replacing_its_picture(window, run_analysis, tmp_path, monkeypatch) -> None:
    """File → Export of ``part.md`` beside an existing ``part.png``: the picture is replaced only
    after the window asks (the file dialog asked about the report alone)."""
    from PySide6.QtWidgets import QMessageBox

    run_analysis(window, TORUS)
    picture = tmp_path / "part.png"
    picture.write_bytes(b"the user's own picture")
    monkeypatch.setattr(window, "ask_export_path", lambda _suffix: str(tmp_path / "part.md"))
    asked: list[str] = []
    monkeypatch.setattr(
        QMessageBox, "question", lambda *args, **_kw: asked.append(args[2]) or QMessageBox.StandardButton.Cancel
    )
    window._export_results()
    assert asked and "part.png" in asked[0]
    assert picture.read_bytes() == b"the user's own picture" and not (tmp_path / "part.md").exists()


def test_every_export_of_the_menu_is_written_in_the_background(
    window, run_analysis, qtbot, tmp_path, monkeypatch
) -> None:
    """File → Export of LaTeX runs in the export process as CAD files do: sympy's printing of a
    large equation took 25 s on the GUI thread, the window frozen meanwhile."""
    run_analysis(window, TORUS)
    path = tmp_path / "torus.tex"
    monkeypatch.setattr(window, "ask_export_path", lambda _suffix: str(path))
    with qtbot.waitSignal(window.cad_export.written, timeout=120_000):
        window._export_results(".tex")
        assert window.cad_export.busy and window.cad_export.pid != __import__("os").getpid()
    assert path.read_text(encoding="utf-8").startswith("\\documentclass")
    assert window.statusBar().currentMessage().startswith(f"Exported {path}")


def _without_time_stamp(step: str) -> str:
    """A STEP file without its FILE_NAME entry (the time of writing)."""
    start = step.index("FILE_NAME(")
    return step[:start] + step[step.index(";", start) :]


def test_a_cad_file_is_written_in_the_background_as_the_command_line_writes_it(
    window, run_analysis, qtbot, tmp_path
) -> None:
    """File → Export to STEP runs in a process of its own (the window stays responsive) and writes
    the same file as ``sorgui analyze -o``, but for the time stamp."""
    pytest.importorskip("OCP")
    run_analysis(window, TORUS)
    (tmp_path / "window").mkdir()
    (tmp_path / "cli").mkdir()
    ours = tmp_path / "window" / "part.step"  # one name: the file's name is its product's
    with qtbot.waitSignal(window.cad_export.written, timeout=120_000):
        window.export_in_background(ours)
        assert window.cad_export.busy
    theirs = tmp_path / "cli" / "part.step"
    done = subprocess.run(
        [sys.executable, "-m", "sorgui.cli", "analyze", TORUS, "-o", str(theirs)], capture_output=True, timeout=300
    )
    assert done.returncode == 0, done.stderr
    assert _without_time_stamp(ours.read_text(encoding="ascii")) == _without_time_stamp(
        theirs.read_text(encoding="ascii")
    )
    assert "TOROIDAL_SURFACE" in ours.read_text(encoding="ascii")
