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
from collections.abc import Sequence

import numpy as np
from OCP.Bnd import Bnd_Box
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepAlgoAPI import BRepAlgoAPI_Common
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepBuilderAPI import (
    BRepBuilderAPI_MakeEdge,
    BRepBuilderAPI_MakeFace,
    BRepBuilderAPI_MakeWire,
    BRepBuilderAPI_NurbsConvert,
    BRepBuilderAPI_Sewing,
    BRepBuilderAPI_Transform,
)
from OCP.BRepGProp import BRepGProp
from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeSphere
from OCP.BRepTools import BRepTools
from OCP.GC import GC_MakeCircle
from OCP.Geom import (
    Geom_BSplineCurve,
    Geom_BSplineSurface,
    Geom_ConicalSurface,
    Geom_CylindricalSurface,
    Geom_Plane,
    Geom_SphericalSurface,
    Geom_SurfaceOfLinearExtrusion,
    Geom_SurfaceOfRevolution,
    Geom_ToroidalSurface,
)
from OCP.gp import gp_Ax1, gp_Ax2, gp_Ax3, gp_Dir, gp_Pnt, gp_Trsf
from OCP.GProp import GProp_GProps
from OCP.OCP.collections import (
    Array1_double,
    Array1_gp_Pnt,
    Array1_int,
    Array2_double,
    Array2_gp_Pnt,
)
from OCP.ShapeUpgrade import ShapeUpgrade_ShapeDivideClosed
from OCP.TopoDS import TopoDS, TopoDS_Compound, TopoDS_Face, TopoDS_Shape

from sorgui.render import ClipBox, ClipSphere

from .conical import Extrusion, Ruled
from .failures import OCCT_ERRORS
from .geometry import Analytic, CadGeometryError, Frame, RationalCurve
from .patch import BezierPatch
from .reading import faces_of

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


def revolution_faces(frame: Frame, curves: Sequence[Geom_BSplineCurve], tolerance: float) -> list[TopoDS_Face]:
    """One face per profile curve, turned a full turn about the axis (edges of ``tolerance``)."""
    axis = gp_Ax1(_point(frame.point), _dir(frame.direction))
    faces = []
    for curve in curves:
        surface = Geom_SurfaceOfRevolution(curve, axis)
        low, high = curve.FirstParameter(), curve.LastParameter()
        try:
            faces.append(_face(BRepBuilderAPI_MakeFace(surface, 0.0, 2 * math.pi, low, high, tolerance)))
        except OCCT_ERRORS:
            faces.append(_turned_about_z(curve, frame, tolerance))
    return faces


def _turned_about_z(curve: Geom_BSplineCurve, frame: Frame, tolerance: float) -> TopoDS_Face:
    """The face of ``curve`` turned about the axis, made in the frame whose z-axis is the axis
    and moved back: there an end pole within ``POLE_GAP`` of the axis is put on it exactly. A
    pole 3e-16 from the axis, where Open CASCADE's normal of the surface is a cross product of
    rounding errors, raised "gp_Dir::CrossCross() - result vector has zero norm"."""
    placed = gp_Trsf()
    placed.SetTransformation(gp_Ax3(_point(frame.point), _dir(frame.direction)))
    local = curve.Copy()
    local.Transform(placed)
    for index in (1, local.NbPoles()):
        pole = local.Pole(index)
        if math.hypot(pole.X(), pole.Y()) <= POLE_GAP * max(1.0, abs(pole.Z())):
            local.SetPole(index, gp_Pnt(0.0, 0.0, pole.Z()))
    surface = Geom_SurfaceOfRevolution(local, gp_Ax1(gp_Pnt(0.0, 0.0, 0.0), gp_Dir(0.0, 0.0, 1.0)))
    face = _face(
        BRepBuilderAPI_MakeFace(surface, 0.0, 2 * math.pi, local.FirstParameter(), local.LastParameter(), tolerance)
    )
    return TopoDS.Face(BRepBuilderAPI_Transform(face, placed.Inverted(), True).Shape())


