"""The plain arrays of the 3D scene of one analysis, built in the worker process.

From an :class:`~sorgui.engine.results.Analysis` this computes, with the builders of
:mod:`sorgui.render`, everything the viewport draws: the mesh of the square-free part of ``f``
(coloured by side), the axis, the profile curve in a plane through the axis, the centre of a
sphere, a patch of the first real parameterization, the axes of the factors of a reducible
surface, and for rounded input the approximate axis and the deviation from the nearest exact
surface (docs/math.md, "Rounded input"). All of it is ``numpy`` data (no Qt, no
VTK objects): a :class:`~sorgui.session.scene.SceneData`, which crosses the process boundary by
pickling, and the GUI thread only wraps it.

The drawn region is a ball. Its centre and radius come from :func:`view_region`, which looks
for the real points of ``f`` on a few lines through a natural centre (the axis, a sphere's
centre, or the origin), so that bounded parts of the surface are shown whole.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import replace
from typing import Any

import numpy as np

from sorgui.engine.patches import patch_maps
from sorgui.engine.results import Analysis, Approximation, Conical, Recognition
from sorgui.engine.rounded import dense
from sorgui.engine.rounded.deviation import extent_directions, is_bounded, view_ball
from sorgui.engine.stage_results import BaseCurve, Parametrization, RealLocus
from sorgui.engine.values import (
    ExpressionError,
    Terms,
    beyond_floats,
    float_vector,
    polynomial_terms,
    rational_function_terms,
    to_float,
    zero_set_profile,
)
from sorgui.engine.vocabulary import no_surface_words
from sorgui.export.text import float_text
from sorgui.render import (
    PATCH_RANGE,
    PATCH_RANGES,
    ClipBox,
    ClipSphere,
    LineData,
    MeshData,
    PatchData,
    axis_line,
    parametric_patch,
    profile_curve,
    sphere_center_marker,
    surface_mesh,
)
from sorgui.render.canal_scene import SmatFamily
from sorgui.render.geometry import clip_to_ball, foot_on_line, readonly
from sorgui.render.mesh import DEFAULT_RESOLUTION
from sorgui.render.sampling import evaluate_points, first_order_distance, term_arrays
from sorgui.session.scene import SceneData

PATCH_GRID = 41
"""Samples per parameter of the patch, drawn as a wireframe: a readable net of curves."""
SURFACE_GRID = 161
"""Samples per parameter of a map's patch drawn as the surface (no implicit equation known)."""


# --- where to look --------------------------------------------------------------------------


def view_region(terms: Terms, center: np.ndarray, axis: np.ndarray | None = None) -> ClipSphere:
    """A ball that shows the interesting part of ``f = 0`` around ``center``: the engine's
    :func:`~sorgui.engine.rounded.deviation.view_ball` (real points on a star of lines, far branches
    dropped), the same ball in which a rounded input's deviation is measured (docs/math.md §8.6)."""
    center = np.asarray(center, dtype=np.float64)
    middle, radius = view_ball(_dense(terms), center, axis, whole=True)
    if np.linalg.norm(middle - center) <= SAME_CENTRE * max(radius, float(np.linalg.norm(center))):
        middle = center  # the exact centre, not one 4e-16 off it (a sphere's CAD part was cut in two)
    return _ball(middle, radius)


SAME_CENTRE = 1e-12
"""How near the view ball's middle must be to the surface's own centre, relative to the ball's
radius or the centre's distance from the origin, to be taken as that centre."""


def _ball(middle: np.ndarray, radius: float) -> ClipSphere:
    return ClipSphere((float(middle[0]), float(middle[1]), float(middle[2])), radius)


def _dense(terms: Terms) -> np.ndarray:
    exps, coefs = term_arrays(terms, 3)
    degree = int(exps.sum(axis=1).max(initial=0))
    return dense.from_terms({(int(e[0]), int(e[1]), int(e[2])): float(c) for e, c in zip(exps, coefs)}, degree)


