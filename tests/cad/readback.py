"""What a CAD engineer checks of a part read back from a file, with Open CASCADE and with gmsh.

* :func:`topology`: validity under ``BRepCheck_Analyzer``, the shells and solids, and the free
  edges (those bounding one face only), sampled as points;
* :func:`gmsh_part`: the same file read by gmsh (its own OCC build): surfaces, volumes, area and
  the points of the curves that bound the union of its surfaces;
* :func:`part_to_surface` and :func:`surface_to_part`: the two-sided distance between the part
  and the real surface in the region (``|f|/|∇f|`` at area-weighted points of the faces; the
  distance from points of the surface to the faces).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepGProp import BRepGProp
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.BRepTools import BRepTools
from OCP.GeomAPI import GeomAPI_ProjectPointOnSurf
from OCP.gp import gp_Pnt, gp_Pnt2d
from OCP.GProp import GProp_GProps
from OCP.IntTools import IntTools_FClass2d
from OCP.ShapeAnalysis import ShapeAnalysis_FreeBounds
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_IN, TopAbs_ON, TopAbs_REVERSED, TopAbs_SHELL, TopAbs_SOLID
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS, TopoDS_Shape

from sorgui.render import ClipBox, ClipSphere
from sorgui.render.sampling import first_order_distance, newton_step, value_and_gradient


def count(shape: TopoDS_Shape, kind) -> int:
    explorer = TopExp_Explorer(shape, kind)
    n = 0
    while explorer.More():
        n += 1
        explorer.Next()
    return n


def edge_points(edge, samples: int = 12) -> np.ndarray:
    curve = BRepAdaptor_Curve(edge)
    a, b = curve.FirstParameter(), curve.LastParameter()
    return np.array([curve.Value(float(u)).Coord() for u in np.linspace(a, b, samples)])


@dataclass(frozen=True)
class Topology:
    valid: bool
    faces: int
    shells: int
    solids: int
    free_points: np.ndarray
    """Points sampled on the free edges (bounding one face only; seams and degenerate edges
    excluded), ``(n, 3)``."""


def topology(shape: TopoDS_Shape, tolerance: float = 1e-7) -> Topology:
    free = ShapeAnalysis_FreeBounds(shape, tolerance, False, False)
    points = []
    for wires in (free.GetClosedWires(), free.GetOpenWires()):
        explorer = TopExp_Explorer(wires, TopAbs_EDGE)
        while explorer.More():
            edge = TopoDS.Edge(explorer.Current())
            if not BRep_Tool.Degenerated_s(edge):
                points.append(edge_points(edge))
            explorer.Next()
    return Topology(
        BRepCheck_Analyzer(shape).IsValid(),
        count(shape, TopAbs_FACE),
        count(shape, TopAbs_SHELL),
        count(shape, TopAbs_SOLID),
        np.concatenate(points) if points else np.zeros((0, 3)),
    )


def on_boundary(points: np.ndarray, region: ClipSphere | ClipBox, slack: float) -> np.ndarray:
    """Whether each point lies on the boundary of ``region`` (to ``slack``)."""
    if isinstance(region, ClipSphere):
        return np.abs(np.linalg.norm(points - np.asarray(region.center), axis=1) - region.radius) <= slack
    low, high = np.array(region.bounds[0::2]), np.array(region.bounds[1::2])
    inside = np.all((points >= low - slack) & (points <= high + slack), axis=1)
    near = np.any((np.abs(points - low) <= slack) | (np.abs(points - high) <= slack), axis=1)
    return inside & near


def area(shape: TopoDS_Shape) -> float:
    props = GProp_GProps()
    BRepGProp.SurfaceProperties_s(shape, props, 1e-9)
    return props.Mass()


def faces_of(shape: TopoDS_Shape) -> list:
    explorer = TopExp_Explorer(shape, TopAbs_FACE)
    out = []
    while explorer.More():
        out.append(TopoDS.Face(explorer.Current()))
        explorer.Next()
    return out


def triangulation(shape: TopoDS_Shape, deflection: float):
    """Nodes, triangles (indices into nodes, turned as the faces are oriented), each triangle's
    cross product and the index of its face: ``(points, triangles, cross, owner)``."""
    BRepMesh_IncrementalMesh(shape, deflection, False, 0.3, True)
    nodes, triangles, owners = [], [], []
    offset = 0
    for number, face in enumerate(faces_of(shape)):
        location = TopLoc_Location()
        mesh = BRep_Tool.Triangulation_s(face, location)
        if mesh is None:
            continue
        transform = location.Transformation()
        xyz = np.array([mesh.Node(i).Transformed(transform).Coord() for i in range(1, mesh.NbNodes() + 1)])
        tri = np.array([mesh.Triangle(i).Get() for i in range(1, mesh.NbTriangles() + 1)]) - 1
        if face.Orientation() == TopAbs_REVERSED:
            tri = tri[:, ::-1]
        nodes.append(xyz)
        triangles.append(tri + offset)
        owners.append(np.full(len(tri), number))
        offset += len(xyz)
    points, tri = np.concatenate(nodes), np.concatenate(triangles)
    cross = np.cross(points[tri[:, 1]] - points[tri[:, 0]], points[tri[:, 2]] - points[tri[:, 0]])
    return points, tri, cross, np.concatenate(owners)


class Feet:
    """The nearest point of a face to a point: the foot on its surface within its (u, v) box,
    if that lies inside the face; else the nearest of points sampled on its edges."""

    def __init__(self, shape: TopoDS_Shape) -> None:
        self.faces = faces_of(shape)
        self.surfaces = [BRep_Tool.Surface_s(f) for f in self.faces]
        self.bounds = [BRepTools.UVBounds_s(f) for f in self.faces]
        self.classifiers = [IntTools_FClass2d(f, 1e-9) for f in self.faces]
        self.edges = []
        for face in self.faces:
            explorer = TopExp_Explorer(face, TopAbs_EDGE)
            samples = []
            while explorer.More():
                edge = TopoDS.Edge(explorer.Current())
                if not BRep_Tool.Degenerated_s(edge):
                    samples.append(edge_points(edge, 400))
                explorer.Next()
            self.edges.append(np.concatenate(samples) if samples else np.zeros((0, 3)))

    def foot(self, k: int, point: np.ndarray) -> np.ndarray:
        """The nearest point of face ``k`` to ``point``."""
        u0, u1, v0, v1 = self.bounds[k]
        projection = GeomAPI_ProjectPointOnSurf(gp_Pnt(*map(float, point)), self.surfaces[k], u0, u1, v0, v1)
        if projection.NbPoints():
            u, v = projection.LowerDistanceParameters()
            if self.classifiers[k].Perform(gp_Pnt2d(u, v)) in (TopAbs_IN, TopAbs_ON):
                return np.array(projection.NearestPoint().Coord())
        edges = self.edges[k]
        if not len(edges):
            return np.full(3, np.inf)
        return edges[int(np.argmin(np.linalg.norm(edges - point, axis=1)))]

    def nearest(self, point: np.ndarray) -> np.ndarray:
        feet = [self.foot(k, point) for k in range(len(self.faces))]
        return min(feet, key=lambda f: float(np.linalg.norm(f - point)))


def part_points(shape: TopoDS_Shape, size: float, count: int = 2000, seed: int = 0):
    """About ``count`` area-weighted points of the faces (triangle centroids moved onto their
    face), with the faces' normals there: ``(points, normals)``."""
    points, triangles, cross, owner = triangulation(shape, 1e-3 * size)
    weights = np.linalg.norm(cross, axis=1)
    rng = np.random.default_rng(seed)
    chosen = rng.choice(len(triangles), size=min(count, len(triangles)), replace=False, p=weights / weights.sum())
    centroids = points[triangles[chosen]].mean(axis=1)
    normals = cross[chosen] / weights[chosen, None]
    feet = Feet(shape)
    on = np.array([feet.foot(int(owner[j]), c) for j, c in zip(chosen, centroids)])
    good = np.all(np.isfinite(on), axis=1)
    return on[good], normals[good]


