"""The triangle mesh of an implicit surface ``f = 0``, built from plain data off the GUI thread.

``surface_mesh(terms, bounds)`` samples ``f`` on a regular grid (``sampling.sample_grid``),
contours the zero level with VTK's multithreaded ``vtkFlyingEdges3D``, optionally clips to a
ball or box, moves every vertex one bounded Newton step onto ``f = 0`` and orients everything
by the analytic gradient. The result, :class:`MeshData`, is plain ``numpy``: a worker returns
it, and the GUI thread turns it into a ``pyvista.PolyData`` with :func:`mesh_to_polydata`.

Design choices, each for a reason:

* The grid is **offset** from the box corner by irrational fractions of the spacing, so
  singular points with simple coordinates (a cone's vertex at the origin) never fall on grid
  nodes, where the sign test of marching cubes is undefined.
* Sampled values are **normalised** (``max |f| = 1`` on the grid, after exact power-of-two
  scaling), so huge or tiny coefficients and boxes neither overflow nor underflow. Non-finite
  coefficients or bounds are refused with ``ValueError``; so no ``nan`` reaches VTK.
* **Sides.** Normals are the unit gradient ``∇f/|∇f|``, pointing into ``{f > 0}``, and every
  triangle is wound counter-clockwise as seen from ``{f > 0}``. So VTK's *front* faces look at
  the side ``f > 0`` and its *back* faces at ``f < 0``: the GUI colours the two sides of the
  surface differently with a back-face property. The per-point scalar ``side`` is
  ``sign(n_mesh · ∇f)``, with ``n_mesh`` the area-weighted normal of the incident triangles:
  ``+1`` almost everywhere, ``0`` where ``∇f`` vanishes (singular points, where the normal is
  taken from the mesh) and ``-1`` where the sampled sheet folds against the gradient (too
  coarse a grid). Colouring by it shows where the picture cannot be trusted.
* Contouring finds sign changes only: components of even multiplicity (``(x²+y²+z²-1)²``),
  isolated real points and real curves of a surface have none and are not drawn. The engine's
  square-free factorization is the place to fix that.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import TYPE_CHECKING

import numpy as np
from vtkmodules.vtkCommonCore import vtkPoints, vtkSMPTools
from vtkmodules.vtkCommonDataModel import vtkBox, vtkImageData, vtkPolyData, vtkSphere
from vtkmodules.vtkFiltersCore import (
    vtkClipPolyData,
    vtkFlyingEdges3D,
    vtkTriangleFilter,
)

from sorgui.render.geometry import (
    ClipBox,
    ClipSphere,
    Region,
    as_bounds,
    as_region,
    readonly,
)
from sorgui.render.sampling import Terms, newton_step, sample_grid, value_and_gradient
from sorgui.render.vtk_arrays import numpy_to_vtk, vtk_to_numpy

if TYPE_CHECKING:
    import pyvista

GRID_OFFSET = (0.41421356237309515, 0.7320508075688772, 0.2360679774997898)
"""Grid offsets as fractions of the spacing: the fractional parts of √2, √3 and √5."""

THIN_SIDE = 4
"""A side of the box shorter than this many spacings is sampled in this many steps of its own."""

MAX_GRID_NODES = 1 << 27
"""At most this many grid nodes (1 GiB of ``float64`` samples): a clear error, not an OOM kill."""

NEWTON_STEP_LIMIT = 0.25
"""The Newton step moves each vertex coordinate by at most this fraction of the grid spacing."""


@dataclass(frozen=True, eq=False)
class MeshData:
    """A triangle mesh as plain arrays (read-only), safe to pass between threads.

    ``points (n, 3) float64``; ``faces``: VTK's flat cell array ``[3, i, j, k, 3, …]``
    (``int64``); ``normals (n, 3) float32``: unit ``∇f`` (into ``f > 0``); ``side (n,)
    float32``: ``sign(n_mesh · ∇f)`` (module docstring); ``spacing``: the grid spacing used,
    a natural tolerance; ``bounds``: the box spanned by the grid nodes.
    """

    points: np.ndarray
    faces: np.ndarray
    normals: np.ndarray
    side: np.ndarray
    spacing: float
    bounds: tuple[float, ...]

    @classmethod
    def empty(cls, spacing: float = 0.0, bounds: tuple[float, ...] = ()) -> MeshData:
        """A mesh without points: the surface has no real points in the region."""
        return cls(
            readonly(np.zeros((0, 3))),
            readonly(np.zeros(0, dtype=np.int64)),
            readonly(np.zeros((0, 3), dtype=np.float32)),
            readonly(np.zeros(0, dtype=np.float32)),
            spacing,
            bounds,
        )

    @property
    def n_points(self) -> int:
        return len(self.points)

    @property
    def n_faces(self) -> int:
        return len(self.faces) // 4

    @property
    def is_empty(self) -> bool:
        return self.n_faces == 0

    @property
    def triangles(self) -> np.ndarray:
        """The faces as an ``(m, 3)`` array of point ids."""
        return self.faces.reshape(-1, 4)[:, 1:]

    def to_polydata(self) -> pyvista.PolyData:
        """A ``pyvista.PolyData`` with point arrays ``Normals`` (active) and ``side``.

        For the GUI thread: building VTK objects for the render window belongs there.
        """
        import pyvista

        if self.is_empty:
            return pyvista.PolyData()
        poly = pyvista.PolyData(np.array(self.points), faces=np.array(self.faces))
        poly.point_data["Normals"] = np.array(self.normals)
        poly.point_data.active_normals_name = "Normals"
        poly.point_data["side"] = np.array(self.side)
        return poly


# --- the sampling grid ----------------------------------------------------------------------


@dataclass(frozen=True)
class SamplingGrid:
    """A regular grid: ``dims`` nodes per axis from ``origin``, ``spacing`` apart, or ``steps``
    apart along each axis when given (a thin side of a box, :func:`sampling_grid`)."""

    origin: tuple[float, float, float]
    spacing: float
    dims: tuple[int, int, int]
    steps: tuple[float, float, float] | None = None

    @property
    def step(self) -> tuple[float, float, float]:
        """The nodes' distance along ``x``, ``y`` and ``z``."""
        return self.steps if self.steps is not None else (self.spacing, self.spacing, self.spacing)

    def axes(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The node coordinates along ``x``, ``y`` and ``z``."""
        (ox, oy, oz), (nx, ny, nz), (sx, sy, sz) = self.origin, self.dims, self.step
        return ox + sx * np.arange(nx), oy + sy * np.arange(ny), oz + sz * np.arange(nz)


def sampling_grid(bounds: tuple[float, ...], resolution: int = 150) -> SamplingGrid:
    """The offset grid inside ``bounds`` with ``resolution`` nodes along the longest side.

    The spacing is the same on every axis (equilateral-ish triangles): ``longest side /
    resolution``, but a side thinner than :data:`THIN_SIDE` spacings gets that many steps of its
    own (a slab 0.01 thick of a torus 8 across had its two nodes across 0.07 apart, and no
    triangle in it). Node ``0`` sits at ``min + GRID_OFFSET·step``, the last node inside the box.
    """
    b = np.asarray(as_bounds(bounds)).reshape(3, 2)
    if resolution < 2:
        raise ValueError("resolution must be at least 2")
    extent = b[:, 1] - b[:, 0]
    spacing = float(extent.max()) / resolution
    steps = np.minimum(spacing, extent / THIN_SIDE)
    offset = np.asarray(GRID_OFFSET) * steps
    dims = np.maximum(np.floor((extent - offset) / steps).astype(int) + 1, 2)
    if int(np.prod(dims, dtype=np.int64)) > MAX_GRID_NODES:
        raise ValueError(f"a {dims[0]}×{dims[1]}×{dims[2]} grid exceeds {MAX_GRID_NODES} nodes")
    nx, ny, nz = (int(n) for n in dims)
    own = None if np.all(steps == spacing) else (float(steps[0]), float(steps[1]), float(steps[2]))
    return SamplingGrid(tuple(b[:, 0] + offset), spacing, (nx, ny, nz), own)


def sample_surface(terms: Terms, grid: SamplingGrid) -> np.ndarray:
    """Normalised samples of ``f`` on ``grid``, shape ``(nz, ny, nx)`` (finite, ``|f| ≤ 1``)."""
    return sample_grid(terms, *grid.axes(), normalise=True)


# --- VTK stages -----------------------------------------------------------------------------


@lru_cache(maxsize=1)
def enable_vtk_threads() -> str:
    """Switch VTK's SMP backend to ``STDThread`` (flying edges then uses every core)."""
    tools = vtkSMPTools()
    tools.SetBackend("STDThread")
    return str(tools.GetBackend())


def contour_zero(values: np.ndarray, grid: SamplingGrid) -> vtkPolyData:
    """The zero level of ``values`` (``(nz, ny, nx)``, x fastest) as triangles (flying edges).

    VTK contours in index space (origin 0, spacing 1) and writes ``float32`` points; the
    points are mapped to world coordinates here in ``float64``, so boxes of any size and
    position keep full precision and never overflow ``float32``.
    """
    enable_vtk_threads()
    image = vtkImageData()
    image.SetDimensions(*grid.dims)
    scalars = numpy_to_vtk(values.reshape(-1), deep=False)  # a view: keep `values` alive
    scalars.SetName("f")
    image.GetPointData().SetScalars(scalars)
    flying = vtkFlyingEdges3D()
    flying.SetInputData(image)
    flying.SetValue(0, 0.0)
    flying.ComputeNormalsOff()
    flying.ComputeGradientsOff()
    flying.ComputeScalarsOff()
    flying.InterpolateAttributesOff()
    flying.Update()
    out = vtkPolyData()
    out.ShallowCopy(flying.GetOutput())
    if out.GetPoints() is not None:
        index = vtk_to_numpy(out.GetPoints().GetData())
        world = np.asarray(grid.origin) + np.asarray(grid.step) * index.astype(np.float64)
        set_points(out, world)
    return out


def set_points(poly: vtkPolyData, points: np.ndarray) -> None:
    """Replace the point coordinates of ``poly`` by ``points (n, 3)`` (copied, ``float64``)."""
    vtk_points = vtkPoints()
    vtk_points.SetData(numpy_to_vtk(np.ascontiguousarray(points, dtype=np.float64), deep=True))
    poly.SetPoints(vtk_points)


def implicit_region(region: Region) -> vtkSphere | vtkBox:
    """The VTK implicit function of ``region`` (negative inside)."""
    if isinstance(region, ClipSphere):
        sphere = vtkSphere()
        sphere.SetCenter(*region.center)
        sphere.SetRadius(region.radius)
        return sphere
    box = vtkBox()
    box.SetBounds(*region.bounds)
    return box


def clip_to_region(poly: vtkPolyData, region: Region) -> vtkPolyData:
    """Keep the part of ``poly`` inside ``region``, cutting cells along its boundary."""
    clipper = vtkClipPolyData()
    clipper.SetInputData(poly)
    clipper.SetClipFunction(implicit_region(region))
    clipper.InsideOutOn()
    clipper.SetValue(0.0)
    clipper.Update()
    out = vtkPolyData()
    out.ShallowCopy(clipper.GetOutput())
    return out


def triangle_arrays(poly: vtkPolyData) -> tuple[np.ndarray, np.ndarray]:
    """``(points (n, 3) float64, triangles (m, 3) int64)`` of the polygons of ``poly``."""
    if poly.GetNumberOfPolys() == 0 or poly.GetPoints() is None:
        return np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64)
    offsets = vtk_to_numpy(poly.GetPolys().GetOffsetsArray())
    if np.any(np.diff(offsets) != 3):
        triangulate = vtkTriangleFilter()
        triangulate.SetInputData(poly)
        triangulate.PassLinesOff()
        triangulate.PassVertsOff()
        triangulate.Update()
        poly = triangulate.GetOutput()
    points = vtk_to_numpy(poly.GetPoints().GetData()).astype(np.float64)
    connectivity = vtk_to_numpy(poly.GetPolys().GetConnectivityArray())
    return points, connectivity.astype(np.int64).reshape(-1, 3)


