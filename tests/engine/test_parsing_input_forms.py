"""Input as users paste it: a byte-order mark, ``f(x, y, z) =``, LaTeX, a statement of Maple,
Singular or Mathematica; and number sizes that every later stage can print."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from sympy import QQ

from sorgui.engine.algebra.polys import XYZ, poly_ring, poly_str
from sorgui.engine.errors import ParseError
from sorgui.engine.parsing import MAX_DIGITS, MAX_PRINTED_DIGITS, parse_polynomial

R = poly_ring(XYZ, QQ)
X, Y, Z = R.gens


@pytest.mark.parametrize(
    "text",
    [
        "\ufeffx^2 + y^2 - z",
        "f(x,y,z) = x^2 + y^2 - z",
        "F(x, y, z) := x^2 + y^2 - z",
        "S ( x , y , z ) = x^2 + y^2 = z",
        "x^{2} + y^{2} - z",
        r"\left( x \right)^{2} + \left(y\right)^2 - z",
        r"x \cdot x + y \times y - z",
        r"\frac{2}{2} x^2 + \frac{y^2}{1} - z",
        r"x^2 + y^2\,-\;z",
        "f := x^2 + y^2 - z;",  # Maple
        "poly f = x2+y2-z;",  # Singular, which writes x2 for x^2
        "f[x_, y_, z_] := x^2 + y^2 - z",  # Mathematica
        "x^2 + y^2 - z == 0",
        "x^2 + y^2 = z;  \n",
        "F = x^2 + y^2 - z:",
        "$x^2 + y^2 - z$",
        "$$ x^{2} + y^{2} = z; $$",
        r"\[ x^{2} + y^{2} - z \]",
        r"\(x^2 + y^2 - z\);",
        "# a paraboloid, from my notes\nx^2 + y^2 - z  # its vertex at (0, 0, 0)",
        "x^2 + y^2 // Singular's comment\n - z;",
        "% MATLAB\nx^2 + y^2 - z; % v1.5",
        "pow(x, 2) + pow(y, 2) - z",  # C, Python, GLSL
        "pow(x,2.0) + pow(-y, 2) - pow(z, 1);",
        "X^2 + Y^2 - Z",  # a CAD system's upper case
        "+1.000000E+00*X**2 +1.000000E+00*Y**2 -1.000000E+00*Z",
    ],
)
def test_pasted_forms_of_the_same_paraboloid(text: str) -> None:
    assert parse_polynomial(text).polynomial == X**2 + Y**2 - Z


@pytest.mark.parametrize(
    "text, expected",
    [
        ("z = x2 + y2", Z - X**2 - Y**2),
        ("xy = 1", X * Y - 1),
        ("x2 = y", X**2 - Y),
        ("2x2y3z - 1", 2 * X**2 * Y**3 * Z - 1),
        ("1/2x2 + y", X**2 / 2 + Y),
    ],
)
def test_a_left_side_that_is_a_monomial_is_no_label(text: str, expected: object) -> None:
    """Only a name that is not a monomial labels an equation; digits right after a variable are
    its exponent, as Singular prints them."""
    assert parse_polynomial(text).polynomial == expected


@pytest.mark.parametrize("text", ["f := x^2 + y^2 - w;", "$x^2 + y^2 - w$", "poly g = x2 + y2 - w;"])
def test_errors_inside_a_statement_point_into_the_text_as_pasted(text: str) -> None:
    with pytest.raises(ParseError, match="unknown name 'w'") as info:
        parse_polynomial(text)
    assert info.value.position == text.index("w")


@pytest.mark.parametrize(
    "text",
    [
        "x = s, y = t, z = s^2 + t^2;",
        "$(s, t, s^2 + t^2)$",
        "x = s; y = t; z = s^2 + t^2;",
        "# a paraboloid\nx = s,  # its axis: z\ny = t,\nz = s^2 + t^2  # up, as (0, 0, 1)",
    ],
)
def test_a_statement_of_a_parametrization_is_read_as_one(text: str) -> None:
    from sorgui.engine.parametric_parsing import parse_parametrization
    from sorgui.engine.parsing import is_parametrization

    assert is_parametrization(text)
    parsed = parse_parametrization(text)
    assert parsed.parameters == ("s", "t")
    assert parsed.components == ("s", "t", "s^2 + t^2")


def test_a_comment_holds_no_separator_and_no_decimal() -> None:
    """Its commas do not make a parametrization, its digits no rounded input; a ``%`` or ``#``
    glued to the equation is no comment (``x%2`` is Python's remainder): an error."""
    from sorgui.engine.parsing import has_decimals, is_parametrization

    text = "x^2 + y^2 - z  # apex (0, 0, 0), version 1.5"
    assert not is_parametrization(text) and not has_decimals(text)
    assert parse_polynomial(text).polynomial == X**2 + Y**2 - Z
    for glued in ("x%2 + y", "x^2#c"):
        with pytest.raises(ParseError, match="unexpected character"):
            parse_polynomial(glued)


def test_the_comma_of_pow_separates_no_components() -> None:
    from sorgui.engine.parametric_parsing import parse_parametrization
    from sorgui.engine.parsing import is_parametrization

    assert not is_parametrization("pow(x, 2) + pow(y, 2) - z")
    assert is_parametrization("(pow(s, 2), t, s)")
    parsed = parse_parametrization("x = pow(s, 2), y = t, z = pow(s + t, 2)")
    assert parsed.parameters == ("s", "t")
    assert parsed.components == ("pow(s, 2)", "t", "pow(s + t, 2)")


@pytest.mark.parametrize(
    "text, plain",
    [
        ("x^2 +\u200b y^2 - z", "x^2 + y^2 - z"),  # a zero-width space
        ("x∙y + x•z + z^2", "x*y + x*z + z^2"),
        ("x^2 + y^2 - z ÷ 2", "x^2 + y^2 - z / 2"),
        ("x^2 + y^2 - 1.5e−3", "x^2 + y^2 - 1.5e-3"),  # the exponent's minus sign
        ("x^2 + y^2 - 1.5·10⁻³ z", "x^2 + y^2 - 1.5*10^(-3) z"),
        ("1.5x² + 1.5y² - z", "1.5x^2 + 1.5y^2 - z"),  # was an internal error
        ("1.5x2 + 1.5y2 - z", "1.5x^2 + 1.5y^2 - z"),
        ("1.5D-03*x^2 + y^2 - 2.5d2 z", "1.5e-03*x^2 + y^2 - 2.5e2 z"),  # Fortran
        ("x^2 + y^2 - 1.5*^-3 z", "x^2 + y^2 - 1.5e-3 z"),  # Mathematica's InputForm
    ],
)
def test_what_a_pdf_copies_reads_as_typed(text: str, plain: str) -> None:
    """Characters a PDF viewer copies, and numbers as Fortran and Mathematica print them: the
    same polynomial, and the same rounding read off the digits, as the text typed on a keyboard."""
    from sorgui.engine.parsing import has_decimals
    from sorgui.engine.rounded.dense import float_coefficients
    from sorgui.engine.rounded.precision import input_rounding

    f = parse_polynomial(text).polynomial
    assert f == parse_polynomial(plain).polynomial
    assert has_decimals(text) == has_decimals(plain)
    if has_decimals(text):
        rounding = input_rounding(text, float_coefficients(f))
        assert rounding is not None and rounding == input_rounding(plain, float_coefficients(f))


def test_latex_square_roots_give_the_number_field() -> None:
    parsed = parse_polynomial(r"x^2 + y^2 - \sqrt{2} z")
    assert parsed.radicands == (2,)


@pytest.mark.parametrize(
    "text, words",
    [
        (r"\frac{1}x", "must be followed by '{numerator}{denominator}'"),
        (r"\alpha x", "unexpected character"),
        ("g(x,y) = x^2", "unknown name 'g'"),
        ("f(x,y,z) = ", "the input is empty"),
        ("pow(x)", "'pow' takes two arguments"),
        ("pow(x, 2, 3)", "'pow' takes two arguments"),
        ("pow x", "'pow' must be followed by"),
        ("pow(x, y)", "an exponent must be a constant number"),
        ("pow(x, 2", "unmatched '('"),
        ("xY + z", "unknown name 'xY'"),  # one case or the other, not a mix
    ],
)
def test_malformed_pasted_forms_are_clear_errors(text: str, words: str) -> None:
    with pytest.raises(ParseError) as info:
        parse_polynomial(text)
    assert words in info.value.message


def test_every_accepted_number_prints() -> None:
    """The parser's size limits and Python's int→str limit agree: 4,300+ digits print."""
    big = parse_polynomial("10^4300*x + y^2 - z").polynomial
    assert str(10**4300) in poly_str(big)
    literal = parse_polynomial("1" * MAX_DIGITS + " x").polynomial
    assert len(poly_str(literal)) > MAX_DIGITS
    assert MAX_PRINTED_DIGITS >= 10 * MAX_DIGITS
    with pytest.raises(ParseError, match="more than 20,000 digits"):
        parse_polynomial("1" * (MAX_DIGITS + 1) + " x")


@pytest.mark.parametrize(
    "text",
    [
        "x^2+y^2-z^2-1\nx^2+y^2-4",  # two equations pasted together: read as -1·x², a product
        "x^2+y^2-1\n\nz",
        "2\nx^2+y^2-1",
        "x^2+y^2-z^2\nx^2-1",
        "x^2+y^2-z^2-1\n(x^2+y^2-4)",
        "x^2+y^2-z^2-1\r\nsqrt(2)*x",
    ],
)
def test_a_line_break_without_an_operator_is_not_a_product(text: str) -> None:
    """Both readers refuse a new line that starts without an operator, pointing at it; an
    equation continued after an operator, or with a ``*``, is read across lines."""
    with pytest.raises(ParseError, match="a new line starts here without an operator") as caught:
        parse_polynomial(text)
    assert text[caught.value.position] not in " \r\n"


@pytest.mark.parametrize("text", ["x^2 +\ny^2 - 1", "x^2\n+ y^2\n- 1", "x^2 + y^2 - 1 *\n1", "2 x^2 + y^2\r\n- 1 x"])
def test_an_equation_goes_on_across_lines_after_an_operator(text: str) -> None:
    assert parse_polynomial(text).polynomial == parse_polynomial(" ".join(text.split())).polynomial


_PIECES = [
    *"xyz0123456789+-*/^ .eE=();,²³⁻[]{}$:",
    "pow(",
    "sqrt(",
    "\\frac",
    "−",
    "==",
    "f :=",
    "\\\\",
    " # c\n",
    " % c",
    " //",
    "x2",
    "D",
    "*^",
    "s",
    "t",
]
"""Pieces of pasted text: every character the readers treat specially, and a few words."""


@settings(max_examples=1500, deadline=None)
@given(st.lists(st.sampled_from(_PIECES), min_size=1, max_size=14).map("".join))
def test_any_text_is_read_or_refused_in_words(text: str) -> None:
    """Whatever is pasted — statements, superscripts, decimals, pow — is read (and its rounding
    read off its digits) or refused with a ParseError; never an internal error (``1.5y²`` was one)."""
    from sorgui.engine.parametric_parsing import parse_parametrization
    from sorgui.engine.parsing import has_decimals, is_parametrization
    from sorgui.engine.rounded.dense import float_coefficients
    from sorgui.engine.rounded.precision import input_rounding

    try:
        if is_parametrization(text):
            parse_parametrization(text)
            return
        f = parse_polynomial(text).polynomial
    except ParseError:
        return
    if has_decimals(text):
        input_rounding(text, float_coefficients(f))


@pytest.mark.parametrize(
    "head",
    ["x", "poly", "f", "P", "x(s, t)", "\n", "$", "\\vec", "lambda s, t:", "(s, t) ->", "def P(s, t):", "np.array"],
)
def test_long_runs_of_white_space_are_read_once(head: str) -> None:
    """Hostile input: a name then 200,000 spaces (or empty lines). Every pattern that looks for a
    label reads such a run once (possessive quantifiers); one that read it again for each way
    of splitting it took 8 s for 40,000 spaces and would take hours for this one, and the fast
    reader of expanded equations split a run before ``)`` one space at a time (100,000 spaces:
    half a minute). No time is asserted: a regression hangs here."""
    from sorgui.engine.parametric_parsing import parse_input

    for tail in ("x", ", t, s", "\nx = s", ")"):
        try:
            parse_input(head + " " * 200_000 + tail)
        except ParseError:
            pass


def test_a_long_equation_of_sorgui_s_latex_file_pastes_back() -> None:
    """sorgui's .tex sets a long equation in a ``multline*`` environment and a quotient's
    numerator in ``\\bigl( … \\bigr)``: pasted back, "unexpected character '\\'"."""
    pasted = "\n".join(
        [
            r"\begin{multline*}",
            r"f = \frac{1}{125 s^{2} + 5}\bigl( x^{4} + 2 x^{2} y^{2} + 2 x^{2} z^{2} - 10 x^{2} + y^{4} \\",
            r"\quad + 2 y^{2} z^{2} - 10 y^{2} + z^{4} + 6 z^{2} + 9\bigr)",
            r"\end{multline*}",
        ]
    ).replace("125 s^{2} + 5", "4")
    torus = parse_polynomial("((x^2+y^2+z^2+3)^2-16*(x^2+y^2))/4").polynomial
    assert parse_polynomial(pasted).polynomial == torus
    assert parse_polynomial(r"\Bigl(x + 1\Bigr)^{2} - y").polynomial == parse_polynomial("(x+1)^2 - y").polynomial


@pytest.mark.parametrize(
    ("opening", "closing"), [("\\[\n", "\n\\]"), ("\\[ ", " \\]"), ("\\( ", " \\)"), ("$", "$"), ("$$", "$$")]
)
def test_a_map_of_sorgui_s_latex_file_pastes_back(opening: str, closing: str) -> None:
    """sorgui's .tex writes a map as three displays, ``\\[ x(s, t) = … \\]`` and so on: pasted
    back, "unmatched ')'" (and "unknown name 's'" without the labels' parameters)."""
    components = [
        r"x(s, t) = \frac{- s^{2} t^{2} - 12 s^{2} + t^{2} + 12}{s^{2} t^{2} + 4 s^{2} + t^{2} + 4}",
        r"y(s, t) = \frac{2 s t^{2} + 24 s}{s^{2} t^{2} + 4 s^{2} + t^{2} + 4}",
        r"z(s, t) = - \frac{4 t}{t^{2} + 4}",
    ]
    typed = "(-s^2*t^2-12*s^2+t^2+12)/(s^2*t^2+4*s^2+t^2+4), (2*s*t^2+24*s)/(s^2*t^2+4*s^2+t^2+4), -4*t/(t^2+4)"
    from sorgui.engine.parametric_parsing import ParsedParametrization, parse_input

    expected = parse_input(typed)
    assert isinstance(expected, ParsedParametrization)
    for labels in (components, [c.replace("(s, t)", "") for c in components]):
        pasted = parse_input("\n".join(opening + c + closing for c in labels))
        assert isinstance(pasted, ParsedParametrization) and pasted.parameters == ("s", "t")
        assert (pasted.map.X, pasted.map.W) == (expected.map.X, expected.map.W)
