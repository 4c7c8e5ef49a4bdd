"""The engine's exact strings decoded: numbers, vectors, polynomials and rational functions,
as sympy objects, floats and plain terms, each read once per process and never evaluated.

The engine reports every number and polynomial as a string in sympy's own output syntax
(``"3/5"``, ``"sqrt(2)/2"``, ``"(t**2 - 1)/(t**2 + 1)"``). This module owns reading them back:
an expanded polynomial over ``QQ`` with flint's reader :func:`.algebra.rationals.expanded_terms`,
everything else with the reader of machine-written formulas (:mod:`.expressions`, which also
reads Singular's answers). Nothing here goes through the parser of the user's text, and nothing
is ever ``eval``-ed or ``sympify``-ed (pasted text is untrusted, and so is everything derived
from it). It has no Qt: the exporters, the window, its worker process and the scene read here.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace
from functools import lru_cache

import numpy as np
import sympy
from flint import fmpq

from .algebra.rationals import Monomial, context, expanded_terms, flint_str, squarefree
from .errors import ExpressionError
from .expressions import SYMPY, read
from .results import Profile

Terms = list[tuple[tuple[int, ...], float]]
"""A polynomial as plain data for :mod:`sorgui.render`: ``[(exponents, coefficient), ...]``."""

__all__ = [
    "ExpressionError",
    "Terms",
    "float_vector",
    "polynomial_terms",
    "rational_function_terms",
    "read_expression",
    "read_number",
    "to_float",
]


@lru_cache(maxsize=4096)
def read_expression(text: str) -> sympy.Expr:
    """The engine string ``text`` as an exact sympy expression; every name other than ``sqrt``
    and ``I`` (the imaginary unit) is a variable. Raises :class:`ExpressionError`.

    Cached: the window, the scene and every export read the same numbers of one analysis (the
    axis, the frame, the parameterizations), and a sympy expression is immutable."""
    return read(text, SYMPY)


def read_number(text: str) -> sympy.Expr:
    """An exact engine number (``"3/5"``, ``"-sqrt(2)/2"``) as a sympy number."""
    return read_expression(text)


@lru_cache(maxsize=4096)
def to_float(text: str) -> float:
    """An exact engine number as the nearest ``float``."""
    return float(read_number(text).evalf(20))


def float_vector(triple: Sequence[str]) -> np.ndarray:
    """An exact engine triple ``("3/5", "-4/5", "0")`` as a ``float64`` array."""
    return np.array([to_float(c) for c in triple], dtype=np.float64)


def polynomial_terms(text: str, names: Sequence[str] = ("x", "y", "z")) -> Terms:
    """The engine polynomial ``text`` in ``names`` as float terms (exponents in that order);
    each exact coefficient is rounded once. An expanded polynomial over ``QQ`` (a degree-40
    surface prints 240 kB) is read by flint's reader in a fraction of a second, where sympy's
    expressions take seconds; one with algebraic coefficients is read as an expression.

    Coefficients beyond the range of ``float`` (a product of polynomials with 300-digit
    coefficients) are all divided by one power of two first: the zero set, which is what the
    floats are for, stays the same."""
    terms = expanded_terms(text, names)
    if terms is not None:
        return _floats(terms)
    symbols = [sympy.Symbol(n) for n in names]
    return _float_terms(read_expression(text), symbols)


def zero_set_profile(profile: Profile) -> Profile:
    """``profile`` with each of its polynomials replaced by its square-free part, in the same
    frame (docs/math.md §5, powers). The profile of a power ``g^k`` (a doubled face) changes no
    sign across its zero set, so neither a contour nor Newton's method finds its points there;
    the square-free part has the same zero set. ``profile`` itself when it is square-free."""
    polynomial, square = (_squarefree_text(text, ("x", "y")) for text in (profile.polynomial, profile.square))
    rational = _squarefree_text(profile.rational, ("s", "r"))
    rational_square = _squarefree_text(profile.rational_square, ("s", "w"))
    if (polynomial, square, rational, rational_square) == (
        profile.polynomial,
        profile.square,
        profile.rational,
        profile.rational_square,
    ):
        return profile
    return replace(profile, polynomial=polynomial, square=square, rational=rational, rational_square=rational_square)


def _squarefree_text(text: str, names: tuple[str, ...]) -> str:
    """The square-free part of the engine polynomial ``text`` (over ``QQ`` with flint, over a
    number field with sympy), printed; ``text`` itself when it is square-free."""
    terms = expanded_terms(text, names)
    if terms is not None:
        whole = context(names).from_dict(terms)
        if whole.is_zero() or whole.is_constant():
            return text
        part = squarefree(whole)
        return text if part.total_degree() == whole.total_degree() else flint_str(part, names)
    poly = sympy.Poly(read_expression(text), *sympy.symbols(names), extension=True)
    part = sympy.sqf_part(poly)
    return text if part.total_degree() == poly.total_degree() else str(part.as_expr())


def _floats(terms: dict[Monomial, fmpq | int]) -> Terms:
    """Exact terms as float terms, all divided by one power of two when beyond floats' range."""
    shift = max(0, max((_bits(c) for c in terms.values()), default=0) - MAX_FLOAT_BITS)
    return [(monomial, _rounded(c, shift)) for monomial, c in terms.items()]


