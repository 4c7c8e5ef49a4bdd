"""From a rounded near-surface of revolution to the exact surface it was meant to be
(docs/math.md §8, "The nearest exact surface").

The fit of :mod:`.near_symmetry` gives a float axis (or centre, or normal) and float
coefficients of the invariant basis ``h^i ρ^j``. Snapping replaces them by the *simplest*
exact values that keep the fit within the input's rounding:

* **Direction:** the primitive integer vector with the smallest common denominator ``D`` that
  approximates the direction's ratios within ``ε`` (simultaneous approximation, searched over
  ``D``), for ``ε = 10⁻², 10⁻³, …``: the first one whose float fit still passes wins. Rational
  unit vectors and directions in a real quadratic field ``QQ(√d)`` (:func:`quadratic_direction`,
  the axes of CAD parts turned by 30° or 45°) are the other two families.
* **Point:** the profile's centre (a cylinder's foot), each coordinate the simplest rational
  (fewest continued-fraction steps) within ``ε·L``, the same way; in a quadric's second pass
  (:func:`snap_again`) refitted on the exact axis, a paraboloid's vertex, decimals first.
* **Coefficients** (:mod:`.coefficients`): snapped from the fit, snapped one ratio at a time
  with some held, or as fitted; the candidate with the fewest bits whose *exact* residual
  passes wins.
* **Minimax axis:** when the simplest coefficients miss the rounding of one coefficient on
  every snapped axis, the axis that makes the largest residual smallest is tried before the
  coefficients as fitted.

The exact surface ``g = Σ q_ij h^i ρ^j`` is then built over ``QQ`` (or ``QQ(√d)``) and checked
by the exact recognizer (docs/math.md §2) before it is returned; a surface within the rounding
is preferred, then the simplest.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, NamedTuple, TypeAlias

import numpy as np
from flint import fmpq, fmpq_mpoly, fmpq_mpoly_ctx
from sympy.polys.domains import QQ

from ..algebra.polys import XYZ, Poly, from_flint, number_field, poly_ring, to_flint
from ..recognition.symmetry import (
    CYLINDER,
    PLANE,
    REVOLUTION,
    SPHERE,
    Symmetry,
    rational_symmetry,
    recognize_symmetry,
)
from ..syntax import square_roots
from . import dense
from .coefficients import (
    HELD,
    SNAPPED,
    TORUS_TERMS,
    Typed,
    bits,
    coefficient_candidates,
    decimal_bits,
    direction_bits,
    matched_scales,
    shape_bits,
    torus_completion,
    within_scale,
)
from .cones import EXPONENTS, Build, Check, nearest_cone
from .cylinders import EXPONENTS as CYLINDER_TERMS
from .cylinders import nearest_cylinder, radius_cost
from .dense import FloatArray
from .directions import (
    FAMILIES,
    POINT_EPSILONS,
    POINT_PRECISION,
    Direction,
    DirectionSnap,
    Quadratic,
    QuadraticVector,
    Vector,
    decimal_near,
    direction_parts,
    integer_vector,
    quadratic_family,
    rational_point,
    simplest_near,
    snapped_directions,
    squared_length,
    three,
)
from .near_symmetry import Candidate, Fit, Normalised, fit, refine_fixed, refine_minimax, refit_point
from .precision import Rounding
from .spheres import EXPONENTS as SPHERE_TERMS
from .spheres import nearest_sphere
from .tori import nearest_torus

AXIS_TRIES = 3
MAX_CHECKS = 16
SPREADS = (3.0, 1.0, 0.3)
"""Radii, in standard errors, within which a refined axis is snapped (widest first)."""
MINIMAX_TRIES = 2
"""Of the simplest coefficients tried on the snapped axes, how many sets get a minimax axis."""
MINIMAX_POINTS = 3
"""About how many exact points (the simplest of the snapped axes') a minimax axis is turned."""
MINIMAX_SPREADS = (0.1, 0.01)
"""The same for the axis that makes the largest residual smallest: that axis is already
within the rounding, and a coarse snap would undo it."""
FLAT_SLOPE = 1e-8
"""A change of the profile's terms of degree ``d - 1`` under a unit shift along the axis below
this (relative to the terms) is the floating-point fit's noise, not a slope: a paraboloid's
term in ``h`` does not change at all, and dividing by that noise put its centre at 10¹⁰."""
DECIMAL_RADIUS = 1e-8
"""The finest radius (relative to the part's size) at which a point is snapped to a decimal
(:func:`exact_axes`, in the second pass): a designer's placement has at most about 8
significant digits, and a finer decimal is no simpler than the simplest rational."""
MAX_SHIFT = 1e3
"""A profile centre farther than this along the axis from its foot (in the units of the
normalised ``f``, whose points are of size 1) is noise: the foot is taken instead."""


@dataclass(frozen=True)
class ExactSurface:
    """The snapped exact surface ``g`` with its exact axis data and its distance to ``f``;
    ``direction`` and ``point`` are the snapped axis (or normal, or centre) in the frame that
    keeps the profile simple, for the exact analysis to use."""

    polynomial: Poly
    symmetry: Symmetry
    residual: float
    largest: float
    relative_distance: float
    direction: Vector | QuadraticVector | None
    point: Vector | None


Built: TypeAlias = fmpq_mpoly | Poly
"""An exact surface as :func:`build` makes it: over ``QQ`` a flint polynomial (made a sympy
``Poly`` only once it passes, :func:`check_surface`), over ``QQ(√d)`` a sympy ``Poly``."""


def exact_axes(
    f: Normalised, best: Fit, directions: list[Direction], tolerance: float, again: bool = False
) -> Iterator[tuple[Direction | None, Vector | None]]:
    """Exact (direction, point) pairs to try, simplest first: the first ``AXIS_TRIES``
    directions whose float fit passes, each with the points near the profile's centre on that
    axis whose float fit passes, coarsest first (docs/math.md §8), each coordinate the simplest
    rational within the radius. A coarse pair can pass with free coefficients and fail once
    they are snapped, so finer pairs follow. On an axis in a quadratic field the point is its
    one rational point, found within ``tolerance`` (the input's relative rounding), when its
    foot is irrational. ``again``, the second pass of a quadric
    (:func:`snap_again`, :func:`_start_points`): for each radius down to :data:`DECIMAL_RADIUS`
    the decimal of fewest places first (a CAD part's vertex is placed in decimals)."""
    kind = best.candidate.kind
    limit = max(1.0 + best.noise, best.residual * 1.5)

    def nearby(eps: float) -> tuple[Callable[[float, float], Fraction], ...]:
        return (decimal_near, simplest_near) if again and eps >= DECIMAL_RADIUS else (simplest_near,)

    tried = 0
    for a in directions if kind in (REVOLUTION, CYLINDER, PLANE) else [None]:
        direction = None if a is None else np.array([float(v) for v in a])
        if kind == PLANE:
            if fit(f, best.candidate, direction=direction).residual <= limit:
                yield a, None
                tried += 1
        else:
            starts = _start_points(f, best, a, tolerance, limit, again)
            if not starts:
                continue
            tried += 1
            seen: list[Vector] = []
            for point in starts:
                passing = False
                for eps, near in ((e, near) for e in POINT_EPSILONS for near in nearby(e)):
                    c = three(near(float(v) * f.length, eps * f.length) for v in point)
                    if c in seen:
                        continue
                    seen.append(c)
                    float_c = np.array([float(v) for v in c]) / f.length
                    passing = passing or fit(f, best.candidate, point=float_c, direction=direction).residual <= limit
                    if passing:
                        yield a, c
        if tried >= AXIS_TRIES:
            return


def _start_points(
    f: Normalised, best: Fit, a: Direction | None, tolerance: float, limit: float, again: bool = False
) -> list[FloatArray]:
    """The points of the axis along ``a`` whose coordinates are snapped, in order, each one whose
    float fit passes: the profile's centre (:func:`profile_centre`; the foot of a cylinder's
    axis, the vertex of a paraboloid) and, on an axis in a quadratic field, its one rational point
    (:func:`.directions.rational_point`, within ``POINT_PRECISION`` times ``tolerance``), first
    for a cylinder, whose foot is irrational when that point is off the origin.

    ``again``, the second pass of a quadric that got no surface within the rounding
    (:func:`snap_again`): a fitted point that fails on the exact axis along ``a`` is fitted
    again for ``a`` (:func:`.near_symmetry.refit_point`; the fitted axis turned to ``a`` about a
    point near the origin misses a vertex 250 units away), a paraboloid's point is its vertex,
    and points are snapped to decimals first (:func:`exact_axes`). Not in the first pass: a
    refitted point makes wrong directions pass as well, whose surfaces use up the checks before
    a right one's."""
    point = best.candidate.point
    assert point is not None  # every kind of surface of revolution but a plane has a point
    if a is None:
        return [point]
    direction = np.array([float(v) for v in a])
    starts = [profile_centre(f, best, direction, vertex=again)]
    if again and fit(f, best.candidate, point=starts[0], direction=direction).residual > limit:
        turned = fit(f, best.candidate, point=refit_point(f, best.candidate, direction), direction=direction)
        starts = [profile_centre(f, turned, direction, vertex=True)]
    quadratic = _quadratic(a)
    if quadratic is not None:
        found = rational_point(starts[0] * f.length, quadratic, POINT_PRECISION * tolerance)
        if found is not None:
            rational = found / f.length
            starts = [rational, *starts] if best.candidate.kind == CYLINDER else [*starts, rational]
    return [p for p in starts if fit(f, best.candidate, point=p, direction=direction).residual <= limit]


def _quadratic(a: Direction | None) -> QuadraticVector | None:
    """``a`` if it is a direction in a quadratic field."""
    if a is None:
        return None
    x, y, z = a
    return (x, y, z) if isinstance(x, Quadratic) and isinstance(y, Quadratic) and isinstance(z, Quadratic) else None


def profile_centre(f: Normalised, best: Fit, direction: FloatArray, vertex: bool = False) -> FloatArray:
    """The point of the axis about which the profile's terms of degree ``d - 1`` are smallest
    (the centre of a torus, the vertex region of a paraboloid): least squares in the shift
    ``t`` along the axis, whose effect on those terms is linear. Where those terms do not move,
    the foot, or with ``vertex`` a quadric's vertex (:func:`_vertex`)."""
    unit = direction / np.linalg.norm(direction)
    point = best.candidate.point
    assert point is not None  # an axis has a point
    foot = point - (point @ unit) * unit
    if best.candidate.kind != REVOLUTION:
        return foot

    def below_top(t: float) -> FloatArray:
        local = fit(f, best.candidate, point=foot + t * unit, direction=unit)
        return np.array([q for (i, j), q in zip(local.exponents, local.coefficients) if i + 2 * j == f.degree - 1])

    at_zero, at_one = below_top(0.0), below_top(1.0)
    slope = at_one - at_zero
    if float(np.linalg.norm(slope)) > FLAT_SLOPE * max(float(np.linalg.norm(at_zero)), 1.0):
        t = -float(slope @ at_zero) / float(slope @ slope)
        if abs(t) <= MAX_SHIFT:
            return foot + t * unit
    return _vertex(f, best, foot, unit) if vertex else foot  # those terms do not move with the point


def _vertex(f: Normalised, best: Fit, foot: FloatArray, unit: FloatArray) -> FloatArray:
    """The vertex of a paraboloid ``d² − 2p·h + k`` about the axis through ``foot`` along
    ``unit``: a shift ``t`` along the axis changes only ``k``, by ``2p·t``, and at the vertex
    ``k = 0``. A CAD part's vertex is its placement, decimals where the foot is not (on an axis
    turned by 30° the foot is irrational). For other surfaces whose terms of degree ``d − 1``
    do not move (none of degree 2), the foot."""
    if f.degree != 2:
        return foot

    def constant(t: float) -> float:
        local = fit(f, best.candidate, point=foot + t * unit, direction=unit)
        return float(local.coefficients[local.exponents.index((0, 0))])

    at_zero = constant(0.0)
    slope = constant(1.0) - at_zero
    if slope == 0.0 or abs(at_zero / slope) > MAX_SHIFT:
        return foot
    return foot - at_zero / slope * unit


def _radius(sigma: FloatArray, spread: float, family: DirectionSnap) -> float | FloatArray:
    """Snapping radii from standard errors (one number for the integer family)."""
    radii = np.maximum(sigma * spread, 1e-15)
    return float(radii.max()) if family is integer_vector else radii


def snap(f: Normalised, best: Fit, exact: Poly, rounding: Rounding) -> ExactSurface | None:
    """The simplest exact surface of the fit's kind within the rounding, or ``None``: for each
    family of directions the first surface that passes, and for a quadric the nearest cone or
    cylinder (:func:`.cones.nearest_cone`, :func:`.cylinders.nearest_cylinder`), and for a
    quartic the nearest torus (:func:`.tori.nearest_torus`: the families' tori may hold the
    rounding on a direction of 23-bit coordinates, with no designer's coefficients); of these a
    torus or a cone (the CAD part) first, then one whose coefficients were snapped (not fitted:
    coefficients fitted to an axis fit it whatever the axis), then the one whose profile
    coefficients and axis have the fewest bits."""
    typed = Typed(to_flint(exact), dense.float_coefficients(exact)) if exact.ring.domain == QQ else None
    found: list[_Found] = []
    for family in FAMILIES if best.candidate.direction is not None else (None,):
        surface = _first_exact(f, best, family, typed, rounding)
        if surface is not None:
            found.append(surface)
    if best.candidate.kind in (REVOLUTION, CYLINDER):
        surface = _first_exact(f, best, quadratic_family, typed, rounding)
        if surface is not None:
            found.append(surface)
    if best.candidate.kind == CYLINDER and f.degree == 2 and typed is not None:
        assert best.candidate.direction is not None  # an axis has a direction
        builder, checker = _quadric_builder(CYLINDER, CYLINDER_TERMS), _checker(f, typed, rounding)
        cylinder = nearest_cylinder(f, typed, rounding, best.candidate.direction, builder, checker)
        if cylinder is not None:
            found.append(_Found(cylinder[0], cylinder[1], False, False))
    if best.candidate.kind == REVOLUTION and f.degree == 2 and typed is not None:
        assert best.candidate.direction is not None  # an axis has a direction
        centre = profile_centre(f, best, best.candidate.direction) * f.length

        cone = nearest_cone(
            f, typed, rounding, centre, _quadric_builder(REVOLUTION, EXPONENTS), _checker(f, typed, rounding)
        )
        found = [item._replace(cone=_about_apex(item.coefficients)) for item in found]
        if cone is not None:
            found.append(_Found(cone[0], cone[1], False, False, True))
    if best.candidate.kind == SPHERE and f.degree == 2 and typed is not None:
        about = _quadric_builder(SPHERE, SPHERE_TERMS)
        sphere = nearest_sphere(
            typed,
            rounding,
            lambda c, coefficients: about(None, c, coefficients),
            lambda c, g: check_surface(g, typed, rounding, f, None, c),
        )
        if sphere is not None:
            found.append(_Found(sphere[0], sphere[1], False, False))
    if best.candidate.kind == REVOLUTION and f.degree == 4 and typed is not None:
        assert best.candidate.direction is not None  # an axis has a direction
        centre = profile_centre(f, best, best.candidate.direction) * f.length
        torus = nearest_torus(
            f, typed, rounding, centre, _quadric_builder(REVOLUTION, TORUS_TERMS), _checker(f, typed, rounding)
        )
        if torus is not None:
            found.append(_Found(torus[0], torus[1], False, True))
    if not found:
        return None
    return min(found, key=_rank).surface


def snap_again(f: Normalised, best: Fit, exact: Poly, rounding: Rounding) -> ExactSurface | None:
    """The second pass of a quadric of revolution whose :func:`snap` found no surface within
    the rounding: the families again, the point refitted on each exact axis and a paraboloid's
    at its vertex (:func:`_start_points`)."""
    if best.candidate.kind != REVOLUTION or f.degree != 2 or exact.ring.domain != QQ:
        return None
    typed = Typed(to_flint(exact), dense.float_coefficients(exact))
    found = [
        surface
        for family in (*FAMILIES, quadratic_family)
        if (surface := _first_exact(f, best, family, typed, rounding, again=True)) is not None
    ]
    return min(found, key=_rank).surface if found else None


def _rank(found: _Found) -> tuple[bool, bool, bool, int]:
    """How :func:`snap` orders the families' surfaces: within the rounding first, then a torus
    or a cone, then snapped coefficients (a cone's, held about its apex, are its structure
    however its slope was found; a cylinder's radius costs its bits, however it was found),
    then the fewest bits of the coefficients (a torus's constant,
    derived, costs none; a cone's slope ``K`` counts :data:`CONE_SLOPE_WEIGHT` times its bits, a
    cylinder's radius :data:`.cylinders.RADIUS_WEIGHT` times) and the axis."""
    size = shape_bits(found.coefficients[1:] if found.torus else found.coefficients)
    squared = _radius_squared(found)
    if squared is not None:
        size = radius_cost(squared)
    slope = _slope(found) if found.cone else None
    if slope is not None:
        size = CONE_SLOPE_WEIGHT * bits([slope])
    return (
        found.surface.largest > 1.0,
        not (found.torus or found.cone),
        found.fitted and not found.cone and squared is None,
        size + _axis_bits(found.surface),
    )


CONE_SLOPE_WEIGHT = 8
"""How many times the bits of a cone's ``K = tan²θ`` count against its axis's (:func:`_rank`):
the slope is the part's design (45°: ``−x² + y²``), while a turned axis's direction is an
approximation at any size (45° on an axis of 52-bit coordinates, not ``−11026149x² +
11026160y²`` on one of 12; a 20° cone on its designed axis ``(10, 20, −7)``, not a simpler
slope on an axis of 82-bit coordinates)."""


def _radius_squared(found: _Found) -> Fraction | None:
    """``r² = −q₀₀/(q₀₁|a|²)`` of a cylinder (``ρ = |a|²|p − c|² − h²``), when ``|a|²`` is rational;
    ``r² = −q₀₀/q₀₁`` of a sphere about its centre."""
    direction = found.surface.direction
    if found.surface.symmetry.kind == SPHERE and len(found.coefficients) == 2 and found.coefficients[1]:
        return -found.coefficients[0] / found.coefficients[1]
    if found.surface.symmetry.kind != CYLINDER or direction is None or len(found.coefficients) != 2:
        return None
    norm2 = squared_length(direction)
    q00, q01 = found.coefficients
    return None if norm2 is None or not q01 else -q00 / (q01 * norm2)


def _slope(found: _Found) -> Fraction | None:
    """``K = −(q₂₀|a|² + q₀₁)/q₀₁`` of a cone about its apex, when ``|a|²`` is rational."""
    direction = found.surface.direction
    norm2 = None if direction is None else squared_length(direction)
    q20, q01 = found.coefficients[2], found.coefficients[3]
    return None if norm2 is None or not q01 else -(q20 * norm2 + q01) / q01


def _quadric_builder(kind: str, exponents: tuple[tuple[int, int], ...]) -> Build:
    """:func:`build` of a surface of ``kind`` on ``exponents``, for :mod:`.cones`,
    :mod:`.cylinders` and :mod:`.tori` (and with no direction, :mod:`.spheres`)."""

    def built(a: Direction | None, c: Vector, coefficients: list[Fraction]) -> Built | None:
        return build(kind, a, c, exponents, coefficients)

    return built


def _checker(f: Normalised, typed: Typed, rounding: Rounding) -> Check[ExactSurface]:
    """:func:`check_surface` against the typed ``f``, for :mod:`.cones`, :mod:`.cylinders` and
    :mod:`.tori`."""

    def checked(g: Built, a: Direction, c: Vector) -> ExactSurface | None:
        return check_surface(g, typed, rounding, f, a, c)

    return checked


def _about_apex(coefficients: list[Fraction]) -> bool:
    """Whether a quadric's ``q_ij`` (on ``1, h, h², ρ``, the fit's terms) are a cone's about its
    apex: no term ``1`` or ``h`` (the general families find cones so when the profile's centre
    snaps to the apex)."""
    return len(coefficients) == 4 and not coefficients[0] and not coefficients[1] and all(coefficients[2:])


def _first_exact(
    f: Normalised,
    best: Fit,
    family: DirectionSnap | None,
    typed: Typed | None,
    rounding: Rounding,
    again: bool = False,
) -> _Found | None:
    """The first exact surface, in the order of :func:`exact_axes`, with every coefficient
    within the rounding (else the first within twice it, in the mean). When the simplest
    coefficients fail on a coarse axis, the axis is refined with them held fixed and snapped
    again, finely."""
    fallback: _Found | None = None
    for found in _exact_surfaces(f, best, family, typed, rounding, again):
        if found.surface.largest <= 1.0:
            return found
        if fallback is None:
            fallback = found
    return fallback


class _Found(NamedTuple):
    """An exact surface of :func:`_exact_surfaces` (or :func:`.cones.nearest_cone`): its
    coefficients, whether they were fitted rather than snapped, and whether they are a torus's
    (:func:`torus_completion`) or a cone's."""

    coefficients: list[Fraction]
    surface: ExactSurface
    fitted: bool
    torus: bool
    cone: bool = False


def _exact_surfaces(
    f: Normalised,
    best: Fit,
    family: DirectionSnap | None,
    typed: Typed | None,
    rounding: Rounding,
    again: bool = False,
) -> Iterator[_Found]:
    """Exact surfaces within twice the rounding (in the mean), simplest axes first; at most
    ``MAX_CHECKS`` exact surfaces are built, and the axis is refined with fixed coefficients
    on the first axis only (an input with irrational data has no simple exact surface, and
    that must be found out quickly). The axes that make the largest residual smallest come
    last, for a torus's coefficients and the simplest ones only: they fit any coefficients, the
    intended ones or not, but they are tried before the coefficients as fitted (which always
    fit), or any that are not a torus's when a torus's failed, are taken."""
    directions: list[Direction] = []
    if family is not None:
        assert best.candidate.direction is not None  # a family snaps the candidate's direction
        directions = snapped_directions(best.candidate.direction, family)
    kind = best.candidate.kind

    def is_torus(a: Direction | None, exponents: tuple[tuple[int, int], ...], coefficients: list[Fraction]) -> bool:
        norm2 = None if kind != REVOLUTION or a is None else squared_length(a)
        return norm2 is not None and torus_completion(exponents, coefficients, norm2) == coefficients

    def checked(
        a: Direction | None,
        c: Vector | None,
        exponents: tuple[tuple[int, int], ...],
        coefficients: list[Fraction],
        simplest: bool = True,
    ) -> tuple[list[Fraction], ExactSurface | None]:
        """The coefficients and the surface they make, if it is near ``f``. When they miss the
        rounding and are among the simplest, they are rescaled by the simplest factor that puts
        every coefficient within it (:func:`within_scale`), and a surface that passes only so
        is kept in ``rescaled`` for after every other axis and coefficient: a rescaled fit is
        a weaker sign than one that holds as snapped."""
        g = build(kind, a, c, exponents, coefficients)
        if g is None:
            return coefficients, None
        surface = check_surface(g, typed, rounding, f, a, c)
        if simplest and (surface is None or surface.largest > 1.0) and isinstance(g, fmpq_mpoly) and typed is not None:
            scale = within_scale(g, typed, rounding)
            if scale is not None and scale != 1:
                coefficients = [scale * v for v in coefficients]
                fitted = check_surface(g * fmpq(scale.numerator, scale.denominator), typed, rounding, f, a, c)
                if fitted is not None and fitted.largest <= 1.0:
                    rescaled.append(_Found(coefficients, fitted, False, is_torus(a, exponents, coefficients)))
        return coefficients, surface

    checks = 0
    within: _Found | None = None
    rescaled: list[_Found] = []
    refitted: list[_Found] = []  # snapped one ratio at a time, some held (.coefficients)
    held: list[_Held] = []
    for first, (a, c) in enumerate(exact_axes(f, best, directions, rounding.tolerance, again)):
        direction = None if a is None else np.array([float(v) for v in a])
        point = None if c is None else np.array([float(v) for v in c]) / f.length
        local = fit(f, best.candidate, point=point, direction=direction)
        degrees = np.array([i + 2 * j for i, j in local.exponents])

        def matched_for(
            ratios: list[Fraction], a: Direction | None = a, c: Vector | None = c, local: Fit = local
        ) -> list[Fraction]:
            g = build(kind, a, c, local.exponents, ratios)
            return [] if not isinstance(g, fmpq_mpoly) or typed is None else matched_scales(g, typed, rounding)

        def within_for(
            ratios: list[Fraction], a: Direction | None = a, c: Vector | None = c, local: Fit = local
        ) -> Fraction | None:
            g = build(kind, a, c, local.exponents, ratios)
            return None if not isinstance(g, fmpq_mpoly) or typed is None else within_scale(g, typed, rounding)

        norm2 = None if kind != REVOLUTION or a is None else squared_length(a)
        candidates = coefficient_candidates(f, local, matched_for, norm2, within_for)
        for rank, (coefficients, source) in enumerate(candidates):
            checks += 1
            if checks > MAX_CHECKS:
                break
            simplest = source == SNAPPED and rank < 2
            coefficients, surface = checked(a, c, local.exponents, coefficients, simplest)
            if source == HELD:
                if surface is not None and surface.largest <= 1.0 and not refitted:
                    refitted.append(_Found(coefficients, surface, True, is_torus(a, local.exponents, coefficients)))
                continue
            torus = is_torus(a, local.exponents, coefficients)
            if surface is not None and surface.largest <= 1.0 and held:
                if not simplest or (not torus and any(item.torus for item in held)):
                    within = _Found(coefficients, surface, source != SNAPPED, torus)  # simpler ones, or a torus,
                    break  # may hold on a minimax axis
            if surface is not None:
                yield _Found(coefficients, surface, source != SNAPPED, torus)
                if surface.largest <= 1.0:
                    return
            if not simplest:
                continue
            fixed = np.array([float(q) for q in coefficients]) * f.length**degrees / f.scale
            size = shape_bits(coefficients)
            held.append(_Held(size, torus, local.exponents, coefficients, fixed, local.candidate, c))
            if first > 0:
                continue
            for a2, c2 in _refined(f, held[-1], family).axes:
                scaled, surface = checked(a2, c2, local.exponents, coefficients)
                if surface is not None:
                    yield _Found(scaled, surface, False, torus)
                    if surface.largest <= 1.0:
                        return
        else:
            continue
        break
    tried: list[list[Fraction]] = []
    ordered = sorted(held, key=lambda item: (not item.torus, item.bits))
    for simple in ordered:
        if simple.coefficients in tried or len(tried) >= MINIMAX_TRIES:
            continue
        tried.append(simple.coefficients)
        refined = _refined(f, simple, family)
        seen = [item.point for item in ordered] + [c for item in held if item.refined for _, c in item.refined.axes]
        points = sorted({c for c in seen if c is not None}, key=lambda c: bits(list(c)))[:MINIMAX_POINTS]
        for a2, c2 in _minimax_axes(f, refined, simple.fixed, family, points):
            scaled, surface = checked(a2, c2, simple.exponents, simple.coefficients)
            if surface is not None:
                yield _Found(scaled, surface, False, simple.torus)
                if surface.largest <= 1.0:
                    return
    if rescaled:
        yield rescaled[0]
    if refitted:
        yield refitted[0]
    if within is not None:
        yield within


@dataclass
class _Held:
    """Simple coefficients (with their bits, whether they are a torus's, and as floats in the
    normalised units) tried on the axis ``candidate`` through the exact ``point``; ``refined``
    is that axis refined for them, once it is."""

    bits: int
    torus: bool
    exponents: tuple[tuple[int, int], ...]
    coefficients: list[Fraction]
    fixed: FloatArray
    candidate: Candidate
    point: Vector | None
    refined: _Refined | None = None


class _Refined(NamedTuple):
    """An axis refined with the coefficients held fixed, the standard errors of its direction's
    and point's coordinates, and the exact axes it was snapped to."""

    candidate: Candidate
    direction_sigma: FloatArray
    point_sigma: FloatArray
    axes: tuple[tuple[Direction | None, Vector | None], ...] = ()


def _refined(f: Normalised, held: _Held, family: DirectionSnap | None) -> _Refined:
    """``held``'s axis refined by least squares for its coefficients and snapped within
    ``SPREADS`` of its standard errors (computed once)."""
    if held.refined is None:
        refined = _Refined(*refine_fixed(f, held.candidate, held.fixed))
        held.refined = refined._replace(axes=tuple(_snapped_axes(f, refined, family, SPREADS)))
    return held.refined


def _minimax_axes(
    f: Normalised, refined: _Refined, fixed: FloatArray, family: DirectionSnap | None, points: list[Vector]
) -> Iterator[tuple[Direction | None, Vector | None]]:
    """Exact axes from the axis that makes the largest residual smallest for coefficients held
    at ``fixed``, snapped finely (``MINIMAX_SPREADS``: that axis is already within the rounding,
    and a coarse snap would undo it): turned about each of the exact ``points`` first (a simple
    point is kept: the simplest coefficients and the simplest point may have come from two
    different snapped axes), then moved as well."""
    for c in points:
        at = Candidate(refined.candidate.kind, refined.candidate.direction, np.array([float(v) for v in c]) / f.length)
        turned = refined._replace(candidate=refine_minimax(f, at, fixed, point_fixed=True))
        for a, _ in _snapped_axes(f, turned, family, MINIMAX_SPREADS):
            yield a, c
    moved = refined._replace(candidate=refine_minimax(f, refined.candidate, fixed))
    yield from _snapped_axes(f, moved, family, MINIMAX_SPREADS)


def _snapped_axes(
    f: Normalised, refined: _Refined, family: DirectionSnap | None, spreads: Sequence[float]
) -> Iterator[tuple[Direction | None, Vector | None]]:
    """The refined axis's direction (in ``family``) and point, each snapped to the simplest
    exact value within ``spread`` standard errors, for each spread."""
    moved = refined.candidate
    for spread in spreads:
        a = None
        if family is not None:
            assert moved.direction is not None  # refined from a candidate with a direction
            a = family(moved.direction, _radius(refined.direction_sigma, spread, family))
            if a is None:
                continue
        c = (
            None
            if moved.point is None
            else three(
                simplest_near(float(v) * f.length, float(max(e * spread, 1e-15)) * f.length)
                for v, e in zip(moved.point, refined.point_sigma)
            )
        )
        yield a, c


def _axis_bits(surface: ExactSurface) -> int:
    """The bits of an exact surface's axis: its point's coordinates and its direction's (both
    parts of a coordinate in ``QQ(√d)``; on a rational direction, :func:`.coefficients.axis_bits`).
    Two families may snap to the same profile coefficients; the simpler axis wins (the turned CAD
    part's ``(0, 1/2, √3/2)``, not a rational direction of 60-bit coordinates within the same
    rounding)."""
    direction = surface.direction
    point = [Fraction(v) for v in surface.point or ()]
    if direction is None:  # a sphere's centre, as a CAD system prints it; a plane's none
        return sum(decimal_bits(v) for v in point)
    if point:
        return direction_bits(direction, point)
    return bits(direction_parts(direction))


def build(
    kind: str,
    a: Direction | None,
    c: Vector | None,
    exponents: tuple[tuple[int, int], ...],
    coefficients: list[Fraction],
) -> Built | None:
    """``g = Σ q_ij h^i ρ^j`` over ``QQ`` (``h = a·(p - c)``, ``ρ = |p - c|²``; for a cylinder
    ``ρ`` is ``|a|²|p - c|² - h²``; for a plane ``h = a·p``), in flint; over ``QQ(√d)`` for a
    direction in that field (:func:`build_quadratic`)."""
    if a is not None and isinstance(a[0], Quadratic):
        return None if c is None else build_quadratic(kind, a, c, exponents, coefficients)
    ctx = to_flint(poly_ring(XYZ, QQ).gens[0]).context()
    x, y, z = ctx.gens()
    gens = (x, y, z)
    zero = fmpq_mpoly(0, ctx)
    origin = c if c is not None else (Fraction(0),) * 3
    shifted = [gens[i] - fmpq(origin[i].numerator, origin[i].denominator) for i in range(3)]
    h = sum((fmpq(a[i].numerator, a[i].denominator) * shifted[i] for i in range(3)), zero) if a is not None else zero
    rho = sum((s * s for s in shifted), zero)
    if kind == CYLINDER:
        assert a is not None  # a cylinder has an axis direction
        norm2 = sum(v * v for v in a)
        rho = fmpq(norm2.numerator, norm2.denominator) * rho - h * h
    top = max(i for i, _ in exponents)
    rho_powers = [rho**0]
    for _ in range(max(j for _, j in exponents)):
        rho_powers.append(rho_powers[-1] * rho)
    by_power_of_h = [zero] * (top + 1)  # g = Σ_i h^i·(Σ_j q_ij ρ^j), then by Horner's rule in h
    for (i, j), q in zip(exponents, coefficients):
        if q:
            by_power_of_h[i] += fmpq(q.numerator, q.denominator) * rho_powers[j]
    g = by_power_of_h[top]
    for i in range(top - 1, -1, -1):
        g = g * h + by_power_of_h[i]
    if g.is_zero() or g.total_degree() < 1:
        return None
    return g


def build_quadratic(
    kind: str, a: QuadraticVector, c: Vector, exponents: tuple[tuple[int, int], ...], coefficients: list[Fraction]
) -> Poly | None:
    """``g = Σ q_ij h^i ρ^j`` over ``QQ(√d)`` for a direction ``a`` in that field (as
    :func:`build`): computed over ``QQ`` with ``w = √d`` as a fourth variable, ``w²`` replaced by
    ``d``."""
    d = a[0].d
    ctx = fmpq_mpoly_ctx.get(("x", "y", "z", "w"), "lex")
    x, y, z, w = ctx.gens()
    zero = fmpq_mpoly(0, ctx)
    shifted = [v - fmpq(q.numerator, q.denominator) for v, q in zip((x, y, z), c)]
    h = sum(
        (
            (fmpq(q.a.numerator, q.a.denominator) + fmpq(q.b.numerator, q.b.denominator) * w) * s
            for q, s in zip(a, shifted)
        ),
        zero,
    )
    rho = sum((s * s for s in shifted), zero)
    if kind == CYLINDER:
        norm2 = _reduce_root(
            sum(
                ((fmpq(q.a.numerator, q.a.denominator) + fmpq(q.b.numerator, q.b.denominator) * w) ** 2 for q in a),
                zero,
            ),
            d,
        )
        rho = norm2 * rho - h * h
    g = zero
    for (i, j), q in zip(exponents, coefficients):
        if q:
            g += fmpq(q.numerator, q.denominator) * _reduce_root(h**i, d) * rho**j
    g = _reduce_root(g, d)
    if g.is_zero() or g.total_degree() < 1:
        return None
    K = number_field((d,))
    root = square_roots(K, (d,))[d]  # √d in K once: K.from_sympy of each coefficient took 30 ms
    terms: dict[tuple[int, int, int], Any] = {}
    for monom, coeff in zip(g.monoms(), g.coeffs()):
        key = dense.monomial(monom[:3])
        value = K.convert(QQ(int(coeff.p), int(coeff.q)))
        terms[key] = terms.get(key, K.zero) + (value * root if monom[3] else value)
    R = poly_ring(XYZ, K)
    return R.from_dict({m: v for m, v in terms.items() if v})


def _reduce_root(p: fmpq_mpoly, d: int) -> fmpq_mpoly:
    """``p`` with ``w²`` replaced by ``d`` (degree at most 1 in ``w``, the last variable)."""
    terms: dict[tuple[int, ...], fmpq] = {}
    for monom, coeff in zip(p.monoms(), p.coeffs()):
        k = int(monom[3])
        key = (*(int(e) for e in monom[:3]), k % 2)
        terms[key] = terms.get(key, fmpq(0)) + coeff * fmpq(d) ** (k // 2)
    return p.context().from_dict({m: c for m, c in terms.items() if c})


def check_surface(
    g: Built, typed: Typed | None, rounding: Rounding, f: Normalised, a: Direction | None, c: Vector | None
) -> ExactSurface | None:
    """``g`` with its exact residual against ``f``, if the exact recognizer agrees it is a
    surface of revolution and the residual is within twice the rounding (tested first: most
    candidates fail it)."""
    rational = isinstance(g, fmpq_mpoly)
    if typed is not None and rational:
        residual_terms = _float_terms(typed.flint - g)
        f_terms = typed.floats
    else:
        g_terms = _float_terms(g) if rational else dense.float_coefficients(g)
        if typed is not None:  # g over QQ(√d): the difference in floats (far below the rounding)
            f_terms = typed.floats
        else:
            scale = f.scale
            f_terms = {m: float(v) * scale / f.length ** sum(m) for m, v in zip(_monomials(f), f.vector)}
        residual_terms = {m: f_terms.get(m, 0.0) - g_terms.get(m, 0.0) for m in set(f_terms) | set(g_terms)}
    count = math.comb(rounding.degree + 3, 3)
    ratios = [abs(r) / rounding.bound(m) for m, r in residual_terms.items()]
    residual = math.sqrt(sum(v * v for v in ratios) / count)
    if residual > 2.0:
        return None
    symmetry = rational_symmetry(g) if rational else recognize_symmetry(g)
    if not symmetry.is_sor:
        return None
    norm_f = math.sqrt(sum(v * v for v in f_terms.values()))
    distance = math.sqrt(sum(r * r for r in residual_terms.values())) / norm_f
    polynomial = from_flint(g, poly_ring(XYZ, QQ)) if rational else g
    return ExactSurface(polynomial, symmetry, residual, max(ratios, default=0.0), distance, a, c)


def _float_terms(p: fmpq_mpoly) -> dict[dense.Monomial, float]:
    """The terms of ``p`` with float coefficients (``monoms`` and ``coeffs`` take a fifth of the
    time of ``to_dict``)."""
    return {dense.monomial(m): float(c) for m, c in zip(p.monoms(), p.coeffs())}


def _monomials(f: Normalised) -> list[tuple[int, int, int]]:
    i, j, k = np.nonzero(f.selected)
    return [(int(a), int(b), int(c)) for a, b, c in zip(i, j, k)]
