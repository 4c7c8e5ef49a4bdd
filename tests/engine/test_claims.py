"""A report's claims checked against its own polynomial (sorgui.engine.claims): every genuine
report passes, every claim changed to a lie is refused naming its field (real analyses, real
Singular)."""

from __future__ import annotations

import dataclasses
import json
from fractions import Fraction
from typing import Any

import pytest
import sympy

from sorgui.engine import analyze
from sorgui.engine.algebra.modular import Point, coprime_basis, embedding
from sorgui.engine.claims.formulas import formula
from sorgui.engine.claims.report import check_report
from sorgui.engine.errors import ClaimError
from sorgui.engine.results import Analysis
from sorgui.examples import example_text
from sorgui.samples import printed_exact, rational_sor

SURFACES = {
    "torus": example_text("torus"),
    "cone over Q(sqrt 2)": example_text("cone"),
    "paper cubic (a complex map)": example_text("paper-cubic"),
    "Dupin cyclide": example_text("dupin-cyclide"),
    "rolling-ball blend": example_text("rolling-ball-blend"),
    "pipe around a twisted cubic": example_text("pipe-twisted-cubic"),
    "sphere": "x^2 + y^2 + z^2 - 2x - 3",
    "plane": "3x - 4y + z - 7",
    "cylinder of revolution": "x^2 + y^2 - 1",
    "extrusion": "x^3 + y^3 - 1",
    "cone of degree 3": "x^3 + y^3 - z^3",
    "over Q(sqrt 5)": "x^2 + y^2 - sqrt(5) z^2 - 1",
    "reducible": "(x^2 + y^2 + z^2 - 1)(x^2 + y^2 - 4)",
    "a square": "(x^2 + y^2 - z)^2",
    "a point": "x^2 + y^2 + z^2",
    "rounded, nearly a sphere": "1.000000001x^2 + y^2 + z^2 - 1",
    "rounded about a rational axis": printed_exact(
        rational_sor(
            (1, 2, 2, 0),
            (Fraction(1), Fraction(-1, 2), Fraction(2)),
            {(2, 0): Fraction(1), (0, 1): Fraction(1), (0, 0): Fraction(-3)},
        ),
        9,
    ),
    "rounded cone printed with 17 digits (a residual over 1)": (
        "(1)*x^2 + (-7)*x + (0.66000000000000014)*y^2 + (1.1777945491468365)*y*z + (-6.5945618440278562)*y"
        " + (-0.020000000000000073)*z^2 + (1.7522431864335473)*z + (1.9955476949651754)"
    ),
    "torus about the axis (2, -2, 1) (its circles need the root of 5)": (
        "x^4 - 4*x^3 + 2*x^2*y^2 + 8*x^2*y + 2*x^2*z^2 - 2*x^2*z + 100*x^2/9 - 4*x*y^2 - 344*x*y/9 - 4*x*z^2"
        " + 136*x*z/9 - 578*x/9 + y^4 + 8*y^3 + 2*y^2*z^2 - 2*y^2*z + 208*y^2/9 + 8*y*z^2 - 172*y*z/9 + 506*y/9"
        " + z^4 - 2*z^3 - 2*z^2/9 - 289*z/9 + 3469/36"
    ),
}


@pytest.fixture(scope="module")
def reports() -> dict[str, Analysis]:
    """Each surface's analysis as a report reads it back (through its JSON)."""
    return {
        name: Analysis.from_json(json.loads(json.dumps(analyze(text).to_json()))) for name, text in SURFACES.items()
    }


@pytest.mark.parametrize("name", list(SURFACES))
def test_every_genuine_report_passes(reports: dict[str, Analysis], name: str) -> None:
    check_report(reports[name])


def tampered(analysis: Analysis, path: tuple[Any, ...], value: Any) -> Analysis:  # noqa: ANN401
    """``analysis`` with the JSON value at ``path`` replaced by ``value``."""
    data = json.loads(json.dumps(analysis.to_json()))
    target = data
    for step in path[:-1]:
        target = target[step]
    target[path[-1]] = value
    return Analysis.from_json(data)


