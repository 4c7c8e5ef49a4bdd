"""Property tests of the canal recognizer: random sphere families (polynomial spines of degree
1–3, constant or linear radius) moved by rational rotations are recognised with the spine they
were built from; the same surfaces plus a small term are not canal."""

from __future__ import annotations

import sympy
from flint import fmpq, fmpq_mpoly_ctx
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from sympy.polys.domains import QQ

from sorgui.engine.algebra.polys import XYZ, Poly, poly_ring
from sorgui.engine.canal.verdict import analyze_canal
from sorgui.samples import quaternion_rotation

small = st.integers(min_value=-3, max_value=3)
quaternions = st.tuples(small, small, small, small).filter(any)
SETTINGS = settings(max_examples=6, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
T = sympy.Symbol("t")


@st.composite
def families(draw: st.DrawFn) -> tuple[tuple[sympy.Expr, ...], sympy.Expr]:
    """A spine ``m(t)`` of degree 1–3 (integer coefficients, leading vectors independent so the
    curve has that degree) and a radius ``r(t)`` that is constant or linear; returns ``(m, r)``."""
    n = draw(st.integers(1, 3))
    coeffs = [[draw(small) for _ in range(3)] for _ in range(n + 1)]
    lead = sympy.Matrix([coeffs[k] for k in range(1, n + 1)])
    if lead.rank() < n:
        coeffs[1:] = [[1, 0, 0], [0, 1, 0], [0, 0, 1]][:n]
    m = tuple(sum(coeffs[k][i] * T**k for k in range(n + 1)) for i in range(3))
    r0 = draw(st.integers(1, 3))
    r1 = draw(st.sampled_from([0, 0, 1, -1]))
    return m, sympy.Integer(r0) + sympy.Rational(r1, 3) * T


def moved(m: tuple[sympy.Expr, ...], rotation: list, shift: tuple[int, int, int]) -> tuple[sympy.Expr, ...]:
    """``R·m(t) + shift`` with the rational rotation ``R``."""
    return tuple(
        sympy.expand(
            sum(sympy.Rational(rotation[i][j].numerator, rotation[i][j].denominator) * m[j] for j in range(3))
            + shift[i]
        )
        for i in range(3)
    )


def envelope(m: tuple[sympy.Expr, ...], r: sympy.Expr) -> Poly:
    """The irreducible factor of largest degree of ``Res_t(S, ∂S/∂t)``, ``S = |X − m|² − r²``."""
    ctx = fmpq_mpoly_ctx.get(("x", "y", "z", "t"), "lex")
    x, y, z, t = ctx.gens()

    def lift(expr: sympy.Expr):  # noqa: ANN202 - flint polynomial
        p = sympy.Poly(expr, T)
        return sum((fmpq(int(c.p), int(c.q)) * t**e for (e,), c in p.terms()), ctx.from_dict({}))

    S = (x - lift(m[0])) ** 2 + (y - lift(m[1])) ** 2 + (z - lift(m[2])) ** 2 - lift(sympy.expand(r * r))
    res = S.resultant(S.derivative(3), "t")
    _, factors = res.factor()
    h = max((g for g, _ in factors), key=lambda g: g.total_degree())
    R = poly_ring(XYZ, QQ)
    return R.from_dict(
        {tuple(int(e) for e in mono[:3]): QQ(int(c.p), int(c.q)) for mono, c in zip(h.monoms(), h.coeffs())}
    )


def vanish(equations: tuple[str, ...], values: dict[str, sympy.Expr]) -> bool:
    symbols = {n: sympy.Symbol(n) for n in ("m1", "m2", "m3", "r")}
    return all(
        sympy.cancel(sympy.parse_expr(e, local_dict=symbols).subs({symbols[k]: v for k, v in values.items()})) == 0
        for e in equations  # engine output, not user input
    )


@SETTINGS
@given(families(), quaternions, st.tuples(small, small, small))
def test_random_families_are_recognised_with_their_spine(family, q, shift) -> None:
    m, r = family
    m = moved(m, quaternion_rotation(q), shift)
    f = envelope(m, r)
    canal = analyze_canal(f, full=False)
    assert canal.is_canal is True, canal.status
    assert canal.certificate is not None and canal.certificate.verified
    values = {"m1": m[0], "m2": m[1], "m3": m[2], "r": sympy.expand(r * r)}
    assert any(vanish(fam.equations, values) for fam in canal.families)
    spine = next(fam for fam in canal.families if vanish(fam.equations, values))
    degree = max(sympy.degree(c, T) for c in m)
    assert spine.degree == degree
    assert spine.on_line == (degree == 1) and ("revolution" in canal.kinds) == (degree == 1)
    assert spine.pipe == (sympy.degree(r, T) == 0)


@SETTINGS
@given(families(), quaternions, st.tuples(small, small, small), st.sampled_from(["x", "y", "z"]))
def test_a_small_term_breaks_the_canal_property(family, q, shift, variable) -> None:
    m, r = family
    f = envelope(moved(m, quaternion_rotation(q), shift), r)
    g = f + f.ring.gens[XYZ.index(variable)] ** 3 * QQ(1, 1000)
    canal = analyze_canal(g, full=False)
    assert canal.is_canal is False
    assert canal.witness is not None and canal.witness.verified
