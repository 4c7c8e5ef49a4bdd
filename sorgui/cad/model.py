"""The B-rep of one analysis: which faces a CAD file gets, and what is said about them.

:func:`surface_model` turns a surface of revolution into faces, preferring, in this order, an
analytic surface, the exact rational profile, and a fitted profile (:mod:`.geometry`);
:func:`patch_model` turns the first verified real parameterization into rational Bézier
patches (:mod:`.patch`). Both return a :class:`CadModel`: the shape, the route taken, the
tolerance and the deviation measured afterwards, and lines for the file's header.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np
import sympy

from sorgui.engine.results import Analysis
from sorgui.engine.values import ExpressionError
from sorgui.numerics import without_noise
from sorgui.render import PATCH_RANGE, ClipBox, ClipSphere, LineData
from sorgui.render.geometry import foot_on_line

from . import shapes
from .geometry import (
    Analytic,
    CadGeometryError,
    Distance,
    Frame,
    MeridianCurve,
    RationalCurve,
    analytic_surface,
    axis_frame,
    exact_profile,
    meridian_curve,
    onto_profile,
    polyline_distance,
    profile_distance,
    traced_profile,
)
from .patch import bezier_patches

FIT_TOLERANCE = 1e-7
"""The default tolerance of a fitted profile, relative to the drawn ball's radius."""

REFINEMENTS = 6
"""How many times the spans of a fitted branch that miss the tolerance are halved, at most
(a span shorter than the tolerance is not halved: its curve cannot stray further)."""

MAX_POINTS = 5_000
"""The most points a fitted branch interpolates."""


class Scene(Protocol):
    """What a CAD export needs of a scene (``sorgui.session.scene_data.SceneData`` has it):
    the drawn ball, the traced profile in it, and the user's box, if one was given."""

    @property
    def region(self) -> ClipSphere: ...

    @property
    def profile_curve(self) -> LineData: ...

    @property
    def box(self) -> ClipBox | None: ...


@dataclass(frozen=True)
class CadModel:
    """Faces for a CAD file. ``route`` is ``"analytic"``, ``"exact"``, ``"fitted"`` or ``"patch"``;
    ``deviation`` the largest distance measured from the written surface to ``X`` (``None``
    where it is exact by construction) and ``tolerance`` the one the fit aimed at."""

    shape: Any
    route: str
    description: tuple[str, ...]
    deviation: float | None = None
    tolerance: float | None = None

    @property
    def faces(self) -> int:
        """How many faces the shape holds."""
        return len(shapes.faces_of(self.shape))


def surface_model(analysis: Analysis, scene: Scene, tolerance: float | None = None) -> CadModel:
    """The faces of a surface of revolution (or a plane or sphere) inside the scene's ball,
    cut to the user's box if there is one."""
    return _cut(_surface_model(analysis, scene, tolerance), scene.box)


