"""Plain floating-point geometry shared by the render layer: regions, lines and VTK cell arrays.

A *region* is where things are drawn: a box ``(xmin, xmax, ymin, ymax, zmin, zmax)`` (pyvista's
bounds order) or a ball. Meshes, axes and curves are clipped to it. Everything here is display
geometry in ``float64``; exact answers (does the normal meet the axis?) come from the engine.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

Vector = np.ndarray | Sequence[float]
Bounds = tuple[float, float, float, float, float, float]
"""``(xmin, xmax, ymin, ymax, zmin, zmax)``, pyvista's order."""


@dataclass(frozen=True)
class ClipBox:
    """Keep what lies inside the axis-aligned box ``bounds``."""

    bounds: Bounds

    def __post_init__(self) -> None:
        object.__setattr__(self, "bounds", as_bounds(self.bounds))


@dataclass(frozen=True)
class ClipSphere:
    """Keep what lies inside the ball of radius ``radius`` about ``center``."""

    center: tuple[float, float, float]
    radius: float

    def __post_init__(self) -> None:
        center = as_vector(self.center, "center")
        if not (np.isfinite(self.radius) and self.radius > 0):
            raise ValueError(f"clip radius must be positive and finite, got {self.radius}")
        object.__setattr__(self, "center", tuple(float(v) for v in center))
        object.__setattr__(self, "radius", float(self.radius))


Region = ClipBox | ClipSphere


def readonly(a: np.ndarray) -> np.ndarray:
    """``a`` (made contiguous) with writing disabled: plain data handed between threads."""
    a = np.ascontiguousarray(a)
    a.flags.writeable = False
    return a


def as_vector(v: Vector, name: str = "vector") -> np.ndarray:
    """``v`` as a finite ``float64`` array of shape ``(3,)``; ``ValueError`` otherwise."""
    out = np.asarray(v, dtype=np.float64).reshape(-1)
    if out.shape != (3,) or not np.all(np.isfinite(out)):
        raise ValueError(f"{name} must be three finite numbers, got {v!r}")
    return out


def as_bounds(bounds: Vector) -> Bounds:
    """Validate ``(xmin, xmax, ymin, ymax, zmin, zmax)``: finite, ``min < max`` on each axis."""
    b = np.asarray(bounds, dtype=np.float64).reshape(-1)
    if b.shape != (6,) or not np.all(np.isfinite(b)) or np.any(b[1::2] <= b[0::2]):
        raise ValueError(f"bounds must be (xmin, xmax, ymin, ymax, zmin, zmax), got {bounds!r}")
    xmin, xmax, ymin, ymax, zmin, zmax = (float(v) for v in b)
    return (xmin, xmax, ymin, ymax, zmin, zmax)


def as_region(region: Region | Sequence[float]) -> Region:
    """A :class:`ClipBox` or :class:`ClipSphere`; plain bounds become a box."""
    if isinstance(region, (ClipBox, ClipSphere)):
        return region
    return ClipBox(as_bounds(region))


def region_bounds(region: Region | Sequence[float]) -> Bounds:
    """The axis-aligned bounding box of ``region``."""
    region = as_region(region)
    if isinstance(region, ClipBox):
        return region.bounds
    c, r = np.asarray(region.center), region.radius
    return as_bounds(np.column_stack([c - r, c + r]).ravel())


def enclosing_sphere(region: Region | Sequence[float]) -> tuple[np.ndarray, float]:
    """A ball ``(center, radius)`` that contains ``region`` (the circumscribed ball of a box)."""
    region = as_region(region)
    if isinstance(region, ClipSphere):
        return np.asarray(region.center), region.radius
    b = np.asarray(region.bounds).reshape(3, 2)
    return b.mean(axis=1), 0.5 * float(np.linalg.norm(b[:, 1] - b[:, 0]))


def inside_region(points: np.ndarray, region: Region | Sequence[float]) -> np.ndarray:
    """Boolean mask of the rows of ``points (n, 3)`` that lie in ``region`` (boundary included)."""
    region = as_region(region)
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    with np.errstate(invalid="ignore"):
        if isinstance(region, ClipSphere):
            d = pts - np.asarray(region.center)
            in_ball: np.ndarray = np.einsum("ij,ij->i", d, d) <= region.radius**2
            return in_ball
        b = np.asarray(region.bounds).reshape(3, 2)
        in_box: np.ndarray = np.all((pts >= b[:, 0]) & (pts <= b[:, 1]), axis=1)
        return in_box


