"""The genus algorithm chosen per curve, each checked against Singular's ``absFactorize`` and
``genus``: a smooth profile ``P`` gives ``genus(P²)`` by Riemann–Hurwitz for
``(s, r) ↦ (s, r²)``; a profile made of lines and smooth conics needs no Singular at all."""

from __future__ import annotations

import pytest
from sympy.polys.domains import QQ

from sorgui.engine.recognition.recognize import recognize
from sorgui.engine.singular import curves
from sorgui.samples import general_position


@pytest.mark.parametrize(("degree", "seed", "drop"), [(4, 1, ()), (6, 2, ()), (6, 3, ((6, 0),)), (8, 4, ())])
def test_riemann_hurwitz_agrees_with_singular(degree: int, seed: int, drop) -> None:
    _, _, profile = recognize(general_position(degree, seed, drop))
    chosen = curves._smooth_double_cover(profile.rational, profile.square, 60.0, None)
    assert chosen is not None
    singular = curves.analyze_curves([profile.rational, profile.square])
    assert [a.genus for a in chosen] == [a.genus for a in singular]
    assert all(a.is_absolutely_irreducible for a in chosen)
    assert chosen[0].genus == (degree - 1) * (degree - 2) // 2


def test_degree_12_in_general_position_has_the_expected_genera() -> None:
    _, _, profile = recognize(general_position(12, 5))
    p, p2 = curves.analyze_profile_pair(profile.rational, profile.square)
    assert (p.genus, p2.genus) == (55, 25)  # smooth of degree 12; (k-1)² for weighted degree 2k = 12


def test_a_singular_profile_falls_back_to_singular() -> None:
    from sorgui.engine.algebra.polys import poly_ring

    R = poly_ring(("s", "r"), QQ)
    s, r = R.gens
    P = (s**2 + r**2) ** 2 - (s**2 - r**2)  # a lemniscate-like quartic with a node at the origin
    assert curves._smooth_double_cover(P, R.zero, 60.0, None) is None


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
    chosen = curves._conic_profile_pair(P, square)
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
    assert curves._conic_profile_pair(P, square) is None
