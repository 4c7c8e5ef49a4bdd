"""An open part capped by the region into a solid (docs/math.md §11).

The faces of the part and the boundary of the region (the ball's sphere or the box) cut the
region into volumes (``BOPAlgo_MakerVolume``; each piece of the part, a factor's shell or solid,
is an argument of its own: Open CASCADE intersects the arguments with one another, never the
shapes inside one, so a sphere and a plane through it given as one compound were not cut by each
other); the solid kept is ``{f ≤ 0}`` inside the region:
the volumes where ``f < 0`` at points inside them (``BRepClass3d_SolidClassifier`` tells which
sampled points are inside), the side the faces' normals point away from. A part that is closed
already (a sphere, a torus inside the ball) gives its own solid.
"""

from __future__ import annotations

import numpy as np
from OCP.Bnd import Bnd_Box
from OCP.BOPAlgo import BOPAlgo_MakerVolume
from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepClass3d import BRepClass3d_SolidClassifier
from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeSphere
from OCP.GeomAbs import GeomAbs_Sphere
from OCP.gp import gp_Pnt
from OCP.TopAbs import TopAbs_COMPOUND, TopAbs_IN, TopAbs_SOLID
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS_Iterator, TopoDS_Shape

from sorgui.engine.values import Terms
from sorgui.render import ClipBox, ClipSphere
from sorgui.render.sampling import value_and_gradient

from .geometry import CadGeometryError
from .reading import faces_of
from .sewing import compound

PROBES = 400
"""Random points of a volume's bounding box tried to find points inside it."""


def capped(shape: TopoDS_Shape, region: ClipSphere | ClipBox, terms: Terms, tolerance: float) -> TopoDS_Shape:
    """The solid ``{f ≤ 0}`` inside ``region`` bounded by the part ``shape`` and the region. A
    part on the ball's own sphere closes itself: that sphere is not added again (a sphere of
    radius 2 in a ball of radius 2 about a centre 4e-16 away gave two solids, the part's and
    the ball's, the area of the file twice the sphere's)."""
    maker = BOPAlgo_MakerVolume()
    for piece in _pieces(shape):
        maker.AddArgument(piece)
    if isinstance(region, ClipBox):
        low, high = region.bounds[0::2], region.bounds[1::2]
        maker.AddArgument(BRepPrimAPI_MakeBox(gp_Pnt(*low), gp_Pnt(*high)).Shape())
    elif not _on_sphere(shape, region, tolerance):
        maker.AddArgument(BRepPrimAPI_MakeSphere(gp_Pnt(*region.center), region.radius).Shape())
    maker.SetIntersect(True)
    maker.SetFuzzyValue(tolerance)
    maker.Perform()
    if maker.HasErrors():
        raise CadGeometryError("Open CASCADE could not split the region by the part to cap it")
    kept = [solid for solid in _solids(maker.Shape()) if _inside_sign(solid, terms, tolerance) < 0]
    if not kept:
        raise CadGeometryError("the region holds no point where f < 0 to make a solid of")
    return kept[0] if len(kept) == 1 else compound(kept)


def _on_sphere(shape: TopoDS_Shape, ball: ClipSphere, tolerance: float) -> bool:
    """Whether every face of ``shape`` lies on the ball's sphere (within ``tolerance``)."""
    faces = faces_of(shape)
    for face in faces:
        surface = BRepAdaptor_Surface(face, False)
        if surface.GetType() != GeomAbs_Sphere:
            return False
        sphere = surface.Sphere()
        centre = np.array(sphere.Location().Coord())
        if np.linalg.norm(centre - ball.center) > tolerance or abs(sphere.Radius() - ball.radius) > tolerance:
            return False
    return bool(faces)


def _pieces(shape: TopoDS_Shape) -> list[TopoDS_Shape]:
    """The shells and solids of a compound (the part's pieces), or the shape itself."""
    if shape.ShapeType() != TopAbs_COMPOUND:
        return [shape]
    pieces = []
    children = TopoDS_Iterator(shape)
    while children.More():
        pieces.extend(_pieces(children.Value()))
        children.Next()
    return pieces


def _solids(shape: TopoDS_Shape) -> list[TopoDS_Shape]:
    out = []
    explorer = TopExp_Explorer(shape, TopAbs_SOLID)
    while explorer.More():
        out.append(explorer.Current())
        explorer.Next()
    return out


def _inside_sign(solid: TopoDS_Shape, terms: Terms, tolerance: float) -> float:
    """The mean sign of ``f`` at sampled points inside ``solid`` (0 if none is found)."""
    box = Bnd_Box()
    BRepBndLib.AddOptimal_s(solid, box, False, False)
    low, high = np.array(box.CornerMin().Coord()), np.array(box.CornerMax().Coord())
    rng = np.random.default_rng(0)
    classifier = BRepClass3d_SolidClassifier(solid)
    inside = []
    for point in low + (high - low) * rng.random((PROBES, 3)):
        classifier.Perform(gp_Pnt(*map(float, point)), tolerance)
        if classifier.State() == TopAbs_IN:
            inside.append(point)
        if len(inside) >= 25:
            break
    if not inside:
        return 0.0
    values = value_and_gradient(terms, np.array(inside), normalise=True)[0]
    return float(np.mean(np.sign(values)))
