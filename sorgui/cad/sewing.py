"""Faces into a part that CAD systems accept: sewn, fixed, oriented and checked (docs/math.md §11).

The usual Open CASCADE pipeline (cadquery's): the faces are sewn (``BRepBuilderAPI_Sewing``), so
that neighbouring faces share their edges; each connected piece becomes one shell whose faces
``ShapeFix_Shell`` orients consistently; a closed shell becomes a solid
(``ShapeFix_Solid::SolidFromShell``: ``BRepBuilderAPI_MakeSolid`` with its faces turned outward);
``BRepCheck_Analyzer`` must accept the result, or nothing is written. An open shell's faces point
along ``∇f``, toward ``f > 0`` (the convention the 3D view's mesh follows), decided by the sign
of ``n·∇f`` at points of each shell. Lengths are relative to the part's ``size`` (the drawn
ball's radius): :func:`precision` is the tolerance every edge, vertex and the STEP file's
uncertainty gets.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from OCP.Bnd import Bnd_Box
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepBuilderAPI import BRepBuilderAPI_Sewing
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepGProp import BRepGProp
from OCP.BRepTools import BRepTools
from OCP.gp import gp_Pnt, gp_Vec
from OCP.GProp import GProp_GProps
from OCP.ShapeFix import ShapeFix_Shell, ShapeFix_Solid
from OCP.TopAbs import TopAbs_FACE, TopAbs_REVERSED, TopAbs_SHELL, TopAbs_SOLID
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Compound, TopoDS_Face, TopoDS_Shape, TopoDS_Shell

from sorgui.engine.values import Terms
from sorgui.render.sampling import value_and_gradient

from .failures import from_occt
from .geometry import CadGeometryError

CONFUSION = 1e-7
"""Open CASCADE's smallest length that tells two points apart (``Precision::Confusion``)."""

RELATIVE_PRECISION = 1e-9
"""A part's tolerance relative to its size, where that is above :data:`CONFUSION`: a part of
size 1e6 gets 1e-3, as its doubles carry about 1e-10 of it."""

SMALLEST_PART = 1e3 * CONFUSION
"""The smallest part written: below it Open CASCADE's fixed precision is a sizeable part of it."""

SEWING = 10.0
"""Edges closer than this many tolerances are sewn into one."""

SAMPLES = 5
"""Points per parameter at which a face's normal is compared with ``∇f``."""


def precision(size: float) -> float:
    """The tolerance of a part of ``size``: :data:`CONFUSION`, or a billionth of a large part."""
    return max(CONFUSION, RELATIVE_PRECISION * size)


def check_size(size: float) -> None:
    """Refuse a part too small for Open CASCADE to resolve (a ``CadGeometryError`` in one sentence)."""
    if not size >= SMALLEST_PART:
        raise CadGeometryError(
            f"the part is {size:.2g} across, too small for Open CASCADE's precision of {CONFUSION:g} "
            "length units: scale the equation"
        )


def extent(faces: Sequence[TopoDS_Face]) -> float:
    """The diagonal of the box that holds the faces."""
    box = Bnd_Box()
    for face in faces:
        BRepBndLib.AddOptimal_s(face, box, False, False)
    if box.IsVoid():
        return 0.0
    return float(np.linalg.norm(np.array(box.CornerMax().Coord()) - np.array(box.CornerMin().Coord())))


def assemble(faces: Sequence[TopoDS_Face], size: float, terms: Terms | None) -> TopoDS_Shape:
    """The faces sewn into shells, closed shells made solids, open ones oriented along ``∇f``
    (``terms``: the square-free ``f``), checked: one shell or solid, or a compound of them."""
    if not faces:
        raise CadGeometryError("the part has no faces")
    check_size(extent(faces))
    tolerance = precision(size)
    sewing = BRepBuilderAPI_Sewing(SEWING * tolerance)
    for face in faces:
        sewing.Add(face)
    try:
        sewing.Perform()
    except Exception as exc:
        if not from_occt(exc):
            raise
        raise CadGeometryError(f"Open CASCADE could not sew the faces ({type(exc).__name__})") from None
    parts: list[TopoDS_Shape] = []
    for shell in _shells(sewing.SewedShape()):
        fix = ShapeFix_Shell(shell)
        fix.Perform()
        for fixed in _explore(fix.Shape(), TopAbs_SHELL):
            parts.append(_finished(TopoDS.Shell(fixed), terms))
    shape = parts[0] if len(parts) == 1 else compound(parts)
    if not BRepCheck_Analyzer(shape).IsValid():
        raise CadGeometryError("Open CASCADE finds the sewn part invalid (BRepCheck)")
    return shape


