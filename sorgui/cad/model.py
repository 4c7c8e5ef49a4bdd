"""The B-rep of one analysis: which faces a CAD file gets, and what is said about them.

:func:`surface_model` turns a surface of revolution into faces, preferring, in this order, an
analytic surface, the exact rational profile, and a fitted profile (:mod:`.geometry`);
:func:`patch_model` turns the first verified real parameterization into rational Bézier
patches (:mod:`.patch`). Both return a :class:`CadModel`: the shape, the route taken, the
tolerance and the deviation measured afterwards, and lines for the file's header.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np
import sympy
from OCP.BRepCheck import BRepCheck_Analyzer

from sorgui.engine.patches import nearest_surface, own_maps, patch_stand_in
from sorgui.engine.results import Analysis
from sorgui.engine.values import ExpressionError, polynomial_terms, zero_set_profile
from sorgui.engine.vocabulary import kind_noun
from sorgui.numerics import without_noise
from sorgui.render import PATCH_RANGES, ClipBox, ClipSphere, LineData, MeshData

from . import shapes
from .canal import Sweep, canal_sweep
from .caps import capped
from .conical import Extrusion, Ruled, lined_part
from .coverage import missing
from .factors import factor_parts
from .fitted import FIT_TOLERANCE, fitted_arc, uncovered
from .geometry import (
    ON_AXIS,
    Analytic,
    CadGeometryError,
    Frame,
    analytic_surfaces,
    axis_frame,
    exact_profile,
    off_axis,
)
from .meridian import meridian_curve, profile_arcs, profile_distance
from .nearest import nearest_lines, nearest_scene, typed_deviation
from .patch import bezier_patches
from .reading import faces_of
from .sewing import CONFUSION, assemble, check_size, compound, precision, solids_of

FULL_PRECISION = 1e-13
"""A rounding read off the digits below this (14 significant digits and more) is that of a
double printed in full: the CAD system's own arithmetic erred more, and no simple exact surface
lies that close; a given ``--tolerance`` finds one."""

EXACT_COVERAGE = 1e-6
"""Exact arcs must pass this close (relative to the ball's radius) to every point of the real
profile (a parameterization of one component of a reducible profile does not)."""


class Scene(Protocol):
    """What a CAD export needs of a scene (``sorgui.session.scene_data.SceneData`` has it):
    the drawn ball, the traced profile in it, the user's box, if one was given, and the mesh of
    the surface in the region (its vertices check that the part covers the surface)."""

    @property
    def region(self) -> ClipSphere: ...

    @property
    def profile_curve(self) -> LineData: ...

    @property
    def box(self) -> ClipBox | None: ...

    @property
    def surface(self) -> MeshData: ...


@dataclass(frozen=True)
class CadModel:
    """A part for a CAD file: its ``shape`` (sewn: one shell or solid, or a compound of them),
    the ``route`` taken (``"analytic"``, ``"exact"``, ``"fitted"`` or ``"patch"``), lines for the
    file's header, the largest distance measured between the part and ``X`` (``None`` where it
    is exact by construction), the ``tolerance`` a fit aimed at, and the ``precision`` of its
    edges and vertices (the STEP file's uncertainty)."""

    shape: Any
    route: str
    description: tuple[str, ...]
    deviation: float | None = None
    tolerance: float | None = None
    precision: float = CONFUSION
    typed_deviation: float | None = None
    """For rounded input written as its nearest exact surface: the part's measured distance from
    the typed surface."""
    beyond_rounding: bool = False
    """That nearest exact surface lies beyond the input's rounding (none simple was found within
    it): the part is the nearest found, and says so."""
    file_note: str = ""
    """What the file written holds beyond the route, in words (a STEP file written again with
    B-spline faces, :data:`.writers.BSPLINE_NOTE`)."""

    @property
    def faces(self) -> int:
        """How many faces the shape holds."""
        return len(faces_of(self.shape))

    @property
    def solids(self) -> int:
        """How many solids the shape holds (closed parts)."""
        return solids_of(self.shape)


@dataclass(frozen=True)
class Faces:
    """The faces of a part before they are cut to the user's box and sewn."""

    faces: list[Any]
    route: str
    description: tuple[str, ...]
    deviation: float | None = None
    tolerance: float | None = None
    groups: tuple[int, ...] = ()
    """A label for each face, if they fall into groups sewn apart (patches on either side of a
    fold of their map, which meet only where it folds)."""


def surface_model(analysis: Analysis, scene: Scene, tolerance: float | None = None, cap: bool = False) -> CadModel:
    """The part of a surface of revolution (or of planes or spheres) inside the scene's ball, cut
    to the user's box if there is one, sewn and checked; for rounded input, the part of the
    nearest exact surface (:mod:`.nearest`)."""
    nearest = nearest_surface(analysis)
    if nearest is not None and nearest.analysis is not None:
        exact = nearest.analysis
        exact_scene = nearest_scene(scene, exact)
        model = surface_model(exact, exact_scene, tolerance)
        deviation = typed_deviation(model.shape, analysis.squarefree, scene)
        lines = (*nearest_lines(nearest, deviation), *model.description)
        model = dataclasses.replace(
            model, description=lines, typed_deviation=deviation, beyond_rounding=not nearest.within_rounding
        )
        return _capped(model, exact_scene, analysis.recognition.polynomial) if cap else model
    size = scene.region.radius
    check_size(size)
    check_size(_drawn_extent(scene))
    own = _of_its_zero_set(analysis)
    faces = _surface_faces(own, scene, tolerance, precision(size))
    try:
        model = finished(faces, scene, analysis.squarefree)
    except CadGeometryError:
        if faces.route != "analytic" or len(analysis.factors) > 1 or own.recognition.profile is None:
            raise
        # Open CASCADE's Boolean of an analytic torus with a ball through its tube can leave an
        # invalid part; the profile's arcs are cut to the ball's disk before they are turned
        faces = _surface_faces(own, scene, tolerance, precision(size), analytic=False)
        model = finished(faces, scene, analysis.squarefree)
    return _capped(model, scene, analysis.recognition.polynomial) if cap else model


def _drawn_extent(scene: Scene) -> float:
    """The diagonal of the box around the drawn surface's points (the ball's radius when none
    is drawn): a torus of R = 3e-6 in its ball of radius 1.4e-4 passed the size check of the
    ball, and its fitted profile was then said to need "a larger fit tolerance"."""
    points = scene.surface.points
    if len(points) == 0:
        return scene.region.radius
    return float(np.linalg.norm(points.max(axis=0) - points.min(axis=0)))


def _of_its_zero_set(analysis: Analysis) -> Analysis:
    """``analysis`` with the profile of its zero set (:func:`~sorgui.engine.values.zero_set_profile`):
    a power's profile, ``g^k``'s, changes no sign, so no point of it settles by Newton's method."""
    rec = analysis.recognition
    if rec.profile is None:
        return analysis
    return dataclasses.replace(analysis, recognition=dataclasses.replace(rec, profile=zero_set_profile(rec.profile)))


def finished(part: Faces, scene: Scene, polynomial: str) -> CadModel:
    """The faces cut to the user's box, sewn into shells and solids (each group apart), checked
    (:func:`.sewing.assemble`); an error if nothing is left."""
    size = scene.region.radius
    terms = polynomial_terms(polynomial)
    labels = part.groups or (0,) * len(part.faces)
    pieces, lines = [], part.description
    for label in sorted(set(labels)):
        group = dataclasses.replace(part, faces=[f for f, g in zip(part.faces, labels) if g == label], groups=())
        faces, lines = _cut(group, scene, precision(size))
        if faces:
            pieces.append(assemble(faces, size, terms))
    if not pieces:
        raise CadGeometryError("the surface has no real points inside the box")
    shape = pieces[0] if len(pieces) == 1 else compound(pieces)
    return CadModel(shape, part.route, lines, part.deviation, part.tolerance, precision(size))


def _capped(model: CadModel, scene: Scene, typed: str) -> CadModel:
    """``model`` capped by the region (the scene's box, else its ball) into the solid ``f ≤ 0``
    inside it, ``f`` as typed (``typed``): its sign, which the square-free part and the nearest
    exact surface do not keep, says which side is the solid. The deviations stay those of the
    surface's faces, measured before the caps were added."""
    region = scene.box if scene.box is not None else scene.region
    shape = capped(model.shape, region, polynomial_terms(typed), model.precision)
    if not BRepCheck_Analyzer(shape).IsValid():
        raise CadGeometryError("Open CASCADE finds the capped solid invalid (BRepCheck)")
    kind = "box" if scene.box is not None else "ball"
    lines = (*model.description, f"capped by the {kind}: the solid f <= 0 inside it")
    return dataclasses.replace(model, shape=shape, description=lines)


def _surface_faces(
    analysis: Analysis, scene: Scene, tolerance: float | None, edge: float, analytic: bool = True
) -> Faces:
    rec = analysis.recognition
    if not rec.decided:
        raise CadGeometryError(
            "the analysis did not finish, so it is not known whether the surface is one of revolution"
        )
    if not rec.is_sor:
        lined = lined_part(analysis, scene.region)
        if lined is not None:
            return _lined_faces(lined, scene.region, edge)
        goal = (tolerance if tolerance is not None else FIT_TOLERANCE) * scene.region.radius
        sweep = canal_sweep(analysis, scene.region, goal, edge)
        if sweep is not None:
            return _swept_faces(sweep, scene.region, goal)
        raise CadGeometryError(_no_part_words(analysis))
    ball = scene.region
    specs = analytic_surfaces(analysis, ball) if analytic else None
    if specs is not None:
        faces = []
        for spec in specs:
            made = shapes.analytic_faces(spec, edge)
            faces += made if _inside(spec, ball) else shapes.cut_to(made, ball)
        if not faces:
            raise _nothing_inside(ball)
        return Faces(faces, "analytic", tuple(line for spec in specs for line in _analytic_lines(spec)))
    if len(analysis.factors) > 1:
        return _factor_faces(analysis, scene, tolerance, edge)
    # a sphere's or a plane's profile is about a chosen line, not an axis of its own
    frame = axis_frame(rec.profile) if rec.profile is not None and rec.axis is not None else None
    if frame is not None and _off_axis(ball, frame):
        raise CadGeometryError(
            "a CAD file of a surface of revolution is cut to a ball centred on its axis or to a box; "
            "give the ball's radius alone (--region R) or a box (--region X0:X1,Y0:Y1,Z0:Z1)"
        )
    if rec.profile is None or rec.axis is None or frame is None:
        raise CadGeometryError(f"a {rec.symmetry} surface has no single axis to turn a profile about")
    curve = meridian_curve(rec.profile, frame, ball)
    arcs = profile_arcs(scene.profile_curve.polylines(), curve, ball)
    if not arcs:
        raise _nothing_inside(ball)
    axis = _axis_line(frame.point, frame.direction)
    goal = (tolerance if tolerance is not None else FIT_TOLERANCE) * ball.radius
    surface = scene.surface.points
    exact = exact_profile(analysis, frame, ball, ball.radius)
    if exact:
        splines = [shapes.bspline_curve(c) for c in exact]
        if uncovered(splines, curve, surface, ball, EXACT_COVERAGE * ball.radius)[1] is None:
            lines = (axis, f"profile: exact rational B-spline, {len(exact)} arcs, degree {exact[0].degree}")
            return Faces(shapes.revolution_faces(frame, splines, edge), "exact", lines)
    distance = profile_distance(curve, floor=goal / 10)
    fits = [fitted_arc(arc, goal, distance, curve) for arc in arcs]
    splines = [f.curve for f in fits]
    missed, where = uncovered(splines, curve, surface, ball, goal)
    deviation = max(missed, *(f.deviation for f in fits))
    if deviation > goal:
        near = f" (near ({', '.join(f'{c:.4g}' for c in where)}))" if where is not None else ""
        raise CadGeometryError(
            f"the fitted profile strays {deviation:.2g} from the surface{near}, more than the tolerance "
            f"{goal:.2g} ({goal / ball.radius:.2g} of the ball's radius); {LARGER_TOLERANCE}"
        )
    lines = (axis, f"profile: B-spline fitted to tolerance {goal:.3g}; measured deviation {deviation:.3g} (within it)")
    return Faces(shapes.revolution_faces(frame, splines, edge), "fitted", lines, deviation, goal)


def _factor_faces(analysis: Analysis, scene: Scene, tolerance: float | None, edge: float) -> Faces:
    """A reducible surface of revolution as the union of its factors' parts, each by its own
    route (:mod:`.factors`): the least exact route names the whole."""
    parts = []
    for own, part_scene in factor_parts(analysis, scene.region, scene.box, scene.profile_curve, scene.surface):
        made = _surface_faces(own, part_scene, tolerance, edge)
        lines = tuple(f"{own.squarefree} = 0: {line}" for line in made.description)
        parts.append(dataclasses.replace(made, description=lines))
    if not parts:
        raise _nothing_inside(scene.region)
    route = max((part.route for part in parts), key=ROUTES.index)
    deviations = [part.deviation for part in parts if part.deviation is not None]
    tolerances = [part.tolerance for part in parts if part.tolerance is not None]
    return Faces(
        [face for part in parts for face in part.faces],
        route,
        tuple(line for part in parts for line in part.description),
        max(deviations) if deviations else None,
        min(tolerances) if tolerances else None,
    )


ROUTES = ("analytic", "exact", "fitted")
"""The routes of a surface of revolution's faces, the most exact first."""


def _swept_faces(sweep: Sweep, ball: ClipSphere, goal: float) -> Faces:
    """A canal surface swept through its characteristic circles (:mod:`.canal`), cut to the ball."""
    if sweep.deviation > goal:
        raise CadGeometryError(
            f"the sweep of the canal surface's circles strays {sweep.deviation:.2g} from the surface, more than "
            f"the tolerance {goal:.2g} ({goal / ball.radius:.2g} of the ball's radius); {LARGER_TOLERANCE}"
        )
    faces = shapes.cut_to(sweep.faces, ball)
    if not faces:
        raise _nothing_inside(ball)
    lines = (
        f"canal surface: B-spline surface through {sweep.circles} of its characteristic circles",
        f"fitted to tolerance {goal:.3g}; measured deviation {sweep.deviation:.3g} (within it)",
    )
    return Faces(faces, "canal", lines, sweep.deviation, goal)


def _lined_faces(lined: Extrusion | Ruled, ball: ClipSphere, edge: float) -> Faces:
    """A cylinder or cone over a curve, cut to the ball (:mod:`.conical`)."""
    if isinstance(lined, Extrusion):
        faces = shapes.cut_to(shapes.extrusion_faces(lined, edge), ball)
        degree = lined.curves[0].degree
        lines = (
            f"cylinder along {_vector(lined.direction)} over its base curve ({lined.method})",
            f"linear extrusion of the exact rational B-spline base curve, {len(lined.curves)} arcs, degree {degree}",
        )
        route = "extrusion"
    else:
        faces = shapes.cut_to(shapes.ruled_faces(lined, edge), ball)
        lines = (
            f"cone with apex {_vector(lined.apex)} over its base curve ({lined.method})",
            f"ruled through the apex: rational Bezier surfaces of degree ({len(lined.spans[0]) - 1}, 1)",
        )
        route = "ruled"
    if not faces:
        raise _nothing_inside(ball)
    return Faces(faces, route, lines)


def _off_axis(ball: ClipSphere, frame: Frame) -> bool:
    """Whether the ball's centre is off the axis: its disk would then differ from one meridian
    half-plane to the next, and a revolved profile cut to one of them would not be the part in
    the ball."""
    return off_axis(np.asarray(ball.center), frame.point, frame.direction) > ON_AXIS * ball.radius


def _inside(spec: Analytic, ball: ClipSphere) -> bool:
    """Whether a whole sphere or torus lies in ``ball``; whether a cylinder or cone is built inside
    it (a ball centred on its axis; one off it is cut to: the part was of the ball moved onto the
    axis, 3 units² more of a unit cylinder in a ball of radius 2.5 about (1, 0, 0)); a plane is."""
    if spec.kind in ("cylinder", "cone"):
        return off_axis(np.asarray(ball.center), spec.origin, spec.direction) <= ON_AXIS * ball.radius
    if spec.kind not in ("sphere", "torus"):
        return True
    reach = spec.radius + spec.minor_radius
    return float(np.linalg.norm(spec.origin - np.asarray(ball.center))) + reach <= ball.radius


SECTORS = (2, 3, 5, 8)
"""Into how many sectors the faces of revolution are cut before they are cut to a box, in the
order tried (:func:`.shapes.sectors`): Open CASCADE's intersection of a revolved B-spline
profile with the box's planes misses curves on the whole face, and on some sectors."""


def _cut(part: Faces, scene: Scene, edge: float) -> tuple[list[Any], tuple[str, ...]]:
    """The faces cut to the user's box and the header's lines; an error if nothing of them is
    left. A cut is accepted when its faces lie in the box and cover the mesh there
    (:func:`.coverage.missing`); Open CASCADE's Boolean misses some intersections of revolved
    B-spline profiles, so the faces are cut in sectors first (:data:`SECTORS`, tried in turn),
    then converted to B-spline surfaces, and the file says so."""
    box = scene.box
    if box is None:
        return part.faces, part.description
    low, high = box.bounds[0::2], box.bounds[1::2]
    lines = [*part.description, f"cut to the box {_vector(np.array(low))} - {_vector(np.array(high))}"]
    size = scene.region.radius
    nurbs = ("faces converted to B-spline surfaces to be cut to the box",)
    attempts = [(count, ()) for count in SECTORS] + [(SECTORS[0], nurbs)]
    for count, note in attempts:
        faces = shapes.sectors(part.faces, count, edge)
        cut = shapes.cut_to(shapes.as_nurbs(faces) if note else faces, box)
        if not cut:
            return [], tuple(lines)
        if shapes.within(cut, box, edge) and missing(cut, scene.surface.points, scene.surface.spacing, size) is None:
            return cut, (*lines, *note)
    raise CadGeometryError(
        "Open CASCADE's cut of the faces to the box leaves part of them outside it or loses part of the surface "
        "(however its faces are divided); a ball (--region R) or another box may do"
    )


def _axis_line(point: np.ndarray, direction: np.ndarray) -> str:
    return f"axis: point {_vector(point)}, direction {_vector(direction)}"


LARGER_TOLERANCE = "a larger fit tolerance may allow it (sorgui analyze --fit-tolerance)"
"""The remedy a fit beyond its tolerance names (the command line's; the window has none)."""


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


def _no_part_words(analysis: Analysis) -> str:
    """Why a surface that is not of revolution has no part, and what may be written instead (a
    patch only when there is a parameterization to make it of)."""
    patch = "; write NAME.patch.step for its rational parameterization" if own_maps(analysis) else ""
    approximate = analysis.approximate
    if approximate is not None and approximate.near_sor:
        distance = approximate.relative_distance
        within = f"within {distance:.2g} (relative) of " if distance is not None else "near "
        unanalysed = approximate.nearest is not None and approximate.nearest.analysis is None
        if analysis.input_kind == "parametrization":
            found = "no nearest exact surface is computed for a parametrization"
        elif unanalysed:
            found = "with --recognition-only its nearest exact surface is not analysed"
        else:
            found = "no exact surface with a rational or quadratic axis was found within its rounding"
        tight = approximate.tolerance_source == "input" and (approximate.tolerance or 1.0) < FULL_PRECISION
        looser = (
            "; its 14 or more digits are finer than the arithmetic that printed them: "
            "a larger tolerance (--tolerance 1e-10) may find one"
            if tight and analysis.input_kind != "parametrization" and not unanalysed
            else ""
        )
        if unanalysed:
            looser = "; analyse without --recognition-only for its part"
        return (
            f"the typed surface is not exactly a surface of revolution, only {within}{kind_noun(approximate.kind)}, "
            f"and {found} to build the part from (the approximate axis is in the report){looser}{patch}"
        )
    conical = analysis.conical
    if conical is not None and conical.kind == "none" and (conical.near_apex or conical.near_direction):
        kind = "cone" if conical.near_apex is not None else "cylinder"
        return (
            f"the typed surface is nearly a {kind} over a curve, not exactly one, and no exact {kind} is made "
            f"from rounded input to build the part from (its approximate "
            f"{'apex' if kind == 'cone' else 'direction'} is in the report){patch}"
        )
    if conical is None and "conical" not in analysis.unfinished:
        return (
            "the surface is not a surface of revolution, and with --recognition-only it is not analysed as a "
            f"cylinder or cone over a curve or a canal surface; analyse without --recognition-only for its part{patch}"
        )
    return (
        "the surface is not a surface of revolution, nor a cylinder or cone over a rational curve, "
        f"nor a canal surface with known circles{patch}"
    )


def patch_model(analysis: Analysis, scene: Scene) -> CadModel:
    """The first verified real rational parameterization (of ``X``, of a canal surface by its
    circles, of a cone or cylinder by its lines, of a sphere by stereographic projection) over
    the window's parameter box, covered once and oriented along ``∇f`` (:mod:`.patch`), cut to
    the drawn ball and to the user's box if there is one; for rounded input, the nearest exact
    surface's (:mod:`.nearest`) when it has one: the map of the patch meshes
    (:func:`~sorgui.engine.patches.patch_maps`)."""
    nearest = patch_stand_in(analysis)
    if nearest is not None and nearest.analysis is not None:
        model = patch_model(nearest.analysis, nearest_scene(scene, nearest.analysis))
        deviation = typed_deviation(model.shape, analysis.squarefree, scene)
        lines = (*nearest_lines(nearest, deviation), *model.description)
        return dataclasses.replace(
            model, description=lines, typed_deviation=deviation, beyond_rounding=not nearest.within_rounding
        )
    size = scene.region.radius
    check_size(size)
    terms = polynomial_terms(analysis.squarefree)
    outside = False
    for box in PATCH_RANGES:  # the first box and map whose patch meets the ball, as the window's
        for param in own_maps(analysis):
            try:
                patches = bezier_patches(param, terms, box)
            except (CadGeometryError, ExpressionError, sympy.PolynomialError):
                continue
            faces, groups = [], []
            for patch in patches:
                face = shapes.patch_face(patch, precision(size))
                cut = shapes.cut_to([shapes.reversed_face(face) if patch.turned else face], scene.region)
                faces += cut
                groups += [int(patch.turned)] * len(cut)
            if not faces:
                outside = True
                continue
            low, high = box
            lines = (
                f"rational B-spline patch of the parameterization ({param.method}) over s, t in [{low:g}, {high:g}]",
            )
            return finished(Faces(faces, "patch", lines, groups=tuple(groups)), scene, analysis.squarefree)
        if not outside:
            break  # no map could be written: a wider box writes none either
    if outside:
        raise CadGeometryError("the parameterization's patch has no point inside the drawn ball")
    raise CadGeometryError("the analysis has no verified real rational parameterization to write as a patch")


def _nothing_inside(ball: ClipSphere) -> CadGeometryError:
    """The refusal of a part with nothing in its ``ball``, naming the ball and what to do (it said
    only "the drawn ball", where the mesh's refusals name it and advise a region)."""
    centre = ", ".join(f"{v:.6g}" for v in ball.center)
    return CadGeometryError(
        f"the surface has no real points inside the ball of radius {ball.radius:.6g} about ({centre}): "
        "give a region that meets it (--region on the command line, the ball radius box of the window)"
    )
