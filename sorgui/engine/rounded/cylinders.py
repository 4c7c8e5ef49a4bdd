"""The nearest exact cylinder of revolution of a rounded quadric (docs/math.md §8.5, "Cylinders").

A cylinder is fixed by its axis direction ``a``, a point ``c`` of its axis and its radius ``r``:

    g = |a|²·|p − c|² − (a·(p − c))² − |a|²·r²,

rational when ``a``, ``c`` and ``r²`` are. The profile's snapping (:mod:`.snapping`) snaps the
coordinates of a point near the axis one by one: the point leaves the axis by the snapping
error, and the radius fitted about it is off by many times its own error (a cylinder of radius
12.7 printed with 6 digits came out as ``r² = 6129/38``, ``r = 12.69998``). Here the axis is
found from every coefficient, and then snapped:

1. with ``a`` held, ``f ≈ λ(|p − c|² − (â·(p − c))² − r²)`` is linear in ``λ``, ``λc`` (two
   coordinates across the axis) and the constant: a weighted least-squares fit (weights: the
   rounding of each coefficient); ``â`` itself is fitted by Gauss and Newton's steps on the two
   angles of ``â``, the rest solved linearly at each step, and snapped in each family (a
   quadratic field's first: a part turned by 30° has ``a = (0, 1, −√3)``);
2. the foot ``c`` of the origin on the axis is snapped through ``|a|²·c``, whose coordinates are
   the designer's (``|a|²·c = |a|²·c₀ − (a·c₀)·a`` for a designed point ``c₀`` of the axis):
   to the nearest decimals of fewest places, then to the simplest rationals, coarsest first, the
   first whose fit (with ``r`` free) is within twice the rounding; on an axis in ``QQ(√d)``,
   whose foot is irrational, its one rational point is snapped instead;
3. ``r`` is snapped to the nearest decimal of fewest places (a CAD radius), else ``r²`` to the
   simplest rational, coarsest first; ``g`` is scaled by the simplest factor that puts every
   coefficient within the rounding (:func:`.coefficients.within_scale`) and checked exactly.

The simplest cylinder that passes, by the bits of its radius (:data:`RADIUS_WEIGHT` times),
point and direction (:func:`.coefficients.axis_bits`: the point as the decimals ``|a|²·c``), is
the answer.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from fractions import Fraction
from typing import TYPE_CHECKING

import numpy as np
from flint import fmpq_mpoly

from .coefficients import Typed, bits, direction_bits, scaled_surface, within_scale
from .cones import DIRECTION_RADII, MAX_RESIDUAL, Build, Check, S, simplest
from .dense import FloatArray, Monomial
from .directions import (
    FAMILIES,
    POINT_PRECISION,
    Direction,
    Quadratic,
    angles_of,
    decimal_near,
    quadratic_family,
    rational_point,
    rational_sqrt,
    simplest_near,
    squared_length,
    three,
    unit_at,
)
from .precision import Rounding

if TYPE_CHECKING:
    from ..algebra.linalg import Vector
    from ..algebra.polys import Poly
    from .near_symmetry import Normalised

EXPONENTS = ((0, 0), (0, 1))
"""The terms ``1, ρ`` of a cylinder about its axis, ``ρ = |a|²|p − c|² − h²`` (:func:`.snapping.build`)."""
FOOT_RADII = tuple(10.0**-k for k in range(2, 13))
"""Radii, relative to the size of the part, within which ``|a|²·c`` is snapped, coarsest first
(the foot of a turned axis has as many digits as the input)."""
RADIUS_RADII = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11)
"""Radii, relative to the radius, within which it is snapped, coarsest first."""
MAX_CHECKS = 300
"""Exact surfaces built and checked at most."""
RADIUS_WEIGHT = 16
"""How many times the bits of the radius count against those of the axis: the radius is the
part's design (``12.7``), a turned axis's direction an approximation at any size (``r =
12.699985`` on a direction of 13-bit coordinates, not ``12.7`` on one of 17)."""
DECIMAL_BITS = 16
"""A radius of fewer bits than this (``127/10``: 11) ends the search of finer directions."""


def nearest_cylinder(
    f: Normalised,
    typed: Typed,
    rounding: Rounding,
    direction: FloatArray,
    build: Build,
    check: Check[S],
) -> tuple[list[Fraction], S] | None:
    """The simplest cylinder of revolution with every coefficient within the rounding of the
    quadric ``f`` (its ``q_ij`` on :data:`EXPONENTS`, and the surface), or ``None``.
    ``direction`` is the fitted axis direction; ``build`` makes ``g`` and ``check`` checks it
    against the typed surface (:func:`.snapping.check_surface`)."""
    if f.degree != 2:
        return None
    monomials = [m for m in typed.floats if sum(m) <= 2]
    weights = np.array([1.0 / rounding.bound(m) for m in monomials])
    target = np.array([typed.floats[m] for m in monomials]) * weights
    unit = _refined_direction(monomials, weights, target, direction / np.linalg.norm(direction))
    found: list[tuple[int, list[Fraction], S]] = []
    checks = 0
    for family in (quadratic_family, *FAMILIES):
        for radius in DIRECTION_RADII:
            a = family(unit, radius)
            if a is None or squared_length(a) is None:
                continue
            passed, tried = _cylinder_along(a, monomials, weights, target, typed, rounding, build, check)
            checks += tried
            if passed is not None:
                found.append(passed)
                if passed[0] < RADIUS_WEIGHT * DECIMAL_BITS:
                    break  # a short radius: a finer direction has no simpler one
            if checks >= MAX_CHECKS:
                return simplest(found)
    return simplest(found)


def _cylinder_along(
    a: Direction,
    monomials: list[Monomial],
    weights: FloatArray,
    target: FloatArray,
    typed: Typed,
    rounding: Rounding,
    build: Build,
    check: Check[S],
) -> tuple[tuple[int, list[Fraction], S] | None, int]:
    """The simplest cylinder along the exact direction ``a`` that passes (its bits, coefficients
    and surface), and how many were checked."""
    norm2 = squared_length(a)
    assert norm2 is not None  # nearest_cylinder takes only directions of rational length
    unit = np.array([float(v) for v in a]) / math.sqrt(float(norm2))
    solved = _linear_fit(monomials, weights, target, unit)
    if solved is None or solved[3] > MAX_RESIDUAL:
        return None, 0
    lam, foot, r2, _ = solved
    if r2 <= 0:
        return None, 0
    scale = max(float(np.linalg.norm(foot)), math.sqrt(r2))
    checks = 0
    best: tuple[int, list[Fraction], S] | None = None
    for c in _snapped_points(a, norm2, foot, scale, rounding.tolerance):
        held = _radius_fit(monomials, weights, target, unit, np.array([float(v) for v in c]))
        if held is None or held[1] > MAX_RESIDUAL or held[0] <= 0:
            continue
        passed, tried = _radius_about(a, c, held[0], typed, rounding, build, check)
        checks += tried
        if passed is not None and (best is None or passed[0] < best[0]):
            best = passed
        if best is not None and (best[0] < RADIUS_WEIGHT * DECIMAL_BITS + direction_bits(a, c) or checks >= MAX_CHECKS):
            return best, checks  # a short radius: a finer point has no simpler one
    return best, checks


def _snapped_points(
    a: Direction, norm2: Fraction, foot: FloatArray, scale: float, tolerance: float
) -> Iterator[tuple[Fraction, Fraction, Fraction]]:
    """Exact points of the axis along ``a`` through ``foot`` (the foot of the origin), coarsest
    first, each snapped within :data:`FOOT_RADII` (times ``scale``) to decimals of fewest places,
    then to the simplest rationals: on a rational direction ``|a|²·c`` is snapped (the
    designer's numbers, module docstring); on one in a quadratic field, whose foot is
    irrational when the part is off the origin, the axis's one rational point
    (:func:`.directions.rational_point`, within :data:`.directions.POINT_PRECISION` times the
    input's relative rounding)."""
    quadratic = [v for v in a if isinstance(v, Quadratic)]
    if len(quadratic) == 3:
        found = rational_point(foot, three(quadratic), POINT_PRECISION * tolerance)
        if found is None:
            return
        point, factor = found, Fraction(1)
    else:
        point, factor = foot * float(norm2), norm2
    seen: set[tuple[Fraction, Fraction, Fraction]] = set()
    for radius in FOOT_RADII:
        for snap in (decimal_near, simplest_near):
            c = three(snap(float(v), radius * scale * float(factor)) / factor for v in point)
            if c not in seen:
                seen.add(c)
                yield c


def _radius_about(
    a: Direction,
    c: Vector,
    r2: float,
    typed: Typed,
    rounding: Rounding,
    build: Build,
    check: Check[S],
) -> tuple[tuple[int, list[Fraction], S] | None, int]:
    """The cylinder about the axis through ``c`` along ``a`` with the coarsest snapped radius
    near ``√r2`` that passes (its cost, coefficients and surface), and how many were checked."""
    norm2 = squared_length(a)
    assert norm2 is not None  # nearest_cylinder takes only directions of rational length
    found, checks = snapped_radius(
        r2, norm2, lambda coefficients: build(a, c, coefficients), typed, rounding, lambda g: check(g, a, c)
    )
    if found is None:
        return None, checks
    squared, coefficients, surface = found
    return (radius_cost(squared) + direction_bits(a, c), coefficients, surface), checks


def snapped_radius(
    r2: float,
    norm2: Fraction,
    build: Callable[[list[Fraction]], fmpq_mpoly | Poly | None],
    typed: Typed,
    rounding: Rounding,
    check: Callable[[fmpq_mpoly | Poly], S | None],
) -> tuple[tuple[Fraction, list[Fraction], S] | None, int]:
    """The coarsest radius snapped near ``√r2`` (:data:`RADIUS_RADII`: the decimal of fewest
    places, else ``r²`` the simplest rational) whose surface ``build([−norm2·r², 1])``, scaled
    within the rounding (:func:`.coefficients.within_scale`), passes ``check`` within it: its
    ``r²``, the scaled coefficients and the surface; and how many were checked (cylinders, and
    spheres with ``norm2 = 1``)."""
    r = math.sqrt(r2)
    checks = 0
    for r_radius in RADIUS_RADII:
        for squared in (decimal_near(r, r_radius * r) ** 2, simplest_near(r2, 2 * r_radius * r2)):
            checks += 1
            coefficients = [-norm2 * squared, Fraction(1)]
            g = build(coefficients)
            factor = None if g is None else within_scale(g, typed, rounding)
            if g is None or factor is None:
                continue
            surface = check(scaled_surface(g, factor))
            if surface is not None and surface.largest <= 1.0:
                return (squared, [factor * q for q in coefficients], surface), checks
    return None, checks


def radius_cost(squared: Fraction) -> int:
    """What the radius ``√squared`` costs against an axis: :data:`RADIUS_WEIGHT` times the bits
    of ``r`` when it is rational, else of ``r²``."""
    root = rational_sqrt(squared) if squared > 0 else None
    return RADIUS_WEIGHT * bits([squared if root is None else root])


def _basis(unit: FloatArray) -> tuple[FloatArray, FloatArray]:
    """An orthonormal pair across ``unit``."""
    e = np.zeros(3)
    e[int(np.argmin(np.abs(unit)))] = 1.0
    first = np.cross(unit, e)
    first /= np.linalg.norm(first)
    return first, np.cross(unit, first)


def _design(monomials: list[Monomial], unit: FloatArray) -> FloatArray:
    """The coefficients of ``λ(|P|² − (â·P)²) ``, ``P = p − c``, at ``monomials`` as linear forms in
    ``(λ, λc·e₁, λc·e₂, constant)`` (``e₁, e₂`` across ``â``)."""
    e1, e2 = _basis(unit)
    rows = []
    for m in monomials:
        row = np.zeros(4)
        powers = [i for i in range(3) for _ in range(m[i])]
        if sum(m) == 2:
            i, j = powers
            row[0] = (1.0 - unit[i] ** 2) if i == j else -2.0 * unit[i] * unit[j]
        elif sum(m) == 1:
            (i,) = powers
            row[1], row[2] = -2.0 * e1[i], -2.0 * e2[i]
        else:
            row[3] = 1.0
        rows.append(row)
    return np.array(rows)


def _linear_fit(
    monomials: list[Monomial], weights: FloatArray, target: FloatArray, unit: FloatArray
) -> tuple[float, FloatArray, float, float] | None:
    """With the axis along ``unit``: ``(λ, the foot of the origin on the axis, r², the weighted
    residual in units of the rounding)`` of the least-squares fit."""
    design = _design(monomials, unit) * weights[:, None]
    z, *_ = np.linalg.lstsq(design, target, rcond=None)
    lam = float(z[0])
    if lam == 0.0:
        return None
    e1, e2 = _basis(unit)
    foot = (z[1] * e1 + z[2] * e2) / lam
    r2 = float(foot @ foot) - float(z[3]) / lam
    residual = float(np.sqrt(np.mean((design @ z - target) ** 2)))
    return lam, foot, r2, residual


def _radius_fit(
    monomials: list[Monomial], weights: FloatArray, target: FloatArray, unit: FloatArray, point: FloatArray
) -> tuple[float, float] | None:
    """With the axis through ``point`` along ``unit`` held: ``(r², the weighted residual)`` of the
    least-squares fit of ``λ(|P|² − (â·P)² − r²)``, linear in ``λ`` and ``λr²``."""
    across = np.eye(3) - np.outer(unit, unit)
    rows = []
    for m in monomials:
        powers = [i for i in range(3) for _ in range(m[i])]
        if sum(m) == 2:
            i, j = powers
            value = across[i, j] * (1.0 if i == j else 2.0)
        elif sum(m) == 1:
            (i,) = powers
            value = -2.0 * float(across[i] @ point)
        else:
            value = float(point @ across @ point)
        rows.append([value, -1.0 if sum(m) == 0 else 0.0])
    design = np.array(rows) * weights[:, None]
    z, *_ = np.linalg.lstsq(design, target, rcond=None)
    if z[0] == 0.0:
        return None
    residual = float(np.sqrt(np.mean((design @ z - target) ** 2)))
    return float(z[1] / z[0]), residual


def _refined_direction(
    monomials: list[Monomial], weights: FloatArray, target: FloatArray, unit: FloatArray
) -> FloatArray:
    """``â`` of the least-squares fit over every coefficient: Gauss and Newton's steps on its two
    angles, the linear unknowns solved at each step (:func:`_linear_fit`)."""

    def residual(angles: FloatArray) -> FloatArray:
        theta, phi = angles
        design = _design(monomials, unit_at(theta, phi)) * weights[:, None]
        z, *_ = np.linalg.lstsq(design, target, rcond=None)
        values: FloatArray = design @ z - target
        return values

    angles = np.array(angles_of(unit))
    for _ in range(8):
        r = residual(angles)
        jacobian = np.empty((len(r), 2))
        for j in range(2):
            step = np.zeros(2)
            step[j] = 1e-7
            jacobian[:, j] = (residual(angles + step) - residual(angles - step)) / 2e-7
        delta, *_ = np.linalg.lstsq(jacobian, -r, rcond=None)
        angles = angles + delta
        if np.all(np.abs(delta) < 1e-15):
            break
    theta, phi = angles
    return unit_at(theta, phi)