def with_bounded_factors(
    region: ClipSphere, factors: list[str], center: np.ndarray, axis: np.ndarray | None
) -> ClipSphere:
    """``region`` grown to hold every bounded factor of a reducible surface whole: the far
    branches the view ball drops can be a whole component (a torus about a thin coaxial
    cylinder, whose many near points made the torus's look far, was left out of the picture and
    the CAD file). An unbounded factor (a plane far along the axis) does not grow it."""
    balls = [region]
    for polynomial in factors:
        array = _dense(polynomial_terms(polynomial))
        if array.shape[0] > 1 and is_bounded(array, extent_directions(axis)):
            middle, radius = view_ball(array, np.asarray(center, dtype=np.float64), axis, whole=True)
            balls.append(_ball(middle, radius))
    return _holding(balls, axis)


APEX_SHARE = 0.5
"""A cone's ball holds the ball about its apex of this share of the apex's distance from the
origin (:func:`with_apex`)."""


def with_apex(region: ClipSphere, conical: Conical | None, axis: np.ndarray | None) -> ClipSphere:
    """``region`` grown to hold a cone's apex (exact, or that of a cone within the rounding) and
    the ball about it of :data:`APEX_SHARE` times its distance from the origin, the one length a
    cone's equation gives. The lines through the foot of the origin on the axis see no size when
    the apex is next to that foot (a cone about ``(30, 40, 1)`` along ``z`` was drawn in a ball of
    radius 1, and its CAD part was 3 units² of cone), and leave the apex out when it is far."""
    if conical is None:
        return region
    apex = float_vector(conical.apex) if conical.kind == "cone" and conical.apex is not None else conical.near_apex
    if apex is None or not np.all(np.isfinite(apex)):
        return region
    size = APEX_SHARE * float(np.linalg.norm(apex))
    if size <= 0:
        return region
    return _holding([region, _ball(np.asarray(apex, dtype=np.float64), size)], axis)


def _holding(balls: list[ClipSphere], axis: np.ndarray | None) -> ClipSphere:
    """The first ball of ``balls`` grown to hold them all: centred on the axis when there is one
    (a ball centred on the axis meets every meridian half-plane in the same disk)."""
    centres = np.array([b.center for b in balls])
    radii = np.array([b.radius for b in balls])
    if np.all(np.linalg.norm(centres - centres[0], axis=1) + radii <= radii[0]):
        return balls[0]
    if axis is not None:
        a = axis / np.linalg.norm(axis)
        heights = (centres - centres[0]) @ a
        middle = centres[0] + 0.5 * ((heights - radii).min() + (heights + radii).max()) * a
    else:
        middle = 0.5 * ((centres - radii[:, None]).min(axis=0) + (centres + radii[:, None]).max(axis=0))
    radius = float((np.linalg.norm(centres - middle, axis=1) + radii).max())
    return _ball(middle, radius)


def ball_about(box: ClipBox, point: np.ndarray, axis: np.ndarray | None) -> ClipSphere:
    """The ball holding ``box`` about its centre, or about the centre's foot on the axis through
    ``point`` (a ball centred on the axis meets every meridian half-plane in the same disk)."""
    low, high = np.array(box.bounds[0::2]), np.array(box.bounds[1::2])
    middle = (low + high) / 2
    if axis is not None:
        middle = foot_on_line(middle, point, axis)
    corners = np.array(list(itertools.product(*zip(low, high))))
    radius = float(np.max(np.linalg.norm(corners - middle, axis=1)))
    return _ball(middle, radius)


