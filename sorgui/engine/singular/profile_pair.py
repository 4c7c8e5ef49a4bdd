"""The genus and absolute irreducibility of a surface of revolution's profile ``P`` and of its
square ``P²`` (docs/math.md §5), with the algorithm chosen per pair of curves
(:func:`analyze_profile_pair`), and the parameterization of ``P²`` on its model of lowest degree
(:func:`parametrize_square`).

Singular's ``genus`` computes a normalization; on the singular curves of degree 12 that surfaces
of revolution give it can take minutes, and on a curve of half the degree seconds. So a profile
made of lines and conics needs no Singular, a smooth profile needs only a test of smoothness
modulo a prime, and otherwise ``P²`` is analysed on the lowest-degree of its images under the
automorphism ``(s, w) ↦ (s, w + λs²)`` and the genus of ``P`` is read off the parameterization of
``P²`` (``P`` is the double cover ``r² = w``).
"""

from __future__ import annotations

import threading
from collections.abc import Sequence
from dataclasses import replace

import sympy
from flint import fmpq, fmpq_mat, fmpq_mpoly, fmpq_poly
from sympy.polys.domains import QQ

from ..algebra import quadratic
from ..algebra.polys import Poly, compose, is_rational_field, poly_ring, primitive, to_expr, to_flint, total_degree
from ..algebra.rationals import primitive as rational_primitive
from ..algebra.rationals import terms as rational_terms
from ..errors import SingularError
from .curves import (
    AbsoluteFactor,
    AbsoluteFactorization,
    CurveAnalysis,
    CurveParametrization,
    _reduced,
    analyze_curves,
    one_result,
    parametrize,
    reduced_fractions,
    square_part,
    variables_of,
)
from .process import emit, poly_to_singular, run_script

SMOOTHNESS_PRIME = 32003
"""The characteristic in which the smoothness of ``P`` is tested: a smooth reduction of the
same degree proves the curve smooth over ``C`` (the singular locus is closed)."""


def analyze_profile_pair(
    P: Poly,
    P2: Poly,
    *,
    shear: object | None = None,
    known: CurveParametrization | None = None,
    timeout: float = 60.0,
    cancel: threading.Event | None = None,
) -> tuple[CurveAnalysis, CurveAnalysis]:
    """The absolute factorization and genus of the profile ``P`` and of its square ``P²``, with
    the algorithm chosen per curve (docs/math.md §5), cheapest first:

    * every factor of ``P`` over ``QQ`` a line or a smooth conic (spheres, quadrics, tori of
      revolution): no Singular at all (:func:`_conic_profile_pair`);
    * ``P`` a smooth projective curve (the general position): genus ``(d-1)(d-2)/2``, and
      Riemann–Hurwitz for ``P → P²`` gives ``genus(P²)``; Singular only tests the smoothness
      modulo a prime (:func:`_smooth_double_cover`);
    * otherwise Singular analyses ``P²`` on its model of lowest degree (:func:`square_model`:
      ``F(h, ρ)`` of docs/math.md §3.2 when the axis frame's ``shear`` lowers the degree), and
      when it has genus 0 the genus of ``P`` follows from its parameterization, without Singular
      (:func:`_through_the_square`); ``P`` goes to Singular only when ``P²`` has positive genus
      or is reducible.

    The analysis of ``P²`` carries its parameterization when one was computed on the way;
    ``known``, a proper parameterization of ``P²`` already at hand (a curve of a typed map), is
    used instead of asking Singular for one."""
    found = _conic_profile_pair(P, P2)
    if found is not None:
        return found
    found = _smooth_double_cover(P, P2, timeout, cancel)
    if found is not None:
        return found
    return _through_the_square(P, P2, shear, timeout, cancel, known)


def square_model(P2: Poly, shear: object | None) -> tuple[Poly, object | None]:
    """``P²`` or, when it has lower degree, its image ``Q(s, v) = P²(s, v − λ·s²)`` under the
    polynomial automorphism ``(s, w) ↦ (s, w + λ·s²)`` of the plane (``λ = shear``), with the
    ``λ`` used (``None``: ``P²`` itself). With ``λ = |a|²/|u|²`` of the axis frame, ``Q`` is
    ``F(h, ρ)`` in scaled variables (docs/math.md §3.2): ``f`` as a polynomial in the height
    along the axis and the squared distance to a point of it, often of half the degree (a
    surface of revolution made from a curve in ``(h, ρ)``, a canal surface of revolution). ``Q``
    is birational to ``P²``: the same genus and absolute irreducibility, and its
    parameterizations map back."""
    if shear is None or not shear:
        return P2, None
    s, w = P2.ring.gens
    model = compose(P2, [s, w - P2.ring.ground_new(P2.ring.domain.convert(shear)) * s**2])
    return (model, shear) if total_degree(model) < total_degree(P2) else (P2, None)


