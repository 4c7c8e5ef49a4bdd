"""A PNG picture of the surface and its axis, rendered off screen for the Markdown/HTML reports.

The scene (``sorgui.session.scene_data.SceneData``: surface mesh, axis segment, profile curve,
sphere centre, rounded input's approximate axis and the axes of a product's factors) is drawn by
an off-screen pyvista plotter in the viewport's colours, from the viewport's isometric
direction; the axes show faint where the surface hides them, as in the window
(:mod:`sorgui.render.hidden_lines`). VTK picks the OpenGL context
itself: GLX under X (or Xvfb), EGL or OSMesa without a display; when none can be had,
:func:`render_png` raises ``RuntimeError`` and the reports are written without a picture.
"""

from __future__ import annotations

import gc
from pathlib import Path
from typing import Protocol

import numpy as np

from sorgui.render import ClipSphere, LineData, MarkerData, MeshData

PICTURE_SIZE = (900, 700)
"""Width and height of the report picture, in pixels."""

SURFACE_COLOR = "#7fa7d6"
BACK_COLOR = "#e8a95b"
AXIS_COLOR = "#1f2a44"
APPROXIMATE_AXIS_COLOR = "#ef6c00"
FACTOR_AXES_COLOR = "#455a64"
PROFILE_COLOR = "#c2185b"
CENTER_COLOR = "#d32f2f"


class PictureScene(Protocol):
    """What the picture needs of a scene."""

    surface: MeshData
    axis_segment: LineData
    approximate_axis: LineData
    factor_axes: LineData
    profile_curve: LineData
    center_marker: MarkerData | None
    region: ClipSphere


def render_png(scene: PictureScene, size: tuple[int, int] = PICTURE_SIZE, transparent: bool = False) -> bytes:
    """The scene as PNG bytes of ``size`` pixels; ``RuntimeError`` without an OpenGL context."""
    import pyvista
    from vtkmodules.vtkCommonCore import vtkObject

    from sorgui.render import mesh_to_polydata
    from sorgui.render.geometry import view_direction, view_up
    from sorgui.render.hidden_lines import HiddenLines
    from sorgui.render.plotting import forwarders

    warnings = vtkObject.GetGlobalWarningDisplay()
    vtkObject.GlobalWarningDisplayOff()  # VTK's note that X is missing before it falls back to EGL
    try:
        plotter = pyvista.Plotter(off_screen=True, window_size=list(size))
        try:
            forwarders(plotter).set_background("white")
            if not scene.surface.is_empty:
                actor = plotter.add_mesh(
                    mesh_to_polydata(scene.surface),
                    color=SURFACE_COLOR,
                    specular=0.35,
                    backface_params={"color": BACK_COLOR},
                    smooth_shading=True,
                )
                actor.prop.interpolation = "gouraud"
            hidden = HiddenLines(plotter)
            axes = (
                ("axis", scene.axis_segment, AXIS_COLOR),
                ("approx_axis", scene.approximate_axis, APPROXIMATE_AXIS_COLOR),
                ("factor_axes", scene.factor_axes, FACTOR_AXES_COLOR),
            )
            for name, data, color in axes:
                if not data.is_empty:
                    plotter.add_mesh(data.to_polydata(), color=color, line_width=4)
                    hidden.show(name, data.to_polydata(), color, 4)
            if not scene.profile_curve.is_empty:
                plotter.add_mesh(scene.profile_curve.to_polydata(), color=PROFILE_COLOR, line_width=4)
            if scene.center_marker is not None:
                plotter.add_mesh(scene.center_marker.to_polydata(), color=CENTER_COLOR)
            direction = view_direction(scene.surface.normals, scene.surface.side)
            forwarders(plotter).view_vector(direction, view_up(direction))
            c, r = np.asarray(scene.region.center), scene.region.radius
            forwarders(plotter).reset_camera(bounds=[v for i in range(3) for v in (c[i] - r, c[i] + r)])
            # The ball's corners are empty: frame the ball, not its box (pyvista leaves zoom unannotated).
            plotter.camera.zoom(1.4)  # type: ignore[no-untyped-call]
            image = plotter.screenshot(None, transparent_background=transparent, return_img=True)
            assert image is not None  # return_img=True
        finally:
            plotter.close()
            plotter.deep_clean()
            del plotter
            gc.collect()  # free the off-screen context's VTK objects now, not in a later collection
    except (RuntimeError, AttributeError, ValueError) as exc:
        raise RuntimeError(f"no off-screen renderer: {exc}") from exc
    finally:
        vtkObject.SetGlobalWarningDisplay(warnings)
    return png_bytes(image)


PICTURE_MARK = ("Software", "sorgui")
"""The PNG text chunk of every picture sorgui writes: a Markdown report's ``NAME.png`` replaces
an earlier picture of sorgui's without a word, but not another file of that name."""


def is_sorgui_picture(path: Path) -> bool:
    """Whether the file at ``path`` is a PNG that sorgui wrote (:data:`PICTURE_MARK`, among the
    chunks before the image data)."""
    try:
        with path.open("rb") as file:
            head = file.read(MARK_WITHIN)
    except OSError:
        return False
    key, value = PICTURE_MARK
    return head.startswith(b"\x89PNG") and f"{key}\0{value}".encode() in head.split(b"IDAT", 1)[0]


MARK_WITHIN = 4096
"""Bytes from the start of a PNG within which :data:`PICTURE_MARK` is looked for (VTK writes the
text chunks right after the header)."""


def png_bytes(image: np.ndarray) -> bytes:
    """An ``(h, w, 3|4)`` ``uint8`` image as PNG bytes (VTK's PNG writer, in memory), marked as
    sorgui's (:data:`PICTURE_MARK`)."""
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkIOImage import vtkPNGWriter

    from sorgui.render.vtk_arrays import numpy_to_vtk

    height, width, channels = image.shape
    data = vtkImageData()
    data.SetDimensions(width, height, 1)
    flipped = np.ascontiguousarray(image[::-1].reshape(-1, channels))  # VTK's rows run bottom-up
    array = numpy_to_vtk(flipped, deep=True)
    data.GetPointData().SetScalars(array)
    writer = vtkPNGWriter()
    writer.AddText(*PICTURE_MARK)
    writer.SetInputData(data)
    writer.WriteToMemoryOn()
    writer.Write()
    result = writer.GetResult()
    return bytes(memoryview(result))
