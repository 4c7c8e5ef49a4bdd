"""File → Export, File → Open of a saved report, and Save Picture: the window's side of the exports.

The formats themselves live in :mod:`sorgui.export` (Qt-free); this module adds the file-dialog
filters, the picture of the viewport and a small dialog for its size and background.

The picture is rendered by the viewport's own render window at a chosen width (the render is
scaled up by a whole factor, then resampled to exactly that width), optionally with a
transparent background. It holds what the user sees in the 3D view — the actors that are
visible, nothing hidden — without the orientation marker in the corner, which is a widget of
the window and not part of the scene.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from PySide6.QtCore import QBuffer, QIODevice, Qt
from PySide6.QtGui import QImage
from PySide6.QtWidgets import (
    QCheckBox,
    QDialog,
    QDialogButtonBox,
    QFormLayout,
    QSpinBox,
    QWidget,
)

from sorgui.export.formats import FORMATS
from sorgui.render.plotting import forwarders

if TYPE_CHECKING:
    import pyvista

    from sorgui.gui.viewport import Viewport

EXPORT_FILTERS = {suffix: form.name for suffix, form in FORMATS.items()}
"""The file dialog's choices for File → Export (every format of :mod:`sorgui.export.formats`)."""

REPORT_FILTER = "sorgui reports and batch results (*.json *.jsonl)"
"""File → Open also opens a report saved as JSON, shown without analysing again."""

MAX_PICTURE_WIDTH = 8000
"""The widest picture Save Picture offers, in pixels."""


PATCH_FILTERS = {
    f".patch{suffix}": f"{form.name}, parametric patch" for suffix, form in FORMATS.items() if form.has_patch
}
"""The meshes and CAD files once more as the patch of the first real parameterization
(``NAME.patch.stl``, ``NAME.patch.step``)."""


def export_filters() -> str:
    """The filter string of the Export dialog, the meshes also as their parametric patch."""
    choices = {**EXPORT_FILTERS, **PATCH_FILTERS}
    return ";;".join(f"{name} (*{suffix})" for suffix, name in choices.items())


CAD_CHOICES = ((".step", "STEP"), (".iges", "IGES"), (".brep", "BRep"))
"""File → Export CAD File's entries: each opens the Export dialog on that format."""


def filter_of_suffix(suffix: str) -> str:
    """The Export dialog's filter of ``suffix`` (``".step"`` → ``"STEP AP242 (B-rep) (*.step)"``)."""
    choices = {**EXPORT_FILTERS, **PATCH_FILTERS}
    return f"{choices[suffix]} (*{suffix})"


def with_suffix_of(path: str, chosen: str) -> str:
    """``path`` with the suffix of the filter ``chosen``, unless it ends in that one already or in
    another of the export suffixes that the user typed on purpose (the typed suffix wins, as in
    every file dialog; a name without one gets the filter's)."""
    wanted = suffix_of_filter(chosen)
    name = Path(path).name.lower()
    if name.endswith(wanted) or any(name.endswith(s) for s in {**EXPORT_FILTERS, **PATCH_FILTERS}):
        return path
    return path + wanted


def without_export_suffix(name: str) -> str:
    """``name`` without its export suffix, if it has one (``part.patch.stl`` → ``part``)."""
    for suffix in sorted({**EXPORT_FILTERS, **PATCH_FILTERS}, key=len, reverse=True):
        if name.lower().endswith(suffix):
            return name[: -len(suffix)]
    return name


def suffix_of_filter(chosen: str) -> str:
    """The suffix of the filter ``chosen`` in the Export dialog (for a name typed without one)."""
    for suffix, name in {**PATCH_FILTERS, **EXPORT_FILTERS}.items():  # the longer names first
        if chosen.startswith(name):
            return suffix
    return ".json"


def is_report_path(path: str | Path) -> bool:
    """Whether File → Open should treat ``path`` as a saved report (or a batch's results file,
    :func:`is_results_path`) rather than an equation."""
    return Path(path).suffix.lower() in (".json", ".jsonl")


def is_results_path(path: str | Path) -> bool:
    """Whether ``path`` names the results file of ``sorgui analyze --each-line`` (JSON Lines),
    one report per input line: File → Open asks which line to show."""
    return Path(path).suffix.lower() == ".jsonl"