POLE_GAP = 1e-12
"""How far (relative to its height along the axis, at least 1) an end of a turned profile may be
from the axis and be put on it (:func:`_turned_about_z`)."""


def extrusion_faces(extrusion: Extrusion, tolerance: float) -> list[TopoDS_Face]:
    """A cylinder over a curve: each Bézier arc of its base curve (weights balanced) extruded
    along the direction (``Geom_SurfaceOfLinearExtrusion``) by ``± length``."""
    direction = _dir(extrusion.direction)
    faces = []
    for arc in (a for curve in extrusion.curves for a in curve.bezier_arcs()):
        curve = bspline_curve(arc)
        surface = Geom_SurfaceOfLinearExtrusion(curve, direction)
        low, high = curve.FirstParameter(), curve.LastParameter()
        faces.append(_face(BRepBuilderAPI_MakeFace(surface, low, high, -extrusion.length, extrusion.length, tolerance)))
    return faces


def ruled_faces(ruled: Ruled, tolerance: float) -> list[TopoDS_Face]:
    """A cone over a curve: on each span of its direction curve, the two nappes as Bézier
    surfaces of degree ``(n, 1)`` from the apex (a degenerate edge) to ``apex ± M·b_k``."""
    faces = []
    for points, reach in zip(ruled.spans, ruled.reach):
        for sign in (1.0, -1.0):
            far = ruled.apex + sign * reach * points
            rows = np.stack([np.broadcast_to(ruled.apex, far.shape), far], axis=1)
            faces.append(patch_face(BezierPatch(rows, np.ones(rows.shape[:2])), tolerance))
    return faces


def reversed_face(face: TopoDS_Face) -> TopoDS_Face:
    """The face with its orientation turned (its normal the other way)."""
    return TopoDS.Face(face.Reversed())


def _face(maker: BRepBuilderAPI_MakeFace) -> TopoDS_Face:
    if not maker.IsDone():
        raise CadGeometryError(f"Open CASCADE could not build a face ({maker.Error()})")
    return maker.Face()


def analytic_faces(spec: Analytic, tolerance: float) -> list[TopoDS_Face]:
    """The faces of an analytic surface: whole spheres and tori, a cylinder between two circles,
    a cone's two nappes as two faces meeting at the apex, a plane as its disk in the ball."""
    frame = gp_Ax3(_point(spec.origin), _dir(spec.direction))
    low, high = spec.extent
    if spec.kind == "sphere":
        return [_face(BRepBuilderAPI_MakeFace(Geom_SphericalSurface(frame, spec.radius), tolerance))]
    if spec.kind == "torus":
        torus = Geom_ToroidalSurface(frame, spec.radius, spec.minor_radius)
        return [_face(BRepBuilderAPI_MakeFace(torus, tolerance))]
    if spec.kind == "cylinder":
        cylinder = Geom_CylindricalSurface(frame, spec.radius)
        return [_face(BRepBuilderAPI_MakeFace(cylinder, 0.0, 2 * math.pi, low, high, tolerance))]
    if spec.kind == "cone":
        cone = Geom_ConicalSurface(frame, spec.semi_angle, 0.0)
        ranges = [(a, b) for a, b in ((low, min(high, 0.0)), (max(low, 0.0), high)) if b - a > tolerance]
        return [_face(BRepBuilderAPI_MakeFace(cone, 0.0, 2 * math.pi, a, b, tolerance)) for a, b in ranges]
    if spec.kind == "plane":
        circle = GC_MakeCircle(gp_Ax2(_point(spec.origin), _dir(spec.direction)), high).Value()
        wire = BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(circle).Edge()).Wire()
        return [_face(BRepBuilderAPI_MakeFace(Geom_Plane(frame), wire, True))]
    raise CadGeometryError(f"no analytic surface of kind {spec.kind}")


def patch_face(patch: BezierPatch, tolerance: float) -> TopoDS_Face:
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
    return _face(BRepBuilderAPI_MakeFace(surface, tolerance))


