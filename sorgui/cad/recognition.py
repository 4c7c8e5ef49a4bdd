"""The faces of a part, recognised: which are planes, spheres, cylinders, cones, tori, surfaces of
revolution, extrusions or cones over a curve, and which share an axis (docs/math.md §12).

A face whose surface the file gives as an analytic one (``PLANE``, ``CYLINDRICAL_SURFACE``,
``SURFACE_OF_REVOLUTION``, …) is read as it is. Any other face (a B-spline, a Bézier or an offset
surface) is sampled over its trimmed domain (:mod:`.sampling`) and fitted by the line complex of
its normals (:mod:`sorgui.engine.rounded.line_complex`): the most special kind whose surface is
within the tolerance of the face both ways (:mod:`.native`) is its kind. The tolerance is the
user's, else the largest of ``1e-7``, the face's own tolerance in the file (how closely its
edges are known to lie on it) and ``1e-9`` of the part's largest coordinate (the precision of
numbers printed with nine digits).

Faces about one axis are grouped: those with one axis (a cylinder, cone, torus or surface of
revolution) when their axes agree (:data:`ANGLE` and :data:`OFFSET`), then the planes across a
group's axis and the spheres centred on it.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.Geom import Geom_Surface
from OCP.GeomAbs import GeomAbs_CurveType, GeomAbs_SurfaceType
from OCP.gp import gp_Ax1
from OCP.TopoDS import TopoDS_Face

from sorgui.engine.results import ApproximateAxis
from sorgui.engine.rounded import line_complex as lc
from sorgui.engine.rounded.line_complex import SurfaceFit
from sorgui.render.geometry import foot_on_line

from . import native as nat
from .failures import OCCT_ERRORS, from_occt
from .part_report import AxisGroup, FaceReport, PartReport
from .reading import Part
from .sampling import FaceError, FaceSamples, sample_face

DEFAULT_TOLERANCE = 1e-7
"""The least tolerance of a face (length units of the file, millimetres)."""
DIGITS = 1e-9
"""The least tolerance relative to the part's largest coordinate: the precision of numbers
printed with nine significant digits, as IGES files often are."""
ANGLE = 1e-6
"""Two axes are one when their directions differ by less than this (radians) …"""
OFFSET = 1e-5
"""… and they pass within this fraction of the part's size (plus ten tolerances) of each other
across the part."""
MISS_LIMIT = 1e-3
"""A rotation is tried as a face's axis only when every normal passes within this fraction of
the face's size of it (the quick test before a profile is fitted)."""

T = GeomAbs_SurfaceType
FILE_TYPES = {
    T.GeomAbs_Plane: "PLANE",
    T.GeomAbs_Cylinder: "CYLINDRICAL_SURFACE",
    T.GeomAbs_Cone: "CONICAL_SURFACE",
    T.GeomAbs_Sphere: "SPHERICAL_SURFACE",
    T.GeomAbs_Torus: "TOROIDAL_SURFACE",
    T.GeomAbs_BezierSurface: "BEZIER_SURFACE",
    T.GeomAbs_BSplineSurface: "B_SPLINE_SURFACE",
    T.GeomAbs_SurfaceOfRevolution: "SURFACE_OF_REVOLUTION",
    T.GeomAbs_SurfaceOfExtrusion: "SURFACE_OF_LINEAR_EXTRUSION",
    T.GeomAbs_OffsetSurface: "OFFSET_SURFACE",
    T.GeomAbs_OtherSurface: "SURFACE",
}
"""What a file calls each kind of surface Open CASCADE reads (STEP's entity names)."""


@dataclass(frozen=True)
class Recognised:
    """A face's report, and the native surface that may replace it (a recognised face whose
    file surface is not already analytic)."""

    report: FaceReport
    surface: Geom_Surface | None = None


def analyse_part(
    part: Part, tolerance: float | None = None, progress: Callable[[int, int], None] | None = None
) -> tuple[PartReport, list[Recognised]]:
    """Every face of ``part`` recognised (``progress(done, total)`` after each), and the groups."""
    started = time.monotonic()
    floor = DIGITS * _reach(part)
    found = []
    for number, face in enumerate(part.faces, start=1):
        found.append(recognise_face(face, number, tolerance, floor))
        if progress is not None:
            progress(number, len(part.faces))
    reports = [r.report for r in found]
    report = PartReport(
        file=str(part.path),
        format=part.format,
        units="mm",
        faces=tuple(reports),
        groups=group_faces(reports, _size(part)),
        warnings=part.warnings,
        seconds=time.monotonic() - started,
    )
    return report, found


