"""The line complex of sampled normals: which surface a cloud of points and normals lies on
(docs/math.md §12).

A face of a CAD part is known only by samples: points ``p_i`` with unit normals ``n_i``. The
normal line at ``p_i`` has Plücker coordinates ``(n_i : p_i × n_i)``, and it meets (or is parallel
to) the line ``(a : b)`` exactly when ``n_i·b + (p_i × n_i)·a = 0``, i.e. when the normal is
perpendicular to the velocity ``b + a × p_i`` of the rigid motion ``(a, b)`` (docs/math.md §2).
The least-squares solutions of these rows, one per sample (the six-column Plücker system of the
paper's Algorithm II, with every sample in place of five random points), are the right singular
vectors of the smallest singular values; the ones that nearly vanish span the motions that keep
the samples on their surface, classified as in §2 by :func:`.near_symmetry.candidates`: one
rotation an axis, a rotation and a translation along it a cylinder, three rotations a sphere,
a rotation and two translations a plane.

Each candidate is then checked in lengths: the plane, sphere, cylinder, cone and torus fitted to
the samples (the profile ``(h, r)`` about an axis fitted by a line or a circle, refined by
Gauss–Newton on the distances), and the largest distance of a sample from it. A candidate with
no closed-form surface (a general revolution, an extrusion, a cone over a curve) gets its
invariant (the axis, the direction, the apex) and the reduced coordinates of the samples (the
profile ``(h, r)``, the section, the central projection), whose image is a curve exactly when the
face is of that kind; the caller measures that with a fitted profile. Everything here is
``float64`` on coordinates centred and scaled to the samples' size; nothing is decided exactly.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass

import numpy as np

from ..results import ApproximateAxis
from .dense import FloatArray
from .near_symmetry import Candidate, candidates, gauss_newton, parametrisation, root_mean_square, scaled_svd

PLANE = "plane"
SPHERE = "sphere"
CYLINDER = "cylinder"
CONE = "cone"
TORUS = "torus"
REVOLUTION = "revolution"
EXTRUSION = "extrusion"
CONE_OVER_CURVE = "cone-over-curve"
NONE = "none"
KINDS = (PLANE, SPHERE, CYLINDER, CONE, TORUS, REVOLUTION, EXTRUSION, CONE_OVER_CURVE, NONE)
"""The kinds of a face, most special first: a face is reported as the first that fits."""
ANALYTIC = (PLANE, SPHERE, CYLINDER, CONE, TORUS)
"""The kinds with a closed-form distance (:func:`analytic_fits`)."""
AXIAL = (CYLINDER, CONE, TORUS, REVOLUTION)
"""The kinds with one axis of revolution (a plane and a sphere have many)."""

REFINE_RANGE = 1e4
"""A fit is refined by Gauss–Newton when its deviation is above the tolerance but within this
many tolerances of it (beyond, the samples are not of that kind; within, it is good enough)."""
ANGLE_LIMIT = 1e-9
"""A cone whose half-angle is within this of 0 or π/2 (radians) is a cylinder or a plane."""


@dataclass(frozen=True)
class Samples:
    """Points on a surface and their unit normals (``N × 3`` each), with the centre and size that
    the computations are scaled by."""

    points: FloatArray
    normals: FloatArray

    @property
    def origin(self) -> FloatArray:
        centre: FloatArray = self.points.mean(axis=0)
        return centre

    @property
    def size(self) -> float:
        """The largest distance of a sample from their centre (1 for a single point)."""
        spread = float(np.linalg.norm(self.points - self.origin, axis=1).max(initial=0.0))
        return spread if spread > 0 else 1.0

    def scaled(self) -> FloatArray:
        """The points centred on :attr:`origin` and divided by :attr:`size`."""
        moved: FloatArray = (self.points - self.origin) / self.size
        return moved


@dataclass(frozen=True)
class SurfaceFit:
    """A surface fitted to samples: its kind and what fixes it, in the samples' length units.

    ``axis``: the axis of a cylinder, cone, torus or surface of revolution, and a plane's normal
    line through the samples' centre; ``center``: a sphere's or torus's centre, a cone's apex;
    ``direction``: an extrusion's; ``radius``: a sphere's, a cylinder's, a torus's major radius;
    ``minor_radius``: a torus's tube; ``half_angle``: a cone's (radians). ``deviation``: the
    largest distance of a sample from the surface (``None``: not measurable in closed form, the
    general kinds, see :func:`reduced`)."""

    kind: str
    deviation: float | None
    axis: ApproximateAxis | None = None
    center: tuple[float, float, float] | None = None
    direction: tuple[float, float, float] | None = None
    radius: float | None = None
    minor_radius: float | None = None
    half_angle: float | None = None


# --- the Plücker system of the normal lines ----------------------------------------------------


def normal_lines(samples: Samples) -> tuple[FloatArray, FloatArray]:
    """Singular values (relative to the largest, largest first) and right singular vectors (rows
    ``(b, a)``, in scaled coordinates) of the rows ``(n_i, p_i × n_i)``, scaled as (★) is
    (:func:`.near_symmetry.scaled_svd`)."""
    p, n = samples.scaled(), samples.normals
    M = np.hstack([n, np.cross(p, n)])
    terms = np.column_stack([p[:, i] * n[:, j] for i, j in ((1, 2), (2, 1), (2, 0), (0, 2), (0, 1), (1, 0))])
    if len(M) < 6:  # fewer samples than unknowns; zero rows keep all six vectors
        M = np.vstack([M, np.zeros((6 - len(M), 6))])
    return scaled_svd(M, root_mean_square(M[:, :3]), root_mean_square(terms))


def motions(samples: Samples, count: int) -> list[Candidate]:
    """The symmetries spanned by the ``count`` smallest singular vectors of :func:`normal_lines`,
    in the samples' own coordinates."""
    _, vectors = normal_lines(samples)
    return [_unscaled(c, samples) for c in candidates(vectors, count)]