def unit(v: Vector) -> np.ndarray:
    """``v / |v|``, or the zero vector when ``v`` is zero or not finite."""
    v = np.asarray(v, dtype=np.float64)
    norm = float(np.linalg.norm(v))
    if not (np.isfinite(norm) and norm > 0.0):
        return np.zeros_like(v)
    return v / norm


def perpendicular_vector(a: Vector) -> np.ndarray:
    """A nonzero vector orthogonal to ``a`` (not normalised): ``a × e`` for the axis ``e``
    least aligned with ``a``."""
    a = as_vector(a, "direction")
    if not np.any(a):
        raise ValueError("direction must be nonzero")
    e = np.zeros(3)
    e[int(np.argmin(np.abs(a)))] = 1.0
    return np.cross(a, e)


def line_in_region(
    point: Vector, direction: Vector, region: Region | Sequence[float]
) -> tuple[np.ndarray, np.ndarray] | None:
    """The segment ``(start, end)`` of the line ``point + t·direction`` inside ``region``.

    ``None`` when the line misses the region (or only touches it in one point).
    """
    p, d = as_vector(point, "point"), as_vector(direction, "direction")
    if not np.any(d):
        raise ValueError("direction must be nonzero")
    region = as_region(region)
    if isinstance(region, ClipSphere):
        # |p + t d - c|² = R²: a quadratic in t.
        q = p - np.asarray(region.center)
        a2, b1, c0 = d @ d, q @ d, q @ q - region.radius**2
        disc = b1 * b1 - a2 * c0
        if disc <= 0.0:
            return None
        root = np.sqrt(disc)
        t0, t1 = (-b1 - root) / a2, (-b1 + root) / a2
    else:
        # Slab method: intersect the parameter intervals of the three slabs.
        b = np.asarray(region.bounds).reshape(3, 2)
        t0, t1 = -np.inf, np.inf
        for v in range(3):
            if d[v] == 0.0:
                if not b[v, 0] <= p[v] <= b[v, 1]:
                    return None
                continue
            ta, tb = sorted(((b[v, 0] - p[v]) / d[v], (b[v, 1] - p[v]) / d[v]))
            t0, t1 = max(t0, ta), min(t1, tb)
        if not t0 < t1:
            return None
    return p + t0 * d, p + t1 * d


def line_skews(points: np.ndarray, directions: np.ndarray, line_point: Vector, line_direction: Vector) -> np.ndarray:
    """``|(c - p_i) · (d̂_i × â)|`` for the lines ``p_i + t·d_i`` (rows) against ``c + t·a``.

    Zero exactly when the lines meet or are parallel; it equals ``distance · sin(angle)`` and
    is the well-conditioned form of the paper's condition ``∇f(p)·(ā + a × p) = 0`` that the
    normal at ``p`` meets the axis ``(a : ā)``. Zero directions give ``0``.
    """
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    d = np.asarray(directions, dtype=np.float64).reshape(-1, 3)
    norms = np.linalg.norm(d, axis=1, keepdims=True)
    with np.errstate(divide="ignore", invalid="ignore"):
        d = np.where(norms > 0.0, d / norms, 0.0)
    a = unit(as_vector(line_direction, "line direction"))
    c = as_vector(line_point, "line point")
    skews: np.ndarray = np.abs(np.einsum("ij,ij->i", c - pts, np.cross(d, a)))
    return skews


def line_distance(p1: Vector, d1: Vector, p2: Vector, d2: Vector, parallel_tol: float = 1e-12) -> float:
    """The distance between the lines ``p1 + t·d1`` and ``p2 + t·d2``.

    Parallel lines (``sin(angle) ≤ parallel_tol``) count as meeting at infinity, the
    projective convention of the paper, and get distance ``0``.
    """
    sine = float(np.linalg.norm(np.cross(unit(as_vector(d1)), unit(as_vector(d2)))))
    if sine <= parallel_tol:
        return 0.0
    return float(line_skews(as_vector(p1), as_vector(d1), p2, d2)[0]) / sine


def foot_on_line(point: Vector, line_point: Vector, line_direction: Vector) -> np.ndarray:
    """The orthogonal projection of ``point`` onto the line ``line_point + t·line_direction``."""
    c, a = as_vector(line_point, "axis point"), unit(as_vector(line_direction, "axis direction"))
    if not np.any(a):
        raise ValueError("axis direction must be nonzero")
    foot: np.ndarray = c + ((as_vector(point, "point") - c) @ a) * a
    return foot


ISOMETRIC = (1.0, 1.0, 1.0)
"""The default view looks from this direction at the centre, with ``z`` up (pyvista's isometric view)."""
FLAT = 0.999
"""A drawn surface is flat when the mean of its front faces' unit normals is this long."""


