"""Arithmetic over K = QQ(√…) through flint: conversions, composition, norms and Trager's
factorization, checked exactly against sympy's own algebraic-field arithmetic on small cases."""

from __future__ import annotations

import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st
from sympy.polys.domains import QQ

from benchmarks.numberfields import BARTH, SARTI
from sorgui.engine.algebra import numberfields as nf
from sorgui.engine.algebra.polys import (
    compose,
    factor,
    number_field,
    poly_ring,
    sqrt_in_field,
)
from sorgui.engine.analysis import analyze
from sorgui.engine.errors import OutOfReach
from sorgui.engine.parsing import parse_polynomial
from sorgui.engine.singular.curves import analyze_curves

FIELDS = [(5,), (2, 3), (2, 3, 6), (2, 3, 5)]


def _ring(radicands: tuple[int, ...], names: tuple[str, ...] = ("x", "y", "z")):
    K = number_field(radicands)
    return K, poly_ring(names, K)


def _sqrt(K, n: int):
    return K.from_sympy(sympy.sqrt(n))


@pytest.mark.parametrize("radicands", FIELDS)
def test_round_trip_through_the_radical_basis(radicands: tuple[int, ...]) -> None:
    K, R = _ring(radicands)
    x, y, z = R.gens
    roots = [_sqrt(K, n) for n in radicands]
    f = (roots[0] * x + roots[-1] * y + 3) ** 3 - sum(roots, K.zero) * z + QQ(1, 7)
    assert nf.from_flint(nf.to_flint(f), R) == f
    for c in f.values():
        assert nf.element_from_radicals(K, nf.element_to_radicals(K, c)) == c


def test_the_independent_radicands_of_a_dependent_list() -> None:
    assert nf.radical_basis(number_field((2, 3, 6))).radicands == (2, 3)
    assert nf.radical_basis(number_field((2, 3, 5, 7))).degree == 16


def test_norm_of_a_linear_form() -> None:
    K, R = _ring((2,), ("x", "y"))
    x, y = R.gens
    F = nf.to_flint(x + _sqrt(K, 2) * y + 1)
    N = nf.norm(F, (2,))
    assert nf.from_flint(N, R) == (x + 1) ** 2 - 2 * y**2


@pytest.mark.parametrize("radicands", FIELDS)
def test_compose_agrees_with_sympy(radicands: tuple[int, ...]) -> None:
    K, R = _ring(radicands)
    S = poly_ring(("s", "r"), K)
    s, r = S.gens
    x, y, z = R.gens
    root = _sqrt(K, radicands[-1])
    f = x**3 + root * x * y * z - 2 * z**2 + root
    images = [s + root * r, root * s - r, s * r + 1]
    expected = S.zero
    for monom, c in f.items():
        term = S(c)
        for h, e in zip(images, monom):
            term *= h**e
        expected += term
    assert compose(f, images) == expected


def _sympy_factors(f):
    c, fs = f.factor_list()
    return c, sorted(((g.monic(), e) for g, e in fs), key=lambda ge: str(ge[0]))


def _ours(f):
    c, fs = factor(f)
    return sorted(((g.monic(), e) for g, e in fs), key=lambda ge: str(ge[0]))


@pytest.mark.parametrize(
    "build",
    [
        lambda K, x, y: x**2 - 2 * y**2,  # splits over QQ(√2): (x - √2y)(x + √2y)
        lambda K, x, y: (x + 1) * (x**2 + _sqrt(K, 2) * x * y + 3) ** 2,
        lambda K, x, y: (x**2 - 2) * (y**2 - 3) * (x * y - _sqrt(K, 6)),
        lambda K, x, y: (x + _sqrt(K, 3) * y) ** 3 * (x - _sqrt(K, 3) * y),
        lambda K, x, y: x**4 - 10 * x**2 + 1,  # the minimal polynomial of √2 + √3: four linear factors
        lambda K, x, y: (x**2 + y**2 + _sqrt(K, 2) * x + 1) * (x * y + _sqrt(K, 3)),
    ],
)
def test_factor_agrees_with_sympy(build) -> None:
    K, R = _ring((2, 3), ("x", "y"))
    x, y = R.gens
    f = build(K, x, y)
    assert _ours(f) == _sympy_factors(f)[1]
    content, factors = factor(f)
    product = R(content)
    for g, e in factors:
        product *= g**e
    assert product == f


