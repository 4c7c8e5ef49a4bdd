"""``-o CANONICAL.step``: each recognised B-spline face rebuilt on its native surface, trimmed by
the same edges, the part valid under ``BRepCheck_Analyzer`` and read back by Open CASCADE and by
gmsh with the native surface types; every new face within the tolerance of the old one."""

from __future__ import annotations

from pathlib import Path

import pytest

pytest.importorskip("OCP")

from OCP.BRep import BRep_Tool  # noqa: E402
from OCP.BRepAdaptor import BRepAdaptor_Surface  # noqa: E402
from OCP.BRepCheck import BRepCheck_Analyzer  # noqa: E402
from OCP.ShapeAnalysis import ShapeAnalysis_Surface  # noqa: E402
from OCP.TopAbs import TopAbs_SOLID  # noqa: E402
from OCP.TopExp import TopExp_Explorer  # noqa: E402

from sorgui.cad.canonical import canonical_file  # noqa: E402
from sorgui.cad.native import _pnt  # noqa: E402
from sorgui.cad.reading import (
    faces_of,  # noqa: E402
    read_part,  # noqa: E402
)
from sorgui.cad.recognition import analyse_part  # noqa: E402
from sorgui.cad.sampling import sample_face  # noqa: E402

from . import parts  # noqa: E402

NATIVE = {
    "plane": "GeomAbs_Plane",
    "sphere": "GeomAbs_Sphere",
    "cylinder": "GeomAbs_Cylinder",
    "cone": "GeomAbs_Cone",
    "torus": "GeomAbs_Torus",
    "revolution": "GeomAbs_SurfaceOfRevolution",
    "extrusion": "GeomAbs_SurfaceOfExtrusion",
}

CASES = {
    "revolved": parts.revolved_spline,
    "part-turn": lambda: parts.revolved_spline(angle=2.0),
    "dome": parts.dome,
    "noisy": lambda: parts.noisy(parts.revolved_spline(), 1e-9),
    "torus": parts.torus,
    "cone": parts.cone,
    "pointed-cone": parts.pointed_cone,
    "sphere": parts.sphere,
    "cylinder": parts.cylinder,
    "extrusion": parts.extruded,
    "boolean": parts.boolean_part,
    "exchanged": parts.exchanged,
    "skewed": parts.skewed,
}


def solids(shape) -> int:
    explorer, count = TopExp_Explorer(shape, TopAbs_SOLID), 0
    while explorer.More():
        count += 1
        explorer.Next()
    return count


def largest_gap(new_face, old_face, tolerance: float) -> float:
    """The largest distance of the new face's samples from the old face's surface."""
    onto = ShapeAnalysis_Surface(BRep_Tool.Surface_s(old_face))
    worst = 0.0
    for p in sample_face(new_face).points:
        onto.ValueOfUV(_pnt(p), 0.01 * tolerance)
        worst = max(worst, onto.Gap())
    return worst


@pytest.mark.parametrize("name", sorted(CASES))
def test_the_canonical_part_is_valid_and_native(tmp_path: Path, name: str) -> None:
    shape = CASES[name]()
    part = parts.as_part(shape)
    report, found = analyse_part(part)
    data, canonical = canonical_file(part, found, "canonical.step", ".step")
    assert canonical.valid and canonical.kept == ()
    assert canonical.replaced == tuple(f.face for f in report.faces)
    path = tmp_path / "canonical.step"
    path.write_bytes(data)
    back = read_part(path)
    assert BRepCheck_Analyzer(back.shape).IsValid()
    assert solids(back.shape) == solids(shape) and len(back.faces) == len(part.faces)
    for old, new, face in zip(part.faces, back.faces, report.faces):
        assert BRepAdaptor_Surface(new).GetType().name == NATIVE[face.kind], face
        assert largest_gap(new, old, face.tolerance) <= face.tolerance
    again, _ = analyse_part(back)
    assert [(f.kind, f.source) for f in again.faces] == [(f.kind, "file") for f in report.faces]


def test_faces_that_are_not_recognised_stay_as_they_were(tmp_path: Path) -> None:
    part = parts.as_part(parts.bumpy())
    report, found = analyse_part(part)
    _, canonical = canonical_file(part, found, "same.brep", ".brep")
    assert canonical.replaced == () and canonical.valid
    (face,) = faces_of(canonical.shape)
    assert BRepAdaptor_Surface(face).GetType().name == "GeomAbs_BSplineSurface"


def test_gmsh_reads_the_canonical_part(tmp_path: Path) -> None:
    gmsh = pytest.importorskip("gmsh")
    part = parts.as_part(parts.boolean_part())
    _, found = analyse_part(part)
    data, _ = canonical_file(part, found, "boolean.step", ".step")
    path = tmp_path / "boolean.step"
    path.write_bytes(data)
    gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.occ.importShapes(str(path))
        gmsh.model.occ.synchronize()
        types = sorted(gmsh.model.getType(2, tag) for _, tag in gmsh.model.getEntities(2))
    finally:
        gmsh.finalize()
    assert types == sorted(["Plane"] * 6 + ["Cylinder", "Torus", "Sphere"])
