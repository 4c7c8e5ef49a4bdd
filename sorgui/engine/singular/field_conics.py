"""Conics over a number field ``K``, parameterized without Singular (docs/math.md §10).

Singular's ``paraPlaneCurve`` accepts only rational coefficients, so a cone or a cylinder over
a conic with coefficients in ``QQ(√2)`` had no parameterization. A conic ``F = 0`` over ``K``
with a point ``P`` over ``K`` is parameterized by the lines through ``P``: on
``U = u₀ + s, V = v₀ + t·s``, ``F = s·(α(t)·s + β(t))`` (``P`` is on the curve), so the second
point is ``s = −β(t)/α(t)``, a proper parameterization over ``K``. The point is looked for on
the lines ``U = u₀`` for small rationals ``u₀``: there ``F`` is a quadratic in ``V`` over ``K``,
with a root in ``K`` exactly when its discriminant is a square in ``K`` (``X² − D`` has a
linear factor over ``K``).
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from sympy.polys.domains import QQ
from sympy.polys.domains.domain import Domain

from ..algebra.polys import Poly, compose, factor, poly_ring, total_degree

POINT_SEARCH = 12
"""Rationals ``u₀ = p/q`` with ``|p| ≤`` this and ``q ≤ 3`` are tried for a point over ``K``."""


def conic_over_field(F: Poly) -> tuple[tuple[Poly, Poly], tuple[Poly, Poly]] | None:
    """``((p₁, q₁), (p₂, q₂))`` in ``K[t]`` with ``F(p₁/q₁, p₂/q₂) = 0`` (not reduced), from a
    point over ``K`` and the lines through it; ``None`` unless ``F`` is a conic with such a point
    among the searched ones. The caller reduces and checks the result (substitution, properness)."""
    if F.ring.ngens != 2 or total_degree(F) != 2:
        return None
    for quadratic in (1, 0):
        if F.degree(quadratic) != 2:
            continue
        point = _point(F, quadratic)
        if point is not None:
            return _lines_through(F, point)
    return None


def _candidates() -> list[Fraction]:
    """Small rationals, in order of height: 0, ±1, ±2, …, ±1/2, …"""
    values = {Fraction(p, q) for q in (1, 2, 3) for p in range(-POINT_SEARCH * q, POINT_SEARCH * q + 1)}
    return sorted(values, key=lambda v: (v.denominator, abs(v.numerator), v < 0))


def _point(F: Poly, quadratic: int) -> tuple[Any, Any] | None:
    """A point ``(x, y)`` of ``F = 0`` over ``K`` with its other coordinate a small rational."""
    K = F.ring.domain
    other = 1 - quadratic
    for value in _candidates():
        u0 = K.convert(QQ(value.numerator, value.denominator))
        a, b, c = (sum((k * u0 ** m[other] for m, k in F.items() if m[quadratic] == e), K.zero) for e in (2, 1, 0))
        if not a:
            continue
        root = _square_root(b * b - 4 * a * c, K)
        if root is None:
            continue
        v0 = (root - b) / (2 * a)
        return (u0, v0) if quadratic == 1 else (v0, u0)
    return None


def _square_root(d: Any, K: Domain) -> Any | None:
    """A square root of ``d`` in ``K``, or ``None`` (``X² − d`` has no linear factor over ``K``)."""
    if not d:
        return d
    R = poly_ring(("X",), K)
    (X,) = R.gens
    for g, _e in factor(X**2 - R.ground_new(d))[1]:
        if g.degree() == 1:
            return -dict(g.items()).get((0,), K.zero) / g.LC
    return None


def _lines_through(F: Poly, point: tuple[Any, Any]) -> tuple[tuple[Poly, Poly], tuple[Poly, Poly]] | None:
    """The second intersection of ``F = 0`` with the line of slope ``t`` through ``point``."""
    K = F.ring.domain
    x0, y0 = point
    R = poly_ring(("s", "t"), K)
    s, t = R.gens
    G = compose(F, [R.ground_new(x0) + s, R.ground_new(y0) + t * s])
    T = poly_ring(("t",), K)
    alpha = T.from_dict({(m[1],): c for m, c in G.items() if m[0] == 2})
    beta = T.from_dict({(m[1],): c for m, c in G.items() if m[0] == 1})
    if not alpha or any(m[0] == 0 and c for m, c in G.items()):
        return None
    (tt,) = T.gens
    return (T.ground_new(x0) * alpha - beta, alpha), (T.ground_new(y0) * alpha - tt * beta, alpha)
