"""Rounded input in the window (docs/math.md §8): the near verdict, the approximate axis, the
deviation colour map and the switch to the nearest exact surface, in a real window with a real
VTK render window and a real worker process."""

from __future__ import annotations

from pathlib import Path

import pytest
from PySide6.QtWidgets import QRadioButton

from sorgui.samples import printed
from tests.engine.test_approximate import _turned_torus

DATA = Path(__file__).resolve().parent.parent / "data"

pytestmark = pytest.mark.gui


def test_a_rounded_torus_is_shown_near_with_its_axis_and_its_nearest_surface(
    window, run_analysis, qtbot, artifacts
) -> None:
    run_analysis(window, printed(_turned_torus()[0], 10), timeout_ms=300_000)
    qtbot.waitUntil(lambda: window.session.nearest_analysis is not None, timeout=300_000)
    banner = window.results.banner.text()
    assert "Nearly a surface of revolution" in banner and "not exactly, but within" in banner
    assert "approx_axis" in window.viewport.actor_names()
    assert not window.viewport.scene.approximate_axis.is_empty
    # the canal verdict on the typed rationals is said with that of the nearest exact surface
    from tests.gui.test_canal import pane_text

    qtbot.waitUntil(lambda: "Canal surface" in pane_text(window), timeout=60_000)
    assert "not exactly canal, but nearly" in pane_text(window)

    qtbot.waitUntil(window.viewport.deviation_box.isEnabled, timeout=60_000)
    window.viewport.deviation_box.setChecked(True)
    assert "deviation" in window.viewport.plotter.scalar_bars
    window.viewport.deviation_box.setChecked(False)
    assert "deviation" not in window.viewport.plotter.scalar_bars

    # the axes in decimals first, copied with a double's 16 digits; the exact one below
    qtbot.waitUntil(lambda: "approximate.nearest.axis" in window.results.views, timeout=60_000)
    views = window.results.views
    approximate = views["approximate.axis"].formula
    assert approximate.plain.count(",") == 4 and len(approximate.plain) > len(approximate.latex)
    decimal, exact = views["approximate.nearest.axis.decimal"].formula, views["approximate.nearest.axis"].formula
    assert "/" not in decimal.plain and "." in decimal.plain and exact.plain != decimal.plain
    views["approximate.nearest.axis.decimal"].copy_plain()
    from PySide6.QtGui import QGuiApplication

    assert QGuiApplication.clipboard().text() == decimal.plain
    views["approximate.nearest.axis"].copy_plain()
    assert QGuiApplication.clipboard().text() == exact.plain

    switch = window.findChild(QRadioButton, "viewNearest")
    assert switch is not None and switch.isEnabled()
    switch.click()
    qtbot.waitUntil(lambda: window.session.view == "nearest", timeout=10_000)
    qtbot.waitUntil(lambda: "nearest exact surface" in window.viewport.caption.text().lower(), timeout=60_000)
    assert "nearest exact surface" in window.results.banner.text().lower()
    assert window.session.nearest_analysis.is_sor
    qtbot.waitUntil(lambda: "polynomial" in window.results.views, timeout=60_000)
    assert window.results.views["polynomial"].formula.text.startswith("g = ")  # g, as the reports name it
    qtbot.wait(1000)
    window.grab().save(str(artifacts / "rounded-nearest.png"))


def test_a_cad_torus_on_an_irrational_axis_switches_to_its_exact_surface_over_a_quadratic_field(
    window, run_analysis, qtbot, artifacts
) -> None:
    """Turned by 30° and 45°, printed with 10 digits: the nearest exact surface is the torus over
    QQ(√6), and the window shows it (its pane and its mesh) when asked."""
    from tests.engine.test_approximate import _cad_torus
    from tests.gui.test_canal import pane_text

    run_analysis(window, _cad_torus(digits=10), timeout_ms=300_000)
    qtbot.waitUntil(lambda: window.session.nearest_analysis is not None, timeout=300_000)
    assert window.session.nearest_analysis.field == "QQ(sqrt(6))"
    switch = window.findChild(QRadioButton, "viewNearest")
    assert switch is not None and switch.isEnabled()
    switch.click()
    qtbot.waitUntil(lambda: "nearest exact surface" in window.viewport.caption.text().lower(), timeout=60_000)
    qtbot.waitUntil(lambda: "QQ(sqrt(6))" in window.results.banner.text() + pane_text(window), timeout=60_000)
    qtbot.wait(500)
    window.grab().save(str(artifacts / "rounded-quadratic-nearest.png"))


BIG_SPHERE = "x^2 + y^2 + z^2 - " + "1234567890" * 9 + "1234567891"
"""A sphere whose radius² has 100 digits: its maps are over ``QQ(√d)`` with ``d`` of 100 digits."""