def natural_center(rec: Recognition, approximate: Approximation | None = None) -> tuple[np.ndarray, np.ndarray | None]:
    """Where to centre the view, and the axis direction if the axis is unique: the exact axis,
    else the approximate axis of rounded input (whose surface is probed about that axis, as its
    exact version is, instead of about the origin, which can leave parts of it outside the
    ball), else the centre, else the origin."""
    if rec.axis is not None:
        point, direction = float_vector(rec.axis.point), float_vector(rec.axis.direction)
        return foot_on_line(np.zeros(3), point, direction), direction
    if approximate is not None and approximate.axis is not None:
        point, direction = np.asarray(approximate.axis.point), np.asarray(approximate.axis.direction)
        if np.all(np.isfinite(point)) and np.all(np.isfinite(direction)) and np.any(direction):
            return foot_on_line(np.zeros(3), point, direction), direction
    if rec.center is not None:
        return float_vector(rec.center), None
    return np.zeros(3), None


# --- the scene ------------------------------------------------------------------------------


def _patch(
    param: Parametrization,
    region: ClipSphere | ClipBox | None,
    n: int = PATCH_GRID,
    box: tuple[float, float] = PATCH_RANGE,
) -> PatchData | None:
    """A grid patch of a real parameterization over ``box × box`` (``None`` if its coordinates
    cannot be read)."""
    try:
        coordinates = [rational_function_terms(c, param.parameters) for c in param.coordinates]
    except (ExpressionError, ValueError, TypeError):
        return None

    def coordinate(numerator: Terms, denominator: Terms) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
        def evaluate(s: np.ndarray, t: np.ndarray) -> np.ndarray:
            st = np.column_stack([np.ravel(s), np.ravel(t)])
            with np.errstate(all="ignore"):
                value = evaluate_points(numerator, st) / evaluate_points(denominator, st)
            shaped: np.ndarray = value.reshape(np.shape(s))
            return shaped

        return evaluate

    fx, fy, fz = (coordinate(n, d) for n, d in coordinates)
    return parametric_patch(fx, fy, fz, box, box, n=n, region=region)


def patch_region(param: Parametrization) -> ClipSphere | None:
    """The ball that holds most of a map's patch over :data:`~sorgui.render.PATCH_RANGE`, for a
    parametrization whose implicit equation is not known (``None`` if no point is finite): about
    the median point, through the 90th percentile of the distances (poles are left out)."""
    patch = _patch(param, None)
    if patch is None:
        return None
    points = np.asarray(patch.points).reshape(-1, 3)
    points = points[np.all(np.isfinite(points), axis=1)]
    if not len(points):
        return None
    middle = np.median(points, axis=0)
    radius = 1.1 * float(np.percentile(np.linalg.norm(points - middle, axis=1), 90)) or 1.0
    return _ball(middle, radius)


def patch_surface(param: Parametrization, clip: ClipSphere | ClipBox, bounds: tuple[float, ...]) -> MeshData:
    """The map's patch over :data:`~sorgui.render.PATCH_RANGE` as a triangle mesh (the valid
    quads of a :data:`SURFACE_GRID` grid halved), its normals from the grid's tangents: what is
    drawn and exported as the surface when the implicit equation is not known."""
    patch = _patch(param, clip, SURFACE_GRID)
    if patch is None or patch.is_empty:
        return MeshData.empty(0.0, bounds)
    points = np.asarray(patch.points)
    ds, dt = np.gradient(np.nan_to_num(points), axis=(0, 1))
    normals = np.cross(ds, dt)
    length = np.linalg.norm(normals, axis=-1, keepdims=True)
    normals = np.divide(normals, length, out=np.zeros_like(normals), where=length > 0)
    ids = np.arange(points.shape[0] * points.shape[1]).reshape(points.shape[:2])
    i, j = np.nonzero(patch.quad_mask())
    a, b, c, d = ids[i, j], ids[i + 1, j], ids[i + 1, j + 1], ids[i, j + 1]
    triangles = np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])
    used, inverse = np.unique(triangles, return_inverse=True)
    faces = np.column_stack([np.full(len(triangles), 3), inverse.reshape(-1, 3)]).ravel().astype(np.int64)
    flat = points.reshape(-1, 3)[used]
    spacing = float(np.max(np.ptp(flat, axis=0))) / SURFACE_GRID
    return MeshData(
        readonly(flat),
        readonly(faces),
        readonly(normals.reshape(-1, 3)[used].astype(np.float32)),
        readonly(np.ones(len(used), dtype=np.float32)),
        spacing,
        bounds,
    )