MAX_FLOAT_BITS = 1000
"""The largest coefficient is brought below ``2^1000`` (floats reach ``2^1024``)."""

DRAWABLE_SPAN_BITS = 600
"""Coefficients whose sizes span more bits than this (about 10¹⁸⁰) put the real points, or the
values of ``f`` near them, beyond what floating-point arithmetic evaluates: ``x² + y² + z² − c``
with ``c`` of 5000 digits is a sphere of radius about 10²⁵⁰⁰."""


def beyond_floats(text: str, names: Sequence[str] = ("x", "y", "z")) -> str | None:
    """Why the zero set of the polynomial ``text`` cannot be drawn at all, in words (``None``
    when it can): the sizes of its nonzero coefficients span more than
    :data:`DRAWABLE_SPAN_BITS` (a sphere of radius 10²⁵⁰⁰), where no ball a user gives helps.
    Only an expanded polynomial over ``QQ`` is measured."""
    terms = expanded_terms(text, names) if text else None
    sizes = [_bits(c) for c in terms.values() if c] if terms else []
    span = max(sizes) - min(sizes) if sizes else 0
    if span <= DRAWABLE_SPAN_BITS:
        return None
    return (
        f"the surface cannot be drawn: its coefficients span about 10^{round(span * math.log10(2))}, "
        "more than floating-point arithmetic evaluates"
    )


def _bits(c: fmpq | int) -> int:
    """About ``log₂ |c|``."""
    return int(c).bit_length() if isinstance(c, int) else int(c.p).bit_length() - int(c.q).bit_length()


def _rounded(c: fmpq | int, shift: int = 0) -> float:
    """The nearest ``float`` to ``c / 2^shift`` (Python's division of integers rounds correctly)."""
    p, q = (c, 1) if isinstance(c, int) else (int(c.p), int(c.q))
    return p / (q << shift)


def rational_function_terms(text: str, names: Sequence[str]) -> tuple[Terms, Terms]:
    """A real rational function in ``names`` as float terms of its numerator and denominator."""
    expr = sympy.together(read_expression(text))
    numerator, denominator = sympy.fraction(expr)
    symbols = [sympy.Symbol(n) for n in names]
    return _float_terms(numerator, symbols), _float_terms(denominator, symbols)


def _float_terms(expr: sympy.Expr, symbols: list[sympy.Symbol]) -> Terms:
    poly = sympy.Poly(sympy.expand(expr), *symbols)
    terms = []
    for monom, coeff in poly.terms():
        value = complex(coeff.evalf(20))
        if value.imag != 0.0:
            raise ExpressionError("the rational function has non-real coefficients")
        terms.append((tuple(int(e) for e in monom), value.real))
    return terms
