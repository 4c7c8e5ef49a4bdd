"""Plane curves with the real Singular: absolute factors, genus, parameterizations.

Known data: the paper's Appendix Example 2 (``P`` of genus 1, ``P²`` of genus 0 with the
corrected constant ``-400``, docs/math.md §1), the cone's two lines, ``x² + y²`` (two complex
lines), ``x² + y² = 3`` (real points, no rational point).
"""

from __future__ import annotations

import threading

import pytest
import sympy
from sympy.polys.domains import QQ

from sorgui.engine.algebra.polys import Poly, number_field, poly_ring
from sorgui.engine.errors import (
    AnalysisError,
    Cancelled,
    SingularError,
    SingularNotFound,
)
from sorgui.engine.singular import curves
from sorgui.engine.singular.curves import (
    ALGEBRAIC,
    AbsoluteFactorization,
    absolute_factorization,
    analyze_curve,
    analyze_curves,
    genus,
    is_on_curve,
    is_proper,
    parametrize,
)

R = poly_ring(("x", "y"), QQ)
x, y = R.gens
X, Y = R.symbols
T = sympy.Symbol("t")
P = -400 - 104 * x**2 - x**4 + 200 * y**2 - 48 * x * y**2 + 26 * x**2 * y**2 - 29 * y**4 + 12 * x * y**4 + y**6
P2 = -400 - 104 * x**2 - x**4 + 200 * y - 48 * x * y + 26 * x**2 * y - 29 * y**2 + 12 * x * y**2 + y**3
P2_AS_PRINTED = P2 + 800  # the paper's +400, an erratum

K2 = number_field((2,))
RK = poly_ring(("x", "y"), K2)
u, v = RK.gens
SQRT2 = K2.from_sympy(sympy.sqrt(2))


def product_of_norms(factorization: AbsoluteFactorization) -> sympy.Expr:
    """∏ Res_a(factor, minpoly)^multiplicity: the product of all absolute factors over QQ."""
    result = sympy.S.One
    for f in factorization.factors:
        norm = f.factor if f.minpoly is None else sympy.resultant(f.factor, f.minpoly, ALGEBRAIC)
        result *= norm**f.multiplicity
    return sympy.expand(result)


def proportional(a: sympy.Expr, b: sympy.Expr) -> bool:
    ratio = sympy.cancel(a / b)
    return ratio.is_Rational and ratio != 0


# --- genus ------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("F", "expected"),
    [
        (y**2 - x**3 - x - 1, 1),  # smooth cubic
        (y**2 - x**3 - x**2, 0),  # nodal cubic
        (x**2 + y**2 - 1, 0),  # conic
        (2 * x - 3 * y + 1, 0),  # line
        (y**2 - x**5 - 1, 2),
        (P, 1),  # the paper's profile curve
        (P2, 0),  # its square P²
        (P2_AS_PRINTED, 3),  # the misprint +400 is not rational
    ],
)
def test_genus_of_known_curves(F: Poly, expected: int) -> None:
    assert genus(F) == expected


@pytest.mark.parametrize(
    ("F", "expected"),
    [
        (v**2 - SQRT2 * u**3 - 1, 1),  # docs/math.md §5: G = 1, g = 1
        (v**2 - SQRT2 * u**5 - 1, 2),
        (u**2 + v**2 - SQRT2, 0),
        (SQRT2 * (u**2 + v**2 - 3), 0),  # a rational multiple goes the QQ way
    ],
)
def test_genus_over_a_real_quadratic_field(F: Poly, expected: int) -> None:
    assert genus(F) == expected


@pytest.mark.parametrize("F", [y**2 - x**2, x**2 + y**2, y**2, (x - 1) * (y**2 - x**3)])
def test_genus_refuses_reducible_or_non_reduced_curves(F: Poly) -> None:
    with pytest.raises(AnalysisError, match="not absolutely irreducible"):
        genus(F)


