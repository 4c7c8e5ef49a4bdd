"""The 3D viewport: the surface, its axis and profile, and point-and-click inspection.

A pyvistaqt ``QtInteractor`` (:class:`~sorgui.gui.render_window.RenderWindow`, which renders
only a scene that may have changed) is embedded in a widget with a small tool row; it is created
after the window is first drawn, pyvista and VTK's rendering imported on a thread
(:meth:`Viewport.start_rendering_soon`), so that the window opens without waiting for them. Actors are built on
the GUI thread from the plain arrays of a :class:`~sorgui.session.scene_data.SceneData` that the
worker process computed, and replaced in place by name (``add_mesh(..., name="surface")``).
The surface's two sides have two colours (the mesh is wound to face ``f > 0``). Right-click
(or P) on the surface picks a point: the viewport draws its normal line and its circle of
latitude, and reports ``f`` there and whether the normal meets the axis (the paper's
characterisation of surfaces of revolution, tested by :func:`sorgui.render.picking.pick_info`);
on a canal surface also the sphere of each rational family that touches the surface there and
its characteristic circle (:mod:`sorgui.render.canal_touch`).

VTK's and pyvista's own key bindings are removed (``p`` drew a red box, ``3`` stereo, ``w``/``s``
wireframe, ``e``/``q`` quit): the only keys are the application's (P picks, listed in Help).
:attr:`Viewport.view_actions` are the standard views (along and across the axis, the
coordinate views, reset), orthographic projection, wireframe and the meridian clip; the window
puts them in its View menu and the tool row. A caption names the surface shown; when the
results are stale the surface is greyed and the caption says it is the previous equation's.
For rounded input the approximate axis is drawn, and the deviation from the nearest exact
surface can colour the surface. For a canal surface the spine and a few characteristic circles
are drawn (the "Canal" box shows or hides them).
"""

from __future__ import annotations

import contextlib
import gc
import importlib
import math
import sys
import threading
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from PySide6.QtCore import QObject, Qt, QTimer, Signal
from PySide6.QtGui import QAction, QCursor, QKeySequence
from PySide6.QtWidgets import (
    QCheckBox,
    QDoubleSpinBox,
    QLabel,
    QToolButton,
    QVBoxLayout,
    QWidget,
)

from sorgui.gui.camera import (
    CameraState,
    coordinate_view,
    meridian_normal,
    view_across,
    view_along,
)
from sorgui.gui.flow_layout import ElidedLabel, FlowLayout
from sorgui.gui.wording import floats
from sorgui.render.canal_touch import Touch, touching_spheres
from sorgui.render.geometry import view_direction, view_up
from sorgui.render.plotting import forwarders

if TYPE_CHECKING:
    import pyvista
    from vtkmodules.vtkCommonDataModel import vtkPlane

    from sorgui.gui.render_window import RenderWindow
    from sorgui.render.hidden_lines import HiddenLines
    from sorgui.render.picking import PickInfo
    from sorgui.session.scene import SceneData

FRONT_COLOR = "#7fa7d6"
"""The side ``f > 0`` of the surface."""
BACK_COLOR = "#e8a95b"
"""The side ``f < 0``."""
AXIS_COLOR = "#1f2a44"
PROFILE_COLOR = "#c2185b"
CENTER_COLOR = "#d32f2f"
BASE_CURVE_COLOR = "#5d4037"
PATCH_COLOR = "#2e7d32"
NORMAL_COLOR = "#0277bd"
LATITUDE_COLOR = "#6a1b9a"
PICK_COLOR = "#111111"
STALE_COLOR = "#b0b6bd"
APPROXIMATE_AXIS_COLOR = "#ef6c00"
FACTOR_AXES_COLOR = "#455a64"
CANAL_SPINE_COLOR = "#00838f"
CANAL_CIRCLE_COLOR = "#26a69a"
DEVIATION_MAP = "viridis"

SCENE_ACTORS = (
    "surface",
    "axis",
    "profile",
    "center",
    "patch",
    "approx_axis",
    "factor_axes",
    "canal_spine",
    "canal_circles",
    "base_curve",
)
AXIS_ACTORS = ("axis", "approx_axis", "factor_axes")
"""The lines drawn through the surface too, faint (:mod:`sorgui.render.hidden_lines`)."""
CANAL_ACTORS = ("canal_spine", "canal_circles")
PICK_ACTORS = ("pick_normal", "pick_circle", "pick_point", "pick_sphere", "pick_canal_circle")
TOUCH_SPHERE_COLOR = "#80cbc4"
TOUCH_CIRCLE_COLOR = "#004d40"

SOFTWARE_RENDERERS = ("llvmpipe", "softpipe", "swrast", "Software Rasterizer")
SOFTWARE_RESOLUTION = 90
HARDWARE_RESOLUTION = 160
"""Grid nodes across the drawn ball (about 33 000 and 105 000 triangles for a torus)."""

LOADING_POLL_MS = 20
"""How often the GUI thread looks whether pyvista and VTK's rendering have been imported."""

RADIUS_DELAY_MS = 500
"""Debounce of the radius box: the ball is re-meshed this long after the last change."""


