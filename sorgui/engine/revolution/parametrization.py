"""Rational parameterizations of a surface of revolution, each checked by substitution (docs/math.md §6).

A *section* of ``X`` is a rational curve meeting every circle of latitude (the paper's
Section 3). In the ``K``-rational axis frame ``(c, a, u, w = a × u)`` a section is

    c + φ(t)·a + ρ₁(t)·u + ρ₂(t)·w,

and rotating it with the ``K``-rational circle of docs/math.md §3 — ``u ↦ t₁u + t₂w``,
``w ↦ -n·t₂u + t₁w`` with ``n = |a|²`` and ``t₁² + n·t₂² = 1`` — parameterizes ``X`` without a
square root of ``|a|²``. Sections come from a rational profile (or profile component) or from
the tubular surface ``T`` when ``genus(P²) = 0``; on ``T`` a real section needs
``h = A² + n·B²`` over ``QQ`` (a norm from ``QQ(√-n)``, docs/math.md §6 with ``i`` replaced by
``√-n``), otherwise ``B = (h - 1)/(2√-n)`` gives the complex one.

Every parameterization is substituted back into ``f`` and must reduce to 0 exactly.
"""

from __future__ import annotations

import math
import statistics
from collections.abc import Callable
from dataclasses import dataclass
from typing import TypeAlias, cast

import mpmath
import sympy
from flint import fmpq, fmpq_mpoly
from sympy.polys.domains import QQ
from sympy.polys.domains.domain import Domain
from sympy.solvers.diophantine.diophantine import diop_ternary_quadratic

from ..algebra import legendre
from ..algebra.linalg import Vector, cross, dot, perpendicular
from ..algebra.polys import Poly, field_generators, field_name, to_expr
from ..algebra.radicals import RadicalRing, radicals_of
from ..algebra.rationals import content
from ..recognition.profile import AxisFrame, ProfileCurve
from ..stage_results import Parametrization

T = sympy.Symbol("t")
PARAMETERS = ("s", "t")


@dataclass(frozen=True)
class Section:
    """A section ``c + φ·a + ρ₁·u + ρ₂·w`` given by sympy rational functions of ``t``;
    ``named`` lists symbols that stand for square roots (symbol, value), such as ``√-n``."""

    phi: sympy.Expr
    rho_u: sympy.Expr
    rho_w: sympy.Expr
    named: tuple[tuple[sympy.Symbol, sympy.Expr], ...] = ()


Quadric = tuple[sympy.Expr, sympy.Expr, sympy.Expr]
"""``(x, Y, Z)(s, t)``: a parameterization of the quadric ``Y² + n·Z² = h(x)``."""


@dataclass(frozen=True)
class SurfaceMap:
    """``(N₁, N₂, N₃)/D``: a parameterization of ``X`` in ``x, y, z``, exact over a radical ring."""

    ring: RadicalRing
    numerators: tuple[fmpq_mpoly, fmpq_mpoly, fmpq_mpoly]
    denominator: fmpq_mpoly
    axial: fmpq_mpoly
    radial: tuple[fmpq_mpoly, fmpq_mpoly]
    """In the axis frame the point is ``c + (axial/D)·a + (radial₀/D)·u + (radial₁/D)·w``."""

    def coordinates(self) -> tuple[sympy.Expr, sympy.Expr, sympy.Expr]:
        """The three coordinates as sympy rational functions in lowest terms (for display)."""
        out = []
        for num in self.numerators:
            g = num.gcd(self.denominator) if num else self.denominator
            top, bottom = num / g, self.denominator / g
            common = content(top, bottom)
            out.append(self.ring.to_expr(top / common) / self.ring.to_expr(bottom / common))
        x, y, z = out
        return x, y, z


