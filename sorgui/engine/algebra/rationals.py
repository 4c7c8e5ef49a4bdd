"""The rational field ``QQ`` on python-flint alone: what the engine's sympy-free path needs.

A recognition-only run of an equation over ``QQ`` never needs sympy (whose import alone costs
more than the whole analysis, docs/benchmarks.md): its polynomials are flint ``fmpq_mpoly``, its
numbers ``fmpq``, and its linear algebra ``fmpq_mat``. This module holds the pieces of that path
that the sympy-based modules share with it, so that both print and normalise alike:
:data:`RATIONALS`, a stand-in for sympy's domain ``QQ`` (whose elements are ``fmpq`` too), the
flint contexts, the printer of polynomials and the reader of expanded ones (for the user's
text and the engine's own alike), primitive parts and factorization over ``QQ``.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Sequence
from functools import lru_cache
from typing import Any

from flint import fmpq, fmpq_mpoly, fmpq_mpoly_ctx, fmpq_poly, fmpz, nmod_mpoly_ctx

Monomial = tuple[int, ...]

WORD_BITS = 64
"""Coefficients up to this many bits are small for :func:`_slow_to_factor`."""
CERTIFYING_PRIMES = (2147483647, 2147483629, 2147483587)
"""The primes modulo which :func:`irreducible_modulo_a_prime` tries to show a polynomial
irreducible: the three largest below ``2³¹`` (python-flint 0.9 sorts the factors modulo a larger
prime through a C ``int`` and fails), fixed (the engine is deterministic), three because a
polynomial that is irreducible over ``QQ`` but splits over a number field stays irreducible
modulo only some primes (half of them for two conjugate components)."""


class RationalField:
    """``QQ`` with ``fmpq`` elements: the part of sympy's ``Domain`` interface that the exact
    linear algebra and the classification of the symmetry algebra use."""

    is_QQ = True
    zero = fmpq(0)
    one = fmpq(1)

    def quo(self, a: Any, b: Any) -> fmpq:
        """``a / b`` (exact)."""
        return fmpq(a) / fmpq(b)

    def __repr__(self) -> str:
        return "QQ"


RATIONALS = RationalField()


@lru_cache(maxsize=64)
def context(names: tuple[str, ...]) -> fmpq_mpoly_ctx:
    """The flint ring ``QQ[names]`` in lex order (the order of sympy's rings)."""
    return fmpq_mpoly_ctx.get(names, "lex")


def terms_str(names: Sequence[str], terms: Iterable[tuple[Monomial, Any]], coefficient: Any = None) -> str:
    """A polynomial as a string that sympy and the project's parser read back exactly.

    Terms come in decreasing total degree, then decreasing lex order. ``coefficient`` maps a
    coefficient to ``(negative, text of its magnitude)``; by default it prints rationals.
    """
    sign = coefficient or _rational_coefficient
    spellings = _spellings(tuple(names))
    bodies: list[tuple[bool, str]] = []
    for monom, c in sorted(terms, key=_degree_then_lex, reverse=True):
        negative, magnitude = sign(c)
        key = tuple(monom)
        variables = spellings.get(key)
        if variables is None:
            if len(spellings) >= SPELLINGS_KEPT:
                spellings.clear()
            variables = spellings[key] = "*".join(n if e == 1 else f"{n}**{e}" for n, e in zip(names, key) if e)
        if not variables:
            body = magnitude
        elif magnitude == "1":
            body = variables
        else:
            body = f"{magnitude}*{variables}"
        bodies.append((negative, body))
    return signed_sum(bodies)


def _degree_then_lex(term: tuple[Monomial, Any]) -> tuple[int, Monomial]:
    """The key of :func:`terms_str`'s order: total degree, then the exponents."""
    monom = term[0]
    return sum(monom), tuple(monom)


SPELLINGS_KEPT = 20_000
"""Printed monomials kept between calls of :func:`terms_str`, per tuple of variable names."""


@lru_cache(maxsize=16)
def _spellings(names: tuple[str, ...]) -> dict[Monomial, str]:
    """The printed monomials (``x**2*y``) in the variables ``names`` that :func:`terms_str` has
    made, kept between calls: a profile prints the same few dozen every time (the spelling was
    half of the printing)."""
    return {}


def signed_sum(terms: Iterable[tuple[bool, str]]) -> str:
    """``[(negative, magnitude text), ...]`` as the sum ``a - b + c`` (``"0"`` when empty)."""
    out: list[str] = []
    for negative, body in terms:
        if out:
            out.append(f" - {body}" if negative else f" + {body}")
        else:
            out.append(f"-{body}" if negative else body)
    return "".join(out) or "0"


def _rational_coefficient(c: Any) -> tuple[bool, str]:
    text = str(c)  # one conversion: comparing a flint rational with 0 costs as much again
    return (True, text[1:]) if text.startswith("-") else (False, text)


def terms(g: fmpq_mpoly) -> list[tuple[Monomial, fmpq]]:
    """The terms of a flint polynomial, exponents as Python ints."""
    return [(tuple(int(e) for e in m), c) for m, c in g.terms()]


def flint_str(g: fmpq_mpoly, names: Sequence[str] | None = None) -> str:
    """:func:`terms_str` of a flint polynomial (named ``names``, else its context's names),
    printed by flint itself: in the ``deglex`` order its terms come as :func:`terms_str` sorts
    them, and its rationals read as ours once ``^`` is written ``**`` (a test compares both).
    The polynomial is moved into that ring by composing with its generators (no Python terms)."""
    printer = fmpq_mpoly_ctx.get(tuple(names or g.context().names()), "deglex")
    return str(g.compose(*printer.gens(), ctx=printer)).replace("^", "**")


def squarefree(F: fmpq_mpoly) -> fmpq_mpoly:
    """The square-free part of ``F`` over ``QQ``."""
    _, parts = F.factor_squarefree()
    out = F.context().constant(1)
    for h, _ in parts:
        out *= h
    return out


def rational_str(q: fmpq) -> str:
    """``str(q)`` (``-3/2``, ``5``), from the numerator and the denominator as Python integers:
    flint's own text of a rational costs three times as much (a report prints dozens)."""
    numerator, denominator = int(q.p), int(q.q)
    return str(numerator) if denominator == 1 else f"{numerator}/{denominator}"


def times_text(q: fmpq, atom: str) -> str:
    """``q·atom`` for ``q > 0`` as sympy prints it: ``atom``, ``3*atom``, ``atom/2``, ``3*atom/2``."""
    numerator, denominator = int(q.p), int(q.q)
    text = atom if numerator == 1 else f"{numerator}*{atom}"
    return text if denominator == 1 else f"{text}/{denominator}"


def content(*polys: fmpq_mpoly) -> fmpq:
    """The positive rational content of ``polys`` together: the gcd of their coefficients over
    ``QQ`` (1 when they are all zero); each divided by it has integer coefficients, gcd 1 in all."""
    coefficients = [c for g in polys for c in g.coeffs()]
    denominator = fmpz(1)
    for c in coefficients:
        denominator = denominator.lcm(c.q)
    numerator = fmpz(0)
    for c in coefficients:
        numerator = numerator.gcd(c.p * (denominator // c.q))
    return fmpq(numerator, denominator) if numerator else fmpq(1)


def primitive(g: fmpq_mpoly) -> fmpq_mpoly:
    """``g`` scaled to integer coefficients with gcd 1 and a positive leading (lex) coefficient."""
    if g.is_zero():
        return g
    scale = 1 / content(g)
    return -g * scale if g.leading_coefficient() < 0 else g * scale


def factor(g: fmpq_mpoly) -> list[tuple[fmpq_mpoly, int]]:
    """The irreducible factors of ``g`` over ``QQ`` with multiplicities, primitive, in the
    engine's deterministic order (degree in the first variable, then the printed text).

    A curve's equation with large coefficients (:func:`_slow_to_factor`) that a prime shows
    irreducible (:func:`irreducible_modulo_a_prime`) is not factored."""
    if _shown_irreducible(g):
        return [(primitive(g), 1)]
    _, factors = g.factor()
    normal = [(primitive(h), int(e)) for h, e in factors]
    if len(normal) > 1:
        normal.sort(key=lambda he: (int(he[0].degrees()[0]), flint_str(he[0])))
    return normal


def irreducible(g: fmpq_mpoly) -> bool:
    """Whether ``g`` is irreducible over ``QQ`` and square-free (one factor, multiplicity 1), by a
    line (:func:`irreducible_on_a_line`), by a prime where flint's factorization would be slow
    (:func:`_slow_to_factor`), else by flint's."""
    if _shown_irreducible(g):
        return True
    _, factors = g.factor()
    return len(factors) == 1 and factors[0][1] == 1


def _shown_irreducible(g: fmpq_mpoly) -> bool:
    """Whether ``g`` is shown irreducible and square-free without flint's factorization: by a
    line (:func:`irreducible_on_a_line`), or by a prime where that factorization would be slow
    (:func:`_slow_to_factor`). ``False`` proves nothing."""
    return irreducible_on_a_line(g) or (_slow_to_factor(g) and irreducible_modulo_a_prime(g))


def _slow_to_factor(g: fmpq_mpoly) -> bool:
    """Whether ``g`` has at most two variables and a coefficient of more than
    :data:`WORD_BITS` bits: then flint's factorization can take seconds where a prime shows
    irreducibility in milliseconds (18 s against 8 ms for ``(s² + w + 10²⁰)²⁰ − 10²⁰·s``, 27 s
    against 20 ms for ``(s² + w + 10¹⁰⁰)³⁰ − 10¹⁰⁰·s``, the ``P²`` of a degree-60 surface).
    Otherwise flint is as fast (in three variables) or faster (``P²`` of a degree-20 surface
    with small coefficients: 0.07 ms against 0.5 ms)."""
    return sum(1 for d in g.degrees() if d) <= 2 and any(c.height_bits() > WORD_BITS for c in g.coeffs())


def irreducible_on_a_line(g: fmpq_mpoly) -> bool:
    """Whether ``g`` in at most two variables is shown irreducible over ``QQ`` (hence square-free)
    by its restriction to one line (docs/math.md §4): when its leading coefficient in its last
    variable ``v`` is a nonzero constant (as that of ``P²(s, w)`` in ``w`` is), and ``g`` at the
    first variable :data:`LINE_POINT` is irreducible in ``QQ[v]``. One univariate factorization,
    a quarter of the time of :func:`irreducible_modulo_a_prime`. ``False`` proves nothing."""
    ring = g.context()
    last = ring.nvars() - 1
    n = int(g.degrees()[-1]) if last <= 1 else 0
    if not n:
        return False
    top = tuple(n if i == last else 0 for i in range(last + 1))
    lead = g[top]
    if not lead or int((g - lead * ring.from_dict({top: 1})).degrees()[-1]) == n:
        return False  # the leading coefficient in v is not a constant
    line = g.subs({0: LINE_POINT}) if last else g
    coefficients = [fmpq(0)] * (n + 1)
    for m, c in zip(line.monoms(), line.coeffs()):
        coefficients[int(m[-1])] = c
    _, factors = fmpq_poly(coefficients).factor()
    return len(factors) == 1 and factors[0][1] == 1


LINE_POINT = 2
"""The value of the first variable on the line of :func:`irreducible_on_a_line`: fixed (the
engine is deterministic), and neither 0 nor ±1, where the torus's ``P² = (s² + w + 3)² − 16·w``
splits (its discriminant in ``w`` is ``64·(1 − s²)``)."""


def irreducible_modulo_a_prime(g: fmpq_mpoly) -> bool:
    """Whether ``g`` is shown irreducible over ``QQ`` (hence square-free) by its reduction modulo
    one of :data:`CERTIFYING_PRIMES` (docs/math.md §4): with ``g`` primitive in ``ZZ[x, …]``, a
    reduction of the same total degree that is irreducible over ``GF(p)``. ``False`` proves
    nothing (``x⁴ + y⁴`` splits modulo every prime)."""
    if g.total_degree() < 1:
        return False
    h = primitive(g)
    degree = h.total_degree()
    names = h.context().names()
    exponents = [tuple(int(e) for e in m) for m in h.monoms()]
    numerators = [c.p for c in h.coeffs()]
    for p in CERTIFYING_PRIMES:
        ring = nmod_mpoly_ctx.get(names, modulus=p)
        reduced = ring.from_dict({m: int(c % p) for m, c in zip(exponents, numerators)})
        if reduced.total_degree() != degree:
            continue  # p divides every coefficient of top degree: this reduction says nothing
        _, factors = reduced.factor()
        if len(factors) == 1 and factors[0][1] == 1:
            return True
    return False


def rational_surd(q: fmpq) -> tuple[fmpq, int]:
    """``√q = k·√d`` for a rational ``q > 0``: the rational ``k`` and the square-free integer ``d``."""
    n = fmpz(q.p) * fmpz(q.q)  # √(a/b) = √(ab)/b
    square, free = fmpz(1), fmpz(1)
    for p, e in n.factor():
        square *= p ** (e // 2)
        free *= p ** (e % 2)
    return fmpq(square, q.q), int(free)


@lru_cache(maxsize=16)
def _expanded_patterns(names: tuple[str, ...]) -> tuple[re.Pattern[str], re.Pattern[str]]:
    """The term and the factor patterns of :func:`expanded_terms` for the variables ``names``."""
    variable = "(?:" + "|".join(re.escape(n) for n in sorted(names, key=len, reverse=True)) + ")"
    term = re.compile(
        r"\s*([-+])?\s*(?:([0-9]+)(?:\s*/\s*([0-9]+))?)?"
        r"((?:\s*\*?\s*" + variable + r"(?:\s*(?:\*\*|\^)\s*[0-9]{1,6})?)*)\s*"
    )
    factor = re.compile("(" + variable + r")(?:\s*(?:\*\*|\^)\s*([0-9]+))?")
    return term, factor


def expanded_terms(
    text: str,
    names: Sequence[str] = ("x", "y", "z"),
    *,
    max_digits: int | None = None,
    max_degree: int | None = None,
) -> dict[Monomial, fmpq | int] | None:
    """The terms of an expanded polynomial with rational coefficients in ``names``
    (``3*x**2*y - 5/2*z + 1``, ``2x^2y - z``): one regular-expression pass, no syntax tree.
    ``None`` for anything else (parentheses, decimals, roots, ``=``, a number of more than
    ``max_digits`` digits, a term of degree above ``max_degree``). Zero terms are dropped."""
    term_pattern, factor_pattern = _expanded_patterns(tuple(names))
    index = {name: i for i, name in enumerate(names)}
    terms: dict[Monomial, fmpq | int] = {}
    position, end = 0, len(text)
    match_term, factors = term_pattern.match, factor_pattern.findall
    while position < end:
        match = match_term(text, position)
        if match is None or match.end() == position:
            return None
        sign, num, den, variables = match.groups()
        if (num is None and (not variables.strip() or variables.lstrip().startswith("*"))) or (
            position > 0 and sign is None
        ):
            return None  # an empty term, a '*' with nothing before it, two terms without a sign between them
        if max_digits is not None and (
            (num is not None and len(num) > max_digits) or (den is not None and len(den) > max_digits)
        ):
            return None
        if den is not None and int(den) == 0:
            return None
        monomial = [0] * len(names)
        for name, exponent in factors(variables) if variables else ():
            monomial[index[name]] += int(exponent) if exponent else 1
        if max_degree is not None and sum(monomial) > max_degree:
            return None
        value: fmpq | int = (int(num) if num is not None else 1) if den is None else fmpq(int(num or 1), int(den))
        key = tuple(monomial)
        previous = terms.get(key)
        value = -value if sign == "-" else value
        terms[key] = value if previous is None else previous + value
        position = match.end()
    return {m: c for m, c in terms.items() if c}
