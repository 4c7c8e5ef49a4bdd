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
* **Point:** the foot of the axis (its point nearest the origin), each coordinate the simplest
  rational (fewest continued-fraction steps) within ``ε·L``, the same way.
* **Coefficients:** each the simplest rational within three standard errors of the weighted
  least-squares fit; or, when ``f`` was normalised by an irrational factor, the ratios to the
  best-determined coefficient and then the overall factor. The candidate with the fewest bits
  whose *exact* residual passes wins.

The exact surface ``g = Σ q_ij h^i ρ^j`` is then built over ``QQ`` (or ``QQ(√d)``) and checked
by the exact recognizer (docs/math.md §2) before it is returned; a surface within the rounding
is preferred, then the simplest.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass
from fractions import Fraction
from functools import lru_cache
from typing import TypeAlias, TypeVar

import numpy as np
import sympy
from flint import fmpq, fmpq_mpoly, fmpq_mpoly_ctx
from sympy.polys.domains import QQ

from ..algebra.polys import XYZ, Poly, from_flint, poly_ring, to_flint
from ..recognition.symmetry import (
    CYLINDER,
    PLANE,
    REVOLUTION,
    Symmetry,
    rational_symmetry,
    recognize_symmetry,
)
from . import dense
from .dense import FloatArray
from .near_symmetry import Fit, Normalised, fit, invariant_basis, refine_fixed
from .precision import Rounding

Vector: TypeAlias = tuple[Fraction, Fraction, Fraction]
EPSILONS = tuple(10.0**-k for k in range(2, 14))
MAX_DENOMINATOR = 10**6
AXIS_TRIES = 3
MAX_CHECKS = 16
SPREADS = (3.0, 1.0, 0.3)
"""Radii, in standard errors, within which a refined axis is snapped (widest first)."""
FLAT_SLOPE = 1e-8
"""A change of the profile's terms of degree ``d - 1`` under a unit shift along the axis below
this (relative to the terms) is the floating-point fit's noise, not a slope: a paraboloid's
term in ``h`` does not change at all, and dividing by that noise put its centre at 10¹⁰."""


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


@dataclass(frozen=True)
class _Typed:
    """The typed polynomial over ``QQ`` in the forms the candidates are compared with: flint's,
    and its terms as floats (computed once per snap, not once per candidate)."""

    flint: fmpq_mpoly
    floats: dict[dense.Monomial, float]


Built: TypeAlias = fmpq_mpoly | Poly
"""An exact surface as :func:`build` makes it: over ``QQ`` a flint polynomial (made a sympy
``Poly`` only once it passes, :func:`_check`), over ``QQ(√d)`` a sympy ``Poly``."""

T = TypeVar("T")


def three(values: Iterable[T]) -> tuple[T, T, T]:
    """The three coordinates of a point or vector as a triple."""
    first, second, third = values
    return first, second, third


def simplest_between(lo: Fraction, hi: Fraction) -> Fraction:
    """The rational with the smallest denominator (then numerator) in ``[lo, hi]``: the
    continued fraction shared by the two ends, with the next term the smallest that fits (the
    classic recursion ``⌊lo⌋ + 1/simplest(1/(hi − ⌊lo⌋), 1/(lo − ⌊lo⌋))``, on integers)."""
    if lo > hi:
        lo, hi = hi, lo
    if lo <= 0 <= hi:
        return Fraction(0)
    if hi < 0:
        return -simplest_between(-hi, -lo)
    a, b, c, d = lo.numerator, lo.denominator, hi.numerator, hi.denominator  # 0 < a/b ≤ c/d
    terms: list[int] = []
    while True:
        whole = a // b
        if a == whole * b:
            terms.append(whole)
            break
        if (whole + 1) * d <= c:
            terms.append(whole + 1)
            break
        terms.append(whole)
        a, b, c, d = d, c - whole * d, b, a - whole * b  # [1/(hi − whole), 1/(lo − whole)]
    numerator, denominator = terms[-1], 1
    for term in reversed(terms[:-1]):
        numerator, denominator = term * numerator + denominator, numerator
    return Fraction(numerator, denominator)


