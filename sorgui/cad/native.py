"""The native surface of a recognised face, and how far it is from the face, both ways
(docs/math.md §12).

A fit of :mod:`sorgui.engine.rounded.line_complex` becomes the surface a CAD kernel keeps: a
``Geom_Plane``, ``Geom_SphericalSurface``, ``Geom_CylindricalSurface``, ``Geom_ConicalSurface``
or ``Geom_ToroidalSurface`` in a frame whose ``x`` direction points at the face's seam (so that
a closed face keeps its seam), a ``Geom_SurfaceOfRevolution`` about the fitted axis of a profile
curve, a ``Geom_SurfaceOfLinearExtrusion`` of a section curve, or the ruled B-spline surface
joining a cone's apex to a curve. The profile, section or directrix is the face's own parameter
line across the direction along which the reduced coordinates (``line_complex.reduced``) stay
put — the iso-curve of a revolved B-spline is its meridian, exactly — or, when no parameter
direction is such a fibre, a B-spline fitted to the reduced points in order.

The deviation is measured both ways: from the face to the surface (every sample projected onto
it, ``ShapeAnalysis_Surface``), and from the surface to the face (a grid over the part of the
surface's parameter box that the face covers, each point projected back onto the face's surface
and kept when it lands inside the face's wires).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve
from OCP.Geom import (
    Geom_BSplineSurface,
    Geom_ConicalSurface,
    Geom_Curve,
    Geom_CylindricalSurface,
    Geom_Plane,
    Geom_SphericalSurface,
    Geom_Surface,
    Geom_SurfaceOfLinearExtrusion,
    Geom_SurfaceOfRevolution,
    Geom_ToroidalSurface,
)
from OCP.GeomAbs import GeomAbs_Shape
from OCP.GeomAPI import GeomAPI_PointsToBSpline
from OCP.GeomConvert import GeomConvert
from OCP.GeomLProp import GeomLProp_SLProps
from OCP.gp import gp_Ax1, gp_Ax3, gp_Dir, gp_Pnt, gp_Pnt2d
from OCP.IntTools import IntTools_FClass2d
from OCP.OCP.collections import Array1_double, Array1_gp_Pnt, Array2_double, Array2_gp_Pnt
from OCP.ShapeAnalysis import ShapeAnalysis_Surface
from OCP.TopAbs import TopAbs_EDGE, TopAbs_State
from OCP.TopExp import TopExp, TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Edge, TopoDS_Face

from sorgui.engine.rounded import line_complex as lc
from sorgui.engine.rounded.line_complex import SurfaceFit

from .failures import OCCT_ERRORS
from .sampling import FaceSamples

BACK_GRID = 10
"""Grid lines in each direction of the surface's box when measuring from the surface to the face."""
FIBRE_RATIO = 0.05
"""A parameter direction is a fibre when the reduced points move along it by less than this
fraction of what they move along the other."""
PROFILE_POINTS = 60
"""Points a profile fitted to unordered samples goes through."""


@dataclass(frozen=True)
class Native:
    """A native surface of a face and its measured distance from it, each way."""

    surface: Geom_Surface
    to_surface: float
    to_face: float

    @property
    def deviation(self) -> float:
        return max(self.to_surface, self.to_face)


def _pnt(v: np.ndarray | tuple[float, ...]) -> gp_Pnt:
    return gp_Pnt(float(v[0]), float(v[1]), float(v[2]))


def _dir(v: np.ndarray | tuple[float, ...]) -> gp_Dir:
    return gp_Dir(float(v[0]), float(v[1]), float(v[2]))


def _xyz(p: gp_Pnt) -> np.ndarray:
    return np.array([p.X(), p.Y(), p.Z()])


# --- the surfaces ------------------------------------------------------------------------------