def _nearest_region(
    analysis: Analysis, region: ClipSphere, center: np.ndarray, direction: np.ndarray | None
) -> ClipSphere:
    """The ball of rounded input: the typed surface's, unless that is many times the nearest
    exact surface's (within the rounding). A cylinder printed with 6 digits is an ellipsoid 1,500
    times longer than wide, whose ball of radius 1,862 left the mesh 8 triangles and cut the CAD
    part 370 units beyond where the typed surface ends."""
    approx = analysis.approximate
    nearest = approx.nearest if approx is not None else None
    if nearest is None or not nearest.within_rounding or analysis.is_sor:
        return region
    exact = view_region(polynomial_terms(nearest.polynomial), center, direction)
    return exact if region.radius > NEAREST_BALL_RATIO * exact.radius else region


NEAREST_BALL_RATIO = 4.0
"""How many times the nearest exact surface's ball the typed one may be before that one is drawn."""


def chosen_region(analysis: Analysis, terms: Terms, center: np.ndarray, axis: np.ndarray | None) -> ClipSphere:
    """The ball ``analysis`` is drawn in when no region is asked for: a map's patch's when its
    equation is not known, else :func:`view_region` about ``center``, grown to hold bounded
    factors, or the nearest exact surface's (:func:`_nearest_region`); a cone's grown to hold
    its apex (:func:`with_apex`)."""
    real = [p for p in analysis.parametrizations if p.real and p.verified]
    patch = patch_region(real[0]) if not analysis.squarefree and real else None
    if patch is not None:
        return patch
    region = view_region(terms, center, axis)
    if len(analysis.factors) > 1:
        region = with_bounded_factors(region, [factor.polynomial for factor in analysis.factors], center, axis)
    return with_apex(_nearest_region(analysis, region, center, axis), analysis.conical, axis)


