"""Property tests: random profiles on random rational axes, moved by random rational rotations."""

from __future__ import annotations

from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from sympy.polys.domains import QQ

from sorgui.engine.recognition.recognize import METHODS, recognize
from sorgui.samples import (
    apply,
    move,
    quaternion_rotation,
    rational_vector,
    revolve,
    same_line,
)

small = st.integers(min_value=-5, max_value=5)
fractions = st.fractions(min_value=-3, max_value=3, max_denominator=4)
directions = st.tuples(small, small, small).filter(any)
quaternions = st.tuples(small, small, small, small).filter(any)


@st.composite
def profiles(draw: st.DrawFn, max_degree: int = 6) -> dict[tuple[int, int], int]:
    """A random ``F(s, w)`` with a mixed term, so the surface has exactly one axis
    (no mixed term could make it a sphere, a plane or a cylinder)."""
    terms = draw(
        st.dictionaries(
            st.tuples(st.integers(0, max_degree), st.integers(0, max_degree // 2)).filter(
                lambda m: m[0] + 2 * m[1] <= max_degree
            ),
            st.integers(-9, 9).filter(bool),
            min_size=1,
            max_size=6,
        )
    )
    i = draw(st.integers(1, max_degree - 2))
    terms[(i, 1)] = draw(st.integers(1, 9))
    return terms


SETTINGS = settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@SETTINGS
@given(
    profiles(),
    st.tuples(fractions, fractions, fractions),
    directions,
    quaternions,
    st.tuples(fractions, fractions, fractions),
)
def test_random_rotated_profile_is_recognised_with_its_axis(F, point, direction, q, shift):
    c, a = rational_vector(point), rational_vector(direction)
    rotation = quaternion_rotation(q)
    f = move(revolve(F, c, a), rotation, rational_vector(shift))
    expected_point = tuple(p + t for p, t in zip(apply(rotation, c), rational_vector(shift)))
    expected_direction = apply(rotation, a)
    for method in METHODS:
        report, sym, profile = recognize(f, method)
        assert sym.kind in {"revolution", "cylinder_of_revolution"}, method
        assert report.is_sor
        assert same_line(sym.axis_point, sym.axis_direction, expected_point, expected_direction)
        assert profile is not None and profile.even and profile.verified


@SETTINGS
@given(profiles(), st.tuples(fractions, fractions, fractions), directions)
def test_a_generic_small_term_destroys_the_symmetry(F, point, direction):
    f = revolve(F, rational_vector(point), rational_vector(direction))
    assume(f.degree() >= 0 and max(sum(m) for m in f.itermonoms()) >= 3)
    x, y, z = f.ring.gens
    perturbed = f + QQ(1, 1000) * (x * y + 2 * y * z + QQ(1, 3) * x)
    for method in METHODS:
        report, _, _ = recognize(perturbed, method)
        assert not report.is_sor
