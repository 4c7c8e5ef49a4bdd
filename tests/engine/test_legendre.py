"""Legendre's equation ``a·x² + b·y² + c·z² = 0`` (docs/math.md §5, "A point of a conic"):
every solution given is one, a solvable equation gets one, and the theorem's test agrees with a
search of small solutions."""

from __future__ import annotations

import math

from hypothesis import given, settings
from hypothesis import strategies as st
from sympy import nextprime

from sorgui.engine.algebra.factoring import LARGEST_BITS, MAX_BITS
from sorgui.engine.algebra.legendre import has_solution, solution

nonzero = st.integers(min_value=-60, max_value=60).filter(bool)


def small_solution(a: int, b: int, c: int, bound: int = 40) -> tuple[int, int, int] | None:
    """A nontrivial solution with ``0 ≤ x < bound``, ``|y| < bound``, by search."""
    for x in range(bound):
        for y in range(-bound, bound):
            rest = -(a * x * x + b * y * y)
            if rest % c == 0 and rest // c >= 0:
                z = math.isqrt(rest // c)
                if z * z == rest // c and (x or y or z):
                    return x, y, z
    return None


@settings(max_examples=300, deadline=None)
@given(nonzero, nonzero, nonzero)
def test_the_theorem_agrees_with_a_search_and_a_solution_is_one(a: int, b: int, c: int) -> None:
    found = solution(a, b, c)
    if small_solution(a, b, c) is not None:
        assert has_solution(a, b, c)
    if has_solution(a, b, c):
        assert found is not None
    if found is not None:
        x, y, z = found
        assert (x, y, z) != (0, 0, 0) and a * x * x + b * y * y + c * z * z == 0
        assert math.gcd(x, y, z) == 1


@settings(max_examples=100, deadline=None)
@given(
    st.integers(1, 10**12),
    st.integers(1, 10**12),
    st.integers(1, 10**15),
    st.integers(1, 10**15),
)
def test_a_large_solvable_equation_gets_a_solution(x: int, y: int, a: int, b: int) -> None:
    """``a·x² − b·y² + c·z² = 0`` with ``c = b·y² − a·x²``: solvable (``(x, y, 1)``), with
    coefficients of up to 40 digits and prime factors far beyond any search."""
    c = b * y * y - a * x * x
    if c == 0:
        return
    found = solution(a, -b, c)
    assert found is not None
    u, v, w = found
    assert a * u * u - b * v * v + c * w * w == 0 and (u, v, w) != (0, 0, 0)


def test_one_sign_or_a_non_residue_has_none() -> None:
    assert not has_solution(1, 1, 1) and solution(1, 1, 1) is None
    assert not has_solution(1, 1, -3)  # x² + y² = 3z²: 3 is no sum of two rational squares
    assert has_solution(1, 1, -2) and solution(1, 1, -2) is not None


def test_a_large_coefficient_is_factored_when_it_is_quick() -> None:
    """Beyond :data:`MAX_BITS` bits, a number of small primes and one large prime is factored;
    the product of two primes of 100 bits is not (the equation is left undecided)."""
    large_prime = nextprime(2**200)
    smooth = 2**40 * 3**25 * 1009 * large_prime
    assert smooth.bit_length() > MAX_BITS
    assert has_solution(1, -smooth, 1) is not None
    hard = nextprime(2**100) * nextprime(2**101)
    assert hard.bit_length() > MAX_BITS
    assert has_solution(1, -hard, 1) is None and solution(1, -hard, 1) is None
    assert has_solution(1, -(2 ** (LARGEST_BITS + 1)), 1) is None  # not even its small primes