LIES = [
    ("torus", ("input",), "x^3+y^3+z^3-1", "polynomial"),
    ("torus", ("polynomial",), "x**4 + y**4 + z**4 - 1", "polynomial"),
    ("torus", ("symmetry",), "sphere", "symmetry"),
    ("torus", ("axis", "point"), ["1", "0", "0"], "axis.point"),
    ("torus", ("axis", "direction"), ["0", "1", "1"], "axis.direction"),
    ("torus", ("axis", "plucker"), ["0", "0", "1", "1", "0", "0"], "axis.plucker"),
    ("torus", ("symmetry_basis", 0), ["0", "0", "1", "1", "0", "0"], "symmetry_basis"),
    ("torus", ("profile", "frame_point"), ["0", "1", "0"], "profile.frame_point"),
    ("torus", ("profile", "frame_normal"), ["1", "0", "1"], "profile.frame_normal"),
    ("torus", ("profile", "frame_direction"), ["0", "0", "0"], "profile.frame_direction"),
    ("torus", ("profile", "rational"), "s**4 + 2*s**2*r**2 + r**4 + 6*s**2 - 10*r**2 + 8", "profile.rational"),
    ("torus", ("profile", "rational_square"), "s**4 + w**2 - 1", "profile.rational_square"),
    ("torus", ("profile", "polynomial"), "x**4 + y**4 - 1", "profile.polynomial"),
    ("torus", ("profile", "square"), "x**2 + y - 1", "profile.square"),
    ("torus", ("squarefree",), "x**2 + y**2 + z**2 - 1", "squarefree"),
    ("torus", ("factors", 0, "polynomial"), "x**2 + y**2 + z**2 - 1", "factors"),
    ("torus", ("parametrizations", 0, "coordinates", 0), "s", "parametrizations[0]"),
    ("torus", ("parametrizations", 0, "coordinates"), ["1", "0", "0"], "parametrizations[0]"),
    ("torus", ("rationality", "table_row"), 3, "rationality.table_row"),
    ("torus", ("rationality", "square_parametrization", 0), "t", "rationality.square_parametrization"),
    ("torus", ("rationality", "h"), "t", "rationality"),
    ("torus", ("rationality", "tau", 1), "y", "rationality.tau"),
    ("torus", ("rationality", "real_roots_of_h"), 2, "rationality.real_roots_of_h"),
    ("torus", ("rationality", "absolute_factors", 0), "r**2 - 3*r + s**2 + 3", "rationality.absolute_factors"),
    ("torus", ("canal", "families", 0, "parametrization", 2), "1", "canal.families[0].parametrization"),
    ("torus", ("canal", "families", 0, "circle_radius_squared"), "2", "canal.families[0].circle_center"),
    ("torus", ("canal", "families", 1, "pipe"), True, "canal.families[1].pipe"),
    ("Dupin cyclide", ("canal", "kinds"), ["dupin", "revolution"], "canal.kinds"),
    ("sphere", ("center",), ["10**300", "0", "0"], "center"),
    ("sphere", ("radius_squared",), "10**400", "radius_squared"),
    ("plane", ("normal",), ["10**400", "0", "1"], "normal"),
    ("cylinder of revolution", ("direction",), ["0", "0", "1"], "direction"),
    ("extrusion", ("direction",), ["1", "0", "0"], "direction"),
    ("cone over Q(sqrt 2)", ("field",), "QQ(sqrt(2))", "field"),
    ("cone over Q(sqrt 2)", ("conical", "apex"), ["1", "0", "0"], "conical.apex"),
    ("cone of degree 3", ("conical", "base_curve", "polynomial"), "x**3 + y**3 - 2", "conical.base_curve"),
    ("extrusion", ("conical", "direction"), ["0", "1", "0"], "conical"),
    ("Dupin cyclide", ("canal", "parametrizations", 0, "coordinates", 2), "0", "canal.parametrizations[0]"),
    ("Dupin cyclide", ("canal", "witness"), None, None),
    (
        "rounded about a rational axis",
        ("approximate", "nearest", "polynomial"),
        "x**2 + y**2 - 1",
        "approximate.nearest",
    ),
    ("rounded about a rational axis", ("approximate", "nearest", "axis", "point"), ["7", "7", "7"], "approximate"),
    ("torus", ("parametrizations", 0, "real"), False, "parametrizations[0].real"),
    ("torus", ("unfinished",), ["rationality"], "unfinished"),
    ("torus", ("unfinished",), ["parametrizations"], "unfinished"),
    ("rounded about a rational axis", ("approximate", "tolerance"), -0.5, "approximate.tolerance"),
    ("rounded about a rational axis", ("approximate", "residual"), 7.0, "approximate.near_sor"),
    ("rounded about a rational axis", ("approximate", "kind"), "none", "approximate.near_sor"),
    ("rounded about a rational axis", ("approximate", "axis", "direction"), [0.0, 0.0, 0.0], "approximate.axis"),
    ("sphere", ("profile", "frame_point"), ["0", "0", "0"], "profile.frame_point"),
    (
        "rounded about a rational axis",
        ("approximate", "nearest", "max_deviation"),
        1e-30,
        "approximate.nearest.max_deviation",
    ),
    (
        "rounded about a rational axis",
        ("approximate", "nearest", "relative_distance"),
        1e-30,
        "approximate.nearest.relative_distance",
    ),
    (
        "rounded about a rational axis",
        ("approximate", "nearest", "within_rounding"),
        False,
        "approximate.nearest.within_rounding",
    ),
    ("rounded about a rational axis", ("approximate", "near_sor"), False, "approximate.nearest"),
    ("torus", ("real_locus",), {"kind": "empty", "dimension": -1}, "real_locus.kind"),
    ("torus", ("canal", "kinds"), ["pipe"], "canal.kinds"),
    ("torus", ("canal", "kinds"), ["pipe", "revolution", "round"], "canal.kinds"),
]


