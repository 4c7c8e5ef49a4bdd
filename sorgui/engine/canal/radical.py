"""Sphere families in radicals, and the surface they parameterize (docs/math.md §9).

A SMAT curve of positive genus has no rational ``m(t), ρ(t)``, yet its equations can often be
solved by square roots, one coordinate at a time: the two-cylinder blend's spine
``{m1² + m3² = 9, m2² + m3² = 16}`` is ``m = (√(9 − t²), √(16 − t²), t)`` with ``t = m3``.
:func:`radical_family` finds such a solution: one SMAT coordinate is the parameter ``t``, and each
other is then fixed by an equation of degree 1 or 2 in it alone, solved by the quadratic
formula, the square root ``s_k = √P_k(t, s₀, …, s_{k−1})`` (``P_k`` a polynomial) named by a new
symbol. The family is verified by substitution into every SMAT equation, reduced modulo the
relations ``s_k² = P_k``.

:func:`radical_surface` gives the surface ``c(t) + R(t)(cos θ·e₁/|e₁| + sin θ·e₂/|e₂|)`` of its
characteristic circles (``ds_k/dt = P_k′/(2 s_k)`` by the chain rule) and verifies it as the
rational families' radical parameterization is verified: ``f(c + a·e₁ + b·e₂)`` with the
denominators cleared, reduced modulo the root relations and the circle
``a²|e₁|² + b²|e₂|² = R²``, must be zero. The arithmetic is python-flint's, reduced after every
product, so a degree-24 blend takes a fraction of a second.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import sympy
from flint import fmpq, fmpq_mpoly, fmpq_mpoly_ctx

from ..algebra.fractions import homogeneous_numerator
from ..algebra.polys import Poly, to_flint
from .parametrization import (
    THETA,
    T,
    frame,
    rational_root,
    reduce_square,
    square_root,
)
from .spine import SMAT_NAMES, SmatCurve

A, B = sympy.symbols("a b")
"""The circle's coordinates in the verification: the point ``c + a·e₁ + b·e₂``."""


@dataclass(frozen=True)
class RadicalFamily:
    """``m(t)``, ``ρ(t)`` rational in ``t`` and the roots ``s_k``, with ``s_k² = P_k`` for the
    ``(s_k, P_k)`` of ``roots`` (``P_k`` a polynomial in ``t`` and the earlier roots);
    ``parameter`` is the SMAT coordinate that ``t`` stands for."""

    m: tuple[sympy.Expr, sympy.Expr, sympy.Expr]
    rho: sympy.Expr
    roots: tuple[tuple[sympy.Symbol, sympy.Expr], ...]
    parameter: str

    def derivative(self, expr: sympy.Expr) -> sympy.Expr:
        """``d expr/dt`` with ``ds_k/dt = (dP_k/dt)/(2 s_k)``."""
        rates: dict[sympy.Symbol, sympy.Expr] = {}
        for s, radicand in self.roots:
            rates[s] = self._total(radicand, rates) / (2 * s)
        return self._total(expr, rates)

    @staticmethod
    def _total(expr: sympy.Expr, rates: dict[sympy.Symbol, sympy.Expr]) -> sympy.Expr:
        return sympy.diff(expr, T) + sum((sympy.diff(expr, s) * rate for s, rate in rates.items()), sympy.Integer(0))

    def reduced(self, expr: sympy.Expr) -> sympy.Expr:
        """``expr`` with numerator and denominator reduced modulo ``s_k² = P_k`` (every root
        to degree ≤ 1), factored."""
        return _reduced(expr, self.roots)

    def radicals(self, expr: sympy.Expr) -> sympy.Expr:
        """``expr`` with every ``s_k`` written as the square root it names."""
        values: dict[sympy.Symbol, sympy.Expr] = {}
        for s, radicand in self.roots:
            values[s] = square_root(radicand.subs(values))
        return expr.subs(values)


