"""The base curve of a cone or a cylinder in words people can picture (docs/math.md §10).

The engine gives the base curve exactly, in the frame it computes in: a cylinder's section in the
plane through the origin spanned by the rational ``U ⟂ a`` and ``W ∥ a × U`` (which are
orthogonal but not of length 1, so ``u, v`` are not lengths), a cone's top-degree form in an
affine chart (``z = 1``: the lines ``c + t·(x, y, 1)`` through the apex ``c``). Here, in floating
point for the reader only:

* the cylinder's section in unit coordinates ``ξ = |U|·u``, ``η = |W|·v`` (lengths in the plane);
* a conic's kind, its centre (a point of space, in the section plane) and its semi-axes with their
  directions: ``an ellipse, centre (1, 2, 0), semi-axes 1 and 0.707 along (1, 0, 0), (0, 1, 0)``;
* for a cone, the chart said relative to the apex, and a conic chart curve as the section at unit
  distance from the apex (a circle of radius ``r``: a circular cone of half-angle ``atan r``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from sorgui.engine.results import Conical
from sorgui.engine.stage_results import BaseCurve
from sorgui.session import math_text
from sorgui.session.math_text import Name, Number, Power, Product, Sum, Unreadable

DIGITS = 4
"""Significant digits of the numbers of a description."""


def polynomial_terms(text: str, names: tuple[str, str]) -> dict[tuple[int, int], float] | None:
    """An expanded polynomial in ``names`` (an engine string) as float terms, read without
    sympy; ``None`` for anything else."""
    try:
        tree = math_text.read(text)
    except Unreadable:
        return None
    out: dict[tuple[int, int], float] = {}
    for term in tree.terms if isinstance(tree, Sum) else (tree,):
        exponents = [0, 0]
        coefficient = 1.0
        factors = [term]
        if isinstance(term, Product):
            if term.denominators:
                return None
            coefficient = float(-term.coefficient if term.negative else term.coefficient)
            factors = list(term.numerators)
        for factor in factors:
            base, power = (
                (factor.base, factor.exponent) if isinstance(factor, Power) else (factor, Number(Fraction(1), "1"))
            )
            if isinstance(base, Name) and base.name in names and isinstance(power, Number):
                exponents[names.index(base.name)] += int(power.value)
            elif isinstance(base, Number) and factor is base:
                coefficient *= float(base.value)
            else:
                try:
                    coefficient *= math_text.evaluate(factor)
                except (ValueError, ZeroDivisionError, OverflowError):
                    return None
        key = (exponents[0], exponents[1])
        out[key] = out.get(key, 0.0) + coefficient
    return out


@dataclass(frozen=True)
class Conic:
    """A real conic in the plane ``origin + ξ·e1 + η·e2`` (``e1, e2`` orthonormal), in its own
    axes: ``kind``, its centre in space (``None`` for a parabola), its semi-axes (or, for a
    parabola, the focal parameter) and their directions in space."""

    kind: str
    centre: tuple[float, float, float] | None
    semi_axes: tuple[float, ...]
    directions: tuple[tuple[float, float, float], ...]


def conic(terms: dict[tuple[int, int], float], origin: np.ndarray, e1: np.ndarray, e2: np.ndarray) -> Conic | None:
    """The conic ``Σ c_ij ξ^i η^j = 0`` (degree 2, in unit coordinates of the plane) described;
    ``None`` when it is not of degree 2."""
    if max((i + j for i, j in terms), default=0) != 2:
        return None
    a, b, c = terms.get((2, 0), 0.0), terms.get((1, 1), 0.0), terms.get((0, 2), 0.0)
    d, e, f = terms.get((1, 0), 0.0), terms.get((0, 1), 0.0), terms.get((0, 0), 0.0)
    matrix = np.array([[a, b / 2], [b / 2, c]])
    values, vectors = np.linalg.eigh(matrix)
    scale = max(abs(values).max(), 1e-300)

    def space(v: np.ndarray) -> tuple[float, float, float]:
        w = v[0] * e1 + v[1] * e2
        return (float(w[0]), float(w[1]), float(w[2]))

    if min(abs(values)) <= 1e-12 * scale:  # a parabola (or parallel lines)
        return Conic("parabola", None, (), (space(vectors[:, int(np.argmax(abs(values)))]),))
    centre = np.linalg.solve(matrix, -0.5 * np.array([d, e]))
    constant = f + 0.5 * (d * centre[0] + e * centre[1])
    point = origin + centre[0] * e1 + centre[1] * e2
    where = (float(point[0]), float(point[1]), float(point[2]))
    if abs(constant) <= 1e-12 * max(scale, abs(f), 1.0):
        return Conic("a point" if values[0] * values[1] > 0 else "two crossing lines", where, (), ())
    ratios = -constant / values
    if np.all(ratios < 0):
        return Conic("no real points (an imaginary ellipse)", where, (), ())
    order = np.argsort(-ratios)  # a hyperbola's transverse axis (it meets the curve) first
    axes = tuple(float(math.sqrt(abs(ratios[k]))) for k in order)
    directions = tuple(space(vectors[:, k]) for k in order)
    if np.all(ratios > 0):
        kind = "circle" if math.isclose(axes[0], axes[1], rel_tol=1e-9) else "ellipse"
    else:
        kind = "hyperbola"
    return Conic(kind, where, axes, directions)


def _g(value: float) -> str:
    return f"{0.0 if abs(value) < 1e-12 else value:.{DIGITS}g}"


def _vector(v: tuple[float, ...]) -> str:
    return "(" + ", ".join(_g(c) for c in v) + ")"


def conic_words(shape: Conic) -> str:
    """``an ellipse, centre (…), semi-axes 1 and 0.5 along (…) and (…)``."""
    if shape.kind == "parabola":
        return f"a parabola, its axis along {_vector(shape.directions[0])}"
    if not shape.semi_axes:
        return shape.kind + ("" if shape.centre is None else f" at {_vector(shape.centre)}")
    assert shape.centre is not None  # a central conic
    if shape.kind == "circle":
        return f"a circle, centre {_vector(shape.centre)}, radius {_g(shape.semi_axes[0])}"
    first, second = shape.semi_axes
    along = f" along {_vector(shape.directions[0])} and {_vector(shape.directions[1])}"
    article = "an ellipse" if shape.kind == "ellipse" else "a hyperbola"
    return f"{article}, centre {_vector(shape.centre)}, semi-axes {_g(first)} and {_g(second)}{along}"


def base_curve_rows(conical: Conical) -> list[tuple[str, str]]:
    """The rows that make the base curve readable: the unit frame of a cylinder's section and the
    curve in it, a conic's centre and semi-axes, the apex-relative chart of a cone."""
    base = conical.base_curve
    if base is None:
        return []
    if conical.kind == "cone" and base.chart is not None and conical.apex is not None:
        return _cone_rows(conical, base)
    if base.frame_u is None or base.frame_w is None:
        return []
    return _cylinder_rows(base)


