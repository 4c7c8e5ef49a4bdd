"""The general parser: pasted text → the syntax tree → an exact polynomial ``f ∈ K[x, y, z]``,
``K = QQ(sqrt(n1), ...)``.

The user's text is never evaluated (no ``eval``, no ``sympify``). A tokenizer feeds a
recursive-descent parser that builds a small syntax tree; a checking pass bounds the degree, the
exponents and the size of every number and collects the square roots (so ``K`` is known); only
then is the tree evaluated: over ``QQ`` into python-flint's ``QQ[x, y, z]``, over a real field
``K`` into sympy's sparse ring ``K[x, y, z]``. Every limit (:mod:`.limits`) is checked before any
expansion, so hostile or mistyped input fails fast with a :class:`ParseError` that points at the
offending characters. The entry points are in :mod:`.parsing`, which reads most equations by the
fast path (:mod:`.expanded`) and loads this module only for the others.

Grammar, from the lowest to the highest precedence::

    equation := sum ['=' sum]                            -- lhs = rhs means lhs - rhs
    sum      := product (('+' | '-') product)*
    product  := factor (('*' | '/') factor | factor)*    -- juxtaposition is '*': 1/2x = x/2
    factor   := ('+' | '-')* atom superscript* ['^' factor]   -- -x^2 = -(x^2), 2^3^2 = 2^9
    atom     := number | x | y | z | 'sqrt' '(' sum ')' | '(' sum ')' | '\\frac' '(' sum ')' '(' sum ')'
              | 'pow' '(' sum ',' sum ')'                -- pow(a, n) = a^n
              | ('cos' | 'sin') '(' [k '*'] parameter ')' -- in a parametrization's component only

``==`` is ``=``, ``[ ]`` and ``{ }`` are parentheses, and a superscript is ``²`` or digits right
after a variable (Singular's ``x2``). A label (``f(x, y, z) =``, ``f :=``) and a final ``;`` are
skipped (:func:`.limits.equation_span`), a byte-order mark is a space, and LaTeX-style input
(``x^{2}``, ``\\cdot``, ``\\left( \\right)``, ``\\sqrt{2}``, ``\\frac{1}{2}``) reads as the plain syntax above.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator
from dataclasses import dataclass
from fractions import Fraction
from functools import lru_cache
from typing import TYPE_CHECKING, Any, NamedTuple, Protocol, TypeAlias, cast

from flint import fmpq, fmpq_mpoly, fmpz

from .algebra import rationals
from .errors import ParseError
from .limits import (
    COMMENT,
    MAX_BITS,
    MAX_DECIMAL_EXPONENT,
    MAX_DEGREE,
    MAX_DIGITS,
    MAX_EXPONENT,
    MAX_LENGTH,
    MAX_NESTING,
    MAX_RADICAND_DIGITS,
    MAX_RADICANDS,
    MAX_TOTAL_BITS,
    MAX_WORK,
    equation_span,
)

if TYPE_CHECKING:
    from sympy.polys.domains.domain import Domain
    from sympy.polys.rings import PolyElement

Rational: TypeAlias = int | Fraction  # exact; integer literals stay ints (faster)
_VARIABLES = ("x", "y", "z")
_VARIABLE_INDEX = {name: i for i, name in enumerate(_VARIABLES)}
_OPERATORS = {
    "**": "^",
    "==": "=",
    "−": "-",
    "–": "-",
    "·": "*",
    "⋅": "*",
    "×": "*",
    "∙": "*",
    "•": "*",
    "÷": "/",
    "∗": "*",
    "{": "(",
    "}": ")",
    "[": "(",
    "]": ")",
    "\\cdot": "*",
    "\\times": "*",
}
_SUPERSCRIPTS = str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹⁻", "0123456789-")
TOKEN = re.compile(
    rf"(?P<space>[\s\ufeff\u200b-\u200d\u2060]+|{COMMENT}"
    r"|\\(?:(?:left|right|quad|qquad|[Bb]igg?[lr]?)(?![A-Za-z])|[,;:! \\]))"
    r"|(?P<num>(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:(?:[eEdD]|\*\^)[-+−]?[0-9]+)?)"
    r"|(?P<name>[A-Za-z]+)"
    r"|(?P<sup>⁻?[⁰¹²³⁴⁵⁶⁷⁸⁹]+)"
    r"|(?P<op>\*\*|==|[-+*/^()=−–·⋅×∗∙•÷{}\[\]]|\\(?:cdot|times)(?![A-Za-z]))"
    r"|(?P<latex>\\(?:sqrt|frac|cos|sin)(?![A-Za-z]))"
    r"|(?P<bad>.)",
    re.DOTALL,
)
_NUMBER = re.compile(r"([0-9]*)(?:\.([0-9]*))?(?:(?:[eEdD]|\*\^)([-+−]?[0-9]+))?")
"""A number: its exponent as C, Fortran (``1.5D-3``) or Mathematica (``1.5*^-3``) prints it."""
_IMPLICIT = frozenset({"var", "sqrt", "frac", "(", "cos", "sin"})  # tokens that start an implicit product


def checked(text: str) -> tuple[Node, Evaluator, bool]:
    """The syntax tree of ``text`` after pass 1 (every limit checked, the radicands known),
    its evaluator, and whether a variable was written."""
    if len(text) > MAX_LENGTH:
        raise ParseError(f"the input is too long (more than {MAX_LENGTH:,} characters)", 0, len(text))
    tree, saw_variable = parsed_tree(text)
    evaluator = Evaluator()
    try:
        evaluator.check(tree)
    except RecursionError:
        raise ParseError("the expression is nested too deeply", 0, len(text)) from None
    return tree, evaluator, saw_variable


@lru_cache(maxsize=1)
def parsed_tree(text: str) -> tuple[Node, bool]:
    """The syntax tree of ``text`` and whether a variable was written, tokenised once for the
    last text read: one analysis reads its text up to three times (the recognition-only path,
    the general one, the digits of rounded input, docs/math.md §8). The tree is immutable; an
    error is raised again each time."""
    try:
        parser = Parser(text)
        return parser.equation(), parser.saw_variable
    except RecursionError:
        raise ParseError("the expression is nested too deeply", 0, len(text)) from None


def evaluate(text: str, evaluator: Evaluator, tree: Node, ring: _Ring, saw_variable: bool) -> Any:
    """Pass 2 in ``ring``; a constant result is an error."""
    try:
        polynomial = evaluator.evaluate(tree, ring)
    except RecursionError:
        raise ParseError("the expression is nested too deeply", 0, len(text)) from None
    if ring.is_constant(polynomial):
        message = (
            "the equation is constant: its variables cancel"
            if saw_variable
            else "the equation has no variables (use x, y and z)"
        )
        raise ParseError(message, 0, len(text))
    return polynomial


def syntax_tree(text: str) -> Node:
    """The syntax tree of ``text``, unchecked and unevaluated: what :mod:`.rounded.precision` reads to
    learn how many digits each number was printed with (docs/math.md §8), the tree the parse built."""
    return parsed_tree(text)[0]


# --- tokens ------------------------------------------------------------------------------


class Token(NamedTuple):
    """A token: ``kind`` is an operator (``+ - * / ^ ( ) =``), num, var, sqrt, sup or end."""

    kind: str
    start: int
    end: int
    value: Any = None  # int or Fraction (num), variable index (var), int exponent (sup)


def token_stream(
    text: str, span: tuple[int, int] | None = None, variables: tuple[str, ...] = _VARIABLES
) -> Iterator[Token]:
    """The tokens of ``text``, lazily, so that the first error in reading order is reported.

    Only :func:`.limits.equation_span` is read: a label (``f(x,y,z) = g`` is the equation
    ``g = 0``), a final ``;`` and LaTeX's ``$ $`` are skipped, and comments (``#``, ``//``,
    ``%`` to the end of the line) are spaces. ``{ }`` and ``[ ]`` are parentheses,
    ``\\cdot`` and ``\\times`` are ``*``, ``\\sqrt`` is ``sqrt``, and ``\\left``, ``\\right``, ``\\bigl``,
    LaTeX spacing and line breaks (``\\\\``) are ignored; Mathematica's ``==`` is ``=``. Digits
    written right after x, y or z are its exponent, as Singular prints them (``x2y`` is
    ``x^2*y``); after a parameter they are refused (``t1`` is no power of ``t``).
    ``span`` (characters ``start:end``, no label skipped) and ``variables`` (the names of the
    variables, by index) read one component of a parametrization in its parameters
    (:mod:`.parametric_parsing`).
    """
    if span is None:
        span = equation_span(text)
    index = _VARIABLE_INDEX if variables == _VARIABLES else {name: i for i, name in enumerate(variables)}
    after_variable = -1  # where the last of x, y, z ends (a parameter's digits are no exponent: t1, t2)
    for match in TOKEN.finditer(text, *span):
        kind, word = match.lastgroup, match.group()
        start, end = match.span()
        if kind == "op":
            yield Token(_OPERATORS.get(word, word), start, end)
        elif kind == "num" and start == after_variable and word.isdigit():
            yield _exponent(word, start, end)  # Singular's x2
        elif kind == "num":
            value = int(word) if len(word) < 500 and word.isdigit() else _number(text, start, end)
            yield Token("num", start, end, value)
        elif kind == "name":
            after_variable = end if word not in ("sqrt", "pow", "Sqrt") and variables == _VARIABLES else -1
            if word in index:  # fast path for a single variable
                yield Token("var", start, end, index[word])
            else:
                yield from _name(word, start, variables)
        elif kind == "latex" and word[1:] in TRIGONOMETRIC:
            yield from _name(word[1:], start + 1, variables)  # \\cos u: in a parametrization only
        elif kind == "latex":
            yield Token(word[1:], start, end)  # sqrt or frac
        elif kind == "sup":
            yield _exponent(word.translate(_SUPERSCRIPTS), start, end)
        elif kind == "bad" and word == ",":
            yield Token(",", start, end)  # between the arguments of pow; the parser refuses any other
        elif kind == "bad":
            raise ParseError(f"unexpected character {word!r}", start)
    yield Token("end", span[1], span[1])


def _exponent(digits: str, start: int, end: int) -> Token:
    """An exponent written without ``^``: Unicode's ``²`` (``10⁻³``), Singular's ``x2``."""
    if len(digits.lstrip("-")) > 6:
        raise ParseError("the exponent is too large", start, end)
    return Token("sup", start, end, int(digits))


def _name(word: str, start: int, variables: tuple[str, ...] = _VARIABLES) -> Iterator[Token]:
    """``sqrt``, ``pow`` (C's and Python's ``pow(a, n)``), or a run of x, y, z (``xyz`` is
    ``x*y*z``; of one-letter ``variables``), in lower or in upper case (a CAD system's ``X``);
    any other name is an error."""
    if word in ("sqrt", "pow", "Sqrt"):
        yield Token(word.lower(), start, start + len(word))  # Mathematica's Sqrt[2] too
    elif word in TRIGONOMETRIC and variables != _VARIABLES:
        yield Token(word.lower(), start, start + len(word))  # cos(u) in a parametrization's component
    elif set(word.lower()) <= set(variables) and (word.islower() or word.isupper()):
        for i, letter in enumerate(word.lower()):
            yield Token("var", start + i, start + i + 1, variables.index(letter))
    else:
        names = ", ".join(variables)
        raise ParseError(
            f"unknown name '{word}' (the variables are {names}; the functions are sqrt and pow)",
            start,
            start + len(word),
        )


def number_parts(text: str, start: int, end: int) -> tuple[str, str | None, str | None]:
    """The digits of a number token ``text[start:end]``: before the point, after it (``None``
    without a point) and the exponent (``None`` without one; a PDF's ``−`` read as ``-``)."""
    match = _NUMBER.fullmatch(text, start, end)
    assert match is not None  # every number token is a literal that _NUMBER matches
    whole, fraction, exponent = match.groups()
    return whole, fraction, None if exponent is None else exponent.replace("−", "-")


def _number(text: str, start: int, end: int) -> Rational:
    """The exact value of a decimal literal such as ``12``, ``0.25``, ``.5`` or ``2.5E+2``."""
    whole, fraction, exponent = number_parts(text, start, end)
    digits = whole + (fraction or "")
    if len(digits) > MAX_DIGITS:
        raise ParseError(f"the number has more than {MAX_DIGITS:,} digits", start, end)
    scale = -len(fraction or "")
    if exponent is not None:
        if len(exponent.lstrip("+-").lstrip("0")) > 6 or abs(int(exponent)) > MAX_DECIMAL_EXPONENT:
            raise ParseError(f"the decimal exponent is too large (the limit is ±{MAX_DECIMAL_EXPONENT})", start, end)
        scale += int(exponent)
    value = 0
    for i in range(0, len(digits), 500):  # chunks: independent of sys.set_int_max_str_digits
        chunk = digits[i : i + 500]
        value = value * 10 ** len(chunk) + int(chunk)
    return Fraction(value * 10**scale) if scale >= 0 else Fraction(value, 10**-scale)


# --- the syntax tree ---------------------------------------------------------------------


@dataclass(frozen=True, slots=True, eq=False)
class _Span:
    """Characters ``start:end`` of the original text; identity equality, so nodes key caches."""

    start: int
    end: int


@dataclass(frozen=True, slots=True, eq=False)
class Num(_Span):
    value: Rational


@dataclass(frozen=True, slots=True, eq=False)
class Var(_Span):
    index: int  # 0, 1, 2 for x, y, z


@dataclass(frozen=True, slots=True, eq=False)
class Neg(_Span):
    arg: Node


@dataclass(frozen=True, slots=True, eq=False)
class Sum(_Span):
    terms: tuple[Node, ...]  # n-ary, so long pasted sums evaluate in linear time


@dataclass(frozen=True, slots=True, eq=False)
class Product(_Span):
    factors: tuple[Node, ...]  # the first factor is never a Reciprocal


@dataclass(frozen=True, slots=True, eq=False)
class Reciprocal(_Span):
    arg: Node  # '/ arg' inside a Product; the span starts at the '/'


@dataclass(frozen=True, slots=True, eq=False)
class Power(_Span):
    base: Node
    exponent: Node


@dataclass(frozen=True, slots=True, eq=False)
class Sqrt(_Span):
    arg: Node


@dataclass(frozen=True, slots=True, eq=False)
class Trig(_Span):
    """``cos(k·u)`` or ``sin(k·u)`` of a parameter ``u`` (its index) of a parametrization."""

    function: str  # "cos" or "sin"
    multiple: int
    index: int


Node: TypeAlias = Num | Var | Neg | Sum | Product | Reciprocal | Power | Sqrt | Trig

TRIGONOMETRIC = frozenset({"cos", "sin", "Cos", "Sin"})
"""The functions a parametrization's component may take of a parameter (Mathematica's too)."""
MAX_MULTIPLE = 12
"""The largest ``k`` of ``cos(k·u)``: degree ``2k`` in ``tan(u/2)``."""


# --- the parser --------------------------------------------------------------------------


class Parser:
    """Recursive descent over the grammar of the module docstring (two frames per nesting)."""

    def __init__(self, text: str, tokens: Iterator[Token] | None = None) -> None:
        self._text = text
        self._tokens = token_stream(text) if tokens is None else tokens
        self._tok = next(self._tokens)
        self._prev = self._tok
        self._open = 0  # parentheses currently open
        self.saw_variable = False

    def _advance(self) -> Token:
        self._prev, self._tok = self._tok, next(self._tokens)
        return self._prev

    def _show(self, tok: Token) -> str:
        return self._text[tok.start : tok.end]

    def equation(self) -> Node:
        if self._tok.kind == "end":
            raise ParseError("the input is empty", 0, len(self._text))
        tree = self._sum(0)
        if self._tok.kind == "=":
            self._advance()
            rhs = self._sum(0)
            if self._tok.kind == "=":
                raise ParseError("only one '=' is allowed", self._tok.start, self._tok.end)
            tree = Sum(tree.start, rhs.end, (tree, Neg(rhs.start, rhs.end, rhs)))
        if self._tok.kind == ")":
            raise ParseError("unmatched ')'", self._tok.start, self._tok.end)
        if self._tok.kind != "end":
            tok = self._tok
            raise ParseError(f"unexpected '{self._show(tok)}'", tok.start, tok.end)
        return tree

    def _sum(self, depth: int) -> Node:
        """``sum`` with ``product`` inlined, which keeps deep nesting within Python's stack."""
        start = self._tok.start
        terms: list[Node] = []
        negative = False
        while True:
            term_start = self._tok.start
            factors = [self._factor(depth)]
            while True:
                tok = self._tok
                if tok.kind == "*":
                    self._advance()
                    factors.append(self._factor(depth))
                elif tok.kind == "/":
                    self._advance()
                    denominator = self._factor(depth)
                    factors.append(Reciprocal(tok.start, self._prev.end, denominator))
                elif tok.kind in _IMPLICIT:
                    if "\n" in self._text[self._prev.end : tok.start]:
                        raise ParseError(
                            "a new line starts here without an operator, which would multiply the two lines: "
                            "end a line with '+', '-' or '*' to go on, or give one equation at a time",
                            tok.start,
                            tok.end,
                        )
                    factors.append(self._factor(depth))
                elif tok.kind == "num":
                    raise ParseError(
                        f"missing operator before '{self._show(tok)}' (write '*' or '^')", tok.start, tok.end
                    )
                else:
                    break
            end = self._prev.end
            term = factors[0] if len(factors) == 1 else Product(term_start, end, tuple(factors))
            terms.append(Neg(term_start, end, term) if negative else term)
            if self._tok.kind not in ("+", "-"):
                break
            negative = self._advance().kind == "-"
        return terms[0] if len(terms) == 1 else Sum(start, self._prev.end, tuple(terms))

    def _factor(self, depth: int) -> Node:
        if depth > MAX_NESTING:
            raise ParseError(
                f"the expression is nested too deeply (the limit is {MAX_NESTING})", self._tok.start, self._tok.end
            )
        start = self._tok.start
        negative = False
        while self._tok.kind in ("+", "-"):
            negative ^= self._advance().kind == "-"
        tok = self._tok
        if tok.kind == "num":
            node: Node = Num(tok.start, tok.end, self._advance().value)
        elif tok.kind == "var":
            self.saw_variable = True
            node = Var(tok.start, tok.end, self._advance().value)
        elif tok.kind == "sqrt":
            self._advance()
            if self._tok.kind != "(":
                raise ParseError("'sqrt' must be followed by '('", tok.start, tok.end)
            arg = self._group(depth)
            node = Sqrt(tok.start, self._prev.end, arg)
        elif tok.kind == "(":
            node = self._group(depth)
        elif tok.kind == "frac":
            node = self._fraction(depth)
        elif tok.kind == "pow":
            node = self._pow(depth)
        elif tok.kind in ("cos", "sin"):
            node = self._trig(depth)
        else:
            raise self._missing_operand(tok)
        while self._tok.kind == "sup":
            sup = self._advance()
            node = Power(tok.start, sup.end, node, Num(sup.start, sup.end, sup.value))
        if self._tok.kind == "^":
            self._advance()
            exponent = self._factor(depth + 1)
            node = Power(tok.start, self._prev.end, node, exponent)
        return Neg(start, self._prev.end, node) if negative else node

    def _fraction(self, depth: int) -> Node:
        """LaTeX's ``\\frac{a}{b}``, read as ``(a)/(b)``."""
        frac = self._advance()
        parts = []
        for _ in range(2):
            if self._tok.kind != "(":
                raise ParseError("'\\frac' must be followed by '{numerator}{denominator}'", frac.start, self._tok.end)
            parts.append(self._group(depth))
        numerator, denominator = parts
        return Product(
            frac.start, self._prev.end, (numerator, Reciprocal(denominator.start, denominator.end, denominator))
        )

    def _pow(self, depth: int) -> Node:
        """``pow(a, n)``, read as ``(a)^(n)``."""
        name = self._advance()
        if self._tok.kind != "(":
            raise ParseError("'pow' must be followed by '(base, exponent)'", name.start, name.end)
        opening = self._advance()
        self._open += 1
        arguments = [self._sum(depth + 1)]
        if self._tok.kind == ",":
            self._advance()
            arguments.append(self._sum(depth + 1))
        tok = self._tok
        if tok.kind == "end":
            raise ParseError("unmatched '('", opening.start, opening.end)
        if tok.kind != ")" or len(arguments) != 2:
            raise ParseError("'pow' takes two arguments: pow(base, exponent)", name.start, tok.end)
        self._advance()
        self._open -= 1
        return Power(name.start, self._prev.end, arguments[0], arguments[1])

    def _trig(self, depth: int) -> Node:
        """``cos(k·u)`` or ``sin(k·u)``: a whole multiple ``k`` (at most :data:`MAX_MULTIPLE`) of
        one parameter, ``cos(u)``, ``sin(2*u)``, ``cos(-u)``, or ``cos u`` (docs/math.md §13)."""
        name = self._advance()
        if self._tok.kind == "var":  # cos u, LaTeX's \\cos u: the one parameter that follows
            parameter = self._advance()
            arg: Node = Var(parameter.start, parameter.end, parameter.value)
        elif self._tok.kind == "(":
            arg = self._group(depth)
        else:
            raise ParseError(f"'{self._show(name)}' must be followed by '(' and a parameter", name.start, name.end)
        sign, inner = 1, arg
        while isinstance(inner, Neg):
            sign, inner = -sign, inner.arg
        multiple, index = 1, None
        if isinstance(inner, Var):
            index = inner.index
        elif isinstance(inner, Product) and len(inner.factors) == 2:
            first, second = inner.factors
            number, variable = (first, second) if isinstance(first, Num) else (second, first)
            if isinstance(number, Num) and isinstance(variable, Var) and isinstance(number.value, int):
                multiple, index = number.value, variable.index
        if index is None or not 1 <= multiple <= MAX_MULTIPLE:
            raise ParseError(
                f"{self._show(name)}(…) takes a whole multiple of one parameter, from 1 to {MAX_MULTIPLE} times"
                " (cos(u), sin(2*u)): the map is then rational in tan(u/2)",
                arg.start,
                arg.end,
            )
        end = self._prev.end
        function = self._show(name).lower()
        node = Trig(name.start, end, function, multiple, index)
        return Neg(name.start, end, node) if sign < 0 and function == "sin" else node

    def _group(self, depth: int) -> Node:
        """``'(' sum ')'``; the error for a missing ')' points at the unmatched '('."""
        opening = self._advance()
        self._open += 1
        inner = self._sum(depth + 1)
        tok = self._tok
        if tok.kind == "end":
            raise ParseError("unmatched '('", opening.start, opening.end)
        if tok.kind != ")":
            raise ParseError(f"expected ')' before '{self._show(tok)}'", tok.start, tok.end)
        self._advance()
        self._open -= 1
        return inner

    def _missing_operand(self, tok: Token) -> ParseError:
        if tok.kind == "end":
            prev = self._prev
            return ParseError(f"something is missing after '{self._show(prev)}'", prev.start, prev.end)
        if tok.kind == ")":
            message = "expected an expression before ')'" if self._open else "unmatched ')'"
            return ParseError(message, tok.start, tok.end)
        return ParseError(f"unexpected '{self._show(tok)}': expected a number, a variable or '('", tok.start, tok.end)


# --- checking and evaluating the tree ----------------------------------------------------

_NOT_RATIONAL = {
    "exponent": ("an exponent must be a constant number", "an exponent must be rational"),
    "radicand": (
        "the square root of a non-constant expression is not allowed: only square roots of numbers (sqrt(2))",
        "nested square roots are not supported",
    ),
}


def _bits(q: Rational) -> int:
    return max(q.numerator.bit_length(), q.denominator.bit_length())


def _monomials(degree: int) -> int:
    """The monomials of total degree at most ``degree`` in three variables."""
    return math.comb(degree + 3, 3)


def _show(n: int) -> str:
    """``n`` for a message; huge numbers cannot (and need not) be printed in full."""
    return f"{n:,}" if n < 10**15 else f"about 2^{n.bit_length() - 1}"


class Evaluator:
    """Pass 1 (:meth:`check`): bounds and radicands over QQ; pass 2 (:meth:`evaluate`): K[x,y,z].
    ``fractions``: the tree is a rational function (a parametrization's component), whose
    non-constant parts may have negative integer powers (``s^-1``); an equation's may not."""

    def __init__(self, *, fractions: bool = False) -> None:
        self.fractions = fractions
        self.radicands: set[int] = set()
        self._rationals: dict[Node, Fraction] = {}
        self._exponents: dict[Power, Rational] = {}
        self._surds: dict[Node, tuple[Fraction, int]] = {}  # c*sqrt(m) for Sqrt and k/2-powers
        self._work = 0

    # pass 1 ---------------------------------------------------------------------------

    def check(self, node: Node) -> tuple[int, int]:
        """Upper bounds ``(total degree, bits of the coefficients)``, without expanding anything.

        deg(a+b) = max, deg(a*b) = sum, deg(a^n) = n*deg(a), deg(a/c) = deg(a).
        """
        degree, bits, _ = self._bounds(node)
        return degree, bits

    def _bounds(self, node: Node) -> tuple[int, int, int]:
        """:meth:`check`'s bounds and the number of terms of the expanded ``node``: a sum has at
        most the sum of its terms', a product the product of its factors', ``a^n`` the number of
        products of ``n`` of ``a``'s terms, each at most the monomials of its degree."""
        match node:
            case Num():
                return 0, _bits(node.value), 1
            case Var():
                return 1, 0, 1  # its coefficient 1 adds no bits to a product (a·z has the bits of a)
            case Neg():
                return self._bounds(node.arg)
            case Reciprocal():
                return 0, self._bounds(node.arg)[1], 1
            case Sqrt():
                c, m = self._surd(node)
                return 0, _bits(c) + m.bit_length(), 1
            case Sum():  # plain loops: a comprehension would cost a stack frame per level
                degree = bits = terms = 0
                for term in node.terms:
                    d, b, t = self._bounds(term)
                    degree, bits, terms = max(degree, d), max(bits, b), terms + t
                return degree, bits + (len(node.terms) - 1).bit_length(), min(terms, _monomials(degree))
            case Product():
                degree = bits = 0
                terms = 1
                for factor in node.factors:
                    d, b, t = self._bounds(factor)
                    degree, bits = degree + d, bits + b
                    terms = min(terms * t, _monomials(degree))
                return self._within_limits(node, degree, bits, terms)
            case Power():
                return self._check_power(node)
            case Trig():
                return 2 * node.multiple, 2 * node.multiple, _monomials(2 * node.multiple)
        raise TypeError(node)

    def _check_power(self, node: Power) -> tuple[int, int, int]:
        n = self._exponent(node)
        degree, bits, terms = self._bounds(node.base)
        if degree > 0:
            if n.denominator != 1 or (n < 0 and not self.fractions):
                raise ParseError(
                    "a non-constant expression can only be raised to "
                    + ("an integer power" if self.fractions else "a non-negative integer power"),
                    node.exponent.start,
                    node.exponent.end,
                )
            k = abs(int(n))
            if degree * k > MAX_DEGREE:  # before the count of its terms, which can be huge
                self._within_limits(node, degree * k, 0, 1)
            products = min(math.comb(terms + k - 1, k), _monomials(degree * k))
            return self._within_limits(node, degree * k, bits * k, products)
        if n.denominator == 1:
            self._check_exponent(node, n)
            return self._within_limits(node, 0, bits * abs(int(n)), 1)
        c, m = self._surd(node)
        return 0, _bits(c) + m.bit_length(), 1

    @staticmethod
    def _within_limits(node: Node, degree: int, bits: int, terms: int) -> tuple[int, int, int]:
        if degree > MAX_DEGREE:
            raise ParseError(
                f"the degree is too high: this part has degree up to {_show(degree)}, the limit is {MAX_DEGREE}",
                node.start,
                node.end,
            )
        if bits > MAX_BITS:
            raise ParseError(
                f"the numbers are too large: this part needs up to {_show(bits)} bits, the limit is {MAX_BITS:,}",
                node.start,
                node.end,
            )
        if terms * bits > MAX_TOTAL_BITS:
            raise ParseError(
                f"the expanded polynomial is too large: this part has up to {terms:,} terms of up to {bits:,} "
                f"bits, about {_show(terms * bits // 8_000_000)} MB; the limit is {MAX_TOTAL_BITS // 8_000_000} MB",
                node.start,
                node.end,
            )
        return degree, bits, terms

    @staticmethod
    def _check_exponent(node: Power, n: Rational) -> None:
        if not -MAX_EXPONENT <= n <= MAX_EXPONENT:
            raise ParseError(
                f"the exponent is too large (the limit is {MAX_EXPONENT})", node.exponent.start, node.exponent.end
            )

    def _exponent(self, node: Power) -> Rational:
        exponent = node.exponent
        if isinstance(exponent, Num) and isinstance(exponent.value, int):
            self._exponents[node] = exponent.value  # fast path: x^2
        elif node not in self._exponents:
            self._exponents[node] = self._rational(exponent, "exponent")
        return self._exponents[node]

    def _rational(self, node: Node, role: str) -> Fraction:
        """The value of a constant, variable-free, rational subexpression (exponents, radicands)."""
        if node in self._rationals:
            return self._rationals[node]
        not_constant, irrational = _NOT_RATIONAL[role]
        match node:
            case Num():
                value = Fraction(node.value)
            case Var() | Trig():
                raise ParseError(not_constant, node.start, node.end)
            case Neg():
                value = -self._rational(node.arg, role)
            case Sum():
                value = Fraction(0)
                for term in node.terms:
                    value += self._rational(term, role)
                    self._within_limits(node, 0, _bits(value), 1)
            case Product():
                value = Fraction(1)
                for factor in node.factors:
                    value *= self._rational(factor, role)
                    self._within_limits(node, 0, _bits(value), 1)
            case Reciprocal():
                denominator = self._rational(node.arg, role)
                if denominator == 0:
                    raise ParseError("division by zero", node.start, node.end)
                value = 1 / denominator
            case Sqrt():
                value, m = self._surd(node)
                if m != 1:
                    raise ParseError(irrational, node.start, node.end)
            case Power():
                n = self._exponent(node)
                if n.denominator != 1:
                    value, m = self._surd(node)
                    if m != 1:
                        raise ParseError(irrational, node.start, node.end)
                else:
                    self._check_exponent(node, n)
                    base = self._rational(node.base, role)
                    if base == 0 and n < 0:
                        raise ParseError("division by zero", node.start, node.end)
                    self._within_limits(node, 0, abs(int(n)) * _bits(base), 1)
                    value = base ** int(n)
        self._rationals[node] = value
        return value

    def _surd(self, node: Sqrt | Power) -> tuple[Fraction, int]:
        """``sqrt(q)`` or ``q^(k/2)`` for a rational ``q >= 0`` as ``c*sqrt(m)``, m square-free."""
        if node in self._surds:
            return self._surds[node]
        if isinstance(node, Sqrt):
            q, k = self._rational(node.arg, "radicand"), 1
        else:
            n = self._exponent(node)
            if n.denominator != 2:
                raise ParseError(
                    "only square roots are supported: the exponent must be an integer or a half-integer",
                    node.exponent.start,
                    node.exponent.end,
                )
            self._check_exponent(node, n)
            q, k = self._rational(node.base, "radicand"), n.numerator
        if q < 0:
            raise ParseError("the square root of a negative number is not real", node.start, node.end)
        if q == 0:
            if k < 0:
                raise ParseError("division by zero", node.start, node.end)
            return self._surds.setdefault(node, (Fraction(0), 1))
        self._within_limits(node, 0, abs(k) * _bits(q), 1)
        c, m = _square_free_part(q, node)
        if m > 1:
            self.radicands.add(m)
            if len(self.radicands) > MAX_RADICANDS:
                raise ParseError(
                    f"too many different square roots (the limit is {MAX_RADICANDS})", node.start, node.end
                )
        return self._surds.setdefault(node, (c * q ** ((k - 1) // 2), m))

    # pass 2 ---------------------------------------------------------------------------

    def evaluate(self, node: Node, ring: _Ring) -> Any:
        """The value of the checked tree in ``ring`` (``QQ[x, y, z]`` or ``K[x, y, z]``)."""
        self._ring = ring
        return self._value(node)

    def _value(self, node: Node) -> Any:
        ring = self._ring
        match node:
            case Num():
                return ring.ground(self._constant(node.value))
            case Var():
                return ring.gens[node.index]
            case Neg():
                return -self._value(node.arg)
            case Sqrt():
                return ring.ground(self._surd_value(node))
            case Sum():
                return self._sum(node)
            case Product():
                result = self._value(node.factors[0])
                for factor in node.factors[1:]:
                    if isinstance(factor, Reciprocal):
                        result = ring.scale(result, self._inverse(factor))
                    else:
                        value = self._value(factor)
                        self._charge(node, len(result) * len(value))
                        result = result * value
                return result
            case Power():
                return self._power_value(node)
        raise TypeError(node)

    def _power_value(self, node: Power) -> Any:
        ring = self._ring
        if node in self._surds:
            return ring.ground(self._surd_value(node))
        n = int(self._exponents[node])
        base = self._value(node.base)
        if ring.is_constant(base):
            return ring.ground(self._constant_power(node, ring.constant_term(base), n))
        return self._power(node, base, n)

    def _sum(self, node: Sum) -> Any:
        """Accumulate all terms into one dict: linear, where repeated ``p + q`` is quadratic."""
        total: dict[tuple[int, ...], Any] = {}
        for term in node.terms:
            negative = False
            if isinstance(term, Neg):
                negative, term = True, term.arg
            monomial = self._monomial(term)
            items = (monomial,) if monomial is not None else self._ring.terms(self._value(term))
            for monom, coeff in items:
                old = total.get(monom)
                if old is None:
                    total[monom] = -coeff if negative else coeff
                else:
                    total[monom] = old - coeff if negative else old + coeff
        return self._ring.from_terms({monom: coeff for monom, coeff in total.items() if coeff})

    def _monomial(self, node: Node) -> tuple[tuple[int, ...], Any] | None:
        """``(exponents, coefficient)`` when ``node`` is a product of numbers and powers of
        variables (the terms of a pasted expanded polynomial), else ``None``: a fast path."""
        exponents = [0, 0, 0]
        coeff = self._ring.one
        for factor in node.factors if isinstance(node, Product) else (node,):
            if isinstance(factor, Var):
                exponents[factor.index] += 1
            elif isinstance(factor, Num):
                coeff = coeff * self._constant(factor.value)
            elif isinstance(factor, Neg) and isinstance(factor.arg, Num):
                coeff = -coeff * self._constant(factor.arg.value)
            elif isinstance(factor, Reciprocal) and isinstance(factor.arg, Num) and factor.arg.value:
                coeff = self._ring.quo(coeff, self._constant(factor.arg.value))
            elif (
                isinstance(factor, Power) and isinstance(factor.base, Var) and isinstance(factor.exponent, Num)
            ):  # a non-negative integer: checked
                exponents[factor.base.index] += int(factor.exponent.value)
            else:
                return None
        return tuple(exponents), coeff

    def _constant(self, q: Rational) -> Any:
        return self._ring.rational(q)

    def _inverse(self, node: Reciprocal) -> Any:
        ring = self._ring
        value = self._value(node.arg)
        if not ring.is_constant(value):
            raise ParseError("division by a non-constant expression", node.start, node.end)
        if not value:
            raise ParseError("division by zero", node.start, node.end)
        return ring.quo(ring.one, ring.constant_term(value))

    def _surd_value(self, node: Node) -> Any:
        c, m = self._surds[node]
        value = self._constant(c)
        return value * self._ring.square_root(m) if m > 1 else value

    def _constant_power(self, node: Power, c: Any, n: int) -> Any:
        """``c^n`` in K by repeated squaring (sympy's ANP power expands before reducing)."""
        ring = self._ring
        if n < 0:
            if not c:
                raise ParseError("division by zero", node.start, node.end)
            c, n = ring.quo(ring.one, c), -n
        result = ring.one
        while n:
            if n & 1:
                result = result * c
            c, n = c * c, n >> 1
        return result

    def _power(self, node: Power, base: Any, n: int) -> Any:
        """``base^n`` for a non-constant base and ``0 <= n <= MAX_DEGREE``, within MAX_WORK."""
        if n == 0:
            return self._ring.ground(self._ring.one)
        if len(base) <= 5:  # a monomial power or the multinomial formula
            degree = max(sum(monom) for monom, _ in self._ring.terms(base))
            terms = min(math.comb(n + len(base) - 1, n), math.comb(n * degree + 3, 3))
            self._charge(node, terms * len(base))
            return base**n
        product = base
        for _ in range(n - 1):  # repeated multiplication: cheaper than squaring for dense bases
            self._charge(node, len(product) * len(base))
            product = product * base
        return product

    def _charge(self, node: Node, products: int) -> None:
        self._work += products * self._ring.cost
        if self._work > MAX_WORK:
            raise ParseError(
                f"the expression is too large to expand (it needs more than {MAX_WORK:,} coefficient multiplications)",
                node.start,
                node.end,
            )


class _Ring(Protocol):
    """The arithmetic of pass 2: polynomials in x, y, z over the field, and its constants."""

    cost: int  # rational multiplications per coefficient product
    one: Any
    gens: tuple[Any, ...]

    def rational(self, q: Rational) -> Any:
        """The rational ``q`` in the field."""
        ...

    def square_root(self, m: int) -> Any:
        """``sqrt(m)`` in the field (``m`` one of its radicands)."""
        ...

    def quo(self, a: Any, b: Any) -> Any:
        """``a / b`` in the field."""
        ...

    def ground(self, c: Any) -> Any:
        """The constant polynomial ``c``."""
        ...

    def is_constant(self, p: Any) -> bool: ...

    def constant_term(self, p: Any) -> Any: ...

    def terms(self, p: Any) -> Iterator[tuple[tuple[int, ...], Any]]: ...

    def from_terms(self, terms: dict[tuple[int, ...], Any]) -> Any: ...

    def scale(self, p: Any, c: Any) -> Any:
        """``c·p`` for a constant ``c`` of the field."""
        ...


class FlintRationals:
    """``QQ[x, y, z]`` in python-flint (no sympy)."""

    cost = 1

    def __init__(self) -> None:
        self._context = rationals.context(("x", "y", "z"))
        self.gens = self._context.gens()
        self.one = fmpq(1)

    def square_root(self, m: int) -> fmpq:
        raise ValueError(f"sqrt({m}) is not in QQ: an equation with square roots is evaluated over its field K")

    def rational(self, q: Rational) -> fmpq:
        return fmpq(q.numerator, q.denominator)

    def quo(self, a: fmpq, b: fmpq) -> fmpq:
        return a / b

    def ground(self, c: Any) -> fmpq_mpoly:
        return self._context.constant(c)

    def is_constant(self, p: fmpq_mpoly) -> bool:
        return p.is_constant()

    def constant_term(self, p: fmpq_mpoly) -> fmpq:
        return p[(0, 0, 0)]

    def terms(self, p: fmpq_mpoly) -> Iterator[tuple[tuple[int, ...], Any]]:
        return iter(rationals.terms(p))

    def from_terms(self, terms: dict[tuple[int, ...], Any]) -> fmpq_mpoly:
        return self._context.from_dict(terms)

    def scale(self, p: fmpq_mpoly, c: fmpq) -> fmpq_mpoly:
        return p * c


class SympyField:
    """``K[x, y, z]`` in sympy's sparse polynomials, ``K`` a real field with square roots."""

    cost = 8  # an ANP product costs ~8 rational ones

    def __init__(self, ring: Any, radicands: tuple[int, ...]) -> None:
        self._ring = ring
        self._field = ring.domain
        self._roots = square_roots(self._field, radicands)
        self.gens = ring.gens
        self.one = self._field.one

    def rational(self, q: Rational) -> Any:
        from .algebra.polys import from_rational

        return from_rational(self._field, q)

    def square_root(self, m: int) -> Any:
        return self._roots[m]

    def quo(self, a: Any, b: Any) -> Any:
        return self._field.quo(a, b)

    def ground(self, c: Any) -> PolyElement:
        return self._ring.ground_new(c)

    def is_constant(self, p: PolyElement) -> bool:
        return cast(bool, p.is_ground)

    def constant_term(self, p: PolyElement) -> Any:
        return p.get(self._ring.zero_monom, self._field.zero)

    def terms(self, p: PolyElement) -> Iterator[tuple[tuple[int, ...], Any]]:
        return iter(p.items())

    def from_terms(self, terms: dict[tuple[int, ...], Any]) -> PolyElement:
        return self._ring.from_dict(terms)

    def scale(self, p: PolyElement, c: Any) -> PolyElement:
        return p.mul_ground(c)


def _square_free_part(q: Fraction, node: Node) -> tuple[Fraction, int]:
    """``sqrt(q) = c*sqrt(m)`` with ``m`` square-free: ``sqrt(a/b) = sqrt(a*b)/b``."""
    n = q.numerator * q.denominator
    root = math.isqrt(n)
    if root * root == n:
        return Fraction(root, q.denominator), 1
    if n >= 10**MAX_RADICAND_DIGITS:
        raise ParseError(
            f"the number under the square root is too large to factor (more than {MAX_RADICAND_DIGITS} digits)",
            node.start,
            node.end,
        )
    square, free = 1, 1
    for p, e in fmpz(n).factor():  # flint: far faster than sympy.factorint at 40+ digits
        square *= int(p) ** (e // 2)
        free *= int(p) ** (e % 2)
    return Fraction(square, q.denominator), free


@lru_cache(maxsize=64)
def square_roots(field: Domain, radicands: tuple[int, ...]) -> dict[int, Any]:
    """``sqrt(m)`` as an element of ``field = number_field(radicands)``, for each radicand.

    ``primitive_element(..., ex=True)`` writes each generator in the primitive element, which
    is much faster than ``field.from_sympy`` for three or more roots; each result is checked.
    """
    import sympy
    from sympy.polys.domains import QQ
    from sympy.polys.numberfields.subfield import primitive_element

    if not radicands:
        return {}
    roots = [sympy.sqrt(m) for m in radicands]
    _, coeffs, reps = primitive_element(roots, ex=True)
    same = sum(c * r for c, r in zip(coeffs, roots)) == field.ext.root
    values = {}
    for m, root, rep in zip(radicands, roots, reps):
        value = field.new([QQ.convert(c) for c in rep]) if same else None
        if value is None or value * value != field.convert(m):
            value = field.from_sympy(root)
        values[m] = value
    return values
