"""The printer of flint polynomials: flint's own ``deglex`` text is the project's term order."""

from __future__ import annotations

from flint import fmpq
from hypothesis import given, settings
from hypothesis import strategies as st

from sorgui.engine.algebra.rationals import context, flint_str, terms, terms_str

monomials = st.tuples(st.integers(0, 4), st.integers(0, 4), st.integers(0, 4))
coefficients = st.builds(fmpq, st.integers(-50, 50), st.sampled_from([1, 1, 2, 3, 7, 12]))


@settings(max_examples=300, deadline=None)
@given(st.dictionaries(monomials, coefficients, max_size=10), st.sampled_from([("x", "y", "z"), ("s", "r", "w")]))
def test_flint_str_prints_as_terms_str(d: dict, names: tuple[str, str, str]) -> None:
    g = context(("x", "y", "z")).from_dict(d)
    assert flint_str(g, names) == terms_str(names, terms(g))
