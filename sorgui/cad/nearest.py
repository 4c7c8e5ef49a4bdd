"""Rounded input: the part of the exact surface it was meant to be (docs/math.md §8, §11).

A CAD system prints its surfaces with rounded coefficients, so the usual input is exactly no
surface of revolution, only within its rounding of one: the engine finds that nearest exact
surface ``g`` (``Approximation.nearest``, with its own exact analysis). Its part is written
instead, in the typed surface's region (the ball moved onto ``g``'s exact axis, the profile of
``g`` traced there as the 3D view traces one), and the file's header and the summary say so:
``g``, its relative distance to ``f`` over the coefficients, and the largest distance from
points of the part to the typed surface ``f = 0``, measured to feet found on it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

from sorgui.engine.results import Analysis, NearestSurface
from sorgui.engine.values import float_vector, polynomial_terms, zero_set_profile
from sorgui.render import ClipBox, ClipSphere, LineData, MeshData, profile_curve
from sorgui.render.geometry import foot_on_line
from sorgui.render.sampling import Terms, first_order_distance, value_and_gradient

from .reading import faces_of
from .sewing import face_normals


class Where(Protocol):
    """What the substitution needs of a scene: its ball, the user's box, the typed mesh."""

    @property
    def region(self) -> ClipSphere: ...

    @property
    def box(self) -> ClipBox | None: ...

    @property
    def surface(self) -> MeshData: ...


SAMPLES = 12
"""Points per parameter of each face at which the distance to the typed surface is measured."""

STEP = 0.01
"""The longest Newton step towards the typed surface, as a fraction of the ball's radius: next
to a singular point of the part (a cone's apex) the typed ``∇f`` nearly vanishes and a full step
``f·∇f/|∇f|²`` jumps across the ball."""
ROUNDS = 20
"""The most slides along the tangent plane towards the nearest point (:func:`foot_distances`)."""
NEWTON = 4
"""Newton steps back onto ``f = 0`` after each slide."""
SETTLED = 1e-10
"""A foot lies on ``f = 0`` when Newton's last step is below this fraction of the ball's radius."""
NORMAL = 1e-3
"""A foot ``q`` of ``p`` is final when the part of ``p − q`` along the tangent plane is below this
fraction of ``|p − q|`` (where ``f = 0`` is flat about ``q``, the distance is then overstated by
at most half its square, ``5e-7`` of it)."""


@dataclass(frozen=True, eq=False)
class NearestScene:
    """The typed surface's scene as the nearest exact surface's: its ball on ``g``'s axis, its
    profile traced there; the user's box and the typed mesh (a witness of coverage: ``g`` lies
    within the rounding of it) are kept."""

    region: ClipSphere
    profile_curve: LineData
    box: ClipBox | None
    surface: MeshData


def nearest_scene(scene: Where, exact: Analysis) -> NearestScene:
    """``scene`` made the exact surface's (see :class:`NearestScene`)."""
    rec = exact.recognition
    region = scene.region
    profile = LineData.empty()
    if rec.axis is not None:
        point, direction = float_vector(rec.axis.point), float_vector(rec.axis.direction)
        centre = foot_on_line(np.asarray(region.center), point, direction)
        region = ClipSphere((float(centre[0]), float(centre[1]), float(centre[2])), region.radius)
    if rec.profile is not None:
        profile = profile_curve(
            polynomial_terms(zero_set_profile(rec.profile).rational, ("s", "r")),
            float_vector(rec.profile.frame_point),
            float_vector(rec.profile.frame_direction),
            float_vector(rec.profile.frame_normal),
            region,
        )
    return NearestScene(region, profile, scene.box, scene.surface)


