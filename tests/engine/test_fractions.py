"""Rational functions over QQ in reduced flint fractions agree with sympy's ``cancel``."""

from __future__ import annotations

import sympy
from flint import fmpq
from hypothesis import given, settings
from hypothesis import strategies as st

from sorgui.engine.algebra.fractions import (
    RationalFunction,
    evaluate,
    factored,
    from_expr,
    square_root,
    square_root_parts,
)
from sorgui.engine.algebra.rationals import context

T, S = sympy.symbols("t s")
RING = context(("t", "s"))

small = st.integers(-4, 4)
polys = st.lists(st.tuples(st.integers(0, 3), st.integers(0, 2), small), min_size=1, max_size=4).map(
    lambda terms: sum((c * T**i * S**j for i, j, c in terms), sympy.Integer(0))
)
nonzero = polys.filter(lambda p: p != 0)
fractions = st.tuples(polys, nonzero).map(lambda pq: pq[0] / pq[1])


def same(f: RationalFunction, expr: sympy.Expr) -> bool:
    return sympy.cancel(f.to_expr((T, S)) - expr) == 0


@settings(max_examples=30, deadline=None)
@given(fractions, fractions)
def test_arithmetic_agrees_with_sympy(a: sympy.Expr, b: sympy.Expr) -> None:
    A, B = from_expr(a, (T, S), RING), from_expr(b, (T, S), RING)
    assert same(A + B, a + b)
    assert same(A - B, a - b)
    assert same(A * B, a * b)
    assert same(A.derivative(0), sympy.diff(a, T))
    if b != 0:
        assert same(A / B, a / b)
    assert A.den.leading_coefficient() == 1
    assert A.num.gcd(A.den).is_one()


@settings(max_examples=12, deadline=None)
@given(fractions, fractions, fractions)
def test_evaluate_is_substitution(a: sympy.Expr, b: sympy.Expr, p: sympy.Expr) -> None:
    u, v = sympy.symbols("u v")
    P = sympy.Poly(sympy.fraction(sympy.together(p))[0].subs({T: u, S: v}), u, v)
    point = [from_expr(a, (T, S), RING), from_expr(b, (T, S), RING)]
    value = evaluate(((m, fmpq(int(c.p), int(c.q))) for m, c in P.terms()), point)
    assert same(value, P.as_expr().subs({u: a, v: b}, simultaneous=True))


@settings(max_examples=25, deadline=None)
@given(fractions, st.integers(1, 12))
def test_square_roots(a: sympy.Expr, c: int) -> None:
    A = from_expr(a, (T, S), RING)
    if A.is_zero():
        return
    root = square_root(A * A * c)
    assert (root is not None) == sympy.sqrt(c).is_Rational
    q, k, N, D = square_root_parts(A * c)
    assert (q * q * k * RationalFunction.make(N, D)) == A * c
    assert sympy.cancel(factored(A, (T, S)) - a) == 0