def _surface_model(analysis: Analysis, scene: Scene, tolerance: float | None) -> CadModel:
    rec = analysis.recognition
    if rec.symmetry == "undecided":
        raise CadGeometryError(
            "the analysis did not finish, so it is not known whether the surface is one of revolution"
        )
    if not rec.is_sor:
        raise CadGeometryError(
            "the surface is not a surface of revolution; write NAME.patch.step for a rational parameterization"
        )
    ball = scene.region
    frame = axis_frame(rec.profile) if rec.profile is not None else None
    if frame is not None and _off_axis(ball, frame):
        raise CadGeometryError(
            "a CAD file of a surface of revolution is cut to a ball centred on its axis or to a box; "
            "give the ball's radius alone (--region R) or a box (--region X0:X1,Y0:Y1,Z0:Z1)"
        )
    spec = analytic_surface(analysis, ball)
    if spec is not None:
        shape = shapes.shell(shapes.analytic_faces(spec))
        if not _inside(spec, ball):
            shape = shapes.cut_to(shape, ball)
        return CadModel(shape, "analytic", _analytic_lines(spec))
    if rec.profile is None or rec.axis is None or frame is None:
        if rec.symmetry == "sphere":  # (x² + y² + z² + 1)³⁰ − 2: spheres about one centre
            raise CadGeometryError(
                f"the surface of degree {rec.degree} has a sphere's symmetry but is not a sphere of degree 2 "
                "(spheres about one centre, of radii outside its field): a CAD file is written of a sphere of degree 2"
            )
        raise CadGeometryError(f"a {rec.symmetry} surface has no single axis to turn a profile about")
    curve = meridian_curve(rec.profile, frame, ball)
    branches = traced_profile(scene.profile_curve.polylines(), curve)
    if not branches:
        raise CadGeometryError("the surface has no real points inside the drawn ball")
    axis = _axis_line(frame.point, frame.direction)
    exact = exact_profile(analysis, frame, ball, ball.radius)
    if exact is not None and _covers(exact, branches, ball.radius):
        faces = shapes.revolution_faces(frame, [shapes.bspline_curve(c) for c in exact])
        lines = (axis, f"profile: exact rational B-spline, {len(exact)} arcs, degree {exact[0].degree}")
        return CadModel(shapes.shell(faces), "exact", lines)
    goal = (tolerance if tolerance is not None else FIT_TOLERANCE) * ball.radius
    distance = profile_distance(curve, floor=goal / 10)
    fits = [_fit(branch, goal, distance, curve) for branch in branches]
    deviation = max(f.deviation for f in fits)
    faces = shapes.revolution_faces(frame, [f.curve for f in fits])
    verdict = "within" if deviation <= goal else "ABOVE"
    lines = (
        axis,
        f"profile: B-spline fitted to tolerance {goal:.3g}; measured deviation {deviation:.3g} ({verdict} it)",
    )
    return CadModel(shapes.shell(faces), "fitted", lines, deviation, goal)


def _off_axis(ball: ClipSphere, frame: Frame) -> bool:
    """Whether the ball's centre is off the axis: its disk would then differ from one meridian
    half-plane to the next, and a revolved profile cut to one of them would not be the part in
    the ball."""
    centre = np.asarray(ball.center)
    return float(np.linalg.norm(centre - foot_on_line(centre, frame.point, frame.direction))) > 1e-9 * ball.radius


def _inside(spec: Analytic, ball: ClipSphere) -> bool:
    """Whether a whole sphere or torus lies in ``ball`` (the other kinds are built inside it)."""
    if spec.kind not in ("sphere", "torus"):
        return True
    reach = spec.radius + spec.minor_radius
    return float(np.linalg.norm(spec.origin - np.asarray(ball.center))) + reach <= ball.radius


def _cut(model: CadModel, box: ClipBox | None) -> CadModel:
    """``model`` cut to the user's ``box``; an error if nothing of it is left. A cut that leaves
    the box (Open CASCADE misses some intersections of revolved B-spline profiles) is done again
    on the faces converted to B-spline surfaces, and the file says so."""
    if box is None:
        return model
    low, high = box.bounds[0::2], box.bounds[1::2]
    lines = [*model.description, f"cut to the box {_vector(np.array(low))} - {_vector(np.array(high))}"]
    shape = shapes.cut_to(model.shape, box)
    if not shapes.within(shape, box):
        shape = shapes.cut_to(shapes.as_nurbs(model.shape), box)
        lines.append("faces converted to B-spline surfaces to be cut to the box")
        if not shapes.within(shape, box):
            raise CadGeometryError("Open CASCADE could not cut the faces to the box")
    if not shapes.faces_of(shape):
        raise CadGeometryError("the surface has no real points inside the box")
    return dataclasses.replace(model, shape=shape, description=tuple(lines))


