"""Rational sphere families, characteristic circles and parameterizations of canal surfaces
(docs/math.md §9).

* ``m(t), ρ(t)`` of a genus-0 SMAT curve: its plane model ``G(u, v)`` is parameterized
  (:func:`sorgui.engine.singular.curves.parametrize`), and the coordinates are rational functions of ``(u, v)`` on
  the curve (:mod:`.spine`, shape lemma). The result is verified by substitution into every
  equation of the SMAT ideal.
* Characteristic circles: centre ``c = m − (ρ′/(2|m′|²))·m′``, radius² ``R² = ρ − ρ′²/(4|m′|²)``,
  in the plane through ``c`` perpendicular to ``m′``.
* The radical parameterization ``c(t) + R(t)(cos θ·e₁ + sin θ·e₂)`` with ``e₁ = m′ × a``,
  ``e₂ = m′ × e₁`` normalised, verified by substitution into ``f`` (with
  ``cos θ = (1 − s²)/(1 + s²)``, ``sin θ = 2s/(1 + s²)`` and the square roots as new variables
  reduced by their squares).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, TypeVar

import sympy
from flint import fmpq, fmpq_mpoly, fmpq_mpoly_ctx, fmpq_poly

from ..algebra.fractions import (
    RationalFunction,
    embed,
    evaluate,
    factored,
    from_expr,
    homogeneous_numerator,
    lcm_all,
    poly_expr,
    square_root_parts,
)
from ..algebra.fractions import square_root as fraction_sqrt
from ..algebra.polys import Poly, to_flint
from ..algebra.rationals import context
from ..errors import AnalysisError
from ..singular.curves import CurveParametrization
from .spine import SMAT_NAMES, SmatCurve

T = sympy.Symbol("t")
Item = TypeVar("Item")
THETA = sympy.Symbol("theta")


FAMILY_RING = ("t", "s")
"""The ring of a family over ``QQ``: its functions of ``t``, and ``s`` of the parameterization."""
S = sympy.Symbol("s")


@dataclass(frozen=True)
class ExactFamily:
    """A sphere family over ``QQ`` as reduced rational functions of ``t`` (flint): ``m``, ``ρ``,
    and the characteristic circles' centre ``c``, radius² ``R²`` and plane normal ``m′``."""

    m: tuple[RationalFunction, RationalFunction, RationalFunction]
    rho: RationalFunction
    center: tuple[RationalFunction, RationalFunction, RationalFunction]
    radius_squared: RationalFunction
    normal: tuple[RationalFunction, RationalFunction, RationalFunction]


@dataclass(frozen=True)
class RationalFamily:
    """A verified rational sphere family ``m(t)``, ``ρ(t)`` (coefficients in ``QQ`` or in the
    field of ``generators``) and its characteristic circles, as sympy expressions (factored, for
    the report) and, over ``QQ``, as the :class:`ExactFamily` the checks compute with."""

    m: tuple[sympy.Expr, sympy.Expr, sympy.Expr]
    rho: sympy.Expr
    generators: tuple[sympy.Expr, ...]
    verified: bool
    center: tuple[sympy.Expr, sympy.Expr, sympy.Expr]
    radius_squared: sympy.Expr
    normal: tuple[sympy.Expr, sympy.Expr, sympy.Expr]
    exact: ExactFamily | None = None

    @property
    def over_qq(self) -> bool:
        return not self.generators


def recover_family(curve: SmatCurve, plane: CurveParametrization) -> RationalFamily:
    """``m(t), ρ(t)`` from the parameterization ``(u(t), v(t))`` of the plane model and the
    inverse of the projection, verified by substitution into every SMAT equation."""
    if curve.inverse is None:
        raise AnalysisError("the plane model of the SMAT curve is not known to be birational")
    if not plane.generators:
        return _recover_over_qq(curve, plane)
    u, v = sympy.Symbol("u"), sympy.Symbol("v")
    subs = {u: plane.x, v: plane.y}
    coords = [sympy.cancel(h.subs(subs, simultaneous=True)).subs(plane.parameter, T) for h in curve.inverse]
    m = (coords[0], coords[1], coords[2])
    rho = coords[3]
    point = dict(zip((sympy.Symbol(n) for n in SMAT_NAMES), coords))
    verified = all(sympy.cancel(g.as_expr().subs(point, simultaneous=True)) == 0 for g in curve.equations)
    center, radius_squared, normal = characteristic_circles(m, rho)
    return RationalFamily(m, rho, tuple(plane.generators), verified, center, radius_squared, normal)


