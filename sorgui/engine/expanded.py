"""The parser's fast path: an expanded polynomial in ``x, y, z`` read in one regular-expression
pass, straight into flint's ``QQ[x, y, z]``, without a syntax tree.

A parts library, a CAS or sorgui itself prints equations as sums of terms, each a number times a
monomial: ``3*x**2*y - 5/2*z + 1`` (sorgui, Maple, Singular), ``43*x**10/59`` (sympy),
``2x^2y - 1.5e-3 z`` (by hand, CAD output), ``z = x^3 - 3xy^2``. One pattern (:data:`_TERM`)
splits the whole text into terms in C; per term only the digits are handed to ``int()`` and the
monomial's exponents are looked up (:func:`_exponents`, cached across calls: a library's
equations share their monomials). Decimals are exact (``0.25`` is ``1/4``), as in the parser.

Anything else (parentheses, roots, powers of numbers, LaTeX, two signs in a row, a limit of the
parser's reached) is declined with ``None``, and the general parser (:mod:`.syntax`) reads it
and reports on it exactly; whatever this path accepts, the general parser reads as the same
polynomial (a property test compares them), so it changes the speed and nothing else.
"""

from __future__ import annotations

import math
import re
from functools import cached_property
from typing import Any, cast

from flint import fmpq, fmpq_mpoly, fmpz_mpoly, fmpz_mpoly_ctx

from .algebra import rationals
from .limits import Limits, equation_span

Monomial = tuple[int, ...]

_NUMBER = r"(?:[0-9]++(?:\.[0-9]*+)?+|\.[0-9]++)(?:[eE][-+]?+[0-9]++)?+"
_POWER = r"(?:\s*+(?:\*\*|\^)\s*+[0-9]{1,6}+)?+"
_TIMES = r"(?:\s*+\*\s*+|[ \t]*+)"
"""A product's ``*``, or none across spaces on one line: a line break with no operator is not a
product (two equations on two lines were multiplied); the parser says so."""
_MONOMIAL = rf"[xyz]{_POWER}(?:{_TIMES}[xyz]{_POWER})*+"
_TERM = re.compile(
    rf"\s*+([-+]?+)\s*+(?:({_NUMBER})(?:\s*+/\s*+([0-9]++))?+(?:{_TIMES}({_MONOMIAL})(?:\s*+/\s*+([0-9]++))?+)?+"
    rf"|({_MONOMIAL})(?:\s*+/\s*+([0-9]++))?+)\s*+|(\s++|.)",
    re.DOTALL,
)
"""A term — ``[sign] number [/ integer] [[*] monomial [/ integer]]`` or ``[sign] monomial
[/ integer]`` — or, in the last group, any other character or a run of spaces that no term
follows (then the text is declined). Every character of the text belongs to exactly one match.
The quantifiers are possessive (a term is never read in two ways, and a text is split in half
the time); a run of spaces before what is not a term is one match, not one per space, each
scanning the rest of the run (``P``, 100,000 spaces and ``)`` took half a minute)."""
_FACTOR = re.compile(r"([xyz])(?:\s*(?:\*\*|\^)\s*([0-9]+))?")
_INDEX = {"x": 0, "y": 1, "z": 2}
_CONSTANT: Monomial = (0, 0, 0)
_INTEGERS = fmpz_mpoly_ctx.get(("x", "y", "z"), "lex")
"""``ZZ[x, y, z]``, in the order of :func:`.algebra.rationals.context`."""
_MONOMIALS: dict[str, Monomial | None] = {}
_MONOMIALS_KEPT = 20_000
"""Monomial texts whose exponents are kept between calls."""
_SPARE_BITS = 256
"""Bits by which the common denominator of the terms may exceed twice the largest one before
the terms are read one rational each (:meth:`_Terms.polynomial`)."""