def face_tolerance(face: TopoDS_Face, tolerance: float | None, floor: float = 0.0) -> float:
    """The user's tolerance, else the largest of :data:`DEFAULT_TOLERANCE`, the face's own and
    ``floor`` (the numbers' precision, :data:`DIGITS` of the part's largest coordinate)."""
    if tolerance is not None:
        return tolerance
    return max(DEFAULT_TOLERANCE, float(BRep_Tool.Tolerance_s(face)), floor)


FACE_FAULTS: tuple[type[Exception], ...] = (FaceError, *OCCT_ERRORS)
"""What makes a face ``none`` with the reason: a face that cannot be sampled, a fault of Open CASCADE."""


def recognise_face(face: TopoDS_Face, number: int, tolerance: float | None = None, floor: float = 0.0) -> Recognised:
    """What face ``number`` is (an evaluation fault of Open CASCADE makes it ``none`` with the
    reason); ``floor`` as for :func:`face_tolerance`."""
    tol = face_tolerance(face, tolerance, floor)
    try:
        if BRep_Tool.Surface_s(face) is None:
            raise FaceError("the face has no surface")
        adaptor = BRepAdaptor_Surface(face, True)
        kind = adaptor.GetType()
        name = FILE_TYPES.get(kind, "SURFACE")
        read = _as_in_file(adaptor, kind, number, name, tol)
        if read is not None and read.kind == lc.REVOLUTION:
            special = _recognised(face, number, name, tol)  # IGES writes a cylinder, a torus, … so
            if special.report.kind in lc.ANALYTIC:
                return special
        if read is not None:
            return Recognised(read)
        return _recognised(face, number, name, tol)
    except FACE_FAULTS as exc:
        said = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
        reason = said or type(exc).__name__
        if from_occt(exc):
            reason = f"Open CASCADE raises {type(exc).__name__}" + (f": {said}" if said else "")
        name = "SURFACE"
        if BRep_Tool.Surface_s(face) is not None:
            try:
                name = FILE_TYPES.get(BRepAdaptor_Surface(face, False).GetType(), "SURFACE")
            except OCCT_ERRORS:
                pass
        return Recognised(FaceReport(number, name, lc.NONE, None, tol, "samples", error=reason))


def _as_in_file(
    adaptor: BRepAdaptor_Surface, kind: GeomAbs_SurfaceType, number: int, name: str, tol: float
) -> FaceReport | None:
    """The report of a face whose surface the file gives as an analytic one (``None`` otherwise)."""
    report = FaceReport(number, name, lc.NONE, 0.0, tol, "file")
    if kind == T.GeomAbs_Plane:
        plane = adaptor.Plane()
        location, n = plane.Location(), plane.Axis().Direction()
        normal = np.array([n.X(), n.Y(), n.Z()])
        foot = (np.array([location.X(), location.Y(), location.Z()]) @ normal) * normal  # the origin, onto the plane
        on_plane = lc.axis_of(foot, normal, foot)
        return replace(report, kind=lc.PLANE, axis=on_plane)
    if kind == T.GeomAbs_Cylinder:
        cylinder = adaptor.Cylinder()
        return replace(report, kind=lc.CYLINDER, axis=_axis(cylinder.Axis()), radius=cylinder.Radius())
    if kind == T.GeomAbs_Cone:
        cone = adaptor.Cone()
        apex = cone.Apex()
        return replace(
            report,
            kind=lc.CONE,
            axis=_axis(cone.Axis()),
            center=(apex.X(), apex.Y(), apex.Z()),
            half_angle=abs(cone.SemiAngle()),
        )
    if kind == T.GeomAbs_Sphere:
        sphere = adaptor.Sphere()
        centre = sphere.Location()
        return replace(report, kind=lc.SPHERE, center=(centre.X(), centre.Y(), centre.Z()), radius=sphere.Radius())
    if kind == T.GeomAbs_Torus:
        torus = adaptor.Torus()
        centre = torus.Location()
        return replace(
            report,
            kind=lc.TORUS,
            axis=_axis(torus.Axis()),
            center=(centre.X(), centre.Y(), centre.Z()),
            radius=torus.MajorRadius(),
            minor_radius=torus.MinorRadius(),
        )
    if kind == T.GeomAbs_SurfaceOfRevolution:
        axis = adaptor.AxeOfRevolution()
        return _turned_circle(report, axis, adaptor.BasisCurve()) or replace(
            report, kind=lc.REVOLUTION, axis=_axis(axis)
        )
    if kind == T.GeomAbs_SurfaceOfExtrusion:
        d = adaptor.Direction()
        return replace(report, kind=lc.EXTRUSION, direction=_canonical_direction((d.X(), d.Y(), d.Z())))
    return None


