"""The implicit equation of the image of a rational map (docs/math.md §13).

When the exact decision (:mod:`.detect`) finds a symmetry, the image is described by a plane
curve, which one resultant implicitizes:

* a surface of revolution (or cylinder of revolution) about ``(c, a)``: the profile curve
  ``(h, ρ)``, ``h = a·(P − c)``, ``ρ = |P − c|²``, has an equation ``F(h, ρ) = 0``, and
  ``f(p) = F(a·(p − c), |p − c|²)``;
* a cylinder along ``a``: the base curve ``(U·P, V·P)`` across it (``U, V ⟂ a``), ``f(p) = F(U·p, V·p)``;
* a cone with apex ``c``: the curve of directions ``q = P − c`` in a chart,
  ``(qᵢ/q_k, q_j/q_k)``, and ``f`` the homogenized ``F`` at ``p − c``;
* a sphere about ``c`` (``|P − c|²`` is constant) and a plane (``n·P`` is constant) directly.

**The plane curve.** Two rational functions ``u, v`` of ``(s, t)`` whose Jacobian vanishes (the
detection proves it) map the parameter plane onto an irreducible curve ``C``, and so does any
parameter line on which they are not constant (its image is dense in ``C``). On such a line
``u = A(τ)/B(τ)``, ``v = C(τ)/D(τ)`` (reduced), ``Res_τ(B·U − A, D·V − C) = c·F^k`` with ``F`` the
irreducible equation of ``C``; of its irreducible factors, ``F`` is the one that vanishes at
``(u(τ), v(τ))`` identically (checked exactly in ``τ``). Everything here is flint over ``QQ``.

Otherwise (no symmetry, no apex) the equation comes from Singular's elimination
(:mod:`sorgui.engine.singular.surfaces`), over ``QQ`` and within a time limit.
"""

from __future__ import annotations

import threading
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import sympy

from ..algebra import rationals
from ..algebra.linalg import Vector, cross, perpendicular
from ..algebra.polys import XYZ, Poly, compose, factor, from_flint, from_rational, poly_ring, primitive
from ..conical.detect import Conicity
from ..errors import AnalysisError
from ..recognition.symmetry import CYLINDER, EXTRUSION, PLANE, REVOLUTION, SPHERE, Symmetry
from .detect import profile_functions
from .maps import ParameterRing, RationalMap

PROFILE_VARIABLES = ("h", "rho")
"""The variables of the profile curve ``F(h, ρ) = 0``: height along the axis, squared distance
to the axis point ``c``."""

LINE_VALUES = (Fraction(2), Fraction(-3), Fraction(5, 2), Fraction(1, 3), Fraction(-7, 4), Fraction(0), Fraction(1))
"""Values of the fixed parameter of the parameter lines tried for a plane curve."""

Fraction2 = tuple[Any, Any]
"""A fraction ``(numerator, denominator)`` in the parameter ring."""


@dataclass(frozen=True)
class ImplicitEquation:
    """``polynomial`` (primitive, in ``K[x, y, z]``) found by ``method``; ``profile`` is
    ``F(h, ρ)`` for a surface of revolution, and ``section`` the curve of the map on the
    parameter line that implicitized it (``t`` its parameter; it meets the circles of latitude
    along the whole profile, so it parameterizes ``P²``, properly when the line is)."""

    polynomial: Poly
    method: str
    profile: Poly | None = None
    section: tuple[sympy.Expr, sympy.Expr, sympy.Expr] | None = None


