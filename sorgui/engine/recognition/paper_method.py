"""The paper's Algorithm II (Recognition of SOR II), with the iteration bound of docs/math.md §1.

Choose points ``p_i`` anywhere in space (by Theorem "SORs are onions" they need not lie on the
surface), take the Plücker coordinates of the normals ``N_i = (∇f(p_i) : p_i × ∇f(p_i))`` of the
level sets through them, and solve ``n_i·ā + n̄_i·a = 0`` for the axis ``(a : ā)``. Five
independent normals determine it; then the paper's exact test decides. Spheres, planes and
cylinders never give five independent normals, so the loop is bounded: after ``max_points``
points the solution space is verified identically by (★) and classified like ``L``.

The points are pseudo-random but seeded, so every run gives the same answer.
"""

from __future__ import annotations

import random
from collections.abc import Callable

from ..algebra import linalg
from ..algebra.linalg import Vector, cross, dot, is_zero
from ..algebra.polys import Poly, derivative, is_rational_field, to_flint
from .profile import profile_curve
from .symmetry import NONE, Motion, Symmetry, classify, satisfies_identity

MAX_POINTS = 60
"""How many random points Algorithm II tries before it accepts fewer than five normals."""

COORDINATE_RANGE = 7
"""Coordinates of the random points are integers in ``[-COORDINATE_RANGE, COORDINATE_RANGE]``."""


def plucker_normal(gradient: Vector, point: Vector) -> Vector:
    """``N = (∇f(p) : p × ∇f(p))``, the Plücker coordinates of the normal line at ``p``."""
    return tuple(gradient) + cross(point, gradient)


def _gradient_evaluator(f: Poly) -> Callable[[Vector], Vector]:
    """A function ``p ↦ ∇f(p)`` with exact arithmetic (flint over ``QQ``, whose elements are
    sympy's ``QQ`` elements under the flint ground types)."""
    K = f.ring.domain
    if is_rational_field(K):
        flint_partials = [to_flint(f).derivative(i) for i in range(3)]
        return lambda p: tuple(K.convert(d(*p)) for d in flint_partials)
    partials = [derivative(f, i) for i in range(3)]
    return lambda p: tuple(K.convert(d(*p)) for d in partials)


def normals_at_random_points(f: Poly, seed: int = 0) -> tuple[list[Vector], int]:
    """Plücker normals at seeded random points, kept while they are linearly independent.

    Stops at five independent normals or after ``MAX_POINTS`` points; returns the normals and
    the number of points used.
    """
    K = f.ring.domain
    rng = random.Random(seed)
    gradient = _gradient_evaluator(f)
    kept: list[Vector] = []
    used = 0
    while len(kept) < 5 and used < MAX_POINTS:
        used += 1
        p = tuple(K.convert(rng.randint(-COORDINATE_RANGE, COORDINATE_RANGE)) for _ in range(3))
        g = gradient(p)
        if is_zero(g):
            continue
        candidate = kept + [plucker_normal(g, p)]
        if linalg.rank(candidate, 6, K) == len(candidate):
            kept = candidate
    return kept, used


def recognize_paper(f: Poly, seed: int = 0) -> Symmetry:
    """Algorithm II: the axis from random normals, then the paper's exact test.

    With five independent normals the unique ``(a : ā)`` must be a line (``a·ā = 0``, ``a ≠ 0``)
    whose profile satisfies ``f = p(x, y² + z²)``. With fewer, the solution space is checked
    identically with (★) and classified; if it fails, the surface has no symmetry.
    """
    K = f.ring.domain
    normals, _ = normals_at_random_points(f, seed)
    # The condition n·ā + n̄·a = 0 has the unknowns (ā, a) = (b, a) of (★) in this order.
    solutions = linalg.nullspace(normals, 6, K)
    basis = [Motion(a=tuple(v[3:]), b=tuple(v[:3])) for v in solutions]
    if len(basis) == 1 and not is_zero(basis[0].a):
        (m,) = basis
        if dot(m.a, m.b):
            return Symmetry(NONE, ())
        candidate = classify(basis, K)
        assert candidate.axis_point is not None and candidate.axis_direction is not None  # a rotation: an axis
        profile = profile_curve(f, candidate.axis_point, candidate.axis_direction)
        return candidate if profile.verified else Symmetry(NONE, ())
    if all(satisfies_identity(f, m) for m in basis):
        return classify(basis, K)
    return Symmetry(NONE, ())
