"""Exact directions near a floating-point one, and the simplest rationals they are made of
(docs/math.md §8.5, "The nearest exact surface"): the three families of directions an axis
is snapped to.

* **Primitive integer vectors**, with the smallest common denominator ``D`` that approximates
  the direction's ratios within ``ε`` (simultaneous approximation, searched over ``D``).
* **Rational unit vectors**, the inverse stereographic images of the simplest rationals near
  the direction's projection: they keep an irrational axis's profile coefficients simple.
* **Directions in a real quadratic field** ``QQ(√d)``: the axes of CAD parts turned by 30° or
  45°.

A rational is *simplest* in an interval when it has the fewest continued-fraction steps (the
smallest denominator, then numerator).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from functools import lru_cache
from typing import TypeAlias, TypeVar

import mpmath
import numpy as np

from .dense import FloatArray

Vector: TypeAlias = tuple[Fraction, Fraction, Fraction]
EPSILONS = tuple(10.0**-k for k in range(2, 14))
"""The radii within which a direction is snapped, coarsest first: finer than ``10⁻¹³`` an
irrational axis (along ``(1, √2, √3)``) is matched by integers of 15 digits and more, no
designer's direction; such an input gets no exact surface, and the note names a tolerance."""
POINT_EPSILONS = tuple(10.0**-k for k in range(2, 17))
"""The radii within which an axis point is snapped (relative to the part's size), coarsest
first: on to ``10⁻¹⁶``, since a part about a point of 16 digits printed with 17 (a double) has
floating point's rounding, which a point within ``10⁻¹³`` misses."""
MAX_DENOMINATOR = 10**6
POINT_PRECISION = 100.0
"""How many times the input's relative rounding a rational point on a quadratic axis may be off
(:func:`.directions.rational_point`)."""

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


def decimal_near(value: float, radius: float) -> Fraction:
    """The decimal of fewest places nearest ``value`` within ``radius``."""
    places = max(0, -math.floor(math.log10(radius))) if radius > 0 else 17
    for p in range(-6, places + 2):
        candidate = Fraction(round(Fraction(value) * Fraction(10) ** p)) / Fraction(10) ** p
        if abs(candidate - Fraction(value)) <= radius:
            return candidate
    return Fraction(value)


def decimal_places(v: Fraction) -> int | None:
    """The fewest ``k`` with ``v = d/10ᵏ`` for an integer ``d``, or ``None`` when ``v`` is no decimal."""
    denominator = v.denominator
    twos = (denominator & -denominator).bit_length() - 1
    rest, fives = denominator >> twos, 0
    while rest % 5 == 0:
        rest, fives = rest // 5, fives + 1
    return max(twos, fives) if rest == 1 else None


def rational_sqrt(squared: Fraction) -> Fraction | None:
    """``√squared`` when it is rational (``squared ≥ 0``), else ``None``."""
    root = Fraction(math.isqrt(squared.numerator), math.isqrt(squared.denominator))
    return root if root * root == squared else None


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


def rational_point(point: FloatArray, direction: QuadraticVector, tolerance: float) -> FloatArray | None:
    """The rational point of the axis through ``point`` along ``direction ∈ QQ(√d)³``, or ``None``.

    Such an axis has at most one rational point ``c`` (``c + t·a`` is irrational for ``t ≠ 0``),
    and its foot, the point nearest the origin, is irrational when ``c·a`` is: a CAD part turned
    by 30° and moved off the origin. Each coordinate of ``a`` is rational or a rational times
    ``√d`` (:func:`quadratic_direction`); for a rational ``a_j`` and an irrational ``a_i = b·√d``
    the value ``K = p_i − √d·(b/a_j)·p_j`` is the same at every point ``p`` of the axis, and at
    ``c`` it reads ``K = c_i − √d·(b/a_j)·c_j``: its rational and irrational parts give ``c_i``
    and ``c_j``, found as the integer relation ``n₀K + n₁ + n₂√d = 0`` (PSLQ) within
    ``tolerance`` (relative to ``|K|``). Three numbers known to ``tolerance`` have chance
    relations of height about ``tolerance^(−1/2)``: only one below ``tolerance^(−1/3)`` is
    taken (a CAD part's placement, ``(3/10, −6/5, 7/10)``, has a small one)."""
    irrational = [i for i, q in enumerate(direction) if q.b]
    rational = [j for j, q in enumerate(direction) if q.a]
    if not irrational or not rational:
        return None
    i, j, d = irrational[0], rational[0], direction[irrational[0]].d
    ratio = direction[i].b / direction[j].a
    a = np.array([float(q) for q in direction])
    unit = a / np.linalg.norm(a)
    scale = max(1.0, float(np.max(np.abs(point))))
    point = point - float(point @ unit) * unit  # K is the same along the axis: read it at the foot
    k = float(point[i]) - math.sqrt(d) * float(ratio) * float(point[j])
    tol = max(tolerance, 1e-15)
    if abs(k) <= tol * scale:  # c_i = c_j = 0 (an axis through the origin, say)
        return point - float(point[j]) / float(direction[j].a) * a
    height = max(10, round(tol ** (-1 / 3)))
    with mpmath.workdps(30):
        relation = mpmath.pslq(
            [mpmath.mpf(k), 1, mpmath.sqrt(d)], tol=mpmath.mpf(tol * max(abs(k), 1.0)), maxcoeff=height, maxsteps=2000
        )
    if relation is None or relation[0] == 0 or max(abs(int(n)) for n in relation) > height:
        return None
    n0, _, n2 = (int(n) for n in relation)
    c_j = Fraction(n2, n0) / ratio  # K's part −√d·(b/a_j)·c_j is −(n₂/n₀)·√d
    t = (float(c_j) - float(point[j])) / float(direction[j].a)
    result: FloatArray = point + t * a
    return result


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