def build_scene(
    analysis: Analysis,
    radius: float | None = None,
    resolution: int | None = None,
    region: ClipSphere | None = None,
    patch: bool = True,
    box: ClipBox | None = None,
) -> SceneData:
    """The scene of ``analysis``; ``radius`` overrides the automatic size of the drawn ball,
    ``region`` the whole ball (the nearest exact surface is drawn in the typed one's ball),
    ``box`` both: the mesh is cut to the box, in the ball about it;
    ``patch=False`` leaves the parameterization patch for :func:`with_patch`; ``resolution`` is
    the mesh's grid (:data:`~sorgui.render.mesh.DEFAULT_RESOLUTION` when not given)."""
    rec = analysis.recognition
    terms = polynomial_terms(analysis.squarefree)
    center, axis_direction = natural_center(rec, analysis.approximate)
    asked = region is not None or box is not None  # a region of the caller's, not the chosen ball
    if box is not None:
        region = ball_about(box, center, axis_direction)
    if region is None:
        region = chosen_region(analysis, terms, center, axis_direction)
    drawn = region  # the chosen ball, when no region was asked for
    if radius is not None:
        region = ClipSphere(region.center, radius)
    bounds, clip = _mesh_region(region, box)
    too_far = _too_far(terms, region, analysis.recognition.degree)
    if too_far is not None:
        empty = LineData.empty()
        return SceneData(terms, region, MeshData.empty(), empty, empty, None, None, None, None, (too_far,), box=box)
    surface = surface_mesh(terms, bounds, resolution=resolution or DEFAULT_RESOLUTION, clip=clip)
    real = [p for p in analysis.parametrizations if p.real and p.verified]
    if not analysis.squarefree and real:  # a parametrization without its equation: its patch is the surface
        surface = patch_surface(real[0], clip, bounds)
    notes = []
    if surface.is_empty:
        spacing = 2 * region.radius / (resolution or DEFAULT_RESOLUTION)
        if asked:
            chosen: ClipSphere | None = chosen_region(analysis, terms, center, axis_direction)
        else:
            chosen = drawn if radius is not None else None
        where = box if box is not None else region
        notes.append(_empty_note(analysis.squarefree, where, chosen, spacing, analysis.real_locus))
    segment, profile = LineData.empty(), LineData.empty()
    axis_point = None
    if rec.axis is not None:
        point, direction = float_vector(rec.axis.point), float_vector(rec.axis.direction)
        segment = axis_line(point, direction, region)
        axis_point = tuple(point)
    if rec.profile is not None:
        profile = profile_curve(
            polynomial_terms(zero_set_profile(rec.profile).rational, ("s", "r")),
            float_vector(rec.profile.frame_point),
            float_vector(rec.profile.frame_direction),
            float_vector(rec.profile.frame_normal),
            region,
        )
    imaginary = rec.radius_squared is not None and to_float(rec.radius_squared) < 0
    # a sphere without real points (x² + y² + z² + 1) drew its centre, a point that is not on it
    marker = sphere_center_marker(float_vector(rec.center), region) if rec.center and not imaginary else None
    if not analysis.squarefree:
        notes.append("The implicit equation is not known: the surface drawn is the given map's patch.")
    factor_lines = [
        axis_line(float_vector(f.recognition.axis.point), float_vector(f.recognition.axis.direction), region)
        for f in analysis.factors
        if f.recognition.axis is not None and len(analysis.factors) > 1
    ]
    typed = rec.polynomial
    return SceneData(
        terms=terms,
        typed_terms=polynomial_terms(typed) if typed and typed != analysis.squarefree else None,
        region=region,
        surface=surface,
        axis_segment=segment,
        profile_curve=profile,
        center_marker=marker,
        patch=_first_patch(patch_maps(analysis) if patch else [], region),
        axis_point=axis_point,
        axis_direction=tuple(axis_direction) if axis_direction is not None else None,
        notes=tuple(notes),
        factor_axes=LineData.from_polylines([line.points for line in factor_lines if not line.is_empty]),
        box=box,
    )


def _mesh_region(region: ClipSphere, box: ClipBox | None) -> tuple[tuple[float, ...], ClipSphere | ClipBox]:
    """The grid's bounds and the clip of a scene's mesh: the box when there is one, else the ball."""
    if box is not None:
        return tuple(box.bounds), box
    c, r = region.center, region.radius
    return tuple(v for i in range(3) for v in (c[i] - r, c[i] + r)), region


def at_full_resolution(scene: SceneData) -> SceneData:
    """The window's ``scene`` with its surface meshed again on the command line's grid when the
    window drew it coarser (software OpenGL): an STL written from the window had a third of the
    command line's triangles. The same surface (typed or nearest), ball or box."""
    surface = scene.surface
    if not scene.terms or surface.is_empty:
        return scene  # a map's patch, or nothing drawn
    bounds, clip = _mesh_region(scene.region, scene.box)
    longest = max(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4])
    if surface.spacing <= longest / DEFAULT_RESOLUTION * (1 + 1e-9):
        return scene
    return replace(scene, surface=surface_mesh(scene.terms, bounds, resolution=DEFAULT_RESOLUTION, clip=clip))


FLOAT_ERROR = 1e-3
"""The error of floating-point values of ``f`` in the ball, relative to their spread there,
above which the surface is not drawn (:func:`_too_far`)."""


