"""Test surfaces as plain terms ``[((i, j, k), c), ...]`` (the render layer's input)."""

from __future__ import annotations

import numpy as np

from tests.conftest import corpus_cases

SPHERE = [((2, 0, 0), 1.0), ((0, 2, 0), 1.0), ((0, 0, 2), 1.0), ((0, 0, 0), -1.0)]
"""x² + y² + z² - 1."""

EMPTY_ELLIPSOID = [((2, 0, 0), 1.0), ((0, 2, 0), 1.0), ((0, 0, 2), 1.0), ((0, 0, 0), 1.0)]
"""x² + y² + z² + 1: no real points."""

CONE = [((0, 2, 0), 1.0), ((1, 0, 1), -2.0)]
"""y² - 2xz: a cone of revolution, vertex at the origin, axis direction (1, 0, 1)."""

ELLIPSOID = [((2, 0, 0), 1.0), ((0, 2, 0), 2.0), ((0, 0, 2), 3.0), ((0, 0, 0), -1.0)]
"""x² + 2y² + 3z² - 1: no axis of revolution."""

TORUS = [
    ((4, 0, 0), 1.0), ((0, 4, 0), 1.0), ((0, 0, 4), 1.0),
    ((2, 2, 0), 2.0), ((2, 0, 2), 2.0), ((0, 2, 2), 2.0),
    ((2, 0, 0), -10.0), ((0, 2, 0), -10.0), ((0, 0, 2), 6.0), ((0, 0, 0), 9.0),
]  # fmt: skip
"""(x² + y² + z² + 3)² - 16(x² + y²): tube radius 1 about the circle of radius 2 in z = 0."""

TORUS_PROFILE_SR = [((0, 4), 1.0), ((2, 2), 2.0), ((4, 0), 1.0), ((0, 2), -10.0), ((2, 0), 6.0), ((0, 0), 9.0)]
"""p̃(s, r) of the torus for c = 0, a = (0, 0, 1), u = (1, 0, 0): (r² + s² + 3)² - 16r²."""


def direct(terms, x, y, z):
    """Term-by-term numpy evaluation, the reference for the fast evaluators."""
    return sum(c * x**i * y**j * z**k for (i, j, k), c in terms)


def corpus_terms(name: str):
    """An expanded integer polynomial of the public corpus (``c*x^i*y^j*z^k`` sums) as terms.

    Only for the corpus's trusted, expanded inputs; the engine's parser handles user text.
    """
    text = next(c["input"] for c in corpus_cases() if c["name"] == name)
    terms: dict[tuple[int, int, int], float] = {}
    for term in text.replace(" ", "").replace("-", "+-").split("+"):
        if not term:
            continue
        coefficient, factors = 1.0, term.split("*")
        if factors[0].startswith("-"):
            coefficient, factors[0] = -1.0, factors[0][1:]
        if factors[0][0].isdigit():
            coefficient *= float(factors.pop(0))
        exps = [0, 0, 0]
        for factor in factors:
            var, _, power = factor.partition("^")
            exps["xyz".index(var)] += int(power or 1)
        terms[tuple(exps)] = terms.get(tuple(exps), 0.0) + coefficient
    return list(terms.items())


def random_terms(rng: np.random.Generator, n: int = 20, degree: int = 5, nvars: int = 3):
    """``n`` random terms of degree ≤ ``degree`` per variable, coefficients normal."""
    return [(tuple(int(e) for e in rng.integers(0, degree + 1, nvars)), float(rng.normal())) for _ in range(n)]
