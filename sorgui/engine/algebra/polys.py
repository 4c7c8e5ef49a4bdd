"""Exact polynomials over the coefficient field K: one facade over sympy and python-flint.

The engine's canonical polynomial is sympy's sparse ``PolyElement`` over a domain ``K``: ``QQ``
or a real algebraic field ``QQ(sqrt(n1), sqrt(n2), ...)`` (docs/math.md: ``K ⊂ R``). Algorithm choice
is made here and nowhere else: the heavy operations (composition, factorization) convert to
python-flint's ``fmpq_mpoly``, which is orders of magnitude faster than pure Python; over an
algebraic field through :mod:`.numberfields` (the square roots as extra variables, factoring by
Trager's norm method).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from fractions import Fraction
from functools import lru_cache
from typing import Any, TypeAlias

import sympy
from flint import fmpq, fmpq_mpoly, fmpq_mpoly_ctx
from sympy.polys.domains import QQ
from sympy.polys.domains.domain import Domain
from sympy.polys.rings import PolyElement, PolyRing, ring

from . import numberfields, sympy_fixes
from .rationals import Monomial, terms_str
from .rationals import factor as rational_factor

if QQ.dtype is not fmpq:  # sympy was imported before sorgui, with other ground types
    raise ImportError(
        "sorgui needs sympy's flint ground types: import sorgui before sympy, or set SYMPY_GROUND_TYPES=flint"
    )


sympy_fixes.install()

Poly: TypeAlias = PolyElement
"""A polynomial of the engine: sympy's sparse ``PolyElement`` over ``K``."""

XYZ = ("x", "y", "z")


# --- the coefficient field K -------------------------------------------------------------


@lru_cache(maxsize=64)
def number_field(radicands: tuple[int, ...] = ()) -> Domain:
    """The real field ``QQ(sqrt(n) for n in radicands)``; ``QQ`` when there are none.

    Radicands are square-free integers > 1 (the parser reduces ``sqrt(8)`` to ``2*sqrt(2)``).
    """
    roots = sorted(set(radicands))
    if not roots:
        return QQ
    return QQ.algebraic_field(*[sympy.sqrt(n) for n in roots])


def is_rational_field(K: Domain) -> bool:
    """True when ``K`` is ``QQ`` (the flint fast path applies)."""
    return bool(K == QQ)


def field_name(K: Domain) -> str:
    """A readable name of ``K``: ``QQ`` or ``QQ(sqrt(2), sqrt(3))``."""
    if is_rational_field(K):
        return "QQ"
    gens = ", ".join(str(g) for g in field_generators(K))
    return f"QQ({gens})"


def field_generators(K: Domain) -> list[sympy.Expr]:
    """The algebraic numbers that generate ``K`` over ``QQ`` (the square roots given by the user)."""
    if is_rational_field(K):
        return []
    return list(K.orig_ext) if getattr(K, "orig_ext", None) else [K.ext.as_expr()]


def to_expr(K: Domain, c: Any) -> sympy.Expr:
    """The coefficient ``c ∈ K`` as an exact sympy expression (``sqrt(2)/2``)."""
    return K.to_sympy(c)


def to_str(K: Domain, c: Any) -> str:
    """``c ∈ K`` as a string that ``sympy.sympify`` reads back exactly (``"3/5"``)."""
    return str(to_expr(K, c))


def from_rational(K: Domain, q: Fraction | int) -> Any:
    """The rational number ``q`` as an element of ``K``."""
    q = Fraction(q)
    return K.convert(QQ(q.numerator, q.denominator))