def cut_to(faces: Sequence[TopoDS_Face], region: ClipSphere | ClipBox) -> list[TopoDS_Face]:
    """The parts of ``faces`` inside ``region``: Open CASCADE's Boolean common with the ball as
    a solid, or with the box's six half-spaces one after the other (each a slab beyond the
    faces; the box's edges and corners in one Boolean miss intersections of revolved B-spline
    profiles). Each face keeps its surface (a torus stays a torus), trimmed by the curves where
    it meets the region's boundary. After a ball's cut no face is left closed along a seam
    (read back from STEP, such a face's boundary is not closed in its (u, v) plane); faces cut
    to a box are cut into sectors before (:func:`sectors`; splitting a trimmed face can lose
    its trimming)."""
    if isinstance(region, ClipSphere):
        return _halves(_common(faces, BRepPrimAPI_MakeSphere(_point(region.center), region.radius).Shape(), region))
    low, high = np.array(region.bounds[0::2]), np.array(region.bounds[1::2])
    around = _bounds(faces)
    if around is None:
        return []
    cut = list(faces)
    margin = 0.5 * float(np.max(around[1] - around[0])) + 1e-3 * float(np.max(high - low))
    for axis in range(3):
        for side, plane in ((0, low[axis]), (1, high[axis])):
            corner, far = around[0] - margin, around[1] + margin
            if (side == 0 and plane >= far[axis]) or (side == 1 and plane <= corner[axis]):
                return []  # every face lies outside this plane
            if not corner[axis] < plane < far[axis]:
                continue  # every face lies inside it
            (corner if side == 0 else far)[axis] = plane
            cut = _common(cut, BRepPrimAPI_MakeBox(_point(corner), _point(far)).Shape())
    return cut


def sectors(faces: Sequence[TopoDS_Face], count: int, tolerance: float) -> list[TopoDS_Face]:
    """The faces with each one over a whole period of its ``u``-periodic surface (a surface of
    revolution, a cylinder, a cone, a torus) made again as ``count`` faces over equal parts of
    that period (sewing joins them again); the others are kept. Open CASCADE cuts such parts of
    a revolved B-spline profile by a box's planes where it misses intersections with the whole."""
    out = []
    for face in faces:
        surface = BRep_Tool.Surface_s(face)
        u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
        if count > 1 and surface.IsUPeriodic() and abs(u1 - u0 - surface.UPeriod()) <= 1e-12 * surface.UPeriod():
            cuts = np.linspace(u0, u1, count + 1)
            for a, b in zip(cuts[:-1], cuts[1:]):
                made = _face(BRepBuilderAPI_MakeFace(surface, float(a), float(b), v0, v1, tolerance))
                out.append(reversed_face(made) if face.Orientation() != made.Orientation() else made)
        else:
            out.append(face)
    return out


def _halves(faces: Sequence[TopoDS_Face]) -> list[TopoDS_Face]:
    """The faces, each closed one split in two along its closed direction."""
    if not faces:
        return []
    halves = ShapeUpgrade_ShapeDivideClosed(_compound(faces))
    halves.SetNbSplitPoints(1)
    halves.Perform()
    return faces_of(halves.Result())


def _common(faces: Sequence[TopoDS_Face], solid: TopoDS_Shape, ball: ClipSphere | None = None) -> list[TopoDS_Face]:
    """The parts of the faces inside ``solid``. The faces are sewn first and cut together, so
    that the parts keep the edges they share; a Boolean over many patches, some degenerate next
    to a pole of their map, can lose some, so the faces are also cut one by one, and the
    joint result is taken only where it has the same area. Cut to a ``ball``, a face that
    comes out empty though points of it lie inside is cut in halves (Open CASCADE loses some
    faces of a cylinder through a node of its base curve)."""
    if not faces:
        return []
    apart = []
    for face in faces:
        apart += _face_common(face, solid, ball, 0)
    if len(faces) == 1:
        return apart
    around = _bounds(faces)
    size = float(np.linalg.norm(around[1] - around[0])) if around is not None else 1.0
    sewing = BRepBuilderAPI_Sewing(10 * max(1e-7, 1e-9 * size))
    for face in faces:
        sewing.Add(face)
    sewing.Perform()
    joint = _boolean(sewing.SewedShape(), solid)
    if abs(_area(joint) - _area(apart)) <= 1e-7 * max(_area(apart), 1e-300):
        return joint
    return apart


