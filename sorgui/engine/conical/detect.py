"""Whether ``X = {f = 0}`` is a cone or a cylinder over some curve (docs/math.md §10).

Both questions are linear over ``K`` and share one matrix ``M``, whose columns are the
coefficient vectors of ``∂f/∂x, ∂f/∂y, ∂f/∂z``:

- a *cylinder* along ``a`` is invariant under the translations ``X ↦ X + s·a``, i.e.
  ``a·∇f = 0`` identically: the directions are the null space of ``M``;
- a *cone* with apex ``c`` is a union of lines through ``c``: ``f(c + X)`` is homogeneous of
  degree ``d``, i.e. by Euler's identity ``∇f(X)·(X − c) = d·f(X)``, that is
  ``M c = (X·∇f − d·f)``: the apexes are the solutions of one linear system.

Both are exact identities in ``K[x, y, z]``, so a solution is a proof (Alcázar and Goldman,
IEEE TVCG 2016, decide the same from ``f``). A cone whose apex is not unique (the set of apexes
is ``c + null space``) is also a cylinder: planes through a line, reported as a cylinder.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ..algebra.linalg import Vector, nullspace, primitive_vector, rref
from ..algebra.polys import Poly, derivative, to_expr, total_degree

if TYPE_CHECKING:
    from ..rounded.dense import Monomial
    from ..rounded.precision import Rounding

NEAR_FACTOR = 10.0
"""How many times the rounding a rounded cone's Euler residual may reach (docs/math.md §10)."""


@dataclass(frozen=True)
class Conicity:
    """The exact answer of :func:`detect`: the translation directions of ``X`` (a basis of the
    null space of ``M``) and, when ``f(c + X)`` is homogeneous for some ``c``, one such apex."""

    directions: tuple[Vector, ...]
    apex: Vector | None

    @property
    def kind(self) -> str:
        """``cylinder`` (some translation leaves ``f`` invariant), ``cone`` (one apex), or ``none``."""
        if self.directions:
            return "cylinder"
        return "cone" if self.apex is not None else "none"


def _system(f: Poly) -> tuple[list[list[Any]], list[Any], list[Monomial]]:
    """The rows of ``M`` and the right-hand side ``X·∇f − d·f``, one per monomial (and those
    monomials)."""
    K = f.ring.domain
    d = total_degree(f)
    gradient = [derivative(f, i) for i in range(3)]
    x, y, z = f.ring.gens
    euler: Poly = x * gradient[0] + y * gradient[1] + z * gradient[2] - d * f
    columns = [dict(g.items()) for g in gradient]
    rhs = dict(euler.items())
    monomials = sorted(set(rhs).union(*columns))
    rows = [[column.get(m, K.zero) for column in columns] for m in monomials]
    return rows, [rhs.get(m, K.zero) for m in monomials], monomials


def detect(f: Poly) -> Conicity:
    """The translations of ``f`` and an apex, from the one linear system above over ``K``."""
    K = f.ring.domain
    rows, rhs, _monomials = _system(f)
    directions = tuple(primitive_vector(v, K) for v in nullspace(rows, 3, K))
    augmented = [[*row, b] for row, b in zip(rows, rhs)]
    reduced, pivots = rref(augmented, 4, K)
    if 3 in pivots:
        return Conicity(directions, None)
    apex = [K.zero] * 3
    for row, p in zip(reduced, pivots):
        apex[p] = row[3]  # the free coordinates (a direction of translation) are set to 0
    return Conicity(directions, tuple(apex))