class Surface:
    """``f`` about a centre near the part: its exact coefficients shifted there (over QQ) and
    rounded once, so that a degree-12 surface far from the origin is evaluated to rounding, not
    to the 1e-3 its float coefficients about the origin leave."""

    def __init__(self, polynomial: str, centre) -> None:
        from sympy import QQ, Rational, ring

        from sorgui.engine.values import read_expression

        self.centre = np.array([float(Rational(round(float(c) * 2**12), 2**12)) for c in centre])
        R, x, y, z = ring("x,y,z", QQ)
        f = R(read_expression(polynomial))
        c = [QQ(Rational(v).p, Rational(v).q) for v in self.centre]
        g = f.compose([(x, x + c[0]), (y, y + c[1]), (z, z + c[2])])
        self.terms = [(m, float(v)) for m, v in g.terms()]

    def distance(self, points: np.ndarray) -> np.ndarray:
        """The smaller of ``|f|/|∇f|`` and the way Newton's method moves the point onto ``f = 0``
        (next to a singular point the first-order distance is far too large)."""
        local = np.asarray(points) - self.centre
        first = first_order_distance(self.terms, local)
        moved = local.copy()
        for _ in range(30):
            moved = newton_step(self.terms, moved, 1e30)
        settled = first_order_distance(self.terms, moved) <= 1e-12 * max(1.0, float(np.abs(moved).max()))
        newton = np.where(settled, np.linalg.norm(moved - local, axis=1), np.inf)
        return np.fmin(first, newton)

    def onto(self, points: np.ndarray) -> np.ndarray:
        """Points moved onto ``f = 0`` by Newton steps (those that do not settle are ``nan``)."""
        moved = np.asarray(points) - self.centre
        for _ in range(12):
            moved = newton_step(self.terms, moved, 1e30)
        settled = first_order_distance(self.terms, moved) <= 1e-13 * max(1.0, float(np.abs(moved).max()))
        return np.where(settled[:, None], moved + self.centre, np.nan)

    def gradient(self, points: np.ndarray) -> np.ndarray:
        return value_and_gradient(self.terms, np.asarray(points) - self.centre, normalise=True)[1]