def analytic_surface(fit: SurfaceFit, face: TopoDS_Face) -> Geom_Surface:
    """The plane, sphere, cylinder, cone or torus of ``fit``, its frame's ``x`` towards the seam."""
    if fit.kind == lc.PLANE:
        assert fit.axis is not None
        return Geom_Plane(gp_Ax3(_pnt(fit.axis.point), _dir(fit.axis.direction)))
    if fit.kind == lc.SPHERE:
        assert fit.center is not None and fit.radius is not None
        centre = np.array(fit.center)
        pole = _degenerate_point(face)
        axis = pole - centre if pole is not None and np.linalg.norm(pole - centre) > 0 else np.array([0.0, 0.0, 1.0])
        return Geom_SphericalSurface(_frame(centre, axis, face), fit.radius)
    assert fit.axis is not None
    point, direction = np.array(fit.axis.point), np.array(fit.axis.direction)
    if fit.kind == lc.CYLINDER:
        assert fit.radius is not None
        return Geom_CylindricalSurface(_frame(point, direction, face), fit.radius)
    if fit.kind == lc.CONE:
        assert fit.center is not None and fit.half_angle is not None
        apex = np.array(fit.center)
        return Geom_ConicalSurface(_frame(apex, direction, face), fit.half_angle, 0.0)
    assert fit.kind == lc.TORUS and fit.center is not None and fit.radius is not None
    assert fit.minor_radius is not None
    return Geom_ToroidalSurface(_frame(np.array(fit.center), direction, face), fit.radius, fit.minor_radius)


def _frame(origin: np.ndarray, direction: np.ndarray, face: TopoDS_Face) -> gp_Ax3:
    """The frame at ``origin`` along ``direction`` whose ``x`` points at the face's seam (any
    perpendicular direction when it has none)."""
    d = direction / np.linalg.norm(direction)
    seam = _seam_point(face)
    x = None if seam is None else (seam - origin) - ((seam - origin) @ d) * d
    if x is None or np.linalg.norm(x) < 1e-9 * (1.0 + np.linalg.norm(seam - origin)):
        x = np.cross(d, np.eye(3)[int(np.argmin(np.abs(d)))])
    return gp_Ax3(_pnt(origin), _dir(d), _dir(x))


def _seam_point(face: TopoDS_Face) -> np.ndarray | None:
    """The middle of an edge the face meets on both sides (its seam), if it has one."""
    for edge in edges_of(face):
        if BRep_Tool.IsClosed_s(edge, face) and not BRep_Tool.Degenerated_s(edge):
            curve = BRepAdaptor_Curve(edge)
            return _xyz(curve.Value(0.5 * (curve.FirstParameter() + curve.LastParameter())))
    return None


def _degenerate_point(face: TopoDS_Face) -> np.ndarray | None:
    """The point of a degenerate edge of the face (a sphere's pole), if it has one."""
    for edge in edges_of(face):
        if BRep_Tool.Degenerated_s(edge):
            return _xyz(BRep_Tool.Pnt_s(TopExp.FirstVertex_s(edge)))
    return None


def edges_of(face: TopoDS_Face) -> list[TopoDS_Edge]:
    """The edges of ``face``, as Open CASCADE explores them."""
    found = []
    explorer = TopExp_Explorer(face, TopAbs_EDGE)
    while explorer.More():
        found.append(TopoDS.Edge(explorer.Current()))
        explorer.Next()
    return found


def swept_surface(fit: SurfaceFit, face: TopoDS_Face, samples: FaceSamples) -> Geom_Surface | None:
    """The surface of revolution, extrusion or cone of ``fit`` over the face's profile curve
    (``None`` when no profile can be had)."""
    curve = profile_curve(fit, face, samples)
    if curve is None:
        return None
    if fit.kind == lc.REVOLUTION:
        assert fit.axis is not None
        axis = gp_Ax1(_pnt(fit.axis.point), _dir(fit.axis.direction))
        return Geom_SurfaceOfRevolution(_seam_away(curve, axis, fit, samples), axis)
    if fit.kind == lc.EXTRUSION:
        assert fit.direction is not None
        return Geom_SurfaceOfLinearExtrusion(curve, _dir(fit.direction))
    assert fit.kind == lc.CONE_OVER_CURVE and fit.center is not None
    return _ruled_from(np.array(fit.center), curve)


