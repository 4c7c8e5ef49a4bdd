"""The symmetry algebra ``L`` of ``f`` and the classification of surfaces by it (docs/math.md §2).

``L`` is the solution space of the identity

    ∇f(p) · (b + a × p) ≡ 0   as a polynomial in x, y, z,           (★)

with six unknowns ``(a, b) ∈ K⁶``: the Lie algebra of infinitesimal rigid motions that leave
every level set ``f = α`` invariant. Each monomial of (★) gives one linear equation, so ``L`` is
a null space over ``K``; its dimension and structure classify the surface (the table of §2), and
a rotation in ``L`` gives the axis with a ``K``-rational point and direction (the paper's
Corollary on ``K``-rational axes, made constructive).

Over ``QQ`` everything here runs on python-flint (:func:`rational_symmetry` needs no sympy, for the
sympy-free recognition of :mod:`.rational_path`); sympy's polynomials are read only over other ``K``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from flint import fmpq, fmpq_mpoly, fmpz_mpoly

from ..algebra import linalg
from ..algebra.linalg import Vector, cross, dot, is_zero, primitive_vector, scale, sub
from ..algebra.rationals import RATIONALS
from ..errors import AnalysisError
from ..results import Canal, CanalEvidence

if TYPE_CHECKING:
    from sympy.polys.domains.domain import Domain

    from ..algebra.polys import Poly

REVOLUTION = "revolution"
CYLINDER = "cylinder_of_revolution"
SPHERE = "sphere"
PLANE = "plane"
EXTRUSION = "extrusion"
NONE = "none"
SOR_KINDS = frozenset({REVOLUTION, CYLINDER, SPHERE, PLANE})


@dataclass(frozen=True)
class Motion:
    """An infinitesimal rigid motion ``v(p) = b + a × p`` (Plücker-like pair ``(a, b)``)."""

    a: Vector
    b: Vector


@dataclass(frozen=True)
class Symmetry:
    """The classified symmetry algebra: its basis and the geometric data it determines.

    ``axis_point``/``axis_direction`` are set for a unique axis (revolution, cylinder of
    revolution); ``center`` for spheres; ``normal`` for planes; ``direction`` for extrusions.
    """

    kind: str
    basis: tuple[Motion, ...]
    axis_point: Vector | None = None
    axis_direction: Vector | None = None
    center: Vector | None = None
    normal: Vector | None = None
    direction: Vector | None = None

    @property
    def dimension(self) -> int:
        """``dim L``."""
        return len(self.basis)

    @property
    def is_sor(self) -> bool:
        """True for surfaces of revolution, spheres, planes and cylinders of revolution."""
        return self.kind in SOR_KINDS


def _generators(g: fmpq_mpoly) -> list[fmpq_mpoly]:
    """The six polynomials whose linear combinations are the left side of (★), over ``QQ``:
    ``f_x, f_y, f_z`` (coefficients of ``b``) and the components of ``p × ∇f`` (those of ``a``,
    since ``∇f·(a × p) = a·(p × ∇f)``)."""
    return _with_moments((g.derivative(0), g.derivative(1), g.derivative(2)))


def _with_moments(gradient: tuple[fmpq_mpoly, fmpq_mpoly, fmpq_mpoly]) -> list[fmpq_mpoly]:
    """The gradient and the components of ``p × ∇f``: the six polynomials of :func:`_generators`."""
    fx, fy, fz = gradient
    x, y, z = fx.context().gens()
    return [fx, fy, fz, y * fz - z * fy, z * fx - x * fz, x * fy - y * fx]


def infinitesimal_generators(f: Poly) -> list[dict[tuple[int, ...], Any]]:
    """The six polynomials of (★) (see :func:`_generators`) as coefficient dictionaries."""
    from ..algebra.polys import derivative, is_rational_field, to_flint

    R = f.ring
    if is_rational_field(R.domain):
        return [p.to_dict() for p in _generators(to_flint(f))]
    x, y, z = R.gens
    fx, fy, fz = (derivative(f, i) for i in range(3))
    polys = [fx, fy, fz, y * fz - z * fy, z * fx - x * fz, x * fy - y * fx]
    return [dict(p.items()) for p in polys]


def symmetry_algebra(f: Poly) -> list[Motion]:
    """A basis of ``L``, the solution space of (★), in reduced (canonical) form."""
    from ..algebra.polys import is_rational_field, to_flint

    K = f.ring.domain
    if is_rational_field(K):
        return rational_symmetry_algebra(to_flint(f))
    columns = infinitesimal_generators(f)
    monomials = sorted(set().union(*columns))
    zero = K.zero
    rows = [[K.convert(col.get(m, zero)) for col in columns] for m in monomials]
    # Unknown order: (b1, b2, b3, a1, a2, a3), matching the columns above.
    basis = linalg.nullspace(rows, 6, K)
    return [Motion(a=tuple(v[3:]), b=tuple(v[:3])) for v in basis]


def rational_symmetry_algebra(
    g: fmpq_mpoly, multiple: Mapping[tuple[int, ...], int] | None = None, whole: fmpz_mpoly | None = None
) -> list[Motion]:
    """``L`` of ``g ∈ QQ[x, y, z]`` from a part of the system of (★), each candidate checked as
    a polynomial identity in flint.

    Any set of equations of (★) has a null space that contains ``L``; when every vector of its
    reduced basis satisfies (★) identically (:func:`_invariant`), the two null spaces (hence their
    reduced bases) are equal, and the answer is exactly that of the whole system. The sets tried,
    cheapest first:

    * for an equation of many terms (:data:`MANY_TERMS`), as a surface in general position has,
      the rows of (★) below a few terms of ``g`` spread over its support (:func:`_row`: each a
      coefficient of the six polynomials, read off the gradient's coefficients; no product of
      polynomials, no evaluation of one);
    * the six polynomials at integer points (each point a random combination of all the rows),
      batch by batch: enough for a sparse equation;
    * the whole system, one row per monomial, as the last resort.

    A surface with no symmetry has the null space ``{0}`` after the first set, which needs no check.
    ``multiple``: the integer coefficients of a multiple of ``g`` by monomial, when the caller has
    them (the reader's): the first set's rows are then read off them (:func:`_integer_row`),
    not off flint's polynomials, a tenth of the time; the rows of a multiple have the same null space.
    ``whole``: that multiple as a polynomial over ``ZZ``, on which the first set's candidates are
    checked (the same identity up to a constant factor, in integer arithmetic: a fifth less time).
    """
    gradient = None  # ∇g, made when first needed
    if len(g) > MANY_TERMS:
        monomials = _row_monomials(g)
        if multiple is None:
            gradient = _gradient(g)
            rows = [_row(gradient, m) for m in monomials]
        else:
            rows = [_integer_row(multiple, m) for m in monomials]
        basis = linalg.nullspace(rows, 6, RATIONALS)
        if whole is None:
            checked = gradient = gradient or _gradient(g)
        else:
            checked = _gradient(whole)
        if all(_invariant(checked, v) for v in basis):
            return _motions(basis)
    gradient = gradient or _gradient(g)
    polys = _with_moments(gradient)
    rows = []
    for batch in range(EVALUATION_BATCHES):
        rows += [_values(polys, point) for point in _points(batch)]
        basis = linalg.nullspace(rows, 6, RATIONALS)
        if all(_invariant(gradient, v) for v in basis):
            return _motions(basis)
    columns = [p.to_dict() for p in polys]
    monomials = sorted(set().union(*columns))
    rows = [[col.get(m, fmpq(0)) for col in columns] for m in monomials]
    return _motions(linalg.nullspace(rows, 6, RATIONALS))


MANY_TERMS = 40
"""Equations with more terms than this try the rows below a few of their terms first; the values
at points of a smaller one cost less than the coefficients of the rows."""
SPREAD_TERMS = 8
"""Terms of ``g`` below which the rows of the first set are taken."""
EVALUATION_BATCHES = 4
"""Batches of 8 evaluation points tried before the whole system."""
_ZERO = fmpq(0)


def _motions(basis: Sequence[Sequence[Any]]) -> list[Motion]:
    """The null space vectors ``(b, a)`` (the unknowns in the order of :func:`_generators`) as motions."""
    return [Motion(a=tuple(v[3:]), b=tuple(v[:3])) for v in basis]


def _row_monomials(g: fmpq_mpoly) -> list[tuple[int, ...]]:
    """The monomials of the first set of rows: ``m − e_v`` for each variable ``v`` of ``m``, for
    :data:`SPREAD_TERMS` terms ``m`` of ``g`` a fixed stride apart over its whole support; each
    row then holds that term's coefficient in a derivative."""
    n = len(g)
    found: set[tuple[int, ...]] = set()
    for k in range(SPREAD_TERMS):
        m = tuple(int(e) for e in g.monomial((k * n) // SPREAD_TERMS))
        for v in range(3):
            if m[v]:
                found.add(tuple(e - (w == v) for w, e in enumerate(m)))
    return sorted(found)


def _row(gradient: tuple[fmpq_mpoly, fmpq_mpoly, fmpq_mpoly], m: tuple[int, ...]) -> list[Any]:
    """The coefficient of ``x^i y^j z^k`` in each of the six polynomials of :func:`_generators`,
    from the gradient's coefficients: ``(y·f_z)[m] = f_z[m − e_y]`` and so on."""
    fx, fy, fz = gradient
    i, j, k = m
    return [
        fx[m],
        fy[m],
        fz[m],
        (fz[i, j - 1, k] if j else _ZERO) - (fy[i, j, k - 1] if k else _ZERO),
        (fx[i, j, k - 1] if k else _ZERO) - (fz[i - 1, j, k] if i else _ZERO),
        (fy[i - 1, j, k] if i else _ZERO) - (fx[i, j - 1, k] if j else _ZERO),
    ]


def _integer_row(terms: Mapping[tuple[int, ...], int], m: tuple[int, ...]) -> list[int]:
    """:func:`_row` of the polynomial with these ``terms``, from its own coefficients:
    ``f_x[m] = (i + 1)·f[m + e_x]`` and so on (Python integers, one dict look-up each)."""
    i, j, k = m
    get = terms.get
    fx = (i + 1) * get((i + 1, j, k), 0)
    fy = (j + 1) * get((i, j + 1, k), 0)
    fz = (k + 1) * get((i, j, k + 1), 0)
    fz_y = (k + 1) * get((i, j - 1, k + 1), 0) if j else 0  # (y·f_z)[m] = f_z[m − e_y]
    fy_z = (j + 1) * get((i, j + 1, k - 1), 0) if k else 0
    fx_z = (i + 1) * get((i + 1, j, k - 1), 0) if k else 0
    fz_x = (k + 1) * get((i - 1, j, k + 1), 0) if i else 0
    fy_x = (j + 1) * get((i - 1, j + 1, k), 0) if i else 0
    fx_y = (i + 1) * get((i + 1, j - 1, k), 0) if j else 0
    return [fx, fy, fz, fz_y - fy_z, fx_z - fz_x, fy_x - fx_y]


def _points(batch: int) -> list[tuple[fmpq, fmpq, fmpq]]:
    """Eight integer points of a fixed, deterministic sequence (batch by batch): small integers
    keep the values of a degree-60 polynomial cheap to compute."""
    found = []
    for k in range(8 * batch, 8 * batch + 8):
        a, b, c = (7 * k + 3) % 19 - 9, (11 * k + 5) % 23 - 11, (13 * k + 2) % 29 - 14
        found.append((fmpq(a), fmpq(b), fmpq(c)))
    return found


def _values(polys: list[fmpq_mpoly], point: tuple[fmpq, fmpq, fmpq]) -> list[fmpq]:
    """The six polynomials of :func:`_generators` at ``point``: ``∇f`` evaluated, and ``p × ∇f``
    from it (three evaluations of a polynomial instead of six)."""
    fx, fy, fz = (p(*point) for p in polys[:3])
    x, y, z = point
    return [fx, fy, fz, y * fz - z * fy, z * fx - x * fz, x * fy - y * fx]


def _gradient(g: Any) -> tuple[Any, Any, Any]:  # noqa: ANN401 - over QQ or ZZ
    """``∇g`` (``g`` over ``QQ`` or ``ZZ``)."""
    return g.derivative(0), g.derivative(1), g.derivative(2)


def _invariant(gradient: Sequence[Any], v: Sequence[Any]) -> bool:
    """Whether the motion ``v = (b, a)`` satisfies (★) identically: ``∇f · (b + a × p) ≡ 0``,
    exactly, in flint (three products by linear polynomials). (★) is linear in ``v``: ``v`` is
    scaled to integers, so that a gradient over ``ZZ`` stays there."""
    fx, fy, fz = gradient[:3]
    x, y, z = fx.context().gens()
    rationals = [fmpq(c) for c in v]
    denominator = math.lcm(*(int(c.q) for c in rationals))
    b1, b2, b3, a1, a2, a3 = (int(c.p) * (denominator // int(c.q)) for c in rationals)
    total = fx * (a2 * z - a3 * y + b1) + fy * (a3 * x - a1 * z + b2) + fz * (a1 * y - a2 * x + b3)
    return bool(total.is_zero())


def satisfies_identity(f: Poly, motion: Motion) -> bool:
    """Whether ``(a, b)`` satisfies (★) identically: the exact invariance test."""
    K = f.ring.domain
    columns = infinitesimal_generators(f)
    weights = list(motion.b) + list(motion.a)
    total: dict[tuple[int, ...], Any] = {}
    for col, w in zip(columns, weights):
        if not w:
            continue
        for m, c in col.items():
            total[m] = total.get(m, K.zero) + w * K.convert(c)
    return not any(total.values())


def classify(basis: Sequence[Motion], K: Domain) -> Symmetry:
    """Classify a symmetry algebra by its dimension and structure (the table of docs/math.md §2)."""
    basis = tuple(basis)
    dim = len(basis)
    if dim == 0:
        return Symmetry(NONE, basis)
    translations = _translation_subspace(basis, K)
    if dim == 1:
        (m,) = basis
        if is_zero(m.a):
            return Symmetry(EXTRUSION, basis, direction=primitive_vector(m.b, K))
        if dot(m.a, m.b):
            raise AnalysisError("the symmetry algebra is a screw motion, which no algebraic surface has")
        point, direction = _axis_of_rotation(m, K)
        return Symmetry(REVOLUTION, basis, axis_point=point, axis_direction=direction)
    if dim == 2 and len(translations) == 1:
        t = translations[0]
        rotation = next(m for m in basis if not is_zero(m.a))
        # Remove the translation component along the axis, so that a·b = 0.
        b = sub(rotation.b, scale(K.quo(dot(rotation.a, rotation.b), dot(rotation.a, t)), t))
        point, direction = _axis_of_rotation(Motion(rotation.a, b), K)
        return Symmetry(CYLINDER, basis, axis_point=point, axis_direction=direction)
    if dim == 3 and not translations:
        return Symmetry(SPHERE, basis, center=_common_center(basis, K))
    if dim == 3 and len(translations) == 2:
        normal = primitive_vector(cross(translations[0], translations[1]), K)
        return Symmetry(PLANE, basis, normal=normal)
    raise AnalysisError(f"unexpected symmetry algebra of dimension {dim}")


def _translation_subspace(basis: Sequence[Motion], K: Domain) -> list[Vector]:
    """Directions ``b`` of the pure translations ``(0, b)`` in the span of ``basis``."""
    rows = [[m.a[i] for m in basis] for i in range(3)]
    combos = linalg.nullspace(rows, len(basis), K)
    result = []
    for lam in combos:
        b = tuple(sum((c * m.b[i] for c, m in zip(lam, basis)), start=K.zero) for i in range(3))
        result.append(b)
    return result


def _axis_of_rotation(m: Motion, K: Domain) -> tuple[Vector, Vector]:
    """The axis of the rotation ``b + a × p`` with ``a·b = 0``: the point ``c = (a × b)/|a|²``
    (the foot of the perpendicular from the origin) and the direction ``a``."""
    norm2 = dot(m.a, m.a)
    point = scale(K.quo(K.one, norm2), cross(m.a, m.b))
    return point, primitive_vector(m.a, K)


def _common_center(basis: Sequence[Motion], K: Domain) -> Vector:
    """The centre ``c`` with ``b = c × a`` for every rotation of ``so(3)`` about ``c``."""
    rows: list[list[Any]] = []
    rhs: list[Any] = []
    for m in basis:
        a1, a2, a3 = m.a
        # c × a = (c2 a3 - c3 a2, c3 a1 - c1 a3, c1 a2 - c2 a1)
        rows += [[K.zero, a3, -a2], [-a3, K.zero, a1], [a2, -a1, K.zero]]
        rhs += list(m.b)
    center = linalg.solve_unique(rows, rhs, K)
    if center is None:
        raise AnalysisError("the rotations of the symmetry algebra have no common centre")
    return center


def recognize_symmetry(f: Poly) -> Symmetry:
    """The symmetry method: compute ``L`` from (★) and classify it."""
    return classify(symmetry_algebra(f), f.ring.domain)


def rational_symmetry(
    g: fmpq_mpoly, multiple: Mapping[tuple[int, ...], int] | None = None, whole: fmpz_mpoly | None = None
) -> Symmetry:
    """The symmetry method over ``QQ`` on python-flint alone (``g ∈ QQ[x, y, z]``; ``multiple``
    and ``whole`` as in :func:`rational_symmetry_algebra`)."""
    return classify(rational_symmetry_algebra(g, multiple, whole), RATIONALS)


SOR_EVIDENCE = CanalEvidence(
    "symmetry",
    "X is a surface of revolution (symmetry algebra): its parallels are the characteristic "
    "circles of the spheres centred on the axis that touch X along them",
    True,
)
"""The canal certificate of a surface of revolution (docs/math.md §9): its symmetry algebra."""

PLANE_CANAL = Canal(
    True,
    "canal: a plane (the limit of a family of spheres)",
    ("developable", "revolution"),
    certificate=CanalEvidence("symmetry", "a plane is a surface of revolution about each normal line", True),
)
"""The canal answer for a plane."""

RECOGNITION_ONLY_NOTE = (
    "recognition only: the symmetry algebra's answer; the other sphere families (the Dupin, "
    "pipe and developable kinds) come with the full analysis"
)


def revolution_canal(degree: int, note: str = RECOGNITION_ONLY_NOTE) -> Canal:
    """The canal answer of a surface of revolution of the given degree from its symmetry algebra
    alone, as a recognition-only analysis (or the nearest exact surface of rounded input) gives
    it: no line test, no Singular."""
    if degree == 1:
        return PLANE_CANAL
    return Canal(True, "canal: a surface of revolution", ("revolution",), certificate=SOR_EVIDENCE, notes=(note,))


NEAREST_CANAL_NOTE = (
    "the nearest exact surface is a surface of revolution, so canal (the spheres centred on "
    "its axis); its other sphere families are not computed"
)
