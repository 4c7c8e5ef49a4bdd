"""The genus algorithm chosen per curve, each checked against Singular's ``absFactorize`` and
``genus``: a smooth profile ``P`` gives ``genus(P²)`` by Riemann–Hurwitz for
``(s, r) ↦ (s, r²)``; a profile made of lines and smooth conics needs no Singular at all."""

from __future__ import annotations

import pytest
from sympy.polys.domains import QQ

from sorgui.engine.recognition.recognize import recognize
from sorgui.engine.singular import curves, profile_pair
from sorgui.samples import PARAPLANECURVE_SEXTIC, general_position


@pytest.mark.parametrize(("degree", "seed", "drop"), [(4, 1, ()), (6, 2, ()), (6, 3, ((6, 0),)), (8, 4, ())])
def test_riemann_hurwitz_agrees_with_singular(degree: int, seed: int, drop) -> None:
    _, _, profile = recognize(general_position(degree, seed, drop))
    chosen = profile_pair._smooth_double_cover(profile.rational, profile.square, 60.0, None)
    assert chosen is not None
    singular = curves.analyze_curves([profile.rational, profile.square])
    assert [a.genus for a in chosen] == [a.genus for a in singular]
    assert all(a.is_absolutely_irreducible for a in chosen)
    assert chosen[0].genus == (degree - 1) * (degree - 2) // 2


def test_degree_12_in_general_position_has_the_expected_genera() -> None:
    _, _, profile = recognize(general_position(12, 5))
    p, p2 = profile_pair.analyze_profile_pair(profile.rational, profile.square)
    assert (p.genus, p2.genus) == (55, 25)  # smooth of degree 12; (k-1)² for weighted degree 2k = 12


def test_a_singular_profile_falls_back_to_singular() -> None:
    from sorgui.engine.algebra.polys import poly_ring

    R = poly_ring(("s", "r"), QQ)
    s, r = R.gens
    P = (s**2 + r**2) ** 2 - (s**2 - r**2)  # a lemniscate-like quartic with a node at the origin
    assert profile_pair._smooth_double_cover(P, R.zero, 60.0, None) is None


