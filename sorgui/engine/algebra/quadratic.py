"""Univariate polynomials over a quadratic field ``K = QQ(α)``, ``α² = −p·α − q``, in flint.

A parameterization of a genus-0 curve comes over ``QQ`` or a quadratic field (paraPlaneCurve's
conic step), often ``QQ(i)``, with coefficients of a hundred digits; sympy's square-free
decomposition over such a field (subresultants, every coefficient an algebraic number inverted
in pure Python) took seconds to a minute. Here a polynomial of ``K[t]`` is a pair ``(A, B)`` of
flint polynomials over ``QQ``, meaning ``A + α·B``; products and exact quotients go through the
norm ``B·B̄ ∈ QQ[t]``, and the greatest common divisor (:func:`gcd`) is computed modulo primes at
the two embeddings ``α ↦ ±ρ`` of ``K`` into ``GF(ℓ)`` and lifted (CRT, rational reconstruction,
checked by exact division), as :mod:`.numberfields` does for the parser's real fields. On top,
Yun's square-free decomposition (:func:`squarefree_decomposition`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy
from flint import fmpq, fmpq_poly, fmpz, nmod, nmod_poly
from sympy.polys.domains import QQ
from sympy.polys.domains.domain import Domain
from sympy.polys.rings import PolyElement, PolyRing

from ..errors import AnalysisError
from .numberfields import _crt, _rational_reconstruction

Pair = tuple[fmpq_poly, fmpq_poly]
"""``A + α·B`` in ``K[t]``."""

MAX_PRIMES = 400
"""Primes tried by the modular gcd before it gives up (each prime adds about 62 bits), at least:
inputs of many bits get more (:func:`_prime_limit`)."""


@dataclass(frozen=True)
class QuadraticField:
    """``QQ(α)`` with ``α² = −p·α − q`` (``p = q = 0`` stands for ``QQ`` itself)."""

    p: fmpq
    q: fmpq

    @property
    def rational(self) -> bool:
        return self.p == 0 and self.q == 0

    def mul(self, x: Pair, y: Pair) -> Pair:
        (a1, b1), (a2, b2) = x, y
        bb = b1 * b2
        return a1 * a2 - bb * self.q, a1 * b2 + a2 * b1 - bb * self.p

    def conjugate(self, x: Pair) -> Pair:
        """``σ(x)``, ``σ(α) = ᾱ = −p − α``."""
        a, b = x
        return a - b * self.p, -b

    def norm(self, x: Pair) -> fmpq_poly:
        """``x·σ(x) ∈ QQ[t]``."""
        a, b = self.mul(x, self.conjugate(x))
        assert b.is_zero()
        return a

    def divide(self, x: Pair, y: Pair) -> Pair | None:
        """``x / y`` when ``y`` divides ``x`` in ``K[t]``, else ``None``."""
        n = self.norm(y)
        a, b = self.mul(x, self.conjugate(y))
        qa, ra = divmod(a, n)
        qb, rb = divmod(b, n)
        return (qa, qb) if ra.is_zero() and rb.is_zero() else None

    def monic(self, x: Pair) -> Pair:
        """``x`` divided by its leading coefficient in ``K``."""
        top = degree(x)
        lead = (fmpq_poly([x[0][top]]), fmpq_poly([x[1][top]]))
        quotient = self.divide(x, lead)
        assert quotient is not None  # a nonzero constant divides everything
        return quotient

    def derivative(self, x: Pair) -> Pair:
        return x[0].derivative(), x[1].derivative()

    def sub(self, x: Pair, y: Pair) -> Pair:
        return x[0] - y[0], x[1] - y[1]


def field_of(D: Domain) -> QuadraticField | None:
    """sympy's ``QQ`` or quadratic ``QQ<α>`` as a :class:`QuadraticField` (``α`` its primitive
    element, of minimal polynomial ``x² + p·x + q``); ``None`` for a field of higher degree."""
    if D.is_QQ:
        return QuadraticField(fmpq(0), fmpq(0))
    if not D.is_AlgebraicField:
        return None
    modulus = [QQ.convert(c) for c in D.mod.to_list()]
    if len(modulus) != 3 or modulus[0] != 1:
        return None
    return QuadraticField(_fmpq(modulus[1]), _fmpq(modulus[2]))


def pair_of(g: PolyElement) -> Pair:
    """A polynomial of ``D[t]`` (sympy, ``D`` as in :func:`field_of`) as ``(A, B)``, ``g = A + α·B``."""
    D = g.ring.domain
    top = max((m[0] for m in g.itermonoms()), default=0)
    a, b = [fmpq(0)] * (top + 1), [fmpq(0)] * (top + 1)
    for (k,), c in g.items():
        parts = [QQ.convert(x) for x in c.to_list()] if D.is_AlgebraicField else [c]
        a[k] = _fmpq(parts[-1]) if parts else fmpq(0)
        b[k] = _fmpq(parts[-2]) if len(parts) > 1 else fmpq(0)
    return fmpq_poly(a), fmpq_poly(b)


def pair_expr(x: Pair, D: Domain, t: sympy.Symbol) -> sympy.Expr:
    """``A(t) + α·B(t)`` as a sympy expression (``α`` written in radicals, e.g. ``I``)."""
    alpha = sympy.Integer(0) if D.is_QQ else D.to_sympy(D([QQ.one, QQ.zero]))
    return sympy.expand(_poly_expr(x[0], t) + alpha * _poly_expr(x[1], t))


def pair_poly(x: Pair, ring: PolyRing) -> PolyElement:
    """``(A, B)`` as an element of sympy's ``D[t]`` (``ring``, ``D`` as in :func:`field_of`)."""
    D = ring.domain
    terms = {}
    for k in range(degree(x) + 1):
        a, b = QQ(int(x[0][k].p), int(x[0][k].q)), QQ(int(x[1][k].p), int(x[1][k].q))
        value = a if D.is_QQ else D([b, a])
        if value:
            terms[(k,)] = value
    return ring.from_dict(terms)


