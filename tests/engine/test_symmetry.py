"""The symmetry algebra and the paper's Algorithm II on one table of known surfaces (docs/math.md §2, §7)."""

from __future__ import annotations

import pytest
import sympy
from sympy.polys.domains import QQ

from sorgui.engine.algebra.linalg import is_zero
from sorgui.engine.algebra.polys import XYZ, number_field, poly_ring
from sorgui.engine.recognition.recognize import METHODS, recognize
from sorgui.engine.recognition.symmetry import satisfies_identity, symmetry_algebra
from sorgui.samples import rational_vector, revolve, same_line

R = poly_ring(XYZ, QQ)
x, y, z = R.gens
K2 = number_field((2,))
R2 = poly_ring(XYZ, K2)
s2 = K2.from_sympy(sympy.sqrt(2))

# name, polynomial, kind, dim L, axis (point, direction) or None, centre or None
TABLE = [
    ("cone", y**2 - 2 * x * z, "revolution", 1, ((0, 0, 0), (1, 0, 1)), None),
    ("torus", (x**2 + y**2 + z**2 + 3) ** 2 - 16 * (x**2 + y**2), "revolution", 1, ((0, 0, 0), (0, 0, 1)), None),
    ("cubic", y**2 + z**2 - x**3 - 3 * x**2 + 2 * x, "revolution", 1, ((0, 0, 0), (1, 0, 0)), None),
    ("sphere", x**2 + y**2 + z**2 - 2 * x - 3, "sphere", 3, None, (1, 0, 0)),
    ("plane", 2 * x - y + 3 * z - 1, "plane", 3, None, None),
    ("cylinder", (x - 1) ** 2 + (y - 2) ** 2 - 4, "cylinder_of_revolution", 2, ((1, 2, 0), (0, 0, 1)), None),
    ("line pair around an axis", x**2 + y**2, "cylinder_of_revolution", 2, ((0, 0, 0), (0, 0, 1)), None),
    ("extrusion", x**3 - y**2 - x, "extrusion", 1, None, None),
    ("ellipsoid", x**2 + 2 * y**2 + 3 * z**2 - 1, "none", 0, None, None),
    (
        "hyperboloid off the origin",
        (x - 1) ** 2 + (y + 2) ** 2 - 3 * (z - 5) ** 2 - 1,
        "revolution",
        1,
        ((1, -2, 5), (0, 0, 1)),
        None,
    ),
    (
        "concentric spheres",
        ((x - 1) ** 2 + y**2 + z**2 - 1) * ((x - 1) ** 2 + y**2 + z**2 - 4),
        "sphere",
        3,
        None,
        (1, 0, 0),
    ),
    (
        "coaxial blend",
        (x**2 + y**2 + (z - 1) ** 2 - 4) * (x**2 + y**2 - 1) - QQ(1, 4),
        "revolution",
        1,
        ((0, 0, 0), (0, 0, 1)),
        None,
    ),
    (
        "non-coaxial blend",
        (x**2 + y**2 + (z - 1) ** 2 - 4) * ((x - z) ** 2 / 2 + y**2 - 1) - QQ(1, 4),
        "none",
        0,
        None,
        None,
    ),
    (
        "tilted torus",
        revolve(
            {(0, 2): 1, (0, 1): 6 - 16, (0, 0): 9, (2, 0): 16}, rational_vector((1, 2, 3)), rational_vector((2, -1, 2))
        ),
        "revolution",
        1,
        ((1, 2, 3), (2, -1, 2)),
        None,
    ),
]


@pytest.mark.parametrize("method", sorted(METHODS))
@pytest.mark.parametrize(("name", "f", "kind", "dim", "axis", "center"), TABLE, ids=[t[0] for t in TABLE])
def test_methods_agree_on_known_surfaces(method, name, f, kind, dim, axis, center):
    report, sym, profile = recognize(f, method)
    assert sym.kind == kind
    assert sym.dimension == dim
    assert report.is_sor == (kind in {"revolution", "cylinder_of_revolution", "sphere", "plane"})
    if axis is not None:
        assert same_line(sym.axis_point, sym.axis_direction, rational_vector(axis[0]), rational_vector(axis[1]))
        assert profile is not None and profile.even and profile.verified
    if center is not None:
        assert sym.center == rational_vector(center)


def test_symmetry_basis_satisfies_the_identity():
    f = TABLE[1][1]
    (m,) = symmetry_algebra(f)
    assert satisfies_identity(f, m)
    assert not is_zero(m.a)


