"""How precisely the input was printed: a rounding bound for every coefficient (docs/math.md §8).

A CAD system prints floating-point coefficients with a fixed number of digits, so a decimal
literal such as ``1.234567`` stands for any number within half a unit of its last printed
place (``±5e-7``). This module turns those digits into a bound ``e_α ≥ 0`` on the rounding of
every coefficient ``f_α`` of the expanded polynomial, by first-order propagation through the
syntax tree: sums add bounds, a product ``u·v`` has bound ``|u|·e_v + e_u·|v|`` (coefficientwise
absolute values), a power ``u^n`` has ``n·|u|^(n-1)·e_u``. Integer literals in an input that has
decimals are read as printed with the same number of significant digits as its most precise
decimal (``%g`` prints ``0.99999999997`` as ``1``); exponents are exact. When no printed
fraction ends in ``0``, the printer dropped trailing zeros (``%g`` prints ``15.44`` for
``15.44000000``), so a literal is never read as coarser than that many significant digits;
when some fraction ends in ``0`` (fixed-point printing, ``15.440000``), every literal's own
last place counts and integers are exact; so too when every decimal has the same number of
digits after the point and none has an exponent (``%.6f`` printing whose last digits happen
not to be ``0``).

The relative tolerance of the input is ``τ = ‖e‖₂ / ‖f‖₂`` over the printed coefficients; a
monomial the input does not print gets the smallest bound of a printed one. A tolerance
given by the user instead (``--tolerance τ``) spreads ``τ·‖f‖₂`` evenly over the monomials of
degree ≤ deg f. Every bound is at least ``FLOAT_FLOOR·max|f_α|``: the coefficients a CAD system
prints were computed in double precision and carry that much noise whatever it prints.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from math import comb
from typing import TypeAlias

from ..syntax import (
    Neg,
    Node,
    Num,
    Power,
    Product,
    Reciprocal,
    Sqrt,
    Sum,
    Var,
    number_parts,
    syntax_tree,
)

FLOAT_FLOOR = 4e-15
"""Relative noise (to the largest coefficient) of coefficients computed in double precision,
below any printed digit: about 18 ulp, a sum of products erring with the largest of them."""

TIE = 1.0 + 1e-12
"""A literal's rounding is half a unit in its last place with both ends included, and a little
over: a designed value that ends in that half (``4R² − 2(R² − r²) = −1370.965`` of a torus of
``R = 25.4``, ``r = 6.35``, printed ``-1370.96``) is at the very end, where the comparisons of a
scaled surface (:data:`.coefficients.WITHIN`) and of floats would cut it off."""

MAX_PRODUCTS = 2_000_000
"""Term products the propagation may spend; past this the bound is taken uniform (see below)."""

Monomial: TypeAlias = tuple[int, int, int]
FloatPoly: TypeAlias = dict[Monomial, float]
_VARIABLES: tuple[Monomial, Monomial, Monomial] = ((1, 0, 0), (0, 1, 0), (0, 0, 1))
"""The monomials ``x``, ``y``, ``z``, by the index of the variable."""


@dataclass(frozen=True)
class Rounding:
    """Bounds ``e_α`` on the rounding of the coefficients of ``f``.

    ``bounds`` holds the monomials that carry a bound of their own; every other monomial of
    degree ≤ ``degree`` has ``default``. ``tolerance`` is ``‖e‖₂/‖f‖₂``; ``source`` is
    ``"input"`` (from the printed digits) or ``"given"``; ``digits`` is the largest number of
    significant digits printed (``None`` when the tolerance was given). An infinite
    ``tolerance`` means the digits could not be read in floating point (a literal beyond it).
    ``read_from`` is the one literal whose digits every other number was read to, when a single
    decimal set them beside integers (``-57.999`` among ``1``, ``58``, ``441``): a printer that
    drops trailing zeros (``%g``) may have printed them with more.
    """

    bounds: dict[Monomial, float]
    default: float
    degree: int
    tolerance: float
    source: str
    digits: int | None
    read_from: str | None = field(default=None, compare=False)  # how it is printed, not a bound

    def bound(self, monomial: Monomial) -> float:
        """``e_α`` for the monomial ``α``."""
        return self.bounds.get(monomial, self.default)


def input_rounding(text: str, coefficients: FloatPoly) -> Rounding | None:
    """The rounding bounds read off the digits of ``text``; ``None`` if it prints no decimal.

    ``coefficients`` are the exact coefficients of the parsed ``f`` as floats.
    """
    tree = syntax_tree(text)
    literals = [node for node in _nodes(tree) if isinstance(node, Num)]
    decimals = [node for node in literals if _is_decimal(text, node)]
    if not decimals:
        return None
    digits = max(_significant_digits(text, node) for node in decimals)
    fixed_point = _fixed_point(text, decimals)
    floors = _float_floors(coefficients)
    floor = min(floors.values())
    degree = max(sum(m) for m in coefficients)
    try:
        propagated = _Propagation(text, digits, fixed_point).run(tree)
        if propagated is None:
            relative = max(
                _literal_bound(text, n, digits, fixed_point) / abs(float(n.value)) for n in decimals if n.value
            )
            errors = {m: relative * abs(c) for m, c in coefficients.items()}
        else:
            errors = {m: propagated.get(m, 0.0) for m in coefficients}
    except OverflowError:  # a literal or product beyond floating point: no bound can be read
        return Rounding({}, math.inf, degree, math.inf, "input", digits)
    bounds = {m: max(e, floors[sum(m)]) for m, e in errors.items()}
    printed = [e for e in errors.values() if e > 0.0]
    default = max(min(printed, default=floor), floor)
    widest = [node for node in decimals if _significant_digits(text, node) == digits]
    alone = len(widest) == 1 and not fixed_point and len(literals) > len(decimals)
    tolerance = _norm(bounds.values()) / _norm(coefficients.values())
    read_from = text[widest[0].start : widest[0].end] if alone else None
    return Rounding(bounds, default, degree, tolerance, "input", digits, read_from)


LARGE_PART = 10.0
"""A part size (:func:`.deviation.part_size`) above which the floor of a coefficient depends on its degree
(:func:`_float_floors`); below it :data:`FLOAT_FLOOR` is of the largest coefficient, as it always
was. A small part's floor, so taken, frees its low-degree coefficients by a few units of their
last digits; a large part's freed its high-degree ones by thousands."""


