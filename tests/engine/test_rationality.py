"""Rationality (docs/math.md §5–§6, the paper's Section 3 and Appendix Example 2), with real Singular."""

from __future__ import annotations

import dataclasses
import random

import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st
from sympy.polys.domains import QQ

from sorgui.engine.analysis import analyze, analyze_polynomial
from sorgui.engine.revolution.parametrization import Section
from sorgui.engine.revolution.rationality import table_row
from sorgui.engine.revolution.reparametrization import rescaling, same_sweep
from sorgui.examples import example_text
from sorgui.samples import PARAPLANECURVE_SEXTIC, move, quaternion_rotation, rational_vector, revolve

t, x, y = sympy.symbols("t x y")


def assert_parametrizations_verified(result) -> None:
    assert result.parametrizations
    for par in result.parametrizations:
        assert par.verified is True
        assert par.parameters == ("s", "t")


def test_table_rows() -> None:
    assert [
        table_row(True, None, 0),
        table_row(True, None, 2),
        table_row(False, 0, 0),
        table_row(False, 1, 0),
        table_row(False, 1, 1),
    ] == [1, 2, 3, 4, 5]


def test_paper_example_2(paper_example_1) -> None:
    result = analyze_polynomial(paper_example_1)
    rat = result.rationality
    assert (rat.genus_profile, rat.genus_profile_square, rat.table_row) == (1, 0, 4)
    assert rat.profile_reducible is False and rat.complex_rational is True
    # docs/math.md §1: P² has the constant -400 (the paper prints +400).
    corrected = -400 - 104 * x**2 - x**4 + 200 * y - 48 * x * y + 26 * x**2 * y - 29 * y**2 + 12 * x * y**2 + y**3
    square = sympy.S(result.recognition.profile.square)
    assert sympy.expand(square - corrected) == 0 or sympy.expand(square - corrected.subs(x, -x)) == 0
    # The paper's (-t³+t, t⁴+4t³+6t²+4t+5) lies on it.
    assert sympy.expand(corrected.subs({x: -(t**3) + t, y: t**4 + 4 * t**3 + 6 * t**2 + 4 * t + 5})) == 0
    # The tubular surface is the paper's y² + z² = (t+1)⁴ + 4, up to a shift of the parameter.
    h = sympy.Poly(sympy.S(rat.h), t)
    paper_h = t**4 + 4 * t**3 + 6 * t**2 + 4 * t + 5
    shift = (h.coeff_monomial(t**3) - 4) / 4
    assert h.degree() == 4 and sympy.expand(paper_h.subs(t, t + shift) - h.as_expr()) == 0
    assert rat.real_roots_of_h == 0 and rat.unirational is True and rat.real_rational is True
    real = [p for p in result.parametrizations if p.real]
    assert real and all(p.verified for p in real)
    assert any(p.proper for p in real)


def test_paper_example_finishes_quickly_enough_for_the_gui(paper_example_1) -> None:
    result = analyze_polynomial(paper_example_1)
    # A loose guard only: the speed goal itself is measured in benchmarks/analysis.py.
    assert sum(seconds for _, seconds in result.timings) < 20


def test_paper_cubic_is_unirational_not_rational() -> None:
    result = analyze("y^2 + z^2 = x^3 + 3x^2 - 2x")
    rat = result.rationality
    assert (rat.table_row, rat.real_roots_of_h) == (4, 3)
    assert rat.unirational is True and rat.real_rational is False
    assert_parametrizations_verified(result)


def test_cone_has_a_reducible_profile() -> None:
    result = analyze("y^2 - 2xz")
    rat = result.rationality
    assert rat.profile_reducible is True and rat.table_row == 1 and rat.genus_profile is None
    assert rat.real_rational is True
    assert_parametrizations_verified(result)
    assert any(p.method == "rotated profile" and p.real for p in result.parametrizations)