def _too_far(terms: Terms, region: ClipSphere, degree: int) -> str | None:
    """Why a surface in ``region`` cannot be drawn in floating point, in words (``None`` when it
    can): the rounding error of ``f``'s values in the ball (``ε·Σ|c_k·x^k|`` at 27 points of it)
    against their spread there. A sphere of radius 10⁻³ about ``(10¹², 0, 0)`` was meshed as a
    flat disc 17 000 across (67 MB), one of radius 1 about ``(10¹⁷, 0, 0)`` failed the whole run's
    drawing stage with an internal error. The spread is measured, not taken as ``r^degree``: a
    ball of radius 0.5 on a torus of radii 250 and 40 a thousand from the origin was refused."""
    c, r = np.asarray(region.center, dtype=float), region.radius
    distance = float(np.linalg.norm(c))
    eps = float(np.finfo(np.float64).eps)
    if distance <= r or eps * (distance / r) ** max(degree, 1) <= FLOAT_ERROR:
        return None  # the terms cannot outgrow the spread by that much
    steps = np.array(list(itertools.product((-0.5, 0.0, 0.5), repeat=3)))
    points = c + r * steps
    with np.errstate(all="ignore"):
        values = evaluate_points(terms, points)
        sizes = evaluate_points([(e, abs(v)) for e, v in terms], np.abs(points))
        spread = float(np.ptp(values))
        error = eps * float(np.max(sizes)) * max(degree, 1)
    if np.all(np.isfinite(values)) and math.isfinite(error) and error <= FLOAT_ERROR * spread:
        return None
    return (
        f"The surface cannot be drawn in floating point: it lies {distance:.3g} from the origin, in a ball of radius "
        f"{region.radius:.3g}, and the rounding of f's values there is larger than their spread (the exact analysis "
        "is not affected; move the part nearer the origin to draw it)."
    )


def _empty_note(
    squarefree: str, where: ClipSphere | ClipBox, chosen: ClipSphere | None, spacing: float, locus: RealLocus | None
) -> str:
    """Why nothing of the surface is drawn in ``where``, as a note of the scene: its numbers
    beyond floating point, its real points (no surface of them: the real locus, docs/math.md
    §3.4), or :func:`_empty_words`."""
    why = beyond_floats(squarefree) or no_surface_words(locus) or _empty_words(where, chosen, spacing)
    return f"{why[0].upper()}{why[1:]}."


def _empty_words(where: ClipSphere | ClipBox, chosen: ClipSphere | None, spacing: float) -> str:
    """What is wrong with ``where`` and what to do; ``chosen``: the ball chosen for the surface
    when ``where`` was asked for instead (``None``: ``where`` is that ball). A ball asked for
    whose mesh's grid (``spacing``) is coarse beside the chosen ball is too large: a unit sphere
    in a ball of radius 1000 was said to have "no real points inside the ball", and a cylinder
    of radius 1 in a ball of radius 10^9 to "lie within about 1.77 of its centre". A region
    asked for is named, with the chosen ball: "give --region" was said of a region given with
    ``--region``."""
    region = _region_words(where)
    if chosen is None:
        return (
            f"the surface has no real points that can be drawn inside {region}, chosen for it: "
            "give a region that holds some (the ball's centre and radius: the ball radius box of the window, "
            "--region on the command line)"
        )
    if isinstance(where, ClipSphere) and chosen.radius < 2 * spacing < where.radius:
        return (
            f"{region} asked for is too large to draw the surface in: the mesh's grid (spacing "
            f"{spacing:.3g}) passes between its points; give a smaller one (the ball chosen for it has radius "
            f"{chosen.radius:.3g}: the ball radius box of the window, --region on the command line)"
        )
    return (
        f"the surface has no real points that can be drawn inside {region} asked for: give a region that "
        f"meets it (without one, {_region_words(chosen)})"
    )


def _region_words(region: ClipSphere | ClipBox) -> str:
    """``the ball of radius 2 about (0, 0, 0)`` or ``the box (0, 0, 0) to (1, 1, 1)``."""
    if isinstance(region, ClipBox):
        low, high = region.bounds[0::2], region.bounds[1::2]
        return f"the box {float_text(low, 6)} to {float_text(high, 6)}"
    return f"the ball of radius {region.radius:.6g} about {float_text(region.center, 6)}"


