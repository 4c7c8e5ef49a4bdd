"""The slow tails of the full analysis made fast, and exact: a degree-12 surface of revolution
whose ``P²`` is Singular's paraPlaneCurve sextic in ``(h, ρ)``, and a canal surface of revolution
with a varying radius, whose canal answer gives the axis as its spine (docs/math.md §5, §9.2)."""

from __future__ import annotations

from pathlib import Path

import sympy

from sorgui.engine import analyze
from sorgui.engine.values import read_expression
from sorgui.samples import PARAPLANECURVE_SEXTIC as SEXTIC
from sorgui.samples import rational_vector, revolve

DATA = Path(__file__).parents[1] / "data"


def test_a_canal_surface_of_revolution_has_the_axis_as_its_spine() -> None:
    """The envelope of the spheres centred on ``(1, 2, −1) + τ·(2, −1, 3)`` with radius ``1 + τ²``:
    its spine family is that line with ``ρ = (1 + τ²)²``, verified; and it has a real
    parameterization through its tubular surface."""
    result = analyze((DATA / "sphere-envelope.txt").read_text(encoding="utf-8"))
    canal = result.canal
    assert canal is not None and canal.is_canal and "revolution" in canal.kinds
    spine = canal.spine
    assert spine is not None and spine.on_line and spine.verified and spine.field == "QQ" and spine.genus == 0
    m1, m2, m3, r = sympy.symbols("m1 m2 m3 r")
    on_line = [read_expression(e) for e in spine.spine_equations]
    for tau in (0, 1, -2):
        point = {m1: 1 + 2 * tau, m2: 2 - tau, m3: -1 + 3 * tau}
        assert all(e.subs(point) == 0 for e in on_line)
    (model,) = [read_expression(e) for e in spine.equations if read_expression(e).has(r)]
    tau = (m3 + 1) / 3
    assert sympy.expand(model.subs(r, (1 + tau**2) ** 2) * 81) == 0
    t = sympy.Symbol("t")
    m = [read_expression(e) for e in spine.parametrization or ()]
    rho = read_expression(spine.radius_squared or "")
    for value in (0, 2, sympy.Rational(1, 3)):
        point = {m1: m[0].subs(t, value), m2: m[1].subs(t, value), m3: m[2].subs(t, value), r: rho.subs(t, value)}
        assert all(read_expression(e).subs(point) == 0 for e in spine.equations)
    methods = {p.method: p for p in result.parametrizations}
    assert methods["via tubular surface (real, stereographic)"].verified
    assert result.rationality is not None and result.rationality.real_rational


def test_the_paraplanecurve_sextic_in_h_and_rho() -> None:
    """``F(h, ρ) = 0`` for the sextic ``F``, on a tilted axis: degree 12, Table 1 row 4 with
    ``genus(P) = 5`` and ``genus(P²) = 0`` (``P²`` analysed on its model ``F`` of degree 6), and a
    verified parameterization."""
    f = revolve(SEXTIC, rational_vector((1, -2, 3)), rational_vector((2, 1, 2)))
    from sorgui.engine.algebra.polys import poly_str

    result = analyze(poly_str(f))
    rationality = result.rationality
    assert result.recognition.degree == 12 and rationality is not None and rationality.status == "decided"
    assert (rationality.table_row, rationality.genus_profile, rationality.genus_profile_square) == (4, 5, 0)
    assert result.parametrizations and all(p.verified for p in result.parametrizations)