def sweep(section: Section, frame: AxisFrame, K: Domain) -> SurfaceMap:
    """Rotate ``section`` about the axis with the ``K``-rational circle (docs/math.md §3):
    ``u ↦ t₁u + t₂w``, ``w ↦ -n·t₂u + t₁w``, ``t₁ = (1 - nσ²)/(1 + nσ²)``, ``t₂ = 2σ/(1 + nσ²)``."""
    vectors = [frame.point, frame.direction, frame.normal, frame.binormal]
    exprs = [[to_expr(K, c) for c in v] for v in vectors]
    n_expr = to_expr(K, dot(frame.direction, frame.direction))
    expressions = [section.phi, section.rho_u, section.rho_w, n_expr, *sum(exprs, [])]
    ring = RadicalRing(PARAMETERS, radicals_of(expressions, dict(section.named)))
    c, a, u, w = ([ring.from_expr(e) for e in v] for v in exprs)
    n = ring.from_expr(n_expr)
    sigma = ring.variable("s")
    (nphi, dphi), (nu, du), (nw, dw) = (ring.fraction(e) for e in (section.phi, section.rho_u, section.rho_w))
    circle = 1 + n * sigma**2
    cos_num, sin_num = 1 - n * sigma**2, 2 * sigma
    den = ring.reduce(dphi * du * dw * circle)
    along_a = ring.reduce(nphi * du * dw * circle)
    rho_u, rho_w = ring.reduce(nu * dphi * dw), ring.reduce(nw * dphi * du)
    along_u = ring.reduce(rho_u * cos_num - n * sin_num * rho_w)
    along_w = ring.reduce(rho_u * sin_num + cos_num * rho_w)
    return _assemble(ring, (c, a, u, w), den, along_a, along_u, along_w)


def frame_map(
    axial: sympy.Expr,
    along_u: sympy.Expr,
    along_w: sympy.Expr,
    frame: AxisFrame,
    K: Domain,
    named: tuple[tuple[sympy.Symbol, sympy.Expr], ...] = (),
) -> SurfaceMap:
    """The map ``c + axial·a + along_u·u + along_w·w`` for rational functions of ``(s, t)``."""
    vectors = [frame.point, frame.direction, frame.normal, frame.binormal]
    exprs = [[to_expr(K, c) for c in v] for v in vectors]
    ring = RadicalRing(PARAMETERS, radicals_of([axial, along_u, along_w, *sum(exprs, [])], dict(named)))
    basis = tuple([ring.from_expr(e) for e in v] for v in exprs)
    (na, da), (nu, du), (nw, dw) = (ring.fraction(e) for e in (axial, along_u, along_w))
    den = ring.reduce(da * du * dw)
    return _assemble(ring, basis, den, ring.reduce(na * du * dw), ring.reduce(nu * da * dw), ring.reduce(nw * da * du))


def _assemble(
    ring: RadicalRing,
    basis: tuple[list[fmpq_mpoly], ...],
    den: fmpq_mpoly,
    along_a: fmpq_mpoly,
    along_u: fmpq_mpoly,
    along_w: fmpq_mpoly,
) -> SurfaceMap:
    """``(c·D + a·along_a + u·along_u + w·along_w) / D`` in the original coordinates."""
    c, a, u, w = basis
    x, y, z = (ring.reduce(c[i] * den + a[i] * along_a + u[i] * along_u + w[i] * along_w) for i in range(3))
    return SurfaceMap(ring, (x, y, z), den, along_a, (along_u, along_w))


@dataclass(frozen=True)
class NormFactorization:
    """``h = (A² + n·B²)·u²·q``: ``A + √-n·B`` collects the factors that split over ``QQ(√-n)``,
    ``u`` the square part, and ``q`` (with the leading coefficient) the rest (docs/math.md §6)."""

    A: sympy.Expr
    B: sympy.Expr
    u: sympy.Expr
    q: sympy.Expr


