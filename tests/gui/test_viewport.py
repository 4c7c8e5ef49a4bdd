"""The 3D viewport: actors by name, picking with the normal test, re-meshing a new ball."""

from __future__ import annotations

import numpy as np
import pytest

from sorgui.examples import example_text

pytestmark = pytest.mark.gui


@pytest.fixture
def torus_window(window, run_analysis):  # noqa: ANN001, ANN201
    run_analysis(window, example_text("torus"))
    return window


def test_picking_a_torus_point_reports_a_normal_meeting_the_axis(torus_window, qtbot) -> None:
    viewport = torus_window.viewport
    with qtbot.waitSignal(viewport.picked, timeout=5000) as blocker:
        info = viewport.pick_point((2.0, 0.0, 1.0))  # the top of the tube: |p|² + 3 = 8 = 4·2
    assert blocker.args[0] is info
    assert abs(info.value) < 1e-9 and info.meets_axis is True
    assert np.allclose(info.normal_direction, (0.0, 0.0, 1.0), atol=1e-9)
    assert {"pick_normal", "pick_circle", "pick_point"} <= viewport.actor_names()
    assert "meets" in viewport.pick_label.text()
    circle = viewport.plotter.renderer.actors["pick_circle"].GetMapper().GetInput()
    radii = np.linalg.norm(np.asarray(circle.GetPoints().GetData())[:, :2], axis=1)
    assert np.allclose(radii, 2.0, atol=1e-6)  # the circle of latitude through the point


def test_right_click_on_the_surface_picks_it(torus_window, qtbot) -> None:
    viewport = torus_window.viewport
    plotter = viewport.plotter
    plotter.view_xz(render=False)  # looking along y at the tube's cross-section x ∈ [1, 3]
    plotter.renderer.reset_camera(render=False)
    plotter.render()
    renderer = plotter.renderer
    renderer.SetWorldPoint(2.0, 0.0, 0.0, 1.0)  # the ray through this point meets the torus on
    # its outer equator (distance 3 from the axis) only
    renderer.WorldToDisplay()
    x, y, _ = renderer.GetDisplayPoint()
    with qtbot.waitSignal(viewport.picked, timeout=5000) as blocker:
        plotter.iren._mouse_right_button_click(int(round(x)), int(round(y)))
    info = blocker.args[0]
    assert abs(np.linalg.norm(info.point[:2]) - 3.0) < 0.05 and abs(info.point[2]) < 0.05
    assert info.meets_axis is True


def test_picking_a_non_sor_reports_no_axis(window, run_analysis) -> None:
    run_analysis(window, example_text("ellipsoid"))
    info = window.viewport.pick_point((1.0, 0.0, 0.0))
    assert info.axis_test is None and abs(info.value) < 1e-12
    assert "pick_circle" not in window.viewport.actor_names()


def test_sphere_shows_its_centre_and_no_axis(window, run_analysis) -> None:
    run_analysis(window, example_text("sphere"))
    names = window.viewport.actor_names()
    assert "surface" in names and "center" in names and "axis" not in names


def test_a_plane_edge_on_to_the_isometric_view_is_shown_from_its_front(window, run_analysis) -> None:
    run_analysis(window, "x - y")  # its normal is perpendicular to the isometric direction (1, 1, 1)
    camera = window.viewport.plotter.renderer.GetActiveCamera()
    sight = np.asarray(camera.GetPosition()) - np.asarray(camera.GetFocalPoint())
    sight /= np.linalg.norm(sight)
    assert abs(sight @ np.array([1.0, -1.0, 0.0])) / np.sqrt(2) > 0.89


def test_radius_box_re_meshes_a_larger_ball(torus_window, qtbot) -> None:
    viewport = torus_window.viewport
    old = viewport.scene.region
    with qtbot.waitSignal(torus_window.result_shown, timeout=60_000) as blocker:
        viewport.radius_box.setValue(2 * old.radius)
    scene = blocker.args[0].scene
    run = torus_window.session.run
    assert blocker.args[0].analysis is run.analysis  # the same analysis: only the scene was rebuilt
    assert scene.region.radius == pytest.approx(2 * old.radius)
    assert viewport.scene is scene and "Re-meshed" in torus_window.stage_label.text()


def test_a_ball_without_the_surface_says_why_nothing_is_drawn(torus_window, qtbot) -> None:
    """The torus of radii 2 and 1 has no points within 1 of its centre: the view was empty and the
    status line said nothing."""
    viewport = torus_window.viewport
    with qtbot.waitSignal(torus_window.result_shown, timeout=60_000) as blocker:
        viewport.radius_box.setValue(0.5)
    assert blocker.args[0].scene.surface.is_empty
    said = torus_window.stage_label.text()
    assert "Re-meshed" in said and "no real points" in said, said