def test_genus_refuses_a_reducible_curve_over_an_extension() -> None:
    with pytest.raises(AnalysisError):
        genus(u**2 - 2 * v**2)


def test_constant_is_not_a_curve() -> None:
    with pytest.raises(AnalysisError):
        analyze_curve(R(3))


# --- absolute factorization -------------------------------------------------------------------


def test_cone_profile_is_two_lines() -> None:
    result = absolute_factorization(y**2 - x**2)
    assert not result.is_absolutely_irreducible
    assert sorted(str(f.factor) for f in result.factors) == ["x + y", "x - y"]
    assert all(f.minpoly is None and f.conjugates == 1 for f in result.factors)


def test_sum_of_squares_splits_over_the_gaussian_numbers() -> None:
    result = absolute_factorization(x**2 + y**2)
    assert not result.is_absolutely_irreducible
    (factor,) = result.factors
    assert factor.conjugates == 2 and factor.minpoly == ALGEBRAIC**2 + 1
    assert proportional(product_of_norms(result), X**2 + Y**2)


@pytest.mark.parametrize("F", [P, P2, x**2 + y**2 - 3, y**2 * (x + 1), (x**2 - 2) * (x**2 + y**2) ** 2, x**4 + y**4])
def test_absolute_factors_multiply_to_the_curve(F: Poly) -> None:
    result = absolute_factorization(F)
    assert proportional(product_of_norms(result), F.as_expr())
    assert result.count == sum(f.multiplicity * f.conjugates for f in result.factors)


def test_multiplicities_are_reported() -> None:
    result = absolute_factorization(y**2 * (x + 1))
    found = sorted((str(f.factor), f.multiplicity) for f in result.factors)
    assert found == [("x + 1", 1), ("y", 2)]
    assert result.count == 3


@pytest.mark.parametrize(
    ("F", "count", "irreducible"),
    [
        (v**2 - SQRT2 * u**3 - 1, 1, True),
        (u**2 + v**2 - SQRT2, 1, True),
        (u**2 + SQRT2 * v**2, 2, False),  # two complex lines, conjugate over QQ(sqrt 2)
        ((u**2 + SQRT2 * v**2) ** 2 * (u - 1), 5, False),
        (u**2 - 2 * v**2, 2, False),
    ],
)
def test_absolute_factors_over_an_extension(F: Poly, count: int, irreducible: bool) -> None:
    """Each class is checked exactly: ``factor`` divides ``F`` with ``θ = generator(a)``,
    modulo the minimal polynomial of ``a``."""
    result = absolute_factorization(F)
    assert result.count == count
    assert result.is_absolutely_irreducible == irreducible
    theta = sympy.sqrt(2)
    for f in result.factors:
        if f.generator is None:
            continue
        assert sympy.rem(sympy.expand(f.generator**2 - 2), f.minpoly, ALGEBRAIC) == 0
        substituted = sympy.expand(F.as_expr().subs(theta, sympy.Symbol("theta")))
        substituted = substituted.subs(sympy.Symbol("theta"), f.generator)
        basis = sympy.groebner([f.factor, f.minpoly], X, Y, ALGEBRAIC, order="lex")
        assert basis.reduce(sympy.expand(substituted))[1] == 0


def test_curves_over_a_field_of_degree_four() -> None:
    K = number_field((2, 3))
    s, w = poly_ring(("s", "w"), K).gens
    r2, r3 = K.from_sympy(sympy.sqrt(2)), K.from_sympy(sympy.sqrt(3))
    elliptic, lines = analyze_curves([w**2 - (r2 + r3) * s**3 - 1, (s - r2) * (w - r3)])
    assert elliptic.genus == 1
    (factor,) = elliptic.factorization.factors
    assert factor.minpoly is None  # written over K itself
    S, W = sympy.symbols("s w")
    expected = S**3 - (sympy.sqrt(3) - sympy.sqrt(2)) * (W**2 - 1)
    assert sympy.simplify(factor.factor - expected) == 0
    assert lines.genus is None
    found = sorted(str(f.factor) for f in lines.factorization.factors)
    assert found == ["s - sqrt(2)", "w - sqrt(3)"]