def _float_floors(coefficients: FloatPoly) -> dict[int, float]:
    """The floor of the bound of a coefficient of each degree: for a large part (size ``L`` above
    :data:`LARGE_PART`), :data:`FLOAT_FLOOR` of the largest coefficient of ``f(L·X)``, brought back
    to ``f``'s own (``L^-d`` for degree ``d``), never above that of ``f``'s largest coefficient;
    else that of ``f``'s largest coefficient. A part of size 4e4 has a constant term near 1e18 and
    quartic ones near 1: floored at 4e-15 of the constant, every coefficient of degree 2 to 4 was
    free to move by thousands, and a torus turned and printed with 10 digits came out as a
    nearest surface 383 units from it; the noise of a coefficient is that of the terms it is a
    sum of, whose size the scale sets."""
    from . import dense  # numpy: loaded here, where decimals are read, not with the module
    from .deviation import part_size

    degree = max(sum(m) for m in coefficients)
    top = max(abs(c) for c in coefficients.values())
    length = part_size(dense.from_terms(coefficients, degree))
    if length is None or not LARGE_PART < length < math.inf:
        return dict.fromkeys(range(degree + 1), FLOAT_FLOOR * top)
    scale = math.log(length)
    largest = max(math.log(abs(c)) + sum(m) * scale for m, c in coefficients.items() if c)
    floors = {}
    for d in range(degree + 1):
        try:
            floors[d] = min(math.exp(math.log(FLOAT_FLOOR) + largest - d * scale), FLOAT_FLOOR * top)
        except OverflowError:
            floors[d] = FLOAT_FLOOR * top
    return floors