def implicit_equation(
    surface: RationalMap,
    symmetry: Symmetry,
    conicity: Conicity,
    *,
    timeout: float,
    cancel: threading.Event | None = None,
) -> ImplicitEquation | None:
    """The implicit equation by the route the symmetry allows (module docstring); ``None`` when
    Singular's elimination is needed and the field is not ``QQ``."""
    route = implicit_route(symmetry, conicity)
    if route == "profile curve":
        assert symmetry.axis_point is not None and symmetry.axis_direction is not None
        return revolution_equation(surface, symmetry.axis_point, symmetry.axis_direction)
    if route == "sphere":
        assert symmetry.center is not None
        return sphere_equation(surface, symmetry.center)
    if route == "plane":
        assert symmetry.normal is not None
        return plane_equation(surface, symmetry.normal)
    if route == "cylinder base curve":
        assert symmetry.direction is not None
        return cylinder_equation(surface, symmetry.direction)
    if route == "cone base curve":
        assert conicity.apex is not None
        return cone_equation(surface, conicity.apex)
    if not surface.ring.is_flint:
        return None
    from ..singular.surfaces import eliminated_equation

    ring = surface.ring
    f = eliminated_equation(
        [ring.to_sympy(c) for c in surface.X], ring.to_sympy(surface.W), timeout=timeout, cancel=cancel
    )
    return None if f is None else ImplicitEquation(f, "elimination")


def implicit_route(symmetry: Symmetry, conicity: Conicity) -> str:
    """The ``method`` by which :func:`implicit_equation` finds the equation of a map with this
    symmetry and apex (module docstring): the plane curve the symmetry allows, else elimination."""
    routes = {REVOLUTION: "profile curve", CYLINDER: "profile curve", SPHERE: "sphere", PLANE: "plane"}
    if symmetry.kind in routes:
        return routes[symmetry.kind]
    if symmetry.kind == EXTRUSION:
        return "cylinder base curve"
    return "cone base curve" if conicity.kind == "cone" else "elimination"


def revolution_equation(surface: RationalMap, point: Vector, direction: Vector) -> ImplicitEquation:
    """``f = F(a·(p − c), |p − c|²)`` from the profile curve ``F(h, ρ) = 0``."""
    ring = surface.ring
    pf = profile_functions(surface, point, direction)
    F, line = plane_curve(ring, (pf.A, pf.W), (pf.B, pf.W * pf.W), PROFILE_VARIABLES)
    R = poly_ring(XYZ, ring.K)
    offset = [g - R.ground_new(c) for g, c in zip(R.gens, point)]
    h = sum((d * R.ground_new(a) for d, a in zip(offset, direction)), start=R.zero)
    rho = sum((d * d for d in offset), start=R.zero)
    return ImplicitEquation(primitive(compose(F, [h, rho])), "profile curve", F, _section(surface, *line))


def _section(surface: RationalMap, index: int, value: Fraction) -> tuple[sympy.Expr, sympy.Expr, sympy.Expr]:
    """The map on the parameter line where parameter ``index`` is ``value``, in ``t``."""
    ring, K = surface.ring, surface.K
    t = sympy.Symbol("t")
    v = from_rational(K, value)

    def restricted(p: Any) -> sympy.Expr:
        return sum((K.to_sympy(c) * t**e for e, c in ring.restrict(p, index, v).items()), start=sympy.Integer(0))

    W = restricted(surface.W)
    x, y, z = (sympy.cancel(restricted(c) / W) for c in surface.X)
    return x, y, z


def sphere_equation(surface: RationalMap, center: Vector) -> ImplicitEquation:
    """``|p − c|² − r²``, ``r²`` the constant value of ``|P − c|²`` (checked identically)."""
    ring = surface.ring
    pf = profile_functions(surface, center, (ring.K.one, ring.K.zero, ring.K.zero))
    point = surface.sample_points(1)[0]
    r2 = ring.K.quo(ring.value(pf.B, point), ring.value(pf.W, point) ** 2)
    if pf.B - pf.W * pf.W * ring.constant(r2):
        raise AnalysisError("the squared distance to the sphere's centre is not constant (internal error)")
    R = poly_ring(XYZ, ring.K)
    f = sum(((g - R.ground_new(c)) ** 2 for g, c in zip(R.gens, center)), start=R.zero) - R.ground_new(r2)
    return ImplicitEquation(primitive(f), "sphere")


