"""Canal surfaces in the window (docs/math.md §9): the Canal section of the results pane, the
spine and characteristic circles in the 3D view with their "Canal" box, and the three canal
examples of the Examples menu.

Real window, real VTK render window (Mesa under Xvfb), real worker process and Singular.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from PySide6.QtWidgets import QLabel

from sorgui.examples import example_text

pytestmark = pytest.mark.gui

SLOW_MS = 300_000
"""Time allowed to an analysis that runs every stage (the canal stage asks Singular too)."""

CANAL_EXAMPLES = ("rolling-ball-blend", "pipe-twisted-cubic", "dupin-cyclide")


def pane_text(window) -> str:  # noqa: ANN001
    """Every label of the results pane, joined (captions and values)."""
    return "\n".join(label.text() for label in window.results.widget().findChildren(QLabel))


def test_dupin_cyclide_canal_section_and_viewport(window, qtbot, run_analysis, artifacts: Path) -> None:
    run_analysis(window, example_text("dupin-cyclide"), timeout_ms=SLOW_MS)
    canal = window.results.analysis.canal
    assert canal is not None and canal.is_canal and "dupin" in canal.kinds
    text = pane_text(window)
    assert "Canal surface" in text
    assert "a canal surface, the envelope of a one-parameter family of spheres" in text
    assert "a Dupin cyclide (canal in two ways)" in text
    assert "a canal surface: a Dupin cyclide (canal in two ways)" in window.results.banner.text()
    assert "f divides every generator" in text or "f divides Res" in text
    assert "family 1" in text and "family 2" in text
    assert "a plane curve of degree 2, genus 0 (rational)" in text
    assert "varies along the spine" in text
    assert "canal.0.spine" in window.results.views and "canal.0.radius" in window.results.views

    viewport = window.viewport
    qtbot.waitUntil(lambda: {"canal_spine", "canal_circles"} <= viewport.actor_names(), timeout=60_000)
    actors = viewport.plotter.renderer.actors
    assert actors["canal_spine"].GetMapper().GetInput().n_points > 100
    assert actors["canal_circles"].GetMapper().GetInput().n_lines >= 4
    assert viewport.canal_box.isEnabled() and viewport.canal_box.isChecked()
    assert actors["canal_spine"].GetVisibility() and actors["canal_circles"].GetVisibility()
    window.save_screenshots(artifacts / "canal-window.png", artifacts / "canal-viewport.png")

    info = viewport.pick_point((6.0, 0.0, 0.0))  # on the cyclide: f(6, 0, 0) = 0
    assert info is not None and abs(info.value) < 1e-6
    assert {"pick_sphere", "pick_canal_circle"} <= viewport.actor_names()
    label = viewport.pick_label.text()
    assert "touching sphere of family 1: centre (5, 0, 0), radius 1" in label
    assert "touching sphere of family 2: centre (-3, " in label and "radius 9" in label
    window.save_screenshots(artifacts / "canal-pick-window.png", artifacts / "canal-pick-viewport.png")

    viewport.canal_box.setChecked(False)
    assert not actors["canal_spine"].GetVisibility() and not actors["canal_circles"].GetVisibility()
    viewport.canal_box.setChecked(True)
    assert actors["canal_spine"].GetVisibility() and actors["canal_circles"].GetVisibility()


def test_canal_examples_in_menu_and_load(window, qtbot) -> None:  # noqa: ANN001
    """The three canal examples are in the menu, load into the editor and are found canal."""
    actions = {a.data(): a for a in window.examples_menu.example_actions()}
    for name in CANAL_EXAMPLES:
        assert name in actions
        assert actions[name].text().startswith("Canal: ")
        with qtbot.waitSignal(window.result_shown, timeout=SLOW_MS) as blocker:
            actions[name].trigger()
        assert window.editor.text() == example_text(name)
        canal = blocker.args[0].analysis.canal
        assert canal is not None and canal.is_canal, name
        assert ("dupin" if name == "dupin-cyclide" else "pipe") in canal.kinds


def test_picking_a_blend_with_a_spine_of_genus_1(window, qtbot, run_analysis, artifacts: Path) -> None:
    """The two-cylinder blend's spine has genus 1 (no rational m(t)): the pane shows m(t) in
    square roots, the spine is traced numerically, and picking a point shows the sphere that
    touches the surface there, found from the SMAT equations."""
    import numpy as np

    data = Path(__file__).resolve().parents[1] / "data" / "canal-examples.txt"
    lines = data.read_text(encoding="utf-8").splitlines()
    text = next(lines[i + 1] for i, line in enumerate(lines) if line.startswith("## blend cylinders R=2"))
    run_analysis(window, text, timeout_ms=SLOW_MS)
    canal = window.results.analysis.canal
    assert canal is not None and canal.is_canal and canal.families[0].parametrization is None
    assert "canal.0.spine" in window.results.views  # m(t) in square roots, typeset
    window.save_screenshots(artifacts / "canal-blend-window.png", artifacts / "canal-blend-viewport.png")
    viewport = window.viewport
    scene = viewport.scene
    assert scene.canal_families, "the SMAT equations reach the window"
    assert {"canal_spine", "canal_circles"} <= viewport.actor_names()  # traced numerically
    spine = np.asarray(scene.canal_spine.points)
    assert len(spine) > 100
    assert np.abs(spine[:, 1] ** 2 + spine[:, 2] ** 2 - 16).max() < 1e-5
    assert np.abs(spine[:, 0] ** 2 + spine[:, 2] ** 2 - 9).max() < 1e-5
    points = np.asarray(scene.surface.points)
    touched = 0
    for point in points[:: max(1, len(points) // 15)][:15]:
        info = viewport.pick_point(point)
        if info is not None and "touching sphere of family 1" in viewport.pick_label.text():
            assert "radius 1" in viewport.pick_label.text()
            assert "pick_sphere" in viewport.actor_names() and "pick_canal_circle" in viewport.actor_names()
            touched += 1
    assert touched >= 10