def near_apex(f: Poly, rounding: Rounding) -> tuple[tuple[float, float, float], float] | None:
    """For rounded input that is no exact cone: the least-squares apex ``c`` of
    ``M c = X·∇f − d·f`` in floating point, each row weighted by its bound (:data:`WEIGHTINGS`
    times), and its residual, relative to ``d·max|f|·(1 + |c|)``;
    ``None`` unless every row's residual is within :data:`NEAR_FACTOR` times what rounding the
    coefficients of an exact cone by their bounds leaves there (:func:`_row_bounds`) and ``M``
    has full rank (no near translation)."""
    import numpy as np  # rounded input only: an exact analysis need not load numpy

    f, k = at_unit_scale(f)
    K = f.ring.domain
    if _definite_top(f, rounding.tolerance):
        return None
    rows, rhs, monomials = _system(f)
    M = np.array([[float(to_expr(K, c)) for c in row] for row in rows])
    b = np.array([float(to_expr(K, c)) for c in rhs])
    # in units of the largest entry: a part printed times 1e300 overflowed the SVD's squares
    unit = max(float(np.abs(M).max(initial=0.0)), float(np.abs(b).max(initial=0.0)))
    if not (np.isfinite(unit) and unit > 0):
        return None
    M, b = M / unit, b / unit
    size = max(abs(float(to_expr(K, c))) for c in f.values()) / unit

    def bounds(apex: Any) -> Any:  # noqa: ANN401 - numpy
        return _row_bounds(monomials, apex, total_degree(f), rounding, k) / unit

    singular = np.linalg.svd(M, compute_uv=False)
    if len(singular) < 3 or singular[-1] <= NEAR_FACTOR * rounding.tolerance * singular[0]:
        return None
    apex, *_ = np.linalg.lstsq(M, b, rcond=None)
    for _ in range(WEIGHTINGS):  # each row in units of its bound (which the apex moves)
        weights = 1.0 / bounds(apex)
        apex, *_ = np.linalg.lstsq(M * weights[:, None], b * weights, rcond=None)
    misses = np.abs(M @ apex - b)
    if np.any(misses > NEAR_FACTOR * bounds(apex)):
        return None
    residual = float(misses.max()) / (total_degree(f) * size * (1 + float(np.linalg.norm(apex))))
    x, y, z = (float(v) * 10.0**k for v in _decimal_apex(apex, lambda c: bool(np.all(np.abs(M @ c - b) <= bounds(c)))))
    return (x, y, z), residual


APEX_PLACES = tuple(10.0**-e for e in range(1, 12))
"""The radii (times ``1 + |c|``) within which :func:`_decimal_apex` looks for a decimal apex."""


def _decimal_apex(apex: Any, consistent: Callable[[Any], bool]) -> Any:  # noqa: ANN401 - numpy
    """The apex of fewest decimal places near the least-squares ``apex`` that is ``consistent``
    with the rounding (every row of ``M c − b`` within its bound, which the exact cone's apex
    meets), else ``apex``: a cone printed with ``%.6g`` about ``(3.1, −2.4, 5.05)`` was "nearly
    a cone about (3.09999, −2.4, 5.05)"."""
    import numpy as np  # rounded input only

    from ..rounded.directions import decimal_near

    scale = 1.0 + float(np.linalg.norm(apex))
    for radius in APEX_PLACES:
        candidate = np.array([float(decimal_near(float(v), radius * scale)) for v in apex])
        if consistent(candidate):
            return candidate
    return apex


def _row_bounds(monomials: list[Monomial], apex: Any, degree: int, rounding: Rounding, k: int) -> Any:  # noqa: ANN401 - numpy
    """What rounding each coefficient of an exact cone by its bound (of ``f(10ᵏ·p)``: times
    ``10^(k·|α|)``) leaves at most in the row of each monomial ``m`` of ``M c − b``:
    ``Σᵢ |cᵢ|·(mᵢ + 1)·e(m + eᵢ) + |d − |m||·e(m)``. A single relative tolerance measured a cone
    printed with ``%.6f`` (bounds of 5e-7 on every coefficient, the constant 6869) against its
    largest coefficient: after the unit scaling its quadratic terms' bounds were 10⁴ times
    larger, and the cone was not "nearly a cone" (its view a ball of radius 1 beside its apex)."""
    import numpy as np  # rounded input only

    def bound(m: Monomial) -> float:
        return rounding.bound(m) * 10.0 ** (k * sum(m))

    bounds = []
    for m in monomials:
        shifted = [(m[0] + 1, m[1], m[2]), (m[0], m[1] + 1, m[2]), (m[0], m[1], m[2] + 1)]
        moved = sum(abs(float(apex[i])) * (m[i] + 1) * bound(shifted[i]) for i in range(3))
        bounds.append(moved + abs(degree - sum(m)) * bound(m))
    return np.array(bounds)