def _freeze_what_is_loaded() -> None:
    """Put everything alive once the render window exists (the modules of Qt, VTK, pyvista and
    numpy, the window itself) out of the cycle collector's reach, once per process: a full
    collection walked its 250 000 objects on the GUI thread, 75-130 ms at a time, the longest
    pause of the window at work (issue 30); later collections walk only what the work makes.
    The analysis and typesetting processes do the same (:mod:`sorgui.session.job`)."""
    if gc.get_freeze_count() == 0:
        gc.freeze()


QT_MODULES_OF_THE_RENDER_WINDOW = ("PySide6.QtOpenGL", "PySide6.QtOpenGLWidgets", "PySide6.QtDataVisualization")
"""The Qt modules that pyvistaqt and VTK's Qt widget load (through qtpy). They are imported on
the GUI thread (a few milliseconds) before :func:`_import_rendering` runs on its thread: a Qt
module's C++ side is initialised on the GUI thread, never beside the widgets being built."""


RENDERING_MODULES = (
    "pyvistaqt",
    "vtkmodules.vtkCommonDataModel",
    "vtkmodules.vtkInteractionWidgets",
    "vtkmodules.vtkViewsContext2D",
    "vtkmodules.vtkViewsCore",
)
"""What the render window needs, imported by :func:`_import_rendering`: pyvistaqt and the VTK
modules that pyvista's interactor imports when it is made (``vtkInteractionWidgets`` alone took a
quarter of a second, on the GUI thread)."""


def _import_rendering() -> None:
    """Import :data:`RENDERING_MODULES` (run on a thread by :meth:`Viewport.start_rendering_soon`,
    after the Qt modules of :data:`QT_MODULES_OF_THE_RENDER_WINDOW`)."""
    for name in RENDERING_MODULES:
        importlib.import_module(name)


def framed(scene: SceneData) -> tuple[np.ndarray, float]:
    """The centre and radius the camera frames: the drawn box's (View → Cut to a Box), else the
    drawn ball's. A box 2 across on a torus 580 across was framed in the ball about the axis that
    holds it, radius 291: a speck."""
    if scene.box is not None:
        low, high = np.asarray(scene.box.bounds[0::2]), np.asarray(scene.box.bounds[1::2])
        return 0.5 * (low + high), 0.5 * float(np.linalg.norm(high - low))
    return np.asarray(scene.region.center), scene.region.radius


