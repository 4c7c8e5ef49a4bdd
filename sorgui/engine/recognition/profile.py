"""The profile curve and the axis frame, all over K (docs/math.md §3).

With ``c`` a point of the axis, ``a`` its direction and ``u ⟂ a`` (all in ``K³``),

    p̃(s, r) = f(c + s·a + r·u) ∈ K[s, r]

is the profile in a ``K``-rational frame. It is even in ``r`` for a surface of revolution;
replacing ``r²`` by ``w`` gives ``P²``. The orthonormal profile ``p(x, y) = p̃(x/|a|, y/|u|)``
is only for presentation (square roots appear when ``|a|²`` is not a square in ``K``); every
later computation uses ``p̃``, which is ``K``-linearly equivalent to it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import sympy
from flint import fmpq
from sympy.polys.domains import QQ
from sympy.polys.domains.domain import Domain

from ..algebra import numberfields
from ..algebra.linalg import Vector, cross, dot, perpendicular
from ..algebra.polys import (
    Poly,
    compose,
    field_generators,
    is_rational_field,
    number_field,
    poly_ring,
    primitive,
    sqrt_in_field,
    to_expr,
    total_degree,
)

S_R = ("s", "r")
S_W = ("s", "w")


@dataclass(frozen=True)
class AxisFrame:
    """A ``K``-rational frame of the axis: point ``c``, direction ``a``, and ``u ⟂ a``.

    ``w = a × u`` completes it; ``|w|² = |a|²·|u|²``.
    """

    point: Vector
    direction: Vector
    normal: Vector

    @property
    def binormal(self) -> Vector:
        """``w = a × u``."""
        return cross(self.direction, self.normal)


@dataclass(frozen=True)
class ProfileCurve:
    """The profile of a surface of revolution in its axis frame.

    ``rational`` is ``p̃(s, r)``, ``square`` is ``P²`` as ``p̃²(s, w)``, ``orthonormal`` is the
    presented profile ``p(x, y)`` (x along the axis, y the distance; over ``K`` or ``K(|a|)``).
    ``verified`` records the paper's exact test ``f = p(x, y² + z²)`` in the axis frame.
    """

    frame: AxisFrame
    rational: Poly
    square: Poly
    orthonormal: Poly
    even: bool
    verified: bool


def axis_frame(point: Vector, direction: Vector, K: Domain) -> AxisFrame:
    """A frame with a simple ``u`` (:func:`sorgui.engine.algebra.linalg.perpendicular`)."""
    return AxisFrame(point=point, direction=direction, normal=perpendicular(direction, K))


def plane_foot(f: Poly) -> tuple[Vector, Vector]:
    """For a plane ``f = n·p + d`` (degree 1): the point of it nearest the origin, ``−d·n/|n|²``,
    and its normal ``n``, the frame of the normal line a plane's profile is read about."""
    K = f.ring.domain
    d = f(K.zero, K.zero, K.zero)
    normal = tuple(f(*(K.one if j == i else K.zero for j in range(3))) - d for i in range(3))
    scale = K.quo(-d, dot(normal, normal))
    return tuple(scale * n for n in normal), normal


def profile_polynomial(f: Poly, frame: AxisFrame) -> Poly:
    """``p̃(s, r) = f(c + s·a + r·u)`` in ``K[s, r]``."""
    K = f.ring.domain
    R = poly_ring(S_R, K)
    s, r = R.gens
    c, a, u = frame.point, frame.direction, frame.normal
    return compose(f, [c[i] + s * a[i] + r * u[i] for i in range(3)])


def is_even_in_second(p: Poly) -> bool:
    """Whether ``p(s, r)`` contains ``r`` in even powers only."""
    return all(m[1] % 2 == 0 for m in p.itermonoms())


