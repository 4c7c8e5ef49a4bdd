"""A report's recognition checked against its polynomial (docs/math.md §2, §3, §14).

The symmetry algebra ``L`` of ``f`` is computed again (:mod:`..recognition.symmetry`, the
deterministic method): the claimed kind and dimension must be its, the claimed basis must lie
in ``L`` and span it, and the axis, the centre of a sphere, the normal of a plane and the
direction of an extrusion must be those ``L`` determines (the same line, the same point, a
parallel vector). A sphere of degree 2 has ``r² = −f(c)/a``. The profile's frame must be a point
of the axis, a direction along it and a normal ``u ⟂ a`` (a sphere's: its centre; a plane's: a
point of it and its normal); the profile ``p̃(s, r)`` is
``f(c + s·a + r·u)`` up to a constant factor, ``P²`` is it with ``r² = w``, and the orthonormal
profile is ``p̃(x/|a|, y/|u|)`` (identities at random points, :mod:`.identities`).
"""

from __future__ import annotations

from typing import Any

from ..algebra import linalg
from ..algebra.linalg import Vector, cross, dot, is_zero, sub
from ..algebra.modular import Point
from ..algebra.polys import power_of_a_plane, to_expr, to_str, total_degree
from ..errors import AnalysisError, ClaimError
from ..recognition.symmetry import CYLINDER, PLANE, REVOLUTION, SPHERE, Symmetry, recognize_symmetry
from ..results import UNDECIDED, Axis, Profile, Recognition
from .formulas import Surface, nonzero, number, values, vector
from .identities import Identities, proportional


def check_recognition(rec: Recognition, surface: Surface, where: str, ids: Identities) -> Symmetry | None:
    """Check ``rec`` against ``surface`` (fields named with the prefix ``where``); the symmetry of
    the polynomial, ``None`` when the report leaves it undecided (a time limit)."""
    g = surface.polynomial
    K = g.ring.domain
    if rec.degree != total_degree(g):
        raise ClaimError(f"{where}degree", f"is {rec.degree}, but the polynomial has degree {total_degree(g)}")
    if undecided(rec, where):
        return None
    try:
        sym = recognize_symmetry(g)
    except AnalysisError as exc:
        raise ClaimError(f"{where}symmetry", f"cannot be: {exc.message}") from None
    check_symmetry(rec, sym, K, where, "the polynomial's")
    _check_radius(rec, sym, surface, f"{where}radius_squared")
    has_axis = sym.kind in (REVOLUTION, CYLINDER)
    # a sphere's profile is about a chosen line through its centre, a plane's about a chosen normal
    about_any_axis = (sym.kind == SPHERE and sym.center is not None) or (sym.kind == PLANE and power_of_a_plane(g))
    if (rec.profile is not None) != has_axis and not about_any_axis:
        raise ClaimError(f"{where}profile", "is given for a surface without one axis" if rec.profile else "is missing")
    if rec.profile is not None:
        check_profile(rec.profile, sym, surface, f"{where}profile", ids)
    return sym


def undecided(rec: Recognition, where: str) -> bool:
    """Whether ``rec`` leaves the symmetry undecided (a time limit); then it may claim nothing
    the symmetry decides."""
    if rec.symmetry != UNDECIDED:
        return False
    claimed = (rec.is_sor, rec.symmetry_basis, rec.axis, rec.center, rec.normal, rec.direction, rec.profile)
    if claimed != (False, (), None, None, None, None, None) or rec.radius_squared is not None:
        raise ClaimError(f"{where}symmetry", "is undecided, but the report gives what it decides")
    return True


def check_symmetry(rec: Recognition, sym: Symmetry, K: Any, where: str, whose: str) -> None:  # noqa: ANN401
    """The kind, dimension, basis, axis, centre, normal and direction ``rec`` claims against the
    symmetry algebra ``sym`` (``whose``: the polynomial's, or the map's normal lines')."""
    if rec.is_sor != sym.is_sor and rec.symmetry == sym.kind:
        raise ClaimError(
            f"{where}is_sor", f"is {str(rec.is_sor).lower()}, but {whose} symmetry algebra is {sym.kind!r}"
        )
    if rec.symmetry != sym.kind or rec.symmetry_dimension != sym.dimension or rec.is_sor != sym.is_sor:
        raise ClaimError(
            f"{where}symmetry",
            f"is {rec.symmetry!r} of dimension {rec.symmetry_dimension}, but {whose} symmetry "
            f"algebra is {sym.kind!r} of dimension {sym.dimension}",
        )
    check_basis(rec.symmetry_basis, sym, K, f"{where}symmetry_basis")
    _check_axis(rec.axis, sym, K, f"{where}axis")
    _check_point(rec.center, sym.center, K, f"{where}center")
    _check_parallel(rec.normal, sym.normal, K, f"{where}normal")
    _check_parallel(rec.direction, sym.direction, K, f"{where}direction")


