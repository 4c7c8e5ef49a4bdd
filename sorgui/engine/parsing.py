"""Reading pasted text: an equation ``f(x, y, z) = 0`` as an exact polynomial ``f ∈ K[x, y, z]``,
``K = QQ(sqrt(n1), ...)``, and what kind of text it is.

Most equations are expanded polynomials, as CAS, CAD systems and sorgui print them: the fast path
(:mod:`.expanded`) reads them in one regular-expression pass straight into python-flint. Any other
text (parentheses, roots, LaTeX, an error to report) goes to the general parser (:mod:`.syntax`),
imported only then; both accept exactly the same language within the same limits
(:mod:`.limits`), and neither ever evaluates the text (no ``eval``, no ``sympify``). Over ``QQ``
the polynomial is python-flint's (:func:`parse_rational`, :func:`read_rational`: no sympy), over a
real field ``K`` sympy's sparse ring (:func:`parse_polynomial`). :func:`is_parametrization` and
:func:`has_decimals` tell a parametrization and rounded input from an equation without reading it.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import TYPE_CHECKING

from flint import fmpq_mpoly

from .expanded import Reading, read_expanded
from .limits import (
    LIMITS,
    MAX_DECIMAL_EXPONENT,
    MAX_DEGREE,
    MAX_DIGITS,
    MAX_LENGTH,
    MAX_NESTING,
    MAX_PRINTED_DIGITS,
    MAX_WORK,
    equation_span,
    without_comments,
)

if TYPE_CHECKING:
    from sympy.polys.domains.domain import Domain
    from sympy.polys.rings import PolyElement

__all__ = [
    "MAX_DECIMAL_EXPONENT",
    "MAX_DEGREE",
    "MAX_DIGITS",
    "MAX_LENGTH",
    "MAX_NESTING",
    "MAX_PRINTED_DIGITS",
    "MAX_WORK",
    "ParsedPolynomial",
    "expanded_polynomial",
    "has_decimals",
    "is_parametrization",
    "parse_polynomial",
    "parse_rational",
    "read_rational",
]


@dataclass(frozen=True)
class ParsedPolynomial:
    """The parsed equation: ``polynomial`` lies in ``poly_ring(("x", "y", "z"), field)``."""

    text: str
    polynomial: PolyElement
    field: Domain
    radicands: tuple[int, ...]  # square-free integers > 1 whose square roots occur, sorted


def parse_polynomial(text: str) -> ParsedPolynomial:
    """Parse ``text`` (``f``, or ``lhs = rhs`` meaning ``lhs - rhs``) into an exact polynomial.

    Raises :class:`ParseError` (and nothing else) for every input that is not a non-constant
    polynomial in x, y, z of total degree at most ``MAX_DEGREE``.
    """
    from .algebra.polys import XYZ, from_flint, number_field, poly_ring

    plain = expanded_polynomial(text)
    if plain is not None:
        ring = poly_ring(XYZ, number_field(()))
        return ParsedPolynomial(text, from_flint(plain, ring), ring.domain, ())
    from . import syntax

    tree, evaluator, saw_variable = syntax.checked(text)
    radicands = tuple(sorted(evaluator.radicands))
    if not radicands:
        ring = poly_ring(XYZ, number_field(()))
        g = syntax.evaluate(text, evaluator, tree, syntax.FlintRationals(), saw_variable)
        return ParsedPolynomial(text, from_flint(g, ring), ring.domain, ())
    field = number_field(radicands)
    polynomial = syntax.evaluate(
        text, evaluator, tree, syntax.SympyField(poly_ring(XYZ, field), radicands), saw_variable
    )
    if all(field.to_sympy(c).is_Rational for c in polynomial.coeffs()):
        # The square roots cancelled (``sqrt(2)*sqrt(2)*x``): the polynomial lives over QQ.
        rational = poly_ring(XYZ, number_field(()))
        terms = {m: rational.domain.from_sympy(field.to_sympy(c)) for m, c in polynomial.items()}
        return ParsedPolynomial(text, rational.from_dict(terms), rational.domain, ())
    return ParsedPolynomial(text, polynomial, field, radicands)


def parse_rational(text: str) -> fmpq_mpoly | None:
    """``f ∈ QQ[x, y, z]`` as a flint polynomial (variables ``x, y, z``), without sympy; ``None``
    when the text has square roots (:func:`parse_polynomial` then gives its field). Raises
    :class:`ParseError` as :func:`parse_polynomial` does."""
    reading = read_rational(text)
    return None if reading is None else reading.polynomial


def read_rational(text: str) -> Reading | None:
    """:func:`parse_rational` with the engine's texts of the polynomial where the fast path has
    them at little cost (:class:`~.expanded.Reading`): what the recognition over ``QQ`` prints."""
    reading = _fast_reading(text)
    if reading is not None:
        return reading
    from . import syntax

    tree, evaluator, saw_variable = syntax.checked(text)
    if evaluator.radicands:
        return None
    g: fmpq_mpoly = syntax.evaluate(text, evaluator, tree, syntax.FlintRationals(), saw_variable)
    return Reading(g)


def expanded_polynomial(text: str) -> fmpq_mpoly | None:
    """The fast path in front of the general parser: an expanded polynomial with rational or
    decimal coefficients, as CAS, CAD systems and sorgui itself print them (``3*x**2*y - 5/2*z
    + 1``, ``43*x**10/59``, ``2x^2y - 1.5e-3 z``, ``z = x^3 - 3xy^2``), read in one
    regular-expression pass straight into flint (:mod:`.expanded`), no syntax tree. ``None``
    for anything else (parentheses, roots, a limit reached, a constant), which the general
    parser then reads and reports on exactly."""
    reading = _fast_reading(text)
    return None if reading is None else reading.polynomial


def _fast_reading(text: str) -> Reading | None:
    """The fast path's reading of ``text`` (:mod:`.expanded`), within the length limit."""
    return read_expanded(text, LIMITS) if len(text) <= MAX_LENGTH else None