def test_parameterization_patch_toggles(torus_window, qtbot) -> None:
    viewport = torus_window.viewport
    assert viewport.patch_box.isEnabled()
    viewport.patch_box.setChecked(True)
    assert viewport.plotter.renderer.actors["patch"].GetVisibility()
    viewport.patch_box.setChecked(False)
    assert not viewport.plotter.renderer.actors["patch"].GetVisibility()


def test_failed_analysis_clears_the_scene(torus_window, qtbot) -> None:
    with qtbot.waitSignal(torus_window.worker.failed, timeout=60_000):  # a job the worker cannot do
        torus_window.session.analyze(example_text("torus"), analysis="not an analysis")
    assert "surface" not in torus_window.viewport.actor_names()
    assert "The analysis failed" in torus_window.results.banner.text()
    assert torus_window.run_panel.notice_kind == "error"


def test_the_render_window_renders_a_frame_once(torus_window, qtbot) -> None:
    """A change of the view is rendered once, not once for VTK's frame and again for the paint
    that shows it; a paint that nothing in the scene asked for (Qt's own: the widget shown,
    moved, grabbed) shows VTK's last frame without rendering it (issue 30: each render of a
    degree-12 surface holds the GUI thread for 20-60 ms in software OpenGL)."""
    viewport = torus_window.viewport
    plotter = viewport.plotter
    frames: list[int] = []
    tag = plotter.ren_win.AddObserver("StartEvent", lambda *_: frames.append(1))
    try:
        qtbot.wait(300)  # the frames asked for by the analysis
        for change in (viewport.reset_camera, plotter.update):
            frames.clear()
            change()
            qtbot.waitUntil(lambda: bool(frames), timeout=5000)
            qtbot.wait(200)
            assert len(frames) == 1, change
        frames.clear()
        image = plotter.grabFramebuffer()  # a paint of the widget into an image, from Qt
        assert not image.isNull() and frames == []
    finally:
        plotter.ren_win.RemoveObserver(tag)


def test_turning_the_view_with_the_mouse_shows_its_frames(torus_window, qtbot) -> None:
    """The frames VTK's interactor renders while the user drags are the ones shown: what the
    window shows after a drag is the scene rendered from the new camera."""
    from PySide6.QtCore import QEvent, QPointF, Qt
    from PySide6.QtGui import QMouseEvent
    from PySide6.QtWidgets import QApplication

    plotter = torus_window.viewport.plotter
    qtbot.wait(300)
    before = plotter.grabFramebuffer()
    position = plotter.camera.position
    start = QPointF(plotter.rect().center())

    def send(kind: QEvent.Type, at: QPointF, button: Qt.MouseButton, buttons: Qt.MouseButton) -> None:
        event = QMouseEvent(kind, at, plotter.mapToGlobal(at), button, buttons, Qt.KeyboardModifier.NoModifier)
        QApplication.sendEvent(plotter, event)

    left, none = Qt.MouseButton.LeftButton, Qt.MouseButton.NoButton
    send(QEvent.Type.MouseButtonPress, start, left, left)
    for step in range(1, 7):
        send(QEvent.Type.MouseMove, start + QPointF(12 * step, 4 * step), none, left)
        qtbot.wait(20)
    send(QEvent.Type.MouseButtonRelease, start + QPointF(72, 24), left, none)
    qtbot.wait(300)
    shown = plotter.grabFramebuffer()
    assert plotter.camera.position != position and shown != before
    plotter.render()
    qtbot.wait(300)
    assert plotter.grabFramebuffer() == shown


def test_what_is_loaded_with_the_render_window_is_out_of_the_collectors_reach(torus_window) -> None:
    """Once the render window exists, the objects of Qt, VTK and pyvista are frozen: a full
    collection of the cycle collector then walks only what the work made since (it walked
    about 250 000 objects on the GUI thread, a pause of 75-130 ms)."""
    import gc

    assert torus_window.viewport.rendering
    assert gc.get_freeze_count() > 100_000


def test_a_picture_on_a_plain_background_never_reaches_the_window(torus_window, qtbot) -> None:
    """The frames an export renders (on black and on white, for a transparent picture) are
    never shown: the window's next frame is the scene with its own background."""
    from sorgui.gui.exporting import viewport_image

    viewport = torus_window.viewport
    plotter = viewport.plotter
    qtbot.wait(300)
    shown = plotter.grabFramebuffer()
    image = viewport_image(viewport, width=2 * plotter.width(), transparent=True)
    assert image.hasAlphaChannel()
    assert plotter.grabFramebuffer() == shown
    qtbot.wait(300)
    assert plotter.grabFramebuffer() == shown


