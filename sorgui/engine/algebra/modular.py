"""Identities tested exactly modulo a random prime at random points (docs/math.md §14).

A report's claims are identities between rational functions whose coefficients lie in a
field ``E = QQ(√d₁, …, √d_k)`` (and, for the circles of a canal surface, in square roots of
polynomials in one parameter and in ``cos θ``, ``sin θ``): a parameterization substituted into
``f`` is zero, a profile is ``f`` in the axis frame. Each identity is tested under a ring
homomorphism of ``E`` onto the integers modulo a prime ``p``: every square root is sent to a
square root modulo ``p``, chosen so that the choices agree (:class:`Embedding`), and every
variable to a random residue. A true identity stays true under it; a false one, a nonzero
rational function of degree ``D``, vanishes at a random point of ``GF(p)ⁿ`` with probability at
most ``D/p`` (Schwartz–Zippel), below ``10⁻¹⁴`` for the degrees a report may hold and a prime of
62 bits, and each claim is tested in :data:`ROUNDS` independent rounds (fresh prime, fresh
point, from the operating system's randomness, so a crafted report cannot aim at them).

Agreeing square roots: the constant radicands are split into a coprime basis by greatest
common divisors (no factoring, so a large radicand costs nothing); pairwise coprime integers that
are not squares are multiplicatively independent modulo squares, so any choice of signs for their
roots is a field embedding. A radicand polynomial ``P(t)`` is factored over ``QQ`` (flint) and
each irreducible factor gets its own root at the point, which is likewise independent. ``cos θ``
and ``sin θ`` become ``((1 - m²)/(1 + m²), 2m/(1 + m²))`` for a random ``m``: a point of the circle.
Nothing here is floating point.
"""

from __future__ import annotations

import secrets
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from math import gcd, isqrt
from typing import Any

import sympy
from flint import fmpq, fmpq_poly
from sympy.ntheory import sqrt_mod

from ..errors import AnalysisError

ROUNDS = 2
"""Independent rounds (prime and point) in which every identity must hold."""

PRIME_BITS = 62
"""The size of the random primes."""

ATTEMPTS = 60
"""Points drawn in one round before it is given up, times ``2^k`` for ``k`` polynomials under a
square root (a denominator vanishes at a random point with probability ``D/p``; a square root
of a polynomial's value exists with probability 1/2)."""

MAX_RADICALS = 12
"""Independent square roots an identity may hold (a prime where all are squares is sought
among about ``2^k`` primes)."""

THETA = "theta"
"""The angle of a canal surface's characteristic circles, the one name read through ``cos`` and ``sin``."""


class Redraw(ArithmeticError):
    """The point does not serve (a denominator is zero there, or a square root does not exist
    modulo ``p``): another point is drawn."""