def simplest_near(value: float, radius: float) -> Fraction:
    """The simplest rational within ``radius`` of ``value``."""
    v = Fraction(value)
    r = Fraction(abs(radius))
    return simplest_between(v - r, v + r)


def integer_directions(direction: FloatArray, epsilons: Sequence[float]) -> list[tuple[int, int, int] | None]:
    """For each ``ε``, the primitive integer vector with the smallest common denominator ``D``
    whose ratios are within ``ε`` of the direction's (``None`` if none has ``D`` up to
    ``MAX_DENOMINATOR``): one vectorised pass over all ``D``, kept for the next ``ε`` asked of
    the same direction (the refinement asks at several spreads)."""
    j = int(np.argmax(np.abs(direction)))
    ratios = direction / direction[j]
    best = _running_error(tuple(float(r) for r in ratios), j)
    found: list[tuple[int, int, int] | None] = []
    for eps in epsilons:
        first = int(np.searchsorted(best, -eps, side="left"))
        if first == len(best):
            found.append(None)
            continue
        ints = [int(round((first + 1) * r)) for r in ratios]
        g = math.gcd(*ints)
        found.append(three(v // g for v in ints))
    return found


@lru_cache(maxsize=2)
def _running_error(ratios: tuple[float, ...], j: int) -> FloatArray:
    """``−min_{D' ≤ D} max_i |D'·rᵢ − round(D'·rᵢ)|/D'`` for ``D = 1 … MAX_DENOMINATOR``: non-decreasing,
    so the first ``D`` within ``ε`` is found by bisection."""
    D = np.arange(1, MAX_DENOMINATOR + 1, dtype=float)
    error = np.zeros_like(D)
    scaled = np.empty_like(D)
    for i, r in enumerate(ratios):
        if i != j:  # the largest ratio is 1: no error at any D
            np.multiply(D, r, out=scaled)
            np.subtract(scaled, np.round(scaled), out=scaled)
            np.maximum(error, np.abs(scaled, out=scaled), out=error)
    error /= D
    best = -np.minimum.accumulate(error)
    best.flags.writeable = False
    return best


def rational_unit_direction(direction: FloatArray, epsilon: float | FloatArray) -> tuple[Fraction, Fraction, Fraction]:
    """A rational unit vector near ``direction``: the inverse stereographic image of the
    simplest rationals ``(u, v)`` within ``epsilon`` (a number, or one radius per coordinate of
    the direction) of the direction's projection from the pole opposite its largest component.
    Its ``h = n·(p - c)`` keeps the profile orthonormal."""
    n = direction / np.linalg.norm(direction)
    k = int(np.argmax(np.abs(n)))
    sign = 1.0 if n[k] > 0 else -1.0
    others = [i for i in range(3) if i != k]
    radii = np.broadcast_to(np.asarray(epsilon, float), (3,))
    u, v = (simplest_near(n[i] / (1.0 + sign * n[k]), radii[i] / (1.0 + sign * n[k])) for i in others)
    denominator = 1 + u * u + v * v
    result = [Fraction(0)] * 3
    result[others[0]], result[others[1]] = 2 * u / denominator, 2 * v / denominator
    result[k] = (1 - u * u - v * v) / denominator * int(sign)
    return three(result)


@dataclass(frozen=True)
class Quadratic:
    """``a + b·√d``: an exact coordinate in the real quadratic field ``QQ(√d)`` (``d`` a
    square-free integer > 1)."""

    a: Fraction
    b: Fraction
    d: int

    def __float__(self) -> float:
        return float(self.a) + float(self.b) * math.sqrt(self.d)


QuadraticVector: TypeAlias = tuple[Quadratic, Quadratic, Quadratic]
Direction: TypeAlias = Vector | QuadraticVector
"""A snapped direction: rational, or in a real quadratic field."""

MAX_SQUARE_FREE = 10**4
"""The squared coordinates of a quadratic direction have numerator times denominator at most
this squared (CAD turns give 1/8, 3/4, …), which also bounds the trial division."""


def quadratic_direction(direction: FloatArray, epsilon: float) -> QuadraticVector | None:
    """A direction in one real quadratic field ``QQ(√d)`` near ``direction``: the squares of the
    unit vector's coordinates snapped to the simplest rationals within ``epsilon`` (they must
    add up to 1), their roots scaled by one common ``√k`` so that a single ``√d`` remains (a
    turn by 30° and 45° gives ``(−1, 1, −√6)``). ``None`` when there is none, or when the
    direction is rational (the other families have it)."""
    n = direction / np.linalg.norm(direction)
    squares = [simplest_near(v * v, max(epsilon, 1e-15)) for v in n]
    if sum(squares) != 1:
        return None
    parts: list[tuple[Fraction, int]] = []  # coordinate = coefficient·√free
    for q, v in zip(squares, n):
        if q == 0:
            parts.append((Fraction(0), 1))
            continue
        split = _square_free(q.numerator * q.denominator)
        if split is None:
            return None
        root, free = split
        parts.append((Fraction(root, q.denominator) * (1 if v > 0 else -1), free))
    for k in sorted({free for c, free in parts if c}):
        roots = [_square_free(free * k) for _, free in parts]
        splits = [split for split in roots if split is not None]
        if len(splits) < len(roots):
            continue
        scaled = [(c * root, rest) for (c, _), (root, rest) in zip(parts, splits)]
        fields = {rest for c, rest in scaled if c and rest != 1}
        if len(fields) == 1:
            (d,) = fields
            return three(
                Quadratic(c if rest == 1 else Fraction(0), c if rest == d else Fraction(0), d) for c, rest in scaled
            )
    return None


def _square_free(m: int) -> tuple[int, int] | None:
    """``(r, f)`` with ``m = r²·f`` and ``f`` square-free (trial division); ``None`` for ``m``
    above :data:`MAX_SQUARE_FREE` squared (no simple direction has it)."""
    if m <= 0 or m > MAX_SQUARE_FREE**2:
        return None
    r, f = 1, 1
    p, rest = 2, m
    while p * p <= rest:
        e = 0
        while rest % p == 0:
            rest //= p
            e += 1
        r *= p ** (e // 2)
        f *= p ** (e % 2)
        p += 1 if p == 2 else 2
    return r, f * rest


def _quadratic_family(direction: FloatArray, epsilon: float | FloatArray) -> QuadraticVector | None:
    """:func:`quadratic_direction` as a family of :func:`snap` (one radius: the largest)."""
    return quadratic_direction(direction, float(np.max(epsilon)))


def perpendicular(direction: Vector) -> Vector:
    """A vector ``u ⟂ a`` with ``|u| = |a|`` when ``|a|`` is rational: the Householder reflection
    that maps the coordinate vector ``e_k`` nearest ``a`` onto ``a/|a|`` maps another coordinate
    vector onto ``u/|u|``; otherwise a primitive ``e_j``-projection. The profile in the frame
    ``(a, u)`` then keeps the coefficients of the snapped profile."""
    a = [Fraction(v) for v in direction]
    norm2 = sum(v * v for v in a)
    k = max(range(3), key=lambda i: abs(a[i]))
    j = (k + 1) % 3
    root = Fraction(math.isqrt(norm2.numerator), math.isqrt(norm2.denominator))
    if root * root != norm2:
        e = [Fraction(0)] * 3
        e[min(range(3), key=lambda i: abs(a[i]))] = Fraction(1)
        return three(norm2 * e[i] - sum(x * y for x, y in zip(a, e)) * a[i] for i in range(3))
    n = [v / root for v in a]
    sign = 1 if n[k] >= 0 else -1
    v = [n[i] - (sign if i == k else 0) for i in range(3)]
    vv = sum(x * x for x in v)
    image = [Fraction(1 if i == j else 0) - (2 * v[i] * v[j] / vv if vv else 0) for i in range(3)]
    return three(root * x for x in image)


def _integer_vector(direction: FloatArray, epsilon: float | FloatArray) -> Vector | None:
    assert isinstance(epsilon, float)  # one radius for the integer family (_radius)
    (a,) = integer_directions(direction, [epsilon])
    return None if a is None else three(Fraction(v) for v in a)


DirectionSnap: TypeAlias = Callable[[FloatArray, float | FloatArray], Direction | None]
"""A family of exact directions: the one near a direction, within a radius (a number, or one
per coordinate)."""
FAMILIES: tuple[DirectionSnap, ...] = (_integer_vector, rational_unit_direction)
"""Primitive integer directions, and rational unit directions (which keep an irrational axis's
profile coefficients simple)."""


def snapped_directions(direction: FloatArray, family: DirectionSnap) -> list[Direction]:
    """The distinct exact directions of one family near ``direction``, simplest first."""
    snapped: list[Direction | None]
    if family is _integer_vector:
        snapped = [
            None if a is None else three(Fraction(v) for v in a) for a in integer_directions(direction, EPSILONS)
        ]
    else:
        snapped = [family(direction, eps) for eps in EPSILONS]
    found: list[Direction] = []
    for a in snapped:
        if a is not None and a not in found:
            found.append(a)
    return found


def exact_axes(
    f: Normalised, best: Fit, directions: list[Direction]
) -> Iterator[tuple[Direction | None, Vector | None]]:
    """Exact (direction, point) pairs to try, simplest first: the first ``AXIS_TRIES``
    directions whose float fit passes, each with the points near the profile's centre on that
    axis whose float fit passes, coarsest first (docs/math.md §8). A coarse pair can pass with
    free coefficients and fail once they are snapped, so finer pairs follow."""
    kind = best.candidate.kind
    limit = max(1.0 + best.noise, best.residual * 1.5)
    tried = 0
    for a in directions if kind in (REVOLUTION, CYLINDER, PLANE) else [None]:
        direction = None if a is None else np.array([float(v) for v in a])
        if kind == PLANE:
            if fit(f, best.candidate, direction=direction).residual <= limit:
                yield a, None
                tried += 1
        else:
            point = best.candidate.point
            assert point is not None  # every kind of surface of revolution but a plane has a point
            if direction is not None:
                point = profile_centre(f, best, direction)
                if fit(f, best.candidate, point=point, direction=direction).residual > limit:
                    continue
            tried += 1
            seen: list[Vector] = []
            passing = False
            for eps in EPSILONS:
                c = three(simplest_near(float(v) * f.length, eps * f.length) for v in point)
                if c in seen:
                    continue
                seen.append(c)
                float_c = np.array([float(v) for v in c]) / f.length
                passing = passing or fit(f, best.candidate, point=float_c, direction=direction).residual <= limit
                if passing:
                    yield a, c
        if tried >= AXIS_TRIES:
            return


def profile_centre(f: Normalised, best: Fit, direction: FloatArray) -> FloatArray:
    """The point of the axis about which the profile's terms of degree ``d - 1`` are smallest
    (the centre of a torus, the vertex region of a paraboloid): least squares in the shift
    ``t`` along the axis, whose effect on those terms is linear."""
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
    if float(np.linalg.norm(slope)) <= FLAT_SLOPE * max(float(np.linalg.norm(at_zero)), 1.0):
        return foot  # those terms do not move with the point (a paraboloid: only the constant does)
    t = -float(slope @ at_zero) / float(slope @ slope)
    return foot + t * unit


def _radius(sigma: FloatArray, spread: float, family: DirectionSnap) -> float | FloatArray:
    """Snapping radii from standard errors (one number for the integer family)."""
    radii = np.maximum(sigma * spread, 1e-15)
    return float(radii.max()) if family is _integer_vector else radii


def snap(f: Normalised, best: Fit, exact: Poly, rounding: Rounding) -> ExactSurface | None:
    """The simplest exact surface of the fit's kind within the rounding, or ``None``: for each
    family of directions the first surface that passes, then the one whose profile
    coefficients have the fewest bits."""
    typed = _Typed(to_flint(exact), dense.float_coefficients(exact)) if exact.ring.domain == QQ else None
    found: list[tuple[int, ExactSurface]] = []
    for family in FAMILIES if best.candidate.direction is not None else (None,):
        surface = _first_exact(f, best, family, typed, rounding)
        if surface is not None:
            found.append(surface)
    if best.candidate.kind in (REVOLUTION, CYLINDER):
        surface = _first_exact(f, best, _quadratic_family, typed, rounding)
        if surface is not None:
            found.append(surface)
    if not found:
        return None
    return min(found, key=lambda item: (item[1].largest > 1.0, item[0]))[1]


def _first_exact(
    f: Normalised, best: Fit, family: DirectionSnap | None, typed: _Typed | None, rounding: Rounding
) -> tuple[int, ExactSurface] | None:
    """The first exact surface, in the order of :func:`exact_axes`, with every coefficient
    within the rounding (else the first within twice it, in the mean), with the bits of its
    coefficients. When the simplest coefficients fail on a coarse axis, the axis is refined with
    them held fixed and snapped again, finely."""
    fallback: tuple[int, ExactSurface] | None = None
    for coefficients, surface in _exact_surfaces(f, best, family, typed, rounding):
        if surface.largest <= 1.0:
            return _bits(coefficients), surface
        if fallback is None:
            fallback = _bits(coefficients), surface
    return fallback


def _exact_surfaces(
    f: Normalised, best: Fit, family: DirectionSnap | None, typed: _Typed | None, rounding: Rounding
) -> Iterator[tuple[list[Fraction], ExactSurface]]:
    """Exact surfaces within twice the rounding (in the mean), simplest axes first; at most
    ``MAX_CHECKS`` exact surfaces are built, and the axis is refined with fixed coefficients
    on the first axis only (an input with irrational data has no simple exact surface, and
    that must be found out quickly)."""
    directions: list[Direction] = []
    if family is not None:
        assert best.candidate.direction is not None  # a family snaps the candidate's direction
        directions = snapped_directions(best.candidate.direction, family)
    kind = best.candidate.kind
    checks = 0
    for first, (a, c) in enumerate(exact_axes(f, best, directions)):
        direction = None if a is None else np.array([float(v) for v in a])
        point = None if c is None else np.array([float(v) for v in c]) / f.length
        local = fit(f, best.candidate, point=point, direction=direction)
        degrees = np.array([i + 2 * j for i, j in local.exponents])

        def matched_scales(
            ratios: list[Fraction], a: Direction | None = a, c: Vector | None = c, local: Fit = local
        ) -> list[Fraction]:
            g = build(kind, a, c, local.exponents, ratios)
            return [] if not isinstance(g, fmpq_mpoly) or typed is None else _matched_scales(g, typed, rounding)

        for rank, coefficients in enumerate(_coefficient_candidates(f, local, matched_scales)):
            checks += 1
            if checks > MAX_CHECKS:
                return
            g = build(kind, a, c, local.exponents, coefficients)
            surface = None if g is None else _check(g, typed, rounding, f, a, c)
            if surface is not None:
                yield coefficients, surface
                if surface.largest <= 1.0:
                    return
            if rank >= 2 or first > 0:
                continue
            fixed = np.array([float(q) for q in coefficients]) * f.length**degrees / f.scale
            moved, direction_sigma, point_sigma = refine_fixed(f, local.candidate, fixed)
            for spread in SPREADS:
                a2 = None
                if family is not None:
                    assert moved.direction is not None  # refined from a candidate with a direction
                    a2 = family(moved.direction, _radius(direction_sigma, spread, family))
                c2 = (
                    None
                    if moved.point is None
                    else three(
                        simplest_near(float(v) * f.length, float(max(e * spread, 1e-15)) * f.length)
                        for v, e in zip(moved.point, point_sigma)
                    )
                )
                if family is not None and a2 is None:
                    continue
                g = build(kind, a2, c2, local.exponents, coefficients)
                surface = None if g is None else _check(g, typed, rounding, f, a2, c2)
                if surface is not None:
                    yield coefficients, surface
                    if surface.largest <= 1.0:
                        return


def _coefficient_candidates(
    f: Normalised, local: Fit, matched_scales: Callable[[list[Fraction]], list[Fraction]]
) -> list[list[Fraction]]:
    """Exact coefficients of ``g`` in the original coordinates, simplest candidates first: each
    snapped on its own; the ratios to the best-determined one snapped, times the scales that
    ``matched_scales`` gives them (or that coefficient snapped, or as fitted); as fitted."""
    degrees = np.array([i + 2 * j for i, j in local.exponents])
    factor = f.scale / f.length**degrees
    values = local.coefficients * factor
    errors = _standard_errors(f, local) * factor * 3.0 * max(1.0, local.residual)
    found = [[simplest_near(v, e) for v, e in zip(values, errors)]]
    pivot = int(np.argmax(np.abs(values) / np.maximum(errors, 1e-300)))
    if values[pivot] != 0.0:
        ratios = values / values[pivot]
        ratio_errors = errors / abs(values[pivot]) + np.abs(ratios) * errors[pivot] / abs(values[pivot])
        snapped = [simplest_near(r, e) for r, e in zip(ratios, ratio_errors)]
        scale = simplest_near(values[pivot], errors[pivot])
        found.append([scale * r for r in snapped])
        for matched in matched_scales(snapped):
            found.append([matched * r for r in snapped])
        found.append([Fraction(values[pivot]) * r for r in snapped])
    found.append([Fraction(v).limit_denominator(10**15) for v in values])
    return sorted(found, key=_bits)


def _matched_scales(g: fmpq_mpoly, typed: _Typed, rounding: Rounding) -> list[Fraction]:
    """Scales ``λ`` that make ``λ·g`` agree with ``f`` where ``f`` is largest: at each of the
    three largest coefficients of ``f``, the simplest rational within its rounding divided by
    ``g``'s coefficient there (a CAD system that divides by its largest coefficient prints an
    exact ``1.000000000``)."""
    g_terms = dict(zip(map(dense.monomial, g.monoms()), g.coeffs()))
    f_terms = typed.floats
    shared = sorted((m for m in f_terms if m in g_terms), key=lambda m: -abs(f_terms[m]))
    scales: list[Fraction] = []
    for m in shared[:3]:
        value = simplest_near(f_terms[m], rounding.bound(m))
        scale = value / Fraction(int(g_terms[m].p), int(g_terms[m].q))
        if scale and scale not in scales:
            scales.append(scale)
    return scales


def _bits(values: list[Fraction]) -> int:
    return sum(v.numerator.bit_length() + v.denominator.bit_length() for v in values)


def _standard_errors(f: Normalised, local: Fit) -> FloatArray:
    """Standard errors of the fitted coefficients, in units of the rounding bounds."""
    weighted = invariant_basis(local.candidate, f.degree, f.selected)[0] * f.weights[:, None]
    norms = np.linalg.norm(weighted, axis=0)
    norms[norms == 0.0] = 1.0
    _, s, vt = np.linalg.svd(weighted / norms, full_matrices=False)
    s = np.maximum(s, s[0] * 1e-15)
    covariance = (vt.T / s**2) @ vt
    errors: FloatArray = np.sqrt(np.abs(np.diag(covariance))) / norms
    return errors


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
    root = sympy.sqrt(d)
    K = QQ.algebraic_field(root)
    terms: dict[tuple[int, int, int], sympy.Expr] = {}
    for monom, coeff in zip(g.monoms(), g.coeffs()):
        key = dense.monomial(monom[:3])
        value = sympy.Rational(int(coeff.p), int(coeff.q)) * (root if monom[3] else 1)
        terms[key] = terms.get(key, sympy.Integer(0)) + value
    R = poly_ring(XYZ, K)
    return R.from_dict({m: K.from_sympy(v) for m, v in terms.items() if v != 0})


def _reduce_root(p: fmpq_mpoly, d: int) -> fmpq_mpoly:
    """``p`` with ``w²`` replaced by ``d`` (degree at most 1 in ``w``, the last variable)."""
    terms: dict[tuple[int, ...], fmpq] = {}
    for monom, coeff in zip(p.monoms(), p.coeffs()):
        k = int(monom[3])
        key = (*(int(e) for e in monom[:3]), k % 2)
        terms[key] = terms.get(key, fmpq(0)) + coeff * fmpq(d) ** (k // 2)
    return p.context().from_dict({m: c for m, c in terms.items() if c})


def _check(
    g: Built, typed: _Typed | None, rounding: Rounding, f: Normalised, a: Direction | None, c: Vector | None
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
