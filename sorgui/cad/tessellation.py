"""The triangles of a part's faces, for drawing it (``BRepMesh_IncrementalMesh``).

Plain arrays come back (points, triangles, the face of each triangle), so that the window draws
the part in its own process without Open CASCADE.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from OCP.Bnd import Bnd_Box
from OCP.BRep import BRep_Tool
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.TopAbs import TopAbs_Orientation
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS_Face, TopoDS_Shape

DEFLECTION = 2e-3
"""How far a triangle may be from its face, relative to the part's size."""
ANGLE = 0.15
"""The largest angle (radians) between the normals of a triangle's corners."""


@dataclass(frozen=True)
class PartMesh:
    """Triangles of a part: ``points`` (``N × 3``), ``triangles`` (``M × 3`` indices into them)
    and ``faces`` (``M``: the 1-based number of the face each triangle is on)."""

    points: np.ndarray
    triangles: np.ndarray
    faces: np.ndarray


def part_mesh(shape: TopoDS_Shape, faces: tuple[TopoDS_Face, ...]) -> PartMesh:
    """The triangles of ``faces`` (the faces of ``shape``), their corners shared within a face."""
    box = Bnd_Box()
    BRepBndLib.Add_s(shape, box, False)
    size = 1.0 if box.IsVoid() else box.CornerMin().Distance(box.CornerMax())
    BRepMesh_IncrementalMesh(shape, DEFLECTION * size, False, ANGLE, True)
    points, triangles, owners = [], [], []
    offset = 0
    for number, face in enumerate(faces, start=1):
        location = TopLoc_Location()
        mesh = BRep_Tool.Triangulation_s(face, location)
        if mesh is None:
            continue
        trsf = location.Transformation()
        nodes = [mesh.Node(k).Transformed(trsf) for k in range(1, mesh.NbNodes() + 1)]
        points += [(p.X(), p.Y(), p.Z()) for p in nodes]
        flip = face.Orientation() == TopAbs_Orientation.TopAbs_REVERSED
        for k in range(1, mesh.NbTriangles() + 1):
            a, b, c = mesh.Triangle(k).Get()
            corners = (a, c, b) if flip else (a, b, c)
            triangles.append(tuple(offset + i - 1 for i in corners))
            owners.append(number)
        offset += len(nodes)
    return PartMesh(
        np.array(points, dtype=float).reshape(-1, 3),
        np.array(triangles, dtype=np.int64).reshape(-1, 3),
        np.array(owners, dtype=np.int64),
    )
