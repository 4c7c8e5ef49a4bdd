"""The recognition-only analysis over QQ on python-flint alone gives exactly the general
pipeline's result (:mod:`sorgui.engine.rational_path`), declines what needs sympy, and prints
numbers as sympy does."""

from __future__ import annotations

from dataclasses import replace

import pytest
import sympy
from flint import fmpq, fmpq_poly
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from sorgui.engine.algebra.linalg import dot, perpendicular
from sorgui.engine.algebra.polys import poly_str
from sorgui.engine.algebra.rationals import RATIONALS, context
from sorgui.engine.analysis import StageClock, analyze_polynomial
from sorgui.engine.canal.lines import univariate_str
from sorgui.engine.errors import ParseError
from sorgui.engine.parsing import parse_polynomial, read_rational
from sorgui.engine.rational_path import _slice_square, _surd_text, recognition_only_analysis
from sorgui.engine.results import Analysis
from sorgui.samples import move, quaternion_rotation, rational_vector, revolve

from ..conftest import corpus_cases
from .test_canal import examples
from .test_properties import directions, fractions, profiles, quaternions

SURFACES = [
    "x^2 + y^2 - z",
    "y^2 + z^2 = x^3 + 3x^2 - 2x",
    "(x^2 + y^2 + z^2 + 3)^2 - 16(x^2 + y^2)",
    "(x^2 + y^2 + z^2 - 1)^5 + x",
    "(x^2 + y^2 - 1)^2 (x^2 + y^2 - 4)",
    "((x-1)^2 + (y+2)^2 + z^2 - 1)((x-1)^2 + (y+2)^2 + (z-3)^2 - 4)",  # P² splits: so does f
    "x^2 + y^2 + z^2 - 1",
    "x^2 + y^2 - 1",
    "(x - 1)(x - 2)",
    "3x - 4y + 12z - 1/2",
    "(y^2 + z^2)^2 - 2/3 x (y^2 + z^2) + x^5 - 7",
    "((x-1)^2 + (y+2)^2 + z^2 + 3)^2 - 16((x-1)^2 + (y+2)^2)",
    "(3x+4y)^2/25 + z^2 - ((4x-3y)/5)^3",
    "(x^2 + y^2 + z^2)^2 - x - y - z",  # axis (1, 1, 1): p(x, y) lies over QQ(sqrt(3))
    "(x^2 + y^2 + z^2)^3 - (x + y + 2z)^3 + 5",  # axis (1, 1, 2): |a|² = 6
    "(x^2 + y^2 + z^2)^2 - (2x + 2y + 2z)^2 + x + y + z",  # QQ(sqrt(3)), odd and even powers of x
    "(x^2 + y^2 + z^2) - (5x + 7y + 11z)^5",  # |a|² = 195
    "(x^2 + y^2 + z^2) - (3x + 3y)^2 + x + y",  # |a|² = 2: cylinder-like quadric
    "x^3 + y^2 z - x y z + 1",  # not a surface of revolution, refuted by a line: not canal
    "x y",  # two planes: canal, developable, not of revolution
    "(x^3 + y^2 z - x y z + 1)(x - y + 3)",
    "x^2 + 2y^2 + 3z^2 - 1",  # the triaxial ellipsoid: not canal
    examples()["pipe parabola + z^6/1000"],
]


def _general(text: str) -> Analysis:
    """The general pipeline's recognition-only analysis of ``text`` (sympy's polynomials)."""
    return analyze_polynomial(parse_polynomial(text).polynomial, text=text, recognition_only=True)


def _without_timings(analysis: Analysis) -> Analysis:
    canal = analysis.canal and replace(analysis.canal, timings=())
    return replace(analysis, timings=(), canal=canal)


@pytest.mark.parametrize("text", SURFACES)
def test_same_analysis_as_the_general_pipeline(text: str) -> None:
    quick = recognition_only_analysis(text, StageClock(None, None))
    assert quick is not None
    assert [name for name, _ in quick.timings] == ["parse", "recognition", "factors", "canal"]
    assert _without_timings(quick) == _without_timings(_general(text))