def _face_common(face: TopoDS_Face, solid: TopoDS_Shape, ball: ClipSphere | None, depth: int) -> list[TopoDS_Face]:
    out = _boolean(face, solid)
    if out or ball is None or depth >= 3 or not _reaches(face, ball):
        return out
    surface = BRep_Tool.Surface_s(face)
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    halves = []
    for a, b in ((u0, (u0 + u1) / 2), ((u0 + u1) / 2, u1)):
        half = _face(BRepBuilderAPI_MakeFace(surface, a, b, v0, v1, BRep_Tool.Tolerance_s(face)))
        halves += _face_common(
            reversed_face(half) if face.Orientation() != half.Orientation() else half, solid, ball, depth + 1
        )
    return halves


def _reaches(face: TopoDS_Face, ball: ClipSphere) -> bool:
    """Whether points of the face's surface over its ``(u, v)`` box lie inside ``ball``."""
    surface = BRep_Tool.Surface_s(face)
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    centre = np.asarray(ball.center)
    for u in np.linspace(u0, u1, 9):
        for v in np.linspace(v0, v1, 9):
            if np.linalg.norm(np.array(surface.Value(float(u), float(v)).Coord()) - centre) < ball.radius:
                return True
    return False


def _boolean(shape: TopoDS_Shape, solid: TopoDS_Shape) -> list[TopoDS_Face]:
    common = BRepAlgoAPI_Common(shape, solid)
    if not common.IsDone():
        raise CadGeometryError("Open CASCADE could not cut the faces to the region")
    return faces_of(common.Shape())


def _area(faces: Sequence[TopoDS_Face]) -> float:
    total = 0.0
    for face in faces:
        props = GProp_GProps()
        BRepGProp.SurfaceProperties_s(face, props, 1e-6)
        total += props.Mass()
    return total


def _bounds(faces: Sequence[TopoDS_Face]) -> tuple[np.ndarray, np.ndarray] | None:
    box = Bnd_Box()
    for face in faces:
        BRepBndLib.AddOptimal_s(face, box, False, False)
    if box.IsVoid():
        return None
    return np.array(box.CornerMin().Coord()), np.array(box.CornerMax().Coord())


def _compound(faces: Sequence[TopoDS_Face]) -> TopoDS_Compound:
    builder = BRep_Builder()
    out = TopoDS_Compound()
    builder.MakeCompound(out)
    for face in faces:
        builder.Add(out, face)
    return out


def as_nurbs(faces: Sequence[TopoDS_Face]) -> list[TopoDS_Face]:
    """``faces`` with every surface converted to a rational B-spline surface (the same faces)."""
    return faces_of(BRepBuilderAPI_NurbsConvert(_compound(faces), True).Shape())


def within(faces: Sequence[TopoDS_Face], box: ClipBox, tolerance: float) -> bool:
    """Whether every face lies in ``box`` (to a millionth of its size): the check
    of a Boolean cut, which Open CASCADE gets wrong for some revolved B-spline profiles."""
    low, high = np.array(box.bounds[0::2]), np.array(box.bounds[1::2])
    slack = 1e-6 * float(np.max(high - low)) + tolerance
    for face in faces:
        bounds = Bnd_Box()
        BRepBndLib.AddOptimal_s(face, bounds, False, False)
        if np.any(np.array(bounds.CornerMin().Coord()) < low - slack):
            return False
        if np.any(np.array(bounds.CornerMax().Coord()) > high + slack):
            return False
    return True