class Reading:
    """An equation read: ``polynomial`` in ``QQ[x, y, z]`` and, made on demand from what the fast
    path read (``None`` where it cannot, then :func:`.algebra.rationals.flint_str` and
    :func:`.algebra.rationals.primitive` make them), the engine's texts of it.

    ``printed`` is :func:`~.algebra.rationals.flint_str` of ``polynomial`` (built from the digits
    as written, when the terms come in the printed order with their fractions in lowest terms,
    as sorgui prints them; the read text itself when they agree, so that an analysis holds one
    string, pickled and encoded once); ``primitive`` is the polynomial scaled to integers with content 1
    and a positive leading (lex) coefficient, from the integers the reader holds (their content, one
    C call), and ``primitive_printed`` its text when it is ``printed``. Reading alone costs
    none of them (the window's editor reads every keystroke)."""

    def __init__(
        self,
        polynomial: fmpq_mpoly,
        terms: _Terms | None = None,
        whole: fmpz_mpoly | None = None,
        integers: dict[Monomial, int] | None = None,
        values: dict[str, int] | None = None,
        text: str | None = None,
    ) -> None:
        self.polynomial = polynomial
        self._terms, self._whole, self._integers, self._values = terms, whole, integers, values
        self._text = text

    @property
    def multiple(self) -> dict[Monomial, int] | None:
        """The coefficients of ``whole``, a multiple of ``polynomial`` by the common denominator
        of the terms, as the reader holds them (``None`` when it holds none): by monomial,
        Python integers (some may be zero)."""
        return self._integers

    @property
    def whole(self) -> fmpz_mpoly | None:
        """That multiple of ``polynomial`` in ``ZZ[x, y, z]`` (``None`` when the reader holds no
        integers): integer arithmetic, for the exact checks that a constant factor leaves alone."""
        return self._whole

    @cached_property
    def printed(self) -> str | None:
        terms, integers, values = self._terms, self._integers, self._values
        if terms is None or integers is None or values is None or not terms.plain:
            return None
        printed = terms._printed(values) if len(integers) == len(terms.monomials) else None
        return self._text if printed == self._text else printed  # one string, pickled and encoded once

    @cached_property
    def _scale(self) -> int | None:
        """The signed content by which ``whole`` divides into ``primitive`` (``None``: no integers)."""
        whole = self._whole
        if whole is None:
            return None
        content = int(whole.content())  # type: ignore[attr-defined]  # in python-flint 0.9, not in its stub
        if not content:
            return None  # the zero polynomial (never read: it is constant)
        return -content if whole.leading_coefficient() < 0 else content

    @cached_property
    def primitive(self) -> fmpq_mpoly | None:
        whole, scale = self._whole, self._scale
        if whole is None or scale is None:
            return None
        primitive = fmpq_mpoly(whole, self.polynomial.context())
        return primitive if scale == 1 else primitive * fmpq(1, scale)

    @cached_property
    def primitive_printed(self) -> str | None:
        printed, primitive, scale = self.printed, self.primitive, self._scale
        if printed is None or primitive is None or scale is None or self._integers is None or self._terms is None:
            return None
        if primitive == self.polynomial:
            return printed
        coefficients = list(self._integers.values())  # in the terms' order: printed, no monomial is twice
        return self._terms.printed_integers(coefficients if scale == 1 else [c // scale for c in coefficients])


def read_expanded(text: str, limits: Limits) -> Reading | None:
    """``text`` as a non-constant polynomial of ``QQ[x, y, z]``, or ``None`` when it is not an
    expanded polynomial within ``limits`` (or is constant): the general parser decides then.
    ``lhs = rhs`` is ``lhs - rhs``; a label such as ``f(x, y, z) =`` and a final ``;`` are skipped
    (:func:`.limits.equation_span`), as in the parser."""
    start, end = equation_span(text)
    body = text[start:end]
    terms = _Terms()
    if "=" in body:
        sides = body.split("=")
        if len(sides) != 2 or not terms.read(sides[0], limits, 1) or not terms.read(sides[1], limits, -1):
            return None
        terms.plain = False  # two sides: a monomial may be written on both
    elif not terms.read(body, limits, 1):
        return None
    reading = terms.reading(text)
    return None if reading.polynomial.is_constant() else reading  # constant or zero: the parser says which


class _Terms:
    """The terms read so far: monomial, integer numerator and the digits of the denominator
    (``""`` for 1) of each, in three lists; the digits of each numerator as written, and whether
    every term so far was written with integers only (``plain``: no decimal, one divisor)."""

    __slots__ = ("denominators", "digits", "monomials", "numerators", "plain")

    def __init__(self) -> None:
        self.monomials: list[Monomial] = []
        self.numerators: list[int] = []
        self.denominators: list[str] = []
        self.digits: list[str] = []
        self.plain = True

    def read(self, text: str, limits: Limits, side: int) -> bool:
        """Add the terms of one side (times ``side``, ±1); ``False`` when it is not expanded."""
        matches = _TERM.findall(text)
        if matches and self._read_integers(matches, limits, side):
            return True
        first = True
        short = limits.bits // 4  # literals this long in all cannot reach the bound on a product's bits
        cached = _MONOMIALS.get
        monomials, numerators, denominators, digits = self.monomials, self.numerators, self.denominators, self.digits
        for sign, number, over, monomial, under, bare, bare_under, other in matches:
            if other or not (sign or first):
                return False  # another character, or two terms without a sign between them
            first = False
            if not number:
                numerator, key, number = 1, bare_under, "1"
                monomial, under = bare, bare_under
            elif number.isdigit() and len(number) <= limits.digits and not (over and under):
                numerator, key = int(number), over or under
            else:
                value = _rational(number, over, under, limits)
                if value is None:
                    return False
                numerator, denominator = value
                key = "" if denominator == 1 else str(denominator)
                self.plain = False
            if key and (len(key) > limits.digits or not key.strip("0")):
                return False  # division by zero, or too many digits: the parser says so
            exponents = (cached(monomial) or _exponents(monomial, limits)) if monomial else _CONSTANT
            if exponents is None:
                return False
            if len(number) + len(over) + len(under) > short and (
                numerator.bit_length() + len(key) * 10 // 3 + sum(exponents) > limits.bits
            ):
                return False  # near the parser's bound on the numbers of a product: it decides
            monomials.append(exponents)
            numerators.append(-numerator if (sign == "-") != (side < 0) else numerator)
            denominators.append(key)
            digits.append(number)
        return not first

    def _read_integers(self, matches: list[tuple[str, ...]], limits: Limits, side: int) -> bool:
        """:meth:`read` for the usual text, whose terms are all written with integers (``3/5*x**2``,
        ``43*x**10/59``, ``x``), far from the parser's limits, their monomials known: each check
        is one pass over a column of the terms (in C) instead of a pass over the terms; the
        numerators go to ``int()`` in one ``map``. ``False`` (nothing added) for any other text,
        which the loop of :meth:`read` then reads term by term."""
        signs, numbers, overs, written, unders, bare, bare_unders, others = zip(*matches)
        if any(others) or not all(signs[1:]) or any(map(all, zip(overs, unders))):
            return False  # another character, two terms without a sign between them, two divisors
        keys = [o or u or b for o, u, b in zip(overs, unders, bare_unders)]
        digits = [n or "1" for n in numbers]
        longest = max(map(len, digits)) + max(map(len, keys))
        # bytes.isdigit: ASCII digits only, by a table (str.isdigit asks Unicode of each character)
        if longest > min(limits.digits, limits.bits // 4) or not ("".join(digits) + "".join(keys)).encode().isdigit():
            return False  # decimals, or long numbers: the loop checks the limits on each
        if any(k and not k.strip("0") for k in set(keys)):
            return False  # a division by zero: the parser says so
        texts = [w or b for w, b in zip(written, bare)]
        cached = list(map(_MONOMIALS.get, texts))
        if None in cached:
            for i, found in enumerate(cached):
                if found is None:
                    cached[i] = _exponents(texts[i], limits) if texts[i] else _CONSTANT
            if None in cached:
                return False  # above the degree limit
        flip = side < 0
        self.monomials += cast("list[Monomial]", cached)  # no None left
        self.numerators += [n if (s == "-") == flip else -n for s, n in zip(signs, map(int, digits))]
        self.denominators += keys
        self.digits += digits
        return True

    def reading(self, text: str) -> Reading:
        """The sum of the terms of ``text``, with what makes its texts on demand (:class:`Reading`).

        Over the common denominator ``L`` of the terms, the numerators are integers, read by
        flint in one call and divided by ``L`` once (a rational per term would cost as much again
        as the reading). When ``L`` is much larger than the denominators themselves, one rational
        per term instead."""
        context = rationals.context(("x", "y", "z"))
        values = {key: int(key) for key in set(self.denominators) if key}
        common = math.lcm(*values.values())
        values[""] = 1
        largest = max(d.bit_length() for d in values.values())
        if common.bit_length() > 2 * largest + _SPARE_BITS:
            fractions = [n if not k else fmpq(n, values[k]) for n, k in zip(self.numerators, self.denominators)]
            return Reading(context.from_dict(self._sum(fractions)))
        factors = {key: common // d for key, d in values.items()}
        coefficients = [n * factors[k] for n, k in zip(self.numerators, self.denominators)]
        integers: dict[Monomial, int] = self._sum(coefficients)
        whole = _INTEGERS.from_dict(integers)  # ZZ's coefficients: read a tenth faster than QQ's
        polynomial = fmpq_mpoly(whole, context)
        if common != 1:
            polynomial *= fmpq(1, common)
        return Reading(polynomial, self, whole, integers, values, text)

    def _sum(self, coefficients: list[Any]) -> dict[Monomial, Any]:
        """The terms by monomial, the coefficients of a monomial written more than once added."""
        terms = dict(zip(self.monomials, coefficients))
        if len(terms) < len(coefficients):
            terms = {}
            for monomial, c in zip(self.monomials, coefficients):
                terms[monomial] = terms.get(monomial, 0) + c
        return terms

    def _printed(self, values: dict[str, int]) -> str | None:
        """:func:`~.algebra.rationals.flint_str` of the sum, built from the digits as written:
        when the terms come in its order (decreasing total degree, then decreasing lex; so no
        monomial twice) and every fraction is in lowest terms without leading zeros; else
        ``None``."""
        keys = [_ORDER.get(m) or _order(m) for m in self.monomials]  # (degree, monomial, spelling)
        if any(a <= b for a, b in zip(keys, keys[1:])):
            return None
        denominators = self.denominators
        if any(d[0] == "0" for d in self.digits) or any(k[0] == "0" or k == "1" for k in set(denominators) if k):
            return None  # a leading zero, or a division by 1
        # lowest terms: gcd(numerator, denominator) = 1 for each term (1 without a denominator), in one C loop
        if max(map(math.gcd, self.numerators, map(values.__getitem__, denominators)), default=1) != 1:
            return None
        magnitudes = [f"{digits}/{key}" if key else digits for digits, key in zip(self.digits, denominators)]
        return _joined([k[2] for k in keys], [n < 0 for n in self.numerators], magnitudes)

    def printed_integers(self, coefficients: list[int]) -> str:
        """:func:`~.algebra.rationals.flint_str` of the polynomial with these integer coefficients
        on the terms' monomials, which :meth:`_printed` found in the printed order."""
        spellings = [(_ORDER.get(m) or _order(m))[2] for m in self.monomials]
        return _joined(spellings, [c < 0 for c in coefficients], [str(abs(c)) for c in coefficients])


def _joined(spellings: list[str], negatives: list[bool], magnitudes: list[str]) -> str:
    """The printed sum of terms ``±magnitude*spelling`` (``spelling`` empty for the constant,
    a magnitude ``1`` not written before a monomial), as :func:`~.algebra.rationals.terms_str` writes it."""
    pieces: list[str] = []  # signs and bodies, joined once (no string per term)
    add = pieces.append
    for spelling, negative, magnitude in zip(spellings, negatives, magnitudes):
        add(" - " if negative else " + ")
        if not spelling:
            add(magnitude)
        elif magnitude == "1":
            add(spelling)
        else:
            add(magnitude)
            add("*")
            add(spelling)
    if not pieces:
        return "0"
    pieces[0] = "-" if negatives[0] else ""
    return "".join(pieces)


def _rational(number: str, over: str, under: str, limits: Limits) -> tuple[int, int] | None:
    """``number / over / under`` as ``(numerator, denominator)`` (not reduced); ``None`` beyond
    the parser's limits or for a division by zero."""
    value = _number(number, limits)
    if value is None:
        return None
    numerator, denominator = value
    for divisor in (over, under):
        if divisor:
            d = int(divisor) if len(divisor) <= limits.digits else 0
            if not d:
                return None
            denominator *= d
    return numerator, denominator


def _number(text: str, limits: Limits) -> tuple[int, int] | None:
    """A number literal as ``(numerator, denominator)``, exactly (``1.5e-3`` is ``15/10⁴``);
    ``None`` beyond the parser's limits on digits and decimal exponents."""
    mantissa, _, exponent = text.replace("E", "e").partition("e")
    whole, _, fraction = mantissa.partition(".")
    digits = whole + fraction
    if len(digits) > limits.digits:
        return None
    scale = -len(fraction)
    if exponent:
        if len(exponent.lstrip("+-")) > 6 or abs(int(exponent)) > limits.decimal_exponent:
            return None
        scale += int(exponent)
    value = int(digits) if digits else 0
    return (value * 10**scale, 1) if scale >= 0 else (value, 10**-scale)


_ORDER: dict[Monomial, tuple[int, Monomial, str]] = {}


def _order(monomial: Monomial) -> tuple[int, Monomial, str]:
    """The key of ``monomial`` in the printed order (total degree, then lex) and its printed
    spelling (``x**2*y``), kept between calls as :data:`_MONOMIALS` is."""
    if len(_ORDER) >= _MONOMIALS_KEPT:
        _ORDER.clear()
    spelling = "*".join(n if e == 1 else f"{n}**{e}" for n, e in zip("xyz", monomial) if e)
    key = _ORDER[monomial] = (sum(monomial), monomial, spelling)
    return key


def _exponents(monomial: str, limits: Limits) -> Monomial | None:
    """The exponents of a monomial's text (``x**2*y``, ``x^2 y``, ``xy``), kept for the next
    time; ``None`` above the degree limit."""
    exponents = [0, 0, 0]
    for name, power in _FACTOR.findall(monomial):
        exponents[_INDEX[name]] += int(power) if power else 1
    found = (exponents[0], exponents[1], exponents[2]) if sum(exponents) <= limits.degree else None
    if len(_MONOMIALS) >= _MONOMIALS_KEPT:
        _MONOMIALS.clear()
    if found is not None:
        _MONOMIALS[monomial] = found
    return found
