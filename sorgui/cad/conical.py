"""Cylinders and cones over a curve as the CAD surfaces they are (docs/math.md §10, §11).

The engine parameterizes such a surface by its lines: ``X(s, t) = A(s) + t·B(s)``, with ``B``
constant for a cylinder (its direction ``a``) and ``A`` constant for a cone (its apex ``c``).

* A **cylinder over a curve** is the linear extrusion (STEP's ``SURFACE_OF_LINEAR_EXTRUSION``)
  of its base curve along ``a``: the section ``A(s)`` moved along ``a`` into the plane through
  the ball's centre across ``a``, ``C(s) = A(s) − ((A(s) − m)·â)·â``, rational of the same
  degree, written exactly as rational Bézier arcs (:func:`.geometry.ball_arcs`) where it lies
  within ``1.05·R`` of ``m``; each is extruded by ``±1.05·R``, then cut to the ball.
* A **cone over a curve** is ruled through its apex: ``c + μ·N(s)``, ``N`` the numerators of
  ``B`` (the rays do not change when ``B`` is multiplied by its denominator, and ``N`` has no
  pole), a polynomial map of the projective ``s``-line. On each span of ``N`` as a Bézier curve
  (control points ``b_k``), the two nappes ``μ ∈ [0, ±M]`` are Bézier surfaces of degree
  ``(n, 1)``, poles ``c`` and ``c ± M·b_k`` — exact; ``M`` takes the rays beyond the ball, then
  the faces are cut to it.
"""

from __future__ import annotations

from dataclasses import dataclass

import mpmath
import numpy as np
import sympy

from sorgui.engine.results import Analysis
from sorgui.engine.stage_results import Parametrization
from sorgui.engine.values import ExpressionError, read_expression
from sorgui.render import ClipSphere

from .geometry import (
    DIGITS,
    MAX_DEGREE,
    CadGeometryError,
    Form,
    RationalCurve,
    Section,
    ball_arcs,
    binary_form,
    over_one_denominator,
    polynomial_spans,
)

MARGIN = 1.05
"""The faces reach this many ball radii, so that the ball's sphere cuts them across (a face's
edge tangent to it, where a base arc ends on the ball's circle, leaves Open CASCADE's cut
unfinished)."""


@dataclass(frozen=True)
class Extrusion:
    """A cylinder over a curve: unit ``direction``, base arcs in the plane across it through the
    ball's centre, extruded by ``± length``."""

    direction: np.ndarray
    curves: list[RationalCurve]
    length: float
    method: str


@dataclass(frozen=True)
class Ruled:
    """A cone over a curve: its ``apex`` and, per span of the direction curve, the Bézier control
    points ``(n + 1, 3)`` of the rays' directions and the reach ``M`` that takes them past the ball."""

    apex: np.ndarray
    spans: list[np.ndarray]
    reach: list[float]
    method: str


def lined_part(analysis: Analysis, ball: ClipSphere) -> Extrusion | Ruled | None:
    """The exact cylinder or cone of the first verified real parameterization by lines, if the
    surface is one over a curve (``None`` otherwise)."""
    conical = analysis.conical
    if conical is None or conical.kind not in ("cone", "cylinder"):
        return None
    for param in conical.parametrizations:
        if not (param.real and param.verified):
            continue
        try:
            lines = _lines(param)
        except (ExpressionError, CadGeometryError, sympy.PolynomialError, TypeError, ValueError):
            continue
        if lines is None:
            continue
        start, step, s = lines
        if conical.kind == "cylinder" and not step.free_symbols:
            return _extrusion(start, step, s, ball, param.method)
        if conical.kind == "cone" and not start.free_symbols:
            return _ruled(start, step, s, ball, param.method)
    return None


def _lines(param: Parametrization) -> tuple[sympy.Matrix, sympy.Matrix, sympy.Symbol] | None:
    """``A(s)`` and ``B(s)`` of ``X(s, t) = A(s) + t·B(s)``, if ``X`` has that form."""
    s, t = (sympy.Symbol(name) for name in param.parameters)
    x = sympy.Matrix([read_expression(c) for c in param.coordinates])
    start = x.subs(t, 0).applyfunc(sympy.cancel)  # a cone's apex: (3s² + 12)/(2s² + 8) is 3/2
    step = (x.subs(t, 1) - start).applyfunc(sympy.cancel)
    if any(sympy.cancel(e) != 0 for e in x - start - t * step):
        return None
    return start, step, s


def _forms(exprs: list[sympy.Expr], s: sympy.Symbol) -> tuple[tuple[Form, Form, Form], Form]:
    polys = [sympy.Poly(e, s) for e in over_one_denominator(exprs)]
    n = max(p.degree() for p in polys)
    if not 0 < n <= MAX_DEGREE:
        raise CadGeometryError(f"the base curve has degree {n}, not between 1 and {MAX_DEGREE}")
    forms = [binary_form(p, n) for p in polys]
    return (forms[0], forms[1], forms[2]), forms[3]


def _extrusion(start: sympy.Matrix, step: sympy.Matrix, s: sympy.Symbol, ball: ClipSphere, method: str) -> Extrusion:
    direction = np.array([float(sympy.N(e, 30)) for e in step])
    unit = direction / np.linalg.norm(direction)
    numerators, denominator = _forms(list(start), s)
    centre = np.asarray(ball.center)
    with mpmath.workdps(DIGITS):
        a = [mpmath.mpf(v) for v in unit]
        along = [
            sum(((numerators[i][k] - mpmath.mpf(centre[i]) * denominator[k]) * a[i] for i in range(3)), mpmath.mpf(0))
            for k in range(len(denominator))
        ]
        moved = [[numerators[i][k] - along[k] * a[i] for k in range(len(denominator))] for i in range(3)]
    reach = MARGIN * ball.radius
    curves = ball_arcs(Section((moved[0], moved[1], moved[2]), denominator), centre, reach)
    if not curves:
        raise CadGeometryError("the cylinder does not meet the drawn ball")
    return Extrusion(unit, curves, reach, method)


def _ruled(start: sympy.Matrix, step: sympy.Matrix, s: sympy.Symbol, ball: ClipSphere, method: str) -> Ruled:
    apex = np.array([float(sympy.N(e, 30)) for e in start])
    numerators, _ = _forms(list(step), s)
    spans = polynomial_spans(numerators)
    far = float(np.linalg.norm(apex - np.asarray(ball.center))) + ball.radius
    reach = []
    for points in spans:
        nearest = float(np.min(np.linalg.norm(_bezier(points, np.linspace(0, 1, 33)), axis=1)))
        if not nearest > 0:
            raise CadGeometryError("the cone's direction curve passes through zero")
        reach.append(MARGIN * far / nearest)
    return Ruled(apex, spans, reach, method)


def _bezier(points: np.ndarray, lam: np.ndarray) -> np.ndarray:
    """Points of the Bézier curve of control ``points`` at parameters ``lam`` (de Casteljau)."""
    out = []
    for value in lam:
        level = points.copy()
        while len(level) > 1:
            level = (1 - value) * level[:-1] + value * level[1:]
        out.append(level[0])
    return np.array(out)
