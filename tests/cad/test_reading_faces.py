"""The faces of parts built with Open CASCADE, converted to B-spline faces, recognised again
(docs/math.md §12): the right kind, the axis to the tolerance, both deviations within it, and no
kind claimed for a face that has none."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("OCP")

from sorgui.cad.part_report import PartReport, faces_words, text_report  # noqa: E402
from sorgui.cad.reading import faces_of  # noqa: E402
from sorgui.cad.recognition import analyse_part, recognise_face  # noqa: E402

from . import parts  # noqa: E402

TOLERANCE = 1e-7


def report_of(shape, tolerance: float | None = None) -> PartReport:
    report, _ = analyse_part(parts.as_part(shape), tolerance)
    return report


def assert_on_axis(face, within: float = 1e-8) -> None:
    """The face's axis is the parts' placed z axis."""
    point, direction = parts.placed_axis()
    assert face.axis is not None
    d, p = np.array(face.axis.direction), np.array(face.axis.point)
    assert np.linalg.norm(np.cross(d, direction)) < within
    assert np.linalg.norm(np.cross(p - point, direction)) < within


def assert_within(face, tolerance: float = TOLERANCE) -> None:
    assert face.source == "samples" and face.tolerance == tolerance
    assert face.deviation is not None and face.deviation <= tolerance
    assert face.to_surface is not None and face.to_face is not None
    assert max(face.to_surface, face.to_face) == face.deviation


def test_a_revolved_bspline_about_an_oblique_axis() -> None:
    report = report_of(parts.revolved_spline())
    (face,) = report.faces
    assert face.type_in_file == "B_SPLINE_SURFACE" and face.kind == "revolution"
    assert_within(face)
    assert face.deviation < 1e-12
    assert_on_axis(face, 1e-10)
    assert [g.faces for g in report.groups] == [(1,)]


def test_part_of_a_turn_and_a_pole() -> None:
    """A face over 2 radians of a turn, and a dome whose profile starts on the axis."""
    for shape in (parts.revolved_spline(angle=2.0), parts.dome()):
        (face,) = report_of(shape).faces
        assert face.kind == "revolution"
        assert_within(face)
        assert_on_axis(face, 1e-9)


def test_any_parameter_layout() -> None:
    """The angle along ``v`` instead of ``u``, and no parameter line a circle at all (the profile
    is then fitted to the samples): a surface of revolution about the z axis either way."""
    (face,) = report_of(parts.exchanged()).faces
    assert face.kind == "revolution" and face.deviation < 1e-12
    assert_on_axis(face, 1e-9)
    (face,) = report_of(parts.skewed()).faces
    assert face.kind == "revolution"
    assert_within(face)
    assert np.linalg.norm(np.cross(face.axis.direction, [0, 0, 1])) < 1e-8
    assert np.hypot(*face.axis.point[:2]) < 1e-8


def test_noise_on_the_poles_stays_within_the_tolerance() -> None:
    """Poles moved by 1e-9: still a surface of revolution about the axis, the deviation of the
    order of the noise, both ways."""
    (face,) = report_of(parts.noisy(parts.revolved_spline(), 1e-9)).faces
    assert face.kind == "revolution"
    assert_within(face)
    assert 1e-11 < face.deviation < 1e-8
    assert_on_axis(face, 1e-8)


def test_noise_above_the_tolerance_is_no_surface_of_revolution() -> None:
    """Poles moved by 1e-4 with a tolerance of 1e-7: no kind, nearest a surface of revolution."""
    (face,) = report_of(parts.noisy(parts.revolved_spline(), 1e-4)).faces
    assert face.kind == "none" and face.nearest == "revolution"
    assert face.deviation is not None and face.deviation > 1e-6


def test_a_converted_torus() -> None:
    (face,) = report_of(parts.torus()).faces
    assert face.kind == "torus"
    assert_within(face)
    assert_on_axis(face)
    assert (face.radius, face.minor_radius) == (pytest.approx(5, abs=1e-9), pytest.approx(1, abs=1e-9))
    assert np.linalg.norm(np.array(face.center) - parts.ORIGIN) < 1e-9


def test_a_converted_cone_and_its_disks() -> None:
    report = report_of(parts.cone())
    assert [f.kind for f in report.faces] == ["cone", "plane", "plane"]
    side = report.faces[0]
    assert_within(side)
    assert_on_axis(side)
    assert side.half_angle == pytest.approx(np.arctan(1 / 3), abs=1e-9)
    assert np.linalg.norm(np.array(side.center) - parts.placed_point((0, 0, 6))) < 1e-8
    for disk in report.faces[1:]:
        assert_within(disk)
        assert np.linalg.norm(np.cross(np.array(disk.axis.direction), parts.AXIS)) < 1e-9
    assert [g.faces for g in report.groups] == [(1, 2, 3)]


def test_a_converted_sphere_and_cylinder() -> None:
    (ball,) = report_of(parts.sphere()).faces
    assert ball.kind == "sphere" and ball.radius == pytest.approx(2, abs=1e-9)
    assert_within(ball)
    assert np.linalg.norm(np.array(ball.center) - parts.ORIGIN) < 1e-9
    side, *disks = report_of(parts.cylinder()).faces
    assert side.kind == "cylinder" and side.radius == pytest.approx(2, abs=1e-9)
    assert_on_axis(side)
    assert [d.kind for d in disks] == ["plane", "plane"]


def test_a_face_of_no_symmetry_is_none() -> None:
    (face,) = report_of(parts.bumpy()).faces
    assert face.kind == "none" and face.source == "samples"
    assert face.deviation is not None and face.deviation > 1e-3
    assert face.axis is None and face.error is None
    assert "not a surface of revolution" in text_report(report_of(parts.bumpy()))


def test_an_extrusion() -> None:
    (face,) = report_of(parts.extruded()).faces
    assert face.kind == "extrusion"
    assert_within(face)
    assert np.linalg.norm(np.cross(np.array(face.direction), parts.EXTRUSION_DIRECTION)) < 1e-9


def test_a_boolean_part() -> None:
    """Planes, a cylinder and a torus about one axis, a sphere off it: one group, of all but the
    sphere and the box's sides."""
    report = report_of(parts.boolean_part())
    kinds = [f.kind for f in report.faces]
    assert sorted(kinds) == sorted(["plane"] * 6 + ["cylinder", "torus", "sphere"])
    for face in report.faces:
        assert_within(face)
    for face in report.faces:
        if face.kind in ("cylinder", "torus"):
            assert_on_axis(face)
    (group,) = report.groups
    across = [f.face for f in report.faces if f.kind == "plane" and abs(np.dot(f.axis.direction, parts.AXIS)) > 0.99]
    about = [f.face for f in report.faces if f.kind in ("cylinder", "torus")]
    assert group.faces == tuple(sorted(across + about)) and len(across) == 2
    sphere = next(f for f in report.faces if f.kind == "sphere")
    assert np.linalg.norm(np.array(sphere.center) - parts.placed_point((3, 3, 0))) < 1e-9