def typed_deviation(shape: object, polynomial: str, scene: Where) -> float:
    """The largest distance from points of the part's faces inside the region to the typed
    surface ``f = 0`` (``polynomial``: its square-free part): to the nearest foot found on it
    (:func:`foot_distances`), the first-order ``|f|/|∇f|`` where none settles."""
    terms = polynomial_terms(polynomial)
    points = np.concatenate([face_normals(face, SAMPLES)[0] for face in faces_of(shape)])
    if scene.box is not None:
        low, high = np.array(scene.box.bounds[0::2]), np.array(scene.box.bounds[1::2])
        points = points[np.all((points >= low) & (points <= high), axis=1)]
    else:
        points = points[np.linalg.norm(points - np.asarray(scene.region.center), axis=1) <= scene.region.radius]
    if not len(points):
        return 0.0
    distance = foot_distances(terms, points, scene.region.radius)
    unsettled = np.isnan(distance)
    distance[unsettled] = first_order_distance(terms, points[unsettled])
    return float(np.nanmax(np.where(np.isfinite(distance), distance, np.nan), initial=0.0))


def foot_distances(terms: Terms, points: np.ndarray, radius: float) -> np.ndarray:
    """The distance from each point ``p`` to the nearest foot ``q`` on ``f = 0`` found from it,
    ``nan`` where none settles: Newton steps ``−f·∇f/|∇f|²`` of at most ``STEP·radius``, then up to
    ``ROUNDS`` times a half step along the tangent plane at ``q`` towards ``p`` and Newton's steps
    back, until ``p − q`` is along ``∇f(q)`` (:data:`NORMAL`). Every foot kept lies on ``f = 0`` to
    ``SETTLED·radius``, so each distance bounds the true one from above; the first-order
    ``|f|/|∇f|`` does not, and near a singular point of the part, where the typed ``∇f`` is only
    the rounding's, it is far too large (0.18 at a point ``2·10⁻⁵`` from the apex of a rounded
    cone whose typed zero set is 0.0025 from it, docs/math.md §11)."""
    start = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    foot = start.copy()
    best = np.full(len(start), np.nan)
    active = np.arange(len(start))
    for _ in range(ROUNDS):
        moved_to = foot[active]
        for _ in range(NEWTON):
            moved_to, last, normal = _newton_step(terms, moved_to, STEP * radius)
        offset = start[active] - moved_to
        distance = np.linalg.norm(offset, axis=1)
        settled = last <= SETTLED * radius
        best[active] = np.fmin(best[active], np.where(settled, distance, np.nan))
        slide = offset - np.einsum("ij,ij->i", offset, normal)[:, None] * normal
        foot[active] = moved_to + 0.5 * slide
        final = settled & (np.linalg.norm(slide, axis=1) <= NORMAL * distance + SETTLED * radius)
        active = active[~final]
        if not len(active):
            break
    return best


def _newton_step(terms: Terms, points: np.ndarray, longest: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One Newton step of every point towards ``f = 0``, shortened to at most ``longest``; the
    points moved, the full step's length (``inf`` where ``∇f`` vanishes and ``f`` does not) and
    the unit normal ``∇f/|∇f|`` at the points given (0 where it vanishes)."""
    values, grads = value_and_gradient(terms, points, normalise=True)
    norm = np.linalg.norm(grads, axis=1)
    usable = (norm > 0) & np.isfinite(norm) & np.isfinite(values)
    safe = np.where(usable, norm, 1.0)
    normal = np.where(usable[:, None], grads / safe[:, None], 0.0)
    length = np.where(usable, np.abs(values) / safe, np.where(values == 0, 0.0, np.inf))
    step = -np.sign(values) * np.minimum(length, longest)
    return points + np.where(usable, step, 0.0)[:, None] * normal, length, normal


def nearest_lines(nearest: NearestSurface, deviation: float) -> tuple[str, ...]:
    """The header's account of the substitution."""
    rounding = "within" if nearest.within_rounding else "beyond"
    return (
        f"rounded input: the part of the nearest exact surface of revolution {nearest.polynomial} = 0",
        f"its coefficients {nearest.relative_distance:.2g} (relative) from the typed ones, {rounding} their rounding",
        f"measured deviation of the part from the typed surface: {deviation:.2g}",
    )