def norm_factorization(h: sympy.Expr, n: sympy.Expr) -> NormFactorization | None:
    """Split ``h ∈ QQ[t]`` as :class:`NormFactorization` (``None`` for irrational coefficients)."""
    poly = sympy.Poly(h, T)
    if poly.degree() < 0 or not all(c.is_Rational for c in poly.coeffs()) or not n.is_Rational:
        return None
    alpha = sympy.sqrt(-n)
    lead, factors = poly.factor_list()
    product, square, rest = sympy.Integer(1), sympy.Integer(1), sympy.Rational(lead)
    for g, e in factors:
        square *= g.as_expr() ** (e // 2)
        if e % 2 == 0:
            continue
        _, split = sympy.factor_list(g.as_expr(), T, extension=alpha)
        if len(split) < 2:
            rest *= g.as_expr()
            continue
        rest *= g.LC()
        product *= sympy.Poly(split[0][0], T, extension=alpha).monic().as_expr()
    A, B = _split(sympy.Poly(sympy.expand(product), T, extension=alpha), n)
    return NormFactorization(A, B, sympy.expand(square), sympy.expand(rest))


def norm_decomposition(h: sympy.Expr, n: sympy.Expr) -> tuple[sympy.Expr, sympy.Expr] | None:
    """``(A, B)`` in ``QQ[t]`` with ``h = A² + n·B²``, or ``None`` when there is none.

    ``h`` is a norm from ``QQ(√-n)[t]`` iff every ``QQ``-irreducible factor of odd multiplicity
    splits over ``QQ(√-n)`` and the leading coefficient is a rational norm ``X² + nY²``
    (solved as the ternary form ``X² + nY² - cZ²`` with sympy's Diophantine solver).
    """
    split = norm_factorization(h, n)
    if split is None or not split.q.is_Rational:
        return None
    point = _rational_norm(split.q, n)
    if point is None:
        return None
    A, B = _times(split.A, split.B, point[0], point[1], n)
    A, B = sympy.expand(A * split.u), sympy.expand(B * split.u)
    return (A, B) if sympy.expand(A**2 + n * B**2 - h) == 0 else None


def _times(A: sympy.Expr, B: sympy.Expr, C: sympy.Expr, D: sympy.Expr, n: sympy.Expr) -> tuple[sympy.Expr, sympy.Expr]:
    """``(A + √-n·B)(C + √-n·D)`` as its two real parts."""
    return A * C - n * B * D, A * D + B * C


def quadric_section(h: sympy.Expr, n: sympy.Expr) -> Quadric | None:
    """A proper real parameterization ``(x, Y, Z)(s, t)`` of ``Y² + n·Z² = h(x)`` when
    ``h = N·u²·q`` with ``deg q ≤ 2`` and ``q`` positive somewhere (docs/math.md §6): the quadric
    ``y'² + n·z'² = q(x)`` is projected stereographically from a real point (a real root of
    ``q``, possibly in a real quadratic field, or a rational point found by a small search).
    """
    split = norm_factorization(h, n)
    if split is None or sympy.degree(split.q, T) not in (1, 2):
        return None
    q = sympy.Poly(split.q, T)
    point = _real_point(q, n)
    if point is None:
        return None
    t0, y0, z0 = point
    m1, m2 = sympy.symbols("s t")
    a = q.coeff_monomial(T**2) if q.degree() == 2 else sympy.Integer(0)
    slope = q.diff(T).as_expr().subs(T, t0)
    k = (slope - 2 * y0 * m1 - 2 * n * z0 * m2) / (m1**2 + n * m2**2 - a)
    x, y1, z1 = t0 + k, y0 + k * m1, z0 + k * m2
    A, B, u = (e.subs(T, x) for e in (split.A, split.B, split.u))
    Y, Z = _times(A, B, y1, z1, n)
    return x, u * Y, u * Z


def _real_point(q: sympy.Poly, n: sympy.Expr) -> tuple[sympy.Expr, sympy.Expr, sympy.Expr] | None:
    """A smooth real point ``(t₀, y₀, z₀)`` of ``y² + n·z² = q(t)``."""
    roots = sorted(_real_roots(q), key=lambda r: (not r.is_Rational, sympy.count_ops(r)))
    for root in roots:
        if q.diff(T).as_expr().subs(T, root) != 0:
            return root, sympy.Integer(0), sympy.Integer(0)
    for t0 in sorted(range(-12, 13), key=abs):
        value = q.as_expr().subs(T, t0)
        found = _rational_norm(value, n) if value > 0 else None
        if found is not None:
            return sympy.Integer(t0), found[0], found[1]
    return None


def _real_roots(q: sympy.Poly) -> list[sympy.Expr]:
    """The real roots of ``q`` (degree 1 or 2, rational coefficients), increasing, in closed
    form: sympy's ``real_roots`` isolates them first, and refined the roots of ``t² − c`` for a
    5000-digit ``c`` in 120,000 steps (6 s)."""
    if q.degree() == 1:
        a, b = q.all_coeffs()
        return [-b / a]
    a, b, c = q.all_coeffs()
    discriminant = b**2 - 4 * a * c
    if discriminant < 0:
        return []
    if discriminant == 0:
        return [-b / (2 * a)]
    root = sympy.sqrt(discriminant)
    roots = [(-b - root) / (2 * a), (-b + root) / (2 * a)]
    return roots if a > 0 else roots[::-1]  # increasing, as sympy gives them


def _split(P: sympy.Poly, n: sympy.Expr) -> tuple[sympy.Expr, sympy.Expr]:
    """``(A, B)`` with ``P = A + √-n·B`` and ``A, B`` real polynomials in ``t``."""
    A, B = sympy.Integer(0), sympy.Integer(0)
    for (k,), c in P.terms():
        re, im = sympy.expand(c).as_real_imag()
        A += re * T**k
        B += sympy.radsimp(im / sympy.sqrt(n)) * T**k
    return sympy.expand(A), sympy.expand(B)


LEGENDRE_BITS = 32
"""``X² + n·Y² = c`` with ``n`` or ``c`` (made integral) of more bits is solved by Legendre's
equation with quick factorizations (:mod:`..algebra.legendre`), not by sympy's
``diop_ternary_quadratic``, whose ECM ran for minutes on the numbers of a rounded hyperboloid's
nearest surface (``None`` when they cannot be factored quickly)."""


def _rational_norm(c: sympy.Expr, n: sympy.Expr) -> tuple[sympy.Expr, sympy.Expr] | None:
    """Rational ``(X, Y)`` with ``X² + n·Y² = c``, or ``None``."""
    c, n = sympy.Rational(c), sympy.Rational(n)
    if c <= 0:
        return None
    root = sympy.sqrt(c)
    if root.is_Rational:
        return root, sympy.Integer(0)
    scale_c, scale_n = c.p * c.q, n.p * n.q
    solution: tuple[int, int, int] | None
    if max(abs(int(scale_c)).bit_length(), abs(int(scale_n)).bit_length()) > LEGENDRE_BITS:
        solution = legendre.solve(1, int(scale_n), -int(scale_c))[1]
    else:
        X, Y, Z = sympy.symbols("X Y Z", integer=True)
        found = diop_ternary_quadratic(X**2 + scale_n * Y**2 - scale_c * Z**2)
        solution = None if found is None or None in found else (int(found[0]), int(found[1]), int(found[2]))
    if solution is None or solution[2] == 0:
        return None
    x0, y0, z0 = (sympy.Integer(v) for v in solution)
    # X² + (n p q) Y² = (c p' q') Z²  ⇒  rescale to X² + n Y² = c.
    return x0 / (z0 * c.q), y0 * n.q / (z0 * c.q)


def tubular_section(
    phi: sympy.Expr,
    d: sympy.Expr,
    q: sympy.Expr,
    A: sympy.Expr,
    B: sympy.Expr,
    named: tuple[tuple[sympy.Symbol, sympy.Expr], ...] = (),
) -> Section:
    """The section ``(φ, d·A/q̃, d·B/q̃)`` of ``X`` through ``τ`` of the paper's Theorem
    "birational to tubular", with ``A² + n·B² = h``."""
    return Section(phi=phi, rho_u=d * A / q, rho_w=d * B / q, named=named)


def vanishes_on(f: Poly, surface: SurfaceMap) -> bool:
    """Whether ``f(N₁/D, N₂/D, N₃/D) = 0`` exactly: the homogenised ``f`` (its coefficients
    written with the radicals of ``K``) is composed with ``(N₁, N₂, N₃, D)`` in flint and reduced
    modulo the radicals' relations. A nonzero normal form with several radicals is rechecked
    over sympy's algebraic field (the normal form is unique only for independent radicands)."""
    K = f.ring.domain
    ring = surface.ring.extended(radicals_of([sympy.Add(*field_generators(K))]))
    kept = ring.context.gens()[: len(surface.ring.variables) + len(surface.ring.radicals)]
    images = [p.compose(*kept, ctx=ring.context) for p in (*surface.numerators, surface.denominator)]
    images += list(ring.context.gens()[len(ring.variables) :])
    degree = max(sum(m) for m in f.itermonoms())
    source = RadicalRing(("x", "y", "z", "w"), ring.radicals)
    if K == QQ:
        zeros = [0] * len(ring.radicals)
        H = source.context.from_dict({(*m, degree - sum(m), *zeros): c for m, c in f.items()})
    else:
        x, y, z, w = source.symbols
        H = source.from_expr(
            sympy.Add(
                *[to_expr(K, c) * x ** m[0] * y ** m[1] * z ** m[2] * w ** (degree - sum(m)) for m, c in f.items()]
            )
        )
    total = ring.reduce(H.compose(*images, ctx=ring.context))
    if total.is_zero() or len(ring.radicals) < 2:
        return total.is_zero()
    return cast(bool, sympy.Poly(ring.to_expr(total), *ring.symbols, extension=True).is_zero)


def section_vanishes(profile: ProfileCurve, section: Section) -> bool:
    """The exact check of a swept section: ``P²(φ, ρ₁² + n·ρ₂²) ≡ 0`` in ``t`` alone.

    ``f(c + s·a + y·u + z·w) = P²(s, y² + n·z²)`` is an exact identity (``profile.verified``)
    and the rotation of :func:`sweep` keeps ``y² + n·z²`` (``(1 − nσ²)² + n(2σ)² = (1 + nσ²)²``),
    so ``f`` vanishes on the whole map exactly when ``P²`` vanishes on the section: one
    univariate identity instead of ``f`` composed with a map in two parameters."""
    n = _frame_norm(profile)
    ring, (phi, rho_u, rho_w) = _univariate(profile, (section.phi, section.rho_u, section.rho_w), section.named)
    (nu, du), (nw, dw) = rho_u, rho_w
    radius = (ring.reduce(nu**2 * dw**2 + ring.from_expr(n) * nw**2 * du**2), ring.reduce(du**2 * dw**2))
    return _square_vanishes(profile, ring, phi, radius)


def tube_section_vanishes(profile: ProfileCurve, section: Section, radius: sympy.Expr) -> bool:
    """The exact check of a section through ``T``: ``ρ₁² + n·ρ₂² ≡ d²h/q̃²`` (``radius``) in ``t``.

    The tube's identity ``d²·h = r̃·q̃`` (checked when ``T`` is made) makes ``radius`` the second
    coordinate ``w = r̃/q̃`` of the verified parameterization ``(φ, w)`` of ``P²``, so
    ``P²(φ, ρ₁² + n·ρ₂²) = P²(φ, w) ≡ 0``: the identity of :func:`section_vanishes`, without
    composing ``P²`` (of degree 12, say) with the section."""
    n = _frame_norm(profile)
    ring, fractions = _univariate(profile, (section.rho_u, section.rho_w, radius), section.named)
    (nu, du), (nw, dw), (nr, dr) = fractions
    rest = ring.reduce(nu**2 * dw**2 * dr + ring.from_expr(n) * nw**2 * du**2 * dr - nr * du**2 * dw**2)
    return _zero(ring, rest)


def quadric_vanishes(quadric: Quadric, h: sympy.Expr, n: sympy.Expr) -> bool:
    """The exact check of the stereographic map through ``T``: ``Y² + n·Z² ≡ h(x)`` on the
    quadric's parameterization, which makes the map's radius ``(d/q̃)²·(Y² + n·Z²)`` that of
    ``T``, ``d²h/q̃² = w``, the second coordinate of the verified parameterization ``(φ, w)`` of
    ``P²`` (see :func:`tube_section_vanishes`). A small identity instead of ``f`` composed with
    the map."""
    x, Y, Z = quadric
    flat = RadicalRing(PARAMETERS, radicals_of([x, Y, Z, h, n]))
    num, _den = flat.fraction(sympy.together(Y**2 + n * Z**2 - h.subs(T, x)))
    return num.is_zero()


def _frame_norm(profile: ProfileCurve) -> sympy.Expr:
    K = profile.square.ring.domain
    return to_expr(K, dot(profile.frame.direction, profile.frame.direction))


def _univariate(
    profile: ProfileCurve,
    expressions: tuple[sympy.Expr, ...],
    named: tuple[tuple[sympy.Symbol, sympy.Expr], ...],
) -> tuple[RadicalRing, list[tuple[fmpq_mpoly, fmpq_mpoly]]]:
    """A radical ring in ``t`` holding ``expressions``, ``n`` and ``K``, and the expressions in it
    as (numerator, denominator)."""
    K = profile.square.ring.domain
    ring = RadicalRing(("t",), radicals_of([*expressions, _frame_norm(profile), *field_generators(K)], dict(named)))
    return ring, [ring.fraction(e) for e in expressions]


def _square_vanishes(
    profile: ProfileCurve,
    ring: RadicalRing,
    phi: tuple[fmpq_mpoly, fmpq_mpoly],
    radius: tuple[fmpq_mpoly, fmpq_mpoly],
) -> bool:
    """``P²(φ, R) ≡ 0`` for the fractions ``φ`` and ``R`` of ``ring``, denominators cleared."""
    K = profile.square.ring.domain
    (nphi, dphi), (nrad, drad) = phi, radius
    top_s = max(i for i, _ in profile.square.itermonoms())
    top_r = max(j for _, j in profile.square.itermonoms())
    total = ring.context.from_dict({})
    for (i, j), c in profile.square.items():
        term = ring.from_expr(to_expr(K, c)) * nphi**i * dphi ** (top_s - i) * nrad**j * drad ** (top_r - j)
        total += ring.reduce(term)
    return _zero(ring, ring.reduce(total))


def _zero(ring: RadicalRing, total: fmpq_mpoly) -> bool:
    """Whether ``total`` (reduced in ``ring``) is zero: its normal form is unique for one radical;
    with several, a nonzero form is checked again over sympy's algebraic field."""
    if total.is_zero() or len(ring.radicals) < 2:
        return total.is_zero()
    return cast(bool, sympy.Poly(ring.to_expr(total), *ring.symbols, extension=True).is_zero)


MpNumber: TypeAlias = mpmath.mpf | mpmath.mpc
"""A real or complex mpmath number (mpmath has no type information)."""

SCREEN_POINTS = ((0.3718, -1.2261), (1.9093, 0.5477), (-0.6632, 2.3149))
"""Parameter values ``(s, t)`` of the numerical screen (:func:`numerically_vanishes`)."""

SCREEN_TOLERANCE = 1e-7
"""``|f(X(s, t))|`` relative to the sum of the absolute values of its terms, above which the
screen rejects a map (the rounding of a true zero stays far below it)."""


def numerically_vanishes(f: Poly, surface: SurfaceMap) -> bool:
    """A screen before the exact check: ``f`` at the map's points for a few parameter values, in
    complex floating point of 30 digits (mpmath: any exponent, so huge coefficients are no
    trouble). ``False`` only when ``f`` is clearly not zero there (a wrong map); ``True`` proves
    nothing: the exact check follows."""
    with mpmath.workdps(30):
        values = [mpmath.mpmathify(complex(sympy.N(r.value, 30))) for r in surface.ring.radicals]
        K = f.ring.domain
        coefficients = [(m, mpmath.mpmathify(sympy.N(to_expr(K, c), 30))) for m, c in f.items()]
        for s, t in SCREEN_POINTS:
            point = (mpmath.mpf(s), mpmath.mpf(t), *values)
            den = _evaluate(surface.denominator, point)
            if abs(den) < mpmath.mpf(10) ** -9 * _size(surface.denominator, point):
                continue  # near a pole of the map: the other points tell
            X = [_evaluate(n, point) / den for n in surface.numerators]
            terms = [c * X[0] ** m[0] * X[1] ** m[1] * X[2] ** m[2] for m, c in coefficients]
            if abs(mpmath.fsum(terms)) > SCREEN_TOLERANCE * mpmath.fsum(abs(term) for term in terms):
                return False
    return True


def _evaluate(p: fmpq_mpoly, point: tuple[MpNumber, ...]) -> MpNumber:
    """``p`` at ``point`` (its variables, then its radicals), in mpmath's current precision."""
    return mpmath.fsum(_terms(p, point))


def _size(p: fmpq_mpoly, point: tuple[MpNumber, ...]) -> mpmath.mpf:
    """The sum of the absolute values of the terms of ``p`` at ``point``."""
    return mpmath.fsum(abs(term) for term in _terms(p, point))


def _terms(p: fmpq_mpoly, point: tuple[MpNumber, ...]) -> list[MpNumber]:
    out = []
    for monom, c in p.to_dict().items():
        term = mpmath.mpf(int(c.p)) / int(c.q)
        for value, e in zip(point, monom):
            if e:
                term *= value ** int(e)
        out.append(term)
    return out


def make_parametrization(
    f: Poly,
    profile: ProfileCurve,
    surface: SurfaceMap,
    identity: Callable[[], bool],
    *,
    method: str,
    proper: bool | None,
) -> Parametrization | None:
    """A verified :class:`Parametrization`, or ``None`` when the substitution does not vanish.

    Verifying must not cost more than finding the map: a numerical screen of ``f`` on the map
    first (:func:`numerically_vanishes`), then the exact check in the axis frame, ``identity``
    (:func:`section_vanishes` or :func:`quadric_vanishes`: small identities that the verified
    profile identity makes equivalent to ``f`` vanishing on the map), and the literal
    substitution into ``f`` (:func:`vanishes_on`) only when that identity was not verified."""
    if not numerically_vanishes(f, surface):
        return None
    in_frame = profile.verified
    if not (identity() if in_frame else vanishes_on(f, surface)):
        return None
    x, y, z = balanced(surface).coordinates()
    return Parametrization(
        coordinates=(str(x), str(y), str(z)),
        parameters=PARAMETERS,
        field=surface.ring.field,
        real=surface.ring.is_real,
        proper=proper,
        method=method,
        verified=True,
        verification=IN_FRAME if in_frame else "substituted into f",
    )


BALANCE_FROM = 100
"""A parameter whose natural scale is this far from 1 (either way) is rescaled by
:func:`balanced`."""


def _appears(polynomial: fmpq_mpoly, index: int) -> bool:
    """Whether the parameter ``index`` occurs in ``polynomial``."""
    return any(monomial[index] for monomial in polynomial.to_dict())


def parameter_scale(polynomial: fmpq_mpoly, index: int) -> int:
    """The power of ten nearest to the natural scale of the parameter ``index`` in a map's
    denominator (or, where it does not occur there, in a numerator): ``(A₀/A_d)^(1/d)``,
    ``A_k`` the largest coefficient of the terms of degree ``k`` in it (``d`` the largest), where
    the terms of lowest and highest degree weigh alike. A map of a hyperboloid on a turned axis
    had ``x ≈ 1.8 + 417·t`` with no ``t`` below the line: its patch over ``t ∈ [−3, 3]`` missed
    the drawn ball."""
    by_degree: dict[int, float] = {}  # log10 of the largest coefficient (exact integers: no overflow)
    for monomial, c in polynomial.to_dict().items():
        if c:
            k = int(monomial[index])
            size = math.log10(abs(int(c.p))) - math.log10(int(c.q))
            by_degree[k] = max(by_degree.get(k, -math.inf), size)
    top = max(by_degree, default=0)
    if top == 0 or 0 not in by_degree:
        return 0
    return round((by_degree[0] - by_degree[top]) / top)


def balanced(surface: SurfaceMap) -> SurfaceMap:
    """The same map with each parameter whose natural scale is a power of ten at least
    :data:`BALANCE_FROM` from 1 scaled by it (``t ↦ 10ᵏ·t``): a map of a torus on a turned axis
    had ``t`` of order 10⁶, and the patch drawn and exported over ``t ∈ [−3, 3]`` was a sliver of
    the surface. A reparameterization by a constant keeps the map, its properness and its field."""
    ctx = surface.ring.context
    gens = list(ctx.gens())
    images = list(gens)
    for index in range(len(surface.ring.variables)):
        power = parameter_scale(surface.denominator, index)
        if not power and not _appears(surface.denominator, index):
            power = round(statistics.median(parameter_scale(n, index) for n in surface.numerators))
        if 10 ** abs(power) >= BALANCE_FROM:
            images[index] = gens[index] * fmpq(10) ** power
    if images == gens:
        return surface
    x, y, z, d, axial, u, w = (
        p.compose(*images, ctx=ctx) for p in (*surface.numerators, surface.denominator, surface.axial, *surface.radial)
    )
    return SurfaceMap(surface.ring, (x, y, z), d, axial, (u, w))


IN_FRAME = "substituted into f in the axis frame"
"""The verification of a map checked through the profile identity (docs/math.md §6)."""


def plane_map(f: Poly, point: Vector, normal: Vector) -> Parametrization:
    """The affine map ``c + s·u + t·w`` of the plane ``f = 0`` through ``point`` with ``normal``:
    ``u`` the simple perpendicular of :func:`~..algebra.linalg.perpendicular` and ``w = n × u``,
    each divided by the integer part of its length (so that a patch over ``s, t ∈ [−3, 3]``
    covers about as much of the plane as of a ball of radius 3); proper and onto, verified by
    substitution into ``f``."""
    K = f.ring.domain
    u = perpendicular(normal, K)
    w = cross(normal, u)
    u, w = _about_unit(u, K), _about_unit(w, K)
    s, t = sympy.symbols("s t")
    images = [to_expr(K, point[i]) + s * to_expr(K, u[i]) + t * to_expr(K, w[i]) for i in range(3)]
    x, y, z = sympy.symbols("x y z")
    value = sympy.expand(f.as_expr().subs({x: images[0], y: images[1], z: images[2]}, simultaneous=True))
    return Parametrization(
        coordinates=(str(sympy.expand(images[0])), str(sympy.expand(images[1])), str(sympy.expand(images[2]))),
        parameters=("s", "t"),
        field=field_name(K),
        real=True,
        proper=True,
        method="affine map of the plane",
        verified=value == 0,
        verification="substituted into f",
    )


def _about_unit(v: Vector, K: Domain) -> Vector:
    """``v`` divided by the integer part of its length (at least 1): a rational vector about as
    long as a unit one."""
    length = math.isqrt(int(sympy.floor(to_expr(K, dot(v, v)))))  # exact: |v|² may be 10⁸⁰⁰
    scale = K.quo(K.one, K.convert(max(1, length)))
    return tuple(c * scale for c in v)