def plane_equation(surface: RationalMap, normal: Vector) -> ImplicitEquation:
    """``n·p − k``, ``k`` the constant value of ``n·P`` (checked identically)."""
    ring = surface.ring
    numerator = sum((x * ring.constant(n) for x, n in zip(surface.X, normal)), start=ring.zero)
    point = surface.sample_points(1)[0]
    k = ring.K.quo(ring.value(numerator, point), ring.value(surface.W, point))
    if numerator - surface.W * ring.constant(k):
        raise AnalysisError("the map does not lie in one plane (internal error)")
    R = poly_ring(XYZ, ring.K)
    f = sum((g * R.ground_new(n) for g, n in zip(R.gens, normal)), start=R.zero) - R.ground_new(k)
    return ImplicitEquation(primitive(f), "plane")


def cylinder_equation(surface: RationalMap, direction: Vector) -> ImplicitEquation:
    """``F(U·p, V·p)`` from the base curve across the direction ``a`` (``U ⟂ a``, ``V = a × U``)."""
    ring = surface.ring
    U = perpendicular(direction, ring.K)
    V = cross(direction, U)
    first, second = (_linear(surface, vector) for vector in (U, V))
    F, _line = plane_curve(ring, (first, surface.W), (second, surface.W), ("u", "v"))
    R = poly_ring(XYZ, ring.K)
    images = [sum((g * R.ground_new(c) for g, c in zip(R.gens, vector)), start=R.zero) for vector in (U, V)]
    return ImplicitEquation(primitive(compose(F, images)), "cylinder base curve")


def cone_equation(surface: RationalMap, apex: Vector) -> ImplicitEquation:
    """The homogenized equation ``G(p − c)`` of the curve of directions ``P − c`` in a chart."""
    ring = surface.ring
    q = [x - surface.W * ring.constant(c) for x, c in zip(surface.X, apex)]
    k = next(i for i in (2, 1, 0) if q[i])
    i, j = (m for m in range(3) if m != k)
    F, _line = plane_curve(ring, (q[i], q[k]), (q[j], q[k]), ("u", "v"))
    degree = max(sum(m) for m in F.itermonoms())
    H = poly_ring(("u", "v", "w"), ring.K)
    G = H.from_dict({(a, b, degree - a - b): c for (a, b), c in F.items()})
    R = poly_ring(XYZ, ring.K)
    shifted = [g - R.ground_new(c) for g, c in zip(R.gens, apex)]
    return ImplicitEquation(primitive(compose(G, [shifted[i], shifted[j], shifted[k]])), "cone base curve")


def _linear(surface: RationalMap, vector: Vector) -> Any:
    ring = surface.ring
    return sum((x * ring.constant(c) for x, c in zip(surface.X, vector)), start=ring.zero)


# --- the plane curve of two functionally dependent fractions -------------------------------------


def plane_curve(
    ring: ParameterRing, first: Fraction2, second: Fraction2, names: Sequence[str]
) -> tuple[Poly, tuple[int, Fraction]]:
    """The irreducible ``F(u, v)`` with ``F(first, second) ≡ 0`` (module docstring), in
    sympy's ring ``K[names]``, and the parameter line it was found on (the index of the fixed
    parameter and its value); ``first`` and ``second`` must be functionally dependent."""
    candidates = []
    for index in (1, 0):
        for value in LINE_VALUES:
            line = _on_line(ring, first, second, index, value)
            if line is not None:
                candidates.append((line, (index, value)))
                break
    if not candidates:
        raise AnalysisError("the plane curve of the map is a point (internal error)")
    curve, where = min(candidates, key=lambda c: max(len(part) for part in c[0]))
    if ring.is_flint:
        return _flint_curve(curve, ring, names), where
    return _sympy_curve(curve, ring, names), where