class Viewport(QWidget):
    """The render window with its controls.

    :attr:`radius_requested` asks for the scene to be rebuilt in a ball of the given radius (0:
    the automatic ball);
    :attr:`picked` carries the :class:`~sorgui.render.picking.PickInfo` of a picked point.
    """

    radius_requested = Signal(float)
    picked = Signal(object)
    pick_cleared = Signal()

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self._plotter: RenderWindow | None = None
        self._loading: threading.Thread | None = None
        self._waiting: tuple[SceneData, bool, CameraState | None] | None = None
        """A scene that came while the import thread ran, whether to frame it and the camera to
        put back: drawn when the render window is made, instead of waiting for the thread on the
        GUI thread (the start of the window froze for 1–4 s on a busy machine)."""
        self._collecting = False
        """Whether the cycle collector is to be enabled again once the import thread ends."""
        self._loading_timer = QTimer(self)
        self._loading_timer.setInterval(LOADING_POLL_MS)
        self._loading_timer.timeout.connect(self._show_loading)
        from PySide6.QtOpenGLWidgets import QOpenGLWidget

        self._gl_anchor = QOpenGLWidget(self)
        """Never shown: an OpenGL widget in the window from its start makes Qt create the window's
        native window for OpenGL at once. The render window, the first OpenGL widget added after
        the window was shown, made Qt destroy and create it again: it lost the keyboard focus
        without a window manager (Ctrl+Return and Esc then did nothing) and flashed with one."""
        self._gl_anchor.hide()
        self._placeholder = QLabel("Starting the 3D view…", self)
        self._placeholder.setAlignment(Qt.AlignmentFlag.AlignCenter)
        self._placeholder.setMinimumSize(120, 120)
        self._scene: SceneData | None = None
        self._software: bool | None = None
        self.software_guess = True
        """What :meth:`software_rendering` answers before the render window exists (the
        window's first analysis starts before it): the last session's finding, else the worst."""
        self._stale = False
        self._clip_plane: vtkPlane | None = None
        """The meridian plane of the section view (a ``vtkPlane``, made with the render window)."""
        self._hidden: HiddenLines | None = None
        """The axes drawn faint where the surface hides them (made with the render window)."""
        self._drop_filter: QObject | None = None

        self.caption = ElidedLabel("No surface yet", self)  # cut with "…" in a narrow window, whole as tooltip
        self.caption.setObjectName("viewportCaption")
        self.caption.setTextFormat(Qt.TextFormat.PlainText)
        self.caption.setContentsMargins(6, 0, 6, 0)
        self.deviation_box = QCheckBox("Deviation", self)
        self.deviation_box.setToolTip(
            "Colour the surface by its distance to the nearest exact surface of revolution (rounded input)"
        )
        self.deviation_box.setEnabled(False)
        self.view_actions = self._build_view_actions()
        self.toolbar = QWidget(self)  # its buttons wrap onto a second line in a narrow window
        self.toolbar.setObjectName("viewToolbar")
        buttons = FlowLayout(self.toolbar, spacing=2)
        for name in ("along", "across", "x", "y", "z", "reset", "parallel", "wireframe", "clip"):
            button = QToolButton(self.toolbar)
            button.setDefaultAction(self.view_actions[name])
            button.setAutoRaise(True)
            buttons.addWidget(button)

        self.radius_box = QDoubleSpinBox(self)
        self.radius_box.setObjectName("radiusBox")
        self.radius_box.setDecimals(3)
        self.radius_box.setRange(0.0, 1e4)  # 0: no ball yet (a surface being analysed), said in words
        self.radius_box.setSpecialValueText("ball radius: automatic")
        self.radius_box.setValue(0.0)
        self.radius_box.setSingleStep(0.25)
        self.radius_box.setPrefix("ball radius ")
        self.radius_box.setToolTip("Radius of the ball the surface is drawn in (re-meshed)")
        self.radius_box.setEnabled(False)
        self.patch_box = QCheckBox("Parameterization", self)
        self.patch_box.setToolTip("Overlay a patch of the first real rational parameterization")
        self.patch_box.setEnabled(False)
        self.profile_box = QCheckBox("Profile", self)
        self.profile_box.setChecked(True)
        self.profile_box.setToolTip("The profile curve in a plane through the axis")
        self.canal_box = QCheckBox("Canal", self)
        self.canal_box.setChecked(True)
        self.canal_box.setToolTip(
            "The spine of a canal surface (the spheres' centres) and a few "
            "characteristic circles (where the spheres touch the surface)"
        )
        self.canal_box.setEnabled(False)
        self.reset_button = QToolButton(self)
        self.reset_button.setText("Reset view")
        self.pick_label = QLabel("Right-click the surface (or press P) to inspect a point.", self)
        self.pick_label.setObjectName("pickLabel")
        self.pick_label.setWordWrap(True)
        self.pick_label.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)

        self.reset_button.setVisible(False)  # the toolbar's Reset does it
        self.controls = QWidget(self)  # like the buttons: wrapped, never hidden behind »
        self.controls.setObjectName("viewControls")
        controls = FlowLayout(self.controls, spacing=8)
        controls.setContentsMargins(6, 0, 6, 0)
        for widget in (self.radius_box, self.profile_box, self.canal_box, self.patch_box, self.deviation_box):
            controls.addWidget(widget)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.setSpacing(2)
        layout.addWidget(self.toolbar)
        layout.addWidget(self.controls)
        layout.addWidget(self.caption)
        layout.addWidget(self._placeholder, 1)
        layout.addWidget(self.pick_label)
        self.pick_label.setContentsMargins(6, 0, 6, 4)

        self._render_timer = QTimer(self)
        self._render_timer.setSingleShot(True)
        self._render_timer.setInterval(0)
        self._render_timer.timeout.connect(self._render_pending)
        self._radius_timer = QTimer(self)
        self._radius_timer.setSingleShot(True)
        self._radius_timer.setInterval(RADIUS_DELAY_MS)
        self._radius_timer.timeout.connect(self._apply_radius)
        self.radius_box.valueChanged.connect(self._on_radius_change)
        self.patch_box.toggled.connect(self._on_patch_visibility_change)
        self.profile_box.toggled.connect(self._on_profile_visibility_change)
        self.canal_box.toggled.connect(self._on_canal_visibility_change)
        self.deviation_box.toggled.connect(self._on_deviation_change)
        self.reset_button.clicked.connect(self.reset_camera)

    # --- the render window, created after the window is drawn ---

    def filter_drops(self, watcher: QObject) -> None:
        """Let ``watcher``'s event filter see the drags and drops on the 3D view, the render
        window included once it exists (pyvistaqt's own drop reads the file as a mesh)."""
        self._drop_filter = watcher
        self.installEventFilter(watcher)
        if self._plotter is not None:
            self._plotter.installEventFilter(watcher)

    @property
    def plotter(self) -> RenderWindow:
        """The pyvistaqt render window (created now if :meth:`start_rendering` has not run)."""
        if self._plotter is None:
            self.start_rendering()
        assert self._plotter is not None  # start_rendering made it
        return self._plotter

    @property
    def rendering(self) -> bool:
        """Whether the render window exists (it is created after the window is first drawn)."""
        return self._plotter is not None

    def start_rendering_soon(self) -> None:
        """Import pyvista and VTK's rendering on a thread (a second of Python that would
        otherwise hold up the GUI thread, and with it the first verdict), then create the
        render window on the GUI thread. The window calls this once it is drawn."""
        if self._plotter is not None or self._loading is not None:
            return
        if all(name in sys.modules for name in RENDERING_MODULES):  # a second window
            QTimer.singleShot(0, self, self.start_rendering)
            return
        for name in QT_MODULES_OF_THE_RENDER_WINDOW:
            with contextlib.suppress(ImportError):  # an add-on module may be missing; qtpy skips it too
                importlib.import_module(name)
        # The cycle collector waits while the thread imports: run there, it could delete a
        # widget that only Python owns, off the GUI thread.
        self._collecting = gc.isenabled()
        gc.disable()
        self._loading = threading.Thread(target=_import_rendering, name="sorgui-import-vtk", daemon=True)
        self._loading.start()
        self._loading_timer.start()

    def _show_loading(self) -> None:
        if self._loading is not None and not self._loading.is_alive():
            self.start_rendering()

    def _end_loading(self) -> None:
        """Wait for the import thread, if any (it imports what the caller is about to), and
        let the cycle collector run again."""
        self._loading_timer.stop()
        if self._loading is not None:
            self._loading.join()
        if self._collecting:
            gc.enable()
            self._collecting = False

    def start_rendering(self) -> None:
        """Import pyvista and VTK's rendering (waiting for :meth:`start_rendering_soon`'s
        thread, if any) and put the render window in place of the placeholder. Anything that
        needs the render window before it exists creates it through :attr:`plotter`."""
        if self._plotter is not None:
            return
        self._end_loading()
        from vtkmodules.vtkCommonDataModel import vtkPlane

        from sorgui.gui.render_window import RenderWindow
        from sorgui.render.hidden_lines import HiddenLines

        plotter = RenderWindow(self, auto_update=False, multi_samples=0)
        self._plotter = plotter
        self._hidden = HiddenLines(plotter)
        forwarders(plotter).set_background("#fbfcfe", top="#d9e2ee")
        forwarders(plotter).add_axes(line_width=3, labels_off=False)
        forwarders(plotter).enable_surface_point_picking(
            callback=self._pick,
            show_message=False,
            show_point=False,
            left_clicking=False,
            clear_on_no_selection=False,
        )
        self._remove_default_key_bindings()
        if self._drop_filter is not None:
            plotter.installEventFilter(self._drop_filter)
        self._clip_plane = vtkPlane()
        layout = self.layout()
        assert layout is not None  # the QVBoxLayout made in __init__
        layout.replaceWidget(self._placeholder, plotter)
        self._placeholder.deleteLater()
        plotter.show()
        self.software_rendering()  # found once the render window shows, for the next meshes
        _freeze_what_is_loaded()
        if self._waiting is not None:
            scene, reset_camera, camera = self._waiting
            stale, self._waiting = self._stale, None
            self.show_scene(scene, reset_camera)
            self.set_stale(stale)
            if camera is not None:
                self.restore_camera(camera)

    # --- public API ---

    @property
    def scene(self) -> SceneData | None:
        return self._scene

    def actor_names(self) -> set[str]:
        """Names of the actors in the renderer (for tests)."""
        return set(self.plotter.renderer.actors)

    def show_scene(self, scene: SceneData, reset_camera: bool = True, caption: str | None = None) -> None:
        """Replace the drawn scene by ``scene`` (actors updated in place by name); ``caption``
        names the surface shown; an empty view says why under it (the scene's note: no real
        points, numbers beyond floating point, a region that misses the surface)."""
        self._scene = scene
        self._stale = False
        if caption is not None:
            empty = scene.surface.is_empty and scene.notes
            self.caption.setText(f"{caption}\n{scene.notes[0]}" if empty else caption)
        if self._plotter is None and self._loading is not None and self._loading.is_alive():
            # A later scene of the same surface (its curves) keeps the camera waiting with the
            # first: the one restored from the last session, else the framing asked for.
            waiting = self._waiting
            camera = None if reset_camera or waiting is None else waiting[2]
            self._waiting = (scene, reset_camera or (waiting is not None and waiting[1]), camera)
            return  # drawn by start_rendering, once pyvista and VTK are imported
        self._clear_pick()
        self._show_surface()
        self._set_axis("axis", scene.axis_segment.to_polydata(), AXIS_COLOR, 4)
        self._set_axis("approx_axis", scene.approximate_axis.to_polydata(), APPROXIMATE_AXIS_COLOR, 3)
        self._set_axis("factor_axes", scene.factor_axes.to_polydata(), FACTOR_AXES_COLOR, 3)
        self.deviation_box.setEnabled(scene.deviation is not None)
        self.view_actions["along"].setEnabled(self._axis() is not None)
        self.view_actions["across"].setEnabled(self._axis() is not None)
        self.view_actions["clip"].setEnabled(scene.axis is not None)
        self._set_actor(
            "profile",
            scene.profile_curve.to_polydata(),
            color=PROFILE_COLOR,
            line_width=4,
            visible=self.profile_box.isChecked(),
        )
        canal = self.canal_box.isChecked()
        self._set_actor(
            "canal_spine", scene.canal_spine.to_polydata(), color=CANAL_SPINE_COLOR, line_width=4, visible=canal
        )
        self._set_actor(
            "canal_circles", scene.canal_circles.to_polydata(), color=CANAL_CIRCLE_COLOR, line_width=2, visible=canal
        )
        self.canal_box.setEnabled(not (scene.canal_spine.is_empty and scene.canal_circles.is_empty))
        self._set_actor("base_curve", scene.base_curve.to_polydata(), color=BASE_CURVE_COLOR, line_width=4)
        import pyvista

        center = scene.center_marker.to_polydata() if scene.center_marker else pyvista.PolyData()
        self._set_actor("center", center, color=CENTER_COLOR, interpolation="gouraud")
        patch = scene.patch.to_polydata() if scene.patch is not None else pyvista.PolyData()
        self._set_actor(
            "patch",
            patch,
            color=PATCH_COLOR,
            style="wireframe",
            line_width=1,
            opacity=0.8,
            visible=self.patch_box.isChecked(),
        )
        self.patch_box.setEnabled(patch.n_points > 0)
        self.radius_box.blockSignals(True)
        _fit_radius_box(self.radius_box, scene.region.radius)
        self.radius_box.setValue(scene.region.radius)
        self.radius_box.blockSignals(False)
        self.radius_box.setEnabled(True)
        if reset_camera:
            self.reset_camera(render=False)
        self.request_render()

    def clear(self, caption: str = "No surface") -> None:
        """Remove the scene (a new analysis started, or the input is not a polynomial)."""
        self._scene = None
        self._waiting = None
        self._stale = False
        self.caption.setText(caption)
        self.radius_box.blockSignals(True)
        self.radius_box.setValue(0.0)
        self.radius_box.blockSignals(False)
        self.radius_box.setEnabled(False)
        self.patch_box.setEnabled(False)
        self.canal_box.setEnabled(False)
        self.deviation_box.setEnabled(False)
        if self._plotter is None:
            return
        self._remove_scalar_bar()
        for name in SCENE_ACTORS + PICK_ACTORS:
            forwarders(self._plotter).remove_actor(name, render=False)
        for name in AXIS_ACTORS:
            self.hidden_lines.remove(name)
        self.request_render()

    def set_stale(self, stale: bool, caption: str | None = None) -> None:
        """Grey the surface (it belongs to the previous equation) or colour it again."""
        if caption is not None:
            self.caption.setText(caption)
        if stale == self._stale or self._scene is None or self._waiting is not None:
            self._stale = stale and self._scene is not None
            return  # a waiting scene is drawn as it then is
        self._stale = stale
        self._show_surface()
        self.request_render()

    @property
    def stale(self) -> bool:
        return self._stale

    def reset_camera(self, render: bool = True) -> None:
        """Look at the drawn ball from an isometric direction (a plane from its front,
        :func:`~sorgui.render.geometry.view_direction`)."""
        if self._scene is None:
            forwarders(self.plotter).view_isometric(render=False)
        else:
            surface = self._scene.surface
            direction = view_direction(surface.normals, surface.side)
            forwarders(self.plotter).view_vector(direction, view_up(direction), render=False)
            c, r = framed(self._scene)
            bounds = tuple(v for i in range(3) for v in (c[i] - r, c[i] + r))
            # The renderer's own method: pyvista's Plotter.reset_camera renders regardless.
            self.plotter.renderer.reset_camera(render=False, bounds=bounds)
        if render:
            self.render_now()

    def set_view(self, name: str) -> None:
        """One of the standard views: ``along``/``across`` the axis, ``x``, ``y``, ``z``, ``reset``."""
        if name == "reset":
            self.reset_camera()
            return
        center, radius = framed(self._scene) if self._scene is not None else (np.zeros(3), 1.0)
        axis = self._axis()
        if name in ("along", "across"):
            if axis is None:
                return
            position, up = (view_along if name == "along" else view_across)(center, radius, axis[1])
        else:
            position, up = coordinate_view(center, radius, name)
        camera = self.plotter.renderer.GetActiveCamera()
        camera.SetFocalPoint(*center)
        camera.SetPosition(*position)
        camera.SetViewUp(*up)
        bounds = tuple(v for i in range(3) for v in (center[i] - radius, center[i] + radius))
        self.plotter.renderer.reset_camera(render=False, bounds=bounds)
        self.render_now()

    def set_parallel_projection(self, parallel: bool) -> None:
        """Orthographic (``True``) or perspective projection."""
        self.plotter.renderer.GetActiveCamera().SetParallelProjection(parallel)
        self.view_actions["parallel"].setChecked(parallel)
        if self._scene is not None:
            self.plotter.renderer.reset_camera(render=False)
        self.render_now()

    def set_wireframe(self, wireframe: bool) -> None:
        """Draw the surface as its triangle edges (``True``) or shaded."""
        self.view_actions["wireframe"].setChecked(wireframe)
        actor = self.plotter.renderer.actors.get("surface")
        if actor is not None:
            actor.prop.style = "wireframe" if wireframe else "surface"
        self.render_now()

    def set_clip(self, clip: bool) -> None:
        """Cut the surface along the meridian plane through the axis (shows the profile)."""
        self.view_actions["clip"].setChecked(clip)
        self._apply_clip()
        self.render_now()

    def camera_state(self) -> CameraState:
        """The camera now (for the settings)."""
        camera = self.plotter.renderer.GetActiveCamera()
        return CameraState(
            tuple(camera.GetPosition()),
            tuple(camera.GetFocalPoint()),
            tuple(camera.GetViewUp()),
            camera.GetViewAngle(),
            camera.GetParallelScale(),
            bool(camera.GetParallelProjection()),
        )

    def restore_camera(self, state: CameraState) -> None:
        """Put the camera where ``state`` says (once the render window exists, when a scene is
        waiting for it)."""
        if self._waiting is not None:
            self._waiting = (*self._waiting[:2], state)
            return
        camera = self.plotter.renderer.GetActiveCamera()
        camera.SetPosition(*state.position)
        camera.SetFocalPoint(*state.focal_point)
        camera.SetViewUp(*state.view_up)
        camera.SetViewAngle(state.view_angle)
        camera.SetParallelScale(state.parallel_scale)
        camera.SetParallelProjection(state.parallel)
        self.view_actions["parallel"].setChecked(state.parallel)
        self.plotter.renderer.ResetCameraClippingRange()
        self.render_now()

    def render_now(self) -> None:
        """Render at once (a view change the user asked for is drawn immediately)."""
        self.plotter.render()

    def request_render(self) -> None:
        """Render in a later turn of the event loop than this one: once however many changes
        are asked for, never in the middle of a handler, and never in the same turn as the
        work that changed the actors (a new mesh's first frame in software OpenGL alone takes
        most of the 100 ms a turn may take)."""
        if self._plotter is None:
            return
        self._plotter.scene_changed()  # a paint before the timer's renders the scene too
        if not self._render_timer.isActive():
            self._render_timer.start()

    def _render_pending(self) -> None:
        if self._plotter is not None:
            self._plotter.update()

    def pick_point(self, point: np.ndarray | tuple[float, float, float]) -> PickInfo | None:
        """Inspect the surface at ``point`` as if it had been picked there."""
        return self._pick(np.asarray(point, dtype=np.float64))

    def screenshot(self, path: str | Path) -> None:
        """Save the render window as a PNG image."""
        self.plotter.screenshot(str(path))

    def close_plotter(self) -> None:
        """Stop timers and release the render window and every VTK object of the scene now,
        while the native window still exists: VTK objects left in reference cycles would
        otherwise be freed by a later garbage collection, after Qt destroyed that window."""
        self._radius_timer.stop()
        self._render_timer.stop()
        self._end_loading()
        if self._plotter is None:
            return
        self._plotter.close()
        self._plotter.deep_clean()
        gc.collect()

    # --- handlers ---

    def _pick(self, point: np.ndarray) -> PickInfo | None:
        import pyvista

        from sorgui.render.picking import pick_info
        from sorgui.render.scene import LineData

        scene = self._scene
        if scene is None or point is None or not np.all(np.isfinite(point)):
            return None
        info = pick_info(
            scene.terms,
            point,
            axis=self._axis(),  # the approximate axis of rounded input too: its height, radius and axis test
            normal_length=0.6 * scene.region.radius,
            snap_distance=2.0 * scene.surface.spacing,
            typed_terms=scene.typed_terms,
        )
        self._set_actor("pick_normal", info.normal.to_polydata(), color=NORMAL_COLOR, line_width=3)
        self._set_actor("pick_circle", info.latitude.to_polydata(), color=LATITUDE_COLOR, line_width=3)
        marker = pyvista.Sphere(radius=0.012 * scene.region.radius, center=info.point)
        self._set_actor("pick_point", marker, color=PICK_COLOR)
        touches = touching_spheres(
            scene.canal_families, info.point, 0.02 * scene.region.radius, normal=info.normal_direction
        )
        spheres = pyvista.PolyData()
        for touch in touches:
            spheres = spheres.merge(
                pyvista.Sphere(radius=touch.radius, center=touch.center, theta_resolution=24, phi_resolution=12)
            )
        self._set_actor("pick_sphere", spheres, color=TOUCH_SPHERE_COLOR, style="wireframe", opacity=0.3, line_width=1)
        circles = LineData.from_polylines([t.circle for t in touches])
        self._set_actor("pick_canal_circle", circles.to_polydata(), color=TOUCH_CIRCLE_COLOR, line_width=4)
        self.pick_label.setText(" · ".join([_pick_text(info)] + [_touch_text(t) for t in touches]))
        self.request_render()
        self.picked.emit(info)
        return info

    def _on_radius_change(self, _value: float) -> None:
        self._radius_timer.start()

    def _apply_radius(self) -> None:
        radius = self.radius_box.value()
        if self._scene is not None and (radius == 0 or abs(radius - self._scene.region.radius) > 1e-9 * radius):
            self.radius_requested.emit(radius)  # 0: the automatic ball again

    def _on_patch_visibility_change(self, visible: bool) -> None:
        self._set_visibility("patch", visible)

    def _on_profile_visibility_change(self, visible: bool) -> None:
        self._set_visibility("profile", visible)

    def _on_canal_visibility_change(self, visible: bool) -> None:
        for name in CANAL_ACTORS:
            self._set_visibility(name, visible)

    # --- helpers ---

    def _set_visibility(self, name: str, visible: bool) -> None:
        actor = self.plotter.renderer.actors.get(name)
        if actor is not None:
            actor.SetVisibility(visible)
            self.request_render()

    def _set_actor(
        self,
        name: str,
        mesh: pyvista.PolyData,
        visible: bool = True,
        interpolation: str | None = None,
        **kwargs: Any,
    ) -> None:
        """Add or replace the actor ``name``; an empty mesh removes it."""
        if mesh.n_points == 0:
            forwarders(self.plotter).remove_actor(name, render=False)
            return
        kwargs.setdefault("pickable", False)
        actor = self.plotter.add_mesh(mesh, name=name, reset_camera=False, render=False, **kwargs)
        if interpolation is not None:
            actor.prop.interpolation = interpolation
        actor.SetVisibility(visible)

    def _set_axis(self, name: str, mesh: pyvista.PolyData, color: str, line_width: float) -> None:
        """Add or replace the axis ``name``, and its faint copy where the surface hides it."""
        self._set_actor(name, mesh, color=color, line_width=line_width)
        self.hidden_lines.show(name, mesh, color, line_width)

    @property
    def hidden_lines(self) -> HiddenLines:
        """The axes drawn faint through the surface (made with the render window)."""
        if self._hidden is None:
            self.start_rendering()
        assert self._hidden is not None  # made by start_rendering
        return self._hidden

    def software_rendering(self) -> bool:
        """Whether OpenGL runs in software (Mesa's llvmpipe, e.g. under Xvfb), found once.

        Then every frame costs the processor, so meshes are coarser, edges are not smoothed and
        one light at the camera replaces the kit of five.
        """
        if self._software is None:
            if self._plotter is None or not self._plotter.isVisible():
                return self.software_guess  # no OpenGL context yet
            ren_win = self.plotter.ren_win
            assert ren_win is not None  # the render window is shown
            ren_win.Render()  # creates the OpenGL context if needed (a cheap frame)
            report = ren_win.ReportCapabilities() or ""
            self._software = any(name in report for name in SOFTWARE_RENDERERS)
            if self._software:
                self._light_from_the_eye()
            else:
                self.plotter.enable_anti_aliasing("fxaa")
        return self._software

    def _light_from_the_eye(self) -> None:
        """One light at the camera instead of pyvista's kit of five: a frame of a degree-12
        surface costs about a quarter less in software OpenGL (issue 30), and the side turned
        to the user is always the lit one."""
        import pyvista

        self.plotter.remove_all_lights()
        self.plotter.add_light(pyvista.Light(light_type="headlight"))

    @property
    def detected_software(self) -> bool | None:
        """Whether OpenGL was found to run in software (``None`` until it was looked at)."""
        return self._software

    def mesh_resolution(self) -> int:
        """Grid nodes across the drawn ball: fewer triangles when rendering in software."""
        return SOFTWARE_RESOLUTION if self.software_rendering() else HARDWARE_RESOLUTION

    def _remove_default_key_bindings(self) -> None:
        """Silence VTK's interactor-style keys and pyvista's; P picks at the mouse instead."""
        iren = self.plotter.iren
        iren.interactor.RemoveObservers("CharEvent")
        iren.clear_key_event_callbacks()
        iren.add_key_event("p", self._pick_at_mouse)
        iren.add_key_event("P", self._pick_at_mouse)

    def _pick_at_mouse(self) -> None:
        """P: pick the point under the pointer where it is now. The interactor's own event
        position is where it last saw the mouse move, and a pointer that has not moved since a
        new render window came under it sends no move (Qt drops a move to the same place)."""
        plotter = self.plotter
        where = plotter.mapFromGlobal(QCursor.pos())
        ratio = plotter.devicePixelRatioF()
        interactor = plotter.iren.interactor
        interactor.SetEventInformationFlipY(int(round(where.x() * ratio)), int(round(where.y() * ratio)))
        x, y = interactor.GetEventPosition()
        plotter.iren.picker.Pick(x, y, 0, plotter.renderer)

    def _build_view_actions(self) -> dict[str, QAction]:
        specs = (
            ("along", "View Along the &Axis", "Ctrl+Alt+A", lambda: self.set_view("along")),
            ("across", "View A&cross the Axis", "Ctrl+Alt+C", lambda: self.set_view("across")),
            ("x", "View Along &x", "Ctrl+Alt+X", lambda: self.set_view("x")),
            ("y", "View Along &y", "Ctrl+Alt+Y", lambda: self.set_view("y")),
            ("z", "View Along &z", "Ctrl+Alt+Z", lambda: self.set_view("z")),
            ("reset", "&Reset View", "Ctrl+R", lambda: self.set_view("reset")),
        )
        actions: dict[str, QAction] = {}
        for name, text, key, slot in specs:
            action = QAction(text, self)
            action.setIconText({"along": "Along axis", "across": "Across axis", "reset": "Reset"}.get(name, name))
            action.setShortcut(QKeySequence(key))
            action.setToolTip(f"{text.replace('&', '')} ({key})")
            action.triggered.connect(lambda _checked=False, f=slot: f())
            actions[name] = action
        toggles = (
            ("parallel", "&Orthographic Projection", "Ctrl+Alt+O", "Ortho", self.set_parallel_projection),
            ("wireframe", "&Wireframe", "Ctrl+Alt+W", "Wireframe", self.set_wireframe),
            ("clip", "&Meridian Section", "Ctrl+Alt+M", "Section", self.set_clip),
        )
        for name, text, key, short, setter in toggles:
            action = QAction(text, self)
            action.setCheckable(True)
            action.setIconText(short)
            action.setShortcut(QKeySequence(key))
            action.setToolTip(f"{text.replace('&', '')} ({key})")
            action.triggered.connect(lambda checked=False, f=setter: f(checked))
            actions[name] = action
        actions["clip"].setToolTip(
            "Cut the surface along the plane through the axis and the profile: "
            "the cut's edge is the profile curve (Ctrl+Alt+M)"
        )
        for name in ("along", "across", "clip"):
            actions[name].setEnabled(False)
        return actions

    def _axis(self) -> tuple[np.ndarray, np.ndarray] | None:
        """The drawn axis: the exact one, else the approximate axis of rounded input, each from
        the point the results pane gives (heights count from it; they counted from where the
        drawn approximate axis leaves the ball)."""
        scene = self._scene
        if scene is None:
            return None
        if scene.axis is not None:
            return scene.axis
        if not scene.approximate_axis.is_empty:
            a, b = scene.approximate_axis.points[0], scene.approximate_axis.points[-1]
            point = scene.approximate_axis_point
            return (a if point is None else np.asarray(point, dtype=float)), b - a
        return None

    def _show_surface(self) -> None:
        """The surface actor as the state asks: side colours, deviation colours, or grey if stale."""
        scene = self._scene
        if scene is None:
            return
        mesh = scene.surface.to_polydata()
        deviation = self.deviation_box.isChecked() and scene.deviation is not None and not self._stale
        self._remove_scalar_bar()
        if self._stale:
            self._set_actor("surface", mesh, color=STALE_COLOR, opacity=0.45, pickable=False, interpolation="gouraud")
        elif deviation and mesh.n_points:
            mesh.point_data["deviation"] = np.asarray(scene.deviation)
            self._set_actor(
                "surface",
                mesh,
                scalars="deviation",
                cmap=DEVIATION_MAP,
                pickable=True,
                interpolation="gouraud",
                nan_color=STALE_COLOR,
                scalar_bar_args={
                    "title": "deviation",
                    "vertical": True,
                    "fmt": "%.1e",
                    "position_x": 0.86,
                    "width": 0.08,
                },
            )
        else:
            self._set_actor(
                "surface",
                mesh,
                color=FRONT_COLOR,
                backface_params={"color": BACK_COLOR},
                specular=0.35,
                specular_power=20.0,
                pickable=True,
                interpolation="gouraud",
            )
        actor = self.plotter.renderer.actors.get("surface")
        if actor is not None and self.view_actions["wireframe"].isChecked():
            actor.prop.style = "wireframe"
        self._apply_clip()

    def _remove_scalar_bar(self) -> None:
        for title in list(self.plotter.scalar_bars.keys()):
            self.plotter.remove_scalar_bar(title, render=False)

    def _apply_clip(self) -> None:
        """Clip the surface (and the patch) by the meridian plane, if asked and there is an axis."""
        scene = self._scene
        plane = None
        if self.view_actions["clip"].isChecked() and scene is not None and scene.axis is not None:
            plane = self._clip_plane
            assert plane is not None  # made with the render window, which drew the scene
            point, direction = scene.axis
            normal = meridian_normal(point, direction, scene.profile_curve.points)
            plane.SetOrigin(*point)
            plane.SetNormal(*normal)
        for name in ("surface", "patch"):
            actor = self.plotter.renderer.actors.get(name)
            if actor is None:
                continue
            mapper = actor.GetMapper()
            mapper.RemoveAllClippingPlanes()
            if plane is not None:
                mapper.AddClippingPlane(plane)

    def _on_deviation_change(self, _checked: bool) -> None:
        self._show_surface()
        self.request_render()

    def hide_inspection(self) -> list[Any]:
        """Hide the visible actors of the picked point (for a picture of the surface alone) and
        return them, to be shown again."""
        hidden = []
        for name in PICK_ACTORS:
            actor = self.plotter.renderer.actors.get(name)
            if actor is not None and actor.GetVisibility():
                actor.SetVisibility(False)
                hidden.append(actor)
        return hidden

    def _clear_pick(self) -> None:
        for name in PICK_ACTORS:
            forwarders(self.plotter).remove_actor(name, render=False)
        self.pick_label.setText("Right-click the surface (or press P) to inspect a point.")
        self.pick_cleared.emit()


