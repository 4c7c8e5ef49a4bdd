"""Plane-curve algorithms of the rationality analysis (docs/math.md §4–§5, the paper's Section 3).

Every function takes a bivariate polynomial ``F`` over ``K`` (``QQ`` or a real algebraic field
``QQ(θ)``) and starts at most one Singular process (:mod:`.process`), which ``timeout`` and
``cancel`` control; :func:`analyze_curves` handles several curves (``P`` and ``P²``) in one run.
Algorithm choice:

* absolute factorization: ``absFactorize`` (absfact.lib) over ``QQ``. It refuses algebraic
  extensions, so over ``K = QQ(θ)`` each square-free part ``G`` of ``F`` goes through its norm
  ``N = Res_t(G(x + sθ, y + s²θ), m(t)) ∈ QQ[x, y]`` (Trager; the shift ``s`` makes ``N``
  square-free). The absolute factors of ``N`` are those of all conjugates of ``G``; a class
  over ``QQ(a)`` contains ``θ = c(a)`` for a root ``c`` of ``m`` (found by a divisibility test)
  and holds ``deg μ / deg m`` factors of ``G``. When ``QQ(a) = K`` the factor is rewritten
  over ``K``.
* genus: ``genus`` (normal.lib) over ``QQ``; over ``QQ(θ)`` the checked workaround of docs/math.md §5,
  ``genus(ideal(F, m(t))) = d·(g - 1) + 1``. Only for absolutely irreducible curves.
* parameterization of a genus-0 curve: the direct route when ``F`` is linear in a variable (no
  Singular at all), else ``paraPlaneCurve`` (paraplanecurves.lib) on the homogenised curve,
  with its conic step replaced by a real-preferring one: when ``rationalPointConic`` picks an
  imaginary field although the conic has real points, a line through an interior point meets
  it in a point over a real quadratic field. Every answer is checked exactly: it satisfies
  ``F`` and its degree equals ``deg F`` (proper). No answer is an :class:`AnalysisError` that
  says why (e.g. ``paraPlaneCurve`` accepts only ``QQ``). When ``paraPlaneCurve`` fails (it does
  on some curves) or Singular is missing, the conic route takes a curve quadratic in one
  variable whose discriminant is a square times a polynomial of degree 1 or 2; for a curve with
  coefficients of more than 64 bits it goes first (``paraPlaneCurve`` is slow on those).
"""

from __future__ import annotations

import threading
from collections.abc import Sequence
from dataclasses import dataclass

import sympy
from flint import fmpq, fmpq_poly
from sympy.polys.domains import QQ
from sympy.polys.domains.domain import Domain

from ..algebra import legendre
from ..algebra import quadratic as quadratic_fields
from ..algebra.polys import (
    Poly,
    compose,
    field_generators,
    is_rational_field,
    poly_ring,
    primitive,
    to_expr,
    total_degree,
)
from ..errors import AnalysisError, SingularError
from .field_conics import conic_over_field
from .process import (
    minpoly_to_singular,
    parse_int,
    parse_intvec,
    parse_list,
    parse_singular,
    poly_to_singular,
    run_script,
)

ALGEBRAIC = sympy.Symbol("a")
"""The algebraic number in absolute factors and parameterizations over an extension."""

PARAMETER = sympy.Symbol("t")
"""The default parameter of rational parameterizations."""


Fraction = tuple[Poly, Poly]
"""A rational function ``p/q`` in ``D[t]``: ``q`` monic, ``gcd(p, q) = 1``."""


# --- results ------------------------------------------------------------------------------


@dataclass(frozen=True)
class AbsoluteFactor:
    """A class of conjugate absolute factors of ``F``: ``factor`` in the curve's variables and
    ``a``, a root of ``minpoly``; with ``minpoly = None`` there is no ``a`` and ``factor`` has
    coefficients in ``K`` (square roots as sympy radicals).

    ``conjugates`` factors of ``F`` lie in the class, each with ``multiplicity``. Over
    ``K = QQ(θ)`` they are ``factor`` at those roots ``a`` of ``minpoly`` with
    ``generator(a) = θ`` (``generator`` is ``None`` over ``QQ``).
    """

    factor: sympy.Expr
    multiplicity: int
    conjugates: int
    minpoly: sympy.Expr | None = None
    generator: sympy.Expr | None = None


@dataclass(frozen=True)
class AbsoluteFactorization:
    """``F`` over ``C`` (docs/math.md §4): classes of conjugate absolute factors."""

    variables: tuple[sympy.Symbol, sympy.Symbol]
    factors: tuple[AbsoluteFactor, ...]

    @property
    def is_absolutely_irreducible(self) -> bool:
        """Exactly one absolute factor: one class, multiplicity 1, no conjugates."""
        return [(f.multiplicity, f.conjugates) for f in self.factors] == [(1, 1)]

    @property
    def count(self) -> int:
        """The number of absolute factors of ``F``, counted with multiplicity."""
        return sum(f.multiplicity * f.conjugates for f in self.factors)


