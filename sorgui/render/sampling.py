"""Floating-point evaluation of polynomials given as plain terms, for display only.

The render layer never sees the engine's exact polynomials. A worker hands it plain data,
``terms = [((i, j, k), c), ...]`` meaning ``Σ c·x^i·y^j·z^k`` (or ``((i, j), c)`` for the
profile ``p̃(s, r)`` of docs/math.md §3), and this module evaluates it quickly in ``float64``.

Two ideas keep it fast and safe:

* **Tensor grids.** On a grid ``xs × ys × zs`` the polynomial is evaluated by nested Horner
  steps, one axis at a time: first in ``z`` on the ``z`` axis alone, then in ``y`` on the
  ``(y, z)`` plane, and the last step in ``x`` is one matrix product with the powers of the
  ``x`` axis. No full-grid power of any coordinate is ever formed; the cost is one pass over
  the output plus work proportional to the size of one grid plane.
* **Exact power-of-two scaling.** Coordinates are divided by a power of two ``2**e`` that
  bounds them, and coefficients by a power of two of the largest scaled term, using
  ``frexp``/``ldexp`` (exact in binary floating point). Every scaled coefficient is < 1 in
  absolute value and every scaled coordinate ≤ 1, so nothing overflows however large the
  coefficients or the box are, and the zero set and the sign of ``f`` are unchanged.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from math import comb

import numpy as np

Terms = Sequence[tuple[tuple[int, ...], float]]
"""A polynomial as plain data: ``[(exponents, coefficient), ...]``; exponents are ``(i, j, k)``
for ``x^i y^j z^k`` or ``(i, j)`` for ``s^i r^j``."""

_POINT_CHUNK_ELEMENTS = 1 << 20
"""Bound on ``points × coefficients`` per chunk at scattered points (keeps chunks in cache)."""


# --- plain terms -> arrays ------------------------------------------------------------------


def term_arrays(terms: Terms, nvars: int) -> tuple[np.ndarray, np.ndarray]:
    """Validate ``terms`` and return ``(exponents (m, nvars) int64, coefficients (m,) float64)``.

    Repeated exponents are summed and zero coefficients dropped. Raises ``ValueError`` for
    negative or non-integral exponents, a wrong number of variables, or a non-finite
    coefficient (a display layer cannot draw ``inf·x``).
    """
    terms = list(terms)
    exps = np.zeros((len(terms), nvars), dtype=np.int64)
    coefs = np.zeros(len(terms), dtype=np.float64)
    for n, (e, c) in enumerate(terms):
        if len(e) != nvars:
            raise ValueError(f"term {n}: expected {nvars} exponents, got {len(e)}")
        if any(int(k) != k or k < 0 for k in e):
            raise ValueError(f"term {n}: exponents must be non-negative integers, got {e}")
        exps[n] = e
        coefs[n] = float(c)
    if not np.all(np.isfinite(coefs)):
        raise ValueError("coefficients must be finite")
    if len(terms) == 0:
        return exps, coefs
    unique, inverse = np.unique(exps, axis=0, return_inverse=True)
    summed = np.bincount(inverse.ravel(), weights=coefs, minlength=len(unique))
    keep = summed != 0.0
    return unique[keep], summed[keep]


def total_degree(terms: Terms, nvars: int = 3) -> int:
    """The total degree of ``terms`` (``-1`` for the zero polynomial)."""
    exps, _ = term_arrays(terms, nvars)
    return int(exps.sum(axis=1).max()) if len(exps) else -1


def _power_of_two_exponent(magnitude: float) -> int:
    """The smallest ``e`` with ``2**e >= magnitude`` (``0`` when the magnitude is zero)."""
    if not np.isfinite(magnitude):
        raise ValueError("coordinates must be finite")
    if magnitude <= 0.0:
        return 0
    mantissa, exponent = np.frexp(magnitude)
    return int(exponent - 1) if mantissa == 0.5 else int(exponent)


@dataclass(frozen=True, eq=False)
class ScaledCoefficients:
    """Dense coefficients ``C`` with ``f(x) = 2**value_exponent · Σ C[i]·Π (x_v / 2**e_v)^i_v``.

    ``C[i1, ..., in]`` is the scaled coefficient of ``x1^i1 ⋯ xn^in``; ``|C| < 1``.
    ``length_exponents[v] = e_v`` is the power-of-two scale of variable ``v``.
    """

    cube: np.ndarray
    length_exponents: tuple[int, ...]
    value_exponent: int


def scaled_coefficients(terms: Terms, nvars: int, length_scales: Sequence[float]) -> ScaledCoefficients:
    """Scale ``terms`` exactly by powers of two for coordinates bounded by ``length_scales``."""
    exps, coefs = term_arrays(terms, nvars)
    length_exponents = tuple(_power_of_two_exponent(float(abs(s))) for s in length_scales)
    if len(exps) == 0:
        return ScaledCoefficients(np.zeros((1,) * nvars), length_exponents, 0)
    mantissa, exponent = np.frexp(coefs)
    total = exponent.astype(np.int64) + exps @ np.asarray(length_exponents, dtype=np.int64)
    value_exponent = int(total.max())
    shift = np.maximum(total - value_exponent, -2000)
    cube = np.zeros(tuple(exps.max(axis=0) + 1))
    cube[tuple(exps.T)] = np.ldexp(mantissa, shift)
    return ScaledCoefficients(cube, length_exponents, value_exponent)


# --- tensor grids ---------------------------------------------------------------------------


def _horner_last(coefficients: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Contract the last axis of ``coefficients`` with the powers of ``t`` by Horner's rule.

    Returns an array of shape ``coefficients.shape[:-1] + t.shape``.
    """
    out = np.repeat(coefficients[..., -1, None], len(t), axis=-1)
    for k in range(coefficients.shape[-1] - 2, -1, -1):
        out *= t
        out += coefficients[..., k, None]
    return out


