"""The nearest exact cone of revolution of a rounded quadric (docs/math.md §8.5, "Cones").

A cone is fixed by its apex ``A``, its axis direction ``a`` and ``K = tan²θ``:

    g = |a|²·|p − A|² − (1 + K)·(a·(p − A))²,

rational when ``A``, ``a`` and ``K`` are. The profile's snapping (:mod:`.snapping`) fits the
coefficients of ``g`` on one exact axis, and a CAD cone on a turned axis comes out as a
hyperboloid there: its axis direction is irrational, a rational one near it leaves the terms of
degree 0 and 1 (``−2QA`` and ``AᵀQA``, large where ``A`` is far from the origin) far outside
their rounding unless the profile keeps them free, and free they are a hyperboloid's. Here the
structure is held and the axis is found from every coefficient:

1. the apex is the profile's centre (where the term in ``h`` vanishes), snapped coordinate by
   coordinate to the shortest decimals, then to the simplest rationals, coarsest first;
2. with the apex held, ``f ≈ (p − A)ᵀ Q (p − A)`` is linear in the six entries of ``Q``: a
   weighted least-squares fit (weights: the rounding of each coefficient) over all ten
   coefficients, whose terms of degree 0 and 1 fix ``Q`` along ``A`` to their rounding;
3. ``Q = λ(I − (1 + K)ââᵀ)``: ``â`` is the eigenvector of the eigenvalue ``−λK``, and ``K``
   is snapped (coarsest first); with ``A`` and ``K`` held, ``(λ, â)`` are fitted again (Gauss
   and Newton's steps), and ``â`` is snapped in each family of directions;
4. ``g`` is scaled by the simplest factor that puts every coefficient within the rounding
   (:func:`.coefficients.within_scale`), and checked exactly (:func:`.snapping.check_surface`).

The simplest cone that passes, by the bits of its coefficients and axis, is the answer.
"""

from __future__ import annotations

from collections.abc import Callable
from fractions import Fraction
from typing import TYPE_CHECKING, NamedTuple, Protocol, TypeAlias, TypeVar

import numpy as np
from flint import fmpq_mpoly

from .coefficients import Typed, bits, scaled_surface, shape_bits, within_scale
from .dense import FloatArray, Monomial
from .directions import (
    FAMILIES,
    Direction,
    DirectionSnap,
    angles_of,
    decimal_near,
    direction_parts,
    quadratic_family,
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


class Checked(Protocol):
    """An exact surface checked against the typed one (:class:`.snapping.ExactSurface`)."""

    @property
    def largest(self) -> float: ...


S = TypeVar("S", bound=Checked)
Build = Callable[["Direction | None", "Vector", list[Fraction]], "fmpq_mpoly | Poly | None"]
"""``g`` of the quadric of revolution with ``q_ij`` on :data:`EXPONENTS` about the axis through
a point along a direction (:func:`.snapping.build`): over ``QQ``, or ``QQ(√d)`` for a direction
in that field."""
Check: TypeAlias = "Callable[[fmpq_mpoly | Poly, Direction, Vector], S | None]"
"""An exact surface checked against the typed one, along its direction through its point
(:func:`.snapping.check_surface`)."""

EXPONENTS = ((0, 0), (1, 0), (2, 0), (0, 1))
"""The terms ``h^i ρ^j`` of a quadric of revolution (:func:`.snapping.build`); a cone about its
apex has only the last two."""
APEX_RADII = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11)
"""Radii, relative to the apex's distance from the origin (at least the size of the surface's
normalised coordinates), within which its coordinates are snapped, coarsest first: down to
10⁻¹¹ for a point of 16 digits printed with 10 (a torus's centre moved by an assembly's
transform was snapped no finer than 10⁻⁷, and no torus held the rounding about it)."""
SLOPE_RADII = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11)
"""The same for ``K = tan²θ``, relative to ``K``."""
DIRECTION_RADII = (1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12)
"""The same for the unit axis direction."""
MAX_RESIDUAL = 2.0
"""The weighted residual (in units of the rounding, root mean square) of the fit of ``Q`` with
the apex held above which that apex is not the cone's."""
MAX_CHECKS = 400
"""Exact surfaces built and checked at most, over all apexes, slopes and directions."""
_QUADRATIC: tuple[Monomial, ...] = ((2, 0, 0), (0, 2, 0), (0, 0, 2), (1, 1, 0), (1, 0, 1), (0, 1, 1))
_LINEAR: tuple[Monomial, ...] = ((1, 0, 0), (0, 1, 0), (0, 0, 1))
_PAIRS = ((0, 1), (0, 2), (1, 2))


