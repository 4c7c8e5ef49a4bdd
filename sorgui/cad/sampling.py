"""Points and normals of a face over its trimmed domain (docs/math.md §12).

A face is a patch of a surface ``S(u, v)`` cut out by its wires. A grid over the face's
parameter box (``BRepTools::UVBounds``) is evaluated on the face's surface with its placement applied
(``BRep_Tool::Surface``); the grid points inside the wires (``IntTools_FClass2d``) and with a
defined normal (``GeomLProp_SLProps``: not at a pole or an apex) are the samples. A face that
covers little of its box (a thin strip) gets a finer grid, so that every face has enough samples.
The grid indices are kept: they tell along which parameter lines a profile is constant.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from OCP.BRep import BRep_Tool
from OCP.BRepTools import BRepTools
from OCP.Geom import Geom_Surface
from OCP.GeomLProp import GeomLProp_SLProps
from OCP.gp import gp_Pnt2d
from OCP.IntTools import IntTools_FClass2d
from OCP.TopAbs import TopAbs_State
from OCP.TopoDS import TopoDS_Face

from sorgui.engine.rounded.line_complex import Samples

GRID = 21
"""Grid lines in each parameter direction at first."""
FINEST = 81
"""The finest grid tried for a face that covers little of its parameter box."""
ENOUGH = 120
"""Samples a face should have (a grid is refined until it has them, up to :data:`FINEST`)."""
TOO_FEW = 12
"""Below this many samples a face cannot be recognised."""


class FaceError(ValueError):
    """A face Open CASCADE cannot evaluate (no surface, an empty or infinite domain)."""


@dataclass(frozen=True)
class FaceSamples:
    """The samples of one face: points and unit normals, their ``(u, v)`` and their grid indices
    ``(i, j)`` (``u`` is the ``i``-th of ``nu`` grid values), and the face's parameter box."""

    points: np.ndarray
    normals: np.ndarray
    uv: np.ndarray
    index: np.ndarray
    shape: tuple[int, int]
    box: tuple[float, float, float, float]

    @property
    def samples(self) -> Samples:
        return Samples(self.points, self.normals)


def sample_face(face: TopoDS_Face) -> FaceSamples:
    """The samples of ``face`` on the coarsest grid that gives :data:`ENOUGH` of them."""
    if BRep_Tool.Surface_s(face) is None:
        raise FaceError("the face has no surface")
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    box = (u0, u1, v0, v1)
    if not all(np.isfinite(box)) or max(abs(b) for b in box) > 1e100:
        raise FaceError("the face's parameter domain is unbounded")
    if not (u1 > u0 and v1 > v0):
        raise FaceError("the face's parameter domain is empty")
    surface = BRep_Tool.Surface_s(face)
    classifier = IntTools_FClass2d(face, max(BRep_Tool.Tolerance_s(face), 1e-9))
    n = GRID
    while True:
        found = _grid(surface, classifier, box, n)
        if len(found.points) >= ENOUGH or n >= FINEST:
            break
        n = min(2 * n - 1, FINEST)
    if len(found.points) < TOO_FEW:
        raise FaceError(
            f"the face is too narrow to sample ({len(found.points)} points of an {FINEST} × {FINEST} grid on it)"
        )
    return found


def _grid(
    surface: Geom_Surface, classifier: IntTools_FClass2d, box: tuple[float, float, float, float], n: int
) -> FaceSamples:
    """The samples at the ``n × n`` grid points of ``box`` inside the face, where the surface
    (with the face's placement applied) has a normal."""
    u0, u1, v0, v1 = box
    us, vs = np.linspace(u0, u1, n), np.linspace(v0, v1, n)
    props = GeomLProp_SLProps(surface, 1, 1e-12)
    points, normals, uv, index = [], [], [], []
    for i, u in enumerate(us):
        for j, v in enumerate(vs):
            if classifier.Perform(gp_Pnt2d(float(u), float(v))) != TopAbs_State.TopAbs_IN:
                continue
            props.SetParameters(float(u), float(v))
            if not props.IsNormalDefined():
                continue
            p, normal = props.Value(), props.Normal()
            points.append((p.X(), p.Y(), p.Z()))
            normals.append((normal.X(), normal.Y(), normal.Z()))
            uv.append((u, v))
            index.append((i, j))
    return FaceSamples(
        np.array(points, dtype=float).reshape(-1, 3),
        np.array(normals, dtype=float).reshape(-1, 3),
        np.array(uv, dtype=float).reshape(-1, 2),
        np.array(index, dtype=int).reshape(-1, 2),
        (n, n),
        box,
    )