@pytest.mark.parametrize(
    ("text", "after"),
    [
        ("(x^2 + y^2 + z^2 + 3)^2 - 16(x^2 + y^2)", " with t ↦ 1/4·t"),
        ("(x - 1)^2 + (y - 2)^2 - 4", ""),
        ("x^2 + y^2 - z^2", ""),
        ("(x^2 + y^2 + z^2 - 5/4)^2 - 4(x^2 + y^2)", " with s ↦ -1/s, t ↦ t/8"),
        ("y^2 - 2xz", " with s ↦ (2*s - sqrt(2))/(2*sqrt(2)*s + 2)"),
    ],
)
def test_the_same_map_is_listed_once(text: str, after: str) -> None:
    """The map through T that is the rotated profile's again (up to ``t ↦ k·t``, or a Möbius map
    of ``t`` and a turn about the axis: the spindle torus's half turn, the cone's turn over
    ``QQ(√2)``) is not listed a second time; the rotated profile's map is then proper, and a note
    says why (docs/math.md §6)."""
    result = analyze(text)
    assert [(p.method, p.real, p.proper) for p in result.parametrizations] == [("rotated profile", True, True)]
    assert (
        f"the map through T is the rotated profile's{after}: listed once, and proper as it is"
        in result.rationality.notes
    )
    assert_parametrizations_verified(result)


def test_a_rescaling_of_the_parameter_is_found_exactly() -> None:
    """``second(t) = first(k·t)``: ``k`` rational or a square root, ``None`` for another section."""
    phi, rho = sympy.sqrt(2) * t / (t**2 + 3), (t**2 - 1) / (t**2 + 3)
    first = Section(phi, rho, sympy.Integer(0))
    for k in (sympy.Rational(1, 4), sympy.sqrt(3), -1):
        assert rescaling(first, Section(phi.subs(t, k * t), rho.subs(t, k * t), sympy.Integer(0))) == k
    assert rescaling(first, Section(phi, rho + 1, sympy.Integer(0))) is None
    assert rescaling(first, Section(rho, phi, sympy.Integer(0))) is None
    line = Section(t, 2 * t, sympy.Integer(0))  # monomials: a cone's generator
    assert rescaling(line, Section(-3 * t, -6 * t, sympy.Integer(0))) == -3
    assert rescaling(line, Section(3 * t, 5 * t, sympy.Integer(0))) is None
    assert rescaling(
        Section(1 / t, t**2, sympy.Integer(0)), Section(2 / t, t**2 / 4, sympy.Integer(0))
    ) == sympy.Rational(1, 2)


@pytest.mark.parametrize("turn", [sympy.Integer(0), sympy.Rational(1, 2), sympy.oo])
@pytest.mark.parametrize("n", [sympy.Integer(1), sympy.Integer(3)])
def test_a_moebius_map_and_a_turn_are_found_exactly(turn: sympy.Expr, n: sympy.Expr) -> None:
    """``second(t) = R(σ₀)·first(ψ(t))``: the reparametrization found makes the two sweeps one
    map, checked by substituting it into the sweep (docs/math.md §6)."""
    s = sympy.Symbol("s")
    phi, rho = (t**2 + 1) / (t**2 - 2 * t + 3), (2 * t - 1) / (t**2 - 2 * t + 3)
    first = Section(phi, rho, sympy.Integer(0))
    psi = (2 * t + 1) / (t - 3)
    t1, t2 = (-1, 0) if turn is sympy.oo else ((1 - n * turn**2) / (1 + n * turn**2), 2 * turn / (1 + n * turn**2))
    u, w = rho.subs(t, psi), sympy.Integer(0)
    second = Section(phi.subs(t, psi), t1 * u - n * t2 * w, t2 * u + t1 * w)
    found = same_sweep(first, second, n)
    assert found is not None and sympy.cancel(found.t_image - psi) == 0

    def swept(section: Section, sigma: sympy.Expr) -> list[sympy.Expr]:
        cos, sin = (1 - n * sigma**2) / (1 + n * sigma**2), 2 * sigma / (1 + n * sigma**2)
        return [section.phi, section.rho_u * cos - n * sin * section.rho_w, section.rho_u * sin + cos * section.rho_w]

    moved = [c.subs({s: found.s_image, t: found.t_image}, simultaneous=True) for c in swept(first, s)]
    assert all(sympy.cancel(a - b) == 0 for a, b in zip(moved, swept(second, s)))
    assert same_sweep(first, Section(phi.subs(t, psi), rho.subs(t, psi) + 1, sympy.Integer(0)), n) is None
    assert same_sweep(first, Section(rho, phi, sympy.Integer(0)), n) is None


def squarefree_polynomial(rng: random.Random, degree: int) -> sympy.Expr:
    """A random square-free polynomial in ``t`` of the given degree with small coefficients."""
    while True:
        g = sum(rng.randint(-4, 4) * t**k for k in range(degree)) + rng.choice([1, -1, 2]) * t**degree
        if sympy.degree(sympy.gcd(g, sympy.diff(g, t)), t) == 0:
            return g


