"""The engine's exact strings as mathematics people read: Unicode text at once, and LaTeX.

The results pane shows every formula the moment it is known, as plain Unicode math
(``x⁴ + 2x²y² − 6x³/5``, ``√2/2``, ``(t² − 1)/(t² + 1)``), and replaces it by the typeset
picture when that is ready (:mod:`sorgui.session.typesetting`). Both forms are printed here from
one reading of the string, with the standard library only: no sympy (whose import costs the
window a second of start-up), no evaluation of any kind. The strings are sympy's output syntax,
as the engine writes them (:mod:`sorgui.engine.expressions` has the grammar): numbers, names,
``sqrt(…)``, ``I``, ``+ - * / **`` and parentheses.

Numbers with many digits are shown short, with the exact value on Copy and on "exact digits":

* ``exact`` mode (exact input): an integer of more than :data:`LONG_DIGITS` digits is
  ``7.914…×10³⁸``, and a coefficient ``p/q`` with such parts is its value in decimals;
* ``decimal`` mode (rounded input, whose nearest exact surface has 40-digit rationals):
  every rational coefficient is shown in decimals, :data:`DECIMAL_DIGITS` significant digits,
  as the input was typed (``1.2x³``, ``4.979476549…x²``); ``…`` marks a decimal that is not
  the whole value.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from fractions import Fraction
from typing import Literal, TypeAlias

Mode: TypeAlias = Literal["exact", "decimal"]

LONG_DIGITS = 15
"""An integer with more digits than this is shown short."""

SHORT_DIGITS = 4
"""Significant digits of a long number shown short (``7.914…×10³⁸``)."""

DECIMAL_DIGITS = 10
"""Significant digits of a coefficient of rounded input's formulas, as CAD systems print them."""

MAX_LENGTH = 200_000
"""Longer strings are not read (they are shown as they are, elided by the pane)."""

SUPERSCRIPTS = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")
SUBSCRIPTS = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")

_TOKEN = re.compile(r"\s*(?:(\d+(?:\.\d+)?)|([A-Za-z_]\w*)|(\*\*|[-+*/^(),]))")


class Unreadable(ValueError):
    """The string is not in the engine's syntax (it is then shown as it is)."""


# --- the tree -------------------------------------------------------------------------------


@dataclass(frozen=True)
class Number:
    value: Fraction
    digits: str
    """As written (``"0.25"`` for a decimal), for the exact form."""


@dataclass(frozen=True)
class Name:
    name: str


@dataclass(frozen=True)
class Call:
    function: str
    argument: Node


@dataclass(frozen=True)
class Power:
    base: Node
    exponent: Node


@dataclass(frozen=True)
class Product:
    """``sign · numerators / denominators``, the numeric factors kept apart as ``coefficient``."""

    negative: bool
    coefficient: Fraction
    numerators: tuple[Node, ...]
    denominators: tuple[Node, ...]
    written: tuple[tuple[str, Node], ...]
    """The factors in the order written, with ``"*"`` or ``"/"``, for the exact form."""


@dataclass(frozen=True)
class Sum:
    terms: tuple[Node, ...]


Node: TypeAlias = Number | Name | Call | Power | Product | Sum


def read(text: str) -> Node:
    """The tree of an engine string; :class:`Unreadable` if it is not one."""
    if len(text) > MAX_LENGTH:
        raise Unreadable("too long to read")
    tokens = _tokens(text)
    reader = _Reader(tokens)
    node = reader.sum()
    if reader.at < len(tokens):
        raise Unreadable(f"unexpected {tokens[reader.at]!r}")
    return node


def _tokens(text: str) -> list[str]:
    out, at = [], 0
    text = text.rstrip()
    while at < len(text):
        match = _TOKEN.match(text, at)
        if match is None:
            raise Unreadable(f"unexpected character {text[at]!r}")
        out.append(match.group(match.lastindex or 0))
        at = match.end()
    return out


