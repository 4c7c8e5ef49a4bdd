"""A canal surface's families as plain float data for the 3D view (docs/math.md §9).

The engine gives each sphere family as exact strings: ``m(t)``, ``ρ(t)`` and the characteristic
circles of a rational family, or the equations of its SMAT curve in ``m1, m2, m3, r``. They are
read here once, in the worker, with the engine's reader of machine-written formulas (never
``eval``), into numerator and denominator coefficient arrays and float terms, so that the
render layer (:mod:`sorgui.render.canal_scene`, :mod:`sorgui.render.canal_touch`) only
evaluates polynomials and needs neither sympy nor the engine.
"""

from __future__ import annotations

import numpy as np
import sympy

from sorgui.engine.expressions import SYMPY, read
from sorgui.engine.results import Canal
from sorgui.render.canal_scene import FamilyCurves, Function, SmatFamily, Terms4

T = sympy.Symbol("t")
SMAT_VARIABLES = sympy.symbols("m1 m2 m3 r")


def family_curves(canal: Canal) -> tuple[FamilyCurves | SmatFamily, ...]:
    """The float curves of every family of ``canal``: ``m(t)``, ``ρ(t)`` and the circles when the
    family has them, else the equations of its SMAT curve."""
    out: list[FamilyCurves | SmatFamily] = []
    for family in canal.families:
        if (
            family.parametrization is None
            or family.radius_squared is None
            or family.circle_center is None
            or family.circle_radius_squared is None
            or family.circle_normal is None
        ):
            if family.equations:
                out.append(SmatFamily(tuple(smat_terms(g) for g in family.equations)))
            continue
        out.append(
            FamilyCurves(
                _triple(family.parametrization),
                rational_function(family.radius_squared),
                _triple(family.circle_center),
                rational_function(family.circle_radius_squared),
                _triple(family.circle_normal),
            )
        )
    return tuple(out)


def rational_function(text: str) -> Function:
    """A rational function of ``t`` (engine string) as numerator and denominator coefficients
    (highest degree first, for :func:`numpy.polyval`)."""
    expr = sympy.together(read(text, SYMPY))
    num, den = sympy.fraction(expr)
    return _coefficients(num), _coefficients(den)


def smat_terms(text: str) -> Terms4:
    """An equation of a SMAT curve (engine string in ``m1, m2, m3, r``) as float terms."""
    poly = sympy.Poly(sympy.expand(read(text, SYMPY)), *SMAT_VARIABLES)
    return tuple((tuple(int(e) for e in monomial), float(sympy.re(c.evalf(20)))) for monomial, c in poly.terms())  # type: ignore[misc]


def _triple(texts: tuple[str, str, str]) -> tuple[Function, Function, Function]:
    return rational_function(texts[0]), rational_function(texts[1]), rational_function(texts[2])


def _coefficients(expr: sympy.Expr) -> np.ndarray:
    poly = sympy.Poly(sympy.expand(expr), T)
    return np.array([float(sympy.re(c.evalf(20))) for c in poly.all_coeffs()], dtype=np.float64)