def _fit(branch: np.ndarray, goal: float, distance: Distance, curve: MeridianCurve) -> shapes.Fit:
    """A curve through the branch's points within ``goal``: every span whose measured distance to
    the profile is larger is halved (its midpoint moved onto the profile), and the curve drawn
    again, at most :data:`REFINEMENTS` times and up to :data:`MAX_POINTS` points."""
    points = _distinct(branch, goal)
    fit = shapes.fitted_curve(points, distance)
    for _ in range(REFINEMENTS):
        length = np.linalg.norm(np.diff(points, axis=0), axis=1)
        wide = np.flatnonzero((fit.spans > goal) & (length > goal))
        if len(wide) == 0 or len(points) + len(wide) > MAX_POINTS:
            break
        halves = curve.frame.to_plane((points[wide] + points[wide + 1]) / 2)
        middles = curve.frame.to_space(onto_profile(curve.terms, halves))
        points = _distinct(np.insert(points, wide + 1, middles, axis=0), goal)
        fit = shapes.fitted_curve(points, distance)
    return fit


def _distinct(points: np.ndarray, gap: float) -> np.ndarray:
    """``points`` without those closer than ``gap / 100`` to the one before (interpolation needs
    distinct points)."""
    step = np.linalg.norm(np.diff(points, axis=0), axis=1)
    keep = np.concatenate([[True], step > gap / 100])
    kept: np.ndarray = points[keep]
    return kept


def _covers(curves: Sequence[RationalCurve], branches: Sequence[np.ndarray], size: float) -> bool:
    """Whether every traced point of the real profile lies on one of the exact arcs (a
    parameterization of one component of a reducible profile does not cover the others)."""
    polylines = [c.points(200) for c in curves]
    for branch in branches:
        probe = branch[:: max(1, len(branch) // 40)]
        near = np.min([polyline_distance(probe, p) for p in polylines], axis=0)
        if np.any(near > 1e-3 * size):
            return False
    return True


def _axis_line(point: np.ndarray, direction: np.ndarray) -> str:
    return f"axis: point {_vector(point)}, direction {_vector(direction)}"


def _vector(v: np.ndarray) -> str:
    return "(" + ", ".join(f"{c:.17g}" for c in without_noise([float(c) for c in v])) + ")"


def _analytic_lines(spec: Analytic) -> tuple[str, ...]:
    words = {
        "plane": f"plane through {_vector(spec.origin)} with normal {_vector(spec.direction)}",
        "sphere": f"sphere about {_vector(spec.origin)}, radius {spec.radius:.17g}",
        "cylinder": f"cylinder of radius {spec.radius:.17g}",
        "cone": f"cone with apex {_vector(spec.origin)}, half-angle {spec.semi_angle:.17g} rad",
        "torus": f"torus about {_vector(spec.origin)}, radii {spec.radius:.17g} and {spec.minor_radius:.17g}",
    }
    lines = [words[spec.kind]]
    if spec.kind in ("cylinder", "cone", "torus"):
        lines.insert(0, _axis_line(spec.origin, spec.direction))
    return tuple(lines)


def patch_model(analysis: Analysis, box: ClipBox | None = None) -> CadModel:
    """The first verified real rational parameterization (of ``X``, of a canal surface by its
    circles, of a cone or cylinder by its lines) over the window's parameter box, cut to the
    user's ``box`` if there is one."""
    candidates = [
        *analysis.parametrizations,
        *(analysis.canal.parametrizations if analysis.canal is not None else ()),
        *(analysis.conical.parametrizations if analysis.conical is not None else ()),
    ]
    for param in candidates:
        if not (param.real and param.verified):
            continue
        try:
            patches = bezier_patches(param)
        except (CadGeometryError, ExpressionError, sympy.PolynomialError):
            continue
        faces = [shapes.patch_face(p) for p in patches]
        low, high = PATCH_RANGE
        lines = (f"rational B-spline patch of the parameterization ({param.method}) over s, t in [{low:g}, {high:g}]",)
        return _cut(CadModel(shapes.shell(faces), "patch", lines), box)
    raise CadGeometryError("the analysis has no verified real rational parameterization to write as a patch")
