"""The reader of rational parametrizations: every form, the parameters found from the text, and
one clear error for each way a text is not the map of a surface (docs/math.md §13)."""

from __future__ import annotations

import pytest
from flint import fmpq

from sorgui.engine.errors import ParseError
from sorgui.engine.parametric_parsing import ParsedParametrization, parse_input, parse_parametrization
from sorgui.engine.parsing import ParsedPolynomial, is_parametrization, parse_polynomial

CONE = "x = (1-t^2)/(1+t^2)*(2+s), y = 2*t/(1+t^2)*(2+s), z = s^2"
"""The issue's example (a surface of revolution about the z-axis)."""


def _values(text: str, point: tuple[int, int]) -> tuple[fmpq, fmpq, fmpq]:
    """The map at a parameter point, in the typed parameters' order."""
    surface = parse_parametrization(text).map
    X, W, _normal = surface.values(tuple(fmpq(c) for c in point))
    return X[0] / W, X[1] / W, X[2] / W


@pytest.mark.parametrize(
    "text",
    [
        CONE,
        "x = (1-t^2)/(1+t^2)*(2+s); y = 2*t/(1+t^2)*(2+s); z = s^2",
        "x = (1-t^2)/(1+t^2)*(2+s)\ny = 2*t/(1+t^2)*(2+s)\nz = s^2",
        "z = s^2, x = (1-t^2)/(1+t^2)*(2+s), y = 2t/(1+t²)·(2+s)",
        "((1-t^2)/(1+t^2)*(2+s), 2t/(1+t^2)*(2+s), s^2)",
        "(1-t^2)/(1+t^2)*(2+s), 2t/(1+t^2)*(2+s), s^2",
        "P(s, t) = ((1-t^2)/(1+t^2)*(2+s), 2t/(1+t^2)*(2+s), s^2)",
        "(x, y, z) = ((1-t^2)/(1+t^2)*(2+s), 2t/(1+t^2)*(2+s), s^2)",
        "x(s,t) = (1-t^2)/(1+t^2)*(2+s), y(s,t) = 2t/(1+t^2)*(2+s), z(s,t) = s^2",
        r"\left( \frac{1-t^{2}}{1+t^{2}} (2+s), \frac{2t}{1+t^{2}} (2+s), s^{2} \right)",
        "x = (1 - t**2)/(1 + t**2)*(2 + s),\ny = 2*t/(1 + t**2)*(2 + s),\nz = s**2",
    ],
)
def test_every_form_reads_the_same_map(text: str) -> None:
    parsed = parse_parametrization(text)
    assert parsed.parameters == ("s", "t")
    for point in ((0, 0), (1, 2), (-3, 1)):
        assert _values(text, point) == _values(CONE, point)


def test_components_are_kept_as_typed() -> None:
    parsed = parse_parametrization("z = s^2;  x = s*t ;y = 1.5e-3*t")
    assert parsed.components == ("s*t", "1.5e-3*t", "s^2")
    assert parse_parametrization(r"\left( s, t, s^{2} \right)").components == ("s", "t", "s^{2}")


@pytest.mark.parametrize(
    "text, parameters",
    [
        ("x = u, y = v, z = u*v", ("u", "v")),
        ("x = v, y = u, z = uv", ("u", "v")),  # alphabetical when nothing names the order
        ("P(v, u) = (v, u, uv)", ("v", "u")),  # a prefix names the order
        ("x(b, a) = a + b, y(b, a) = a - b, z(b, a) = a*b", ("b", "a")),
        ("x = theta, y = phi, z = theta*phi", ("phi", "theta")),
        ("x = st, y = s, z = t^2", ("s", "t")),  # a run of one-letter parameters is a product
    ],
)
def test_the_parameters_are_found_from_the_text(text: str, parameters: tuple[str, str]) -> None:
    assert parse_parametrization(text).parameters == parameters


def test_a_run_of_letters_is_a_product() -> None:
    assert _values("x = st, y = s, z = t", (2, 3))[0] == 6


def test_coefficients_as_for_equations() -> None:
    parsed = parse_parametrization("x = 0.25*s, y = sqrt(8)*t, z = 1.5e-3*s*t")
    assert parsed.radicands == (2,)
    exact = parse_parametrization("x = s/4, y = t, z = 3/2000*s*t")
    assert exact.field.is_QQ and _values("x = 0.25*s, y = t, z = 1.5e-3*s*t", (2, 3)) == _values(
        "x = s/4, y = t, z = 3/2000*s*t", (2, 3)
    )


