"""What the 3D view draws for one analysis, as plain data: :class:`SceneData`.

Built in the worker process (:mod:`sorgui.session.scene_data`) and pickled to the window, which
only wraps its arrays in VTK objects. Its own module, light beside the builders: the window
unpickles a scene with it and the render layer's data classes (loaded by then with the render
window), not the builders' engine and sympy.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from sorgui.export.text import float_text
from sorgui.render.canal_scene import FamilyCurves, SmatFamily
from sorgui.render.geometry import ClipBox, ClipSphere
from sorgui.render.mesh import MeshData
from sorgui.render.scene import LineData, MarkerData, PatchData

if TYPE_CHECKING:
    from sorgui.engine.values import Terms


@dataclass(frozen=True, eq=False)
class SceneData:
    """Everything the viewport draws for one analysis, as plain data.

    ``terms``: float terms of the square-free part of ``f`` (for picking: its zero set and
    normals); ``typed_terms``: those of ``f`` as typed when it is not that part (a multiple, a
    power, decimals), whose value and gradient the pick reports; ``region``: the drawn
    ball; ``axis_point``/``axis_direction``: the unique axis as floats, if there is one;
    ``notes``: what the picture leaves out, in words for the user. ``factor_axes``: the axes
    of the factors of a reducible surface (one polyline each); ``approximate_axis``: the
    floating-point axis of rounded input, and ``approximate_axis_point`` its point as the report
    gives it (the probe's heights count from it, as from the exact axis's point); ``deviation``:
    per surface point, the distance to the nearest exact surface (``|g|/|∇g|``, length units),
    when there is one.
    ``canal_spine``/``canal_circles``: the spines and a few characteristic circles of a canal
    surface's sphere families (docs/math.md §9; a spine of positive genus traced numerically);
    ``canal_families``: those families as float curves or SMAT equations, to find the sphere
    touching the surface at a picked point. ``base_curve``: the base curve of a cone or a
    cylinder over a curve, drawn where it lies on the surface (docs/math.md §10). ``box``: the
    user's box, if one was given: the mesh and CAD faces are cut to it, and ``region`` is the
    ball about it.
    """

    terms: Terms
    region: ClipSphere
    surface: MeshData
    axis_segment: LineData
    profile_curve: LineData
    center_marker: MarkerData | None
    patch: PatchData | None
    axis_point: tuple[float, float, float] | None
    axis_direction: tuple[float, float, float] | None
    notes: tuple[str, ...]
    factor_axes: LineData = LineData.empty()
    approximate_axis: LineData = LineData.empty()
    deviation: np.ndarray | None = None
    canal_spine: LineData = LineData.empty()
    canal_circles: LineData = LineData.empty()
    canal_families: tuple[FamilyCurves | SmatFamily, ...] = ()
    box: ClipBox | None = None
    base_curve: LineData = LineData.empty()
    typed_terms: Terms | None = None
    approximate_axis_point: tuple[float, float, float] | None = None

    @property
    def axis(self) -> tuple[np.ndarray, np.ndarray] | None:
        """``(point, direction)`` of the unique axis, for the picking test."""
        if self.axis_point is None or self.axis_direction is None:
            return None
        return np.asarray(self.axis_point), np.asarray(self.axis_direction)

    def summary(self) -> str:
        """Short facts for the status bar: triangles and the drawn ball (its centre without
        rounding noise: ``(0, 0, 0)``, not ``(1.11e-16, 1.67e-16, 5.55e-17)``) or box."""
        if self.box is not None:
            low, high = self.box.bounds[0::2], self.box.bounds[1::2]
            digits = digits_at_scale([*low, *high], max(h - lo for lo, h in zip(low, high)))
            return (
                f"{self.surface.n_faces:,} triangles in the box {float_text(low, digits)} to {float_text(high, digits)}"
            )
        center = float_text(self.region.center, digits_at_scale(self.region.center, self.region.radius))
        return f"{self.surface.n_faces:,} triangles in a ball of radius {self.region.radius:.3g} about {center}"


def digits_at_scale(values: Sequence[float], size: float) -> int:
    """Significant digits that show ``values`` (a place) to 3 digits of ``size`` (a region's):
    a box from 1289 to 1291 was "(1.29e+03, …) to (1.29e+03, …)" with 3 digits."""
    largest = max((abs(v) for v in values), default=0.0)
    if size <= 0 or largest <= size or not math.isfinite(largest / size):
        return 3
    return min(3 + math.ceil(math.log10(largest / size)), 12)