def _floats(triple: tuple[str, ...] | None) -> np.ndarray | None:
    if triple is None:
        return None
    try:
        return np.array([math_text.evaluate(math_text.read(v)) for v in triple])
    except (Unreadable, ValueError, ZeroDivisionError):
        return None


def _cylinder_rows(base: BaseCurve) -> list[tuple[str, str]]:
    u, w, origin = _floats(base.frame_u), _floats(base.frame_w), _floats(base.frame_point)
    terms = polynomial_terms(base.polynomial, base.variables)
    if u is None or w is None or terms is None:
        return []
    origin = np.zeros(3) if origin is None else origin
    lu, lw = float(np.linalg.norm(u)), float(np.linalg.norm(w))
    unit = {(i, j): c / (lu**i * lw**j) for (i, j), c in terms.items()}
    rows = []
    if not (math.isclose(lu, 1.0) and math.isclose(lw, 1.0)):  # U and W are not unit vectors: lengths said
        degree = max(i + j for i, j in unit)
        top = max(abs(c) for (i, j), c in unit.items() if i + j == degree)
        ordered = sorted(unit.items(), key=lambda t: (-t[0][0] - t[0][1], -t[0][0]))
        shown = " ".join(_term(c / top, i, j, ("ξ", "η"), first=k == 0) for k, ((i, j), c) in enumerate(ordered))
        rows.append(
            (
                "in unit axes",
                f"ξ = {_g(lu)}·{base.variables[0]} and η = {_g(lw)}·{base.variables[1]} are lengths along "
                f"{_vector(tuple(u / lu))} and {_vector(tuple(w / lw))} from {_vector(tuple(origin))}: {shown} = 0",
            )
        )
    shape = conic(unit, origin, u / lu, w / lw)
    if shape is not None:
        rows.append(("section", conic_words(shape)))
    return rows


def _cone_rows(conical: Conical, base: BaseCurve) -> list[tuple[str, str]]:
    first, second = base.variables
    height = (base.chart or "").split("=")[0].strip()
    apex = _floats(conical.apex)
    where = "" if apex is None else f" {_vector(tuple(apex))}"
    rows = [
        (
            "relative to the apex",
            f"the lines apex + t·({_chart_vector(first, second, height)}), for the points ({first}, {second}) of "
            f"the curve below: {first} and {second} are measured from the apex{where}, in the plane at distance 1 "
            f"along {height}",
        )
    ]
    terms = polynomial_terms(base.polynomial, base.variables)
    if terms is None:
        return rows
    names = ("x", "y", "z")
    e = np.eye(3)
    shape = conic(terms, e[names.index(height)], e[names.index(first)], e[names.index(second)])
    if shape is None or not shape.semi_axes:
        return rows
    rows.append((f"at {height} = 1", conic_words(shape).replace("centre", "centre apex +", 1)))
    if shape.kind == "circle" and shape.centre is not None and math.hypot(*shape.centre) - 1 < 1e-12:
        angle = math.degrees(math.atan(shape.semi_axes[0]))
        rows.append(("opening", f"a circular cone about the {height}-axis through the apex, half-angle {_g(angle)}°"))
    return rows


def _chart_vector(first: str, second: str, height: str) -> str:
    """``x, y, 1`` in the order of the coordinates (the chart's coordinate is 1)."""
    values = {first: first, second: second, height: "1"}
    return ", ".join(values[n] for n in ("x", "y", "z"))


def _term(value: float, i: int, j: int, names: tuple[str, str], first: bool) -> str:
    sign = "−" if value < 0 else "+"
    magnitude = abs(value)
    monomial = "".join(
        n + (str(k).translate(math_text.SUPERSCRIPTS) if k > 1 else "") for n, k in zip(names, (i, j)) if k
    )
    number = "" if monomial and math.isclose(magnitude, 1.0, rel_tol=1e-12) else _g(magnitude)
    body = number + monomial
    if first:
        return ("−" if value < 0 else "") + body
    return f"{sign} {body}"
