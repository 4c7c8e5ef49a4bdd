"""Reading parts (STEP, IGES, BRep): bad files are refused in one line each, what a reader reads
past is said, and sorgui's own CAD exports read back as the surfaces they were written as."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("OCP")

from sorgui.cad.reading import PartError, read_part  # noqa: E402
from sorgui.cad.recognition import analyse_part  # noqa: E402
from sorgui.cad.writers import WRITERS, CadHeader  # noqa: E402
from sorgui.engine import analyze  # noqa: E402
from sorgui.export.files import export_analysis  # noqa: E402
from sorgui.session.scene_data import build_scene  # noqa: E402

from . import parts  # noqa: E402


def written(tmp_path: Path, shape, name: str) -> Path:
    path = tmp_path / name
    path.write_bytes(WRITERS[path.suffix](shape, CadHeader("", ("a test part",), "0", name)))
    return path


@pytest.mark.parametrize("suffix", [".step", ".stp", ".iges", ".igs", ".brep"])
def test_every_format_reads_the_same_faces(tmp_path: Path, suffix: str) -> None:
    shape = parts.boolean_part()
    part = read_part(written(tmp_path, shape, f"part{suffix}"))
    assert len(part.faces) == 9 and part.warnings == ()
    assert part.format == {".step": "STEP", ".stp": "STEP", ".iges": "IGES", ".igs": "IGES", ".brep": "BRep"}[suffix]
    report, _ = analyse_part(part)
    assert sorted(f.kind for f in report.faces) == sorted(["plane"] * 6 + ["cylinder", "torus", "sphere"])
    assert all(f.deviation is not None and f.deviation <= f.tolerance for f in report.faces)


BAD = {
    "not-cad.step": (b"x^2 + y^2 - 1\n", "is not a STEP file"),
    "empty.stp": (b"", "is empty"),
    "binary.iges": (bytes(range(256)) * 4, "is not an IGES file"),
    "text.brep": (b"hello\n", "is not a BRep file"),
    "nothing.step": (b"ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\nENDSEC;\nEND-ISO-10303-21;\n", "holds no faces"),
}


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_files_are_refused_in_one_line(tmp_path: Path, name: str, capfd: pytest.CaptureFixture[str]) -> None:
    data, words = BAD[name]
    path = tmp_path / name
    path.write_bytes(data)
    with pytest.raises(PartError) as caught:
        read_part(path)
    message = str(caught.value)
    assert words in message and str(path) in message and "\n" not in message
    assert capfd.readouterr().out == "", "Open CASCADE's messages stay off standard output"


def test_a_truncated_step_file(tmp_path: Path, capfd: pytest.CaptureFixture[str]) -> None:
    whole = written(tmp_path, parts.cone(), "whole.step").read_bytes()
    path = tmp_path / "cut.step"
    path.write_bytes(whole[: len(whole) // 2])
    with pytest.raises(PartError, match=r"cut\.step is not a readable STEP file: .*truncated"):
        read_part(path)
    assert capfd.readouterr().out == ""


def test_missing_and_unknown_files(tmp_path: Path) -> None:
    with pytest.raises(PartError, match="No such file"):
        read_part(tmp_path / "missing.step")
    with pytest.raises(PartError, match="is not a CAD part"):
        read_part(tmp_path / "part.stl")


def test_faulty_entities_are_left_out_and_said(tmp_path: Path) -> None:
    """A STEP file with one entity garbled: the faces that need it are left out, with a warning."""
    lines = written(tmp_path, parts.cone(), "cone.step").read_text().splitlines()
    k = next(i for i, line in enumerate(lines) if "B_SPLINE_SURFACE" in line and line.startswith("#"))
    lines[k] = lines[k].split("=")[0] + "= FOO(1,2;"
    path = tmp_path / "garbled.step"
    path.write_text("\n".join(lines) + "\n")
    part = read_part(path)
    assert len(part.faces) < 3
    (warning,) = part.warnings
    assert "faulty and left out" in warning


def test_sorgui_exports_read_back(tmp_path: Path) -> None:
    """A tilted torus (an analytic torus in the file), the paraboloid of an exact profile (a
    surface of revolution) and the paraboloid's parameterization as rational patches (B-spline
    faces, recognised about the exact axis)."""
    torus = analyze("((x-1)^2+(y-2)^2+(z-3)^2+3)^2-16*((x-1)^2+(y-2)^2)")
    path = export_analysis(torus, tmp_path / "torus.step", scene=build_scene(torus))
    report, _ = analyse_part(read_part(path))
    assert [(f.type_in_file, f.kind, f.source) for f in report.faces] == [("TOROIDAL_SURFACE", "torus", "file")]
    (face,) = report.faces
    assert np.linalg.norm(np.cross(face.axis.direction, [0, 0, 1])) < 1e-12
    assert (face.radius, face.minor_radius) == (pytest.approx(2), pytest.approx(1))

    paraboloid = analyze("x^2+y^2-z")
    scene = build_scene(paraboloid)
    exact = export_analysis(paraboloid, tmp_path / "paraboloid.step", scene=scene)
    report, _ = analyse_part(read_part(exact))
    assert {(f.type_in_file, f.kind) for f in report.faces} == {("SURFACE_OF_REVOLUTION", "revolution")}

    patches = export_analysis(paraboloid, tmp_path / "paraboloid.patch.step", scene=scene)
    report, _ = analyse_part(read_part(patches))
    assert report.faces and all(f.type_in_file == "B_SPLINE_SURFACE" for f in report.faces)
    for face in report.faces:
        assert face.kind == "revolution", face
        assert np.linalg.norm(np.cross(face.axis.direction, [0, 0, 1])) < 1e-7
        assert math.hypot(face.axis.point[0], face.axis.point[1]) < 1e-6
    assert len(report.groups) == 1 and len(report.groups[0].faces) == len(report.faces)


def test_nine_digits_far_from_the_origin(tmp_path: Path) -> None:
    """Open CASCADE's own IGES writer keeps nine significant digits: 3000 mm from the origin a
    revolved B-spline is 3e-7 from a surface of revolution, within the default tolerance there
    (1e-9 of the largest coordinate)."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
    from OCP.gp import gp_Trsf, gp_Vec
    from OCP.IGESControl import IGESControl_Writer

    move = gp_Trsf()
    move.SetTranslation(gp_Vec(1000, 2000, 3000))
    writer = IGESControl_Writer()
    writer.AddShape(BRepBuilderAPI_Transform(parts.revolved_spline(), move, True).Shape())
    writer.ComputeModel()
    path = tmp_path / "far.igs"
    assert writer.Write(str(path))
    (face,) = analyse_part(read_part(path))[0].faces
    assert face.kind == "revolution" and 3e-6 < face.tolerance < 3.1e-6
    assert 1e-8 < face.deviation < face.tolerance
    (strict,) = analyse_part(read_part(path), 1e-7)[0].faces
    assert strict.kind == "none" and strict.nearest == "revolution"


