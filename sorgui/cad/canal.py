"""A canal surface (a pipe among them) as the sweep of its characteristic circles (docs/math.md §9, §11).

A canal surface is the envelope of a one-parameter family of spheres; it is the union of its
characteristic circles, centre ``k(t)``, radius² ``r²(t)``, plane normal ``n(t)``, all rational
in the spine parameter ``t`` (``CanalFamily.circle_*``). The part in the ball is swept through
circles at parameters ``t`` where they meet the ball (``|k − m| ≤ R + r``), each circle's start
point carried along the spine (the previous start projected into the next plane, so the sweep
does not twist): ``BRepOffsetAPI_ThruSections`` makes a B-spline surface through them, a fitted
surface like a fitted profile. Its distance to ``f = 0`` is measured at points between the
circles, the circles doubled where it is above the tolerance, and the figure is stated; then
the faces are cut to the ball. The normals are kept turning one way (``n(t)`` of the family
can change sign, which would turn a circle round and twist the sweep).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from OCP.BRep import BRep_Tool
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakeWire
from OCP.BRepOffsetAPI import BRepOffsetAPI_ThruSections
from OCP.BRepTools import BRepTools
from OCP.GC import GC_MakeCircle
from OCP.GeomAPI import GeomAPI_ProjectPointOnSurf
from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt
from OCP.TopoDS import TopoDS_Face

from sorgui.engine.results import Analysis
from sorgui.engine.stage_results import CanalFamily
from sorgui.engine.values import ExpressionError, Terms, polynomial_terms, rational_function_terms
from sorgui.render import ClipSphere

from .failures import from_occt
from .geometry import CadGeometryError, surface_distance
from .reading import faces_of

SAMPLES = 4096
"""Parameters ``t = tan(θ/2)`` at which the circles are tried against the ball."""

SECTIONS = (24, 48, 96, 128, 160, 192, 256)
"""The circles each sweep of a run goes through, tried in turn until one is within the tolerance
(the best is kept). Beyond some hundreds the loft's own approximation strays more again, and
between them its deviation is not monotone: the bundled Dupin cyclide was 7e-8 from its sweep
through 160 circles, 1.7e-6 through 192 and 6.9e-8 through 256, and when the count was doubled
from 24 (to 384) it was refused at 1.7e-6 against a tolerance of 1.1e-6."""


@dataclass(frozen=True)
class Sweep:
    """The faces through the circles, their measured distance to ``f = 0`` and the circles used."""

    faces: list[TopoDS_Face]
    deviation: float
    circles: int


class _Circles:
    """The characteristic circles of one sphere family, evaluated in floats."""

    def __init__(self, family: CanalFamily) -> None:
        if family.circle_center is None or family.circle_radius_squared is None or family.circle_normal is None:
            raise CadGeometryError("the canal surface's characteristic circles are not known")
        names = (family.parameter,)
        self.centre = [rational_function_terms(c, names) for c in family.circle_center]
        self.normal = [rational_function_terms(c, names) for c in family.circle_normal]
        self.radius2 = rational_function_terms(family.circle_radius_squared, names)

    def at(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Centres ``(n, 3)``, unit normals ``(n, 3)`` and radii ``(n,)`` at ``t = tan(θ/2)``,
        evaluated in homogeneous coordinates ``(sin θ/2, cos θ/2)`` (finite at ``t = ∞``)."""
        theta = np.asarray(theta, dtype=np.float64)
        with np.errstate(all="ignore"):
            centre = np.column_stack([_value(f, theta) for f in self.centre])
            normal = np.column_stack([_value(f, theta) for f in self.normal])
            normal = normal / np.linalg.norm(normal, axis=1, keepdims=True)
            radius = np.sqrt(_value(self.radius2, theta))
        return centre, normal, radius


def _value(fraction: tuple[Terms, Terms], theta: np.ndarray) -> np.ndarray:
    """``N(t)/D(t)`` at ``t = tan(θ/2)``, as ``N(T, W)/D(T, W)`` of one degree."""
    numerator, denominator = fraction
    degree = max(m[0] for m, _ in [*numerator, *denominator])
    T, W = np.sin(theta / 2), np.cos(theta / 2)

    def form(terms: Terms) -> np.ndarray:
        return np.asarray(sum(c * T ** m[0] * W ** (degree - m[0]) for m, c in terms))

    return np.asarray(form(numerator) / form(denominator))


def canal_sweep(analysis: Analysis, ball: ClipSphere, goal: float, tolerance: float) -> Sweep | None:
    """The sweep of the first verified family with known circles, within ``goal`` if it can be
    (``None`` for a surface that is no canal surface with such a family)."""
    canal = analysis.canal
    if canal is None or not canal.is_canal:
        return None
    for family in canal.families:
        if not family.verified:
            continue
        try:
            circles = _Circles(family)
        except (CadGeometryError, ExpressionError, ValueError, TypeError):
            continue
        terms = polynomial_terms(analysis.squarefree)
        runs = _runs(circles, ball)
        if not runs:
            raise CadGeometryError("the canal surface has no characteristic circle in the drawn ball")
        best = None
        for sections in SECTIONS:
            faces = [f for low, high, closed in runs for f in _loft(circles, low, high, closed, sections, tolerance)]
            sweep = Sweep(faces, _deviation(faces, terms, ball), sections * len(runs))
            if best is None or sweep.deviation < best.deviation:
                best = sweep
            if sweep.deviation <= goal:
                break
        return best
    return None


