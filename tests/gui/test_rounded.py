"""Rounded input in the window (docs/math.md §8): the near verdict, the approximate axis, the
deviation colour map and the switch to the nearest exact surface, in a real window with a real
VTK render window and a real worker process."""

from __future__ import annotations

import pytest
from PySide6.QtWidgets import QRadioButton

from sorgui.samples import printed
from tests.engine.test_approximate import _turned_torus

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


ROUNDED_PROLATE = (
    "0.172059*z^2 + 0.196915*y*z + 0.125626*y^2 + 0.0489472*x*z - 0.0618315*x*y + 0.242315*x^2"
    " - 0.638162*z + 0.0429165*y - 1.61362*x + 2.08005"
)
"""A prolate spheroid about a tilted axis, printed with 6 digits: its nearest exact surface has
maps over ``QQ(√d)`` with ``d`` of more than 100 digits."""


def test_a_field_of_a_hundred_digits_does_not_widen_the_results_pane(window, run_analysis, qtbot, artifacts) -> None:
    """The nearest surface's maps were listed "over QQ(sqrt(4258300637…))" with every digit, one
    unbreakable line that made the results pane wider than its view (a horizontal scroll bar,
    the right half of every row out of sight). Long numbers in the pane's words are shortened."""
    from tests.gui.test_canal import pane_text

    run_analysis(window, ROUNDED_PROLATE, timeout_ms=300_000)
    qtbot.waitUntil(lambda: window.session.nearest_analysis is not None, timeout=300_000)
    switch = window.findChild(QRadioButton, "viewNearest")
    assert switch is not None and switch.isEnabled()
    switch.click()
    qtbot.waitUntil(lambda: "digits])" in pane_text(window), timeout=60_000)
    qtbot.wait(300)
    window.grab().save(str(artifacts / "rounded-long-field.png"))
    pane = window.results
    assert pane.horizontalScrollBar().maximum() == 0
    assert pane.widget().width() <= pane.viewport().width()


TORUS_FIXED_DECIMALS = (
    "1.000000*x^4 - 482.000000*x^3 + 2.000000*x^2*y^2 + 140.800000*x^2*y + 2.000000*x^2*z^2 - "
    "320.000000*x^2*z + 97990.603743*x^2 - 482.000000*x*y^2 - 36944.545809*x*y - "
    "482.000000*x*z^2 + 81999.028210*x*z - 10114550.211232*x + 1.000000*y^4 + 140.800000*y^3 + "
    "2.000000*y^2*z^2 - 320.000000*y^2*z + 46472.028174*y^2 + 140.800000*y*z^2 - "
    "30659.713683*y*z + 3936169.584053*y + 1.000000*z^4 - 320.000000*z^3 + 71192.768084*z^2 - "
    "8169002.114326*z + 519897350.237484"
)
"""A torus in millimetres about a tilted axis, printed with 6 fixed decimals: the nearest exact
surface found lies outside its rounding (one coefficient 6.8 times its rounding off)."""


def test_a_nearest_surface_outside_the_rounding_is_not_called_the_one_meant(window, run_analysis, qtbot) -> None:
    """Switched to it, its banner said "the surface of revolution that the rounded input was meant
    to be", while the typed view said none was found within the rounding."""
    from tests.gui.test_canal import pane_text

    run_analysis(window, TORUS_FIXED_DECIMALS, timeout_ms=300_000)
    qtbot.waitUntil(lambda: window.session.nearest_analysis is not None, timeout=300_000)
    assert not window.session.run.analysis.approximate.nearest.within_rounding
    switch = window.findChild(QRadioButton, "viewNearest")
    assert switch is not None and switch.isEnabled()
    switch.click()
    qtbot.waitUntil(lambda: "outside its rounding" in window.results.banner.text() + pane_text(window), timeout=60_000)
    shown = window.results.banner.text() + pane_text(window)
    assert "not known to be the one meant" in shown and "was meant to be" not in shown
