"""Whether a part covers the surface it stands for, in 3D (docs/math.md §11).

A Boolean cut to the user's box can lose a piece of a face or leave one outside the box; any
route can miss a branch. The 3D view's mesh of ``f = 0`` in the region is an independent
witness: every mesh vertex must lie near the part. The part is triangulated
(``BRepMesh_IncrementalMesh``) and each vertex's distance to the triangles found with VTK's
cell locator (pyvista's ``find_closest_cell``); a vertex farther than the mesh's own error (its grid spacing) plus
the triangulation's deflection marks a piece of the surface the part lacks. This checks the
topology of the cut, not the tolerance (the routes measure that themselves).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pyvista
from OCP.BRep import BRep_Tool
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS_Face

from .sewing import compound

SAMPLES = 3000
"""At most this many mesh vertices are checked."""

DEFLECTION = 1e-3
"""The triangulation's deflection, relative to the region's size."""


def missing(faces: list[TopoDS_Face], vertices: np.ndarray, spacing: float, size: float) -> np.ndarray | None:
    """A mesh vertex farther from the faces than ``2·spacing`` plus the triangulation's
    deflection (``DEFLECTION·size``), if there is one: a part of the surface the faces miss."""
    if not len(vertices):
        return None
    if not faces:
        return np.asarray(vertices[0])
    deflection = DEFLECTION * size
    triangles = _triangles(faces, deflection)
    if triangles is None:
        return np.asarray(vertices[0])
    rng = np.random.default_rng(0)
    chosen = vertices if len(vertices) <= SAMPLES else vertices[rng.choice(len(vertices), SAMPLES, replace=False)]
    chosen = np.asarray(chosen, dtype=np.float64)
    found: Any = triangles.find_closest_cell(chosen, return_closest_point=True)
    closest = np.asarray(found[1])
    far = np.flatnonzero(np.linalg.norm(closest - chosen, axis=1) > 2 * spacing + 2 * deflection)
    return chosen[far[0]] if len(far) else None


def _triangles(faces: list[TopoDS_Face], deflection: float) -> pyvista.PolyData | None:
    """The faces' triangulation as a VTK mesh (``None`` if Open CASCADE makes none)."""
    BRepMesh_IncrementalMesh(compound(faces), deflection, False, 0.5, True)
    nodes, cells = [], []
    offset = 0
    for face in faces:
        location = TopLoc_Location()
        mesh = BRep_Tool.Triangulation_s(face, location)
        if mesh is None:
            continue
        transform = location.Transformation()
        nodes.append(np.array([mesh.Node(i).Transformed(transform).Coord() for i in range(1, mesh.NbNodes() + 1)]))
        cells.append(np.array([mesh.Triangle(i).Get() for i in range(1, mesh.NbTriangles() + 1)]) - 1 + offset)
        offset += mesh.NbNodes()
    if not cells:
        return None
    triangles = np.concatenate(cells).astype(np.int64)
    cell_array = np.column_stack([np.full(len(triangles), 3), triangles]).ravel()
    return pyvista.PolyData(np.concatenate(nodes), cell_array)
