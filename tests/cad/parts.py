"""Parts built with Open CASCADE itself for the tests of reading and recognising faces: solids
about an oblique axis, converted to B-spline faces (``BRepBuilderAPI_NurbsConvert``), with or
without noise on their poles, faces of no symmetry at all, and a face Open CASCADE cannot
evaluate."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut, BRepAlgoAPI_Fuse
from OCP.BRepBuilderAPI import (
    BRepBuilderAPI_MakeEdge,
    BRepBuilderAPI_MakeFace,
    BRepBuilderAPI_NurbsConvert,
    BRepBuilderAPI_Transform,
)
from OCP.BRepPrimAPI import (
    BRepPrimAPI_MakeBox,
    BRepPrimAPI_MakeCone,
    BRepPrimAPI_MakeCylinder,
    BRepPrimAPI_MakePrism,
    BRepPrimAPI_MakeRevol,
    BRepPrimAPI_MakeSphere,
    BRepPrimAPI_MakeTorus,
)
from OCP.Geom import Geom_BSplineSurface, Geom_OffsetSurface, Geom_Plane
from OCP.GeomAbs import GeomAbs_Shape
from OCP.GeomAPI import GeomAPI_PointsToBSpline, GeomAPI_PointsToBSplineSurface
from OCP.gp import gp_Ax1, gp_Ax2, gp_Ax3, gp_Dir, gp_Pln, gp_Pnt, gp_Trsf, gp_Vec
from OCP.OCP.collections import Array1_double, Array1_gp_Pnt, Array1_int, Array2_gp_Pnt
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS_Compound, TopoDS_Shape

from sorgui.cad.reading import Part, faces_of

ORIGIN = np.array([1.0, 2.0, 3.0])
"""Where the parts' own origin is placed."""
AXIS = np.array([1.0, 1.0, 1.0]) / math.sqrt(3.0)
"""Where the parts' own z axis points: every part's axis is oblique."""


def placement() -> gp_Trsf:
    """The rigid motion taking the parts' own frame to ``ORIGIN``, ``AXIS``."""
    trsf = gp_Trsf()
    trsf.SetTransformation(gp_Ax3(gp_Pnt(*ORIGIN), gp_Dir(*AXIS), gp_Dir(1, -1, 0)), gp_Ax3())
    return trsf


def placed(shape: TopoDS_Shape) -> TopoDS_Shape:
    return BRepBuilderAPI_Transform(shape, placement(), True).Shape()


def converted(shape: TopoDS_Shape) -> TopoDS_Shape:
    """Every face as a B-spline face: the axis is lost from the file."""
    return BRepBuilderAPI_NurbsConvert(shape, True).Shape()


def as_part(shape: TopoDS_Shape, name: str = "part.brep") -> Part:
    return Part(shape, tuple(faces_of(shape)), Path(name), "BRep")


def placed_point(p: tuple[float, float, float]) -> np.ndarray:
    q = gp_Pnt(*p).Transformed(placement())
    return np.array([q.X(), q.Y(), q.Z()])


def placed_axis() -> tuple[np.ndarray, np.ndarray]:
    """The parts' z axis after :func:`placement`: a point and the unit direction."""
    axis = gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)).Transformed(placement())
    p, d = axis.Location(), axis.Direction()
    return np.array([p.X(), p.Y(), p.Z()]), np.array([d.X(), d.Y(), d.Z()])


def profile_spline(points: list[tuple[float, float]]) -> BRepBuilderAPI_MakeEdge:
    """The edge of the B-spline through ``(x, 0, z)`` for the ``(x, z)`` given."""
    array = Array1_gp_Pnt(1, len(points))
    for k, (x, z) in enumerate(points, start=1):
        array.SetValue(k, gp_Pnt(x, 0, z))
    return BRepBuilderAPI_MakeEdge(GeomAPI_PointsToBSpline(array).Curve()).Edge()


def revolved_spline(angle: float = 2 * math.pi) -> TopoDS_Shape:
    """A B-spline profile turned about the z axis, placed obliquely and converted."""
    edge = profile_spline([(2, 0), (3, 1), (2.5, 2), (3.5, 3), (2, 4)])
    revolved = BRepPrimAPI_MakeRevol(edge, gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), angle).Shape()
    return converted(placed(revolved))


