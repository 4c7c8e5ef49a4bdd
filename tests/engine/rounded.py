"""Rounded surfaces for the tests of docs/math.md §8: what a CAD system prints.

``random_sor`` builds ``Σ q_ij h^i ρ^j`` (``h = n·(p - c)``, ``ρ = |p - c|²``) about an axis
turned by a random unit quaternion in floats (an irrational rotation) and shifted; ``printed``
writes any polynomial the way ``%.{k-1}e`` prints it, ``k`` significant digits per coefficient.
``rational_sor`` builds an exact surface on a rational axis with a rational profile.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
from flint import fmpq, fmpq_mpoly_ctx

from sorgui.engine.rounded import dense


def rotation(quaternion: np.ndarray) -> np.ndarray:
    """The rotation matrix of a quaternion (normalised here)."""
    a, b, c, d = quaternion / np.linalg.norm(quaternion)
    return np.array(
        [
            [a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)],
            [2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b)],
            [2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d],
        ]
    )


def random_sor(rng: np.random.Generator, degree: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A random surface of revolution of the given degree: dense array, axis direction, point."""
    n = rotation(rng.normal(size=4))[:, 2]
    point = rng.uniform(-2.0, 2.0, 3)
    one = dense.from_terms({(0, 0, 0): 1.0}, degree)
    h, rho = dense.linear_form(n, point), dense.squared_distance(point)
    total = dense.zeros(degree)
    for j, rj in enumerate(dense.powers(one, rho, degree // 2 + 1)):
        for term in dense.powers(rj, h, degree - 2 * j + 1):
            total += rng.uniform(-1.0, 1.0) * term
    return total, n, point


def sphere(center: np.ndarray, radius: float) -> np.ndarray:
    """``|p - c|² - r²``."""
    return dense.from_terms(dict(dense.squared_distance(center)), 2) - radius**2 * dense.from_terms({(0, 0, 0): 1.0}, 2)


def cylinder(direction: np.ndarray, point: np.ndarray, radius: float) -> np.ndarray:
    """``|p - c|² - (n·(p - c))² - r²`` for a unit ``n``."""
    rho = dense.from_terms(dict(dense.squared_distance(point)), 2)
    h = dense.from_terms(dict(dense.linear_form(direction, point)), 2)
    return rho - dense.times(h, dense.linear_form(direction, point)) - radius**2 * dense.from_terms({(0, 0, 0): 1.0}, 2)


def printed(array: np.ndarray, digits: int) -> str:
    """The polynomial as a CAD system prints it: every coefficient to ``digits`` significant digits."""
    return _print(array, f"+.{digits - 1}e")


def printed_fixed(array: np.ndarray, decimals: int) -> str:
    """The polynomial printed in fixed point, ``decimals`` digits after the point (``%.6f``)."""
    return _print(array, f"+.{decimals}f")


def _print(array: np.ndarray, spec: str) -> str:
    terms = []
    for i, j, k in zip(*np.nonzero(array)):
        monomial = "".join(f"*{v}^{e}" for v, e in zip("xyz", (i, j, k)) if e)
        terms.append(f"{array[i, j, k]:{spec}}{monomial}")
    return " ".join(terms)


def rational_sor(
    quaternion: tuple[int, int, int, int], point: tuple[Fraction, ...], profile: dict[tuple[int, int], Fraction]
) -> dict[tuple[int, int, int], Fraction]:
    """The exact ``Σ q_ij h^i ρ^j`` about the rational axis through ``point`` along the image of
    the z-axis under the rational rotation of an integer quaternion, as exact coefficients."""
    a, b, c, d = quaternion
    norm = a * a + b * b + c * c + d * d
    n = [
        Fraction(2 * (b * d + a * c), norm),
        Fraction(2 * (c * d - a * b), norm),
        Fraction(a * a - b * b - c * c + d * d, norm),
    ]
    ctx = fmpq_mpoly_ctx.get(("x", "y", "z"), "lex")
    gens = ctx.gens()
    shifted = [g - fmpq(p.numerator, p.denominator) for g, p in zip(gens, point)]
    h = sum((fmpq(v.numerator, v.denominator) * s for v, s in zip(n, shifted)), ctx.from_dict({}))
    rho = sum((s * s for s in shifted), ctx.from_dict({}))
    total = ctx.from_dict({})
    for (i, j), q in profile.items():
        total += fmpq(q.numerator, q.denominator) * h**i * rho**j
    return {tuple(int(e) for e in m): Fraction(int(c.p), int(c.q)) for m, c in total.to_dict().items()}


def printed_exact(coefficients: dict[tuple[int, int, int], Fraction], digits: int) -> str:
    """Exact coefficients divided by the largest, printed to ``digits`` significant digits."""
    top = max(abs(c) for c in coefficients.values())
    terms = []
    for (i, j, k), c in sorted(coefficients.items()):
        monomial = "".join(f"*{v}^{e}" for v, e in zip("xyz", (i, j, k)) if e)
        terms.append(f"{float(c / top):+.{digits - 1}e}{monomial}")
    return " ".join(terms)
