"""The parameter domain of a rational map and the points it misses, stated in the formula files.

For every rational map, :class:`Coverage` states over which parameter domain it is defined and
which points it misses (docs/math.md, "Parameterizations"):

* **excluded parameter values**: the zeros of the denominators, as the irreducible factors
  of their product, with whether each has real zeros (decided exactly for factors in one
  parameter; stated as a curve ``g = 0`` of the parameter plane otherwise);
* **points reached only in a limit**: for each parameter ``p → ∞`` (the other one free), the
  limit of the map — a curve or a point of ``X`` that no finite value of ``p`` gives on that
  parameter line, such as the meridian at angle π of a rotation ``s ↦ ((1-s²)/(1+s²),
  2s/(1+s²))`` or the circle swept by the point at infinity of the profile — or the statement
  that the points run off to infinity (nothing affine is missed there).

Made when a file asks for it (:attr:`sorgui.export.formulas.Formula.coverage`), with sympy.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import sympy


@dataclass(frozen=True)
class Excluded:
    """One irreducible factor ``g`` of the denominators: the map is undefined where ``g = 0``.

    ``real_zeros`` is ``True``/``False`` when decided exactly (``g`` in one parameter), ``None``
    for a curve in two parameters; ``roots`` are then its exact roots: the real ones for a real
    parameterization, all of them for a complex one.
    """

    factor: sympy.Expr
    real_zeros: bool | None
    roots: tuple[sympy.Expr, ...] = ()


@dataclass(frozen=True)
class Limit:
    """What the map tends to as ``parameter → ∞`` with the other parameters free.

    ``point`` is the limit (expressions in the remaining parameters), or ``None`` when some
    coordinate tends to infinity there (points at infinity: nothing affine is missed).
    ``check`` is an exact test at one sample value ``v`` of the other parameter: ``(v, missed)``
    with ``missed`` true when no parameter value at all, complex ones included, maps to the
    limit point there (a Gröbner basis of ``N_i - P_i·D_i = 0, u·D - 1 = 0`` is ``[1]``);
    ``None`` when the map is too large for the test or the limit is a curve of two parameters.
    """

    parameter: sympy.Symbol
    point: tuple[sympy.Expr, ...] | None
    check: tuple[sympy.Expr, bool] | None = None
    finite: tuple[sympy.Expr, ...] | None = None
    """For a map of one parameter (a curve: a spine, a circle of centres), the finite parameter
    values that give the limit point as well (real ones for a real map); ``()`` when none does;
    ``None`` when not decided (coefficients beyond ``QQ``)."""


@dataclass(frozen=True)
class Coverage:
    """The parameter domain of a rational map and the points it misses (module docstring)."""

    parameters: tuple[sympy.Symbol, ...]
    real: bool
    excluded: tuple[Excluded, ...]
    limits: tuple[Limit, ...]

    def lines(self, style: CoverageStyle | None = None) -> list[str]:
        """The coverage in words, one statement per line, with formulas printed by ``style``."""
        st = style or CoverageStyle()
        names = ", ".join(st.expr(p) for p in self.parameters)
        space = (st.real if self.real else st.complex) + st.power(len(self.parameters))
        out = [f"parameter domain: {st.math(f'({names}) {st.element} {space}')}"]
        if not self.excluded:
            out.append("no denominator: defined for every parameter value")
        for item in self.excluded:
            out.append(f"undefined where {st.math(st.expr(item.factor) + ' = 0')}: {_zeros_text(item, self.real, st)}")
        for limit in self.limits:
            tends = st.math(f"{st.expr(limit.parameter)} {st.to} {st.infinity}")
            if limit.point is None:
                out.append(f"as {tends} the points run off to infinity: no affine point is missed there")
                continue
            point = st.math("(" + ", ".join(st.expr(c) for c in limit.point) + ")")
            rest = [p for p in self.parameters if p != limit.parameter]
            moving = [p for p in rest if any(c.has(p) for c in limit.point)]
            what = f"the curve {point} over {', '.join(st.expr(p) for p in moving)}" if moving else f"the point {point}"
            fixed = f" with {', '.join(st.expr(p) for p in rest)} fixed" if rest else ""
            if not rest and limit.finite != ():
                out.append(f"as {tends} the map tends to {what}" + _finite_text(limit, st))
                continue
            out.append(f"reached only as {tends}, by no finite {st.math(st.expr(limit.parameter))}{fixed}: {what}")
            if limit.check is not None and moving:
                value, missed = limit.check
                at = st.math(f"{st.expr(moving[0])} = {st.expr(value)}")
                out.append(
                    f"  checked exactly at {at}: "
                    + (
                        "no parameter value, complex ones included, gives that point: it is missed"
                        if missed
                        else "some other parameter value gives that point: it is not missed there"
                    )
                )
        return out


@dataclass(frozen=True)
class CoverageStyle:
    """How :meth:`Coverage.lines` prints formulas: sympy's syntax by default; the LaTeX, Maple
    and Mathematica writers pass their printers (``math`` wraps a formula, e.g. in ``$…$``)."""

    expr: Callable[[Any], str] = sympy.sstr
    math: Callable[[str], str] = str
    real: str = "R"
    complex: str = "C"
    element: str = "in"
    to: str = "->"
    infinity: str = "oo"
    power: Callable[[int], str] = field(default=lambda n: "" if n == 1 else f"^{n}")


def _finite_text(limit: Limit, st: CoverageStyle) -> str:
    """The end of the line of a curve's limit point that a finite parameter value gives too, or
    that was not decided."""
    if limit.finite is None:
        return f"; whether a finite {st.math(st.expr(limit.parameter))} gives it too was not decided"
    values = ", ".join(st.math(f"{st.expr(limit.parameter)} = {st.expr(v)}") for v in limit.finite)
    return f", which {values} gives too: no point is missed there"


def _zeros_text(item: Excluded, real: bool, st: CoverageStyle) -> str:
    if item.real_zeros is None:
        return "the real points of this curve of parameter values" if real else "a curve of parameter values"
    if real and not item.real_zeros:
        return "no real zeros"
    if not item.roots:
        return "it has real zeros"
    return ("the real zeros " if real else "the zeros ") + ", ".join(st.math(st.expr(r)) for r in item.roots)


def coverage(
    coordinates: tuple[sympy.Expr, ...], parameters: tuple[sympy.Symbol, ...], real: bool, limits: bool = True
) -> Coverage:
    """The domain and missed points of the rational map ``parameters ↦ coordinates``
    (``limits=False`` for a map of space such as ``τ``, where only the domain matters)."""
    fractions = [sympy.fraction(sympy.cancel(sympy.together(c))) for c in coordinates]
    factors: list[sympy.Expr] = []
    for _numerator, denominator in fractions:
        if not denominator.has(*parameters):
            continue
        for factor, _multiplicity in sympy.factor_list(denominator, *parameters)[1]:
            monic = sympy.Poly(factor, *parameters).monic().as_expr()
            if not any(sympy.expand(monic - known) == 0 for known in factors):
                factors.append(monic)
    excluded = tuple(_excluded(g, parameters, real) for g in factors)
    if not limits:
        return Coverage(parameters, real, excluded, ())
    return Coverage(
        parameters,
        real,
        excluded,
        tuple(_checked(_limit(fractions, p), fractions, parameters, real) for p in parameters),
    )


def _excluded(factor: sympy.Expr, parameters: tuple[sympy.Symbol, ...], real: bool) -> Excluded:
    used = [p for p in parameters if factor.has(p)]
    if len(used) > 1 and _positive_definite(factor, used):
        return Excluded(factor, False)  # s² + t² + 1: no real zero, the map is defined on all of R²
    if len(used) != 1:
        return Excluded(factor, None)
    poly = sympy.Poly(factor, used[0])
    roots = sympy.roots(poly)
    if sum(roots.values()) != poly.degree():  # no closed form: count the real roots instead
        if not (poly.domain.is_QQ or poly.domain.is_ZZ):
            return Excluded(factor, None)
        return Excluded(factor, poly.count_roots() > 0)
    real_roots = [r for r in roots if r.is_real]
    shown = real_roots if real else list(roots)
    return Excluded(factor, bool(real_roots), tuple(sorted(shown, key=sympy.default_sort_key)))


def _positive_definite(factor: sympy.Expr, parameters: list[sympy.Symbol]) -> bool:
    """Whether ``factor`` (or its negative) is a sum of even monomials with coefficients of one
    sign and a nonzero constant: positive at every real point, so it has no real zero."""
    try:
        poly = sympy.Poly(factor, *parameters)
    except sympy.PolynomialError:
        return False
    if not (poly.domain.is_QQ or poly.domain.is_ZZ):
        return False
    terms = poly.terms()
    signs = {c > 0 for _, c in terms}
    constant = any(not any(m) for m, _ in terms)
    return len(signs) == 1 and constant and all(e % 2 == 0 for m, _ in terms for e in m)


def _limit(fractions: list[tuple[sympy.Expr, sympy.Expr]], parameter: sympy.Symbol) -> Limit:
    """The limit as ``parameter → ∞`` of each ``numerator/denominator`` (generic other parameters)."""
    point = []
    for numerator, denominator in fractions:
        top = sympy.Poly(numerator, parameter)
        bottom = sympy.Poly(denominator, parameter)
        if top.degree() > bottom.degree():
            return Limit(parameter, None)
        leading = top.coeff_monomial(parameter ** bottom.degree()) if top.degree() == bottom.degree() else 0
        point.append(sympy.cancel(leading / bottom.LC()))
    return Limit(parameter, tuple(point))


CHECK_MAX_DEGREE = 6
"""The exact missed-point test runs for maps over ``QQ`` of total degree at most this (it takes
~0.05 s at 5)."""

SAMPLE_VALUES = (sympy.Rational(7, 3), sympy.Rational(-5, 11), sympy.Rational(13, 2))
"""Sample values of the free parameter for that test (the first where the limit is defined)."""


def _checked(
    limit: Limit, fractions: list[tuple[sympy.Expr, sympy.Expr]], parameters: tuple[sympy.Symbol, ...], real: bool
) -> Limit:
    """``limit`` with its exact missed-point test (see :class:`Limit`), when it is affordable."""
    rest = [p for p in parameters if p != limit.parameter]
    if limit.point is not None and not rest:
        return replace(limit, finite=_finite_values(limit, fractions, real))
    if limit.point is None or len(rest) != 1:
        return limit
    polys = [sympy.Poly(e, *parameters) for pair in fractions for e in pair]
    if max(p.total_degree() for p in polys) > CHECK_MAX_DEGREE or not all(
        p.domain.is_ZZ or p.domain.is_QQ for p in polys
    ):
        return limit  # over an algebraic field the Gröbner basis took minutes (a nearest surface's map over QQ(√21, i))
    other = rest[0]
    for value in SAMPLE_VALUES:
        if any(sympy.fraction(sympy.together(c))[1].subs(other, value) == 0 for c in limit.point):
            continue
        target = [sympy.cancel(c.subs(other, value)) for c in limit.point]
        u = sympy.Dummy("u")
        denominator = sympy.prod([d for _n, d in fractions])
        equations = [sympy.expand(n - pc * d) for (n, d), pc in zip(fractions, target)]
        basis = sympy.groebner([*equations, sympy.expand(u * denominator - 1)], u, *parameters, order="grevlex")
        return Limit(limit.parameter, limit.point, (value, list(basis.exprs) == [1]))
    return limit


def _finite_values(
    limit: Limit, fractions: list[tuple[sympy.Expr, sympy.Expr]], real: bool
) -> tuple[sympy.Expr, ...] | None:
    """The values ``t`` of a curve's parameter where ``N_i(t) − P_i·D_i(t) = 0`` for every
    coordinate and no ``D_i`` vanishes: those that give the limit point ``P`` (a spine
    ``4t/(t² − 1)`` along the axis tends to the origin, which ``t = 0`` gives too). Real ones for
    a real map; ``None`` over a field beyond ``QQ``."""
    assert limit.point is not None  # a limit point is checked
    t = limit.parameter
    common: sympy.Poly | None = None
    denominators = sympy.Poly(1, t, domain="QQ")
    for (numerator, denominator), coordinate in zip(fractions, limit.point):
        try:
            difference = sympy.Poly(sympy.expand(numerator - coordinate * denominator), t, domain="QQ")
            denominators *= sympy.Poly(denominator, t, domain="QQ")
        except (sympy.PolynomialError, sympy.CoercionFailed):
            return None
        common = difference if common is None else common.gcd(difference)
    if common is None or common.is_zero:
        return None
    while common.degree() > 0 and not common.gcd(denominators).is_one:
        common = common.exquo(common.gcd(denominators))
    if common.degree() <= 0:
        return ()
    roots = sympy.real_roots(common) if real else sympy.Poly(common).all_roots()
    return tuple(sorted(set(roots), key=sympy.default_sort_key))