class _Reader:
    """Recursive descent: ``sum := product (± product)*``, ``product := unary ((*|/) unary)*``,
    ``unary := - unary | power``, ``power := atom [** unary]``."""

    def __init__(self, tokens: list[str]) -> None:
        self.tokens, self.at = tokens, 0

    def peek(self) -> str | None:
        return self.tokens[self.at] if self.at < len(self.tokens) else None

    def take(self) -> str:
        token = self.peek()
        if token is None:
            raise Unreadable("it ends too early")
        self.at += 1
        return token

    def sum(self) -> Node:
        terms = [self.product()]
        while self.peek() in ("+", "-"):
            sign = self.take()
            term = self.product()
            terms.append(_negated(term) if sign == "-" else term)
        return terms[0] if len(terms) == 1 else Sum(tuple(terms))

    def product(self) -> Node:
        negative = False
        while self.peek() in ("-", "+"):
            negative ^= self.take() == "-"
        written: list[tuple[str, Node]] = [("*", self.unary())]
        while self.peek() in ("*", "/"):
            written.append((self.take(), self.unary()))
        if len(written) == 1 and not negative:
            return written[0][1]
        return _product(negative, written)

    def unary(self) -> Node:
        if self.peek() == "-":
            self.take()
            return _negated(self.unary())
        return self.power()

    def power(self) -> Node:
        base = self.atom()
        if self.peek() in ("**", "^"):
            self.take()
            return Power(base, self.unary())
        return base

    def atom(self) -> Node:
        token = self.take()
        if token[0].isdigit():
            return Number(Fraction(token), token)
        if token == "(":
            inner = self.sum()
            if self.take() != ")":
                raise Unreadable("a parenthesis is not closed")
            return inner
        if token[0].isalpha() or token[0] == "_":
            if self.peek() == "(":
                self.take()
                argument = self.sum()
                if self.take() != ")":
                    raise Unreadable("a parenthesis is not closed")
                return Call(token, argument)
            return Name(token)
        raise Unreadable(f"unexpected {token!r}")


def _product(negative: bool, written: list[tuple[str, Node]]) -> Product:
    coefficient = Fraction(1)
    numerators: list[Node] = []
    denominators: list[Node] = []
    for operator, factor in written:
        if isinstance(factor, Product):  # a negated factor: its sign and its parts join this one
            negative ^= factor.negative
            inner = factor.coefficient
            coefficient = coefficient * inner if operator == "*" else coefficient / inner
            side, other = (numerators, denominators) if operator == "*" else (denominators, numerators)
            side.extend(factor.numerators)
            other.extend(factor.denominators)
        elif isinstance(factor, Number):
            coefficient = coefficient * factor.value if operator == "*" else coefficient / factor.value
        else:
            (numerators if operator == "*" else denominators).append(factor)
    return Product(negative, coefficient, tuple(numerators), tuple(denominators), tuple(written))


def _negated(node: Node) -> Node:
    if isinstance(node, Product):
        return Product(not node.negative, node.coefficient, node.numerators, node.denominators, node.written)
    if isinstance(node, Sum):  # -(a + b) as written: a product with one factor
        return Product(True, Fraction(1), (node,), (), (("*", node),))
    return _product(True, [("*", node)])


def evaluate(node: Node) -> float:
    """The value of a tree of numbers and square roots (``ValueError`` for a name or another
    function): for a point of a line that is shown in decimals."""
    match node:
        case Number(value):
            return float(value)
        case Call("sqrt", argument):
            return math.sqrt(evaluate(argument))
        case Power(base, exponent):
            return float(evaluate(base) ** evaluate(exponent))
        case Product(negative, coefficient, numerators, denominators):
            total = float(coefficient)
            for factor in numerators:
                total *= evaluate(factor)
            for factor in denominators:
                total /= evaluate(factor)
            return -total if negative else total
        case Sum(terms):
            return math.fsum(evaluate(term) for term in terms)
    raise ValueError(f"not a number: {node}")


# --- numbers --------------------------------------------------------------------------------


def _digits(n: int) -> int:
    return len(str(abs(n)))


def is_long(value: Fraction) -> bool:
    """Whether a number has a part of more than :data:`LONG_DIGITS` digits."""
    return _digits(value.numerator) > LONG_DIGITS or _digits(value.denominator) > LONG_DIGITS


