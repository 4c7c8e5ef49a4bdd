"""The engine's exact strings as sympy expressions, floats and plain terms, without ``eval``.

The engine reports every number and polynomial as a string in sympy's own output syntax
(``"3/5"``, ``"sqrt(2)/2"``, ``"(t**2 - 1)/(t**2 + 1)"``). They are read back here:
polynomials through the project's parser :func:`~sorgui.engine.parsing.parse_polynomial` (which
also gives the exact field ``K``), and numbers and rational functions of the parameterizations
through the engine's reader of machine-written formulas (:mod:`sorgui.engine.expressions`, which
also reads Singular's answers); it builds sympy objects with their constructors (never
``sympify``: pasted text is untrusted, and so is everything derived from it). It has no Qt:
the exporters, the GUI and its analysis worker process all read through it.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from functools import lru_cache

import numpy as np
import sympy

from sorgui.engine.errors import ExpressionError
from sorgui.engine.expressions import SYMPY, read
from sorgui.engine.parsing import parse_polynomial

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


def _renamed(text: str, names: Sequence[str]) -> str:
    """``text`` with the variables ``names`` renamed to ``x, y, z`` (at once) for the parser."""
    mapping = dict(zip(names, ("x", "y", "z")))
    pattern = re.compile(r"\b(" + "|".join(re.escape(n) for n in mapping) + r")\b")
    return pattern.sub(lambda match: mapping[match.group(1)], text)


def polynomial_terms(text: str, names: Sequence[str] = ("x", "y", "z")) -> Terms:
    """The engine polynomial ``text`` in ``names`` as float terms (exponents in that order).

    Read with the project's parser; each exact coefficient in ``K`` is rounded once.
    """
    parsed = parse_polynomial(_renamed(text, names))
    K = parsed.field
    nvars = len(names)
    return [
        (tuple(int(e) for e in monom[:nvars]), float(K.to_sympy(c).evalf(20))) for monom, c in parsed.polynomial.items()
    ]


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
