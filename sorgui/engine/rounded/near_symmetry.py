"""The floating-point symmetry algebra of a rounded polynomial and its nearest invariant fit
(docs/math.md §8).

Three steps, each in ``float64`` on the normalised input (coordinates scaled by a length ``L``
that balances the coefficients of the lowest and the highest degree; coefficients divided by
the largest one):

1. **Singular values of (★).** The six columns of (★) (``f_x, f_y, f_z`` and the components of
   ``p × ∇f``), the three of each kind scaled by one factor, form a matrix whose small singular values count the
   approximate infinitesimal isometries of ``f``; their right singular vectors are approximate
   Killing fields ``b + a × p``, classified as in §2 (revolution, cylinder of revolution,
   sphere, plane, extrusion) to give a first axis, centre or normal.
2. **Nearest invariant polynomial.** For a candidate axis, the polynomials invariant under the
   rotations about it are spanned by ``h^i ρ^j`` (``h = n·(p - c)``, ``ρ = |p - c|²``); for
   the other kinds by the analogous bases. The nearest one is a weighted linear least-squares
   fit, each coefficient weighted by ``1/e_α`` (the rounding bound of :mod:`.precision`), so the
   residual is measured in units of the input's rounding: ``χ = ‖(f - f̄)/e‖₂/√N ≤ 1`` means
   "within the rounding".
3. **Gauss–Newton on the axis.** The axis parameters (two for the direction, two for the point)
   are refined by Gauss–Newton with a line search on that weighted residual (variable
   projection: the fit is redone at every step), so the axis is as accurate as the digits allow.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import cast

import numpy as np

from ..recognition.symmetry import CYLINDER, EXTRUSION, PLANE, REVOLUTION, SPHERE
from . import dense
from .dense import BoolArray, FloatArray, IntArray
from .precision import Rounding

GN_ITERATIONS = 12
GN_GAIN = 1e-4
"""Gauss–Newton stops when a step lowers the squared residual by less than this fraction."""
FD_STEP = 1e-7
MINIMAX_ROUNDS = 4
LAWSON_STEPS = 40
"""Relinearisations, and reweightings of each, of :func:`refine_minimax`."""


@dataclass(frozen=True)
class Normalised:
    """``f`` as a dense float polynomial in ``X = p / length``, divided by ``scale``, with the
    rounding bound of every coefficient in the same units."""

    degree: int
    length: float
    scale: float
    array: FloatArray
    bounds: FloatArray
    selected: BoolArray

    @property
    def vector(self) -> FloatArray:
        return self.array[self.selected]

    @property
    def weights(self) -> FloatArray:
        return 1.0 / self.bounds[self.selected]


@dataclass(frozen=True)
class Candidate:
    """An approximate symmetry in normalised coordinates: ``kind`` with its ``direction``
    (axis, plane normal or extrusion direction) and ``point`` (on the axis, or the centre)."""

    kind: str
    direction: FloatArray | None
    point: FloatArray | None


@dataclass(frozen=True)
class Fit:
    """The nearest invariant polynomial for a candidate: basis coefficients, residuals."""

    candidate: Candidate
    coefficients: FloatArray
    exponents: tuple[tuple[int, int], ...]
    residual: float
    largest: float
    relative_distance: float
    noise: float


def normalise(coefficients: dict[tuple[int, int, int], float], rounding: Rounding) -> Normalised:
    """Scale coordinates and coefficients so that the float computations are well balanced."""
    degree = rounding.degree
    array = dense.from_terms(coefficients, degree)
    bounds = np.full(array.shape, rounding.default)
    for (i, j, k), e in rounding.bounds.items():
        bounds[i, j, k] = e
    by_degree: dict[int, float] = {}
    for (i, j, k), c in coefficients.items():
        by_degree[i + j + k] = by_degree.get(i + j + k, 0.0) + c * c
    low, high = min(by_degree), max(by_degree)
    length = 1.0
    if high > low:
        length = (math.sqrt(by_degree[low]) / math.sqrt(by_degree[high])) ** (1.0 / (high - low))
        length = min(max(length, 1e-6), 1e6)
    array = dense.scaled(array, length)
    bounds = dense.scaled(bounds, length)
    scale = float(np.abs(array).max())
    return Normalised(degree, length, scale, array / scale, bounds / scale, dense.mask(degree))


# --- 1. the singular values of (★) -------------------------------------------------------------


def killing_system(f: Normalised) -> tuple[FloatArray, FloatArray]:
    """Singular values (largest first, relative to the largest), right singular vectors (rows,
    as ``(b, a)`` in normalised coordinates) of the scaled float system (★)."""
    A = f.array
    fx, fy, fz = (dense.derivative(A, axis) for axis in range(3))
    x, y, z = ([((1, 0, 0), 1.0)], [((0, 1, 0), 1.0)], [((0, 0, 1), 1.0)])
    terms = [dense.times(fz, y), dense.times(fy, z), dense.times(fx, z), dense.times(fz, x), dense.times(fy, x)]
    terms.append(dense.times(fx, y))
    columns = [fx, fy, fz, terms[0] - terms[1], terms[2] - terms[3], terms[4] - terms[5]]
    M = dense.stack(columns, f.selected)
    rotation_scale = root_mean_square(dense.stack(terms, f.selected))
    if len(M) < 6:  # degree 1: fewer monomials than unknowns; zero rows keep all six vectors
        M = np.vstack([M, np.zeros((6 - len(M), 6))])
    return scaled_svd(M, root_mean_square(M[:, :3]), rotation_scale)


def root_mean_square(columns: FloatArray) -> float:
    """The root mean square of the norms of the columns."""
    return float(np.linalg.norm(columns)) / math.sqrt(columns.shape[1])


def scaled_svd(M: FloatArray, translation_scale: float, rotation_scale: float) -> tuple[FloatArray, FloatArray]:
    """Singular values (relative to the largest, largest first) and unit right singular vectors
    (rows) of the six columns ``(b, a)`` of ``M``, the translation columns divided first by
    ``translation_scale`` and the rotation columns by ``rotation_scale``, so that neither kind
    of unknown weighs more for its units. The rotation columns' scale is the size of their two
    terms before they cancel (``y f_z`` and ``z f_y`` for the first), so that a column that
    nearly vanishes stays small: one factor per kind keeps the system equivariant under
    rotations, whereas a column scaled alone to unit length blew up the rotation about a
    coordinate axis that is the surface's axis (and the three of a near-sphere)."""
    norms = np.repeat([translation_scale, rotation_scale], 3)
    norms[norms == 0.0] = 1.0
    _, sigma, vt = np.linalg.svd(M / norms, full_matrices=False)
    vectors = vt / norms[None, :]
    vectors /= np.linalg.norm(vectors, axis=1)[:, None]
    return sigma / (sigma[0] if sigma[0] > 0 else 1.0), vectors


