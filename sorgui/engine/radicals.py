"""Fast exact polynomials with square-root coefficients: ``QQ(√d₁, …, √d_k)[vars]`` over flint.

Parameterizations have coefficients in small multiquadratic fields (``√3``, ``i``, ``√-n``).
Instead of sympy's primitive-element arithmetic, which is slow in several variables, each
radical ``√dᵢ`` becomes an extra flint variable ``rᵢ`` with the relation ``rᵢ² = dᵢ``; every
result is reduced modulo the relations. The reduced form is unique when the radicands are
multiplicatively independent modulo squares (sympy already writes ``√2·√3`` as ``√6``), so a
zero normal form proves an identity; a nonzero one is only trusted after an exact recheck by
the caller.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import sympy
from flint import fmpq, fmpq_mpoly, fmpq_mpoly_ctx


def radicals_of(expressions: Iterable[sympy.Expr]) -> tuple[sympy.Expr, ...]:
    """The square roots of rationals (``sqrt(3)``, ``I``) in the expressions, sorted."""
    found: set[sympy.Expr] = set()
    for e in expressions:
        found |= {a for a in e.atoms(sympy.Pow) if a.exp == sympy.Rational(1, 2) and a.base.is_Rational}
        if e.has(sympy.I):
            found.add(sympy.I)
    return tuple(sorted(found, key=str))


@dataclass(frozen=True)
class RadicalRing:
    """``QQ[variables, r₁, …, r_k]`` modulo ``rᵢ² = radicalᵢ²``."""

    variables: tuple[str, ...]
    radicals: tuple[sympy.Expr, ...]

    @property
    def context(self) -> fmpq_mpoly_ctx:
        names = self.variables + tuple(f"_r{i}" for i in range(len(self.radicals)))
        return fmpq_mpoly_ctx.get(names, "lex")

    @property
    def symbols(self) -> tuple[sympy.Symbol, ...]:
        return tuple(sympy.Symbol(v) for v in self.variables)

    @property
    def is_real(self) -> bool:
        """Whether every radical is real (the field lies in ``R``)."""
        return all(r.is_real for r in self.radicals)

    @property
    def field(self) -> str:
        """``QQ`` or ``QQ(sqrt(3), I)``."""
        return "QQ(" + ", ".join(map(str, self.radicals)) + ")" if self.radicals else "QQ"

    def relations(self) -> list[fmpq_mpoly]:
        """``rᵢ² - dᵢ``."""
        ctx = self.context
        gens = ctx.gens()[len(self.variables):]
        return [g**2 - _rational(r**2) for g, r in zip(gens, self.radicals)]

    def reduce(self, p: fmpq_mpoly) -> fmpq_mpoly:
        """The normal form of ``p`` modulo the relations (degree ≤ 1 in each ``rᵢ``)."""
        for rel in self.relations():
            p = p % rel
        return p

    def from_expr(self, expr: sympy.Expr) -> fmpq_mpoly:
        """A polynomial sympy expression in the variables and the radicals, as a flint polynomial."""
        marks = [sympy.Symbol(f"_r{i}") for i in range(len(self.radicals))]
        replaced = sympy.expand(expr).xreplace(dict(zip(self.radicals, marks)))
        poly = sympy.Poly(replaced, *self.symbols, *marks, domain="QQ")
        return self.reduce(self.context.from_dict({m: _rational(c) for m, c in poly.terms()}))

    def fraction(self, expr: sympy.Expr) -> tuple[fmpq_mpoly, fmpq_mpoly]:
        """A rational sympy expression as (numerator, denominator)."""
        num, den = sympy.fraction(sympy.together(expr))
        return self.from_expr(num), self.from_expr(den)

    def to_expr(self, p: fmpq_mpoly) -> sympy.Expr:
        """Back to sympy, with the radicals in place of the ``rᵢ``."""
        values = (*self.symbols, *self.radicals)
        return sympy.Add(*[sympy.Rational(int(c.p), int(c.q)) * sympy.Mul(*[v**int(e) for v, e in zip(values, m)])
                           for m, c in p.to_dict().items()])

    def variable(self, name: str) -> fmpq_mpoly:
        return self.context.gens()[self.variables.index(name)]


def _rational(q: object) -> fmpq:
    q = sympy.Rational(q)
    return fmpq(int(q.p), int(q.q))