def _on_line(
    ring: ParameterRing, first: Fraction2, second: Fraction2, index: int, value: Fraction
) -> tuple[list[Any], list[Any], list[Any], list[Any]] | None:
    """The four restricted polynomials in ``τ`` (coefficient lists, lowest first) on the line
    where parameter ``index`` is ``value``; ``None`` when a denominator vanishes on it or both
    fractions are constant there."""
    K = ring.K
    v = from_rational(K, value)
    parts = []
    for p in (*first, *second):
        coefficients = ring.restrict(p, index, v)
        top = max(coefficients, default=-1)
        parts.append([coefficients.get(e, K.zero) for e in range(top + 1)])
    nu, du, nv, dv = parts
    if not du or not dv:
        return None
    constant = all(_proportional(n, d) for n, d in ((nu, du), (nv, dv)))
    return None if constant else (nu, du, nv, dv)


def _proportional(n: list[Any], d: list[Any]) -> bool:
    """Whether the univariate fraction ``n/d`` is constant: ``nᵢ·d_j = n_j·dᵢ`` for all ``i, j``."""
    size = max(len(n), len(d))
    zero = d[0] * 0
    n, d = n + [zero] * (size - len(n)), d + [zero] * (size - len(d))
    return all(n[i] * d[j] == n[j] * d[i] for i in range(size) for j in range(i + 1, size))


def _flint_curve(curve: tuple[list[Any], ...], ring: ParameterRing, names: Sequence[str]) -> Poly:
    ctx = rationals.context(("tau", "u", "v"))
    tau, u, v = ctx.gens()

    def poly(coefficients: list[Any]) -> Any:
        return ctx.from_dict({(e, 0, 0): c for e, c in enumerate(coefficients) if c})

    nu, du, nv, dv = (poly(c) for c in curve)
    nu, du = _reduce(nu, du)
    nv, dv = _reduce(nv, dv)
    resultant = (du * u - nu).resultant(dv * v - nv, "tau")
    factors = [g for g, _e in rationals.factor(resultant) if not g.is_constant()]
    for g in factors:
        if len(factors) == 1 or _vanishes_flint(g, nu, du, nv, dv):
            plane = rationals.context(tuple(names))
            G = plane.from_dict({(int(m[1]), int(m[2])): c for m, c in g.terms()})
            return from_flint(G, poly_ring(tuple(names), ring.K))
    raise AnalysisError("no factor of the resultant vanishes on the curve (internal error)")


def _reduce(n: Any, d: Any) -> tuple[Any, Any]:
    g = n.gcd(d)
    return (n / g, d / g) if not g.is_constant() else (n, d)


def _vanishes_flint(g: Any, nu: Any, du: Any, nv: Any, dv: Any) -> bool:
    """``g(nu/du, nv/dv) ≡ 0`` in ``τ``, cleared of denominators."""
    a, b = int(g.degrees()[1]), int(g.degrees()[2])
    total = nu * 0
    for m, c in g.terms():
        i, j = int(m[1]), int(m[2])
        total += c * nu**i * du ** (a - i) * nv**j * dv ** (b - j)
    return bool(total.is_zero())


def _sympy_curve(curve: tuple[list[Any], ...], ring: ParameterRing, names: Sequence[str]) -> Poly:
    R = poly_ring(("tau", *names), ring.K)
    tau, u, v = R.gens

    def poly(coefficients: list[Any]) -> Poly:
        return R.from_dict({(e, 0, 0): c for e, c in enumerate(coefficients) if c})

    nu, du, nv, dv = (poly(c) for c in curve)
    nu, du = _reduce_sympy(nu, du)
    nv, dv = _reduce_sympy(nv, dv)
    resultant = (du * u - nu).resultant(dv * v - nv)
    _content, factors = factor(resultant)
    factors_ = [g for g, _e in factors if not g.is_ground]
    for g in factors_:
        a, b = g.degrees()
        total = R.zero
        for (i, j), c in g.items():
            total += nu**i * du ** (a - i) * nv**j * dv ** (b - j) * c
        if len(factors_) == 1 or not total:
            return g.set_ring(poly_ring(tuple(names), ring.K))
    raise AnalysisError("no factor of the resultant vanishes on the curve (internal error)")


def _reduce_sympy(n: Poly, d: Poly) -> tuple[Poly, Poly]:
    g = n.gcd(d)
    return (n.exquo(g), d.exquo(g)) if not g.is_ground else (n, d)