def nearest_cone(
    f: Normalised,
    typed: Typed,
    rounding: Rounding,
    centre: FloatArray,
    build: Build,
    check: Check[S],
) -> tuple[list[Fraction], S] | None:
    """The simplest cone of revolution with every coefficient within the rounding of the
    quadric ``f`` (its ``q_ij`` on :data:`EXPONENTS`, and the surface), or ``None``. ``centre``
    is the profile's centre in ``f``'s coordinates: the apex, for a cone. ``build`` makes ``g``
    and ``check`` checks it against the typed surface (:func:`.snapping.check_surface`)."""
    if f.degree != 2 or not np.all(np.isfinite(centre)):
        return None
    monomials = [m for m in typed.floats if sum(m) <= 2]
    weights = np.array([1.0 / rounding.bound(m) for m in monomials])
    target = np.array([typed.floats[m] for m in monomials]) * weights
    scale = max(float(np.linalg.norm(centre)), f.length)

    def tries(design: FloatArray, q: FloatArray) -> Tries | None:
        axis = _axis(_matrix(q))
        if axis is None:
            return None
        lam, slope, unit = axis
        slopes = dict.fromkeys(simplest_near(slope, radius * slope) for radius in SLOPE_RADII)
        shapes = [Shape(K, _cone_coefficients(K), _cone_model(float(K))) for K in slopes if K > 0]
        return shapes, least_squares(design, target, lam, unit)

    def design_at(A: FloatArray) -> FloatArray:
        design: FloatArray = form_design(monomials, A) * weights[:, None]
        return design

    return nearest_about(snapped_points(centre, scale), design_at, target, tries, typed, rounding, build, check)


def nearest_about(
    points: list[tuple[Fraction, Fraction, Fraction]],
    design_at: Callable[[FloatArray], FloatArray],
    target: FloatArray,
    tries: Callable[[FloatArray, FloatArray], Tries | None],
    typed: Typed,
    rounding: Rounding,
    build: Build,
    check: Check[S],
) -> tuple[list[Fraction], S] | None:
    """The simplest surface that passes about the first of ``points`` (a cone's apex, a torus's
    centre; coarsest first) about which one passes. At each, the weighted least-squares fit of
    ``design_at(point)`` to ``target`` (refuted by a residual above :data:`MAX_RESIDUAL`) gives,
    through ``tries``, the shapes to snap and the axis refit (:func:`first_shapes`); at most
    :data:`MAX_CHECKS` exact surfaces are checked in all."""
    found: list[tuple[int, list[Fraction], S]] = []
    checks = 0
    for point in dict.fromkeys(points):
        design = design_at(np.array([float(v) for v in point]))
        solution, *_ = np.linalg.lstsq(design, target, rcond=None)
        if np.sqrt(np.mean((design @ solution - target) ** 2)) > MAX_RESIDUAL:
            continue
        shapes = tries(design, np.asarray(solution, dtype=np.float64))
        if shapes is None:
            continue
        passed, used = first_shapes(*shapes, point, typed, rounding, build, check, MAX_CHECKS - checks)
        found += passed
        checks += used
        if found or checks >= MAX_CHECKS:
            break
    return simplest(found)


Model = Callable[[float, FloatArray], FloatArray]
"""The unknowns of a fit's design for ``(λ, â)``, the shape held (:func:`refit_direction`)."""


Tries: TypeAlias = "tuple[list[Shape], Callable[[Model], FloatArray]]"
"""The shapes to try about a point, and the axis refit for each one's model."""


class Shape(NamedTuple):
    """A shape tried about a snapped point: its snapped parameters (a cone's ``K``, a torus's
    radii), its ``q_ij`` for a direction of ``|a|²``, and its model of the fit."""

    key: object
    coefficients_of: Callable[[Fraction], list[Fraction]]
    model: Model