def _unscaled(candidate: Candidate, samples: Samples) -> Candidate:
    point = None if candidate.point is None else samples.origin + samples.size * candidate.point
    return Candidate(candidate.kind, candidate.direction, point)


def rotation_axis(samples: Samples) -> ApproximateAxis | None:
    """The axis of the rotation that the smallest singular vector of :func:`normal_lines` is
    nearest to (``None`` when that vector is a translation)."""
    for candidate in motions(samples, 1):
        if candidate.kind == "revolution" and candidate.point is not None and candidate.direction is not None:
            return axis_of(candidate.point, candidate.direction, samples.origin)
    return None


def translation_direction(samples: Samples) -> FloatArray:
    """The unit ``d`` with ``Σ (n_i·d)²`` least: the direction the normals are most nearly
    perpendicular to (the rows of :func:`normal_lines` with ``a = 0``)."""
    _, _, vt = np.linalg.svd(samples.normals, full_matrices=False)
    direction: FloatArray = vt[-1]
    return direction


def cone_apex(samples: Samples) -> FloatArray:
    """The point nearest (in the least-squares sense) to every tangent plane: ``n_i·(x - p_i) = 0``."""
    p, n = samples.scaled(), samples.normals
    solution = np.linalg.lstsq(n, np.einsum("ij,ij->i", n, p), rcond=None)[0]
    apex: FloatArray = samples.origin + samples.size * solution
    return apex


def axis_of(point: FloatArray, direction: FloatArray, near: FloatArray) -> ApproximateAxis:
    """The line through ``point`` along ``direction`` as its point nearest ``near`` and a unit
    direction whose largest component is positive."""
    d = direction / np.linalg.norm(direction)
    if d[int(np.argmax(np.abs(d)))] < 0:
        d = -d
    foot = point + ((near - point) @ d) * d
    return ApproximateAxis(_triple(foot), _triple(d))


def _triple(v: FloatArray) -> tuple[float, float, float]:
    return (float(v[0]), float(v[1]), float(v[2]))


# --- distances to the analytic surfaces --------------------------------------------------------