def _vandermonde(t: np.ndarray, degree: int) -> np.ndarray:
    """Columns ``t**0, ..., t**degree`` (shape ``(len(t), degree + 1)``) by repeated products."""
    out = np.empty((len(t), degree + 1))
    out[:, 0] = 1.0
    for k in range(1, degree + 1):
        np.multiply(out[:, k - 1], t, out=out[:, k])
    return out


def _finish(values: np.ndarray, value_exponent: int, normalise: bool) -> np.ndarray:
    """Undo the value scaling, or normalise to ``max |f| = 1`` (all ``0`` stays ``0``).

    Scaled values are finite by construction: inputs are validated finite, ``|C| < 1`` and
    scaled coordinates are ``≤ 1``, so ``|f| ≤`` the number of terms.
    """
    if not normalise:
        with np.errstate(over="ignore"):
            unscaled: np.ndarray = np.ldexp(values, value_exponent, out=values)
            return unscaled
    peak = max(float(values.max(initial=0.0)), -float(values.min(initial=0.0)))
    if peak > 0.0:
        values *= 1.0 / peak
    return values


def _axis(t: np.ndarray | Sequence[float], name: str) -> np.ndarray:
    t = np.asarray(t, dtype=np.float64).ravel()
    if len(t) == 0 or not np.all(np.isfinite(t)):
        raise ValueError(f"grid axis {name} must be non-empty and finite")
    return t


def sample_grid(
    terms: Terms,
    xs: np.ndarray | Sequence[float],
    ys: np.ndarray | Sequence[float],
    zs: np.ndarray | Sequence[float],
    normalise: bool = True,
) -> np.ndarray:
    """``f`` on the tensor grid ``xs × ys × zs`` as a C-ordered array of shape ``(nz, ny, nx)``.

    The memory layout has ``x`` fastest, which is VTK's point order for ``vtkImageData``, so
    ``values.ravel()`` can be handed to VTK without a copy. With ``normalise`` the values are
    divided by their largest absolute value (the zero set is unchanged) and never overflow;
    otherwise they are the true values of ``f``, which may overflow to ``±inf``.
    """
    xs, ys, zs = _axis(xs, "x"), _axis(ys, "y"), _axis(zs, "z")
    sc = scaled_coefficients(terms, 3, [np.abs(xs).max(), np.abs(ys).max(), np.abs(zs).max()])
    ex, ey, ez = sc.length_exponents
    x, y, z = np.ldexp(xs, -ex), np.ldexp(ys, -ey), np.ldexp(zs, -ez)
    dx = sc.cube.shape[0] - 1
    g = _horner_last(sc.cube, z)  # (dx+1, dy+1, nz): Horner in z on the z axis
    h = _horner_last(np.ascontiguousarray(g.transpose(0, 2, 1)), y)  # (dx+1, nz, ny)
    # Last step, in x: one matrix product with the powers of the x axis (BLAS, one output pass).
    values = h.reshape(dx + 1, -1).T @ _vandermonde(x, dx).T
    return _finish(values.reshape(len(zs), len(ys), len(xs)), sc.value_exponent, normalise)