def dome() -> TopoDS_Shape:
    """A B-spline profile from the axis, turned: a face with a pole."""
    edge = profile_spline([(0, 4), (1.5, 3.5), (2.5, 2), (2, 1), (3, 0)])
    revolved = BRepPrimAPI_MakeRevol(edge, gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 2 * math.pi).Shape()
    return converted(placed(revolved))


def noisy(shape: TopoDS_Shape, size: float, seed: int = 7) -> TopoDS_Shape:
    """The first face of ``shape`` with every pole moved by ``size`` in a random direction."""
    rng = np.random.default_rng(seed)
    surface = BRep_Tool.Surface_s(faces_of(shape)[0]).Copy()
    assert isinstance(surface, Geom_BSplineSurface)
    for i in range(1, surface.NbUPoles() + 1):
        for j in range(1, surface.NbVPoles() + 1):
            p = surface.Pole(i, j)
            d = rng.standard_normal(3)
            d *= size / np.linalg.norm(d)
            surface.SetPole(i, j, gp_Pnt(p.X() + d[0], p.Y() + d[1], p.Z() + d[2]))
    u0, u1, v0, v1 = surface.Bounds()
    return BRepBuilderAPI_MakeFace(surface, u0, u1, v0, v1, 1e-7).Face()


def torus() -> TopoDS_Shape:
    return converted(placed(BRepPrimAPI_MakeTorus(5, 1).Shape()))


def cone() -> TopoDS_Shape:
    """A truncated cone: a conical face and two disks."""
    return converted(placed(BRepPrimAPI_MakeCone(2, 1, 3).Shape()))


def pointed_cone() -> TopoDS_Shape:
    """A cone up to its apex (a degenerate edge there) on a disk."""
    return converted(placed(BRepPrimAPI_MakeCone(2, 0, 3).Shape()))


def sphere() -> TopoDS_Shape:
    return converted(placed(BRepPrimAPI_MakeSphere(2).Shape()))


def cylinder() -> TopoDS_Shape:
    return converted(placed(BRepPrimAPI_MakeCylinder(2, 5).Shape()))


def bumpy() -> TopoDS_Shape:
    """A B-spline face through a wavy grid: no symmetry, no ruling."""
    poles = Array2_gp_Pnt(1, 5, 1, 5)
    for i in range(5):
        for j in range(5):
            poles.SetValue(i + 1, j + 1, gp_Pnt(i, j, 0.3 * math.sin(1.3 * i + 0.7 * j) + 0.05 * i * j))
    return BRepBuilderAPI_MakeFace(GeomAPI_PointsToBSplineSurface(poles).Surface(), 1e-7).Face()


def extruded() -> TopoDS_Shape:
    """A B-spline curve swept along an oblique direction, converted."""
    array = Array1_gp_Pnt(1, 5)
    for k, (x, y) in enumerate([(0, 0), (1, 1), (2, 0.5), (3, 1.5), (4, 0)], start=1):
        array.SetValue(k, gp_Pnt(x, y, 0))
    edge = BRepBuilderAPI_MakeEdge(GeomAPI_PointsToBSpline(array).Curve()).Edge()
    return converted(BRepPrimAPI_MakePrism(edge, gp_Vec(0.3, 0.2, 3)).Shape())


EXTRUSION_DIRECTION = np.array([0.3, 0.2, 3.0]) / np.linalg.norm([0.3, 0.2, 3.0])


def boolean_part() -> TopoDS_Shape:
    """A box with a torus fused on top, a hole through it and a spherical pocket at a corner,
    placed obliquely and converted: planes, a cylinder and a torus about one axis, a sphere off it."""
    box = BRepPrimAPI_MakeBox(gp_Pnt(-5, -5, 0), 10, 10, 6).Shape()
    hole = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -1), gp_Dir(0, 0, 1)), 2, 8).Shape()
    ring = BRepPrimAPI_MakeTorus(gp_Ax2(gp_Pnt(0, 0, 6), gp_Dir(0, 0, 1)), 3, 1).Shape()
    pocket = BRepPrimAPI_MakeSphere(gp_Pnt(3, 3, 0), 1.5).Shape()
    shape = BRepAlgoAPI_Cut(BRepAlgoAPI_Cut(BRepAlgoAPI_Fuse(box, ring).Shape(), hole).Shape(), pocket).Shape()
    return converted(placed(shape))