def general_position(profile: dict[tuple[int, int], int], seed: int):
    """``F(s, w)`` (``w`` the squared distance to the axis) on a rational axis, rotated."""
    rng = random.Random(seed)
    c = rational_vector([QQ(rng.randint(-3, 3), rng.randint(1, 3)) for _ in range(3)])
    a = rational_vector([rng.randint(1, 3), rng.randint(-2, 2), rng.randint(-2, 2)])
    q = [rng.randint(-2, 2) for _ in range(3)] + [1]
    f = revolve(profile, c, a, axis_distance=True)
    return move(f, quaternion_rotation(q), rational_vector((1, -1, QQ(1, 2))))


def on_x_axis(profile: dict[tuple[int, int], int]):
    """``F(x, y² + z²)``."""
    return revolve(profile, rational_vector((0, 0, 0)), rational_vector((1, 0, 0)), axis_distance=True)


@pytest.mark.parametrize("degree", [3, 4, 5, 6])
@pytest.mark.parametrize("placed", ["axis", "general"])
def test_tube_over_a_polynomial(degree: int, placed: str) -> None:
    """``y² + z² = g(x)``: P² is rational, P is hyperelliptic of genus ⌊(deg g - 1)/2⌋."""
    g = sympy.Poly(squarefree_polynomial(random.Random(degree), degree), t)
    profile = {(0, 1): 1} | {(k, 0): -int(c) for (k,), c in g.terms()}
    f = on_x_axis(profile) if placed == "axis" else general_position(profile, degree)
    rat = analyze_polynomial(f).rationality
    assert rat.genus_profile == (degree - 1) // 2
    assert rat.genus_profile_square == 0
    assert rat.table_row == (3 if degree <= 2 else 4)
    assert rat.complex_rational is True


@pytest.mark.parametrize("degree", [3, 4, 5, 6])
@pytest.mark.parametrize("placed", ["axis", "general"])
def test_squared_tube_over_a_polynomial(degree: int, placed: str) -> None:
    """``(y² + z²)² = g(x)``: P² is hyperelliptic of genus ⌊(deg g - 1)/2⌋."""
    g = sympy.Poly(squarefree_polynomial(random.Random(10 + degree), degree), t)
    profile = {(0, 2): 1} | {(k, 0): -int(c) for (k,), c in g.terms()}
    f = on_x_axis(profile) if placed == "axis" else general_position(profile, degree)
    rat = analyze_polynomial(f).rationality
    expected = (degree - 1) // 2
    assert rat.genus_profile_square == expected
    if expected > 0:
        assert rat.table_row == 5 and rat.complex_rational is False and rat.unirational is False


def test_general_position_parametrization_is_verified_in_original_coordinates() -> None:
    f = general_position({(0, 1): 1, (2, 0): -1, (0, 0): -1}, seed=3)  # a hyperboloid
    result = analyze_polynomial(f)
    assert result.rationality.table_row == 3
    assert_parametrizations_verified(result)
    assert any(p.real for p in result.parametrizations)


def test_algebraic_coefficients_say_what_is_undecidable() -> None:
    result = analyze("y^2 + z^2 - sqrt(2) x^3 - 1")
    rat = result.rationality
    assert result.field == "QQ(sqrt(2))"
    assert rat.genus_profile == 1 and rat.genus_profile_square == 0 and rat.table_row == 4
    assert_parametrizations_verified(result)


def test_reducible_surface_is_not_analysed_as_a_whole() -> None:
    result = analyze("(x^2 + y^2 + z^2 - 1)(x^2 + y^2 - 4)")
    assert result.recognition.symmetry == "revolution"
    assert result.rationality.status.startswith("not analysed")
    assert len(result.factors) == 2


def test_json_round_trip() -> None:
    from sorgui.engine.results import Analysis

    result = analyze("y^2 - 2xz")
    again = Analysis.from_json(result.to_json())
    assert again == result


def test_high_degree_parametrization_is_verified_in_the_axis_frame() -> None:
    profile = {(0, 1): 1, (6, 1): 1, (8, 0): -1, (3, 0): 2, (0, 0): -5}
    result = analyze_polynomial(general_position(profile, seed=8))
    assert result.recognition.degree == 8 and result.rationality.genus_profile_square == 0
    assert_parametrizations_verified(result)
    assert {p.verification for p in result.parametrizations} == {"substituted into f in the axis frame"}


