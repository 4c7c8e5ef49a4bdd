"""Rational parameterizations of a surface of revolution, each checked by substitution (MATH.md §6).

A *section* of ``X`` is a rational curve meeting every circle of latitude (the paper's
Section 3). In the ``K``-rational axis frame ``(c, a, u, w = a × u)`` a section is

    c + φ(t)·a + ρ₁(t)·u + ρ₂(t)·w,

and rotating it with the ``K``-rational circle of MATH.md §3 — ``u ↦ t₁u + t₂w``,
``w ↦ -n·t₂u + t₁w`` with ``n = |a|²`` and ``t₁² + n·t₂² = 1`` — parameterizes ``X`` without a
square root of ``|a|²``. Sections come from a rational profile (or profile component) or from
the tubular surface ``T`` when ``genus(P²) = 0``; on ``T`` a real section needs
``h = A² + n·B²`` over ``QQ`` (a norm from ``QQ(√-n)``, MATH.md §6 with ``i`` replaced by
``√-n``), otherwise ``B = (h - 1)/(2√-n)`` gives the complex one.

Every parameterization is substituted back into ``f`` and must reduce to 0 exactly.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import sympy
from flint import fmpq_mpoly
from sympy.polys.domains import QQ
from sympy.polys.domains.domain import Domain
from sympy.solvers.diophantine.diophantine import diop_ternary_quadratic

from .linalg import Vector, dot
from .polys import Poly, field_generators, to_expr
from .radicals import RadicalRing, radicals_of
from .profile import AxisFrame
from .report import Parametrization

T = sympy.Symbol("t")
PARAMETERS = ("s", "t")


@dataclass(frozen=True)
class Section:
    """A section ``c + φ·a + ρ₁·u + ρ₂·w`` given by sympy rational functions of ``t``."""

    phi: sympy.Expr
    rho_u: sympy.Expr
    rho_w: sympy.Expr


@dataclass(frozen=True)
class SurfaceMap:
    """``(N₁, N₂, N₃)/D``: a parameterization of ``X`` in ``x, y, z``, exact over a radical ring."""

    ring: RadicalRing
    numerators: tuple[fmpq_mpoly, fmpq_mpoly, fmpq_mpoly]
    denominator: fmpq_mpoly

    def coordinates(self) -> tuple[sympy.Expr, sympy.Expr, sympy.Expr]:
        """The three coordinates as sympy rational functions in lowest terms (for display)."""
        out = []
        for num in self.numerators:
            g = num.gcd(self.denominator) if num else self.denominator
            out.append(self.ring.to_expr(num / g) / self.ring.to_expr(self.denominator / g))
        return tuple(out)  # type: ignore[return-value]


def sweep(section: Section, frame: AxisFrame, K: Domain) -> SurfaceMap:
    """Rotate ``section`` about the axis with the ``K``-rational circle (MATH.md §3):
    ``u ↦ t₁u + t₂w``, ``w ↦ -n·t₂u + t₁w``, ``t₁ = (1 - nσ²)/(1 + nσ²)``, ``t₂ = 2σ/(1 + nσ²)``."""
    vectors = [frame.point, frame.direction, frame.normal, frame.binormal]
    exprs = [[to_expr(K, c) for c in v] for v in vectors]
    n_expr = to_expr(K, dot(frame.direction, frame.direction))
    ring = RadicalRing(PARAMETERS, radicals_of([section.phi, section.rho_u, section.rho_w, n_expr, *sum(exprs, [])]))
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
    nums = tuple(ring.reduce(c[i] * den + a[i] * along_a + u[i] * along_u + w[i] * along_w) for i in range(3))
    return SurfaceMap(ring, nums, den)  # type: ignore[arg-type]


def norm_decomposition(h: sympy.Expr, n: sympy.Expr) -> tuple[sympy.Expr, sympy.Expr] | None:
    """``(A, B)`` in ``QQ[t]`` with ``h = A² + n·B²``, or ``None`` when there is none.

    ``h`` is a norm from ``QQ(√-n)[t]`` iff every ``QQ``-irreducible factor of odd multiplicity
    splits over ``QQ(√-n)`` and the leading coefficient is a rational norm ``X² + nY²``
    (solved as the ternary form ``X² + nY² - cZ²`` with sympy's Diophantine solver).
    """
    poly = sympy.Poly(h, T)
    if poly.degree() < 0 or not all(c.is_Rational for c in poly.coeffs()) or not n.is_Rational:
        return None
    alpha = sympy.sqrt(-n)
    lead, factors = poly.factor_list()
    product = sympy.Integer(1)
    for g, e in factors:
        if e % 2 == 0:
            product *= g.as_expr() ** (e // 2)
            continue
        _, split = sympy.factor_list(g.as_expr(), T, extension=alpha)
        if len(split) < 2:
            return None
        G = sympy.Poly(split[0][0], T, extension=alpha).monic()
        lead *= g.LC()
        product *= G.as_expr() ** e
    point = _rational_norm(lead, n)
    if point is None:
        return None
    product *= point[0] + alpha * point[1]
    A, B = _split(sympy.Poly(sympy.expand(product), T, extension=alpha), n)
    if sympy.expand(A**2 + n * B**2 - h) != 0:
        return None
    return A, B


def _split(P: sympy.Poly, n: sympy.Expr) -> tuple[sympy.Expr, sympy.Expr]:
    """``(A, B)`` with ``P = A + √-n·B`` and ``A, B`` real polynomials in ``t``."""
    A, B = sympy.Integer(0), sympy.Integer(0)
    for (k,), c in P.terms():
        re, im = sympy.expand(c).as_real_imag()
        A += re * T**k
        B += sympy.radsimp(im / sympy.sqrt(n)) * T**k
    return sympy.expand(A), sympy.expand(B)


def _rational_norm(c: sympy.Expr, n: sympy.Expr) -> tuple[sympy.Expr, sympy.Expr] | None:
    """Rational ``(X, Y)`` with ``X² + n·Y² = c``, or ``None``."""
    c, n = sympy.Rational(c), sympy.Rational(n)
    if c <= 0:
        return None
    root = sympy.sqrt(c)
    if root.is_Rational:
        return root, sympy.Integer(0)
    X, Y, Z = sympy.symbols("X Y Z", integer=True)
    scale_c, scale_n = c.p * c.q, n.p * n.q
    solution = diop_ternary_quadratic(X**2 + scale_n * Y**2 - scale_c * Z**2)
    if solution is None or None in solution or solution[2] == 0:
        return None
    x0, y0, z0 = (sympy.Integer(v) for v in solution)
    # X² + (n p q) Y² = (c p' q') Z²  ⇒  rescale to X² + n Y² = c.
    return x0 / (z0 * c.q), y0 * n.q / (z0 * c.q)


def tubular_section(
    phi: sympy.Expr, d: sympy.Expr, q: sympy.Expr, A: sympy.Expr, B: sympy.Expr
) -> Section:
    """The section ``(φ, d·A/q̃, d·B/q̃)`` of ``X`` through ``τ`` of the paper's Theorem
    "birational to tubular", with ``A² + n·B² = h``."""
    return Section(phi=phi, rho_u=d * A / q, rho_w=d * B / q)


def vanishes_on(f: Poly, surface: SurfaceMap) -> bool:
    """Whether ``f(N₁/D, N₂/D, N₃/D) = 0`` exactly: the homogenised ``f`` at ``(N₁, N₂, N₃, D)``,
    composed in flint and reduced modulo the radicals' relations. A nonzero normal form with
    several radicals is rechecked over sympy's algebraic field (the normal form is unique only
    for independent radicands)."""
    ring = surface.ring
    if f.ring.domain != QQ:
        ring = RadicalRing(ring.variables, tuple(sorted({*ring.radicals, *field_generators(f.ring.domain)}, key=str)))
        surface = SurfaceMap(ring, *(_recast(surface, ring)))
    degree = max(sum(m) for m in f.itermonoms())
    ctx = ring.context
    images = (*surface.numerators, surface.denominator)
    total = ctx.from_dict({})
    powers: dict[tuple[int, int], fmpq_mpoly] = {}
    for monom, coeff in f.items():
        term = ring.from_expr(to_expr(f.ring.domain, coeff))
        for i, e in enumerate((*monom, degree - sum(monom))):
            if e:
                if (i, e) not in powers:
                    powers[(i, e)] = ring.reduce(images[i] ** e)
                term = ring.reduce(term * powers[(i, e)])
        total += term
    total = ring.reduce(total)
    if total.is_zero() or len(ring.radicals) < 2:
        return total.is_zero()
    expr = ring.to_expr(total)
    return sympy.Poly(expr, *ring.symbols, extension=True).is_zero


def _recast(surface: SurfaceMap, ring: RadicalRing) -> tuple[tuple[fmpq_mpoly, ...], fmpq_mpoly]:
    """The same map written in a ring with more radicals."""
    nums = tuple(ring.from_expr(surface.ring.to_expr(p)) for p in surface.numerators)
    return nums, ring.from_expr(surface.ring.to_expr(surface.denominator))


def make_parametrization(f: Poly, surface: SurfaceMap, *, method: str, proper: bool | None) -> Parametrization | None:
    """A verified :class:`Parametrization`, or ``None`` when the substitution does not vanish."""
    if not vanishes_on(f, surface):
        return None
    return Parametrization(
        coordinates=tuple(str(c) for c in surface.coordinates()),  # type: ignore[arg-type]
        parameters=PARAMETERS,
        field=surface.ring.field,
        real=surface.ring.is_real,
        proper=proper,
        method=method,
        verified=True,
    )