def _poly_expr(a: fmpq_poly, t: sympy.Symbol) -> sympy.Expr:
    return sympy.Add(*(sympy.Rational(int(c.p), int(c.q)) * t**k for k, c in enumerate(a.coeffs()) if c))


def _fmpq(c: Any) -> fmpq:  # noqa: ANN401 - an element of sympy's QQ
    return fmpq(int(QQ.numer(c)), int(QQ.denom(c)))


def degree(x: Pair) -> int:
    return max(x[0].degree(), x[1].degree())


def gcd(K: QuadraticField, x: Pair, y: Pair) -> Pair:
    """The monic ``gcd(x, y)`` in ``K[t]`` (``x`` nonzero)."""
    if K.rational:
        g = x[0].gcd(y[0])
        return g, fmpq_poly([])
    if degree(y) < 0:
        return K.monic(x)
    best: int | None = None
    used = 0
    modulus = fmpz(1)
    residues: list[fmpz] = []
    previous: Pair | None = None
    prime = (1 << 62) + 1
    discriminant = K.p * K.p - 4 * K.q
    for _ in range(_prime_limit(K, x, y)):
        prime = _next_prime(prime, discriminant)
        images = _images(K, x, y, prime, discriminant)
        if images is None:
            continue
        plus, minus, at_plus, root = images
        if plus.degree() != minus.degree():
            continue
        d = plus.degree()
        if best is not None and d > best:
            continue  # an unlucky prime
        if best is None or d < best:
            best, modulus, residues, previous, used = d, fmpz(1), [], None, 0
        inverse = pow(root, -1, prime)
        current = []
        for k in range(d + 1):
            u, v = int(plus[k]), int(minus[k])
            g1 = (u - v) * inverse % prime  # g(a±) = G₀ + a±·G₁ at the roots a± of α's polynomial
            current += [(u - at_plus * g1) % prime, g1]
        residues = [_crt(residues[i] if residues else fmpz(0), modulus, c, prime) for i, c in enumerate(current)]
        modulus *= prime
        used += 1
        if used & (used - 1):
            continue  # lift after 1, 2, 4, 8, … primes: a lift costs more than an image
        found = [_rational_reconstruction(r, modulus) for r in residues]
        lifted = [c for c in found if c is not None]
        if len(lifted) < len(found):
            continue
        candidate = (
            fmpq_poly([lifted[2 * k] for k in range(d + 1)]),
            fmpq_poly([lifted[2 * k + 1] for k in range(d + 1)]),
        )
        if candidate == previous and K.divide(x, candidate) is not None and K.divide(y, candidate) is not None:
            return candidate
        previous = candidate
    raise AnalysisError("the modular gcd over a quadratic field did not settle (internal error)")