# --- numpy stages ---------------------------------------------------------------------------


def orient_by_gradient(
    points: np.ndarray, triangles: np.ndarray, grads: np.ndarray, length_scale: float = 1.0
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Wind triangles to face ``f > 0``; return ``(triangles, normals, side)``.

    A triangle is flipped when its geometric normal disagrees with the sum of the unit
    gradients at its corners. Normals are the unit gradient, or the mesh normal where the
    gradient vanishes. Edges are divided by ``length_scale`` (the grid spacing) so that
    their cross products cannot overflow.
    """
    norms = np.linalg.norm(grads, axis=1)
    regular = np.isfinite(norms) & (norms > 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        gunit = np.where(regular[:, None], grads / norms[:, None], 0.0)
    corners = points[triangles] * (1.0 / length_scale)
    face_normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    corner_gradients = gunit[triangles[:, 0]] + gunit[triangles[:, 1]] + gunit[triangles[:, 2]]
    flip = np.einsum("ij,ij->i", face_normals, corner_gradients) < 0.0
    triangles = triangles.copy()
    triangles[flip] = triangles[flip][:, ::-1]
    face_normals[flip] *= -1.0
    ids = triangles.ravel()
    mesh_normals = np.column_stack([np.bincount(ids, np.repeat(face_normals[:, c], 3), len(points)) for c in range(3)])
    mesh_norms = np.linalg.norm(mesh_normals, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        mesh_unit = np.where(mesh_norms[:, None] > 0.0, mesh_normals / mesh_norms[:, None], 0.0)
    normals = np.where(regular[:, None], gunit, mesh_unit)
    side = np.sign(np.einsum("ij,ij->i", mesh_unit, gunit))
    return triangles, normals.astype(np.float32), side.astype(np.float32)


# --- the public entry points ----------------------------------------------------------------


def grid_bounds(grid: SamplingGrid) -> tuple[float, ...]:
    """The box spanned by the nodes of ``grid``, in pyvista's bounds order."""
    return tuple(v for o, n, s in zip(grid.origin, grid.dims, grid.step) for v in (o, o + (n - 1) * s))


def zero_level_triangles(
    values: np.ndarray, grid: SamplingGrid, clip: Region | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Contour and clip: ``(points (n, 3), triangles (m, 3))``, empty if ``f`` keeps its sign."""
    if not (values.min() < 0.0 < values.max()):
        return np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64)
    poly = contour_zero(values, grid)
    if clip is not None:
        poly = clip_to_region(poly, as_region(clip))
    return triangle_arrays(poly)


def finish_mesh(
    terms: Terms,
    points: np.ndarray,
    triangles: np.ndarray,
    grid: SamplingGrid,
    refine: bool = True,
) -> MeshData:
    """Refine and orient the contoured triangles and pack them as :class:`MeshData`."""
    if len(triangles) == 0:
        return MeshData.empty(grid.spacing, grid_bounds(grid))
    if refine:
        points = newton_step(terms, points, NEWTON_STEP_LIMIT * grid.spacing)
    grads = value_and_gradient(terms, points, normalise=True)[1]
    triangles, normals, side = orient_by_gradient(points, triangles, grads, grid.spacing)
    faces = np.column_stack([np.full(len(triangles), 3, dtype=np.int64), triangles]).ravel()
    return MeshData(
        readonly(points),
        readonly(faces),
        readonly(normals),
        readonly(side),
        grid.spacing,
        grid_bounds(grid),
    )


CLIP_MARGIN = 2
"""Grid spacings by which a clipped mesh's grid reaches beyond the clip's box (:func:`surface_mesh`)."""

DEFAULT_RESOLUTION = 150
"""Grid nodes along each side of the sampled box (150³ samples, docs/benchmarks.md's mesh table)."""


def surface_mesh(
    terms: Terms,
    bounds: tuple[float, ...],
    resolution: int = DEFAULT_RESOLUTION,
    clip: Region | None = None,
    refine: bool = True,
) -> MeshData:
    """The mesh of ``f = 0`` inside ``bounds`` (``(xmin, xmax, ymin, ymax, zmin, zmax)``).

    ``resolution`` nodes along the longest side of the box; ``clip`` a :class:`ClipSphere` or
    :class:`ClipBox` (or ``None``: the box ``bounds`` itself); ``refine`` moves vertices onto
    the surface by one bounded Newton step. An empty :class:`MeshData` when the surface has no
    real points there (``x²+y²+z²+1``) or ``f`` is constant. ``ValueError`` on invalid input.

    With a ball for ``clip``, the grid reaches :data:`CLIP_MARGIN` spacings beyond ``bounds``, so
    that the ball, not the last row of grid cells, makes the rim: the ball's box touches the ball,
    and a surface through such a point would end in a flat cut short of it. (A box's faces are
    not passed: the refinement would move the rim's vertices out of the box.)
    """
    if isinstance(clip, ClipSphere):
        margin = CLIP_MARGIN * float(np.ptp(np.asarray(as_bounds(bounds)).reshape(3, 2), axis=1).max()) / resolution
        bounds = tuple(v + (margin if i % 2 else -margin) for i, v in enumerate(as_bounds(bounds)))
    grid = sampling_grid(bounds, resolution)
    points, triangles = zero_level_triangles(sample_surface(terms, grid), grid, clip)
    return finish_mesh(terms, points, triangles, grid, refine)


def mesh_to_polydata(mesh: MeshData) -> pyvista.PolyData:
    """:meth:`MeshData.to_polydata` as a function (GUI thread only)."""
    return mesh.to_polydata()


__all__ = [
    "ClipBox",
    "ClipSphere",
    "MeshData",
    "SamplingGrid",
    "finish_mesh",
    "mesh_to_polydata",
    "sample_surface",
    "sampling_grid",
    "surface_mesh",
    "zero_level_triangles",
]
