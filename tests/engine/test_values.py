"""The engine's strings decoded: the profile of a power's zero set (docs/math.md §5, powers)."""

from __future__ import annotations

import pytest
import sympy

from sorgui.engine.analysis import analyze
from sorgui.engine.values import read_expression, zero_set_profile

FIELDS = ("polynomial", "square", "rational", "rational_square")


def _same_zero_set(a: str, b: str) -> bool:
    """``a`` and ``b`` are the same polynomial up to a nonzero constant."""
    ratio = sympy.cancel(read_expression(a) / read_expression(b), extension=True)
    return not ratio.free_symbols and ratio != 0


@pytest.mark.parametrize(
    ("power", "zero_set"),
    [
        ("((x^2 + y^2 + z^2 + 3)^2 - 16(x^2 + y^2))^3", "(x^2 + y^2 + z^2 + 3)^2 - 16(x^2 + y^2)"),
        # about the axis along (1, 1, 0), whose orthonormal profile has sqrt(2) in it
        ("(x^2 + y^2 + z^2 - (x + y)^2/2 - (x + y))^2", "x^2 + y^2 + z^2 - (x + y)^2/2 - (x + y)"),
    ],
)
def test_a_power_has_the_profile_of_its_zero_set(power: str, zero_set: str) -> None:
    """Each of the four polynomials of a power's profile becomes that of ``g`` (same frame)."""
    whole, own = analyze(power).recognition.profile, analyze(zero_set).recognition.profile
    assert whole is not None and own is not None and whole.frame_direction == own.frame_direction
    made = zero_set_profile(whole)
    for field in FIELDS:
        assert _same_zero_set(getattr(made, field), getattr(own, field)), field
    assert (made.frame_point, made.even, made.verified) == (whole.frame_point, whole.even, whole.verified)


def test_a_power_times_another_face_keeps_both() -> None:
    """``g²·h``: the profile of ``g·h``, whose zero set is the same."""
    profile = analyze("((x^2 + y^2 + z^2 + 3)^2 - 16(x^2 + y^2))^2 * (x^2 + y^2 + z^2 - 36)").recognition.profile
    assert profile is not None
    s, r = sympy.symbols("s r")
    expected = ((s**2 + r**2 + 3) ** 2 - 16 * r**2) * (s**2 + r**2 - 36)
    assert _same_zero_set(zero_set_profile(profile).rational, str(sympy.expand(expected)))


def test_a_square_free_profile_is_kept() -> None:
    profile = analyze("(x^2 + y^2 + z^2 + 3)^2 - 16(x^2 + y^2)").recognition.profile
    assert profile is not None and zero_set_profile(profile) is profile


def test_a_polynomial_beyond_floating_point_is_named() -> None:
    """Coefficients spanning more than floats evaluate (a sphere of radius 10^200) are named
    with their span; a 300-digit coefficient alone, or a polynomial that is not expanded over
    ``QQ``, is not."""
    from sorgui.engine.values import beyond_floats

    assert beyond_floats("x**2 + y**2 + z**2 - " + "1" + "0" * 400) == (
        "the surface cannot be drawn: its coefficients span about 10^400, more than floating-point arithmetic evaluates"
    )
    assert beyond_floats("x**2 + y**2 - 1/" + "7" * 420) is not None
    assert beyond_floats("x**2 + y**2 + z**2 - " + "3" * 150) is None
    assert beyond_floats("x**2 + y**2 - 2*sqrt(2)") is None and beyond_floats("") is None