def _prime_limit(K: QuadraticField, x: Pair, y: Pair) -> int:
    """How many primes the modular gcd may use: :data:`MAX_PRIMES`, or for inputs of many bits
    the power of two (a lift comes after 1, 2, 4, … primes) that covers four times their bits
    and the field's. The gcd of the ``P²`` of a 6-digit rounded torus's nearest surface, over
    ``QQ(√d)`` with a 1,200-bit ``d`` and coefficients of 10,000 bits, settled after 512."""
    field = (K.p.p, K.p.q, K.q.p, K.q.q)
    bits = _bits(x) + _bits(y) + sum(abs(int(n)).bit_length() for n in field)
    needed = 4 * bits // 62 + 1
    return max(MAX_PRIMES, 1 << (needed - 1).bit_length())


def _bits(x: Pair) -> int:
    """The most bits of a numerator or denominator of ``x``'s coefficients."""
    return max((max(abs(int(c.p)).bit_length(), int(c.q).bit_length()) for part in x for c in part.coeffs()), default=0)


def squarefree_decomposition(K: QuadraticField, x: Pair) -> list[tuple[Pair, int]]:
    """``[(g₁, 1), (g₂, 2), …]`` with ``x = c·Π gᵢ^i``, the ``gᵢ`` monic, square-free and coprime
    (Yun's algorithm; the ``gᵢ`` equal to 1 are left out)."""
    c = gcd(K, x, K.derivative(x))
    w, y = _quotient(K, x, c), _quotient(K, K.derivative(x), c)
    out = []
    i = 1
    while degree(w) > 0:
        z = K.sub(y, K.derivative(w))
        g = gcd(K, w, z)
        if degree(g) > 0:
            out.append((g, i))
        w, y = _quotient(K, w, g), _quotient(K, z, g)
        i += 1
    return out


def _quotient(K: QuadraticField, x: Pair, y: Pair) -> Pair:
    found = K.divide(x, y)
    if found is None:
        raise AnalysisError("an exact division in K[t] left a remainder (internal error)")
    return found


def _next_prime(prime: int, discriminant: fmpq) -> int:
    """The next prime modulo which the discriminant of α's polynomial is a nonzero square (so
    that ``K`` has two embeddings into ``GF(ℓ)``)."""
    n, d = int(discriminant.p), int(discriminant.q)
    while True:
        prime += 2
        if not fmpz(prime).is_prime() or d % prime == 0:
            continue
        value = n * pow(d, -1, prime) % prime
        if value and pow(value, (prime - 1) // 2, prime) == 1:
            return prime


def _images(
    K: QuadraticField, x: Pair, y: Pair, prime: int, discriminant: fmpq
) -> tuple[nmod_poly, nmod_poly, int, int] | None:
    """The gcds of the images of ``x`` and ``y`` at both embeddings ``α ↦ a± = (−p ± ρ)/2``
    (``ρ² = Δ``), ``a₊`` and ``ρ``; ``None`` when a denominator or a leading coefficient vanishes
    modulo ``prime``."""
    root = int(nmod(int(discriminant.p) * pow(int(discriminant.q), -1, prime), prime).sqrt())
    p = _mod(K.p, prime)
    if p is None or not root:
        return None
    parts = []
    for pair in (x, y):
        reduced = [_poly_mod(part, prime) for part in pair]
        if reduced[0] is None or reduced[1] is None:
            return None
        parts.append((reduced[0], reduced[1], degree(pair)))
    half = pow(2, -1, prime)
    roots = [(-p + root) * half % prime, (-p - root) * half % prime]
    gcds = []
    for alpha in roots:
        images = [a + b * alpha for a, b, _ in parts]
        if any(image.degree() != d for image, (_, _, d) in zip(images, parts)):
            return None
        gcds.append(images[0].gcd(images[1]))
    return gcds[0], gcds[1], roots[0], root


def _mod(c: fmpq, prime: int) -> int | None:
    d = int(c.q) % prime
    return None if not d else int(c.p) * pow(d, -1, prime) % prime


def _poly_mod(a: fmpq_poly, prime: int) -> nmod_poly | None:
    """``a`` modulo ``prime`` (its numerator in C, times the inverse of its denominator)."""
    d = int(a.denom()) % prime
    if not d:
        return None
    return nmod_poly(a.numer(), prime) * pow(d, -1, prime)
