"""CAD parts on axes turned by 30° or 60° (directions in QQ(√3)), printed coarsely as a CAD
system prints them (``%.6g``, ``%.6f``): the nearest exact surface is the designed part over
QQ(√3), not a rational direction of 4–9 digit integers near it (docs/math.md §8.5)."""

from __future__ import annotations

import pytest
import sympy

from sorgui.engine import analyze
from sorgui.engine.algebra.polys import to_flint
from sorgui.engine.parsing import parse_polynomial
from sorgui.engine.rounded import dense
from sorgui.engine.rounded.coefficients import Typed, within_scale
from sorgui.engine.rounded.precision import input_rounding

x, y, z = sympy.symbols("x y z")


def _about(axis: tuple[sympy.Expr, ...], centre: tuple[sympy.Expr, ...]) -> tuple[sympy.Expr, sympy.Expr]:
    """``ρ = |p − c|²`` and ``h = â·(p − c)`` of the axis through ``centre`` along ``axis``."""
    a = sympy.Matrix(axis) / sympy.sqrt(sum(v**2 for v in axis))
    p = sympy.Matrix([x, y, z]) - sympy.Matrix(centre)
    return p.dot(p), a.dot(p)


def torus(R: sympy.Expr, r: sympy.Expr, axis: tuple, centre: tuple) -> sympy.Expr:
    rho, h = _about(axis, centre)
    return sympy.expand((rho + R**2 - r**2) ** 2 - 4 * R**2 * (rho - h**2))


def cylinder(r: sympy.Expr, axis: tuple, point: tuple) -> sympy.Expr:
    rho, h = _about(axis, point)
    return sympy.expand(rho - h**2 - r**2)


def cone(slope: sympy.Expr, axis: tuple, apex: tuple) -> sympy.Expr:
    """The cone of ``tan²θ = slope`` about its axis."""
    rho, h = _about(axis, apex)
    return sympy.expand((1 + slope) * h**2 - rho)


def printed(f: sympy.Expr, form: str) -> str:
    """``f`` with each coefficient printed with the C format ``form``."""
    terms = []
    for monomial, c in sympy.Poly(f, x, y, z).terms():
        powers = "".join(f"*{v}^{k}" for v, k in zip("xyz", monomial) if k)
        terms.append(f"{form % float(c)}{powers}")
    return " + ".join(terms).replace("+ -", "- ")


SQRT3 = sympy.sqrt(3)
INCH = sympy.Rational(254, 10)
PARTS = {
    "a torus of 1 in and 1/4 in turned by 30° about z": torus(INCH, INCH / 4, (SQRT3, 1, 0), (0, 0, 0)),
    "a torus of 32 and 8 turned by 60° about x, moved": torus(32, 8, (0, 1, -SQRT3), (10, 5, 0)),
    "a cylinder of radius 12.7 turned by 60° about x, moved": cylinder(INCH / 2, (0, 1, -SQRT3), (10, 5, 0)),
    "a 30° cone turned by 60° about x, moved": cone(sympy.Rational(1, 3), (0, 1, -SQRT3), (1, 2, 3)),
}


@pytest.mark.parametrize("form", ["%.6g", "%.6f", "%.10g"])
@pytest.mark.parametrize("name", PARTS)
def test_a_part_turned_by_30_degrees_snaps_back_over_qq_sqrt3(name: str, form: str) -> None:
    designed = PARTS[name]
    approx = analyze(printed(designed, form), recognition_only=True).approximate
    assert approx is not None and approx.near_sor and approx.nearest is not None
    assert approx.nearest.within_rounding
    g = parse_polynomial(approx.nearest.polynomial).polynomial
    exact = parse_polynomial(str(designed)).polynomial
    assert g == exact, approx.nearest.polynomial


def test_a_coefficient_at_a_rounding_tie_is_within_the_rounding() -> None:
    """``4R² − 2(R² − r²) = −1370.965`` of the inch torus, printed ``-1370.96`` with ``%.6g``, lies
    at the very end of its last digit's rounding, and both ends belong to it: the designed
    surface itself is within the rounding, not that surface times ``1451610/1451611``."""
    text = "1*z^4 - 1370.96*z^2 + 365828"
    f = parse_polynomial(text).polynomial
    rounding = input_rounding(text, dense.float_coefficients(f))
    assert rounding is not None
    typed = Typed(to_flint(f), dense.float_coefficients(f))
    designed = to_flint(parse_polynomial("z^4 - 274193/200*z^2 + 2341301769/6400").polynomial)
    assert within_scale(designed, typed, rounding) == 1


def test_a_small_part_far_from_the_origin_has_its_zero_set_compared() -> None:
    """A torus of radii 0.03 and 0.007 (metres) centred 2.8 from the origin, printed with ``%.5g``:
    its coefficients are within the rounding of an exact torus, but the typed zero set is a blob
    ten times larger. The deviation of the zero sets was looked for from the recognizer's point of
    the axis, far from the torus, found no point and was said as "-", the torus "within the
    rounding". It is now looked for about the centre of the part on the axis."""
    designed = torus(sympy.Rational(3, 100), sympy.Rational(7, 1000), (4, -3, 15), (sympy.Rational(3, 10), -2, 2))
    nearest = analyze(printed(designed, "%.5g"), recognition_only=True).approximate.nearest
    assert nearest is not None and nearest.max_deviation is not None
    assert nearest.max_deviation > 0.1 and not nearest.within_rounding