@pytest.mark.parametrize(
    "text, words",
    [
        ("x = s, y = s^2, z = s^3", "one parameter (s): the image is a curve"),
        ("x = s + t, y = (s + t)^2, z = 1/(s + t)", "the image is a curve or a point"),
        ("x = 1, y = 2, z = 3", "no parameter"),
        ("x = s, y = t, z = 1", "the component z is constant"),
        ("x = s, y = t, z = s + t - s - t + 2", "the component z is constant"),
        ("x = s, y = t, z = sin(s)", "s is written both inside cos or sin and outside them"),
        ("x = cos(s + 1), y = t, z = s", "takes a whole multiple of one parameter"),
        ("x = cos(13*s), y = sin(t), z = t", "from 1 to 12 times"),
        ("x = cos(s/2), y = sin(t), z = t", "takes a whole multiple of one parameter"),
        ("x = tan(s), y = t, z = s", "'tan' is not allowed"),
        ("x = s, y = t, z = exp(s*t)", "'exp' is not allowed"),
        ("x = s, y = t, z = f(s)", "'f(…)' is not allowed"),
        ("x = s, y = t, z = abc(s)", "'abc(…)' is not allowed"),
        ("x = s, y = t, z = s*t*u", "3 parameters (s, t, u)"),
        ("x = s/(t - t), y = t, z = s", "the denominator is identically zero"),
        ("x = s/0, y = t, z = s", "division by zero"),
        ("x = s, y = t", "three components"),
        ("x = s, y = t, z = s, w = t", "three components"),
        ("x = s, x = t, z = s*t", "'x' is given twice"),
        ("x = x + s, y = t, z = s", "cannot use 'x'"),
        ("x = s, y = t, z = ", "the component z is empty"),
        ("x = s, t, z = s*t", "has no label"),
        ("(s, t, s*t", "unmatched '('"),
        ("(s, t, s*t))", "unmatched ')'"),
        ("x = s, y = t = 2, z = s", "cannot hold '='"),
        ("x = s, y = t, z = s^(1/2)", "can only be raised to an integer power"),
        ("x = s, y = t, z = s^70", "degree is too high"),
        ("x = 1/(1+s)^40, y = 1/(1+t)^40, z = s", "degree is too high"),
    ],
)
def test_bad_maps_are_one_line_errors(text: str, words: str) -> None:
    with pytest.raises(ParseError) as info:
        parse_parametrization(text)
    assert words in info.value.message, info.value.message
    assert "\n" not in info.value.message
    assert 0 <= info.value.position <= len(text)


def test_the_error_points_at_the_component() -> None:
    text = "x = s, y = t, z = 1"
    with pytest.raises(ParseError) as info:
        parse_parametrization(text)
    assert text[info.value.position : info.value.end].strip() == "1"


@pytest.mark.parametrize(
    "text",
    [
        "x^2 + y^2 - z",
        "f(x, y, z) = x^2 + y^2 - 1",
        "x = y^2 + z^2",  # one label only: the implicit equation x - y² - z²
        "x^2 + y^2\n - z",
        r"x^2 \, + y^2 \; - z",
    ],
)
def test_equations_stay_equations(text: str) -> None:
    assert not is_parametrization(text)
    parsed = parse_input(text)
    assert isinstance(parsed, ParsedPolynomial)
    assert parsed.polynomial == parse_polynomial(text).polynomial


def test_an_equation_with_a_stray_comma_says_what_a_parametrization_needs() -> None:
    with pytest.raises(ParseError) as info:
        parse_input("x^2 + y^2, z")
    assert "three components" in info.value.message


@pytest.mark.parametrize(
    ("text", "words", "at"),
    [
        ("1,5x + y", "write decimals with a point (1.5)", ","),
        ("x + 2,5*y^2 - z", "write decimals with a point (2.5)", ","),
        ("x^2 + 1,5*y^2 + 2,5*z^2 - 1", "write decimals with a point (1.5)", ","),  # three "components"
        ("x^2 + y^2; + z^2 - 1", "three components", ";"),
        ("(s, t, s^2 + t^2)+", "follows the triple (X, Y, Z)", "+"),
        ("2*(s, t, s^2 + t^2)", "comes before the triple (X, Y, Z)", "2*"),
    ],
)
def test_a_stray_separator_is_pointed_at_where_it_is(text: str, words: str, at: str) -> None:
    """Not "at character 1": the decimal comma, a stray ";", the text around a triple."""
    with pytest.raises(ParseError) as info:
        parse_input(text)
    assert words in info.value.message, info.value.message
    assert text[info.value.position : info.value.end].strip() == at