def sample_grid_2d(
    terms: Terms,
    ss: np.ndarray | Sequence[float],
    rs: np.ndarray | Sequence[float],
    normalise: bool = True,
) -> np.ndarray:
    """A bivariate ``p̃(s, r)`` on the grid ``ss × rs``, shape ``(nr, ns)`` (``s`` fastest)."""
    ss, rs = _axis(ss, "s"), _axis(rs, "r")
    sc = scaled_coefficients(terms, 2, [np.abs(ss).max(), np.abs(rs).max()])
    es, er = sc.length_exponents
    s, r = np.ldexp(ss, -es), np.ldexp(rs, -er)
    ds = sc.cube.shape[0] - 1
    g = _horner_last(sc.cube, r)  # (ds+1, nr): Horner in r on the r axis
    values = np.ascontiguousarray(g.T @ _vandermonde(s, ds).T)
    return _finish(values, sc.value_exponent, normalise)


# --- scattered points -----------------------------------------------------------------------


def _derivative_vandermonde(powers: np.ndarray) -> np.ndarray:
    """Columns ``d/dt t**k = k·t**(k-1)`` for ``k = 0..degree``, from the powers of ``t``."""
    out = np.zeros_like(powers)
    out[:, 1:] = powers[:, :-1] * np.arange(1, powers.shape[1])
    return out


def _contract_points(
    cube: np.ndarray, powers: list[np.ndarray], dpowers: list[np.ndarray]
) -> tuple[np.ndarray, np.ndarray]:
    """Value and gradient of ``Σ cube[i] Π t_v^i_v`` from the powers of each coordinate.

    Variables are contracted from the last to the first; partial derivatives ride along, each
    with one variable differentiated. ``einsum`` rather than ``@``: these products are long
    and thin, where multithreaded BLAS is slower and its timing erratic.
    """
    n, nvars = len(powers[0]), cube.ndim
    flat = np.ascontiguousarray(cube.reshape(-1, cube.shape[-1]).T)
    value = np.einsum("nk,km->nm", powers[-1], flat).reshape((n,) + cube.shape[:-1])
    partials = [np.einsum("nk,km->nm", dpowers[-1], flat).reshape((n,) + cube.shape[:-1])]
    for v in range(nvars - 2, -1, -1):
        partials = [np.einsum("n...k,nk->n...", q, powers[v]) for q in partials]
        partials.insert(0, np.einsum("n...k,nk->n...", value, dpowers[v]))
        value = np.einsum("n...k,nk->n...", value, powers[v])
    return value, np.stack(partials, axis=-1)


def _points(points: np.ndarray | Sequence[Sequence[float]], nvars: int) -> np.ndarray:
    pts = np.asarray(points, dtype=np.float64)
    if pts.ndim == 1:
        pts = pts[None, :]
    if pts.ndim != 2 or pts.shape[1] != nvars:
        raise ValueError(f"points must have shape (n, {nvars})")
    return pts