def given_rounding(tolerance: float, coefficients: FloatPoly) -> Rounding:
    """Uniform bounds for a relative tolerance given by the user: ``e_α = τ·‖f‖₂/√N``."""
    degree = max(sum(m) for m in coefficients)
    count = comb(degree + 3, 3)
    top = max(abs(c) for c in coefficients.values())
    default = max(tolerance * _norm(coefficients.values()) / math.sqrt(count), FLOAT_FLOOR * top)
    return Rounding({}, default, degree, tolerance, "given", None)


def _norm(values: Iterable[float]) -> float:
    """The Euclidean norm, scaled so that coefficients near 1e200 do not overflow."""
    sizes = [abs(v) for v in values]
    top = max(sizes, default=0.0)
    if top == 0.0 or not math.isfinite(top):
        return top
    return top * math.sqrt(sum((v / top) ** 2 for v in sizes))


# --- reading the printed digits ---------------------------------------------------------------


def _nodes(node: Node) -> Iterator[Node]:
    """Every node of the tree, iteratively (pasted sums can be long)."""
    stack = [node]
    while stack:
        node = stack.pop()
        yield node
        match node:
            case Neg(arg=arg) | Reciprocal(arg=arg) | Sqrt(arg=arg):
                stack.append(arg)
            case Sum(terms=children) | Product(factors=children):
                stack.extend(children)
            case Power(base=base, exponent=exponent):
                stack += [base, exponent]


def _is_decimal(text: str, node: Num) -> bool:
    return any(ch in ".eEdD^" for ch in text[node.start : node.end])


def _literal(text: str, node: Num) -> tuple[str, str | None, str | None]:
    """The digits of a literal: whole part, fraction (or ``None``), exponent (or ``None``)."""
    return number_parts(text, node.start, node.end)


def _significant_digits(text: str, node: Num) -> int:
    """Significant digits of a literal: ``0.00120`` has 3, ``1.5e-3`` has 2."""
    whole, fraction, _ = _literal(text, node)
    return max(len((whole + (fraction or "")).lstrip("0")), 1)


def _fixed_point(text: str, decimals: list[Num]) -> bool:
    """Whether the input was printed in fixed point (``%.6f``): some printed fraction ends in
    ``0``, or every decimal has the same number of digits after the point and no exponent."""
    fractions = [_fraction(text, node) for node in decimals]
    if any(f.endswith("0") for f in fractions):
        return True
    exponents = any(ch in "eE" for node in decimals for ch in text[node.start : node.end])
    return len(decimals) >= 3 and not exponents and len({len(f) for f in fractions}) == 1


def _fraction(text: str, node: Num) -> str:
    return _literal(text, node)[1] or ""


def _literal_bound(text: str, node: Num, digits: int, fixed_point: bool) -> float:
    """Half a unit in the last printed place of a literal (:data:`TIE`), read as the module docstring says; 0
    for a superscript (``x²``, ``10⁻³``), an exponent and exact."""
    if not text[node.start].isascii():
        return 0.0
    _, fraction, exponent = _literal(text, node)
    value = abs(float(node.value))
    decimal = fraction is not None or exponent is not None
    if not decimal and fixed_point:
        return 0.0
    by_digits = TIE * 0.5 * 10.0 ** (math.floor(math.log10(value)) - digits + 1) if value else 0.0
    if not decimal:
        return by_digits
    own = TIE * 0.5 * 10.0 ** (int(exponent or 0) - len(fraction or ""))
    return own if fixed_point else min(own, by_digits) if value else own


