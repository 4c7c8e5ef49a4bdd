"""Two sections that sweep to one map of ``X`` up to a change of parameters (docs/math.md §6,
"One map, listed once").

A section ``c + φ(t)·a + ρ₁(t)·u + ρ₂(t)·w`` (:class:`.parametrization.Section`) is swept about
the axis by the rotations ``R(σ)`` of the ``K``-rational circle, ``R(σ)·R(σ₀) = R(μ(σ))`` with
``μ(σ) = (σ + σ₀)/(1 − n·σ·σ₀)`` (``n = |a|²``; the half turn ``σ₀ = ∞`` gives
``μ(σ) = −1/(n·σ)``). So when ``second(t) = R(σ₀)·first(ψ(t))`` for a Möbius map ``ψ``, the two
sweeps are one map after the bijections ``σ ↦ μ(σ)``, ``t ↦ ψ(t)``: :func:`same_sweep` finds
``ψ`` and ``σ₀`` exactly, or says there are none it can prove. A typed parametrization that is
itself a sweep (:func:`typed_sweep`) is compared with the swept maps the same way.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy

from ..algebra.linalg import Vector
from .parametrization import Section, T

S = sympy.Symbol("s")
SAMPLES = (0, 1, -1, 2, -2, 3, -3, sympy.Rational(1, 2), sympy.Rational(-1, 2), sympy.Rational(1, 3))
"""The values of ``t`` at which ``second`` is matched with ``first`` to find ``ψ``: three are
needed where each has one preimage under ``first``'s height and radius (a pole or a double point
is passed over)."""


@dataclass(frozen=True)
class Reparametrization:
    """``sweep(second)(s, t) = sweep(first)(s_image, t_image)``, both images Möbius maps."""

    s_image: sympy.Expr
    t_image: sympy.Expr

    def describe(self) -> str:
        """`` with t ↦ 1/4·t`` (a rescaling, as it has always been written), `` with s ↦ −1/s,
        t ↦ −t − 2``, or ``""`` for the identity."""
        if self.s_image == S:
            if self.t_image == T:
                return ""
            k = sympy.cancel(self.t_image / T)
            if not k.has(T):
                return f" with t ↦ {k}·t"
        changes = [f"{old} ↦ {new}" for old, new in ((S, self.s_image), (T, self.t_image)) if new != old]
        return f" with {', '.join(changes)}"


def same_sweep(first: Section, second: Section, n: sympy.Expr) -> Reparametrization | None:
    """How ``second``'s sweep is ``first``'s after bijections of the parameters, or ``None``: a
    rescaling ``t ↦ k·t`` (``k`` real, perhaps irrational: :func:`rescaling`), else a Möbius map
    of ``t`` over ``K`` with a rotation about the axis (:func:`_turned`)."""
    if first.named or second.named:
        return None
    k = rescaling(first, second)
    if k is not None:
        return Reparametrization(S, k * T)
    return _turned(first, second, n)


def rescaling(first: Section, second: Section) -> sympy.Expr | None:
    """The real constant ``k ≠ 0`` with ``second(t) = first(k·t)``, or ``None`` (docs/math.md §6):
    then both sweep to the same map up to ``t ↦ k·t``, a bijection of the parameter line.

    In lowest terms, ``first(k·t) = second(t)`` scales the coefficient of ``tʲ`` in a numerator
    or denominator of ``first`` by ``kʲ`` (up to one common factor), so two of its terms, of
    degrees ``i < j``, give ``k^(j−i)`` (a monomial ``c·tᵐ`` gives ``kᵐ``); each real root is a
    candidate, accepted only when the three identities hold exactly."""
    if first.named or second.named:
        return None
    pairs = list(zip((first.phi, first.rho_u, first.rho_w), (second.phi, second.rho_u, second.rho_w)))
    moving = [(a, b) for a, b in pairs if a.has(T)]
    candidates = _scales(*moving[0]) if moving else [sympy.Integer(1)]
    for k in candidates:
        if all(_vanishes(a.subs(T, k * T) - b) for a, b in pairs):
            return k
    return None


def _scales(a: sympy.Expr, b: sympy.Expr) -> list[sympy.Expr]:
    """The real ``k`` that the terms of ``a`` and ``b`` allow for ``a(k·t) = b(t)`` (see
    :func:`rescaling`); ``a`` depends on ``t``."""
    for mine, theirs in zip(sympy.fraction(sympy.cancel(a)), sympy.fraction(sympy.cancel(b))):
        p, q = sympy.Poly(mine, T), sympy.Poly(theirs, T)
        terms = p.terms()
        if len(terms) < 2:
            continue
        (j,), top = terms[0]
        (i,), low = terms[-1]
        if q.degree() != j or q.coeff_monomial(T**i) == 0:
            return []
        return _real_roots_of_power(q.coeff_monomial(T**j) * low / (q.coeff_monomial(T**i) * top), j - i)
    ratio = sympy.cancel(b / a)  # a = c·tᵐ: b = c·kᵐ·tᵐ
    numerator, denominator = sympy.fraction(sympy.cancel(a))
    m = sympy.degree(numerator, T) - sympy.degree(denominator, T)
    return [] if ratio.has(T) or m == 0 else _real_roots_of_power(ratio if m > 0 else 1 / ratio, abs(m))


def _real_roots_of_power(ratio: sympy.Expr, n: int) -> list[sympy.Expr]:
    """The real ``k`` with ``kⁿ = ratio`` (``n ≥ 1``)."""
    ratio = sympy.radsimp(ratio)
    if ratio == 0 or not ratio.is_real:
        return []
    root = sympy.root(abs(ratio), n)
    if n % 2:
        return [root if ratio > 0 else -root]
    return [root, -root] if ratio > 0 else []


def _turned(first: Section, second: Section, n: sympy.Expr) -> Reparametrization | None:
    """``second(t) = R(σ₀)·first(ψ(t))`` with ``ψ`` Möbius: ``ψ`` from three values of ``t``
    where ``first``'s height ``φ`` and squared radius ``ρ₁² + n·ρ₂²`` (which a rotation keeps)
    take ``second``'s values at one ``τ`` only (the gcd of the two numerators is linear), then
    ``R(σ₀) = (t₁, t₂)`` from ``t₁·N = ρ₁'·ρ₁ + n·ρ₂'·ρ₂``, ``t₂·N = ρ₂'·ρ₁ − ρ₁'·ρ₂`` (``'``:
    ``second``'s; ``ρ`` taken at ``ψ(t)``, ``N`` its squared radius), which must be constants. Every
    identity is then checked exactly."""
    invariants = [
        (first.phi, second.phi),
        (first.rho_u**2 + n * first.rho_w**2, second.rho_u**2 + n * second.rho_w**2),
    ]
    if any(_degree(a) != _degree(b) for a, b in invariants):
        return None  # a Möbius map keeps the degree of a rational function
    moving = [(sympy.cancel(a), sympy.cancel(b)) for a, b in invariants if a.has(T)]
    if not moving:
        return None
    points = _matched_points(moving)
    if points is None:
        return None
    psi = _moebius(points)
    if psi is None:
        return None
    u1, w1 = first.rho_u.subs(T, psi), first.rho_w.subs(T, psi)
    u2, w2 = second.rho_u, second.rho_w
    norm = u1**2 + n * w1**2
    if _vanishes(norm):
        return None
    t1, t2 = sympy.cancel((u2 * u1 + n * w2 * w1) / norm), sympy.cancel((w2 * u1 - u2 * w1) / norm)
    if t1.has(T) or t2.has(T):
        return None
    identities = (first.phi.subs(T, psi) - second.phi, t1 * u1 - n * t2 * w1 - u2, t2 * u1 + t1 * w1 - w2)
    if not all(_vanishes(e) for e in identities):
        return None
    if _vanishes(t1 + 1):
        s_image = -1 / (n * S)  # the half turn
    else:
        sigma0 = sympy.cancel(t2 / (1 + t1))
        s_image = S if sigma0 == 0 else sympy.cancel((S + sigma0) / (1 - n * S * sigma0))
    return Reparametrization(s_image, psi)


def _matched_points(moving: list[tuple[sympy.Expr, sympy.Expr]]) -> list[tuple[sympy.Expr, sympy.Expr]] | None:
    """Three pairs ``(t₀, τ)`` with ``a(τ) = b(t₀)`` for every ``(a, b)`` of ``moving`` at exactly one
    ``τ`` (from :data:`SAMPLES`); ``None`` when fewer are found."""
    points: list[tuple[sympy.Expr, sympy.Expr]] = []
    for t0 in SAMPLES:
        values = [b.subs(T, t0) for _, b in moving]
        if not all(v.is_finite for v in values):
            continue
        common: sympy.Poly | None = None
        for (a, _), value in zip(moving, values):
            equation = sympy.Poly(sympy.numer(sympy.together(a - value)), T, extension=True)
            common = equation if common is None else sympy.gcd(common, equation)
        if common is None or common.degree() != 1:
            continue
        low, high = common.all_coeffs()[::-1]
        points.append((sympy.Integer(t0), -low / high))
        if len(points) == 3:
            return points
    return None


def _moebius(points: list[tuple[sympy.Expr, sympy.Expr]]) -> sympy.Expr | None:
    """The Möbius map ``(α·t + β)/(γ·t + δ)`` sending each ``t₀`` to its ``τ``, or ``None``."""
    rows = sympy.Matrix([[t0, 1, -tau * t0, -tau] for t0, tau in points])
    null = rows.nullspace()
    if len(null) != 1:
        return None
    alpha, beta, gamma, delta = (sympy.radsimp(c) for c in null[0])
    if _vanishes(alpha * delta - beta * gamma):
        return None
    return sympy.cancel((alpha * T + beta) / (gamma * T + delta))


def _degree(a: sympy.Expr, variable: sympy.Symbol = T) -> int:
    """The degree of the rational function ``a`` of ``variable``: its numerator's or
    denominator's, the larger, in lowest terms."""
    numerator, denominator = sympy.fraction(sympy.cancel(a))
    return int(max(sympy.degree(numerator, variable), sympy.degree(denominator, variable)))


def _vanishes(e: sympy.Expr) -> bool:
    """Whether the rational function ``e`` is zero: its numerator expands to 0."""
    return bool(sympy.expand(sympy.numer(sympy.together(e))) == 0)


@dataclass(frozen=True)
class TypedSweep:
    """A typed map ``X(s, t)`` that is a sweep: in the axis frame its height and squared radius
    depend on the parameter ``profile_index`` alone, and ``X(q, v) = sweep(section)(σ(q), v)``
    with ``σ`` a Möbius map of the other parameter ``q`` (``v`` written ``t`` in ``section``)."""

    section: Section
    profile_index: int
    sigma: tuple[sympy.Expr, sympy.Expr, sympy.Expr, sympy.Expr]
    """``(α, β, γ, δ)``: ``σ(q) = (α·q + β)/(γ·q + δ)``."""

    def given_in(self, found: Reparametrization) -> tuple[sympy.Expr, sympy.Expr]:
        """The typed map's ``(s, t)`` as functions of another sweep's ``(s, t)``, when that sweep
        is this section's after ``found`` (:func:`same_sweep`): ``X(q, v)`` with ``v = ψ(t)``
        and ``σ(q) = μ(s)``."""
        alpha, beta, gamma, delta = self.sigma
        y = found.s_image  # σ(q) = y: q = (δ·y − β)/(α − γ·y)
        q_image = sympy.cancel((delta * y - beta) / (alpha - gamma * y))
        return (q_image, found.t_image) if self.profile_index == 1 else (found.t_image, q_image)


def typed_sweep(given: GivenMap, frame: tuple[Vector, Vector, Vector, Vector], n: Any) -> TypedSweep | None:
    """The typed map ``given`` as a sweep about the axis of ``frame`` (``c, a, u, w = a × u``
    over ``K``; ``n = |a|²``), or ``None`` when it is not one (docs/math.md §6, "One map, listed
    once"). With ``D = X − c·W`` its frame coordinates are ``φ = a·D/(n·W)``, ``ρ_u = U/(|u|²·W)``,
    ``ρ_w = V/(n·|u|²·W)`` (``U = u·D``, ``V = w·D``). In polynomials of ``K[s, t]``, no
    cancellation: ``φ`` and the squared radius ``(n·U² + V²)/(n·|u|⁴·W²)`` depend on one parameter
    ``v`` alone (their derivatives in the other, ``q``, vanish); the section is the map at a value
    ``q₀`` (``U₀, V₀, W₀``); ``σ(q) = t₂/(1 + t₁)`` of the turn taking it to ``X(q, v)`` (as in
    :func:`_turned`) is read at one value of ``v`` and must be a Möbius map, and the map is then
    checked to be that turn of the section, identically."""
    ring, (X, W) = given.ring, (given.numerators, given.denominator)
    K = ring.domain
    c, a, u, w = ([ring.ground_new(K.convert(x)) for x in vector] for vector in frame)
    n = ring.ground_new(K.convert(n))
    D = [x - ci * W for x, ci in zip(X, c)]
    phi, U, V = (sum((vi * d for vi, d in zip(vector, D)), ring.zero) for vector in (a, u, w))
    radius = n * U**2 + V**2
    free = [
        q
        for q in ring.gens
        if not (phi.diff(q) * W - phi * W.diff(q)) and not (radius.diff(q) * W - 2 * radius * W.diff(q))
    ]
    if len(free) != 1:
        return None  # height and radius must follow one parameter: the profile's
    q = free[0]
    v = ring.gens[1] if q == ring.gens[0] else ring.gens[0]
    for q0 in SAMPLES:
        U0, V0, W0 = (p.subs(q, K.convert(q0)) for p in (U, V, W))
        radius0 = n * U0**2 + V0**2
        if not W0 or not radius0:
            continue
        top = (V * U0 - U * V0) * W0  # t₂ and 1 + t₁ over one denominator
        bottom = radius0 * W + (n * U * U0 + V * V0) * W0
        sigma = _moebius_in(q, v, top, bottom)
        if sigma is None:
            return None
        A, B = sigma
        turned = (B**2 - n * A**2, 2 * A * B, B**2 + n * A**2)  # R(σ) = (B² − nA², 2AB)/(B² + nA²)
        if U * W0 * turned[2] != W * (turned[0] * U0 - turned[1] * V0) or V * W0 * turned[2] != W * (
            turned[1] * U0 * n + turned[0] * V0
        ):
            return None
        uu = sum((ui * ui for ui in u), ring.zero)
        named = {v.as_expr(): T}
        section = Section(
            *(
                sympy.cancel((p.as_expr() / d.as_expr()).subs(named))
                for p, d in ((phi.subs(q, K.convert(q0)), n * W0), (U0, uu * W0), (V0, n * uu * W0))
            )
        )
        (alpha, beta), (gamma, delta) = ((K.to_sympy(p.coeff(q)), K.to_sympy(p.coeff(1))) for p in (A, B))
        return TypedSweep(section, 0 if v == ring.gens[0] else 1, (alpha, beta, gamma, delta))
    return None


def _moebius_in(q: Any, v: Any, top: Any, bottom: Any) -> tuple[Any, Any] | None:
    """``top/bottom`` (polynomials in ``q`` and ``v``) as ``A(q)/B(q)`` in lowest terms, read at a
    value of ``v`` where ``bottom`` does not vanish, when that is a Möbius map of ``q``; else ``None``.
    That it does not depend on ``v`` is left to the identities the caller checks."""
    K = top.ring.domain
    for v0 in SAMPLES:
        b = bottom.subs(v, K.convert(v0))
        if not b:
            continue
        A, B = top.subs(v, K.convert(v0)), b
        common = A.gcd(B)
        A, B = A.quo(common), B.quo(common)
        if max(A.degree(q), B.degree(q)) != 1 or not (A * B.diff(q) - B * A.diff(q)):
            return None
        return A, B
    return None


@dataclass(frozen=True)
class GivenMap:
    """A typed parametrization ``X/W``: its numerators and denominator in ``K[s, t]`` (sympy's
    sparse polynomials, generators :data:`S` and :data:`T`), and the names the user gave its two
    parameters."""

    numerators: tuple[Any, Any, Any]
    denominator: Any
    names: tuple[str, str]

    @property
    def ring(self) -> Any:  # noqa: ANN401 - sympy's PolyRing
        return self.denominator.ring