def test_a_profile_of_3001_digit_coefficients_is_one_factor() -> None:
    """``(x² + y² + z² + 10¹⁰⁰)³⁰ − 10¹⁰⁰·x``: its ``P²`` is shown irreducible modulo a prime
    (flint's factorization of it took 18 to 47 s), so ``f`` is its one factor, as in the general
    pipeline."""
    text = "(x^2+y^2+z^2+10^100)^30-10^100*x"
    quick = recognition_only_analysis(text, StageClock(None, None))
    assert quick is not None and quick.is_sor and quick.recognition.axis is not None
    assert [(factor.polynomial, factor.multiplicity) for factor in quick.factors] == [(quick.recognition.polynomial, 1)]
    assert _without_timings(quick) == _without_timings(_general(text))


@pytest.mark.parametrize(
    "text",
    [
        "x^2 + y^2 - sqrt(2) z",  # a square root: K = QQ(sqrt(2))
        examples()["pipe parabola"],  # canal on the lines tested: the spine needs Singular and sympy
        "x^2 + y^2 + z^2 - 1.5",  # decimals: the rounded-input stage
    ],
)
def test_declines_what_needs_sympy(text: str) -> None:
    assert recognition_only_analysis(text, StageClock(None, None)) is None


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(profiles(), st.tuples(fractions, fractions, fractions), directions, quaternions)
def test_rotated_profiles_agree(F, point, direction, q) -> None:  # type: ignore[no-untyped-def]
    """A random profile on a random axis, turned by a random rational rotation: whenever the
    rational path answers, as the general pipeline does."""
    f = move(
        revolve(F, rational_vector(point), rational_vector(direction)),
        quaternion_rotation(q),
        rational_vector((0, 0, 0)),
    )
    text = poly_str(f)
    quick = recognition_only_analysis(text, StageClock(None, None))
    assert quick is not None
    assert _without_timings(quick) == _without_timings(_general(text))


@settings(max_examples=60, deadline=None)
@given(
    profiles(),
    st.tuples(fractions, fractions, fractions),
    st.tuples(*[st.sampled_from([0, 0, 1, -2, 3])] * 3).filter(any),
)
def test_the_slice_gives_the_profile_of_the_whole_composition(F, point, direction) -> None:  # type: ignore[no-untyped-def]
    """``P²`` from a coordinate slice (docs/math.md §3.1) is ``g(c + s·a + r·u)`` with ``r²`` as
    ``w``, on axes along a coordinate, in a coordinate plane and in general position."""
    g = read_rational(poly_str(revolve(F, rational_vector(point), rational_vector(direction))))
    assert g is not None
    c = tuple(fmpq(x.numerator, x.denominator) for x in point)
    a = tuple(fmpq(x) for x in direction)
    u = perpendicular(a, RATIONALS)
    s, r = context(("s", "r")).gens()
    whole = g.polynomial.compose(*[c[i] + s * a[i] + r * u[i] for i in range(3)])
    assert _slice_square(g.polynomial, c, a, dot(u, u)).inflate([1, 2]).to_dict() == whole.to_dict()


@pytest.mark.parametrize("case", corpus_cases(), ids=lambda case: case["name"])
def test_corpus_cases_agree(case: dict) -> None:
    """Every corpus case the rational path answers, it answers as the general pipeline does."""
    text = case["input"]
    try:
        quick = recognition_only_analysis(text, StageClock(None, None))
    except ParseError:
        with pytest.raises(ParseError):
            _general(text)
        return
    if quick is not None:
        assert _without_timings(quick) == _without_timings(_general(text))


rationals = st.fractions(min_value=-50, max_value=50, max_denominator=12)


@settings(max_examples=200, deadline=None)
@given(st.lists(rationals, max_size=6))
def test_univariate_printer_is_sympys(coefficients: list) -> None:  # type: ignore[type-arg]
    """The witness restriction is printed as sympy prints the expression (without sympy)."""
    F = fmpq_poly([fmpq(c.numerator, c.denominator) for c in coefficients])
    tau = sympy.Symbol("tau")
    expected = str(
        sum(
            (sympy.Rational(c.numerator, c.denominator) * tau**i for i, c in enumerate(coefficients)),
            start=sympy.Integer(0),
        )
    )
    assert univariate_str(F, "tau") == expected


@settings(max_examples=60, deadline=None)
@given(rationals.filter(bool), st.sampled_from([2, 3, 5, 6, 7, 10, 15, 195]))
def test_surd_printer_is_sympys(q, d: int) -> None:  # type: ignore[no-untyped-def]
    expr = sympy.Rational(q.numerator, q.denominator) * sympy.sqrt(d)
    negative, text = _surd_text((fmpq(q.numerator, q.denominator), d))
    assert (negative, text) == (bool(expr.could_extract_minus_sign()), str(abs(expr)))