def test_one_singular_run_analyses_several_curves(monkeypatch: pytest.MonkeyPatch) -> None:
    calls = []
    original = curves.run_script

    def counting(script: str, **kwargs: object) -> dict[str, list[str]]:
        calls.append(script)
        return original(script, **kwargs)

    monkeypatch.setattr(curves, "run_script", counting)
    p, p2 = analyze_curves([P, P2])
    assert len(calls) == 1
    assert (p.genus, p2.genus) == (1, 0)
    assert p.is_absolutely_irreducible and p2.is_absolutely_irreducible


def test_cancel_reaches_singular() -> None:
    cancel = threading.Event()
    cancel.set()
    with pytest.raises(Cancelled):
        analyze_curves([P, P2], cancel=cancel)


# --- parameterizations ------------------------------------------------------------------------


@pytest.fixture
def singular_forbidden(monkeypatch: pytest.MonkeyPatch) -> None:
    """Singular may not run in the test (a call fails it)."""

    def no_singular(*args: object, **kwargs: object) -> None:
        raise AssertionError("Singular must not run")

    monkeypatch.setattr(curves, "run_script", no_singular)


def check(F: Poly, para: curves.CurveParametrization) -> None:
    assert is_on_curve(F, para.x, para.y, para.parameter, para.generators)
    assert is_proper(F, para.x, para.y, para.parameter, para.generators)


def test_paper_parametrization_of_p_square_is_exact_and_proper() -> None:
    assert is_on_curve(P2, -(T**3) + T, T**4 + 4 * T**3 + 6 * T**2 + 4 * T + 5, T)
    assert is_proper(P2, -(T**3) + T, T**4 + 4 * T**3 + 6 * T**2 + 4 * T + 5, T)
    assert not is_on_curve(P2_AS_PRINTED, -(T**3) + T, T**4 + 4 * T**3 + 6 * T**2 + 4 * T + 5, T)


@pytest.mark.parametrize("known_genus_zero", [False, True])
def test_parametrize_p_square_with_singular(known_genus_zero: bool) -> None:
    para = parametrize(P2, known_genus_zero=known_genus_zero)
    assert para.method == "paraPlaneCurve" and para.field == "QQ" and para.is_real
    check(P2, para)


def test_paraplanecurve_alone_picks_the_gaussian_field_for_a_real_circle() -> None:
    """What docs/math.md §5 warns about: x² + y² = 3z² comes back over QQ(i)."""
    found = curves.run_script(
        "ring q = 0,(x,y,z),dp;\n"
        "def P = paraPlaneCurve(x^2+y^2-3*z^2); setring P; short = 0;\n"
        'sorguiEmit("minpoly", string(minpoly));'
    )
    assert found["minpoly"] == ["(a^2+1)"]


@pytest.mark.parametrize(
    "F",
    [
        x**2 + y**2 - 3,  # real points, no rational point: QQ(sqrt 3)
        x**2 + y**2 - 3 * x**2 * y**2,  # a quartic whose conic has no rational point
        x**2 - 3 * y**2 - 2,  # a hyperbola without rational points
    ],
)
def test_parametrization_is_real_when_the_curve_has_real_points(F: Poly) -> None:
    para = parametrize(F)
    assert para.is_real and para.generators
    check(F, para)


def test_circle_of_radius_sqrt3_is_parametrized_over_qq_sqrt3() -> None:
    para = parametrize(x**2 + y**2 - 3)
    assert para.generators == (sympy.sqrt(3),)


def test_curve_without_real_points_keeps_an_imaginary_field() -> None:
    para = parametrize(x**2 + y**2 + 3)
    assert not para.is_real
    check(x**2 + y**2 + 3, para)