def decimal_digits(value: Fraction, digits: int) -> tuple[str, int, bool]:
    """``(mantissa digits, exponent of the first, exact)``: ``value ≠ 0`` rounded to ``digits``
    significant digits, exactly (integer arithmetic); ``exact`` when nothing was dropped."""
    p, q = abs(value.numerator), value.denominator
    exponent = _digits(p) - _digits(q)
    if p * 10 ** max(0, -exponent) < q * 10 ** max(0, exponent):
        exponent -= 1
    shift = digits - 1 - exponent
    scaled = Fraction(p * 10 ** max(shift, 0), q * 10 ** max(-shift, 0))
    mantissa = (scaled.numerator * 2 + scaled.denominator) // (2 * scaled.denominator)
    exact = scaled.denominator == 1
    if _digits(mantissa) > digits:  # 9.99… rounded up to 10.0…
        mantissa //= 10
        exponent += 1
    text = str(mantissa).rstrip("0") if exact else str(mantissa)
    return text or "0", exponent, exact


@dataclass(frozen=True)
class Decimal:
    """A number in decimals: sign, the digits before and after the point (or a mantissa and a
    power of ten), and whether digits were dropped."""

    negative: bool
    mantissa: str
    exponent: int
    exact: bool
    scientific: bool

    def unicode(self) -> str:
        return self._text("…", lambda e: "×10" + str(e).translate(SUPERSCRIPTS))

    def latex(self) -> str:
        return self._text(r"\ldots", lambda e: rf"\times 10^{{{e}}}")

    def _text(self, ellipsis: str, power: object) -> str:
        more = "" if self.exact else ellipsis
        if self.scientific:
            head, tail = self.mantissa[0], self.mantissa[1:]
            body = head + ("." + tail if tail else "") + more
            assert callable(power)
            return body + str(power(self.exponent))
        if self.exponent >= 0:
            whole = self.mantissa[: self.exponent + 1].ljust(self.exponent + 1, "0")
            frac = self.mantissa[self.exponent + 1 :]
        else:
            whole, frac = "0", "0" * (-self.exponent - 1) + self.mantissa
        return whole + ("." + frac if frac else "") + more


def to_decimal(value: Fraction, digits: int) -> Decimal:
    """``value`` with ``digits`` significant digits: plain for ``10⁻⁴ ≤ |value| < 10¹⁰``,
    else as a power of ten."""
    if value == 0:
        return Decimal(False, "0", 0, True, False)
    mantissa, exponent, exact = decimal_digits(value, digits)
    if value.denominator == 1 and _digits(value.numerator) <= digits:
        return Decimal(value < 0, str(abs(value.numerator)), _digits(value.numerator) - 1, True, False)
    return Decimal(value < 0, mantissa, exponent, exact, not -4 <= exponent < 10)


# --- printing -------------------------------------------------------------------------------


@dataclass(frozen=True)
class Printed:
    """A formula printed: Unicode, LaTeX, and its top-level terms in LaTeX with their signs
    (where a long one may be wrapped); ``shortened`` when some digits are not shown."""

    unicode: str
    latex: str
    pieces: tuple[str, ...]
    shortened: bool