def check_basis(basis: tuple[tuple[str, ...], ...], sym: Symmetry, K: Any, where: str) -> None:  # noqa: ANN401
    """The claimed motions (``a`` then ``b``) lie in ``L`` and span it."""
    claimed = [tuple(number(K, c, f"{where}[{i}]") for c in motion) for i, motion in enumerate(basis)]
    if any(len(m) != 6 for m in claimed):
        raise ClaimError(where, "must hold motions of six numbers")
    true = [tuple(m.a) + tuple(m.b) for m in sym.basis]
    dimension = len(true)
    if len(claimed) != dimension or linalg.rank(claimed, 6, K) != dimension:
        raise ClaimError(where, f"does not span the symmetry algebra (of dimension {dimension})")
    if linalg.rank(true + claimed, 6, K) != dimension:
        raise ClaimError(where, "holds a motion that does not leave the surface invariant")


def _check_axis(axis: Axis | None, sym: Symmetry, K: Any, where: str) -> None:  # noqa: ANN401
    if sym.axis_point is None or sym.axis_direction is None:
        if axis is not None:
            raise ClaimError(where, f"is given, but a {sym.kind} surface has no single axis")
        return
    if axis is None:
        raise ClaimError(where, "is missing")
    point = vector(K, axis.point, f"{where}.point")
    direction = nonzero(vector(K, axis.direction, f"{where}.direction"), f"{where}.direction")
    if not is_zero(cross(direction, sym.axis_direction)):
        raise ClaimError(f"{where}.direction", "is not the direction of the surface's axis")
    if not is_zero(cross(sub(point, sym.axis_point), sym.axis_direction)):
        raise ClaimError(f"{where}.point", "is not a point of the surface's axis")
    plucker = tuple(number(K, c, f"{where}.plucker[{i}]") for i, c in enumerate(axis.plucker))
    expected = tuple(direction) + cross(point, direction)
    if is_zero(plucker) or linalg.rank([plucker, expected], 6, K) != 1:
        raise ClaimError(f"{where}.plucker", "are not the Plücker coordinates of the axis")


def _check_point(claimed: tuple[str, str, str] | None, true: Vector | None, K: Any, where: str) -> None:  # noqa: ANN401
    if true is None:
        if claimed is not None:
            raise ClaimError(where, "is given, but the surface is not a sphere")
        return
    if claimed is None or vector(K, claimed, where) != tuple(true):
        raise ClaimError(where, f"is not the centre ({', '.join(to_str(K, c) for c in true)}) of the surface")


def _check_parallel(claimed: tuple[str, str, str] | None, true: Vector | None, K: Any, where: str) -> None:  # noqa: ANN401
    if true is None:
        if claimed is not None:
            raise ClaimError(where, "is given, but the surface has none")
        return
    if claimed is None:
        raise ClaimError(where, "is missing")
    if not is_zero(cross(nonzero(vector(K, claimed, where), where), true)):
        raise ClaimError(where, f"is not along ({', '.join(to_str(K, c) for c in true)}), the surface's")


def _check_radius(rec: Recognition, sym: Symmetry, surface: Surface, where: str) -> None:
    g = surface.polynomial
    K = g.ring.domain
    if sym.kind != SPHERE or sym.center is None or total_degree(g) != 2:
        if rec.radius_squared is not None:
            raise ClaimError(where, "is given, but the surface is not a sphere of degree 2")
        return
    x = g.ring.gens[0]
    true = K.quo(-g(*sym.center), g.coeff(x**2))
    if rec.radius_squared is None or number(K, rec.radius_squared, where) != true:
        raise ClaimError(where, f"is not the square of the sphere's radius, {to_str(K, true)}")