@dataclass(frozen=True)
class Embedding:
    """A prime ``p`` and square roots modulo ``p`` of the coprime basis of the constant radicands
    (``-1`` included when ``I`` occurs), so that ``√q`` is the same residue wherever it occurs."""

    prime: int
    basis: tuple[int, ...]
    roots: Mapping[int, int]

    def rational(self, q: sympy.Rational | fmpq | int) -> int:
        """``q`` modulo ``p`` (:class:`Redraw` when its denominator is divisible by ``p``)."""
        numerator, denominator = _fraction(q)
        if denominator % self.prime == 0:
            raise Redraw("a denominator is divisible by the prime")
        return numerator * pow(denominator, -1, self.prime) % self.prime

    def sqrt_rational(self, q: sympy.Rational | fmpq | int) -> int:
        """``√q`` modulo ``p``, a product of the basis roots (``√(n/d) = √(n·d)/d``)."""
        numerator, denominator = _fraction(q)
        value = numerator * denominator
        root = self.rational(fmpq(1, denominator))
        if value < 0:
            root = root * self.roots[-1] % self.prime
            value = -value
        for b in self.basis:
            exponent = 0
            while value % b == 0:
                value //= b
                exponent += 1
            root = root * pow(b, exponent // 2, self.prime) % self.prime
            if exponent % 2:
                root = root * self.roots[b] % self.prime
        if value != 1:
            raise AnalysisError("a square root outside the radicands collected (internal error)")
        return root


def coprime_basis(numbers: Iterable[int]) -> tuple[int, ...]:
    """Pairwise coprime integers ``> 1``, none a perfect square, whose products (times squares)
    give every ``|n|`` of ``numbers``: gcd refinement (Bach, Driscoll and Shallit)."""
    basis: list[int] = []
    pending = [abs(n) for n in numbers if abs(n) > 1]
    while pending:
        n = pending.pop()
        if n == 1:
            continue
        for i, b in enumerate(basis):
            g = gcd(n, b)
            if g > 1:
                del basis[i]
                pending += [g, b // g, n // g]
                break
        else:
            root = isqrt(n)
            if root * root == n:
                pending.append(root)
            else:
                basis.append(n)
    return tuple(sorted(basis))


def embedding(radicands: Iterable[sympy.Rational | int], complex_unit: bool) -> Embedding:
    """A random prime of :data:`PRIME_BITS` bits where every basis element of ``radicands`` (and
    ``-1`` when ``complex_unit``) is a nonzero square, with a root of each."""
    cores: list[int] = []
    for q in radicands:
        numerator, denominator = _fraction(q)
        cores.append(numerator * denominator)
        complex_unit = complex_unit or numerator < 0
    basis = coprime_basis(cores)
    if len(basis) + complex_unit > MAX_RADICALS:
        raise AnalysisError(f"more than {MAX_RADICALS} independent square roots")
    for _ in range(64 << len(basis)):
        p = int(sympy.nextprime(secrets.randbits(PRIME_BITS) | 1 << (PRIME_BITS - 1)))
        if complex_unit and p % 4 != 1:
            continue
        if all(b % p and pow(b, (p - 1) // 2, p) == 1 for b in basis):
            roots = {b: int(sqrt_mod(b, p)) for b in basis}
            if complex_unit:
                roots[-1] = int(sqrt_mod(p - 1, p))
            return Embedding(p, basis, roots)
    raise AnalysisError("no prime found where the square roots exist (internal error)")


@dataclass
class Point:
    """Random residues modulo the embedding's prime for the names of a report's formulas, with
    the square roots of polynomial radicands chosen at that point (memoized, so one factor has
    one root everywhere) and the point ``(cos θ, sin θ)`` of the circle."""

    embedding: Embedding
    values: dict[str, int] = field(default_factory=dict)
    cos_sin: tuple[int, int] | None = None
    _roots: dict[Any, int] = field(default_factory=dict)
    base: Point | None = None
    """The point this one was derived from (:meth:`with_values`): it draws the other names."""
    _memo: dict[sympy.Basic, int] = field(default_factory=dict)
    _jets: dict[tuple[sympy.Basic, str], tuple[int, int]] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if self.cos_sin is None:
            p = self.embedding.prime
            m = secrets.randbelow(p)
            denominator = (1 + m * m) % p
            if denominator == 0:
                raise Redraw("the angle's point is at infinity")
            inverse = pow(denominator, -1, p)
            self.cos_sin = ((1 - m * m) * inverse % p, 2 * m * inverse % p)

    @property
    def prime(self) -> int:
        return self.embedding.prime

    def with_values(self, values: Mapping[str, int]) -> Point:
        """The same point with some variables set to other residues (the square roots chosen
        so far are kept: one radicand value, one root)."""
        return Point(self.embedding, dict(values), self.cos_sin, self._roots, self)

    def fresh(self) -> Point:
        """Another random point of the same embedding."""
        return Point(self.embedding)

    def of(self, name: str) -> int:
        """The residue of the variable ``name`` (drawn when first asked for)."""
        if name not in self.values:
            if self.base is not None:
                return self.base.of(name)
            self.values[name] = secrets.randbelow(self.prime)
        return self.values[name]

    def value(self, expr: sympy.Basic) -> int:
        """``expr`` (a formula as sympy's constructors built it) modulo ``p`` at this point."""
        if expr in self._memo:
            return self._memo[expr]
        result = self._value(expr)
        self._memo[expr] = result
        return result

    def _value(self, expr: sympy.Basic) -> int:
        p = self.prime
        if expr.is_Rational:
            return self.embedding.rational(sympy.Rational(expr))
        if expr is sympy.I:
            return self.embedding.roots[-1]
        if expr.is_Symbol:
            return self.of(str(expr))
        if expr.is_Add:
            return sum(self.value(a) for a in expr.args) % p
        if expr.is_Mul:
            total = 1
            for a in expr.args:
                total = total * self.value(a) % p
            return total
        if expr.is_Pow:
            base, exponent = expr.args
            if exponent.is_Integer:
                value = self.value(base)
                if exponent < 0:
                    if value == 0:
                        raise Redraw("a denominator vanishes at the point")
                    value = pow(value, -1, p)
                return pow(value, abs(int(exponent)), p)
            if exponent.is_Rational and exponent.q == 2:
                root = self.sqrt(base)
                return self.value(sympy.Pow(base, exponent - sympy.Rational(1, 2))) * root % p
        if isinstance(expr, (sympy.cos, sympy.sin)) and expr.args == (sympy.Symbol(THETA),):
            assert self.cos_sin is not None  # drawn with the point
            return self.cos_sin[0 if isinstance(expr, sympy.cos) else 1]
        raise AnalysisError(f"cannot evaluate {type(expr).__name__} modulo a prime")

    def jet(self, expr: sympy.Basic, name: str) -> tuple[int, int]:
        """``expr`` and its derivative in the variable ``name`` at this point, modulo ``p``: the
        expression evaluated in dual numbers ``a + b·ε`` (``ε² = 0``), no symbolic derivative."""
        key = (expr, name)
        if key in self._jets:
            return self._jets[key]
        result = self._jet(expr, name)
        self._jets[key] = result
        return result

    def _jet(self, expr: sympy.Basic, name: str) -> tuple[int, int]:
        p = self.prime
        if not expr.free_symbols or (str(name) not in {str(s) for s in expr.free_symbols}):
            return self.value(expr), 0
        if expr.is_Symbol:
            return self.value(expr), 1
        if expr.is_Add:
            parts = [self.jet(a, name) for a in expr.args]
            return sum(a for a, _ in parts) % p, sum(b for _, b in parts) % p
        if expr.is_Mul:
            value, slope = 1, 0
            for a in expr.args:
                u, du = self.jet(a, name)
                value, slope = value * u % p, (value * du + slope * u) % p
            return value, slope
        if expr.is_Pow:
            base, exponent = expr.args
            u, du = self.jet(base, name)
            value = self.value(expr)
            if u == 0:
                raise Redraw("a power's base vanishes at the point")
            # d(u^e) = e·u^e·du/u, for integer and half-integer e alike
            e = self.embedding.rational(sympy.Rational(exponent))
            return value, e * value % p * du % p * pow(u, -1, p) % p
        if isinstance(expr, (sympy.cos, sympy.sin)) and expr.args == (sympy.Symbol(THETA),):
            assert self.cos_sin is not None
            cos, sin = self.cos_sin
            return (cos, -sin % p) if isinstance(expr, sympy.cos) else (sin, cos)
        raise AnalysisError(f"cannot differentiate {type(expr).__name__} modulo a prime")

    def sqrt(self, radicand: sympy.Basic) -> int:
        """``√radicand`` modulo ``p``: a rational by the embedding; a polynomial in one variable
        by its irreducible factors, each with one root at this point; any other constant (a
        number of ``K``, as the orthonormal profile's ``√|a|²``) with one root of its own."""
        if radicand.is_Rational:
            return self.embedding.sqrt_rational(sympy.Rational(radicand))
        names = sorted(str(s) for s in radicand.free_symbols)
        if not names:
            return self.root(("constant", radicand), self.value(radicand))
        if len(names) != 1:
            raise AnalysisError("a square root of a polynomial in several variables")
        content, factors = radicand_factors(radicand, names[0])
        root = self.embedding.sqrt_rational(content)
        t = self.of(names[0])
        for coefficients, exponent in factors:
            value = _poly_value(coefficients, t, self.embedding)
            root = root * pow(value, exponent // 2, self.prime) % self.prime
            if exponent % 2:
                root = root * self.root((coefficients, value), value) % self.prime
        return root

    def root(self, key: Any, value: int) -> int:  # noqa: ANN401 - a hashable key
        """A square root of ``value`` modulo ``p``, the same for one ``key`` at this point
        (:class:`Redraw` when there is none)."""
        if key not in self._roots:
            p = self.prime
            if value == 0 or pow(value, (p - 1) // 2, p) != 1:
                raise Redraw("a square root does not exist modulo the prime at the point")
            self._roots[key] = int(sqrt_mod(value, p))
        return self._roots[key]


def radicand_factors(radicand: sympy.Basic, name: str) -> tuple[fmpq, list[tuple[tuple[fmpq, ...], int]]]:
    """The polynomial ``radicand`` in ``name`` as its content and irreducible factors over ``QQ``
    (each as its coefficients, lowest first, primitive with a positive leading coefficient)."""
    poly = sympy.Poly(sympy.expand(radicand), sympy.Symbol(name), domain="QQ")
    coefficients = [fmpq(int(c.p), int(c.q)) for c in reversed(poly.all_coeffs())]
    content, factors = fmpq_poly(coefficients).factor()
    return content, [(tuple(g.coeffs()), int(e)) for g, e in factors]


@dataclass(frozen=True)
class Radicands:
    """The square roots of some formulas: the rational radicands (``√q``, and the contents of
    the polynomial radicands), whether ``I`` occurs (what :func:`embedding` needs), and how many
    different irreducible polynomials are under a root (each must be a square at a point: about
    ``2^k`` points are drawn for one that serves)."""

    rationals: frozenset[sympy.Rational]
    complex_unit: bool
    polynomial_factors: int


def radicands_of(expressions: Iterable[sympy.Basic]) -> Radicands:
    """The :class:`Radicands` of ``expressions``."""
    found: set[sympy.Rational] = set()
    factors: set[Any] = set()
    complex_unit = False
    for expr in expressions:
        for power in expr.atoms(sympy.Pow):
            if power.exp.is_Rational and power.exp.q == 2:
                base = power.base
                if base.is_Rational:
                    found.add(sympy.Rational(base))
                elif len(base.free_symbols) == 1:
                    content, irreducible = radicand_factors(base, str(next(iter(base.free_symbols))))
                    found.add(sympy.Rational(int(content.p), int(content.q)))
                    factors |= {g for g, e in irreducible if e % 2}
        complex_unit = complex_unit or expr.has(sympy.I)
    return Radicands(frozenset(found), complex_unit, len(factors))


def _poly_value(coefficients: tuple[fmpq, ...], t: int, embedding: Embedding) -> int:
    p = embedding.prime
    total = 0
    for c in reversed(coefficients):
        total = (total * t + embedding.rational(c)) % p
    return total


def _fraction(q: sympy.Rational | fmpq | int) -> tuple[int, int]:
    if isinstance(q, int):
        return q, 1
    return int(q.p), int(q.q)