@pytest.mark.parametrize(
    ("name", "path", "value", "named"), LIES, ids=[f"{n}:{'.'.join(map(str, p))}" for n, p, *_ in LIES]
)
def test_a_lie_is_refused_naming_its_field(
    reports: dict[str, Analysis],
    name: str,
    path: tuple[Any, ...],
    value: Any,
    named: str | None,  # noqa: ANN401
) -> None:
    refused_naming(tampered(reports[name], path, value), named)  # None: a claim left out is no lie


def refused_naming(analysis: Analysis, named: str | None) -> None:
    """``analysis`` is refused in one line that begins with the field ``named`` (accepted: None)."""
    if named is None:
        check_report(analysis)
        return
    with pytest.raises(ClaimError) as caught:
        check_report(analysis)
    assert caught.value.message.startswith(named), caught.value.message
    assert "\n" not in caught.value.message


def test_another_surfaces_nearest_surface_is_refused(reports: dict[str, Analysis]) -> None:
    """The nearest exact surface of a rounded cone pasted into the report of a rounded quadric
    about another axis: its symmetry and axis agree with its own polynomial, but it is far from
    the typed one, and the report said it within the rounding."""
    cone = reports["rounded cone printed with 17 digits (a residual over 1)"].to_json()["approximate"]["nearest"]
    swapped = tampered(reports["rounded about a rational axis"], ("approximate", "nearest"), cone)
    refused_naming(swapped, "approximate.nearest.relative_distance")


def test_a_constant_map_on_the_surface_is_no_parameterization(reports: dict[str, Analysis]) -> None:
    """A point of the torus ``(3, 0, 0)`` as a 'map' satisfies ``f(X) = 0`` but has rank 0."""
    with pytest.raises(ClaimError, match="rank below 2"):
        check_report(tampered(reports["torus"], ("parametrizations", 0, "coordinates"), ["3", "0", "0"]))


def test_square_roots_agree_wherever_they_occur() -> None:
    """√2·√3 = √6 and √(12) = 2√3 modulo the prime: the coprime basis of the radicands."""
    assert coprime_basis([6, 2, 12, 50]) == (2, 3, 5)
    assert coprime_basis([4, 9, 35]) == (2, 3, 35)  # squares split into their roots
    embedded = embedding({sympy.Integer(2), sympy.Integer(6), sympy.Rational(3, 5)}, complex_unit=True)
    p = embedded.prime
    root = embedded.sqrt_rational
    assert root(2) * root(3) % p == root(6) and root(12) == 2 * root(3) % p
    assert root(sympy.Rational(3, 5)) ** 2 * 5 % p == 3 and embedded.roots[-1] ** 2 % p == p - 1


def test_a_square_root_of_a_polynomial_is_one_root_of_each_factor() -> None:
    """``√((t² + 1)(t + 2)) = √(t² + 1)·√(t + 2)`` at every point where both exist."""
    embedded = embedding(set(), complex_unit=False)
    agreed = 0
    for _ in range(200):
        point = Point(embedded)
        try:
            together = point.value(formula("sqrt((t**2 + 1)*(t + 2))"))
            apart = point.value(formula("sqrt(t**2 + 1)*sqrt(t + 2)"))
        except ArithmeticError:
            continue
        assert together == apart
        agreed += 1
    assert agreed > 10


def test_derivatives_are_exact_in_dual_numbers() -> None:
    embedded = embedding({sympy.Integer(2)}, complex_unit=False)
    point = Point(embedded)
    p = embedded.prime
    t = point.of("t")
    expr = formula("(t**3 + sqrt(2)*t)/(t**2 + 1) + sin(theta)*t")
    derivative = formula("(3*t**2 + sqrt(2))/(t**2 + 1) - 2*t*(t**3 + sqrt(2)*t)/(t**2 + 1)**2 + sin(theta)")
    assert point.jet(expr, "t") == (point.value(expr), point.value(derivative))
    cos, sin = point.cos_sin
    assert point.jet(formula("sin(theta)*t"), "theta")[1] == cos * t % p and (cos * cos + sin * sin) % p == 1


def test_an_unfinished_report_claims_nothing_it_did_not_decide(reports: dict[str, Analysis]) -> None:
    from sorgui.engine.timelimit import skeleton

    torus = reports["torus"]
    from sorgui.engine.parsing import parse_polynomial

    start = skeleton(parse_polynomial(torus.input).polynomial, text=torus.input, method="symmetry")
    check_report(start)
    lying = dataclasses.replace(start, recognition=dataclasses.replace(start.recognition, axis=torus.recognition.axis))
    with pytest.raises(ClaimError, match="symmetry"):
        check_report(lying)