def _recover_over_qq(curve: SmatCurve, plane: CurveParametrization) -> RationalFamily:
    """:func:`recover_family` over ``QQ``, in reduced flint fractions: the inverse of the
    projection composed with ``(u(t), v(t))``, and each SMAT equation evaluated there."""
    ring = context(FAMILY_RING)
    uv = (plane.x, plane.y)
    at = tuple(from_expr(c, [plane.parameter], ring) for c in uv)
    coords = []
    for h in curve.inverse or ():
        H = from_expr(h, sympy.symbols("u v"))
        coords.append(_at(H.num, at) / _at(H.den, at))
    verified = all(_at(to_flint(g), coords).is_zero() for g in curve.equations)
    m, rho = (coords[0], coords[1], coords[2]), coords[3]
    dm = tuple(c.derivative(0) for c in m)
    drho = rho.derivative(0)
    n2 = dm[0] * dm[0] + dm[1] * dm[1] + dm[2] * dm[2]
    center = _three([c - drho / (2 * n2) * d for c, d in zip(m, dm)])
    exact = ExactFamily(m, rho, center, rho - drho * drho / (4 * n2), _three(dm))
    return RationalFamily(
        _three([_shown(c) for c in m]),
        _shown(rho),
        (),
        verified,
        _three([_shown(c) for c in exact.center]),
        _shown(exact.radius_squared),
        _three([_shown(c) for c in exact.normal]),
        exact,
    )


def _three(values: Sequence[Item]) -> tuple[Item, Item, Item]:
    """The three coordinates of a point."""
    return values[0], values[1], values[2]


def _at(p: fmpq_mpoly, point: Sequence[RationalFunction]) -> RationalFunction:
    """The polynomial ``p`` at a point of rational functions."""
    return evaluate(zip(p.monoms(), p.coeffs()), point)


def _shown(f: RationalFunction) -> sympy.Expr:
    """``f`` factored, in ``t`` (and ``s``), as the report prints it."""
    return factored(f, (T, S))


def characteristic_circles(
    m: tuple[sympy.Expr, sympy.Expr, sympy.Expr],
    rho: sympy.Expr,
) -> tuple[tuple[sympy.Expr, sympy.Expr, sympy.Expr], sympy.Expr, tuple[sympy.Expr, sympy.Expr, sympy.Expr]]:
    """``c(t)``, ``R²(t)`` and the plane normal ``m′(t)`` of the characteristic circles."""
    dm = tuple(sympy.diff(c, T) for c in m)
    drho = sympy.diff(rho, T)
    n2 = sum(d * d for d in dm)
    center = _three([sympy.factor(sympy.cancel(c - drho / (2 * n2) * d)) for c, d in zip(m, dm)])
    radius_squared = sympy.factor(sympy.cancel(rho - drho**2 / (4 * n2)))
    normal = _three([sympy.factor(sympy.cancel(d)) for d in dm])
    return center, radius_squared, normal


def frame(normal: tuple[sympy.Expr, ...]) -> tuple[tuple[sympy.Expr, ...], tuple[sympy.Expr, ...]]:
    """Two vectors ``e₁ = n × a``, ``e₂ = n × e₁`` perpendicular to ``n`` (``a`` a coordinate
    axis not parallel to ``n``), not normalised."""
    for a in ((1, 0, 0), (0, 1, 0), (0, 0, 1)):
        e1 = _cross(normal, a)
        if any(sympy.cancel(c) != 0 for c in e1):
            return e1, _cross(normal, e1)
    raise AnalysisError("the spine has a vanishing tangent")


def _cross(u: tuple[Any, ...], v: tuple[Any, ...]) -> tuple[Any, Any, Any]:
    """``u × v`` for vectors of sympy expressions or of :class:`RationalFunction` (``v`` may hold integers)."""
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


def radical_parametrization(family: RationalFamily) -> tuple[sympy.Expr, sympy.Expr, sympy.Expr]:
    """``c(t) + R(t)(cos θ·e₁/|e₁| + sin θ·e₂/|e₂|)``: exact, with square roots where the
    squares of ``|e₁|``, ``|e₂|``, ``R`` are not squares of rational functions (where they are,
    the rational root is taken: its sign only turns or mirrors the angle on the same circle)."""
    if family.exact is not None:
        return _exact_radical(family.exact)
    e1, e2 = frame(family.normal)
    n1 = square_root(sum(c * c for c in e1))
    n2 = square_root(sum(c * c for c in e2))
    R = square_root(family.radius_squared)
    return _three(
        [
            c
            + sympy.factor(sympy.cancel(R * a / n1)) * sympy.cos(THETA)
            + sympy.factor(sympy.cancel(R * b / n2)) * sympy.sin(THETA)
            for c, a, b in zip(family.center, e1, e2)
        ]
    )