@pytest.mark.parametrize("in_frame", [True, False])
def test_a_wrong_parametrization_is_never_reported(monkeypatch, in_frame: bool) -> None:
    """The numerical screen and both exact checks (into f in the axis frame through the section,
    and into f itself) accept a section on the surface and reject one that is off it."""
    from sorgui.engine.recognition.recognize import recognize
    from sorgui.engine.revolution import parametrization as pm

    f = on_x_axis({(0, 1): 1, (2, 0): -1, (0, 0): -1})  # y² + z² = x² + 1
    _, _, profile = recognize(f)
    zero = sympy.Integer(0)
    good = pm.Section(phi=(t**2 - 1) / (2 * t), rho_u=(t**2 + 1) / (2 * t), rho_w=zero)
    wrong = pm.Section(phi=(t**2 - 1) / (2 * t), rho_u=(t**2 + 2) / (2 * t), rho_w=zero)
    good_map, wrong_map = (pm.sweep(section, profile.frame, QQ) for section in (good, wrong))
    assert pm.numerically_vanishes(f, good_map) and not pm.numerically_vanishes(f, wrong_map)
    assert pm.section_vanishes(profile, good) and not pm.section_vanishes(profile, wrong)
    assert pm.vanishes_on(f, good_map) and not pm.vanishes_on(f, wrong_map)
    monkeypatch.setattr(pm, "numerically_vanishes", lambda *_: True)  # the exact check alone
    if not in_frame:  # make_parametrization substitutes into f itself
        profile = dataclasses.replace(profile, verified=False)
    for section, surface, expected in ((good, good_map, True), (wrong, wrong_map, False)):
        found = pm.make_parametrization(
            f, profile, surface, lambda s=section: pm.section_vanishes(profile, s), method="test", proper=None
        )
        assert (found is not None) == expected
        if found is not None:
            assert found.verified and found.real
            assert found.verification == ("substituted into f in the axis frame" if in_frame else "substituted into f")


@pytest.mark.parametrize(
    ("equation", "row", "field"),
    [
        ("y^2 + z^2 = x^2 - 1", 3, "QQ"),
        ("y^2 + z^2 = (x^2 + 1)(x^2 - 2)", 4, "QQ(sqrt(2))"),
    ],
)
def test_sign_changing_h_gets_a_real_proper_parametrization(equation: str, row: int, field: str) -> None:
    """h = N·u²·q with deg q ≤ 2: the quadric is projected from a real point (docs/math.md §6)."""
    result = analyze(equation)
    assert result.rationality.table_row == row and result.rationality.real_rational is True
    stereographic = [p for p in result.parametrizations if "stereographic" in p.method]
    assert len(stereographic) == 1
    par = stereographic[0]
    assert par.verified and par.real and par.proper is True and par.field == field


def test_quadric_section_of_a_rational_root() -> None:
    from sorgui.engine.revolution.parametrization import quadric_section

    x, Y, Z = quadric_section(t**2 - 1, sympy.Integer(1))
    assert sympy.simplify(Y**2 + Z**2 - (x**2 - 1)) == 0


@given(st.integers(-30, 30).filter(bool), st.integers(-30, 30), st.integers(-30, 30), st.integers(1, 9))
@settings(max_examples=60, deadline=None)
def test_the_real_roots_of_a_quadric_section_are_sympys(a: int, b: int, c: int, over: int) -> None:
    """The closed form of a quadratic's real roots (no isolation: sympy refined the roots of
    ``t² − c`` for a 5000-digit ``c`` for seconds) gives sympy's roots, in its order."""
    from sorgui.engine.revolution.parametrization import _real_roots

    q = sympy.Poly(sympy.Rational(a, over) * t**2 + b * t + c, t)
    ours = _real_roots(q)
    assert len(ours) == len(set(q.real_roots()))
    assert all(sympy.expand(q.as_expr().subs(t, r)) == 0 for r in ours)
    assert sorted(ours, key=float) == ours


def test_a_sphere_of_a_1500_digit_radius_squared_gets_its_maps() -> None:
    """A hostile constant: ``x² + y² + z² = c`` with ``c`` of 1500 digits, not a square. sympy
    tests the cofactor of each radicand for primality (flint does it, not sympy's pure Python:
    :func:`sorgui.engine.algebra.sympy_fixes.probable_prime`); the maps are over ``QQ(√c)``."""
    rng = random.Random(5)
    c = rng.randrange(10**1499, 10**1500)
    analysis = analyze(f"x^2 + y^2 + z^2 - {c}")
    assert analysis.rationality is not None and analysis.rationality.table_row == 3
    proper = [p for p in analysis.parametrizations if p.real and p.proper and p.verified]
    assert proper and all(str(c)[:40] in p.field for p in proper)


