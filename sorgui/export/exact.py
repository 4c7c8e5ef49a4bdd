"""The engine's exact strings as sympy expressions, floats and plain terms, without ``eval``.

The engine reports every number and polynomial as a string in sympy's own output syntax
(``"3/5"``, ``"sqrt(2)/2"``, ``"(t**2 - 1)/(t**2 + 1)"``). They are read back here:
polynomials through the project's parser :func:`~sorgui.engine.parsing.parse_polynomial` (which
also gives the exact field ``K``), and numbers and rational functions of the parameterizations
through a small recursive-descent reader of that output syntax, which builds sympy objects with
their constructors (never ``sympify``: pasted text is untrusted, and so is everything derived
from it). It has no Qt: the exporters, the GUI and its analysis worker process all read through it.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

import numpy as np
import sympy

from sorgui.engine.parsing import parse_polynomial

Terms = list[tuple[tuple[int, ...], float]]
"""A polynomial as plain data for :mod:`sorgui.render`: ``[(exponents, coefficient), ...]``."""

_TOKEN = re.compile(r"\s*(?:(\d+(?:\.\d+)?)|([A-Za-z_]\w*)|(\*\*|[-+*/^()]))")
_FUNCTIONS = {"sqrt": sympy.sqrt}
_CONSTANTS = {"I": sympy.I}


class ExpressionError(ValueError):
    """An engine string that is not in sympy's arithmetic output syntax."""


class _Reader:
    """Recursive descent over ``expr := term (± term)*``, ``term := unary ((*|/) unary)*``,
    ``unary := (-|+) unary | power``, ``power := atom (** unary)?``, ``atom := number | name |
    sqrt(expr) | (expr)``; ``^`` is read as ``**``, and ``-x**2`` is ``-(x**2)`` as in sympy."""

    def __init__(self, text: str) -> None:
        self.tokens = self._tokenize(text)
        self.position = 0

    @staticmethod
    def _tokenize(text: str) -> list[str]:
        tokens, index = [], 0
        text = text.strip()
        while index < len(text):
            match = _TOKEN.match(text, index)
            if match is None or match.end() == index:
                raise ExpressionError(f"unexpected character {text[index]!r} in {text!r}")
            tokens.append(next(group for group in match.groups() if group is not None))
            index = match.end()
        return tokens

    def _peek(self) -> str | None:
        return self.tokens[self.position] if self.position < len(self.tokens) else None

    def _take(self, expected: str | None = None) -> str:
        token = self._peek()
        if token is None or (expected is not None and token != expected):
            raise ExpressionError(f"expected {expected or 'more input'}, found {token!r}")
        self.position += 1
        return token

    def read(self) -> sympy.Expr:
        value = self._expression()
        if self._peek() is not None:
            raise ExpressionError(f"unexpected {self._peek()!r}")
        return value

    def _expression(self) -> sympy.Expr:
        terms = [self._term()]
        while self._peek() in ("+", "-"):
            sign = self._take()
            right = self._term()
            terms.append(right if sign == "+" else -right)
        return sympy.Add(*terms)  # one n-ary sum: pasted sums are long

    def _term(self) -> sympy.Expr:
        factors = [self._unary()]
        while self._peek() in ("*", "/"):
            operator = self._take()
            right = self._unary()
            factors.append(right if operator == "*" else sympy.Pow(right, -1))
        return sympy.Mul(*factors)

    def _unary(self) -> sympy.Expr:
        if self._peek() in ("-", "+"):
            sign = self._take()
            value = self._unary()
            return -value if sign == "-" else value
        return self._power()

    def _power(self) -> sympy.Expr:
        base = self._atom()
        if self._peek() in ("**", "^"):
            self._take()
            return sympy.Pow(base, self._unary())  # right-associative; -x**2 is -(x**2)
        return base

    def _atom(self) -> sympy.Expr:
        token = self._take()
        if token == "(":
            value = self._expression()
            self._take(")")
            return value
        if token[0].isdigit():
            return sympy.Rational(token)
        if token in _FUNCTIONS and self._peek() == "(":
            self._take("(")
            argument = self._expression()
            self._take(")")
            return _FUNCTIONS[token](argument)
        if token in _FUNCTIONS:
            raise ExpressionError(f"{token} needs an argument in parentheses")
        if token in _CONSTANTS:
            return _CONSTANTS[token]
        if token[0].isalpha():
            return sympy.Symbol(token)
        raise ExpressionError(f"unexpected {token!r}")


def read_expression(text: str) -> sympy.Expr:
    """The engine string ``text`` as an exact sympy expression; every name other than ``sqrt``
    and ``I`` (the imaginary unit) is a variable."""
    return _Reader(text).read()


def read_number(text: str) -> sympy.Expr:
    """An exact engine number (``"3/5"``, ``"-sqrt(2)/2"``) as a sympy number."""
    return read_expression(text)


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
        (tuple(int(e) for e in monom[:nvars]), float(K.to_sympy(c).evalf(20)))
        for monom, c in parsed.polynomial.items()
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