def _turned_circle(report: FaceReport, axis: gp_Ax1, curve: Any) -> FaceReport | None:  # noqa: ANN401 - an Adaptor3d_Curve
    """A torus (a spindle torus too, which Open CASCADE's toroidal surface does not hold and
    sorgui writes as a circle turned about the axis) when the turned curve is a circle in a plane
    through the axis; ``None`` otherwise."""
    if curve.GetType() != GeomAbs_CurveType.GeomAbs_Circle:
        return None
    circle = curve.Circle()
    c, n = circle.Location(), circle.Axis().Direction()
    p, d = axis.Location(), axis.Direction()
    centre, normal = np.array([c.X(), c.Y(), c.Z()]), np.array([n.X(), n.Y(), n.Z()])
    point, direction = np.array([p.X(), p.Y(), p.Z()]), np.array([d.X(), d.Y(), d.Z()])
    foot = foot_on_line(centre, point, direction)
    major = float(np.linalg.norm(centre - foot))
    scale = max(major, circle.Radius())
    if abs(normal @ direction) > PLANAR or abs((centre - point) @ normal) > PLANAR * scale or major <= PLANAR * scale:
        return None
    return replace(
        report,
        kind=lc.TORUS,
        axis=_axis(axis),
        center=(float(foot[0]), float(foot[1]), float(foot[2])),
        radius=major,
        minor_radius=circle.Radius(),
    )


PLANAR = 1e-9
"""How far off the axis's plane (relative) a turned circle may be and make a torus."""


def _axis(axis: gp_Ax1) -> ApproximateAxis:
    p, d = axis.Location(), axis.Direction()
    return lc.axis_of(np.array([p.X(), p.Y(), p.Z()]), np.array([d.X(), d.Y(), d.Z()]), np.zeros(3))


def _canonical_direction(d: tuple[float, float, float]) -> tuple[float, float, float]:
    return lc.axis_of(np.zeros(3), np.array(d), np.zeros(3)).direction


def _recognised(face: TopoDS_Face, number: int, name: str, tol: float) -> Recognised:
    """The most special kind within ``tol`` of the sampled face, both ways."""
    samples = sample_face(face)
    tried: list[tuple[float, str]] = []
    for fit in lc.analytic_fits(samples.samples, tol):
        assert fit.deviation is not None
        tried.append((fit.deviation, fit.kind))
        if fit.deviation > tol:
            continue
        found = nat.measured(nat.analytic_surface(fit, face), face, samples, tol, fit.deviation)
        tried[-1] = (found.deviation, fit.kind)
        if found.deviation <= tol:
            return Recognised(_report(number, name, tol, fit, found), found.surface)
    for fit in _general_fits(samples, tol):
        surface = nat.swept_surface(fit, face, samples)
        if surface is None:
            continue
        found = nat.measured(surface, face, samples, tol)
        tried.append((found.deviation, fit.kind))
        if found.deviation <= tol:
            rewritable = fit.kind != lc.CONE_OVER_CURVE
            return Recognised(_report(number, name, tol, fit, found), found.surface if rewritable else None)
    deviation, nearest = min(tried, default=(None, None))
    return Recognised(FaceReport(number, name, lc.NONE, deviation, tol, "samples", nearest=nearest))