def candidates(vectors: FloatArray, count: int) -> list[Candidate]:
    """The symmetries that the ``count`` smallest singular vectors span (docs/math.md §2)."""
    V = vectors[-count:]
    B, A = V[:, :3].T, V[:, 3:].T  # columns: translation parts b, rotation parts a
    if count == 1:
        b, a = B[:, 0], A[:, 0]
        found = [_rotation(a, b, REVOLUTION)] if np.linalg.norm(a) > 1e-9 else []
        if np.linalg.norm(b) > 1e-9:
            found.append(Candidate(EXTRUSION, _unit(b), None))
        return found
    _, s, wt = np.linalg.svd(A)
    if count == 2:
        t = B @ wt[-1]
        if np.linalg.norm(t) <= 1e-9:  # two rotations and no translation: no cylinder
            return []
        a, b = A @ wt[0], B @ wt[0]
        if np.linalg.norm(a) <= 1e-9:  # two translations and no rotation: no axis to place
            return []
        return [_rotation(a, b, CYLINDER, along=t)]
    if count == 3:
        found = []
        if s[-1] > 1e-3 * s[0]:
            rows = np.vstack([_cross_matrix(A[:, i]) for i in range(3)])
            # numpy's stubs type lstsq's float64 solution as a float of any size
            center = cast(FloatArray, np.linalg.lstsq(-rows, B.T.reshape(-1), rcond=None)[0])
            found.append(Candidate(SPHERE, None, center))
        normal = np.cross(B @ wt[-1], B @ wt[-2])
        if np.linalg.norm(normal) > 1e-12:
            found.append(Candidate(PLANE, _unit(normal), None))
        return found
    return []


