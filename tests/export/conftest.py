"""Analyses shared by the export tests, each computed once with the real engine (Singular included)."""

from __future__ import annotations

import numpy as np
import pytest

from sorgui.engine import analyze
from sorgui.engine.results import Analysis
from sorgui.engine.values import polynomial_terms
from sorgui.examples import example_text

EXAMPLES = ("paper-example-1", "torus", "cone", "paper-cubic")
"""Example 1 of the paper (row 4 of Table 1), a torus (two real parameterizations, circles
missed), a cone over Q(√2) and the paper's cubic (only a complex parameterization)."""


@pytest.fixture(scope="session")
def analyses() -> dict[str, Analysis]:
    return {name: analyze(example_text(name)) for name in EXAMPLES}


def relative_residual(polynomial: str, points: np.ndarray) -> np.ndarray:
    """``|f(p)| / Σ|c·p^m|`` at each point: 0 on the surface, rounding-sized for a float point on it."""
    terms = polynomial_terms(polynomial)
    points = np.asarray(points)
    value = np.zeros(len(points), dtype=points.dtype)
    scale = np.zeros(len(points))
    for exponents, coefficient in terms:
        term = coefficient * np.prod(points ** np.asarray(exponents), axis=1)
        value = value + term
        scale += np.abs(term)
    return np.abs(value) / np.maximum(scale, np.finfo(float).tiny)