def radical_family(curve: SmatCurve) -> RadicalFamily | None:
    """``m(t)``, ``ρ(t)`` of ``curve`` in square roots (the module docstring), verified, with the
    parameter that needs the fewest and smallest roots; ``None`` when no SMAT coordinate leads
    to a solution by roots of degree 2 (or it fails to verify)."""
    names = [sympy.Symbol(n) for n in SMAT_NAMES]
    equations = [g.as_expr() for g in curve.equations]
    found = []
    for index in range(3):
        family = _solve(equations, names, index)
        if family is not None and all(
            _vanishes(family, g.subs(dict(zip(names, (*family.m, family.rho))))) for g in equations
        ):
            found.append(family)
    return min(found, key=_size, default=None)


def _size(family: RadicalFamily) -> tuple[int, int]:
    """How many roots, and how large their radicands (total degree)."""
    return len(family.roots), sum(
        sympy.Poly(P, T, *(s for s, _ in family.roots)).total_degree() for _, P in family.roots
    )


def _solve(equations: list[sympy.Expr], names: list[sympy.Symbol], index: int) -> RadicalFamily | None:
    """The coordinates solved one by one, ``names[index]`` being ``t``."""
    values: dict[sympy.Symbol, sympy.Expr] = {names[index]: T}
    roots: list[tuple[sympy.Symbol, sympy.Expr]] = []
    pending = list(equations)
    while len(values) < len(names):
        for g in pending:
            numerator = sympy.numer(sympy.together(g.subs(values)))
            unknown = [v for v in names if v not in values and numerator.has(v)]
            if len(unknown) != 1:
                continue
            v = unknown[0]
            poly = sympy.Poly(numerator, v)
            if poly.degree() == 1:
                values[v] = sympy.cancel(-poly.coeff_monomial(1) / poly.coeff_monomial(v))
            elif poly.degree() == 2:
                a, b, c = (poly.coeff_monomial(v**k) for k in (2, 1, 0))
                values[v] = sympy.cancel((-b + _new_root(sympy.cancel(b * b - 4 * a * c), roots)) / (2 * a))
            else:
                continue
            pending.remove(g)
            break
        else:
            return None
    m = (values[names[0]], values[names[1]], values[names[2]])
    return RadicalFamily(m, values[names[3]], tuple(roots), str(names[index]))


def _new_root(square: sympy.Expr, roots: list[tuple[sympy.Symbol, sympy.Expr]]) -> sympy.Expr:
    """A square root of the rational function ``square``: itself when ``square`` is a square in
    ``QQ(t)``, else ``s/D`` for a new root ``s = √(N·D)`` when ``square = N/D`` (so every
    radicand is a polynomial)."""
    square = _reduced(square, roots)
    root = rational_root(square) if square.free_symbols <= {T} else None
    if root is not None:
        return root
    numerator, denominator = sympy.fraction(sympy.cancel(square))
    s = sympy.Symbol(f"s{len(roots)}")
    roots.append((s, _reduced(sympy.expand(numerator * denominator), roots)))
    return s / denominator


def _reduced(expr: sympy.Expr, roots: Sequence[tuple[sympy.Symbol, sympy.Expr]]) -> sympy.Expr:
    """``expr`` with numerator and denominator reduced modulo ``s² = P`` for the ``(s, P)`` of
    ``roots``, the last first (its radicand holds the earlier roots), factored."""
    parts = []
    for part in sympy.fraction(sympy.together(expr)):
        part = sympy.expand(part)
        for s, radicand in reversed(roots):
            part = sympy.rem(part, s**2 - radicand, s) if part.has(s) else part
        parts.append(sympy.factor(part))
    return parts[0] / parts[1]


