"""The genus algorithm chosen per curve: a smooth profile ``P`` gives ``genus(P²)`` by
Riemann–Hurwitz for ``(s, r) ↦ (s, r²)``, checked against Singular's ``genus`` of ``P²``."""

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