def _seam_away(curve: Geom_Curve, axis: gp_Ax1, fit: SurfaceFit, samples: FaceSamples) -> Geom_Curve:
    """``curve`` turned about the axis to the side opposite the face, when the face does not go
    all the way round: the surface's seam (angle 0) then stays off the face, whose curves in
    ``(u, v)`` do not cross it. A face all the way round keeps its own seam."""
    assert fit.axis is not None
    point, d = np.array(fit.axis.point), np.array(fit.axis.direction)
    e1, e2 = lc.across(d)
    angles = np.sort(np.mod(np.arctan2((samples.points - point) @ e2, (samples.points - point) @ e1), 2 * math.pi))
    gaps = np.diff(np.concatenate([angles, [angles[0] + 2 * math.pi]]))
    k = int(np.argmax(gaps))
    if gaps[k] < math.pi / 8:
        return curve
    middle = angles[k] + gaps[k] / 2
    at = _xyz(curve.Value(0.5 * (curve.FirstParameter() + curve.LastParameter()))) - point
    now = math.atan2(at @ e2, at @ e1)
    turned: Geom_Curve = curve.Rotated(axis, middle - now)
    return turned


def profile_curve(fit: SurfaceFit, face: TopoDS_Face, samples: FaceSamples) -> Geom_Curve | None:
    """The face's parameter line across its fibres (the direction along which the reduced
    points stay put), else (not for a cone over a curve) a B-spline through the reduced points in
    order."""
    q = lc.reduced(fit, samples.points)
    along_u, along_v = _spread(q, samples.index, 0), _spread(q, samples.index, 1)
    surface = BRep_Tool.Surface_s(face)
    u0, u1, v0, v1 = samples.box
    try:
        if along_u <= FIBRE_RATIO * along_v:
            return surface.UIso(_fibre_parameter(fit, surface, samples, 0, u0, u1))
        if along_v <= FIBRE_RATIO * along_u:
            return surface.VIso(_fibre_parameter(fit, surface, samples, 1, v0, v1))
    except OCCT_ERRORS:
        return None
    if fit.kind == lc.CONE_OVER_CURVE:
        return None  # its directrix is a parameter line of the face's, or there is none
    return _fitted_profile(fit, q)


def _spread(q: np.ndarray, index: np.ndarray, axis: int) -> float:
    """How far the reduced points move along the grid lines on which only parameter ``axis``
    changes: the largest distance of a point from the mean of its line."""
    line = index[:, 1 - axis]
    count = np.bincount(line)
    means = np.column_stack([np.bincount(line, q[:, k]) for k in range(2)]) / np.maximum(count, 1)[:, None]
    distance = np.linalg.norm(q - means[line], axis=1)
    return float(distance[count[line] > 1].max(initial=0.0))


def _fibre_parameter(
    fit: SurfaceFit, surface: Geom_Surface, samples: FaceSamples, axis: int, low: float, high: float
) -> float:
    """Where along the fibre direction the profile is taken: at the seam of a face closed that
    way (so that its seam is the profile's), at the end farthest from a cone's apex (the ruled
    surface then reaches every sample), else in the middle."""
    closed = surface.IsUPeriodic() if axis == 0 else surface.IsVPeriodic()
    period = (surface.UPeriod() if axis == 0 else surface.VPeriod()) if closed else 0.0
    if closed and abs((high - low) - period) < 1e-9 * max(1.0, period):
        return low
    if fit.kind == lc.CONE_OVER_CURVE and fit.center is not None:
        near_low = samples.uv[:, axis] <= 0.5 * (low + high)
        distance = np.linalg.norm(samples.points - np.array(fit.center), axis=1)
        if near_low.any() and (~near_low).any():
            return low if distance[near_low].mean() > distance[~near_low].mean() else high
    return 0.5 * (low + high)