def parametrize_square(
    P2: Poly, shear: object | None, *, timeout: float = 60.0, cancel: threading.Event | None = None
) -> CurveParametrization:
    """A proper parameterization of the genus-0 curve ``P²``, computed (and verified) on its model
    of lowest degree (:func:`square_model`) and mapped back: ``P²(φ, ψ − λφ²) = Q(φ, ψ)`` holds
    identically, and an automorphism of the plane keeps a map proper, so nothing is left to check."""
    model, used = square_model(P2, shear)
    par = parametrize(model, timeout=timeout, cancel=cancel, known_genus_zero=True, prefer_conic=True)
    if used is None:
        return par
    assert par.fractions is not None  # parametrize keeps its fractions
    (p1, q1), (p2, q2) = par.fractions
    value = p1.ring.domain.convert(used, P2.ring.domain)
    mapped = _reduced_fraction(p2 * q1**2 - p1**2 * q2 * value, q2 * q1**2)
    y = mapped[0].as_expr().subs(p1.ring.symbols[0], par.parameter) / mapped[1].as_expr().subs(
        p1.ring.symbols[0], par.parameter
    )
    return CurveParametrization(
        variables_of(P2), par.x, y, par.parameter, par.generators, par.method, (par.fractions[0], mapped)
    )


def _reduced_fraction(p: Poly, q: Poly) -> tuple[Poly, Poly]:
    """``p/q`` in lowest terms with a monic denominator, in flint over ``QQ`` and quadratic
    fields (:mod:`..algebra.quadratic`), in sympy over others."""
    K = quadratic.field_of(p.ring.domain)
    if K is None:
        return _reduced(p, q)
    x, y = quadratic.pair_of(p), quadratic.pair_of(q)
    g = quadratic.gcd(K, y, x)
    top, bottom = K.divide(x, g), K.divide(y, g)
    assert top is not None and bottom is not None  # g divides both
    degree = quadratic.degree(bottom)
    lead = (fmpq_poly([bottom[0][degree]]), fmpq_poly([bottom[1][degree]]))
    top, bottom = K.divide(top, lead), K.divide(bottom, lead)
    assert top is not None and bottom is not None  # a nonzero constant divides everything
    return quadratic.pair_poly(top, p.ring), quadratic.pair_poly(bottom, p.ring)


