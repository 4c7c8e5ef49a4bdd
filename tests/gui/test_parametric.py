"""Parametrizations in the window (docs/math.md §13): the editor accepts and checks the form, the
pane shows the components as typed and whether the map is proper; a map whose implicit equation
is not known is drawn as its patch; a parametrization's saved report opens as saved, and one that
lies about its map is refused in one line. Real window, worker process and Singular."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from PySide6.QtWidgets import QLabel

from sorgui.engine import analyze
from sorgui.export.files import export_file
from sorgui.samples import bicubic_patch, map_text

pytestmark = pytest.mark.gui

ISSUE = "x = (1-t^2)/(1+t^2)*(2+s), y = 2*t/(1+t^2)*(2+s), z = s^2"


def _pane_text(window) -> str:  # noqa: ANN001
    return "\n".join(label.text() for label in window.results.widget().findChildren(QLabel))


def test_the_editor_checks_a_parametrization(window) -> None:  # noqa: ANN001
    assert window.input_label.text() == "<b>f(x, y, z) = 0</b>"
    window.editor.set_text("x = u, y = v,\nz = u^2 + v^2")
    assert window.editor.is_valid is True
    assert window.input_label.text() == "<b>x, y, z: a rational map</b>"  # the heading says what is typed
    assert "a parametrization in u and v of degree 2 over QQ" in window.editor.status_label.text()
    window.editor.set_text("x = s, y = t, z = exp(s)")
    assert window.editor.is_valid is False
    assert "'exp' is not allowed" in window.editor.status_label.text()
    (selection,) = window.editor.error_selections()
    assert selection.cursor.selectedText() == "exp"
    window.editor.set_text("x = (2 + cos(v)) cos(u), y = (2 + cos(v)) sin(u), z = sin(v)")
    assert window.editor.is_valid is True
    assert "of degree 4 over QQ, in tan(u/2) and tan(v/2)" in window.editor.status_label.text()
    window.editor.set_text("x^2 + y^2 - z")
    assert window.input_label.text() == "<b>f(x, y, z) = 0</b>"


def test_the_pane_shows_the_map_as_typed_and_that_it_is_proper(
    window,
    run_analysis,
    artifacts: Path,  # noqa: ANN001
) -> None:
    result = run_analysis(window, ISSUE, timeout_ms=300_000)
    assert result.analysis.input_kind == "parametrization" and result.analysis.is_sor
    text = _pane_text(window)
    assert "Parametrization (as typed)" in text
    assert "(1-t^2)/(1+t^2)*(2+s)" in text and "s^2" in text
    assert "yes: one parameter point over a point of X" in text
    assert "∂(h, ρ)/∂(s, t) ≡ 0 about the axis: yes" in text
    assert "polynomial" in window.results.views  # the implicit equation, typeset
    assert "parametrization.0.x" in window.results.views  # the given map among the others
    window.save_screenshots(artifacts / "parametric-window.png", artifacts / "parametric-viewport.png")


def test_a_map_without_its_equation_is_drawn_as_its_patch(window, run_analysis, artifacts: Path) -> None:  # noqa: ANN001
    result = run_analysis(window, map_text(bicubic_patch(seed=3)), timeout_ms=120_000)
    assert not result.analysis.is_sor and result.analysis.recognition.polynomial in ("", result.analysis.squarefree)
    text = _pane_text(window)
    assert "Parametrization (as typed)" in text
    if not result.analysis.recognition.polynomial:
        assert "not known" in text
        assert window.viewport.scene is not None and window.viewport.scene.patch is not None
        assert not window.viewport.scene.patch.is_empty
    window.save_screenshots(artifacts / "parametric-patch-window.png", artifacts / "parametric-patch-viewport.png")


@pytest.mark.parametrize(
    ("text", "options"),
    [(ISSUE, {}), (map_text(bicubic_patch(seed=3)), {"recognition_only": True, "timeout": 3})],
    ids=["with its equation", "without"],
)
def test_a_saved_parametrization_opens_and_a_lying_one_is_refused(
    window,  # noqa: ANN001
    qtbot,  # noqa: ANN001
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    artifacts: Path,
    text: str,
    options: dict,
) -> None:
    """File → Open of a parametrization's report (its claims checked against the map): shown as
    saved; the same report with another map is refused naming the field, in one line."""
    report = tmp_path / "map.sorgui.json"
    export_file(analyze(text, **{"timeout": 120, **options}), report)
    with qtbot.waitSignal(window.result_shown, timeout=120_000):
        assert window.open_file(str(report))
    assert "Parametrization (as typed)" in _pane_text(window)
    if not options:
        window.save_screenshots(artifacts / "parametric-report-window.png", artifacts / "parametric-report-3d.png")
    shown: list[str] = []
    monkeypatch.setattr(window, "_show_error", lambda title, message: shown.append(f"{title}: {message}"))
    data = json.loads(report.read_text(encoding="utf-8"))
    data["parametric"]["map"][2] = "s**3 + t"
    report.write_text(json.dumps(data), encoding="utf-8")
    with qtbot.waitSignal(window.report_reader.refused, timeout=120_000):
        assert window.open_file(str(report))  # read in a process of its own, which refuses it
    assert len(shown) == 1 and "refused: its parametric.map is not the map" in shown[0] and "\n" not in shown[0]
