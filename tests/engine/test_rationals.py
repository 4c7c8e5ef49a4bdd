"""The printer of flint polynomials: flint's own ``deglex`` text is the project's term order; the
factorization over ``QQ``, and the primes that show a polynomial irreducible without it."""

from __future__ import annotations

from flint import fmpq
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from sorgui.engine.algebra.rationals import (
    context,
    factor,
    flint_str,
    irreducible,
    irreducible_modulo_a_prime,
    irreducible_on_a_line,
    primitive,
    rational_str,
    terms,
    terms_str,
)

monomials = st.tuples(st.integers(0, 4), st.integers(0, 4), st.integers(0, 4))
coefficients = st.builds(fmpq, st.integers(-50, 50), st.sampled_from([1, 1, 2, 3, 7, 12]))


@settings(max_examples=300, deadline=None)
@given(st.dictionaries(monomials, coefficients, max_size=10), st.sampled_from([("x", "y", "z"), ("s", "r", "w")]))
def test_flint_str_prints_as_terms_str(d: dict, names: tuple[str, str, str]) -> None:
    g = context(("x", "y", "z")).from_dict(d)
    assert flint_str(g, names) == terms_str(names, terms(g))


@given(st.integers(-(10**40), 10**40), st.integers(1, 10**30))
def test_rational_str_is_flints_text(numerator: int, denominator: int) -> None:
    q = fmpq(numerator, denominator)
    assert rational_str(q) == str(q)


def test_a_prime_shows_irreducible_what_flint_took_27_s_to_factor() -> None:
    """``P²`` of ``(x² + y² + z² + 10¹⁰⁰)³⁰ − 10¹⁰⁰·x`` (3001-digit coefficients) is irreducible
    modulo a prime, so over ``QQ`` (docs/math.md §4): its one factor, without flint's factorization."""
    s, w = context(("s", "w")).gens()
    square = (s**2 + w + 10**100) ** 30 - 10**100 * s
    assert irreducible_modulo_a_prime(square) and irreducible(square)
    assert factor(square) == [(primitive(square), 1)]


def test_what_no_prime_shows_irreducible_is_factored_in_full() -> None:
    x, y, z = context(("x", "y", "z")).gens()
    quartic = x**4 + y**4  # irreducible over QQ, split modulo every prime
    assert not irreducible_modulo_a_prime(quartic) and factor(quartic) == [(quartic, 1)]
    assert not irreducible_modulo_a_prime((x**2 + y**2 - z) ** 2)  # a square is no prime's irreducible
    assert factor(-2 * (x**2 + y**2 - z) ** 2 * (x - 1) / 3) == [(x - 1, 1), (x**2 + y**2 - z, 2)]
    assert not irreducible_modulo_a_prime(context(("x", "y", "z")).constant(5))


@settings(max_examples=200, deadline=None)
@given(
    st.lists(st.dictionaries(monomials, coefficients, min_size=1, max_size=4), min_size=1, max_size=3),
    st.sampled_from([1, 10**30]),
    st.booleans(),
)
def test_factor_is_flints_factorization(parts: list[dict], scale: int, curve: bool) -> None:  # type: ignore[type-arg]
    """Whether or not a prime is asked first (two variables, large coefficients), :func:`factor`
    is flint's factorization (primitive factors) and :func:`irreducible` says what it says; a
    polynomial a prime shows irreducible is one factor of multiplicity 1 in flint's too."""
    ring = context(("x", "y", "z"))
    g = ring.constant(1)
    for i, d in enumerate(parts):
        h = ring.from_dict(d) + scale
        g *= h.subs({2: 1}) if curve else h ** (1 + i % 2)
    assume(g.total_degree() >= 1)
    _, flints = g.factor()
    expected = sorted(((primitive(h), int(e)) for h, e in flints), key=str)
    assert sorted(factor(g), key=str) == expected
    assert irreducible(g) == (len(flints) == 1 and flints[0][1] == 1)
    if irreducible_modulo_a_prime(g):
        assert [e for _, e in flints] == [1]
    if irreducible_on_a_line(g):
        assert [e for _, e in flints] == [1]


@settings(max_examples=300, deadline=None)
@given(
    st.lists(
        st.dictionaries(st.tuples(st.integers(0, 4), st.integers(0, 3)), coefficients, max_size=5),
        min_size=1,
        max_size=3,
    )
)
def test_a_line_shows_irreducible_only_what_flint_finds_irreducible(parts: list[dict]) -> None:  # type: ignore[type-arg]
    """A curve ``g(s, w)`` whose leading coefficient in ``w`` is constant and whose restriction to
    ``s = 2`` is irreducible is irreducible and square-free in flint's factorization too; the
    torus's ``P²``, which splits at ``s = 0`` and ``s = 1``, is shown irreducible."""
    ring = context(("s", "w"))
    s, w = ring.gens()
    g = ring.constant(1)
    for i, d in enumerate(parts):
        g *= (ring.from_dict(d) + w ** (4 + i)) ** (1 + i % 2)  # a constant leading coefficient in w
    _, flints = g.factor()
    if irreducible_on_a_line(g):
        assert len(flints) == 1 and flints[0][1] == 1
    torus = (s**2 + w + 3) ** 2 - 16 * w
    assert irreducible_on_a_line(torus) and not irreducible_on_a_line((s**2 + w) ** 2)