def _fitted_profile(fit: SurfaceFit, q: np.ndarray) -> Geom_Curve | None:
    """A B-spline through :data:`PROFILE_POINTS` of the reduced points, ordered along their
    principal direction (a profile that is a graph over it), placed back in space."""
    centre = q.mean(axis=0)
    _, _, vt = np.linalg.svd(q - centre, full_matrices=False)
    s = (q - centre) @ vt[0]
    targets = np.linspace(s.min(), s.max(), PROFILE_POINTS)
    chosen = np.unique([int(np.argmin(np.abs(s - t))) for t in targets])
    chosen = chosen[np.argsort(s[chosen])]
    if len(chosen) < 4:
        return None
    points = _placed(fit, q[chosen])
    array = Array1_gp_Pnt(1, len(points))
    for k, p in enumerate(points, start=1):
        array.SetValue(k, _pnt(p))
    try:
        approximation = GeomAPI_PointsToBSpline(array, 3, 8, GeomAbs_Shape.GeomAbs_C2, 1e-9)
    except OCCT_ERRORS:
        return None
    return approximation.Curve() if approximation.IsDone() else None


def _placed(fit: SurfaceFit, q: np.ndarray) -> np.ndarray:
    """Reduced points back in space: in a meridian half-plane of the axis, in the plane through
    the origin across an extrusion's direction."""
    if fit.kind == lc.REVOLUTION:
        assert fit.axis is not None
        point, d = np.array(fit.axis.point), np.array(fit.axis.direction)
        e1, _ = lc.across(d)
        meridian: np.ndarray = point + q[:, :1] * d + q[:, 1:] * e1
        return meridian
    assert fit.kind == lc.EXTRUSION and fit.direction is not None  # a cone's directrix is the face's
    e1, e2 = lc.across(np.array(fit.direction))
    return q[:, :1] * e1 + q[:, 1:] * e2


def _ruled_from(apex: np.ndarray, curve: Geom_Curve) -> Geom_Surface:
    """The rational B-spline surface ``apex + s·(C(t) − apex)``, ``0 ≤ s ≤ 1``: degree 1 in ``s``,
    one row of poles at the apex, the other the poles of ``C``, both rows with ``C``'s weights."""
    spline = GeomConvert.CurveToBSplineCurve_s(curve)
    n = spline.NbPoles()
    poles, weights = Array2_gp_Pnt(1, 2, 1, n), Array2_double(1, 2, 1, n)
    for k in range(1, n + 1):
        poles.SetValue(1, k, _pnt(apex))
        poles.SetValue(2, k, spline.Pole(k))
        weights.SetValue(1, k, spline.Weight(k))
        weights.SetValue(2, k, spline.Weight(k))
    knots = Array1_double(1, spline.NbKnots())
    mults = spline.Multiplicities()
    for k in range(1, spline.NbKnots() + 1):
        knots.SetValue(k, spline.Knot(k))
    from OCP.OCP.collections import Array1_int

    ends, twos = Array1_double(1, 2), Array1_int(1, 2)
    ends.SetValue(1, 0.0)
    ends.SetValue(2, 1.0)
    twos.SetValue(1, 2)
    twos.SetValue(2, 2)
    return Geom_BSplineSurface(poles, weights, ends, knots, twos, mults, 1, spline.Degree(), False, spline.IsPeriodic())


# --- the deviation, both ways ---------------------------------------------------------------------


def measured(
    surface: Geom_Surface, face: TopoDS_Face, samples: FaceSamples, tolerance: float, to_surface: float | None = None
) -> Native:
    """``surface`` with its distance from the face's samples and from the face (see the module).
    ``to_surface``: the first, known already (in closed form); then only the samples on the rim
    of the face's grid are projected, for the parameter box the face covers."""
    onto = _Projection(surface, tolerance)
    chosen = np.arange(len(samples.points)) if to_surface is None else _rim(samples.index)
    feet, gaps = [], []
    for p in samples.points[chosen]:
        uv = onto.foot(_pnt(p))
        feet.append((uv.X(), uv.Y()))
        gaps.append(onto.gap())
    forward = max(gaps, default=0.0) if to_surface is None else max(to_surface, max(gaps, default=0.0))
    return Native(surface, forward, _back(surface, np.array(feet), face, samples, tolerance))


