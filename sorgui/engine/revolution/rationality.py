"""Rationality of a surface of revolution: Table 1 of the paper and the tubular surface (docs/math.md §5).

From the ``K``-rational profile ``P: p̃(s, r) = 0`` and its square ``P²: p̃²(s, w) = 0``:

* ``X_C`` is rational iff ``genus(P²) = 0`` (Theorem "rationality of SOR");
* ``P`` reducible over ``C`` means ``p̃ = g(s, r)·g(s, -r)`` (the cone's two lines);
* the row of Table 1 follows from "reducible / genus(P)" and "genus(P²)";
* when ``genus(P²) = 0``, a proper parameterization ``(φ, r/q)`` of ``P²`` gives the tubular
  surface ``T: y² + z² = h(x)`` with ``h = r̂·q̂`` (Theorem "birational to tubular"), and the
  real surface is rational iff it is unirational and ``h`` has at most two real roots (the
  Corollary), counted exactly with Sturm sequences.

Every Singular call runs under the time limit; a limit reached ends in an "undecided" status,
never in a hang.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass, replace
from typing import TypedDict

import sympy
from flint import fmpq_poly
from sympy.polys.domains import QQ
from sympy.polys.domains.domain import Domain
from sympy.polys.polyerrors import BasePolynomialError

from ..algebra import numberfields, quadratic
from ..algebra.linalg import dot
from ..algebra.polys import (
    Poly,
    field_generators,
    from_flint,
    is_rational_field,
    number_field,
    poly_ring,
    to_expr,
    to_flint,
)
from ..algebra.realroots import count_real_roots
from ..errors import AnalysisError, OutOfReach, SingularError, SingularTimeout
from ..recognition.profile import ProfileCurve
from ..singular import curves, profile_pair
from ..singular.curves import CurveAnalysis, CurveParametrization
from ..stage_results import Parametrization, Rationality
from .parametrization import (
    Section,
    T,
    frame_map,
    make_parametrization,
    norm_decomposition,
    quadric_section,
    quadric_vanishes,
    section_vanishes,
    sweep,
    tube_section_vanishes,
    tubular_section,
)
from .reparametrization import GivenMap, Reparametrization, same_sweep, typed_sweep

UNSUPPORTED = (BasePolynomialError, NotImplementedError)
"""What sympy raises for coefficient fields it cannot handle; a parameterization is then left
out with a note (:data:`UNSUPPORTED_NOTE`), and the rest of the analysis stands."""

UNSUPPORTED_NOTE = (
    "not computed: it needs exact arithmetic over a field that sorgui cannot handle "
    "(nested square roots, or roots that are not written in radicals)"
)

ALPHA = sympy.Symbol("alpha")
"""Stands for ``√-n`` (``n = |a|²``) in the complex parameterization through ``T``."""


@dataclass(frozen=True)
class TubularSurface:
    """``T: y² + z² = h(x)`` and the map ``τ(x, y, z) = (φ(x), d(x)·y/q̃(x), d(x)·z/q̃(x))``."""

    phi: sympy.Expr
    h: sympy.Expr
    d: sympy.Expr
    q: sympy.Expr
    field: tuple[sympy.Expr, ...]


class _TableFacts(TypedDict):
    """The facts of Table 1 that every :class:`Rationality` past the genus computation carries
    (keyword arguments of :class:`Rationality`)."""

    profile_reducible: bool
    absolute_factors: tuple[str, ...]
    genus_profile: int | None
    genus_profile_square: int
    table_row: int
    complex_rational: bool


class _TubeFacts(TypedDict):
    """The parameterization of ``P²`` and the tubular surface built from it, as every
    :class:`Rationality` that has them carries them (keyword arguments of :class:`Rationality`)."""

    square_parametrization: tuple[str, str]
    tubular_surface: str
    h: str
    tau: tuple[str, str, str]


def table_row(reducible: bool, genus_p: int | None, genus_p2: int) -> int:
    """The row (1–5, top to bottom) of Table 1 of the paper."""
    if reducible:
        return 1 if genus_p2 == 0 else 2
    if genus_p == 0:
        return 3
    return 4 if genus_p2 == 0 else 5


def tubular_surface(par: CurveParametrization) -> TubularSurface:
    """The tubular surface of a proper parameterization ``(φ(t), r(t)/q(t))`` of ``P²``:
    cancel ``gcd(r, q)``, write ``r̃·q̃ = h·d²`` with ``h`` square-free (odd multiplicities).
    Over a quadratic field the decomposition is flint's (:mod:`..algebra.quadratic`)."""
    quick = _quadratic_tube(par)
    if quick is not None:
        return quick
    phi = sympy.cancel(par.x.subs(par.parameter, T))
    r, q = sympy.fraction(sympy.cancel(par.y.subs(par.parameter, T)))
    product = _univariate(r * q, par.generators)
    lead, factors = product.sqf_list()
    h, d = product.ring.domain.to_sympy(lead), sympy.Integer(1)
    for g, e in factors:
        h *= g.as_expr() ** (e % 2)
        d *= g.as_expr() ** (e // 2)
    tube = TubularSurface(phi=phi, h=sympy.expand(h), d=sympy.expand(d), q=sympy.expand(q), field=par.generators)
    if _univariate(tube.h * tube.d**2, par.generators) != product:
        raise AnalysisError("the tubular surface's h·d² is not r̃·q̃ (internal error)")
    return tube


def _quadratic_tube(par: CurveParametrization) -> TubularSurface | None:
    """:func:`tubular_surface` of a parameterization over a quadratic field, from its fractions
    over ``D = QQ(α)`` in flint; ``None`` over ``QQ`` (sympy is fast there) and other fields."""
    if par.fractions is None:
        return None
    (p1, q1), (r, q) = par.fractions
    D = r.ring.domain
    K = quadratic.field_of(D)
    if K is None or K.rational:
        return None
    product = K.mul(quadratic.pair_of(r), quadratic.pair_of(q))
    top = quadratic.degree(product)
    lead = (fmpq_poly([product[0][top]]), fmpq_poly([product[1][top]]))
    h, d = lead, (fmpq_poly([1]), fmpq_poly([]))
    for g, e in quadratic.squarefree_decomposition(K, product):
        for _ in range(e % 2):
            h = K.mul(h, g)
        for _ in range(e // 2):
            d = K.mul(d, g)
    if K.mul(h, K.mul(d, d)) != product:
        raise AnalysisError("the tubular surface's h·d² is not r̃·q̃ (internal error)")

    def expr(x: quadratic.Pair) -> sympy.Expr:
        return quadratic.pair_expr(x, D, T)

    phi = expr(quadratic.pair_of(p1)) / expr(quadratic.pair_of(q1))
    return TubularSurface(phi=phi, h=expr(h), d=expr(d), q=expr(quadratic.pair_of(q)), field=par.generators)


def count_real_roots_of(h: sympy.Expr, generators: tuple[sympy.Expr, ...]) -> int:
    """The number of real roots of ``h`` (coefficients in ``QQ`` or a real field), exactly."""
    return count_real_roots(_univariate(h, generators))


def _univariate(expr: sympy.Expr, generators: tuple[sympy.Expr, ...]) -> Poly:
    """``expr ∈ QQ(generators)[t]`` as a ring element; a real multiquadratic field goes through
    its radical basis (fast), any other through sympy."""
    radicands = numberfields.real_radicands(generators)
    if radicands is not None:
        return numberfields.from_expr(expr, poly_ring(("t",), number_field(radicands)))
    K = QQ.algebraic_field(*generators)
    # Coefficient by coefficient: sympy's ring would convert the factors of ``I*sqrt(5)`` one by
    # one, and ``I`` alone is not in ``QQ(sqrt(-5))``.
    terms = sympy.Poly(sympy.expand(expr), T, domain="EX").terms()
    return poly_ring(("t",), K).from_dict({monom: K.from_sympy(c.as_expr()) for monom, c in terms})


def has_real_surface(h: sympy.Expr, real_roots: int) -> bool:
    """Whether ``y² + z² = h(x)`` has a two-dimensional real part: ``h > 0`` somewhere."""
    poly = sympy.Poly(h, T)
    return real_roots > 0 or poly.degree() % 2 == 1 or bool(poly.LC() > 0)


def analyze_rationality(
    profile: ProfileCurve,
    *,
    timeout: float = 60.0,
    cancel: threading.Event | None = None,
    section: tuple[sympy.Expr, sympy.Expr, sympy.Expr] | None = None,
) -> tuple[Rationality, TubularSurface | None]:
    """The rationality facts of a surface of revolution with the given profile; ``section`` is
    a rational curve ``Q(t)`` on ``X`` (from a typed parametrization, docs/math.md §13) whose
    image in the axis frame parameterizes ``P²`` when it is proper (then no Singular is asked
    for a parameterization of ``P²``)."""
    if all(m == (0, 1) for m in profile.square.itermonoms()):
        # P² = c·w: X is y² + z² = 0 in the axis frame, two complex planes (docs/math.md §4).
        return Rationality(
            status="not applicable: X is a pair of complex planes through the axis (not absolutely irreducible)"
        ), None
    frame = profile.frame
    shear = profile.square.ring.domain.quo(dot(frame.direction, frame.direction), dot(frame.normal, frame.normal))
    known = None if section is None else _from_section(profile, section)
    try:
        p, p2 = profile_pair.analyze_profile_pair(
            profile.rational, profile.square, shear=shear, known=known, timeout=timeout, cancel=cancel
        )
    except SingularTimeout as exc:
        return Rationality(status=f"undecided within the time limit: {exc.message}"), None
    except (SingularError, OutOfReach) as exc:
        return Rationality(status=f"undecided: {exc.message}"), None
    absolute = _absolute_factors(p)
    reducible = not p.is_absolutely_irreducible
    if p2.genus is None:
        return Rationality(
            status="not applicable: X is not absolutely irreducible (P² splits over C)",
            profile_reducible=reducible,
            absolute_factors=absolute,
        ), None
    row = table_row(reducible, p.genus, p2.genus)
    base = _TableFacts(
        profile_reducible=reducible,
        absolute_factors=absolute,
        genus_profile=None if reducible else p.genus,
        genus_profile_square=p2.genus,
        table_row=row,
        complex_rational=p2.genus == 0,
    )
    if p2.genus > 0:
        return Rationality(status="decided", unirational=False, real_rational=False, **base), None
    try:
        par = (
            p2.parametrization
            or known
            or profile_pair.parametrize_square(profile.square, shear, timeout=timeout, cancel=cancel)
        )
    except SingularTimeout as exc:
        return Rationality(
            status=f"partly undecided: {exc.message}",
            **base,
            notes=("no parameterization of P² within the time limit",),
        ), None
    except (AnalysisError, SingularError) as exc:
        return Rationality(
            status="partly undecided", **base, notes=(f"no parameterization of P²: {exc.message}",)
        ), None
    tube = tubular_surface(par)
    facts: _TubeFacts = {
        "square_parametrization": (str(par.x), str(par.y)),
        "tubular_surface": _tube_str(tube),
        "h": str(tube.h),
        "tau": _tau_str(tube),
    }
    notes: tuple[str, ...] = ("T and τ live in the axis frame p = c + s·a + y·u + z·(a × u)/|a| of the profile",)
    if not par.is_real:
        return Rationality(
            status="decided",
            unirational=False,
            real_rational=False,
            notes=(*notes, f"P² has no real parameterization (field {par.field})"),
            **facts,
            **base,
        ), tube
    try:
        roots = count_real_roots_of(tube.h, par.generators)
    except OutOfReach as exc:
        notes = (*notes, f"the real roots of h were not counted: {exc.message}")
        return Rationality(status="partly undecided", notes=notes, **facts, **base), tube
    unirational = has_real_surface(tube.h, roots)
    return Rationality(
        status="decided",
        unirational=unirational,
        real_rational=unirational and roots <= 2,
        real_roots_of_h=roots,
        notes=notes,
        **facts,
        **base,
    ), tube


def _from_section(
    profile: ProfileCurve, section: tuple[sympy.Expr, sympy.Expr, sympy.Expr]
) -> CurveParametrization | None:
    """``(s, w)(t)`` of a curve ``Q(t)`` on ``X`` in the profile's frame ``(c, a, u)``:
    ``s = a·(Q − c)/|a|²``, ``w = |Q − c − s·a|²/|u|²``; ``None`` unless it is a proper
    parameterization of ``P²`` (checked exactly, :func:`~.curves.is_on_curve`, :func:`~.curves.is_proper`)."""
    K = profile.square.ring.domain
    t = curves.PARAMETER
    c, a, u = (
        [to_expr(K, v) for v in vector]
        for vector in (profile.frame.point, profile.frame.direction, profile.frame.normal)
    )
    q = [e.subs(sympy.Symbol("t"), t) - ci for e, ci in zip(section, c)]  # already sympy: never text
    s = sympy.cancel(sum(ai * qi for ai, qi in zip(a, q)) / sum(ai * ai for ai in a))
    w = sympy.cancel(sum((qi - s * ai) ** 2 for qi, ai in zip(q, a)) / sum(ui * ui for ui in u))
    generators = tuple(field_generators(K))
    if not curves.is_on_curve(profile.square, s, w, t, generators) or not curves.is_proper(
        profile.square, s, w, t, generators
    ):
        return None
    variables = tuple(sympy.Symbol(str(v)) for v in profile.square.ring.symbols)
    return CurveParametrization((variables[0], variables[1]), s, w, t, generators, "a curve of the given map")


def _absolute_factors(analysis: CurveAnalysis) -> tuple[str, ...]:
    """The absolute factors as strings, with the algebraic number ``a`` named where present."""
    out = []
    for fac in analysis.factorization.factors:
        text = str(fac.factor)
        if fac.minpoly is not None:
            text += f"  where {fac.minpoly} = 0"
        if fac.multiplicity > 1:
            text = f"({text})^{fac.multiplicity}"
        out.append(text)
    return tuple(out)


def _tube_str(tube: TubularSurface) -> str:
    x, y, z = sympy.symbols("x y z")
    return str(y**2 + z**2 - tube.h.subs(T, x))


def _tau_str(tube: TubularSurface) -> tuple[str, str, str]:
    x, y, z = sympy.symbols("x y z")
    factor = (tube.d / tube.q).subs(T, x)
    return str(tube.phi.subs(T, x)), str(sympy.cancel(factor * y)), str(sympy.cancel(factor * z))


# --- parameterizations of X -----------------------------------------------------------------


def parametrizations(
    f: Poly,
    profile: ProfileCurve,
    rationality: Rationality,
    tube: TubularSurface | None,
    *,
    timeout: float = 60.0,
    cancel: threading.Event | None = None,
    given: GivenMap | None = None,
) -> tuple[tuple[Parametrization, ...], tuple[str, ...], bool]:
    """Every parameterization docs/math.md §6 provides, each verified; notes on those that could
    not be built; and whether the ``given`` (typed) map is proper. A map that is the given map's
    after a change of parameters is left out, with a note (docs/math.md §6, "One map, listed
    once"); the change being a bijection, the given map is proper when that map is."""
    found: list[Parametrization] = []
    swept: list[tuple[Section, Parametrization]] = []
    notes: list[str] = []
    K = f.ring.domain
    frame = profile.frame
    rotated: tuple[Section, Parametrization] | None = None
    if rationality.genus_profile == 0 or rationality.profile_reducible:
        try:
            section = _profile_section(profile, rationality, timeout=timeout, cancel=cancel)
            proper = False if not rationality.profile_reducible else None
            par = _swept(f, profile, section, method="rotated profile", proper=proper)
            if par is not None:
                found.append(par)
                rotated = section, par
                swept.append(rotated)
        except (AnalysisError, SingularError) as exc:
            notes.append(f"rotated profile: {exc.message}")
        except UNSUPPORTED:
            notes.append(f"rotated profile: {UNSUPPORTED_NOTE}")
    if tube is not None:
        n = to_expr(K, dot(frame.direction, frame.direction))
        try:
            real = _real_tube_section(tube, n)
            same = _same_sweep(rotated[0], real, n) if rotated and real else None
            if rotated is not None and same is not None:  # one map, listed once: proper as the tube's is
                proper_map = replace(rotated[1], proper=True)
                found[found.index(rotated[1])] = proper_map
                swept[swept.index(rotated)] = (rotated[0], proper_map)
                after = same.describe()
                par, note = None, f"the map through T is the rotated profile's{after}: listed once, and proper as it is"
            else:
                par, note = _tubular_parametrization(f, profile, tube, n, K, rationality, real)
                if par is not None and real is not None:
                    swept.append((real, par))
        except UNSUPPORTED:
            par, note = None, f"parameterization through T: {UNSUPPORTED_NOTE}"
        found += [par] if par is not None else []
        notes += [note] if note else []
    given_proper = False
    if given is not None and swept:
        for par, note in _given_again(given, swept, profile, K):
            found.remove(par)
            notes.append(note)
            given_proper = given_proper or par.proper is True
    return tuple(found), tuple(notes), given_proper


def _given_again(
    given: GivenMap, swept: list[tuple[Section, Parametrization]], profile: ProfileCurve, K: Domain
) -> list[tuple[Parametrization, str]]:
    """The maps of ``swept`` that are the typed map's after a change of parameters
    (:func:`.reparametrization.typed_sweep`, :func:`.reparametrization.same_sweep`), each with
    its note; none when sympy cannot decide it."""
    frame = profile.frame
    n = dot(frame.direction, frame.direction)
    again = []
    try:
        typed = typed_sweep(given, (frame.point, frame.direction, frame.normal, frame.binormal), n)
        if typed is None:
            return []
        n_expr = to_expr(K, n)
        for section, par in swept:
            same = same_sweep(typed.section, section, n_expr)
            if same is not None:
                first, second = typed.given_in(same)
                names = ", ".join(given.names)
                name = "the rotated profile's map" if par.method == "rotated profile" else "the map through T"
                again.append((par, f"{name} is the given map at ({names}) = ({first}, {second}): listed once"))
    except UNSUPPORTED:
        return []
    return again


def _real_tube_section(tube: TubularSurface, n: sympy.Expr) -> Section | None:
    """The real section through ``T`` when ``h = A² + n·B²`` (docs/math.md §6), else ``None``."""
    real = norm_decomposition(tube.h, n)
    return None if real is None else tubular_section(tube.phi, tube.d, tube.q, *real)


def _same_sweep(rotated: Section, real: Section, n: sympy.Expr) -> Reparametrization | None:
    """How the real section through ``T`` sweeps to the rotated profile's map after bijections of
    the parameters (:func:`.reparametrization.same_sweep`); ``None`` otherwise, also when sympy
    cannot decide it (the map through ``T`` is then made and listed as usual)."""
    try:
        return same_sweep(rotated, real, n)
    except UNSUPPORTED:
        return None


def _tubular_parametrization(
    f: Poly,
    profile: ProfileCurve,
    tube: TubularSurface,
    n: sympy.Expr,
    K: Domain,
    rationality: Rationality,
    real: Section | None,
) -> tuple[Parametrization | None, str]:
    """The parameterization through ``T`` (docs/math.md §6): real when ``h = A² + n·B²`` (``real``
    is then its section, :func:`_real_tube_section`), or when the rest after the norm part is of
    degree ≤ 2 (a quadric, projected stereographically); the complex one otherwise. Returns it
    and a note on what could not be done."""
    frame = profile.frame
    radius = tube.d**2 * tube.h / tube.q**2
    if real is not None:
        return _swept(f, profile, real, method="via tubular surface (real)", proper=True, radius=radius), ""
    quadric = quadric_section(tube.h, n)
    if quadric is not None:
        x, Y, Z = quadric
        scale = (tube.d / tube.q).subs(T, x)
        surface = frame_map(tube.phi.subs(T, x), scale * Y, scale * Z, frame, K)

        def on_tube() -> bool:
            return quadric_vanishes(quadric, tube.h, n)

        return make_parametrization(
            f, profile, surface, on_tube, method="via tubular surface (real, stereographic)", proper=True
        ), ""
    A, B = (tube.h + 1) / 2, (tube.h - 1) / (2 * ALPHA)
    section = tubular_section(tube.phi, tube.d, tube.q, A, B, named=((ALPHA, sympy.sqrt(-n)),))
    complex_par = _swept(f, profile, section, method="via tubular surface (complex)", proper=True, radius=radius)
    if not rationality.unirational:
        note = ""
    elif (rationality.real_roots_of_h or 0) > 2:
        note = (
            "X is unirational but not rational: h has more than two real roots, so the real surface "
            "is disconnected (the paper's Corollary); sorgui gives the complex parameterization only"
        )
    else:
        note = (
            "no real parameterization through T was found: h = N·u²·q with q of degree > 2, h "
            "has irrational coefficients, or no rational point of y² + n·z² = q(t) was found (its "
            "numbers not factored quickly); sorgui gives the complex parameterization only"
        )
    return complex_par, note


def _swept(
    f: Poly,
    profile: ProfileCurve,
    section: Section,
    *,
    method: str,
    proper: bool | None,
    radius: sympy.Expr | None = None,
) -> Parametrization | None:
    """The verified parameterization sweeping ``section`` about the axis (docs/math.md §6); a
    section through ``T`` (``radius`` the tube's ``d²h/q̃²``) is checked against it."""
    surface = sweep(section, profile.frame, f.ring.domain)

    def identity() -> bool:
        if radius is None:
            return section_vanishes(profile, section)
        return tube_section_vanishes(profile, section, radius)

    return make_parametrization(f, profile, surface, identity, method=method, proper=proper)


def _profile_section(
    profile: ProfileCurve, rationality: Rationality, *, timeout: float, cancel: threading.Event | None
) -> Section:
    """A section from a rational profile ``P`` or from a component ``P⁺`` of a reducible one."""
    curve = profile.rational
    if rationality.profile_reducible:
        curve = _real_component(profile.rational, timeout=timeout, cancel=cancel)
    par = curves.parametrize(curve, timeout=timeout, cancel=cancel, prefer_conic=True)
    return Section(phi=par.x.subs(par.parameter, T), rho_u=par.y.subs(par.parameter, T), rho_w=sympy.Integer(0))


def _real_component(p: Poly, *, timeout: float, cancel: threading.Event | None) -> Poly:
    """A component ``g(s, r)`` of ``p̃ = g(s, r)·g(s, -r)`` over a real field, as a polynomial: over
    ``QQ`` when flint's factorization finds one (no Singular run), else from the absolute one."""
    rational = _rational_component(p)
    if rational is not None:
        return rational
    factorization = curves.absolute_factorization(p, timeout=timeout, cancel=cancel)
    s, r = sympy.symbols("s r")
    real = False
    for fac in factorization.factors:
        if fac.minpoly is None:
            candidates = [fac.factor]
        else:
            candidates = [fac.factor.subs(curves.ALGEBRAIC, root) for root in _real_roots(fac.minpoly)]
        real = real or bool(candidates)
        for expr in candidates:
            expr = sympy.expand(expr)
            roots = {a for a in expr.atoms(sympy.Pow) if not a.exp.is_Integer}
            numbers = sorted(roots, key=str)
            if expr.has(sympy.CRootOf) or not all(a.exp == sympy.Rational(1, 2) and a.base.is_Rational for a in roots):
                continue  # not in square roots of rationals: no field sorgui can write it over
            K = QQ.algebraic_field(*numbers) if numbers else QQ
            R = poly_ring(("s", "r"), K)
            return (
                R.from_expr(expr.subs({s: R.symbols[0], r: R.symbols[1]}))
                if numbers
                else R(sympy.Poly(expr, s, r).as_expr())
            )
    if not real:
        raise AnalysisError("not computed: no component of the profile is real (its components are complex conjugates)")
    raise AnalysisError(
        "not computed: no component of the profile is defined over a real field of square "
        "roots of rational numbers (its components need nested or higher roots)"
    )


def _rational_component(p: Poly) -> Poly | None:
    """An irreducible factor ``g`` of ``p̃`` over ``QQ`` that is not even in ``r``, so that
    ``g(s, r)·g(s, -r)`` divides ``p̃``: a real component (``None`` over another field)."""
    if not is_rational_field(p.ring.domain):
        return None
    _, factors = to_flint(p).factor()
    for g, _ in factors:
        component = from_flint(g, p.ring)
        if any(m[1] % 2 for m in component.itermonoms()):
            return component
    return None


def _real_roots(minpoly: sympy.Expr) -> list[sympy.Expr]:
    """The real roots of ``minpoly``, in radicals when sympy finds them (degree ≤ 4: the field of
    a component of a torus's profile over ``QQ(√6)`` has degree 4), else as ``CRootOf``."""
    poly = sympy.Poly(minpoly, curves.ALGEBRAIC)
    radicals = sympy.roots(poly)
    if sum(radicals.values()) == poly.degree():
        return [root for root in radicals if root.is_real or (root.is_real is None and _numerically_real(root))]
    return [root for root in poly.all_roots() if root.is_real]


def _numerically_real(root: sympy.Expr) -> bool:
    """Whether a root in radicals whose realness sympy cannot decide is real to 60 digits (the
    parameterizations built from it are checked exactly anyway)."""
    value = sympy.N(root, 60)
    return bool(abs(sympy.im(value)) <= 10**-50 * max(1, abs(sympy.re(value))))  # the comparison gives a sympy Boolean