def test_axis_over_an_algebraic_field():
    a = (K2.one, s2, K2.zero)
    c = (K2.one, K2.zero, K2.convert(QQ(1, 2)))
    f = revolve({(1, 1): 1, (0, 1): -3, (2, 0): 2, (0, 0): 1}, c, a, K2)
    assert f.ring.domain == K2
    for method in METHODS:
        _, sym, profile = recognize(f, method)
        assert sym.kind == "revolution"
        assert same_line(sym.axis_point, sym.axis_direction, c, a)
        assert profile is not None and profile.verified


def test_paper_example_axis_and_profile(paper_example_1):
    report, sym, profile = recognize(paper_example_1)
    assert same_line(
        sym.axis_point, sym.axis_direction, rational_vector(("3/5", "-4/5", 0)), rational_vector((4, 3, 0))
    )
    X, Y = sympy.symbols("x y")
    paper_p = (
        -400 - 104 * X**2 - X**4 + 200 * Y**2 - 48 * X * Y**2 + 26 * X**2 * Y**2 - 29 * Y**4 + 12 * X * Y**4 + Y**6
    )
    p = profile.orthonormal.as_expr()
    assert sympy.expand(p - paper_p) == 0 or sympy.expand(p - paper_p.subs(X, -X)) == 0
    # docs/math.md §1 erratum: with (v : p × v) the Plücker coordinates are (4:3:0:0:0:5).
    assert report.axis.plucker == ("4", "3", "0", "0", "0", "5")


@pytest.mark.parametrize("seed", range(12))
def test_the_rows_below_a_few_terms_give_the_whole_systems_algebra(seed: int) -> None:
    """Over QQ, the algebra found from a part of (★) (a few rows, or values at points) is the
    null space of the whole system, one row per monomial: on dense surfaces of revolution in
    general position, on the same surfaces moved slightly off revolution, on a sphere and on a
    sparse surface of revolution."""
    import random

    from sorgui.engine.algebra import linalg
    from sorgui.engine.algebra.polys import to_flint
    from sorgui.engine.algebra.rationals import RATIONALS, content
    from sorgui.engine.recognition.symmetry import _generators, rational_symmetry_algebra

    rng = random.Random(seed)
    point = rational_vector([rng.randint(-9, 9) for _ in range(3)])
    direction = rational_vector([rng.randint(1, 9) for _ in range(3)])
    profile = {(i, j): rng.randint(-5, 5) for i in range(7) for j in range(3) if i + 2 * j <= 6}
    profile[(0, 3)] = 1
    surfaces = [
        revolve(profile, point, direction),
        (x - rng.randint(-3, 3)) ** 2 + (y + rng.randint(-3, 3)) ** 2 + z**2 - rng.randint(1, 9),
        (x + 2 * y) ** 2 + (y - 2 * x) ** 2 + 5 * z**4 - 1,
    ]
    surfaces.append(surfaces[0] + x * y * z)
    for f in surfaces:
        g = to_flint(f)
        columns = [p.to_dict() for p in _generators(g)]
        monomials = sorted(set().union(*columns))
        rows = [[col.get(m, 0) for col in columns] for m in monomials]
        whole = [(m.b, m.a) for m in rational_symmetry_algebra(g)]
        expected = [(tuple(v[:3]), tuple(v[3:])) for v in linalg.nullspace(rows, 6, RATIONALS)]
        assert whole == expected
        h = g * (6 / content(g))  # a multiple with integer coefficients, as the reader holds them
        multiple = {tuple(int(e) for e in m): int(c.p) for m, c in zip(h.monoms(), h.coeffs())}
        assert [(m.b, m.a) for m in rational_symmetry_algebra(g, multiple)] == expected


@pytest.mark.parametrize(
    ("g", "point", "direction", "normal"),
    [
        (2 * x - y + QQ(1, 3) * z + 1, (QQ(-9, 23), QQ(9, 46), QQ(-3, 46)), (6, -3, 1), (2, -1, -15)),
        (x**2 + y**2 + z**2 - 2 * x + QQ(1, 2), (1, 0, 0), (0, 0, 1), (1, 0, 0)),
    ],
)
def test_the_profile_of_a_power_of_a_plane_or_a_sphere_is_read_off_its_base(g, point, direction, normal) -> None:  # noqa: ANN001
    """``(x + y + z + 1)^45`` spent 2 s of a 3 s analysis, outside every stage, composing the
    45th power in the axis frame to verify its profile: the profile of ``c·g^k`` is that of
    ``g`` to the ``k``th power (the same :class:`ProfileCurve` as composing ``f``)."""
    from sorgui.engine.recognition.profile import power_profile, profile_curve

    vectors = [tuple(QQ(v) for v in vector) for vector in (point, direction, normal)]
    for k in (1, 2, 3):
        f = 7 * g**k
        assert power_profile(f, g, *vectors) == profile_curve(f, *vectors)