def meridian(points: FloatArray, point: FloatArray, direction: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The profile coordinates ``(h, r)`` of ``points`` about the axis: the height along the unit
    ``direction`` from ``point`` and the distance to the axis."""
    d = direction / np.linalg.norm(direction)
    rel = points - point
    h = rel @ d
    r = np.linalg.norm(rel - h[:, None] * d, axis=1)
    return h, r


def normal_miss(samples: Samples, axis: ApproximateAxis) -> FloatArray:
    """How far each normal line passes from the axis (0 where they are parallel): every normal of
    a surface of revolution meets its axis."""
    c, d = np.array(axis.point), np.array(axis.direction)
    crossed = np.cross(samples.normals, d)
    size = np.linalg.norm(crossed, axis=1)
    safe = np.where(size > 1e-12, size, 1.0)
    miss: FloatArray = np.where(size > 1e-12, np.abs(np.einsum("ij,ij->i", crossed, samples.points - c)) / safe, 0.0)
    return miss


def plane_fit(samples: Samples) -> SurfaceFit:
    """The plane through the samples' centre normal to their least spread."""
    c = samples.origin
    _, _, vt = np.linalg.svd(samples.points - c, full_matrices=False)
    normal = vt[-1]
    deviation = float(np.abs((samples.points - c) @ normal).max())
    return SurfaceFit(PLANE, deviation, axis=axis_of(c, normal, c))


def sphere_fit(samples: Samples, tolerance: float | None = None) -> SurfaceFit | None:
    """The sphere about the centre the three smallest motions rotate about, refined."""
    found = [c for c in motions(samples, 3) if c.kind == SPHERE and c.point is not None]
    centre = found[0].point if found else _normals_meet(samples)
    if centre is None:
        return None
    centre = _refined(samples, Candidate(SPHERE, None, centre), _sphere_residual, tolerance).point
    assert centre is not None
    distance = np.linalg.norm(samples.points - centre, axis=1)
    radius = float(distance.mean())
    return SurfaceFit(SPHERE, float(np.abs(distance - radius).max()), center=_triple(centre), radius=radius)


def _normals_meet(samples: Samples) -> FloatArray | None:
    """The point nearest every normal line (least squares), ``None`` if they are all parallel."""
    n, p = samples.normals, samples.scaled()
    projector = np.eye(3)[None, :, :] - n[:, :, None] * n[:, None, :]
    matrix, rhs = projector.sum(axis=0), np.einsum("kij,kj->i", projector, p)
    if np.linalg.cond(matrix) > 1e12:
        return None
    meet: FloatArray = samples.origin + samples.size * np.linalg.solve(matrix, rhs)
    return meet


def cylinder_fit(samples: Samples, tolerance: float | None = None) -> SurfaceFit | None:
    """The cylinder about the axis of the two smallest motions (a rotation and a translation
    along it), refined."""
    found = [c for c in motions(samples, 2) if c.point is not None and c.direction is not None]
    if not found:
        return None
    start = Candidate("revolution", found[0].direction, found[0].point)
    candidate = _refined(samples, start, _cylinder_residual, tolerance)
    assert candidate.point is not None and candidate.direction is not None
    _, r = meridian(samples.points, candidate.point, candidate.direction)
    radius = float(r.mean())
    return SurfaceFit(
        CYLINDER,
        float(np.abs(r - radius).max()),
        axis=axis_of(candidate.point, candidate.direction, samples.origin),
        radius=radius,
    )


def cone_fit(samples: Samples, axis: Candidate, tolerance: float | None = None) -> SurfaceFit | None:
    """The cone about ``axis`` whose profile is the line nearest the samples' ``(h, r)``, refined."""
    candidate = _refined(samples, axis, _cone_residual, tolerance)
    assert candidate.point is not None and candidate.direction is not None
    h, r = meridian(samples.points, candidate.point, candidate.direction)
    centre, along = _line_2d(h, r)
    half_angle = math.atan2(abs(along[1]), abs(along[0]))
    if not ANGLE_LIMIT < half_angle < math.pi / 2 - ANGLE_LIMIT:
        return None
    apex_h = centre[0] - centre[1] * along[0] / along[1]
    d = candidate.direction / np.linalg.norm(candidate.direction)
    apex = candidate.point + apex_h * d
    deviation = float(np.abs(_line_residual(h, r, centre, along)).max())
    return SurfaceFit(
        CONE,
        deviation,
        axis=axis_of(candidate.point, candidate.direction, samples.origin),
        center=_triple(apex),
        half_angle=half_angle,
    )


def torus_fit(samples: Samples, axis: Candidate, tolerance: float | None = None) -> SurfaceFit | None:
    """The torus about ``axis`` whose profile is the circle nearest the samples' ``(h, r)``, refined."""
    candidate = _refined(samples, axis, _torus_residual, tolerance)
    assert candidate.point is not None and candidate.direction is not None
    h, r = meridian(samples.points, candidate.point, candidate.direction)
    circle = _circle_2d(h, r)
    if circle is None:
        return None
    (ch, cr), minor = circle
    d = candidate.direction / np.linalg.norm(candidate.direction)
    deviation = float(np.abs(np.hypot(h - ch, r - cr) - minor).max())
    return SurfaceFit(
        TORUS,
        deviation,
        axis=axis_of(candidate.point, candidate.direction, samples.origin),
        center=_triple(candidate.point + ch * d),
        radius=abs(cr),
        minor_radius=minor,
    )


def analytic_fits(samples: Samples, tolerance: float | None = None) -> Iterator[SurfaceFit]:
    """The plane, sphere, cylinder, cone and torus nearest the samples (those that can be
    fitted), in the order of :data:`KINDS`, each with its largest distance from the samples (a
    generator: the caller stops at the first that fits). Fits are refined by Gauss–Newton (see
    :func:`_refined`; always, without a ``tolerance``)."""
    yield plane_fit(samples)
    for fitted in (sphere_fit(samples, tolerance), cylinder_fit(samples, tolerance)):
        if fitted is not None:
            yield fitted
    axis = rotation_axis(samples)
    if axis is None:
        return
    start = Candidate("revolution", np.array(axis.direction), np.array(axis.point))
    for fit_about in (cone_fit, torus_fit):
        fitted = fit_about(samples, start, tolerance)
        if fitted is not None:
            yield fitted


# --- the general kinds: an invariant and the reduced coordinates ----------------------------------


def revolution_fit(samples: Samples) -> SurfaceFit | None:
    """The axis of the smallest motion, if a rotation; the distance is measured by the caller."""
    axis = rotation_axis(samples)
    return None if axis is None else SurfaceFit(REVOLUTION, None, axis=axis)


def extrusion_fit(samples: Samples) -> SurfaceFit:
    """The direction every normal is nearest perpendicular to."""
    d = translation_direction(samples)
    direction = axis_of(samples.origin, d, samples.origin).direction
    return SurfaceFit(EXTRUSION, None, direction=direction)


def cone_over_curve_fit(samples: Samples) -> SurfaceFit:
    """The point nearest every tangent plane, and the largest distance of a tangent plane from
    it (0 for a cone over any curve: every tangent plane holds the apex)."""
    apex = cone_apex(samples)
    miss = np.abs(np.einsum("ij,ij->i", samples.normals, samples.points - apex))
    return SurfaceFit(CONE_OVER_CURVE, float(miss.max()), center=_triple(apex))


def reduced(fit: SurfaceFit, points: FloatArray) -> FloatArray:
    """The points in the plane a general kind reduces them to (``N × 2``): the profile ``(h, r)``
    about a revolution's axis, the coordinates across an extrusion's direction, the central
    projection from a cone's apex onto the plane at distance 1 along the mean ray. The face is of
    that kind exactly when the image is a curve."""
    if fit.kind == REVOLUTION:
        assert fit.axis is not None
        h, r = meridian(points, np.array(fit.axis.point), np.array(fit.axis.direction))
        return np.column_stack([h, r])
    if fit.kind == EXTRUSION:
        assert fit.direction is not None
        e1, e2 = across(np.array(fit.direction))
        return np.column_stack([points @ e1, points @ e2])
    assert fit.kind == CONE_OVER_CURVE and fit.center is not None
    rays = points - np.array(fit.center)
    mean = rays.mean(axis=0)
    m = mean / np.linalg.norm(mean)
    e1, e2 = across(m)
    depth = rays @ m
    central: FloatArray = np.column_stack([rays @ e1, rays @ e2]) / depth[:, None]
    return central


def across(d: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Two unit vectors completing ``d`` to an orthonormal frame."""
    d = d / np.linalg.norm(d)
    e = np.zeros(3)
    e[int(np.argmin(np.abs(d)))] = 1.0
    e1 = np.cross(d, e)
    e1 /= np.linalg.norm(e1)
    return e1, np.cross(d, e1)


# --- profiles in the meridian half-plane, and the Gauss–Newton refinement --------------------------


def _line_2d(x: FloatArray, y: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The line nearest the points ``(x, y)`` (total least squares): a point and a unit direction."""
    q = np.column_stack([x, y])
    centre = q.mean(axis=0)
    _, _, vt = np.linalg.svd(q - centre, full_matrices=False)
    along: FloatArray = vt[0]
    return centre, along


def _line_residual(x: FloatArray, y: FloatArray, centre: FloatArray, along: FloatArray) -> FloatArray:
    normal = np.array([-along[1], along[0]])
    residual: FloatArray = (np.column_stack([x, y]) - centre) @ normal
    return residual


def _circle_2d(x: FloatArray, y: FloatArray, refine: bool = True) -> tuple[tuple[float, float], float] | None:
    """The circle nearest the points (Kåsa's algebraic fit ``x² + y² + Dx + Ey + F = 0``, then,
    if ``refine``, Gauss–Newton on the distances): its centre and radius, ``None`` for collinear
    points."""
    A = np.column_stack([x, y, np.ones_like(x)])
    scale = float(np.abs(A[:, :2]).max(initial=1.0)) or 1.0
    solution, _, rank, _ = np.linalg.lstsq(A / [scale, scale, 1.0], -(x * x + y * y), rcond=None)
    if rank < 3:
        return None
    D, E, F = solution[0] / scale, solution[1] / scale, solution[2]
    centre = np.array([-D / 2, -E / 2])
    squared = float(centre @ centre - F)
    if squared <= 0:
        return None

    def residual(c: FloatArray) -> FloatArray:
        distance = np.hypot(x - c[0], y - c[1])
        remainder: FloatArray = distance - distance.mean()
        return remainder

    if refine:
        centre = gauss_newton(residual, centre)[0]
    radius = float(np.hypot(x - centre[0], y - centre[1]).mean())
    return (float(centre[0]), float(centre[1])), radius


def _sphere_residual(points: FloatArray, candidate: Candidate) -> FloatArray:
    assert candidate.point is not None
    distance = np.linalg.norm(points - candidate.point, axis=1)
    residual: FloatArray = distance - distance.mean()
    return residual


def _cylinder_residual(points: FloatArray, candidate: Candidate) -> FloatArray:
    assert candidate.point is not None and candidate.direction is not None
    _, r = meridian(points, candidate.point, candidate.direction)
    residual: FloatArray = r - r.mean()
    return residual


def _cone_residual(points: FloatArray, candidate: Candidate) -> FloatArray:
    assert candidate.point is not None and candidate.direction is not None
    h, r = meridian(points, candidate.point, candidate.direction)
    return _line_residual(h, r, *_line_2d(h, r))


def _torus_residual(points: FloatArray, candidate: Candidate) -> FloatArray:
    assert candidate.point is not None and candidate.direction is not None
    h, r = meridian(points, candidate.point, candidate.direction)
    circle = _circle_2d(h, r, refine=False)
    if circle is None:
        return np.full(len(points), 1e3)
    (ch, cr), radius = circle
    residual: FloatArray = np.hypot(h - ch, r - cr) - radius
    return residual


def _refined(
    samples: Samples,
    start: Candidate,
    residual: Callable[[FloatArray, Candidate], FloatArray],
    tolerance: float | None = None,
) -> Candidate:
    """``start`` (an axis or a centre) moved by Gauss–Newton to make the distances of the samples
    from the fitted surface least (variable projection: the profile is refitted at every step),
    in scaled coordinates; left as it is when its deviation is within ``tolerance`` or beyond
    :data:`REFINE_RANGE` tolerances."""
    origin, size = samples.origin, samples.size
    point = None if start.point is None else (start.point - origin) / size
    scaled = Candidate(start.kind, start.direction, point)
    theta, build = parametrisation(scaled)
    points = samples.scaled()
    if tolerance is not None:
        deviation = float(np.abs(residual(points, scaled)).max()) * size
        if not tolerance < deviation <= REFINE_RANGE * tolerance:
            return start
    best = gauss_newton(lambda t: residual(points, build(t)), theta)[0]
    found = build(best)
    if np.abs(residual(points, found)).max() > np.abs(residual(points, scaled)).max():
        found = scaled
    assert found.point is not None
    return Candidate(start.kind, found.direction, origin + size * found.point)
