"""The rational map ``P(s, t) = X(s, t)/W(s, t)`` over ``K`` and its normal (docs/math.md §13).

A parametrization is kept over one common denominator: ``X = (X₁, X₂, X₃)`` and ``W`` in
``K[s, t]``. Over ``QQ`` these are python-flint's ``fmpq_mpoly`` (the ring
``rationals.context(("s", "t"))``), over a real field ``K`` with square roots sympy's sparse
polynomials; :class:`ParameterRing` holds the few operations where the two differ.

The normal of ``P`` is rational: expanding ``(X_s W − X W_s) × (X_t W − X W_t)`` and dividing by
``W`` gives ``P_s × P_t = Ñ/W³`` with

    Ñ = W·(X_s × X_t) + W_t·(X × X_s) + W_s·(X_t × X),

a polynomial vector that vanishes identically exactly when the image of ``P`` is a curve or a
point. Everything the exact decision needs is linear in a few unknowns with coefficients built
from ``X``, ``W`` and ``Ñ``; its rows come from values at rational parameter points
(:meth:`RationalMap.values`), which cost no polynomial products.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from fractions import Fraction
from functools import cached_property
from typing import Any

from flint import fmpq
from sympy.polys.domains import QQ
from sympy.polys.domains.domain import Domain

from ..algebra import rationals
from ..algebra.linalg import Vector, cross
from ..algebra.polys import Poly, from_rational, is_rational_field, poly_ring, poly_str

PARAMETERS = ("s", "t")
"""The internal names of the two parameters (the typed names are kept beside them)."""


class ParameterRing:
    """``K[s, t]``: flint over ``QQ``, sympy's sparse polynomials over other ``K``."""

    def __init__(self, K: Domain) -> None:
        self.K = K
        self.is_flint = is_rational_field(K)
        if self.is_flint:
            self._ctx = rationals.context(PARAMETERS)
            self.gens: tuple[Any, Any] = tuple(self._ctx.gens())  # type: ignore[assignment]
            self.zero: Any = self._ctx.from_dict({})
            self.one: Any = self._ctx.constant(1)
        else:
            self._ring = poly_ring(PARAMETERS, K)
            self.gens = tuple(self._ring.gens)
            self.zero = self._ring.zero
            self.one = self._ring.one

    def constant(self, c: Any) -> Any:
        """The constant polynomial ``c`` (an element of ``K``, or an ``int`` or ``Fraction``)."""
        if isinstance(c, (int, Fraction)):
            c = from_rational(self.K, c)
        return self._ctx.constant(c) if self.is_flint else self._ring.ground_new(c)

    def terms(self, p: Any) -> list[tuple[tuple[int, int], Any]]:
        """The terms of ``p``: exponents ``(i, j)`` of ``s^i t^j`` and coefficients in ``K``."""
        if self.is_flint:
            return [((int(m[0]), int(m[1])), c) for m, c in p.terms()]
        return [((int(m[0]), int(m[1])), c) for m, c in p.items()]

    def derivative(self, p: Any, i: int) -> Any:
        """``∂p/∂s`` (``i = 0``) or ``∂p/∂t`` (``i = 1``)."""
        return p.derivative(i) if self.is_flint else p.diff(self._ring.gens[i])

    def value(self, p: Any, point: Sequence[Any]) -> Any:
        """``p(s₀, t₀)`` in ``K``."""
        if self.is_flint:
            return p(*(fmpq(c) if not isinstance(c, fmpq) else c for c in point))
        return self.K.convert(p(*point)) if p else self.K.zero

    def is_constant(self, p: Any) -> bool:
        return bool(p.is_constant()) if self.is_flint else bool(p.is_ground)

    def degree(self, p: Any) -> int:
        """The total degree (``-1`` for ``0``)."""
        if self.is_flint:
            return int(p.total_degree())
        return max((sum(m) for m in p.itermonoms()), default=-1)

    def degrees(self, p: Any) -> tuple[int, int]:
        """The degrees in ``s`` and in ``t``."""
        if not p:
            return -1, -1
        return (int(p.degrees()[0]), int(p.degrees()[1]))

    def gcd(self, a: Any, b: Any) -> Any:
        return a.gcd(b)

    def exquo(self, a: Any, b: Any) -> Any:
        """``a / b`` for a divisor ``b`` of ``a``."""
        return a / b if self.is_flint else a.exquo(b)

    def leading_coefficient(self, p: Any) -> Any:
        return p.leading_coefficient() if self.is_flint else p.LC

    def restrict(self, p: Any, index: int, value: Any) -> dict[int, Any]:
        """``p`` with parameter ``index`` set to ``value``: the coefficients of the other one."""
        out: dict[int, Any] = {}
        for (i, j), c in self.terms(p):
            free, fixed = (j, i) if index == 0 else (i, j)
            out[free] = out.get(free, self.K.zero) + c * value**fixed
        return {k: c for k, c in out.items() if c}

    def to_sympy(self, p: Any) -> Poly:
        """``p`` as a polynomial of sympy's ring ``K[s, t]`` (for Singular and the printer)."""
        return poly_ring(PARAMETERS, self.K).from_dict(dict(self.terms(p)))

    def text(self, p: Any, names: Sequence[str] = PARAMETERS) -> str:
        """``p`` as an exact string in ``names`` (sympy's syntax)."""
        if self.is_flint:
            return rationals.flint_str(p, names)
        return poly_str(poly_ring(tuple(names), self.K).from_dict(dict(self.terms(p))))