@pytest.mark.parametrize(
    "text", ["[s, t, s^2 + t^2]", "X1 := [s, t, s^2 + t^2];", "X = (s, t, s^2 + t^2)", "P = {s, t, s^2 + t^2};"]
)
def test_a_named_triple_in_brackets_or_braces_is_a_parametrization(text: str) -> None:
    parsed = parse_parametrization(text)
    assert parsed.parameters == ("s", "t")
    assert parsed.components == ("s", "t", "s^2 + t^2")


@pytest.mark.parametrize(("text", "at"), [("x = t1, y = t2, z = t1*t2", "t1"), ("(s, t, 3s2 + t)", "s2")])
def test_digits_after_a_parameter_are_refused_where_they_are(text: str, at: str) -> None:
    """Not read as Singular's powers (which x, y, z take in an equation): ``t1, t2`` were one
    parameter, and the map a curve."""
    with pytest.raises(ParseError) as info:
        parse_parametrization(text)
    assert text[info.value.position : info.value.end] == at
    assert "a parameter's name is letters only" in info.value.message


@pytest.mark.parametrize(
    "text",
    [
        "{x -> s, y -> t, z -> s^2 + t^2}",  # Mathematica's rules
        "f[s_, t_] := {s, t, s^2 + t^2}",  # Mathematica's function
        "x=s,y=t,z=s^2 + t^2,",  # an item of a list
    ],
)
def test_mathematica_forms_and_a_final_comma_are_read(text: str) -> None:
    parsed = parse_parametrization(text)
    assert parsed.parameters == ("s", "t") and parsed.components == ("s", "t", "s^2 + t^2")


def test_mathematica_sqrt_is_sqrt() -> None:
    assert parse_parametrization("{u, v, Sqrt[2]*u*v}").radicands == (2,)


@pytest.mark.parametrize(
    ("text", "at", "words"),
    [
        ("(s, t, s^2+t^2+r)", "r", "3 parameters"),
        ("x = s, y = t, z = s + q", "q", "3 parameters"),
        ("x = s, y = t, z = s^2 @ t^2 + q", "@", "unexpected character"),
    ],
)
def test_the_error_points_at_the_odd_one_out(text: str, at: str, words: str) -> None:
    """The name written last for the first time, not the third in alphabetical order (``t``);
    a stray character before any name is counted."""
    with pytest.raises(ParseError) as info:
        parse_parametrization(text)
    assert text[info.value.position : info.value.end] == at and words in info.value.message


def test_a_negative_power_of_a_parameter_is_a_denominator() -> None:
    """Components are rational functions: ``s^-1`` and ``(s^2+t^2)^-1`` are read as Maple and
    Mathematica users write them (an equation still refuses them)."""
    same = parse_parametrization("(s, t, 1/(s^2+t^2) + 1/s^2)").map
    parsed = parse_parametrization("(s, t, (s^2+t^2)^-1 + s^(-2))").map
    assert (parsed.X, parsed.W) == (same.X, same.W)
    for text, words in (
        ("(s, t, (s-s)^-1 + t)", "the denominator is identically zero"),
        ("(s, t, 0^-1*s)", "division by zero"),
    ):
        with pytest.raises(ParseError, match=words):
            parse_parametrization(text)


TORUS_UV = "x = (1-u^2)/(1+u^2)*(2+v), y = 2*u/(1+u^2)*(2+v), z = v^2"
TORUS_ST = "x = (1-s^2)/(1+s^2)*(2+t), y = 2*s/(1+s^2)*(2+t), z = t^2"
"""The map of a surface of revolution about the z-axis, as pasted from other tools below."""
LATEX = r"\frac{1-u^2}{1+u^2}(2+v), \frac{2u}{1+u^2}(2+v), v^2"
PLAIN = "(1-s^2)/(1+s^2)*(2+t), 2*s/(1+s^2)*(2+t), t^2"
PYTHON = "(1-s**2)/(1+s**2)*(2+t), 2*s/(1+s**2)*(2+t), t**2"