@dataclass(frozen=True)
class CurveAnalysis:
    """Absolute factorization and, for an absolutely irreducible curve, its geometric genus."""

    factorization: AbsoluteFactorization
    genus: int | None
    parametrization: CurveParametrization | None = None
    """A proper parameterization of a genus-0 curve, when one was computed on the way
    (:func:`.profile_pair.analyze_profile_pair`)."""

    @property
    def is_absolutely_irreducible(self) -> bool:
        return self.factorization.is_absolutely_irreducible


@dataclass(frozen=True)
class CurveParametrization:
    """A proper rational parameterization ``(x(t), y(t))`` of a plane curve, verified exactly.

    ``generators`` are the algebraic numbers in its coefficients (``()`` over ``QQ``,
    ``(sqrt(3),)``, ``(I,)``); ``method`` is ``"direct"`` or ``"paraPlaneCurve"``.
    """

    variables: tuple[sympy.Symbol, sympy.Symbol]
    x: sympy.Expr
    y: sympy.Expr
    parameter: sympy.Symbol
    generators: tuple[sympy.Expr, ...]
    method: str
    fractions: tuple[Fraction, Fraction] | None = None
    """``x`` and ``y`` as reduced fractions of the ring ``D[t]`` they were computed in (``D`` the
    field of the generators): what exact arithmetic on them starts from, without reading the
    expressions back."""

    @property
    def coordinates(self) -> tuple[sympy.Expr, sympy.Expr]:
        return self.x, self.y

    @property
    def field(self) -> str:
        """``QQ``, ``QQ(sqrt(3))`` or ``QQ(sqrt(-1))``: the field of the coefficients."""
        if not self.generators:
            return "QQ"
        names = [f"sqrt({g**2})" if (g**2).is_Rational else str(g) for g in self.generators]
        return "QQ(" + ", ".join(names) + ")"

    @property
    def is_real(self) -> bool:
        return all(g.is_real for g in self.generators)


# --- absolute factorization and genus -------------------------------------------------------


def analyze_curves(
    curves: Sequence[Poly],
    *,
    with_genus: bool = True,
    timeout: float = 60.0,
    cancel: threading.Event | None = None,
) -> tuple[CurveAnalysis, ...]:
    """Absolute factorization and genus of several curves in ONE Singular run (e.g. ``P`` and
    ``P²`` of the paper); the genus is ``None`` unless the curve is absolutely irreducible."""
    known = {i: _linear_curve(F) for i, F in enumerate(curves)}
    plans = {i: _Plan(F, f"c{i}", with_genus) for i, F in enumerate(curves) if known[i] is None}
    found = run_script("".join(p.code for p in plans.values()), timeout=timeout, cancel=cancel) if plans else {}
    return tuple(known[i] or plans[i].read(found) for i in range(len(curves)))


def _linear_curve(F: Poly) -> CurveAnalysis | None:
    """``F = A(x)·y + C(x)`` over ``K = QQ(θ)`` with ``gcd(A, C) = 1`` (or the same with ``x`` and
    ``y`` swapped): the graph of ``-C/A``, absolutely irreducible of genus 0 (docs/math.md §5), known
    without Singular, whose norm route over ``K`` is slow. ``None`` otherwise, and over ``QQ``,
    where ``absFactorize`` is fast and gives the canonical form of the factor."""
    if is_rational_field(F.ring.domain) or F.ring.ngens != 2 or total_degree(F) < 1:
        return None
    split = _linear_split(F)
    if split is None:
        return None
    _, A, C = split
    if A.gcd(C).degree() > 0:
        return None
    factor = AbsoluteFactor(F.monic().as_expr(), 1, 1)
    return CurveAnalysis(AbsoluteFactorization(variables_of(F), (factor,)), 0)


def analyze_curve(F: Poly, *, timeout: float = 60.0, cancel: threading.Event | None = None) -> CurveAnalysis:
    """:func:`analyze_curves` for one curve."""
    return analyze_curves([F], timeout=timeout, cancel=cancel)[0]


def absolute_factorization(
    F: Poly, *, timeout: float = 60.0, cancel: threading.Event | None = None
) -> AbsoluteFactorization:
    """The factors of ``F`` over ``C``, in classes of conjugates (docs/math.md §4)."""
    return analyze_curves([F], with_genus=False, timeout=timeout, cancel=cancel)[0].factorization


def genus(F: Poly, *, timeout: float = 60.0, cancel: threading.Event | None = None) -> int:
    """The geometric genus of the absolutely irreducible curve ``F = 0`` (points at infinity
    included). Raises :class:`AnalysisError` when ``F`` is absolutely reducible or not reduced,
    where Singular's ``genus`` answers nonsense: factor first."""
    analysis = analyze_curve(F, timeout=timeout, cancel=cancel)
    if analysis.genus is None:
        raise AnalysisError(
            f"the curve {F.as_expr()} = 0 is not absolutely irreducible "
            f"({analysis.factorization.count} absolute factors): its genus is not defined"
        )
    return analysis.genus


