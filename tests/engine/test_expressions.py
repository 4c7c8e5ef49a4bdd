"""The one reader of machine-written formulas: sympy's output syntax and Singular's answers."""

from __future__ import annotations

import pytest
import sympy

from sorgui.engine.errors import ExpressionError
from sorgui.engine.expressions import MAX_EXPONENT, SYMPY, read, singular_syntax

x, y, a = sympy.symbols("x y a")
SINGULAR = singular_syntax({"x": x, "y": y, "a": a})


def test_both_syntaxes_read_the_same_polynomial() -> None:
    expected = x**2 / 2 - (3 * a + 1) * y
    assert sympy.expand(read("x**2/2 - (3*a + 1)*y", SYMPY) - expected) == 0
    assert sympy.expand(read("1/2*x^2+(-3*a-1)*y", SINGULAR) - expected) == 0


def test_sympy_syntax_has_sqrt_i_decimals_and_any_name() -> None:
    assert read("-sqrt(2)/2 + 3/5*I") == -sympy.sqrt(2) / 2 + sympy.Rational(3, 5) * sympy.I
    assert read("0.25*t") == sympy.Symbol("t") / 4
    assert read("-x**2") == -(x**2) and read("2**3**2") == 2**9


@pytest.mark.parametrize("text", ["x**2", "sqrt(2)", "I", "0.5*x", "t", "x^(1/2)"])
def test_singular_syntax_is_strict(text: str) -> None:
    with pytest.raises(ExpressionError):
        read(text, SINGULAR)


@pytest.mark.parametrize(
    "text",
    [
        "",
        "x +",
        "(x",
        "x)",
        "1/0",
        "0^-1",
        f"x^{MAX_EXPONENT + 1}",
        "x^y",
        "__import__('os')",
        "x.real",
        "lambda: 1",
        "sqrt",
    ],
)
def test_everything_else_is_an_expression_error(text: str) -> None:
    with pytest.raises(ExpressionError):
        read(text)


def test_expression_errors_are_engine_errors_and_value_errors() -> None:
    from sorgui.engine.errors import SorguiError

    with pytest.raises(SorguiError):
        read("x +")
    with pytest.raises(ValueError):
        read("x +")