def fraction_text(ring: ParameterRing, numerator: Any, denominator: Any, names: Sequence[str] = PARAMETERS) -> str:
    """``N/D`` as an exact string in ``names``: ``N`` when ``D`` is ``1``, ``(N)/(D)`` else."""
    top = ring.text(numerator, names)
    if denominator == ring.one:  # not value(…) == 1: an element of QQ(√2) is never equal to the int 1
        return top
    return f"({top})/({ring.text(denominator, names)})"


@dataclass(frozen=True)
class RationalMap:
    """``P = X/W`` with ``X = (X₁, X₂, X₃)`` and ``W ≠ 0`` in ``K[s, t]`` (no common factor of
    all four is needed)."""

    ring: ParameterRing
    X: tuple[Any, Any, Any]
    W: Any

    @classmethod
    def from_fractions(cls, ring: ParameterRing, fractions: Sequence[tuple[Any, Any]]) -> RationalMap:
        """The map of three reduced fractions ``Nᵢ/Dᵢ``: ``W`` is the least common multiple of
        the ``Dᵢ`` with leading coefficient 1."""
        W = ring.one
        for _numerator, denominator in fractions:
            W = ring.exquo(W * denominator, ring.gcd(W, denominator))
        W = W * (ring.K.one / ring.leading_coefficient(W)) if ring.is_flint else W.monic()
        X = tuple(n * ring.exquo(W, d) for n, d in fractions)
        return cls(ring, (X[0], X[1], X[2]), W)

    @property
    def K(self) -> Domain:
        return self.ring.K

    @property
    def degree(self) -> int:
        """The largest total degree of ``X₁, X₂, X₃, W``."""
        return max(self.ring.degree(p) for p in (*self.X, self.W))

    @cached_property
    def derivatives(self) -> tuple[tuple[Any, Any, Any], tuple[Any, Any, Any], Any, Any]:
        """``X_s``, ``X_t``, ``W_s``, ``W_t``."""
        d = self.ring.derivative
        return (
            (d(self.X[0], 0), d(self.X[1], 0), d(self.X[2], 0)),
            (d(self.X[0], 1), d(self.X[1], 1), d(self.X[2], 1)),
            d(self.W, 0),
            d(self.W, 1),
        )

    @cached_property
    def normal(self) -> Vector:
        """``Ñ = W·(X_s × X_t) + W_t·(X × X_s) + W_s·(X_t × X)``, a polynomial vector."""
        Xs, Xt, Ws, Wt = self.derivatives
        first, second, third = cross(Xs, Xt), cross(self.X, Xs), cross(Xt, self.X)
        return tuple(self.W * first[i] + Wt * second[i] + Ws * third[i] for i in range(3))

    def values(self, point: Sequence[Any]) -> tuple[Vector, Any, Vector]:
        """``X(p)``, ``W(p)`` and ``Ñ(p)`` at a parameter point, from values only."""
        v = self.ring.value
        Xs, Xt, Ws, Wt = self.derivatives
        X = tuple(v(c, point) for c in self.X)
        W = v(self.W, point)
        xs, xt = tuple(v(c, point) for c in Xs), tuple(v(c, point) for c in Xt)
        ws, wt = v(Ws, point), v(Wt, point)
        first, second, third = cross(xs, xt), cross(X, xs), cross(xt, X)
        return X, W, tuple(W * first[i] + wt * second[i] + ws * third[i] for i in range(3))

    def sample_points(self, count: int, batch: int = 0) -> list[tuple[Any, Any]]:
        """``count`` rational parameter points of a fixed sequence (batch by batch) at which
        ``W`` does not vanish: small numerators and denominators keep the values cheap."""
        found: list[tuple[Any, Any]] = []
        for k in _point_sequence(batch):
            point = k if self.ring.is_flint else tuple(self.K.convert(c, QQ) for c in k)
            if self.ring.value(self.W, point):
                found.append(point)
                if len(found) == count:
                    break
        return found

    def fractions(self) -> tuple[tuple[Any, Any], tuple[Any, Any], tuple[Any, Any]]:
        """``(Xᵢ/g, W/g)`` for each coordinate, ``g = gcd(Xᵢ, W)``: the reduced components."""
        out = []
        for c in self.X:
            g = self.ring.gcd(c, self.W)
            out.append((self.ring.exquo(c, g), self.ring.exquo(self.W, g)))
        return out[0], out[1], out[2]


def _point_sequence(batch: int) -> Iterator[tuple[fmpq, fmpq]]:
    """Parameter points ``(a/q, b/r)`` spread over ``[-10, 10]²``, a deterministic sequence of
    fractions with small denominators (rarely the special values ``0`` and ``±1``, where the
    poles and fixed points of Möbius reparametrizations usually sit)."""
    k = 40 * batch
    while True:
        a, b = (17 * k + 7) % 41 - 20, (29 * k + 11) % 43 - 21
        q, r = 3 + k % 5, 2 + (7 * k) % 5
        k += 1
        yield fmpq(a, q), fmpq(b, r)
