"""The window's words for a refused equation (gui/wording.py): Qt-free, no window needed."""

from __future__ import annotations

import pytest

from sorgui.engine.errors import ParseError
from sorgui.engine.parsing import parse_polynomial
from sorgui.gui.wording import invalid_heading


@pytest.mark.parametrize(
    ("text", "heading"), [("x^-2+y", "Not a polynomial in x, y, z"), ("3", "No surface: the equation is constant")]
)
def test_a_refused_equation_s_heading_names_what_is_wrong(text: str, heading: str) -> None:
    """``x^-2 + y`` was headed "No surface: the equation is constant": its message says a
    "non-constant expression" can only be raised to a whole power."""
    with pytest.raises(ParseError) as refused:
        parse_polynomial(text)
    assert invalid_heading(str(refused.value)) == heading