def build_scene_of(analysis: Analysis, request: Any) -> SceneData:
    """The scene a worker's job asks for (``request``: a ``JobRequest``): its ball radius, its
    mesh resolution and its box; the patch comes later (:func:`with_patch`)."""
    box = ClipBox(request.box) if request.box is not None else None
    return build_scene(analysis, request.radius, request.resolution, patch=False, box=box)


def with_patch(scene: SceneData, analysis: Analysis) -> SceneData:
    """``scene`` with the patch of the first map of :func:`~sorgui.engine.patches.patch_maps`."""
    return replace(scene, patch=_first_patch(patch_maps(analysis), scene.region))


def _first_patch(maps: list[Parametrization], region: ClipSphere | ClipBox) -> PatchData | None:
    """The patch of the first of ``maps`` that has points inside ``region`` over the first box of
    :data:`~sorgui.render.PATCH_RANGES` where one does (as the CAD file's patch,
    :func:`sorgui.cad.model.patch_model`), else of the first whose coordinates can be read
    (``None``: none). A hyperboloid's first map, about a turned axis, met the ball only outside
    ``[−3, 3]²``, and its second one covered it; a small hyperboloid's only map meets it at
    ``t ≈ 9``."""
    readable = None
    for box in PATCH_RANGES:
        for param in maps:
            patch = _patch(param, region, box=box)
            if patch is not None and not patch.is_empty:
                return patch
            readable = readable or patch
        if readable is None:
            return None  # no map can be read: a wider box reads none either
    return readable


def with_approximation(scene: SceneData, analysis: Analysis) -> SceneData:
    """``scene`` with the approximate axis of rounded input and, when the nearest exact surface
    ``g`` is known, each surface point's distance to it, ``|g(p)| / |∇g(p)|`` (first order)."""
    approx = analysis.approximate
    if approx is None:
        return scene
    deviation = None
    if approx.nearest is not None and not scene.surface.is_empty:
        deviation = surface_deviation(polynomial_terms(approx.nearest.polynomial), scene.surface.points)
    point = None if approx.axis is None else approx.axis.point
    return replace(
        scene,
        approximate_axis=approximate_axis(analysis, scene.region),
        approximate_axis_point=point,
        deviation=deviation,
    )


def approximate_axis(analysis: Analysis, region: ClipSphere) -> LineData:
    """Rounded input's approximate axis inside ``region`` (empty when there is none)."""
    approx = analysis.approximate
    if approx is None or approx.axis is None:
        return LineData.empty()
    return axis_line(np.asarray(approx.axis.point), np.asarray(approx.axis.direction), region)


def with_canal(scene: SceneData, analysis: Analysis) -> SceneData:
    """``scene`` with the spines and characteristic circles of the canal surface of ``analysis``
    (:func:`sorgui.render.canal_scene.canal_scene`), cut to the drawn ball."""
    canal = analysis.canal
    if canal is None or not canal.is_canal:
        return scene
    from sorgui.render.canal_scene import canal_scene
    from sorgui.session.canal_data import family_curves

    bound = float(np.linalg.norm(scene.region.center)) + 1.5 * scene.region.radius
    families = family_curves(canal)
    drawn = canal_scene(families, bound=bound)
    spines, circles = list(drawn.spines), list(drawn.circles)
    implicit = [f for f in families if isinstance(f, SmatFamily)]
    if implicit and not scene.surface.is_empty:  # spines of positive genus: traced from the surface
        from sorgui.render.canal_trace import smat_scene

        surface = scene.surface
        traced = smat_scene(
            implicit,
            surface.points,
            np.asarray(surface.normals, dtype=np.float64),
            bound=bound,
            step=scene.region.radius / 80,
        )
        spines += traced.spines
        circles += traced.circles
    # cut to the drawn ball, as the surface is: whole circles beyond it floated about a cylinder
    spines = [piece for line in spines for piece in clip_to_ball(line, scene.region)]
    circles = [piece for line in circles for piece in clip_to_ball(line, scene.region)]
    return replace(
        scene,
        canal_spine=LineData.from_polylines(spines),
        canal_circles=LineData.from_polylines(circles),
        canal_families=families,
    )