@pytest.mark.parametrize(
    ("text", "plain"),
    [
        (rf"\mathbf{{r}}(u,v) = \left( {LATEX} \right)", TORUS_UV),
        (rf"$\mathbf{{r}}(u,v) = \left( {LATEX} \right)$", TORUS_UV),
        (rf"r(u, v) = ({LATEX})", TORUS_UV),
        (rf"\vec{{r}}(u,v) = ({LATEX})", TORUS_UV),
        (rf"\vec r(u, v) = \left({LATEX}\right)", TORUS_UV),
        (rf"\boldsymbol{{x}}(u, v) = ({LATEX})", TORUS_UV),
        (rf"X(u,v) = ({LATEX})", TORUS_UV),
        (rf"(u, v) \mapsto \left( {LATEX} \right)", TORUS_UV),
        (f"(u, v) ↦ ({LATEX})", TORUS_UV),
        (f"P := (s,t) -> [{PLAIN}];", TORUS_ST),
        (f"P := (s, t) -> [{PLAIN}]:", TORUS_ST),
        (f"[{PLAIN}];", TORUS_ST),
        (f"[{PLAIN}]:", TORUS_ST),
        (f"{{{PLAIN}}}", TORUS_ST),
        (f"f[s_, t_] := {{{PLAIN}}}", TORUS_ST),
        (f"np.array([{PYTHON}])", TORUS_ST),
        (f"numpy.array([{PYTHON}])", TORUS_ST),
        (f"lambda s, t: ({PYTHON})", TORUS_ST),
        (f"P = lambda s, t: np.array([{PYTHON}])", TORUS_ST),
        (f"return ({PYTHON})", TORUS_ST),
        (f"return {PYTHON}", TORUS_ST),
        (f"def P(s, t):\n    return np.array([{PYTHON}])", TORUS_ST),
    ],
)
def test_a_map_pasted_from_another_tool_is_the_plain_map(text: str, plain: str) -> None:
    """LaTeX, Maple, Mathematica and numpy/Python print a map with a label, a function's head or
    a call around the triple; each is the map of ``x = …, y = …, z = …`` (they were refused, as
    'not 1 component' or as a third parameter 'return')."""
    parsed = parse_input(text)
    expected = parse_parametrization(plain)
    assert isinstance(parsed, ParsedParametrization)
    assert parsed.parameters == expected.parameters
    assert (parsed.map.X, parsed.map.W) == (expected.map.X, expected.map.W)


@pytest.mark.parametrize(
    ("text", "parameters"),
    [
        (r"\mathbf{r}(v, u) = \left( u, v, uv \right)", ("v", "u")),
        ("P := (v, u) -> [u, v, u*v];", ("v", "u")),
        ("lambda v, u: (u, v, u*v)", ("v", "u")),
        ("def P(v, u): return (u, v, u*v)", ("v", "u")),
        ("return (u, v, u*v)", ("u", "v")),  # nothing names them: alphabetical
    ],
)
def test_a_label_or_a_head_names_the_parameters_in_its_order(text: str, parameters: tuple[str, str]) -> None:
    assert parse_parametrization(text).parameters == parameters


@pytest.mark.parametrize(
    ("text", "words", "at"),
    [
        ("lambda t: (t, t^2, t^3)", "the map takes one parameter (t): the image is a curve", "t"),
        ("(s, t, r) -> [s, t, r]", "the map takes 3 parameters (s, t, r)", "s, t, r"),
        ("P(u, v) := (s, t) -> [s, t, s*t]", "named (u, v) before and (s, t) here", "s, t"),
        ("np.array([s, t, s*t]) + 1", "np.array(…) holds the whole triple", "np.array([s, t, s*t]) + 1"),
        ("np.array([s, t, s*t]", "unmatched '('", "("),
        ("np.array([s, t])", "three components", ","),
        ("lambda s, t: x = s, y = t, z = s*t", "have no labels", "x ="),
        (r"\mathbf{r}(u,v) = (s, t, s*t)", "unknown name 's'", "s"),
    ],
)
def test_a_mistyped_head_or_call_is_a_one_line_error(text: str, words: str, at: str) -> None:
    with pytest.raises(ParseError) as info:
        parse_input(text)
    assert words in info.value.message and "\n" not in info.value.message, info.value.message
    assert text[info.value.position : info.value.end] == at