def test_a_report_picture_leaves_out_the_picked_point(torus_window, qtbot) -> None:
    """A report's picture is of the surface and its axis: the picked point's normal, circle and
    marker are hidden for it, and shown again in the window afterwards."""
    from sorgui.gui.exporting import viewport_image

    viewport = torus_window.viewport
    plain = viewport_image(viewport)
    viewport.pick_point((2.0, 0.0, 1.0))
    qtbot.wait(300)  # the picked point's actors are added on the next turn of the event loop
    assert viewport_image(viewport) != plain
    assert viewport_image(viewport, inspection=False) == plain
    actors = viewport.plotter.renderer.actors
    assert all(actors[name].GetVisibility() for name in ("pick_normal", "pick_circle", "pick_point"))
    transparent = viewport_image(viewport, transparent=True)  # the view's own size: one frame each
    assert transparent.pixelColor(1, 1).alpha() == 0  # the background
    assert transparent.pixelColor(transparent.width() // 2, transparent.height() // 2).alpha() == 255  # the axis


def test_software_opengl_lights_the_scene_from_the_camera(torus_window) -> None:
    """Under software OpenGL (Xvfb here) one headlight replaces pyvista's kit of five lights:
    a frame costs about a quarter less, and the surface is still lit and shaded."""
    viewport = torus_window.viewport
    lights = list(viewport.plotter.renderer.lights)
    if viewport.software_rendering():  # always under Xvfb, as in CI
        assert len(lights) == 1 and lights[0].is_headlight
    else:
        assert len(lights) == 5


def _viewport_still_importing(qtbot):  # noqa: ANN001, ANN202 - a QtBot; (Viewport, threading.Event)
    """A shown viewport whose import thread (pyvista and VTK) runs until the event is set."""
    import threading

    from sorgui.gui.viewport import Viewport

    released = threading.Event()
    viewport = Viewport()
    qtbot.addWidget(viewport)
    viewport.resize(400, 300)
    viewport.show()
    viewport._loading = threading.Thread(target=released.wait, args=(30.0,), daemon=True)  # an import still running
    viewport._loading.start()
    viewport._loading_timer.start()
    return viewport, released


def test_a_scene_that_comes_while_vtk_is_imported_waits_for_it_without_freezing(torus_window, qtbot) -> None:
    """At start-up the first scene (and the camera saved by the last session) came while the
    import thread was still loading pyvista and VTK, and the GUI thread waited for it: 1–4 s of
    a frozen window on a busy machine. The scene now waits instead, and is drawn, framed as
    saved, once the render window is made."""
    import time

    scene, camera = torus_window.viewport.scene, torus_window.viewport.camera_state()
    assert scene is not None
    viewport, released = _viewport_still_importing(qtbot)
    start = time.monotonic()
    viewport.show_scene(scene, reset_camera=True, caption="the torus")
    viewport.restore_camera(camera)
    viewport.set_stale(True)
    assert time.monotonic() - start < 1.0 and not viewport.rendering
    assert viewport.caption.text() == "the torus"
    released.set()
    qtbot.waitUntil(lambda: viewport.rendering, timeout=30_000)
    assert "surface" in viewport.actor_names() and "axis" in viewport.actor_names()
    assert np.allclose(viewport.camera_state().position, camera.position)
    assert viewport.stale
    viewport.close_plotter()


def test_the_saved_camera_survives_a_second_scene_that_comes_while_vtk_is_imported(torus_window, qtbot) -> None:
    """At start-up the saved camera was restored on the first scene, still waiting for the
    render window, and the scene with the curves, which came next, dropped it: the surface was
    drawn from VTK's unframed camera, at (1, 1, 1) looking at the origin (for a CAD cone, a
    brown wall of its inside), and that camera was saved for the next start."""
    from sorgui.gui.camera import UNFRAMED, CameraState

    scene, camera = torus_window.viewport.scene, torus_window.viewport.camera_state()
    assert scene is not None
    viewport, released = _viewport_still_importing(qtbot)
    viewport.show_scene(scene, reset_camera=False, caption="the torus")  # a camera is restored: no framing
    viewport.restore_camera(camera)
    viewport.show_scene(scene, reset_camera=False, caption="the torus")  # the scene with its curves
    released.set()
    qtbot.waitUntil(lambda: viewport.rendering, timeout=30_000)
    assert np.allclose(viewport.camera_state().position, camera.position)
    viewport.close_plotter()
    assert CameraState.from_dict(UNFRAMED.to_dict()) is None  # such a camera saved before is not restored


def test_the_axis_shows_faintly_through_the_surface_that_hides_it(window, run_analysis) -> None:
    """A cylinder hides its axis from end to end (a rounded CAD cone showed a few pixels of it,
    at the apex): the axis is drawn again, faint, on a layer over the scene."""
    from sorgui.gui.exporting import viewport_image
    from sorgui.render.hidden_lines import HIDDEN_OPACITY

    run_analysis(window, "x^2 + y^2 - 1")
    viewport = window.viewport
    assert viewport.hidden_lines.names() == {"axis"}
    viewport.set_view("across")
    image = viewport_image(viewport)
    middle = image.pixelColor(image.width() // 2, image.height() // 2)
    viewport.hidden_lines.set_visible("axis", False)
    surface = viewport_image(viewport).pixelColor(image.width() // 2, image.height() // 2)
    viewport.hidden_lines.set_visible("axis", True)
    axis = (0x1F, 0x2A, 0x44)  # AXIS_COLOR
    seen = (surface.red(), surface.green(), surface.blue())
    assert max(abs(a - b) for a, b in zip(axis, seen)) > 40  # the cylinder, not the axis, without the copy
    expected = [HIDDEN_OPACITY * a + (1 - HIDDEN_OPACITY) * b for a, b in zip(axis, seen)]
    assert np.allclose((middle.red(), middle.green(), middle.blue()), expected, atol=12), (middle, seen)


def test_the_render_windows_surface_leaves_pysides_wrappers_with_it(qtbot) -> None:
    """pyvistaqt keeps a wrapper of the render window's OpenGL surface, which Qt deletes with the
    render window. Left in PySide's table of wrappers, its address, once taken by a new widget,
    made Qt's deletion of that widget crash (SIGSEGV in BindingManager::releaseWrapper)."""
    import shiboken6
    from PySide6.QtCore import QCoreApplication, QEvent

    from sorgui.gui.viewport import Viewport

    viewport = Viewport()
    viewport.resize(400, 300)
    viewport.show()
    plotter = viewport.plotter
    qtbot.waitUntil(lambda: plotter.context() is not None, timeout=10_000)  # initializeGL has run
    address = shiboken6.getCppPointer(plotter.context().surface())[0]
    viewport.close_plotter()
    viewport.deleteLater()
    QCoreApplication.sendPostedEvents(None, QEvent.Type.DeferredDelete)
    assert not shiboken6.isValid(viewport)
    left = [w for w in shiboken6.getAllValidWrappers() if shiboken6.getCppPointer(w)[0] == address]
    assert not left, f"wrappers of deleted objects still registered: {left}"


@pytest.mark.parametrize(
    ("text", "shown"), [("x^2+y^2+z^2-9e12", "ball radius 3"), ("x^2+y^2-1e-8", "ball radius 0.000")]
)
def test_the_radius_box_shows_a_large_or_small_ball_and_automatic_brings_it_back(
    window, run_analysis, qtbot, text: str, shown: str
) -> None:
    """The box's fixed range of 0 to 10⁴ with 3 decimals showed a ball of radius 3.75e6 as
    10000.000 (one step down drew a ball that held none of the part) and one of radius 0.000177
    as "automatic"; "automatic" kept the last ball asked for."""
    run_analysis(window, text)
    viewport = window.viewport
    automatic = viewport.scene.region.radius
    box = viewport.radius_box
    assert box.text().startswith(shown) and box.value() == pytest.approx(automatic, rel=1e-3), box.text()
    with qtbot.waitSignal(window.result_shown, timeout=60_000) as blocker:
        box.stepDown()
    smaller = blocker.args[0].scene
    assert automatic * 0.5 < smaller.region.radius < automatic and not smaller.surface.is_empty
    with qtbot.waitSignal(window.result_shown, timeout=60_000) as blocker:
        box.setValue(0.0)
    assert blocker.args[0].scene.region.radius == pytest.approx(automatic)


def test_the_render_window_keeps_the_window_and_its_keyboard_focus(make_window, qtbot) -> None:
    """The render window, the first OpenGL widget added once the window was shown, made Qt
    destroy the window's native window and create another: without a window manager the window
    lost the keyboard focus for good (Ctrl+Return and Esc did nothing), and with one it flashed."""
    from PySide6.QtWidgets import QApplication

    window = make_window()
    window.activateWindow()
    qtbot.waitUntil(lambda: QApplication.activeWindow() is window, timeout=10_000)
    native = int(window.winId())
    window.viewport.start_rendering()
    qtbot.wait(500)
    assert int(window.winId()) == native
    assert QApplication.activeWindow() is window
