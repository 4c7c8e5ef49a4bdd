"""Open CASCADE faces of what :mod:`.geometry` worked out (docs/math.md §11).

A surface of revolution is ``Geom_SurfaceOfRevolution`` about the exact axis (``gp_Ax1``) of a
profile B-spline in a meridian half-plane, one face per profile arc; the analytic kinds are
Open CASCADE's own surfaces (``Geom_Plane``, ``Geom_SphericalSurface``, ``Geom_CylindricalSurface``,
``Geom_ConicalSurface``, ``Geom_ToroidalSurface``); a profile with no exact rational form is
interpolated (``GeomAPI_Interpolate``) at points on it, refined where the distance measured on
the curve afterwards is too large.
A parameterization becomes a rational B-spline patch (``Geom_BSplineSurface``). OCP is imported
with this module, which is loaded only when a CAD file is written.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from OCP.Bnd import Bnd_Box
from OCP.BRep import BRep_Builder
from OCP.BRepAlgoAPI import BRepAlgoAPI_Common
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepBuilderAPI import (
    BRepBuilderAPI_MakeEdge,
    BRepBuilderAPI_MakeFace,
    BRepBuilderAPI_MakeWire,
    BRepBuilderAPI_NurbsConvert,
)
from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeSphere
from OCP.GC import GC_MakeCircle
from OCP.Geom import (
    Geom_BSplineCurve,
    Geom_BSplineSurface,
    Geom_ConicalSurface,
    Geom_CylindricalSurface,
    Geom_Plane,
    Geom_SphericalSurface,
    Geom_SurfaceOfRevolution,
    Geom_ToroidalSurface,
)
from OCP.GeomAPI import GeomAPI_Interpolate
from OCP.gp import gp_Ax1, gp_Ax2, gp_Ax3, gp_Dir, gp_Pnt
from OCP.OCP.collections import (
    Array1_double,
    Array1_gp_Pnt,
    Array1_int,
    Array2_double,
    Array2_gp_Pnt,
    HArray1_gp_Pnt,
)
from OCP.ShapeUpgrade import ShapeUpgrade_ShapeDivideClosed
from OCP.TopAbs import TopAbs_FACE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Face, TopoDS_Shape, TopoDS_Shell

from sorgui.render import ClipBox, ClipSphere

from .geometry import Analytic, CadGeometryError, Frame, RationalCurve
from .patch import BezierPatch

TOLERANCE = 1e-7
"""The tolerance (length units) Open CASCADE builds edges and faces with."""


Vector = Sequence[float] | np.ndarray


def _point(p: Vector) -> gp_Pnt:
    return gp_Pnt(float(p[0]), float(p[1]), float(p[2]))


def _dir(d: Vector) -> gp_Dir:
    return gp_Dir(float(d[0]), float(d[1]), float(d[2]))


def _reals(values: Sequence[float] | np.ndarray) -> Array1_double:
    out = Array1_double(1, len(values))
    for k, v in enumerate(values, start=1):
        out.SetValue(k, float(v))
    return out


def _integers(values: Sequence[int]) -> Array1_int:
    out = Array1_int(1, len(values))
    for k, v in enumerate(values, start=1):
        out.SetValue(k, int(v))
    return out


def _bezier_knots(arcs: int, degree: int) -> tuple[Array1_double, Array1_int]:
    """Knots ``0 … arcs`` with end multiplicity ``degree + 1`` and inner ones ``degree``."""
    return _reals(range(arcs + 1)), _integers([degree + 1] + [degree] * (arcs - 1) + [degree + 1])


def bspline_curve(curve: RationalCurve) -> Geom_BSplineCurve:
    """The rational B-spline of ``curve`` (its Bézier arcs joined with ``C⁰`` knots)."""
    poles = Array1_gp_Pnt(1, len(curve.poles))
    for k, p in enumerate(curve.poles, start=1):
        poles.SetValue(k, _point(p))
    knots, mults = _bezier_knots(curve.arcs, curve.degree)
    return Geom_BSplineCurve(poles, _reals(curve.weights), knots, mults, curve.degree)


def revolution_faces(frame: Frame, curves: Sequence[Geom_BSplineCurve]) -> list[TopoDS_Face]:
    """One face per profile curve, turned a full turn about the axis."""
    axis = gp_Ax1(_point(frame.point), _dir(frame.direction))
    faces = []
    for curve in curves:
        surface = Geom_SurfaceOfRevolution(curve, axis)
        maker = BRepBuilderAPI_MakeFace(
            surface, 0.0, 2 * math.pi, curve.FirstParameter(), curve.LastParameter(), TOLERANCE
        )
        faces.append(_face(maker))
    return faces


def _face(maker: BRepBuilderAPI_MakeFace) -> TopoDS_Face:
    if not maker.IsDone():
        raise CadGeometryError(f"Open CASCADE could not build a face ({maker.Error()})")
    return maker.Face()


def analytic_faces(spec: Analytic) -> list[TopoDS_Face]:
    """The faces of an analytic surface: whole spheres and tori, a cylinder between two circles,
    a cone's two nappes as two faces meeting at the apex, a plane as its disk in the ball."""
    frame = gp_Ax3(_point(spec.origin), _dir(spec.direction))
    low, high = spec.extent
    if spec.kind == "sphere":
        return [_face(BRepBuilderAPI_MakeFace(Geom_SphericalSurface(frame, spec.radius), TOLERANCE))]
    if spec.kind == "torus":
        torus = Geom_ToroidalSurface(frame, spec.radius, spec.minor_radius)
        return [_face(BRepBuilderAPI_MakeFace(torus, TOLERANCE))]
    if spec.kind == "cylinder":
        cylinder = Geom_CylindricalSurface(frame, spec.radius)
        return [_face(BRepBuilderAPI_MakeFace(cylinder, 0.0, 2 * math.pi, low, high, TOLERANCE))]
    if spec.kind == "cone":
        cone = Geom_ConicalSurface(frame, spec.semi_angle, 0.0)
        ranges = [(a, b) for a, b in ((low, min(high, 0.0)), (max(low, 0.0), high)) if b - a > TOLERANCE]
        return [_face(BRepBuilderAPI_MakeFace(cone, 0.0, 2 * math.pi, a, b, TOLERANCE)) for a, b in ranges]
    if spec.kind == "plane":
        circle = GC_MakeCircle(gp_Ax2(_point(spec.origin), _dir(spec.direction)), high).Value()
        wire = BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(circle).Edge()).Wire()
        return [_face(BRepBuilderAPI_MakeFace(Geom_Plane(frame), wire, True))]
    raise CadGeometryError(f"no analytic surface of kind {spec.kind}")


