"""Cones and cylinders over any curve in the window (docs/math.md §10): the banner names the
apex, and the "Cone or cylinder" section gives the apex or direction, the base curve with its
genus and the verified parameterization. Real window, worker process and Singular."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PySide6.QtWidgets import QLabel

pytestmark = pytest.mark.gui

SLOW_MS = 300_000
"""Time allowed to an analysis that runs every stage (the canal stage asks Singular too)."""


def _pane_text(window) -> str:  # noqa: ANN001
    return "\n".join(label.text() for label in window.results.widget().findChildren(QLabel))


def _marker(window):  # noqa: ANN001, ANN202
    return window.viewport.plotter.renderer.actors["center"].GetMapper().GetInput()


def _base_curve_points(window, qtbot) -> np.ndarray:  # noqa: ANN001
    """The points of the drawn base curve, once it is drawn."""
    from vtkmodules.util.numpy_support import vtk_to_numpy

    def drawn():  # noqa: ANN202
        return window.viewport.plotter.renderer.actors["base_curve"].GetMapper().GetInput()

    qtbot.waitUntil(
        lambda: "base_curve" in window.viewport.actor_names() and drawn().GetNumberOfPoints() > 50, timeout=30_000
    )
    return vtk_to_numpy(drawn().GetPoints().GetData())


def _on_surface(window, points: np.ndarray) -> float:  # noqa: ANN001
    """The largest first-order distance ``|f|/|∇f|`` of ``points`` to the drawn surface."""
    from sorgui.render.sampling import first_order_distance

    distance = first_order_distance(window.viewport.scene.terms, points)
    return float(np.nanmax(distance))


def test_a_cone_shows_its_apex_and_base_curve(window, run_analysis, qtbot, artifacts: Path) -> None:
    result = run_analysis(window, "(x-1)^3+2*(y-2)^3-(z-3)^2*(x-1)+(x-1)*(y-2)*(z-3)", timeout_ms=SLOW_MS)
    conical = result.analysis.conical
    assert conical.kind == "cone" and conical.apex == ("1", "2", "3")
    assert "a cone with apex (1, 2, 3) over a curve of degree 3, genus 1 (not rational)" in window.results.banner.text()
    text = _pane_text(window)
    assert "Cone or cylinder" in text and "the top-degree form of f in the chart z = 1" in text
    assert "degree 3, genus 1" in text
    assert "conical.apex" in window.results.views and "conical.base" in window.results.views
    assert "cone over a curve: YES, apex (1, 2, 3)" in window.results.plain_text()
    qtbot.waitUntil(lambda: _marker(window).GetNumberOfPoints() > 0, timeout=30_000)  # the apex, drawn
    center = np.asarray(_marker(window).GetCenter())
    assert np.allclose(center, (1, 2, 3), atol=0.05)
    base = _base_curve_points(window, qtbot)  # f₃ in a plane z = const, where it lies on the cone
    assert np.ptp(base[:, 2]) < 1e-9 and abs(base[0, 2] - 3) > 0.5
    assert _on_surface(window, base) < 1e-3 * window.viewport.scene.region.radius
    window.save_screenshots(artifacts / "cone-window.png", artifacts / "cone-viewport.png")


def test_a_rational_cylinder_shows_its_direction_and_a_verified_map(window, run_analysis, qtbot) -> None:
    result = run_analysis(window, "(x-z)^3-(y-2*z)^2", timeout_ms=SLOW_MS)
    conical = result.analysis.conical
    assert conical.kind == "cylinder" and conical.direction == ("1", "2", "1") and conical.rational
    text = _pane_text(window)
    assert "a cylinder along (1, 2, 1) over a curve of degree 3, genus 0 (rational)" in window.results.banner.text()
    assert "degree 3, genus 0" in text and "real, proper, over QQ · verified by substitution" in text
    assert all(f"conical.parametrization.0.{name}" in window.results.views for name in "xyz")
    base = _base_curve_points(window, qtbot)  # the section by a plane across (1, 2, 1)
    assert np.ptp(base @ np.array([1.0, 2.0, 1.0])) < 1e-9
    smooth = np.linalg.norm(base, axis=1) > 0.05  # away from the cusp, at the origin
    assert _on_surface(window, base[smooth]) < 1e-3 * window.viewport.scene.region.radius