class _Printer:
    """Prints one tree in one mode, as Unicode or LaTeX (``latex``); ``shorten=False`` prints
    every digit (what Copy gives)."""

    def __init__(self, mode: Mode, latex: bool, shorten: bool = True, fold: bool = False) -> None:
        self.mode, self.latex, self.shorten, self.fold = mode, latex, shorten, fold
        self.shortened = False

    # numbers

    def decimals(self, value: Fraction) -> bool:
        """Whether a coefficient is shown as one number in decimals (not ``p`` and ``/q`` apart)."""
        return self.shorten and (self.mode == "decimal" and value.denominator != 1 or is_long(value))

    def number(self, value: Fraction) -> str:
        """A nonnegative coefficient ``value`` (its sign is printed by the caller)."""
        if self.decimals(value):
            digits = DECIMAL_DIGITS if self.mode == "decimal" else SHORT_DIGITS
            shown = to_decimal(value, digits)
            self.shortened = self.shortened or not shown.exact
            return shown.latex() if self.latex else shown.unicode()
        if value.denominator == 1:
            return str(value.numerator)
        if self.latex and not self.fold:
            return rf"\frac{{{value.numerator}}}{{{value.denominator}}}"
        return f"{value.numerator}/{value.denominator}"

    # nodes

    def node(self, node: Node) -> str:
        match node:
            case Number(value):
                return self.number(value)
            case Name(name):
                return self.name(name)
            case Call(function, argument):
                return self.call(function, argument)
            case Power(base, exponent):
                return self.power(base, exponent)
            case Product():
                return self.minus + self.product(node) if node.negative else self.product(node)
            case Sum(terms):
                return "".join(self.term(term, index) for index, term in enumerate(terms))
        raise AssertionError(node)

    @property
    def minus(self) -> str:
        return "-" if self.latex else "−"

    def term(self, node: Node, index: int) -> str:
        """A term of a sum with its sign: ``x``, ``−x`` first, `` + x``, `` − x`` after."""
        negative = isinstance(node, Product) and node.negative
        body = self.product(node) if isinstance(node, Product) else self.node(node)
        if index == 0:
            return self.minus + body if negative else body
        return (f" {self.minus} " if negative else " + ") + body

    def name(self, name: str) -> str:
        if name == "I":
            return "i"
        match = re.fullmatch(r"([A-Za-z])(\d+)", name)
        if match:  # m1 → m₁
            letter, digits = match.groups()
            return f"{letter}_{{{digits}}}" if self.latex else letter + digits.translate(SUBSCRIPTS)
        return name

    def call(self, function: str, argument: Node) -> str:
        inner = self.node(argument)
        if function == "sqrt":
            if self.latex:
                return rf"\sqrt{{{inner}}}"
            return "√" + (inner if isinstance(argument, (Number, Name)) else f"({inner})")
        if self.latex:
            return rf"\operatorname{{{function}}}\left({inner}\right)"
        return f"{function}({inner})"

    def power(self, base: Node, exponent: Node) -> str:
        shown = self.node(base)
        bare = isinstance(base, Name) or isinstance(base, Number) and base.value.denominator == 1
        if not bare:
            shown = self.parenthesised(shown)
        integer = _integer(exponent)
        if integer == 1:
            return self.node(base)
        if self.latex:
            return f"{shown}^{{{integer if integer is not None else self.node(exponent)}}}"
        if integer is not None:
            return shown + str(integer).translate(SUPERSCRIPTS)
        return f"{shown}^({self.node(exponent)})"

    def parenthesised(self, text: str) -> str:
        return rf"\left({text}\right)" if self.latex else f"({text})"

    def factor(self, node: Node) -> str:
        """A factor of a product: a sum (or a negated product) in parentheses."""
        text = self.node(node)
        if isinstance(node, (Sum, Product)):
            return self.parenthesised(text)
        return text

    def joined(self, factors: list[Node], coefficient: str = "") -> str:
        """Factors side by side: ``2x²y``, ``2√2·x``, ``m₁·m₂``, ``2(t + 1)``; in LaTeX with spaces."""
        parts = ([coefficient] if coefficient else []) + [self.factor(f) for f in factors]
        scaled = "×" in coefficient or r"\times" in coefficient  # 7.914…×10³⁸·x, not 10³⁸x
        kinds = ([("other" if scaled else "number")] if coefficient else []) + [_kind(f) for f in factors]
        out = parts[0] if parts else ""
        for before, kind, part in zip(kinds, kinds[1:], parts[1:]):
            if self.latex:
                out += (r" \cdot " if before == kind == "number" or before == "other" == kinds[0] else " ") + part
            else:
                tight = kind in ("letter", "group") and before in ("number", "letter", "group")
                out += part if tight or kind == "root" and before == "number" else "·" + part
        return out

    def product(self, node: Product) -> str:
        """A product without its sign: ``6x³/5`` (LaTeX ``\\frac{6}{5} x^{3}``), ``√2/2``,
        ``2t/(t² + 1)``, and a coefficient shown in decimals first: ``4.979476549…x²``."""
        coefficient, top, bottom = node.coefficient, list(node.numerators), list(node.denominators)
        if self.decimals(coefficient):
            return self.fraction(top, bottom, self.number(coefficient), "")
        p, q = coefficient.numerator, coefficient.denominator
        if self.latex and q != 1 and not bottom and not (top and all(_kind(f) == "root" for f in top)):
            return self.joined(top, self.number(coefficient))  # \frac{6}{5} x^{3}, 3/5 folded
        return self.fraction(top, bottom, "" if p == 1 and top else str(p), "" if q == 1 else str(q))

    def fraction(self, top: list[Node], bottom: list[Node], p: str, q: str) -> str:
        """``p·top / (q·bottom)``; in LaTeX a lone sum in a numerator or denominator is bare."""
        if not bottom and not q:
            return self.joined(top, p)
        if self.latex:
            return rf"\frac{{{self.side(top, p)}}}{{{self.side(bottom, q)}}}"
        numerator, denominator = self.joined(top, p), self.joined(bottom, q)
        if len(bottom) + bool(q) > 1:
            denominator = f"({denominator})"
        return f"{numerator}/{denominator}"

    def side(self, factors: list[Node], number: str) -> str:
        if not number and len(factors) == 1 and isinstance(factors[0], Sum):
            return self.node(factors[0])
        return self.joined(factors, number) or "1"


