"""The one reader of machine-written expressions: Singular's answers and the engine's own strings.

Two kinds of text come back into sorgui as formulas: Singular's ``short=0`` output (numbers,
the ring's variables and parameter, ``+ - * / ^`` and parentheses), and the engine's result
strings in sympy's output syntax (``"3/5"``, ``"-sqrt(2)/2"``, ``"(t**2 - 1)/(t**2 + 1)"``)
that the exporters and the window read back. Both are read here by one recursive-descent
reader that builds sympy objects with their constructors; nothing is ever evaluated
(``eval``, ``sympify``), since the text derives from pasted input. The user's own input goes
through :mod:`.parsing` instead, which also bounds degrees and sizes before expanding. Both
read an expanded polynomial over ``QQ`` with :func:`.algebra.rationals.expanded_terms` first.

Grammar (``-x^2`` is ``-(x^2)`` and powers are right-associative, as in sympy)::

    expr  := term (('+' | '-') term)*
    term  := unary (('*' | '/') unary)*
    unary := ('-' | '+') unary | power
    power := atom [('^' | '**') unary]
    atom  := number | name | function '(' expr ')' | '(' expr ')'
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

import sympy

from .algebra import sympy_fixes
from .errors import ExpressionError

sympy_fixes.install()  # the exports read the engine's roots of large integers here

MAX_EXPONENT = 10_000
"""The largest ``|n|`` accepted in ``base^n``: a larger power is never a sensible answer."""

MAX_NUMBER_BITS = 1_000_000
"""A power of a number is refused when it would exceed this many bits (``(2^10000)^10000``):
each exponent is bounded, but a power of a power would still grow without end."""

_TOKEN = re.compile(r"\s*(?:(\d+(?:\.\d+)?)|([A-Za-z_]\w*)|(\*\*|[-+*/^()]))")


@dataclass(frozen=True)
class Syntax:
    """What a reader accepts: the power operators, decimals, functions, constants, and the
    names (``names`` ``None``: every other identifier is a :class:`sympy.Symbol`)."""

    powers: tuple[str, ...]
    decimals: bool
    rational_exponents: bool
    functions: Mapping[str, Callable[[sympy.Expr], sympy.Expr]] = field(default_factory=dict)
    constants: Mapping[str, sympy.Expr] = field(default_factory=dict)
    names: Mapping[str, sympy.Expr] | None = None


SYMPY = Syntax(
    powers=("**", "^"), decimals=True, rational_exponents=True, functions={"sqrt": sympy.sqrt}, constants={"I": sympy.I}
)
"""sympy's output syntax, the form of every exact string in the engine's results."""


def singular_syntax(names: Mapping[str, sympy.Expr]) -> Syntax:
    """Singular's ``short=0`` output over the ring whose variables and parameters are ``names``."""
    return Syntax(powers=("^",), decimals=False, rational_exponents=False, names=names)


def read(text: str, syntax: Syntax = SYMPY) -> sympy.Expr:
    """The exact sympy expression written in ``text``; :class:`ExpressionError` otherwise."""
    try:
        return _Reader(text, syntax).read()
    except RecursionError:
        raise ExpressionError("it is nested too deeply") from None


def _bits(number: sympy.Rational) -> int:
    return int(number.p).bit_length() + int(number.q).bit_length()


class _Reader:
    """Recursive descent over the grammar of the module docstring."""

    def __init__(self, text: str, syntax: Syntax) -> None:
        self.syntax = syntax
        self.tokens = self._tokenize(text.strip())
        self.position = 0

    def _tokenize(self, text: str) -> list[str]:
        tokens, index = [], 0
        while index < len(text):
            match = _TOKEN.match(text, index)
            if match is None or match.end() == index:
                raise ExpressionError(f"unexpected character {text[index]!r}")
            token = next(group for group in match.groups() if group is not None)
            if "." in token and not self.syntax.decimals:
                raise ExpressionError(f"unexpected decimal number {token!r}")
            if token in ("**", "^") and token not in self.syntax.powers:
                raise ExpressionError(f"unexpected {token!r}")
            tokens.append(token)
            index = match.end()
        if not tokens:
            raise ExpressionError("it is empty")
        return tokens

    def _peek(self) -> str | None:
        return self.tokens[self.position] if self.position < len(self.tokens) else None

    def _take(self, expected: str | None = None) -> str:
        token = self._peek()
        if token is None:
            raise ExpressionError(f"it ends before {expected or 'the expression is complete'}")
        if expected is not None and token != expected:
            raise ExpressionError(f"expected {expected!r}, found {token!r}")
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
        return sympy.Add(*terms)  # one n-ary sum: long sums stay linear

    def _term(self) -> sympy.Expr:
        factors = [self._unary()]
        while self._peek() in ("*", "/"):
            operator = self._take()
            right = self._unary()
            if operator == "/" and right == 0:
                raise ExpressionError("division by zero")
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
        if self._peek() in self.syntax.powers:
            self._take()
            exponent = self._unary()
            allowed = exponent.is_Rational if self.syntax.rational_exponents else exponent.is_Integer
            if not allowed or abs(exponent) > MAX_EXPONENT:
                kind = "a rational" if self.syntax.rational_exponents else "an integer"
                raise ExpressionError(f"an exponent must be {kind} number of size at most {MAX_EXPONENT}")
            if base == 0 and exponent < 0:
                raise ExpressionError("division by zero")
            if base.is_Rational and exponent.is_Integer and _bits(base) * abs(int(exponent)) > MAX_NUMBER_BITS:
                raise ExpressionError(f"a power of a number larger than {MAX_NUMBER_BITS:,} bits")
            return sympy.Pow(base, exponent)
        return base

    def _atom(self) -> sympy.Expr:
        token = self._take()
        if token == "(":
            value = self._expression()
            self._take(")")
            return value
        if token[0].isdigit():
            return sympy.Rational(token)
        syntax = self.syntax
        if token in syntax.functions:
            if self._peek() != "(":
                raise ExpressionError(f"{token} needs an argument in parentheses")
            self._take("(")
            argument = self._expression()
            self._take(")")
            return syntax.functions[token](argument)
        if token in syntax.constants:
            return syntax.constants[token]
        if token[0].isalpha() or token[0] == "_":
            if syntax.names is None:
                return sympy.Symbol(token)
            if token in syntax.names:
                return syntax.names[token]
            raise ExpressionError(f"unknown name {token!r}")
        raise ExpressionError(f"unexpected {token!r}")