def test_a_time_limit_ends_in_an_undecided_result() -> None:
    result = analyze(example_text("paper-example-1"), singular_timeout=0.001)
    assert result.recognition.is_sor and result.rationality.status.startswith("undecided within the time limit")
    assert result.rationality.table_row is None and result.parametrizations == ()


def test_missing_singular_is_reported_not_raised(monkeypatch) -> None:
    from sorgui.engine.singular.process import ENV_VARIABLE

    monkeypatch.setenv(ENV_VARIABLE, "/nonexistent/Singular")
    result = analyze("y^2 + z^2 = x^3 + 3x^2 - 2x")
    assert result.recognition.is_sor
    assert result.rationality.status.startswith("undecided") and ENV_VARIABLE in result.rationality.status


def test_complex_plane_pair_is_not_analysed() -> None:
    """x² + y² = 0 has P² = w: two complex planes through the axis (docs/math.md §4)."""
    result = analyze("x^2 + y^2")
    assert result.recognition.symmetry == "cylinder_of_revolution"
    assert result.rationality.status.startswith("not applicable") and result.parametrizations == ()


def test_real_parametrization_over_an_algebraic_field_of_definition() -> None:
    """An ellipsoid of revolution whose axis needs sqrt(2): the real proper parameterization
    through T lives in a real field containing K."""
    result = analyze("(x + sqrt(2)y)^2 + x^2 + y^2 + z^2 - 1")
    assert result.field == "QQ(sqrt(2))" and result.rationality.table_row == 3
    proper_real = [p for p in result.parametrizations if p.real and p.proper]
    assert proper_real and all(p.verified for p in proper_real)


def test_the_paraplanecurve_sextic_with_its_roles_swapped_is_parameterized() -> None:
    """``P²(s, w) = f2(w, s, 1)`` of paraPlaneCurve's example: Singular parameterizes it over
    ``QQ(sqrt(-5))``, whose elements sympy prints with ``I`` and ``sqrt(5)`` apart (once an internal
    error); X_C is rational and gets its complex parameterization, verified."""
    coefficients = PARAPLANECURVE_SEXTIC
    swapped = {(j, i): c for (i, j), c in coefficients.items()}
    result = analyze_polynomial(
        revolve(swapped, rational_vector((0, 0, 0)), rational_vector((1, 0, 0)), axis_distance=True)
    )
    rationality = result.rationality
    assert rationality.table_row == 4 and rationality.complex_rational and rationality.real_rational is False
    assert "QQ(sqrt(-5))" in " ".join(rationality.notes)
    (par,) = result.parametrizations
    assert par.verified and not par.real and par.method == "via tubular surface (complex)"
    assert par.field.count("sqrt(-1)") <= 1


def test_a_profile_in_nested_roots_is_explained_in_words() -> None:
    """Two coaxial cylinders joined by a potential blend: the profile's components are lines
    ``r = √((5 ± √13)/2)``, in nested roots, which no field of sorgui's holds."""
    result = analyze("(x^2+y^2-1)*(x^2+y^2-4)-1")
    notes = " ".join(result.rationality.notes)
    assert "nested or higher roots" in notes and "Error" not in notes and "_rho" not in notes


def test_a_norm_equation_of_large_numbers_is_solved_by_legendres_equation() -> None:
    """``X² + n·Y² = c`` for numbers beyond 32 bits comes from Legendre's equation with quick
    factorizations; sympy's ``diop_ternary_quadratic`` ran ECM for minutes on those of a rounded
    hyperboloid's nearest surface. Numbers that cannot be factored quickly give ``None``."""
    from sorgui.engine.revolution.parametrization import _rational_norm

    c = sympy.Integer(2**61 - 1) * 5 * 13  # a Mersenne prime ≡ 3 mod 4, times two primes ≡ 1 mod 4
    found = _rational_norm(c, sympy.Integer(2**61 - 1))
    assert found is not None and found[0] ** 2 + (2**61 - 1) * found[1] ** 2 == c
    hard = sympy.Integer(sympy.nextprime(2**200)) * sympy.nextprime(2**201)
    assert _rational_norm(hard, sympy.Integer(3)) is None