def _runs(circles: _Circles, ball: ClipSphere) -> list[tuple[float, float, bool]]:
    """The angle intervals ``θ`` (``t = tan(θ/2)``) where the circles meet the ball, widened by
    one sample so that the sweep reaches past it, and whether one is the whole closed family."""
    theta = np.linspace(-math.pi, math.pi, SAMPLES, endpoint=False)
    centre, _, radius = circles.at(theta)
    meets = np.linalg.norm(centre - np.asarray(ball.center), axis=1) <= ball.radius + radius
    meets &= np.isfinite(radius) & np.all(np.isfinite(centre), axis=1)
    if meets.all():
        return [(-math.pi, math.pi, True)]
    if meets[0] and meets[-1]:  # a run through θ = ±π: start the angles where the circles miss
        shift = int(np.argmin(meets))
        theta, meets = np.roll(theta, -shift), np.roll(meets, -shift)
        theta = np.unwrap(theta)
    step = 2 * math.pi / SAMPLES
    runs = []
    for run in np.split(np.flatnonzero(meets), np.flatnonzero(np.diff(np.flatnonzero(meets)) > 1) + 1):
        if len(run):
            runs.append((float(theta[run[0]] - step), float(theta[run[-1]] + step), False))
    return runs


EXTRA = 4
"""Circles added beyond each end of a sweep and trimmed off again: a loft strays most next to
its first and last sections."""


def _loft(circles: _Circles, low: float, high: float, closed: bool, count: int, tolerance: float) -> list[TopoDS_Face]:
    """The B-spline surface through ``count`` circles at angles evenly between ``low`` and
    ``high`` and :data:`EXTRA` more beyond each end, trimmed to the first and last of the
    ``count`` (a closed family, ``-π`` to ``π``, is swept in two halves that meet there and at
    ``0``: sewing closes it)."""
    if closed:
        return [
            *_loft(circles, low, 0.0, False, count // 2, tolerance),
            *_loft(circles, 0.0, high, False, count // 2, tolerance),
        ]
    step = (high - low) / (count - 1)
    theta = np.linspace(low - EXTRA * step, high + EXTRA * step, count + 2 * EXTRA)
    centres, normals, radii = circles.at(theta)
    loft = BRepOffsetAPI_ThruSections(False, False, tolerance)
    loft.CheckCompatibility(False)
    start, previous, ends = None, None, []
    for k, (centre, normal, radius) in enumerate(zip(centres, normals, radii)):
        if not (np.all(np.isfinite(centre)) and np.all(np.isfinite(normal)) and radius > 0):
            continue
        if previous is not None and normal @ previous < 0:
            normal = -normal  # the circles keep one sense of turning
        previous = normal
        start = _start_direction(normal, start)
        frame = gp_Ax2(gp_Pnt(*centre), gp_Dir(*normal), gp_Dir(*start))
        circle = GC_MakeCircle(frame, float(radius)).Value()
        loft.AddWire(BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(circle).Edge()).Wire())
        if k in (EXTRA, EXTRA + count - 1):
            ends.append(centre + radius * start)
    try:
        loft.Build()
        done = loft.IsDone()
    except Exception as exc:
        if not from_occt(exc):
            raise
        done = False
    if not done or len(ends) != 2:
        raise CadGeometryError("Open CASCADE could not sweep the canal surface's circles")
    return [_trimmed(face, ends, tolerance) for face in faces_of(loft.Shape())]


def _trimmed(face: TopoDS_Face, ends: list[np.ndarray], tolerance: float) -> TopoDS_Face:
    """The loft's face between the sections through the two ``ends`` (points on them)."""
    surface = BRep_Tool.Surface_s(face)
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    at = []
    for point in ends:
        projection = GeomAPI_ProjectPointOnSurf(gp_Pnt(*map(float, point)), surface)
        if projection.NbPoints() == 0:
            raise CadGeometryError("Open CASCADE could not trim the canal surface's sweep")
        at.append(projection.LowerDistanceParameters()[1])
    low, high = sorted(at)
    made = BRepBuilderAPI_MakeFace(surface, u0, u1, max(low, v0), min(high, v1), tolerance)
    if not made.IsDone():
        raise CadGeometryError("Open CASCADE could not trim the canal surface's sweep")
    return made.Face()


def _start_direction(normal: np.ndarray, previous: np.ndarray | None) -> np.ndarray:
    """A unit vector in the circle's plane: the previous one projected into it (no twist)."""
    guess = previous if previous is not None else np.eye(3)[int(np.argmin(np.abs(normal)))]
    direction = guess - (guess @ normal) * normal
    length = float(np.linalg.norm(direction))
    if length < 1e-6:
        guess = np.eye(3)[int(np.argmin(np.abs(normal)))]
        direction = guess - (guess @ normal) * normal
        length = float(np.linalg.norm(direction))
    return np.asarray(direction / length)


def _deviation(faces: list[TopoDS_Face], terms: Terms, ball: ClipSphere) -> float:
    """The largest first-order distance ``|f|/|∇f|`` from points of the faces inside the ball,
    on a grid of each face's ``(u, v)`` box that includes its edges (a sweep strays most at its
    first and last circles)."""
    worst = 0.0
    centre = np.asarray(ball.center)
    for face in faces:
        surface = BRep_Tool.Surface_s(face)
        u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
        grid = np.linspace(0.0, 1.0, 41)
        edge = np.concatenate([grid[:4] / 3, grid, 1 - grid[:4] / 3])
        points = np.array(
            [surface.Value(float(u0 + (u1 - u0) * a), float(v0 + (v1 - v0) * b)).Coord() for a in edge for b in edge]
        )
        points = points[np.linalg.norm(points - centre, axis=1) <= ball.radius]
        if len(points):
            worst = max(worst, float(np.max(surface_distance(terms, points))))
    return worst
