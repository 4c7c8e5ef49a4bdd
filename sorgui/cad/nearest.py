"""Rounded input: the part of the exact surface it was meant to be (docs/math.md §8, §11).

A CAD system prints its surfaces with rounded coefficients, so the usual input is exactly no
surface of revolution, only within its rounding of one: the engine finds that nearest exact
surface ``g`` (``Approximation.nearest``, with its own exact analysis). Its part is written
instead, in the typed surface's region (the ball moved onto ``g``'s exact axis, the profile of
``g`` traced there as the 3D view traces one), and the file's header and the summary say so:
``g``, its relative distance to ``f`` over the coefficients, and the largest distance from
points of the part to the typed surface ``f = 0``, measured.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

from sorgui.engine.results import Analysis, NearestSurface
from sorgui.engine.values import float_vector, polynomial_terms, zero_set_profile
from sorgui.render import ClipBox, ClipSphere, LineData, MeshData, profile_curve
from sorgui.render.geometry import foot_on_line
from sorgui.render.sampling import first_order_distance

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
    """The largest first-order distance ``|f|/|∇f|`` from points of the part's faces inside the
    region to the typed surface ``f = 0`` (``polynomial``: its square-free part)."""
    terms = polynomial_terms(polynomial)
    points = np.concatenate([face_normals(face, SAMPLES)[0] for face in faces_of(shape)])
    if scene.box is not None:
        low, high = np.array(scene.box.bounds[0::2]), np.array(scene.box.bounds[1::2])
        points = points[np.all((points >= low) & (points <= high), axis=1)]
    else:
        points = points[np.linalg.norm(points - np.asarray(scene.region.center), axis=1) <= scene.region.radius]
    if not len(points):
        return 0.0
    distance = first_order_distance(terms, points)
    return float(np.nanmax(np.where(np.isfinite(distance), distance, np.nan), initial=0.0))


def nearest_lines(nearest: NearestSurface, deviation: float) -> tuple[str, ...]:
    """The header's account of the substitution."""
    rounding = "within" if nearest.within_rounding else "beyond"
    return (
        f"rounded input: the part of the nearest exact surface of revolution {nearest.polynomial} = 0",
        f"its coefficients {nearest.relative_distance:.2g} (relative) from the typed ones, {rounding} their rounding",
        f"measured deviation of the part from the typed surface: {deviation:.2g}",
    )