def squared_length(a: Direction) -> Fraction | None:
    """``|a|²`` when it is rational: always for a rational direction, and for a quadratic one
    whose coordinates are each rational or a rational multiple of ``√d``."""
    rational = [v for v in a if isinstance(v, Fraction)]
    if len(rational) == 3:
        return sum((v * v for v in rational), Fraction(0))
    quadratic = [v for v in a if isinstance(v, Quadratic)]
    if len(quadratic) < 3 or any(q.a and q.b for q in quadratic):
        return None
    return sum((q.a**2 + q.b**2 * q.d for q in quadratic), Fraction(0))


def direction_parts(a: Direction) -> list[Fraction]:
    """The rationals ``a`` is written with, whose bits it costs: its coordinates, or both parts
    of each coordinate ``a + b·√d`` of a direction in a quadratic field."""
    parts: list[Fraction] = []
    for v in a:
        parts += [v.a, v.b] if isinstance(v, Quadratic) else [Fraction(v)]
    return parts


def quadratic_family(direction: FloatArray, epsilon: float | FloatArray) -> QuadraticVector | None:
    """:func:`quadratic_direction` as a family of :func:`snap` (one radius: the largest)."""
    return quadratic_direction(direction, float(np.max(epsilon)))


def perpendicular(direction: Vector) -> Vector:
    """A vector ``u ⟂ a`` with ``|u| = |a|`` when ``|a|`` is rational: the Householder reflection
    that maps the coordinate vector ``e_k`` nearest ``a`` onto ``a/|a|`` maps another coordinate
    vector onto ``u/|u|``; otherwise a primitive ``e_j``-projection. The profile in the frame
    ``(a, u)`` then keeps the coefficients of the snapped profile."""
    a = [Fraction(v) for v in direction]
    norm2 = sum((v * v for v in a), Fraction(0))
    k = max(range(3), key=lambda i: abs(a[i]))
    j = (k + 1) % 3
    root = rational_sqrt(norm2)
    if root is None:
        e = [Fraction(0)] * 3
        e[min(range(3), key=lambda i: abs(a[i]))] = Fraction(1)
        return three(norm2 * e[i] - sum(x * y for x, y in zip(a, e)) * a[i] for i in range(3))
    n = [v / root for v in a]
    sign = 1 if n[k] >= 0 else -1
    v = [n[i] - (sign if i == k else 0) for i in range(3)]
    vv = sum(x * x for x in v)
    image = [Fraction(1 if i == j else 0) - (2 * v[i] * v[j] / vv if vv else 0) for i in range(3)]
    return three(root * x for x in image)


def integer_vector(direction: FloatArray, epsilon: float | FloatArray) -> Vector | None:
    assert isinstance(epsilon, float)  # one radius for the integer family (_radius)
    (a,) = integer_directions(direction, [epsilon])
    return None if a is None else three(Fraction(v) for v in a)


DirectionSnap: TypeAlias = Callable[[FloatArray, float | FloatArray], Direction | None]
"""A family of exact directions: the one near a direction, within a radius (a number, or one
per coordinate)."""
FAMILIES: tuple[DirectionSnap, ...] = (integer_vector, rational_unit_direction)
"""Primitive integer directions, and rational unit directions (which keep an irrational axis's
profile coefficients simple)."""


def snapped_directions(direction: FloatArray, family: DirectionSnap) -> list[Direction]:
    """The distinct exact directions of one family near ``direction``, simplest first."""
    snapped: list[Direction | None]
    if family is integer_vector:
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


def unit_at(theta: float, phi: float) -> FloatArray:
    """The unit vector of polar angle ``theta`` and azimuth ``phi``: the two parameters of a
    direction fitted by Gauss and Newton's steps (cones, cylinders, tori)."""
    return np.array([np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)])


def angles_of(unit: FloatArray) -> tuple[float, float]:
    """``(theta, phi)`` of the unit vector ``unit`` (:func:`unit_at`)."""
    return float(np.arccos(np.clip(unit[2], -1.0, 1.0))), float(np.arctan2(unit[1], unit[0]))
