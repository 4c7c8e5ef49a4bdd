"""Sphere families in square roots (docs/math.md §9): the two-cylinder blend, whose SMAT curve
has genus 1, gets m(t), ρ(t) by roots and a verified parameterization of its circles."""

from __future__ import annotations

from pathlib import Path

import pytest
import sympy

from sorgui.engine.algebra.polys import Poly, to_flint
from sorgui.engine.canal.lines import LINES, SEED, Lines
from sorgui.engine.canal.parametrization import T, square_root
from sorgui.engine.canal.radical import RadicalFamily, radical_family, radical_surface
from sorgui.engine.canal.spine import SmatCurve, smat_curves
from sorgui.engine.parsing import parse_polynomial

EXAMPLES = Path(__file__).resolve().parents[1] / "data" / "canal-examples.txt"


def _example(prefix: str) -> Poly:
    lines = EXAMPLES.read_text(encoding="utf-8").splitlines()
    return parse_polynomial(
        next(lines[i + 1] for i, line in enumerate(lines) if line.startswith("## " + prefix))
    ).polynomial


@pytest.fixture(scope="module")
def blend() -> tuple[Poly, SmatCurve]:
    f = _example("blend cylinders R=2")
    lines = Lines(to_flint(f), SEED)
    for _ in range(LINES):
        lines.next()
    (curve,), _ = smat_curves(lines.sample, seed=SEED, timeout=60.0, cancel=None)
    return f, curve


@pytest.mark.parametrize(
    ("square", "root"),
    [
        (64 * (T**2 + 7), 8 * sympy.sqrt(T**2 + 7)),
        (T**2 / (T**2 + 4) ** 6, T / (T**2 + 4) ** 3),
        (sympy.Rational(9, 4), sympy.Rational(3, 2)),
        (2 * T**2, sympy.sqrt(2) * T),
        (1 / (T + 1), sympy.sqrt(T + 1) / (T + 1)),
    ],
)
def test_square_roots_take_the_squares_out(square: sympy.Expr, root: sympy.Expr) -> None:
    found = square_root(square)
    assert sympy.simplify(found - root) == 0 and sympy.simplify(found**2 - square) == 0


def test_the_blend_spine_in_square_roots(blend: tuple[Poly, SmatCurve]) -> None:
    _, curve = blend
    family = radical_family(curve)
    assert isinstance(family, RadicalFamily) and len(family.roots) == 2 and family.rho == 1
    spine = tuple(family.radicals(c) for c in family.m)
    m1, m2, m3 = spine
    assert sympy.simplify(m2**2 + m3**2 - 16) == 0 and sympy.simplify(m1**2 + m3**2 - 9) == 0


def test_the_circles_of_the_family_lie_on_the_blend_and_not_on_another_surface(blend: tuple[Poly, SmatCurve]) -> None:
    f, curve = blend
    family = radical_family(curve)
    assert family is not None
    coordinates, verified = radical_surface(f, family)
    assert verified and all(
        c.has(sympy.cos(sympy.Symbol("theta"))) or c.has(sympy.sin(sympy.Symbol("theta"))) for c in coordinates
    )
    x = f.ring.gens[0]
    assert radical_surface(f + x**3, family)[1] is False