WEIGHTINGS = 3
"""Weighted least-squares solutions of :func:`near_apex`, each with the rows' bounds at the last."""

SPHERE_POINTS = 400
"""Directions on which :func:`_definite_top` evaluates the top form."""


def _definite_top(f: Poly, tolerance: float) -> bool:
    """Whether the top homogeneous part of ``f`` keeps one sign on the unit sphere, farther from 0
    than :data:`NEAR_FACTOR` times the rounding of its largest value: then every cone within the
    rounding has no real point but its apex (a torus 8 cm across about ``(5, 0, 0)`` with two
    printed digits was "nearly a cone" about its centre, the point ``(x² + y² + z²)² = 0``, and
    its view was grown to a ball of radius 2.5 about that apex)."""
    import numpy as np  # rounded input only

    K = f.ring.domain
    degree = total_degree(f)
    top = [(m, float(to_expr(K, c))) for m, c in f.items() if sum(m) == degree]
    index = np.arange(SPHERE_POINTS) + 0.5
    height = 1 - 2 * index / SPHERE_POINTS
    angle = np.pi * (1 + 5**0.5) * index
    across = np.sqrt(1 - height**2)
    x, y, z = across * np.cos(angle), across * np.sin(angle), height
    values = sum((c * x ** m[0] * y ** m[1] * z ** m[2] for m, c in top), np.zeros(SPHERE_POINTS))
    bound = NEAR_FACTOR * tolerance * float(np.abs(values).max(initial=0.0))
    return bool(bound > 0 and (values.min() > bound or values.max() < -bound))


def at_unit_scale(f: Poly) -> tuple[Poly, int]:
    """``f(10ᵏ·p)`` and ``k``, with ``10ᵏ`` near the size of the part
    (:func:`..rounded.deviation.part_size`) when that is below 0.1 or above 10, else ``f`` and
    0. The near tests compare coefficients: a torus 4 cm across written in metres, whose lower
    terms are small beside ``(x² + y² + z²)²``, read as nearly the cone ``(x² + y² + z²)² = 0``;
    one 8 m across written in mm, whose lower terms are large, as nearly a cone far away."""
    import math

    from ..rounded import dense
    from ..rounded.deviation import part_size

    length = part_size(dense.from_terms(dense.float_coefficients(f), total_degree(f)))
    if length is None or 0.1 <= length <= 10 or not math.isfinite(length):
        return f, 0
    k = round(math.log10(length))
    K = f.ring.domain
    scale = K.convert(10) ** k if k > 0 else K.one / K.convert(10) ** (-k)
    return f.ring.from_dict({m: c * scale ** sum(m) for m, c in f.items()}), k


def near_direction(f: Poly, tolerance: float) -> tuple[tuple[float, float, float], float] | None:
    """For rounded input that is no exact cylinder: the direction ``a`` of a cylinder within the
    rounding, the right singular vector of ``M`` (``M a = 0`` for an exact one) whose singular
    value is within :data:`NEAR_FACTOR` times the rounding of the largest, and that ratio (the
    relative residual ``|M a| / |M|``); ``None`` unless exactly one such direction exists."""
    import numpy as np  # rounded input only

    f, _k = at_unit_scale(f)  # a direction is the same at any scale
    K = f.ring.domain
    rows, _rhs, _monomials = _system(f)
    M = np.array([[float(to_expr(K, c)) for c in row] for row in rows])
    unit = float(np.abs(M).max(initial=0.0))  # the SVD's squares overflowed for a part times 1e300
    if not (np.isfinite(unit) and unit > 0):
        return None
    _u, singular, vt = np.linalg.svd(M / unit)
    if len(singular) < 3 or singular[0] == 0:
        return None
    small = singular <= NEAR_FACTOR * tolerance * singular[0]
    if int(small.sum()) != 1 or not small[-1]:
        return None
    a = vt[-1] / np.linalg.norm(vt[-1])
    a = a if a[int(np.argmax(np.abs(a)))] > 0 else -a
    x, y, z = (float(v) for v in a)
    return (x, y, z), float(singular[-1] / singular[0])