def _exact_radical(exact: ExactFamily) -> tuple[sympy.Expr, sympy.Expr, sympy.Expr]:
    """:func:`radical_parametrization` of a family over ``QQ``: the coefficient of ``cos θ`` is
    ``e₁·√(R²/|e₁|²)``, of ``sin θ`` ``e₂·√(R²/|e₂|²)``, their rational parts in flint."""
    e1, e2 = exact_frame(exact.normal)
    terms = []
    for e, angle in ((e1, sympy.cos(THETA)), (e2, sympy.sin(THETA))):
        q, c, N, D = square_root_parts(exact.radius_squared / sum((x * x for x in e[1:]), e[0] * e[0]))
        root = sympy.sqrt(sympy.Rational(int(c.p), int(c.q))) * sympy.sqrt(_shown(RationalFunction.of(N)))
        root /= sympy.sqrt(_shown(RationalFunction.of(D)))
        terms.append([_shown(x * q) * root * angle for x in e])
    return _three([_shown(c) + a + b for c, a, b in zip(exact.center, *terms)])


def square_root(square: sympy.Expr) -> sympy.Expr:
    """A square root of the rational function ``square``, written ``q·√P``: the square factors
    taken out, the denominator's odd factors moved into the polynomial radicand ``P`` (a
    rational function when ``P`` is 1). A negative constant stays under the root; a non-real one
    (a family whose circles are not real) raises :class:`AnalysisError`."""
    square = sympy.factor(sympy.cancel(square))
    if not (square.free_symbols <= {T} and square.is_rational_function(T)):
        return sympy.sqrt(square)
    outside, inside = sympy.Integer(1), sympy.Integer(1)
    for part, sign in zip(sympy.fraction(square), (1, -1)):
        constant, factors = sympy.factor_list(part, T)
        if constant.is_extended_real is not True:
            raise AnalysisError(f"the radius of the circles needs the square root of the non-real {constant}")
        outside *= sympy.sqrt(abs(constant)) ** sign
        if constant < 0:
            inside = -inside
        for g, e in factors:
            outside *= g ** (sign * (e // 2))
            if e % 2:
                inside *= g
                outside *= g ** min(sign, 0)
    return outside * sympy.sqrt(inside)


def rational_root(square: sympy.Expr) -> sympy.Expr | None:
    """A rational function of ``t`` over ``QQ`` whose square is ``square``, or ``None``."""
    root = square_root(square)
    if root.has(sympy.I) or any(p.exp == sympy.S.Half or p.exp == -sympy.S.Half for p in root.atoms(sympy.Pow)):
        return None
    return root


def verify_radical(f: Poly, family: RationalFamily) -> bool:
    """Whether ``f`` vanishes on every characteristic circle, exactly: ``f(c + a·e₁ + b·e₂)``, a
    polynomial in ``t, a, b`` (denominators cleared), reduced modulo the circle
    ``a²|e₁|² + b²|e₂|² = R²`` (``a²`` replaced), must be zero. This is the radical
    parameterization substituted into ``f`` with ``(a, b) = R(cos θ/|e₁|, sin θ/|e₂|)``. Over
    ``QQ`` only.
    """
    exact = family.exact
    if exact is None:
        return False
    e1, e2 = exact_frame(exact.normal)
    ctx = context(("t", "a", "b"))
    _, a, b = ctx.gens()
    rows = (*exact.center, *e1, *e2)
    den = lcm_all(r.den for r in rows)
    D = embed(den, ctx)
    coords = []
    for i in range(3):
        parts = [embed(rows[j].num * (den / rows[j].den), ctx) for j in (i, 3 + i, 6 + i)]
        coords.append(parts[0] + a * parts[1] + b * parts[2])
    g = to_flint(f)
    value = homogeneous_numerator(zip(g.monoms(), g.coeffs()), coords, D, ctx)
    n1, n2 = (sum((c * c for c in e[1:]), e[0] * e[0]) for e in (e1, e2))
    common = lcm_all((n1.den, n2.den, exact.radius_squared.den))
    lead = embed(n1.num * (common / n1.den), ctx)
    rest = embed(n2.num * (common / n2.den), ctx) * b * b - embed(
        exact.radius_squared.num * (common / exact.radius_squared.den), ctx
    )
    return reduce_square(value, 1, lead, -rest, ctx).is_zero()


def exact_frame(
    normal: tuple[RationalFunction, ...],
) -> tuple[tuple[RationalFunction, ...], tuple[RationalFunction, ...]]:
    """:func:`frame` of rational functions over ``QQ``."""
    zero = normal[0] - normal[0]
    for k in range(3):
        a = tuple(zero + (1 if i == k else 0) for i in range(3))
        e1 = _cross(normal, a)
        if any(not c.is_zero() for c in e1):
            return e1, _cross(normal, e1)
    raise AnalysisError("the spine has a vanishing tangent")


def reduce_square(p: fmpq_mpoly, index: int, A: fmpq_mpoly, B: fmpq_mpoly, ctx: fmpq_mpoly_ctx) -> fmpq_mpoly:
    """``A^k·p`` with ``(generator index)²`` replaced by ``B/A`` (``k`` half the degree), so that
    ``p`` vanishes on ``A·g² = B`` exactly when the result is zero."""
    top = max((m[index] for m in p.monoms()), default=0) // 2
    out = ctx.from_dict({})
    for monom, coeff in zip(p.monoms(), p.coeffs()):
        k = monom[index] // 2
        rest = list(monom)
        rest[index] -= 2 * k
        out += ctx.from_dict({tuple(rest): coeff}) * B**k * A ** (top - k)
    return out


def family_resultant_certificate(f: Poly, family: RationalFamily) -> bool:
    """Whether ``f`` divides ``Res_t(S, ∂S/∂t)`` for ``S = L·(|X − m(t)|² − ρ(t))`` (``L`` clears
    the denominators): the envelope certificate of a rational family over ``QQ``."""
    ctx = fmpq_mpoly_ctx.get(("x", "y", "z", "t"), "lex")
    x, y, z, t = ctx.gens()
    fracs = [sympy.fraction(sympy.cancel(c)) for c in (*family.m, family.rho)]
    polys = [(_univariate(n), _univariate(d)) for n, d in fracs]
    L = fmpq_poly(1)
    for _n, d in polys[:3]:
        L = _lcm(L, d * d)
    L = _lcm(L, polys[3][1])
    Lc = _lift(L, ctx)
    S = Lc * (x * x + y * y + z * z)
    const = fmpq_poly(0)
    for (n, d), X in zip(polys[:3], (x, y, z)):
        S -= 2 * X * _lift(n * (L / d), ctx)
        const += n * n * (L / (d * d))
    const -= polys[3][0] * (L / polys[3][1])
    S += _lift(const, ctx)
    res = S.resultant(S.derivative(3), "t")
    F = ctx.from_dict({(*m, 0): c for m, c in zip(to_flint(f).monoms(), to_flint(f).coeffs())})
    return not res.is_zero() and (res % F).is_zero()


def _univariate(expr: sympy.Expr) -> fmpq_poly:
    p = sympy.Poly(expr, T)
    if p.is_zero:
        return fmpq_poly(0)
    coeffs: list[fmpq | int] = [0] * (p.degree() + 1)
    for (e,), c in p.terms():
        coeffs[e] = fmpq(int(sympy.Rational(c).p), int(sympy.Rational(c).q))
    return fmpq_poly(coeffs)


def _lcm(a: fmpq_poly, b: fmpq_poly) -> fmpq_poly:
    return a * b / a.gcd(b)


def _lift(p: fmpq_poly, ctx: fmpq_mpoly_ctx) -> fmpq_mpoly:
    t = ctx.gens()[3]
    out = ctx.from_dict({})
    for e, c in enumerate(p.coeffs()):
        if c:
            out += c * t**e
    return out


def family_strings(family: RationalFamily) -> tuple[tuple[str, str, str], str]:
    """``m(t)`` and ``ρ(t)`` as strings sympy reads back."""
    x, y, z = (str(sympy.factor(c)) for c in family.m)
    return (x, y, z), str(sympy.factor(family.rho))


def rational_parametrization(f: Poly, family: RationalFamily) -> tuple[tuple[sympy.Expr, ...], bool] | None:
    """A real rational parameterization ``X(t, s)`` of the canal surface of a rational MAT
    (``ρ = r(t)²``, ``r`` rational) over ``QQ``, and whether it passed the substitution into ``f``.

    ``X = m + r·n`` with the unit normal ``n = (2u, 2v, u² + v² − 1)/(u² + v² + 1)`` (stereographic
    projection) on the circle ``n·m′ = −r′``, which in ``(u, v)`` is
    ``(u + a)² + (v + b)² = (|m′|² − r′²)/(m₃′ + r′)²``. The sum-of-two-squares step writes the
    numerator ``|m′|² − r′²`` as ``A² + B²`` over ``QQ`` (factorization over ``QQ(i)``); then the
    circle is ``(u + a, v + b) = (A cos θ − B sin θ, A sin θ + B cos θ)/(m₃′ + r′)`` with the
    rational ``cos θ = (1 − s²)/(1 + s²)``, ``sin θ = 2s/(1 + s²)``. ``None`` when a step fails.
    All of it is computed in reduced flint fractions of ``QQ(t, s)``.
    """
    exact = family.exact
    if exact is None:
        return None
    r = fraction_sqrt(exact.rho)
    if r is None:
        return None
    dm = [c.derivative(0) for c in exact.m]
    dr = r.derivative(0)
    for order in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
        if not (dm[order[2]] + dr).is_zero():
            break
    else:
        return None
    p, q, w = (dm[i] for i in order)
    rest = p * p + q * q + w * w - dr * dr
    split = _two_squares(sympy.Poly(poly_expr(rest.num, (T, S)), T))
    if split is None:
        return None
    # den is a square: (p² + q² + w² − r′²) has the square of the common denominator below.
    root = fraction_sqrt(RationalFunction.of(rest.den))
    if root is None:
        return None
    ring = rest.ctx
    A, B = (from_expr(c, (T,), ring) / root for c in split)
    s_ = RationalFunction.of(ring.gens()[1])
    one_plus = 1 + s_ * s_
    cos, sin = (1 - s_ * s_) / one_plus, 2 * s_ / one_plus
    lead = w + dr
    u = (A * cos - B * sin - p) / lead
    v = (A * sin + B * cos - q) / lead
    uu = u * u + v * v
    norm = uu + 1
    n = [2 * u / norm, 2 * v / norm, (uu - 1) / norm]
    normal: list[RationalFunction] = [n[0]] * 3
    for k, i in enumerate(order):
        normal[i] = n[k]
    point = tuple(exact.m[i] + r * normal[i] for i in range(3))
    return tuple(c.to_expr((T, S)) for c in point), _at(to_flint(f), point).is_zero()


def _two_squares(P: sympy.Poly) -> tuple[sympy.Expr, sympy.Expr] | None:
    """``(A, B)`` in ``QQ[t]`` with ``P = A² + B²``, from the factorization of ``P`` over ``QQ(i)``:
    each factor ``g`` with its conjugate ``ḡ`` contributes ``g`` to ``G = A + iB``, factors over
    ``QQ`` of even multiplicity contribute their square roots; the constant must be a sum of two
    rational squares."""
    c, factors = sympy.factor_list(P.as_expr(), T, extension=sympy.I)
    c = sympy.Rational(c)
    if c <= 0:
        return None
    G = sympy.Integer(1)
    seen: list[sympy.Expr] = []
    for g, e in factors:
        if any(sympy.expand(g - _conjugate(h)) == 0 for h in seen):
            continue
        conj = _conjugate(g)
        if sympy.expand(conj - g) == 0:
            if e % 2:
                return None
            G *= g ** (e // 2)
        else:
            seen.append(g)
            partner = next((ee for gg, ee in factors if sympy.expand(gg - conj) == 0), None)
            if partner != e:
                return None
            G *= g**e
    a, b = _rational_two_squares(c)
    if a is None:
        return None
    G = sympy.expand((a + sympy.I * b) * G)
    A, B = sympy.expand(G.subs(sympy.I, 0)), sympy.expand((G - G.subs(sympy.I, 0)) / sympy.I)
    if sympy.expand(A * A + B * B - P.as_expr()) != 0:
        return None
    return A, B


def _conjugate(g: sympy.Expr) -> sympy.Expr:
    """Complex conjugation of a polynomial over ``QQ(i)`` in the real variable ``t``."""
    return sympy.expand(g.subs(sympy.I, -sympy.I))


def _rational_two_squares(c: sympy.Rational) -> tuple[sympy.Rational | None, sympy.Rational | None]:
    """``(a, b)`` rational with ``a² + b² = c``, or ``(None, None)``."""
    from sympy.solvers.diophantine.diophantine import sum_of_squares

    n = int(c.p) * int(c.q)
    root = sympy.integer_nthroot(n, 2)
    if root[1]:
        return sympy.Rational(root[0], c.q), sympy.Integer(0)
    for a, b in sum_of_squares(n, 2, zeros=True):
        return sympy.Rational(a, c.q), sympy.Rational(b, c.q)
    return None, None
