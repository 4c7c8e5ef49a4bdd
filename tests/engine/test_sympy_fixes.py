"""The two gaps of sympy's flint ground types that sorgui closes (sorgui.engine.algebra.sympy_fixes):
the same answers as sympy's own helpers, and square roots of large integers that sympy could not
take (real sympy, real flint)."""

from __future__ import annotations

import random
import re

import pytest
import sympy
from hypothesis import given
from hypothesis import strategies as st
from sympy.external.ntheory import is_strong_bpsw_prp

from sorgui.engine.algebra import polys, sympy_fixes  # noqa: F401 - importing polys installs the fixes
from sorgui.engine.analysis import analyze


@pytest.mark.parametrize(
    "n",
    [2, 7919, 561, 2**61 - 1, 2**89 - 1, 2**89 + 1, 3215031751, 2**521 - 1, (2**127 - 1) * (2**89 - 1), 10**400 + 267],
)
def test_the_primality_test_is_sympys(n: int) -> None:
    """flint's strong BPSW test agrees with sympy's pure Python one on primes, Carmichael numbers
    and products of two large primes, and ``sympy.isprime`` uses it."""
    from sympy.ntheory import primetest

    assert primetest.is_strong_bpsw_prp is sympy_fixes.probable_prime
    assert sympy_fixes.probable_prime(n) == is_strong_bpsw_prp(n)
    assert sympy.isprime(n) == is_strong_bpsw_prp(n)


@pytest.mark.parametrize("seed", range(8))
def test_roots_of_large_powers_are_taken(seed: int) -> None:
    """``sympy.sqrt`` and the cube root of ``b^k·m`` for a ``b`` of hundreds of digits: sympy's
    perfect-power test took ``math.log`` of flint's roots and raised ``OverflowError`` (159 of
    180 such roots before the fix). Each root is checked by raising it to its power again."""
    rng = random.Random(seed)
    base = rng.randrange(10**350, 10**400)
    n = base ** rng.choice([2, 3, 4, 6]) * rng.choice([1, 2, 12, 360, 7**5])
    for value in (sympy.Integer(n), sympy.Rational(3, n)):
        assert sympy.sqrt(value) ** 2 == value
        assert sympy.expand(sympy.root(value, 3) ** 3) == value


def test_a_paraboloid_with_a_2000_digit_coefficient_is_analysed() -> None:
    """``z = c·(x² + y²)`` with ``c`` of 2000 digits stopped with an internal error (the canal
    stage's square root of ``1/(4c)²…``); it is a surface of revolution about the z-axis, with
    real parameterizations."""
    c = random.Random(7).randrange(10**1999, 10**2000)
    analysis = analyze(f"z - {c}*(x^2 + y^2)")
    assert analysis.is_sor and analysis.recognition.axis is not None
    assert analysis.recognition.axis.direction == ("0", "0", "1")
    assert analysis.canal is not None and analysis.canal.is_canal
    assert any(p.real and p.verified for p in analysis.parametrizations)


@given(st.text(alphabet="xy_(*)/+-0123456789 ", max_size=40))
def test_generators_are_split_as_sympy_splits_them(text: str) -> None:
    """The linear pattern gives sympy's own name and index for any one-line generator text."""
    sympys = re.compile(r"^(.*?)(\d*)$", re.MULTILINE)
    assert sympy_fixes.GENERATOR.match(text).groups() == sympys.match(text).groups()