def with_conical(scene: SceneData, analysis: Analysis) -> SceneData:
    """``scene`` with what a cone or a cylinder over a curve shows (docs/math.md §10): the apex
    of a cone, marked as a sphere's centre is (a surface has one or the other), and the base
    curve where it lies on the surface, in its plane."""
    conical = analysis.conical
    if conical is None or conical.kind not in ("cone", "cylinder"):
        return scene
    if conical.kind == "cone" and conical.apex is not None and scene.center_marker is None:
        scene = replace(scene, center_marker=sphere_center_marker(float_vector(conical.apex), scene.region))
    base = conical.base_curve
    if base is None:
        return scene
    try:
        terms = polynomial_terms(base.polynomial, base.variables)
    except (ExpressionError, ValueError, TypeError):
        return scene
    plane = _base_plane(conical, base, terms, scene.region)
    if plane is None:
        return scene
    curve_terms, point, first, second = plane
    return replace(scene, base_curve=profile_curve(curve_terms, point, first, second, scene.region))


def _base_plane(
    conical: Conical, base: BaseCurve, terms: Terms, region: ClipSphere
) -> tuple[Terms, np.ndarray, np.ndarray, np.ndarray] | None:
    """The base curve as terms in ``(s, r)`` of the plane ``point + s·first + r·second``, a plane
    through the drawn ball where the curve lies on the surface. A cone's chart ``z = 1`` becomes
    the parallel plane at the distance ``d`` from the apex where the ball is (``f_d`` is
    homogeneous: its terms are scaled by powers of ``d``); a cylinder's section plane is moved
    along the direction to the ball's centre (the surface does not change along it)."""
    centre = np.asarray(region.center)
    if conical.kind == "cylinder" and None not in (base.frame_point, base.frame_u, base.frame_w, conical.direction):
        assert base.frame_point and base.frame_u and base.frame_w and conical.direction
        origin, a = float_vector(base.frame_point), float_vector(conical.direction)
        point = origin + ((centre - origin) @ a) / (a @ a) * a
        return terms, point, float_vector(base.frame_u), float_vector(base.frame_w)
    if conical.kind == "cone" and conical.apex is not None and base.chart is not None:
        names = ("x", "y", "z")
        chart, first, second = (names.index(n) for n in (base.chart.split("=")[0].strip(), *base.variables))
        apex, unit = float_vector(conical.apex), np.eye(3)
        d = float((centre - apex) @ unit[chart])
        if abs(d) < region.radius / 4:
            d = region.radius / 2
        scaled = [(m, c * d ** (base.degree - sum(m))) for m, c in terms]
        return scaled, apex + d * unit[chart], unit[first], unit[second]
    return None


def surface_deviation(terms: Terms, points: np.ndarray) -> np.ndarray:
    """``|g(p)| / |∇g(p)|`` at ``points``: the first-order distance from ``p`` to ``g = 0``."""
    distance = first_order_distance(terms, points)
    return np.where(np.isfinite(distance), distance, np.nan)


def with_component_axes(scene: SceneData, recognitions: list[Recognition]) -> SceneData:
    """``scene`` with the axes of the typed components of a blend (:mod:`.components`) as its
    factor axes; a sphere's centre gets the line through it parallel to the first axis."""
    axes = [(float_vector(r.axis.point), float_vector(r.axis.direction)) for r in recognitions if r.axis is not None]
    if axes:
        axes += [(float_vector(r.center), axes[0][1]) for r in recognitions if r.center is not None]
    lines = [axis_line(point, direction, scene.region) for point, direction in axes]
    return replace(scene, factor_axes=LineData.from_polylines([ln.points for ln in lines if not ln.is_empty]))