def sqrt_in_field(K: Domain, c: Any) -> Any | None:
    """A square root of ``c`` in ``K``, or ``None`` when ``c`` is not a square in ``K``."""
    if K.is_zero(c):
        return K.zero
    if is_rational_field(K):
        q = QQ.convert(c)
        root = sympy.sqrt(sympy.Rational(int(QQ.numer(q)), int(QQ.denom(q))))
        return QQ.from_sympy(root) if root.is_Rational else None
    vector = numberfields.element_to_radicals(K, c) if numberfields.supports(K) else {}
    if set(vector) == {0}:  # a rational number: its root is a radical monomial (fast path)
        return numberfields.rational_sqrt(K, vector[0])
    t = sympy.Symbol("t")
    gens = field_generators(K)
    _, factors = sympy.factor_list(t**2 - to_expr(K, c), t, extension=gens or None)
    for g, _ in factors:
        p = sympy.Poly(g, t)
        if p.degree() == 1:
            root = -p.coeff_monomial(1) / p.coeff_monomial(t)
            value = K.from_sympy(sympy.nsimplify(root) if not gens else root)
            return value if K.to_sympy(value).is_nonnegative is not False else -value
    return None


# --- rings and conversions ---------------------------------------------------------------


@lru_cache(maxsize=256)
def poly_ring(names: tuple[str, ...], K: Domain) -> PolyRing:
    """The ring ``K[names]`` (cached, so rings compare equal across calls)."""
    R, *_ = ring(",".join(names), K)
    return R


@lru_cache(maxsize=256)
def _flint_ctx(nvars: int) -> fmpq_mpoly_ctx:
    names = tuple(f"v{i}" for i in range(nvars))
    return fmpq_mpoly_ctx.get(names, "lex")


def to_flint(f: Poly) -> fmpq_mpoly:
    """``f ∈ QQ[...]`` as a flint ``fmpq_mpoly`` (the fast representation)."""
    return _flint_ctx(f.ring.ngens).from_dict(dict(f.items()))


def from_flint(g: fmpq_mpoly, R: PolyRing) -> Poly:
    """The flint polynomial ``g`` as an element of ``R`` (over ``QQ``)."""
    return R.from_dict({tuple(map(int, m)): c for m, c in g.to_dict().items()})


def compose(f: Poly, images: Sequence[Poly]) -> Poly:
    """``f(images[0], images[1], ...)``: all images in one common target ring.

    This is the workhorse of the profile ``p̃(s, r) = f(c + s·a + r·u)`` and of every identity
    check (docs/math.md §3).
    """
    target = next(h.ring for h in images if isinstance(h, PolyElement))
    # A constant image may arrive as a bare coefficient (``c + 0·s`` is ``c`` in sympy).
    images = [h if isinstance(h, PolyElement) else target.ground_new(h) for h in images]
    if is_rational_field(f.ring.domain) and is_rational_field(target.domain):
        ctx = _flint_ctx(target.ngens)
        g = to_flint(f).compose(*[to_flint(h) for h in images], ctx=ctx)
        return from_flint(g, target)
    if is_rational_field(target.domain):
        images = [h.set_ring(poly_ring(tuple(map(str, target.symbols)), f.ring.domain)) for h in images]
    if numberfields.supports(images[0].ring.domain):
        return numberfields.compose(f, images)
    return _compose_terms(f, images)


def _compose_terms(f: Poly, images: Sequence[Poly]) -> Poly:
    """``f(images)`` term by term in sympy (fields other than real multiquadratic ones)."""
    target = images[0].ring
    result = target.zero
    powers: dict[tuple[int, int], Poly] = {}
    for monom, coeff in f.items():
        term = target.ground_new(target.domain.convert(coeff, f.ring.domain))
        for i, e in enumerate(monom):
            if e:
                if (i, e) not in powers:
                    powers[(i, e)] = images[i] ** e
                term = term * powers[(i, e)]
        result += term
    return result


def power(f: Poly, n: int, charge: Callable[[int], None] | None = None) -> Poly:
    """``f^n`` (``n ≥ 1``) by repeated multiplication, which is cheaper than squaring for dense
    polynomials; over ``QQ`` in flint. ``charge`` is told the number of coefficient products of
    each step before it is done (the parser's work limit)."""
    if is_rational_field(f.ring.domain):
        base = to_flint(f)
        result = base
        for _ in range(n - 1):
            if charge is not None:
                charge(len(result) * len(base))
            result = result * base
        return from_flint(result, f.ring)
    product = f
    for _ in range(n - 1):
        if charge is not None:
            charge(len(product) * len(f))
        product = product * f
    return product