def check_profile(profile: Profile, sym: Symmetry, surface: Surface, where: str, ids: Identities) -> None:
    """The frame against the axis exactly (a sphere's: any line through its centre); the four
    forms of the profile at random points."""
    K = surface.polynomial.ring.domain
    c = vector(K, profile.frame_point, f"{where}.frame_point")
    a = nonzero(vector(K, profile.frame_direction, f"{where}.frame_direction"), f"{where}.frame_direction")
    u = nonzero(vector(K, profile.frame_normal, f"{where}.frame_normal"), f"{where}.frame_normal")
    if sym.kind == SPHERE:
        assert sym.center is not None  # a sphere's profile is checked only with its centre
        if not is_zero(sub(c, sym.center)):
            raise ClaimError(f"{where}.frame_point", "is not the centre of the sphere")
    elif sym.kind == PLANE:
        assert sym.normal is not None  # a plane's symmetry gives its normal
        if surface.polynomial(*c):
            raise ClaimError(f"{where}.frame_point", "is not a point of the plane")
        if not is_zero(cross(a, sym.normal)):
            raise ClaimError(f"{where}.frame_direction", "is not along the normal of the plane")
    else:
        assert sym.axis_point is not None and sym.axis_direction is not None  # a unique axis
        if not is_zero(cross(sub(c, sym.axis_point), sym.axis_direction)):
            raise ClaimError(f"{where}.frame_point", "is not a point of the axis")
        if not is_zero(cross(a, sym.axis_direction)):
            raise ClaimError(f"{where}.frame_direction", "is not along the axis")
    if dot(a, u):
        raise ClaimError(f"{where}.frame_normal", "is not perpendicular to the axis")
    if not (profile.even and profile.verified):
        raise ClaimError(f"{where}.verified", "must hold for a surface of revolution (its symmetry algebra says so)")
    frame = [[to_expr(K, v) for v in w] for w in (c, a, u)]
    ids.need(*surface.radicands)
    squares = [to_expr(K, dot(w, w)) for w in (a, u)]
    ids.need(*[q for q in squares if q.is_Rational])

    def truth(point: Point) -> int:
        s, r = point.of("s"), point.of("r")
        p = point.prime
        images = [
            point.value(frame[0][i]) + s * point.value(frame[1][i]) + r * point.value(frame[2][i]) for i in range(3)
        ]
        return surface.at(point, [v % p for v in images])

    def rational(point: Point) -> int:
        return values(point, [profile.rational])[0]

    def rational_square(point: Point) -> int:
        r = point.of("r")
        return values(point, [profile.rational_square], w=r * r % point.prime)[0]

    def orthonormal(point: Point) -> int:
        return values(point, [profile.polynomial], x=point.of("s"), y=point.of("r"))[0]

    def orthonormal_square(point: Point) -> int:
        r = point.of("r")
        return values(point, [profile.square], x=point.of("s"), y=r * r % point.prime)[0]

    def rational_scaled(point: Point) -> int:
        """``p̃(x/|a|, y/|u|)`` at ``(x, y) = (s, r)`` of the point."""
        p = point.prime
        roots = [point.sqrt(q) for q in squares]
        if 0 in roots:
            raise ClaimError(f"{where}.frame_direction", "has length zero")
        s = point.of("s") * pow(roots[0], -1, p) % p
        r = point.of("r") * pow(roots[1], -1, p) % p
        return values(point, [profile.rational], s=s, r=r)[0]

    fails = "is not the surface's profile in the frame of the report (f(c + s·a + r·u))"
    ids.add(f"{where}.rational", fails, lambda P: proportional(rational, truth, P), [profile.rational])
    ids.add(
        f"{where}.rational_square",
        "is not the profile with r² written w",
        lambda P: proportional(rational_square, rational, P),
        [profile.rational_square],
    )
    ids.add(
        f"{where}.polynomial",
        "is not the profile in orthonormal coordinates, p̃(x/|a|, y/|u|)",
        lambda P: proportional(orthonormal, rational_scaled, P),
        [profile.polynomial],
    )
    ids.add(
        f"{where}.square",
        "is not the orthonormal profile with y² written y",
        lambda P: proportional(orthonormal_square, orthonormal, P),
        [profile.square],
    )