class _Projection:
    """Points projected onto ``surface`` one after another (ShapeAnalysis_Surface): each from
    the previous foot by Newton's method, which is many times faster than a search of the whole
    surface when the points follow a grid; the whole search where the foot found that way is
    farther than ``tolerance`` (a false foot would only make the distance larger)."""

    def __init__(self, surface: Geom_Surface, tolerance: float) -> None:
        self.onto = ShapeAnalysis_Surface(surface)
        self.precision, self.tolerance = 0.01 * tolerance, tolerance
        self.last: gp_Pnt2d | None = None

    def foot(self, point: gp_Pnt) -> gp_Pnt2d:
        """The parameters of the foot of ``point`` on the surface."""
        if self.last is None:
            self.last = self.onto.ValueOfUV(point, self.precision)
        else:
            self.last = self.onto.NextValueOfUV(self.last, point, self.precision, self.tolerance)
        return self.last

    def gap(self) -> float:
        """The distance from the last point to its foot."""
        return float(self.onto.Gap())


def _rim(index: np.ndarray) -> np.ndarray:
    """The samples first and last on each grid line (both ways): the rim of the face's grid."""
    chosen: set[int] = set()
    for axis in (0, 1):
        line, along = index[:, axis], index[:, 1 - axis]
        for value in np.unique(line):
            members = np.nonzero(line == value)[0]
            chosen.update((int(members[np.argmin(along[members])]), int(members[np.argmax(along[members])])))
    return np.array(sorted(chosen))


def _back(surface: Geom_Surface, feet: np.ndarray, face: TopoDS_Face, samples: FaceSamples, tolerance: float) -> float:
    """The largest distance from the face of the surface's points over the box of the feet."""
    us = _covering(feet[:, 0], surface.UPeriod() if surface.IsUPeriodic() else None)
    vs = _covering(feet[:, 1], surface.VPeriod() if surface.IsVPeriodic() else None)
    own = BRep_Tool.Surface_s(face)
    onto = _Projection(own, tolerance)
    classifier = IntTools_FClass2d(face, max(BRep_Tool.Tolerance_s(face), 1e-9))
    u0, u1, v0, v1 = samples.box
    uperiod = own.UPeriod() if own.IsUPeriodic() else None
    vperiod = own.VPeriod() if own.IsVPeriodic() else None
    props = GeomLProp_SLProps(own, 1, 1e-12)
    worst = 0.0
    for u in us:
        for v in vs:
            q = surface.Value(float(u), float(v))
            uv = onto.foot(q)
            gap = onto.gap()
            inside = gp_Pnt2d(_into(uv.X(), u0, uperiod), _into(uv.Y(), v0, vperiod))
            if classifier.Perform(inside) != TopAbs_State.TopAbs_IN:
                continue
            if gap > tolerance and not _orthogonal(props, uv.X(), uv.Y(), _xyz(q)):
                continue  # the nearest point is on the rim of the face's surface: q is beyond it
            worst = max(worst, gap)
    return worst


def _orthogonal(props: GeomLProp_SLProps, u: float, v: float, q: np.ndarray) -> bool:
    """Whether ``q`` lies on the normal line of the surface at ``(u, v)`` (to a thousandth of its
    distance): then that point is its foot, not a point on the surface's rim."""
    props.SetParameters(u, v)
    if not props.IsNormalDefined():
        return True
    foot, normal = _xyz(props.Value()), props.Normal()
    w = q - foot
    return bool(np.linalg.norm(np.cross(w, [normal.X(), normal.Y(), normal.Z()])) <= 1e-3 * np.linalg.norm(w))


def _covering(values: np.ndarray, period: float | None) -> np.ndarray:
    """:data:`BACK_GRID` values between those of ``values`` at the midpoints of equal steps (on
    a periodic parameter, the shortest arc that holds them all)."""
    low, high = float(values.min()), float(values.max())
    if period is not None and len(values) > 1:
        ordered = np.sort(np.mod(values, period))
        gaps = np.diff(np.concatenate([ordered, [ordered[0] + period]]))
        k = int(np.argmax(gaps))
        low = float(ordered[(k + 1) % len(ordered)])
        high = low + period - float(gaps[k])
    steps = (np.arange(BACK_GRID) + 0.5) / BACK_GRID
    return low + (high - low) * steps


def _into(value: float, start: float, period: float | None) -> float:
    """``value`` moved by whole periods into ``[start, start + period)``."""
    if period is None:
        return value
    return start + math.fmod(math.fmod(value - start, period) + period, period)