def _integer(node: Node) -> int | None:
    if isinstance(node, Number) and node.value.denominator == 1:
        return node.value.numerator
    if isinstance(node, Product) and not node.numerators and not node.denominators:
        value = -node.coefficient if node.negative else node.coefficient
        return value.numerator if value.denominator == 1 else None
    return None


def _kind(node: Node) -> str:
    """How a factor joins its neighbours: a number, a square root, a one-letter name (or a power
    of one), a group in parentheses, or anything else (joined with ``·``)."""
    if isinstance(node, Number):
        return "number"
    if isinstance(node, Call) and node.function == "sqrt":
        return "root"
    base = node.base if isinstance(node, Power) else node
    if isinstance(base, Name) and len(base.name) == 1:
        return "letter"
    if isinstance(node, (Sum, Product)) or isinstance(node, Power) and isinstance(node.base, (Sum, Product)):
        return "group"
    return "other"


def printed(text: str, mode: Mode = "exact", fold: bool = False, latex: bool = True) -> Printed:
    """``text`` (an engine string) as Unicode and LaTeX in ``mode``; :class:`Unreadable` if it
    is not in the engine's syntax. ``fold`` writes a rational number ``p/q`` on one line in
    LaTeX too (an entry of a vector: a stacked fraction there is set too small to read);
    ``latex=False`` prints no LaTeX (a formula too long to typeset)."""
    tree = read(text)
    unicode_printer, latex_printer = _Printer(mode, False), _Printer(mode, True, fold=fold)
    unicode_text = unicode_printer.node(tree)
    terms = tree.terms if isinstance(tree, Sum) else (tree,)
    pieces = tuple(latex_printer.term(term, index) for index, term in enumerate(terms)) if latex else ()
    return Printed(unicode_text, "".join(pieces), pieces, unicode_printer.shortened or latex_printer.shortened)


def exact_unicode(text: str) -> str:
    """The exact Unicode of an engine string, every digit (the pane's "exact digits")."""
    return _Printer("exact", False, shorten=False).node(read(text))


def exact_latex(text: str) -> str:
    """The exact LaTeX of an engine string, every digit (what "Copy as LaTeX" gives)."""
    return _Printer("exact", True, shorten=False).node(read(text))


_LABEL_LETTERS = ((r"\varphi", "φ"), (r"\rho", "ρ"), (r"\tau", "τ"), (r"\tilde{p}", "p̃"))


def unicode_label(latex: str) -> str:
    """A LaTeX label of the pane (``\\varphi =``, ``\\tau_x =``, ``P^2(x, y) =``, ``g_1(u, v) =``)
    in Unicode: ``φ =``, ``τ_x =``, ``P²(x, y) =``, ``g₁(u, v) =``."""
    text = latex
    for command, letter in _LABEL_LETTERS:
        text = text.replace(command, letter)
    text = re.sub(r"\^\{?(\d+)\}?", lambda m: m.group(1).translate(SUPERSCRIPTS), text)
    return re.sub(r"_\{?(\d+)\}?", lambda m: m.group(1).translate(SUBSCRIPTS), text)