def test_cos_and_sin_of_a_parameter_are_read_in_the_tangent_of_its_half_angle() -> None:
    """A textbook's torus, ``((2 + cos v) cos u, (2 + cos v) sin u, sin v)``: with
    ``t = tan(u/2)``, ``cos(k·u)`` and ``sin(k·u)`` are the parts of ``((1 − t² + 2i·t)/(1 + t²))^k``
    (docs/math.md §13), and the map is rational in ``t`` and ``s = tan(v/2)``."""
    import math

    text = "x = (2 + cos(v))*cos(2*u), y = (2 + cos(v)) sin(2 u), z = -sin(-v)"
    parsed = parse_parametrization(text)
    assert parsed.angles == (("u", "t"), ("v", "s")) and parsed.names == ("t", "s")
    assert "t = tan(u/2)" in parsed.notes[0] and "s = tan(v/2)" in parsed.notes[1]
    for u, v in ((0.3, 1.1), (2.0, -0.7), (-2.5, 3.0)):
        point = tuple(fmpq(*math.tan(a / 2).as_integer_ratio()) for a in (u, v))
        X, W, _normal = parsed.map.values(point)
        got = [float(c / W) for c in X]
        expected = [(2 + math.cos(v)) * math.cos(2 * u), (2 + math.cos(v)) * math.sin(2 * u), math.sin(v)]
        assert all(abs(a - b) < 1e-12 for a, b in zip(got, expected))
    assert parse_parametrization("x = s, y = t, z = s*t").angles == ()


@pytest.mark.parametrize(
    "text",
    [
        "x = (2 + cos v) cos u, y = (2 + cos v) sin u, z = sin v",
        "{(2 + Cos[v]) Cos[u], (2 + Cos[v]) Sin[u], Sin[v]}",
        "\\mathbf{r}(u, v) = \\left( (2 + \\cos v)\\cos u, (2 + \\cos v)\\sin u, \\sin v \\right)",
        "\\left((2 + \\cos v)\\,\\cos u,\\ (2 + \\cos v)\\,\\sin u,\\ \\sin v\\right)",  # LaTeX's spaces
    ],
)
def test_cos_and_sin_as_papers_and_other_programs_write_them(text: str) -> None:
    """``cos u`` without parentheses (the one parameter that follows), Mathematica's ``Cos[u]``,
    LaTeX's ``\\cos u``: the same torus as ``cos(u)``."""
    torus = "x = (2 + cos(v))*cos(u), y = (2 + cos(v))*sin(u), z = sin(v)"
    assert _values(text, (2, 3)) == _values(torus, (2, 3))


@pytest.mark.parametrize("text", ["x^2 + cos(y)", "x^2 + \\cos y", "x^2 + Sin[z]"])
def test_cos_and_sin_stay_refused_in_an_equation(text: str) -> None:
    with pytest.raises(ParseError, match="unknown name '(cos|sin|Sin)'"):
        parse_polynomial(text)


def test_a_module_s_name_before_a_function_is_read_as_python_means_it() -> None:
    """``lambda u, v: (u*np.cos(v), …)`` was refused ("unexpected character '.'") beside the
    README's ``np.array``; a function a rational map has no place for is still refused, at its
    own position."""
    with_module = parse_parametrization("lambda u, v: np.array([u*np.cos(v), u*numpy.sin(v), math.sqrt(2)*u**2])")
    plain = parse_parametrization("lambda u, v: (u*cos(v), u*sin(v), sqrt(2)*u**2)")
    assert (with_module.map.X, with_module.map.W, with_module.angles) == (plain.map.X, plain.map.W, plain.angles)
    assert with_module.components == ("u*cos(v)", "u*sin(v)", "sqrt(2)*u**2")
    with pytest.raises(ParseError, match="'exp' is not allowed") as refused:
        parse_parametrization("lambda u, v: (u*np.cos(v), u*np.sin(v), np.exp(u))")
    assert refused.value.position == "lambda u, v: (u*np.cos(v), u*np.sin(v), np.exp(u))".index("exp")


def test_a_complex_map_s_imaginary_unit_is_said_to_be_one() -> None:
    """A complex parameterization of sorgui's Maple file pasted back said "the components use 3
    parameters (I, s, t)"."""
    with pytest.raises(ParseError, match="'I' is taken for a third parameter: a map with complex coefficients"):
        parse_parametrization("X1 := [s, I*t, s^2 + t^2];")
