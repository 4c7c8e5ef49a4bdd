"""Polynomials over ``K = QQ(√d₁, …, √d_k)`` computed over ``QQ`` in flint (docs/math.md §5).

sympy's arithmetic over an algebraic field is pure Python and, in several variables, orders of
magnitude slower than flint over ``QQ``. Here an element of ``K`` is written in the radical
basis: each independent square root becomes an extra flint variable ``ρᵢ`` with ``ρᵢ² = dᵢ``,
and a polynomial over ``K`` is an ``fmpq_mpoly`` in ``(variables, ρ₁, …, ρ_k)`` reduced to
degree ≤ 1 in every ``ρᵢ`` (a unique normal form: the ``dᵢ`` are chosen multiplicatively
independent modulo squares). On top of it:

* :func:`compose`: ``f(images)`` over ``K`` (the profile ``p̃(s, r) = f(c + s·a + r·u)``);
* :func:`norm`: ``N(F) = Π_σ σ(F) ∈ QQ[variables]``, by ``A + ρB ↦ A² - d·B²`` once per root;
* :func:`factor`: Trager's algorithm. After a shift ``x ↦ x - s·θ`` (``θ = Σ ρᵢ``) the norm of
  ``F`` is factored over ``QQ`` by flint, ``N = c·Π Pᵢ^eᵢ``; each ``Pᵢ`` gives the factor
  ``gᵢ = gcd_K(F, Pᵢ(x + s·θ))``. One ``Pᵢ`` with ``eᵢ = 1`` means ``F`` is irreducible over ``K``
  (``N(F)`` irreducible over ``QQ``); otherwise the gcds are computed modulo primes at all
  ``2^k`` embeddings of ``K`` and lifted (CRT and rational reconstruction). The answer is
  checked exactly: ``F = c·Π gᵢ^eᵢ`` and ``N(gᵢ) = Pᵢ`` up to a constant (so each ``gᵢ`` is
  irreducible over ``K``).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache
from itertools import product
from math import isqrt
from typing import Any, TypeAlias

import sympy
from flint import fmpq, fmpq_mat, fmpq_mpoly, fmpq_mpoly_ctx, fmpz, nmod, nmod_mpoly, nmod_mpoly_ctx
from sympy.polys.domains import QQ
from sympy.polys.domains.domain import Domain
from sympy.polys.rings import PolyElement, PolyRing

from ..errors import AnalysisError, OutOfReach
from .factoring import quick_factorization

Poly: TypeAlias = PolyElement


# --- the radical basis of K ---------------------------------------------------------------


@dataclass(frozen=True)
class RadicalBasis:
    """``K = QQ(√d₁, …, √d_k)`` with independent square-free ``dᵢ``: the change of basis between
    sympy's powers ``1, θ, …, θⁿ⁻¹`` of the primitive element and the radical monomials
    ``ρ^S = Π_{i∈S} ρᵢ`` (``S`` a bit mask, ``n = 2^k``)."""

    radicands: tuple[int, ...]
    to_radicals: fmpq_mat
    from_radicals: fmpq_mat

    @property
    def degree(self) -> int:
        return 1 << len(self.radicands)


RADICAND_BITS = 192
"""A radicand of at most this many bits (57 digits) is factored whole, as before there was a
limit (flint: seconds at worst): a field's square roots must not become undecided where they
were not."""


@lru_cache(maxsize=256)
def _factors(m: int) -> tuple[tuple[int, int], ...]:
    """The factorization of ``m > 0`` as ``(prime, exponent)`` pairs, kept: the radicands of a
    field are factored again for every square root taken in it, and those of a nearest exact
    surface have 30–60 digits (tens of milliseconds each). Only as far as is quick
    (:func:`.factoring.quick_factorization`): the nearest surface of a rounded torus printed
    with 6 digits had a radicand of hundreds of digits, and flint ran for minutes."""
    found = quick_factorization(m, RADICAND_BITS)
    if found is None:
        digits = len(str(m))
        raise OutOfReach(
            f"the square-free part of an integer of {digits} digits is needed; it was not factored quickly"
        )
    return tuple(sorted(found.items()))


def _squarefree(m: int) -> tuple[int, int]:
    """``m = core·q²`` with ``core`` square-free: ``(core, q)``."""
    core, q = 1, 1
    for p, e in _factors(m):
        core *= p ** (e % 2)
        q *= p ** (e // 2)
    return core, q


def _odd_primes(m: int) -> frozenset[int]:
    """The primes dividing the square-free part of ``m``."""
    return frozenset(p for p, e in _factors(m) if e % 2)


def squarefree_core(m: int) -> int:
    """The square-free part of the positive integer ``m``."""
    return _squarefree(m)[0]


class _Decomposer:
    """Writes ``√m`` as ``ρ^S / q`` in the independent radicands (linear algebra over GF(2) on
    the sets of primes dividing the square-free radicands)."""

    def __init__(self) -> None:
        self.radicands: list[int] = []
        self.pivots: dict[int, tuple[frozenset[int], int]] = {}  # prime -> (primes, mask)

    def _reduce(self, primes: frozenset[int]) -> tuple[frozenset[int], int]:
        mask = 0
        for p in sorted(self.pivots, reverse=True):
            if p in primes:
                other, m = self.pivots[p]
                primes, mask = primes ^ other, mask ^ m
        return primes, mask

    def add(self, m: int) -> None:
        core, _ = _squarefree(m)
        rest, mask = self._reduce(_odd_primes(m))
        if rest:
            bit = 1 << len(self.radicands)
            self.radicands.append(core)
            self.pivots[max(rest)] = (rest, mask ^ bit)

    def decompose(self, m: int) -> tuple[int, fmpq]:
        """``(S, c)`` with ``√m = c·ρ^S``."""
        core, q = _squarefree(m)
        rest, mask = self._reduce(_odd_primes(m))
        if rest:
            raise AnalysisError(f"sqrt({m}) does not lie in the coefficient field")
        prod = 1
        for i, d in enumerate(self.radicands):
            if mask >> i & 1:
                prod *= d
        # ρ^S = √prod = √(core·(prod/core)) and prod/core is a perfect square.
        _, r = _squarefree(prod // core)
        return mask, fmpq(q, r)


def _multiply(u: dict[int, fmpq], v: dict[int, fmpq], radicands: Sequence[int]) -> dict[int, fmpq]:
    """The product of two elements of ``K`` in the radical basis (bit mask → coefficient)."""
    out: dict[int, fmpq] = {}
    for a, x in u.items():
        for b, y in v.items():
            c = x * y
            for i, d in enumerate(radicands):
                if a >> i & 1 and b >> i & 1:
                    c *= d
            out[a ^ b] = out.get(a ^ b, fmpq(0)) + c
    return out


@lru_cache(maxsize=64)
def radical_basis(K: Domain) -> RadicalBasis:
    """The radical basis of the real multiquadratic field ``K`` (``QQ(√…)`` from the parser)."""
    dec = _Decomposer()
    for g in K.orig_ext:
        value = sympy.expand(g**2)
        if not (value.is_Rational and value > 0):
            raise AnalysisError(f"the field {K} is not a real multiquadratic field")
        dec.add(int(value.p * value.q))
    n = 1 << len(dec.radicands)
    if n != K.mod.degree():
        raise AnalysisError(f"the field {K} is not a multiquadratic field of degree {n}")
    theta: dict[int, fmpq] = {}
    for term in sympy.Add.make_args(sympy.expand(K.ext.as_expr())):
        coeff, rest = term.as_coeff_Mul()
        value = sympy.Rational(rest**2)
        mask, c = dec.decompose(int(value.p * value.q))
        c = c / value.q if value.q != 1 else c
        theta[mask] = theta.get(mask, fmpq(0)) + c * fmpq(int(sympy.Rational(coeff).p), int(sympy.Rational(coeff).q))
    power: dict[int, fmpq] = {0: fmpq(1)}
    columns = []
    for _ in range(n):
        columns.append([power.get(mask, fmpq(0)) for mask in range(n)])
        power = _multiply(power, theta, dec.radicands)
    to_radicals = fmpq_mat(n, n, [columns[j][i] for i in range(n) for j in range(n)])
    return RadicalBasis(tuple(dec.radicands), to_radicals, to_radicals.inv())


def supports(K: Domain) -> bool:
    """Whether ``K`` is a real multiquadratic field ``QQ(√d₁, …)`` (the parser's fields), which
    this module handles; other algebraic fields stay with sympy."""
    try:
        radical_basis(K)
    except AnalysisError:
        return False
    return True


# --- elements -------------------------------------------------------------------------------


def element_to_radicals(K: Domain, c: Any) -> dict[int, fmpq]:
    """``c ∈ K`` in the radical basis: bit mask ``S`` → coefficient of ``ρ^S``."""
    basis = radical_basis(K)
    n = basis.degree
    dense = [_qq(q) for q in c.to_list()]
    dense = [fmpq(0)] * (n - len(dense)) + dense
    column = basis.to_radicals * fmpq_mat(n, 1, dense[::-1])
    return {mask: column[mask, 0] for mask in range(n) if column[mask, 0] != 0}


def element_from_radicals(K: Domain, vector: dict[int, fmpq]) -> Any:
    """The element ``Σ c_S·ρ^S`` of ``K``."""
    basis = radical_basis(K)
    n = basis.degree
    theta = basis.from_radicals * fmpq_mat(n, 1, [vector.get(mask, fmpq(0)) for mask in range(n)])
    return K([QQ(int(theta[i, 0].p), int(theta[i, 0].q)) for i in reversed(range(n))])


def _radicand_product(radicands: Sequence[int], mask: int) -> int:
    value = 1
    for i, d in enumerate(radicands):
        if mask >> i & 1:
            value *= d
    return value


def embed(c: Any, K: Domain, L: Domain) -> Any:
    """``c ∈ K`` as an element of the multiquadratic field ``L ⊇ K``."""
    if K == L:
        return c
    source = radical_basis(K).radicands
    target = _decomposer(L)
    vector: dict[int, fmpq] = {}
    for mask, q in element_to_radicals(K, c).items():
        image, scale = target.decompose(_radicand_product(source, mask))
        vector[image] = vector.get(image, fmpq(0)) + q * scale
    return element_from_radicals(L, vector)


def rational_sqrt(K: Domain, q: fmpq) -> Any | None:
    """The non-negative square root of the rational ``q ≥ 0`` in ``K``, or ``None`` if it is not
    in ``K`` (or ``q < 0``: ``K`` is real)."""
    if q < 0:
        return None
    if q == 0:
        return K.zero
    try:
        mask, scale = _decomposer(K).decompose(int(q.p * q.q))
    except AnalysisError:
        return None
    return element_from_radicals(K, {mask: scale / int(q.q)})


@lru_cache(maxsize=64)
def _decomposer(K: Domain) -> _Decomposer:
    dec = _Decomposer()
    for d in radical_basis(K).radicands:
        dec.add(d)
    return dec


# --- conversions ----------------------------------------------------------------------------


def _bits(mask: int, k: int) -> tuple[int, ...]:
    return tuple(mask >> i & 1 for i in range(k))


@lru_cache(maxsize=256)
def context(nvars: int, k: int) -> fmpq_mpoly_ctx:
    """The flint ring ``QQ[v₀, …, v_{nvars-1}, ρ₁, …, ρ_k]`` (lex)."""
    names = tuple(f"v{i}" for i in range(nvars)) + tuple(f"rho{i}" for i in range(k))
    return fmpq_mpoly_ctx.get(names, "lex")


def _qq(c: Any) -> fmpq:
    c = QQ.convert(c)
    return fmpq(int(QQ.numer(c)), int(QQ.denom(c)))


def to_flint(f: Poly) -> fmpq_mpoly:
    """``f ∈ K[...]`` in the radical basis, as an ``fmpq_mpoly``."""
    K = f.ring.domain
    basis = radical_basis(K)
    n, k = basis.degree, len(basis.radicands)
    terms = list(f.items())
    if not terms:
        return context(f.ring.ngens, k).from_dict({})
    columns = []
    for _, c in terms:
        dense = [_qq(q) for q in c.to_list()]
        columns.append([fmpq(0)] * (n - len(dense)) + dense[::-1][::-1] if dense else [fmpq(0)] * n)
    # columns[t] holds the θ-coefficients highest first; row i of the matrix is θ^i.
    theta = fmpq_mat(n, len(terms), [columns[t][n - 1 - i] for i in range(n) for t in range(len(terms))])
    radical = basis.to_radicals * theta
    out: dict[tuple[int, ...], fmpq] = {}
    for t, (monom, _) in enumerate(terms):
        for mask in range(n):
            c = radical[mask, t]
            if c != 0:
                out[tuple(monom) + _bits(mask, k)] = c
    return context(f.ring.ngens, k).from_dict(out)


def from_flint(g: fmpq_mpoly, R: PolyRing) -> Poly:
    """The reduced ``g`` (radical basis) as an element of ``R = K[...]``."""
    K = R.domain
    basis = radical_basis(K)
    n = basis.degree
    grouped: dict[tuple[int, ...], list[fmpq]] = {}
    for monom, c in g.to_dict().items():
        monom = tuple(int(e) for e in monom)
        head, tail = monom[: R.ngens], monom[R.ngens :]
        mask = sum(1 << i for i, e in enumerate(tail) if e)
        grouped.setdefault(head, [fmpq(0)] * n)[mask] = c
    if not grouped:
        return R.zero
    keys = list(grouped)
    radical = fmpq_mat(n, len(keys), [grouped[key][mask] for mask in range(n) for key in keys])
    theta = basis.from_radicals * radical
    result = {}
    for t, key in enumerate(keys):
        coeffs = [QQ(int(theta[i, t].p), int(theta[i, t].q)) for i in reversed(range(n))]
        value = K(coeffs)
        if value:
            result[key] = value
    return R.from_dict(result)


def reduce(p: fmpq_mpoly, radicands: Sequence[int]) -> fmpq_mpoly:
    """The normal form of ``p`` modulo ``ρᵢ² = dᵢ`` (degree ≤ 1 in each ``ρᵢ``)."""
    gens = p.context().gens()
    first = len(gens) - len(radicands)
    for g, d in zip(gens[first:], radicands):
        if any(m[gens.index(g)] > 1 for m in p.monoms()):
            p = p % (g**2 - d)
    return p


def from_expr(expr: sympy.Expr, R: PolyRing) -> Poly:
    """A polynomial sympy expression whose coefficients are written with square roots of
    rationals (``3*sqrt(2)*t/2``) as an element of ``R = K[...]``, through the radical basis
    (sympy's own conversion searches a field isomorphism numerically, which takes seconds)."""
    K = R.domain
    index = {s: i for i, s in enumerate(R.symbols)}
    dec = _decomposer(K) if K != QQ else _Decomposer()
    vectors: dict[tuple[int, ...], dict[int, fmpq]] = {}
    for term in sympy.Add.make_args(sympy.expand(expr)):
        coeff, rest = term.as_coeff_Mul()
        monom = [0] * len(index)
        radicand = sympy.Integer(1)
        for base, e in rest.as_powers_dict().items():
            if base == 1:
                continue
            if base in index and e.is_Integer and e >= 0:
                monom[index[base]] += int(e)
            elif base.is_Rational and base > 0 and e == sympy.Rational(1, 2):
                radicand *= base
            else:
                raise AnalysisError(f"{term} is not a term with a real square-root coefficient")
        mask, scale = dec.decompose(int(radicand.p * radicand.q))
        c = fmpq(int(sympy.Rational(coeff).p), int(sympy.Rational(coeff).q)) * scale / int(radicand.q)
        vector = vectors.setdefault(tuple(monom), {})
        vector[mask] = vector.get(mask, fmpq(0)) + c
    if K == QQ:
        return R.from_dict({m: QQ(int(v[0].p), int(v[0].q)) for m, v in vectors.items() if v.get(0, 0) != 0})
    out = {m: element_from_radicals(K, v) for m, v in vectors.items()}
    return R.from_dict({m: c for m, c in out.items() if c})


def real_radicands(generators: Sequence[sympy.Expr]) -> tuple[int, ...] | None:
    """The square-free radicands of real square roots ``sqrt(n)`` (``None`` if one is not real)."""
    out = []
    for g in generators:
        value = sympy.Rational(sympy.expand(g**2))
        if value <= 0:
            return None
        out.append(squarefree_core(int(value.p * value.q)))
    return tuple(sorted(set(out) - {1}))


# --- composition and norm -----------------------------------------------------------------


def compose(f: Poly, images: Sequence[Poly]) -> Poly:
    """``f(images)`` over ``K``: all images in one ring ``K[...]`` (``f`` over ``K`` or ``QQ``)."""
    target = images[0].ring
    basis = radical_basis(target.domain)
    k = len(basis.radicands)
    ctx = context(target.ngens, k)
    rhos = list(ctx.gens()[target.ngens :])
    if f.ring.domain == target.domain:
        F = to_flint(f)
    else:  # f over QQ: no radicals
        F = context(f.ring.ngens, k).from_dict({tuple(m) + (0,) * k: _qq(c) for m, c in f.items()})
    result = F.compose(*[to_flint(h) for h in images], *rhos, ctx=ctx)
    return from_flint(reduce(result, basis.radicands), target)


def norm(G: fmpq_mpoly, radicands: Sequence[int]) -> fmpq_mpoly:
    """``N(G) = Π_σ σ(G)`` for reduced ``G`` in the radical basis: free of every ``ρᵢ``."""
    ctx = G.context()
    names = ctx.names()
    first = len(names) - len(radicands)
    for i, d in enumerate(radicands):
        name = names[first + i]
        A = G.subs({name: 0})
        B = G.subs({name: 1}) - A
        G = reduce(A * A - B * B * d, radicands)
    return G


# --- factorization (Trager) -------------------------------------------------------------------


MAX_NORM_DEGREE = 120
"""Above this degree of the norm ``N(F)`` (``[K:QQ]·deg F``) Trager's method is not used: the
norm's size (and memory) grows like its degree to the number of variables."""


def norm_degree(f: Poly) -> int:
    """``[K:QQ]·deg f``: the degree of the norm that :func:`factor` would factor over ``QQ``."""
    return radical_basis(f.ring.domain).degree * max((sum(m) for m in f.itermonoms()), default=0)


def factor(f: Poly) -> tuple[Any, list[tuple[Poly, int]]]:
    """``f = c·Π gᵢ^eᵢ`` over ``K`` with ``gᵢ`` irreducible over ``K`` and monic (lex), checked
    exactly (module docstring). Factor order is unspecified."""
    R, K = f.ring, f.ring.domain
    basis = radical_basis(K)
    radicands = basis.radicands
    F = to_flint(f)
    ctx = F.context()
    nv = R.ngens
    used = [i for i in range(nv) if any(m[i] for m in F.monoms())]
    if not used:
        return f.LC, []
    for shift in _shifts(used):
        found = _trager(F, ctx, nv, radicands, shift)
        if found is not None:
            lead = K.one
            factors = []
            for g, e in found:
                G = from_flint(g, R)
                G = G.monic()
                factors.append((G, e))
                lead *= G.LC**e
            return K.quo(f.LC, lead), factors
    raise AnalysisError("no shift gave a factorization over the coefficient field (internal error)")


def _shifts(used: Sequence[int]) -> list[dict[int, int]]:
    """Shifts ``x_v ↦ x_v - s_v·θ`` to try (variable → ``s_v``): none first, then every used
    variable at once with distinct small multipliers (a factor free of one variable must move
    too, or its norm stays a power)."""
    out: list[dict[int, int]] = [{}]
    for s in (1, -1, 2, -2, 3, 5, -7, 11):
        out.append({v: s * (j + 1) for j, v in enumerate(used)})
        out.append({v: s * (-1) ** j * (2 * j + 1) for j, v in enumerate(used)})
    return out


def _trager(
    F: fmpq_mpoly, ctx: fmpq_mpoly_ctx, nv: int, radicands: Sequence[int], shift: dict[int, int]
) -> list[tuple[fmpq_mpoly, int]] | None:
    """The factors of ``F`` from the norm after ``shift``, or ``None`` when the shift is bad."""
    gens = ctx.gens()
    theta = sum(gens[nv:], ctx.from_dict({}))
    s = bool(shift)
    forward, backward = list(gens), list(gens)
    for v, c in shift.items():
        forward[v] = gens[v] - c * theta
        backward[v] = gens[v] + c * theta
    G = reduce(F.compose(*forward, ctx=ctx), radicands) if s else F
    N = norm(G, radicands)
    _, pieces = N.factor()
    pieces = [(P, int(e)) for P, e in pieces]
    n = 1 << len(radicands)
    if len(pieces) == 1 and pieces[0][1] == 1:
        return [(F, 1)]
    result = []
    for P, e in pieces:
        shifted = reduce(P.compose(*backward, ctx=ctx), radicands) if s else P
        g = _modular_gcd(F, shifted, nv, radicands)
        if g is None or _degree(tuple(m[:nv] for m in g.monoms())) * n != P.total_degree():
            return None
        Ng = norm(reduce(g.compose(*forward, ctx=ctx), radicands) if s else g, radicands)
        if not _proportional(Ng, P):
            return None
        result.append((g, e))
    check = _leading(F, nv)  # the g are monic in lex order of the variables
    for g, e in result:
        check = reduce(check * g**e, radicands)
    return result if check == F else None


def _leading(F: fmpq_mpoly, nv: int) -> fmpq_mpoly:
    """The coefficient (an element of ``K``, in the ``ρᵢ``) of the lex-leading monomial of ``F``
    in the variables."""
    terms = {tuple(int(e) for e in m): c for m, c in F.to_dict().items()}
    top = max(m[:nv] for m in terms)
    zeros = (0,) * nv
    return F.context().from_dict({zeros + m[nv:]: c for m, c in terms.items() if m[:nv] == top})


def _proportional(a: fmpq_mpoly, b: fmpq_mpoly) -> bool:
    """Whether ``a = c·b`` for a rational ``c ≠ 0`` (both free of the ``ρᵢ``)."""
    if a.is_zero() or b.is_zero():
        return False
    c = a.leading_coefficient() / b.leading_coefficient()
    return a == b * c


# --- gcd over K modulo primes -------------------------------------------------------------


def _modular_gcd(A: fmpq_mpoly, B: fmpq_mpoly, nv: int, radicands: Sequence[int]) -> fmpq_mpoly | None:
    """``gcd_K(A, B)``, monic in lex order, from its images at all ``2^k`` embeddings of ``K``
    into ``GF(p)`` for primes ``p`` where every ``dᵢ`` is a square; lifted by CRT and rational
    reconstruction until two consecutive lifts agree and the lift divides ``A`` exactly."""
    k = len(radicands)
    n = 1 << k
    ctx = A.context()
    names = ctx.names()[:nv]
    modulus = fmpz(1)
    residues: dict[tuple[int, ...], fmpz] = {}
    shape: tuple[tuple[int, ...], ...] | None = None
    previous = None
    p = (1 << 62) + 1
    for _ in range(400):
        p = _next_prime(p, radicands)
        roots = [int(nmod(d, p).sqrt()) for d in radicands]
        images: list[tuple[tuple[int, ...], nmod_mpoly]] = []
        for signs in product((1, -1), repeat=k):
            values = [r * s % p for r, s in zip(roots, signs)]
            ga = _image(A, nv, values, p, names)
            gb = _image(B, nv, values, p, names)
            if ga is None or gb is None:
                images = []
                break
            images.append((signs, ga.gcd(gb)))
        if not images:
            continue
        monomials = tuple(sorted({tuple(int(e) for e in m) for _, g in images for m in g.monoms()}))
        if shape is not None and _degree(monomials) > _degree(shape):
            continue  # an unlucky prime: the image gcd is too large
        if shape is None or _degree(monomials) < _degree(shape):
            shape, modulus, residues, previous = monomials, fmpz(1), {}, None
        # Interpolate the radical-basis coefficients from the 2^k embeddings (a Hadamard transform).
        inverse_n = pow(n, -1, p)
        current: dict[tuple[int, ...], int] = {}
        tables = [{tuple(int(e) for e in m): int(c) for m, c in g.to_dict().items()} for _, g in images]
        for mono in shape:
            values = [table.get(mono, 0) for table in tables]
            for mask in range(n):
                total = 0
                for (signs, _), value in zip(images, values):
                    chi = 1
                    for i in range(k):
                        if mask >> i & 1:
                            chi *= signs[i]
                    total += chi * value
                scale = 1
                for i in range(k):
                    if mask >> i & 1:
                        scale = scale * roots[i] % p
                current[mono + _bits(mask, k)] = total * inverse_n * pow(scale, -1, p) % p
        residues = {
            key: _crt(residues.get(key, fmpz(0)), modulus, current.get(key, 0), p)
            for key in set(residues) | set(current)
        }
        modulus *= p
        lifted = {}
        for key, r in residues.items():
            q = _rational_reconstruction(r, modulus)
            if q is None:
                break
            if q != 0:
                lifted[key] = q
        else:
            candidate = ctx.from_dict(lifted)
            if previous is not None and candidate == previous:
                return candidate
            previous = candidate
    return None


def _degree(monomials: tuple[tuple[int, ...], ...]) -> int:
    return max((sum(m) for m in monomials), default=0)


def _next_prime(p: int, radicands: Sequence[int]) -> int:
    """The next prime after ``p`` modulo which every radicand is a nonzero square."""
    while True:
        p += 2
        if fmpz(p).is_prime() and all(d % p and pow(d, (p - 1) // 2, p) == 1 for d in radicands):
            return p


def _image(P: fmpq_mpoly, nv: int, values: Sequence[int], p: int, names: Sequence[str]) -> nmod_mpoly | None:
    """``P`` with ``ρᵢ = valuesᵢ`` in ``GF(p)[variables]``; ``None`` when a denominator vanishes."""
    out: dict[tuple[int, ...], int] = {}
    for monom, c in P.to_dict().items():
        den = int(c.q) % p
        if not den:
            return None
        value = int(c.p) * pow(den, -1, p) % p
        for e, r in zip(monom[nv:], values):
            value = value * pow(r, int(e), p) % p
        key = tuple(int(e) for e in monom[:nv])
        out[key] = (out.get(key, 0) + value) % p
    return nmod_mpoly_ctx.get(tuple(names), modulus=p, ordering="lex").from_dict({m: c for m, c in out.items() if c})


def _crt(r1: fmpz, m1: fmpz, r2: int, m2: int) -> fmpz:
    """The residue modulo ``m1·m2`` that is ``r1`` mod ``m1`` and ``r2`` mod ``m2``."""
    if m1 == 1:
        return fmpz(r2)
    t = (r2 - r1) * pow(int(m1 % m2), -1, m2) % m2
    return r1 + m1 * t


def _rational_reconstruction(r: fmpz, m: fmpz) -> fmpq | None:
    """``a/b ≡ r (mod m)`` with ``|a|, b ≤ √(m/2)``, or ``None``."""
    residue, modulus = int(r) % int(m), int(m)
    bound = isqrt(modulus // 2)
    r0, r1, s0, s1 = modulus, residue, 0, 1
    while r1 > bound:
        q = r0 // r1
        r0, r1, s0, s1 = r1, r0 - q * r1, s1, s0 - q * s1
    if s1 == 0 or abs(s1) > bound:
        return None
    return fmpq(r1, s1) if s1 > 0 else fmpq(-r1, -s1)
