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


def test_rounded_input_cancelled_in_its_rounding_is_not_a_plain_no() -> None:
    """Esc while a rounded torus's rounding was analysed showed a red "Not a surface of
    revolution" banner; the analysis, whole, says "nearly"."""
    from dataclasses import replace

    from sorgui.engine import analyze
    from sorgui.gui.wording import verdict

    analysis = replace(analyze("1.0000001*x^2 + y^2 - z^2 - 1", recognition_only=True), approximate=None)
    assert verdict(analysis)[0] == "Not a surface of revolution"
    title, detail, kind = verdict(analysis, rounding_stopped=True)
    assert title == "Not exactly a surface of revolution" and kind == "info"
    assert "within the rounding of its digits was not decided" in detail