def _rotation(a: FloatArray, b: FloatArray, kind: str, along: FloatArray | None = None) -> Candidate:
    """The axis of ``b + a × p``: direction ``a`` (or ``along``), point ``(a × b)/|a|²``."""
    b = b - (a @ b) / (a @ a) * a
    direction = _unit(a if along is None else along)
    return Candidate(kind, direction, np.cross(a, b) / (a @ a))


def _cross_matrix(a: FloatArray) -> FloatArray:
    """The matrix of ``c ↦ a × c`` (a rotation about the centre has ``b = c × a = -(a × c)``)."""
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def _unit(v: FloatArray) -> FloatArray:
    return v / np.linalg.norm(v)


# --- 2. the nearest invariant polynomial ---------------------------------------------------------


def invariant_basis(
    candidate: Candidate,
    degree: int,
    selected: BoolArray,
    point: FloatArray | None = None,
    direction: FloatArray | None = None,
) -> tuple[FloatArray, list[tuple[int, int]]]:
    """A basis of the polynomials of degree ≤ ``degree`` invariant under the candidate's group,
    as the columns of a matrix over the monomials ``selected``, with the exponents ``(i, j)`` of
    each element ``h^i ρ^j`` (``(i, j)`` = powers of the two coordinates ``u·p, w·p`` for an
    extrusion). ``point``/``direction`` override the candidate's (they need not be unit: an
    exact integer direction keeps ``h`` exact)."""
    kind = candidate.kind
    n = candidate.direction if direction is None else direction
    c = candidate.point if point is None else point
    one = dense.from_terms({(0, 0, 0): 1.0}, degree)
    columns: list[FloatArray] = []
    exponents: list[tuple[int, int]] = []

    def grid(first: dense.SparseForm, second: dense.SparseForm, first_weight: int, second_count: int) -> None:
        """``second^j · first^i`` for ``first_weight·j + i ≤ degree`` (the weight of ``second``)."""
        for j, outer in enumerate(dense.powers(one, second, second_count)):
            for i, term in enumerate(dense.powers(outer, first, degree - first_weight * j + 1)):
                columns.append(term[selected])
                exponents.append((i, j))

    if kind == PLANE:
        assert n is not None  # a plane's candidate has its normal
        grid(dense.linear_form(n, np.zeros(3)), [], 1, 1)
    elif kind == SPHERE:
        assert c is not None  # a sphere's candidate has its centre
        for j, term in enumerate(dense.powers(one, dense.squared_distance(c), degree // 2 + 1)):
            columns.append(term[selected])
            exponents.append((0, j))
    elif kind == EXTRUSION:
        assert n is not None  # an extrusion's candidate has its direction
        u = _unit(np.cross(n, _least_aligned(n)))
        w = np.cross(_unit(n), u)
        grid(dense.linear_form(u, np.zeros(3)), dense.linear_form(w, np.zeros(3)), 1, degree + 1)
    elif kind == CYLINDER:
        assert n is not None and c is not None  # an axis: direction and point (_rotation)
        h, rho = dense.linear_form(n, c), dense.squared_distance(c)
        # |a|²·|p - c|² - (a·(p - c))²: the squared distance to the axis, times |a|².
        across = [(m, float(n @ n) * v) for m, v in rho] + [(m, -v) for m, v in dense.form_product(h, h)]
        for j, term in enumerate(dense.powers(one, across, degree // 2 + 1)):
            columns.append(term[selected])
            exponents.append((0, j))
    else:
        assert n is not None and c is not None  # an axis: direction and point (_rotation)
        grid(dense.linear_form(n, c), dense.squared_distance(c), 2, degree // 2 + 1)
    return np.column_stack(columns), exponents


def _least_aligned(n: FloatArray) -> FloatArray:
    e = np.zeros(3)
    e[int(np.argmin(np.abs(n)))] = 1.0
    return e


def fit(
    f: Normalised, candidate: Candidate, point: FloatArray | None = None, direction: FloatArray | None = None
) -> Fit:
    """The nearest invariant polynomial in the weighted least-squares sense (step 2)."""
    basis, exponents = invariant_basis(candidate, f.degree, f.selected, point, direction)
    w = f.weights
    weighted = basis * w[:, None]
    norms = np.linalg.norm(weighted, axis=0)
    norms[norms == 0.0] = 1.0
    target = f.vector * w
    solution, _, _, sv = np.linalg.lstsq(weighted / norms, target, rcond=None)
    coefficients = solution / norms
    fitted = basis @ coefficients
    residual = (f.vector - fitted) * w
    count = len(residual)
    condition = float(sv[0] / sv[-1]) if sv[-1] > 0 else math.inf
    noise = 4 * np.finfo(float).eps * condition * float(np.linalg.norm(target)) / math.sqrt(count)
    degrees = _degrees(f)
    unscaled = (f.vector - fitted) / f.length**degrees
    original = f.vector / f.length**degrees
    return Fit(
        candidate=Candidate(
            candidate.kind,
            candidate.direction if direction is None else direction,
            candidate.point if point is None else point,
        ),
        coefficients=coefficients,
        exponents=tuple(exponents),
        residual=float(np.linalg.norm(residual) / math.sqrt(count)),
        largest=float(np.abs(residual).max()),
        relative_distance=float(np.linalg.norm(unscaled) / np.linalg.norm(original)),
        noise=float(noise),
    )


def _degrees(f: Normalised) -> IntArray:
    shape: tuple[int, int, int] = f.array.shape
    i, j, k = np.indices(shape)
    degrees: IntArray = (i + j + k)[f.selected]
    return degrees


# --- 3. Gauss–Newton on the axis -----------------------------------------------------------------


def refine(f: Normalised, candidate: Candidate) -> Fit:
    """Refine the candidate's parameters by Gauss–Newton on the weighted residual (step 3)."""
    params, build = parametrisation(candidate)
    if len(params) == 0:
        return fit(f, candidate)
    return fit(f, build(gauss_newton(_free_residual(f, build), params)[0]))


def refit_point(f: Normalised, candidate: Candidate, direction: FloatArray) -> FloatArray:
    """The point of the axis along ``direction`` (held: a snapped exact direction) that fits
    ``f`` best, by Gauss–Newton on its two offsets across the axis from ``candidate``'s point.
    An exact direction turns the fitted axis about that point, and far from it (the vertex of a
    paraboloid 250 units away) the turned axis leaves the rounding."""
    params, build = parametrisation(Candidate(candidate.kind, _unit(direction), candidate.point))
    if len(params) != 4:
        assert candidate.point is not None  # only an axis has a point to move across it
        return candidate.point

    def moved(theta: FloatArray) -> Candidate:
        return build(np.concatenate([np.zeros(2), theta]))

    point = moved(gauss_newton(_free_residual(f, moved), np.zeros(2))[0]).point
    assert point is not None  # an axis keeps its point
    return point


def _free_residual(f: Normalised, build: Callable[[FloatArray], Candidate]) -> Callable[[FloatArray], FloatArray]:
    """The weighted residual of the nearest invariant polynomial of the candidate ``build(θ)``,
    its coefficients free (variable projection: the fit is redone at every ``θ``)."""

    def residual_vector(theta: FloatArray) -> FloatArray:
        basis = invariant_basis(build(theta), f.degree, f.selected)[0] * f.weights[:, None]
        norms = np.linalg.norm(basis, axis=0)
        norms[norms == 0.0] = 1.0
        target = f.vector * f.weights
        solution, *_ = np.linalg.lstsq(basis / norms, target, rcond=None)
        remainder: FloatArray = target - (basis / norms) @ solution
        return remainder

    return residual_vector


def plain_distance(f: Normalised, candidate: Candidate) -> float:
    """The one figure of how far ``f`` is from the symmetry of ``candidate``'s kind:
    ``min ‖f − f̄‖₂ / ‖f‖₂`` over the input's own coefficients, ``f̄`` invariant, the axis (or
    centre, or normal) refined by Gauss–Newton from ``candidate``'s for this plain norm. It
    does not depend on the tolerance, whose rounding weights only the fit that decides
    nearness (the residual): the same input is the same distance away with every tolerance."""
    weights = 1.0 / f.length ** _degrees(f)
    target = f.vector * weights

    def remainder(c: Candidate) -> FloatArray:
        basis = invariant_basis(c, f.degree, f.selected)[0] * weights[:, None]
        norms = np.linalg.norm(basis, axis=0)
        norms[norms == 0.0] = 1.0
        solution, *_ = np.linalg.lstsq(basis / norms, target, rcond=None)
        rest: FloatArray = (target - (basis / norms) @ solution) / np.linalg.norm(target)
        return rest

    params, build = parametrisation(candidate)
    if len(params):
        params = gauss_newton(lambda theta: remainder(build(theta)), params)[0]
    return float(np.linalg.norm(remainder(build(params) if len(params) else candidate)))


def refine_fixed(
    f: Normalised, candidate: Candidate, coefficients: FloatArray
) -> tuple[Candidate, FloatArray, FloatArray]:
    """Refine the axis (or centre, or normal) with the invariant's coefficients held fixed: once
    they are snapped, the axis is determined more sharply than with them free. Returns the
    refined candidate and the standard errors of its direction's and point's coordinates (from
    the Gauss–Newton Jacobian, each residual having unit variance in rounding units)."""
    params, scaled, residual_vector = _fixed_problem(f, candidate, coefficients, free_scale=True)
    theta, jacobian = gauss_newton(residual_vector, params)
    refined = scaled(theta)
    covariance = np.linalg.pinv(jacobian.T @ jacobian)
    n = refined.direction
    if n is None:
        return refined, np.zeros(3), np.sqrt(np.abs(np.diag(covariance)))
    e1 = _unit(np.cross(n, _least_aligned(n)))
    frame = np.column_stack([e1, np.cross(_unit(n), e1)])
    direction_sigma = np.sqrt(np.abs(np.diag(frame @ covariance[:2, :2] @ frame.T)))
    point_sigma = np.zeros(3)
    if len(theta) == 4:
        point_sigma = np.sqrt(np.abs(np.diag(frame @ covariance[2:, 2:] @ frame.T)))
    return refined, direction_sigma, point_sigma


def refine_minimax(
    f: Normalised, candidate: Candidate, coefficients: FloatArray, *, point_fixed: bool = False
) -> Candidate:
    """The axis (or centre, or normal) with the coefficients held fixed that makes the *largest*
    weighted residual smallest, from ``candidate`` (the least-squares one): "every coefficient
    within its rounding" is a bound on the largest, and the least-squares axis can miss it where
    the axis the input was printed from keeps it. Lawson's iteratively reweighted least squares
    on the linearised problem (docs/math.md §8.5), relinearised a few times. With
    ``point_fixed``, an axis keeps its point (already snapped) and only turns."""
    params, scaled, residual_vector = _fixed_problem(f, candidate, coefficients)
    if point_fixed and candidate.direction is not None and len(params) == 4:
        turned, whole = scaled, residual_vector
        params = params[:2]

        def scaled(theta: FloatArray) -> Candidate:
            return turned(np.concatenate([theta, np.zeros(2)]))

        def residual_vector(theta: FloatArray) -> FloatArray:
            return whole(np.concatenate([theta, np.zeros(2)]))

    if not len(params):
        return candidate
    return scaled(lawson(residual_vector, params))


def lawson(residual_vector: Callable[[FloatArray], FloatArray], theta: FloatArray) -> FloatArray:
    """The parameters near ``theta`` that make the largest entry of ``residual_vector`` smallest:
    Lawson's iteratively reweighted least squares on the linearised problem, relinearised
    :data:`MINIMAX_ROUNDS` times while the largest residual falls."""
    r = residual_vector(theta)
    for _ in range(MINIMAX_ROUNDS):
        jacobian = forward_jacobian(residual_vector, theta, r)
        weights = np.full(len(r), 1.0 / len(r))
        step = np.zeros(len(theta))
        for _ in range(LAWSON_STEPS):
            root = np.sqrt(weights)
            step, *_ = np.linalg.lstsq(jacobian * root[:, None], -r * root, rcond=None)
            weights = weights * np.abs(r + jacobian @ step)
            total = float(weights.sum())
            if total == 0.0:
                break
            weights /= total
        trial = residual_vector(theta + step)
        if np.abs(trial).max() >= np.abs(r).max():
            break
        theta, r = theta + step, trial
    return theta


def _fixed_problem(
    f: Normalised, candidate: Candidate, coefficients: FloatArray, *, free_scale: bool = False
) -> tuple[FloatArray, Callable[[FloatArray], Candidate], Callable[[FloatArray], FloatArray]]:
    """The axis parameters around ``candidate``, the candidate they give (its direction as long
    as the given one), and the weighted residual of the fixed invariant there; with
    ``free_scale``, of the fixed invariant times the factor that fits best (variable
    projection): the coefficients then fix the surface, not the scale of its equation."""
    params, build = parametrisation(candidate)
    length = 1.0 if candidate.direction is None else float(np.linalg.norm(candidate.direction))

    def scaled(theta: FloatArray) -> Candidate:
        c = build(theta)
        return c if c.direction is None else Candidate(c.kind, c.direction * length, c.point)

    def residual_vector(theta: FloatArray) -> FloatArray:
        basis = invariant_basis(scaled(theta), f.degree, f.selected)[0]
        target, fitted = f.vector * f.weights, (basis @ coefficients) * f.weights
        if free_scale and fitted @ fitted > 0.0:
            fitted = fitted * float(target @ fitted / (fitted @ fitted))
        residual: FloatArray = target - fitted
        return residual

    return params, scaled, residual_vector


def forward_jacobian(residual: Callable[[FloatArray], FloatArray], theta: FloatArray, r: FloatArray) -> FloatArray:
    """The Jacobian of ``residual`` at ``theta`` (where it is ``r``) by forward differences."""
    return np.column_stack([(residual(theta + FD_STEP * e) - r) / FD_STEP for e in np.eye(len(theta))])


def gauss_newton(residual: Callable[[FloatArray], FloatArray], theta: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Minimise ``‖residual(θ)‖²`` by Gauss–Newton with a forward-difference Jacobian and a
    halving line search, from ``theta``; returns ``θ`` and the last Jacobian."""
    r = residual(theta)

    for _ in range(GN_ITERATIONS):
        jacobian = forward_jacobian(residual, theta, r)
        step, *_ = np.linalg.lstsq(jacobian, -r, rcond=None)
        for factor in (1.0, 0.5, 0.25, 0.125):
            trial = theta + factor * step
            r_trial = residual(trial)
            if r_trial @ r_trial < r @ r:
                break
        else:
            break
        gain = 1.0 - (r_trial @ r_trial) / (r @ r)
        theta, r = trial, r_trial
        if gain < GN_GAIN:
            break
    return theta, forward_jacobian(residual, theta, r)


def parametrisation(candidate: Candidate) -> tuple[FloatArray, Callable[[FloatArray], Candidate]]:
    """Local coordinates around the candidate: offsets of the direction (in two perpendicular
    directions) and of the point (across the axis; all three for a sphere's centre)."""
    kind, n, c = candidate.kind, candidate.direction, candidate.point
    if kind == SPHERE:
        assert c is not None  # a sphere's candidate has its centre
        return np.zeros(3), lambda t: Candidate(SPHERE, None, c + t)
    assert n is not None  # every kind but a sphere has a direction
    e1 = _unit(np.cross(n, _least_aligned(n)))
    e2 = np.cross(n, e1)

    def direction(t: FloatArray) -> FloatArray:
        return _unit(n + t[0] * e1 + t[1] * e2)

    if kind in (PLANE, EXTRUSION):
        return np.zeros(2), lambda t: Candidate(kind, direction(t), None)
    assert c is not None  # an axis: direction and point (_rotation)
    return np.zeros(4), lambda t: Candidate(kind, direction(t), c + t[2] * e1 + t[3] * e2)
