"""The 3D viewport: the surface, its axis and profile, and point-and-click inspection.

A pyvistaqt ``QtInteractor`` is embedded in a widget with a small tool row. Actors are built on
the GUI thread from the plain arrays of a :class:`~sorgui.gui.scene_data.SceneData` that the
worker process computed, and replaced in place by name (``add_mesh(..., name="surface")``).
The surface's two sides have two colours (the mesh is wound to face ``f > 0``). Right-click
(or P) on the surface picks a point: the viewport draws its normal line and its circle of
latitude, and reports ``f`` there and whether the normal meets the axis (the paper's
characterisation of surfaces of revolution, tested by :func:`sorgui.render.picking.pick_info`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pyvista
from pyvistaqt import QtInteractor
from PySide6.QtCore import Qt, QTimer, Signal
from PySide6.QtWidgets import (
    QCheckBox,
    QDoubleSpinBox,
    QHBoxLayout,
    QLabel,
    QToolButton,
    QVBoxLayout,
    QWidget,
)

from sorgui.gui.scene_data import SceneData
from sorgui.render import mesh_to_polydata, pick_info, to_polydata
from sorgui.render.picking import PickInfo

FRONT_COLOR = "#7fa7d6"
"""The side ``f > 0`` of the surface."""
BACK_COLOR = "#e8a95b"
"""The side ``f < 0``."""
AXIS_COLOR = "#1f2a44"
PROFILE_COLOR = "#c2185b"
CENTER_COLOR = "#d32f2f"
PATCH_COLOR = "#2e7d32"
NORMAL_COLOR = "#ff6f00"
LATITUDE_COLOR = "#6a1b9a"
PICK_COLOR = "#111111"

SCENE_ACTORS = ("surface", "axis", "profile", "center", "patch")
PICK_ACTORS = ("pick_normal", "pick_circle", "pick_point")

SOFTWARE_RENDERERS = ("llvmpipe", "softpipe", "swrast", "Software Rasterizer")
SOFTWARE_RESOLUTION = 90
HARDWARE_RESOLUTION = 160
"""Grid nodes across the drawn ball (about 33 000 and 105 000 triangles for a torus)."""

RADIUS_DELAY_MS = 500
"""Debounce of the radius box: the ball is re-meshed this long after the last change."""


class Viewport(QWidget):
    """The render window with its controls.

    :attr:`radius_requested` asks for the scene to be rebuilt in a ball of the given radius;
    :attr:`picked` carries the :class:`~sorgui.render.picking.PickInfo` of a picked point.
    """

    radius_requested = Signal(float)
    picked = Signal(object)

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.plotter = QtInteractor(self, auto_update=False, multi_samples=0)
        self.plotter.set_background("#fbfcfe", top="#d9e2ee")
        self.plotter.add_axes(line_width=3, labels_off=False)
        self.plotter.enable_surface_point_picking(
            callback=self._on_pick_change, show_message=False, show_point=False,
            left_clicking=False, clear_on_no_selection=False,
        )
        self._scene: SceneData | None = None
        self._software: bool | None = None

        self.radius_box = QDoubleSpinBox(self)
        self.radius_box.setObjectName("radiusBox")
        self.radius_box.setDecimals(3)
        self.radius_box.setRange(1e-3, 1e4)
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
        self.reset_button = QToolButton(self)
        self.reset_button.setText("Reset view")
        self.pick_label = QLabel("Right-click the surface (or press P) to inspect a point.", self)
        self.pick_label.setObjectName("pickLabel")
        self.pick_label.setWordWrap(True)
        self.pick_label.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)

        controls = QHBoxLayout()
        controls.setContentsMargins(6, 4, 6, 0)
        for widget in (self.reset_button, self.radius_box, self.profile_box, self.patch_box):
            controls.addWidget(widget)
        controls.addStretch(1)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.setSpacing(2)
        layout.addLayout(controls)
        layout.addWidget(self.plotter, 1)
        layout.addWidget(self.pick_label)
        self.pick_label.setContentsMargins(6, 0, 6, 4)

        self._radius_timer = QTimer(self)
        self._radius_timer.setSingleShot(True)
        self._radius_timer.setInterval(RADIUS_DELAY_MS)
        self._radius_timer.timeout.connect(self._on_radius_timer_change)
        self.radius_box.valueChanged.connect(self._on_radius_change)
        self.patch_box.toggled.connect(self._on_patch_visibility_change)
        self.profile_box.toggled.connect(self._on_profile_visibility_change)
        self.reset_button.clicked.connect(self.reset_camera)

    # --- public API ---

    @property
    def scene(self) -> SceneData | None:
        return self._scene

    def actor_names(self) -> set[str]:
        """Names of the actors in the renderer (for tests)."""
        return set(self.plotter.renderer.actors)

    def show_scene(self, scene: SceneData, reset_camera: bool = True) -> None:
        """Replace the drawn scene by ``scene`` (actors updated in place by name)."""
        self._scene = scene
        self._clear_pick()
        self._set_actor("surface", mesh_to_polydata(scene.surface), color=FRONT_COLOR,
                        backface_params={"color": BACK_COLOR}, specular=0.35,
                        specular_power=20.0, pickable=True, interpolation="gouraud")
        self._set_actor("axis", to_polydata(scene.axis_segment), color=AXIS_COLOR, line_width=4)
        self._set_actor("profile", to_polydata(scene.profile_curve), color=PROFILE_COLOR,
                        line_width=4, visible=self.profile_box.isChecked())
        center = to_polydata(scene.center_marker) if scene.center_marker else pyvista.PolyData()
        self._set_actor("center", center, color=CENTER_COLOR, interpolation="gouraud")
        patch = scene.patch.to_polydata() if scene.patch is not None else pyvista.PolyData()
        self._set_actor("patch", patch, color=PATCH_COLOR, style="wireframe", line_width=1,
                        opacity=0.8, visible=self.patch_box.isChecked())
        self.patch_box.setEnabled(patch.n_points > 0)
        self.radius_box.blockSignals(True)
        self.radius_box.setValue(scene.region.radius)
        self.radius_box.blockSignals(False)
        self.radius_box.setEnabled(True)
        if reset_camera:
            self.reset_camera(render=False)
        self.request_render()

    def clear(self) -> None:
        """Remove the scene (e.g. when the input is not a polynomial)."""
        self._scene = None
        for name in SCENE_ACTORS + PICK_ACTORS:
            self.plotter.remove_actor(name, render=False)
        self.radius_box.setEnabled(False)
        self.patch_box.setEnabled(False)
        self.request_render()

    def reset_camera(self, render: bool = True) -> None:
        """Look at the drawn ball from an isometric direction."""
        self.plotter.view_isometric(render=False)
        if self._scene is not None:
            c, r = np.asarray(self._scene.region.center), self._scene.region.radius
            bounds = tuple(v for i in range(3) for v in (c[i] - r, c[i] + r))
            # The renderer's own method: pyvista's Plotter.reset_camera renders regardless.
            self.plotter.renderer.reset_camera(render=False, bounds=bounds)
        if render:
            self.request_render()

    def request_render(self) -> None:
        """Render at the next paint event: the GUI thread renders once per event-loop turn,
        after the actors are updated, never in the middle of a handler."""
        self.plotter.update()

    def pick_point(self, point: np.ndarray | tuple[float, float, float]) -> PickInfo | None:
        """Inspect the surface at ``point`` as if it had been picked there."""
        return self._on_pick_change(np.asarray(point, dtype=np.float64))

    def screenshot(self, path: str | Path) -> None:
        """Save the render window as a PNG image."""
        self.plotter.screenshot(str(path))

    def close_plotter(self) -> None:
        """Stop timers and release the render window (before the widget is destroyed)."""
        self._radius_timer.stop()
        self.plotter.close()

    # --- handlers ---

    def _on_pick_change(self, point: np.ndarray) -> PickInfo | None:
        scene = self._scene
        if scene is None or point is None or not np.all(np.isfinite(point)):
            return None
        info = pick_info(
            scene.terms, point, axis=scene.axis,
            normal_length=0.6 * scene.region.radius,
            snap_distance=2.0 * scene.surface.spacing,
        )
        self._set_actor("pick_normal", to_polydata(info.normal), color=NORMAL_COLOR, line_width=3)
        self._set_actor("pick_circle", to_polydata(info.latitude), color=LATITUDE_COLOR, line_width=3)
        marker = pyvista.Sphere(radius=0.012 * scene.region.radius, center=info.point)
        self._set_actor("pick_point", marker, color=PICK_COLOR)
        self.pick_label.setText(_pick_text(info))
        self.request_render()
        self.picked.emit(info)
        return info

    def _on_radius_change(self, _value: float) -> None:
        self._radius_timer.start()

    def _on_radius_timer_change(self) -> None:
        if self._scene is not None and abs(self.radius_box.value() - self._scene.region.radius) > 1e-9:
            self.radius_requested.emit(self.radius_box.value())

    def _on_patch_visibility_change(self, visible: bool) -> None:
        self._set_visibility("patch", visible)

    def _on_profile_visibility_change(self, visible: bool) -> None:
        self._set_visibility("profile", visible)

    # --- helpers ---

    def _set_visibility(self, name: str, visible: bool) -> None:
        actor = self.plotter.renderer.actors.get(name)
        if actor is not None:
            actor.SetVisibility(visible)
            self.request_render()

    def _set_actor(
        self, name: str, mesh: pyvista.PolyData, visible: bool = True,
        interpolation: str | None = None, **kwargs: object,
    ) -> None:
        """Add or replace the actor ``name``; an empty mesh removes it."""
        if mesh.n_points == 0:
            self.plotter.remove_actor(name, render=False)
            return
        kwargs.setdefault("pickable", False)
        actor = self.plotter.add_mesh(mesh, name=name, reset_camera=False, render=False, **kwargs)
        if interpolation is not None:
            actor.prop.interpolation = interpolation
        actor.SetVisibility(visible)

    def software_rendering(self) -> bool:
        """Whether OpenGL runs in software (Mesa's llvmpipe, e.g. under Xvfb), found once.

        Then every frame costs the processor, so meshes are coarser and edges are not smoothed.
        """
        if self._software is None:
            if not self.plotter.isVisible():
                return True  # no OpenGL context before the window shows: assume the worst
            self.plotter.ren_win.Render()  # creates the OpenGL context if needed (a cheap frame)
            report = self.plotter.ren_win.ReportCapabilities() or ""
            self._software = any(name in report for name in SOFTWARE_RENDERERS)
            if not self._software:
                self.plotter.enable_anti_aliasing("fxaa")
        return self._software

    def mesh_resolution(self) -> int:
        """Grid nodes across the drawn ball: fewer triangles when rendering in software."""
        return SOFTWARE_RESOLUTION if self.software_rendering() else HARDWARE_RESOLUTION

    def _clear_pick(self) -> None:
        for name in PICK_ACTORS:
            self.plotter.remove_actor(name, render=False)
        self.pick_label.setText("Right-click the surface (or press P) to inspect a point.")


def _pick_text(info: PickInfo) -> str:
    """The picked point's report, in words."""
    x, y, z = info.point
    parts = [f"<b>p</b> = ({x:.5g}, {y:.5g}, {z:.5g})", f"f(p) = {info.value:.3g}"]
    if info.is_singular:
        parts.append("singular point: ∇f = 0, no normal line")
    elif info.axis_test is not None:
        verdict = "<b>meets</b> the axis" if info.axis_test.meets else "<b>misses</b> the axis"
        parts.append(f"normal {verdict} (distance {info.axis_test.distance:.2g})")
    if np.isfinite(info.radius):
        parts.append(f"height {info.height:.4g}, radius {info.radius:.4g}")
    return " · ".join(parts)

