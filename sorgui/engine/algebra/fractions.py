"""Rational functions over ``QQ`` as reduced fractions of python-flint polynomials.

The canal surface's sphere families ``m(t), ρ(t)``, their characteristic circles and the
parameterizations built on them (docs/math.md §9) are rational functions of one or two
parameters. sympy's ``cancel`` on such nested expressions took seconds for a Dupin cyclide;
here every operation keeps ``numerator / denominator`` coprime with a monic denominator (flint's
multivariate ``gcd``), and sympy sees the result only once, when it is printed.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from math import gcd, lcm
from typing import Any

import sympy
from flint import fmpq, fmpq_mpoly, fmpq_mpoly_ctx
from flint.utils.flint_exceptions import DomainError
from sympy.core.mul import _keep_coeff

from .rationals import context

Monomial = tuple[int, ...]


@dataclass(frozen=True, eq=False)
class RationalFunction:
    """``num / den`` in ``QQ(names)``, with ``gcd(num, den) = 1`` and ``den`` monic (its leading
    coefficient in the context's order is 1), so that equal functions have equal parts."""

    num: fmpq_mpoly
    den: fmpq_mpoly

    @staticmethod
    def make(num: fmpq_mpoly, den: fmpq_mpoly) -> RationalFunction:
        """``num / den`` reduced; ``den`` must not be zero."""
        if den.is_zero():
            raise ZeroDivisionError("a rational function with a zero denominator")
        if num.is_zero():
            return RationalFunction(num, den.context().from_dict({(0,) * den.context().nvars(): 1}))
        g = num.gcd(den)
        if not g.is_one():
            num, den = num / g, den / g
        lead = den.leading_coefficient()
        return RationalFunction(num / lead, den / lead) if lead != 1 else RationalFunction(num, den)

    @staticmethod
    def constant(c: int | fmpq, ctx: fmpq_mpoly_ctx) -> RationalFunction:
        one = ctx.from_dict({(0,) * ctx.nvars(): 1})
        return RationalFunction(one * fmpq(c), one)

    @staticmethod
    def of(p: fmpq_mpoly) -> RationalFunction:
        """The polynomial ``p`` as a rational function."""
        return RationalFunction(p, p.context().from_dict({(0,) * p.context().nvars(): 1}))

    @property
    def ctx(self) -> fmpq_mpoly_ctx:
        return self.num.context()

    def is_zero(self) -> bool:
        return self.num.is_zero()

    def __add__(self, other: RationalFunction | int) -> RationalFunction:
        other = self._lift(other)
        if self.den == other.den:
            return RationalFunction.make(self.num + other.num, self.den)
        return RationalFunction.make(self.num * other.den + other.num * self.den, self.den * other.den)

    __radd__ = __add__

    def __neg__(self) -> RationalFunction:
        return RationalFunction(-self.num, self.den)

    def __sub__(self, other: RationalFunction | int) -> RationalFunction:
        return self + (-self._lift(other))

    def __rsub__(self, other: int) -> RationalFunction:
        return self._lift(other) - self

    def __mul__(self, other: RationalFunction | int | fmpq) -> RationalFunction:
        if not isinstance(other, RationalFunction):
            return RationalFunction.make(self.num * fmpq(other), self.den)
        # Cross-cancel first: the factors stay the size of the inputs.
        g1, g2 = self.num.gcd(other.den), other.num.gcd(self.den)
        num = (self.num / g1) * (other.num / g2)
        den = (self.den / g2) * (other.den / g1)
        return RationalFunction.make(num, den)

    __rmul__ = __mul__

    def __truediv__(self, other: RationalFunction | int | fmpq) -> RationalFunction:
        if not isinstance(other, RationalFunction):
            return self * (1 / fmpq(other))
        if other.is_zero():
            raise ZeroDivisionError("division by the zero rational function")
        return self * RationalFunction(other.den, other.num)

    def __eq__(self, other: object) -> bool:
        if isinstance(other, int):
            other = self._lift(other)
        if not isinstance(other, RationalFunction):
            return NotImplemented
        return self.num == other.num and self.den == other.den

    def derivative(self, var: int | str) -> RationalFunction:
        """The partial derivative with respect to the generator ``var``."""
        n, d = self.num, self.den
        return RationalFunction.make(n.derivative(var) * d - n * d.derivative(var), d * d)

    def _lift(self, other: RationalFunction | int) -> RationalFunction:
        return other if isinstance(other, RationalFunction) else RationalFunction.constant(other, self.ctx)

    def to_expr(self, symbols: Sequence[sympy.Symbol]) -> sympy.Expr:
        """The function as a sympy expression ``num/den`` in ``symbols`` with integer
        coefficients of no common factor, as ``sympy.cancel`` writes it (for printing)."""
        coeffs = [*self.num.coeffs(), *self.den.coeffs()]
        scale = fmpq(lcm(*(int(c.q) for c in coeffs)), gcd(*(int(c.p) for c in coeffs)))
        return poly_expr(self.num * scale, symbols) / poly_expr(self.den * scale, symbols)


def poly_expr(p: fmpq_mpoly, symbols: Sequence[sympy.Symbol]) -> sympy.Expr:
    """The flint polynomial ``p`` as a sympy expression in ``symbols``."""
    return sympy.Add(
        *(
            sympy.Rational(int(c.p), int(c.q)) * sympy.Mul(*(s**e for s, e in zip(symbols, m)))
            for m, c in zip(p.monoms(), p.coeffs())
        )
    )


def from_expr(expr: sympy.Expr, symbols: Sequence[sympy.Symbol], ctx: fmpq_mpoly_ctx | None = None) -> RationalFunction:
    """A rational function over ``QQ`` in ``symbols``, given as a sympy expression, in ``ctx``
    (whose first generators stand for ``symbols``; by default the ring named after them)."""
    ctx = ctx or context(tuple(str(s) for s in symbols))
    num, den = sympy.fraction(sympy.together(expr))
    return RationalFunction.make(_from_poly(num, symbols, ctx), _from_poly(den, symbols, ctx))


def _from_poly(expr: sympy.Expr, symbols: Sequence[sympy.Symbol], ctx: fmpq_mpoly_ctx) -> fmpq_mpoly:
    p = sympy.Poly(expr, *symbols, domain="QQ")
    pad = (0,) * (ctx.nvars() - len(symbols))
    return ctx.from_dict({(*m, *pad): fmpq(int(c.numerator), int(c.denominator)) for m, c in p.terms()})


def lcm_all(polys: Iterable[fmpq_mpoly]) -> fmpq_mpoly:
    """The least common multiple of the nonempty ``polys`` (a common denominator)."""
    out = None
    for p in polys:
        out = p if out is None else out * (p / p.gcd(out))
    assert out is not None
    return out


def evaluate(terms: Iterable[tuple[Monomial, Any]], point: Sequence[RationalFunction]) -> RationalFunction:
    """``Σ c·xᵐ`` at ``x = point``, over one common denominator ``D``: the numerator of
    :func:`homogeneous_numerator` at ``xᵢ = (nᵢ·D/dᵢ) / D``, over ``D^deg``."""
    terms = [(tuple(m), fmpq(c)) for m, c in terms]
    ctx = point[0].ctx
    if not terms:
        return RationalFunction.constant(0, ctx)
    D = lcm_all(p.den for p in point)
    scaled = [p.num * (D / p.den) for p in point]
    degree = max(sum(m) for m, _ in terms)
    return RationalFunction.make(homogeneous_numerator(terms, scaled, D, ctx), D**degree)


def homogeneous_numerator(
    terms: Iterable[tuple[Monomial, Any]],
    scaled: Sequence[fmpq_mpoly],
    common: fmpq_mpoly,
    ctx: fmpq_mpoly_ctx,
    reduce: Callable[[fmpq_mpoly], fmpq_mpoly] = lambda p: p,
) -> fmpq_mpoly:
    """``Σ c·Π sᵢ^{mᵢ}·D^{deg − |m|}``: the numerator of ``Σ c·xᵐ`` (of total degree ``deg``)
    at the point ``xᵢ = sᵢ / D``, whose value is this over ``D^deg``. ``reduce`` is applied
    after every product (a normal form modulo relations the point satisfies, which keeps the
    products small); the powers of each ``sᵢ`` and of ``D`` are computed once."""
    terms = [(tuple(m), c) for m, c in terms]
    if not terms:
        return ctx.from_dict({})
    degree = max(sum(m) for m, _ in terms)
    bases = (*scaled, common)
    powers: dict[tuple[int, int], fmpq_mpoly] = {}

    def power(i: int, e: int) -> fmpq_mpoly:
        if (i, e) not in powers:
            powers[(i, e)] = bases[i] if e == 1 else reduce(power(i, e - 1) * bases[i])
        return powers[(i, e)]

    total = ctx.from_dict({})
    for m, c in terms:
        term = ctx.from_dict({(0,) * ctx.nvars(): c})
        for i, e in enumerate((*m, degree - sum(m))):
            if e:
                term = reduce(term * power(i, e))
        total += term
    return reduce(total)


def factored(f: RationalFunction, symbols: Sequence[sympy.Symbol]) -> sympy.Expr:
    """``f`` as sympy prints a factored rational function: the content times the integer,
    primitive, irreducible factors of the numerator over those of the denominator."""
    (cn, num), (cd, den) = f.num.factor(), f.den.factor()
    content = cn / cd
    body = sympy.Mul(*(poly_expr(g, symbols) ** e for g, e in num)) / sympy.Mul(
        *(poly_expr(g, symbols) ** e for g, e in den)
    )
    return _keep_coeff(sympy.Rational(int(content.p), int(content.q)), body)


def square_root(f: RationalFunction) -> RationalFunction | None:
    """A rational function whose square is ``f``, or ``None`` when ``f`` is not a square."""
    try:
        return RationalFunction(f.num.sqrt(), f.den.sqrt())
    except DomainError:
        return None


def square_root_parts(f: RationalFunction) -> tuple[RationalFunction, fmpq, fmpq_mpoly, fmpq_mpoly]:
    """``(q, c, N, D)`` with ``f = q²·c·N/D``: ``N`` and ``D`` the products of the factors of
    odd multiplicity of ``f``'s numerator and denominator, so that ``√f = q·√c·√N/√D``."""
    (cn, num), (cd, den) = f.num.factor(), f.den.factor()
    ctx = f.ctx
    one = ctx.from_dict({(0,) * ctx.nvars(): 1})
    outside, below = one, one
    odd = [one, one]
    for k, factors in enumerate((num, den)):
        for g, e in factors:
            if k == 0:
                outside *= g ** (e // 2)
            else:
                below *= g ** (e // 2)
            if e % 2:
                odd[k] *= g
    return RationalFunction.make(outside, below), cn / cd, odd[0], odd[1]


def embed(p: fmpq_mpoly, ctx: fmpq_mpoly_ctx) -> fmpq_mpoly:
    """``p`` in the ring ``ctx`` whose first generators are ``p``'s (the others not occurring)."""
    n = ctx.nvars()
    return ctx.from_dict({(*m, *(0,) * (n - len(m)))[:n]: c for m, c in zip(p.monoms(), p.coeffs())})
