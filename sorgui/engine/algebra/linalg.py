"""Exact linear algebra over K: null spaces and ranks of small-width matrices.

Algorithm choice: over ``QQ`` (sympy's domain or :data:`.rationals.RATIONALS`, both with ``fmpq``
elements) the matrices go to python-flint's ``fmpq_mat`` (reduced row echelon form in C); over an
algebraic field they go to sympy's ``DomainMatrix``, whose ``ANP`` arithmetic is exact (sympy is
imported only then). Both return a basis of the null space in reduced form, so the answers are
canonical: the same input always gives the same basis, whichever method produced the matrix.
"""

from __future__ import annotations

from collections.abc import Sequence
from math import gcd
from typing import TYPE_CHECKING, Any

from flint import fmpq, fmpq_mat

if TYPE_CHECKING:
    from sympy.polys.domains.domain import Domain

Vector = tuple[Any, ...]


def rref(rows: Sequence[Sequence[Any]], ncols: int, K: Domain) -> tuple[list[list[Any]], list[int]]:
    """The nonzero rows of the reduced row echelon form and the pivot columns."""
    if not rows:
        return [], []
    if K.is_QQ:
        M = fmpq_mat(len(rows), ncols, [c for row in rows for c in row])
        R, rank = M.rref()
        reduced = [[fmpq(R[i, j]) for j in range(ncols)] for i in range(rank)]
    else:
        from sympy.polys.matrices import DomainMatrix

        dm = DomainMatrix([list(row) for row in rows], (len(rows), ncols), K)
        R, _ = dm.rref()
        reduced = [row for row in R.to_list() if any(row)]
    pivots = [next(j for j, c in enumerate(row) if c) for row in reduced]
    return reduced, pivots


def nullspace(rows: Sequence[Sequence[Any]], ncols: int, K: Domain) -> list[Vector]:
    """A basis of ``{v : M v = 0}``, one vector per free column, in reduced form."""
    reduced, pivots = rref(rows, ncols, K)
    free = [j for j in range(ncols) if j not in pivots]
    basis: list[Vector] = []
    for j in free:
        v = [K.zero] * ncols
        v[j] = K.one
        for row, p in zip(reduced, pivots):
            v[p] = -row[j]
        basis.append(tuple(v))
    return basis


def rank(rows: Sequence[Sequence[Any]], ncols: int, K: Domain) -> int:
    """The rank of the matrix with the given rows."""
    return len(rref(rows, ncols, K)[1])


def solve_unique(rows: Sequence[Sequence[Any]], rhs: Sequence[Any], K: Domain) -> Vector | None:
    """The unique solution of ``M v = rhs``, or ``None`` when there is none or it is not unique."""
    n = len(rows[0])
    augmented = [list(r) + [b] for r, b in zip(rows, rhs)]
    reduced, pivots = rref(augmented, n + 1, K)
    if n in pivots or len(pivots) != n:
        return None
    return tuple(row[n] for row in reduced)


def dot(u: Vector, v: Vector) -> Any:
    """The Euclidean inner product ``u·v``."""
    return sum((a * b for a, b in zip(u, v)), start=u[0] - u[0])


def cross(u: Vector, v: Vector) -> Vector:
    """The cross product ``u × v`` in ``K³``."""
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


def scale(c: Any, v: Vector) -> Vector:
    """``c·v``."""
    return tuple(c * x for x in v)


def sub(u: Vector, v: Vector) -> Vector:
    """``u - v``."""
    return tuple(a - b for a, b in zip(u, v))


def is_zero(v: Vector) -> bool:
    """Whether every coordinate of ``v`` is zero."""
    return not any(v)


def perpendicular(a: Vector, K: Domain) -> Vector:
    """A simple vector ``u ⟂ a``: the projection onto ``a⊥`` of the coordinate vector ``e_k`` most
    orthogonal to ``a`` (smallest ``|a_k|``, the first on ties), made primitive; so the x-axis
    gets ``u = (0, 1, 0)``, as in the paper."""
    size = abs if K.is_QQ else (lambda c: abs(K.to_sympy(c)))
    k = min(range(3), key=lambda i: (size(a[i]), i))
    norm2 = dot(a, a)
    return primitive_vector(tuple(norm2 * (K.one if i == k else K.zero) - a[k] * a[i] for i in range(3)), K)


def primitive_vector(v: Vector, K: Domain) -> Vector:
    """A canonical nonzero multiple of ``v``: coprime integers over ``QQ``, first nonzero entry
    positive; over an algebraic field the first nonzero entry is scaled to 1."""
    lead = next(c for c in v if c)
    if not K.is_QQ:
        return tuple(K.quo(c, lead) for c in v)
    den = 1
    for c in v:
        den = den * int(c.denominator) // gcd(den, int(c.denominator))
    ints = [int(c * den) for c in v]
    g = 0
    for n in ints:
        g = gcd(g, abs(n))
    sign = -1 if lead < 0 else 1
    return tuple(fmpq(sign * n // g) for n in ints)