def _shells(sewn: TopoDS_Shape) -> list[TopoDS_Shell]:
    """The shells of the sewn shape, and each face left outside them in a shell of its own."""
    shells = [TopoDS.Shell(s) for s in _explore(sewn, TopAbs_SHELL)]
    builder = BRep_Builder()
    explorer = TopExp_Explorer(sewn, TopAbs_FACE, TopAbs_SHELL)
    while explorer.More():
        shell = TopoDS_Shell()
        builder.MakeShell(shell)
        builder.Add(shell, explorer.Current())
        shells.append(shell)
        explorer.Next()
    return shells


FLAT_SOLID = 1e-6
"""A solid whose volume is below this times its area^(3/2) encloses nothing: its faces cover a
sheet twice (a torus of radii 1000 and 1, the thinnest part a user may draw, has 2.5e-3)."""


def _finished(shell: TopoDS_Shell, terms: Terms | None) -> TopoDS_Shape:
    """A closed shell as a solid whose faces point out of it; an open one along ``∇f`` (by the
    sign of ``n·∇f`` over all its faces: where ``f`` has a singular curve, a node of a profile,
    ``∇f`` turns over across it while the sheet's orientation goes on). A solid of no positive
    volume is refused (:data:`FLAT_SOLID`): a rounded cone's nearest surface had a face that
    covered one nappe twice, sewn on itself into a "solid" of volume 4e-10 (−1797 read back) that
    BRepCheck passes and its STEP file does not."""
    if BRep_Tool.IsClosed_s(shell):
        solid = ShapeFix_Solid().SolidFromShell(shell)
        solid = next(iter(_explore(solid, TopAbs_SOLID)), solid)
        volume, area = GProp_GProps(), GProp_GProps()
        BRepGProp.VolumeProperties_s(solid, volume)
        BRepGProp.SurfaceProperties_s(solid, area)
        if not volume.Mass() > FLAT_SOLID * area.Mass() ** 1.5:
            raise CadGeometryError(
                "Open CASCADE made a closed sheet of the part into a solid of no volume: a face covers "
                "part of the surface twice (write a mesh instead, .stl or .obj)"
            )
        return solid
    if terms is not None and gradient_agreement(shell, terms) < 0:
        return shell.Reversed()
    return shell


def gradient_agreement(shape: TopoDS_Shape, terms: Terms) -> float:
    """The mean of ``sign(n·∇f)`` over points of every face of ``shape`` (``n`` the face's normal
    as its orientation has it; points where ``∇f`` nearly vanishes are left out): ``1`` when
    every face points toward ``f > 0``, ``-1`` when every one points away."""
    points, normals = [], []
    for face in _explore(shape, TopAbs_FACE):
        p, n = face_normals(TopoDS.Face(face))
        points.append(p)
        normals.append(n)
    if not points:
        return 0.0
    xyz, normal = np.concatenate(points), np.concatenate(normals)
    _, gradient = value_and_gradient(terms, xyz, normalise=True)
    length = np.linalg.norm(gradient, axis=1)
    usable = np.isfinite(length) & (length > 1e-8 * np.nanmax(length, initial=0.0))
    if not np.any(usable):
        return 0.0
    return float(np.mean(np.sign(np.einsum("ij,ij->i", normal[usable], gradient[usable]))))


def face_normals(face: TopoDS_Face, samples: int = SAMPLES) -> tuple[np.ndarray, np.ndarray]:
    """Points on the surface of ``face`` over its ``(u, v)`` box and the unit normals there, as
    the face's orientation has them (where the surface is degenerate no normal is given)."""
    surface = BRepAdaptor_Surface(face)
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    sign = -1.0 if face.Orientation() == TopAbs_REVERSED else 1.0
    steps = (np.arange(samples) + 0.5) / samples
    points, normals = [], []
    for u in u0 + (u1 - u0) * steps:
        for v in v0 + (v1 - v0) * steps:
            p, du, dv = gp_Pnt(), gp_Vec(), gp_Vec()
            surface.D1(float(u), float(v), p, du, dv)
            n = np.cross(du.Coord(), dv.Coord())
            length = float(np.linalg.norm(n))
            if length > 0 and math.isfinite(length):
                points.append(p.Coord())
                normals.append(sign * n / length)
    return np.array(points).reshape(-1, 3), np.array(normals).reshape(-1, 3)


def compound(shapes: Sequence[TopoDS_Shape]) -> TopoDS_Compound:
    """The shapes in one compound (one product of a STEP file: the writer makes no assembly)."""
    builder = BRep_Builder()
    out = TopoDS_Compound()
    builder.MakeCompound(out)
    for shape in shapes:
        builder.Add(out, shape)
    return out


def _explore(shape: TopoDS_Shape, kind: object) -> list[TopoDS_Shape]:
    found = []
    explorer = TopExp_Explorer(shape, kind)
    while explorer.More():
        found.append(explorer.Current())
        explorer.Next()
    return found


def solids_of(shape: TopoDS_Shape) -> int:
    """How many solids ``shape`` holds."""
    return len(_explore(shape, TopAbs_SOLID))