def _general_fits(samples: FaceSamples, tol: float) -> list[SurfaceFit]:
    """The surface of revolution, extrusion and cone over a curve worth a profile: those whose
    normals pass the quick test (they meet the axis, are across the direction, have tangent
    planes through the apex, within :data:`MISS_LIMIT` of the face's size)."""
    s = samples.samples
    limit = max(MISS_LIMIT * s.size, 10 * tol)
    fits = []
    revolution = lc.revolution_fit(s)
    if revolution is not None and revolution.axis is not None and lc.normal_miss(s, revolution.axis).max() <= limit:
        fits.append(revolution)
    extrusion = lc.extrusion_fit(s)
    assert extrusion.direction is not None
    if float(np.abs(s.normals @ np.array(extrusion.direction)).max()) * s.size <= limit:
        fits.append(extrusion)
    cone = lc.cone_over_curve_fit(s)
    assert cone.deviation is not None
    if cone.deviation <= limit and _finite_apex(cone, s):
        fits.append(cone)
    return fits


def _finite_apex(fit: SurfaceFit, samples: lc.Samples) -> bool:
    """Whether a cone's apex is near enough to be one (not a cylinder's apex at infinity)."""
    assert fit.center is not None
    return bool(np.linalg.norm(np.array(fit.center) - samples.origin) < 1e3 * samples.size)


def _report(number: int, name: str, tol: float, fit: SurfaceFit, found: nat.Native) -> FaceReport:
    return FaceReport(
        face=number,
        type_in_file=name,
        kind=fit.kind,
        deviation=found.deviation,
        tolerance=tol,
        source="samples",
        axis=fit.axis,
        center=fit.center,
        direction=fit.direction,
        radius=fit.radius,
        minor_radius=fit.minor_radius,
        half_angle=fit.half_angle,
        to_surface=found.to_surface,
        to_face=found.to_face,
    )


def _reach(part: Part) -> float:
    """The largest absolute coordinate of the part's bounding box."""
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib

    box = Bnd_Box()
    BRepBndLib.Add_s(part.shape, box, False)
    if box.IsVoid():
        return 0.0
    return float(np.abs([*box.CornerMin().Coord(), *box.CornerMax().Coord()]).max())


def _size(part: Part) -> float:
    """The radius of the part's bounding box (for comparing axes across it)."""
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib

    box = Bnd_Box()
    BRepBndLib.Add_s(part.shape, box, False)
    if box.IsVoid():
        return 1.0
    low, high = np.array(box.CornerMin().Coord()), np.array(box.CornerMax().Coord())
    return max(float(np.linalg.norm(high - low)) / 2, 1e-12)


# --- faces about one axis --------------------------------------------------------------------------


def same_axis(a: ApproximateAxis, b: ApproximateAxis, size: float, tol: float) -> bool:
    """Whether two axes are one line across a part of radius ``size``."""
    da, db = np.array(a.direction), np.array(b.direction)
    if np.linalg.norm(np.cross(da, db)) > ANGLE:
        return False
    return _distance_to_line(np.array(b.point), a) <= OFFSET * size + 10 * tol


def _distance_to_line(point: np.ndarray, axis: ApproximateAxis) -> float:
    c, d = np.array(axis.point), np.array(axis.direction)
    return float(np.linalg.norm(np.cross(point - c, d)))


def group_faces(faces: Sequence[FaceReport], size: float) -> tuple[AxisGroup, ...]:
    """The faces about each axis that a cylinder, cone, torus or surface of revolution has, with
    the planes across it and the spheres centred on it; axes in the order of their first face."""
    groups: list[tuple[ApproximateAxis, list[FaceReport]]] = []
    for face in faces:
        if face.kind not in lc.AXIAL or face.axis is None:
            continue
        for axis, members in groups:
            if same_axis(axis, face.axis, size, max(face.tolerance, members[0].tolerance)):
                members.append(face)
                break
        else:
            groups.append((face.axis, [face]))
    out = []
    for _, members in groups:
        best = min(members, key=lambda f: f.deviation if f.deviation is not None else np.inf)
        assert best.axis is not None
        axis = best.axis
        joined = list(members)
        for face in faces:
            if face in members:
                continue
            if face.kind == lc.PLANE and face.axis is not None:
                if np.linalg.norm(np.cross(np.array(face.axis.direction), np.array(axis.direction))) <= ANGLE:
                    joined.append(face)
            elif face.kind == lc.SPHERE and face.center is not None:
                if _distance_to_line(np.array(face.center), axis) <= OFFSET * size + 10 * face.tolerance:
                    joined.append(face)
        joined.sort(key=lambda f: f.face)
        out.append(AxisGroup(tuple(f.face for f in joined), axis, tuple(f.kind for f in joined)))
    return tuple(out)