def _through_the_square(
    P: Poly,
    P2: Poly,
    shear: object | None,
    timeout: float,
    cancel: threading.Event | None,
    known: CurveParametrization | None = None,
) -> tuple[CurveAnalysis, CurveAnalysis]:
    """``P²`` analysed by Singular on its model of lowest degree; when it is absolutely
    irreducible of genus 0, ``P`` from its proper parameterization ``(φ(t), w(t))``.

    ``P`` is the double cover ``r² = w`` of ``P²``, so its function field is that of
    ``y² = h(t)``, ``h`` the product of the factors of odd multiplicity of the numerator times
    the denominator of ``w`` (the ``h`` of the tubular surface, docs/math.md §5): ``P`` is
    absolutely irreducible of genus ``⌈deg h / 2⌉ − 1`` when ``h`` is not constant, and splits
    into two mirror components over ``C`` when it is (then only their factorization is asked of
    Singular)."""
    model, used = square_model(P2, shear)
    square = _mapped_back(analyze_curves([model], timeout=timeout, cancel=cancel)[0], used, P2)
    if not (square.is_absolutely_irreducible and square.genus == 0 and is_rational_field(P.ring.domain)):
        return analyze_curves([P], timeout=timeout, cancel=cancel)[0], square
    par = known or parametrize_square(P2, shear, timeout=timeout, cancel=cancel)
    fractions = par.fractions or reduced_fractions(par.x, par.y, par.parameter, par.generators)
    _, (numerator, denominator) = fractions
    odd = _odd_degree(numerator, denominator)
    if odd >= 1:
        (normal,) = _singular_normal_forms([to_flint(P)], variables_of(P))
        factorization = AbsoluteFactorization(variables_of(P), (AbsoluteFactor(normal, 1, 1),))
        profile = CurveAnalysis(factorization, (odd + 1) // 2 - 1)
    else:
        profile = CurveAnalysis(
            analyze_curves([P], with_genus=False, timeout=timeout, cancel=cancel)[0].factorization, None
        )
    return profile, replace(square, parametrization=par)


def _odd_degree(numerator: Poly, denominator: Poly) -> int:
    """The degree of the product of the factors of odd multiplicity of ``numerator·denominator``
    in ``D[t]``: in flint over ``QQ`` and quadratic fields (:mod:`..algebra.quadratic`), in sympy
    over others."""
    K = quadratic.field_of(numerator.ring.domain)
    if K is None:
        return int(square_part(numerator * denominator)[1].degree())
    product = K.mul(quadratic.pair_of(numerator), quadratic.pair_of(denominator))
    return sum(quadratic.degree(g) for g, e in quadratic.squarefree_decomposition(K, product) if e % 2)


def _mapped_back(analysis: CurveAnalysis, shear: object | None, P2: Poly) -> CurveAnalysis:
    """The analysis of the model ``Q(s, v) = P²(s, v − λs²)`` as that of ``P²``: its absolute
    factors with ``v = w + λs²``."""
    if shear is None:
        return analysis
    x, y = variables_of(P2)
    value = to_expr(P2.ring.domain, P2.ring.domain.convert(shear))
    factors = tuple(
        replace(f, factor=sympy.expand(f.factor.subs(y, y + value * x**2))) for f in analysis.factorization.factors
    )
    return CurveAnalysis(AbsoluteFactorization(analysis.factorization.variables, factors), analysis.genus)


def _conic_profile_pair(P: Poly, P2: Poly) -> tuple[CurveAnalysis, CurveAnalysis] | None:
    """Both analyses without Singular when ``P`` over ``QQ`` is a product of distinct lines and
    smooth conics, each absolutely irreducible of genus 0; else ``None``.

    Then every factor ``G`` of ``P²`` over ``QQ`` is absolutely irreducible of genus 0 too
    (docs/math.md §5): ``G(s, r²)`` is one factor ``F`` of ``P`` (even in ``r``) or a mirror pair
    ``F(s, r)·F(s, −r)``; a splitting of ``G`` over ``C`` would split ``F`` or give an even
    polynomial divisible by ``F`` alone, and ``G`` is the image of the rational curve ``F``
    (Lüroth)."""
    if not (is_rational_field(P.ring.domain) and is_rational_field(P2.ring.domain)):
        return None
    p_factors = _rational_factors(P)
    if p_factors is None or not all(_is_line_or_smooth_conic(F) for F in p_factors):
        return None
    p2_factors = _rational_factors(P2)
    if p2_factors is None:
        return None
    analyses = []
    for F, factors in ((P, p_factors), (P2, p2_factors)):
        classes = tuple(AbsoluteFactor(expr, 1, 1) for expr in _singular_normal_forms(factors, variables_of(F)))
        factorization = AbsoluteFactorization(variables_of(F), classes)
        analyses.append(CurveAnalysis(factorization, 0 if len(classes) == 1 else None))
    return analyses[0], analyses[1]


def _rational_factors(F: Poly) -> list[fmpq_mpoly] | None:
    """The irreducible factors of ``F`` over ``QQ`` (flint); ``None`` unless square-free."""
    _, factors = to_flint(F).factor()
    if any(e > 1 for _, e in factors):
        return None
    return [G for G, _ in factors]


def _singular_normal_forms(
    factors: Sequence[fmpq_mpoly], variables: tuple[sympy.Symbol, sympy.Symbol]
) -> list[sympy.Expr]:
    """The factors as ``absFactorize`` writes them: primitive over ``ZZ`` with a positive
    leading coefficient in Singular's ``dp`` order (degree, then lexicographic), and listed by
    their ``dp`` monomials, then coefficients (the order it gives for a torus's profile)."""
    normal = []
    for G in factors:
        terms = sorted(rational_terms(rational_primitive(G)), key=lambda t: _dp_monomial(t[0]), reverse=True)
        sign = -1 if terms[0][1] < 0 else 1
        normal.append([(_dp_monomial(m), m, sign * c) for m, c in terms])
    normal.sort(key=lambda t: ([d for d, _, _ in t], [c for _, _, c in t]))
    x, y = variables
    return [sympy.Add(*(sympy.Integer(int(c.p)) * x ** m[0] * y ** m[1] for _, m, c in t)) for t in normal]


def _dp_monomial(m: tuple[int, ...]) -> tuple[int, ...]:
    return (sum(m), *m)


def _is_line_or_smooth_conic(F: fmpq_mpoly) -> bool:
    """Degree 1, or degree 2 with the nonsingular symmetric matrix of its homogenisation: then
    ``F`` is absolutely irreducible of genus 0."""
    degree = F.total_degree()
    if degree == 1:
        return True
    if degree != 2:
        return False
    c = {tuple(map(int, m)): v for m, v in F.to_dict().items()}
    a, b, cc = c.get((2, 0), 0), c.get((1, 1), 0), c.get((0, 2), 0)
    d, e, f = c.get((1, 0), 0), c.get((0, 1), 0), c.get((0, 0), 0)
    matrix = fmpq_mat([[2 * a, b, d], [b, 2 * cc, e], [d, e, 2 * f]])
    return matrix.det() != 0


def _smooth_double_cover(
    P: Poly, P2: Poly, timeout: float, cancel: threading.Event | None
) -> tuple[CurveAnalysis, CurveAnalysis] | None:
    """Both analyses when the projective closure of ``P`` is smooth, else ``None``.

    A smooth plane curve is absolutely irreducible, so ``P → P²`` has degree 2 and ``P²`` is
    absolutely irreducible too. The involution ``σ: r ↦ -r`` of ``P`` fixes exactly the points
    of ``P`` on the line ``r = 0`` and the point ``(0:1:0)`` if it lies on ``P``; on a smooth
    curve every fixed point is a ramification point, so with ``B`` of them
    ``2g(P) - 2 = 2(2g(P²) - 2) + B``.
    """
    d = total_degree(P)
    if not is_rational_field(P.ring.domain) or d < 3 or any(m[1] % 2 for m in P.itermonoms()):
        return None
    factors = to_flint(P).factor()[1]
    if len(factors) > 1 or factors[0][1] > 1:
        return None  # reducible over QQ, so singular: no smoothness test
    H = poly_ring(("s", "r", "z"), QQ).from_dict({(i, j, d - i - j): c for (i, j), c in primitive(P).items()})
    if all(int(c) % SMOOTHNESS_PRIME == 0 for c in H.values()):
        return None
    script = (
        f"ring sorguiS = {SMOOTHNESS_PRIME},(s,r,z),dp;\n"
        f"poly F = {poly_to_singular(H, ['s', 'r', 'z'])};\n"
        "ideal J = jacob(F), F;\n" + emit("cone_dimension", "string(dim(std(J)))")
    )
    if one_result(run_script(script, timeout=timeout, cancel=cancel), "cone_dimension") != "0":
        return None
    on_line = fmpq_poly([_fmpq(c) for c in _dense(P)])
    distinct = on_line.degree() - on_line.gcd(on_line.derivative()).degree()
    coefficients = dict(P.items())
    fixed = distinct + (on_line.degree() < d) + ((0, d) not in coefficients)
    genus_p = (d - 1) * (d - 2) // 2
    twice, rest = divmod(2 * genus_p - 2 - fixed, 4)
    if rest:
        raise SingularError("Riemann-Hurwitz gave a fractional genus (internal error)")
    analyses = []
    for F, g in ((P, genus_p), (P2, twice + 1)):
        factor = AbsoluteFactor(primitive(F).as_expr(), 1, 1)
        analyses.append(CurveAnalysis(AbsoluteFactorization(variables_of(F), (factor,)), g))
    return analyses[0], analyses[1]


def _dense(P: Poly) -> list[object]:
    """The coefficients of ``P(s, 0)``, lowest degree first."""
    top = max((i for (i, j) in P.itermonoms() if j == 0), default=0)
    out = [QQ.zero] * (top + 1)
    for (i, j), c in P.items():
        if j == 0:
            out[i] = c
    return out


def _fmpq(c: object) -> fmpq:
    """A rational number of sympy's ``QQ`` as flint's ``fmpq``."""
    return fmpq(int(QQ.numer(c)), int(QQ.denom(c)))
