"""A profile with no exact rational form, fitted within a stated tolerance and measured both ways.

Each arc of the real profile (:mod:`.meridian`) is interpolated by a cubic ``C²`` B-spline
(``GeomAPI_Interpolate``, chord-length parameters; periodic for a loop) through points on it; its
distance to the profile is measured at :data:`SAMPLES` points of every span, and every span
farther than the tolerance is halved (its midpoint moved onto the profile), up to
:data:`REFINEMENTS` times. That is one side. The other: points of the real surface in the region
(the 3D view's mesh vertices, moved onto the profile in the meridian half-plane) must each lie
within the tolerance of a fitted curve — so a branch missed, or a band between two pieces of the
tracing, is a measured deviation, not a silent gap (docs/math.md §11).
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass

import numpy as np
from OCP.Geom import Geom_BSplineCurve
from OCP.GeomAPI import GeomAPI_Interpolate, GeomAPI_ProjectPointOnCurve
from OCP.gp import gp_Pnt
from OCP.OCP.collections import HArray1_gp_Pnt

from sorgui.render import ClipSphere

from .failures import from_occt
from .geometry import CadGeometryError
from .meridian import Arc, Distance, MeridianCurve

FIT_TOLERANCE = 1e-7
"""The default tolerance of a fitted profile, relative to the drawn ball's radius."""

REFINEMENTS = 12
"""How many times the spans of a fitted arc that miss the tolerance are halved, at most (a span
shorter than the tolerance is not halved: its curve cannot stray further)."""

MAX_POINTS = 20_000
"""The most points a fitted arc interpolates."""

SAMPLES = 10
"""Points per span at which a fitted curve's distance to the profile is measured."""

COVERAGE_CELLS = 800
"""The mesh's vertices, turned into the meridian half-plane, are checked one per square cell of
a side this many times smaller than the ball's radius: every part of the profile the mesh sees
(a band of the surface missing from the part is one), at a cost that follows the profile's
length, not the mesh's size."""


@dataclass(frozen=True)
class Fit:
    """A fitted profile curve, the largest distance measured from it to the profile, and that
    distance on each span between two consecutive points it interpolates."""

    curve: Geom_BSplineCurve
    deviation: float
    spans: np.ndarray


def fitted_arc(arc: Arc, goal: float, distance: Distance, curve: MeridianCurve) -> Fit:
    """A curve through the arc's points within ``goal``: every span whose measured distance to
    the profile is larger is halved (its midpoint moved onto the profile), and the curve drawn
    again, at most :data:`REFINEMENTS` times and up to :data:`MAX_POINTS` points."""
    xy = _distinct(arc.points, arc.closed)
    fit = fitted_curve(curve.frame.to_space(xy), distance, arc.closed)
    for _ in range(REFINEMENTS):
        following = np.roll(xy, -1, axis=0) if arc.closed else xy[1:]
        length = np.linalg.norm(following - xy[: len(following)], axis=1)
        wide = np.flatnonzero((fit.spans > goal) & (length > goal / 100))
        if len(wide) == 0 or len(xy) + len(wide) > MAX_POINTS:
            break
        middles = curve.curve.onto((xy[wide] + following[wide]) / 2)
        xy = _distinct(np.insert(xy, wide + 1, middles, axis=0), arc.closed)
        fit = fitted_curve(curve.frame.to_space(xy), distance, arc.closed)
    return fit


def _distinct(points: np.ndarray, closed: bool) -> np.ndarray:
    """``points`` without those that repeat the one before (interpolation needs distinct points);
    the ends are kept, and a loop's last point does not repeat its first."""
    scale = max(1.0, float(np.abs(points).max()))
    step = np.linalg.norm(np.diff(points, axis=0), axis=1)
    keep = np.concatenate([[True], step > 1e-12 * scale])
    if not keep[-1] and len(points) > 2:
        keep[-1], keep[-2] = True, False
    kept: np.ndarray = points[keep]
    if closed and len(kept) > 3 and np.linalg.norm(kept[-1] - kept[0]) <= 1e-12 * scale:
        kept = kept[:-1]
    return kept