class _Plan:
    """The Singular code for one curve of :func:`analyze_curves` and the reader of its results.

    Over ``K = QQ(θ)`` the curve is split into square-free parts over ``K``; a part with a
    rational multiple goes to ``absFactorize`` directly, the others through their norms.
    """

    def __init__(self, F: Poly, key: str, with_genus: bool) -> None:
        if F.ring.ngens != 2:
            raise ValueError("a plane curve needs a polynomial ring with two generators")
        if total_degree(F) < 1:
            raise AnalysisError("a constant polynomial does not define a curve")
        self.key = key
        self.variables = variables_of(F)
        self.symbols = {"x": self.variables[0], "y": self.variables[1], "a": ALGEBRAIC}
        rational = _over_qq(F)
        self.degree = 1
        self.parts: list[tuple[Poly, int, bool]] = [] if rational is None else [(rational, 1, True)]
        minpoly = ""
        if rational is None:
            K = self.domain = F.ring.domain
            self.degree = len(K.mod.to_list()) - 1
            minpoly = minpoly_to_singular(K, "t")
            for G, e in F.sqf_list()[1]:
                G_qq = _over_qq(G)
                self.parts.append((G if G_qq is None else G_qq, e, G_qq is not None))
        self.genus_wanted = with_genus and len(self.parts) == 1 and self.parts[0][1] == 1
        wanted = int(self.genus_wanted)
        code = []
        for j, (G, _, is_rational) in enumerate(self.parts):
            k = f"{key}_{j}"
            if is_rational:
                code.append(
                    f"ring sorguiQ_{k} = 0,(x,y),dp;\n"
                    f'sorguiAbsQQ({poly_to_singular(G, ["x", "y"])}, "{k}", {wanted});\n'
                )
            else:
                code.append(
                    f"ring sorguiN_{k} = 0,(x,y,t),dp;\n"
                    f"sorguiAbsNorm({poly_to_singular(G, ['x', 'y'], 't')}, {minpoly}, "
                    f'{self.degree}, "{k}", {wanted});\n'
                )
        self.code = "".join(code)

    def read(self, found: dict[str, list[str]]) -> CurveAnalysis:
        """The :class:`CurveAnalysis` from the script's results."""
        factors: list[AbsoluteFactor] = []
        for j, (_, e, is_rational) in enumerate(self.parts):
            k = f"{self.key}_{j}"
            factors += self._read_qq(found, k, e) if is_rational else self._read_norm(found, k, e)
        factorization = AbsoluteFactorization(self.variables, tuple(factors))
        value = None
        if self.genus_wanted and factorization.is_absolutely_irreducible:
            G = parse_int(one_result(found, f"genus_{self.key}_0"))
            if self.parts[0][2]:
                value = G
            elif (G - 1) % self.degree == 0:  # docs/math.md §5: G = d·(g - 1) + 1
                value = (G - 1) // self.degree + 1
            else:
                raise SingularError(f"the conjugate curves have genus {G}, not d·(g-1)+1")
        return CurveAnalysis(factorization, value)

    def _read_qq(self, found: dict[str, list[str]], k: str, e: int) -> list[AbsoluteFactor]:
        polys = parse_list(one_result(found, f"factors_{k}"), self.symbols)[1:]
        mults = parse_intvec(one_result(found, f"mult_{k}"))[1:]
        minpolys = parse_list(one_result(found, f"minpolys_{k}"), self.symbols)[1:]
        result = []
        for g, m, mu in zip(polys, mults, minpolys, strict=True):
            n = sympy.degree(mu, ALGEBRAIC)
            result.append(AbsoluteFactor(g, m * e, max(n, 1), mu if n > 1 else None))
        return result

    def _read_norm(self, found: dict[str, list[str]], k: str, e: int) -> list[AbsoluteFactor]:
        if one_result(found, f"squarefree_{k}") != "1":
            raise SingularError("no shift made the norm of the curve square-free")
        result = []
        for text in found.get(f"class_{k}", []):
            mu_text, c_text, h_text = text.split("|")
            mu = parse_singular(mu_text, self.symbols)
            n = int(sympy.degree(mu, ALGEBRAIC))
            if n % self.degree:
                raise SingularError(f"a class of absolute factors over a field of degree {n}")
            h = sympy.expand(parse_singular(h_text, self.symbols))
            c = parse_singular(c_text, self.symbols)
            if n == self.degree:  # QQ(a) = K: write the factor over K itself
                result.append(AbsoluteFactor(self._over_k(h, mu, c), e, 1))
            else:
                result.append(AbsoluteFactor(h, e, n // self.degree, mu, c))
        count = parse_int(one_result(found, f"count_{k}"))
        if sum(f.conjugates for f in result) * self.degree != count:
            raise SingularError("the absolute factors of the norm do not match the curve")
        return result

    def _over_k(self, h: sympy.Expr, mu: sympy.Expr, c: sympy.Expr) -> sympy.Expr:
        """``h(x, y, a)`` over ``K = QQ(θ)`` when ``QQ(a) = K`` and ``θ = c(a)``: solve
        ``a = φ(θ)`` in the basis ``1, c, c², ...`` of ``QQ[a]/(mu)``, then substitute."""
        a, d = ALGEBRAIC, self.degree
        K = self.domain
        powers = [sympy.Poly(c**j, a).rem(sympy.Poly(mu, a)) for j in range(d)]
        matrix = sympy.Matrix(d, d, lambda i, j: powers[j].coeff_monomial(a**i))
        phi = matrix.solve(sympy.Matrix(d, 1, lambda i, _: 1 if i == 1 else 0))
        a_in_k = sum((K.convert(QQ.convert(phi[j])) * K([QQ.one, QQ.zero]) ** j for j in range(d)), K.zero)
        R = poly_ring(tuple(str(v) for v in self.variables), K)
        G = R.zero
        for monom, coeff in sympy.Poly(h, *self.variables).terms():
            value = K.zero
            for (k,), q in sympy.Poly(coeff, a).terms():
                value += K.convert(QQ.convert(q)) * a_in_k**k
            G += R({monom: value})
        return G.monic().as_expr()


def variables_of(F: Poly) -> tuple[sympy.Symbol, sympy.Symbol]:
    x, y = F.ring.symbols
    return x, y


def one_result(found: dict[str, list[str]], name: str) -> str:
    """The single result ``name``; a missing one means the script did not get there."""
    values = found.get(name)
    if not values:
        raise SingularError(f"Singular did not report {name!r}")
    return values[0]


def _over_qq(F: Poly) -> Poly | None:
    """``F`` as an element of ``QQ[x, y]`` if a multiple of it has rational coefficients."""
    if is_rational_field(F.ring.domain):
        return F
    G = F.monic()
    if any(len(c.to_list()) > 1 for c in G.values()):
        return None
    R = poly_ring(tuple(str(s) for s in F.ring.symbols), QQ)
    return R.from_dict({m: QQ.convert(c.to_list()[0]) for m, c in G.items() if c.to_list()})


# --- rational parameterization --------------------------------------------------------------


def parametrize(
    F: Poly,
    *,
    parameter: sympy.Symbol = PARAMETER,
    timeout: float = 60.0,
    cancel: threading.Event | None = None,
    known_genus_zero: bool = False,
    prefer_conic: bool = False,
) -> CurveParametrization:
    """A proper rational parameterization of the genus-0 curve ``F = 0``, verified exactly.

    The direct route first (docs/math.md §5: ``A(x)·y + C(x)`` gives ``(t, -C(t)/A(t))``, and the
    same with the roles swapped), without Singular; else ``paraPlaneCurve`` over ``QQ``, whose
    field is made real when the curve has real points (see the module docstring), and the conic
    route (:func:`_conic`) when Singular fails or is missing, or first for large coefficients
    (:data:`LARGE_COEFFICIENT_BITS`); a conic with coefficients outside ``QQ`` through a point
    over its field (:mod:`.field_conics`). Raises
    :class:`AnalysisError` with the reason when there is none: the curve is reducible or of
    positive genus, or ``F`` has irrational coefficients and is linear in neither variable
    (``paraPlaneCurve`` accepts only ``QQ``). With ``known_genus_zero`` the caller vouches that
    the curve is absolutely irreducible of genus 0 (as the rationality analysis has just
    computed), and Singular does not compute it again. With ``prefer_conic`` the conic route
    is tried before Singular whatever the coefficients (a profile's conics: one Singular run
    fewer); the SMAT curves of a canal surface keep paraPlaneCurve first, whose smaller
    parameterizations make their sphere families faster to verify.
    """
    if F.ring.ngens != 2 or total_degree(F) < 1:
        raise AnalysisError("parametrize needs a non-constant polynomial in two variables")
    variables = variables_of(F)
    found = _direct(F)
    curve, method = F, "direct"
    if found is None and _over_qq(F) is None:
        conic = conic_over_field(F)
        if conic is None:
            raise AnalysisError(
                "no parameterization: the curve has coefficients outside QQ and is linear in "
                "neither variable, and Singular's paraPlaneCurve accepts only rational "
                "coefficients (ground field is not Q); a conic over the field gets one only "
                "from a point over it, and none was found"
            )
        found, method = (_reduced(*conic[0]), _reduced(*conic[1])), "conic over K"
        if not _vanishes(curve, *found[0], *found[1]):
            found = None
    elif found is None:
        rational = _over_qq(F)
        assert rational is not None
        curve, method = rational, "paraPlaneCurve"
        conic = _conic(rational) if prefer_conic or _large(rational) else None
        if conic is not None:
            candidates, method = [conic], "conic"
        else:
            try:
                candidates = _sheared_candidates(rational, timeout, cancel, known_genus_zero)
            except SingularError:
                conic = _conic(rational)
                if conic is None:
                    raise
                candidates, method = [conic], "conic"
        found = next((c for c in candidates if _vanishes(curve, *c[0], *c[1])), None)
    elif not _vanishes(curve, *found[0], *found[1]):
        found = None
    if found is None:
        raise SingularError(f"the parameterization from {method} does not satisfy F = 0")
    (p1, q1), (p2, q2) = found
    if not _proper_degree(curve, p1, q1, p2, q2):
        raise SingularError(f"the parameterization from {method} is not proper")
    D = p1.ring.domain
    generators = () if is_rational_field(D) else tuple(field_generators(D))
    x, y = ((p.as_expr() / q.as_expr()).subs(p.ring.symbols[0], parameter) for p, q in found)
    return CurveParametrization(variables, x, y, parameter, generators, method, (found[0], found[1]))


def _direct(F: Poly) -> tuple[Fraction, Fraction] | None:
    """``(t, -C(t)/A(t))`` when ``F = A(x)·y + C(x)``, or the same with ``x`` and ``y``
    swapped, over ``K``; ``None`` when ``F`` is linear in neither variable."""
    split = _linear_split(F)
    if split is None:
        return None
    linear, A, C = split
    if A.gcd(C).degree() > 0:
        raise AnalysisError(f"the curve {F.as_expr()} = 0 is reducible: it contains a line")
    free, value = (A.ring.gens[0], A.ring.one), _reduced(-C, A)
    return (free, value) if linear == 1 else (value, free)


def _linear_split(F: Poly) -> tuple[int, Poly, Poly] | None:
    """``(i, A, C)`` with ``F = A(t)·v_i + C(t)`` (``t`` the other variable), trying ``y`` before
    ``x``; ``None`` when ``F`` is linear in neither variable."""
    R = poly_ring(("t",), F.ring.domain)
    for linear in (1, 0):
        if F.degree(linear) != 1:
            continue
        other = 1 - linear
        A = R.from_dict({(m[other],): c for m, c in F.items() if m[linear] == 1})
        C = R.from_dict({(m[other],): c for m, c in F.items() if m[linear] == 0})
        return linear, A, C
    return None


LARGE_COEFFICIENT_BITS = 64
"""A curve whose coefficients (numerators and denominators, made integral) exceed this many bits
takes the conic route before Singular: paraPlaneCurve's time grows fast with their size (an
exact torus near a printed one, with 50-digit coefficients, took minutes)."""


def _large(F: Poly) -> bool:
    """Whether the coefficients of ``F ∈ QQ[x, y]`` need more than :data:`LARGE_COEFFICIENT_BITS`."""
    G = primitive(F)
    return any(int(abs(QQ.numer(c))).bit_length() > LARGE_COEFFICIENT_BITS for c in G.values())


CONIC_POINT_SEARCH = 50
"""The conic route looks for a rational point ``(u₀, w₀)`` of ``w² = q(u)`` among the integers
``|u₀| ≤`` this (after the points at infinity and ``u₀ = 0``); Singular takes the curve if none
is found, unless its coefficients are large (:data:`CONIC_LEGENDRE_BITS`)."""
CONIC_LEGENDRE_BITS = 32
"""A conic ``w² = q(u)`` whose coefficients (made integral) exceed this many bits and that has no
small rational point gets its point from Legendre's equation (:mod:`..algebra.legendre`), or
over a quadratic field when it has no rational point, instead of from Singular, which took 11 s
on 54-bit coefficients (the nearest exact surface of a rounded torus)."""


def _conic(F: Poly) -> tuple[Fraction, Fraction] | None:
    """A proper parameterization over ``QQ`` when ``F = a(u)·v² + b(u)·v + c(u)`` and the
    discriminant is ``s(u)²·q(u)`` with ``deg q ∈ {1, 2}``: the curve is birational to the conic
    ``w² = q(u)`` by ``w = (2a·v + b)/s``, so the conic through a rational point and
    ``v = (−b + s·w)/(2a)`` parameterize it. With ``a, b, c`` coprime and ``q`` not constant,
    ``F`` is absolutely irreducible (Gauss's lemma; its discriminant is no square) of genus 0,
    so no check is needed. ``None`` when ``F`` is not of this kind or no point is found.
    Paraplanecurves' adjoint map fails on some such curves (with a tacnode at infinity, as the
    second focal conic of a torus), and this needs no Singular at all."""
    if not is_rational_field(F.ring.domain):
        return None
    R = poly_ring(("t",), QQ)
    for quadratic in (1, 0):
        if F.degree(quadratic) != 2:
            continue
        other = 1 - quadratic
        a, b, c = (R.from_dict({(m[other],): k for m, k in F.items() if m[quadratic] == e}) for e in (2, 1, 0))
        if a.gcd(b).gcd(c).degree() > 0:
            continue  # a line u = u₀ splits off: Singular's checks say so
        discriminant = b**2 - 4 * a * c
        if not discriminant:
            continue  # a double curve
        s, q = square_part(discriminant)
        conic = _conic_points(q)
        if conic is None:
            continue
        u, w, generators = conic
        at_u = {R.symbols[0]: u}
        v = sympy.cancel((-b.as_expr().subs(at_u) + s.as_expr().subs(at_u) * w) / (2 * a.as_expr().subs(at_u)))
        x, y = (u, v) if quadratic == 1 else (v, u)
        return _over_root(x, y, generators[0]) if generators else reduced_fractions(x, y, PARAMETER, ())
    return None


def _over_root(x: sympy.Expr, y: sympy.Expr, root: sympy.Expr) -> tuple[Fraction, Fraction]:
    """``x`` and ``y``, rational functions of the parameter with coefficients ``a + b·root``
    (``root = √n``), as reduced fractions over ``QQ(root)``: the coefficients are read off as
    polynomials in ``root``, not by sympy's conversion into the field, whose numerical field
    isomorphism fails on a root of a number of many digits."""
    D = QQ.algebraic_field(root)
    R = poly_ring(("t",), D)
    theta = D([QQ.one, QQ.zero])  # root itself: the field's generator
    out = []
    for expr in (x, y):
        parts = []
        for part in sympy.fraction(sympy.together(expr)):
            terms: dict[tuple[int], object] = {}
            for (i, j), c in sympy.Poly(sympy.expand(part), PARAMETER, root, domain=QQ).terms():
                terms[(i,)] = terms.get((i,), D.zero) + D.convert(QQ.convert(c)) * theta**j
            parts.append(R.from_dict(terms))
        out.append(_reduced(parts[0], parts[1]))
    return out[0], out[1]


def square_part(D: Poly) -> tuple[Poly, Poly]:
    """``(s, q)`` with ``D = s²·q`` and ``q`` free of square factors but for its constant."""
    constant, factors = D.sqf_list()
    s, q = D.ring.one, D.ring.ground_new(constant)
    for g, k in factors:
        s *= g ** (k // 2)
        if k % 2:
            q *= g
    return s, q


def _conic_points(q: Poly) -> tuple[sympy.Expr, sympy.Expr, tuple[sympy.Expr, ...]] | None:
    """``(u(t), w(t))`` parameterizing ``w² = q(u)`` properly (``deg q`` 1 or 2), and the
    generators of their field (none: ``QQ``): the lines through a point, at infinity when the
    leading coefficient is a square, else at ``u₀ = 0, ±1, …, ±``:data:`CONIC_POINT_SEARCH`; for
    large coefficients (:data:`CONIC_LEGENDRE_BITS`) then the point of Legendre's equation, or
    when the conic has no rational point, or its coefficients are not factored quickly, a real
    one over ``QQ(√q(u₀))`` (``q(u₀) > 0`` of smallest height): Singular took past its 10-s limit
    on such a conic of a rounded paraboloid's nearest surface. ``None`` if there is none."""
    t = PARAMETER
    coefficients = {m[0]: QQ.to_sympy(c) for m, c in q.items()}
    if q.degree() == 1:
        alpha, beta = (coefficients.get(k, sympy.Integer(0)) for k in (1, 0))
        return (t**2 - beta) / alpha, t, ()
    if q.degree() != 2:
        return None
    alpha, beta, gamma = (coefficients.get(k, sympy.Integer(0)) for k in (2, 1, 0))
    root = _rational_sqrt(alpha)
    if root is not None:  # the point at infinity: w = root·u + t
        u = (gamma - t**2) / (2 * root * t - beta)
        return u, root * u + t, ()
    search = sorted(range(-CONIC_POINT_SEARCH, CONIC_POINT_SEARCH + 1), key=abs)
    for u0 in search:
        w0 = _rational_sqrt(alpha * u0**2 + beta * u0 + gamma)
        if w0 is not None:
            return _line_through(alpha, beta, u0, w0) + ((),)
    if max(abs(k).p.bit_length() + abs(k).q.bit_length() for k in (alpha, beta, gamma)) <= CONIC_LEGENDRE_BITS:
        return None
    exists, point = _legendre_point(alpha, beta, gamma)
    if point is not None:
        return _line_through(alpha, beta, *point) + ((),)
    positive = [(u0, value) for u0 in search if (value := alpha * u0**2 + beta * u0 + gamma) > 0]
    if positive and exists is not True:  # no rational point, or not known (not factored quickly)
        u0, value = min(positive, key=lambda point: abs(point[1].p * point[1].q))
        w0 = sympy.sqrt(value)
        _, root = w0.as_coeff_Mul()  # √(p/q) = √(pq)/q
        return _line_through(alpha, beta, u0, w0) + ((root,),)
    return None


def _line_through(alpha: sympy.Expr, beta: sympy.Expr, u0: sympy.Expr, w0: sympy.Expr) -> tuple[sympy.Expr, sympy.Expr]:
    """The lines ``w = w₀ + t·(u − u₀)`` through the point ``(u₀, w₀)`` of ``w² = α·u² + β·u + γ``,
    each meeting the conic again at ``u(t)``: ``(u(t), w(t))``."""
    t = PARAMETER
    u = (alpha * u0 + beta + t**2 * u0 - 2 * w0 * t) / (t**2 - alpha)
    return u, w0 + t * (u - u0)


def _legendre_point(
    alpha: sympy.Rational, beta: sympy.Rational, gamma: sympy.Rational
) -> tuple[bool | None, tuple[sympy.Expr, sympy.Expr] | None]:
    """Whether ``w² = α·u² + β·u + γ`` has a rational point (``None``: undecided, a coefficient
    not factored quickly, :mod:`..algebra.legendre`) and one,
    ``(u₀, w₀)``, from Legendre's equation ``A·W² + B·U² + C·Z² = 0`` with ``w = W/Z`` and
    ``u = U/Z − β/(2α)`` (completing the square: ``w² = α·(u + β/2α)² + δ``, ``δ = γ − β²/4α``,
    over a common denominator)."""
    delta = gamma - beta**2 / (4 * alpha)
    if not delta:
        return None, None  # two lines: not a conic the route parameterizes
    exists, found = legendre.solve(int(alpha.q * delta.q), int(-alpha.p * delta.q), int(-delta.p * alpha.q))
    if found is None or found[2] == 0:
        return exists, None
    W, U, Z = (sympy.Integer(k) for k in found)
    return exists, (U / Z - beta / (2 * alpha), W / Z)


def _rational_sqrt(c: sympy.Rational) -> sympy.Rational | None:
    """The non-negative rational square root of ``c``, or ``None``."""
    if c < 0:
        return None
    p, exact_p = sympy.integer_nthroot(int(c.p), 2)
    q, exact_q = sympy.integer_nthroot(int(c.q), 2)
    return sympy.Rational(p, q) if exact_p and exact_q else None


def _para_plane_curve(
    F: Poly, timeout: float, cancel: threading.Event | None, checked: bool = False
) -> list[tuple[Fraction, Fraction]]:
    """``sorguiParaCurve`` on ``F ∈ QQ[x, y]``: the checks (skipped when ``checked``: the caller
    already knows the curve is absolutely irreducible of genus 0), then paraPlaneCurve's PARA
    dehomogenised at ``s = 1``, over ``QQ`` or the quadratic field of its ``minpoly``: one
    candidate per root of ``minpoly`` with a nonzero third coordinate."""
    script = "ring sorguiP = 0,(x,y),dp;\n" + f"sorguiParaCurve({poly_to_singular(F, ['x', 'y'])}, {int(checked)});\n"
    found = run_script(script, timeout=timeout, cancel=cancel)
    if one_result(found, "irreducible") != "1":
        raise AnalysisError(f"the curve {F.as_expr()} = 0 is not absolutely irreducible")
    g = parse_int(one_result(found, "genus"))
    if g != 0:
        raise AnalysisError(f"the curve has genus {g}, so it has no rational parameterization")
    s, t, a = sympy.symbols("s t a")
    D, roots = QQ, [QQ.zero]
    if "minpoly" in found:
        D, roots = _quadratic_roots(parse_singular(one_result(found, "minpoly"), {"a": a}), a)
    R = poly_ring(("t",), D)
    coordinates = parse_list(one_result(found, "para"), {"s": s, "t": t, "a": a})
    if len(coordinates) != 3:
        raise SingularError(f"paraPlaneCurve gave {len(coordinates)} coordinates, not 3")
    candidates = []
    for root in roots:
        para = []
        for p in coordinates:
            terms: dict[tuple[int], object] = {}
            for (_, j, k), c in sympy.Poly(p, s, t, a, domain=QQ).terms():
                terms[(j,)] = terms.get((j,), D.zero) + D.convert(QQ.convert(c)) * root**k
            para.append(R.from_dict(terms))
        if para[2]:
            candidates.append((_reduced(para[0], para[2]), _reduced(para[1], para[2])))
    return candidates


SHEARS = ((0, 0), (1, 1), (-2, 3), (3, -2))
"""The birational changes of coordinates ``(x, y) ↦ (x + k·y, y + m)`` tried in turn when
paraPlaneCurve's answer for a curve is no parameterization of it (a zero denominator at every
root of its field, or a map off the curve): another position of the same curve gives it other
adjoint curves and another rational point."""


def _sheared_candidates(
    F: Poly, timeout: float, cancel: threading.Event | None, checked: bool
) -> list[tuple[Fraction, Fraction]]:
    """Candidate parameterizations of ``F ∈ QQ[x, y]`` from paraPlaneCurve, of ``F`` itself first
    and then of its images under :data:`SHEARS`, mapped back; raises :class:`AnalysisError`
    when none of them gives one."""
    x, y = F.ring.gens
    for k, m in SHEARS:
        G = compose(F, [x + k * y, y + m]) if (k, m) != (0, 0) else F
        candidates = [_unshear(c, k, m) for c in _para_plane_curve(G, timeout, cancel, checked)]
        good = [c for c in candidates if _vanishes(F, *c[0], *c[1])]
        if good:
            return good
        checked = True  # the first call has checked irreducibility and genus
    raise AnalysisError(
        "paraPlaneCurve gave no parameterization of the curve, in any of "
        f"{len(SHEARS)} positions (a zero denominator, or a map off the curve)"
    )


def _unshear(candidate: tuple[Fraction, Fraction], k: int, m: int) -> tuple[Fraction, Fraction]:
    """``(X + k·Y, Y + m)`` for a parameterization ``(X, Y)`` of ``F(x + k·y, y + m)``."""
    (p1, q1), (p2, q2) = candidate
    return _reduced(p1 * q2 + p2 * q1 * k, q1 * q2), _reduced(p2 + q2 * m, q2)


def _quadratic_roots(mu: sympy.Expr, a: sympy.Symbol) -> tuple[Domain, list[object]]:
    """The field ``D = QQ(sqrt(n))`` of the quadratic ``mu(a)`` (``QQ(sqrt(-3))`` is printed
    ``QQ<sqrt(3)*I>``) and the roots of ``mu`` in it. When ``mu`` is reducible (a square
    discriminant: the conic step met the conic in rational points) ``D = QQ``, and Singular's
    answer, computed in ``QQ[a]/(mu)``, may hold at one root only: both are tried."""
    poly = sympy.Poly(mu, a)
    if poly.degree() != 2:
        raise SingularError(f"paraPlaneCurve chose the field QQ[a]/({mu}), not a quadratic one")
    c2, c1, c0 = poly.all_coeffs()
    k, generator = sympy.sqrt(c1**2 - 4 * c2 * c0).as_coeff_Mul()
    D = QQ if generator == 1 else QQ.algebraic_field(generator)
    root = D.one if generator == 1 else D([QQ.one, QQ.zero])
    k, c1, c2 = (D.convert(QQ.convert(c)) for c in (k, c1, c2))
    return D, [(root * k - c1) / (2 * c2), (-root * k - c1) / (2 * c2)]


def _reduced(p: Poly, q: Poly) -> Fraction:
    """``p/q`` in lowest terms with a monic denominator."""
    if not q:
        raise AnalysisError("a parameterization has a zero denominator")
    g = p.gcd(q)
    p, q = p.exquo(g), q.exquo(g)
    return p.quo_ground(q.LC), q.monic()


def _vanishes(F: Poly, p1: Poly, q1: Poly, p2: Poly, q2: Poly) -> bool:
    """``F(p1/q1, p2/q2) = 0``: with denominators cleared,
    ``Σ c·p1^i q1^(nx-i) p2^j q2^(ny-j) = 0``; in flint over ``QQ`` and quadratic fields
    (:func:`_vanishes_quadratic`), in sympy's ring otherwise."""
    D, K = p1.ring.domain, F.ring.domain
    nx, ny = F.degree(0), F.degree(1)
    if is_rational_field(K) and quadratic_fields.field_of(D) is not None:
        return _vanishes_quadratic(F, (p1, q1, p2, q2), nx, ny)
    total = p1.ring.zero
    for (i, j), c in F.items():
        if K != D:
            c = D.convert(c, K) if is_rational_field(K) else D.from_sympy(to_expr(K, c))
        total += p1**i * q1 ** (nx - i) * p2**j * q2 ** (ny - j) * c
    return not total


def _vanishes_quadratic(F: Poly, fractions: tuple[Poly, Poly, Poly, Poly], nx: int, ny: int) -> bool:
    """:func:`_vanishes` for ``F`` over ``QQ`` and a map over ``QQ`` or a quadratic field, with
    each polynomial of ``D[t]`` as two flint polynomials over ``QQ`` (:mod:`..algebra.quadratic`;
    sympy's arithmetic over an algebraic field took seconds on a curve of degree 12)."""
    K = quadratic_fields.field_of(fractions[0].ring.domain)
    assert K is not None

    def powers(x: quadratic_fields.Pair, top: int) -> list[quadratic_fields.Pair]:
        out = [(fmpq_poly([1]), fmpq_poly([]))]
        for _ in range(top):
            out.append(K.mul(out[-1], x))
        return out

    p1, q1, p2, q2 = (powers(quadratic_fields.pair_of(g), n) for g, n in zip(fractions, (nx, nx, ny, ny)))
    total_a, total_b = fmpq_poly([]), fmpq_poly([])
    for (i, j), c in F.items():
        a, b = K.mul(K.mul(p1[i], q1[nx - i]), K.mul(p2[j], q2[ny - j]))
        value = fmpq(int(QQ.numer(c)), int(QQ.denom(c)))
        total_a += a * value
        total_b += b * value
    return total_a.is_zero() and total_b.is_zero()


def _proper_degree(F: Poly, p1: Poly, q1: Poly, p2: Poly, q2: Poly) -> bool:
    """With ``x = P₁/Q``, ``y = P₂/Q`` in lowest terms, ``max deg(P₁, P₂, Q)`` is the degree of
    the map times ``deg F``: it equals ``deg F`` exactly when the map is birational."""
    q = q1.lcm(q2)
    P1, P2 = p1 * q.exquo(q1), p2 * q.exquo(q2)
    return max(total_degree(P1), total_degree(P2), total_degree(q)) == total_degree(F)


def reduced_fractions(
    x: sympy.Expr, y: sympy.Expr, t: sympy.Symbol, generators: Sequence[sympy.Expr]
) -> tuple[Fraction, Fraction]:
    """``x`` and ``y`` as reduced fractions in ``QQ(generators)[t]``."""
    D = QQ.algebraic_field(*generators) if generators else QQ
    R = poly_ring(("t",), D)
    result = []
    for expr in (x, y):
        p, q = (
            R.from_dict({m: D.from_sympy(c) for m, c in sympy.Poly(part, t).terms()})
            for part in sympy.fraction(sympy.together(expr))
        )
        result.append(_reduced(p, q))
    return result[0], result[1]


def is_on_curve(F: Poly, x: sympy.Expr, y: sympy.Expr, t: sympy.Symbol, generators: Sequence[sympy.Expr] = ()) -> bool:
    """True when ``F(x(t), y(t)) = 0`` exactly in ``QQ(generators)[t]`` (docs/math.md §6: every
    parameterization is checked by substitution)."""
    (p1, q1), (p2, q2) = reduced_fractions(x, y, t, generators)
    return _vanishes(F, p1, q1, p2, q2)


def is_proper(F: Poly, x: sympy.Expr, y: sympy.Expr, t: sympy.Symbol, generators: Sequence[sympy.Expr] = ()) -> bool:
    """True when ``(x(t), y(t))`` parameterizes the irreducible curve ``F = 0`` birationally
    (the degree criterion of :func:`_proper_degree`)."""
    (p1, q1), (p2, q2) = reduced_fractions(x, y, t, generators)
    return _proper_degree(F, p1, q1, p2, q2)