def view_direction(normals: np.ndarray, side: np.ndarray) -> np.ndarray:
    """The unit vector from the centre to the camera of the default view of a mesh whose unit
    normals are ``normals`` and whose front faces point along ``side · normals``: the isometric
    direction, unless the mesh is flat (a plane), which that direction may see edge-on or from
    behind; a plane is seen from its front, within 27° of its normal, leaning towards the
    isometric direction."""
    isometric = unit(ISOMETRIC)
    if len(normals):
        mean = (np.asarray(normals, dtype=np.float64) * np.asarray(side, dtype=np.float64)[:, None]).mean(axis=0)
        if np.linalg.norm(mean) > FLAT:
            normal = unit(mean)
            return unit(2.0 * normal + isometric - (isometric @ normal) * normal)
    return isometric


def view_up(direction: Vector) -> np.ndarray:
    """The up vector of a camera looking from ``direction``: ``z``, or ``y`` when ``direction``
    is nearly ``z`` itself."""
    return np.array([0.0, 1.0, 0.0]) if abs(unit(direction)[2]) > 0.99 else np.array([0.0, 0.0, 1.0])


# --- VTK flat cell arrays -------------------------------------------------------------------


def runs(points: np.ndarray, keep: Sequence[bool] | np.ndarray) -> list[np.ndarray]:
    """The stretches of the polyline ``points`` whose points are all kept (two points at least)."""
    pieces, start = [], None
    for i, kept in enumerate([*keep, False]):
        if kept and start is None:
            start = i
        elif not kept and start is not None:
            if i - start >= 2:
                pieces.append(points[start:i])
            start = None
    return pieces


def clip_to_ball(points: np.ndarray, ball: ClipSphere) -> list[np.ndarray]:
    """The pieces of the polyline ``points (n, 3)`` inside ``ball``, each ending where its
    segment crosses the sphere (not at the last point inside, which left gaps of a segment at
    the boundary); non-finite points end a piece."""
    center, radius2 = np.asarray(ball.center), ball.radius**2
    pts = np.asarray(points, dtype=np.float64)
    finite = np.all(np.isfinite(pts), axis=1)
    with np.errstate(invalid="ignore"):
        inside = finite & (np.sum((np.nan_to_num(pts) - center) ** 2, axis=1) <= radius2)
    pieces: list[np.ndarray] = []
    current: list[np.ndarray] = []
    for i in range(len(pts)):
        if inside[i]:
            if not current and i > 0 and finite[i - 1]:
                current.append(_crossing(pts[i], pts[i - 1], center, radius2))
            current.append(pts[i])
            continue
        if current:
            if finite[i]:
                current.append(_crossing(pts[i - 1], pts[i], center, radius2))
            pieces.append(np.array(current))
            current = []
    if current:
        pieces.append(np.array(current))
    return [piece for piece in pieces if len(piece) >= 2]


def _crossing(inner: np.ndarray, outer: np.ndarray, center: np.ndarray, radius2: float) -> np.ndarray:
    """The point where the segment from ``inner`` (inside the sphere) to ``outer`` (outside)
    crosses it: the root in ``[0, 1]`` of ``|inner − center + s (outer − inner)|² = radius²``."""
    d, e = outer - inner, inner - center
    a, b, c = d @ d, 2.0 * (d @ e), e @ e - radius2
    s = (-b + np.sqrt(max(b * b - 4.0 * a * c, 0.0))) / (2.0 * a) if a > 0 else 0.0
    point: np.ndarray = inner + min(max(s, 0.0), 1.0) * d
    return point


def polyline_cells(lengths: Sequence[int], closed: Sequence[bool] | None = None) -> np.ndarray:
    """The VTK flat cell array ``[n, i0, …, i(n-1), …]`` for consecutive polylines.

    Polyline ``k`` uses the next ``lengths[k]`` points; a closed one repeats its first index.
    """
    cells: list[np.ndarray] = []
    start = 0
    for k, n in enumerate(lengths):
        ids = np.arange(start, start + n, dtype=np.int64)
        if closed is not None and closed[k] and n > 2:
            ids = np.append(ids, start)
        cells.append(np.concatenate([[len(ids)], ids]))
        start += n
    return np.concatenate(cells) if cells else np.zeros(0, dtype=np.int64)


def split_cells(cells: np.ndarray) -> list[np.ndarray]:
    """The point ids of each cell of a VTK flat cell array."""
    out, k = [], 0
    cells = np.asarray(cells, dtype=np.int64)
    while k < len(cells):
        n = int(cells[k])
        out.append(cells[k + 1 : k + 1 + n])
        k += n + 1
    return out