def fitted_curve(points: np.ndarray, distance: Distance, periodic: bool = False) -> Fit:
    """The cubic ``C²`` B-spline through ``points`` (3D, distinct, ordered along one profile arc;
    ``GeomAPI_Interpolate``, chord-length parameters; ``periodic`` for a loop), with its distance
    to the profile measured by ``distance`` at :data:`SAMPLES` points of every span."""
    if len(points) < (3 if periodic else 2):
        raise CadGeometryError("a profile arc has too few points to fit")
    array = HArray1_gp_Pnt(1, len(points))
    for k, p in enumerate(points, start=1):
        array.SetValue(k, gp_Pnt(float(p[0]), float(p[1]), float(p[2])))
    try:
        interpolation = GeomAPI_Interpolate(array, periodic, 0.0)
        interpolation.Perform()
        done = interpolation.IsDone()
    except Exception as exc:
        if not from_occt(exc):
            raise
        done = False
    if not done:
        raise CadGeometryError("Open CASCADE could not fit a B-spline to the profile")
    curve = interpolation.Curve()
    knots = np.array([curve.Knot(k) for k in range(1, curve.NbKnots() + 1)])
    steps = np.arange(1, SAMPLES + 1) / (SAMPLES + 1)
    samples = (knots[:-1, None] + np.diff(knots)[:, None] * steps).ravel()
    xyz = np.array([curve.Value(float(u)).Coord() for u in samples])
    spans = np.max(distance(xyz).reshape(len(knots) - 1, SAMPLES), axis=1)
    return Fit(curve, float(spans.max(initial=0.0)), spans)


def uncovered(
    curves: Sequence[Geom_BSplineCurve], curve: MeridianCurve, surface: np.ndarray, ball: ClipSphere, goal: float
) -> tuple[float, np.ndarray | None]:
    """The largest distance from a point of the real profile to the ``curves`` (3D, in the
    frame's half-plane), over ``surface`` points (the mesh's vertices) turned into the half-plane
    and moved onto the profile (one per :data:`COVERAGE_CELLS` cell); and the surface point
    where it is largest, if above ``goal``. Points that Newton's method does not bring onto the
    profile (next to a singular point) are left out."""
    if not len(surface) or not curves:
        return 0.0, None
    frame = curve.frame
    relative = np.asarray(surface, dtype=np.float64) - frame.point
    along = relative @ frame.direction
    radial = np.linalg.norm(relative - np.outer(along, frame.direction), axis=1)
    xy, origins = _one_per_cell(np.column_stack([along, radial]), surface, ball.radius / COVERAGE_CELLS)
    xy = curve.curve.onto(xy, steps=30)
    centre = np.array([float(frame.to_plane(np.array([ball.center]))[0, 0]), 0.0])
    settled = np.linalg.norm(curve.curve.onto(xy, steps=1) - xy, axis=1) <= min(goal, 1e-9 * ball.radius) / 10
    inside = np.linalg.norm(xy - centre, axis=1) <= ball.radius
    keep = settled & inside & (xy[:, 1] >= 0)
    points, origins = frame.to_space(xy[keep]), origins[keep]
    if not len(points):
        return 0.0, None
    distances = ball.radius * _curve_distances(*_in_unit_ball(curves, points, ball), 1.0 / COVERAGE_CELLS)
    worst = int(np.argmax(distances))
    return float(distances[worst]), (origins[worst] if distances[worst] > goal else None)


def _in_unit_ball(
    curves: Sequence[Geom_BSplineCurve], points: np.ndarray, ball: ClipSphere
) -> tuple[list[Geom_BSplineCurve], np.ndarray]:
    """Copies of ``curves`` and ``points`` moved and scaled so that ``ball`` is the unit ball:
    Open CASCADE's projection onto a curve stops within its absolute confusion (1e-7), and a
    paraboloid's exact profile in a ball of radius 0.014 was found 4e-8 from it, 3 times the
    tolerance of its part (refused)."""
    centre = gp_Pnt(*map(float, ball.center))
    scaled = []
    for curve in curves:
        copy = curve.Copy()
        copy.Translate(centre, gp_Pnt(0.0, 0.0, 0.0))
        copy.Scale(gp_Pnt(0.0, 0.0, 0.0), 1.0 / ball.radius)
        scaled.append(copy)
    return scaled, (np.asarray(points) - np.asarray(ball.center)) / ball.radius


