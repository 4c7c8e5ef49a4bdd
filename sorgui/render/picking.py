"""What the viewport shows about a picked point: ``f``, ``∇f``, the normal line, the axis test.

The paper's recognition rests on one fact: on a surface of revolution every normal line meets
the axis (Section 2; docs/math.md §2 turns it into the identity ``∇f(p)·(ā + a × p) ≡ 0``). The
viewport lets the user *see* it: pick a point, draw its normal and its latitude circle, and
report how far the normal passes from the axis. This is floating-point display; the exact
answer is the engine's.

All functions take plain data (terms as in :mod:`sorgui.render.sampling`) and return plain
data, so they may run on a worker thread.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from sorgui.render.geometry import (
    Vector,
    as_vector,
    foot_on_line,
    line_distance,
    line_skews,
    unit,
)
from sorgui.render.sampling import Terms, newton_step, value_and_gradient
from sorgui.render.scene import LineData, latitude_circle, normal_line

DEFAULT_REL_TOL = 1e-6
"""Relative tolerance of :func:`normal_meets_axis`, in units of ``max(|p - c|, |p|, |c|)``."""


@dataclass(frozen=True)
class AxisTest:
    """How the normal line at a point sits relative to an axis.

    ``distance``: the distance between the two lines (``0`` when they are parallel: they meet
    at infinity, the paper's projective convention). ``skew``: ``distance · sin(angle)``, the
    well-conditioned quantity the decision uses. ``meets``: ``skew ≤ rel_tol · scale``.
    """

    distance: float
    skew: float
    meets: bool
    sine: float = 1.0
    """``sin(angle)`` between the two lines: near 0 the distance is the skew divided by it, noise
    (a rounded torus's tube top gave 0.0586 where others gave 1e-9)."""

    def words(self, mark: Callable[[str], str] = str) -> str:
        """The normal meets or misses the axis (the verb through ``mark``, the window's bold), and
        how far apart they are where that is known."""
        verdict = f"{mark('meets' if self.meets else 'misses')} the axis"
        if self.meets and self.sine < NEARLY_PARALLEL and self.distance != 0:
            return f"normal {verdict} (nearly parallel)"
        return f"normal {verdict} (distance {self.distance:.3g})"


NEARLY_PARALLEL = 1e-2
"""Below this ``sin(angle)`` a normal that meets the axis is said to be nearly parallel to it,
and no distance is printed (but an exact 0, the top of an exact torus's tube)."""


@dataclass(frozen=True, eq=False)
class PickInfo:
    """Everything the viewport reports about a picked point.

    ``point``: the point (after optional snapping onto ``f = 0``); ``value``: ``f(point)``;
    ``gradient``: ``∇f(point)``; ``normal_direction``: the unit gradient (zero at a singular
    point); ``normal``: the normal segment to draw; ``height`` and ``radius``: the point's
    coordinates in the axis frame (position along the unit axis from ``c``, distance from the
    axis), ``nan`` without an axis; ``axis_test``: ``None`` without an axis or at a singular
    point; ``latitude``: the circle through the point about the axis (empty without an axis).
    """

    point: np.ndarray
    value: float
    gradient: np.ndarray
    normal_direction: np.ndarray
    normal: LineData
    height: float
    radius: float
    axis_test: AxisTest | None
    latitude: LineData

    @property
    def is_singular(self) -> bool:
        """True where ``∇f`` vanishes (numerically exactly): there is no normal line."""
        return not bool(np.any(self.normal_direction))

    @property
    def meets_axis(self) -> bool | None:
        return None if self.axis_test is None else self.axis_test.meets

    @property
    def axis_distance(self) -> float | None:
        return None if self.axis_test is None else self.axis_test.distance

    def summary(self) -> str:
        """One line for a status bar."""
        x, y, z = self.point
        parts = [f"p = ({x:.6g}, {y:.6g}, {z:.6g})", f"f(p) = {self.value:.3g}"]
        if self.is_singular:
            parts.append("singular point (∇f = 0)")
        else:
            gx, gy, gz = self.gradient
            parts.append(f"∇f = ({gx:.3g}, {gy:.3g}, {gz:.3g})")
        if np.isfinite(self.radius):
            parts.append(f"height {self.height:.6g}, radius {self.radius:.6g}")
        if self.axis_test is not None:
            parts.append(self.axis_test.words())
        return "; ".join(parts)


def normal_meets_axis(
    point: Vector,
    normal_direction: Vector,
    axis_point: Vector,
    axis_direction: Vector,
    rel_tol: float = DEFAULT_REL_TOL,
) -> AxisTest:
    """Does the normal line ``point + t·normal_direction`` meet the axis ``c + t·a``?

    Decides on ``skew = |(c - p)·(n̂ × â)|``, which vanishes when the lines meet or are
    parallel (docs/math.md §2: ``∇f(p)·(ā + a × p) = 0``, normalised), against
    ``rel_tol · max(|p - c|, |p|, |c|)``: the size of the numbers the computation loses
    digits on. ``ValueError`` for a zero direction.
    """
    p, n = as_vector(point, "point"), as_vector(normal_direction, "normal direction")
    c, a = as_vector(axis_point, "axis point"), as_vector(axis_direction, "axis direction")
    if not np.any(n) or not np.any(a):
        raise ValueError("the normal and axis directions must be nonzero")
    skew, tolerance = _skew_and_tolerance(p[None, :], n[None, :], c, a, rel_tol)
    sine = float(np.linalg.norm(np.cross(unit(n), unit(a))))
    return AxisTest(line_distance(p, n, c, a), float(skew[0]), bool(skew[0] <= tolerance[0]), sine)


def _skew_and_tolerance(
    points: np.ndarray, normals: np.ndarray, c: np.ndarray, a: np.ndarray, rel_tol: float
) -> tuple[np.ndarray, np.ndarray]:
    """The skew of each normal line against the axis and its tolerance ``rel_tol · scale``."""
    skew = line_skews(points, normals, c, a)
    scale = np.maximum(np.linalg.norm(points - c, axis=1), np.linalg.norm(points, axis=1))
    scale = np.maximum(scale, float(np.linalg.norm(c)))
    return skew, rel_tol * np.where(scale > 0.0, scale, 1.0)


def axis_coordinates(point: Vector, axis_point: Vector, axis_direction: Vector) -> tuple[float, float]:
    """``(height, radius)`` of ``point``: signed position along the unit axis from
    ``axis_point``, and distance from the axis (the orthonormal profile frame of docs/math.md §3)."""
    p = as_vector(point, "point")
    foot = foot_on_line(p, axis_point, axis_direction)
    a = unit(as_vector(axis_direction, "axis direction"))
    height = float((foot - as_vector(axis_point, "axis point")) @ a)
    return height, float(np.linalg.norm(p - foot))


def snap_to_surface(terms: Terms, point: Vector, max_distance: float, iterations: int = 8) -> np.ndarray:
    """Newton-project ``point`` onto ``f = 0``, moving it at most ``max_distance`` in total.

    A pick lands on a triangle of the mesh, a little off the surface; this moves it onto the
    surface along the gradient (Newton's method; a singular point stays put).
    """
    start = as_vector(point, "point")
    p = start
    for _ in range(iterations):
        q = newton_step(terms, p[None, :], max_distance)[0]
        converged = np.linalg.norm(q - p) <= 1e-15 * max(1.0, float(np.linalg.norm(q)))
        p = q
        if converged:
            break
    moved = float(np.linalg.norm(p - start))
    if moved > max_distance:
        p = start + (p - start) * (max_distance / moved)
    return p


def pick_info(
    terms: Terms,
    point: Vector,
    axis: tuple[Vector, Vector] | None = None,
    normal_length: float = 1.0,
    rel_tol: float = DEFAULT_REL_TOL,
    snap_distance: float = 0.0,
    circle_points: int = 128,
    typed_terms: Terms | None = None,
) -> PickInfo:
    """Inspect ``f`` at a picked ``point``; with ``axis = (c, a)`` test it against that axis.

    ``snap_distance > 0`` first moves the point onto ``f = 0`` (:func:`snap_to_surface`), e.g.
    by the mesh's grid spacing. The normal segment has total length ``normal_length``. The
    latitude circle is drawn whenever an axis is given; it lies on the surface when the
    surface is one of revolution about that axis. ``terms`` give the zero set and the normal;
    the value and the gradient reported are those of ``typed_terms`` when given (the equation
    as typed, where ``terms`` are its square-free part: another scale, or another power).
    """
    p = as_vector(point, "point")
    if snap_distance > 0.0:
        p = snap_to_surface(terms, p, snap_distance)
    values, grads = value_and_gradient(terms if typed_terms is None else typed_terms, p[None, :])
    value, gradient = float(values[0]), grads[0]
    # The direction from the overflow-free normalised gradient, which has the same direction.
    direction = unit(value_and_gradient(terms, p[None, :], normalise=True)[1][0])
    normal = normal_line(p, direction, normal_length)
    if axis is None:
        empty = LineData.empty()
        return PickInfo(p, value, gradient, direction, normal, np.nan, np.nan, None, empty)
    c, a = as_vector(axis[0], "axis point"), as_vector(axis[1], "axis direction")
    height, radius = axis_coordinates(p, c, a)
    test = None if not np.any(direction) else normal_meets_axis(p, direction, c, a, rel_tol)
    latitude = latitude_circle(p, c, a, circle_points)
    return PickInfo(p, value, gradient, direction, normal, height, radius, test, latitude)


def pick_many(
    terms: Terms,
    points: np.ndarray | Sequence[Sequence[float]],
    axis: tuple[Vector, Vector],
    rel_tol: float = DEFAULT_REL_TOL,
) -> np.ndarray:
    """Vectorised axis test for many points: a boolean per point, ``True`` where the normal
    meets the axis (singular points count as meeting). Useful to colour a mesh by it."""
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    _, grads = value_and_gradient(terms, pts, normalise=True)
    c, a = as_vector(axis[0], "axis point"), as_vector(axis[1], "axis direction")
    norms = np.linalg.norm(grads, axis=1)
    singular = ~(np.isfinite(norms) & (norms > 0.0))
    skew, tolerance = _skew_and_tolerance(pts, grads, c, a, rel_tol)
    meets: np.ndarray = singular | (skew <= tolerance)
    return meets