# --- the full analysis without sympy ---------------------------------------------------------

NEITHER = [
    "x^2y^2 + x^2z^2 + xyz + y^2z^2",  # Steiner's Roman surface
    "x^2 + y^2 + z^2 + 2xyz - 1",  # a nodal cubic
    "z = x^3 - 3xy^2",  # the monkey saddle
    "x^2 + 2y^2 + 3z^2 - 1",  # the triaxial ellipsoid
    "(x^3 + y^2 z - x y z + 1)(x - y + 3)",
    "x^4 + y^4 + z^4 - (x^2 + y^2 + z^2)",  # the tooth surface
]


def _general_full(text: str) -> Analysis:
    return analyze_polynomial(parse_polynomial(text).polynomial, text=text)


@pytest.mark.parametrize("text", NEITHER)
def test_the_full_analysis_of_a_surface_that_is_neither_is_the_general_pipelines(text: str) -> None:
    from sorgui.engine.rational_path import full_analysis

    quick = full_analysis(text, StageClock(None, None))
    assert quick is not None
    assert [name for name, _ in quick.timings] == ["parse", "recognition", "factors", "conical", "canal"]
    assert _without_timings(quick) == _without_timings(_general_full(text))


@pytest.mark.parametrize(
    "text",
    [
        "(x^2 + y^2 + z^2 + 3)^2 - 16(x^2 + y^2)",  # of revolution: real locus, Table 1, Singular
        "x^2 + 2y^2 - 3z^2",  # a cone over an ellipse
        "x^2 + 2y^2 - 1",  # a cylinder
        "x^3 - y^2 z",  # a cone with its apex at 0
        examples()["pipe parabola"],  # canal on the lines tested
        "x^2 + 2y^2 + 3z^2 - 1.5",  # decimals
    ],
)
def test_the_full_analysis_leaves_the_rest_to_the_general_pipeline(text: str) -> None:
    from sorgui.engine.rational_path import full_analysis

    assert full_analysis(text, StageClock(None, None)) is None


@pytest.mark.parametrize(
    "text", ["x^2 + 2y^2 - 3z^2", "(x-1)^2 + 2(y+2)^2 - 3(z-1)^2", "x^3 - y^2", "x^2 + 2y^2 - 1", *NEITHER]
)
def test_the_conical_kind_is_the_detectors(text: str) -> None:
    from sorgui.engine.conical.detect import detect
    from sorgui.engine.parsing import parse_rational
    from sorgui.engine.rational_path import conical_kind

    g = parse_rational(text)
    assert g is not None
    assert conical_kind(g) == detect(parse_polynomial(text).polynomial).kind


def test_the_full_analysis_of_steiners_surface_loads_no_sympy() -> None:
    import subprocess
    import sys

    code = (
        "import sys\n"
        "from sorgui.engine import analyze\n"
        "a = analyze('x^2y^2 + x^2z^2 + xyz + y^2z^2')\n"
        "print(a.canal.is_canal, a.conical.kind, 'sympy' in sys.modules)\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=True)
    assert done.stdout.split() == ["False", "none", "False"]


def test_a_batch_line_reports_none_of_the_quick_stages() -> None:
    """The flint-only path runs on the analysis's clock, so that a time limit met there reports
    its stages; a batch's line (``quick_stages=False``) sends none of those messages (each a
    wake-up of the parent: 100 lines of degree 10 took 0.71 s instead of 0.55 s), and gets the
    same analysis."""
    from sorgui.engine import analyze
    from sorgui.session.supervised import AnalysisRequest

    text = "(x^2 + y^2 + z^2 + 3)^2 - 16(x^2 + y^2)"
    heard: list[object] = []

    def listen(*what: object) -> None:
        heard.append(what)

    told = analyze(text, recognition_only=True, progress=listen, stage_done=listen, parsed=listen)
    assert [stage for (stage,) in heard[:1]] == ["parse"] and len(heard) >= 8
    heard.clear()
    quiet = analyze(text, recognition_only=True, progress=listen, stage_done=listen, parsed=listen, quick_stages=False)
    assert heard == [] and replace(quiet, timings=()) == replace(told, timings=())
    assert AnalysisRequest(text).options()["quick_stages"] is True
    from argparse import Namespace

    from sorgui.batch.run import _requests

    line = _requests(Namespace(method="symmetry", recognition_only=True, tolerance=None, timeout=None))(text)
    assert line.options()["quick_stages"] is False