@pytest.mark.parametrize(
    "F",
    [
        x**2 - y**3,  # cusp
        y**2 - x**3 - x**2,  # node
        x**2 + y**2 - 1,
        x**3 + y**3 - 3 * x * y,  # folium of Descartes
        (x**2 + y**2) ** 2 - 2 * (x**2 - y**2),  # lemniscate of Bernoulli
    ],
)
def test_rational_curves_over_qq(F: Poly) -> None:
    para = parametrize(F)
    assert para.field == "QQ"
    check(F, para)


TORUS_FOCAL = x**4 - 4 * x**3 - 2 * x**2 * y + 22 * x**2 + 4 * x * y - 36 * x + y**2 - 22 * y + 81
"""The plane model of the second focal conic of a torus (docs/math.md §9): paraPlaneCurve fails on
it ("Pn has odd dimension": its adjoint map is wrong at the tacnode at infinity)."""


def test_the_conic_route_parameterizes_what_paraplanecurve_fails_on() -> None:
    with pytest.raises(SingularError, match="odd dimension"):
        curves._para_plane_curve(TORUS_FOCAL, 60.0, None, True)
    para = parametrize(TORUS_FOCAL, known_genus_zero=True)
    assert para.method == "conic" and para.field == "QQ" and para.is_real
    check(TORUS_FOCAL, para)


@pytest.mark.parametrize(
    "F",
    [
        y**2 - 2 * x**2 - 7,  # a hyperbola whose point (1, 3) is found by the search
        (y - x**2) ** 2 - x**3,  # the discriminant 4x³ = (2x)²·x: a parabola w² = x
        x**2 * y**2 - (x**2 + 1) * (x - 2) ** 2,  # a(x)·y² = c(x), with a(x) not constant
    ],
)
def test_the_conic_route_without_singular(monkeypatch: pytest.MonkeyPatch, F: Poly) -> None:
    """With no Singular at all, a curve quadratic in one variable whose discriminant is a
    square times a polynomial of degree 1 or 2 is still parameterized, and checked."""

    def no_singular(*args: object, **kwargs: object) -> None:
        raise SingularNotFound("no Singular here")

    monkeypatch.setattr(curves, "run_script", no_singular)
    para = parametrize(F)
    assert para.method == "conic" and para.field == "QQ" and para.is_real
    check(F, para)


def test_large_coefficients_take_the_conic_route_before_singular(singular_forbidden: None) -> None:
    F = y**2 - (2**70 * x**2 + 3**45) * (x - 1) ** 2
    para = parametrize(F, known_genus_zero=True)
    assert para.method == "conic" and para.field == "QQ"
    check(F, para)


def test_a_large_conic_without_a_small_point_gets_one_from_legendres_equation(singular_forbidden: None) -> None:
    """The hyperbola ``y² − a·x² = y₀² − a·x₀²`` through ``(x₀, y₀)``, beyond the search of small
    points, with 45-bit coefficients: its point comes from Legendre's equation, not Singular."""

    a, x0, y0 = 35184372088891, 987654321, 123456789012345
    F = y**2 - a * x**2 - (y0**2 - a * x0**2)
    para = parametrize(F, known_genus_zero=True, prefer_conic=True)
    assert para.method == "conic" and para.field == "QQ" and para.is_real
    check(F, para)


NEAREST_TORUS_CONIC = 9007199254726754 * x**2 + 562949953421312 * y**2 - 5629499534380882 * y + 5066549580791807
"""``P²`` of the nearest exact surface of a rounded torus (the tests of rounded input), sheared to a
conic: it has no rational point, and paraPlaneCurve took 11 s to find a point over a quadratic
field of a 78-digit discriminant."""


