"""Real roots over QQ and real multiquadratic fields, counted exactly (Sturm and arb balls)."""

from __future__ import annotations

from collections.abc import Sequence

import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st
from sympy.polys.domains import QQ

from sorgui.engine.algebra.polys import Poly, number_field, poly_ring
from sorgui.engine.algebra.realroots import count_real_roots

T = sympy.Symbol("t")
x, y = poly_ring(("x", "y"), QQ).gens

Rt = poly_ring(("t",), QQ)
(t,) = Rt.gens


@pytest.mark.parametrize(
    ("h", "expected"),
    [
        (t**4 + 4 * t**3 + 6 * t**2 + 4 * t + 5, 0),  # the paper's tubular surface
        (t**3 + 3 * t**2 - 2 * t, 3),  # docs/math.md §7: two components
        ((t - 1) ** 3 * (t**2 + 1), 1),
        (t**2 - 2, 2),
        (Rt(5), 0),
    ],
)
def test_count_real_roots_over_qq(h: Poly, expected: int) -> None:
    assert count_real_roots(h) == expected


def test_count_real_roots_over_a_multiquadratic_field() -> None:
    K = number_field((2, 3))
    (s,) = poly_ring(("s",), K).gens
    r2, r3 = K.from_sympy(sympy.sqrt(2)), K.from_sympy(sympy.sqrt(3))
    assert count_real_roots((s - r2) * (s - r3) * (s**2 - r3 + r2)) == 4
    assert count_real_roots((s - r2) * (s - r3) * (s**2 + r3 - r2)) == 2
    assert count_real_roots(s**2 - (5 - 2 * r2 * r3)) == 2  # 5 - 2√6 ≈ 0.1 > 0
    assert count_real_roots(s**2 + (2 * r2 * r3 - 5)) == 2
    assert count_real_roots((s**2 - 2) * (s - r2)) == 2  # a double root counts once


def test_count_real_roots_rejects_bad_input() -> None:
    with pytest.raises(ValueError):
        count_real_roots(x * y - 1)
    with pytest.raises(ValueError):
        count_real_roots(Rt.zero)


def linear_and_quadratic(factors: Sequence[tuple[int, int, int]]) -> Poly:
    h = Rt.one
    for a, b, c in factors:
        h *= a * t**2 + b * t + c if a else b * t + c or t
    return h


@settings(max_examples=80, deadline=None)
@given(st.lists(st.tuples(st.integers(-3, 3), st.integers(-5, 5), st.integers(-5, 5)), min_size=1, max_size=5))
def test_count_real_roots_agrees_with_sympy(factors: list[tuple[int, int, int]]) -> None:
    h = linear_and_quadratic(factors)
    if h.is_ground:
        return
    assert count_real_roots(h) == len(set(sympy.Poly(h.as_expr(), T).real_roots()))
