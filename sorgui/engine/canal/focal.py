"""The focal-sheet test of a canal surface, evaluated exactly on lines (docs/math.md §9).

For ``g = ∇f`` and ``H = Hess f`` the bordered matrix ``B(ν) = [[I − νH, g], [gᵀ, 0]]`` has
determinant ``Q(x, ν) = a₂ν² + a₁ν + a₀``; its roots give the two focal points ``p − νg`` of the
surface point ``p``. With ``(e, s) = adj(B(ν))·w`` (a principal direction) the canal condition is
``C = s·Q_ν − ∇ₓQ·e``; reduced by ``Q`` in ``ν`` it is ``C₁ν + C₀``, and

* X is canal ⇔ ``R = a₂C₀² − a₁C₀C₁ + a₀C₁² ≡ 0`` on X, Dupin ⇔ ``C₀ ≡ C₁ ≡ 0``,
  totally umbilic ⇔ ``a₁² − 4a₀a₂ ≡ 0``, developable ⇔ ``a₂ ≡ 0`` (then the finite root
  ``ν = −a₀/a₁`` must satisfy ``C``).

Everything is evaluated on a line ``p = p₀ + τd`` in the ring ``A = QQ[τ]/(F)``, ``F`` the
square-free part of ``f(p₀ + τd)``: an identity on X holds at every affine point of X ∩ line, so one
line with ``R ≢ 0 mod F`` proves "not canal". ``∇ₓQ`` comes from Jacobi's formula
``∂Q/∂x_k = tr(adj B · ∂B/∂x_k)`` with the third derivatives of ``f``. On canal lines the same
computation gives the points ``(m, ρ) = (p − ν*g, ν*²|g|²)`` of the SMAT, in ``A`` or, for the two
focal conics of a Dupin cyclide, in ``A[s]/(s² − (a₁² − 4a₀a₂))``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any

from flint import fmpq, fmpq_mpoly, fmpq_poly, nmod_poly

from ..errors import AnalysisError

NuPoly = list[Any]
"""A polynomial in ``ν`` with coefficients in ``A`` (``fmpq_poly`` mod ``F``, or ``nmod_poly`` in
the modular screen): coefficient of ``ν^i`` at index ``i``."""

PRINCIPAL_WEIGHTS = (3, -5, 7, 2)
"""The fixed vector ``w`` of ``(e, s) = adj(B)·w`` (any vector outside a proper subvariety)."""

GENERAL = "general"
DUPIN = "dupin"
UMBILIC = "umbilic"
DEVELOPABLE = "developable"


class UnluckyLine(AnalysisError):
    """The line is special for the test (``F`` constant, a needed inverse does not exist)."""


@dataclass(frozen=True)
class Pair:
    """An element ``u + v·s`` of ``A[s]/(s² − D)`` (``v = 0`` off the Dupin branch)."""

    u: fmpq_poly
    v: fmpq_poly


@dataclass(frozen=True)
class LineTest:
    """The focal-sheet test on one line: the values mod ``F`` and what they say.

    ``branch`` is ``general``, ``developable`` (``a₂ ≡ 0``), ``dupin`` (``C₀ ≡ C₁ ≡ 0``) or
    ``umbilic`` (``a₁² − 4a₀a₂ ≡ 0``); ``canal`` says whether the canal condition holds on the
    line. ``smat`` are the SMAT points ``(M₁, M₂, M₃, Mρ; W)``, ``(m, ρ) = (M, Mρ)/W``
    (``None`` when not canal or umbilic). ``residue`` and ``discriminant`` are ``None`` on a
    line proved not canal modulo a prime (:func:`line_test`).
    """

    point: tuple[int, int, int]
    direction: tuple[int, int, int]
    F: fmpq_poly
    branch: str
    canal: bool
    residue: fmpq_poly | None
    smat: tuple[Pair, Pair, Pair, Pair, Pair] | None
    discriminant: fmpq_poly | None


class Derivatives:
    """``f`` and its partial derivatives up to order 3 (flint), computed once per surface."""

    def __init__(self, f: fmpq_mpoly) -> None:
        self.f = f
        self.g = [f.derivative(i) for i in range(3)]
        self.h = {(i, j): self.g[i].derivative(j) for i in range(3) for j in range(i, 3)}
        self.t = {(i, j, k): self.h[(i, j)].derivative(k) for i in range(3) for j in range(i, 3) for k in range(j, 3)}

    def restrict(self, h: fmpq_mpoly, line: Sequence[fmpq_poly]) -> fmpq_poly:
        """``h(p₀ + τd)`` as a univariate polynomial."""
        result = fmpq_poly(0)
        powers: dict[tuple[int, int], fmpq_poly] = {}
        for monom, coeff in zip(h.monoms(), h.coeffs()):
            term = fmpq_poly(coeff)
            for i, e in enumerate(monom):
                if e:
                    if (i, e) not in powers:
                        powers[(i, e)] = line[i] ** e
                    term *= powers[(i, e)]
            result += term
        return result


def line_test(D: Derivatives, point: Sequence[int], direction: Sequence[int]) -> LineTest:
    """The focal-sheet test of ``f`` on the line ``point + τ·direction`` (exact).

    The test is first computed modulo the prime :data:`SCREEN_PRIME`: reduction modulo ``p`` is a
    ring homomorphism from ``A`` (its ``p``-integral elements) onto ``F_p[τ]/(F)``, so an element
    that is not zero there is not zero in ``A``. When ``a₂``, the discriminant, ``(C₀, C₁)`` and
    ``R`` are all nonzero modulo ``p``, the line is a witness of "not canal" without the
    computation over ``QQ``, whose coefficients grow with the degree; otherwise ``A`` decides.
    """
    line = [fmpq_poly([point[i], direction[i]]) for i in range(3)]
    fl = D.restrict(D.f, line)
    if fl.degree() < 1:
        raise UnluckyLine("f is constant on the line")
    F = fl.gcd(fl.derivative())
    F = _monic(fl / F if F.degree() > 0 else fl)
    x, y, z = point
    dx, dy, dz = direction
    key = ((x, y, z), (dx, dy, dz))
    restricted = (
        [D.restrict(h, line) for h in D.g],
        {k: D.restrict(h, line) for k, h in D.h.items()},
        {k: D.restrict(h, line) for k, h in D.t.items()},
    )
    if _fails_modulo_prime(F, *restricted):
        return LineTest(*key, F, GENERAL, False, None, None, None)
    ring = _Ring(F)
    g = [ring.reduce(h) for h in restricted[0]]
    H = {k: ring.reduce(h) for k, h in restricted[1].items()}
    T = {k: ring.reduce(h) for k, h in restricted[2].items()}
    a0, a1, a2, disc, C = _focal_terms(g, H, T, ring)
    p = [ring.reduce(x) for x in line]
    norm_g = ring.reduce(sum((gi * gi for gi in g), fmpq_poly(0)))
    if a2 == 0:
        if a1 == 0:
            raise UnluckyLine("both focal parameters are infinite on the line")
        # Developable: the finite root ν = −a₀/a₁ must satisfy C.
        value = _evaluate_at_ratio(C, -a0, a1, ring)
        canal = value.is_zero()
        smat = None
        if canal:
            smat = _smat(p, g, norm_g, Pair(-a0, fmpq_poly(0)), a1, ring)
        return LineTest(*key, F, DEVELOPABLE, canal, value, smat, disc)
    if disc == 0:
        return LineTest(*key, F, UMBILIC, True, fmpq_poly(0), None, disc)
    C0, C1 = _pseudo_remainder(C, a0, a1, a2, ring)
    if C0 == 0 and C1 == 0:
        nu = Pair(-a1, fmpq_poly(1))
        return LineTest(*key, F, DUPIN, True, fmpq_poly(0), _smat(p, g, norm_g, nu, 2 * a2, ring, disc), disc)
    R = _canal_polynomial(C0, C1, a0, a1, a2, ring)
    if R != 0:
        return LineTest(*key, F, GENERAL, False, R, None, disc)
    return LineTest(*key, F, GENERAL, True, R, _smat(p, g, norm_g, Pair(-C0, fmpq_poly(0)), C1, ring), disc)


def _focal_terms(
    g: list[Any], H: dict[tuple[int, int], Any], T: dict[tuple[int, int, int], Any], ring: _Ring
) -> tuple[Any, Any, Any, Any, NuPoly]:
    """``a₀, a₁, a₂`` of ``Q = det B(ν)``, its discriminant in ``ν`` and the canal polynomial
    ``C = s·Q_ν − ∇ₓQ·e``, in ``ring`` (``A``, or its image modulo a prime)."""
    B = _bordered(g, H, ring)
    adj = _adjugate(B, ring)
    Q = ring.trim(ring.add(*(ring.mul(B[0][c], adj[c][0]) for c in range(4))))
    a0, a1, a2 = (Q + [ring.zero] * 3)[:3]
    disc = ring.reduce(a1 * a1 - 4 * a0 * a2)
    dQ = [_jacobi(adj, _bordered_derivative(H, T, k, ring), ring) for k in range(3)]
    principal = [ring.add(*(ring.scale(w, adj[a][b]) for b, w in enumerate(PRINCIPAL_WEIGHTS))) for a in range(4)]
    Qnu = [Q[i] * i for i in range(1, len(Q))] or [ring.zero]
    C = ring.mul(principal[3], Qnu)
    for k in range(3):
        C = ring.add(C, ring.neg(ring.mul(dQ[k], principal[k])))
    return a0, a1, a2, disc, ring.trim(C)


SCREEN_PRIME = 2**61 - 1
"""The prime of the modular screen of :func:`line_test` (a Mersenne prime: no rational of a
surface's derivatives on a line has it in a denominator unless built to)."""


def _fails_modulo_prime(
    F: fmpq_poly,
    g: list[fmpq_poly],
    H: dict[tuple[int, int], fmpq_poly],
    T: dict[tuple[int, int, int], fmpq_poly],
) -> bool:
    """Whether the canal condition fails on the line already modulo :data:`SCREEN_PRIME` (a
    proof that it fails over ``QQ``; ``False`` means only that ``A`` must decide)."""
    image = _modular(F)
    if image is None:
        return False
    ring = _Ring(image)
    parts = []
    for h in (*g, *H.values(), *T.values()):
        part = _modular(h)
        if part is None:
            return False
        parts.append(ring.reduce(part))
    gm = parts[:3]
    Hm = dict(zip(H, parts[3 : 3 + len(H)]))
    Tm = dict(zip(T, parts[3 + len(H) :]))
    a0, a1, a2, disc, C = _focal_terms(gm, Hm, Tm, ring)
    if a2 == 0 or disc == 0:
        return False
    C0, C1 = _pseudo_remainder(C, a0, a1, a2, ring)
    if C0 == 0 and C1 == 0:
        return False
    R = _canal_polynomial(C0, C1, a0, a1, a2, ring)
    return bool(R != 0)


def _modular(h: fmpq_poly) -> nmod_poly | None:
    """``h`` modulo :data:`SCREEN_PRIME`, or ``None`` when a denominator is divisible by it."""
    p = SCREEN_PRIME
    coefficients = []
    for c in h.coeffs():
        q = int(c.q)
        if q % p == 0:
            return None
        coefficients.append(int(c.p) * pow(q, -1, p) % p)
    return nmod_poly(coefficients, p)


class _Ring:
    """Arithmetic in ``A = QQ[τ]/(F)`` and in ``A[ν]``."""

    def __init__(self, F: Any) -> None:
        self.F = F
        self.zero = F * 0
        self.one = self.zero + 1

    def reduce(self, a: Any) -> Any:
        return a % self.F

    def mul(self, P: NuPoly, Q: NuPoly) -> NuPoly:
        out = [self.zero] * (len(P) + len(Q) - 1)
        for i, a in enumerate(P):
            if a == 0:
                continue
            for j, b in enumerate(Q):
                if b != 0:
                    out[i + j] += a * b
        return [c % self.F for c in out]

    def add(self, *terms: NuPoly) -> NuPoly:
        n = max(len(t) for t in terms)
        return [sum((t[i] for t in terms if i < len(t)), self.zero) for i in range(n)]

    @staticmethod
    def neg(P: NuPoly) -> NuPoly:
        return [-c for c in P]

    def scale(self, c: int, P: NuPoly) -> NuPoly:
        return [c * x for x in P]

    @staticmethod
    def trim(P: NuPoly) -> NuPoly:
        P = list(P)
        while len(P) > 1 and P[-1] == 0:
            P.pop()
        return P


def _monic(F: fmpq_poly) -> fmpq_poly:
    return F / F.coeffs()[-1]


def _bordered(g: list[Any], H: dict[tuple[int, int], Any], ring: _Ring) -> list[list[NuPoly]]:
    """``B(ν) = [[I − νH, g], [gᵀ, 0]]`` with entries in ``A[ν]``."""
    one, zero = ring.one, ring.zero
    B: list[list[NuPoly]] = [[[zero]] * 4 for _ in range(4)]
    for i in range(3):
        for j in range(3):
            B[i][j] = [one if i == j else zero, -H[(min(i, j), max(i, j))]]
        B[i][3] = [g[i]]
        B[3][i] = [g[i]]
    return B


def _bordered_derivative(
    H: dict[tuple[int, int], Any], T: dict[tuple[int, int, int], Any], k: int, ring: _Ring
) -> list[list[NuPoly]]:
    """``∂B/∂x_k = [[−ν·∂H/∂x_k, ∂g/∂x_k], [∂gᵀ/∂x_k, 0]]``."""
    zero = ring.zero
    dB: list[list[NuPoly]] = [[[zero]] * 4 for _ in range(4)]
    for i in range(3):
        for j in range(3):
            first, second, third = sorted((i, j, k))
            dB[i][j] = [zero, -T[(first, second, third)]]
        dB[i][3] = [H[(min(i, k), max(i, k))]]
        dB[3][i] = dB[i][3]
    return dB


def _det(M: list[list[NuPoly]], ring: _Ring) -> NuPoly:
    """The determinant by expansion along the first row (matrices of size ≤ 3 here)."""
    if len(M) == 1:
        return M[0][0]
    total: NuPoly = [ring.zero]
    for j, entry in enumerate(M[0]):
        if all(c == 0 for c in entry):
            continue
        minor = [row[:j] + row[j + 1 :] for row in M[1:]]
        term = ring.mul(entry, _det(minor, ring))
        total = ring.add(total, term if j % 2 == 0 else ring.neg(term))
    return total


def _adjugate(B: list[list[NuPoly]], ring: _Ring) -> list[list[NuPoly]]:
    """``adj(B)[a][b] = (−1)^(a+b)·det(B without row b and column a)``."""
    adj: list[list[NuPoly]] = [[[]] * 4 for _ in range(4)]
    for a in range(4):
        for b in range(4):
            minor = [[B[r][c] for c in range(4) if c != a] for r in range(4) if r != b]
            d = _det(minor, ring)
            adj[a][b] = d if (a + b) % 2 == 0 else ring.neg(d)
    return adj


def _jacobi(adj: list[list[NuPoly]], dB: list[list[NuPoly]], ring: _Ring) -> NuPoly:
    """``tr(adj(B)·dB)``: the derivative of ``det B`` (Jacobi's formula)."""
    return ring.add(*(ring.mul(adj[a][b], dB[b][a]) for a in range(4) for b in range(4)))


def _pseudo_remainder(C: NuPoly, a0: Any, a1: Any, a2: Any, ring: _Ring) -> tuple[Any, Any]:
    """``a₂^k·C mod Q`` in ``ν``: the pair ``(C₀, C₁)`` of ``C₁ν + C₀``."""
    C = list(C)
    while len(C) > 2:
        lead, n = C[-1], len(C) - 1
        C = [ring.reduce(c * a2) for c in C]
        C[n - 2] = ring.reduce(C[n - 2] - lead * a0)
        C[n - 1] = ring.reduce(C[n - 1] - lead * a1)
        C.pop()
    C += [ring.zero] * (2 - len(C))
    return C[0], C[1]


def _canal_polynomial(C0: Any, C1: Any, a0: Any, a1: Any, a2: Any, ring: _Ring) -> Any:
    """``R = a₂C₀² − a₁C₀C₁ + a₀C₁²``: the resultant in ``ν`` of ``Q`` and ``C₁ν + C₀``, which
    vanishes on X exactly when X is canal (docs/math.md §9)."""
    return ring.reduce(a2 * ring.reduce(C0 * C0) - a1 * ring.reduce(C0 * C1) + a0 * ring.reduce(C1 * C1))


def _evaluate_at_ratio(C: NuPoly, num: fmpq_poly, den: fmpq_poly, ring: _Ring) -> fmpq_poly:
    """``den^n·C(num/den)``: ``C`` at the root of ``den·ν − num`` (homogenised)."""
    n = len(C) - 1
    total = fmpq_poly(0)
    for i, c in enumerate(C):
        total += ring.reduce(c * ring.reduce(num**i) * ring.reduce(den ** (n - i)))
    reduced: fmpq_poly = ring.reduce(total)
    return reduced


def _smat(
    p: list[fmpq_poly],
    g: list[fmpq_poly],
    norm_g: fmpq_poly,
    nu: Pair,
    den: fmpq_poly,
    ring: _Ring,
    disc: fmpq_poly | None = None,
) -> tuple[Pair, Pair, Pair, Pair, Pair]:
    """The SMAT points for ``ν = nu/den`` in homogeneous form ``(M₁, M₂, M₃, Mρ; W)`` with
    ``m = M/W``, ``ρ = Mρ/W``, ``W = den²``: ``M = den·(den·p − nu·g)``, ``Mρ = nu²|g|²``.
    No inverse in ``A`` is computed (slow over ``QQ``); ``den`` must be a unit mod ``F``."""
    if ring.F.gcd(ring.reduce(den)).degree() > 0:
        raise UnluckyLine("the focal parameter has a pole at a point of the line")
    arith = PairRing(ring.F, disc if disc is not None else fmpq_poly(0))
    zero = fmpq_poly(0)
    d = Pair(ring.reduce(den), zero)
    m1, m2, m3 = (
        arith.mul(d, arith.sub(arith.mul(d, Pair(p[i], zero)), arith.mul(nu, Pair(g[i], zero)))) for i in range(3)
    )
    rho = arith.mul(arith.mul(nu, nu), Pair(norm_g, zero))
    return m1, m2, m3, rho, arith.mul(d, d)


class PairRing:
    """Arithmetic in ``A[s]/(s² − D)``; with ``D = 0`` and ``v = 0`` it is ``A`` itself."""

    def __init__(self, F: fmpq_poly, D: fmpq_poly) -> None:
        self.F = F
        self.D = D

    def mul(self, a: Pair, b: Pair) -> Pair:
        F = self.F
        if a.v.is_zero() and b.v.is_zero():
            return Pair((a.u * b.u) % F, fmpq_poly(0))
        return Pair((a.u * b.u + ((a.v * b.v) % F) * self.D) % F, (a.u * b.v + a.v * b.u) % F)

    def sub(self, a: Pair, b: Pair) -> Pair:
        return Pair(a.u - b.u, a.v - b.v)

    def linear(self, coeffs: Sequence[fmpq | int], values: Sequence[Pair]) -> Pair:
        """``Σ cᵢ·valuesᵢ``."""
        u, v = fmpq_poly(0), fmpq_poly(0)
        for c, x in zip(coeffs, values):
            u += c * x.u
            v += c * x.v
        return Pair(u % self.F, v % self.F)


@dataclass(frozen=True)
class SmatSample:
    """The SMAT points of several canal lines, ready for interpolation (docs/math.md §9)."""

    tests: tuple[LineTest, ...]

    @cached_property
    def rings(self) -> tuple[PairRing, ...]:
        rings = []
        for t in self.tests:
            assert t.discriminant is not None  # a sample's lines are canal lines, decided over QQ
            rings.append(PairRing(t.F, t.discriminant))
        return tuple(rings)

    @property
    def point_count(self) -> int:
        """The number of (conjugate) points: ``deg F`` per line, twice on the Dupin branch."""
        return sum(t.F.degree() * (2 if t.branch == DUPIN else 1) for t in self.tests)
