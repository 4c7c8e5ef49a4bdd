"""Singular on rational maps ``P = X/W`` of the plane into space (docs/math.md §13).

* :func:`eliminated_equation`: the implicit equation of the image, the generator of
  ``(W·x − X₁, W·y − X₂, W·z − X₃, 1 − w·W) ∩ QQ[x, y, z]`` (``eliminate``; the last generator
  removes the base points, where ``X`` and ``W`` vanish together).
* :func:`fibre_size`: the number of parameter points over one point of the image, the
  dimension of ``QQ(s₀, t₀)[s, t]/(X(s, t)·W(s₀, t₀) − X(s₀, t₀)·W(s, t), 1 − w·W)`` (``vdim``
  of a standard basis) for the generic point ``(s₀, t₀)`` (ring parameters), or for one given
  rational point. The generic fibre is reduced (characteristic 0), so its size is the degree of
  the map: 1 exactly when the map is proper.

Over ``QQ`` only: both take polynomials of sympy's ring ``QQ[s, t]``.
"""

from __future__ import annotations

import threading
from collections.abc import Sequence
from typing import Any

import sympy

from ..algebra.polys import Poly, poly_ring, primitive
from .process import emit, parse_int, parse_singular, poly_to_singular, run_script

SPACE = ("s", "t", "w", "x", "y", "z")


def eliminated_equation(
    X: Sequence[Poly], W: Poly, *, timeout: float, cancel: threading.Event | None = None
) -> Poly | None:
    """The implicit equation of the image of ``X/W`` (primitive, in ``QQ[x, y, z]``), or
    ``None`` when the elimination ideal is not principal (it always is for a surface)."""
    R = poly_ring(SPACE, X[0].ring.domain)
    s, t, w, x, y, z = R.gens
    images = [_lift(p, R) for p in (*X, W)]
    generators = [images[3] * c - images[i] for i, c in enumerate((x, y, z))] + [1 - w * images[3]]
    ideal = ", ".join(poly_to_singular(g, list(SPACE)) for g in generators)
    script = (
        f"ring sorguiElim = 0, ({', '.join(SPACE)}), dp;\nideal I = {ideal};\n"
        "ideal J = eliminate(I, s*t*w);\nshort = 0;\n"
        + emit("size", "string(size(J))")
        + emit("equation", "string(J[1])")
    )
    found = run_script(script, timeout=timeout, cancel=cancel)
    if parse_int(found["size"][0]) != 1:
        return None
    symbols = {name: sympy.Symbol(name) for name in ("x", "y", "z")}
    expression = parse_singular(found["equation"][0], symbols)
    target = poly_ring(("x", "y", "z"), R.domain)
    return primitive(target.from_expr(expression))


def fibre_size(
    X: Sequence[Poly],
    W: Poly,
    point: tuple[Any, Any] | None = None,
    *,
    timeout: float,
    cancel: threading.Event | None = None,
) -> int:
    """How many parameter points map to ``P(point)`` (``None``: the generic point)."""
    names = ("s", "t", "s0", "t0")
    R = poly_ring(names, X[0].ring.domain)
    s, t, s0, t0 = R.gens
    polys = [_lift(p, R) for p in (*X, W)]
    if point is None:
        at = [p.compose([(s, s0), (t, t0)]) for p in polys]
    else:
        at = [R.ground_new(_value(p, point)) for p in polys]
    generators = [polys[i] * at[3] - at[i] * polys[3] for i in range(3)]
    ideal = ", ".join(poly_to_singular(g, list(names)) for g in generators if g)
    saturation = poly_to_singular(polys[3], list(names))
    header = (
        "ring sorguiFibre = (0, s0, t0), (s, t, w), dp;" if point is None else "ring sorguiFibre = 0, (s, t, w), dp;"
    )
    script = f"{header}\nideal I = {ideal}, 1 - w*({saturation});\nideal G = std(I);\n" + emit(
        "vdim", "string(vdim(G))"
    )
    return parse_int(run_script(script, timeout=timeout, cancel=cancel)["vdim"][0])


def _lift(p: Poly, R: Any) -> Poly:
    """``p ∈ K[s, t]`` in the larger ring ``R`` whose first two variables are ``s, t``."""
    zeros = (0,) * (R.ngens - 2)
    return R.from_dict({(*m, *zeros): c for m, c in p.items()})


def _value(p: Poly, point: tuple[Any, Any]) -> Any:
    """``p(s₀, t₀)`` for ``p`` lifted into a ring whose first two variables are ``s, t``."""
    total = p.ring.domain.zero
    for m, c in p.items():
        total += c * point[0] ** m[0] * point[1] ** m[1]
    return total