def test_analytic_faces_are_read_as_the_file_gives_them() -> None:
    report = report_of(parts.placed(parts.BRepPrimAPI_MakeCylinder(2, 5).Shape()))
    assert [(f.type_in_file, f.kind, f.source, f.deviation) for f in report.faces] == [
        ("CYLINDRICAL_SURFACE", "cylinder", "file", 0.0),
        ("PLANE", "plane", "file", 0.0),
        ("PLANE", "plane", "file", 0.0),
    ]
    assert_on_axis(report.faces[0], 1e-12)


def test_a_tolerance_of_the_users() -> None:
    """Noise of 1e-4 on the poles is a surface of revolution within 1e-3, not within 1e-7."""
    shape = parts.noisy(parts.revolved_spline(), 1e-4)
    (loose,) = report_of(shape, 1e-3).faces
    assert loose.kind == "revolution" and loose.tolerance == 1e-3
    assert_on_axis(loose, 1e-3)


def test_a_face_without_a_surface_is_said_in_one_line() -> None:
    from OCP.BRep import BRep_Builder
    from OCP.TopoDS import TopoDS_Face

    face = TopoDS_Face()
    BRep_Builder().MakeFace(face)
    found = recognise_face(face, 4)
    assert found.report.kind == "none" and found.report.error == "the face has no surface"
    assert "\n" not in found.report.error


def test_the_report_reads_back_from_its_json() -> None:
    report = report_of(parts.boolean_part())
    assert PartReport.from_json(report.to_json()) == report
    assert len(faces_of(parts.boolean_part())) == len(report.faces)


def test_many_faces_are_named_in_runs() -> None:
    """A group of the 2000 faces of a long shaft is one short line (runs of three or more)."""
    assert faces_words([4]) == "face 4"
    assert faces_words([3, 7, 9]) == "faces 3, 7, 9"
    assert faces_words([*range(1, 2001), 2003, 2004]) == "faces 1–2000, 2003, 2004"


def test_a_cone_over_a_curve_with_no_ruling_among_its_parameter_lines() -> None:
    """The cone's directrix is taken from a parameter line of the face; with none (the samples lie
    along helices) the face is reported, never an internal error (it was a ValueError)."""
    (face,) = report_of(parts.skewed_cone(), 1e-6).faces
    assert face.error is None and face.kind in ("cone-over-curve", "none")
