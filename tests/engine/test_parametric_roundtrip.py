"""Round trips (docs/math.md §13): every surface of revolution, cone and cylinder of the test
corpus that sorgui parameterizes is analysed as an equation, a verified real parameterization of
it is moved by a rational rotation and a translation and reparameterized by a Möbius map of each
parameter, and that map, typed as input, gives the same axis, apex or direction (moved), and its
implicit equation is the moved equation."""

from __future__ import annotations

import json
from functools import cache
from pathlib import Path

import pytest
import sympy
from sympy import QQ

from sorgui.engine import analyze
from sorgui.engine.algebra.linalg import cross
from sorgui.engine.algebra.polys import XYZ, poly_ring
from sorgui.engine.parametric.detect import conicity, parametric_symmetry
from sorgui.engine.parametric.implicit import implicit_equation
from sorgui.engine.parametric_parsing import parse_parametrization
from sorgui.engine.stage_results import Parametrization
from sorgui.samples import apply, move, quaternion_rotation, rational_vector, same_line

DATA = Path(__file__).resolve().parents[1] / "data"
ROTATION = quaternion_rotation((1, 2, -2, 4))
SHIFT = rational_vector((1, "-1/2", 3))
S, T = sympy.symbols("s t")
MOBIUS = {S: (2 * S + 1) / (S - 3), T: (T - 2) / (3 * T + 1)}


def _corpus() -> list[tuple[str, str]]:
    cases = json.loads((DATA / "cases.json").read_text(encoding="utf-8"))
    found = [(c["name"], c["input"]) for c in cases if not c["expect"].get("error")]
    for block in (DATA / "canal-examples.txt").read_text(encoding="utf-8").split("## ")[1:]:
        head, body = block.split("\n", 1)
        lines = [line for line in body.splitlines() if line.strip() and not line.startswith("#")]
        if lines:
            found.append((head.split("|")[0].strip(), lines[0]))
    return found


@cache
def _analysed(text: str):  # type: ignore[no-untyped-def]
    return analyze(text, timeout=120)


def _maps() -> list[tuple[str, str, int, str]]:
    """(case, equation, index, kind) for every real verified map of a SOR, cone or cylinder."""
    out = []
    for name, text in _corpus():
        analysis = _analysed(text)
        conical = analysis.conical
        wanted = analysis.is_sor or (conical is not None and conical.kind != "none")
        if not wanted:
            continue
        for i, p in enumerate(analysis.parametrizations):
            if p.real and p.verified:
                out.append((name, text, i, "surface"))
        for i, p in enumerate(conical.parametrizations if conical is not None else ()):
            if p.real and p.verified:
                out.append((name, text, i, "conical"))
    return out


def _moved_text(par: Parametrization) -> str:
    """The map ``R·P(μ(s), ν(t)) + shift`` as a user would type it."""
    s, t = (sympy.Symbol(n) for n in par.parameters)
    P = [sympy.sympify(c, locals={str(s): S, str(t): T}) for c in par.coordinates]
    rotated = [
        sum(sympy.Rational(ROTATION[i][j].numerator, ROTATION[i][j].denominator) * P[j] for j in range(3))
        + sympy.Rational(str(SHIFT[i]))
        for i in range(3)
    ]
    moved = [sympy.cancel(sympy.together(c.subs(MOBIUS, simultaneous=True))) for c in rotated]
    return ", ".join(f"{n} = {sympy.sstr(c)}" for n, c in zip("xyz", moved))


def _moved_point(v: tuple[str, str, str]) -> tuple:
    point = apply(ROTATION, rational_vector(v))
    return tuple(p + q for p, q in zip(point, SHIFT))


@pytest.mark.parametrize("case, text, index, kind", _maps())
def test_a_moved_and_reparameterized_map_has_the_moved_axis_apex_or_direction(
    case: str, text: str, index: int, kind: str
) -> None:
    analysis = _analysed(text)
    conical = analysis.conical
    par = (analysis.parametrizations if kind == "surface" else conical.parametrizations)[index]
    source = parse_parametrization(_moved_text(par))
    K = source.field

    def field(v: tuple) -> tuple:
        return tuple(K.convert(c, QQ) for c in v)

    symmetry = parametric_symmetry(source.map)
    rec = analysis.recognition
    assert symmetry.kind == rec.symmetry, case
    if rec.axis is not None:
        assert same_line(
            symmetry.axis_point,
            symmetry.axis_direction,
            field(_moved_point(rec.axis.point)),
            field(apply(ROTATION, rational_vector(rec.axis.direction))),
        )
    cones = conicity(source.map)
    if conical is not None and conical.kind == "cone":
        assert cones.kind == "cone" and cones.apex == field(_moved_point(conical.apex))
    if conical is not None and conical.kind == "cylinder":
        direction = field(apply(ROTATION, rational_vector(conical.direction)))
        assert cones.kind == "cylinder"
        assert any(not any(cross(d, direction)) for d in cones.directions)
    found = implicit_equation(source.map, symmetry, cones, timeout=60)
    expected = move(poly_ring(XYZ, QQ).from_expr(sympy.sympify(rec.polynomial)), ROTATION, SHIFT)
    assert found is not None
    g = found.polynomial
    assert g * g.ring.domain.convert(expected.LC, QQ) == expected.set_ring(g.ring) * g.LC


def test_the_corpus_gives_maps_of_every_kind() -> None:
    kinds = {(_analysed(text).recognition.symmetry, kind) for _name, text, _i, kind in _maps()}
    assert {("revolution", "surface"), ("cylinder_of_revolution", "surface"), ("extrusion", "conical")} <= kinds
    assert ("revolution", "conical") in kinds  # the cone's lines through its apex


@pytest.mark.parametrize(
    "text, kind, fact",
    [
        ("x = 2s/(1+s^2+t^2) + 1, y = 2t/(1+s^2+t^2), z = (1-s^2-t^2)/(1+s^2+t^2) - 3", "sphere", ("1", "0", "-3")),
        ("x = s + t, y = s - t, z = s", "plane", ("1", "1", "-2")),
        ("x = (1-t^2)/(1+t^2) + 1, y = 2t/(1+t^2), z = s", "cylinder_of_revolution", None),
    ],
)
def test_spheres_planes_and_cylinders_have_their_own_solution_spaces(text: str, kind: str, fact: object) -> None:
    symmetry = parametric_symmetry(parse_parametrization(text).map)
    assert symmetry.kind == kind
    assert symmetry.dimension == {"sphere": 3, "plane": 3, "cylinder_of_revolution": 2}[kind]
    if kind == "sphere":
        assert tuple(str(c) for c in symmetry.center) == fact
    if kind == "plane":
        assert tuple(str(c) for c in symmetry.normal) == fact