@dataclass(frozen=True)
class Fit:
    """A fitted profile curve, the largest distance measured from it to the profile, and that
    distance on each span between two consecutive points it interpolates."""

    curve: Geom_BSplineCurve
    deviation: float
    spans: np.ndarray


SAMPLES = 10
"""Points per span at which a fitted curve's distance to the profile is measured."""


def fitted_curve(points: np.ndarray, distance: Callable[[np.ndarray], np.ndarray]) -> Fit:
    """The cubic ``C²`` B-spline through ``points`` (3D, distinct, ordered along one profile
    branch; ``GeomAPI_Interpolate``, chord-length parameters), with its distance to the profile
    measured afterwards by ``distance`` at :data:`SAMPLES` points of every span."""
    array = HArray1_gp_Pnt(1, len(points))
    for k, p in enumerate(points, start=1):
        array.SetValue(k, _point(p))
    interpolation = GeomAPI_Interpolate(array, False, 0.0)
    interpolation.Perform()
    if not interpolation.IsDone():
        raise CadGeometryError("Open CASCADE could not fit a B-spline to the profile")
    curve = interpolation.Curve()
    knots = np.array([curve.Knot(k) for k in range(1, curve.NbKnots() + 1)])
    steps = np.arange(1, SAMPLES + 1) / (SAMPLES + 1)
    samples = (knots[:-1, None] + np.diff(knots)[:, None] * steps).ravel()
    xyz = np.array([_xyz(curve.Value(float(u))) for u in samples])
    spans = np.max(distance(xyz).reshape(len(knots) - 1, SAMPLES), axis=1)
    return Fit(curve, float(spans.max(initial=0.0)), spans)


