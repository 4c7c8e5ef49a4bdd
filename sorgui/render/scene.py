"""Plain-data builders for the actors around the surface: axis, profile, circles, normals.

Each builder returns a frozen dataclass of ``numpy`` arrays that a worker may compute and hand
to the GUI thread, which calls ``to_polydata()`` (or :func:`to_polydata`) to get the
``pyvista`` object. Names follow docs/math.md: the axis is the line ``c + t·a``; the profile
``p̃(s, r)`` lives in the plane of the points ``c + s·a + r·u`` with ``u ⟂ a``; neither ``a``
nor ``u`` needs to be a unit vector (the engine keeps them ``K``-rational).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPolyData
from vtkmodules.vtkFiltersCore import vtkFlyingEdges2D, vtkStripper

from sorgui.render.geometry import (
    Region,
    Vector,
    as_region,
    as_vector,
    enclosing_sphere,
    foot_on_line,
    inside_region,
    line_in_region,
    polyline_cells,
    readonly,
    split_cells,
    unit,
)
from sorgui.render.mesh import (
    GRID_OFFSET,
    NEWTON_STEP_LIMIT,
    clip_to_region,
    set_points,
)
from sorgui.render.sampling import Terms, newton_step, sample_grid_2d
from sorgui.render.vtk_arrays import numpy_to_vtk, vtk_to_numpy

if TYPE_CHECKING:
    import pyvista


# --- plain data -----------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class LineData:
    """One or more polylines: ``points (n, 3) float64`` and ``lines``, VTK's flat cell array
    ``[k, i0, …, i(k-1), …]`` (``int64``). A closed polyline repeats its first point id."""

    points: np.ndarray
    lines: np.ndarray

    @classmethod
    def empty(cls) -> LineData:
        return cls(readonly(np.zeros((0, 3))), readonly(np.zeros(0, dtype=np.int64)))

    @classmethod
    def from_polylines(cls, polylines: Sequence[np.ndarray], closed: bool = False) -> LineData:
        """Polylines given as ``(k, 3)`` point arrays; ``closed`` joins each end to its start."""
        polylines = [np.asarray(p, dtype=np.float64).reshape(-1, 3) for p in polylines]
        polylines = [p for p in polylines if len(p) >= 2]
        if not polylines:
            return cls.empty()
        cells = polyline_cells([len(p) for p in polylines], [closed] * len(polylines))
        return cls(readonly(np.concatenate(polylines)), readonly(cells))

    @property
    def is_empty(self) -> bool:
        return len(self.lines) == 0

    def polylines(self) -> list[np.ndarray]:
        """Each polyline as an ``(k, 3)`` array of its points, in order."""
        return [self.points[ids] for ids in split_cells(self.lines)]

    def to_polydata(self) -> pyvista.PolyData:
        import pyvista

        if self.is_empty:
            return pyvista.PolyData()
        return pyvista.PolyData(np.array(self.points), lines=np.array(self.lines))


@dataclass(frozen=True)
class MarkerData:
    """A small ball at ``center``: the centre of a sphere, through which every line is an axis."""

    center: tuple[float, float, float]
    radius: float

    def to_polydata(self) -> pyvista.PolyData:
        import pyvista

        return pyvista.Sphere(radius=self.radius, center=self.center, theta_resolution=24, phi_resolution=16)


@dataclass(frozen=True, eq=False)
class PatchData:
    """A parametric patch on an ``(ns, nt)`` grid: ``points (ns, nt, 3)`` (``nan`` where
    invalid) and ``mask (ns, nt)``, true where the point is finite and inside the region."""

    points: np.ndarray
    mask: np.ndarray

    @property
    def is_empty(self) -> bool:
        return not bool(self.quad_mask().any())

    def quad_mask(self) -> np.ndarray:
        """``(ns-1, nt-1)``: the grid cells whose four corners are all valid."""
        m = self.mask
        quads: np.ndarray = m[:-1, :-1] & m[1:, :-1] & m[1:, 1:] & m[:-1, 1:]
        return quads

    def to_polydata(self) -> pyvista.PolyData:
        """The valid quads only, with the unused points dropped (they would skew the bounds)."""
        import pyvista

        quads = self.quad_mask()
        if not quads.any():
            return pyvista.PolyData()
        ns, nt = self.mask.shape
        ids = np.arange(ns * nt).reshape(ns, nt)
        i, j = np.nonzero(quads)
        corners = np.column_stack([ids[i, j], ids[i + 1, j], ids[i + 1, j + 1], ids[i, j + 1]])
        used, inverse = np.unique(corners, return_inverse=True)
        faces = np.column_stack([np.full(len(i), 4), inverse.reshape(-1, 4)]).ravel()
        return pyvista.PolyData(self.points.reshape(-1, 3)[used], faces=faces)


def to_polydata(data: LineData | MarkerData | PatchData) -> pyvista.PolyData:
    """The ``pyvista`` object of any scene item (GUI thread only)."""
    return data.to_polydata()


# --- the axis and lines through a point -----------------------------------------------------


def axis_line(point: Vector, direction: Vector, bounds: Region | Sequence[float]) -> LineData:
    """The axis ``point + t·direction`` clipped to the box or ball ``bounds`` (empty if missed)."""
    segment = line_in_region(point, direction, bounds)
    if segment is None:
        return LineData.empty()
    return LineData.from_polylines([np.array(segment)])


def normal_line(point: Vector, gradient: Vector, length: float) -> LineData:
    """The segment of the surface normal at ``point``, of total ``length``, centred there.

    Empty when the gradient vanishes (a singular point has no normal line).
    """
    p, n = as_vector(point, "point"), unit(as_vector(gradient, "gradient"))
    if not np.any(n) or not (np.isfinite(length) and length > 0):
        return LineData.empty()
    half = 0.5 * float(length) * n
    return LineData.from_polylines([np.array([p - half, p + half])])


def latitude_circle(point_on_surface: Vector, axis_point: Vector, axis_direction: Vector, n: int = 128) -> LineData:
    """The circle through ``point_on_surface`` about the axis: a closed polyline of ``n`` points.

    On a surface of revolution it lies on the surface. Empty for a point on the axis.
    """
    p = as_vector(point_on_surface, "point")
    a = unit(as_vector(axis_direction, "axis direction"))
    foot = foot_on_line(p, axis_point, a)
    radial = p - foot
    if float(np.linalg.norm(radial)) <= 1e-14 * max(1.0, float(np.linalg.norm(p))):
        return LineData.empty()
    tangent = np.cross(a, radial)  # same length as `radial`, since a is a unit vector ⟂ radial
    theta = 2.0 * np.pi * np.arange(n) / n
    circle = foot + np.cos(theta)[:, None] * radial + np.sin(theta)[:, None] * tangent
    return LineData.from_polylines([circle], closed=True)


def sphere_center_marker(center: Vector, bounds: Region | Sequence[float], relative_size: float = 0.015) -> MarkerData:
    """A marker ball at a sphere's centre, its radius a fraction of the region's size."""
    x, y, z = (float(v) for v in as_vector(center, "center"))
    _, radius = enclosing_sphere(bounds)
    return MarkerData((x, y, z), relative_size * radius)


# --- the profile curve ----------------------------------------------------------------------


def _contour_2d(values: np.ndarray, origin: Vector, spacing: Vector) -> vtkPolyData:
    """Zero level of ``values (nr, ns)`` (s fastest) as joined polylines in ``(s, r, 0)``.

    Contoured in index space and mapped in ``float64`` (see ``mesh.contour_zero``).
    """
    image = vtkImageData()
    image.SetDimensions(values.shape[1], values.shape[0], 1)
    scalars = numpy_to_vtk(values.reshape(-1), deep=False)
    image.GetPointData().SetScalars(scalars)
    flying = vtkFlyingEdges2D()
    flying.SetInputData(image)
    flying.SetValue(0, 0.0)
    flying.ComputeScalarsOff()
    flying.Update()
    out = _strip(flying.GetOutput())
    if out.GetPoints() is not None:
        index = vtk_to_numpy(out.GetPoints().GetData()).astype(np.float64)
        sr = np.zeros_like(index)
        sr[:, :2] = np.asarray(origin) + np.asarray(spacing) * index[:, :2]
        set_points(out, sr)
    return out


def _strip(poly: vtkPolyData) -> vtkPolyData:
    """Join line segments into maximal polylines."""
    stripper = vtkStripper()
    stripper.SetInputData(poly)
    stripper.JoinContiguousSegmentsOn()
    stripper.Update()
    out = vtkPolyData()
    out.ShallowCopy(stripper.GetOutput())
    return out


def _lines_of(poly: vtkPolyData) -> tuple[np.ndarray, np.ndarray]:
    """``(points (n, 3) float64, flat cell array)`` of the lines of ``poly``."""
    if poly.GetNumberOfLines() == 0 or poly.GetPoints() is None:
        return np.zeros((0, 3)), np.zeros(0, dtype=np.int64)
    points = vtk_to_numpy(poly.GetPoints().GetData()).astype(np.float64)
    offsets = vtk_to_numpy(poly.GetLines().GetOffsetsArray()).astype(np.int64)
    connectivity = vtk_to_numpy(poly.GetLines().GetConnectivityArray()).astype(np.int64)
    sizes = np.diff(offsets)
    starts = np.cumsum(np.concatenate([[0], sizes[:-1] + 1]))
    cells = np.empty(len(connectivity) + len(sizes), dtype=np.int64)
    cells[starts] = sizes
    mask = np.ones(len(cells), dtype=bool)
    mask[starts] = False
    cells[mask] = connectivity
    return points, cells


def profile_curve(
    profile_terms_sr: Terms,
    point: Vector,
    direction: Vector,
    u: Vector,
    bounds: Region | Sequence[float],
    resolution: int = 400,
) -> LineData:
    """The profile ``p̃(s, r) = 0`` drawn in the plane ``c + s·a + r·u`` through the axis.

    ``p̃`` is sampled on an offset ``(s, r)`` grid covering the plane's part of ``bounds``
    (``resolution`` nodes per side, spacing equal in 3D length), its zero level is traced with
    ``vtkFlyingEdges2D``, each vertex takes one bounded Newton step onto ``p̃ = 0``, and the
    polylines are mapped to 3D and clipped to ``bounds``. Both halves ``r > 0`` and ``r < 0``
    are drawn (``p̃`` is even in ``r``).
    """
    c, a, w = as_vector(point, "point"), as_vector(direction, "direction"), as_vector(u, "u")
    la, lw = float(np.linalg.norm(a)), float(np.linalg.norm(w))
    if la == 0.0 or lw == 0.0:
        raise ValueError("direction and u must be nonzero")
    if abs(float(a @ w)) > 1e-9 * la * lw:
        raise ValueError("u must be orthogonal to the axis direction")
    if resolution < 2:
        raise ValueError("resolution must be at least 2")
    region = as_region(bounds)
    centre, radius = enclosing_sphere(region)
    d = centre - c
    mid = np.array([d @ a / la**2, d @ w / lw**2])  # (s, r) of the region's centre
    half = np.array([radius / la, radius / lw])
    spacing = 2.0 * half / (resolution - 1)
    origin = mid - half + np.asarray(GRID_OFFSET[:2]) * spacing
    ss = origin[0] + spacing[0] * np.arange(resolution - 1)
    rs = origin[1] + spacing[1] * np.arange(resolution - 1)
    values = sample_grid_2d(profile_terms_sr, ss, rs, normalise=True)
    if not (values.min() < 0.0 < values.max()):
        return LineData.empty()
    poly = _contour_2d(values, origin, spacing)
    if poly.GetNumberOfLines() == 0:
        return LineData.empty()
    sr = vtk_to_numpy(poly.GetPoints().GetData())[:, :2]
    sr = newton_step(profile_terms_sr, sr, NEWTON_STEP_LIMIT * spacing)
    xyz = c + sr[:, :1] * a + sr[:, 1:] * w
    set_points(poly, xyz)
    if not np.all(inside_region(xyz, region)):
        poly = _strip(clip_to_region(poly, region))
    points, cells = _lines_of(poly)
    if len(cells) == 0:
        return LineData.empty()
    return LineData(readonly(points), readonly(cells))


# --- parametric overlays --------------------------------------------------------------------

PATCH_RANGE = (-3.0, 3.0)
"""Range of both parameters of the drawn parametric patch (the rotation parameter ``s`` is the
tangent of half the angle, so ``±3`` covers about 287° and leaves the seam open); a CAD patch
export covers the same box."""

PATCH_RANGES = (PATCH_RANGE, (-30.0, 30.0), (-300.0, 300.0))
"""The boxes tried in turn when no map's patch over :data:`PATCH_RANGE` meets the drawn ball (a
small hyperboloid whose map reaches its neck at ``t ≈ 9``); the window and a CAD patch export
take the first box and map that meet it."""

PatchCoordinate = Callable[[Any, Any], Any] | float
"""A coordinate of a patch: ``fn(s, t)``, called on the grid's arrays (or, where that fails, on
each pair of numbers), or a constant."""


def _evaluate(fn: PatchCoordinate, s: np.ndarray, t: np.ndarray) -> np.ndarray:
    """``fn(s, t)`` on the grid; falls back to point-by-point calls, a failing point gives nan."""
    if not callable(fn):
        return np.full(s.shape, float(fn))
    with np.errstate(all="ignore"):
        try:
            out = np.asarray(fn(s, t), dtype=np.float64)
            return np.array(np.broadcast_to(out, s.shape))
        except (TypeError, ValueError, ZeroDivisionError, OverflowError, ArithmeticError):
            pass

        def one(si: float, ti: float) -> float:
            try:
                return float(fn(si, ti))
            except (TypeError, ValueError, ZeroDivisionError, OverflowError, ArithmeticError):
                return np.nan

        pointwise: np.ndarray = np.vectorize(one, otypes=[np.float64])(s, t)
        return pointwise


def parametric_patch(
    fx: PatchCoordinate,
    fy: PatchCoordinate,
    fz: PatchCoordinate,
    s_range: tuple[float, float],
    t_range: tuple[float, float],
    n: int | tuple[int, int] = 64,
    region: Region | Sequence[float] | None = None,
) -> PatchData:
    """Sample ``(fx, fy, fz)(s, t)`` on an ``n × n`` (or ``ns × nt``) grid for an overlay.

    Robust to poles: points that are not finite (a parameterization's pole or a failing call)
    or lie outside ``region`` are masked, and the quads touching them are not drawn.
    """
    ns, nt = (n, n) if isinstance(n, int) else n
    if ns < 2 or nt < 2:
        raise ValueError("the patch needs at least 2 × 2 samples")
    s, t = np.meshgrid(np.linspace(*s_range, ns), np.linspace(*t_range, nt), indexing="ij")
    points = np.stack([_evaluate(f, s, t) for f in (fx, fy, fz)], axis=-1)
    mask = np.all(np.isfinite(points), axis=-1)
    if region is not None:
        mask &= inside_region(np.where(mask[..., None], points, 0.0), region).reshape(ns, nt)
    points[~mask] = np.nan
    return PatchData(readonly(points), readonly(mask))