def test_the_part_formats_agree() -> None:
    """The window and the part process name the formats without importing Open CASCADE."""
    from sorgui.cad import CAD_SUFFIXES
    from sorgui.cad.reading import FORMATS
    from sorgui.session.part_job import PART_SUFFIXES

    assert PART_SUFFIXES == CAD_SUFFIXES and set(FORMATS) == set(CAD_SUFFIXES)


def test_an_iges_surface_of_revolution_is_read_as_the_cylinder_or_cone_it_is(tmp_path: Path) -> None:
    """IGES writes every face of a revolved profile as a surface of revolution (type 120): a
    cylinder, a cone and a sphere were reported only as "a surface of revolution (as the file
    says)", without their radius, where the same part in STEP gives them."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakeWire
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeRevol
    from OCP.gp import gp_Ax1, gp_Dir, gp_Pnt

    corners = [gp_Pnt(x, 0, z) for x, z in ((0, 0), (10, 0), (10, 20), (6, 30), (0, 30))]
    wire = BRepBuilderAPI_MakeWire()
    for start, end in zip(corners, corners[1:] + corners[:1]):
        wire.Add(BRepBuilderAPI_MakeEdge(start, end).Edge())
    profile = BRepBuilderAPI_MakeFace(wire.Wire()).Face()
    shape = BRepPrimAPI_MakeRevol(profile, gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 2 * math.pi).Shape()
    report, _ = analyse_part(read_part(written(tmp_path, shape, "turned.igs")))
    revolved = [f for f in report.faces if f.type_in_file == "SURFACE_OF_REVOLUTION"]
    assert sorted(f.kind for f in revolved) == ["cone", "cylinder"]
    (cylinder,) = [f for f in revolved if f.kind == "cylinder"]
    assert cylinder.radius == pytest.approx(10) and np.linalg.norm(np.cross(cylinder.axis.direction, [0, 0, 1])) < 1e-9


def test_a_spindle_torus_reads_back_as_a_torus(tmp_path: Path) -> None:
    """Open CASCADE's toroidal surface holds no spindle torus (R < r): sorgui writes it as a
    circle turned about the axis, which its reader called only "a surface of revolution"."""
    spindle = analyze("((x-1)^2+(y-2)^2+(z-3)^2-3)^2-4*((x-1)^2+(y-2)^2)")
    path = export_analysis(spindle, tmp_path / "spindle.step", scene=build_scene(spindle))
    report, _ = analyse_part(read_part(path))
    assert [(f.type_in_file, f.kind) for f in report.faces] == [("SURFACE_OF_REVOLUTION", "torus")]
    (face,) = report.faces
    assert (face.radius, face.minor_radius) == (pytest.approx(1), pytest.approx(2))
    assert face.center == pytest.approx((1, 2, 3))