def part_to_surface(shape: TopoDS_Shape, surface: Surface, size: float, count: int = 2000) -> float:
    """The largest distance from area-weighted points of the faces to ``f = 0``."""
    points, _ = part_points(shape, size, count)
    return float(np.nanmax(surface.distance(points)))


def normal_agreement(shape: TopoDS_Shape, surface: Surface, size: float, count: int = 500) -> np.ndarray:
    """``sign(n · ∇f)`` at area-weighted points of the faces (``n`` as the faces orient it)."""
    points, normals = part_points(shape, size, count)
    return np.sign(np.einsum("ij,ij->i", normals, surface.gradient(points)))


def surface_points(
    surface: Surface, mesh_points: np.ndarray, region: ClipSphere | ClipBox, count: int = 2000
) -> np.ndarray:
    """Points of the real surface in ``region``: mesh vertices moved onto ``f = 0`` by Newton
    steps, those still inside the region (by a margin) kept, ``count`` of them at most."""
    rng = np.random.default_rng(1)
    points = surface.onto(
        mesh_points[rng.choice(len(mesh_points), size=min(4 * count, len(mesh_points)), replace=False)]
    )
    size = region.radius if isinstance(region, ClipSphere) else float(np.ptp(region.bounds))
    keep = np.all(np.isfinite(points), axis=1)
    if isinstance(region, ClipSphere):
        keep &= np.linalg.norm(points - np.asarray(region.center), axis=1) <= region.radius * (1 - 1e-3)
    else:
        low, high = np.array(region.bounds[0::2]), np.array(region.bounds[1::2])
        keep &= np.all((points >= low + 1e-3 * size) & (points <= high - 1e-3 * size), axis=1)
    return points[keep][:count]


def surface_to_part(shape: TopoDS_Shape, points: np.ndarray) -> np.ndarray:
    """The distance from each point to the part (the nearest foot on its faces)."""
    feet = Feet(shape)
    return np.array([np.linalg.norm(feet.nearest(p) - p) for p in points])


@dataclass(frozen=True)
class GmshPart:
    surfaces: int
    volumes: int
    area: float
    boundary_points: np.ndarray


def gmsh_part(path: Path) -> GmshPart:
    """The file read by gmsh's own Open CASCADE reader."""
    import gmsh

    gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("part")
        gmsh.model.occ.importShapes(str(path), highestDimOnly=False)
        gmsh.model.occ.synchronize()
        surfaces = gmsh.model.getEntities(2)
        total = sum(gmsh.model.occ.getMass(2, tag) for _, tag in surfaces)
        boundary = gmsh.model.getBoundary(surfaces, combined=True, oriented=False) if surfaces else []
        points = []
        for _, tag in boundary:
            low, high = gmsh.model.getParametrizationBounds(1, abs(tag))
            u = np.linspace(low[0], high[0], 12)
            xyz = np.reshape(gmsh.model.getValue(1, abs(tag), u), (-1, 3))
            if np.ptp(xyz, axis=0).max() > 1e-9 * max(1.0, float(np.abs(xyz).max())):  # not a pole or an apex
                points.append(xyz)
        return GmshPart(
            len(surfaces),
            len(gmsh.model.getEntities(3)),
            total,
            np.concatenate(points) if points else np.zeros((0, 3)),
        )
    finally:
        gmsh.finalize()