def least_squares(
    design: FloatArray, target: FloatArray, lam: float, unit: FloatArray
) -> Callable[[Model], FloatArray]:
    """The axis refitted for a shape's model by least squares (:func:`refit_direction`)."""
    return lambda model: refit_direction(design, target, model, lam, unit)


def first_shapes(
    shapes: list[Shape],
    refit: Callable[[Model], FloatArray],
    point: tuple[Fraction, Fraction, Fraction],
    typed: Typed,
    rounding: Rounding,
    build: Build,
    check: Check[S],
    budget: int,
) -> tuple[list[tuple[int, list[Fraction], S]], int]:
    """For each family of directions (a quadratic field's first, a CAD part turned by 30°, which
    has none near a rational direction and costs nothing there; then the rational ones), the
    first of ``shapes`` (coarsest first) that passes about ``point`` along the direction
    ``refit`` fits for it (:func:`first_direction`), and the exact surfaces checked (at most
    about ``budget``: a rational family counts every radius, the quadratic one the directions
    it had)."""
    refits: dict[object, FloatArray] = {}
    found = []
    checks = 0
    for family in (quadratic_family, *FAMILIES):
        for shape in shapes:
            if shape.key not in refits:
                refits[shape.key] = refit(shape.model)
            passed, tried = first_direction(
                family, refits[shape.key], shape.coefficients_of, point, typed, rounding, build, check
            )
            checks += tried if family is quadratic_family else len(DIRECTION_RADII) if passed is None else 1
            if passed is not None:
                found.append(passed)
                break  # the coarsest shape of this family that passes
            if checks >= budget:
                return found, checks
    return found, checks


def first_direction(
    family: DirectionSnap,
    unit: FloatArray,
    coefficients_of: Callable[[Fraction], list[Fraction]],
    point: tuple[Fraction, Fraction, Fraction],
    typed: Typed,
    rounding: Rounding,
    build: Build,
    check: Check[S],
) -> tuple[tuple[int, list[Fraction], S] | None, int]:
    """The surface about the axis through ``point`` along the coarsest direction ``a`` of
    ``family`` near ``unit`` (within :data:`DIRECTION_RADII`) with every coefficient within the
    rounding, once scaled; ``coefficients_of(|a|²)`` are its ``q_ij``. Its bits (coefficients,
    point and axis), coefficients and surface, and how many directions were tried."""
    tried = 0
    for radius in DIRECTION_RADII:
        a = family(unit, radius)
        norm2 = None if a is None else squared_length(a)
        if a is None or norm2 is None:
            continue
        tried += 1
        coefficients = coefficients_of(norm2)
        g = build(a, point, coefficients)
        if g is None:
            continue
        factor = within_scale(g, typed, rounding)
        if factor is None:
            continue
        surface = check(scaled_surface(g, factor), a, point)
        if surface is not None and surface.largest <= 1.0:
            scaled = [factor * c for c in coefficients]
            return (shape_bits(scaled) + bits([*point, *direction_parts(a)]), scaled, surface), tried
    return None, tried


def _cone_coefficients(K: Fraction) -> Callable[[Fraction], list[Fraction]]:
    """A cone's ``q_ij`` about its apex on :data:`EXPONENTS`, for a direction of ``|a|²``."""
    return lambda norm2: [Fraction(0), Fraction(0), -(1 + K), norm2]


def snapped_points(centre: FloatArray, scale: float) -> list[tuple[Fraction, Fraction, Fraction]]:
    """A point's coordinates (a cone's apex, a torus's centre) snapped within each of
    :data:`APEX_RADII` (times ``scale``): to the nearest decimals of fewest places first (a CAD
    part's ``−0.00725`` m, not the simpler ``−1/138``), then to the simplest rationals."""
    found = []
    for radius in APEX_RADII:
        r = radius * scale
        found.append(three(decimal_near(float(v), r) for v in centre))
        found.append(three(simplest_near(float(v), r) for v in centre))
    return found


def simplest(found: list[tuple[int, list[Fraction], S]]) -> tuple[list[Fraction], S] | None:
    """The coefficients and surface of the fewest bits of ``found``, if any."""
    if not found:
        return None
    _, coefficients, surface = min(found, key=lambda item: item[0])
    return coefficients, surface