def test_a_large_conic_without_rational_points_gets_a_real_point_over_a_quadratic_field(
    singular_forbidden: None,
) -> None:
    para = parametrize(NEAREST_TORUS_CONIC, known_genus_zero=True, prefer_conic=True)
    assert para.method == "conic" and para.field != "QQ" and para.is_real
    check(NEAREST_TORUS_CONIC, para)


NEAREST_TORUS_CONIC_LARGER = (
    274877906944346313476562500 * x**2
    + 17179869183999982820130816 * y**2
    - 171798691837916320800781250 * y
    + 154618822656000030517578125
)
"""The same for another rounded torus (seed 42 of ``benchmarks.rounded_tori``): its Legendre
coefficients have 254–258 bits, products of small primes and one prime of 103 bits, and the
quadratic field's root is that of a 42-digit number."""


def test_a_conic_of_larger_coefficients_without_rational_points_too(singular_forbidden: None) -> None:
    para = parametrize(NEAREST_TORUS_CONIC_LARGER, known_genus_zero=True, prefer_conic=True)
    assert para.method == "conic" and para.field != "QQ" and para.is_real
    # Checked on its fractions: sympy's conversion of the printed map into the field fails on the
    # root of a 42-digit number (its numerical field isomorphism), so `check` cannot read it back.
    assert para.fractions is not None
    (p1, q1), (p2, q2) = para.fractions
    assert curves._vanishes(NEAREST_TORUS_CONIC_LARGER, p1, q1, p2, q2)
    assert curves._proper_degree(NEAREST_TORUS_CONIC_LARGER, p1, q1, p2, q2)


def test_a_conic_whose_coefficients_are_not_factored_quickly_gets_a_real_point_over_a_quadratic_field(
    singular_forbidden: None,
) -> None:
    """``w² = a·u² + 3`` with ``a`` the product of two primes of 100 bits: whether it has a
    rational point is not known quickly, and Singular ran past its 10-s limit on such a conic
    (a rounded paraboloid's nearest surface); a real point over ``QQ(√3)`` parameterizes it."""
    a = int(sympy.nextprime(2**100)) * int(sympy.nextprime(2**101))
    F = y**2 - a * x**2 - 3
    para = parametrize(F, known_genus_zero=True, prefer_conic=True)
    assert para.method == "conic" and para.field == "QQ(sqrt(3))" and para.is_real
    check(F, para)


def test_a_large_conic_without_real_points_is_left_to_singular() -> None:
    """No rational point and no real one: the conic route declines (Singular finds the field)."""
    assert curves._conic(y**2 + 35184372088891 * x**2 + 98765432109877) is None


@pytest.mark.parametrize(
    "F",
    [
        x**2 + y**2 - 3,  # real points, none rational
        y**2 - x**3 + x,  # genus 1: the discriminant has degree 3
        (y + x) ** 2,  # a double line
        (x - 1) * (y**2 - x),  # a line splits off
    ],
)
def test_the_conic_route_declines(F: Poly) -> None:
    assert curves._conic(F) is None


def test_linear_in_y_takes_the_direct_route_without_singular(singular_forbidden: None) -> None:
    F = y - x**3 - 3 * x**2 + 2 * x
    para = parametrize(F)
    assert para.method == "direct" and para.coordinates == (T, T**3 + 3 * T**2 - 2 * T)
    check(F, para)
    G = x * (y**2 + 1) - y**3
    para = parametrize(G)
    assert para.method == "direct" and para.y == T
    check(G, para)


def test_direct_route_over_an_extension() -> None:
    F = u**2 * v - SQRT2 * u + 1
    para = parametrize(F)
    assert para.method == "direct" and para.field == "QQ(sqrt(2))"
    check(F, para)


def test_extension_without_direct_route_says_why() -> None:
    with pytest.raises(AnalysisError, match="ground field is not Q"):
        parametrize(u**2 + v**2 - SQRT2)