def test_an_integer_out_of_reach_leaves_the_rationality_undecided(monkeypatch: pytest.MonkeyPatch) -> None:
    """A radicand that flint cannot factor quickly (:class:`OutOfReach`) ends the stage with an
    honest status, not with the whole analysis: undecided in the profile's analysis, partly
    undecided when only the real roots of ``h`` need it."""
    from sorgui.engine.errors import OutOfReach
    from sorgui.engine.revolution import rationality

    def out_of_reach(*args: object, **kwargs: object) -> None:
        raise OutOfReach("the square-free part of an integer of 400 digits is needed, not factored quickly")

    monkeypatch.setattr(rationality, "count_real_roots_of", out_of_reach)
    partly = analyze(example_text("paper-example-1")).rationality
    assert partly.status == "partly undecided" and partly.table_row == 4
    assert any("400 digits" in note for note in partly.notes)
    monkeypatch.setattr(rationality.profile_pair, "analyze_profile_pair", out_of_reach)
    undecided = analyze(example_text("paper-example-1"))
    assert undecided.recognition.is_sor and undecided.rationality.status.startswith("undecided: ")


@pytest.mark.parametrize(
    ("text", "field"),
    [
        ("x^2 + y^2 + z^2 - 2x - 3", "QQ"),
        ("x^2 + y^2 + z^2 - 2", "QQ(sqrt(2))"),
        ("x^2 + y^2 + z^2 - 7", "QQ(sqrt(7))"),
        ("(x^2 + y^2 + z^2 - 2x - 3)^2", "QQ"),  # a power: its zero set is the sphere's
    ],
)
def test_a_sphere_gets_its_table_1_row_and_a_proper_real_parameterization(text: str, field: str) -> None:
    """Every line through a sphere's centre is an axis: Table 1 is read about the one along z
    (a circle: row 3), and the stereographic map of the tubular surface is proper and real: over
    QQ for radius 2; over QQ(√2) for radius² 2 (the map found is not the one from the sphere's
    rational point (1, 1, 0)); over QQ(√7) for radius² 7, which is no sum of three rational
    squares."""
    analysis = analyze(text)
    assert analysis.recognition.symmetry == "sphere" and analysis.recognition.profile is not None
    assert analysis.rationality is not None and analysis.rationality.table_row == 3
    assert any("every line through its centre is an axis" in note for note in analysis.rationality.notes)
    proper = [p for p in analysis.parametrizations if p.real and p.proper and p.verified]
    assert proper and proper[0].field == field


@pytest.mark.parametrize(
    ("text", "field"),
    [("x + 2y - 3z - 1", "QQ"), ("z", "QQ"), ("x + sqrt(2) y - 1", "QQ(sqrt(2))"), ("(x + 2y - 3z - 1)^3", "QQ")],
)
def test_a_plane_gets_its_table_1_row_and_its_affine_map_first(text: str, field: str) -> None:
    """Every normal line of a plane is an axis: Table 1 is read about the one through its point
    nearest the origin (a line: row 3), and its first map is the affine one, proper and onto; a
    saved report of it passes the claims' checks (its profile's frame is a point of the plane and
    its normal)."""
    from sorgui.engine.claims.report import check_report

    analysis = analyze(text)
    assert analysis.recognition.symmetry == "plane" and analysis.recognition.profile is not None
    assert analysis.rationality is not None and analysis.rationality.table_row == 3
    assert any("every line along its normal is an axis" in note for note in analysis.rationality.notes)
    first = analysis.parametrizations[0]
    assert first.method == "affine map of the plane" and first.verified and first.proper and first.field == field
    assert all(p.verified for p in analysis.parametrizations)
    check_report(analysis)


def test_a_surface_without_real_points_is_told_apart_from_the_real_column_of_table_1() -> None:
    """``x² + y² + 1``: row 1 (its profile splits over C), whose real column says "rational";
    the report says the column assumes real points, and why no rotated profile was made (its
    two components are complex conjugates, not "nested or higher roots")."""
    from sorgui.export.text import text_report

    analysis = analyze("x^2 + y^2 + 1")
    assert analysis.rationality.table_row == 1 and analysis.rationality.real_rational is False
    assert any("its components are complex conjugates" in note for note in analysis.rationality.notes)
    assert "the table's real column is for a surface with real points" in text_report(analysis)