def is_parametrization(text: str) -> bool:
    """Whether ``text`` has the form of a parametrization (not whether it is a valid one): a
    ``,`` or ``;`` (an equation has none) outside a label and a final ``;``
    (:func:`.limits.equation_span`), or two lines that start with ``x =``, ``y =`` or ``z =``.
    Cheap: no tokenizing, no sympy."""
    if len(text) > MAX_LENGTH:
        return False
    if "," in text or ";" in text:  # a long equation has neither: its span is not looked for
        start, end = equation_span(text)
        body = without_comments(text)[start:end]  # comments become spaces: no separator is added
        if ("," in body or ";" in body) and _SEPARATOR.search(body) and _separates(body):
            return True
    return "\n" in text and len(_LABEL_LINE.findall(text, 0, 10_000)) >= 2


def _separates(body: str) -> bool:
    """Whether a ``,`` or ``;`` of ``body`` lies outside the parentheses of every ``pow(a, n)``
    (whose comma separates its arguments, not components)."""
    if "pow" not in body:
        return True
    calls = {match.end() - 1 for match in _POW_CALL.finditer(body)}  # where each pow's '(' is
    inside_pow: list[bool] = []  # for each parenthesis open, whether it is a pow's
    for match in _BRACKET_OR_SEPARATOR.finditer(body):
        character = match.group()
        if character in "([{":
            inside_pow.append(match.start() in calls)
        elif character in ")]}":
            if inside_pow:
                inside_pow.pop()
        elif not (inside_pow and inside_pow[-1]):
            return True
    return False


_SEPARATOR = re.compile(r"(?<!\\)[,;]")
_POW_CALL = re.compile(r"(?<![A-Za-z])pow\s*\(")
_BRACKET_OR_SEPARATOR = re.compile(r"[(\[{)\]}]|(?<!\\)[,;]")
_LABEL_LINE = re.compile(r"(?m)^[^\S\n]*+(?:\\[(\[]|\$\$?+)?+[^\S\n]*+[xyz][^\S\n]*+(?:\([^()\n]*+\))?+[^\S\n]*+:?=")
"""A line that starts with ``x =`` (or ``x(u, v) =``), also inside LaTeX's ``\\[``, ``\\(`` or
``$`` (sorgui's LaTeX file writes a map's components as three displays); possessive and within
its line, so that a page of spaces or of empty lines is read once."""


_DECIMAL_MARK = re.compile(r"[0-9]\.|\.[0-9]|[0-9](?:[eEdD]|\*\^)[-+−]?[0-9]")
"""A decimal point or an exponent inside a number literal of the parser's tokenizer (which reads
``2.``, ``.5``, ``2e-3``, ``2e−3``, ``2D-3`` and ``2*^-3`` as numbers and nothing else of a
valid equation as a point, an ``e``, a ``D`` or ``*^``); a search, so that the check costs no
second parse of a long pasted equation."""


def has_decimals(text: str) -> bool:
    """Whether ``text`` prints a number with a decimal point or an exponent (``1.5``, ``2e-3``,
    ``2D-3``, ``2*^-3``; in a comment, none counts). Most equations have none of ``.``, ``e``,
    ``E``, ``d``, ``D`` and ``*^``, which ``in`` finds faster than a search."""
    if not any(mark in text for mark in (".", "e", "E", "d", "D", "*^")):
        return False
    return _DECIMAL_MARK.search(without_comments(text)) is not None
