"""The exact decision on a rational map, without its implicit equation (docs/math.md §13).

Alcázar and Goldman (IEEE TVCG 2016) decide from the parametrization itself. With
``P = X/W`` and the normal ``P_s × P_t = Ñ/W³`` (:mod:`.maps`):

* **Surfaces of revolution.** ``X`` is a surface of revolution about the line ``(a : b)``
  (Plücker coordinates) exactly when every normal line meets it, ``N·b + (P × N)·a ≡ 0``; times
  ``W⁴`` this is the polynomial identity ``W·(Ñ·b) + (X × Ñ)·a ≡ 0``, linear in ``(a, b)``.
  Read as ``Ñ·(b + a × P) ≡ 0`` it says that the infinitesimal motion ``b + a × p`` is tangent
  to ``X`` everywhere: its solution space is the symmetry algebra ``L`` of docs/math.md §2, and
  it is classified by the same table (:func:`~sorgui.engine.recognition.symmetry.classify`):
  one rotation (a surface of revolution), the rotations about a point (a sphere), the motions
  of a plane, a rotation and a translation (a cylinder of revolution), a translation (a
  cylinder over a curve).
* **Cones and cylinders.** An apex ``c`` has ``det(P − c, P_s, P_t) ≡ 0``, i.e.
  ``W·(c·Ñ) ≡ X·Ñ``; a direction ``a`` of a cylinder has ``det(a, P_s, P_t) ≡ 0``, i.e.
  ``a·Ñ ≡ 0``: one homogeneous system ``W·(c·Ñ) − λ·(X·Ñ) ≡ 0`` in ``(c, λ)`` gives both.
* **Cross-check.** About the axis, the height ``h = a·(P − c)`` and the squared distance
  ``ρ = |P − c|²`` are functions of each other on ``X``: ``∂(h, ρ)/∂(s, t) ≡ 0``.

Each system's rows are its identity at rational parameter points; the null space of those rows
contains the true one, and equals it once every vector of its reduced basis satisfies the
identity as a polynomial (checked exactly). An empty null space needs no check at all: a
bicubic patch is decided by a few dozen values.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any

from ..algebra.linalg import Vector, cross, dot, nullspace, primitive_vector, rref, scale, sub
from ..conical.detect import Conicity
from ..recognition.symmetry import Motion, Symmetry, classify
from .maps import RationalMap

POINT_BATCHES = 4
"""Batches of :data:`POINTS_PER_BATCH` parameter points tried before the system with one row
per monomial (the last resort)."""
POINTS_PER_BATCH = 8


@dataclass(frozen=True)
class _Identity:
    """A linear identity ``Σ wᵢ·columnᵢ(s, t) ≡ 0`` in unknowns ``w``: its columns as values at
    a point (cheap) and as polynomials (for the exact check, computed once when needed)."""

    surface: RationalMap
    row: Callable[[Sequence[Any]], list[Any]]
    build: Callable[[], list[Any]]

    @cached_property
    def columns(self) -> list[Any]:
        return self.build()

    def holds(self, weights: Sequence[Any]) -> bool:
        ring = self.surface.ring
        total = ring.zero
        for column, w in zip(self.columns, weights):
            if w:
                total += column * ring.constant(w)
        return not total

    def nullspace(self, ncols: int) -> list[Vector]:
        """A basis (reduced, canonical) of the weights for which the identity holds."""
        K = self.surface.K
        rows: list[list[Any]] = []
        for batch in range(POINT_BATCHES):
            rows += [self.row(p) for p in self.surface.sample_points(POINTS_PER_BATCH, batch)]
            basis = nullspace(rows, ncols, K)
            if all(self.holds(v) for v in basis):
                return basis
        ring = self.surface.ring
        coefficients = [dict(ring.terms(c)) for c in self.columns]
        monomials = sorted(set().union(*coefficients))
        full = [[c.get(m, K.zero) for c in coefficients] for m in monomials]
        return nullspace(full, ncols, K)


def symmetry_algebra(surface: RationalMap) -> list[Motion]:
    """``L``: the motions ``(a, b)`` with ``W·(Ñ·b) + (X × Ñ)·a ≡ 0`` (unknowns ordered
    ``b₁, b₂, b₃, a₁, a₂, a₃`` as in :mod:`~sorgui.engine.recognition.symmetry`)."""

    def row(point: Sequence[Any]) -> list[Any]:
        X, W, N = surface.values(point)
        return [W * N[0], W * N[1], W * N[2], *cross(X, N)]

    def build() -> list[Any]:
        N = surface.normal
        return [surface.W * N[0], surface.W * N[1], surface.W * N[2], *cross(surface.X, N)]

    basis = _Identity(surface, row, build).nullspace(6)
    return [Motion(a=tuple(v[3:]), b=tuple(v[:3])) for v in basis]


def parametric_symmetry(surface: RationalMap) -> Symmetry:
    """The classified symmetry of the image of ``surface`` (the table of docs/math.md §2)."""
    return classify(symmetry_algebra(surface), surface.K)


def conicity(surface: RationalMap) -> Conicity:
    """The directions ``a`` with ``a·Ñ ≡ 0`` and an apex ``c`` with ``W·(c·Ñ) ≡ X·Ñ`` (free
    coordinates along the directions set to 0), as :func:`~sorgui.engine.conical.detect.detect`
    gives them for an equation."""
    K = surface.K

    def row(point: Sequence[Any]) -> list[Any]:
        X, W, N = surface.values(point)
        return [W * N[0], W * N[1], W * N[2], -dot(X, N)]

    def build() -> list[Any]:
        N = surface.normal
        return [surface.W * N[0], surface.W * N[1], surface.W * N[2], -dot(surface.X, N)]

    basis = _Identity(surface, row, build).nullspace(4)
    with_apex = [v for v in basis if v[3]]
    if not with_apex:
        return Conicity(tuple(primitive_vector(v[:3], K) for v in basis), None)
    cone = with_apex[0]
    apex = scale(K.quo(K.one, cone[3]), cone[:3])
    others = [sub(v, scale(K.quo(v[3], cone[3]), cone)) for v in basis if v is not cone]
    directions = tuple(primitive_vector(v[:3], K) for v in others)
    if directions:  # the free coordinates of the apex along the directions set to 0
        apex = _reduced_apex(apex, directions, K)
    return Conicity(directions, tuple(apex))


def _reduced_apex(apex: Vector, directions: Sequence[Vector], K: Any) -> Vector:
    """The apex moved along the directions so that its coordinates at their pivots are 0."""
    rows = [list(d) for d in directions]
    reduced, pivots = rref(rows, 3, K)
    point = list(apex)
    for r, p in zip(reduced, pivots):
        point = [c - point[p] * r[i] for i, c in enumerate(point)]
    return tuple(point)


@dataclass(frozen=True)
class ProfileFunctions:
    """``h = A/W`` (the height along the axis) and ``ρ = B/W²`` (the squared distance to the
    point ``c``) of a map about the axis through ``c`` with direction ``a``."""

    A: Any
    B: Any
    W: Any


def profile_functions(surface: RationalMap, point: Vector, direction: Vector) -> ProfileFunctions:
    """``A = a·X − (a·c)·W`` and ``B = |X − c·W|²``."""
    ring = surface.ring
    W = surface.W
    offset = [surface.X[i] - W * ring.constant(point[i]) for i in range(3)]
    A = sum((offset[i] * ring.constant(direction[i]) for i in range(3)), start=ring.zero)
    B = sum((c * c for c in offset), start=ring.zero)
    return ProfileFunctions(A, B, W)


def profile_is_a_curve(surface: RationalMap, point: Vector, direction: Vector) -> bool:
    """The cross-check ``∂(h, ρ)/∂(s, t) ≡ 0``: with ``h = A/W``, ``ρ = B/W²`` its numerator is
    ``(A_s W − A W_s)(B_t W − 2B W_t) − (A_t W − A W_t)(B_s W − 2B W_s)``."""
    ring = surface.ring
    f = profile_functions(surface, point, direction)
    d = ring.derivative
    A, B, W = f.A, f.B, f.W
    Ws, Wt = d(W, 0), d(W, 1)
    hs, ht = d(A, 0) * W - A * Ws, d(A, 1) * W - A * Wt
    rs, rt = d(B, 0) * W - 2 * B * Ws, d(B, 1) * W - 2 * B * Wt
    return not (hs * rt - ht * rs)
