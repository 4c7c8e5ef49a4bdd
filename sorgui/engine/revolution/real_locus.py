"""The real points of a surface of revolution: empty, points, a curve or a surface (docs/math.md §3.4).

``X`` is the half-plane curve ``Z = {p̃(s, r) = 0, r ≥ 0}`` turned about the axis: a piece of
``Z`` off the axis sweeps a piece of surface, an isolated point of ``Z`` off the axis a circle,
a point on the axis stays a point. With ``G(s, w) = P²`` (``w = r²``), ``G = w^k·c(s)·H(s, w)``:

* surface: first a certified look along a few lines ``s = s₀`` and ``w = w₀ > 0`` for a simple
  real point with ``w > 0`` (a real branch passes through it); then exactly: a real root of the
  content ``c`` (a plane across the axis), or one sample ``s₀`` in each interval between the
  real roots of ``lc_w(H)·disc_w(H)·H(s, 0)`` with a positive root of ``H(s₀, w)``;
* otherwise circles are the real singular points ``H = H_s = H_w = 0`` with ``w > 0``, counted
  with a lexicographic Gröbner basis in shape position and the Sturm–Tarski theorem; the axis
  line lies on ``X`` when ``k > 0``; points are the real roots of ``G(s, 0)``.

The exact steps are bounded by the size of ``H`` (:data:`EXACT_LIMIT`, :data:`CIRCLES_LIMIT`);
beyond it the answer is ``undecided``, never a guess.

Spheres and planes use their normal forms ``g(|p - c|²)`` and ``g(n·p)`` (docs/math.md §2).
Every sign is exact (rationals, or ball arithmetic in ``K`` that refines until it excludes 0).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any, cast

import flint
import sympy
from sympy.polys.domains import QQ
from sympy.polys.domains.domain import Domain
from sympy.polys.polyerrors import NotInvertible

from ..algebra import numberfields
from ..algebra.linalg import Vector
from ..algebra.polys import Poly, compose, is_rational_field, poly_ring, to_flint
from ..algebra.realroots import count_real_roots, sign, sign_changes
from ..errors import AnalysisError
from ..recognition.profile import ProfileCurve
from ..recognition.symmetry import PLANE, SPHERE, Symmetry
from ..stage_results import RealLocus

S, W, T = sympy.symbols("s w t")

EMPTY, POINTS, CURVE, SURFACE, UNDECIDED = "empty", "points", "curve", "surface", "undecided"
DIMENSION = {EMPTY: -1, POINTS: 0, CURVE: 1, SURFACE: 2, UNDECIDED: None}

QUICK_SAMPLES = tuple(QQ(n, d) for n, d in ((0, 1), (1, 1), (-1, 1), (1, 2), (-1, 2), (2, 1), (-2, 1), (3, 1)))
"""Values of ``s`` tried before the discriminant is computed: most real surfaces show a simple
positive root ``w`` at one of them."""

QUICK_HEIGHTS = tuple(QQ(4) ** j for j in range(4, -33, -1))
"""Values ``w₀ > 0`` (squared distances to the axis) tried in the same way, down to ``4⁻³²``:
thin real surfaces hug the axis."""

EXACT_LIMIT = 90
"""Above this ``deg_s(H)·deg_w(H)`` the discriminant is not attempted when the first look found
no real surface: the answer is ``undecided``."""

CIRCLES_LIMIT = 40
"""The same bound for counting circles and points with Gröbner bases."""

SHEARS = 12
"""How many shears ``t = s + λ·w`` are tried to bring the singular points into shape position."""


def real_locus(f: Poly, symmetry: Symmetry, profile: ProfileCurve | None) -> RealLocus | None:
    """The real points of ``X = {f = 0}``; ``None`` when ``X`` has no unique axis and is neither
    a sphere nor a plane (then it is not a surface of revolution)."""
    if symmetry.kind == SPHERE:
        assert symmetry.center is not None  # a sphere's symmetry gives its centre
        return sphere_locus(f, symmetry.center)
    if symmetry.kind == PLANE:
        assert symmetry.normal is not None  # a plane's symmetry gives its normal
        return plane_locus(f, symmetry.normal)
    if profile is None:
        return None
    return profile_locus(profile.square)


def _locus(
    kind: str, *, points: int | None = None, circles: int | None = None, axis_line: bool | None = None
) -> RealLocus:
    return RealLocus(kind=kind, dimension=DIMENSION[kind], points=points, circles=circles, axis_line=axis_line)


def sphere_locus(f: Poly, center: Vector) -> RealLocus:
    """Concentric spheres ``f = g(|p - c|²)``: ``φ(t) = f(c + t·e₁) = g(t²)`` has a real root
    ``t ≠ 0`` for every real sphere, and the root 0 when the centre is on ``X``."""
    K = f.ring.domain
    R = poly_ring(("t",), K)
    (t,) = R.gens
    phi = compose(f, [center[0] + t, R.ground_new(center[1]), R.ground_new(center[2])])
    roots = count_real_roots(phi)
    on_center = (0,) not in phi
    if roots > int(on_center):
        return _locus(SURFACE)
    return _locus(POINTS, points=1) if on_center else _locus(EMPTY, points=0)


def plane_locus(f: Poly, normal: Vector) -> RealLocus:
    """Parallel planes ``f = g(n·p)``: one real plane for each real root of ``f(t·n)``."""
    R = poly_ring(("t",), f.ring.domain)
    (t,) = R.gens
    psi = compose(f, [normal[0] * t, normal[1] * t, normal[2] * t])
    return _locus(SURFACE) if count_real_roots(psi) else _locus(EMPTY, points=0)


def profile_locus(square: Poly) -> RealLocus:
    """The real points of the surface of revolution whose ``P²`` is ``square`` = ``G(s, w)``."""
    if _quick_surface(square):
        return _locus(SURFACE)
    K = square.ring.domain
    G = _native(dict(square), (S, W), K)
    k = min(m[1] for m in G.monoms())
    G1 = sympy.Poly.from_dict({(i, j - k): c for (i, j), c in G.as_dict(native=True).items()}, S, W, domain=K)
    content = _content_in_s(G1)
    if content.degree() > 0 and _real_roots(content):
        return _locus(SURFACE)
    H = G1.exquo(_native({(i, 0): c for (i,), c in content.as_dict(native=True).items()}, (S, W), K))
    if H.degree(W) > 0:
        H = H.exquo(H.gcd(H.diff(W)))
        size = H.degree(S) * H.degree(W)
        if size > EXACT_LIMIT:
            return _locus(UNDECIDED)
        if _has_surface(H, _cell_samples(H)):
            return _locus(SURFACE)
        if size > CIRCLES_LIMIT:
            return _locus(UNDECIDED)
        circles = _circles(H)
    else:
        circles = 0
    points = 0 if k else _real_roots(G.eval(W, 0))
    kind = CURVE if k or circles else (POINTS if points else EMPTY)
    return _locus(kind, points=points, circles=circles, axis_line=bool(k))


def _quick_surface(square: Poly) -> bool:
    """A certified first look: a line ``s = s₀``, or ``w = w₀ > 0``, that meets the reduced curve
    ``G = 0`` in a simple real point with ``w > 0``. Through it passes a real branch (implicit
    function theorem), so ``X`` has a real surface. ``False`` proves nothing."""
    if not is_rational_field(square.ring.domain):
        H = _native(dict(square), (S, W), square.ring.domain)
        return _has_surface(H.exquo(H.gcd(H.diff(W))), QUICK_SAMPLES)
    G = to_flint(square)
    _, factors = G.factor_squarefree()
    reduced = G.context().from_dict({(0, 0): 1})
    for g, _e in factors:
        reduced *= g
    names = reduced.context().names()
    for i, values, positive in ((0, QUICK_SAMPLES, True), (1, QUICK_HEIGHTS, False)):
        for value in values:
            line = reduced.subs({names[i]: flint.fmpq(int(value.numerator), int(value.denominator))})
            coefficients = [flint.fmpq(0)] * (line.degrees()[1 - i] + 1)
            for monom, c in line.to_dict().items():
                coefficients[monom[1 - i]] = c
            if _simple_real_root(flint.fmpq_poly(coefficients), positive):
                return True
    return False


def _simple_real_root(p: flint.fmpq_poly, positive: bool) -> bool:
    """Whether square-free ``p`` has a real root (a positive one when ``positive``), certified by
    arb root isolation (real roots come back with imaginary part exactly 0)."""
    if p.degree() <= 0 or p.gcd(p.derivative()).degree() > 0:
        return False
    # flint's stub says list[acb]: the roots come with their multiplicities
    roots = cast(list[tuple[flint.acb, int]], p.numer().complex_roots())
    for root, _m in roots:
        if root.imag == 0 and (not positive or root.real > 0):
            return True
    return False


def _native(terms: Mapping[tuple[int, ...], Any], gens: tuple[sympy.Symbol, ...], K: Domain) -> sympy.Poly:
    """A ``sympy.Poly`` over ``K`` from exponents and coefficients already in ``K``: going
    through an expression would make sympy search a field isomorphism (seconds per call)."""
    return sympy.Poly.from_dict({tuple(m): c for m, c in terms.items()}, *gens, domain=K)


def _coefficient_in_w(G: sympy.Poly, j: int) -> sympy.Poly:
    """The coefficient of ``w^j`` in ``G(s, w)``, a polynomial in ``s``."""
    return _native({(i,): c for (i, e), c in G.as_dict(native=True).items() if e == j}, (S,), G.domain)


def _content_in_s(G: sympy.Poly) -> sympy.Poly:
    """The gcd in ``K[s]`` of the coefficients of ``G`` as a polynomial in ``w``."""
    K = G.domain
    content = sympy.Poly(0, S, domain=K)
    for j in range(G.degree(W) + 1):
        content = content.gcd(_coefficient_in_w(G, j))
    return content.monic() if content.degree() > 0 else sympy.Poly(1, S, domain=K)


def _real_roots(p: sympy.Poly) -> int:
    """The number of distinct real roots of a univariate ``p`` over ``K`` (0 for a constant)."""
    if p.degree() <= 0:
        if p.is_zero:
            raise AnalysisError("a real-root count of the zero polynomial (internal error)")
        return 0
    R = poly_ring(("t",), p.domain)
    return count_real_roots(R.from_dict({(m[0],): c for m, c in p.as_dict(native=True).items()}))


def _has_surface(H: sympy.Poly, samples: Sequence[Any]) -> bool:
    """Whether some ``s₀`` has ``H(s₀, w)`` square-free with a positive root ``w``: by the
    implicit function theorem a real branch of ``H = 0`` with ``w > 0`` passes through it."""
    K = H.domain
    for s0 in samples:
        h = H.eval(S, K.convert(s0, QQ))
        if h.degree() <= 0 or h.gcd(h.diff(W)).degree() > 0:
            continue
        in_t = _native({(2 * i,): c for (i,), c in h.as_dict(native=True).items()}, (T,), K)
        if _real_roots(in_t) > (0 if h.eval(0) else 1):
            return True
    return False


def _cell_samples(H: sympy.Poly) -> list[Any]:
    """One rational ``s`` in each open interval cut out by the real roots of
    ``lc_w(H)·disc_w(H)·H(s, 0)`` (over ``K``, by way of its norm over ``QQ``)."""
    K = H.domain
    critical = _coefficient_in_w(H, H.degree(W)) * _coefficient_in_w(H, 0)
    if H.degree(W) > 1:
        critical *= _native(H.reorder(W, S).discriminant().as_dict(native=True), (S,), K)
    critical = _norm_in_s(critical).sqf_part()
    if critical.degree() <= 0:
        return [QQ(0)]
    eps = None
    while True:
        intervals = sorted(critical.intervals(eps=eps)) if eps else sorted(critical.intervals())
        bounds = [(sympy.Rational(a), sympy.Rational(b)) for (a, b), _ in intervals]
        if not bounds:
            return [QQ(0)]
        samples = [bounds[0][0] - 1, bounds[-1][1] + 1]
        samples += [(b + a) / 2 for (_, b), (a, _) in zip(bounds, bounds[1:])]
        if all(critical.eval(x) for x in samples):
            return [QQ(int(x.p), int(x.q)) for x in samples]
        eps = min(b - a for a, b in bounds if b > a) / 4 if eps is None else eps / 4


def _norm_in_s(p: sympy.Poly) -> sympy.Poly:
    """``N(p) ∈ QQ[s]``, the product of the conjugates of ``p ∈ K[s]`` (up to a constant):
    in flint through the radical basis for the parser's fields, else sympy's resultant."""
    K = p.domain
    if is_rational_field(K):
        return p
    if not numberfields.supports(K):
        return sympy.Poly(p.norm().as_expr(), S, domain=QQ)
    element = poly_ring(("s",), K).from_dict({tuple(m): c for m, c in p.as_dict(native=True).items()})
    N = numberfields.norm(numberfields.to_flint(element), numberfields.radical_basis(K).radicands)
    return _native({m[:1]: QQ(int(c.p), int(c.q)) for m, c in N.to_dict().items()}, (S,), QQ)


def _circles(H: sympy.Poly) -> int:
    """The number of real singular points of ``H = 0`` with ``w > 0`` (each turns into a circle)."""
    K = H.domain
    system = [H.as_expr(), H.diff(S).as_expr(), H.diff(W).as_expr()]
    radical = _radical(system, K)
    if radical is None:
        return 0
    q, v = _shape(radical, K)
    return _positive_at_roots(q, v)


def _lex_basis(system: list[sympy.Expr], first: sympy.Symbol, second: sympy.Symbol, K: Domain) -> sympy.GroebnerBasis:
    """The reduced lexicographic Gröbner basis (``first > second``) of a zero-dimensional ideal:
    F5B in degree order, then FGLM to lex (much faster than Buchberger in lex directly, which is
    the resort where sympy's FGLM fails: over ``QQ(√2)`` it divided by an unreduced zero)."""
    basis = sympy.groebner(system, first, second, order="grevlex", method="f5b", domain=K)
    if basis.exprs == [1]:
        return basis
    try:
        return basis.fglm("lex")
    except NotInvertible:  # sympy's FGLM over an algebraic field divided by a zero it did not reduce
        return sympy.groebner(system, first, second, order="lex", domain=K)


def _radical(system: list[sympy.Expr], K: Domain) -> list[sympy.Expr] | None:
    """Generators of the radical of the zero-dimensional ideal of ``system`` (Seidenberg: add the
    square-free eliminants in ``s`` and ``w``), as a reduced basis; ``None`` when the ideal is the
    whole ring."""
    basis = _lex_basis(system, W, S, K)
    if basis.exprs == [1]:
        return None
    eliminants = [basis.exprs[-1], _lex_basis(system, S, W, K).exprs[-1]]
    for e, x in zip(eliminants, (S, W)):
        if e.free_symbols != {x}:
            raise AnalysisError("the singular points of the profile are not finitely many (internal error)")
    radical = basis.exprs + [sympy.Poly(e, x, domain=K).sqf_part().as_expr() for e, x in zip(eliminants, (S, W))]
    return cast(list[sympy.Expr], _lex_basis(radical, W, S, K).exprs)


def _shape(radical: list[sympy.Expr], K: Domain) -> tuple[sympy.Poly, sympy.Poly]:
    """``(q, v)`` with ``V = {(t - λ·v(t), v(t)) : q(t) = 0}`` for the first shear ``s = t - λ·w``
    that puts the radical ideal in shape position (lex basis ``{w - v(t), q(t)}``). ``radical``
    is already a reduced lex basis, so ``λ = 0`` needs no new one."""
    for lam in range(SHEARS):
        sheared = [e.subs(S, T - lam * W) for e in radical]
        basis = sheared if lam == 0 else _lex_basis(sheared, W, T, K).exprs
        if len(basis) != 2:
            continue
        first = sympy.Poly(basis[0], W, T, domain=K)
        if first.degree(W) != 1 or sympy.Poly(basis[0], W).LC() != 1 or basis[1].has(W):
            continue
        return sympy.Poly(basis[1], T, domain=K), sympy.Poly(W - basis[0], T, domain=K)
    raise AnalysisError("the singular points of the profile did not come into shape position")


def _positive_at_roots(q: sympy.Poly, v: sympy.Poly) -> int:
    """``#{ξ ∈ R : q(ξ) = 0, v(ξ) > 0}`` for square-free ``q``, by the Sturm–Tarski theorem:
    ``TaQ(v, q) = #{v > 0} - #{v < 0}`` is the sign-change difference of the signed remainder
    sequence of ``q`` and ``q'·v``."""
    K = q.domain
    total = _real_roots(q)
    zero = _real_roots(q.gcd(v))
    sequence = [q, q.diff(T) * v]
    while not sequence[-1].is_zero:
        sequence.append(-sequence[-2].rem(sequence[-1]))
    sequence.pop()
    at_plus = [sign(K, p.rep.LC()) for p in sequence]
    at_minus = [s * (-1) ** p.degree() for s, p in zip(at_plus, sequence, strict=True)]
    tarski = sign_changes(at_minus) - sign_changes(at_plus)
    return (total - zero + tarski) // 2
