"""Builders shared by the engine tests: surfaces of revolution placed on known axes."""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction

from sympy.polys.domains import QQ
from sympy.polys.domains.domain import Domain

from sorgui.engine.algebra.linalg import Vector, cross, dot, is_zero
from sorgui.engine.algebra.polys import XYZ, Poly, compose, poly_ring


def rational_vector(values: Sequence[object], K: Domain = QQ) -> Vector:
    """Integers, fractions, strings like ``"3/5"`` or ``QQ`` elements as a vector over ``K``."""
    out = []
    for v in values:
        if isinstance(v, (int, str, Fraction)):
            q = Fraction(v)
            v = QQ(q.numerator, q.denominator)
        out.append(K.convert(v))
    return tuple(out)


def revolve(
    profile: dict[tuple[int, int], int], point: Vector, direction: Vector, K: Domain = QQ, axis_distance: bool = False
) -> Poly:
    """``f = F(a·(p - c), |p - c|²)`` for ``F(s, w) = Σ F_ij s^i w^j``: a SOR about the axis (c, a).

    With ``axis_distance`` the second variable is the squared distance to the axis,
    ``|p - c|² - (a·(p - c))²/|a|²``, so ``F(s, w) = w - g(s)`` is the tube ``y² + z² = g(x)``.
    """
    R = poly_ring(XYZ, K)
    x, y, z = R.gens
    d = [x - point[0], y - point[1], z - point[2]]
    h = sum((direction[i] * d[i] for i in range(3)), start=R.zero)
    rho = sum((d[i] ** 2 for i in range(3)), start=R.zero)
    if axis_distance:
        rho = rho - h**2 * K.quo(K.one, dot(direction, direction))
    F = poly_ring(("s", "w"), K).from_dict({m: K.convert(c) for m, c in profile.items()})
    return compose(F, [h, rho])


def quaternion_rotation(q: Sequence[int]) -> list[list[Fraction]]:
    """The rational rotation matrix of the (non-normalised) integer quaternion ``q``."""
    a, b, c, d = q
    n = a * a + b * b + c * c + d * d
    m = [
        [a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)],
        [2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b)],
        [2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d],
    ]
    return [[Fraction(v, n) for v in row] for row in m]


def move(f: Poly, rotation: list[list[Fraction]], shift: Vector) -> Poly:
    """``g(p) = f(Rᵀ(p - t))``: the surface moved by the rigid motion ``p ↦ R p + t``."""
    R = f.ring
    K = R.domain
    gens = R.gens
    d = [gens[i] - shift[i] for i in range(3)]
    images = [
        sum(
            (K.convert(QQ(rotation[j][i].numerator, rotation[j][i].denominator)) * d[j] for j in range(3)), start=R.zero
        )
        for i in range(3)
    ]
    return compose(f, images)


def apply(rotation: list[list[Fraction]], v: Vector, K: Domain = QQ) -> Vector:
    """``R v``."""
    return tuple(
        sum(
            (K.convert(QQ(rotation[i][j].numerator, rotation[i][j].denominator)) * v[j] for j in range(3)), start=K.zero
        )
        for i in range(3)
    )


def same_line(point: Vector, direction: Vector, other_point: Vector, other_direction: Vector) -> bool:
    """Whether two (point, direction) pairs describe the same line."""
    diff = tuple(p - q for p, q in zip(point, other_point))
    return is_zero(cross(direction, other_direction)) and is_zero(cross(diff, direction))


__all__ = ["apply", "dot", "move", "quaternion_rotation", "rational_vector", "revolve", "same_line"]
