"""Rational sphere families, characteristic circles and parameterizations of canal surfaces
(docs/math.md §9).

* ``m(t), ρ(t)`` of a genus-0 SMAT curve: its plane model ``G(u, v)`` is parameterized
  (:func:`.curves.parametrize`), and the coordinates are rational functions of ``(u, v)`` on
  the curve (:mod:`.canal_spine`, shape lemma). The result is verified by substitution into every
  equation of the SMAT ideal.
* Characteristic circles: centre ``c = m − (ρ′/(2|m′|²))·m′``, radius² ``R² = ρ − ρ′²/(4|m′|²)``,
  in the plane through ``c`` perpendicular to ``m′``.
* The radical parameterization ``c(t) + R(t)(cos θ·e₁ + sin θ·e₂)`` with ``e₁ = m′ × a``,
  ``e₂ = m′ × e₁`` normalised, verified by substitution into ``f`` (with
  ``cos θ = (1 − s²)/(1 + s²)``, ``sin θ = 2s/(1 + s²)`` and the square roots as new variables
  reduced by their squares).
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy
from flint import fmpq, fmpq_mpoly, fmpq_mpoly_ctx, fmpq_poly

from .canal_spine import SMAT_NAMES, SmatCurve
from .curves import CurveParametrization
from .errors import AnalysisError
from .polys import Poly, to_flint

T = sympy.Symbol("t")
THETA = sympy.Symbol("theta")


@dataclass(frozen=True)
class RationalFamily:
    """A verified rational sphere family ``m(t)``, ``ρ(t)`` (coefficients in ``QQ`` or in the
    field of ``generators``) and its characteristic circles."""

    m: tuple[sympy.Expr, sympy.Expr, sympy.Expr]
    rho: sympy.Expr
    generators: tuple[sympy.Expr, ...]
    verified: bool
    center: tuple[sympy.Expr, sympy.Expr, sympy.Expr]
    radius_squared: sympy.Expr
    normal: tuple[sympy.Expr, sympy.Expr, sympy.Expr]

    @property
    def over_qq(self) -> bool:
        return not self.generators


def recover_family(curve: SmatCurve, plane: CurveParametrization) -> RationalFamily:
    """``m(t), ρ(t)`` from the parameterization ``(u(t), v(t))`` of the plane model and the
    inverse of the projection, verified by substitution into every SMAT equation."""
    if curve.inverse is None:
        raise AnalysisError("the plane model of the SMAT curve is not known to be birational")
    u, v = sympy.Symbol("u"), sympy.Symbol("v")
    subs = {u: plane.x, v: plane.y}
    coords = [sympy.cancel(h.subs(subs, simultaneous=True)).subs(plane.parameter, T) for h in curve.inverse]
    m = (coords[0], coords[1], coords[2])
    rho = coords[3]
    point = dict(zip((sympy.Symbol(n) for n in SMAT_NAMES), coords))
    verified = all(sympy.cancel(g.as_expr().subs(point, simultaneous=True)) == 0 for g in curve.equations)
    center, radius_squared, normal = characteristic_circles(m, rho)
    return RationalFamily(m, rho, tuple(plane.generators), verified, center, radius_squared, normal)


def characteristic_circles(
    m: tuple[sympy.Expr, sympy.Expr, sympy.Expr], rho: sympy.Expr,
) -> tuple[tuple[sympy.Expr, sympy.Expr, sympy.Expr], sympy.Expr, tuple[sympy.Expr, sympy.Expr, sympy.Expr]]:
    """``c(t)``, ``R²(t)`` and the plane normal ``m′(t)`` of the characteristic circles."""
    dm = tuple(sympy.diff(c, T) for c in m)
    drho = sympy.diff(rho, T)
    n2 = sum(d * d for d in dm)
    center = tuple(sympy.factor(sympy.cancel(c - drho / (2 * n2) * d)) for c, d in zip(m, dm))
    radius_squared = sympy.factor(sympy.cancel(rho - drho**2 / (4 * n2)))
    normal = tuple(sympy.factor(sympy.cancel(d)) for d in dm)
    return center, radius_squared, normal  # type: ignore[return-value]


def frame(normal: tuple[sympy.Expr, ...]) -> tuple[tuple[sympy.Expr, ...], tuple[sympy.Expr, ...]]:
    """Two vectors ``e₁ = n × a``, ``e₂ = n × e₁`` perpendicular to ``n`` (``a`` a coordinate
    axis not parallel to ``n``), not normalised."""
    for a in ((1, 0, 0), (0, 1, 0), (0, 0, 1)):
        e1 = _cross(normal, a)
        if any(sympy.cancel(c) != 0 for c in e1):
            return e1, _cross(normal, e1)
    raise AnalysisError("the spine has a vanishing tangent")


def _cross(u: tuple, v: tuple) -> tuple[sympy.Expr, sympy.Expr, sympy.Expr]:
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


def radical_parametrization(family: RationalFamily) -> tuple[sympy.Expr, sympy.Expr, sympy.Expr]:
    """``c(t) + R(t)(cos θ·e₁/|e₁| + sin θ·e₂/|e₂|)``: exact, with square roots."""
    e1, e2 = frame(family.normal)
    n1 = sympy.sqrt(sympy.factor(sympy.cancel(sum(c * c for c in e1))))
    n2 = sympy.sqrt(sympy.factor(sympy.cancel(sum(c * c for c in e2))))
    R = sympy.sqrt(family.radius_squared)
    return tuple(  # type: ignore[return-value]
        c + R * (sympy.cos(THETA) * sympy.cancel(a) / n1 + sympy.sin(THETA) * sympy.cancel(b) / n2)
        for c, a, b in zip(family.center, e1, e2)
    )


def verify_radical(f: Poly, family: RationalFamily) -> bool:
    """Whether ``f`` vanishes on every characteristic circle, exactly: ``f(c + a·e₁ + b·e₂)``, a
    polynomial in ``t, a, b`` (denominators cleared), reduced modulo the circle
    ``a²|e₁|² + b²|e₂|² = R²`` (``a²`` replaced), must be zero. This is the radical
    parameterization substituted into ``f`` with ``(a, b) = R(cos θ/|e₁|, sin θ/|e₂|)``. Over
    ``QQ`` only.
    """
    if family.generators:
        return False
    e1, e2 = frame(family.normal)
    ctx = fmpq_mpoly_ctx.get(("t", "a", "b"), "lex")
    _, a, b = ctx.gens()
    rows = [sympy.cancel(c) for c in (*family.center, *e1, *e2)]
    den = sympy.Integer(1)
    for expr in rows:
        den = sympy.lcm(den, sympy.fraction(expr)[1])
    D = _to_ctx(den, ctx)
    coords = []
    for i in range(3):
        parts = [_to_ctx(sympy.cancel(rows[j] * den), ctx) for j in (i, 3 + i, 6 + i)]
        coords.append(parts[0] + a * parts[1] + b * parts[2])
    value = _compose_fraction(to_flint(f), coords, [D, D, D], ctx, common=D)
    sa, sb = sympy.Symbol("a"), sympy.Symbol("b")
    circle = sympy.fraction(sympy.cancel(
        sum(c * c for c in e1) * sa**2 + sum(c * c for c in e2) * sb**2 - family.radius_squared))[0]
    circle = sympy.expand(circle)
    lead = circle.coeff(sa, 2)
    A = _to_ctx_ab(lead, ctx)
    rest = _to_ctx_ab(sympy.expand(circle - lead * sa**2), ctx)
    return _reduce_square(value, 1, A, -rest, ctx).is_zero()


def _to_ctx_ab(expr: sympy.Expr, ctx: fmpq_mpoly_ctx) -> fmpq_mpoly:
    """A polynomial in ``t, a, b`` as an element of ``ctx``."""
    p = sympy.Poly(expr, T, sympy.Symbol("a"), sympy.Symbol("b"))
    return ctx.from_dict({m: fmpq(int(sympy.Rational(c).p), int(sympy.Rational(c).q)) for m, c in p.terms()})


def _reduce_square(p: fmpq_mpoly, index: int, A: fmpq_mpoly, B: fmpq_mpoly, ctx: fmpq_mpoly_ctx) -> fmpq_mpoly:
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


def _to_ctx(expr: sympy.Expr, ctx: fmpq_mpoly_ctx) -> fmpq_mpoly:
    """A polynomial in ``t`` (rational coefficients) as an element of ``ctx``."""
    p = sympy.Poly(expr, T)
    t = ctx.gens()[0]
    out = ctx.from_dict({})
    for (e,), c in p.terms():
        out += fmpq(int(sympy.Rational(c).p), int(sympy.Rational(c).q)) * t**e
    return out


def _compose_fraction(
    f: fmpq_mpoly, nums: list[fmpq_mpoly], dens: list[fmpq_mpoly], ctx: fmpq_mpoly_ctx,
    common: fmpq_mpoly | None = None,
) -> fmpq_mpoly:
    """``D^deg f · f(nᵢ/dᵢ)`` with ``D = Π dᵢ`` (or the given common multiple of the ``dᵢ``):
    the numerator of ``f`` at the rational point."""
    d = f.total_degree()
    total = ctx.from_dict({})
    common = dens[0] * dens[1] * dens[2] if common is None else common
    scaled = [nums[i] * (common / dens[i]) for i in range(3)]
    cache: dict[tuple[int, int], fmpq_mpoly] = {}
    for monom, coeff in zip(f.monoms(), f.coeffs()):
        term = ctx.from_dict({(0,) * ctx.nvars(): coeff})
        for i, e in enumerate(monom):
            if e:
                if (i, e) not in cache:
                    cache[(i, e)] = scaled[i] ** e
                term *= cache[(i, e)]
        k = d - sum(monom)
        if k:
            if (3, k) not in cache:
                cache[(3, k)] = common**k
            term *= cache[(3, k)]
        total += term
    return total


def family_resultant_certificate(f: Poly, family: RationalFamily) -> bool:
    """Whether ``f`` divides ``Res_t(S, ∂S/∂t)`` for ``S = L·(|X − m(t)|² − ρ(t))`` (``L`` clears
    the denominators): the envelope certificate of a rational family over ``QQ``."""
    ctx = fmpq_mpoly_ctx.get(("x", "y", "z", "t"), "lex")
    x, y, z, t = ctx.gens()
    fracs = [sympy.fraction(sympy.cancel(c)) for c in (*family.m, family.rho)]
    polys = [(_univariate(n), _univariate(d)) for n, d in fracs]
    L = fmpq_poly(1)
    for n, d in polys[:3]:
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
    coeffs = [0] * (p.degree() + 1)
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
    return tuple(str(sympy.factor(c)) for c in family.m), str(sympy.factor(family.rho))  # type: ignore[return-value]
