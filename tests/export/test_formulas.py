"""The named formulas and what each parameterization covers: domain, poles, missed points."""

from __future__ import annotations

from dataclasses import replace

import sympy

from sorgui.export.coverage import coverage
from sorgui.export.formulas import analysis_formulas

s, t, x, y, z = sympy.symbols("s t x y z")


def test_names_are_letters_and_digits_and_vectors_are_tuples(analyses) -> None:
    formulas = analysis_formulas(analyses["paper-example-1"])
    names = [f.name for f in formulas]
    assert all(name.isalnum() for name in names), names
    assert {"f", "axisPoint", "axisDirection", "p", "P2", "P2K", "P2param", "T", "tau", "X1"} <= set(names)
    by_name = {f.name: f for f in formulas}
    assert by_name["axisDirection"].value == (4, 3, 0)
    assert by_name["axisPoint"].value == (sympy.Rational(3, 5), sympy.Rational(-4, 5), 0)


def test_torus_parameterization_misses_two_circles(analyses) -> None:
    """X1 of the torus (its only map): poles only at complex parameters; as s → ∞ the meridian at angle π and as
    t → ∞ a circle of latitude are missed, both checked exactly to be reached by no parameter."""
    by_name = {f.name: f for f in analysis_formulas(analyses["torus"])}
    cov = by_name["X1"].coverage
    assert cov is not None and cov.real and cov.parameters == (s, t)
    assert {sympy.expand(e.factor) for e in cov.excluded} == {s**2 + 1, t**2 + 4}
    assert all(e.real_zeros is False for e in cov.excluded)
    at_s, at_t = cov.limits
    assert at_s.parameter == s and at_t.parameter == t
    expected = [(1 - s**2) / (s**2 + 1), 2 * s / (s**2 + 1), 0]
    assert all(sympy.simplify(c - e) == 0 for c, e in zip(at_t.point, expected))
    # the inner equator x² + y² = 1, z = 0 of the torus (x² + y² + z² + 3)² = 16(x² + y²)
    circle = [c for c in at_t.point]
    assert sympy.simplify(circle[0] ** 2 + circle[1] ** 2 - 1) == 0
    assert at_s.check == (sympy.Rational(7, 3), True) and at_t.check == (sympy.Rational(7, 3), True)
    assert cov.lines()[0] == "parameter domain: (s, t) in R^2"


def test_example_1_poles_and_points_at_infinity(analyses) -> None:
    cov = {f.name: f for f in analysis_formulas(analyses["paper-example-1"])}["X1"].coverage
    assert [sympy.expand(e.factor) for e in cov.excluded] == [s**2 + sympy.Rational(1, 25)]
    assert cov.limits[1].point is None  # t → ∞ runs off to infinity: nothing affine is missed
    assert cov.limits[0].point is not None and cov.limits[0].check[1] is True


def test_complex_parameterization_lists_its_complex_poles(analyses) -> None:
    cov = {f.name: f for f in analysis_formulas(analyses["paper-cubic"])}["X1"].coverage
    assert not cov.real
    assert cov.excluded[0].roots == (-sympy.I, sympy.I)
    assert "C^2" in cov.lines()[0]


def test_real_poles_are_listed_exactly() -> None:
    cov = coverage((1 / (t**2 - 2), t), (t,), True)
    assert cov.excluded[0].real_zeros is True
    assert set(cov.excluded[0].roots) == {sympy.sqrt(2), -sympy.sqrt(2)}
    assert cov.limits[0].point is None
    line = cov.lines()[1]
    assert "sqrt(2)" in line and "t**2 - 2 = 0" in line


def test_a_point_reached_again_is_not_called_missed() -> None:
    """x = s²/(s² + 1) reaches its limit 1 (as s → ∞) for no s, while x = s/(s² + 1) + t tends to
    t, which s = 0 reaches: the exact test tells the two apart."""
    missed = coverage((s**2 / (s**2 + 1), t, t), (s, t), True).limits[0]
    reached = coverage((s / (s**2 + 1) + t, t, t), (s, t), True).limits[0]
    assert missed.check[1] is True
    assert reached.check[1] is False


def test_a_curve_s_limit_point_that_a_finite_value_gives_is_not_called_missed() -> None:
    """The torus's second sphere family has the spine ``(0, 0, 4t/(t² − 1))``: it tends to the
    origin as t → ∞, and t = 0 gives the origin too (the files said "reached only as t → ∞, by
    no finite t"); the circle ``((1 − t²)/(1 + t²), 2t/(1 + t²))`` misses its limit ``(−1, 0)``;
    over the reals a point that only complex values give is missed."""
    spine = coverage((sympy.Integer(0), sympy.Integer(0), 4 * t / (t**2 - 1)), (t,), True)
    assert spine.limits[0].finite == (0,)
    assert (
        spine.lines()[-1]
        == "as t -> oo the map tends to the point (0, 0, 0), which t = 0 gives too: no point is missed there"
    )
    circle = coverage(((1 - t**2) / (1 + t**2), 2 * t / (1 + t**2)), (t,), True)
    assert circle.limits[0].finite == ()
    assert circle.lines()[-1].startswith("reached only as t -> oo, by no finite t: the point (-1, 0)")
    curve = ((t**3 + t**2 + 2) / (t**3 + 1), sympy.Integer(0))  # the limit 1 at t = ±i
    assert coverage(curve, (t,), real=True).limits[0].finite == ()
    assert set(coverage(curve, (t,), real=False).limits[0].finite) == {sympy.I, -sympy.I}
    algebraic = coverage((sympy.sqrt(2) * t / (t**2 + 1), t / (t**2 + 1)), (t,), True).limits[0]
    assert (
        algebraic.finite is None
        and "was not decided" in coverage((sympy.sqrt(2) * t / (t**2 + 1), t / (t**2 + 1)), (t,), True).lines()[-1]
    )


def test_the_exact_missed_point_test_is_for_maps_over_the_rationals() -> None:
    """Over an algebraic field its Gröbner basis took minutes (a rounded torus's nearest surface's
    complex map over QQ(√21, i), whose files were then not written in the time limit): the limit
    is stated, not checked."""
    algebraic = coverage((sympy.sqrt(2) * s**2 / (s**2 + 1), t, t), (s, t), True).limits[0]
    assert algebraic.point is not None and not algebraic.check


def test_a_denominator_positive_everywhere_in_two_parameters_has_no_real_zeros() -> None:
    """The stereographic map's ``s² + t² + 1``: defined on all of R², not "undefined on the real
    points of a curve of parameter values"."""
    s, t = sympy.symbols("s t")
    d = s**2 + t**2 + 1
    found = coverage((2 * s / d, 2 * t / d, (s**2 + t**2 - 1) / d), (s, t), real=True, limits=False)
    text = "\n".join(found.lines())
    assert "s**2 + t**2 + 1 = 0: no real zeros" in text and "curve of parameter values" not in text


def test_a_map_substitution_did_not_verify_says_so(analyses) -> None:
    """The catalogue lists every parameterization; one that substitution did not verify says so."""
    torus = analyses["torus"]
    unverified = replace(torus, parametrizations=(replace(torus.parametrizations[0], verified=False),))
    descriptions = {f.name: f.description for f in analysis_formulas(unverified)}
    assert descriptions["X1"].endswith(", NOT verified)")
    assert "NOT verified" not in {f.name: f.description for f in analysis_formulas(torus)}["X1"]