class _Propagation:
    """First-order propagation of literal rounding through the syntax tree, in floats."""

    def __init__(self, text: str, digits: int, fixed_point: bool) -> None:
        self.text = text
        self.digits = digits
        self.fixed_point = fixed_point
        self.work = 0

    def run(self, tree: Node) -> FloatPoly | None:
        """The bound of every coefficient, or ``None`` when the expansion is too large."""
        try:
            _, error = self._pair(tree)
        except _TooLarge:
            return None
        return error

    def _pair(self, node: Node) -> tuple[FloatPoly, FloatPoly]:
        """``(value, bound)`` of a subtree as float polynomials."""
        value: FloatPoly
        error: FloatPoly
        match node:
            case Num():
                return {(0, 0, 0): float(node.value)}, {
                    (0, 0, 0): _literal_bound(self.text, node, self.digits, self.fixed_point)
                }
            case Var():
                return {_VARIABLES[node.index]: 1.0}, {}
            case Neg():
                value, error = self._pair(node.arg)
                return {m: -c for m, c in value.items()}, error
            case Sum():
                value = {}
                error = {}
                for term in node.terms:
                    v2, e2 = self._pair(term)
                    _accumulate(value, v2)
                    _accumulate(error, e2)
                return value, error
            case Product():
                value, error = self._pair(node.factors[0])
                for factor in node.factors[1:]:
                    if isinstance(factor, Reciprocal):
                        c, e = self._constant(factor.arg)
                        value = {m: v / c for m, v in value.items()}
                        error = {m: ev / abs(c) + abs(value.get(m, 0.0)) * e / abs(c) for m, ev in error.items()}
                        continue
                    v2, e2 = self._pair(factor)
                    value, error = self._times(value, error, v2, e2)
                return value, error
            case Power():
                n = self._constant(node.exponent)[0]
                if n != int(n) or n < 0:  # a surd such as 2^(1/2): a constant
                    base, e = self._constant(node.base)
                    return {(0, 0, 0): base**n}, {(0, 0, 0): abs(n * base ** (n - 1)) * e}
                return self._power(*self._pair(node.base), int(n))
            case Sqrt():
                c, e = self._constant(node.arg)
                root = math.sqrt(abs(c))
                return {(0, 0, 0): root}, {(0, 0, 0): e / (2.0 * root) if root else 0.0}
        raise TypeError(node)

    def _constant(self, node: Node) -> tuple[float, float]:
        value, error = self._pair(node)
        return value.get((0, 0, 0), 0.0), error.get((0, 0, 0), 0.0)

    def _power(self, value: FloatPoly, error: FloatPoly, n: int) -> tuple[FloatPoly, FloatPoly]:
        result: FloatPoly = {(0, 0, 0): 1.0}
        bound: FloatPoly = {}
        for _ in range(n):
            result, bound = self._times(result, bound, value, error)
        return result, bound

    def _times(self, v1: FloatPoly, e1: FloatPoly, v2: FloatPoly, e2: FloatPoly) -> tuple[FloatPoly, FloatPoly]:
        self.work += len(v1) * len(v2) + len(v1) * len(e2) + len(e1) * len(v2)
        if self.work > MAX_PRODUCTS:
            raise _TooLarge
        value = _product(v1, v2, signed=True)
        error = _product({m: abs(c) for m, c in v1.items()}, e2, signed=False)
        _accumulate(error, _product(e1, {m: abs(c) for m, c in v2.items()}, signed=False))
        return value, error


class _TooLarge(Exception):
    """The propagation would cost more than :data:`MAX_PRODUCTS` term products."""


def _accumulate(total: FloatPoly, part: FloatPoly) -> None:
    for m, c in part.items():
        total[m] = total.get(m, 0.0) + c


def _product(a: FloatPoly, b: FloatPoly, *, signed: bool) -> FloatPoly:
    result: FloatPoly = {}
    for (i, j, k), c in a.items():
        for (p, q, r), d in b.items():
            m = (i + p, j + q, k + r)
            result[m] = result.get(m, 0.0) + c * d
    return result if signed else {m: abs(c) for m, c in result.items()}
