"""Recognition of one polynomial: symmetry, axis, profile, and its factors (docs/math.md §2–§4).

Two interchangeable methods find the symmetry: ``"symmetry"`` (the algebra ``L`` of (★),
deterministic, the default) and ``"paper"`` (the paper's Algorithm II with random points). Both
return a :class:`~sorgui.engine.recognition.symmetry.Symmetry`; everything after that is shared.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import overload

from sympy.polys.domains.domain import Domain

from ..algebra.linalg import Vector, cross, dot, is_zero, primitive_vector, sub
from ..algebra.polys import Poly, factor, poly_str, to_str, total_degree
from ..errors import AnalysisError
from ..results import Axis, Factor, Profile, Recognition, Triple
from .paper_method import recognize_paper
from .profile import ProfileCurve, profile_curve
from .symmetry import CYLINDER, REVOLUTION, SPHERE, Symmetry, recognize_symmetry

METHODS: dict[str, Callable[[Poly], Symmetry]] = {
    "symmetry": recognize_symmetry,
    "paper": recognize_paper,
}


def find_symmetry(f: Poly, method: str = "symmetry") -> Symmetry:
    """The classified symmetry of ``f`` by the named method."""
    try:
        return METHODS[method](f)
    except KeyError:
        raise AnalysisError(f"unknown method {method!r}; choose one of {', '.join(METHODS)}") from None


@overload
def _triple(K: Domain, v: Vector) -> Triple: ...


@overload
def _triple(K: Domain, v: Vector | None) -> Triple | None: ...


def _triple(K: Domain, v: Vector | None) -> Triple | None:
    if v is None:
        return None
    x, y, z = v
    return to_str(K, x), to_str(K, y), to_str(K, z)


def axis_report(point: Vector, direction: Vector, K: Domain) -> Axis:
    """The axis as point, direction and Plücker coordinates ``(v : p × v)`` (docs/math.md §1 erratum)."""
    plucker = primitive_vector(tuple(direction) + cross(point, direction), K)
    return Axis(
        point=_triple(K, point),
        direction=_triple(K, direction),
        plucker=_triple(K, plucker[:3]) + _triple(K, plucker[3:]),
    )


def profile_report(profile: ProfileCurve, K: Domain) -> Profile:
    """The profile as exact strings."""
    p = profile.orthonormal
    square = p.ring.from_dict({(i, j // 2): c for (i, j), c in p.items()})
    return Profile(
        polynomial=poly_str(p),
        square=poly_str(square),
        rational=poly_str(profile.rational),
        rational_square=poly_str(profile.square),
        frame_point=_triple(K, profile.frame.point),
        frame_direction=_triple(K, profile.frame.direction),
        frame_normal=_triple(K, profile.frame.normal),
        even=profile.even,
        verified=profile.verified,
    )


def recognize(
    f: Poly, method: str = "symmetry", frame: tuple[Vector, Vector, Vector] | None = None
) -> tuple[Recognition, Symmetry, ProfileCurve | None]:
    """Recognise ``f``: the report, the classified symmetry, and the profile when the axis is unique.

    ``frame`` (a point, a direction and a normal ``u ⟂ a``) is used for the profile instead of
    the foot point and primitive direction of the axis when it lies on the same line: a rounded
    input's snapped surface passes the frame that keeps its profile's coefficients small
    (docs/math.md §8). The axis is then reported through the frame's point (one point of the
    axis for both), and the frame's direction is turned to the axis direction's sign.
    """
    K = f.ring.domain
    sym = find_symmetry(f, method)
    profile = None
    axis_point = sym.axis_point
    if sym.kind in (REVOLUTION, CYLINDER):
        assert sym.axis_point is not None and sym.axis_direction is not None  # a unique axis (classify)
        point, direction = sym.axis_point, sym.axis_direction
        normal: Vector | None = None
        if frame is not None and _same_line(frame[:2], (point, direction)):
            point, direction, normal = frame
            if K.to_sympy(dot(direction, sym.axis_direction)) < 0:
                direction = tuple(-c for c in direction)
            axis_point = point
        profile = profile_curve(f, point, direction, normal)
        if not profile.verified:
            raise AnalysisError("the axis found does not pass the exact profile test (internal error)")
    report = Recognition(
        polynomial=poly_str(f),
        degree=total_degree(f),
        is_sor=sym.is_sor,
        symmetry=sym.kind,
        symmetry_dimension=sym.dimension,
        symmetry_basis=tuple(tuple(to_str(K, c) for c in m.a + m.b) for m in sym.basis),
        axis=axis_report(axis_point, sym.axis_direction, K)
        if axis_point is not None and sym.axis_direction is not None
        else None,
        center=_triple(K, sym.center),
        normal=_triple(K, sym.normal),
        direction=_triple(K, sym.direction),
        profile=profile_report(profile, K) if profile is not None else None,
        radius_squared=None
        if sym.kind != SPHERE or sym.center is None or total_degree(f) != 2
        else to_str(K, _radius_squared(f, sym.center)),
    )
    return report, sym, profile


def _radius_squared(f: Poly, center: Vector) -> object:
    """``r²`` of the sphere ``f = a·|p − c|² − a·r²``: ``−f(c)/a``."""
    x = f.ring.gens[0]
    return -f(*center) / f.coeff(x**2)


def _same_line(first: tuple[Vector, Vector], second: tuple[Vector, Vector]) -> bool:
    """Whether two (point, direction) pairs describe the same line, exactly."""
    (p, a), (q, b) = first, second
    return is_zero(cross(a, b)) and is_zero(cross(sub(p, q), b))


def factor_reports(f: Poly, whole: Recognition, method: str = "symmetry") -> tuple[tuple[Factor, ...], list[Poly]]:
    """The irreducible factors of ``f`` over ``K``, each recognised, and the distinct factors.

    When ``f`` is irreducible its only factor's recognition is ``whole`` (not computed twice).
    """
    _, factors = factor(f)
    distinct = [g for g, _e in factors]
    if len(factors) == 1 and factors[0][1] == 1:
        return (Factor(poly_str(factors[0][0]), 1, whole),), distinct
    reports = tuple(Factor(poly_str(g), e, recognize(g, method)[0]) for g, e in factors)
    return reports, distinct