def _xyz(p: gp_Pnt) -> tuple[float, float, float]:
    return (p.X(), p.Y(), p.Z())


def patch_face(patch: BezierPatch) -> TopoDS_Face:
    """The face of one rational Bézier patch (a ``Geom_BSplineSurface`` without inner knots)."""
    m, n = patch.weights.shape[0] - 1, patch.weights.shape[1] - 1
    poles = Array2_gp_Pnt(1, m + 1, 1, n + 1)
    weights = Array2_double(1, m + 1, 1, n + 1)
    for i in range(m + 1):
        for j in range(n + 1):
            poles.SetValue(i + 1, j + 1, _point(patch.poles[i, j]))
            weights.SetValue(i + 1, j + 1, float(patch.weights[i, j]))
    uknots, umults = _bezier_knots(1, m)
    vknots, vmults = _bezier_knots(1, n)
    surface = Geom_BSplineSurface(poles, weights, uknots, vknots, umults, vmults, m, n)
    return _face(BRepBuilderAPI_MakeFace(surface, TOLERANCE))


def shell(faces: Sequence[TopoDS_Face]) -> TopoDS_Shape:
    """The faces in one open shell, one product of a STEP file (a compound would make an
    assembly of one product per face)."""
    builder = BRep_Builder()
    shape = TopoDS_Shell()
    builder.MakeShell(shape)
    for face in faces:
        builder.Add(shape, face)
    return shape


def cut_to(shape: TopoDS_Shape, region: ClipSphere | ClipBox) -> TopoDS_Shape:
    """The part of ``shape`` inside ``region``: Open CASCADE's Boolean common with the ball or
    box as a solid. Each face keeps its surface (a torus stays a torus), trimmed by the curves
    where it meets the region's boundary. A cut face still closed along its seam is split in
    two: read back from STEP, such a face's boundary is not closed in its (u, v) plane."""
    if isinstance(region, ClipSphere):
        solid = BRepPrimAPI_MakeSphere(_point(region.center), region.radius).Shape()
    else:
        low, high = region.bounds[0::2], region.bounds[1::2]
        solid = BRepPrimAPI_MakeBox(_point(low), _point(high)).Shape()
    common = BRepAlgoAPI_Common(shape, solid)
    if not common.IsDone():
        raise CadGeometryError("Open CASCADE could not cut the faces to the region")
    halves = ShapeUpgrade_ShapeDivideClosed(common.Shape())
    halves.SetNbSplitPoints(1)
    halves.Perform()
    return shell(faces_of(halves.Result()))


def as_nurbs(shape: TopoDS_Shape) -> TopoDS_Shape:
    """``shape`` with every surface converted to a rational B-spline surface (the same faces)."""
    return BRepBuilderAPI_NurbsConvert(shape, True).Shape()


def within(shape: TopoDS_Shape, box: ClipBox) -> bool:
    """Whether every face of ``shape`` lies in ``box`` (to a millionth of its size): the check
    of a Boolean cut, which Open CASCADE gets wrong for some revolved B-spline profiles."""
    low, high = np.array(box.bounds[0::2]), np.array(box.bounds[1::2])
    slack = 1e-6 * float(np.max(high - low)) + TOLERANCE
    for face in faces_of(shape):
        bounds = Bnd_Box()
        BRepBndLib.AddOptimal_s(face, bounds, False, False)
        if np.any(np.array(bounds.CornerMin().Coord()) < low - slack):
            return False
        if np.any(np.array(bounds.CornerMax().Coord()) > high + slack):
            return False
    return True


def faces_of(shape: TopoDS_Shape) -> list[TopoDS_Face]:
    """The faces of ``shape``, in the order Open CASCADE explores them."""
    found = []
    explorer = TopExp_Explorer(shape, TopAbs_FACE)
    while explorer.More():
        found.append(TopoDS.Face(explorer.Current()))
        explorer.Next()
    return found
