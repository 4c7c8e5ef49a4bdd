"""Fast exact polynomials with square-root coefficients: ``QQ(√d₁, …, √d_k)[vars]`` over flint.

Parameterizations have coefficients in small multiquadratic fields (``√3``, ``i``, ``√-n``).
Instead of sympy's primitive-element arithmetic, which is slow in several variables, each
radical becomes an extra flint variable ``ρᵢ`` with the relation ``ρᵢ² = dᵢ``, and results are
reduced modulo the relations. A radical is either a square root that sympy prints
(``sqrt(3)``, ``I``) or a symbol the caller introduces for a number sympy would split, such as
``√-14`` (sympy writes ``I*sqrt(14)``, two radicals where one suffices). The reduced form is
unique when the radicands are multiplicatively independent modulo squares, so a zero normal
form proves an identity; a nonzero one is only trusted after an exact recheck by the caller.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass

import sympy
from flint import fmpq, fmpq_mpoly, fmpq_mpoly_ctx


@dataclass(frozen=True)
class Radical:
    """A square root ``value`` (``sqrt(3)``, ``I``, ``I*sqrt(14)``) named ``symbol`` in the ring."""

    symbol: sympy.Symbol
    value: sympy.Expr

    @property
    def square(self) -> sympy.Rational:
        return sympy.Rational(sympy.expand(self.value**2))


def radicals_of(
    expressions: Iterable[sympy.Expr], named: Mapping[sympy.Symbol, sympy.Expr] | None = None
) -> tuple[Radical, ...]:
    """The radicals of the expressions: square roots of rationals and ``I`` as sympy prints them,
    plus the caller's ``named`` symbols (symbol → its value) that occur."""
    named = named or {}
    atoms: set[sympy.Expr] = set()
    symbols: set[sympy.Symbol] = set()
    for e in expressions:
        atoms |= {a for a in e.atoms(sympy.Pow) if a.exp == sympy.Rational(1, 2) and a.base.is_Rational}
        if e.has(sympy.I):
            atoms.add(sympy.I)
        symbols |= {s for s in e.free_symbols if s in named}
    found = [Radical(sympy.Symbol(f"_rho{i}"), a) for i, a in enumerate(sorted(atoms, key=str))]
    found += [Radical(s, named[s]) for s in sorted(symbols, key=str)]
    return tuple(found)


@dataclass(frozen=True)
class RadicalRing:
    """``QQ[variables, ρ₁, …, ρ_k]`` modulo ``ρᵢ² = dᵢ``."""

    variables: tuple[str, ...]
    radicals: tuple[Radical, ...]

    @property
    def context(self) -> fmpq_mpoly_ctx:
        names = self.variables + tuple(str(r.symbol) for r in self.radicals)
        return fmpq_mpoly_ctx.get(names, "lex")

    @property
    def symbols(self) -> tuple[sympy.Symbol, ...]:
        return tuple(sympy.Symbol(v) for v in self.variables)

    @property
    def is_real(self) -> bool:
        """Whether every radical is real (the coefficient field lies in ``R``)."""
        return all(r.square > 0 for r in self.radicals)

    @property
    def field(self) -> str:
        """``QQ`` or ``QQ(sqrt(3), sqrt(-14))``."""
        cores = [sympy.sqrt(r.square).as_coeff_Mul()[1] for r in self.radicals]
        names = list(dict.fromkeys(f"sqrt({sympy.expand(core**2)})" for core in cores))  # √-n may be i again
        return "QQ(" + ", ".join(names) + ")" if names else "QQ"

    def reduce(self, p: fmpq_mpoly) -> fmpq_mpoly:
        """The normal form of ``p`` modulo the relations (degree ≤ 1 in each ``ρᵢ``)."""
        gens = self.context.gens()[len(self.variables) :]
        for g, r in zip(gens, self.radicals):
            p = p % (g**2 - _rational(r.square))
        return p

    def from_expr(self, expr: sympy.Expr) -> fmpq_mpoly:
        """A polynomial sympy expression in the variables and the radicals, as a flint polynomial."""
        marks = [r.symbol for r in self.radicals]
        printed = {r.value: r.symbol for r in self.radicals if r.symbol.name.startswith("_rho")}
        replaced = sympy.expand(sympy.expand(expr).xreplace(printed))
        poly = sympy.Poly(replaced, *self.symbols, *marks, domain="QQ")
        return self.reduce(self.context.from_dict({m: _rational(c) for m, c in poly.terms()}))

    def fraction(self, expr: sympy.Expr) -> tuple[fmpq_mpoly, fmpq_mpoly]:
        """A rational sympy expression as (numerator, denominator)."""
        num, den = sympy.fraction(sympy.together(expr))
        return self.from_expr(num), self.from_expr(den)

    def to_expr(self, p: fmpq_mpoly) -> sympy.Expr:
        """Back to sympy, with the radicals' values in place of the ``ρᵢ``."""
        values = (*self.symbols, *(r.value for r in self.radicals))
        return sympy.Add(
            *[
                sympy.Rational(int(c.p), int(c.q)) * sympy.Mul(*[v ** int(e) for v, e in zip(values, m)])
                for m, c in p.to_dict().items()
            ]
        )

    def variable(self, name: str) -> fmpq_mpoly:
        return self.context.gens()[self.variables.index(name)]

    def extended(self, more: Iterable[Radical]) -> RadicalRing:
        """The ring with further radicals (those whose value is new)."""
        known = {r.value for r in self.radicals}
        extra = [r for r in more if r.value not in known]
        renamed = [Radical(sympy.Symbol(f"_rho{len(self.radicals) + i}"), r.value) for i, r in enumerate(extra)]
        return RadicalRing(self.variables, self.radicals + tuple(renamed))


def _rational(q: object) -> fmpq:
    value = sympy.Rational(q)
    return fmpq(int(value.p), int(value.q))