def viewport_image(
    viewport: Viewport, width: int | None = None, transparent: bool = False, inspection: bool = True
) -> QImage:
    """The 3D view as an image ``width`` pixels wide (default: the view's own size);
    ``inspection=False`` leaves out the picked point's normal, circle and touching spheres (a
    report's picture is of the surface and its axis).

    A transparent background is computed, not asked of OpenGL (the window's surface has no
    alpha channel): the view is rendered once on black and once on white, and each pixel's
    opacity is ``1 - (white - black)``, its colour the one on black divided by that opacity —
    exact for opaque surfaces and for their smoothed edges alike.
    """
    plotter = viewport.plotter
    own_width = max(1, int(plotter.window_size[0]))
    scale = max(1, math.ceil((width or own_width) / own_width))
    renderer = plotter.renderer
    background = (renderer.GetBackground(), renderer.GetBackground2(), renderer.GetGradientBackground())
    forwarders(plotter).hide_axes()
    hidden = [] if inspection else viewport.hide_inspection()
    try:
        if transparent:
            renderer.GradientBackgroundOff()
            on_black = _render(plotter, scale, (0.0, 0.0, 0.0)).astype(np.float64)
            on_white = _render(plotter, scale, (1.0, 1.0, 1.0)).astype(np.float64)
            alpha = np.clip(255.0 - (on_white - on_black).max(axis=-1), 0.0, 255.0)
            with np.errstate(divide="ignore", invalid="ignore"):
                color = np.where(alpha[..., None] > 0, on_black * 255.0 / alpha[..., None], 0.0)
            pixels = np.dstack([np.clip(color, 0, 255), alpha]).round().astype(np.uint8)
        else:
            pixels = _screenshot(plotter, scale)
    finally:
        renderer.SetBackground(*background[0])
        renderer.SetBackground2(*background[1])
        renderer.SetGradientBackground(background[2])
        forwarders(plotter).show_axes()
        for actor in hidden:
            actor.SetVisibility(True)
        viewport.request_render()
    pixels = np.ascontiguousarray(pixels)
    height, full_width, channels = pixels.shape
    form = QImage.Format.Format_RGBA8888 if channels == 4 else QImage.Format.Format_RGB888
    image = QImage(pixels.data, full_width, height, channels * full_width, form).copy()
    if width is not None and width != full_width:
        image = image.scaledToWidth(width, Qt.TransformationMode.SmoothTransformation)
    return image


def _render(plotter: pyvista.BasePlotter, scale: int, color: tuple[float, float, float]) -> np.ndarray:
    """One render of the view on a plain background ``color``, as ``(h, w, 3)`` pixels."""
    plotter.renderer.SetBackground(*color)
    return _screenshot(plotter, scale)


def _screenshot(plotter: pyvista.BasePlotter, scale: int) -> np.ndarray:
    """The view rendered ``scale`` times larger, as ``(h, w, 3)`` pixels. At scale 1 VTK reads
    the last frame without rendering again, and pyvistaqt's ``render()`` only asks for one
    later: the frame with this picture's background and actors is rendered here, at once."""
    window = plotter.render_window
    if scale == 1 and window is not None:
        window.Render()
    image = plotter.screenshot(None, return_img=True, scale=scale)
    assert image is not None  # return_img=True
    pixels: np.ndarray = image[..., :3]
    return pixels


def png_bytes(image: QImage) -> bytes:
    """``image`` encoded as PNG."""
    buffer = QBuffer()
    buffer.open(QIODevice.OpenModeFlag.WriteOnly)
    image.save(buffer, "PNG")  # type: ignore[call-overload]  # PySide6 takes str; its stub says bytes
    return bytes(buffer.data().data())


class PictureDialog(QDialog):
    """Asks for the picture's width in pixels and whether its background is transparent."""

    def __init__(self, view_width: int, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle("Save picture")
        self.width_box = QSpinBox(self)
        self.width_box.setObjectName("pictureWidth")
        self.width_box.setRange(64, MAX_PICTURE_WIDTH)
        self.width_box.setSuffix(" px")
        self.width_box.setValue(min(2 * view_width, MAX_PICTURE_WIDTH))
        self.width_box.setToolTip(f"The view is {view_width} px wide; 2× is {2 * view_width} px")
        self.transparent_box = QCheckBox("Transparent background", self)
        self.transparent_box.setObjectName("pictureTransparent")
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel, self)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        layout = QFormLayout(self)
        layout.addRow("Width", self.width_box)
        layout.addRow("", self.transparent_box)
        layout.addRow(buttons)
