"""The base curve of a cone or a cylinder, its genus, and the verified rational
parameterizations of the surface (docs/math.md §10).

- A cone with apex ``c``: ``f(c + X) = f_d(X)``, the top-degree form, so ``X`` is the cone over
  the projective plane curve ``f_d = 0``. It is written in the affine chart ``z = 1`` (or
  ``y = 1``, ``x = 1``: the first coordinate that does not divide ``f_d``, so that the chart
  keeps every component) and ``X = c + t·γ(s)`` for a parameterization ``γ`` of that chart.
- A cylinder along ``a``: the section by the plane through the origin spanned by the
  ``K``-rational ``U ⟂ a`` and ``W``, the primitive multiple of ``a × U``, ``g(u, v) = f(u·U + v·W)``, and
  ``X = γ₁(s)·U + γ₂(s)·W + t·a``.

``X`` is rational exactly when its base curve is (the ruling parameter ``t`` is rational), and
a proper parameterization of the curve gives a proper one of ``X``. Genus and
parameterization come from the plane-curve layer (:mod:`..singular.curves`); every map is
substituted into ``f`` exactly.
"""

from __future__ import annotations

import threading
from dataclasses import replace
from typing import TYPE_CHECKING, Any

import sympy
from sympy.polys.domains.domain import Domain

from ..algebra.linalg import Vector, perpendicular, primitive_vector
from ..algebra.polys import (
    Poly,
    compose,
    factor,
    poly_ring,
    poly_str,
    power_of_a_plane,
    to_expr,
    to_str,
    total_degree,
)
from ..errors import SorguiError
from ..recognition.profile import AxisFrame
from ..results import Conical
from ..revolution.parametrization import PARAMETERS, SurfaceMap, frame_map, numerically_vanishes, vanishes_on
from ..singular.curves import analyze_curve, parametrize
from ..stage_results import BaseCurve, Parametrization
from .detect import Conicity, detect, near_apex, near_direction

if TYPE_CHECKING:
    from ..rounded.precision import Rounding

S, T = (sympy.Symbol(name) for name in PARAMETERS)
CHARTS = (2, 1, 0)
"""The affine charts of a cone's base curve, in the order tried: ``z = 1``, ``y = 1``, ``x = 1``."""
NAMES = ("x", "y", "z")
PLANE_NOTE = "a plane: a cone about each of its points and a cylinder along each of its directions"
PLANE = ("u", "v")
"""The coordinates of a cylinder's section plane, along ``U`` and ``W``."""


def analyze_conical(
    f: Poly, *, timeout: float = 60.0, cancel: threading.Event | None = None, rounding: Rounding | None = None
) -> Conical:
    """Cone, cylinder or neither (:func:`.detect.detect`); for a cone or a cylinder whose
    base curve is a curve (not points), its genus and the verified parameterizations. With the
    ``rounding`` of rounded input, a surface that is exactly neither may be nearly a cone
    (:func:`.detect.near_apex`) or nearly a cylinder (:func:`.detect.near_direction`)."""
    if total_degree(f) < 2:
        return Conical("none", notes=(PLANE_NOTE,))
    found = detect(f)
    K = f.ring.domain
    apex = None if found.apex is None else _triple(K, found.apex)
    if found.kind == "none":
        if rounding is None:
            return Conical("none")
        near = near_apex(f, rounding)
        if near is not None:
            return Conical("none", near_apex=near[0], near_residual=near[1])
        along = near_direction(f, rounding.tolerance)
        if along is not None:
            return Conical("none", near_direction=along[0], near_residual=along[1])
        return Conical("none")
    if len(found.directions) > 1:
        if power_of_a_plane(f):  # parallel planes, but only one: a plane's answer
            return Conical("none", notes=(PLANE_NOTE,))
        return Conical(
            "cylinder",
            apex=apex,
            direction=_triple(K, found.directions[0]),
            notes=("X is invariant under translations in a plane: a union of parallel planes",),
        )
    curve, frame, base = _base_curve(f, found)
    notes: list[str] = []
    _, factors = factor(curve)
    reducible = len(factors) > 1 or any(e > 1 for _, e in factors)
    base = replace(base, reducible=reducible)
    parametrizations: tuple[Parametrization, ...] = ()
    rational: bool | None = None
    components: tuple[BaseCurve, ...] = ()
    if reducible:
        components = tuple(_component(g, e, base, timeout=timeout, cancel=cancel) for g, e in factors)
    else:
        try:
            analysis = analyze_curve(curve, timeout=timeout, cancel=cancel)
        except SorguiError as exc:
            notes.append(f"the genus of the base curve is not known: {exc}")
        else:
            base = replace(base, absolutely_irreducible=analysis.is_absolutely_irreducible, genus=analysis.genus)
            if analysis.genus is not None:
                rational = analysis.genus == 0
            if rational:
                parametrizations, more = _parametrizations(f, curve, frame, found, timeout=timeout, cancel=cancel)
                notes += more
    return Conical(
        found.kind,
        apex=apex,
        direction=None if not found.directions else _triple(K, found.directions[0]),
        base_curve=base,
        rational=rational,
        parametrizations=parametrizations,
        notes=tuple(notes),
        components=components,
    )