def _touch_text(touch: Touch) -> str:
    """The sphere of a canal family touching the surface at the picked point, in words (the
    search's floating-point noise, below 1e-9 of the centre's size, shown as 0)."""
    centre = floats(tuple(float(c) for c in touch.center), digits=4, tolerance=TOUCH_NOISE)
    return f"touching sphere of family {touch.family + 1}: centre {centre}, radius {touch.radius:.4g}"


TOUCH_NOISE = 1e-9
"""The relative precision of the touching sphere's centre (a search over the family's parameter)."""


def _pick_text(info: PickInfo) -> str:
    """The picked point's report, in words."""
    x, y, z = info.point
    parts = [f"<b>p</b> = ({x:.5g}, {y:.5g}, {z:.5g})", f"f(p) = {info.value:.3g}"]
    if info.is_singular:
        parts.append("singular point: ∇f = 0, no normal line")
    elif info.axis_test is not None:
        parts.append(info.axis_test.words(lambda verb: f"<b>{verb}</b>"))
    if np.isfinite(info.radius):
        parts.append(f"height {info.height:.4g}, radius {info.radius:.4g}")
    return " · ".join(parts)


def _fit_radius_box(box: QDoubleSpinBox, radius: float) -> None:
    """The radius box's digits, range and step for a ball of ``radius``: about four significant
    digits, up to 100 times it, a step of a quarter of its power of ten. A fixed range of 0 to
    10⁴ with 3 decimals showed a part's ball of radius 5e6 as 10000.000 (one step down drew a
    ball that held none of it) and one of radius 0.000177 as "automatic"."""
    magnitude = math.floor(math.log10(radius)) if radius > 0 and math.isfinite(radius) else 0
    box.setDecimals(min(max(3, 3 - magnitude), 15))
    box.setRange(0.0, max(1e4, 100.0 * radius) if math.isfinite(radius) else 1e4)
    box.setSingleStep(0.25 * 10.0**magnitude)