def form_design(monomials: list[Monomial], A: FloatArray) -> FloatArray:
    """The coefficients of ``(p − A)ᵀ Q (p − A)`` at ``monomials`` (of degree at most 2; 0 at
    the others) as linear forms in the entries ``(Q₀₀, Q₁₁, Q₂₂, Q₀₁, Q₀₂, Q₁₂)``."""
    rows = []
    for m in monomials:
        row = np.zeros(6)
        if m in _QUADRATIC:
            index = _QUADRATIC.index(m)
            row[index] = 1.0 if index < 3 else 2.0
        elif m in _LINEAR:
            i = _LINEAR.index(m)
            row[i] = -2.0 * A[i]
            for index, (r, s) in enumerate(_PAIRS, start=3):
                if i in (r, s):
                    row[index] = -2.0 * A[s if i == r else r]
        elif not any(m):  # the constant AᵀQA
            row[:3] = A**2
            row[3:] = [2.0 * A[r] * A[s] for r, s in _PAIRS]
        rows.append(row)
    return np.array(rows)


def _matrix(q: FloatArray) -> FloatArray:
    return np.array([[q[0], q[3], q[4]], [q[3], q[1], q[5]], [q[4], q[5], q[2]]])


def _axis(Q: FloatArray) -> tuple[float, float, FloatArray] | None:
    """``(λ, K, â)`` of ``Q ≈ λ(I − (1 + K)ââᵀ)``: the two nearest eigenvalues are ``λ``, the
    third ``−λK`` with the eigenvector ``â``; ``None`` unless ``K > 0`` (a real cone)."""
    values, vectors = np.linalg.eigh(Q)
    gaps = [abs(values[1] - values[2]), abs(values[0] - values[2]), abs(values[0] - values[1])]
    odd = int(np.argmin(gaps))  # the eigenvalue not in the nearest pair
    lam = float(np.mean([values[i] for i in range(3) if i != odd]))
    if lam == 0.0:
        return None
    slope = -float(values[odd]) / lam
    return (lam, slope, vectors[:, odd]) if slope > 0 else None


def _cone_model(K: float) -> Model:
    """The entries of ``Q = λ(I − (1 + K)ââᵀ)`` for ``(λ, â)``, ``K`` held."""

    def entries(scale: float, n: FloatArray) -> FloatArray:
        return form_entries(scale * (np.eye(3) - (1 + K) * np.outer(n, n)))

    return entries


def form_entries(Q: FloatArray) -> FloatArray:
    """``(Q₀₀, Q₁₁, Q₂₂, Q₀₁, Q₀₂, Q₁₂)``, the unknowns of :func:`form_design`."""
    return np.array([Q[0, 0], Q[1, 1], Q[2, 2], Q[0, 1], Q[0, 2], Q[1, 2]])


def refit_direction(
    design: FloatArray,
    target: FloatArray,
    model: Model,
    lam: float,
    unit: FloatArray,
) -> FloatArray:
    """``â`` of the least-squares fit of ``design @ model(λ, â) ≈ target`` (Gauss and Newton's
    steps in ``λ`` and the two angles of ``â``, from ``unit``): the axis refitted with the
    surface's shape held (a cone's ``K``, a torus's radii)."""

    def entries(params: FloatArray) -> FloatArray:
        scale, theta, phi = params
        return model(scale, unit_at(theta, phi))

    unit = unit / np.linalg.norm(unit)
    params = np.array([lam, *angles_of(unit)])
    for _ in range(8):
        residual = design @ entries(params) - target
        jacobian = np.empty((len(target), 3))
        for j in range(3):
            step = np.zeros(3)
            step[j] = 1e-7 * max(1.0, abs(params[j]))
            jacobian[:, j] = (design @ entries(params + step) - design @ entries(params - step)) / (2 * step[j])
        delta, *_ = np.linalg.lstsq(jacobian, -residual, rcond=None)
        params = params + delta
        if np.all(np.abs(delta[1:]) < 1e-15):
            break
    _, theta, phi = params
    return unit_at(theta, phi)