def derivative(f: Poly, i: int) -> Poly:
    """``∂f/∂(i-th variable)``."""
    if is_rational_field(f.ring.domain):
        return from_flint(to_flint(f).derivative(i), f.ring)
    return f.diff(f.ring.gens[i])


def factor(f: Poly) -> tuple[Any, list[tuple[Poly, int]]]:
    """``f = c · Π gᵢ^eᵢ`` over ``K``, with monic-content factors sorted deterministically."""
    if f.is_ground:
        return f.LC if f else f.ring.domain.zero, []
    if is_rational_field(f.ring.domain):
        factors = [(from_flint(g, f.ring), e) for g, e in rational_factor(to_flint(f))]
    elif numberfields.supports(f.ring.domain) and numberfields.norm_degree(f) <= numberfields.MAX_NORM_DEGREE:
        factors = numberfields.factor(f)[1]
    else:  # the norm would be too large for flint's factorization over QQ: sympy's own route
        factors = f.factor_list()[1]
    factors = [_normalize_sign(g, e) for g, e in factors]
    K = f.ring.domain
    lead = K.one
    for g, e in factors:  # the leading coefficient is multiplicative: no need to expand the product
        lead *= K.convert(g.LC) ** e
    content = K.quo(f.LC, lead)
    factors.sort(key=lambda ge: (ge[0].degree() if ge[0] else 0, poly_str(ge[0])))  # as rationals.factor
    return content, factors


def power_of_a_plane(f: Poly) -> bool:
    """Whether ``f`` is a power of one linear polynomial: its zero set is one plane."""
    if total_degree(f) == 1:
        return True
    factors = factor(f)[1]
    return len(factors) == 1 and total_degree(factors[0][0]) == 1


def _normalize_sign(g: Poly, e: int) -> tuple[Poly, int]:
    """Make the leading coefficient of a factor positive, so printed factors are stable."""
    K = g.ring.domain
    lc = K.to_sympy(g.LC)
    return (-g if lc.is_negative else g), e


def primitive(f: Poly) -> Poly:
    """``f`` scaled to integer coefficients with gcd 1 and a positive leading coefficient (over QQ).

    Over an algebraic field only the leading coefficient is normalised to 1.
    """
    if not f:
        return f
    K = f.ring.domain
    if is_rational_field(K):
        _, g = f.clear_denoms()
        g = g.primitive()[1]
        return -g if g.LC < 0 else g
    return f.monic()


def poly_str(f: Poly) -> str:
    """``f`` as a string that sympy (and the project's parser) reads back exactly
    (:func:`.rationals.terms_str`: terms in decreasing total degree).

    The string is written directly from the terms: sympy's printer needs seconds for the
    thousands of terms of a degree-30 surface.
    """
    K = f.ring.domain
    names = [str(g) for g in f.ring.symbols]
    if is_rational_field(K):
        return terms_str(names, f.terms())
    return terms_str(names, f.terms(), lambda c: _signed_coefficient(K, c))


def _signed_coefficient(K: Domain, c: Any) -> tuple[bool, str]:
    """The sign of a coefficient in an algebraic field and the text of its magnitude
    (parenthesised when a sum)."""
    expr = K.to_sympy(c)
    negative = expr.could_extract_minus_sign()
    text = str(-expr if negative else expr)
    return negative, f"({text})" if isinstance(-expr if negative else expr, sympy.Add) else text


def total_degree(f: Poly) -> int:
    """The total degree of ``f`` (``-1`` for the zero polynomial)."""
    if not f:
        return -1
    monomials: Iterator[Monomial] = f.itermonoms()
    return max(sum(m) for m in monomials)