def test_a_field_of_a_hundred_digits_does_not_widen_the_results_pane(window, run_analysis, qtbot, artifacts) -> None:
    """The maps of a rounded prolate spheroid's nearest surface were listed "over
    QQ(sqrt(4258300637…))" with every digit, one unbreakable line that made the results pane
    wider than its view (a horizontal scroll bar, the right half of every row out of sight).
    Long numbers in the pane's words are shortened (here a sphere's maps, over the field of its
    radius)."""
    from tests.gui.test_canal import pane_text

    run_analysis(window, BIG_SPHERE, timeout_ms=300_000)
    qtbot.waitUntil(lambda: "digits])" in pane_text(window), timeout=60_000)
    qtbot.wait(300)
    window.grab().save(str(artifacts / "rounded-long-field.png"))
    pane = window.results
    assert pane.horizontalScrollBar().maximum() == 0
    assert pane.widget().width() <= pane.viewport().width()


CONE_OUTSIDE = (DATA / "rounded-cone-outside.txt").read_text(encoding="utf-8")
"""A cone of 7.5° printed with 6 decimals: the nearest exact surface found lies outside its
rounding (one coefficient 2.7 times its rounding off)."""


def test_a_nearest_surface_outside_the_rounding_is_not_called_the_one_meant(window, run_analysis, qtbot) -> None:
    """Switched to it, its banner said "the surface of revolution that the rounded input was meant
    to be", while the typed view said none was found within the rounding."""
    from tests.gui.test_canal import pane_text

    run_analysis(window, CONE_OUTSIDE, timeout_ms=300_000)
    qtbot.waitUntil(lambda: window.session.nearest_analysis is not None, timeout=300_000)
    assert not window.session.run.analysis.approximate.nearest.within_rounding
    switch = window.findChild(QRadioButton, "viewNearest")
    assert switch is not None and switch.isEnabled()
    switch.click()
    qtbot.waitUntil(lambda: "outside its rounding" in window.results.banner.text() + pane_text(window), timeout=60_000)
    shown = window.results.banner.text() + pane_text(window)
    assert "not known to be the one meant" in shown and "was meant to be" not in shown


def test_a_rounded_cone_shows_its_apex_as_the_text_report_does(window, run_analysis, qtbot) -> None:
    """The typed cone's apex within the rounding was shown with 10 digits
    (``(0.9999979276, 1.999997171, 2.999993479)``), the text report's with 6."""
    from sorgui.export.text import float_text
    from tests.engine.test_rounded_quadrics import turned_cone
    from tests.gui.test_canal import pane_text

    run_analysis(window, turned_cone(15.0, (17.0, 41.0), ".6g"), timeout_ms=300_000)
    apex = window.session.run.analysis.conical.near_apex
    assert apex is not None
    qtbot.waitUntil(lambda: "apex (about)" in pane_text(window), timeout=60_000)
    assert f"apex (about)\n{float_text(apex, 6)}" in pane_text(window)


def test_numbers_beyond_floating_point_are_shown_to_the_end(window, run_analysis, qtbot) -> None:
    """A sphere of radius² 10⁴⁰⁰: exact, and its nearness undecided (no tolerance in floating
    point). Its approximation section raised a TypeError on every message, and the pane stayed
    at "being decided" after the analysis had ended."""
    from tests.gui.test_canal import pane_text

    run_analysis(window, "x^2 + y^2 + z^2 - 1e400")
    qtbot.waitUntil(lambda: not window.session.run.running, timeout=120_000)
    qtbot.waitUntil(lambda: "being decided" not in pane_text(window), timeout=60_000)
    text = pane_text(window)
    assert "beyond floating point (relative, from the digits of the input)" in text
    assert "not decided (see the note)" in text and "no continuous symmetry within the tolerance" not in text


def test_a_probe_on_rounded_input_counts_heights_from_the_axis_point_shown(window, run_analysis, qtbot) -> None:
    """The height of a picked point of a rounded torus along its approximate axis counts from
    the axis point the results pane gives (it counted from where the drawn axis leaves the
    ball); its radius is the distance to that axis."""
    import numpy as np

    from tests.engine.test_approximate import _turned_torus

    _, direction, centre = _turned_torus()
    run_analysis(window, printed(_turned_torus()[0], 10), timeout_ms=300_000)
    qtbot.waitUntil(lambda: not window.viewport.scene.approximate_axis.is_empty, timeout=60_000)
    approximate = window.session.run.analysis.approximate.axis
    point = centre + direction + 3 * np.array([0.0, 0.0, 1.0])  # height 1 and radius 3 about the centre
    info = window.viewport.pick_point(tuple(point))
    unit = np.asarray(approximate.direction) / np.linalg.norm(approximate.direction)
    expected = float(np.dot(info.point - np.asarray(approximate.point), unit))
    assert abs(info.height - expected) < 1e-6 and abs(info.radius - 3.0) < 1e-3
    assert f"height {expected:.4g}" in window.viewport.pick_label.text()