def radical_surface(f: Poly, family: RadicalFamily) -> tuple[tuple[sympy.Expr, sympy.Expr, sympy.Expr], bool]:
    """The characteristic circles ``c + R(cos θ·e₁/|e₁| + sin θ·e₂/|e₂|)`` of ``family`` written
    with square roots, and whether ``f`` vanishes on them exactly (the module docstring)."""
    dm = tuple(family.derivative(c) for c in family.m)
    drho = family.derivative(family.rho)
    n2 = sum((d * d for d in dm), sympy.Integer(0))
    center = tuple(c - drho / (2 * n2) * d for c, d in zip(family.m, dm))
    radius_squared = family.rho - drho**2 / (4 * n2)
    e1, e2 = frame(dm)
    norm1, norm2 = (sum((c * c for c in e), sympy.Integer(0)) for e in (e1, e2))
    verified = _on_circles(f, family, center, radius_squared, e1, e2, norm1, norm2)
    shown = family.radicals
    radius, length1, length2 = (square_root(shown(family.reduced(q))) for q in (radius_squared, norm1, norm2))
    x, y, z = (
        shown(family.reduced(c))
        + radius
        * (
            sympy.cos(THETA) * shown(family.reduced(u)) / length1
            + sympy.sin(THETA) * shown(family.reduced(w)) / length2
        )
        for c, u, w in zip(center, e1, e2)
    )
    return (x, y, z), verified


def _on_circles(
    f: Poly,
    family: RadicalFamily,
    center: tuple[sympy.Expr, ...],
    radius_squared: sympy.Expr,
    e1: tuple[sympy.Expr, ...],
    e2: tuple[sympy.Expr, ...],
    norm1: sympy.Expr,
    norm2: sympy.Expr,
) -> bool:
    """``f(c + a·e₁ + b·e₂) ≡ 0`` modulo the root relations and ``a²|e₁|² + b²|e₂|² = R²``."""
    circle = sympy.numer(sympy.together(A**2 * norm1 + B**2 * norm2 - radius_squared))
    ring = _Ring(family, circle)
    points = [sympy.fraction(sympy.together(c + A * u + B * w)) for c, u, w in zip(center, e1, e2)]
    common = sympy.Integer(1)
    for _, den in points:
        common = sympy.lcm(common, den)
    coords = [ring.element(num * sympy.cancel(common / den)) for num, den in points]
    D = ring.element(common)
    g = to_flint(f)
    value = homogeneous_numerator(zip(g.monoms(), g.coeffs()), coords, D, ring.ctx, ring.reduce)
    lead = sympy.expand(circle).coeff(A, 2)
    rest = sympy.expand(circle - lead * A**2)
    return ring.reduce(
        reduce_square(value, len(ring.roots), ring.element(lead), -ring.element(rest), ring.ctx)
    ).is_zero()


class _Ring:
    """``QQ[s_k…, s₀, a, t, b]`` (lexicographic, the roots first) with the root relations and,
    when given, the circle's (it divides every product too, which keeps the degree in ``a``
    low; a zero remainder still proves membership)."""

    def __init__(self, family: RadicalFamily, circle: sympy.Expr | None = None) -> None:
        self.roots = [s for s, _ in family.roots]
        self.symbols = (*reversed(self.roots), A, T, B)
        self.ctx = fmpq_mpoly_ctx.get(tuple(str(s) for s in self.symbols), "lex")
        self.relations = [
            self.ctx.gens()[len(self.roots) - 1 - k] ** 2 - self.element(radicand)
            for k, (_, radicand) in enumerate(family.roots)
        ]
        if circle is not None:
            self.relations.append(self.reduce(self.element(circle)))

    def element(self, expr: sympy.Expr) -> fmpq_mpoly:
        """A polynomial expression in the ring's symbols as an element of the context."""
        poly = sympy.Poly(sympy.expand(expr), *self.symbols)
        return self.ctx.from_dict(
            {m: fmpq(int(sympy.Rational(c).p), int(sympy.Rational(c).q)) for m, c in poly.terms()}
        )

    def reduce(self, p: fmpq_mpoly) -> fmpq_mpoly:
        """``p`` with every ``s_k²`` replaced, the last root first (its radicand holds the
        earlier ones), after the circle's relation when there is one."""
        for relation in reversed(self.relations):
            p = p % relation
        return p


def _vanishes(family: RadicalFamily, expr: sympy.Expr) -> bool:
    """Whether ``expr`` (rational in ``t`` and the roots) is zero given the root relations."""
    ring = _Ring(family)
    return ring.reduce(ring.element(sympy.numer(sympy.together(expr)))).is_zero()