def _profiles(profile):
    from sorgui.engine.algebra.polys import poly_ring

    R = poly_ring(("s", "r"), QQ)
    W = poly_ring(("s", "w"), QQ)
    P = profile(*R.gens)
    square = W.from_dict({(i, j // 2): c for (i, j), c in P.items()})
    return P, square


@pytest.mark.parametrize(
    "profile",
    [
        lambda s, r: (r**2 - 4 * r + s**2 + 3) * (r**2 + 4 * r + s**2 + 3),  # a ring torus: two circles
        lambda s, r: (4 * r**2 - 8 * r + 4 * s**2 - 5) * (4 * r**2 + 8 * r + 4 * s**2 - 5),  # a spindle torus
        lambda s, r: 2 * r**2 + 3 * s**2 - 7,  # an ellipsoid of revolution
        lambda s, r: r**2 - s**2 - 1,  # a hyperboloid of two sheets
        lambda s, r: r**2 - s,  # a paraboloid
        lambda s, r: (r**2 + s**2 - 1) * (r**2 + (s - 3) ** 2 - 1),  # two spheres on one axis
        lambda s, r: (s - 1) * (r**2 + s**2 - 4),  # a plane across a sphere
        lambda s, r: (r - s - 1) * (r + s + 1),  # a cone: two lines, mirrors of each other
    ],
)
def test_lines_and_smooth_conics_are_known_without_singular(profile) -> None:
    P, square = _profiles(profile)
    chosen = profile_pair._conic_profile_pair(P, square)
    assert chosen is not None
    singular = curves.analyze_curves([P, square])
    for mine, theirs in zip(chosen, singular, strict=True):
        assert mine.genus == theirs.genus
        assert mine.factorization.count == theirs.factorization.count
        assert {str(f.factor) for f in mine.factorization.factors} == {
            str(f.factor) for f in theirs.factorization.factors
        }


@pytest.mark.parametrize(
    "profile",
    [
        lambda s, r: r**2 - 2 * s**2,  # two lines over QQ(sqrt(2)): absolutely reducible
        lambda s, r: (r**2 + s**2 - 1) ** 2,  # not square-free
        lambda s, r: (s**2 + r**2) ** 2 - (s**2 - r**2),  # a quartic
    ],
)
def test_other_profiles_go_to_singular(profile) -> None:
    P, square = _profiles(profile)
    assert profile_pair._conic_profile_pair(P, square) is None


# --- P² on its model of lowest degree, P from the parameterization of P² -----------------------

SEXTIC = PARAPLANECURVE_SEXTIC


def test_the_square_is_analysed_on_its_model_of_half_the_degree() -> None:
    """A surface of revolution ``F(h, ρ) = 0`` for the sextic ``F`` (degree 12, on a tilted axis):
    ``P²(s, w) = F(|a|²s, |a|²s² + |u|²w)`` has degree 12, its model ``F`` degree 6; the genus of
    ``P`` read off the parameterization of ``P²`` is Singular's."""
    from sorgui.engine.algebra.linalg import dot
    from sorgui.samples import rational_vector, revolve

    f = revolve(SEXTIC, rational_vector((1, -2, 3)), rational_vector((2, 1, 2)))
    _, _, profile = recognize(f)
    frame = profile.frame
    shear = QQ.quo(dot(frame.direction, frame.direction), dot(frame.normal, frame.normal))
    model, used = profile_pair.square_model(profile.square, shear)
    assert used == shear and model.degree(0) <= 6 and profile.square.degree(0) == 12
    p, p2 = profile_pair.analyze_profile_pair(profile.rational, profile.square, shear=shear)
    assert (p.genus, p2.genus) == (5, 0) and p.is_absolutely_irreducible and p2.is_absolutely_irreducible
    par = p2.parametrization
    assert par is not None
    assert curves.is_on_curve(profile.square, par.x, par.y, par.parameter, par.generators)
    assert curves.is_proper(profile.square, par.x, par.y, par.parameter, par.generators)
    (singular,) = curves.analyze_curves([profile.rational])
    assert singular.genus == 5


@pytest.mark.parametrize(
    ("coefficients", "genus"),
    [
        (SEXTIC, 3),  # y² + z² given by the sextic: P² is the sextic itself
        ({(2, 0): 1, (0, 3): -1, (0, 2): -1}, None),  # a nodal cubic s² = w²(w + 1)
    ],
)
def test_the_genus_of_p_from_the_square_is_singulars(coefficients, genus) -> None:
    """``P`` is the double cover ``r² = w`` of ``P²``: its genus from ``h`` of the tubular surface
    agrees with Singular's ``genus`` of ``P``."""
    from sorgui.samples import rational_vector, revolve

    f = revolve(coefficients, rational_vector((0, 0, 0)), rational_vector((1, 1, 0)), axis_distance=True)
    _, _, profile = recognize(f)
    p, p2 = profile_pair._through_the_square(profile.rational, profile.square, None, 60.0, None)
    (singular,) = curves.analyze_curves([profile.rational])
    assert p2.genus == 0 and p.genus == singular.genus and (genus is None or p.genus == genus)
    assert p.is_absolutely_irreducible == singular.is_absolutely_irreducible


def test_the_map_of_a_quadratic_field_is_checked_in_flint() -> None:
    """The flint check of ``F(x(t), y(t)) = 0`` over ``QQ(i)`` gives sympy's answer."""
    from sorgui.samples import rational_vector, revolve

    f = revolve(SEXTIC, rational_vector((0, 0, 0)), rational_vector((1, 0, 0)), axis_distance=True)
    _, _, profile = recognize(f)
    par = curves.parametrize(profile.square, known_genus_zero=True)
    assert par.fractions is not None and par.field == "QQ(sqrt(-1))"
    (a, b), (c, d) = par.fractions
    F = profile.square
    nx, ny = F.degree(0), F.degree(1)
    for candidate in ((a, b, c, d), (a, b, c * 2, d)):
        sympy_answer = not sum(
            (
                candidate[0] ** i * candidate[1] ** (nx - i) * candidate[2] ** j * candidate[3] ** (ny - j) * k
                for (i, j), k in F.items()
            ),
            a.ring.zero,
        )
        assert curves._vanishes(F, *candidate) == sympy_answer
    assert curves._vanishes(F, a, b, c, d)
