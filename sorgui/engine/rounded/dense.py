"""Dense floating-point polynomials in x, y, z, for the approximate analysis (docs/math.md §8).

A polynomial of degree ≤ ``D`` is a ``float64`` array ``A`` of shape ``(D+1, D+1, D+1)`` with
``A[i, j, k]`` the coefficient of ``x^i y^j z^k``; entries with ``i + j + k > D`` stay zero.
Multiplying by a linear or quadratic form is a handful of shifted array additions, so the
invariant bases of §8 (powers of ``h = n·(p - c)`` times powers of ``ρ = |p - c|²``) cost
microseconds each. The exact polynomial never enters here except through
:func:`float_coefficients`; nothing here decides anything exactly.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator

import numpy as np
from flint import fmpq

from ..algebra.polys import Poly, is_rational_field, to_flint

Monomial = tuple[int, int, int]
SparseForm = list[tuple[Monomial, float]]
"""A small polynomial (a linear or quadratic form) as ``[(monomial, coefficient), ...]``."""


def float_coefficients(f: Poly) -> dict[Monomial, float]:
    """The coefficients of the exact ``f`` as floats (exact rationals rounded once)."""
    if is_rational_field(f.ring.domain):
        return {tuple(int(e) for e in m): _float(c) for m, c in to_flint(f).to_dict().items()}
    K = f.ring.domain
    return {tuple(m): float(K.to_sympy(c).evalf(20)) for m, c in f.items()}


def _float(c: fmpq) -> float:
    """``c`` as a float, ``±inf`` beyond the float range (the caller refuses those)."""
    try:
        return float(c)
    except OverflowError:
        return math.inf if c > 0 else -math.inf


def zeros(degree: int) -> np.ndarray:
    """The zero polynomial of degree ≤ ``degree``."""
    return np.zeros((degree + 1,) * 3)


def from_terms(terms: dict[Monomial, float], degree: int) -> np.ndarray:
    """The dense array of a polynomial given by its terms."""
    array = zeros(degree)
    for (i, j, k), c in terms.items():
        array[i, j, k] += c
    return array


def mask(degree: int) -> np.ndarray:
    """Boolean array of the monomials of degree ≤ ``degree``: the coordinates of the vectors."""
    i, j, k = np.indices((degree + 1,) * 3)
    return i + j + k <= degree


def times(array: np.ndarray, form: SparseForm) -> np.ndarray:
    """``array · form``, truncated to the array's degree (callers keep products within it)."""
    n = array.shape[0]
    result = np.zeros_like(array)
    for (a, b, c), coefficient in form:
        if coefficient:
            result[a:, b:, c:] += coefficient * array[: n - a, : n - b, : n - c]
    return result


def linear_form(normal: np.ndarray, point: np.ndarray) -> SparseForm:
    """``h(p) = normal · (p - point)``."""
    return [((0, 0, 0), -float(normal @ point)), ((1, 0, 0), normal[0]), ((0, 1, 0), normal[1]), ((0, 0, 1), normal[2])]


def squared_distance(point: np.ndarray) -> SparseForm:
    """``ρ(p) = |p - point|²``."""
    cx, cy, cz = point
    return [
        ((0, 0, 0), float(point @ point)),
        ((1, 0, 0), -2 * cx),
        ((0, 1, 0), -2 * cy),
        ((0, 0, 1), -2 * cz),
        ((2, 0, 0), 1.0),
        ((0, 2, 0), 1.0),
        ((0, 0, 2), 1.0),
    ]


def form_product(first: SparseForm, second: SparseForm) -> SparseForm:
    """The product of two small forms, as a form."""
    total: dict[Monomial, float] = {}
    for (a, b, c), u in first:
        for (d, e, g), v in second:
            m = (a + d, b + e, c + g)
            total[m] = total.get(m, 0.0) + u * v
    return list(total.items())


def powers(array: np.ndarray, form: SparseForm, count: int) -> Iterator[np.ndarray]:
    """``array, array·form, array·form², ...`` (``count`` of them), lazily: only the last one is
    kept, so a basis of degree 60 never holds more than a few cubes."""
    current = array
    for k in range(count):
        yield current
        if k + 1 < count:
            current = times(current, form)


def derivative(array: np.ndarray, axis: int) -> np.ndarray:
    """``∂/∂x_axis`` (the degree bound of the array is kept)."""
    n = array.shape[0]
    result = np.zeros_like(array)
    index = [slice(None)] * 3
    index[axis] = slice(1, None)
    shape = [1, 1, 1]
    shape[axis] = n - 1
    factors = np.arange(1, n, dtype=float).reshape(shape)
    target = [slice(None)] * 3
    target[axis] = slice(0, n - 1)
    result[tuple(target)] = array[tuple(index)] * factors
    return result


def scaled(array: np.ndarray, length: float) -> np.ndarray:
    """The coefficients of ``f(length·X)``: entry ``α`` times ``length^|α|``."""
    n = array.shape[0]
    i, j, k = np.indices((n,) * 3)
    return array * float(length) ** (i + j + k)


def evaluate(array: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Values at ``points`` (shape ``(m, 3)``, real or complex), one coordinate at a time."""
    points = np.atleast_2d(points)
    n = array.shape[0]
    exponents = np.arange(n)
    x, y, z = (points[:, a, None] ** exponents for a in range(3))
    inner = np.einsum("ijk,mk->mij", array, z)
    return np.einsum("mi,mi->m", np.einsum("mij,mj->mi", inner, y), x)


def gradient(array: np.ndarray, points: np.ndarray) -> np.ndarray:
    """The gradient at ``points``, shape ``(m, 3)``."""
    return np.column_stack([evaluate(derivative(array, a), points) for a in range(3)])


def restriction_to_line(array: np.ndarray, point: np.ndarray, direction: np.ndarray) -> np.ndarray:
    """Coefficients (lowest degree first) of ``t ↦ f(point + t·direction)``, by a DFT of the
    values at the roots of unity (well conditioned, exact up to rounding)."""
    n = array.shape[0]
    t = np.exp(2j * np.pi * np.arange(n) / n)
    values = evaluate(array, point[None, :] + t[:, None] * direction[None, :])
    return (np.fft.fft(values) / n).real


def real_roots(coefficients: np.ndarray) -> np.ndarray:
    """The real roots of a univariate polynomial (lowest degree first), numerically."""
    c = np.asarray(coefficients, dtype=np.float64)
    top = float(np.abs(c).max(initial=0.0))
    if top == 0.0 or not np.isfinite(top):
        return np.zeros(0)
    c = c / top
    nonzero = np.nonzero(np.abs(c) > 1e-12)[0]
    if len(nonzero) == 0 or nonzero[-1] == 0:
        return np.zeros(0)
    roots = np.roots(c[: nonzero[-1] + 1][::-1])
    real = roots[np.abs(roots.imag) <= 1e-6 * np.maximum(1.0, np.abs(roots))].real
    return real[np.isfinite(real)]


def stack(arrays: Iterable[np.ndarray], selected: np.ndarray) -> np.ndarray:
    """The matrix whose columns are the coefficient vectors of ``arrays``."""
    return np.column_stack([a[selected] for a in arrays])