@settings(max_examples=25, deadline=None)
@given(
    st.lists(
        st.tuples(st.integers(-3, 3), st.integers(-3, 3), st.integers(-3, 3), st.integers(1, 2)),
        min_size=1,
        max_size=3,
    )
)
def test_factor_of_random_products_over_qq_sqrt2(pieces) -> None:
    K, R = _ring((2,), ("x", "y"))
    x, y = R.gens
    root = _sqrt(K, 2)
    f = R.one
    for a, b, c, e in pieces:
        f *= (x**2 + a * root * x * y + b * y + c * root) ** e
    assert _ours(f) == _sympy_factors(f)[1]


def test_sqrt_in_field_and_the_field_of_a_rational_root() -> None:
    K = number_field((2, 3))
    assert sqrt_in_field(K, K.convert(QQ(6))) == _sqrt(K, 6)
    assert sqrt_in_field(K, K.convert(QQ(8, 9))) == K.convert(QQ(2, 3)) * _sqrt(K, 2)
    assert sqrt_in_field(K, K.convert(QQ(5))) is None
    L = number_field((2, 3, 5))
    assert nf.embed(_sqrt(K, 6) + 1, K, L) == _sqrt(L, 6) + 1
    assert nf.rational_sqrt(L, nf.fmpq(20)) == 2 * _sqrt(L, 5)


def test_from_expr_reads_square_root_coefficients() -> None:
    K = number_field((2, 3))
    R = poly_ring(("t",), K)
    t = sympy.Symbol("t")
    expr = 3 * sympy.sqrt(2) * t**2 / 2 - sympy.sqrt(6) * t + sympy.Rational(5, 4)
    assert nf.from_expr(expr, R) == R.from_expr(expr)


def test_a_line_over_k_is_rational_without_singular() -> None:
    K, R = _ring((2, 3, 5, 7), ("s", "w"))
    s, w = R.gens
    (line,) = analyze_curves([w + _sqrt(K, 5) * s + _sqrt(K, 7)], timeout=0.001)
    assert line.genus == 0 and line.is_absolutely_irreducible


@pytest.mark.parametrize("text", [BARTH, SARTI])
def test_published_surfaces_are_irreducible_over_k_and_not_of_revolution(text: str) -> None:
    f = parse_polynomial(text).polynomial
    content, factors = factor(f)
    assert len(factors) == 1 and factors[0][1] == 1
    assert factors[0][0] * content == f
    result = analyze(text, recognition_only=True)
    assert result.recognition.is_sor is False and len(result.factors) == 1


def test_paraboloid_with_four_square_roots_is_decided() -> None:
    result = analyze("x^2+y^2+sqrt(2)x+sqrt(3)y+sqrt(5)z+sqrt(7)", recognition_only=True)
    assert result.recognition.is_sor is True and result.field == "QQ(sqrt(2), sqrt(3), sqrt(5), sqrt(7))"
    assert result.recognition.axis.direction == ("0", "0", "1")


def test_other_algebraic_fields_stay_with_sympy() -> None:
    imaginary = QQ.algebraic_field(sympy.sqrt(-3))
    assert not nf.supports(imaginary) and nf.supports(number_field((2, 3)))
    R = poly_ring(("x", "y"), imaginary)
    x, y = R.gens
    _, factors = factor(x**2 + 3 * y**2)  # splits over QQ(√-3), through sympy
    assert len(factors) == 2


def test_a_radicand_that_cannot_be_factored_quickly_is_out_of_reach() -> None:
    """Two primes of 200 bits: flint could take minutes over their product's square-free part
    (a 6-digit rounded torus's nearest surface had radicands of hundreds of digits); a product
    of small primes and one large prime is still factored."""
    p, q = int(sympy.nextprime(2**200)), int(sympy.nextprime(2**201))
    with pytest.raises(OutOfReach, match="not factored quickly"):
        nf.squarefree_core(p * q)
    assert nf.squarefree_core(p * 3**3 * 5**2) == p * 3