def turned_part(steps: int = 12) -> TopoDS_Shape:
    """A stepped shaft: ``steps`` collars (cylinders, cones and planes) and tori in grooves, fused,
    placed obliquely and converted (about 50 faces for 12 steps)."""
    shape = None
    for k in range(steps):
        collar = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 2.0 * k), gp_Dir(0, 0, 1)), 3 + (k % 3), 1.5).Shape()
        taper = BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, 2.0 * k + 1.5), gp_Dir(0, 0, 1)), 2.5, 2.0, 0.5).Shape()
        piece = BRepAlgoAPI_Fuse(collar, taper).Shape()
        shape = piece if shape is None else BRepAlgoAPI_Fuse(shape, piece).Shape()
    assert shape is not None
    return converted(placed(shape))


def exchanged() -> TopoDS_Shape:
    """Part of a turn of the revolved B-spline with its parameters exchanged (``v`` the angle)."""
    surface = BRep_Tool.Surface_s(faces_of(revolved_spline(angle=2.5))[0]).Copy()
    surface.ExchangeUV()
    u0, u1, v0, v1 = surface.Bounds()
    return BRepBuilderAPI_MakeFace(surface, u0, u1, v0, v1, 1e-7).Face()


def skewed(count: int = 25) -> TopoDS_Shape:
    """A B-spline through points of ``r = 2 + 0.3 sin 2h`` about the z axis laid out along
    helices (angle ``a + 0.4 h``): a surface of revolution none of whose parameter lines is a
    circle, interpolated within 1e-9."""
    grid = Array2_gp_Pnt(1, count, 1, count)
    for i in range(count):
        for j in range(count):
            a, h = 2.0 * i / (count - 1), 3.0 * j / (count - 1)
            r, theta = 2 + 0.3 * math.sin(2 * h), a + 0.4 * h
            grid.SetValue(i + 1, j + 1, gp_Pnt(r * math.cos(theta), r * math.sin(theta), h))
    surface = GeomAPI_PointsToBSplineSurface(grid, 3, 8, GeomAbs_Shape.GeomAbs_C2, 1e-9).Surface()
    return BRepBuilderAPI_MakeFace(surface, 1e-7).Face()


def unevaluable() -> TopoDS_Shape:
    """A face Open CASCADE cannot evaluate, beside the revolved B-spline: a unit square whose
    surface is then set to an offset of a B-spline collapsed to a point (no normal anywhere, so
    ``Geom_OffsetSurface`` raises ``Geom_UndefinedValue`` and ``Geom_UndefinedDerivative``)."""
    poles = Array2_gp_Pnt(1, 2, 1, 2)
    for i in (1, 2):
        for j in (1, 2):
            poles.SetValue(i, j, gp_Pnt(1, 2, 3))
    knots, mults = Array1_double(1, 2), Array1_int(1, 2)
    for k in (1, 2):
        knots.SetValue(k, float(k - 1))
        mults.SetValue(k, 2)
    collapsed = Geom_BSplineSurface(poles, knots, knots, mults, mults, 1, 1)
    face = BRepBuilderAPI_MakeFace(Geom_Plane(gp_Pln()), 0.0, 1.0, 0.0, 1.0, 1e-7).Face()
    BRep_Builder().UpdateFace(face, Geom_OffsetSurface(collapsed, 1.0), TopLoc_Location(), 1e-7)
    compound = TopoDS_Compound()
    builder = BRep_Builder()
    builder.MakeCompound(compound)
    builder.Add(compound, revolved_spline())
    builder.Add(compound, face)
    return compound


def skewed_cone(count: int = 25) -> TopoDS_Shape:
    """A B-spline through points of the elliptic cone ``(x/2)² + y² = z²`` laid out along helices
    (angle ``a + 0.4 z``): a cone over a curve none of whose parameter lines is a ruling."""
    grid = Array2_gp_Pnt(1, count, 1, count)
    for i in range(count):
        for j in range(count):
            a, h = 2.0 * i / (count - 1), 1.0 + 2.0 * j / (count - 1)
            theta = a + 0.4 * h
            grid.SetValue(i + 1, j + 1, gp_Pnt(2 * h * math.cos(theta), h * math.sin(theta), h))
    surface = GeomAPI_PointsToBSplineSurface(grid, 3, 8, GeomAbs_Shape.GeomAbs_C2, 1e-9).Surface()
    return BRepBuilderAPI_MakeFace(surface, 1e-7).Face()