@pytest.mark.parametrize(
    ("F", "reason"),
    [
        (y**2 - x**5 - 1, "genus 2"),
        (P, "genus 1"),
        (x**2 - y**2, "not absolutely irreducible"),
        (x * y, "reducible"),
    ],
)
def test_parametrize_refuses_curves_without_one(F: Poly, reason: str) -> None:
    with pytest.raises(AnalysisError, match=reason):
        parametrize(F)


def test_improper_parametrization_is_detected() -> None:
    F = y - x**2
    assert is_on_curve(F, T**2, T**4, T)
    assert not is_proper(F, T**2, T**4, T)
    assert not is_on_curve(F, T, T**3, T)


# --- the degree-6 rational curve of paraPlaneCurve's documentation as P² ---------------------


@pytest.mark.parametrize(
    ("point", "direction"), [((0, 0, 0), (1, 0, 0)), ((1, -2, 3), (2, 1, 2)), ((0, 0, 0), (1, 1, 1))]
)
def test_profile_square_of_the_paraplanecurve_sextic_on_a_rational_axis(point, direction) -> None:
    """A surface of revolution whose ``P²`` is ``f2(s, w, 1)`` of the example of ``paraPlaneCurve``
    (paraplanecurves.lib: x⁶+3x⁴y²+3x²y⁴+y⁶-4x⁴z²-34x³yz²-7x²y²z²+12xy³z²+6y⁴z²+36x²z⁴+36xyz⁴+9y²z⁴,
    a rational sextic) about a rational axis: P² is parameterized properly and exactly."""
    from sorgui.engine.recognition.recognize import recognize
    from sorgui.samples import PARAPLANECURVE_SEXTIC, rational_vector, revolve

    coefficients = PARAPLANECURVE_SEXTIC
    f = revolve(coefficients, rational_vector(point), rational_vector(direction), axis_distance=True)
    _, _, profile = recognize(f)
    par = parametrize(profile.square, known_genus_zero=True)
    assert par.method == "paraPlaneCurve"
    assert is_on_curve(profile.square, par.x, par.y, par.parameter, par.generators)
    assert is_proper(profile.square, par.x, par.y, par.parameter, par.generators)


def test_a_reducible_minimal_polynomial_gives_both_rational_roots() -> None:
    a = sympy.Symbol("a")
    D, roots = curves._quadratic_roots(a**2 - 1, a)
    assert D == QQ and sorted(roots) == [QQ(-1), QQ(1)]
    D, roots = curves._quadratic_roots(2 * a**2 - 4, a)
    assert {D.to_sympy(r) for r in roots} == {sympy.sqrt(2), -sympy.sqrt(2)}


def test_a_sheared_position_parameterizes_what_paraplanecurve_gives_no_map_for(monkeypatch: pytest.MonkeyPatch) -> None:
    """When paraPlaneCurve's answer is no parameterization of the curve itself (a zero denominator
    at every root of its field), the curve is moved by a shear (x, y) ↦ (x + k·y, y + m), which
    is birational, parameterized there, and the map brought back and verified."""
    original = curves._para_plane_curve
    calls: list[Poly] = []

    def fails_on_the_curve_itself(F: Poly, timeout: float, cancel: object, checked: bool = False) -> list:
        calls.append(F)
        return [] if len(calls) == 1 else original(F, timeout, cancel, checked)

    monkeypatch.setattr(curves, "_para_plane_curve", fails_on_the_curve_itself)
    F = x**3 + y**3 - 3 * x * y  # the folium of Descartes, linear in neither variable
    par = parametrize(F)
    assert len(calls) == 2 and calls[1] != F
    assert is_on_curve(F, par.x, par.y, par.parameter, par.generators)
    assert is_proper(F, par.x, par.y, par.parameter, par.generators)


def test_no_position_gives_a_map_says_so(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(curves, "_para_plane_curve", lambda *_args: [])
    with pytest.raises(AnalysisError, match="paraPlaneCurve gave no parameterization of the curve"):
        parametrize(x**3 + y**3 - 3 * x * y)