def value_and_gradient(
    terms: Terms,
    points: np.ndarray | Sequence[Sequence[float]],
    normalise: bool = False,
) -> tuple[np.ndarray, np.ndarray]:
    """``(f, ∇f)`` at ``points (n, nvars)``, ``nvars`` taken from the points (2 or 3).

    With ``normalise`` both are multiplied by the same positive power of two, chosen so that
    nothing overflows: directions, signs, zero sets and Newton steps ``f/|∇f|`` are exact, the
    magnitudes are not. Without it they are the true values (``±inf`` on overflow).
    Non-finite points give ``nan``.
    """
    pts = _points(points, np.asarray(points).shape[-1])
    nvars = pts.shape[1]
    finite = np.all(np.isfinite(pts), axis=1)
    safe = np.where(finite[:, None], pts, 0.0)
    scale = float(np.abs(safe).max(initial=0.0))
    sc = scaled_coefficients(terms, nvars, [scale] * nvars)
    e = sc.length_exponents[0]
    scaled = np.ldexp(safe, -e)
    powers = [_vandermonde(scaled[:, v], sc.cube.shape[v] - 1) for v in range(nvars)]
    dpowers = [_derivative_vandermonde(p) for p in powers]
    values = np.empty(len(pts))
    grads = np.empty((len(pts), nvars))
    chunk = max(1, _POINT_CHUNK_ELEMENTS // sc.cube.size)
    for start in range(0, len(pts), chunk):
        part = slice(start, start + chunk)
        values[part], grads[part] = _contract_points(sc.cube, [p[part] for p in powers], [d[part] for d in dpowers])
    with np.errstate(over="ignore"):
        if normalise:
            np.ldexp(grads, -e, out=grads)
        else:
            np.ldexp(values, sc.value_exponent, out=values)
            np.ldexp(grads, sc.value_exponent - e, out=grads)
    values[~finite] = np.nan
    grads[~finite] = np.nan
    return values, grads


def newton_step(terms: Terms, points: np.ndarray, max_step: float | np.ndarray) -> np.ndarray:
    """One Newton step ``p - f·∇f/|∇f|²`` of every point towards ``f = 0``.

    The step is shortened so that no coordinate moves by more than ``max_step`` (a scalar or
    one bound per variable): near singular points and thin features the linearisation is
    poor and a vertex must not jump to another sheet. Where ``∇f`` vanishes or is not
    finite the point stays put.
    """
    values, grads = value_and_gradient(terms, points, normalise=True)
    norm2 = np.einsum("ij,ij->i", grads, grads)
    with np.errstate(divide="ignore", invalid="ignore"):
        step = -(values / norm2)[:, None] * grads
        factor = np.min(np.asarray(max_step) / np.abs(step), axis=1, initial=1.0)
    ok = (norm2 > 0.0) & np.isfinite(factor) & np.all(np.isfinite(step), axis=1)
    return points + np.where(ok[:, None], step * factor[:, None], 0.0)


def first_order_distance(terms: Terms, points: np.ndarray | Sequence[Sequence[float]]) -> np.ndarray:
    """``|f(p)| / |∇f(p)|`` at ``points``: the first-order distance from ``p`` to ``f = 0``
    (``nan`` where both vanish, ``inf`` where only the gradient does)."""
    values, grads = value_and_gradient(terms, points)
    with np.errstate(divide="ignore", invalid="ignore"):
        distance: np.ndarray = np.abs(values) / np.linalg.norm(grads, axis=1)
    return distance


def evaluate_points(terms: Terms, points: np.ndarray | Sequence[Sequence[float]]) -> np.ndarray:
    """The true values of ``f`` at ``points (n, nvars)`` (see :func:`value_and_gradient`)."""
    return value_and_gradient(terms, points)[0]


def gradient_points(terms: Terms, points: np.ndarray | Sequence[Sequence[float]]) -> np.ndarray:
    """The true gradients ``∇f`` at ``points (n, nvars)``, shape ``(n, nvars)``."""
    return value_and_gradient(terms, points)[1]


# --- the profile in a plane through the axis ------------------------------------------------


def profile_terms(
    terms: Terms,
    point: Sequence[float],
    direction: Sequence[float],
    u: Sequence[float],
) -> list[tuple[tuple[int, int], float]]:
    """Floating-point ``p̃(s, r) = f(c + s·a + r·u)`` (docs/math.md §3) as bivariate terms.

    The engine computes ``p̃`` exactly; this float version serves previews and tests. Each of
    ``x, y, z`` is an affine form in ``(s, r)``; its powers are expanded by the binomial
    theorem into dense ``(s, r)`` coefficient arrays and combined term by term.
    """
    exps, coefs = term_arrays(terms, 3)
    c, a, w = (np.asarray(v, dtype=np.float64).reshape(3) for v in (point, direction, u))
    degree = int(exps.sum(axis=1).max()) if len(exps) else 0
    size = degree + 1
    # powers[v][k][i, j] = coefficient of s^i r^j in (c_v + a_v s + w_v r)^k
    powers = []
    for v in range(3):
        table = np.zeros((size, size, size))
        for k in range(size):
            for i in range(k + 1):
                for j in range(k - i + 1):
                    multinomial = comb(k, i) * comb(k - i, j)
                    table[k, i, j] = multinomial * a[v] ** i * w[v] ** j * c[v] ** (k - i - j)
        powers.append(table)
    out = np.zeros((size, size))
    for (i, j, k), coef in zip(exps, coefs):
        xy = _multiply_2d(powers[0][i], powers[1][j], size)
        out += coef * _multiply_2d(xy, powers[2][k], size)
    return [((int(i), int(j)), float(out[i, j])) for i, j in zip(*np.nonzero(out))]


def _multiply_2d(p: np.ndarray, q: np.ndarray, size: int) -> np.ndarray:
    """The product of two dense bivariate coefficient arrays, truncated to ``size × size``."""
    out = np.zeros((size, size))
    for i, j in zip(*np.nonzero(p)):
        out[i:, j:] += p[i, j] * q[: size - i, : size - j]
    return out