def _one_per_cell(xy: np.ndarray, origins: np.ndarray, cell: float) -> tuple[np.ndarray, np.ndarray]:
    """One point of ``xy`` (and its row of ``origins``) per square cell of side ``cell``."""
    keys = np.floor(xy / cell).astype(np.int64)
    _, first = np.unique(keys, axis=0, return_index=True)
    return xy[first], origins[first]


def _curve_distances(curves: Sequence[Geom_BSplineCurve], points: np.ndarray, spacing: float) -> np.ndarray:
    """The distance of each point to the nearest of ``curves``: the samples at most about
    ``spacing`` apart found first, then the exact foot (``GeomAPI_ProjectPointOnCurve``) on the
    curves between the samples next to each sample within ``spacing`` of the nearest one. Not
    the nearest sample's alone: where a curve comes back close to itself (two branches into a
    cusp, the seam of a loop) the nearest sample can lie on the other branch."""
    samples, owners, parameters = [], [], []
    for index, c in enumerate(curves):
        u = _samples(c, spacing)
        samples.append(np.array([c.Value(float(t)).Coord() for t in u]))
        owners.append(np.full(len(u), index))
        parameters.append(u)
    xyz, owner = np.concatenate(samples), np.concatenate(owners)
    place = np.concatenate([np.arange(len(u)) for u in parameters])
    out = np.empty(len(points))
    for start in range(0, len(points), 256):
        chunk = points[start : start + 256]
        gaps = np.linalg.norm(chunk[:, None, :] - xyz[None, :, :], axis=2)
        for k, row in enumerate(gaps):
            spans = _spans(np.flatnonzero(row <= row.min() + spacing), owner, place, parameters)
            out[start + k] = min(float(row.min()), *(_foot_distance(curves[c], chunk[k], a, b) for c, a, b in spans))
    return out


def _spans(
    near: np.ndarray, owner: np.ndarray, place: np.ndarray, parameters: list[np.ndarray]
) -> Iterator[tuple[int, float, float]]:
    """``(curve, low, high)``: the parameter ranges about the runs of consecutive samples ``near``
    (indices into all curves' samples, in order), one sample beyond each end of a run."""
    for run in np.split(near, np.flatnonzero(np.diff(near) != 1) + 1):
        for c in np.unique(owner[run]):
            u, ours = parameters[c], place[run[owner[run] == c]]
            yield int(c), u[max(int(ours.min()) - 1, 0)], u[min(int(ours.max()) + 1, len(u) - 1)]


def _samples(curve: Geom_BSplineCurve, spacing: float) -> np.ndarray:
    """Parameters of ``curve``: its knots, and each span cut into pieces about ``spacing`` long."""
    knots = np.array([curve.Knot(k) for k in range(1, curve.NbKnots() + 1)])
    out = [knots[:1]]
    for a, b in zip(knots[:-1], knots[1:]):
        probe = np.array([curve.Value(float(t)).Coord() for t in np.linspace(a, b, 5)])
        length = float(np.linalg.norm(np.diff(probe, axis=0), axis=1).sum())
        pieces = min(200, max(2, int(np.ceil(length / spacing))))
        out.append(np.linspace(a, b, pieces + 1)[1:])
    return np.concatenate(out)


def _foot_distance(curve: Geom_BSplineCurve, point: np.ndarray, low: float, high: float) -> float:
    """The distance from ``point`` to ``curve`` over ``[low, high]`` (``inf`` without a foot)."""
    try:
        projection = GeomAPI_ProjectPointOnCurve(gp_Pnt(*map(float, point)), curve, float(low), float(high))
        if projection.NbPoints() == 0:
            return float("inf")
        return float(projection.LowerDistance())
    except Exception as exc:
        if not from_occt(exc):
            raise
        return float("inf")