def _component(
    g: Poly, multiplicity: int, base: BaseCurve, *, timeout: float, cancel: threading.Event | None
) -> BaseCurve:
    """One irreducible factor (over ``K``) of a reducible base curve: a cone or a cylinder over
    it is one component of ``X``, rational exactly when the factor is of genus 0."""
    part = replace(
        base,
        polynomial=poly_str(g),
        degree=total_degree(g),
        reducible=False,
        multiplicity=multiplicity,
    )
    if total_degree(g) == 1:
        return replace(part, absolutely_irreducible=True, genus=0)
    try:
        analysis = analyze_curve(g, timeout=timeout, cancel=cancel)
    except SorguiError:
        return part
    return replace(part, absolutely_irreducible=analysis.is_absolutely_irreducible, genus=analysis.genus)


def _base_curve(f: Poly, found: Conicity) -> tuple[Poly, AxisFrame, BaseCurve]:
    """The base curve, the frame that maps it back to ``X`` (see :func:`_surface_map`), and
    its description without genus."""
    K = f.ring.domain
    zero = (K.zero,) * 3
    if found.directions:
        a = found.directions[0]
        u = perpendicular(a, K)
        frame = AxisFrame(point=zero, direction=a, normal=u)
        w = primitive_vector(frame.binormal, K)
        R = poly_ring(PLANE, K)
        s, t = R.gens
        images = [s * u[i] + t * w[i] for i in range(3)]
        curve = compose(f, images)
        description = BaseCurve(
            polynomial=poly_str(curve),
            variables=PLANE,
            degree=total_degree(curve),
            frame_point=_triple(K, zero),
            frame_u=_triple(K, u),
            frame_w=_triple(K, w),
        )
        return curve, frame, description
    assert found.apex is not None
    d = total_degree(f)
    top = {m: c for m, c in f.items() if sum(m) == d}
    chart = next((k for k in CHARTS if any(m[k] == 0 for m in top)), CHARTS[0])
    first, second = (i for i in range(3) if i != chart)
    kept = (first, second)
    R = poly_ring(tuple(NAMES[i] for i in kept), K)
    curve = R.from_dict(_collect(top, kept, K))
    e = [tuple(K.one if i == j else K.zero for i in range(3)) for j in range(3)]
    frame = AxisFrame(point=found.apex, direction=e[chart], normal=e[kept[0]])
    description = BaseCurve(
        polynomial=poly_str(curve),
        variables=(NAMES[kept[0]], NAMES[kept[1]]),
        degree=total_degree(curve),
        chart=f"{NAMES[chart]} = 1",
    )
    return curve, frame, description


def _collect(top: dict[tuple[int, ...], Any], kept: tuple[int, int], K: Domain) -> dict[tuple[int, int], Any]:
    """The terms of ``f_d`` with the chart's coordinate set to 1 (coefficients in ``K``)."""
    out: dict[tuple[int, int], Any] = {}
    for m, c in top.items():
        key = (m[kept[0]], m[kept[1]])
        out[key] = out.get(key, K.zero) + c
    return {m: c for m, c in out.items() if c}


def _parametrizations(
    f: Poly,
    curve: Poly,
    frame: AxisFrame,
    found: Conicity,
    *,
    timeout: float,
    cancel: threading.Event | None,
) -> tuple[tuple[Parametrization, ...], list[str]]:
    """The parameterization of ``X`` from one of its base curve, substituted into ``f``."""
    try:
        gamma = parametrize(curve, parameter=S, timeout=timeout, cancel=cancel, known_genus_zero=True)
    except SorguiError as exc:
        return (), [f"the base curve is rational, but no parameterization of it was found ({exc})"]
    surface = _surface_map(gamma.x, gamma.y, frame, found, f.ring.domain)
    if not (numerically_vanishes(f, surface) and vanishes_on(f, surface)):
        return (), ["the parameterization found does not satisfy f = 0 (not shown)"]
    kind = "the cone over" if found.apex is not None and not found.directions else "the cylinder over"
    return (
        Parametrization(
            coordinates=_coordinates(surface.coordinates()),
            parameters=PARAMETERS,
            field=surface.ring.field,
            real=surface.ring.is_real,
            proper=True,
            method=f"{kind} the base curve's {gamma.method} parameterization",
            verified=True,
        ),
    ), []


def _surface_map(x: sympy.Expr, y: sympy.Expr, frame: AxisFrame, found: Conicity, K: Domain) -> SurfaceMap:
    """``c + t·(x·e_i ± y·e_j + e_k)`` for a cone (``frame``: ``c``, ``e_k``, ``e_i``; the sign
    makes ``e_k × e_i`` the chart's second axis), ``x·U + y·W + t·a`` for a cylinder."""
    if found.directions:  # W = primitive(a × U) = (a × U)/k
        k = next(c for c in frame.binormal if c) / next(c for c in primitive_vector(frame.binormal, K) if c)
        return frame_map(T, x, y / to_expr(K, k), frame, K)
    second = next(i for i in range(3) if frame.binormal[i])
    sign = 1 if frame.binormal[second] == K.one else -1
    return frame_map(T, T * x, sign * T * y, frame, K)


def _coordinates(exprs: tuple[sympy.Expr, sympy.Expr, sympy.Expr]) -> tuple[str, str, str]:
    """The coordinates as text, each fraction in lowest terms (constant factors too; over the
    field of the square roots it holds, which plain ``cancel`` does not see)."""
    x, y, z = (str(sympy.cancel(e, extension=True) if _has_roots(e) else sympy.cancel(e)) for e in exprs)
    return x, y, z


def _has_roots(e: sympy.Expr) -> bool:
    return any(not power.exp.is_Integer for power in e.atoms(sympy.Pow))


def _triple(K: Domain, v: Vector) -> tuple[str, str, str]:
    x, y, z = (to_str(K, c) for c in v)
    return x, y, z