def square_profile(p: Poly) -> Poly:
    """``P²``: the even polynomial ``p̃(s, r)`` with ``r²`` replaced by ``w``."""
    R = poly_ring(S_W, p.ring.domain)
    return R.from_dict({(m[0], m[1] // 2): c for m, c in p.items()})


def verify_profile(f: Poly, frame: AxisFrame, square: Poly) -> bool:
    """The paper's exact test in the axis frame: ``f(c + s·a + r₁·u + r₂·w) = P²(s, r₁² + |a|²r₂²)``.

    The point ``c + s·a + r₁u + r₂w`` lies at squared distance ``|u|²(r₁² + |a|²r₂²)`` from the
    axis, so this is ``f = p(x, y² + z²)`` written without square roots.
    """
    K = f.ring.domain
    R = poly_ring(("s", "r1", "r2"), K)
    s, r1, r2 = R.gens
    c, a, u, w = frame.point, frame.direction, frame.normal, frame.binormal
    lhs = compose(f, [c[i] + s * a[i] + r1 * u[i] + r2 * w[i] for i in range(3)])
    rhs = compose(square, [s, r1**2 + dot(a, a) * r2**2])
    return bool(lhs == rhs)


def orthonormal_profile(p: Poly, frame: AxisFrame) -> Poly:
    """``p(x, y) = p̃(x/|a|, y/|u|)`` for presentation, in a canonical scale (the top coefficient
    in ``y`` positive; integer coefficients with content 1 when they are rational).

    Its field is ``K``, or ``K(|a|)`` when ``|a|²`` is not a square in ``K``; ``y`` only occurs
    squared, so ``|u|`` never needs a square root.
    """
    K = p.ring.domain
    n = dot(frame.direction, frame.direction)
    root = sqrt_in_field(K, n)
    convert: Callable[[Any], Any]
    L, convert = K, (lambda c: c)
    if root is None:
        L, root, convert = _adjoin_root(K, n)
    inverse_root = L.quo(L.one, root)
    inverse_m = L.quo(L.one, convert(dot(frame.normal, frame.normal)))
    R = poly_ring(("x", "y"), L)
    terms = {(i, j): convert(c) * inverse_root**i * inverse_m ** (j // 2) for (i, j), c in p.items()}
    top = terms[max(terms, key=lambda m: (m[1], m[0]))]
    scaled = {m: to_expr(L, L.quo(c, top)) for m, c in terms.items()}
    if all(c.is_Rational for c in scaled.values()):
        rational = primitive(poly_ring(("x", "y"), QQ).from_dict({m: QQ.from_sympy(c) for m, c in scaled.items()}))
        top_monomial = max(scaled, key=lambda m: (m[1], m[0]))
        return rational if dict(rational.items())[top_monomial] > 0 else -rational
    return R.from_dict({m: L.quo(c, top) for m, c in terms.items()})


def _adjoin_root(K: Domain, n: Any) -> tuple[Domain, Any, Callable[[Any], Any]]:
    """``L = K(√n)``, ``√n ∈ L`` and the embedding ``K → L``. A rational ``n`` keeps ``L``
    multiquadratic, so the embedding goes through the radical basis (no field isomorphism
    search); otherwise sympy builds ``L``."""
    value = to_expr(K, n)
    if value.is_Rational and not is_rational_field(K):
        q = fmpq(int(value.p), int(value.q))
        core = numberfields.squarefree_core(int(value.p * value.q))
        L = number_field(tuple(numberfields.radical_basis(K).radicands) + (core,))
        return L, numberfields.rational_sqrt(L, q), lambda c: numberfields.embed(c, K, L)
    L = QQ.algebraic_field(*field_generators(K), sympy.sqrt(value))
    return L, L.from_sympy(sympy.sqrt(value)), lambda c: L.convert(c, K)


def profile_curve(f: Poly, point: Vector, direction: Vector, normal: Vector | None = None) -> ProfileCurve:
    """The profile of ``f`` about the axis through ``point`` with ``direction`` (docs/math.md §3);
    ``normal`` (``u ⟂ a``) is chosen by :func:`axis_frame` unless given."""
    K = f.ring.domain
    frame = axis_frame(point, direction, K) if normal is None else AxisFrame(point, direction, normal)
    raw = profile_polynomial(f, frame)
    even = is_even_in_second(raw)
    verified = even and verify_profile(f, frame, square_profile(raw))
    rational = primitive(raw)
    return ProfileCurve(
        frame=frame,
        rational=rational,
        square=square_profile(rational) if even else poly_ring(S_W, K).zero,
        orthonormal=orthonormal_profile(rational, frame) if even else poly_ring(("x", "y"), K).zero,
        even=even,
        verified=verified,
    )


def power_profile(f: Poly, g: Poly, point: Vector, direction: Vector, normal: Vector) -> ProfileCurve:
    """The profile of ``f = c·g^k`` about the axis through ``point`` (:func:`profile_curve`), read
    off ``g``'s: ``p̃_f`` is ``p̃_g^k`` up to a constant, verified when ``p̃_g`` is. A plane or a
    sphere taken to the 45th power was composed in the axis frame and verified there (2 s,
    outside every stage). ``f`` itself when ``g``'s profile is not even in ``r``."""
    if f == g:
        return profile_curve(f, point, direction, normal)
    own = profile_curve(g, point, direction, normal)
    if not own.even:
        return profile_curve(f, point, direction, normal)
    rational = primitive(own.rational ** (total_degree(f) // total_degree(g)))
    return ProfileCurve(
        frame=own.frame,
        rational=rational,
        square=square_profile(rational),
        orthonormal=orthonormal_profile(rational, own.frame),
        even=True,
        verified=own.verified,
    )
