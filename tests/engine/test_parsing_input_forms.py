"""Input as users paste it: a byte-order mark, ``f(x, y, z) =``, LaTeX; and number sizes that
every later stage can print."""

from __future__ import annotations

import pytest
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
    ],
)
def test_pasted_forms_of_the_same_paraboloid(text: str) -> None:
    assert parse_polynomial(text).polynomial == X**2 + Y**2 - Z


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
