"""The canal answer of a torus read off its profile (docs/math.md §9.1): tori in general position
are recognised with their centre, axis and radii, both families satisfy their SMAT equations,
the answer agrees with the SMAT route's, and surfaces of revolution that are not real tori are
left to that route."""

from __future__ import annotations

from fractions import Fraction

import sympy
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from sorgui.engine.algebra.linalg import cross, dot
from sorgui.engine.algebra.polys import poly_str
from sorgui.engine.canal.torus import torus_of
from sorgui.engine.canal.verdict import analyze_canal
from sorgui.engine.recognition.profile import profile_curve
from sorgui.engine.recognition.recognize import recognize
from sorgui.engine.stage_results import CanalFamily
from sorgui.samples import rational_vector, revolve

small = st.integers(min_value=-3, max_value=3)
directions = st.tuples(small, small, small).filter(any)
radii = st.fractions(min_value=Fraction(1, 4), max_value=9, max_denominator=4)


def torus(point: tuple[int, ...], direction: tuple[int, ...], core: Fraction, tube: Fraction):
    """``(h²/A + d² + R² − r²)² − 4R²d²`` times ``A²``, with ``h = a·(p − c)`` and ``d`` the
    distance to the axis: the torus of core radius² ``R²`` and tube radius² ``r²``."""
    A = dot(direction, direction)
    k = A * (core - tube)
    profile = {
        (4, 0): 1,
        (2, 1): 2 * A,
        (0, 2): A**2,
        (2, 0): 2 * k,
        (0, 1): 2 * A * k - 4 * A**2 * core,
        (0, 0): k * k,
    }
    return revolve(profile, rational_vector(point), rational_vector(direction), axis_distance=True)


def profile_of(f):
    recognition, _, profile = recognize(f, "symmetry", None)
    assert recognition.is_sor
    return profile


def satisfies_smat(family: CanalFamily) -> bool:
    """``m(t)``, ``ρ(t)`` of the report substituted into its own SMAT equations (sympy, here only)."""
    m = [sympy.sympify(c) for c in family.parametrization]
    rho = sympy.sympify(family.radius_squared)
    values = dict(zip(sympy.symbols("m1 m2 m3 r"), (*m, rho)))
    return all(sympy.cancel(sympy.sympify(g).subs(values)) == 0 for g in family.equations)


@settings(max_examples=12, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(point=st.tuples(small, small, small), direction=directions, core=radii, tube=radii)
def test_a_torus_in_general_position_is_read_off_its_profile(point, direction, core, tube) -> None:
    f = torus(point, direction, core, tube)
    found = torus_of(profile_of(f))
    assert found is not None
    assert found.core == core and found.tube == tube
    assert found.center == tuple(Fraction(c) for c in point)
    assert not any(cross(found.direction, tuple(Fraction(c) for c in direction)))
    canal = analyze_canal(f, is_sor=True, profile=profile_of(f))
    assert canal.is_canal and set(canal.kinds) == {"dupin", "pipe", "revolution"}
    assert canal.certificate.verified and canal.certificate.method == "profile+rotation"
    pipe, axis = canal.families
    assert pipe.pipe and pipe.radius_squared == str(sympy.Rational(tube.numerator, tube.denominator))
    assert axis.on_line and not axis.pipe
    for family in canal.families:
        assert family.genus == 0
        if family.parametrization is not None:
            assert family.verified and satisfies_smat(family)


def test_the_torus_of_the_corpus_agrees_with_the_smat_route() -> None:
    f = torus((1, -2, 3), (1, 2, 2), Fraction(4), Fraction(1))
    fast = analyze_canal(f, is_sor=True, profile=profile_of(f))
    slow = analyze_canal(f)
    assert fast.is_canal is slow.is_canal is True
    assert set(fast.kinds) == set(slow.kinds)
    assert sorted(f.pipe for f in fast.families) == sorted(f.pipe for f in slow.families)
    assert {f.radius_squared for f in fast.families if f.pipe} == {f.radius_squared for f in slow.families if f.pipe}
    assert all(satisfies_smat(family) for family in fast.families)


def test_surfaces_of_revolution_that_are_not_real_tori_take_the_smat_route() -> None:
    point, direction = rational_vector((0, 0, 0)), rational_vector((0, 0, 1))
    complex_core = revolve(
        {(4, 0): 1, (2, 1): 2, (0, 2): 1, (0, 1): 4, (0, 0): -1}, point, direction, axis_distance=True
    )  # (ζ² + d² − 1)² + 4d²: R² = −1
    quartic = revolve({(4, 0): 1, (0, 1): 1, (0, 0): -1}, point, direction, axis_distance=True)  # d² = 1 − ζ⁴
    imaginary_tube = torus((0, 0, 0), (0, 0, 1), Fraction(1), Fraction(-1))
    for f in (complex_core, quartic, imaginary_tube):
        profile = profile_curve(f, point, direction)
        assert torus_of(profile) is None, poly_str(f)


def test_a_torus_whose_families_need_a_square_root_gives_them_by_their_equations() -> None:
    """POV-Ray's Torus_40_12: ``12V² − τ² = 40`` has no rational point (mod 3), so the spheres
    centred on the axis have no ``m(t)``, ``ρ(t)`` over ``QQ``; the core circle has one."""
    from sorgui.engine.parsing import parse_polynomial

    f = parse_polynomial("x^4 + 2x^2y^2 + 2x^2z^2 - 104x^2 + y^4 + 2y^2z^2 + 56y^2 + z^4 - 104z^2 + 784").polynomial
    canal = analyze_canal(f, is_sor=True, profile=profile_of(f))
    pipe, axis = canal.families
    assert pipe.parametrization is not None and satisfies_smat(pipe) and pipe.radius_squared == "12"
    assert axis.parametrization is None and not axis.verified and len(axis.equations) == 3


def test_a_torus_with_huge_radii_finishes() -> None:
    """Core radius 2·10⁷⁵: the search for a rational point of a family's conic stays short (it once
    built a range of 10⁷⁵ candidates and raised OverflowError)."""
    f = torus((0, 0, 0), (0, 0, 1), Fraction(4 * 10**150), Fraction(10**150))
    canal = analyze_canal(f, is_sor=True, profile=profile_of(f))
    assert canal.is_canal and all(satisfies_smat(family) for family in canal.families if family.verified)
