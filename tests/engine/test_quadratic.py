"""Polynomials over a quadratic field in flint (engine/algebra/quadratic.py): products, exact
quotients, the modular gcd and Yun's square-free decomposition, against sympy."""

from __future__ import annotations

import random

import pytest
import sympy
from flint import fmpq, fmpq_poly
from sympy.polys.domains import QQ

from sorgui.engine.algebra import quadratic
from sorgui.engine.algebra.polys import poly_ring

T = sympy.Symbol("t")


def random_pair(rng: random.Random, degree: int) -> quadratic.Pair:
    return (
        fmpq_poly([fmpq(rng.randint(-9, 9), rng.randint(1, 5)) for _ in range(degree)] + [1]),
        fmpq_poly([fmpq(rng.randint(-9, 9), rng.randint(1, 5)) for _ in range(degree + 1)]),
    )


@pytest.mark.parametrize("generator", [sympy.I, sympy.sqrt(2), sympy.sqrt(-7)])
@pytest.mark.parametrize("seed", [1, 2])
def test_the_squarefree_decomposition_is_sympys(generator: sympy.Expr, seed: int) -> None:
    D = QQ.algebraic_field(generator)
    K = quadratic.field_of(D)
    assert K is not None and not K.rational
    rng = random.Random(seed)
    factors = [random_pair(rng, d) for d in (1, 2, 1)]
    product = (fmpq_poly([fmpq(3, 7)]), fmpq_poly([]))
    for factor, e in zip(factors, (1, 2, 3)):
        for _ in range(e):
            product = K.mul(product, factor)
    ring = poly_ring(("t",), D)
    mine = {e: quadratic.pair_expr(g, D, T) for g, e in quadratic.squarefree_decomposition(K, product)}
    _, theirs = quadratic.pair_poly(product, ring).sqf_list()
    assert set(mine) == {e for _, e in theirs}
    for g, e in theirs:
        assert sympy.expand(mine[e] - g.monic().as_expr()) == 0


def test_gcd_and_division_over_the_gaussian_rationals() -> None:
    D = QQ.algebraic_field(sympy.I)
    K = quadratic.field_of(D)
    assert K is not None
    t, one, zero = fmpq_poly([0, 1]), fmpq_poly([1]), fmpq_poly([])
    common = (t * t + 1, one * 2)  # t² + 1 + 2i
    a = K.mul(common, (t, -one))
    b = K.mul(common, (t + 3, one))
    g = quadratic.gcd(K, a, b)
    assert g == K.monic(common)
    assert K.divide(a, g) == (t, -one) and K.divide(a, (t + 5, zero)) is None


def test_the_rational_field_is_plain_flint() -> None:
    K = quadratic.field_of(QQ)
    assert K is not None and K.rational
    t, zero = fmpq_poly([0, 1]), fmpq_poly([])
    square = ((t - 1) ** 2 * (t + 2), zero)
    found = quadratic.squarefree_decomposition(K, square)
    assert found == [((t + 2, zero), 1), ((t - 1, zero), 2)]


def test_the_gcd_of_polynomials_of_thousands_of_bits_settles() -> None:
    """The ``P²`` of a 6-digit rounded torus's nearest surface lives over ``QQ(√d)`` with a
    1,200-bit ``d`` and has coefficients of 10,000 bits: its gcd needed 512 primes, and 400 were
    allowed ("the modular gcd did not settle", the whole analysis lost)."""
    rng = random.Random(5)
    K = quadratic.QuadraticField(fmpq(0), fmpq(-(rng.getrandbits(1200) | 1)))
    big = lambda: fmpq(rng.getrandbits(8000) - (1 << 7999), rng.getrandbits(8000) | 1)  # noqa: E731
    common = (fmpq_poly([big(), big(), 1]), fmpq_poly([big(), big()]))
    a = K.mul(common, (fmpq_poly([big(), big(), big(), 1]), fmpq_poly([big(), big()])))
    b = K.mul(common, (fmpq_poly([big(), big(), 1]), fmpq_poly([big()])))
    assert quadratic.gcd(K, a, b) == K.monic(common)
