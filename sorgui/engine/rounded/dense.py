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
from collections.abc import Iterable, Iterator, Sequence
from typing import TYPE_CHECKING, TypeAlias, overload

import numpy as np
from flint import fmpq
from numpy.typing import NDArray

if TYPE_CHECKING:
    from ..algebra.polys import Poly

Monomial: TypeAlias = tuple[int, int, int]
SparseForm: TypeAlias = list[tuple[Monomial, float]]
"""A small polynomial (a linear or quadratic form) as ``[(monomial, coefficient), ...]``."""
FloatArray: TypeAlias = NDArray[np.float64]
"""A ``float64`` array: a dense polynomial, a point or vector, a matrix of coefficient vectors."""
ComplexArray: TypeAlias = NDArray[np.complex128]
"""A ``complex128`` array: points off the real space (the roots of unity of a restriction)."""
IntArray: TypeAlias = NDArray[np.int_]
"""An integer array: the degrees of monomials."""
BoolArray: TypeAlias = NDArray[np.bool_]
"""A boolean array: the monomials selected by :func:`mask`."""


def monomial(exponents: Sequence[int]) -> Monomial:
    """The exponents ``(i, j, k)`` of a monomial ``x^i y^j z^k`` as Python integers."""
    i, j, k = exponents
    return int(i), int(j), int(k)


def float_coefficients(f: Poly) -> dict[Monomial, float]:
    """The coefficients of the exact ``f`` as floats (exact rationals rounded once). The exact
    layer (sympy) is imported here only: the rest of this module is numpy, for the 3D view too."""
    from ..algebra.polys import is_rational_field, to_flint

    if is_rational_field(f.ring.domain):
        return {monomial(m): _float(c) for m, c in to_flint(f).to_dict().items()}
    K = f.ring.domain
    return {monomial(m): float(K.to_sympy(c).evalf(20)) for m, c in f.items()}


def _float(c: fmpq) -> float:
    """``c`` as a float, ``±inf`` beyond the float range (the caller refuses those)."""
    try:
        return float(c)
    except OverflowError:
        return math.inf if c > 0 else -math.inf


def zeros(degree: int) -> FloatArray:
    """The zero polynomial of degree ≤ ``degree``."""
    return np.zeros((degree + 1,) * 3)


def from_terms(terms: dict[Monomial, float], degree: int) -> FloatArray:
    """The dense array of a polynomial given by its terms."""
    array = zeros(degree)
    for (i, j, k), c in terms.items():
        array[i, j, k] += c
    return array


def mask(degree: int) -> BoolArray:
    """Boolean array of the monomials of degree ≤ ``degree``: the coordinates of the vectors."""
    i, j, k = np.indices((degree + 1,) * 3)
    selected: BoolArray = i + j + k <= degree
    return selected


def times(array: FloatArray, form: SparseForm) -> FloatArray:
    """``array · form``, truncated to the array's degree (callers keep products within it)."""
    n = array.shape[0]
    result = np.zeros_like(array)
    for (a, b, c), coefficient in form:
        if coefficient:
            result[a:, b:, c:] += coefficient * array[: n - a, : n - b, : n - c]
    return result


def linear_form(normal: FloatArray, point: FloatArray) -> SparseForm:
    """``h(p) = normal · (p - point)``."""
    return [((0, 0, 0), -float(normal @ point)), ((1, 0, 0), normal[0]), ((0, 1, 0), normal[1]), ((0, 0, 1), normal[2])]


def squared_distance(point: FloatArray) -> SparseForm:
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


def powers(array: FloatArray, form: SparseForm, count: int) -> Iterator[FloatArray]:
    """``array, array·form, array·form², ...`` (``count`` of them), lazily: only the last one is
    kept, so a basis of degree 60 never holds more than a few cubes."""
    current = array
    for k in range(count):
        yield current
        if k + 1 < count:
            current = times(current, form)


def derivative(array: FloatArray, axis: int) -> FloatArray:
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


def scaled(array: FloatArray, length: float) -> FloatArray:
    """The coefficients of ``f(length·X)``: entry ``α`` times ``length^|α|``."""
    n = array.shape[0]
    i, j, k = np.indices((n,) * 3)
    result: FloatArray = array * float(length) ** (i + j + k)
    return result


def translated(array: FloatArray, point: FloatArray) -> FloatArray:
    """The coefficients of ``f(point + X)``: each variable shifted in turn by the binomial
    expansion ``(x + a)^i = Σ_j C(i, j) a^(i − j) x^j``."""
    n = array.shape[0]
    i, j = np.indices((n, n))
    binomials = np.array([[math.comb(int(a), int(b)) if b <= a else 0 for b in range(n)] for a in range(n)], float)
    result: FloatArray = array
    for axis, shift in enumerate(np.asarray(point, dtype=np.float64)):
        with np.errstate(all="ignore"):
            matrix = np.where(j <= i, binomials * float(shift) ** np.maximum(i - j, 0), 0.0)  # [i, j]: x^i to x^j
        result = np.moveaxis(np.tensordot(np.moveaxis(result, axis, -1), matrix, axes=([-1], [0])), -1, axis)
    return result


@overload
def evaluate(array: FloatArray, points: FloatArray) -> FloatArray: ...


@overload
def evaluate(array: FloatArray, points: ComplexArray) -> ComplexArray: ...


def evaluate(array: FloatArray, points: FloatArray | ComplexArray) -> FloatArray | ComplexArray:
    """Values at ``points`` (shape ``(m, 3)``, real or complex), one coordinate at a time."""
    rows = np.atleast_2d(points)
    n = array.shape[0]
    exponents = np.arange(n)
    x, y, z = (rows[:, a, None] ** exponents for a in range(3))
    inner = np.einsum("ijk,mk->mij", array, z)
    values: FloatArray | ComplexArray = np.einsum("mi,mi->m", np.einsum("mij,mj->mi", inner, y), x)
    return values


def gradient(array: FloatArray, points: FloatArray) -> FloatArray:
    """The gradient at ``points``, shape ``(m, 3)``."""
    return np.column_stack([evaluate(derivative(array, a), points) for a in range(3)])


def restriction_to_line(array: FloatArray, point: FloatArray, direction: FloatArray) -> FloatArray:
    """Coefficients (lowest degree first) of ``t ↦ f(point + t·direction)``, by a DFT of the
    values at the roots of unity (well conditioned, exact up to rounding)."""
    n = array.shape[0]
    t = np.exp(2j * np.pi * np.arange(n) / n)
    values = evaluate(array, point[None, :] + t[:, None] * direction[None, :])
    coefficients: FloatArray = (np.fft.fft(values) / n).real
    return coefficients


def stack(arrays: Iterable[FloatArray], selected: BoolArray) -> FloatArray:
    """The matrix whose columns are the coefficient vectors of ``arrays``."""
    return np.column_stack([a[selected] for a in arrays])
